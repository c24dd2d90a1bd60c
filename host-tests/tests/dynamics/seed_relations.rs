//! Relations of seed §6.4–6.9 that the library computes through its existing API, each checked
//! against an independent computation (direct sums over point masses, central differences,
//! explicit 2×2 complex matrices, the seed's printed matrices and closed forms):
//!
//! - the torque law `dL/dt = N` (6.4.10a) for every integrator;
//! - rigid-body kinematics and momenta of point masses (6.4.4), (6.4.8)–(6.4.9), (6.5.1)–(6.5.14a);
//! - Euler `ZYZ` as a matrix and a spinor (6.6.1b), (6.6.3); Euler angles from axis angles
//!   (6.6.5b); the polar axis-angle decomposition (6.6.11a–d);
//! - the seed's constrained rotor (6.7.19)–(6.7.30); the energy ellipsoids (6.7.27b–c);
//! - the Levi-Civita matrix and lab momentum (6.8.1)–(6.8.2); the six-mass rotor (6.8.8a–b);
//! - Hamilton's `ω = ∂H/∂J` for every body Hamiltonian (6.5.14a), (6.8.5d), (6.9.2b);
//! - gyro-rotor and symmetric-top energies linear and quadratic in `K = J_z` (6.9.5)–(6.9.6).
#![allow(clippy::needless_range_loop)] // 3×3 index loops read like the formulas

use gyrostat::dynamics::closed_form::analysis::{
    momentum_ellipsoid_radii, velocity_ellipsoid_radii,
};
use gyrostat::dynamics::mass::{inertia_from_point_masses, total_mass_and_center};
use gyrostat::dynamics::{
    BodyHamiltonian, Control, Gyrostat, Inertia, Integrator, Quartic, State, lab_momentum,
};
use gyrostat::rotation::{Euler, EulerSequence, PolarAxisAngle};
use gyrostat::{Mat3, Real, Su2, UnitQuat, Vec3};
use host_tests::cast::{m64, mat3, u2_64, unit_quat, v64, vec3};
use host_tests::ref_dynamics::{RefModel, inverse};
use host_tests::reference::{
    C, M3, V3, cross, dot, levi_civita, mat_mul, mat_vec, su2_matrix, transpose, u2_dist, u2_mul,
    vec_dist,
};

/// A full, non-diagonal physical tensor (the torque-law, gradient and ellipsoid tests).
const FULL: M3 = [[3.0, -0.4, 0.25], [-0.4, 4.0, 0.3], [0.25, 0.3, 5.0]];

// --- (6.4.10a): the torque law -----------------------------------------------------------------

/// A lab-fixed torque `N(t) = N₀ + N₁ sin Ωt` applied through the body-frame torque law
/// `τ = q*·N·q` for `steps` steps over 10 s: the largest deviation of the lab momentum `q J q*`
/// from `L(t) = L₀ + N₀t + N₁(1 − cos Ωt)/Ω` (6.4.10a), which must hold whatever the body does.
fn torque_law_error<T: Real>(integ: Integrator, n1: f64, steps: usize) -> f64 {
    let body = Gyrostat::rigid(Inertia::try_from_tensor(mat3::<T>(&FULL)).unwrap());
    let (n0, n1v, big_omega) = ([0.05, -0.02, 0.03], [0.0, n1, 0.5 * n1], 1.3);
    let torque = |t: f64| [0, 1, 2].map(|i| n0[i] + n1v[i] * (big_omega * t).sin());
    let mut s = State::new(
        unit_quat::<T>([0.9, 0.1, -0.3, 0.2]),
        vec3([0.4, -1.2, 2.0]),
    );
    let l0 = v64(lab_momentum(s.attitude, s.momentum));
    let t_end = 10.0;
    let dt = T::from_f64(t_end / steps as f64);
    for k in 0..steps {
        let t = T::from_f64(k as f64 * t_end / steps as f64);
        let law = |t: T, st: &State<T>| {
            Control::torque(st.attitude.inverse_rotate(vec3(torque(t.to_f64()))))
        };
        s = body.step_with(integ, &s, t, dt, law).unwrap();
    }
    let l = v64(lab_momentum(s.attitude, s.momentum));
    let want = [0, 1, 2]
        .map(|i| l0[i] + n0[i] * t_end + n1v[i] * (1.0 - (big_omega * t_end).cos()) / big_omega);
    vec_dist(&l, &want)
}

