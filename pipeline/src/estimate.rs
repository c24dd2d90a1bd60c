//! The estimator's loop over the samples of a log, once for every face (the `estimate` tool,
//! Python's `gyrostat.estimate`, the BROAD runner of `host-tests`; the C test driver
//! `ffi/tests/c/faces.c` follows the same steps through the C interface).
//!
//! Per sample, in this order ([`Run::push`]):
//! 1. **Bad row**: a non-finite time stamp or gyroscope value is a logger's glitch. Without
//!    [`Options::skip_bad_rows`] it ends the run ([`RowError::NonFinite`]); with it the sample
//!    is [`Step::Skipped`]: the state is unchanged, the clock keeps the last good time stamp, so
//!    the next good sample propagates over the whole interval since the last good one (that step
//!    is checked as any other).
//! 2. **Step**: the library's sample clock ([`SampleClock`]) on the time stamps in the input's
//!    unit. The first time stamp has no step: the estimator is given NaN, which it neither uses
//!    nor checks until its attitude is initialised (the library's first-sample rule,
//!    [`Estimator::update`]), so a log may start while the sensor turns fast. Later steps are
//!    `(t − t_prev) · time_scale` in f64: a time stamp not after the previous one is
//!    [`RowError::NotAfter`], a step longer than [`MAX_STEP`] is [`RowError::TooLong`] (a gap
//!    shorter than that is propagated over, the rate checked against the half-turn limit).
//! 3. **Calibration** ([`Options::calibration`]) in f64, then each value rounded to `T`.
//! 4. **Update**: [`Estimator::update`] (the magnetometer dropped in 6D). A gyroscope value
//!    finite in f64 but not in `T` (f32) is a bad row as in 1.; any other error of the
//!    estimator ends the run ([`RowError::Rejected`]); a value the estimator clips
//!    (`gyro_range`, `accel_range`) or ignores is reported in its [`Outcome`].

use core::fmt::{self, Debug};

use gyrostat::estimation::{Estimator, Gains, MAX_STEP, Outcome, Params, SensorUse};
use gyrostat::propagation::{CompensatedAttitude, PropagatedAttitude};
use gyrostat::sensor::{InertialCalibration, Interval, MagnetometerCalibration, SampleClock};
use gyrostat::{Error, Real, UnitQuat, Vec3};

/// The sensor models applied to every sample before the estimator (f64, after the unit
/// conversion): `corrected = M·diag(s)·(raw − b)` for the gyroscope and the accelerometer,
/// `S·(raw − h)` for the magnetometer (`gyrostat::sensor::calibration`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Calibration {
    /// Gyroscope model.
    pub gyro: InertialCalibration<f64>,
    /// Accelerometer model.
    pub accel: InertialCalibration<f64>,
    /// Magnetometer model.
    pub mag: MagnetometerCalibration<f64>,
}

/// How a run treats its samples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Drop the magnetometer (gyroscope and accelerometer only).
    pub six_d: bool,
    /// A non-finite time stamp or gyroscope value becomes a gap instead of ending the run.
    pub skip_bad_rows: bool,
    /// The time stamps' unit in s (1 for s, 1e-3 for ms, 1e-6 for µs).
    pub time_scale: f64,
    /// The sensor models, when given.
    pub calibration: Option<Calibration>,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            six_d: false,
            skip_bad_rows: false,
            time_scale: 1.0,
            calibration: None,
        }
    }
}

/// One sample: the time stamp in the input's unit, the gyroscope (rad/s), the accelerometer
/// (m/s², specific force) and, when the row has one, the magnetometer (any unit), sensor frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// Time stamp, input unit ([`Options::time_scale`]).
    pub t: f64,
    /// Rate, rad/s.
    pub gyro: [f64; 3],
    /// Specific force, m/s².
    pub accel: [f64; 3],
    /// Field, or `None` for a row without a magnetometer sample.
    pub mag: Option<[f64; 3]>,
}

/// What became of a sample.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Step {
    /// The estimator took it; what it did with each sensor.
    Updated(Outcome),
    /// A bad row turned into a gap ([`Options::skip_bad_rows`]): the state is unchanged.
    Skipped,
}

