//! The crate's typed error.
//!
//! Every fallible gyrostat function returns `Result<_, Error>`; none panics on bad input and none
//! returns a silent NaN. The enum is exhaustive on purpose: every face (the C interface's status
//! codes, the Python messages) names every variant in a match without a wildcard, so that a new
//! variant fails to compile until each face has a code for it (a new variant is a breaking
//! change of the library).

use core::fmt;

/// Why an input was rejected.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Error {
    /// An input number was NaN or infinite.
    NonFinite,
    /// A quaternion, axis or vector that must be normalised has (near-)zero norm: its direction is
    /// undefined. For quaternions the threshold is [`crate::UnitQuat::MIN_NORM`].
    ZeroNorm,
    /// A quaternion that must already be of unit norm is too far from it (the caller's data is
    /// not an attitude).
    NotUnit,
    /// A matrix that must be a rotation is not orthonormal with determinant +1 within tolerance.
    NotRotation,
    /// The requested conversion or inverse is singular at this configuration (gimbal lock, a
    /// 180° Gibbs vector, a non-invertible matrix).
    Singular,
    /// An inertia tensor is not physical: not symmetric, not positive definite, or its principal
    /// moments violate the triangle inequality `I_a ≤ I_b + I_c`.
    NonPhysicalInertia,
    /// An iterative solve did not reach its stated accuracy within its step budget.
    NotConverged,
    /// A step is longer than its method's validity limit: the rotation it would take in one step
    /// (`|ω|·Δt`, a gyro increment, an accumulated update interval) is beyond the bound the method
    /// documents ([`crate::step_limit::MAX_STEP_ANGLE`] for the approximate methods), where its
    /// result would carry no correct digit. Take shorter steps.
    StepTooLong,
    /// An argument is outside the documented domain (for example a negative step or count, or a
    /// magnitude whose square, product or reciprocal would overflow the type).
    InvalidArgument,
    /// A value does not fit the fixed-point format it is converted to, or a sum of a checked
    /// fixed-point update would saturate it (see [`crate::fixed`]).
    OutOfRange,
    /// A raw sensor reading is at its register's limit (the sensor saturated: the true value may
    /// be larger), and the caller's [`crate::sensor::ClipPolicy`] rejects such readings.
    Clipped,
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = match self {
            Error::NonFinite => "input is NaN or infinite",
            Error::ZeroNorm => "input has zero norm, its direction is undefined",
            Error::NotUnit => "quaternion is too far from unit norm",
            Error::NotRotation => "matrix is not a proper rotation",
            Error::Singular => "configuration is singular for this conversion",
            Error::NonPhysicalInertia => "inertia tensor is not physical",
            Error::NotConverged => "iterative solve did not converge",
            Error::StepTooLong => "step too long: beyond the method's validity limit",
            Error::InvalidArgument => "argument outside the documented domain",
            Error::OutOfRange => "value outside the range of the fixed-point format",
            Error::Clipped => "sensor reading clipped at its register's limit",
        };
        f.write_str(s)
    }
}

impl core::error::Error for Error {}
