//! Lie–Poisson splitting and RK4 on torque-free models: measured orders against the independent
//! reference, Casimir and energy behaviour over long runs, the spherical gyro-rotor (6.9.6) and
//! the quartic models (6.8.20).

use gyrostat::dynamics::{FreeRigidBody, Gyrostat, Inertia, Integrator, State, lab_momentum};
use gyrostat::{Real, UnitQuat};
use host_tests::cast::{body_hamiltonian, vec3};
use host_tests::ref_dynamics::{RefModel, lie_poisson_rk4, linear_fit, log_log_slope};
use host_tests::reference::{IDENTITY, M3, cross, dot, mat_dist, norm, quat_matrix, rodrigues};

fn model<T: Real>(m: &RefModel) -> Gyrostat<T> {
    Gyrostat::from(body_hamiltonian(m))
}

fn run<T: Real>(h: &Gyrostat<T>, integ: Integrator, j0: [f64; 3], dt: f64, n: usize) -> State<T> {
    let mut s = State::new(UnitQuat::IDENTITY, vec3(j0));
    for _ in 0..n {
        s = h.step(integ, &s, T::from_f64(dt)).unwrap();
    }
    s
}

fn err_vs_ref<T: Real>(s: &State<T>, r: &M3, j: [f64; 3]) -> f64 {
    let q = s.attitude.to_array().map(|c| c.to_f64());
    let m = s.momentum;
    let dj = [
        m.x.to_f64() - j[0],
        m.y.to_f64() - j[1],
        m.z.to_f64() - j[2],
    ];
    mat_dist(&quat_matrix(q), r).max(dj.iter().fold(0.0f64, |a, b| a.max(b.abs())))
}

/// The asymmetric rotor of Fig. 6.8.1, `(I₁, I₂, I₃) = (6, 4, 3)`.
const RIGID: RefModel = RefModel::new([6.0, 4.0, 3.0], [0.0; 3], 0.0, 0.0);
/// An asymmetric gyro-rotor (6.9.2b).
const GYRO: RefModel = RefModel::new([2.0, 3.0, 4.0], [0.3, -0.2, 0.5], 0.0, 0.0);
const OCTA: RefModel = RefModel::new([2.0, 3.0, 4.0], [0.0; 3], 0.05, 0.0);
const CUBIC: RefModel = RefModel::new([2.0, 3.0, 4.0], [0.0; 3], 0.0, 0.08);
const J0: [f64; 3] = [0.9, 0.5, -0.7];

/// Measures the global error at T = 4 for dt = 0.1·2⁻ᵏ and fits the order.
fn measured_order(m: &RefModel, integ: Integrator, dts: &[f64]) -> (f64, Vec<f64>) {
    let t_end = 4.0;
    let (r_ref, j_ref) = lie_poisson_rk4(m, &IDENTITY, J0, t_end, 40_000);
    let h = model::<f64>(m);
    let errs: Vec<f64> = dts
        .iter()
        .map(|&dt| {
            let n = (t_end / dt).round() as usize;
            err_vs_ref(&run(&h, integ, J0, dt, n), &r_ref, j_ref)
        })
        .collect();
    (log_log_slope(dts, &errs), errs)
}

/// Orders 2 (Strang) and 4 (Yoshida, Suzuki, RK4), measured as least-squares log–log slopes of
/// the global error against the reference over a halving sequence of steps, for the rigid,
/// gyro-rotor and both quartic models. Accepted band ±0.3 around the nominal order (the fit over
/// four halvings of a smooth problem is within ±0.1 in practice; ±0.3 still separates 2 from 4).
#[test]
fn measured_orders() {
    let coarse = [0.2, 0.1, 0.05, 0.025];
    for (name, m) in [
        ("rigid", RIGID),
        ("gyro", GYRO),
        ("octahedral", OCTA),
        ("cubic", CUBIC),
    ] {
        for (integ, p) in [
            (Integrator::Strang, 2.0),
            (Integrator::Yoshida4, 4.0),
            (Integrator::Suzuki4, 4.0),
            (Integrator::Rk4, 4.0),
        ] {
            let (slope, errs) = measured_order(&m, integ, &coarse);
            println!("{name:>10} {integ:?}: order {slope:.3}, errors {errs:?}");
            assert!((slope - p).abs() < 0.3, "{name} {integ:?}: order {slope}");
            assert!(errs[3] > 1e-12, "error must stay above the reference floor");
        }
    }
    // Suzuki's composition has the smaller error constant at equal step (it costs 5/3 more).
    let (_, ey) = measured_order(&RIGID, Integrator::Yoshida4, &[0.05]);
    let (_, es) = measured_order(&RIGID, Integrator::Suzuki4, &[0.05]);
    println!(
        "error at dt = 0.05: Yoshida {:.3e}, Suzuki {:.3e}",
        ey[0], es[0]
    );
    assert!(es[0] < ey[0] / 3.0);
}

