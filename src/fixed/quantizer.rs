//! The conversion of increments to a fixed-point format without a rounding bias:
//! [`IncrementQuantizer`], with the remainder of each conversion carried into the next. Why it
//! exists and what was measured: the [module docs](super), "Rounding bias".

use crate::real::Fixed;
use crate::real::wide::round_shift;
use crate::{Error, Vec3};

/// Converts a stream of f64 increments to the fixed-point format with the rounding remainder of
/// each carried into the next (error feedback), as a rate-integrating gyro keeps the fraction of
/// a pulse it has not yet output.
///
/// Rounding each increment on its own (as [`Vec3::try_from_f64`]) makes the same error every
/// time the same increment comes again: a constant rate, or the constant axial component of a
/// coning motion, then turns by a wrong angle every sample, a drift up to 2^−(F+1) rad per sample
/// (4.7e-7 rad/s at 1 kHz in Q1.30; measured in the [module docs](super)). With the remainder
/// carried, the sum of the converted increments stays within 2^−(F+1) of the sum of the given
/// ones, for ever.
///
/// Exact in integers on the IEEE bits (the same on every target, no floating-point
/// instruction): each increment is first taken to units of 2⁻⁶¹ rad (rounded to nearest, ties
/// to even: below 2⁻⁶² rad the input is not represented), the remainder added, the sum rounded
/// to the format and the new remainder kept (|remainder| ≤ half a unit of the format).
///
/// ```
/// use gyrostat::fixed::IncrementQuantizer;
/// use gyrostat::real::Q30;
/// use gyrostat::Vec3;
/// let mut quant = IncrementQuantizer::<30>::new();
/// let mut sum = 0i64;
/// for _ in 0..1_000_000 {
///     sum += i64::from(quant.try_quantize(Vec3::new(1e-3, 0.0, 0.0))?.x.to_bits());
/// }
/// // 1000 rad in units of 2^-30, to within half a unit (rounding each: 0.18 units per sample off).
/// assert!((sum as f64 - 1000.0 * 2f64.powi(30)).abs() <= 0.5);
/// # Ok::<(), gyrostat::Error>(())
/// ```
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct IncrementQuantizer<const F: u32> {
    /// The remainder of each component, units 2⁻⁶¹.
    pub(crate) remainder: [i64; 3],
}

/// Fraction bits of the wide value an increment is first taken to.
pub(crate) const QUANTIZER_WIDE: u32 = 61;
const WIDE: u32 = QUANTIZER_WIDE;

impl<const F: u32> IncrementQuantizer<F> {
    /// No remainder.
    pub const fn new() -> Self {
        Self { remainder: [0; 3] }
    }

    /// The increment `v` (rad) in the format, with the remainder of the previous conversions
    /// added and the new remainder kept.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite component; [`Error::OutOfRange`] when a
    /// component (with the remainder) leaves the format's range. Either way the remainder is
    /// unchanged.
    pub fn try_quantize(&mut self, v: Vec3<f64>) -> Result<Vec3<Fixed<F>>, Error> {
        const { assert!(F <= 30, "IncrementQuantizer: at most 30 fraction bits") };
        let k = WIDE - F;
        let mut out = [0i32; 3];
        let mut rem = self.remainder;
        for ((o, r), x) in out.iter_mut().zip(rem.iter_mut()).zip(v.to_array()) {
            let w = wide_bits(x)? + *r;
            let q = round_shift(w, k);
            if q.abs() > i64::from(i32::MAX) {
                return Err(Error::OutOfRange);
            }
            *r = w - (q << k);
            *o = q as i32;
        }
        self.remainder = rem;
        Ok(Vec3::new(Fixed(out[0]), Fixed(out[1]), Fixed(out[2])))
    }

    /// The carried remainders in rad (each at most half a unit of the format).
    pub fn remainder(&self) -> Vec3<f64> {
        let s = crate::real::fixed::pow2_neg(WIDE);
        Vec3::new(
            self.remainder[0] as f64 * s,
            self.remainder[1] as f64 * s,
            self.remainder[2] as f64 * s,
        )
    }
}

/// `x` in units of 2⁻⁶¹, rounded to nearest (ties to even); `|x| < 2` (else
/// [`Error::OutOfRange`]; [`Error::NonFinite`] for NaN and ±∞). Integer code on the IEEE bits.
fn wide_bits(x: f64) -> Result<i64, Error> {
    let b = x.to_bits();
    let exp = ((b >> 52) & 0x7FF) as i32;
    if exp == 0x7FF {
        return Err(Error::NonFinite);
    }
    if exp == 0 {
        return Ok(0);
    }
    if exp >= 1024 {
        return Err(Error::OutOfRange); // |x| ≥ 2
    }
    let m = ((b & ((1u64 << 52) - 1)) | (1u64 << 52)) as i64;
    // x = m·2^(exp − 1075), in units 2⁻⁶¹: m·2^(exp − 1014).
    let shift = 1014 - exp;
    let mag = if shift <= 0 {
        m << (-shift) // exp ≤ 1023: at most m·2⁹ < 2⁶²
    } else if shift >= 55 {
        0 // below a quarter of the unit
    } else {
        round_shift(m, shift as u32)
    };
    Ok(if b >> 63 != 0 { -mag } else { mag })
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    #[test]
    fn wide_bits_are_exact_and_checked() {
        assert_eq!(wide_bits(1.0), Ok(1 << 61));
        assert_eq!(wide_bits(-0.5), Ok(-(1 << 60)));
        assert_eq!(wide_bits(2f64.powi(-61)), Ok(1));
        assert_eq!(wide_bits(1.5 * 2f64.powi(-61)), Ok(2)); // tie to even
        assert_eq!(wide_bits(2.5 * 2f64.powi(-61)), Ok(2));
        assert_eq!(wide_bits(2f64.powi(-70)), Ok(0));
        assert_eq!(wide_bits(2.0 - 2f64.powi(-52)), Ok((1 << 62) - (1 << 9))); // 2⁻⁵²·2⁶¹ = 2⁹
        assert_eq!(wide_bits(2.0), Err(Error::OutOfRange));
        assert_eq!(wide_bits(f64::NAN), Err(Error::NonFinite));
        assert_eq!(wide_bits(f64::NEG_INFINITY), Err(Error::NonFinite));
    }

    #[test]
    fn quantizer_keeps_the_running_sum() {
        let mut quant = IncrementQuantizer::<30>::new();
        let v = Vec3::new(1e-3, -7.3e-4, 2.2e-10);
        let mut sum = [0i64; 3];
        for n in 1..=100_000i64 {
            let d = quant.try_quantize(v).unwrap();
            for (s, c) in sum.iter_mut().zip(d.to_array()) {
                *s += i64::from(c.to_bits());
            }
            for (s, x) in sum.iter().zip(v.to_array()) {
                let want = n as f64 * x * 2f64.powi(30);
                assert!(
                    (*s as f64 - want).abs() <= 0.5 + 1e-6 * want.abs().max(1.0),
                    "{n}"
                );
            }
        }
        let r = quant.remainder();
        assert!(r.x.abs() <= 2f64.powi(-31) && r.y.abs() <= 2f64.powi(-31));
        // An out-of-range or non-finite increment leaves the remainder as it was.
        let before = quant;
        assert_eq!(
            quant.try_quantize(Vec3::new(0.0, 2.0, 0.0)),
            Err(Error::OutOfRange)
        );
        assert_eq!(
            quant.try_quantize(Vec3::new(f64::NAN, 0.0, 0.0)),
            Err(Error::NonFinite)
        );
        assert_eq!(quant, before);
    }
}
