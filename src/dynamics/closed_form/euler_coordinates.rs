//! The rigid rotor in Euler coordinates (seed §6.7.b–f): the metric of the Euler-angle
//! Lagrangian, the Euler momenta, the kinetic energy, the Hamiltonian in Euler momenta and
//! Hamilton's velocity equations; and the seed's closed forms for the symmetric top.
//!
//! # Conventions
//! Euler angles `θ = (θ₁, θ₂, θ₃)` are in any of the 24 conventions ([`Euler`]); rates `θ̇` and
//! momenta `p = ∂L/∂θ̇` are in the order of the sequence's letters. The body rate is
//! `ω = E_body·θ̇` ([`Euler::rates_to_body_matrix`], (6.7.5d) for `ZYZ`), the inertia tensor `I`
//! is body-frame (constant for a rigid body). Then
//!
//! - `L = T = ½ ω·I·ω = ½ θ̇·g·θ̇` with the metric `g = E_bodyᵀ·I·E_body` ((6.7.31)–(6.7.33));
//! - `p = g·θ̇ = E_bodyᵀ·J`, `J = I·ω` ((6.7.6), (6.7.9), (6.7.34));
//! - `T = ½ p·θ̇ = ½ J·ω` in every frame (6.7.16);
//! - `H = ½ p·g⁻¹·p = ½ J·I⁻¹·J` and `θ̇ = ∂H/∂p = g⁻¹·p` ((6.7.17c), (6.7.35a–b)).
//!
//! `g⁻¹` is applied as `E_body⁻¹·I⁻¹·(E_body⁻¹)ᵀ` (never by inverting `g`), so the only singular
//! factor is the rate matrix: the functions that need it return [`Error::Singular`] within
//! [`crate::rotation::euler_rate_min_det`] of gimbal lock, like [`Euler::try_rates_from_body`].
//!
//! Domain: finite angles, rates and momenta whose results are representable; a result that
//! overflows the type (rates or momenta near its largest values, moments near its range's
//! ends) gives [`Error::InvalidArgument`], never an infinite `Ok`.
//!
//! [`SymmetricTop`] evaluates the seed's closed forms for `ZYZ` `(α, β, γ)` and
//! `I₁ = I₂ = I_II`: (6.7.32a–b), (6.7.33)–(6.7.37), (6.7.44).

use crate::dynamics::inertia::Inertia;
use crate::rotation::{Euler, euler_rate_min_det};
use crate::{Error, Mat3, Real, Vec3};

fn finite3<T: Real>(x: [T; 3]) -> Result<Vec3<T>, Error> {
    Vec3::from_array(x).try_finite()
}

/// A result computed from finite input: [`Error::InvalidArgument`] if it overflowed (an input
/// outside the documented domain of magnitudes, see the module docs).
fn representable<T: Real>(xs: &[T]) -> Result<(), Error> {
    if xs.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(Error::InvalidArgument)
    }
}

fn representable3<T: Real>(x: [T; 3]) -> Result<[T; 3], Error> {
    representable(&x).map(|()| x)
}

fn representable1<T: Real>(x: T) -> Result<T, Error> {
    representable(&[x]).map(|()| x)
}

fn finite_angles<T: Real>(e: &Euler<T>) -> Result<(), Error> {
    if e.angles.iter().all(|a| a.is_finite()) {
        Ok(())
    } else {
        Err(Error::NonFinite)
    }
}

/// The metric `g = E_bodyᵀ·I·E_body` of the rigid-rotor Lagrangian in Euler rates,
/// `L = ½ θ̇·g·θ̇` (the general form of (6.7.33); its entries are the squares (6.7.31) summed
/// with the moments). Symmetric; singular (rank 2) at gimbal lock, where two angles turn the
/// body about the same axis.
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite angle; [`Error::InvalidArgument`] when the metric
/// overflows the type (module docs).
pub fn euler_metric<T: Real>(inertia: &Inertia<T>, angles: &Euler<T>) -> Result<Mat3<T>, Error> {
    finite_angles(angles)?;
    let e = angles.rates_to_body_matrix();
    let g = e.transpose() * inertia.tensor() * e;
    if g.is_finite() {
        Ok(g)
    } else {
        Err(Error::InvalidArgument)
    }
}

