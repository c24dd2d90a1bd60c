//! The exact exponential-map step for a body rate held constant over the step.
//!
//! A constant body rate `ω` held for `Δt` turns the body by the seed's Darboux whirl `R[Θ]`,
//! `Θ = ω Δt` (6.6.4), applied in the body frame: `q(t + Δt) = q(t) ⊗ exp(ω Δt)`. This is the
//! exact solution of `q̇ = ½ q ⊗ (0, ω)` for any `|ω| Δt`, including beyond π (the spinor then
//! keeps turning continuously: a 2π whirl gives `−q`, seed (6.6.6c)). The exponential is
//! [`UnitQuat::try_exp`], which uses a series for small angles: no division by a tiny angle and no
//! cutoff that returns the identity.

use crate::propagation::{ConingTerms, Normalization};
use crate::step_limit::exact_step_angle_limit;
use crate::rotation::ExpMap;
use crate::{Error, Real, UnitQuat, Vec3};

/// `q ⊗ exp(ω_body Δt)`: the exact attitude after a constant body rate held for `dt` (6.6.4).
///
/// A negative `dt` propagates backwards (the exact inverse step). The result is a product of
/// two unit quaternions, unit to about one ulp; renormalise periodically in a long loop (see
/// [`Normalization`]).
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite rate, step or attitude component;
/// [`Error::StepTooLong`] when the angle `|ω|·Δt` is beyond [`exact_step_angle_limit`] (its
/// rounding alone exceeds half a radian), including when it overflows the type.
///
/// ```
/// use gyrostat::{UnitQuat, Vec3};
/// use gyrostat::propagation::exponential::step_constant_rate;
/// // 1 rad/s about body z for π/2 s: a quarter turn.
/// let q = step_constant_rate(UnitQuat::IDENTITY, Vec3::new(0.0, 0.0, 1.0), core::f64::consts::FRAC_PI_2)?;
/// assert!((q.rotate(Vec3::X) - Vec3::Y).norm() < 1e-15);
/// # Ok::<(), gyrostat::Error>(())
/// ```
pub fn step_constant_rate<T: Real>(
    q: UnitQuat<T>,
    omega_body: Vec3<T>,
    dt: T,
) -> Result<UnitQuat<T>, Error> {
    if !dt.is_finite() || !q.as_quat().is_finite() {
        return Err(Error::NonFinite);
    }
    let phi = omega_body.try_finite()?.scale(dt);
    // ω finite and Δt finite can still overflow to ∞ in the product: then the square does too.
    let limit = exact_step_angle_limit::<T>();
    let within = phi.norm_squared() <= limit * limit;
    if !within {
        return Err(Error::StepTooLong);
    }
    Ok(q * UnitQuat::exp_unchecked(phi))
}

/// [`step_constant_rate`] without the checks, for an inner loop with validated input: the
/// update kernel [`apply_rotation_vector`] with `φ = ω Δt`, not renormalised. Domain: finite
/// `ω`, `Δt` with `|ω·Δt|` representable (a NaN or overflowing angle gives a NaN attitude).
#[inline]
pub fn step_constant_rate_unchecked<T: Real>(
    q: UnitQuat<T>,
    omega_body: Vec3<T>,
    dt: T,
) -> UnitQuat<T> {
    apply_rotation_vector(q, omega_body.scale(dt), Normalization::None)
}

/// The update kernel of every exponential-map rule: `q ⊗ exp(φ)` followed by the normalisation
/// policy, for a body-frame rotation vector `φ` accumulated over one update interval (by a coning
/// rule, the two-speed accumulator, Magnus-4 or CF4). Unchecked: a non-finite `φ` (or one whose
/// norm overflows) gives a non-finite attitude.
///
/// `φ` is a plain [`Vec3`] or, from a coning rule, its [`ConingTerms`] `sum + lever × last`
/// (see [`RotationVectorForm`]). For the floats both are `q * UnitQuat::exp_unchecked(φ)` (series
/// below the type's small-angle threshold). Fixed point fuses the product with the exponential
/// ([`UnitQuat::mul_exp`]: one rounding per component, the rotation increment carried 3 bits finer
/// than the format) and, for a coning rule, also forms the cross product exactly and adds it at
/// that finer resolution ([`UnitQuat::mul_exp_coning`]).
#[inline(always)]
pub fn apply_rotation_vector<T: ExpMap, P: RotationVectorForm<T>>(
    q: UnitQuat<T>,
    phi: P,
    norm: Normalization,
) -> UnitQuat<T> {
    norm.apply(phi.mul_exp_onto(q))
}

mod sealed {
    pub trait Sealed {}
}

/// The forms of a rotation vector `φ` that [`apply_rotation_vector`] takes: a plain [`Vec3`], or
/// a coning rule's [`ConingTerms`] (`φ = sum + lever × last`). Sealed.
pub trait RotationVectorForm<T: ExpMap>: Copy + sealed::Sealed {
    /// `q ⊗ exp(φ)`, not renormalised.
    fn mul_exp_onto(self, q: UnitQuat<T>) -> UnitQuat<T>;
}

impl<T> sealed::Sealed for Vec3<T> {}
impl<T> sealed::Sealed for ConingTerms<T> {}

/// [`UnitQuat::mul_exp_unchecked`].
impl<T: ExpMap> RotationVectorForm<T> for Vec3<T> {
    #[inline(always)]
    fn mul_exp_onto(self, q: UnitQuat<T>) -> UnitQuat<T> {
        q.mul_exp_unchecked(self)
    }
}

/// [`UnitQuat::mul_exp_coning_unchecked`].
impl<T: ExpMap> RotationVectorForm<T> for ConingTerms<T> {
    #[inline(always)]
    fn mul_exp_onto(self, q: UnitQuat<T>) -> UnitQuat<T> {
        q.mul_exp_coning_unchecked(self.sum, self.lever, self.last)
    }
}
