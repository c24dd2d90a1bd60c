//! The unchecked attitude updates: the hot-path kernels behind the checked integrators.
//!
//! Every function here skips validation: it trusts its input to be finite and within the
//! step's validity limit ([`crate::step_limit::MAX_STEP_ANGLE`] for the approximate methods),
//! which the checked entry points ([`crate::propagation::IncrementIntegrator::push`],
//! [`crate::propagation::ConingAccumulator::push`], [`crate::propagation::RateIntegrator::push`],
//! [`crate::propagation::exponential::step_constant_rate`]) test once per sample. Outside it a
//! non-finite input gives a non-finite attitude, never a panic. Call them from an inner loop
//! whose input was validated where it was read.
//!
//! - [`UnitQuat::mul_exp_unchecked`] (defined here): the one update kernel every exponential-map
//!   rule goes through, `q ← normalise(q ⊗ exp(φ))`;
//! - [`coning2_update`]: the complete 2-sample coning update (fixed point: [`crate::fixed`]);
//! - [`magnus4_step`], [`cf4_step`], [`rk4_step`]: one step of the rate-sample methods from the
//!   rates at their nodes ([`crate::propagation::rate_samples`]);
//! - [`step_constant_rate`]: the exact step of a rate held constant.

use crate::propagation::coning::{
    ConingRule, ConingTerms, coning_terms_for, two_sample_terms, two_sample_unequal_terms,
};
use crate::propagation::kinematics::quat_rate_body;
use crate::propagation::normalization::Normalization;
use crate::propagation::rate_samples::{
    END, G1, G2, MID, RateMethod, START, Weights, cf4_rotation_vectors, interp,
    magnus4_rotation_vector,
};
use crate::rotation::ExpMap;
use crate::step_limit::within_step_limit;
use crate::{Error, Quat, Real, Ring, UnitQuat, Vec3};

/// The forms of a body-frame rotation vector `φ` that the attitude update `q ⊗ exp(φ)` takes,
/// on every attitude type under one name ([`UnitQuat::mul_exp_unchecked`],
/// [`crate::propagation::CompensatedAttitude::mul_exp_unchecked`],
/// [`crate::propagation::CarriedAttitude::mul_exp_unchecked`], and their checked `try_mul_exp`):
/// - a plain [`Vec3`];
/// - a coning rule's [`ConingTerms`], `φ = sum + lever × last` (fixed point forms the cross
///   product exactly and adds it at a finer resolution than the format; the compensated attitude
///   adds it to the low part);
/// - a compensated pair `(φ, φ_lo)`, `φ = φ + φ_lo` with `φ_lo` below an ulp of `φ` or a small
///   correction (the compensated attitude keeps it apart; the others add it first).
///
/// Sealed.
pub trait RotationVectorForm<T: Ring>: Copy + sealed::Sealed<T> {}

pub(crate) mod sealed {
    use crate::propagation::coning::ConingTerms;
    use crate::rotation::ExpMap;
    use crate::{UnitQuat, Vec3};

    /// A rotation vector's form, taken apart by each attitude type's update.
    pub enum Form<T> {
        /// A plain vector.
        Vector(Vec3<T>),
        /// `sum + lever × last`.
        Coning(ConingTerms<T>),
        /// `hi + lo`.
        Pair(Vec3<T>, Vec3<T>),
    }

    pub trait Sealed<T> {
        /// The form.
        fn form(self) -> Form<T>;
        /// `q ⊗ exp(φ)`, not renormalised: the plain update of each form, through the rotation
        /// layer's non-generic `UnitQuat::mul_exp_plain` / `mul_exp_coning_plain` (the call
        /// chain the kernels had before the rename: taking the form apart with [`Sealed::form`]
        /// instead cost the f32 coning updates 37 to 62 instructions and the estimator's update
        /// 35 on a Cortex-M4F, measured with `fw_icount` and `fw_icount_estimation`).
        fn mul_exp_onto(self, q: UnitQuat<T>) -> UnitQuat<T>
        where
            T: ExpMap;
    }

    impl<T> Sealed<T> for Vec3<T> {
        #[inline(always)]
        fn form(self) -> Form<T> {
            Form::Vector(self)
        }
        #[inline(always)]
        fn mul_exp_onto(self, q: UnitQuat<T>) -> UnitQuat<T>
        where
            T: ExpMap,
        {
            q.mul_exp_plain(self)
        }
    }

