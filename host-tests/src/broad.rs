//! IMU logs in, attitude estimates out, and BROAD's metric: the data path of the attitude
//! estimator on recorded data ([`gyrostat::estimation`]), shared by the research runner
//! (`broad_estimate`) and the regression test (`tests/estimation.rs`). The `estimate` tool
//! (`tools/`) has its own reader and the same metric; its tests check its numbers against this
//! module and `score.py`.
//!
//! - [`read_log`] / [`open_log`]: a CSV log with one header line. Columns are found by name:
//!   BROAD's (`t_s`, `gyr_x_rad_s`…, `acc_x_m_s2`…, `mag_x_uT`…, `opt_qw`…, `movement`) or the
//!   short ones (`t`, `gx gy gz`, `ax ay az`, `mx my mz`, `qw qx qy qz`); a `.gz` file is
//!   decompressed. Units: [`Units`] (BROAD's are SI: rad/s, m/s²; the magnetometer's unit does
//!   not matter, the estimator uses only its direction and relative norm).
//! - [`estimate`]: runs the estimator over a log in f64 or f32 and returns one row per input
//!   row; [`write_estimate`] prints them as `t,qw,qx,qy,qz,bx,by,bz` (`t` as in the input).
//! - [`score`]: BROAD's official metric, computed exactly as the dataset's `score.py` (the same
//!   operations in the same order): the error `q_err = q_est ⊗ q_opt⁻¹` (earth frame), total
//!   `2·acos|w|`, heading `2·atan|z/w|`, inclination `2·acos√(w² + z²)`, RMS in degrees over the
//!   rows with `movement == 1` that have an optical attitude.

use std::collections::HashMap;
use std::fmt;
use std::io::{self, BufRead, BufReader, Write};
use std::path::{Path, PathBuf};

use gyrostat::estimation::{Estimator, Outcome, Params, SensorUse};
use gyrostat::{Real, Vec3};

/// One input row.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// The time stamp as written in the input (the output repeats it).
    pub t_text: String,
    /// The time stamp, s.
    pub t: f64,
    /// Body rate, rad/s, sensor frame.
    pub gyro: [f64; 3],
    /// Specific force, m/s², sensor frame.
    pub accel: [f64; 3],
    /// Magnetic field (input unit), sensor frame, when the log has it.
    pub mag: Option<[f64; 3]>,
    /// The reference attitude `(w, x, y, z)`, sensor → earth, when the row has one.
    pub truth: Option<[f64; 4]>,
    /// BROAD's `movement` flag: `Some(true)` on the scored phase.
    pub movement: Option<bool>,
}

/// A log: its rows and which optional columns it has.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Log {
    /// The rows, in file order.
    pub rows: Vec<Row>,
    /// Whether the magnetometer columns are present.
    pub has_mag: bool,
    /// Whether the reference quaternion columns are present.
    pub has_truth: bool,
}

/// Multipliers from the input's units to SI.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Units {
    /// Input gyroscope unit in rad/s (1 for rad/s, π/180 for °/s).
    pub gyro: f64,
    /// Input accelerometer unit in m/s² (1 for m/s², 9.80665 for g).
    pub accel: f64,
}

impl Units {
    /// rad/s and m/s² (BROAD's units).
    pub const SI: Units = Units {
        gyro: 1.0,
        accel: 1.0,
    };
    /// °/s and g (standard gravity, 9.80665 m/s²).
    pub const DEG_G: Units = Units {
        gyro: core::f64::consts::PI / 180.0,
        accel: 9.80665,
    };
}

/// A read error: the line (counted from 1, the header is line 1) and why.
#[derive(Clone, Debug, PartialEq)]
pub struct ReadError {
    /// Line number, from 1; 0 when the file could not be opened or read.
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line == 0 {
            write!(f, "{}", self.message)
        } else {
            write!(f, "line {}: {}", self.line, self.message)
        }
    }
}

impl std::error::Error for ReadError {}

