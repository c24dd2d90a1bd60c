//! The body: a gyrostat, a rigid body with constant rotor spins and `N` reaction wheels, and its
//! step. A rigid body is the zero-wheel case.
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
//!
//! # Stepping
//! [`Gyrostat::step`] advances a torque-free body (wheels coasting); [`Gyrostat::step_with`]
//! takes an input, either a [`Control`] held over the step (the firmware form, see
//! [`Gyrostat::control`]) or a law `f(t, state)` evaluated at the integrator's stages (the host
//! form). Both check the step once and return a typed error for a non-finite result or a step
//! beyond the methods' validity limit: the body may turn by at most
//! [`MAX_STEP_ANGLE`](crate::step_limit::MAX_STEP_ANGLE) (half a turn) per step, `|ω|·dt ≤ π` at
//! the start and at the end of the step ([`Error::StepTooLong`]).
//!
//! ```
//! use gyrostat::dynamics::{Gyrostat, Inertia, Integrator, State, lab_momentum};
//! use gyrostat::{UnitQuat, Vec3};
//! let body = Gyrostat::rigid(Inertia::try_from_principal(Vec3::new(6.0f64, 4.0, 3.0))?);
//! let mut s = State::new(UnitQuat::IDENTITY, Vec3::new(0.1, 1.0, 0.1));
//! let l0 = lab_momentum(s.attitude, s.momentum);
//! for _ in 0..1000 {
//!     s = body.step(Integrator::Strang, &s, 0.01)?;
//! }
//! // The splitting conserves |J| and the lab momentum to rounding.
//! assert!((s.momentum.norm() - l0.norm()).abs() < 1e-13);
//! assert!((lab_momentum(s.attitude, s.momentum) - l0).norm() < 1e-12);
//! # Ok::<(), gyrostat::Error>(())
//! ```

use crate::dynamics::hamiltonian::BodyHamiltonian;
use crate::dynamics::inertia::Inertia;
use crate::dynamics::monitors::{Invariants, lab_momentum, momentum_norm};
use crate::dynamics::splitting::Stages;
use crate::dynamics::state::{CompensatedState, Control, ControlLaw, State, WheelCommand};
use crate::step_limit::within_step_limit;
use crate::{Error, Real, UnitQuat, Vec3};

/// The integration method of a step.
///
/// - [`Integrator::Rk4`]: the classical Runge–Kutta method on `(q, J, wheel speeds)`, the
///   quaternion renormalised after each step. The baseline of Basilisk and NASA 42: order 4, but
///   its energy and `|J|` errors grow linearly with time.
/// - The Lie–Poisson splittings ([`crate::dynamics::splitting`]): every sub-step an exact
///   rotation, so `|J|` and the lab momentum are conserved to rounding and the energy error stays
///   bounded.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Integrator {
    /// Classical Runge–Kutta, order 4, quaternion renormalised each step.
    Rk4,
    /// Lie–Poisson splitting, Strang composition, order 2 (5 exact one-axis rotations).
    Strang,
    /// Yoshida's 3-stage symmetric composition of Strang steps, order 4.
    Yoshida4,
    /// Suzuki's 5-stage symmetric composition of Strang steps, order 4, smaller error constant.
    Suzuki4,
}

impl Integrator {
    /// Every method, in the order above.
    pub const ALL: [Integrator; 4] = [
        Integrator::Rk4,
        Integrator::Strang,
        Integrator::Yoshida4,
        Integrator::Suzuki4,
    ];

