//! Widening gyrostat values of any scalar type to the reference's plain f64 arrays.

use gyrostat::{Mat3, Real, UnitQuat, Vec3};

/// `[w, x, y, z]` in f64.
pub fn q64<T: Real>(q: UnitQuat<T>) -> [f64; 4] {
    q.to_array().map(|c| c.to_f64())
}

/// `[x, y, z]` in f64.
pub fn v64<T: Real>(v: Vec3<T>) -> [f64; 3] {
    v.to_array().map(|c| c.to_f64())
}

/// `m[row][col]` in f64.
pub fn m64<T: Real>(m: &Mat3<T>) -> [[f64; 3]; 3] {
    m.m.map(|r| r.map(|c| c.to_f64()))
}
