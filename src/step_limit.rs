//! The validity limits of a step, shared by attitude propagation ([`crate::propagation`]) and
//! the dynamics ([`crate::dynamics`]): every approximate method may turn the body by at most
//! [`MAX_STEP_ANGLE`] per step, and an exact step by at most [`exact_step_angle_limit`].
//!
//! One module for both, below both: the coning rules, the rate-sample methods and the
//! rigid-body integrators are all truncated series in the step's rotation angle, and they fail
//! beyond the same angle for the same reason (see [`MAX_STEP_ANGLE`]).

use crate::{Real, Ring, Vec3};

/// The largest rotation one step of an approximate propagation or dynamics method may take:
/// `π` rad, half a turn. A longer step gives [`crate::Error::StepTooLong`].
///
/// Why π: every approximate update in gyrostat is a truncated series in the step's rotation
/// angle `θ` (`|ω|·Δt`, a gyro increment, or an accumulated update interval). The coning rules
/// and the two-speed accumulator truncate the Bortz rotation-vector equation and Magnus-4 and
/// CF4 the Magnus expansion, both of which converge only for `θ < 2π` (Moan & Niesen, *Found.
/// Comput. Math.* 8 (2008), for Magnus); classical RK4 is unstable on the rotation's
/// eigenvalues `±iθ/2` beyond `θ = 4√2 ≈ 5.66`; the Lie–Poisson splittings' error terms are
/// powers of the sub-step angles. At `π` each method is at half its radius of convergence or
/// closer to the origin; at `2π` none of them approximates anything. A step of more than half a
/// turn is also aliased for everything downstream: the attitudes at its ends are joined by the
/// shorter rotation the other way ([`crate::propagation::kinematics::body_rate_between`]).
///
/// The checked entry points test it ([`crate::propagation::IncrementIntegrator::push`] with a
/// coning rule, [`crate::propagation::ConingAccumulator::push`],
/// [`crate::propagation::RateIntegrator::push`], [`crate::dynamics::Gyrostat::step`]); the
/// kernels ([`crate::propagation::kernels`]) state it as their domain.
pub const MAX_STEP_ANGLE: f64 = core::f64::consts::PI;

/// `true` when a rotation vector `v` turns by at most [`MAX_STEP_ANGLE`]: `|v/4|² ≤ π²/16`.
///
/// The quarter keeps the square inside Q1.30's range (`|v/4|² < 0.75` for components below
/// 2 rad); for the floats it is exact, so the test is `|v|² ≤ π²` (the rational
/// 223764909/362754007 is π²/16 to 7e-19). An overflowing square fails, and so does a NaN: the
/// callers check their inputs for finiteness first, so a NaN here is a rate that could not be
/// represented.
#[inline]
pub(crate) fn within_step_limit<T: Ring>(v: Vec3<T>) -> bool {
    v.scale(T::ratio::<1, 4>()).norm_squared() <= T::ratio::<223_764_909, 362_754_007>()
}

/// [`within_step_limit`] for the floats, without the quarter (which only keeps the square inside
/// Q1.30's range): `|v|² ≤ π²` (`π²` rounded to `T` once), for a hot path that pays for every
/// multiplication (the estimator's step checks). An overflowing square fails, and so does a NaN.
#[inline]
pub(crate) fn within_step_limit_real<T: Real>(v: Vec3<T>) -> bool {
    v.norm_squared() <= T::from_f64(MAX_STEP_ANGLE * MAX_STEP_ANGLE)
}

/// The validity limit of the exact steps (the exponential of a rate held constant,
/// [`crate::propagation::exponential::step_constant_rate`], and the closed-form free rigid body,
/// [`crate::dynamics::FreeRigidBody::try_state_at`]): `|ω|·Δt ≤ 1/ε` (8.4e6 rad in f32, 4.5e15 in f64).
///
/// An exact step has no truncation error at any angle, but its angle is the product `ω·Δt`
/// rounded to the type, off by up to `ε/2` of itself: beyond `1/ε` that rounding alone is half a
/// radian or more, and the attitude after the step has no correct digit.
#[inline]
pub fn exact_step_angle_limit<T: Real>() -> T {
    T::ONE / T::EPSILON
}
