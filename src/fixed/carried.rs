//! The fixed-point attitude without a rounding bias: [`CarriedAttitude`], the attitude with the
//! discarded low bits of each rounding carried into the next update, and [`IncrementQuantizer`],
//! the conversion of increments to the format with the remainder carried. Why they exist and
//! what was measured: the [module docs](super), "Rounding bias".

use crate::fixed::{Fixed, IncrementScale, Q30};
use crate::propagation::ConingTerms;
use crate::propagation::attitude::{PropagatedAttitude, sealed::Propagate};
use crate::propagation::coning::{ConingRule, coning_terms_for, two_sample_terms};
use crate::propagation::normalization::Normalization;
use crate::propagation::rate_samples::{RateMethod, Weights};
use crate::real::wide::{mul_wide, round_shift, saturate};
use crate::rotation::half_angle_series;
use crate::{Error, Real, Ring, UnitQuat, Vec3};

/// Extra fraction bits of the rotation vector and of the rotation increment inside an update
/// (as in the plain fused update, `fixed/exp.rs`).
const FINE: u32 = 3;

/// A fixed-point attitude with the rounding residuals of its updates carried: `q` (the attitude
/// in the format, what firmware reads and logs) and the low bits that each update's roundings
/// discarded, added back into the next update (error feedback, exact in integers).
///
/// Three roundings of the plain update ([`UnitQuat::mul_exp_coning_unchecked`] +
/// [`Normalization::Fast`]) repeat their error update after update when the motion repeats or
/// changes slowly, and so integrate into a drift (measured, see the [module docs](super)); here
/// each keeps its residual:
/// - the coning term `lever × last`, formed exactly and rounded to the fine scale 2^−(F+3): its
///   residual (units 2^−2F) is added to the next coning term;
/// - the rotation increment `u = sin(θ/2)/θ·φ` at 2^−(F+3): its residual (units 2^−(2F+3)) is
///   added to the next one;
/// - the attitude itself, each component of `q ⊗ (cos(θ/2), u)` summed in 64 bits and rounded to
///   2^−F: the residual (units 2^−(2F+1)) is added to the next update's sum. (The residual is
///   carried unrotated: the error of that, `|u|·2^−(F+1)` per update, is the rounding error times
///   the per-update angle.)
///
/// The renormalisation is folded into the update instead of rounding the attitude a second time:
/// the increment `(cos(θ/2), u)` is scaled by `1 + (1 − |q|²)/2` ([`Normalization::Fast`]: one
/// Newton step, from the attitude before the update) or by `1/|q|` ([`Normalization::Exact`]),
/// so every update rounds the attitude once, with its residual carried.
///
/// What remains: the series of the exponential (rounded to 2⁻³⁰, a relative 2⁻³⁰ of the
/// per-update angle), the lever's coefficient and the 2 low bits of each `q·u` product at
/// 2^−(2F+3) (≤ 3·2⁻⁶³ per update): no measurable drift over 10⁸ updates.
///
/// State: 14 words (the attitude and 10 residuals). Give it to
/// [`crate::propagation::IncrementIntegrator::new`] in place of a [`UnitQuat`] to run that
/// integrator carried (what `propagate --fixed` does), or call
/// [`CarriedAttitude::coning2_update`] from the firmware's gyro interrupt.
///
/// ```
/// use gyrostat::fixed::{CarriedAttitude, Q30};
/// use gyrostat::UnitQuat;
/// use gyrostat::Vec3;
/// let mut q = CarriedAttitude::new(UnitQuat::<Q30>::IDENTITY);
/// let t = Vec3::<Q30>::try_from_f64(Vec3::new(3e-4, -2e-4, 5e-4))?; // 1 ms of a steady rate
/// for _ in 0..50_000 {
///     q = q.coning2_update(t, t);
/// }
/// // 100 s: the exact answer is exp(10⁵·t) of the received increments.
/// let exact = UnitQuat::try_exp(t.to_f64().scale(1e5))?;
/// let err = (exact.inverse() * q.attitude().to_f64()).angle();
/// assert!(err < 5e-8, "{err:e}");
/// # Ok::<(), gyrostat::Error>(())
/// ```
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CarriedAttitude<const F: u32> {
    q: UnitQuat<Fixed<F>>,
    /// Residual of the attitude's rounding, units 2^−(2F+1).
    q_lo: [i32; 4],
    /// Residual of the coning term's rounding, units 2^−2F.
    coning_lo: [i32; 3],
    /// Residual of the rotation increment's rounding, units 2^−(2F+3).
    u_lo: [i32; 3],
}

