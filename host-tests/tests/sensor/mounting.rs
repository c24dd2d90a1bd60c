//! Mounting: the 24 remaps against the proper signed permutation matrices enumerated here by
//! brute force, parsing, and rotations of vectors and attitudes.

use super::Rng;
use gyrostat::real::Q30;
use gyrostat::sensor::{AxisRemap, Mounting};
use gyrostat::{Axis, Error, Quat, UnitQuat, Vec3};
use host_tests::reference::{M3, det, mat_mul, mat_vec, qmul, qrotate, transpose};
use std::collections::BTreeSet;

type IM = [[i32; 3]; 3];

/// Every 3×3 matrix with entries in {−1, 0, 1} that is orthogonal with determinant +1.
fn proper_signed_permutations() -> BTreeSet<IM> {
    let mut out = BTreeSet::new();
    for code in 0..3i32.pow(9) {
        let mut m = [[0i32; 3]; 3];
        let mut c = code;
        for row in m.iter_mut() {
            for e in row.iter_mut() {
                *e = c % 3 - 1;
                c /= 3;
            }
        }
        let f: M3 = m.map(|r| r.map(f64::from));
        let ident = mat_mul(&f, &transpose(&f));
        let orthogonal =
            (0..3).all(|i| (0..3).all(|j| ident[i][j] == if i == j { 1.0 } else { 0.0 }));
        if orthogonal && det(&f) == 1.0 {
            out.insert(m);
        }
    }
    out
}

fn as_int(r: &AxisRemap) -> IM {
    r.matrix::<f64>().m.map(|row| row.map(|x| x as i32))
}

