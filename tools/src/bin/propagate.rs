//! `propagate`: integrate gyro increments or rate samples from stdin into attitudes on stdout.
//!
//! ```text
//! propagate --input increments|rates --algo ALGO --dt SECONDS [--q0 w,x,y,z] [--f32 | --fixed] \
//!     [--compensated] [--every N] [--gyro-unit U] [--calibration FILE] [--remap x,-z,y]
//! propagate --time-column --input increments|rates --algo ALGO [--dt NOMINAL] [--t0 T] \
//!     [--f32 | --fixed] [--time-unit s|ms|us] [--gap-factor K] [--gyro-unit U] \
//!     [--calibration FILE] [--remap R]
//! ```
//! Run with `--help` for the full description of the input and output formats.

use std::collections::VecDeque;
use std::fmt::Debug;
use std::io::{self, Write};
use std::process::ExitCode;
use std::str::FromStr;

use gyrostat::fixed::IncrementQuantizer;
use gyrostat::propagation::CarriedAttitude;
use gyrostat::propagation::coning::{
    ConingTerms, two_sample_unequal_coefficient, two_sample_unequal_terms,
};
use gyrostat::propagation::kernels::{cf4_step_unequal, magnus4_step_unequal, rk4_step_unequal};
use gyrostat::propagation::{
    CompensatedAttitude, ConingRule, Normalization, PropagatedAttitude, RateMethod,
};
use gyrostat::real::Q30;
use gyrostat::sensor::{
    AxisRemap, ClipGuard, ClipLimit, ClipPolicy, InertialCalibration, Interval, MicrosClock,
    SampleClock,
};
use gyrostat::step_limit::MAX_STEP_ANGLE;
use gyrostat::{Quat, Real, Ring, UnitQuat, Vec3};
use gyrostat_pipeline::propagate::{self, PropagateError, TURN_RESOLUTION};
use gyrostat_tools::calibration;
use gyrostat_tools::flags::{self, Cli, Flag, Flags};
use gyrostat_tools::stream::{self, Csv, Lines};
use gyrostat_tools::units::{GyroUnit, TimeUnit};

const CLI: Cli = Cli {
    name: "propagate",
    help: HELP,
    flags: &[
        Flag::value("--input"),
        Flag::value("--algo"),
        Flag::value("--dt"),
        Flag::value("--q0"),
        Flag::switch("--f32"),
        Flag::switch("--fixed"),
        Flag::switch("--compensated"),
        Flag::value("--every"),
        Flag::switch("--time-column"),
        Flag::value("--t0"),
        Flag::value("--gap-factor"),
        Flag::value("--gyro-unit"),
        Flag::value("--time-unit"),
        Flag::value("--calibration"),
        Flag::value("--remap"),
        Flag::switch("--time-wrap"),
        Flag::value("--gyro-full-scale"),
        Flag::value("--on-clip"),
    ],
};

const HELP: &str = "\
propagate: integrate gyro increments or rate samples into attitude quaternions

USAGE:
    propagate --input increments|rates --algo ALGO --dt SECONDS [--q0 w,x,y,z] [--f32 | --fixed]
              [--compensated] [--every N] [SENSOR OPTIONS]
    propagate --time-column --input increments|rates --algo ALGO [--dt NOMINAL] [--t0 T]
              [--f32 | --fixed] [--time-unit s|ms|us] [--gap-factor K] [--q0 w,x,y,z]
              [--every N] [SENSOR OPTIONS]

    Flags take their value as the next argument or after `=` (--dt 0.01, --dt=0.01); a flag
    given twice is an error.

INPUT (stdin): one sample per line, three comma-separated numbers `dx,dy,dz` (body frame).
    --input increments   sample k (0-based) is the integral of omega over [k*dt, (k+1)*dt], rad
    --input rates        sample k is omega(k*dt), rad/s
    Blanks around numbers are allowed. Blank lines (empty or only blanks) are skipped, the last
    one too; they count for line numbers but are not samples.

ALGO for --input increments:
    exp       one exponential per increment, no coning correction
    coning1   one increment per update with the previous-interval correction dth(k-1) x dth(k) / 12
    coning2   2-sample rule, one attitude update per 2 increments
    coning3   3-sample rule, one attitude update per 3 increments
    coning4   4-sample rule, one attitude update per 4 increments
ALGO for --input rates (each integrates from t = 0 to the last sample's time):
    magnus4   4th-order Magnus (one exponential per sample interval)
    cf4       commutator-free 4th order (two exponentials, weights 1/4 +- sqrt(3)/6)
    rk4       classical RK4 on the quaternion, renormalised
    The rates at the Gauss nodes / midpoints come from the cubic interpolant through four
    consecutive samples (quadratic for a 3-sample record, linear for a 2-sample one).

OPTIONS:
    --dt SECONDS   sample interval, finite and > 0 (required, except with --time-column)
    --q0 w,x,y,z   initial attitude (scalar first, maps body to lab), default 1,0,0,0;
                   its norm must be within 1e-3 of 1 (it is then normalised exactly)
    --f32          run the propagation in f32 (default f64)
    --fixed        run the propagation in Q1.30 fixed point, the integer code of the firmware
                   (--input increments only): each number is converted to the nearest multiple
                   of 2^-30 rad with the remainder of the previous rows added and the new
                   remainder carried to the next row (gyrostat::fixed::IncrementQuantizer: the
                   sum of the converted increments stays within 2^-31 of the sum of the given
                   ones; |value| < 2 rad, else a row error), q0 is rounded likewise (after its
                   exact normalisation in f64), and the attitude is a
                   gyrostat::propagation::CarriedAttitude: every update carries the low bits its
                   roundings discard into the next one and folds the fast renormalisation
                   q + q(1 - |q|^2)/2 into the increment, so the rounding does not drift.
                   The output is bit for bit what gyrostat's fixed-point firmware computes from
                   the same increments: every printed number is an exact multiple of 2^-30.
    --compensated  carry the attitude's rounding error beside it (compensated accumulation,
                   gyrostat::propagation::compensated_attitude): every update adds its increment
                   without losing its rounding, so an f32 attitude stays within about 1e-5 rad
                   over an hour at 1 kHz where the plain f32 attitude drifts up to 2e-2 rad (it
                   rounds q the same way again and again); the rate methods also take --dt's
                   f32 rounding into account. Without --f32 it does the same in f64 (not with
                   --fixed). Costs more per update; the output format is unchanged.
    --every N      print every N-th sample (N >= 1, default 1)
    --help         print this text

