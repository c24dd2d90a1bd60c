//! The fixed-point attitude without a rounding bias: [`CarriedAttitude`], the attitude with the
//! discarded low bits of each rounding carried into the next update (the fixed-point
//! counterpart of the f32/f64 [`CompensatedAttitude`](super::CompensatedAttitude), with the same
//! methods). Why it exists and what was measured: [`crate::fixed`], "Rounding bias".

use crate::propagation::ConingTerms;
use crate::propagation::attitude::{PropagatedAttitude, sealed::Propagate};
use crate::propagation::coning::{ConingRule, coning_terms_for, two_sample_terms};
use crate::propagation::kernels::sealed::Form;
use crate::propagation::kernels::{RotationVectorForm, check_rotation_vector};
use crate::propagation::normalization::Normalization;
use crate::propagation::rate_samples::{RateMethod, Weights};
use crate::real::Fixed;
use crate::real::wide::{mul_wide, round_shift, saturate};
use crate::rotation::half_angle_series;
use crate::{Error, Real, Ring, UnitQuat, Vec3};

/// Extra fraction bits of the rotation vector and of the rotation increment inside an update
/// (as in the plain fused update, `fixed/exp.rs`).
const FINE: u32 = 3;

/// A fixed-point attitude with the rounding residuals of its updates carried: `q` (the attitude
/// in the format, what firmware reads and logs) and the low bits that each update's roundings
/// discarded, added back into the next update (error feedback, exact in integers).
///
/// Three roundings of the plain update ([`UnitQuat::mul_exp_unchecked`] of the
/// [`ConingTerms`] with [`Normalization::Fast`]) repeat their error update after update when the motion repeats or
/// changes slowly, and so integrate into a drift (measured, see the [`crate::fixed`] docs); here
/// each keeps its residual:
/// - the coning term `lever × last`, formed exactly and rounded to the fine scale 2^−(F+3): its
///   residual (units 2^−2F) is added to the next coning term;
/// - the rotation increment `u = sin(θ/2)/θ·φ` at 2^−(F+3): its residual (units 2^−(2F+3)) is
///   added to the next one;
/// - the attitude itself, each component of `q ⊗ (cos(θ/2), u)` summed in 64 bits and rounded to
///   2^−F: the residual (units 2^−(2F+1)) is added to the next update's sum. (The residual is
///   carried unrotated: the error of that, `|u|·2^−(F+1)` per update, is the rounding error times
///   the per-update angle.)
///
/// The renormalisation is folded into the update instead of rounding the attitude a second time:
/// the increment `(cos(θ/2), u)` is scaled by `1 + (1 − |q|²)/2` ([`Normalization::Fast`]: one
/// Newton step, from the attitude before the update) or by `1/|q|` ([`Normalization::Exact`]),
/// so every update rounds the attitude once, with its residual carried.
///
/// What remains: the series of the exponential (rounded to 2⁻³⁰, a relative 2⁻³⁰ of the
/// per-update angle), the lever's coefficient and the 2 low bits of each `q·u` product at
/// 2^−(2F+3) (≤ 3·2⁻⁶³ per update): no measurable drift over 10⁸ updates.
///
/// State: 14 words (the attitude and 10 residuals). Give it to
/// [`crate::propagation::IncrementIntegrator::new`] in place of a [`UnitQuat`] to run that
/// integrator carried (what `propagate --fixed` does), or call
/// [`CarriedAttitude::coning2_update`] from the firmware's gyro interrupt.
///
/// ```
/// use gyrostat::propagation::CarriedAttitude;
/// use gyrostat::real::Q30;
/// use gyrostat::UnitQuat;
/// use gyrostat::Vec3;
/// let mut q = CarriedAttitude::new(UnitQuat::<Q30>::IDENTITY);
/// let t = Vec3::<Q30>::try_from_f64(Vec3::new(3e-4, -2e-4, 5e-4))?; // 1 ms of a steady rate
/// for _ in 0..50_000 {
///     q = q.coning2_update(t, t);
/// }
/// // 100 s: the exact answer is exp(10⁵·t) of the received increments.
/// let exact = UnitQuat::try_exp(t.to_f64().scale(1e5))?;
/// let err = (exact.inverse() * q.attitude().to_f64()).angle();
/// assert!(err < 5e-8, "{err:e}");
/// # Ok::<(), gyrostat::Error>(())
/// ```
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CarriedAttitude<const F: u32> {
    q: UnitQuat<Fixed<F>>,
    /// Residual of the attitude's rounding, units 2^−(2F+1).
    q_lo: [i32; 4],
    /// Residual of the coning term's rounding, units 2^−2F.
    coning_lo: [i32; 3],
    /// Residual of the rotation increment's rounding, units 2^−(2F+3).
    u_lo: [i32; 3],
}

