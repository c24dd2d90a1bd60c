//! Compensated steps: the splitting and RK4 steps of a [`CompensatedState`], accurate in f32.
//!
//! # Why a plain f32 splitting loses to RK4
//! Every sub-step of a splitting method is an exact rotation, yet in f32 the plain Yoshida4 and
//! Suzuki4 steps end 2.9–108× further from the truth than a plain f32 RK4 at the same step
//! (`dt = 0.004`, horizons 12–60, eight well-conditioned torque-free cases), and 1300–2900×
//! further with a constant torque. The causes, found by changing one thing at a time in a
//! replica of these flows that reproduces the library bit for bit
//! (`host-tests/tests/dynamics_f32_rounding.rs`, `cause_experiment`; the table is in
//! BENCHMARKS.md, "Dynamics in f32"):
//!
//! - *Rounding the value at every sub-step.* Each of the 13 (Yoshida) or 21 (Suzuki) rotations
//!   of a step rounds `J` and `q` to f32, where RK4 rounds them once per step. An error in `J`
//!   changes the rates, so the phase error it causes keeps growing after it is made: the errors
//!   are amplified, not just added. Carrying each rounding error instead of dropping it (below)
//!   takes the errors from 2.9–108× RK4's to 0.01–2.3×. Making the roundings unbiased (stochastic
//!   rounding in the replica) does not: 0.4–97×, worse than round-to-nearest on the symmetric
//!   tops, where nearest rounding happens to return the spin component to the same value.
//! - *Rounding the same way every time.* A constant kick `J ← J + τh` rounds with the same sign
//!   while `J` stays in one binade (mean signed error −0.43 … +0.34 ulp per kick, as large as
//!   its magnitude): a bias. The half angle of a sub-step, `ψ = rate·h/2`, and `sin ψ` are
//!   rounded to f32 the same way at every sub-step when the rate is constant (a symmetric top
//!   about its axis): the body turns by the same wrong angle each time, a phase error growing
//!   with the total angle turned. It is what is left after the carry (oblate top 2.2×) and it
//!   is not the `sin` kernel: f64-rounded `sin`/`cos` give the same numbers to three digits.
//!
//! Ruled out by the same experiment: the f32 `sin`/`cos` kernel, the merging of same-axis
//! rotations at stage boundaries, and, alone, the multiplicative form of the co-rotation
//! (`q·cos ψ + sin ψ·(q ⊗ eᵢ)`; the increment form alone changes the errors by 0.3–1.4×).
//!
//! # The compensated step
//! 1. *Increment form*: every update is `x ← x + d` with a small increment `d`: the co-rotation
//!    `q ← q + q ⊗ (cos ψ − 1, sin ψ·eᵢ)`, the momentum `J ← J + (R − 1)J`, the kick
//!    `J ← J + τh`, the renormalisation `q ← q + q·(1 − |q|²)/2`.
//! 2. *Compensated sums*: each increment is added through Fast2Sum and the rounding error is
//!    carried to the next update, `(x, e) ← Fast2Sum(x, d + e)`, the increment computed from
//!    the carried value (`d = (R − 1)(J + e_J)`, `d = (q + e_q) ⊗ (…)`);
//! 3. *the carry kept across steps* in the [`CompensatedState`];
//! 4. *exact half angles*: `ψ = rate·(h/2)` is formed exactly as a pair (Dekker's product) and
//!    `sin ψ = ψ + ψ³·(…)` by its Taylor series, so that only the small tail is rounded; the
//!    kicks' `τh` and RK4's `h/6` are exact pairs too.
//!
//! Each increment is added as a double-f32 sum (`crate::compensated`'s `add_pair`): its small
//! parts (the low part of `sin ψ`, the carried errors' share) below an ulp of the increment
//! would otherwise round away the same way every time.
//!
//! With all four, the f32 Yoshida4 and Suzuki4 errors are 0.002–0.11× those of a plain f32 RK4
//! at the same step on the eight cases, 0.16× with a constant torque; over 10⁶ steps `|J|`
//! drifts ≤ 2.1e-7 relative and the lab momentum ≤ 2.7e-7 (plain: 8e-6…1e-3 and 2e-4…1e-2);
//! the energy error is the random walk of the increments' roundings (1.0e-6 after 10⁶ steps at
//! `dt = 0.1`, against a drift to 2.5e-4 for the plain step); RK4 on a compensated state is
//! 0.001–0.12× the plain RK4. Costs are in BENCHMARKS.md (Cortex-M4F
//! instruction counts beside the plain rows, host times). The plain [`State`] keeps the plain,
//! cheaper flows: use it for short horizons (a control loop whose state is reset from sensors),
//! the compensated state for propagating a model for long (a simulator, a predictor without
//! measurements).
//!
//! In f64 the compensated step works the same way and is accurate to about `u²` per sub-step;
//! the plain f64 splitting is already accurate to its truncation error on every horizon tested,
//! so there the compensation buys little.
//!
//! [`State`]: crate::dynamics::State

