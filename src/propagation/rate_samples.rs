//! The rate-sample path: 4th-order integrators from equally spaced angular-rate samples.
//!
//! Most MEMS gyros deliver rate samples `ωₖ = ω(k h)` (a FIFO at a fixed output data rate), not
//! increments. Three integrators of `q̇ = ½ q ⊗ (0, ω(t))` are offered, each advancing one
//! sample interval `[tₖ, tₖ₊₁]` per step:
//!
//! - **Magnus-4** ([`magnus4_step`]): `q ← q ⊗ exp(φ)` with
//!   `φ = (h/2)(ω₁ + ω₂) + (√3/12) h² ω₁ × ω₂`, the two-point Gauss truncation of the Magnus
//!   series (Iserles, Munthe-Kaas, Nørsett & Zanna 2000, *Acta Numerica* 9, §4; Blanes, Casas,
//!   Oteo & Ros 2009, *Phys. Rep.* 470 eq. (257) with the sign of the commutator flipped because
//!   the attitude is multiplied on the right). One exponential.
//! - **CF4**, commutator-free ([`cf4_step`]): `q ← q ⊗ exp(h(a ω₁ + b ω₂)) ⊗ exp(h(b ω₁ + a ω₂))`
//!   with `a = ¼ + √3/6`, `b = ¼ − √3/6` (Blanes & Moan 2006, *Appl. Numer. Math.* 56; Celledoni,
//!   Marthinsen & Owren 2003). Two exponentials, no cross product. The exponential weighted
//!   towards the EARLIER node is applied first (leftmost, since body-frame rotations compose on
//!   the right); in the other order the second-order commutator term has the wrong sign and
//!   the method drops to order 2.
//! - **RK4** on the quaternion ([`rk4_step`]) with the rates at the start, middle and end of the
//!   interval, followed by the renormalisation policy: the classical baseline. It does not stay
//!   on the unit sphere by itself.
//!
//! # How samples map to the nodes
//! `ω₁, ω₂` are the rates at the Gauss nodes `tₖ + (½ ∓ √3/6) h`; RK4 needs `ω(tₖ + h/2)`.
//! Neither falls on a sample, so they are taken from the cubic Lagrange interpolant through four
//! consecutive samples that contain the interval. Its error is `O(h⁴)` in `ω`, so each step
//! keeps a local error `O(h⁵)` and all three methods converge with order 4 (measured in
//! `host-tests/tests/propagation_rates.rs`). [`RateIntegrator`] uses, for the interval ending at
//! the newest sample `k`, the samples `k−3 … k` (no look-ahead, so no latency), except at the
//! start, where the first three intervals wait for sample 3 and use samples `0 … 3`. A record of
//! only three samples uses the quadratic interpolant (still order 3 locally), one of two samples
//! the linear one (order 2).
//!
//! The interpolation, not the integrator, dominates the error: on the coning test motion the
//! three methods fed samples agree to within 4% of each other and are about 35× less accurate
//! than the same steps fed the exact rates at the nodes (measured in
//! `host-tests/tests/propagation_rates.rs`). If a sensor can deliver rates at two points per
//! interval (or the step can span two sample intervals), feed [`magnus4_step`] / [`cf4_step`]
//! directly. A centred window (`k−1 … k+2` for `[tₖ, tₖ₊₁]`) was measured only 1.65× more
//! accurate than the backward one on the same motion, not worth its one-sample latency.

use heapless::Vec as HVec;

#[cfg(doc)]
use crate::propagation::compensated::CompensatedAttitude;
use crate::propagation::compensated::PropagatedAttitude;
use crate::propagation::exponential::apply_rotation_vector;
use crate::propagation::kinematics::quat_rate_body;
use crate::propagation::Normalization;
use crate::step_limit::within_step_limit;
use crate::{Error, Quat, Real, UnitQuat, Vec3};

/// `√3`, to the f64 rounding.
const SQRT_3: f64 = 1.732_050_807_568_877_2;
/// First Gauss–Legendre node on `[0, 1]`: `½ − √3/6`.
pub const GAUSS_NODE_1: f64 = 0.5 - SQRT_3 / 6.0;
/// Second Gauss–Legendre node on `[0, 1]`: `½ + √3/6`.
pub const GAUSS_NODE_2: f64 = 0.5 + SQRT_3 / 6.0;
/// CF4 weight of the near node: `¼ + √3/6`.
const CF4_A: f64 = 0.25 + SQRT_3 / 6.0;
/// CF4 weight of the far node: `¼ − √3/6`.
const CF4_B: f64 = 0.25 - SQRT_3 / 6.0;

