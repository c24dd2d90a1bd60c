//! Body-frame Hamiltonians: rigid, gyro-rotor and centrifugally distorted (semi-rigid) rotors.
//!
//! Every model is a function `H(J)` of the body-frame total angular momentum `J`, whose motion
//! is the Lie–Poisson flow `J̇ = J × ∇H(J)` with body rate `ω = ∇H(J)` (6.8.5), the attitude
//! co-propagated by `q̇ = ½ q ⊗ (0, ω)`:
//!
//! - rigid: `H = ½ J·I⁻¹·J` (6.5.11), `I` any physical tensor (full, non-diagonal allowed);
//! - gyro-rotor: `H = ½ (J − S)·I⁻¹·(J − S)`, in principal axes `Σ Aᵢ (Jᵢ − Sᵢ)²` with
//!   `Aᵢ = 1/(2Iᵢ)` (6.9.2b), `S` the body-fixed rotor momentum (constant spins and, in a
//!   [`crate::dynamics::gyrostat::Gyrostat`], the reaction wheels);
//! - semi-rigid: the rigid (or gyro-rotor) part plus an octahedral `t₄(J₁⁴ + J₂⁴ + J₃⁴)`
//!   (6.8.20a) or cubic `t₂₂(J₁²J₂² + J₁²J₃² + J₂²J₃²)` (6.8.20b) centrifugal-distortion term.
//!
//! The monitors are here too: [`BodyHamiltonian::energy`], the Casimir `|J|`
//! ([`momentum_norm`]) and the lab-frame angular momentum `q ⊗ J ⊗ q*` ([`lab_momentum`]).

use crate::dynamics::inertia::Inertia;
use crate::{Error, Real, UnitQuat, Vec3};

/// A quartic centrifugal-distortion term added to the quadratic Hamiltonian (6.8.20).
///
/// The polynomials are in the body axes, which must then be the principal axes (the seed's
/// `T⁽⁴⁾` tensors are written in a molecule's symmetry axes); [`BodyHamiltonian::try_new`]
/// rejects a quartic term with a non-diagonal inertia tensor.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Quartic<T> {
    /// No quartic term: a rigid body or gyro-rotor.
    #[default]
    None,
    /// Octahedral `t₄ (J₁⁴ + J₂⁴ + J₃⁴)` (6.8.20a, 6.8.20c).
    Octahedral(T),
    /// Cubic `t₂₂ (J₁²J₂² + J₁²J₃² + J₂²J₃²)` (6.8.20b, 6.8.20d).
    Cubic(T),
}

/// A body-frame Hamiltonian `H(J) = ½ (J − S)·I⁻¹·(J − S) + quartic(J)`.
///
/// `S` is the constant body-fixed rotor momentum (zero for a rigid body). The quadratic part is
/// the gyro-rotor (6.9.2b); with `S = 0` it is the rigid rotor (6.7.27a).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyHamiltonian<T> {
    pub(crate) inertia: Inertia<T>,
    pub(crate) spin: Vec3<T>,
    pub(crate) quartic: Quartic<T>,
    /// `Aᵢ = 1/(2λᵢ)` on the principal axes (6.9.2).
    pub(crate) half_inverse: Vec3<T>,
}

impl<T: Real> BodyHamiltonian<T> {
    /// The rigid rotor `H = ½ J·I⁻¹·J` (6.5.11), infallible because `inertia` is validated.
    pub fn rigid(inertia: Inertia<T>) -> Self {
        let m = inertia.principal_moments();
        Self {
            inertia,
            spin: Vec3::ZERO,
            quartic: Quartic::None,
            half_inverse: Vec3::new(T::HALF / m.x, T::HALF / m.y, T::HALF / m.z),
        }
    }

