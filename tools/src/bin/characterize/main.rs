//! `characterize`: the noise of a resting IMU from a log (overlapping Allan deviation and the
//! fitted white noise, bias instability and rate random walk per axis).
//!
//! ```text
//! characterize [--rows A:B | --from T --to T | --rest-phase] [--rate HZ] [--per-decade K] [--fit-from TAU]
//!     [--gyro-unit U] [--accel-unit U] [--mag-unit U] [--time-unit U]
//!     [--plot FILE.svg] [--spec FILE] [--params FILE] [FILE]
//! ```
//! Run with `--help` for the full description of the input and output formats.

mod plot;

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use gyrostat_tools::allan::Spacing;
use gyrostat_tools::characterization::{self, AxisReport};
use gyrostat_tools::flags::{self, Cli, Flag, Flags};
use gyrostat_tools::imu_log::{self, Layout, OpenError, Scales, parse_row};
use gyrostat_tools::stream::{Csv, Lines};
use gyrostat_tools::units::{AccelUnit, GyroUnit, MagUnit, TimeUnit};

const CLI: Cli = Cli {
    name: "characterize",
    help: HELP,
    flags: &[
        Flag::value("--rows"),
        Flag::value("--from"),
        Flag::value("--to"),
        Flag::switch("--rest-phase"),
        Flag::value("--rate"),
        Flag::value("--per-decade"),
        Flag::value("--fit-from"),
        Flag::value("--gyro-unit"),
        Flag::value("--accel-unit"),
        Flag::value("--mag-unit"),
        Flag::value("--time-unit"),
        Flag::value("--plot"),
        Flag::value("--spec"),
        Flag::value("--params"),
    ],
};

const HELP: &str = "\
characterize: the noise of a resting IMU from a log: the overlapping Allan deviation of each
gyroscope and accelerometer axis and the fitted white noise N, bias instability B and rate
random walk K (IEEE Std 952/1293), and the magnetometer's noise

USAGE:
    characterize [--rows A:B | --from T --to T | --rest-phase] [--rate HZ] [--per-decade K]
                 [--fit-from TAU] [--gyro-unit rad/s|deg/s] [--accel-unit m/s^2|g] [--mag-unit uT|nT|G|any]
                 [--time-unit s|ms|us] [--plot FILE.svg] [--spec FILE] [--params FILE] [FILE]

    Reads FILE (standard input without FILE, or with FILE `-`; gzip recognised by its first
    bytes): the CSV of `estimate` (the same column names, units and positional fields:
    t,gx,gy,gz,ax,ay,az[,mx,my,mz]; reference columns are ignored). The sensor must rest (the
    Allan deviation of a moving sensor measures its motion). Flags take their value as the
    next argument or after `=`; a flag given twice is an error.

OPTIONS:
    --rows A:B     only the data rows A to B (counted from 1 over the samples, B included;
                   `A:` to the end, `:B` from the start)
    --from T, --to T
                   only the rows with time stamps in [T, TO] (seconds, after --time-unit)
    --rest-phase   only the leading rows with movement = 0 (BROAD's rest at the start of a
                   trial; needs a movement column)
    --rate HZ      the sample rate (default: (rows - 1) / (last time - first time)); the Allan
                   deviation assumes uniform sampling
    --per-decade K about K averaging times per decade (default: octaves, m = 1, 2, 4, ...)
    --fit-from TAU fit only the points with tau >= TAU seconds (default 0: all). A sensor
                   whose output is low-pass filtered, or that vibrates, has correlated noise
                   at short tau (a bump, then a slope steeper than -1/2) that the three terms
                   cannot take: fit above it. A fit with chi2/dof > 10 is reported on stderr.
    --gyro-unit, --accel-unit, --mag-unit, --time-unit
                   the input's units, as for estimate (default rad/s, m/s^2, any (uT), s)
    --plot FILE    an SVG of the log-log curves (gyro and accelerometer panels), each axis's
                   fitted model, and the three fitted slopes (-1/2, 0, +1/2) of its largest-N axis
    --spec FILE    write the sensor spec (rate, gyro_/accel_noise_density, _bias_instability,
                   _rate_random_walk, mag_noise; SI; the largest axis, per-axis values as comments)
    --params FILE  write the estimator's parameter file (gyro_noise_density,
                   gyro_bias_stability, gyro_bias_time; see the comments in the file)
    --help         print this text

