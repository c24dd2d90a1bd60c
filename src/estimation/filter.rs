//! The attitude-and-bias estimator: gyroscope propagation, inclination from the accelerometer,
//! heading from the magnetometer.

use super::covariance::Covariance;
use super::field::FieldMonitor;
use super::hard_iron::HardIron;
use super::init::{attitude_from_gravity, attitude_from_gravity_and_field};
use super::lowpass::{LowPass, first_order_gain};
use super::params::{EarthFrame, FieldThresholds, Gains, Mode, Params};
use super::rate_window::{RateWindow, StepRotation};
use super::rest::RestDetector;
use crate::propagation::coning::one_plus_previous_terms;
use crate::propagation::{CompensatedAttitude, Normalization, PropagatedAttitude, RateMethod};
use crate::sensor::ClipLimit;
use crate::step_limit::within_step_limit_real;
use crate::{Error, Quat, Real, UnitQuat, Vec3};

// The light mode (its own file; a child module for the estimator's private state).
#[path = "light.rs"]
mod light;

/// What became of one sensor's sample in an update.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SensorUse {
    /// The sample corrected the estimate.
    Used,
    /// No sample was given (a 6D update has no magnetometer).
    #[default]
    Absent,
    /// A component was NaN or infinite: the sample was ignored.
    NonFinite,
    /// A component was at or beyond the sensor's range: the sample was ignored.
    Saturated,
    /// The sample was finite but rejected as disturbed: a specific force far from gravity, or a
    /// magnetic field whose norm or dip differs from the reference.
    Disturbed,
    /// A zero vector: no direction.
    Zero,
}

impl SensorUse {
    /// The name in the `estimate` tool's output and the other faces: `used`, `absent`,
    /// `nonfinite`, `saturated`, `disturbed`, `zero`.
    pub const fn name(self) -> &'static str {
        match self {
            SensorUse::Used => "used",
            SensorUse::Absent => "absent",
            SensorUse::NonFinite => "nonfinite",
            SensorUse::Saturated => "saturated",
            SensorUse::Disturbed => "disturbed",
            SensorUse::Zero => "zero",
        }
    }
}

/// The report of one update: what each sensor's sample did. The state is valid whatever it
/// says.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Outcome {
    /// `true` when a gyroscope component was at or beyond its range: the attitude was
    /// propagated with the clipped rate and its uncertainty increased.
    pub gyro_saturated: bool,
    /// The accelerometer sample.
    pub accel: SensorUse,
    /// The magnetometer sample.
    pub mag: SensorUse,
    /// Whether the sensor was at rest.
    pub at_rest: bool,
    /// Whether this update initialised the attitude (the first usable accelerometer sample).
    pub initialized: bool,
}

/// The attitude and gyroscope-bias estimator (see the module docs for the design).
///
/// `A` is how the strapdown attitude (sensor → gyroscope frame) is carried between
/// corrections: the plain [`UnitQuat`] (the default, [`Estimator::try_new`]) or the
/// [`CompensatedAttitude`] ([`Estimator::try_new_compensated`]: every prediction's rounding
/// error carried, so an f32 filter propagating for long without corrections drifts no more
/// than its f64 counterpart; module docs of [`crate::propagation::compensated_attitude`]).
/// Everything else is the same filter.
#[derive(Clone, Copy, Debug)]
pub struct Estimator<T, A = UnitQuat<T>> {
    params: Params<T>,
    initialized: bool,
    /// Sensor → gyroscope frame (almost inertial): the bias-corrected strapdown attitude.
    q_gyro: A,
    /// Gyroscope frame → earth (ENU): the accumulated corrections.
    q_corr: UnitQuat<T>,
    bias: Vec3<T>,
    /// The previous gyroscope sample (clipped), for the mean rate over a step.
    last_gyro: Vec3<T>,
    /// The rate (bias removed) the output is carried forward with ([`Params::gyro_delay`]);
    /// zero until the first propagation (the initial attitude is that of its own sample).
    lead_rate: Vec3<T>,
    /// Whether the rates given are means over the step (increments) rather than samples.
    rate_is_mean: bool,
    /// Whether `last_gyro` was saturated (clipped).
    last_saturated: bool,
    p: Covariance<T>,
    accel_lp: LowPass<T>,
    /// Time (s) the accelerometer's low-pass has averaged since it started (0: only its
    /// starting sample); below `accel_time_constant` it holds the running mean
    /// ([`LowPass::mean_update`]).
    accel_warm: T,
    /// Whether the inclination is still taken in full from the low-pass's running mean: from
    /// initialisation until the low-pass has averaged `accel_time_constant` (see
    /// [`Estimator::accel_update`]).
    tilt_from_mean: bool,
    rest: RestDetector<T>,
    field: FieldMonitor<T>,
    field_started: bool,
    last: Outcome,
    /// The strapdown attitude `q_g` (sensor → gyroscope frame) on a time grid of step
    /// [`MAG_HISTORY_STEP`]: `history[head]` at the newest grid time `g₀ ≤ t`, the slot before
    /// it at `g₀ − h`, and so on (a ring).
    history: [UnitQuat<T>; MAG_HISTORY],
    head: usize,
    /// How many grid attitudes `history` holds (up to [`MAG_HISTORY`]).
    filled: usize,
    /// `t − g₀`, s: how long ago the newest grid attitude was, in `[0, h)`.
    grid_age: T,
    /// The estimated magnetometer delay, s.
    lag: T,
    /// Per candidate delay `k·h`: the mean field in the gyroscope frame and the mean squared
    /// sine of its heading deviation from that mean.
    lag_mean: [Vec3<T>; MAG_HISTORY],
    lag_residual: [T; MAG_HISTORY],
    /// Time (s) the delay statistics have been fed.
    lag_time: T,
    /// Time (s) since the delay statistics were last offered a sample.
    lag_clock: T,
    /// The online hard-iron fit and the offset subtracted from the field samples.
    hard_iron: HardIron<T>,
    /// The converged offset large enough to use (zero otherwise), updated as the fit is fed.
    hard_iron_offer: Vec3<T>,
    hard_iron_applied: Vec3<T>,
    /// Time (s) since the hard-iron fit was last fed.
    hard_iron_clock: T,
    /// Time (s) since the last magnetometer sample that reached the heading update (the
    /// initialising sample, or initialisation without one), excluding the current row; at
    /// most [`MAG_INTERVAL_MAX`]. In the light mode: from that sample's row to the last
    /// correction. See [`Estimator::update`] for the magnetometer's interval.
    mag_clock: T,
    /// Set by a saturated gyroscope sample: the rotation since the low-pass was fed is unknown,
    /// so its gyroscope-frame average mixes frames; it restarts from the next usable sample.
    lowpass_stale: bool,
    /// The light mode's accumulators ([`Mode::Light`]).
    light: light::LightState<T>,
    /// The bias before the current rest's updates (`None` when not at rest).
    rest_bias: Option<Vec3<T>>,
    /// How long (s) the current rest has lasted ([`Self::rest_ended`]).
    rest_time: T,
    /// The 4th-order rate rules' window ([`RateRule`]): the last rate samples
    /// (clipped) and their intervals.
    window: RateWindow<T>,
}

/// The step `h` (s) of the time grid on which the strapdown attitude is kept for the
/// magnetometer's delay, and the spacing of the candidate delays of its online estimate.
pub const MAG_HISTORY_STEP: f64 = 0.01;

