//! The fixed-point kernels behind [`crate::Ring::exp_beyond_series`] and
//! [`crate::Ring::inv_sqrt_near_one`].

use super::Fixed;
use super::wide::{mul_wide, round_shift, saturate};
use crate::rotation::half_angle_series;
use crate::{Quat, Ring, Vec3};

/// Halvings needed at most: `|φ|² < 3·2² = 12` for components in `[−2, 2)`, and `12/4⁵ < 1/64`.
const MAX_HALVINGS: u32 = 5;

/// `exp(φ)` for `|φ|² > 1/64` (θ > 1/8 rad), by scaling and squaring.
///
/// With `θₖ = θ/2ᵏ` for the smallest `k` that brings `θₖ² ≤ 1/64` (exact: `θ²` is formed in 64
/// bits from the raw components, then shifted), the series gives `cₖ = cos(θₖ/2)` and
/// `sₖ = sin(θₖ/2)/θₖ`, and `Pₖ = sₖ²θₖ² = sin²(θₖ/2)`. Each doubling of the angle is
/// `c ← c² − P`, `P ← 4c²P`, `s ← c·s` (`cos 2x = cos²x − sin²x`, `sin²2x = 4cos²x sin²x`,
/// `sin(2x)/(2θ) = cos x · sin(x)/θ`); every quantity stays in `[−1, 1]`, so nothing is divided
/// and no precision is lost to small magnitudes. The result `(c₀, s₀·φ)` scales the original `φ`.
/// Each doubling at most doubles the rounding error of `c`: ≤ 5 doublings, measured error in
/// `host-tests/tests/fixed_point.rs`.
pub(crate) fn exp_large<const F: u32>(phi: Vec3<Fixed<F>>) -> Quat<Fixed<F>> {
    // θ² in units of 2^-(2F−2): each square < 2⁶², shifted by 2, three of them < 3·2⁶⁰.
    let sq = |x: Fixed<F>| mul_wide(x.0, x.0) >> 2;
    let t2 = sq(phi.x) + sq(phi.y) + sq(phi.z);
    // 1/64 in the same units.
    let limit = 1i64 << (2 * F - 2 - 6);
    let mut k = 0u32;
    while k < MAX_HALVINGS && t2 > (limit << (2 * k)) {
        k += 1;
    }
    let tk2 = Fixed::<F>(saturate(round_shift(t2, 2 * k + F - 2)));
    let (mut c, mut s) = half_angle_series(tk2);
    let mut p = (s * s) * tk2;
    for _ in 0..k {
        let cc = c * c;
        let c_next = cc - p;
        p = (cc * p).twice().twice();
        s = c * s;
        c = c_next;
    }
    Quat::from_parts(c, phi.scale(s))
}

/// Newton iterations allowed: from `r = 1`, `x = 0.26` (the slowest case of the domain) needs 7.
const MAX_NEWTON: u32 = 8;

/// `1/√x` for `x ∈ (¼, 2)` by Newton's iteration `r ← r + r(1 − x r²)/2` from `r = 1`, until
/// the correction rounds to zero (at most 8 steps; for a drifting unit quaternion, `|x − 1|` of a
/// few units of resolution, one or two). Outside the domain the result saturates or is
/// inaccurate, never a panic.
pub(crate) fn inv_sqrt_near_one<const F: u32>(x: Fixed<F>) -> Fixed<F> {
    let one = Fixed::<F>::ONE;
    let mut r = one;
    for _ in 0..MAX_NEWTON {
        let e = one - x * (r * r);
        let d = (r * e) * Fixed::<F>::HALF;
        if d == Fixed::<F>::ZERO {
            break;
        }
        r += d;
    }
    r
}
