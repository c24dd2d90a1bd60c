//! Euler momenta (`Euler::*euler_momenta*`, (6.7.6)–(6.7.16)) and the rigid rotor in Euler
//! coordinates (`gyrostat::dynamics::closed_form::euler_coordinates`, (6.7.31)–(6.7.44)).
//!
//! References, none of which calls the library's rate or momentum maps:
//! - the angular velocity of the reference Euler matrices moved along each angle (central
//!   differences), from which the Lagrangian `L(θ̇) = ½ω·I·ω` and its exact derivatives
//!   `p = ∂L/∂θ̇` follow (L is quadratic in the rates);
//! - the seed's printed ZYZ matrices (6.7.5c–f), (6.7.10a–d), (6.6.1b), typed in here;
//! - central differences of the Cartesian Hamiltonian `½ΣJᵢ²/Iᵢ` and Lagrangian, and an RK4
//!   integration of the free symmetric top.
#![allow(clippy::needless_range_loop)] // 3×3 index loops read like the formulas

use gyrostat::dynamics::closed_form::analysis::symmetric_top_rates;
use gyrostat::dynamics::closed_form::euler_coordinates::{
    SymmetricTop, euler_hamiltonian, euler_metric, kinetic_energy, try_euler_momenta,
    try_euler_rates_from_momenta,
};
use gyrostat::dynamics::inertia::Inertia;
use gyrostat::rotation::{Euler, EulerSequence, euler_rate_min_det};
use gyrostat::{Error, Mat3, Quat, UnitQuat, Vec3};
use host_tests::cast::{m64, mat3, v64};
use host_tests::ref_exact::{self, RigidState};
use host_tests::ref_rotation::{
    all_sequences, euler_matrix, is_proper, omega_from_matrices, poles,
};
use host_tests::reference::{M3, V3, dot, mat_dist, mat_mul, mat_vec, transpose, vec_dist};

const TENSOR: M3 = [[5.0, 0.3, -0.2], [0.3, 4.0, 0.1], [-0.2, 0.1, 3.0]];

// --- the symmetric top, seed §6.7.f ----------------------------------------------------------

const I_T: f64 = 3.0;
const I_3: f64 = 1.7;

/// The seed's (6.7.5d) body rate, typed in.
fn omega_body(beta: f64, gamma: f64, rates: V3) -> V3 {
    let (sb, cb) = beta.sin_cos();
    let (sg, cg) = gamma.sin_cos();
    let [ad, bd, gd] = rates;
    [
        -sb * cg * ad + sg * bd,
        sb * sg * ad + cg * bd,
        cb * ad + gd,
    ]
}

/// `L = ½ Σ Iᵢωᵢ²` with ω from (6.7.5d) (γ = 0.37: L must not depend on it).
fn lagrangian_ref(beta: f64, rates: V3) -> f64 {
    let w = omega_body(beta, 0.37, rates);
    0.5 * (I_T * (w[0] * w[0] + w[1] * w[1]) + I_3 * w[2] * w[2])
}

/// `H = ½ Σ Jᵢ²/Iᵢ` with `J = (6.7.10b)·p`, typed in (γ = 0.37).
fn hamiltonian_ref(beta: f64, p: V3) -> f64 {
    let (sb, cb) = beta.sin_cos();
    let (sg, cg) = 0.37f64.sin_cos();
    let (cot, csc) = (cb / sb, 1.0 / sb);
    let m = [
        [-cg * csc, sg, cot * cg],
        [sg * csc, cg, -cot * sg],
        [0.0, 0.0, 1.0],
    ];
    let j = mat_vec(&m, &p);
    0.5 * (j[0] * j[0] / I_T + j[1] * j[1] / I_T + j[2] * j[2] / I_3)
}

