//! Compensated attitude accumulation: [`CompensatedAttitude`], the attitude with its rounding
//! error carried, for the increment and rate integrators.
//!
//! # Why the plain f32 attitude drifts
//! An attitude update `q ← normalise(q ⊗ exp(φ))` rounds each component of `q` to f32, half an
//! ulp (3e-8) at every update. At 1 kHz that is 3.6·10⁶ roundings an hour, and they do not
//! average out: when the body turns steadily, `q` passes through nearly the same values every
//! turn, the rounding is a function of those values, and each turn adds about the same error.
//! The error then grows linearly with time instead of as a random walk. Measured through
//! `propagate --f32` (constant body rate (0.5, −0.8, 0.6) rad/s, increments rounded to f32 so
//! that the exact answer is known, one hour): 2.4e-2 rad with `exp`, 1.2e-2 with `coning2`,
//! 4.4e-3 with `coning3`, 1.3e-3 with `coning4` (BENCHMARKS.md). For steady motion every rule
//! forms the same rotation vector exactly (the cross products vanish), so the rule is not the
//! cause; only how many products are rounded, and at which points of the orbit.
//!
//! That is also why, at a low rate, `exp` and `coning2` can differ by an order of magnitude on
//! the same input: at (0.05, −0.08, 0.06) rad/s `exp` ends the hour 1.1e-4 rad off and `coning2`
//! 1.3e-3, while about z at 0.1 rad/s it is the other way round (1.4e-4 and 1.7e-6). Both form
//! the exact rotation vector of the steady motion; `exp` rounds the product every 1 ms, `coning2`
//! every 2 ms at other points of the orbit, and whose rounding errors happen to pile up depends
//! on the input. With the compensated attitude both end within 1.5e-8 rad at these two rates
//! and 6.3e-8 rad at the higher one above.
//!
//! # The compensated attitude
//! [`CompensatedAttitude`] keeps `q` as a pair `(q, q_lo)`: every update adds its increment
//! `d = (q + q_lo) ⊗ (cos(θ/2) − 1, sin(θ/2)/θ·φ)` through Fast2Sum and carries the rounding
//! error in `q_lo` instead of dropping it; the exponential's vector part is split as
//! `φ/2 + (sin(θ/2)/θ − ½)·φ`, so that its large part is exact, and the increment's large part
//! `q ⊗ (cos(θ/2) − 1, φ/2)` is itself added unrounded (its factors split in halves whose
//! products are exact, each product added with its rounding carried); the renormalisation is the
//! same increment form (it scales `q + q_lo` and moves only the norm). The rules form their
//! rotation vector as a compensated pair too (the sum of the increments by TwoSum, the coning
//! term added to the low part), and the rate methods interpolate in difference form (the
//! samples' differences, so that a constant rate is reproduced exactly), take the products with
//! the step exactly and take the step `dt` with its rounding remainder
//! ([`RateIntegrator::try_with_step_remainder`]). What is left is the rounding of terms some
//! 2¹¹ times below the increment (`u·2⁻¹¹·|φ|` per update) and of the final attitude to `T`.
//!
//! Why the increment's product matters: rounded (`fl(q ⊗ (m, φ/2))`, half an ulp of `|φ|/2` per
//! component), its error is a function of the attitude and the increment, so when the motion
//! repeats it repeats too. Measured on the classical coning motion (1° half-angle at 10 Hz, 1 kHz,
//! 60 s, the input repeating every 100 increments; the same f32-rounded increments in f32 and
//! f64), the 4-sample rule ended 5.6e-7 rad from the f64 run with the product rounded, 8.8e-11
//! with it carried (the attitude rounded to f32); the rule's rotation vector and the
//! renormalisation, each made exact in f64 in turn, changed nothing
//! (`host-tests/tests/propagation/compensated_ablation.rs`).
//!
//! Measured over one hour at 1 kHz (3.6·10⁶ updates; `host-tests/tests/propagation/compensated.rs`,
//! BENCHMARKS.md), in f32: steady rotation up to 1.1 rad/s, every increment rule ≤ 6.3e-8 rad
//! from the exact attitude (plain: 1.7e-6…2.4e-2), Magnus-4 and CF4 from rate samples ≤ 4.9e-8
//! (plain: 1.0e-4…6.8e-2), RK4 from rate samples ≤ 1.1e-5 (plain: up to 3.5e-4: its slope sum
//! is added rounded); coning motion at 0.89 rad/s, the f32 arithmetic's share (distance to the
//! same rule in f64) ≤ 2.4e-8 for every increment rule (plain: up to 1.1e-4), ≤ 5.9e-8 for
//! Magnus-4 and CF4 and 1.3e-6 for RK4 (plain: up to 3.2e-2). All but RK4 are below the f32
//! floor, 1.03e-7 rad: the turn of a unit quaternion by rounding its components to f32 once.
//!
//! # When to pay
//! The compensated update costs more instructions on a Cortex-M4F (BENCHMARKS.md) and twice the
//! attitude's memory. A navigation-grade gyro drifts 0.01°/h (1.7e-4 rad/h): below that, the
//! plain f32 attitude, not the sensor, limits the accuracy after a few minutes. Pay when an f32
//! attitude is propagated for long without an absolute reference (dead reckoning, an estimator
//! between rare fixes, a simulator); a filter that corrects the attitude every few seconds from
//! an accelerometer, magnetometer or star tracker does not need it. In f64 the plain path
//! drifts by the same mechanism at the f64 ulp (1e-11 rad/h), so there the compensation buys
//! nothing a user would notice; it is offered for symmetry.
//!
//! [`RateIntegrator::try_with_step_remainder`]: crate::propagation::RateIntegrator::try_with_step_remainder

