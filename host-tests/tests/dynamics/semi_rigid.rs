//! Semi-rigid rotors (`gyrostat::dynamics::semi_rigid`, seed (6.8.11)–(6.8.20)) against a direct
//! numerical minimisation of the spring-plus-centrifugal energy at fixed angular momentum.
//!
//! The reference never uses the library's expansion: it builds the inertia tensor of the
//! stretched masses from their positions, inverts it by cofactors and minimises
//! `Σ ½k(r_j − r₀)² + ½ J·I(r)⁻¹·J` over the radii by golden-section search (coordinate descent
//! for several masses), in f64. What is checked:
//! - the exact equilibrium and (6.8.12) against the minimiser;
//! - the first-order stretch (6.8.13), (6.8.17) against the minimiser, to their `O(J⁴)`;
//! - the quartic energy (6.8.15), (6.8.18)–(6.8.20): the residual against the minimum scales as
//!   `J⁶` (halving `J` divides it by 64), so the quartic is the leading correction, and for the
//!   one-mass rotor its `J⁶` coefficient is the hand-derived `3/(2m⁵ω_v⁴r₀¹⁰)`;
//! - the closed forms of the module table (derived by hand, not by the library's sum);
//! - the isotropic term as a Casimir turn, against an RK4 integration of the full Hamiltonian.

use gyrostat::dynamics::semi_rigid::{
    Arrangement, QuarticBasis, SemiRigidRotor, SpringRotor, StretchMode, radial_stretches,
};
use gyrostat::dynamics::{Gyrostat, Integrator, Quartic, State};
use gyrostat::{Error, UnitQuat, Vec3};
use host_tests::cast::{q64, unit_quat, v64, vec3};
use host_tests::ref_dynamics::{RefModel, inverse, lie_poisson_rk4};
use host_tests::reference::{M3, V3, mat_dist, quat_matrix, vec_dist};

// A rotor with no unit values, so that a wrong power of m, ω_v or r₀ shows.
const M: f64 = 1.3;
const W: f64 = 2.1;
const R0: f64 = 0.7;

