//! `propagate --time-column` and the sensor options, against computations written here:
//!
//! - the real x-io Fusion log (its first 4000 samples, 40 s, in
//!   `data/fusion/sensor_data.first4000.csv.gz`; deg/s gyro with jittery timestamps, steps
//!   7.56–30.24 ms, turns up to 6.4 rad/s): the f64 result against an independent integration on
//!   the real timestamps (a product of exponentials, one per interval, of the trapezoid rotation
//!   vector with its commutator term, on plain arrays);
//! - synthetic coning streams with jitter (increments and rates), a dropped sample (a gap),
//!   repeated and backwards timestamps, units, a calibration file and a remap.

use std::f64::consts::TAU;
use std::io::Read;
use std::path::PathBuf;

use crate::cli::{numbers, row, run};
use host_tests::ref_propagation::Coning;
use host_tests::reference::{Q, V3, add, cross, norm, qmul, quat_angle, scale};

/// `k,t,qw,qx,qy,qz` rows.
fn timed_rows(stdout: &str) -> Vec<(u64, f64, Q)> {
    stdout
        .lines()
        .map(|l| {
            let v = numbers(l);
            assert_eq!(v.len(), 6, "{l}");
            (v[0] as u64, v[1], [v[2], v[3], v[4], v[5]])
        })
        .collect()
}

/// `exp(φ)` written out.
fn qexp(phi: V3) -> Q {
    let th = norm(phi);
    if th == 0.0 {
        return [1.0, 0.0, 0.0, 0.0];
    }
    let s = (0.5 * th).sin() / th;
    [(0.5 * th).cos(), s * phi[0], s * phi[1], s * phi[2]]
}

fn fusion() -> Vec<(f64, V3)> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../data/fusion/sensor_data.first4000.csv.gz");
    let file = std::fs::File::open(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut text = String::new();
    flate2::read::GzDecoder::new(file)
        .read_to_string(&mut text)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.lines()
        .skip(1)
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.trim().parse().unwrap()).collect();
            (v[0], [v[1], v[2], v[3]])
        })
        .collect()
}

#[test]
fn fusion_log_on_its_own_timestamps() {
    let data = fusion();
    assert_eq!(data.len(), 4000);
    let input: String = data
        .iter()
        .map(|(t, w)| format!("{t},{}\n", row(w)))
        .collect();
    let out = run(
        "propagate",
        &[
            "--time-column",
            "--input",
            "rates",
            "--algo",
            "magnus4",
            "--dt",
            "0.01",
            "--gyro-unit",
            "deg/s",
        ],
        &input,
    );
    assert_eq!(out.status, Some(0), "{}", out.stderr);
    let rows = timed_rows(&out.stdout);
    assert_eq!(rows.len(), data.len());
    // The reference, written here: per interval [t_{k−1}, t_k], the cubic Lagrange interpolant
    // through the samples k−3..k (0..3 for the first three intervals: the window the tool
    // documents), and q̇ = ½ q ⊗ (0, ω(t)) integrated across the interval by classical RK4 on
    // 64 substeps (a different integrator on the same continuous rate model; 16 substeps give the
    // same result to 2e-10 rad: converged).
    let d2r = TAU / 360.0;
    let ts: Vec<f64> = data.iter().map(|d| d.0).collect();
    let ws: Vec<V3> = data.iter().map(|d| scale(d.1, d2r)).collect();
    let mut q: Q = [1.0, 0.0, 0.0, 0.0];
    let mut worst = 0.0f64;
    // The linear-interpolant model, for scale: per interval φ = h(ω_a + ω_b)/2 + h²/12 ω_a × ω_b.
    let mut q_lin: Q = [1.0, 0.0, 0.0, 0.0];
    for k in 1..ts.len() {
        let first = k.saturating_sub(3).min(ts.len() - 4);
        let (wt, ww) = (&ts[first..first + 4], &ws[first..first + 4]);
        let rate = |t: f64| -> V3 {
            let mut acc = [0.0; 3];
            for i in 0..4 {
                let mut l = 1.0;
                for j in 0..4 {
                    if i != j {
                        l *= (t - wt[j]) / (wt[i] - wt[j]);
                    }
                }
                acc = add(acc, scale(ww[i], l));
            }
            acc
        };
        let f = |q: Q, t: f64| {
            let o = rate(t);
            qmul(q, [0.0, o[0], o[1], o[2]]).map(|x| 0.5 * x)
        };
        let (ta, tb) = (ts[k - 1], ts[k]);
        let hs = (tb - ta) / 64.0;
        for i in 0..64 {
            let t = ta + i as f64 * hs;
            let k1 = f(q, t);
            let k2 = f(
                std::array::from_fn(|j| q[j] + 0.5 * hs * k1[j]),
                t + 0.5 * hs,
            );
            let k3 = f(
                std::array::from_fn(|j| q[j] + 0.5 * hs * k2[j]),
                t + 0.5 * hs,
            );
            let k4 = f(std::array::from_fn(|j| q[j] + hs * k3[j]), t + hs);
            q = std::array::from_fn(|j| {
                q[j] + hs / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j])
            });
        }
        let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
        q = q.map(|x| x / n);
        let h = tb - ta;
        let (wa, wb) = (ws[k - 1], ws[k]);
        let phi = add(
            scale(add(wa, wb), 0.5 * h),
            scale(cross(wa, wb), h * h / 12.0),
        );
        q_lin = qmul(q_lin, qexp(phi));
        let (rk, rt, rq) = rows[k];
        assert_eq!((rk, rt), (k as u64, tb));
        worst = worst.max(quat_angle(q, rq));
    }
    let model = quat_angle(q, q_lin);
    println!(
        "fusion: worst angle between the tool and the reference {worst:e} rad; the linear-interpolant \
         model ends {model:e} rad from the cubic one"
    );
    // Magnus-4 is 4th order in the interval: with steps up to 30 ms at up to 6.4 rad/s
    // (|ω|h ≤ 0.19 rad) its truncation against the converged reference was measured at 3.2e-7
    // rad worst over these 40 s (8.6e-6 over the full 135 s log), 4000× below the interpolation
    // model's own uncertainty (the linear model ends 1.3e-3 rad away).
    assert!(worst < 2e-6, "{worst:e}");
    // The same log on a fixed 10 ms clock (its mean step is 10.01 ms): far off.
    let fixed: String = data.iter().map(|(_, w)| row(w) + "\n").collect();
    let out = run(
        "propagate",
        &[
            "--input",
            "rates",
            "--algo",
            "magnus4",
            "--dt",
            "0.01",
            "--gyro-unit",
            "deg/s",
        ],
        &fixed,
    );
    assert_eq!(out.status, Some(0), "{}", out.stderr);
    let last = numbers(out.stdout.lines().last().unwrap());
    let wrong = quat_angle(q, [last[1], last[2], last[3], last[4]]);
    println!("fusion on a fixed 10 ms clock: {wrong:e} rad from the reference");
    assert!(wrong > 100.0 * worst, "{wrong:e}");
}

