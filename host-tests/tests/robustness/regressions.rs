//! Named regression tests: every library case listed by the robustness issue (an adversarial
//! campaign found them returning `Ok` with NaN, infinity, a zero quaternion or a wrong
//! rotation), each pinned to its typed error or to a correct finite result, in f32 and f64 where
//! the case has a value for both. The command-line tools have their own tests.

use gyrostat::dynamics::closed_form::analysis::rotational_energy;
use gyrostat::dynamics::closed_form::elliptic::{carlson_rf, incomplete_f, sn_cn_dn};
use gyrostat::dynamics::closed_form::free_rigid_body::Regime;
use gyrostat::dynamics::{FreeRigidBody, Gyrostat, Inertia, Integrator, State};
use gyrostat::propagation::kinematics::body_rate_between;
use gyrostat::propagation::{
    ConingAccumulator, ConingRule, IncrementIntegrator, Normalization, RateIntegrator, RateMethod,
};
use gyrostat::rotation::{AxisAngle, Euler, EulerSequence, Frame, GimbalPolicy, Mrp};
use gyrostat::{Axis, Dcm, Error, Mat3, Quat, UnitQuat, Vec3};
use host_tests::campaign::{Limits, norm_error};
use host_tests::cast::vec3;

/// `Gyrostat::step` with RK4 from `J = (1e60, 0, 0)` on the unit sphere, `dt = 1`: the squared
/// norm of the RK4 quaternion overflowed, the renormalisation multiplied by zero and the step
/// returned `Ok` with the zero quaternion.
#[test]
fn rk4_long_step_zero_quaternion_f64() {
    let body = Gyrostat::rigid(Inertia::try_from_principal(Vec3::new(1.0f64, 1.0, 1.0)).unwrap());
    let s = State::new(UnitQuat::IDENTITY, Vec3::new(1e60, 0.0, 0.0));
    assert_eq!(body.step(Integrator::Rk4, &s, 1.0), Err(Error::StepTooLong));
}

/// The same defect with plausible f32 values: `|ω|·dt ≈ 1000` rad per step.
#[test]
fn rk4_long_step_zero_quaternion_f32() {
    let i =
        Inertia::try_from_principal(Vec3::new(0.546_691_24f32, 1.350_183_6, 1.890_168_4)).unwrap();
    let body = Gyrostat::rigid(i);
    let s = State::new(
        UnitQuat::IDENTITY,
        Vec3::new(-57.255_016f32, 24.834_936, -0.919_495_7),
    );
    for integ in Integrator::ALL {
        assert_eq!(
            body.step(integ, &s, 10.0),
            Err(Error::StepTooLong),
            "{integ:?}"
        );
    }
    // Within the limit the same body steps, and the result is a unit attitude.
    let w = body.omega(&s).norm();
    let ok = body.step(Integrator::Rk4, &s, 0.5 / w).unwrap();
    assert!(norm_error(ok.attitude) < 1e-6);
}

/// `RateIntegrator` with RK4 and the default fast renormalisation, `dt = 0.1`, samples of
/// 100 rad/s: |q| grew to 4.9e3, 6e14, 1e48, all `Ok`.
#[test]
fn rate_integrator_rk4_fast_long_step() {
    let mut integ = RateIntegrator::try_new(
        UnitQuat::<f64>::IDENTITY,
        RateMethod::Rk4,
        Normalization::Fast,
        0.1,
    )
    .unwrap();
    for _ in 0..4 {
        assert_eq!(
            integ.push(Vec3::new(100.0, 0.0, 0.0)),
            Err(Error::StepTooLong)
        );
    }
    // At about 30 rad/s (3 rad per step, within π) every attitude is unit.
    let mut integ = RateIntegrator::try_new(
        UnitQuat::<f64>::IDENTITY,
        RateMethod::Rk4,
        Normalization::Fast,
        0.1,
    )
    .unwrap();
    for k in 0..8 {
        let w = Vec3::new(29.0, f64::from(k), 0.0);
        for q in integ.push(w).unwrap() {
            assert!(norm_error(q) < 1e-14, "{q:?}");
        }
    }
}

