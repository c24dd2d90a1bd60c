//! Attitude estimation on BROAD, the Rust peers: uf-ahrs 0.2.2 (VQF, Madgwick, Mahony; 9D and 6D)
//! and the vqf crate 0.4.1 (a 6D Rust port of VQF), run online over the shared BROAD trials. Each
//! estimate is written as CSV (`t_s,qw,qx,qy,qz`, sensor → ENU with y towards magnetic north, one
//! row per trial row) under `target/broad-peers/rust/<filter>/<trial>.csv`, where
//! `benches/broad/run_peers.py` scores it with BROAD's `score.py` in the same table as the PyPI
//! peers and gyrostat. Not a criterion bench and not in the test suite:
//!
//! ```text
//! cargo bench --bench broad_peers                       # every trial of $GYROSTAT_BROAD_DIR
//!                                                       # (else ../shared/real-data/broad)
//! cargo bench --bench broad_peers -- --trials 07,24 --data DIR
//! python3 benches/broad/run_peers.py --rust             # runs this, then scores everything
//! ```
//!
//! Initialisation, BROAD's rule (the attitude of the first sample's accelerometer and
//! magnetometer; 6D: the accelerometer alone, the smallest rotation putting it on +z), then one
//! update per sample from the first sample on:
//! - Madgwick (β = 0.12, BROAD's best common value; uf-ahrs's default is 0.05) and Mahony
//!   (uf-ahrs's defaults, kp = 0.74, ki = 0.0012, which are BROAD's best common gains):
//!   `new_with_orientation(q0)`, q0 in their own earth frame (NWU: x towards magnetic north).
//! - uf-ahrs VQF and vqf-crate VQF: `new` with default parameters. Neither takes a full initial
//!   attitude: `Vqf::new_with_orientation` sets only the gyro-integrated part, which the first
//!   accelerometer sample (mean-initialised low-pass, full correction) and, in 9D, the first
//!   magnetometer sample (initial heading gain 1) overwrite. Their own start-up therefore already
//!   is BROAD's rule; the program checks it (the first 9D output against q0) and prints the
//!   difference.
//!
//! Frames (checked on every trial's rest phase by the Python script, and for the 9D filters on
//! the first sample here): uf-ahrs's Madgwick, Mahony and 9D VQF (`heading_orientation`, the
//! `Ahrs::update` output) put the magnetometer's horizontal part on +x (NWU) and are mapped by
//! Rz(+90°); the 6D outputs (`Vqf::orientation` of both crates) have an arbitrary heading. Sensor data: rad/s, m/s², µT, as f32 (the filters' type); the
//! sample period is BROAD's 3.5 ms (`t_s` = row / 285.714 Hz).
//!
//! BROAD: D. Laidig, M. Caruso, A. Cereatti, T. Seel, "BROAD — A Benchmark for Robust Inertial
//! Orientation Estimation", Data 6(7):72, 2021, doi:10.3390/data6070072 (CC BY 4.0).

use std::fmt::Write as _;
use std::fs;
use std::io::{self, Read as _};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};
use uf_ahrs::{Ahrs, Madgwick, MadgwickParams, Mahony, MahonyParams, Vqf, VqfParams};

/// One BROAD trial: times and sensor samples (rad/s, m/s², µT).
struct Trial {
    stem: String,
    t: Vec<String>,
    gyr: Vec<[f64; 3]>,
    acc: Vec<[f64; 3]>,
    mag: Vec<[f64; 3]>,
}

