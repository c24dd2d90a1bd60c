//! The classical Runge–Kutta step ([`crate::dynamics::Integrator::Rk4`]) on the whole state
//! `(q, J, wheel speeds)`: `q̇ = ½ q ⊗ (0, ω)`, `J̇ = J × ω + τ`, `Ω̇ᵢ = ḣᵢ / I_wᵢ`, with
//! `ω = ∇H(J)` (6.8.5). The intermediate quaternions leave the unit sphere by the truncation
//! error; the step's caller renormalises the result.

use crate::dynamics::gyrostat::Gyrostat;
use crate::dynamics::state::{ControlLaw, State};
use crate::{Quat, Real, UnitQuat, Vec3};

/// The time derivative of a state, or (from [`slopes`]) a weighted sum of such derivatives.
pub(crate) struct Rate<T, const N: usize> {
    pub(crate) attitude: Quat<T>,
    pub(crate) momentum: Vec3<T>,
    pub(crate) wheel_speeds: [T; N],
}

/// One RK4 step of length `h` from time `t`. Not renormalised.
pub(crate) fn step<T: Real, const N: usize, L: ControlLaw<T, N>>(
    body: &Gyrostat<T, N>,
    x: &State<T, N>,
    t: T,
    h: T,
    input: &mut L,
) -> State<T, N> {
    let k = slopes(body, x, t, h, input);
    let sixth = h / T::from_f64(6.0);
    let mut wheel_speeds = x.wheel_speeds;
    for (w, dw) in wheel_speeds.iter_mut().zip(k.wheel_speeds.iter()) {
        *w += sixth * *dw;
    }
    State {
        attitude: UnitQuat::new_unchecked(x.attitude.into_quat() + k.attitude.scale(sixth)),
        momentum: x.momentum + k.momentum * sixth,
        wheel_speeds,
    }
}

/// The weighted slopes of one RK4 step, `k₁ + 2k₂ + 2k₃ + k₄`: the step adds `h/6` times
/// them ([`step`]; the compensated step with `h/6` as an exact pair).
pub(crate) fn slopes<T: Real, const N: usize, L: ControlLaw<T, N>>(
    body: &Gyrostat<T, N>,
    x: &State<T, N>,
    t: T,
    h: T,
    input: &mut L,
) -> Rate<T, N> {
    let half = h * T::HALF;
    let k1 = rate(body, t, x, input);
    let k2 = rate(body, t + half, &advance(x, &k1, half), input);
    let k3 = rate(body, t + half, &advance(x, &k2, half), input);
    let k4 = rate(body, t + h, &advance(x, &k3, h), input);
    let mut wheel_speeds = [T::ZERO; N];
    for ((((w, d1), d2), d3), d4) in wheel_speeds
        .iter_mut()
        .zip(k1.wheel_speeds.iter())
        .zip(k2.wheel_speeds.iter())
        .zip(k3.wheel_speeds.iter())
        .zip(k4.wheel_speeds.iter())
    {
        *w = *d1 + T::TWO * (*d2 + *d3) + *d4;
    }
    Rate {
        attitude: k1.attitude + (k2.attitude + k3.attitude).scale(T::TWO) + k4.attitude,
        momentum: k1.momentum + (k2.momentum + k3.momentum) * T::TWO + k4.momentum,
        wheel_speeds,
    }
}

/// The stage state `x + d·s` (the quaternion off the unit sphere by `O(s)`).
#[inline]
fn advance<T: Real, const N: usize>(x: &State<T, N>, d: &Rate<T, N>, s: T) -> State<T, N> {
    let mut wheel_speeds = x.wheel_speeds;
    for (w, dw) in wheel_speeds.iter_mut().zip(d.wheel_speeds.iter()) {
        *w += *dw * s;
    }
    State {
        attitude: UnitQuat::new_unchecked(x.attitude.into_quat() + d.attitude.scale(s)),
        momentum: x.momentum + d.momentum * s,
        wheel_speeds,
    }
}

/// `(q̇, J̇, Ω̇)` at time `t` in state `x`.
#[inline]
fn rate<T: Real, const N: usize, L: ControlLaw<T, N>>(
    body: &Gyrostat<T, N>,
    t: T,
    x: &State<T, N>,
    input: &mut L,
) -> Rate<T, N> {
    let c = input.control(t, x);
    let omega = body.omega(x);
    let mut wheel_speeds = [T::ZERO; N];
    for ((d, u), wheel) in wheel_speeds
        .iter_mut()
        .zip(c.wheel_torques.iter())
        .zip(body.wheels().iter())
    {
        *d = wheel.acceleration(*u);
    }
    Rate {
        attitude: (x.attitude.into_quat() * Quat::from_parts(T::ZERO, omega)).scale(T::HALF),
        momentum: x.momentum.cross(omega) + c.torque,
        wheel_speeds,
    }
}
