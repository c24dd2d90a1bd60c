//! The seed's closed forms (`gyrostat::dynamics::closed_form::analysis`) against the seed's worked values and
//! independent computations (direct sums, RK4 integration of Euler's equations).

use gyrostat::dynamics::Inertia;
use gyrostat::dynamics::closed_form::analysis::{
    SmallMotionKind, constant_energy_radius, direction, gyro_multipoles, rotational_energy,
    separatrix_angle, small_motion, symmetric_top_rates,
};
use gyrostat::{Axis, Error, Real, Vec3};
use host_tests::ref_exact::{self, RigidState};

/// The validated inertia `diag(i1, i2, i3)`.
fn principal<T: Real>(i1: T, i2: T, i3: T) -> Inertia<T> {
    Inertia::try_from_principal(Vec3::new(i1, i2, i3)).unwrap()
}

fn deg(x: f64) -> f64 {
    x.to_degrees()
}

#[test]
fn separatrix_seed_values_6_8_10() {
    // (6.8.10), Fig. 6.8.1: (6, 4, 3) → γ_B = ±45°.
    let g = separatrix_angle(&principal(6.0f64, 4.0, 3.0)).unwrap();
    assert!((deg(g) - 45.0).abs() < 1e-12, "{}", deg(g));
    let g32 = separatrix_angle(&principal(6.0f32, 4.0, 3.0)).unwrap();
    assert!((deg(g32 as f64) - 45.0).abs() < 1e-5);
    // Fig. 6.8.2 (b), (c): I₂ = 5.0 → 63.4°, I₂ = 3.2 → 20.7° (seed's rounding to 0.1°).
    for (i2, want) in [(5.0, 63.4), (3.2, 20.7)] {
        let g = deg(separatrix_angle(&principal(6.0f64, i2, 3.0)).unwrap());
        assert!((g - want).abs() <= 0.05, "I₂ = {i2}: {g}");
        let g32 = deg(separatrix_angle(&principal(6.0f32, i2 as f32, 3.0)).unwrap() as f64);
        assert!((g32 - want).abs() <= 0.05);
    }
    // Fig. 6.8.2 (a) prints I₂ = 5.6 → 75.5°, but (6.8.10) gives tan²γ_B = 2·2.6/0.4 = 13,
    // γ_B = 74.50°. We assert the formula's value and record the seed's misprint: 75.5° belongs
    // to I₂ ≈ 5.646.
    let g = deg(separatrix_angle(&principal(6.0f64, 5.6, 3.0)).unwrap());
    assert!((g - 13f64.sqrt().atan().to_degrees()).abs() < 1e-12);
    assert!((g - 74.5).abs() <= 0.05, "{g}");
    let g = deg(separatrix_angle(&principal(6.0f64, 5.646, 3.0)).unwrap());
    assert!((g - 75.5).abs() <= 0.05, "{g}");
    // Either ordering of the extremes works; I₂ must be intermediate.
    let a = separatrix_angle(&principal(3.0f64, 4.0, 6.0)).unwrap();
    assert!(a > 0.0 && a < core::f64::consts::FRAC_PI_2);
    assert_eq!(
        separatrix_angle(&principal(4.0f64, 6.0, 3.0)),
        Err(Error::InvalidArgument)
    );
    assert_eq!(
        separatrix_angle(&principal(6.0f64, 6.0, 3.0)),
        Err(Error::InvalidArgument)
    );
    // (1, 4, 6) violates the triangle inequality: rejected when the inertia is built.
    assert_eq!(
        Inertia::try_from_principal(Vec3::new(1.0f64, 4.0, 6.0)),
        Err(Error::NonPhysicalInertia)
    );
}

