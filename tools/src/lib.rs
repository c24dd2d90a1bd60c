//! The command-line tools of gyrostat (`convert`, `propagate`, `simulate`, `estimate`,
//! `characterize`, `synthesize`) and what they share: one flag dialect and error style
//! ([`flags`]), one stream reader and CSV writer ([`stream`]), the units of sensor data on the
//! command line ([`units`]), the IMU log columns of `estimate` and `characterize` ([`imu_log`]),
//! the `key = numbers` line syntax of the calibration file and the sensor spec
//! ([`key_values`]), the plots' colours ([`plot`]), the scenarios of `simulate` ([`simulation`], with the external
//! torque of [`torque`]), the sensor noise model ([`noise`]) and its characterisation by the
//! Allan deviation ([`allan`], [`characterization`]), which the Python package (`python/`) runs
//! too; and the synthetic logs of `synthesize`: closed-form motions ([`motion`]), the sensor
//! spec file and its presets ([`sensor_spec`]) and the sensor model that turns a motion into
//! measurements ([`synthesis`]).
//!
//! What the tools share with the Python package and host-tests' BROAD runner lives one crate
//! below, in `gyrostat-pipeline`: the IMU log's columns and units ([`imu_log`] and [`units`],
//! re-exported here), the estimator's loop of `estimate` and the propagation loops of
//! `propagate` with their policies, BROAD's reader and metric.
//!
//! The tools are binaries of this crate (`src/bin/`); install them with
//! `cargo install --path tools`, or run them from a checkout with the cargo aliases of
//! `.cargo/config.toml` (`cargo simulate`, `cargo convert ...`, `cargo propagate ...`,
//! `cargo estimate ...`, `cargo characterize ...`, `cargo synthesize ...`). Their interfaces
//! (flags, formats, exit statuses) are in each tool's `--help` and in README.md; the library
//! itself (`gyrostat`) stays `no_std` and knows nothing of them.
//!
//! A further tool is one more file in `src/bin/` that declares its [`flags::Cli`] and reads its
//! input with [`stream::Lines`].

pub mod allan;
pub mod calibration;
pub mod characterization;
pub mod flags;
pub mod key_values;
pub mod motion;
pub mod noise;
pub mod plot;
pub mod sensor_spec;
pub mod simulation;
pub mod stream;
pub mod synthesis;
pub mod torque;

/// The IMU log's columns and units live in `gyrostat-pipeline` (below the tools and host-tests).
pub use gyrostat_pipeline::{imu_log, units};
