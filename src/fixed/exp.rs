//! The fixed-point kernels of the exponential map: [`ExpMap`] for [`Fixed<F>`], beside the
//! floats' (in `rotation/exp.rs`). The arithmetic they rest on is the scalar layer's
//! (`real/wide.rs`); the algorithms are documented in the [module docs](super).

use crate::real::fixed::Fixed;
use crate::real::wide::{mul_wide, round_shift, saturate};
use crate::rotation::{ExpMap, half_angle_series};
use crate::{Quat, Ring, Vec3};

/// Scaling and squaring past the series; the product with the exponential fused on the series
/// domain.
impl<const F: u32> ExpMap for Fixed<F> {
    #[inline]
    fn exp_beyond_series(phi: Vec3<Self>, _theta_sq: Self) -> Quat<Self> {
        exp_large(phi)
    }
    #[inline]
    fn mul_exp(q: Quat<Self>, phi: Vec3<Self>) -> Quat<Self> {
        mul_exp(q, phi)
    }
    #[inline]
    fn mul_exp_coning(
        q: Quat<Self>,
        sum: Vec3<Self>,
        lever: Vec3<Self>,
        last: Vec3<Self>,
    ) -> Quat<Self> {
        mul_exp_coning(q, sum, lever, last)
    }
}

/// Halvings needed at most: `|φ|² ≤ 12` (components in `[−2, 2)` in Q1.30; in the other formats
/// the angle is first reduced to `|φ| ≤ π`, see [`exp_reduced`]), and `12/4⁵ < 1/64`.
const MAX_HALVINGS: u32 = 5;

/// `⌊π²·2⁵⁸⌋`: the threshold `θ² > π²` of the angle reduction, in units of `2⁻⁵⁸`.
const PI_SQ_Q58: i64 = 2_844_719_788_994_575_540;
/// `round(2⁶²/(2π))`.
const INV_2PI_Q62: i128 = 733_972_625_820_500_307;
/// `round(2π·2¹⁰⁰)`.
const TWO_PI_Q100: i128 = 7_964_883_625_991_394_727_376_702_227_904;

/// `round(v/2ᵏ)` (ties up) in 128 bits, `1 ≤ k ≤ 126`.
#[inline]
fn round_shift_wide(v: i128, k: u32) -> i128 {
    (v + (1i128 << (k - 1))) >> k
}

/// `round(num/den)` for `den > 0` (ties away from zero); 0 for `den ≤ 0` (not reached).
#[inline]
fn div_round(num: i128, den: i128) -> i128 {
    if den <= 0 {
        return 0;
    }
    let q = num.checked_div(den).unwrap_or(0);
    let r = num.checked_rem(den).unwrap_or(0);
    if 2 * r.abs() >= den {
        q + num.signum()
    } else {
        q
    }
}

/// The exponential of a rotation vector of any length in `Fixed<F>`, `F ≤ 29` (whose range
/// holds angles beyond π; Q1.30's does not), `t2 = |φ|²` in units of `2^−(2F−2)`. For
/// `F < 28` also below π (then `n = 0` and `φ' = φ` exactly), for the Q3.28 accuracy.
///
/// `exp` has period 2π in the angle up to sign: `exp((θ − 2πn)·n̂) = (−1)ⁿ exp(θn̂)`. The angle
/// `θ = √t2` is formed with 28 extra bits (an integer square root in 128 bits), `n =
/// round(θ/2π)`, `θ' = θ − 2πn ∈ [−π, π]` (2π to 2⁻¹⁰⁰), and the reduced vector
/// `φ' = φ·θ'/θ` is rounded into `Fixed<G>` (`G = 28`, or 29 for `F = 29`: a format holding
/// `|φ'| ≤ π` with the most fraction bits), whose exponential ([`exp_large`] at most 5 halvings,
/// or the series) is rounded back to `Fixed<F>` and negated for odd `n`. So every format's
/// exponential has the accuracy of the Q3.28 one (a few units of 2⁻²⁸) and then its own
/// rounding: the number of halvings no longer grows with the format's range.
fn exp_reduced<const F: u32, const G: u32>(phi: Vec3<Fixed<F>>, t2: i64) -> Quat<Fixed<F>> {
    // θ in units of 2^-(F+27): √(t2·2⁵⁶), t2 in units of 2^-(2F−2).
    let t2 = u128::try_from(t2).unwrap_or(0);
    let theta = i128::try_from((t2 << 56).isqrt()).unwrap_or(0);
    let n = round_shift_wide(theta * INV_2PI_Q62, 62 + F + 27);
    let reduced = theta - round_shift_wide(n * TWO_PI_Q100, 73 - F);
    // φ' = φ·θ'/θ in units of 2^-G.
    let up = G.saturating_sub(F);
    let scale = |c: Fixed<F>| {
        let raw = div_round((i128::from(c.0) << up) * reduced, theta);
        Fixed::<G>(saturate(i64::try_from(raw).unwrap_or(0)))
    };
    let phi_g = Vec3::new(scale(phi.x), scale(phi.y), scale(phi.z));
    let sq = |x: Fixed<G>| mul_wide(x.0, x.0) >> 2;
    let e = exp_halving(phi_g, sq(phi_g.x) + sq(phi_g.y) + sq(phi_g.z));
    let odd = n & 1 == 1;
    let back = |c: Fixed<G>| {
        let v = saturate(round_shift(i64::from(c.0), up));
        Fixed::<F>(if odd { -v } else { v })
    };
    Quat::new(back(e.w), back(e.x), back(e.y), back(e.z))
}

