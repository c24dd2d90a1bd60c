//! Euler angles in all 24 conventions against the independent matrix reference, the accuracy
//! contract at and near gimbal lock, and the seed's Euler worked numbers (6.6.6a–d).
#![allow(clippy::needless_range_loop)] // 3×3 index loops read like the formulas

use gyrostat::rotation::{
    Euler, EulerSequence, Frame, GimbalPolicy, PolarAxisAngle, Pole, gimbal_lock_threshold,
};
use gyrostat::{Quat, UnitQuat};
use host_tests::cast::q64;
use host_tests::ref_rotation::{all_sequences, euler_matrix, is_proper, poles, rot_dist};
use host_tests::reference::quat_matrix;
use host_tests::tolerance::Tolerance;

/// Outer-angle pairs for the sweep: generic values, values at ±π, zeros, equal values.
const OUTER: [(f64, f64); 10] = [
    (0.3, -1.1),
    (2.9, 3.1),
    (-3.1, 0.0),
    (1.0, 1.0),
    (0.0, 0.0),
    (-2.0, 2.5),
    (core::f64::consts::PI, -core::f64::consts::PI),
    (1e-9, -1e-9),
    (-0.7, 0.7),
    (2.2, -0.4),
];

/// Distances of the middle angle from its pole, both sides.
fn distances() -> Vec<f64> {
    let mut d = vec![0.0];
    for e in [-9, -8, -7, -6, -5, -4, -3, -2] {
        let x = 10f64.powi(e);
        d.push(x);
        d.push(-x);
    }
    d
}

/// The sweep of `quat_to_euler_contract`; returns the worst error.
fn sweep<T: Tolerance>() -> f64 {
    let mut worst: f64 = 0.0;
    for seq_s in all_sequences() {
        let seq = EulerSequence::try_from_str(&seq_s).unwrap();
        for pole in poles(&seq_s) {
            for d in distances() {
                for &(a, c) in &OUTER {
                    let angles = [a, pole + d, c];
                    // Input quaternion: f64 product of elementary rotations, rounded to T.
                    let q = Euler::new(seq, angles).to_unit_quat_unchecked();
                    let q = UnitQuat::<T>::new_unchecked(Quat::new(
                        T::from_f64(q.w()),
                        T::from_f64(q.x()),
                        T::from_f64(q.y()),
                        T::from_f64(q.z()),
                    ));
                    let r_in = quat_matrix(q64(q));
                    for policy in [
                        GimbalPolicy::ZeroFirst,
                        GimbalPolicy::ZeroThird,
                        GimbalPolicy::ClosestTo([T::from_f64(-2.0), T::ZERO, T::from_f64(1.5)]),
                    ] {
                        let sol = q.to_euler(seq, policy);
                        let ang = sol.euler.angles.map(|x| x.to_f64());
                        assert!(ang.iter().all(|x| x.is_finite()));
                        let err = rot_dist(&r_in, &euler_matrix(&seq_s, ang));
                        assert!(
                            err <= T::CONTRACT,
                            "{seq_s} {angles:?} {policy:?}: error {err:e} > {:e} (got {ang:?})",
                            T::CONTRACT
                        );
                        worst = worst.max(err);
                        // Ranges.
                        let pi = core::f64::consts::PI;
                        assert!(ang[0] > -pi - 1e-6 && ang[0] <= pi + 1e-6);
                        assert!(ang[2] > -pi - 1e-6 && ang[2] <= pi + 1e-6);
                        if is_proper(&seq_s) {
                            assert!((0.0..=pi + 1e-6).contains(&ang[1]));
                        } else {
                            assert!(ang[1].abs() <= pi / 2.0 + 1e-6);
                        }
                        // Flag: never when clearly off the pole; always when exactly on it
                        // (f64 input) within the threshold.
                        let thr = gimbal_lock_threshold::<T>().to_f64();
                        if d.abs() >= 1e-5 {
                            assert!(sol.singularity.is_none(), "{seq_s} {angles:?}");
                        }
                        if let Some(lock) = sol.singularity {
                            assert!(lock.distance_to_pole.to_f64() <= thr);
                            let expect_pole = if pole == poles(&seq_s)[0] {
                                Pole::Lower
                            } else {
                                Pole::Upper
                            };
                            assert_eq!(lock.pole, expect_pole, "{seq_s} {angles:?}");
                            // The policy's zero is honoured.
                            match policy {
                                GimbalPolicy::ZeroFirst => assert_eq!(ang[0], 0.0),
                                GimbalPolicy::ZeroThird => assert_eq!(ang[2], 0.0),
                                GimbalPolicy::ClosestTo(_) => {}
                            }
                            // first + s·third = combined (mod 2π).
                            let s = lock.sign.to_f64();
                            let comb = lock.combined_angle.to_f64();
                            let diff = (ang[0] + s * ang[2] - comb).rem_euclid(2.0 * pi);
                            assert!(diff.min(2.0 * pi - diff) < 1e-5, "{seq_s}: {diff}");
                        }
                        assert!(sol.distance_to_pole.to_f64() <= (d.abs() + 1e-6).max(1e-6));
                    }
                }
            }
        }
    }
    worst
}

