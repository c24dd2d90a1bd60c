//! The Lie–Poisson splittings (see the [module docs](super)): the stages of each method, their
//! composition, written once over the one-axis flows of a state kind ([`Flows`]), and the plain
//! flows of a [`State`]. The compensated flows of a [`crate::dynamics::CompensatedState`] are in
//! [`super::compensated`].

use crate::dynamics::gyrostat::Gyrostat;
use crate::dynamics::hamiltonian::{BodyHamiltonian, Quartic};
use crate::dynamics::integrators::Integrator;
use crate::dynamics::state::{ControlLaw, State};
use crate::step_limit::within_step_limit;
use crate::{Axis, Quat, Real, UnitQuat, Vec3};

/// Yoshida (1990) order-4 outer weight `w₁ = 1/(2 − 2^{1/3})`; middle stage `w₀ = 1 − 2w₁`.
const YOSHIDA_W1: f64 = 1.351_207_191_959_657_6;
/// Suzuki (1990) order-4 weight `p = 1/(4 − 4^{1/3})`; middle stage `1 − 4p`.
const SUZUKI_P: f64 = 0.414_490_771_794_375_7;

/// The Strang stage lengths of a splitting method for one step (1, 3 or 5 stages).
pub(crate) struct Stages<T> {
    h: [T; 5],
    len: usize,
}

impl<T: Real> Stages<T> {
    /// The stages of `integrator` for a step `dt`; `None` for RK4, which is not a splitting.
    /// The middle stage is `dt` minus the others, so that the stages add up to `dt` in `T`
    /// exactly.
    #[inline]
    pub(crate) fn of(integrator: Integrator, dt: T) -> Option<Self> {
        let z = T::ZERO;
        match integrator {
            Integrator::Rk4 => None,
            Integrator::Strang => Some(Self {
                h: [dt, z, z, z, z],
                len: 1,
            }),
            Integrator::Yoshida4 => {
                let h1 = dt * T::from_f64(YOSHIDA_W1);
                Some(Self {
                    h: [h1, dt - T::TWO * h1, h1, z, z],
                    len: 3,
                })
            }
            Integrator::Suzuki4 => {
                let p = dt * T::from_f64(SUZUKI_P);
                let mid = dt - T::from_f64(4.0) * p;
                Some(Self {
                    h: [p, p, mid, p, p],
                    len: 5,
                })
            }
        }
    }

    /// The stage lengths, in order.
    #[inline]
    pub(crate) fn as_slice(&self) -> &[T] {
        self.h.get(..self.len).unwrap_or(&[])
    }
}

/// The exact one-axis flows of a kind of state (a plain [`State`], or a compensated state that
/// carries its rounding errors), and its kick: everything the composition of a splitting method
/// needs. The composition ([`free`], [`kicked`]) is written once over this trait; the rates of
/// the flows are computed there too ([`axis_rate`]), so the two kinds differ only in how they
/// apply a rotation and add an increment.
pub trait Flows<T: Real, const N: usize>: Copy {
    /// The attitude and momentum the flows turn (with their low-order parts for a compensated
    /// state), held apart from the wheel speeds while a drift runs.
    type Turned: Copy;
    /// The attitude and momentum of the state.
    fn turned(&self) -> Self::Turned;
    /// Stores the attitude and momentum back into the state.
    fn set_turned(&mut self, turned: Self::Turned);
    /// The body momentum `J` (rounded to `T`): what the rates are computed from.
    fn momentum(turned: &Self::Turned) -> Vec3<T>;
    /// The wheel speeds (rounded to `T`).
    fn wheel_speeds(&self) -> &[T; N];
    /// The flow about the body axis `axis` at the rate `rate` for time `h`: `J` turned by
    /// `−θ` in the plane of the other two axes, `q ← q ⊗ (cos θ/2, sin θ/2 eᵢ)`, `θ = rate·h`.
    fn principal_axis_flow(turned: &mut Self::Turned, axis: Axis, rate: T, h: T);
    /// The flow about the unit body-frame axis `n` at the rate `rate` for time `h`:
    /// `J ← R(n, −θ) J`, `q ← q ⊗ (cos θ/2, sin θ/2 · n)`.
    fn general_axis_flow(turned: &mut Self::Turned, n: Vec3<T>, rate: T, h: T);
    /// The Casimir flow of a cubic term: `J` fixed, `q ← q ⊗ exp(rate·h·J)`.
    fn casimir_flow(turned: &mut Self::Turned, rate: T, h: T);
    /// The kick of length `h`: `J ← J + τ h`, `Ωᵢ ← Ωᵢ + (ḣᵢ/I_wᵢ) h`, with the control at `t`
    /// and the state.
    fn kick<L: ControlLaw<T, N>>(&mut self, body: &Gyrostat<T, N>, t: T, h: T, input: &mut L);
}