/// Jittered sample times `t_k` (k = 0..=n) with mean `h`, ±40 %.
fn jittered(h: f64, n: usize, seed: u64) -> Vec<f64> {
    let mut s = seed;
    let mut t = vec![0.0];
    for _ in 0..n {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let u = (s >> 11) as f64 / (1u64 << 53) as f64;
        t.push(t.last().unwrap() + h * (0.6 + 0.8 * u));
    }
    t
}

#[test]
fn jittered_coning_increments_and_rates() {
    let c = Coning {
        alpha: 0.05,
        omega_c: TAU * 3.3,
    };
    let ts = jittered(1e-3, 6000, 7);
    let q0 = row(&c.attitude(0.0));
    // Increments in deg over each interval, timestamps in ms: t is the interval's end.
    let inc: String = ts
        .windows(2)
        .map(|w| {
            format!(
                "{},{}\n",
                w[1] * 1e3,
                row(&scale(c.increment(w[0], w[1]), 360.0 / TAU))
            )
        })
        .collect();
    for (algo, bound) in [("coning2", 1e-8), ("exp", 1e-4)] {
        let out = run(
            "propagate",
            &[
                "--time-column",
                "--input",
                "increments",
                "--algo",
                algo,
                "--dt",
                "0.001",
                "--t0",
                "0",
                "--time-unit",
                "ms",
                "--gyro-unit",
                "deg/s",
                "--q0",
                &q0,
            ],
            &inc,
        );
        assert_eq!(out.status, Some(0), "{}", out.stderr);
        let rows = timed_rows(&out.stdout);
        assert_eq!(rows.len(), 6000);
        let (_, t, q) = *rows.last().unwrap();
        assert!((t - ts[6000]).abs() < 1e-12);
        let e = quat_angle(q, c.attitude(t));
        println!("{algo} on a jittered clock: {e:e} rad after {t} s");
        assert!(e < bound, "{algo} {e:e}");
    }
    // Rates at the jittered times: Magnus-4 on the actual times.
    let rates: String = ts
        .iter()
        .map(|&t| format!("{t},{}\n", row(&c.body_rate(t))))
        .collect();
    let out = run(
        "propagate",
        &[
            "--time-column",
            "--input",
            "rates",
            "--algo",
            "magnus4",
            "--dt",
            "0.001",
            "--q0",
            &q0,
        ],
        &rates,
    );
    assert_eq!(out.status, Some(0), "{}", out.stderr);
    let rows = timed_rows(&out.stdout);
    assert_eq!(rows.len(), ts.len());
    let worst = rows
        .iter()
        .map(|(_, t, q)| quat_angle(*q, c.attitude(*t)))
        .fold(0.0, f64::max);
    println!("magnus4 on jittered rate samples: worst {worst:e} rad");
    // Measured 1.9e-9 (4th order at h ≤ 1.4 ms); a 2nd-order (linear) interpolant or a fixed
    // clock would be orders of magnitude off.
    assert!(worst < 5e-9, "{worst:e}");
}

