//! A rest log characterised: per axis the Allan curve and its fit ([`crate::allan`]), the mean
//! and spread ([`gyrostat::sensor::RestNoise`], the firmware's streaming statistics), and the
//! files written from them: the sensor spec of the synthetic-log generator and the estimator's
//! parameter file (`key = value  # comment`, SI units).

use gyrostat::Vec3;
use gyrostat::sensor::RestNoise;

use crate::allan::{self, AllanError, Characterization, Noise, Spacing};
use crate::noise::FLICKER_FLOOR;

/// One axis of a rest log.
#[derive(Clone, Debug, PartialEq)]
pub struct AxisReport {
    /// The Allan curve and the fitted N, B, K.
    pub allan: Characterization,
    /// The mean (the bias plus, for the accelerometer, gravity's component).
    pub mean: f64,
    /// The sample standard deviation.
    pub std: f64,
    /// The successive-difference deviation `√(½·mean(Δy)²)`, the Allan deviation at one sample:
    /// the per-sample white noise.
    pub sample_noise: f64,
    /// Whether each of N, B, K is resolved: its term is the largest of the fitted model at some
    /// point of the curve (else the log says little about it: too short, or below the others).
    pub resolved: [bool; 3],
}

/// The three axes of one sensor, from per-axis samples (`samples[k] = [x, y, z]`) at `rate` Hz.
pub fn triad(
    samples: &[[f64; 3]],
    rate: f64,
    spacing: Spacing,
    fit_from: f64,
) -> Result<[AxisReport; 3], String> {
    let mut rest = RestNoise::<f64>::new();
    for (k, s) in samples.iter().enumerate() {
        rest.try_push(Vec3::new(s[0], s[1], s[2]))
            .map_err(|e| format!("sample {k}: {e}"))?;
    }
    let (mean, std, dvar) = match (rest.mean(), rest.std_dev(), rest.difference_variance()) {
        (Ok(m), Ok(s), Ok(d)) => (m.to_array(), s.to_array(), d.to_array()),
        _ => return Err(AllanError::TooShort(samples.len()).to_string()),
    };
    let axis = |i: usize| -> Result<AxisReport, String> {
        let y: Vec<f64> = samples.iter().map(|s| s[i]).collect();
        let allan = allan::characterize(&y, rate, spacing, fit_from).map_err(|e| e.to_string())?;
        let f = allan.fit;
        let dominates = |n: Noise| {
            allan
                .points
                .iter()
                .any(|p| p.tau >= fit_from && f.dominant(p.tau) == n)
        };
        let resolved = [
            f.noise_density > 0.0 && dominates(Noise::White),
            f.bias_instability > 0.0 && dominates(Noise::Flicker),
            f.rate_random_walk > 0.0 && dominates(Noise::RandomWalk),
        ];
        Ok(AxisReport {
            allan,
            mean: mean[i],
            std: std[i],
            sample_noise: dvar[i].sqrt(),
            resolved,
        })
    };
    Ok([axis(0)?, axis(1)?, axis(2)?])
}

/// The per-sample noise of a magnetometer at rest (µT), per axis: the successive-difference
/// deviation over the distinct samples (a row that repeats the previous row's field exactly is a
/// held sample of a slower magnetometer and is skipped). `None` with fewer than two.
pub fn mag_noise(samples: &[[f64; 3]]) -> Option<[f64; 3]> {
    let mut rest = RestNoise::<f64>::new();
    let mut last: Option<[f64; 3]> = None;
    for s in samples {
        if last == Some(*s) {
            continue;
        }
        last = Some(*s);
        rest.try_push(Vec3::new(s[0], s[1], s[2])).ok()?;
    }
    rest.difference_variance()
        .ok()
        .map(|v| v.to_array().map(f64::sqrt))
}

/// The largest of the three axes' values and its axis index.
fn worst(values: [f64; 3]) -> (f64, usize) {
    let mut best = (values[0], 0);
    for (i, &v) in values.iter().enumerate().skip(1) {
        if v > best.0 {
            best = (v, i);
        }
    }
    best
}

const AXES: [&str; 3] = ["x", "y", "z"];

/// Formats a number for the files: shortest round-trip text.
fn num(v: f64) -> String {
    format!("{v:e}")
}

/// One spec/params line for a per-axis coefficient: the largest axis as the value, every axis in
/// the comment, and whether it is resolved.
fn coefficient_line(key: &str, unit: &str, values: [f64; 3], resolved: [bool; 3]) -> String {
    let (v, i) = worst(values);
    let per_axis: Vec<String> = (0..3)
        .map(|a| {
            format!(
                "{} {}{}",
                AXES[a],
                num(values[a]),
                if resolved[a] { "" } else { " (not resolved)" }
            )
        })
        .collect();
    format!(
        "{key} = {}  # {unit}, largest axis ({}); {}\n",
        num(v),
        AXES[i],
        per_axis.join(", ")
    )
}