/// The torque law (6.4.10a) in f64: RK4 integrates a constant lab torque to its order, and with
/// the sinusoid every method converges at its order. (The splittings with a constant torque, in
/// f32 and f64: `torque_law_6_4_10a_constant_lab_torque`.)
#[test]
fn torque_law_6_4_10a() {
    let e_rk4 = torque_law_error::<f64>(Integrator::Rk4, 0.0, 1000);
    println!("Rk4: constant lab torque, |ΔL| after 1000 steps: f64 {e_rk4:.1e}");
    assert!(e_rk4 < 1e-8);
    // Time-varying torque: errors shrink with the step at each method's order.
    for (integ, order) in [
        (Integrator::Rk4, 4.0),
        (Integrator::Strang, 2.0),
        (Integrator::Yoshida4, 4.0),
    ] {
        let (e1, e2) = (
            torque_law_error::<f64>(integ, 0.04, 200),
            torque_law_error::<f64>(integ, 0.04, 400),
        );
        let measured = (e1 / e2).log2();
        println!("{integ:?}: sinusoidal lab torque, |ΔL| {e1:.1e} → {e2:.1e}, order {measured:.2}");
        assert!(
            e2 < 1e-5 && measured > order - 0.3,
            "{integ:?}: {e1:e} {e2:e} order {measured}"
        );
    }
}

// --- point masses: (6.4.4), (6.4.8)–(6.4.9), (6.5.1)–(6.5.14a) ----------------------------------

fn cloud() -> Vec<(f64, V3)> {
    (0..9)
        .map(|k| {
            let t = k as f64;
            (
                0.4 + (0.61 * t).sin().abs(),
                [
                    (1.3 * t).cos() + 0.2,
                    (0.9 * t).sin() - 0.1,
                    (0.4 * t).cos() * 1.1,
                ],
            )
        })
        .collect()
}

// --- §6.6: Euler ZYZ, axis angles, the polar decomposition -------------------------------------

const DEG: f64 = core::f64::consts::PI / 180.0;

fn cexp(phase: f64) -> C {
    C::new(phase.cos(), phase.sin())
}

/// Seed (6.6.5b): Euler angles from axis angles, `α = φ − π/2 + T`, `β = 2 sin⁻¹(sin(Θ/2) sin ϑ)`,
/// `γ = π/2 − φ + T`, `T = tan⁻¹(tan(Θ/2) cos ϑ)` (the seed writes `tan(Ω/2)`: Θ = Ωt). For
/// `Θ < π` these give the same spinor as `R[φ, ϑ, Θ]`; and the seed's (6.6.6a) numbers.
#[test]
fn seed_6_6_5b_euler_from_axis_angles() {
    for (phi, th, big) in [
        (80.0 * DEG, 34.0 * DEG, 129.0 * DEG),
        (0.3, 1.2, 2.5),
        (-1.0, 2.6, 0.4),
    ] {
        let t = ((big / 2.0f64).tan() * f64::cos(th)).atan();
        let alpha = phi - core::f64::consts::FRAC_PI_2 + t;
        let beta = 2.0 * ((big / 2.0f64).sin() * f64::sin(th)).asin();
        let gamma = core::f64::consts::FRAC_PI_2 - phi + t;
        let qe = Euler::new(EulerSequence::ZYZ, [alpha, beta, gamma]).to_unit_quat_unchecked();
        let qp = PolarAxisAngle::new(phi, th, big)
            .try_to_unit_quat()
            .unwrap();
        let d = (qe.into_quat() - qp.into_quat()).norm();
        assert!(d < 1e-15, "[{phi}, {th}, {big}]: {qe:?} vs {qp:?}");
        if phi == 80.0 * DEG {
            // (6.6.6a): R[80°, 34°, 129°] = R(50°, 60°, 70°) to the seed's rounding.
            for (got, want) in [alpha, beta, gamma].iter().zip([50.0, 60.0, 70.0]) {
                assert!((got / DEG - want).abs() < 1.0, "{}", got / DEG);
            }
        }
    }
}

// --- §6.7: the constrained rotor (6.7.19)–(6.7.30), ellipsoids (6.7.27) -----------------------

