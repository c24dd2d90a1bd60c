//! # gyrostat-ffi: the C interface of gyrostat
//!
//! A static library (`libgyrostat_ffi.a`) and its header `include/gyrostat.h` (generated from this
//! file by cbindgen; `tests/header.rs` regenerates it and fails when the committed header differs).
//! Like the library it is `#![no_std]`, allocates nothing and has no panicking branch (the
//! `panic-link-check` feature proves it at link time on bare metal).
//!
//! # Conventions of the C API
//! - Every function returns a [`gyro_status`]; results go to out-pointers, written only on
//!   `GYRO_OK` (an error leaves every output and every state unchanged).
//! - A pointer that is null or misaligned for its type gives `GYRO_BAD_POINTER` (no undefined
//!   behaviour from a null pointer; a dangling pointer cannot be detected). Optional pointers are
//!   marked "may be NULL".
//! - Plain data: vectors `{x, y, z}`, quaternions `{w, x, y, z}` (scalar first, Hamilton,
//!   body → reference: `v_ref = q ⊗ v_body ⊗ q*`), matrices `m[row][col]` with the body axes as
//!   columns, angles in radians, Q1.30 values as `int32_t` (value = bits / 2³⁰).
//! - Quaternion inputs: one whose squared norm is within `8·ε` of 1 is taken bit for bit; any
//!   other finite, non-zero quaternion is normalised (`GYRO_ZERO_NORM`, `GYRO_NON_FINITE`
//!   otherwise), as scipy's `from_quat`.
//! - State structs (integrators, gyrostat model, estimator) are plain structs of a fixed size that
//!   the header declares, so C allocates them statically or on the stack (no heap); only the
//!   `gyro_*_init` functions write their contents. A struct that was never initialised (all
//!   zero, as static storage starts) gives `GYRO_NOT_INITIALIZED`. A state may be copied with
//!   `memcpy` (it holds no pointer).
//! - f32 and f64 variants have the same names with `_f32`/`_f64`; the fixed-point attitude path
//!   is `_q30`.
//! - Enumerated arguments are `uint32_t` constants (`GYRO_CONING_*`, `GYRO_NORM_*`, ...): an
//!   unknown value gives `GYRO_INVALID_ARGUMENT`.
#![no_std]
#![allow(non_camel_case_types)]

// The host static library links with std's panic handler (and a C host program with the system
// libraries `cargo rustc --print native-static-libs` lists); bare metal has its own below.
#[cfg(not(target_os = "none"))]
extern crate std;

use core::ffi::c_char;
use core::mem::{align_of, size_of};

use gyrostat::dynamics::{Control, Gyrostat, Inertia, Integrator, State, Wheel};
use gyrostat::estimation::{
    EarthFrame, Estimator, Gains, Mode, Outcome, Params, RateRule, SensorUse,
};
use gyrostat::fixed::IncrementQuantizer;
use gyrostat::propagation::CarriedAttitude;
use gyrostat::propagation::{
    CompensatedAttitude, ConingRule, IncrementIntegrator, Normalization, RateIntegrator, RateMethod,
};
use gyrostat::real::{Fixed, Q30};
use gyrostat::rotation::{Euler, EulerSequence, EulerSolution, GimbalPolicy, Pole};
use gyrostat::sensor::RawScale;
use gyrostat::{Dcm, Error, Mat3, Quat, Real, RotationVector, UnitQuat, Vec3};

#[cfg(all(target_os = "none", not(test)))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    #[cfg(feature = "panic-link-check")]
    {
        unsafe extern "C" {
            // Defined nowhere: with the feature, a C program links only if no call to the
            // panic handler survives optimisation.
            fn gyrostat_ffi_panicking_branch_linked() -> !;
        }
        unsafe { gyrostat_ffi_panicking_branch_linked() }
    }
    #[cfg(not(feature = "panic-link-check"))]
    loop {
        core::hint::spin_loop();
    }
}

/// The result of every function.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum gyro_status {
    /// Success: the outputs are written.
    GYRO_OK = 0,
    /// A required pointer is null or misaligned for its type.
    GYRO_BAD_POINTER = 1,
    /// A state struct that no `gyro_*_init` function has written.
    GYRO_NOT_INITIALIZED = 2,
    /// An argument outside its documented domain (an unknown enumerated value among them).
    GYRO_INVALID_ARGUMENT = 3,
    /// A NaN or infinite input.
    GYRO_NON_FINITE = 4,
    /// A zero vector or quaternion where a direction is needed.
    GYRO_ZERO_NORM = 5,
    /// A quaternion too far from unit norm.
    GYRO_NOT_UNIT = 6,
    /// A matrix that is not a proper rotation.
    GYRO_NOT_ROTATION = 7,
    /// A singular configuration for the conversion.
    GYRO_SINGULAR = 8,
    /// An inertia that is not physical (not positive definite, or violating the triangle
    /// inequality).
    GYRO_NON_PHYSICAL_INERTIA = 9,
    /// An iteration that did not converge.
    GYRO_NOT_CONVERGED = 10,
    /// A step beyond the method's validity limit (half a turn).
    GYRO_STEP_TOO_LONG = 11,
    /// A value outside the range of the fixed-point format.
    GYRO_OUT_OF_RANGE = 12,
    /// A raw sensor reading at its register's limit, rejected by the clip policy (the
    /// library's `Error::Clipped`; the code that versions before it called `GYRO_OTHER_ERROR`).
    GYRO_CLIPPED = 13,
}

use gyro_status::*;

/// Every library error has its own code. The match has no wildcard: a new `Error` variant does
/// not compile until it has one (`tests/contract.rs` checks the codes are distinct and
/// documented in the header).
impl From<Error> for gyro_status {
    fn from(e: Error) -> Self {
        match e {
            Error::NonFinite => GYRO_NON_FINITE,
            Error::ZeroNorm => GYRO_ZERO_NORM,
            Error::NotUnit => GYRO_NOT_UNIT,
            Error::NotRotation => GYRO_NOT_ROTATION,
            Error::Singular => GYRO_SINGULAR,
            Error::NonPhysicalInertia => GYRO_NON_PHYSICAL_INERTIA,
            Error::NotConverged => GYRO_NOT_CONVERGED,
            Error::StepTooLong => GYRO_STEP_TOO_LONG,
            Error::InvalidArgument => GYRO_INVALID_ARGUMENT,
            Error::OutOfRange => GYRO_OUT_OF_RANGE,
            Error::Clipped => GYRO_CLIPPED,
        }
    }
}

/// `ConingRule::Exp`: one exponential per increment, `φ = θ`.
pub const GYRO_CONING_EXP: u32 = 0;
/// `ConingRule::OnePlusPrevious`: `φ = θₖ + (1/12) θₖ₋₁ × θₖ`.
pub const GYRO_CONING_ONE_PLUS_PREVIOUS: u32 = 1;
/// `ConingRule::TwoSample`: two increments per update, `φ = θ₁ + θ₂ + ⅔ θ₁ × θ₂`.
pub const GYRO_CONING_TWO_SAMPLE: u32 = 2;
/// `ConingRule::ThreeSample`: three increments per update.
pub const GYRO_CONING_THREE_SAMPLE: u32 = 3;
/// `ConingRule::FourSample`: four increments per update.
pub const GYRO_CONING_FOUR_SAMPLE: u32 = 4;

/// `Normalization::Exact`: `q/|q|` after each update.
pub const GYRO_NORM_EXACT: u32 = 0;
/// `Normalization::Fast`: one Newton step `q + q(1 − |q|²)/2` after each update.
pub const GYRO_NORM_FAST: u32 = 1;
/// `Normalization::None`: no renormalisation.
pub const GYRO_NORM_NONE: u32 = 2;

/// `RateMethod::Magnus4`: fourth-order Magnus, one exponential per step.
pub const GYRO_RATE_MAGNUS4: u32 = 0;
/// `RateMethod::Cf4`: fourth-order commutator-free, two exponentials per step.
pub const GYRO_RATE_CF4: u32 = 1;
/// `RateMethod::Rk4`: classical Runge–Kutta on `q̇ = ½ q ⊗ ω`, then the normalisation.
pub const GYRO_RATE_RK4: u32 = 2;

/// `Integrator::Rk4` for the gyrostat step.
pub const GYRO_INTEGRATOR_RK4: u32 = 0;
/// `Integrator::Strang`: second-order splitting.
pub const GYRO_INTEGRATOR_STRANG: u32 = 1;
/// `Integrator::Yoshida4`: fourth-order splitting (Yoshida).
pub const GYRO_INTEGRATOR_YOSHIDA4: u32 = 2;
/// `Integrator::Suzuki4`: fourth-order splitting (Suzuki).
pub const GYRO_INTEGRATOR_SUZUKI4: u32 = 3;

/// At a gimbal lock the first angle is 0 and the third carries the determined combination.
pub const GYRO_GIMBAL_ZERO_FIRST: u32 = 0;
/// At a gimbal lock the third angle is 0 and the first carries the combination (scipy).
pub const GYRO_GIMBAL_ZERO_THIRD: u32 = 1;
/// At a gimbal lock the split closest to `previous` (continuity of telemetry).
pub const GYRO_GIMBAL_CLOSEST_TO: u32 = 2;

/// Estimator earth frame: x east, y magnetic north, z up.
pub const GYRO_FRAME_ENU: u32 = 0;
/// Estimator earth frame: x magnetic north, y east, z down.
pub const GYRO_FRAME_NED: u32 = 1;

/// Estimator mode: every part of the filter on every sample (the default).
pub const GYRO_MODE_FULL: u32 = 0;
/// Estimator mode: the prediction every sample, the covariance and the corrections once per
/// `correction_period` (the library's `Mode::Light`).
pub const GYRO_MODE_LIGHT: u32 = 1;

/// Estimator rate rule (`rate_rule` of the parameter structs): the rule the library gives
/// parameters of the struct's other choices (frame, gains, mode; its `Params::from_values`, on
/// which `Params::default()` is built), whatever it is in this version. The default parameters
/// (`gyro_estimator_*_default_params`) hold this code.
pub const GYRO_RATE_RULE_DEFAULT: u32 = 0;
/// Estimator rate rule: the mean of the step's two end samples (`RateRule::Trapezoid`, order 2,
/// name `trapezoid`).
pub const GYRO_RATE_RULE_TRAPEZOID: u32 = 1;
/// Estimator rate rule: Magnus-4 on the Gauss-node rates of the interpolant through the last
/// four samples (`RateRule::Magnus4`, order 4, one exponential, name `magnus4`).
pub const GYRO_RATE_RULE_MAGNUS4: u32 = 2;
/// Estimator rate rule: commutator-free CF4 on the same Gauss-node rates (`RateRule::Cf4`,
/// order 4, two exponentials, name `cf4`).
pub const GYRO_RATE_RULE_CF4: u32 = 3;

/// A sensor sample corrected the estimate.
pub const GYRO_SENSOR_USED: u32 = 0;
/// No sample was given (a 6D update has no magnetometer).
pub const GYRO_SENSOR_ABSENT: u32 = 1;
/// A NaN or infinite component: the sample was ignored.
pub const GYRO_SENSOR_NON_FINITE: u32 = 2;
/// A component at or beyond the sensor's range: ignored.
pub const GYRO_SENSOR_SATURATED: u32 = 3;
/// Finite but rejected as disturbed.
pub const GYRO_SENSOR_DISTURBED: u32 = 4;
/// A zero vector: no direction.
pub const GYRO_SENSOR_ZERO: u32 = 5;

/// The most reaction wheels a `gyro_gyrostat_*` model holds.
pub const GYRO_MAX_WHEELS: usize = 4;

/// A 3-vector, f32.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct gyro_vec3_f32 {
    /// x component.
    pub x: f32,
    /// y component.
    pub y: f32,
    /// z component.
    pub z: f32,
}