impl<const F: u32> Default for CarriedAttitude<F> {
    /// The identity rotation.
    fn default() -> Self {
        Self::new(UnitQuat::IDENTITY)
    }
}

impl<const F: u32> From<UnitQuat<Fixed<F>>> for CarriedAttitude<F> {
    /// [`CarriedAttitude::new`].
    fn from(q: UnitQuat<Fixed<F>>) -> Self {
        Self::new(q)
    }
}

impl<const F: u32> CarriedAttitude<F> {
    /// Starts at `q`, every residual zero.
    #[inline]
    pub const fn new(q: UnitQuat<Fixed<F>>) -> Self {
        Self {
            q,
            q_lo: [0; 4],
            coning_lo: [0; 3],
            u_lo: [0; 3],
        }
    }

    /// The attitude in the format (the residuals are below its resolution).
    #[inline]
    pub const fn attitude(&self) -> UnitQuat<Fixed<F>> {
        self.q
    }

    /// `q ← q ⊗ exp(φ)` with the normalisation policy folded in (see the type docs): the update
    /// of every attitude type under one name (as [`UnitQuat::mul_exp_unchecked`]). `φ` is any
    /// [`RotationVectorForm`]: a plain vector, a coning rule's [`ConingTerms`] (the cross product
    /// formed exactly, its residual carried) or a pair `(φ, φ_lo)` (added first).
    /// Unchecked: the domain of [`UnitQuat::mul_exp_unchecked`];
    /// [`CarriedAttitude::try_mul_exp`] is the checked form. Beyond the fused exponential's
    /// domain (a component of `φ` ≥ ¼ rad or `|φ| > 1/8` rad, no gyro update at ≥ 300 Hz) the
    /// plain update runs and the residuals restart at zero.
    #[inline]
    pub fn mul_exp_unchecked<P: RotationVectorForm<Fixed<F>>>(
        self,
        phi: P,
        norm: Normalization,
    ) -> Self {
        match phi.form() {
            Form::Vector(v) => self.mul_exp_vector(v, norm),
            Form::Coning(c) => self.mul_exp_coning(c, norm),
            Form::Pair(hi, lo) => self.mul_exp_vector(hi + lo, norm),
        }
    }

    /// [`CarriedAttitude::mul_exp_unchecked`], checked.
    ///
    /// # Errors
    /// As [`UnitQuat::try_mul_exp`]: [`Error::StepTooLong`] when `φ` turns by more than
    /// [`MAX_STEP_ANGLE`](crate::step_limit::MAX_STEP_ANGLE) (fixed point is always finite).
    #[inline]
    pub fn try_mul_exp<P: RotationVectorForm<Fixed<F>>>(
        self,
        phi: P,
        norm: Normalization,
    ) -> Result<Self, Error> {
        check_rotation_vector(phi)?;
        Ok(self.mul_exp_unchecked(phi, norm))
    }

    /// The normalisation policy alone (folded into an update by a zero rotation vector).
    #[inline]
    pub fn normalized(self, norm: Normalization) -> Self {
        self.mul_exp_vector(Vec3::ZERO, norm)
    }

