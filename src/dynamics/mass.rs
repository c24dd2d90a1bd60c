//! Mass properties: inertia tensors of point-mass bodies (6.5.4)–(6.5.5), the parallel-axis
//! theorem (6.5.15), radius of gyration (6.4.18)–(6.4.19), and the response to an impulse
//! (6.4.11)–(6.4.15).
//!
//! Inputs are slices of `(mass, position)` pairs (no allocation). Positions and tensors are in
//! one frame, chosen by the caller (usually the body frame); SI units.

use crate::{Error, Mat3, Real, Vec3};

/// `m[(r·r)1 − r rᵀ]`, the inertia of one point mass about the origin (6.5.4).
fn point_inertia<T: Real>(m: T, r: Vec3<T>) -> Mat3<T> {
    // Off-diagonals computed once so the result is exactly symmetric.
    let (xy, xz, yz) = (-m * r.x * r.y, -m * r.x * r.z, -m * r.y * r.z);
    let (xx, yy, zz) = (r.x * r.x, r.y * r.y, r.z * r.z);
    Mat3::from_rows(
        [m * (yy + zz), xy, xz],
        [xy, m * (xx + zz), yz],
        [xz, yz, m * (xx + yy)],
    )
}

fn check_points<T: Real>(points: &[(T, Vec3<T>)]) -> Result<(), Error> {
    if points.is_empty() {
        return Err(Error::InvalidArgument);
    }
    for (m, r) in points {
        if !m.is_finite() || !r.is_finite() {
            return Err(Error::NonFinite);
        }
        if *m < T::ZERO {
            return Err(Error::InvalidArgument);
        }
    }
    Ok(())
}

/// The inertia tensor about the origin of a set of point masses,
/// `I = Σ mⱼ [(rⱼ·rⱼ)1 − rⱼ rⱼᵀ]` (6.5.4), i.e. the matrix of (6.5.5b):
/// diagonal `Σ m(y² + z²)`, …, off-diagonal `−Σ m x y`, ….
///
/// Example (the seed's bent axle, (6.5.6)): one mass at `r(1/√2, 1/√2, 0)` has
/// `I = m r² [[½, −½, 0], [−½, ½, 0], [0, 0, 1]]`.
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite mass or coordinate; [`Error::InvalidArgument`] for an
/// empty slice or a negative mass.
pub fn inertia_from_point_masses<T: Real>(points: &[(T, Vec3<T>)]) -> Result<Mat3<T>, Error> {
    check_points(points)?;
    let mut sum = Mat3::ZERO;
    for (m, r) in points {
        sum = sum + point_inertia(*m, *r);
    }
    if !sum.is_finite() {
        return Err(Error::NonFinite);
    }
    Ok(sum)
}

/// Total mass `M = Σ mⱼ` and centre of mass `r_CM = Σ mⱼ rⱼ / M` of point masses.
///
/// # Errors
/// As [`inertia_from_point_masses`], plus [`Error::InvalidArgument`] if the total mass is zero.
pub fn total_mass_and_center<T: Real>(points: &[(T, Vec3<T>)]) -> Result<(T, Vec3<T>), Error> {
    check_points(points)?;
    let mut m_sum = T::ZERO;
    let mut moment = Vec3::ZERO;
    for (m, r) in points {
        m_sum += *m;
        moment += r.scale(*m);
    }
    if m_sum <= T::ZERO {
        return Err(Error::InvalidArgument);
    }
    let c = moment.scale(T::ONE / m_sum);
    if !c.is_finite() || !m_sum.is_finite() {
        return Err(Error::NonFinite);
    }
    Ok((m_sum, c))
}

/// The parallel-axis theorem (6.5.15): the inertia about a point displaced by `-r_cm` from the
/// centre of mass, i.e. about the origin when the centre of mass sits at `r_cm`:
/// `I_origin = I_cm + M[(r_cm·r_cm)1 − r_cm r_cmᵀ]`
/// ("the inertia of `M` concentrated at `r_CM` plus the inertia about the CM").
///
/// # Errors
/// [`Error::NonFinite`]; [`Error::InvalidArgument`] for a negative mass.
pub fn parallel_axis_shift<T: Real>(
    i_cm: &Mat3<T>,
    mass: T,
    r_cm: Vec3<T>,
) -> Result<Mat3<T>, Error> {
    if !i_cm.is_finite() || !mass.is_finite() || !r_cm.is_finite() {
        return Err(Error::NonFinite);
    }
    if mass < T::ZERO {
        return Err(Error::InvalidArgument);
    }
    let out = *i_cm + point_inertia(mass, r_cm);
    if !out.is_finite() {
        return Err(Error::NonFinite);
    }
    Ok(out)
}

