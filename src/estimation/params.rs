//! The estimator's parameters, declared once.
//!
//! [`estimator_parameters!`](crate::estimator_parameters) is the one table of the numeric
//! parameters: per parameter its documentation (what it is, its unit and convention, how its
//! default follows from a datasheet or a design choice), its flat name, its place in [`Params`]
//! (a field of [`Params`], of [`FieldThresholds`] or of [`RestThresholds`]), its default and its
//! domain ([`Domain`]). Everything else follows from the table: the three structs, their
//! [`Default`], [`Params::NAMES`] and [`Params::FLAT_NAMES`], the accessors by name
//! ([`Params::parameter_mut`], [`Params::set_by_name`]), [`Params::map`] (f64 ↔ f32), the check
//! of [`Params::validate`], the parameter file ([`super::params_text`]) and, in `gyrostat-ffi`,
//! the C structs `gyro_estimator_params_f32/_f64`. Adding a parameter is one row of the table.
//!
//! The choices that are not numbers ([`EarthFrame`], [`Gains`], [`Mode`], [`RateRule`]) are
//! fields of [`Params`] beside the table's.

use core::fmt;
use core::str::FromStr;

use crate::propagation::RateMethod;
use crate::{Error, Real};

/// The table of the estimator's numeric parameters: invokes `$callback! { rows }`, each row
///
/// ```text
/// /// documentation (unit, convention, where the default comes from)
/// flat_name [@ group.field]: default, Domain;
/// ```
///
/// in the order of [`Params::NAMES`](crate::estimation::Params::NAMES) (the order of the
/// parameter file). `flat_name` is a field of
/// [`Params`](crate::estimation::Params), or with `@ field.x` / `@ rest.x` the field `x` of
/// [`FieldThresholds`](crate::estimation::FieldThresholds) /
/// [`RestThresholds`](crate::estimation::RestThresholds), named `field.x` / `rest.x` in the
/// parameter file; the flat name (no dots) is the name in the C structs and the Python keywords.
/// `default` is an `f64` expression in SI units (`deg(x)`: `x` degrees in rad;
/// `STANDARD_GRAVITY`: 9.806 65 m/s²), `Domain` one of
/// [`Domain`](crate::estimation::params::Domain)'s variants.
///
/// The library builds [`Params`](crate::estimation::Params) from it; the C interface
/// (`gyrostat-ffi`) builds its parameter structs from it, so that both follow one declaration.
#[macro_export]
macro_rules! estimator_parameters {
    ($callback:ident) => {
        $callback! {
            /// Gyroscope white noise, rad/s/√Hz (angle random walk). Default: the rate noise
            /// spectral density of a consumer MEMS gyroscope (MPU-9250: 0.01 °/s/√Hz); a
            /// characterisation reads it as the Allan deviation's slope −½ at 1 s.
            gyro_noise_density: deg(0.01), NonNegative;
            /// Rate-proportional gyroscope error, 1/√Hz: scale-factor and axis-misalignment
            /// errors (and timing) turn the estimate by an error proportional to the rate,
            /// modelled as white noise of density `s·|ω|` added to `gyro_noise_density`.
            /// Default: the sensitivity tolerance and cross-axis sensitivity (MPU-9250: ±3 %,
            /// ±2 % raw) after a calibration to 0.2 %, as a density over 1 s.
            gyro_scale_noise: 0.002, NonNegative;
            /// Standard deviation of the gyroscope bias at start, rad/s. Default: the zero-rate
            /// output after a power-on calibration (raw tolerance ±5 °/s).
            gyro_bias_initial: deg(0.5), NonNegative;
            /// How far the bias wanders (rad/s) within `gyro_bias_time`: a random walk of
            /// variance `σ²·Δt/τ` per step. Default: the zero-rate output's temperature drift
            /// (MPU-9250: ±30 °/s over −40…85 °C, 0.24 °/s/K) over the 0.4 K a device warms in
            /// 100 s; an Allan deviation's bias-instability floor is its lower bound.
            gyro_bias_stability: deg(0.1), NonNegative;
            /// The time (s) over which the bias wanders by `gyro_bias_stability` (positive).
            gyro_bias_time: 100.0, Positive;
            /// The largest bias magnitude per axis, rad/s (estimates are clipped to it).
            /// Default: a bound on the calibrated bias.
            gyro_bias_max: deg(2.0), NonNegative;
            /// The gyroscope's full scale, rad/s: a component at or beyond it is saturated
            /// (clipped, its uncertainty added); `+∞` disables the check. Set it to the
            /// sensor's range. Default: the largest range of consumer MEMS gyroscopes
            /// (MPU-9250: ±2000 °/s).
            gyro_range: deg(2000.0), Range;
            /// Delay (s) of the gyroscope's samples behind the motion: the group delay of its
            /// digital low-pass filter and of the sampling chain. The filter integrates the
            /// samples as they come and the output attitude is carried forward by this time at
            /// the rate extrapolated to its middle, `q̂ ⊗ exp(ω̄·d_g)`, `ω̄ = ω − b̂ +
            /// (ω − ω_prev)·min(d_g/(2Δt), 1)` (the light mode: `ω − b̂`, the last rate);
            /// the corrections are unaffected. 0
            /// outputs the attitude of the samples' own time. Default: the digital low-pass
            /// delay at its common setting (MPU-9250: 184 Hz bandwidth, 2.9 ms).
            gyro_delay: 0.0029, NonNegative;
            /// The accelerometer's full scale, m/s²: a component at or beyond it is saturated
            /// (the sample is not used), so that garbage values (1e30 m/s²) are not fed to the
            /// inclination low-pass; `+∞` disables the check. Set it to the sensor's range.
            /// Default: the largest range of consumer MEMS accelerometers (MPU-9250: ±16 g).
            accel_range: 16.0 * STANDARD_GRAVITY, Range;
            /// Time constant (s) of the low-pass filter of the specific force in the
            /// gyroscope's (almost inertial) frame; 0 uses each sample as it is. Default: a
            /// design choice (module docs of `estimation`).
            accel_time_constant: 3.0, NonNegative;
            /// Standard deviation (rad) of the inclination measured from the (filtered)
            /// accelerometer (positive). Default: the zero-g offset after calibration (5 mg ≈
            /// 0.3°); the noise density (300 µg/√Hz) averages out in the low-pass.
            accel_tilt_noise: deg(0.3), Positive;
            /// Correlation time (s) of that error: one independent measurement per this time.
            /// Default: a design choice.
            accel_correlation_time: 1.0, NonNegative;
            /// Largest relative deviation of the low-passed specific force's norm from gravity
            /// (9.81 m/s²) for the inclination update to use it: a larger one is acceleration
            /// that the low-pass filter could not average out (a sustained push). Every sample
            /// still feeds the filter. Default: a design choice.
            accel_reject: 0.2, NonNegative;
            /// Standard deviation (rad) of the heading measured from the magnetometer
            /// (positive). Default: the magnetometer's resolution and noise (AK8963: 0.6 µT)
            /// over a horizontal field of about 17 µT.
            mag_heading_noise: deg(2.0), Positive;
            /// Correlation time (s) of that error. Default: a design choice.
            mag_correlation_time: 5.0, NonNegative;
            /// Delay (s) of the magnetometer behind the gyroscope: its sample is compared with
            /// the attitude that long ago (linear between the two nearest attitudes of the
            /// history, up to `MAG_DELAY_MAX`). Default 0: set it when known, else it is
            /// estimated online (`mag_delay_estimation_time`). The light mode makes no
            /// estimate: it uses a positive value as it is, and without one a fixed default
            /// (`Mode::LIGHT_MAG_DELAY`). A sensor's delay is not a datasheet figure (it is
            /// the magnetometer's conversion and output timing against the gyroscope's
            /// filter); the full mode measures it from a log with rotation (`estimate
            /// --params-out FILE` writes it as a parameter file).
            mag_delay: 0.0, NonNegative;
            /// Averaging time `τ_d` (s of rotation in an undisturbed field) of the online
            /// estimate of the magnetometer's delay; 0 keeps `mag_delay` fixed. A positive
            /// value starts at `mag_delay` and, after `τ_d` of rotation faster than
            /// `field.new_field_min_rate` in an undisturbed field, replaces it by the delay
            /// whose earth-frame field heading deviates least from its recent mean (module docs
            /// of `estimation`). Default: a design choice.
            mag_delay_estimation_time: 10.0, NonNegative;
            /// Random-walk time `τ_h` (s) of the online hard-iron estimate: the offset may
            /// drift by 1 % of the field's norm over `τ_h`; 0 switches the estimate off (the
            /// field is used as it comes). Once the fit has converged an offset larger than
            /// `field.norm` of the field's norm is subtracted from a field sample when the
            /// corrected field is closer to the disturbance monitor's reference than the raw
            /// one. Default: a design choice.
            mag_hard_iron_time: 10.0, NonNegative;
            /// Weight of a disturbed field's heading error: 0 rejects a disturbed field
            /// outright; a positive `g` uses it with the heading variance increased by
            /// `(g·ε·|B|/|B_h|)²`, `ε = ||B| − |B|_ref|/|B|_ref + |δ − δ_ref|` bounding the
            /// relative size of the disturbance. Default: a design choice.
            mag_disturbance_weight: 0.3, NonNegative;
            /// Disturbance monitor, `th_B`: the largest relative change of the field's norm,
            /// `||B| − |B|_ref| / |B|_ref`.
            field_norm @ field.norm: 0.1, NonNegative;
            /// Disturbance monitor, `th_δ` (rad): the largest change of the dip angle.
            field_dip @ field.dip: deg(10.0), NonNegative;
            /// Disturbance monitor, `τ_ref` (s): how slowly the reference follows an
            /// undisturbed field.
            field_reference_time_constant @ field.reference_time_constant: 20.0, NonNegative;
            /// Disturbance monitor, `t_back` (s): how long the field must be back within the
            /// thresholds to count as undisturbed again.
            field_min_undisturbed @ field.min_undisturbed: 0.5, NonNegative;
            /// Disturbance monitor, `t_new` (s): how long a new homogeneous field must be seen
            /// while turning to replace the reference.
            field_new_field_time @ field.new_field_time: 20.0, NonNegative;
            /// Disturbance monitor, `ω_new` (rad/s): the least rate at which that time counts.
            field_new_field_min_rate @ field.new_field_min_rate: deg(20.0), NonNegative;
            /// Rest detector, `τ_rest` (s): the time constant of the means.
            rest_time_constant @ rest.time_constant: 0.5, NonNegative;
            /// Rest detector, `th_ω` (rad/s): the largest deviation of the rate from its mean
            /// at rest.
            rest_gyro @ rest.gyro: deg(2.0), NonNegative;
            /// Rest detector, `th_a` (m/s²): the largest deviation of the specific force from
            /// its mean at rest.
            rest_accel @ rest.accel: 0.5, NonNegative;
            /// Rest detector: the largest mean rate `|ω̄|` (rad/s) taken as a bias; a steadier
            /// turn is motion.
            rest_max_bias @ rest.max_bias: deg(2.0), NonNegative;
            /// Rest detector, `t_min` (s): how long the sensor must be still before it counts
            /// as at rest.
            rest_min_duration @ rest.min_duration: 1.5, NonNegative;
            /// Standard deviation (rad/s) of the mean rate at rest as a bias measurement
            /// (positive).
            rest_bias_noise: deg(0.03), Positive;
        }
    };
}