host_tests::per_type! {
    /// For every convention: the library's Euler momenta are `∂L/∂θ̇` of the Lagrangian built
    /// from the reference matrices (6.7.6), (6.7.9); the maps both ways match (6.7.10a–d); the
    /// pairing `p·θ̇ = J·ω` is frame-invariant (6.7.16); the metric, the inverse (Hamilton's
    /// velocities) and the Hamiltonian of `euler_coordinates` agree. f64: central differences with h = 1e-5,
    /// truncation ~1e-10 on order-one columns (bound 1e-9); f32: the short-chain budget 2e-6.
    #[test]
    fn euler_momenta_all_conventions() {
        let tol = T::per_type(2e-6, 1e-9);
        let h = 1e-5;
        let inertia = Inertia::try_from_tensor(mat3::<T>(&TENSOR)).unwrap();
        for seq_s in all_sequences() {
            let seq = EulerSequence::try_from_str(&seq_s).unwrap();
            let b = if is_proper(&seq_s) { 0.9 } else { 0.4 };
            let ang = [0.7, b, -1.3];
            let rates = [0.3, -0.8, 1.1];
            let e = Euler::new(seq, ang.map(T::from_f64));
            // ω_body for a unit rate of each angle: the columns ω_k; ω(θ̇) = Σ θ̇_k ω_k.
            let col = |k: usize| {
                let at = |s: f64| {
                    let mut a = ang;
                    a[k] += s;
                    euler_matrix(&seq_s, a)
                };
                omega_from_matrices(&at(-h), &at(h), h, true)
            };
            let cols = [col(0), col(1), col(2)];
            let omega: V3 = [0, 1, 2].map(|i| (0..3).map(|k| rates[k] * cols[k][i]).sum());
            let j_body = mat_vec(&TENSOR, &omega);
            let r = euler_matrix(&seq_s, ang);
            let j_lab = mat_vec(&r, &j_body);
            // L = ½ ω·I·ω is quadratic in θ̇: ∂L/∂θ̇_k = ω_k·I·ω exactly.
            let p: V3 = [0, 1, 2].map(|k| dot(cols[k], j_body));
            let metric: M3 =
                [0, 1, 2].map(|k| [0, 1, 2].map(|l| dot(cols[k], mat_vec(&TENSOR, &cols[l]))));
            let scale = 10.0; // |J|, |p| are of order 10 here
            let got = e
                .try_euler_momenta_from_body(Vec3::from_array(j_body.map(T::from_f64)))
                .unwrap()
                .map(|x| x.to_f64());
            assert!(
                vec_dist(&got, &p) < tol * scale,
                "{seq_s} (6.7.10d): {got:?} vs {p:?}"
            );
            let got = e
                .try_euler_momenta_from_lab(Vec3::from_array(j_lab.map(T::from_f64)))
                .unwrap()
                .map(|x| x.to_f64());
            assert!(vec_dist(&got, &p) < tol * scale, "{seq_s} (6.7.10c)");
            let pt = p.map(T::from_f64);
            let got = v64(e.try_body_momentum_from_euler_momenta(pt).unwrap());
            assert!(
                vec_dist(&got, &j_body) < 10.0 * tol * scale,
                "{seq_s} (6.7.10b)"
            );
            let got = v64(e.try_lab_momentum_from_euler_momenta(pt).unwrap());
            assert!(
                vec_dist(&got, &j_lab) < 10.0 * tol * scale,
                "{seq_s} (6.7.10a)"
            );
            // (6.7.16): ½ p·θ̇ = ½ J·ω in the body and in the lab frame.
            let t_euler = 0.5 * dot(p, rates);
            let omega_lab = mat_vec(&r, &omega);
            assert!((t_euler - 0.5 * dot(j_body, omega)).abs() < 1e-9);
            assert!((t_euler - 0.5 * dot(j_lab, omega_lab)).abs() < 1e-9);
            let rt = rates.map(T::from_f64);
            let t_lib = kinetic_energy(&inertia, &e, rt).unwrap().to_f64();
            assert!(
                (t_lib - t_euler).abs() < tol * scale,
                "{seq_s} T: {t_lib} vs {t_euler}"
            );
            // The metric g = ∂²L/∂θ̇² and p = g θ̇.
            let g = m64(&euler_metric(&inertia, &e).unwrap());
            for k in 0..3 {
                assert!(vec_dist(&g[k], &metric[k]) < tol * scale, "{seq_s} metric");
            }
            let got = try_euler_momenta(&inertia, &e, rt)
                .unwrap()
                .map(|x| x.to_f64());
            assert!(vec_dist(&got, &p) < tol * scale, "{seq_s} p = gθ̇");
            // Hamilton's velocity equations θ̇ = g⁻¹p (6.7.17c), H = ½ p·g⁻¹·p = T.
            let back = try_euler_rates_from_momenta(&inertia, &e, pt)
                .unwrap()
                .map(|x| x.to_f64());
            assert!(
                vec_dist(&back, &rates) < 10.0 * tol * scale,
                "{seq_s} θ̇ = g⁻¹p"
            );
            let hm = euler_hamiltonian(&inertia, &e, pt).unwrap().to_f64();
            assert!(
                (hm - t_euler).abs() < 10.0 * tol * scale,
                "{seq_s} H: {hm} vs {t_euler}"
            );
        }
    }

    /// The maps out of the Euler momenta share the rate maps' typed error at gimbal lock.
    #[test]
    fn euler_momenta_are_singular_at_gimbal_lock() {
        let thr = euler_rate_min_det::<T>().to_f64();
        let inertia = Inertia::try_from_principal(Vec3::new(
            T::from_f64(3.0),
            T::from_f64(3.0),
            T::from_f64(2.0),
        ))
        .unwrap();
        for seq_s in all_sequences() {
            let seq = EulerSequence::try_from_str(&seq_s).unwrap();
            for pole in poles(&seq_s) {
                for d in [0.0, 0.5 * thr, -0.5 * thr] {
                    let e = Euler::new(seq, [0.3, pole + d, -0.2].map(T::from_f64));
                    let p = [T::ONE; 3];
                    assert_eq!(e.try_euler_momenta_to_body_matrix(), Err(Error::Singular));
                    assert_eq!(e.try_euler_momenta_to_lab_matrix(), Err(Error::Singular));
                    assert_eq!(
                        e.try_body_momentum_from_euler_momenta(p),
                        Err(Error::Singular),
                        "{seq_s}"
                    );
                    assert_eq!(
                        e.try_lab_momentum_from_euler_momenta(p),
                        Err(Error::Singular)
                    );
                    assert_eq!(
                        try_euler_rates_from_momenta(&inertia, &e, p),
                        Err(Error::Singular)
                    );
                    assert_eq!(euler_hamiltonian(&inertia, &e, p), Err(Error::Singular));
                    // The maps into the Euler momenta are defined at the pole.
                    assert!(e.try_euler_momenta_from_body(Vec3::X).is_ok());
                }
                let e = Euler::new(seq, [0.3, pole + 4.0 * thr, -0.2].map(T::from_f64));
                assert!(e.try_euler_momenta_to_body_matrix().unwrap().is_finite());
            }
        }
        let nan = Euler::new(
            EulerSequence::ZYZ,
            [T::ZERO, T::from_f64(f64::NAN), T::ZERO],
        );
        assert_eq!(
            nan.try_euler_momenta_from_body(Vec3::X),
            Err(Error::NonFinite)
        );
        let e = Euler::new(EulerSequence::ZYZ, [T::ZERO, T::ONE, T::ZERO]);
        assert_eq!(
            e.try_euler_momenta_from_lab(Vec3::new(T::from_f64(f64::INFINITY), T::ZERO, T::ZERO)),
            Err(Error::NonFinite)
        );
        assert_eq!(
            try_euler_momenta(&inertia, &e, [T::ZERO, T::from_f64(f64::NAN), T::ZERO]),
            Err(Error::NonFinite)
        );
    }

    /// Seed (6.7.31)–(6.7.44) for a symmetric top. f64: 1e-13; f32: order-one quantities through
    /// ~20 f32 roundings (and sin/cos of β), 4e-6.
    #[test]
    fn symmetric_top() {
        let tol = T::per_type(4e-6, 1e-13);
        let top = SymmetricTop::try_new(T::from_f64(I_T), T::from_f64(I_3)).unwrap();
        let beta = 0.9;
        let rates = [0.4, -0.3, 1.1];
        let (bt, rt) = (T::from_f64(beta), rates.map(T::from_f64));
        let (sb, cb) = beta.sin_cos();
        // (6.7.31)–(6.7.32a): L from the Cartesian body rates.
        let l = top.lagrangian(bt, rt).unwrap().to_f64();
        assert!((l - lagrangian_ref(beta, rates)).abs() < tol, "(6.7.32a)");
        // (6.7.32b): the spherical top.
        let sph = SymmetricTop::try_new(T::from_f64(2.0), T::from_f64(2.0)).unwrap();
        let [ad, bd, gd] = rates;
        let l_sph = 0.5 * 2.0 * (ad * ad + bd * bd + 2.0 * ad * gd * cb + gd * gd);
        assert!(
            (sph.lagrangian(bt, rt).unwrap().to_f64() - l_sph).abs() < tol,
            "(6.7.32b)"
        );
        // (6.7.33): the metric, against g = Eᵀ I E from (6.7.5d) and the general library form.
        let e: M3 = {
            let cols = [
                omega_body(beta, 0.37, [1.0, 0.0, 0.0]),
                omega_body(beta, 0.37, [0.0, 1.0, 0.0]),
                omega_body(beta, 0.37, [0.0, 0.0, 1.0]),
            ];
            [0, 1, 2].map(|i| [0, 1, 2].map(|k| cols[k][i]))
        };
        let i_diag = [[I_T, 0.0, 0.0], [0.0, I_T, 0.0], [0.0, 0.0, I_3]];
        let g_ref = mat_mul(&mat_mul(&transpose(&e), &i_diag), &e);
        let g = m64(&top.metric(bt).unwrap());
        let inertia = Inertia::try_from_principal(Vec3::new(
            T::from_f64(I_T),
            T::from_f64(I_T),
            T::from_f64(I_3),
        ))
        .unwrap();
        let euler = Euler::new(EulerSequence::ZYZ, [0.2, beta, 0.37].map(T::from_f64));
        let g_gen = m64(&euler_metric(&inertia, &euler).unwrap());
        for i in 0..3 {
            assert!(vec_dist(&g[i], &g_ref[i]) < tol, "(6.7.33)");
            assert!(vec_dist(&g_gen[i], &g_ref[i]) < tol, "(6.7.33) general");
        }
        // (6.7.34), (6.7.44): J_μ = g_μν ν̇.
        let p_ref = mat_vec(&g_ref, &rates);
        let p = top.try_momenta(bt, rt).unwrap().map(|x| x.to_f64());
        assert!(vec_dist(&p, &p_ref) < tol, "(6.7.34)");
        let p_gen = try_euler_momenta(&inertia, &euler, rt)
            .unwrap()
            .map(|x| x.to_f64());
        assert!(vec_dist(&p_gen, &p_ref) < tol);
        let pt = p_ref.map(T::from_f64);
        // (6.7.35b): H in Euler momenta is the Cartesian ½ΣJᵢ²/Iᵢ, and equals L at these momenta.
        let hm = top.hamiltonian(bt, pt).unwrap().to_f64();
        assert!((hm - hamiltonian_ref(beta, p_ref)).abs() < tol, "(6.7.35b)");
        assert!((hm - l).abs() < tol);
        // (6.7.35a): θ̇ = ∂H/∂p, by central differences of the Cartesian H, and = g⁻¹p.
        let back = top.try_rates(bt, pt).unwrap().map(|x| x.to_f64());
        assert!(vec_dist(&back, &rates) < 4.0 * tol, "(6.7.35a) inverse");
        let h = 1e-6;
        for k in 0..3 {
            let (mut pp, mut pm) = (p_ref, p_ref);
            pp[k] += h;
            pm[k] -= h;
            let fd = (hamiltonian_ref(beta, pp) - hamiltonian_ref(beta, pm)) / (2.0 * h);
            assert!(
                (back[k] - fd).abs() < 4.0 * tol + 1e-8,
                "(6.7.35a) ∂H/∂p_{k}"
            );
        }
        // (6.7.36): J̇_β = −∂H/∂β at fixed p = ∂L/∂β at fixed θ̇.
        let torque_h = top.beta_torque(bt, pt).unwrap().to_f64();
        let torque_l = top.beta_torque_from_rates(bt, rt).unwrap().to_f64();
        let fd_h =
            -(hamiltonian_ref(beta + h, p_ref) - hamiltonian_ref(beta - h, p_ref)) / (2.0 * h);
        let fd_l = (lagrangian_ref(beta + h, rates) - lagrangian_ref(beta - h, rates)) / (2.0 * h);
        assert!(
            (torque_h - fd_h).abs() < 4.0 * tol + 1e-8,
            "(6.7.36) H: {torque_h} vs {fd_h}"
        );
        assert!(
            (torque_l - fd_l).abs() < 4.0 * tol + 1e-8,
            "(6.7.36) L: {torque_l} vs {fd_l}"
        );
        // (6.7.37a–b): the factors of the torque in rates.
        let (ja, jg) = (p_ref[0], p_ref[2]);
        assert!(
            (ja - jg * cb - I_T * ad * sb * sb).abs() < 1e-14,
            "(6.7.37a)"
        );
        let b37 = (I_T - I_3) * ad * sb * sb * cb - I_3 * gd * sb * sb;
        assert!((ja * cb - jg - b37).abs() < 1e-14, "(6.7.37b)");
        // (6.7.38)–(6.7.43): lab J on z. Euler momenta (J, 0, J cos β); rates α̇ = J/I_II,
        // β̇ = 0, γ̇ = (1/I₃ − 1/I_II) J cos β (6.7.39), (6.7.43a); body J (6.7.40).
        let jm = 2.0;
        let pz = euler
            .try_euler_momenta_from_lab(Vec3::new(T::ZERO, T::ZERO, T::from_f64(jm)))
            .unwrap();
        let pz64 = pz.map(|x| x.to_f64());
        assert!(vec_dist(&pz64, &[jm, 0.0, jm * cb]) < tol, "(6.7.38)");
        let rz = top.try_rates(bt, pz).unwrap().map(|x| x.to_f64());
        let gamma_dot = (1.0 / I_3 - 1.0 / I_T) * jm * cb;
        assert!(
            vec_dist(&rz, &[jm / I_T, 0.0, gamma_dot]) < 4.0 * tol,
            "(6.7.39)"
        );
        let top64 = Inertia::try_from_principal(Vec3::new(I_T, I_T, I_3)).unwrap();
        let an = symmetric_top_rates(&top64, jm, beta).unwrap();
        assert!(
            (an.body_precession - gamma_dot).abs() < 1e-14
                && (an.lab_precession - jm / I_T).abs() < 1e-15
        );
        let jb = v64(euler.try_body_momentum_from_euler_momenta(pz).unwrap());
        let gam = 0.37f64;
        let want = [-jm * sb * gam.cos(), jm * sb * gam.sin(), jm * cb];
        assert!(vec_dist(&jb, &want) < 4.0 * tol, "(6.7.40)");
        // (6.7.43b–d): J₃ = J cos β = I₃ω₃, ω₃ = J cos β/I₃, γ̇ = (I_II − I₃)/I_II · ω₃.
        let w3 = jb[2] / I_3;
        assert!((w3 - jm * cb / I_3).abs() < 4.0 * tol);
        assert!((gamma_dot - (I_T - I_3) / I_T * w3).abs() < 4.0 * tol);
        // (6.7.41a–b) with rates (α̇, 0, γ̇): ω_lab = α̇ z + γ̇ z̄, ω_body = α̇ z(in body) + γ̇ z̄.
        let r41 = Vec3::new(T::from_f64(jm / I_T), T::ZERO, T::from_f64(gamma_dot));
        let wl = v64(euler.rates_to_lab_matrix() * r41);
        let zb = [0.2f64.cos() * sb, 0.2f64.sin() * sb, cb];
        let want = [0, 1, 2].map(|i| jm / I_T * [0.0, 0.0, 1.0][i] + gamma_dot * zb[i]);
        assert!(vec_dist(&wl, &want) < 4.0 * tol, "(6.7.41a)");
        let wb = v64(euler.rates_to_body_matrix() * r41);
        let zl = [-sb * gam.cos(), sb * gam.sin(), cb];
        let want = [0, 1, 2].map(|i| jm / I_T * zl[i] + gamma_dot * [0.0, 0.0, 1.0][i]);
        assert!(vec_dist(&wb, &want) < 4.0 * tol, "(6.7.41b)");
        // (6.7.42a–b) at α = γ = 0.
        let e0 = Euler::new(EulerSequence::ZYZ, [T::ZERO, bt, T::ZERO]);
        let wl0 = v64(e0.rates_to_lab_matrix() * r41);
        let wb0 = v64(e0.rates_to_body_matrix() * r41);
        let a_dot = jm / I_T;
        assert!(vec_dist(&wl0, &[gamma_dot * sb, 0.0, a_dot + gamma_dot * cb]) < 4.0 * tol);
        assert!(vec_dist(&wb0, &[-a_dot * sb, 0.0, a_dot * cb + gamma_dot]) < 4.0 * tol);
        assert!(vec_dist(&wb0, &v64(an.omega_body)) < 4.0 * tol, "(6.7.42b)");
        assert!(vec_dist(&wl0, &v64(an.omega_lab)) < 4.0 * tol, "(6.7.42a)");
        // Gimbal lock and bad input.
        assert_eq!(top.try_rates(T::ZERO, pt), Err(Error::Singular));
        assert_eq!(
            top.hamiltonian(T::from_f64(core::f64::consts::PI), pt),
            Err(Error::Singular)
        );
        assert_eq!(top.beta_torque(T::ZERO, pt), Err(Error::Singular));
        assert!(
            top.beta_torque_from_rates(T::ZERO, rt)
                .unwrap()
                .to_f64()
                .abs()
                < tol
        );
        assert_eq!(
            top.try_momenta(T::from_f64(f64::NAN), rt),
            Err(Error::NonFinite)
        );
        assert_eq!(
            SymmetricTop::try_new(T::ONE, T::from_f64(2.5)),
            Err(Error::NonPhysicalInertia)
        );
        assert_eq!(
            SymmetricTop::try_new(T::ZERO, T::ONE),
            Err(Error::NonPhysicalInertia)
        );
    }
}

