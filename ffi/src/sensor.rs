//! The sensor front end from C (`gyrostat::sensor`): the sample clocks with their first-sample
//! and gap policy, the clip guard of raw `int16_t` registers, the raw LSB scale, the
//! calibration models and the axis remap of a mounting. The conventions are the interface's
//! (see the crate docs): every function returns a `gyro_status`, outputs are written only on
//! `GYRO_OK`, states are plain structs written by their `_init` function.
//!
//! The order of a sample through the front end, as the `estimate` tool's loop
//! (`gyrostat-pipeline`) and the C driver of the cross-face test (`tests/c/faces.c`) run it:
//! clock (`gyro_sample_clock_*_interval`: the step, or the first sample with none) → raw scale
//! and clip guard (register readings) → calibration → axis remap → estimator or integrator.

use gyrostat::Axis;
use gyrostat::sensor::{
    AxisRemap, ClipGuard, ClipLimit, ClipPolicy, InertialCalibration, Interval,
    MagnetometerCalibration, MicrosClock, RawFormat, RawScale, SampleClock,
};

use super::*;

/// `gyro_sample_clock_*_interval`: the first time stamp (or the first after a restart): no
/// step; `*dt` is NaN, which the estimator's update takes as "no step" (its first-sample rule:
/// until the attitude is initialised no sample propagates and the step is not checked).
pub const GYRO_INTERVAL_FIRST: u32 = 0;
/// A regular step `0 < dt ≤ gap_factor · nominal`: `*dt` is the elapsed time.
pub const GYRO_INTERVAL_STEP: u32 = 1;
/// A step longer than `gap_factor · nominal` (samples were lost): `*dt` is the elapsed time;
/// the clock accepted the time stamp.
pub const GYRO_INTERVAL_GAP: u32 = 2;
/// The same time stamp as the previous accepted one (a duplicate row): `*dt` is 0; the clock
/// keeps its state.
pub const GYRO_INTERVAL_REPEATED: u32 = 3;
/// A time stamp before the previous accepted one: `*dt` is by how much (positive); the clock
/// keeps its state.
pub const GYRO_INTERVAL_BACKWARDS: u32 = 4;

/// `gyro_clip_guard_init`: the clipped reading reaches the core as it is.
pub const GYRO_CLIP_PASS: u32 = 0;
/// Each clipped axis is replaced by that axis's last unclipped reading (a rate hold).
pub const GYRO_CLIP_HOLD_LAST: u32 = 1;
/// A clipped reading is an error (the library's `Error::Clipped`).
pub const GYRO_CLIP_REJECT: u32 = 2;

/// A raw register reading of three axes (`int16_t`, the sensor's LSBs).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct gyro_vec3_i16 {
    /// x register.
    pub x: i16,
    /// y register.
    pub y: i16,
    /// z register.
    pub z: i16,
}

/// Words of `gyro_sample_clock_f32`'s storage.
pub const GYRO_SAMPLE_CLOCK_F32_WORDS: usize = 3;
/// Words of `gyro_sample_clock_f64`'s storage.
pub const GYRO_SAMPLE_CLOCK_F64_WORDS: usize = 5;
/// Words of `gyro_micros_clock`'s storage.
pub const GYRO_MICROS_CLOCK_WORDS: usize = 3;
/// Words of `gyro_clip_guard`'s storage.
pub const GYRO_CLIP_GUARD_WORDS: usize = 3;
/// Words of `gyro_inertial_calibration_f32`'s storage.
pub const GYRO_INERTIAL_CALIBRATION_F32_WORDS: usize = 12;
/// Words of `gyro_inertial_calibration_f64`'s storage.
pub const GYRO_INERTIAL_CALIBRATION_F64_WORDS: usize = 22;
/// Words of `gyro_mag_calibration_f32`'s storage.
pub const GYRO_MAG_CALIBRATION_F32_WORDS: usize = 12;
/// Words of `gyro_mag_calibration_f64`'s storage.
pub const GYRO_MAG_CALIBRATION_F64_WORDS: usize = 22;
/// Words of `gyro_axis_remap`'s storage.
pub const GYRO_AXIS_REMAP_WORDS: usize = 1;

/// A sample clock on time stamps in seconds, f32 (`SampleClock`): each time stamp becomes a
/// step, a gap, the first sample, a repeated or a backwards time stamp
/// (`GYRO_INTERVAL_*`). Contents private; write with `gyro_sample_clock_f32_init`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct gyro_sample_clock_f32 {
    _tag: u32,
    _storage: [u64; GYRO_SAMPLE_CLOCK_F32_WORDS],
}

