//! Low-pass filters for samples at irregular intervals.
//!
//! [`LowPass`] is two first-order stages in cascade (a critically damped second-order filter),
//! each `y ← y + k·(x − y)` with `k = 1 − exp(−Δt/(τ/2))` ([`first_order_gain`]): the exact
//! discretisation of `τ/2·ẏ = x − y` for an input held over the step, so that the same `τ`
//! gives the same filter at any sample rate and with any per-sample `Δt` (a gain `Δt/τ` or
//! `Δt/(τ + Δt)` lengthens or shortens the time constant by a share of order `Δt/τ`). Its DC group
//! delay is `τ` (each stage delays by `τ/2`), the delay of the second-order Butterworth filter
//! that VQF uses with the same `τ`; unlike a Butterworth filter its coefficients need no `tan`
//! and follow a per-sample `Δt`. The step response does not overshoot.

use crate::{Real, Vec3};

/// The gain `k = 1 − exp(−Δt/τ)` of the first-order low-pass `y ← y + k·(x − y)` that is the
/// exact discretisation of `τ·ẏ = x − y` over a step `dt` (input held over the step): after
/// any split of an interval into steps, the filter has decayed by `exp(−T/τ)`. `tau = 0` gives
/// `k = 1` (no filtering). For `Δt/τ < 1/64` the series `x(1 − x/2 + x²/6)`, `x = Δt/τ`
/// (error below `x⁴/24`, under 2·10⁻⁸ relative), keeps the small gain's precision in f32,
/// where `1 − exp(−x)` would lose it to cancellation.
#[inline]
pub fn first_order_gain<T: Real>(dt: T, tau: T) -> T {
    if tau <= T::ZERO {
        return T::ONE;
    }
    let x = dt / tau;
    if x < T::from_f64(1.0 / 64.0) {
        x * (T::ONE - x * (T::HALF - x / T::from_f64(6.0)))
    } else {
        T::ONE - (-x).exp()
    }
}

/// A critically damped second-order low-pass filter of a 3-vector (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LowPass<T> {
    stage1: Vec3<T>,
    stage2: Vec3<T>,
}

impl<T: Real> LowPass<T> {
    /// A filter at rest on `x` (its output is `x` until the input changes).
    pub fn at(x: Vec3<T>) -> Self {
        Self {
            stage1: x,
            stage2: x,
        }
    }

    /// The stage gain `k = 1 − exp(−Δt/(τ/2))` for a time constant `tau` and a step `dt`
    /// ([`first_order_gain`]; `tau = 0` passes the input through: `k = 1`).
    #[inline]
    pub fn gain(tau: T, dt: T) -> T {
        first_order_gain(dt, tau * T::HALF)
    }

    /// Feeds one sample with the stage gain `k` ([`LowPass::gain`]) and returns the output.
    #[inline]
    pub fn update(&mut self, x: Vec3<T>, k: T) -> Vec3<T> {
        self.stage1 += (x - self.stage1).scale(k);
        self.stage2 += (self.stage1 - self.stage2).scale(k);
        self.stage2
    }

    /// Feeds one sample into a running mean held in both stages: `y ← y + w·(x − y)` with
    /// the sample's weight `w` (its share of the time averaged so far, `Δt/T`), the output
    /// that mean. A filter started on one noisy sample ([`LowPass::at`]) carries that sample's
    /// error for several `τ`; fed this way over its first `τ` it starts from the mean of that
    /// time instead (at rest on it: the normal updates continue without a step).
    #[inline]
    pub fn mean_update(&mut self, x: Vec3<T>, w: T) -> Vec3<T> {
        self.stage1 += (x - self.stage1).scale(w);
        self.stage2 = self.stage1;
        self.stage2
    }

    /// The current output.
    #[inline]
    pub fn output(&self) -> Vec3<T> {
        self.stage2
    }
}