/// Lagrange basis on the nodes `0, 1, …, M−1` evaluated at `tau`.
const fn lagrange<const M: usize>(tau: f64) -> [f64; M] {
    let mut w = [0.0; M];
    let mut i = 0;
    while i < M {
        let mut num = 1.0;
        let mut den = 1.0;
        let mut j = 0;
        while j < M {
            if j != i {
                num *= tau - j as f64;
                den *= i as f64 - j as f64;
            }
            j += 1;
        }
        w[i] = num / den;
        i += 1;
    }
    w
}

/// Interpolation weights for one interval `[j, j+1]` of an `M`-sample window:
/// `[Gauss node 1, Gauss node 2, midpoint, start, end]`.
const fn interval_weights<const M: usize>(j: usize) -> [[f64; M]; 5] {
    let t = j as f64;
    [
        lagrange::<M>(t + GAUSS_NODE_1),
        lagrange::<M>(t + GAUSS_NODE_2),
        lagrange::<M>(t + 0.5),
        lagrange::<M>(t),
        lagrange::<M>(t + 1.0),
    ]
}

/// The interpolation rows of one interval of an `M`-sample window:
/// `[Gauss node 1, Gauss node 2, midpoint, start, end]`.
pub(crate) type Weights<const M: usize> = [[f64; M]; 5];

const W4: [[[f64; 4]; 5]; 3] = [
    interval_weights::<4>(0),
    interval_weights::<4>(1),
    interval_weights::<4>(2),
];
const W3: [[[f64; 3]; 5]; 2] = [interval_weights::<3>(0), interval_weights::<3>(1)];
const W2: [[[f64; 2]; 5]; 1] = [interval_weights::<2>(0)];

/// Row indices into the weight tables.
pub(crate) const G1: usize = 0;
pub(crate) const G2: usize = 1;
pub(crate) const MID: usize = 2;
pub(crate) const START: usize = 3;
pub(crate) const END: usize = 4;

/// The interpolant `Σᵢ wᵢ sᵢ` at one row of weights.
///
/// An index loop rather than an iterator fold (here and in [`interp_difference`]): it unrolls
/// inside the step, so the f64 weights become constants of `T`. A `Zip::fold` that the optimiser
/// leaves out of line gets the weights by pointer and converts each one at run time (a
/// soft-float `f64 → f32` call on a single-precision FPU).
#[inline(always)]
fn interp<T: Real, const M: usize>(s: &[Vec3<T>; M], w: &[f64; M]) -> Vec3<T> {
    let mut acc = Vec3::ZERO;
    let mut i = 0;
    while i < M {
        acc += s[i].scale(T::from_f64(w[i]));
        i += 1;
    }
    acc
}

/// The interpolant in difference form, `s_last + Σᵢ wᵢ (sᵢ − s_last)` (the weights add up to
/// one): the same value as [`interp`] in exact arithmetic, but a constant rate comes out exactly
/// and a slowly varying one with the rounding of its small differences only, where [`interp`]
/// rounds each weighted sample (and the weights themselves do not add up to one in f32). The
/// compensated step uses it.
#[inline(always)]
pub(crate) fn interp_difference<T: Real, const M: usize>(
    s: &[Vec3<T>; M],
    w: &[f64; M],
) -> Vec3<T> {
    let last = s.last().copied().unwrap_or(Vec3::ZERO);
    let mut acc = last;
    let mut i = 0;
    while i + 1 < M {
        acc += (s[i] - last).scale(T::from_f64(w[i]));
        i += 1;
    }
    acc
}

/// The rates at the two Gauss nodes of interval `interval` (0, 1 or 2; larger values mean 2)
/// of a window of four consecutive equally spaced samples, from their cubic interpolant.
#[inline]
pub fn gauss_rates<T: Real>(window: &[Vec3<T>; 4], interval: usize) -> (Vec3<T>, Vec3<T>) {
    let w = match interval {
        0 => &W4[0],
        1 => &W4[1],
        _ => &W4[2],
    };
    (interp(window, &w[G1]), interp(window, &w[G2]))
}

/// The rate at the midpoint of interval `interval` (0, 1 or 2; larger values mean 2) of a
/// window of four consecutive equally spaced samples, from their cubic interpolant.
#[inline]
pub fn midpoint_rate<T: Real>(window: &[Vec3<T>; 4], interval: usize) -> Vec3<T> {
    let w = match interval {
        0 => &W4[0],
        1 => &W4[1],
        _ => &W4[2],
    };
    interp(window, &w[MID])
}