    impl<T> Sealed<T> for ConingTerms<T> {
        #[inline(always)]
        fn form(self) -> Form<T> {
            Form::Coning(self)
        }
        #[inline(always)]
        fn mul_exp_onto(self, q: UnitQuat<T>) -> UnitQuat<T>
        where
            T: ExpMap,
        {
            q.mul_exp_coning_plain(self.sum, self.lever, self.last)
        }
    }

    impl<T> Sealed<T> for (Vec3<T>, Vec3<T>) {
        #[inline(always)]
        fn form(self) -> Form<T> {
            Form::Pair(self.0, self.1)
        }
        #[inline(always)]
        fn mul_exp_onto(self, q: UnitQuat<T>) -> UnitQuat<T>
        where
            T: ExpMap,
        {
            q.mul_exp_plain(self.0 + self.1)
        }
    }
}

use sealed::Form;

impl<T: Ring> RotationVectorForm<T> for Vec3<T> {}
impl<T: Ring> RotationVectorForm<T> for ConingTerms<T> {}
impl<T: Ring> RotationVectorForm<T> for (Vec3<T>, Vec3<T>) {}

/// The rotation vector a form stands for, as one vector (`sum + lever × last`, `hi + lo`).
#[inline(always)]
pub(crate) fn form_vector<T: Ring, P: RotationVectorForm<T>>(phi: P) -> Vec3<T> {
    match phi.form() {
        Form::Vector(v) => v,
        Form::Coning(c) => c.sum + c.lever.cross(c.last),
        Form::Pair(hi, lo) => hi + lo,
    }
}

/// The check of the attitude updates' `try_mul_exp`: the rotation vector finite
/// ([`Error::NonFinite`]) and turning by at most
/// [`MAX_STEP_ANGLE`](crate::step_limit::MAX_STEP_ANGLE) ([`Error::StepTooLong`], the domain of
/// every approximate step, [`within_step_limit`]).
#[inline]
pub(crate) fn check_rotation_vector<T: Ring, P: RotationVectorForm<T>>(
    phi: P,
) -> Result<(), Error> {
    let v = form_vector(phi);
    if !v.is_finite() {
        Err(Error::NonFinite)
    } else if !within_step_limit(v) {
        Err(Error::StepTooLong)
    } else {
        Ok(())
    }
}

impl<T: ExpMap> UnitQuat<T> {
    /// `q ⊗ exp(φ)` followed by the normalisation policy: the attitude update by a body-frame
    /// rotation vector `φ` accumulated over one update interval (an increment, a coning rule's
    /// terms, Magnus-4's or CF4's vector), the one kernel every exponential-map rule goes
    /// through. The same name on the compensated and the carried attitudes
    /// ([`crate::propagation::CompensatedAttitude::mul_exp_unchecked`],
    /// [`crate::propagation::CarriedAttitude::mul_exp_unchecked`]); [`UnitQuat::try_mul_exp`]
    /// is the checked form.
    ///
    /// Unchecked: a non-finite `φ` (or one whose norm overflows) gives a non-finite attitude;
    /// the approximate rules are valid within
    /// [`MAX_STEP_ANGLE`](crate::step_limit::MAX_STEP_ANGLE). `φ` is any
    /// [`RotationVectorForm`]. For the floats every form is `q * UnitQuat::exp_unchecked(φ)`
    /// (series below the type's small-angle threshold). Fixed point fuses the product with the
    /// exponential ([`ExpMap::mul_exp`]: one rounding per component, the rotation increment
    /// carried 3 bits finer than the format) and, for [`ConingTerms`], also forms the cross
    /// product exactly and adds it at that finer resolution ([`ExpMap::mul_exp_coning`]).
    #[inline(always)]
    pub fn mul_exp_unchecked<P: RotationVectorForm<T>>(self, phi: P, norm: Normalization) -> Self {
        norm.apply(phi.mul_exp_onto(self))
    }

    /// [`UnitQuat::mul_exp_unchecked`], checked.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite `φ`; [`Error::StepTooLong`] when `φ` turns by more
    /// than [`MAX_STEP_ANGLE`](crate::step_limit::MAX_STEP_ANGLE) (the checks of
    /// [`crate::propagation::IncrementIntegrator::push`]).
    #[inline]
    pub fn try_mul_exp<P: RotationVectorForm<T>>(
        self,
        phi: P,
        norm: Normalization,
    ) -> Result<Self, Error> {
        check_rotation_vector(phi)?;
        Ok(self.mul_exp_unchecked(phi, norm))
    }
}