host_tests::per_type! {
    /// |J| conserved by the splitting to ≤ 1e-12 relative (f64) over 10⁵ steps (measured ≤ 6e-14);
    /// the lab-frame momentum `q J q*` to 30× that (it also carries the attitude's rounding).
    /// f32: every sub-step rounds |J| by ~ε = 6e-8 relative at random, so 5·10⁵ (Strang) to
    /// 1.3·10⁶ (Yoshida) sub-steps random-walk to ~4e-5…7e-5 (measured ≤ 3.7e-5); bound 2e-4. The
    /// f32 lab momentum adds the attitude's rounding (measured ≤ 2.9e-3, more than a pure random
    /// walk of ~1e-4 would give: part of it is systematic; bound 6e-3).
    #[test]
    fn casimir_conserved_over_1e5_steps() {
        let tol = T::per_type(2e-4, 1e-12);
        for m in [RIGID, GYRO, OCTA, CUBIC] {
            for integ in [Integrator::Strang, Integrator::Yoshida4] {
                let h = model::<T>(&m);
                let s0 = State::new(UnitQuat::IDENTITY, vec3::<T>(J0));
                let n0 = s0.momentum.norm().to_f64();
                let l0 = lab_momentum(s0.attitude, s0.momentum);
                let mut s = s0;
                let mut worst = 0.0f64;
                for k in 0..100_000 {
                    s = h.step(integ, &s, T::from_f64(0.01)).unwrap();
                    if k % 100 == 0 {
                        worst = worst.max((s.momentum.norm().to_f64() - n0).abs() / n0);
                    }
                }
                let dl = (lab_momentum(s.attitude, s.momentum) - l0).norm().to_f64() / n0;
                println!(
                    "{:?} {integ:?} {}: |J| drift {worst:.2e}, lab drift {dl:.2e}",
                    m.moments,
                    T::NAME
                );
                assert!(worst <= tol, "|J| drift {worst}");
                assert!(dl <= 30.0 * tol, "lab momentum drift {dl}");
            }
        }
    }

    /// The spherical gyro-rotor `H = B(J − S)²` (6.9.5): every J precesses about S at the same
    /// rate `2B|S| = |S|/I` whatever its direction (6.9.6), with `J·Ŝ` constant. Each direction's
    /// rate is measured from the angle swept in 20 s and compared with the closed form; the whole
    /// trajectory is compared with the Rodrigues rotation of `J₀` about `Ŝ`.
    #[test]
    fn spherical_gyro_rotor_precesses_at_one_rate() {
        // f64: the Yoshida truncation error at dt = 0.01 is ≤ 3e-9 (measured). f32: 2000 steps ×
        // 13 sub-steps; at the stationary J ∥ S the roundings repeat identically every step, so
        // they add linearly, worst case 26000·ε/2·|J| ≈ 2e-3, measured ≤ 1.1e-4; bound 5e-4.
        let tol = T::per_type(5e-4, 1e-8);
        let (i, s) = (2.0, [0.3, -0.4, 1.2]);
        let sn = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
        let rate = sn / i;
        let m = RefModel::new([i; 3], s, 0.0, 0.0);
        let h = model::<T>(&m);
        let dirs = [
            [0.3, -0.4, 1.2],    // along +S
            [-0.29, 0.41, -1.2], // near −S
            [1.0, 0.0, -0.25],   // perpendicular-ish
            [0.0, 1.0, 0.5],
            [-0.7, -0.7, 0.1],
        ];
        let (dt, n) = (0.01, 2000);
        let t = dt * n as f64;
        for d in dirs {
            let j0 = d.map(|c| 2.0 * c);
            let st = run(&h, Integrator::Yoshida4, j0, dt, n);
            let want = host_tests::reference::mat_vec(&rodrigues(s, rate * t), &j0);
            let got = [
                st.momentum.x.to_f64(),
                st.momentum.y.to_f64(),
                st.momentum.z.to_f64(),
            ];
            let e = (0..3).map(|k| (got[k] - want[k]).abs()).fold(0.0, f64::max);
            println!("{} {d:?}: {e:.2e}", T::NAME);
            assert!(e < tol, "direction {d:?}: {e}");
            // Measured rate from the swept angle of the component perpendicular to S.
            let sh = s.map(|c| c / sn);
            let perp = |j: [f64; 3]| {
                let k: f64 = (0..3).map(|i| j[i] * sh[i]).sum();
                [j[0] - k * sh[0], j[1] - k * sh[1], j[2] - k * sh[2]]
            };
            let (p0, p1) = (perp(j0), perp(got));
            if norm(p0) > 0.1 {
                let c = cross(p0, p1);
                let ang = dot(c, sh)
                    .atan2(dot(p0, p1));
                // Unwrap: rate·t = 0.64·20 = 12.8 rad → two full turns plus remainder.
                let turns = ((rate * t - ang) / (2.0 * std::f64::consts::PI)).round();
                let measured = (ang + turns * 2.0 * std::f64::consts::PI) / t;
                assert!((measured - rate).abs() < tol, "rate {measured} vs {rate}");
            }
        }
    }

    /// f32 and f64 on the same run against the reference: f64 to its truncation error (measured
    /// ≤ 4.3e-11, bound 1e-9), f32 to its rounding budget (400 steps × ~13 sub-steps × a few
    /// roundings of ε = 6e-8 on values of order one: random walk ~1e-5, measured ≤ 1.2e-5; bound
    /// 5e-5).
    #[test]
    fn yoshida4_against_reference() {
        let tol = T::per_type(5e-5, 1e-9);
        let (dt, n) = (0.01, 400);
        for m in [RIGID, GYRO, OCTA, CUBIC] {
            let (r_ref, j_ref) = lie_poisson_rk4(&m, &IDENTITY, J0, dt * n as f64, 20_000);
            let e = err_vs_ref(
                &run(&model::<T>(&m), Integrator::Yoshida4, J0, dt, n),
                &r_ref,
                j_ref,
            );
            println!("{:?}: {} {e:.2e}", m.moments, T::NAME);
            assert!(e < tol);
        }
    }

    /// The intermediate-axis flip: the mean interval between sign changes of J₂ measured on a
    /// Suzuki run (200 s, 9 flips) equals the closed form 2K(m)/λ of `FreeRigidBody` (f64: the
    /// measured interval is limited by the linear interpolation of the crossings, ~1e-8 relative;
    /// bound 1e-7. f32: the splitting's rounding walk in E (~4e-5) shifts the flip timing near the
    /// separatrix logarithmically; measured 2e-4, bound 1e-3). Attitude against the closed form's.
    #[test]
    fn flip_interval_matches_closed_form() {
        // Attitude: √(1 − |q·q_e|) ≈ half the angle/√2; f64 Suzuki at dt = 0.01 is ~1e-10 accurate
        // (bound 1e-7), f32 carries the flip-timing shift above (measured 4e-3, bound 2e-2).
        let (tol, tol_att) = (T::per_type(1e-3, 1e-7), T::per_type(2e-2, 1e-7));
        let j0 = [0.3, 4.0, 0.03];
        let inertia = Inertia::try_from_principal(vec3::<f64>(RIGID.moments)).unwrap();
        let exact =
            FreeRigidBody::try_new(&inertia, &State::new(UnitQuat::IDENTITY, vec3(j0))).unwrap();
        let closed = exact.flip_interval().unwrap();
        let h = model::<T>(&RIGID);
        let mut s = State::new(UnitQuat::IDENTITY, vec3::<T>(j0));
        let dt = 0.01;
        let mut prev = s.momentum.y.to_f64();
        let mut crossings = Vec::new();
        let mut worst_att = 0.0f64;
        for k in 1..=20_000 {
            s = h.step(Integrator::Suzuki4, &s, T::from_f64(dt)).unwrap();
            let y = s.momentum.y.to_f64();
            if (y > 0.0) != (prev > 0.0) {
                crossings.push((k as f64 - 1.0 + prev / (prev - y)) * dt);
            }
            prev = y;
            if k % 500 == 0 {
                let qe = exact.state_at_unchecked(k as f64 * dt).attitude;
                let d: f64 = (0..4)
                    .map(|i| s.attitude.to_array()[i].to_f64() * qe.to_array()[i])
                    .sum();
                worst_att = worst_att.max((1.0 - d.abs().min(1.0)).sqrt());
            }
        }
        let n = crossings.len();
        assert!(n >= 8, "{n} flips");
        let measured = (crossings[n - 1] - crossings[0]) / (n - 1) as f64;
        println!(
            "{}: flips {n}, interval {measured} vs closed form {closed}, attitude {worst_att:.1e}",
            T::NAME
        );
        assert!((measured - closed).abs() < tol * closed);
        assert!(worst_att < tol_att);
    }
}