use crate::error_free::{
    add_compensated, renormalize_compensated, renormalize_exact_factor, rotate_compensated,
    sixth_pair, two_sum,
};
use crate::propagation::coning::{ConingRule, coning_terms_for};
use crate::propagation::kernels::sealed::Form;
use crate::propagation::kernels::{RotationVectorForm, check_rotation_vector, rk4_slope_sum};
use crate::propagation::normalization::Normalization;
use crate::propagation::rate_samples::{
    END, G1, G2, MID, RateMethod, SQRT_3, START, Weights, interp_difference,
};
use crate::{Error, Quat, Real, UnitQuat, Vec3};

/// An attitude with its rounding error carried: `q + q_lo`, `q` the attitude rounded to `T`.
///
/// Give it to [`crate::propagation::IncrementIntegrator::new`] or
/// [`crate::propagation::RateIntegrator::try_new`] in place of a [`UnitQuat`] to run that
/// integrator compensated (see the module docs); or update it directly with
/// [`CompensatedAttitude::mul_exp_unchecked`] (for example with the rotation vector of a
/// [`crate::propagation::ConingAccumulator`]).
///
/// ```
/// use gyrostat::propagation::{CompensatedAttitude, ConingRule, IncrementIntegrator, Normalization};
/// use gyrostat::{Quat, UnitQuat, Vec3};
/// let q0 = CompensatedAttitude::new(UnitQuat::<f32>::IDENTITY);
/// let mut integ = IncrementIntegrator::new(q0, ConingRule::TwoSample, Normalization::Fast);
/// let d = Vec3::new(5e-4f32, -8e-4, 6e-4); // 1 ms of a steady rate, rad
/// for _ in 0..100_000 {
///     integ.push(d)?;
/// }
/// // 100 s: the exact answer is exp(10⁵·d), here in f64.
/// let exact = UnitQuat::try_exp(Vec3::from_array(d.to_array().map(|c| 1e5 * f64::from(c))))?;
/// let q = UnitQuat::new_unchecked(Quat::from_array(integ.attitude().to_array().map(f64::from)));
/// assert!((exact.inverse() * q).angle() < 1e-6);
/// # Ok::<(), gyrostat::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CompensatedAttitude<T> {
    q: UnitQuat<T>,
    lo: Quat<T>,
}

impl<T: Real> Default for CompensatedAttitude<T> {
    /// The identity rotation.
    fn default() -> Self {
        Self::new(UnitQuat::IDENTITY)
    }
}

impl<T: Real> From<UnitQuat<T>> for CompensatedAttitude<T> {
    /// [`CompensatedAttitude::new`].
    fn from(q: UnitQuat<T>) -> Self {
        Self::new(q)
    }
}

impl<T: Real> CompensatedAttitude<T> {
    /// Starts at `q` (low part zero).
    #[inline]
    pub const fn new(q: UnitQuat<T>) -> Self {
        Self { q, lo: Quat::ZERO }
    }

    /// The attitude, rounded to `T` (unit within a few ulp).
    #[inline]
    pub const fn attitude(&self) -> UnitQuat<T> {
        self.q
    }

    /// The low-order part: the attitude is the direction of `attitude() + low()`.
    #[inline]
    pub const fn low(&self) -> Quat<T> {
        self.lo
    }

