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
//! | | | one sample + previous (`Δθₖ₋₁ × Δθₖ / 12`), also as the two-speed [`ConingAccumulator`] | `α²Ω(Ωh)⁴/60` |
//! | | | 2-, 3-, 4-sample rules | `α²Ω(ΩT)⁴/960`, `α²Ω(ΩT)⁶/204120`, `α²Ω(ΩT)⁸/82575360` |
//! | equally spaced rate samples `ω(k h)` | [`rate_samples`] | Magnus-4, commutator-free CF4, RK4 + renormalisation | order 4 |
//!
//! (`α` half-cone angle, `Ω` coning frequency, `h` sample interval, `T` attitude update interval;
//! the drifts are the rates at which pure coning motion makes the attitude error grow along the
//! cone axis, measured in `host-tests/tests/propagation/coning.rs`.)
//!
//! Every exponential-map rule forms a body-frame rotation vector `φ` and then goes through one
//! update kernel, [`crate::UnitQuat::mul_exp_unchecked`]: `q ← normalise(q ⊗ exp(φ))`, the same name
//! (and the checked `try_mul_exp`) on the [`CompensatedAttitude`] and the [`CarriedAttitude`].
//! [`kinematics`] has the differential equation itself and the rate between two attitudes;
//! [`normalization`] the renormalisation policy and the `|q|` health value.
//!
//! # Checked entry points and kernels
//! The streaming integrators check every sample (NaN, infinity, the step's validity limit
//! [`crate::step_limit::MAX_STEP_ANGLE`]) and return [`crate::Error`]: [`IncrementIntegrator`]
//! for gyro increments (any [`ConingRule`]), [`ConingAccumulator`] for the two-speed form,
//! [`RateIntegrator`] for rate samples (any [`RateMethod`]). Each carries a
//! [`PropagatedAttitude`]: a plain [`crate::UnitQuat`] or a [`CompensatedAttitude`] (the f32
//! attitude with its rounding carried, [`compensated_attitude`]) or a [`CarriedAttitude`] (the
//! fixed-point attitude with its roundings' residuals carried, [`carried_attitude`]), with the same
//! methods. The updates they run are the
//! unchecked [`kernels`], for an inner loop whose input was validated upstream:
//! [`kernels::coning2_update`] is the complete 2-sample update (rotation vector, exponential by
//! series, product, fast renormalisation).
//!
//! Files: the rules' formulas ([`coning`], [`rate_samples`]) at the bottom, then the
//! [`kernels`] and the [`compensated_attitude`] and [`carried_attitude`] updates built on them, the attitude trait over both, and
//! the integrators on top.

pub(crate) mod attitude;
pub mod carried_attitude;
pub mod compensated_attitude;
pub mod coning;
pub mod exponential;
mod increment_integrator;
pub mod kernels;
pub mod kinematics;
pub mod normalization;
mod rate_integrator;
pub mod rate_samples;

pub use attitude::PropagatedAttitude;
pub use carried_attitude::CarriedAttitude;
pub use compensated_attitude::CompensatedAttitude;
pub use coning::{ConingAccumulator, ConingRule, ConingTerms};
pub use increment_integrator::{IncrementBuffer, IncrementIntegrator};
pub use kernels::RotationVectorForm;
pub use normalization::Normalization;
pub use rate_integrator::{Attitudes, RateIntegrator};
pub use rate_samples::RateMethod;