/// The seed's constrained rotor (Fig. 6.7.1): one mass `m` on a rod at polar angle `β`, turned
/// about the lab z axis at `α̇`. Its lab inertia, momentum and energy are the printed (6.7.19a),
/// (6.7.20a–b), (6.7.21); the Euler-momentum map gives the same `J` from `J_α = ∂L/∂α̇` alone
/// (6.7.22b); the bearing torque is `ω × J` (6.7.24), (6.7.30a), of size `|λ|` (6.7.23); the
/// body-frame `J` is constant (6.7.28)–(6.7.29); and the rod tensors rotate as (6.7.25), (6.7.26).
#[test]
fn constrained_rotor_6_7_19_to_6_7_30() {
    let (m, r, beta, alpha_dot) = (1.3f64, 0.8f64, 0.6f64, 1.7f64);
    let mr2 = m * r * r;
    let (sb, cb) = beta.sin_cos();
    let inertia_lab = |alpha: f64| {
        let x3 = [alpha.cos() * sb, alpha.sin() * sb, cb].map(|c| c * r);
        inertia_from_point_masses(&[(m, Vec3::from_array(x3))]).unwrap()
    };
    let omega = Vec3::new(0.0, 0.0, alpha_dot); // (6.7.19b)
    for alpha in [0.0, 0.7, 2.9] {
        let (sa, ca) = f64::sin_cos(alpha);
        // (6.7.19a)
        let want = [
            [1.0 - ca * ca * sb * sb, -sa * ca * sb * sb, -ca * sb * cb],
            [-sa * ca * sb * sb, 1.0 - sa * sa * sb * sb, -sa * sb * cb],
            [-ca * sb * cb, -sa * sb * cb, sb * sb],
        ];
        let i = inertia_lab(alpha);
        for k in 0..3 {
            assert!(
                vec_dist(&i.m[k], &want[k].map(|c| c * mr2)) < 1e-15,
                "(6.7.19a)"
            );
        }
        // (6.7.20a)–(6.7.20b)
        let j = i * omega;
        let j20a = [-ca * sb * cb, -sa * sb * cb, sb * sb].map(|c| c * mr2 * alpha_dot);
        assert!(vec_dist(&v64(j), &j20a) < 1e-15, "(6.7.20a)");
        let jj = mr2 * alpha_dot * sb;
        let rz = UnitQuat::try_from_axis_angle(Vec3::Z, alpha).unwrap();
        let j20b = rz.rotate(Vec3::new(-cb, 0.0, sb).scale(jj));
        assert!((j20b - j).norm() < 1e-15, "(6.7.20b)");
        // (6.7.21): T = ½ ω·J = ½ m r² α̇² sin²β.
        let t = 0.5 * omega.dot(j);
        assert!((t - 0.5 * mr2 * alpha_dot * alpha_dot * sb * sb).abs() < 1e-15);
        // (6.7.22b): J from J_α = ∂L/∂α̇ = m r² α̇ sin²β through (6.7.10a), J_β = J_γ = 0.
        let e = Euler::new(EulerSequence::ZYZ, [alpha, beta, 0.0]);
        let j_alpha = mr2 * alpha_dot * sb * sb;
        let j22 = e
            .try_lab_momentum_from_euler_momenta([j_alpha, 0.0, 0.0])
            .unwrap();
        assert!((j22 - j).norm() < 1e-15, "(6.7.22b): {j22:?} vs {j:?}");
        // (6.7.24), (6.7.30a): dJ/dt = ω × J by central differences in time; size |λ| (6.7.23).
        let h = 1e-5;
        let jd = (inertia_lab(alpha + alpha_dot * h) * omega
            - inertia_lab(alpha - alpha_dot * h) * omega)
            .scale(1.0 / (2.0 * h));
        let j24 = [sa, -ca, 0.0].map(|c| c * mr2 * alpha_dot * alpha_dot * sb * cb);
        assert!(vec_dist(&v64(jd), &j24) < 1e-9, "(6.7.24)");
        assert!(vec_dist(&v64(omega.cross(j)), &j24) < 1e-15, "(6.7.30a)");
        let lambda = -mr2 * alpha_dot * alpha_dot * sb * cb;
        assert!(
            (omega.cross(j).norm() - lambda.abs()).abs() < 1e-15,
            "(6.7.23)"
        );
        // (6.7.28)–(6.7.29): J_body = Rᵀ(αβ0) J is the same at every α.
        let jb = e.to_unit_quat_unchecked().inverse_rotate(j);
        // The mass is on z̄: I_body = m r² diag(1, 1, 0), ω_body = α̇(−sin β, 0, cos β).
        let jb_want = Vec3::new(-mr2 * alpha_dot * sb, 0.0, 0.0);
        assert!((jb - jb_want).norm() < 1e-15, "(6.7.29a): {jb:?}");
        // (6.7.25a–b): z̄ = R(αβ0) z and z̄z̄ᵀ = R zzᵀ Rᵀ; (6.7.25d), (6.7.26): a body tensor
        // diag(I, I, ι) seen in the lab.
        let rot = m64(&e.to_unit_quat_unchecked().to_rotation_matrix());
        let zbar = v64(e.to_unit_quat_unchecked().rotate(Vec3::Z));
        assert!(
            vec_dist(&zbar, &[ca * sb, sa * sb, cb]) < 1e-15,
            "(6.7.25a)"
        );
        let zz = [[0.0; 3], [0.0; 3], [0.0, 0.0, 1.0]];
        let zzbar = mat_mul(&mat_mul(&rot, &zz), &transpose(&rot));
        let want = [
            [ca * ca * sb * sb, sa * ca * sb * sb, ca * sb * cb],
            [sa * ca * sb * sb, sa * sa * sb * sb, sa * sb * cb],
            [ca * sb * cb, sa * sb * cb, cb * cb],
        ];
        for k in 0..3 {
            assert!(vec_dist(&zzbar[k], &want[k]) < 1e-15, "(6.7.25b)");
        }
        let (it, iota) = (mr2, 0.05 * mr2);
        let body = Inertia::try_from_principal(Vec3::new(it, it, iota)).unwrap();
        let lab = mat_mul(&mat_mul(&rot, &m64(&body.tensor())), &transpose(&rot));
        let d = iota - it;
        let want = [
            [
                it + d * ca * ca * sb * sb,
                d * sa * ca * sb * sb,
                d * ca * sb * cb,
            ],
            [
                d * sa * ca * sb * sb,
                it + d * sa * sa * sb * sb,
                d * sa * sb * cb,
            ],
            [
                d * ca * sb * cb,
                d * sa * sb * cb,
                it * sb * sb + iota * cb * cb,
            ],
        ];
        for k in 0..3 {
            assert!(vec_dist(&lab[k], &want[k]) < 1e-15, "(6.7.26)");
        }
    }
}