/// The Euler momenta `p = ∂L/∂θ̇ = g·θ̇ = E_bodyᵀ·I·ω` of a rigid rotor turning at Euler rates
/// `rates` (6.7.6), (6.7.9); for the symmetric top in `ZYZ` this is (6.7.34).
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite angle or rate; [`Error::InvalidArgument`] when a
/// momentum overflows the type (module docs).
pub fn try_euler_momenta<T: Real>(
    inertia: &Inertia<T>,
    angles: &Euler<T>,
    rates: [T; 3],
) -> Result<[T; 3], Error> {
    finite_angles(angles)?;
    let omega = angles.rates_to_body_matrix() * finite3(rates)?;
    representable3((angles.body_to_euler_momenta_matrix() * inertia.mul_vec(omega)).to_array())
}

/// The kinetic energy from Euler rates, `T = ½ (p₁θ̇₁ + p₂θ̇₂ + p₃θ̇₃) = ½ J·ω` (6.7.16), with
/// `p` from [`try_euler_momenta`]; equal to `½ ω·I·ω` (6.7.18a) in any frame.
///
/// # Errors
/// As [`try_euler_momenta`].
pub fn kinetic_energy<T: Real>(
    inertia: &Inertia<T>,
    angles: &Euler<T>,
    rates: [T; 3],
) -> Result<T, Error> {
    let p = try_euler_momenta(inertia, angles, rates)?;
    representable1(T::HALF * (p[0] * rates[0] + p[1] * rates[1] + p[2] * rates[2]))
}

/// Hamilton's velocity equations in Euler coordinates, `θ̇ = ∂H/∂p = g⁻¹·p` ((6.7.17c), the
/// general form of (6.7.35a)), evaluated as `θ̇ = E_body⁻¹·I⁻¹·(E_body⁻¹)ᵀ·p`.
///
/// # Errors
/// [`Error::Singular`] within [`euler_rate_min_det`] of gimbal lock; [`Error::NonFinite`] for a
/// non-finite angle or momentum; [`Error::InvalidArgument`] when a result overflows the type
/// (module docs).
pub fn try_euler_rates_from_momenta<T: Real>(
    inertia: &Inertia<T>,
    angles: &Euler<T>,
    momenta: [T; 3],
) -> Result<[T; 3], Error> {
    let j = angles.try_body_momentum_from_euler_momenta(momenta)?;
    let w = inertia.solve(j);
    representable(&w.to_array())?;
    angles.try_rates_from_body(w)
}

/// The rigid-rotor Hamiltonian in Euler momenta, `H = ½ p·g⁻¹·p = ½ J·I⁻¹·J` with
/// `J = (E_body⁻¹)ᵀ·p` ((6.7.18b); for the symmetric top in `ZYZ` this is (6.7.35b)).
///
/// # Errors
/// As [`try_euler_rates_from_momenta`].
pub fn euler_hamiltonian<T: Real>(
    inertia: &Inertia<T>,
    angles: &Euler<T>,
    momenta: [T; 3],
) -> Result<T, Error> {
    let j = angles.try_body_momentum_from_euler_momenta(momenta)?;
    representable1(inertia.energy_from_momentum(j))
}

/// A free symmetric top, `I₁ = I₂ = I_II` (transverse) and `I₃` (axial), in the seed's `ZYZ`
/// Euler angles `(α, β, γ)` (§6.7.f). Only `β` enters: the top's Lagrangian and Hamiltonian do not
/// depend on `α` (lab isotropy) or `γ` (body symmetry), so `J_α` and `J_γ` are conserved (6.7.36).
///
/// A spherical top is the case `I_II = I₃` ((6.7.32b)). Rates and momenta are `[α̇, β̇, γ̇]` and
/// `[J_α, J_β, J_γ]`.
///
/// # Invariant
/// `I_II, I₃` finite, positive, `I₃ ≤ 2 I_II` (triangle inequality); built by
/// [`SymmetricTop::try_new`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SymmetricTop<T> {
    transverse: T,
    axial: T,
}

