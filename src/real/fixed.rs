//! The fixed-point number [`Fixed<F>`]: a 32-bit signed value with `F` fraction bits, its
//! saturating, round-to-nearest-even arithmetic and its [`Ring`] implementation, and the exact
//! conversions from and to the floats. The formats, the arithmetic and the measured accuracy
//! are documented once, in [`crate::fixed`]; the exponential map's fixed-point kernels are at the
//! rotation layer (`fixed/exp.rs`, [`crate::rotation::ExpMap`]).

use core::ops::{Add, AddAssign, Mul, MulAssign, Neg, Sub, SubAssign};

use super::Ring;
use super::wide::{mul_wide, ratio_bits, round_shift, sat_add, sat_sub, saturate};
use crate::Error;

/// A signed fixed-point number with `FRAC` fraction bits in an `i32`: the format `Q(31−FRAC).FRAC`,
/// value `raw · 2^−FRAC`. See the [`crate::fixed`] module docs for the arithmetic and the formats.
///
/// `FRAC` must be between 6 and 30 for the [`Ring`] operations (a larger value has no room for
/// `1`, a smaller one none for the exponential map's threshold 1/64); using them outside that
/// range is a compile-time error.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[repr(transparent)]
pub struct Fixed<const FRAC: u32>(pub(crate) i32);

/// Q1.30: unit quaternions, unit vectors, rotation matrices, increments and rotation vectors
/// (rad), time steps (s). Range `[−2, 2)`, resolution 2⁻³⁰.
pub type Q30 = Fixed<30>;

/// Q7.24: body rates (rad/s). Range `[−128, 128)`, resolution 2⁻²⁴.
pub type Q24 = Fixed<24>;

impl<const F: u32> Fixed<F> {
    /// The supported formats, checked at compile time: `6 ≤ F ≤ 30` (Q25.6 to Q1.30). Below 6
    /// the exponential's 1/64 threshold and its squaring shifts have no room; above 30 the value
    /// 1 is not representable (and from 53 on `2^−F` leaves the f64 exponent's normal range).
    /// Every constructor and conversion evaluates it, so a program naming `Fixed<F>` outside the
    /// range and using it does not compile:
    ///
    /// ```compile_fail
    /// let _ = gyrostat::real::Fixed::<1024>::from_bits(1).to_f64();
    /// ```
    /// ```compile_fail
    /// let _ = gyrostat::real::Fixed::<31>::try_from_f64(0.5);
    /// ```
    /// ```compile_fail
    /// let _ = gyrostat::real::Fixed::<5>::from_bits(1);
    /// ```
    /// ```
    /// assert_eq!(gyrostat::real::Fixed::<6>::from_bits(1).to_f64(), 1.0 / 64.0);
    /// assert_eq!(gyrostat::real::Fixed::<30>::from_bits(1).to_f64(), 2f64.powi(-30));
    /// ```
    pub const SUPPORTED: () = assert!(F >= 6 && F <= 30, "Fixed<F> supports 6 ≤ F ≤ 30");

    /// The number of fraction bits.
    pub const FRAC_BITS: u32 = F;
    /// The largest value, `(2³¹ − 1)·2^−F`.
    pub const MAX: Self = {
        let () = Self::SUPPORTED;
        Self(i32::MAX)
    };
    /// The smallest value, `−(2³¹ − 1)·2^−F` (the range is symmetric).
    pub const MIN: Self = {
        let () = Self::SUPPORTED;
        Self(-i32::MAX)
    };
    /// The resolution `2^−F` (one unit of the raw integer).
    pub const DELTA: Self = {
        let () = Self::SUPPORTED;
        Self(1)
    };

    /// The value whose raw integer is `raw` (`raw · 2^−F`); `i32::MIN` is clamped to
    /// [`Fixed::MIN`].
    #[inline]
    pub const fn from_bits(raw: i32) -> Self {
        let () = Self::SUPPORTED;
        Self(if raw == i32::MIN { -i32::MAX } else { raw })
    }

    /// The raw integer: the value times `2^F`.
    #[inline]
    pub const fn to_bits(self) -> i32 {
        let () = Self::SUPPORTED;
        self.0
    }

