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
//!
//! The light mode ([`super::Mode::Light`]) forms Magnus-4's rotation vector from weights on the
//! samples that depend on the intervals alone ([`Magnus4Weights`]), computed once for a run of
//! equal intervals (a fixed sample rate), with the commutator's rate difference taken from the
//! step's two end samples (order 4 still): [`RateWindow::magnus4_cached`].

use crate::propagation::attitude::sealed::Propagate;
use crate::propagation::kernels::gauss_node_rates;
use crate::propagation::rate_samples::{
    GAUSS_NODE_1, GAUSS_NODE_2, cf4_rotation_vectors, magnus4_rotation_vector,
};
use crate::propagation::{Normalization, RateMethod};
use crate::step_limit::{MAX_STEP_ANGLE, within_step_limit_real};
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
    /// The light mode's Magnus-4 weights for the last intervals it saw.
    weights: Magnus4Weights<T>,
}

impl<T: Real> Default for RateWindow<T> {
    fn default() -> Self {
        Self {
            rates: [Vec3::ZERO; 4],
            steps: [T::ZERO; 3],
            len: 0,
            weights: Magnus4Weights::default(),
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
    /// two samples (an interval equal to the previous one, a regular clock, skips the ratio's
    /// products).
    #[inline]
    pub(super) fn push(&mut self, gyro: Vec3<T>, dt: T, saturated: bool) {
        let [_, s1, s2] = self.steps;
        let r = T::from_f64(GAP_RATIO);
        let len = if self.len >= 2 && dt != s2 && (dt > r * s2 || dt * r < s2) {
            1
        } else {
            self.len
        };
        let [_, r1, r2, r3] = self.rates;
        self.rates = [r1, r2, r3, gyro];
        self.steps = [s1, s2, dt];
        self.len = if saturated { 0 } else { (len + 1).min(4) };
    }

    /// The rates at the step's two Gauss nodes and the step `h`
    /// ([`gauss_node_rates`] of the interpolant through the window: the cubic through four
    /// samples, the line through the step's ends with two or three); `None` with fewer than two.
    #[inline]
    fn gauss_node_rates(&self) -> Option<(Vec3<T>, Vec3<T>, T)> {
        let [s0, s1, s2] = self.steps;
        let [_, _, r2, r3] = self.rates;
        let t2 = -s2;
        let t1 = t2 - s1;
        match self.len {
            4 => Some(gauss_node_rates(
                &[t1 - s0, t1, t2, T::ZERO],
                &self.rates,
                t2,
                T::ZERO,
            )),
            2 | 3 => Some(gauss_node_rates(&[t2, T::ZERO], &[r2, r3], t2, T::ZERO)),
            _ => None,
        }
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
        let Some((w1, w2, h)) = self.gauss_node_rates() else {
            return StepRotation::at_rate(gyro - bias, dt);
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

impl<T: Real> RateWindow<T> {
    /// The light mode's Magnus-4 rotation of the step ending at the newest sample: the same
    /// interpolant, nodes and fallbacks as [`RateWindow::rotation`] with [`RateMethod::Magnus4`],
    /// formed as `φ = φ₀ + φ₀ × δ`, `φ₀ = h(ω₃ − b̂) + Σᵢ cᵢ(ωᵢ − ω₃)` (`ω₃` the newest sample,
    /// `i` over the older ones, the [`Magnus4Weights`] of the window's intervals, computed only
    /// when the intervals change) and `δ = (h/12)(ω₃ − ω₂)`. `φ₀ = (h/2)(ω₁ + ω₂)` for the
    /// Gauss-node rates `ω₁`, `ω₂` (bias removed), Magnus-4's mean term. Its commutator
    /// `(√3/12)h² ω₁ × ω₂ = φ₀ × δ'` with `δ' = (√3/12)·h·(ω₂ − ω₁)` (as
    /// `ω₁ × ω₂ = m × (ω₂ − ω₁)`, `m = (ω₁ + ω₂)/2`) takes the step's end samples' difference
    /// for the Gauss nodes': `ω₂ − ω₁ = (h/√3)(ω̇ + h²ω⃛/36 + …)` and
    /// `ω₃ − ω₂ = h(ω̇ + h²ω⃛/24 + …)` at the step's middle, so `δ − δ' = O(h⁴)` and the
    /// commutator changes by `O(h⁵)`, the order of Magnus-4's local error (the rule stays of
    /// order 4; on the line through the step's ends, with fewer than four samples, `δ = δ'`
    /// exactly). Per sample: 15 products and a cross product, against the interpolation's
    /// divisions and some forty products of [`RateWindow::rotation`] (a soft-float division is
    /// some hundred instructions on a Cortex-M0).
    /// `rate` is the newest sample with the bias removed, `ω₃ − b̂`; returns `φ` and `|φ|²`.
    #[inline]
    pub(super) fn magnus4_cached(&mut self, rate: Vec3<T>, dt: T) -> (Vec3<T>, T) {
        let [s0, s1, s2] = self.steps;
        let held = |w: Vec3<T>| {
            let phi = w.scale(dt);
            (phi, phi.norm_squared())
        };
        let key = match self.len {
            4 => [s0, s1, s2],
            2 | 3 => [T::ZERO, T::ZERO, s2],
            _ => return held(rate),
        };
        if key != self.weights.key {
            self.weights = Magnus4Weights::new(key);
        }
        let w = &self.weights;
        let [r0, r1, r2, r3] = self.rates;
        let d2 = r2 - r3;
        let phi = rate.scale(s2)
            + (r0 - r3).scale(w.mean[0])
            + (r1 - r3).scale(w.mean[1])
            + d2.scale(w.mean[2]);
        let phi = phi + phi.cross(d2.scale(w.spread));
        let n2 = phi.norm_squared();
        // The shared step limit, `within_step_limit_real`'s test on the square at hand.
        if n2 <= T::from_f64(MAX_STEP_ANGLE * MAX_STEP_ANGLE) {
            (phi, n2)
        } else {
            held(rate)
        }
    }
}

/// Magnus-4's weights on the older samples of a [`RateWindow`] for one set of intervals, in
/// difference form (on `ωᵢ − ω₃`, `ω₃` the newest sample): with `lᵢ` the Lagrange basis of the
/// window's interpolant (the cubic through the four samples, or the line through the step's
/// two ends) and `g₁`, `g₂` the step's Gauss nodes, `cᵢ = (h/2)(lᵢ(g₁) + lᵢ(g₂))`; and the
/// commutator's `−h/12` on `ω₂ − ω₃` ([`RateWindow::magnus4_cached`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Magnus4Weights<T> {
    /// The intervals (`[s₀, s₁, h]`; `[0, 0, h]` for the line) these are for; zero before the
    /// first.
    key: [T; 3],
    /// `cᵢ` for the three older samples (zero for those the line leaves out).
    mean: [T; 3],
    /// `−h/12`: `δ = −(h/12)(ω₂ − ω₃)`.
    spread: T,
}

impl<T: Real> Magnus4Weights<T> {
    /// The weights for the intervals `key` (`[s₀, s₁, h]` oldest first, or `[0, 0, h]`: the
    /// line through the last two samples). Unchecked: the intervals positive.
    fn new(key: [T; 3]) -> Self {
        let [s0, s1, h] = key;
        let t2 = -h;
        let t1 = t2 - s1;
        let times = [t1 - s0, t1, t2, T::ZERO];
        let g1 = t2 + h * T::from_f64(GAUSS_NODE_1);
        let g2 = t2 + h * T::from_f64(GAUSS_NODE_2);
        let first = if s0 == T::ZERO { 2 } else { 0 };
        let half_h = h * T::HALF;
        let mut w = Self {
            key,
            spread: -h / T::from_f64(12.0),
            ..Self::default()
        };
        for i in first..3 {
            let (mut den, mut n1, mut n2) = (T::ONE, T::ONE, T::ONE);
            for (j, tj) in times.iter().enumerate().skip(first) {
                if i != j {
                    den *= times[i] - *tj;
                    n1 *= g1 - *tj;
                    n2 *= g2 - *tj;
                }
            }
            w.mean[i] = half_h * (n1 / den + n2 / den);
        }
        w
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

    /// The single rotation vector `φ`: `q ⊗ exp(φ)`.
    #[inline]
    pub(super) fn single(first: Vec3<T>) -> Self {
        Self {
            first,
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
        self.apply_normalised(q, Normalization::Fast)
    }

    /// [`StepRotation::apply`] with the renormalisation `norm` after the last exponential.
    #[inline]
    pub(super) fn apply_normalised<A: Propagate<T>>(&self, q: A, norm: Normalization) -> A {
        match self.second {
            Some(b) => apply_two(q, self.first, b, norm),
            None => q.mul_exp_vector(self.first, norm),
        }
    }
}

impl<T: Real> StepRotation<T> {
    /// [`StepRotation::apply_normalised`] given `total_sq`, `total().norm_squared()` as the
    /// caller formed it: a single rotation's exponential takes it for its own `|φ|²` (the
    /// same bits).
    #[inline]
    pub(super) fn apply_normalised_sq<A: Propagate<T>>(
        &self,
        q: A,
        total_sq: T,
        norm: Normalization,
    ) -> A {
        match self.second {
            Some(b) => apply_two(q, self.first, b, norm),
            None => q.mul_exp_vector_sq(self.first, total_sq, norm),
        }
    }
}

/// `q ⊗ exp(a) ⊗ exp(b)`, renormalised by `norm` after the second. Out of line: inlined, its
/// two copies of the update kernel grew the estimator's update past the size at which the
/// compiler inlines the light mode's per-sample helpers (measured on a Cortex-M0 with
/// `fw_icount_estimation`).
#[inline(never)]
fn apply_two<T: Real, A: Propagate<T>>(q: A, a: Vec3<T>, b: Vec3<T>, norm: Normalization) -> A {
    q.mul_exp_vector(a, Normalization::None)
        .mul_exp_vector(b, norm)
}

#[cfg(test)]
mod tests {
    use super::{RateMethod, RateWindow};
    use crate::{Real, Vec3};

    /// The light mode's rule written out from the window's interpolation (the reference path's
    /// Gauss-node rates): `φ₀ = (h/2)(ω₁ + ω₂ − 2b̂)` at the Gauss nodes,
    /// `φ = φ₀ + φ₀ × (h/12)(ω₃ − ω₂)` with the step's end samples; `None` where the window
    /// holds fewer than two samples (the rate held).
    fn written_out<T: Real>(w: &RateWindow<T>, bias: Vec3<T>) -> Option<Vec3<T>> {
        let (w1, w2, h) = w.gauss_node_rates()?;
        let [_, _, r2, r3] = w.rates;
        let mean = (w1 - bias + w2 - bias).scale(h * T::HALF);
        Some(mean + mean.cross((r3 - r2).scale(h / T::from_f64(12.0))))
    }

    /// A rate that does not repeat (incommensurate frequencies, rad/s) and jittered intervals
    /// with two gaps: the light mode's cached rotation against the rule written out from the
    /// window's interpolation at every sample (runs of one to four samples, after each
    /// restart, intervals that change every step and runs of equal ones), and against the full
    /// mode's Magnus-4 within the rules' `O(h⁵)` difference. Tolerances (rad): f64
    /// `1e-13·(|φ| + 1e-9)`, f32 `2e-6·(|φ| + 1e-6)` (rounding of differently ordered sums of
    /// four samples and of the weights' divisions); against Magnus-4 `|ω|²|ω̈|h⁵`-sized,
    /// `2e-8` at these rates and steps (measured: at most 3.1e-10 rad in f64).
    fn cached_matches_written_out<T: Real>(tol: f64, floor: f64) {
        let rate = |t: f64| {
            Vec3::new(
                T::from_f64(2.0 * (1.3 * t).sin() + 0.7 * (5.1 * t).cos()),
                T::from_f64(1.5 * (0.9 * t + 0.4).cos() - 0.3 * (7.3 * t).sin()),
                T::from_f64(0.8 * (2.2 * t).sin() * (0.37 * t).cos() + 0.2),
            )
        };
        let bias = Vec3::new(T::from_f64(0.01), T::from_f64(-0.02), T::from_f64(0.005));
        let mut w = RateWindow::<T>::default();
        let mut t = 0.0f64;
        w.start(rate(t));
        for k in 1..2000u32 {
            // Equal intervals in runs, jittered ones between them, two gaps.
            let dt = match k {
                700 | 1500 => 0.05,
                _ if (k / 100) % 2 == 0 => 0.01,
                _ => 0.01 * (1.0 + 0.3 * (0.77 * f64::from(k)).sin()),
            };
            t += dt;
            let g = rate(t);
            let dtt = T::from_f64(dt);
            w.push(g, dtt, false);
            let reference = written_out(&w, bias).unwrap_or((g - bias).scale(dtt));
            let (fast, n2) = w.magnus4_cached(g - bias, dtt);
            let scale = reference.norm().to_f64();
            let e = (fast - reference).norm().to_f64();
            assert!(
                e <= tol * (scale + floor),
                "sample {k}: {fast:?} against {reference:?}"
            );
            let n2_err = (n2 - fast.norm_squared()).abs().to_f64();
            assert!(
                n2_err <= tol * (scale * scale + floor),
                "sample {k}: |φ|² {n2_err}"
            );
            let magnus = w.rotation(RateMethod::Magnus4, g, bias, dtt).total();
            let e = (fast - magnus).norm().to_f64();
            assert!(
                e <= 2e-8 + tol * (scale + floor),
                "sample {k}: {fast:?} against Magnus-4 {magnus:?}"
            );
        }
    }

    #[test]
    fn cached_rule_matches_the_interpolated_one_f64() {
        cached_matches_written_out::<f64>(1e-13, 1e-9);
    }

    #[test]
    fn cached_rule_matches_the_interpolated_one_f32() {
        cached_matches_written_out::<f32>(2e-6, 1e-6);
    }
}