/// A 3-vector, f64.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct gyro_vec3_f64 {
    /// x component.
    pub x: f64,
    /// y component.
    pub y: f64,
    /// z component.
    pub z: f64,
}

/// A 3-vector in Q1.30 (value = bits / 2³⁰).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct gyro_vec3_q30 {
    /// x component.
    pub x: i32,
    /// y component.
    pub y: i32,
    /// z component.
    pub z: i32,
}

/// A quaternion `w + xi + yj + zk`, f32 (scalar first, Hamilton).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct gyro_quat_f32 {
    /// Scalar part.
    pub w: f32,
    /// `i` component.
    pub x: f32,
    /// `j` component.
    pub y: f32,
    /// `k` component.
    pub z: f32,
}

/// A quaternion `w + xi + yj + zk`, f64 (scalar first, Hamilton).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct gyro_quat_f64 {
    /// Scalar part.
    pub w: f64,
    /// `i` component.
    pub x: f64,
    /// `j` component.
    pub y: f64,
    /// `k` component.
    pub z: f64,
}

/// A unit quaternion in Q1.30 (value = bits / 2³⁰), scalar first.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct gyro_quat_q30 {
    /// Scalar part.
    pub w: i32,
    /// `i` component.
    pub x: i32,
    /// `j` component.
    pub y: i32,
    /// `k` component.
    pub z: i32,
}

/// A 3×3 matrix `m[row][col]`, f32; as a rotation, the body axes are its columns.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct gyro_mat3_f32 {
    /// Entries, row-major.
    pub m: [[f32; 3]; 3],
}

/// A 3×3 matrix `m[row][col]`, f64; as a rotation, the body axes are its columns.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct gyro_mat3_f64 {
    /// Entries, row-major.
    pub m: [[f64; 3]; 3],
}

/// Euler angles extracted from an attitude, with the gimbal lock reported (f32).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct gyro_euler_f32 {
    /// `[first, second, third]` (rad) in the order of the sequence's letters: first and third
    /// in `(−π, π]`, the middle in `[0, π]` (proper) or `[−π/2, π/2]` (Tait–Bryan).
    pub angles: [f32; 3],
    /// Distance (rad) of the middle angle from the nearest pole, always set.
    pub distance_to_pole: f32,
    /// 0: no gimbal lock; −1: locked at the lower pole (middle 0 or −π/2); +1: at the upper
    /// pole (π or +π/2). Within `2·FLT_EPSILON` of a pole only `first + sign·third` is
    /// determined; the split follows the `GYRO_GIMBAL_*` policy.
    pub gimbal_lock: i32,
    /// With a gimbal lock, the sign `s = ±1` of the combination `first + s·third`; else 0.
    pub sign: f32,
    /// With a gimbal lock, `first + s·third` wrapped to `(−π, π]`; else 0.
    pub combined_angle: f32,
}

/// Euler angles extracted from an attitude, with the gimbal lock reported (f64; see
/// `gyro_euler_f32`, the threshold is `2·DBL_EPSILON`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct gyro_euler_f64 {
    /// `[first, second, third]` (rad) in the order of the sequence's letters.
    pub angles: [f64; 3],
    /// Distance (rad) of the middle angle from the nearest pole, always set.
    pub distance_to_pole: f64,
    /// 0: no gimbal lock; −1: lower pole; +1: upper pole.
    pub gimbal_lock: i32,
    /// With a gimbal lock, the sign of the combination `first + s·third`; else 0.
    pub sign: f64,
    /// With a gimbal lock, `first + s·third` wrapped to `(−π, π]`; else 0.
    pub combined_angle: f64,
}

/// A reaction wheel: spin axis (body frame, normalised by `init`) and axial inertia (kg·m²), f32.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct gyro_wheel_f32 {
    /// Spin axis, body frame.
    pub axis: gyro_vec3_f32,
    /// Axial moment of inertia, kg·m², > 0.
    pub inertia: f32,
}

/// A reaction wheel, f64 (see `gyro_wheel_f32`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct gyro_wheel_f64 {
    /// Spin axis, body frame.
    pub axis: gyro_vec3_f64,
    /// Axial moment of inertia, kg·m², > 0.
    pub inertia: f64,
}

/// The state of a gyrostat, f32: attitude (body → lab), body-frame total angular momentum `J`
/// (N·m·s) and the wheel speeds relative to the body (rad/s; entries past the model's wheel
/// count are ignored on input and written as 0).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct gyro_gyrostat_state_f32 {
    /// Attitude, body → lab.
    pub attitude: gyro_quat_f32,
    /// Total angular momentum, body frame.
    pub momentum: gyro_vec3_f32,
    /// Wheel speeds relative to the body.
    pub wheel_speeds: [f32; GYRO_MAX_WHEELS],
}

/// The state of a gyrostat, f64 (see `gyro_gyrostat_state_f32`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct gyro_gyrostat_state_f64 {
    /// Attitude, body → lab.
    pub attitude: gyro_quat_f64,
    /// Total angular momentum, body frame.
    pub momentum: gyro_vec3_f64,
    /// Wheel speeds relative to the body.
    pub wheel_speeds: [f64; GYRO_MAX_WHEELS],
}

/// What became of each sensor's sample in one estimator update.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct gyro_estimator_outcome {
    /// 1 when a gyroscope component was at or beyond its range (propagated clipped).
    pub gyro_saturated: u32,
    /// The accelerometer sample: a `GYRO_SENSOR_*` value.
    pub accel: u32,
    /// The magnetometer sample: a `GYRO_SENSOR_*` value.
    pub mag: u32,
    /// 1 when the sensor was at rest.
    pub at_rest: u32,
    /// 1 when this update initialised the attitude.
    pub initialized: u32,
}

// --- Plain-data conversions ------------------------------------------------------------------

/// The C types of one float width.
trait CFloat: Real {
    type V: Copy;
    type Q: Copy;
    type M: Copy;
    type E;
    fn v_in(v: Self::V) -> Vec3<Self>;
    fn v_out(v: Vec3<Self>) -> Self::V;
    fn q_in(q: Self::Q) -> Quat<Self>;
    fn q_out(q: UnitQuat<Self>) -> Self::Q;
    fn m_in(m: Self::M) -> Mat3<Self>;
    fn m_out(m: Mat3<Self>) -> Self::M;
    fn e_out(s: EulerSolution<Self>) -> Self::E;
}

macro_rules! cfloat {
    ($t:ty, $v:ident, $q:ident, $m:ident, $e:ident) => {
        impl CFloat for $t {
            type V = $v;
            type Q = $q;
            type M = $m;
            type E = $e;
            fn v_in(v: $v) -> Vec3<$t> {
                Vec3::new(v.x, v.y, v.z)
            }
            fn v_out(v: Vec3<$t>) -> $v {
                $v {
                    x: v.x,
                    y: v.y,
                    z: v.z,
                }
            }
            fn q_in(q: $q) -> Quat<$t> {
                Quat::new(q.w, q.x, q.y, q.z)
            }
            fn q_out(q: UnitQuat<$t>) -> $q {
                let q = q.into_quat();
                $q {
                    w: q.w,
                    x: q.x,
                    y: q.y,
                    z: q.z,
                }
            }
            fn m_in(m: $m) -> Mat3<$t> {
                Mat3 { m: m.m }
            }
            fn m_out(m: Mat3<$t>) -> $m {
                $m { m: m.m }
            }
            fn e_out(s: EulerSolution<$t>) -> $e {
                let (gimbal_lock, sign, combined_angle) = match s.singularity {
                    None => (0, 0.0, 0.0),
                    Some(l) => (
                        match l.pole {
                            Pole::Lower => -1,
                            Pole::Upper => 1,
                        },
                        l.sign,
                        l.combined_angle,
                    ),
                };
                $e {
                    angles: s.euler.angles,
                    distance_to_pole: s.distance_to_pole,
                    gimbal_lock,
                    sign,
                    combined_angle,
                }
            }
        }
    };
}
cfloat!(
    f32,
    gyro_vec3_f32,
    gyro_quat_f32,
    gyro_mat3_f32,
    gyro_euler_f32
);
cfloat!(
    f64,
    gyro_vec3_f64,
    gyro_quat_f64,
    gyro_mat3_f64,
    gyro_euler_f64
);

fn v30_in(v: gyro_vec3_q30) -> Vec3<Q30> {
    Vec3::new(
        Fixed::from_bits(v.x),
        Fixed::from_bits(v.y),
        Fixed::from_bits(v.z),
    )
}

fn v30_out(v: Vec3<Q30>) -> gyro_vec3_q30 {
    gyro_vec3_q30 {
        x: v.x.to_bits(),
        y: v.y.to_bits(),
        z: v.z.to_bits(),
    }
}

fn q30_out(q: UnitQuat<Q30>) -> gyro_quat_q30 {
    let [w, x, y, z] = q.to_bits();
    gyro_quat_q30 { w, x, y, z }
}

/// A Q1.30 attitude taken bit for bit when `| |q|² − 1 | ≤ 2⁻¹⁶` (integer arithmetic; the
/// integrators' renormalisation assumes a nearly unit start), `GYRO_NOT_UNIT` otherwise.
fn q30_in(q: gyro_quat_q30) -> Result<UnitQuat<Q30>, gyro_status> {
    let sq = |c: i32| i128::from(c) * i128::from(c);
    let n2 = sq(q.w) + sq(q.x) + sq(q.y) + sq(q.z); // units 2⁻⁶⁰
    if (n2 - (1i128 << 60)).abs() > 1i128 << 44 {
        return Err(GYRO_NOT_UNIT);
    }
    let f = Fixed::from_bits;
    Ok(UnitQuat::new_unchecked(Quat::new(
        f(q.w),
        f(q.x),
        f(q.y),
        f(q.z),
    )))
}

/// A quaternion input: kept bit for bit when unit to rounding, otherwise normalised.
fn unit_in<T: CFloat>(q: T::Q) -> Result<UnitQuat<T>, gyro_status> {
    let q = T::q_in(q);
    if !q.is_finite() {
        return Err(GYRO_NON_FINITE);
    }
    let d = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z - T::ONE;
    if d.abs() <= T::from_f64(8.0) * T::EPSILON {
        return Ok(UnitQuat::new_unchecked(q));
    }
    Ok(UnitQuat::try_new(q)?)
}

fn finite_in<T: CFloat>(v: T::V) -> Result<Vec3<T>, gyro_status> {
    let v = T::v_in(v);
    if v.is_finite() {
        Ok(v)
    } else {
        Err(GYRO_NON_FINITE)
    }
}

// --- Pointers ----------------------------------------------------------------------------------

fn ok_ptr<P>(p: *const P) -> Result<(), gyro_status> {
    if p.is_null() || !p.is_aligned() {
        Err(GYRO_BAD_POINTER)
    } else {
        Ok(())
    }
}

/// Reads a required input.
fn read<P: Copy>(p: *const P) -> Result<P, gyro_status> {
    ok_ptr(p)?;
    // SAFETY: non-null and aligned; the caller promises it points to a valid `P`.
    Ok(unsafe { p.read() })
}

/// Reads an optional input (`None` for NULL).
fn read_opt<P: Copy>(p: *const P) -> Result<Option<P>, gyro_status> {
    if p.is_null() {
        Ok(None)
    } else {
        read(p).map(Some)
    }
}

/// Writes an output checked with `ok_ptr` (or NULL for an optional one: nothing is written).
fn write<P>(p: *mut P, v: P) {
    if !p.is_null() && p.is_aligned() {
        // SAFETY: non-null and aligned; the caller promises it points to writable memory.
        unsafe { p.write(v) }
    }
}

/// Checks an optional output: NULL or aligned.
fn ok_opt<P>(p: *const P) -> Result<(), gyro_status> {
    if p.is_null() { Ok(()) } else { ok_ptr(p) }
}