/// Why a sample ends the run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RowError {
    /// A non-finite time stamp or gyroscope value (in f32: beyond its range).
    NonFinite,
    /// A time stamp not after the previous accepted one (`previous`, input unit).
    NotAfter {
        /// The previous accepted time stamp.
        previous: f64,
    },
    /// A step longer than [`MAX_STEP`] (s).
    TooLong {
        /// The step, s.
        dt: f64,
    },
    /// The estimator rejected the sample.
    Rejected {
        /// Its error.
        error: Error,
        /// The step, s (NaN for the first sample).
        dt: f64,
    },
}

impl RowError {
    /// The reason as the tools print it after `line N: ` (`t_text`: the row's time stamp as
    /// written).
    pub fn message(&self, t_text: &str) -> String {
        match *self {
            RowError::NonFinite => {
                "a non-finite time stamp or gyroscope value (in f32: beyond its range)".into()
            }
            RowError::NotAfter { previous } => {
                format!("time stamp {t_text} is not after the previous row's ({previous})")
            }
            RowError::TooLong { dt } => format!(
                "a step of {dt} s since the previous row: longer than {MAX_STEP} s (restart the estimator after a gap)"
            ),
            RowError::Rejected {
                error: Error::StepTooLong,
                dt,
            } => {
                format!("the rate turns the sensor by more than half a turn in the step of {dt} s")
            }
            RowError::Rejected {
                error: Error::NonFinite,
                ..
            } => "a non-finite gyroscope value (in f32: beyond its range)".into(),
            RowError::Rejected { error, dt } => {
                format!("the estimator rejected the sample (step {dt} s): {error}")
            }
        }
    }
}

/// A failed run: the index of the sample (from 0) and why.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fault {
    /// The sample's index, from 0.
    pub index: usize,
    /// Why.
    pub error: RowError,
}

impl fmt::Display for RowError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RowError::NotAfter { previous } => {
                write!(f, "a time stamp not after the previous row's ({previous})")
            }
            other => write!(f, "{}", other.message("")),
        }
    }
}

impl fmt::Display for Fault {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "sample {}: {}", self.index, self.error)
    }
}

impl std::error::Error for Fault {}

/// The estimator and the state of the loop around it; `A` the estimator's strapdown attitude
/// (plain by default, [`Run::try_new_compensated`] for the compensated one).
pub struct Run<T: Real, A = UnitQuat<T>> {
    filter: Estimator<T, A>,
    clock: SampleClock<f64>,
    options: Options,
    skipped: usize,
}

/// The `heading` column: `ok`, `unsure` or `none` (see the `estimate` tool's help).
pub fn heading_flag<T: Real, A: PropagatedAttitude<T>>(
    filter: &Estimator<T, A>,
    six_d: bool,
) -> &'static str {
    if six_d {
        "none"
    } else if filter.heading_trusted() {
        "ok"
    } else {
        "unsure"
    }
}

impl<T: Real + Debug> Run<T> {
    /// A run with the estimator's parameters and the loop's options.
    ///
    /// # Errors
    /// The estimator's ([`Estimator::try_new`]): a parameter out of its domain.
    pub fn try_new(params: Params<T>, options: Options) -> Result<Self, Error> {
        Self::with_filter(Estimator::try_new(params)?, options)
    }
}

impl<T: Real + Debug> Run<T, CompensatedAttitude<T>> {
    /// [`Run::try_new`] with the estimator's strapdown attitude carried compensated
    /// ([`Estimator::try_new_compensated`]).
    ///
    /// # Errors
    /// As [`Run::try_new`].
    pub fn try_new_compensated(params: Params<T>, options: Options) -> Result<Self, Error> {
        Self::with_filter(Estimator::try_new_compensated(params)?, options)
    }
}

impl<T: Real + Debug, A: PropagatedAttitude<T>> Run<T, A> {
    fn with_filter(filter: Estimator<T, A>, options: Options) -> Result<Self, Error> {
        Ok(Self {
            filter,
            // Every forward step is a `Step` (the longest step is checked after the unit
            // conversion, against MAX_STEP): the clock gives the first-sample rule and the order.
            clock: SampleClock::try_with_gap_factor(f64::MAX, 1.0)?,
            options,
            skipped: 0,
        })
    }

    /// The estimator.
    pub fn estimator(&self) -> &Estimator<T, A> {
        &self.filter
    }

    /// The options.
    pub fn options(&self) -> &Options {
        &self.options
    }

    /// How many samples were skipped as bad rows.
    pub fn skipped(&self) -> usize {
        self.skipped
    }

