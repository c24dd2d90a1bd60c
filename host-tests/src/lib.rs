//! Host-side test support for gyrostat: an independent `std` f64 reference and one harness.
//!
//! Nothing here calls gyrostat's algorithms: the reference is written differently on purpose
//! (rotation matrices from the Rodrigues formula, spinors as explicit complex 2×2 matrices,
//! dynamics integrated on matrices and body rates), so that an agreement between the two is
//! evidence, not a tautology.
//!
//! - [`mod@reference`]: the shared f64 toolkit — vectors, matrices, quaternion arrays, Rodrigues
//!   rotations (6.6.13)–(6.6.15), SU(2) matrices (6.6.4), the angle between attitudes.
//! - [`ref_rotation`]: Euler-angle matrices and representation conversions.
//! - [`ref_propagation`]: closed-form coning motion and spin precession.
//! - [`ref_dynamics`]: rigid-body reference integrators, Hamiltonian models, eigen-solver.
//! - [`ref_exact`]: quadrature elliptic integrals, Newton-inverted Jacobi functions and a
//!   tiny-step RK4 free rigid body.
//! - [`tolerance`]: the one tolerance trait, [`tolerance::Tolerance`].
//! - [`cast`]: gyrostat values of any scalar type to and from f64 arrays.
//! - [`examples`]: the firmware examples' targets and the output CI hands to the tests.
//! - [`per_type!`]: runs test items for f32 and for f64.
//! - [`campaign`]: the adversarial input campaign (generators, checks, runner, `ROBUSTNESS.md`
//!   tables); [`family!`] declares one API family.

pub mod broad;
pub mod campaign;
pub mod cast;
pub mod examples;
pub mod ref_dynamics;
pub mod ref_exact;
pub mod ref_propagation;
pub mod ref_rotation;
pub mod reference;
pub mod tolerance;

/// Instantiates the enclosed items once per scalar type: in `mod on_f32` with `type T = f32`
/// and in `mod on_f64` with `type T = f64`, with `Real`, `Ring` and `Tolerance` in scope (the
/// pattern of glam's `impl_quat_tests!`). A test is written once, in terms of `T`, and its
/// per-type bounds come from
/// [`tolerance::Tolerance`] (`T::SHORT`, `T::CONTRACT`, `T::per_type(f32_bound, f64_bound)`);
/// the two instances run as `on_f32::name` and `on_f64::name`. The items see the enclosing
/// module (`use super::*`), so shared helpers stay outside; invoke it once per module.
///
/// ```
/// host_tests::per_type! {
///     // In a test file: `#[test] fn two_is_one_plus_one()`.
///     pub fn two_is_one_plus_one() {
///         let two = T::ONE + T::ONE;
///         assert!((two.to_f64() - 2.0).abs() <= T::SHORT, "{}", T::NAME);
///     }
/// }
/// # fn main() { on_f32::two_is_one_plus_one(); on_f64::two_is_one_plus_one(); }
/// ```
#[macro_export]
macro_rules! per_type {
    ($($item:item)*) => {
        #[allow(unused_imports)]
        mod on_f32 {
            use super::*;
            use $crate::tolerance::Tolerance;
            use gyrostat::{Real, Ring};
            /// The scalar type of this instance.
            type T = f32;
            $($item)*
        }
        #[allow(unused_imports)]
        mod on_f64 {
            use super::*;
            use $crate::tolerance::Tolerance;
            use gyrostat::{Real, Ring};
            /// The scalar type of this instance.
            type T = f64;
            $($item)*
        }
    };
}