/// The number of grid attitudes kept: delays from 0 to `(MAG_HISTORY − 1)·h` =
/// [`MAG_DELAY_MAX`] at any sample rate (an attitude between two samples is interpolated).
pub const MAG_HISTORY: usize = 6;

/// The longest magnetometer delay (s) the filter compensates: [`Params::mag_delay`] and the
/// online estimate are clipped to it.
pub const MAG_DELAY_MAX: f64 = MAG_HISTORY_STEP * (MAG_HISTORY - 1) as f64;

/// Time constant (s) of the mean field against which each candidate delay's heading deviation
/// is measured: longer than a sample, shorter than the drift of the gyroscope frame.
const LAG_MEAN_TIME: f64 = 1.0;

/// The delay statistics take a sample at most once per this time (s): averages over seconds
/// need no more, and their cost per update then falls as the rate rises (at 285.7 Hz a sixth
/// of the updates feed them).
const LAG_FEED_STEP: f64 = 0.02;

/// The hard-iron fit takes a sample at most once per this time (s) while turning. Its clock
/// (this feed, its random walk and its statistics' time constants) is the magnetometer's
/// interval, true time whatever the gyroscope's rate, each fed sample standing for the time
/// since the last feed (at most [`MAG_INTERVAL_MAX`]): the fit's physics per second is the same
/// beside a gyroscope of any rate (test `hard_iron_time_is_the_magnetometers`).
const HARD_IRON_FEED_STEP: f64 = 0.02;

/// The longest interval (s) one magnetometer sample stands for in the magnetometer's time
/// scales (the disturbance monitor's times, the hard-iron fit's clock and random walk, the rest
/// detector's field low-pass, the delay statistics, the heading measurement's variance): a
/// sample after a longer gap (no samples, or rejected ones) counts for this long, since the
/// field during the gap was not seen. 0.25 s: a magnetometer at 4 Hz or faster (consumer parts
/// run at 8–100 Hz) is taken at its own interval, and the disturbance monitor's
/// `field.min_undisturbed` (0.5 s by default) still takes two samples after a gap.
pub const MAG_INTERVAL_MAX: f64 = 0.25;

/// The longest step [`Estimator::update`] takes, s: a longer gap is an error (restart the
/// estimator after it).
pub const MAX_STEP: f64 = 1000.0;

/// The attitude uncertainty (rad, per axis) of one step beyond which the step's rotation counts
/// as unknown (the accelerometer low-pass and the attitude history restart).
const STEP_UNCERTAINTY: f64 = 0.1;

/// The variance (rad²) of a heading known to be anywhere: uniform over ±π, `π²/3`.
const UNKNOWN_HEADING_VARIANCE: f64 = core::f64::consts::PI * core::f64::consts::PI / 3.0;

/// The earth's gravity used for the accelerometer gate, m/s².
const GRAVITY: f64 = 9.81;

/// The range of a sample's largest component `m` within which its `|v|²` (between `m²` and
/// `3m²`) is finite and not zero in f32 and f64: `2⁻⁶⁰ ≤ m ≤ 2⁶⁰` (`Estimator::check`).
const NORM_CHECK_MIN: f64 = 1.0 / NORM_CHECK_MAX;
/// See [`NORM_CHECK_MIN`].
const NORM_CHECK_MAX: f64 = (1u64 << 60) as f64;

/// One sample `a_gyro` of the accelerometer low-pass's first `accel_time_constant`, `warm` the
/// time it has averaged so far (0: only its starting sample): the running mean of the samples
/// ([`LowPass::mean_update`]), the starting sample counting as one step of this length `dt`.
/// Both modes.
fn accel_mean_update<T: Real>(
    lp: &mut LowPass<T>,
    warm: &mut T,
    a_gyro: Vec3<T>,
    dt: T,
) -> Vec3<T> {
    let prior = if *warm > T::ZERO { *warm } else { dt };
    *warm = prior + dt;
    lp.mean_update(a_gyro, dt / *warm)
}

impl<T: Real> Estimator<T> {
    /// An estimator with these parameters, waiting for its first sample; the strapdown
    /// attitude a plain [`UnitQuat`].
    ///
    /// # Errors
    /// Those of [`Params::validate`]: [`Error::NonFinite`] when a noise, time or threshold is
    /// NaN or infinite (infinite ranges are allowed); [`Error::InvalidArgument`] when one is
    /// negative or a time constant that divides is zero.
    pub fn try_new(params: Params<T>) -> Result<Self, Error> {
        Self::try_new_carried(params)
    }
}

impl<T: Real> Estimator<T, CompensatedAttitude<T>> {
    /// [`Estimator::try_new`] with the strapdown attitude carried compensated
    /// ([`CompensatedAttitude`]: the prediction's rounding error kept in a low part; twice
    /// the attitude's memory and the compensated update's instructions, BENCHMARKS.md).
    ///
    /// # Errors
    /// Those of [`Estimator::try_new`].
    pub fn try_new_compensated(params: Params<T>) -> Result<Self, Error> {
        Self::try_new_carried(params)
    }
}

impl<T: Real, A: PropagatedAttitude<T>> Estimator<T, A> {
    /// An estimator whose strapdown attitude is carried as `A`.
    fn try_new_carried(params: Params<T>) -> Result<Self, Error> {
        params.validate()?;
        let b0 = params.gyro_bias_initial;
        Ok(Self {
            params,
            initialized: false,
            q_gyro: A::from_unit(UnitQuat::IDENTITY),
            q_corr: UnitQuat::IDENTITY,
            bias: Vec3::ZERO,
            last_gyro: Vec3::ZERO,
            lead_rate: Vec3::ZERO,
            rate_is_mean: false,
            last_saturated: false,
            window: RateWindow::default(),
            p: Covariance::diagonal(T::ZERO, b0 * b0),
            accel_lp: LowPass::default(),
            accel_warm: T::ZERO,
            tilt_from_mean: false,
            rest: RestDetector::default(),
            field: FieldMonitor::default(),
            field_started: false,
            last: Outcome::default(),
            history: [UnitQuat::IDENTITY; MAG_HISTORY],
            head: 0,
            filled: 0,
            grid_age: T::ZERO,
            lag: T::ZERO,
            lag_mean: [Vec3::ZERO; MAG_HISTORY],
            lag_residual: [T::ZERO; MAG_HISTORY],
            lag_time: T::ZERO,
            lag_clock: T::ZERO,
            hard_iron: HardIron::default(),
            hard_iron_offer: Vec3::ZERO,
            hard_iron_applied: Vec3::ZERO,
            hard_iron_clock: T::ZERO,
            mag_clock: T::ZERO,
            lowpass_stale: false,
            light: light::LightState::default(),
            rest_bias: None,
            rest_time: T::ZERO,
        })
    }

    /// The parameters.
    pub fn params(&self) -> &Params<T> {
        &self.params
    }

    /// One 6D update (no magnetometer): body rate `gyro` (rad/s, sensor frame), specific force
    /// `accel` (m/s², sensor frame), `dt` (s) since the previous sample.
    ///
    /// # Errors
    /// See [`Estimator::update`].
    pub fn update_6d(&mut self, gyro: Vec3<T>, accel: Vec3<T>, dt: T) -> Result<Outcome, Error> {
        self.update(gyro, accel, None, dt)
    }

    /// One 9D update: [`Estimator::update_6d`] plus the magnetic field `mag` (any unit, sensor
    /// frame).
    ///
    /// # Errors
    /// See [`Estimator::update`].
    pub fn update_9d(
        &mut self,
        gyro: Vec3<T>,
        accel: Vec3<T>,
        mag: Vec3<T>,
        dt: T,
    ) -> Result<Outcome, Error> {
        self.update(gyro, accel, Some(mag), dt)
    }