fn text(r: &AxisRemap) -> String {
    r.source()
        .iter()
        .zip(r.negate())
        .map(|(a, n)| {
            let name = match a {
                Axis::X => "x",
                Axis::Y => "y",
                Axis::Z => "z",
            };
            if n {
                format!("-{name}")
            } else {
                name.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join(",")
}

#[test]
fn the_24_remaps_are_the_proper_signed_permutations() {
    let want = proper_signed_permutations();
    assert_eq!(want.len(), 24);
    let all = AxisRemap::all();
    let got: BTreeSet<IM> = all.iter().map(as_int).collect();
    assert_eq!(got, want);
    // try_new accepts exactly the 24 of the 48 signed permutations.
    let axes = [Axis::X, Axis::Y, Axis::Z];
    let mut accepted = 0;
    for a in axes {
        for b in axes {
            for c in axes {
                for bits in 0..8 {
                    let neg = [bits & 1 != 0, bits & 2 != 0, bits & 4 != 0];
                    let r = AxisRemap::try_new([a, b, c], neg);
                    if a == b || b == c || a == c {
                        assert_eq!(r, Err(Error::InvalidArgument));
                        continue;
                    }
                    // The matrix built here: row i has ±1 in column source[i].
                    let mut m = [[0.0; 3]; 3];
                    for (i, (s, n)) in [a, b, c].iter().zip(neg).enumerate() {
                        m[i][s.index()] = if n { -1.0 } else { 1.0 };
                    }
                    if det(&m) > 0.0 {
                        let r = r.unwrap();
                        accepted += 1;
                        assert_eq!(r.matrix::<f64>().m, m);
                        assert_eq!(AxisRemap::try_parse(&text(&r)), Ok(r));
                    } else {
                        assert_eq!(r, Err(Error::NotRotation));
                    }
                }
            }
        }
    }
    assert_eq!(accepted, 24);
}

#[test]
fn remap_applies_as_its_matrix_in_every_format() {
    let mut rng = Rng::new(20);
    for r in AxisRemap::all() {
        let m = r.matrix::<f64>().m;
        let q = r.to_unit_quat::<f64>();
        let inv = r.inverse();
        for _ in 0..50 {
            let v = [
                rng.range(-3.0, 3.0),
                rng.range(-3.0, 3.0),
                rng.range(-3.0, 3.0),
            ];
            let want = mat_vec(&m, &v);
            assert_eq!(r.apply(Vec3::from_array(v)).to_array(), want);
            assert_eq!(inv.apply(r.apply(Vec3::from_array(v))).to_array(), v);
            let qa = q.to_array();
            let rot = qrotate(qa, v);
            for k in 0..3 {
                assert!((rot[k] - want[k]).abs() < 1e-15 * 4.0, "{r:?}");
            }
            // Exact in f32 and Q1.30 (a permutation and negations).
            let v32 = Vec3::from_array(v.map(|x| x as f32));
            assert_eq!(
                r.apply(v32).to_array(),
                mat_vec(&m, &v.map(|x| x as f32 as f64)).map(|x| x as f32)
            );
            let vq = Vec3::<Q30>::try_from_f64(Vec3::from_array(v.map(|x| x / 2.0))).unwrap();
            let got = r.apply(vq).to_f64().to_array();
            assert_eq!(got, mat_vec(&m, &vq.to_f64().to_array()));
        }
    }
    // Extremes of Q1.30: negation of the symmetric range is exact.
    let r = AxisRemap::try_parse("-x,-y,z").unwrap();
    let out = r.apply(Vec3::new(Q30::MAX, Q30::MIN, Q30::MAX));
    assert_eq!((out.x, out.y, out.z), (Q30::MIN, Q30::MAX, Q30::MAX));
}

#[test]
fn parse_forms_and_errors() {
    let r = AxisRemap::try_parse("x,-z,y").unwrap();
    assert_eq!(
        r.apply(Vec3::new(1.0, 2.0, 3.0)).to_array(),
        [1.0, -3.0, 2.0]
    );
    assert_eq!(AxisRemap::try_parse(" +X , -Z ,Y "), Ok(r));
    assert_eq!(AxisRemap::try_parse("x,y,z"), Ok(AxisRemap::IDENTITY));
    for bad in [
        "", "x,y", "x,y,z,x", "x,y,w", "x,,z", "--x,y,z", "x,x,z", "xy,z,x", "x;y;z",
    ] {
        assert_eq!(
            AxisRemap::try_parse(bad),
            Err(Error::InvalidArgument),
            "{bad}"
        );
    }
    for refl in ["-x,y,z", "y,x,z", "x,z,y", "-x,-y,-z"] {
        assert_eq!(
            AxisRemap::try_parse(refl),
            Err(Error::NotRotation),
            "{refl}"
        );
    }
}

#[test]
fn mounting_rotation_of_vectors_and_attitudes() {
    let mut rng = Rng::new(21);
    for _ in 0..500 {
        let qbs = [
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ];
        let n = qbs.iter().map(|x| x * x).sum::<f64>().sqrt();
        let qbs = qbs.map(|x| x / n);
        let qls = [
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ];
        let n = qls.iter().map(|x| x * x).sum::<f64>().sqrt();
        let qls = qls.map(|x| x / n);
        let mount = Mounting::new(UnitQuat::try_new(Quat::from_array(qbs)).unwrap());
        let v_s = [
            rng.range(-2.0, 2.0),
            rng.range(-2.0, 2.0),
            rng.range(-2.0, 2.0),
        ];
        let v_b = mount.to_body(Vec3::from_array(v_s)).to_array();
        let want = qrotate(qbs, v_s);
        assert!((0..3).all(|k| (v_b[k] - want[k]).abs() < 1e-14));
        // The body attitude maps the body vector to the same lab vector as the sensor attitude
        // maps the sensor vector.
        let q_lb = mount.body_attitude(UnitQuat::try_new(Quat::from_array(qls)).unwrap());
        let lab_from_body = qrotate(q_lb.to_array(), v_b);
        let lab_from_sensor = qrotate(qls, v_s);
        assert!((0..3).all(|k| (lab_from_body[k] - lab_from_sensor[k]).abs() < 1e-14));
        let back = mount.sensor_attitude(q_lb).to_array();
        let d = qmul(back, [qls[0], -qls[1], -qls[2], -qls[3]]);
        assert!((d[0].abs() - 1.0).abs() < 1e-14);
    }
    // From a remap.
    let r = AxisRemap::try_parse("z,x,y").unwrap();
    let m: Mounting<f64> = r.into();
    let got = m.to_body(Vec3::new(1.0, 2.0, 3.0)).to_array();
    assert!((0..3).all(|k| (got[k] - [3.0, 1.0, 2.0][k]).abs() < 1e-15));
}