/// A sample clock on time stamps in seconds, f64 (see `gyro_sample_clock_f32`).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct gyro_sample_clock_f64 {
    _tag: u32,
    _storage: [u64; GYRO_SAMPLE_CLOCK_F64_WORDS],
}

/// A sample clock on a free-running 32-bit microsecond counter that wraps (`MicrosClock`):
/// differences are taken modulo 2³², so a wrap between two samples is an ordinary step; a
/// wrapped difference of 2³¹ µs or more is a backwards time stamp.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct gyro_micros_clock {
    _tag: u32,
    _storage: [u64; GYRO_MICROS_CLOCK_WORDS],
}

/// A clip guard on a stream of raw `int16_t` readings (`ClipGuard`): the full scale, the
/// policy (`GYRO_CLIP_*`) and the last unclipped reading of each axis.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct gyro_clip_guard {
    _tag: u32,
    _storage: [u64; GYRO_CLIP_GUARD_WORDS],
}

/// A gyroscope or accelerometer calibration, f32 (`InertialCalibration`):
/// `corrected = M · diag(s) · (raw − b)`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct gyro_inertial_calibration_f32 {
    _tag: u32,
    _storage: [u64; GYRO_INERTIAL_CALIBRATION_F32_WORDS],
}

/// A gyroscope or accelerometer calibration, f64 (see `gyro_inertial_calibration_f32`).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct gyro_inertial_calibration_f64 {
    _tag: u32,
    _storage: [u64; GYRO_INERTIAL_CALIBRATION_F64_WORDS],
}

/// A magnetometer calibration, f32 (`MagnetometerCalibration`): `corrected = S · (raw − h)`,
/// soft-iron matrix `S`, hard-iron offset `h`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct gyro_mag_calibration_f32 {
    _tag: u32,
    _storage: [u64; GYRO_MAG_CALIBRATION_F32_WORDS],
}

/// A magnetometer calibration, f64 (see `gyro_mag_calibration_f32`).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct gyro_mag_calibration_f64 {
    _tag: u32,
    _storage: [u64; GYRO_MAG_CALIBRATION_F64_WORDS],
}

/// The axis remap of a sensor mounted on a board (`AxisRemap`): each body axis is a sensor
/// axis with a sign, a proper rotation.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct gyro_axis_remap {
    _tag: u32,
    _storage: [u64; GYRO_AXIS_REMAP_WORDS],
}

slot!(gyro_sample_clock_f32, SampleClock<f32>, 0x6779_0501);
slot!(gyro_sample_clock_f64, SampleClock<f64>, 0x6779_0502);
slot!(gyro_micros_clock, MicrosClock, 0x6779_0503);
slot!(gyro_clip_guard, ClipGuard, 0x6779_0504);
slot!(
    gyro_inertial_calibration_f32,
    InertialCalibration<f32>,
    0x6779_0505
);
slot!(
    gyro_inertial_calibration_f64,
    InertialCalibration<f64>,
    0x6779_0506
);
slot!(
    gyro_mag_calibration_f32,
    MagnetometerCalibration<f32>,
    0x6779_0507
);
slot!(
    gyro_mag_calibration_f64,
    MagnetometerCalibration<f64>,
    0x6779_0508
);
slot!(gyro_axis_remap, AxisRemap, 0x6779_0509);

/// The kind code and the duration of an interval (`nan` for the first sample, zero for a
/// repeated time stamp).
fn interval_out<D: Copy>(i: Interval<D>, zero: D, none: D) -> (u32, D) {
    match i {
        Interval::First => (GYRO_INTERVAL_FIRST, none),
        Interval::Step(d) => (GYRO_INTERVAL_STEP, d),
        Interval::Gap(d) => (GYRO_INTERVAL_GAP, d),
        Interval::Repeated => (GYRO_INTERVAL_REPEATED, zero),
        Interval::Backwards(d) => (GYRO_INTERVAL_BACKWARDS, d),
    }
}

// --- Sample clocks ---------------------------------------------------------------------------

fn clock_init<T: CFloat, S: Slot<Inner = SampleClock<T>>>(
    s: *mut S,
    nominal: T,
    gap_factor: T,
) -> gyro_status {
    status((|| {
        init(s, SampleClock::try_with_gap_factor(nominal, gap_factor)?)
    })())
}

