//! Tests of the rotation layer (`gyrostat::rotation` and the foundation types below it) against
//! the independent f64 reference of `host_tests`, for f32 and f64. One module per part of
//! `src/` (the whole map is in `host-tests/README.md`):
//!
//! - [`quat`]: `Quat`, `UnitQuat`, `Su2` and `Mat3` against the Rodrigues and 2×2 matrix forms;
//!   the exponential map; the mint/nalgebra round trips (`src/rotation/{quat,unit_quat,su2,exp}.rs`,
//!   `src/linalg/`, `src/interop/`).
//! - [`repr`]: every representation and conversion (`src/rotation/{dcm,axis_angle,rotvec,mrp,
//!   gibbs,canonical}.rs`), slerp, the double cover, property-based round trips.
//! - [`euler`]: Euler angles in all 24 conventions and gimbal lock (`src/rotation/euler.rs`).
//! - [`euler_rates`]: Euler-rate kinematics (`src/rotation/euler_rates.rs`).
//! - [`firmware`]: the output of the `fw_rotations` firmware under QEMU (ignored unless CI
//!   hands it the output: `-- --ignored firmware::`).

mod euler;
mod euler_rates;
mod firmware;
mod quat;
mod repr;