    /// One update from a gyroscope increment `dtheta` (rad, the integral of the body rate over
    /// the sample interval `dt`) instead of a rate: the rate `dtheta/dt` is the mean over the
    /// step as it is (no trapezoid with the previous sample), and the attitude takes the
    /// one-plus-previous coning rule `θₖ + (1/12) θₖ₋₁ × θₖ` of [`crate::propagation::coning`]
    /// on the bias-corrected increments (not after a saturated sample). Unlike a rate sample, an
    /// increment needs its interval even on the first sample (to form the rate the rest
    /// detector starts from).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a `dt` that is not finite and positive; otherwise see
    /// [`Estimator::update`].
    pub fn update_increment(
        &mut self,
        dtheta: Vec3<T>,
        accel: Vec3<T>,
        mag: Option<Vec3<T>>,
        dt: T,
    ) -> Result<Outcome, Error> {
        if !(dt.is_finite() && dt > T::ZERO) {
            return Err(Error::InvalidArgument);
        }
        self.rate_is_mean = true;
        // Means over steps are no samples to interpolate: the rate rule's window restarts.
        self.window.restart();
        let r = self.update(dtheta.scale(T::ONE / dt), accel, mag, dt);
        self.rate_is_mean = false;
        r
    }

    /// One update: propagation by the gyroscope, then the corrections.
    ///
    /// **The first-sample rule.** The first sample with a usable accelerometer initialises the
    /// attitude (from the magnetometer too, when given: [`super::init`]) and does not
    /// propagate; neither do the samples before it (no attitude yet). Until the estimator is
    /// initialised ([`Estimator::is_initialized`]) `dt` is therefore neither used nor
    /// checked: the first sample of a log, which has no previous time stamp, may be given any
    /// value (NaN included), and a log that starts while the sensor turns fast is accepted.
    /// From the sample after the initialising one on, `dt` is the time since the previous
    /// sample and is checked as below.
    ///
    /// **The magnetometer's interval.** `mag` may be `None` on rows without a new field
    /// sample (a magnetometer slower than the gyroscope). Every magnetometer time scale runs on
    /// the magnetometer's own interval: the time since the previous field sample that reached
    /// the heading update (in the light mode: that was taken to a correction), or since
    /// initialisation for the first one, at most [`MAG_INTERVAL_MAX`]. An absent sample and a
    /// rejected one (not finite, saturated, zero) add their rows' time to the next sample's
    /// interval, within that bound.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite gyroscope component; once initialised,
    /// [`Error::InvalidArgument`] for a `dt` that is not finite and positive or longer than
    /// [`MAX_STEP`] and [`Error::StepTooLong`] when the (clipped) rate turns by more than half a
    /// turn in `dt`. The sample is then ignored and the state is unchanged. A bad accelerometer
    /// or magnetometer sample is not an error: the propagation goes on and the [`Outcome`]
    /// says why the correction was skipped.
    pub fn update(
        &mut self,
        gyro: Vec3<T>,
        accel: Vec3<T>,
        mag: Option<Vec3<T>>,
        dt: T,
    ) -> Result<Outcome, Error> {
        if self.initialized && !(dt.is_finite() && dt > T::ZERO && dt <= T::from_f64(MAX_STEP)) {
            return Err(Error::InvalidArgument);
        }
        let gyro = gyro.try_finite()?;
        let mut out = Outcome::default();
        // The sensor layer's clip policy at the gyroscope's range: each clipped axis saturated
        // at ±range (`ClipPolicy::Saturate`; the range was checked with the parameters).
        let (gyro, clipped) =
            ClipLimit::new_unchecked(self.params.gyro_range).saturate(gyro.to_array());
        out.gyro_saturated = clipped.any();
        let gyro = Vec3::from_array(gyro);
        // More than half a turn in one step: no step of any method is valid there (the shared
        // `step_limit::MAX_STEP_ANGLE`); an overflowing square fails too.
        // (The light mode knows from the last step of the same length when no clipped rate can.)
        if self.initialized
            && !self.light.step_within_limit(dt)
            && !within_step_limit_real(gyro.scale(dt))
        {
            return Err(Error::StepTooLong);
        }
        let accel_use = self.check(accel, self.params.accel_range);
        let mag_use = match mag {
            Some(m) => self.check(m, T::from_f64(f64::INFINITY)),
            None => SensorUse::Absent,
        };

        if !self.initialized {
            if accel_use != SensorUse::Used {
                out.accel = accel_use;
                out.mag = mag_use;
                self.last = out;
                return Ok(out);
            }
            self.initialize(gyro, accel, mag.filter(|_| mag_use == SensorUse::Used));
            out.initialized = true;
            out.accel = SensorUse::Used;
            out.mag = mag_use;
            self.last = out;
            return Ok(out);
        }

        // The 4th-order rule on rate samples (`RateRule`; increments take the mean rate below).
        let fourth = if self.rate_is_mean {
            None
        } else {
            self.params.rate_rule.method()
        };
        // The mean rate over the step: the trapezoid of the two samples at its ends (an
        // increment's rate is that mean already, and the previous increment is the coning
        // lever of its step, unless either was saturated).
        let mean_rate = if fourth.is_some() {
            gyro
        } else if self.rate_is_mean {
            if !out.gyro_saturated && !self.last_saturated {
                self.coned_rate(gyro, dt)
            } else {
                gyro
            }
        } else {
            // Halved before the sum: two finite samples near the type's limit stay finite. A
            // trapezoid turning by more than half a turn (a huge previous sample over a tiny
            // step, then an ordinary step) is no mean of this step: the sample alone is used.
            // A saturated sample at either end is no rate to average with.
            let m = gyro.scale(T::HALF) + self.last_gyro.scale(T::HALF);
            if !out.gyro_saturated && !self.last_saturated && within_step_limit_real(m.scale(dt)) {
                m
            } else {
                gyro
            }
        };
        // The light mode carries the output at the last rate alone: the slope's division per
        // sample is most of a correction's saving on a soft-float core (M0 light 9D 39 836 →
        // 41 033 instructions with it), and it gains the light mode nothing on BROAD.
        self.lead_rate = if self.params.mode == Mode::Full {
            self.lead_rate(gyro, dt, out.gyro_saturated)
        } else {
            gyro - self.bias
        };
        self.last_gyro = gyro;
        self.last_saturated = out.gyro_saturated;
        if let Mode::Light { correction_period } = self.params.mode {
            let (step, theta2) = match fourth {
                Some(RateMethod::Magnus4) => {
                    self.window.push(gyro, dt, out.gyro_saturated);
                    let (phi, n2) = self.window.magnus4_cached(self.lead_rate, dt);
                    (StepRotation::single(phi), n2)
                }
                other => {
                    let step = match other {
                        Some(method) => {
                            self.fourth_order_step(method, gyro, dt, out.gyro_saturated)
                        }
                        None => StepRotation::at_rate(mean_rate - self.bias, dt),
                    };
                    (step, step.total().norm_squared())
                }
            };
            return Ok(self.update_light(
                (step, theta2),
                mean_rate,
                gyro,
                accel,
                mag,
                (accel_use, mag_use),
                out,
                dt,
                correction_period,
            ));
        }
        let step = match fourth {
            Some(method) => self.fourth_order_step(method, gyro, dt, out.gyro_saturated),
            None => StepRotation::at_rate(mean_rate - self.bias, dt),
        };
        self.predict(step, dt, out.gyro_saturated);
        let mut x = [T::ZERO; 6];

        if accel_use == SensorUse::Used {
            out.at_rest = self.rest.update(gyro, accel, dt, &self.params.rest);
            self.rest_correction(out.at_rest, dt, &mut x);
            out.accel = self.accel_update(accel, dt, &mut x);
        } else {
            out.accel = accel_use;
        }
        self.inject(&x);

        // The magnetometer's time scales run on its own interval: the time since the previous
        // sample that reached the heading update (a magnetometer slower than the gyroscope
        // leaves rows without a sample).
        out.mag = match (mag, mag_use) {
            (Some(m), SensorUse::Used) => {
                let mag_dt = (self.mag_clock + dt).min(T::from_f64(MAG_INTERVAL_MAX));
                self.mag_clock = T::ZERO;
                let u = self.mag_update(m, gyro, mag_dt);
                if u == SensorUse::Used {
                    let pr = &self.params;
                    self.rest.update_field(m, mag_dt, pr.field.dip, &pr.rest);
                }
                u
            }
            (_, u) => {
                self.mag_clock = (self.mag_clock + dt).min(T::from_f64(MAG_INTERVAL_MAX));
                u
            }
        };
        self.last = out;
        Ok(out)
    }

