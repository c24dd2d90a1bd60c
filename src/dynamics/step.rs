//! The step of a body: [`Gyrostat::step`] (torque-free) and [`Gyrostat::step_with`] (a held
//! [`Control`] or a control law), for a plain [`State`] or a [`CompensatedState`].
//!
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
//!
//! The step checks its input and its result and dispatches to the integrators
//! ([`crate::dynamics::integrators`]), which know the body and nothing of the step.

use crate::dynamics::gyrostat::Gyrostat;
use crate::dynamics::integrators::Integrator;
use crate::dynamics::integrators::splitting::{self, Stages};
use crate::dynamics::state::{CompensatedState, Control, ControlLaw, State};
use crate::step_limit::within_step_limit;
use crate::{Error, Real};

impl<T: Real, const N: usize> Gyrostat<T, N> {
    /// One torque-free step of length `dt`, the wheels coasting.
    ///
    /// `state` is a [`State`] (the plain step) or a [`CompensatedState`] (the compensated step,
    /// see [`crate::dynamics::integrators`]); the result is of the same type.
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
    /// [`Error::InvalidArgument`] for `dt ≤ 0`; [`Error::StepTooLong`] beyond the validity limit
    /// (for a splitting method, also when one of its pieces would turn by more than the limit:
    /// a cubic quartic term at high spin, whose pieces cancel in the net rate),
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
            Some(stages) => {
                self.check_pieces(state.plain(), stages.as_slice())?;
                splitting::free(self, state, stages.as_slice())
            }
            None => state.rk4(self, T::ZERO, dt, &mut torque_free),
        };
        self.finish(next, dt)
    }

    /// One step from time `t` with an input: a [`Control`] held over the step (see
    /// [`Gyrostat::control`]) or a law `f(t, state) → Control` evaluated at the integrator's
    /// stages. See [`crate::dynamics::integrators`] for the order of the splitting methods with
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
            Some(stages) => {
                self.check_pieces(state.plain(), stages.as_slice())?;
                splitting::kicked(self, state, t, stages.as_slice(), &mut input)
            }
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

    /// The splittings' own limit: every piece's rotation within the validity limit
    /// ([`splitting::pieces_within_limit`]; only the cubic quartic's pieces can exceed it while
    /// the net rate does not).
    #[inline]
    fn check_pieces(&self, state: &State<T, N>, stages: &[T]) -> Result<(), Error> {
        let s = self.rotor_momentum(&state.wheel_speeds);
        if splitting::pieces_within_limit(self.model(), state.momentum, s, stages) {
            Ok(())
        } else {
            Err(Error::StepTooLong)
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
/// step) or [`CompensatedState`] (the compensated step, [`crate::dynamics::integrators`]).
/// Sealed: implemented for these two types only.
pub trait StepState<T: Real, const N: usize>: sealed::Advance<T, N> {}

impl<T: Real, const N: usize> StepState<T, N> for State<T, N> {}
impl<T: Real, const N: usize> StepState<T, N> for CompensatedState<T, N> {}

mod sealed {
    use super::{CompensatedState, ControlLaw, Gyrostat, Real, State};
    use crate::dynamics::integrators::splitting::Flows;
    use crate::dynamics::integrators::{compensated_flows, rk4};

    /// The steps of a state type (crate-internal: the methods of [`super::StepState`]) beside
    /// its splitting flows ([`Flows`]).
    pub trait Advance<T: Real, const N: usize>: Flows<T, N> {
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
        fn rk4<L: ControlLaw<T, N>>(
            &self,
            body: &Gyrostat<T, N>,
            t: T,
            h: T,
            input: &mut L,
        ) -> Self {
            compensated_flows::rk4_step(body, self, t, h, input)
        }
        #[inline]
        fn plain(&self) -> &State<T, N> {
            &self.state
        }
        #[inline]
        fn renormalized(self) -> Option<Self> {
            compensated_flows::finish(self).ok()
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
