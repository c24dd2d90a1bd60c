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
//! # Tasks
//! The jobs a user comes for, each with the API that does it and the shortest correct example
//! (every block below is compiled and run as a test).
//!
//! | job | API |
//! |---|---|
//! | [strapdown attitude from gyro increments, in f32](#strapdown-attitude-from-gyro-increments-in-f32) | [`propagation::IncrementIntegrator`], [`propagation::ConingRule`], [`propagation::CompensatedAttitude`] |
//! | [attitude from rate samples](#attitude-from-rate-samples) | [`propagation::RateIntegrator`], [`propagation::RateMethod`] |
//! | [fixed point on a Cortex-M0](#fixed-point-on-a-cortex-m0) | [`real::Q30`], [`sensor::RawScale`], [`fixed::IncrementQuantizer`], [`propagation::CarriedAttitude`] |
//! | [Euler angles, with gimbal lock](#euler-angles-with-gimbal-lock) | [`UnitQuat::to_euler`], [`rotation::EulerSequence`], [`rotation::GimbalPolicy`] |
//! | [a gyrostat with a reaction wheel](#a-gyrostat-with-a-reaction-wheel) | [`dynamics::Gyrostat::with_wheels`], [`dynamics::Gyrostat::step_with`], [`dynamics::Control`] |
//! | [a real sensor stream: timestamps, calibration, mounting](#a-real-sensor-stream-timestamps-calibration-mounting) | [`sensor::SampleClock`], [`sensor::MicrosClock`], [`sensor::InertialCalibration`], [`sensor::AxisRemap`], [`sensor::ClipGuard`], [`propagation::kernels::coning2_update_unequal`], [`propagation::kernels::magnus4_step_unequal`] |
//! | [attitude and gyro bias from an IMU](#attitude-and-gyro-bias-from-an-imu) | [`estimation::Estimator`], [`estimation::Params`], [`estimation::Outcome`] |
//! | [converting an attitude log](#converting-an-attitude-log) | [`Quat::try_normalize`], [`UnitQuat::to_euler_angles`], [`RotationVector`], [`Dcm`] |
//!
//! ## Strapdown attitude from gyro increments, in f32
//! A rate-integrating gyro delivers increments `Δθ` (rad, body frame). An
//! [`IncrementIntegrator`](propagation::IncrementIntegrator) checks each one and updates the
//! attitude with a coning rule; started from a
//! [`CompensatedAttitude`](propagation::CompensatedAttitude) it carries the f32 rounding errors,
//! so the attitude does not drift from rounding over hours (start it from a plain `UnitQuat` for
//! short runs).
//! ```
//! use gyrostat::propagation::{CompensatedAttitude, ConingRule, IncrementIntegrator, Normalization};
//! use gyrostat::{UnitQuat, Vec3};
//!
//! let start = CompensatedAttitude::new(UnitQuat::<f32>::IDENTITY);
//! let mut imu = IncrementIntegrator::new(start, ConingRule::TwoSample, Normalization::Fast);
//! for _ in 0..1000 {
//!     imu.push(Vec3::new(0.0, 0.0, 1e-3))?; // 1 mrad about body z per sample
//! }
//! let q = imu.attitude(); // 1 rad about z
//! assert!((q.rotate(Vec3::X) - Vec3::new(1.0f32.cos(), 1.0f32.sin(), 0.0)).norm() < 1e-6);
//! # Ok::<(), gyrostat::Error>(())
//! ```
//!
//! ## Attitude from rate samples
//! A MEMS gyro's FIFO delivers rates `ω(k·dt)` (rad/s, body frame). A
//! [`RateIntegrator`](propagation::RateIntegrator) integrates them to fourth order (Magnus-4, CF4
//! or RK4 between the samples' cubic interpolant) and returns the attitude at each sample time.
//! ```
//! use gyrostat::propagation::{Normalization, RateIntegrator, RateMethod};
//! use gyrostat::{UnitQuat, Vec3};
//!
//! let dt = 1e-3; // 1 kHz
//! let mut imu = RateIntegrator::try_new(UnitQuat::IDENTITY, RateMethod::Magnus4, Normalization::Fast, dt)?;
//! for _ in 0..=1000 {
//!     for _q in imu.push(Vec3::new(0.5f64, 0.0, 0.0))? {} // the attitudes newly reached
//! }
//! // 1000 intervals of 1 ms at 0.5 rad/s about x: 0.5 rad.
//! assert!((imu.attitude().angle() - 0.5).abs() < 1e-12);
//! # Ok::<(), gyrostat::Error>(())
//! ```
//!
//! ## Fixed point on a Cortex-M0
//! With no FPU, run the update in Q1.30 ([`fixed`]): the same generic functions take
//! [`real::Q30`] instead of `f32`, in integer arithmetic only and with the same bits on every
//! target. Raw sensor registers become Q1.30 increments through a scale checked once, with the
//! rounding remainder carried from one reading to the next ([`fixed::IncrementQuantizer`]); the
//! attitude is a [`propagation::CarriedAttitude`], which carries the low bits its roundings discard
//! into the next update, so that neither drifts from rounding (the plain `UnitQuat<Q30>` with
//! [`propagation::kernels::coning2_update`] does: see the [`fixed`] docs, "Rounding bias").
//! ```
//! use gyrostat::fixed::IncrementQuantizer;
//! use gyrostat::propagation::CarriedAttitude;
//! use gyrostat::real::Q30;
//! use gyrostat::sensor::RawScale;
//! use gyrostat::UnitQuat;
//!
//! let scale = RawScale::<Q30>::try_new(1.0653e-6)?; // the gyro's rad per LSB, checked once
//! let mut quant = IncrementQuantizer::new();
//! let mut q = CarriedAttitude::new(UnitQuat::IDENTITY);
//! let (r1, r2) = ([120i16, -40, 7], [118i16, -43, 9]); // two raw increment readings
//! q = q.coning2_update(quant.quantize_raw(&scale, r1), quant.quantize_raw(&scale, r2));
//! let _bits = q.attitude().to_bits(); // log these: a ground tool reproduces them exactly
//! assert!(q.attitude().to_f64().angle() < 3e-4);
//! # Ok::<(), gyrostat::Error>(())
//! ```
//!
//! ## Euler angles, with gimbal lock
//! [`UnitQuat::to_euler`] extracts the angles of any of the 24 conventions (uppercase intrinsic,
//! lowercase extrinsic, as scipy) and reports a gimbal lock instead of hiding it: there only a
//! combination of the outer angles is determined, and a [`rotation::GimbalPolicy`] chooses the
//! split.
//! ```
//! use gyrostat::rotation::{EulerSequence, GimbalPolicy};
//! use gyrostat::{UnitQuat, Vec3};
//! use core::f64::consts::FRAC_PI_2;
//!
//! let pitched_up = UnitQuat::try_from_axis_angle(Vec3::Y, FRAC_PI_2)?;
//! let sol = pitched_up.to_euler(EulerSequence::ZYX, GimbalPolicy::ZeroThird);
//! let [yaw, pitch, roll] = sol.euler.angles;
//! assert!((pitch - FRAC_PI_2).abs() < 1e-15 && roll == 0.0);
//! let lock = sol.singularity.expect("pitch ±90° is the ZYX gimbal lock");
//! assert!((lock.combined_angle - yaw).abs() < 1e-15); // yaw − roll is all that is determined
//! # Ok::<(), gyrostat::Error>(())
//! ```
//!
//! ## A gyrostat with a reaction wheel
//! A body with wheels is a [`Gyrostat`](dynamics::Gyrostat); its [`State`](dynamics::State)
//! holds the attitude, the total body momentum `J` and the wheel speeds. A wheel torque is
//! internal: it trades momentum between wheel and body and leaves `|J|` unchanged.
//! ```
//! use gyrostat::dynamics::{Control, Gyrostat, Inertia, Integrator, Wheel};
//! use gyrostat::{UnitQuat, Vec3};
//!
//! let inertia = Inertia::try_from_principal(Vec3::new(6.0, 4.0, 3.0))?; // wheels locked
//! let body = Gyrostat::with_wheels(inertia, [Wheel::try_new(Vec3::Y, 0.05)?]);
//! let mut s = body.try_state_from_omega(UnitQuat::IDENTITY, Vec3::new(0.05, 1.0, 0.01), [60.0])?;
//! let spin_down = Control { torque: Vec3::ZERO, wheel_torques: [-0.015] }; // held, N·m
//! let j0 = s.momentum.norm();
//! for k in 0..1000 {
//!     s = body.step_with(Integrator::Yoshida4, &s, k as f64 * 0.01, 0.01, spin_down)?;
//! }
//! assert!((s.wheel_speeds[0] - 57.0).abs() < 1e-9); // 60 − 0.015/0.05 · 10 s
//! assert!((s.momentum.norm() - j0).abs() < 1e-12);
//! # Ok::<(), gyrostat::Error>(())
//! ```
//!
//! ## A real sensor stream: timestamps, calibration, mounting
//! Real samples jitter, drop and clip, and the sensor is neither calibrated nor aligned with the
//! body. [`sensor`] turns each sample into what the core needs: the interval from its timestamp
//! (a gap, a repeated or a backwards timestamp is a typed [`sensor::Interval`], never a silent
//! jump), the calibration `K·(raw − b·Δt)`, the mounting remap; the 2-sample rule for unequal
//! intervals then uses the coefficient `(h₁ + h₂)²/(6 h₁ h₂)` (⅔ when equal).
//! ```
//! use gyrostat::propagation::coning::two_sample_unequal_coefficient;
//! use gyrostat::propagation::kernels::coning2_update_unequal;
//! use gyrostat::sensor::{AxisRemap, InertialCalibration, Interval, SampleClock};
//! use gyrostat::{Mat3, UnitQuat, Vec3};
//!
//! let cal = InertialCalibration::try_new(Mat3::IDENTITY, Vec3::new(1.0, 1.0, 1.0), Vec3::new(0.01, 0.0, 0.0))?;
//! let remap = AxisRemap::try_parse("x,-z,y")?; // body y = −sensor z
//! let mut clock = SampleClock::try_new(0.01)?; // 100 Hz nominal, a gap beyond 50 ms
//! clock.restart(Some(0.0));
//! let mut q = UnitQuat::<f64>::IDENTITY;
//! let mut pending = None;
//! // 1 rad/s about sensor x read with a +0.01 rad/s bias, over 9.8 ms then 10.5 ms.
//! for (t, raw) in [(0.0098, [0.009_898, 0.0, 0.0]), (0.0203, [0.010_605, 0.0, 0.0])] {
//!     let Interval::Step(h) = clock.interval(t)? else {
//!         continue; // a gap, a repeat or a backwards step: see sensor::timing's policy
//!     };
//!     let d = remap.apply(cal.apply_increment(Vec3::from_array(raw), h));
//!     match pending.take() {
//!         None => pending = Some((d, h)),
//!         Some((d1, h1)) => {
//!             q = coning2_update_unequal(q, d1, d, two_sample_unequal_coefficient(h1, h));
//!         }
//!     }
//! }
//! // The bias removed: 0.0203 rad about body x.
//! assert!((q.angle() - 0.0203).abs() < 1e-9);
//! # Ok::<(), gyrostat::Error>(())
//! ```
//!
//! ## Attitude and gyro bias from an IMU
//! A gyroscope, an accelerometer and (optionally) a magnetometer sampled together: an
//! [`Estimator`](estimation::Estimator) propagates the attitude with the bias-corrected rate and
//! corrects it with gravity (inclination) and the field (heading only), estimating the gyroscope
//! bias online ([`estimation`]: the filter, its parameters and its handling of disturbed or bad
//! samples). The first sample sets the attitude; the frame is ENU (x east, y magnetic north).
//! ```
//! use gyrostat::estimation::{Estimator, Params};
//! use gyrostat::Vec3;
//!
//! let mut f = Estimator::<f32>::try_new(Params::default())?;
//! let bias = Vec3::new(0.01, -0.005, 0.002); // rad/s
//! // A sensor lying still for 20 s at 100 Hz: the gyroscope reads its bias alone.
//! let (gravity, field) = (Vec3::new(0.0, 0.0, 9.81), Vec3::new(0.0, 15.8, -40.7));
//! let mut at_rest = false;
//! for _ in 0..2000 {
//!     at_rest = f.update_9d(bias, gravity, field, 0.01)?.at_rest;
//! }
//! assert!(at_rest); // the rest detector saw it
//! assert!((f.bias() - bias).norm() < 1e-3); // learnt at rest
//! assert!(f.attitude().angle() < 1e-2); // sensor axes = ENU
//! # Ok::<(), gyrostat::Error>(())
//! ```
//!
//! ## Converting an attitude log
//! Every representation converts to and from [`UnitQuat`] (`From`, or `TryFrom` and a `try_`
//! method where the conversion can fail). A bad row becomes an [`Error`], never a NaN. (The
//! `convert` command-line tool does this for CSV files.)
//! ```
//! use gyrostat::rotation::EulerSequence;
//! use gyrostat::{Dcm, Quat, RotationVector};
//!
//! // Rows in scipy's order x, y, z, w (gyrostat is scalar-first).
//! let log = [[0.0, 0.0, 0.382_683_432, 0.923_879_533], [0.0, 0.0, 0.0, 0.0]];
//! for [x, y, z, w] in log {
//!     let Ok(q) = Quat::new(w, x, y, z).try_normalize() else {
//!         continue; // the zero row: Error::ZeroNorm
//!     };
//!     let [yaw, _pitch, _roll] = q.to_euler_angles(EulerSequence::ZYX).map(f64::to_degrees);
//!     let phi = RotationVector::from(q).vector(); // rad
//!     let r = Dcm::from(q).into_matrix(); // body axes as columns
//!     assert!((yaw - 45.0).abs() < 1e-6 && (phi.z - core::f64::consts::FRAC_PI_4).abs() < 1e-8);
//!     assert!((r.col(0).y - yaw.to_radians().sin()).abs() < 1e-8);
//! }
//! ```
//!
//! # Conventions (fixed for the whole crate)
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
//! # Names
//! One rule throughout the crate:
//! - **`try_`**: a constructor or conversion that can fail returns `Result<_, Error>` and is
//!   named `try_…`: [`UnitQuat::try_new`], [`UnitQuat::try_exp`],
//!   [`Dcm::try_from_matrix_orthonormalized`], [`rotation::EulerSequence::try_new`],
//!   [`propagation::RateIntegrator::try_new`], [`Gibbs::try_from_unit_quat`],
//!   [`Euler::try_to_unit_quat`]. Infallible ones carry no prefix ([`Gibbs::to_unit_quat`],
//!   [`propagation::IncrementIntegrator::new`]).
//! - **`_unchecked`**, or a **`kernels`** module: a function that skips validation, for a hot
//!   loop whose input was checked upstream, says so: [`UnitQuat::new_unchecked`],
//!   [`UnitQuat::exp_unchecked`], [`UnitQuat::mul_exp_unchecked`],
//!   [`Euler::to_unit_quat_unchecked`], and every function of [`propagation::kernels`]
//!   ([`coning2_update`](propagation::kernels::coning2_update),
//!   [`magnus4_step`](propagation::kernels::magnus4_step),
//!   [`rk4_step`](propagation::kernels::rk4_step), ...). Where both exist, the checked one is
//!   the `try_` name or the checked entry point (a `push`, a `step`).
//! - **Computations and steps** that can fail (a step, a `push`, a special function, a closed
//!   form) return `Result` under the name of what they compute ([`dynamics::Gyrostat::step`],
//!   [`propagation::IncrementIntegrator::push`],
//!   [`dynamics::closed_form::elliptic::complete_k`]); their `# Errors` section says when.
//! - **One name per conversion**: `X::from_unit_quat` and `X::to_unit_quat` (with `try_` where
//!   they can fail) beside the `From`/`TryFrom` impls; one type per quantity
//!   ([`rotation::AxisAngle::to_rotation_vector`] returns a [`RotationVector`]).
//! - **One name for `q ⊗ exp(φ)`** on every attitude type: `mul_exp_unchecked(φ, norm)` (the
//!   update, then the [`propagation::Normalization`] policy) and the checked
//!   `try_mul_exp(φ, norm)`, on [`UnitQuat`], [`propagation::CompensatedAttitude`] and
//!   [`propagation::CarriedAttitude`]; `φ` a vector, a coning rule's terms or a compensated pair
//!   ([`propagation::RotationVectorForm`]).
//! - Fixed point and the compensated f32 attitude use the float path's names
//!   ([`real::Fixed`] is a [`Ring`]; [`propagation::CompensatedAttitude`] is given to the same
//!   integrators as a `UnitQuat`).
//!
//! # Layers
//! Every module depends only on the layers above it in this table, and on exactly the layers its
//! row lists (a host test, `layer_table` in `src/lib.rs`, reads this table and every module's
//! `crate::` paths and fails when they disagree). The crate's [`Error`] is used by every layer.
//!
//! | layer | modules | contents | depends on |
//! |---|---|---|---|
//! | scalars | [`real`] | [`Ring`], [`Real`], their f32/f64 implementations and the fixed-point number [`real::Fixed`] ([`real::Q30`], [`real::Q24`]) | nothing |
//! | linear algebra | [`linalg`] | [`Vec3`], [`Mat3`], [`Complex`], [`Axis`] | scalars |
//! | rotations | [`rotation`] | [`Quat`], [`UnitQuat`] and every representation; the exponential map ([`ExpMap`]) | scalars, linear algebra |
//! | compensated arithmetic | `error_free` (private) | error-free sums and products, the compensated rotation update | scalars, linear algebra, rotations |
//! | step limits | [`step_limit`] | the validity limit of a step, shared by the two layers below | scalars, linear algebra |
//! | propagation | [`propagation`] | rules and interpolation, then the [`propagation::kernels`], the compensated (f32/f64) and carried (fixed-point) attitudes, the attitude trait, the integrators | scalars, linear algebra, rotations, compensated arithmetic, step limits |
//! | dynamics | [`dynamics`] | the body (inertia, Hamiltonian, gyrostat, state), the [`dynamics::integrators`] and the [`dynamics::closed_form`] on it, the step on the integrators | scalars, linear algebra, rotations, compensated arithmetic, step limits |
//! | fixed point | [`fixed`] | the fixed-point formats' documentation and conversions, the raw increment scale and quantizer, Q1.30's exponential map | scalars, linear algebra, rotations |
//! | sensor streams | [`sensor`] | timestamps and gap policy, calibration, mounting, raw registers and clipping, in f32, f64 and Q1.30, before the propagation core | scalars, linear algebra, rotations, fixed point |
//! | estimation | [`estimation`] | the attitude and gyro-bias estimator: initialisation, covariance, rest detector, field monitor, the filter | scalars, linear algebra, rotations, step limits, propagation, sensor streams |
//! | integrations | `interop` (private; the features below) | conversions to and from nalgebra and mint, `defmt::Format` | scalars, linear algebra, rotations |
//!
//! # Data path
//! sensor samples or torques → a step function → [`UnitQuat`] (and body momentum) → conversions.
//! Every step is a small pure function over plain-data state, callable from an interrupt handler.
//!
//! # Errors
//! Bad input gets a typed [`Error`]: non-finite numbers, zero-norm quaternions or axes, matrices
//! that are not rotations, singular configurations, steps beyond their method's validity.
//! Functions documented as infallible cannot fail for any input that satisfies their type's
//! invariant.
//!
//! # Features
//! | feature     | what it adds |
//! |-------------|--------------|
//! | *(none)*    | everything; math from `libm`, except f32 `sin`/`cos` from gyrostat's own f32 kernel ([`real`]) |
//! | `micromath` | micromath's fast f32 `sin`/`cos`/`atan2`/`sqrt` instead of libm (see [`real`] for the measured errors) |
//! | `defmt`     | `defmt::Format` for the foundation types ([`Vec3`], [`Mat3`], [`Complex`], [`Quat`], [`UnitQuat`], [`Su2`]), [`Error`], the propagation types ([`propagation::ConingRule`], [`propagation::Normalization`], [`propagation::RateMethod`], [`propagation::IncrementIntegrator`], [`propagation::ConingAccumulator`], [`propagation::RateIntegrator`]) and the fixed-point types ([`real::Fixed`], [`sensor::RawScale`], [`propagation::CarriedAttitude`]), the sensor clocks, calibrations and clipping types ([`sensor::SampleClock`], [`sensor::MicrosClock`], [`sensor::Interval`], [`sensor::InertialCalibration`], [`sensor::MagnetometerCalibration`], [`sensor::ClipGuard`], …); not [`sensor::AxisRemap`], [`sensor::Mounting`], the other rotation representations nor the dynamics types |
//! | `nalgebra`  | `From`/`Into` nalgebra's `UnitQuaternion`, `Quaternion`, `Vector3`, `Matrix3` (no std) |
//! | `mint`      | `From`/`Into` mint's types, so glam, cgmath and others convert for free |
//!
//! Each integration is one file (`src/interop/`) and keeps the conventions above: quaternions are
//! Hamilton in every library, the scalar part is `w`, and a unit quaternion means the same
//! rotation on both sides (nalgebra's `UnitQuaternion` is also Hamilton and active). Fixed point
//! ([`fixed`]) needs no feature: it is plain integer code.
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

pub mod dynamics;
mod error;
mod error_free;
pub mod estimation;
pub mod fixed;
mod interop;
pub mod linalg;
pub mod propagation;
pub mod real;
pub mod rotation;
pub mod sensor;
pub mod step_limit;

pub use error::Error;
pub use linalg::{Axis, Complex, Mat3, Vec3};
pub use real::{Real, Ring};
pub use rotation::{
    AxisAngle, Dcm, Euler, EulerSequence, ExpMap, Gibbs, GimbalPolicy, Mrp, PolarAxisAngle, Quat,
    RotationVector, Su2, UnitQuat,
};

/// The `heapless` crate, whose `Vec` appears in public types
/// ([`propagation::Attitudes`], [`propagation::IncrementBuffer`]): re-exported so that callers
/// name those types with the version this crate was built with (`gyrostat::heapless::Vec`).
#[doc(no_inline)]
pub use heapless;

#[cfg(test)]
mod layer_table;

/// The README's Rust examples, compiled and run as doctests so that they stay true.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