    /// How a sample `v` with the full scale `range` can be used: not finite, saturated (a
    /// component at the range, or `|v|²` overflowing), zero (`|v|² = 0`, underflow included),
    /// or used. With `m = max|vᵢ|`, `m² ≤ |v|² ≤ 3m²`: for `2⁻⁶⁰ ≤ m ≤ 2⁶⁰` the square is
    /// finite and not zero in f32 and f64 (2⁻¹²⁰ is above f32's smallest normal 2⁻¹²⁶,
    /// 3·2¹²⁰ below its largest), so it is formed only outside that range (a soft-float core
    /// saves its three products and two sums on every sample).
    fn check(&self, v: Vec3<T>, range: T) -> SensorUse {
        if !v.is_finite() {
            return SensorUse::NonFinite;
        }
        let m = v.max_abs();
        if m >= range {
            return SensorUse::Saturated;
        }
        if m >= T::from_f64(NORM_CHECK_MIN) && m <= T::from_f64(NORM_CHECK_MAX) {
            return SensorUse::Used;
        }
        if !v.norm_squared().is_finite() {
            SensorUse::Saturated
        } else if v.norm_squared() == T::ZERO {
            SensorUse::Zero
        } else {
            SensorUse::Used
        }
    }

    fn initialize(&mut self, gyro: Vec3<T>, accel: Vec3<T>, mag: Option<Vec3<T>>) {
        let q = match mag {
            Some(m) => {
                attitude_from_gravity_and_field(accel, m).or_else(|_| attitude_from_gravity(accel))
            }
            None => attitude_from_gravity(accel),
        };
        let q = q.unwrap_or(UnitQuat::IDENTITY);
        self.q_gyro = A::from_unit(q);
        self.q_corr = UnitQuat::IDENTITY;
        self.accel_lp = LowPass::at(q.rotate(accel));
        self.accel_warm = T::ZERO;
        self.tilt_from_mean = self.params.accel_time_constant > T::ZERO;
        self.rest = RestDetector::new(gyro, accel);
        self.mag_clock = T::ZERO;
        self.last_gyro = gyro;
        self.window.start(gyro);
        self.lead_rate = Vec3::ZERO;
        // The first sample's direction errors: the inclination from one accelerometer sample
        // and (with a magnetometer) the heading from one field sample.
        let s_tilt = self.params.accel_tilt_noise;
        let s_head = self.params.mag_heading_noise;
        let b0 = self.params.gyro_bias_initial;
        let mut p = Covariance::diagonal(s_tilt * s_tilt, b0 * b0);
        p.attitude.m[2][2] = s_head * s_head;
        self.p = p;
        if let Some(m) = mag {
            let (norm, dip, _) = norm_dip(q.rotate(m));
            self.field = FieldMonitor::new(norm, dip);
            self.field_started = true;
        }
        self.initialized = true;
    }

    /// The step's rotation by a 4th-order rule: the sample `gyro` into the window, the rule's
    /// rotation vector(s) from it ([`RateWindow::rotation`]).
    // Out of line, as `coned_rate`: only the full mode's 4th-order rules and the light mode's
    // CF4 take it.
    #[inline(never)]
    fn fourth_order_step(
        &mut self,
        method: RateMethod,
        gyro: Vec3<T>,
        dt: T,
        saturated: bool,
    ) -> StepRotation<T> {
        self.window.push(gyro, dt, saturated);
        self.window.rotation(method, gyro, self.bias, dt)
    }

    /// The mean rate of an increment's step with the previous increment's coning correction:
    /// the one-plus-previous rule of [`crate::propagation::coning`],
    /// `φ = θₖ + (1/12) θₖ₋₁ × θₖ` on the bias-corrected increments (`θₖ₋₁` the previous
    /// sample's rate over this step: the previous increment for equal intervals), as the rate
    /// `φ/Δt + b` that the prediction's `q ⊗ exp((ω − b)·Δt)` turns by `φ`.
    // Out of line: only increments take it, and inlined into `update` it cost the rate path 4
    // instructions per update on a Cortex-M4F (measured with `fw_icount_estimation`).
    #[inline(never)]
    fn coned_rate(&self, increment_rate: Vec3<T>, dt: T) -> Vec3<T> {
        let b = self.bias;
        let terms = one_plus_previous_terms(
            (self.last_gyro - b).scale(dt),
            (increment_rate - b).scale(dt),
        );
        terms.rotation_vector().scale(T::ONE / dt) + b
    }

    /// The mean rate (bias removed) over the output's lead `d` = [`Params::gyro_delay`]
    /// after the last sample: the rate extrapolated to `d/2` by the last two samples,
    /// `ω + (ω − ω_prev)·d/(2Δt)` (the lead's rotation `∫ω = ω·d + ω̇·d²/2` to second
    /// order). The factor `d/(2Δt)` is at most 1 (steps shorter than half the lead would
    /// amplify the samples' noise); a saturated sample at either end, or an extrapolation
    /// that is not finite, gives the last rate alone.
    fn lead_rate(&self, gyro: Vec3<T>, dt: T, saturated: bool) -> Vec3<T> {
        let w = gyro - self.bias;
        if saturated || self.last_saturated {
            return w;
        }
        let factor = (self.params.gyro_delay * T::HALF / dt).min(T::ONE);
        let lead = w + (gyro - self.last_gyro).scale(factor);
        if lead.is_finite() { lead } else { w }
    }

