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
//!
//! With `GYROSTAT_BENCH_MIN=1` the bench first prints a second table, less sensitive to a busy
//! machine than criterion's estimates: for every row, the three crates timed back to back in
//! batches (100 passes over the 256 inputs), 150 batches each, and the fastest batch kept
//! (a batch that other processes interrupted only reads slower, never faster).

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
                    black_box(Euler::new(seq, *e).to_unit_quat_unchecked());
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

/// f64 reference rotation matrix of intrinsic ZYX `(yaw, pitch, roll)`: `R_z R_y R_x`.
fn zyx_matrix(e: [f64; 3]) -> [[f64; 3]; 3] {
    let (sz, cz) = e[0].sin_cos();
    let (sy, cy) = e[1].sin_cos();
    let (sx, cx) = e[2].sin_cos();
    [
        [cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx],
        [sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx],
        [-sy, cy * sx, cy * cx],
    ]
}

/// f64 rotation matrix of a quaternion `[w, x, y, z]` (normalised here).
fn quat_matrix(q: [f64; 4]) -> [[f64; 3]; 3] {
    let n = q.iter().map(|c| c * c).sum::<f64>().sqrt();
    let [w, x, y, z] = q.map(|c| c / n);
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
        ],
        [
            2.0 * (x * y + w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - w * x),
        ],
        [
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]
}

/// Geodesic angle between two rotation matrices (atan2 form, accurate for tiny angles).
fn rot_dist(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> f64 {
    let m = |i: usize, j: usize| (0..3).map(|k| a[k][i] * b[k][j]).sum::<f64>();
    let s = 0.5
        * ((m(2, 1) - m(1, 2)).powi(2) + (m(0, 2) - m(2, 0)).powi(2) + (m(1, 0) - m(0, 1)).powi(2))
            .sqrt();
    let c = 0.5 * (m(0, 0) + m(1, 1) + m(2, 2) - 1.0);
    s.atan2(c)
}

/// Not a timing: the worst quat → ZYX Euler → rotation error of each crate, for pitch at
/// distances 0 and 1e-7 … 1e-2 from ±90° (both sides) and at generic pitches, over a grid of yaw
/// and roll; inputs are the same quaternions (rounded to the type) for all three. Printed once
/// per bench run, for f32 and f64.
macro_rules! accuracy {
    ($t:ty, $gq:ty, $name:literal) => {{
        let mut worst = [[0.0f64; 3]; 2]; // [near pole, generic][gyrostat, nalgebra, glam]
        let half_pi = core::f64::consts::FRAC_PI_2;
        let mut pitches = vec![];
        for p in [-half_pi, half_pi] {
            pitches.push((p, 0));
            for e in 2..=7 {
                let d = 10f64.powi(-e);
                pitches.push((p + d, 0));
                pitches.push((p - d, 0));
            }
        }
        for p in [-1.2, -0.4, 0.0, 0.7, 1.3] {
            pitches.push((p, 1));
        }
        for &(pitch, kind) in &pitches {
            for yaw in [-3.0, -1.7, -0.2, 0.0, 0.9, 2.4, 3.1] {
                for roll in [-2.9, -1.0, 0.0, 0.3, 1.9, 3.0] {
                    let qd =
                        Euler::new(EulerSequence::ZYX, [yaw, pitch, roll]).to_unit_quat_unchecked();
                    let qt = qd.to_array().map(|c| c as $t);
                    let r_in = quat_matrix(qt.map(|c| c as f64));
                    let gy = UnitQuat::new_unchecked(Quat::from_array(qt))
                        .to_euler_angles(EulerSequence::ZYX);
                    let na = nalgebra::UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(
                        qt[0], qt[1], qt[2], qt[3],
                    ))
                    .euler_angles();
                    let gl =
                        <$gq>::from_xyzw(qt[1], qt[2], qt[3], qt[0]).to_euler(glam::EulerRot::ZYX);
                    let outs = [
                        [gy[0], gy[1], gy[2]],
                        [na.2, na.1, na.0],
                        [gl.0, gl.1, gl.2],
                    ];
                    for (k, e) in outs.iter().enumerate() {
                        let err = if e.iter().all(|x| x.is_finite()) {
                            rot_dist(&r_in, &zyx_matrix(e.map(|x| x as f64)))
                        } else {
                            f64::INFINITY
                        };
                        worst[kind][k] = worst[kind][k].max(err);
                    }
                }
            }
        }
        println!(concat!(
            "\n",
            $name,
            " quat -> ZYX Euler -> rotation, worst geodesic error (rad):"
        ));
        println!(
            "  near pitch ±90° (0, 1e-7..1e-2): gyrostat {:.2e}, nalgebra {:.2e}, glam {:.2e}",
            worst[0][0], worst[0][1], worst[0][2]
        );
        println!(
            "  generic pitch:                   gyrostat {:.2e}, nalgebra {:.2e}, glam {:.2e}\n",
            worst[1][0], worst[1][1], worst[1][2]
        );
    }};
}