THE FIT: sigma^2(tau) = N^2/tau + (0.664 B)^2 + K^2 tau/3, all three terms at once by weighted
    least squares of sigma^2 (each point weighted by its equivalent degrees of freedom, NIST
    SP 1065 Table 5, for the term that dominates there; each coefficient >= 0). N is the
    fitted -1/2 line at tau = 1 s, B the floor / 0.664, K the +1/2 line at tau = 3 s.

OUTPUT (stdout): two CSV tables separated by a blank line (SI units: rad/s, m/s^2, uT).
    sensor,axis,mean,std,sample_noise,noise_density,bias_instability,rate_random_walk,
        floor_bound,floor_tau,resolved,chi2
      one row per gyro and accelerometer axis: the mean, the standard deviation, the
      per-sample noise sqrt(0.5 mean(diff^2)) (the Allan deviation at one sample), N, B, K,
      the lowest point of the curve / 0.664 (the classical reading of B, an upper bound) and
      its tau, which of N, B, K are resolved (their term dominates some fitted point: e.g.
      `NB`) and the fit's chi2 per degree of freedom (see gyrostat_tools::allan::Fit);
      then one row per magnetometer axis with its mean, std and per-sample noise over the
      distinct samples (a row repeating the previous field exactly is a held sample).
    sensor,axis,tau,m,adev,terms,clusters,edf,fit
      the Allan curves: tau (s), the averaging factor, the deviation, the number of
      overlapping terms, of non-overlapping clusters, the equivalent degrees of freedom (the
      relative error of adev is about 1/sqrt(2 edf)), and the fitted model there.

ERRORS (stderr): error: line N: reason  (a row that estimate rejects, a non-finite
    accelerometer value, a time stamp not after the previous one: exit 1); error: reason  (a
    bad command line, a unit flag contradicting a column name, --rest-phase without a movement
    column: exit 2; an unreadable FILE, fewer than 3 rows selected: exit 1). Nothing is
    printed or written after an error.
";

/// Which rows.
enum Select {
    All,
    Rows(u64, u64),
    Time(f64, f64),
    RestPhase,
}

struct Args {
    file: Option<PathBuf>,
    select: Select,
    rate: Option<f64>,
    spacing: Spacing,
    fit_from: f64,
    gyro: Option<GyroUnit>,
    accel: Option<AccelUnit>,
    mag: Option<MagUnit>,
    time: Option<TimeUnit>,
    plot: Option<PathBuf>,
    spec: Option<PathBuf>,
    params: Option<PathBuf>,
}

fn row_range(flag: &str, text: &str) -> Result<(u64, u64), String> {
    let (a, b) = text
        .split_once(':')
        .ok_or_else(|| format!("{flag}: expected A:B, got '{text}'"))?;
    let bound = |s: &str, default: u64| -> Result<u64, String> {
        let s = s.trim();
        if s.is_empty() {
            Ok(default)
        } else {
            flags::at_least_one(flag, s)
        }
    };
    let (a, b) = (bound(a, 1)?, bound(b, u64::MAX)?);
    if b < a {
        return Err(format!("{flag}: the end {b} is before the start {a}"));
    }
    Ok((a, b))
}

