//! The C interface against the Rust API.
//!
//! `tests/c/scenario.c` calls every function family of `include/gyrostat.h` on inputs drawn
//! from a xorshift32 sequence (no input repeats) and prints each result as hexadecimal bits.
//! This file computes the same lines with gyrostat's Rust API (the library called directly, not
//! through the C interface), then:
//! - `host_c_program_matches_the_rust_api` builds the scenario with the host C compiler (`cc`)
//!   against the host static library (`cargo build --release -p gyrostat-ffi`), runs it and
//!   requires every line to be equal: the C interface adds no rounding and reports every error
//!   with its status code;
//! - `firmware::*` (ignored; run by `.ci/run` after the bare-metal C program ran under QEMU)
//!   compares the QEMU outputs of the same scenario (`tests/c/Makefile`, Cortex-M4F and
//!   Cortex-M0) with the same lines.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

use gyrostat::dynamics::{Control, Gyrostat, Inertia, Integrator, State, Wheel};
use gyrostat::estimation::{EarthFrame, Estimator, Outcome, Params, RateRule, SensorUse};
use gyrostat::fixed::IncrementQuantizer;
use gyrostat::propagation::CarriedAttitude;
use gyrostat::propagation::{
    CompensatedAttitude, ConingRule, IncrementIntegrator, Normalization, RateIntegrator, RateMethod,
};
use gyrostat::real::{Fixed, Q30};
use gyrostat::rotation::{Euler, EulerSequence, EulerSolution, GimbalPolicy, Pole};
use gyrostat::sensor::RawScale;
use gyrostat::{Dcm, Error, Quat, Real, RotationVector, UnitQuat, Vec3};

/// The scenario's input sequence (the same xorshift32 as `scenario.c`).
struct Rng(u32);

impl Rng {
    fn next_u32(&mut self) -> u32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 17;
        self.0 ^= self.0 << 5;
        self.0
    }
    fn f32(&mut self) -> f32 {
        self.next_u32() as i32 as f32 * 2f32.powi(-31)
    }
    fn f64(&mut self) -> f64 {
        self.next_u32() as i32 as f64 * 2f64.powi(-31)
    }
    fn vec32(&mut self, s: f32, c: [f32; 3]) -> Vec3<f32> {
        let x = c[0] + self.f32() * s;
        let y = c[1] + self.f32() * s;
        let z = c[2] + self.f32() * s;
        Vec3::new(x, y, z)
    }
    fn vec64(&mut self, s: f64, c: [f64; 3]) -> Vec3<f64> {
        let x = c[0] + self.f64() * s;
        let y = c[1] + self.f64() * s;
        let z = c[2] + self.f64() * s;
        Vec3::new(x, y, z)
    }
    fn quat32(&mut self) -> Quat<f32> {
        let (w, x, y, z) = (self.f32(), self.f32(), self.f32(), self.f32());
        Quat::new(w, x, y, z)
    }
    fn quat64(&mut self) -> Quat<f64> {
        let (w, x, y, z) = (self.f64(), self.f64(), self.f64(), self.f64());
        Quat::new(w, x, y, z)
    }
    fn raw16(&mut self) -> i16 {
        (self.next_u32() as i32 >> 20) as i16
    }
}

/// The status code the C interface documents for each error (the header's `gyro_status`).
fn code(e: Error) -> u32 {
    match e {
        Error::NonFinite => 4,
        Error::ZeroNorm => 5,
        Error::NotUnit => 6,
        Error::NotRotation => 7,
        Error::Singular => 8,
        Error::NonPhysicalInertia => 9,
        Error::NotConverged => 10,
        Error::StepTooLong => 11,
        Error::InvalidArgument => 3,
        Error::OutOfRange => 12,
        Error::Clipped => 13,
    }
}
const BAD_POINTER: u32 = 1;
const NOT_INITIALIZED: u32 = 2;
const INVALID_ARGUMENT: u32 = 3;

/// Hexadecimal bits of the scenario's numbers.
trait Bits: Copy {
    fn hex(self) -> String;
}
impl Bits for f32 {
    fn hex(self) -> String {
        format!("{:08x}", self.to_bits())
    }
}
impl Bits for f64 {
    fn hex(self) -> String {
        format!("{:016x}", self.to_bits())
    }
}

/// The scenario's output lines.
#[derive(Default)]
struct Lines {
    text: String,
}

