//! The one tolerance trait: every per-type bound of the comparison tests goes through it.
//!
//! The numbers compared are mostly of order one (unit quaternions, rotation matrices, unit-norm
//! vectors), so the tolerances are absolute unless a test says otherwise. Each bound states the
//! rounding budget it allows, where it is defined: the two shared ones here, the others at the
//! test that uses them through [`Tolerance::per_type`].

use gyrostat::Real;

/// A scalar type under test (f32 or f64) with its tolerances. Each bound is a two-entry table,
/// f32 first, read at the type's [`Tolerance::INDEX`].
pub trait Tolerance: Real {
    /// The type's column in the per-type tables: 0 for f32, 1 for f64.
    const INDEX: usize;

    /// The type's name in test output: `"f32"` or `"f64"`.
    const NAME: &'static str = ["f32", "f64"][Self::INDEX];

    /// Absolute tolerance for a short chain of operations on order-one values.
    ///
    /// f32: 2e-6 ≈ 17 ulp at 1.0 (each of ~10 roundings of ≤ 0.5 ulp, plus the ≤ 1-ulp sin/cos
    /// at the inputs, with margin). f64: 1e-13 ≈ 450 ulp at 1.0, the same budget scaled by the
    /// larger number of roundings a proptest input chain can accumulate.
    const SHORT: f64 = [2e-6, 1e-13][Self::INDEX];

    /// The accuracy contract of gyrostat's `rotation` module (rad, stated in its docs): f32 1e-6
    /// (inputs rounded to f32), f64 1e-14.
    const CONTRACT: f64 = [1e-6, 1e-14][Self::INDEX];

    /// A bound stated per type at the test that uses it: `f32_bound` for f32, `f64_bound` for
    /// f64. The test's doc comment says where each number comes from.
    fn per_type(f32_bound: f64, f64_bound: f64) -> f64 {
        [f32_bound, f64_bound][Self::INDEX]
    }
}

impl Tolerance for f32 {
    const INDEX: usize = 0;
}

impl Tolerance for f64 {
    const INDEX: usize = 1;
}
