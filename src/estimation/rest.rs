//! Rest detection: the sensor is still when, for long enough, neither the gyroscope nor the
//! accelerometer moves away from its own recent mean.
//!
//! Both signals are low-pass filtered ([`LowPass`], time constant `τ_rest`); the sensor counts
//! as moving whenever `|ω − ω̄| ≥ th_ω`, `|a − ā| ≥ th_a`, or `|ω̄|` exceeds the largest
//! plausible bias (a slow steady turn is not rest). After `t_min` seconds without motion it is
//! at rest, and `ω̄` is then a measurement of the gyroscope bias, averaged over `τ_rest`.

use super::lowpass::LowPass;
use crate::{Real, Vec3};

/// The rest detector's state (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RestDetector<T> {
    gyro: LowPass<T>,
    accel: LowPass<T>,
    still_for: T,
    at_rest: bool,
}

/// The rest detector's thresholds, declared with the estimator's parameters.
pub use super::params::RestThresholds;

impl<T: Real> RestDetector<T> {
    /// Starts on the first sample (`gyro`, `accel`), not at rest.
    pub fn new(gyro: Vec3<T>, accel: Vec3<T>) -> Self {
        Self {
            gyro: LowPass::at(gyro),
            accel: LowPass::at(accel),
            still_for: T::ZERO,
            at_rest: false,
        }
    }

    /// Feeds one sample taken `dt` after the previous one; returns whether the sensor is at
    /// rest.
    pub fn update(&mut self, gyro: Vec3<T>, accel: Vec3<T>, dt: T, th: &RestThresholds<T>) -> bool {
        let k = LowPass::gain(th.time_constant, dt);
        let g = self.gyro.update(gyro, k);
        let a = self.accel.update(accel, k);
        let b = th.max_bias;
        let moving = (gyro - g).norm_squared() >= th.gyro * th.gyro
            || (accel - a).norm_squared() >= th.accel * th.accel
            || g.x.abs() > b
            || g.y.abs() > b
            || g.z.abs() > b;
        if moving {
            self.still_for = T::ZERO;
            self.at_rest = false;
        } else {
            self.still_for += dt;
            if self.still_for >= th.min_duration {
                self.at_rest = true;
            }
        }
        self.at_rest
    }

    /// Whether the last sample was at rest.
    #[inline]
    pub fn at_rest(&self) -> bool {
        self.at_rest
    }

    /// The mean rate `ω̄` (rad/s): the bias measurement while at rest.
    #[inline]
    pub fn mean_rate(&self) -> Vec3<T> {
        self.gyro.output()
    }
}