/// `x` degrees in radians (the table's defaults).
fn deg(x: f64) -> f64 {
    x.to_radians()
}

/// The standard gravity `g₀` (m/s²) of the accelerometer's range in g.
const STANDARD_GRAVITY: f64 = 9.806_65;

/// The values a numeric parameter may take ([`Params::validate`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Domain {
    /// Finite and `≥ 0`.
    NonNegative,
    /// Finite and `> 0` (a noise or time that divides).
    Positive,
    /// `≥ 0`, `+∞` allowed (a sensor's range: `+∞` is none).
    Range,
}

impl Domain {
    /// `true` when `v` is a number this domain calls non-finite: NaN, and ±∞ except a range's.
    fn non_finite<T: Real>(self, v: T) -> bool {
        match self {
            // NaN is the one value not ≤ +∞.
            Domain::Range => v.partial_cmp(&T::from_f64(f64::INFINITY)).is_none(),
            Domain::NonNegative | Domain::Positive => !v.is_finite(),
        }
    }

    /// `true` when `v` (not non-finite) is in the domain.
    fn contains<T: Real>(self, v: T) -> bool {
        match self {
            Domain::NonNegative | Domain::Range => v >= T::ZERO,
            Domain::Positive => v > T::ZERO,
        }
    }
}

/// The earth frame of the output attitude (sensor → earth).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum EarthFrame {
    /// x east, y magnetic north, z up (the default; BROAD's frame).
    #[default]
    Enu,
    /// x magnetic north, y east, z down.
    Ned,
}