    /// A rotor with body-fixed constant rotor momentum `spin` (`S`, body frame) and an optional
    /// quartic distortion term.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite `spin` or quartic coefficient;
    /// [`Error::InvalidArgument`] for a quartic term with a non-diagonal inertia tensor (the
    /// quartic polynomials are defined on principal axes).
    pub fn try_new(inertia: Inertia<T>, spin: Vec3<T>, quartic: Quartic<T>) -> Result<Self, Error> {
        let spin = spin.try_finite()?;
        match quartic {
            Quartic::None => {}
            Quartic::Octahedral(t) | Quartic::Cubic(t) => {
                if !t.is_finite() {
                    return Err(Error::NonFinite);
                }
                if !inertia.is_diagonal() {
                    return Err(Error::InvalidArgument);
                }
            }
        }
        let mut h = Self::rigid(inertia);
        h.spin = spin;
        h.quartic = quartic;
        Ok(h)
    }

    /// The inertia tensor.
    #[inline]
    pub fn inertia(&self) -> &Inertia<T> {
        &self.inertia
    }

    /// The constant rotor momentum `S` (body frame).
    #[inline]
    pub fn spin(&self) -> Vec3<T> {
        self.spin
    }

    /// The quartic term.
    #[inline]
    pub fn quartic(&self) -> Quartic<T> {
        self.quartic
    }

    /// `H(J)` with the model's own rotor momentum `S`.
    #[inline]
    pub fn energy(&self, j: Vec3<T>) -> T {
        self.energy_with_rotor(j, self.spin)
    }

    /// The body rate `ω = ∇H(J)` with the model's own rotor momentum.
    #[inline]
    pub fn omega(&self, j: Vec3<T>) -> Vec3<T> {
        self.omega_with_rotor(j, self.spin)
    }

    /// `H(J)` with total rotor momentum `s` (the model's spin plus any wheel momentum):
    /// `½ (J − s)·I⁻¹·(J − s) + quartic(J)`.
    pub fn energy_with_rotor(&self, j: Vec3<T>, s: Vec3<T>) -> T {
        let r = j - s;
        T::HALF * r.dot(self.inertia.solve(r)) + quartic_energy(self.quartic, j)
    }

    /// `ω = ∇H(J) = I⁻¹(J − s) + ∇quartic(J)` with total rotor momentum `s`.
    pub fn omega_with_rotor(&self, j: Vec3<T>, s: Vec3<T>) -> Vec3<T> {
        self.inertia.solve(j - s) + quartic_gradient(self.quartic, j)
    }
}

/// The quartic energy term (6.8.20).
#[inline]
pub(crate) fn quartic_energy<T: Real>(q: Quartic<T>, j: Vec3<T>) -> T {
    let (x2, y2, z2) = (j.x * j.x, j.y * j.y, j.z * j.z);
    match q {
        Quartic::None => T::ZERO,
        Quartic::Octahedral(t4) => t4 * (x2 * x2 + y2 * y2 + z2 * z2),
        Quartic::Cubic(t22) => t22 * (x2 * y2 + x2 * z2 + y2 * z2),
    }
}

/// Gradient of the quartic term: octahedral `4t₄Jᵢ³`, cubic `2t₂₂Jᵢ(|J|² − Jᵢ²)`.
#[inline]
pub(crate) fn quartic_gradient<T: Real>(q: Quartic<T>, j: Vec3<T>) -> Vec3<T> {
    let (x2, y2, z2) = (j.x * j.x, j.y * j.y, j.z * j.z);
    match q {
        Quartic::None => Vec3::ZERO,
        Quartic::Octahedral(t4) => {
            let k = T::from_f64(4.0) * t4;
            Vec3::new(k * x2 * j.x, k * y2 * j.y, k * z2 * j.z)
        }
        Quartic::Cubic(t22) => {
            let k = T::TWO * t22;
            Vec3::new(
                k * j.x * (y2 + z2),
                k * j.y * (x2 + z2),
                k * j.z * (x2 + y2),
            )
        }
    }
}

/// The Casimir `|J|`: conserved by every torque-free body-frame flow `J̇ = J × ∇H`.
#[inline]
pub fn momentum_norm<T: Real>(j: Vec3<T>) -> T {
    j.norm()
}

/// The lab-frame angular momentum `q ⊗ J ⊗ q*` (6.8.2): constant for torque-free motion.
#[inline]
pub fn lab_momentum<T: Real>(attitude: UnitQuat<T>, j_body: Vec3<T>) -> Vec3<T> {
    attitude.rotate(j_body)
}
