//! `gyrostat::sensor::{RunningVariance, RestNoise}` against an independent two-pass f64
//! computation over the same (type-rounded) samples: the mean `Σx/n`, then the variance
//! `Σ(x − mean)²/(n − 1)`, the successive-difference variance `Σ(x_k − x_{k−1})²/(2(n − 1))`.
//!
//! Tolerances (relative): f64 1e-12 (Welford's rounding over 20 000 samples is a few ε·√n).
//! f32, an axis whose mean is 10⁴ times its spread (an accelerometer axis at 9.8 m/s² with
//! 1 mm/s² noise): the mean to 1e-5 (each update rounds μ by up to ulp(9.8)/2 = 4.8e-7, and
//! the error of update k survives with weight k/n: about ulp/(2√3)·√(n/3) = 2e-5 m/s² over
//! 20 000 samples, 2e-6 relative), the variance to 1e-3 (a numpy float32 replica of the update
//! on such data: 1.3e-4); with a zero mean the variance to 1e-5 (the replica: 3e-6) and the
//! mean to 1e-5 of the spread.

use gyrostat::Vec3;
use gyrostat::sensor::{RestNoise, RunningVariance};

use super::Rng;

/// A standard normal deviate (Box–Muller on the shared uniform generator).
fn normal(rng: &mut Rng) -> f64 {
    let u1 = 1.0 - rng.uniform();
    let u2 = rng.uniform();
    (-2.0 * u1.ln()).sqrt() * (core::f64::consts::TAU * u2).cos()
}

/// Two-pass mean, sample variance and successive-difference variance.
fn two_pass(xs: &[f64]) -> (f64, f64, f64) {
    let n = xs.len() as f64;
    let mean = xs.iter().sum::<f64>() / n;
    let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    let dvar = xs.windows(2).map(|w| (w[1] - w[0]).powi(2)).sum::<f64>() / (2.0 * (n - 1.0));
    (mean, var, dvar)
}

/// A rest log of one sensor: per axis a mean, white noise and a slow sinusoidal drift (so the
/// variance and the difference variance differ), n samples.
fn rest_log(seed: u64, n: usize, mean: [f64; 3], sigma: [f64; 3], drift: f64) -> Vec<[f64; 3]> {
    let mut rng = Rng::new(seed);
    (0..n)
        .map(|k| {
            let slow = drift * (k as f64 * 1.3e-3).sin();
            [0, 1, 2].map(|i| mean[i] + sigma[i] * normal(&mut rng) + slow)
        })
        .collect()
}

fn check<T: gyrostat::Real>(log: &[[f64; 3]], tol_mean: f64, tol_var: f64) {
    let rounded: Vec<[f64; 3]> = log
        .iter()
        .map(|s| s.map(|v| T::from_f64(v).to_f64()))
        .collect();
    let mut rest = RestNoise::<T>::new();
    for s in &rounded {
        rest.try_push(Vec3::new(
            T::from_f64(s[0]),
            T::from_f64(s[1]),
            T::from_f64(s[2]),
        ))
        .unwrap();
    }
    assert_eq!(rest.count() as usize, log.len());
    let (mean, var, dvar) = (
        rest.mean().unwrap(),
        rest.variance().unwrap(),
        rest.difference_variance().unwrap(),
    );
    let got = |v: Vec3<T>| [v.x.to_f64(), v.y.to_f64(), v.z.to_f64()];
    for axis in 0..3 {
        let column: Vec<f64> = rounded.iter().map(|s| s[axis]).collect();
        let (m, v, d) = two_pass(&column);
        let rel = |a: f64, b: f64| ((a - b) / b).abs();
        assert!(
            rel(got(mean)[axis], m) < tol_mean || (got(mean)[axis] - m).abs() < tol_mean * v.sqrt(),
            "axis {axis}: mean {} vs {m}",
            got(mean)[axis]
        );
        assert!(
            rel(got(var)[axis], v) < tol_var,
            "axis {axis}: var {} vs {v}",
            got(var)[axis]
        );
        assert!(
            rel(got(dvar)[axis], d) < tol_var,
            "axis {axis}: dvar {} vs {d}",
            got(dvar)[axis]
        );
        let std = rest.std_dev().unwrap();
        assert!(rel(got(std)[axis], v.sqrt()) < tol_var);
    }
}

