//! The checked streaming integrator of rate samples: [`RateIntegrator`].

use heapless::Vec as HVec;

#[cfg(doc)]
use crate::propagation::CompensatedAttitude;
use crate::propagation::attitude::PropagatedAttitude;
use crate::propagation::normalization::Normalization;
use crate::propagation::rate_samples::{RateMethod, W2, W3, W4, Weights};
use crate::step_limit::within_step_limit;
use crate::{Error, Real, UnitQuat, Vec3};

#[cfg(doc)]
use crate::propagation::kernels::{cf4_step, magnus4_step, rk4_step};

/// The checks of [`RateIntegrator::push`] on one sample, with its errors.
///
/// `|ωᵢ| < MAX/4 ⇔ 4ω is finite` (and a finite `4ω` implies a finite `ω`, so one test covers
/// both until it fails): then every weighted sum of the window (the weights' magnitudes add up
/// to at most 1.625) and every RK4 stage stays finite. Out of line, like
/// [`RateIntegrator::start_up`], so that `push` stays small enough for LLVM to inline the whole
/// steady-state step into it (measured on the Cortex-M4F: otherwise the compensated step's
/// quaternion products stay calls).
#[inline(never)]
fn check_sample<T: Real>(omega: Vec3<T>, dt: T) -> Result<(), Error> {
    if !omega.scale(T::from_f64(4.0)).is_finite() {
        return Err(if omega.is_finite() {
            Error::InvalidArgument
        } else {
            Error::NonFinite
        });
    }
    if !within_step_limit(omega.scale(dt)) {
        return Err(Error::StepTooLong);
    }
    Ok(())
}

/// The attitudes at the sample times a [`RateIntegrator`] call newly reached, oldest first.
pub type Attitudes<T> = HVec<UnitQuat<T>, 3>;

/// Streaming rate-sample integrator: owns the attitude and the last four samples.
///
/// Feed the samples `ω₀, ω₁, …` (body frame, rad/s, equally spaced by `dt`) with
/// [`RateIntegrator::push`]; it returns the attitudes at the sample times it newly reached:
/// `[q(t₀)] = [q0]` after sample 0, nothing after samples 1 and 2, `[q(t₁), q(t₂), q(t₃)]`
/// after sample 3 (the start-up window), then `[q(tₖ)]` after each sample `k`. A record of
/// fewer than four samples is completed by [`RateIntegrator::finish`]. See the module docs for
/// the interpolation.
///
/// The attitude it carries is a [`UnitQuat`] (the plain update) or, when it is started from a
/// [`CompensatedAttitude`], the compensated pair (see [`crate::propagation::compensated_attitude`]).
#[derive(Clone, Debug)]
pub struct RateIntegrator<T, A = UnitQuat<T>> {
    q: A,
    method: RateMethod,
    norm: Normalization,
    dt: T,
    /// `dt`'s rounding remainder (used by the compensated attitude).
    dt_lo: T,
    /// The last samples, oldest first; the first `count` are valid while `count < 4`.
    window: [Vec3<T>; 4],
    count: u8,
}

impl<T: Real, A: PropagatedAttitude<T>> RateIntegrator<T, A> {
    /// Starts at attitude `q0` (a [`UnitQuat`] or a [`CompensatedAttitude`]) with sample
    /// interval `dt` (seconds).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite `dt` or `q0`; [`Error::InvalidArgument`] for
    /// `dt ≤ 0`.
    pub fn try_new(q0: A, method: RateMethod, norm: Normalization, dt: T) -> Result<Self, Error> {
        if !dt.is_finite() || !q0.attitude().as_quat().is_finite() {
            return Err(Error::NonFinite);
        }
        if dt <= T::ZERO {
            return Err(Error::InvalidArgument);
        }
        Ok(Self {
            q: q0,
            method,
            norm,
            dt,
            dt_lo: T::ZERO,
            window: [Vec3::ZERO; 4],
            count: 0,
        })
    }