    fn predict(&mut self, step: StepRotation<T>, dt: T, saturated: bool) {
        let before = self.q_gyro.attitude();
        self.q_gyro = step.apply(self.q_gyro);
        self.advance_grid(before, dt);
        let r = self.attitude_enu().to_rotation_matrix();
        let f = r.scale(-dt);
        let pr = &self.params;
        // The rate-proportional noise `(s·|ω|)²·Δt = θ²·s²/Δt` with `θ = |ω|·Δt` the step's
        // rotation (at most π, checked by `update`): formed from `θ`, not from `|ω|`, which
        // can overflow where `θ` is small, and bounded by `θ²` (an error as large as the
        // rotation itself, a scale factor wrong by 100 %), which only binds for `Δt < s²`.
        let theta2 = step.total().norm_squared();
        let s2 = pr.gyro_scale_noise * pr.gyro_scale_noise;
        let q_scale = theta2 * (s2 / dt).min(T::ONE);
        let q_theta = pr.gyro_noise_density * pr.gyro_noise_density * dt + q_scale;
        let q_bias = pr.gyro_bias_stability * pr.gyro_bias_stability * dt / pr.gyro_bias_time;
        let trace =
            |p: &Covariance<T>| p.attitude.m[0][0] + p.attitude.m[1][1] + p.attitude.m[2][2];
        let before = trace(&self.p);
        self.p.predict(f, q_theta, q_bias);
        if saturated {
            // The true rate is somewhere beyond the range: up to a range's worth of rotation
            // per step (at most a half turn) is unknown.
            let a = (pr.gyro_range * dt).min(T::PI);
            self.p.inflate_attitude(a * a);
        }
        // A step whose own attitude uncertainty exceeds (0.1 rad)² per axis (a saturated
        // sample, a long gap with an uncertain bias) turned the sensor by an unknown rotation:
        // the gyroscope-frame low-pass of the specific force and the attitudes kept for the
        // magnetometer's delay span it, so the low-pass restarts at the next usable sample and
        // the history refills before it is used (or feeds the delay estimate) again.
        let added = trace(&self.p) - before;
        let limit = T::from_f64(3.0 * STEP_UNCERTAINTY * STEP_UNCERTAINTY);
        if saturated || !added.is_finite() || added > limit {
            self.lowpass_stale = true;
            self.filled = 0;
        }
        self.p.bound(T::PI * T::PI, self.bias_variance_max());
    }

    /// The largest bias variance: the bias is clipped to [`Params::gyro_bias_max`], so its
    /// uncertainty is at most that squared (or the initial variance, when that is larger).
    fn bias_variance_max(&self) -> T {
        let pr = &self.params;
        let m = pr.gyro_bias_max * pr.gyro_bias_max;
        let b0 = pr.gyro_bias_initial * pr.gyro_bias_initial;
        m.max(b0)
    }

    /// Pushes the strapdown attitudes at the grid times passed in this step (from `before`, at
    /// `t − dt`, to `q_g` now): linear between the two, renormalised, as the exponential map
    /// of a constant rate over the step would place them to first order.
    fn advance_grid(&mut self, before: UnitQuat<T>, dt: T) {
        let h = T::from_f64(MAG_HISTORY_STEP);
        let mut age = self.grid_age + dt;
        // A step longer than the history: only its last MAG_HISTORY grid times matter.
        let span = h * T::from_f64(MAG_HISTORY as f64);
        if age >= span + h {
            age -= ((age - span) / h).floor() * h;
        }
        let (a, b) = (before.into_quat(), self.q_gyro.attitude().into_quat());
        for _ in 0..=MAG_HISTORY {
            if age < h {
                break;
            }
            age -= h;
            // The grid time t − age lies at the fraction (dt − age)/dt of the step.
            let f = ((dt - age) / dt).max(T::ZERO).min(T::ONE);
            let q = UnitQuat::new_unchecked(a + (b - a).scale(f)).renormalize_fast();
            self.head = (self.head + 1) % MAG_HISTORY;
            if let Some(slot) = self.history.get_mut(self.head) {
                *slot = q;
            }
            self.filled = (self.filled + 1).min(MAG_HISTORY);
        }
        self.grid_age = age.max(T::ZERO).min(h);
    }

    /// The grid attitude `j` steps back (0: the newest), the current attitude when the grid
    /// does not reach that far yet.
    fn grid(&self, j: usize) -> UnitQuat<T> {
        if j >= self.filled {
            return self.q_gyro.attitude();
        }
        let idx = (self.head + MAG_HISTORY - j.min(MAG_HISTORY - 1)) % MAG_HISTORY;
        self.history
            .get(idx)
            .copied()
            .unwrap_or(self.q_gyro.attitude())
    }

    /// The field sample mapped to the gyroscope frame by the attitude `delay` seconds ago
    /// (linear between the two neighbouring attitudes of the grid, or between the newest grid
    /// attitude and now; the oldest kept when the grid is shorter).
    fn field_at(&self, mag: Vec3<T>, delay: T) -> Vec3<T> {
        if let Mode::Light { .. } = self.params.mode {
            return self.light_field(mag);
        }
        if delay <= T::ZERO || self.filled == 0 {
            return self.q_gyro.attitude().rotate(mag);
        }
        let age = self.grid_age;
        if delay <= age {
            let now = self.q_gyro.attitude().rotate(mag);
            let u0 = self.grid(0).rotate(mag);
            return now + (u0 - now).scale(delay / age);
        }
        let h = T::from_f64(MAG_HISTORY_STEP);
        let x = (delay - age) / h;
        let j = x.floor();
        let frac = x - j;
        let last = self.filled - 1;
        // back = j as an index (counted in T: no integer-float conversion on the hot path).
        let mut back = 0usize;
        let mut mid = T::HALF;
        while back < last && mid < j {
            back += 1;
            mid += T::ONE;
        }
        let a = self.grid(back).rotate(mag);
        if back < last && frac > T::ZERO {
            let b = self.grid(back + 1).rotate(mag);
            a + (b - a).scale(frac)
        } else {
            a
        }
    }

    /// At rest, the rest update (`dt` the step the bias was last propagated over); after a
    /// rest that the specific force or the field showed to be a slow turn
    /// ([`RestDetector::turning`]) and that the gyroscope saw as one, what it taught undone:
    /// the bias back to its value before that rest, its variance widened by the change the
    /// rest made (per axis), and the attitude variances by the turn the attitude missed while
    /// the bias cancelled it.
    ///
    /// The rest's bias change `Δb` (earth frame, `R̂ (b̂ − b_before)`) is the rate of the turn
    /// it cancelled. The detector called the rest a turn when, over the still period it watched
    /// (the rest's duration `T` plus `t_min` before it), the specific force moved by `th_a`
    /// (a tilt of `th_a/g`) or the field's horizontal direction by the field monitor's
    /// direction threshold `th_δ` ([`RestDetector::turned_by_field`]). A turn of the sensor
    /// shows in the gyroscope: relative to the bias before the rest it turned by
    /// `|Δb|·(T + t_min)`, so the rest is undone when that covers at least half the angle of
    /// the check that called it a turn, `|Δb_xy|·(T + t_min) ≥ th_a/(2g)` for the specific
    /// force, `|Δb_z|·(T + t_min) ≥ th_δ/2` for the field. A field that changed while the
    /// sensor stood still (a
    /// magnet passing by) turns the field's horizontal direction as well, but the gyroscope saw
    /// no turn (`Δb` is then the error of the bias before the rest): the rest's bias stands and
    /// the heading keeps its weight against the changing field. The missed turn is `Δb·T`:
    /// the tilt variances are raised by `min(|Δb_xy|² T², (th_a/g)²)` and the heading variance
    /// by `min(Δb_z² T², th_δ²)` (the detector's angles bound it).
    fn rest_correction(&mut self, at_rest: bool, dt: T, x: &mut [T; 6]) {
        if at_rest {
            self.rest_update(dt, x);
        } else if self.rest_bias.is_some() {
            self.rest_ended();
        }
    }