fn read_trial(path: &Path) -> io::Result<Trial> {
    // The shared trials are gzip CSV; `gzip -dc` keeps this program free of a decompressor crate.
    let mut child = Command::new("gzip")
        .arg("-dc")
        .arg(path)
        .stdout(Stdio::piped())
        .spawn()?;
    let mut text = String::new();
    if let Some(out) = child.stdout.as_mut() {
        out.read_to_string(&mut text)?;
    }
    if !child.wait()?.success() {
        return Err(io::Error::other(format!(
            "gzip -dc {} failed",
            path.display()
        )));
    }
    let bad = |what: &str| io::Error::other(format!("{}: {what}", path.display()));
    let mut lines = text.lines();
    let head: Vec<&str> = lines
        .next()
        .ok_or_else(|| bad("empty"))?
        .split(',')
        .collect();
    let col = |name: &str| {
        head.iter()
            .position(|h| *h == name)
            .ok_or_else(|| bad(&format!("no column {name}")))
    };
    let it = col("t_s")?;
    let ig = [
        col("gyr_x_rad_s")?,
        col("gyr_y_rad_s")?,
        col("gyr_z_rad_s")?,
    ];
    let ia = [col("acc_x_m_s2")?, col("acc_y_m_s2")?, col("acc_z_m_s2")?];
    let im = [col("mag_x_uT")?, col("mag_y_uT")?, col("mag_z_uT")?];
    let stem = path
        .file_name()
        .and_then(|n| n.to_str())
        .and_then(|n| n.strip_suffix(".csv.gz"))
        .ok_or_else(|| bad("not a .csv.gz"))?
        .to_string();
    let mut trial = Trial {
        stem,
        t: Vec::new(),
        gyr: Vec::new(),
        acc: Vec::new(),
        mag: Vec::new(),
    };
    for (n, line) in lines.enumerate() {
        let f: Vec<&str> = line.split(',').collect();
        let get = |i: usize| -> io::Result<f64> {
            f.get(i)
                .and_then(|s| s.parse::<f64>().ok())
                .filter(|v| v.is_finite())
                .ok_or_else(|| bad(&format!("line {}: column {}", n + 2, i + 1)))
        };
        let v3 =
            |i: [usize; 3]| -> io::Result<[f64; 3]> { Ok([get(i[0])?, get(i[1])?, get(i[2])?]) };
        trial
            .t
            .push(f.get(it).ok_or_else(|| bad("t_s"))?.to_string());
        trial.gyr.push(v3(ig)?);
        trial.acc.push(v3(ia)?);
        trial.mag.push(v3(im)?);
    }
    Ok(trial)
}

fn v32(v: [f64; 3]) -> Vector3<f32> {
    Vector3::new(v[0] as f32, v[1] as f32, v[2] as f32)
}

/// BROAD's initial state, sensor → ENU (y towards magnetic north): the accelerometer on +z, the
/// magnetometer's horizontal part on +y. Without a magnetometer: the smallest rotation that puts
/// the accelerometer on +z.
fn initial_enu(acc: [f64; 3], mag: Option<[f64; 3]>) -> UnitQuaternion<f64> {
    let up = Vector3::from(acc).normalize();
    match mag {
        Some(m) => {
            let east = Vector3::from(m).cross(&up).normalize();
            let north = up.cross(&east);
            // Rows: the earth axes in sensor coordinates (v_earth = C v_sensor).
            let c = Matrix3::from_rows(&[east.transpose(), north.transpose(), up.transpose()]);
            UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(c))
        }
        None => UnitQuaternion::rotation_between(&up, &Vector3::z())
            .unwrap_or_else(UnitQuaternion::identity),
    }
}

/// Rz(+90°): NWU (x towards magnetic north) → ENU (y towards magnetic north).
fn enu_from_nwu() -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Vector3::z_axis(), core::f64::consts::FRAC_PI_2)
}

fn to64(q: UnitQuaternion<f32>) -> UnitQuaternion<f64> {
    q.cast::<f64>()
}

/// One online estimator over one trial: initial attitude (ENU) → the ENU estimate after each row.
type Runner = fn(&Trial, UnitQuaternion<f64>, Duration) -> Vec<UnitQuaternion<f64>>;

struct Filter {
    label: &'static str,
    /// How the filter is run, for the score table.
    about: &'static str,
    slug: &'static str,
    nine: bool,
    run: Runner,
}

/// The initial attitude in the NWU earth frame of uf-ahrs's Madgwick and Mahony, as f32.
fn nwu_f32(q0_enu: UnitQuaternion<f64>) -> UnitQuaternion<f32> {
    (enu_from_nwu().inverse() * q0_enu).cast::<f32>()
}

const MADGWICK_BETA: f32 = 0.12;

