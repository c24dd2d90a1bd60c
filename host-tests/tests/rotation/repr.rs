//! Representations and their conversions against the independent matrix reference; the seed's
//! worked formulas (6.6.10b), (6.6.14–15), (6.6.16a–c) and the magic angle; the double cover
//! algebra (canonicalisation, geodesic angle, similarity transform, slerp, nlerp); property-based
//! round trips through every representation in f32 and f64.
#![allow(clippy::needless_range_loop)] // 3×3 index loops read like the formulas

use gyrostat::rotation::{
    AxisAngle, Dcm, Euler, EulerSequence, Gibbs, GimbalPolicy, Mrp, PolarAxisAngle, RotationVector,
};
use gyrostat::{Error, Mat3, Quat, Real, Su2, UnitQuat, Vec3};
use host_tests::cast::{m64, q64, unit_quat, v64};
use host_tests::ref_rotation::{
    all_sequences, euler_matrix, gibbs_matrix, mrp_matrix, rot_dist, rotvec_matrix,
};
use host_tests::reference::{mat_dist, quat_matrix, rodrigues, su2_matrix, u2_dist, u2_mul};
use host_tests::tolerance::Tolerance;
use proptest::prelude::*;

host_tests::per_type! {
    /// Rotation vector ↔ quaternion, MRP ↔ quaternion, Gibbs, axis-angle, DCM: at small angles
    /// (series regime), generic angles, and next to 180°, against the reference matrices.
    #[test]
    fn representations_against_reference() {
        let axes = [[1.0, 0.0, 0.0], [0.3, -0.5, 0.8], [-0.1, 0.2, -0.9]];
        let angles = [
            0.0,
            1e-12,
            1e-8,
            1e-5,
            1e-3,
            0.05,
            0.3,
            1.0,
            2.0,
            3.0,
            core::f64::consts::PI - 3e-6,
            core::f64::consts::PI - 6e-10,
        ];
        let tol = T::CONTRACT;
        for ax in axes {
            let n = (ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]).sqrt();
            for &t in &angles {
                let rv = [ax[0] / n * t, ax[1] / n * t, ax[2] / n * t];
                let rv_t = Vec3::from_array(rv.map(T::from_f64));
                // rotvec → quat, compared with Rodrigues of the (rounded) input.
                let q = RotationVector::try_new(rv_t).unwrap().to_unit_quat();
                let r_ref = rotvec_matrix(v64(rv_t));
                let e = rot_dist(&r_ref, &quat_matrix(q64(q)));
                assert!(e <= tol, "rotvec→quat {ax:?} {t}: {e:e}");
                // quat → rotvec.
                let back = RotationVector::from_unit_quat(q);
                let e = rot_dist(&quat_matrix(q64(q)), &rotvec_matrix(v64(back.vector())));
                assert!(e <= tol, "quat→rotvec {ax:?} {t}: {e:e}");
                // quat → MRP → matrix, MRP → quat.
                let m = Mrp::from_unit_quat(q);
                assert!(m.vector().norm().to_f64() <= 1.0 + 1e-6);
                let e = rot_dist(&quat_matrix(q64(q)), &mrp_matrix(v64(m.vector())));
                assert!(e <= tol, "quat→mrp {ax:?} {t}: {e:e}");
                let e = rot_dist(
                    &mrp_matrix(v64(m.vector())),
                    &quat_matrix(q64(m.to_unit_quat())),
                );
                assert!(e <= tol, "mrp→quat {ax:?} {t}: {e:e}");
                // Axis-angle.
                let aa = AxisAngle::from(q);
                let e = rot_dist(
                    &quat_matrix(q64(q)),
                    &rodrigues(v64(aa.axis()), aa.angle().to_f64()),
                );
                assert!(e <= tol, "quat→axis-angle {ax:?} {t}: {e:e}");
                // DCM both ways.
                let d = Dcm::from(q);
                assert!(mat_dist(&m64(d.matrix()), &quat_matrix(q64(q))) <= 4.0 * tol);
                let e = rot_dist(&quat_matrix(q64(q)), &quat_matrix(q64(d.to_unit_quat())));
                assert!(e <= 4.0 * tol, "dcm→quat {ax:?} {t}: {e:e}");
                // Gibbs (away from 180°).
                if t < 3.0 {
                    let g = Gibbs::try_from_unit_quat(q).unwrap();
                    let e = rot_dist(&quat_matrix(q64(q)), &gibbs_matrix(v64(g.vector())));
                    assert!(e <= 10.0 * tol, "gibbs {ax:?} {t}: {e:e}");
                    let e = rot_dist(
                        &gibbs_matrix(v64(g.vector())),
                        &quat_matrix(q64(g.to_unit_quat())),
                    );
                    assert!(e <= tol, "gibbs→quat {ax:?} {t}: {e:e}");
                }
            }
        }
        // Small-angle series: no snapping to the identity.
        let tiny = RotationVector::try_new(Vec3::new(T::from_f64(1e-20), T::ZERO, T::ZERO)).unwrap();
        let q = tiny.to_unit_quat();
        assert!((q.x().to_f64() - 5e-21).abs() < 5e-21 * 1e-6);
        let back = RotationVector::from_unit_quat(q).vector().x.to_f64();
        assert!((back - 1e-20).abs() < 1e-20 * 1e-6);
        let m = Mrp::from_unit_quat(q).vector().x.to_f64();
        assert!((m - 2.5e-21).abs() < 2.5e-21 * 1e-6);
    }

    /// The slerp contract: attitudes 1e-3 rad apart, t = 0.3, error ≤ 1e-6 rad in f32 (and 1e-14
    /// in f64) against the reference point `a·exp(0.3·φ)` computed with matrices.
    #[test]
    fn slerp_contract() {
        let a0 = [0.3, -0.4, 0.5, 0.7];
        for (dir, sep) in [
            ([0.0, 0.0, 1.0], 1e-3),
            ([0.6, 0.8, 0.0], 1e-3),
            ([1.0, 0.0, 0.0], 1e-6),
            ([0.0, 1.0, 0.0], 2.0),
            ([0.0, 0.6, 0.8], 3.1),
        ] {
            let a = unit_quat::<T>(a0);
            let step = Vec3::from_array(dir.map(|x| T::from_f64(x * sep)));
            let b = a * UnitQuat::try_exp(step).unwrap();
            let b = -b; // the other hemisphere: slerp must still take the short way
            let want = host_tests::reference::mat_mul(
                &quat_matrix(q64(a)),
                &rotvec_matrix(v64(step).map(|x| 0.3 * x)),
            );
            let got = a.slerp(b, T::from_f64(0.3));
            let e = rot_dist(&quat_matrix(q64(got)), &want);
            assert!(e <= T::CONTRACT, "slerp {dir:?} {sep}: {e:e}");
            // Endpoints.
            assert!(
                rot_dist(&quat_matrix(q64(a.slerp(b, T::ZERO))), &quat_matrix(q64(a))) <= T::CONTRACT
            );
            assert!(
                rot_dist(&quat_matrix(q64(a.slerp(b, T::ONE))), &quat_matrix(q64(b))) <= T::CONTRACT
            );
            // nlerp: same endpoints, near the geodesic for small separations.
            let n = a.nlerp(b, T::from_f64(0.3));
            let e = rot_dist(&quat_matrix(q64(n)), &want);
            assert!(e <= T::CONTRACT + sep.powi(3), "nlerp {sep}: {e:e}");
        }
    }

    proptest! {
        #[test]
        fn round_trip_every_representation(q in unit_quat_strategy(), s in 0usize..24) {
            round_trips::<T>(q, s)?;
        }
    }
}

