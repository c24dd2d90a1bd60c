//! The exponential and logarithm maps between rotation vectors and unit quaternions.
//!
//! `exp(φ) = (cos(|φ|/2), sin(|φ|/2)·φ/|φ|)`: the rotation by the angle `|φ|` about `φ̂`. The
//! rotation vector `φ` is the seed's whirl vector `Θ = Ω τ` (6.6.4): a constant body rate `Ω`
//! held for a time `τ` turns the body by `exp(Ω τ)`.
//!
//! Both maps switch to truncated Taylor series below a per-type threshold, so that no tiny angle
//! is ever divided by and the identity is approached smoothly (there is no cutoff that returns
//! the identity).

use crate::{Error, Quat, Real, UnitQuat, Vec3};

/// Squared angle below which the series are used: the largest `θ²` for which the first dropped
/// term is below half an ulp of the result.
///
/// For `c(θ) = cos(θ/2) = 1 − θ²/8 + θ⁴/384 − θ⁶/46080 + …` and
/// `s(θ) = sin(θ/2)/θ = ½ − θ²/48 + θ⁴/3840 − θ⁶/645120 + …`, truncating after `θ⁴` leaves at
/// most `θ⁶/46080` (relative, for `c`). Requiring `θ⁶/46080 ≤ ε/2` gives `θ² ≤ (23040 ε)^{1/3}`;
/// the thresholds below are that bound rounded down: f32 (ε = 2⁻²³) `θ² ≤ 0.14` (θ ≤ 0.37 rad),
/// f64 (ε = 2⁻⁵²) `θ² ≤ 1.7e-4` (θ ≤ 0.013 rad). Types at least as precise as f64 (fixed point
/// with fewer than 33 fraction bits is less precise and takes the f32 value) use the f64 value.
#[inline]
pub(crate) fn series_threshold_sq<T: Real>() -> T {
    if T::EPSILON.to_f64() > 1e-10 {
        T::from_f64(0.14)
    } else {
        T::from_f64(1.7e-4)
    }
}

/// `(cos(θ/2), sin(θ/2)/θ)` for `θ² = theta_sq`, by series for small angles.
#[inline]
pub(crate) fn half_angle_cos_sinc<T: Real>(theta_sq: T) -> (T, T) {
    if theta_sq <= series_threshold_sq::<T>() {
        let t2 = theta_sq;
        let c = T::ONE - t2 / T::from_f64(8.0) + t2 * t2 / T::from_f64(384.0);
        let s = T::HALF - t2 / T::from_f64(48.0) + t2 * t2 / T::from_f64(3840.0);
        (c, s)
    } else {
        let theta = theta_sq.sqrt();
        // The reciprocal is formed while sin/cos are computed, not after them (a multiply
        // instead of a division at the end of the chain; one more rounding, ≤ 1 ulp).
        let inv = T::ONE / theta;
        let (s, c) = (theta * T::HALF).sin_cos();
        (c, s * inv)
    }
}

impl<T: Real> UnitQuat<T> {
    /// The exponential map: the rotation by `|φ|` about `φ̂`, `(cos(|φ|/2), sin(|φ|/2)·φ/|φ|)`.
    ///
    /// Valid for any angle, including beyond π (the result is then the spinor a continuous
    /// rotation through that angle reaches: `exp` of a 2π rotation vector is `−1`, seed
    /// (6.6.6c)). Small angles use a series (see the module docs): no division by a tiny angle.
    ///
    /// # Errors
    /// [`Error::NonFinite`] if a component of `φ` is NaN or infinite; [`Error::InvalidArgument`]
    /// if `|φ|` overflows (components near the type's maximum), where no angle is representable.
    ///
    /// ```
    /// use gyrostat::{UnitQuat, Vec3};
    /// let q = UnitQuat::exp(Vec3::new(0.0f64, 0.0, core::f64::consts::PI))?;
    /// assert!((q.z() - 1.0).abs() < 1e-15); // half-turn about z
    /// let tiny = UnitQuat::exp(Vec3::new(1e-30f32, 0.0, 0.0))?;
    /// assert_eq!(tiny.x(), 5e-31); // not snapped to the identity
    /// # Ok::<(), gyrostat::Error>(())
    /// ```
    #[inline]
    pub fn exp(phi: Vec3<T>) -> Result<Self, Error> {
        let phi = phi.try_finite()?;
        if !phi.norm_squared().is_finite() && !phi.norm().is_finite() {
            // |φ| itself overflows: the angle (mod 4π) is not representable.
            return Err(Error::InvalidArgument);
        }
        Ok(Self::exp_unchecked(phi))
    }

    /// [`UnitQuat::exp`] without the finiteness check, for a hot loop whose input was validated
    /// upstream. A non-finite `φ` gives a non-finite result.
    #[inline]
    pub fn exp_unchecked(phi: Vec3<T>) -> Self {
        let n2 = phi.norm_squared();
        if !n2.is_finite() {
            // |φ|² overflowed (|φ| ≳ 1e19 in f32, 1e154 in f64): take the angle with hypot and
            // scale by 1/|φ| instead (no tiny-angle issue at this size).
            let theta = phi.norm();
            let (s, c) = (theta * T::HALF).sin_cos();
            return Self::new_unchecked(Quat::from_parts(c, phi.scale(T::ONE / theta).scale(s)));
        }
        let (c, s) = half_angle_cos_sinc(n2);
        Self::new_unchecked(Quat::from_parts(c, phi.scale(s)))
    }

    /// The logarithm map onto rotation vectors of angle in `[0, π]`: the inverse of
    /// [`UnitQuat::exp`] on that range.
    ///
    /// This is an SO(3) view: `q` and `−q` give the same rotation vector (the sign is chosen so
    /// that `w ≥ 0`). The angle is `2·atan2(|v|, |w|)`, accurate at every angle including near 0
    /// and π; near 0 a series replaces `angle/|v|`.
    #[inline]
    pub fn log(self) -> Vec3<T> {
        let q = *self.as_quat();
        // For w < 0 the result of −q: |w| and the vector part times −1 (folded into the final
        // factor, a select rather than a branch on an unpredictable sign).
        let (w, v) = (q.w.abs(), q.vector());
        let sign = T::ONE.copysign(q.w);
        let s2 = v.norm_squared();
        // angle/|v| = 2·atan2(s, w)/s. Small-s series with w = √(1 − s²) (unit norm):
        // 2·asin(s)/s = 2·(1 + s²/6 + 3s⁴/40 + …); the dropped 15 s⁶/336 is below ε/2 for
        // s² ≤ 0.05 × series_threshold_sq (f32: s² ≤ 7e-3, 15s⁶/336 ≤ 1.5e-8; f64: s² ≤ 8.5e-6,
        // ≤ 2.7e-17).
        let factor = if s2 <= series_threshold_sq::<T>() * T::from_f64(0.05) {
            T::TWO * (T::ONE + s2 / T::from_f64(6.0) + T::from_f64(0.075) * s2 * s2)
        } else {
            let s = s2.sqrt();
            // 2/s formed while atan2 runs (see `half_angle_cos_sinc`).
            let two_inv = T::TWO / s;
            s.atan2(w) * two_inv
        };
        v.scale(factor * sign)
    }

    /// The rotation angle in `[0, π]` (SO(3) view: `q` and `−q` give the same angle):
    /// `2·atan2(|v|, |w|)`.
    #[inline]
    pub fn angle(self) -> T {
        let q = self.as_quat();
        T::TWO * q.vector().norm().atan2(q.w.abs())
    }
}
