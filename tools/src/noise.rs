//! The inertial sensor noise model of the tools: white noise, bias instability and rate random
//! walk per axis (IEEE Std 952-1997 Annex C, IEEE Std 1293-2018), seeded and deterministic.
//!
//! # The model
//!
//! A [`NoiseSpec`] gives the three coefficients of the Allan deviation of one sensor (gyro or
//! accelerometer, the same for its three axes), in SI units:
//!
//! | coefficient | gyro | accelerometer | Allan deviation term |
//! |---|---|---|---|
//! | `noise_density` N (angle/velocity random walk) | rad/s/√Hz | m/s²/√Hz | `N/√τ` (slope −1/2) |
//! | `bias_instability` B | rad/s | m/s² | floor `√(2 ln 2/π)·B = 0.664·B` (slope 0) |
//! | `rate_random_walk` K | rad/s/√s | m/s²/√s | `K·√(τ/3)` (slope +1/2) |
//!
//! so that the Allan variance of the error of one axis is, where each term dominates,
//! `σ²(τ) ≈ N²/τ + (0.664·B)² + K²·τ/3`.
//!
//! The error of one axis at a sample that closes a step of length `dt` (seconds) is
//! `e = w + b + r`, the sum of three independent processes:
//!
//! - **white noise** `w ~ 𝒩(0, N²/dt)`, independent from sample to sample: a rate averaged over
//!   `dt` whose power spectral density is `N²` (one-sided);
//! - **bias instability** `b`: flicker (1/f) noise of one-sided PSD `S(f) = h/f`, `h = B²/π`
//!   (whose Allan variance is `2 ln 2·h = (0.664·B)²` at every τ), approximated by a sum of
//!   first-order Gauss–Markov processes `b = Σᵢ xᵢ` with time constants log-spaced
//!   [`FLICKER_PER_DECADE`] per decade, `Tᵢ = dt₀·r^i` from the first step `dt₀` up to the first
//!   at or beyond [`FLICKER_T_MAX`] (ratio `r = 10^(1/FLICKER_PER_DECADE)`; the processes are
//!   created at the first sample, so that the band starts at the sampling whatever the rate),
//!   each of stationary variance `q² = h·ln r`: a Lorentzian `4q²Tᵢ/(1 + (2πfTᵢ)²)` per process,
//!   whose sum over a log-uniform grid of `Tᵢ` is `q²/(f ln r) = h/f` between the corners
//!   `1/(2πT_max)` and `1/(2πdt₀)`. Each process is discretised exactly for any step:
//!   `xᵢ ← e^(−dt/Tᵢ)·xᵢ + q·√(1 − e^(−2dt/Tᵢ))·ν`,
//!   `ν ~ 𝒩(0, 1)`, and starts from its stationary distribution `𝒩(0, q²)`;
//! - **rate random walk** `r ← r + K·√dt·ν`, starting at 0 (a turn-on bias is not noise: the
//!   sensor model adds it).
//!
//! How flat the floor is: the Allan deviation of the sum, computed in closed form from the
//! continuous-time Gauss–Markov Allan variance
//! `σ²(τ) = (2q²T/τ)·[1 − (T/2τ)(3 − 4e^(−τ/T) + e^(−2τ/T))]` (see [`flicker_allan_deviation`]),
//! stays within 3 % of `0.664·B` for τ from 20·dt₀ to 2·10⁴ s and within 8 % from 5·dt₀ to
//! 5·10⁴ s (checked by this module's tests for dt₀ = 0.01 s). Sampled at dt₀ (the overlapping
//! Allan deviation of 400 000 samples at 100 Hz, allantools), it is 0.93, 0.92, 0.94, 0.96, 0.98,
//! 0.99, 1.00 times the floor at τ = 1, 2, 4, … 64 dt₀. Below that band it falls like `√τ`
//! (where the white noise of any real sensor hides it), above it like `1/√τ`. A
//! characterisation of pure bias instability that fits the curve down to τ = dt₀ reads B about
//! 5 % low; with white noise dominant below about 100·dt₀ (every real sensor) the deficit is
//! hidden.
//!
//! # Randomness
//!
//! [`Rng`] is xoshiro256++ (Blackman and Vigna) seeded through SplitMix64, with normal deviates
//! from the Box–Muller transform: the same seed gives the same numbers on every platform (the
//! transform uses `ln`, `sqrt`, `sin` and `cos` of std, which can differ in the last bit across
//! platforms' math libraries; the generator's integers do not). [`TriadNoise`] draws each axis
//! from its own stream (the seed mixed with the axis index), so the axes are independent and an
//! axis's numbers do not depend on the others'.
//!
//! ```
//! use gyrostat_tools::noise::{NoiseSpec, TriadNoise};
//!
//! // A consumer MEMS gyro: 0.01 °/s/√Hz, 5 °/h bias instability, a small rate random walk.
//! let d = core::f64::consts::PI / 180.0;
//! let spec = NoiseSpec {
//!     noise_density: 0.01 * d,
//!     bias_instability: 5.0 * d / 3600.0,
//!     rate_random_walk: 1e-5,
//! };
//! let mut noise = TriadNoise::try_new(spec, 42).unwrap();
//! let e = noise.sample(0.01).unwrap(); // the error of each axis at a 100 Hz sample
//! assert!(e.iter().all(|v| v.is_finite()));
//! ```

