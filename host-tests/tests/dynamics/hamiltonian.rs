//! The body model's maps against the independent reference model (`host_tests::ref_dynamics::
//! RefModel`, its gradient written out per component): the momentum of a given body rate
//! (Newton's method with the Hessian), the Hessian itself, the gyrostat's state from a rate, and
//! the conserved-quantity monitors, for f32 and f64.

use gyrostat::dynamics::{
    BodyHamiltonian, DriftMonitor, Gyrostat, Inertia, Integrator, Quartic, State, Wheel,
};
use gyrostat::{Error, UnitQuat, Vec3};
use host_tests::cast::{body_hamiltonian, m64, q64, v64, vec3};
use host_tests::ref_dynamics::RefModel;
use host_tests::reference::{norm, qrotate};

/// Rigid, gyro-rotor and both quartic models (principal axes), coefficients small enough that
/// the quartic term is a perturbation of the quadratic one at the rates below.
const MODELS: [RefModel; 4] = [
    RefModel::new([6.0, 4.0, 3.0], [0.0; 3], 0.0, 0.0),
    RefModel::new([2.0, 3.0, 4.0], [0.3, -0.2, 0.5], 0.0, 0.0),
    RefModel::new([2.0, 3.0, 4.0], [0.0; 3], 0.01, 0.0),
    RefModel::new([6.0, 4.0, 3.0], [0.1, 0.0, -0.2], 0.0, 0.002),
];

const RATES: [[f64; 3]; 3] = [[0.5, 1.0, 0.3], [-0.2, 0.05, 0.4], [0.0, 0.0, 0.7]];

