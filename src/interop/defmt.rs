//! `defmt::Format` for the foundation types and the error (feature `defmt`); the propagation
//! types implement it beside their definitions (see [`crate::interop`]).

use defmt::{Format, Formatter, write};

use crate::{Complex, Error, Mat3, Quat, Real, Ring, Su2, UnitQuat, Vec3};

impl<T: Ring + Format> Format for Vec3<T> {
    fn format(&self, f: Formatter<'_>) {
        write!(f, "Vec3({}, {}, {})", self.x, self.y, self.z)
    }
}

impl<T: Ring + Format> Format for Mat3<T> {
    fn format(&self, f: Formatter<'_>) {
        let m = &self.m;
        write!(
            f,
            "Mat3[[{}, {}, {}], [{}, {}, {}], [{}, {}, {}]]",
            m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2]
        )
    }
}

impl<T: Real + Format> Format for Complex<T> {
    fn format(&self, f: Formatter<'_>) {
        write!(f, "({} + {}i)", self.re, self.im)
    }
}

impl<T: Ring + Format> Format for Quat<T> {
    fn format(&self, f: Formatter<'_>) {
        write!(
            f,
            "Quat(w={}, x={}, y={}, z={})",
            self.w, self.x, self.y, self.z
        )
    }
}

impl<T: Ring + Format> Format for UnitQuat<T> {
    fn format(&self, f: Formatter<'_>) {
        write!(
            f,
            "UnitQuat(w={}, x={}, y={}, z={})",
            self.w(),
            self.x(),
            self.y(),
            self.z()
        )
    }
}

impl<T: Real + Format> Format for Su2<T> {
    fn format(&self, f: Formatter<'_>) {
        write!(f, "Su2(a={}, b={})", self.a(), self.b())
    }
}

impl Format for Error {
    fn format(&self, f: Formatter<'_>) {
        let s = match self {
            Error::NonFinite => "NonFinite",
            Error::ZeroNorm => "ZeroNorm",
            Error::NotUnit => "NotUnit",
            Error::NotRotation => "NotRotation",
            Error::Singular => "Singular",
            Error::NonPhysicalInertia => "NonPhysicalInertia",
            Error::NotConverged => "NotConverged",
            Error::StepTooLong => "StepTooLong",
            Error::InvalidArgument => "InvalidArgument",
            Error::OutOfRange => "OutOfRange",
            Error::Clipped => "Clipped",
        };
        write!(f, "Error::{}", s)
    }
}