use crate::compensated::{
    HalfTurn, add_compensated, add_compensated_vec, add_pair, renormalize_compensated,
    rotate_compensated, sixth_pair, two_product,
};
use crate::dynamics::gyrostat::Gyrostat;
use crate::dynamics::hamiltonian::{BodyHamiltonian, Quartic};
use crate::dynamics::rk4;
use crate::dynamics::state::{CompensatedState, ControlLaw};
use crate::{Axis, Error, Quat, Real, UnitQuat, Vec3};

/// The attitude and momentum of a compensated step in progress, each with its low-order part.
/// `q` is off the unit sphere by rounding until the step's renormalisation.
#[derive(Clone, Copy, Debug)]
struct Carried<T> {
    q: Quat<T>,
    q_lo: Quat<T>,
    j: Vec3<T>,
    j_lo: Vec3<T>,
}

impl<T: Real> Carried<T> {
    #[inline(always)]
    fn of<const N: usize>(x: &CompensatedState<T, N>) -> Self {
        Self {
            q: x.state.attitude.into_quat(),
            q_lo: x.attitude_lo,
            j: x.state.momentum,
            j_lo: x.momentum_lo,
        }
    }

    #[inline(always)]
    fn store<const N: usize>(self, x: &mut CompensatedState<T, N>) {
        x.state.attitude = UnitQuat::new_unchecked(self.q);
        x.attitude_lo = self.q_lo;
        x.state.momentum = self.j;
        x.momentum_lo = self.j_lo;
    }
}

/// The torque-free composition of Strang stages of lengths `stages`, the wheels coasting, with
/// the same-axis rotations at stage boundaries merged as in the plain step
/// ([`crate::dynamics::splitting`]). Not renormalised.
pub(crate) fn free<T: Real, const N: usize>(
    body: &Gyrostat<T, N>,
    state: &CompensatedState<T, N>,
    stages: &[T],
) -> CompensatedState<T, N> {
    let model = body.model();
    let s = body.rotor_momentum(&state.state.wheel_speeds);
    let mut c = Carried::of(state);
    let mut pending = T::ZERO;
    let mut total = T::ZERO;
    for &h in stages {
        let half = h * T::HALF;
        piece(model, Axis::X, &mut c, s, pending + half);
        piece(model, Axis::Y, &mut c, s, half);
        piece(model, Axis::Z, &mut c, s, h);
        piece(model, Axis::Y, &mut c, s, half);
        pending = half;
        total += h;
    }
    piece(model, Axis::X, &mut c, s, pending);
    casimir(model, &mut c, total);
    let mut next = *state;
    c.store(&mut next);
    next
}

/// The compensated kick–drift–kick composition from time `t` (the plain
/// [`crate::dynamics::splitting`]'s `kicked`, half-kicks at stage boundaries merged). Not
/// renormalised.
pub(crate) fn kicked<T: Real, const N: usize, L: ControlLaw<T, N>>(
    body: &Gyrostat<T, N>,
    state: &CompensatedState<T, N>,
    t: T,
    stages: &[T],
    input: &mut L,
) -> CompensatedState<T, N> {
    let mut x = *state;
    let mut t = t;
    let mut pending = T::ZERO;
    for &h in stages {
        kick(body, &mut x, t, (pending + h) * T::HALF, input);
        let s = body.rotor_momentum(&x.state.wheel_speeds);
        let mut c = Carried::of(&x);
        drift(body.model(), &mut c, s, h);
        c.store(&mut x);
        t += h;
        pending = h;
    }
    kick(body, &mut x, t, pending * T::HALF, input);
    x
}

