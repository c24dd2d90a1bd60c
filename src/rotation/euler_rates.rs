//! Euler-angle rate kinematics for all 24 conventions.
//!
//! For a convention whose matrices multiply as `R = R_i(θ₁)·R_j(θ₂)·R_k(θ₃)` (intrinsic letters in
//! order; extrinsic letters reversed, angles likewise), the angular velocity is the sum of each
//! angle's rate times its axis, expressed in the wanted frame:
//!
//! ```text
//! ω_lab  = θ̇₁·e_i + θ̇₂·R_i(θ₁)·e_j + θ̇₃·R_i(θ₁)R_j(θ₂)·e_k
//! ω_body = θ̇₁·R_k(θ₃)ᵀR_j(θ₂)ᵀ·e_i + θ̇₂·R_k(θ₃)ᵀ·e_j + θ̇₃·e_k
//! ```
//!
//! For the seed's intrinsic `ZYZ` `(α, β, γ)` these are (6.7.5c) (lab) and (6.7.5d) (body); the
//! inverses are (6.7.5e–f). The matrices' determinant is `±sin θ₂` (proper sequences) or
//! `±cos θ₂` (Tait–Bryan): the inverses are singular at gimbal lock and return
//! [`Error::Singular`] within [`euler_rate_min_det`] of it.

use crate::{Axis, Error, Mat3, Real, Vec3};

use super::euler::{Euler, Frame};

/// `|det|` (= `|sin|` or `|cos|` of the middle angle) below which the inverse rate maps return
/// [`Error::Singular`]: `√ε` (3.5e-4 for f32, 1.5e-8 for f64).
///
/// Why: the rates are `ω/det`, and their sensitivity to the middle angle is `ω/det²`. The middle
/// angle itself carries a rounding error of about `ε`, so below `det = √ε` that error alone
/// changes the rates by more than their own size: they have no correct digit.
pub fn euler_rate_min_det<T: Real>() -> T {
    T::EPSILON.sqrt()
}

/// `R_axis(angle)ᵀ·v` when `transpose`, else `R_axis(angle)·v`.
fn rot_axis<T: Real>(axis: Axis, angle: T, v: Vec3<T>, transpose: bool) -> Vec3<T> {
    let (s, c) = angle.sin_cos();
    let s = if transpose { -s } else { s };
    match axis {
        Axis::X => Vec3::new(v.x, c * v.y - s * v.z, s * v.y + c * v.z),
        Axis::Y => Vec3::new(c * v.x + s * v.z, v.y, -s * v.x + c * v.z),
        Axis::Z => Vec3::new(c * v.x - s * v.y, s * v.x + c * v.y, v.z),
    }
}

impl<T: Real> Euler<T> {
    /// Product-order axes and angles `(i, j, k)`, `(θ₁, θ₂, θ₃)`.
    fn product(&self) -> ([Axis; 3], [T; 3]) {
        let (axes, _) = self.sequence.product_order();
        let [a, b, c] = self.angles;
        match self.sequence.frame() {
            Frame::Intrinsic => (axes, [a, b, c]),
            Frame::Extrinsic => (axes, [c, b, a]),
        }
    }

    /// Reorders product-order columns back to the caller's angle order.
    fn columns(&self, c1: Vec3<T>, c2: Vec3<T>, c3: Vec3<T>) -> Mat3<T> {
        match self.sequence.frame() {
            Frame::Intrinsic => Mat3::from_cols(c1, c2, c3),
            Frame::Extrinsic => Mat3::from_cols(c3, c2, c1),
        }
    }

    /// The matrix `E_body` with `ω_body = E_body·[ȧ, ḃ, ċ]` (rates in the order of the
    /// sequence's letters). Seed (6.7.5d) for intrinsic `ZYZ`.
    pub fn rates_to_body_matrix(&self) -> Mat3<T> {
        let ([i, j, k], [_, t2, t3]) = self.product();
        let c1 = rot_axis(k, t3, rot_axis(j, t2, Vec3::unit(i), true), true);
        let c2 = rot_axis(k, t3, Vec3::unit(j), true);
        let c3 = Vec3::unit(k);
        self.columns(c1, c2, c3)
    }

