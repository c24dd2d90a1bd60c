//! The C interface's contract for bad calls, called from Rust as C calls it: a NULL or
//! misaligned pointer gives `GYRO_BAD_POINTER`, a state never initialised
//! `GYRO_NOT_INITIALIZED`, an unknown enumerated value `GYRO_INVALID_ARGUMENT`; an error writes
//! no output and leaves the state as it was.

use std::mem::MaybeUninit;
use std::ptr::{null, null_mut};

use gyrostat_ffi::gyro_status::*;
use gyrostat_ffi::*;

const ID32: gyro_quat_f32 = gyro_quat_f32 {
    w: 1.0,
    x: 0.0,
    y: 0.0,
    z: 0.0,
};
const ID64: gyro_quat_f64 = gyro_quat_f64 {
    w: 1.0,
    x: 0.0,
    y: 0.0,
    z: 0.0,
};
const SENTINEL: gyro_quat_f64 = gyro_quat_f64 {
    w: 7.0,
    x: 7.0,
    y: 7.0,
    z: 7.0,
};

/// A state struct as static C storage starts: all zero.
fn zeroed<T>() -> T {
    // SAFETY: the state structs are a u32 tag and u64 words; zero is a valid bit pattern.
    unsafe { MaybeUninit::zeroed().assume_init() }
}

#[test]
fn null_pointers_are_a_status() {
    let mut q = ID64;
    let v = gyro_vec3_f64 {
        x: 0.1,
        y: 0.2,
        z: 0.3,
    };
    let mut m = gyro_mat3_f64::default();
    let mut e = gyro_euler_f64::default();
    unsafe {
        assert_eq!(gyro_quat_normalize_f64(null(), &mut q), GYRO_BAD_POINTER);
        assert_eq!(gyro_quat_normalize_f64(&ID64, null_mut()), GYRO_BAD_POINTER);
        assert_eq!(gyro_quat_mul_f64(&ID64, null(), &mut q), GYRO_BAD_POINTER);
        assert_eq!(
            gyro_quat_rotate_f64(&ID64, null(), null_mut()),
            GYRO_BAD_POINTER
        );
        assert_eq!(gyro_quat_to_dcm_f64(null(), &mut m), GYRO_BAD_POINTER);
        assert_eq!(
            gyro_quat_from_dcm_f64(null(), 1e-9, &mut q),
            GYRO_BAD_POINTER
        );
        assert_eq!(gyro_quat_from_rotvec_f64(&v, null_mut()), GYRO_BAD_POINTER);
        assert_eq!(
            gyro_quat_to_rotvec_f32(null(), null_mut()),
            GYRO_BAD_POINTER
        );
        assert_eq!(
            gyro_quat_from_axis_angle_f32(null(), 1.0, null_mut()),
            GYRO_BAD_POINTER
        );
        assert_eq!(
            gyro_quat_to_euler_f64(&ID64, null(), GYRO_GIMBAL_ZERO_THIRD, null(), &mut e),
            GYRO_BAD_POINTER
        );
        assert_eq!(
            gyro_quat_from_euler_f64(c"ZYX".as_ptr(), null(), &mut q),
            GYRO_BAD_POINTER
        );
        assert_eq!(
            gyro_increment_integrator_f32_init(null_mut(), &ID32, 2, 1, 0),
            GYRO_BAD_POINTER
        );
        let mut inc: gyro_increment_integrator_f64 = zeroed();
        assert_eq!(
            gyro_increment_integrator_f64_init(&mut inc, null(), 2, 1, 0),
            GYRO_BAD_POINTER
        );
        assert_eq!(
            gyro_increment_integrator_f64_init(&mut inc, &ID64, 2, 1, 0),
            GYRO_OK
        );
        assert_eq!(
            gyro_increment_integrator_f64_push(&mut inc, null(), null_mut(), null_mut()),
            GYRO_BAD_POINTER
        );
        assert_eq!(
            gyro_increment_integrator_f64_attitude(&inc, 0, null_mut()),
            GYRO_BAD_POINTER
        );
        assert_eq!(
            gyro_rate_integrator_f64_init(null_mut(), &ID64, 0, 1, 0.01, 0),
            GYRO_BAD_POINTER
        );
        assert_eq!(
            gyro_gyrostat_f64_init(null_mut(), &v, null(), null(), 0),
            GYRO_BAD_POINTER
        );
        let mut body: gyro_gyrostat_f64 = zeroed();
        // One wheel announced, none given.
        assert_eq!(
            gyro_gyrostat_f64_init(&mut body, &v, null(), null(), 1),
            GYRO_BAD_POINTER
        );
        assert_eq!(gyro_estimator_f64_init(null_mut(), 0), GYRO_BAD_POINTER);
        assert_eq!(
            gyro_increment_quantizer_q30_quantize(null_mut(), null(), null_mut()),
            GYRO_BAD_POINTER
        );
    }
}

