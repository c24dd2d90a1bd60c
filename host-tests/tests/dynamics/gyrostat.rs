//! Torque-driven Euler equations with a full inertia tensor, and the gyrostat with reaction
//! wheels, against the independent body-rate reference `ω̇ = I⁻¹(τ − ḣ − ω × (Iω + h))`.

use gyrostat::dynamics::{
    BodyHamiltonian, Control, Gyrostat, Inertia, Integrator, Quartic, State, Wheel, WheelCommand,
    angular_acceleration, lab_momentum,
};
use gyrostat::{Error, Mat3, Real, UnitQuat, Vec3};
use host_tests::cast::vec3;
use host_tests::ref_dynamics::{euler_rk4, log_log_slope};
use host_tests::reference::{IDENTITY, M3, cross, mat_dist, mat_vec, quat_matrix};

/// A full, non-diagonal but physical tensor (a rotated box plus products of inertia).
const I_FULL: M3 = [[3.0, -0.4, 0.25], [-0.4, 4.0, 0.3], [0.25, 0.3, 5.0]];
const W0: [f64; 3] = [0.4, -0.3, 0.8];

fn inertia<T: Real>() -> Inertia<T> {
    Inertia::try_from_tensor(Mat3::from_rows(
        I_FULL[0].map(T::from_f64),
        I_FULL[1].map(T::from_f64),
        I_FULL[2].map(T::from_f64),
    ))
    .unwrap()
}

/// A time- and attitude-dependent torque: a sinusoid plus a lab-fixed "gravity-gradient-like"
/// term expressed in the body frame (only the attitude enters, so the splitting keeps its order).
fn torque_ref(t: f64, r: &M3) -> [f64; 3] {
    let lab = [0.0, 0.0, 1.0];
    let zb = [
        r[0][2] * lab[0] + r[1][2] * lab[1] + r[2][2] * lab[2],
        0.0,
        0.0,
    ];
    let b = [r[2][0], r[2][1], r[2][2]]; // lab z in body coordinates (row 2 of R)
    [
        0.05 * (1.3 * t).sin() + 0.02 * b[1] * b[2] + 0.0 * zb[0],
        -0.03 * (0.7 * t).cos() - 0.02 * b[0] * b[2],
        0.01,
    ]
}

fn torque_lib<T: Real>(t: T, s: &State<T>) -> Control<T> {
    let r = s.attitude.to_rotation_matrix();
    let m: M3 = [0, 1, 2].map(|i| [0, 1, 2].map(|j| r.m[i][j].to_f64()));
    Control::torque(vec3(torque_ref(t.to_f64(), &m)))
}

fn err<T: Real>(s: &State<T>, body: &Gyrostat<T>, r: &M3, w: [f64; 3]) -> f64 {
    let q = s.attitude.to_array().map(|c| c.to_f64());
    let om = body.omega(s);
    let dw = [
        om.x.to_f64() - w[0],
        om.y.to_f64() - w[1],
        om.z.to_f64() - w[2],
    ];
    mat_dist(&quat_matrix(q), r).max(dw.iter().fold(0.0f64, |a, b| a.max(b.abs())))
}

fn run_torqued<T: Real>(integ: Integrator, dt: f64, t_end: f64) -> (State<T>, Gyrostat<T>) {
    let body = Gyrostat::rigid(inertia::<T>());
    let mut s = body
        .try_state_from_omega(UnitQuat::IDENTITY, vec3(W0), [])
        .unwrap();
    let n = (t_end / dt).round() as usize;
    for k in 0..n {
        let t = T::from_f64(k as f64 * dt);
        s = body
            .step_with(integ, &s, t, T::from_f64(dt), torque_lib::<T>)
            .unwrap();
    }
    (s, body)
}

/// The torque-driven reference of the tests below: RK4 on (R, ω) with the full tensor I_FULL,
/// 50 000 steps over `t_end` = 5 s.
fn torqued_reference() -> (M3, [f64; 3]) {
    euler_rk4(
        &I_FULL,
        &IDENTITY,
        W0,
        5.0,
        50_000,
        &|t, r, _w| torque_ref(t, r),
        &|_t| ([0.0; 3], [0.0; 3]),
    )
}

