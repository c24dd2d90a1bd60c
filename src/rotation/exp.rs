//! The exponential and logarithm maps between rotation vectors and unit quaternions.
//!
//! `exp(φ) = (cos(|φ|/2), sin(|φ|/2)·φ/|φ|)`: the rotation by the angle `|φ|` about `φ̂`. The
//! rotation vector `φ` is the seed's whirl vector `Θ = Ω τ` (6.6.4): a constant body rate `Ω`
//! held for a time `τ` turns the body by `exp(Ω τ)`.
//!
//! Both maps switch to truncated Taylor series below a per-type threshold (associated consts:
//! [`Ring::EXP_SERIES_MAX_SQ`], [`Real::LOG_SERIES_MAX_SQ`]), so that no tiny angle is ever
//! divided by and the identity is approached smoothly (there is no cutoff that returns the
//! identity). The exponential map is generic over [`Ring`] (it runs in fixed point too); the
//! logarithm over [`Real`].

use crate::{Error, Quat, Real, Ring, UnitQuat, Vec3};

/// `(cos(θ/2), sin(θ/2)/θ)` for `θ² = theta_sq ≤` [`Ring::EXP_SERIES_MAX_SQ`], by the series
/// `cos(θ/2) = 1 − θ²/8 + θ⁴/384 − …`, `sin(θ/2)/θ = ½ − θ²/48 + θ⁴/3840 − …` truncated after
/// `θ⁴` (the threshold per type keeps the first dropped term below half a unit in the last
/// place). Each series is one [`Ring::dot`] of `(θ², θ⁴)` with the coefficients, added to its
/// constant term.
#[inline]
pub(crate) fn half_angle_series<T: Ring>(theta_sq: T) -> (T, T) {
    let t4 = theta_sq * theta_sq;
    let c = T::ONE + T::dot([theta_sq, t4], [T::ratio::<-1, 8>(), T::ratio::<1, 384>()]);
    let s = T::HALF
        + T::dot(
            [theta_sq, t4],
            [T::ratio::<-1, 48>(), T::ratio::<1, 3840>()],
        );
    (c, s)
}

/// The floats' [`Ring::exp_beyond_series`]: `sin`/`cos` of the half angle, and the overflow path.
#[inline]
pub(crate) fn exp_beyond_series_real<T: Real>(phi: Vec3<T>, n2: T) -> Quat<T> {
    if !n2.is_finite() {
        // |φ|² overflowed (|φ| ≳ 1e19 in f32, 1e154 in f64): take the angle with hypot and
        // scale by 1/|φ| instead (no tiny-angle issue at this size).
        let theta = phi.norm();
        let (s, c) = (theta * T::HALF).sin_cos();
        return Quat::from_parts(c, phi.scale(T::ONE / theta).scale(s));
    }
    let theta = n2.sqrt();
    let (s, c) = (theta * T::HALF).sin_cos();
    Quat::from_parts(c, phi.scale(s / theta))
}

impl<T: Ring> UnitQuat<T> {
    /// [`UnitQuat::exp`] without the finiteness check, for a hot loop whose input was validated
    /// upstream. A non-finite `φ` gives a non-finite result.
    ///
    /// Below [`Ring::EXP_SERIES_MAX_SQ`] (f32: 0.37 rad, f64: 0.013 rad, Q1.30: 1/8 rad) the
    /// series, no trigonometric call; beyond, [`Ring::exp_beyond_series`]. For fixed point this
    /// is the exponential map itself: total on every representable `φ`, integer arithmetic only
    /// (see [`crate::fixed`]).
    #[inline]
    pub fn exp_unchecked(phi: Vec3<T>) -> Self {
        let n2 = phi.norm_squared();
        if n2 <= T::EXP_SERIES_MAX_SQ {
            let (c, s) = half_angle_series(n2);
            Self::new_unchecked(Quat::from_parts(c, phi.scale(s)))
        } else {
            Self::new_unchecked(T::exp_beyond_series(phi, n2))
        }
    }
}

impl<T: Ring> UnitQuat<T> {
    /// `self ⊗ exp(φ)`: the attitude after the body-frame rotation vector `φ`, unchecked (see
    /// [`UnitQuat::exp_unchecked`]). Equal to `self * UnitQuat::exp_unchecked(phi)` for the
    /// floats; fused in fixed point ([`Ring::mul_exp`]): one rounding per component, with the
    /// small rotation increment carried at a finer resolution than the format.
    #[inline]
    pub fn mul_exp(self, phi: Vec3<T>) -> Self {
        Self::new_unchecked(T::mul_exp(self.into_quat(), phi))
    }

    /// `self ⊗ exp(φ)` for a coning rule's rotation vector `φ = sum + lever × last`
    /// ([`crate::propagation::ConingTerms`]). Equal to `self.mul_exp(terms.rotation_vector())`
    /// for the floats; in fixed point the coning term is formed exactly and kept at the fused
    /// exponential's finer resolution ([`Ring::mul_exp_coning`]).
    #[inline]
    pub fn mul_exp_coning(self, terms: crate::propagation::ConingTerms<T>) -> Self {
        Self::new_unchecked(T::mul_exp_coning(
            self.into_quat(),
            terms.sum,
            terms.lever,
            terms.last,
        ))
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

    /// The logarithm map onto rotation vectors of angle in `[0, π]`: the inverse of
    /// [`UnitQuat::exp`] on that range.
    ///
    /// This is an SO(3) view: `q` and `−q` give the same rotation vector (the sign is chosen so
    /// that `w ≥ 0`). The angle is `2·atan2(|v|, |w|)`, accurate at every angle including near 0
    /// and π; near 0 a series replaces `angle/|v|`.
    pub fn log(self) -> Vec3<T> {
        let q = *self.as_quat();
        let (w, v) = if q.w < T::ZERO {
            (-q.w, -q.vector())
        } else {
            (q.w, q.vector())
        };
        let s2 = v.norm_squared();
        // angle/|v| = 2·atan2(s, w)/s. Small-s series with w = √(1 − s²) (unit norm):
        // 2·asin(s)/s = 2·(1 + s²/6 + 3s⁴/40 + …), accurate below Real::LOG_SERIES_MAX_SQ.
        let factor = if s2 <= T::LOG_SERIES_MAX_SQ {
            T::TWO * (T::ONE + s2 * T::ratio::<1, 6>() + T::ratio::<3, 40>() * s2 * s2)
        } else {
            let s = s2.sqrt();
            T::TWO * s.atan2(w) / s
        };
        v.scale(factor)
    }

    /// The rotation angle in `[0, π]` (SO(3) view: `q` and `−q` give the same angle):
    /// `2·atan2(|v|, |w|)`.
    #[inline]
    pub fn angle(self) -> T {
        let q = self.as_quat();
        T::TWO * q.vector().norm().atan2(q.w.abs())
    }
}