#[test]
fn gibbs_is_singular_at_180_degrees() {
    let q = UnitQuat::<f64>::try_from_axis_angle(Vec3::new(0.0, 1.0, 1.0), core::f64::consts::PI)
        .unwrap();
    assert_eq!(Gibbs::try_from_unit_quat(q), Err(Error::Singular));
    let q = UnitQuat::new_unchecked(Quat::new(0.0f32, 1.0, 0.0, 0.0));
    assert_eq!(Gibbs::try_from_unit_quat(q), Err(Error::Singular));
    // Huge but finite Gibbs vectors go back without overflow.
    let g = Gibbs::try_new(Vec3::new(1e30f32, 0.0, 0.0)).unwrap();
    let q = g.to_unit_quat();
    assert!(q.w() > 0.0 && (q.x() - 1.0).abs() < 1e-6);
}

#[test]
fn mrp_shadow_set() {
    // 270° about z: |σ| = tan(67.5°) > 1; switched gives the 90° the other way.
    let s = Mrp::try_new(Vec3::new(0.0f64, 0.0, (270.0f64.to_radians() / 4.0).tan())).unwrap();
    let sw = s.switched();
    assert!(sw.vector().norm() <= 1.0);
    assert!((sw.vector().z + (90.0f64.to_radians() / 4.0).tan()).abs() < 1e-15);
    let e = rot_dist(&mrp_matrix(v64(s.vector())), &mrp_matrix(v64(sw.vector())));
    assert!(e < 1e-14);
    let sh = sw.try_shadow().unwrap();
    assert!((sh.vector().z - s.vector().z).abs() < 1e-14);
    assert_eq!(
        Mrp::try_new(Vec3::<f64>::ZERO).unwrap().try_shadow(),
        Err(Error::Singular)
    );
    // At exactly 180° the returned set has |σ| = 1.
    let q = UnitQuat::<f64>::try_from_axis_angle(Vec3::X, core::f64::consts::PI).unwrap();
    assert!((Mrp::from_unit_quat(q).vector().norm() - 1.0).abs() < 1e-15);
}