/// Torque-driven Euler equations with the full tensor I_FULL: every integrator against the
/// reference, with measured orders (Strang 2, Yoshida/Suzuki/RK4 4; band ±0.3).
#[test]
fn torqued_euler_full_inertia_orders() {
    let t_end = 5.0;
    let (r_ref, w_ref) = torqued_reference();
    let dts = [0.1, 0.05, 0.025, 0.0125];
    for (integ, p) in [
        (Integrator::Strang, 2.0),
        (Integrator::Yoshida4, 4.0),
        (Integrator::Suzuki4, 4.0),
        (Integrator::Rk4, 4.0),
    ] {
        let errs: Vec<f64> = dts
            .iter()
            .map(|&dt| {
                let (s, h) = run_torqued::<f64>(integ, dt, t_end);
                err(&s, &h, &r_ref, w_ref)
            })
            .collect();
        let order = log_log_slope(&dts, &errs);
        println!("{integ:?}: order {order:.3}, errors {errs:?}");
        assert!((order - p).abs() < 0.3, "{integ:?} order {order}");
        assert!(errs[3] > 1e-12);
    }
}

host_tests::per_type! {
    /// f32 and f64 at dt = 0.01 against the torque-driven reference (Yoshida4, 500 steps): f64 to
    /// its truncation error (measured 1.0e-9, bound 1e-8), f32 to its rounding budget (500 steps ×
    /// ~13 sub-steps and 4 kicks, each rounding values of order one by ε = 6e-8; measured 1.4e-5,
    /// bound 1e-4).
    #[test]
    fn torqued_yoshida4_at_dt_0_01() {
        let (r_ref, w_ref) = torqued_reference();
        let (s, body) = run_torqued::<T>(Integrator::Yoshida4, 0.01, 5.0);
        let e = err(&s, &body, &r_ref, w_ref);
        println!("{} Yoshida4 dt = 0.01: {e:.2e}", T::NAME);
        assert!(e < T::per_type(1e-4, 1e-8));
    }

    /// `angular_acceleration` solves I ω̇ = −ω × (Iω + h) + τ − ḣ: check it against the reference formula
    /// (cofactor inverse) at a few points, f32 and f64 (relative tolerances: f64 1e-14, f32 2e-6).
    #[test]
    fn angular_acceleration_matches_reference_formula() {
        let tol = T::per_type(2e-6, 1e-14);
        let i = inertia::<T>();
        let inv = host_tests::ref_dynamics::inverse(&I_FULL);
        for (w, h, hd, tau) in [
            (
                [0.4, -0.3, 0.8],
                [0.1, 0.0, 0.2],
                [0.0, 0.01, -0.02],
                [0.03, 0.0, 0.1],
            ),
            (
                [-1.0, 2.0, 0.5],
                [0.0, 0.0, 0.0],
                [0.0, 0.0, 0.0],
                [0.0, 0.0, 0.0],
            ),
        ] {
            let got = angular_acceleration(&i, vec3(w), vec3(h), vec3(hd), vec3(tau));
            let l = [0, 1, 2].map(|k| mat_vec(&I_FULL, &w)[k] + h[k]);
            let c = cross(w, l);
            let rhs = [0, 1, 2].map(|k| tau[k] - hd[k] - c[k]);
            let want = mat_vec(&inv, &rhs);
            let scale = want.iter().fold(1.0f64, |a, b| a.max(b.abs()));
            for (g, w) in got.to_array().iter().zip(want) {
                assert!((g.to_f64() - w).abs() < tol * scale);
            }
        }
    }

    /// Wheel torques only (no external torque): the wheels take momentum from the body, the body
    /// rate changes a lot, and the total lab-frame momentum is conserved — by the splitting to
    /// rounding (f64 ≤ 1e-12 relative over 2000 steps, measured ≤ 3e-14; f32: 2000 steps × 5–13
    /// general-axis rotations of ~20 roundings of ε = 6e-8 each, a random walk of a few 1e-5,
    /// measured ≤ 3e-5, bound 1e-4), by RK4 to its truncation error (f64 measured 8e-13, bound
    /// 1e-9; f32 its rounding, measured 1.5e-6, bound 1e-4). The state is also checked against
    /// the reference driven by the same wheel momentum profile h(t) (constant wheel torque ⇒ Ω
    /// linear in t): f64 to the truncation error of each method (Strang 2.9e-6, bound 1e-4;
    /// Yoshida4 and RK4 ≤ 2.3e-10, bound 1e-8), f32 to its rounding (measured ≤ 7.2e-5, bounds
    /// 2e-4 Strang, 1e-4 Yoshida4 and RK4).
    #[test]
    fn wheel_exchange_conserves_total_momentum() {
        // (integrator, lab-momentum bound, reference bound): see the doc comment.
        for (integ, tol_lab, tol_ref) in [
            (Integrator::Strang, T::per_type(1e-4, 1e-12), T::per_type(2e-4, 1e-4)),
            (Integrator::Yoshida4, T::per_type(1e-4, 1e-12), T::per_type(1e-4, 1e-8)),
            (Integrator::Rk4, T::per_type(1e-4, 1e-9), T::per_type(1e-4, 1e-8)),
        ] {
            let body = BodyHamiltonian::rigid(inertia::<T>());
            let g = Gyrostat::new(body, wheels::<T>());
            let speeds0 = [10.0, -5.0, 0.0, 20.0].map(T::from_f64);
            let mut s = g
                .try_state_from_omega(UnitQuat::IDENTITY, vec3(W0), speeds0)
                .unwrap();
            let l0 = lab_momentum(s.attitude, s.momentum);
            let u = [0.002, -0.001, 0.003, -0.0015];
            let cmd = WheelCommand::Torque(u.map(T::from_f64));
            let (dt, n) = (0.005, 2000);
            let w_start = g.omega(&s);
            let dt_t = T::from_f64(dt);
            for _ in 0..n {
                let held = g.control(&s, dt_t, Vec3::ZERO, &cmd);
                s = g.step_with(integ, &s, T::ZERO, dt_t, held).unwrap();
            }
            let dl = (lab_momentum(s.attitude, s.momentum) - l0).norm().to_f64() / l0.norm().to_f64();
            let dw = (g.omega(&s) - w_start).norm().to_f64();
            // Reference: the same motion with the prescribed rotor momentum.
            let t_end = dt * n as f64;
            let ws = wheels::<f64>();
            let rotor = |t: f64| {
                let mut h = [0.0; 3];
                let mut hd = [0.0; 3];
                for (k, w) in ws.iter().enumerate() {
                    let om = [10.0, -5.0, 0.0, 20.0][k] + u[k] / w.inertia() * t;
                    let ax = w.axis();
                    for (c, a) in [ax.x, ax.y, ax.z].iter().enumerate() {
                        h[c] += w.inertia() * om * a;
                        hd[c] += u[k] * a;
                    }
                }
                (h, hd)
            };
            let (r_ref, w_ref) = euler_rk4(
                &I_FULL,
                &IDENTITY,
                W0,
                t_end,
                20_000,
                &|_, _, _| [0.0; 3],
                &rotor,
            );
            let q = s.attitude.to_array().map(|c| c.to_f64());
            let om = g.omega(&s);
            let e = mat_dist(&quat_matrix(q), &r_ref)
                .max((om.x.to_f64() - w_ref[0]).abs())
                .max((om.y.to_f64() - w_ref[1]).abs())
                .max((om.z.to_f64() - w_ref[2]).abs());
            // Wheel speeds: Ω = Ω₀ + u/I_w·t exactly (up to rounding).
            for (k, w) in s.wheel_speeds.iter().enumerate() {
                let want = [10.0, -5.0, 0.0, 20.0][k] + u[k] / ws[k].inertia() * t_end;
                assert!(
                    (w.to_f64() - want).abs() < 1e3 * tol_ref.max(1e-12),
                    "wheel {k}"
                );
            }
            println!(
                "{integ:?} {}: lab drift {dl:.2e}, body-rate change {dw:.3}, vs reference {e:.2e}",
                T::NAME
            );
            assert!(dw > 0.05, "the wheels must actually exchange momentum");
            assert!(dl < tol_lab, "lab momentum drift {dl}");
            assert!(e < tol_ref, "reference error {e}");
        }
    }
}

