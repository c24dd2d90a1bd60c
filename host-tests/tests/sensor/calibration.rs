//! Calibration: the model `M·diag(s)·(raw − b)` against plain-array arithmetic written here,
//! inverse round trips, validation, and the same model in f32 and Q1.30.

use super::Rng;
use gyrostat::real::Q30;
use gyrostat::sensor::{InertialCalibration, MagnetometerCalibration};
use gyrostat::{Error, Mat3, Vec3};
use host_tests::reference::{M3, V3, mat_vec};

fn near_identity(rng: &mut Rng, eps: f64) -> M3 {
    let mut m = [[0.0; 3]; 3];
    for (i, row) in m.iter_mut().enumerate() {
        for (j, e) in row.iter_mut().enumerate() {
            *e = if i == j { 1.0 } else { 0.0 } + rng.range(-eps, eps);
        }
    }
    m
}

fn mat(m: &M3) -> Mat3<f64> {
    Mat3::from_rows(m[0], m[1], m[2])
}

fn v(a: V3) -> Vec3<f64> {
    Vec3::from_array(a)
}

/// The reference model: `M · (s ∘ (raw − b))`, elementwise, no matrix product of gyrostat.
fn model(m: &M3, s: V3, b: V3, raw: V3) -> V3 {
    let d = [
        (raw[0] - b[0]) * s[0],
        (raw[1] - b[1]) * s[1],
        (raw[2] - b[2]) * s[2],
    ];
    mat_vec(m, &d)
}

fn close(a: Vec3<f64>, b: V3, tol: f64) -> bool {
    (a.x - b[0]).abs() <= tol && (a.y - b[1]).abs() <= tol && (a.z - b[2]).abs() <= tol
}

#[test]
fn inertial_model_and_round_trip() {
    let mut rng = Rng::new(10);
    for _ in 0..2000 {
        let m = near_identity(&mut rng, 0.05);
        let s = [
            rng.range(0.9, 1.1),
            rng.range(0.9, 1.1),
            rng.range(0.9, 1.1),
        ];
        let b = [
            rng.range(-0.1, 0.1),
            rng.range(-0.1, 0.1),
            rng.range(-0.1, 0.1),
        ];
        let cal = InertialCalibration::try_new(mat(&m), v(s), v(b)).unwrap();
        let raw = [
            rng.range(-10.0, 10.0),
            rng.range(-10.0, 10.0),
            rng.range(-10.0, 10.0),
        ];
        let want = model(&m, s, b, raw);
        let got = cal.apply(v(raw));
        assert!(close(got, want, 1e-13), "{got:?} {want:?}");
        assert_eq!(cal.try_apply(v(raw)), Ok(got));
        let back = cal.raw_from_corrected(got);
        assert!(close(back, raw, 1e-13), "{back:?} {raw:?}");
        // Increments: the bias is a rate, subtracted over the step.
        let dt = rng.range(0.0005, 0.02);
        let inc = [raw[0] * dt, raw[1] * dt, raw[2] * dt];
        let want_inc = model(&m, s, [b[0] * dt, b[1] * dt, b[2] * dt], inc);
        let got_inc = cal.apply_increment(v(inc), dt);
        assert!(close(got_inc, want_inc, 1e-15));
        let back_inc = cal.raw_increment_from_corrected(got_inc, dt);
        assert!(close(back_inc, inc, 1e-15));
    }
}

#[test]
fn inertial_model_in_f32_and_q30() {
    let mut rng = Rng::new(11);
    let mut worst_q = 0.0f64;
    for _ in 0..2000 {
        let m = near_identity(&mut rng, 0.03);
        let s = [
            rng.range(0.95, 1.05),
            rng.range(0.95, 1.05),
            rng.range(0.95, 1.05),
        ];
        let b = [
            rng.range(-0.05, 0.05),
            rng.range(-0.05, 0.05),
            rng.range(-0.05, 0.05),
        ];
        let cal = InertialCalibration::try_new(mat(&m), v(s), v(b)).unwrap();
        let m32 = Mat3::from_rows(
            m[0].map(|x| x as f32),
            m[1].map(|x| x as f32),
            m[2].map(|x| x as f32),
        );
        let cal32 = InertialCalibration::try_new(
            m32,
            Vec3::from_array(s.map(|x| x as f32)),
            Vec3::from_array(b.map(|x| x as f32)),
        )
        .unwrap();
        let rate = [
            rng.range(-8.0, 8.0),
            rng.range(-8.0, 8.0),
            rng.range(-8.0, 8.0),
        ];
        let want = model(&m, s, b, rate);
        let got32 = cal32.apply(Vec3::from_array(rate.map(|x| x as f32)));
        // f32: inputs and coefficients rounded (relative 2⁻²⁴ each), |rate| ≤ 8·√3.
        let tol32 = 8.0 * 14.0 * f32::EPSILON as f64;
        assert!(close(
            Vec3::from_array(got32.to_array().map(f64::from)),
            want,
            tol32
        ));
        // Q1.30: increments of 1 ms steps, bias in Q7.24 rad/s.
        let q = cal.try_to_q30().unwrap();
        let dt = Q30::try_from_f64(rng.range(0.0008, 0.0012)).unwrap();
        let dtf = dt.to_f64();
        let inc = Vec3::<Q30>::try_from_f64(v(rate) * dtf).unwrap();
        let incf = inc.to_f64().to_array();
        let want_q = model(&m, s, [b[0] * dtf, b[1] * dtf, b[2] * dtf], incf);
        let got_q = q.apply_increment(inc, dt).to_f64();
        // K rounded to 2⁻³¹ per entry (|inc| ≤ 0.014), the bias to 2⁻²⁵ rad/s (× dt), the
        // bias increment and each of three dot products rounded once: a few 2⁻³⁰.
        for (g, w) in got_q.to_array().iter().zip(want_q) {
            worst_q = worst_q.max((g - w).abs());
        }
    }
    assert!(worst_q <= 3.0 * 2f64.powi(-30), "{worst_q:e}");
}