SENSOR OPTIONS (every mode): each sample goes raw -> unit -> calibration -> remap -> propagation.
    --gyro-unit rad/s|deg/s   the unit of the rates (default rad/s); with --input increments
                   the angle unit of the increments (rad or deg: the same factor)
    --calibration FILE        the gyro model of FILE, corrected = M diag(s) (raw - b), applied in
                   rad/s after the unit conversion (for increments: M diag(s) (raw - b dt),
                   dt the sample's interval). FILE holds `key = numbers` lines (`#` comments):
                   gyro_bias = bx,by,bz (rad/s), gyro_scale = sx,sy,sz (> 0),
                   gyro_misalignment = 9 numbers row-major, and accel_*, mag_hard_iron,
                   mag_soft_iron (read and checked, used by other tools). Errors name the line.
    --remap X,Y,Z  the sensor's axes in the body: body x,y,z = the listed sensor axes, each
                   with an optional sign (x,-z,y: body y = -sensor z). Only the 24 proper
                   rotations are accepted (a reflection is an error). Applied after calibration.

TIME COLUMN (--time-column; f64, --f32, or --fixed for increments; not --compensated): each
    row starts with its timestamp, `t,x,y,z`.
    --time-unit s|ms|us       the unit of t and --t0 (default s)
    --dt NOMINAL   the nominal sample interval (s), for the gap policy only. Optional: without
                   it, the median of the intervals between the first 17 timestamps (for
                   increments --t0 and the first 16 rows; fewer in a shorter input; the mean of
                   the two middle ones for an even count; rounded to whole us with --time-wrap).
                   The first rows are then read before the first line is printed. A median that
                   is not positive (timestamps that do not increase) is a row error.
    --gap-factor K an interval longer than K*NOMINAL is a gap (K >= 1, default 5)
    --input increments   t is the END of the interval the increment covers; the first interval
                   starts at --t0 T (required). Every ALGO, in the form for unequal intervals:
                   exp       one exponential per increment
                   coning1   th + c th(k-1) x th, c = h^2/(6 h(k-1) (h(k-1) + h)) (1/12 when
                             equal): the linear rate model through the two intervals
                   coning2   2-sample rule, coefficient (h1+h2)^2/(6 h1 h2) (2/3 when equal)
                   coning3, coning4   N-sample rule of the rate polynomial of degree N-1 fitted
                             to the N increments on their own intervals:
                             phi = sum th_i + sum_{i<j} c_ij th_i x th_j, the coefficients
                             from the intervals (at equal intervals 57/80, 33/80, 57/80 for
                             three; for four 736/945, 334/945, 526/945, 218/315, 334/945,
                             736/945: the polynomial rules, while the fixed-interval coning3
                             and coning4 are Miller's rules tuned for pure coning, which have no
                             unequal-interval form)
                   coningN updates once per N increments; a row inside a group, and the last
                   row of an unfinished group, apply the pending increments by the rule of their
                   number (one: an exponential), not fed back. --fixed: the increments are
                   quantised as without --time-column, the attitude is the carried Q1.30
                   attitude, the coefficients are computed from the timestamps in f64 and
                   rounded to Q1.30 (|c| < 2, else a row error); coning1 and coning2 carry their
                   coning term's residual, coning3 and coning4 round their further cross
                   products each update.
    --input rates        the rate sampled at t. ALGO magnus4, cf4 or rk4 on the Lagrange
                   interpolant through the actual times of samples k-3..k (the first three
                   intervals use samples 0..3; a record of 2 or 3 samples the linear or
                   quadratic interpolant): Magnus-4 and CF4 at the interval's Gauss nodes, RK4
                   at its start, midpoint and end. --t0 is not used.
    --time-wrap    t is a free-running 32-bit microsecond counter (whole numbers 0..2^32-1, needs
                   --time-unit us and a whole --gap-factor) that wraps every 2^32 us (71.6 min):
                   intervals are wrapped differences, the printed t is unwrapped (counted from
                   the first value; --t0 a counter value too). A wrapped difference of 2^31 us
                   or more reads as backwards.
    --gyro-full-scale R  the gyro's full scale in --gyro-unit (rad or deg for increments): a
                   row with an axis at |value| >= R is clipped (the sensor saturated)
    --on-clip error|pass|hold   error (default): the row is an error; pass: integrate it as
                   read; hold: each clipped axis takes its last unclipped rate (times the
                   row's interval for increments; passed when there is none yet). With pass
                   or hold, stderr ends with a note of how many rows were clipped.
    Policy: an interval longer than K*NOMINAL (samples were lost), a repeated timestamp and a
    timestamp before the previous one stop the run with a row error (exit status 1): the
    attitude is never carried silently across them.
    Output: `k,t,qw,qx,qy,qz`, t in seconds: increments, the attitude at the end of row k's
    interval; rates, the attitude at row k's time (row 0 prints q0).

OUTPUT (stdout): `k,qw,qx,qy,qz` after sample k (0-based) whenever k is a multiple of N, and
    always after the last sample consumed (the last valid one when the run stops at an error).
    Rows are written as they are computed (flushed at least every 0.1 s and whenever the input
    stalls). Numbers are printed in the shortest form that
    round-trips to the same f64 (or f32 with --f32). The attitude is renormalised exactly after
    every update (with --compensated: the compensated pair is, and the line is its part rounded
    to f64 or f32, unit within a few ulp; with --fixed: the fast renormalisation folded into each update, see above).
    increments: the line for sample k is the attitude at time (k+1)*dt, after increments 0..=k.
        coningN updates the attitude once per N increments (after samples N-1, 2N-1, ...). A
        line printed inside a group, and the final line if the input ends inside a group,
        applies the pending increments with the highest-order rule that fits them (1 pending:
        coning1 with the increment before it; 2: coning2; 3: coning3), so every increment
        consumed is integrated; inside-group lines are not fed back into later updates.
    rates: the line for sample k is the attitude at time k*dt (k = 0 prints q0).

ERRORS (stderr, nothing else on stdout after them):
    error: line N: reason      (N counts every line from 1, blank ones too) exit status 1
        A line that is not three finite numbers, not UTF-8 text, or longer than 1 MiB, a sample
        that turns the body by more than half a turn (coning rules and rate methods: their
        series are meaningless there), an --algo exp increment so long that its angle is not
        known to 1e-3 rad (beyond 4.5e12 rad in f64, 8.4e3 rad with --f32), and a sample whose
        attitude would not be a finite unit quaternion stop the run there. The rows before it are kept, and the attitude
        after the last valid sample is printed as promised above (after a malformed line the
        samples before it are integrated to their end, as if the input ended there).
    error: reason              bad command-line arguments: exit status 2, no output
    When stdout is closed early (a pipe into `head`), the run stops quietly with status 0.
";

#[derive(Clone, Copy)]
enum Algo {
    Increments(ConingRule),
    Rates(RateMethod),
}

/// The arithmetic a run uses.
#[derive(Clone, Copy, PartialEq)]
enum Arith {
    F64,
    F32,
    Fixed,
}

struct Args {
    algo: Algo,
    /// `--dt`: required without `--time-column`; with it, the nominal interval, inferred from
    /// the timestamps when not given ([`nominal_from`]).
    dt: Option<f64>,
    q0: [f64; 4],
    arith: Arith,
    compensated: bool,
    every: u64,
    sensor: Sensor,
    timed: Option<Timed>,
}

/// The sensor model applied to every sample before the propagation.
struct Sensor {
    gyro_factor: f64,
    calibration: Option<InertialCalibration<f64>>,
    remap: Option<AxisRemap>,
}

impl Sensor {
    /// A rate sample (or, with `dt`, an increment over `dt`) in rad/s (rad), body axes.
    fn apply(&self, raw: Vec3<f64>, dt: Option<f64>) -> Vec3<f64> {
        let v = raw * self.gyro_factor;
        let v = match (&self.calibration, dt) {
            (Some(c), Some(dt)) => c.apply_increment(v, dt),
            (Some(c), None) => c.apply(v),
            (None, _) => v,
        };
        self.remap.map_or(v, |r| r.apply(v))
    }
}

/// The arguments of the time-column mode.
struct Timed {
    time_factor: f64,
    t0: Option<f64>,
    gap_factor: f64,
    wrap: bool,
    clip: Option<(ClipLimit<f64>, ClipPolicy)>,
}

/// The clipping check of the time-column mode: the library's guard on the raw readings (in
/// --gyro-unit) against the full scale, its policy from `--on-clip` (`error`: Reject, `pass`:
/// Pass, `hold`: HoldLast, which for increments holds the last unclipped rate times the row's
/// own interval, [`ClipGuard::filter_increment`]), and the count of clipped rows.
struct Clip {
    guard: ClipGuard<f64>,
    count: u64,
}

impl Clip {
    fn new(limit: ClipLimit<f64>, policy: ClipPolicy) -> Self {
        Self {
            guard: ClipGuard::new(limit, policy),
            count: 0,
        }
    }

    /// The raw sample the propagation gets (`h` the interval of an increment, `None` for a
    /// rate), or the row error under `--on-clip error`.
    fn filter(&mut self, raw: Vec3<f64>, h: Option<f64>) -> Result<Vec3<f64>, String> {
        let raw = raw.to_array();
        let filtered = match h {
            Some(h) => self.guard.filter_increment(raw, h),
            None => self.guard.filter(raw),
        };
        match filtered {
            Ok((out, clipped)) => {
                self.count += u64::from(clipped.any());
                Ok(Vec3::from_array(out))
            }
            Err(gyrostat::Error::Clipped) => {
                let limit = self.guard.limit();
                let axis = limit.check(raw).axes.iter().position(|&c| c).unwrap_or(0);
                let v = raw[axis];
                Err(format!(
                    "gyro axis {} clipped: |{v}| reaches the full scale {} (--on-clip error)",
                    ["x", "y", "z"][axis],
                    limit.limit()
                ))
            }
            Err(e) => Err(format!("interval not positive and finite: {e}")),
        }
    }
}

/// The arguments of a run, from the flags given.
fn arguments(f: &Flags) -> Result<Args, String> {
    let input = f.value("--input");
    let algo = f.value("--algo");
    let dt = f.get("--dt", flags::positive)?;
    let q0 = f
        .get("--q0", |flag, v| flags::numbers::<4>(flag, v, "w,x,y,z"))?
        .unwrap_or([1.0, 0.0, 0.0, 0.0]);
    let arith = match (f.switch("--f32"), f.switch("--fixed")) {
        (true, true) => return Err("--f32 and --fixed exclude each other".into()),
        (true, false) => Arith::F32,
        (false, true) => Arith::Fixed,
        (false, false) => Arith::F64,
    };
    let compensated = f.switch("--compensated");
    let every = f.get("--every", flags::at_least_one)?.unwrap_or(1);
    let gyro_factor = f
        .get("--gyro-unit", GyroUnit::parse)?
        .unwrap_or_default()
        .to_si();
    let calibration = f
        .value("--calibration")
        .map(|p| calibration::read(p).map(|c| c.gyro))
        .transpose()?;
    let remap = f
        .value("--remap")
        .map(|r| {
            AxisRemap::try_parse(r).map_err(|e| match e {
                gyrostat::Error::NotRotation => format!(
                    "--remap: '{r}' is a reflection (determinant -1), not a rotation of the axes"
                ),
                _ => format!("--remap: expected three distinct signed axes like x,-z,y, got '{r}'"),
            })
        })
        .transpose()?;
    let sensor = Sensor {
        gyro_factor,
        calibration,
        remap,
    };
    let time_factor = f.get("--time-unit", TimeUnit::parse)?.map(TimeUnit::to_si);
    let t0 = f.get("--t0", flags::number)?;
    let gap_factor = f.get("--gap-factor", flags::number)?;
    let timed = if f.switch("--time-column") {
        let gap_factor = gap_factor.unwrap_or(5.0);
        if gap_factor < 1.0 {
            return Err(format!("--gap-factor: must be >= 1, got {gap_factor}"));
        }
        let wrap = f.switch("--time-wrap");
        if wrap && time_factor != Some(1e-6) {
            return Err("--time-wrap needs --time-unit us (a 32-bit microsecond counter)".into());
        }
        if wrap && gap_factor.fract() != 0.0 {
            return Err(format!(
                "--gap-factor: must be a whole number with --time-wrap, got {gap_factor}"
            ));
        }
        let full_scale = f.get("--gyro-full-scale", flags::positive)?;
        let policy = match f.value("--on-clip") {
            None | Some("error") => ClipPolicy::Reject,
            Some("pass") => ClipPolicy::Pass,
            Some("hold") => ClipPolicy::HoldLast,
            Some(o) => {
                return Err(format!(
                    "--on-clip: expected error, pass or hold, got '{o}'"
                ));
            }
        };
        if full_scale.is_none() && f.value("--on-clip").is_some() {
            return Err("--on-clip needs --gyro-full-scale".into());
        }
        Some(Timed {
            time_factor: time_factor.unwrap_or(1.0),
            t0,
            gap_factor,
            wrap,
            clip: full_scale
                .map(|full_scale| {
                    ClipLimit::try_new(full_scale)
                        .map(|limit| (limit, policy))
                        .map_err(|_| format!("--gyro-full-scale: must be > 0, got {full_scale}"))
                })
                .transpose()?,
        })
    } else {
        for (given, name) in [
            (time_factor.is_some(), "--time-unit"),
            (t0.is_some(), "--t0"),
            (gap_factor.is_some(), "--gap-factor"),
            (f.switch("--time-wrap"), "--time-wrap"),
            (f.value("--gyro-full-scale").is_some(), "--gyro-full-scale"),
            (f.value("--on-clip").is_some(), "--on-clip"),
        ] {
            if given {
                return Err(format!("{name} needs --time-column"));
            }
        }
        None
    };
    let input = input.ok_or("--input is required (increments or rates)")?;
    let algo_name = algo.ok_or("--algo is required")?;
    if timed.is_none() && dt.is_none() {
        return Err("--dt is required".into());
    }
    let algo = match input {
        "increments" => Algo::Increments(algo_name.parse().map_err(|_| {
            let names = ConingRule::ALL.map(ConingRule::name).join(", ");
            format!("--algo '{algo_name}' is not an increments algorithm ({names})")
        })?),
        "rates" => Algo::Rates(algo_name.parse().map_err(|_| {
            let names = RateMethod::ALL.map(RateMethod::name).join(", ");
            format!("--algo '{algo_name}' is not a rates algorithm ({names})")
        })?),
        i => return Err(format!("--input must be increments or rates, got '{i}'")),
    };
    if timed.is_some() {
        if compensated {
            return Err("--time-column runs in f64, f32 or Q1.30, not --compensated".into());
        }
        if matches!(algo, Algo::Increments(_)) && timed.as_ref().is_some_and(|t| t.t0.is_none()) {
            return Err(
                "--time-column --input increments needs --t0 (the start of the first interval)"
                    .into(),
            );
        }
    }
    if arith == Arith::Fixed && matches!(algo, Algo::Rates(_)) {
        return Err("--fixed supports --input increments only".into());
    }
    if arith == Arith::Fixed && compensated {
        return Err(
            "--compensated needs floating point (--f32 or the default f64), not --fixed".into(),
        );
    }
    Ok(Args {
        algo,
        dt,
        q0,
        arith,
        compensated,
        every,
        sensor,
        timed,
    })
}

/// Parses one `dx,dy,dz` row.
fn parse_row<T: Real + FromStr>(line: &str) -> Result<Vec3<T>, String> {
    let parts: Vec<&str> = line.split(',').collect();
    if parts.len() != 3 {
        return Err(format!(
            "expected 3 comma-separated numbers dx,dy,dz, found {}",
            parts.len()
        ));
    }
    let mut v = [T::ZERO; 3];
    for (slot, p) in v.iter_mut().zip(&parts) {
        let p = p.trim();
        let x: T = p.parse().map_err(|_| format!("invalid number '{p}'"))?;
        if !x.is_finite() {
            return Err(format!("non-finite value '{p}'"));
        }
        *slot = x;
    }
    Ok(Vec3::new(v[0], v[1], v[2]))
}

/// The rows on stdout.
struct Printer {
    out: Csv,
    every: u64,
    last_printed: Option<u64>,
}

impl Printer {
    fn print<T: Debug>(&mut self, k: u64, [w, x, y, z]: [T; 4]) -> io::Result<()> {
        self.last_printed = Some(k);
        writeln!(self.out, "{k},{w:?},{x:?},{y:?},{z:?}")?;
        self.out.row_done()
    }
    fn due(&self, k: u64) -> bool {
        k.is_multiple_of(self.every)
    }
    /// Prints `q` as the attitude after sample `k` unless that row is out already.
    fn print_last<T: Debug>(&mut self, k: u64, q: [T; 4]) -> io::Result<()> {
        if self.last_printed == Some(k) {
            return Ok(());
        }
        self.print(k, q)
    }
}

enum Failure {
    Usage(String),
    Row(u64, String),
    Io(io::Error),
}

impl From<io::Error> for Failure {
    fn from(e: io::Error) -> Self {
        Failure::Io(e)
    }
}

/// The next non-blank row of the input parsed by `parse`, with its line number; `Ok(None)` at
/// the end. Pending output is flushed before a read that may wait.
fn next_row<X, R: io::Read>(
    lines: &mut Lines<R>,
    out: &mut Csv,
    parse: impl FnOnce(&str) -> Result<X, String>,
) -> Result<Option<(u64, X)>, Failure> {
    loop {
        if lines.will_read() {
            out.flush()?;
        }
        let Some((n, line)) = lines.next_line()? else {
            return Ok(None);
        };
        match line {
            Ok(text) if text.trim().is_empty() => continue,
            Ok(text) => {
                return parse(text)
                    .map(|x| Some((n, x)))
                    .map_err(|e| Failure::Row(n, e));
            }
            Err(reason) => return Err(Failure::Row(n, reason)),
        }
    }
}

/// The next sample of the input through the sensor model ([`next_row`]).
fn next_sample<T: Real + FromStr, R: io::Read>(
    lines: &mut Lines<R>,
    out: &mut Csv,
    sensor: &Sensor,
    dt: Option<f64>,
) -> Result<Option<(u64, Vec3<T>)>, Failure> {
    next_row(lines, out, |text| {
        parse_row::<T>(text).map(|v| {
            let v = sensor.apply(Vec3::from_array(v.to_array().map(T::to_f64)), dt);
            Vec3::from_array(v.to_array().map(T::from_f64))
        })
    })
}

/// The error of the sample on line `n` that stops a propagation ([`propagate::Increments`],
/// [`propagate::Rates`], [`propagate::FixedIncrements`]); `what`: which attitude.
fn stopped<T: Real>(e: PropagateError, n: u64, what: &str) -> Failure {
    Failure::Row(
        n,
        match e {
            PropagateError::NonFinite => gyrostat::Error::NonFinite.to_string(),
            PropagateError::Unresolvable { turn, limit } => format!(
                "the increment turns the body {turn:.3e} rad in one sample: beyond {limit:.2e} rad \
                 the angle itself is not known to {TURN_RESOLUTION:e} rad in {}",
                if T::EPSILON.to_f64() < 1e-10 {
                    "f64"
                } else {
                    "f32"
                }
            ),
            PropagateError::Library(e) => e.to_string(),
            PropagateError::Quantize(e) => format!("{e} (Q1.30 holds |value| < 2 rad)"),
            PropagateError::NotUnit(c) => format!(
                "the attitude {what} is not a finite unit quaternion ({:?}): the {} too large for \
                 this step",
                c.map(T::from_f64),
                if what.contains("time") {
                    "rates or --dt are"
                } else {
                    "increments are"
                }
            ),
        },
    )
}

/// Integrates increments; the outcome of the input (`Err(Failure::Row)` at a bad line) after the
/// rows it allows are printed.
fn increments<T, A, R>(
    lines: &mut Lines<R>,
    p: &mut Printer,
    q0: UnitQuat<T>,
    rule: ConingRule,
    sensor: &Sensor,
    dt: f64,
) -> Result<(), Failure>
where
    T: Real + FromStr + Debug,
    A: PropagatedAttitude<T> + From<UnitQuat<T>>,
    R: io::Read,
{
    let mut integ = propagate::Increments::<T, A>::new(q0, rule);
    let mut k: u64 = 0; // samples consumed
    let mut last = q0; // the attitude after sample k - 1
    let mut n = 0; // the line of the latest sample
    let stop = loop {
        let v = match next_sample::<T, R>(lines, &mut p.out, sensor, Some(dt)) {
            Ok(Some((line, v))) => {
                n = line;
                v
            }
            Ok(None) => break None,
            // A rejected line leaves the integrator as it was: end the record there.
            Err(Failure::Row(n, e)) => break Some(Failure::Row(n, e)),
            Err(e) => return Err(e),
        };
        let q = match integ.push(v) {
            Ok(q) => q,
            // An increment the rule cannot resolve leaves the integrator as it was.
            Err(e @ (PropagateError::Unresolvable { .. } | PropagateError::NonFinite)) => {
                break Some(stopped::<T>(e, n, "after this sample"));
            }
            Err(e) => {
                // The integrator is spoilt: the attitude after the previous sample is the last.
                if k > 0 {
                    p.print_last(k - 1, last.to_array())?;
                }
                return Err(stopped::<T>(e, n, "after this sample"));
            }
        };
        if p.due(k) {
            p.print(k, q.to_array())?;
        }
        last = q;
        k += 1;
    };
    if k > 0 {
        let q = integ
            .flush()
            .map_err(|e| stopped::<T>(e, n, "after the last sample"))?;
        p.print_last(k - 1, q.to_array())?;
    }
    stop.map_or(Ok(()), Err)
}

/// Integrates rate samples; like [`increments`].
fn rates<T, A, R>(
    lines: &mut Lines<R>,
    p: &mut Printer,
    q0: UnitQuat<T>,
    method: RateMethod,
    args_dt: f64,
    sensor: &Sensor,
) -> Result<(), Failure>
where
    T: Real + FromStr + Debug,
    A: PropagatedAttitude<T> + From<UnitQuat<T>>,
    R: io::Read,
{
    let mut integ = propagate::Rates::<T, A>::try_new(q0, method, args_dt)
        .map_err(|e| Failure::Usage(format!("--dt: {e}")))?;
    let mut reached: u64 = 0; // the next sample index whose attitude is due
    let mut last = q0;
    let mut n = 0; // the line of the latest sample
    let mut emit =
        |p: &mut Printer, q: Result<UnitQuat<T>, PropagateError>, n: u64| -> Result<(), Failure> {
            let q =
                q.map_err(|e| stopped::<T>(e, n, &format!("at the time of sample {reached}")))?;
            if p.due(reached) {
                p.print(reached, q.to_array())?;
            }
            last = q;
            reached += 1;
            Ok(())
        };
    let stop = loop {
        let v = match next_sample::<T, R>(lines, &mut p.out, sensor, None) {
            Ok(Some((line, v))) => {
                n = line;
                v
            }
            Ok(None) => break None,
            // A rejected line leaves the integrator as it was: end the record there.
            Err(Failure::Row(n, e)) => break Some(Failure::Row(n, e)),
            Err(e) => return Err(e),
        };
        let pushed = integ
            .push(v)
            .map_err(|e| stopped::<T>(e, n, "after this sample"))
            .and_then(|qs| qs.into_iter().try_for_each(|q| emit(p, q, n)));
        if let Err(e) = pushed {
            if reached > 0 {
                p.print_last(reached - 1, last.to_array())?;
            }
            return Err(e);
        }
    };
    let finished = integ.finish().into_iter().try_for_each(|q| emit(p, q, n));
    if reached > 0 {
        p.print_last(reached - 1, last.to_array())?;
    }
    finished?;
    stop.map_or(Ok(()), Err)
}

/// Runs the propagation in `T`, the integrators carrying the attitude as `A` (a plain
/// `UnitQuat<T>` or a `CompensatedAttitude<T>`).
fn run<T: Real + FromStr + Debug, A: PropagatedAttitude<T> + From<UnitQuat<T>>>(
    args: &Args,
) -> Result<(), Failure> {
    let t = |x: f64| T::from_f64(x);
    let q0 = UnitQuat::try_from_near_unit(
        Quat::new(t(args.q0[0]), t(args.q0[1]), t(args.q0[2]), t(args.q0[3])),
        t(1e-3),
    )
    .map_err(|e| Failure::Usage(format!("--q0: {e}: its norm must be within 1e-3 of 1")))?;
    let dt_given = args.dt.unwrap_or(1.0);
    let dt = t(dt_given);
    if !(dt.is_finite() && dt > T::ZERO) {
        return Err(Failure::Usage(format!(
            "--dt: {dt_given:?} is not a positive finite f32"
        )));
    }
    let mut p = Printer {
        out: Csv::stdout(),
        every: args.every,
        last_printed: None,
    };
    let mut lines = Lines::new(io::stdin().lock());
    let result = match args.algo {
        Algo::Increments(rule) => {
            increments::<T, A, _>(&mut lines, &mut p, q0, rule, &args.sensor, dt_given)
        }
        Algo::Rates(method) => {
            rates::<T, A, _>(&mut lines, &mut p, q0, method, dt_given, &args.sensor)
        }
    };
    finish(result, &mut p)
}

/// `--fixed`: the increment path in Q1.30, the firmware's integer code; lines, errors and the
/// last attitude as [`increments`] (a Q1.30 attitude is always finite: no check of it).
fn run_fixed(args: &Args) -> Result<(), Failure> {
    let Algo::Increments(rule) = args.algo else {
        return Err(Failure::Usage(
            "--fixed supports --input increments only".into(),
        ));
    };
    let [w, x, y, z] = args.q0;
    let q0 = UnitQuat::try_from_near_unit(Quat::new(w, x, y, z), 1e-3)
        .map_err(|e| Failure::Usage(format!("--q0: {e}: its norm must be within 1e-3 of 1")))?;
    let q0 = UnitQuat::<Q30>::try_from_f64(q0).map_err(|e| Failure::Usage(format!("--q0: {e}")))?;
    let mut integ = propagate::FixedIncrements::new(q0, rule);
    let mut p = Printer {
        out: Csv::stdout(),
        every: args.every,
        last_printed: None,
    };
    let mut lines = Lines::new(io::stdin().lock());
    let exact = |q: UnitQuat<Q30>| q.to_f64().to_array();
    let mut k: u64 = 0; // samples consumed
    let mut last = q0; // the attitude after sample k - 1
    let result = (|| -> Result<(), Failure> {
        let stop = loop {
            let (n, v) = match next_sample::<f64, _>(&mut lines, &mut p.out, &args.sensor, args.dt)
            {
                Ok(Some(s)) => s,
                Ok(None) => break None,
                Err(Failure::Row(n, e)) => break Some(Failure::Row(n, e)),
                Err(e) => return Err(e),
            };
            match integ.push(v) {
                Ok(q) => last = q,
                // A value outside Q1.30 leaves the state as it was: end the record there.
                Err(e @ PropagateError::Quantize(_)) => {
                    break Some(stopped::<f64>(e, n, "after this sample"));
                }
                Err(e) => {
                    if k > 0 {
                        p.print_last(k - 1, exact(last))?;
                    }
                    return Err(stopped::<f64>(e, n, "after this sample"));
                }
            }
            if p.due(k) {
                p.print(k, exact(last))?;
            }
            k += 1;
        };
        if k > 0 {
            p.print_last(k - 1, exact(integ.flush()))?;
        }
        stop.map_or(Ok(()), Err)
    })();
    finish(result, &mut p)
}

/// Parses one `t,x,y,z` row of the time-column mode.
fn parse_timed_row(line: &str) -> Result<(f64, Vec3<f64>), String> {
    let parts: Vec<&str> = line.split(',').collect();
    if parts.len() != 4 {
        return Err(format!(
            "expected 4 comma-separated numbers t,x,y,z, found {}",
            parts.len()
        ));
    }
    let mut v = [0.0; 4];
    for (slot, p) in v.iter_mut().zip(&parts) {
        let p = p.trim();
        let x: f64 = p.parse().map_err(|_| format!("invalid number '{p}'"))?;
        if !x.is_finite() {
            return Err(format!("non-finite value '{p}'"));
        }
        *slot = x;
    }
    let [t, x, y, z] = v;
    Ok((t, Vec3::new(x, y, z)))
}

/// The clock of the time-column mode: timestamps in seconds, or a wrapping 32-bit microsecond
/// counter (`--time-wrap`) with the time unwrapped since its first value.
enum TimedClock {
    Seconds(SampleClock<f64>, f64),
    Counter(MicrosClock, u64),
}

impl TimedClock {
    /// Starts the first interval at the raw timestamp `t0`.
    fn restart(&mut self, t0: f64, n: u64) -> Result<(), Failure> {
        match self {
            TimedClock::Seconds(c, factor) => c.restart(Some(t0 * *factor)),
            TimedClock::Counter(c, unwrapped) => {
                let t = counter(t0).ok_or_else(|| {
                    Failure::Row(n, format!("--t0 {t0}: not a 32-bit counter value"))
                })?;
                c.restart(Some(t));
                *unwrapped = u64::from(t);
            }
        }
        Ok(())
    }
}

/// A raw timestamp as a 32-bit counter value (a whole number in `[0, 2^32)`).
fn counter(t: f64) -> Option<u32> {
    ((0.0..4_294_967_296.0).contains(&t) && t.fract() == 0.0).then_some(t as u32)
}

/// The time (s, unwrapped) and the elapsed time of a raw timestamp by the clock's policy: a
/// step, or the row error of a gap, a repeated or a backwards timestamp.
fn timed_step(clock: &mut TimedClock, raw: f64, n: u64) -> Result<(f64, Option<f64>), Failure> {
    let row = |e: String| Failure::Row(n, e);
    let (t, interval, nominal, max) = match clock {
        TimedClock::Seconds(c, factor) => {
            let t = raw * *factor;
            let i = c.interval(t).map_err(|e| row(format!("timestamp: {e}")))?;
            (t, i, c.nominal(), c.max_step())
        }
        TimedClock::Counter(c, unwrapped) => {
            let value = counter(raw)
                .ok_or_else(|| row(format!("timestamp {raw}: not a 32-bit counter value")))?;
            let i = c.interval(value);
            match i {
                Interval::First => *unwrapped = u64::from(value),
                Interval::Step(d) | Interval::Gap(d) => *unwrapped += u64::from(d),
                _ => {}
            }
            let i = match i {
                Interval::First => Interval::First,
                Interval::Step(d) => Interval::Step(f64::from(d) * 1e-6),
                Interval::Gap(d) => Interval::Gap(f64::from(d) * 1e-6),
                Interval::Repeated => Interval::Repeated,
                Interval::Backwards(d) => Interval::Backwards(f64::from(d) * 1e-6),
            };
            let to_s = |us: u32| f64::from(us) * 1e-6;
            (
                *unwrapped as f64 * 1e-6,
                i,
                to_s(c.nominal_us()),
                to_s(c.max_step_us()),
            )
        }
    };
    match interval {
        Interval::First => Ok((t, None)),
        Interval::Step(h) => Ok((t, Some(h))),
        Interval::Gap(h) => Err(row(format!(
            "gap: {h:e} s since the previous sample, more than --gap-factor {} times the nominal \
             {nominal:e} s (samples lost)",
            max / nominal
        ))),
        Interval::Repeated => Err(row("repeated timestamp".into())),
        Interval::Backwards(d) => Err(row(format!(
            "timestamp {d:e} s before the previous sample's"
        ))),
    }
}

/// The next `t,x,y,z` row (t raw, in the input's unit), skipping blank lines ([`next_row`]).
fn next_timed<R: io::Read>(
    lines: &mut Lines<R>,
    out: &mut Csv,
) -> Result<Option<(u64, f64, Vec3<f64>)>, Failure> {
    Ok(next_row(lines, out, parse_timed_row)?.map(|(n, (t, v))| (n, t, v)))
}

/// Rows read ahead to infer the nominal interval when `--dt` is not given: the intervals
/// between the first 17 timestamps (16 intervals; for increments `--t0` and the first 16 rows).
const NOMINAL_ROWS: usize = 17;

/// The rows of the time-column mode: the rows read ahead at the start (with the row error that
/// stopped the reading ahead, reported in its turn), then the rest of the input.
struct TimedRows<'a, R> {
    lines: &'a mut Lines<R>,
    ahead: VecDeque<Result<TimedRow, Failure>>,
}

/// A row of the time-column mode: line number, raw timestamp, the three numbers.
type TimedRow = (u64, f64, Vec3<f64>);

impl<R: io::Read> TimedRows<'_, R> {
    /// The next `t,x,y,z` row (t raw, in the input's unit), skipping blank lines.
    fn next(&mut self, out: &mut Csv) -> Result<Option<(u64, f64, Vec3<f64>)>, Failure> {
        match self.ahead.pop_front() {
            Some(r) => r.map(Some),
            None => next_timed(self.lines, out),
        }
    }

    /// Reads up to `n` rows ahead (fewer at the end of the input or at a bad row) and returns
    /// their line numbers and raw timestamps.
    fn read_ahead(&mut self, out: &mut Csv, n: usize) -> Result<Vec<(u64, f64)>, Failure> {
        let mut rows = Vec::new();
        while self.ahead.len() < n {
            match next_timed(self.lines, out) {
                Ok(Some(r)) => {
                    rows.push((r.0, r.1));
                    self.ahead.push_back(Ok(r));
                }
                Ok(None) => break,
                Err(e @ Failure::Row(..)) => {
                    self.ahead.push_back(Err(e));
                    break;
                }
                Err(e) => return Err(e),
            }
        }
        Ok(rows)
    }
}