impl EarthFrame {
    /// Every frame, in the order of its C constants (`GYRO_FRAME_*`).
    pub const ALL: [EarthFrame; 2] = [EarthFrame::Enu, EarthFrame::Ned];

    /// The name the tools, Python and the parameter file use: `enu` or `ned`.
    pub const fn name(self) -> &'static str {
        match self {
            EarthFrame::Enu => "enu",
            EarthFrame::Ned => "ned",
        }
    }
}

impl FromStr for EarthFrame {
    type Err = Error;
    /// The frame of [`EarthFrame::name`].
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for any other text.
    fn from_str(s: &str) -> Result<Self, Error> {
        Self::ALL
            .into_iter()
            .find(|f| f.name() == s)
            .ok_or(Error::InvalidArgument)
    }
}

impl fmt::Display for EarthFrame {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// How the accelerometer and magnetometer corrections are weighted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Gains<T> {
    /// Kalman gains from the error covariance (the measurement variances below).
    Kalman,
    /// Complementary: the low-passed inclination is applied in full at every sample and the
    /// heading error with the first-order gain `1 − exp(−Δt/τ)`; the bias still from the Kalman
    /// update.
    Fixed {
        /// `τ` (s) of the heading correction.
        heading_time_constant: T,
    },
}

/// How much work an update does (the corrections are the same; see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Mode<T> {
    /// Every part of the filter on every sample.
    #[default]
    Full,
    /// The prediction, the rest detector, the accelerometer's low-pass filter and the
    /// hard-iron fit on every sample; the covariance over the whole interval
    /// (`Φ = [[I, −R̂·T_c], [0, I]]`, `R̂` at its end) and the rest, inclination and heading
    /// updates (variances for one measurement per `T_c`) once per `correction_period` `T_c`
    /// (s, sample time). No magnetometer-delay estimate: the field sample is carried back by a
    /// delay `d` to first order, `m − d·(ω × m)`, `d` = [`Params::mag_delay`] when it is
    /// positive or [`Params::mag_delay_estimation_time`] is 0, else [`Mode::LIGHT_MAG_DELAY`]. Between
    /// corrections the [`Outcome`](super::Outcome) reports a valid magnetometer sample as the
    /// last correction did. Cost and accuracy: BENCHMARKS.md (about a third of the full mode's
    /// cost on the M4F).
    Light {
        /// The time (s) between two corrections.
        correction_period: T,
    },
}

