//! The light mode of [`Estimator`] ([`Mode::Light`]): the same filter with its corrections
//! taken at a lower rate than the prediction.
//!
//! Every sample: the strapdown prediction `q_g ← q_g ⊗ exp(φ)` with the step's rotation `φ`
//! by [`Params::rate_rule`] as in the full mode (the default Magnus-4 from weights computed
//! once per run of equal intervals: `rate_window`'s `magnus4_cached`, the full mode's mean
//! rotation to rounding, its commutator from the step's end samples, which changes the step by
//! the order of Magnus-4's own local error), renormalised every
//! eighth prediction, the rest detector, and the specific force rotated into the gyroscope frame
//! and low-passed there. Every `T_c` ([`Mode::Light`]'s `correction_period`,
//! measured in sample time, so the same at any rate): the covariance prediction over the whole
//! interval, `Φ = [[I, −R̂·T_c], [0, I]]` (the attitude's transition is the identity in the
//! earth frame, so `k` steps of the full mode collapse into one with `R̂` held at its value at
//! the end of the interval), with `Q = diag((σ_g²·T_c + s²·Σ|ω|²Δt)·I, σ_b²T_c/τ_b·I)`; the
//! rest, inclination and heading updates of the full mode, with their measurement variances
//! for one measurement per `T_c` (`σ²·τ_c/T_c`); and the latest valid field sample since the
//! last correction, in the frame of its own row (a magnetometer slower than the corrections
//! loses no sample to them), standing for the magnetometer's interval. The error
//! dynamics (bias, tilt and heading drift) are slow against `T_c`, so the corrections lose
//! little by waiting (see BENCHMARKS.md for the measured accuracy on BROAD).
//!
//! What the light mode leaves out: the attitude history on the time grid and the online
//! estimate of the magnetometer's delay. A fixed delay `d` is applied to first order in the
//! sensor frame: the sample taken `d` ago is mapped to the current sensor frame by
//! `exp(−ω·d) ≈ I − d[ω]×`, `m' = m − d·(ω × m)`. `d` is [`Params::mag_delay`] when it is
//! given (positive) or when [`Params::mag_delay_estimation_time`] is 0 (a fixed delay asked
//! for, 0 included). With neither (the defaults: no delay given, an estimate asked for, which
//! the light mode does not make) `d` = [`Mode::LIGHT_MAG_DELAY`] at every sample rate: a value
//! read off BROAD, not a sensor figure. The sensor's own delay is measured by the full mode:
//! `estimate --params-out FILE` writes its estimate as a parameter file for `--params`
//! (BENCHMARKS.md, "The light mode's magnetometer delay from the sensor": with the sensor's
//! true delay the light mode scores as the full mode does with it, no offset between them).
//!
//! Between corrections the [`Outcome`] reports the accelerometer sample as used (it fed the
//! low-pass filter) and a valid magnetometer sample with the report of the last correction
//! that took a field sample.

use super::{
    Estimator, GRAVITY, Gains, HARD_IRON_FEED_STEP, MAG_DELAY_MAX, MAG_INTERVAL_MAX, Mode, Outcome,
    Params, SensorUse, accel_mean_update, horizontal, length,
};
use crate::estimation::lowpass::LowPass;
use crate::estimation::rate_window::StepRotation;
use crate::estimation::rest::RestFactors;
use crate::propagation::{Normalization, PropagatedAttitude};
use crate::step_limit::within_step_limit_real;
use crate::{Real, UnitQuat, Vec3};

/// What the light mode accumulates between two corrections.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct LightState<T> {
    /// Time (s) since the last correction.
    elapsed: T,
    /// The rate-proportional attitude noise (rad²) accumulated since the last correction.
    q_scale: T,
    /// Attitude variance (rad²) added by saturated gyroscope samples since the last correction.
    saturated: T,
    /// Whether an accelerometer sample fed the low-pass filter since the last correction.
    accel_fed: bool,
    /// Whether the rest detector said "at rest" at the last accelerometer sample.
    at_rest: bool,
    /// The magnetometer's report at the last correction.
    mag: SensorUse,
    /// The latest valid field sample since the last correction, taken to the next one (and
    /// set during that correction's heading update only).
    field: Option<PendingField<T>>,
    /// The bias-corrected rate (rad/s) at the correction, for the field's delay.
    rate: Vec3<T>,
    /// The per-step factors of the last step length, kept across corrections.
    steps: StepFactors<T>,
    /// The predictions since `q_g` was last renormalised, kept across corrections (at most
    /// [`RENORMALISATION_STEPS`]).
    unnormalised: u8,
}

