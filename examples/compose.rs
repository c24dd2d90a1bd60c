//! Host demo: compose a fixed set of rotations in f32 and print them beside the f64 computation,
//! with the error.
//!
//! ```text
//! cargo run --release --example compose
//! ```
//! The same cases as the firmware example `fw_rotations` (examples/fw/rotation_cases.rs): for each,
//! `q = q(axis₁, angle₁) ⊗ q(axis₂, angle₂)` and `v' = q v q*`, computed by gyrostat in f32 and in
//! f64, and the f64 rotation matrix `R₁R₂` built from the Rodrigues formula (6.6.15) as a check
//! that does not use quaternions. Errors are the largest absolute component differences.

include!("fw/rotation_cases.rs");

use gyrostat::{Real, UnitQuat, Vec3};

/// Rodrigues rotation matrix (6.6.15) in plain f64.
fn rodrigues(axis: [f64; 3], angle: f64) -> [[f64; 3]; 3] {
    let n = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
    let [x, y, z] = axis.map(|c| c / n);
    let (s, c) = angle.sin_cos();
    let k = 1.0 - c;
    [
        [c + k * x * x, k * x * y - z * s, k * x * z + y * s],
        [k * x * y + z * s, c + k * y * y, k * y * z - x * s],
        [k * x * z - y * s, k * y * z + x * s, c + k * z * z],
    ]
}

fn mat_vec(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2])
}

fn mat_mul(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| (0..3).map(|k| a[i][k] * b[k][j]).sum()))
}

fn compose<T: Real>(
    c: &([f32; 3], f32, [f32; 3], f32, [f32; 3]),
) -> Result<([f64; 4], [f64; 3]), gyrostat::Error> {
    let v3 = |a: [f32; 3]| {
        Vec3::new(
            T::from_f64(a[0].into()),
            T::from_f64(a[1].into()),
            T::from_f64(a[2].into()),
        )
    };
    let q1 = UnitQuat::try_from_axis_angle(v3(c.0), T::from_f64(c.1.into()))?;
    let q2 = UnitQuat::try_from_axis_angle(v3(c.2), T::from_f64(c.3.into()))?;
    let q = q1 * q2;
    let r = q.rotate(v3(c.4));
    Ok((
        q.to_array().map(|e| e.to_f64()),
        [r.x.to_f64(), r.y.to_f64(), r.z.to_f64()],
    ))
}

fn main() -> Result<(), gyrostat::Error> {
    println!("gyrostat compose demo: q = q(a1,t1) * q(a2,t2), v' = q v q*   (f32 core vs f64)");
    println!(
        "{:>4} {:>44} {:>10} {:>10} {:>10}",
        "case", "q (f32: w, x, y, z)", "|dq|", "|dv|", "|dv| R64"
    );
    let mut worst: f64 = 0.0;
    for (i, c) in CASES.iter().enumerate() {
        let (q32, v32) = compose::<f32>(c)?;
        let (q64, v64) = compose::<f64>(c)?;
        let widen = |a: [f32; 3]| a.map(f64::from);
        let rm = mat_mul(
            &rodrigues(widen(c.0), c.1.into()),
            &rodrigues(widen(c.2), c.3.into()),
        );
        let v_ref = mat_vec(&rm, widen(c.4));
        let dq = (0..4).map(|k| (q32[k] - q64[k]).abs()).fold(0.0, f64::max);
        let dv = (0..3).map(|k| (v32[k] - v64[k]).abs()).fold(0.0, f64::max);
        let dr = (0..3)
            .map(|k| (v64[k] - v_ref[k]).abs())
            .fold(0.0, f64::max);
        worst = worst.max(dq).max(dv);
        println!(
            "{i:>4} {:>10.7} {:>10.7} {:>10.7} {:>10.7} {dq:>10.2e} {dv:>10.2e} {dr:>10.2e}",
            q32[0], q32[1], q32[2], q32[3]
        );
    }
    println!(
        "worst f32 error vs f64: {worst:.2e} (f32 epsilon {:.2e})",
        f32::EPSILON
    );
    println!(
        "|dv| R64: the f64 quaternion result against the f64 Rodrigues matrix product (6.6.15)"
    );
    Ok(())
}