#[test]
fn drops_repeats_and_backwards_are_row_errors() {
    let base = |ts: &[f64]| -> String { ts.iter().map(|t| format!("{t},0.1,0,0\n")).collect() };
    let args = [
        "--time-column",
        "--input",
        "rates",
        "--algo",
        "magnus4",
        "--dt",
        "0.01",
    ];
    // 5 samples then one lost (a 20 ms step is fine, a 60 ms one is a gap at factor 5).
    let out = run(
        "propagate",
        &args,
        &base(&[0.0, 0.01, 0.02, 0.03, 0.04, 0.06, 0.12]),
    );
    assert_eq!(out.status, Some(1));
    assert!(
        out.stderr.starts_with("error: line 7: gap:"),
        "{}",
        out.stderr
    );
    // The rows before it are kept: up to sample 5 (t = 0.06).
    let rows = timed_rows(&out.stdout);
    assert_eq!(rows.last().unwrap().0, 5);
    let mut a = args.to_vec();
    a.extend(["--gap-factor", "7"]);
    assert_eq!(
        run(
            "propagate",
            &a,
            &base(&[0.0, 0.01, 0.02, 0.03, 0.04, 0.06, 0.12])
        )
        .status,
        Some(0)
    );
    let out = run("propagate", &args, &base(&[0.0, 0.01, 0.02, 0.02]));
    assert_eq!(out.stderr, "error: line 4: repeated timestamp\n");
    // Only two samples integrated before the error: the linear interpolant over [0, 0.01] and
    // [0.01, 0.02], rate 0.1 rad/s constant: 2 mrad about x.
    let rows = timed_rows(&out.stdout);
    assert_eq!(rows.len(), 3);
    assert!((rows[2].2[1] - (0.001f64).sin()).abs() < 1e-15);
    let out = run("propagate", &args, &base(&[0.0, 0.01, 0.005]));
    assert!(
        out.stderr.starts_with("error: line 3: timestamp 5"),
        "{}",
        out.stderr
    );
    assert_eq!(out.status, Some(1));
    // Increments: the first interval starts at --t0.
    let out = run(
        "propagate",
        &[
            "--time-column",
            "--input",
            "increments",
            "--algo",
            "exp",
            "--dt",
            "0.01",
            "--t0",
            "0",
        ],
        "0.1,0.001,0,0\n",
    );
    assert!(
        out.stderr.starts_with("error: line 1: gap:"),
        "{}",
        out.stderr
    );
    // Usage errors.
    for (bad, msg) in [
        (
            vec![
                "--time-column",
                "--input",
                "rates",
                "--algo",
                "rk4",
                "--dt",
                "0.01",
                "--compensated",
            ],
            "--time-column runs in f64, f32 or Q1.30, not --compensated",
        ),
        (
            vec![
                "--time-column",
                "--input",
                "rates",
                "--algo",
                "cf4",
                "--fixed",
            ],
            "--fixed supports --input increments only",
        ),
        (
            vec![
                "--time-column",
                "--input",
                "increments",
                "--algo",
                "coning3",
            ],
            "--time-column --input increments needs --t0",
        ),
        (
            vec!["--input", "increments", "--algo", "coning3"],
            "--dt is required",
        ),
        (
            vec![
                "--input", "rates", "--algo", "magnus4", "--dt", "0.01", "--t0", "1",
            ],
            "--t0 needs --time-column",
        ),
        (
            vec![
                "--time-column",
                "--input",
                "rates",
                "--algo",
                "magnus4",
                "--dt",
                "0.01",
                "--time-unit",
                "min",
            ],
            "--time-unit: unknown unit 'min' (one of s, ms, us)",
        ),
        (
            vec![
                "--input",
                "rates",
                "--algo",
                "magnus4",
                "--dt",
                "0.01",
                "--gyro-unit",
                "rpm",
            ],
            "--gyro-unit: unknown unit 'rpm' (one of rad/s, deg/s)",
        ),
        (
            vec![
                "--input", "rates", "--algo", "magnus4", "--dt", "0.01", "--remap", "y,x,z",
            ],
            "--remap: 'y,x,z' is a reflection",
        ),
        (
            vec![
                "--input", "rates", "--algo", "magnus4", "--dt", "0.01", "--remap", "x,x,z",
            ],
            "--remap: expected three distinct",
        ),
        (
            vec![
                "--input",
                "rates",
                "--algo",
                "magnus4",
                "--dt",
                "0.01",
                "--calibration",
                "/nonexistent/cal.txt",
            ],
            "--calibration /nonexistent/cal.txt:",
        ),
    ] {
        let out = run("propagate", &bad, "");
        assert_eq!(out.status, Some(2), "{bad:?}");
        assert!(
            out.stderr.starts_with(&format!("error: {msg}")),
            "{bad:?}: {}",
            out.stderr
        );
    }
}

