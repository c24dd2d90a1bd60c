//! Conversions with [`mint`]'s plain types (feature `mint`).
//!
//! `mint::Quaternion { v, s }` stores the vector part first; the conversion maps `s ↔ w`, so the
//! meaning is the same Hamilton quaternion. A `mint::Quaternion` converts into a [`UnitQuat`]
//! only through `TryFrom` (it normalises, like [`UnitQuat::try_new`]).

use crate::{Error, Mat3, Quat, Real, UnitQuat, Vec3};

impl<T: Real> From<Vec3<T>> for mint::Vector3<T> {
    fn from(v: Vec3<T>) -> Self {
        mint::Vector3 {
            x: v.x,
            y: v.y,
            z: v.z,
        }
    }
}

impl<T: Real> From<mint::Vector3<T>> for Vec3<T> {
    fn from(v: mint::Vector3<T>) -> Self {
        Vec3::new(v.x, v.y, v.z)
    }
}

impl<T: Real> From<Quat<T>> for mint::Quaternion<T> {
    fn from(q: Quat<T>) -> Self {
        mint::Quaternion {
            v: q.vector().into(),
            s: q.w,
        }
    }
}

impl<T: Real> From<mint::Quaternion<T>> for Quat<T> {
    fn from(q: mint::Quaternion<T>) -> Self {
        Quat::new(q.s, q.v.x, q.v.y, q.v.z)
    }
}

impl<T: Real> From<UnitQuat<T>> for mint::Quaternion<T> {
    fn from(q: UnitQuat<T>) -> Self {
        q.into_quat().into()
    }
}

impl<T: Real> TryFrom<mint::Quaternion<T>> for UnitQuat<T> {
    type Error = Error;
    fn try_from(q: mint::Quaternion<T>) -> Result<Self, Error> {
        UnitQuat::try_new(q.into())
    }
}

impl<T: Real> From<Mat3<T>> for mint::RowMatrix3<T> {
    fn from(m: Mat3<T>) -> Self {
        mint::RowMatrix3 {
            x: m.row(0).into(),
            y: m.row(1).into(),
            z: m.row(2).into(),
        }
    }
}

impl<T: Real> From<mint::RowMatrix3<T>> for Mat3<T> {
    fn from(m: mint::RowMatrix3<T>) -> Self {
        Mat3::from_rows(
            [m.x.x, m.x.y, m.x.z],
            [m.y.x, m.y.y, m.y.z],
            [m.z.x, m.z.y, m.z.z],
        )
    }
}

impl<T: Real> From<Mat3<T>> for mint::ColumnMatrix3<T> {
    fn from(m: Mat3<T>) -> Self {
        mint::ColumnMatrix3 {
            x: m.col(0).into(),
            y: m.col(1).into(),
            z: m.col(2).into(),
        }
    }
}

impl<T: Real> From<mint::ColumnMatrix3<T>> for Mat3<T> {
    fn from(m: mint::ColumnMatrix3<T>) -> Self {
        Mat3::from_cols(m.x.into(), m.y.into(), m.z.into())
    }
}
