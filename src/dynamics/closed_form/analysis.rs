//! The seed's closed-form analysis of free rotors (Harter, Unit 6, §6.7–6.9): rotational energy
//! surfaces, the momentum and velocity ellipsoids, the separatrix, small-oscillation and
//! divergence rates, symmetric-top rates, and the multipole coefficients of a gyro-rotor
//! Hamiltonian.
//!
//! # Conventions
//! Every function takes the body's validated [`Inertia`] and works with its principal moments
//! `(I₁, I₂, I₃)` ([`Inertia::principal_moments`], in the body-axis order for a diagonal tensor)
//! in the principal frame. The seed's BOD-frame direction of `J` at polar angle `β` and azimuth
//! `γ` is `Ĵ = (−cos γ sin β, sin γ sin β, cos β)` (the `⟨z|` row of `R(αβγ)`, (6.7.40)).
//! Rigid-rotor constants are `A = 1/(2I₁)`, `B = 1/(2I₂)`, `C = 1/(2I₃)` (6.9.2). Angles are in
//! radians.
//!
//! # Domain
//! Every function takes finite arguments whose results are representable: a momentum,
//! energy or spin whose energies, radii and rates overflow the type (for example
//! `rotational_energy` of `|J| = 1e200` in f64) gives [`Error::InvalidArgument`], never an
//! infinite `Ok`. Ratios of moments are formed before products, so bodies anywhere in the
//! type's range are handled.

use super::elliptic::pow2_scale;
use super::free_rigid_body::EQUAL_MOMENTS_TOLERANCE;
use crate::dynamics::inertia::Inertia;
use crate::{Axis, Error, Real, Vec3};

fn check_finite<T: Real>(xs: &[T]) -> Result<(), Error> {
    if xs.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(Error::NonFinite)
    }
}

/// Results computed from finite input: [`Error::InvalidArgument`] if one overflowed (an input
/// outside the documented domain of magnitudes, see the module docs).
fn representable<T: Real>(xs: &[T]) -> Result<(), Error> {
    if xs.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(Error::InvalidArgument)
    }
}

/// The seed's BOD-frame unit direction `Ĵ(β, γ) = (−cos γ sin β, sin γ sin β, cos β)` (6.7.40).
pub fn direction<T: Real>(beta: T, gamma: T) -> Vec3<T> {
    let (sb, cb) = beta.sin_cos();
    let (sg, cg) = gamma.sin_cos();
    Vec3::new(-cg * sb, sg * sb, cb)
}

/// `Σ Ĵᵢ²/(2Iᵢ)` for the direction `(β, γ)`.
fn energy_per_j2<T: Real>(i: Vec3<T>, beta: T, gamma: T) -> T {
    let d = direction(beta, gamma);
    T::HALF * (d.x * d.x / i.x + d.y * d.y / i.y + d.z * d.z / i.z)
}

/// The rotational energy surface (RES) radius
/// `E(J, β, γ) = J² cos²γ sin²β/(2I₁) + J² sin²γ sin²β/(2I₂) + J² cos²β/(2I₃)` (6.8.7): the
/// energy of momentum magnitude `j` pointing along `Ĵ(β, γ)` in the body frame.
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite argument; [`Error::InvalidArgument`] when the energy
/// overflows the type.
pub fn rotational_energy<T: Real>(
    inertia: &Inertia<T>,
    j: T,
    beta: T,
    gamma: T,
) -> Result<T, Error> {
    check_finite(&[j, beta, gamma])?;
    let e = j * j * energy_per_j2(inertia.principal_moments(), beta, gamma);
    representable(&[e])?;
    Ok(e)
}

