//! Rigid-body dynamics: inertia, Euler equations, gyrostats, body-frame Hamiltonians and their
//! structure-preserving integrators; the exact torque-free rigid body and the seed's analysis.
//!
//! Conventions (crate docs): `J` is the body-frame total angular momentum `J = I·ω + h`, `ω` the
//! body rate, `q` the attitude (body → lab). Torque-free motion is the Lie–Poisson flow
//! `J̇ = J × ∇H(J)` with `ω = ∇H(J)` (6.8.5), the attitude `q̇ = ½ q ⊗ (0, ω)`.
//!
//! - [`inertia`]: the validated [`Inertia`] tensor, principal axes ([`inertia::symmetric_eigen`]).
//! - [`hamiltonian`]: rigid, gyro-rotor (6.9.2) and quartic (6.8.20) models [`BodyHamiltonian`];
//!   monitors (energy, `|J|`, lab momentum).
//! - [`integrators`]: RK4 and the Lie–Poisson splittings (Strang, Yoshida, Suzuki) with torques.
//! - [`gyrostat`]: reaction wheels and constant rotors, [`Gyrostat`]; [`gyrostat::euler_rate`].
//! - [`elliptic`]: `K(m)`, Jacobi `sn, cn, dn`, Carlson `R_F`, `R_J`, `F(φ|m)`, `Π(n; φ|m)`.
//! - [`free_rigid_body`]: the exact torque-free rigid body (Landau–Lifshitz §37 for the body
//!   momentum, the elliptic integral of the third kind for the attitude).
//! - [`analysis`]: the seed's closed forms of §6.7–6.9 (6.7.39–43, 6.8.6–10, 6.9.4).
//! - [`mass`]: inertia tensors from point masses, parallel-axis shift, radius of gyration,
//!   impulses (6.4.11–15, 6.5.4–6, 6.5.15).
//! - [`euler_coordinates`]: the rigid rotor in Euler angles — metric, Euler momenta, kinetic
//!   energy, Hamiltonian and Hamilton's velocity equations; the symmetric top (6.7.16–6.7.44).
//! - [`semi_rigid`]: centrifugal stretching of spring-mass rotors and the quartic Hamiltonian
//!   coefficients it produces (6.8.11–6.8.20).

// --- inertia, Hamiltonians, integrators, gyrostat (branch dynamics) ---
pub mod gyrostat;
pub mod hamiltonian;
pub mod inertia;
pub mod integrators;

pub use gyrostat::{Gyrostat, WheelCommand, euler_rate};
pub use hamiltonian::{BodyHamiltonian, Quartic, lab_momentum, momentum_norm};
pub use inertia::Inertia;
pub use integrators::{Control, GyrostatState, Integrator, State, Wheel};

// --- exact solutions, seed analysis and mass properties (branch dyn-exact) ---
pub mod analysis;
pub mod elliptic;
pub mod free_rigid_body;
pub mod mass;

// --- Euler coordinates and semi-rigid rotors ---
pub mod euler_coordinates;
pub mod semi_rigid;
