//! Raw `i16` sensor registers: their LSB scale and their clipping.
//!
//! A reading becomes a physical value through one model in every number format:
//! `value = raw · lsb` (rad/s, rad, m/s², … per LSB), then the calibration
//! ([`crate::sensor::InertialCalibration`]) and the mounting ([`crate::sensor::AxisRemap`]).
//! [`RawScale`] holds the LSB in every number format: for the floats it multiplies (one rounding);
//! for Q1.30 increments (`RawScale<Q30>`) it is an integer product and one rounding, converted
//! with the rounding remainder carried by [`IncrementQuantizer::quantize_raw`].
//!
//! # Clipping
//! A MEMS sensor that saturates reports its register's limit: the true value is at least that
//! large. [`ClipLimit`] flags a reading whose magnitude reaches the configured full scale
//! (default: `+32767` or `≤ −32767`, so `i16::MIN` too) per axis ([`Clipped`]), and the caller's
//! [`ClipPolicy`] chooses what reaches the core. One policy for every reading type ([`Reading`]):
//! raw `i16` registers, and f32/f64 values against the sensor's range in physical units (the
//! [estimator](crate::estimation::Estimator) saturates its gyroscope samples at
//! [`Params::gyro_range`](crate::estimation::Params::gyro_range) this way).
//!
//! | policy | the core gets | when |
//! |---|---|---|
//! | [`ClipPolicy::Pass`] | the clipped reading as it is (its magnitude a lower bound) | short excursions where losing the sample is worse; the flags are still returned |
//! | [`ClipPolicy::Saturate`] | each clipped axis set to `±limit` (no state: [`ClipLimit::saturate`]) | a value beyond the sensor's range, read in physical units (the estimator's gyroscope samples) |
//! | [`ClipPolicy::HoldLast`] | each clipped axis replaced by that axis's last unclipped reading (a rate hold); a clip before any unclipped reading is passed | a gyro that clips briefly while rotating steadily |
//! | [`ClipPolicy::Reject`] | nothing: [`Error::Clipped`] | the caller must re-initialise from an absolute reference |
//!
//! Rates and increments hold differently when the intervals are unequal. Holding a rate reading
//! holds the rate, which is the steady-rotation assumption of [`ClipPolicy::HoldLast`]. An
//! increment `θ = ω·h` over its own interval `h` holds the rate too: the clipped axis becomes
//! `(θ_last / h_last)·h` ([`ClipGuard::filter_increment`]), not `θ_last`, which would scale the
//! held rate by `h_last / h` on a jittered clock. At a fixed interval the two agree and
//! [`ClipGuard::filter`] serves increments as well.

use crate::fixed::IncrementQuantizer;
use crate::fixed::quantizer::QUANTIZER_WIDE;
use crate::real::wide::{mul_wide, round_shift, saturate};
use crate::real::{Fixed, Q30};
use crate::{Error, Real, Ring, Vec3};

/// Which axes of a reading are at the register's limit.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Clipped {
    /// One flag per axis `x, y, z`.
    pub axes: [bool; 3],
}

impl Clipped {
    /// `true` when any axis is clipped.
    pub fn any(&self) -> bool {
        self.axes.iter().any(|&a| a)
    }
}

/// The number type of a sensor reading that can clip: a raw register (`i16`) or a value already
/// in physical units (f32, f64: a gyroscope rate against the sensor's range). Sealed.
pub trait Reading: Copy + PartialEq + clip_sealed::Reading {}

impl Reading for i16 {}
impl<T: Real> Reading for T {}

pub(crate) mod clip_sealed {
    use crate::Real;

    /// The clipping arithmetic of a reading type.
    pub trait Reading: Copy {
        /// The limit of [`super::ClipLimit::default`]: the register's own for `i16`, none (∞)
        /// for the floats.
        fn default_limit() -> Self;
        /// A usable limit: positive (and not NaN).
        fn valid_limit(limit: Self) -> bool;
        /// `r ≥ limit` or `r ≤ −limit`.
        fn reaches(r: Self, limit: Self) -> bool;
        /// `±limit` with the sign of `r`.
        fn saturated(r: Self, limit: Self) -> Self;
    }