impl<const F: u32> Default for CarriedAttitude<F> {
    /// The identity rotation.
    fn default() -> Self {
        Self::new(UnitQuat::IDENTITY)
    }
}

impl<const F: u32> From<UnitQuat<Fixed<F>>> for CarriedAttitude<F> {
    /// [`CarriedAttitude::new`].
    fn from(q: UnitQuat<Fixed<F>>) -> Self {
        Self::new(q)
    }
}

impl<const F: u32> CarriedAttitude<F> {
    /// Starts at `q`, every residual zero.
    #[inline]
    pub const fn new(q: UnitQuat<Fixed<F>>) -> Self {
        Self {
            q,
            q_lo: [0; 4],
            coning_lo: [0; 3],
            u_lo: [0; 3],
        }
    }

    /// The attitude in the format (the residuals are below its resolution).
    #[inline]
    pub const fn attitude(&self) -> UnitQuat<Fixed<F>> {
        self.q
    }

    /// `q ← q ⊗ exp(φ)` with the normalisation policy folded in (see the type docs).
    /// Unchecked: the domain of [`UnitQuat::mul_exp_unchecked`]. Beyond the fused exponential's
    /// domain (a component of `φ` ≥ ¼ rad or `|φ| > 1/8` rad, no gyro update at ≥ 300 Hz) the
    /// plain update runs and the residuals restart at zero.
    #[inline]
    pub fn rotated_unchecked(self, phi: Vec3<Fixed<F>>, norm: Normalization) -> Self {
        let f = [phi.x.0, phi.y.0, phi.z.0].map(|s| i64::from(s) << FINE);
        match self.update_fine(f, self.coning_lo, norm) {
            Some(r) => r,
            None => Self::new(norm.apply(self.q.mul_exp_unchecked(phi))),
        }
    }

    /// `q ← q ⊗ exp(sum + lever × last)`, the update of a coning rule, with the coning term's
    /// residual carried and the normalisation policy folded in. Unchecked, as
    /// [`CarriedAttitude::rotated_unchecked`].
    #[inline]
    pub fn rotated_coning_unchecked(
        self,
        terms: ConingTerms<Fixed<F>>,
        norm: Normalization,
    ) -> Self {
        let (l, b, s) = (terms.lever, terms.last, terms.sum);
        // Exact, units 2^−2F (each difference of two products < 2⁶³), plus the carried residual
        // (|·| ≤ 2^(F−FINE−1)).
        let cross = [
            mul_wide(l.y.0, b.z.0) - mul_wide(l.z.0, b.y.0),
            mul_wide(l.z.0, b.x.0) - mul_wide(l.x.0, b.z.0),
            mul_wide(l.x.0, b.y.0) - mul_wide(l.y.0, b.x.0),
        ];
        let sum = [s.x.0, s.y.0, s.z.0];
        let mut f = [0i64; 3];
        let mut lo = [0i32; 3];
        for i in 0..3 {
            let c = cross[i].saturating_add(i64::from(self.coning_lo[i]));
            let r = round_shift(c, F - FINE);
            lo[i] = (c - (r << (F - FINE))) as i32;
            f[i] = (i64::from(sum[i]) << FINE) + r;
        }
        match self.update_fine(f, lo, norm) {
            Some(r) => r,
            None => Self::new(norm.apply(self.q.mul_exp_coning_unchecked(s, l, b))),
        }
    }