#[test]
fn misaligned_pointers_are_a_status() {
    let buf = [0u64; 8];
    // One byte into an 8-aligned buffer: misaligned for every struct of the interface.
    let p = unsafe { (buf.as_ptr() as *const u8).add(1) };
    let mut q = SENTINEL;
    unsafe {
        assert_eq!(
            gyro_quat_normalize_f64(p as *const gyro_quat_f64, &mut q),
            GYRO_BAD_POINTER
        );
        assert_eq!(
            gyro_quat_normalize_f64(&ID64, p as *mut gyro_quat_f64),
            GYRO_BAD_POINTER
        );
        assert_eq!(
            gyro_estimator_f64_update(
                p as *mut gyro_estimator_f64,
                null(),
                null(),
                null(),
                0.01,
                null_mut()
            ),
            GYRO_BAD_POINTER
        );
    }
    assert_eq!(q, SENTINEL, "no output on an error");
}

#[test]
fn uninitialised_states_are_a_status() {
    let d32 = gyro_vec3_f32::default();
    let d64 = gyro_vec3_f64::default();
    let mut q32 = ID32;
    let mut q64 = SENTINEL;
    unsafe {
        let mut inc: gyro_increment_integrator_f32 = zeroed();
        assert_eq!(
            gyro_increment_integrator_f32_push(&mut inc, &d32, null_mut(), null_mut()),
            GYRO_NOT_INITIALIZED
        );
        assert_eq!(
            gyro_increment_integrator_f32_flush(&mut inc, &mut q32),
            GYRO_NOT_INITIALIZED
        );
        let inc30: gyro_increment_integrator_q30 = zeroed();
        let mut q30 = gyro_quat_q30::default();
        assert_eq!(
            gyro_increment_integrator_q30_attitude(&inc30, &mut q30),
            GYRO_NOT_INITIALIZED
        );
        let mut quant: gyro_increment_quantizer_q30 = zeroed();
        let mut v30 = gyro_vec3_q30::default();
        assert_eq!(
            gyro_increment_quantizer_q30_quantize(&mut quant, &[1, 2, 3], &mut v30),
            GYRO_NOT_INITIALIZED
        );
        let rate: gyro_rate_integrator_f64 = zeroed();
        assert_eq!(
            gyro_rate_integrator_f64_attitude(&rate, &mut q64),
            GYRO_NOT_INITIALIZED
        );
        let body: gyro_gyrostat_f64 = zeroed();
        let mut s = gyro_gyrostat_state_f64::default();
        assert_eq!(
            gyro_gyrostat_f64_state_from_omega(&body, &ID64, &d64, null(), &mut s),
            GYRO_NOT_INITIALIZED
        );
        let mut est: gyro_estimator_f64 = zeroed();
        assert_eq!(
            gyro_estimator_f64_update(&mut est, &d64, &d64, null(), 0.01, null_mut()),
            GYRO_NOT_INITIALIZED
        );
    }
    assert_eq!(q64, SENTINEL);
}