/// Column names: BROAD's first, then the short form.
const TIME: [&str; 2] = ["t_s", "t"];
const GYRO: [[&str; 3]; 2] = [
    ["gyr_x_rad_s", "gyr_y_rad_s", "gyr_z_rad_s"],
    ["gx", "gy", "gz"],
];
const ACCEL: [[&str; 3]; 2] = [
    ["acc_x_m_s2", "acc_y_m_s2", "acc_z_m_s2"],
    ["ax", "ay", "az"],
];
const MAG: [[&str; 3]; 2] = [["mag_x_uT", "mag_y_uT", "mag_z_uT"], ["mx", "my", "mz"]];
const TRUTH: [[&str; 4]; 2] = [
    ["opt_qw", "opt_qx", "opt_qy", "opt_qz"],
    ["qw", "qx", "qy", "qz"],
];

fn find<const N: usize>(head: &[&str], options: &[[&str; N]]) -> Option<[usize; N]> {
    options.iter().find_map(|names| {
        let mut idx = [0; N];
        for (slot, name) in idx.iter_mut().zip(names) {
            *slot = head.iter().position(|h| h == name)?;
        }
        Some(idx)
    })
}

/// Reads a CSV log (see the module docs) in the given units.
///
/// # Errors
/// A [`ReadError`] naming the line: a header without the time, gyroscope or accelerometer
/// columns, a row with too few fields or a field that is not a number (empty fields are
/// allowed only in the reference columns, where they mean "no reference").
pub fn read_log(reader: impl BufRead, units: Units) -> Result<Log, ReadError> {
    let mut lines = reader.lines();
    let io_err = |line: usize, e: io::Error| ReadError {
        line,
        message: e.to_string(),
    };
    let header = match lines.next() {
        Some(h) => h.map_err(|e| io_err(1, e))?,
        None => {
            return Err(ReadError {
                line: 1,
                message: "empty input: no header".into(),
            });
        }
    };
    let head: Vec<&str> = header.split(',').map(str::trim).collect();
    let missing = |what: &str| ReadError {
        line: 1,
        message: format!("header has no {what} columns"),
    };
    let it = find(&head, &[[TIME[0]], [TIME[1]]]).ok_or_else(|| missing("time (t_s or t)"))?[0];
    let ig = find(&head, &GYRO).ok_or_else(|| missing("gyroscope"))?;
    let ia = find(&head, &ACCEL).ok_or_else(|| missing("accelerometer"))?;
    let im = find(&head, &MAG);
    let iq = find(&head, &TRUTH);
    let imv = head.iter().position(|h| *h == "movement");
    let mut log = Log {
        rows: Vec::new(),
        has_mag: im.is_some(),
        has_truth: iq.is_some(),
    };
    for (n, line) in lines.enumerate() {
        let line_no = n + 2;
        let line = line.map_err(|e| io_err(line_no, e))?;
        if line.trim().is_empty() {
            continue;
        }
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let err = |message: String| ReadError {
            line: line_no,
            message,
        };
        let get = |i: usize| -> Result<&str, ReadError> {
            fields
                .get(i)
                .copied()
                .ok_or_else(|| err(format!("{} fields, column {} missing", fields.len(), i + 1)))
        };
        let num = |i: usize| -> Result<f64, ReadError> {
            let s = get(i)?;
            s.parse::<f64>().map_err(|_| {
                err(format!(
                    "column {} ({}): not a number: {s:?}",
                    i + 1,
                    head[i]
                ))
            })
        };
        let vec3 = |idx: [usize; 3], scale: f64| -> Result<[f64; 3], ReadError> {
            Ok([
                num(idx[0])? * scale,
                num(idx[1])? * scale,
                num(idx[2])? * scale,
            ])
        };
        let truth = match iq {
            Some(iq) if !get(iq[0])?.is_empty() => {
                Some([num(iq[0])?, num(iq[1])?, num(iq[2])?, num(iq[3])?])
            }
            _ => None,
        };
        let movement = match imv {
            Some(i) => Some(get(i)? == "1"),
            None => None,
        };
        log.rows.push(Row {
            t_text: get(it)?.to_string(),
            t: num(it)?,
            gyro: vec3(ig, units.gyro)?,
            accel: vec3(ia, units.accel)?,
            mag: im.map(|im| vec3(im, 1.0)).transpose()?,
            truth,
            movement,
        });
    }
    Ok(log)
}

