//! Euler momenta: the momenta `(p₁, p₂, p₃) = ∂L/∂(ȧ, ḃ, ċ)` conjugate to Euler angles, and
//! their maps to and from the Cartesian angular momentum, for all 24 conventions.
//!
//! With `ω = E·θ̇` (the rate matrices of [`Euler::rates_to_body_matrix`] and
//! [`Euler::rates_to_lab_matrix`]) and `J = ∂L/∂ω`, the chain rule (6.7.9) gives
//! `p = ∂L/∂θ̇ = Eᵀ·J`: momenta go through the *transposed* velocity matrices, the other way
//! (6.7.10). For the seed's intrinsic `ZYZ` `(α, β, γ)`:
//!
//! | map | matrix | seed |
//! |-----|--------|------|
//! | lab `J` → `(J_α, J_β, J_γ)` | `E_labᵀ` | (6.7.10c) |
//! | body `J` → `(J_α, J_β, J_γ)` | `E_bodyᵀ` | (6.7.10d) |
//! | `(J_α, J_β, J_γ)` → lab `J` | `(E_lab⁻¹)ᵀ` | (6.7.10a) |
//! | `(J_α, J_β, J_γ)` → body `J` | `(E_body⁻¹)ᵀ` | (6.7.10b) |
//!
//! The products `(E_lab⁻¹)ᵀ·E_bodyᵀ` and `E_lab·E_body⁻¹` are both the attitude matrix `R`
//! (6.7.15b), (6.6.15a): lab and body momenta (and rates) differ by the rotation, whichever way
//! round one goes through the Euler coordinates. Because the maps are inverse-transposes of the
//! rate maps, the pairing is invariant: `p·θ̇ = J·ω` in every frame (6.7.16).
//!
//! The maps into the Euler momenta are defined everywhere; the maps out of them are singular at
//! gimbal lock (`β = 0, π` for `ZYZ`, where `J_α` and `J_γ` are the same component) and return
//! [`Error::Singular`] within [`super::euler_rate_min_det`] of it, exactly like the inverse rate
//! maps.

use crate::{Error, Mat3, Real, Vec3};

use super::euler::Euler;
use super::euler_rates::representable;

impl<T: Real> Euler<T> {
    /// `E_bodyᵀ`: the Euler momenta from the body-frame angular momentum,
    /// `[p₁, p₂, p₃] = E_bodyᵀ·J_body` (momenta in the order of the sequence's letters).
    /// Seed (6.7.10d) for intrinsic `ZYZ`.
    #[inline]
    pub fn body_to_euler_momenta_matrix(&self) -> Mat3<T> {
        self.rates_to_body_matrix().transpose()
    }

    /// `E_labᵀ`: the Euler momenta from the lab-frame angular momentum. Seed (6.7.10c) for
    /// intrinsic `ZYZ`.
    #[inline]
    pub fn lab_to_euler_momenta_matrix(&self) -> Mat3<T> {
        self.rates_to_lab_matrix().transpose()
    }

    /// `(E_body⁻¹)ᵀ`: the body-frame angular momentum from the Euler momenta,
    /// `J_body = (E_body⁻¹)ᵀ·p`. Seed (6.7.10b) for intrinsic `ZYZ`.
    ///
    /// # Errors
    /// [`Error::Singular`] within [`super::euler_rate_min_det`] of gimbal lock;
    /// [`Error::NonFinite`] for a non-finite angle.
    #[inline]
    pub fn try_euler_momenta_to_body_matrix(&self) -> Result<Mat3<T>, Error> {
        self.try_body_to_rates_matrix().map(|m| m.transpose())
    }

    /// `(E_lab⁻¹)ᵀ`: the lab-frame angular momentum from the Euler momenta. Seed (6.7.10a) for
    /// intrinsic `ZYZ`.
    ///
    /// # Errors
    /// As [`Euler::try_euler_momenta_to_body_matrix`].
    #[inline]
    pub fn try_euler_momenta_to_lab_matrix(&self) -> Result<Mat3<T>, Error> {
        self.try_lab_to_rates_matrix().map(|m| m.transpose())
    }

    /// The Euler momenta `E_bodyᵀ·J_body` (6.7.10d).
    ///
    /// Domain: finite angles and a finite momentum whose Euler momenta are representable (the
    /// entries of `E_bodyᵀ` are at most 1 in magnitude, so `|J|` up to about `MAX/2`).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite angle or momentum; [`Error::InvalidArgument`] when a
    /// momentum overflows the type.
    pub fn try_euler_momenta_from_body(&self, momentum_body: Vec3<T>) -> Result<[T; 3], Error> {
        let m = finite_matrix(self, self.body_to_euler_momenta_matrix())?;
        representable(m * momentum_body.try_finite()?).map(Vec3::to_array)
    }

    /// The Euler momenta `E_labᵀ·J_lab` (6.7.10c).
    ///
    /// # Errors
    /// As [`Euler::try_euler_momenta_from_body`].
    pub fn try_euler_momenta_from_lab(&self, momentum_lab: Vec3<T>) -> Result<[T; 3], Error> {
        let m = finite_matrix(self, self.lab_to_euler_momenta_matrix())?;
        representable(m * momentum_lab.try_finite()?).map(Vec3::to_array)
    }

    /// The body-frame angular momentum `(E_body⁻¹)ᵀ·p` from Euler momenta `p` (6.7.10b).
    ///
    /// Domain: as [`Euler::try_rates_from_body`] (the entries of `(E_body⁻¹)ᵀ` are at most
    /// `2/|det|`).
    ///
    /// # Errors
    /// As [`Euler::try_euler_momenta_to_body_matrix`], [`Error::NonFinite`] for a non-finite
    /// momentum, and [`Error::InvalidArgument`] when a component overflows the type.
    pub fn try_body_momentum_from_euler_momenta(&self, momenta: [T; 3]) -> Result<Vec3<T>, Error> {
        let m = self.try_euler_momenta_to_body_matrix()?;
        representable(m * Vec3::from_array(momenta).try_finite()?)
    }

    /// The lab-frame angular momentum `(E_lab⁻¹)ᵀ·p` from Euler momenta `p` (6.7.10a).
    ///
    /// # Errors
    /// As [`Euler::try_body_momentum_from_euler_momenta`].
    pub fn try_lab_momentum_from_euler_momenta(&self, momenta: [T; 3]) -> Result<Vec3<T>, Error> {
        let m = self.try_euler_momenta_to_lab_matrix()?;
        representable(m * Vec3::from_array(momenta).try_finite()?)
    }
}

fn finite_matrix<T: Real>(e: &Euler<T>, m: Mat3<T>) -> Result<Mat3<T>, Error> {
    if e.angles.iter().all(|a| a.is_finite()) {
        Ok(m)
    } else {
        Err(Error::NonFinite)
    }
}
