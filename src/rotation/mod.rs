//! Attitude representations and the algebra of rotations.
//!
//! All types follow the crate-level conventions: Hamilton quaternions stored scalar-first,
//! attitude `q` maps body vectors to the lab frame, `R(q)` has the body axes as columns.
//!
//! - [`Quat`]: a general quaternion (no invariant).
//! - [`UnitQuat`]: a unit quaternion, the attitude; built only through a checked constructor or an
//!   explicit `_unchecked` one.
//! - [`Su2`]: the same rotation as a 2×2 complex unitary matrix of seed (6.6.4), the spinor view
//!   whose sign is physical (a 2π rotation is `−1`).

mod exp;
mod quat;
mod su2;
mod unit_quat;

pub use quat::Quat;
pub use su2::Su2;
pub use unit_quat::UnitQuat;