/// One RK4 step with the increment `(h/6)(k₁ + 2k₂ + 2k₃ + k₄)` added to the carried pairs,
/// `h/6` taken as an exact pair. Not renormalised.
pub(crate) fn rk4_step<T: Real, const N: usize, L: ControlLaw<T, N>>(
    body: &Gyrostat<T, N>,
    state: &CompensatedState<T, N>,
    t: T,
    h: T,
    input: &mut L,
) -> CompensatedState<T, N> {
    let k = rk4::slopes(body, &state.state, t, h, input);
    let (h6, h6_lo) = sixth_pair(h);
    let mut x = *state;
    let mut q = x.state.attitude.into_quat();
    add_compensated(
        &mut q,
        &mut x.attitude_lo,
        k.attitude.scale(h6),
        k.attitude.scale(h6_lo),
    );
    x.state.attitude = UnitQuat::new_unchecked(q);
    add_compensated_vec(
        &mut x.state.momentum,
        &mut x.momentum_lo,
        k.momentum * h6,
        k.momentum * h6_lo,
    );
    let mut large = [T::ZERO; N];
    let mut small = [T::ZERO; N];
    for ((l, s), dw) in large
        .iter_mut()
        .zip(small.iter_mut())
        .zip(k.wheel_speeds.iter())
    {
        (*l, *s) = (*dw * h6, *dw * h6_lo);
    }
    add_wheels(&mut x, &large, &small);
    x
}

/// Renormalises the attitude in compensated form and rejects a non-finite result.
#[inline]
pub(crate) fn finish<T: Real, const N: usize>(
    mut x: CompensatedState<T, N>,
) -> Result<CompensatedState<T, N>, Error> {
    let mut q = x.state.attitude.into_quat();
    renormalize_compensated(&mut q, &mut x.attitude_lo);
    x.state.attitude = UnitQuat::new_unchecked(q);
    if x.is_finite() {
        Ok(x)
    } else {
        Err(Error::NonFinite)
    }
}

/// `Ωᵢ ← Ωᵢ + (largeᵢ + smallᵢ)` on the carried wheel speeds.
#[inline(always)]
fn add_wheels<T: Real, const N: usize>(
    x: &mut CompensatedState<T, N>,
    large: &[T; N],
    small: &[T; N],
) {
    for (((w, lo), l), s) in x
        .state
        .wheel_speeds
        .iter_mut()
        .zip(x.wheel_speeds_lo.iter_mut())
        .zip(large.iter())
        .zip(small.iter())
    {
        (*w, *lo) = add_pair(*w, *lo, *l, *s);
    }
}

/// The kick of length `h` on the carried pairs: `J ← J + τ h`, `Ωᵢ ← Ωᵢ + (ḣᵢ/I_wᵢ) h`, the
/// control at `(t, state)`, each product taken exactly (a constant torque's `τh` would otherwise
/// round the same way at every kick).
#[inline]
fn kick<T: Real, const N: usize, L: ControlLaw<T, N>>(
    body: &Gyrostat<T, N>,
    x: &mut CompensatedState<T, N>,
    t: T,
    h: T,
    input: &mut L,
) {
    let c = input.control(t, &x.state);
    let (jx, ex) = two_product(c.torque.x, h);
    let (jy, ey) = two_product(c.torque.y, h);
    let (jz, ez) = two_product(c.torque.z, h);
    add_compensated_vec(
        &mut x.state.momentum,
        &mut x.momentum_lo,
        Vec3::new(jx, jy, jz),
        Vec3::new(ex, ey, ez),
    );
    let mut large = [T::ZERO; N];
    let mut small = [T::ZERO; N];
    for (((l, s), u), wheel) in large
        .iter_mut()
        .zip(small.iter_mut())
        .zip(c.wheel_torques.iter())
        .zip(body.wheels().iter())
    {
        (*l, *s) = two_product(wheel.acceleration(*u), h);
    }
    add_wheels(x, &large, &small);
}

