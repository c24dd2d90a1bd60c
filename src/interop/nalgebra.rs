//! Conversions with [`nalgebra`]'s types (feature `nalgebra`, no std needed).
//!
//! nalgebra's `Quaternion::new(w, i, j, k)` and `UnitQuaternion` are Hamilton quaternions with
//! the same active meaning as gyrostat's, so conversions copy components one to one.
//! `UnitQuaternion → UnitQuat` keeps nalgebra's invariant (no renormalisation);
//! `Quaternion → UnitQuat` is only through [`crate::UnitQuat::try_new`].

use nalgebra::{Matrix3, Quaternion, Unit, UnitQuaternion, Vector3};

use crate::{Mat3, Quat, Real, UnitQuat, Vec3};

impl<T: Real + nalgebra::Scalar> From<Vec3<T>> for Vector3<T> {
    fn from(v: Vec3<T>) -> Self {
        Vector3::new(v.x, v.y, v.z)
    }
}

impl<T: Real + nalgebra::Scalar> From<Vector3<T>> for Vec3<T> {
    fn from(v: Vector3<T>) -> Self {
        Vec3::new(v[0], v[1], v[2])
    }
}

impl<T: Real + nalgebra::Scalar> From<Quat<T>> for Quaternion<T> {
    fn from(q: Quat<T>) -> Self {
        Quaternion::new(q.w, q.x, q.y, q.z)
    }
}

impl<T: Real + nalgebra::Scalar> From<Quaternion<T>> for Quat<T> {
    fn from(q: Quaternion<T>) -> Self {
        // nalgebra stores [i, j, k, w].
        Quat::new(q.coords[3], q.coords[0], q.coords[1], q.coords[2])
    }
}

impl<T: Real + nalgebra::Scalar> From<UnitQuat<T>> for UnitQuaternion<T> {
    fn from(q: UnitQuat<T>) -> Self {
        Unit::new_unchecked(q.into_quat().into())
    }
}

impl<T: Real + nalgebra::Scalar> From<UnitQuaternion<T>> for UnitQuat<T> {
    fn from(q: UnitQuaternion<T>) -> Self {
        UnitQuat::new_unchecked(q.into_inner().into())
    }
}

impl<T: Real + nalgebra::Scalar> From<Mat3<T>> for Matrix3<T> {
    fn from(m: Mat3<T>) -> Self {
        let m = m.m;
        Matrix3::new(
            m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2],
        )
    }
}

impl<T: Real + nalgebra::Scalar> From<Matrix3<T>> for Mat3<T> {
    fn from(m: Matrix3<T>) -> Self {
        Mat3::from_rows(
            [m[(0, 0)], m[(0, 1)], m[(0, 2)]],
            [m[(1, 0)], m[(1, 1)], m[(1, 2)]],
            [m[(2, 0)], m[(2, 1)], m[(2, 2)]],
        )
    }
}
