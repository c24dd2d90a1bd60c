//! Sensor calibration applied before the propagation core: bias, scale factor and misalignment
//! for the gyro and the accelerometer, hard- and soft-iron for the magnetometer.
//!
//! # Convention
//! Inertial sensors (gyro, accelerometer):
//!
//! `corrected = M · diag(s) · (raw − b)`
//!
//! with `b` the bias (in the raw reading's unit: rad/s for a gyro rate, m/s² or g for an
//! accelerometer), `s` the per-axis scale factors (each the true value per unit of raw reading,
//! `1` for a perfect axis) and `M` the misalignment matrix (`I` for orthogonal, aligned axes;
//! row `i` is sensor axis `i`'s sensitivity to the true body components after scaling). The
//! product `K = M · diag(s)` is formed once when the calibration is built. For gyro increments
//! over an interval `Δt` the bias is a rate: `corrected Δθ = K · (Δθ_raw − b·Δt)`
//! ([`InertialCalibration::apply_increment`]).
//!
//! Magnetometer: `corrected = S · (raw − h)`, `h` the hard-iron offset, `S` the soft-iron matrix
//! (the inverse of the ellipsoid's shape, `I` for none).
//!
//! # Validation
//! [`InertialCalibration::try_new`] and [`MagnetometerCalibration::try_new`] check every number
//! (finite), every scale factor (positive: an axis's sign belongs to the mounting,
//! [`crate::sensor::AxisRemap`]) and the matrix: invertible with a positive determinant (a
//! calibration close to the identity; a negative determinant is a reflection, a wiring or mounting
//! error, not a calibration) and a condition number `‖K‖_F·‖K⁻¹‖_F ≤` [`MAX_CONDITION`] (beyond,
//! the correction would amplify the raw noise and quantisation by that factor: the calibration is
//! almost certainly wrong). The inverse model ([`InertialCalibration::raw_from_corrected`]) is
//! kept for simulation and round trips.
//!
//! # Number formats
//! Build in f64 or f32; for fixed point convert a checked f64 calibration with
//! [`InertialCalibration::try_to_q30`]: `K` in Q1.30 (entries below 2), the bias in Q7.24
//! rad/s, applied to Q1.30 increments with a Q1.30 step ([`InertialCalibration::apply_increment`]
//! is generic over [`Ring`] through [`Bias`]).

use crate::fixed::increment_from_rate;
use crate::real::{Q24, Q30};
use crate::{Error, Mat3, Real, Ring, Vec3};

/// The largest accepted Frobenius condition number `‖K‖_F·‖K⁻¹‖_F` of a calibration matrix
/// (the identity has 3). A real misalignment matrix is within a few percent of the identity, and
/// scale factors of one sensor within a factor of a few of each other.
pub const MAX_CONDITION: f64 = 100.0;

/// How a bias is subtracted from an increment over a step: `Δθ − b·Δt`. Implemented for the
/// floats (bias and step in `T`) and for Q1.30 increments (bias in Q7.24 rad/s, step in Q1.30 s,
/// through [`increment_from_rate`]).
pub trait Bias<T>: Copy {
    /// The bias's increment over the step `dt`.
    fn over(self, dt: T) -> Vec3<T>;
}

impl<T: Real> Bias<T> for Vec3<T> {
    #[inline]
    fn over(self, dt: T) -> Vec3<T> {
        self * dt
    }
}

impl Bias<Q30> for Vec3<Q24> {
    #[inline]
    fn over(self, dt: Q30) -> Vec3<Q30> {
        increment_from_rate(self, dt)
    }
}

fn frobenius<T: Real>(m: &Mat3<T>) -> T {
    (m.row(0).norm_squared() + m.row(1).norm_squared() + m.row(2).norm_squared()).sqrt()
}