host_tests::per_type! {
    /// Quaternion → Euler → rotation, all 24 conventions, every distance from the pole
    /// including 0, every policy: the geodesic error of the rebuilt rotation is within the
    /// contract; gimbal lock is flagged exactly when within the threshold and never far from
    /// the pole.
    #[test]
    fn quat_to_euler_contract() {
        let w = sweep::<T>();
        println!("worst {} quat→Euler→rotation error: {w:e}", T::NAME);
    }

    /// An Euler triple set exactly at the pole (b = 0 or π for proper sequences, ±π/2 for
    /// Tait–Bryan, as constants of the type) and converted in that type is reported as gimbal
    /// lock in every convention.
    #[test]
    fn exact_pole_is_flagged() {
        for seq_s in all_sequences() {
            let seq = EulerSequence::try_from_str(&seq_s).unwrap();
            for pole in poles(&seq_s) {
                for &(a, c) in &OUTER {
                    let q = Euler::new(seq, [a, pole, c].map(T::from_f64)).to_unit_quat_unchecked();
                    let sol = q.to_euler(seq, GimbalPolicy::ZeroThird);
                    assert!(
                        sol.singularity.is_some(),
                        "{seq_s} pole {pole} ({a}, {c}): distance {:e}",
                        sol.distance_to_pole.to_f64()
                    );
                }
            }
        }
    }

    /// Euler → quaternion against the reference matrices, random-ish angles, all conventions.
    #[test]
    fn euler_to_quat_contract() {
        let mut worst: f64 = 0.0;
        let vals = [
            -3.1,
            -2.0,
            -0.9,
            -1e-7,
            0.0,
            0.4,
            core::f64::consts::FRAC_PI_2,
            2.5,
            3.1,
            core::f64::consts::PI,
        ];
        for seq_s in all_sequences() {
            let seq = EulerSequence::try_from_str(&seq_s).unwrap();
            for &a in &vals {
                for &b in &vals {
                    for &c in &vals {
                        let ang = [a, b, c].map(T::from_f64);
                        let q = Euler::new(seq, ang).to_unit_quat_unchecked();
                        let r_ref = euler_matrix(&seq_s, ang.map(|x| x.to_f64()));
                        let err = rot_dist(&r_ref, &quat_matrix(q64(q)));
                        assert!(err <= T::CONTRACT, "{seq_s} {a} {b} {c}: {err:e}");
                        worst = worst.max(err);
                    }
                }
            }
        }
        println!("worst {} Euler→quat error: {worst:e}", T::NAME);
    }
}

/// Round trip of the angles themselves away from the poles (where they are unique): the
/// extracted angles equal the input ones (modulo 2π) in every convention.
#[test]
fn angles_round_trip_off_pole() {
    for seq_s in all_sequences() {
        let seq = EulerSequence::try_from_str(&seq_s).unwrap();
        let b = if is_proper(&seq_s) { 1.1 } else { -0.6 };
        let input: [f64; 3] = [2.3, b, -0.4];
        let q = Euler::new(seq, input).to_unit_quat_unchecked();
        let out = q.to_euler_angles(seq);
        for k in 0..3 {
            assert!((out[k] - input[k]).abs() < 1e-14, "{seq_s}: {out:?}");
        }
        // Sign of q does not matter.
        let out_neg = (-q).to_euler_angles(seq);
        for k in 0..3 {
            assert!(
                (out_neg[k] - input[k]).abs() < 1e-14,
                "{seq_s}: {out_neg:?}"
            );
        }
    }
}

