//! The Lie–Poisson splitting flows and their compositions: the exact one-axis rotations that
//! [`Integrator::Strang`], [`Integrator::Yoshida4`] and [`Integrator::Suzuki4`] are built from.
//!
//! The quadratic Hamiltonian in principal axes is a sum `Σ Hᵢ(Jᵢ)` of one-axis pieces; the flow
//! of `Hᵢ` keeps `Jᵢ` fixed and rotates `J` about `eᵢ` at the constant rate
//! `ωᵢ = H′ᵢ(Jᵢ) = 2Aᵢ(Jᵢ − Sᵢ)` (6.9.2), while the attitude turns about the same body axis by the
//! same angle, `q ← q ⊗ exp(θ eᵢ/2)`. Each sub-step is an exact rotation, so `|J|` and the lab
//! momentum `q J q*` are conserved to rounding and the energy error stays bounded (the method is
//! symplectic on the coadjoint orbit). The Strang step is `A₁(h/2) A₂(h/2) A₃(h) A₂(h/2)
//! A₁(h/2)` (order 2); Yoshida (1990, three stages) and Suzuki (1990, five-stage "fractal")
//! compose it symmetrically to order 4, Suzuki with a leading error constant ~100× smaller for
//! the rigid body of the tests, for 5/3 of the cost.
//!
//! External torque `τ` and reaction-wheel torques `ḣ` enter by splitting too: a "kick"
//! `J ← J + τ·h/2`, `Ωᵢ ← Ωᵢ + (ḣᵢ/I_wᵢ)·h/2` before and after the Hamiltonian flow (the wheel
//! torque is internal and does not change the total momentum `J`; it changes the rotor momentum
//! inside `H`). For a torque that depends on time and attitude only the kicks are exact flows and
//! the orders above hold; a torque that depends on `J` or `ω` (rate damping) makes the kick an
//! explicit Euler sub-step and the splitting first order — use RK4 for such laws.
//!
//! Quartic models (6.8.20) keep the structure: the octahedral term `t₄Jᵢ⁴` is a function of `Jᵢ`
//! alone, so it joins the i-th piece (rate `+4t₄Jᵢ³`); the cubic term is reduced with `|J|²`,
//! `J₁²J₂² + J₁²J₃² + J₂²J₃² = ½|J|⁴ − ½ΣJᵢ⁴`, into one-axis pieces (rate `−2t₂₂Jᵢ³`) plus the
//! Casimir `½t₂₂|J|⁴`, whose flow leaves `J` fixed and turns the attitude about `J` at the rate
//! `2t₂₂|J|²·|J|` (it commutes with every other piece). Every piece is again an exact rotation.
//!
//! In f32 these plain flows round `J` and `q` at every sub-step; over long runs that makes them
//! less accurate than a plain f32 RK4 at the same step. [`crate::dynamics::compensated`] has the
//! cause and the compensated flows a [`crate::dynamics::CompensatedState`] runs through.
//!
//! A non-diagonal inertia tensor is handled by rotating about its principal axes expressed in
//! the body frame (the columns of [`crate::dynamics::Inertia::principal_axes`]): the same exact
//! one-axis flows, with the Rodrigues form for a general axis.

use crate::dynamics::gyrostat::{Gyrostat, Integrator};
use crate::dynamics::hamiltonian::{BodyHamiltonian, Quartic};
use crate::dynamics::state::{ControlLaw, State};
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

/// The torque-free composition of Strang stages of lengths `stages` (negative lengths allowed),
/// the wheels coasting. With no kicks between stages, the closing `A₁(hₖ/2)` of a stage and the
/// opening `A₁(hₖ₊₁/2)` of the next are flows of the same one-axis piece and merge exactly into
/// `A₁((hₖ + hₖ₊₁)/2)` (one rotation fewer per stage boundary: Yoshida 13 rotations instead of
/// 15, Suzuki 21 instead of 25). The Casimir flow of a cubic term commutes with every piece and
/// is applied once for the whole step. Not renormalised.
pub(crate) fn free<T: Real, const N: usize>(
    body: &Gyrostat<T, N>,
    state: &State<T, N>,
    stages: &[T],
) -> State<T, N> {
    let model = body.model();
    let s = body.rotor_momentum(&state.wheel_speeds);
    let (mut q, mut j) = (state.attitude, state.momentum);
    let mut pending = T::ZERO;
    let mut total = T::ZERO;
    for &h in stages {
        let half = h * T::HALF;
        (q, j) = piece(model, Axis::X, q, j, s, pending + half);
        (q, j) = piece(model, Axis::Y, q, j, s, half);
        (q, j) = piece(model, Axis::Z, q, j, s, h);
        (q, j) = piece(model, Axis::Y, q, j, s, half);
        pending = half;
        total += h;
    }
    (q, j) = piece(model, Axis::X, q, j, s, pending);
    (q, j) = casimir(model, q, j, total);
    State {
        attitude: q,
        momentum: j,
        wheel_speeds: state.wheel_speeds,
    }
}

