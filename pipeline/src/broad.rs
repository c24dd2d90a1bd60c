//! A log read whole, and BROAD's metric: what the BROAD research runner and the regression
//! tests of `host-tests` and the `estimate` tool's `--truth` share.
//!
//! - [`read_log`] / [`open_log`]: a CSV log by the columns of [`crate::imu_log`] (the short
//!   names, BROAD's, the x-io Fusion log's; gzip recognised by its first bytes), every row
//!   parsed by [`crate::imu_log::parse_row`], the values in SI units (time in s).
//! - [`errors`], [`Metric`], [`score`]: BROAD's official metric, computed exactly as the
//!   dataset's `score.py` (the same operations in the same order): the error
//!   `q_err = q_est ⊗ q_ref⁻¹` (earth frame), total `2·acos|w|`, heading `2·atan|z/w|`,
//!   inclination `2·acos√(w² + z²)`, RMS in degrees over the scored rows: those with a
//!   reference and `movement == 1` (every row with a reference when the log has no movement
//!   column). A scored row without a finite, non-zero estimate counts as missing.

use std::collections::HashMap;
use std::fmt;
use std::io::{BufRead, BufReader};
use std::path::Path;

use crate::imu_log::{self, Layout, OpenError, Scales, parse_row};
use crate::units::{AccelUnit, GyroUnit};

/// One input row (SI units).
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
    /// Magnetic field (µT, or the input's unit when the names state none), sensor frame, when
    /// the row has it.
    pub mag: Option<[f64; 3]>,
    /// The reference attitude `(w, x, y, z)`, sensor → earth, when the row has one.
    pub truth: Option<[f64; 4]>,
    /// BROAD's `movement` flag, when the log has the column: `Some(true)` on the scored phase.
    pub movement: Option<bool>,
}

impl Row {
    /// Whether the metric scores the row: it has a reference, and `movement == 1` or the log
    /// has no movement column.
    pub fn scored(&self) -> bool {
        self.truth.is_some() && self.movement != Some(false)
    }
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

/// The units of the input's rates and specific forces where the column names state none
/// (`None`: the names' unit, else SI).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Units {
    /// The gyroscope's.
    pub gyro: Option<GyroUnit>,
    /// The accelerometer's.
    pub accel: Option<AccelUnit>,
}

impl Units {
    /// The units the column names state, else rad/s and m/s² (BROAD's names state SI).
    pub const SI: Units = Units {
        gyro: None,
        accel: None,
    };
    /// °/s and g (standard gravity, 9.80665 m/s²).
    pub const DEG_G: Units = Units {
        gyro: Some(GyroUnit::DegPerSecond),
        accel: Some(AccelUnit::StandardGravity),
    };
}

/// A read error: the line (counted from 1) and why.
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

/// Reads a CSV log (see the module docs) in the given units.
///
/// # Errors
/// A [`ReadError`] naming the line: no header or sample, a header without the time,
/// gyroscope or accelerometer columns, a unit that contradicts a column name, a row that
/// [`crate::imu_log::parse_row`] rejects (wrong field count, a field that is not a number, a
/// non-finite time stamp, gyroscope value or reference).
pub fn read_log(reader: impl BufRead, units: Units) -> Result<Log, ReadError> {
    let err = |line: usize, message: String| ReadError { line, message };
    let mut layout: Option<(Layout, Scales)> = None;
    let mut log = Log::default();
    for (n, line) in reader.lines().enumerate() {
        let line_no = n + 1;
        let text = line.map_err(|e| err(line_no, e.to_string()))?;
        if text.trim().is_empty() {
            continue;
        }
        if layout.is_none() {
            let l = Layout::from_first_line(&text).map_err(|e| err(line_no, e))?;
            let s = Scales::resolve(&l, None, units.gyro, units.accel, None)
                .map_err(|e| err(line_no, e))?;
            log.has_mag = l.mag.is_some();
            log.has_truth = l.truth.is_some();
            let header = l.header;
            layout = Some((l, s));
            if header {
                continue;
            }
        }
        let Some((layout, scales)) = &layout else {
            continue;
        };
        let s = parse_row(&text, layout, scales, true).map_err(|e| err(line_no, e.reason))?;
        log.rows.push(Row {
            t_text: s.t_text.to_string(),
            t: s.t * scales.time,
            gyro: s.gyro,
            accel: s.accel,
            mag: s.mag,
            truth: s.truth,
            movement: layout.movement.map(|_| s.scored),
        });
    }
    if layout.is_none() {
        return Err(err(1, "empty input: no header and no sample".into()));
    }
    Ok(log)
}

