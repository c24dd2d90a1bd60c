//! `estimate`: attitude and gyroscope bias from an IMU log (`gyrostat::estimation::Estimator`).
//!
//! ```text
//! estimate [--6d | --9d] [--f32] [--mode full|light] [--frame enu|ned] [--gyro-unit U] [--accel-unit U]
//!     [--mag-unit U] [--time-unit U] [--truth] [--plot FILE.svg] [--params-out FILE]
//!     [--set NAME=VALUE]... [FILE]
//! ```
//! Run with `--help` for the full description of the input and output formats.

mod plot;

use std::fmt::Debug;
use std::io::{self, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use gyrostat::Real;
use gyrostat::estimation::{EarthFrame, Estimator, Mode, Params, SensorUse};
use gyrostat_pipeline::broad::{Metric, Score, errors};
use gyrostat_pipeline::estimate::{self as pipeline, Calibration, HEADER, Options, Run, Step};
use gyrostat_tools::calibration::{self, CalibrationFile};
use gyrostat_tools::flags::{self, Cli, Flag, Flags};
use gyrostat_tools::imu_log::{self, Layout, OpenError, Scales, parse_row};
use gyrostat_tools::stream::{self, Csv, Lines};
use gyrostat_tools::units::{AccelUnit, GyroUnit, MagUnit, TimeUnit};

const CLI: Cli = Cli {
    name: "estimate",
    help: HELP,
    flags: &[
        Flag::switch("--6d"),
        Flag::switch("--9d"),
        Flag::switch("--f32"),
        Flag::value("--mode"),
        Flag::value("--frame"),
        Flag::value("--gyro-unit"),
        Flag::value("--accel-unit"),
        Flag::value("--mag-unit"),
        Flag::value("--time-unit"),
        Flag::switch("--truth"),
        Flag::switch("--skip-bad-rows"),
        Flag::value("--plot"),
        Flag::value("--calibration"),
        Flag::value("--params"),
        Flag::value("--params-out"),
        Flag::repeated("--set"),
    ],
};

const HELP: &str = "\
estimate: attitude and gyroscope bias from an IMU log (gyrostat's attitude estimator)

USAGE:
    estimate [--6d | --9d] [--f32] [--mode full|light] [--frame enu|ned]
             [--gyro-unit rad/s|deg/s]
             [--accel-unit m/s^2|g] [--mag-unit uT|nT|G|any] [--time-unit s|ms|us]
             [--calibration FILE] [--params FILE] [--truth] [--skip-bad-rows]
             [--plot FILE.svg] [--params-out FILE]
             [--set NAME=VALUE]... [FILE]

    Reads FILE (standard input without FILE, or with FILE `-`); gzip-compressed input (BROAD's
    .csv.gz files) is recognised by its first bytes and decompressed. Flags take their value as
    the next argument or after `=`; a flag given twice is an error (except --set).

INPUT: CSV, one sample per line, blank lines skipped (they count for line numbers).
    With a header line (the first line that is not all numbers), columns are found by name and
    others are ignored:
        time           t | t_s (s) | Time (s)
        gyroscope      gx,gy,gz | gyr_x_rad_s,... (rad/s) | Gyroscope X (deg/s),...
        accelerometer  ax,ay,az | acc_x_m_s2,... (m/s^2) | Accelerometer X (g),...
        magnetometer   mx,my,mz | mag_x_uT,... (uT) | Magnetometer X (uT),...      (optional)
        reference      qw,qx,qy,qz | opt_qw,...       (optional, read with --truth only)
        movement       movement  (0/1, BROAD's scored phase; optional, --truth only)
    (The short names, BROAD's, and the x-io Fusion log's.) A unit in a column's
    name is the data's unit: a unit flag that contradicts it is an error.
    Without a header, the fields are positional: t,gx,gy,gz,ax,ay,az (7 fields),
    + mx,my,mz (10), + qw,qx,qy,qz after them (11 or 14).
    Every row has as many fields as the header (or the first row). All three magnetometer
    fields of a row empty: no magnetometer sample in that row. Reference fields empty (qw
    empty): no reference in that row. The sensor frame is the data's; the estimator takes the
    accelerometer's specific force (+9.8 m/s^2 up at rest), not gravity.

OPTIONS:
    --6d, --9d     without / with the magnetometer; default: --9d when the input has
                   magnetometer columns, else --6d (--9d without them is an error)
    --f32          run the estimator in f32 (inputs, after the unit conversion, rounded to
                   f32; the steps are differences of the time stamps taken in f64); the output
                   prints the f32 values
    --mode M       full (default: every part of the filter on every sample) or light (the
                   prediction every sample, the covariance and the corrections every 25 ms,
                   a fixed magnetometer delay; about a fifth of the cost; --set
                   light_period=S selects light with another correction period)
    --frame F      the earth frame of the output attitude: enu (default: x east, y magnetic
                   north, z up; BROAD's frame: its reference rotates the resting accelerometer
                   onto +z and the magnetometer's horizontal part onto +y) or ned (x magnetic
                   north, y east, z down)
    --gyro-unit    rad/s (default) or deg/s
    --accel-unit   m/s^2 (default) or g (9.80665 m/s^2)
    --mag-unit     uT, nT, G or any (default): the values are converted to uT before the
                   estimator. The estimator uses only the field's direction and its norm
                   relative to a reference it learns from the data, so the unit does not change
                   the estimate (beyond rounding); the flag states the data's unit and is
                   checked against a unit-named column (mag_x_uT).
    --time-unit    s (default), ms or us: the unit of the time stamps
    --truth        compare with the reference columns (required): prints BROAD's metric to
                   stderr, `truth: total X deg, heading Y deg, inclination Z deg, n = N`: the RMS
                   of the angle of q_err = q_est * inv(q_ref) (earth frame), of its heading part
                   2 atan|z/w| and of its inclination part 2 acos sqrt(w^2 + z^2), over the rows
                   with a reference and movement == 1 (every row with a reference when there is
                   no movement column); computed from the numbers as printed, exactly as BROAD's
                   score.py computes it from the output (`, MISSING K` when K scored rows have no
                   estimate). The reference is an attitude sensor -> the output's earth frame.
                   With --6d only the inclination is meaningful (the heading is free).
    --calibration FILE
                   the sensor model of FILE (the format `propagate --calibration` reads:
                   gyro_* and accel_* give corrected = M diag(s) (raw - b), mag_* give
                   corrected = S (raw - h)), applied to every sample after the unit conversion,
                   in f64, before the estimator; keys a file leaves out are identities.
    --skip-bad-rows
                   a row whose time stamp or gyroscope value is not finite (nan, inf, or
                   beyond the f32 range with --f32; a logger's glitch) becomes a gap instead
                   of ending the run: its output row repeats the state with the flags
                   `skipped`, and the next good row propagates over the whole interval since
                   the last good one (that step is checked as any other). At the end one line
                   on stderr counts the skipped rows and names the first.
    --plot FILE    also write an SVG plot (the folder must exist: checked before the run): the estimate's heading (2 atan2(qz, qw)) and
                   inclination (2 acos sqrt(qw^2 + qz^2), the tilt of the sensor's z axis),
                   with the reference's when --truth; the error against the reference (total,
                   heading, inclination; --truth); the bias estimate; the rest and
                   disturbance flags. About 2000 points per curve (each flag: whether it was
                   set anywhere in the rows a point stands for).
    --params FILE  the estimator's parameters from a parameter file (the format of
                   gyrostat::estimation::params_text: `name = value  # comment` per line,
                   names as for --set, SI units, `rate_rule = NAME` for the rate rule; the
                   characterisation tool writes it; an unknown name or rule, a repeated name
                   or a bad number is `error: --params: FILE: line N: reason`, status 2);
                   names it does not give keep their defaults; --set applies after it
    --params-out FILE
                   after the run, write the magnetometer's delay behind the gyroscope that the
                   full mode estimated (9D, --mode full, mag_delay_estimation_time > 0) as a
                   parameter file: `mag_delay = D` and `mag_delay_estimation_time = 0`, with
                   comments (the log, the seconds of rotation the estimate rests on). Given to
                   --params of another run (appended to characterize's --params file, say), it
                   makes the light mode, which does not estimate the delay, use this sensor's
                   instead of its fixed default (Mode::LIGHT_MAG_DELAY, 9.25 ms), and the full
                   mode use it from the first sample. The log needs at least
                   mag_delay_estimation_time (10 s) of rotation faster than
                   field.new_field_min_rate in an undisturbed field: with less, no file is
                   written and the run ends with `error: --params-out: ...` (status 1, the
                   rows already written). The folder must exist (checked before the run).
                   The estimate averages over about the last mag_delay_estimation_time of
                   that rotation: for a measurement, a log with a minute or more of turning and
                   --set mag_delay_estimation_time=30 scatter less (BENCHMARKS.md, \"The light
                   mode's magnetometer delay from the sensor\").
    --set NAME=VALUE  an estimator parameter (gyrostat::estimation::Params; SI units, angles
                   in rad; a value ending in deg or deg/s is converted): gains=kalman,
                   heading_time_constant (complementary gains), light_period (light mode, s),
                   rate_rule (how rate samples become a step's rotation: trapezoid, magnus4,
                   cf4; default: the library's, Params::rate_rule),
                   gyro_noise_density,
                   gyro_scale_noise, gyro_bias_initial, gyro_bias_stability, gyro_bias_time,
                   gyro_bias_max, gyro_range, gyro_delay, accel_range, accel_time_constant,
                   accel_tilt_noise, accel_correlation_time, accel_reject, mag_heading_noise,
                   mag_correlation_time, mag_delay, mag_delay_estimation_time,
                   mag_hard_iron_time,
                   mag_disturbance_weight, field.norm, field.dip,
                   field.reference_time_constant, field.min_undisturbed,
                   field.new_field_time, field.new_field_min_rate, rest.time_constant,
                   rest.gyro, rest.accel, rest.max_bias, rest.min_duration, rest_bias_noise.
                   Repeatable.
    --help         print this text

OUTPUT (stdout): the header `t,qw,qx,qy,qz,bx,by,bz,rest,gyro,accel,mag,heading`, then one row per
    input row: `t` as written in the input, the attitude (scalar first, sensor -> earth:
    v_earth = q v q*) and the gyroscope bias estimate (rad/s, sensor frame; subtract it from
    the rate) after that row's update, then what the update did: rest 1 when the sensor was at
    rest (its mean rate measured the bias); gyro `used` or `saturated` (beyond --set
    gyro_range: clipped); accel and mag `used`, `disturbed` (rejected or, for the field,
    down-weighted: the low-passed specific force far from gravity, a field whose norm or dip
    differs from the reference), `nonfinite` or `saturated` or `zero` (ignored), mag `absent`
    (6D or an empty field); heading `ok` when the heading rests on a confirmed magnetic
    reference (the field has agreed with the reference learned from it), `unsure` while it
    does not yet (9D: the first field samples, or a first field sample taken in a disturbed
    field, whose wrong heading lasts until the true field replaces the reference, seen while
    the sensor turns for field.new_field_time), `none` in 6D (no magnetometer: the heading
    is the gyroscope's, from zero). Numbers in the shortest form that round-trips to the same f64 (f32
    with --f32). The first row with a usable accelerometer sample initialises the attitude
    (TRIAD from gravity and the field; from gravity alone in 6D, heading zero); rows before it
    print nan for the attitude and the bias. The step of each update is the difference of its
    time stamp and the previous row's. The first row has no step: no row propagates before
    the attitude is initialised, so the rate of the rows up to that one is not checked
    against the half-turn limit (a log may start while the sensor turns fast).

ERRORS (stderr; the rows before them are kept):
    error: line N: reason    exit status 1, the run stops there: a row with the wrong number
        of fields, a field that is not a number, a non-finite time stamp or gyroscope value, a
        time stamp not after the previous one, a step longer than 1000 s, a rate turning more
        than half a turn in one step, a line that is not UTF-8 text; a header without the time,
        gyroscope or accelerometer columns. No metric and no plot after an error.
    error: reason            a bad command line (also --9d without magnetometer columns,
        --truth without reference columns, a unit flag contradicting a column name): exit
        status 2, no output; an unreadable FILE or a --plot FILE whose folder does not
        exist: exit status 1, no output.
    When stdout is closed early (a pipe into `head`), the run stops quietly with status 0.
";

/// Which sensors the run uses.
#[derive(Clone, Copy, PartialEq)]
enum Sensors {
    Auto,
    SixD,
    NineD,
}

struct Args {
    file: Option<PathBuf>,
    sensors: Sensors,
    f32: bool,
    truth: bool,
    skip_bad_rows: bool,
    plot: Option<PathBuf>,
    params_out: Option<PathBuf>,
    calibration: Option<CalibrationFile>,
    gyro: Option<GyroUnit>,
    accel: Option<AccelUnit>,
    mag: Option<MagUnit>,
    time: Option<TimeUnit>,
    params: Params<f64>,
}

/// The arguments of a run, from the flags given.
fn arguments(f: &Flags, operands: Vec<String>) -> Result<Args, String> {
    let sensors = match (f.switch("--6d"), f.switch("--9d")) {
        (true, true) => return Err("--6d and --9d exclude each other".into()),
        (true, false) => Sensors::SixD,
        (false, true) => Sensors::NineD,
        (false, false) => Sensors::Auto,
    };
    let frame = match f.value("--frame").map(str::trim) {
        None => EarthFrame::Enu,
        Some(name) => name
            .parse()
            .map_err(|_| format!("--frame must be enu or ned, got '{name}'"))?,
    };
    let mode = match f.value("--mode").map(str::trim) {
        None => Mode::Full,
        Some(name) => name
            .parse()
            .map_err(|_| format!("--mode must be full or light, got '{name}'"))?,
    };
    let mut params = Params::<f64>::defaults_of(frame, mode);
    if let Some(path) = f.value("--params") {
        let text = std::fs::read_to_string(path).map_err(|e| format!("--params: {path}: {e}"))?;
        params
            .set_from_text(&text)
            .map_err(|e| format!("--params: {path}: {e}"))?;
    }
    for kv in f.values("--set") {
        let (name, value) = kv
            .split_once('=')
            .ok_or_else(|| format!("--set: expected NAME=VALUE, got '{kv}'"))?;
        pipeline::set_param(&mut params, name, value).map_err(|e| format!("--set: {e}"))?;
    }
    // The parameters are checked here, so that a bad one is a usage error before any input.
    Estimator::try_new(params)
        .map_err(|e| format!("--set/--params: the parameters are invalid: {e}"))?;
    let params_out = f.value("--params-out").map(PathBuf::from);
    if params_out.is_some() {
        if params.mode != Mode::Full {
            return Err(
                "--params-out: the light mode does not estimate the magnetometer's \
                        delay: run the full mode (--mode full, no light_period)"
                    .into(),
            );
        }
        if params.mag_delay_estimation_time <= 0.0 {
            return Err(
                "--params-out: mag_delay_estimation_time is 0: the delay is not \
                        estimated (it stays mag_delay)"
                    .into(),
            );
        }
        if sensors == Sensors::SixD {
            return Err(
                "--params-out: the magnetometer's delay needs the magnetometer (9D)".into(),
            );
        }
    }
    let file = match operands.as_slice() {
        [] => None,
        [one] if one == "-" => None,
        [one] => Some(PathBuf::from(one)),
        [_, second, ..] => return Err(format!("more than one FILE: '{second}' (see --help)")),
    };
    Ok(Args {
        file,
        sensors,
        f32: f.switch("--f32"),
        truth: f.switch("--truth"),
        skip_bad_rows: f.switch("--skip-bad-rows"),
        plot: f.value("--plot").map(PathBuf::from),
        params_out,
        calibration: f
            .value("--calibration")
            .map(|p| calibration::read(p).map_err(|e| format!("--calibration: {e}")))
            .transpose()?,
        gyro: f.get("--gyro-unit", GyroUnit::parse)?,
        accel: f.get("--accel-unit", AccelUnit::parse)?,
        mag: f.get("--mag-unit", MagUnit::parse)?,
        time: f.get("--time-unit", TimeUnit::parse)?,
        params,
    })
}

enum Failure {
    Usage(String),
    Row(u64, String),
    Io(io::Error),
    Other(String),
}

impl From<io::Error> for Failure {
    fn from(e: io::Error) -> Self {
        Failure::Io(e)
    }
}

// ---------------------------------------------------------------------------------------------
// What the plot keeps (the loop, its policies and BROAD's metric are gyrostat_pipeline's)

/// Heading and inclination of an attitude (degrees): the twist about the earth's z axis and the
/// angle of the rest (the tilt of the sensor's z axis).
fn heading_inclination(q: [f64; 4]) -> (f64, f64) {
    let [w, _, _, z] = if q[0] < 0.0 { q.map(|v| -v) } else { q };
    let n = (q.iter().map(|v| v * v).sum::<f64>()).sqrt();
    (
        (2.0 * z.atan2(w)).to_degrees(),
        (2.0 * ((w * w + z * z).sqrt() / n).min(1.0).acos()).to_degrees(),
    )
}

/// One row as the plot keeps it.
struct PlotRow {
    t: f64,
    est: (f64, f64),
    reference: (f64, f64),
    error: [f64; 3],
    bias: [f64; 3],
    rest: bool,
    accel_disturbed: bool,
    mag_disturbed: bool,
}

// ---------------------------------------------------------------------------------------------
// The run

/// The scalar types the estimator runs in, with the text and the value of a printed number.
trait Scalar: Real + Debug {
    /// The value a reader of the printed text gets (shortest round-trip form).
    fn as_printed(self) -> f64;
}

impl Scalar for f64 {
    fn as_printed(self) -> f64 {
        self
    }
}

impl Scalar for f32 {
    fn as_printed(self) -> f64 {
        format!("{self:?}").parse().unwrap_or(f64::NAN)
    }
}

/// What a finished run leaves for the summary and the plot.
struct Done {
    metric: Option<Metric>,
    rows: Vec<PlotRow>,
    six_d: bool,
    /// The magnetometer delay in use at the end (s) and the seconds of rotation its estimate
    /// was fed ([`Estimator::mag_delay_evidence`]).
    mag_delay: (f64, f64),
}

/// Reads the input, runs the estimator in `T` and prints the rows.
fn run<T: Scalar>(args: &Args, params: Params<T>, out: &mut Csv) -> Result<Done, Failure> {
    let input = imu_log::open_input(args.file.as_deref()).map_err(|e| match e {
        OpenError::File(e) => Failure::Other(e),
        OpenError::Io(e) => Failure::Io(e),
    })?;
    let mut lines = Lines::new(input);
    let mut last_line = 0u64;
    // The first non-blank line: the header or the first sample.
    let first = loop {
        if lines.will_read() {
            out.flush()?;
        }
        let next = lines
            .next_line()
            .map_err(|e| Failure::Row(last_line + 1, format!("reading the input: {e}")))?;
        let Some((n, line)) = next else {
            return Err(Failure::Other(
                "empty input: no header and no sample".into(),
            ));
        };
        last_line = n;
        match line {
            Ok(text) if text.trim().is_empty() => continue,
            Ok(text) => break (n, text.to_string()),
            Err(reason) => return Err(Failure::Row(n, reason)),
        }
    };
    let layout = Layout::from_first_line(&first.1).map_err(|e| Failure::Row(first.0, e))?;
    let scales = Scales::resolve(&layout, args.time, args.gyro, args.accel, args.mag)
        .map_err(Failure::Usage)?;
    let six_d = match (args.sensors, layout.mag.is_some()) {
        (Sensors::NineD, false) => {
            return Err(Failure::Usage(
                "--9d: the input has no magnetometer columns (mx,my,mz or mag_x_uT,...)".into(),
            ));
        }
        (Sensors::SixD, _) | (Sensors::Auto, false) => true,
        (Sensors::NineD | Sensors::Auto, true) => false,
    };
    if six_d && args.params_out.is_some() {
        return Err(Failure::Usage(
            "--params-out: the input has no magnetometer columns: the delay needs them".into(),
        ));
    }
    if args.truth && layout.truth.is_none() {
        return Err(Failure::Usage(
            "--truth: the input has no reference columns (qw,qx,qy,qz or opt_qw,...)".into(),
        ));
    }

    let options = Options {
        six_d,
        skip_bad_rows: args.skip_bad_rows,
        time_scale: scales.time,
        calibration: args.calibration.map(|c| Calibration {
            gyro: c.gyro,
            accel: c.accel,
            mag: c.mag,
        }),
    };
    let mut pipeline = Run::try_new(params, options)
        .map_err(|e| Failure::Usage(format!("--set: the parameters are invalid: {e}")))?;
    let mut metric = args.truth.then(Metric::default);
    let mut rows = Vec::new();
    writeln!(out, "{HEADER}")?;
    // Rows skipped by --skip-bad-rows: how many, and the first one's line.
    let mut skipped = (0u64, 0u64);
    let mut pending = (!layout.header).then_some(first);
    loop {
        let (n, text) = match pending.take() {
            Some(row) => row,
            None => {
                if lines.will_read() {
                    out.flush()?;
                }
                let next = lines
                    .next_line()
                    .map_err(|e| Failure::Row(last_line + 1, format!("reading the input: {e}")))?;
                let Some((n, line)) = next else { break };
                last_line = n;
                match line {
                    Ok(text) if text.trim().is_empty() => continue,
                    Ok(text) => (n, text.to_string()),
                    Err(reason) => return Err(Failure::Row(n, reason)),
                }
            }
        };
        let (s, step) = match parse_row(&text, &layout, &scales, args.truth) {
            Ok(s) => {
                let sample = pipeline::Sample {
                    t: s.t,
                    gyro: s.gyro,
                    accel: s.accel,
                    mag: s.mag,
                };
                match pipeline.push(&sample) {
                    Ok(step) => (s, step),
                    Err(e) => return Err(Failure::Row(n, e.message(s.t_text))),
                }
            }
            // A non-finite time stamp or gyroscope value: the loop's bad-row policy.
            Err(bad) if bad.glitch => match pipeline.bad_row() {
                Ok(step) => {
                    let t_text = text.split(',').nth(layout.time).unwrap_or("").trim();
                    writeln!(out, "{}", pipeline.row_text(t_text, &step))?;
                    out.row_done()?;
                    count_skipped(&mut skipped, n);
                    continue;
                }
                Err(_) => return Err(Failure::Row(n, bad.reason)),
            },
            Err(bad) => return Err(Failure::Row(n, bad.reason)),
        };
        writeln!(out, "{}", pipeline.row_text(s.t_text, &step))?;
        out.row_done()?;
        let outcome = match step {
            Step::Updated(o) => o,
            Step::Skipped => {
                count_skipped(&mut skipped, n);
                continue;
            }
        };
        let filter = pipeline.estimator();
        let (q, b) = if filter.is_initialized() {
            (
                Some(filter.attitude().to_array().map(T::as_printed)),
                filter.bias().to_array().map(T::as_printed),
            )
        } else {
            (None, [f64::NAN; 3])
        };
        let mut error = None;
        if let (Some(m), Some(r), true) = (metric.as_mut(), s.truth, s.scored) {
            error = m.add(q, r);
        } else if let (Some(q), Some(r)) = (q, s.truth) {
            error = Some(errors(q, r));
        }
        if args.plot.is_some() {
            let nan2 = (f64::NAN, f64::NAN);
            rows.push(PlotRow {
                t: s.t * scales.time,
                est: q.map_or(nan2, heading_inclination),
                reference: s.truth.map_or(nan2, heading_inclination),
                error: error.map_or([f64::NAN; 3], |e| e.map(f64::to_degrees)),
                bias: b,
                rest: outcome.at_rest,
                accel_disturbed: outcome.accel == SensorUse::Disturbed,
                mag_disturbed: outcome.mag == SensorUse::Disturbed,
            });
        }
    }
    if skipped.0 > 0 {
        gyrostat_tools::say!(
            "estimate: skipped {} row(s) with a non-finite time stamp or gyroscope value (--skip-bad-rows), the first at line {}",
            skipped.0,
            skipped.1
        );
    }
    let filter = pipeline.estimator();
    Ok(Done {
        metric,
        rows,
        six_d,
        mag_delay: (
            filter.mag_delay().to_f64(),
            filter.mag_delay_evidence().to_f64(),
        ),
    })
}

/// Counts a row skipped by `--skip-bad-rows` in `skipped` (count, first line).
fn count_skipped(skipped: &mut (u64, u64), line: u64) {
    if skipped.0 == 0 {
        skipped.1 = line;
    }
    skipped.0 += 1;
}

/// The metric line: `truth: total X deg, heading Y deg, inclination Z deg, n = N`.
fn summary(m: &Metric, six_d: bool) -> String {
    let Score {
        total: t,
        heading: h,
        inclination: i,
        n,
        missing,
    } = m.score();
    format!(
        "truth: total {t:.6} deg, heading {h:.6} deg, inclination {i:.6} deg, n = {}{}{}",
        n,
        if missing > 0 {
            format!(", MISSING {}", missing)
        } else {
            String::new()
        },
        if six_d {
            " (6D: only the inclination is meaningful)"
        } else {
            ""
        }
    )
}

/// The plot of a run: about 2000 points per curve.
fn figure(args: &Args, done: &Done) -> plot::Figure {
    use plot::{Figure, Panel, Series};
    let rows = &done.rows;
    let stride = rows.len().div_ceil(2000).max(1);
    let chunks: Vec<&[PlotRow]> = rows.chunks(stride).collect();
    let first = |f: &dyn Fn(&PlotRow) -> f64| -> Vec<f64> {
        chunks
            .iter()
            .map(|c| c.first().map_or(f64::NAN, f))
            .collect()
    };
    let any = |f: &dyn Fn(&PlotRow) -> bool, level: f64| -> Vec<f64> {
        chunks
            .iter()
            .map(|c| level + if c.iter().any(f) { 0.8 } else { 0.0 })
            .collect()
    };
    let mut attitude = vec![
        Series {
            label: "heading",
            y: first(&|r| r.est.0),
        },
        Series {
            label: "inclination",
            y: first(&|r| r.est.1),
        },
    ];
    let mut panels = Vec::new();
    if args.truth {
        attitude.push(Series {
            label: "reference heading",
            y: first(&|r| r.reference.0),
        });
        attitude.push(Series {
            label: "reference inclination",
            y: first(&|r| r.reference.1),
        });
    }
    panels.push(Panel {
        caption:
            "attitude: heading (about the earth z axis) and inclination (tilt of the sensor z axis)"
                .into(),
        unit: "degrees",
        series: attitude,
    });
    if args.truth {
        panels.push(Panel {
            caption: "error against the reference (BROAD's decomposition)".into(),
            unit: "degrees",
            series: vec![
                Series {
                    label: "total",
                    y: first(&|r| r.error[0]),
                },
                Series {
                    label: "heading",
                    y: first(&|r| r.error[1]),
                },
                Series {
                    label: "inclination",
                    y: first(&|r| r.error[2]),
                },
            ],
        });
    }
    panels.push(Panel {
        caption: "gyroscope bias estimate (sensor frame)".into(),
        unit: "deg/s",
        series: ["bx", "by", "bz"]
            .iter()
            .enumerate()
            .map(|(i, &label)| Series {
                label,
                y: first(&|r| r.bias.get(i).copied().unwrap_or(f64::NAN).to_degrees()),
            })
            .collect(),
    });
    panels.push(Panel {
        caption: "flags (raised where set): rest, accelerometer disturbed, field disturbed".into(),
        unit: "",
        series: vec![
            Series {
                label: "rest",
                y: any(&|r| r.rest, 0.0),
            },
            Series {
                label: "accel disturbed",
                y: any(&|r| r.accel_disturbed, 1.0),
            },
            Series {
                label: "mag disturbed",
                y: any(&|r| r.mag_disturbed, 2.0),
            },
        ],
    });
    Figure {
        title: format!(
            "estimate {}: {} rows ({}, {})",
            args.file
                .as_deref()
                .map_or("(stdin)".into(), |p| p.display().to_string()),
            rows.len(),
            if done.six_d { "6D" } else { "9D" },
            if args.f32 { "f32" } else { "f64" }
        ),
        t: first(&|r| r.t),
        panels,
    }
}

fn main() -> ExitCode {
    let args = match CLI
        .command_line_with_operands()
        .and_then(|(f, ops)| arguments(&f, ops).map_err(|e| flags::usage_error(&e)))
    {
        Ok(a) => a,
        Err(status) => return status,
    };
    if let Some(path) = &args.plot
        && let Err(e) = gyrostat_tools::plot::check_folder(path)
    {
        flags::error(&format!("--plot {}: {e}", path.display()));
        return ExitCode::FAILURE;
    }
    if let Some(path) = &args.params_out
        && let Err(e) = gyrostat_tools::plot::check_folder(path)
    {
        flags::error(&format!("--params-out {}: {e}", path.display()));
        return ExitCode::FAILURE;
    }
    let mut out = Csv::stdout();
    let result = if args.f32 {
        run::<f32>(&args, args.params.map(|x| x as f32), &mut out)
    } else {
        run::<f64>(&args, args.params, &mut out)
    };
    let flushed = out.flush();
    let result = match (result, flushed) {
        (Err(Failure::Io(e)), _) | (Ok(_), Err(e)) if stream::is_closed_pipe(&e) => {
            return ExitCode::SUCCESS;
        }
        (Err(e), _) => Err(e),
        (Ok(_), Err(e)) => Err(Failure::Io(e)),
        (Ok(done), Ok(())) => Ok(done),
    };
    let done = match result {
        Ok(done) => done,
        Err(Failure::Usage(e)) => return flags::usage_error(&e),
        Err(Failure::Row(n, e)) => {
            flags::line_error(n, &e);
            return ExitCode::FAILURE;
        }
        Err(Failure::Io(e)) => {
            flags::error(&format!("reading the input or writing stdout: {e}"));
            return ExitCode::FAILURE;
        }
        Err(Failure::Other(e)) => {
            flags::error(&e);
            return ExitCode::FAILURE;
        }
    };
    if let Some(m) = &done.metric {
        gyrostat_tools::say!("{}", summary(m, done.six_d));
    }
    if let Some(path) = &args.plot
        && let Err(e) = plot::write_svg(path, &figure(&args, &done))
    {
        flags::error(&format!("--plot {}: {e}", path.display()));
        return ExitCode::FAILURE;
    }
    if let Some(path) = &args.params_out {
        let (delay, evidence) = done.mag_delay;
        let needed = args.params.mag_delay_estimation_time;
        if evidence < needed {
            flags::error(&format!(
                "--params-out: the magnetometer's delay was not estimated: {evidence:.1} s of \
                 rotation in an undisturbed field, {needed} s needed \
                 (mag_delay_estimation_time); no file written"
            ));
            return ExitCode::FAILURE;
        }
        let text = delay_params_text(&args, delay, evidence);
        if let Err(e) = std::fs::write(path, text) {
            flags::error(&format!("--params-out {}: {e}", path.display()));
            return ExitCode::FAILURE;
        }
    }
    ExitCode::SUCCESS
}

/// The parameter file of `--params-out`: the full mode's estimate of the magnetometer's delay
/// `delay` (s), fed `evidence` seconds of rotation, kept fixed.
fn delay_params_text(args: &Args, delay: f64, evidence: f64) -> String {
    let source = args
        .file
        .as_deref()
        .map_or("(stdin)".into(), |p| p.display().to_string());
    format!(
        "# The magnetometer's delay behind the gyroscope, estimated by estimate's full mode\n\
         # from {source}\n\
         # over {evidence:.1} s of rotation in an undisturbed field (averaged over about the last\n\
         # {tau} s of it: mag_delay_estimation_time), kept fixed: the light mode uses it in place\n\
         # of its default (Mode::LIGHT_MAG_DELAY), the full mode from the first sample.\n\
         mag_delay = {delay:?}  # s\n\
         mag_delay_estimation_time = 0  # s: no online estimate, mag_delay as it is\n",
        tau = args.params.mag_delay_estimation_time,
    )
}
