//! Tests of the fixed-point layer (`gyrostat::fixed`, `src/fixed/`) against the independent f64
//! reference, beside the f32 path (the whole map is in `host-tests/README.md`):
//!
//! - [`accuracy`]: Q1.30 products, exponential, renormalisation, range edges, coning drift and
//!   raw sensor increments.
//! - [`ablation`]: the fixed-point update re-written in `i128` with each rounding carried or
//!   forgotten: which rounding drifts (leave one out).
//! - [`carried`]: the carried attitude and the quantizer (no rounding bias) against the closed
//!   form on inputs that do not repeat, and the causes of the plain path's bias.
//! - [`firmware`]: the `fw_fixed` scenario on the host, and the boards' output bit for bit
//!   (ignored unless CI hands it the output: `-- --ignored firmware::`).

mod ablation;
mod accuracy;
mod carried;
mod firmware;
