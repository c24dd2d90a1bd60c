//! Tolerances for comparing gyrostat against the f64 reference, per scalar type.
//!
//! The numbers compared are of order one (unit quaternions, rotation matrices, unit-norm
//! vectors), so the tolerances are absolute. Each states the rounding budget it allows.

/// A scalar type under test, with its comparison tolerance for short (a few operations) chains
/// of order-one quantities.
pub trait Tolerance {
    /// Absolute tolerance for a short chain of operations on order-one values.
    ///
    /// f32: 2e-6 ≈ 17 ulp at 1.0 (each of ~10 roundings of ≤ 0.5 ulp, plus libm's ≤ 1 ulp
    /// sin/cos at the inputs, with margin). f64: 1e-13 ≈ 450 ulp at 1.0, the same budget scaled
    /// by the larger number of roundings a proptest input chain can accumulate.
    const SHORT: f64;
}

impl Tolerance for f32 {
    const SHORT: f64 = 2e-6;
}

impl Tolerance for f64 {
    const SHORT: f64 = 1e-13;
}

/// The accuracy contract of gyrostat's `rotation` module (rad), per type: f32 1e-6 (inputs
/// rounded to f32), f64 1e-14. The contract itself is stated in the `rotation` module docs.
pub trait Contract: gyrostat::Real {
    /// Worst allowed rotation error, radians.
    const CONTRACT: f64;
}

impl Contract for f32 {
    const CONTRACT: f64 = 1e-6;
}

impl Contract for f64 {
    const CONTRACT: f64 = 1e-14;
}