    /// The update by a plain vector.
    #[inline]
    fn mul_exp_vector(self, phi: Vec3<Fixed<F>>, norm: Normalization) -> Self {
        let f = [phi.x.0, phi.y.0, phi.z.0].map(|s| i64::from(s) << FINE);
        match self.update_fine(f, self.coning_lo, norm) {
            Some(r) => r,
            None => Self::new(self.q.mul_exp_unchecked(phi, norm)),
        }
    }

    /// The update of a coning rule, `q ← q ⊗ exp(sum + lever × last)`, with the coning term's
    /// residual carried.
    #[inline]
    fn mul_exp_coning(self, terms: ConingTerms<Fixed<F>>, norm: Normalization) -> Self {
        let (l, b, s) = (terms.lever, terms.last, terms.sum);
        // Exact, units 2^−2F (each difference of two products < 2⁶³), plus the carried residual
        // (|·| ≤ 2^(F−FINE−1)).
        let cross = [
            mul_wide(l.y.0, b.z.0) - mul_wide(l.z.0, b.y.0),
            mul_wide(l.z.0, b.x.0) - mul_wide(l.x.0, b.z.0),
            mul_wide(l.x.0, b.y.0) - mul_wide(l.y.0, b.x.0),
        ];
        let sum = [s.x.0, s.y.0, s.z.0];
        let mut f = [0i64; 3];
        let mut lo = [0i32; 3];
        for i in 0..3 {
            let c = cross[i].saturating_add(i64::from(self.coning_lo[i]));
            let r = round_shift(c, F - FINE);
            lo[i] = (c - (r << (F - FINE))) as i32;
            f[i] = (i64::from(sum[i]) << FINE) + r;
        }
        match self.update_fine(f, lo, norm) {
            Some(r) => r,
            None => Self::new(self.q.mul_exp_unchecked(terms, norm)),
        }
    }

    /// The complete 2-sample update, `q ⊗ exp(θ₁ + θ₂ + ⅔ θ₁ × θ₂)` with the fast
    /// renormalisation, carried: the counterpart of
    /// [`crate::propagation::kernels::coning2_update`], integer arithmetic only. Unchecked, as
    /// there (finite increments of at most
    /// [`MAX_STEP_ANGLE`](crate::step_limit::MAX_STEP_ANGLE) each).
    #[inline]
    pub fn coning2_update(self, t1: Vec3<Fixed<F>>, t2: Vec3<Fixed<F>>) -> Self {
        self.mul_exp_coning(two_sample_terms(t1, t2), Normalization::Fast)
    }