/// The complete 2-sample update on the hot path: `q ⊗ exp(θ₁ + θ₂ + ⅔ θ₁ × θ₂)`, then the fast
/// renormalisation `q + q·(1 − |q|²)/2`. Generic over [`ExpMap`]: with `T = Q30` it is the
/// fixed-point update, integer arithmetic only (see [`crate::fixed`]).
///
/// Unchecked (a non-finite increment gives a non-finite attitude): for an inner loop whose
/// increments were validated when they were read. Domain: finite increments of at most
/// [`MAX_STEP_ANGLE`](crate::step_limit::MAX_STEP_ANGLE) rad each (the checks of
/// [`crate::propagation::IncrementIntegrator::push`]). The exponential of the small per-update angle uses the series
/// of [`UnitQuat::try_exp`] (no trigonometric call below 0.37 rad in f32, 1/8 rad in Q1.30); the
/// rule's [`ConingTerms`] go through the update kernel [`UnitQuat::mul_exp_unchecked`] (in fixed point:
/// [`ExpMap::mul_exp_coning`]).
#[inline]
pub fn coning2_update<T: ExpMap>(q: UnitQuat<T>, t1: Vec3<T>, t2: Vec3<T>) -> UnitQuat<T> {
    q.mul_exp_unchecked(two_sample_terms(t1, t2), Normalization::Fast)
}

/// The 2-sample update over unequal sub-intervals: `q ⊗ exp(θ₁ + θ₂ + c θ₁ × θ₂)` with the
/// coefficient `c = (h₁ + h₂)²/(6 h₁ h₂)` ([`crate::propagation::coning::two_sample_unequal_terms`],
/// where the rule is derived), then the fast renormalisation. Equal to [`coning2_update`] for
/// `c = ⅔`. Fixed point: pass the coefficient in Q1.30 (precomputed per interval pattern).
///
/// Unchecked: the domain of [`coning2_update`].
#[inline]
pub fn coning2_update_unequal<T: ExpMap>(
    q: UnitQuat<T>,
    t1: Vec3<T>,
    t2: Vec3<T>,
    coefficient: T,
) -> UnitQuat<T> {
    q.mul_exp_unchecked(
        two_sample_unequal_terms(t1, t2, coefficient),
        Normalization::Fast,
    )
}

/// The Lagrange interpolant through `(tᵢ, ωᵢ)` evaluated at `x`: `Σ ωᵢ Πⱼ≠ᵢ (x − tⱼ)/(tᵢ − tⱼ)`.
/// Unchecked: the times must be distinct.
#[inline]
fn lagrange_at<T: Real, const M: usize>(t: &[T; M], w: &[Vec3<T>; M], x: T) -> Vec3<T> {
    let mut acc = Vec3::ZERO;
    for (i, (ti, wi)) in t.iter().zip(w).enumerate() {
        let mut l = T::ONE;
        for (j, tj) in t.iter().enumerate() {
            if i != j {
                l *= (x - *tj) / (*ti - *tj);
            }
        }
        acc += *wi * l;
    }
    acc
}

/// One Magnus-4 step on rate samples at unequal times: advances from `t0` to `t1` with the
/// rates at the step's Gauss nodes taken from the Lagrange interpolant through the `M` samples
/// `(times[i], rates[i])` (the [`crate::propagation::rate_samples`] scheme with the weights formed
/// from the actual times). Not renormalised.
///
/// Use it like the equal-interval integrator: over `[tₖ₋₁, tₖ]` with the window of samples
/// `k−3 … k` (no look-ahead), and, at the start, the first three intervals with samples `0 … 3`.
/// Order: the cubic interpolant's error is `O(h⁴)` in `ω` (for a jitter that keeps the window's
/// intervals comparable), so the local error is `O(h⁵)` and the method converges with order 4 on
/// a jittered clock as on a regular one (a window of three samples: order 3, of two: order 2;
/// measured in `host-tests/tests/sensor/`).
///
/// Unchecked: the times must be distinct (repeated times give NaN; see
/// [`crate::sensor::SampleClock`] for the checks), `[t0, t1]` inside the window's span
/// (outside, the interpolant extrapolates, less accurately), and the domain of [`magnus4_step`]
/// holds. `M = 0` gives a zero rate.
#[inline]
pub fn magnus4_step_unequal<T: Real, const M: usize>(
    q: UnitQuat<T>,
    times: &[T; M],
    rates: &[Vec3<T>; M],
    t0: T,
    t1: T,
) -> UnitQuat<T> {
    let (w1, w2, h) = gauss_node_rates(times, rates, t0, t1);
    magnus4_step(q, w1, w2, h)
}