fn status(r: Result<(), gyro_status>) -> gyro_status {
    match r {
        Ok(()) => GYRO_OK,
        Err(s) => s,
    }
}

fn coning(rule: u32) -> Result<ConingRule, gyro_status> {
    Ok(match rule {
        GYRO_CONING_EXP => ConingRule::Exp,
        GYRO_CONING_ONE_PLUS_PREVIOUS => ConingRule::OnePlusPrevious,
        GYRO_CONING_TWO_SAMPLE => ConingRule::TwoSample,
        GYRO_CONING_THREE_SAMPLE => ConingRule::ThreeSample,
        GYRO_CONING_FOUR_SAMPLE => ConingRule::FourSample,
        _ => return Err(GYRO_INVALID_ARGUMENT),
    })
}

fn normalization(norm: u32) -> Result<Normalization, gyro_status> {
    Ok(match norm {
        GYRO_NORM_EXACT => Normalization::Exact,
        GYRO_NORM_FAST => Normalization::Fast,
        GYRO_NORM_NONE => Normalization::None,
        _ => return Err(GYRO_INVALID_ARGUMENT),
    })
}

fn flag(f: u32) -> Result<bool, gyro_status> {
    match f {
        0 => Ok(false),
        1 => Ok(true),
        _ => Err(GYRO_INVALID_ARGUMENT),
    }
}

/// Parses a NUL-terminated sequence of three letters, scipy's notation (`"ZYX"` intrinsic,
/// `"zyx"` extrinsic).
fn sequence(p: *const c_char) -> Result<EulerSequence, gyro_status> {
    ok_ptr(p)?;
    let p = p.cast::<u8>();
    let mut b = [0u8; 3];
    for (i, slot) in b.iter_mut().enumerate() {
        // SAFETY: bytes before the terminating NUL are readable (a C string).
        let c = unsafe { p.add(i).read() };
        if c == 0 {
            return Err(GYRO_INVALID_ARGUMENT);
        }
        *slot = c;
    }
    // SAFETY: the three bytes before it were not NUL.
    if unsafe { p.add(3).read() } != 0 {
        return Err(GYRO_INVALID_ARGUMENT);
    }
    let s = core::str::from_utf8(&b).map_err(|_| GYRO_INVALID_ARGUMENT)?;
    Ok(EulerSequence::try_from_str(s)?)
}

// --- State storage -----------------------------------------------------------------------------

/// A C state struct: a tag written by `init` and storage for the Rust state.
///
/// # Safety
/// `storage` points to at least `size_of::<Self>() − 8` bytes at offset 8, aligned to 8.
unsafe trait Slot: Sized {
    type Inner: Clone;
    const MAGIC: u32;
    fn tag(&self) -> u32;
    fn set_tag(&mut self, t: u32);
    fn storage(&mut self) -> *mut u8;
    fn storage_ref(&self) -> *const u8;
}

macro_rules! slot {
    ($c:ident, $inner:ty, $magic:expr) => {
        // SAFETY: `_storage` is a `[u64; N]` after the `u32` tag (offset 8, aligned to 8).
        unsafe impl Slot for $c {
            type Inner = $inner;
            const MAGIC: u32 = $magic;
            fn tag(&self) -> u32 {
                self._tag
            }
            fn set_tag(&mut self, t: u32) {
                self._tag = t;
            }
            fn storage(&mut self) -> *mut u8 {
                self._storage.as_mut_ptr().cast()
            }
            fn storage_ref(&self) -> *const u8 {
                self._storage.as_ptr().cast()
            }
        }
    };
}

// The sensor front end (clocks, clip guard, raw scale, calibration, axis remap), after the
// `slot!` macro it uses.
mod sensor;
pub use sensor::*;

fn init<S: Slot>(s: *mut S, v: S::Inner) -> Result<(), gyro_status> {
    const {
        assert!(size_of::<S::Inner>() + 8 <= size_of::<S>());
        assert!(align_of::<S::Inner>() <= 8);
    }
    ok_ptr(s)?;
    // SAFETY: checked non-null and aligned; the storage fits `Inner` (asserted above).
    let s = unsafe { &mut *s };
    unsafe { s.storage().cast::<S::Inner>().write(v) };
    s.set_tag(S::MAGIC);
    Ok(())
}

fn state<'a, S: Slot>(s: *mut S) -> Result<&'a mut S::Inner, gyro_status> {
    ok_ptr(s)?;
    // SAFETY: checked non-null and aligned.
    let s = unsafe { &mut *s };
    if s.tag() != S::MAGIC {
        return Err(GYRO_NOT_INITIALIZED);
    }
    // SAFETY: the tag says `init` wrote an `Inner` there.
    Ok(unsafe { &mut *s.storage().cast::<S::Inner>() })
}

/// A state read without modifying it (through a `const` pointer: no mutable reference made).
fn state_ref<'a, S: Slot>(s: *const S) -> Result<&'a S::Inner, gyro_status> {
    ok_ptr(s)?;
    // SAFETY: checked non-null and aligned.
    let s = unsafe { &*s };
    if s.tag() != S::MAGIC {
        return Err(GYRO_NOT_INITIALIZED);
    }
    // SAFETY: the tag says `init` wrote an `Inner` there.
    Ok(unsafe { &*s.storage_ref().cast::<S::Inner>() })
}

// --- Rotation conversions ----------------------------------------------------------------------

fn quat_normalize<T: CFloat>(q: *const T::Q, out: *mut T::Q) -> gyro_status {
    status((|| {
        let q = read(q)?;
        ok_ptr(out)?;
        write(out, T::q_out(UnitQuat::try_new(T::q_in(q))?));
        Ok(())
    })())
}

/// `out = q / |q|`.
///
/// Errors: `GYRO_NON_FINITE`, `GYRO_ZERO_NORM` (a norm below the smallest normal number).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_quat_normalize_f32(
    q: *const gyro_quat_f32,
    out: *mut gyro_quat_f32,
) -> gyro_status {
    quat_normalize::<f32>(q, out)
}

/// `out = q / |q|` (see `gyro_quat_normalize_f32`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_quat_normalize_f64(
    q: *const gyro_quat_f64,
    out: *mut gyro_quat_f64,
) -> gyro_status {
    quat_normalize::<f64>(q, out)
}

fn quat_mul<T: CFloat>(a: *const T::Q, b: *const T::Q, out: *mut T::Q) -> gyro_status {
    status((|| {
        let (a, b) = (unit_in::<T>(read(a)?)?, unit_in::<T>(read(b)?)?);
        ok_ptr(out)?;
        write(out, T::q_out(a * b));
        Ok(())
    })())
}

/// The composition `out = a ⊗ b` (apply `b`, then `a`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_quat_mul_f32(
    a: *const gyro_quat_f32,
    b: *const gyro_quat_f32,
    out: *mut gyro_quat_f32,
) -> gyro_status {
    quat_mul::<f32>(a, b, out)
}

/// The composition `out = a ⊗ b` (apply `b`, then `a`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_quat_mul_f64(
    a: *const gyro_quat_f64,
    b: *const gyro_quat_f64,
    out: *mut gyro_quat_f64,
) -> gyro_status {
    quat_mul::<f64>(a, b, out)
}

fn quat_rotate<T: CFloat>(q: *const T::Q, v: *const T::V, out: *mut T::V) -> gyro_status {
    status((|| {
        let q = unit_in::<T>(read(q)?)?;
        let v = finite_in::<T>(read(v)?)?;
        ok_ptr(out)?;
        write(out, T::v_out(q.rotate(v)));
        Ok(())
    })())
}

/// `out = q ⊗ v ⊗ q*`: a body-frame vector in the reference frame.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_quat_rotate_f32(
    q: *const gyro_quat_f32,
    v: *const gyro_vec3_f32,
    out: *mut gyro_vec3_f32,
) -> gyro_status {
    quat_rotate::<f32>(q, v, out)
}

/// `out = q ⊗ v ⊗ q*`: a body-frame vector in the reference frame.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_quat_rotate_f64(
    q: *const gyro_quat_f64,
    v: *const gyro_vec3_f64,
    out: *mut gyro_vec3_f64,
) -> gyro_status {
    quat_rotate::<f64>(q, v, out)
}

fn quat_from_axis_angle<T: CFloat>(axis: *const T::V, angle: T, out: *mut T::Q) -> gyro_status {
    status((|| {
        let axis = T::v_in(read(axis)?);
        ok_ptr(out)?;
        write(out, T::q_out(UnitQuat::try_from_axis_angle(axis, angle)?));
        Ok(())
    })())
}

/// `out = (cos(angle/2), sin(angle/2)·axis/|axis|)`.
///
/// Errors: `GYRO_NON_FINITE`, `GYRO_ZERO_NORM` (zero axis).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_quat_from_axis_angle_f32(
    axis: *const gyro_vec3_f32,
    angle: f32,
    out: *mut gyro_quat_f32,
) -> gyro_status {
    quat_from_axis_angle::<f32>(axis, angle, out)
}

/// `out = (cos(angle/2), sin(angle/2)·axis/|axis|)`.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_quat_from_axis_angle_f64(
    axis: *const gyro_vec3_f64,
    angle: f64,
    out: *mut gyro_quat_f64,
) -> gyro_status {
    quat_from_axis_angle::<f64>(axis, angle, out)
}

fn quat_from_rotvec<T: CFloat>(v: *const T::V, out: *mut T::Q) -> gyro_status {
    status((|| {
        let v = RotationVector::try_new(T::v_in(read(v)?))?;
        ok_ptr(out)?;
        write(out, T::q_out(v.to_unit_quat()));
        Ok(())
    })())
}

/// The attitude of rotation vector `v` (rad): `out = exp(v/2)`.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_quat_from_rotvec_f32(
    v: *const gyro_vec3_f32,
    out: *mut gyro_quat_f32,
) -> gyro_status {
    quat_from_rotvec::<f32>(v, out)
}

/// The attitude of rotation vector `v` (rad): `out = exp(v/2)`.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_quat_from_rotvec_f64(
    v: *const gyro_vec3_f64,
    out: *mut gyro_quat_f64,
) -> gyro_status {
    quat_from_rotvec::<f64>(v, out)
}

fn quat_to_rotvec<T: CFloat>(q: *const T::Q, out: *mut T::V) -> gyro_status {
    status((|| {
        let q = unit_in::<T>(read(q)?)?;
        ok_ptr(out)?;
        write(out, T::v_out(RotationVector::from(q).vector()));
        Ok(())
    })())
}

/// The rotation vector (rad, angle in `[0, π]`) of attitude `q`.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_quat_to_rotvec_f32(
    q: *const gyro_quat_f32,
    out: *mut gyro_vec3_f32,
) -> gyro_status {
    quat_to_rotvec::<f32>(q, out)
}

/// The rotation vector (rad, angle in `[0, π]`) of attitude `q`.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_quat_to_rotvec_f64(
    q: *const gyro_quat_f64,
    out: *mut gyro_vec3_f64,
) -> gyro_status {
    quat_to_rotvec::<f64>(q, out)
}

fn quat_to_dcm<T: CFloat>(q: *const T::Q, out: *mut T::M) -> gyro_status {
    status((|| {
        let q = unit_in::<T>(read(q)?)?;
        ok_ptr(out)?;
        write(out, T::m_out(Dcm::from(q).into_matrix()));
        Ok(())
    })())
}

/// The rotation matrix of `q` (body axes as columns, body → reference).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_quat_to_dcm_f32(
    q: *const gyro_quat_f32,
    out: *mut gyro_mat3_f32,
) -> gyro_status {
    quat_to_dcm::<f32>(q, out)
}

/// The rotation matrix of `q` (body axes as columns, body → reference).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_quat_to_dcm_f64(
    q: *const gyro_quat_f64,
    out: *mut gyro_mat3_f64,
) -> gyro_status {
    quat_to_dcm::<f64>(q, out)
}