#[test]
fn calibration_file_and_remap() {
    // A sensor mounted with body = (sensor x, −sensor z, sensor y), with bias, scale and
    // misalignment: the test writes what such a sensor reads (the inverse model, computed here)
    // and the tool must recover the body rates.
    let c = Coning {
        alpha: 0.2,
        omega_c: TAU * 1.7,
    };
    let m = [
        [1.0, 0.003, -0.002],
        [0.001, 1.0, 0.004],
        [-0.003, 0.002, 1.0],
    ];
    let s = [1.02, 0.97, 1.01];
    let b = [0.01, -0.02, 0.005];
    let dir = std::env::temp_dir().join(format!("gyrostat-cal-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("cal.txt");
    std::fs::write(
        &file,
        format!(
            "# a test sensor\ngyro_bias = {}\ngyro_scale = {}\ngyro_misalignment = {}, {}, {}\n\naccel_bias = 0, 0, 0.01\n",
            row(&b),
            row(&s),
            row(&m[0]),
            row(&m[1]),
            row(&m[2])
        ),
    )
    .unwrap();
    // K = M·diag(s); raw = K⁻¹·ω_sensor + b, with K⁻¹ by Cramer's rule here.
    let k: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| m[i][j] * s[j]));
    let det = k[0][0] * (k[1][1] * k[2][2] - k[1][2] * k[2][1])
        - k[0][1] * (k[1][0] * k[2][2] - k[1][2] * k[2][0])
        + k[0][2] * (k[1][0] * k[2][1] - k[1][1] * k[2][0]);
    let solve = |v: V3| -> V3 {
        std::array::from_fn(|col| {
            let mut kk = k;
            for r in 0..3 {
                kk[r][col] = v[r];
            }
            (kk[0][0] * (kk[1][1] * kk[2][2] - kk[1][2] * kk[2][1])
                - kk[0][1] * (kk[1][0] * kk[2][2] - kk[1][2] * kk[2][0])
                + kk[0][2] * (kk[1][0] * kk[2][1] - kk[1][1] * kk[2][0]))
                / det
        })
    };
    let ts = jittered(2e-3, 1500, 9);
    // body (x, y, z) = (sx, −sz, sy) ⇒ sensor (sx, sy, sz) = (bx, bz, −by).
    let to_sensor = |w: V3| [w[0], w[2], -w[1]];
    let input: String = ts
        .iter()
        .map(|&t| {
            let raw = add(solve(to_sensor(c.body_rate(t))), b);
            format!("{},{}\n", t * 1e6, row(&scale(raw, 360.0 / TAU)))
        })
        .collect();
    let q0 = row(&c.attitude(0.0));
    let fp = file.to_str().unwrap();
    let args = [
        "--time-column",
        "--input",
        "rates",
        "--algo",
        "magnus4",
        "--dt",
        "0.002",
        "--time-unit",
        "us",
        "--gyro-unit",
        "deg/s",
        "--q0",
        &q0,
        "--calibration",
        fp,
        "--remap",
        "x,-z,y",
    ];
    let out = run("propagate", &args, &input);
    assert_eq!(out.status, Some(0), "{}", out.stderr);
    let rows = timed_rows(&out.stdout);
    let worst = rows
        .iter()
        .map(|(_, t, q)| quat_angle(*q, c.attitude(*t)))
        .fold(0.0, f64::max);
    println!("calibrated, remapped: worst {worst:e} rad");
    assert!(worst < 1e-8, "{worst:e}");
    // Without the calibration the bias alone turns the body by ~0.02 rad/s × 3 s.
    let out = run("propagate", &args[..args.len() - 4], &input);
    let rows = timed_rows(&out.stdout);
    let (_, t, q) = *rows.last().unwrap();
    assert!(quat_angle(q, c.attitude(t)) > 1e-2);
    // A bad calibration file names its line.
    std::fs::write(&file, "gyro_bias = 1,2,3\ngyro_scale = 1, 0, 1\n").unwrap();
    let out = run("propagate", &args, &input);
    assert_eq!(out.status, Some(2));
    assert!(
        out.stderr
            .starts_with(&format!("error: --calibration {fp}: gyro (lines 1, 2): ")),
        "{}",
        out.stderr
    );
    std::fs::write(&file, "gyro_bias = 1,2,3\n\ngyro_bias = 1,2,3\n").unwrap();
    let out = run("propagate", &args, &input);
    assert!(
        out.stderr.contains("line 3: 'gyro_bias' given twice"),
        "{}",
        out.stderr
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn wrapping_microsecond_counter() {
    // A 32-bit µs counter that starts 2.5 s before its wrap; jittered ~1 ms steps for 6 s, so
    // the stream crosses 2³² µs. Times are whole microseconds.
    let c = Coning {
        alpha: 0.05,
        omega_c: TAU * 2.3,
    };
    let start: u64 = (1 << 32) - 2_500_000;
    let mut us = vec![0u64];
    let mut s: u64 = 11;
    while *us.last().unwrap() < 6_000_000 {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        us.push(us.last().unwrap() + 600 + (s >> 33) % 800);
    }
    let counter = |k: usize| (start + us[k]) % (1 << 32);
    assert!(counter(us.len() - 1) < counter(0), "the stream wraps");
    let q0 = row(&c.attitude(0.0));
    let sec = |k: usize| us[k] as f64 * 1e-6;
    // Rates at the counter times.
    let rates: String = (0..us.len())
        .map(|k| format!("{},{}\n", counter(k), row(&c.body_rate(sec(k)))))
        .collect();
    let args = [
        "--time-column",
        "--time-wrap",
        "--time-unit",
        "us",
        "--input",
        "rates",
        "--algo",
        "magnus4",
        "--dt",
        "0.001",
        "--q0",
        &q0,
    ];
    let out = run("propagate", &args, &rates);
    assert_eq!(out.status, Some(0), "{}", out.stderr);
    let rows = timed_rows(&out.stdout);
    assert_eq!(rows.len(), us.len());
    let t_first = start as f64 * 1e-6;
    let mut worst = 0.0f64;
    for (k, (rk, t, q)) in rows.iter().enumerate() {
        assert_eq!(*rk, k as u64);
        // The printed time is unwrapped: it keeps growing across the wrap.
        assert!((t - (t_first + sec(k))).abs() < 1e-9, "{k} {t}");
        worst = worst.max(quat_angle(*q, c.attitude(sec(k))));
    }
    println!("rates across the counter wrap: worst {worst:e} rad");
    assert!(worst < 5e-9, "{worst:e}");
    // Increments: --t0 the counter value at the start.
    let inc: String = (1..us.len())
        .map(|k| format!("{},{}\n", counter(k), row(&c.increment(sec(k - 1), sec(k)))))
        .collect();
    let t0 = counter(0).to_string();
    let out = run(
        "propagate",
        &[
            "--time-column",
            "--time-wrap",
            "--time-unit",
            "us",
            "--input",
            "increments",
            "--algo",
            "coning2",
            "--dt",
            "0.001",
            "--t0",
            &t0,
            "--q0",
            &q0,
        ],
        &inc,
    );
    assert_eq!(out.status, Some(0), "{}", out.stderr);
    let (_, t, q) = *timed_rows(&out.stdout).last().unwrap();
    let e = quat_angle(q, c.attitude(sec(us.len() - 1)));
    assert!((t - (t_first + sec(us.len() - 1))).abs() < 1e-9);
    println!("coning2 across the counter wrap: {e:e} rad");
    assert!(e < 1e-8, "{e:e}");
    // Not a counter value, a counter that steps back, usage errors.
    let out = run("propagate", &args, "4294967295,0,0,0\n12.5,0,0,0\n");
    assert_eq!(
        out.stderr,
        "error: line 2: timestamp 12.5: not a 32-bit counter value\n"
    );
    let out = run("propagate", &args, "100,0,0,0\n50,0,0,0\n");
    assert!(
        out.stderr.starts_with("error: line 2: timestamp 4.99"),
        "{}",
        out.stderr
    );
    let out = run(
        "propagate",
        &[
            "--time-column",
            "--time-wrap",
            "--input",
            "rates",
            "--algo",
            "magnus4",
            "--dt",
            "0.001",
        ],
        "",
    );
    assert_eq!(out.status, Some(2));
    assert!(
        out.stderr
            .starts_with("error: --time-wrap needs --time-unit us"),
        "{}",
        out.stderr
    );
}

#[test]
fn clipped_rows_by_policy() {
    // A constant 1 rad/s about x on a jittered clock; rows 10 and 11 read the full scale (the
    // sensor saturated: the true value is unknown, here the rate stayed 1 rad/s).
    let ts = jittered(1e-3, 40, 13);
    let rates: String = ts
        .iter()
        .enumerate()
        .map(|(k, t)| format!("{t},{},0.1,0\n", if k == 10 || k == 11 { 2.0 } else { 1.0 }))
        .collect();
    let base = [
        "--time-column",
        "--input",
        "rates",
        "--algo",
        "magnus4",
        "--dt",
        "0.001",
        "--gyro-full-scale",
        "2",
    ];
    let out = run("propagate", &base, &rates);
    assert_eq!(out.status, Some(1));
    assert_eq!(
        out.stderr,
        "error: line 11: gyro axis x clipped: |2| reaches the full scale 2 (--on-clip error)\n"
    );
    let t_end = ts[40] - ts[0];
    // The exact attitude of the constant rate (1, 0.1, 0) over t_end.
    let w = [1.0f64, 0.1, 0.0];
    let exact = qexp(scale(w, t_end));
    let last = |args: &[&str], input: &str| {
        let out = run("propagate", args, input);
        assert_eq!(out.status, Some(0), "{}", out.stderr);
        let (_, _, q) = *timed_rows(&out.stdout).last().unwrap();
        (q, out.stderr)
    };
    let mut hold = base.to_vec();
    hold.extend(["--on-clip", "hold"]);
    let (q, err) = last(&hold, &rates);
    assert!(quat_angle(q, exact) < 1e-14, "{}", quat_angle(q, exact));
    assert_eq!(
        err,
        "note: 2 samples had an axis at the full scale 2 (each clipped axis held at its last unclipped rate)\n"
    );
    let mut pass = base.to_vec();
    pass.extend(["--on-clip", "pass"]);
    let (q, err) = last(&pass, &rates);
    assert!(quat_angle(q, exact) > 1e-4);
    assert_eq!(
        err,
        "note: 2 samples had an axis at the full scale 2 (passed as read)\n"
    );
    // Increments: the full scale is an angle per row; hold takes the last rate times the row's
    // own interval.
    let inc: String = ts
        .windows(2)
        .enumerate()
        .map(|(k, p)| {
            let h = p[1] - p[0];
            let x = if k == 20 { 0.0015 } else { h };
            format!("{},{x},{},0\n", p[1], 0.1 * h)
        })
        .collect();
    let (q, err) = last(
        &[
            "--time-column",
            "--input",
            "increments",
            "--algo",
            "coning2",
            "--dt",
            "0.001",
            "--t0",
            "0",
            "--gyro-full-scale",
            "0.0015",
            "--on-clip",
            "hold",
        ],
        &inc,
    );
    assert!(quat_angle(q, exact) < 1e-14, "{}", quat_angle(q, exact));
    assert!(err.starts_with("note: 1 samples"), "{err}");
    let out = run(
        "propagate",
        &[
            "--input",
            "rates",
            "--algo",
            "magnus4",
            "--dt",
            "0.001",
            "--on-clip",
            "hold",
        ],
        "",
    );
    assert_eq!(out.stderr, "error: --on-clip needs --time-column\n");
}

#[test]
fn sensor_options_on_the_fixed_clock() {
    // Without --time-column the sensor options apply too: a constant rate (deg/s, sensor axes)
    // with a bias in the calibration file and a remap, on a fixed --dt, in f64, f32 and Q1.30.
    let dir = std::env::temp_dir().join(format!("gyrostat-cal2-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("cal.txt");
    std::fs::write(&file, "gyro_bias = 0.01, 0, 0   # rad/s\n").unwrap();
    let fp = file.to_str().unwrap();
    // Sensor reads x: 1 rad/s + 0.01 bias; body = (sensor z, sensor x, sensor y) ("z,x,y").
    let w_sensor = [1.01f64, 0.0, 0.2];
    let line = row(&scale(w_sensor, 360.0 / TAU)) + "\n";
    let rates = line.repeat(1001);
    // Body rate: (0.2, 1.0, 0.0) rad/s over 1 s.
    let exact = qexp([0.2, 1.0, 0.0]);
    for extra in [&[][..], &["--f32"][..]] {
        let mut args = vec![
            "--input",
            "rates",
            "--algo",
            "magnus4",
            "--dt",
            "0.001",
            "--gyro-unit",
            "deg/s",
            "--calibration",
            fp,
            "--remap",
            "z,x,y",
        ];
        args.extend(extra);
        let out = run("propagate", &args, &rates);
        assert_eq!(out.status, Some(0), "{}", out.stderr);
        let last = numbers(out.stdout.lines().last().unwrap());
        let e = quat_angle([last[1], last[2], last[3], last[4]], exact);
        assert!(
            e < if extra.is_empty() { 1e-12 } else { 1e-5 },
            "{extra:?} {e:e}"
        );
    }
    // Increments (deg per sample) through --fixed: the bias is subtracted over --dt.
    let inc = row(&scale(w_sensor, 1e-3 * 360.0 / TAU)) + "\n";
    let out = run(
        "propagate",
        &[
            "--input",
            "increments",
            "--algo",
            "coning2",
            "--dt",
            "0.001",
            "--gyro-unit",
            "deg/s",
            "--calibration",
            fp,
            "--remap",
            "z,x,y",
            "--fixed",
        ],
        &inc.repeat(1000),
    );
    assert_eq!(out.status, Some(0), "{}", out.stderr);
    let last = numbers(out.stdout.lines().last().unwrap());
    let e = quat_angle([last[1], last[2], last[3], last[4]], exact);
    assert!(e < 1e-7, "{e:e}");
    std::fs::remove_dir_all(&dir).ok();
}

/// The arithmetic flag of a run and its name.
const ARITH: [(&str, &[&str]); 3] = [("f64", &[]), ("f32", &["--f32"]), ("Q1.30", &["--fixed"])];

/// Every increment rule in f64, f32 and Q1.30 and every rate method in f64 and f32 on a jittered
/// clock (±40 % around 1 ms; coning at 3.3 Hz, half-angle 0.05 rad): the final and worst
/// attitude against the closed form of the motion (`host_tests::ref_propagation::Coning`,
/// exact), and the same samples integrated on the nominal 1 ms clock (timestamps ignored) far
/// off. Bounds: the measured error times about 3 (printed), per rule and type; the order of the
/// rules is the theory's (exp first order, coning1..4 and the rate methods higher).
#[test]
fn every_rule_and_method_on_a_jittered_clock() {
    let c = Coning {
        alpha: 0.05,
        omega_c: TAU * 3.3,
    };
    let n = 4000;
    let ts = jittered(1e-3, n, 11);
    let q0 = row(&c.attitude(0.0));
    let inc: Vec<V3> = ts.windows(2).map(|w| c.increment(w[0], w[1])).collect();
    let timed_inc: String = ts[1..]
        .iter()
        .zip(&inc)
        .map(|(t, v)| format!("{t},{}\n", row(v)))
        .collect();
    let plain_inc: String = inc.iter().map(|v| row(v) + "\n").collect();
    // (algo, bound f64, bound f32, bound Q1.30), about 3 times the measured worst: exp 8.6e-6
    // (first order: the coning drift) in every type; the coning rules 4.9e-9 to 5.9e-9 in f64
    // and Q1.30 (the third-order terms of the rotation vector, which no rule here carries: at
    // these steps they dominate the rules' own truncation), f32 at its rounding floor (7e-8 to
    // 2.2e-7). With the timestamps ignored every coning rule ends 4e-7 to 8e-7 rad off.
    // In Q1.30 coning3 and coning4 form their cross products of earlier increments in the
    // format, rounded each update (the carried attitude carries the residual of one
    // `lever × last` term, which is all the 1- and 2-sample rules have): their floor here is
    // 7e-8 rad, against 6e-9 for coning1 and coning2.
    let cases = [
        ("exp", 3e-5, 3e-5, 3e-5),
        ("coning1", 2e-8, 7e-7, 2e-8),
        ("coning2", 2e-8, 3e-7, 2e-8),
        ("coning3", 2e-8, 3e-7, 2e-7),
        ("coning4", 2e-8, 3e-7, 2e-7),
    ];
    for (algo, b64, b32, bq) in cases {
        for ((arith, flag), bound) in ARITH.iter().zip([b64, b32, bq]) {
            let mut args = vec![
                "--time-column",
                "--input",
                "increments",
                "--algo",
                algo,
                "--t0",
                "0",
                "--q0",
                &q0,
            ];
            args.extend_from_slice(flag);
            let out = run("propagate", &args, &timed_inc);
            assert_eq!(out.status, Some(0), "{algo} {arith}: {}", out.stderr);
            let rows = timed_rows(&out.stdout);
            assert_eq!(rows.len(), n, "{algo} {arith}");
            let worst = rows
                .iter()
                .map(|(_, t, q)| quat_angle(*q, c.attitude(*t)))
                .fold(0.0, f64::max);
            let (k, t, _) = rows[n - 1];
            assert_eq!((k, t), ((n - 1) as u64, ts[n]));
            // The same increments on the nominal clock: the rule's coefficients for equal
            // intervals, the printed time k·dt.
            let mut fixed_clock = vec![
                "--input",
                "increments",
                "--algo",
                algo,
                "--dt",
                "0.001",
                "--q0",
                &q0,
            ];
            fixed_clock.extend_from_slice(flag);
            let out = run("propagate", &fixed_clock, &plain_inc);
            assert_eq!(out.status, Some(0), "{}", out.stderr);
            let last = numbers(out.stdout.lines().last().unwrap());
            let ignored = quat_angle([last[1], last[2], last[3], last[4]], c.attitude(ts[n]));
            println!(
                "{algo} {arith}: worst {worst:.2e} rad on the jittered clock; its timestamps ignored: {ignored:.2e} rad at the end"
            );
            assert!(worst < bound, "{algo} {arith}: {worst:e}");
            // (In f32, and for coning3 and coning4 in Q1.30, the rounding floor hides part of
            // the difference.)
            if algo != "exp" && (*arith == "f64" || (*arith == "Q1.30" && algo < "coning3")) {
                assert!(ignored > 10.0 * worst, "{algo} {arith}: {ignored:e}");
            }
        }
    }
    let rates: String = ts
        .iter()
        .map(|&t| format!("{t},{}\n", row(&c.body_rate(t))))
        .collect();
    // Measured worst: f64 1.35e-9 (magnus4, cf4) and 1.42e-9 (rk4), fourth order at h <= 1.4
    // ms; f32 1.7e-7 to 2.9e-7 (its rounding floor).
    for algo in ["magnus4", "cf4", "rk4"] {
        for ((arith, flag), bound) in ARITH[..2].iter().zip([5e-9, 1e-6]) {
            let mut args = vec![
                "--time-column",
                "--input",
                "rates",
                "--algo",
                algo,
                "--q0",
                &q0,
            ];
            args.extend_from_slice(flag);
            let out = run("propagate", &args, &rates);
            assert_eq!(out.status, Some(0), "{algo} {arith}: {}", out.stderr);
            let rows = timed_rows(&out.stdout);
            assert_eq!(rows.len(), n + 1);
            let worst = rows
                .iter()
                .map(|(_, t, q)| quat_angle(*q, c.attitude(*t)))
                .fold(0.0, f64::max);
            println!("{algo} {arith}: worst {worst:.2e} rad on jittered rate samples");
            assert!(worst < bound, "{algo} {arith}: {worst:e}");
        }
    }
}

/// On an exactly regular clock (whole microseconds) the time-column rules whose unequal form
/// reduces to the equal one give the fixed-interval run's attitudes bit for bit in Q1.30 (exp,
/// coning1, coning2: the coefficients 1/12 and 2/3 of equal intervals, rounded to Q1.30 as the
/// library's rules round them); the unequal rule's coefficients there, checked through coning3
/// and coning4 on a rate polynomial of degree 2 and 3, leave only the third-order terms.
#[test]
fn regular_clock_reduces_to_the_fixed_interval_rules() {
    let c = Coning {
        alpha: 0.3,
        omega_c: TAU * 2.1,
    };
    let n = 600;
    let ts: Vec<f64> = (0..=n).map(|k| k as f64 * 1e-3).collect();
    let inc: Vec<V3> = ts.windows(2).map(|w| c.increment(w[0], w[1])).collect();
    let timed_inc: String = (0..n)
        .map(|k| format!("{},{}\n", (k + 1) * 1000, row(&inc[k])))
        .collect();
    let plain_inc: String = inc.iter().map(|v| row(v) + "\n").collect();
    for algo in ["exp", "coning1", "coning2"] {
        let timed = run(
            "propagate",
            &[
                "--time-column",
                "--input",
                "increments",
                "--algo",
                algo,
                "--t0",
                "0",
                "--time-unit",
                "us",
                "--fixed",
            ],
            &timed_inc,
        );
        assert_eq!(timed.status, Some(0), "{}", timed.stderr);
        let plain = run(
            "propagate",
            &[
                "--input",
                "increments",
                "--algo",
                algo,
                "--dt",
                "0.001",
                "--fixed",
            ],
            &plain_inc,
        );
        // The attitudes after each update (inside a group the two modes print different
        // provisional attitudes: the fixed-interval one by the rule of the pending number with
        // the increment before them, the time-column one without it).
        let group = if algo == "coning2" { 2 } else { 1 };
        let attitudes = |s: &str, drop: usize| -> Vec<String> {
            s.lines()
                .enumerate()
                .filter(|(k, _)| (k + 1) % group == 0)
                .map(|(_, l)| l.split(',').skip(drop).collect::<Vec<_>>().join(","))
                .collect()
        };
        let (a, b) = (attitudes(&timed.stdout, 2), attitudes(&plain.stdout, 1));
        assert_eq!(a.len(), n / group, "{algo}");
        let first = a.iter().zip(&b).position(|(x, y)| x != y);
        assert!(
            first.is_none(),
            "{algo}: update {first:?}: {:?} vs {:?}",
            first.map(|k| &a[k]),
            first.map(|k| &b[k])
        );
    }
}

/// `--dt` is optional with `--time-column`: the nominal interval is the median of the first 16
/// intervals. The attitudes are those of a run with `--dt` (it only sets the gap threshold), the
/// gap threshold follows the inferred interval, a wrapping microsecond counter infers it
/// modulo 2^32, and timestamps that do not increase give no nominal interval.
#[test]
fn nominal_interval_from_the_timestamps() {
    let c = Coning {
        alpha: 0.05,
        omega_c: TAU * 3.3,
    };
    let ts = jittered(1e-2, 300, 5);
    let rates: String = ts
        .iter()
        .map(|&t| format!("{t},{}\n", row(&c.body_rate(t))))
        .collect();
    let base = ["--time-column", "--input", "rates", "--algo", "rk4"];
    let inferred = run("propagate", &base, &rates);
    assert_eq!(inferred.status, Some(0), "{}", inferred.stderr);
    let mut with_dt = base.to_vec();
    with_dt.extend(["--dt", "0.01"]);
    assert_eq!(inferred.stdout, run("propagate", &with_dt, &rates).stdout);
    // 10 ms samples with a 60 ms step: a gap at the default factor 5 of the inferred 10 ms
    // (with --dt 0.02 it is not).
    let gap: String = (0..20)
        .map(|k| format!("{},0.1,0,0\n", if k < 18 { k * 10 } else { k * 10 + 50 }))
        .collect();
    let ms = [
        "--time-column",
        "--input",
        "rates",
        "--algo",
        "cf4",
        "--time-unit",
        "ms",
    ];
    let out = run("propagate", &ms, &gap);
    assert_eq!(out.status, Some(1));
    assert!(
        out.stderr.starts_with("error: line 19: gap: 6e-2 s since the previous sample, more than --gap-factor 5 times the nominal 1e-2 s"),
        "{}",
        out.stderr
    );
    let mut ms20 = ms.to_vec();
    ms20.extend(["--dt", "0.02"]);
    assert_eq!(run("propagate", &ms20, &gap).status, Some(0));
    // A 32-bit microsecond counter wrapping in the first intervals: 1 ms inferred.
    let start = 4_294_967_296u64 - 3_000;
    let wrapped: String = (0..40u64)
        .map(|k| format!("{},0,0,0.5\n", (start + k * 1000) % 4_294_967_296))
        .collect();
    let out = run(
        "propagate",
        &[
            "--time-column",
            "--input",
            "rates",
            "--algo",
            "magnus4",
            "--time-unit",
            "us",
            "--time-wrap",
        ],
        &wrapped,
    );
    assert_eq!(out.status, Some(0), "{}", out.stderr);
    let rows = timed_rows(&out.stdout);
    let (_, t, q) = rows[39];
    assert!((t - rows[0].1 - 0.039).abs() < 1e-9, "{t}");
    assert!((q[3] - (0.5f64 * 0.039 / 2.0).sin()).abs() < 1e-12, "{q:?}");
    // Increments: --t0 and the first rows; repeated timestamps give no nominal interval.
    let same: String = (0..20).map(|_| "5,0.001,0,0\n").collect();
    let out = run(
        "propagate",
        &[
            "--time-column",
            "--input",
            "increments",
            "--algo",
            "coning4",
            "--t0",
            "5",
        ],
        &same,
    );
    assert_eq!(out.status, Some(1));
    assert!(
        out.stderr.starts_with(
            "error: line 16: no --dt and the first 17 timestamps give no nominal interval"
        ),
        "{}",
        out.stderr
    );
    assert_eq!(out.stdout, "");
}
