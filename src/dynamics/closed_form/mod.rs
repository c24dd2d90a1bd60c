//! The closed forms of rigid-body rotation: the exact torque-free rigid body, the elliptic
//! functions it is written in, the rigid rotor and the symmetric top in Euler coordinates, and
//! the seed's analysis of the motion. The integrators are tested against them; none of them
//! steps a state.
//!
//! - [`free_rigid_body`]: the exact torque-free rigid body [`FreeRigidBody`] (Landau–Lifshitz
//!   §37 for the body momentum, the elliptic integral of the third kind for the attitude).
//! - [`elliptic`]: `K(m)`, Jacobi `sn, cn, dn`, Carlson `R_F`, `R_J`, `F(φ|m)`, `Π(n; φ|m)`.
//! - [`euler_coordinates`]: the rigid rotor in Euler angles — metric, Euler momenta, kinetic
//!   energy, Hamiltonian and Hamilton's velocity equations; the symmetric top (6.7.16–6.7.44).
//! - [`analysis`]: the seed's closed forms of §6.7–6.9 (6.7.27, 6.7.39–43, 6.8.6–10, 6.9.4).
//!
//! They depend on the body's inertia and state ([`crate::dynamics::Inertia`],
//! [`crate::dynamics::State`]) and on nothing else of the dynamics.

pub mod analysis;
pub mod elliptic;
pub mod euler_coordinates;
pub mod free_rigid_body;

pub use free_rigid_body::FreeRigidBody;