impl<T: Real> Mode<T> {
    /// The default correction period (s) of [`Mode::Light`]: 25 ms (40 Hz).
    pub const LIGHT_PERIOD: f64 = 0.025;

    /// The magnetometer delay `d` (s) the light mode applies when no delay is given
    /// ([`Params::mag_delay`] 0 with an online estimate asked for, the defaults), at every
    /// sample rate: 9.25 ms. **It is fitted to BROAD, not taken from a sensor**: read off
    /// BROAD's trials of half A (01 05 09 14 21 26 30 34: the light mode's mean total over
    /// fixed delays 8–10 ms at 285.7, 142.9, 95.2 and 47.6 Hz, Magnus-4 rate rule). Half B's
    /// best fixed delay is shorter, about 7 ms at 285.7 and 47.6 Hz, and the full mode with a
    /// fixed delay has the same two optima (BENCHMARKS.md, "The light mode's magnetometer
    /// delay from the sensor"). No sensor figure replaces it: the delay is the magnetometer's
    /// conversion and output timing against the gyroscope's filter, which datasheets do not
    /// state as one number (the AK8963's, for one, gives a 100 Hz continuous mode and data
    /// ready at the end of each measurement: a sample is at least half a period, 5 ms, old on
    /// average when read at a higher rate; MS1356-E-02, 2013/10, section 6.4.3, page 15),
    /// and 5 ms loses 0.23° on half A at 285.7 Hz (1.185° → 1.418°). For another sensor set
    /// [`Params::mag_delay`] to its own delay, measured by the full mode (`estimate
    /// --params-out FILE`): on synthetic logs with a known delay the light mode does best
    /// with the true delay (given the gyroscope's true delay, [`Params::gyro_delay`]), with no
    /// offset for the corrections' period or the sample step. The full mode's online
    /// estimates on BROAD are 5.3–14.7 ms at every rate. With [`RateRule::Trapezoid`] the
    /// delay that scores best falls by about a quarter of the sample step: that rule's error
    /// at long steps, which a shorter delay partly offsets, not a property of the sensor.
    pub const LIGHT_MAG_DELAY: f64 = 0.009_25;

    /// [`Mode::Light`] with the default correction period [`Mode::LIGHT_PERIOD`].
    pub fn light() -> Self {
        Mode::Light {
            correction_period: T::from_f64(Self::LIGHT_PERIOD),
        }
    }
}

impl<T> Mode<T> {
    /// The name the tools and Python use: `full` or `light` (whatever the period).
    pub const fn name(&self) -> &'static str {
        match self {
            Mode::Full => "full",
            Mode::Light { .. } => "light",
        }
    }
}