/// `exp(φ)` for `|φ|² > 1/64` (θ > 1/8 rad), by scaling and squaring.
///
/// With `θⱼ = θ/2ʲ` and the smallest `k` that brings `θₖ² ≤ 1/64` (exact: `θ²` is formed in 64
/// bits from the raw components, then shifted), the series gives `cₖ = cos(θₖ/2)` and
/// `sₖ = sin(θₖ/2)/θₖ`. Each doubling of the angle, from level `j` to `j − 1`, is
/// `c ← c² − Pⱼ`, `s ← c·s` with `Pⱼ = sin²(θⱼ/2)` (`cos 2x = cos²x − sin²x`,
/// `sin(2x)/(2θ) = cos x · sin(x)/θ`, and the sinc is taken against `θⱼ₋₁ = 2θⱼ`, so `s` keeps
/// the scale of `φ`). `Pⱼ` is tracked as `P̃ⱼ = Pⱼ·4^(j−2)`, which stays near `θ²/16` at every
/// level (`P̃ⱼ₋₁ = cⱼ² P̃ⱼ`): a small `Pⱼ` never loses its relative precision to the format's
/// absolute resolution, so the error of `c` grows only by the doubling of `c² − P` (≤ 2ᵏ times
/// the series' rounding, measured in `host-tests/tests/fixed/accuracy.rs`). Nothing is divided.
/// The result `(c₀, s₀·φ)` scales the original `φ`. In the formats whose range holds angles
/// beyond π (all but Q1.30) such an angle is first reduced ([`exp_reduced`]), so at most
/// [`MAX_HALVINGS`] halvings are ever needed.
fn exp_large<const F: u32>(phi: Vec3<Fixed<F>>) -> Quat<Fixed<F>> {
    const { assert!(F >= 6 && F <= 30, "Fixed<F> supports 6 ≤ F ≤ 30") };
    // θ² in units of 2^-(2F−2): each square < 2⁶², shifted by 2, three of them < 3·2⁶⁰.
    let sq = |x: Fixed<F>| mul_wide(x.0, x.0) >> 2;
    let t2 = sq(phi.x) + sq(phi.y) + sq(phi.z);
    // Formats with fewer than 28 fraction bits take every angle past the series in Q3.28 (their
    // own halvings would double their coarser rounding up to five times); Q3.28 and Q2.29 reduce
    // the angles beyond π. Q1.30 (|φ| < 2√3) needs neither, and these branches are not compiled
    // into it.
    if F < 28 {
        return exp_reduced::<F, 28>(phi, t2);
    }
    if F <= 29 && t2 > PI_SQ_Q58 >> (60 - 2 * F.min(29)) {
        return if F == 29 {
            exp_reduced::<F, 29>(phi, t2)
        } else {
            exp_reduced::<F, 28>(phi, t2)
        };
    }
    exp_halving(phi, t2)
}

/// The scaling and squaring of [`exp_large`] for `t2 = |φ|² ≤ 12` (units of `2^−(2F−2)`), any
/// angle in it (at or below the series threshold `k = 0` and the series alone is used).
fn exp_halving<const F: u32>(phi: Vec3<Fixed<F>>, t2: i64) -> Quat<Fixed<F>> {
    // 1/64 in the same units.
    let limit = 1i64 << (2 * F - 2 - 6);
    let mut k = 0u32;
    while k < MAX_HALVINGS && t2 > (limit << (2 * k)) {
        k += 1;
    }
    let tk2 = Fixed::<F>(saturate(round_shift(t2, 2 * k + F - 2)));
    let (mut c, mut s) = half_angle_series(tk2);
    // P̃ₖ = sₖ²·θ²/16 (θ²/16 < 3/4).
    let theta_sq_16 = Fixed::<F>(saturate(round_shift(t2, F + 2)));
    let mut pt = (s * s) * theta_sq_16;
    for j in (1..=k).rev() {
        let cc = c * c;
        let p = if j >= 2 {
            Fixed::<F>(saturate(round_shift(i64::from(pt.0), 2 * (j - 2))))
        } else {
            pt.twice().twice()
        };
        let c_next = cc - p;
        pt = cc * pt;
        s = c * s;
        c = c_next;
    }
    Quat::from_parts(c, phi.scale(s))
}

/// Extra fraction bits of the fused exponential's rotation vector and increment.
const FINE: u32 = 3;

