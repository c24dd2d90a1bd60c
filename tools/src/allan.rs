//! The overlapping Allan deviation of a rate signal and the fit of the three noise coefficients
//! of an inertial sensor (IEEE Std 952-1997 Annex C, IEEE Std 1293-2018; NIST SP 1065 for the
//! estimator and its degrees of freedom): the computation behind `characterize` and the Python
//! package's `allan_deviation`/`characterize`.
//!
//! # The Allan deviation
//!
//! From `n` samples `y₀ … y_{n−1}` of a rate (one gyro or accelerometer axis) at `rate` Hz
//! (`τ₀ = 1/rate`), the angle (or velocity) `x₀ = 0`, `x_{k+1} = x_k + (y_k − ȳ)·τ₀` (`N = n + 1`
//! points; subtracting the mean `ȳ` changes nothing in exact arithmetic and keeps the sums small),
//! and for an averaging factor `m` (`τ = m·τ₀`) the overlapping Allan variance
//!
//! ```text
//! σ²(τ) = Σ_{k=0}^{N−2m−1} (x_{k+2m} − 2x_{k+m} + x_k)² / (2 τ² (N − 2m))
//! ```
//!
//! (NIST SP 1065 eq. 11; the same as `allantools.oadev(y, rate, data_type="freq")`, which
//! builds the same `x`). `N − 2m` is the number of (overlapping) terms; a τ needs at least two.
//! The confidence of each point is given as its equivalent degrees of freedom `edf` (NIST SP
//! 1065 Table 5, for the noise type that dominates the fitted model at that τ: white rate noise
//! α = 0, flicker α = −1, random walk α = −2): `σ²·edf/σ²_true` is χ² with `edf` degrees of
//! freedom, so the relative standard deviation of σ is about `1/√(2·edf)`.
//!
//! # The fit
//!
//! The three terms of the model `σ²(τ) = N²/τ + (0.664·B)² + K²τ/3` (see [`crate::noise`]) are
//! fitted at once, by weighted least squares of `σ²` (linear in `a = N²`, `b = (0.664·B)²`,
//! `c = K²/3`), each point weighted by the inverse of its variance `2σ⁴/edf`, iterated three
//! times with `σ⁴` and `edf` taken from the previous fit (the first pass from the measured
//! curve and white-noise `edf`), each coefficient constrained to be ≥ 0 (the best of the fits
//! over every subset of the three terms whose coefficients are all ≥ 0). Then
//! `N = √a` is the fitted −1/2 line at τ = 1 s, `B = √b/0.664` the floor, `K = √(3c)` the
//! fitted +1/2 line at τ = 3 s.
//!
//! Why the three-term fit and not a line per slope: the regions where each term dominates
//! overlap (the minimum of the curve is `√(N²/τ + (0.664 B)² + K²τ/3)` at its lowest, larger
//! than `0.664·B` whenever N and K are not negligible there), and a line fitted to one region
//! needs its ends picked by eye; the joint fit uses every point with the weight its confidence
//! gives and reads each coefficient where its term is the model's. The minimum of the measured
//! curve over 0.664 (the classical reading of B, an upper bound) is reported beside it
//! ([`Fit::floor_bound`]).

use std::fmt;

use crate::noise::FLICKER_FLOOR;

/// One point of an Allan deviation curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AllanPoint {
    /// Averaging time τ = m/rate, s.
    pub tau: f64,
    /// Averaging factor m (samples per cluster).
    pub m: usize,
    /// Overlapping Allan deviation σ(τ), in the unit of the data.
    pub adev: f64,
    /// Number of overlapping terms of the sum, `N − 2m` (`N` = samples + 1).
    pub terms: usize,
    /// Number of non-overlapping clusters of m samples, `⌊n/m⌋`.
    pub clusters: usize,
    /// Equivalent degrees of freedom of σ² (NIST SP 1065 Table 5) for the noise type named by
    /// the fit ([`Fit`]; white rate noise for a curve not yet fitted).
    pub edf: f64,
}

