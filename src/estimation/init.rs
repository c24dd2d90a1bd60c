//! The initial attitude from one accelerometer (and magnetometer) sample: gravity and north.
//!
//! At rest an accelerometer measures the specific force `f = −g`, which points *up* in the earth
//! frame; a magnetometer measures the local field, whose horizontal part points to magnetic
//! north. In the sensor frame, with `u = f/|f|` (up), the east axis is `e = (m × u)/|m × u|`
//! and north `n = u × e`; the attitude `R` (sensor → earth, ENU: x east, y north, z up) is the
//! matrix whose rows are `e`, `n`, `u` (the TRIAD construction with gravity as the exact
//! direction and the magnetometer only fixing the heading). Without a magnetometer the heading
//! is free: the shortest rotation taking `u` to the earth's `z` axis is taken (zero yaw).

use crate::rotation::Dcm;
use crate::{Error, Mat3, Quat, Real, UnitQuat, Vec3};

/// The attitude (sensor → earth, ENU) whose earth `z` axis is the measured specific force `acc`
/// and whose heading is the shortest rotation from the sensor frame (no yaw about the vertical).
///
/// `q = (1 + u_z, u_y, −u_x, 0)/|…|` with `u = acc/|acc|`: the rotation about the horizontal
/// axis `u × ẑ` by the angle between `u` and `ẑ`. Below the horizon (`u_z < 0`) `1 + u_z`
/// cancels; it is formed there as `h²/(1 − u_z)`, `h² = u_x² + u_y²` (equal for a unit `u`), so
/// the tilt stays exact to a few ε up to the sensor upside down. At `u = −ẑ` exactly the axis
/// is undefined; the half turn about the sensor's `x` axis is taken there.
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite component, [`Error::ZeroNorm`] for a zero vector.
pub fn attitude_from_gravity<T: Real>(acc: Vec3<T>) -> Result<UnitQuat<T>, Error> {
    let u = acc.try_finite()?.try_normalize()?;
    let h2 = u.x * u.x + u.y * u.y;
    let w = if u.z >= T::ZERO {
        T::ONE + u.z
    } else {
        h2 / (T::ONE - u.z)
    };
    if w <= T::ZERO || h2 <= T::ZERO && u.z < T::ZERO {
        return Ok(UnitQuat::new_unchecked(Quat::new(
            T::ZERO,
            T::ONE,
            T::ZERO,
            T::ZERO,
        )));
    }
    // Scaled to a largest component of 1 first: near upside down all three are tiny.
    let s = w.max(u.x.abs()).max(u.y.abs());
    Quat::new(w / s, u.y / s, -u.x / s, T::ZERO).try_normalize()
}

/// The attitude (sensor → earth, ENU) from gravity and the magnetic field (TRIAD, see the module
/// docs): the earth `z` axis along `acc`, the earth `y` axis along the part of `mag`
/// perpendicular to it.
///
/// # Errors
/// [`Error::NonFinite`] for a non-finite component; [`Error::ZeroNorm`] for a zero vector or a
/// magnetic field parallel to gravity (no horizontal part: the heading is undefined).
pub fn attitude_from_gravity_and_field<T: Real>(
    acc: Vec3<T>,
    mag: Vec3<T>,
) -> Result<UnitQuat<T>, Error> {
    let u = acc.try_finite()?.try_normalize()?;
    let m = mag.try_finite()?.try_normalize()?;
    let east = m.cross(u);
    // The horizontal part is |m × u| = sin(angle between field and vertical) of a unit field:
    // below 1e-6 (a field within 0.06 mdeg of the vertical, only at a magnetic pole) there is
    // no usable heading.
    if east.norm_squared() <= T::from_f64(1e-12) {
        return Err(Error::ZeroNorm);
    }
    // `m × u` is perpendicular to `u` only up to its rounding, which is relative to `|m||u|`
    // while `|m × u|` is the sine of the angle: near the vertical the normalised east axis
    // leans towards `u` by about ε/sin. One Gram–Schmidt step against `u` removes that lean
    // (to ε), so the rows stay orthonormal and gravity the exact third row.
    let e = east.try_normalize()?;
    let e = (e - u.scale(e.dot(u))).try_normalize()?;
    let n = u.cross(e);
    let r = Mat3::from_rows(e.to_array(), n.to_array(), u.to_array());
    Ok(Dcm::from_matrix_unchecked(r).to_unit_quat())
}