#[test]
fn separatrix_is_the_saddle_energy_contour() {
    // Independent check of (6.8.9)–(6.8.10): every direction in the plane containing the I₂ axis
    // at azimuth γ_B (from the I₃ axis towards I₁) has E = J²/(2I₂), by a direct sum.
    for i2 in [3.2, 4.0, 5.0, 5.6] {
        let (i1, i3) = (6.0f64, 3.0f64);
        let g = separatrix_angle(&principal(i1, i2, i3)).unwrap();
        for k in 0..=12 {
            let b = k as f64 * core::f64::consts::PI / 12.0;
            let j = [g.sin() * b.sin(), b.cos(), g.cos() * b.sin()];
            let e = j[0] * j[0] / (2.0 * i1) + j[1] * j[1] / (2.0 * i2) + j[2] * j[2] / (2.0 * i3);
            assert!((e - 1.0 / (2.0 * i2)).abs() < 1e-15, "I₂={i2}, β={b}: {e}");
        }
    }
}

#[test]
fn energy_surfaces_6_8_7_and_6_8_8() {
    let i = &principal(6.0f64, 4.0, 3.0);
    for kb in 0..=8 {
        for kg in 0..=16 {
            let (b, g) = (kb as f64 * 0.4, kg as f64 * 0.4);
            // Direct sum with the seed's direction (−cos γ sin β, sin γ sin β, cos β).
            let d = [-g.cos() * b.sin(), g.sin() * b.sin(), b.cos()];
            let jm = 2.5;
            let e_direct = jm * jm * (d[0] * d[0] / 12.0 + d[1] * d[1] / 8.0 + d[2] * d[2] / 6.0);
            let e = rotational_energy(i, jm, b, g).unwrap();
            assert!((e - e_direct).abs() < 1e-15 * e_direct.max(1.0));
            // The CES radius at that energy recovers |J|.
            let r = constant_energy_radius(i, e, b, g).unwrap();
            assert!((r - jm).abs() < 1e-14);
            let dv = direction(b, g);
            assert!((dv.x - d[0]).abs() < 1e-15 && (dv.y - d[1]).abs() < 1e-15);
        }
    }
    // The RES extremes lie on the principal axes: min on the I₁ = 6 axis, max on I₃ = 3.
    let e_min = rotational_energy(i, 1.0, core::f64::consts::FRAC_PI_2, 0.0).unwrap();
    let e_max = rotational_energy(i, 1.0, 0.0, 0.0).unwrap();
    assert!((e_min - 1.0 / 12.0).abs() < 1e-16 && (e_max - 1.0 / 6.0).abs() < 1e-16);
    assert_eq!(
        constant_energy_radius(i, -1.0, 0.0, 0.0),
        Err(Error::InvalidArgument)
    );
    assert_eq!(
        rotational_energy(i, f64::NAN, 0.0, 0.0),
        Err(Error::NonFinite)
    );
}