/// The nominal interval (s) inferred from raw timestamps when `--dt` is not given: the median
/// of the intervals between consecutive ones (the mean of the two middle ones for an even
/// count), the intervals of a `--time-wrap` counter taken modulo 2^32 µs; `None` when there is
/// no interval, `Some` of a value that is not positive when the timestamps do not increase.
fn nominal_from(raw: &[f64], time_factor: f64, wrap: bool) -> Option<f64> {
    let mut d: Vec<f64> = raw
        .windows(2)
        .filter_map(|w| {
            if wrap {
                let (a, b) = (counter(w[0])?, counter(w[1])?);
                Some(f64::from(b.wrapping_sub(a)) * 1e-6)
            } else {
                Some((w[1] - w[0]) * time_factor)
            }
        })
        .collect();
    if d.is_empty() {
        return None;
    }
    d.sort_by(f64::total_cmp);
    let m = d.len() / 2;
    Some(if d.len() % 2 == 1 {
        d[m]
    } else {
        0.5 * (d[m - 1] + d[m])
    })
}

/// `--time-column`: increments over their own intervals (every rule, in the form for unequal
/// intervals) or rates at their own times (every method on the interpolant through the actual
/// times), in f64, f32 or (increments) Q1.30.
fn run_timed(args: &Args) -> Result<(), Failure> {
    let Some(timed) = &args.timed else {
        return Err(Failure::Usage("--time-column expected".into()));
    };
    let mut clip = timed.clip.map(|(limit, policy)| Clip::new(limit, policy));
    let [w, x, y, z] = args.q0;
    let q0 = UnitQuat::try_from_near_unit(Quat::new(w, x, y, z), 1e-3)
        .map_err(|e| Failure::Usage(format!("--q0: {e}: its norm must be within 1e-3 of 1")))?;
    let increments = matches!(args.algo, Algo::Increments(_));
    let t0 = match (increments, timed.t0) {
        (true, None) => return Err(Failure::Usage("--t0 is required".into())),
        (_, t0) => t0,
    };
    let mut p = Printer {
        out: Csv::stdout(),
        every: args.every,
        last_printed: None,
    };
    let mut lines = Lines::new(io::stdin().lock());
    let mut rows = TimedRows {
        lines: &mut lines,
        ahead: VecDeque::new(),
    };
    let nominal = match args.dt {
        Some(dt) => dt,
        None => {
            let ahead = rows.read_ahead(&mut p.out, NOMINAL_ROWS - usize::from(increments))?;
            let raw: Vec<f64> = t0
                .filter(|_| increments)
                .into_iter()
                .chain(ahead.iter().map(|r| r.1))
                .collect();
            match nominal_from(&raw, timed.time_factor, timed.wrap) {
                // No interval in the input: the nominal interval is never used.
                None => 1.0,
                Some(h) if h > 0.0 && h.is_finite() => h,
                Some(h) => {
                    let line = ahead.last().map_or(0, |r| r.0);
                    return finish(
                        Err(Failure::Row(
                            line,
                            format!(
                                "no --dt and the first {} timestamps give no nominal interval \
                                 (their median interval is {h:e} s): give --dt",
                                raw.len()
                            ),
                        )),
                        &mut p,
                    );
                }
            }
        }
    };
    let mut clock = if timed.wrap {
        let nominal_us = (nominal * 1e6).round();
        if !(1.0..4_294_967_296.0).contains(&nominal_us) || timed.gap_factor >= 4_294_967_296.0 {
            return Err(Failure::Usage(format!(
                "--dt {nominal}: with --time-wrap a whole number of microseconds >= 1"
            )));
        }
        let c = MicrosClock::try_new(nominal_us as u32, timed.gap_factor as u32).map_err(|e| {
            Failure::Usage(format!(
                "--dt, --gap-factor: {e} (the gap threshold must stay below 2^31 us)"
            ))
        })?;
        TimedClock::Counter(c, 0)
    } else {
        let c = SampleClock::try_with_gap_factor(nominal, timed.gap_factor)
            .map_err(|e| Failure::Usage(format!("--dt, --gap-factor: {e}")))?;
        TimedClock::Seconds(c, timed.time_factor)
    };
    if let Some(t0) = t0.filter(|_| increments) {
        clock.restart(t0, 0).map_err(|e| match e {
            Failure::Row(_, m) => Failure::Usage(m),
            e => e,
        })?;
    }
    let mut run = TimedRun {
        rows,
        p: &mut p,
        clock: &mut clock,
        clip: &mut clip,
        sensor: &args.sensor,
    };
    let result = match (args.algo, args.arith) {
        (Algo::Increments(rule), Arith::F64) => run.increments(q0, rule),
        (Algo::Increments(rule), Arith::F32) => {
            q0_in::<f32>(args.q0).and_then(|q| run.increments(q, rule))
        }
        (Algo::Increments(rule), Arith::Fixed) => UnitQuat::<Q30>::try_from_f64(q0)
            .map_err(|e| Failure::Usage(format!("--q0: {e}")))
            .and_then(|q| run.increments(CarriedAttitude::new(q), rule)),
        (Algo::Rates(m), Arith::F64) => run.rates(q0, m),
        (Algo::Rates(m), Arith::F32) => q0_in::<f32>(args.q0).and_then(|q| run.rates(q, m)),
        (Algo::Rates(_), Arith::Fixed) => Err(Failure::Usage(
            "--fixed supports --input increments only".into(),
        )),
    };
    if let Some(c) = &clip
        && c.count > 0
    {
        let what = if c.guard.policy() == ClipPolicy::HoldLast {
            "each clipped axis held at its last unclipped rate"
        } else {
            "passed as read"
        };
        eprintln!(
            "note: {} samples had an axis at the full scale {} ({what})",
            c.count,
            c.guard.limit().limit()
        );
    }
    finish(result, &mut p)
}