    /// Converts an f64, rounding to the nearest value of the format (ties to even).
    ///
    /// Pure integer code on the IEEE bits: exact, the same on every target, and with no
    /// floating-point instruction (cheap on an FPU-less core).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for NaN or ±∞; [`Error::OutOfRange`] when the rounded value is outside
    /// `[−(2³¹ − 1), 2³¹ − 1]·2^−F`.
    pub fn try_from_f64(x: f64) -> Result<Self, Error> {
        let () = Self::SUPPORTED;
        let b = x.to_bits();
        let exp = ((b >> 52) & 0x7FF) as i32;
        if exp == 0x7FF {
            return Err(Error::NonFinite);
        }
        if exp == 0 {
            // Zero or subnormal (|x| < 2⁻¹⁰²²): rounds to zero in every format.
            return Ok(Self(0));
        }
        let m = ((b & ((1u64 << 52) - 1)) | (1u64 << 52)) as i64;
        // x = m·2^(exp − 1075), raw = m·2^(exp − 1075 + F) = m / 2^shift.
        let shift = 1075 - exp - F as i32;
        if shift <= 0 {
            return Err(Error::OutOfRange);
        }
        // m < 2⁵³: a shift of 55 or more leaves less than ¼, which rounds to 0.
        let mag = if shift >= 55 {
            0
        } else {
            round_shift(m, shift as u32)
        };
        if mag > i64::from(i32::MAX) {
            return Err(Error::OutOfRange);
        }
        let mag = mag as i32;
        Ok(Self(if b >> 63 != 0 { -mag } else { mag }))
    }

    /// Converts an f32 (widened to f64 exactly, then as [`Fixed::try_from_f64`]).
    ///
    /// # Errors
    /// As [`Fixed::try_from_f64`].
    #[inline]
    pub fn try_from_f32(x: f32) -> Result<Self, Error> {
        Self::try_from_f64(f64::from(x))
    }

    /// The exact value as an f64 (every `Q(31−F).F` value is an f64).
    #[inline]
    pub fn to_f64(self) -> f64 {
        let () = Self::SUPPORTED;
        f64::from(self.0) * pow2_neg(F)
    }

    /// The value rounded to the nearest f32 (ties to even; exact when the raw integer has at
    /// most 24 significant bits).
    #[inline]
    pub fn to_f32(self) -> f32 {
        let () = Self::SUPPORTED;
        // One rounding (i32 → f32), then an exact scaling by a power of two.
        (self.0 as f32) * (pow2_neg(F) as f32)
    }

    /// The product in another format: `self · other` rounded (ties to even) to `H` fraction bits,
    /// saturated. For example a rate in Q7.24 times a step in Q1.30 gives an increment in Q1.30
    /// ([`crate::fixed::increment_from_rate`]). `F + G ≥ H` is checked at compile time.
    #[inline]
    pub fn mul_to<const G: u32, const H: u32>(self, other: Fixed<G>) -> Fixed<H> {
        let shift = const {
            assert!(F + G >= H && F + G - H <= 62, "mul_to: F + G must be ≥ H");
            F + G - H
        };
        Fixed(saturate(round_shift(mul_wide(self.0, other.0), shift)))
    }
}

/// `2^−f` as an f64 (exact), without a float power function.
#[inline]
pub(crate) fn pow2_neg(f: u32) -> f64 {
    f64::from_bits(((1023 - u64::from(f)) & 0x7FF) << 52)
}

impl<const F: u32> Add for Fixed<F> {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Self(sat_add(self.0, o.0))
    }
}

impl<const F: u32> Sub for Fixed<F> {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        Self(sat_sub(self.0, o.0))
    }
}

/// Exact: the range is symmetric.
impl<const F: u32> Neg for Fixed<F> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self(self.0.wrapping_neg())
    }
}

/// Rounded to nearest (ties to even), saturated.
impl<const F: u32> Mul for Fixed<F> {
    type Output = Self;
    #[inline]
    fn mul(self, o: Self) -> Self {
        Self(saturate(round_shift(mul_wide(self.0, o.0), F)))
    }
}

