//! Attitude representations and the algebra of rotations.
//!
//! All types follow the [crate's conventions](crate#conventions-fixed-for-the-whole-crate).
//!
//! | type | what | seed |
//! |------|------|------|
//! | [`Quat`] | a general quaternion (no invariant) | |
//! | [`UnitQuat`] | the attitude; checked or explicit `_unchecked` constructors | (6.6.4) |
//! | [`Su2`] | the 2×2 complex unitary (spinor) view; its sign is physical | (6.6.3–4), (6.6.10) |
//! | [`Dcm`] | rotation matrix, orthonormality checked or enforced (polar iteration) | (6.6.1b), (6.6.14–15) |
//! | [`AxisAngle`] | unit axis and angle | (6.6.13) |
//! | [`PolarAxisAngle`] | the seed's axis angles `[φ, ϑ, Θ]` | (6.6.5) |
//! | [`RotationVector`] | the whirl vector `Θ = Ωτ` (exp/log with small-angle series) | (6.6.4) |
//! | [`Mrp`] | modified Rodrigues parameters, shadow-set switching to `|σ| ≤ 1` | |
//! | [`Gibbs`] | classical Rodrigues parameters; [`crate::Error::Singular`] at 180° | |
//! | [`Euler`] | Euler angles in any of the 24 conventions ([`EulerSequence`]) | (6.6.1a) = `ZYZ` |
//!
//! Every representation converts to and from [`UnitQuat`] (`From`/`Into`, or `try_` where the
//! conversion can fail), so any pair converts through it. Euler extraction
//! ([`UnitQuat::to_euler`]) works on the quaternion directly (Bernardes & Viollet 2022) and
//! reports gimbal lock ([`GimbalLock`], [`GimbalPolicy`]). Algebra on the double cover:
//! [`UnitQuat::canonical`] (SO(3) sign choice), composition (`*`, the U(2) product (6.6.10)),
//! inverse, [`UnitQuat::similarity_transform`] (6.6.8), [`UnitQuat::angle_to`] (geodesic
//! distance), [`UnitQuat::slerp`], [`UnitQuat::nlerp`]. Euler-rate kinematics for every
//! convention: [`Euler::rates_to_body_matrix`] and friends ((6.7.5c–f) for `ZYZ`); the Euler
//! momenta conjugate to the angles, [`Euler::body_to_euler_momenta_matrix`] and friends
//! ((6.7.10a–d) for `ZYZ`).
//!
//! # Accuracy contract
//! Enforced by the tests in `host-tests/tests/rotation/` against an independent f64
//! reference (rotation matrices built as products of elementary matrices). Errors are measured
//! as effects — the geodesic angle between the rotation a result represents and the exact one —
//! not as raw angles (at gimbal lock the angles are not unique, the rotation is).
//!
//! | conversion | f32 (inputs rounded to f32) | f64 |
//! |------------|-----|-----|
//! | quaternion → Euler → rotation, all 24 conventions, every distance from the pole incl. 0 | ≤ 1e-6 rad | ≤ 1e-14 rad |
//! | Euler → quaternion | ≤ 1e-6 rad | ≤ 1e-14 rad |
//! | rotation vector ↔ quaternion, MRP ↔ quaternion | ≤ 1e-6 rad | ≤ 1e-14 rad |
//! | slerp between attitudes 1e-3 rad apart at t = 0.3 | ≤ 1e-6 rad | ≤ 1e-14 rad |
//!
//! No conversion returns NaN or infinity for finite input (those that can be singular return
//! [`crate::Error::Singular`]).

mod axis_angle;
mod canonical;
mod dcm;
mod euler;
mod euler_momenta;
mod euler_rates;
mod exp;
mod gibbs;
mod mrp;
mod quat;
mod rotvec;
mod su2;
mod unit_quat;

pub use crate::linalg::Axis;
pub use axis_angle::{AxisAngle, PolarAxisAngle};
pub use dcm::Dcm;
pub use euler::{
    Euler, EulerSequence, EulerSolution, Frame, GIMBAL_LOCK_THRESHOLD, GimbalLock, GimbalPolicy,
    Pole, gimbal_lock_threshold,
};
pub use euler_rates::euler_rate_min_det;
pub use gibbs::Gibbs;
pub use mrp::Mrp;
pub use quat::Quat;
pub use rotvec::RotationVector;
pub use su2::Su2;
pub use unit_quat::UnitQuat;

pub use exp::ExpMap;
pub(crate) use exp::half_angle_series;