/// The Magnus-4 rotation vector over one step `h` from the rates at the two Gauss nodes:
/// `φ = (h/2)(ω₁ + ω₂) + (√3/12) h² ω₁ × ω₂` (earlier node first in the cross product).
///
/// The commutator term is formed as `(hω₁) × (hω₂)`, products of the step's own angles, so that
/// neither `h²` (a long step at a slow rate) nor `ω₁ × ω₂` (a short step at a fast rate)
/// overflows: the result is finite whenever `|ω|·h` is (the domain of the step functions).
#[inline]
pub fn magnus4_rotation_vector<T: Real>(w1: Vec3<T>, w2: Vec3<T>, h: T) -> Vec3<T> {
    let (a, b) = (w1.scale(h), w2.scale(h));
    (a + b).scale(T::HALF) + a.cross(b).scale(T::from_f64(SQRT_3 / 12.0))
}

/// One Magnus-4 step: `q ⊗ exp(φ)` with φ from [`magnus4_rotation_vector`]. Unchecked, not
/// renormalised (a product of unit quaternions, unit to about one ulp). Domain (of this and the
/// other step functions of this module): finite rates with `|ω|·h` at most a few times
/// [`MAX_STEP_ANGLE`](crate::step_limit::MAX_STEP_ANGLE) (the series stop converging at `2π`).
#[inline]
pub fn magnus4_step<T: Real>(q: UnitQuat<T>, w1: Vec3<T>, w2: Vec3<T>, h: T) -> UnitQuat<T> {
    apply_rotation_vector(q, magnus4_rotation_vector(w1, w2, h), Normalization::None)
}

/// The two CF4 rotation vectors `(φ_first, φ_second)` over one step `h` from the Gauss-node
/// rates: `φ_first = h(a ω₁ + b ω₂)`, `φ_second = h(b ω₁ + a ω₂)`, `a = ¼ + √3/6`, `b = ¼ − √3/6`.
/// The attitude update is `q ⊗ exp(φ_first) ⊗ exp(φ_second)`, in this order.
#[inline]
pub fn cf4_rotation_vectors<T: Real>(w1: Vec3<T>, w2: Vec3<T>, h: T) -> (Vec3<T>, Vec3<T>) {
    let a = h * T::from_f64(CF4_A);
    let b = h * T::from_f64(CF4_B);
    (w1.scale(a) + w2.scale(b), w1.scale(b) + w2.scale(a))
}

/// One commutator-free CF4 step: `q ⊗ exp(φ_first) ⊗ exp(φ_second)` (see
/// [`cf4_rotation_vectors`]). Unchecked, not renormalised.
#[inline]
pub fn cf4_step<T: Real>(q: UnitQuat<T>, w1: Vec3<T>, w2: Vec3<T>, h: T) -> UnitQuat<T> {
    cf4_update(q, w1, w2, h, Normalization::None)
}

/// [`cf4_step`] followed by the normalisation policy: two applications of the update kernel
/// [`apply_rotation_vector`], the policy applied once, after the second.
#[inline]
fn cf4_update<T: Real>(
    q: UnitQuat<T>,
    w1: Vec3<T>,
    w2: Vec3<T>,
    h: T,
    norm: Normalization,
) -> UnitQuat<T> {
    let (p1, p2) = cf4_rotation_vectors(w1, w2, h);
    apply_rotation_vector(apply_rotation_vector(q, p1, Normalization::None), p2, norm)
}

/// One classical RK4 step of `q̇ = ½ q ⊗ (0, ω)` with the rates at the start, midpoint and end
/// of the step. Returns the raw quaternion, off the unit sphere by the truncation error
/// (`|q|² = 1 − θ⁶/4608 + …` for the step angle `θ = |ω| h`): apply a [`Normalization`] to it.
/// Within [`MAX_STEP_ANGLE`](crate::step_limit::MAX_STEP_ANGLE) `|q|²` stays above 0.85.
#[inline]
pub fn rk4_step<T: Real>(
    q: Quat<T>,
    w_start: Vec3<T>,
    w_mid: Vec3<T>,
    w_end: Vec3<T>,
    h: T,
) -> Quat<T> {
    let hh = h * T::HALF;
    let k1 = quat_rate_body(q, w_start);
    let k2 = quat_rate_body(q + k1.scale(hh), w_mid);
    let k3 = quat_rate_body(q + k2.scale(hh), w_mid);
    let k4 = quat_rate_body(q + k3.scale(h), w_end);
    q + (k1 + (k2 + k3).scale(T::TWO) + k4).scale(h / T::from_f64(6.0))
}