impl<T: Real> FromStr for Mode<T> {
    type Err = Error;
    /// `full` is [`Mode::Full`], `light` is [`Mode::light`] (the default period).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for any other text.
    fn from_str(s: &str) -> Result<Self, Error> {
        match s {
            "full" => Ok(Mode::Full),
            "light" => Ok(Mode::light()),
            _ => Err(Error::InvalidArgument),
        }
    }
}

impl<T> fmt::Display for Mode<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// How the prediction turns a step's rate samples into its rotation (the rate path; gyroscope
/// increments always take the one-plus-previous coning rule, [`super::Estimator::update_increment`]).
/// The 4th-order rules are the propagation module's unequal-interval rate methods
/// ([`crate::propagation::rate_samples`], [`crate::propagation::kernels::magnus4_step_unequal`]):
/// the rates at the step's two Gauss nodes from the backward Lagrange interpolant through the
/// last four samples at their own times (`k−3 … k`: no look-ahead, no latency), the step's
/// rotation vector from them, and the shared step limit
/// ([`crate::step_limit::MAX_STEP_ANGLE`]) on it. At the start, after a saturated sample, and
/// after an interval more than twice or less than half the one before it (a gap, a clock
/// restart), the window restarts and the rule falls back until it holds four samples: the
/// linear interpolant through the step's two ends (order 2), or with one sample its rate
/// alone.
///
/// **The full mode's default, Magnus-4**, chosen by the project's rule (it wins or ties within
/// the noise on every benchmark, per half; BENCHMARKS.md, "The estimator's rate rule"): on the
/// 16 BROAD trials the mean total RMSE ties at 285.7 Hz (half A 1.219 → 1.220, B 1.212 →
/// 1.212; the per-trial differences' standard error 0.003 / 0.006) and at 142.9 Hz (A 1.220 →
/// 1.224 ± 0.010, B 1.249 → 1.238) and wins at 95.2 Hz (A 1.248 → 1.215, B 1.294 → 1.261)
/// and 47.6 Hz (A 1.666 → 1.260, B 1.662 → 1.321); the 6D inclination wins or ties on every
/// half at every rate; the synthetic grid ties (differences of opposite sign on the two seeds,
/// within ±0.04°). CF4 gives the same numbers to ±0.001° with a second exponential.
///
/// **The light mode honours the rule too, with the same default, Magnus-4**, formed from
/// weights on the samples computed once per run of equal intervals (the same mean rotation to
/// rounding, the commutator's rate difference from the step's end samples: order 4 still; the
/// estimation module's rate window). Against the trapezoid it kept before, on
/// the 16 BROAD trials (light 9D, its magnetometer delay [`Mode::LIGHT_MAG_DELAY`]): half A
/// 1.186 / 1.201 / 1.221 / 1.554 → 1.185 / 1.189 / 1.184 / 1.217, half B 1.193 / 1.216 /
/// 1.261 / 1.656 → 1.193 / 1.212 / 1.241 / 1.306 at 285.7 / 142.9 / 95.2 / 47.6 Hz. The light
/// mode's Cortex-M0 update costs 39 580 instructions with it, within the 40 000 budget
/// (BENCHMARKS.md, "The light mode's rate rule"); [`RateRule::Trapezoid`] is the cheapest
/// choice there.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum RateRule {
    /// The mean of the step's two end samples, `φ = (ω_prev + ω)/2·Δt − b̂Δt`: order 2, one
    /// exponential, no interpolation.
    Trapezoid,
    /// Magnus-4 on the Gauss-node rates, `φ = (h/2)(ω₁ + ω₂) + (√3/12) h² ω₁ × ω₂`
    /// ([`crate::propagation::rate_samples::magnus4_rotation_vector`], bias removed from both
    /// nodes): order 4, one exponential. The default.
    #[default]
    Magnus4,
    /// Commutator-free CF4 on the Gauss-node rates, `q ⊗ exp(φ₁) ⊗ exp(φ₂)`
    /// ([`crate::propagation::rate_samples::cf4_rotation_vectors`]): order 4, two exponentials.
    Cf4,
}

impl RateRule {
    /// Every rule, in the order above.
    pub const ALL: [RateRule; 3] = [RateRule::Trapezoid, RateRule::Magnus4, RateRule::Cf4];

