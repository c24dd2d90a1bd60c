//! One name for `q ⊗ exp(φ)` on every attitude type: `mul_exp_unchecked(φ, norm)` and the
//! checked `try_mul_exp(φ, norm)` on `UnitQuat`, `CompensatedAttitude` and `CarriedAttitude`, for
//! a vector, a coning rule's terms and a compensated pair, against the closed-form exponential
//! of the reference (`host_tests::reference`).

use gyrostat::propagation::coning::two_sample_terms;
use gyrostat::propagation::{CarriedAttitude, CompensatedAttitude, Normalization};
use gyrostat::real::Q30;
use gyrostat::{Error, UnitQuat, Vec3};
use host_tests::cast::{q64, vec3};
use host_tests::reference::{Q, qmul, quat_angle};

/// `exp(φ)` in closed form.
fn exp_ref(phi: [f64; 3]) -> Q {
    let t = (phi[0] * phi[0] + phi[1] * phi[1] + phi[2] * phi[2]).sqrt();
    let (s, c) = (0.5 * t).sin_cos();
    let k = if t > 0.0 { s / t } else { 0.5 };
    [c, k * phi[0], k * phi[1], k * phi[2]]
}

#[test]
fn every_attitude_type_takes_the_same_update() {
    let q0 = UnitQuat::<f64>::try_from_axis_angle(Vec3::new(0.3, -0.5, 0.8), 0.9).unwrap();
    let phi = [0.012, -0.007, 0.021];
    let want = qmul(q64(q0), exp_ref(phi));
    let n = Normalization::Exact;
    let plain = q0.mul_exp_unchecked(vec3::<f64>(phi), n);
    let checked = q0.try_mul_exp(vec3::<f64>(phi), n).unwrap();
    assert_eq!(plain, checked);
    assert!(quat_angle(q64(plain), want) < 1e-15);
    let comp = CompensatedAttitude::new(q0).mul_exp_unchecked(vec3::<f64>(phi), n);
    assert!(quat_angle(q64(comp.attitude()), want) < 1e-15);
    // A compensated pair (φ, φ_lo) is φ + φ_lo on every type.
    let (hi, lo) = (
        vec3::<f64>([0.01, -0.007, 0.02]),
        vec3::<f64>([0.002, 0.0, 0.001]),
    );
    assert!(quat_angle(q64(q0.mul_exp_unchecked((hi, lo), n)), want) < 1e-15);
    assert!(
        quat_angle(
            q64(CompensatedAttitude::new(q0)
                .mul_exp_unchecked((hi, lo), n)
                .attitude()),
            want
        ) < 1e-15
    );
    // A coning rule's terms: the 2-sample rule's φ = θ₁ + θ₂ + ⅔ θ₁ × θ₂.
    let (t1, t2) = ([0.004, 0.001, -0.002], [0.003, -0.002, 0.001]);
    let c = [
        t1[1] * t2[2] - t1[2] * t2[1],
        t1[2] * t2[0] - t1[0] * t2[2],
        t1[0] * t2[1] - t1[1] * t2[0],
    ];
    let rule = exp_ref([0, 1, 2].map(|i| t1[i] + t2[i] + 2.0 / 3.0 * c[i]));
    let want = qmul(q64(q0), rule);
    let terms = two_sample_terms(vec3::<f64>(t1), vec3::<f64>(t2));
    assert!(quat_angle(q64(q0.mul_exp_unchecked(terms, n)), want) < 1e-15);
    let comp = CompensatedAttitude::new(q0).mul_exp_unchecked(terms, n);
    assert!(quat_angle(q64(comp.attitude()), want) < 1e-15);
    let comp2 = CompensatedAttitude::new(q0).coning2_update(vec3(t1), vec3(t2));
    assert!(quat_angle(q64(comp2.attitude()), want) < 1e-15);
    // Fixed point: the carried attitude, within a few units of 2⁻³⁰.
    let qq = UnitQuat::<Q30>::try_from_f64(q0).unwrap();
    let tq = |v: [f64; 3]| Vec3::<Q30>::try_from_f64(Vec3::from_array(v)).unwrap();
    let carried = CarriedAttitude::new(qq)
        .try_mul_exp(two_sample_terms(tq(t1), tq(t2)), Normalization::Fast)
        .unwrap();
    assert!(quat_angle(carried.attitude().to_f64().to_array(), want) < 1e-8);
    let same = CarriedAttitude::new(qq).coning2_update(tq(t1), tq(t2));
    assert_eq!(same, carried);
}

#[test]
fn the_checked_update_rejects_what_the_integrators_reject() {
    let q = UnitQuat::<f32>::IDENTITY;
    let n = Normalization::Fast;
    assert_eq!(
        q.try_mul_exp(Vec3::new(f32::NAN, 0.0, 0.0), n),
        Err(Error::NonFinite)
    );
    // Half a turn is the limit (step_limit::MAX_STEP_ANGLE), beyond it StepTooLong.
    assert!(q.try_mul_exp(Vec3::new(3.1, 0.0, 0.0), n).is_ok());
    assert_eq!(
        q.try_mul_exp(Vec3::new(3.15, 0.0, 0.0), n),
        Err(Error::StepTooLong)
    );
    let c = CompensatedAttitude::new(UnitQuat::<f64>::IDENTITY);
    assert_eq!(
        c.try_mul_exp((Vec3::new(3.0, 0.0, 0.0), Vec3::new(0.2, 0.0, 0.0)), n),
        Err(Error::StepTooLong)
    );
    let carried = CarriedAttitude::new(UnitQuat::<Q30>::IDENTITY);
    let big = Vec3::<Q30>::try_from_f64(Vec3::new(1.9, 1.9, 1.9)).unwrap();
    assert_eq!(carried.try_mul_exp(big, n), Err(Error::StepTooLong));
}