    impl Reading for i16 {
        fn default_limit() -> i16 {
            i16::MAX
        }
        fn valid_limit(limit: i16) -> bool {
            limit > 0
        }
        #[inline(always)]
        fn reaches(r: i16, limit: i16) -> bool {
            // limit > 0 (checked when built), so the negation is exact; saturating keeps the
            // compiler from seeing an overflow branch it cannot rule out.
            r >= limit || r <= 0i16.saturating_sub(limit)
        }
        #[inline(always)]
        fn saturated(r: i16, limit: i16) -> i16 {
            if r < 0 {
                0i16.saturating_sub(limit)
            } else {
                limit
            }
        }
    }

    impl<T: Real> Reading for T {
        fn default_limit() -> T {
            T::from_f64(f64::INFINITY)
        }
        fn valid_limit(limit: T) -> bool {
            limit > T::ZERO
        }
        #[inline(always)]
        fn reaches(r: T, limit: T) -> bool {
            r.abs() >= limit
        }
        #[inline(always)]
        fn saturated(r: T, limit: T) -> T {
            if r < T::ZERO { -limit } else { limit }
        }
    }
}

/// The full scale at which a reading counts as clipped: a reading `r` with `r ≥ limit` or
/// `r ≤ −limit` (so for `i16` the value `i16::MIN` is clipped for every limit). The reading type
/// `T` is a raw register (`i16`, the default) or a value in f32/f64 (a rate against the
/// gyroscope's range: what the [estimator](crate::estimation::Estimator) applies to its
/// samples).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClipLimit<T: Reading = i16> {
    limit: T,
}

impl<T: Reading> Default for ClipLimit<T> {
    /// The register's own limit for `i16` ([`ClipLimit::FULL_REGISTER`]); no limit (∞) for the
    /// floats.
    fn default() -> Self {
        Self {
            limit: T::default_limit(),
        }
    }
}

impl ClipLimit<i16> {
    /// The register's own limit: `+32767` and `−32767`, `−32768`.
    pub const FULL_REGISTER: Self = Self { limit: i16::MAX };
}

impl<T: Reading> ClipLimit<T> {
    /// A configured full scale (for a sensor that saturates below the register's range, or the
    /// range of a reading in physical units; `∞` for the floats never clips).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for `limit ≤ 0` (or NaN).
    pub fn try_new(limit: T) -> Result<Self, Error> {
        if !T::valid_limit(limit) {
            return Err(Error::InvalidArgument);
        }
        Ok(Self { limit })
    }

    /// A limit the caller has checked (positive, not NaN).
    #[inline]
    pub(crate) const fn new_unchecked(limit: T) -> Self {
        Self { limit }
    }

    /// The limit.
    pub fn limit(&self) -> T {
        self.limit
    }

    /// The clipped axes of a reading.
    #[inline]
    pub fn check(&self, raw: [T; 3]) -> Clipped {
        Clipped {
            axes: raw.map(|r| T::reaches(r, self.limit)),
        }
    }

    /// The reading with each clipped axis set to `±limit` (its sign kept; the reading's
    /// magnitude is at least that), and the flags of the original reading: the
    /// [`ClipPolicy::Saturate`] policy, which needs no state.
    #[inline]
    pub fn saturate(&self, raw: [T; 3]) -> ([T; 3], Clipped) {
        let clipped = self.check(raw);
        let mut out = raw;
        if clipped.any() {
            for (o, c) in out.iter_mut().zip(clipped.axes) {
                if c {
                    *o = T::saturated(*o, self.limit);
                }
            }
        }
        (out, clipped)
    }
}

/// What reaches the core from a clipped reading (see the [module docs](self)).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum ClipPolicy {
    /// The clipped reading as it is.
    #[default]
    Pass,
    /// Each clipped axis set to `±limit`, its sign kept ([`ClipLimit::saturate`]).
    Saturate,
    /// Each clipped axis replaced by the last unclipped reading of that axis.
    HoldLast,
    /// [`Error::Clipped`].
    Reject,
}