use std::fmt;

/// The longest time constant of the Gauss–Markov processes that approximate flicker noise, s.
pub const FLICKER_T_MAX: f64 = 1e5;
/// Gauss–Markov processes per decade of time constant.
pub const FLICKER_PER_DECADE: u32 = 2;

/// `√(2 ln 2 / π)`: the Allan deviation of flicker noise over its bias instability coefficient
/// (IEEE Std 952, C.3: the floor `σ = 0.664·B`).
pub const FLICKER_FLOOR: f64 = 0.664_282_470_267_96;

/// The noise coefficients of one sensor (the same for its three axes), SI units (see the module
/// documentation for the model and the units).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NoiseSpec {
    /// White noise density N: rad/s/√Hz (gyro, the angle random walk in rad/√s) or m/s²/√Hz
    /// (accelerometer, the velocity random walk in m/s/√s). Allan deviation `N/√τ`.
    pub noise_density: f64,
    /// Bias instability B: rad/s or m/s². Allan deviation floor `0.664·B`.
    pub bias_instability: f64,
    /// Rate random walk K: rad/s/√s or m/s²/√s. Allan deviation `K·√(τ/3)`.
    pub rate_random_walk: f64,
}

impl NoiseSpec {
    /// No noise.
    pub const ZERO: Self = Self {
        noise_density: 0.0,
        bias_instability: 0.0,
        rate_random_walk: 0.0,
    };

    /// Checks that every coefficient is finite and ≥ 0.
    pub fn validate(&self) -> Result<(), NoiseError> {
        for (name, v) in [
            ("noise_density", self.noise_density),
            ("bias_instability", self.bias_instability),
            ("rate_random_walk", self.rate_random_walk),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(NoiseError::Coefficient(name, v));
            }
        }
        Ok(())
    }

    /// The model's Allan deviation at averaging time `tau` (s), `√(N²/τ + (0.664·B)² + K²τ/3)`:
    /// the asymptotes of the three terms summed (the flicker term as its ideal floor, not the
    /// finite band of the generator).
    pub fn allan_deviation(&self, tau: f64) -> f64 {
        let b = FLICKER_FLOOR * self.bias_instability;
        (self.noise_density.powi(2) / tau + b * b + self.rate_random_walk.powi(2) * tau / 3.0)
            .sqrt()
    }
}

