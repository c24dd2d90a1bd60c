//! The sample pipeline under gyrostat's faces, host side (std): what the `estimate` tool, the
//! Python package (`python/`) and the BROAD research runner (`host-tests`) share, written once.
//!
//! - [`units`]: the units of sensor data (`--gyro-unit`, `--accel-unit`, `--mag-unit`,
//!   `--time-unit`) and their factors to SI;
//! - [`imu_log`]: the IMU log's stream (gzip recognised by its first bytes), its column names
//!   (the short ones, BROAD's, the x-io Fusion log's) and the parsing of a row;
//! - [`estimate`]: the estimator's loop over samples: the first-sample rule, the step and
//!   order checks (through the library's [`gyrostat::sensor::SampleClock`]), the calibration,
//!   the bad-row policy (`--skip-bad-rows`) and the output row of the `estimate` tool;
//! - [`propagate`]: the propagation loops (increments with a coning rule, rates with a method,
//!   the Q1.30 increment path) with the checks of every sample and attitude, for the
//!   `propagate` tool and Python's `propagate_increments` / `propagate_rates`;
//! - [`broad`]: a log read whole (BROAD's trials and the short-named logs) and BROAD's metric
//!   (the computation of the dataset's `score.py`).
//!
//! The crate sits below both `gyrostat-tools` (which re-exports [`units`] and [`imu_log`]) and
//! `host-tests` (whose research runner and regression tests read and score the trials with
//! it), so that neither depends on the other's library.

pub mod broad;
pub mod estimate;
pub mod imu_log;
pub mod propagate;
pub mod units;