#[test]
fn unknown_enumerated_values_are_invalid_arguments() {
    let mut inc: gyro_increment_integrator_f32 = zeroed();
    let mut rate: gyro_rate_integrator_f32 = zeroed();
    let mut est: gyro_estimator_f32 = zeroed();
    let mut body: gyro_gyrostat_f32 = zeroed();
    let mut e = gyro_euler_f32::default();
    let diag = gyro_vec3_f32 {
        x: 2.0,
        y: 3.0,
        z: 4.0,
    };
    unsafe {
        for (rule, norm, comp) in [(5, 1, 0), (2, 3, 0), (2, 1, 2), (u32::MAX, 1, 0)] {
            assert_eq!(
                gyro_increment_integrator_f32_init(&mut inc, &ID32, rule, norm, comp),
                GYRO_INVALID_ARGUMENT
            );
        }
        assert_eq!(
            gyro_rate_integrator_f32_init(&mut rate, &ID32, 3, 1, 0.01, 0),
            GYRO_INVALID_ARGUMENT
        );
        assert_eq!(gyro_estimator_f32_init(&mut est, 2), GYRO_INVALID_ARGUMENT);
        assert_eq!(
            gyro_quat_to_euler_f32(&ID32, c"ZYX".as_ptr(), 3, null(), &mut e),
            GYRO_INVALID_ARGUMENT
        );
        for bad in [c"ZYXZ", c"zYx", c"ZZY", c"", c"ABC"] {
            assert_eq!(
                gyro_quat_to_euler_f32(&ID32, bad.as_ptr(), 1, null(), &mut e),
                GYRO_INVALID_ARGUMENT,
                "{bad:?}"
            );
        }
        assert_eq!(
            gyro_gyrostat_f32_init(&mut body, &diag, null(), null(), 0),
            GYRO_OK
        );
        let mut s = gyro_gyrostat_state_f32 {
            attitude: ID32,
            ..Default::default()
        };
        let before = s;
        assert_eq!(
            gyro_gyrostat_f32_step(&body, 4, &s, 0.0, 0.01, null(), null(), &mut s),
            GYRO_INVALID_ARGUMENT
        );
        assert_eq!(s, before);
    }
    // Every failed init left the struct uninitialised.
    let mut q = ID32;
    unsafe {
        assert_eq!(
            gyro_increment_integrator_f32_attitude(&inc, 0, &mut q),
            GYRO_NOT_INITIALIZED
        );
        assert_eq!(
            gyro_rate_integrator_f32_attitude(&rate, &mut q),
            GYRO_NOT_INITIALIZED
        );
    }
}

#[test]
fn an_error_leaves_the_state_unchanged() {
    let mut inc: gyro_increment_integrator_f64 = zeroed();
    let mut est: gyro_estimator_f64 = zeroed();
    let (mut a, mut b) = (SENTINEL, SENTINEL);
    let (mut bias_a, mut bias_b) = (gyro_vec3_f64::default(), gyro_vec3_f64::default());
    let nan = gyro_vec3_f64 {
        x: f64::NAN,
        y: 0.0,
        z: 0.0,
    };
    unsafe {
        assert_eq!(
            gyro_increment_integrator_f64_init(&mut inc, &ID64, GYRO_CONING_THREE_SAMPLE, 0, 0),
            GYRO_OK
        );
        // Two increments pending of a three-sample group; then a NaN is refused.
        let d = gyro_vec3_f64 {
            x: 1e-3,
            y: -2e-3,
            z: 5e-4,
        };
        for _ in 0..2 {
            let mut updated = 9;
            assert_eq!(
                gyro_increment_integrator_f64_push(&mut inc, &d, &mut updated, null_mut()),
                GYRO_OK
            );
            assert_eq!(updated, 0);
        }
        assert_eq!(
            gyro_increment_integrator_f64_attitude(&inc, 1, &mut a),
            GYRO_OK
        );
        let mut updated = 9;
        assert_eq!(
            gyro_increment_integrator_f64_push(&mut inc, &nan, &mut updated, &mut b),
            GYRO_NON_FINITE
        );
        assert_eq!((updated, b), (9, SENTINEL), "no output on an error");
        assert_eq!(
            gyro_increment_integrator_f64_attitude(&inc, 1, &mut b),
            GYRO_OK
        );
        assert_eq!(a, b, "the pending increments survive a refused one");
        // The third increment completes the group.
        assert_eq!(
            gyro_increment_integrator_f64_push(&mut inc, &d, &mut updated, &mut b),
            GYRO_OK
        );
        assert_eq!(updated, 1);

        assert_eq!(gyro_estimator_f64_init(&mut est, GYRO_FRAME_ENU), GYRO_OK);
        let g = gyro_vec3_f64 {
            x: 0.01,
            y: 0.0,
            z: 0.02,
        };
        let acc = gyro_vec3_f64 {
            x: 0.1,
            y: 0.2,
            z: 9.8,
        };
        let mut o = gyro_estimator_outcome::default();
        assert_eq!(
            gyro_estimator_f64_update(&mut est, &g, &acc, null(), 0.01, &mut o),
            GYRO_OK
        );
        assert_eq!(
            (o.initialized, o.accel, o.mag),
            (1, GYRO_SENSOR_USED, GYRO_SENSOR_ABSENT)
        );
        assert_eq!(
            gyro_estimator_f64_attitude(&est, &mut a, &mut bias_a),
            GYRO_OK
        );
        for dt in [0.0, -1.0, f64::NAN, 2000.0] {
            assert_eq!(
                gyro_estimator_f64_update(&mut est, &g, &acc, null(), dt, &mut o),
                GYRO_INVALID_ARGUMENT
            );
        }
        assert_eq!(
            gyro_estimator_f64_update(&mut est, &nan, &acc, null(), 0.01, &mut o),
            GYRO_NON_FINITE
        );
        assert_eq!(
            gyro_estimator_f64_attitude(&est, &mut b, &mut bias_b),
            GYRO_OK
        );
        assert_eq!((a, bias_a), (b, bias_b));
    }
}

