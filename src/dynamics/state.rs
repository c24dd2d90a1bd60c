//! The state of a body and the inputs of a step.
//!
//! One state type serves every body: [`State`] holds the attitude, the body-frame total angular
//! momentum and the speeds of `N` reaction wheels. A rigid body (or a gyro-rotor with constant
//! spins) is the case `N = 0`, the default, so `State<T>` is the rigid-body state.
//!
//! [`CompensatedState`] is the same state with the rounding errors of its attitude, momentum and
//! wheel speeds carried beside it, for compensated integration (see
//! [`crate::dynamics::integrators`]): the step takes and returns either type.
//!
//! The inputs of a step are a [`Control`] (external torque and wheel torques), either held over
//! the step (the firmware form: one value per control cycle) or produced by a law `f(t, state)`
//! evaluated at the integrator's stages (the host form); both are a [`ControlLaw`].

use crate::{Quat, Real, UnitQuat, Vec3};

/// The state of a body with `N` reaction wheels (`N = 0`: a rigid body).
///
/// `J` is the body-frame total angular momentum `J = I·ω + S + Σ I_wᵢ Ωᵢ gᵢ` (crate docs: `J = I ω
/// + h`), with `I` the tensor of the whole body with the wheels locked, `S` the constant rotor
/// spins of the model and `Ωᵢ` the wheel speeds relative to the body.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct State<T, const N: usize = 0> {
    /// Attitude `q`, body → lab.
    pub attitude: UnitQuat<T>,
    /// Body-frame total angular momentum `J`.
    pub momentum: Vec3<T>,
    /// Wheel speeds `Ωᵢ` relative to the body, rad/s.
    pub wheel_speeds: [T; N],
}

impl<T: Real, const N: usize> State<T, N> {
    /// Attitude and total momentum, with every wheel at rest relative to the body.
    ///
    /// ```
    /// use gyrostat::dynamics::State;
    /// use gyrostat::{UnitQuat, Vec3};
    /// let rigid: State<f32> = State::new(UnitQuat::IDENTITY, Vec3::new(0.1, 1.0, 0.0));
    /// assert_eq!(rigid.wheel_speeds, []);
    /// ```
    #[inline]
    pub const fn new(attitude: UnitQuat<T>, momentum: Vec3<T>) -> Self {
        Self {
            attitude,
            momentum,
            wheel_speeds: [T::ZERO; N],
        }
    }

    /// `true` when every component is finite.
    #[inline]
    pub fn is_finite(&self) -> bool {
        self.attitude.as_quat().is_finite()
            && self.momentum.is_finite()
            && self.wheel_speeds.iter().all(|w| w.is_finite())
    }
}

/// A [`State`] with the rounding errors of its components carried beside it: the state of a
/// compensated integration ([`crate::dynamics::integrators`]).
///
/// Each component is a pair: the value rounded to `T` ([`CompensatedState::state`], what the
/// caller reads and what a control law sees) and its low-order part, the rounding error of the
/// last update (below half an ulp of the value). [`crate::dynamics::Gyrostat::step`] and
/// [`crate::dynamics::Gyrostat::step_with`] take and return it like a [`State`]; every
/// rotation, kick and renormalisation then adds its increment to the pair without losing its
/// rounding, so f32 runs do not drift from the rounding bias described in
/// [`crate::dynamics::integrators`]. The attitude is the direction of `q + q_lo`; its norm is 1
/// within a few ulp.
///
/// ```
/// use gyrostat::dynamics::{CompensatedState, Gyrostat, Inertia, Integrator, State};
/// use gyrostat::{UnitQuat, Vec3};
/// let body = Gyrostat::rigid(Inertia::try_from_principal(Vec3::new(6.0f32, 4.0, 3.0))?);
/// let mut s = CompensatedState::new(State::new(UnitQuat::IDENTITY, Vec3::new(3.9, 0.5, 0.4)));
/// for _ in 0..1000 {
///     s = body.step(Integrator::Suzuki4, &s, 0.004)?;
/// }
/// let j = s.state().momentum;
/// assert!((j.norm() - Vec3::new(3.9f32, 0.5, 0.4).norm()).abs() < 1e-6);
/// # Ok::<(), gyrostat::Error>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CompensatedState<T, const N: usize = 0> {
    pub(crate) state: State<T, N>,
    pub(crate) attitude_lo: Quat<T>,
    pub(crate) momentum_lo: Vec3<T>,
    pub(crate) wheel_speeds_lo: [T; N],
}

