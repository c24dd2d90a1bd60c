//! Cost of one step of each dynamics integrator (f32 and f64): rigid body with a diagonal and
//! with a full tensor, and a gyrostat with 4 reaction wheels and an external torque, each on a
//! plain `State` and on a `CompensatedState` (`…_compensated` rows); and of one evaluation of
//! the exact free rigid body.

use criterion::{Criterion, criterion_group, criterion_main};
use gyrostat::dynamics::{
    CompensatedState, FreeRigidBody, Gyrostat, Inertia, Integrator, State, Wheel, WheelCommand,
};
use gyrostat::{Mat3, Real, UnitQuat, Vec3};
use std::hint::black_box;

fn v<T: Real>(a: [f64; 3]) -> Vec3<T> {
    Vec3::new(T::from_f64(a[0]), T::from_f64(a[1]), T::from_f64(a[2]))
}

fn bench_type<T: Real>(c: &mut Criterion, ty: &str) {
    let diag = Gyrostat::rigid(Inertia::try_from_principal(v::<T>([6.0, 4.0, 3.0])).unwrap());
    let full = Gyrostat::rigid(
        Inertia::try_from_tensor(Mat3::from_rows(
            [3.0, -0.4, 0.25].map(T::from_f64),
            [-0.4, 4.0, 0.3].map(T::from_f64),
            [0.25, 0.3, 5.0].map(T::from_f64),
        ))
        .unwrap(),
    );
    let s0 = State::new(UnitQuat::IDENTITY, v::<T>([0.3, 4.0, 0.05]));
    let dt = T::from_f64(0.01);
    let mut g = c.benchmark_group(format!("dynamics_step_{ty}"));
    for integ in Integrator::ALL {
        let name = integ.name();
        g.bench_function(format!("rigid_diag/{name}"), |b| {
            let mut s = s0;
            b.iter(|| {
                s = diag.step(integ, black_box(&s), dt).unwrap();
            })
        });
        g.bench_function(format!("rigid_full/{name}"), |b| {
            let mut s = s0;
            b.iter(|| {
                s = full.step(integ, black_box(&s), dt).unwrap();
            })
        });
        g.bench_function(format!("rigid_diag_compensated/{name}"), |b| {
            let mut s = CompensatedState::new(s0);
            b.iter(|| {
                s = diag.step(integ, black_box(&s), dt).unwrap();
            })
        });
        g.bench_function(format!("rigid_full_compensated/{name}"), |b| {
            let mut s = CompensatedState::new(s0);
            b.iter(|| {
                s = full.step(integ, black_box(&s), dt).unwrap();
            })
        });
    }
    let a = 1.0 / 3.0f64.sqrt();
    let wheels = [
        Wheel::try_new(v::<T>([1.0, 0.0, 0.0]), T::from_f64(0.02)).unwrap(),
        Wheel::try_new(v::<T>([0.0, 1.0, 0.0]), T::from_f64(0.02)).unwrap(),
        Wheel::try_new(v::<T>([0.0, 0.0, 1.0]), T::from_f64(0.02)).unwrap(),
        Wheel::try_new(v::<T>([a, a, a]), T::from_f64(0.02)).unwrap(),
    ];
    let gyro = Gyrostat::new(*full.model(), wheels);
    let cmd = WheelCommand::Torque([0.001, -0.002, 0.0005, 0.0].map(T::from_f64));
    let tau = v::<T>([0.01, 0.0, -0.005]);
    for integ in Integrator::ALL {
        let name = integ.name();
        g.bench_function(format!("gyrostat4_torque/{name}"), |b| {
            let mut s = gyro
                .try_state_from_omega(UnitQuat::IDENTITY, v([0.1, 0.5, 0.2]), [T::ZERO; 4])
                .unwrap();
            b.iter(|| {
                let held = gyro.control(&s, dt, tau, &cmd);
                s = gyro
                    .step_with(integ, black_box(&s), T::ZERO, dt, held)
                    .unwrap();
            })
        });
        g.bench_function(format!("gyrostat4_torque_compensated/{name}"), |b| {
            let mut s = CompensatedState::new(
                gyro.try_state_from_omega(UnitQuat::IDENTITY, v([0.1, 0.5, 0.2]), [T::ZERO; 4])
                    .unwrap(),
            );
            b.iter(|| {
                let held = gyro.control(s.state(), dt, tau, &cmd);
                s = gyro
                    .step_with(integ, black_box(&s), T::ZERO, dt, held)
                    .unwrap();
            })
        });
    }
    let exact = FreeRigidBody::try_new(
        &Inertia::try_from_principal(v::<T>([1.0, 2.0, 3.0])).unwrap(),
        &State::new(UnitQuat::IDENTITY, v([0.4, 0.5, 2.5])),
    )
    .unwrap();
    g.bench_function("exact_free_body/state_at", |b| {
        let mut t = T::ZERO;
        b.iter(|| {
            t += T::from_f64(1e-3);
            black_box(exact.state_at_unchecked(black_box(t)))
        })
    });
    g.finish();
}

fn benches(c: &mut Criterion) {
    bench_type::<f32>(c, "f32");
    bench_type::<f64>(c, "f64");
}

criterion_group!(dynamics, benches);
criterion_main!(dynamics);