    /// A bad row (non-finite time stamp or gyroscope value, found by the caller's parser or by
    /// [`Run::push`]): [`Step::Skipped`] under [`Options::skip_bad_rows`], else
    /// [`RowError::NonFinite`].
    ///
    /// # Errors
    /// [`RowError::NonFinite`] without [`Options::skip_bad_rows`].
    pub fn bad_row(&mut self) -> Result<Step, RowError> {
        if self.options.skip_bad_rows {
            self.skipped += 1;
            Ok(Step::Skipped)
        } else {
            Err(RowError::NonFinite)
        }
    }

    /// The step of the time stamp `t` (input unit), s: NaN for the first (see the module docs).
    fn step(&mut self, t: f64) -> Result<f64, RowError> {
        let previous = self.clock.last();
        let scale = self.options.time_scale;
        let restore = |clock: &mut SampleClock<f64>| clock.restart(previous);
        match self.clock.interval(t) {
            Ok(Interval::First) => Ok(f64::NAN),
            Ok(Interval::Step(d) | Interval::Gap(d)) => {
                let dt = d * scale;
                if dt <= 0.0 {
                    restore(&mut self.clock);
                    Err(RowError::NotAfter {
                        previous: previous.unwrap_or(f64::NAN),
                    })
                } else if dt > MAX_STEP {
                    restore(&mut self.clock);
                    Err(RowError::TooLong { dt })
                } else {
                    Ok(dt)
                }
            }
            Ok(Interval::Repeated | Interval::Backwards(_)) => Err(RowError::NotAfter {
                previous: previous.unwrap_or(f64::NAN),
            }),
            // The difference overflowed (both stamps finite): ±∞.
            Err(_) => {
                let p = previous.unwrap_or(f64::NAN);
                if t < p {
                    Err(RowError::NotAfter { previous: p })
                } else {
                    Err(RowError::TooLong {
                        dt: (t - p) * scale,
                    })
                }
            }
        }
    }

    /// One sample through the loop (see the module docs).
    ///
    /// # Errors
    /// A [`RowError`]: the run should stop (the state is that before the sample).
    pub fn push(&mut self, s: &Sample) -> Result<Step, RowError> {
        if !s.t.is_finite() || !s.gyro.iter().all(|g| g.is_finite()) {
            return self.bad_row();
        }
        let previous = self.clock.last();
        let dt = self.step(s.t)?;
        let (gyro, accel, mag) = match &self.options.calibration {
            None => (s.gyro, s.accel, s.mag),
            Some(c) => {
                let v = |a: [f64; 3]| Vec3::new(a[0], a[1], a[2]);
                (
                    c.gyro.apply(v(s.gyro)).to_array(),
                    c.accel.apply(v(s.accel)).to_array(),
                    s.mag.map(|m| c.mag.apply(v(m)).to_array()),
                )
            }
        };
        let v = |a: [f64; 3]| Vec3::new(T::from_f64(a[0]), T::from_f64(a[1]), T::from_f64(a[2]));
        let mag = if self.options.six_d { None } else { mag.map(v) };
        match self.filter.update(v(gyro), v(accel), mag, T::from_f64(dt)) {
            Ok(o) => Ok(Step::Updated(o)),
            Err(e) => {
                self.clock.restart(previous);
                match e {
                    Error::NonFinite => self.bad_row(),
                    error => Err(RowError::Rejected { error, dt }),
                }
            }
        }
    }

    /// The output row of the `estimate` tool after a sample, without the line end:
    /// `t,qw,qx,qy,qz,bx,by,bz,rest,gyro,accel,mag,heading`, `t` as written (`t_text`), the
    /// numbers in the shortest form that round-trips to the same `T`, `nan` before the
    /// attitude is initialised.
    pub fn row_text(&self, t_text: &str, step: &Step) -> String {
        let flags = match step {
            Step::Updated(o) => format!(
                "{},{},{},{}",
                u8::from(o.at_rest),
                if o.gyro_saturated {
                    SensorUse::Saturated
                } else {
                    SensorUse::Used
                }
                .name(),
                o.accel.name(),
                o.mag.name(),
            ),
            Step::Skipped => "0,skipped,skipped,skipped".into(),
        };
        let heading = heading_flag(&self.filter, self.options.six_d);
        if self.filter.is_initialized() {
            let [w, x, y, z] = self.filter.attitude().to_array();
            let [bx, by, bz] = self.filter.bias().to_array();
            format!("{t_text},{w:?},{x:?},{y:?},{z:?},{bx:?},{by:?},{bz:?},{flags},{heading}")
        } else {
            format!("{t_text},nan,nan,nan,nan,nan,nan,nan,{flags},{heading}")
        }
    }
}