/// Checks a calibration matrix (finite, invertible, `det > 0`, conditioned) and returns its
/// inverse.
fn checked_inverse<T: Real>(k: &Mat3<T>) -> Result<Mat3<T>, Error> {
    if !k.is_finite() {
        return Err(Error::NonFinite);
    }
    let inv = k.try_inverse()?;
    if k.determinant() <= T::ZERO {
        return Err(Error::InvalidArgument);
    }
    let cond = frobenius(k) * frobenius(&inv);
    if !cond.is_finite() || cond > T::from_f64(MAX_CONDITION) {
        return Err(Error::Singular);
    }
    Ok(inv)
}

/// A gyro or accelerometer calibration `corrected = K·(raw − b)`, `K = M·diag(s)` (see the
/// [module docs](self)). `B` is the bias type: `Vec3<T>` for the floats, `Vec3<Q24>` (rad/s)
/// for Q1.30 increments.
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InertialCalibration<T, B = Vec3<T>> {
    k: Mat3<T>,
    k_inv: Mat3<T>,
    bias: B,
}

impl<T: Real> InertialCalibration<T> {
    /// The identity calibration (no bias, unit scale, no misalignment).
    pub const IDENTITY: Self = Self {
        k: Mat3::IDENTITY,
        k_inv: Mat3::IDENTITY,
        bias: Vec3::new(T::ZERO, T::ZERO, T::ZERO),
    };

    /// A calibration from its misalignment matrix `M`, scale factors `s` and bias `b`.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite number; [`Error::InvalidArgument`] for a scale
    /// factor `≤ 0` or `det K ≤ 0`; [`Error::Singular`] for a `K` that is not invertible or whose
    /// condition number exceeds [`MAX_CONDITION`].
    pub fn try_new(misalignment: Mat3<T>, scale: Vec3<T>, bias: Vec3<T>) -> Result<Self, Error> {
        if !misalignment.is_finite() || !scale.is_finite() || !bias.is_finite() {
            return Err(Error::NonFinite);
        }
        if scale.x <= T::ZERO || scale.y <= T::ZERO || scale.z <= T::ZERO {
            return Err(Error::InvalidArgument);
        }
        let k = misalignment * Mat3::from_diagonal(scale);
        let k_inv = checked_inverse(&k)?;
        Ok(Self { k, k_inv, bias })
    }

    /// The inverse model, `raw = K⁻¹·corrected + b`: what a sensor with this calibration reads
    /// for a true value (simulation, round trips). Infallible for finite input.
    #[inline]
    pub fn raw_from_corrected(&self, corrected: Vec3<T>) -> Vec3<T> {
        self.k_inv * corrected + self.bias
    }

    /// The inverse model for an increment over `dt`: `raw Δθ = K⁻¹·Δθ + b·dt`.
    #[inline]
    pub fn raw_increment_from_corrected(&self, corrected: Vec3<T>, dt: T) -> Vec3<T> {
        self.k_inv * corrected + self.bias * dt
    }

    /// `K⁻¹`.
    pub fn inverse_matrix(&self) -> Mat3<T> {
        self.k_inv
    }

    /// Converts to Q1.30 increments with a Q7.24 bias (rad/s), each number rounded to nearest.
    ///
    /// # Errors
    /// [`Error::OutOfRange`] for an entry of `K` or `K⁻¹` of magnitude 2 or more, or a bias
    /// of 128 rad/s or more.
    pub fn try_to_q30(&self) -> Result<InertialCalibration<Q30, Vec3<Q24>>, Error> {
        let m = |a: &Mat3<T>| -> Result<Mat3<Q30>, Error> {
            let r = |i: usize| {
                Vec3::<Q30>::try_from_f64(Vec3::from_array(a.row(i).to_array().map(T::to_f64)))
            };
            Ok(Mat3::from_rows(
                r(0)?.to_array(),
                r(1)?.to_array(),
                r(2)?.to_array(),
            ))
        };
        Ok(InertialCalibration {
            k: m(&self.k)?,
            k_inv: m(&self.k_inv)?,
            bias: Vec3::<Q24>::try_from_f64(Vec3::from_array(self.bias.to_array().map(T::to_f64)))?,
        })
    }
}