fn clock_interval<T: CFloat, S: Slot<Inner = SampleClock<T>>>(
    s: *mut S,
    t: T,
    kind: *mut u32,
    dt: *mut T,
) -> gyro_status {
    status((|| {
        ok_ptr(kind)?;
        ok_ptr(dt)?;
        let i = state(s)?.interval(t)?;
        let (k, d) = interval_out(i, T::ZERO, T::from_f64(f64::NAN));
        write(kind, k);
        write(dt, d);
        Ok(())
    })())
}

fn clock_restart<T: CFloat, S: Slot<Inner = SampleClock<T>>>(
    s: *mut S,
    has_t: u32,
    t: T,
) -> gyro_status {
    status((|| {
        let start = if flag(has_t)? {
            if !t.is_finite() {
                return Err(GYRO_NON_FINITE);
            }
            Some(t)
        } else {
            None
        };
        state(s)?.restart(start);
        Ok(())
    })())
}

/// Starts a sample clock with nominal interval `nominal` (s) and gap factor `gap_factor` (an
/// elapsed time beyond `gap_factor · nominal` is a gap; the library's default is 5).
///
/// Errors: `GYRO_NON_FINITE` (a NaN or infinite argument); `GYRO_INVALID_ARGUMENT`
/// (`nominal ≤ 0`, `gap_factor < 1`, or a product that overflows).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_sample_clock_f32_init(
    s: *mut gyro_sample_clock_f32,
    nominal: f32,
    gap_factor: f32,
) -> gyro_status {
    clock_init::<f32, _>(s, nominal, gap_factor)
}

/// Starts a sample clock, f64 (see `gyro_sample_clock_f32_init`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_sample_clock_f64_init(
    s: *mut gyro_sample_clock_f64,
    nominal: f64,
    gap_factor: f64,
) -> gyro_status {
    clock_init::<f64, _>(s, nominal, gap_factor)
}

/// Classifies the time stamp `t` (s) against the last accepted one: `*kind` is a
/// `GYRO_INTERVAL_*` and `*dt` its duration (NaN for `GYRO_INTERVAL_FIRST`, 0 for
/// `GYRO_INTERVAL_REPEATED`). A first sample, a step or a gap accepts `t`; a repeated or
/// backwards time stamp leaves the clock as it was (skip the sample).
///
/// Errors: `GYRO_NON_FINITE` for a NaN or infinite `t` or an elapsed time that overflows
/// (the clock unchanged: a logger's glitch, which a caller may skip as a gap).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_sample_clock_f32_interval(
    s: *mut gyro_sample_clock_f32,
    t: f32,
    kind: *mut u32,
    dt: *mut f32,
) -> gyro_status {
    clock_interval::<f32, _>(s, t, kind, dt)
}

/// Classifies a time stamp, f64 (see `gyro_sample_clock_f32_interval`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_sample_clock_f64_interval(
    s: *mut gyro_sample_clock_f64,
    t: f64,
    kind: *mut u32,
    dt: *mut f64,
) -> gyro_status {
    clock_interval::<f64, _>(s, t, kind, dt)
}

/// Restarts the clock: with `has_t` 1 the next interval is measured from `t` (s), with
/// `has_t` 0 the next time stamp is a first sample again.
///
/// Errors: `GYRO_INVALID_ARGUMENT` (`has_t` not 0 or 1), `GYRO_NON_FINITE` (a NaN or infinite
/// `t` with `has_t` 1).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_sample_clock_f32_restart(
    s: *mut gyro_sample_clock_f32,
    has_t: u32,
    t: f32,
) -> gyro_status {
    clock_restart::<f32, _>(s, has_t, t)
}

/// Restarts the clock, f64 (see `gyro_sample_clock_f32_restart`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_sample_clock_f64_restart(
    s: *mut gyro_sample_clock_f64,
    has_t: u32,
    t: f64,
) -> gyro_status {
    clock_restart::<f64, _>(s, has_t, t)
}

/// Starts a microsecond-counter clock with nominal interval `nominal_us` µs and gap factor
/// `gap_factor`.
///
/// Errors: `GYRO_INVALID_ARGUMENT` (`nominal_us` or `gap_factor` 0, or a product of 2³¹ µs or
/// more, which could not be told from a backwards step).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_micros_clock_init(
    s: *mut gyro_micros_clock,
    nominal_us: u32,
    gap_factor: u32,
) -> gyro_status {
    status((|| init(s, MicrosClock::try_new(nominal_us, gap_factor)?))())
}