/// The constant-energy surface (CES) radius
/// `J(E, β, γ) = √(E / (cos²γ sin²β/(2I₁) + sin²γ sin²β/(2I₂) + cos²β/(2I₃)))` (6.8.8): the
/// momentum magnitude that has energy `energy` along `Ĵ(β, γ)`.
///
/// # Errors
/// As [`rotational_energy`], plus [`Error::InvalidArgument`] for `energy < 0` or a radius that
/// overflows the type.
pub fn constant_energy_radius<T: Real>(
    inertia: &Inertia<T>,
    energy: T,
    beta: T,
    gamma: T,
) -> Result<T, Error> {
    check_finite(&[energy, beta, gamma])?;
    if energy < T::ZERO {
        return Err(Error::InvalidArgument);
    }
    // The denominator is ≥ 1/(2 I_max) > 0.
    let r = (energy / energy_per_j2(inertia.principal_moments(), beta, gamma)).sqrt();
    representable(&[r])?;
    Ok(r)
}

/// The separatrix azimuth `γ_B` (6.8.10): the separatrix of the rigid rotor (the constant-`J`
/// contour `E = J²/(2I₂)` through the saddle points on the intermediate `±J₂` axes) is a pair of
/// great circles through the `I₂` axis, in the planes at azimuth `±γ_B` about that axis measured
/// from the `I₃` axis towards the `I₁` axis:
///
/// `tan γ_B = √((I₁/I₃)(I₂ − I₃)/(I₁ − I₂))`, evaluated as
/// `γ_B = atan2(√(I₁|I₂ − I₃|), √(I₃|I₁ − I₂|)) ∈ (0, π/2)`.
///
/// The seed's example `(I₁, I₂, I₃) = (6, 4, 3)` gives `γ_B = 45°` (Fig. 6.8.1); Fig. 6.8.2 gives
/// `I₂ = 5.0 → 63.4°` and `3.2 → 20.7°`, which this formula reproduces; its caption's
/// `I₂ = 5.6 → 75.5°` is not: (6.8.10) gives `tan²γ_B = 13`, `γ_B = 74.50°` (75.5° would need
/// `I₂ ≈ 5.646`). The test `analysis_seed` records this.
///
/// # Errors
/// [`Error::InvalidArgument`] unless `I₂` lies strictly between `I₁` and `I₃` (no separatrix for
/// a symmetric top, and `I₂` must be the intermediate moment).
pub fn separatrix_angle<T: Real>(inertia: &Inertia<T>) -> Result<T, Error> {
    let moments = inertia.principal_moments();
    let (i1, i2, i3) = (moments.x, moments.y, moments.z);
    let between = (i1 > i2 && i2 > i3) || (i1 < i2 && i2 < i3);
    if !between {
        return Err(Error::InvalidArgument);
    }
    // On the moments scaled by an exact power of two to order one (no overflow or underflow
    // of the products; the angle is scale-free).
    let s = pow2_scale(i1.max(i2).max(i3));
    let (i1, i2, i3) = (i1 / s, i2 / s, i3 / s);
    let num = (i1 * (i2 - i3).abs()).sqrt();
    let den = (i3 * (i1 - i2).abs()).sqrt();
    Ok(num.atan2(den))
}

/// The kind of small motion of `J` near a principal axis, (6.8.6a–c).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SmallMotionKind {
    /// Stable axis (major or minor): `J` circles it harmonically, `e^{±iΩt}` (6.8.6a, b).
    Oscillation,
    /// Unstable intermediate axis: `J` leaves and approaches it exponentially, `e^{±Ξt}` (6.8.6c).
    Divergence,
    /// The axis belongs to a degenerate pair (symmetric top): neutral, rate 0.
    Neutral,
}

/// The rate of small motion of `J` about one principal axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SmallMotion<T> {
    /// `Ω` (rad/s) for [`SmallMotionKind::Oscillation`], `Ξ` (1/s) for
    /// [`SmallMotionKind::Divergence`], 0 for [`SmallMotionKind::Neutral`].
    pub rate: T,
    /// Stable, unstable or neutral.
    pub kind: SmallMotionKind,
}

