//! The rate-sample path: 4th-order integrators from equally spaced angular-rate samples.
//!
//! Most MEMS gyros deliver rate samples `ωₖ = ω(k h)` (a FIFO at a fixed output data rate), not
//! increments. Three integrators of `q̇ = ½ q ⊗ (0, ω(t))` are offered, each advancing one
//! sample interval `[tₖ, tₖ₊₁]` per step:
//!
//! - **Magnus-4** ([`magnus4_step`]): `q ← q ⊗ exp(φ)` with
//!   `φ = (h/2)(ω₁ + ω₂) + (√3/12) h² ω₁ × ω₂`, the two-point Gauss truncation of the Magnus
//!   series (Iserles, Munthe-Kaas, Nørsett & Zanna 2000, *Acta Numerica* 9, §4; Blanes, Casas,
//!   Oteo & Ros 2009, *Phys. Rep.* 470 eq. (257) with the sign of the commutator flipped because
//!   the attitude is multiplied on the right). One exponential.
//! - **CF4**, commutator-free ([`cf4_step`]): `q ← q ⊗ exp(h(a ω₁ + b ω₂)) ⊗ exp(h(b ω₁ + a ω₂))`
//!   with `a = ¼ + √3/6`, `b = ¼ − √3/6` (Blanes & Moan 2006, *Appl. Numer. Math.* 56; Celledoni,
//!   Marthinsen & Owren 2003). Two exponentials, no cross product. The exponential weighted
//!   towards the EARLIER node is applied first (leftmost, since body-frame rotations compose on
//!   the right); in the other order the second-order commutator term has the wrong sign and
//!   the method drops to order 2.
//! - **RK4** on the quaternion ([`rk4_step`]) with the rates at the start, middle and end of the
//!   interval, followed by the renormalisation policy: the classical baseline. It does not stay
//!   on the unit sphere by itself.
//!
//! # How samples map to the nodes
//! `ω₁, ω₂` are the rates at the Gauss nodes `tₖ + (½ ∓ √3/6) h`; RK4 needs `ω(tₖ + h/2)`.
//! Neither falls on a sample, so they are taken from the cubic Lagrange interpolant through four
//! consecutive samples that contain the interval. Its error is `O(h⁴)` in `ω`, so each step
//! keeps a local error `O(h⁵)` and all three methods converge with order 4 (measured in
//! `host-tests/tests/propagation/rate_samples.rs`). [`RateIntegrator`] uses, for the interval ending at
//! the newest sample `k`, the samples `k−3 … k` (no look-ahead, so no latency), except at the
//! start, where the first three intervals wait for sample 3 and use samples `0 … 3`. A record of
//! only three samples uses the quadratic interpolant (still order 3 locally), one of two samples
//! the linear one (order 2).
//!
//! The interpolation, not the integrator, dominates the error: on the coning test motion the
//! three methods fed samples agree to within 4% of each other and are about 35× less accurate
//! than the same steps fed the exact rates at the nodes (measured in
//! `host-tests/tests/propagation/rate_samples.rs`). If a sensor can deliver rates at two points per
//! interval (or the step can span two sample intervals), feed [`magnus4_step`] / [`cf4_step`]
//! directly. A centred window (`k−1 … k+2` for `[tₖ, tₖ₊₁]`) was measured only 1.65× more
//! accurate than the backward one on the same motion, not worth its one-sample latency.

use crate::{Real, Vec3};

#[cfg(doc)]
use crate::propagation::RateIntegrator;
#[cfg(doc)]
use crate::propagation::kernels::{cf4_step, magnus4_step, rk4_step};

/// `√3`, to the f64 rounding.
pub(crate) const SQRT_3: f64 = 1.732_050_807_568_877_2;
/// First Gauss–Legendre node on `[0, 1]`: `½ − √3/6`.
pub const GAUSS_NODE_1: f64 = 0.5 - SQRT_3 / 6.0;
/// Second Gauss–Legendre node on `[0, 1]`: `½ + √3/6`.
pub const GAUSS_NODE_2: f64 = 0.5 + SQRT_3 / 6.0;
/// CF4 weight of the near node: `¼ + √3/6`.
pub(crate) const CF4_A: f64 = 0.25 + SQRT_3 / 6.0;
/// CF4 weight of the far node: `¼ − √3/6`.
pub(crate) const CF4_B: f64 = 0.25 - SQRT_3 / 6.0;