#[test]
fn welford_matches_two_pass_f64() {
    let log = rest_log(11, 20_000, [0.01, -0.02, 9.8], [1e-3, 2e-3, 5e-3], 3e-3);
    check::<f64>(&log, 1e-12, 1e-12);
}

#[test]
fn welford_matches_two_pass_f32_large_mean() {
    // The accelerometer case: mean 9.8, spread 1e-3 (10⁴ apart).
    let log = rest_log(12, 20_000, [9.8, -9.8, 0.5], [1e-3, 1e-3, 1e-3], 0.0);
    check::<f32>(&log, 1e-5, 1e-3);
}

#[test]
fn welford_matches_two_pass_f32_zero_mean() {
    let log = rest_log(13, 20_000, [0.0, 0.0, 0.0], [1e-3, 2e-2, 0.3], 1e-3);
    check::<f32>(&log, 1e-5, 1e-5);
}

#[test]
fn noise_density_of_white_noise() {
    // White noise of density N at rate r: per-sample σ = N·√r, and N back from σ_Δ/√r. 40 000
    // samples: the relative standard error of σ_Δ² is about √(3/n) ≈ 0.9 %, of N half that;
    // 3 % is more than 6 standard errors.
    let (density, rate) = (2e-3, 200.0);
    let sigma = density * f64::sqrt(rate);
    let log = rest_log(14, 40_000, [0.3, 0.0, -0.1], [sigma; 3], 0.0);
    let mut rest = RestNoise::<f64>::new();
    for s in &log {
        rest.try_push(Vec3::new(s[0], s[1], s[2])).unwrap();
    }
    let n = rest.noise_density(rate).unwrap();
    for v in [n.x, n.y, n.z] {
        assert!((v / density - 1.0).abs() < 0.03, "{v} vs {density}");
    }
    // A drift inflates the variance but hardly the difference variance.
    let drifting = rest_log(15, 40_000, [0.0; 3], [sigma; 3], 5.0 * sigma);
    let mut rest = RestNoise::<f64>::new();
    for s in &drifting {
        rest.try_push(Vec3::new(s[0], s[1], s[2])).unwrap();
    }
    let var = rest.variance().unwrap().x;
    let dvar = rest.difference_variance().unwrap().x;
    assert!(var > 5.0 * sigma * sigma, "{var}");
    assert!((dvar / (sigma * sigma) - 1.0).abs() < 0.05, "{dvar}");
}

#[test]
fn typed_errors_leave_the_statistics_unchanged() {
    let mut r = RunningVariance::<f32>::new();
    assert_eq!(r.mean(), Err(gyrostat::Error::InvalidArgument));
    r.try_push(1.0).unwrap();
    assert_eq!(r.mean(), Ok(1.0));
    assert_eq!(r.variance(), Err(gyrostat::Error::InvalidArgument));
    let before = r;
    assert_eq!(r.try_push(f32::NAN), Err(gyrostat::Error::NonFinite));
    assert_eq!(r.try_push(f32::INFINITY), Err(gyrostat::Error::NonFinite));
    assert_eq!(r, before);
    // A finite sample whose square overflows the sums.
    r.try_push(3.0).unwrap();
    let before = r;
    assert_eq!(r.try_push(f32::MAX), Err(gyrostat::Error::NonFinite));
    assert_eq!(r, before);
    assert_eq!(r.variance(), Ok(2.0));

    let mut rest = RestNoise::<f64>::new();
    assert_eq!(
        rest.difference_variance(),
        Err(gyrostat::Error::InvalidArgument)
    );
    rest.try_push(Vec3::new(1.0, 2.0, 3.0)).unwrap();
    let before = rest;
    assert_eq!(
        rest.try_push(Vec3::new(1.0, f64::NAN, 3.0)),
        Err(gyrostat::Error::NonFinite)
    );
    assert_eq!(rest, before);
    rest.try_push(Vec3::new(3.0, 2.0, 3.0)).unwrap();
    assert_eq!(rest.difference_variance().unwrap().x, 2.0);
    assert_eq!(
        rest.noise_density(0.0),
        Err(gyrostat::Error::InvalidArgument)
    );
    assert_eq!(
        rest.noise_density(f64::NAN),
        Err(gyrostat::Error::InvalidArgument)
    );
    rest.reset();
    assert_eq!(rest.count(), 0);
}
