//! Named regression tests for the second, independent adversarial campaign (issue 19): its 17
//! reproducers with their exact inputs, each asserting the documented contract — a unit
//! attitude, an `Ok` that satisfies its equation or equals the rule's composition of
//! exponentials (computed here independently in f64), a typed error — in f32 and f64 where both
//! apply. A panic fails the test (nothing here catches one).

use gyrostat::dynamics::semi_rigid::{Arrangement, QuarticBasis, SemiRigidRotor, SpringRotor};
use gyrostat::dynamics::state::CompensatedState;
use gyrostat::dynamics::{
    BodyHamiltonian, Drift, Gyrostat, Inertia, Integrator, Invariants, Quartic, State,
};
use gyrostat::propagation::kernels::rk4_step;
use gyrostat::propagation::{
    CompensatedAttitude, ConingRule, IncrementIntegrator, Normalization, RateIntegrator, RateMethod,
};
use gyrostat::real::{Fixed, Q24, Q30};
use gyrostat::{Error, Quat, Real, UnitQuat, Vec3};

/// `|q|` of a quaternion, in f64.
fn norm<T: Real>(q: Quat<T>) -> f64 {
    q.to_array()
        .iter()
        .map(|c| c.to_f64() * c.to_f64())
        .sum::<f64>()
        .sqrt()
}

/// The attitude `q + q_lo` of a compensated attitude, normalised, in f64.
fn carried<T: Real>(c: CompensatedAttitude<T>) -> [f64; 4] {
    let (q, lo) = (c.attitude().into_quat().to_array(), c.low().to_array());
    let v: [f64; 4] = core::array::from_fn(|i| q[i].to_f64() + lo[i].to_f64());
    let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    v.map(|x| x / n)
}

fn unit_f64<T: Real>(q: UnitQuat<T>) -> [f64; 4] {
    let v = q.into_quat().to_array().map(|c| c.to_f64());
    let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    v.map(|x| x / n)
}

/// The rotation angle between two attitudes (f64, sign-insensitive).
fn angle(a: [f64; 4], b: [f64; 4]) -> f64 {
    let d = mul_ref([a[0], -a[1], -a[2], -a[3]], b);
    let s = (d[1] * d[1] + d[2] * d[2] + d[3] * d[3]).sqrt();
    2.0 * s.atan2(d[0].abs())
}

/// `exp(φ)` in f64 by its closed form (independent of the library).
fn exp_ref(p: [f64; 3]) -> [f64; 4] {
    let t = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    if t == 0.0 {
        return [1.0, 0.0, 0.0, 0.0];
    }
    let s = (t / 2.0).sin() / t;
    [(t / 2.0).cos(), s * p[0], s * p[1], s * p[2]]
}