/// `--q0` in `T` (normalised exactly there, as the fixed-interval runs do).
fn q0_in<T: Real>(q0: [f64; 4]) -> Result<UnitQuat<T>, Failure> {
    let [w, x, y, z] = q0.map(T::from_f64);
    UnitQuat::try_from_near_unit(Quat::new(w, x, y, z), T::from_f64(1e-3))
        .map_err(|e| Failure::Usage(format!("--q0: {e}: its norm must be within 1e-3 of 1")))
}

/// A step's rotation within the methods' validity limit, else a row error.
fn within_limit(angle: f64, n: u64) -> Result<(), Failure> {
    if angle <= MAX_STEP_ANGLE {
        return Ok(());
    }
    Err(Failure::Row(
        n,
        format!("the sample turns the body {angle:.3e} rad in one interval: beyond half a turn"),
    ))
}

/// The coefficients `c[i][j]` (`i < j`) of the `N`-sample coning rule on unequal intervals
/// (`N = h.len()`, 1 to 4): `φ = Σθᵢ + Σ_{i<j} c[i][j] θᵢ × θⱼ`, the rotation vector to second
/// order of the rate polynomial of degree `N − 1` whose integrals over the intervals `h` are the
/// increments (Bortz: `φ = ∫ω + ½ ∫ θ(t) × ω(t) dt`, `θ(t)` the integral from the group's
/// start). In the time normalised by the group's length, with `M[i][k] = ∫ uᵏ` over interval
/// `i`, `G = M⁻¹` and `B[k][l] = 1/((k+1)(k+l+2))`: `C = ½ Gᵀ B G`, `c[i][j] = C[i][j] − C[j][i]`.
/// At equal intervals: 2/3 for two samples (the library's 2-sample rule; on unequal ones its
/// `(h₁+h₂)²/(6 h₁ h₂)`), 57/80, 33/80, 57/80 for three and 736/945, 334/945, 526/945,
/// 218/315, 334/945, 736/945 for four (the polynomial rules: the library's 3- and 4-sample rules
/// are Miller's, tuned for pure coning, with no unequal-interval form). `None` if an interval
/// is not positive.
fn unequal_coning_coefficients(h: &[f64]) -> Option<[[f64; 4]; 4]> {
    let n = h.len();
    if n == 0 || n > 4 || h.iter().any(|x| x.is_nan() || *x <= 0.0) {
        return None;
    }
    let total: f64 = h.iter().sum();
    let mut u = [0.0; 5];
    for i in 0..n {
        u[i + 1] = u[i] + h[i] / total;
    }
    // [M | I] reduced to [I | G] by Gauss–Jordan elimination with partial pivoting.
    let mut a = [[0.0f64; 8]; 4];
    for (i, row) in a.iter_mut().enumerate().take(n) {
        for (k, m) in row.iter_mut().enumerate().take(n) {
            *m = (u[i + 1].powi(k as i32 + 1) - u[i].powi(k as i32 + 1)) / (k + 1) as f64;
        }
        row[n + i] = 1.0;
    }
    for c in 0..n {
        let p = (c..n).max_by(|&x, &y| a[x][c].abs().total_cmp(&a[y][c].abs()))?;
        a.swap(c, p);
        let pivot = a[c][c];
        if pivot == 0.0 {
            return None;
        }
        for v in a[c].iter_mut() {
            *v /= pivot;
        }
        for r in 0..n {
            if r != c {
                let f = a[r][c];
                let row = a[c];
                for (x, y) in a[r].iter_mut().zip(row) {
                    *x -= f * y;
                }
            }
        }
    }
    let g = |k: usize, i: usize| a[k][n + i];
    let b = |k: usize, l: usize| 1.0 / ((k + 1) * (k + l + 2)) as f64;
    let big_c = |i: usize, j: usize| -> f64 {
        let mut s = 0.0;
        for k in 0..n {
            for l in 0..n {
                s += g(k, i) * b(k, l) * g(l, j);
            }
        }
        0.5 * s
    };
    let mut c = [[0.0; 4]; 4];
    for (i, row) in c.iter_mut().enumerate().take(n) {
        for (j, cij) in row.iter_mut().enumerate().take(n).skip(i + 1) {
            *cij = big_c(i, j) - big_c(j, i);
        }
    }
    c.iter().flatten().all(|x| x.is_finite()).then_some(c)
}

