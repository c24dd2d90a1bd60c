//! The command-line tools as processes: their interfaces (flags, formats, errors, exit statuses)
//! and their numbers against the independent references of `host_tests`. One module per tool
//! (`tools/src/bin/`), the adversarial campaign over all three, and `propagate --fixed` against
//! the fixed-point firmware:
//!
//! - [`convert`]: every representation and operation against the reference matrices.
//! - [`propagate`]: the coning rules and rate methods against closed-form coning motion, and
//!   `--compensated`.
//! - [`simulate`]: the free rigid body and a gyrostat with wheels and torques against tiny-step
//!   references, the plot, the error paths.
//! - [`fixed`]: `propagate --fixed` reproduces the firmware's Q1.30 bits.
//! - [`estimate`]: convergence on a closed-form motion, BROAD's metric against `score.py` and
//!   `host_tests::broad`, input dialects, frames, f32, the plot, the error paths.
//! - [`characterize`]: the Allan characterisation recovers simulated noise (N, K within 10 %,
//!   B within 25 %), the tool's tables, files, plot and errors, BROAD's rest phases.
//! - [`campaign`]: garbage input, bad flags, overflowing values and closed pipes for all three.
//! - [`timed`]: `propagate --time-column` and the sensor options on the real Fusion log and on
//!   jittered synthetic streams.
//! - [`synthesize`]: synthetic logs against closed-form motion and an independent sensor
//!   model, `estimate --truth` on them, a slice of the synthetic benchmark grid.
//! - [`cli`]: the tools as processes (`CARGO_BIN_EXE_*`).

mod campaign;
mod characterize;
mod cli;
mod convert;
mod estimate;
mod fixed;
mod propagate;
mod simulate;
mod synthesize;
mod timed;
