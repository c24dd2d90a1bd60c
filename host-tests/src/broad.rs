//! IMU logs in, attitude estimates out, and BROAD's metric: the data path of the attitude
//! estimator on recorded data ([`gyrostat::estimation`]), for the research runner
//! (`broad_estimate`) and the regression tests (`tests/estimation.rs`). The reader, the metric
//! and the estimator's loop are `gyrostat-pipeline`'s, the ones the `estimate` tool and the
//! Python package run (re-exported here: [`read_log`], [`open_log`], [`score`], ...).
//!
//! - [`read_log`] / [`open_log`]: a CSV log by the column names of
//!   `gyrostat_pipeline::imu_log` (BROAD's `t_s`, `gyr_x_rad_s`…, `acc_x_m_s2`…, `mag_x_uT`…,
//!   `opt_qw`…, `movement`, the short ones `t`, `gx gy gz`, …); gzip is recognised by its
//!   first bytes. Units: [`Units`].
//! - [`estimate`]: runs the estimator over a log in f64 or f32 through
//!   `gyrostat_pipeline::estimate::Run` and returns one row per input row; [`write_estimate`]
//!   prints them as `t,qw,qx,qy,qz,bx,by,bz` (`t` as in the input).
//! - [`score`]: BROAD's official metric, computed exactly as the dataset's `score.py`
//!   (`gyrostat_pipeline::broad`).

use std::io::{self, Write};
use std::path::{Path, PathBuf};

use gyrostat::estimation::{Estimator, Outcome, Params, SensorUse};
use gyrostat::propagation::PropagatedAttitude;
use gyrostat::{Real, Vec3};
use gyrostat_pipeline::estimate::{Fault, Options, Run, Sample, Step};

pub use gyrostat_pipeline::broad::{
    Log, Metric, ReadError, Row, Score, Units, errors, open_log, read_log, score,
};

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
    /// What the update did; `None` for a row skipped as bad
    /// (`gyrostat_pipeline::estimate::Options::skip_bad_rows`).
    pub outcome: Option<Outcome>,
}

/// Which sensors [`estimate`] uses and in which scalar type.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Mode {
    /// Gyroscope and accelerometer only (no magnetometer).
    pub six_d: bool,
    /// Run the filter in f32 (the inputs rounded to f32).
    pub f32: bool,
    /// Carry the filter's strapdown attitude compensated
    /// ([`Estimator::try_new_compensated`]).
    pub compensated: bool,
}

/// Why [`estimate`] stopped: bad parameters, or a row the estimator's loop rejects.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum EstimateError {
    /// The parameters are out of their domain.
    Params(gyrostat::Error),
    /// A row ends the run (`gyrostat_pipeline::estimate`'s policies, as the `estimate` tool).
    Row(Fault),
}

impl std::fmt::Display for EstimateError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            EstimateError::Params(e) => write!(f, "the parameters are invalid: {e}"),
            EstimateError::Row(fault) => write!(f, "{fault}"),
        }
    }
}

impl std::error::Error for EstimateError {}

/// Runs the estimator over `log` and returns one row per input row, through the loop the
/// `estimate` tool and the Python package run (`gyrostat_pipeline::estimate::Run`: the first
/// row has no step, NaN, which the estimator neither uses nor checks until its attitude is
/// initialised; later steps are the differences of the time stamps, checked).
///
/// # Errors
/// [`EstimateError`]: invalid parameters, or the first row the loop rejects.
pub fn estimate(
    log: &Log,
    params: &Params<f64>,
    mode: Mode,
) -> Result<Vec<EstimateRow>, EstimateError> {
    let options = Options {
        six_d: mode.six_d,
        ..Options::default()
    };
    let p32 = params.map(|x| x as f32);
    let e = EstimateError::Params;
    match (mode.f32, mode.compensated) {
        (true, false) => run(log, Run::try_new(p32, options).map_err(e)?),
        (true, true) => run(log, Run::try_new_compensated(p32, options).map_err(e)?),
        (false, false) => run(log, Run::try_new(*params, options).map_err(e)?),
        (false, true) => run(log, Run::try_new_compensated(*params, options).map_err(e)?),
    }
}

fn run<T: Real + std::fmt::Debug, A: PropagatedAttitude<T>>(
    log: &Log,
    mut run: Run<T, A>,
) -> Result<Vec<EstimateRow>, EstimateError> {
    let mut out = Vec::with_capacity(log.rows.len());
    for (index, row) in log.rows.iter().enumerate() {
        let sample = Sample {
            t: row.t,
            gyro: row.gyro,
            accel: row.accel,
            mag: row.mag,
        };
        let step = run
            .push(&sample)
            .map_err(|error| EstimateError::Row(Fault { index, error }))?;
        let f: &Estimator<T, A> = run.estimator();
        out.push(EstimateRow {
            t_text: row.t_text.clone(),
            t: row.t,
            q: f.attitude().to_array().map(Real::to_f64),
            bias: f.bias().to_array().map(Real::to_f64),
            mag_delay: f.mag_delay().to_f64(),
            hard_iron: {
                let (applied, fit) = f.hard_iron();
                let (h, sd) = fit.estimate();
                let sd = Vec3::new(sd.x, sd.y, fit.consistency());
                [applied, h, sd].map(|v| v.to_array().map(Real::to_f64))
            },
            outcome: match step {
                Step::Updated(o) => Some(o),
                Step::Skipped => None,
            },
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
    /// Rows skipped as bad.
    pub skipped: usize,
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
            None => c.skipped += 1,
        }
    }
    c
}

/// One `NAME=VALUE` parser for every face: the `estimate` tool's `--set` and the runners here.
pub use gyrostat_pipeline::estimate::set_param;