/// Max |ΔE/E| in each of `w` consecutive windows of a run of `n` steps.
fn energy_windows(m: &RefModel, integ: Integrator, dt: f64, n: usize, w: usize) -> Vec<f64> {
    let h = model::<f64>(m);
    let mut s = State::new(UnitQuat::IDENTITY, vec3::<f64>(J0));
    let e0 = h.energy(&s);
    let mut out = vec![0.0f64; w];
    for k in 0..n {
        s = h.step(integ, &s, dt).unwrap();
        let e = ((h.energy(&s) - e0) / e0).abs();
        let slot = &mut out[k * w / n];
        *slot = slot.max(e);
    }
    out
}

/// The energy windows of [`energy_windows`] with the least-squares growth of their maxima over
/// the run: `(windows, fitted growth over the run, largest window)`.
fn energy_growth(
    m: &RefModel,
    integ: Integrator,
    dt: f64,
    n: usize,
    w: usize,
) -> (Vec<f64>, f64, f64) {
    let t: Vec<f64> = (0..w)
        .map(|i| (i as f64 + 0.5) / w as f64 * n as f64 * dt)
        .collect();
    let ew = energy_windows(m, integ, dt, n, w);
    let (slope, _) = linear_fit(&t, &ew);
    let level = ew.iter().cloned().fold(0.0, f64::max);
    (ew, slope * n as f64 * dt, level)
}