impl AllanPoint {
    /// The approximate relative standard deviation of `adev`, `1/√(2·edf)`.
    pub fn relative_error(&self) -> f64 {
        1.0 / (2.0 * self.edf).sqrt()
    }
}

/// What cannot be characterised.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AllanError {
    /// The sample rate is not finite and > 0.
    Rate(f64),
    /// Too few samples for any τ (at least 3 are needed: two terms at m = 1).
    TooShort(usize),
    /// A sample (index) is not finite.
    NonFinite(usize),
    /// An averaging factor (given) is 0 or leaves fewer than two terms.
    Factor(usize),
    /// Too few points for a fit (fewer than two).
    TooFewPoints(usize),
}

impl fmt::Display for AllanError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Rate(r) => write!(f, "the sample rate must be finite and > 0, got {r}"),
            Self::TooShort(n) => write!(f, "{n} samples: at least 3 are needed"),
            Self::NonFinite(i) => write!(f, "sample {i} is not finite"),
            Self::Factor(m) => write!(
                f,
                "averaging factor {m}: must be >= 1 and leave at least two terms"
            ),
            Self::TooFewPoints(n) => write!(f, "{n} Allan points: at least 2 are needed"),
        }
    }
}

impl std::error::Error for AllanError {}

/// The τ grid of a curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Spacing {
    /// m = 1, 2, 4, 8, … (allantools' `"octave"`).
    Octave,
    /// About `k` factors per decade, log-spaced and rounded to distinct integers.
    PerDecade(u32),
}

/// The largest averaging factor with at least two terms for `n` samples, `⌊(n − 1)/2⌋`.
pub fn max_factor(n: usize) -> usize {
    n.saturating_sub(1) / 2
}

/// The averaging factors of `spacing` for `n` samples (every one with at least two terms).
pub fn factors(n: usize, spacing: Spacing) -> Vec<usize> {
    let max = max_factor(n);
    let mut out = Vec::new();
    match spacing {
        Spacing::Octave => {
            let mut m = 1usize;
            while m <= max {
                out.push(m);
                m = m.saturating_mul(2);
            }
        }
        Spacing::PerDecade(k) => {
            let k = f64::from(k.max(1));
            let mut i = 0u32;
            loop {
                let m = 10f64.powf(f64::from(i) / k).round() as usize;
                if m > max {
                    break;
                }
                if out.last() != Some(&m) {
                    out.push(m);
                }
                i += 1;
            }
        }
    }
    out
}

/// The overlapping Allan deviation of the rate samples `y` at `rate` Hz for the averaging
/// factors `ms` (see the module documentation), with white-noise `edf`.
pub fn overlapping(y: &[f64], rate: f64, ms: &[usize]) -> Result<Vec<AllanPoint>, AllanError> {
    if !(rate.is_finite() && rate > 0.0) {
        return Err(AllanError::Rate(rate));
    }
    if y.len() < 3 {
        return Err(AllanError::TooShort(y.len()));
    }
    if let Some(i) = y.iter().position(|v| !v.is_finite()) {
        return Err(AllanError::NonFinite(i));
    }
    let n = y.len();
    let tau0 = 1.0 / rate;
    let mean = y.iter().sum::<f64>() / n as f64;
    let mut x = Vec::with_capacity(n + 1);
    x.push(0.0);
    let mut acc = 0.0;
    for v in y {
        acc += (v - mean) * tau0;
        x.push(acc);
    }
    let big_n = n + 1;
    ms.iter()
        .map(|&m| {
            if m == 0 || m > max_factor(n) {
                return Err(AllanError::Factor(m));
            }
            let terms = big_n - 2 * m;
            let sum: f64 = (0..terms)
                .map(|k| {
                    let d = x[k + 2 * m] - 2.0 * x[k + m] + x[k];
                    d * d
                })
                .sum();
            let tau = m as f64 * tau0;
            let avar = sum / (2.0 * tau * tau * terms as f64);
            Ok(AllanPoint {
                tau,
                m,
                adev: avar.sqrt(),
                terms,
                clusters: n / m,
                edf: edf(big_n, m, Noise::White),
            })
        })
        .collect()
}

