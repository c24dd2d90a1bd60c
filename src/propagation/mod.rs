//! Attitude propagation: integrating body rates or gyro increments into an attitude.
//!
//! Every function follows the crate conventions: `q` maps body vectors to the lab frame, the
//! body rate `ω` is in the body frame, and the attitude evolves by `q̇ = ½ q ⊗ (0, ω)`, so that a
//! rotation vector `φ` accumulated in the body frame over a step updates the attitude on the
//! right: `q ← q ⊗ exp(φ)` (the seed's whirl `R[Θ]`, (6.6.4), applied in the body frame).
//!
//! Which algorithm fits which sensor:
//!
//! | sensor delivers | module | algorithm | order / residual drift |
//! |---|---|---|---|
//! | a rate held constant over the step | [`exponential`] | exact step `q ⊗ exp(ω Δt)` | exact |
//! | integrated increments `Δθ` | [`coning`] | one exponential per increment | drift `α²Ω(Ωh)²/12` |
//! | | | one sample + previous (`Δθₖ₋₁ × Δθₖ / 12`), also as the two-speed [`coning::ConingAccumulator`] | `α²Ω(Ωh)⁴/60` |
//! | | | 2-, 3-, 4-sample rules | `α²Ω(ΩT)⁴/960`, `α²Ω(ΩT)⁶/204120`, `α²Ω(ΩT)⁸/82575360` |
//! | equally spaced rate samples `ω(k h)` | [`rate_samples`] | Magnus-4, commutator-free CF4, RK4 + renormalisation | order 4 |
//!
//! (`α` half-cone angle, `Ω` coning frequency, `h` sample interval, `T` attitude update interval;
//! the drifts are the rates at which pure coning motion makes the attitude error grow along the
//! cone axis, measured in `host-tests/tests/propagation_coning.rs`.)
//!
//! Every exponential-map rule forms a body-frame rotation vector `φ` and then goes through one
//! update kernel, [`exponential::apply_rotation_vector`]: `q ← normalise(q ⊗ exp(φ))`.
//! [`kinematics`] has the differential equation itself and the rate between two attitudes;
//! [`normalization`] the renormalisation policy and the `|q|` health value.
//!
//! # Hot path
//! Each module has a validated entry point (a constructor or a `push` that checks its input
//! for NaN and infinity and returns [`crate::Error`]) and lean unchecked step functions for an
//! inner loop whose input was validated upstream: [`coning::coning2_update`] is the complete
//! 2-sample update (rotation vector, exponential by series, product, fast renormalisation).

pub mod compensated;

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
/// shorter rotation the other way ([`kinematics::body_rate_between`]).
///
/// The checked entry points test it ([`coning::IncrementIntegrator::push`] with a coning rule,
/// [`coning::ConingAccumulator::push`], [`rate_samples::RateIntegrator::push`],
/// [`crate::dynamics::Gyrostat::step`]); the unchecked step functions state it as their domain.
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

/// The validity limit of the exact steps (the exponential of a rate held constant,
/// [`exponential::step_constant_rate`]): `|ω|·Δt ≤ 1/ε` (8.4e6 rad in f32, 4.5e15 in f64).
///
/// An exact step has no truncation error at any angle, but its angle is the product `ω·Δt`
/// rounded to the type, off by up to `ε/2` of itself: beyond `1/ε` that rounding alone is half a
/// radian or more, and the attitude after the step has no correct digit.
#[inline]
pub fn exact_step_angle_limit<T: Real>() -> T {
    T::ONE / T::EPSILON
}

pub mod coning;
pub mod exponential;
pub mod kinematics;
pub mod normalization;
pub mod rate_samples;

pub use compensated::{CompensatedAttitude, PropagatedAttitude};
pub use coning::{ConingAccumulator, ConingRule, ConingTerms, IncrementIntegrator};
pub use exponential::RotationVectorForm;
pub use normalization::Normalization;
pub use rate_samples::{RateIntegrator, RateMethod};
