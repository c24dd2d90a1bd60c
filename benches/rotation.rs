//! Rotation conversions, side by side with nalgebra and glam on identical inputs.
//!
//! Each measurement converts the same batch of 256 attitudes (a fixed pseudo-random set), so the
//! per-call time is the reported time / 256. Euler angles are intrinsic ZYX (yaw, pitch, roll)
//! for all three crates: it is the only convention nalgebra's `euler_angles()` /
//! `from_euler_angles(roll, pitch, yaw)` offer (`R = R_z(yaw) R_y(pitch) R_x(roll)`), and glam's
//! `EulerRot::ZYX` is the same intrinsic sequence. glam is measured with `Quat` (f32) and `DQuat`
//! (f64).
//!
//! Run: `cargo bench --bench rotation -- --warm-up-time 1 --measurement-time 3`.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use gyrostat::rotation::{Dcm, Euler, EulerSequence};
use gyrostat::{Quat, UnitQuat, Vec3};

const N: usize = 256;

/// A fixed set of unit quaternions (xorshift, normalised), as f64 `[w, x, y, z]`.
fn quats() -> Vec<[f64; 4]> {
    let mut s: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    (0..N)
        .map(|_| {
            let q = [next(), next(), next(), next()];
            let n = q.iter().map(|c| c * c).sum::<f64>().sqrt();
            q.map(|c| c / n)
        })
        .collect()
}

macro_rules! suite {
    ($c:expr, $t:ty, $name:literal, $gq:ty, $gv:ty, $gm:ty) => {{
        let c: &mut Criterion = $c;
        let qs = quats();
        let gy: Vec<UnitQuat<$t>> = qs
            .iter()
            .map(|q| UnitQuat::new_unchecked(Quat::from_array(q.map(|x| x as $t))))
            .collect();
        let na: Vec<nalgebra::UnitQuaternion<$t>> = qs
            .iter()
            .map(|q| {
                nalgebra::UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(
                    q[0] as $t, q[1] as $t, q[2] as $t, q[3] as $t,
                ))
            })
            .collect();
        let gl: Vec<$gq> = qs
            .iter()
            .map(|q| <$gq>::from_xyzw(q[1] as $t, q[2] as $t, q[3] as $t, q[0] as $t))
            .collect();
        let seq = EulerSequence::ZYX;
        let eul: Vec<[$t; 3]> = gy.iter().map(|q| q.to_euler_angles(seq)).collect();
        let rv: Vec<[$t; 3]> = gy.iter().map(|q| q.log().to_array()).collect();

        let mut g = c.benchmark_group(concat!("quat_to_euler_zyx_", $name));
        g.bench_function("gyrostat", |b| {
            b.iter(|| {
                for q in black_box(&gy) {
                    black_box(q.to_euler_angles(seq));
                }
            })
        });
        g.bench_function("nalgebra", |b| {
            b.iter(|| {
                for q in black_box(&na) {
                    black_box(q.euler_angles());
                }
            })
        });
        g.bench_function("glam", |b| {
            b.iter(|| {
                for q in black_box(&gl) {
                    black_box(q.to_euler(glam::EulerRot::ZYX));
                }
            })
        });
        g.finish();

        let mut g = c.benchmark_group(concat!("euler_zyx_to_quat_", $name));
        g.bench_function("gyrostat", |b| {
            b.iter(|| {
                for e in black_box(&eul) {
                    black_box(Euler::new(seq, *e).to_unit_quat());
                }
            })
        });
        g.bench_function("nalgebra", |b| {
            b.iter(|| {
                for e in black_box(&eul) {
                    black_box(nalgebra::UnitQuaternion::from_euler_angles(
                        e[2], e[1], e[0],
                    ));
                }
            })
        });
        g.bench_function("glam", |b| {
            b.iter(|| {
                for e in black_box(&eul) {
                    black_box(<$gq>::from_euler(glam::EulerRot::ZYX, e[0], e[1], e[2]));
                }
            })
        });
        g.finish();

        let mut g = c.benchmark_group(concat!("quat_to_matrix_", $name));
        g.bench_function("gyrostat", |b| {
            b.iter(|| {
                for q in black_box(&gy) {
                    black_box(q.to_rotation_matrix());
                }
            })
        });
        g.bench_function("nalgebra", |b| {
            b.iter(|| {
                for q in black_box(&na) {
                    black_box(q.to_rotation_matrix());
                }
            })
        });
        g.bench_function("glam", |b| {
            b.iter(|| {
                for q in black_box(&gl) {
                    black_box(<$gm>::from_quat(*q));
                }
            })
        });
        g.finish();

        let gy_m: Vec<Dcm<$t>> = gy.iter().map(|q| Dcm::from(*q)).collect();
        let na_m: Vec<nalgebra::Rotation3<$t>> =
            na.iter().map(|q| q.to_rotation_matrix()).collect();
        let gl_m: Vec<$gm> = gl.iter().map(|q| <$gm>::from_quat(*q)).collect();
        let mut g = c.benchmark_group(concat!("matrix_to_quat_", $name));
        g.bench_function("gyrostat", |b| {
            b.iter(|| {
                for m in black_box(&gy_m) {
                    black_box(m.to_unit_quat());
                }
            })
        });
        g.bench_function("nalgebra", |b| {
            b.iter(|| {
                for m in black_box(&na_m) {
                    black_box(nalgebra::UnitQuaternion::from_rotation_matrix(m));
                }
            })
        });
        g.bench_function("glam", |b| {
            b.iter(|| {
                for m in black_box(&gl_m) {
                    black_box(<$gq>::from_mat3(m));
                }
            })
        });
        g.finish();

        let mut g = c.benchmark_group(concat!("rotvec_to_quat_", $name));
        g.bench_function("gyrostat", |b| {
            b.iter(|| {
                for v in black_box(&rv) {
                    black_box(UnitQuat::exp_unchecked(Vec3::from_array(*v)));
                }
            })
        });
        g.bench_function("nalgebra", |b| {
            b.iter(|| {
                for v in black_box(&rv) {
                    black_box(nalgebra::UnitQuaternion::from_scaled_axis(
                        nalgebra::Vector3::new(v[0], v[1], v[2]),
                    ));
                }
            })
        });
        g.bench_function("glam", |b| {
            b.iter(|| {
                for v in black_box(&rv) {
                    black_box(<$gq>::from_scaled_axis(<$gv>::new(v[0], v[1], v[2])));
                }
            })
        });
        g.finish();

        let mut g = c.benchmark_group(concat!("quat_to_rotvec_", $name));
        g.bench_function("gyrostat", |b| {
            b.iter(|| {
                for q in black_box(&gy) {
                    black_box(q.log());
                }
            })
        });
        g.bench_function("nalgebra", |b| {
            b.iter(|| {
                for q in black_box(&na) {
                    black_box(q.scaled_axis());
                }
            })
        });
        g.bench_function("glam", |b| {
            b.iter(|| {
                for q in black_box(&gl) {
                    black_box(q.to_scaled_axis());
                }
            })
        });
        g.finish();
    }};
}

fn f32_suite(c: &mut Criterion) {
    suite!(c, f32, "f32", glam::Quat, glam::Vec3, glam::Mat3);
}

fn f64_suite(c: &mut Criterion) {
    suite!(c, f64, "f64", glam::DQuat, glam::DVec3, glam::DMat3);
}

criterion_group!(benches, f32_suite, f64_suite);
criterion_main!(benches);