/// The attitude of the time-column mode, in the arithmetic of a run: a plain `UnitQuat` in f64
/// or f32, or the Q1.30 [`CarriedAttitude`] of the firmware.
trait TimedAttitude: Copy {
    /// The number type of the increments and the coning terms.
    type N: Ring + Copy;
    /// An increment (rad, after the sensor model) in the run's numbers, or the row error.
    fn increment(v: Vec3<f64>, quant: &mut IncrementQuantizer<30>)
    -> Result<Vec3<Self::N>, String>;
    /// A coefficient in the run's numbers, or the row error.
    fn coefficient(c: f64) -> Result<Self::N, String>;
    /// `q ⊗ exp(φ)`, renormalised (the run's policy).
    fn rotated(self, phi: Vec3<Self::N>) -> Self;
    /// `q ⊗ exp(sum + lever × last)`, renormalised (Q1.30: with the coning residual carried).
    fn rotated_coning(self, terms: ConingTerms<Self::N>) -> Self {
        self.rotated(terms.rotation_vector())
    }
    /// The attitude as f64 components for the output, and whether it is finite.
    fn components(&self) -> [f64; 4];
    /// Prints one component as the run's type does (shortest round trip).
    fn print(&self, p: &mut Printer, k: u64, t: f64) -> io::Result<()>;
}

