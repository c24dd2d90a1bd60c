//! Inertia validation and the principal-axis decomposition against an independent computation.

use gyrostat::dynamics::inertia::{Inertia, symmetric_eigen};
use gyrostat::{Error, Mat3, UnitQuat, Vec3};
use host_tests::cast::mat3;
use host_tests::ref_dynamics::{sym_eigenvalues, sym_eigenvector};
use host_tests::reference::{M3, cross, mat_mul, norm, rodrigues, transpose};
use host_tests::tolerance::Tolerance;
use proptest::prelude::*;

/// A physical tensor `R diag(λ) Rᵀ` with λ from the box-inertia formula (so the triangle
/// inequality holds), rotated by the Rodrigues reference.
fn rotated_box(a: f64, b: f64, c: f64, axis: [f64; 3], angle: f64) -> M3 {
    let l = [b * b + c * c, a * a + c * c, a * a + b * b];
    let r = rodrigues(axis, angle);
    let d = [[l[0], 0.0, 0.0], [0.0, l[1], 0.0], [0.0, 0.0, l[2]]];
    mat_mul(&mat_mul(&r, &d), &transpose(&r))
}

/// Rotated boxes with sides in [0.5, 2] and any orientation.
fn rotated_boxes() -> impl Strategy<Value = M3> {
    (
        (0.5f64..2.0, 0.5f64..2.0, 0.5f64..2.0),
        (-1.0f64..1.0, -1.0f64..1.0, 0.1f64..1.0, -3.0f64..3.0),
    )
        .prop_map(|((a, b, c), (ax, ay, az, angle))| rotated_box(a, b, c, [ax, ay, az], angle))
}

/// Eigenvalues and eigenvectors against the trigonometric reference (Smith 1961).
///
/// Tolerances (relative to the largest moment): eigenvalues f32 4e-6 (Jacobi rounding ≈ a few
/// ε·‖I‖ with ε = 1.2e-7, plus the f32 rounding of the input entries), f64 1e-13. Eigenvectors
/// depend on the gap: we require moments separated by ≥ 5 % and allow the vector error
/// ε·‖I‖/gap ×  a factor 20 (f32 2e-5·(λmax/gap), f64 5e-14·(λmax/gap)).
fn check_eigen<T: Tolerance>(a: &M3) {
    let (tol_val, tol_vec) = (T::per_type(4e-6, 1e-13), T::per_type(2e-5, 5e-14));
    let (vals, vecs) = symmetric_eigen(&mat3::<T>(a));
    let mut got: Vec<(f64, [f64; 3])> = (0..3)
        .map(|i| {
            let c = vecs.col(i);
            (
                vals.to_array()[i].to_f64(),
                [c.x.to_f64(), c.y.to_f64(), c.z.to_f64()],
            )
        })
        .collect();
    got.sort_by(|x, y| x.0.total_cmp(&y.0));
    let want = sym_eigenvalues(a);
    let scale = want[2];
    let gap = (want[1] - want[0]).min(want[2] - want[1]);
    for i in 0..3 {
        assert!(
            (got[i].0 - want[i]).abs() <= tol_val * scale,
            "eigenvalue {i}: {} vs {}",
            got[i].0,
            want[i]
        );
        let v = sym_eigenvector(a, want[i]);
        // Same line (the sign is free): |v × v_got| = sin of the angle between them.
        let err = norm(cross(v, got[i].1));
        assert!(err <= tol_vec * scale / gap, "eigenvector {i}: {err}");
    }
    // Proper rotation.
    assert!((vecs.determinant().to_f64() - 1.0).abs() < 10.0 * tol_val);
}