/// A clipping guard on a stream of readings of type `T` (raw `i16` registers by default, or f32
/// / f64 values): the limit, the policy and the last unclipped reading of each axis (for
/// [`ClipPolicy::HoldLast`]).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct ClipGuard<T: Reading = i16> {
    limit: ClipLimit<T>,
    policy: ClipPolicy,
    last: [Option<T>; 3],
}

impl<T: Reading> ClipGuard<T> {
    /// A guard with the given limit and policy.
    pub fn new(limit: ClipLimit<T>, policy: ClipPolicy) -> Self {
        Self {
            limit,
            policy,
            last: [None; 3],
        }
    }

    /// The limit.
    pub fn limit(&self) -> ClipLimit<T> {
        self.limit
    }

    /// The policy.
    pub fn policy(&self) -> ClipPolicy {
        self.policy
    }

    /// The reading the core gets and the flags of the original reading.
    ///
    /// # Errors
    /// [`Error::Clipped`] under [`ClipPolicy::Reject`] when an axis is clipped.
    pub fn filter(&mut self, raw: [T; 3]) -> Result<([T; 3], Clipped), Error> {
        let clipped = self.limit.check(raw);
        if clipped.any() && self.policy == ClipPolicy::Reject {
            return Err(Error::Clipped);
        }
        let mut out = raw;
        for ((o, last), c) in out.iter_mut().zip(self.last.iter_mut()).zip(clipped.axes) {
            if !c {
                *last = Some(*o);
            } else {
                match (self.policy, *last) {
                    (ClipPolicy::HoldLast, Some(l)) => *o = l,
                    (ClipPolicy::Saturate, _) => *o = T::saturated(*o, self.limit.limit),
                    _ => {}
                }
            }
        }
        Ok((out, clipped))
    }
}

impl<T: Real> ClipGuard<T> {
    /// An increment `θ` over its own interval `h` (> 0): the reading is checked against the
    /// limit as it is (an angle per sample), and [`ClipPolicy::HoldLast`] holds the last
    /// unclipped *rate*: a clipped axis becomes `(θ_last · (1/h_last)) · h` (see the
    /// [module docs](self)); the other policies are those of [`ClipGuard::filter`]. A guard is fed
    /// either by this method or by [`ClipGuard::filter`], not both (the held value is a rate
    /// here, a reading there).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for `h` not positive and finite (the guard is unchanged);
    /// [`Error::Clipped`] under [`ClipPolicy::Reject`] when an axis is clipped.
    pub fn filter_increment(
        &mut self,
        increment: [T; 3],
        h: T,
    ) -> Result<([T; 3], Clipped), Error> {
        if !(h > T::ZERO && h.is_finite()) {
            return Err(Error::InvalidArgument);
        }
        let clipped = self.limit.check(increment);
        if clipped.any() && self.policy == ClipPolicy::Reject {
            return Err(Error::Clipped);
        }
        let per_s = T::ONE / h;
        let mut out = increment;
        for ((o, last), c) in out.iter_mut().zip(self.last.iter_mut()).zip(clipped.axes) {
            if !c {
                *last = Some(*o * per_s);
            } else {
                match (self.policy, *last) {
                    (ClipPolicy::HoldLast, Some(rate)) => *o = rate * h,
                    (ClipPolicy::Saturate, _) => {
                        *o = clip_sealed::Reading::saturated(*o, self.limit.limit)
                    }
                    _ => {}
                }
            }
        }
        Ok((out, clipped))
    }
}