impl<T: Real + Debug> TimedAttitude for UnitQuat<T> {
    type N = T;
    fn increment(v: Vec3<f64>, _: &mut IncrementQuantizer<30>) -> Result<Vec3<T>, String> {
        Ok(Vec3::from_array(v.to_array().map(T::from_f64)))
    }
    fn coefficient(c: f64) -> Result<T, String> {
        Ok(T::from_f64(c))
    }
    fn rotated(self, phi: Vec3<T>) -> Self {
        (self * UnitQuat::exp_unchecked(phi)).renormalize()
    }
    fn rotated_coning(self, terms: ConingTerms<T>) -> Self {
        self.mul_exp_unchecked(terms, Normalization::Fast)
            .renormalize()
    }
    fn components(&self) -> [f64; 4] {
        self.to_array().map(T::to_f64)
    }
    fn print(&self, p: &mut Printer, k: u64, t: f64) -> io::Result<()> {
        p.last_printed = Some(k);
        let [w, x, y, z] = self.to_array();
        writeln!(p.out, "{k},{t:?},{w:?},{x:?},{y:?},{z:?}")?;
        p.out.row_done()
    }
}

impl TimedAttitude for CarriedAttitude<30> {
    type N = Q30;
    fn increment(v: Vec3<f64>, quant: &mut IncrementQuantizer<30>) -> Result<Vec3<Q30>, String> {
        quant
            .try_quantize(v)
            .map_err(|e| format!("{e} (Q1.30 holds |value| < 2 rad)"))
    }
    fn coefficient(c: f64) -> Result<Q30, String> {
        Q30::try_from_f64(c).map_err(|_| {
            format!("the coning coefficient {c:e} of these intervals is outside Q1.30 (|c| < 2)")
        })
    }
    fn rotated(self, phi: Vec3<Q30>) -> Self {
        self.mul_exp_unchecked(phi, Normalization::Fast)
    }
    fn rotated_coning(self, terms: ConingTerms<Q30>) -> Self {
        self.mul_exp_unchecked(terms, Normalization::Fast)
    }
    fn components(&self) -> [f64; 4] {
        self.attitude().to_f64().to_array()
    }
    fn print(&self, p: &mut Printer, k: u64, t: f64) -> io::Result<()> {
        p.last_printed = Some(k);
        let [w, x, y, z] = self.components();
        writeln!(p.out, "{k},{t:?},{w:?},{x:?},{y:?},{z:?}")?;
        p.out.row_done()
    }
}