/// Opens and reads a log file (gzip-compressed when its name ends in `.gz`).
///
/// # Errors
/// A [`ReadError`] with line 0 when the file cannot be opened, else as [`read_log`].
pub fn open_log(path: &Path, units: Units) -> Result<Log, ReadError> {
    let file = std::fs::File::open(path).map_err(|e| ReadError {
        line: 0,
        message: format!("{}: {e}", path.display()),
    })?;
    if path.extension().is_some_and(|e| e == "gz") {
        read_log(
            BufReader::new(flate2::read::MultiGzDecoder::new(file)),
            units,
        )
    } else {
        read_log(BufReader::new(file), units)
    }
}

/// One output row of [`estimate`].
#[derive(Clone, Debug, PartialEq)]
pub struct EstimateRow {
    /// The input's time stamp text.
    pub t_text: String,
    /// The time stamp, s.
    pub t: f64,
    /// The attitude `(w, x, y, z)`, sensor → earth.
    pub q: [f64; 4],
    /// The gyroscope bias estimate, rad/s.
    pub bias: [f64; 3],
    /// The magnetometer delay in use after the row, s ([`Estimator::mag_delay`]).
    pub mag_delay: f64,
    /// The hard-iron offset subtracted after the row (input units), the fit's estimate, and
    /// the standard deviations of its x and y components and its consistency (mean
    /// normalised innovation squared) ([`Estimator::hard_iron`]).
    pub hard_iron: [[f64; 3]; 3],
    /// What the update did; `None` when the filter rejected the row (see `error`).
    pub outcome: Option<Outcome>,
    /// The filter's error for a rejected row (the previous attitude is repeated).
    pub error: Option<gyrostat::Error>,
}

/// Which sensors [`estimate`] uses and in which scalar type.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Mode {
    /// Gyroscope and accelerometer only (no magnetometer).
    pub six_d: bool,
    /// Run the filter in f32 (the inputs rounded to f32).
    pub f32: bool,
}

/// Runs the estimator over `log` and returns one row per input row. The step `dt` of each row
/// is the difference of its time stamp and the previous row's; the first row has none and is
/// given NaN (the library's first-sample rule, [`gyrostat::estimation::Estimator::update`]:
/// until the attitude is initialised `dt` is neither used nor checked).
pub fn estimate(
    log: &Log,
    params: &Params<f64>,
    mode: Mode,
) -> Result<Vec<EstimateRow>, gyrostat::Error> {
    if mode.f32 {
        run::<f32>(log, &params.map(|x| x as f32), mode)
    } else {
        run::<f64>(log, params, mode)
    }
}

fn run<T: Real>(
    log: &Log,
    params: &Params<T>,
    mode: Mode,
) -> Result<Vec<EstimateRow>, gyrostat::Error> {
    let mut f = Estimator::try_new(*params)?;
    let v = |a: [f64; 3]| Vec3::new(T::from_f64(a[0]), T::from_f64(a[1]), T::from_f64(a[2]));
    let mut out = Vec::with_capacity(log.rows.len());
    let mut prev_t: Option<f64> = None;
    for row in &log.rows {
        let dt = prev_t.map_or(f64::NAN, |p| row.t - p);
        prev_t = Some(row.t);
        let mag = if mode.six_d { None } else { row.mag.map(v) };
        let r = f.update(v(row.gyro), v(row.accel), mag, T::from_f64(dt));
        let q = f.attitude().to_array().map(Real::to_f64);
        let b = f.bias().to_array().map(Real::to_f64);
        let (outcome, error) = match r {
            Ok(o) => (Some(o), None),
            Err(e) => (None, Some(e)),
        };
        out.push(EstimateRow {
            t_text: row.t_text.clone(),
            t: row.t,
            q,
            bias: b,
            mag_delay: f.mag_delay().to_f64(),
            hard_iron: {
                let (applied, fit) = f.hard_iron();
                let (h, sd) = fit.estimate();
                let sd = Vec3::new(sd.x, sd.y, fit.consistency());
                [applied, h, sd].map(|v| v.to_array().map(Real::to_f64))
            },
            outcome,
            error,
        });
    }
    Ok(out)
}