#[test]
fn quaternion_inputs_unit_to_rounding_are_taken_bit_for_bit() {
    // A unit quaternion whose normalisation would move its last bits: taken as it is.
    let q = gyro_quat_f64 {
        w: 0.1,
        x: 0.7,
        y: -0.5,
        z: (1.0f64 - 0.01 - 0.49 - 0.25).sqrt(),
    };
    let mut out = SENTINEL;
    let axis = gyro_vec3_f64 {
        x: 0.0,
        y: 0.0,
        z: 1.0,
    };
    let mut zero_turn = SENTINEL;
    unsafe {
        assert_eq!(
            gyro_quat_from_axis_angle_f64(&axis, 0.0, &mut zero_turn),
            GYRO_OK
        );
        assert_eq!(gyro_quat_mul_f64(&q, &zero_turn, &mut out), GYRO_OK);
    }
    assert_eq!(out, q);
    let mut normalised = SENTINEL;
    unsafe {
        assert_eq!(gyro_quat_normalize_f64(&q, &mut normalised), GYRO_OK);
    }
    assert_ne!(
        normalised, q,
        "normalising would have changed the input's bits"
    );
    // A far-from-unit one is normalised (scipy's from_quat): (2, 0, 0, 0) is the identity.
    let two = gyro_quat_f64 {
        w: 2.0,
        x: 0.0,
        y: 0.0,
        z: 0.0,
    };
    unsafe {
        assert_eq!(gyro_quat_mul_f64(&two, &ID64, &mut out), GYRO_OK);
    }
    assert_eq!(out, ID64);
}