    /// Sets the rounding remainder of the sample interval, `dt_lo = dt_exact − dt` (for example
    /// `(0.001 − f64::from(0.001f32)) as f32` for 1 kHz in f32), which the compensated attitude
    /// adds to every step: without it an f32 step of 1 ms is 4.7e-8 relative too long, 1.8e-4 rad
    /// an hour at 1 rad/s. The plain attitude ignores it.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite `dt_lo`; [`Error::InvalidArgument`] for
    /// `|dt_lo| > ε·dt` (`ε` the machine epsilon): a rounding remainder of `dt` is at most half
    /// an ulp of `dt`, `ε·dt/2`; anything larger is not one (and a remainder of the size of `dt`
    /// or beyond would make every step's products overflow or mean a different step).
    pub fn try_with_step_remainder(mut self, dt_lo: T) -> Result<Self, Error> {
        if !dt_lo.is_finite() {
            return Err(Error::NonFinite);
        }
        if dt_lo.abs() > T::EPSILON * self.dt {
            return Err(Error::InvalidArgument);
        }
        self.dt_lo = dt_lo;
        Ok(self)
    }

    /// The latest attitude computed (at the time of the newest sample once four have arrived).
    pub fn attitude(&self) -> UnitQuat<T> {
        self.q.attitude()
    }

    /// The carried attitude (for a [`CompensatedAttitude`], with its low part).
    pub fn carried_attitude(&self) -> A {
        self.q
    }

    /// One step over an interval of an `M`-sample window, given that interval's weight rows.
    #[inline(always)]
    fn advance<const M: usize>(&mut self, s: &[Vec3<T>; M], w: &Weights<M>) -> UnitQuat<T> {
        self.q = self
            .q
            .rates(self.method, s, w, self.dt, self.dt_lo, self.norm);
        self.q.attitude()
    }

    /// The fourth sample: completes the start-up window and integrates its three intervals.
    /// Once per record, so kept out of [`RateIntegrator::push`]'s steady-state path.
    #[cold]
    #[inline(never)]
    fn start_up(&mut self, omega: Vec3<T>) -> Attitudes<T> {
        let mut out = Attitudes::new();
        let [a, b, c, _] = self.window;
        let s = [a, b, c, omega];
        self.window = s;
        self.count = 4;
        for w in &W4 {
            let q = self.advance(&s, w);
            let _ = out.push(q);
        }
        out
    }

    /// Adds the next rate sample (rad/s, body frame) and integrates every interval it completes.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite component; [`Error::InvalidArgument`] for a
    /// component beyond a quarter of the type's largest value (the interpolant's weighted sums of
    /// four samples would overflow); [`Error::StepTooLong`] when the
    /// sample turns the body by more than [`MAX_STEP_ANGLE`](crate::step_limit::MAX_STEP_ANGLE) in one sample interval
    /// (`|ω|·dt > π`, where the methods' series stop converging; the interpolated node rates are
    /// at most 1.625 times the largest sample of the window, the largest sum of the magnitudes of
    /// the cubic Lagrange weights, so every step stays below `2π`). Either way the sample is
    /// discarded and the state is unchanged.
    pub fn push(&mut self, omega: Vec3<T>) -> Result<Attitudes<T>, Error> {
        check_sample(omega, self.dt)?;
        let mut out = Attitudes::new();
        match self.count {
            0..=2 => {
                if let Some(slot) = self.window.get_mut(usize::from(self.count)) {
                    *slot = omega;
                }
                self.count += 1;
                if self.count == 1 {
                    let _ = out.push(self.q.attitude());
                }
            }
            3 => out = self.start_up(omega),
            _ => {
                let [_, b, c, d] = self.window;
                let s = [b, c, d, omega];
                self.window = s;
                let q = self.advance(&s, &W4[2]);
                let _ = out.push(q);
            }
        }
        Ok(out)
    }

    /// Ends the record: integrates what a record of fewer than four samples left pending (two
    /// samples: the linear interpolant, order 2; three: the quadratic one) and returns those
    /// attitudes. After four or more samples everything was already integrated and the result is
    /// empty.
    pub fn finish(mut self) -> Attitudes<T> {
        let mut out = Attitudes::new();
        let [a, b, c, _] = self.window;
        match self.count {
            2 => {
                let _ = out.push(self.advance(&[a, b], &W2[0]));
            }
            3 => {
                for w in &W3 {
                    let q = self.advance(&[a, b, c], w);
                    let _ = out.push(q);
                }
            }
            _ => {}
        }
        out
    }
}

#[cfg(feature = "defmt")]
impl<T: Real + defmt::Format> defmt::Format for RateIntegrator<T> {
    fn format(&self, f: defmt::Formatter<'_>) {
        defmt::write!(
            f,
            "RateIntegrator(q={}, method={}, norm={}, dt={}, samples={})",
            self.q,
            self.method,
            self.norm,
            self.dt,
            self.count
        )
    }
}
