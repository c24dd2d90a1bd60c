//! The exact exponential-map step for a body rate held constant over the step.
//!
//! A constant body rate `ω` held for `Δt` turns the body by the seed's Darboux whirl `R[Θ]`,
//! `Θ = ω Δt` (6.6.4), applied in the body frame: `q(t + Δt) = q(t) ⊗ exp(ω Δt)`. This is the
//! exact solution of `q̇ = ½ q ⊗ (0, ω)` for any `|ω| Δt`, including beyond π (the spinor then
//! keeps turning continuously: a 2π whirl gives `−q`, seed (6.6.6c)). The exponential is
//! [`UnitQuat::try_exp`], which uses a series for small angles: no division by a tiny angle and no
//! cutoff that returns the identity.

use crate::step_limit::exact_step_angle_limit;
use crate::{Error, Real, UnitQuat, Vec3};

#[cfg(doc)]
use crate::propagation::normalization::Normalization;

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