/// A symmetric composition of kick–drift–kick Strang stages of lengths `stages` from time `t`.
/// The last half-kick of a stage and the first of the next are merged into one kick: both are
/// evaluated at the same time and attitude, so for a torque law of time and attitude the result
/// is the same, with fewer law evaluations and fewer small increments rounded into `J` (which
/// matters in f32). Not renormalised.
pub(crate) fn kicked<T: Real, const N: usize, L: ControlLaw<T, N>>(
    body: &Gyrostat<T, N>,
    state: &State<T, N>,
    t: T,
    stages: &[T],
    input: &mut L,
) -> State<T, N> {
    let mut x = *state;
    let mut t = t;
    let mut pending = T::ZERO;
    for &h in stages {
        kick(body, &mut x, t, (pending + h) * T::HALF, input);
        let s = body.rotor_momentum(&x.wheel_speeds);
        (x.attitude, x.momentum) = drift(body.model(), x.attitude, x.momentum, s, h);
        t += h;
        pending = h;
    }
    kick(body, &mut x, t, pending * T::HALF, input);
    x
}

/// The kick of length `h`: `J ← J + τ h`, `Ωᵢ ← Ωᵢ + (ḣᵢ/I_wᵢ) h`, with the control at `(t, x)`.
#[inline]
fn kick<T: Real, const N: usize, L: ControlLaw<T, N>>(
    body: &Gyrostat<T, N>,
    x: &mut State<T, N>,
    t: T,
    h: T,
    input: &mut L,
) {
    let c = input.control(t, x);
    x.momentum += c.torque * h;
    for ((w, u), wheel) in x
        .wheel_speeds
        .iter_mut()
        .zip(c.wheel_torques.iter())
        .zip(body.wheels().iter())
    {
        *w += wheel.acceleration(*u) * h;
    }
}

/// The Hamiltonian flow for time `h` by the axis splitting, rotor momentum `s` held fixed:
/// `A₁(h/2) A₂(h/2) A₃(h) A₂(h/2) A₁(h/2)`, then the Casimir flow of a cubic term.
#[inline]
fn drift<T: Real>(
    model: &BodyHamiltonian<T>,
    q: UnitQuat<T>,
    j: Vec3<T>,
    s: Vec3<T>,
    h: T,
) -> (UnitQuat<T>, Vec3<T>) {
    let half = h * T::HALF;
    let (q, j) = piece(model, Axis::X, q, j, s, half);
    let (q, j) = piece(model, Axis::Y, q, j, s, half);
    let (q, j) = piece(model, Axis::Z, q, j, s, h);
    let (q, j) = piece(model, Axis::Y, q, j, s, half);
    let (q, j) = piece(model, Axis::X, q, j, s, half);
    casimir(model, q, j, h)
}

/// The flow of the principal piece along `axis` for time `h`. For a diagonal tensor the axis is
/// a body axis ([`principal_axis_flow`]); otherwise it is that principal axis expressed in the
/// body frame ([`general_axis_flow`]): rotating about it rather than moving `J` and `q` into the
/// principal frame and back, whose rounded round trip is not the identity (measured to drift f32
/// runs by ~1e-7 per stage).
#[inline]
fn piece<T: Real>(
    model: &BodyHamiltonian<T>,
    axis: Axis,
    q: UnitQuat<T>,
    j: Vec3<T>,
    s: Vec3<T>,
    h: T,
) -> (UnitQuat<T>, Vec3<T>) {
    let inertia = model.inertia();
    if inertia.is_diagonal() {
        principal_axis_flow(axis, model, q, j, s[axis], h)
    } else {
        let n = inertia.principal_axes().col(axis.index());
        general_axis_flow(n, model.half_inverse()[axis], q, j, s, h)
    }
}

/// `(sin θ/2, cos θ/2, 1 − cos θ, sin θ)` for `θ = rate·h`, the last two from the half angle
/// (`2 sin²(θ/2)`, `2 sin(θ/2) cos(θ/2)`): see [`principal_axis_flow`] for why.
#[inline(always)]
fn rotation_terms<T: Real>(rate: T, h: T) -> (T, T, T, T) {
    let (s2, c2) = (rate * h * T::HALF).sin_cos();
    (s2, c2, T::TWO * s2 * s2, T::TWO * s2 * c2)
}