/// The plain step of [`RateIntegrator`] over one interval of an `M`-sample window.
#[inline(always)]
pub(crate) fn advance_plain<T: Real, const M: usize>(
    q: UnitQuat<T>,
    method: RateMethod,
    s: &[Vec3<T>; M],
    w: &Weights<M>,
    h: T,
    norm: Normalization,
) -> UnitQuat<T> {
    match method {
        RateMethod::Magnus4 => {
            let phi = magnus4_rotation_vector(interp(s, &w[G1]), interp(s, &w[G2]), h);
            apply_rotation_vector(q, phi, norm)
        }
        RateMethod::Cf4 => cf4_update(q, interp(s, &w[G1]), interp(s, &w[G2]), h, norm),
        RateMethod::Rk4 => {
            let q = rk4_step(
                *q.as_quat(),
                interp(s, &w[START]),
                interp(s, &w[MID]),
                interp(s, &w[END]),
                h,
            );
            norm.apply_quat(q)
        }
    }
}

/// The checks of [`RateIntegrator::push`] on one sample, with its errors.
///
/// `|ωᵢ| < MAX/4 ⇔ 4ω is finite` (and a finite `4ω` implies a finite `ω`, so one test covers
/// both until it fails): then every weighted sum of the window (the weights' magnitudes add up
/// to at most 1.625) and every RK4 stage stays finite. Out of line, like
/// [`RateIntegrator::start_up`], so that `push` stays small enough for LLVM to inline the whole
/// steady-state step into it (measured on the Cortex-M4F: otherwise the compensated step's
/// quaternion products stay calls).
#[inline(never)]
fn check_sample<T: Real>(omega: Vec3<T>, dt: T) -> Result<(), Error> {
    if !omega.scale(T::from_f64(4.0)).is_finite() {
        return Err(if omega.is_finite() {
            Error::InvalidArgument
        } else {
            Error::NonFinite
        });
    }
    if !within_step_limit(omega.scale(dt)) {
        return Err(Error::StepTooLong);
    }
    Ok(())
}

/// Which rate-sample integrator a [`RateIntegrator`] runs.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RateMethod {
    /// [`magnus4_step`]: one exponential and one cross product per step.
    Magnus4,
    /// [`cf4_step`]: two exponentials per step.
    Cf4,
    /// [`rk4_step`] followed by the normalisation policy.
    Rk4,
}

/// The attitudes at the sample times a [`RateIntegrator`] call newly reached, oldest first.
pub type Attitudes<T> = HVec<UnitQuat<T>, 3>;

/// Streaming rate-sample integrator: owns the attitude and the last four samples.
///
/// Feed the samples `ω₀, ω₁, …` (body frame, rad/s, equally spaced by `dt`) with
/// [`RateIntegrator::push`]; it returns the attitudes at the sample times it newly reached:
/// `[q(t₀)] = [q0]` after sample 0, nothing after samples 1 and 2, `[q(t₁), q(t₂), q(t₃)]`
/// after sample 3 (the start-up window), then `[q(tₖ)]` after each sample `k`. A record of
/// fewer than four samples is completed by [`RateIntegrator::finish`]. See the module docs for
/// the interpolation.
///
/// The attitude it carries is a [`UnitQuat`] (the plain update) or, when it is started from a
/// [`CompensatedAttitude`], the compensated pair (see [`crate::propagation::compensated`]).
#[derive(Clone, Debug)]
pub struct RateIntegrator<T, A = UnitQuat<T>> {
    q: A,
    method: RateMethod,
    norm: Normalization,
    dt: T,
    /// `dt`'s rounding remainder (used by the compensated attitude).
    dt_lo: T,
    /// The last samples, oldest first; the first `count` are valid while `count < 4`.
    window: [Vec3<T>; 4],
    count: u8,
}

impl<T: Real, A: PropagatedAttitude<T>> RateIntegrator<T, A> {
    /// Starts at attitude `q0` (a [`UnitQuat`] or a [`CompensatedAttitude`]) with sample
    /// interval `dt` (seconds).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite `dt` or `q0`; [`Error::InvalidArgument`] for
    /// `dt ≤ 0`.
    pub fn new(q0: A, method: RateMethod, norm: Normalization, dt: T) -> Result<Self, Error> {
        if !dt.is_finite() || !q0.attitude().as_quat().is_finite() {
            return Err(Error::NonFinite);
        }
        if dt <= T::ZERO {
            return Err(Error::InvalidArgument);
        }
        Ok(Self {
            q: q0,
            method,
            norm,
            dt,
            dt_lo: T::ZERO,
            window: [Vec3::ZERO; 4],
            count: 0,
        })
    }