impl<T: Real, const N: usize> CompensatedState<T, N> {
    /// Starts a compensated integration at `state` (every low-order part zero).
    #[inline]
    pub const fn new(state: State<T, N>) -> Self {
        Self {
            state,
            attitude_lo: Quat::ZERO,
            momentum_lo: Vec3::ZERO,
            wheel_speeds_lo: [T::ZERO; N],
        }
    }

    /// The state, each component rounded to `T`.
    #[inline]
    pub const fn state(&self) -> &State<T, N> {
        &self.state
    }

    /// The low-order part of the attitude quaternion: the attitude is the direction of
    /// `state().attitude + attitude_low()`.
    #[inline]
    pub const fn attitude_low(&self) -> Quat<T> {
        self.attitude_lo
    }

    /// The low-order part of the body momentum `J`.
    #[inline]
    pub const fn momentum_low(&self) -> Vec3<T> {
        self.momentum_lo
    }

    /// The low-order parts of the wheel speeds.
    #[inline]
    pub const fn wheel_speeds_low(&self) -> [T; N] {
        self.wheel_speeds_lo
    }

    /// `true` when every component and low-order part is finite.
    #[inline]
    pub fn is_finite(&self) -> bool {
        self.state.is_finite()
            && self.attitude_lo.is_finite()
            && self.momentum_lo.is_finite()
            && self.wheel_speeds_lo.iter().all(|w| w.is_finite())
    }
}

impl<T: Real, const N: usize> From<State<T, N>> for CompensatedState<T, N> {
    /// [`CompensatedState::new`].
    #[inline]
    fn from(state: State<T, N>) -> Self {
        Self::new(state)
    }
}

/// The inputs of one evaluation: external torque and wheel torques.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Control<T, const N: usize = 0> {
    /// External torque `τ`, body frame.
    pub torque: Vec3<T>,
    /// Wheel torques `ḣᵢ = I_wᵢ Ω̇ᵢ` (the rate of each wheel's momentum relative to the body).
    pub wheel_torques: [T; N],
}

impl<T: Real, const N: usize> Control<T, N> {
    /// No torque at all.
    pub const ZERO: Self = Self {
        torque: Vec3::ZERO,
        wheel_torques: [T::ZERO; N],
    };

    /// An external body-frame torque, with no wheel torque.
    #[inline]
    pub const fn torque(torque: Vec3<T>) -> Self {
        Self {
            torque,
            wheel_torques: [T::ZERO; N],
        }
    }

    /// `true` when every component is finite.
    #[inline]
    pub fn is_finite(&self) -> bool {
        self.torque.is_finite() && self.wheel_torques.iter().all(|u| u.is_finite())
    }
}

/// What the wheels are told to do during one step (see
/// [`crate::dynamics::Gyrostat::control`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WheelCommand<T, const N: usize> {
    /// Wheel torques `ḣᵢ = I_wᵢ Ω̇ᵢ`, held over the step.
    Torque([T; N]),
    /// Wheel speeds `Ωᵢ` (rad/s, relative to the body) to reach at the end of the step: an
    /// ideal speed loop, realised as the constant torque `I_wᵢ (Ωᵢ,cmd − Ωᵢ)/dt`.
    Speed([T; N]),
}

/// The input of a step: a [`Control`] evaluated at time `t` and a stage state.
///
/// Implemented for a [`Control`] value (held over the whole step) and for every closure
/// `FnMut(T, &State<T, N>) -> Control<T, N>` (a law evaluated at the integrator's stages). See
/// [`crate::dynamics::integrators`] for the order of the splitting methods with state-dependent
/// laws.
pub trait ControlLaw<T, const N: usize> {
    /// The control at time `t` in state `state`.
    fn control(&mut self, t: T, state: &State<T, N>) -> Control<T, N>;
}

impl<T: Real, const N: usize> ControlLaw<T, N> for Control<T, N> {
    #[inline]
    fn control(&mut self, _t: T, _state: &State<T, N>) -> Control<T, N> {
        *self
    }
}

impl<T, const N: usize, F> ControlLaw<T, N> for F
where
    F: FnMut(T, &State<T, N>) -> Control<T, N>,
{
    #[inline]
    fn control(&mut self, t: T, state: &State<T, N>) -> Control<T, N> {
        self(t, state)
    }
}