impl Lines {
    /// One line: a label, a status and, on success, the values (wrapped as `scenario.c` wraps:
    /// a new `+` line before a value that would start past column 216).
    fn put<T: Bits>(&mut self, label: &str, r: Result<Vec<T>, u32>) {
        let mut line = label.to_string();
        match r {
            Ok(values) => {
                line.push_str(" 00");
                for v in values {
                    if line.len() > 216 {
                        writeln!(self.text, "{line}").unwrap();
                        line = "+".to_string();
                    }
                    line.push(' ');
                    line.push_str(&v.hex());
                }
            }
            Err(c) => write!(line, " {c:02x}").unwrap(),
        }
        writeln!(self.text, "{line}").unwrap();
    }
    fn status(&mut self, label: &str, r: Result<(), u32>) {
        match r {
            Ok(()) => writeln!(self.text, "{label} 00").unwrap(),
            Err(c) => writeln!(self.text, "{label} {c:02x}").unwrap(),
        }
    }
    fn raw(&mut self, line: String) {
        writeln!(self.text, "{line}").unwrap();
    }
}

fn err<T>(r: Result<T, Error>) -> Result<T, u32> {
    r.map_err(code)
}

/// The C interface's quaternion input rule (see its crate docs): kept bit for bit within
/// `8·ε` of unit norm, normalised otherwise.
fn unit_in<T: Real>(q: Quat<T>) -> Result<UnitQuat<T>, Error> {
    let d = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z - T::ONE;
    if q.is_finite() && d.abs() <= T::from_f64(8.0) * T::EPSILON {
        Ok(UnitQuat::new_unchecked(q))
    } else {
        UnitQuat::try_new(q)
    }
}

fn q<T: Real>(u: UnitQuat<T>) -> Vec<T> {
    let q = u.into_quat();
    vec![q.w, q.x, q.y, q.z]
}

fn v<T: Real>(v: Vec3<T>) -> Vec<T> {
    vec![v.x, v.y, v.z]
}

fn m<T: Real>(u: UnitQuat<T>) -> Vec<T> {
    Dcm::from(u).into_matrix().m.into_iter().flatten().collect()
}

fn euler_line<T: Real + Bits>(l: &mut Lines, label: &str, s: Result<EulerSolution<T>, u32>) {
    match s {
        Err(c) => l.put::<T>(label, Err(c)),
        Ok(s) => {
            let (lock, sign, comb) = match s.singularity {
                None => (0i32, T::ZERO, T::ZERO),
                Some(g) => (
                    match g.pole {
                        Pole::Lower => -1,
                        Pole::Upper => 1,
                    },
                    g.sign,
                    g.combined_angle,
                ),
            };
            let mut line = format!("{label} 00");
            for a in s.euler.angles {
                write!(line, " {}", a.hex()).unwrap();
            }
            write!(
                line,
                " {} {:08x} {} {}",
                s.distance_to_pole.hex(),
                lock as u32,
                sign.hex(),
                comb.hex()
            )
            .unwrap();
            l.raw(line);
        }
    }
}

fn seq(s: &str) -> EulerSequence {
    EulerSequence::try_from_str(s).unwrap()
}

