//! Research runner: the attitude estimator on the shared BROAD trials, scored with BROAD's
//! metric (the computation of the dataset's `score.py`).
//!
//! ```text
//! cargo run --release -p host-tests --bin broad_estimate -- [OPTIONS] [TRIAL...]
//!   TRIAL            trial numbers (01 07 …) or file paths; default: the 16 shared trials
//!   --data DIR       the folder of the full trials (default: $GYROSTAT_BROAD_DIR, else
//!                    ../shared/real-data/broad beside the repository; see data/README.md for
//!                    where to get them; the repository keeps only trimmed copies in data/broad)
//!   --f32            run the filter in f32 (default f64)
//!   --both           run f64 and f32 and print the largest difference of the scores
//!   --compensated    carry the filter's strapdown attitude compensated
//!                    (Estimator::try_new_compensated; with --both: both precisions)
//!   --6d             no magnetometer (inclination is the meaningful score)
//!   --params FILE    parameters from a parameter file (gyrostat::estimation::params_text),
//!                    applied where it stands among the --set options
//!   --set NAME=VALUE a parameter (SI units; a value ending in `deg` is converted to rad,
//!                    `deg/s` too); repeatable. Names: gyrostat_pipeline::estimate::set_param
//!   --out DIR        write each estimate as DIR/NN.csv (t,qw,qx,qy,qz,bx,by,bz)
//!   --every N        keep every Nth row (rows 0, N, 2N, …; nothing else changed): the trial
//!                    at 1/N of its rate, the rows `run_peers.py --every N` gives the peers
//!   --quiet          print only the group means
//! ```
//! Prints per trial the total, heading and inclination RMSE (degrees) and the means over the
//! undisturbed, disturbed and all trials, and over the two halves of the split the design is
//! checked on (A: 01 05 09 14 21 26 30 34, B: 03 07 11 16 24 28 32 36).

use std::path::PathBuf;
use std::process::ExitCode;

use gyrostat::estimation::Params;
use host_tests::broad::{
    self, EstimateRow, Log, Mode, Score, TRIALS, Units, estimate, open_log, score_rows,
};

/// The half-split the design is checked on: the two halves of the 16 shared trials.
const HALF_A: [&str; 8] = ["01", "05", "09", "14", "21", "26", "30", "34"];
const HALF_B: [&str; 8] = ["03", "07", "11", "16", "24", "28", "32", "36"];

struct Job {
    name: String,
    disturbed: bool,
    path: PathBuf,
}