#[test]
fn estimator_parameters_from_c() {
    let mut p = gyro_estimator_params_f64::default();
    let mut a: gyro_estimator_f64 = zeroed();
    let mut b: gyro_estimator_f64 = zeroed();
    let g = gyro_vec3_f64 {
        x: 0.3,
        y: -0.1,
        z: 0.2,
    };
    let acc = gyro_vec3_f64 {
        x: 0.5,
        y: 0.2,
        z: 9.7,
    };
    let (mut qa, mut qb) = (SENTINEL, SENTINEL);
    let (mut oa, mut ob) = (
        gyro_estimator_outcome::default(),
        gyro_estimator_outcome::default(),
    );
    unsafe {
        assert_eq!(gyro_estimator_f64_default_params(&mut p), GYRO_OK);
        assert_eq!(p.frame, GYRO_FRAME_ENU);
        assert!((p.gyro_range - 2000f64.to_radians()).abs() < 1e-12 && p.gyro_noise_density > 0.0);
        // The defaults through the struct: the same estimator as gyro_estimator_f64_init.
        assert_eq!(gyro_estimator_f64_init_params(&mut a, &p), GYRO_OK);
        assert_eq!(gyro_estimator_f64_init(&mut b, GYRO_FRAME_ENU), GYRO_OK);
        for k in 0..50 {
            let dt = 0.01 + 1e-4 * f64::from(k);
            assert_eq!(
                gyro_estimator_f64_update(&mut a, &g, &acc, null(), dt, &mut oa),
                GYRO_OK
            );
            assert_eq!(
                gyro_estimator_f64_update(&mut b, &g, &acc, null(), dt, &mut ob),
                GYRO_OK
            );
        }
        assert_eq!(
            gyro_estimator_f64_attitude(&a, &mut qa, null_mut()),
            GYRO_OK
        );
        assert_eq!(
            gyro_estimator_f64_attitude(&b, &mut qb, null_mut()),
            GYRO_OK
        );
        assert_eq!((qa, oa), (qb, ob));
        // A parameter takes effect: a gyro range below the rate saturates it.
        p.gyro_range = 0.25;
        assert_eq!(gyro_estimator_f64_init_params(&mut a, &p), GYRO_OK);
        assert_eq!(
            gyro_estimator_f64_update(&mut a, &g, &acc, null(), 0.01, &mut oa),
            GYRO_OK
        );
        assert_eq!(
            gyro_estimator_f64_update(&mut a, &g, &acc, null(), 0.01, &mut oa),
            GYRO_OK
        );
        assert_eq!(oa.gyro_saturated, 1);
        // The light mode through the struct: the library's estimator in `Mode::Light`, bit for
        // bit, on a record with a magnetometer; it differs from the full mode.
        p.gyro_range = f64::INFINITY;
        assert_eq!(p.mode, GYRO_MODE_FULL);
        assert_eq!(p.correction_period, 0.025);
        let mut full: gyro_estimator_f64 = zeroed();
        assert_eq!(gyro_estimator_f64_init_params(&mut full, &p), GYRO_OK);
        p.mode = GYRO_MODE_LIGHT;
        assert_eq!(gyro_estimator_f64_init_params(&mut a, &p), GYRO_OK);
        let mut lib =
            gyrostat::estimation::Estimator::<f64>::try_new(gyrostat::estimation::Params::light())
                .unwrap();
        let mag = gyro_vec3_f64 {
            x: 3.0,
            y: 15.8,
            z: -40.7,
        };
        let mut qf = SENTINEL;
        for k in 0..200 {
            let dt = 0.004 + 1e-5 * f64::from(k);
            let gk = gyro_vec3_f64 {
                x: g.x * (0.01 * f64::from(k)).cos(),
                ..g
            };
            assert_eq!(
                gyro_estimator_f64_update(&mut a, &gk, &acc, &mag, dt, &mut oa),
                GYRO_OK
            );
            assert_eq!(
                gyro_estimator_f64_update(&mut full, &gk, &acc, &mag, dt, &mut ob),
                GYRO_OK
            );
            let v = |v: gyro_vec3_f64| gyrostat::Vec3::new(v.x, v.y, v.z);
            lib.update_9d(v(gk), v(acc), v(mag), dt).unwrap();
        }
        assert_eq!(
            gyro_estimator_f64_attitude(&a, &mut qa, null_mut()),
            GYRO_OK
        );
        assert_eq!(
            gyro_estimator_f64_attitude(&full, &mut qf, null_mut()),
            GYRO_OK
        );
        let ql = lib.attitude();
        assert_eq!((qa.w, qa.x, qa.y, qa.z), (ql.w(), ql.x(), ql.y(), ql.z()));
        assert_ne!(qa, qf);
        let mut bad = p;
        bad.mode = 2;
        assert_eq!(
            gyro_estimator_f64_init_params(&mut a, &bad),
            GYRO_INVALID_ARGUMENT
        );
        // Bad parameters are refused and leave the struct as it was.
        let mut c: gyro_estimator_f32 = zeroed();
        let mut p32 = gyro_estimator_params_f32::default();
        assert_eq!(gyro_estimator_f32_default_params(&mut p32), GYRO_OK);
        for (field, value) in [(0, -1.0f32), (1, f32::NAN)] {
            let mut bad = p32;
            match field {
                0 => bad.gyro_noise_density = value,
                _ => bad.accel_tilt_noise = value,
            }
            let want = if value.is_nan() {
                GYRO_NON_FINITE
            } else {
                GYRO_INVALID_ARGUMENT
            };
            assert_eq!(gyro_estimator_f32_init_params(&mut c, &bad), want);
        }
        let mut bad = p32;
        bad.fixed_gains = 2;
        assert_eq!(
            gyro_estimator_f32_init_params(&mut c, &bad),
            GYRO_INVALID_ARGUMENT
        );
        let mut q32 = ID32;
        assert_eq!(
            gyro_estimator_f32_attitude(&c, &mut q32, null_mut()),
            GYRO_NOT_INITIALIZED
        );
        p32.fixed_gains = 1;
        p32.heading_time_constant = 5.0;
        p32.frame = GYRO_FRAME_NED;
        assert_eq!(gyro_estimator_f32_init_params(&mut c, &p32), GYRO_OK);
    }
}