/// The Hamiltonian flow for time `h`, rotor momentum `s` held fixed:
/// `A₁(h/2) A₂(h/2) A₃(h) A₂(h/2) A₁(h/2)`, then the Casimir flow of a cubic term.
#[inline]
fn drift<T: Real>(model: &BodyHamiltonian<T>, c: &mut Carried<T>, s: Vec3<T>, h: T) {
    let half = h * T::HALF;
    piece(model, Axis::X, c, s, half);
    piece(model, Axis::Y, c, s, half);
    piece(model, Axis::Z, c, s, h);
    piece(model, Axis::Y, c, s, half);
    piece(model, Axis::X, c, s, half);
    casimir(model, c, h);
}

/// The flow of the principal piece along `axis` for time `h` (body axis for a diagonal tensor,
/// the principal axis in the body frame otherwise).
#[inline]
fn piece<T: Real>(model: &BodyHamiltonian<T>, axis: Axis, c: &mut Carried<T>, s: Vec3<T>, h: T) {
    let inertia = model.inertia();
    if inertia.is_diagonal() {
        principal_axis_flow(axis, model, c, s[axis], h);
    } else {
        let n = inertia.principal_axes().col(axis.index());
        general_axis_flow(n, model.half_inverse()[axis], c, s, h);
    }
}

/// The flow of the Casimir part `½t₂₂|J|⁴` of a cubic term, `q ← q ⊗ exp(2t₂₂|J|²J·h)`, with
/// the product `2t₂₂|J|²·h` taken exactly. The identity for the other models.
#[inline]
fn casimir<T: Real>(model: &BodyHamiltonian<T>, c: &mut Carried<T>, h: T) {
    if let Quartic::Cubic(t22) = model.quartic() {
        let rate = T::TWO * t22 * c.j.norm_squared();
        let (p, p_lo) = two_product(rate, h);
        let phi = c.j * p;
        let phi_lo = c.j * p_lo + c.j_lo * p;
        rotate_compensated(&mut c.q, &mut c.q_lo, phi, phi_lo);
    }
}

/// The two body axes after `axis` in cyclic order: the plane a rotation about `axis` turns.
#[inline(always)]
fn plane(axis: Axis) -> (Axis, Axis) {
    (axis.next(), axis.next().next())
}

/// `q ⊗ (c, s·eᵢ)` for the body axis `eᵢ = axis`.
#[inline(always)]
fn times_axis<T: Real>(q: Quat<T>, axis: Axis, c: T, s: T) -> Quat<T> {
    let Quat { w, x, y, z } = q;
    match axis {
        Axis::X => Quat::new(w * c - x * s, w * s + x * c, y * c + z * s, z * c - y * s),
        Axis::Y => Quat::new(w * c - y * s, x * c - z * s, w * s + y * c, z * c + x * s),
        Axis::Z => Quat::new(w * c - z * s, x * c + y * s, y * c - x * s, w * s + z * c),
    }
}

/// `a ⊗ (0, sa·eᵢ) + b ⊗ (0, sb·eᵢ)`: the small terms of a compensated co-rotation.
#[inline(always)]
fn times_axis_vector<T: Real>(a: Quat<T>, sa: T, b: Quat<T>, sb: T, axis: Axis) -> Quat<T> {
    match axis {
        Axis::X => Quat::new(
            -(a.x * sa + b.x * sb),
            a.w * sa + b.w * sb,
            a.z * sa + b.z * sb,
            -(a.y * sa + b.y * sb),
        ),
        Axis::Y => Quat::new(
            -(a.y * sa + b.y * sb),
            -(a.z * sa + b.z * sb),
            a.w * sa + b.w * sb,
            a.x * sa + b.x * sb,
        ),
        Axis::Z => Quat::new(
            -(a.z * sa + b.z * sb),
            a.y * sa + b.y * sb,
            -(a.x * sa + b.x * sb),
            a.w * sa + b.w * sb,
        ),
    }
}