/// Radius of gyration `r = √(I/M)` from `I = M r²` (6.4.19); for the seed's stick of length
/// `2ℓ`, `I = Mℓ²/3` gives `r = ℓ/√3` (6.4.18).
///
/// # Errors
/// [`Error::NonFinite`]; [`Error::InvalidArgument`] unless `M > 0` and `I ≥ 0`.
pub fn radius_of_gyration<T: Real>(moment: T, mass: T) -> Result<T, Error> {
    if !moment.is_finite() || !mass.is_finite() {
        return Err(Error::NonFinite);
    }
    if mass <= T::ZERO || moment < T::ZERO {
        return Err(Error::InvalidArgument);
    }
    let r = (moment / mass).sqrt();
    if r.is_finite() {
        Ok(r)
    } else {
        Err(Error::NonFinite)
    }
}

/// Percussion radius `p = r_gyro² / h` (6.4.16)–(6.4.17) generalised with (6.4.19): the point on
/// the far side of the centre of mass that is momentarily at rest after an impulse at distance
/// `h` (for the stick, `r_gyro² = ℓ²/3` gives the seed's `p = ℓ²/(3h)`).
///
/// # Errors
/// [`Error::NonFinite`]; [`Error::InvalidArgument`] for `h = 0` (a hit through the centre of
/// mass: no rotation, `p = ∞`) or a negative radius.
pub fn percussion_radius<T: Real>(radius_of_gyration: T, h: T) -> Result<T, Error> {
    if !radius_of_gyration.is_finite() || !h.is_finite() {
        return Err(Error::NonFinite);
    }
    if h == T::ZERO || radius_of_gyration < T::ZERO {
        return Err(Error::InvalidArgument);
    }
    let p = radius_of_gyration * radius_of_gyration / h;
    if p.is_finite() {
        Ok(p)
    } else {
        Err(Error::NonFinite)
    }
}

/// The change of motion of a free rigid body hit by an impulse.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImpulseResponse<T> {
    /// Change of angular velocity `Δω = I⁻¹ (r × Π)` (6.4.13)–(6.4.15), in the frame of `I`.
    pub delta_omega: Vec3<T>,
    /// Change of the centre-of-mass velocity `ΔV = Π / M` (6.4.11)–(6.4.12), whatever `r`.
    pub delta_velocity: Vec3<T>,
    /// The angular impulse `Λ = r × Π` (6.4.13); `|Λ| = hΠ` (6.4.14).
    pub angular_impulse: Vec3<T>,
}

/// Response to a linear impulse `Π` applied at lever arm `r` from the centre of mass, for a
/// body of mass `M` and inertia tensor `I` about its centre of mass (same frame as `r`, `Π`):
/// `Δω = I⁻¹(r × Π)`, `ΔV = Π/M` (6.4.11)–(6.4.15).
///
/// # Errors
/// [`Error::NonFinite`]; [`Error::InvalidArgument`] for `M ≤ 0`; [`Error::Singular`] if `I` is
/// not invertible.
pub fn impulse_response<T: Real>(
    inertia: &Mat3<T>,
    mass: T,
    lever_arm: Vec3<T>,
    impulse: Vec3<T>,
) -> Result<ImpulseResponse<T>, Error> {
    if !inertia.is_finite() || !mass.is_finite() || !lever_arm.is_finite() || !impulse.is_finite() {
        return Err(Error::NonFinite);
    }
    if mass <= T::ZERO {
        return Err(Error::InvalidArgument);
    }
    let inv = inertia.try_inverse()?;
    let lambda = lever_arm.cross(impulse);
    let out = ImpulseResponse {
        delta_omega: inv * lambda,
        delta_velocity: impulse.scale(T::ONE / mass),
        angular_impulse: lambda,
    };
    if out.delta_omega.is_finite() && out.delta_velocity.is_finite() {
        Ok(out)
    } else {
        Err(Error::NonFinite)
    }
}