/// Over 10⁶ steps the splitting's energy error is bounded (no secular growth) while RK4's grows
/// linearly. Measured as a least-squares fit of the per-window maximum |ΔE/E| against time:
/// for RK4 the fitted growth over the run exceeds 5× the first window's error; for Strang and
/// Yoshida it is below 10 % of the (bounded, oscillating) error level.
#[test]
fn energy_bounded_for_splitting_growing_for_rk4() {
    let (dt, n, w) = (0.1, 1_000_000, 20);
    for integ in [Integrator::Strang, Integrator::Yoshida4, Integrator::Rk4] {
        let (ew, growth, level) = energy_growth(&RIGID, integ, dt, n, w);
        println!(
            "{integ:?}: first window {:.3e}, last {:.3e}, fitted growth over run {growth:.3e}",
            ew[0],
            ew[w - 1]
        );
        if integ == Integrator::Rk4 {
            assert!(growth > 5.0 * ew[0], "RK4 energy should drift");
        } else {
            assert!(
                growth.abs() < 0.1 * level,
                "{integ:?} energy should not drift"
            );
        }
    }
}

/// The same boundedness for the gyro-rotor and both quartic models (2·10⁵ Strang steps at
/// dt = 0.05: the fitted growth is below 10 % of the bounded error level), the structure the
/// |J|²-reduced quartic splitting is built to keep.
#[test]
fn energy_bounded_for_gyro_and_quartic_models() {
    let (dt, n, w) = (0.05, 200_000, 10);
    for m in [GYRO, OCTA, CUBIC] {
        let (_, growth, level) = energy_growth(&m, Integrator::Strang, dt, n, w);
        println!("{m:?}: level {level:.3e}, fitted growth {growth:.3e}");
        assert!(level > 0.0 && growth.abs() < 0.1 * level);
    }
}

/// The methods' names as the `simulate` tool (`--integrator`) and Python (`integrator=`) spell
/// them.
#[test]
fn integrator_names() {
    for (method, name) in Integrator::ALL
        .into_iter()
        .zip(["rk4", "strang", "yoshida4", "suzuki4"])
    {
        assert_eq!(method.name(), name);
        assert_eq!(method.to_string(), name);
        assert_eq!(name.parse::<Integrator>(), Ok(method));
    }
    for bad in ["", "RK4", "exact", "yoshida"] {
        assert_eq!(
            bad.parse::<Integrator>(),
            Err(gyrostat::Error::InvalidArgument),
            "{bad:?}"
        );
    }
}
