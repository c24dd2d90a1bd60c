//! Rigid-body dynamics: inertia, the body and its step, body-frame Hamiltonians and their
//! structure-preserving integrators; the exact torque-free rigid body and the seed's analysis.
//!
//! Conventions (crate docs): `J` is the body-frame total angular momentum `J = I·ω + h`, `ω` the
//! body rate, `q` the attitude (body → lab). Torque-free motion is the Lie–Poisson flow
//! `J̇ = J × ∇H(J)` with `ω = ∇H(J)` (6.8.5), the attitude `q̇ = ½ q ⊗ (0, ω)`.
//!
//! One body type, one state type, one step: a [`Gyrostat`] (rigid body when it has no wheels)
//! advances a [`State`] with [`Gyrostat::step`] (torque-free) or [`Gyrostat::step_with`] (a held
//! [`Control`] or a control law).
//!
//! - [`inertia`]: the validated [`Inertia`] tensor, principal axes ([`inertia::symmetric_eigen`]).
//! - [`hamiltonian`]: rigid, gyro-rotor (6.9.2) and quartic (6.8.20) models [`BodyHamiltonian`],
//!   their body rate, Hessian and the momentum of a given rate.
//! - [`state`]: [`State`], [`Control`], [`ControlLaw`], [`WheelCommand`].
//! - [`gyrostat`]: the body [`Gyrostat`] (reaction wheels, constant rotors), [`Integrator`],
//!   the step, and the Euler equation [`angular_acceleration`].
//! - [`splitting`]: the Lie–Poisson flows and their compositions (Strang, Yoshida, Suzuki);
//!   RK4 is the private `rk4` module.
//! - [`monitors`]: energy, `|J|`, lab momentum ([`Invariants`]) and their drift over a run
//!   ([`DriftMonitor`]).
//! - [`elliptic`]: `K(m)`, Jacobi `sn, cn, dn`, Carlson `R_F`, `R_J`, `F(φ|m)`, `Π(n; φ|m)`.
//! - [`free_rigid_body`]: the exact torque-free rigid body [`FreeRigidBody`] (Landau–Lifshitz
//!   §37 for the body momentum, the elliptic integral of the third kind for the attitude).
//! - [`analysis`]: the seed's closed forms of §6.7–6.9 (6.7.27, 6.7.39–43, 6.8.6–10, 6.9.4).
//! - [`mass`]: inertia tensors from point masses, parallel-axis shift, radius of gyration,
//!   impulses (6.4.11–15, 6.5.4–6, 6.5.15).
//! - [`euler_coordinates`]: the rigid rotor in Euler angles — metric, Euler momenta, kinetic
//!   energy, Hamiltonian and Hamilton's velocity equations; the symmetric top (6.7.16–6.7.44).
//! - [`semi_rigid`]: centrifugal stretching of spring-mass rotors and the quartic Hamiltonian
//!   coefficients it produces (6.8.11–6.8.20).

pub mod analysis;
pub mod elliptic;
pub mod euler_coordinates;
pub mod free_rigid_body;
pub mod gyrostat;
pub mod hamiltonian;
pub mod inertia;
pub mod mass;
pub mod monitors;
mod rk4;
pub mod semi_rigid;
pub mod splitting;
pub mod state;

pub use free_rigid_body::FreeRigidBody;
pub use gyrostat::{Gyrostat, Integrator, Wheel, angular_acceleration};
pub use hamiltonian::{BodyHamiltonian, Quartic};
pub use inertia::Inertia;
pub use monitors::{Drift, DriftMonitor, Invariants, lab_momentum, momentum_norm};
pub use state::{Control, ControlLaw, State, WheelCommand};