/// `RateIntegrator::try_new` accepted `dt = 1e300`; the attitudes were NaN.
#[test]
fn rate_integrator_huge_dt() {
    let mut integ = RateIntegrator::try_new(
        UnitQuat::<f64>::IDENTITY,
        RateMethod::Magnus4,
        Normalization::Fast,
        1e300,
    )
    .unwrap();
    assert_eq!(
        integ.push(Vec3::new(1e-3, 0.0, 0.0)),
        Err(Error::StepTooLong)
    );
    // A body at rest is within any step.
    for _ in 0..4 {
        for q in integ.push(Vec3::ZERO).unwrap() {
            assert_eq!(q, UnitQuat::IDENTITY);
        }
    }
}

/// Moments 65 ε apart (above the 16 ε tolerance for equal moments) were classed as a
/// separatrix (the tolerance was relative to `J²`, not to the terms of `J² − 2E·I_mid`), and
/// `try_state_at(0.0)` gave `J.x = 0.2345` instead of 1.0027.
#[test]
fn free_body_nearly_equal_moments_not_a_separatrix() {
    let i = Inertia::try_from_principal(Vec3::new(
        0.372_219_245_709_405_2f64,
        0.372_219_245_709_410_45,
        0.372_219_245_709_415_8,
    ))
    .unwrap();
    let j0 = Vec3::new(
        1.002_698_129_079_976,
        4.245_196_742_473_897,
        0.221_903_944_383_328_83,
    );
    let body = FreeRigidBody::try_new(&i, &State::new(UnitQuat::IDENTITY, j0)).unwrap();
    assert!(
        matches!(body.regime(), Regime::Circulating { .. }),
        "{:?}",
        body.regime()
    );
    let s = body.try_state_at(0.0).unwrap();
    assert!(
        (s.momentum - j0).norm() < 1e-12 * j0.norm(),
        "{:?}",
        s.momentum
    );
    assert!(s.attitude.angle_to(UnitQuat::IDENTITY) < 1e-12);
    // And it stays on the momentum sphere.
    let s = body.try_state_at(10.0).unwrap();
    assert!((s.momentum.norm() - j0.norm()).abs() < 1e-12 * j0.norm());
}

/// `Inertia::try_from_components((1, 1, 1), (1e308, 1e308, 1e308))` returned `Ok` with NaN
/// moments and inverse.
#[test]
fn inertia_huge_off_diagonal_f64() {
    let r =
        Inertia::try_from_components(Vec3::new(1.0f64, 1.0, 1.0), Vec3::new(1e308, 1e308, 1e308));
    assert_eq!(r, Err(Error::NonPhysicalInertia));
}

/// The f32 form: off-diagonals (4.1301284e37, 1.8202964e38, 1.0295708e37).
#[test]
fn inertia_huge_off_diagonal_f32() {
    let r = Inertia::try_from_components(
        Vec3::new(1.0f32, 1.0, 1.0),
        Vec3::new(4.130_128_4e37, 1.820_296_4e38, 1.029_570_8e37),
    );
    assert_eq!(r, Err(Error::NonPhysicalInertia));
}

/// Found by the long campaign: an f32 attitude 1.5e-7 rad from the pole of `ZXY` (extrinsic)
/// came back from `to_euler` encoding a rotation 1.0e-6 rad off (over the 1e-6 contract), with
/// every gimbal policy at 0.9e-6 or more. Cause: the locked combination `first + s·third` was
/// summed from the wrapped outer angles (four roundings of angles up to π) and each wrap took
/// `2π` rounded to f32 (off by 1.7e-7). Now it is twice one half-angle, wrapped once with `2π`
/// in two parts; what remains is libm's `atan2f` (2e-7 here, doubled) and the split.
#[test]
fn euler_pole_f32_contract() {
    let a = [-0.332_099_38f32, -0.332_099_3, -0.624_267_7, 0.624_267_64];
    let q = UnitQuat::new_unchecked(Quat::from_array(a));
    let exact = UnitQuat::try_new(Quat::from_array(a.map(f64::from))).unwrap();
    let seq = EulerSequence::try_new(Axis::Z, Axis::X, Axis::Y, Frame::Extrinsic).unwrap();
    for policy in [
        GimbalPolicy::ZeroFirst,
        GimbalPolicy::ZeroThird,
        GimbalPolicy::ClosestTo([-3.212_433_8e25, -4.635_519_3e-21, 2.141_285_7e35]),
        GimbalPolicy::ClosestTo([1.0, 0.0, 2.0]),
    ] {
        let sol = q.to_euler(seq, policy);
        assert!(sol.singularity.is_some(), "{policy:?}");
        let back = Euler::new(seq, sol.euler.angles.map(f64::from)).to_unit_quat_unchecked();
        let err = back.angle_to(exact);
        assert!(err < 6e-7, "{policy:?}: {:?} is {err:e} rad off", sol.euler);
    }
}

