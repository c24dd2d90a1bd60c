//! The exponential and logarithm maps between rotation vectors and unit quaternions.
//!
//! `exp(φ) = (cos(|φ|/2), sin(|φ|/2)·φ/|φ|)`: the rotation by the angle `|φ|` about `φ̂`. The
//! rotation vector `φ` is the seed's whirl vector `Θ = Ω τ` (6.6.4): a constant body rate `Ω`
//! held for a time `τ` turns the body by `exp(Ω τ)`.
//!
//! Both maps switch to truncated Taylor series below a per-type threshold (associated consts:
//! [`Ring::EXP_SERIES_MAX_SQ`], [`Real::LOG_SERIES_MAX_SQ`]), so that no tiny angle is ever
//! divided by and the identity is approached smoothly (there is no cutoff that returns the
//! identity). The exponential map is generic over [`ExpMap`] (every float, and fixed point); the
//! logarithm over [`Real`].

use crate::{Error, Quat, Real, Ring, UnitQuat, Vec3};

/// The scalar types the exponential map runs on, with their per-type kernels: f32 and f64
/// (every [`Real`]) and the fixed-point [`crate::real::Fixed`].
///
/// The map itself, [`UnitQuat::exp_unchecked`], is one generic series below
/// [`Ring::EXP_SERIES_MAX_SQ`]; past it, and in the attitude update `q ⊗ exp(φ)`, each kind of
/// scalar has its own algorithm: the floats take `sin`/`cos` of the half angle, fixed point
/// halves the angle until the series applies and doubles back, and fuses the product with the
/// exponential so that the small rotation increment is never rounded to the format's step (see
/// [`crate::fixed`]). These kernels belong to the rotation layer, which owns quaternions, and
/// not to the scalar traits below it, which know nothing of vectors: hence a trait of its own,
/// implemented here for every [`Real`] and in `fixed/exp.rs` for fixed point.
///
/// Every [`Real`] implements it, so code generic over [`Real`] uses the exponential map without
/// naming this trait; code generic over [`Ring`] that calls the map (the increment path of
/// [`crate::propagation`]) is generic over `ExpMap` instead. Only gyrostat's scalar types can
/// implement it ([`Ring`] is sealed).
pub trait ExpMap: Ring {
    /// The exponential map `exp(φ) = (cos(θ/2), sin(θ/2)·φ/θ)`, `θ = |φ|`, for
    /// `theta_sq = |φ|² >` [`Ring::EXP_SERIES_MAX_SQ`] (or not finite): the part of
    /// [`UnitQuat::exp_unchecked`] past its series.
    fn exp_beyond_series(phi: Vec3<Self>, theta_sq: Self) -> Quat<Self>;

    /// `q ⊗ exp(φ)`: the attitude update by a body-frame rotation vector, the step of every
    /// increment integrator (`UnitQuat::mul_exp_unchecked` of
    /// [`crate::propagation`]).
    ///
    /// The floats form `exp(φ)` and multiply. Fixed point fuses the two on the series domain:
    /// `sin(θ/2)/θ·φ`, a small vector, is kept with 3 more fraction bits than the format, and each
    /// component of the product is summed in 64 bits and rounded once, so that the rotation
    /// increment itself is never rounded to the format's resolution (a constant rate would
    /// otherwise integrate that rounding linearly).
    // Always inlined: with the estimator's 4th-order rate rules as more callers, the compiler
    // left the float version out of line, and the call cost the light estimator 560
    // instructions per update on a Cortex-M0 (39 634 → 40 193, past its 40 000 budget;
    // `fw_icount_estimation`).
    #[inline(always)]
    fn mul_exp(q: Quat<Self>, phi: Vec3<Self>) -> Quat<Self> {
        q * *UnitQuat::exp_unchecked(phi).as_quat()
    }

    /// `q ⊗ exp(sum + lever × last)`: the attitude update of a coning rule
    /// (`UnitQuat::mul_exp_unchecked` of [`crate::propagation`] given its `ConingTerms`). The floats form the rotation vector and call
    /// [`ExpMap::mul_exp`]; fixed point forms the cross product exactly and adds it to the sum at
    /// the finer resolution of its fused exponential, so that the small coning term is rounded to
    /// 2^−(F+3), not to the format's step.
    #[inline]
    fn mul_exp_coning(
        q: Quat<Self>,
        sum: Vec3<Self>,
        lever: Vec3<Self>,
        last: Vec3<Self>,
    ) -> Quat<Self> {
        Self::mul_exp(q, sum + lever.cross(last))
    }
}

/// The floats: `sin`/`cos` of the half angle past the series.
impl<T: Real> ExpMap for T {
    #[inline]
    fn exp_beyond_series(phi: Vec3<T>, theta_sq: T) -> Quat<T> {
        exp_beyond_series_real(phi, theta_sq)
    }
}

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