#[test]
fn dcm_checks_and_orthonormalises() {
    let q = unit_quat::<f64>([0.4, -0.2, 0.7, 0.1]);
    let r = q.to_rotation_matrix();
    assert!(Dcm::try_from_matrix(r, Dcm::default_tolerance()).is_ok());
    // A reflection is not a rotation.
    assert_eq!(Dcm::try_from_matrix(-r, 1e-6), Err(Error::NotRotation));
    // A scaled matrix is not within tolerance.
    assert_eq!(
        Dcm::try_from_matrix(r.scale(1.01), 1e-6),
        Err(Error::NotRotation)
    );
    let mut bad = r;
    bad.m[0][0] = f64::NAN;
    assert_eq!(Dcm::try_from_matrix(bad, 1e-6), Err(Error::NonFinite));
    // Noisy matrix: the orthonormalised one is orthonormal and close to the clean rotation.
    let mut noisy = r;
    let noise = [
        [1e-3, -2e-3, 5e-4],
        [-1e-3, 3e-3, 2e-3],
        [7e-4, -4e-4, -1e-3],
    ];
    for i in 0..3 {
        for j in 0..3 {
            noisy.m[i][j] += noise[i][j];
        }
    }
    let d = Dcm::try_from_matrix_orthonormalized(noisy).unwrap();
    let m = d.into_matrix();
    assert!((m.transpose() * m - Mat3::IDENTITY).max_abs() < 1e-15);
    assert!((m.determinant() - 1.0).abs() < 1e-15);
    assert!(rot_dist(&m64(&m), &m64(&r)) < 5e-3);
    // The polar factor is the nearest rotation: no other nearby rotation is closer (Frobenius).
    let frob = |a: &Mat3<f64>| {
        let d = *a - noisy;
        d.m.iter().flatten().map(|x| x * x).sum::<f64>()
    };
    for v in [[1e-4, 0.0, 0.0], [0.0, -1e-4, 0.0], [0.0, 0.0, 1e-4]] {
        let p = UnitQuat::try_exp(Vec3::from_array(v))
            .unwrap()
            .to_rotation_matrix();
        assert!(frob(&(p * m)) >= frob(&m));
    }
    assert_eq!(
        Dcm::try_from_matrix_orthonormalized(-r),
        Err(Error::NotRotation)
    );
    assert_eq!(
        Dcm::try_from_matrix_orthonormalized(Mat3::<f64>::ZERO),
        Err(Error::NotRotation)
    );
    // Shepperd: each branch (w, x, y, z largest).
    for q in [
        [0.9, 0.1, 0.3, -0.2],
        [0.1, 0.9, -0.3, 0.2],
        [0.1, 0.3, -0.9, 0.2],
        [-0.1, 0.3, 0.2, 0.9],
        [0.0, 0.0, 0.0, 1.0],
    ] {
        let q = unit_quat::<f64>(q);
        let back = Dcm::from(q).to_unit_quat();
        assert!(q.angle_to(back) < 1e-15);
    }
}

