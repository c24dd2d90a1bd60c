//! `synthesize` as a process: the noise-free log against closed-form motion (a constant rate
//! about a tilted axis, the torque-free symmetric top through `simulate`, the hand-held rotation
//! integrated back to its truth, the translation's specific force), every part of the sensor
//! model against an independent computation (bias, scale, misalignment, saturation,
//! quantisation, hard and soft iron, the magnetometer's delay and rate, a magnet fixed on the
//! device, a passing dipole, white noise, clock jitter), `estimate --truth` on a noise-free log,
//! a slice of the synthetic benchmark grid (benches/synthetic/grid.py), determinism, and the
//! error paths.
//!
//! The references are the test's own: rotation matrices from `host_tests::reference::quat_matrix`
//! (not the tool's quaternion sandwich), matrix inverses by cofactors
//! (`host_tests::ref_dynamics::inverse`, not the library's), the symmetric top's rates in
//! closed form (Euler's equations solved by hand), the dipole's field as `μ0/(4π)` times the
//! gradient form.

use std::io::Write;

use host_tests::ref_dynamics::inverse;
use host_tests::reference::{
    M3, mat_mul, mat_vec, qmul, quat_angle, quat_exp, quat_matrix, transpose,
};

use crate::cli::{Closed, Output, run, run_closed};

const HEADER: &str = "t_s,gyr_x_rad_s,gyr_y_rad_s,gyr_z_rad_s,acc_x_m_s2,acc_y_m_s2,acc_z_m_s2,mag_x_uT,mag_y_uT,mag_z_uT,opt_qw,opt_qx,opt_qy,opt_qz,movement";
const G: f64 = 9.81;
const FIELD: [f64; 3] = [0.0, 15.8, -40.7];

/// One row of a log: the numbers (NaN for an empty field).
struct Row(Vec<f64>);

impl Row {
    fn t(&self) -> f64 {
        self.0[0]
    }
    fn gyr(&self) -> [f64; 3] {
        [self.0[1], self.0[2], self.0[3]]
    }
    fn acc(&self) -> [f64; 3] {
        [self.0[4], self.0[5], self.0[6]]
    }
    fn mag(&self) -> Option<[f64; 3]> {
        self.0[7]
            .is_finite()
            .then(|| [self.0[7], self.0[8], self.0[9]])
    }
    fn q(&self) -> [f64; 4] {
        [self.0[10], self.0[11], self.0[12], self.0[13]]
    }
    fn moving(&self) -> bool {
        self.0[14] == 1.0
    }
    /// The `--kinematics` columns from 15 on: rate, position, linear and body acceleration.
    fn extra(&self, k: usize) -> [f64; 3] {
        [self.0[15 + 3 * k], self.0[16 + 3 * k], self.0[17 + 3 * k]]
    }
}

fn ok(out: &Output) {
    assert_eq!(out.status, Some(0), "stderr: {}", out.stderr);
}

fn log(args: &[&str]) -> Vec<Row> {
    log_with(args, "")
}