    /// The end of a rest ([`Self::rest_correction`]).
    #[inline(never)]
    fn rest_ended(&mut self) {
        let Some(b) = self.rest_bias.take() else {
            return;
        };
        if !self.rest.turning() {
            return;
        }
        let d = self.bias - b;
        let pr = &self.params;
        let a = pr.rest.accel / T::from_f64(GRAVITY);
        let h = pr.field.dip;
        let rate = self.attitude_enu().rotate(d);
        let (tilt2, heading2) = (rate.x * rate.x + rate.y * rate.y, rate.z * rate.z);
        let watched = self.rest_time + pr.rest.min_duration;
        let (w2, quarter) = (watched * watched, T::from_f64(0.25));
        let seen = if self.rest.turned_by_field() {
            heading2 * w2 >= quarter * h * h
        } else {
            tilt2 * w2 >= quarter * a * a
        };
        if !seen {
            return;
        }
        self.bias = b;
        for (i, di) in d.to_array().into_iter().enumerate() {
            if let Some(row) = self.p.bias.m.get_mut(i)
                && let Some(v) = row.get_mut(i)
            {
                *v += di * di;
            }
        }
        let t2 = self.rest_time * self.rest_time;
        self.p.inflate_attitude((tilt2 * t2).min(a * a));
        self.p.inflate_heading((heading2 * t2).min(h * h));
        self.p.bound(T::PI * T::PI, self.bias_variance_max());
    }

    /// At rest, the mean rate measures the bias: `z = ω̄ − b̂ = δb + noise` (the bias before
    /// the rest kept, see [`Self::rest_correction`]); `dt` the step the current bias was
    /// propagated over, added to the rest's duration.
    fn rest_update(&mut self, dt: T, x: &mut [T; 6]) {
        match self.rest_bias {
            Some(_) => self.rest_time += dt,
            None => {
                self.rest_bias = Some(self.bias);
                self.rest_time = T::ZERO;
            }
        }
        let z = self.rest.mean_rate() - self.bias;
        let s = self.params.rest_bias_noise;
        let r = s * s;
        for (i, zi) in z.to_array().into_iter().enumerate() {
            self.scalar_update(x, i + 3, zi, r);
        }
    }

    fn accel_update(&mut self, accel: Vec3<T>, dt: T, x: &mut [T; 6]) -> SensorUse {
        let (tau_a, reject, gains) = (
            self.params.accel_time_constant,
            self.params.accel_reject,
            self.params.gains,
        );
        // Filter in the gyroscope frame, map to the earth frame by the corrections.
        let a_gyro = self.q_gyro.attitude().rotate(accel);
        if self.lowpass_stale {
            self.restart_accel_lowpass(a_gyro);
        }
        let v = if self.accel_warm < tau_a {
            accel_mean_update(&mut self.accel_lp, &mut self.accel_warm, a_gyro, dt)
        } else {
            let k = if tau_a > T::ZERO {
                LowPass::gain(tau_a, dt)
            } else {
                T::ONE
            };
            self.accel_lp.update(a_gyro, k)
        };
        // What the low-pass filter left of non-gravitational acceleration shows in its norm.
        let g = T::from_f64(GRAVITY);
        let residual = (length(v) - g).abs() / g;
        if residual > reject {
            return SensorUse::Disturbed;
        }
        let v = self.q_corr.rotate(v);
        // The rotation taking v to +z: about (v_y, −v_x, 0) by the angle between v and z.
        let h = horizontal(v);
        let angle = h.atan2(v.z);
        let (ex, ey) = if h > T::ZERO {
            (v.y * angle / h, -v.x * angle / h)
        } else {
            (T::ZERO, T::ZERO)
        };
        if self.tilt_from_the_mean(ex, ey, x) {
            return SensorUse::Used;
        }
        self.persistent_tilt(ex, ey);
        match gains {
            Gains::Kalman => {
                let r = self.tilt_variance(dt);
                self.scalar_update(x, 0, ex, r);
                self.scalar_update(x, 1, ey, r);
            }
            Gains::Fixed { .. } => {
                // The bias from the Kalman update, the attitude in full.
                let r = self.tilt_variance(dt);
                let x0 = *x;
                self.scalar_update(x, 0, ex, r);
                self.scalar_update(x, 1, ey, r);
                x[0] = x0[0] + ex;
                x[1] = x0[1] + ey;
            }
        }
        SensorUse::Used
    }

    /// A tilt disagreement that persists: the inclination innovation `(e_x, e_y)` (earth frame,
    /// of the specific force low-passed over `τ_a`, so a disagreement that shows has lasted) is
    /// beyond three standard deviations of what the filter expects of it,
    /// `|e|² > 9·(P_xx + P_yy + 2σ_a²)`: the attitude is off by more than its variance says (a
    /// tilt learned from a sustained acceleration, which the filter then trusts). Each tilt
    /// variance is raised to at least `e_i²`, so the next updates correct the error at once
    /// instead of at the steady-state gain (about 25 s per e-fold at 20 Hz).
    ///
    /// The heading learned meanwhile is suspect too: it came from the field seen through the
    /// wrong tilt, and a tilt error `ε` turns the field's horizontal direction by up to
    /// `ε·tan δ` (`δ` the reference dip). The heading variance is raised by `|e|²·tan²δ`
    /// (at most [`UNKNOWN_HEADING_VARIANCE`]; nothing without a field reference).
    fn persistent_tilt(&mut self, ex: T, ey: T) {
        let s = self.params.accel_tilt_noise;
        let a = &mut self.p.attitude.m;
        let (pxx, pyy) = (a[0][0], a[1][1]);
        let e2 = ex * ex + ey * ey;
        if e2 > T::from_f64(9.0) * (pxx + pyy + (s + s) * s) {
            a[0][0] = pxx.max(ex * ex);
            a[1][1] = pyy.max(ey * ey);
            let (sn, cs) = self.field.reference().1.sin_cos();
            let (num, den) = (e2 * sn * sn, cs * cs);
            let cap = T::from_f64(UNKNOWN_HEADING_VARIANCE);
            let v = if num < cap * den { num / den } else { cap };
            if v > T::ZERO {
                self.p.inflate_heading(v);
            }
        }
    }

    fn tilt_variance(&self, dt: T) -> T {
        let pr = &self.params;
        let s = pr.accel_tilt_noise;
        s * s * (pr.accel_correlation_time / dt).max(T::ONE)
    }

    /// Restarts the accelerometer's low-pass on `a_gyro` (after a saturated step): no running
    /// mean and no inclination taken from it.
    fn restart_accel_lowpass(&mut self, a_gyro: Vec3<T>) {
        self.accel_lp = LowPass::at(a_gyro);
        self.accel_warm = T::ZERO;
        self.tilt_from_mean = false;
        self.lowpass_stale = false;
    }

    /// The inclination error `(ex, ey)` taken in full into `x` while the low-pass holds the
    /// running mean of its first `accel_time_constant` after initialisation (true then): the
    /// initial inclination came from one sample, whose noise grows as the square root of the
    /// sample rate, and the mean shares that sample's offset with less of its noise. Both
    /// modes.
    fn tilt_from_the_mean(&mut self, ex: T, ey: T, x: &mut [T; 6]) -> bool {
        if !self.tilt_from_mean {
            return false;
        }
        self.tilt_from_mean = self.accel_warm < self.params.accel_time_constant;
        x[0] = ex;
        x[1] = ey;
        true
    }

    /// The hard-iron offset offered to the heading update: the fit's converged offset when it
    /// is larger than the disturbance monitor's norm threshold (`field.norm` of the reference
    /// norm), else zero (module docs of `hard_iron`). Both modes, after each feed of the fit.
    fn hard_iron_offer_now(&self) -> Vec3<T> {
        match self.hard_iron.offset() {
            Some(h) if h.norm() > self.params.field.norm * self.field.reference().0 => h,
            _ => Vec3::ZERO,
        }
    }