/// Seed (6.6.14–15): the Rodrigues matrix in polar axis angles `[φ, ϑ, Θ]`, entry by entry.
#[test]
fn seed_6_6_15_rodrigues_matrix() {
    let (phi, theta, big) = (0.7f64, 1.1, 2.3);
    let p = PolarAxisAngle::new(phi, theta, big);
    let r = p.try_to_unit_quat().unwrap().to_rotation_matrix();
    let (x, y, z) = (
        phi.cos() * theta.sin(),
        phi.sin() * theta.sin(),
        theta.cos(),
    );
    let (s, c) = big.sin_cos();
    let k = 1.0 - c;
    let want = [
        [c + k * x * x, k * x * y - z * s, k * x * z + y * s],
        [k * x * y + z * s, c + k * y * y, k * y * z - x * s],
        [k * x * z - y * s, k * y * z + x * s, c + k * z * z],
    ];
    assert!(mat_dist(&m64(&r), &want) < 1e-15);
    // And the index form (6.6.14) of the reference agrees with the same matrix.
    assert!(mat_dist(&rodrigues([x, y, z], big), &want) < 1e-15);
    // f32
    let r32 = PolarAxisAngle::new(0.7f32, 1.1, 2.3)
        .try_to_unit_quat()
        .unwrap()
        .to_rotation_matrix();
    assert!(mat_dist(&m64(&r32), &want) < 2e-6);
}

/// Seed (6.6.10): the U(2) product `R[Θ']R[Θ] = R[Θ'']` with
/// `cos Θ''/2 = cos Θ'/2 cos Θ/2 − sin Θ'/2 sin Θ/2 Θ̂'·Θ̂` and
/// `sin Θ''/2 Θ̂'' = cos Θ'/2 sin Θ/2 Θ̂ + cos Θ/2 sin Θ'/2 Θ̂' + sin Θ'/2 sin Θ/2 Θ̂'×Θ̂`.
/// (The seed's printed (6.6.10b) drops the `Θ̂'·Θ̂` term and swaps which axis goes with which
/// sine; the form here is the product of the printed matrices (6.6.4), which the test also checks
/// directly with the reference's 2×2 complex matrices.)
#[test]
fn seed_6_6_10_u2_product() {
    let (n1, t1) = ([0.0f64, 0.6, 0.8], 1.3); // Θ'
    let (n2, t2) = ([1.0f64, 0.0, 0.0], 0.9); // Θ
    let a = Su2::from(UnitQuat::try_from_axis_angle(Vec3::from_array(n1), t1).unwrap());
    let b = Su2::from(UnitQuat::try_from_axis_angle(Vec3::from_array(n2), t2).unwrap());
    let prod = UnitQuat::from(a * b);
    let (c1, s1) = ((t1 / 2.0).cos(), (t1 / 2.0).sin());
    let (c2, s2) = ((t2 / 2.0).cos(), (t2 / 2.0).sin());
    let dot = n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2];
    let cross = [
        n1[1] * n2[2] - n1[2] * n2[1],
        n1[2] * n2[0] - n1[0] * n2[2],
        n1[0] * n2[1] - n1[1] * n2[0],
    ];
    let w = c1 * c2 - s1 * s2 * dot;
    let v = [0, 1, 2].map(|i| c1 * s2 * n2[i] + c2 * s1 * n1[i] + s1 * s2 * cross[i]);
    let got = q64(prod);
    assert!((got[0] - w).abs() < 1e-15);
    for i in 0..3 {
        assert!((got[i + 1] - v[i]).abs() < 1e-15, "{got:?} {v:?}");
    }
    // Against explicit 2×2 matrices (6.6.4).
    let m = u2_mul(&su2_matrix(n1, t1), &su2_matrix(n2, t2));
    let mm = (a * b).matrix();
    let conv =
        [0, 1].map(|i| [0, 1].map(|j| host_tests::reference::C::new(mm[i][j].re, mm[i][j].im)));
    assert!(u2_dist(&m, &conv) < 1e-15);
}