    /// The matrix `E_lab` with `ω_lab = E_lab·[ȧ, ḃ, ċ]`. Seed (6.7.5c) for intrinsic `ZYZ`.
    pub fn rates_to_lab_matrix(&self) -> Mat3<T> {
        let ([i, j, k], [t1, t2, _]) = self.product();
        let c1 = Vec3::unit(i);
        let c2 = rot_axis(i, t1, Vec3::unit(j), false);
        let c3 = rot_axis(i, t1, rot_axis(j, t2, Vec3::unit(k), false), false);
        self.columns(c1, c2, c3)
    }

    /// `E_body⁻¹`: Euler rates from the body angular velocity, `[ȧ, ḃ, ċ] = E_body⁻¹·ω_body`.
    /// Seed (6.7.5f) for intrinsic `ZYZ`.
    ///
    /// # Errors
    /// [`Error::Singular`] within [`euler_rate_min_det`] of gimbal lock; [`Error::NonFinite`] for
    /// a non-finite angle.
    pub fn try_body_to_rates_matrix(&self) -> Result<Mat3<T>, Error> {
        invert_rate_matrix(self, self.rates_to_body_matrix())
    }

    /// `E_lab⁻¹`: Euler rates from the lab angular velocity. Seed (6.7.5e) for intrinsic `ZYZ`.
    ///
    /// # Errors
    /// As [`Euler::try_body_to_rates_matrix`].
    pub fn try_lab_to_rates_matrix(&self) -> Result<Mat3<T>, Error> {
        invert_rate_matrix(self, self.rates_to_lab_matrix())
    }

    /// Euler-angle rates from the body angular velocity: `E_body⁻¹·ω_body`.
    ///
    /// Domain: finite `ω` whose rates are representable (the entries of `E_body⁻¹` are at most
    /// `2/|det|`, so `|ω|` up to about `MAX·|det|/4`).
    ///
    /// # Errors
    /// As [`Euler::try_body_to_rates_matrix`], [`Error::NonFinite`] for a non-finite `ω`, and
    /// [`Error::InvalidArgument`] when a rate overflows the type.
    pub fn try_rates_from_body(&self, omega_body: Vec3<T>) -> Result<[T; 3], Error> {
        let m = self.try_body_to_rates_matrix()?;
        representable(m * omega_body.try_finite()?).map(Vec3::to_array)
    }

    /// Euler-angle rates from the lab angular velocity: `E_lab⁻¹·ω_lab`.
    ///
    /// # Errors
    /// As [`Euler::try_rates_from_body`].
    pub fn try_rates_from_lab(&self, omega_lab: Vec3<T>) -> Result<[T; 3], Error> {
        let m = self.try_lab_to_rates_matrix()?;
        representable(m * omega_lab.try_finite()?).map(Vec3::to_array)
    }
}

/// A result computed from finite input: [`Error::InvalidArgument`] if it overflowed (the input
/// was outside the documented domain of magnitudes).
#[inline]
pub(crate) fn representable<T: Real>(v: Vec3<T>) -> Result<Vec3<T>, Error> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Error::InvalidArgument)
    }
}

fn invert_rate_matrix<T: Real>(e: &Euler<T>, m: Mat3<T>) -> Result<Mat3<T>, Error> {
    if !e.angles.iter().all(|a| a.is_finite()) {
        return Err(Error::NonFinite);
    }
    // Columns are unit vectors, so det is sin or cos of the middle angle, O(1) scaled.
    let (r0, r1, r2) = (m.row(0), m.row(1), m.row(2));
    let (c0, c1, c2) = (r1.cross(r2), r2.cross(r0), r0.cross(r1));
    let det = r0.dot(c0);
    if det.abs() <= euler_rate_min_det::<T>() {
        return Err(Error::Singular);
    }
    Ok(Mat3::from_cols(c0, c1, c2).scale(T::ONE / det))
}