impl<const F: u32> AddAssign for Fixed<F> {
    #[inline]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl<const F: u32> SubAssign for Fixed<F> {
    #[inline]
    fn sub_assign(&mut self, o: Self) {
        *self = *self - o;
    }
}

impl<const F: u32> MulAssign for Fixed<F> {
    #[inline]
    fn mul_assign(&mut self, o: Self) {
        *self = *self * o;
    }
}

/// The sum of products of [`Ring::dot`], rounded to the format's resolution but not yet
/// saturated (an `i64` raw value).
#[inline]
fn dot_wide<const F: u32, const N: usize>(a: [Fixed<F>; N], b: [Fixed<F>; N]) -> i64 {
    const { assert!(N >= 1 && N <= 4, "Fixed::dot takes 1 to 4 terms") };
    let mut p = [0i64; 4];
    for (slot, (x, y)) in p.iter_mut().zip(a.into_iter().zip(b)) {
        *slot = mul_wide(x.0, y.0);
    }
    // Each |product| < 2⁶² (symmetric range), so a pair sums without overflow; with 3 or 4
    // terms the pair sums are halved first.
    if N <= 2 {
        round_shift(p[0] + p[1], F)
    } else {
        round_shift(((p[0] + p[1]) >> 1) + ((p[2] + p[3]) >> 1), F - 1)
    }
}

impl<const F: u32> Ring for Fixed<F> {
    const ZERO: Self = {
        let () = Self::SUPPORTED;
        Self(0)
    };
    const ONE: Self = {
        assert!(F >= 6 && F <= 30, "Fixed<F> implements Ring for 6 ≤ F ≤ 30");
        Self(1 << F)
    };
    const HALF: Self = {
        assert!(F >= 6 && F <= 30, "Fixed<F> implements Ring for 6 ≤ F ≤ 30");
        Self(1 << (F - 1))
    };
    /// 1/64: θ ≤ 1/8 rad (see the module docs).
    const EXP_SERIES_MAX_SQ: Self = {
        assert!(F >= 6 && F <= 30, "Fixed<F> implements Ring for 6 ≤ F ≤ 30");
        Self(1 << (F - 6))
    };

    #[inline]
    fn is_finite(self) -> bool {
        true
    }
    #[inline]
    fn abs(self) -> Self {
        Self(self.0.wrapping_abs())
    }
    #[inline]
    fn twice(self) -> Self {
        Self(sat_add(self.0, self.0))
    }
    #[inline]
    fn ratio<const N: i32, const D: i32>() -> Self {
        Self(const { ratio_bits(N, D, F) })
    }
    #[inline]
    fn dot<const N: usize>(a: [Self; N], b: [Self; N]) -> Self {
        Self(saturate(dot_wide(a, b)))
    }
    #[inline]
    fn dot_fits<const N: usize>(a: [Self; N], b: [Self; N]) -> bool {
        let s = dot_wide(a, b);
        s >= -i64::from(i32::MAX) && s <= i64::from(i32::MAX)
    }
    #[inline]
    fn inv_sqrt_near_one(x: Self) -> Self {
        inv_sqrt_near_one(x)
    }
}

/// Newton iterations allowed: from `r = 1`, `x` just below 2 (the slowest case of the domain)
/// needs 6.
const MAX_NEWTON: u32 = 8;

