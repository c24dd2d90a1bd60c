//! The adversarial input campaign: every public API family called with a seeded mix of random
//! and adversarial inputs, each call under `catch_unwind`, each result checked.
//!
//! A family is one entry: a name and a function that draws an input from a [`Gen`], calls the
//! API through [`probe`] and checks what comes back:
//!
//! ```ignore
//! family!("UnitQuat::try_new", |g| {
//!     let q = g.quat();
//!     probe(&q, || unit(UnitQuat::try_new(q)?))
//! }),
//! ```
//!
//! A call passes when it returns a typed [`gyrostat::Error`], or an `Ok` value that is finite and
//! within its invariant ([`unit()`] for a `UnitQuat`, [`rotation`] for a `Dcm`, …). It fails when
//! it panics ([`Trial::Panic`], with the input) or returns an `Ok` value that breaks its
//! invariant ([`Trial::Bad`], with the input and the reason). [`run_campaign`] runs a list of
//! families for f32 and f64, prints one table row per family and type, asserts that no call
//! failed, and with `GYROSTAT_CAMPAIGN_WRITE=1` rewrites the matching table of `ROBUSTNESS.md`.
//!
//! Settings (environment variables):
//! - `GYROSTAT_CAMPAIGN_N`: inputs per family and type (default [`DEFAULT_INPUTS`]; the long
//!   setting of `ROBUSTNESS.md` is 1 000 000);
//! - `GYROSTAT_CAMPAIGN_SEED`: the base seed (default [`DEFAULT_SEED`]); each family's stream is
//!   seeded from it and the family's name, so adding a family leaves the others' inputs alone;
//! - `GYROSTAT_CAMPAIGN_WRITE=1`: write the table into `ROBUSTNESS.md`.

use std::cell::Cell;
use std::collections::BTreeMap;
use std::fmt::{Debug, Write as _};
use std::panic::{self, AssertUnwindSafe};
use std::sync::Once;
use std::time::Instant;

use gyrostat::rotation::{Euler, EulerSequence};
use gyrostat::{Dcm, Error, Mat3, Quat, Real, UnitQuat, Vec3};

use crate::tolerance::Tolerance;

/// Inputs per family and type when `GYROSTAT_CAMPAIGN_N` is not set: enough to meet every kind
/// of adversarial input many times, small enough that the README test command stays fast.
pub const DEFAULT_INPUTS: u64 = 20_000;

/// The base seed when `GYROSTAT_CAMPAIGN_SEED` is not set.
pub const DEFAULT_SEED: u64 = 0x6779_726f_7374_6174; // "gyrostat"

/// The outcome of one call (or one short sequence of calls on one input).
#[derive(Debug)]
pub enum Trial {
    /// `Ok`, finite and within its invariant.
    Ok,
    /// A typed error.
    Err(Error),
    /// An `Ok` value that is not finite or breaks its invariant: input, value and reason.
    Bad(String),
    /// A panic: input and message.
    Panic(String),
}

/// Why a checked call did not pass: a typed error (fine) or a broken invariant (a defect).
#[derive(Debug)]
pub enum Fail {
    /// The API returned a typed error.
    Error(Error),
    /// The API returned an `Ok` value that breaks its invariant.
    Bad(String),
}

impl From<Error> for Fail {
    fn from(e: Error) -> Self {
        Fail::Error(e)
    }
}

/// What a checked call returns: `Ok(())` when every value passed its check.
pub type Check = Result<(), Fail>;

thread_local! {
    /// Set while a probe runs, so that the panic hook stays quiet for panics the probe reports.
    static PROBING: Cell<bool> = const { Cell::new(false) };
    /// The largest `||q| − 1|` (in ε of the type) that [`unit()`] accepted in the current family.
    static WORST_UNIT: Cell<f64> = const { Cell::new(0.0) };
}

static HOOK: Once = Once::new();

/// Installs (once) a panic hook that is silent while a probe runs and defers to the previous
/// hook otherwise, so that other tests in the same binary keep their panic messages.
fn install_hook() {
    HOOK.call_once(|| {
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if !PROBING.with(Cell::get) {
                previous(info);
            }
        }));
    });
}

/// Calls `f` under `catch_unwind` and classifies the outcome; `input` is reported with a panic or
/// a broken invariant.
pub fn probe<I: Debug>(input: &I, f: impl FnOnce() -> Check) -> Trial {
    install_hook();
    PROBING.with(|p| p.set(true));
    let r = panic::catch_unwind(AssertUnwindSafe(f));
    PROBING.with(|p| p.set(false));
    match r {
        Ok(Ok(())) => Trial::Ok,
        Ok(Err(Fail::Error(e))) => Trial::Err(e),
        Ok(Err(Fail::Bad(why))) => Trial::Bad(format!("{why}; input {input:?}")),
        Err(payload) => {
            let msg = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "non-string panic payload".into());
            Trial::Panic(format!("panicked: {msg}; input {input:?}"))
        }
    }
}

/// A broken invariant.
pub fn bad(why: impl Into<String>) -> Check {
    Err(Fail::Bad(why.into()))
}

/// `Ok` when `cond`, else a broken invariant described by `why`.
pub fn ensure(cond: bool, why: impl FnOnce() -> String) -> Check {
    if cond { Ok(()) } else { bad(why()) }
}

// ---------------------------------------------------------------------------------------------
// Invariant checks

/// The tolerance on `||q| − 1|` of a `UnitQuat` a function returns: 32 ε (3.8e-6 f32, 7.1e-15
/// f64). The invariant is "unit to rounding": a result computed from unit inputs by a short
/// chain (a product, an exponential, a renormalisation) carries a few ulp; 32 ulp leaves room
/// for inputs that are themselves a few ulp off (the generator draws such inputs) and is far
/// below any real defect (a collapsed or exploded norm).
pub fn unit_tolerance<T: Tolerance>() -> f64 {
    32.0 * T::EPSILON.to_f64()
}