/// Classifies the counter value `t_us` (every value is a time stamp): `*kind` a
/// `GYRO_INTERVAL_*`, `*dt_us` its duration in µs (0 for a first sample or a repeated time
/// stamp).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_micros_clock_interval(
    s: *mut gyro_micros_clock,
    t_us: u32,
    kind: *mut u32,
    dt_us: *mut u32,
) -> gyro_status {
    status((|| {
        ok_ptr(kind)?;
        ok_ptr(dt_us)?;
        let (k, d) = interval_out(state(s)?.interval(t_us), 0, 0);
        write(kind, k);
        write(dt_us, d);
        Ok(())
    })())
}

/// Restarts the counter clock: with `has_t` 1 the next interval is measured from `t_us`, with
/// `has_t` 0 the next value is a first sample.
///
/// Errors: `GYRO_INVALID_ARGUMENT` (`has_t` not 0 or 1).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_micros_clock_restart(
    s: *mut gyro_micros_clock,
    has_t: u32,
    t_us: u32,
) -> gyro_status {
    status((|| {
        let start = flag(has_t)?.then_some(t_us);
        state(s)?.restart(start);
        Ok(())
    })())
}

// --- Raw registers: scale and clipping -------------------------------------------------------

/// Starts a clip guard: a reading `r` of an axis is clipped when `r ≥ limit` or `r ≤ −limit`
/// (so -32768 always is; `limit` 32767 is the register's own range), and `policy`
/// (`GYRO_CLIP_PASS`, `GYRO_CLIP_HOLD_LAST`, `GYRO_CLIP_REJECT`) decides what reaches the core.
///
/// Errors: `GYRO_INVALID_ARGUMENT` (`limit ≤ 0`, an unknown policy).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_clip_guard_init(
    s: *mut gyro_clip_guard,
    limit: i16,
    policy: u32,
) -> gyro_status {
    status((|| {
        let policy = match policy {
            GYRO_CLIP_PASS => ClipPolicy::Pass,
            GYRO_CLIP_HOLD_LAST => ClipPolicy::HoldLast,
            GYRO_CLIP_REJECT => ClipPolicy::Reject,
            _ => return Err(GYRO_INVALID_ARGUMENT),
        };
        init(s, ClipGuard::new(ClipLimit::try_new(limit)?, policy))
    })())
}

/// One raw reading through the guard: `*out` the reading the core gets (the clipped axes held
/// at their last unclipped value under `GYRO_CLIP_HOLD_LAST`; a clip before any unclipped
/// reading passes as it is), `*clipped` (may be NULL) the clipped axes of the original
/// reading as bits (1 x, 2 y, 4 z).
///
/// Errors: under `GYRO_CLIP_REJECT` a clipped reading is the library's `Error::Clipped` (its
/// status code; the guard unchanged).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_clip_guard_filter(
    s: *mut gyro_clip_guard,
    raw: *const gyro_vec3_i16,
    out: *mut gyro_vec3_i16,
    clipped: *mut u32,
) -> gyro_status {
    status((|| {
        let r = read(raw)?;
        ok_ptr(out)?;
        ok_opt(clipped)?;
        let (o, c) = state(s)?.filter([r.x, r.y, r.z])?;
        let [x, y, z] = o;
        write(out, gyro_vec3_i16 { x, y, z });
        let [cx, cy, cz] = c.axes;
        write(
            clipped,
            u32::from(cx) | u32::from(cy) << 1 | u32::from(cz) << 2,
        );
        Ok(())
    })())
}

fn raw_scale<T: CFloat + RawFormat>(
    raw: *const gyro_vec3_i16,
    lsb: T,
    out: *mut T::V,
) -> gyro_status {
    status((|| {
        let r = read(raw)?;
        ok_ptr(out)?;
        write(
            out,
            T::v_out(RawScale::<T>::try_new(lsb.to_f64())?.apply([r.x, r.y, r.z])),
        );
        Ok(())
    })())
}

/// A raw reading as a physical value: `out = raw · lsb` per axis (`lsb` the value of one LSB:
/// rad/s, m/s², µT, … per count), one rounding.
///
/// Errors: `GYRO_NON_FINITE`, `GYRO_INVALID_ARGUMENT` (`lsb ≤ 0`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_raw_scale_f32(
    raw: *const gyro_vec3_i16,
    lsb: f32,
    out: *mut gyro_vec3_f32,
) -> gyro_status {
    raw_scale::<f32>(raw, lsb, out)
}