/// The LSB scale of a raw `i16` register in a number format `T` (f32, f64 or Q1.30,
/// [`RawFormat`]): `value = raw · lsb`, one type for every format and every sensor (rate,
/// increment, specific force, field).
///
/// - f32, f64: the LSB rounded to `T` once; a reading is `raw · lsb`, one rounding.
/// - [`Q30`] (gyro increments in rad, for FPU-less cores): the LSB stored as a 31-bit mantissa
///   and a shift, fixed when the scale is built (the only place a float is read); a reading is
///   `round(raw · m / 2^shift)` in units of 2⁻³⁰ rad, one exact integer product and one rounding
///   (ties to even), no floating point at run time. The scale's own rounding is relative 2⁻³¹ at
///   most. Give it to [`IncrementQuantizer::quantize_raw`] to carry the readings' rounding
///   remainder.
///
/// ```
/// use gyrostat::real::Q30;
/// use gyrostat::sensor::RawScale;
///
/// let accel = RawScale::<f32>::try_new(9.80665 / 16384.0)?; // ±2 g, m/s² per LSB
/// assert!((accel.apply([0, 0, 16384]).z - 9.80665).abs() < 1e-6);
/// let gyro = RawScale::<Q30>::try_new(1.0 / 1048576.0)?; // 2⁻²⁰ rad per LSB
/// assert_eq!(gyro.apply([1024, 0, 0]).x.to_bits(), 1 << 20); // 2⁻¹⁰ rad
/// # Ok::<(), gyrostat::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RawScale<T: RawFormat> {
    scale: <T as sealed::Format>::Scale,
}

#[cfg(feature = "defmt")]
impl<T: RawFormat> defmt::Format for RawScale<T> {
    fn format(&self, f: defmt::Formatter) {
        defmt::write!(f, "RawScale {{ lsb: {=f64} }}", self.lsb())
    }
}

impl<T: RawFormat> RawScale<T> {
    /// The scale `lsb` (the unit's value of one LSB: rad/s, rad, m/s², … per LSB).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for NaN or ±∞; [`Error::InvalidArgument`] for `lsb ≤ 0` (or one
    /// that rounds to 0 in `T`) or, in a float type, a full scale `32768·lsb` that overflows;
    /// in Q1.30, [`Error::OutOfRange`] for a scale `≥ 2⁻¹⁴` rad/LSB (a full-scale reading,
    /// 32768 LSB, would reach 2 rad and leave Q1.30) or `< 2⁻³⁰` (below the resolution of
    /// Q1.30: every reading would round to a multiple of it).
    pub fn try_new(lsb: f64) -> Result<Self, Error> {
        Ok(Self {
            scale: T::try_scale(lsb)?,
        })
    }

    /// The scale of a rate register (unit/s per LSB) integrated over a step `dt` (s):
    /// `lsb_per_s · dt` per LSB, the rectangle rule for a rate sampled once per step (a gyro rate
    /// register read as increments).
    ///
    /// # Errors
    /// As [`RawScale::try_new`] for the product.
    pub fn try_from_rate(lsb_per_s: f64, dt: f64) -> Result<Self, Error> {
        Self::try_new(lsb_per_s * dt)
    }

    /// The LSB value, exactly as stored.
    pub fn lsb(&self) -> f64 {
        T::lsb(&self.scale)
    }

    /// One reading, `raw · lsb` in `T`. Infallible: the scale was checked so that no `i16`
    /// leaves the format's range.
    #[inline]
    pub fn reading(&self, raw: i16) -> T {
        T::reading(&self.scale, raw)
    }

    /// `raw · lsb` per axis of an `[x, y, z]` register triple (infallible: the scale was
    /// checked).
    #[inline]
    pub fn apply(&self, raw: [i16; 3]) -> Vec3<T> {
        Vec3::new(
            self.reading(raw[0]),
            self.reading(raw[1]),
            self.reading(raw[2]),
        )
    }
}

impl RawScale<Q30> {
    /// The stored mantissa and shift (`lsb = mantissa · 2^−(shift + 30)`).
    #[inline]
    pub(crate) fn parts(&self) -> (i32, u32) {
        (self.scale.mantissa, self.scale.shift)
    }
}

/// The number formats a raw register is read into: f32, f64 and Q1.30 ([`Q30`]). Sealed.
pub trait RawFormat: Ring + sealed::Format {}

impl RawFormat for f32 {}
impl RawFormat for f64 {}
impl RawFormat for Q30 {}

pub(crate) mod sealed {
    use crate::real::Fixed;
    use crate::real::Q30;
    use crate::real::fixed::pow2_neg;
    use crate::real::wide::{mul_wide, round_shift, saturate};
    use crate::{Error, Real};