/// The torque-free composition of Strang stages of lengths `stages` (negative lengths allowed),
/// the wheels coasting. With no kicks between stages, the closing `A₁(hₖ/2)` of a stage and the
/// opening `A₁(hₖ₊₁/2)` of the next are flows of the same one-axis piece and merge exactly into
/// `A₁((hₖ + hₖ₊₁)/2)` (one rotation fewer per stage boundary: Yoshida 13 rotations instead of
/// 15, Suzuki 21 instead of 25). The Casimir flow of a cubic term commutes with every piece and
/// is applied once for the whole step. Not renormalised.
#[inline]
pub(crate) fn free<T: Real, const N: usize, S: Flows<T, N>>(
    body: &Gyrostat<T, N>,
    state: &S,
    stages: &[T],
) -> S {
    let model = body.model();
    let s = body.rotor_momentum(state.wheel_speeds());
    let mut x = state.turned();
    let mut pending = T::ZERO;
    let mut total = T::ZERO;
    for &h in stages {
        let half = h * T::HALF;
        piece::<T, N, S>(model, Axis::X, &mut x, s, pending + half);
        piece::<T, N, S>(model, Axis::Y, &mut x, s, half);
        piece::<T, N, S>(model, Axis::Z, &mut x, s, h);
        piece::<T, N, S>(model, Axis::Y, &mut x, s, half);
        pending = half;
        total += h;
    }
    piece::<T, N, S>(model, Axis::X, &mut x, s, pending);
    casimir::<T, N, S>(model, &mut x, total);
    let mut next = *state;
    next.set_turned(x);
    next
}

/// A symmetric composition of kick–drift–kick Strang stages of lengths `stages` from time `t`.
/// The last half-kick of a stage and the first of the next are merged into one kick: both are
/// evaluated at the same time and attitude, so for a torque law of time and attitude the result
/// is the same, with fewer law evaluations and fewer small increments rounded into `J` (which
/// matters in f32). Not renormalised.
#[inline]
pub(crate) fn kicked<T: Real, const N: usize, S: Flows<T, N>, L: ControlLaw<T, N>>(
    body: &Gyrostat<T, N>,
    state: &S,
    t: T,
    stages: &[T],
    input: &mut L,
) -> S {
    let mut x = *state;
    let mut t = t;
    let mut pending = T::ZERO;
    for &h in stages {
        x.kick(body, t, (pending + h) * T::HALF, input);
        let s = body.rotor_momentum(x.wheel_speeds());
        let mut turned = x.turned();
        drift::<T, N, S>(body.model(), &mut turned, s, h);
        x.set_turned(turned);
        t += h;
        pending = h;
    }
    x.kick(body, t, pending * T::HALF, input);
    x
}

/// The Hamiltonian flow for time `h` by the axis splitting, rotor momentum `s` held fixed:
/// `A₁(h/2) A₂(h/2) A₃(h) A₂(h/2) A₁(h/2)`, then the Casimir flow of a cubic term.
#[inline]
fn drift<T: Real, const N: usize, S: Flows<T, N>>(
    model: &BodyHamiltonian<T>,
    x: &mut S::Turned,
    s: Vec3<T>,
    h: T,
) {
    let half = h * T::HALF;
    piece::<T, N, S>(model, Axis::X, x, s, half);
    piece::<T, N, S>(model, Axis::Y, x, s, half);
    piece::<T, N, S>(model, Axis::Z, x, s, h);
    piece::<T, N, S>(model, Axis::Y, x, s, half);
    piece::<T, N, S>(model, Axis::X, x, s, half);
    casimir::<T, N, S>(model, x, h);
}

/// The flow of the principal piece along `axis` for time `h`. For a diagonal tensor the axis is
/// a body axis ([`Flows::principal_axis_flow`]); otherwise it is that principal axis expressed in
/// the body frame ([`Flows::general_axis_flow`]): rotating about it rather than moving `J` and
/// `q` into the principal frame and back, whose rounded round trip is not the identity (measured
/// to drift f32 runs by ~1e-7 per stage).
#[inline]
fn piece<T: Real, const N: usize, S: Flows<T, N>>(
    model: &BodyHamiltonian<T>,
    axis: Axis,
    x: &mut S::Turned,
    s: Vec3<T>,
    h: T,
) {
    let inertia = model.inertia();
    if inertia.is_diagonal() {
        let rate = axis_rate(model, axis, S::momentum(x)[axis], s[axis]);
        S::principal_axis_flow(x, axis, rate, h);
    } else {
        let n = inertia.principal_axes().col(axis.index());
        // The piece `Aᵢ (n·(J − s))²`: rate `ωᵢ = 2Aᵢ n·(J − s)`.
        let rate = T::TWO * model.half_inverse()[axis] * n.dot(S::momentum(x) - s);
        S::general_axis_flow(x, n, rate, h);
    }
}