/// Small-oscillation and divergence rates of `J` (magnitude `j`) near the principal axis
/// `axis`, (6.8.6a–c): with `a` that axis and `b, c` the others,
///
/// `rate = (J/I_a) √(|(I_b − I_a)(I_c − I_a)| / (I_b I_c))`,
///
/// an oscillation frequency `Ω` when `I_a` is the largest or smallest moment (6.8.6a: about the
/// minimum-inertia axis, `Ω^z = (J/I₃)√((I₁−I₃)(I₂−I₃)/(I₁I₂))`; 6.8.6b: about the maximum),
/// the divergence rate `Ξ` when it is the intermediate one (6.8.6c:
/// `Ξ^y = (J/I₂)√((I₁−I₂)(I₂−I₃)/(I₁I₃))`). The oscillation frequency is the `m → 0` limit of
/// the exact `|λ|` of [`super::free_rigid_body`].
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite `j`; [`Error::InvalidArgument`] when the rate
/// overflows the type.
pub fn small_motion<T: Real>(
    inertia: &Inertia<T>,
    j: T,
    axis: Axis,
) -> Result<SmallMotion<T>, Error> {
    check_finite(&[j])?;
    let moments = inertia.principal_moments();
    let (ia, ib, ic) = (
        moments[axis],
        moments[axis.next()],
        moments[axis.next().next()],
    );
    // The ratios (I_b − I_a)/I_b and (I_c − I_a)/I_c first: scale-free, no overflow.
    let prod = ((ib - ia) / ib) * ((ic - ia) / ic);
    let rate = j.abs() / ia * prod.abs().sqrt();
    representable(&[rate])?;
    let kind = if prod > T::ZERO {
        SmallMotionKind::Oscillation
    } else if prod < T::ZERO {
        SmallMotionKind::Divergence
    } else {
        SmallMotionKind::Neutral
    };
    Ok(SmallMotion { rate, kind })
}

/// Rates of the free symmetric top (seed §6.7.d, (6.7.39)–(6.7.43)), for lab momentum `J` on
/// the lab `z` axis and the body symmetry axis tilted by `β` from it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SymmetricTopRates<T> {
    /// LAB precession ("wobble") rate `α̇ = J/I_II` (6.7.43a).
    pub lab_precession: T,
    /// BOD precession rate `γ̇ = (1/I₃ − 1/I_II) J cos β = ((I_II − I₃)/I_II) ω₃` (6.7.39),
    /// (6.7.43d): the rate at which the body sees `J` (and the lab `z` axis) turn about its
    /// symmetry axis — clockwise, i.e. `J_body` turns by `−γ̇ t`.
    pub body_precession: T,
    /// Axial body rate `ω₃ = J cos β / I₃` (6.7.43c).
    pub axial_rate: T,
    /// Body-frame angular velocity at `γ = 0`: `(−α̇ sin β, 0, α̇ cos β + γ̇)` (6.7.42b).
    pub omega_body: Vec3<T>,
    /// Lab-frame angular velocity at `α = 0`: `(γ̇ sin β, 0, α̇ + γ̇ cos β)` (6.7.42a).
    pub omega_lab: Vec3<T>,
}

/// Symmetric-top rates (6.7.39)–(6.7.43) for a body whose first two principal moments are the
/// transverse moment `I_II = I₁ = I₂` and whose third is the axial moment `I₃`, momentum
/// magnitude `j` and tilt `β` of the symmetry axis from `J`.
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite argument; [`Error::InvalidArgument`] unless `I₁ = I₂`
/// (within [`EQUAL_MOMENTS_TOLERANCE`] ulp, relative), or when a rate overflows the type.
pub fn symmetric_top_rates<T: Real>(
    inertia: &Inertia<T>,
    j: T,
    beta: T,
) -> Result<SymmetricTopRates<T>, Error> {
    check_finite(&[j, beta])?;
    let m = inertia.principal_moments();
    let tol = T::from_f64(EQUAL_MOMENTS_TOLERANCE) * T::EPSILON * m.x.max(m.y);
    if (m.x - m.y).abs() > tol {
        return Err(Error::InvalidArgument);
    }
    let (i_transverse, i_axial) = ((m.x + m.y) * T::HALF, m.z);
    let (sb, cb) = beta.sin_cos();
    let alpha_dot = j / i_transverse;
    let gamma_dot = (T::ONE / i_axial - T::ONE / i_transverse) * j * cb;
    let omega3 = j * cb / i_axial;
    let r = SymmetricTopRates {
        lab_precession: alpha_dot,
        body_precession: gamma_dot,
        axial_rate: omega3,
        omega_body: Vec3::new(-alpha_dot * sb, T::ZERO, alpha_dot * cb + gamma_dot),
        omega_lab: Vec3::new(gamma_dot * sb, T::ZERO, alpha_dot + gamma_dot * cb),
    };
    representable(&[r.lab_precession, r.body_precession, r.axial_rate])?;
    representable(&r.omega_body.to_array())?;
    representable(&r.omega_lab.to_array())?;
    Ok(r)
}