/// The light mode renormalises the strapdown attitude `q_g` (fast, [`Normalization::Fast`])
/// after every this many predictions, not after each: a product of unit quaternions drifts
/// from unit norm by about an ulp (a random walk), so `|q_g|` stays within some eight ulp of 1
/// between renormalisations (the output's [`Params::gyro_delay`] lead renormalises it once
/// more), and a Cortex-M0 saves some 1400 of its soft-float instructions per sample
/// (`|q|²`, the correction's factor and the four products and sums of
/// [`crate::UnitQuat::renormalize_fast`] on seven samples of eight).
const RENORMALISATION_STEPS: u8 = 8;

/// What the light mode's per-sample work computes from the step `Δt` alone, kept for the next
/// sample with the same `Δt` (a fixed sample rate): four divisions and two exponentials or
/// their series fewer per sample, which is most of a soft-float core's cost of a sample, and the
/// magnetometer delay computed once (the values are the same numbers as computed afresh).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct StepFactors<T> {
    /// The step these are for; 0 (no valid step) before the first.
    dt: T,
    /// `min(s²/Δt, 1)`: the rate-proportional noise per squared step rotation.
    scale_noise: T,
    /// The inertial low-pass's stage gain ([`LowPass::gain`]).
    lowpass_gain: T,
    /// The rest detector's low-pass stage gain ([`LowPass::gain`] of its time constant) and
    /// squared thresholds ([`RestFactors`]).
    rest: RestFactors<T>,
    /// The magnetometer delay `d` (s) the field sample is carried back by (module docs).
    mag_delay: T,
    /// Whether every clipped rate turns within the shared step limit over `Δt`:
    /// `3·(r·Δt)² ≤ MAX_STEP_ANGLE²` for the gyroscope's range `r` (rounded as the test on a
    /// sample, whose square can then not exceed it), so that the per-sample test is moot.
    within_step_limit: bool,
}

/// A valid field sample waiting for the next correction, with what its row knew.
#[derive(Clone, Copy, Debug, PartialEq)]
struct PendingField<T> {
    /// The sample (sensor frame, input units).
    mag: Vec3<T>,
    /// The strapdown attitude `q_g` after its row's prediction.
    q_gyro: UnitQuat<T>,
    /// The time (s) from the last correction to its row.
    elapsed: T,
}

impl<T: Real> StepFactors<T> {
    fn for_step(&mut self, dt: T, pr: &Params<T>) -> Self {
        if dt != self.dt {
            let s2 = pr.gyro_scale_noise * pr.gyro_scale_noise;
            *self = Self {
                dt,
                scale_noise: (s2 / dt).min(T::ONE),
                lowpass_gain: LowPass::gain(pr.accel_time_constant, dt),
                rest: RestFactors::new(&pr.rest, dt),
                mag_delay: mag_delay(pr),
                within_step_limit: {
                    let a = pr.gyro_range * dt;
                    within_step_limit_real(Vec3::new(a, a, a))
                },
            };
        }
        *self
    }
}

impl<T: Real> LightState<T> {
    /// Whether no clipped rate can turn by more than the shared step limit over `dt`, known
    /// from the last step of the same length (`false` when not known: the caller tests the
    /// sample).
    #[inline]
    pub(super) fn step_within_limit(&self, dt: T) -> bool {
        self.steps.dt == dt && self.steps.within_step_limit
    }
}