/// The rate `ωᵢ = H′ᵢ(Jᵢ)` of the one-axis piece along the body axis `axis` (diagonal tensor),
/// `si` the rotor momentum along it: `2Aᵢ(Jᵢ − sᵢ)` (6.9.2), plus the quartic one-axis rates,
/// octahedral `+4t₄Jᵢ³`, cubic (reduced) `−2t₂₂Jᵢ³`.
#[inline(always)]
fn axis_rate<T: Real>(model: &BodyHamiltonian<T>, axis: Axis, ji: T, si: T) -> T {
    let ai = model.half_inverse()[axis];
    let k = match model.quartic() {
        Quartic::None => T::ZERO,
        Quartic::Octahedral(t4) => T::from_f64(4.0) * t4,
        Quartic::Cubic(t22) => -T::TWO * t22,
    };
    T::TWO * ai * (ji - si) + k * ji * ji * ji
}

/// `true` when every rotation a splitting step of `stages` makes stays within
/// [`MAX_STEP_ANGLE`](crate::step_limit::MAX_STEP_ANGLE), for a body of momentum `j` and rotor
/// momentum `s`.
///
/// For every model but the cubic quartic the pieces' rates are components of the body rate `ω`
/// (`Hᵢ′(Jᵢ)`), which the net check `|ω|·dt ≤ π` already bounds. The cubic term is split as
/// one-axis pieces of rate `2Aᵢ(Jᵢ − sᵢ) − 2t₂₂Jᵢ³` and the Casimir flow of rate `2t₂₂|J|²`
/// about `J`: at a high spin these are huge rotations that cancel in `ω` (sphere 1e10,
/// `t₂₂ = 10⁻³`, `J = 10⁶ e_y`: `|ω| = 10⁻⁴` but pieces of 2·10¹⁵ rad, rounded to a quarter of a
/// radian each in f64), and the step loses the attitude while the net check passes. Bounded
/// here with `|Jᵢ| ≤ |J|` (which every piece preserves) and the longest stage.
#[inline]
pub(crate) fn pieces_within_limit<T: Real>(
    model: &BodyHamiltonian<T>,
    j: Vec3<T>,
    s: Vec3<T>,
    stages: &[T],
) -> bool {
    let Quartic::Cubic(t22) = model.quartic() else {
        return true;
    };
    let h = stages.iter().fold(T::ZERO, |m, h| m.max(h.abs()));
    let n2 = j.norm_squared();
    let n = n2.sqrt();
    let quartic = (T::TWO * t22).abs() * n2 * n;
    let casimir = (T::TWO * t22).abs() * n2 * n * h;
    let axis = |a: Axis| {
        let rate = T::TWO * model.half_inverse()[a].abs() * (n + s[a].abs()) + quartic;
        within_step_limit(Vec3::new(rate * h, T::ZERO, T::ZERO))
    };
    axis(Axis::X)
        && axis(Axis::Y)
        && axis(Axis::Z)
        && within_step_limit(Vec3::new(casimir, T::ZERO, T::ZERO))
}

/// The flow of the Casimir part `½t₂₂|J|⁴` of a cubic term: `ω = 2t₂₂|J|²J`, `J` fixed,
/// `q ← q ⊗ exp(ω h)`. The identity for the other models.
#[inline]
fn casimir<T: Real, const N: usize, S: Flows<T, N>>(
    model: &BodyHamiltonian<T>,
    x: &mut S::Turned,
    h: T,
) {
    if let Quartic::Cubic(t22) = model.quartic() {
        let rate = T::TWO * t22 * S::momentum(x).norm_squared();
        S::casimir_flow(x, rate, h);
    }
}

/// The two body axes after `axis` in cyclic order: the plane a rotation about `axis` turns.
#[inline(always)]
pub(crate) fn plane(axis: Axis) -> (Axis, Axis) {
    (axis.next(), axis.next().next())
}

