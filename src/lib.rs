//! # gyrostat
//!
//! Attitude kinematics and rigid-body (gyrostat) dynamics for flight software and simulation:
//! `#![no_std]`, no allocation, no panicking paths, generic over f32 and f64 through two narrow
//! scalar traits ([`Ring`] below [`Real`]). The Q-format fixed-point type of [`fixed`] implements
//! [`Ring`], so that on FPU-less MCUs the attitude hot path (quaternion product, rotation,
//! exponential map, coning rules, renormalisation) runs in integer arithmetic, with the same bits
//! on every target.
//!
//! The physics follows W. G. Harter, *Unit 6: rigid and semi-rigid body rotation*; doc comments
//! cite its equation numbers, like `(6.6.4)`.
//!
//! ## Conventions (fixed for the whole crate)
//! - **Quaternion**: Hamilton convention (`i·j = k`); fields and all I/O are scalar-first
//!   `w, x, y, z`.
//! - **Attitude**: the attitude quaternion `q` maps body-frame vectors to the lab (inertial)
//!   frame: `v_lab = q ⊗ v_body ⊗ q*`. Its rotation matrix `R(q)` has the body axes as columns,
//!   in lab coordinates: the seed's active rotation `R(αβγ)` taking lab axes to body axes (6.6.1b).
//! - **SU(2)**: `q = (w, x, y, z)` is `U = w·1 − i(x·σx + y·σy + z·σz)`, the seed's
//!   `R[Θ] = cos(Θ/2)·1 − i·sin(Θ/2)·Θ̂·σ` (6.6.4). `q` and `−q` rotate vectors identically but are
//!   different spinors: a 2π rotation is `−1` in SU(2) (§6.6.b.1). SU(2) values are never silently
//!   sign-canonicalised; SO(3) views may be.
//! - **Angular velocity** `ω` is in the BODY frame unless a name says otherwise:
//!   `q̇ = ½ q ⊗ (0, ω_body) = ½ (0, ω_lab) ⊗ q`.
//! - **Exponential map**: `exp(φ) = (cos(|φ|/2), sin(|φ|/2)·φ/|φ|)`; the rotation vector `φ` is the
//!   seed's whirl vector `Θ = Ωτ`.
//! - **Euler angles**: uppercase (`ZYX`) is intrinsic, `R = R_Z(a) R_Y(b) R_X(c)`; lowercase (`zyx`)
//!   is extrinsic, `R = R_x(c) R_y(b) R_z(a)` — exactly scipy's `Rotation.from_euler`. The seed's
//!   `R(αβγ) = R_z(α) R_y(β) R_z(γ)` is intrinsic `ZYZ` (6.6.1a); aerospace yaw-pitch-roll is `ZYX`.
//! - **Inertia and momentum**: body-frame total angular momentum of a gyrostat is `J = I·ω + h`,
//!   `h` the sum of body-fixed rotor momenta; torque-free motion obeys `J̇ = J × ω` in the body frame
//!   with `ω = ∂H/∂J` (6.8.5, 6.9.2).
//! - Angles in radians, SI units, unless a name or type says otherwise.
//!
//! ## Data path
//! sensor samples or torques → a step function → [`UnitQuat`] (and body momentum) → conversions.
//! Every step is a small pure function over plain-data state, callable from an interrupt handler.
//!
//! ## Errors
//! Bad input gets a typed [`Error`]: non-finite numbers, zero-norm quaternions or axes, matrices
//! that are not rotations, singular configurations. Functions documented as infallible cannot
//! fail for any input that satisfies their type's invariant.
//!
//! ## Features
//! | feature     | what it adds |
//! |-------------|--------------|
//! | *(none)*    | everything; math from `libm`, except f32 `sin`/`cos` from gyrostat's own f32 kernel ([`real`]) |
//! | `micromath` | micromath's fast f32 `sin`/`cos`/`atan2`/`sqrt` instead of libm (see [`real`] for the measured errors) |
//! | `defmt`     | `defmt::Format` for the foundation types, [`Error`], the propagation types and the fixed-point types ([`interop`] lists them) |
//! | `nalgebra`  | `From`/`Into` nalgebra's `UnitQuaternion`, `Quaternion`, `Vector3`, `Matrix3` (no std) |
//! | `mint`      | `From`/`Into` mint's types, so glam, cgmath and others convert for free |
//!
//! Fixed point ([`fixed`]) needs no feature: it is plain integer code.
//!
//! ## Example
//! ```
//! use gyrostat::{UnitQuat, Vec3};
//! use core::f32::consts::FRAC_PI_2;
//!
//! // The body is yawed by 90° about the lab z axis.
//! let q = UnitQuat::try_from_axis_angle(Vec3::Z, FRAC_PI_2)?;
//! // Its body x axis points along lab y.
//! let x_body_in_lab = q.rotate(Vec3::X);
//! assert!((x_body_in_lab - Vec3::Y).norm() < 1e-6);
//! # Ok::<(), gyrostat::Error>(())
//! ```
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

mod compensated;
pub mod dynamics;
mod error;
pub mod estimation;
pub mod fixed;
pub mod interop;
pub mod linalg;
pub mod propagation;
pub mod real;
pub mod rotation;

pub use error::Error;

/// The README's Rust examples, compiled and run as doctests so that they stay true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
pub use linalg::{Axis, Complex, Mat3, Vec3};
pub use real::{Real, Ring};
pub use rotation::{
    AxisAngle, Dcm, Euler, EulerSequence, Gibbs, GimbalPolicy, Mrp, PolarAxisAngle, RotationVector,
};
pub use rotation::{Quat, Su2, UnitQuat};