impl<T: Real> SymmetricTop<T> {
    /// A symmetric top with transverse moment `I_II` and axial moment `I₃`.
    ///
    /// # Errors
    /// [`Error::NonFinite`]; [`Error::NonPhysicalInertia`] unless both are positive and
    /// `I₃ ≤ 2 I_II`.
    pub fn try_new(transverse: T, axial: T) -> Result<Self, Error> {
        if !(transverse.is_finite() && axial.is_finite()) {
            return Err(Error::NonFinite);
        }
        if transverse <= T::ZERO || axial <= T::ZERO || axial > T::TWO * transverse {
            return Err(Error::NonPhysicalInertia);
        }
        Ok(Self { transverse, axial })
    }

    /// The transverse moment `I_II = I₁ = I₂`.
    #[inline]
    pub fn transverse(&self) -> T {
        self.transverse
    }

    /// The axial moment `I₃`.
    #[inline]
    pub fn axial(&self) -> T {
        self.axial
    }

    /// `L = ½ I_II (α̇² sin²β + β̇²) + ½ I₃ (α̇ cos β + γ̇)²` (6.7.32a); with `I_II = I₃` it is
    /// the spherical top's `½ I (α̇² + β̇² + 2α̇γ̇ cos β + γ̇²)` (6.7.32b).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite `β` or rate; [`Error::InvalidArgument`] when the
    /// result overflows the type (module docs; likewise for the other methods).
    pub fn lagrangian(&self, beta: T, rates: [T; 3]) -> Result<T, Error> {
        let [ad, bd, gd] = finite3(rates)?.to_array();
        let (sb, cb) = finite_sin_cos(beta)?;
        let axial_rate = ad * cb + gd;
        representable1(
            T::HALF * self.transverse * (ad * ad * sb * sb + bd * bd)
                + T::HALF * self.axial * axial_rate * axial_rate,
        )
    }

    /// The metric `g_μν` of (6.7.33):
    /// `[[I_II sin²β + I₃ cos²β, 0, I₃ cos β], [0, I_II, 0], [I₃ cos β, 0, I₃]]`.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite `β`.
    pub fn metric(&self, beta: T) -> Result<Mat3<T>, Error> {
        let (sb, cb) = finite_sin_cos(beta)?;
        let (it, i3) = (self.transverse, self.axial);
        let z = T::ZERO;
        // Finite moments and |sin|, |cos| ≤ 1: every entry is at most 2·max(I_II, I₃), and
        // I₃ ≤ 2 I_II keeps that finite unless I_II is within a factor 4 of the maximum.
        let g = Mat3::from_rows(
            [it * sb * sb + i3 * cb * cb, z, i3 * cb],
            [z, it, z],
            [i3 * cb, z, i3],
        );
        if g.is_finite() {
            Ok(g)
        } else {
            Err(Error::InvalidArgument)
        }
    }

    /// The Euler momenta `J_μ = g_μν ν̇` (6.7.34), (6.7.44):
    /// `J_α = I_II α̇ sin²β + I₃ (α̇ cos²β + γ̇ cos β)`, `J_β = I_II β̇`,
    /// `J_γ = I₃ (α̇ cos β + γ̇)`.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite `β` or rate.
    pub fn try_momenta(&self, beta: T, rates: [T; 3]) -> Result<[T; 3], Error> {
        let [ad, bd, gd] = finite3(rates)?.to_array();
        let (sb, cb) = finite_sin_cos(beta)?;
        let j_gamma = self.axial * (ad * cb + gd);
        representable3([
            self.transverse * ad * sb * sb + j_gamma * cb,
            self.transverse * bd,
            j_gamma,
        ])
    }