/// A finite scalar.
pub fn finite<T: Real>(x: T) -> Check {
    ensure(x.is_finite(), || format!("non-finite value {x:?}"))
}

/// Finite scalars.
pub fn finite_all<T: Real>(xs: &[T]) -> Check {
    ensure(xs.iter().all(|x| x.is_finite()), || {
        format!("non-finite value in {xs:?}")
    })
}

/// A finite vector.
pub fn finite_vec<T: Real>(v: Vec3<T>) -> Check {
    ensure(v.is_finite(), || format!("non-finite vector {v:?}"))
}

/// A finite matrix.
pub fn finite_mat<T: Real>(m: &Mat3<T>) -> Check {
    ensure(m.is_finite(), || format!("non-finite matrix {m:?}"))
}

/// `||q| − 1|` computed in f64 from the components (exact squares for f32).
pub fn norm_error<T: Real>(q: UnitQuat<T>) -> f64 {
    let n2: f64 = q.to_array().iter().map(|c| c.to_f64() * c.to_f64()).sum();
    (n2.sqrt() - 1.0).abs()
}

/// A unit quaternion: finite, `||q| − 1| ≤` [`unit_tolerance`]. The largest accepted error is
/// recorded for the family's row.
pub fn unit<T: Tolerance>(q: UnitQuat<T>) -> Check {
    unit_within(q, unit_tolerance::<T>())?;
    let e = norm_error(q) / T::EPSILON.to_f64();
    WORST_UNIT.with(|w| w.set(w.get().max(e)));
    Ok(())
}

/// A unit quaternion with a stated tolerance on `||q| − 1|` (for results whose norm error is
/// documented, such as an RK4 step without renormalisation).
pub fn unit_within<T: Real>(q: UnitQuat<T>, tol: f64) -> Check {
    if !q.as_quat().is_finite() {
        return bad(format!("non-finite UnitQuat {q:?}"));
    }
    let e = norm_error(q);
    ensure(e <= tol, || {
        format!("UnitQuat {q:?} off unit norm by {e:e} (tolerance {tol:e})")
    })
}

/// `‖MᵀM − 1‖_max` in f64.
pub fn orthonormality_error<T: Real>(m: &Mat3<T>) -> f64 {
    let a = m.m.map(|r| r.map(|c| c.to_f64()));
    let mut e: f64 = 0.0;
    for i in 0..3 {
        for j in 0..3 {
            let d: f64 = (0..3).map(|k| a[k][i] * a[k][j]).sum::<f64>() - f64::from(i == j);
            e = e.max(d.abs());
        }
    }
    e
}

/// A rotation matrix: finite, `‖RᵀR − 1‖_max ≤ tol`, `det R > 0`.
pub fn rotation_within<T: Real>(m: &Mat3<T>, tol: f64) -> Check {
    finite_mat(m)?;
    let e = orthonormality_error(m);
    let det = m.determinant().to_f64();
    ensure(e <= tol && det > 0.0, || {
        format!("matrix {m:?}: |RᵀR − 1| = {e:e} (tolerance {tol:e}), det {det}")
    })
}

/// A `Dcm` within [`Dcm::default_tolerance`] of orthonormal with `det > 0`.
pub fn rotation<T: Real>(d: &Dcm<T>) -> Check {
    rotation_within(d.matrix(), Dcm::<T>::default_tolerance().to_f64())
}

/// Both checks pass.
pub fn both(a: Check, b: Check) -> Check {
    a.and(b)
}

/// An `Err` where the contract promises `Ok` is a defect too.
pub fn must<V>(r: Result<V, Error>, what: &str) -> Result<V, Fail> {
    r.map_err(|e| {
        Fail::Bad(format!(
            "{what} returned {e:?} where the contract promises Ok"
        ))
    })
}

// ---------------------------------------------------------------------------------------------
// Random and adversarial inputs