#[test]
fn sequence_parsing_matches_scipy_notation() {
    assert_eq!(
        EulerSequence::try_from_str("ZYX").unwrap(),
        EulerSequence::ZYX
    );
    assert_eq!(
        EulerSequence::try_from_str("zyx").unwrap().frame(),
        Frame::Extrinsic
    );
    for bad in ["", "ZY", "ZYXZ", "Zyx", "ZZX", "XYY", "abc", "zy1"] {
        assert!(EulerSequence::try_from_str(bad).is_err(), "{bad}");
    }
    for s in all_sequences() {
        assert_eq!(EulerSequence::try_from_str(&s).unwrap().to_string(), s);
    }
    assert_eq!(EulerSequence::ALL.len(), 24);
    let mut names: Vec<String> = EulerSequence::ALL.iter().map(|s| s.to_string()).collect();
    names.sort();
    let mut expect = all_sequences();
    expect.sort();
    assert_eq!(names, expect);
}

/// Intrinsic "ABC" with (a, b, c) is extrinsic "cba" with (c, b, a) (scipy's identity).
#[test]
fn intrinsic_is_reversed_extrinsic() {
    let q1 = Euler::new(EulerSequence::try_from_str("XYZ").unwrap(), [0.1, 0.2, 0.3])
        .to_unit_quat_unchecked();
    let q2 = Euler::new(EulerSequence::try_from_str("zyx").unwrap(), [0.3, 0.2, 0.1])
        .to_unit_quat_unchecked();
    assert!(q1.angle_to(q2) < 1e-15);
}

const DEG: f64 = core::f64::consts::PI / 180.0;

/// Seed (6.6.6a): R(α=50°, β=60°, γ=70°) = R[φ=80°, ϑ=34°, Θ=129°], to the seed's rounding (the
/// exact values are φ = 80°, ϑ = 33.69°, Θ = 128.68°).
#[test]
fn seed_6_6_6a_euler_to_axis_angles() {
    let q = Euler::new(EulerSequence::ZYZ, [50.0 * DEG, 60.0 * DEG, 70.0 * DEG])
        .to_unit_quat_unchecked();
    let p = PolarAxisAngle::from_unit_quat(q);
    assert!((p.phi / DEG - 80.0).abs() < 0.5, "{}", p.phi / DEG);
    assert!((p.theta / DEG - 34.0).abs() < 0.5, "{}", p.theta / DEG);
    assert!((p.angle / DEG - 129.0).abs() < 0.5, "{}", p.angle / DEG);
    // Closed forms from (6.6.5a): cos Θ/2 = cos((α+γ)/2) cos(β/2), φ = (α − γ + π)/2 (6.6.5c).
    let cos_half = (60.0 * DEG).cos() * (30.0 * DEG).cos();
    assert!((p.angle - 2.0 * cos_half.acos()).abs() < 1e-14);
    assert!((p.phi - (50.0 - 70.0 + 180.0) / 2.0 * DEG).abs() < 1e-14);
    // And back: the seed's rounded axis angles give the Euler angles within the rounding.
    let back = PolarAxisAngle::new(80.0 * DEG, 34.0 * DEG, 129.0 * DEG)
        .try_to_unit_quat()
        .unwrap()
        .to_euler_angles(EulerSequence::ZYZ)
        .map(|x| x / DEG);
    for (got, want) in back.iter().zip([50.0, 60.0, 70.0]) {
        assert!((got - want).abs() < 1.0, "{back:?}");
    }
}