    /// The complete 2-sample update, `q ⊗ exp(θ₁ + θ₂ + ⅔ θ₁ × θ₂)` with the fast
    /// renormalisation, carried: the counterpart of
    /// [`crate::propagation::kernels::coning2_update`], integer arithmetic only. Unchecked, as
    /// there (finite increments of at most
    /// [`MAX_STEP_ANGLE`](crate::step_limit::MAX_STEP_ANGLE) each).
    #[inline]
    pub fn coning2_update(self, t1: Vec3<Fixed<F>>, t2: Vec3<Fixed<F>>) -> Self {
        self.rotated_coning_unchecked(two_sample_terms(t1, t2), Normalization::Fast)
    }

    /// The carried update from the fine rotation vector `f` (units 2^−(F+3)) and the coning
    /// residual to keep; `None` beyond the fused domain (a component ≥ ¼ rad, or `|φ|² > 1/64`).
    #[inline]
    fn update_fine(self, f: [i64; 3], coning_lo: [i32; 3], norm: Normalization) -> Option<Self> {
        let limit = 1i64 << (F + FINE - 2); // ¼ rad at the fine scale
        if f.iter().any(|x| x.abs() >= limit) {
            return None;
        }
        let f = f.map(|x| x as i32);
        // θ² in units 2^−(2F+2·FINE−2) (each square < 2⁶², shifted by 2); 1/64 is 2^(2F−2) there.
        let t2_wide: i64 = f.iter().map(|&x| mul_wide(x, x) >> 2).sum();
        if t2_wide > 1i64 << (2 * F + 2 * FINE - 2 - 6) {
            return None;
        }
        let t2 = Fixed::<F>(saturate(round_shift(t2_wide, F + 2 * FINE - 2)));
        let (mut c, s) = half_angle_series(t2);
        // u = s·φ at the fine scale, its residual carried (units 2^−(2F+FINE), |·| ≤ 2^(F−1)).
        let mut u = [0i32; 3];
        let mut u_lo = [0i32; 3];
        for i in 0..3 {
            let w = mul_wide(s.0, f[i]) + i64::from(self.u_lo[i]);
            let r = round_shift(w, F);
            u_lo[i] = (w - (r << F)) as i32;
            u[i] = saturate(r);
        }
        // The renormalisation, folded into the increment: (c, u)·(1 + e).
        let q = self.q.into_quat();
        let e = match norm {
            Normalization::Fast => (Fixed::<F>::ONE - q.norm_squared()) * Fixed::<F>::HALF,
            Normalization::Exact => {
                Fixed::<F>::inv_sqrt_near_one(q.norm_squared()) - Fixed::<F>::ONE
            }
            Normalization::None => Fixed::<F>::ZERO,
        };
        if e != Fixed::<F>::ZERO {
            c += c * e;
            for x in u.iter_mut() {
                *x = saturate(i64::from(*x) + round_shift(mul_wide(*x, e.0), F));
            }
        }
        // Each component of q ⊗ (c, u) in units 2^−(2F+1) (as the plain fused update), plus the
        // carried residual; rounded once, the new residual kept.
        let (qw, qx, qy, qz) = (q.w.0, q.x.0, q.y.0, q.z.0);
        let [ux, uy, uz] = u;
        let cc = |a: i32| mul_wide(a, c.0) << 1;
        let uu = |a: i32, b: i32| mul_wide(a, b) >> 2;
        let wide = [
            cc(qw) - uu(qx, ux) - uu(qy, uy) - uu(qz, uz),
            cc(qx) + uu(qw, ux) + uu(qy, uz) - uu(qz, uy),
            cc(qy) + uu(qw, uy) - uu(qx, uz) + uu(qz, ux),
            cc(qz) + uu(qw, uz) + uu(qx, uy) - uu(qy, ux),
        ];
        let mut out = [0i32; 4];
        let mut q_lo = [0i32; 4];
        for i in 0..4 {
            let w = wide[i] + i64::from(self.q_lo[i]);
            let r = round_shift(w, F + 1);
            q_lo[i] = (w - (r << (F + 1))) as i32;
            out[i] = saturate(r);
        }
        Some(Self {
            q: UnitQuat::new_unchecked(crate::Quat::new(
                Fixed(out[0]),
                Fixed(out[1]),
                Fixed(out[2]),
                Fixed(out[3]),
            )),
            q_lo,
            coning_lo,
            u_lo,
        })
    }
}

