//! The estimator's prediction from gyroscope increments goes through the propagation core: the
//! one-plus-previous coning rule of `gyrostat::propagation::coning`, on the bias-corrected
//! increments. Checked against the closed-form coning motion (`host_tests::ref_propagation`,
//! independent of the library), with the accelerometer unusable after the first sample so that
//! only the prediction moves the attitude.

use gyrostat::estimation::{Estimator, Params};
use gyrostat::propagation::{ConingRule, IncrementIntegrator, Normalization};
use gyrostat::{Quat, UnitQuat, Vec3};
use host_tests::cast::{q64, vec3};
use host_tests::ref_propagation::Coning;
use host_tests::reference::{Q, qconj, qmul, quat_angle};

/// The rotation from `a` to `b` in the body frame, `a* ⊗ b`.
fn relative(a: Q, b: Q) -> Q {
    qmul(qconj(a), b)
}

/// Classical coning (half-angle 0.05 rad at 5 Hz) sampled as increments at 100 Hz for 20 s:
/// the estimator's attitude change follows the closed form with the one-plus-previous rule's
/// drift (`α²Ω(Ωh)⁴/60`, 1.3e-5 rad/s here), not the single exponential's (`α²Ω(Ωh)²/12`,
/// 6.5e-4 rad/s), and equals the propagation module's `IncrementIntegrator` with
/// `ConingRule::OnePlusPrevious` to rounding.
#[test]
fn increments_take_the_coning_rule() {
    let cone = Coning {
        alpha: 0.05,
        omega_c: 2.0 * core::f64::consts::PI * 5.0,
    };
    let h = 0.01;
    let n = 2000;
    let p = Params {
        gyro_delay: 0.0,
        ..Params::default()
    };
    let mut f = Estimator::<f64>::try_new(p).unwrap();
    // The first sample initialises the attitude from gravity (the sensor is turning, so the
    // increment of the step before it gives the rate the rest detector starts from).
    let g = vec3([0.0, 0.0, 9.81]);
    let first = f
        .update_increment(vec3(cone.increment(-h, 0.0)), g, None, h)
        .unwrap();
    assert!(first.initialized);
    let start = q64(f.attitude());
    let mut exp = IncrementIntegrator::new(
        UnitQuat::<f64>::IDENTITY,
        ConingRule::Exp,
        Normalization::Fast,
    );
    let mut rule = IncrementIntegrator::new(
        UnitQuat::<f64>::IDENTITY,
        ConingRule::OnePlusPrevious,
        Normalization::Fast,
    );
    // The rule's previous increment: the one before the first step.
    rule.push(vec3(cone.increment(-h, 0.0))).unwrap();
    let reset = rule.attitude();
    let mut rule_q = UnitQuat::<f64>::IDENTITY;
    for k in 0..n {
        let d = cone.increment(k as f64 * h, (k + 1) as f64 * h);
        // No usable accelerometer (zero) and no magnetometer: no correction.
        f.update_increment(vec3(d), Vec3::ZERO, None, h).unwrap();
        exp.push(vec3(d)).unwrap();
        rule.push(vec3(d)).unwrap();
        rule_q = reset.inverse() * rule.attitude();
    }
    let t = n as f64 * h;
    let truth = relative(cone.attitude(0.0), cone.attitude(t));
    let est = relative(start, q64(f.attitude()));
    let err = quat_angle(truth, est);
    let err_exp = quat_angle(truth, q64(exp.attitude()));
    let to_rule = quat_angle(q64(rule_q), est);
    // One-plus-previous: 1.3e-5 rad/s · 20 s = 2.6e-4 rad; the exponential alone 1.3e-2 rad.
    assert!(err < 5e-4, "estimator {err:e} rad from the closed form");
    assert!(err_exp > 20.0 * err, "exp rule {err_exp:e} against {err:e}");
    assert!(
        to_rule < 1e-9,
        "estimator {to_rule:e} rad from the propagation module's rule"
    );
    // The quaternion of the estimate is unit (the fast renormalisation of the kernel).
    let q = Quat::from_array(q64(f.attitude()));
    assert!((q.norm() - 1.0).abs() < 1e-12);
}
