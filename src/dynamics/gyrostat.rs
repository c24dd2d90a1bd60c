//! The body: a gyrostat, a rigid body with constant rotor spins and `N` reaction wheels. A rigid
//! body is the zero-wheel case. Its step is in [`crate::dynamics::Gyrostat::step`].
//!
//! Body-frame total momentum `J = I·ω + S + Σ I_wᵢ Ωᵢ gᵢ` (crate docs: `J = I ω + h`), where `I`
//! is the whole body's tensor with the wheels locked, `S` the constant rotor spins and `Ωᵢ` the
//! wheel speeds relative to the body ([`State`]). With external torque `τ` and wheel torques
//! `ḣᵢ = I_wᵢ Ω̇ᵢ` the motion is
//!
//! `J̇ = J × ω + τ`, `ω = ∇H(J) = I⁻¹(J − h) + ∇quartic(J)`, `h = S + Σ I_wᵢ Ωᵢ gᵢ`,
//!
//! which is the Euler equation `I ω̇ = −ω × (I ω + h) + τ − ḣ` ([`angular_acceleration`]) written
//! for the conserved quantity `J` (seed (6.8.5), (6.9.2)): the wheel torque is internal, so it
//! moves momentum between the wheels and the body without changing `J`.

use crate::dynamics::hamiltonian::BodyHamiltonian;
use crate::dynamics::inertia::Inertia;
use crate::dynamics::monitors::{Invariants, lab_momentum, momentum_norm};
use crate::dynamics::state::{Control, State, WheelCommand};
use crate::{Error, Real, UnitQuat, Vec3};

/// One reaction wheel: a symmetric rotor spinning about a body-fixed unit axis `g`.
///
/// Its momentum relative to the body is `I_w Ω g`. The body tensor of the [`Gyrostat`] includes
/// the wheels as if locked (all their mass and inertia), so the total momentum is
/// `J = I·ω + Σ I_w Ω g` exactly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wheel<T> {
    axis: Vec3<T>,
    inertia: T,
    inv_inertia: T,
}

impl<T: Real> Wheel<T> {
    /// A wheel with spin axis `axis` (body frame, normalised here) and axial inertia `inertia`.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for non-finite input, [`Error::ZeroNorm`] for a zero axis,
    /// [`Error::InvalidArgument`] for `inertia ≤ 0`.
    pub fn try_new(axis: Vec3<T>, inertia: T) -> Result<Self, Error> {
        if !inertia.is_finite() {
            return Err(Error::NonFinite);
        }
        let axis = axis.try_normalize()?;
        if inertia <= T::ZERO {
            return Err(Error::InvalidArgument);
        }
        Ok(Self {
            axis,
            inertia,
            inv_inertia: T::ONE / inertia,
        })
    }

    /// The unit spin axis (body frame).
    #[inline]
    pub fn axis(&self) -> Vec3<T> {
        self.axis
    }

    /// The axial inertia `I_w`.
    #[inline]
    pub fn inertia(&self) -> T {
        self.inertia
    }

    /// The wheel's speed rate `Ω̇ = ḣ / I_w` under wheel torque `torque`.
    #[inline]
    pub(crate) fn acceleration(&self, torque: T) -> T {
        torque * self.inv_inertia
    }
}

/// A gyrostat: a body Hamiltonian (inertia with the wheels locked, constant spins `S`, optional
/// quartic term) and `N` reaction wheels. `Gyrostat<T>` (`N = 0`) is a rigid body or gyro-rotor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gyrostat<T, const N: usize = 0> {
    model: BodyHamiltonian<T>,
    wheels: [Wheel<T>; N],
}

impl<T: Real> Gyrostat<T> {
    /// The rigid body `H = ½ J·I⁻¹·J` (6.5.11): no rotors, no wheels. Infallible because
    /// `inertia` is validated.
    #[inline]
    pub fn rigid(inertia: Inertia<T>) -> Self {
        Self::new(BodyHamiltonian::rigid(inertia), [])
    }
}

impl<T: Real> From<BodyHamiltonian<T>> for Gyrostat<T> {
    /// The body of a Hamiltonian, with no wheels.
    #[inline]
    fn from(model: BodyHamiltonian<T>) -> Self {
        Self::new(model, [])
    }
}

impl<T: Real, const N: usize> Gyrostat<T, N> {
    /// Builds from a validated model and validated wheels (infallible).
    #[inline]
    pub fn new(model: BodyHamiltonian<T>, wheels: [Wheel<T>; N]) -> Self {
        Self { model, wheels }
    }