host_tests::per_type! {
    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]
        #[test]
        fn eigen_matches_reference(t in rotated_boxes()) {
            let l = sym_eigenvalues(&t);
            prop_assume!((l[1] - l[0]).min(l[2] - l[1]) > 0.05 * l[2]);
            check_eigen::<T>(&t);
        }
    }

    /// Bad tensors, masses and axes give typed errors.
    #[test]
    fn validation_errors_are_typed() {
        let v = |a: f64, b: f64, c: f64| Vec3::new(T::from_f64(a), T::from_f64(b), T::from_f64(c));
        let np = Err(Error::NonPhysicalInertia);
        // Triangle inequality I_a ≤ I_b + I_c violated.
        assert_eq!(
            Inertia::try_from_principal(v(8.0, 4.0, 3.0)).map(|_| ()),
            np
        );
        // Flat lamina: equality is physical.
        assert!(Inertia::try_from_principal(v(1.0, 2.0, 3.0)).is_ok());
        // Thin rod (zero moment) and negative moment: not positive definite.
        assert_eq!(
            Inertia::try_from_principal(v(1.0, 1.0, 0.0)).map(|_| ()),
            np
        );
        assert_eq!(
            Inertia::try_from_principal(v(-1.0, 1.0, 1.0)).map(|_| ()),
            np
        );
        // Indefinite with positive diagonal (off-diagonal too large).
        let r = Inertia::try_from_components(v(1.0, 1.0, 1.0), v(0.9, 0.9, 0.9));
        assert_eq!(r.map(|_| ()), np);
        // Non-symmetric.
        let t = Mat3::from_rows(
            [T::from_f64(2.0), T::from_f64(0.1), T::ZERO],
            [T::ZERO, T::from_f64(2.0), T::ZERO],
            [T::ZERO, T::ZERO, T::from_f64(2.0)],
        );
        assert_eq!(Inertia::try_from_tensor(t).map(|_| ()), np);
        // Non-finite.
        let nan = T::from_f64(f64::NAN);
        assert_eq!(
            Inertia::try_from_principal(Vec3::new(nan, T::ONE, T::ONE)).map(|_| ()),
            Err(Error::NonFinite)
        );
        assert_eq!(
            Inertia::try_from_components(
                v(1.0, 1.0, 1.0),
                Vec3::new(T::ZERO, T::from_f64(f64::INFINITY), T::ZERO)
            )
            .map(|_| ()),
            Err(Error::NonFinite)
        );
        // Radius of gyration: bad masses.
        let i = Inertia::try_from_principal(v(2.0, 3.0, 4.0)).unwrap();
        assert_eq!(i.radii_of_gyration(T::ZERO), Err(Error::InvalidArgument));
        assert_eq!(i.radii_of_gyration(nan), Err(Error::NonFinite));
        assert_eq!(
            i.radius_of_gyration_about(Vec3::ZERO, T::ONE),
            Err(Error::ZeroNorm)
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]
    #[test]
    fn inertia_reconstructs_and_inverts(t in rotated_boxes()) {
        let i = Inertia::<f64>::try_from_tensor(mat3(&t)).unwrap();
        // I = R(P) diag(λ) R(P)ᵀ with R(P) from the principal quaternion.
        let p = i.principal_rotation();
        let r = p.to_rotation_matrix();
        let back = r * Mat3::from_diagonal(i.principal_moments()) * r.transpose();
        prop_assert!((back - mat3(&t)).max_abs() < 1e-13 * 8.0);
        let id = i.inverse() * i.tensor();
        prop_assert!((id - Mat3::IDENTITY).max_abs() < 1e-13);
        // ω = I⁻¹(Iω) round trip.
        let w = Vec3::new(0.3, -1.2, 0.7);
        prop_assert!((i.solve(i.mul_vec(w)) - w).norm() < 1e-13);
    }
}

/// Solid box of mass M and sides (a, b, c): I₁ = M(b² + c²)/12, so k₁ = √((b² + c²)/12).
#[test]
fn radius_of_gyration_of_a_box() {
    let (m, a, b, c) = (3.0f64, 1.0, 2.0, 0.5);
    let moments = Vec3::new(
        m * (b * b + c * c) / 12.0,
        m * (a * a + c * c) / 12.0,
        m * (a * a + b * b) / 12.0,
    );
    let i = Inertia::try_from_principal(moments).unwrap();
    let k = i.radii_of_gyration(m).unwrap();
    assert!((k.x - ((b * b + c * c) / 12.0f64).sqrt()).abs() < 1e-15);
    assert!((k.z - ((a * a + b * b) / 12.0f64).sqrt()).abs() < 1e-15);
    // About the body diagonal direction (1,1,0)/√2: k² = (I₁ + I₂)/(2M).
    let kd = i
        .radius_of_gyration_about(Vec3::new(1.0, 1.0, 0.0), m)
        .unwrap();
    assert!((kd * kd - (moments.x + moments.y) / (2.0 * m)).abs() < 1e-15);
}

/// A diagonal tensor keeps the body axes: the principal rotation is the identity exactly, and a
/// rotated one recovers the rotation (up to the axis order and signs, compared on the tensor).
#[test]
fn principal_rotation_of_rotated_body() {
    let q = UnitQuat::try_from_axis_angle(Vec3::new(0.2f64, -0.4, 1.0), 0.7).unwrap();
    let r = q.to_rotation_matrix();
    let d = Mat3::from_diagonal(Vec3::new(3.0, 4.0, 5.0));
    let i = Inertia::try_from_tensor(r * d * r.transpose()).unwrap();
    assert!(!i.is_diagonal());
    // In the principal frame the tensor is diagonal: Pᵀ I P.
    let p = i.principal_rotation().to_rotation_matrix();
    let dp = p.transpose() * i.tensor() * p;
    let off = dp.m[0][1].abs() + dp.m[0][2].abs() + dp.m[1][2].abs();
    assert!(off < 1e-14, "off-diagonal {off}");
    let di = Inertia::try_from_principal(Vec3::new(3.0f32, 4.0, 5.0)).unwrap();
    assert_eq!(di.principal_rotation(), UnitQuat::IDENTITY);
}