fn quat_from_dcm<T: CFloat>(m: *const T::M, tolerance: T, out: *mut T::Q) -> gyro_status {
    status((|| {
        let dcm = Dcm::try_from_matrix(T::m_in(read(m)?), tolerance)?;
        ok_ptr(out)?;
        write(out, T::q_out(dcm.to_unit_quat()));
        Ok(())
    })())
}

/// The attitude of rotation matrix `m`, accepted when `max |mᵀm − I| ≤ tolerance` and
/// `det m > 0`.
///
/// Errors: `GYRO_NON_FINITE`, `GYRO_INVALID_ARGUMENT` (tolerance outside `[0, 1)`),
/// `GYRO_NOT_ROTATION`.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_quat_from_dcm_f32(
    m: *const gyro_mat3_f32,
    tolerance: f32,
    out: *mut gyro_quat_f32,
) -> gyro_status {
    quat_from_dcm::<f32>(m, tolerance, out)
}

/// The attitude of rotation matrix `m` (see `gyro_quat_from_dcm_f32`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_quat_from_dcm_f64(
    m: *const gyro_mat3_f64,
    tolerance: f64,
    out: *mut gyro_quat_f64,
) -> gyro_status {
    quat_from_dcm::<f64>(m, tolerance, out)
}

fn quat_to_euler<T: CFloat>(
    q: *const T::Q,
    seq: *const c_char,
    policy: u32,
    previous: *const [T; 3],
    out: *mut T::E,
) -> gyro_status {
    status((|| {
        let q = unit_in::<T>(read(q)?)?;
        let seq = sequence(seq)?;
        let policy = match policy {
            GYRO_GIMBAL_ZERO_FIRST => GimbalPolicy::ZeroFirst,
            GYRO_GIMBAL_ZERO_THIRD => GimbalPolicy::ZeroThird,
            GYRO_GIMBAL_CLOSEST_TO => GimbalPolicy::ClosestTo(read(previous)?),
            _ => return Err(GYRO_INVALID_ARGUMENT),
        };
        ok_ptr(out)?;
        write(out, T::e_out(q.to_euler(seq, policy)));
        Ok(())
    })())
}

/// Euler angles of `q` in sequence `seq` (scipy's notation: `"ZYX"` intrinsic yaw–pitch–roll,
/// `"zyx"` extrinsic; any of the 24), with the gimbal lock reported in `out` and the
/// undetermined split chosen by `policy` (`GYRO_GIMBAL_*`; `previous`, three angles, is read
/// only for `GYRO_GIMBAL_CLOSEST_TO` and may be NULL otherwise).
///
/// Errors: `GYRO_INVALID_ARGUMENT` for a bad sequence or policy.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type; `seq` is NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_quat_to_euler_f32(
    q: *const gyro_quat_f32,
    seq: *const c_char,
    policy: u32,
    previous: *const [f32; 3],
    out: *mut gyro_euler_f32,
) -> gyro_status {
    quat_to_euler::<f32>(q, seq, policy, previous, out)
}

/// Euler angles of `q` with the gimbal lock reported (see `gyro_quat_to_euler_f32`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type; `seq` is NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_quat_to_euler_f64(
    q: *const gyro_quat_f64,
    seq: *const c_char,
    policy: u32,
    previous: *const [f64; 3],
    out: *mut gyro_euler_f64,
) -> gyro_status {
    quat_to_euler::<f64>(q, seq, policy, previous, out)
}

fn quat_from_euler<T: CFloat>(
    seq: *const c_char,
    angles: *const [T; 3],
    out: *mut T::Q,
) -> gyro_status {
    status((|| {
        let seq = sequence(seq)?;
        let e = Euler::new(seq, read(angles)?);
        ok_ptr(out)?;
        write(out, T::q_out(e.try_to_unit_quat()?));
        Ok(())
    })())
}

/// The attitude of Euler angles `angles` (rad) in sequence `seq` (scipy's notation).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type; `seq` is NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_quat_from_euler_f32(
    seq: *const c_char,
    angles: *const [f32; 3],
    out: *mut gyro_quat_f32,
) -> gyro_status {
    quat_from_euler::<f32>(seq, angles, out)
}

/// The attitude of Euler angles `angles` (rad) in sequence `seq` (scipy's notation).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type; `seq` is NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_quat_from_euler_f64(
    seq: *const c_char,
    angles: *const [f64; 3],
    out: *mut gyro_quat_f64,
) -> gyro_status {
    quat_from_euler::<f64>(seq, angles, out)
}

// --- Increment integrator ----------------------------------------------------------------------

#[derive(Clone)]
enum Inc<T: Real> {
    Plain(IncrementIntegrator<T>),
    Compensated(IncrementIntegrator<T, CompensatedAttitude<T>>),
}

/// Words of `gyro_increment_integrator_f32`'s storage.
pub const GYRO_INCREMENT_INTEGRATOR_F32_WORDS: usize = 16;
/// Words of `gyro_increment_integrator_f64`'s storage.
pub const GYRO_INCREMENT_INTEGRATOR_F64_WORDS: usize = 30;
/// Words of `gyro_increment_integrator_q30`'s storage.
pub const GYRO_INCREMENT_INTEGRATOR_Q30_WORDS: usize = 20;

/// An increment integrator, f32 (`IncrementIntegrator`): gyro increments `Δθ` (rad, body
/// frame) in, attitude out, with a coning rule, plain or compensated (the f32 rounding errors
/// carried, no drift from rounding over hours). Contents private; write with
/// `gyro_increment_integrator_f32_init`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct gyro_increment_integrator_f32 {
    _tag: u32,
    _storage: [u64; GYRO_INCREMENT_INTEGRATOR_F32_WORDS],
}

/// An increment integrator, f64 (see `gyro_increment_integrator_f32`).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct gyro_increment_integrator_f64 {
    _tag: u32,
    _storage: [u64; GYRO_INCREMENT_INTEGRATOR_F64_WORDS],
}

/// An increment integrator in Q1.30 (integer arithmetic only, the same bits on every target),
/// its attitude a `CarriedAttitude` (the rounding low bits carried into the next update).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct gyro_increment_integrator_q30 {
    _tag: u32,
    _storage: [u64; GYRO_INCREMENT_INTEGRATOR_Q30_WORDS],
}

slot!(gyro_increment_integrator_f32, Inc<f32>, 0x6779_0101);
slot!(gyro_increment_integrator_f64, Inc<f64>, 0x6779_0102);
slot!(
    gyro_increment_integrator_q30,
    IncrementIntegrator<Q30, CarriedAttitude<30>>,
    0x6779_0103
);

fn inc_init<T: CFloat, S: Slot<Inner = Inc<T>>>(
    s: *mut S,
    q0: *const T::Q,
    rule: u32,
    norm: u32,
    compensated: u32,
) -> gyro_status {
    status((|| {
        let q0 = unit_in::<T>(read(q0)?)?;
        let (rule, norm) = (coning(rule)?, normalization(norm)?);
        let v = if flag(compensated)? {
            Inc::Compensated(IncrementIntegrator::new(
                CompensatedAttitude::new(q0),
                rule,
                norm,
            ))
        } else {
            Inc::Plain(IncrementIntegrator::new(q0, rule, norm))
        };
        init(s, v)
    })())
}

fn inc_push<T: CFloat, S: Slot<Inner = Inc<T>>>(
    s: *mut S,
    dtheta: *const T::V,
    updated: *mut u32,
    attitude: *mut T::Q,
) -> gyro_status {
    status((|| {
        let d = T::v_in(read(dtheta)?);
        ok_opt(updated)?;
        ok_opt(attitude)?;
        let st = state(s)?;
        let (new, q) = match st {
            Inc::Plain(i) => (i.push(d)?, i.attitude()),
            Inc::Compensated(i) => (i.push(d)?, i.attitude()),
        };
        write(updated, u32::from(new.is_some()));
        write(attitude, T::q_out(q));
        Ok(())
    })())
}

fn inc_attitude<T: CFloat, S: Slot<Inner = Inc<T>>>(
    s: *const S,
    provisional: u32,
    out: *mut T::Q,
) -> gyro_status {
    status((|| {
        let st = state_ref(s)?;
        let provisional = flag(provisional)?;
        ok_ptr(out)?;
        let q = match (st, provisional) {
            (Inc::Plain(i), false) => i.attitude(),
            (Inc::Plain(i), true) => i.provisional_attitude(),
            (Inc::Compensated(i), false) => i.attitude(),
            (Inc::Compensated(i), true) => i.provisional_attitude(),
        };
        write(out, T::q_out(q));
        Ok(())
    })())
}

fn inc_flush<T: CFloat, S: Slot<Inner = Inc<T>>>(s: *mut S, out: *mut T::Q) -> gyro_status {
    status((|| {
        ok_opt(out)?;
        let q = match state(s)? {
            Inc::Plain(i) => i.flush(),
            Inc::Compensated(i) => i.flush(),
        };
        write(out, T::q_out(q));
        Ok(())
    })())
}

/// Starts an increment integrator at attitude `q0` with coning rule `rule` (`GYRO_CONING_*`),
/// normalisation `norm` (`GYRO_NORM_*`), and `compensated` 0 (plain attitude) or 1 (the
/// compensated attitude: f32 rounding carried, for long runs).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_increment_integrator_f32_init(
    s: *mut gyro_increment_integrator_f32,
    q0: *const gyro_quat_f32,
    rule: u32,
    norm: u32,
    compensated: u32,
) -> gyro_status {
    inc_init::<f32, _>(s, q0, rule, norm, compensated)
}

/// Starts an increment integrator, f64 (see `gyro_increment_integrator_f32_init`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_increment_integrator_f64_init(
    s: *mut gyro_increment_integrator_f64,
    q0: *const gyro_quat_f64,
    rule: u32,
    norm: u32,
    compensated: u32,
) -> gyro_status {
    inc_init::<f64, _>(s, q0, rule, norm, compensated)
}

/// Adds one increment `Δθ` (rad, body frame). `*updated` (may be NULL) is 1 when it completed
/// an update group (the rule's 1 to 4 samples), 0 otherwise; `*attitude` (may be NULL) is the
/// attitude after the last completed group.
///
/// Errors (the increment is discarded, the state unchanged): `GYRO_NON_FINITE`;
/// `GYRO_STEP_TOO_LONG` for an increment beyond half a turn with a coning rule;
/// `GYRO_INVALID_ARGUMENT` with `GYRO_CONING_EXP` when `|Δθ|²` overflows.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_increment_integrator_f32_push(
    s: *mut gyro_increment_integrator_f32,
    dtheta: *const gyro_vec3_f32,
    updated: *mut u32,
    attitude: *mut gyro_quat_f32,
) -> gyro_status {
    inc_push::<f32, _>(s, dtheta, updated, attitude)
}

/// Adds one increment, f64 (see `gyro_increment_integrator_f32_push`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_increment_integrator_f64_push(
    s: *mut gyro_increment_integrator_f64,
    dtheta: *const gyro_vec3_f64,
    updated: *mut u32,
    attitude: *mut gyro_quat_f64,
) -> gyro_status {
    inc_push::<f64, _>(s, dtheta, updated, attitude)
}

/// The attitude after the last completed update group (`provisional` 0), or after every
/// increment received so far without committing (`provisional` 1: the pending increments with
/// the highest-order rule that fits their number).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_increment_integrator_f32_attitude(
    s: *const gyro_increment_integrator_f32,
    provisional: u32,
    out: *mut gyro_quat_f32,
) -> gyro_status {
    inc_attitude::<f32, _>(s, provisional, out)
}

/// The attitude (see `gyro_increment_integrator_f32_attitude`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_increment_integrator_f64_attitude(
    s: *const gyro_increment_integrator_f64,
    provisional: u32,
    out: *mut gyro_quat_f64,
) -> gyro_status {
    inc_attitude::<f64, _>(s, provisional, out)
}