fn log_with(args: &[&str], stdin: &str) -> Vec<Row> {
    let out = run("synthesize", args, stdin);
    ok(&out);
    let mut lines = out.stdout.lines();
    let head = lines.next().expect("a header");
    assert!(head.starts_with(HEADER), "{head}");
    lines
        .map(|l| {
            Row(l
                .split(',')
                .map(|f| {
                    if f.is_empty() {
                        f64::NAN
                    } else {
                        f.parse().unwrap()
                    }
                })
                .collect())
        })
        .collect()
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// `R(q)ᵀ v` through the rotation matrix.
fn to_body(q: [f64; 4], v: [f64; 3]) -> [f64; 3] {
    mat_vec(&transpose(&quat_matrix(q)), &v)
}

fn rows_of(v: &[f64]) -> M3 {
    [[v[0], v[1], v[2]], [v[3], v[4], v[5]], [v[6], v[7], v[8]]]
}

fn diag(v: [f64; 3]) -> M3 {
    [[v[0], 0.0, 0.0], [0.0, v[1], 0.0], [0.0, 0.0, v[2]]]
}

fn write_spec(name: &str, text: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("gyrostat-synthesize-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::File::create(&path)
        .and_then(|mut f| f.write_all(text.as_bytes()))
        .unwrap();
    path
}

// ---------------------------------------------------------------------------------------------
// Closed-form motion

/// A constant body rate about a tilted axis: `q(t) = q0 ⊗ exp(W t/2)`, the gyro `W`, the
/// specific force `R(q)ᵀ g ẑ`, the field `R(q)ᵀ B`, every row to rounding.
#[test]
fn constant_rate_about_a_tilted_axis_is_exact() {
    let q0 = qmul(quat_exp([0.0, 0.0, 0.5]), quat_exp([0.3, 0.0, 0.0]));
    let q0s = format!("{:?},{:?},{:?},{:?}", q0[0], q0[1], q0[2], q0[3]);
    let w = [0.3, -0.5, 0.81];
    let rows = log(&[
        "--motion",
        "spin:0.3,-0.5,0.81",
        "--rest",
        "0",
        "--ramp",
        "0",
        "--phases",
        "1",
        "--duration",
        "20",
        "--rate",
        "50",
        "--q0",
        &q0s,
    ]);
    assert_eq!(rows.len(), 1001);
    for r in &rows {
        let t = r.t();
        let q = qmul(q0, quat_exp(w.map(|x| x * t)));
        assert!(quat_angle(r.q(), q) < 1e-12, "t {t}: attitude");
        assert!(dist(r.gyr(), w) < 1e-15, "t {t}: gyro {:?}", r.gyr());
        assert!(
            dist(r.acc(), to_body(q, [0.0, 0.0, G])) < 1e-12,
            "t {t}: accel"
        );
        assert!(
            dist(r.mag().unwrap(), to_body(q, FIELD)) < 1e-12,
            "t {t}: mag"
        );
        assert!(r.moving());
    }
}

/// `simulate`'s torque-free symmetric top (I1 = I2) through `synthesize --motion -`: the gyro
/// is Euler's closed form `ω3 = const`, `ω1 + iω2 = (ω1 + iω2)(0)·e^(iλt)`,
/// `λ = (I3 − I1)/I1·ω3`, after a rest phase of zero rate at the first attitude; the lab
/// momentum `R(q)·I·ω` of the log's own attitude and gyro stays constant.
#[test]
fn simulated_symmetric_top_gyro_is_the_closed_form() {
    let sim = run(
        "simulate",
        &[
            "--inertia",
            "2,2,3",
            "--omega",
            "0.4,-0.3,1.5",
            "--q0",
            "0.9,0.3,-0.1,0.3",
            "--dt",
            "0.01",
            "--steps",
            "2000",
            "--integrator",
            "exact",
        ],
        "",
    );
    assert!(
        sim.status == Some(0) || !sim.stderr.contains("error"),
        "{}",
        sim.stderr
    );
    let q0 = {
        let q = [0.9f64, 0.3, -0.1, 0.3];
        let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
        q.map(|x| x / n)
    };
    let rows = log_with(&["--motion", "-", "--rest", "1"], &sim.stdout);
    assert_eq!(rows.len(), 100 + 2001);
    let lambda = (3.0 - 2.0) / 2.0 * 1.5;
    let inertia = diag([2.0, 2.0, 3.0]);
    let mut l0 = None;
    for (k, r) in rows.iter().enumerate() {
        if k < 100 {
            assert_eq!(r.gyr(), [0.0; 3], "rest row {k}");
            assert!(quat_angle(r.q(), q0) < 1e-12 && !r.moving());
            continue;
        }
        let t = (k - 100) as f64 * 0.01;
        assert!((r.t() - (1.0 + t)).abs() < 1e-9);
        let (s, c) = (lambda * t).sin_cos();
        let w = [0.4 * c + 0.3 * s, 0.4 * s - 0.3 * c, 1.5];
        assert!(
            dist(r.gyr(), w) < 1e-9,
            "t {t}: gyro {:?} vs {w:?}",
            r.gyr()
        );
        assert!(dist(r.acc(), to_body(r.q(), [0.0, 0.0, G])) < 1e-12);
        let l = mat_vec(&quat_matrix(r.q()), &mat_vec(&inertia, &r.gyr()));
        let l0 = *l0.get_or_insert(l);
        assert!(dist(l, l0) < 1e-9, "t {t}: lab momentum {l:?} vs {l0:?}");
        assert!(r.moving());
    }
}

/// The hand-held rotation's gyro (closed-form Euler-angle rates through the warped time),
/// integrated by RK4 over pairs of 1 kHz samples (the middle sample is the midpoint rate),
/// reproduces the log's closed-form attitude: the rates and the attitude describe one motion.
#[test]
fn handheld_gyro_integrates_to_its_truth() {
    let rows = log(&[
        "--motion",
        "handheld",
        "--rate",
        "1000",
        "--rest",
        "1",
        "--duration",
        "12",
        "--phases",
        "2",
        "--ramp",
        "0.7",
        "--seed",
        "7",
    ]);
    let h = 2e-3;
    let deriv = |q: [f64; 4], w: [f64; 3]| {
        let d = qmul(q, [0.0, w[0], w[1], w[2]]);
        d.map(|x| 0.5 * x)
    };
    let axpy = |q: [f64; 4], a: f64, d: [f64; 4]| -> [f64; 4] {
        core::array::from_fn(|i| q[i] + a * d[i])
    };
    let mut q = rows[0].q();
    let mut worst: f64 = 0.0;
    let mut peak_rate: f64 = 0.0;
    for k in (0..rows.len() - 2).step_by(2) {
        let (w0, w1, w2) = (rows[k].gyr(), rows[k + 1].gyr(), rows[k + 2].gyr());
        peak_rate = peak_rate.max(w0.iter().map(|x| x * x).sum::<f64>().sqrt());
        let k1 = deriv(q, w0);
        let k2 = deriv(axpy(q, h / 2.0, k1), w1);
        let k3 = deriv(axpy(q, h / 2.0, k2), w1);
        let k4 = deriv(axpy(q, h, k3), w2);
        q = core::array::from_fn(|i| q[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
        worst = worst.max(quat_angle(q, rows[k + 2].q()));
    }
    assert!(
        peak_rate > 1.5,
        "a hand-held motion turns: peak {peak_rate} rad/s"
    );
    // Measured 1.5e-12 rad (RK4's h⁴ error at h = 2 ms and f64 rounding).
    assert!(worst < 1e-10, "integrated gyro vs truth: {worst} rad");
    // The rest phases hold still, and the movement flag marks the phases.
    let moving = rows.iter().filter(|r| r.moving()).count();
    assert_eq!(
        moving,
        2 * 12000 + 1 + 1,
        "two 12 s phases (their end samples included)"
    );
    for r in rows.iter().filter(|r| !r.moving()) {
        assert!(dist(r.gyr(), [0.0; 3]) < 1e-15);
    }
}

/// The translation: the specific force is `R(q)ᵀ(a + g ẑ)` with `a` the closed-form linear
/// acceleration (`--kinematics`), and that `a` is the second derivative of the position (a
/// fourth-order difference of the closed-form position at 1 kHz), through the ramps too.
#[test]
fn translation_specific_force_is_exact() {
    let rows = log(&[
        "--motion",
        "handheld",
        "--translation",
        "0.3",
        "--rate",
        "1000",
        "--rest",
        "0.5",
        "--duration",
        "6",
        "--phases",
        "1",
        "--ramp",
        "0.8",
        "--kinematics",
        "--seed",
        "3",
    ]);
    let mut peak: f64 = 0.0;
    for r in &rows {
        let a = r.extra(2);
        let up = [a[0], a[1], a[2] + G];
        assert!(dist(r.acc(), to_body(r.q(), up)) < 1e-12, "t {}", r.t());
        assert_eq!(r.extra(3), [0.0; 3]);
        assert!(dist(r.extra(0), r.gyr()) < 1e-15);
        peak = peak.max(a.iter().map(|x| x.abs()).fold(0.0, f64::max));
    }
    assert!(peak > 2.0, "the translation accelerates: {peak} m/s^2");
    let h = 1e-3;
    // The ramps' jerk jumps at their edges (s is C² there, not C³): a stencil straddling an
    // edge is off by about h times the jump; elsewhere it is exact to its h⁴ error.
    let edges = [0.5, 1.3, 5.7, 6.5];
    let (mut worst, mut worst_edge): (f64, f64) = (0.0, 0.0);
    for k in 2..rows.len() - 2 {
        let p = |j: usize| rows[j].extra(1);
        let fd: [f64; 3] = core::array::from_fn(|i| {
            (-p(k - 2)[i] + 16.0 * p(k - 1)[i] - 30.0 * p(k)[i] + 16.0 * p(k + 1)[i] - p(k + 2)[i])
                / (12.0 * h * h)
        });
        let e = dist(fd, rows[k].extra(2));
        if edges.iter().any(|t| (rows[k].t() - t).abs() < 2.5 * h) {
            worst_edge = worst_edge.max(e);
        } else {
            worst = worst.max(e);
        }
    }
    // Measured 1.9e-9 (rounding: ε·|p|/h²) and 4.8e-4 m/s².
    assert!(worst < 1e-6, "d²p/dt² vs a: {worst} m/s^2");
    assert!(
        worst_edge < 2e-3,
        "d²p/dt² vs a at the ramps' edges: {worst_edge} m/s^2"
    );
}

// ---------------------------------------------------------------------------------------------
// The sensor model, against the test's own computation

const SPEC: &str = "\
rate = 200
gyro_bias = 0.01, -0.02, 0.005
gyro_scale = 1.02, 0.97, 1.01
gyro_misalignment = 1,0.01,-0.02, 0.015,1,0.01, -0.01,0.02,1
gyro_range = 1.5
gyro_lsb = 0.002
accel_bias = 0.1, -0.2, 0.15
accel_scale = 0.98, 1.03, 1.0
accel_misalignment = 1,-0.01,0.02, 0.01,1,-0.015, 0.02,0.01,1
accel_range = 9.5
accel_lsb = 0.01
mag_hard_iron = 5, -3, 12
mag_soft_iron = 1.05,0.02,-0.01, 0.02,0.95,0.03, -0.01,0.03,1.02
mag_delay = 0.015
mag_rate = 50
";

/// `M·diag(s)·(raw − b)` undoes the sensor: raw = (M·diag(s))⁻¹·true + b, clipped, rounded.
fn inertial(true_v: [f64; 3], m: &[f64], s: [f64; 3], b: [f64; 3], range: f64) -> [f64; 3] {
    let k_inv = inverse(&mat_mul(&rows_of(m), &diag(s)));
    let raw = mat_vec(&k_inv, &true_v);
    core::array::from_fn(|i| (raw[i] + b[i]).clamp(-range, range))
}

fn check_quantised(got: f64, want: f64, lsb: f64, what: &str) {
    let n = got / lsb;
    assert!(
        (n - n.round()).abs() < 1e-6,
        "{what}: {got} is not a multiple of {lsb}"
    );
    assert!(
        (got - want).abs() <= lsb / 2.0 + 1e-9,
        "{what}: {got} vs {want} (lsb {lsb})"
    );
}

/// Bias, scale, misalignment, saturation and quantisation of gyro and accelerometer; hard and
/// soft iron, the delay and the rate of the magnetometer: the log of a spec against the ideal
/// log of the same motion, each value recomputed here.
#[test]
fn sensor_errors_match_an_independent_model() {
    let spec = write_spec("errors.spec", SPEC);
    let common = [
        "--motion",
        "handheld",
        "--translation",
        "0.2",
        "--rest",
        "1",
        "--duration",
        "10",
        "--phases",
        "1",
        "--seed",
        "11",
    ];
    let ideal = log(&[&common[..], &["--rate", "200"]].concat());
    let real = log(&[&common[..], &["--sensor", spec.to_str().unwrap()]].concat());
    assert_eq!(ideal.len(), real.len());
    let (mut gyro_sat, mut accel_sat, mut mags) = (0, 0, 0);
    let s_inv = inverse(&rows_of(&[
        1.05, 0.02, -0.01, 0.02, 0.95, 0.03, -0.01, 0.03, 1.02,
    ]));
    for (k, (i, r)) in ideal.iter().zip(&real).enumerate() {
        assert_eq!(i.q(), r.q());
        let g = inertial(
            i.gyr(),
            &[1.0, 0.01, -0.02, 0.015, 1.0, 0.01, -0.01, 0.02, 1.0],
            [1.02, 0.97, 1.01],
            [0.01, -0.02, 0.005],
            1.5,
        );
        let a = inertial(
            i.acc(),
            &[1.0, -0.01, 0.02, 0.01, 1.0, -0.015, 0.02, 0.01, 1.0],
            [0.98, 1.03, 1.0],
            [0.1, -0.2, 0.15],
            9.5,
        );
        for j in 0..3 {
            check_quantised(r.gyr()[j], g[j], 0.002, &format!("row {k} gyro {j}"));
            check_quantised(r.acc()[j], a[j], 0.01, &format!("row {k} accel {j}"));
        }
        gyro_sat += g.iter().filter(|x| x.abs() == 1.5).count();
        accel_sat += a.iter().filter(|x| x.abs() == 9.5).count();
        // The magnetometer: every 4th row (50 of 200 Hz), 3 rows (15 ms) behind.
        assert_eq!(r.mag().is_some(), k % 4 == 0, "row {k}: mag rate");
        if let Some(m) = r.mag()
            && k >= 3
        {
            let behind = to_body(ideal[k - 3].q(), FIELD);
            let want = mat_vec(&s_inv, &behind);
            let want = [want[0] + 5.0, want[1] - 3.0, want[2] + 12.0];
            assert!(dist(m, want) < 1e-9, "row {k}: mag {m:?} vs {want:?}");
            mags += 1;
        }
    }
    assert!(
        gyro_sat > 10 && accel_sat > 10,
        "saturation exercised: {gyro_sat}, {accel_sat}"
    );
    assert!(mags > 400);
}

/// A magnet fixed on the device adds its field to the raw reading from its time on, and
/// nothing before; a passing dipole adds `μ0/(4π)·(3(m·r)r/|r|⁵ − m/|r|³)` along its path.
#[test]
fn magnetic_disturbances_match_their_physics() {
    let base = [
        "--motion",
        "rest",
        "--rest",
        "1",
        "--duration",
        "20",
        "--phases",
        "1",
        "--rate",
        "20",
    ];
    let clean = log(&base);
    let fixed = log(&[&base[..], &["--magnet-fixed", "20,-10,15,7.5"]].concat());
    for (c, f) in clean.iter().zip(&fixed) {
        let d = dist(f.mag().unwrap(), c.mag().unwrap());
        let want = if c.t() >= 7.5 {
            (400.0f64 + 100.0 + 225.0).sqrt()
        } else {
            0.0
        };
        assert!((d - want).abs() < 1e-9, "t {}: {d}", c.t());
    }
    // The pass: 2 A m², 0.25 m north of the sensor at its closest, 0.1 m/s east, at the middle of
    // the phase (t = 1 + 10 s); the moment along (0.48, -0.6, 0.64).
    let pass = log(&[&base[..], &["--magnet-pass", "2,0.25,0.1"]].concat());
    let m = [0.48 * 2.0, -0.6 * 2.0, 0.64 * 2.0];
    let mut peak: f64 = 0.0;
    for (c, p) in clean.iter().zip(&pass) {
        let r = [-(0.1 * (c.t() - 11.0)), -0.25, 0.0];
        let r2: f64 = r.iter().map(|x| x * x).sum();
        let mr: f64 = m.iter().zip(&r).map(|(a, b)| a * b).sum();
        let b: [f64; 3] = core::array::from_fn(|i| {
            1e-7 * 1e6 * (3.0 * mr * r[i] / r2.powf(2.5) - m[i] / r2.powf(1.5))
        });
        let got: [f64; 3] = core::array::from_fn(|i| p.mag().unwrap()[i] - c.mag().unwrap()[i]);
        assert!(dist(got, b) < 1e-9, "t {}: {got:?} vs {b:?}", c.t());
        peak = peak.max(dist(got, [0.0; 3]));
    }
    assert!(peak > 10.0, "the pass disturbs: {peak} uT");
    // Steel: the field changes by w·ΔB, w = sin²(π u/L) over the middle half of the phase
    // (u from a quarter in, L half the phase: from t = 6 s for 10 s here), earth frame.
    let steel = log(&[&base[..], &["--steel", "10,-8,12"]].concat());
    for (c, p) in clean.iter().zip(&steel) {
        let u = c.t() - 6.0;
        let w = if (0.0..10.0).contains(&u) {
            (std::f64::consts::PI * u / 10.0).sin().powi(2)
        } else {
            0.0
        };
        let got: [f64; 3] = core::array::from_fn(|i| p.mag().unwrap()[i] - c.mag().unwrap()[i]);
        assert!(
            dist(got, [10.0 * w, -8.0 * w, 12.0 * w]) < 1e-9,
            "t {}: {got:?}",
            c.t()
        );
    }
}

/// Vibration and taps: the specific force is `R(q)ᵀ(a + g ẑ)` plus the body-frame acceleration
/// the `--kinematics` columns give, which is zero at rest and reaches the taps' amplitude.
#[test]
fn vibration_and_taps_add_in_the_sensor_frame() {
    let rows = log(&[
        "--motion",
        "handheld",
        "--vibration",
        "3,40",
        "--taps",
        "20",
        "--rate",
        "1000",
        "--rest",
        "1",
        "--duration",
        "8",
        "--phases",
        "1",
        "--kinematics",
        "--seed",
        "4",
    ]);
    let mut peak: f64 = 0.0;
    for r in &rows {
        let a = r.extra(2);
        let f = to_body(r.q(), [a[0], a[1], a[2] + G]);
        let b = r.extra(3);
        let want = [f[0] + b[0], f[1] + b[1], f[2] + b[2]];
        assert!(dist(r.acc(), want) < 1e-12, "t {}", r.t());
        if !r.moving() {
            assert_eq!(b, [0.0; 3]);
        }
        peak = peak.max(dist(b, [0.0; 3]));
    }
    assert!(
        peak > 15.0 && peak < 20.0 + 3.0 * 3f64.sqrt(),
        "peak body acceleration {peak}"
    );
}

/// White noise: at rest, the gyro's sample standard deviation is `N·√rate` (within 3 %: 3 × 20
/// 000 samples); the time stamps jitter by the spec's standard deviation while the truth stays
/// on the nominal grid; the seed makes the log, byte for byte.
#[test]
fn noise_jitter_and_seeds() {
    let spec = write_spec(
        "noise.spec",
        "rate = 400\ngyro_noise_density = 1e-3\nclock_jitter = 1e-4\n",
    );
    let args = [
        "--motion",
        "rest",
        "--rest",
        "50",
        "--phases",
        "0",
        "--sensor",
        spec.to_str().unwrap(),
    ];
    let rows = log(&args);
    assert_eq!(rows.len(), 20_001);
    let want = 1e-3 * 400f64.sqrt();
    for j in 0..3 {
        let n = rows.len() as f64;
        let mean = rows.iter().map(|r| r.gyr()[j]).sum::<f64>() / n;
        let sd = (rows
            .iter()
            .map(|r| (r.gyr()[j] - mean).powi(2))
            .sum::<f64>()
            / (n - 1.0))
            .sqrt();
        assert!(
            (sd / want - 1.0).abs() < 0.03,
            "axis {j}: sd {sd} vs {want}"
        );
    }
    let e: Vec<f64> = rows
        .iter()
        .enumerate()
        .map(|(k, r)| r.t() - k as f64 / 400.0)
        .collect();
    let sd = (e.iter().map(|x| x * x).sum::<f64>() / e.len() as f64).sqrt();
    assert!((sd / 1e-4 - 1.0).abs() < 0.03, "jitter sd {sd}");
    let a = run("synthesize", &[&args[..], &["--seed", "5"]].concat(), "");
    let b = run("synthesize", &[&args[..], &["--seed", "5"]].concat(), "");
    let c = run("synthesize", &[&args[..], &["--seed", "6"]].concat(), "");
    assert_eq!(a.stdout, b.stdout);
    assert_ne!(a.stdout, c.stdout);
}

// ---------------------------------------------------------------------------------------------
// Estimators on synthetic logs

fn truth_of(stderr: &str) -> [f64; 3] {
    let line = stderr
        .lines()
        .find(|l| l.starts_with("truth: "))
        .expect("a truth line");
    let v: Vec<f64> = line
        .split([' ', ','])
        .filter_map(|w| w.parse().ok())
        .collect();
    [v[0], v[1], v[2]]
}

fn score(args: &[&str]) -> [f64; 3] {
    let out = run("synthesize", args, "");
    ok(&out);
    let est = run("estimate", &["--truth"], &out.stdout);
    ok(&est);
    truth_of(&est.stderr)
}

/// A noise-free log scores near zero: what is left is the estimator's own lag (measured
/// 0.35° total for this motion; the bound leaves room for estimator changes, not for a
/// wrong sign or frame, which cost tens of degrees).
#[test]
fn estimate_scores_a_noise_free_log_near_zero() {
    let [total, heading, incl] = score(&["--seed", "0"]);
    assert!(
        total < 1.0 && heading < 1.0 && incl < 0.5,
        "{total} {heading} {incl}"
    );
}

/// A slice of the synthetic benchmark grid (benches/synthetic/grid.py: the same synthesize
/// flags): consumer grade at 25 and 285.7 Hz, undisturbed and with a passing magnet, 10 s
/// phases. The bounds are about twice today's (measured: undisturbed 4.7-5.2° total, 0.7-0.9°
/// inclination; the magnet 9.6-14.5°): a regression guard, and the disturbance must show.
#[test]
fn grid_slice() {
    for rate in ["25", "285.714285714"] {
        let base = [
            "--sensor",
            "consumer",
            "--rate",
            rate,
            "--seed",
            "0",
            "--duration",
            "10",
            "--phases",
            "2",
            "--rest",
            "5",
        ];
        let clean = score(&base);
        let magnet = score(&[&base[..], &["--magnet-pass", "1,0.2,0.05"]].concat());
        assert!(
            clean[0] < 12.0 && clean[2] < 2.0,
            "{rate} Hz undisturbed: {clean:?}"
        );
        assert!(magnet[0] < 30.0, "{rate} Hz passing magnet: {magnet:?}");
        assert!(
            magnet[1] > clean[1],
            "{rate} Hz: the magnet must cost heading: {magnet:?} vs {clean:?}"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// The interface

#[test]
fn presets_print_and_errors_are_one_line() {
    for p in ["ideal", "consumer", "industrial", "tactical"] {
        let out = run("synthesize", &["--sensor", p, "--print-sensor"], "");
        ok(&out);
        assert!(out.stdout.contains("rate ="), "{p}");
    }
    let spec = write_spec("bad.spec", "rate = 100\n\ngyro_wobble = 1\n");
    let cases: [(&[&str], &str, &str); 8] = [
        (
            &["--sensor", "nope"],
            "",
            "error: --sensor nope: not a preset",
        ),
        (
            &["--sensor", spec.to_str().unwrap()],
            "",
            "line 3: unknown key 'gyro_wobble'",
        ),
        (
            &["--rate", "0"],
            "",
            "error: --rate: must be finite and > 0, got 0",
        ),
        (
            &["--motion", "spin:1,2"],
            "",
            "error: --motion: expected 3 comma-separated numbers",
        ),
        (
            &["--motion", "-", "--rate", "10"],
            "t,qw,qx,qy,qz,w1,w2,w3\n0,1,0,0,0,0,0,0\n0.1,1,0,0,0,0,0,0\n",
            "error: --rate: not with --motion FILE",
        ),
        (
            &["--motion", "-"],
            "t,qw,qx,qy,qz,w1,w2,w3\n0,1,0,0,0,0,0,0\n0.1,1,0,0,0,0,0,0\n0.3,1,0,0,0,0,0,0\n",
            "not uniformly spaced",
        ),
        (
            &["--duration", "1", "--ramp", "0.6"],
            "",
            "error: --ramp: two ramps",
        ),
        (
            &["--seed", "1", "--seed", "2"],
            "",
            "error: --seed given more than once",
        ),
    ];
    for (args, stdin, want) in cases {
        let out = run("synthesize", args, stdin);
        assert_eq!(out.status, Some(2), "{args:?}: {}", out.stderr);
        assert!(out.stdout.is_empty(), "{args:?}");
        assert_eq!(out.stderr.lines().count(), 1, "{args:?}: {}", out.stderr);
        assert!(out.stderr.contains(want), "{args:?}: {}", out.stderr);
    }
}

/// The loop the spec file closes: a rest log of the industrial preset, characterised by
/// `characterize --spec`, gives a spec `synthesize` reads; its white noise densities are the
/// preset's (within 10 %: 1 h at 200 Hz; tools/tests/tools/characterize.rs holds the rest of the fit).
#[test]
fn characterize_writes_a_spec_synthesize_reads() {
    let log = run(
        "synthesize",
        &[
            "--motion",
            "rest",
            "--rest",
            "3600",
            "--phases",
            "0",
            "--sensor",
            "industrial",
            "--seed",
            "2",
        ],
        "",
    );
    ok(&log);
    let spec = write_spec("characterized.spec", "");
    let out = run(
        "characterize",
        &["--spec", spec.to_str().unwrap()],
        &log.stdout,
    );
    ok(&out);
    let printed = run(
        "synthesize",
        &["--sensor", spec.to_str().unwrap(), "--print-sensor"],
        "",
    );
    ok(&printed);
    let value = |key: &str| -> f64 {
        let line = printed
            .stdout
            .lines()
            .find(|l| l.starts_with(&format!("{key} =")))
            .unwrap_or_else(|| panic!("{key} in {}", printed.stdout));
        line.split(['=', '#'])
            .nth(1)
            .unwrap()
            .trim()
            .parse()
            .unwrap()
    };
    assert!((value("gyro_noise_density") / 9.9e-5 - 1.0).abs() < 0.1);
    assert!((value("accel_noise_density") / 6.2e-4 - 1.0).abs() < 0.1);
    assert!((value("rate") / 200.0 - 1.0).abs() < 1e-6);
    let again = run(
        "synthesize",
        &[
            "--sensor",
            spec.to_str().unwrap(),
            "--motion",
            "rest",
            "--rest",
            "1",
            "--phases",
            "0",
        ],
        "",
    );
    ok(&again);
}

/// Absurd lengths are usage errors before any output; a closed stdout ends a run quietly.
#[test]
fn huge_logs_and_closed_pipes() {
    for args in [
        &["--duration", "1e300"][..],
        &["--rest", "1e300"][..],
        &["--rate", "1e12", "--duration", "1"][..],
    ] {
        let out = run("synthesize", args, "");
        assert_eq!(out.status, Some(2), "{args:?}: {}", out.stderr);
        assert!(
            out.stderr.contains("more than 100000000"),
            "{args:?}: {}",
            out.stderr
        );
        assert!(out.stdout.is_empty());
    }
    let (status, stderr) = run_closed("synthesize", &["--rate", "1000"], "", Closed::Stdout);
    assert_eq!(status, Some(0), "{stderr}");
    assert!(stderr.is_empty(), "{stderr}");
}

// ---------------------------------------------------------------------------------------------
// The estimator's online hard iron on synthetic logs

/// A magnetometer whose samples lie exactly on a sphere about a known offset: ideal inertial
/// sensors, 0.2 µT of white noise per axis at 50 Hz, a residual hard iron of (1, −0.6, 1.5) µT,
/// no soft iron (the spec's error keys are the calibration that undoes the sensor: the sample
/// is the field plus the offset).
const HARD_IRON_SPEC: &str =
    "rate = 100\nmag_noise = 0.2\nmag_hard_iron = 1.0, -0.6, 1.5\nmag_rate = 50\n";

/// Runs the f64 estimator with default parameters over a log and returns per row: time, the
/// fit's estimate and standard deviation (µT), whether it offers the offset, the offset
/// subtracted, whether the field sample was used undisturbed, and the heading error (°).
#[allow(clippy::type_complexity)]
fn hard_iron_run(rows: &[Row]) -> Vec<(f64, [f64; 3], [f64; 3], bool, [f64; 3], bool, f64)> {
    use gyrostat::Vec3;
    use gyrostat::estimation::{Estimator, Params, SensorUse};
    let v = |a: [f64; 3]| Vec3::new(a[0], a[1], a[2]);
    let mut f = Estimator::<f64>::try_new(Params::default()).unwrap();
    let mut prev: Option<f64> = None;
    let mut out = Vec::new();
    for r in rows {
        let dt = prev.map_or(f64::NAN, |p| r.t() - p);
        prev = Some(r.t());
        let o = f
            .update(v(r.gyr()), v(r.acc()), r.mag().map(v), dt)
            .unwrap();
        let (applied, fit) = f.hard_iron();
        let (h, sd) = fit.estimate();
        // Heading error: the angle about the earth's z between the true and estimated
        // attitude's images of the sensor's x axis (their horizontal projections).
        let q = f.attitude().to_array();
        let x_est = host_tests::reference::qrotate(q, [1.0, 0.0, 0.0]);
        let x_true = host_tests::reference::qrotate(r.q(), [1.0, 0.0, 0.0]);
        let d = (x_est[1].atan2(x_est[0]) - x_true[1].atan2(x_true[0])).to_degrees();
        let heading = (d + 540.0).rem_euclid(360.0) - 180.0;
        out.push((
            r.t(),
            h.to_array(),
            sd.to_array(),
            fit.offset().is_some(),
            applied.to_array(),
            o.mag == SensorUse::Used,
            heading,
        ));
    }
    out
}

/// The fixed magnet of the synthetic grid (`--magnet-fixed 20,-10,15`, attached at t = 15 s,
/// a third into the first of two 30 s phases of hand-held rotation): the offset becomes
/// (21, −10.6, 16.5) µT (the magnet plus the residual). Within 20 s of the attachment (15 s of
/// it turning) the fit offers its estimate, and from then to the end of the log the estimate
/// is within 3 standard deviations (its own) of the true offset on every axis, those
/// deviations below 1 % of the field's norm (0.44 µT); the offset is offered and subtracted
/// on more than half of the samples from t = 35 s (the fit restarts when its samples stop
/// fitting one sphere and offers nothing until it has converged again). Before the attachment
/// no offset is subtracted; before it the fit follows the residual alone. (Measured, seed 3:
/// offered 16.0 s after the attachment; the largest error from t = 35 s 0.437 µT, 1.32 σ;
/// offered on 68 % of those samples.)
#[test]
fn hard_iron_converges_on_a_fixed_magnet() {
    let spec = write_spec("hard-iron.spec", HARD_IRON_SPEC);
    let spec = spec.to_str().unwrap();
    let args = [
        "--sensor",
        spec,
        "--seed",
        "3",
        "--magnet-fixed",
        "20,-10,15",
    ];
    let rows = log(&args);
    let truth = [21.0, -10.6, 16.5];
    let run = hard_iron_run(&rows);
    let first = run.iter().find(|r| r.0 > 15.0 && r.3).map(|r| r.0);
    let first = first.expect("the offset is never offered");
    assert!(first < 35.0, "offered only at {first} s");
    let (mut worst, mut worst_sigma, mut used, mut n) = (0.0f64, 0.0f64, 0usize, 0usize);
    let mut offered_n = 0usize;
    for (t, h, sd, offered, applied, _, _) in run.iter().filter(|r| r.0 >= 35.0) {
        n += 1;
        if !*offered {
            continue;
        }
        offered_n += 1;
        for i in 0..3 {
            let e = (h[i] - truth[i]).abs();
            assert!(e < 3.0 * sd[i], "t {t}: axis {i}: {h:?} ± {sd:?}");
            assert!(sd[i] < 0.44, "t {t}: axis {i}: sd {sd:?}");
            worst = worst.max(e);
            worst_sigma = worst_sigma.max(e / sd[i]);
        }
        if dist(*applied, *h) < 1e-9 {
            used += 1;
        } else {
            assert!(
                dist(*applied, [0.0; 3]) == 0.0,
                "t {t}: applied {applied:?}"
            );
        }
    }
    let offered_share = offered_n as f64 / n as f64;
    let share = used as f64 / n as f64;
    assert!(
        offered_share > 0.5,
        "the offset offered on {offered_share} of the samples"
    );
    assert!(
        share > 0.5,
        "the offset subtracted on {share} of the samples"
    );
    for (t, h, _, offered, applied, _, _) in run.iter().filter(|r| r.0 < 15.0) {
        assert!(
            dist(*applied, [0.0; 3]) == 0.0,
            "t {t}: applied {applied:?} before the magnet"
        );
        if *offered {
            assert!(dist(*h, [1.0, -0.6, 1.5]) < 0.5, "t {t}: {h:?}");
        }
    }
    eprintln!(
        "fixed magnet: offered {:.1} s after the attachment; from t = 35 s the largest error \
         {worst:.3} µT ({worst_sigma:.2} σ), offered on {:.1} %, subtracted on {:.1} % of the samples",
        first - 15.0,
        100.0 * offered_share,
        100.0 * share
    );
}

/// The passing magnet of the synthetic grid (`--magnet-pass 1,0.2,0.05`, up to 25 µT in the
/// middle of each phase): a field that changes in the earth frame is not a sphere about any
/// offset. The fit never offers an offset more than 2 µT from the residual (a tenth of the
/// pass; measured 1.48 µT: the pass bends the samples' sphere a little), no offset is
/// subtracted, and the heading update rejects the field near the magnet: at the peak of each
/// pass (t = 20 s and 55 s, ±1 s) no field sample is used.
#[test]
fn hard_iron_rejects_a_passing_magnet() {
    let spec = write_spec("hard-iron-pass.spec", HARD_IRON_SPEC);
    let spec = spec.to_str().unwrap();
    let args = [
        "--sensor",
        spec,
        "--seed",
        "3",
        "--magnet-pass",
        "1,0.2,0.05",
    ];
    let rows = log(&args);
    let run = hard_iron_run(&rows);
    let mut drift = 0.0f64;
    for (t, h, sd, offered, applied, used, _) in &run {
        if *offered {
            let d = dist(*h, [1.0, -0.6, 1.5]);
            assert!(d < 2.0, "t {t}: offered {h:?} ± {sd:?}");
            drift = drift.max(d);
        }
        assert!(
            dist(*applied, [0.0; 3]) == 0.0,
            "t {t}: applied {applied:?}"
        );
        if (*t - 20.0).abs() < 1.0 || (*t - 55.0).abs() < 1.0 {
            assert!(!used, "t {t}: the field near the magnet was used");
        }
    }
    let worst = run.iter().map(|r| r.6.abs()).fold(0.0, f64::max);
    eprintln!(
        "passing magnet: offered offsets within {drift:.2} µT of the residual; largest heading \
         error {worst:.2}°"
    );
}

/// The hard-iron fit keeps its time in seconds whatever the magnetometer's rate: the fixed
/// magnet of `hard_iron_converges_on_a_fixed_magnet` on six seeds, the magnetometer at the
/// gyroscope's 100 Hz and at a fifth of it (20 Hz, the other rows without a field), in the full
/// and the light mode. The time from the attachment to the first offer of the offset differs
/// by less than 4 s on average over the seeds. On a clock that counts the rows' steps instead
/// (the fit fed at half or a tenth of its samples, each standing for one row's step) it
/// differs by about 16 s: the random walk and the consistency statistics run five times slower
/// beside the 20 Hz magnetometer (measured on that clock: 16.2 s on average, the largest
/// 29.0 s). Measured on the magnetometer's clock: full mode 2.05 s, light mode 2.80 s.
#[test]
fn hard_iron_time_is_the_magnetometers() {
    use gyrostat::Vec3;
    use gyrostat::estimation::{Estimator, Mode, Params};
    let v = |a: [f64; 3]| Vec3::new(a[0], a[1], a[2]);
    let first_offer = |rows: &[Row], light: bool| -> f64 {
        let mut p = Params::default();
        if light {
            p.mode = Mode::light();
        }
        let mut f = Estimator::<f64>::try_new(p).unwrap();
        let mut prev: Option<f64> = None;
        for r in rows {
            let dt = prev.map_or(f64::NAN, |p| r.t() - p);
            prev = Some(r.t());
            f.update(v(r.gyr()), v(r.acc()), r.mag().map(v), dt)
                .unwrap();
            if r.t() > 15.0 && f.hard_iron().1.offset().is_some() {
                return r.t() - 15.0;
            }
        }
        f64::INFINITY
    };
    for light in [false, true] {
        let (mut sum, mut worst) = (0.0f64, 0.0f64);
        for seed in 1..=6 {
            let times: Vec<f64> = [100, 20]
                .iter()
                .map(|mag_rate| {
                    let spec = write_spec(
                        &format!("hard-iron-rate-{mag_rate}.spec"),
                        &format!(
                            "rate = 100\nmag_noise = 0.2\nmag_hard_iron = 1.0, -0.6, 1.5\n\
                             mag_rate = {mag_rate}\n"
                        ),
                    );
                    let seed = seed.to_string();
                    let rows = log(&[
                        "--sensor",
                        spec.to_str().unwrap(),
                        "--seed",
                        &seed,
                        "--magnet-fixed",
                        "20,-10,15",
                    ]);
                    first_offer(&rows, light)
                })
                .collect();
            assert!(
                times.iter().all(|t| t.is_finite()),
                "light {light}, seed {seed}: never offered: {times:?}"
            );
            let d = (times[0] - times[1]).abs();
            sum += d;
            worst = worst.max(d);
            eprintln!("light {light}, seed {seed}: offered after {times:?} s (100 / 20 Hz)");
        }
        let mean = sum / 6.0;
        eprintln!("light {light}: mean difference {mean:.2} s, largest {worst:.2} s");
        assert!(mean < 4.0, "light {light}: mean difference {mean} s");
    }
}