#[test]
fn symmetric_top_rates_6_7_39_to_43() {
    // Fig. 6.7.5 worked cases: very prolate I_II = 9 I₃ → γ̇ = 8 α̇ cos β = (8/9) ω₃;
    // most oblate I_II = I₃/2 → γ̇ = −½ α̇ cos β = −ω₃.
    let (j, beta) = (2.0f64, 0.6f64);
    let p = symmetric_top_rates(&principal(9.0, 9.0, 1.0), j, beta).unwrap();
    assert!((p.body_precession - 8.0 * p.lab_precession * beta.cos()).abs() < 1e-14);
    assert!((p.body_precession - 8.0 / 9.0 * p.axial_rate).abs() < 1e-14);
    let o = symmetric_top_rates(&principal(1.0, 1.0, 2.0), j, beta).unwrap();
    assert!((o.body_precession + 0.5 * o.lab_precession * beta.cos()).abs() < 1e-15);
    assert!((o.body_precession + o.axial_rate).abs() < 1e-15);
    // (6.7.43a) α̇ = J/I_II, (6.7.43c) ω₃ = J cos β / I₃.
    assert!(
        (p.lab_precession - j / 9.0).abs() < 1e-16 && (p.axial_rate - j * beta.cos()).abs() < 1e-15
    );
    // (6.7.42b): ω_body = I⁻¹ J_body with J_body = J(−sin β, 0, cos β) (6.7.40 at γ = 0).
    let (it, ia) = (3.0f64, 1.7f64);
    let r = symmetric_top_rates(&principal(it, it, ia), j, beta).unwrap();
    let w = [-j * beta.sin() / it, 0.0, j * beta.cos() / ia];
    assert!((r.omega_body.x - w[0]).abs() < 1e-15 && (r.omega_body.z - w[2]).abs() < 1e-15);
    // (6.7.42a): ω_lab = R_y(β) ω_body.
    let wl = [
        beta.cos() * w[0] + beta.sin() * w[2],
        0.0,
        -beta.sin() * w[0] + beta.cos() * w[2],
    ];
    assert!((r.omega_lab.x - wl[0]).abs() < 1e-15 && (r.omega_lab.z - wl[2]).abs() < 1e-15);
    // (6.7.39) against integration: the body sees J turn about the symmetry axis at −γ̇.
    let s0 = RigidState {
        j: [-j * beta.sin(), 0.0, j * beta.cos()],
        q: [1.0, 0.0, 0.0, 0.0],
    };
    let t = 3.0;
    let s = ref_exact::integrate_rigid([it, it, ia], s0, &[t], 1e-4)[0];
    let turned = s.j[1].atan2(s.j[0]) - s0.j[1].atan2(s0.j[0]);
    let turned = (turned + core::f64::consts::PI).rem_euclid(2.0 * core::f64::consts::PI)
        - core::f64::consts::PI;
    assert!(
        (turned + r.body_precession * t).abs() < 1e-10,
        "{turned} vs {}",
        -r.body_precession * t
    );
    // I₃ > 2 I_II is not a body; unequal transverse moments are not a symmetric top.
    assert!(Inertia::try_from_principal(Vec3::new(1.0f64, 1.0, 2.5)).is_err());
    assert_eq!(
        symmetric_top_rates(&principal(3.0f64, 3.1, 1.7), 1.0, 0.0),
        Err(Error::InvalidArgument)
    );
    // f32
    let r32 = symmetric_top_rates(&principal(3.0f32, 3.0f32, 1.7), 2.0, 0.6).unwrap();
    assert!((r32.body_precession as f64 - r.body_precession).abs() < 1e-6);
}