/// Seed (6.6.16a–c): a spin vector starting on the A = Z axis precesses about the whirl axis
/// `[φ = 0, ϑ]`; its components follow the closed forms. And the magic angle
/// `ϑ = acos(1/√3)`, `φ = π/4`: at Θ = 120° the spin is along B = X, at 240° along C = Y.
#[test]
fn seed_6_6_16_spin_precession_and_magic_angle() {
    let theta = 0.6f64;
    for k in 0..=12 {
        let big = k as f64 * 0.5;
        let q = PolarAxisAngle::new(0.0, theta, big)
            .try_to_unit_quat()
            .unwrap();
        let s = q.rotate(Vec3::Z);
        let half = (big / 2.0).sin().powi(2);
        assert!((s.z - (1.0 - 2.0 * theta.sin().powi(2) * half)).abs() < 1e-15); // (6.6.16a)
        assert!((s.x - (2.0 * theta).sin() * half).abs() < 1e-15); // (6.6.16b)
        assert!((s.y + theta.sin() * big.sin()).abs() < 1e-15); // (6.6.16c)
        // The SU(2) similarity transform (6.6.8) gives the same vector.
        let s2 = Su2::from(q).rotate(Vec3::Z);
        assert!((s2 - s).norm() < 1e-15);
    }
    let magic = (1.0f64 / 3.0f64.sqrt()).acos();
    assert!((magic.to_degrees() - 54.7).abs() < 0.05);
    let p = |big: f64| {
        PolarAxisAngle::new(core::f64::consts::FRAC_PI_4, magic, big)
            .try_to_unit_quat()
            .unwrap()
            .rotate(Vec3::Z)
    };
    let third = 2.0 * core::f64::consts::PI / 3.0;
    assert!((p(third) - Vec3::X).norm() < 1e-15);
    assert!((p(2.0 * third) - Vec3::Y).norm() < 1e-15);
    assert!((p(3.0 * third) - Vec3::Z).norm() < 1e-15);
    // In f32 too.
    let q32 = PolarAxisAngle::new(core::f32::consts::FRAC_PI_4, magic as f32, third as f32)
        .try_to_unit_quat()
        .unwrap();
    assert!((q32.rotate(Vec3::Z) - Vec3::X).norm() < 1e-6);
}

#[test]
fn canonical_sign_and_ties() {
    let cases: [([f64; 4], [f64; 4]); 5] = [
        ([-0.5, 0.5, 0.5, 0.5], [0.5, -0.5, -0.5, -0.5]),
        ([0.0, -1.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0]),
        ([0.0, 0.0, -0.6, 0.8], [0.0, 0.0, 0.6, -0.8]),
        ([0.0, 0.0, 0.0, -1.0], [0.0, 0.0, 0.0, 1.0]),
        ([-0.0, 0.6, -0.8, 0.0], [-0.0, 0.6, -0.8, 0.0]),
    ];
    for (q, want) in cases {
        let c = UnitQuat::new_unchecked(Quat::from_array(q)).canonical();
        assert_eq!(c.to_array(), want, "{q:?}");
    }
    // SU(2) keeps the sign: −q is a different spinor.
    let q = unit_quat::<f64>([-0.5, 0.5, 0.5, 0.5]);
    assert_eq!(UnitQuat::from(Su2::from(q)), q);
}

/// Geodesic angle: accurate for tiny separations (where 2·acos(|dot|) returns 0) and at π.
#[test]
fn geodesic_angle() {
    let a = unit_quat::<f64>([0.3, -0.4, 0.5, 0.7]);
    for t in [1e-12, 1e-8, 1e-3, 1.0, 3.0, core::f64::consts::PI] {
        let b = a * UnitQuat::try_exp(Vec3::new(0.0, t, 0.0)).unwrap();
        let got = a.angle_to(b);
        assert!((got - t).abs() <= 1e-15 * t.max(1.0), "{t}: {got}");
        assert!((a.angle_to(-b) - got).abs() < 1e-16 * got.max(1.0));
    }
    let a32 = unit_quat::<f32>([0.3, -0.4, 0.5, 0.7]);
    let b32 = a32 * UnitQuat::try_exp(Vec3::new(0.0f32, 1e-6, 0.0)).unwrap();
    assert!((a32.angle_to(b32) - 1e-6).abs() < 2e-7);
}