/// The noise types of the model, by the slope of their Allan deviation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Noise {
    /// White rate noise (angle/velocity random walk, slope −1/2; NIST α = 0).
    White,
    /// Flicker rate noise (bias instability, slope 0; α = −1).
    Flicker,
    /// Random-walk rate noise (rate random walk, slope +1/2; α = −2).
    RandomWalk,
}

/// The equivalent degrees of freedom of the overlapping Allan variance of `big_n` phase points
/// at factor `m` for a noise type (NIST SP 1065, Table 5).
pub fn edf(big_n: usize, m: usize, noise: Noise) -> f64 {
    let (nn, m) = (big_n as f64, m as f64);
    let e = match noise {
        Noise::White => {
            (3.0 * (nn - 1.0) / (2.0 * m) - 2.0 * (nn - 2.0) / nn) * (4.0 * m * m)
                / (4.0 * m * m + 5.0)
        }
        Noise::Flicker if m < 1.5 => 2.0 * (nn - 2.0) / (2.3 * nn - 4.9),
        Noise::Flicker => 5.0 * nn * nn / (4.0 * m * (nn + 3.0 * m)),
        Noise::RandomWalk => {
            (nn - 2.0) / (m * (nn - 3.0).powi(2))
                * ((nn - 1.0).powi(2) - 3.0 * m * (nn - 1.0) + 4.0 * m * m)
        }
    };
    // The table's formulas are approximations that can fall below 1 at the largest factors.
    e.max(1.0)
}

/// The fitted noise coefficients of one axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fit {
    /// White noise density N: the fitted −1/2 line at τ = 1 s (unit/√Hz).
    pub noise_density: f64,
    /// Bias instability B: the fitted floor over 0.664 (unit).
    pub bias_instability: f64,
    /// Rate random walk K: the fitted +1/2 line at τ = 3 s (unit/√s).
    pub rate_random_walk: f64,
    /// The minimum of the measured curve over 0.664: the classical reading of B, an upper bound
    /// of it (unit).
    pub floor_bound: f64,
    /// The τ of that minimum, s.
    pub floor_tau: f64,
}

impl Fit {
    /// The fitted model's Allan deviation at τ.
    pub fn allan_deviation(&self, tau: f64) -> f64 {
        let b = FLICKER_FLOOR * self.bias_instability;
        (self.noise_density.powi(2) / tau + b * b + self.rate_random_walk.powi(2) * tau / 3.0)
            .sqrt()
    }

    /// The term of the fitted model that is largest at τ.
    pub fn dominant(&self, tau: f64) -> Noise {
        let w = self.noise_density.powi(2) / tau;
        let f = (FLICKER_FLOOR * self.bias_instability).powi(2);
        let r = self.rate_random_walk.powi(2) * tau / 3.0;
        if w >= f && w >= r {
            Noise::White
        } else if f >= r {
            Noise::Flicker
        } else {
            Noise::RandomWalk
        }
    }
}