/// The rates at the two Gauss nodes of `[t0, t1]` from the Lagrange interpolant through the `M`
/// samples, and the step `h = t1 − t0`: the inputs of the fourth-order steps on unequal times
/// (these steps and the estimator's 4th-order rate rules,
/// [`crate::estimation::RateRule`]). The basis `lᵢ(x) = Πⱼ≠ᵢ (x − tⱼ) / Πⱼ≠ᵢ (tᵢ − tⱼ)` shares
/// its denominators between the two nodes: `M` divisions per step (a soft-float division is
/// some hundred instructions on a Cortex-M0); the newest sample's basis function is not needed
/// (difference form, `M − 1` divisions). Unchecked: the times distinct.
#[inline]
pub(crate) fn gauss_node_rates<T: Real, const M: usize>(
    times: &[T; M],
    rates: &[Vec3<T>; M],
    t0: T,
    t1: T,
) -> (Vec3<T>, Vec3<T>, T) {
    let h = t1 - t0;
    let g1 = t0 + h * T::from_f64(crate::propagation::rate_samples::GAUSS_NODE_1);
    let g2 = t0 + h * T::from_f64(crate::propagation::rate_samples::GAUSS_NODE_2);
    // Difference form, `ω_last + Σ lᵢ(x)(ωᵢ − ω_last)` (the basis adds up to one): a constant
    // rate comes out exactly and a slowly varying one with the rounding of its small
    // differences only (as `rate_samples::interp_difference`).
    let last = rates.last().copied().unwrap_or(Vec3::ZERO);
    let (mut w1, mut w2) = (last, last);
    for (i, (ti, wi)) in times
        .iter()
        .zip(rates)
        .enumerate()
        .take(M.saturating_sub(1))
    {
        let (mut den, mut n1, mut n2) = (T::ONE, T::ONE, T::ONE);
        for (j, tj) in times.iter().enumerate() {
            if i != j {
                den *= *ti - *tj;
                n1 *= g1 - *tj;
                n2 *= g2 - *tj;
            }
        }
        let r = T::ONE / den;
        let d = *wi - last;
        w1 += d * (n1 * r);
        w2 += d * (n2 * r);
    }
    (w1, w2, h)
}

/// One commutator-free CF4 step on rate samples at unequal times: [`cf4_step`] from `t0` to
/// `t1` with the rates at the step's Gauss nodes taken from the Lagrange interpolant through the
/// `M` samples, as [`magnus4_step_unequal`] (the same window, order and domain). Not
/// renormalised.
#[inline]
pub fn cf4_step_unequal<T: Real, const M: usize>(
    q: UnitQuat<T>,
    times: &[T; M],
    rates: &[Vec3<T>; M],
    t0: T,
    t1: T,
) -> UnitQuat<T> {
    let (w1, w2, h) = gauss_node_rates(times, rates, t0, t1);
    cf4_step(q, w1, w2, h)
}

/// One classical RK4 step on rate samples at unequal times: [`rk4_step`] from `t0` to `t1` with
/// the rates at the step's start, midpoint and end taken from the Lagrange interpolant through
/// the `M` samples (the start and end are samples of the window when `t0` and `t1` are two of
/// its times, as in use), as [`magnus4_step_unequal`] (the same window, order and domain).
/// Returns the raw quaternion, as [`rk4_step`]: apply a [`Normalization`] to it.
#[inline]
pub fn rk4_step_unequal<T: Real, const M: usize>(
    q: Quat<T>,
    times: &[T; M],
    rates: &[Vec3<T>; M],
    t0: T,
    t1: T,
) -> Quat<T> {
    let h = t1 - t0;
    rk4_step(
        q,
        lagrange_at(times, rates, t0),
        lagrange_at(times, rates, t0 + h * T::HALF),
        lagrange_at(times, rates, t1),
        h,
    )
}