/// The state of a time-column run.
struct TimedRun<'a, 'l, R> {
    rows: TimedRows<'l, R>,
    p: &'a mut Printer,
    clock: &'a mut TimedClock,
    clip: &'a mut Option<Clip>,
    sensor: &'a Sensor,
}

impl<R: io::Read> TimedRun<'_, '_, R> {
    /// The next row with its time and interval, through the clock's policy, the clipping check
    /// and the sensor model (`increment`: the row is an increment over its interval). `Ok(None)`
    /// at the end; a row error ends the record.
    #[allow(clippy::type_complexity)]
    fn next(
        &mut self,
        increment: bool,
    ) -> Result<Option<(u64, f64, Option<f64>, Vec3<f64>)>, Failure> {
        let Some((n, raw_t, raw)) = self.rows.next(&mut self.p.out)? else {
            return Ok(None);
        };
        let (t, h) = timed_step(self.clock, raw_t, n)?;
        let h_inc = if increment {
            Some(h.ok_or_else(|| Failure::Row(n, "no interval start (--t0)".into()))?)
        } else {
            None
        };
        let raw = match self.clip.as_mut() {
            Some(c) => c.filter(raw, h_inc).map_err(|e| Failure::Row(n, e))?,
            None => raw,
        };
        Ok(Some((n, t, h, self.sensor.apply(raw, h_inc))))
    }

    /// Increments over their own intervals: `exp`; `coning1` with the previous interval's
    /// correction `h²/(6 h₋₁ (h₋₁ + h)) θ₋₁ × θ` (1/12 when equal); `coningN` one update per `N`
    /// increments by the rule of [`unequal_coning_coefficients`] (coning2 in the library's
    /// closed form); a row inside a group, and the last row of an unfinished group, apply the
    /// pending increments by the rule of their number (one: an exponential), not fed back.
    fn increments<A: TimedAttitude>(&mut self, q0: A, rule: ConingRule) -> Result<(), Failure> {
        let group = rule.samples_per_update();
        let mut quant = IncrementQuantizer::<30>::new();
        let mut q = q0;
        let mut pending: Vec<(Vec3<A::N>, f64)> = Vec::with_capacity(4);
        let mut previous: Option<(Vec3<A::N>, f64)> = None;
        let mut k: u64 = 0;
        let mut last = None; // (k, t, attitude) of the latest sample
        let coefficient = |c: f64, n: u64| A::coefficient(c).map_err(|e| Failure::Row(n, e));
        // The pending increments by the rule of their number.
        let apply = |q: A, pending: &[(Vec3<A::N>, f64)], n: u64| -> Result<A, Failure> {
            Ok(match pending {
                [] => q,
                [(v, _)] => q.rotated(*v),
                [(v1, h1), (v2, h2)] => q.rotated_coning(two_sample_unequal_terms(
                    *v1,
                    *v2,
                    coefficient(two_sample_unequal_coefficient(*h1, *h2), n)?,
                )),
                _ => {
                    let hs: Vec<f64> = pending.iter().map(|s| s.1).collect();
                    let c = unequal_coning_coefficients(&hs)
                        .ok_or_else(|| Failure::Row(n, "interval not positive".into()))?;
                    let mut phi = pending[0].0;
                    for (j, (vj, _)) in pending.iter().enumerate().skip(1) {
                        phi += *vj;
                        for (i, (vi, _)) in pending.iter().enumerate().take(j) {
                            phi += vi.cross(*vj).scale(coefficient(c[i][j], n)?);
                        }
                    }
                    q.rotated(phi)
                }
            })
        };
        let stop = loop {
            let (n, t, h, v) = match self.next(true) {
                Ok(Some(r)) => r,
                Ok(None) => break None,
                Err(e @ Failure::Row(..)) => break Some(e),
                Err(e) => return Err(e),
            };
            let h = h.unwrap_or(0.0);
            if let Err(e) = within_limit(v.norm(), n) {
                break Some(e);
            }
            let v = match A::increment(v, &mut quant) {
                Ok(v) => v,
                Err(e) => break Some(Failure::Row(n, e)),
            };
            let shown = match rule {
                ConingRule::Exp => {
                    q = q.rotated(v);
                    Ok(q)
                }
                ConingRule::OnePlusPrevious => {
                    let terms = match previous {
                        Some((v1, h1)) => {
                            coefficient(h * h / (6.0 * h1 * (h1 + h)), n).map(|c| ConingTerms {
                                sum: v,
                                lever: v1.scale(c),
                                last: v,
                            })
                        }
                        None => Ok(ConingTerms {
                            sum: v,
                            lever: Vec3::ZERO,
                            last: v,
                        }),
                    };
                    previous = Some((v, h));
                    terms.map(|terms| {
                        q = q.rotated_coning(terms);
                        q
                    })
                }
                _ => {
                    pending.push((v, h));
                    let r = apply(q, &pending, n);
                    if pending.len() == group {
                        pending.clear();
                        if let Ok(qn) = r {
                            q = qn;
                        }
                    }
                    r
                }
            };
            let shown = match shown {
                Ok(s) => s,
                Err(e) => break Some(e),
            };
            if !shown.components().iter().all(|c| c.is_finite()) {
                break Some(Failure::Row(n, "the attitude is not finite".into()));
            }
            if self.p.due(k) {
                shown.print(self.p, k, t)?;
            }
            last = Some((k, t, shown));
            k += 1;
        };
        if let Some((k, t, q)) = last
            && self.p.last_printed != Some(k)
        {
            q.print(self.p, k, t)?;
        }
        stop.map_or(Ok(()), Err)
    }