/// The rate rule through the C struct: the default parameters hold `GYRO_RATE_RULE_DEFAULT`,
/// which is the library's rule of the full and of the light mode's parameters; each named code
/// is the library's rule of that name (set in the struct, read back from the library's
/// parameters and written back), and an estimator started with it is the library's estimator
/// with that rule, bit for bit (f64 and f32, on a turning record that does not repeat); the
/// three rules give three estimates; an unknown code is `GYRO_INVALID_ARGUMENT` and leaves the
/// estimator as it was.
#[test]
fn rate_rule_from_c() {
    use gyrostat::estimation::{Estimator, Params, RateRule};
    let mut p = gyro_estimator_params_f64::default();
    let mut p32 = gyro_estimator_params_f32::default();
    unsafe {
        assert_eq!(gyro_estimator_f64_default_params(&mut p), GYRO_OK);
        assert_eq!(gyro_estimator_f32_default_params(&mut p32), GYRO_OK);
    }
    assert_eq!(
        (p.rate_rule, p32.rate_rule),
        (GYRO_RATE_RULE_DEFAULT, GYRO_RATE_RULE_DEFAULT)
    );
    assert_eq!(p.to_params().unwrap(), Params::<f64>::default());
    let mut light = p;
    light.mode = GYRO_MODE_LIGHT;
    assert_eq!(light.to_params().unwrap(), Params::<f64>::light());
    assert_eq!(
        gyro_estimator_params_f64::from_params(&Params::<f64>::light()),
        light
    );

    // A level-ish sensor turning about a wandering axis; steps and rates never repeat.
    let samples: Vec<(gyro_vec3_f64, gyro_vec3_f64, gyro_vec3_f64, f64)> = (0..400)
        .map(|k| {
            let t = f64::from(k);
            let g = gyro_vec3_f64 {
                x: 0.8 * (0.031 * t).sin(),
                y: 0.5 * (0.017 * t + 0.4).cos(),
                z: 1.2 + 0.3 * (0.0123 * t * t.sqrt()).sin(),
            };
            let a = gyro_vec3_f64 {
                x: 0.2 * (0.05 * t).cos(),
                y: 0.1,
                z: 9.8,
            };
            let m = gyro_vec3_f64 {
                x: 15.8 * (0.02 * t).sin(),
                y: 15.8 * (0.02 * t).cos(),
                z: -40.7,
            };
            (g, a, m, 0.01 + 0.002 * (1.7 * t).sin())
        })
        .collect();
    let v = |v: gyro_vec3_f64| gyrostat::Vec3::new(v.x, v.y, v.z);
    let v32 = |v: gyro_vec3_f64| gyrostat::Vec3::new(v.x as f32, v.y as f32, v.z as f32);
    let mut finals = Vec::new();
    for (code, name) in [
        (GYRO_RATE_RULE_TRAPEZOID, "trapezoid"),
        (GYRO_RATE_RULE_MAGNUS4, "magnus4"),
        (GYRO_RATE_RULE_CF4, "cf4"),
    ] {
        p.rate_rule = code;
        p32.rate_rule = code;
        let lib = p.to_params().unwrap();
        let lib32 = p32.to_params().unwrap();
        assert_eq!(lib.rate_rule.name(), name);
        assert_eq!(lib32.rate_rule, lib.rate_rule);
        assert_eq!(
            lib,
            Params {
                rate_rule: name.parse::<RateRule>().unwrap(),
                ..Params::default()
            }
        );
        // Written back: the code, or the default code where it is the library's default rule.
        let back = gyro_estimator_params_f64::from_params(&lib);
        let want = if lib.rate_rule == Params::<f64>::default().rate_rule {
            GYRO_RATE_RULE_DEFAULT
        } else {
            code
        };
        assert_eq!(back.rate_rule, want, "{name}");
        assert_eq!(back.to_params().unwrap(), lib);
        assert_eq!(
            gyro_estimator_params_f32::from_params(&lib32).to_params(),
            Ok(lib32)
        );

        let mut c: gyro_estimator_f64 = zeroed();
        let mut c32: gyro_estimator_f32 = zeroed();
        let mut e = Estimator::<f64>::try_new(lib).unwrap();
        let mut e32 = Estimator::<f32>::try_new(lib32).unwrap();
        let mut o = gyro_estimator_outcome::default();
        unsafe {
            assert_eq!(gyro_estimator_f64_init_params(&mut c, &p), GYRO_OK);
            assert_eq!(gyro_estimator_f32_init_params(&mut c32, &p32), GYRO_OK);
            for &(g, a, m, dt) in &samples {
                assert_eq!(
                    gyro_estimator_f64_update(&mut c, &g, &a, &m, dt, &mut o),
                    GYRO_OK
                );
                let f = |v: gyro_vec3_f64| gyro_vec3_f32 {
                    x: v.x as f32,
                    y: v.y as f32,
                    z: v.z as f32,
                };
                assert_eq!(
                    gyro_estimator_f32_update(&mut c32, &f(g), &f(a), &f(m), dt as f32, &mut o),
                    GYRO_OK
                );
                e.update_9d(v(g), v(a), v(m), dt).unwrap();
                e32.update_9d(v32(g), v32(a), v32(m), dt as f32).unwrap();
            }
        }
        let mut q = SENTINEL;
        let mut q32 = ID32;
        unsafe {
            assert_eq!(gyro_estimator_f64_attitude(&c, &mut q, null_mut()), GYRO_OK);
            assert_eq!(
                gyro_estimator_f32_attitude(&c32, &mut q32, null_mut()),
                GYRO_OK
            );
        }
        let (ql, ql32) = (e.attitude(), e32.attitude());
        assert_eq!(
            (q.w, q.x, q.y, q.z),
            (ql.w(), ql.x(), ql.y(), ql.z()),
            "{name}"
        );
        assert_eq!(
            (q32.w, q32.x, q32.y, q32.z),
            (ql32.w(), ql32.x(), ql32.y(), ql32.z()),
            "{name} f32"
        );
        finals.push(q);

        // An unknown code: refused, the running estimator unchanged.
        for bad in [GYRO_RATE_RULE_CF4 + 1, u32::MAX] {
            let mut b = p;
            b.rate_rule = bad;
            assert_eq!(b.to_params(), Err(GYRO_INVALID_ARGUMENT));
            let mut b32 = p32;
            b32.rate_rule = bad;
            let mut after = SENTINEL;
            unsafe {
                assert_eq!(
                    gyro_estimator_f64_init_params(&mut c, &b),
                    GYRO_INVALID_ARGUMENT
                );
                assert_eq!(
                    gyro_estimator_f32_init_params(&mut c32, &b32),
                    GYRO_INVALID_ARGUMENT
                );
                assert_eq!(
                    gyro_estimator_f64_attitude(&c, &mut after, null_mut()),
                    GYRO_OK
                );
            }
            assert_eq!(after, q);
        }
    }
    assert_ne!(finals[0], finals[1]);
    assert_ne!(finals[0], finals[2]);
    assert_ne!(finals[1], finals[2]);
}

