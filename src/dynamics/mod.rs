//! Rigid-body dynamics: inertia, Euler equations, gyrostats, body-frame Hamiltonians and their
//! structure-preserving integrators.
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

pub mod gyrostat;
pub mod hamiltonian;
pub mod inertia;
pub mod integrators;

pub use gyrostat::{Gyrostat, WheelCommand, euler_rate};
pub use hamiltonian::{BodyHamiltonian, Quartic, lab_momentum, momentum_norm};
pub use inertia::Inertia;
pub use integrators::{Control, GyrostatState, Integrator, State, Wheel};

// --- exact solutions and seed analysis (branch dyn-exact) ---