/// Golden-section minimum of `f` on `[a, b]`: `(x, f(x))`. Stops when the bracket is below
/// `1e-13·(|a| + |b|)` or after 200 steps; the minimum value is then exact to rounding (the
/// function is flat there), the argument to about `√ε` of the scale.
fn golden(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> (f64, f64) {
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let mut c = b - g * (b - a);
    let mut d = a + g * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..200 {
        if (b - a).abs() < 1e-13 * (a.abs() + b.abs()) {
            break;
        }
        if fc < fd {
            b = d;
            d = c;
            fd = fc;
            c = b - g * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + g * (b - a);
            fd = f(d);
        }
    }
    let x = 0.5 * (a + b);
    (x, f(x))
}

/// The seed's (6.8.11) at `p_v = 0`, written out.
fn planar_energy(r: f64, j: f64) -> f64 {
    0.5 * M * W * W * (r - R0).powi(2) + j * j / (2.0 * M * r * r)
}

#[test]
fn spring_rotor_matches_direct_minimisation_6_8_11_to_6_8_15() {
    let rotor = SpringRotor::try_new(M, W, R0).unwrap();
    let mu0 = 1.0 / (M * R0 * R0);
    let mut residual = Vec::new();
    for j in [0.05, 0.025] {
        let (r_min, e_min) = golden(|r| planar_energy(r, j), R0, 1.5 * R0);
        // The exact equilibrium: the library's Newton root is the minimiser (golden section
        // locates it to ~1e-9 of r₀), and its energy is not above the minimum found.
        let r = rotor.equilibrium_radius(j).unwrap();
        assert!((r - r_min).abs() < 1e-7 * R0, "J={j}: {r} vs {r_min}");
        let e_at = rotor.energy(r, 0.0, j).unwrap();
        assert!(e_at <= e_min * (1.0 + 1e-15), "J={j}: {e_at} > {e_min}");
        // (6.8.12) at the minimiser's own rate ω_J = J/(m r²) gives back the minimiser.
        let omega_j = j / (M * r_min * r_min);
        let r612 = rotor.stretched_radius(omega_j).unwrap();
        assert!(
            (r612 - r_min).abs() < 1e-7 * R0,
            "(6.8.12): {r612} vs {r_min}"
        );
        // (6.8.13): d = J²/(m²ω_v²r₀³) to first order. The exact stretch solves
        // k d = J²/(m (r₀+d)³) ≈ (J²/(m r₀³))(1 − 3d/r₀): the first-order value is high by ≈ 3d²/r₀.
        let d = rotor.mode().stretch(j).unwrap();
        let d_closed = j * j / (M * M * W * W * R0.powi(3));
        assert!((d - d_closed).abs() < 1e-15 * d_closed);
        let dd = d - (r_min - R0);
        assert!(
            dd > 0.0 && dd < 4.0 * d * d / R0,
            "J={j}: {dd} vs 3d²/r₀ = {}",
            3.0 * d * d / R0
        );
        // (6.8.15): E = ½μ₀J² − J⁴/(2m³ω_v²r₀⁶) + O(J⁶).
        let e4 = rotor.effective_energy(j).unwrap();
        let t = -1.0 / (2.0 * M.powi(3) * W * W * R0.powi(6));
        assert!((e4 - (0.5 * mu0 * j * j + t * j.powi(4))).abs() < 1e-15 * e4);
        residual.push((j, e_min - e4));
    }
    // The quartic is the leading correction: the residual is O(J⁶) — halving J divides it by
    // 2⁶ = 64 (measured 63.7), and its coefficient is the hand expansion
    // μ′²μ″/(16k²) = 3/(2m⁵ω_v⁴r₀¹⁰) (1% at J = 0.025, where the O(J⁸) term is 0.2%).
    let ratio = residual[0].1 / residual[1].1;
    assert!(
        (ratio - 64.0).abs() < 0.01 * 64.0,
        "J⁶ scaling: ratio {ratio}"
    );
    let c6 = 3.0 / (2.0 * M.powi(5) * W.powi(4) * R0.powi(10));
    let (j, res) = residual[1];
    assert!(
        (res / j.powi(6) - c6).abs() < 0.01 * c6,
        "{} vs {c6}",
        res / j.powi(6)
    );
    println!("one-mass rotor: residual ratio J=0.05/0.025 = {ratio:.3} (J⁶: 64)");
}

#[test]
fn spring_rotor_errors_are_typed() {
    let rotor = SpringRotor::try_new(M, W, R0).unwrap();
    // (6.8.12) has no equilibrium once the rate reaches the spring frequency.
    assert_eq!(rotor.stretched_radius(W), Err(Error::InvalidArgument));
    assert_eq!(
        rotor.stretched_radius(-1.5 * W),
        Err(Error::InvalidArgument)
    );
    assert!(rotor.stretched_radius(0.99 * W).unwrap() > 40.0 * R0);
    assert_eq!(rotor.stretched_radius(f64::NAN), Err(Error::NonFinite));
    assert_eq!(
        rotor.equilibrium_radius(f64::INFINITY),
        Err(Error::NonFinite)
    );
    assert_eq!(rotor.energy(0.0, 0.0, 1.0), Err(Error::InvalidArgument));
    assert_eq!(
        SpringRotor::try_new(0.0, W, R0),
        Err(Error::InvalidArgument)
    );
    assert_eq!(SpringRotor::try_new(M, -W, R0), Err(Error::InvalidArgument));
    assert_eq!(SpringRotor::try_new(M, W, f64::NAN), Err(Error::NonFinite));
    assert_eq!(StretchMode::try_new(M, W, f64::NAN), Err(Error::NonFinite));
    assert_eq!(
        StretchMode::try_new(M, 0.0, -1.0),
        Err(Error::InvalidArgument)
    );
    // A huge momentum: many rest radii of stretch, still a root (no panic, no NaN).
    let r = rotor.equilibrium_radius(1e3).unwrap();
    let g = M * W * W * (r - R0) - 1e6 / (M * r.powi(3));
    assert!(g.abs() < 1e-9 * M * W * W * r, "{g}");
}

fn directions(a: Arrangement) -> Vec<V3> {
    let s = 1.0 / 3f64.sqrt();
    match a {
        Arrangement::Octahedral => vec![
            [1.0, 0.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
        ],
        Arrangement::Cubic => {
            let mut v = Vec::new();
            for a in [1.0, -1.0] {
                for b in [1.0, -1.0] {
                    for c in [1.0, -1.0] {
                        v.push([a * s, b * s, c * s]);
                    }
                }
            }
            v
        }
        Arrangement::Tetrahedral => vec![[s, s, s], [s, -s, -s], [-s, s, -s], [-s, -s, s]],
    }
}

/// `Σ ½k(ρ_j − r₀)² + ½ J·I(ρ)⁻¹·J` with `I(ρ) = Σ m(|p|²1 − p pᵀ)`, `p_j = ρ_j n̂_j`.
fn body_energy(dirs: &[V3], radii: &[f64], j: V3) -> f64 {
    let mut i: M3 = [[0.0; 3]; 3];
    let mut spring = 0.0;
    for (n, &rho) in dirs.iter().zip(radii) {
        let p = n.map(|c| c * rho);
        let p2 = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
        for a in 0..3 {
            for b in 0..3 {
                i[a][b] += M * (if a == b { p2 } else { 0.0 } - p[a] * p[b]);
            }
        }
        spring += 0.5 * M * W * W * (rho - R0).powi(2);
    }
    let inv = inverse(&i);
    let w: f64 = (0..3)
        .map(|a| (0..3).map(|b| j[a] * inv[a][b] * j[b]).sum::<f64>())
        .sum();
    spring + 0.5 * w
}

/// Coordinate descent with golden-section line searches: the radii and the minimum energy.
fn minimise(dirs: &[V3], j: V3) -> (Vec<f64>, f64) {
    let mut radii = vec![R0; dirs.len()];
    let mut e = body_energy(dirs, &radii, j);
    for _ in 0..60 {
        let mut moved: f64 = 0.0;
        for k in 0..dirs.len() {
            let f = |x: f64| {
                let mut r = radii.clone();
                r[k] = x;
                body_energy(dirs, &r, j)
            };
            let (x, fx) = golden(f, 0.9 * R0, 1.3 * R0);
            if fx <= e {
                moved = moved.max((x - radii[k]).abs());
                radii[k] = x;
                e = fx;
            }
        }
        if moved < 1e-12 {
            break;
        }
    }
    (radii, e)
}

fn unit(v: V3, len: f64) -> V3 {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| c / n * len)
}

fn t4_sum(j: V3) -> f64 {
    j.iter().map(|c| c.powi(4)).sum()
}

fn t22_sum(j: V3) -> f64 {
    let s = j.map(|c| c * c);
    s[0] * s[1] + s[0] * s[2] + s[1] * s[2]
}

fn positions(a: Arrangement) -> Vec<(f64, Vec3<f64>)> {
    directions(a)
        .iter()
        .map(|n| (M, Vec3::from_array(n.map(|c| c * R0))))
        .collect()
}

#[test]
fn symmetric_rotors_match_direct_minimisation_6_8_16_to_6_8_20() {
    let c = 1.0 / (M.powi(3) * W * W * R0.powi(6));
    // Hand-derived (module table): I₀ per axis, and the quartic −κ(|J|⁴ + T) with T = T⁽⁴⁾
    // (octahedron) or T⁽²²⁾ (cube, tetrahedron).
    let cases = [
        (Arrangement::Octahedral, 4.0 * M * R0 * R0, c / 256.0, true),
        (
            Arrangement::Cubic,
            16.0 / 3.0 * M * R0 * R0,
            9.0 * c / 4096.0,
            false,
        ),
        (
            Arrangement::Tetrahedral,
            8.0 / 3.0 * M * R0 * R0,
            9.0 * c / 512.0,
            false,
        ),
    ];
    for (arr, i0, kappa, octa) in cases {
        let rotor = SemiRigidRotor::try_symmetric(arr, M, W, R0).unwrap();
        let general = SemiRigidRotor::try_from_radial_springs(&positions(arr), W).unwrap();
        assert_eq!(rotor, general);
        let m = v64(rotor.rest_inertia().principal_moments());
        assert!(
            m.iter().all(|x| (x - i0).abs() < 1e-14 * i0),
            "{arr:?}: {m:?}"
        );
        // Closed forms, in the arrangement's natural basis.
        let basis = arr.natural_basis();
        let iso = rotor.isotropic(basis);
        assert!(
            (iso + kappa).abs() < 1e-12 * kappa,
            "{arr:?}: t₀ {iso} vs {}",
            -kappa
        );
        match (rotor.quartic(basis), octa) {
            (Quartic::Octahedral(t4), true) => assert!((t4 + kappa).abs() < 1e-12 * kappa),
            (Quartic::Cubic(t22), false) => assert!((t22 + kappa).abs() < 1e-12 * kappa),
            (q, _) => panic!("{arr:?}: natural basis gave {q:?}"),
        }
        // Both bases describe the same Hamiltonian (6.8.19): t₂₂ = −2t₄, t₀ adjusted.
        let q_o = rotor.quartic(QuarticBasis::Octahedral);
        let q_c = rotor.quartic(QuarticBasis::Cubic);
        let (Quartic::Octahedral(t4), Quartic::Cubic(t22)) = (q_o, q_c) else {
            panic!("bases")
        };
        assert!((t22 + 2.0 * t4).abs() <= 1e-15 * t4.abs());

        let mut res = Vec::new();
        let mut worst_rel: f64 = 0.0;
        for dir in [
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [1.0, 1.0, 1.0],
            [0.3, -0.5, 0.8],
        ] {
            let mut per_j = Vec::new();
            for len in [0.1, 0.05] {
                let j = unit(dir, len);
                let (radii, e_min) = minimise(&directions(arr), j);
                let e = rotor.energy(Vec3::from_array(j)).unwrap();
                let j2 = len * len;
                let aniso = if octa { t4_sum(j) } else { t22_sum(j) };
                let closed = j2 / (2.0 * i0) - kappa * (j2 * j2 + aniso);
                assert!(
                    (e - closed).abs() < 1e-14 * e,
                    "{arr:?} {dir:?}: {e} vs {closed}"
                );
                // Each body basis gives the same energy through BodyHamiltonian + t|J|⁴.
                for b in [QuarticBasis::Octahedral, QuarticBasis::Cubic] {
                    let h = rotor.try_body_hamiltonian(b).unwrap();
                    let e_b = h.energy(Vec3::from_array(j)) + rotor.isotropic(b) * j2 * j2;
                    assert!((e_b - e).abs() < 1e-15 * e, "{arr:?} {b:?}");
                }
                // The quartic carries the whole stretch energy to O(J²) relative: at |J| = 0.05
                // within 0.1% (measured ≤ 0.052%, tetrahedron).
                let quartic_min = e_min - j2 / (2.0 * i0);
                let quartic = e - j2 / (2.0 * i0);
                if len == 0.05 {
                    worst_rel = worst_rel.max((quartic_min / quartic - 1.0).abs());
                    assert!(
                        (quartic_min / quartic - 1.0).abs() < 1e-3,
                        "{arr:?} {dir:?}: {quartic_min} vs {quartic}"
                    );
                }
                // (6.8.17): the first-order stretches against the minimiser's radii; the
                // first-order value is high by O(d²/r₀) (as for one mass: ≈ 3d²/r₀).
                let mut d = vec![0.0; radii.len()];
                radial_stretches(&positions(arr), W, Vec3::from_array(j), &mut d).unwrap();
                let dmax = d.iter().fold(0.0f64, |a, x| a.max(x.abs()));
                for (dk, rk) in d.iter().zip(&radii) {
                    let diff = (dk - (rk - R0)).abs();
                    assert!(
                        diff < 4.0 * dmax * dmax / R0 + 1e-8,
                        "{arr:?} {dir:?}: {dk} vs {}",
                        rk - R0
                    );
                }
                per_j.push(e_min - e);
            }
            // Residual O(J⁶): halving |J| divides it by 64 (within 3%; measured ≤ 0.3%).
            let ratio = per_j[0] / per_j[1];
            assert!(
                (ratio - 64.0).abs() < 0.03 * 64.0,
                "{arr:?} {dir:?}: ratio {ratio}"
            );
            res.push(ratio);
        }
        println!(
            "{arr:?}: residual ratios |J| = 0.1/0.05 over four directions: {res:.3?}; \
             quartic vs minimised stretch energy at |J| = 0.05: {worst_rel:.1e}"
        );
        // Which axes are valleys, from the minimiser alone: octahedron (100), cube and
        // tetrahedron (111).
        let e100 = minimise(&directions(arr), unit([1.0, 0.0, 0.0], 0.1)).1;
        let e111 = minimise(&directions(arr), unit([1.0, 1.0, 1.0], 0.1)).1;
        assert_eq!(e100 < e111, octa, "{arr:?}: E(100) {e100} E(111) {e111}");
        assert_eq!(rotor.t4() < 0.0, octa);
    }
}

#[test]
fn f32_coefficients_match_closed_forms() {
    let c = 1.0 / (M.powi(3) * W * W * R0.powi(6));
    for (arr, kappa) in [
        (Arrangement::Octahedral, c / 256.0),
        (Arrangement::Cubic, 9.0 * c / 4096.0),
        (Arrangement::Tetrahedral, 9.0 * c / 512.0),
    ] {
        let r = SemiRigidRotor::try_symmetric(arr, M as f32, W as f32, R0 as f32).unwrap();
        let iso = r.isotropic(arr.natural_basis()) as f64;
        // f32: the inputs' rounding (≤ 6e-8 each, raised to the 6th power of r₀) and ~20 roundings.
        assert!(
            (iso + kappa).abs() < 2e-6 * kappa,
            "{arr:?}: {iso} vs {}",
            -kappa
        );
    }
}

#[test]
fn semi_rigid_errors_are_typed() {
    let mut pts = positions(Arrangement::Octahedral);
    assert!(SemiRigidRotor::try_from_radial_springs(&pts, W).is_ok());
    // One mass moved by 1e-3 of its radius along its rod: no longer cubic.
    pts[0].1 = pts[0].1.scale(1.001);
    assert_eq!(
        SemiRigidRotor::try_from_radial_springs(&pts, W),
        Err(Error::InvalidArgument)
    );
    // A cube rotated off the body axes: cubic, but not about these axes.
    let q = UnitQuat::try_from_axis_angle(Vec3::new(0.3, 0.2, 1.0), 0.4).unwrap();
    let rotated: Vec<(f64, Vec3<f64>)> = positions(Arrangement::Cubic)
        .iter()
        .map(|(m, r)| (*m, q.rotate(*r)))
        .collect();
    assert_eq!(
        SemiRigidRotor::try_from_radial_springs(&rotated, W),
        Err(Error::InvalidArgument)
    );
    let mut at_origin = positions(Arrangement::Octahedral);
    at_origin.push((M, Vec3::ZERO));
    assert_eq!(
        SemiRigidRotor::try_from_radial_springs(&at_origin, W),
        Err(Error::ZeroNorm)
    );
    assert_eq!(
        SemiRigidRotor::<f64>::try_from_radial_springs(&[], W),
        Err(Error::InvalidArgument)
    );
    assert_eq!(
        SemiRigidRotor::try_symmetric(Arrangement::Cubic, M, 0.0, R0),
        Err(Error::InvalidArgument)
    );
    assert_eq!(
        SemiRigidRotor::try_symmetric(Arrangement::Cubic, M, W, f64::NAN),
        Err(Error::NonFinite)
    );
    let pts = positions(Arrangement::Tetrahedral);
    let mut short = [0.0; 3];
    assert_eq!(
        radial_stretches(&pts, W, Vec3::X, &mut short),
        Err(Error::InvalidArgument)
    );
    let rotor = SemiRigidRotor::try_symmetric(Arrangement::Tetrahedral, M, W, R0).unwrap();
    assert_eq!(
        rotor.energy(Vec3::new(f64::NAN, 0.0, 0.0)),
        Err(Error::NonFinite)
    );
    // J = 0: no turn.
    let turn = rotor
        .isotropic_turn(QuarticBasis::Cubic, Vec3::ZERO, 10.0)
        .unwrap();
    assert_eq!(q64(turn), [1.0, 0.0, 0.0, 0.0]);
}

host_tests::per_type! {
    /// The "for a body" form (6.8.13)–(6.8.15): any stretch coordinate given ∂μ/∂r. With the spring
    /// rotor's ∂μ/∂r = −2/(m r₀³) it reproduces the rotor; the spring energy at the stretch is the
    /// loss. Relative tolerances: f64 1e-14, f32 4e-6 (a few f32 roundings of order-one ratios).
    #[test]
    fn stretch_mode_for_a_body_6_8_13_to_6_8_15() {
        let rel = T::per_type(4e-6, 1e-14);
        let dmu = T::from_f64(-2.0 / (M * R0.powi(3)));
        let mode = StretchMode::try_new(T::from_f64(M), T::from_f64(W), dmu).unwrap();
        let t = -1.0 / (2.0 * M.powi(3) * W * W * R0.powi(6));
        let got = mode.quartic_coefficient().to_f64();
        assert!((got - t).abs() < rel * t.abs(), "{got} vs {t}");
        let j = T::from_f64(0.05);
        let loss = mode.stretch_energy(j).unwrap().to_f64();
        assert!(
            (loss + t * 0.05f64.powi(4)).abs() < rel * loss,
            "½kd² = −tJ⁴"
        );
        // (6.8.14a): μ ≈ μ₀ + μ′d = μ₀ − μ′²J²/(2k).
        let mu0 = 1.0 / (M * R0 * R0);
        let mu = mode
            .stretched_inverse_inertia(T::from_f64(mu0), j)
            .unwrap()
            .to_f64();
        let want = mu0 - (2.0 / (M * R0.powi(3))).powi(2) * 0.0025 / (2.0 * M * W * W);
        assert!((mu - want).abs() < rel * want);
        let rotor = SpringRotor::try_new(T::from_f64(M), T::from_f64(W), T::from_f64(R0)).unwrap();
        assert!((rotor.mode().quartic_coefficient().to_f64() - t).abs() < rel * t.abs());
        let e = rotor.effective_energy(j).unwrap().to_f64();
        let e_mode = mode.effective_energy(T::from_f64(mu0), j).unwrap().to_f64();
        assert!((e - e_mode).abs() < rel * e);
        // The exact root in this type against the f64 minimiser.
        let (r_min, _) = golden(|r| planar_energy(r, 0.05), R0, 1.5 * R0);
        let r = rotor.equilibrium_radius(j).unwrap().to_f64();
        assert!((r - r_min).abs() < rel.max(1e-7) * R0, "{r} vs {r_min}");
    }

    /// The isotropic term as a Casimir turn, against an RK4 integration of the full Hamiltonian.
    /// A strongly distorted octahedron, so that the isotropic turn 4t|J|³·t is large: J = 1.2
    /// with m = ω_v = r₀ = 1 gives t₀ = t₄ = −1/256, turning 4·1.728/256·t ≈ 0.027 t rad.
    /// f64: Suzuki-4 at dt = 0.01 and the RK4 reference at 5e-4 agree to ~1e-9; f32: rounding
    /// of 2000 steps (~2000·6e-8).
    #[test]
    fn isotropic_term_is_a_casimir_turn() {
        let (tol_q, tol_j) = (T::per_type(3e-4, 1e-8), T::per_type(3e-4, 1e-8));
        let rotor =
            SemiRigidRotor::try_symmetric(Arrangement::Octahedral, T::ONE, T::ONE, T::ONE).unwrap();
        let j0 = [0.9, 0.7, 0.35];
        let q0 = [0.9, 0.1, -0.3, 0.2];
        let n = (q0.iter().map(|c| c * c).sum::<f64>()).sqrt();
        let q0 = q0.map(|c| c / n);
        let t_end = 20.0;
        // Reference: RK4 on the full Hamiltonian ½|J|²/4 + t₀|J|⁴ + t₄ΣJᵢ⁴, written as
        // (t₀ + t₄)ΣJᵢ⁴ + 2t₀ΣJᵢ²Jⱼ² (|J|⁴ = T⁽⁴⁾ + 2T⁽²²⁾).
        let (t0, t4) = (-1.0 / 256.0, -1.0 / 256.0);
        let model = RefModel {
            moments: [4.0; 3],
            spin: [0.0; 3],
            t4: t0 + t4,
            t22: 2.0 * t0,
        };
        let (r_ref, j_ref) = lie_poisson_rk4(&model, &quat_matrix(q0), j0, t_end, 40_000);
        for basis in [QuarticBasis::Octahedral, QuarticBasis::Cubic] {
            let body = Gyrostat::from(rotor.try_body_hamiltonian(basis).unwrap());
            let mut s = State::new(unit_quat::<T>(q0), vec3(j0));
            let steps = 2000;
            let dt = T::from_f64(t_end / steps as f64);
            for _ in 0..steps {
                s = body.step(Integrator::Suzuki4, &s, dt).unwrap();
            }
            let full = s.attitude
                * rotor
                    .isotropic_turn(basis, s.momentum, T::from_f64(t_end))
                    .unwrap();
            let dq = mat_dist(&quat_matrix(q64(full)), &r_ref);
            let dj = vec_dist(&v64(s.momentum), &j_ref);
            assert!(dq < tol_q, "{basis:?}: attitude {dq:e}");
            assert!(dj < tol_j, "{basis:?}: momentum {dj:e}");
            // Without the turn the attitude is off by the isotropic rotation (~0.5 rad here).
            let dq_without = mat_dist(&quat_matrix(q64(s.attitude)), &r_ref);
            assert!(dq_without > 100.0 * tol_q, "{basis:?}: {dq_without:e}");
        }
    }
}