fn madgwick(
    tr: &Trial,
    q0: UnitQuaternion<f64>,
    dt: Duration,
    nine: bool,
) -> Vec<UnitQuaternion<f64>> {
    let params = MadgwickParams {
        beta: MADGWICK_BETA,
    };
    let mut f = Madgwick::new_with_orientation(dt, params, nwu_f32(q0));
    (0..tr.t.len())
        .map(|i| {
            let q = if nine {
                f.update(v32(tr.gyr[i]), v32(tr.acc[i]), v32(tr.mag[i]))
            } else {
                f.update_imu(v32(tr.gyr[i]), v32(tr.acc[i]))
            };
            enu_from_nwu() * to64(q)
        })
        .collect()
}

fn mahony(
    tr: &Trial,
    q0: UnitQuaternion<f64>,
    dt: Duration,
    nine: bool,
) -> Vec<UnitQuaternion<f64>> {
    let mut f = Mahony::new_with_orientation(dt, MahonyParams::default(), nwu_f32(q0));
    (0..tr.t.len())
        .map(|i| {
            let q = if nine {
                f.update(v32(tr.gyr[i]), v32(tr.acc[i]), v32(tr.mag[i]))
            } else {
                f.update_imu(v32(tr.gyr[i]), v32(tr.acc[i]))
            };
            enu_from_nwu() * to64(q)
        })
        .collect()
}

fn uf_vqf(
    tr: &Trial,
    _q0: UnitQuaternion<f64>,
    dt: Duration,
    nine: bool,
) -> Vec<UnitQuaternion<f64>> {
    let mut f = Vqf::new(dt, VqfParams::default());
    (0..tr.t.len())
        .map(|i| {
            if nine {
                enu_from_nwu() * to64(f.update(v32(tr.gyr[i]), v32(tr.acc[i]), v32(tr.mag[i])))
            } else {
                f.update2(v32(tr.gyr[i]), v32(tr.acc[i]));
                to64(f.orientation())
            }
        })
        .collect()
}

fn crate_vqf(tr: &Trial, _q0: UnitQuaternion<f64>, dt: Duration) -> Vec<UnitQuaternion<f64>> {
    use nalgebra033::Vector3 as V;
    let mut f = vqf::Vqf::new(dt, dt, vqf::VqfParameters::default());
    let v = |x: [f64; 3]| V::new(x[0] as f32, x[1] as f32, x[2] as f32);
    (0..tr.t.len())
        .map(|i| {
            f.update(v(tr.gyr[i]), v(tr.acc[i]));
            let q = f.orientation();
            UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
                f64::from(q.w),
                f64::from(q.i),
                f64::from(q.j),
                f64::from(q.k),
            ))
        })
        .collect()
}

const FILTERS: [Filter; 7] = [
    Filter {
        label: "uf-ahrs VQF 9D",
        about: "uf-ahrs 0.2.2 Vqf::new defaults, Ahrs::update, NWU mapped",
        slug: "uf-ahrs-vqf-9d",
        nine: true,
        run: |t, q, d| uf_vqf(t, q, d, true),
    },
    Filter {
        label: "uf-ahrs VQF 6D",
        about: "uf-ahrs 0.2.2 Vqf::new defaults, update2 + orientation()",
        slug: "uf-ahrs-vqf-6d",
        nine: false,
        run: |t, q, d| uf_vqf(t, q, d, false),
    },
    Filter {
        label: "uf-ahrs Madgwick 9D",
        about: "uf-ahrs 0.2.2 Madgwick beta 0.12, new_with_orientation(q0), NWU mapped",
        slug: "uf-ahrs-madgwick-9d",
        nine: true,
        run: |t, q, d| madgwick(t, q, d, true),
    },
    Filter {
        label: "uf-ahrs Madgwick 6D",
        about: "uf-ahrs 0.2.2 Madgwick beta 0.12, new_with_orientation(q0), update_imu",
        slug: "uf-ahrs-madgwick-6d",
        nine: false,
        run: |t, q, d| madgwick(t, q, d, false),
    },
    Filter {
        label: "uf-ahrs Mahony 9D",
        about: "uf-ahrs 0.2.2 Mahony defaults kp 0.74 ki 0.0012, new_with_orientation(q0), NWU mapped",
        slug: "uf-ahrs-mahony-9d",
        nine: true,
        run: |t, q, d| mahony(t, q, d, true),
    },
    Filter {
        label: "uf-ahrs Mahony 6D",
        about: "uf-ahrs 0.2.2 Mahony defaults kp 0.74 ki 0.0012, new_with_orientation(q0), update_imu",
        slug: "uf-ahrs-mahony-6d",
        nine: false,
        run: |t, q, d| mahony(t, q, d, false),
    },
    Filter {
        label: "vqf crate 6D",
        about: "vqf 0.4.1 Vqf::new defaults, update + orientation()",
        slug: "vqf-crate-6d",
        nine: false,
        run: crate_vqf,
    },
];