    /// A rigid body carrying reaction wheels: `inertia` is the whole body's tensor with the
    /// wheels locked, `H = ½ (J − h)·I⁻¹·(J − h)` with `h` the wheels' momentum. Infallible
    /// because both are validated ([`Inertia::try_from_principal`], [`Wheel::try_new`]); the
    /// rigid body is `Gyrostat::rigid`, the same with no wheels.
    ///
    /// ```
    /// use gyrostat::dynamics::{Gyrostat, Inertia, Wheel};
    /// use gyrostat::Vec3;
    /// let inertia = Inertia::try_from_principal(Vec3::new(6.0f64, 4.0, 3.0))?;
    /// let wheel = Wheel::try_new(Vec3::new(0.0, 1.0, 0.0), 0.05)?;
    /// let body = Gyrostat::with_wheels(inertia, [wheel]);
    /// assert_eq!(body.rotor_momentum(&[60.0]), Vec3::new(0.0, 3.0, 0.0));
    /// # Ok::<(), gyrostat::Error>(())
    /// ```
    #[inline]
    pub fn with_wheels(inertia: Inertia<T>, wheels: [Wheel<T>; N]) -> Self {
        Self::new(BodyHamiltonian::rigid(inertia), wheels)
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

    /// The total rotor momentum `h = S + Σ I_wᵢ Ωᵢ gᵢ` (body frame).
    #[inline]
    pub fn rotor_momentum(&self, wheel_speeds: &[T; N]) -> Vec3<T> {
        let mut s = self.model.spin();
        for (wheel, speed) in self.wheels.iter().zip(wheel_speeds.iter()) {
            s += wheel.axis * (wheel.inertia * *speed);
        }
        s
    }

    /// The body rate `ω = ∇H(J) = I⁻¹(J − h) + ∇quartic(J)`.
    ///
    /// Domain (of this, [`Gyrostat::energy`] and [`Gyrostat::invariants`]): a finite state whose
    /// rate and energy are representable (see [`BodyHamiltonian::energy_with_rotor`] with the
    /// rotor momentum `h` of the wheel speeds); outside it the result is infinite or NaN.
    #[inline]
    pub fn omega(&self, state: &State<T, N>) -> Vec3<T> {
        self.model
            .omega_with_rotor(state.momentum, self.rotor_momentum(&state.wheel_speeds))
    }

    /// The body Hamiltonian `H(J)` at the current rotor momentum: conserved when no torque acts
    /// and the wheels coast. (The wheels' own spin energy `Σ ½ I_w Ωᵢ²` is not included.)
    #[inline]
    pub fn energy(&self, state: &State<T, N>) -> T {
        self.model
            .energy_with_rotor(state.momentum, self.rotor_momentum(&state.wheel_speeds))
    }

    /// The conserved quantities of torque-free motion at `state`: energy, `|J|`, lab momentum
    /// (see [`crate::dynamics::monitors`]).
    #[inline]
    pub fn invariants(&self, state: &State<T, N>) -> Invariants<T> {
        Invariants {
            energy: self.energy(state),
            momentum_norm: momentum_norm(state.momentum),
            lab_momentum: lab_momentum(state.attitude, state.momentum),
        }
    }

    /// The state with body rate `omega` (body frame) instead of momentum: the `J` with
    /// `∇H(J) = ω` at the rotor momentum of `wheel_speeds` (`J = I·ω + h` without a quartic
    /// term; see [`BodyHamiltonian::try_momentum_from_omega_with_rotor`]).
    ///
    /// # Errors
    /// As [`BodyHamiltonian::try_momentum_from_omega_with_rotor`].
    pub fn try_state_from_omega(
        &self,
        attitude: UnitQuat<T>,
        omega: Vec3<T>,
        wheel_speeds: [T; N],
    ) -> Result<State<T, N>, Error> {
        let h = self.rotor_momentum(&wheel_speeds);
        Ok(State {
            attitude,
            momentum: self.model.try_momentum_from_omega_with_rotor(omega, h)?,
            wheel_speeds,
        })
    }

    /// The control held over one step of length `dt` from `state` (a zero-order hold): the
    /// external body torque `torque` and the wheel torques that realise `command` (for
    /// [`WheelCommand::Speed`], `I_wᵢ (Ωᵢ,cmd − Ωᵢ)/dt` from the speeds of `state`). Pass it to
    /// [`Gyrostat::step_with`] with the same `state` and `dt`.
    ///
    /// A non-finite input, or `dt = 0` with a speed command, gives a non-finite control, which
    /// the step rejects with [`Error::NonFinite`].
    pub fn control(
        &self,
        state: &State<T, N>,
        dt: T,
        torque: Vec3<T>,
        command: &WheelCommand<T, N>,
    ) -> Control<T, N> {
        let wheel_torques = match command {
            WheelCommand::Torque(u) => *u,
            WheelCommand::Speed(target) => {
                let inv_dt = T::ONE / dt;
                let mut u = [T::ZERO; N];
                for (((u, tgt), now), wheel) in u
                    .iter_mut()
                    .zip(target.iter())
                    .zip(state.wheel_speeds.iter())
                    .zip(self.wheels.iter())
                {
                    *u = wheel.inertia * (*tgt - *now) * inv_dt;
                }
                u
            }
        };
        Control {
            torque,
            wheel_torques,
        }
    }
}

/// The Euler equation with a full inertia tensor, rotor momentum and torque, solved for the body
/// angular acceleration: `ω̇ = I⁻¹ (−ω × (I ω + h) + τ − ḣ)` (seed (6.8.5) with rotors, (6.9.2)).
///
/// `h` is the body-frame rotor momentum (relative to the body), `h_dot` its rate (the wheel
/// torques), `torque` the external torque (body frame).
pub fn angular_acceleration<T: Real>(
    inertia: &Inertia<T>,
    omega: Vec3<T>,
    h: Vec3<T>,
    h_dot: Vec3<T>,
    torque: Vec3<T>,
) -> Vec3<T> {
    let l = inertia.mul_vec(omega) + h;
    inertia.solve(torque - h_dot - omega.cross(l))
}