fn main() -> ExitCode {
    let mut params = Params::<f64>::default();
    let mut mode = Mode::default();
    let mut both = false;
    let mut quiet = false;
    let mut out: Option<PathBuf> = None;
    let mut every = 1usize;
    let mut lead = 0.0f64;
    let mut data: Option<PathBuf> = None;
    // (name, disturbed, stem of a listed trial or a path)
    let mut picked: Vec<(String, bool, Result<&str, PathBuf>)> = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--f32" => mode.f32 = true,
            "--compensated" => mode.compensated = true,
            "--6d" => mode.six_d = true,
            "--both" => both = true,
            "--quiet" => quiet = true,
            "--out" => out = args.next().map(PathBuf::from),
            "--lead" => match args.next().and_then(|v| v.parse::<f64>().ok()) {
                Some(x) if x.is_finite() => lead = x,
                _ => {
                    eprintln!("error: --lead needs seconds");
                    return ExitCode::from(2);
                }
            },
            "--every" => match args.next().and_then(|v| v.parse::<usize>().ok()) {
                Some(n) if n >= 1 => every = n,
                _ => {
                    eprintln!("error: --every needs a whole number ≥ 1");
                    return ExitCode::from(2);
                }
            },
            "--params" => {
                let Some(path) = args.next() else {
                    eprintln!("error: --params needs FILE");
                    return ExitCode::from(2);
                };
                let text = match std::fs::read_to_string(&path) {
                    Ok(t) => t,
                    Err(e) => {
                        eprintln!("error: --params: {path}: {e}");
                        return ExitCode::from(2);
                    }
                };
                if let Err(e) = params.set_from_text(&text) {
                    eprintln!("error: --params: {path}: {e}");
                    return ExitCode::from(2);
                }
            }
            "--data" => data = args.next().map(PathBuf::from),
            "--set" => {
                let Some(kv) = args.next() else {
                    eprintln!("error: --set needs NAME=VALUE");
                    return ExitCode::from(2);
                };
                let Some((k, v)) = kv.split_once('=') else {
                    eprintln!("error: --set needs NAME=VALUE, got {kv:?}");
                    return ExitCode::from(2);
                };
                if let Err(e) = broad::set_param(&mut params, k, v) {
                    eprintln!("error: {e}");
                    return ExitCode::from(2);
                }
            }
            s if s.starts_with("--") => {
                eprintln!("error: unknown option {s}");
                return ExitCode::from(2);
            }
            s => {
                if let Some((stem, d)) = TRIALS.iter().find(|(stem, _)| stem.starts_with(s)) {
                    picked.push((stem[..2].to_string(), *d, Ok(stem)));
                } else {
                    picked.push((s.to_string(), false, Err(PathBuf::from(s))));
                }
            }
        }
    }
    if picked.is_empty() {
        picked = TRIALS
            .iter()
            .map(|(stem, d)| (stem[..2].to_string(), *d, Ok(*stem)))
            .collect();
    }
    let dir = data.or_else(broad::broad_dir);
    let mut jobs = Vec::new();
    for (name, disturbed, which) in picked {
        let path = match which {
            Err(path) => path,
            Ok(stem) => match &dir {
                Some(d) => d.join(format!("{stem}.csv.gz")),
                None => {
                    eprintln!("error: {} (or pass --data DIR)", broad::BROAD_DIR_HELP);
                    return ExitCode::from(2);
                }
            },
        };
        jobs.push(Job {
            name,
            disturbed,
            path,
        });
    }
    if let Some(dir) = &out
        && let Err(e) = std::fs::create_dir_all(dir)
    {
        eprintln!("error: {}: {e}", dir.display());
        return ExitCode::from(1);
    }

    type Run = (Score, Option<Score>, broad::UseCounts, f64, [[f64; 3]; 3]);
    let run_one = |job: &Job| -> Result<Run, String> {
        let mut log: Log = open_log(&job.path, Units::SI).map_err(|e| e.to_string())?;
        if every > 1 {
            log.rows = log.rows.into_iter().step_by(every).collect();
        }
        let mut rows: Vec<EstimateRow> =
            estimate(&log, &params, mode).map_err(|e| e.to_string())?;
        if lead != 0.0 {
            // Research: the output carried forward by `lead` seconds at the last rate.
            for (r, row) in rows.iter_mut().zip(&log.rows) {
                let w = host_tests::reference::add(
                    row.gyro,
                    host_tests::reference::scale(r.bias, -1.0),
                );
                let e = host_tests::reference::quat_exp(host_tests::reference::scale(w, lead));
                r.q = host_tests::reference::qmul(r.q, e);
            }
        }
        if let Some(dir) = &out {
            let f = std::fs::File::create(dir.join(format!("{}.csv", job.name)))
                .map_err(|e| e.to_string())?;
            broad::write_estimate(std::io::BufWriter::new(f), &rows).map_err(|e| e.to_string())?;
        }
        let other = if both {
            let m = Mode {
                f32: !mode.f32,
                ..mode
            };
            let r2 = estimate(&log, &params, m).map_err(|e| e.to_string())?;
            Some(score_rows(&log, &r2))
        } else {
            None
        };
        let delay = rows.last().map_or(0.0, |r| r.mag_delay);
        Ok((
            score_rows(&log, &rows),
            other,
            broad::use_counts(&rows),
            delay,
            rows.last().map_or([[0.0; 3]; 3], |r| r.hard_iron),
        ))
    };

    // Two worker threads over the trials.
    let results: Vec<_> = std::thread::scope(|s| {
        let chunks: Vec<Vec<&Job>> = (0..2)
            .map(|w| jobs.iter().skip(w).step_by(2).collect())
            .collect();
        let handles: Vec<_> = chunks
            .into_iter()
            .map(|c| s.spawn(move || c.into_iter().map(|j| (j, run_one(j))).collect::<Vec<_>>()))
            .collect();
        let mut all: Vec<_> = handles
            .into_iter()
            .flat_map(|h| h.join().unwrap_or_default())
            .collect();
        all.sort_by(|a, b| a.0.name.cmp(&b.0.name));
        all
    });

    let mut status = ExitCode::SUCCESS;
    // undisturbed, disturbed, all, then the half-split's two halves.
    let mut groups: [(f64, f64, f64, usize); 5] = [(0.0, 0.0, 0.0, 0); 5];
    let mut worst_diff = 0.0f64;
    if !quiet {
        println!(
            "| trial | total ° | heading ° | inclination ° | n | rest | acc rej | mag rej | delay ms | hard iron (fit ± sd) |{}",
            if both { " f32−f64 total °|" } else { "" }
        );
        println!(
            "|---|---|---|---|---|---|---|---|---|---|{}",
            if both { "---|" } else { "" }
        );
    }
    for (job, r) in &results {
        match r {
            Ok((s, other, c, delay, hi)) => {
                let half = if HALF_A.contains(&job.name.as_str()) {
                    Some(3)
                } else if HALF_B.contains(&job.name.as_str()) {
                    Some(4)
                } else {
                    None
                };
                for g in [usize::from(job.disturbed), 2].into_iter().chain(half) {
                    groups[g].0 += s.total;
                    groups[g].1 += s.heading;
                    groups[g].2 += s.inclination;
                    groups[g].3 += 1;
                }
                let diff = other.map(|o| {
                    let d = (o.total - s.total)
                        .abs()
                        .max((o.heading - s.heading).abs())
                        .max((o.inclination - s.inclination).abs());
                    worst_diff = worst_diff.max(d);
                    format!(" {d:.4} |")
                });
                if !quiet {
                    println!(
                        "| {} | {:.3} | {:.3} | {:.3} | {} | {} | {} | {} | {:.2} | {:.1} ({:.1} {:.1} {:.1} ± {:.1}) |{}",
                        job.name,
                        s.total,
                        s.heading,
                        s.inclination,
                        s.n,
                        c.rest,
                        c.accel_disturbed,
                        c.mag_disturbed,
                        delay * 1e3,
                        hi[0].iter().map(|v| v * v).sum::<f64>().sqrt(),
                        hi[1][0],
                        hi[1][1],
                        hi[1][2],
                        hi[2].iter().copied().fold(0.0, f64::max),
                        diff.unwrap_or_default()
                    );
                }
                if s.missing > 0 || c.skipped > 0 {
                    eprintln!(
                        "{}: {} missing, {} skipped rows",
                        job.name, s.missing, c.skipped
                    );
                }
            }
            Err(e) => {
                eprintln!("error: {}: {e}", job.name);
                status = ExitCode::from(1);
            }
        }
    }
    let labels = ["undisturbed", "disturbed", "all", "half A", "half B"];
    for (label, g) in labels.iter().zip(groups) {
        if g.3 > 0 {
            let n = g.3 as f64;
            println!(
                "mean {label:<12} total {:.3}  heading {:.3}  inclination {:.3}  ({} trials)",
                g.0 / n,
                g.1 / n,
                g.2 / n,
                g.3
            );
        }
    }
    if both {
        println!("largest |f32 − f64| of a score: {worst_diff:.4}°");
    }
    status
}
