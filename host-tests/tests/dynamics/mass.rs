//! Mass properties (`gyrostat::dynamics::mass`) against the seed's worked examples and direct
//! computations.

use gyrostat::dynamics::mass::{
    impulse_response, inertia_from_point_masses, parallel_axis_shift, percussion_radius,
    radius_of_gyration, total_mass_and_center,
};
use gyrostat::{Error, Mat3, Vec3};

#[test]
fn bent_axle_6_5_6() {
    // One mass m at r(1/√2, 1/√2, 0): I = m r² [[½, −½, 0], [−½, ½, 0], [0, 0, 1]] and
    // L = I (0, ω, 0) = m r² ω (−½, ½, 0) (6.5.6).
    let (m, r, w) = (1.5f64, 0.8f64, 3.0f64);
    let s = r / 2f64.sqrt();
    let i = inertia_from_point_masses(&[(m, Vec3::new(s, s, 0.0))]).unwrap();
    let mr2 = m * r * r;
    let want = [[0.5, -0.5, 0.0], [-0.5, 0.5, 0.0], [0.0, 0.0, 1.0]];
    for (row, wrow) in i.m.iter().zip(want.iter()) {
        for (x, y) in row.iter().zip(wrow.iter()) {
            assert!((x - mr2 * y).abs() < 1e-15, "{i:?}");
        }
    }
    let l = i * Vec3::new(0.0, w, 0.0);
    assert!(
        (l.x + 0.5 * mr2 * w).abs() < 1e-15 && (l.y - 0.5 * mr2 * w).abs() < 1e-15 && l.z == 0.0
    );
    // f32
    let s32 = s as f32;
    let i32m = inertia_from_point_masses(&[(1.5f32, Vec3::new(s32, s32, 0.0))]).unwrap();
    assert!((i32m.m[0][1] as f64 + 0.5 * mr2).abs() < 1e-6);
}

fn cloud() -> Vec<(f64, Vec3<f64>)> {
    (0..17)
        .map(|k| {
            let t = k as f64;
            (
                0.5 + (0.37 * t).sin().abs(),
                Vec3::new(
                    (1.1 * t).cos() + 0.4,
                    (0.7 * t).sin() - 0.2,
                    (0.3 * t).cos() * 1.3 + 0.9,
                ),
            )
        })
        .collect()
}

#[test]
fn parallel_axis_6_5_15() {
    let pts = cloud();
    let (m, c) = total_mass_and_center(&pts).unwrap();
    // Independent centre of mass and inertia about the CM by direct sums.
    let msum: f64 = pts.iter().map(|p| p.0).sum();
    assert!((m - msum).abs() < 1e-14);
    let shifted: Vec<(f64, Vec3<f64>)> = pts.iter().map(|(mm, r)| (*mm, *r - c)).collect();
    let i_cm = inertia_from_point_masses(&shifted).unwrap();
    let i_origin = inertia_from_point_masses(&pts).unwrap();
    let via_theorem = parallel_axis_shift(&i_cm, m, c).unwrap();
    for r in 0..3 {
        for k in 0..3 {
            assert!(
                (via_theorem.m[r][k] - i_origin.m[r][k]).abs() < 1e-13,
                "{r}{k}"
            );
        }
    }
    // Direct element check of (6.5.5b): I_xx = Σ m (y² + z²), I_xy = −Σ m x y.
    let ixx: f64 = pts.iter().map(|(mm, r)| mm * (r.y * r.y + r.z * r.z)).sum();
    let ixy: f64 = pts.iter().map(|(mm, r)| -mm * r.x * r.y).sum();
    assert!((i_origin.m[0][0] - ixx).abs() < 1e-13 && (i_origin.m[0][1] - ixy).abs() < 1e-13);
    assert!(i_origin.m[1][0] == i_origin.m[0][1]);
}