    /// `q ⊗ exp(φ)` in compensated form, then the normalisation policy (see the module docs):
    /// the update of every attitude type under one name (as [`UnitQuat::mul_exp_unchecked`]).
    /// `φ` is taken as exact, in any [`RotationVectorForm`]: a plain vector, a coning rule's
    /// [`ConingTerms`](crate::propagation::ConingTerms) (the coning term `lever × last` added to
    /// the low part) or a compensated pair `(φ, φ_lo)` (`φ_lo` below an ulp of `φ`, or a small
    /// correction). Unchecked: the domain of [`UnitQuat::mul_exp_unchecked`];
    /// [`CompensatedAttitude::try_mul_exp`] is the checked form.
    #[inline]
    pub fn mul_exp_unchecked<P: RotationVectorForm<T>>(self, phi: P, norm: Normalization) -> Self {
        let (phi, phi_lo) = match phi.form() {
            Form::Vector(v) => (v, Vec3::ZERO),
            Form::Coning(c) => (c.sum, c.lever.cross(c.last)),
            Form::Pair(hi, lo) => (hi, lo),
        };
        self.mul_exp_pair(phi, phi_lo, norm)
    }

    /// The update by a pair (the integrators' path: not generic, so that its inlining is the
    /// compiler's choice per call site).
    #[inline]
    pub(crate) fn mul_exp_pair(
        mut self,
        phi: Vec3<T>,
        phi_lo: Vec3<T>,
        norm: Normalization,
    ) -> Self {
        let mut q = self.q.into_quat();
        rotate_compensated(&mut q, &mut self.lo, phi, phi_lo);
        self.q = UnitQuat::new_unchecked(q);
        self.normalized(norm)
    }

    /// [`CompensatedAttitude::mul_exp_unchecked`], checked.
    ///
    /// # Errors
    /// As [`UnitQuat::try_mul_exp`]: [`Error::NonFinite`], [`Error::StepTooLong`].
    #[inline]
    pub fn try_mul_exp<P: RotationVectorForm<T>>(
        self,
        phi: P,
        norm: Normalization,
    ) -> Result<Self, Error> {
        check_rotation_vector(phi)?;
        Ok(self.mul_exp_unchecked(phi, norm))
    }

    /// The complete 2-sample update, `q ⊗ exp(θ₁ + θ₂ + ⅔ θ₁ × θ₂)` with the fast
    /// renormalisation, compensated (the increments summed exactly, the coning term in the low
    /// part): the counterpart of [`crate::propagation::kernels::coning2_update`] and
    /// [`crate::propagation::CarriedAttitude::coning2_update`]. Unchecked, as there.
    #[inline]
    pub fn coning2_update(self, t1: Vec3<T>, t2: Vec3<T>) -> Self {
        let (phi, phi_lo) = rule_vector(ConingRule::TwoSample, Vec3::ZERO, &[t1, t2]);
        self.mul_exp_pair(phi, phi_lo, Normalization::Fast)
    }

    /// `q + (large + small)` in compensated form (an integrator's increment), then the
    /// normalisation policy.
    #[inline]
    pub(crate) fn incremented(
        mut self,
        large: Quat<T>,
        small: Quat<T>,
        norm: Normalization,
    ) -> Self {
        let mut q = self.q.into_quat();
        add_compensated(&mut q, &mut self.lo, large, small);
        self.q = UnitQuat::new_unchecked(q);
        self.normalized(norm)
    }

    /// The normalisation policy in compensated form: [`Normalization::Fast`] adds
    /// `q·(1 − |q|²)/2`, [`Normalization::Exact`] `q·(1/|q| − 1)`, both through the carried
    /// sum (they scale `q + q_lo` and move only its norm); [`Normalization::None`] nothing.
    #[inline]
    pub fn normalized(mut self, norm: Normalization) -> Self {
        let mut q = self.q.into_quat();
        match norm {
            Normalization::Fast => renormalize_compensated(&mut q, &mut self.lo),
            Normalization::Exact => {
                let d = q.scale(renormalize_exact_factor(q.norm_squared()));
                add_compensated(&mut q, &mut self.lo, d, Quat::ZERO);
            }
            Normalization::None => {}
        }
        self.q = UnitQuat::new_unchecked(q);
        self
    }
}

/// `a + b` as a compensated pair, component by component (TwoSum).
#[inline(always)]
fn two_sum_vec<T: Real>(a: Vec3<T>, b: Vec3<T>) -> (Vec3<T>, Vec3<T>) {
    let (x, ex) = two_sum(a.x, b.x);
    let (y, ey) = two_sum(a.y, b.y);
    let (z, ez) = two_sum(a.z, b.z);
    (Vec3::new(x, y, z), Vec3::new(ex, ey, ez))
}

