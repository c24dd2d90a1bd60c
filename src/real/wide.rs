//! Integer kernels of the fixed-point type: the exact 32×32 → 64-bit product, rounding of a wide
//! value to the nearest (ties to even), and saturation to the symmetric 32-bit range.

/// The exact signed product `a·b` as an `i64`.
///
/// ARMv6-M (Cortex-M0/M0+) has no long multiply (`smull`): LLVM lowers `i64` products to a call
/// of `__aeabi_lmul`, a general 64×64-bit multiply. There, gyrostat uses [`mul_wide_split`]
/// (four 16×16 → 32-bit `muls`, no call); every other target uses the native widening multiply.
/// Both give the same exact product, so results are bit-identical across targets. ARMv6-M is
/// recognised as the ARM profile without 32-bit compare-and-swap atomics
/// (`not(target_has_atomic = "32")`): stable Rust exposes no ARM architecture cfg.
#[inline(always)]
pub(crate) fn mul_wide(a: i32, b: i32) -> i64 {
    #[cfg(all(target_arch = "arm", not(target_has_atomic = "32")))]
    {
        mul_wide_split(a, b)
    }
    #[cfg(not(all(target_arch = "arm", not(target_has_atomic = "32"))))]
    {
        i64::from(a) * i64::from(b)
    }
}

/// `a·b` exactly, from 16-bit halves: `a = aₕ·2¹⁶ + aₗ` with `aₗ ∈ [0, 2¹⁶)` unsigned and `aₕ`
/// signed, so every partial product fits 32 bits (`|aₗ·bₕ| < 2³¹`, `|aₕ·bₕ| ≤ 2³⁰`,
/// `aₗ·bₗ < 2³²` unsigned) and `a·b = aₕbₕ·2³² + (aₗbₕ + aₕbₗ)·2¹⁶ + aₗbₗ`.
#[cfg_attr(
    not(all(target_arch = "arm", not(target_has_atomic = "32"))),
    allow(dead_code) // used on ARMv6-M; tested on the host
)]
#[inline(always)]
pub(crate) fn mul_wide_split(a: i32, b: i32) -> i64 {
    let (al, ah) = ((a & 0xFFFF) as u32, a >> 16);
    let (bl, bh) = ((b & 0xFFFF) as u32, b >> 16);
    let ll = al * bl; // < 2³², no overflow
    let lh = (al as i32) * bh; // |·| < 2³¹
    let hl = ah * (bl as i32);
    let hh = ah * bh;
    ((i64::from(hh)) << 32) + (i64::from(lh) << 16) + (i64::from(hl) << 16) + i64::from(ll)
}

/// `s / 2^k` rounded to the nearest integer, ties to even (`k ≤ 62`; `k = 0` returns `s`).
///
/// Unbiased: a tie (`s mod 2^k = 2^(k−1)`) goes up or down with the parity of the quotient, so
/// products by ½ (every odd value is a tie) do not drift. Caller guarantees
/// `|s| < 2⁶³ − 2^k` (no overflow of the rounding add).
#[inline(always)]
pub(crate) fn round_shift(s: i64, k: u32) -> i64 {
    if k == 0 {
        return s;
    }
    let odd = (s >> k) & 1;
    (s + ((1i64 << (k - 1)) - 1) + odd) >> k
}

/// Clamps to the symmetric range `[−(2³¹ − 1), 2³¹ − 1]` (`i32::MIN` is never produced, so that
/// negation and absolute value are exact).
#[inline(always)]
pub(crate) fn saturate(s: i64) -> i32 {
    if s > i64::from(i32::MAX) {
        i32::MAX
    } else if s < -i64::from(i32::MAX) {
        -i32::MAX
    } else {
        s as i32
    }
}

/// Saturating `a + b` in the symmetric range.
#[inline(always)]
pub(crate) fn sat_add(a: i32, b: i32) -> i32 {
    a.saturating_add(b).max(-i32::MAX)
}

/// Saturating `a − b` in the symmetric range.
#[inline(always)]
pub(crate) fn sat_sub(a: i32, b: i32) -> i32 {
    a.saturating_sub(b).max(-i32::MAX)
}

