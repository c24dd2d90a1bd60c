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
//! says so, and the estimator undoes what a rest that ended this way taught its bias when the
//! gyroscope saw the turn (relative to the bias before the rest; a field that changes around a
//! still sensor turns the field's direction too, [`RestDetector::turned_by_field`]). A turn
//! about the vertical leaves `a` alone; the field's horizontal direction shows it
//! ([`RestDetector::update_field`], fed by the estimator with undisturbed field samples and the
//! field monitor's direction threshold: a smaller angle ended true rests on BROAD's magnetically
//! disturbed trials).

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
    /// Whether that turn was found by the field's horizontal direction (not by the specific
    /// force).
    field_turn: bool,
    /// The mean field over the still period (`None` until its first field sample).
    field: Option<LowPass<T>>,
    /// The horizontal direction of the mean field when the rest began (unit; zero until then).
    field_anchor: Vec3<T>,
}

/// What the rest detector's update computes from its thresholds and the step alone: the
/// low-pass stage gain and the squared thresholds (kept by the light mode for a run of equal
/// steps).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct RestFactors<T> {
    /// [`LowPass::gain`]`(τ_rest, Δt)`.
    gain: T,
    /// `th_ω²`.
    gyro2: T,
    /// `th_a²`.
    accel2: T,
}

impl<T: Real> RestFactors<T> {
    /// The factors of the thresholds `th` for the step `dt`.
    pub(crate) fn new(th: &RestThresholds<T>, dt: T) -> Self {
        Self {
            gain: LowPass::gain(th.time_constant, dt),
            gyro2: th.gyro * th.gyro,
            accel2: th.accel * th.accel,
        }
    }
}

/// The rest detector's thresholds, declared with the estimator's parameters.
pub use super::params::RestThresholds;

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
            field_turn: false,
            field: None,
            field_anchor: Vec3::ZERO,
        }
    }

    /// Feeds one sample taken `dt` after the previous one; returns whether the sensor is at
    /// rest.
    pub fn update(&mut self, gyro: Vec3<T>, accel: Vec3<T>, dt: T, th: &RestThresholds<T>) -> bool {
        self.update_with_factors(gyro, accel, dt, RestFactors::new(th, dt), th)
    }

    /// [`RestDetector::update`] with the factors of the thresholds and the step given
    /// ([`RestFactors::new`]; the light mode computes them once for a run of equal steps).
    #[inline]
    pub(crate) fn update_with_factors(
        &mut self,
        gyro: Vec3<T>,
        accel: Vec3<T>,
        dt: T,
        f: RestFactors<T>,
        th: &RestThresholds<T>,
    ) -> bool {
        let g = self.gyro.update(gyro, f.gain);
        let a = self.accel.update(accel, f.gain);
        let b = th.max_bias;
        let th_a2 = f.accel2;
        let gyro_moving = (gyro - g).norm_squared() >= f.gyro2;
        if gyro_moving {
            self.turning = false;
        } else if self.still_for > T::ZERO && (a - self.anchor).norm_squared() >= th_a2 {
            self.turning = true;
            self.field_turn = false;
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
                self.field = None;
                self.field_anchor = Vec3::ZERO;
            }
            self.still_for += dt;
            if self.still_for >= th.min_duration {
                self.at_rest = true;
            }
        }
        self.at_rest
    }

    /// Feeds one magnetometer sample (any unit, sensor frame) taken `dt` after the previous
    /// sample. A steady turn about the vertical leaves the specific force alone but turns the
    /// field's horizontal direction `ĥ` (the mean field `m̄`, time constant `τ_rest`, less its
    /// component along `ā`, normalised). When, during a rest, `ĥ` has turned by `angle` (rad)
    /// or more from its direction when the rest began (the mean then settled for `t_min`), the
    /// steady rate is a turn, as for the specific force ([`RestDetector::turning`]). Outside a
    /// still period it does nothing.
    #[inline]
    pub fn update_field(&mut self, mag: Vec3<T>, dt: T, angle: T, th: &RestThresholds<T>) {
        if self.still_for > T::ZERO {
            self.field_still(mag, dt, angle, th);
        }
    }

    /// [`RestDetector::update_field`] in a still period.
    #[inline(never)]
    fn field_still(&mut self, mag: Vec3<T>, dt: T, angle: T, th: &RestThresholds<T>) {
        let m = match &mut self.field {
            Some(lp) => lp.update(mag, LowPass::gain(th.time_constant, dt)),
            None => {
                self.field = Some(LowPass::at(mag));
                return;
            }
        };
        if !self.at_rest {
            return;
        }
        let up = self.accel.output();
        let n2 = up.norm_squared();
        if n2 <= T::ZERO || !n2.is_finite() {
            return;
        }
        let h = m - up.scale(m.dot(up) / n2);
        let h2 = h.norm_squared();
        if !(h2 > T::ZERO && h2.is_finite()) {
            return;
        }
        let h = h.scale(T::ONE / h2.sqrt());
        if self.field_anchor == Vec3::ZERO {
            self.field_anchor = h;
            return;
        }
        if (h - self.field_anchor).norm_squared() >= angle * angle {
            self.turning = true;
            self.field_turn = true;
            self.still_for = T::ZERO;
            self.at_rest = false;
        }
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

    /// Whether the turn of [`RestDetector::turning`] was found by the field's horizontal
    /// direction ([`RestDetector::update_field`]: a turn about the vertical, or a field that
    /// changed) rather than by the specific force (meaningful while `turning`).
    #[inline]
    pub fn turned_by_field(&self) -> bool {
        self.field_turn
    }

    /// The mean rate `ω̄` (rad/s): the bias measurement while at rest.
    #[inline]
    pub fn mean_rate(&self) -> Vec3<T> {
        self.gyro.output()
    }
}