/// The Hamilton product `a ⊗ b` in f64.
fn mul_ref(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

fn v<T: Real>(x: f64, y: f64, z: f64) -> Vec3<T> {
    Vec3::new(T::from_f64(x), T::from_f64(y), T::from_f64(z))
}

fn sphere<T: Real>(i: f64) -> Gyrostat<T> {
    Gyrostat::rigid(Inertia::try_from_principal(v(i, i, i)).unwrap())
}

/// 1. Compensated RK4 step, sphere of inertia 1, J = (3, 0, 0), dt = 1 (|ω|dt = 3 < π): the
///    fast renormalisation had no exact fallback on the compensated path (|q| = 0.994955).
fn compensated_rk4_step_unit<T: Real>(tol: f64) {
    let body = sphere::<T>(1.0);
    let s = State::new(UnitQuat::IDENTITY, v(3.0, 0.0, 0.0));
    let plain = body.step(Integrator::Rk4, &s, T::ONE).unwrap();
    let comp = body
        .step(Integrator::Rk4, &CompensatedState::new(s), T::ONE)
        .unwrap();
    let n = norm(comp.state().attitude.into_quat());
    assert!((n - 1.0).abs() < tol, "|q| = {n}");
    let a = angle(unit_f64(plain.attitude), unit_f64(comp.state().attitude));
    assert!(a < 1e3 * tol, "compensated {a} rad from plain");
}

#[test]
fn r01_compensated_rk4_step_unit_f64() {
    compensated_rk4_step_unit::<f64>(1e-14);
}

#[test]
fn r01_compensated_rk4_step_unit_f32() {
    compensated_rk4_step_unit::<f32>(1e-6);
}

/// 2. Compensated rate integrator, RK4 + Fast, four samples (3, 0, 0), dt = 1 (|q| = 0.99397).
fn compensated_rate_rk4_fast_unit<T: Real>(tol: f64) {
    let q0 = CompensatedAttitude::new(UnitQuat::<T>::IDENTITY);
    let mut integ =
        RateIntegrator::try_new(q0, RateMethod::Rk4, Normalization::Fast, T::ONE).unwrap();
    for _ in 0..4 {
        for q in integ.push(v(3.0, 0.0, 0.0)).unwrap() {
            let n = norm(q.into_quat());
            assert!((n - 1.0).abs() < tol, "|q| = {n}");
        }
    }
    let n = norm(integ.attitude().into_quat());
    assert!((n - 1.0).abs() < tol, "|q| = {n}");
}

#[test]
fn r02_compensated_rate_rk4_fast_unit_f64() {
    compensated_rate_rk4_fast_unit::<f64>(1e-14);
}

#[test]
fn r02_compensated_rate_rk4_fast_unit_f32() {
    compensated_rate_rk4_fast_unit::<f32>(1e-6);
}

/// 3. The compensated two-sample update is `q ⊗ exp(φ)` with `φ` the rule's rotation vector:
///    increments (0.5, 0, 0), (0, 0.5, 0); the plain update is 4e-17 rad from it, the
///    compensated one was 3.5e-3 rad (the coning term added outside the exponential's angle).
fn compensated_coning_is_exp<T: Real>(tol: f64) {
    let (a, b) = ([0.5, 0.0, 0.0], [0.0, 0.5, 0.0]);
    // Two-sample rule: φ = a + b + (2/3) a × b.
    let c = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let phi: [f64; 3] = core::array::from_fn(|i| a[i] + b[i] + 2.0 / 3.0 * c[i]);
    let want = exp_ref(phi);
    for norm in [
        Normalization::Fast,
        Normalization::Exact,
        Normalization::None,
    ] {
        let q0 = CompensatedAttitude::new(UnitQuat::<T>::IDENTITY);
        let mut integ = IncrementIntegrator::new(q0, ConingRule::TwoSample, norm);
        integ.push(v(a[0], a[1], a[2])).unwrap();
        integ.push(v(b[0], b[1], b[2])).unwrap();
        let got = carried(integ.carried_attitude());
        let e = angle(got, want);
        assert!(e < tol, "{norm:?}: compensated {e} rad from exp(φ)");
        let mut plain =
            IncrementIntegrator::new(UnitQuat::<T>::IDENTITY, ConingRule::TwoSample, norm);
        plain.push(v(a[0], a[1], a[2])).unwrap();
        plain.push(v(b[0], b[1], b[2])).unwrap();
        let e = angle(unit_f64(plain.attitude()), want);
        assert!(e < tol, "{norm:?}: plain {e} rad from exp(φ)");
    }
    // mul_exp_unchecked(((0.5, 0, 0), (0, 0.05, 0))) is exp(φ + φ_lo).
    let q = CompensatedAttitude::new(UnitQuat::<T>::IDENTITY)
        .mul_exp_unchecked((v(0.5, 0.0, 0.0), v(0.0, 0.05, 0.0)), Normalization::Exact);
    let e = angle(carried(q), exp_ref([0.5, 0.05, 0.0]));
    assert!(
        e < tol,
        "mul_exp_unchecked of a pair {e} rad from exp(φ + φ_lo)"
    );
}

#[test]
fn r03_compensated_coning_is_exp_f64() {
    compensated_coning_is_exp::<f64>(1e-15);
}

#[test]
fn r03_compensated_coning_is_exp_f32() {
    compensated_coning_is_exp::<f32>(3e-7);
}

/// 4. Compensated Magnus-4 and CF4 equal the plain integrator: samples 0, (0.5,0,0),
///    (0,0.5,0), (0,0,0.5), dt = 1 (they were 2.45e-4 and 1.22e-3 rad apart).
fn compensated_rate_equals_plain<T: Real>(tol: f64) {
    let samples = [[0.0; 3], [0.5, 0.0, 0.0], [0.0, 0.5, 0.0], [0.0, 0.0, 0.5]];
    for method in [RateMethod::Magnus4, RateMethod::Cf4, RateMethod::Rk4] {
        let mut plain = RateIntegrator::try_new(
            UnitQuat::<T>::IDENTITY,
            method,
            Normalization::Exact,
            T::ONE,
        )
        .unwrap();
        let q0 = CompensatedAttitude::new(UnitQuat::<T>::IDENTITY);
        let mut comp = RateIntegrator::try_new(q0, method, Normalization::Exact, T::ONE).unwrap();
        for s in samples {
            let p: Vec<_> = plain
                .push(v(s[0], s[1], s[2]))
                .unwrap()
                .into_iter()
                .collect();
            let c: Vec<_> = comp
                .push(v(s[0], s[1], s[2]))
                .unwrap()
                .into_iter()
                .collect();
            assert_eq!(p.len(), c.len());
            for (p, c) in p.iter().zip(c.iter()) {
                let e = angle(unit_f64(*p), unit_f64(*c));
                assert!(e < tol, "{method:?}: compensated {e} rad from plain");
            }
        }
    }
}

#[test]
fn r04_compensated_magnus_cf4_equal_plain_f64() {
    compensated_rate_equals_plain::<f64>(1e-14);
}

#[test]
fn r04_compensated_magnus_cf4_equal_plain_f32() {
    compensated_rate_equals_plain::<f32>(1e-6);
}

/// 5. The compensated `Exp` rule with large increments (documented: any increment with a finite
///    squared norm): a unit attitude, the plain rule's rotation.
fn compensated_exp_large<T: Real>(mags: &[f64], tol: f64) {
    for &m in mags {
        for norm in [Normalization::Fast, Normalization::Exact] {
            let q0 = CompensatedAttitude::new(UnitQuat::<T>::IDENTITY);
            let mut comp = IncrementIntegrator::new(q0, ConingRule::Exp, norm);
            let mut plain =
                IncrementIntegrator::new(UnitQuat::<T>::IDENTITY, ConingRule::Exp, norm);
            for d in [v::<T>(m, 0.0, 0.0), v(0.3 * m, -0.7 * m, 0.2 * m)] {
                match (comp.push(d), plain.push(d)) {
                    (Ok(_), Ok(_)) => {
                        let q = comp.attitude();
                        let n = norm_of(q);
                        assert!((n - 1.0).abs() < tol, "{m:e} {norm:?}: |q| = {n}");
                        assert!(q.into_quat().is_finite());
                        let e = angle(unit_f64(q), unit_f64(plain.attitude()));
                        assert!(e < 1e3 * tol, "{m:e} {norm:?}: {e} rad from plain");
                    }
                    (Err(a), Err(b)) => assert_eq!(a, b),
                    (a, b) => panic!("{m:e} {norm:?}: compensated {a:?}, plain {b:?}"),
                }
            }
        }
    }
}

fn norm_of<T: Real>(q: UnitQuat<T>) -> f64 {
    norm(q.into_quat())
}

#[test]
fn r05_compensated_exp_large_increments_f64() {
    compensated_exp_large::<f64>(&[1e16, 1e100, 1e153, 3e153], 1e-14);
}

#[test]
fn r05_compensated_exp_large_increments_f32() {
    compensated_exp_large::<f32>(&[1e8, 1e15, 1e18, 1e19], 1e-6);
}

/// 6. `mul_exp_unchecked((1e200, 0, 0), Exact)` is finite and unit, like `UnitQuat::mul_exp_unchecked`.
#[test]
fn r06_compensated_rotated_huge_angle() {
    for m in [1e200f64, 1e300, 1e154] {
        let phi = Vec3::new(m, 0.0, 0.0);
        let q = CompensatedAttitude::new(UnitQuat::<f64>::IDENTITY)
            .mul_exp_unchecked(phi, Normalization::Exact);
        let plain = (UnitQuat::<f64>::IDENTITY).mul_exp_unchecked(phi, Normalization::Exact);
        assert!(q.attitude().into_quat().is_finite(), "{m:e}: {q:?}");
        assert!((norm_of(q.attitude()) - 1.0).abs() < 1e-14, "{m:e}: {q:?}");
        let e = angle(carried(q), unit_f64(plain));
        assert!(e < 1e-12, "{m:e}: {e}");
    }
    let phi = Vec3::new(1e30f32, 0.0, 0.0);
    let q = CompensatedAttitude::new(UnitQuat::<f32>::IDENTITY)
        .mul_exp_unchecked(phi, Normalization::Exact);
    assert!((norm_of(q.attitude()) - 1.0).abs() < 1e-6, "{q:?}");
}

/// 7. A step remainder that is not a rounding remainder of `dt` is a typed error (dt = 0.01,
///    dt_lo = 1e300 made every push `Ok(NaN)`); a true remainder is taken.
#[test]
fn r07_step_remainder_validated() {
    let q0 = CompensatedAttitude::new(UnitQuat::<f64>::IDENTITY);
    let integ =
        || RateIntegrator::try_new(q0, RateMethod::Magnus4, Normalization::Fast, 0.01).unwrap();
    assert_eq!(
        integ().try_with_step_remainder(1e300).err(),
        Some(Error::InvalidArgument)
    );
    assert_eq!(
        integ().try_with_step_remainder(1e-3).err(),
        Some(Error::InvalidArgument)
    );
    assert_eq!(
        integ().try_with_step_remainder(f64::NAN).err(),
        Some(Error::NonFinite)
    );
    let q0 = CompensatedAttitude::new(UnitQuat::<f32>::IDENTITY);
    let integ =
        RateIntegrator::try_new(q0, RateMethod::Magnus4, Normalization::Fast, 0.001f32).unwrap();
    let lo = (0.001 - f64::from(0.001f32)) as f32;
    let mut integ = integ.try_with_step_remainder(lo).unwrap();
    for k in 0..8 {
        for q in integ.push(Vec3::new(1.0, 0.1 * k as f32, 0.0)).unwrap() {
            assert!((norm_of(q) - 1.0).abs() < 1e-6);
        }
    }
    assert!(
        RateIntegrator::try_new(q0, RateMethod::Magnus4, Normalization::Fast, 0.001f32)
            .unwrap()
            .try_with_step_remainder(1e-9)
            .is_err()
    );
}

/// 8. Intermediates of the compensated rate path that overflow although inputs and result are
///    in range: the result is the plain integrator's, or a typed error, never `Ok(NaN)`.
fn rate_extremes<T: Real>(dt: f64, sample: f64, methods: &[RateMethod], tol: f64) {
    for &method in methods {
        let q0 = CompensatedAttitude::new(UnitQuat::<T>::IDENTITY);
        let dt = T::from_f64(dt);
        let mut comp = RateIntegrator::try_new(q0, method, Normalization::Exact, dt).unwrap();
        let mut plain =
            RateIntegrator::try_new(UnitQuat::<T>::IDENTITY, method, Normalization::Exact, dt)
                .unwrap();
        for k in 0..6 {
            let f = 1.0 - 0.1 * f64::from(k);
            let s = v::<T>(sample * f, sample * 0.5 * f64::from(k % 2), -0.25 * sample);
            match (comp.push(s), plain.push(s)) {
                (Ok(c), Ok(p)) => {
                    for (c, p) in c.into_iter().zip(p) {
                        assert!(c.into_quat().is_finite(), "{method:?}: {c:?}");
                        let e = angle(unit_f64(c), unit_f64(p));
                        assert!(e < tol, "{method:?} sample {k}: {e} rad from plain");
                    }
                }
                (Err(a), Err(b)) => assert_eq!(a, b),
                (c, p) => panic!("{method:?}: compensated {c:?}, plain {p:?}"),
            }
        }
    }
}

const METHODS: [RateMethod; 3] = [RateMethod::Magnus4, RateMethod::Cf4, RateMethod::Rk4];

#[test]
fn r08_compensated_rate_intermediate_overflow_f32() {
    rate_extremes::<f32>(1e-30, 3e19, &METHODS, 1e-5);
    rate_extremes::<f32>(1e38, 1.5e-38, &METHODS, 1e-5);
    rate_extremes::<f32>(1e-36, 5e35, &METHODS, 1e-5);
}

#[test]
fn r08_compensated_rate_intermediate_overflow_f64() {
    rate_extremes::<f64>(1e-301, 1e300, &METHODS, 1e-12);
    rate_extremes::<f64>(1e-300, 1e299, &METHODS, 1e-12);
    rate_extremes::<f64>(1e300, 1e-300, &METHODS, 1e-12);
}

/// The residual of the equilibrium `mω_v²(r − r₀) = J²/(mr³)` at `r`, relative to the larger
/// side, in f64 from the rotor's parameters.
fn equilibrium_residual(m: f64, w: f64, r0: f64, j: f64, r: f64) -> f64 {
    let lhs = m * w * w * (r - r0);
    let rhs = j * j / (m * r * r * r);
    (lhs - rhs).abs() / lhs.abs().max(rhs.abs())
}

/// 9. `equilibrium_radius` returns a root (`r ≥ r₀`, the equation satisfied) or a typed error,
///    never a non-root as `Ok` (f32: `Ok(0.0)`; f64: `Ok(1.82e8)` for a root near 6.8e9).
#[test]
fn r09_equilibrium_radius_is_a_root_f64() {
    let (m, w, r0) = (36.96577205523286, 0.5805200227269618, 1.8387119191336736);
    let rotor = SpringRotor::try_new(m, w, r0).unwrap();
    for j in [1e20, 1e10, 1e30, -1e25, 3.0, 1e100] {
        match rotor.equilibrium_radius(j) {
            Ok(r) => {
                assert!(r >= r0, "J = {j:e}: r = {r}");
                let res = equilibrium_residual(m, w, r0, j, r);
                assert!(res < 1e-12, "J = {j:e}: r = {r}, residual {res}");
            }
            Err(e) => assert!(
                matches!(
                    e,
                    Error::NotConverged | Error::NonFinite | Error::InvalidArgument
                ),
                "{e:?}"
            ),
        }
    }
    // The f64 reproducer has a representable root: it is found, and it is the root found by
    // bisection on the equation in log r (independent of Newton).
    let r = rotor.equilibrium_radius(1e20).unwrap();
    let f = |r: f64| m * w * w * (r - r0) - 1e40 / (m * r * r * r);
    let (mut lo, mut hi) = (r0.ln(), 300f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid.exp()) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    assert!((r / lo.exp() - 1.0).abs() < 1e-12, "{r} vs {}", lo.exp());
}

#[test]
fn r09_equilibrium_radius_is_a_root_f32() {
    let (m, w, r0) = (0.008_455_155f32, 1e-20f32, 94.808_06f32);
    // A rotor whose stiffness m·ω_v² is subnormal in f32 is not constructed; any constructed
    // rotor's `Ok` is a root.
    match SpringRotor::try_new(m, w, r0) {
        Err(e) => assert_eq!(e, Error::InvalidArgument),
        Ok(rotor) => match rotor.equilibrium_radius(-593.063f32) {
            Ok(r) => {
                assert!(r >= r0, "r = {r}");
                let res = equilibrium_residual(m.into(), w.into(), r0.into(), -593.063, r.into());
                assert!(res < 1e-4, "r = {r}, residual {res}");
            }
            Err(e) => assert!(matches!(e, Error::NotConverged | Error::NonFinite)),
        },
    }
    let rotor = SpringRotor::try_new(1.0f32, 3.0, 0.5).unwrap();
    for j in [0.1f32, 1.0, 10.0, 1e3, 1e6, 1e12] {
        if let Ok(r) = rotor.equilibrium_radius(j) {
            assert!(r >= 0.5);
            let res = equilibrium_residual(1.0, 3.0, 0.5, j.into(), r.into());
            assert!(res < 1e-5, "J = {j:e}: r = {r}, residual {res}");
        }
    }
    assert!(rotor.equilibrium_radius(1e3).is_ok());
}

/// 10. `try_new` rejects parameters whose derived constants underflow (1/(m·r₀²) = 0 in f32).
#[test]
fn r10_spring_rotor_derived_constants_representable() {
    assert_eq!(
        SpringRotor::try_new(0.116_587_505f32, 0.025_478_598, 3.402_823_5e38),
        Err(Error::InvalidArgument)
    );
    assert_eq!(
        SpringRotor::try_new(0.1f64, 0.02, 1e308),
        Err(Error::InvalidArgument)
    );
    // Every constructed rotor has normal, finite derived constants.
    for (m, w, r0) in [(1.0f32, 1.0, 1.0), (1e-10, 1e-5, 1e3), (5.0, 1e6, 1e-6)] {
        if let Ok(r) = SpringRotor::try_new(m, w, r0) {
            let mu = r.rest_inverse_inertia();
            assert!(mu.is_normal(), "{mu}");
            assert!(r.mode().stiffness().is_normal());
        }
    }
}

/// 11. `stretched_radius ≥ r₀` for every constructed rotor (f32: ω_v² subnormal gave
///     1.6681427 < r₀ = 1.6681467).
#[test]
fn r11_stretched_radius_at_least_rest() {
    for (m, w, r0) in [
        (2.460_706_7f32, 1e-20f32, 1.668_146_7f32),
        (1.0, 1e-19, 3.0),
        (1.0, 1e-30, 0.7),
        (1.0, 2.0, 1.1),
    ] {
        if let Ok(rotor) = SpringRotor::try_new(m, w, r0) {
            for wj in [0.0f32, 0.1 * w, 0.5 * w, 0.999 * w] {
                let r = rotor.stretched_radius(wj).unwrap();
                assert!(r >= r0, "ω_v = {w:e}, ω_J = {wj:e}: {r} < {r0}");
                let x = f64::from(wj) / f64::from(w);
                let want = f64::from(r0) / (1.0 - x * x);
                // Rounding of x, x², 1 − x² and the quotient: ≤ 4u/(1 − x²) relative.
                let bound = 4.0 * f64::from(f32::EPSILON) / (1.0 - x * x);
                assert!((f64::from(r) / want - 1.0).abs() < bound, "{r} vs {want}");
            }
        }
    }
    let rotor = SpringRotor::try_new(1.0f64, 1e-150, 2.0).unwrap();
    assert_eq!(
        SpringRotor::try_new(1.0f64, 1e-160, 2.0),
        Err(Error::InvalidArgument)
    );
    assert!(rotor.stretched_radius(0.0).unwrap() >= 2.0);
}

/// 12. `try_body_hamiltonian` cannot fail for a constructed rotor (the docs say so).
#[test]
fn r12_body_hamiltonian_total_for_constructed_rotor() {
    for arrangement in [
        Arrangement::Octahedral,
        Arrangement::Cubic,
        Arrangement::Tetrahedral,
    ] {
        for (m, w, r) in [
            (0.1f32, 5.248_066_5e-19, 1.0),
            (1.0, 1e-19, 1.0),
            (1e-3, 1.0, 1e-6),
        ] {
            if let Ok(rotor) = SemiRigidRotor::try_symmetric(arrangement, m, w, r) {
                for basis in [QuarticBasis::Octahedral, QuarticBasis::Cubic] {
                    assert!(
                        rotor.try_body_hamiltonian(basis).is_ok(),
                        "{arrangement:?} ({m}, {w:e}, {r}) {basis:?}"
                    );
                }
            }
        }
        for (m, w, r) in [(1e-100f64, 1e-100, 1e-50), (1e-10, 1e-100, 1e-30)] {
            if let Ok(rotor) = SemiRigidRotor::try_symmetric(arrangement, m, w, r) {
                for basis in [QuarticBasis::Octahedral, QuarticBasis::Cubic] {
                    assert!(rotor.try_body_hamiltonian(basis).is_ok());
                }
            }
        }
    }
}

/// 13. `rk4_step` with `h = 0` returns `q` (huge rates gave a NaN component).
#[test]
fn r13_rk4_step_zero_h() {
    let q = Quat::new(0.5f64, 0.5, -0.5, 0.5);
    let w = Vec3::new(1e308, 0.0, 0.0);
    assert_eq!(rk4_step(q, w, w, w, 0.0), q);
    let w = Vec3::new(3e38f32, -1e38, 0.0);
    let q = Quat::new(0.5f32, 0.5, -0.5, 0.5);
    assert_eq!(rk4_step(q, w, w, w, 0.0), q);
    // With a step of 1e-300 the result is q to rounding (|ω|h = 0.1).
    let w = Vec3::new(1e299, 0.0, 0.0);
    let r = rk4_step(Quat::new(1.0f64, 0.0, 0.0, 0.0), w, w, w, 1e-300);
    let want = exp_ref([0.1, 0.0, 0.0]);
    let got = r.to_array();
    for i in 0..4 {
        assert!((got[i] - want[i]).abs() < 1e-6, "{got:?}");
    }
}

/// 14. The fixed-point exponential is total on every representable φ in every format: Q24
///     `exp((50, 0, 0))` had |q| = 0.247, (100, 0, 0) gave zero.
fn fixed_exp_total<const F: u32>(angles: &[f64], tol: f64) {
    for &a in angles {
        for dir in [[1.0, 0.0, 0.0], [0.6, -0.8, 0.0], [0.48, 0.6, -0.64]] {
            let p = dir.map(|d: f64| d * a);
            let phi = Vec3::new(
                Fixed::<F>::try_from_f64(p[0]).unwrap(),
                Fixed::<F>::try_from_f64(p[1]).unwrap(),
                Fixed::<F>::try_from_f64(p[2]).unwrap(),
            );
            let exact = [phi.x.to_f64(), phi.y.to_f64(), phi.z.to_f64()];
            let q = UnitQuat::<Fixed<F>>::exp_unchecked(phi);
            let got = q.into_quat().to_array().map(|c| c.to_f64());
            let n = got.iter().map(|x| x * x).sum::<f64>().sqrt();
            assert!((n - 1.0).abs() < tol, "F = {F}, |φ| = {a}: |q| = {n}");
            let e = angle(got.map(|x| x / n), exp_ref(exact));
            assert!(e < tol, "F = {F}, |φ| = {a}: {e} rad");
        }
    }
}

#[test]
fn r14_fixed_exp_total_in_wide_formats() {
    fixed_exp_total::<24>(&[0.5, 3.0, 10.0, 50.0, 100.0, 127.9], 1e-5);
    fixed_exp_total::<20>(&[50.0, 100.0, 1000.0, 2047.0], 1e-4);
    fixed_exp_total::<16>(&[1000.0, 32767.0], 2e-3);
    fixed_exp_total::<10>(&[1e4, 2e6], 3e-2);
    fixed_exp_total::<30>(&[0.5, 1.0, 1.99], 4e-8);
}

/// 15. A `Fixed<F>` at the extremes of its accepted const parameter (6 ≤ F ≤ 30) is exact:
///     `from_bits(1)` is `2⁻ᶠ`. Formats outside the range (`Fixed<1024>` panicked in `to_f64`,
///     `Fixed<1023>` gave 0) do not compile: the `compile_fail` doc tests on
///     `Fixed::SUPPORTED`.
#[test]
fn r15_fixed_const_parameter_extremes() {
    assert_eq!(Fixed::<30>::from_bits(1).to_f64(), 2f64.powi(-30));
    assert_eq!(Q30::from_bits(1).to_f64(), 2f64.powi(-30));
    assert_eq!(Q24::from_bits(-1).to_f64(), -(2f64.powi(-24)));
    assert_eq!(Fixed::<6>::from_bits(3).to_f64(), 3.0 / 64.0);
    assert_eq!(
        Fixed::<6>::from_bits(i32::MAX).to_f64(),
        f64::from(i32::MAX) / 64.0
    );
    assert_eq!(
        Fixed::<30>::try_from_f64(0.25).map(|x| x.to_f64()),
        Ok(0.25)
    );
    assert_eq!(Fixed::<6>::try_from_f64(1e6).map(|x| x.to_f64()), Ok(1e6));
    assert_eq!(Fixed::<6>::try_from_f64(4e7), Err(Error::OutOfRange));
    // The exponential at both extremes of the format range (its halving count sized for each).
    fixed_exp_total::<6>(&[0.5, 3.0, 1e3, 1e6, 3.3e7], 0.1);
    fixed_exp_total::<30>(&[0.2, 1.0, 1.99], 4e-8);
}

/// 16. The quartic splitting at high spin with |ω|dt ≪ π: sphere 1e10, `Quartic::Cubic(1e-3)`,
///     J = (0, 1e6, 0), dt = 1 (|ω|dt = 1e-4). The split pieces are huge rotations that cancel;
///     the step either agrees with RK4 or is rejected, never loses the attitude.
fn quartic_high_spin<T: Real>(tol: f64) {
    let inertia = Inertia::try_from_principal(v::<T>(1e10, 1e10, 1e10)).unwrap();
    let h =
        BodyHamiltonian::try_new(inertia, Vec3::ZERO, Quartic::Cubic(T::from_f64(1e-3))).unwrap();
    let body = Gyrostat::from(h);
    let s = State::new(UnitQuat::IDENTITY, v::<T>(0.0, 1e6, 0.0));
    let rk4 = body.step(Integrator::Rk4, &s, T::ONE).unwrap();
    for integ in [
        Integrator::Strang,
        Integrator::Yoshida4,
        Integrator::Suzuki4,
    ] {
        match body.step(integ, &s, T::ONE) {
            Ok(n) => {
                let e = angle(unit_f64(n.attitude), unit_f64(rk4.attitude));
                assert!(e < tol, "{integ:?}: {e} rad from RK4");
            }
            Err(e) => assert_eq!(e, Error::StepTooLong, "{integ:?}"),
        }
        match body.step(integ, &CompensatedState::new(s), T::ONE) {
            Ok(n) => {
                let q = n.state().attitude;
                assert!((norm_of(q) - 1.0).abs() < 1e3 * tol, "{integ:?}: {q:?}");
                let e = angle(unit_f64(q), unit_f64(rk4.attitude));
                assert!(e < tol, "{integ:?} compensated: {e} rad from RK4");
            }
            Err(e) => assert_eq!(e, Error::StepTooLong, "{integ:?}"),
        }
    }
}

#[test]
fn r16_quartic_splitting_high_spin_f64() {
    quartic_high_spin::<f64>(1e-9);
}

#[test]
fn r16_quartic_splitting_high_spin_f32() {
    quartic_high_spin::<f32>(1e-5);
}

/// 17. `Drift::between` with differences in range has finite drifts (f32: the norm of the
///     lab-momentum difference overflowed).
#[test]
fn r17_drift_between_finite() {
    // |L| in f64, rounded to f32 (the f32 `norm` of these vectors overflows).
    let inv = |l: Vec3<f32>| Invariants {
        energy: 1.0f32,
        momentum_norm: [l.x, l.y, l.z]
            .iter()
            .map(|c| f64::from(*c).powi(2))
            .sum::<f64>()
            .sqrt() as f32,
        lab_momentum: l,
    };
    let a = inv(Vec3::new(1.315_531_1e38, -3.873_812_5e37, 1.554_169_5e38));
    let b = inv(Vec3::new(-1.159_402_6e38, 3.414_064_5e37, -1.369_719_2e38));
    let d = Drift::between(&a, &b);
    assert!(d.lab_momentum.is_finite(), "{d:?}");
    assert!(d.energy.is_finite() && d.momentum_norm.is_finite(), "{d:?}");
    // The relative drift |L − L₀|/|J₀|, from the f64 values.
    let diff = [
        1.315_531_1e38f64 + 1.159_402_6e38,
        -3.873_812_5e37 - 3.414_064_5e37,
        1.554_169_5e38 + 1.369_719_2e38,
    ];
    let want = diff.iter().map(|x| x * x).sum::<f64>().sqrt() / f64::from(a.momentum_norm);
    assert!(
        (f64::from(d.lab_momentum) / want - 1.0).abs() < 1e-5,
        "{d:?} vs {want}"
    );
    let a = Invariants {
        energy: 1.0f64,
        momentum_norm: 1e308,
        lab_momentum: Vec3::new(1e308, 1e308, 0.0),
    };
    let b = Invariants {
        energy: 1.0f64,
        momentum_norm: 1e308,
        lab_momentum: Vec3::new(-7e307, -7e307, 0.0),
    };
    assert!(Drift::between(&a, &b).lab_momentum.is_finite());
}