/// `q ⊗ (c, s·eᵢ)` for the body axis `eᵢ = axis`.
#[inline(always)]
pub(crate) fn times_axis<T: Real>(q: Quat<T>, axis: Axis, c: T, s: T) -> Quat<T> {
    let Quat { w, x, y, z } = q;
    match axis {
        Axis::X => Quat::new(w * c - x * s, w * s + x * c, y * c + z * s, z * c - y * s),
        Axis::Y => Quat::new(w * c - y * s, x * c - z * s, w * s + y * c, z * c + x * s),
        Axis::Z => Quat::new(w * c - z * s, x * c + y * s, y * c - x * s, w * s + z * c),
    }
}

/// `(sin θ/2, cos θ/2, 1 − cos θ, sin θ)` for `θ = rate·h`, the last two from the half angle
/// (`2 sin²(θ/2)`, `2 sin(θ/2) cos(θ/2)`): see the plain [`Flows::principal_axis_flow`] for why.
#[inline(always)]
fn rotation_terms<T: Real>(rate: T, h: T) -> (T, T, T, T) {
    let (s2, c2) = (rate * h * T::HALF).sin_cos();
    (s2, c2, T::TWO * s2 * s2, T::TWO * s2 * c2)
}

/// The attitude and momentum of a plain state.
#[derive(Clone, Copy, Debug)]
pub struct Plain<T> {
    q: UnitQuat<T>,
    j: Vec3<T>,
}

/// The plain flows: each sub-step an exact rotation, rounded to `T`.
impl<T: Real, const N: usize> Flows<T, N> for State<T, N> {
    type Turned = Plain<T>;

    #[inline(always)]
    fn turned(&self) -> Plain<T> {
        Plain {
            q: self.attitude,
            j: self.momentum,
        }
    }

    #[inline(always)]
    fn set_turned(&mut self, turned: Plain<T>) {
        self.attitude = turned.q;
        self.momentum = turned.j;
    }

    #[inline(always)]
    fn momentum(turned: &Plain<T>) -> Vec3<T> {
        turned.j
    }

    #[inline(always)]
    fn wheel_speeds(&self) -> &[T; N] {
        &self.wheel_speeds
    }

    /// The plane rotation by `−θ` is applied as `J + (s·J⊥′ − v·J⊥)` with `v = 1 − cos θ = 2s₂²`
    /// and `s = sin θ = 2s₂c₂` (`s₂`, `c₂` of the half angle). Forming `cos θ` itself would round
    /// a number next to 1 the same way at every sub-step (slowly varying `θ`), scaling `|J|` by
    /// the same `(1 ± ε)` again and again: a linear drift of `|J|` (measured 2.6e-3 over 10⁵ f32
    /// steps). The small corrections `v·J`, `s·J` keep full relative precision instead, and the
    /// rounding of the final sums is unbiased (measured: 4e-14 relative f64, see tests).
    #[inline]
    fn principal_axis_flow(x: &mut Plain<T>, axis: Axis, rate: T, h: T) {
        let (s2, c2, v, sn) = rotation_terms(rate, h);
        let (a, b) = plane(axis);
        let (ja, jb) = (x.j[a], x.j[b]);
        x.j[a] = ja + (sn * jb - v * ja);
        x.j[b] = jb - (sn * ja + v * jb);
        // A product with an exact rotation: unit to rounding.
        x.q = UnitQuat::new_unchecked(times_axis(x.q.into_quat(), axis, c2, s2));
    }

    /// `J ← J − sin θ (n × J) + (1 − cos θ) n × (n × J)`, with `1 − cos θ = 2 sin²(θ/2)` (see
    /// the principal-axis flow).
    #[inline]
    fn general_axis_flow(x: &mut Plain<T>, n: Vec3<T>, rate: T, h: T) {
        let (s2, c2, v, sn) = rotation_terms(rate, h);
        let nj = n.cross(x.j);
        x.j += n.cross(nj) * v - nj * sn;
        // `n` is a unit column of a rotation matrix: the factor is a unit quaternion to rounding.
        x.q = x.q * UnitQuat::new_unchecked(Quat::from_parts(c2, n * s2));
    }

    #[inline]
    fn casimir_flow(x: &mut Plain<T>, rate: T, h: T) {
        x.q = x.q * UnitQuat::exp_unchecked(x.j * (rate * h));
    }

    #[inline]
    fn kick<L: ControlLaw<T, N>>(&mut self, body: &Gyrostat<T, N>, t: T, h: T, input: &mut L) {
        let c = input.control(t, self);
        self.momentum += c.torque * h;
        for ((w, u), wheel) in self
            .wheel_speeds
            .iter_mut()
            .zip(c.wheel_torques.iter())
            .zip(body.wheels().iter())
        {
            *w += wheel.acceleration(*u) * h;
        }
    }
}
