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
