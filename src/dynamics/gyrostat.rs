//! The gyrostat: a rigid body with constant rotor spins and `N` reaction wheels.
//!
//! Body-frame total momentum `J = I·ω + S + Σ I_wᵢ Ωᵢ gᵢ` (DESIGN: `J = I ω + h`), where `I` is
//! the whole spacecraft's tensor with the wheels locked, `S` the constant rotor spins and
//! `Ωᵢ` the wheel speeds relative to the body (state). With external torque `τ` and wheel
//! torques `ḣᵢ = I_wᵢ Ω̇ᵢ` the motion is
//!
//! `J̇ = J × ω + τ`, `ω = I⁻¹(J − h)`, `h = S + Σ I_wᵢ Ωᵢ gᵢ`,
//!
//! which is the Euler equation `I ω̇ = −ω × (I ω + h) + τ − ḣ` ([`euler_rate`]) written for the
//! conserved quantity `J`: the wheel torque is internal, so it moves momentum between the wheels
//! and the body without changing `J`.
//!
//! Inputs come either as plain values per step ([`Gyrostat::step`] with a [`WheelCommand`]: the
//! firmware form) or as a law `f(t, state)` evaluated at the integrator's stages
//! ([`Gyrostat::step_with`]: the host form).

use crate::dynamics::hamiltonian::BodyHamiltonian;
use crate::dynamics::inertia::Inertia;
use crate::dynamics::integrators::{Control, Engine, GyrostatState, Integrator, Wheel};
use crate::{Error, Real, Vec3};

/// What the wheels are told to do during one step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WheelCommand<T, const N: usize> {
    /// Wheel torques `ḣᵢ = I_wᵢ Ω̇ᵢ`, held over the step.
    Torque([T; N]),
    /// Wheel speeds `Ωᵢ` (rad/s, relative to the body) to reach at the end of the step: an
    /// ideal speed loop, realised as the constant torque `I_wᵢ (Ωᵢ,cmd − Ωᵢ)/dt`.
    Speed([T; N]),
}

/// A gyrostat: a body Hamiltonian (inertia with the wheels locked, constant spins `S`, optional
/// quartic term) and `N` reaction wheels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gyrostat<T, const N: usize> {
    model: BodyHamiltonian<T>,
    wheels: [Wheel<T>; N],
}

impl<T: Real, const N: usize> Gyrostat<T, N> {
    /// Builds from a validated model and validated wheels (infallible).
    pub fn new(model: BodyHamiltonian<T>, wheels: [Wheel<T>; N]) -> Self {
        Self { model, wheels }
    }

    /// The body Hamiltonian.
    #[inline]
    pub fn model(&self) -> &BodyHamiltonian<T> {
        &self.model
    }

    /// The wheels.
    #[inline]
    pub fn wheels(&self) -> &[Wheel<T>; N] {
        &self.wheels
    }

    fn engine(&self) -> Engine<'_, T, N> {
        Engine {
            model: &self.model,
            wheels: &self.wheels,
        }
    }

    /// The total rotor momentum `h = S + Σ I_wᵢ Ωᵢ gᵢ` (body frame).
    #[inline]
    pub fn rotor_momentum(&self, wheel_speeds: &[T; N]) -> Vec3<T> {
        self.engine().rotor(wheel_speeds)
    }

    /// The body rate `ω = ∇H(J) = I⁻¹(J − h) + ∇quartic`.
    #[inline]
    pub fn omega(&self, state: &GyrostatState<T, N>) -> Vec3<T> {
        self.model
            .omega_with_rotor(state.momentum, self.rotor_momentum(&state.wheel_speeds))
    }

    /// The body Hamiltonian `H(J)` at the current rotor momentum: conserved when no torque acts
    /// and the wheels coast. (The wheels' own spin energy `Σ ½ I_w Ωᵢ²` is not included.)
    #[inline]
    pub fn energy(&self, state: &GyrostatState<T, N>) -> T {
        self.model
            .energy_with_rotor(state.momentum, self.rotor_momentum(&state.wheel_speeds))
    }

    /// The state with body rate `omega` (body frame) instead of momentum: `J = I·ω + h`.
    pub fn state_from_omega(
        &self,
        attitude: crate::UnitQuat<T>,
        omega: Vec3<T>,
        wheel_speeds: [T; N],
    ) -> GyrostatState<T, N> {
        let momentum = self.model.inertia.mul_vec(omega) + self.rotor_momentum(&wheel_speeds);
        GyrostatState {
            attitude,
            momentum,
            wheel_speeds,
        }
    }

    /// One step with plain inputs held over the step: external body torque `torque` and a
    /// wheel command (the firmware form).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for non-finite input or result; [`Error::InvalidArgument`] for
    /// `dt ≤ 0`.
    pub fn step(
        &self,
        integrator: Integrator,
        state: &GyrostatState<T, N>,
        dt: T,
        torque: Vec3<T>,
        command: &WheelCommand<T, N>,
    ) -> Result<GyrostatState<T, N>, Error> {
        if !dt.is_finite() {
            return Err(Error::NonFinite);
        }
        if dt <= T::ZERO {
            return Err(Error::InvalidArgument);
        }
        let torque = torque.try_finite()?;
        let mut wheel_torques = [T::ZERO; N];
        match command {
            WheelCommand::Torque(u) => wheel_torques = *u,
            WheelCommand::Speed(target) => {
                let inv_dt = T::ONE / dt;
                for (((u, tgt), now), wheel) in wheel_torques
                    .iter_mut()
                    .zip(target.iter())
                    .zip(state.wheel_speeds.iter())
                    .zip(self.wheels.iter())
                {
                    *u = wheel.inertia * (*tgt - *now) * inv_dt;
                }
            }
        }
        if !wheel_torques.iter().all(|u| u.is_finite()) {
            return Err(Error::NonFinite);
        }
        let control = Control {
            torque,
            wheel_torques,
        };
        self.engine()
            .step(integrator, state, T::ZERO, dt, true, |_, _| control)
    }

    /// One step from time `t` with a control law `f(t, state) → Control` evaluated at the
    /// integrator's stages (the host form). See [`crate::dynamics::integrators`] for the order
    /// of the splitting methods with state-dependent laws.
    ///
    /// # Errors
    /// As [`Gyrostat::step`].
    pub fn step_with<F>(
        &self,
        integrator: Integrator,
        state: &GyrostatState<T, N>,
        t: T,
        dt: T,
        law: F,
    ) -> Result<GyrostatState<T, N>, Error>
    where
        F: FnMut(T, &GyrostatState<T, N>) -> Control<T, N>,
    {
        self.engine().step(integrator, state, t, dt, true, law)
    }
}

/// The Euler equation with a full inertia tensor, rotor momentum and torque, solved for the
/// body angular acceleration: `ω̇ = I⁻¹ (−ω × (I ω + h) + τ − ḣ)` (seed (6.8.5) with rotors,
/// (6.9.2)).
///
/// `h` is the body-frame rotor momentum (relative to the body), `h_dot` its rate (the wheel
/// torques), `torque` the external torque (body frame).
pub fn euler_rate<T: Real>(
    inertia: &Inertia<T>,
    omega: Vec3<T>,
    h: Vec3<T>,
    h_dot: Vec3<T>,
    torque: Vec3<T>,
) -> Vec3<T> {
    let l = inertia.mul_vec(omega) + h;
    inertia.solve(torque - h_dot - omega.cross(l))
}