/// Similarity transform (6.6.8): g·q·g⁻¹ is the rotation by the same angle about g·n̂.
#[test]
fn similarity_transform() {
    let q = UnitQuat::try_from_axis_angle(Vec3::new(0.2f64, 0.3, -0.9), 1.2).unwrap();
    let g = UnitQuat::try_from_axis_angle(Vec3::new(-0.5f64, 0.1, 0.4), 0.8).unwrap();
    let s = q.similarity_transform(g);
    let r = quat_matrix(q64(g));
    let want = host_tests::reference::mat_mul(
        &host_tests::reference::mat_mul(&r, &quat_matrix(q64(q))),
        &host_tests::reference::transpose(&r),
    );
    assert!(rot_dist(&quat_matrix(q64(s)), &want) < 1e-15);
    let axis = AxisAngle::from(s).axis();
    let n = Vec3::new(0.2f64, 0.3, -0.9).try_normalize().unwrap();
    assert!((axis - g.rotate(n)).norm() < 1e-14);
}

fn unit_quat_strategy() -> impl Strategy<Value = [f64; 4]> {
    prop::array::uniform4(-1.0f64..1.0)
        .prop_filter("non-zero", |q| q.iter().map(|c| c * c).sum::<f64>() > 1e-3)
}

fn round_trips<T: Tolerance>(q: [f64; 4], seq_idx: usize) -> Result<(), TestCaseError> {
    let q = unit_quat::<T>(q);
    let r = quat_matrix(q64(q));
    let tol = T::CONTRACT;
    let check = |name: &str, p: UnitQuat<T>, tol: f64| -> Result<(), TestCaseError> {
        let e = rot_dist(&r, &quat_matrix(q64(p)));
        prop_assert!(e <= tol, "{}: {:e}", name, e);
        Ok(())
    };
    check("dcm", Dcm::from(q).to_unit_quat(), 4.0 * tol)?;
    check("rotvec", RotationVector::from(q).to_unit_quat(), tol)?;
    check("mrp", Mrp::from(q).to_unit_quat(), tol)?;
    check("axis-angle", AxisAngle::from(q).to_unit_quat(), tol)?;
    check(
        "polar",
        PolarAxisAngle::from(q).try_to_unit_quat().unwrap(),
        tol,
    )?;
    check("su2", UnitQuat::from(Su2::from(q)), 0.0)?;
    if let Ok(g) = Gibbs::try_from_unit_quat(q) {
        // Gibbs amplifies the rounding of w by 1/|w| near 180°.
        check(
            "gibbs",
            g.to_unit_quat(),
            tol / q.w().to_f64().abs().max(1e-3),
        )?;
    }
    let seq = EulerSequence::ALL[seq_idx % 24];
    let e = q.to_euler(seq, GimbalPolicy::ZeroThird).euler;
    check("euler", e.to_unit_quat_unchecked(), 2.0 * tol)?;
    // Euler → Dcm equals the reference matrix of the extracted angles.
    let seq_s = seq.to_string();
    let em = euler_matrix(&seq_s, e.angles.map(|x| x.to_f64()));
    prop_assert!(rot_dist(&r, &em) <= tol);
    // Sign-keeping conversions return the same spinor.
    let p = PolarAxisAngle::from_unit_quat(q)
        .try_to_unit_quat()
        .unwrap();
    prop_assert!((p.into_quat() - q.into_quat()).norm().to_f64() <= 4.0 * tol);
    let aa = AxisAngle::from_unit_quat(q).to_unit_quat();
    prop_assert!((aa.into_quat() - q.into_quat()).norm().to_f64() <= 4.0 * tol);
    Ok(())
}