fn wheels<T: Real>() -> [Wheel<T>; 4] {
    let a = 1.0 / 3.0f64.sqrt();
    [
        Wheel::try_new(vec3([1.0, 0.0, 0.0]), T::from_f64(0.02)).unwrap(),
        Wheel::try_new(vec3([0.0, 1.0, 0.0]), T::from_f64(0.02)).unwrap(),
        Wheel::try_new(vec3([0.0, 0.0, 1.0]), T::from_f64(0.02)).unwrap(),
        Wheel::try_new(vec3([a, a, a]), T::from_f64(0.03)).unwrap(),
    ]
}

/// A speed command is reached at the end of the step; the body takes the opposite momentum.
#[test]
fn wheel_speed_command_is_reached() {
    let body = BodyHamiltonian::rigid(inertia::<f64>());
    let g = Gyrostat::new(body, wheels::<f64>());
    let s0: State<f64, 4> = g
        .try_state_from_omega(UnitQuat::IDENTITY, Vec3::ZERO, [0.0; 4])
        .unwrap();
    let target = [100.0, -50.0, 25.0, 10.0];
    let held = g.control(&s0, 0.01, Vec3::ZERO, &WheelCommand::Speed(target));
    let s1 = g
        .step_with(Integrator::Yoshida4, &s0, 0.0, 0.01, held)
        .unwrap();
    for (got, want) in s1.wheel_speeds.iter().zip(target) {
        assert!((got - want).abs() < 1e-12);
    }
    // Total J unchanged (internal torque), so the body spins opposite to the wheel momentum.
    let hw = g.rotor_momentum(&s1.wheel_speeds);
    let iw = g.model().inertia().mul_vec(g.omega(&s1));
    assert!((iw + hw).norm() < 1e-12);
    assert!(hw.norm() > 1.0);
}