    /// The heading update from one field sample, `dt` the magnetometer's interval
    /// ([`Estimator::update`]), also the hard-iron fit's clock ([`HARD_IRON_FEED_STEP`]).
    fn mag_update(&mut self, mag: Vec3<T>, gyro: Vec3<T>, dt: T) -> SensorUse {
        let pr = MagParams::of(&self.params);
        let rate = length(gyro - self.bias);
        // (The light mode feeds the fit on every sample itself: `light.rs`.)
        if pr.mag_hard_iron_time > T::ZERO && self.params.mode == Mode::Full {
            self.hard_iron_clock = (self.hard_iron_clock + dt).min(T::from_f64(MAG_INTERVAL_MAX));
            let turning = rate >= pr.field.new_field_min_rate;
            if self.hard_iron_clock >= T::from_f64(HARD_IRON_FEED_STEP) {
                if turning {
                    self.hard_iron
                        .update(mag, self.hard_iron_clock, pr.mag_hard_iron_time);
                    self.hard_iron_offer = self.hard_iron_offer_now();
                } else {
                    self.hard_iron.idle();
                }
                self.hard_iron_clock = T::ZERO;
            }
        }
        let estimating = pr.mag_delay_estimation_time > T::ZERO;
        let lag = if estimating && self.lag_time >= pr.mag_delay_estimation_time {
            self.lag
        } else {
            pr.mag_delay
        };
        let lag = lag.max(T::ZERO).min(T::from_f64(MAG_DELAY_MAX));
        let mut m = self.q_corr.rotate(self.field_at(mag, lag));
        let (mut norm, mut dip, mut h_field) = norm_dip(m);
        // The offered hard-iron offset is subtracted when the corrected field is closer to
        // the reference (relative norm plus dip) than the raw one.
        self.hard_iron_applied = Vec3::ZERO;
        let h = self.hard_iron_offer;
        if self.field_started && h != Vec3::ZERO {
            let mc = self.q_corr.rotate(self.field_at(mag - h, lag));
            let (nc, dc, hc) = norm_dip(mc);
            if self.field.deviation(nc, dc) < self.field.deviation(norm, dip) {
                (m, norm, dip, h_field) = (mc, nc, dc, hc);
                self.hard_iron_applied = h;
            }
        }
        let mag = mag - self.hard_iron_applied;
        if !self.field_started {
            self.field = FieldMonitor::new(norm, dip);
            self.field_started = true;
        }
        let was_confirmed = self.field.confirmed();
        let disturbed = self.field.update(norm, dip, dt, rate, &pr.field);
        if !was_confirmed && self.field.replaced() {
            // The heading came from a reference the field never agreed with (a disturbed first
            // sample): it may be wrong by any angle, whatever its variance says.
            self.p
                .inflate_heading(T::from_f64(UNKNOWN_HEADING_VARIANCE));
        }
        if estimating {
            self.lag_clock += dt;
            if self.lag_clock >= T::from_f64(LAG_FEED_STEP) {
                if !disturbed && self.filled == MAG_HISTORY && rate >= pr.field.new_field_min_rate {
                    self.estimate_lag(mag, self.lag_clock);
                }
                self.lag_clock = T::ZERO;
            }
        }
        let g = pr.mag_disturbance_weight;
        if disturbed && g <= T::ZERO {
            return SensorUse::Disturbed;
        }
        let h = h_field;
        if h <= T::ZERO {
            return SensorUse::Disturbed;
        }
        let psi = m.x.atan2(m.y);
        let (rn, rd) = self.field.reference();
        let eps = if disturbed {
            g * ((norm - rn).abs() / rn + (dip - rd).abs()) * norm / h
        } else {
            T::ZERO
        };
        let s = pr.mag_heading_noise;
        let var = s * s + eps * eps;
        let r = var * (pr.mag_correlation_time / dt).max(T::ONE);
        let k = match pr.gains {
            Gains::Kalman => self.p.update_heading(-m.z / h, r),
            Gains::Fixed {
                heading_time_constant,
            } => {
                let k = first_order_gain(dt, heading_time_constant) * (s * s / var);
                self.p.update_attitude_axis_only(2, k, r)
            }
        };
        // The heading correction: a turn about the earth vertical only.
        let (sn, cs) = (k * psi * T::HALF).sin_cos();
        let turn = UnitQuat::new_unchecked(Quat::new(cs, T::ZERO, T::ZERO, sn));
        self.q_corr = (turn * self.q_corr).renormalize_fast();
        if disturbed {
            SensorUse::Disturbed
        } else {
            SensorUse::Used
        }
    }

    /// Feeds the delay statistics with one field sample (rotating, undisturbed) standing for
    /// the time `dt` since the last offer ([`LAG_FEED_STEP`]) and, after `τ_d` of them, moves the
    /// delay to their minimum (refined by a parabola).
    ///
    /// Candidate `k` is the delay `k·h`: the field mapped by the attitude at `t − k·h`, linear
    /// between the grid attitudes `k − 1` and `k` at the same fraction `1 − age/h` for every
    /// `k ≥ 1` (the grid is uniform), so each grid attitude rotates the sample once. The heading
    /// deviation is measured about the earth's vertical seen in the gyroscope frame.
    fn estimate_lag(&mut self, mag: Vec3<T>, dt: T) {
        let tau = self.params.mag_delay_estimation_time;
        let k_mean = first_order_gain(dt, T::from_f64(LAG_MEAN_TIME));
        let k_res = first_order_gain(dt, tau);
        let first = self.lag_time <= T::ZERO;
        let h = T::from_f64(MAG_HISTORY_STEP);
        let frac = T::ONE - self.grid_age / h;
        let up = self.q_corr.inverse_rotate(Vec3::Z);
        let now = self.q_gyro.attitude().rotate(mag);
        let mut newer = self.grid(0).rotate(mag);
        for k in 0..MAG_HISTORY {
            let m = if k == 0 {
                now
            } else {
                let older = self.grid(k).rotate(mag);
                let m = newer + (older - newer).scale(frac);
                newer = older;
                m
            };
            let (Some(mean), Some(res)) = (self.lag_mean.get_mut(k), self.lag_residual.get_mut(k))
            else {
                continue;
            };
            if first {
                *mean = m;
            }
            let d = m - *mean;
            let vm = m.dot(up);
            let vn = mean.dot(up);
            let hm = m.norm_squared() - vm * vm;
            let hn = mean.norm_squared() - vn * vn;
            let c = m.cross(*mean).dot(up);
            let e = if hm > T::ZERO && hn > T::ZERO {
                c * c / (hm * hn)
            } else {
                T::ZERO
            };
            *mean += d.scale(k_mean);
            *res += k_res * (e - *res);
        }
        self.lag_time += dt;
        if self.lag_time < tau {
            return;
        }
        // The minimum, refined by the parabola through it and its neighbours.
        let r = &self.lag_residual;
        let mut j = 0usize;
        for (i, v) in r.iter().enumerate() {
            if r.get(j).is_some_and(|best| v < best) {
                j = i;
            }
        }
        let mut lag = T::from_f64(j as f64);
        if let (Some(&a), Some(&b), Some(&c)) = (
            j.checked_sub(1).and_then(|i| r.get(i)),
            r.get(j),
            r.get(j + 1),
        ) {
            let curv = a - b - b + c;
            if curv > T::ZERO {
                let off = (a - c) * T::HALF / curv;
                lag += off.max(-T::HALF).min(T::HALF);
            }
        }
        self.lag = lag * h;
    }