/// Every entry of `m` within 1e-15 of the printed matrix `want`.
fn close(m: &Mat3<f64>, want: M3, what: &str) {
    let d = mat_dist(&m64(m), &want);
    assert!(d < 1e-15, "{what}: {m:?} vs {want:?} ({d:e})");
}

/// Seed (6.7.10a–d) for ZYZ, entry by entry from the printed matrices; and the factorisations
/// of the rotation (6.6.15a) (printed in §6.7 with that number) and (6.7.15b), with
/// `R(αβγ)` from the printed (6.6.1b).
#[test]
fn seed_6_7_10_zyz_matrices_and_6_7_15_factorisations() {
    let (a, b, g) = (0.4f64, 1.1, -0.7);
    let e = Euler::new(EulerSequence::ZYZ, [a, b, g]);
    let (sa, ca) = a.sin_cos();
    let (sb, cb) = b.sin_cos();
    let (sg, cg) = g.sin_cos();
    let (cot, csc) = (cb / sb, 1.0 / sb);
    let m10a = [
        [-ca * cot, -sa, ca * csc],
        [-sa * cot, ca, sa * csc],
        [1.0, 0.0, 0.0],
    ];
    let m10b = [
        [-cg * csc, sg, cot * cg],
        [sg * csc, cg, -cot * sg],
        [0.0, 0.0, 1.0],
    ];
    let m10c = [[0.0, 0.0, 1.0], [-sa, ca, 0.0], [ca * sb, sa * sb, cb]];
    let m10d = [[-sb * cg, sb * sg, cb], [sg, cg, 0.0], [0.0, 0.0, 1.0]];
    close(
        &e.try_euler_momenta_to_lab_matrix().unwrap(),
        m10a,
        "(6.7.10a)",
    );
    close(
        &e.try_euler_momenta_to_body_matrix().unwrap(),
        m10b,
        "(6.7.10b)",
    );
    close(&e.lab_to_euler_momenta_matrix(), m10c, "(6.7.10c)");
    close(&e.body_to_euler_momenta_matrix(), m10d, "(6.7.10d)");
    // (6.6.1b)
    let r = [
        [ca * cb * cg - sa * sg, -ca * cb * sg - sa * cg, ca * sb],
        [sa * cb * cg + ca * sg, -sa * cb * sg + ca * cg, sa * sb],
        [-cg * sb, sg * sb, cb],
    ];
    // (6.6.15a): (6.7.5c)·(6.7.5f) = R; (6.7.15b): (6.7.10a)·(6.7.10d) = R.
    let m5c = [[0.0, -sa, ca * sb], [0.0, ca, sa * sb], [1.0, 0.0, cb]];
    let m5f = [
        [-cg * csc, sg * csc, 0.0],
        [sg, cg, 0.0],
        [cot * cg, -cot * sg, 1.0],
    ];
    let p1 = mat_mul(&m5c, &m5f);
    let p2 = mat_mul(&m10a, &m10d);
    let lib1 = e.rates_to_lab_matrix() * e.try_body_to_rates_matrix().unwrap();
    let lib2 = e.try_euler_momenta_to_lab_matrix().unwrap() * e.body_to_euler_momenta_matrix();
    for i in 0..3 {
        for j in 0..3 {
            assert!((p1[i][j] - r[i][j]).abs() < 1e-15, "seed (6.6.15a) product");
            assert!((p2[i][j] - r[i][j]).abs() < 1e-15, "seed (6.7.15b) product");
            assert!((lib1.m[i][j] - r[i][j]).abs() < 1e-15);
            assert!((lib2.m[i][j] - r[i][j]).abs() < 1e-15);
        }
    }
    // The seed's own example (6.7.38): lab J on z gives (J_α, J_β, J_γ) = (J, 0, J cos β).
    let p = e
        .try_euler_momenta_from_lab(Vec3::new(0.0, 0.0, 2.0))
        .unwrap();
    assert!((p[0] - 2.0).abs() < 1e-15 && p[1].abs() < 1e-15 && (p[2] - 2.0 * cb).abs() < 1e-15);
}