/// A raw reading as a physical value, f64 (see `gyro_raw_scale_f32`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_raw_scale_f64(
    raw: *const gyro_vec3_i16,
    lsb: f64,
    out: *mut gyro_vec3_f64,
) -> gyro_status {
    raw_scale::<f64>(raw, lsb, out)
}

// --- Calibration -----------------------------------------------------------------------------

fn inertial_init<T: CFloat, S: Slot<Inner = InertialCalibration<T>>>(
    s: *mut S,
    misalignment: *const T::M,
    scale: *const T::V,
    bias: *const T::V,
) -> gyro_status {
    status((|| {
        let m = T::m_in(read(misalignment)?);
        let (k, b) = (T::v_in(read(scale)?), T::v_in(read(bias)?));
        init(s, InertialCalibration::try_new(m, k, b)?)
    })())
}

fn inertial_apply<T: CFloat, S: Slot<Inner = InertialCalibration<T>>>(
    s: *const S,
    raw: *const T::V,
    out: *mut T::V,
) -> gyro_status {
    status((|| {
        let r = T::v_in(read(raw)?);
        ok_ptr(out)?;
        write(out, T::v_out(state_ref(s)?.try_apply(r)?));
        Ok(())
    })())
}

fn mag_init<T: CFloat, S: Slot<Inner = MagnetometerCalibration<T>>>(
    s: *mut S,
    soft_iron: *const T::M,
    hard_iron: *const T::V,
) -> gyro_status {
    status((|| {
        let m = T::m_in(read(soft_iron)?);
        let h = T::v_in(read(hard_iron)?);
        init(s, MagnetometerCalibration::try_new(m, h)?)
    })())
}

fn mag_apply<T: CFloat, S: Slot<Inner = MagnetometerCalibration<T>>>(
    s: *const S,
    raw: *const T::V,
    out: *mut T::V,
) -> gyro_status {
    status((|| {
        let r = T::v_in(read(raw)?);
        ok_ptr(out)?;
        write(out, T::v_out(state_ref(s)?.try_apply(r)?));
        Ok(())
    })())
}

/// Starts a gyroscope or accelerometer calibration `corrected = M · diag(s) · (raw − b)`:
/// misalignment `M` (row-major), per-axis scale `s`, bias `b` (in the raw reading's unit).
///
/// Errors: `GYRO_NON_FINITE`; `GYRO_INVALID_ARGUMENT` (a scale ≤ 0, `det M ≤ 0`);
/// `GYRO_SINGULAR` (`M·diag(s)` not invertible or worse conditioned than 100).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_inertial_calibration_f32_init(
    s: *mut gyro_inertial_calibration_f32,
    misalignment: *const gyro_mat3_f32,
    scale: *const gyro_vec3_f32,
    bias: *const gyro_vec3_f32,
) -> gyro_status {
    inertial_init::<f32, _>(s, misalignment, scale, bias)
}

/// Starts a gyroscope or accelerometer calibration, f64 (see
/// `gyro_inertial_calibration_f32_init`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_inertial_calibration_f64_init(
    s: *mut gyro_inertial_calibration_f64,
    misalignment: *const gyro_mat3_f64,
    scale: *const gyro_vec3_f64,
    bias: *const gyro_vec3_f64,
) -> gyro_status {
    inertial_init::<f64, _>(s, misalignment, scale, bias)
}

/// `*out = M · diag(s) · (*raw − b)`.
///
/// Errors: `GYRO_NON_FINITE` (a NaN or infinite reading, or a result that overflows).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_inertial_calibration_f32_apply(
    s: *const gyro_inertial_calibration_f32,
    raw: *const gyro_vec3_f32,
    out: *mut gyro_vec3_f32,
) -> gyro_status {
    inertial_apply::<f32, _>(s, raw, out)
}

/// Applies a gyroscope or accelerometer calibration, f64 (see
/// `gyro_inertial_calibration_f32_apply`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_inertial_calibration_f64_apply(
    s: *const gyro_inertial_calibration_f64,
    raw: *const gyro_vec3_f64,
    out: *mut gyro_vec3_f64,
) -> gyro_status {
    inertial_apply::<f64, _>(s, raw, out)
}