impl<const F: u32> PropagatedAttitude<Fixed<F>> for CarriedAttitude<F> {}

impl<const F: u32> Propagate<Fixed<F>> for CarriedAttitude<F> {
    #[inline(always)]
    fn attitude(&self) -> UnitQuat<Fixed<F>> {
        self.q
    }
    #[inline(always)]
    fn increments(
        self,
        rule: ConingRule,
        previous: Vec3<Fixed<F>>,
        samples: &[Vec3<Fixed<F>>],
        norm: Normalization,
    ) -> Self {
        match (rule, samples) {
            (ConingRule::Exp, s) => {
                let phi = match s {
                    [a] => *a,
                    s => s.iter().fold(Vec3::ZERO, |acc, t| acc + *t),
                };
                self.rotated_unchecked(phi, norm)
            }
            (_, s) => self.rotated_coning_unchecked(coning_terms_for(previous, s), norm),
        }
    }
    /// Never called: fixed point has no rate methods (`Fixed` is not [`Real`]).
    #[inline(always)]
    fn rates<const M: usize>(
        self,
        _method: RateMethod,
        _window: &[Vec3<Fixed<F>>; M],
        _weights: &Weights<M>,
        _h: Fixed<F>,
        _h_lo: Fixed<F>,
        _norm: Normalization,
    ) -> Self
    where
        Fixed<F>: Real,
    {
        self
    }
}

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
/// use gyrostat::fixed::{IncrementQuantizer, Q30};
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
    remainder: [i64; 3],
}

/// Fraction bits of the wide value an increment is first taken to.
const WIDE: u32 = 61;

impl IncrementQuantizer<30> {
    /// A raw `[x, y, z]` increment register triple in Q1.30 rad, scaled by `scale` (as
    /// [`IncrementScale::increment`]) with the remainder of the previous conversions added and
    /// the new remainder kept: the scaled reading `raw · m / 2^shift` is exact in units of
    /// 2⁻⁶¹ (`|raw · m| < 2⁴⁶`, times `2^(31 − shift) ≤ 2¹⁶`), so a reading that repeats does not
    /// repeat its rounding. Infallible: the scale was checked so that no `i16` leaves the range
    /// (a remainder of half a unit at the range's edge saturates).
    pub fn quantize_raw(&mut self, scale: &IncrementScale, raw: [i16; 3]) -> Vec3<Q30> {
        let k = WIDE - 30;
        let (m, shift) = scale.parts();
        let mut out = [0i32; 3];
        for ((o, r), x) in out.iter_mut().zip(self.remainder.iter_mut()).zip(raw) {
            let w = (mul_wide(i32::from(x), m) << (31 - shift)) + *r;
            let q = round_shift(w, k);
            *r = w - (q << k);
            *o = saturate(q);
        }
        Vec3::new(Fixed(out[0]), Fixed(out[1]), Fixed(out[2]))
    }
}

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

    #[test]
    fn raw_readings_keep_the_running_sum() {
        let scale = IncrementScale::try_new(1.0653e-6).unwrap();
        let exact = scale.rad_per_lsb() * 2f64.powi(30); // units of 2⁻³⁰ per LSB
        let mut quant = IncrementQuantizer::<30>::new();
        let raw = [120i16, -4321, 7];
        let mut sum = [0i64; 3];
        let mut plain = [0i64; 3];
        for n in 1..=100_000i64 {
            let d = quant.quantize_raw(&scale, raw);
            let p = scale.increment(raw);
            for i in 0..3 {
                sum[i] += i64::from(d.to_array()[i].to_bits());
                plain[i] += i64::from(p.to_array()[i].to_bits());
            }
            for i in 0..3 {
                let want = n as f64 * f64::from(raw[i]) * exact;
                assert!(
                    (sum[i] as f64 - want).abs() <= 0.5 + 1e-9 * want.abs(),
                    "{n} {i}"
                );
            }
        }
        // Rounding each reading alone drifts (here by thousands of units over 10⁵ readings).
        let want = 1e5 * f64::from(raw[1]) * exact;
        assert!((plain[1] as f64 - want).abs() > 1000.0);
    }
}
