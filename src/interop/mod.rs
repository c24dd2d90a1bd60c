//! Optional integrations, one file per dependency.
//!
//! - `defmt` (feature `defmt`): `defmt::Format`, for logging on targets, for the foundation
//!   types (`Vec3`, `Mat3`, `Complex`, `Quat`, `UnitQuat`, `Su2`) and [`crate::Error`] (in
//!   `interop/defmt.rs`), and for the propagation types `ConingRule`, `Normalization`,
//!   `RateMethod`, `IncrementIntegrator`, `ConingAccumulator` and `RateIntegrator` and the
//!   fixed-point type `Fixed<F>`, the carried attitude and `RawScale` (beside their definitions). The rotation
//!   representations and the dynamics types do not implement it.
//! - `nalgebra` (feature `nalgebra`): conversions with nalgebra's geometry types, without std.
//! - `mint` (feature `mint`): conversions with mint's plain types, the lingua franca of glam,
//!   cgmath and other math crates.
//!
//! Every conversion keeps the conventions of the crate docs: quaternions are Hamilton, the
//! scalar part is `w` in every library, and a unit quaternion means the same rotation on both
//! sides (nalgebra's `UnitQuaternion` is also Hamilton and also active).

#[cfg(feature = "defmt")]
mod defmt;
#[cfg(feature = "mint")]
mod mint;
#[cfg(feature = "nalgebra")]
mod nalgebra;