/// One Magnus-4 step: `q ⊗ exp(φ)` with φ from [`magnus4_rotation_vector`]. Unchecked, not
/// renormalised (a product of unit quaternions, unit to about one ulp). Domain (of this and the
/// other step functions of this module): finite rates with `|ω|·h` at most a few times
/// [`MAX_STEP_ANGLE`](crate::step_limit::MAX_STEP_ANGLE) (the series stop converging at `2π`).
#[inline]
pub fn magnus4_step<T: Real>(q: UnitQuat<T>, w1: Vec3<T>, w2: Vec3<T>, h: T) -> UnitQuat<T> {
    q.mul_exp_unchecked(magnus4_rotation_vector(w1, w2, h), Normalization::None)
}

/// One commutator-free CF4 step: `q ⊗ exp(φ_first) ⊗ exp(φ_second)` (see
/// [`cf4_rotation_vectors`]). Unchecked, not renormalised.
#[inline]
pub fn cf4_step<T: Real>(q: UnitQuat<T>, w1: Vec3<T>, w2: Vec3<T>, h: T) -> UnitQuat<T> {
    cf4_update(q, w1, w2, h, Normalization::None)
}

/// [`cf4_step`] followed by the normalisation policy: two applications of the update kernel
/// [`UnitQuat::mul_exp_unchecked`], the policy applied once, after the second.
#[inline]
fn cf4_update<T: Real>(
    q: UnitQuat<T>,
    w1: Vec3<T>,
    w2: Vec3<T>,
    h: T,
    norm: Normalization,
) -> UnitQuat<T> {
    let (p1, p2) = cf4_rotation_vectors(w1, w2, h);
    q.mul_exp_unchecked(p1, Normalization::None)
        .mul_exp_unchecked(p2, norm)
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
    // The slopes of the step's angles `hω` over a unit step: the same polynomial as
    // `(h/6)·Σ kᵢ(ω)`, but `h` multiplies the rates first, so that a short step of a fast rate
    // (`|ω|` near the type's maximum) does not overflow in the slopes, and `h = 0` returns `q`.
    let sum = rk4_slope_sum(q, w_start.scale(h), w_mid.scale(h), w_end.scale(h), T::ONE);
    q + sum.scale(T::ONE / T::from_f64(6.0))
}

/// The weighted slopes of one RK4 step, `k₁ + 2k₂ + 2k₃ + k₄` (the step adds `h/6` times them:
/// [`rk4_step`]; the compensated step with `h/6` as an exact pair).
#[inline(always)]
pub(crate) fn rk4_slope_sum<T: Real>(
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
    k1 + (k2 + k3).scale(T::TWO) + k4
}

/// [`crate::propagation::exponential::step_constant_rate`] without the checks, for an inner loop
/// with validated input: the
/// update kernel [`UnitQuat::mul_exp_unchecked`] with `φ = ω Δt`, not renormalised. Domain: finite
/// `ω`, `Δt` with `|ω·Δt|` representable (a NaN or overflowing angle gives a NaN attitude).
#[inline]
pub fn step_constant_rate<T: Real>(q: UnitQuat<T>, omega_body: Vec3<T>, dt: T) -> UnitQuat<T> {
    q.mul_exp_unchecked(omega_body.scale(dt), Normalization::None)
}

/// The plain update of [`crate::propagation::IncrementIntegrator`]: `normalise(q ⊗ exp(φ))` through the update
/// kernel [`UnitQuat::mul_exp_unchecked`], with `φ` the sum of `samples` (a plain vector) for
/// [`ConingRule::Exp`], else the [`ConingTerms`] of the rule that fits their number
/// ([`coning_terms_for`]).
#[inline]
pub(crate) fn apply_rule<T: ExpMap>(
    q: UnitQuat<T>,
    rule: ConingRule,
    previous: Vec3<T>,
    samples: &[Vec3<T>],
    norm: Normalization,
) -> UnitQuat<T> {
    match (rule, samples) {
        (ConingRule::Exp, s) => {
            let phi = match s {
                [a] => *a,
                s => s.iter().fold(Vec3::ZERO, |acc, t| acc + *t),
            };
            q.mul_exp_unchecked(phi, norm)
        }
        (_, s) => q.mul_exp_unchecked(coning_terms_for(previous, s), norm),
    }
}

/// The plain step of [`crate::propagation::RateIntegrator`] over one interval of an `M`-sample window.
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
            q.mul_exp_unchecked(phi, norm)
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
            norm.apply_quat_unchecked(q)
        }
    }
}