/// `round(n·2^f / d)` (ties to even) as a 32-bit raw value, for compile-time constants.
/// Panics (at compile time, where it is used in a `const` block) when `d = 0` or the ratio is
/// outside the symmetric range.
pub(crate) const fn ratio_bits(n: i32, d: i32, f: u32) -> i32 {
    assert!(d != 0, "ratio with a zero denominator");
    assert!(f <= 30, "at most 30 fraction bits");
    let (n, d) = if d < 0 {
        (-(n as i128), -(d as i128))
    } else {
        (n as i128, d as i128)
    };
    let num = n << f;
    let q = num.div_euclid(d);
    let r = num.rem_euclid(d);
    let q = if 2 * r > d || (2 * r == d && q % 2 != 0) {
        q + 1
    } else {
        q
    };
    assert!(
        q <= i32::MAX as i128 && q >= -(i32::MAX as i128),
        "ratio outside the fixed-point range"
    );
    q as i32
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// A small deterministic generator (xorshift), so that the test needs no dependency.
    fn xorshift(state: &mut u64) -> u64 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        *state
    }

    #[test]
    fn split_product_is_exact() {
        let edges = [
            0,
            1,
            -1,
            0xFFFF,
            0x10000,
            -0x10000,
            i32::MAX,
            -i32::MAX,
            i32::MIN,
        ];
        for &a in &edges {
            for &b in &edges {
                assert_eq!(mul_wide_split(a, b), i64::from(a) * i64::from(b), "{a} {b}");
            }
        }
        let mut s = 0x9E37_79B9_7F4A_7C15u64;
        for _ in 0..1_000_000 {
            let a = xorshift(&mut s) as i32;
            let b = xorshift(&mut s) as i32;
            assert_eq!(mul_wide_split(a, b), i64::from(a) * i64::from(b), "{a} {b}");
        }
    }

    #[test]
    fn rounding_is_to_nearest_ties_to_even() {
        // 2.5 → 2, 3.5 → 4, −2.5 → −2, −3.5 → −4, 2.25 → 2, 2.75 → 3 (k = 2: quarters).
        let cases = [
            (10, 2),
            (14, 4),
            (-10, -2),
            (-14, -4),
            (9, 2),
            (11, 3),
            (-9, -2),
            (-11, -3),
        ];
        for (s, want) in cases {
            assert_eq!(round_shift(s, 2), want, "{s}");
        }
        // Against an independent i128 computation with explicit ties-to-even.
        let mut st = 0x1234_5678_9ABC_DEF1u64;
        for _ in 0..200_000 {
            let s = (xorshift(&mut st) as i64) >> 2;
            let k = 1 + (xorshift(&mut st) % 40) as u32;
            let q = (s as i128).div_euclid(1 << k);
            let r = (s as i128).rem_euclid(1 << k);
            let half = 1i128 << (k - 1);
            let want = if r > half || (r == half && q % 2 != 0) {
                q + 1
            } else {
                q
            };
            assert_eq!(i128::from(round_shift(s, k)), want, "{s} {k}");
        }
    }

    #[test]
    fn saturation_is_symmetric() {
        assert_eq!(saturate(i64::MAX), i32::MAX);
        assert_eq!(saturate(i64::MIN), -i32::MAX);
        assert_eq!(saturate(i64::from(i32::MIN)), -i32::MAX);
        assert_eq!(sat_add(-i32::MAX, -1), -i32::MAX);
        assert_eq!(sat_sub(-i32::MAX, 5), -i32::MAX);
        assert_eq!(sat_add(i32::MAX, 1), i32::MAX);
        assert_eq!(ratio_bits(2, 3, 30), 715_827_883); // 2^31/3 = 715827882.67
        assert_eq!(ratio_bits(-1, 6, 30), -178_956_971); // −2^30/6 = −178956970.67
        assert_eq!(ratio_bits(1, 2, 0), 0); // ½ → 0 (tie to even)
        assert_eq!(ratio_bits(3, 2, 0), 2); // 1.5 → 2
    }
}
