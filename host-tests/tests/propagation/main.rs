//! Tests of the propagation layer (`gyrostat::propagation`) against closed-form motion: one
//! module per part of `src/propagation/` (the whole map is in `host-tests/README.md`):
//!
//! - [`kinematics`]: `q̇`, the exact exponential step, spin precession and the normalisation
//!   policies (`kinematics.rs`, `exponential.rs`, `normalization.rs`).
//! - [`coning`]: the gyro-increment rules and the increment integrators (`coning.rs`).
//! - [`rate_samples`]: the rate-sample methods and their orders (`rate_samples.rs`).
//! - [`compensated`]: the compensated attitude over an hour at 1 kHz (`compensated.rs`).
//! - [`compensated_ablation`]: why compensated f32 drifted under coning, one part of the update
//!   changed at a time (`compensated.rs`).
//! - [`long_run`]: 10⁶ f32 exponential steps at a constant rate.

mod compensated;
mod compensated_ablation;
mod coning;
mod kinematics;
mod long_run;
mod mul_exp;
mod rate_samples;
