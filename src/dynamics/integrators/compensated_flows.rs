//! The compensated flows of a [`CompensatedState`] (see the [module docs](super), "In f32: the
//! compensated step"): every rotation, kick and renormalisation adds its increment to the
//! carried pairs; and the compensated RK4 step.

use crate::dynamics::gyrostat::Gyrostat;
use crate::dynamics::integrators::rk4;
use crate::dynamics::integrators::splitting::{Flows, plane, times_axis};
use crate::dynamics::state::{CompensatedState, ControlLaw};
use crate::error_free::{
    HalfTurn, add_compensated, add_compensated_vec, add_pair, renormalize_compensated,
    rotate_compensated, sixth_pair, two_product,
};
use crate::{Axis, Error, Quat, Real, UnitQuat, Vec3};

/// The attitude and momentum of a compensated step in progress, each with its low-order part.
/// `q` is off the unit sphere by rounding until the step's renormalisation.
#[derive(Clone, Copy, Debug)]
pub struct Carried<T> {
    q: Quat<T>,
    q_lo: Quat<T>,
    j: Vec3<T>,
    j_lo: Vec3<T>,
}

/// The compensated flows: each rotation's and kick's increment added to the carried pairs.
impl<T: Real, const N: usize> Flows<T, N> for CompensatedState<T, N> {
    type Turned = Carried<T>;

    #[inline(always)]
    fn turned(&self) -> Carried<T> {
        Carried {
            q: self.state.attitude.into_quat(),
            q_lo: self.attitude_lo,
            j: self.state.momentum,
            j_lo: self.momentum_lo,
        }
    }

    #[inline(always)]
    fn set_turned(&mut self, turned: Carried<T>) {
        self.state.attitude = UnitQuat::new_unchecked(turned.q);
        self.attitude_lo = turned.q_lo;
        self.state.momentum = turned.j;
        self.momentum_lo = turned.j_lo;
    }

    #[inline(always)]
    fn momentum(turned: &Carried<T>) -> Vec3<T> {
        turned.j
    }

    #[inline(always)]
    fn wheel_speeds(&self) -> &[T; N] {
        &self.state.wheel_speeds
    }

    /// The compensated flow about the body axis `axis`: the half angle `ψ = rate·h/2` exact ([`HalfTurn::of_product`]), then
    /// `J ← J + (R_i(−θ) − 1)(J + J_lo)` and `q ← q + (q + q_lo) ⊗ (cos ψ − 1, sin ψ·eᵢ)`, each
    /// increment added through Fast2Sum.
    #[inline(always)]
    fn principal_axis_flow(x: &mut Carried<T>, axis: Axis, rate: T, h: T) {
        let turn = HalfTurn::of_product(rate, h * T::HALF);
        // J in the plane (a, b) turned by −θ: Jₐ += sin θ·J_b − v·Jₐ, J_b −= sin θ·Jₐ + v·J_b, with
        // sin θ = sn + sn_lo and v = 1 − cos θ.
        let (sn_lo, v) = turn.full_angle_terms();
        let sn = T::TWO * turn.sin;
        let (a, b) = plane(axis);
        let (ja, jb, ea, eb) = (x.j[a], x.j[b], x.j_lo[a], x.j_lo[b]);
        // Each increment as a large part and a small one (the low parts' share), added as a pair.
        let (la, sa) = (sn * jb - v * ja, (sn_lo * jb + sn * eb) - v * ea);
        let (lb, sb) = (-(sn * ja + v * jb), -((sn_lo * ja + sn * ea) + v * eb));
        (x.j[a], x.j_lo[a]) = add_pair(ja, ea, la, sa);
        (x.j[b], x.j_lo[b]) = add_pair(jb, eb, lb, sb);
        // q: the increment (q + q_lo) ⊗ (m, sin ψ eᵢ): large q ⊗ (m, sin ψ eᵢ), small
        // q ⊗ (0, sin_lo eᵢ) + q_lo ⊗ (0, sin ψ eᵢ) (q_lo·m is below u²).
        let large = times_axis(x.q, axis, turn.cos_m1, turn.sin);
        let small = times_axis_vector(x.q, turn.sin_lo, x.q_lo, turn.sin, axis);
        add_compensated(&mut x.q, &mut x.q_lo, large, small);
    }

    /// The compensated flow about a unit body-frame axis `n`: the plain general-axis flow in the
    /// form of the principal-axis flow.
    #[inline]
    fn general_axis_flow(x: &mut Carried<T>, n: Vec3<T>, rate: T, h: T) {
        let turn = HalfTurn::of_product(rate, h * T::HALF);
        let (sn_lo, v) = turn.full_angle_terms();
        let sn = T::TWO * turn.sin;
        // J ← J − sin θ (n × J) + (1 − cos θ) n × (n × J), on J + J_lo.
        let nj = n.cross(x.j);
        let nj_lo = n.cross(x.j_lo);
        let large = n.cross(nj) * v - nj * sn;
        let small = -(nj * sn_lo + nj_lo * sn);
        add_compensated_vec(&mut x.j, &mut x.j_lo, large, small);
        let large = x.q * Quat::from_parts(turn.cos_m1, n * turn.sin);
        let small = x.q * Quat::from_parts(T::ZERO, n * turn.sin_lo)
            + x.q_lo * Quat::from_parts(T::ZERO, n * turn.sin);
        add_compensated(&mut x.q, &mut x.q_lo, large, small);
    }

    /// `q ← q ⊗ exp(rate·h·J)` with the product `rate·h` taken exactly.
    #[inline]
    fn casimir_flow(x: &mut Carried<T>, rate: T, h: T) {
        let (p, p_lo) = two_product(rate, h);
        let phi = x.j * p;
        let phi_lo = x.j * p_lo + x.j_lo * p;
        rotate_compensated(&mut x.q, &mut x.q_lo, phi, phi_lo);
    }

    /// The kick of length `h` on the carried pairs: `J ← J + τ h`, `Ωᵢ ← Ωᵢ + (ḣᵢ/I_wᵢ) h`, the
    /// control at `(t, state)`, each product taken exactly (a constant torque's `τh` would otherwise
    /// round the same way at every kick).
    #[inline]
    fn kick<L: ControlLaw<T, N>>(&mut self, body: &Gyrostat<T, N>, t: T, h: T, input: &mut L) {
        let c = input.control(t, &self.state);
        let (jx, ex) = two_product(c.torque.x, h);
        let (jy, ey) = two_product(c.torque.y, h);
        let (jz, ez) = two_product(c.torque.z, h);
        add_compensated_vec(
            &mut self.state.momentum,
            &mut self.momentum_lo,
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
        add_wheels(self, &large, &small);
    }
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