proptest! {

    /// Random attitudes moved to within 1e-9…1e-2 of a pole of a random convention (or onto
    /// it): the Euler contract holds.
    #[test]
    fn euler_contract_near_poles(
        a in -3.2f64..3.2, c in -3.2f64..3.2, s in 0usize..24, upper in any::<bool>(),
        exp in -12i32..-1, side in any::<bool>(), exact in any::<bool>(),
        pa in -10.0f64..10.0, pc in -10.0f64..10.0, pol in 0usize..3,
    ) {
        let seq = EulerSequence::ALL[s];
        let seq_s = seq.to_string();
        let pole = match (seq.is_proper(), upper) {
            (true, false) => 0.0,
            (true, true) => core::f64::consts::PI,
            (false, false) => -core::f64::consts::FRAC_PI_2,
            (false, true) => core::f64::consts::FRAC_PI_2,
        };
        let d = if exact { 0.0 } else { 10f64.powi(exp) * if side { 1.0 } else { -1.0 } };
        let q64v = Euler::new(seq, [a, pole + d, c]).to_unit_quat_unchecked();
        for f32_mode in [false, true] {
            fn policy<T: Real>(pol: usize, pa: f64, pc: f64) -> GimbalPolicy<T> {
                match pol {
                    0 => GimbalPolicy::ZeroFirst,
                    1 => GimbalPolicy::ZeroThird,
                    _ => GimbalPolicy::ClosestTo([T::from_f64(pa), T::ZERO, T::from_f64(pc)]),
                }
            }
            let (ang, q_in): ([f64; 3], [f64; 4]) = if f32_mode {
                let q: UnitQuat<f32> = UnitQuat::new_unchecked(Quat::from_array(q64v.to_array().map(|x| x as f32)));
                (q.to_euler(seq, policy(pol, pa, pc)).euler.angles.map(|x| x as f64), q64(q))
            } else {
                (q64v.to_euler(seq, policy(pol, pa, pc)).euler.angles, q64(q64v))
            };
            let e = rot_dist(&quat_matrix(q_in), &euler_matrix(&seq_s, ang));
            let tol = if f32_mode { 1e-6 } else { 1e-14 };
            prop_assert!(e <= tol, "{} {:?}: {:e}", seq_s, [a, pole + d, c], e);
        }
    }
}

#[test]
fn no_nan_for_extreme_inputs() {
    for v in [1e-300, 1e-30, 1e30, 1e300, f64::MAX / 4.0] {
        let rv = RotationVector::try_new(Vec3::new(v, -v, v)).unwrap();
        assert!(rv.to_unit_quat().into_quat().is_finite());
        let m = Mrp::try_new(Vec3::new(v, 0.0, -v)).unwrap();
        assert!(m.to_unit_quat().into_quat().is_finite());
        let g = Gibbs::try_new(Vec3::new(v, v, 0.0)).unwrap();
        assert!(g.to_unit_quat().into_quat().is_finite());
    }
    assert_eq!(
        RotationVector::try_new(Vec3::new(f64::NAN, 0.0, 0.0)),
        Err(Error::NonFinite)
    );
    assert_eq!(
        RotationVector::try_new(Vec3::new(f64::MAX, f64::MAX, 0.0)),
        Err(Error::InvalidArgument)
    );
    assert_eq!(
        UnitQuat::try_exp(Vec3::new(f32::MAX, 0.0, -f32::MAX)),
        Err(Error::InvalidArgument)
    );
    for s in all_sequences() {
        let seq = EulerSequence::try_from_str(&s).unwrap();
        assert_eq!(
            Euler::new(seq, [0.0, f32::INFINITY, 0.0]).try_to_unit_quat(),
            Err(Error::NonFinite)
        );
    }
}

/// Orthonormalisation of a badly conditioned (but det > 0) matrix converges thanks to the scaled
/// iteration, and yields the polar factor (here: the identity for a positive diagonal matrix).
#[test]
fn orthonormalise_ill_conditioned() {
    let m = Mat3::from_diagonal(Vec3::new(1e-10f64, 1.0, 3e5));
    let d = Dcm::try_from_matrix_orthonormalized(m).unwrap();
    assert!((d.into_matrix() - Mat3::IDENTITY).max_abs() < 1e-14);
    let m = Mat3::from_diagonal(Vec3::new(1e-5f32, 1.0, 30.0));
    let d = Dcm::try_from_matrix_orthonormalized(m).unwrap();
    assert!((d.into_matrix() - Mat3::IDENTITY).max_abs() < 1e-6);
}