host_tests::per_type! {
    /// `try_momentum_from_omega` returns the J whose reference gradient is the given rate: the
    /// residual |∇H_ref(J) − ω|/|ω| stays within f64 1e-13 (Newton converges to rounding;
    /// measured 2.0e-16) and f32 2e-6 (the f32 J carries a relative rounding of ~ε = 6e-8
    /// amplified by the condition of the Hessian, ≈ 6; measured 6.8e-8).
    #[test]
    fn momentum_from_omega_inverts_the_reference_gradient() {
        let tol = T::per_type(2e-6, 1e-13);
        let mut worst = 0.0f64;
        for m in &MODELS {
            let h = body_hamiltonian::<T>(m);
            for w in RATES {
                let j = h.try_momentum_from_omega(vec3(w)).unwrap();
                let w_ref = m.gradient(v64(j));
                let e = norm([0, 1, 2].map(|k| w_ref[k] - vec3::<T>(w).to_array()[k].to_f64()))
                    / norm(w);
                worst = worst.max(e);
            }
        }
        println!("{}: try_momentum_from_omega residual {worst:.2e}", T::NAME);
        assert!(worst <= tol, "{worst}");
    }

    /// The Hessian is the Jacobian of the body rate: against central differences of the
    /// reference gradient (step 1e-5: truncation ~1e-10 for these coefficients). Bounds: f64
    /// 1e-8, f32 2e-6 (the rounding of the f32 entries, ~10 ulp of values of order 1/I).
    #[test]
    fn hessian_is_the_jacobian_of_the_reference_gradient() {
        let tol = T::per_type(2e-6, 1e-8);
        let d = 1e-5;
        for m in &MODELS {
            let h = body_hamiltonian::<T>(m);
            for j in [[0.9, 0.5, -0.7], [2.0, -1.0, 0.3]] {
                let got = m64(&h.hessian(vec3(j)));
                let jt = v64(vec3::<T>(j));
                for c in 0..3 {
                    let (mut jp, mut jm) = (jt, jt);
                    jp[c] += d;
                    jm[c] -= d;
                    let (gp, gm) = (m.gradient(jp), m.gradient(jm));
                    for r in 0..3 {
                        let want = (gp[r] - gm[r]) / (2.0 * d);
                        assert!(
                            (got[r][c] - want).abs() <= tol,
                            "{m:?} {j:?} [{r}][{c}]: {} vs {want}",
                            got[r][c]
                        );
                    }
                }
            }
        }
    }

    /// The gyrostat's state from a body rate has that rate, with wheels spinning and with a
    /// quartic term (bound: f64 1e-13, f32 2e-6 relative, as above).
    #[test]
    fn state_from_omega_has_that_rate() {
        let tol = T::per_type(2e-6, 1e-13);
        let wheels = [
            Wheel::try_new(Vec3::X, T::from_f64(0.02)).unwrap(),
            Wheel::try_new(vec3([1.0, 1.0, 1.0]), T::from_f64(0.03)).unwrap(),
        ];
        for m in &MODELS {
            let g = Gyrostat::new(body_hamiltonian::<T>(m), wheels);
            for w in RATES {
                let speeds = [T::from_f64(10.0), T::from_f64(-20.0)];
                let s = g.try_state_from_omega(UnitQuat::IDENTITY, vec3(w), speeds).unwrap();
                assert_eq!(s.wheel_speeds, speeds);
                let e = (g.omega(&s) - vec3(w)).norm().to_f64() / norm(w);
                assert!(e <= tol, "{m:?} {w:?}: {e}");
            }
        }
    }

    /// The drift monitor's worst drifts equal the same quantities computed independently in
    /// f64 from the widened states (reference energy, quaternion-array rotation of J), over a
    /// Strang and an RK4 run of the gyro-rotor. The drifts are relative, so the two agree to
    /// the rounding of evaluating E, |J| and L in the type: bound on the absolute difference
    /// f64 1e-14 (measured 1.5e-16), f32 1e-6 (≈ 16 ε; measured 1.4e-7).
    #[test]
    fn drift_monitor_matches_direct_computation() {
        let tol = T::per_type(1e-6, 1e-14);
        let m = &MODELS[1];
        let body = Gyrostat::from(body_hamiltonian::<T>(m));
        let mut largest = 0.0f64;
        for integ in [Integrator::Strang, Integrator::Rk4] {
            let mut s = State::new(UnitQuat::IDENTITY, vec3([0.9, 0.5, -0.7]));
            let mut monitor = DriftMonitor::new(body.invariants(&s));
            let j0 = v64(s.momentum);
            let (e0, n0, l0) = (m.energy(j0), norm(j0), qrotate(q64(s.attitude), j0));
            let mut want = [0.0f64; 3];
            for _ in 0..2000 {
                s = body.step(integ, &s, T::from_f64(0.05)).unwrap();
                monitor.record(&body.invariants(&s));
                let j = v64(s.momentum);
                let l = qrotate(q64(s.attitude), j);
                want[0] = want[0].max(((m.energy(j) - e0) / e0).abs());
                want[1] = want[1].max((norm(j) - n0).abs() / n0);
                want[2] = want[2].max(norm([l[0] - l0[0], l[1] - l0[1], l[2] - l0[2]]) / n0);
            }
            let worst = monitor.worst();
            let got = [worst.energy, worst.momentum_norm, worst.lab_momentum].map(|x| x.to_f64());
            println!("{} {integ:?}: monitor {got:?}, direct {want:?}", T::NAME);
            for k in 0..3 {
                assert!((got[k] - want[k]).abs() <= tol, "{k}: {got:?} {want:?}");
            }
            largest = want.iter().fold(largest, |a, b| a.max(*b));
        }
        // The runs drift measurably: the comparison is not one of two zeros.
        assert!(largest > 10.0 * tol, "{largest}");
    }

    /// A rate the quadratic guess hardly reaches by Newton's method (the cubic term dominating)
    /// gives a typed error or a verified root, never a NaN momentum; non-finite rates are
    /// rejected. (Whether the iteration lands on the root `J ≈ (0.308, 3.813, 0.167)` depends on
    /// the rounding of its path: f64 does not, f32 does since the Hessian's inverse is formed on
    /// the scaled matrix.)
    #[test]
    fn momentum_from_omega_errors_are_typed() {
        let i = Inertia::try_from_principal(vec3::<T>([6.0, 4.0, 3.0])).unwrap();
        let h = BodyHamiltonian::try_new(i, Vec3::ZERO, Quartic::Cubic(T::from_f64(0.05))).unwrap();
        let omega = vec3([0.5, 1.0, 0.3]);
        match h.try_momentum_from_omega(omega) {
            Err(Error::NotConverged) => {}
            Ok(j) => {
                let r = (h.omega(j) - omega).norm().to_f64();
                assert!(r <= 1e-6 * 2.0, "{j:?}: residual {r}");
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(
            h.try_momentum_from_omega(vec3([f64::NAN, 1.0, 0.3])),
            Err(Error::NonFinite)
        );
        let rigid = BodyHamiltonian::rigid(i);
        assert_eq!(
            rigid.try_momentum_from_omega(vec3([0.5, 1.0, f64::INFINITY])),
            Err(Error::NonFinite)
        );
    }
}
