//! Tests of the dynamics layer (`gyrostat::dynamics`) against independent references
//! (tiny-step RK4 on matrices and body rates, quadratures, direct sums over point masses, the
//! seed's worked values): one module per part of `src/dynamics/` (the whole map is in
//! `host-tests/README.md`):
//!
//! - [`inertia`]: validation and principal axes (`inertia.rs`).
//! - [`mass`]: mass properties (`mass.rs`).
//! - [`hamiltonian`]: the body model's maps and the monitors (`hamiltonian.rs`, `monitors.rs`).
//! - [`gyrostat`]: Euler's equations with torques, full inertia and reaction wheels
//!   (`gyrostat.rs`, `state.rs`, `rk4.rs`).
//! - [`splitting`]: the Lie–Poisson splittings and RK4 on torque-free models (`splitting.rs`).
//! - [`compensated`]: the splittings in f32 with the rounding errors carried (`compensated.rs`).
//! - [`elliptic`], [`free_rigid_body`]: the exact free rigid body (`elliptic.rs`,
//!   `free_rigid_body.rs`).
//! - [`euler_coordinates`]: the rotor in Euler coordinates and the Euler momenta
//!   (`euler_coordinates.rs`, `src/rotation/euler_momenta.rs`).
//! - [`semi_rigid`]: semi-rigid spring-mass rotors (`semi_rigid.rs`).
//! - [`analysis`]: the seed's closed forms (`analysis.rs`).
//! - [`seed_relations`]: relations of seed §6.4–6.9 across the API; [`seed_index`]: `SEED.md`
//!   cites only items and tests that exist.

mod analysis;
mod compensated;
mod elliptic;
mod euler_coordinates;
mod free_rigid_body;
mod gyrostat;
mod hamiltonian;
mod inertia;
mod mass;
mod seed_index;
mod seed_relations;
mod semi_rigid;
mod splitting;
