//! Low-pass filters for samples at irregular intervals.
//!
//! [`LowPass`] is two first-order stages in cascade (a critically damped second-order filter),
//! each `y ← y + k·(x − y)` with `k = Δt/(τ/2 + Δt)`: the backward-Euler discretisation of
//! `τ/2·ẏ = x − y`, stable for every `Δt > 0` and exact at `Δt → 0`. Its DC group delay is `τ`
//! (each stage delays by `τ/2`), the delay of the second-order Butterworth filter that VQF uses
//! with the same `τ`; unlike a Butterworth filter its coefficients need no `tan` and follow a
//! per-sample `Δt`. The step response does not overshoot.

use crate::{Real, Vec3};

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

    /// The stage gain `k = Δt/(τ/2 + Δt)` for a time constant `tau` and a step `dt`
    /// (both positive; `tau = 0` passes the input through: `k = 1`).
    #[inline]
    pub fn gain(tau: T, dt: T) -> T {
        dt / (tau * T::HALF + dt)
    }

    /// Feeds one sample with the stage gain `k` ([`LowPass::gain`]) and returns the output.
    #[inline]
    pub fn update(&mut self, x: Vec3<T>, k: T) -> Vec3<T> {
        self.stage1 += (x - self.stage1).scale(k);
        self.stage2 += (self.stage1 - self.stage2).scale(k);
        self.stage2
    }

    /// The current output.
    #[inline]
    pub fn output(&self) -> Vec3<T> {
        self.stage2
    }
}