/// The compensated flow of the one-axis piece `Hᵢ(Jᵢ)` about the body axis `axis`: the rate as
/// in the plain flow, the half angle `ψ = rate·h/2` exact ([`HalfTurn::of_product`]), then
/// `J ← J + (R_i(−θ) − 1)(J + J_lo)` and `q ← q + (q + q_lo) ⊗ (cos ψ − 1, sin ψ·eᵢ)`, each
/// increment added through Fast2Sum.
#[inline(always)]
fn principal_axis_flow<T: Real>(
    axis: Axis,
    model: &BodyHamiltonian<T>,
    c: &mut Carried<T>,
    si: T,
    h: T,
) {
    let (ai, ji) = (model.half_inverse()[axis], c.j[axis]);
    let k = match model.quartic() {
        Quartic::None => T::ZERO,
        Quartic::Octahedral(t4) => T::from_f64(4.0) * t4,
        Quartic::Cubic(t22) => -T::TWO * t22,
    };
    let rate = T::TWO * ai * (ji - si) + k * ji * ji * ji;
    let turn = HalfTurn::of_product(rate, h * T::HALF);
    // J in the plane (a, b) turned by −θ: Jₐ += sin θ·J_b − v·Jₐ, J_b −= sin θ·Jₐ + v·J_b, with
    // sin θ = sn + sn_lo and v = 1 − cos θ.
    let (sn_lo, v) = turn.full_angle_terms();
    let sn = T::TWO * turn.sin;
    let (a, b) = plane(axis);
    let (ja, jb, ea, eb) = (c.j[a], c.j[b], c.j_lo[a], c.j_lo[b]);
    // Each increment as a large part and a small one (the low parts' share), added as a pair.
    let (la, sa) = (sn * jb - v * ja, (sn_lo * jb + sn * eb) - v * ea);
    let (lb, sb) = (-(sn * ja + v * jb), -((sn_lo * ja + sn * ea) + v * eb));
    (c.j[a], c.j_lo[a]) = add_pair(ja, ea, la, sa);
    (c.j[b], c.j_lo[b]) = add_pair(jb, eb, lb, sb);
    // q: the increment (q + q_lo) ⊗ (m, sin ψ eᵢ): large q ⊗ (m, sin ψ eᵢ), small
    // q ⊗ (0, sin_lo eᵢ) + q_lo ⊗ (0, sin ψ eᵢ) (q_lo·m is below u²).
    let large = times_axis(c.q, axis, turn.cos_m1, turn.sin);
    let small = times_axis_vector(c.q, turn.sin_lo, c.q_lo, turn.sin, axis);
    add_compensated(&mut c.q, &mut c.q_lo, large, small);
}

/// The compensated flow of `Aᵢ (n·(J − s))²` about a unit body-frame axis `n` (the plain
/// `general_axis_flow` of [`crate::dynamics::splitting`] in the form of
/// [`principal_axis_flow`]).
#[inline]
fn general_axis_flow<T: Real>(n: Vec3<T>, ai: T, c: &mut Carried<T>, s: Vec3<T>, h: T) {
    let rate = T::TWO * ai * n.dot(c.j - s);
    let turn = HalfTurn::of_product(rate, h * T::HALF);
    let (sn_lo, v) = turn.full_angle_terms();
    let sn = T::TWO * turn.sin;
    // J ← J − sin θ (n × J) + (1 − cos θ) n × (n × J), on J + J_lo.
    let nj = n.cross(c.j);
    let nj_lo = n.cross(c.j_lo);
    let large = n.cross(nj) * v - nj * sn;
    let small = -(nj * sn_lo + nj_lo * sn);
    add_compensated_vec(&mut c.j, &mut c.j_lo, large, small);
    let large = c.q * Quat::from_parts(turn.cos_m1, n * turn.sin);
    let small = c.q * Quat::from_parts(T::ZERO, n * turn.sin_lo)
        + c.q_lo * Quat::from_parts(T::ZERO, n * turn.sin);
    add_compensated(&mut c.q, &mut c.q_lo, large, small);
}