/// Commits a trailing partial group (end of a record) and writes the attitude after every
/// increment received to `out` (may be NULL).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_increment_integrator_f32_flush(
    s: *mut gyro_increment_integrator_f32,
    out: *mut gyro_quat_f32,
) -> gyro_status {
    inc_flush::<f32, _>(s, out)
}

/// Commits a trailing partial group (see `gyro_increment_integrator_f32_flush`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_increment_integrator_f64_flush(
    s: *mut gyro_increment_integrator_f64,
    out: *mut gyro_quat_f64,
) -> gyro_status {
    inc_flush::<f64, _>(s, out)
}

/// Starts a Q1.30 increment integrator at `q0` (its squared norm within 2⁻¹⁶ of 1, taken bit for
/// bit; `GYRO_NOT_UNIT` otherwise), coning rule `rule`, normalisation `norm`.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_increment_integrator_q30_init(
    s: *mut gyro_increment_integrator_q30,
    q0: *const gyro_quat_q30,
    rule: u32,
    norm: u32,
) -> gyro_status {
    status((|| {
        let q0 = q30_in(read(q0)?)?;
        let (rule, norm) = (coning(rule)?, normalization(norm)?);
        init(
            s,
            IncrementIntegrator::new(CarriedAttitude::new(q0), rule, norm),
        )
    })())
}

/// Adds one Q1.30 increment (rad). `*updated` and `*attitude` (each may be NULL) as in
/// `gyro_increment_integrator_f32_push`.
///
/// Errors (the increment is discarded): `GYRO_OUT_OF_RANGE` for a component of 0.25 rad or
/// more with a coning rule; `GYRO_STEP_TOO_LONG` beyond half a turn.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_increment_integrator_q30_push(
    s: *mut gyro_increment_integrator_q30,
    dtheta: *const gyro_vec3_q30,
    updated: *mut u32,
    attitude: *mut gyro_quat_q30,
) -> gyro_status {
    status((|| {
        let d = v30_in(read(dtheta)?);
        ok_opt(updated)?;
        ok_opt(attitude)?;
        let st = state(s)?;
        let new = st.push(d)?;
        write(updated, u32::from(new.is_some()));
        write(attitude, q30_out(st.attitude()));
        Ok(())
    })())
}

/// The Q1.30 attitude after the last completed update group.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_increment_integrator_q30_attitude(
    s: *const gyro_increment_integrator_q30,
    out: *mut gyro_quat_q30,
) -> gyro_status {
    status((|| {
        let st = state_ref(s)?;
        ok_ptr(out)?;
        write(out, q30_out(st.attitude()));
        Ok(())
    })())
}

/// Words of `gyro_increment_quantizer_q30`'s storage.
pub const GYRO_INCREMENT_QUANTIZER_Q30_WORDS: usize = 5;

/// Raw gyro increment registers to Q1.30 rad, with the scale (rad per LSB, checked once by
/// `init`) and the rounding remainder carried from one reading to the next (`RawScale<Q30>`,
/// `IncrementQuantizer`): a repeating reading does not repeat its rounding.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct gyro_increment_quantizer_q30 {
    _tag: u32,
    _storage: [u64; GYRO_INCREMENT_QUANTIZER_Q30_WORDS],
}

slot!(
    gyro_increment_quantizer_q30,
    (RawScale<Q30>, IncrementQuantizer<30>),
    0x6779_0104
);

/// Starts a quantizer for a gyro of `rad_per_lsb` rad per LSB of its increment registers (the
/// only floating-point operation of the fixed-point path).
///
/// Errors: `GYRO_NON_FINITE`; `GYRO_INVALID_ARGUMENT` for a scale that is not positive;
/// `GYRO_OUT_OF_RANGE` for one that would take an `int16_t` out of Q1.30's range of the
/// integrator (`[2⁻³⁰, 2⁻¹⁴)` rad per LSB).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_increment_quantizer_q30_init(
    s: *mut gyro_increment_quantizer_q30,
    rad_per_lsb: f64,
) -> gyro_status {
    status((|| {
        let scale = RawScale::<Q30>::try_new(rad_per_lsb)?;
        init(s, (scale, IncrementQuantizer::new()))
    })())
}

/// Converts one raw `[x, y, z]` increment reading to Q1.30 rad (integer arithmetic only).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_increment_quantizer_q30_quantize(
    s: *mut gyro_increment_quantizer_q30,
    raw: *const [i16; 3],
    out: *mut gyro_vec3_q30,
) -> gyro_status {
    status((|| {
        let raw = read(raw)?;
        ok_ptr(out)?;
        let (scale, quant) = state(s)?;
        write(out, v30_out(quant.quantize_raw(scale, raw)));
        Ok(())
    })())
}

// --- Rate integrator ---------------------------------------------------------------------------

#[derive(Clone)]
enum Rate<T: Real> {
    Plain(RateIntegrator<T>),
    Compensated(RateIntegrator<T, CompensatedAttitude<T>>),
}

/// Words of `gyro_rate_integrator_f32`'s storage.
pub const GYRO_RATE_INTEGRATOR_F32_WORDS: usize = 14;
/// Words of `gyro_rate_integrator_f64`'s storage.
pub const GYRO_RATE_INTEGRATOR_F64_WORDS: usize = 28;

/// A rate integrator, f32 (`RateIntegrator`): rate samples `ω(k·dt)` (rad/s, body frame) in,
/// the attitude at the sample times out, to fourth order. Contents private.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct gyro_rate_integrator_f32 {
    _tag: u32,
    _storage: [u64; GYRO_RATE_INTEGRATOR_F32_WORDS],
}

/// A rate integrator, f64 (see `gyro_rate_integrator_f32`).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct gyro_rate_integrator_f64 {
    _tag: u32,
    _storage: [u64; GYRO_RATE_INTEGRATOR_F64_WORDS],
}

slot!(gyro_rate_integrator_f32, Rate<f32>, 0x6779_0201);
slot!(gyro_rate_integrator_f64, Rate<f64>, 0x6779_0202);

fn rate_init<T: CFloat, S: Slot<Inner = Rate<T>>>(
    s: *mut S,
    q0: *const T::Q,
    method: u32,
    norm: u32,
    dt: T,
    compensated: u32,
) -> gyro_status {
    status((|| {
        let q0 = unit_in::<T>(read(q0)?)?;
        let method = match method {
            GYRO_RATE_MAGNUS4 => RateMethod::Magnus4,
            GYRO_RATE_CF4 => RateMethod::Cf4,
            GYRO_RATE_RK4 => RateMethod::Rk4,
            _ => return Err(GYRO_INVALID_ARGUMENT),
        };
        let norm = normalization(norm)?;
        let v = if flag(compensated)? {
            Rate::Compensated(RateIntegrator::try_new(
                CompensatedAttitude::new(q0),
                method,
                norm,
                dt,
            )?)
        } else {
            Rate::Plain(RateIntegrator::try_new(q0, method, norm, dt)?)
        };
        init(s, v)
    })())
}

/// Writes up to three attitudes and their count.
fn write_attitudes<T: CFloat>(
    a: &[UnitQuat<T>],
    out: *mut [T::Q; 3],
    count: *mut u32,
) -> Result<(), gyro_status> {
    if !out.is_null() {
        // SAFETY: checked NULL or aligned by the caller (`ok_opt`), three writable quaternions.
        let out = unsafe { &mut *out };
        for (o, q) in out.iter_mut().zip(a) {
            *o = T::q_out(*q);
        }
    }
    write(count, u32::try_from(a.len()).unwrap_or(0));
    Ok(())
}

fn rate_push<T: CFloat, S: Slot<Inner = Rate<T>>>(
    s: *mut S,
    omega: *const T::V,
    out: *mut [T::Q; 3],
    count: *mut u32,
) -> gyro_status {
    status((|| {
        let w = T::v_in(read(omega)?);
        ok_opt(out)?;
        ok_opt(count)?;
        let a = match state(s)? {
            Rate::Plain(r) => r.push(w)?,
            Rate::Compensated(r) => r.push(w)?,
        };
        write_attitudes::<T>(&a, out, count)
    })())
}

fn rate_finish<T: CFloat, S: Slot<Inner = Rate<T>>>(
    s: *mut S,
    out: *mut [T::Q; 3],
    count: *mut u32,
) -> gyro_status {
    status((|| {
        ok_opt(out)?;
        ok_opt(count)?;
        let a = match state(s)?.clone() {
            Rate::Plain(r) => r.finish(),
            Rate::Compensated(r) => r.finish(),
        };
        // SAFETY: `state` checked the pointer.
        unsafe { &mut *s }.set_tag(0);
        write_attitudes::<T>(&a, out, count)
    })())
}

fn rate_attitude<T: CFloat, S: Slot<Inner = Rate<T>>>(s: *const S, out: *mut T::Q) -> gyro_status {
    status((|| {
        let st = state_ref(s)?;
        ok_ptr(out)?;
        let q = match st {
            Rate::Plain(r) => r.attitude(),
            Rate::Compensated(r) => r.attitude(),
        };
        write(out, T::q_out(q));
        Ok(())
    })())
}

/// Starts a rate integrator at `q0` with method `method` (`GYRO_RATE_*`), normalisation `norm`,
/// sample interval `dt` (s) and `compensated` 0 or 1.
///
/// Errors: `GYRO_NON_FINITE`, `GYRO_INVALID_ARGUMENT` for `dt ≤ 0`.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_rate_integrator_f32_init(
    s: *mut gyro_rate_integrator_f32,
    q0: *const gyro_quat_f32,
    method: u32,
    norm: u32,
    dt: f32,
    compensated: u32,
) -> gyro_status {
    rate_init::<f32, _>(s, q0, method, norm, dt, compensated)
}

/// Starts a rate integrator, f64 (see `gyro_rate_integrator_f32_init`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_rate_integrator_f64_init(
    s: *mut gyro_rate_integrator_f64,
    q0: *const gyro_quat_f64,
    method: u32,
    norm: u32,
    dt: f64,
    compensated: u32,
) -> gyro_status {
    rate_init::<f64, _>(s, q0, method, norm, dt, compensated)
}

/// Adds the rate sample `omega` (rad/s, body frame) and writes the attitudes newly reached
/// (0 to 3: the integrator looks ahead by samples) to `out[0..*count]` (`out` and `count` may
/// be NULL).
///
/// Errors (the sample is discarded): `GYRO_NON_FINITE`, `GYRO_STEP_TOO_LONG`.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_rate_integrator_f32_push(
    s: *mut gyro_rate_integrator_f32,
    omega: *const gyro_vec3_f32,
    out: *mut [gyro_quat_f32; 3],
    count: *mut u32,
) -> gyro_status {
    rate_push::<f32, _>(s, omega, out, count)
}

/// Adds a rate sample, f64 (see `gyro_rate_integrator_f32_push`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_rate_integrator_f64_push(
    s: *mut gyro_rate_integrator_f64,
    omega: *const gyro_vec3_f64,
    out: *mut [gyro_quat_f64; 3],
    count: *mut u32,
) -> gyro_status {
    rate_push::<f64, _>(s, omega, out, count)
}

/// Ends the record: the attitudes not yet returned (at the last samples' times, the end of the
/// record integrated with the lower-order interpolant) go to `out[0..*count]`, and the state
/// becomes uninitialised.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_rate_integrator_f32_finish(
    s: *mut gyro_rate_integrator_f32,
    out: *mut [gyro_quat_f32; 3],
    count: *mut u32,
) -> gyro_status {
    rate_finish::<f32, _>(s, out, count)
}

/// Ends the record, f64 (see `gyro_rate_integrator_f32_finish`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_rate_integrator_f64_finish(
    s: *mut gyro_rate_integrator_f64,
    out: *mut [gyro_quat_f64; 3],
    count: *mut u32,
) -> gyro_status {
    rate_finish::<f64, _>(s, out, count)
}

