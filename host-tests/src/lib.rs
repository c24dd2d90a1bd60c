//! Host-side test support for gyrostat: an independent `std` f64 reference.
//!
//! Nothing here calls gyrostat's algorithms: the reference is written differently on purpose
//! (rotation matrices from the Rodrigues formula, spinors as explicit complex 2×2 matrices), so
//! that an agreement between the two is evidence, not a tautology. Each area of the library has
//! its own module.
//!
//! - [`mod@reference`]: matrices, Rodrigues rotations (6.6.13)–(6.6.15), SU(2) matrices (6.6.4).
//! - [`ref_rotation`]: Euler-angle matrices and representation conversions (issue: rotations).
//! - [`ref_propagation`]: closed-form coning motion and kinematics (issue: propagation).
//! - [`ref_dynamics`]: rigid-body reference integrators and closed forms (issue: dynamics).
//! - [`ref_exact`]: quadrature elliptic integrals, Newton-inverted Jacobi functions and a tiny-step
//!   RK4 free rigid body (issue 5: exact free rigid body).
//! - [`tolerance`]: the per-type tolerances shared by the comparison tests.
//! - [`widen`]: gyrostat values of any scalar type as plain f64 arrays.

pub mod ref_dynamics;
pub mod ref_exact;
pub mod ref_propagation;
pub mod ref_rotation;
pub mod reference;
pub mod tolerance;
pub mod widen;