    /// The carried update from the fine rotation vector `f` (units 2^−(F+3)) and the coning
    /// residual to keep; `None` beyond the fused domain (a component ≥ ¼ rad, or `|φ|² > 1/64`).
    #[inline]
    fn update_fine(self, f: [i64; 3], coning_lo: [i32; 3], norm: Normalization) -> Option<Self> {
        let limit = 1i64 << (F + FINE - 2); // ¼ rad at the fine scale
        if f.iter().any(|x| x.abs() >= limit) {
            return None;
        }
        let f = f.map(|x| x as i32);
        // θ² in units 2^−(2F+2·FINE−2) (each square < 2⁶², shifted by 2); 1/64 is 2^(2F−2) there.
        let t2_wide: i64 = f.iter().map(|&x| mul_wide(x, x) >> 2).sum();
        if t2_wide > 1i64 << (2 * F + 2 * FINE - 2 - 6) {
            return None;
        }
        let t2 = Fixed::<F>(saturate(round_shift(t2_wide, F + 2 * FINE - 2)));
        let (mut c, s) = half_angle_series(t2);
        // u = s·φ at the fine scale, its residual carried (units 2^−(2F+FINE), |·| ≤ 2^(F−1)).
        let mut u = [0i32; 3];
        let mut u_lo = [0i32; 3];
        for i in 0..3 {
            let w = mul_wide(s.0, f[i]) + i64::from(self.u_lo[i]);
            let r = round_shift(w, F);
            u_lo[i] = (w - (r << F)) as i32;
            u[i] = saturate(r);
        }
        // The renormalisation, folded into the increment: (c, u)·(1 + e).
        let q = self.q.into_quat();
        let e = match norm {
            Normalization::Fast => (Fixed::<F>::ONE - q.norm_squared()) * Fixed::<F>::HALF,
            Normalization::Exact => {
                Fixed::<F>::inv_sqrt_near_one(q.norm_squared()) - Fixed::<F>::ONE
            }
            Normalization::None => Fixed::<F>::ZERO,
        };
        if e != Fixed::<F>::ZERO {
            c += c * e;
            for x in u.iter_mut() {
                *x = saturate(i64::from(*x) + round_shift(mul_wide(*x, e.0), F));
            }
        }
        // Each component of q ⊗ (c, u) in units 2^−(2F+1) (as the plain fused update), plus the
        // carried residual; rounded once, the new residual kept.
        let (qw, qx, qy, qz) = (q.w.0, q.x.0, q.y.0, q.z.0);
        let [ux, uy, uz] = u;
        let cc = |a: i32| mul_wide(a, c.0) << 1;
        let uu = |a: i32, b: i32| mul_wide(a, b) >> 2;
        let wide = [
            cc(qw) - uu(qx, ux) - uu(qy, uy) - uu(qz, uz),
            cc(qx) + uu(qw, ux) + uu(qy, uz) - uu(qz, uy),
            cc(qy) + uu(qw, uy) - uu(qx, uz) + uu(qz, ux),
            cc(qz) + uu(qw, uz) + uu(qx, uy) - uu(qy, ux),
        ];
        let mut out = [0i32; 4];
        let mut q_lo = [0i32; 4];
        for i in 0..4 {
            let w = wide[i] + i64::from(self.q_lo[i]);
            let r = round_shift(w, F + 1);
            q_lo[i] = (w - (r << (F + 1))) as i32;
            out[i] = saturate(r);
        }
        Some(Self {
            q: UnitQuat::new_unchecked(crate::Quat::new(
                Fixed(out[0]),
                Fixed(out[1]),
                Fixed(out[2]),
                Fixed(out[3]),
            )),
            q_lo,
            coning_lo,
            u_lo,
        })
    }
}

impl<const F: u32> PropagatedAttitude<Fixed<F>> for CarriedAttitude<F> {}

impl<const F: u32> Propagate<Fixed<F>> for CarriedAttitude<F> {
    #[inline(always)]
    fn attitude(&self) -> UnitQuat<Fixed<F>> {
        self.q
    }
    #[inline(always)]
    fn from_unit(q: UnitQuat<Fixed<F>>) -> Self {
        CarriedAttitude::new(q)
    }
    #[inline(always)]
    fn mul_exp_vector(self, phi: Vec3<Fixed<F>>, norm: Normalization) -> Self {
        CarriedAttitude::mul_exp_vector(self, phi, norm)
    }
    #[inline(always)]
    fn increments(
        self,
        rule: ConingRule,
        previous: Vec3<Fixed<F>>,
        samples: &[Vec3<Fixed<F>>],
        norm: Normalization,
    ) -> Self {
        match (rule, samples) {
            (ConingRule::Exp, s) => {
                let phi = match s {
                    [a] => *a,
                    s => s.iter().fold(Vec3::ZERO, |acc, t| acc + *t),
                };
                self.mul_exp_vector(phi, norm)
            }
            (_, s) => self.mul_exp_coning(coning_terms_for(previous, s), norm),
        }
    }
    /// Never called: fixed point has no rate methods (`Fixed` is not [`Real`]).
    #[inline(always)]
    fn rates<const M: usize>(
        self,
        _method: RateMethod,
        _window: &[Vec3<Fixed<F>>; M],
        _weights: &Weights<M>,
        _h: Fixed<F>,
        _h_lo: Fixed<F>,
        _norm: Normalization,
    ) -> Self
    where
        Fixed<F>: Real,
    {
        self
    }
}
