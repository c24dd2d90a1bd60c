//! Rest detection: the sensor is still when, for long enough, neither the gyroscope nor the
//! accelerometer moves away from its own recent mean.
//!
//! Both signals are low-pass filtered ([`LowPass`], time constant `τ_rest`); the sensor counts
//! as moving whenever `|ω − ω̄| ≥ th_ω`, `|a − ā| ≥ th_a`, or `|ω̄|` exceeds the largest
//! plausible bias (a steady turn faster than any bias is not rest). After `t_min` seconds
//! without motion it is at rest, and `ω̄` is then a measurement of the gyroscope bias, averaged
//! over `τ_rest`.
//!
//! A steady turn slower than the largest bias passes those tests (the gyroscope cannot tell it
//! from a bias, and the deviation of `a` from its lagging mean is only `|ω × a|·τ_rest`), but it
//! turns the specific force: the sensor is also moving when `ā` has moved `th_a` or more from
//! the sample `a₀` that started the still period, `|ā − a₀| ≥ th_a`. That steady rate is then
//! a turn, and stays one (no rest) until the gyroscope moves (`|ω − ω̄| ≥ th_ω`): a slow turn
//! would otherwise be still again for `t_min` after each restart. [`RestDetector::turning`]
//! says so, and the estimator undoes what a rest that ended this way taught its bias. A turn
//! about the vertical leaves `a` alone and is not found: the magnetometer's heading update
//! bounds its effect (the field's horizontal direction would find it too, but a magnetic
//! disturbance at rest turns it as well: on BROAD's disturbed trials such a test ended true
//! rests and cost accuracy).

use super::lowpass::LowPass;
use crate::{Real, Vec3};

/// The rest detector's state (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RestDetector<T> {
    gyro: LowPass<T>,
    accel: LowPass<T>,
    /// `a₀`: the specific force at the start of the still period (a sample, not the mean: the
    /// mean may still be settling after the motion, within `th_a` of the sample).
    anchor: Vec3<T>,
    still_for: T,
    at_rest: bool,
    /// A steady rate found to be a turn (the specific force drifted), until the gyroscope moves.
    turning: bool,
}

/// The rest detector's thresholds (SI units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RestThresholds<T> {
    /// `τ_rest` (s): the time constant of the means.
    pub time_constant: T,
    /// `th_ω` (rad/s): the largest deviation of the rate from its mean at rest.
    pub gyro: T,
    /// `th_a` (m/s²): the largest deviation of the specific force from its mean at rest.
    pub accel: T,
    /// The largest `|ω̄|` (rad/s) taken as a bias: a steadier turn is motion.
    pub max_bias: T,
    /// `t_min` (s): how long the sensor must be still before it counts as at rest.
    pub min_duration: T,
}

impl<T: Real> RestDetector<T> {
    /// Starts on the first sample (`gyro`, `accel`), not at rest.
    pub fn new(gyro: Vec3<T>, accel: Vec3<T>) -> Self {
        Self {
            gyro: LowPass::at(gyro),
            accel: LowPass::at(accel),
            anchor: accel,
            still_for: T::ZERO,
            at_rest: false,
            turning: false,
        }
    }

    /// Feeds one sample taken `dt` after the previous one; returns whether the sensor is at
    /// rest.
    pub fn update(&mut self, gyro: Vec3<T>, accel: Vec3<T>, dt: T, th: &RestThresholds<T>) -> bool {
        let k = LowPass::gain(th.time_constant, dt);
        let g = self.gyro.update(gyro, k);
        let a = self.accel.update(accel, k);
        let b = th.max_bias;
        let th_a2 = th.accel * th.accel;
        let gyro_moving = (gyro - g).norm_squared() >= th.gyro * th.gyro;
        if gyro_moving {
            self.turning = false;
        } else if self.still_for > T::ZERO && (a - self.anchor).norm_squared() >= th_a2 {
            self.turning = true;
        }
        let moving = gyro_moving
            || self.turning
            || (accel - a).norm_squared() >= th_a2
            || g.x.abs() > b
            || g.y.abs() > b
            || g.z.abs() > b;
        if moving {
            self.still_for = T::ZERO;
            self.at_rest = false;
        } else {
            if self.still_for <= T::ZERO {
                self.anchor = accel;
            }
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

    /// Whether the steady rate is a turn: the specific force drifted `th_a` from its value at
    /// the start of the still period while the gyroscope stayed steady (see the module docs);
    /// until the gyroscope moves.
    #[inline]
    pub fn turning(&self) -> bool {
        self.turning
    }

    /// The mean rate `ω̄` (rad/s): the bias measurement while at rest.
    #[inline]
    pub fn mean_rate(&self) -> Vec3<T> {
        self.gyro.output()
    }
}