/// Multipole coefficients of the body-fixed gyro-rotor Hamiltonian
/// `H = A(J_x − S_x)² + B(J_y − S_y)² + C(J_z − S_z)²` (6.9.2b), expanded as
/// `H = constant + M₀ T₀ + Σ D_d T_d + Q_zz T_zz + Q_{x²−y²} T_{x²−y²}` (6.9.2c), (6.9.4).
///
/// Tensor normalisation (see [`GyroMultipoles::evaluate`]): `T₀ = J²/3` (6.9.3a),
/// `T_d = J_d` (6.9.3b), `T_{x²−y²} = J_x² − J_y²` (6.9.3c), and `T_zz = 2J_z² − J_x² − J_y²`.
/// The seed prints `T_zz` with an extra factor ½ in (6.9.3c) while giving
/// `Q_zz = (2C − A − B)/6` in (6.9.4c); with the ½ the expansion would not reproduce `H`, so this
/// module keeps the seed's coefficient and drops the ½ (the test checks the expansion against
/// `H` directly).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GyroMultipoles<T> {
    /// `A S_x² + B S_y² + C S_z²`: the `J`-independent part (the seed's "const.1").
    pub constant: T,
    /// Monopole `M₀ = A + B + C` (6.9.4a; the seed adds `3H'_S`, a constant rotor energy, which
    /// is kept out of this coefficient).
    pub monopole: T,
    /// Dipoles `D = (−2A S_x, −2B S_y, −2C S_z)` (6.9.4b).
    pub dipole: Vec3<T>,
    /// Quadrupole `Q_zz = (2C − A − B)/6` (6.9.4c).
    pub q_zz: T,
    /// Quadrupole `Q_{x²−y²} = (A − B)/2` (6.9.4c).
    pub q_x2_y2: T,
}

impl<T: Real> GyroMultipoles<T> {
    /// The Hamiltonian rebuilt from the multipoles at body momentum `j`:
    /// `constant + M₀ J²/3 + D·J + Q_zz (2J_z² − J_x² − J_y²) + Q_{x²−y²}(J_x² − J_y²)`.
    pub fn evaluate(&self, j: Vec3<T>) -> T {
        let (x2, y2, z2) = (j.x * j.x, j.y * j.y, j.z * j.z);
        let three = T::from_f64(3.0);
        self.constant
            + self.monopole * (x2 + y2 + z2) / three
            + self.dipole.dot(j)
            + self.q_zz * (T::TWO * z2 - x2 - y2)
            + self.q_x2_y2 * (x2 - y2)
    }
}