fn arguments(f: &Flags, operands: Vec<String>) -> Result<Args, String> {
    let rows = f.get("--rows", row_range)?;
    let from = f.get("--from", flags::number)?;
    let to = f.get("--to", flags::number)?;
    let rest = f.switch("--rest-phase");
    let select = match (rows, from.is_some() || to.is_some(), rest) {
        (None, false, false) => Select::All,
        (Some((a, b)), false, false) => Select::Rows(a, b),
        (None, true, false) => {
            let (a, b) = (
                from.unwrap_or(f64::NEG_INFINITY),
                to.unwrap_or(f64::INFINITY),
            );
            if b < a {
                return Err(format!("--to {b} is before --from {a}"));
            }
            Select::Time(a, b)
        }
        (None, false, true) => Select::RestPhase,
        _ => return Err("--rows, --from/--to and --rest-phase exclude each other".into()),
    };
    let spacing = match f.get("--per-decade", flags::at_least_one)? {
        None => Spacing::Octave,
        Some(k) => Spacing::PerDecade(
            u32::try_from(k)
                .ok()
                .filter(|&k| k <= 100)
                .ok_or_else(|| format!("--per-decade: at most 100, got {k}"))?,
        ),
    };
    let file = match operands.as_slice() {
        [] => None,
        [one] if one == "-" => None,
        [one] => Some(PathBuf::from(one)),
        [_, second, ..] => return Err(format!("more than one FILE: '{second}' (see --help)")),
    };
    Ok(Args {
        file,
        select,
        rate: f.get("--rate", flags::positive)?,
        spacing,
        fit_from: f.get("--fit-from", flags::number)?.unwrap_or(0.0).max(0.0),
        gyro: f.get("--gyro-unit", GyroUnit::parse)?,
        accel: f.get("--accel-unit", AccelUnit::parse)?,
        mag: f.get("--mag-unit", MagUnit::parse)?,
        time: f.get("--time-unit", TimeUnit::parse)?,
        plot: f.value("--plot").map(PathBuf::from),
        spec: f.value("--spec").map(PathBuf::from),
        params: f.value("--params").map(PathBuf::from),
    })
}

enum Failure {
    Usage(String),
    Row(u64, String),
    Other(String),
}

/// The selected samples, SI units.
struct Log {
    t: Vec<f64>,
    gyro: Vec<[f64; 3]>,
    accel: Vec<[f64; 3]>,
    mag: Vec<[f64; 3]>,
}

fn read(args: &Args) -> Result<Log, Failure> {
    let input = imu_log::open_input(args.file.as_deref()).map_err(|e| match e {
        OpenError::File(e) => Failure::Other(e),
        OpenError::Io(e) => Failure::Other(format!("reading the input: {e}")),
    })?;
    let mut lines = Lines::new(input);
    let mut layout: Option<(Layout, Scales)> = None;
    let mut log = Log {
        t: Vec::new(),
        gyro: Vec::new(),
        accel: Vec::new(),
        mag: Vec::new(),
    };
    let mut row = 0u64;
    let mut last_line = 0u64;
    loop {
        let next = lines
            .next_line()
            .map_err(|e| Failure::Row(last_line + 1, format!("reading the input: {e}")))?;
        let Some((n, line)) = next else { break };
        last_line = n;
        let text = match line {
            Ok(text) if text.trim().is_empty() => continue,
            Ok(text) => text.to_string(),
            Err(reason) => return Err(Failure::Row(n, reason)),
        };
        if layout.is_none() {
            let l = Layout::from_first_line(&text).map_err(|e| Failure::Row(n, e))?;
            let s = Scales::resolve(&l, args.time, args.gyro, args.accel, args.mag)
                .map_err(Failure::Usage)?;
            if matches!(args.select, Select::RestPhase) && l.movement.is_none() {
                return Err(Failure::Usage(
                    "--rest-phase: the input has no movement column".into(),
                ));
            }
            let header = l.header;
            layout = Some((l, s));
            if header {
                continue;
            }
        }
        let Some((l, s)) = &layout else { continue };
        let sample = parse_row(&text, l, s, false).map_err(|e| {
            // The shared reader's note on the estimator does not apply here.
            Failure::Row(
                n,
                e.reason
                    .replace(" (the estimator cannot propagate across it)", ""),
            )
        })?;
        row += 1;
        let t = sample.t * s.time;
        let keep = match args.select {
            Select::All => true,
            Select::Rows(a, b) => {
                if row > b {
                    break;
                }
                row >= a
            }
            Select::Time(a, b) => (a..=b).contains(&t),
            Select::RestPhase => {
                if sample.scored {
                    break;
                }
                true
            }
        };
        if !keep {
            continue;
        }
        if let Some(&prev) = log.t.last()
            && t <= prev
        {
            return Err(Failure::Row(
                n,
                format!(
                    "time stamp {} is not after the previous row's",
                    sample.t_text
                ),
            ));
        }
        if !sample.accel.iter().all(|v| v.is_finite()) {
            return Err(Failure::Row(n, "non-finite accelerometer value".into()));
        }
        log.t.push(t);
        log.gyro.push(sample.gyro);
        log.accel.push(sample.accel);
        if let Some(m) = sample.mag
            && m.iter().all(|v| v.is_finite())
        {
            log.mag.push(m);
        }
    }
    if log.t.len() < 3 {
        return Err(Failure::Other(format!(
            "{} rows selected: at least 3 are needed",
            log.t.len()
        )));
    }
    Ok(log)
}