    /// Hamilton's velocity equations `ν̇ = g^νμ J_μ = ∂H/∂J_ν` (6.7.35a):
    /// `α̇ = (J_α − J_γ cos β)/(I_II sin²β)`, `β̇ = J_β/I_II`,
    /// `γ̇ = J_γ/I₃ − cos β (J_α − J_γ cos β)/(I_II sin²β)`.
    ///
    /// # Errors
    /// [`Error::Singular`] when `|sin β| ≤` [`euler_rate_min_det`] (gimbal lock: `J_α` and
    /// `J_γ` are then the same component and `α̇`, `γ̇` are not separately defined);
    /// [`Error::NonFinite`] for a non-finite input.
    pub fn try_rates(&self, beta: T, momenta: [T; 3]) -> Result<[T; 3], Error> {
        let [ja, jb, jg] = finite3(momenta)?.to_array();
        let (sb, cb) = self.off_pole(beta)?;
        let alpha_dot = (ja - jg * cb) / (self.transverse * sb * sb);
        representable3([
            alpha_dot,
            jb / self.transverse,
            jg / self.axial - cb * alpha_dot,
        ])
    }

    /// The symmetric-top Hamiltonian in Euler momenta (6.7.35b):
    /// `H = (J_α − J_γ cos β)²/(2 I_II sin²β) + J_β²/(2 I_II) + J_γ²/(2 I₃)`.
    ///
    /// # Errors
    /// As [`SymmetricTop::try_rates`].
    pub fn hamiltonian(&self, beta: T, momenta: [T; 3]) -> Result<T, Error> {
        let [ja, jb, jg] = finite3(momenta)?.to_array();
        let (sb, cb) = self.off_pole(beta)?;
        let a = ja - jg * cb;
        let two = T::TWO;
        representable1(
            a * a / (two * self.transverse * sb * sb)
                + jb * jb / (two * self.transverse)
                + jg * jg / (two * self.axial),
        )
    }

    /// The torque on the `β` coordinate in Hamiltonian form (6.7.36):
    /// `J̇_β = −∂H/∂β = (J_α − J_γ cos β)(J_α cos β − J_γ)/(I_II sin³β)`. (`J̇_α = J̇_γ = 0`.)
    ///
    /// # Errors
    /// As [`SymmetricTop::try_rates`].
    pub fn beta_torque(&self, beta: T, momenta: [T; 3]) -> Result<T, Error> {
        let [ja, _, jg] = finite3(momenta)?.to_array();
        let (sb, cb) = self.off_pole(beta)?;
        representable1((ja - jg * cb) * (ja * cb - jg) / (self.transverse * sb * sb * sb))
    }

    /// The same torque in Lagrangian form, `J̇_β = ∂L/∂β`
    /// `= (I_II − I₃) α̇² sin β cos β − I₃ α̇ γ̇ sin β` ((6.7.36), (6.7.44)); defined at every `β`.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite input.
    pub fn beta_torque_from_rates(&self, beta: T, rates: [T; 3]) -> Result<T, Error> {
        let [ad, _, gd] = finite3(rates)?.to_array();
        let (sb, cb) = finite_sin_cos(beta)?;
        representable1(
            (self.transverse - self.axial) * ad * ad * sb * cb - self.axial * ad * gd * sb,
        )
    }

    fn off_pole(&self, beta: T) -> Result<(T, T), Error> {
        let (sb, cb) = finite_sin_cos(beta)?;
        if sb.abs() <= euler_rate_min_det::<T>() {
            return Err(Error::Singular);
        }
        Ok((sb, cb))
    }
}

fn finite_sin_cos<T: Real>(x: T) -> Result<(T, T), Error> {
    if x.is_finite() {
        Ok(x.sin_cos())
    } else {
        Err(Error::NonFinite)
    }
}