/// `1/√x` for `x ∈ (½, 2)` by Newton's iteration `r ← r + r(1 − x r²)/2` from `r = 1`, until
/// the correction rounds to zero (at most 8 steps; for a drifting unit quaternion, `|x − 1|` of a
/// few units of resolution, one or two). The domain's lower end is where `r² = 1/x` leaves
/// Q1.30 (`r² < 2`): below it `r·r` saturates and the result is wrong (`x = 0.39` gives a scale
/// that leaves `|q|²` at 1.56). Outside the domain the result saturates or is inaccurate, never
/// a panic.
fn inv_sqrt_near_one<const F: u32>(x: Fixed<F>) -> Fixed<F> {
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

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    #[test]
    fn conversions_round_to_nearest_even_and_check_the_range() {
        let d = Q30::DELTA.to_f64();
        assert_eq!(d, 2f64.powi(-30));
        assert_eq!(Q30::try_from_f64(1.0).unwrap().to_bits(), 1 << 30);
        assert_eq!(Q30::try_from_f64(-0.0).unwrap().to_bits(), 0);
        assert_eq!(Q30::try_from_f64(2.5 * d).unwrap().to_bits(), 2);
        assert_eq!(Q30::try_from_f64(3.5 * d).unwrap().to_bits(), 4);
        assert_eq!(Q30::try_from_f64(-2.5 * d).unwrap().to_bits(), -2);
        assert_eq!(Q30::try_from_f64(0.49 * d).unwrap().to_bits(), 0);
        assert_eq!(Q30::try_from_f64(1e-300).unwrap().to_bits(), 0);
        assert_eq!(Q30::try_from_f64(2.0 - d).unwrap(), Q30::MAX);
        assert_eq!(Q30::try_from_f64(-(2.0 - d)).unwrap(), Q30::MIN);
        assert_eq!(Q30::try_from_f64(2.0), Err(Error::OutOfRange));
        assert_eq!(Q30::try_from_f64(-2.0), Err(Error::OutOfRange));
        assert_eq!(Q30::try_from_f64(2.0 - 0.4 * d), Err(Error::OutOfRange));
        assert_eq!(Q30::try_from_f64(1e300), Err(Error::OutOfRange));
        assert_eq!(Q30::try_from_f64(f64::NAN), Err(Error::NonFinite));
        assert_eq!(Q30::try_from_f64(f64::NEG_INFINITY), Err(Error::NonFinite));
        assert_eq!(Q24::try_from_f64(100.0).unwrap().to_f64(), 100.0);
        // Round trip of every representable value class.
        for raw in [1, -1, 12345, -i32::MAX, i32::MAX, 1 << 29] {
            let x = Q30::from_bits(raw);
            assert_eq!(Q30::try_from_f64(x.to_f64()).unwrap(), x);
        }
        assert_eq!(Q30::from_bits(i32::MIN), Q30::MIN);
        assert_eq!(Q30::from_bits(1 << 30).to_f32(), 1.0f32);
    }

    #[test]
    fn arithmetic_saturates_and_rounds() {
        let q = |x: f64| Q30::try_from_f64(x).unwrap();
        assert_eq!(Q30::MAX + Q30::DELTA, Q30::MAX);
        assert_eq!(Q30::MIN - Q30::DELTA, Q30::MIN);
        assert_eq!(-Q30::MIN, Q30::MAX);
        assert_eq!(Q30::MIN.abs(), Q30::MAX);
        assert_eq!(q(1.5) * q(1.5), Q30::MAX); // 2.25 saturates
        assert_eq!(q(-1.5) * q(1.5), Q30::MIN);
        assert_eq!(q(1.5).twice(), Q30::MAX);
        // 3 units × ½ = 1.5 units → 2 (tie to even), 5 × ½ = 2.5 → 2, −3 × ½ → −2.
        let h = Q30::HALF;
        assert_eq!((Q30::from_bits(3) * h).to_bits(), 2);
        assert_eq!((Q30::from_bits(5) * h).to_bits(), 2);
        assert_eq!((Q30::from_bits(-3) * h).to_bits(), -2);
        // dot rounds once: four products of 1 unit × ½ (each a tie) sum to 2 units exactly.
        let d = Q30::dot([Q30::DELTA; 4], [h; 4]);
        assert_eq!(d.to_bits(), 2);
        // No overflow at the extremes: MAX·MAX·4 saturates.
        assert_eq!(Q30::dot([Q30::MAX; 4], [Q30::MAX; 4]), Q30::MAX);
        assert_eq!(Q30::dot([Q30::MAX; 4], [Q30::MIN; 4]), Q30::MIN);
        assert_eq!(Q30::dot([Q30::MAX; 2], [Q30::MIN; 2]), Q30::MIN);
        assert_eq!(Q30::ratio::<2, 3>().to_bits(), 715_827_883);
        assert_eq!(Q30::ratio::<-27, 20>().to_bits(), -1_449_551_462); // −1.35·2³⁰ = −1449551462.4
    }
}