#[test]
fn small_motion_rates_6_8_6() {
    // Measured from RK4: perturb J off each axis by 1e-6 and time the oscillation or growth.
    let inertia = [6.0, 4.0, 3.0];
    let jm = 2.0;
    let iv = &principal(6.0f64, 4.0, 3.0);
    // Axis 2 (I₃ = 3, minimum): oscillation (6.8.6a); axis 0 (I₁ = 6, maximum): (6.8.6b).
    for (axis, other) in [(Axis::Z, 0usize), (Axis::X, 2)] {
        let sm = small_motion(iv, jm, axis).unwrap();
        assert_eq!(sm.kind, SmallMotionKind::Oscillation);
        let mut j0 = [0.0; 3];
        j0[axis.index()] = jm;
        j0[other] = 1e-6;
        let s0 = RigidState {
            j: j0,
            q: [1.0, 0.0, 0.0, 0.0],
        };
        let period_guess = 2.0 * core::f64::consts::PI / sm.rate;
        let (half, n) =
            ref_exact::measured_sign_change_interval(inertia, s0, other, 6.0 * period_guess, 1e-3);
        assert!(n >= 4);
        let measured = core::f64::consts::PI / half;
        assert!(
            (measured - sm.rate).abs() < 1e-8 * sm.rate,
            "axis {axis:?}: {measured} vs {}",
            sm.rate
        );
    }
    // Axis 1 (intermediate): divergence (6.8.6c); growth rate of the perturbation.
    let sm = small_motion(iv, jm, Axis::Y).unwrap();
    assert_eq!(sm.kind, SmallMotionKind::Divergence);
    // Start on the unstable eigendirection is unknown; measure the asymptotic growth of |J⊥|.
    let s0 = RigidState {
        j: [1e-9, jm, 1e-9],
        q: [1.0, 0.0, 0.0, 0.0],
    };
    let (t1, t2) = (4.0 / sm.rate, 8.0 / sm.rate);
    let st = ref_exact::integrate_rigid(inertia, s0, &[t1, t2], 1e-3);
    let perp = |s: &RigidState| (s.j[0] * s.j[0] + s.j[2] * s.j[2]).sqrt();
    let measured = (perp(&st[1]) / perp(&st[0])).ln() / (t2 - t1);
    assert!(
        (measured - sm.rate).abs() < 1e-4 * sm.rate,
        "{measured} vs {}",
        sm.rate
    );
    // Seed's closed forms with (I₁, I₂, I₃) = (6, 4, 3).
    let om_z = jm / 3.0 * ((6.0 - 3.0) * (4.0 - 3.0) / (6.0 * 4.0f64)).sqrt();
    let om_x = jm / 6.0 * ((6.0 - 4.0) * (6.0 - 3.0) / (4.0 * 3.0f64)).sqrt();
    let xi_y = jm / 4.0 * ((6.0 - 4.0) * (4.0 - 3.0) / (6.0 * 3.0f64)).sqrt();
    assert!((small_motion(iv, jm, Axis::Z).unwrap().rate - om_z).abs() < 1e-15);
    assert!((small_motion(iv, jm, Axis::X).unwrap().rate - om_x).abs() < 1e-15);
    assert!((small_motion(iv, jm, Axis::Y).unwrap().rate - xi_y).abs() < 1e-15);
    let sym = small_motion(&principal(4.0f64, 4.0, 3.0), jm, Axis::X).unwrap();
    assert_eq!(sym.kind, SmallMotionKind::Neutral);
}

#[test]
fn gyro_multipoles_6_9_4_reproduce_hamiltonian() {
    let i = &principal(5.0f64, 3.0, 2.5);
    let s = Vec3::new(0.3, -0.7, 1.1);
    let mp = gyro_multipoles(i, s).unwrap();
    let (a, b, c) = (0.1, 1.0 / 6.0, 0.2);
    // (6.9.4): M₀ = A + B + C, D = −2(A S_x, B S_y, C S_z), Q_zz = (2C − A − B)/6, Q = (A − B)/2.
    assert!((mp.monopole - (a + b + c)).abs() < 1e-16);
    assert!(
        (mp.dipole.x + 2.0 * a * s.x).abs() < 1e-16 && (mp.dipole.z + 2.0 * c * s.z).abs() < 1e-16
    );
    assert!((mp.q_zz - (2.0 * c - a - b) / 6.0).abs() < 1e-16);
    assert!((mp.q_x2_y2 - (a - b) / 2.0).abs() < 1e-16);
    // The expansion reproduces H = Σ Aᵢ (Jᵢ − Sᵢ)² (6.9.2b) everywhere.
    for k in 0..50 {
        let t = k as f64 * 0.7;
        let j = Vec3::new(t.sin() * 2.0, (1.3 * t).cos() * 1.5, (0.4 * t).sin() - 0.2);
        let h = a * (j.x - s.x).powi(2) + b * (j.y - s.y).powi(2) + c * (j.z - s.z).powi(2);
        assert!(
            (mp.evaluate(j) - h).abs() < 1e-14,
            "{} vs {h}",
            mp.evaluate(j)
        );
    }
    // Spherical rotor: both quadrupoles vanish (the gyro-RES of Fig. 6.9.2 is pure monopole + dipole).
    let sph = gyro_multipoles(&principal(2.0f64, 2.0, 2.0), s).unwrap();
    assert!(sph.q_zz == 0.0 && sph.q_x2_y2 == 0.0);
    assert_eq!(
        Inertia::try_from_principal(Vec3::new(1.0f64, 1.0, 3.0)),
        Err(Error::NonPhysicalInertia)
    );
}