    /// The propagation module's rate method a 4th-order rule runs (`None` for the trapezoid).
    pub const fn method(self) -> Option<RateMethod> {
        match self {
            RateRule::Trapezoid => None,
            RateRule::Magnus4 => Some(RateMethod::Magnus4),
            RateRule::Cf4 => Some(RateMethod::Cf4),
        }
    }

    /// The rule's name in the tools (`--set rate_rule=NAME`), the parameter file
    /// (`rate_rule = NAME`, [`super::params_text`]) and Python (`estimate(rate_rule=NAME)`):
    /// `trapezoid`, or the rate method's ([`RateMethod::name`]: `magnus4`, `cf4`). The C
    /// interface gives each rule a code (`GYRO_RATE_RULE_TRAPEZOID`, `_MAGNUS4`, `_CF4`).
    pub const fn name(self) -> &'static str {
        match self.method() {
            None => "trapezoid",
            Some(m) => m.name(),
        }
    }
}

impl FromStr for RateRule {
    type Err = Error;
    /// The rule of [`RateRule::name`].
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for any other text (`rk4` included: it gives no rotation
    /// vector to carry the compensated attitude or the covariance with).
    fn from_str(s: &str) -> Result<Self, Error> {
        Self::ALL
            .into_iter()
            .find(|r| r.name() == s)
            .ok_or(Error::InvalidArgument)
    }
}

impl fmt::Display for RateRule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The parameter-file name of a row: `flat` or `group.field`.
macro_rules! param_name {
    ($flat:ident) => {
        stringify!($flat)
    };
    ($flat:ident @ $g:ident . $f:ident) => {
        concat!(stringify!($g), ".", stringify!($f))
    };
}

/// A row's place in a `Params` value `$p`.
macro_rules! param_place {
    ($p:ident, $flat:ident) => {
        $p.$flat
    };
    ($p:ident, $flat:ident @ $g:ident . $f:ident) => {
        $p.$g.$f
    };
}

/// Sorts the table's rows into [`Params`]' own fields and its two groups (each entry its
/// documentation, field, flat name and default), then defines the three structs (each field's
/// documentation ending with its default) and the constructor from the values in table order.
macro_rules! params_structs {
    // A field of the disturbance monitor.
    (@sort $top:tt [$($field:tt)*] $rest:tt [$($all:ident)*]
        $(#[$m:meta])* $flat:ident @ field . $f:ident : $d:expr, $dom:ident; $($tail:tt)*) => {
        params_structs!(@sort $top [$($field)* { $(#[$m])* $f $flat = $d }] $rest [$($all)* $flat] $($tail)*);
    };
    // A field of the rest detector.
    (@sort $top:tt $field:tt [$($rest:tt)*] [$($all:ident)*]
        $(#[$m:meta])* $flat:ident @ rest . $f:ident : $d:expr, $dom:ident; $($tail:tt)*) => {
        params_structs!(@sort $top $field [$($rest)* { $(#[$m])* $f $flat = $d }] [$($all)* $flat] $($tail)*);
    };
    // A field of `Params`.
    (@sort [$($top:tt)*] $field:tt $rest:tt [$($all:ident)*]
        $(#[$m:meta])* $flat:ident : $d:expr, $dom:ident; $($tail:tt)*) => {
        params_structs!(@sort [$($top)* { $(#[$m])* $flat = $d }] $field $rest [$($all)* $flat] $($tail)*);
    };
    (@sort [$({ $(#[$tm:meta])* $t:ident = $td:expr })*]
        [$({ $(#[$fm:meta])* $f:ident $ff:ident = $fd:expr })*]
        [$({ $(#[$rm:meta])* $r:ident $rf:ident = $rd:expr })*]
        [$($all:ident)*]) => {
        /// The estimator's parameters, in SI units (angles in rad), every time in seconds
        /// (none in samples: the same parameters describe the same filter at any rate).
        ///
        /// [`Params::default`] describes a typical consumer MEMS IMU from its datasheet
        /// figures (InvenSense MPU-9250 with its AK8963 magnetometer, the common 9-axis part;
        /// a characterisation of the actual sensor, written as a parameter file, replaces
        /// them), and the filter's own design choices (the low-pass and correlation times,
        /// the gates, the online estimates' times; see the module docs of
        /// [`estimation`](super) for how they were chosen). Each field says where its default
        /// comes from and ends with its value (`deg(x)`: `x` degrees in rad;
        /// `STANDARD_GRAVITY`: 9.806 65 m/s²). The numeric fields are declared once, in
        /// [`estimator_parameters!`](crate::estimator_parameters) ([`super::params`]); the
        /// parameter file ([`super::params_text`]) sets any of them by name.
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct Params<T> {
            /// The earth frame of [`Estimator::attitude`](super::Estimator::attitude).
            pub frame: EarthFrame,
            /// How corrections are weighted.
            pub gains: Gains<T>,
            /// Full or light update ([`Mode`]).
            pub mode: Mode<T>,
            /// How rate samples become a step's rotation, in both modes ([`RateRule`];
            /// `rate_rule` in the tools' `--set`). Default: [`RateRule::Magnus4`].
            pub rate_rule: RateRule,
            $(
                $(#[$tm])*
                #[doc = ""]
                #[doc = concat!("Default value: `", stringify!($td), "`.")]
                pub $t: T,
            )*
            /// The magnetic disturbance monitor.
            pub field: FieldThresholds<T>,
            /// The rest detector.
            pub rest: RestThresholds<T>,
        }

        /// The disturbance monitor's settings (see [`super::field`]; `field.*` in the
        /// parameter file).
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct FieldThresholds<T> {
            $(
                $(#[$fm])*
                #[doc = ""]
                #[doc = concat!("Default value: `", stringify!($fd), "`.")]
                pub $f: T,
            )*
        }

        /// The rest detector's thresholds (SI units; see [`super::rest`]; `rest.*` in the
        /// parameter file).
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct RestThresholds<T> {
            $(
                $(#[$rm])*
                #[doc = ""]
                #[doc = concat!("Default value: `", stringify!($rd), "`.")]
                pub $r: T,
            )*
        }

        impl<T> Params<T> {
            /// The parameters of these choices and numeric values (in the order of
            /// [`Params::NAMES`], as [`Params::values`] gives them).
            pub fn from_values(
                frame: EarthFrame,
                gains: Gains<T>,
                mode: Mode<T>,
                values: [T; PARAMETER_COUNT],
            ) -> Self {
                let [$($all),*] = values;
                Params {
                    frame,
                    gains,
                    mode,
                    rate_rule: RateRule::default(),
                    $($t,)*
                    field: FieldThresholds { $($f: $ff,)* },
                    rest: RestThresholds { $($r: $rf,)* },
                }
            }
        }
    };
    ($($rows:tt)*) => {
        params_structs!(@sort [] [] [] [] $($rows)*);
    };
}

/// Everything of [`Params`] that takes the rows in table order.
macro_rules! params_flat {
    ($( $(#[$m:meta])* $flat:ident $(@ $g:ident . $f:ident)? : $d:expr, $dom:ident; )*) => {
        /// How many numeric parameters the table declares.
        pub const PARAMETER_COUNT: usize = [$(param_name!($flat $(@ $g.$f)?)),*].len();

        impl<T> Params<T> {
            /// The names of the numeric parameters in the parameter file, in its order: the
            /// field names, those of [`Params::field`] and [`Params::rest`] prefixed `field.`
            /// and `rest.` (the heading time constant of [`Gains::Fixed`] is a choice of
            /// gains, not among them).
            pub const NAMES: [&'static str; PARAMETER_COUNT] =
                [$(param_name!($flat $(@ $g.$f)?)),*];

            /// The same names without dots (`field.norm` is `field_norm`): the fields of the
            /// C parameter structs and the Python keywords.
            pub const FLAT_NAMES: [&'static str; PARAMETER_COUNT] = [$(stringify!($flat)),*];

            /// The domain of each parameter, in the order of [`Params::NAMES`].
            pub const DOMAINS: [Domain; PARAMETER_COUNT] = [$(Domain::$dom),*];

            /// The numeric parameters' values in the order of [`Params::NAMES`].
            pub fn values(&self) -> [T; PARAMETER_COUNT]
            where
                T: Copy,
            {
                let p = self;
                [$(param_place!(p, $flat $(@ $g.$f)?)),*]
            }

            /// The numeric parameters in the order of [`Params::NAMES`], for setting them.
            pub fn values_mut(&mut self) -> [&mut T; PARAMETER_COUNT] {
                let p = self;
                [$(&mut param_place!(p, $flat $(@ $g.$f)?)),*]
            }
        }

        impl<T: Real> Default for Params<T> {
            fn default() -> Self {
                Params::from_values(
                    EarthFrame::Enu,
                    Gains::Kalman,
                    Mode::Full,
                    [$(T::from_f64($d)),*],
                )
            }
        }
    };
}

estimator_parameters!(params_structs);
estimator_parameters!(params_flat);

impl<T> Params<T> {
    /// The numeric parameter called `name` (one of [`Params::NAMES`]), for setting it by name
    /// (command lines, bindings); `None` for any other name.
    pub fn parameter_mut(&mut self, name: &str) -> Option<&mut T> {
        let i = Self::NAMES.iter().position(|n| *n == name)?;
        self.values_mut().into_iter().nth(i)
    }

    /// The numeric parameter whose flat name is `flat` (one of [`Params::FLAT_NAMES`]: the C
    /// fields' and Python keywords' spelling), as [`Params::parameter_mut`]; `None` for any other
    /// name.
    pub fn flat_parameter_mut(&mut self, flat: &str) -> Option<&mut T> {
        let i = Self::FLAT_NAMES.iter().position(|n| *n == flat)?;
        self.values_mut().into_iter().nth(i)
    }

    /// Sets the numeric parameter `name` to `value`: one of [`Params::NAMES`];
    /// `heading_time_constant`, which selects [`Gains::Fixed`] with that time constant; or
    /// `light_period`, which selects [`Mode::Light`] with that correction period. `false`
    /// (and nothing changed) for any other name.
    pub fn set_by_name(&mut self, name: &str, value: T) -> bool {
        if name == "heading_time_constant" {
            self.gains = Gains::Fixed {
                heading_time_constant: value,
            };
            return true;
        }
        if name == "light_period" {
            self.mode = Mode::Light {
                correction_period: value,
            };
            return true;
        }
        match self.parameter_mut(name) {
            Some(slot) => {
                *slot = value;
                true
            }
            None => false,
        }
    }

    /// The same parameters with every number mapped by `f`, the frame and the choice of gains
    /// kept: `p.map(|x| x as f32)` is the f32 filter of the f64 parameters `p`.
    pub fn map<U>(&self, f: impl Fn(T) -> U) -> Params<U>
    where
        T: Copy,
    {
        let gains = match self.gains {
            Gains::Kalman => Gains::Kalman,
            Gains::Fixed {
                heading_time_constant,
            } => Gains::Fixed {
                heading_time_constant: f(heading_time_constant),
            },
        };
        let mode = match self.mode {
            Mode::Full => Mode::Full,
            Mode::Light { correction_period } => Mode::Light {
                correction_period: f(correction_period),
            },
        };
        Params {
            rate_rule: self.rate_rule,
            ..Params::from_values(self.frame, gains, mode, self.values().map(&f))
        }
    }
}

impl<T: Real> Params<T> {
    /// The default parameters in [`Mode::light`].
    pub fn light() -> Self {
        Self {
            mode: Mode::light(),
            ..Self::default()
        }
    }

    /// The default parameters in earth frame `frame` and mode `mode`: the numbers and gains of
    /// [`Params::default`], and the choices [`Params::from_values`] gives that frame and mode
    /// (the rate rule among them). The faces that take a frame and a mode by name (the
    /// `estimate` tool, Python's `estimate`) start from these, and the C structs' default rate
    /// rule code is the same rule, so that a default that depends on the mode reaches them all.
    pub fn defaults_of(frame: EarthFrame, mode: Mode<T>) -> Self {
        let d = Self::default();
        Self::from_values(frame, d.gains, mode, d.values())
    }

    /// Checks every parameter against its [`Domain`] ([`Params::DOMAINS`]), the heading time
    /// constant of [`Gains::Fixed`] and the period of [`Mode::Light`] (finite, `≥ 0`).
    /// [`Estimator::try_new`](super::Estimator::try_new) starts with it.
    ///
    /// # Errors
    /// [`Error::NonFinite`] when a numeric parameter is NaN or infinite (a range may be `+∞`);
    /// otherwise [`Error::InvalidArgument`] when one is outside its domain (negative, or zero
    /// where [`Domain::Positive`]), or the time constant or period is not finite and `≥ 0`.
    pub fn validate(&self) -> Result<(), Error> {
        let values = self.values();
        let checked = || values.iter().zip(Self::DOMAINS);
        if checked().any(|(v, d)| d.non_finite(*v)) {
            return Err(Error::NonFinite);
        }
        if checked().any(|(v, d)| !d.contains(*v)) {
            return Err(Error::InvalidArgument);
        }
        if let Gains::Fixed {
            heading_time_constant,
        } = self.gains
            && (!heading_time_constant.is_finite() || heading_time_constant < T::ZERO)
        {
            return Err(Error::InvalidArgument);
        }
        if let Mode::Light { correction_period } = self.mode
            && !(correction_period.is_finite() && correction_period >= T::ZERO)
        {
            return Err(Error::InvalidArgument);
        }
        Ok(())
    }
}