/// Writes the header `t,qw,qx,qy,qz,bx,by,bz` and one line per row (quaternion and bias with 10
/// significant digits after the point, enough for the metric's 1e-9 rad).
pub fn write_estimate(mut w: impl Write, rows: &[EstimateRow]) -> io::Result<()> {
    writeln!(w, "t,qw,qx,qy,qz,bx,by,bz")?;
    for r in rows {
        let [qw, qx, qy, qz] = r.q;
        let [bx, by, bz] = r.bias;
        writeln!(
            w,
            "{},{qw:.12},{qx:.12},{qy:.12},{qz:.12},{bx:.10e},{by:.10e},{bz:.10e}",
            r.t_text
        )?;
    }
    Ok(())
}

/// BROAD's metric over one trial (degrees).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Score {
    /// RMS of the total error angle.
    pub total: f64,
    /// RMS of the heading error (about the earth vertical).
    pub heading: f64,
    /// RMS of the inclination error.
    pub inclination: f64,
    /// Rows scored.
    pub n: usize,
    /// Scored rows without a finite, non-zero estimate.
    pub missing: usize,
}

/// The metric of `score.py` over the rows of `log` with `movement == 1` and a reference, the
/// estimate matched to them by the time stamp rounded to the microsecond (see the module docs).
pub fn score(log: &Log, estimate: &[(f64, [f64; 4])]) -> Score {
    // Python's round() rounds half to even, as round_ties_even.
    let key = |t: f64| (t * 1e6).round_ties_even() as i64;
    let est: HashMap<i64, [f64; 4]> = estimate.iter().map(|(t, q)| (key(*t), *q)).collect();
    let (mut se, mut sh, mut si) = (0.0f64, 0.0f64, 0.0f64);
    let (mut n, mut missing) = (0usize, 0usize);
    for row in &log.rows {
        let (Some(true), Some(qo)) = (row.movement, row.truth) else {
            continue;
        };
        let qe = match est.get(&key(row.t)) {
            Some(q)
                if q.iter().all(|v| v.is_finite())
                    && q.iter().map(|v| v * v).sum::<f64>() != 0.0 =>
            {
                *q
            }
            _ => {
                missing += 1;
                continue;
            }
        };
        // sum(v * v for v in q) in Python adds from 0 left to right.
        let sumsq = |q: &[f64; 4]| q.iter().fold(0.0, |s, v| s + v * v);
        let (ne, no) = (sumsq(&qe).sqrt(), sumsq(&qo).sqrt());
        let [w1, x1, y1, z1] = qe.map(|v| v / ne);
        let (w2, x2, y2, z2) = (qo[0] / no, -qo[1] / no, -qo[2] / no, -qo[3] / no);
        let w = w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2;
        let z = w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2;
        se += (2.0 * w.abs().min(1.0).acos()).powi(2);
        sh += (if w != 0.0 {
            2.0 * (z / w).abs().atan()
        } else {
            core::f64::consts::PI
        })
        .powi(2);
        si += (2.0 * (w * w + z * z).sqrt().min(1.0).acos()).powi(2);
        n += 1;
    }
    let d = |s: f64| {
        if n > 0 {
            (s / n as f64).sqrt().to_degrees()
        } else {
            f64::NAN
        }
    };
    Score {
        total: d(se),
        heading: d(sh),
        inclination: d(si),
        n,
        missing,
    }
}

/// [`score`] of an [`estimate`] result.
pub fn score_rows(log: &Log, rows: &[EstimateRow]) -> Score {
    let est: Vec<(f64, [f64; 4])> = rows.iter().map(|r| (r.t, r.q)).collect();
    score(log, &est)
}

/// The environment variable naming the folder of the full BROAD trials (gzip CSV, as
/// [`TRIALS`] names them; `data/README.md` says where to get them).
pub const BROAD_DIR_VAR: &str = "GYROSTAT_BROAD_DIR";

/// The folder of the full BROAD trials: `$GYROSTAT_BROAD_DIR` when set, else
/// `../shared/real-data/broad` beside the repository when that folder exists; `None` otherwise
/// (a clone on its own: the tests then use the trimmed copies, [`fixture_path`]).
pub fn broad_dir() -> Option<PathBuf> {
    if let Some(d) = std::env::var_os(BROAD_DIR_VAR) {
        return Some(PathBuf::from(d));
    }
    let d = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/real-data/broad");
    d.is_dir().then_some(d)
}