/// The gyro-rotor multipole coefficients (6.9.4) for principal moments `(I₁, I₂, I₃)` and
/// rotor spin `S` (`A = 1/(2I₁)`, … (6.9.2)). `spin` is given in the body frame; the multipoles
/// are those of the principal frame, so a non-diagonal tensor's spin is rotated into it
/// (`P* ⊗ S ⊗ P`) first.
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite spin; [`Error::InvalidArgument`] when a coefficient
/// overflows the type (a spin far beyond the body's momenta, or moments near the range's
/// lower end).
pub fn gyro_multipoles<T: Real>(
    inertia: &Inertia<T>,
    spin: Vec3<T>,
) -> Result<GyroMultipoles<T>, Error> {
    if !spin.is_finite() {
        return Err(Error::NonFinite);
    }
    let moments = inertia.principal_moments();
    let spin = if inertia.is_diagonal() {
        spin
    } else {
        inertia.principal_rotation().inverse_rotate(spin)
    };
    let a = T::HALF / moments.x;
    let b = T::HALF / moments.y;
    let c = T::HALF / moments.z;
    let six = T::from_f64(6.0);
    let m = GyroMultipoles {
        constant: a * spin.x * spin.x + b * spin.y * spin.y + c * spin.z * spin.z,
        monopole: a + b + c,
        dipole: Vec3::new(
            -T::TWO * a * spin.x,
            -T::TWO * b * spin.y,
            -T::TWO * c * spin.z,
        ),
        q_zz: (T::TWO * c - a - b) / six,
        q_x2_y2: (a - b) * T::HALF,
    };
    representable(&[m.constant, m.monopole, m.q_zz, m.q_x2_y2])?;
    representable(&m.dipole.to_array())?;
    Ok(m)
}

/// The semi-axes `aᵢ = √(2E·Iᵢ)` of the momentum ellipsoid `H(J) = J₁²/(2I₁) + J₂²/(2I₂) +
/// J₃²/(2I₃) = E` (6.7.27a–b), on the principal axes in the order of
/// [`Inertia::principal_moments`]: proportional to `√Iᵢ`, largest along the axis of largest
/// inertia.
///
/// The seed prints `a = √I₁/√(2E)` in (6.7.27b) (and `I₁ = 2a²E` in (6.8.8b)); that has the
/// dimension of a time, not of a momentum, and does not satisfy `H/E = J₁²/a² + …`: the
/// semi-axis is `√(2EI₁)`, as its own sentence "proportional to √I" requires. The test
/// `seed_relations::ellipsoid_radii_6_7_27` checks the formula against `H` directly.
///
/// # Errors
/// [`Error::NonFinite`]; [`Error::InvalidArgument`] for `energy < 0` or a radius that
/// overflows the type.
pub fn momentum_ellipsoid_radii<T: Real>(
    inertia: &Inertia<T>,
    energy: T,
) -> Result<Vec3<T>, Error> {
    ellipsoid_radii(inertia, energy, |two_e, moment| (two_e * moment).sqrt())
}

/// The semi-axes `Aᵢ = √(2E/Iᵢ)` of the angular-velocity ellipsoid
/// `L(ω) = ½(I₁ω₁² + I₂ω₂² + I₃ω₃²) = E` (6.7.27c), on the principal axes: inversely
/// proportional to `√Iᵢ`, shaped like the body. (The seed prints `A = 1/√(2EI₁)`, which has the
/// dimension of an inverse momentum; see [`momentum_ellipsoid_radii`].)
///
/// # Errors
/// As [`momentum_ellipsoid_radii`].
pub fn velocity_ellipsoid_radii<T: Real>(
    inertia: &Inertia<T>,
    energy: T,
) -> Result<Vec3<T>, Error> {
    ellipsoid_radii(inertia, energy, |two_e, moment| (two_e / moment).sqrt())
}

/// `radius(2E, Iᵢ)` on each principal axis, for a checked energy `E ≥ 0`.
fn ellipsoid_radii<T: Real>(
    inertia: &Inertia<T>,
    energy: T,
    radius: impl Fn(T, T) -> T,
) -> Result<Vec3<T>, Error> {
    check_finite(&[energy])?;
    if energy < T::ZERO {
        return Err(Error::InvalidArgument);
    }
    let m = inertia.principal_moments();
    let two_e = T::TWO * energy;
    let r = Vec3::new(radius(two_e, m.x), radius(two_e, m.y), radius(two_e, m.z));
    representable(&r.to_array())?;
    Ok(r)
}
