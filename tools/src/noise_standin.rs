//! A stand-in for the noise model of `noise.rs` (owned by the Allan characterisation work):
//! the same shape, replaced when that module is merged. One axis's stochastic error: white
//! noise, bias instability (one first-order Gauss–Markov process) and rate random walk.

use crate::synthesis::Rng;

/// The stochastic errors of one sensor axis, SI units (gyro: rad/s/√Hz, rad/s, rad/s/√s;
/// accelerometer: m/s²/√Hz, m/s², m/s²/√s).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NoiseSpec {
    /// White noise density `N`: the sample's white part has standard deviation `N/√Δt`.
    pub noise_density: f64,
    /// Bias instability `B`: the flat floor of the Allan deviation.
    pub bias_instability: f64,
    /// Rate random walk `K`: the bias's random-walk increments have variance `K²Δt`.
    pub rate_random_walk: f64,
}

/// The sample errors of one axis, step by step.
pub struct AxisNoise {
    spec: NoiseSpec,
    dt: f64,
    rng: Rng,
    markov: f64,
    walk: f64,
}

impl AxisNoise {
    /// The correlation time of the bias-instability process, s.
    const TAU: f64 = 100.0;

    /// Noise of `spec` sampled every `dt` seconds, from `seed`.
    pub fn new(spec: NoiseSpec, dt: f64, seed: u64) -> Self {
        Self {
            spec,
            dt,
            rng: Rng::new(seed),
            markov: 0.0,
            walk: 0.0,
        }
    }

    /// The error of the next sample.
    pub fn next_error(&mut self) -> f64 {
        let s = self.spec;
        let white = s.noise_density / self.dt.sqrt() * self.rng.normal();
        // A Gauss–Markov process whose Allan deviation peaks near B at τ ≈ 1.9 T (stationary
        // standard deviation B/0.437·√(…) approximated as B/0.62).
        let phi = (-self.dt / Self::TAU).exp();
        let sigma = s.bias_instability / 0.62;
        self.markov = phi * self.markov + sigma * (1.0 - phi * phi).sqrt() * self.rng.normal();
        self.walk += s.rate_random_walk * self.dt.sqrt() * self.rng.normal();
        white + self.markov + self.walk
    }
}