/// A bad coefficient or step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NoiseError {
    /// A coefficient (named) is negative or not finite.
    Coefficient(&'static str, f64),
    /// A step is not finite and > 0.
    Step(f64),
}

impl fmt::Display for NoiseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Coefficient(name, v) => write!(f, "{name} must be finite and >= 0, got {v}"),
            Self::Step(dt) => write!(f, "the step must be finite and > 0, got {dt}"),
        }
    }
}

impl std::error::Error for NoiseError {}

/// A seeded pseudo-random generator: xoshiro256++ seeded by SplitMix64, normal deviates by
/// Box–Muller. Deterministic: the same seed gives the same sequence.
#[derive(Clone, Debug)]
pub struct Rng {
    s: [u64; 4],
    spare: Option<f64>,
}

impl Rng {
    /// The generator of `seed` (any value, 0 included).
    pub fn new(seed: u64) -> Self {
        let mut z = seed;
        let mut next = || {
            z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut x = z;
            x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            x ^ (x >> 31)
        };
        Self {
            s: [next(), next(), next(), next()],
            spare: None,
        }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        let [s0, s1, s2, s3] = self.s;
        let result = s0.wrapping_add(s3).rotate_left(23).wrapping_add(s0);
        let t = s1 << 17;
        let mut s = [s0, s1, s2 ^ s0, s3 ^ s1];
        s[1] ^= s[2];
        s[0] ^= s[3];
        s[2] ^= t;
        s[3] = s[3].rotate_left(45);
        self.s = s;
        result
    }

    /// A uniform deviate in [0, 1) (53 random bits).
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// A standard normal deviate 𝒩(0, 1) (Box–Muller: two per pair of uniforms, the second
    /// kept for the next call).
    pub fn normal(&mut self) -> f64 {
        if let Some(z) = self.spare.take() {
            return z;
        }
        // u1 in (0, 1]: ln is finite.
        let u1 = 1.0 - self.uniform();
        let u2 = self.uniform();
        let r = (-2.0 * u1.ln()).sqrt();
        let (s, c) = (core::f64::consts::TAU * u2).sin_cos();
        self.spare = Some(r * s);
        r * c
    }
}

/// One first-order Gauss–Markov process of the flicker approximation.
#[derive(Clone, Debug)]
struct Markov {
    time: f64,
    std: f64,
    x: f64,
    /// `(dt, e^(−dt/T), q·√(1 − e^(−2dt/T)))` of the last step, reused while dt repeats.
    cached: (f64, f64, f64),
}

/// The noise of one axis (see the module documentation for the model).
#[derive(Clone, Debug)]
pub struct AxisNoise {
    spec: NoiseSpec,
    rng: Rng,
    flicker: Vec<Markov>,
    walk: f64,
}

impl AxisNoise {
    /// The noise of one axis with coefficients `spec`, drawn from the stream of `seed`.
    pub fn try_new(spec: NoiseSpec, seed: u64) -> Result<Self, NoiseError> {
        spec.validate()?;
        Ok(Self {
            spec,
            rng: Rng::new(seed),
            flicker: Vec::new(),
            walk: 0.0,
        })
    }

    /// The coefficients.
    pub fn spec(&self) -> NoiseSpec {
        self.spec
    }

