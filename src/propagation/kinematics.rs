//! Attitude kinematics: the quaternion differential equation and the rate between attitudes.
//!
//! With `q` mapping body vectors to the lab frame, a body rotating at the body-frame rate `ω`
//! (lab-frame rate `ω_lab = q ⊗ ω ⊗ q*`) has
//!
//! `q̇ = ½ q ⊗ (0, ω) = ½ (0, ω_lab) ⊗ q`,
//!
//! the quaternion form of the seed's whirl (6.6.4): over a short time `τ` at constant rate the
//! attitude turns by `R[Θ]` with `Θ = ω τ`, applied in the body frame (right factor) or in the
//! lab frame (left factor).

use crate::{Error, Quat, Real, UnitQuat, Vec3};

/// `q̇ = ½ q ⊗ (0, ω_body)`: the attitude rate for a BODY-frame angular velocity.
///
/// `q` need not be unit (an integrator's intermediate stage is not).
#[inline]
pub fn quat_rate_body<T: Real>(q: Quat<T>, omega_body: Vec3<T>) -> Quat<T> {
    (q * Quat::from_parts(T::ZERO, omega_body)).scale(T::HALF)
}

/// `q̇ = ½ (0, ω_lab) ⊗ q`: the attitude rate for a LAB-frame angular velocity.
#[inline]
pub fn quat_rate_lab<T: Real>(q: Quat<T>, omega_lab: Vec3<T>) -> Quat<T> {
    (Quat::from_parts(T::ZERO, omega_lab) * q).scale(T::HALF)
}

/// The body rate that produces `q_dot` at attitude `q`: `ω_body = 2·vec(q* ⊗ q̇)`, the inverse of
/// [`quat_rate_body`] (the scalar part of `q* ⊗ q̇` vanishes for a unit `q`).
#[inline]
pub fn body_rate_from_quat_rate<T: Real>(q: UnitQuat<T>, q_dot: Quat<T>) -> Vec3<T> {
    (q.as_quat().conjugate() * q_dot).vector().scale(T::TWO)
}

/// The constant BODY-frame rate that turns `q0` into `q1` in `dt`: `log(q0* ⊗ q1) / dt`.
///
/// This is the log map of the relative rotation, so it is exact for a constant rate (the inverse
/// of [`crate::propagation::exponential::step_constant_rate`]) and the mean rate over the step
/// otherwise. It is an SO(3) view: the relative rotation is taken as the shortest one (angle
/// ≤ π), so a body that really turned by more than π during `dt` is aliased (sample faster).
///
/// Domain: `dt` long enough for the rate to be representable (`dt` above about `π/MAX`; a
/// subnormal `dt` between distinct attitudes overflows the rate).
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite `dt` or attitude component; [`Error::InvalidArgument`]
/// for `dt ≤ 0` or a rate that overflows the type.
pub fn body_rate_between<T: Real>(
    q0: UnitQuat<T>,
    q1: UnitQuat<T>,
    dt: T,
) -> Result<Vec3<T>, Error> {
    check_dt(q0, q1, dt)?;
    rate((q0.inverse() * q1).log(), dt)
}

/// The constant LAB-frame rate that turns `q0` into `q1` in `dt`: `log(q1 ⊗ q0*) / dt`
/// (equal to `q0 ⊗ body_rate_between(q0, q1, dt) ⊗ q0*`). SO(3) view, as [`body_rate_between`].
///
/// # Errors
/// As [`body_rate_between`].
pub fn lab_rate_between<T: Real>(
    q0: UnitQuat<T>,
    q1: UnitQuat<T>,
    dt: T,
) -> Result<Vec3<T>, Error> {
    check_dt(q0, q1, dt)?;
    rate((q1 * q0.inverse()).log(), dt)
}

/// `φ/dt`, rejected with [`Error::InvalidArgument`] if it overflows (division, not a reciprocal:
/// `1/dt` overflows for a subnormal `dt` even when `φ/dt` is representable).
fn rate<T: Real>(phi: Vec3<T>, dt: T) -> Result<Vec3<T>, Error> {
    let w = phi / dt;
    if w.is_finite() {
        Ok(w)
    } else {
        Err(Error::InvalidArgument)
    }
}

fn check_dt<T: Real>(q0: UnitQuat<T>, q1: UnitQuat<T>, dt: T) -> Result<(), Error> {
    if !dt.is_finite() || !q0.as_quat().is_finite() || !q1.as_quat().is_finite() {
        return Err(Error::NonFinite);
    }
    if dt <= T::ZERO {
        return Err(Error::InvalidArgument);
    }
    Ok(())
}