// --- §6.8 ---------------------------------------------------------------------------------------

/// (6.8.1): the Levi-Civita matrix `ε·ω` is the cross-product matrix; (6.8.2): the lab momentum of
/// body momentum `(0, 0, J)` at attitude `R(αβγ)` is `J(cos α sin β, sin α sin β, cos β)`.
#[test]
fn levi_civita_and_lab_momentum_6_8_1_and_6_8_2() {
    let w = [0.3, -1.2, 0.7];
    let s = Mat3::skew(Vec3::from_array(w));
    for jj in 0..3 {
        for l in 0..3 {
            let want: f64 = (0..3).map(|k| levi_civita(jj, k, l) * w[k]).sum();
            assert_eq!(s.m[jj][l], want, "(6.8.1) ({jj}, {l})");
        }
    }
    let (a, b, g, jm) = (0.4f64, 1.1f64, -0.7f64, 2.5f64);
    let q = Euler::new(EulerSequence::ZYZ, [a, b, g]).to_unit_quat_unchecked();
    let l = v64(lab_momentum(q, Vec3::new(0.0, 0.0, jm)));
    let want = [a.cos() * b.sin(), a.sin() * b.sin(), b.cos()].map(|c| c * jm);
    assert!(vec_dist(&l, &want) < 1e-15, "(6.8.2)");
}

/// (6.8.8a–b): the rotor of Fig. 6.8.1 — three pairs of masses `m` at `±r₁x̂, ±r₂ŷ, ±r₃ẑ` —
/// has `Iᵢ = 2m(r_j² + r_k²)`; radii `r² ∝ (½, 5/2, 7/2)` give `I₁ : I₂ : I₃ = 6 : 4 : 3`, and
/// its momentum ellipsoid has semi-axes `aᵢ² = 2EIᵢ` (not the printed `Iᵢ = 2aᵢ²E`).
#[test]
fn six_mass_rotor_6_8_8() {
    let (m, k) = (0.7f64, 0.3f64);
    let r = [0.5f64, 2.5, 3.5].map(|x| (x * k).sqrt());
    let mut pts = Vec::new();
    for (axis, ri) in r.iter().enumerate() {
        for s in [1.0, -1.0] {
            let mut p = [0.0; 3];
            p[axis] = s * ri;
            pts.push((m, Vec3::from_array(p)));
        }
    }
    let i = inertia_from_point_masses(&pts).unwrap();
    let unit = 2.0 * m * k;
    let want = [
        2.0 * m * (r[1] * r[1] + r[2] * r[2]),
        2.0 * m * (r[0] * r[0] + r[2] * r[2]),
        2.0 * m * (r[0] * r[0] + r[1] * r[1]),
    ];
    assert!(vec_dist(&v64(i.diagonal()), &want) < 1e-14, "(6.8.8a)");
    assert!(vec_dist(&v64(i.diagonal()).map(|c| c / unit), &[6.0, 4.0, 3.0]) < 1e-14);
    let inertia = Inertia::try_from_tensor(i).unwrap();
    let energy = 1.7;
    let a = v64(momentum_ellipsoid_radii(&inertia, energy).unwrap());
    let moments = v64(inertia.principal_moments());
    for k in 0..3 {
        assert!(
            (a[k] * a[k] - 2.0 * energy * moments[k]).abs() < 1e-13,
            "(6.8.8b)"
        );
        assert!(
            (2.0 * a[k] * a[k] * energy - moments[k]).abs() > 1.0,
            "printed (6.8.8b)"
        );
    }
}

// --- §6.9 ---------------------------------------------------------------------------------------

// --- f32 and f64 -------------------------------------------------------------------------------