/// `q ⊗ exp(φ)`, fused on the series domain (`|φ|² ≤ 1/64`); beyond it, the product with
/// [`exp_large`]. See [`mul_exp_fine`].
fn mul_exp<const F: u32>(q: Quat<Fixed<F>>, phi: Vec3<Fixed<F>>) -> Quat<Fixed<F>> {
    // Components below ¼ rad fit 32 bits with FINE more fraction bits.
    let quarter = 1i32 << (F - 2);
    let fits = |x: Fixed<F>| x.0.unsigned_abs() < quarter as u32;
    if fits(phi.x) && fits(phi.y) && fits(phi.z) {
        let f = [phi.x.0 << FINE, phi.y.0 << FINE, phi.z.0 << FINE];
        if let Some(r) = mul_exp_fine(q, f) {
            return r;
        }
    }
    q * exp_large(phi)
}

/// `q ⊗ exp(sum + lever × last)`: the cross product is formed exactly (64 bits) and rounded once
/// to the fine scale 2^−(F+3), where it is added to the sum (exact there); then as
/// [`mul_exp_fine`]. Beyond the fused domain, the rounded rotation vector goes to [`mul_exp`].
fn mul_exp_coning<const F: u32>(
    q: Quat<Fixed<F>>,
    sum: Vec3<Fixed<F>>,
    lever: Vec3<Fixed<F>>,
    last: Vec3<Fixed<F>>,
) -> Quat<Fixed<F>> {
    let (l, b) = (lever, last);
    // Each difference of two products < 2⁶³ (symmetric range); units 2^−2F.
    let cross = [
        mul_wide(l.y.0, b.z.0) - mul_wide(l.z.0, b.y.0),
        mul_wide(l.z.0, b.x.0) - mul_wide(l.x.0, b.z.0),
        mul_wide(l.x.0, b.y.0) - mul_wide(l.y.0, b.x.0),
    ];
    let s = [sum.x.0, sum.y.0, sum.z.0];
    let limit = 1i64 << (F + FINE - 2); // ¼ rad at the fine scale
    let mut f = [0i32; 3];
    let mut fused = true;
    for ((slot, &si), &ci) in f.iter_mut().zip(&s).zip(&cross) {
        let v = (i64::from(si) << FINE) + round_shift(ci, F - FINE);
        fused &= v.abs() < limit;
        *slot = saturate(v);
    }
    if fused && let Some(r) = mul_exp_fine(q, f) {
        return r;
    }
    mul_exp(q, sum + lever.cross(last))
}

/// `q ⊗ exp(φ)` for `φ` given at the fine scale 2^−(F+3) (components below ¼ rad), or `None`
/// beyond the series domain `|φ|² > 1/64`.
///
/// With `c = cos(θ/2)` and `s = sin(θ/2)/θ` from the series, `u = s·φ` (`|u| ≤ 1/16`) is rounded
/// to the fine scale (2⁻³³ in Q1.30, 8 times finer than the format), and each component of
/// `q ⊗ (c, u)`, `(q_w c − q·u, c q_v + q_w u + q_v × u)`, is summed exactly in 64 bits (units
/// 2^−(2F+1): the `c` products shifted left by one, the `u` products right by two; no overflow
/// for any components in range) and rounded once, ties to even. The rotation increment itself is
/// never rounded to the format's step: a constant rate would otherwise integrate that rounding
/// linearly.
fn mul_exp_fine<const F: u32>(q: Quat<Fixed<F>>, f: [i32; 3]) -> Option<Quat<Fixed<F>>> {
    // θ² in units 2^−(2F+2·FINE−2) (each square < 2⁶², shifted by 2); 1/64 is 2^(2F−2) there.
    let t2_wide: i64 = f.iter().map(|&x| mul_wide(x, x) >> 2).sum();
    if t2_wide > 1i64 << (2 * F + 2 * FINE - 2 - 6) {
        return None;
    }
    let t2 = Fixed::<F>(saturate(round_shift(t2_wide, F + 2 * FINE - 2)));
    let (c, s) = half_angle_series(t2);
    let fine = |x: i32| saturate(round_shift(mul_wide(s.0, x), F));
    let (ux, uy, uz) = (fine(f[0]), fine(f[1]), fine(f[2]));
    let (qw, qx, qy, qz) = (q.w.0, q.x.0, q.y.0, q.z.0);
    let cc = |a: i32| mul_wide(a, c.0) << 1;
    let uu = |a: i32, b: i32| mul_wide(a, b) >> 2;
    let out = |sum: i64| Fixed::<F>(saturate(round_shift(sum, F + 1)));
    Some(Quat::new(
        out(cc(qw) - uu(qx, ux) - uu(qy, uy) - uu(qz, uz)),
        out(cc(qx) + uu(qw, ux) + uu(qy, uz) - uu(qz, uy)),
        out(cc(qy) + uu(qw, uy) - uu(qx, uz) + uu(qz, ux)),
        out(cc(qz) + uu(qw, uz) + uu(qx, uy) - uu(qy, ux)),
    ))
}