    /// The error of the sample that closes a step of `dt` seconds (white + bias instability +
    /// rate random walk; the processes advance by `dt`). `dt` may vary from step to step.
    pub fn sample(&mut self, dt: f64) -> Result<f64, NoiseError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(NoiseError::Step(dt));
        }
        if self.flicker.is_empty() && self.spec.bias_instability > 0.0 {
            let std = flicker_std(self.spec.bias_instability);
            for time in flicker_times(dt) {
                let x = std * self.rng.normal();
                self.flicker.push(Markov {
                    time,
                    std,
                    x,
                    cached: (f64::NAN, 0.0, 0.0),
                });
            }
        }
        let mut e = 0.0;
        if self.spec.noise_density > 0.0 {
            e += self.spec.noise_density / dt.sqrt() * self.rng.normal();
        }
        for m in &mut self.flicker {
            if m.cached.0 != dt {
                let a = (-dt / m.time).exp();
                m.cached = (dt, a, m.std * (-(-2.0 * dt / m.time).exp_m1()).sqrt());
            }
            m.x = m.cached.1 * m.x + m.cached.2 * self.rng.normal();
            e += m.x;
        }
        if self.spec.rate_random_walk > 0.0 {
            self.walk += self.spec.rate_random_walk * dt.sqrt() * self.rng.normal();
        }
        Ok(e + self.walk)
    }

    /// The current bias-instability and random-walk parts (the slowly varying bias), without
    /// advancing: what a sample's error is besides its white noise (0 before the first sample).
    pub fn bias(&self) -> f64 {
        self.flicker.iter().map(|m| m.x).sum::<f64>() + self.walk
    }
}

/// The noise of the three axes of one sensor, independent streams of one seed.
#[derive(Clone, Debug)]
pub struct TriadNoise {
    axes: [AxisNoise; 3],
}

impl TriadNoise {
    /// The noise of three axes with coefficients `spec`; axis `i` draws from the stream of
    /// [`axis_seed`]`(seed, i)`.
    pub fn try_new(spec: NoiseSpec, seed: u64) -> Result<Self, NoiseError> {
        Ok(Self {
            axes: [
                AxisNoise::try_new(spec, axis_seed(seed, 0))?,
                AxisNoise::try_new(spec, axis_seed(seed, 1))?,
                AxisNoise::try_new(spec, axis_seed(seed, 2))?,
            ],
        })
    }

    /// The errors of the three axes at the sample closing a step of `dt` seconds.
    pub fn sample(&mut self, dt: f64) -> Result<[f64; 3], NoiseError> {
        let [x, y, z] = &mut self.axes;
        Ok([x.sample(dt)?, y.sample(dt)?, z.sample(dt)?])
    }

    /// The current slowly varying bias of each axis (see [`AxisNoise::bias`]).
    pub fn bias(&self) -> [f64; 3] {
        [
            self.axes[0].bias(),
            self.axes[1].bias(),
            self.axes[2].bias(),
        ]
    }
}

/// The seed of axis `axis` of a triad seeded with `seed` (a SplitMix64 step of the pair, so that
/// neighbouring seeds give unrelated streams).
pub fn axis_seed(seed: u64, axis: u64) -> u64 {
    let mut x = seed ^ axis.wrapping_mul(0xd1b5_4a32_d192_ed03);
    x = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
    x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    x ^ (x >> 31)
}

/// The time constants of the flicker approximation for a first step `dt0`, s: `dt0·r^i` up to
/// the first at or beyond [`FLICKER_T_MAX`].
fn flicker_times(dt0: f64) -> impl Iterator<Item = f64> {
    let decades = (FLICKER_T_MAX / dt0).log10().max(0.0);
    let n = (decades * f64::from(FLICKER_PER_DECADE)).ceil() as u32;
    (0..=n).map(move |i| dt0 * 10f64.powf(f64::from(i) / f64::from(FLICKER_PER_DECADE)))
}

/// The stationary standard deviation `q = √(h ln r)`, `h = B²/π`, of each Gauss–Markov process.
fn flicker_std(bias_instability: f64) -> f64 {
    let ln_r = core::f64::consts::LN_10 / f64::from(FLICKER_PER_DECADE);
    bias_instability * (ln_r / core::f64::consts::PI).sqrt()
}