#[test]
fn stick_gyration_impulse_percussion_6_4() {
    // A stick of length 2ℓ, mass M, as N equal masses at the midpoints of N cells along x:
    // Σ xᵢ² = N·ℓ²(1/3 − 1/(3N²)), so I_yy = M ℓ² (1 − 1/N²)/3 → Mℓ²/3 (6.4.15a).
    let (mass, ell, n) = (2.0f64, 0.6f64, 400usize);
    let pts: Vec<(f64, Vec3<f64>)> = (0..n)
        .map(|k| {
            (
                mass / n as f64,
                Vec3::new(-ell + (2 * k + 1) as f64 * ell / n as f64, 0.0, 0.0),
            )
        })
        .collect();
    let i = inertia_from_point_masses(&pts).unwrap();
    let want = mass * ell * ell * (1.0 - 1.0 / (n * n) as f64) / 3.0;
    assert!((i.m[1][1] - want).abs() < 1e-14);
    // Radius of gyration ℓ/√3 for I = Mℓ²/3 (6.4.18)–(6.4.19).
    let rg = radius_of_gyration(mass * ell * ell / 3.0, mass).unwrap();
    assert!((rg - ell / 3f64.sqrt()).abs() < 1e-15);
    // Hammer hit Π ê_y at h along the stick: ΔV = Π/M (6.4.12), ω = 3hΠ/(Mℓ²) about z (6.4.15b).
    let stick = Mat3::from_diagonal(Vec3::new(
        1e-3,
        mass * ell * ell / 3.0,
        mass * ell * ell / 3.0,
    ));
    let (h, pi) = (0.45f64, 0.8f64);
    let resp = impulse_response(
        &stick,
        mass,
        Vec3::new(h, 0.0, 0.0),
        Vec3::new(0.0, pi, 0.0),
    )
    .unwrap();
    assert!((resp.delta_velocity.y - pi / mass).abs() < 1e-16);
    assert!((resp.delta_omega.z - 3.0 * h * pi / (mass * ell * ell)).abs() < 1e-14);
    assert!((resp.angular_impulse.z - h * pi).abs() < 1e-16); // Λ = hΠ (6.4.14)
    // Sweet spot p = ℓ²/(3h) (6.4.17): h = ℓ → p = ℓ/3; the point −p is momentarily at rest.
    let p = percussion_radius(rg, ell).unwrap();
    assert!((p - ell / 3.0).abs() < 1e-15);
    let p = percussion_radius(rg, h).unwrap();
    let v_at = resp.delta_velocity.y + resp.delta_omega.z * (-p); // v = V + ω × r, r = −p x̂
    assert!(v_at.abs() < 1e-14, "{v_at}");
}

#[test]
fn errors_are_typed() {
    assert_eq!(
        inertia_from_point_masses::<f64>(&[]),
        Err(Error::InvalidArgument)
    );
    assert_eq!(
        inertia_from_point_masses(&[(-1.0f64, Vec3::X)]),
        Err(Error::InvalidArgument)
    );
    assert_eq!(
        inertia_from_point_masses(&[(1.0f32, Vec3::new(f32::NAN, 0.0, 0.0))]),
        Err(Error::NonFinite)
    );
    assert_eq!(
        total_mass_and_center(&[(0.0f64, Vec3::X)]),
        Err(Error::InvalidArgument)
    );
    assert_eq!(radius_of_gyration(1.0f64, 0.0), Err(Error::InvalidArgument));
    assert_eq!(percussion_radius(1.0f64, 0.0), Err(Error::InvalidArgument));
    assert_eq!(
        impulse_response(&Mat3::<f64>::ZERO, 1.0, Vec3::X, Vec3::Y).unwrap_err(),
        Error::Singular
    );
    assert_eq!(
        impulse_response(&Mat3::<f64>::IDENTITY, 0.0, Vec3::X, Vec3::Y).unwrap_err(),
        Error::InvalidArgument
    );
    assert_eq!(
        parallel_axis_shift(&Mat3::<f64>::IDENTITY, -1.0, Vec3::X),
        Err(Error::InvalidArgument)
    );
}