/// The factorisations hold in every convention: `E_lab·E_body⁻¹ = R = (E_lab⁻¹)ᵀ·E_bodyᵀ`.
#[test]
fn rotation_factorises_through_euler_coordinates_all_conventions() {
    for seq_s in all_sequences() {
        let seq = EulerSequence::try_from_str(&seq_s).unwrap();
        let b = if is_proper(&seq_s) { 0.9 } else { 0.4 };
        let ang = [0.7, b, -1.3];
        let e = Euler::new(seq, ang);
        let r = euler_matrix(&seq_s, ang);
        let lib1 = m64(&(e.rates_to_lab_matrix() * e.try_body_to_rates_matrix().unwrap()));
        let lib2 =
            m64(&(e.try_euler_momenta_to_lab_matrix().unwrap() * e.body_to_euler_momenta_matrix()));
        for i in 0..3 {
            assert!(vec_dist(&lib1[i], &r[i]) < 1e-14, "{seq_s}");
            assert!(vec_dist(&lib2[i], &r[i]) < 1e-14, "{seq_s}");
        }
    }
}

/// The free symmetric top moving (RK4 reference): `J_α` and `J_γ` stay constant, the rates
/// measured from the Euler angles of the trajectory are Hamilton's (6.7.35a), and the measured
/// `J̇_β` is the torque (6.7.36).
#[test]
fn symmetric_top_motion_6_7_35_and_6_7_36() {
    let top = SymmetricTop::try_new(I_T, I_3).unwrap();
    let q0 = {
        let q = [0.8f64, 0.3, -0.4, 0.2];
        let n = q.iter().map(|c| c * c).sum::<f64>().sqrt();
        q.map(|c| c / n)
    };
    let s0 = RigidState {
        j: [0.7, -0.4, 1.1],
        q: q0,
    };
    let h = 1e-3;
    let mut times = Vec::new();
    for k in 1..=6 {
        let t = k as f64 * 0.7;
        times.extend([t - h, t, t + h]);
    }
    let states = ref_exact::integrate_rigid([I_T, I_T, I_3], s0, &times, 1e-4);
    let euler_of = |s: &RigidState| {
        let q = UnitQuat::try_new(Quat::new(s.q[0], s.q[1], s.q[2], s.q[3])).unwrap();
        let ang = q.to_euler_angles(EulerSequence::ZYZ);
        let lab = q.rotate(Vec3::from_array(s.j));
        let e = Euler::new(EulerSequence::ZYZ, ang);
        (ang, e.try_euler_momenta_from_lab(lab).unwrap())
    };
    let (_, p_start) = euler_of(&states[1]);
    for w in states.chunks(3) {
        let (am, pm) = euler_of(&w[0]);
        let (a, p) = euler_of(&w[1]);
        let (ap, pp) = euler_of(&w[2]);
        // J_α (lab J_z) and J_γ (body J₃) are conserved (6.7.36).
        assert!((p[0] - p_start[0]).abs() < 1e-10 && (p[2] - p_start[2]).abs() < 1e-10);
        // (6.7.35a): the rates of the trajectory's Euler angles (no wrap over 2 ms here).
        let rates_fd = [0, 1, 2].map(|k| (ap[k] - am[k]) / (2.0 * h));
        let rates = top.try_rates(a[1], p).unwrap();
        assert!(
            vec_dist(&rates, &rates_fd) < 1e-5,
            "{rates:?} vs {rates_fd:?}"
        );
        // (6.7.36): dJ_β/dt.
        let torque_fd = (pp[1] - pm[1]) / (2.0 * h);
        let torque = top.beta_torque(a[1], p).unwrap();
        assert!((torque - torque_fd).abs() < 1e-5, "{torque} vs {torque_fd}");
        let torque_l = top.beta_torque_from_rates(a[1], rates).unwrap();
        assert!((torque - torque_l).abs() < 1e-12);
    }
}