/// The flow of the Casimir part `½t₂₂|J|⁴` of a cubic term: `ω = 2t₂₂|J|²J`, `J` fixed,
/// `q ← q ⊗ exp(ω h)`. The identity for the other models.
#[inline]
fn casimir<T: Real>(
    model: &BodyHamiltonian<T>,
    q: UnitQuat<T>,
    j: Vec3<T>,
    h: T,
) -> (UnitQuat<T>, Vec3<T>) {
    match model.quartic() {
        Quartic::Cubic(t22) => {
            let rate = T::TWO * t22 * j.norm_squared();
            (q * UnitQuat::exp_unchecked(j * (rate * h)), j)
        }
        _ => (q, j),
    }
}

/// The exact flow of the one-axis piece `Hᵢ(Jᵢ)` about the body axis `axis` (diagonal tensor),
/// `si` the rotor momentum along it: `Jᵢ` fixed, rate `ωᵢ = H′ᵢ(Jᵢ)`, `J ← R_i(−θ) J`, `q ← q ⊗ (cos θ/2, sin θ/2 eᵢ)`, `θ = ωᵢ h`.
#[inline]
fn principal_axis_flow<T: Real>(
    axis: Axis,
    model: &BodyHamiltonian<T>,
    q: UnitQuat<T>,
    j: Vec3<T>,
    si: T,
    h: T,
) -> (UnitQuat<T>, Vec3<T>) {
    let (ai, ji) = (model.half_inverse()[axis], j[axis]);
    // Quartic one-axis rates: octahedral +4t₄Jᵢ³, cubic (reduced) −2t₂₂Jᵢ³.
    let k = match model.quartic() {
        Quartic::None => T::ZERO,
        Quartic::Octahedral(t4) => T::from_f64(4.0) * t4,
        Quartic::Cubic(t22) => -T::TWO * t22,
    };
    let rate = T::TWO * ai * (ji - si) + k * ji * ji * ji;
    // The plane rotation by −θ is applied as J + (s·J⊥′ − v·J⊥) with v = 1 − cos θ = 2s₂² and
    // s = sin θ = 2s₂c₂ (s₂, c₂ of the half angle). Forming cos θ itself would round a number
    // next to 1 the same way at every sub-step (slowly varying θ), scaling |J| by the same
    // (1 ± ε) again and again: a linear drift of |J| (measured 2.6e-3 over 10⁵ f32 steps). The
    // small corrections v·J, s·J keep full relative precision instead, and the rounding of the
    // final sums is unbiased (measured: 4e-14 relative f64, see tests).
    let (s2, c2, v, sn) = rotation_terms(rate, h);
    let Quat { w, x, y, z } = q.into_quat();
    let (q, j) = match axis {
        Axis::X => (
            Quat::new(
                w * c2 - x * s2,
                w * s2 + x * c2,
                y * c2 + z * s2,
                z * c2 - y * s2,
            ),
            Vec3::new(j.x, j.y + (sn * j.z - v * j.y), j.z - (sn * j.y + v * j.z)),
        ),
        Axis::Y => (
            Quat::new(
                w * c2 - y * s2,
                x * c2 - z * s2,
                w * s2 + y * c2,
                z * c2 + x * s2,
            ),
            Vec3::new(j.x - (sn * j.z + v * j.x), j.y, j.z + (sn * j.x - v * j.z)),
        ),
        Axis::Z => (
            Quat::new(
                w * c2 - z * s2,
                x * c2 + y * s2,
                y * c2 - x * s2,
                w * s2 + z * c2,
            ),
            Vec3::new(j.x + (sn * j.y - v * j.x), j.y - (sn * j.x + v * j.y), j.z),
        ),
    };
    // A product with an exact rotation: unit to rounding.
    (UnitQuat::new_unchecked(q), j)
}

/// The exact flow of `Aᵢ (n·(J − s))²` about a unit body-frame axis `n`: rate
/// `ωᵢ = 2Aᵢ n·(J − s)`, `J ← R(n, −θ) J = J − sin θ (n × J) + (1 − cos θ) n × (n × J)`,
/// `q ← q ⊗ (cos θ/2, sin θ/2 · n)`, with `1 − cos θ = 2 sin²(θ/2)` (see
/// [`principal_axis_flow`]).
#[inline]
fn general_axis_flow<T: Real>(
    n: Vec3<T>,
    ai: T,
    q: UnitQuat<T>,
    j: Vec3<T>,
    s: Vec3<T>,
    h: T,
) -> (UnitQuat<T>, Vec3<T>) {
    let rate = T::TWO * ai * n.dot(j - s);
    let (s2, c2, v, sn) = rotation_terms(rate, h);
    let nj = n.cross(j);
    let j = j + (n.cross(nj) * v - nj * sn);
    // `n` is a unit column of a rotation matrix: the factor is a unit quaternion to rounding.
    let q = q * UnitQuat::new_unchecked(Quat::from_parts(c2, n * s2));
    (q, j)
}