host_tests::per_type! {
    /// The torque law (6.4.10a) with a constant lab torque: every splitting method integrates it
    /// exactly (each kick adds `N·h/2` in the lab, the free flow keeps `L`), so after 1000 steps
    /// (|L| ≈ 2.4) f64 is exact to rounding (1e-12); f32: up to 25 exact rotations per step, each
    /// rounding |L| ≈ 2.4 by ~ε = 6e-8, a linear budget of 25 000·ε·|L| ≈ 4e-3; measured ≤ 1.7e-4
    /// (Suzuki4), bound 1e-3.
    #[test]
    fn torque_law_6_4_10a_constant_lab_torque() {
        for integ in [
            Integrator::Strang,
            Integrator::Yoshida4,
            Integrator::Suzuki4,
        ] {
            let e = torque_law_error::<T>(integ, 0.0, 1000);
            println!("{integ:?}: constant lab torque, |ΔL| after 1000 steps: {} {e:.1e}", T::NAME);
            assert!(e < T::per_type(1e-3, 1e-12), "{integ:?} {}", T::NAME);
        }
    }

    /// Point masses (6.4.4), (6.4.8)–(6.4.9), (6.5.1)–(6.5.13): centre of mass, momentum, kinetic
    /// energy and velocities by direct sums, against the library's tensor and Hamiltonian.
    /// Tolerances: f64 1e-14, f32 the short-chain budget 2e-6 (relative to |L|, |T| ≈ 10).
    #[test]
    fn rigid_point_masses() {
        let tol = T::per_type(2e-6, 1e-14);
        let pts = cloud();
        let lib_pts: Vec<(T, Vec3<T>)> = pts.iter().map(|(m, r)| (T::from_f64(*m), vec3(*r))).collect();
        let omega = [0.7, -1.1, 0.4];
        // (6.4.4): the centre of mass by a direct sum.
        let msum: f64 = pts.iter().map(|p| p.0).sum();
        let cm = [0, 1, 2].map(|i| pts.iter().map(|(m, r)| m * r[i]).sum::<f64>() / msum);
        let (m_lib, c_lib) = total_mass_and_center(&lib_pts).unwrap();
        assert!((m_lib.to_f64() - msum).abs() < tol * msum);
        assert!(vec_dist(&v64(c_lib), &cm) < tol, "(6.4.4)");
        // (6.4.9a–b), (6.5.2)–(6.5.3): L = Σ r × m (ω × r) = I ω.
        let l_sum = pts.iter().fold([0.0; 3], |acc, (m, r)| {
            let l = cross(*r, cross(omega, *r)).map(|c| c * m);
            [acc[0] + l[0], acc[1] + l[1], acc[2] + l[2]]
        });
        let i = inertia_from_point_masses(&lib_pts).unwrap();
        let l_lib = v64(i * vec3(omega));
        let scale = 10.0;
        assert!(
            vec_dist(&l_lib, &l_sum) < tol * scale,
            "(6.5.3): {l_lib:?} vs {l_sum:?}"
        );
        // (6.5.7)–(6.5.9): T = ½ Σ m |ω × r|² = ½ ω·I·ω.
        let t_sum: f64 = pts
            .iter()
            .map(|(m, r)| {
                let u = cross(omega, *r);
                0.5 * m * dot(u, u)
            })
            .sum();
        let inertia = Inertia::try_from_tensor(i).unwrap();
        let t_lib = 0.5 * dot(omega, l_lib);
        assert!((t_lib - t_sum).abs() < tol * scale, "(6.5.8)");
        // (6.5.10): in the principal axes, T = ½ Σ λᵢ ω_pᵢ².
        let (lam, axes) = (
            v64(inertia.principal_moments()),
            m64(&inertia.principal_axes()),
        );
        let wp = mat_vec(&transpose(&axes), &omega);
        let t_principal = 0.5 * (0..3).map(|k| lam[k] * wp[k] * wp[k]).sum::<f64>();
        assert!((t_principal - t_sum).abs() < tol * scale, "(6.5.10)");
        // (6.5.11)–(6.5.12): T = ½ L·I⁻¹·L = Σ L_pᵢ²/(2λᵢ).
        let t_h = inertia.energy_from_momentum(vec3(l_sum)).to_f64();
        assert!((t_h - t_sum).abs() < tol * scale, "(6.5.11)");
        let t_rigid = BodyHamiltonian::rigid(inertia).energy(vec3(l_sum)).to_f64();
        assert!((t_rigid - t_sum).abs() < tol * scale, "(6.5.12)");
        // (6.5.13): L = ∂T/∂ω by central differences of the direct sum.
        let h = 1e-6;
        for k in 0..3 {
            let t_at = |d: f64| {
                let mut w = omega;
                w[k] += d;
                pts.iter()
                    .map(|(m, r)| {
                        let u = cross(w, *r);
                        0.5 * m * dot(u, u)
                    })
                    .sum::<f64>()
            };
            let fd = (t_at(h) - t_at(-h)) / (2.0 * h);
            assert!((fd - l_lib[k]).abs() < tol * scale + 1e-8, "(6.5.13) {k}");
        }
        // (6.4.8), (6.5.1): a body point's lab velocity is ω_lab × r_lab (central differences of
        // the attitude q(t) = q₀·exp(ω_body t)).
        let q0 = unit_quat::<T>([0.8, -0.2, 0.5, 0.1]);
        let r_body = vec3::<T>(pts[3].1);
        let at = |t: f64| v64(q0 * UnitQuat::try_exp(vec3::<T>(omega.map(|c| c * t))).unwrap() * r_body);
        let ht = 1e-3;
        let fd = [0, 1, 2].map(|k| (at(ht)[k] - at(-ht)[k]) / (2.0 * ht));
        let w_lab = v64(q0.rotate(vec3(omega)));
        let want = cross(w_lab, at(0.0));
        // f64: central-difference truncation ≈ ht²|ω|³|r|/6 ≈ 5e-7; f32: the positions' rounding
        // (6e-8·|r|) over 2ht, ≈ 5e-5.
        let fd_tol = T::per_type(1e-4, 1e-6);
        assert!(vec_dist(&fd, &want) < fd_tol, "(6.4.8): {fd:?} vs {want:?}");
    }


    /// Hamilton's equation `ω = ∂H/∂J` ((6.5.14a), (6.7.17c) BOD form, (6.8.5d), (6.9.2b)) for the
    /// rigid body with a full tensor, the gyro-rotor and both quartic models: `BodyHamiltonian::omega`
    /// against central differences of an independently written `H`.
    #[test]
    fn omega_is_the_gradient_of_h_6_5_14a() {
        let tol = T::per_type(2e-6, 1e-14);
        let inv = inverse(&FULL);
        let spin = [0.3, -0.2, 0.5];
        let j = [0.9, -1.3, 0.6];
        let h = 1e-6;
        // Full tensor with spin: H = ½ (J − S)·I⁻¹·(J − S).
        let inertia = Inertia::try_from_tensor(mat3::<T>(&FULL)).unwrap();
        let model = BodyHamiltonian::try_new(inertia, vec3(spin), Quartic::None).unwrap();
        let e_ref = |j: V3| {
            let r = [j[0] - spin[0], j[1] - spin[1], j[2] - spin[2]];
            0.5 * dot(r, mat_vec(&inv, &r))
        };
        let w = v64(model.omega(vec3(j)));
        for k in 0..3 {
            let (mut p, mut m) = (j, j);
            p[k] += h;
            m[k] -= h;
            let fd = (e_ref(p) - e_ref(m)) / (2.0 * h);
            assert!((w[k] - fd).abs() < tol + 1e-8, "full tensor {k}");
        }
        assert!((model.energy(vec3(j)).to_f64() - e_ref(j)).abs() < tol);
        // Principal axes with the quartic terms (6.8.20a–b).
        let moments = [6.0, 4.0, 3.0];
        let principal = Inertia::try_from_principal(vec3(moments)).unwrap();
        for (q, t4, t22) in [
            (Quartic::Octahedral(T::from_f64(0.02)), 0.02, 0.0),
            (Quartic::Cubic(T::from_f64(-0.03)), 0.0, -0.03),
        ] {
            let model = BodyHamiltonian::try_new(principal, vec3(spin), q).unwrap();
            let rm = RefModel {
                moments,
                spin,
                t4,
                t22,
            };
            let w = v64(model.omega(vec3(j)));
            for k in 0..3 {
                let (mut p, mut m) = (j, j);
                p[k] += h;
                m[k] -= h;
                let fd = (rm.energy(p) - rm.energy(m)) / (2.0 * h);
                assert!((w[k] - fd).abs() < tol + 1e-8, "{q:?} {k}");
            }
        }
    }

    /// Seed (6.6.1b) and (6.6.3): `R(αβγ)` as the printed 3×3 matrix and 2×2 spinor, against the
    /// library's intrinsic `ZYZ`, sign of the spinor included.
    #[test]
    fn seed_6_6_1b_and_6_6_3_euler_zyz() {
        let tol = T::per_type(2e-6, 1e-15);
        for (a, b, g) in [
            (0.4, 1.1, -0.7),
            (50.0 * DEG, 60.0 * DEG, 70.0 * DEG),
            (3.0, -2.0, 5.5),
        ] {
            let q = Euler::new(EulerSequence::ZYZ, [a, b, g].map(T::from_f64)).to_unit_quat_unchecked();
            let (sa, ca) = f64::sin_cos(a);
            let (sb, cb) = f64::sin_cos(b);
            let (sg, cg) = f64::sin_cos(g);
            let r = [
                [ca * cb * cg - sa * sg, -ca * cb * sg - sa * cg, ca * sb],
                [sa * cb * cg + ca * sg, -sa * cb * sg + ca * cg, sa * sb],
                [-cg * sb, sg * sb, cb],
            ];
            let m = m64(&q.to_rotation_matrix());
            for i in 0..3 {
                assert!(vec_dist(&m[i], &r[i]) < tol, "(6.6.1b)");
            }
            let (c2, s2) = ((b / 2.0).cos(), (b / 2.0).sin());
            let u = [
                [
                    cexp(-(a + g) / 2.0).mul(C::new(c2, 0.0)),
                    cexp((g - a) / 2.0).mul(C::new(-s2, 0.0)),
                ],
                [
                    cexp((a - g) / 2.0).mul(C::new(s2, 0.0)),
                    cexp((a + g) / 2.0).mul(C::new(c2, 0.0)),
                ],
            ];
            assert!(u2_dist(&u2_64(&Su2::from(q)), &u) < tol, "(6.6.3)");
        }
    }

    /// Seed (6.6.11a–d): `R[φ, ϑ, Θ] = T e^{−iΘS_Z} T†` with `T = R(φϑ0)`
    /// `= R(φ00) R(0ϑ0) R(00Θ) R(0−ϑ0) R(−φ00) = e^{−iφS_Z} e^{−iϑS_Y} e^{−iΘS_Z} e^{iϑS_Y} e^{iφS_Z}`:
    /// `PolarAxisAngle` against products of library Euler rotations and against products of the
    /// reference's explicit 2×2 matrices (6.6.4), as spinors (sign included, Θ up to 4π).
    #[test]
    fn polar_axis_angle_decomposition_6_6_11() {
        let tol = T::per_type(4e-6, 1e-14);
        let zyz = |a: f64, b: f64, g: f64| {
            Euler::new(EulerSequence::ZYZ, [a, b, g].map(T::from_f64)).to_unit_quat_unchecked()
        };
        for (phi, th, big) in [
            (80.0 * DEG, 34.0 * DEG, 129.0 * DEG),
            (80.0 * DEG, 34.0 * DEG, 489.0 * DEG),
            (-2.0, 2.9, 6.0),
            (0.5, 0.0, 1.0),
            (1.1, core::f64::consts::PI, 3.5),
            (2.2, 1.3, 4.0 * core::f64::consts::PI - 0.1),
        ] {
            let p = PolarAxisAngle::new(T::from_f64(phi), T::from_f64(th), T::from_f64(big));
            let q = p.try_to_unit_quat().unwrap();
            // (6.6.11a–b): the similarity transform of the z twist by T = R(φϑ0).
            let t_op = zyz(phi, th, 0.0);
            let b = zyz(0.0, 0.0, big).similarity_transform(t_op);
            let b2 = t_op * zyz(0.0, 0.0, big) * t_op.inverse();
            // (6.6.11c): five Euler factors.
            let c = zyz(phi, 0.0, 0.0)
                * zyz(0.0, th, 0.0)
                * zyz(0.0, 0.0, big)
                * zyz(0.0, -th, 0.0)
                * zyz(-phi, 0.0, 0.0);
            for (name, x) in [
                ("(6.6.11b)", b),
                ("(6.6.11b) product", b2),
                ("(6.6.11c)", c),
            ] {
                let d = (x.into_quat() - q.into_quat()).norm().to_f64();
                assert!(d < tol, "{name} [{phi}, {th}, {big}]: {d:e}");
            }
            // (6.6.11d) with explicit 2×2 exponentials e^{−iθS} = R[θ n̂] (6.6.4).
            let (z, y) = ([0.0, 0.0, 1.0], [0.0, 1.0, 0.0]);
            let d5 = [
                su2_matrix(z, phi),
                su2_matrix(y, th),
                su2_matrix(z, big),
                su2_matrix(y, -th),
                su2_matrix(z, -phi),
            ]
            .iter()
            .fold(su2_matrix(z, 0.0), |acc, m| u2_mul(&acc, m));
            assert!(
                u2_dist(&u2_64(&Su2::from(q)), &d5) < tol,
                "(6.6.11d) [{phi}, {th}, {big}]"
            );
        }
    }

    /// (6.7.27b–c): the momentum ellipsoid has semi-axes `√(2EIᵢ)`, the velocity ellipsoid
    /// `√(2E/Iᵢ)`: the points at those distances along each principal axis have energy `E` (checked
    /// with an independently inverted tensor). The seed's printed `√Iᵢ/√(2E)` and `1/√(2EIᵢ)`
    /// (and `Iᵢ = 2aᵢ²E` in (6.8.8b)) do not, except at `E = ½`.
    #[test]
    fn ellipsoid_radii_6_7_27() {
        let tol = T::per_type(4e-6, 1e-14);
        let inv = inverse(&FULL);
        let inertia = Inertia::try_from_tensor(mat3::<T>(&FULL)).unwrap();
        let axes = m64(&inertia.principal_axes());
        let moments = v64(inertia.principal_moments());
        let energy = 0.8;
        let a = v64(momentum_ellipsoid_radii(&inertia, T::from_f64(energy)).unwrap());
        let w = v64(velocity_ellipsoid_radii(&inertia, T::from_f64(energy)).unwrap());
        for k in 0..3 {
            let n = [axes[0][k], axes[1][k], axes[2][k]];
            let jk = n.map(|c| c * a[k]);
            assert!(
                (0.5 * dot(jk, mat_vec(&inv, &jk)) - energy).abs() < tol,
                "(6.7.27b) {k}"
            );
            let wk = n.map(|c| c * w[k]);
            assert!(
                (0.5 * dot(wk, mat_vec(&FULL, &wk)) - energy).abs() < tol,
                "(6.7.27c) {k}"
            );
            // The printed forms are off by a factor 2E (momentum) and 1/(2E) (velocity).
            let printed = (moments[k] / (2.0 * energy)).sqrt();
            assert!((a[k] / printed - 2.0 * energy).abs() < tol);
        }
    }

    /// (6.8.20c–d): the quartic tensors along the seed's BOD direction
    /// `Ĵ = (−cos γ sin β, sin γ sin β, cos β)` (6.7.40). The library's quartic energies (difference
    /// of a `BodyHamiltonian` with and without the term) match the printed angle form of `T⁽⁴⁾`
    /// (6.8.20c). For `T⁽²²⁾` the printed `J⁴[cos²2γ sin²β + sin²2β]` is a misprint: expanding
    /// `Ĵ₁²Ĵ₂² + Ĵ₁²Ĵ₃² + Ĵ₂²Ĵ₃²` gives `¼J⁴[sin²2γ sin⁴β + sin²2β]` (the printed form is 0 at
    /// β = 90°, γ = 45°, where `T⁽²²⁾ = J⁴/4`).
    #[test]
    fn quartic_tensors_in_angles_6_8_20c_d() {
        let tol = T::per_type(2e-5, 1e-13); // differences of order-one energies of ~3 in f32
        let inertia = Inertia::try_from_principal(vec3::<T>([6.0, 4.0, 3.0])).unwrap();
        let rigid = BodyHamiltonian::rigid(inertia);
        let octa =
            BodyHamiltonian::try_new(inertia, Vec3::ZERO, Quartic::Octahedral(T::ONE)).unwrap();
        let cubic = BodyHamiltonian::try_new(inertia, Vec3::ZERO, Quartic::Cubic(T::ONE)).unwrap();
        let jm = 1.3f64;
        for kb in 0..=6 {
            for kg in 0..=8 {
                let (b, g) = (kb as f64 * 0.5, kg as f64 * 0.75);
                let d = [-g.cos() * b.sin(), g.sin() * b.sin(), b.cos()];
                let j = vec3::<T>(d.map(|c| c * jm));
                let t4 = (octa.energy(j) - rigid.energy(j)).to_f64();
                let t22 = (cubic.energy(j) - rigid.energy(j)).to_f64();
                let j4 = jm.powi(4);
                let (sb, cb, sg, cg) = (b.sin(), b.cos(), g.sin(), g.cos());
                let printed_c =
                    j4 * (cg.powi(4) * sb.powi(4) + sg.powi(4) * sb.powi(4) + cb.powi(4));
                assert!((t4 - printed_c).abs() < tol, "(6.8.20c) β={b} γ={g}");
                let corrected_d =
                    0.25 * j4 * ((2.0 * g).sin().powi(2) * sb.powi(4) + (2.0 * b).sin().powi(2));
                assert!((t22 - corrected_d).abs() < tol, "(6.8.20d) β={b} γ={g}");
            }
        }
        // The printed (6.8.20d) at β = 90°, γ = 45°.
        let (b, g) = (core::f64::consts::FRAC_PI_2, core::f64::consts::FRAC_PI_4);
        let printed_d = (2.0 * g).cos().powi(2) * b.sin().powi(2) + (2.0 * b).sin().powi(2);
        let j = vec3::<T>([-g.cos() * b.sin(), g.sin() * b.sin(), b.cos()]);
        let t22 = (cubic.energy(j) - rigid.energy(j)).to_f64();
        assert!((t22 - 0.25).abs() < tol && printed_d.abs() < 1e-15);
    }

    /// (6.9.5)–(6.9.6b): a spherical gyro-rotor's energy is linear in `K = J_z` (spin on z),
    /// `E = BS² + BJ² − 2BSK` with `gμ = 2B`; a symmetric rigid top's is quadratic,
    /// `E = BJ² + (C − B)K²` (`B = 1/(2I₁)`, `C = 1/(2I₃)`).
    #[test]
    fn gyro_and_symmetric_top_energies_6_9_5_and_6_9_6() {
        let tol = T::per_type(1e-6, 1e-15);
        let (i, s) = (2.5, 0.8);
        let bb = 1.0 / (2.0 * i);
        let sph = BodyHamiltonian::try_new(
            Inertia::try_from_principal(vec3::<T>([i, i, i])).unwrap(),
            vec3([0.0, 0.0, s]),
            Quartic::None,
        )
        .unwrap();
        let (it, i3) = (3.0, 1.7);
        let (b2, c2) = (1.0 / (2.0 * it), 1.0 / (2.0 * i3));
        let top = BodyHamiltonian::rigid(Inertia::try_from_principal(vec3([it, it, i3])).unwrap());
        for j in [[0.3, -0.4, 1.2], [1.0, 0.0, 0.0], [0.2, 0.9, -0.5]] {
            let (j2, kk) = (dot(j, j), j[2]);
            let e = sph.energy(vec3::<T>(j)).to_f64();
            assert!(
                (e - (bb * s * s + bb * j2 - 2.0 * bb * s * kk)).abs() < tol,
                "(6.9.5)"
            );
            let e = top.energy(vec3::<T>(j)).to_f64();
            assert!(
                (e - (b2 * j2 + (c2 - b2) * kk * kk)).abs() < tol,
                "(6.9.6b)"
            );
        }
    }
}
