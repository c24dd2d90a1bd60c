//! Per-step cost of the propagation algorithms, f32 and f64, side by side with the same update
//! built from nalgebra's `UnitQuaternion` (`from_scaled_axis` for the exponential,
//! `renormalize_fast` for the fast renormalisation, `Quaternion` arithmetic for RK4).
//!
//! `cargo bench --bench propagation -- --warm-up-time 1 --measurement-time 3`
//!
//! Every benchmark carries the attitude from one iteration to the next (a dependency chain, as
//! in a real propagator), with the inputs behind `black_box`.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use gyrostat::propagation::coning::{four_sample, one_plus_previous, three_sample};
use gyrostat::propagation::kernels::{self, cf4_step, coning2_update, magnus4_step, rk4_step};
use gyrostat::propagation::rate_samples::{gauss_rates, midpoint_rate};
use gyrostat::propagation::{ConingAccumulator, Normalization};
use gyrostat::{UnitQuat, Vec3};
use nalgebra::{Quaternion, UnitQuaternion, Vector3};

macro_rules! bench_type {
    ($c:ident, $t:ty, $name:literal) => {{
        type T = $t;
        let mut g = $c.benchmark_group(concat!("propagation/", $name));
        let th: [Vec3<T>; 4] = [
            Vec3::new(1.0e-3, -2.0e-3, 0.5e-3),
            Vec3::new(1.2e-3, -1.9e-3, 0.6e-3),
            Vec3::new(1.4e-3, -1.7e-3, 0.7e-3),
            Vec3::new(1.5e-3, -1.4e-3, 0.8e-3),
        ];
        let nth: [Vector3<T>; 4] = th.map(|v| Vector3::new(v.x, v.y, v.z));
        let w = Vec3::new(0.3 as T, -0.2, 0.5);
        let nw = Vector3::new(w.x, w.y, w.z);
        let dt: T = 1e-3;
        let window: [Vec3<T>; 4] = th.map(|v| v.scale(1000.0));
        let fast = Normalization::Fast;

        // Exact constant-rate step + fast renormalisation.
        let mut q = UnitQuat::<T>::IDENTITY;
        g.bench_function("exp_step/gyrostat", |b| {
            b.iter(|| {
                q = fast.apply(kernels::step_constant_rate(q, black_box(w), black_box(dt)));
                q
            })
        });
        let mut nq = UnitQuaternion::<T>::identity();
        g.bench_function("exp_step/nalgebra", |b| {
            b.iter(|| {
                nq *= UnitQuaternion::from_scaled_axis(black_box(nw) * black_box(dt));
                nq.renormalize_fast();
                nq
            })
        });

        // One increment with the previous-interval correction.
        g.bench_function("coning1/gyrostat", |b| {
            b.iter(|| {
                q = q
                    .mul_exp_unchecked(one_plus_previous(black_box(th[0]), black_box(th[1])), fast);
                q
            })
        });
        g.bench_function("coning1/nalgebra", |b| {
            b.iter(|| {
                let (p, c) = (black_box(nth[0]), black_box(nth[1]));
                nq *= UnitQuaternion::from_scaled_axis(c + p.cross(&c) * (1.0 / 12.0));
                nq.renormalize_fast();
                nq
            })
        });

        // 2-sample coning + exponential + fast renormalisation (the M4F target update).
        g.bench_function("coning2/gyrostat", |b| {
            b.iter(|| {
                q = coning2_update(q, black_box(th[0]), black_box(th[1]));
                q
            })
        });
        g.bench_function("coning2/nalgebra", |b| {
            b.iter(|| {
                let (a, c) = (black_box(nth[0]), black_box(nth[1]));
                nq *= UnitQuaternion::from_scaled_axis(a + c + a.cross(&c) * (2.0 / 3.0));
                nq.renormalize_fast();
                nq
            })
        });

        g.bench_function("coning3/gyrostat", |b| {
            b.iter(|| {
                let t = black_box(th);
                q = q.mul_exp_unchecked(three_sample(t[0], t[1], t[2]), fast);
                q
            })
        });
        g.bench_function("coning3/nalgebra", |b| {
            b.iter(|| {
                let t = black_box(nth);
                let phi =
                    t[0] + t[1] + t[2] + (t[0] * (9.0 / 20.0) + t[1] * (27.0 / 20.0)).cross(&t[2]);
                nq *= UnitQuaternion::from_scaled_axis(phi);
                nq.renormalize_fast();
                nq
            })
        });

        g.bench_function("coning4/gyrostat", |b| {
            b.iter(|| {
                let t = black_box(th);
                q = q.mul_exp_unchecked(four_sample(t[0], t[1], t[2], t[3]), fast);
                q
            })
        });
        g.bench_function("coning4/nalgebra", |b| {
            b.iter(|| {
                let t = black_box(nth);
                let c = t[0] * (54.0 / 105.0) + t[1] * (92.0 / 105.0) + t[2] * (214.0 / 105.0);
                let phi = t[0] + t[1] + t[2] + t[3] + c.cross(&t[3]);
                nq *= UnitQuaternion::from_scaled_axis(phi);
                nq.renormalize_fast();
                nq
            })
        });

        // Two-speed: one high-rate accumulation (per gyro sample, no exponential).
        let mut acc = ConingAccumulator::<T>::new();
        g.bench_function("two_speed_push/gyrostat", |b| {
            b.iter(|| {
                acc.push_unchecked(black_box(th[2]));
                if acc.count() >= 1000 {
                    let _ = acc.take();
                }
            })
        });
        let (mut na, mut nb, mut np) = (
            Vector3::<T>::zeros(),
            Vector3::<T>::zeros(),
            Vector3::<T>::zeros(),
        );
        g.bench_function("two_speed_push/nalgebra", |b| {
            b.iter(|| {
                let d = black_box(nth[2]);
                nb += (na + np * (1.0 / 6.0)).cross(&d) * 0.5;
                na += d;
                np = d;
                black_box(&nb);
            })
        });

        // Rate samples: interpolation to the nodes + step + (RK4) renormalisation.
        let nwin: [Vector3<T>; 4] = window.map(|v| Vector3::new(v.x, v.y, v.z));
        let (g1, _) = gauss_rates(&window, 2);
        let wm = midpoint_rate(&window, 2);
        g.bench_function("magnus4/gyrostat", |b| {
            b.iter(|| {
                let (w1, w2) = gauss_rates(black_box(&window), 2);
                q = fast.apply(magnus4_step(q, w1, w2, black_box(dt)));
                q
            })
        });
        // nalgebra: the same cubic Lagrange weights at the nodes of the last interval of the
        // window (computed once outside the loop, as gyrostat's are constants).
        let lag = |tau: T| -> [T; 4] {
            let l0 = -(tau - 1.0) * (tau - 2.0) * (tau - 3.0) / 6.0;
            let l1 = tau * (tau - 2.0) * (tau - 3.0) / 2.0;
            let l2 = -tau * (tau - 1.0) * (tau - 3.0) / 2.0;
            let l3 = tau * (tau - 1.0) * (tau - 2.0) / 6.0;
            [l0, l1, l2, l3]
        };
        let s3 = (3.0 as T).sqrt();
        let (n1, n2, nm) = (lag(2.5 - s3 / 6.0), lag(2.5 + s3 / 6.0), lag(2.5));
        let interp = |win: &[Vector3<T>; 4], l: &[T; 4]| {
            win[0] * l[0] + win[1] * l[1] + win[2] * l[2] + win[3] * l[3]
        };
        assert!((interp(&nwin, &n1) - Vector3::new(g1.x, g1.y, g1.z)).norm() < 1e-4);
        assert!((interp(&nwin, &nm) - Vector3::new(wm.x, wm.y, wm.z)).norm() < 1e-4);
        g.bench_function("magnus4/nalgebra", |b| {
            b.iter(|| {
                let win = black_box(&nwin);
                let (w1, w2) = (interp(win, &n1), interp(win, &n2));
                let h = black_box(dt);
                let phi = (w1 + w2) * (h * 0.5) + w1.cross(&w2) * (h * h * s3 / 12.0);
                nq *= UnitQuaternion::from_scaled_axis(phi);
                nq.renormalize_fast();
                nq
            })
        });
        g.bench_function("cf4/gyrostat", |b| {
            b.iter(|| {
                let (w1, w2) = gauss_rates(black_box(&window), 2);
                q = fast.apply(cf4_step(q, w1, w2, black_box(dt)));
                q
            })
        });
        g.bench_function("cf4/nalgebra", |b| {
            b.iter(|| {
                let win = black_box(&nwin);
                let (w1, w2) = (interp(win, &n1), interp(win, &n2));
                let h = black_box(dt);
                let (a, c) = (h * (0.25 + s3 / 6.0), h * (0.25 - s3 / 6.0));
                nq = nq
                    * UnitQuaternion::from_scaled_axis(w1 * a + w2 * c)
                    * UnitQuaternion::from_scaled_axis(w1 * c + w2 * a);
                nq.renormalize_fast();
                nq
            })
        });
        g.bench_function("rk4/gyrostat", |b| {
            b.iter(|| {
                let win = black_box(&window);
                let wmid = midpoint_rate(win, 2);
                q = fast.apply_quat_unchecked(rk4_step(
                    *q.as_quat(),
                    win[2],
                    wmid,
                    win[3],
                    black_box(dt),
                ));
                q
            })
        });
        g.bench_function("rk4/nalgebra", |b| {
            b.iter(|| {
                let win = black_box(&nwin);
                let wmid = interp(win, &nm);
                let h = black_box(dt);
                let f = |q: Quaternion<T>, w: Vector3<T>| q * Quaternion::from_imag(w) * 0.5;
                let q0 = *nq.quaternion();
                let k1 = f(q0, win[2]);
                let k2 = f(q0 + k1 * (h * 0.5), wmid);
                let k3 = f(q0 + k2 * (h * 0.5), wmid);
                let k4 = f(q0 + k3 * h, win[3]);
                let qn = q0 + (k1 + (k2 + k3) * 2.0 + k4) * (h / 6.0);
                nq = UnitQuaternion::new_unchecked(qn);
                nq.renormalize_fast();
                nq
            })
        });
        g.finish();
    }};
}

fn benches(c: &mut Criterion) {
    bench_type!(c, f32, "f32");
    bench_type!(c, f64, "f64");
}

criterion_group!(propagation, benches);
criterion_main!(propagation);