fn rotations(r: &mut Rng, l: &mut Lines) {
    for _ in 0..6 {
        let (r32, r64) = (r.quat32(), r.quat64());
        let (v32, v64) = (r.vec32(1.0, [0.0; 3]), r.vec64(1.0, [0.0; 3]));
        let q32 = UnitQuat::try_new(r32).unwrap();
        let q64 = UnitQuat::try_new(r64).unwrap();
        l.put("normalize32", Ok(q(q32)));
        l.put("normalize64", Ok(q(q64)));
        l.put("dcm32", Ok(m(q32)));
        l.put("dcm64", Ok(m(q64)));
        let from_dcm32 = err(Dcm::try_from_matrix(Dcm::from(q32).into_matrix(), 1e-5))
            .map(|d| q(d.to_unit_quat()));
        let from_dcm64 = err(Dcm::try_from_matrix(Dcm::from(q64).into_matrix(), 1e-12))
            .map(|d| q(d.to_unit_quat()));
        l.put("from_dcm32", from_dcm32);
        l.put("from_dcm64", from_dcm64);
        l.put("rotvec32", Ok(v(RotationVector::from(q32).vector())));
        l.put("rotvec64", Ok(v(RotationVector::from(q64).vector())));
        let p32 = RotationVector::try_new(v32).unwrap().to_unit_quat();
        let p64 = RotationVector::try_new(v64).unwrap().to_unit_quat();
        l.put("from_rotvec32", Ok(q(p32)));
        l.put("from_rotvec64", Ok(q(p64)));
        let a32 = UnitQuat::try_from_axis_angle(v32, r.f32() * 3.0).unwrap();
        let a64 = UnitQuat::try_from_axis_angle(v64, r.f64() * 3.0).unwrap();
        l.put("axis_angle32", Ok(q(a32)));
        l.put("axis_angle64", Ok(q(a64)));
        let m32 = unit_in(q32.into_quat()).unwrap() * unit_in(a32.into_quat()).unwrap();
        let m64 = unit_in(q64.into_quat()).unwrap() * unit_in(a64.into_quat()).unwrap();
        l.put("mul32", Ok(q(m32)));
        l.put("mul64", Ok(q(m64)));
        l.put("rotate32", Ok(v(q32.rotate(v32))));
        l.put("rotate64", Ok(v(q64.rotate(v64))));
        let e32 = q32.to_euler(seq("ZYX"), GimbalPolicy::ZeroThird);
        let e64 = q64.to_euler(seq("zxz"), GimbalPolicy::ZeroFirst);
        euler_line(l, "euler_ZYX32", Ok(e32));
        euler_line(l, "euler_zxz64", Ok(e64));
        let b32 = err(Euler::new(seq("ZYX"), e32.euler.angles).try_to_unit_quat());
        let b64 = err(Euler::new(seq("zxz"), e64.euler.angles).try_to_unit_quat());
        l.put("from_euler32", b32.map(q));
        l.put("from_euler64", b64.map(q));
    }
    let lq32 = Euler::new(seq("ZYX"), [0.3f32, core::f32::consts::FRAC_PI_2, 0.1])
        .try_to_unit_quat()
        .unwrap();
    l.put("lock_q32", Ok(q(lq32)));
    let e = unit_in(lq32.into_quat())
        .unwrap()
        .to_euler(seq("ZYX"), GimbalPolicy::ZeroThird);
    assert!(e.singularity.is_some(), "pitch π/2 is a gimbal lock");
    euler_line(l, "lock32", Ok(e));
    let lq64 = Euler::new(seq("ZYZ"), [-2.5, 0.0, 0.7])
        .try_to_unit_quat()
        .unwrap();
    l.put("lock_q64", Ok(q(lq64)));
    let e = unit_in(lq64.into_quat())
        .unwrap()
        .to_euler(seq("ZYZ"), GimbalPolicy::ClosestTo([0.5, 0.0, 0.0]));
    euler_line(l, "lock64", Ok(e));
    // The error statuses: the Rust API's errors through the documented codes, and the C
    // interface's own (NULL pointers, a state never initialised, unknown enumerated values).
    l.status(
        "err_zero_norm",
        err(UnitQuat::try_new(Quat::new(0.0f32, 0.0, 0.0, 0.0)).map(|_| ())),
    );
    l.status(
        "err_non_finite",
        err(UnitQuat::try_new(Quat::new(f64::NAN, 0.0, 0.0, 0.0)).map(|_| ())),
    );
    l.status("err_null_in", Err(BAD_POINTER));
    l.status("err_null_out", Err(BAD_POINTER));
    let reflection = gyrostat::Mat3 {
        m: [[-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    };
    l.status(
        "err_reflection",
        err(Dcm::try_from_matrix(reflection, 1e-9).map(|_| ())),
    );
    l.status(
        "err_sequence",
        err(EulerSequence::try_from_str("ZZX").map(|_| ())),
    );
    l.status("err_short_sequence", Err(INVALID_ARGUMENT));
    l.status("err_policy", Err(INVALID_ARGUMENT));
    l.status("err_closest_null", Err(BAD_POINTER));
    l.status("err_uninitialized", Err(NOT_INITIALIZED));
    l.status("err_rule", Err(INVALID_ARGUMENT));
}

fn increments(r: &mut Rng, l: &mut Lines) {
    for label in [
        "inc32_init",
        "inc32c_init",
        "inc64_init",
        "inc30_init",
        "quant_init",
    ] {
        l.status(label, Ok(()));
    }
    let mut i32p = IncrementIntegrator::new(
        UnitQuat::<f32>::IDENTITY,
        ConingRule::TwoSample,
        Normalization::Fast,
    );
    let mut i32c = IncrementIntegrator::new(
        CompensatedAttitude::new(UnitQuat::<f32>::IDENTITY),
        ConingRule::ThreeSample,
        Normalization::Fast,
    );
    let mut i64p = IncrementIntegrator::new(
        UnitQuat::<f64>::IDENTITY,
        ConingRule::FourSample,
        Normalization::Exact,
    );
    let mut i30 = IncrementIntegrator::new(
        CarriedAttitude::<30>::new(UnitQuat::IDENTITY),
        ConingRule::TwoSample,
        Normalization::Fast,
    );
    let scale = RawScale::<Q30>::try_new(1.0653e-6).unwrap();
    let mut quant = IncrementQuantizer::<30>::new();
    let (mut n32, mut n32c, mut n64, mut n30) = (0u32, 0u32, 0u32, 0u32);
    for k in 1..=203 {
        let d32 = r.vec32(2f32.powi(-8), [0.0; 3]);
        let d64 = r.vec64(2f64.powi(-8), [0.0; 3]);
        let raw = [r.raw16(), r.raw16(), r.raw16()];
        n32 += u32::from(i32p.push(d32).unwrap().is_some());
        n32c += u32::from(i32c.push(d32).unwrap().is_some());
        n64 += u32::from(i64p.push(d64).unwrap().is_some());
        let d30: Vec3<Q30> = quant.quantize_raw(&scale, raw);
        n30 += u32::from(i30.push(d30).unwrap().is_some());
        if k % 50 == 0 {
            l.put("inc32", Ok(q(i32p.attitude())));
            l.put("inc32c", Ok(q(i32c.attitude())));
            l.put("inc64", Ok(q(i64p.attitude())));
            let b = i30.attitude().to_bits();
            let bits = |x: Fixed<30>| x.to_bits() as u32;
            l.raw(format!(
                "inc30 {:08x} {:08x} {:08x} {:08x} {:08x} {:08x} {:08x}",
                b[0] as u32,
                b[1] as u32,
                b[2] as u32,
                b[3] as u32,
                bits(d30.x),
                bits(d30.y),
                bits(d30.z)
            ));
        }
    }
    l.raw(format!(
        "inc_updates {n32:08x} {n32c:08x} {n64:08x} {n30:08x}"
    ));
    l.put("inc32_provisional", Ok(q(i32p.provisional_attitude())));
    l.put("inc32c_flush", Ok(q(i32c.flush())));
    l.put("inc64_flush", Ok(q(i64p.flush())));
    l.status(
        "err_step_too_long",
        err(i32p.push(Vec3::new(4.0, 0.0, 0.0)).map(|_| ())),
    );
    let big: Vec3<Q30> = Vec3::new(
        Fixed::from_bits(1 << 28),
        Fixed::from_bits(0),
        Fixed::from_bits(0),
    );
    l.status("err_q30_range", err(i30.push(big).map(|_| ())));
}

fn rates(r: &mut Rng, l: &mut Lines) {
    l.status("rate32_init", Ok(()));
    l.status("rate64_init", Ok(()));
    let mut r32 = RateIntegrator::try_new(
        UnitQuat::<f32>::IDENTITY,
        RateMethod::Magnus4,
        Normalization::Fast,
        0.01,
    )
    .unwrap();
    let mut r64 = RateIntegrator::try_new(
        CompensatedAttitude::new(UnitQuat::<f64>::IDENTITY),
        RateMethod::Cf4,
        Normalization::Exact,
        0.01,
    )
    .unwrap();
    let (mut t32, mut t64) = (0usize, 0usize);
    for k in 0..101 {
        let w32 = r.vec32(2.0, [0.0; 3]);
        let w64 = r.vec64(2.0, [0.0; 3]);
        let o32 = r32.push(w32).unwrap();
        let o64 = r64.push(w64).unwrap();
        t32 += o32.len();
        t64 += o64.len();
        if k % 25 == 0 {
            if let Some(x) = o32.last() {
                l.put("rate32", Ok(q(*x)));
            }
            if let Some(x) = o64.last() {
                l.put("rate64", Ok(q(*x)));
            }
        }
    }
    let f32s = r32.finish();
    let f64s = r64.finish();
    l.put(
        "rate32_finish",
        Ok(f32s.last().map(|x| q(*x)).unwrap_or_default()),
    );
    l.put(
        "rate64_finish",
        Ok(f64s.last().map(|x| q(*x)).unwrap_or_default()),
    );
    l.raw(format!(
        "rate_counts {:08x} {:08x}",
        t32 + f32s.len(),
        t64 + f64s.len()
    ));
    l.status("err_finished", Err(NOT_INITIALIZED));
}

fn state_values<T: Real, const N: usize>(s: &State<T, N>) -> Vec<T> {
    let mut out = q(s.attitude);
    out.extend(v(s.momentum));
    for i in 0..4 {
        out.push(s.wheel_speeds.get(i).copied().unwrap_or(T::ZERO));
    }
    out
}

fn bodies(r: &mut Rng, l: &mut Lines) {
    let inertia64 =
        Inertia::try_from_components(Vec3::new(6.0, 4.0, 3.0), Vec3::new(0.05, -0.02, 0.01))
            .unwrap();
    let b64 = Gyrostat::with_wheels(inertia64, [Wheel::try_new(Vec3::Y, 0.05).unwrap()]);
    let b32 = Gyrostat::rigid(
        Inertia::try_from_components(Vec3::new(2.0f32, 3.0, 4.5), Vec3::new(0.0, 0.0, 0.0))
            .unwrap(),
    );
    l.status("body64_init", Ok(()));
    l.status("body32_init", Ok(()));
    let mut s64 = b64
        .try_state_from_omega(UnitQuat::IDENTITY, Vec3::new(0.05, 1.0, 0.01), [60.0])
        .unwrap();
    let mut s32 = b32
        .try_state_from_omega(UnitQuat::IDENTITY, Vec3::new(0.3, -0.2, 0.9), [])
        .unwrap();
    l.put("body64_state", Ok(state_values(&s64)));
    l.put("body32_state", Ok(state_values(&s32)));
    for k in 0..100 {
        let tau = r.vec64(0.01, [0.0; 3]);
        let wt = [r.f64() * 0.02];
        let control = Control {
            torque: tau,
            wheel_torques: wt,
        };
        // The C interface takes the state's attitude through its input rule at every step.
        s64.attitude = unit_in(s64.attitude.into_quat()).unwrap();
        s64 = b64
            .step_with(Integrator::Yoshida4, &s64, 0.01 * k as f64, 0.01, control)
            .unwrap();
        s32.attitude = unit_in(s32.attitude.into_quat()).unwrap();
        s32 = b32
            .step_with(
                Integrator::Rk4,
                &s32,
                0.02 * k as f32,
                0.02,
                Control::<f32, 0>::ZERO,
            )
            .unwrap();
        if k % 33 == 0 {
            l.put("body64", Ok(state_values(&s64)));
            l.put("body32", Ok(state_values(&s32)));
        }
    }
    l.put("body64_end", Ok(state_values(&s64)));
    l.put("body32_end", Ok(state_values(&s32)));
    l.status(
        "err_inertia",
        err(Inertia::try_from_components(Vec3::new(1.0, 1.0, 3.0), Vec3::ZERO).map(|_| ())),
    );
    l.status("err_wheels", Err(INVALID_ARGUMENT));
    l.status(
        "err_dt",
        err(b64
            .step_with(Integrator::Strang, &s64, 0.0, -0.01, Control::ZERO)
            .map(|_| ())),
    );
}

fn sensor(u: SensorUse) -> u32 {
    match u {
        SensorUse::Used => 0,
        SensorUse::Absent => 1,
        SensorUse::NonFinite => 2,
        SensorUse::Saturated => 3,
        SensorUse::Disturbed => 4,
        SensorUse::Zero => 5,
    }
}

fn outcome(o: &Outcome) -> String {
    format!(
        "{:x} {:x} {:x} {:x} {:x}",
        u32::from(o.gyro_saturated),
        sensor(o.accel),
        sensor(o.mag),
        u32::from(o.at_rest),
        u32::from(o.initialized)
    )
}

/// `f64`: whether the scenario runs the f64 estimator (the Cortex-M0 build leaves it out:
/// `GYRO_SCENARIO_NO_F64_ESTIMATOR`; its random inputs are drawn all the same).
fn estimators(r: &mut Rng, l: &mut Lines, f64: bool) {
    l.status("est32_params", Ok(()));
    l.status("est32_init", Ok(()));
    if f64 {
        l.status("est64_init", Ok(()));
    }
    let mut e32 = Estimator::<f32>::try_new(Params {
        gyro_range: 0.24,
        rate_rule: RateRule::Cf4,
        ..Params::default()
    })
    .unwrap();
    let mut e64 = Estimator::<f64>::try_new(Params {
        frame: EarthFrame::Ned,
        ..Params::default()
    })
    .unwrap();
    let (mut o32, mut o64) = (Outcome::default(), Outcome::default());
    let mut saturated = 0u32;
    for k in 0..300 {
        let g32 = r.vec32(0.05, [0.0, 0.0, 0.2]);
        let a32 = r.vec32(0.1, [0.0, 0.5, 9.8]);
        let g64 = r.vec64(0.05, [0.0, 0.1, 0.0]);
        let a64 = r.vec64(0.1, [0.3, 0.0, -9.8]);
        let m64 = r.vec64(1.0, [20.0, 1.0, 40.0]);
        o32 = e32.update(g32, a32, None, 0.01).unwrap();
        saturated += u32::from(o32.gyro_saturated);
        o64 = e64.update(g64, a64, Some(m64), 0.01).unwrap();
        if k % 100 == 99 {
            l.put("est32", Ok(q(e32.attitude())));
            l.put("est32_bias", Ok(v(e32.bias())));
            if f64 {
                l.put("est64", Ok(q(e64.attitude())));
                l.put("est64_bias", Ok(v(e64.bias())));
                l.raw(format!("est_outcome {} {}", outcome(&o32), outcome(&o64)));
            } else {
                l.raw(format!("est_outcome {}", outcome(&o32)));
            }
        }
    }
    let _ = (o32, o64);
    assert!(saturated > 0, "the f32 estimator's gyro range is reached");
    l.raw(format!("est32_saturated {saturated:08x}"));
    let o = e32.update(Vec3::ZERO, Vec3::ZERO, None, 0.01);
    l.status("zero_accel", err(o.map(|_| ())));
    l.raw(format!("zero_accel_outcome {:x}", sensor(o.unwrap().accel)));
    l.status(
        "err_est_dt",
        err(e32.update(Vec3::ZERO, Vec3::ZERO, None, 0.0).map(|_| ())),
    );
}

/// The sensor front end (`sensors()` of `scenario.c`): the clocks, the clip guard, the raw
/// scale, the calibrations and the axis remap, through the library's `sensor` API. `f64`:
/// whether the scenario runs the f64 calibrations (the Cortex-M0 build leaves them out with
/// the f64 estimator, for flash; their random inputs are drawn all the same).
fn sensors(r: &mut Rng, l: &mut Lines, f64: bool) {
    use gyrostat::Axis;
    use gyrostat::Mat3;
    use gyrostat::sensor::{
        AxisRemap, ClipGuard, ClipLimit, ClipPolicy, InertialCalibration, Interval,
        MagnetometerCalibration, MicrosClock, RawScale, SampleClock,
    };
    fn kind<D>(i: &Interval<D>) -> u32 {
        match i {
            Interval::First => 0,
            Interval::Step(_) => 1,
            Interval::Gap(_) => 2,
            Interval::Repeated => 3,
            Interval::Backwards(_) => 4,
        }
    }
    fn line<T: Real + Bits>(l: &mut Lines, label: &str, i: Result<Interval<T>, Error>) {
        match i {
            Ok(i) => {
                let d = match i {
                    Interval::First => T::from_f64(f64::NAN),
                    Interval::Repeated => T::ZERO,
                    Interval::Step(d) | Interval::Gap(d) | Interval::Backwards(d) => d,
                };
                l.raw(format!("{label} 00 {:x} {}", kind(&i), d.hex()));
            }
            Err(e) => l.raw(format!("{label} {:02x}", code(e))),
        }
    }
    l.status(
        "clock_bad_nominal",
        err(SampleClock::try_new(0.0f64).map(|_| ())),
    );
    l.status(
        "clock_bad_factor",
        err(SampleClock::try_with_gap_factor(0.01f32, 0.5).map(|_| ())),
    );
    let mut c64 = SampleClock::try_with_gap_factor(0.01f64, 5.0).unwrap();
    let mut c32 = SampleClock::try_with_gap_factor(0.01f32, 5.0).unwrap();
    l.status("clock64_init", Ok(()));
    l.status("clock32_init", Ok(()));
    let mut t64 = 100.0 + r.f64();
    let mut t32 = 100.0f32 + r.f32();
    for k in 0..8 {
        let (mut d64, mut d32) = (0.01 + 0.002 * r.f64(), 0.01f32 + 0.002 * r.f32());
        match k {
            3 => (d64, d32) = (0.0, 0.0),
            4 => (d64, d32) = (-0.003, -0.003),
            6 => (d64, d32) = (0.25, 0.25),
            _ => {}
        }
        line(l, "clock64", c64.interval(t64 + d64));
        line(l, "clock32", c32.interval(t32 + d32));
        if k != 3 && k != 4 {
            t64 += d64;
            t32 += d32;
        }
    }
    l.status("clock64_nan", err(c64.interval(f64::NAN).map(|_| ())));
    c64.restart(None);
    l.status("clock64_restart", Ok(()));
    line(l, "clock64_first", c64.interval(t64));
    l.status("us_bad", err(MicrosClock::try_new(0, 5).map(|_| ())));
    let mut us = MicrosClock::try_new(10_000, 5).unwrap();
    l.status("us_init", Ok(()));
    let mut t = u32::MAX - 25_000;
    for k in 0..6 {
        let mut d = 9000 + (r.next_u32() >> 20);
        match k {
            2 => d = 0,
            3 => d = u32::MAX - 99,
            4 => d = 80_000,
            _ => {}
        }
        let i = us.interval(t.wrapping_add(d));
        let dt = match i {
            Interval::Step(d) | Interval::Gap(d) | Interval::Backwards(d) => d,
            Interval::First | Interval::Repeated => 0,
        };
        l.raw(format!("us 00 {:x} {dt:08x}", kind(&i)));
        if k != 2 && k != 3 {
            t = t.wrapping_add(d);
        }
    }
    l.status("clip_bad", err(ClipLimit::try_new(0).map(|_| ())));
    let mut guard = ClipGuard::new(ClipLimit::try_new(30_000).unwrap(), ClipPolicy::HoldLast);
    l.status("clip_init", Ok(()));
    for k in 0..5 {
        let mut raw = [r.raw16(), r.raw16(), r.raw16()];
        if k == 2 {
            raw[0] = 32767;
            raw[2] = -32768;
        }
        if k == 3 {
            raw[1] = 30_000;
        }
        let (o, c) = guard.filter(raw).unwrap();
        let mask = c
            .axes
            .iter()
            .enumerate()
            .fold(0u32, |m, (i, &a)| m | (u32::from(a) << i));
        l.raw(format!(
            "clip 00 {:04x} {:04x} {:04x} {mask:x}",
            o[0] as u16, o[1] as u16, o[2] as u16
        ));
        l.put(
            "raw32",
            Ok(v(RawScale::<f32>::try_new(f64::from(0.00106526f32))
                .unwrap()
                .apply(o))),
        );
        l.put(
            "raw64",
            Ok(v(RawScale::<f64>::try_new(0.00106526f64).unwrap().apply(o))),
        );
    }
    let mut reject = ClipGuard::new(ClipLimit::try_new(1000).unwrap(), ClipPolicy::Reject);
    l.status("clip_reject_init", Ok(()));
    l.status("clip_reject", err(reject.filter([5, -1000, 7]).map(|_| ())));
    let (mut m32, mut m64) = (Mat3::<f32>::IDENTITY, Mat3::<f64>::IDENTITY);
    for i in 0..3 {
        for j in 0..3 {
            let (e32, e64) = if i == j { (1.0, 1.0) } else { (0.0, 0.0) };
            m32.m[i][j] = e32 + 0.01 * r.f32();
            m64.m[i][j] = e64 + 0.01 * r.f64();
        }
    }
    let (s32, b32) = (r.vec32(0.02, [1.0; 3]), r.vec32(0.01, [0.0; 3]));
    let (s64, b64) = (r.vec64(0.02, [1.0; 3]), r.vec64(0.01, [0.0; 3]));
    let cal32 = InertialCalibration::try_new(m32, s32, b32).unwrap();
    let cal64 = InertialCalibration::try_new(m64, s64, b64).unwrap();
    let mcal32 = MagnetometerCalibration::try_new(m32, b32).unwrap();
    let mcal64 = MagnetometerCalibration::try_new(m64, b64).unwrap();
    l.status("cal32_init", Ok(()));
    l.status("mcal32_init", Ok(()));
    if f64 {
        l.status("cal64_init", Ok(()));
        l.status("mcal64_init", Ok(()));
    }
    l.status(
        "cal32_bad",
        err(InertialCalibration::try_new(m32, Vec3::new(1.0, -1.0, 1.0), b32).map(|_| ())),
    );
    for _ in 0..3 {
        let (r32, r64) = (r.vec32(2.0, [0.0; 3]), r.vec64(2.0, [0.0; 3]));
        l.put("cal32", err(cal32.try_apply(r32).map(v)));
        l.put("mcal32", err(mcal32.try_apply(r32).map(v)));
        if f64 {
            l.put("cal64", err(cal64.try_apply(r64).map(v)));
            l.put("mcal64", err(mcal64.try_apply(r64).map(v)));
        }
    }
    l.status(
        "remap_twice",
        err(AxisRemap::try_new([Axis::X, Axis::X, Axis::Y], [false; 3]).map(|_| ())),
    );
    l.status(
        "remap_reflection",
        err(AxisRemap::try_new([Axis::X, Axis::Y, Axis::Z], [true, false, false]).map(|_| ())),
    );
    let remap = AxisRemap::try_new([Axis::Z, Axis::X, Axis::Y], [false, true, true]).unwrap();
    l.status("remap_init", Ok(()));
    let (v32, v64) = (r.vec32(1.0, [0.0; 3]), r.vec64(1.0, [0.0; 3]));
    l.put("remap32", Ok(v(remap.apply(v32))));
    l.put("remap64", Ok(v(remap.apply(v64))));
}

/// The lines `scenario.c` must print, from the Rust API.
fn expected() -> String {
    expected_with(true)
}

/// The same, with or without the f64 estimator.
fn expected_with(f64_estimator: bool) -> String {
    let mut r = Rng(0x9E37_79B9);
    let mut l = Lines::default();
    rotations(&mut r, &mut l);
    increments(&mut r, &mut l);
    rates(&mut r, &mut l);
    bodies(&mut r, &mut l);
    estimators(&mut r, &mut l, f64_estimator);
    sensors(&mut r, &mut l, f64_estimator);
    l.raw("done".to_string());
    l.text
}

/// Fails with the first differing line.
fn compare(what: &str, got: &str, want: &str) {
    let (g, w): (Vec<_>, Vec<_>) = (got.lines().collect(), want.lines().collect());
    for (i, (a, b)) in g.iter().zip(&w).enumerate() {
        assert_eq!(
            a,
            b,
            "{what}: line {} differs (left: C, right: Rust API)",
            i + 1
        );
    }
    assert_eq!(
        g.len(),
        w.len(),
        "{what}: {} lines, expected {}",
        g.len(),
        w.len()
    );
}

fn ffi_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The workspace's target directory (this test runs from `target/<profile>/deps`).
fn target_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test executable path");
    exe.ancestors()
        .nth(3)
        .map(Path::to_path_buf)
        .expect("target/<profile>/deps/<test>")
}

#[test]
fn host_c_program_matches_the_rust_api() {
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".to_string());
    if Command::new(&cc).arg("--version").output().is_err() {
        eprintln!("SKIPPED: no C compiler `{cc}` (set CC or install gcc) to build tests/c");
        return;
    }
    // The host static library, as a C project builds it (`cargo build --release`).
    let status = Command::new(env!("CARGO"))
        .args(["build", "--release", "-p", "gyrostat-ffi"])
        .status()
        .expect("cargo build");
    assert!(
        status.success(),
        "cargo build --release -p gyrostat-ffi failed"
    );
    let lib = target_dir().join("release/libgyrostat_ffi.a");
    assert!(lib.exists(), "{} not built", lib.display());
    let exe = target_dir().join("ffi-host-test");
    let dir = ffi_dir();
    let out = Command::new(&cc)
        .args([
            "-std=c11",
            "-Wall",
            "-Wextra",
            "-Werror",
            "-O2",
            "-ffp-contract=off",
        ])
        .arg("-I")
        .arg(dir.join("include"))
        .arg(dir.join("tests/c/host_main.c"))
        .arg(dir.join("tests/c/scenario.c"))
        .arg(&lib)
        // `cargo rustc -p gyrostat-ffi --crate-type staticlib -- --print native-static-libs`
        .args([
            "-lgcc_s",
            "-lutil",
            "-lrt",
            "-lpthread",
            "-lm",
            "-ldl",
            "-lc",
        ])
        .arg("-o")
        .arg(&exe)
        .output()
        .expect("run the C compiler");
    assert!(
        out.status.success(),
        "C build failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let run = Command::new(&exe).output().expect("run the C program");
    assert!(run.status.success(), "the C program failed");
    let got = String::from_utf8(run.stdout).expect("ASCII output");
    compare("host C program", &got, &expected());
}

/// The bare-metal C program's outputs under QEMU (`make -C ffi/tests/c qemu`), in
/// `GYROSTAT_FIRMWARE_OUTPUT` (as `.ci/run` writes them).
mod firmware {
    use super::*;

    fn check(name: &str, f64_estimator: bool) {
        let dir = std::env::var("GYROSTAT_FIRMWARE_OUTPUT")
            .expect("GYROSTAT_FIRMWARE_OUTPUT: the directory of the QEMU outputs");
        let path = Path::new(&dir).join(name);
        let got =
            std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        compare(name, &got, &expected_with(f64_estimator));
    }

    #[test]
    #[ignore = "needs the QEMU outputs of tests/c (.ci/run)"]
    fn cortex_m4f_c_program_matches_the_rust_api() {
        check("ffi-c-thumbv7em-none-eabihf.txt", true);
    }

    #[test]
    #[ignore = "needs the QEMU outputs of tests/c (.ci/run)"]
    fn cortex_m0_c_program_matches_the_rust_api() {
        check("ffi-c-thumbv6m-none-eabi.txt", false);
    }
}
