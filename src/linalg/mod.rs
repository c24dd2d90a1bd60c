//! Linear-algebra primitives: only what the library needs.
//!
//! [`Vec3`] and [`Mat3`] (row-major, `m[row][col]`) for vectors, rotation matrices and inertia
//! tensors; [`Axis`] for the coordinate axes; [`Complex`] for the SU(2) spinor matrices of seed
//! (6.6.4).

mod axis;
mod complex;
mod mat3;
mod vec3;

pub use axis::Axis;
pub use complex::Complex;
pub use mat3::Mat3;
pub use vec3::Vec3;