host_tests::per_type! {
    /// `UnitQuat::try_new` of a quaternion with one subnormal component returned `Ok(NaN)`.
    #[test]
    fn subnormal_quaternion_is_zero_norm() {
        let tiny = T::from_f64(Limits::of::<T>().min_subnormal);
        let z = T::ZERO;
        assert_eq!(UnitQuat::try_new(Quat::new(z, tiny, z, z)), Err(Error::ZeroNorm));
        assert_eq!(Quat::new(tiny, z, z, z).try_normalize(), Err(Error::ZeroNorm));
    }

    /// `Vec3::try_normalize` of a subnormal vector returned `Ok((inf, NaN, NaN))`; it reached
    /// `AxisAngle::try_new`, `UnitQuat::try_from_axis_angle` and `Wheel::try_new`.
    #[test]
    fn subnormal_vector_normalizes() {
        let tiny = T::from_f64(Limits::of::<T>().min_subnormal);
        let v = Vec3::new(tiny, T::ZERO, T::ZERO);
        assert_eq!(v.try_normalize(), Ok(Vec3::X));
        let a = AxisAngle::try_new(v, T::ONE).unwrap();
        assert_eq!(a.axis(), Vec3::X);
        let q = UnitQuat::try_from_axis_angle(v, T::ONE).unwrap();
        assert!(norm_error(q) < 4.0 * T::EPSILON.to_f64());
        let w = gyrostat::dynamics::Wheel::try_new(v, T::ONE).unwrap();
        assert_eq!(w.axis(), Vec3::X);
    }

    /// `AxisAngle::from(UnitQuat::try_exp((1e-309, 0, 0)))` (f32: 1e-40) had a NaN axis.
    #[test]
    fn tiny_rotation_axis_angle() {
        let q = UnitQuat::try_exp(vec3::<T>([T::per_type(1e-40, 1e-309), 0.0, 0.0])).unwrap();
        for a in [AxisAngle::from(q), AxisAngle::from_unit_quat(q)] {
            assert_eq!(a.axis(), Vec3::X);
            assert!(a.angle().is_finite());
        }
    }

    /// `Quat::try_inverse` of a quaternion near 1e-160 (f32: 1e-21) returned infinities: its
    /// inverse is representable and now computed.
    #[test]
    fn tiny_quaternion_inverse() {
        let s = T::per_type(1e-21, 1e-160);
        let q = Quat::from_array([1.0, 2.0, -2.0, 4.0].map(|c| T::from_f64(c * s)));
        let inv = q.try_inverse().unwrap();
        let p = q * inv;
        assert!((p.w.to_f64() - 1.0).abs() < 8.0 * T::EPSILON.to_f64(), "{p:?}");
        assert!(p.vector().norm().to_f64() < 8.0 * T::EPSILON.to_f64(), "{p:?}");
    }

    /// `Mat3::try_inverse` of 1e-105·I (f32: 1e-15·I) returned infinities.
    #[test]
    fn tiny_matrix_inverse() {
        let s = T::per_type(1e-15, 1e-105);
        let m = Mat3::IDENTITY.scale(T::from_f64(s));
        let inv = m.try_inverse().unwrap();
        assert!(((inv * m) - Mat3::IDENTITY).max_abs().to_f64() < 4.0 * T::EPSILON.to_f64());
    }

    /// `Mrp::try_shadow` of σ near 1e-160 (f32: 1e-21) returned infinities.
    #[test]
    fn tiny_mrp_shadow() {
        let s = T::per_type(1e-21, 1e-160);
        let m = Mrp::try_new(vec3::<T>([s, 0.0, 0.0])).unwrap();
        let sh = m.try_shadow().unwrap();
        assert!(sh.vector().is_finite());
        assert!((sh.vector().x.to_f64() * s + 1.0).abs() < 4.0 * T::EPSILON.to_f64());
    }

    /// `body_rate_between` with `dt = 1e-320` (f32: 1e-44) returned `Ok(inf)`.
    #[test]
    fn subnormal_dt_rate_between() {
        let q1 = UnitQuat::try_exp(vec3::<T>([0.1, 0.0, 0.0])).unwrap();
        let dt = T::from_f64(T::per_type(1e-44, 1e-320));
        assert_eq!(
            body_rate_between(UnitQuat::IDENTITY, q1, dt),
            Err(Error::InvalidArgument)
        );
    }

    /// `Inertia::try_from_principal` of 1e-320 (f32: 1e-44) was `Ok`, with a NaN energy after.
    #[test]
    fn subnormal_moments() {
        let m = T::from_f64(T::per_type(1e-44, 1e-320));
        assert_eq!(
            Inertia::try_from_principal(Vec3::new(m, m, m)),
            Err(Error::InvalidArgument)
        );
    }

    /// Euler rates from ω = (MAX, 0, MAX) returned `Ok([inf, 0, inf])` (at a pitch of 1.2 rad
    /// the inverse rate matrix has entries up to 1/cos 1.2 ≈ 2.8).
    #[test]
    fn euler_rates_overflow() {
        let max = T::from_f64(Limits::of::<T>().max);
        let e = Euler::new(EulerSequence::ZYX, [0.3, 1.2, -0.4].map(T::from_f64));
        assert_eq!(
            e.try_rates_from_body(Vec3::new(max, T::ZERO, max)),
            Err(Error::InvalidArgument)
        );
    }

    /// `slerp(.., MAX)` returned NaN.
    #[test]
    fn slerp_huge_t() {
        let a = UnitQuat::try_exp(vec3::<T>([0.3, -0.2, 0.1])).unwrap();
        let b = UnitQuat::try_exp(vec3::<T>([-1.0, 2.0, 0.5])).unwrap();
        let max = T::from_f64(Limits::of::<T>().max);
        for t in [max, -max, max * T::HALF] {
            let q = a.slerp(b, t);
            assert!(norm_error(q) < 8.0 * T::EPSILON.to_f64(), "{q:?}");
        }
    }

    /// Coning pushes of 1e200 (f32: 1e30) returned `Ok(NaN/inf)`; the two-speed accumulator
    /// too (f32: 1e20).
    #[test]
    fn coning_huge_increments() {
        let huge = vec3::<T>([T::per_type(1e30, 1e200), 0.5, 0.0]);
        for rule in ConingRule::ALL {
            let mut integ = IncrementIntegrator::new(UnitQuat::IDENTITY, rule, Normalization::Fast);
            // The exact exponential takes any increment whose square is finite (this one's is
            // not); the coning rules stop at their step limit.
            let want = if rule == ConingRule::Exp {
                Error::InvalidArgument
            } else {
                Error::StepTooLong
            };
            assert_eq!(integ.push(huge), Err(want), "{rule:?}");
            assert_eq!(integ.pending(), 0);
        }
        // A long rotation vector is applied as given by the exact exponential: 10 rad about z
        // is 10 − 2π ≈ 3.717 rad about z.
        let mut integ =
            IncrementIntegrator::new(UnitQuat::IDENTITY, ConingRule::Exp, Normalization::Exact);
        let q = integ.push(vec3::<T>([0.0, 0.0, 10.0])).unwrap().unwrap();
        let want = UnitQuat::try_from_axis_angle(vec3::<T>([0.0, 0.0, 1.0]), T::from_f64(10.0));
        assert!(q.angle_to(want.unwrap()).to_f64() < T::CONTRACT * 10.0, "{q:?}");
        let mut acc = ConingAccumulator::<T>::new();
        let big = vec3::<T>([T::per_type(1e20, 1e200), 1.0, 0.0]);
        assert_eq!(acc.push(big), Err(Error::StepTooLong));
        assert_eq!(acc.count(), 0);
    }

    /// The elliptic functions at the range's ends returned NaN or infinity:
    /// `carlson_rf(0.5, MAX, MAX)` (finite: R_F is homogeneous), `sn_cn_dn(MAX, 0.87)` and
    /// `incomplete_f(MAX, 0.5)` (arguments beyond 1/ε: a typed error).
    #[test]
    fn elliptic_extremes() {
        let max = T::from_f64(Limits::of::<T>().max);
        let rf = carlson_rf(T::HALF, max, max).unwrap();
        assert!(rf.is_finite() && rf > T::ZERO);
        // R_F(x, y, y) ≈ π/(2√y) for y ≫ x.
        let want = std::f64::consts::FRAC_PI_2 / max.to_f64().sqrt();
        assert!((rf.to_f64() - want).abs() < 1e-3 * want, "{rf:?} {want}");
        assert_eq!(sn_cn_dn(max, T::from_f64(0.87)), Err(Error::InvalidArgument));
        assert_eq!(incomplete_f(max, T::HALF), Err(Error::InvalidArgument));
    }

    /// `rotational_energy((6, 4, 3), 1e200, ..)` (f32: 1e20) returned `Ok(inf)`.
    #[test]
    fn rotational_energy_overflow() {
        let i = Inertia::try_from_principal(vec3::<T>([6.0, 4.0, 3.0])).unwrap();
        let j = T::from_f64(T::per_type(1e20, 1e200));
        assert_eq!(
            rotational_energy(&i, j, T::HALF, T::HALF),
            Err(Error::InvalidArgument)
        );
    }

    /// `to_euler` with `ClosestTo([p, 0, 0])` at the pole encoded the wrong rotation for a huge
    /// previous angle p (f32: 8e-4 rad at p = 1e12).
    #[test]
    fn euler_closest_to_huge_previous() {
        let seq = EulerSequence::ZYX;
        let e = Euler::new(seq, [T::from_f64(0.3), T::FRAC_PI_2, T::from_f64(0.1)]);
        let q = e.to_unit_quat_unchecked();
        for p in [1e12, -3e20, T::per_type(3e38, 1e300)] {
            let sol = q.to_euler(seq, GimbalPolicy::ClosestTo([T::from_f64(p), T::ZERO, T::ZERO]));
            assert!(sol.singularity.is_some());
            for a in sol.euler.angles {
                assert!(a.to_f64().abs() <= std::f64::consts::PI + 1e-6, "{:?}", sol.euler);
            }
            let back = sol.euler.to_unit_quat_unchecked();
            assert!(back.angle_to(q).to_f64() < T::CONTRACT, "p = {p}: {:?}", sol.euler);
        }
    }

    /// `Dcm::try_from_matrix(1e154·I, MAX)` returned `Ok`, then a zero quaternion; a tolerance
    /// of one or more is outside the domain.
    #[test]
    fn dcm_tolerance_domain() {
        let max = T::from_f64(Limits::of::<T>().max);
        let m = Mat3::IDENTITY.scale(T::from_f64(T::per_type(1e19, 1e154)));
        assert_eq!(Dcm::try_from_matrix(m, max), Err(Error::InvalidArgument));
        assert_eq!(Dcm::try_from_matrix(Mat3::IDENTITY, T::ONE), Err(Error::InvalidArgument));
        assert_eq!(Dcm::try_from_matrix(Mat3::IDENTITY, -T::EPSILON), Err(Error::InvalidArgument));
        assert!(Dcm::try_from_matrix(Mat3::IDENTITY, T::HALF).is_ok());
    }

    /// `try_from_near_unit(Quat::ZERO, 2.0)` returned `Ok(NaN)`.
    #[test]
    fn near_unit_tolerance_domain() {
        assert_eq!(
            UnitQuat::try_from_near_unit(Quat::<T>::ZERO, T::TWO),
            Err(Error::InvalidArgument)
        );
        assert_eq!(
            UnitQuat::try_from_near_unit(Quat::<T>::ZERO, T::from_f64(0.999)),
            Err(Error::NotUnit)
        );
    }
}

/// Fixed point: increments whose sums saturate Q1.30 were accepted by the checked pushes, and
/// the attitude moved by the saturated (wrong) rotation. Two increments of 1.5 rad about x sum to
/// 3 rad, within the step limit but beyond Q1.30's 2: the accumulator now refuses the second;
/// the increment integrator refuses components of a quarter of the range (0.25 rad) or more.
#[test]
fn fixed_point_saturating_sums_are_out_of_range() {
    use gyrostat::real::Q30;
    let x = |v: f64| {
        Vec3::new(
            Q30::try_from_f64(v).unwrap(),
            Q30::from_bits(0),
            Q30::from_bits(0),
        )
    };
    let mut acc = ConingAccumulator::<Q30>::new();
    assert_eq!(acc.push(x(1.5)), Ok(()));
    assert_eq!(acc.push(x(1.5)), Err(Error::OutOfRange));
    assert_eq!(acc.rotation_vector(), x(1.5));
    let mut it = IncrementIntegrator::new(
        UnitQuat::<Q30>::IDENTITY,
        ConingRule::TwoSample,
        Normalization::Fast,
    );
    assert_eq!(it.push(x(0.3)), Err(Error::OutOfRange));
    assert_eq!(it.push(x(0.2)), Ok(None));
}
