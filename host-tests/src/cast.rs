//! Conversions between gyrostat values of any scalar type and the reference's plain f64 arrays.
//!
//! Widening (`q64`, `v64`, `m64`, `u2_64`) is exact for f32 and f64. Narrowing (`vec3`, `mat3`,
//! `unit_quat`) rounds each f64 input to the type under test, so a test hands the reference the
//! rounded inputs (widen them back) when it compares at the type's own rounding level.
//! [`body_hamiltonian`] builds the library's model of a reference model.

use gyrostat::dynamics::{BodyHamiltonian, Inertia, Quartic};
use gyrostat::{Mat3, Quat, Real, Su2, UnitQuat, Vec3};

use crate::ref_dynamics::RefModel;
use crate::reference::{C, M3, Q, U2, V3};

/// `[w, x, y, z]` in f64.
pub fn q64<T: Real>(q: UnitQuat<T>) -> Q {
    q.to_array().map(|c| c.to_f64())
}

/// `[x, y, z]` in f64.
pub fn v64<T: Real>(v: Vec3<T>) -> V3 {
    v.to_array().map(|c| c.to_f64())
}

/// `m[row][col]` in f64.
pub fn m64<T: Real>(m: &Mat3<T>) -> M3 {
    m.m.map(|r| r.map(|c| c.to_f64()))
}

/// The spinor's 2×2 complex matrix (6.6.4) in f64.
pub fn u2_64<T: Real>(u: &Su2<T>) -> U2 {
    u.matrix()
        .map(|row| row.map(|c| C::new(c.re.to_f64(), c.im.to_f64())))
}

/// The vector `a` in `T` (each component rounded).
pub fn vec3<T: Real>(a: V3) -> Vec3<T> {
    Vec3::from_array(a.map(T::from_f64))
}

/// The matrix `a` in `T` (each entry rounded).
pub fn mat3<T: Real>(a: &M3) -> Mat3<T> {
    Mat3::from_rows(
        a[0].map(T::from_f64),
        a[1].map(T::from_f64),
        a[2].map(T::from_f64),
    )
}

/// The quaternion `q` in `T`, normalised there (panics on a zero quaternion: test input).
pub fn unit_quat<T: Real>(q: Q) -> UnitQuat<T> {
    UnitQuat::try_new(Quat::from_array(q.map(T::from_f64))).expect("a non-zero test quaternion")
}

/// The gyrostat model of the reference model `m` in `T` (principal axes = body axes; a quartic
/// term from whichever of `t4`, `t22` is non-zero).
pub fn body_hamiltonian<T: Real>(m: &RefModel) -> BodyHamiltonian<T> {
    let quartic = if m.t4 != 0.0 {
        Quartic::Octahedral(T::from_f64(m.t4))
    } else if m.t22 != 0.0 {
        Quartic::Cubic(T::from_f64(m.t22))
    } else {
        Quartic::None
    };
    let inertia = Inertia::try_from_principal(vec3(m.moments)).expect("physical test moments");
    BodyHamiltonian::try_new(inertia, vec3(m.spin), quartic).expect("a valid test model")
}
