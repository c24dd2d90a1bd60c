//! Rigid-body dynamics: inertia, the body and its step, body-frame Hamiltonians and their
//! structure-preserving integrators; the exact torque-free rigid body and the seed's analysis.
//!
//! Conventions (crate docs): `J` is the body-frame total angular momentum `J = I·ω + h`, `ω` the
//! body rate, `q` the attitude (body → lab). Torque-free motion is the Lie–Poisson flow
//! `J̇ = J × ∇H(J)` with `ω = ∇H(J)` (6.8.5), the attitude `q̇ = ½ q ⊗ (0, ω)`.
//!
//! One body type, one state type, one step: a [`Gyrostat`] (rigid body when it has no wheels)
//! advances a [`State`] with [`Gyrostat::step`] (torque-free) or [`Gyrostat::step_with`] (a held
//! [`Control`] or a control law). The same step advances a [`CompensatedState`], the state with
//! its rounding errors carried, for long f32 runs as accurate as the method
//! ([`integrators`]).
//!
//! The body:
//! - [`inertia`]: the validated [`Inertia`] tensor, principal axes ([`inertia::symmetric_eigen`]).
//! - [`hamiltonian`]: rigid, gyro-rotor (6.9.2) and quartic (6.8.20) models [`BodyHamiltonian`],
//!   their body rate, Hessian and the momentum of a given rate.
//! - [`gyrostat`]: the body [`Gyrostat`] (reaction wheels, constant rotors) and the Euler
//!   equation [`angular_acceleration`].
//! - [`state`]: [`State`], [`CompensatedState`], [`Control`], [`ControlLaw`], [`WheelCommand`].
//! - [`monitors`]: energy, `|J|`, lab momentum ([`Invariants`]) and their drift over a run
//!   ([`DriftMonitor`]).
//! - [`mass`]: inertia tensors from point masses, parallel-axis shift, radius of gyration,
//!   impulses (6.4.11–15, 6.5.4–6, 6.5.15).
//! - [`semi_rigid`]: centrifugal stretching of spring-mass rotors and the quartic Hamiltonian
//!   coefficients it produces (6.8.11–6.8.20).
//!
//! The step and the methods:
//! - [`Gyrostat::step`], [`Gyrostat::step_with`] and [`StepState`] (a private `step` module): the
//!   checks of a step and the dispatch to a method.
//! - [`integrators`]: [`Integrator`] (RK4, the Lie–Poisson splittings Strang, Yoshida, Suzuki),
//!   each on the plain and the compensated state, and why a plain f32 splitting loses to RK4 on
//!   long runs (measured). Each method depends on the body only.
//!
//! The closed forms ([`closed_form`]): the exact free rigid body [`FreeRigidBody`], the elliptic
//! functions, the rigid rotor and symmetric top in Euler coordinates, the seed's analysis.
//!
//! Layers inside: the body at the bottom (inertia, Hamiltonian, gyrostat, state, monitors); the
//! integrators and the closed forms on the body; the step on the integrators.

pub mod closed_form;
pub mod gyrostat;
pub mod hamiltonian;
pub mod inertia;
pub mod integrators;
pub mod mass;
pub mod monitors;
pub mod semi_rigid;
pub mod state;
mod step;

pub use closed_form::FreeRigidBody;
pub use gyrostat::{Gyrostat, Wheel, angular_acceleration};
pub use hamiltonian::{BodyHamiltonian, Quartic};
pub use inertia::Inertia;
pub use integrators::Integrator;
pub use monitors::{Drift, DriftMonitor, Invariants, lab_momentum, momentum_norm};
pub use state::{CompensatedState, Control, ControlLaw, State, WheelCommand};
pub use step::StepState;