/// The sensor spec (the synthetic-log generator's keys; the largest axis of each coefficient,
/// the per-axis values as comments). `source` names the log in the header comment.
pub fn spec_text(
    source: &str,
    rate: f64,
    gyro: &[AxisReport; 3],
    accel: &[AxisReport; 3],
    mag: Option<[f64; 3]>,
) -> String {
    let mut s = format!(
        "# Sensor spec from the rest log {source} (characterize: overlapping Allan deviation,\n\
         # joint fit of sigma^2 = N^2/tau + (0.664 B)^2 + K^2 tau/3). SI units. Each value is the\n\
         # largest axis's; '(not resolved)' marks an axis whose term dominates no point of its\n\
         # curve (the log is too short or that noise is below the others): its value is the\n\
         # fit's and says little.\n"
    );
    let longest = gyro[0].allan.points.last().map_or(0.0, |p| p.tau);
    s += &format!("# longest averaging time: {longest:.4} s\n");
    s += &format!("rate = {}  # Hz, from the log's time stamps\n", num(rate));
    for (name, rep, unit) in [
        ("gyro", gyro, ["rad/s/sqrt(Hz)", "rad/s", "rad/s/sqrt(s)"]),
        ("accel", accel, ["m/s^2/sqrt(Hz)", "m/s^2", "m/s^2/sqrt(s)"]),
    ] {
        let get = |f: fn(&AxisReport) -> f64| [f(&rep[0]), f(&rep[1]), f(&rep[2])];
        let res = |i: usize| [rep[0].resolved[i], rep[1].resolved[i], rep[2].resolved[i]];
        s += &coefficient_line(
            &format!("{name}_noise_density"),
            unit[0],
            get(|r| r.allan.fit.noise_density),
            res(0),
        );
        s += &coefficient_line(
            &format!("{name}_bias_instability"),
            unit[1],
            get(|r| r.allan.fit.bias_instability),
            res(1),
        );
        s += &coefficient_line(
            &format!("{name}_rate_random_walk"),
            unit[2],
            get(|r| r.allan.fit.rate_random_walk),
            res(2),
        );
    }
    if let Some(m) = mag {
        s += &coefficient_line(
            "mag_noise",
            "uT rms per sample (successive differences / sqrt 2)",
            m,
            [true; 3],
        );
    }
    s
}

/// The estimator's bias random walk from one gyro axis: `(gyro_bias_stability, gyro_bias_time)`
/// and how they were found (see [`params_text`]).
pub fn bias_random_walk(rep: &AxisReport) -> (f64, f64, &'static str) {
    let f = rep.allan.fit;
    let points = &rep.allan.points;
    let (first, last) = (
        points.first().map_or(1.0, |p| p.tau),
        points.last().map_or(1.0, |p| p.tau),
    );
    let (n2, b2, c) = (
        f.noise_density.powi(2),
        (FLICKER_FLOOR * f.bias_instability).powi(2),
        f.rate_random_walk.powi(2) / 3.0,
    );
    if rep.resolved[1] || rep.resolved[2] {
        // The minimum of the fitted model: √(N²/c) with a random walk, else the longest τ.
        let t = if c > 0.0 { (n2 / c).sqrt() } else { last };
        let t = t.clamp(first, last);
        let sigma_bias = (b2 + c * t).sqrt();
        (
            3f64.sqrt() * sigma_bias,
            t,
            "the fitted bias part (0.664 B)^2 + K^2 T/3 at T",
        )
    } else {
        // Neither term is seen: the measured deviation at the longest τ bounds the bias part.
        let top = points.last().map_or(0.0, |p| p.adev);
        (
            3f64.sqrt() * top,
            last,
            "an upper bound: neither B nor K is resolved by this log, the measured Allan deviation at the longest T bounds the bias part",
        )
    }
}

/// The estimator's parameter file (`gyrostat::estimation::Params` names, SI units): the gyro
/// noise density (the largest axis's N) and the bias random walk
/// (`gyro_bias_stability`, `gyro_bias_time`): the estimator's bias is a random walk of variance
/// `σ²·Δt/T` per step, whose Allan deviation is `(σ/√T)·√(τ/3)`; it is matched to the fitted
/// curve's bias part `√((0.664·B)² + K²τ/3)` at τ = T, the τ where the fitted curve is lowest
/// (`T = √3·N/K`, the longest τ of the curve without a random walk): `σ = √3·√((0.664·B)² +
/// K²T/3)` (with B = 0 exactly the rate random walk, `σ = K·√T`). The largest axis's σ.
pub fn params_text(source: &str, gyro: &[AxisReport; 3]) -> String {
    let n = [0, 1, 2].map(|i| gyro[i].allan.fit.noise_density);
    let (nv, ni) = worst(n);
    let walks = [0, 1, 2].map(|i| bias_random_walk(&gyro[i]));
    let (sv, si) = worst(walks.map(|w| w.0));
    let (_, t, how) = walks[si];
    format!(
        "# Estimator parameters from the rest log {source} (characterize), SI units.\n\
         gyro_noise_density = {}  # rad/s/sqrt(Hz): the fitted -1/2 line of the Allan deviation at tau = 1 s, largest axis ({}); x {}, y {}, z {}\n\
         gyro_bias_stability = {}  # rad/s: sqrt(3) times {how} = {} s, largest axis ({}); x {}, y {}, z {}\n\
         gyro_bias_time = {}  # s: T, where the fitted Allan deviation is lowest (sqrt(3) N/K; the longest tau without a random walk)\n",
        num(nv),
        AXES[ni],
        num(n[0]),
        num(n[1]),
        num(n[2]),
        num(sv),
        num(t),
        AXES[si],
        num(walks[0].0),
        num(walks[1].0),
        num(walks[2].0),
        num(t),
    )
}