/// The Allan deviation at `tau` of the generator's bias instability alone (the sum of its
/// Gauss–Markov processes in continuous time, in closed form) for a bias instability
/// coefficient `b` and a first step `dt0`: how far the approximation is from the ideal floor
/// `0.664·b`.
pub fn flicker_allan_deviation(b: f64, dt0: f64, tau: f64) -> f64 {
    let q2 = flicker_std(b).powi(2);
    flicker_times(dt0)
        .map(|t| {
            let x = tau / t;
            // 3 − 4e^(−x) + e^(−2x) = (1 − e^(−x))² + 2(1 − e^(−x)), written with expm1 for
            // small x.
            let u = -(-x).exp_m1();
            let bracket = u * u + 2.0 * u;
            // (2q²T/τ)[1 − bracket/(2x)]; for small x the difference cancels: use the series
            // 1 − bracket/(2x) = x²/3 − x³/4 + … there.
            let inner = if x < 1e-3 {
                x * x / 3.0 - x * x * x / 4.0
            } else {
                1.0 - bracket / (2.0 * x)
            };
            2.0 * q2 * t / tau * inner
        })
        .sum::<f64>()
        .sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flicker_floor_is_flat() {
        let floor = FLICKER_FLOOR * 2.0;
        let mut worst_in = 0.0f64;
        let mut worst_wide = 0.0f64;
        for i in 0..=120 {
            let tau = 10f64.powf(-2.0 + 7.0 * f64::from(i) / 120.0);
            let rel = (flicker_allan_deviation(2.0, 0.01, tau) / floor - 1.0).abs();
            if (0.2..=2e4).contains(&tau) {
                worst_in = worst_in.max(rel);
            }
            if (0.05..=5e4).contains(&tau) {
                worst_wide = worst_wide.max(rel);
            }
        }
        assert!(worst_in < 0.03, "{worst_in}");
        assert!(worst_wide < 0.08, "{worst_wide}");
        assert!((FLICKER_FLOOR - (2.0 * 2f64.ln() / core::f64::consts::PI).sqrt()).abs() < 1e-15);
    }

    #[test]
    fn markov_allan_series_matches_closed_form() {
        // Near x = 1e-3 the series and the closed form agree.
        let x: f64 = 1e-3;
        let u = -(-x).exp_m1();
        let closed = 1.0 - (u * u + 2.0 * u) / (2.0 * x);
        assert!((closed - (x * x / 3.0 - x * x * x / 4.0)).abs() < 1e-9);
    }

    #[test]
    fn deterministic_and_checked() {
        let spec = NoiseSpec {
            noise_density: 0.1,
            bias_instability: 0.01,
            rate_random_walk: 0.001,
        };
        let mut a = TriadNoise::try_new(spec, 7).unwrap();
        let mut b = TriadNoise::try_new(spec, 7).unwrap();
        let mut c = TriadNoise::try_new(spec, 8).unwrap();
        let (x, y, z) = (a.sample(0.01), b.sample(0.01), c.sample(0.01));
        assert_eq!(x, y);
        assert_ne!(x, z);
        assert_eq!(a.sample(0.0), Err(NoiseError::Step(0.0)));
        assert!(a.sample(f64::NAN).is_err());
        let bad = NoiseSpec {
            noise_density: -1.0,
            ..spec
        };
        assert_eq!(
            TriadNoise::try_new(bad, 1).err(),
            Some(NoiseError::Coefficient("noise_density", -1.0))
        );
    }

    #[test]
    fn white_noise_variance() {
        // The white part alone: per-sample variance N²/dt (20 000 samples: the sample variance
        // is within 4 % at 4 standard errors, √(2/n) = 1 %).
        let spec = NoiseSpec {
            noise_density: 0.02,
            ..NoiseSpec::ZERO
        };
        let mut n = AxisNoise::try_new(spec, 3).unwrap();
        let dt = 0.004;
        let xs: Vec<f64> = (0..20_000).map(|_| n.sample(dt).unwrap()).collect();
        let mean = xs.iter().sum::<f64>() / xs.len() as f64;
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (xs.len() - 1) as f64;
        let expected = 0.02f64.powi(2) / dt;
        assert!((var / expected - 1.0).abs() < 0.04, "{var} vs {expected}");
    }
}
