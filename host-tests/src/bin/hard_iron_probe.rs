//! Research probe: the online hard-iron fit over a log (`synthesize`'s CSV or a BROAD trial,
//! `.csv.gz`), default parameters with `NAME=VALUE` changes, printed every `STEP` seconds
//! (environment variable, default 1) keeping every `EVERY`th row (default 1): the offset subtracted,
//! the fit's estimate and standard deviations (µT), its mean normalised innovation squared,
//! its measured noise and whether it offers the offset.
//!
//! ```text
//! cargo run --release -p host-tests --bin hard_iron_probe -- LOG [NAME=VALUE]...
//! ```
//! The log is read by the pipeline's BROAD reader (`gyrostat_pipeline::broad::open_log`, the
//! column finder of `broad_estimate`, the `estimate` tool and Python) and run through its
//! estimate loop (`gyrostat_pipeline::estimate::Run`: the first-sample rule, the checked steps).

use std::path::Path;
use std::process::ExitCode;

use gyrostat::estimation::Params;
use gyrostat_pipeline::broad::{Units, open_log};
use gyrostat_pipeline::estimate::{Options, Run, Sample, set_param};

/// An environment setting, or its default when unset or not a number.
fn setting<T: std::str::FromStr>(name: &str, default: T) -> T {
    std::env::var(name)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run() -> Result<(), String> {
    let mut args = std::env::args().skip(1);
    let path = args
        .next()
        .ok_or("usage: hard_iron_probe LOG [NAME=VALUE]...")?;
    let mut p = Params::<f64>::default();
    for s in args {
        let (n, v) = s
            .split_once('=')
            .ok_or_else(|| format!("expected NAME=VALUE, got '{s}'"))?;
        set_param(&mut p, n, v)?;
    }
    let every: usize = setting("EVERY", 1).max(1);
    let step: f64 = setting("STEP", 1.0);
    let log = open_log(Path::new(&path), Units::SI).map_err(|e| e.to_string())?;
    let mut run = Run::try_new(p, Options::default()).map_err(|e| format!("parameters: {e}"))?;
    let mut next = 0.0;
    for row in log.rows.iter().step_by(every) {
        let sample = Sample {
            t: row.t,
            gyro: row.gyro,
            accel: row.accel,
            mag: row.mag,
        };
        // A rejected row leaves the filter as it was; the probe goes on with the next.
        let _ = run.push(&sample);
        if row.t >= next {
            next = row.t + step;
            let (ap, fit) = run.estimator().hard_iron();
            let (h, sd) = fit.estimate();
            println!(
                "{:5.1} applied {:6.2} {:6.2} {:6.2} | est {:7.2} {:7.2} {:7.2} sd {:6.2} {:6.2} {:6.2} nis {:8.2} r {:.4} ok {}",
                row.t,
                ap.x,
                ap.y,
                ap.z,
                h.x,
                h.y,
                h.z,
                sd.x,
                sd.y,
                sd.z,
                fit.consistency(),
                fit.noise(),
                fit.offset().is_some()
            );
        }
    }
    Ok(())
}