    /// Sets the rounding remainder of the sample interval, `dt_lo = dt_exact − dt` (for example
    /// `(0.001 − f64::from(0.001f32)) as f32` for 1 kHz in f32), which the compensated attitude
    /// adds to every step: without it an f32 step of 1 ms is 4.7e-8 relative too long, 1.8e-4 rad
    /// an hour at 1 rad/s. The plain attitude ignores it. A non-finite value is ignored.
    pub fn with_step_remainder(mut self, dt_lo: T) -> Self {
        if dt_lo.is_finite() {
            self.dt_lo = dt_lo;
        }
        self
    }

    /// The latest attitude computed (at the time of the newest sample once four have arrived).
    pub fn attitude(&self) -> UnitQuat<T> {
        self.q.attitude()
    }

    /// The carried attitude (for a [`CompensatedAttitude`], with its low part).
    pub fn carried_attitude(&self) -> A {
        self.q
    }

    /// One step over an interval of an `M`-sample window, given that interval's weight rows.
    #[inline(always)]
    fn advance<const M: usize>(&mut self, s: &[Vec3<T>; M], w: &Weights<M>) -> UnitQuat<T> {
        self.q = self
            .q
            .rates(self.method, s, w, self.dt, self.dt_lo, self.norm);
        self.q.attitude()
    }

    /// The fourth sample: completes the start-up window and integrates its three intervals.
    /// Once per record, so kept out of [`RateIntegrator::push`]'s steady-state path.
    #[cold]
    #[inline(never)]
    fn start_up(&mut self, omega: Vec3<T>) -> Attitudes<T> {
        let mut out = Attitudes::new();
        let [a, b, c, _] = self.window;
        let s = [a, b, c, omega];
        self.window = s;
        self.count = 4;
        for w in &W4 {
            let q = self.advance(&s, w);
            let _ = out.push(q);
        }
        out
    }

    /// Adds the next rate sample (rad/s, body frame) and integrates every interval it completes.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite component; [`Error::InvalidArgument`] for a
    /// component beyond a quarter of the type's largest value (the interpolant's weighted sums of
    /// four samples would overflow); [`Error::StepTooLong`] when the
    /// sample turns the body by more than [`MAX_STEP_ANGLE`](crate::step_limit::MAX_STEP_ANGLE) in one sample interval
    /// (`|ω|·dt > π`, where the methods' series stop converging; the interpolated node rates are
    /// at most 1.625 times the largest sample of the window, the largest sum of the magnitudes of
    /// the cubic Lagrange weights, so every step stays below `2π`). Either way the sample is
    /// discarded and the state is unchanged.
    pub fn push(&mut self, omega: Vec3<T>) -> Result<Attitudes<T>, Error> {
        check_sample(omega, self.dt)?;
        let mut out = Attitudes::new();
        match self.count {
            0..=2 => {
                if let Some(slot) = self.window.get_mut(usize::from(self.count)) {
                    *slot = omega;
                }
                self.count += 1;
                if self.count == 1 {
                    let _ = out.push(self.q.attitude());
                }
            }
            3 => out = self.start_up(omega),
            _ => {
                let [_, b, c, d] = self.window;
                let s = [b, c, d, omega];
                self.window = s;
                let q = self.advance(&s, &W4[2]);
                let _ = out.push(q);
            }
        }
        Ok(out)
    }

    /// Ends the record: integrates what a record of fewer than four samples left pending (two
    /// samples: the linear interpolant, order 2; three: the quadratic one) and returns those
    /// attitudes. After four or more samples everything was already integrated and the result is
    /// empty.
    pub fn finish(mut self) -> Attitudes<T> {
        let mut out = Attitudes::new();
        let [a, b, c, _] = self.window;
        match self.count {
            2 => {
                let _ = out.push(self.advance(&[a, b], &W2[0]));
            }
            3 => {
                for w in &W3 {
                    let q = self.advance(&[a, b, c], w);
                    let _ = out.push(q);
                }
            }
            _ => {}
        }
        out
    }
}

#[cfg(feature = "defmt")]
impl<T: Real + defmt::Format> defmt::Format for RateIntegrator<T> {
    fn format(&self, f: defmt::Formatter<'_>) {
        defmt::write!(
            f,
            "RateIntegrator(q={}, method={}, norm={}, dt={}, samples={})",
            self.q,
            self.method,
            self.norm,
            self.dt,
            self.count
        )
    }
}