    /// The magnetometer's delay behind the gyroscope in use, s: [`Params::mag_delay`], or, once
    /// estimated ([`Params::mag_delay_estimation_time`]), the estimate; both clipped to
    /// [`MAG_DELAY_MAX`].
    pub fn mag_delay(&self) -> T {
        let d = if self.params.mag_delay_estimation_time > T::ZERO
            && self.lag_time >= self.params.mag_delay_estimation_time
        {
            self.lag
        } else {
            self.params.mag_delay
        };
        d.max(T::ZERO).min(T::from_f64(MAG_DELAY_MAX))
    }

    /// How long (s) the online estimate of the magnetometer's delay has been fed: the time of
    /// rotation faster than `field.new_field_min_rate` in an undisturbed field so far. The
    /// estimate replaces [`Params::mag_delay`] in [`Estimator::mag_delay`] once this reaches
    /// [`Params::mag_delay_estimation_time`] (never when that is 0, nor in the light mode,
    /// which makes no estimate).
    pub fn mag_delay_evidence(&self) -> T {
        self.lag_time
    }

    /// A sequential scalar Kalman update of error-state component `i` with measurement `z`:
    /// the innovation is `z − xᵢ` (the state already accumulated in this update).
    fn scalar_update(&mut self, x: &mut [T; 6], i: usize, z: T, r: T) {
        let i = i.min(5);
        let innovation = z - x[i];
        let k = self.p.update_component(i, r);
        for (xj, kj) in x.iter_mut().zip(k) {
            *xj += kj * innovation;
        }
    }

    /// Moves the accumulated error state into the attitude and bias, and resets it.
    fn inject(&mut self, x: &[T; 6]) {
        let dtheta = Vec3::new(x[0], x[1], x[2]);
        if dtheta.norm_squared() > T::ZERO {
            self.q_corr = (UnitQuat::exp_unchecked(dtheta) * self.q_corr).renormalize_fast();
        }
        let m = self.params.gyro_bias_max;
        let clip = |c: T| c.max(-m).min(m);
        let b = self.bias + Vec3::new(x[3], x[4], x[5]);
        self.bias = Vec3::new(clip(b.x), clip(b.y), clip(b.z));
    }

    fn attitude_enu(&self) -> UnitQuat<T> {
        self.q_corr * self.q_gyro.attitude()
    }

    /// The attitude, sensor → earth, in the frame of [`Params::frame`], at the time of the
    /// motion the last samples describe: the filter's attitude carried forward by
    /// [`Params::gyro_delay`] at the rate extrapolated to the middle of that time (the last
    /// two samples' slope; the light mode: the last rate). The identity before the first
    /// usable sample.
    pub fn attitude(&self) -> UnitQuat<T> {
        let q = self.attitude_enu();
        let d = self.params.gyro_delay;
        let q = if d > T::ZERO && self.initialized {
            q.mul_exp_unchecked(self.lead_rate.scale(d), Normalization::Fast)
        } else {
            q
        };
        match self.params.frame {
            EarthFrame::Enu => q,
            EarthFrame::Ned => {
                // ENU → NED: the half turn about (x + y)/√2.
                let s = T::from_f64(core::f64::consts::FRAC_1_SQRT_2);
                let t = UnitQuat::new_unchecked(Quat::new(T::ZERO, s, s, T::ZERO));
                (t * q).renormalize_fast()
            }
        }
    }

    /// The estimated gyroscope bias, rad/s, sensor frame (subtract it from the rate).
    pub fn bias(&self) -> Vec3<T> {
        self.bias
    }

    /// The error covariance: attitude (earth frame, ENU axes, rad²), bias (rad²/s²).
    pub fn covariance(&self) -> &Covariance<T> {
        &self.p
    }

    /// The standard deviations (rad) of the heading error (about the earth vertical) and of the
    /// inclination error (the root sum of the two horizontal axes' variances).
    pub fn attitude_std(&self) -> (T, T) {
        let a = &self.p.attitude.m;
        let h = a[2][2].max(T::ZERO).sqrt();
        let i = (a[0][0] + a[1][1]).max(T::ZERO).sqrt();
        (h, i)
    }

    /// Whether the attitude has been initialised.
    pub fn is_initialized(&self) -> bool {
        self.initialized
    }

    /// The last update's report.
    pub fn last_outcome(&self) -> Outcome {
        self.last
    }

    /// The hard-iron offset subtracted from the last field sample (input units, sensor frame;
    /// zero when none was, [`Params::mag_hard_iron_time`]), and the online fit.
    pub fn hard_iron(&self) -> (Vec3<T>, HardIron<T>) {
        (self.hard_iron_applied, self.hard_iron)
    }

    /// Whether the heading rests on a confirmed magnetic reference
    /// ([`FieldMonitor::confirmed`]): `false` in 6D, before a field was seen, and while the
    /// reference is still the one learned from the first field sample without the field having
    /// agreed with it since (a first sample taken in a disturbed field gives a wrong heading
    /// and a wrong reference; that heading is not trustworthy until the reference is replaced
    /// by the true field, seen while turning for [`FieldThresholds::new_field_time`]).
    pub fn heading_trusted(&self) -> bool {
        self.field_started && self.field.confirmed()
    }

    /// The magnetic reference (norm in input units, dip in rad), once a field was seen.
    pub fn field_reference(&self) -> Option<(T, T)> {
        self.field_started.then(|| self.field.reference())
    }
}

/// The parameters the heading update reads, copied out of [`Params`] (the whole of it is
/// larger than the update needs to copy).
#[derive(Clone, Copy)]
struct MagParams<T> {
    gains: Gains<T>,
    mag_heading_noise: T,
    mag_correlation_time: T,
    mag_delay: T,
    mag_delay_estimation_time: T,
    mag_hard_iron_time: T,
    mag_disturbance_weight: T,
    field: FieldThresholds<T>,
}

impl<T: Copy> MagParams<T> {
    fn of(p: &Params<T>) -> Self {
        Self {
            gains: p.gains,
            mag_heading_noise: p.mag_heading_noise,
            mag_correlation_time: p.mag_correlation_time,
            mag_delay: p.mag_delay,
            mag_delay_estimation_time: p.mag_delay_estimation_time,
            mag_hard_iron_time: p.mag_hard_iron_time,
            mag_disturbance_weight: p.mag_disturbance_weight,
            field: p.field,
        }
    }
}

/// The norm, dip angle (rad, positive below the horizontal) and horizontal magnitude
/// `√(x² + y²)` of an earth-frame (ENU) field (as [`length`] and [`horizontal`]).
fn norm_dip<T: Real>(m: Vec3<T>) -> (T, T, T) {
    let h = horizontal(m);
    (length(m), (-m.z).atan2(h), h)
}

/// `|v| = √(x² + y² + z²)` for the estimator's vectors, whose squares are finite (the checked
/// samples and what is made of them: rotated, low-passed, a bias or offset removed). One square
/// root where [`Vec3::norm`] takes two overflow-safe `hypot`s (libm's f32 `hypot` works in f64:
/// about 400 instructions each on a single-precision FPU, more in soft float); the result
/// differs from it by rounding only. A square that overflows gives `+∞`.
pub(super) fn length<T: Real>(v: Vec3<T>) -> T {
    v.norm_squared().sqrt()
}

/// The horizontal norm `√(x² + y²)` of an earth-frame vector (as [`length`]).
pub(super) fn horizontal<T: Real>(v: Vec3<T>) -> T {
    (v.x * v.x + v.y * v.y).sqrt()
}
