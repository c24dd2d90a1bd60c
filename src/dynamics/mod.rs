//! Rigid-body dynamics: the exact torque-free rigid body and its special functions, the seed's
//! analysis functions (energy surfaces, separatrices, precession rates) and mass properties.
//!
//! - [`elliptic`]: `K(m)`, Jacobi `sn, cn, dn`, Carlson `R_F`, `R_J`, `F(φ|m)`, `Π(n; φ|m)`.
//! - [`free_rigid_body`]: the exact torque-free rigid body (Landau–Lifshitz §37 for the body
//!   momentum, the elliptic integral of the third kind for the attitude).
//! - [`analysis`]: the seed's closed forms of §6.7–6.9 (6.7.39–43, 6.8.6–10, 6.9.4).
//! - [`mass`]: inertia tensors from point masses, parallel-axis shift, radius of gyration,
//!   impulses (6.4.11–15, 6.5.4–6, 6.5.15).

pub mod analysis;
pub mod elliptic;
pub mod free_rigid_body;
pub mod mass;