impl<T: Ring, B: Copy> InertialCalibration<T, B> {
    /// `K = M·diag(s)`.
    pub fn matrix(&self) -> Mat3<T> {
        self.k
    }

    /// The bias `b`.
    pub fn bias(&self) -> B {
        self.bias
    }

    /// `K·v` for a reading whose bias was already removed (or has none).
    #[inline]
    pub fn apply_unbiased(&self, v: Vec3<T>) -> Vec3<T> {
        self.k * v
    }

    /// `corrected Δθ = K·(Δθ_raw − b·dt)`: a gyro increment over `dt` (or an accelerometer's
    /// velocity increment). Infallible (a non-finite float input gives a non-finite output;
    /// Q1.30 saturates).
    #[inline]
    pub fn apply_increment(&self, raw: Vec3<T>, dt: T) -> Vec3<T>
    where
        B: Bias<T>,
    {
        self.k * (raw - self.bias.over(dt))
    }
}

impl<T: Real> InertialCalibration<T> {
    /// `corrected = K·(raw − b)`: a rate or a specific force. Infallible (a non-finite input
    /// gives a non-finite output; see [`InertialCalibration::try_apply`]).
    #[inline]
    pub fn apply(&self, raw: Vec3<T>) -> Vec3<T> {
        self.k * (raw - self.bias)
    }

    /// [`InertialCalibration::apply`] with the input and the result checked.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite input or a result that overflows.
    pub fn try_apply(&self, raw: Vec3<T>) -> Result<Vec3<T>, Error> {
        raw.try_finite()?;
        self.apply(raw).try_finite()
    }
}

/// A magnetometer calibration `corrected = S·(raw − h)`: hard-iron offset `h`, soft-iron matrix
/// `S` (see the [module docs](self)).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MagnetometerCalibration<T> {
    soft_iron: Mat3<T>,
    soft_iron_inv: Mat3<T>,
    hard_iron: Vec3<T>,
}

impl<T: Real> MagnetometerCalibration<T> {
    /// The identity calibration.
    pub const IDENTITY: Self = Self {
        soft_iron: Mat3::IDENTITY,
        soft_iron_inv: Mat3::IDENTITY,
        hard_iron: Vec3::new(T::ZERO, T::ZERO, T::ZERO),
    };

    /// A calibration from the soft-iron matrix `S` and the hard-iron offset `h` (in the raw
    /// reading's unit).
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite number; [`Error::InvalidArgument`] for
    /// `det S ≤ 0`; [`Error::Singular`] for an `S` that is not invertible or whose condition
    /// number exceeds [`MAX_CONDITION`].
    pub fn try_new(soft_iron: Mat3<T>, hard_iron: Vec3<T>) -> Result<Self, Error> {
        if !soft_iron.is_finite() || !hard_iron.is_finite() {
            return Err(Error::NonFinite);
        }
        let soft_iron_inv = checked_inverse(&soft_iron)?;
        Ok(Self {
            soft_iron,
            soft_iron_inv,
            hard_iron,
        })
    }

    /// `S·(raw − h)`. Infallible (a non-finite input gives a non-finite output).
    #[inline]
    pub fn apply(&self, raw: Vec3<T>) -> Vec3<T> {
        self.soft_iron * (raw - self.hard_iron)
    }

    /// [`MagnetometerCalibration::apply`] with the input and the result checked.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a non-finite input or a result that overflows.
    pub fn try_apply(&self, raw: Vec3<T>) -> Result<Vec3<T>, Error> {
        raw.try_finite()?;
        self.apply(raw).try_finite()
    }

    /// The inverse model `raw = S⁻¹·corrected + h`.
    #[inline]
    pub fn raw_from_corrected(&self, corrected: Vec3<T>) -> Vec3<T> {
        self.soft_iron_inv * corrected + self.hard_iron
    }

    /// `S`.
    pub fn soft_iron(&self) -> Mat3<T> {
        self.soft_iron
    }

    /// `h`.
    pub fn hard_iron(&self) -> Vec3<T> {
        self.hard_iron
    }
}