    /// Rates at their own times: one step of `method` per interval on the Lagrange interpolant
    /// through the samples `k−3 … k` (the first three intervals with samples `0 … 3`; a record of
    /// 2 or 3 samples, the linear or quadratic interpolant), in the run's type `T`.
    fn rates<T: Real + Debug>(
        &mut self,
        q0: UnitQuat<T>,
        method: RateMethod,
    ) -> Result<(), Failure> {
        // The last four samples (t, ω, line).
        let mut win: Vec<(f64, Vec3<T>, u64)> = Vec::with_capacity(5);
        let mut q = q0;
        let mut k: u64 = 0; // samples read
        let mut last: Option<(u64, f64, UnitQuat<T>)> = None;
        // Integrates the interval ending at window index `end` (≥ 1) with the whole window.
        let step = |q: UnitQuat<T>,
                    win: &[(f64, Vec3<T>, u64)],
                    end: usize|
         -> Result<UnitQuat<T>, Failure> {
            let (t_a, w_a, _) = win[end - 1];
            let (t_b, w_b, n) = win[end];
            within_limit(w_a.norm().max(w_b.norm()).to_f64() * (t_b - t_a), n)?;
            let base = win[0].0;
            let ts: Vec<T> = win.iter().map(|s| T::from_f64(s.0 - base)).collect();
            let ws: Vec<Vec3<T>> = win.iter().map(|s| s.1).collect();
            let (a, b) = (ts[end - 1], ts[end]);
            let q = match (ts.as_slice(), ws.as_slice()) {
                (&[t0, t1], &[w0, w1]) => rate_step(method, q, &[t0, t1], &[w0, w1], a, b),
                (&[t0, t1, t2], &[w0, w1, w2]) => {
                    rate_step(method, q, &[t0, t1, t2], &[w0, w1, w2], a, b)
                }
                (&[t0, t1, t2, t3], &[w0, w1, w2, w3]) => {
                    rate_step(method, q, &[t0, t1, t2, t3], &[w0, w1, w2, w3], a, b)
                }
                _ => Some(q),
            };
            match q {
                Some(q) if q.to_array().iter().all(|c| c.is_finite()) => Ok(q),
                _ => Err(Failure::Row(n, "the attitude is not finite".into())),
            }
        };
        let print = |p: &mut Printer, k: u64, t: f64, q: &UnitQuat<T>| q.print(p, k, t);
        let mut emit = |p: &mut Printer, idx: u64, t: f64, q: UnitQuat<T>| -> io::Result<()> {
            if p.due(idx) {
                print(p, idx, t, &q)?;
            }
            last = Some((idx, t, q));
            Ok(())
        };
        let stop = loop {
            let (n, t, _, v) = match self.next(false) {
                Ok(Some(r)) => r,
                Ok(None) => break None,
                Err(e @ Failure::Row(..)) => break Some(e),
                Err(e) => return Err(e),
            };
            win.push((t, Vec3::from_array(v.to_array().map(T::from_f64)), n));
            if win.len() > 4 {
                win.remove(0);
            }
            let p = &mut *self.p;
            let r = match k {
                0 => emit(p, 0, t, q).map_err(Failure::Io),
                1 | 2 => Ok(()),
                3 => (1..=3).try_for_each(|j| {
                    q = step(q, &win, j)?;
                    emit(p, j as u64, win[j].0, q).map_err(Failure::Io)
                }),
                _ => step(q, &win, 3).and_then(|qn| {
                    q = qn;
                    emit(p, k, t, q).map_err(Failure::Io)
                }),
            };
            if let Err(e) = r {
                break Some(e);
            }
            k += 1;
        };
        // A record of 2 or 3 samples: the intervals wait for the end.
        if (2..=3).contains(&k) {
            for j in 1..win.len() {
                q = step(q, &win, j)?;
                emit(self.p, j as u64, win[j].0, q)?;
            }
        }
        if let Some((k, t, q)) = last
            && self.p.last_printed != Some(k)
        {
            print(self.p, k, t, &q)?;
        }
        stop.map_or(Ok(()), Err)
    }
}

/// One step of `method` from `a` to `b` on the interpolant through the window, renormalised
/// exactly; `None` when RK4's quaternion cannot be normalised.
fn rate_step<T: Real, const M: usize>(
    method: RateMethod,
    q: UnitQuat<T>,
    ts: &[T; M],
    ws: &[Vec3<T>; M],
    a: T,
    b: T,
) -> Option<UnitQuat<T>> {
    Some(match method {
        RateMethod::Magnus4 => magnus4_step_unequal(q, ts, ws, a, b).renormalize(),
        RateMethod::Cf4 => cf4_step_unequal(q, ts, ws, a, b).renormalize(),
        RateMethod::Rk4 => rk4_step_unequal(q.into_quat(), ts, ws, a, b)
            .try_normalize()
            .ok()?,
    })
}

/// Flushes the rows; a closed stdout is a quiet end, as if the input ended there.
fn finish(result: Result<(), Failure>, p: &mut Printer) -> Result<(), Failure> {
    let flushed = p.out.flush();
    match (result, flushed) {
        (Err(Failure::Io(e)), _) | (Ok(()), Err(e)) if stream::is_closed_pipe(&e) => Ok(()),
        (Err(e), _) => Err(e),
        (Ok(()), Err(e)) => Err(Failure::Io(e)),
        (Ok(()), Ok(())) => Ok(()),
    }
}

fn main() -> ExitCode {
    let args = match CLI
        .command_line()
        .and_then(|f| arguments(&f).map_err(|e| flags::usage_error(&e)))
    {
        Ok(a) => a,
        Err(status) => return status,
    };
    let r = match (args.arith, args.compensated) {
        _ if args.timed.is_some() => run_timed(&args),
        (Arith::F64, false) => run::<f64, UnitQuat<f64>>(&args),
        (Arith::F64, true) => run::<f64, CompensatedAttitude<f64>>(&args),
        (Arith::F32, false) => run::<f32, UnitQuat<f32>>(&args),
        (Arith::F32, true) => run::<f32, CompensatedAttitude<f32>>(&args),
        (Arith::Fixed, _) => run_fixed(&args),
    };
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::Usage(e)) => flags::usage_error(&e),
        Err(Failure::Row(n, e)) => {
            flags::line_error(n, &e);
            ExitCode::FAILURE
        }
        Err(Failure::Io(e)) => {
            flags::error(&e.to_string());
            ExitCode::FAILURE
        }
    }
}
