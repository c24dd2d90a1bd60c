//! The estimator's rate path: the window of the last rate samples and their intervals that the
//! 4th-order rules ([`super::RateRule::Magnus4`], [`super::RateRule::Cf4`]) interpolate, and a
//! step's rotation as the prediction applies it.
//!
//! The window is plain data (four samples, three intervals, a count), filled by
//! [`RateWindow::push`] and read by [`RateWindow::rotation`], which forms the step's rotation
//! vector with the propagation module's kernels: the Gauss-node rates of the backward
//! interpolant at the samples' own times
//! ([`crate::propagation::kernels::magnus4_step_unequal`]'s interpolation) and the Magnus-4 or
//! CF4 rotation vectors ([`crate::propagation::rate_samples`]). The times are kept relative to
//! the newest sample (`0`, `−Δtₖ`, `−Δtₖ − Δtₖ₋₁`, …), so an f32 filter interpolates over
//! differences of a few steps, never over a growing clock.

use crate::propagation::attitude::sealed::Propagate;
use crate::propagation::kernels::gauss_node_rates;
use crate::propagation::rate_samples::{cf4_rotation_vectors, magnus4_rotation_vector};
use crate::propagation::{Normalization, RateMethod};
use crate::step_limit::within_step_limit_real;
use crate::{Real, Vec3};

/// The largest ratio between an interval and the one before it that keeps the window: a longer
/// interval (a gap) or a shorter one (a clock restart, a burst) starts it again from the
/// interval's own two samples, so that the interpolant is never stretched over samples whose
/// spacing differs by more than this.
const GAP_RATIO: f64 = 2.0;

/// The last rate samples (clipped, bias not removed) and the intervals between them.
#[derive(Clone, Copy, Debug)]
pub(super) struct RateWindow<T> {
    /// Oldest first: `rates[3]` is the newest sample.
    rates: [Vec3<T>; 4],
    /// `steps[i]`, s: the interval from `rates[i]` to `rates[i + 1]`.
    steps: [T; 3],
    /// How many of the newest samples form one unbroken run (0 to 4).
    len: u8,
}

impl<T: Real> Default for RateWindow<T> {
    fn default() -> Self {
        Self {
            rates: [Vec3::ZERO; 4],
            steps: [T::ZERO; 3],
            len: 0,
        }
    }
}

impl<T: Real> RateWindow<T> {
    /// Forgets every sample (the next push starts the run).
    #[inline]
    pub(super) fn restart(&mut self) {
        self.len = 0;
    }

    /// Starts the run at the initialising sample.
    #[inline]
    pub(super) fn start(&mut self, gyro: Vec3<T>) {
        self.rates[3] = gyro;
        self.len = 1;
    }

    /// Adds the sample `gyro` taken `dt` after the newest. A saturated sample (at either end of
    /// the interval) is no rate to interpolate through: the window keeps it alone, so that this
    /// step takes its rate alone and the next one restarts after it. An interval beyond
    /// [`GAP_RATIO`] times the previous one, or below its inverse, keeps only the interval's
    /// two samples.
    #[inline]
    pub(super) fn push(&mut self, gyro: Vec3<T>, dt: T, saturated: bool) {
        let [_, s1, s2] = self.steps;
        let r = T::from_f64(GAP_RATIO);
        let len = if self.len >= 2 && (dt > r * s2 || dt * r < s2) {
            1
        } else {
            self.len
        };
        let [_, r1, r2, r3] = self.rates;
        self.rates = [r1, r2, r3, gyro];
        self.steps = [s1, s2, dt];
        self.len = if saturated { 0 } else { (len + 1).min(4) };
    }

    /// The rotation of the step ending at the newest sample (`gyro`, `dt` after the one before
    /// it), bias `bias` removed from every sample: `method`'s rotation vector(s) from the
    /// Gauss-node rates of the interpolant through the window (four samples: cubic, order 4;
    /// two or three: linear through the step's ends, order 2, the trapezoid's mean with the
    /// commutator term; the quadratic for three was left out, 484 bytes of Cortex-M0 flash for
    /// one step after each restart), or `(gyro − b)·Δt` with fewer than two samples or when
    /// the rule's rotation exceeds the shared step limit (an interpolant overshooting between
    /// wildly different samples).
    #[inline]
    pub(super) fn rotation(
        &self,
        method: RateMethod,
        gyro: Vec3<T>,
        bias: Vec3<T>,
        dt: T,
    ) -> StepRotation<T> {
        let [s0, s1, s2] = self.steps;
        let [_, _, r2, r3] = self.rates;
        let t2 = -s2;
        let t1 = t2 - s1;
        let (w1, w2, h) = match self.len {
            4 => gauss_node_rates(&[t1 - s0, t1, t2, T::ZERO], &self.rates, t2, T::ZERO),
            2 | 3 => gauss_node_rates(&[t2, T::ZERO], &[r2, r3], t2, T::ZERO),
            _ => return StepRotation::at_rate(gyro - bias, dt),
        };
        let (w1, w2) = (w1 - bias, w2 - bias);
        let step = match method {
            RateMethod::Cf4 => {
                let (a, b) = cf4_rotation_vectors(w1, w2, h);
                StepRotation {
                    first: a,
                    second: Some(b),
                }
            }
            // `RateRule` offers Magnus-4 and CF4 only.
            _ => StepRotation {
                first: magnus4_rotation_vector(w1, w2, h),
                second: None,
            },
        };
        if within_step_limit_real(step.total()) {
            step
        } else {
            StepRotation::at_rate(gyro - bias, dt)
        }
    }
}

/// A step's rotation in the body (sensor) frame, as the prediction applies it:
/// `q ⊗ exp(first)`, then `⊗ exp(second)` when there is a second (CF4).
#[derive(Clone, Copy, Debug)]
pub(super) struct StepRotation<T> {
    pub(super) first: Vec3<T>,
    pub(super) second: Option<Vec3<T>>,
}

impl<T: Real> StepRotation<T> {
    /// The rotation of the (bias-removed) rate `w` held over `dt`: `w·Δt`.
    #[inline]
    pub(super) fn at_rate(w: Vec3<T>, dt: T) -> Self {
        Self {
            first: w.scale(dt),
            second: None,
        }
    }

    /// The step's rotation vector to first order, `first + second` (the covariance's
    /// rate-proportional noise, the step limit).
    #[inline]
    pub(super) fn total(&self) -> Vec3<T> {
        match self.second {
            Some(b) => self.first + b,
            None => self.first,
        }
    }

    /// `q ⊗ exp(first) [⊗ exp(second)]`, renormalised once (fast), after the last, by the
    /// attitude kind's update kernel (plain or compensated).
    #[inline]
    pub(super) fn apply<A: Propagate<T>>(&self, q: A) -> A {
        match self.second {
            Some(b) => apply_two(q, self.first, b),
            None => q.mul_exp_vector(self.first, Normalization::Fast),
        }
    }
}

/// `q ⊗ exp(a) ⊗ exp(b)`, renormalised after the second. Out of line: inlined, its two copies
/// of the update kernel grew the estimator's update past the size at which the compiler
/// inlines the light mode's per-sample helpers (measured on a Cortex-M0 with
/// `fw_icount_estimation`).
#[inline(never)]
fn apply_two<T: Real, A: Propagate<T>>(q: A, a: Vec3<T>, b: Vec3<T>) -> A {
    q.mul_exp_vector(a, Normalization::None)
        .mul_exp_vector(b, Normalization::Fast)
}

impl<T: Real> StepRotation<T> {}