/// `a·s` as a compensated pair, component by component (Dekker's product).
#[inline(always)]
fn two_product_vec<T: Real>(a: Vec3<T>, s: T) -> (Vec3<T>, Vec3<T>) {
    use crate::error_free::two_product;
    let (x, ex) = two_product(a.x, s);
    let (y, ey) = two_product(a.y, s);
    let (z, ez) = two_product(a.z, s);
    (Vec3::new(x, y, z), Vec3::new(ex, ey, ez))
}

/// The rotation vector of one update of `rule` as a compensated pair: the sum of the increments
/// exactly (TwoSum), the coning term `lever × last` of the rule that fits their number
/// ([`coning_terms_for`], the plain update's terms) added to the low part; [`ConingRule::Exp`]
/// has no coning term.
pub(crate) fn rule_vector<T: Real>(
    rule: ConingRule,
    previous: Vec3<T>,
    samples: &[Vec3<T>],
) -> (Vec3<T>, Vec3<T>) {
    let (mut sum, mut lo) = (Vec3::ZERO, Vec3::ZERO);
    for t in samples {
        let (s, e) = two_sum_vec(sum, *t);
        sum = s;
        lo += e;
    }
    let coning = match (rule, samples) {
        (ConingRule::Exp, _) | (_, []) => Vec3::ZERO,
        (_, s) => {
            let terms = coning_terms_for(previous, s);
            terms.lever.cross(terms.last)
        }
    };
    (sum, lo + coning)
}

/// One compensated step of a rate method: the node rates interpolated in difference form, the
/// large part of each rotation vector formed as an exact pair. Inlined, so that the f64
/// interpolation weights fold into f32 constants (a call would convert them at run time: about
/// 900 more instructions per step on a Cortex-M4F).
#[inline(always)]
pub(crate) fn advance_compensated<T: Real, const M: usize>(
    q: CompensatedAttitude<T>,
    method: RateMethod,
    s: &[Vec3<T>; M],
    w: &Weights<M>,
    h: T,
    h_lo: T,
    norm: Normalization,
) -> CompensatedAttitude<T> {
    match method {
        RateMethod::Magnus4 | RateMethod::Cf4 => {
            let (w1, w2) = (interp_difference(s, &w[G1]), interp_difference(s, &w[G2]));
            // The mean rate's sum (ω₁ + ω₂) as a pair, times h/2 (Magnus) or h/4 (CF4).
            let (m, m_lo) = two_sum_vec(w1, w2);
            let k = if method == RateMethod::Magnus4 {
                T::HALF
            } else {
                T::from_f64(0.25)
            };
            let (base, base_lo) = two_product_vec(m, h * k);
            let base_lo = base_lo + m_lo.scale(h * k) + m.scale(h_lo * k);
            if method == RateMethod::Magnus4 {
                // φ = (h/2)(ω₁ + ω₂) + (√3/12) h² ω₁ × ω₂.
                // Each rate scaled by the step before the product (w₁ × w₂ alone can overflow
                // for rates and steps whose angles are small).
                let commutator = w1
                    .scale(h)
                    .cross(w2.scale(h))
                    .scale(T::from_f64(SQRT_3 / 12.0));
                q.mul_exp_pair(base, base_lo + commutator, norm)
            } else {
                // φ₁,₂ = (h/4)(ω₁ + ω₂) ± (√3/6) h (ω₁ − ω₂): the CF4 weights ¼ ± √3/6.
                let diff = (w1 - w2).scale(h * T::from_f64(SQRT_3 / 6.0));
                q.mul_exp_pair(base, base_lo + diff, Normalization::None)
                    .mul_exp_pair(base, base_lo - diff, norm)
            }
        }
        RateMethod::Rk4 => {
            let (ws, wm, we) = (
                interp_difference(s, &w[START]),
                interp_difference(s, &w[MID]),
                interp_difference(s, &w[END]),
            );
            let sum = rk4_slope_sum(q.q.into_quat(), ws, wm, we, h);
            // h/6 as an exact pair, plus the step's remainder h_lo/6.
            let (h6, h6_lo) = sixth_pair(h);
            let small = sum.scale(h6_lo + h_lo / T::from_f64(6.0));
            q.incremented(sum.scale(h6), small, norm)
        }
    }
}