/// Opens and reads a log file (gzip-compressed when it starts with gzip's magic bytes).
///
/// # Errors
/// A [`ReadError`] with line 0 when the file cannot be opened, else as [`read_log`].
pub fn open_log(path: &Path, units: Units) -> Result<Log, ReadError> {
    let input = imu_log::open_input(Some(path)).map_err(|e| ReadError {
        line: 0,
        message: match e {
            OpenError::File(m) => m,
            OpenError::Io(e) => format!("{}: {e}", path.display()),
        },
    })?;
    read_log(BufReader::new(input), units)
}

/// The error of an estimate `qe` against a reference `qo` (both `(w, x, y, z)`, any norm),
/// BROAD's decomposition in `score.py`'s operations and order: `(total, heading,
/// inclination)` in rad.
pub fn errors(qe: [f64; 4], qo: [f64; 4]) -> [f64; 3] {
    // sum(v * v for v in q) in Python adds from 0 left to right.
    let sumsq = |q: &[f64; 4]| q.iter().fold(0.0, |s, v| s + v * v);
    let (ne, no) = (sumsq(&qe).sqrt(), sumsq(&qo).sqrt());
    let [w1, x1, y1, z1] = qe.map(|v| v / ne);
    let (w2, x2, y2, z2) = (qo[0] / no, -qo[1] / no, -qo[2] / no, -qo[3] / no);
    let w = w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2;
    let z = w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2;
    [
        2.0 * w.abs().min(1.0).acos(),
        if w != 0.0 {
            2.0 * (z / w).abs().atan()
        } else {
            core::f64::consts::PI
        },
        2.0 * (w * w + z * z).sqrt().min(1.0).acos(),
    ]
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

/// The running sums of the metric, one scored row at a time.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Metric {
    sums: [f64; 3],
    n: usize,
    missing: usize,
}

impl Metric {
    /// Adds a scored row: the estimate (`None`, non-finite or zero: missing) against the
    /// reference. Returns the row's errors ([`errors`], rad) when it has an estimate.
    pub fn add(&mut self, estimate: Option<[f64; 4]>, reference: [f64; 4]) -> Option<[f64; 3]> {
        let qe = estimate.filter(|q| {
            q.iter().all(|v| v.is_finite()) && q.iter().map(|v| v * v).sum::<f64>() != 0.0
        });
        let Some(qe) = qe else {
            self.missing += 1;
            return None;
        };
        let e = errors(qe, reference);
        for (sum, e) in self.sums.iter_mut().zip(e) {
            *sum += e * e;
        }
        self.n += 1;
        Some(e)
    }

    /// The RMS of each error in degrees (NaN with no row scored), and the counts.
    pub fn score(&self) -> Score {
        let rms = |s: f64| {
            if self.n > 0 {
                (s / self.n as f64).sqrt().to_degrees()
            } else {
                f64::NAN
            }
        };
        let [total, heading, inclination] = self.sums.map(rms);
        Score {
            total,
            heading,
            inclination,
            n: self.n,
            missing: self.missing,
        }
    }
}

/// The metric of `score.py` over the scored rows of `log` ([`Row::scored`]), the estimate
/// `(t, q)` matched to them by the time stamp rounded to the microsecond (see the module docs).
pub fn score(log: &Log, estimate: &[(f64, [f64; 4])]) -> Score {
    // Python's round() rounds half to even, as round_ties_even.
    let key = |t: f64| (t * 1e6).round_ties_even() as i64;
    let est: HashMap<i64, [f64; 4]> = estimate.iter().map(|(t, q)| (key(*t), *q)).collect();
    let mut m = Metric::default();
    for row in &log.rows {
        if let (true, Some(qo)) = (row.scored(), row.truth) {
            m.add(est.get(&key(row.t)).copied(), qo);
        }
    }
    m.score()
}