    /// How a format stores its LSB scale and applies it to one reading.
    pub trait Format: Sized {
        /// The stored scale.
        type Scale: Copy + core::fmt::Debug + PartialEq;
        /// The scale of `lsb` (checked).
        fn try_scale(lsb: f64) -> Result<Self::Scale, Error>;
        /// `raw · lsb` in the format (infallible for a checked scale).
        fn reading(scale: &Self::Scale, raw: i16) -> Self;
        /// The stored scale as an f64 (exact).
        fn lsb(scale: &Self::Scale) -> f64;
    }

    /// The floats: the LSB rounded to the type once; a reading is `raw · lsb`, one rounding.
    fn try_float_scale<T: Real>(lsb: f64) -> Result<T, Error> {
        if !lsb.is_finite() {
            return Err(Error::NonFinite);
        }
        let l = T::from_f64(lsb);
        if l <= T::ZERO || !(l * T::from_f64(32768.0)).is_finite() {
            return Err(Error::InvalidArgument);
        }
        Ok(l)
    }

    impl Format for f32 {
        type Scale = f32;
        fn try_scale(lsb: f64) -> Result<f32, Error> {
            try_float_scale(lsb)
        }
        #[inline(always)]
        fn reading(scale: &f32, raw: i16) -> f32 {
            f32::from(raw) * *scale
        }
        fn lsb(scale: &f32) -> f64 {
            f64::from(*scale)
        }
    }

    impl Format for f64 {
        type Scale = f64;
        fn try_scale(lsb: f64) -> Result<f64, Error> {
            try_float_scale(lsb)
        }
        #[inline(always)]
        fn reading(scale: &f64, raw: i16) -> f64 {
            f64::from(raw) * *scale
        }
        fn lsb(scale: &f64) -> f64 {
            *scale
        }
    }

    impl Format for Q30 {
        type Scale = FixedScale;
        fn try_scale(lsb: f64) -> Result<FixedScale, Error> {
            FixedScale::try_new(lsb)
        }
        #[inline(always)]
        fn reading(scale: &FixedScale, raw: i16) -> Q30 {
            scale.reading(raw)
        }
        fn lsb(scale: &FixedScale) -> f64 {
            scale.lsb()
        }
    }

    /// The Q1.30 scale: `lsb = mantissa · 2^−(shift + 30)`, `shift ∈ [15, 30]`.
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
    pub struct FixedScale {
        pub(crate) mantissa: i32,
        pub(crate) shift: u32,
    }

    impl FixedScale {
        fn try_new(rad_per_lsb: f64) -> Result<Self, Error> {
            let b = rad_per_lsb.to_bits();
            let exp = ((b >> 52) & 0x7FF) as i32;
            if exp == 0x7FF {
                return Err(Error::NonFinite);
            }
            if b >> 63 != 0 || rad_per_lsb == 0.0 {
                return Err(Error::InvalidArgument);
            }
            // x = M·2^(exp − 1075), M ∈ [2⁵², 2⁵³) (a subnormal x is far below the lower bound);
            // x·2³⁰ = round(M/2²²)·2^(exp − 1023) = m / 2^(1023 − exp).
            let big_m = ((b & ((1u64 << 52) - 1)) | (1u64 << 52)) as i64;
            let mut m = round_shift(big_m, 22);
            let mut shift = 1023 - exp;
            if m == 1 << 31 {
                m = 1 << 30;
                shift -= 1;
            }
            // x < 2⁻¹⁴ ⇔ shift ≥ 15; x ≥ 2⁻³⁰ ⇔ shift ≤ 30.
            if exp == 0 || !(15..=30).contains(&shift) {
                return Err(Error::OutOfRange);
            }
            Ok(Self {
                mantissa: m as i32,
                shift: shift as u32,
            })
        }

        fn lsb(&self) -> f64 {
            f64::from(self.mantissa) * pow2_neg(self.shift + 30)
        }