/// The attitude at the last sample time reached.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_rate_integrator_f32_attitude(
    s: *const gyro_rate_integrator_f32,
    out: *mut gyro_quat_f32,
) -> gyro_status {
    rate_attitude::<f32, _>(s, out)
}

/// The attitude at the last sample time reached.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_rate_integrator_f64_attitude(
    s: *const gyro_rate_integrator_f64,
    out: *mut gyro_quat_f64,
) -> gyro_status {
    rate_attitude::<f64, _>(s, out)
}

// --- Gyrostat ----------------------------------------------------------------------------------

#[derive(Clone, Copy)]
enum Body<T: Real> {
    W0(Gyrostat<T, 0>),
    W1(Gyrostat<T, 1>),
    W2(Gyrostat<T, 2>),
    W3(Gyrostat<T, 3>),
    W4(Gyrostat<T, 4>),
}

/// Words of `gyro_gyrostat_f32`'s storage.
pub const GYRO_GYROSTAT_F32_WORDS: usize = 40;
/// Words of `gyro_gyrostat_f64`'s storage.
pub const GYRO_GYROSTAT_F64_WORDS: usize = 72;

/// A gyrostat model, f32: a rigid body (inertia with the wheels locked) with up to
/// `GYRO_MAX_WHEELS` reaction wheels (`Gyrostat`). Contents private.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct gyro_gyrostat_f32 {
    _tag: u32,
    _storage: [u64; GYRO_GYROSTAT_F32_WORDS],
}

/// A gyrostat model, f64 (see `gyro_gyrostat_f32`).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct gyro_gyrostat_f64 {
    _tag: u32,
    _storage: [u64; GYRO_GYROSTAT_F64_WORDS],
}

slot!(gyro_gyrostat_f32, Body<f32>, 0x6779_0301);
slot!(gyro_gyrostat_f64, Body<f64>, 0x6779_0302);

fn wheels<T: Real, const N: usize>(w: &[(Vec3<T>, T)]) -> Result<[Wheel<T>; N], gyro_status> {
    let mut out = [Wheel::try_new(Vec3::new(T::ONE, T::ZERO, T::ZERO), T::ONE)?; N];
    for (o, (axis, inertia)) in out.iter_mut().zip(w) {
        *o = Wheel::try_new(*axis, *inertia)?;
    }
    Ok(out)
}

fn body_init<T: CFloat, S: Slot<Inner = Body<T>>>(
    s: *mut S,
    diagonal: *const T::V,
    off_diagonal: *const T::V,
    w: &[(Vec3<T>, T)],
) -> Result<(), gyro_status> {
    let diagonal = T::v_in(read(diagonal)?);
    let off = read_opt(off_diagonal)?.map_or(Vec3::new(T::ZERO, T::ZERO, T::ZERO), T::v_in);
    let inertia = Inertia::try_from_components(diagonal, off)?;
    let body = match w.len() {
        0 => Body::W0(Gyrostat::rigid(inertia)),
        1 => Body::W1(Gyrostat::with_wheels(inertia, wheels(w)?)),
        2 => Body::W2(Gyrostat::with_wheels(inertia, wheels(w)?)),
        3 => Body::W3(Gyrostat::with_wheels(inertia, wheels(w)?)),
        4 => Body::W4(Gyrostat::with_wheels(inertia, wheels(w)?)),
        _ => return Err(GYRO_INVALID_ARGUMENT),
    };
    init(s, body)
}

/// Up to `GYRO_MAX_WHEELS` wheels: axis and inertia.
type WheelList<T> = [(Vec3<T>, T); GYRO_MAX_WHEELS];

/// Reads `n ≤ GYRO_MAX_WHEELS` wheels from C.
fn read_wheels<W: Copy, T: Real>(
    p: *const W,
    n: u32,
    f: impl Fn(W) -> (Vec3<T>, T),
) -> Result<(WheelList<T>, usize), gyro_status> {
    let n = usize::try_from(n).map_err(|_| GYRO_INVALID_ARGUMENT)?;
    if n > GYRO_MAX_WHEELS {
        return Err(GYRO_INVALID_ARGUMENT);
    }
    let mut out = [(Vec3::new(T::ZERO, T::ZERO, T::ZERO), T::ZERO); GYRO_MAX_WHEELS];
    if n > 0 {
        ok_ptr(p)?;
        for (i, o) in out.iter_mut().take(n).enumerate() {
            // SAFETY: the caller passes `n` wheels.
            *o = f(unsafe { p.add(i).read() });
        }
    }
    Ok((out, n))
}

/// The plain state of any wheel count, in Rust types.
type Plain<T> = (Quat<T>, Vec3<T>, [T; GYRO_MAX_WHEELS]);

fn pad<T: Real, const N: usize>(s: State<T, N>) -> Plain<T> {
    let mut w = [T::ZERO; GYRO_MAX_WHEELS];
    for (o, x) in w.iter_mut().zip(s.wheel_speeds) {
        *o = x;
    }
    (s.attitude.into_quat(), s.momentum, w)
}

fn first<T: Real, const N: usize>(a: [T; GYRO_MAX_WHEELS]) -> [T; N] {
    let mut out = [T::ZERO; N];
    for (o, x) in out.iter_mut().zip(a) {
        *o = x;
    }
    out
}

fn step_n<T: Real, const N: usize>(
    g: &Gyrostat<T, N>,
    integrator: Integrator,
    s: (UnitQuat<T>, Vec3<T>, [T; GYRO_MAX_WHEELS]),
    t: T,
    dt: T,
    torque: Vec3<T>,
    wheel_torques: [T; GYRO_MAX_WHEELS],
) -> Result<Plain<T>, Error> {
    let state = State {
        attitude: s.0,
        momentum: s.1,
        wheel_speeds: first(s.2),
    };
    let control = Control {
        torque,
        wheel_torques: first(wheel_torques),
    };
    g.step_with(integrator, &state, t, dt, control).map(pad)
}

fn omega_n<T: Real, const N: usize>(
    g: &Gyrostat<T, N>,
    q: UnitQuat<T>,
    omega: Vec3<T>,
    ws: [T; GYRO_MAX_WHEELS],
) -> Result<Plain<T>, Error> {
    g.try_state_from_omega(q, omega, first(ws)).map(pad)
}

fn body_step<T: Real>(
    b: &Body<T>,
    integrator: u32,
    s: (UnitQuat<T>, Vec3<T>, [T; GYRO_MAX_WHEELS]),
    t: T,
    dt: T,
    torque: Vec3<T>,
    wheel_torques: [T; GYRO_MAX_WHEELS],
) -> Result<Plain<T>, gyro_status> {
    let i = match integrator {
        GYRO_INTEGRATOR_RK4 => Integrator::Rk4,
        GYRO_INTEGRATOR_STRANG => Integrator::Strang,
        GYRO_INTEGRATOR_YOSHIDA4 => Integrator::Yoshida4,
        GYRO_INTEGRATOR_SUZUKI4 => Integrator::Suzuki4,
        _ => return Err(GYRO_INVALID_ARGUMENT),
    };
    Ok(match b {
        Body::W0(g) => step_n(g, i, s, t, dt, torque, wheel_torques),
        Body::W1(g) => step_n(g, i, s, t, dt, torque, wheel_torques),
        Body::W2(g) => step_n(g, i, s, t, dt, torque, wheel_torques),
        Body::W3(g) => step_n(g, i, s, t, dt, torque, wheel_torques),
        Body::W4(g) => step_n(g, i, s, t, dt, torque, wheel_torques),
    }?)
}

fn body_omega<T: Real>(
    b: &Body<T>,
    q: UnitQuat<T>,
    omega: Vec3<T>,
    ws: [T; GYRO_MAX_WHEELS],
) -> Result<Plain<T>, gyro_status> {
    Ok(match b {
        Body::W0(g) => omega_n(g, q, omega, ws),
        Body::W1(g) => omega_n(g, q, omega, ws),
        Body::W2(g) => omega_n(g, q, omega, ws),
        Body::W3(g) => omega_n(g, q, omega, ws),
        Body::W4(g) => omega_n(g, q, omega, ws),
    }?)
}

/// Reads an optional array of `GYRO_MAX_WHEELS` values (zeros for NULL).
fn read_wheel_array<T: Real>(
    p: *const [T; GYRO_MAX_WHEELS],
) -> Result<[T; GYRO_MAX_WHEELS], gyro_status> {
    Ok(read_opt(p)?.unwrap_or([T::ZERO; GYRO_MAX_WHEELS]))
}

macro_rules! gyrostat_state_io {
    ($t:ty, $st:ident, $q:ident) => {
        impl $st {
            fn rust(&self) -> Result<(UnitQuat<$t>, Vec3<$t>, [$t; GYRO_MAX_WHEELS]), gyro_status> {
                Ok((
                    unit_in::<$t>(self.attitude)?,
                    <$t>::v_in(self.momentum),
                    self.wheel_speeds,
                ))
            }
            fn from_rust(p: Plain<$t>) -> Self {
                $st {
                    attitude: $q {
                        w: p.0.w,
                        x: p.0.x,
                        y: p.0.y,
                        z: p.0.z,
                    },
                    momentum: <$t>::v_out(p.1),
                    wheel_speeds: p.2,
                }
            }
        }
    };
}
gyrostat_state_io!(f32, gyro_gyrostat_state_f32, gyro_quat_f32);
gyrostat_state_io!(f64, gyro_gyrostat_state_f64, gyro_quat_f64);

/// Defines a gyrostat model: the inertia tensor with the wheels locked (kg·m², body frame) from
/// its `diagonal` `(I_xx, I_yy, I_zz)` and `off_diagonal` `(I_xy, I_xz, I_yz)` (may be NULL:
/// principal axes), and `n_wheels` (0 to `GYRO_MAX_WHEELS`) wheels from `wheels` (may be NULL
/// when `n_wheels` is 0).
///
/// Errors: `GYRO_NON_FINITE`, `GYRO_NON_PHYSICAL_INERTIA`, `GYRO_ZERO_NORM` (a wheel axis),
/// `GYRO_INVALID_ARGUMENT` (a wheel inertia ≤ 0, more than `GYRO_MAX_WHEELS` wheels).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type; `wheels` to `n_wheels` of them.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_gyrostat_f32_init(
    s: *mut gyro_gyrostat_f32,
    diagonal: *const gyro_vec3_f32,
    off_diagonal: *const gyro_vec3_f32,
    wheels: *const gyro_wheel_f32,
    n_wheels: u32,
) -> gyro_status {
    status((|| {
        let (w, n) = read_wheels(wheels, n_wheels, |w: gyro_wheel_f32| {
            (f32::v_in(w.axis), w.inertia)
        })?;
        body_init::<f32, _>(s, diagonal, off_diagonal, w.get(..n).unwrap_or(&[]))
    })())
}

/// Defines a gyrostat model, f64 (see `gyro_gyrostat_f32_init`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type; `wheels` to `n_wheels` of them.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_gyrostat_f64_init(
    s: *mut gyro_gyrostat_f64,
    diagonal: *const gyro_vec3_f64,
    off_diagonal: *const gyro_vec3_f64,
    wheels: *const gyro_wheel_f64,
    n_wheels: u32,
) -> gyro_status {
    status((|| {
        let (w, n) = read_wheels(wheels, n_wheels, |w: gyro_wheel_f64| {
            (f64::v_in(w.axis), w.inertia)
        })?;
        body_init::<f64, _>(s, diagonal, off_diagonal, w.get(..n).unwrap_or(&[]))
    })())
}