/// Lagrange basis on the nodes `0, 1, …, M−1` evaluated at `tau`.
const fn lagrange<const M: usize>(tau: f64) -> [f64; M] {
    let mut w = [0.0; M];
    let mut i = 0;
    while i < M {
        let mut num = 1.0;
        let mut den = 1.0;
        let mut j = 0;
        while j < M {
            if j != i {
                num *= tau - j as f64;
                den *= i as f64 - j as f64;
            }
            j += 1;
        }
        w[i] = num / den;
        i += 1;
    }
    w
}

/// Interpolation weights for one interval `[j, j+1]` of an `M`-sample window:
/// `[Gauss node 1, Gauss node 2, midpoint, start, end]`.
const fn interval_weights<const M: usize>(j: usize) -> [[f64; M]; 5] {
    let t = j as f64;
    [
        lagrange::<M>(t + GAUSS_NODE_1),
        lagrange::<M>(t + GAUSS_NODE_2),
        lagrange::<M>(t + 0.5),
        lagrange::<M>(t),
        lagrange::<M>(t + 1.0),
    ]
}

/// The interpolation rows of one interval of an `M`-sample window:
/// `[Gauss node 1, Gauss node 2, midpoint, start, end]`.
pub(crate) type Weights<const M: usize> = [[f64; M]; 5];

pub(crate) const W4: [[[f64; 4]; 5]; 3] = [
    interval_weights::<4>(0),
    interval_weights::<4>(1),
    interval_weights::<4>(2),
];
pub(crate) const W3: [[[f64; 3]; 5]; 2] = [interval_weights::<3>(0), interval_weights::<3>(1)];
pub(crate) const W2: [[[f64; 2]; 5]; 1] = [interval_weights::<2>(0)];

/// Row indices into the weight tables.
pub(crate) const G1: usize = 0;
pub(crate) const G2: usize = 1;
pub(crate) const MID: usize = 2;
pub(crate) const START: usize = 3;
pub(crate) const END: usize = 4;

/// The interpolant `Σᵢ wᵢ sᵢ` at one row of weights.
///
/// An index loop rather than an iterator fold (here and in [`interp_difference`]): it unrolls
/// inside the step, so the f64 weights become constants of `T`. A `Zip::fold` that the optimiser
/// leaves out of line gets the weights by pointer and converts each one at run time (a
/// soft-float `f64 → f32` call on a single-precision FPU).
#[inline(always)]
pub(crate) fn interp<T: Real, const M: usize>(s: &[Vec3<T>; M], w: &[f64; M]) -> Vec3<T> {
    let mut acc = Vec3::ZERO;
    let mut i = 0;
    while i < M {
        acc += s[i].scale(T::from_f64(w[i]));
        i += 1;
    }
    acc
}

/// The interpolant in difference form, `s_last + Σᵢ wᵢ (sᵢ − s_last)` (the weights add up to
/// one): the same value as [`interp`] in exact arithmetic, but a constant rate comes out exactly
/// and a slowly varying one with the rounding of its small differences only, where [`interp`]
/// rounds each weighted sample (and the weights themselves do not add up to one in f32). The
/// compensated step uses it.
#[inline(always)]
pub(crate) fn interp_difference<T: Real, const M: usize>(
    s: &[Vec3<T>; M],
    w: &[f64; M],
) -> Vec3<T> {
    let last = s.last().copied().unwrap_or(Vec3::ZERO);
    let mut acc = last;
    let mut i = 0;
    while i + 1 < M {
        acc += (s[i] - last).scale(T::from_f64(w[i]));
        i += 1;
    }
    acc
}

/// The rates at the two Gauss nodes of interval `interval` (0, 1 or 2; larger values mean 2)
/// of a window of four consecutive equally spaced samples, from their cubic interpolant.
#[inline]
pub fn gauss_rates<T: Real>(window: &[Vec3<T>; 4], interval: usize) -> (Vec3<T>, Vec3<T>) {
    let w = match interval {
        0 => &W4[0],
        1 => &W4[1],
        _ => &W4[2],
    };
    (interp(window, &w[G1]), interp(window, &w[G2]))
}