/// The header of [`Run::row_text`]'s rows.
pub const HEADER: &str = "t,qw,qx,qy,qz,bx,by,bz,rest,gyro,accel,mag,heading";

/// Sets one estimator parameter from a command line's `NAME=VALUE` (the `estimate` tool's
/// `--set`, the BROAD runner's, the research probes'): every name [`Params::set_by_name`] takes
/// (the field names of [`Params`], `field.norm`, `rest.gyro`, … for the nested ones,
/// `heading_time_constant` for fixed gains, `light_period` for the light mode) with a finite
/// value in SI units, where a value ending in `deg` or `deg/s` is converted to rad or rad/s;
/// `gains=kalman`; and `rate_rule=trapezoid|magnus4|cf4` ([`gyrostat::estimation::RateRule`]). Name and value are trimmed.
///
/// # Errors
/// One line naming the reason: `gains` other than `kalman`, a value that is not a finite
/// number, an unknown name.
pub fn set_param(p: &mut Params<f64>, name: &str, value: &str) -> Result<(), String> {
    let (name, value) = (name.trim(), value.trim());
    if name == "gains" {
        return match value {
            "kalman" => {
                p.gains = Gains::Kalman;
                Ok(())
            }
            _ => Err(format!(
                "gains: only 'kalman' (set heading_time_constant for complementary gains), got '{value}'"
            )),
        };
    }
    if name == "rate_rule" {
        p.rate_rule = value
            .parse()
            .map_err(|_| format!("rate_rule: unknown '{value}' (trapezoid, magnus4, cf4)"))?;
        return Ok(());
    }
    let (number, factor) = match value
        .strip_suffix("deg/s")
        .or_else(|| value.strip_suffix("deg"))
    {
        Some(n) => (n.trim(), core::f64::consts::PI / 180.0),
        None => (value, 1.0),
    };
    let x: f64 = number
        .parse()
        .map_err(|_| format!("{name}: invalid number '{number}'"))?;
    if !x.is_finite() {
        return Err(format!("{name}: not a finite number '{number}'"));
    }
    if p.set_by_name(name, x * factor) {
        Ok(())
    } else {
        Err(format!("unknown parameter '{name}' (see --help)"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A level sensor turning about z at `rate`, sampled at `dt` with a jitter that does not
    /// repeat; the field turns with it.
    fn log(n: usize, dt: f64, rate: f64) -> Vec<Sample> {
        let mut t = 0.0;
        (0..n)
            .map(|k| {
                let a = rate * t;
                let s = Sample {
                    t,
                    gyro: [1e-3 * (k as f64 * 0.7).sin(), 0.0, rate],
                    accel: [0.01 * (k as f64 * 1.3).cos(), 0.0, 9.81],
                    mag: Some([15.8 * a.sin(), 15.8 * a.cos(), -40.7]),
                };
                t += dt * (1.0 + 0.1 * (k as f64 * 0.37).sin());
                s
            })
            .collect()
    }

    fn run<T: Real + Debug>(samples: &[Sample], options: Options) -> Vec<Result<Step, RowError>> {
        let mut r = Run::<T>::try_new(Params::default(), options).unwrap();
        samples.iter().map(|s| r.push(s)).collect()
    }

    fn attitudes(samples: &[Sample], options: Options) -> Vec<[f64; 4]> {
        let mut r = Run::<f64>::try_new(Params::default(), options).unwrap();
        samples
            .iter()
            .map(|s| {
                r.push(s).unwrap();
                r.estimator().attitude().to_array()
            })
            .collect()
    }

    /// The first-sample rule: a log that starts while the sensor turns at 5 rad/s, at 1 Hz
    /// (the first step, had it one, would be 5 rad: beyond half a turn) is accepted.
    #[test]
    fn a_log_may_start_in_motion() {
        let mut s = log(10, 1.0, 0.0);
        s[0].gyro = [0.0, 0.0, 5.0];
        for r in run::<f64>(&s, Options::default()) {
            assert!(matches!(r, Ok(Step::Updated(_))), "{r:?}");
        }
        for r in run::<f32>(&s, Options::default()) {
            assert!(matches!(r, Ok(Step::Updated(_))), "{r:?}");
        }
    }

    /// A skipped bad row is a gap: the run with it skipped equals, bit for bit, the run of the
    /// same log without that row (the next good sample propagates over the whole interval).
    #[test]
    fn a_skipped_row_is_a_gap() {
        let good = log(400, 0.01, 0.3);
        let skip = Options {
            skip_bad_rows: true,
            ..Options::default()
        };
        for bad in [
            Sample {
                gyro: [f64::NAN, 0.0, 0.0],
                ..good[200]
            },
            Sample {
                t: f64::INFINITY,
                ..good[200]
            },
        ] {
            let mut with = good.clone();
            with.insert(201, bad);
            let a = attitudes(&with, skip);
            let b = attitudes(&good, skip);
            assert_eq!(a[..201], b[..201]);
            assert_eq!(a[201], a[200], "the skipped row repeats the state");
            assert_eq!(a[202..], b[201..]);
            let stopped = run::<f64>(&with, Options::default());
            assert_eq!(stopped[201], Err(RowError::NonFinite));
        }
        // f32: a rate finite in f64 but not in f32 is a bad row in f32 only.
        let mut big = good.clone();
        big[300].gyro[2] = 1e39;
        let r = run::<f32>(&big, skip);
        assert_eq!(r[300], Ok(Step::Skipped));
        assert!(matches!(run::<f64>(&big, skip)[300], Ok(Step::Updated(o)) if o.gyro_saturated));
    }

    /// Order and length of the steps: a repeated or earlier time stamp, before and after the
    /// attitude is initialised, and a step over MAX_STEP end the run; a step of MAX_STEP does
    /// not; the time scale applies to the difference.
    #[test]
    fn steps_are_checked() {
        let mut s = log(5, 0.01, 0.0);
        s[1].t = s[0].t;
        assert_eq!(
            run::<f64>(&s, Options::default())[1],
            Err(RowError::NotAfter { previous: s[0].t })
        );
        let mut s = log(5, 0.01, 0.0);
        s[3].t = s[1].t;
        assert!(matches!(
            run::<f64>(&s, Options::default())[3],
            Err(RowError::NotAfter { .. })
        ));
        let mut s = log(3, 0.01, 0.0);
        s[1].t = s[0].t + MAX_STEP;
        s[2].t = s[1].t + MAX_STEP * 1.000_001;
        let r = run::<f64>(&s, Options::default());
        assert!(matches!(r[1], Ok(Step::Updated(_))));
        assert!(matches!(r[2], Err(RowError::TooLong { dt }) if dt > MAX_STEP));
        // Milliseconds: 1.5e6 ms is 1500 s.
        let mut s = log(2, 0.01, 0.0);
        s[1].t = s[0].t + 1.5e6;
        let ms = Options {
            time_scale: 1e-3,
            ..Options::default()
        };
        assert!(matches!(run::<f64>(&s, ms)[1], Err(RowError::TooLong { dt }) if dt == 1500.0));
    }

    /// The `NAME=VALUE` parser of every face: degrees converted, names and values trimmed,
    /// `gains=kalman`, and one-line errors for the rest.
    #[test]
    fn set_param_by_name() {
        let mut p = Params::<f64>::default();
        set_param(&mut p, " gyro_range ", " 1000 deg/s").unwrap();
        let want = 1000.0 * core::f64::consts::PI / 180.0;
        assert!(
            (p.gyro_range - want).abs() <= 1e-15 * want,
            "{}",
            p.gyro_range
        );
        set_param(&mut p, "gyro_range", "3.5").unwrap();
        assert_eq!(p.gyro_range, 3.5);
        set_param(&mut p, "heading_time_constant", "20").unwrap();
        assert!(
            matches!(p.gains, Gains::Fixed { heading_time_constant } if heading_time_constant == 20.0)
        );
        set_param(&mut p, "gains", "kalman").unwrap();
        assert!(matches!(p.gains, Gains::Kalman));
        let before = p;
        for (name, value, error) in [
            (
                "gains",
                "fixed",
                "gains: only 'kalman' (set heading_time_constant for complementary gains), got 'fixed'",
            ),
            ("gyro_range", "fast", "gyro_range: invalid number 'fast'"),
            (
                "gyro_range",
                "inf deg",
                "gyro_range: not a finite number 'inf'",
            ),
            ("gyro_range", "NaN", "gyro_range: not a finite number 'NaN'"),
            ("bogus", "1", "unknown parameter 'bogus' (see --help)"),
        ] {
            assert_eq!(set_param(&mut p, name, value), Err(error.to_string()));
        }
        assert_eq!(p, before);
    }
}