/// The state of attitude `q`, body rate `omega` (rad/s) and wheel speeds `wheel_speeds`
/// (rad/s relative to the body; may be NULL: at rest): `J = I·ω + Σ I_w Ω a`.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_gyrostat_f32_state_from_omega(
    s: *const gyro_gyrostat_f32,
    q: *const gyro_quat_f32,
    omega: *const gyro_vec3_f32,
    wheel_speeds: *const [f32; GYRO_MAX_WHEELS],
    out: *mut gyro_gyrostat_state_f32,
) -> gyro_status {
    status((|| {
        let b = state_ref(s)?;
        let q = unit_in::<f32>(read(q)?)?;
        let w = f32::v_in(read(omega)?);
        let ws = read_wheel_array(wheel_speeds)?;
        ok_ptr(out)?;
        let p = body_omega(b, q, w, ws)?;
        write(out, gyro_gyrostat_state_f32::from_rust(p));
        Ok(())
    })())
}

/// The state from attitude, body rate and wheel speeds, f64 (see
/// `gyro_gyrostat_f32_state_from_omega`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_gyrostat_f64_state_from_omega(
    s: *const gyro_gyrostat_f64,
    q: *const gyro_quat_f64,
    omega: *const gyro_vec3_f64,
    wheel_speeds: *const [f64; GYRO_MAX_WHEELS],
    out: *mut gyro_gyrostat_state_f64,
) -> gyro_status {
    status((|| {
        let b = state_ref(s)?;
        let q = unit_in::<f64>(read(q)?)?;
        let w = f64::v_in(read(omega)?);
        let ws = read_wheel_array(wheel_speeds)?;
        ok_ptr(out)?;
        let p = body_omega(b, q, w, ws)?;
        write(out, gyro_gyrostat_state_f64::from_rust(p));
        Ok(())
    })())
}

/// One step of length `dt` (s) from time `t` with integrator `integrator`
/// (`GYRO_INTEGRATOR_*`), the external body torque `torque` (N·m; may be NULL: none) and the
/// wheel torques `wheel_torques` (N·m; may be NULL: none) held over the step: `out` may be
/// `state`.
///
/// Errors: `GYRO_NON_FINITE`, `GYRO_INVALID_ARGUMENT` (`dt ≤ 0`, unknown integrator),
/// `GYRO_STEP_TOO_LONG` (`|ω|·dt > π`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_gyrostat_f32_step(
    s: *const gyro_gyrostat_f32,
    integrator: u32,
    state: *const gyro_gyrostat_state_f32,
    t: f32,
    dt: f32,
    torque: *const gyro_vec3_f32,
    wheel_torques: *const [f32; GYRO_MAX_WHEELS],
    out: *mut gyro_gyrostat_state_f32,
) -> gyro_status {
    status((|| {
        let b = state_ref(s)?;
        let x = read(state)?.rust()?;
        let tau = read_opt(torque)?.map_or(Vec3::new(0.0, 0.0, 0.0), f32::v_in);
        let wt = read_wheel_array(wheel_torques)?;
        ok_ptr(out)?;
        let p = body_step(b, integrator, x, t, dt, tau, wt)?;
        write(out, gyro_gyrostat_state_f32::from_rust(p));
        Ok(())
    })())
}

/// One gyrostat step, f64 (see `gyro_gyrostat_f32_step`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_gyrostat_f64_step(
    s: *const gyro_gyrostat_f64,
    integrator: u32,
    state: *const gyro_gyrostat_state_f64,
    t: f64,
    dt: f64,
    torque: *const gyro_vec3_f64,
    wheel_torques: *const [f64; GYRO_MAX_WHEELS],
    out: *mut gyro_gyrostat_state_f64,
) -> gyro_status {
    status((|| {
        let b = state_ref(s)?;
        let x = read(state)?.rust()?;
        let tau = read_opt(torque)?.map_or(Vec3::new(0.0, 0.0, 0.0), f64::v_in);
        let wt = read_wheel_array(wheel_torques)?;
        ok_ptr(out)?;
        let p = body_step(b, integrator, x, t, dt, tau, wt)?;
        write(out, gyro_gyrostat_state_f64::from_rust(p));
        Ok(())
    })())
}

// --- Estimator ---------------------------------------------------------------------------------

/// Words of `gyro_estimator_f32`'s storage.
pub const GYRO_ESTIMATOR_F32_WORDS: usize = 139;
/// Words of `gyro_estimator_f64`'s storage.
pub const GYRO_ESTIMATOR_F64_WORDS: usize = 274;

/// The attitude and gyro-bias estimator, f32 (`Estimator`, the library's default parameters).
/// Contents private.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct gyro_estimator_f32 {
    _tag: u32,
    _storage: [u64; GYRO_ESTIMATOR_F32_WORDS],
}

/// The attitude and gyro-bias estimator, f64 (see `gyro_estimator_f32`).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct gyro_estimator_f64 {
    _tag: u32,
    _storage: [u64; GYRO_ESTIMATOR_F64_WORDS],
}

slot!(gyro_estimator_f32, Estimator<f32>, 0x6779_0401);
slot!(gyro_estimator_f64, Estimator<f64>, 0x6779_0402);

/// Items and their source text (`$name`), for cbindgen, which does not expand macros: the
/// header test hands it the text of the items a macro made (`tests/header.rs`).
macro_rules! with_source {
    ($name:ident, $($item:tt)*) => {
        $($item)*
        #[doc(hidden)]
        pub const $name: &str = stringify!($($item)*);
    };
}

/// The library's rule of a `GYRO_RATE_RULE_*` code other than `GYRO_RATE_RULE_DEFAULT`.
fn rate_rule_of(code: u32) -> Option<RateRule> {
    match code {
        GYRO_RATE_RULE_TRAPEZOID => Some(RateRule::Trapezoid),
        GYRO_RATE_RULE_MAGNUS4 => Some(RateRule::Magnus4),
        GYRO_RATE_RULE_CF4 => Some(RateRule::Cf4),
        _ => None,
    }
}

/// The `GYRO_RATE_RULE_*` code of a rule.
fn rate_rule_code(rule: RateRule) -> u32 {
    match rule {
        RateRule::Trapezoid => GYRO_RATE_RULE_TRAPEZOID,
        RateRule::Magnus4 => GYRO_RATE_RULE_MAGNUS4,
        RateRule::Cf4 => GYRO_RATE_RULE_CF4,
    }
}