/// Everything a run found.
struct Report {
    rate: f64,
    samples: usize,
    duration: f64,
    gyro: [AxisReport; 3],
    accel: [AxisReport; 3],
    mag: Option<([f64; 3], [f64; 3], [f64; 3])>,
}

fn characterise(args: &Args, log: &Log) -> Result<Report, Failure> {
    let n = log.t.len();
    let duration = log.t[n - 1] - log.t[0];
    let rate = match args.rate {
        Some(r) => r,
        None => (n - 1) as f64 / duration,
    };
    let gyro = characterization::triad(&log.gyro, rate, args.spacing, args.fit_from)
        .map_err(|e| Failure::Other(format!("gyroscope: {e}")))?;
    let accel = characterization::triad(&log.accel, rate, args.spacing, args.fit_from)
        .map_err(|e| Failure::Other(format!("accelerometer: {e}")))?;
    let mag = characterization::mag_noise(&log.mag).map(|noise| {
        let count = log.mag.len() as f64;
        let mean = [0, 1, 2].map(|i| log.mag.iter().map(|m| m[i]).sum::<f64>() / count);
        let std = [0, 1, 2].map(|i| {
            (log.mag
                .iter()
                .map(|m| (m[i] - mean[i]).powi(2))
                .sum::<f64>()
                / (count - 1.0))
                .sqrt()
        });
        (mean, std, noise)
    });
    Ok(Report {
        rate,
        samples: n,
        duration,
        gyro,
        accel,
        mag,
    })
}

