//! The command-line tools of gyrostat (`convert`, `propagate`, `simulate`, `estimate`) and what
//! they share: one flag dialect and error style ([`flags`]), one stream reader and CSV writer
//! ([`stream`]), the units of sensor data on the command line ([`units`]), the plots' colours
//! ([`plot`]), and the scenarios of `simulate` ([`simulation`], with the external torque of
//! [`torque`]), which the Python package (`python/`) runs too.
//!
//! The tools are binaries of this crate (`src/bin/`); install them with
//! `cargo install --path tools`, or run them from a checkout with the cargo aliases of
//! `.cargo/config.toml` (`cargo simulate`, `cargo convert ...`, `cargo propagate ...`,
//! `cargo estimate ...`). Their interfaces (flags, formats, exit statuses) are in each tool's
//! `--help` and in README.md; the library itself (`gyrostat`) stays `no_std` and knows nothing
//! of them.
//!
//! A further tool is one more file in `src/bin/` that declares its [`flags::Cli`] and reads its
//! input with [`stream::Lines`].

pub mod allan;
pub mod calibration;
pub mod flags;
pub mod motion;
pub mod noise;
pub mod plot;
pub mod sensor_spec;
pub mod simulation;
pub mod stream;
pub mod synthesis;
pub mod torque;
pub mod units;