/// The fastest of 150 batches of 100 passes over `N` inputs, in ns per call.
fn min_ns<F: FnMut()>(mut f: F) -> f64 {
    let mut best = f64::MAX;
    for _ in 0..150 {
        let t = std::time::Instant::now();
        for _ in 0..100 {
            f();
        }
        best = best.min(t.elapsed().as_nanos() as f64 / (100 * N) as f64);
    }
    best
}

/// The min-of-batches table (see the crate docs), one markdown row per conversion.
macro_rules! min_table {
    ($t:ty, $name:literal, $gq:ty, $gv:ty, $gm:ty) => {{
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
        let gy_m: Vec<Dcm<$t>> = gy.iter().map(|q| Dcm::from(*q)).collect();
        let na_m: Vec<nalgebra::Rotation3<$t>> =
            na.iter().map(|q| q.to_rotation_matrix()).collect();
        let gl_m: Vec<$gm> = gl.iter().map(|q| <$gm>::from_quat(*q)).collect();
        let row = |name: &str, g: f64, n: f64, l: f64| {
            println!(
                "| `{name}_{}` | {g:.1} | {n:.1} | {l:.1} | {:.2} | {:.2} |",
                $name,
                g / n,
                g / l
            )
        };
        row(
            "quat_to_euler_zyx",
            min_ns(|| {
                for q in black_box(&gy) {
                    black_box(q.to_euler_angles(seq));
                }
            }),
            min_ns(|| {
                for q in black_box(&na) {
                    black_box(q.euler_angles());
                }
            }),
            min_ns(|| {
                for q in black_box(&gl) {
                    black_box(q.to_euler(glam::EulerRot::ZYX));
                }
            }),
        );
        row(
            "euler_zyx_to_quat",
            min_ns(|| {
                for e in black_box(&eul) {
                    black_box(Euler::new(seq, *e).to_unit_quat_unchecked());
                }
            }),
            min_ns(|| {
                for e in black_box(&eul) {
                    black_box(nalgebra::UnitQuaternion::from_euler_angles(
                        e[2], e[1], e[0],
                    ));
                }
            }),
            min_ns(|| {
                for e in black_box(&eul) {
                    black_box(<$gq>::from_euler(glam::EulerRot::ZYX, e[0], e[1], e[2]));
                }
            }),
        );
        row(
            "quat_to_matrix",
            min_ns(|| {
                for q in black_box(&gy) {
                    black_box(q.to_rotation_matrix());
                }
            }),
            min_ns(|| {
                for q in black_box(&na) {
                    black_box(q.to_rotation_matrix());
                }
            }),
            min_ns(|| {
                for q in black_box(&gl) {
                    black_box(<$gm>::from_quat(*q));
                }
            }),
        );
        row(
            "matrix_to_quat",
            min_ns(|| {
                for m in black_box(&gy_m) {
                    black_box(m.to_unit_quat());
                }
            }),
            min_ns(|| {
                for m in black_box(&na_m) {
                    black_box(nalgebra::UnitQuaternion::from_rotation_matrix(m));
                }
            }),
            min_ns(|| {
                for m in black_box(&gl_m) {
                    black_box(<$gq>::from_mat3(m));
                }
            }),
        );
        row(
            "rotvec_to_quat",
            min_ns(|| {
                for v in black_box(&rv) {
                    black_box(UnitQuat::exp_unchecked(Vec3::from_array(*v)));
                }
            }),
            min_ns(|| {
                for v in black_box(&rv) {
                    black_box(nalgebra::UnitQuaternion::from_scaled_axis(
                        nalgebra::Vector3::new(v[0], v[1], v[2]),
                    ));
                }
            }),
            min_ns(|| {
                for v in black_box(&rv) {
                    black_box(<$gq>::from_scaled_axis(<$gv>::new(v[0], v[1], v[2])));
                }
            }),
        );
        row(
            "quat_to_rotvec",
            min_ns(|| {
                for q in black_box(&gy) {
                    black_box(q.log());
                }
            }),
            min_ns(|| {
                for q in black_box(&na) {
                    black_box(q.scaled_axis());
                }
            }),
            min_ns(|| {
                for q in black_box(&gl) {
                    black_box(q.to_scaled_axis());
                }
            }),
        );
    }};
}

fn min_report(_: &mut Criterion) {
    if std::env::var_os("GYROSTAT_BENCH_MIN").is_none() {
        return;
    }
    println!("\nfastest batch, ns per call (GYROSTAT_BENCH_MIN):");
    println!("| conversion | gyrostat | nalgebra | glam | gyrostat / nalgebra | gyrostat / glam |");
    println!("|---|---:|---:|---:|---:|---:|");
    min_table!(f32, "f32", glam::Quat, glam::Vec3, glam::Mat3);
    min_table!(f64, "f64", glam::DQuat, glam::DVec3, glam::DMat3);
    println!();
}

fn accuracy_report(_: &mut Criterion) {
    accuracy!(f32, glam::Quat, "f32");
    accuracy!(f64, glam::DQuat, "f64");
}

criterion_group!(benches, accuracy_report, min_report, f32_suite, f64_suite);
criterion_main!(benches);