/// How to get the full trials, for messages when [`broad_dir`] is `None`.
pub const BROAD_DIR_HELP: &str = "the full BROAD trials are not here: set GYROSTAT_BROAD_DIR to a \
    folder of NN_name.csv.gz trials (converted from the dataset's MATLAB files, see data/README.md; \
    dataset: https://github.com/dlaidig/broad)";

/// The trimmed BROAD trials kept in the repository (`data/broad/`, cut by `data/trim.py`): file
/// stem, seconds kept from the start (the rest phase and the first part of the movement).
pub const FIXTURES: [(&str, u32); 2] = [
    ("07_undisturbed_fast_rotation_B", 60),
    ("32_disturbed_attached_magnet_1cm", 65),
];

/// The path of a trimmed trial in the repository by its stem (see [`FIXTURES`]); panics on a
/// stem that is not one of them.
pub fn fixture_path(stem: &str) -> PathBuf {
    let (_, s) = FIXTURES
        .iter()
        .find(|(f, _)| *f == stem)
        .unwrap_or_else(|| panic!("{stem} is not a trimmed fixture (host_tests::broad::FIXTURES)"));
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../data/broad")
        .join(format!("{stem}.first{s}s.csv.gz"))
}

/// The 16 shared BROAD trials: file stem and whether the trial is in the disturbed group.
pub const TRIALS: [(&str, bool); 16] = [
    ("01_undisturbed_slow_rotation_A", false),
    ("03_undisturbed_slow_rotation_C", false),
    ("05_undisturbed_slow_rotation_with_breaks_B", false),
    ("07_undisturbed_fast_rotation_B", false),
    ("09_undisturbed_fast_rotation_with_breaks_B", false),
    ("11_undisturbed_slow_translation_B", false),
    ("14_undisturbed_slow_translation_with_breaks_B", false),
    ("16_undisturbed_fast_translation_B", false),
    ("21_undisturbed_fast_combined", false),
    ("24_disturbed_tapping_A", true),
    ("26_disturbed_phone_vibration_A", true),
    ("28_disturbed_stationary_magnet_A", true),
    ("30_disturbed_stationary_magnet_C", true),
    ("32_disturbed_attached_magnet_1cm", true),
    ("34_disturbed_attached_magnet_3cm", true),
    ("36_disturbed_attached_magnet_5cm", true),
];

/// The path of a full trial by its stem (see [`TRIALS`]) in [`broad_dir`]; `None` when there is
/// no such folder.
pub fn trial_path(stem: &str) -> Option<PathBuf> {
    broad_dir().map(|d| d.join(format!("{stem}.csv.gz")))
}

/// Counts of the sensors' uses over a run (for reports).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct UseCounts {
    /// Rows at rest.
    pub rest: usize,
    /// Accelerometer samples rejected as disturbed.
    pub accel_disturbed: usize,
    /// Magnetometer samples rejected as disturbed.
    pub mag_disturbed: usize,
    /// Rows the filter rejected.
    pub errors: usize,
}

/// Counts what the updates of a run did.
pub fn use_counts(rows: &[EstimateRow]) -> UseCounts {
    let mut c = UseCounts::default();
    for r in rows {
        match r.outcome {
            Some(o) => {
                c.rest += usize::from(o.at_rest);
                c.accel_disturbed += usize::from(o.accel == SensorUse::Disturbed);
                c.mag_disturbed += usize::from(o.mag == SensorUse::Disturbed);
            }
            None => c.errors += 1,
        }
    }
    c
}

/// Sets one parameter by name from a value in SI units (angles in rad), for research runs and
/// tools: the field names of [`Params`] (`field.norm`, `rest.gyro`, … for the nested ones), and
/// `gains=kalman` or `heading_time_constant=τ` (fixed gains).
///
/// # Errors
/// An unknown name or a value that is not a number.
pub fn set_param(p: &mut Params<f64>, name: &str, value: &str) -> Result<(), String> {
    use gyrostat::estimation::Gains;
    if name == "gains" && value == "kalman" {
        p.gains = Gains::Kalman;
        return Ok(());
    }
    let v: f64 = value
        .parse()
        .map_err(|_| format!("{name}: not a number: {value:?}"))?;
    if p.set_by_name(name, v) {
        Ok(())
    } else {
        Err(format!("unknown parameter {name:?}"))
    }
}