/// Typed errors: bad steps, bad wheels, quartic with a non-diagonal tensor.
#[test]
fn errors_are_typed() {
    let body = Gyrostat::rigid(inertia::<f64>());
    let s = State::new(UnitQuat::IDENTITY, Vec3::new(1.0, 0.0, 0.0));
    assert_eq!(
        body.step(Integrator::Strang, &s, 0.0),
        Err(Error::InvalidArgument)
    );
    assert_eq!(
        body.step(Integrator::Rk4, &s, -0.1),
        Err(Error::InvalidArgument)
    );
    assert_eq!(
        body.step(Integrator::Rk4, &s, f64::NAN),
        Err(Error::NonFinite)
    );
    for integ in Integrator::ALL {
        let held = Control::torque(Vec3::new(f64::INFINITY, 0.0, 0.0));
        assert_eq!(
            body.step_with(integ, &s, 0.1, 0.1, held),
            Err(Error::NonFinite)
        );
        let law = |_, _: &State<f64>| Control::torque(Vec3::new(f64::NAN, 0.0, 0.0));
        assert_eq!(
            body.step_with(integ, &s, 0.0, 0.1, law),
            Err(Error::NonFinite)
        );
        assert_eq!(
            body.step_with(integ, &s, f64::NAN, 0.1, Control::ZERO),
            Err(Error::NonFinite)
        );
    }
    assert_eq!(Wheel::try_new(Vec3::ZERO, 0.1f64), Err(Error::ZeroNorm));
    assert_eq!(Wheel::try_new(Vec3::X, 0.0f64), Err(Error::InvalidArgument));
    assert_eq!(
        BodyHamiltonian::try_new(inertia::<f64>(), Vec3::ZERO, Quartic::Cubic(0.1)),
        Err(Error::InvalidArgument)
    );
}