/// The rate at the midpoint of interval `interval` (0, 1 or 2; larger values mean 2) of a
/// window of four consecutive equally spaced samples, from their cubic interpolant.
#[inline]
pub fn midpoint_rate<T: Real>(window: &[Vec3<T>; 4], interval: usize) -> Vec3<T> {
    let w = match interval {
        0 => &W4[0],
        1 => &W4[1],
        _ => &W4[2],
    };
    interp(window, &w[MID])
}

/// The Magnus-4 rotation vector over one step `h` from the rates at the two Gauss nodes:
/// `φ = (h/2)(ω₁ + ω₂) + (√3/12) h² ω₁ × ω₂` (earlier node first in the cross product).
///
/// The commutator term is formed as `(hω₁) × (hω₂)`, products of the step's own angles, so that
/// neither `h²` (a long step at a slow rate) nor `ω₁ × ω₂` (a short step at a fast rate)
/// overflows: the result is finite whenever `|ω|·h` is (the domain of the step functions).
#[inline]
pub fn magnus4_rotation_vector<T: Real>(w1: Vec3<T>, w2: Vec3<T>, h: T) -> Vec3<T> {
    let (a, b) = (w1.scale(h), w2.scale(h));
    (a + b).scale(T::HALF) + a.cross(b).scale(T::from_f64(SQRT_3 / 12.0))
}

/// The two CF4 rotation vectors `(φ_first, φ_second)` over one step `h` from the Gauss-node
/// rates: `φ_first = h(a ω₁ + b ω₂)`, `φ_second = h(b ω₁ + a ω₂)`, `a = ¼ + √3/6`, `b = ¼ − √3/6`.
/// The attitude update is `q ⊗ exp(φ_first) ⊗ exp(φ_second)`, in this order.
///
/// `φ_second` is formed as the step's mean rotation less the first, `(h/2)(ω₁ + ω₂) − φ_first`:
/// the same vector, but the two add up to the mean rotation to one rounding, where `a` and `b`
/// rounded to f32 add up to ½ only within 1e-8, a scale error of every rotation that
/// accumulates with the angle turned (measured in the estimator: 4.2e-6 rad over 10 minutes of
/// hand-held motion in f32, compensated, against 1.8e-7 for Magnus-4;
/// `host-tests/tests/estimation/rates.rs`).
#[inline]
pub fn cf4_rotation_vectors<T: Real>(w1: Vec3<T>, w2: Vec3<T>, h: T) -> (Vec3<T>, Vec3<T>) {
    let first = w1.scale(h * T::from_f64(CF4_A)) + w2.scale(h * T::from_f64(CF4_B));
    (first, (w1 + w2).scale(h * T::HALF) - first)
}

/// Which rate-sample integrator a [`RateIntegrator`] runs.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RateMethod {
    /// [`magnus4_step`]: one exponential and one cross product per step.
    Magnus4,
    /// [`cf4_step`]: two exponentials per step.
    Cf4,
    /// [`rk4_step`] followed by the normalisation policy.
    Rk4,
}

impl RateMethod {
    /// Every method, in the order above.
    pub const ALL: [RateMethod; 3] = [RateMethod::Magnus4, RateMethod::Cf4, RateMethod::Rk4];

    /// The method's name in the tools and Python: `magnus4`, `cf4`, `rk4`.
    pub const fn name(self) -> &'static str {
        match self {
            RateMethod::Magnus4 => "magnus4",
            RateMethod::Cf4 => "cf4",
            RateMethod::Rk4 => "rk4",
        }
    }
}

impl core::str::FromStr for RateMethod {
    type Err = crate::Error;
    /// The method of [`RateMethod::name`].
    ///
    /// # Errors
    /// [`crate::Error::InvalidArgument`] for any other text.
    fn from_str(s: &str) -> Result<Self, crate::Error> {
        Self::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or(crate::Error::InvalidArgument)
    }
}

impl core::fmt::Display for RateMethod {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}