fn print(out: &mut Csv, r: &Report) -> std::io::Result<()> {
    const AXES: [&str; 3] = ["x", "y", "z"];
    writeln!(
        out,
        "sensor,axis,mean,std,sample_noise,noise_density,bias_instability,rate_random_walk,floor_bound,floor_tau,resolved,chi2"
    )?;
    for (name, rep) in [("gyro", &r.gyro), ("accel", &r.accel)] {
        for (axis, a) in AXES.iter().zip(rep.iter()) {
            let f = a.allan.fit;
            let resolved: String = ["N", "B", "K"]
                .iter()
                .zip(a.resolved)
                .filter(|(_, r)| *r)
                .map(|(s, _)| *s)
                .collect();
            writeln!(
                out,
                "{name},{axis},{:?},{:?},{:?},{:?},{:?},{:?},{:?},{:?},{resolved},{:.3}",
                a.mean,
                a.std,
                a.sample_noise,
                f.noise_density,
                f.bias_instability,
                f.rate_random_walk,
                f.floor_bound,
                f.floor_tau,
                f.chi2_per_dof
            )?;
        }
    }
    if let Some((mean, std, noise)) = r.mag {
        for i in 0..3 {
            writeln!(
                out,
                "mag,{},{:?},{:?},{:?},,,,,,,",
                AXES[i], mean[i], std[i], noise[i]
            )?;
        }
    }
    writeln!(out)?;
    writeln!(out, "sensor,axis,tau,m,adev,terms,clusters,edf,fit")?;
    for (name, rep) in [("gyro", &r.gyro), ("accel", &r.accel)] {
        for (axis, a) in AXES.iter().zip(rep.iter()) {
            for p in &a.allan.points {
                writeln!(
                    out,
                    "{name},{axis},{:?},{},{:?},{},{},{:.1},{:?}",
                    p.tau,
                    p.m,
                    p.adev,
                    p.terms,
                    p.clusters,
                    p.edf,
                    a.allan.fit.allan_deviation(p.tau)
                )?;
            }
        }
    }
    Ok(())
}

fn source_name(args: &Args) -> String {
    args.file
        .as_ref()
        .map_or("<stdin>".into(), |p| p.display().to_string())
}

fn main() -> ExitCode {
    let args = match CLI
        .command_line_with_operands()
        .and_then(|(f, ops)| arguments(&f, ops).map_err(|e| flags::usage_error(&e)))
    {
        Ok(a) => a,
        Err(status) => return status,
    };
    let result = read(&args).and_then(|log| characterise(&args, &log));
    let report = match result {
        Ok(r) => r,
        Err(Failure::Usage(e)) => return flags::usage_error(&e),
        Err(Failure::Row(n, e)) => {
            flags::line_error(n, &e);
            return ExitCode::FAILURE;
        }
        Err(Failure::Other(e)) => {
            flags::error(&e);
            return ExitCode::FAILURE;
        }
    };
    let mut out = Csv::stdout();
    match print(&mut out, &report).and_then(|()| out.flush()) {
        Err(e) if gyrostat_tools::stream::is_closed_pipe(&e) => return ExitCode::SUCCESS,
        Err(e) => {
            flags::error(&format!("writing stdout: {e}"));
            return ExitCode::FAILURE;
        }
        Ok(()) => {}
    }
    for (name, rep) in [("gyro", &report.gyro), ("accel", &report.accel)] {
        for (axis, a) in ["x", "y", "z"].iter().zip(rep.iter()) {
            let c = a.allan.fit.chi2_per_dof;
            if c > 10.0 {
                gyrostat_tools::say!(
                    "characterize: {name} {axis}: the model fits the curve poorly (chi2/dof {c:.0}): correlated noise at short tau? (see --fit-from)"
                );
            }
        }
    }
    let source = source_name(&args);
    if let Some(path) = &args.spec {
        let text = characterization::spec_text(
            &source,
            report.rate,
            &report.gyro,
            &report.accel,
            report.mag.map(|m| m.2),
        );
        if let Err(e) = std::fs::write(path, text) {
            flags::error(&format!("--spec {}: {e}", path.display()));
            return ExitCode::FAILURE;
        }
    }
    if let Some(path) = &args.params {
        let text = characterization::params_text(&source, &report.gyro);
        if let Err(e) = std::fs::write(path, text) {
            flags::error(&format!("--params {}: {e}", path.display()));
            return ExitCode::FAILURE;
        }
    }
    if let Some(path) = &args.plot {
        let title = format!(
            "characterize {source}: {} samples at {:.6} Hz ({:.1} s)",
            report.samples, report.rate, report.duration
        );
        if let Err(e) = plot::write_svg(path, &title, &report.gyro, &report.accel) {
            flags::error(&format!("--plot {}: {e}", path.display()));
            return ExitCode::FAILURE;
        }
    }
    ExitCode::SUCCESS
}