        #[inline(always)]
        fn reading(&self, raw: i16) -> Q30 {
            Fixed(saturate(round_shift(
                mul_wide(i32::from(raw), self.mantissa),
                self.shift,
            )))
        }
    }
}

impl IncrementQuantizer<30> {
    /// A raw `[x, y, z]` increment register triple in Q1.30 rad, scaled by `scale` (as
    /// [`RawScale::apply`]) with the remainder of the previous conversions added and the new
    /// remainder kept: the scaled reading `raw · m / 2^shift` is exact in units of 2⁻⁶¹
    /// (`|raw · m| < 2⁴⁶`, times `2^(31 − shift) ≤ 2¹⁶`), so a reading that repeats does not
    /// repeat its rounding. Infallible: the scale was checked so that no `i16` leaves the range
    /// (a remainder of half a unit at the range's edge saturates).
    pub fn quantize_raw(&mut self, scale: &RawScale<Q30>, raw: [i16; 3]) -> Vec3<Q30> {
        let k = QUANTIZER_WIDE - 30;
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

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    #[test]
    fn q30_scale_is_checked_once() {
        let s = RawScale::<Q30>::try_new(2f64.powi(-20)).unwrap();
        assert_eq!(s.lsb(), 2f64.powi(-20));
        assert_eq!(s.reading(1).to_bits(), 1 << 10);
        assert_eq!(s.reading(i16::MIN).to_bits(), -(1 << 25));
        let g = RawScale::<Q30>::try_new(1.0653e-6).unwrap();
        let want = 1.0653e-6 * 32767.0 * 2f64.powi(30);
        assert!(
            (f64::from(g.reading(32767).to_bits()) - want).abs() <= 0.5 + want * 2f64.powi(-31)
        );
        assert!((g.lsb() / 1.0653e-6 - 1.0).abs() < 2f64.powi(-30));
        assert_eq!(
            RawScale::<Q30>::try_new(2f64.powi(-14)),
            Err(Error::OutOfRange)
        );
        assert!(RawScale::<Q30>::try_new(2f64.powi(-14) * 0.999).is_ok());
        assert!(RawScale::<Q30>::try_new(2f64.powi(-30)).is_ok());
        assert_eq!(
            RawScale::<Q30>::try_new(2f64.powi(-31)),
            Err(Error::OutOfRange)
        );
        assert_eq!(RawScale::<Q30>::try_new(0.0), Err(Error::InvalidArgument));
        assert_eq!(RawScale::<Q30>::try_new(-1e-6), Err(Error::InvalidArgument));
        assert_eq!(RawScale::<Q30>::try_new(f64::NAN), Err(Error::NonFinite));
        // A scale that rounds (to 31 bits) up to 2⁻¹⁴ is rejected; the largest valid one keeps
        // every i16 inside Q1.30.
        assert_eq!(
            RawScale::<Q30>::try_new(2f64.powi(-14) * (1.0 - 2f64.powi(-40))),
            Err(Error::OutOfRange)
        );
        let top = RawScale::<Q30>::try_new(2f64.powi(-14) * (1.0 - 2f64.powi(-20))).unwrap();
        assert!(top.reading(i16::MIN) > Q30::MIN && top.reading(i16::MAX) < Q30::MAX);
        // A rate register: 0.061 °/s per LSB at 1 kHz.
        let r = RawScale::<Q30>::try_from_rate(0.061f64.to_radians(), 1e-3).unwrap();
        assert!((r.lsb() / (0.061f64.to_radians() * 1e-3) - 1.0).abs() < 1e-9);
    }

    #[test]
    fn raw_readings_keep_the_running_sum() {
        let scale = RawScale::<Q30>::try_new(1.0653e-6).unwrap();
        let exact = scale.lsb() * 2f64.powi(30); // units of 2⁻³⁰ per LSB
        let mut quant = IncrementQuantizer::<30>::new();
        let raw = [120i16, -4321, 7];
        let mut sum = [0i64; 3];
        let mut plain = [0i64; 3];
        for n in 1..=100_000i64 {
            let d = quant.quantize_raw(&scale, raw);
            let p = scale.apply(raw);
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
