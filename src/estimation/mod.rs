//! Attitude estimation from a real IMU: gyroscope propagation corrected by the accelerometer
//! (inclination) and the magnetometer (heading only), with the gyroscope bias estimated online.
//!
//! (Design notes and the measured comparison of the candidate designs: see below once chosen.)

pub mod covariance;
pub mod field;
pub mod filter;
pub mod init;
pub mod lowpass;
pub mod rest;

pub use covariance::Covariance;
pub use field::{FieldMonitor, FieldThresholds};
pub use filter::{EarthFrame, Estimator, Gains, Outcome, Params, SensorUse};
pub use init::{attitude_from_gravity, attitude_from_gravity_and_field};
pub use lowpass::LowPass;
pub use rest::{RestDetector, RestThresholds};