/// The C parameter struct of one float width and its conversions to and from `Params`: the
/// choices (frame, gains, mode, rate rule) as `uint32_t` codes, then every numeric parameter of
/// the library's table (`gyrostat::estimator_parameters!`), in its order, under its flat name.
macro_rules! c_params_struct {
    ($t:ty, $c:ident, $source:ident, [$(#[$doc:meta])*],
        [$( $(#[$m:meta])* $flat:ident; )*]) => {
        with_source! { $source,
            $(#[$doc])*
            #[repr(C)]
            #[derive(Clone, Copy, Debug, Default, PartialEq)]
            pub struct $c {
                /// The earth frame of the attitude: `GYRO_FRAME_ENU` or `GYRO_FRAME_NED`.
                pub frame: u32,
                /// 0: Kalman gains from the covariance (the default); 1: complementary gains,
                /// the heading corrected with the first-order gain
                /// `1 − exp(−dt/heading_time_constant)`.
                pub fixed_gains: u32,
                /// `τ` (s) of the heading correction with `fixed_gains` 1 (ignored otherwise).
                pub heading_time_constant: $t,
                /// `GYRO_MODE_FULL` (the default) or `GYRO_MODE_LIGHT`.
                pub mode: u32,
                /// The time (s) between two corrections with `mode` `GYRO_MODE_LIGHT` (ignored
                /// otherwise; the defaults hold 0.025).
                pub correction_period: $t,
                /// How rate samples become a step's rotation: `GYRO_RATE_RULE_DEFAULT` (the
                /// library's rule for the other choices; the defaults hold it),
                /// `GYRO_RATE_RULE_TRAPEZOID`, `GYRO_RATE_RULE_MAGNUS4` or `GYRO_RATE_RULE_CF4`
                /// (the library's `Params::rate_rule`, named `trapezoid`, `magnus4`, `cf4` in
                /// the parameter file and Python).
                pub rate_rule: u32,
                $(
                    $(#[$m])*
                    pub $flat: $t,
                )*
            }
        }

        impl $c {
            /// The library's parameters of these (`GYRO_INVALID_ARGUMENT` for an unknown
            /// frame, gains, mode or rate rule code).
            #[doc(hidden)]
            pub fn to_params(self) -> Result<Params<$t>, gyro_status> {
                let frame = match self.frame {
                    GYRO_FRAME_ENU => EarthFrame::Enu,
                    GYRO_FRAME_NED => EarthFrame::Ned,
                    _ => return Err(GYRO_INVALID_ARGUMENT),
                };
                let gains = match self.fixed_gains {
                    0 => Gains::Kalman,
                    1 => Gains::Fixed {
                        heading_time_constant: self.heading_time_constant,
                    },
                    _ => return Err(GYRO_INVALID_ARGUMENT),
                };
                let mode = match self.mode {
                    GYRO_MODE_FULL => Mode::Full,
                    GYRO_MODE_LIGHT => Mode::Light {
                        correction_period: self.correction_period,
                    },
                    _ => return Err(GYRO_INVALID_ARGUMENT),
                };
                let p = Params::from_values(frame, gains, mode, [$(self.$flat),*]);
                let rate_rule = match self.rate_rule {
                    GYRO_RATE_RULE_DEFAULT => p.rate_rule,
                    code => rate_rule_of(code).ok_or(GYRO_INVALID_ARGUMENT)?,
                };
                Ok(Params { rate_rule, ..p })
            }

            /// The numeric parameter `i` of the table (the order of `Params::NAMES`).
            fn numeric_mut(&mut self, i: usize) -> Option<&mut $t> {
                [$(&mut self.$flat),*].into_iter().nth(i)
            }

            /// The C struct of the library's parameters `p` (their rate rule as
            /// `GYRO_RATE_RULE_DEFAULT` when it is the library's rule for their other choices).
            #[doc(hidden)]
            pub fn from_params(p: &Params<$t>) -> Self {
                let (fixed_gains, heading_time_constant) = match p.gains {
                    Gains::Kalman => (0, 0.0),
                    Gains::Fixed {
                        heading_time_constant,
                    } => (1, heading_time_constant),
                };
                let (mode, correction_period) = match p.mode {
                    Mode::Full => (GYRO_MODE_FULL, <$t>::from_f64(Mode::<$t>::LIGHT_PERIOD)),
                    Mode::Light { correction_period } => (GYRO_MODE_LIGHT, correction_period),
                };
                let frame = match p.frame {
                    EarthFrame::Enu => GYRO_FRAME_ENU,
                    EarthFrame::Ned => GYRO_FRAME_NED,
                };
                // The library's rule for these choices is written as the default code, so
                // that a change of `mode` keeps following the library.
                let default_rule = Params::from_values(p.frame, p.gains, p.mode, p.values()).rate_rule;
                let rate_rule = if p.rate_rule == default_rule {
                    GYRO_RATE_RULE_DEFAULT
                } else {
                    rate_rule_code(p.rate_rule)
                };
                let [$($flat),*] = p.values();
                $c {
                    frame,
                    fixed_gains,
                    heading_time_constant,
                    mode,
                    correction_period,
                    rate_rule,
                    $($flat,)*
                }
            }
        }
    };
}

/// The callback of `gyrostat::estimator_parameters!`: the f32 and f64 parameter structs.
macro_rules! c_params {
    ($( $(#[$m:meta])* $flat:ident $(@ $g:ident . $f:ident)? : $d:expr, $dom:ident; )*) => {
        c_params_struct!(
            f32,
            gyro_estimator_params_f32,
            ESTIMATOR_PARAMS_F32_SOURCE,
            [
                /// The estimator's parameters, f32 (SI units, angles in rad): the library's
                /// `Params` field for field, generated from its parameter table
                /// (`gyrostat::estimator_parameters!`; group fields flattened, `field.norm` is
                /// `field_norm`). `gyro_estimator_f32_default_params` fills it with the
                /// defaults (each one's value is in the library's `Params` documentation).
            ],
            [$( $(#[$m])* $flat; )*]
        );
        c_params_struct!(
            f64,
            gyro_estimator_params_f64,
            ESTIMATOR_PARAMS_F64_SOURCE,
            [
                /// The estimator's parameters, f64 (see `gyro_estimator_params_f32`).
                /// `gyro_estimator_f64_default_params` fills it with the defaults.
            ],
            [$( $(#[$m])* $flat; )*]
        );
    };
}

gyrostat::estimator_parameters!(c_params);

/// The longest parameter name `gyro_estimator_params_*_set` reads (bytes before the NUL).
const PARAM_NAME_MAX: usize = 64;

/// Sets the numeric parameter named by the C string `name` (a name of the parameter file).
fn params_set<P, T>(
    params: *mut P,
    name: *const c_char,
    value: T,
    slot: fn(&mut P, usize) -> Option<&mut T>,
) -> gyro_status {
    status((|| {
        ok_ptr(name)?;
        ok_ptr(params.cast_const())?;
        let p = name.cast::<u8>();
        let mut buf = [0u8; PARAM_NAME_MAX];
        let mut len = None;
        for (i, b) in buf.iter_mut().enumerate() {
            // SAFETY: the bytes up to the terminating NUL are readable (a C string); the loop
            // stops at it.
            let c = unsafe { p.add(i).read() };
            if c == 0 {
                len = Some(i);
                break;
            }
            *b = c;
        }
        let bytes = buf
            .get(..len.ok_or(GYRO_INVALID_ARGUMENT)?)
            .ok_or(GYRO_INVALID_ARGUMENT)?;
        let text = core::str::from_utf8(bytes).map_err(|_| GYRO_INVALID_ARGUMENT)?;
        let i = Params::<f64>::NAMES
            .iter()
            .position(|n| *n == text)
            .ok_or(GYRO_INVALID_ARGUMENT)?;
        // SAFETY: checked non-null and aligned; the caller passes a valid struct.
        let params = unsafe { &mut *params };
        *slot(params, i).ok_or(GYRO_INVALID_ARGUMENT)? = value;
        Ok(())
    })())
}

/// Sets the numeric parameter `name` of `params` to `value`: `name` is its name in the
/// parameter file (`"gyro_noise_density"`, `"field.norm"`, ...; the library's `Params::NAMES`),
/// the same field as the struct's flat name (`field_norm`). Nothing is checked but the name:
/// `gyro_estimator_f32_init_params` checks the values.
///
/// Errors: `GYRO_INVALID_ARGUMENT` for an unknown name (or one longer than 63 bytes).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type; `name` is NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_estimator_params_f32_set(
    params: *mut gyro_estimator_params_f32,
    name: *const c_char,
    value: f32,
) -> gyro_status {
    params_set(params, name, value, gyro_estimator_params_f32::numeric_mut)
}

/// Sets the numeric parameter `name` of `params` to `value`, f64 (see
/// `gyro_estimator_params_f32_set`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type; `name` is NUL-terminated.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_estimator_params_f64_set(
    params: *mut gyro_estimator_params_f64,
    name: *const c_char,
    value: f64,
) -> gyro_status {
    params_set(params, name, value, gyro_estimator_params_f64::numeric_mut)
}

fn est_init<T: CFloat, S: Slot<Inner = Estimator<T>>>(s: *mut S, frame: u32) -> gyro_status {
    status((|| {
        let frame = match frame {
            GYRO_FRAME_ENU => EarthFrame::Enu,
            GYRO_FRAME_NED => EarthFrame::Ned,
            _ => return Err(GYRO_INVALID_ARGUMENT),
        };
        init(
            s,
            Estimator::try_new(Params::defaults_of(frame, Mode::Full))?,
        )
    })())
}

fn sensor(u: SensorUse) -> u32 {
    match u {
        SensorUse::Used => GYRO_SENSOR_USED,
        SensorUse::Absent => GYRO_SENSOR_ABSENT,
        SensorUse::NonFinite => GYRO_SENSOR_NON_FINITE,
        SensorUse::Saturated => GYRO_SENSOR_SATURATED,
        SensorUse::Disturbed => GYRO_SENSOR_DISTURBED,
        SensorUse::Zero => GYRO_SENSOR_ZERO,
    }
}

fn outcome(o: Outcome) -> gyro_estimator_outcome {
    gyro_estimator_outcome {
        gyro_saturated: u32::from(o.gyro_saturated),
        accel: sensor(o.accel),
        mag: sensor(o.mag),
        at_rest: u32::from(o.at_rest),
        initialized: u32::from(o.initialized),
    }
}

fn est_update<T: CFloat, S: Slot<Inner = Estimator<T>>>(
    s: *mut S,
    gyro: *const T::V,
    accel: *const T::V,
    mag: *const T::V,
    dt: T,
    out: *mut gyro_estimator_outcome,
) -> gyro_status {
    status((|| {
        let g = T::v_in(read(gyro)?);
        let a = T::v_in(read(accel)?);
        let m = read_opt(mag)?.map(T::v_in);
        ok_opt(out)?;
        let o = state(s)?.update(g, a, m, dt)?;
        write(out, outcome(o));
        Ok(())
    })())
}

fn est_attitude<T: CFloat, S: Slot<Inner = Estimator<T>>>(
    s: *const S,
    attitude: *mut T::Q,
    bias: *mut T::V,
) -> gyro_status {
    status((|| {
        ok_opt(attitude)?;
        ok_opt(bias)?;
        let e = state_ref(s)?;
        write(attitude, T::q_out(e.attitude()));
        write(bias, T::v_out(e.bias()));
        Ok(())
    })())
}

/// Starts an estimator in earth frame `frame` (`GYRO_FRAME_ENU` or `GYRO_FRAME_NED`) with the
/// library's default parameters; it waits for its first usable accelerometer sample.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_estimator_f32_init(
    s: *mut gyro_estimator_f32,
    frame: u32,
) -> gyro_status {
    est_init::<f32, _>(s, frame)
}

/// Starts an estimator, f64 (see `gyro_estimator_f32_init`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_estimator_f64_init(
    s: *mut gyro_estimator_f64,
    frame: u32,
) -> gyro_status {
    est_init::<f64, _>(s, frame)
}

/// One update: the gyro rate `gyro` (rad/s), the specific force `accel` (m/s²) and, for a 9D
/// update, the magnetic field `mag` (any unit; NULL for a 6D update), all in the sensor frame,
/// `dt` (s) since the previous sample. `*out` (may be NULL) says what each sample did; a bad
/// accelerometer or magnetometer sample is reported there, not as an error.
///
/// Errors (the sample is ignored, the state unchanged): `GYRO_NON_FINITE` (gyro); once the
/// attitude is initialised, `GYRO_INVALID_ARGUMENT` (`dt` not finite and positive, or above
/// 1000 s) and `GYRO_STEP_TOO_LONG`. Until then no sample propagates and `dt` is not checked
/// (the first sample of a log has no step: pass any value).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_estimator_f32_update(
    s: *mut gyro_estimator_f32,
    gyro: *const gyro_vec3_f32,
    accel: *const gyro_vec3_f32,
    mag: *const gyro_vec3_f32,
    dt: f32,
    out: *mut gyro_estimator_outcome,
) -> gyro_status {
    est_update::<f32, _>(s, gyro, accel, mag, dt, out)
}

/// One estimator update, f64 (see `gyro_estimator_f32_update`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_estimator_f64_update(
    s: *mut gyro_estimator_f64,
    gyro: *const gyro_vec3_f64,
    accel: *const gyro_vec3_f64,
    mag: *const gyro_vec3_f64,
    dt: f64,
    out: *mut gyro_estimator_outcome,
) -> gyro_status {
    est_update::<f64, _>(s, gyro, accel, mag, dt, out)
}

/// The estimated attitude (sensor → earth; may be NULL) and gyro bias (rad/s, sensor frame;
/// may be NULL).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_estimator_f32_attitude(
    s: *const gyro_estimator_f32,
    attitude: *mut gyro_quat_f32,
    bias: *mut gyro_vec3_f32,
) -> gyro_status {
    est_attitude::<f32, _>(s, attitude, bias)
}

/// The estimated attitude and gyro bias, f64 (see `gyro_estimator_f32_attitude`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_estimator_f64_attitude(
    s: *const gyro_estimator_f64,
    attitude: *mut gyro_quat_f64,
    bias: *mut gyro_vec3_f64,
) -> gyro_status {
    est_attitude::<f64, _>(s, attitude, bias)
}

/// The library's default estimator parameters (ENU, Kalman gains, the full mode and its rate
/// rule as `GYRO_RATE_RULE_DEFAULT`; tuned on BROAD without per-recording tuning) in `out`, to
/// adjust before `gyro_estimator_f32_init_params`.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_estimator_f32_default_params(
    out: *mut gyro_estimator_params_f32,
) -> gyro_status {
    status((|| {
        ok_ptr(out)?;
        write(
            out,
            gyro_estimator_params_f32::from_params(&Params::default()),
        );
        Ok(())
    })())
}

/// The default estimator parameters, f64 (see `gyro_estimator_f32_default_params`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_estimator_f64_default_params(
    out: *mut gyro_estimator_params_f64,
) -> gyro_status {
    status((|| {
        ok_ptr(out)?;
        write(
            out,
            gyro_estimator_params_f64::from_params(&Params::default()),
        );
        Ok(())
    })())
}

/// Starts an estimator with the parameters `params`.
///
/// Errors: `GYRO_NON_FINITE` for a NaN parameter (infinite ranges are allowed);
/// `GYRO_INVALID_ARGUMENT` for a negative one, a zero time constant that divides, or an
/// unknown `frame`, `fixed_gains`, `mode` or `rate_rule`.
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_estimator_f32_init_params(
    s: *mut gyro_estimator_f32,
    params: *const gyro_estimator_params_f32,
) -> gyro_status {
    status((|| {
        let p = read(params)?.to_params()?;
        init(s, Estimator::try_new(p)?)
    })())
}

/// Starts an estimator with the parameters `params`, f64 (see
/// `gyro_estimator_f32_init_params`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_estimator_f64_init_params(
    s: *mut gyro_estimator_f64,
    params: *const gyro_estimator_params_f64,
) -> gyro_status {
    status((|| {
        let p = read(params)?.to_params()?;
        init(s, Estimator::try_new(p)?)
    })())
}

/// Storage sizes of the Rust states (bytes), for the tests that check the header's words leave
/// room on every target.
#[doc(hidden)]
pub fn state_sizes() -> [(usize, usize); 11] {
    [
        (
            size_of::<Inc<f32>>(),
            size_of::<gyro_increment_integrator_f32>(),
        ),
        (
            size_of::<Inc<f64>>(),
            size_of::<gyro_increment_integrator_f64>(),
        ),
        (
            size_of::<IncrementIntegrator<Q30, CarriedAttitude<30>>>(),
            size_of::<gyro_increment_integrator_q30>(),
        ),
        (
            size_of::<(RawScale<Q30>, IncrementQuantizer<30>)>(),
            size_of::<gyro_increment_quantizer_q30>(),
        ),
        (
            size_of::<Rate<f32>>(),
            size_of::<gyro_rate_integrator_f32>(),
        ),
        (
            size_of::<Rate<f64>>(),
            size_of::<gyro_rate_integrator_f64>(),
        ),
        (size_of::<Body<f32>>(), size_of::<gyro_gyrostat_f32>()),
        (size_of::<Body<f64>>(), size_of::<gyro_gyrostat_f64>()),
        (size_of::<Estimator<f32>>(), size_of::<gyro_estimator_f32>()),
        (size_of::<Estimator<f64>>(), size_of::<gyro_estimator_f64>()),
        (0, 0),
    ]
}