    /// `true` for the Lie–Poisson splitting methods (exact `|J|`, bounded energy error).
    #[inline]
    pub fn is_splitting(self) -> bool {
        !matches!(self, Integrator::Rk4)
    }
}

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
    /// term; see [`BodyHamiltonian::momentum_from_omega_with_rotor`]).
    ///
    /// # Errors
    /// As [`BodyHamiltonian::momentum_from_omega_with_rotor`].
    pub fn state_from_omega(
        &self,
        attitude: UnitQuat<T>,
        omega: Vec3<T>,
        wheel_speeds: [T; N],
    ) -> Result<State<T, N>, Error> {
        let h = self.rotor_momentum(&wheel_speeds);
        Ok(State {
            attitude,
            momentum: self.model.momentum_from_omega_with_rotor(omega, h)?,
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

    /// One torque-free step of length `dt`, the wheels coasting.
    ///
    /// `state` is a [`State`] (the plain step) or a [`CompensatedState`] (the compensated step,
    /// see [`crate::dynamics::compensated`]); the result is of the same type.
    ///
    /// Validity limit: the body turns by at most
    /// [`MAX_STEP_ANGLE`](crate::step_limit::MAX_STEP_ANGLE) in the step, `|ω|·dt ≤ π` with the
    /// body rate `ω` of the state before and of the state after the step. Every method here is a
    /// series in that angle (RK4's polynomial, the splittings' composition error); beyond half a
    /// turn per step none of them approximates the motion. (`|J|` and the energy of a state are
    /// otherwise unrestricted: a fast body needs short steps, not a different method.)
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite `dt` or state, or a non-finite result;
    /// [`Error::InvalidArgument`] for `dt ≤ 0`; [`Error::StepTooLong`] beyond the validity limit,
    /// or when the result's attitude has left the unit sphere by more than any step within the
    /// limit could (`|q|²` outside `[½, 2]` before renormalisation: a collapsed or exploded
    /// norm, never renormalised into a valid-looking attitude).
    pub fn step<S: StepState<T, N>>(
        &self,
        integrator: Integrator,
        state: &S,
        dt: T,
    ) -> Result<S, Error> {
        check_step(T::ZERO, dt)?;
        self.check_start(state.plain(), dt)?;
        let mut torque_free = Control::ZERO;
        let next = match Stages::of(integrator, dt) {
            Some(stages) => state.free(self, stages.as_slice()),
            None => state.rk4(self, T::ZERO, dt, &mut torque_free),
        };
        self.finish(next, dt)
    }

    /// One step from time `t` with an input: a [`Control`] held over the step (see
    /// [`Gyrostat::control`]) or a law `f(t, state) → Control` evaluated at the integrator's
    /// stages. See [`crate::dynamics::splitting`] for the order of the splitting methods with
    /// state-dependent laws. The input is a trait ([`ControlLaw`]), so a closure states its
    /// state argument's type: `|t, s: &State<T, N>| …`. `state` is a [`State`] or a
    /// [`CompensatedState`] (the law then sees its rounded [`CompensatedState::state`]).
    ///
    /// # Errors
    /// As [`Gyrostat::step`] (with the same validity limit), plus [`Error::NonFinite`] for a
    /// non-finite `t` and for an input that makes the result non-finite (a non-finite torque).
    ///
    /// ```
    /// use gyrostat::dynamics::{Control, Gyrostat, Inertia, Integrator, State};
    /// use gyrostat::{UnitQuat, Vec3};
    /// let body = Gyrostat::rigid(Inertia::try_from_principal(Vec3::new(2.0f32, 2.0, 2.0))?);
    /// let s = State::new(UnitQuat::IDENTITY, Vec3::ZERO);
    /// // A held torque of 0.5 N·m about z for 2 s adds 1 N·m·s of momentum.
    /// let held = Control::torque(Vec3::new(0.0, 0.0, 0.5));
    /// let s1 = body.step_with(Integrator::Strang, &s, 0.0, 2.0, held)?;
    /// assert!((s1.momentum.z - 1.0).abs() < 1e-6);
    /// // The same torque as a law of time and state.
    /// let s2 = body.step_with(Integrator::Rk4, &s, 0.0, 2.0, |_t, _s: &State<f32>| held)?;
    /// assert!((s2.momentum.z - 1.0).abs() < 1e-6);
    /// # Ok::<(), gyrostat::Error>(())
    /// ```
    pub fn step_with<S: StepState<T, N>, L: ControlLaw<T, N>>(
        &self,
        integrator: Integrator,
        state: &S,
        t: T,
        dt: T,
        mut input: L,
    ) -> Result<S, Error> {
        check_step(t, dt)?;
        self.check_start(state.plain(), dt)?;
        let next = match Stages::of(integrator, dt) {
            Some(stages) => state.kicked(self, t, stages.as_slice(), &mut input),
            None => state.rk4(self, t, dt, &mut input),
        };
        self.finish(next, dt)
    }

    /// The checks of a step's initial state: `|ω|·dt` within the validity limit. A non-finite
    /// state fails that test too (its rate is NaN or infinite); it is told apart on the error
    /// path only, so the accepted path costs one rate evaluation.
    #[inline]
    fn check_start(&self, state: &State<T, N>, dt: T) -> Result<(), Error> {
        if within_step_limit(self.omega(state).scale(dt)) {
            Ok(())
        } else if state.is_finite() {
            Err(Error::StepTooLong)
        } else {
            Err(Error::NonFinite)
        }
    }

    /// Renormalises the attitude of a step's result after checking it: its norm not collapsed
    /// or exploded (`|q|² ∈ [½, 2]`; the splittings keep `|q| = 1` to rounding and an RK4 step
    /// within the limit keeps `|q|²` above 0.85, so anything outside is a step far beyond its
    /// validity, for example a torque law that blew up within the step), and `|ω|·dt` within the
    /// validity limit at the end of the step. Passing both implies a finite state (a NaN or
    /// infinite component fails one of them); which error a failure is, is decided on the
    /// error path. The norm is near 1, far from overflow, so [`UnitQuat::renormalize`]'s plain
    /// square root is safe.
    #[inline]
    fn finish<S: StepState<T, N>>(&self, next: S, dt: T) -> Result<S, Error> {
        let n2 = next.plain().attitude.as_quat().norm_squared();
        if n2 >= T::HALF
            && n2 <= T::TWO
            && let Some(next) = next.renormalized()
            && within_step_limit(self.omega(next.plain()).scale(dt))
        {
            return Ok(next);
        }
        if next.plain().is_finite() {
            Err(Error::StepTooLong)
        } else {
            Err(Error::NonFinite)
        }
    }
}

/// A state that [`Gyrostat::step`] and [`Gyrostat::step_with`] advance: [`State`] (the plain
/// step) or [`CompensatedState`] (the compensated step, [`crate::dynamics::compensated`]).
/// Sealed: implemented for these two types only.
pub trait StepState<T: Real, const N: usize>: sealed::Advance<T, N> {}

impl<T: Real, const N: usize> StepState<T, N> for State<T, N> {}
impl<T: Real, const N: usize> StepState<T, N> for CompensatedState<T, N> {}

mod sealed {
    use super::{CompensatedState, ControlLaw, Gyrostat, Real, State};
    use crate::dynamics::{compensated, rk4, splitting};

    /// The steps of a state type (crate-internal: the methods of [`super::StepState`]).
    pub trait Advance<T: Real, const N: usize>: Copy {
        /// The torque-free splitting of Strang stages `stages`. Not renormalised.
        fn free(&self, body: &Gyrostat<T, N>, stages: &[T]) -> Self;
        /// The kicked splitting of Strang stages `stages` from time `t`. Not renormalised.
        fn kicked<L: ControlLaw<T, N>>(
            &self,
            body: &Gyrostat<T, N>,
            t: T,
            stages: &[T],
            input: &mut L,
        ) -> Self;
        /// One RK4 step. Not renormalised.
        fn rk4<L: ControlLaw<T, N>>(
            &self,
            body: &Gyrostat<T, N>,
            t: T,
            h: T,
            input: &mut L,
        ) -> Self;
        /// The state rounded to its working type (the state itself for a plain [`State`]).
        fn plain(&self) -> &State<T, N>;
        /// The attitude renormalised, for a norm already checked to be near 1; `None` when a
        /// carried low-order part is not finite.
        fn renormalized(self) -> Option<Self>;
    }

    impl<T: Real, const N: usize> Advance<T, N> for State<T, N> {
        #[inline]
        fn free(&self, body: &Gyrostat<T, N>, stages: &[T]) -> Self {
            splitting::free(body, self, stages)
        }
        #[inline]
        fn kicked<L: ControlLaw<T, N>>(
            &self,
            body: &Gyrostat<T, N>,
            t: T,
            stages: &[T],
            input: &mut L,
        ) -> Self {
            splitting::kicked(body, self, t, stages, input)
        }
        #[inline]
        fn rk4<L: ControlLaw<T, N>>(
            &self,
            body: &Gyrostat<T, N>,
            t: T,
            h: T,
            input: &mut L,
        ) -> Self {
            rk4::step(body, self, t, h, input)
        }
        #[inline]
        fn plain(&self) -> &State<T, N> {
            self
        }
        #[inline]
        fn renormalized(mut self) -> Option<Self> {
            self.attitude = self.attitude.renormalize();
            Some(self)
        }
    }

    impl<T: Real, const N: usize> Advance<T, N> for CompensatedState<T, N> {
        #[inline]
        fn free(&self, body: &Gyrostat<T, N>, stages: &[T]) -> Self {
            compensated::free(body, self, stages)
        }
        #[inline]
        fn kicked<L: ControlLaw<T, N>>(
            &self,
            body: &Gyrostat<T, N>,
            t: T,
            stages: &[T],
            input: &mut L,
        ) -> Self {
            compensated::kicked(body, self, t, stages, input)
        }
        #[inline]
        fn rk4<L: ControlLaw<T, N>>(
            &self,
            body: &Gyrostat<T, N>,
            t: T,
            h: T,
            input: &mut L,
        ) -> Self {
            compensated::rk4_step(body, self, t, h, input)
        }
        #[inline]
        fn plain(&self) -> &State<T, N> {
            &self.state
        }
        #[inline]
        fn renormalized(self) -> Option<Self> {
            compensated::finish(self).ok()
        }
    }
}

/// The checks every step makes of its time and step length.
#[inline]
fn check_step<T: Real>(t: T, dt: T) -> Result<(), Error> {
    if !dt.is_finite() || !t.is_finite() {
        return Err(Error::NonFinite);
    }
    if dt <= T::ZERO {
        return Err(Error::InvalidArgument);
    }
    Ok(())
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