/// Fits N, B and K to a curve (see the module documentation) and sets each point's `edf` to
/// the noise type the fit says dominates there. `samples` is the length of the data (for the
/// `edf`).
pub fn fit(points: &mut [AllanPoint], samples: usize) -> Result<Fit, AllanError> {
    if points.len() < 2 {
        return Err(AllanError::TooFewPoints(points.len()));
    }
    let big_n = samples + 1;
    let (floor_tau, floor_adev) =
        points
            .iter()
            .map(|p| (p.tau, p.adev))
            .fold((f64::NAN, f64::INFINITY), |best, p| {
                if p.1 < best.1 { p } else { best }
            });
    // Pass 0 weighs by the measured variance and white-noise edf, later passes by the model's.
    let mut weights: Vec<f64> = points
        .iter()
        .map(|p| edf(big_n, p.m, Noise::White) / (2.0 * p.adev.powi(4).max(f64::MIN_POSITIVE)))
        .collect();
    let mut coef = [0.0; 3];
    for _ in 0..4 {
        coef = nonnegative_least_squares(points, &weights);
        let model = |tau: f64| coef[0] / tau + coef[1] + coef[2] * tau;
        for (w, p) in weights.iter_mut().zip(points.iter()) {
            let s2 = model(p.tau).max(f64::MIN_POSITIVE);
            let f = to_fit(coef, floor_adev, floor_tau);
            *w = edf(big_n, p.m, f.dominant(p.tau)) / (2.0 * s2 * s2);
        }
    }
    let f = to_fit(coef, floor_adev, floor_tau);
    for p in points.iter_mut() {
        p.edf = edf(big_n, p.m, f.dominant(p.tau));
    }
    Ok(f)
}

fn to_fit(coef: [f64; 3], floor_adev: f64, floor_tau: f64) -> Fit {
    Fit {
        noise_density: coef[0].sqrt(),
        bias_instability: coef[1].sqrt() / FLICKER_FLOOR,
        rate_random_walk: (3.0 * coef[2]).sqrt(),
        floor_bound: floor_adev / FLICKER_FLOOR,
        floor_tau,
    }
}

/// The weighted least-squares `[a, b, c]` of `σ² ≈ a/τ + b + cτ` with every coefficient ≥ 0:
/// the lowest-cost fit among the subsets of the three terms whose unconstrained solution is
/// ≥ 0 (an exhaustive search, exact for three unknowns).
fn nonnegative_least_squares(points: &[AllanPoint], weights: &[f64]) -> [f64; 3] {
    let basis = |tau: f64| [1.0 / tau, 1.0, tau];
    let mut best = ([0.0; 3], f64::INFINITY);
    for mask in 1u8..8 {
        let idx: Vec<usize> = (0..3).filter(|i| mask & (1 << i) != 0).collect();
        let k = idx.len();
        // Normal equations, scaled per column to keep them well conditioned.
        let mut scale = [0.0f64; 3];
        for (j, &c) in idx.iter().enumerate() {
            scale[j] = points
                .iter()
                .zip(weights)
                .map(|(p, w)| w * basis(p.tau)[c].powi(2))
                .sum::<f64>()
                .sqrt()
                .max(f64::MIN_POSITIVE);
        }
        let mut a = [[0.0f64; 4]; 3];
        for (p, w) in points.iter().zip(weights) {
            let phi = basis(p.tau);
            let y = p.adev * p.adev;
            for r in 0..k {
                let pr = phi[idx[r]] / scale[r];
                for c in 0..k {
                    a[r][c] += w * pr * phi[idx[c]] / scale[c];
                }
                a[r][3] += w * pr * y;
            }
        }
        let Some(sol) = solve(&mut a, k) else {
            continue;
        };
        let mut coef = [0.0; 3];
        for (j, &c) in idx.iter().enumerate() {
            coef[c] = sol[j] / scale[j];
        }
        if coef.iter().any(|&v| v < 0.0 || !v.is_finite()) {
            continue;
        }
        let cost: f64 = points
            .iter()
            .zip(weights)
            .map(|(p, w)| {
                let phi = basis(p.tau);
                let m = coef[0] * phi[0] + coef[1] * phi[1] + coef[2] * phi[2];
                w * (p.adev * p.adev - m).powi(2)
            })
            .sum();
        if cost < best.1 {
            best = (coef, cost);
        }
    }
    best.0
}