/// Every library error, listed beside a match without a wildcard: a new variant does not
/// compile here until it is added to the list.
fn every_error() -> Vec<gyrostat::Error> {
    use gyrostat::Error as E;
    let list = vec![
        E::NonFinite,
        E::ZeroNorm,
        E::NotUnit,
        E::NotRotation,
        E::Singular,
        E::NonPhysicalInertia,
        E::NotConverged,
        E::StepTooLong,
        E::InvalidArgument,
        E::OutOfRange,
        E::Clipped,
    ];
    for e in &list {
        match e {
            E::NonFinite
            | E::ZeroNorm
            | E::NotUnit
            | E::NotRotation
            | E::Singular
            | E::NonPhysicalInertia
            | E::NotConverged
            | E::StepTooLong
            | E::InvalidArgument
            | E::OutOfRange
            | E::Clipped => {}
        }
    }
    list
}

/// The C body of `typedef enum|struct { ... } NAME;` in the committed header.
fn header_body(name: &str) -> String {
    let header = include_str!("../include/gyrostat.h");
    let end = header
        .find(&format!("}} {name};"))
        .unwrap_or_else(|| panic!("{name} in the header"));
    let start = header[..end].rfind("typedef ").expect("typedef");
    header[start..end].to_string()
}

/// Each library error has its own status code (none of them `GYRO_OK`, none shared), and the
/// header declares that code with a comment.
#[test]
fn every_error_has_its_own_documented_code() {
    let body = header_body("gyro_status");
    let mut seen = std::collections::BTreeMap::new();
    for e in every_error() {
        let s = gyro_status::from(e);
        assert_ne!(s, GYRO_OK, "{e:?}");
        if let Some(other) = seen.insert(s as u32, e) {
            panic!("{e:?} and {other:?} share the code {s:?}");
        }
        let declaration = format!("{s:?} = {},", s as u32);
        let at = body
            .find(&declaration)
            .unwrap_or_else(|| panic!("the header declares `{declaration}`"));
        assert!(
            body[..at].trim_end().ends_with("*/"),
            "{s:?} has a comment in the header"
        );
    }
    assert_eq!(seen.len(), every_error().len());
}