/// Seed (6.6.6b–d): the 4π sequence. Θ = 360° is −1 (the "2nd origin" |170°, 0, 190°⟩, whose
/// spinor is also −1), and Θ = 129° + 360° is the spinor of |230°, −60°, 250°⟩ = −R(50°, 60°, 70°).
#[test]
fn seed_6_6_6cd_four_pi_sequence() {
    let q0 = Euler::new(EulerSequence::ZYZ, [50.0 * DEG, 60.0 * DEG, 70.0 * DEG])
        .to_unit_quat_unchecked();
    let p = PolarAxisAngle::from_unit_quat(q0);
    // (6.6.6b): Θ = 0 is the origin |φ − 90°, 0, 90° − φ⟩ = |−10°, 0, 10°⟩, spinor +1.
    let origin =
        Euler::new(EulerSequence::ZYZ, [-10.0 * DEG, 0.0, 10.0 * DEG]).to_unit_quat_unchecked();
    assert!((origin.w() - 1.0).abs() < 1e-15);
    // (6.6.6c)
    let full = PolarAxisAngle::new(p.phi, p.theta, 2.0 * core::f64::consts::PI)
        .try_to_unit_quat()
        .unwrap();
    let second_origin =
        Euler::new(EulerSequence::ZYZ, [170.0 * DEG, 0.0, 190.0 * DEG]).to_unit_quat_unchecked();
    assert!((full.w() + 1.0).abs() < 1e-15 && (second_origin.w() + 1.0).abs() < 1e-15);
    // (6.6.6d): same spinor, sign included.
    let q489 = PolarAxisAngle::new(p.phi, p.theta, p.angle + 2.0 * core::f64::consts::PI)
        .try_to_unit_quat()
        .unwrap();
    let e = Euler::new(EulerSequence::ZYZ, [230.0 * DEG, -60.0 * DEG, 250.0 * DEG])
        .to_unit_quat_unchecked();
    let d = (q489.into_quat() - e.into_quat()).norm();
    assert!(d < 1e-14, "{q489:?} vs {e:?}");
    assert!((q489.into_quat() + q0.into_quat()).norm() < 1e-14);
    // 720° returns to +1.
    let q720 = PolarAxisAngle::new(p.phi, p.theta, 4.0 * core::f64::consts::PI)
        .try_to_unit_quat()
        .unwrap();
    assert!((q720.w() - 1.0).abs() < 1e-15);
}

/// Seed §6.6.a (Fig. 6.6.2d): (α, 0, γ) ≡ (α − φ, 0, γ + φ); extraction reports the lock with
/// the combined angle α + γ, and the policies split it as asked.
#[test]
fn seed_gimbal_equivalence() {
    let (alpha, gamma): (f64, f64) = (0.7, -0.2);
    let q = Euler::new(EulerSequence::ZYZ, [alpha, 0.0, gamma]).to_unit_quat_unchecked();
    for phi in [-2.0, -0.3, 0.0, 0.5, 3.0] {
        let q2 = Euler::new(EulerSequence::ZYZ, [alpha - phi, 0.0, gamma + phi])
            .to_unit_quat_unchecked();
        assert!(q.angle_to(q2) < 1e-15);
    }
    let sol = q.to_euler(EulerSequence::ZYZ, GimbalPolicy::ZeroFirst);
    let lock = sol.singularity.unwrap();
    assert_eq!(lock.pole, Pole::Lower);
    assert_eq!(lock.sign, 1.0);
    assert!((lock.combined_angle - 0.5).abs() < 1e-15);
    assert_eq!(sol.euler.angles[0], 0.0);
    assert!((sol.euler.angles[2] - 0.5).abs() < 1e-15);
    // Closest to a previous solution (0.6, 0, −0.05): the split moves both by the same amount.
    let sol = q.to_euler(
        EulerSequence::ZYZ,
        GimbalPolicy::ClosestTo([0.6, 0.0, -0.05]),
    );
    let [a, _, c] = sol.euler.angles;
    assert!(
        (a - 0.575).abs() < 1e-15 && (c + 0.075).abs() < 1e-15,
        "{a} {c}"
    );
    // Upper pole β = π: only α − γ is determined.
    let q = Euler::new(EulerSequence::ZYZ, [alpha, core::f64::consts::PI, gamma])
        .to_unit_quat_unchecked();
    let sol = q.to_euler(EulerSequence::ZYZ, GimbalPolicy::ZeroThird);
    let lock = sol.singularity.unwrap();
    assert_eq!((lock.pole, lock.sign), (Pole::Upper, -1.0));
    assert!((lock.combined_angle - 0.9).abs() < 1e-15);
}

/// ClosestTo keeps a telemetry stream continuous through the pole: the outer angles follow a
/// previous solution instead of jumping to a zero.
#[test]
fn closest_to_is_continuous_through_the_pole() {
    let seq = EulerSequence::ZYX;
    let mut prev = [0.4f64, 1.2, -0.3];
    for k in 0..=40 {
        let pitch = 1.2 + (core::f64::consts::FRAC_PI_2 - 1.2) * (k as f64 / 20.0);
        let pitch = pitch.min(core::f64::consts::FRAC_PI_2);
        let q = Euler::new(seq, [0.4, pitch, -0.3]).to_unit_quat_unchecked();
        let sol = q.to_euler(seq, GimbalPolicy::ClosestTo(prev));
        let a = sol.euler.angles;
        assert!(
            (a[0] - prev[0]).abs() < 1e-9 && (a[2] - prev[2]).abs() < 1e-9,
            "{a:?}"
        );
        prev = a;
    }
}