#[test]
fn q30_conversion_ranges() {
    let cal =
        InertialCalibration::try_new(Mat3::IDENTITY, Vec3::new(1.9, 1.0, 1.0), Vec3::ZERO).unwrap();
    assert!(cal.try_to_q30().is_ok());
    let cal =
        InertialCalibration::try_new(Mat3::IDENTITY, Vec3::new(2.5, 1.0, 1.0), Vec3::ZERO).unwrap();
    assert_eq!(cal.try_to_q30().map(|_| ()), Err(Error::OutOfRange));
    // K⁻¹ must fit too: a scale of 0.45 has an inverse of 2.2.
    let cal = InertialCalibration::try_new(Mat3::IDENTITY, Vec3::new(0.45, 1.0, 1.0), Vec3::ZERO)
        .unwrap();
    assert_eq!(cal.try_to_q30().map(|_| ()), Err(Error::OutOfRange));
    let cal = InertialCalibration::try_new(
        Mat3::IDENTITY,
        Vec3::new(1.0, 1.0, 1.0),
        Vec3::new(0.0, 200.0, 0.0),
    )
    .unwrap();
    assert_eq!(cal.try_to_q30().map(|_| ()), Err(Error::OutOfRange));
}

#[test]
fn inertial_validation() {
    let i = Mat3::<f64>::IDENTITY;
    let one = Vec3::new(1.0, 1.0, 1.0);
    let z = Vec3::ZERO;
    assert_eq!(
        InertialCalibration::try_new(i, Vec3::new(1.0, f64::NAN, 1.0), z),
        Err(Error::NonFinite)
    );
    assert_eq!(
        InertialCalibration::try_new(i, one, Vec3::new(f64::INFINITY, 0.0, 0.0)),
        Err(Error::NonFinite)
    );
    let mut nan = i;
    nan.m[1][2] = f64::NAN;
    assert_eq!(
        InertialCalibration::try_new(nan, one, z),
        Err(Error::NonFinite)
    );
    assert_eq!(
        InertialCalibration::try_new(i, Vec3::new(1.0, 0.0, 1.0), z),
        Err(Error::InvalidArgument)
    );
    assert_eq!(
        InertialCalibration::try_new(i, Vec3::new(1.0, -1.0, 1.0), z),
        Err(Error::InvalidArgument)
    );
    // Singular: two equal rows.
    let sing = Mat3::from_rows([1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
    assert_eq!(
        InertialCalibration::try_new(sing, one, z),
        Err(Error::Singular)
    );
    // A reflection (det −1) is a mounting error, not a calibration.
    let refl = Mat3::from_rows([0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
    assert_eq!(
        InertialCalibration::try_new(refl, one, z),
        Err(Error::InvalidArgument)
    );
    // Ill-conditioned: scales 1 and 1e-3 (condition ≈ 1000 > 100); 1 and 0.05 passes (≈ 34).
    assert_eq!(
        InertialCalibration::try_new(i, Vec3::new(1.0, 1.0, 1e-3), z),
        Err(Error::Singular)
    );
    assert!(InertialCalibration::try_new(i, Vec3::new(1.0, 1.0, 0.05), z).is_ok());
    let cal = InertialCalibration::try_new(i, one, z).unwrap();
    assert_eq!(
        cal.try_apply(Vec3::new(f64::NAN, 0.0, 0.0)),
        Err(Error::NonFinite)
    );
    let big = InertialCalibration::try_new(i, Vec3::new(10.0, 10.0, 10.0), z).unwrap();
    assert_eq!(
        big.try_apply(Vec3::new(f64::MAX, 0.0, 0.0)),
        Err(Error::NonFinite)
    );
}

#[test]
fn magnetometer_model_and_round_trip() {
    let mut rng = Rng::new(12);
    for _ in 0..2000 {
        let r = near_identity(&mut rng, 0.2);
        // Symmetric soft iron, as an ellipsoid fit gives.
        let s: M3 =
            std::array::from_fn(|i| std::array::from_fn(|j| if j < i { r[j][i] } else { r[i][j] }));
        let h = [
            rng.range(-30.0, 30.0),
            rng.range(-30.0, 30.0),
            rng.range(-30.0, 30.0),
        ];
        let cal = MagnetometerCalibration::try_new(mat(&s), v(h)).unwrap();
        let raw = [
            rng.range(-60.0, 60.0),
            rng.range(-60.0, 60.0),
            rng.range(-60.0, 60.0),
        ];
        let want = mat_vec(&s, &[raw[0] - h[0], raw[1] - h[1], raw[2] - h[2]]);
        let got = cal.apply(v(raw));
        assert!(close(got, want, 1e-12));
        assert!(close(cal.raw_from_corrected(got), raw, 1e-12));
    }
    let sing = Mat3::from_rows([1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 0.0, 1.0]);
    assert_eq!(
        MagnetometerCalibration::try_new(sing, Vec3::ZERO),
        Err(Error::Singular)
    );
    assert_eq!(
        MagnetometerCalibration::try_new(Mat3::IDENTITY, Vec3::new(0.0, f64::NAN, 0.0)),
        Err(Error::NonFinite)
    );
    let refl = Mat3::from_diagonal(Vec3::new(1.0, 1.0, -1.0));
    assert_eq!(
        MagnetometerCalibration::try_new(refl, Vec3::ZERO),
        Err(Error::InvalidArgument)
    );
}