/// Solves the `k × k` system in the augmented matrix `a` (column 3 the right-hand side) by
/// Gaussian elimination with partial pivoting; `None` when singular.
fn solve(a: &mut [[f64; 4]; 3], k: usize) -> Option<[f64; 3]> {
    for col in 0..k {
        let piv = (col..k).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[piv][col].abs() < 1e-12 {
            return None;
        }
        a.swap(col, piv);
        let pivot = a[col];
        for row in a.iter_mut().take(k).skip(col + 1) {
            let f = row[col] / pivot[col];
            for (v, p) in row.iter_mut().zip(pivot).skip(col) {
                *v -= f * p;
            }
        }
    }
    let mut x = [0.0; 3];
    for r in (0..k).rev() {
        let mut s = a[r][3];
        for c in r + 1..k {
            s -= a[r][c] * x[c];
        }
        x[r] = s / a[r][r];
    }
    Some(x)
}

/// One axis characterised: its curve and its fit.
#[derive(Clone, Debug, PartialEq)]
pub struct Characterization {
    /// The Allan deviation curve (each point's `edf` for the fitted dominant noise).
    pub points: Vec<AllanPoint>,
    /// The fitted coefficients.
    pub fit: Fit,
}

/// The curve of `y` at `rate` Hz on the grid `spacing` and its fit.
pub fn characterize(
    y: &[f64],
    rate: f64,
    spacing: Spacing,
) -> Result<Characterization, AllanError> {
    let ms = factors(y.len(), spacing);
    let mut points = overlapping(y, rate, &ms)?;
    let fit = fit(&mut points, y.len())?;
    Ok(Characterization { points, fit })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn factors_follow_allantools_octaves() {
        assert_eq!(factors(10, Spacing::Octave), vec![1, 2, 4]);
        assert_eq!(factors(9, Spacing::Octave), vec![1, 2, 4]);
        assert_eq!(factors(8, Spacing::Octave), vec![1, 2]);
        assert_eq!(
            factors(100, Spacing::PerDecade(3)),
            vec![1, 2, 5, 10, 22, 46]
        );
    }

    #[test]
    fn small_case_by_hand() {
        // At m = 1 the Allan variance is half the mean square of the successive differences of
        // y: y = [1, 3, 2, 6] → differences 2, -1, 4 → σ² = (4 + 1 + 16)/(2·3) = 3.5.
        let p = overlapping(&[1.0, 3.0, 2.0, 6.0], 2.0, &[1]).unwrap();
        let expected = 3.5f64.sqrt();
        assert!((p[0].adev - expected).abs() < 1e-15);
        assert_eq!((p[0].terms, p[0].clusters), (3, 4));
        assert_eq!(
            overlapping(&[1.0, 3.0, 2.0, 6.0], 2.0, &[2]),
            Err(AllanError::Factor(2))
        );
        assert_eq!(
            overlapping(&[1.0, 2.0], 1.0, &[1]),
            Err(AllanError::TooShort(2))
        );
        assert_eq!(
            overlapping(&[1.0, f64::NAN, 2.0], 1.0, &[1]),
            Err(AllanError::NonFinite(1))
        );
        assert_eq!(
            overlapping(&[1.0; 5], 0.0, &[1]),
            Err(AllanError::Rate(0.0))
        );
    }

    #[test]
    fn fit_recovers_an_exact_model() {
        // Points on an exact model: the fit gives its coefficients back.
        let (n, b, k) = (2e-3, 3e-4, 5e-5);
        let truth = Fit {
            noise_density: n,
            bias_instability: b,
            rate_random_walk: k,
            floor_bound: 0.0,
            floor_tau: 0.0,
        };
        let mut pts: Vec<AllanPoint> = factors(1 << 22, Spacing::Octave)
            .into_iter()
            .map(|m| {
                let tau = m as f64 / 100.0;
                AllanPoint {
                    tau,
                    m,
                    adev: truth.allan_deviation(tau),
                    terms: 0,
                    clusters: 0,
                    edf: 1.0,
                }
            })
            .collect();
        let f = fit(&mut pts, 1 << 22).unwrap();
        assert!((f.noise_density / n - 1.0).abs() < 1e-9);
        assert!((f.bias_instability / b - 1.0).abs() < 1e-9);
        assert!((f.rate_random_walk / k - 1.0).abs() < 1e-9);
    }
}
