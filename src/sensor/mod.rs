//! Real sensor streams before the propagation core: timestamps, calibration, mounting and raw
//! registers.
//!
//! The data path of one sample:
//!
//! `raw i16 registers` → [`ClipGuard`] (clipping flags and policy) → LSB scale ([`RawScale`], in f32, f64
//! or Q1.30) → [`InertialCalibration`]
//! (`K·(raw − b)`) → mounting ([`AxisRemap`] or [`Mounting`]) → propagation with the interval
//! from [`SampleClock`] / [`MicrosClock`] ([`crate::propagation::kernels::coning2_update_unequal`]
//! for increments over unequal intervals, [`crate::propagation::kernels::magnus4_step_unequal`] for rates
//! at unequal sample times).
//!
//! Everything here is `no_std`, allocation-free and panic-free; the floats (f32, f64) and, where
//! a function says so, Q1.30 take the same names.
//!
//! - [`timing`]: intervals from timestamps in seconds or from a wrapping 32-bit microsecond
//!   counter; gaps, repeated and backwards timestamps as typed results with a documented policy.
//! - [`calibration`]: gyro and accelerometer bias, scale, misalignment; magnetometer hard and soft
//!   iron.
//! - [`mounting`]: the 24 proper signed axis permutations and an arbitrary mounting rotation.
//! - [`raw`]: LSB scales and clipping.
//! - [`variance`]: streaming rest-noise statistics (Welford mean and variance, the
//!   successive-difference variance, the white noise density) per axis.

pub mod calibration;
pub mod mounting;
pub mod raw;
pub mod timing;
pub mod variance;

pub use calibration::{InertialCalibration, MagnetometerCalibration};
pub use mounting::{AxisRemap, Mounting};
pub use raw::{ClipGuard, ClipLimit, ClipPolicy, Clipped, RawFormat, RawScale, Reading};
pub use timing::{Interval, MicrosClock, SampleClock};
pub use variance::{RestNoise, RunningVariance};