/// The C parameter structs follow the library's parameter table: the header's fields are the
/// choices then `Params::FLAT_NAMES` in order, every field reaches its parameter (distinct
/// values through the struct come out of `Params::values` in the order of `Params::NAMES`, and
/// back), and the default struct holds `Params::default()`.
#[test]
fn parameter_structs_follow_the_library_table() {
    use gyrostat::estimation::Params;
    for name in ["gyro_estimator_params_f32", "gyro_estimator_params_f64"] {
        let body = header_body(name);
        let fields: Vec<&str> = body
            .lines()
            .map(str::trim)
            .filter(|l| l.ends_with(';') && !l.starts_with('*'))
            .map(|l| l.trim_end_matches(';').rsplit(' ').next().unwrap())
            .collect();
        let mut want = vec![
            "frame",
            "fixed_gains",
            "heading_time_constant",
            "mode",
            "correction_period",
            "rate_rule",
        ];
        want.extend(Params::<f64>::FLAT_NAMES);
        assert_eq!(fields, want, "{name}");
    }
    macro_rules! check {
        ($( $(#[$m:meta])* $flat:ident $(@ $g:ident . $f:ident)? : $d:expr, $dom:ident; )*) => {{
            let mut c = gyro_estimator_params_f64::default();
            unsafe {
                assert_eq!(gyro_estimator_f64_default_params(&mut c), GYRO_OK);
            }
            assert_eq!([$(c.$flat),*], Params::<f64>::default().values());
            let mut k = 0.0;
            $(
                k += 1.0;
                c.$flat = k / 8.0;
            )*
            let p = c.to_params().unwrap();
            let want: Vec<f64> = (1..=Params::<f64>::NAMES.len()).map(|k| k as f64 / 8.0).collect();
            assert_eq!(p.values().to_vec(), want);
            assert_eq!(gyro_estimator_params_f64::from_params(&p), c);
            let c32 = gyro_estimator_params_f32::from_params(&p.map(|x| x as f32));
            assert_eq!([$(f64::from(c32.$flat)),*].to_vec(), want);
        }};
    }
    gyrostat::estimator_parameters!(check);
}

/// `gyro_estimator_params_*_set` reaches, for every name of the parameter file, the parameter
/// of that name (the library's `Params::parameter_mut`); an unknown or dotless-group name, a
/// name without its NUL within 64 bytes and a NULL pointer are errors that change nothing.
#[test]
fn parameters_are_set_by_name() {
    use gyrostat::estimation::Params;
    use std::ffi::CString;
    for (k, name) in Params::<f64>::NAMES.iter().enumerate() {
        let value = k as f64 + 0.25;
        let mut c = gyro_estimator_params_f64::default();
        let mut c32 = gyro_estimator_params_f32::default();
        let cname = CString::new(*name).unwrap();
        unsafe {
            assert_eq!(gyro_estimator_f64_default_params(&mut c), GYRO_OK);
            assert_eq!(gyro_estimator_f32_default_params(&mut c32), GYRO_OK);
            assert_eq!(
                gyro_estimator_params_f64_set(&mut c, cname.as_ptr(), value),
                GYRO_OK
            );
            assert_eq!(
                gyro_estimator_params_f32_set(&mut c32, cname.as_ptr(), value as f32),
                GYRO_OK
            );
        }
        let mut want = Params::<f64>::default();
        *want.parameter_mut(name).unwrap() = value;
        assert_eq!(c.to_params().unwrap(), want, "{name}");
        assert_eq!(c32.to_params().unwrap(), want.map(|x| x as f32), "{name}");
    }
    let mut c = gyro_estimator_params_f64::default();
    unsafe {
        assert_eq!(gyro_estimator_f64_default_params(&mut c), GYRO_OK);
    }
    let before = c;
    let long = "x".repeat(100);
    for bad in [
        "field_norm",
        "heading_time_constant",
        "",
        "gyro_noise_density ",
        long.as_str(),
    ] {
        let cname = CString::new(bad).unwrap();
        unsafe {
            assert_eq!(
                gyro_estimator_params_f64_set(&mut c, cname.as_ptr(), 1.0),
                GYRO_INVALID_ARGUMENT,
                "{bad:?}"
            );
        }
    }
    let cname = CString::new("rest.gyro").unwrap();
    unsafe {
        assert_eq!(
            gyro_estimator_params_f64_set(&mut c, null(), 1.0),
            GYRO_BAD_POINTER
        );
        assert_eq!(
            gyro_estimator_params_f64_set(null_mut(), cname.as_ptr(), 1.0),
            GYRO_BAD_POINTER
        );
    }
    assert_eq!(c, before);
}