/// The floats' [`ExpMap::exp_beyond_series`]: `sin`/`cos` of the half angle, and the overflow path.
#[inline]
fn exp_beyond_series_real<T: Real>(phi: Vec3<T>, n2: T) -> Quat<T> {
    if !n2.is_finite() {
        // |φ|² overflowed (|φ| ≳ 1e19 in f32, 1e154 in f64): take the angle with hypot and
        // scale by 1/|φ| instead (no tiny-angle issue at this size).
        let theta = phi.norm();
        let (s, c) = (theta * T::HALF).sin_cos();
        return Quat::from_parts(c, phi.scale(T::ONE / theta).scale(s));
    }
    let theta = n2.sqrt();
    // The reciprocal is formed while sin/cos are computed, not after them (a multiply instead of
    // a division at the end of the chain; one more rounding, ≤ 1 ulp).
    let inv = T::ONE / theta;
    let (s, c) = (theta * T::HALF).sin_cos();
    Quat::from_parts(c, phi.scale(s * inv))
}

impl<T: ExpMap> UnitQuat<T> {
    /// [`UnitQuat::try_exp`] without the finiteness check, for a hot loop whose input was validated
    /// upstream. A non-finite `φ` gives a non-finite result.
    ///
    /// Below [`Ring::EXP_SERIES_MAX_SQ`] (f32: 0.37 rad, f64: 0.013 rad, Q1.30: 1/8 rad) the
    /// series, no trigonometric call; beyond, [`ExpMap::exp_beyond_series`]. For fixed point this
    /// is the exponential map itself: total on every representable `φ`, integer arithmetic only
    /// (see [`crate::fixed`]).
    #[inline(always)]
    pub fn exp_unchecked(phi: Vec3<T>) -> Self {
        Self::exp_unchecked_sq(phi, phi.norm_squared())
    }

    /// [`UnitQuat::exp_unchecked`] given `n2 = |φ|²` as `phi.norm_squared()` forms it (the
    /// same bits; a caller that formed it saves the products).
    #[inline(always)]
    pub(crate) fn exp_unchecked_sq(phi: Vec3<T>, n2: T) -> Self {
        if n2 <= T::EXP_SERIES_MAX_SQ {
            let (c, s) = half_angle_series(n2);
            Self::new_unchecked(Quat::from_parts(c, phi.scale(s)))
        } else {
            Self::new_unchecked(T::exp_beyond_series(phi, n2))
        }
    }
}

impl<T: ExpMap> UnitQuat<T> {
    /// `self ⊗ exp(φ)`, not renormalised: [`ExpMap::mul_exp`] on the attitude (the plain update
    /// behind `UnitQuat::mul_exp_unchecked` of [`crate::propagation`]).
    #[inline]
    pub(crate) fn mul_exp_plain(self, phi: Vec3<T>) -> Self {
        Self::new_unchecked(T::mul_exp(self.into_quat(), phi))
    }

    /// `self ⊗ exp(sum + lever × last)`, not renormalised: [`ExpMap::mul_exp_coning`].
    #[inline]
    pub(crate) fn mul_exp_coning_plain(self, sum: Vec3<T>, lever: Vec3<T>, last: Vec3<T>) -> Self {
        Self::new_unchecked(T::mul_exp_coning(self.into_quat(), sum, lever, last))
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
    /// let q = UnitQuat::try_exp(Vec3::new(0.0f64, 0.0, core::f64::consts::PI))?;
    /// assert!((q.z() - 1.0).abs() < 1e-15); // half-turn about z
    /// let tiny = UnitQuat::try_exp(Vec3::new(1e-30f32, 0.0, 0.0))?;
    /// assert_eq!(tiny.x(), 5e-31); // not snapped to the identity
    /// # Ok::<(), gyrostat::Error>(())
    /// ```
    #[inline]
    pub fn try_exp(phi: Vec3<T>) -> Result<Self, Error> {
        let phi = phi.try_finite()?;
        if !phi.norm_squared().is_finite() && !phi.norm().is_finite() {
            // |φ| itself overflows: the angle (mod 4π) is not representable.
            return Err(Error::InvalidArgument);
        }
        Ok(Self::exp_unchecked(phi))
    }

    /// The logarithm map onto rotation vectors of angle in `[0, π]`: the inverse of
    /// [`UnitQuat::try_exp`] on that range.
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
        // 2·asin(s)/s = 2·(1 + s²/6 + 3s⁴/40 + …), accurate below Real::LOG_SERIES_MAX_SQ.
        let factor = if s2 <= T::LOG_SERIES_MAX_SQ {
            T::TWO * (T::ONE + s2 * T::ratio::<1, 6>() + T::ratio::<3, 40>() * s2 * s2)
        } else {
            let s = s2.sqrt();
            // 2/s formed while atan2 runs (see `exp_beyond_series_real`).
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