impl<T: Real, A: PropagatedAttitude<T>> Estimator<T, A> {
    /// The light mode's update after the checks and the initialisation of
    /// [`Estimator::update`]: the prediction every sample, the corrections every `period`.
    #[allow(
        clippy::too_many_arguments,
        reason = "the checked samples and their reports, as `update` holds them"
    )]
    pub(super) fn update_light(
        &mut self,
        (step, theta2): (StepRotation<T>, T),
        mean_rate: Vec3<T>,
        gyro: Vec3<T>,
        accel: Vec3<T>,
        mag: Option<Vec3<T>>,
        (accel_use, mag_use): (SensorUse, SensorUse),
        mut out: Outcome,
        dt: T,
        period: T,
    ) -> Outcome {
        let s = &mut self.light;
        s.unnormalised += 1;
        let norm = if s.unnormalised >= RENORMALISATION_STEPS {
            s.unnormalised = 0;
            Normalization::Fast
        } else {
            Normalization::None
        };
        self.q_gyro = step.apply_normalised_sq(self.q_gyro, theta2, norm);
        // Borrowed, not copied, on the per-sample path.
        let pr = &self.params;
        let s = &mut self.light;
        s.elapsed += dt;
        let factors = s.steps.for_step(dt, pr);
        // The full mode's rate-proportional noise per step, `θ²·min(s²/Δt, 1)`, summed.
        s.q_scale += theta2 * factors.scale_noise;
        if out.gyro_saturated {
            let a = (pr.gyro_range * dt).min(T::PI);
            s.saturated += a * a;
            self.lowpass_stale = true;
        }
        if accel_use == SensorUse::Used {
            s.at_rest = self
                .rest
                .update_with_factors(gyro, accel, dt, factors.rest, &pr.rest);
            let a_gyro = self.q_gyro.attitude().rotate(accel);
            if self.lowpass_stale {
                // `Estimator::restart_accel_lowpass` (the fields, `pr` borrowed).
                self.accel_lp = LowPass::at(a_gyro);
                self.accel_warm = T::ZERO;
                self.tilt_from_mean = false;
                self.lowpass_stale = false;
            }
            if self.accel_warm < pr.accel_time_constant {
                // The full mode's start: the running mean over the first `τ_a`.
                accel_mean_update(&mut self.accel_lp, &mut self.accel_warm, a_gyro, dt);
            } else if pr.accel_time_constant > T::ZERO {
                self.accel_lp.update(a_gyro, factors.lowpass_gain);
            } else {
                self.accel_lp = LowPass::at(a_gyro);
            }
            self.light.accel_fed = true;
        }
        // The magnetometer's interval (`Estimator::update`): the time from the row of the sample
        // taken to the last correction (`mag_clock` before the correction's interval, no
        // arithmetic per sample) to this one's row (bounded where it is used).
        if let (Some(m), SensorUse::Used) = (mag, mag_use) {
            self.light.field = Some(PendingField {
                mag: m,
                q_gyro: self.q_gyro.attitude(),
                elapsed: self.light.elapsed,
            });
            self.light_hard_iron(m, gyro);
        }
        out.at_rest = self.light.at_rest && accel_use == SensorUse::Used;
        out.accel = accel_use;
        let mag_ok = mag_use == SensorUse::Used;
        if self.light.elapsed < period {
            // A valid sample reports as the last correction did (as used before the first).
            out.mag = match (mag_ok, self.light.mag) {
                (true, SensorUse::Absent) => SensorUse::Used,
                (true, last) => last,
                (false, _) => mag_use,
            };
            self.last = out;
            return out;
        }

        // The bias-corrected rate for the field's delay, with the bias before the corrections.
        let w = mean_rate - self.bias;
        let pr = self.params;
        let s = core::mem::take(&mut self.light);
        self.light.steps = s.steps;
        self.light.unnormalised = s.unnormalised;
        let tc = s.elapsed;
        // The hard-iron fit's last feed, restated from this period's start to the next's (no
        // arithmetic per sample: `light_hard_iron`).
        self.hard_iron_clock = (self.hard_iron_clock - tc).max(T::from_f64(-MAG_INTERVAL_MAX));
        // The covariance over the interval, R̂ at its end.
        let f = self.attitude_enu().to_rotation_matrix().scale(-tc);
        let q_theta = pr.gyro_noise_density * pr.gyro_noise_density * tc + s.q_scale;
        let q_bias = pr.gyro_bias_stability * pr.gyro_bias_stability * tc / pr.gyro_bias_time;
        self.p.predict(f, q_theta, q_bias);
        if s.saturated > T::ZERO {
            self.p.inflate_attitude(s.saturated);
        }
        self.p.bound(T::PI * T::PI, self.bias_variance_max());

        let mut x = [T::ZERO; 6];
        if s.accel_fed {
            self.rest_correction(s.at_rest, tc, &mut x);
            let used = self.tilt_update(self.accel_lp.output(), tc, &mut x);
            if accel_use == SensorUse::Used {
                out.accel = used;
            }
        }
        self.inject(&x);

        // The latest valid field sample since the last correction, in the frame of its row,
        // standing for the magnetometer's time since the one before it (the rate and the
        // gyroscope sample are the correction's: they move little within a period).
        self.light.rate = w;
        self.light.mag = match s.field {
            Some(p) => {
                self.light.field = Some(p);
                let interval = (self.mag_clock + p.elapsed).min(T::from_f64(MAG_INTERVAL_MAX));
                // From its row to this correction.
                self.mag_clock = tc - p.elapsed;
                let u = self.mag_update(p.mag, gyro, interval);
                self.light.field = None;
                u
            }
            // No new sample: the last report stands (for the valid samples until the next).
            None => {
                self.mag_clock = (self.mag_clock + tc).min(T::from_f64(MAG_INTERVAL_MAX));
                s.mag
            }
        };
        out.mag = if mag_ok { self.light.mag } else { mag_use };
        self.last = out;
        out
    }

    /// The light mode's field sample (sensor frame; raw or hard-iron corrected) in the
    /// gyroscope frame: the sample of `d` ago carried to its row's sensor frame to first order,
    /// `m − d·(ω × m)`, then rotated by that row's `q_g` (see the module docs for `d`).
    pub(super) fn light_field(&self, mag: Vec3<T>) -> Vec3<T> {
        match self.light.field {
            Some(p) => {
                let d = self.light.steps.mag_delay;
                p.q_gyro.rotate(mag - self.light.rate.cross(mag).scale(d))
            }
            None => self.q_gyro.attitude().rotate(mag),
        }
    }

    /// The full mode's hard-iron feed (`mag_update`) on every sample rather than at the
    /// corrections: the fit's information grows with the samples it is fed (measured on BROAD
    /// trial 36: fed at the 25 ms corrections 1.86°, on every sample 1.2°, as the full mode).
    /// The fit's clock is the magnetometer's time since the last feed (true time, as the full
    /// mode's), each fed sample standing for at most [`MAG_INTERVAL_MAX`]
    /// ([`HARD_IRON_FEED_STEP`]). In this mode `hard_iron_clock` holds the time of the last
    /// feed from the start of the current correction period (`light.elapsed`'s origin; at most
    /// [`MAG_INTERVAL_MAX`] before it), so that no arithmetic is added per sample.
    fn light_hard_iron(&mut self, mag: Vec3<T>, gyro: Vec3<T>) {
        let pr = &self.params;
        if pr.mag_hard_iron_time <= T::ZERO {
            return;
        }
        let since = self.light.elapsed - self.hard_iron_clock;
        if since < T::from_f64(HARD_IRON_FEED_STEP) {
            return;
        }
        let min_rate = pr.field.new_field_min_rate;
        if (gyro - self.bias).norm_squared() >= min_rate * min_rate {
            let credit = since.min(T::from_f64(MAG_INTERVAL_MAX));
            self.hard_iron
                .update_fit_only(mag, credit, pr.mag_hard_iron_time);
            self.hard_iron_offer = self.hard_iron_offer_now();
        }
        self.hard_iron_clock = self.light.elapsed;
    }

    /// The inclination update from the low-passed specific force `v` (gyroscope frame): the
    /// full mode's, for one measurement per `dt`.
    fn tilt_update(&mut self, v: Vec3<T>, dt: T, x: &mut [T; 6]) -> SensorUse {
        let pr = self.params;
        let g = T::from_f64(GRAVITY);
        let residual = (length(v) - g).abs() / g;
        if residual > pr.accel_reject {
            return SensorUse::Disturbed;
        }
        let v = self.q_corr.rotate(v);
        let (ex, ey) = tilt_error(v);
        if self.tilt_from_the_mean(ex, ey, x) {
            return SensorUse::Used;
        }
        let r = self.tilt_variance(dt);
        match pr.gains {
            Gains::Kalman => {
                self.scalar_update(x, 0, ex, r);
                self.scalar_update(x, 1, ey, r);
            }
            Gains::Fixed { .. } => {
                let x0 = *x;
                self.scalar_update(x, 0, ex, r);
                self.scalar_update(x, 1, ey, r);
                x[0] = x0[0] + ex;
                x[1] = x0[1] + ey;
            }
        }
        SensorUse::Used
    }
}

/// The light mode's magnetometer delay `d` (s) (module docs): [`Params::mag_delay`] (at most
/// `MAG_DELAY_MAX`) when it is given (positive) or a fixed delay is asked for
/// (`mag_delay_estimation_time` 0), else [`Mode::LIGHT_MAG_DELAY`].
fn mag_delay<T: Real>(pr: &Params<T>) -> T {
    if pr.mag_delay_estimation_time > T::ZERO && pr.mag_delay <= T::ZERO {
        T::from_f64(Mode::<T>::LIGHT_MAG_DELAY)
    } else {
        pr.mag_delay.max(T::ZERO).min(T::from_f64(MAG_DELAY_MAX))
    }
}

/// The rotation vector (x, y parts) taking the earth-frame vector `v` to +z: about
/// `(v_y, −v_x, 0)` by the angle between `v` and z.
fn tilt_error<T: Real>(v: Vec3<T>) -> (T, T) {
    let h = horizontal(v);
    let angle = h.atan2(v.z);
    if h > T::ZERO {
        (v.y * angle / h, -v.x * angle / h)
    } else {
        (T::ZERO, T::ZERO)
    }
}