/// SplitMix64 (Steele, Lea & Flood 2014): a small, seedable, reproducible generator.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// A generator from a seed.
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)`.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform in `0..n` (`n > 0`).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    /// `true` with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }

    /// A random sign.
    pub fn sign(&mut self) -> f64 {
        if self.next_u64() & 1 == 0 { 1.0 } else { -1.0 }
    }

    /// One element of a non-empty slice.
    pub fn pick<'a, V>(&mut self, xs: &'a [V]) -> &'a V {
        &xs[self.below(xs.len())]
    }
}

/// The range constants of the type under test, in f64 (exact for both types).
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// The largest finite value.
    pub max: f64,
    /// The smallest positive normal value.
    pub min_positive: f64,
    /// The smallest positive subnormal value.
    pub min_subnormal: f64,
    /// Machine epsilon.
    pub eps: f64,
    /// `√max`: the largest magnitude whose square is finite.
    pub sqrt_max: f64,
}

impl Limits {
    /// The limits of `T`.
    pub fn of<T: Tolerance>() -> Self {
        Self {
            max: T::per_type(f32::MAX as f64, f64::MAX),
            min_positive: T::per_type(f32::MIN_POSITIVE as f64, f64::MIN_POSITIVE),
            min_subnormal: T::per_type(f32::from_bits(1) as f64, f64::from_bits(1)),
            eps: T::EPSILON.to_f64(),
            sqrt_max: T::per_type((f32::MAX as f64).sqrt(), f64::MAX.sqrt()),
        }
    }
}

/// The input generator of one family: a seeded stream of scalars, vectors, quaternions,
/// attitudes, matrices, time steps and inertias, mixing ordinary random values with the
/// adversarial ones of the campaign (NaN, ±∞, ±0, subnormals, the largest finite values,
/// values just off unit norm, gimbal-lock poles, antipodal quaternions, zero vectors, huge and
/// tiny steps, degenerate inertia, huge momenta).
pub struct Gen<T> {
    /// The random stream.
    pub rng: Rng,
    /// The range constants of `T`.
    pub lim: Limits,
    _t: std::marker::PhantomData<T>,
}

impl<T: Tolerance> Gen<T> {
    /// A generator seeded with `seed`.
    pub fn new(seed: u64) -> Self {
        Self {
            rng: Rng::new(seed),
            lim: Limits::of::<T>(),
            _t: std::marker::PhantomData,
        }
    }

    fn t(x: f64) -> T {
        T::from_f64(x)
    }

    /// A magnitude log-uniform over the whole positive finite range of `T`, subnormals included.
    pub fn any_magnitude(&mut self) -> f64 {
        let lo = self.lim.min_subnormal.ln();
        let hi = self.lim.max.ln();
        self.rng.range(lo, hi).exp().min(self.lim.max)
    }

    /// A magnitude log-uniform in `[lo, hi]`.
    pub fn magnitude_in(&mut self, lo: f64, hi: f64) -> f64 {
        self.rng.range(lo.ln(), hi.ln()).exp()
    }

    /// A finite adversarial constant (signed).
    pub fn special_f64(&mut self) -> f64 {
        let l = self.lim;
        let pi = std::f64::consts::PI;
        let xs = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            l.eps,
            1.0 + l.eps,
            1.0 - l.eps / 2.0,
            pi,
            pi / 2.0,
            2.0 * pi,
            l.max,
            l.max / 2.0,
            l.min_positive,
            l.min_subnormal,
            l.min_subnormal * 3.0,
            l.sqrt_max,
            l.sqrt_max * 4.0,
            1.0 / l.sqrt_max,
            l.max.cbrt(),
            l.max.sqrt().sqrt(),
            1e30,
            1e-30,
            T::per_type(1e20, 1e200),
            T::per_type(1e-20, 1e-200),
        ];
        let x = *self.rng.pick(&xs);
        x * self.rng.sign()
    }

    /// A finite scalar: ordinary values most of the time, otherwise any magnitude or an
    /// adversarial constant.
    pub fn finite(&mut self) -> T {
        let x = match self.rng.below(20) {
            0..=7 => self.rng.range(-4.0, 4.0),
            8..=10 => self.rng.sign() * self.magnitude_in(1e-6, 1e6),
            11..=14 => self.rng.sign() * self.any_magnitude(),
            _ => self.special_f64(),
        };
        Self::t(x)
    }

    /// Any scalar: as [`Gen::finite`], and NaN or ±∞ one time in twenty.
    pub fn scalar(&mut self) -> T {
        if self.rng.chance(0.05) {
            Self::t(*self.rng.pick(&[f64::NAN, f64::INFINITY, f64::NEG_INFINITY]))
        } else {
            self.finite()
        }
    }

    /// A finite ordinary scalar in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> T {
        Self::t(self.rng.range(lo, hi))
    }

    /// A positive quantity of any size (moments, masses, frequencies, radii): mostly ordinary,
    /// sometimes any magnitude or an edge value.
    pub fn positive(&mut self) -> T {
        let x = match self.rng.below(10) {
            0..=5 => self.magnitude_in(1e-2, 1e2),
            6..=7 => self.any_magnitude(),
            _ => self.special_f64().abs(),
        };
        Self::t(x)
    }

    /// A time step: mostly ordinary (1e-4 … 1 s), often huge or tiny, sometimes zero,
    /// negative, NaN or ±∞.
    pub fn dt(&mut self) -> T {
        let x = match self.rng.below(20) {
            0..=9 => self.magnitude_in(1e-4, 1.0),
            10..=12 => self.magnitude_in(1.0, self.lim.max),
            13..=15 => self.magnitude_in(self.lim.min_subnormal, 1e-4),
            16 => 0.0,
            17 => -self.magnitude_in(1e-4, 1.0),
            18 => self.special_f64(),
            _ => *self.rng.pick(&[f64::NAN, f64::INFINITY, f64::NEG_INFINITY]),
        };
        Self::t(x)
    }

    /// A finite, positive, ordinary time step (1e-4 … 0.1 s): for calls whose subject is not the
    /// step.
    pub fn ordinary_dt(&mut self) -> T {
        Self::t(self.magnitude_in(1e-4, 0.1))
    }

    fn unit_direction(&mut self) -> [f64; 3] {
        loop {
            let v = [
                self.rng.range(-1.0, 1.0),
                self.rng.range(-1.0, 1.0),
                self.rng.range(-1.0, 1.0),
            ];
            let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            if n > 0.1 && n <= 1.0 {
                return v.map(|c| c / n);
            }
        }
    }

    /// A finite vector: ordinary, zero, along an axis, a direction times a magnitude of any
    /// size (all components huge, or all tiny), or independent finite components.
    pub fn finite_vec(&mut self) -> Vec3<T> {
        match self.rng.below(10) {
            0..=3 => Vec3::new(
                self.uniform(-4.0, 4.0),
                self.uniform(-4.0, 4.0),
                self.uniform(-4.0, 4.0),
            ),
            4 => {
                let s = [0.0, -0.0];
                Vec3::new(
                    Self::t(*self.rng.pick(&s)),
                    Self::t(*self.rng.pick(&s)),
                    Self::t(*self.rng.pick(&s)),
                )
            }
            5 => {
                let mut v = Vec3::ZERO;
                v[*self.rng.pick(&gyrostat::Axis::ALL)] = self.finite();
                v
            }
            6..=7 => {
                let d = self.unit_direction();
                let m = self.any_magnitude();
                Vec3::from_array(d.map(|c| Self::t(c * m)))
            }
            _ => Vec3::new(self.finite(), self.finite(), self.finite()),
        }
    }

    /// Any vector: as [`Gen::finite_vec`], and one non-finite component one time in fifteen.
    pub fn vec(&mut self) -> Vec3<T> {
        let mut v = self.finite_vec();
        if self.rng.chance(1.0 / 15.0) {
            let bad = *self.rng.pick(&[f64::NAN, f64::INFINITY, f64::NEG_INFINITY]);
            v[*self.rng.pick(&gyrostat::Axis::ALL)] = Self::t(bad);
        }
        v
    }

    /// A finite vector of magnitude at most `bound` (ordinary, tiny, or up to the bound), for
    /// the documented domains of infallible functions.
    pub fn vec_within(&mut self, bound: f64) -> Vec3<T> {
        let d = self.unit_direction();
        let m = match self.rng.below(6) {
            0 => 0.0,
            1 => self.magnitude_in(self.lim.min_subnormal, bound),
            2 => bound,
            _ => self.rng.range(0.0, bound),
        };
        let v = Vec3::from_array(d.map(|c| Self::t(c * m)));
        // Rounding to T can push the norm a hair above the bound: pull it back.
        let n = v.norm().to_f64();
        if n > bound {
            v.scale(Self::t(bound / n * (1.0 - 4.0 * self.lim.eps)))
        } else {
            v
        }
    }

    /// Any quaternion: near unit, zero, a direction times any magnitude, one subnormal
    /// component, or independent components (possibly non-finite).
    pub fn quat(&mut self) -> Quat<T> {
        match self.rng.below(8) {
            0..=1 => {
                let q = self.unit_quat_f64();
                let s = 1.0 + self.rng.range(-8.0, 8.0) * self.lim.eps;
                Quat::from_array(q.map(|c| Self::t(c * s)))
            }
            2 => Quat::ZERO,
            3 => {
                let q = self.unit_quat_f64();
                let m = self.any_magnitude();
                Quat::from_array(q.map(|c| Self::t(c * m)))
            }
            4 => {
                let mut a = [0.0; 4];
                a[self.rng.below(4)] = self.rng.sign() * self.lim.min_subnormal;
                Quat::from_array(a.map(|c| Self::t(c)))
            }
            _ => Quat::new(self.scalar(), self.scalar(), self.scalar(), self.scalar()),
        }
    }

    /// A unit quaternion uniformly distributed on S³, in f64.
    pub fn unit_quat_f64(&mut self) -> [f64; 4] {
        loop {
            let a = [
                self.rng.range(-1.0, 1.0),
                self.rng.range(-1.0, 1.0),
                self.rng.range(-1.0, 1.0),
                self.rng.range(-1.0, 1.0),
            ];
            let n = a.iter().map(|c| c * c).sum::<f64>().sqrt();
            if n > 0.1 && n <= 1.0 {
                return a.map(|c| c / n);
            }
        }
    }

    /// A valid attitude (unit to a few ulp): random, the identity or its negative, half-turns,
    /// tiny angles down to subnormal, exact and near gimbal-lock poles of a random convention,
    /// or a random attitude a few ulp off unit norm.
    pub fn unit_quat(&mut self) -> UnitQuat<T> {
        let q = match self.rng.below(12) {
            0..=4 => self.unit_quat_f64(),
            5 => [self.rng.sign(), 0.0, 0.0, 0.0],
            6 => {
                let d = self.unit_direction();
                if self.rng.chance(0.5) {
                    let mut a = [0.0; 4];
                    a[1 + self.rng.below(3)] = self.rng.sign();
                    a
                } else {
                    [0.0, d[0], d[1], d[2]]
                }
            }
            7 => {
                // A tiny rotation: the vector part down to subnormal.
                let d = self.unit_direction();
                let s = self.magnitude_in(self.lim.min_subnormal, 1e-3);
                let c = (1.0 - s * s).sqrt();
                [c, d[0] * s, d[1] * s, d[2] * s]
            }
            8..=9 => return self.pole_attitude().0,
            _ => {
                let q = self.unit_quat_f64();
                let s = 1.0 + self.rng.range(-4.0, 4.0) * self.lim.eps;
                return UnitQuat::new_unchecked(Quat::from_array(q.map(|c| Self::t(c * s))));
            }
        };
        let q = Quat::from_array(q.map(|c| Self::t(c)));
        UnitQuat::try_new(q).unwrap_or(UnitQuat::IDENTITY)
    }

    /// Two attitudes: independent, equal, antipodal (`q`, `−q`), a tiny rotation apart, or a
    /// half-turn apart.
    pub fn unit_quat_pair(&mut self) -> (UnitQuat<T>, UnitQuat<T>) {
        let a = self.unit_quat();
        let b = match self.rng.below(6) {
            0..=1 => self.unit_quat(),
            2 => a,
            3 => -a,
            4 => {
                let v = self.vec_within(1e-3);
                a * UnitQuat::exp_unchecked(v)
            }
            _ => {
                let d = self.unit_direction();
                let h = Quat::new(T::ZERO, Self::t(d[0]), Self::t(d[1]), Self::t(d[2]));
                a * UnitQuat::try_new(h).unwrap_or(UnitQuat::IDENTITY)
            }
        };
        (a, b)
    }

    /// A random Euler convention (of the 24).
    pub fn sequence(&mut self) -> EulerSequence {
        *self.rng.pick(&EulerSequence::ALL)
    }

    /// An attitude exactly at (or a few ulp from) a gimbal-lock pole of a random convention,
    /// with that convention.
    pub fn pole_attitude(&mut self) -> (UnitQuat<T>, EulerSequence) {
        let seq = self.sequence();
        let pi = std::f64::consts::PI;
        let pole = if seq.is_proper() {
            *self.rng.pick(&[0.0, pi])
        } else {
            *self.rng.pick(&[pi / 2.0, -pi / 2.0])
        };
        let off = if self.rng.chance(0.5) {
            0.0
        } else {
            self.rng.range(-8.0, 8.0) * self.lim.eps
        };
        let a = self.uniform(-pi, pi);
        let c = self.uniform(-pi, pi);
        let e = Euler::new(seq, [a, Self::t(pole + off), c]);
        (e.to_unit_quat_unchecked(), seq)
    }

    /// Euler angles: ordinary, at or near a pole, multiples of π/2, huge, or any scalar.
    pub fn euler_angles(&mut self, seq: EulerSequence) -> [T; 3] {
        let pi = std::f64::consts::PI;
        match self.rng.below(6) {
            0..=1 => [
                self.uniform(-pi, pi),
                self.uniform(-pi, pi),
                self.uniform(-pi, pi),
            ],
            2 => {
                let pole = if seq.is_proper() {
                    *self.rng.pick(&[0.0, pi, -pi])
                } else {
                    *self.rng.pick(&[pi / 2.0, -pi / 2.0])
                };
                let off =
                    self.rng.range(-8.0, 8.0) * self.lim.eps * f64::from(self.rng.below(2) as u8);
                [
                    self.uniform(-pi, pi),
                    Self::t(pole + off),
                    self.uniform(-pi, pi),
                ]
            }
            3 => {
                let k = [-2.0, -1.0, 0.0, 1.0, 2.0, 3.0, 4.0];
                [
                    Self::t(*self.rng.pick(&k) * pi / 2.0),
                    Self::t(*self.rng.pick(&k) * pi / 2.0),
                    Self::t(*self.rng.pick(&k) * pi / 2.0),
                ]
            }
            4 => [self.finite(), self.finite(), self.finite()],
            _ => [self.scalar(), self.scalar(), self.scalar()],
        }
    }

    /// A finite 3×3 matrix: a rotation, a rotation a little or far off, a scaled rotation (any
    /// magnitude), a reflection, a singular matrix, or independent entries.
    pub fn finite_mat(&mut self) -> Mat3<T> {
        let r = self.unit_quat().to_rotation_matrix();
        match self.rng.below(8) {
            0..=1 => r,
            2 => {
                let e = self.magnitude_in(self.lim.eps, 1.0);
                let mut m = r;
                for row in m.m.iter_mut() {
                    for c in row.iter_mut() {
                        *c += Self::t(self.rng.range(-e, e));
                    }
                }
                m
            }
            3 => r.scale(Self::t(self.rng.sign() * self.any_magnitude())),
            4 => r.scale(-T::ONE),
            5 => {
                let mut m = r;
                m.m[2] = m.m[1];
                m
            }
            _ => Mat3::from_rows(
                [self.finite(), self.finite(), self.finite()],
                [self.finite(), self.finite(), self.finite()],
                [self.finite(), self.finite(), self.finite()],
            ),
        }
    }

    /// Any 3×3 matrix: as [`Gen::finite_mat`], and one non-finite entry one time in fifteen.
    pub fn mat(&mut self) -> Mat3<T> {
        let mut m = self.finite_mat();
        if self.rng.chance(1.0 / 15.0) {
            let bad = *self.rng.pick(&[f64::NAN, f64::INFINITY, f64::NEG_INFINITY]);
            m.m[self.rng.below(3)][self.rng.below(3)] = Self::t(bad);
        }
        m
    }

    /// Principal moments, as f64: ordinary, a sphere, a symmetric top, a flat lamina
    /// (`I₃ = I₁ + I₂`), near-singular (one moment tiny, the other two nearly equal), nearly
    /// equal moments a few tens of ulp apart, scaled to any magnitude, or arbitrary (possibly
    /// non-physical) values.
    pub fn moments_f64(&mut self) -> [f64; 3] {
        let base = match self.rng.below(9) {
            0..=2 => {
                let a = self.rng.range(0.5, 2.0);
                let b = self.rng.range(0.5, 2.0);
                let lo = (a - b).abs();
                [a, b, self.rng.range(lo.max(0.05), a + b)]
            }
            3 => [1.0; 3],
            4 => {
                let a = self.rng.range(0.5, 2.0);
                let c = self.rng.range(0.3, 2.0 * a);
                [a, a, c]
            }
            5 => {
                let a = self.rng.range(0.5, 2.0);
                let b = self.rng.range(0.5, 2.0);
                [a, b, a + b]
            }
            6 => {
                let tiny = self.magnitude_in(1e-12, 1e-3);
                [tiny, 1.0, 1.0 + tiny * self.rng.range(0.0, 1.0)]
            }
            7 => {
                let a = self.rng.range(0.3, 3.0);
                let k = self.rng.range(1.0, 200.0) * self.lim.eps;
                [a, a * (1.0 + k), a * (1.0 + 2.0 * k)]
            }
            _ => [
                self.rng.range(-1.0, 3.0),
                self.rng.range(-1.0, 3.0),
                self.rng.range(-1.0, 3.0),
            ],
        };
        let mut m = base;
        // Permute the axes.
        let p = self.rng.below(6);
        m = match p {
            0 => [m[0], m[1], m[2]],
            1 => [m[0], m[2], m[1]],
            2 => [m[1], m[0], m[2]],
            3 => [m[1], m[2], m[0]],
            4 => [m[2], m[0], m[1]],
            _ => [m[2], m[1], m[0]],
        };
        let scale = match self.rng.below(5) {
            0..=2 => 1.0,
            3 => self.any_magnitude(),
            _ => *self.rng.pick(&[
                1e-30,
                1e30,
                T::per_type(1e-36, 1e-300),
                T::per_type(1e36, 1e300),
            ]),
        };
        m.map(|c| c * scale)
    }

    /// A body-frame inertia tensor (possibly invalid input): diagonal principal moments, or
    /// principal moments rotated by a random attitude, or arbitrary symmetric or asymmetric
    /// entries.
    pub fn inertia_tensor(&mut self) -> Mat3<T> {
        let m = self.moments_f64();
        match self.rng.below(6) {
            0..=2 => Mat3::from_diagonal(Vec3::from_array(m.map(|c| Self::t(c)))),
            3..=4 => {
                let r = crate::cast::m64(&self.unit_quat().to_rotation_matrix());
                let mut a = [[0.0; 3]; 3];
                for i in 0..3 {
                    for j in 0..3 {
                        a[i][j] = (0..3).map(|k| r[i][k] * m[k] * r[j][k]).sum();
                    }
                }
                crate::cast::mat3(&a)
            }
            _ => {
                let d = Vec3::new(self.finite(), self.finite(), self.finite());
                let o = Vec3::new(self.finite(), self.finite(), self.finite());
                Mat3::from_rows([d.x, o.x, o.y], [o.x, d.y, o.z], [o.y, o.z, d.z])
            }
        }
    }

    /// A valid inertia (retries [`Gen::inertia_tensor`] until the constructor accepts one; a
    /// fixed body after 100 refusals).
    pub fn inertia(&mut self) -> gyrostat::dynamics::Inertia<T> {
        for _ in 0..100 {
            if let Ok(i) = gyrostat::dynamics::Inertia::try_from_tensor(self.inertia_tensor()) {
                return i;
            }
        }
        gyrostat::dynamics::Inertia::try_from_principal(Vec3::new(
            Self::t(6.0),
            Self::t(4.0),
            Self::t(3.0),
        ))
        .unwrap_or_else(|_| unreachable!("a physical fixed body"))
    }

    /// A valid inertia with a diagonal tensor.
    pub fn diagonal_inertia(&mut self) -> gyrostat::dynamics::Inertia<T> {
        for _ in 0..100 {
            let m = self.moments_f64();
            let v = Vec3::from_array(m.map(|c| Self::t(c)));
            if let Ok(i) = gyrostat::dynamics::Inertia::try_from_principal(v) {
                return i;
            }
        }
        gyrostat::dynamics::Inertia::try_from_principal(Vec3::new(
            Self::t(6.0),
            Self::t(4.0),
            Self::t(3.0),
        ))
        .unwrap_or_else(|_| unreachable!("a physical fixed body"))
    }

    /// An angular momentum for `inertia` (body frame): ordinary, zero, along a principal axis
    /// (stationary), on or next to the separatrix, huge, tiny, or any vector.
    pub fn momentum(&mut self, inertia: &gyrostat::dynamics::Inertia<T>) -> Vec3<T> {
        let p = inertia.principal_rotation();
        let i = crate::cast::v64(inertia.principal_moments());
        let principal = match self.rng.below(10) {
            0..=3 => {
                let d = self.unit_direction();
                let m = self.magnitude_in(1e-2, 1e2);
                d.map(|c| c * m)
            }
            4 => {
                let mut a = [0.0; 3];
                a[self.rng.below(3)] = self.rng.sign() * self.magnitude_in(1e-2, 1e2);
                a
            }
            5 => {
                // On (or a few ulp off) the separatrix J² = 2E·I_mid: with the moments sorted
                // lo < mid < hi, J_lo² (I_mid − I_lo)/I_lo = J_hi² (I_hi − I_mid)/I_hi.
                let mut idx = [0usize, 1, 2];
                idx.sort_by(|&a, &b| i[a].total_cmp(&i[b]));
                let [lo, mid, hi] = idx;
                let a = (i[hi] - i[mid]) / i[hi];
                let b = (i[mid] - i[lo]) / i[lo];
                let j_lo = self.rng.range(0.1, 2.0);
                let j_hi = if a > 0.0 { j_lo * (b / a).sqrt() } else { 1.0 };
                let j_hi = j_hi * (1.0 + self.rng.range(-64.0, 64.0) * self.lim.eps);
                let mut v = [0.0; 3];
                v[lo] = self.rng.sign() * j_lo;
                v[mid] = self.rng.sign() * self.rng.range(0.0, 3.0);
                v[hi] = self.rng.sign() * j_hi;
                v
            }
            6 => {
                let d = self.unit_direction();
                let m = self.any_magnitude();
                d.map(|c| c * m)
            }
            _ => return self.vec(),
        };
        let jp = Vec3::from_array(principal.map(|c| Self::t(c)));
        if inertia.is_diagonal() {
            jp
        } else {
            p.rotate(jp)
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The estimator's covariance

/// `P = [[A, B], [Bᵀ, C]]` of the estimator as a dense 6×6 matrix in f64.
pub fn covariance_dense<T: Real>(p: &gyrostat::estimation::Covariance<T>) -> [[f64; 6]; 6] {
    let mut m = [[0.0; 6]; 6];
    for i in 0..3 {
        for j in 0..3 {
            m[i][j] = p.attitude.m[i][j].to_f64();
            m[i][j + 3] = p.cross.m[i][j].to_f64();
            m[j + 3][i] = p.cross.m[i][j].to_f64();
            m[i + 3][j + 3] = p.bias.m[i][j].to_f64();
        }
    }
    m
}

/// Whether `m + δI` has a Cholesky factor (in f64), `δ = tol·max|mᵢᵢ|`: `m` is positive
/// semi-definite up to a perturbation of relative size `tol`.
pub fn psd_within(m: &[[f64; 6]; 6], tol: f64) -> bool {
    let scale = (0..6).map(|i| m[i][i].abs()).fold(0.0, f64::max);
    let delta = tol * scale + f64::MIN_POSITIVE;
    let mut l = [[0.0f64; 6]; 6];
    for j in 0..6 {
        let mut d = m[j][j] + delta;
        for x in l[j].iter().take(j) {
            d -= x * x;
        }
        if d.is_nan() || d <= 0.0 {
            return false;
        }
        l[j][j] = d.sqrt();
        for i in j + 1..6 {
            let s = m[i][j] - (0..j).map(|k| l[i][k] * l[j][k]).sum::<f64>();
            l[i][j] = s / l[j][j];
        }
    }
    true
}

/// The estimator covariance's contract: finite; its attitude and bias blocks exactly equal to
/// their transposes (the cross block is stored once); positive semi-definite to 64 ε of the
/// type relative to its largest variance.
pub fn covariance_ok<T: Real>(p: &gyrostat::estimation::Covariance<T>) -> Check {
    let m = covariance_dense(p);
    if m.iter().flatten().any(|x| !x.is_finite()) {
        return bad(format!("non-finite covariance {m:?}"));
    }
    for i in 0..3 {
        for j in 0..3 {
            if p.attitude.m[i][j] != p.attitude.m[j][i] || p.bias.m[i][j] != p.bias.m[j][i] {
                return bad(format!("asymmetric covariance {m:?}"));
            }
        }
    }
    if !psd_within(&m, 64.0 * T::EPSILON.to_f64()) {
        return bad(format!("covariance not positive semi-definite {m:?}"));
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// Families and the runner

/// One API family: a name and one trial (draw an input, call, check).
pub struct Family<T> {
    /// The name in the table (the API called).
    pub name: &'static str,
    /// One trial.
    pub trial: fn(&mut Gen<T>) -> Trial,
}

/// `Family { name, trial }` in one line.
#[macro_export]
macro_rules! family {
    ($name:expr, $trial:expr) => {
        $crate::campaign::Family {
            name: $name,
            trial: $trial,
        }
    };
}

/// The counts of one family and type.
#[derive(Clone, Debug, Default)]
pub struct Tally {
    /// The family's name.
    pub name: &'static str,
    /// `"f32"` or `"f64"`.
    pub type_name: &'static str,
    /// Inputs tried.
    pub inputs: u64,
    /// `Ok` results (finite, within their invariant).
    pub ok: u64,
    /// Typed errors by variant.
    pub errors: BTreeMap<String, u64>,
    /// `Ok` results that break their invariant.
    pub bad: u64,
    /// Panics.
    pub panics: u64,
    /// The first few failures (input and reason).
    pub examples: Vec<String>,
    /// The largest `||q| − 1|`, in ε of the type, of the unit quaternions the family's checks
    /// accepted (0 when it returns none).
    pub worst_unit: f64,
    /// Wall time, seconds.
    pub seconds: f64,
}

/// The number of inputs per family and type: `GYROSTAT_CAMPAIGN_N`, else [`DEFAULT_INPUTS`].
pub fn inputs_per_family() -> u64 {
    std::env::var("GYROSTAT_CAMPAIGN_N")
        .ok()
        .and_then(|s| s.replace('_', "").parse().ok())
        .unwrap_or(DEFAULT_INPUTS)
}

fn base_seed() -> u64 {
    std::env::var("GYROSTAT_CAMPAIGN_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(DEFAULT_SEED)
}

/// A stable 64-bit hash of a name (FNV-1a), for per-family seeds.
fn fnv(s: &str) -> u64 {
    s.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// Runs `n` trials of one family.
pub fn run_family<T: Tolerance>(f: &Family<T>, n: u64) -> Tally {
    let seed = base_seed() ^ fnv(f.name) ^ (T::INDEX as u64).wrapping_mul(0x9e37_79b9);
    let mut g = Gen::<T>::new(seed);
    let mut t = Tally {
        name: f.name,
        type_name: T::NAME,
        ..Tally::default()
    };
    let start = Instant::now();
    WORST_UNIT.with(|w| w.set(0.0));
    for _ in 0..n {
        t.inputs += 1;
        match (f.trial)(&mut g) {
            Trial::Ok => t.ok += 1,
            Trial::Err(e) => *t.errors.entry(format!("{e:?}")).or_insert(0) += 1,
            Trial::Bad(why) => {
                t.bad += 1;
                if t.examples.len() < 8 {
                    t.examples.push(format!("bad: {why}"));
                }
            }
            Trial::Panic(why) => {
                t.panics += 1;
                if t.examples.len() < 8 {
                    t.examples.push(why);
                }
            }
        }
    }
    t.seconds = start.elapsed().as_secs_f64();
    t.worst_unit = WORST_UNIT.with(Cell::get);
    t
}

fn group(n: u64) -> String {
    let s = n.to_string();
    let mut out = String::new();
    for (i, ch) in s.chars().enumerate() {
        if i > 0 && (s.len() - i).is_multiple_of(3) {
            out.push('\u{202f}');
        }
        out.push(ch);
    }
    out
}

/// The Markdown table of a campaign section: one row per family and type.
pub fn table(tallies: &[Tally]) -> String {
    let mut s = String::new();
    s.push_str(
        "| family | type | inputs | `Ok` | typed errors | bad `Ok` | panics | max ‖q‖−1 (ε) | s |\n",
    );
    s.push_str("|---|---|--:|--:|---|--:|--:|--:|--:|\n");
    for t in tallies {
        let errors = if t.errors.is_empty() {
            "—".to_string()
        } else {
            t.errors
                .iter()
                .map(|(k, v)| format!("{k} {}", group(*v)))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let worst = if t.worst_unit > 0.0 {
            format!("{:.1}", t.worst_unit)
        } else {
            "—".into()
        };
        let _ = writeln!(
            s,
            "| `{}` | {} | {} | {} | {} | {} | {} | {} | {:.2} |",
            t.name,
            t.type_name,
            group(t.inputs),
            group(t.ok),
            errors,
            t.bad,
            t.panics,
            worst,
            t.seconds
        );
    }
    s
}

/// Runs every family for f32 and f64 (the two types on two threads), prints the table and the
/// time, writes the table into `ROBUSTNESS.md` between the markers of `section` when
/// `GYROSTAT_CAMPAIGN_WRITE=1`, and fails listing every panic and broken invariant.
pub fn run_campaign(section: &str, f32s: Vec<Family<f32>>, f64s: Vec<Family<f64>>) {
    let n = inputs_per_family();
    run_campaign_n(section, n, n, f32s, f64s);
}

/// [`run_campaign`] for families whose input is a stream of about `updates` calls (the
/// estimator's): `n/updates` streams per family and type, `n` = [`inputs_per_family`], so
/// that the setting counts calls as the other campaigns do (the long setting, 10⁶, is 10⁶
/// calls per family and type).
pub fn run_stream_campaign(
    section: &str,
    updates: u64,
    f32s: Vec<Family<f32>>,
    f64s: Vec<Family<f64>>,
) {
    let n = inputs_per_family();
    run_campaign_n(section, n, (n / updates).max(1), f32s, f64s);
}

/// Runs `trials` inputs of every family; `n` is the setting (`GYROSTAT_CAMPAIGN_N`) the table
/// is written for.
fn run_campaign_n(
    section: &str,
    n: u64,
    trials: u64,
    f32s: Vec<Family<f32>>,
    f64s: Vec<Family<f64>>,
) {
    let start = Instant::now();
    let (a, b) = std::thread::scope(|s| {
        let h32 = s.spawn(|| {
            f32s.iter()
                .map(|f| run_family(f, trials))
                .collect::<Vec<_>>()
        });
        let h64 = s.spawn(|| {
            f64s.iter()
                .map(|f| run_family(f, trials))
                .collect::<Vec<_>>()
        });
        (
            h32.join().expect("f32 campaign thread"),
            h64.join().expect("f64 campaign thread"),
        )
    });
    let wall = start.elapsed().as_secs_f64();
    // Interleave: each family's f32 row, then its f64 row.
    let mut rows = Vec::new();
    for (x, y) in a.iter().zip(b.iter()) {
        rows.push(x.clone());
        rows.push(y.clone());
    }
    let t = table(&rows);
    let calls: u64 = rows.iter().map(|r| r.inputs).sum();
    let cpu: f64 = rows.iter().map(|r| r.seconds).sum();
    println!(
        "campaign `{section}`: {trials} inputs per family and type, {calls} in all, {wall:.1} s wall, \
         {cpu:.1} s in the families"
    );
    for r in &rows {
        println!(
            "  {:<44} {} {:>8.2} s  ok {:>9}  errors {:>9}  bad {}  panics {}",
            r.name,
            r.type_name,
            r.seconds,
            r.ok,
            r.errors.values().sum::<u64>(),
            r.bad,
            r.panics
        );
    }
    println!("{t}");
    if std::env::var("GYROSTAT_CAMPAIGN_WRITE").as_deref() == Ok("1") {
        write_section(section, n, trials, calls, cpu, &t);
    }
    let failures: Vec<String> = rows
        .iter()
        .filter(|r| r.bad > 0 || r.panics > 0)
        .map(|r| {
            format!(
                "{} ({}): {} bad Ok, {} panics\n    {}",
                r.name,
                r.type_name,
                r.bad,
                r.panics,
                r.examples.join("\n    ")
            )
        })
        .collect();
    assert!(
        failures.is_empty(),
        "campaign `{section}` found defects:\n{}",
        failures.join("\n")
    );
}

/// The setting a count belongs to in `ROBUSTNESS.md`: `ci` for [`DEFAULT_INPUTS`] (what the
/// README test command runs), `long` for any other count (the count is written beside the table).
fn setting(n: u64) -> &'static str {
    if n == DEFAULT_INPUTS { "ci" } else { "long" }
}

/// Rewrites the table of `section` for the setting of `n` in `ROBUSTNESS.md` (between
/// `<!-- campaign:SECTION:SETTING -->` and `<!-- /campaign:SECTION:SETTING -->`).
fn write_section(section: &str, n: u64, trials: u64, calls: u64, cpu: f64, table: &str) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../ROBUSTNESS.md");
    let doc = std::fs::read_to_string(&path).expect("ROBUSTNESS.md");
    let tag = format!("campaign:{section}:{}", setting(n));
    let open = format!("<!-- {tag} -->");
    let close = format!("<!-- /{tag} -->");
    let (Some(a), Some(b)) = (doc.find(&open), doc.find(&close)) else {
        panic!("ROBUSTNESS.md has no markers {open} … {close}");
    };
    let seed = match std::env::var("GYROSTAT_CAMPAIGN_SEED") {
        Ok(s) => format!("GYROSTAT_CAMPAIGN_SEED={s} "),
        Err(_) => String::new(),
    };
    let count = if n == DEFAULT_INPUTS {
        String::new()
    } else {
        format!("GYROSTAT_CAMPAIGN_N={n} ")
    };
    let body = format!(
        "{open}\n`{seed}{count}cargo test --release -p host-tests --test robustness {section}:: \
         -- --nocapture`: {} inputs per family and type, {} calls in all, seed {:#x}, \
         {cpu:.1} s of one core in the families.\n\n{table}",
        group(trials),
        group(calls),
        base_seed()
    );
    let new = format!("{}{}{}", &doc[..a], body, &doc[b..]);
    std::fs::write(&path, new).expect("write ROBUSTNESS.md");
}