/// Starts a magnetometer calibration `corrected = S · (raw − h)`: soft-iron matrix `S`
/// (row-major), hard-iron offset `h` (in the raw reading's unit).
///
/// Errors: `GYRO_NON_FINITE`; `GYRO_INVALID_ARGUMENT` (`det S ≤ 0`); `GYRO_SINGULAR` (`S` not
/// invertible or worse conditioned than 100).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_mag_calibration_f32_init(
    s: *mut gyro_mag_calibration_f32,
    soft_iron: *const gyro_mat3_f32,
    hard_iron: *const gyro_vec3_f32,
) -> gyro_status {
    mag_init::<f32, _>(s, soft_iron, hard_iron)
}

/// Starts a magnetometer calibration, f64 (see `gyro_mag_calibration_f32_init`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_mag_calibration_f64_init(
    s: *mut gyro_mag_calibration_f64,
    soft_iron: *const gyro_mat3_f64,
    hard_iron: *const gyro_vec3_f64,
) -> gyro_status {
    mag_init::<f64, _>(s, soft_iron, hard_iron)
}

/// `*out = S · (*raw − h)`.
///
/// Errors: `GYRO_NON_FINITE` (a NaN or infinite reading, or a result that overflows).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_mag_calibration_f32_apply(
    s: *const gyro_mag_calibration_f32,
    raw: *const gyro_vec3_f32,
    out: *mut gyro_vec3_f32,
) -> gyro_status {
    mag_apply::<f32, _>(s, raw, out)
}

/// Applies a magnetometer calibration, f64 (see `gyro_mag_calibration_f32_apply`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_mag_calibration_f64_apply(
    s: *const gyro_mag_calibration_f64,
    raw: *const gyro_vec3_f64,
    out: *mut gyro_vec3_f64,
) -> gyro_status {
    mag_apply::<f64, _>(s, raw, out)
}

// --- Mounting ----------------------------------------------------------------------------------

/// Starts an axis remap: body axis `i` (x, y, z) is sensor axis `source[i]` (0 x, 1 y, 2 z),
/// negated when `negate[i]` is 1: `body[i] = ±sensor[source[i]]`.
///
/// Errors: `GYRO_INVALID_ARGUMENT` (an index above 2, an axis used twice, a flag not 0 or 1);
/// `GYRO_NOT_ROTATION` (a reflection: the remap must be a proper rotation).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type; `source` and `negate` point
/// to three values each.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_axis_remap_init(
    s: *mut gyro_axis_remap,
    source: *const u32,
    negate: *const u32,
) -> gyro_status {
    status((|| {
        let axis = |i: u32| match i {
            0 => Ok(Axis::X),
            1 => Ok(Axis::Y),
            2 => Ok(Axis::Z),
            _ => Err(GYRO_INVALID_ARGUMENT),
        };
        // Three values each: read as arrays (the alignment of one value).
        let [a, b, c] = read(source.cast::<[u32; 3]>())?;
        let [na, nb, nc] = read(negate.cast::<[u32; 3]>())?;
        let source = [axis(a)?, axis(b)?, axis(c)?];
        let negate = [flag(na)?, flag(nb)?, flag(nc)?];
        init(s, AxisRemap::try_new(source, negate)?)
    })())
}

fn remap_apply<T: CFloat>(
    s: *const gyro_axis_remap,
    sensor: *const T::V,
    body: *mut T::V,
) -> gyro_status {
    status((|| {
        let v = T::v_in(read(sensor)?);
        ok_ptr(body)?;
        write(body, T::v_out(state_ref(s)?.apply(v)));
        Ok(())
    })())
}

/// A sensor-frame vector in the body frame: `body[i] = ±sensor[source[i]]` (exact: no
/// rounding).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_axis_remap_apply_f32(
    s: *const gyro_axis_remap,
    sensor: *const gyro_vec3_f32,
    body: *mut gyro_vec3_f32,
) -> gyro_status {
    remap_apply::<f32>(s, sensor, body)
}

/// A sensor-frame vector in the body frame, f64 (see `gyro_axis_remap_apply_f32`).
///
/// # Safety
/// Every pointer is NULL or points to a valid object of its type.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn gyro_axis_remap_apply_f64(
    s: *const gyro_axis_remap,
    sensor: *const gyro_vec3_f64,
    body: *mut gyro_vec3_f64,
) -> gyro_status {
    remap_apply::<f64>(s, sensor, body)
}