fn write_estimate(path: &Path, t: &[String], q: &[UnitQuaternion<f64>]) -> io::Result<()> {
    let mut s = String::with_capacity(t.len() * 56);
    s.push_str("t_s,qw,qx,qy,qz\n");
    for (t, q) in t.iter().zip(q) {
        let _ = writeln!(s, "{t},{:.8},{:.8},{:.8},{:.8}", q.w, q.i, q.j, q.k);
    }
    fs::write(path, s)
}

fn usage() -> ! {
    eprintln!(
        "usage: cargo bench --bench broad_peers [-- --data DIR] [--trials 07,24] [--out DIR]"
    );
    std::process::exit(2)
}

fn main() -> io::Result<()> {
    // The repository (this package is its benches/ folder).
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    // The full trials (data/README.md says where to get them).
    let mut data = std::env::var_os("GYROSTAT_BROAD_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("../shared/real-data/broad"));
    let mut out = root.join("target/broad-peers/rust");
    let mut trials: Option<Vec<String>> = None;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--bench" => {} // passed by `cargo bench`
            "--data" => data = args.next().map(PathBuf::from).unwrap_or_else(|| usage()),
            "--out" => out = args.next().map(PathBuf::from).unwrap_or_else(|| usage()),
            "--trials" => {
                trials = Some(
                    args.next()
                        .unwrap_or_else(|| usage())
                        .split(',')
                        .map(str::to_string)
                        .collect(),
                )
            }
            _ => usage(),
        }
    }
    let mut paths: Vec<PathBuf> = fs::read_dir(&data)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.to_str().is_some_and(|s| s.ends_with(".csv.gz")))
        .filter(|p| {
            let num = p
                .file_name()
                .and_then(|n| n.to_str())
                .and_then(|n| n.split('_').next())
                .unwrap_or("");
            trials.as_ref().is_none_or(|t| t.iter().any(|x| x == num))
        })
        .collect();
    paths.sort();
    if paths.is_empty() {
        eprintln!("error: no trials in {}", data.display());
        std::process::exit(1);
    }
    for f in &FILTERS {
        let dir = out.join(f.slug);
        fs::create_dir_all(&dir)?;
        fs::write(dir.join("label.txt"), format!("{}\n{}\n", f.label, f.about))?;
    }
    let dt = Duration::from_micros(3500);
    let mut seconds = [0.0f64; FILTERS.len()];
    let mut updates = 0usize;
    for path in &paths {
        let tr = read_trial(path)?;
        updates += tr.t.len();
        let (Some(&a0), Some(&m0)) = (tr.acc.first(), tr.mag.first()) else {
            continue;
        };
        let q9 = initial_enu(a0, Some(m0));
        let q6 = initial_enu(a0, None);
        let mut line = format!("{:<46}", tr.stem);
        for (k, f) in FILTERS.iter().enumerate() {
            let q0 = if f.nine { q9 } else { q6 };
            let t0 = Instant::now();
            let est = (f.run)(&tr, q0, dt);
            seconds[k] += t0.elapsed().as_secs_f64();
            if f.nine
                && let Some(first) = est.first()
            {
                let _ = write!(
                    line,
                    " {}: {:.3}°",
                    f.slug,
                    first.angle_to(&q9).to_degrees()
                );
            }
            write_estimate(
                &out.join(f.slug).join(format!("{}.csv", tr.stem)),
                &tr.t,
                &est,
            )?;
        }
        eprintln!("{line}  (first 9D output vs initial state)");
    }
    for (k, f) in FILTERS.iter().enumerate() {
        eprintln!(
            "{:<22} {:6.2} µs per update on this host (bench profile)",
            f.label,
            seconds[k] * 1e6 / updates.max(1) as f64
        );
    }
    eprintln!("estimates: {}", out.display());
    Ok(())
}
