//! Attitude conversions over arrays of rows, in scipy's conventions.
//!
//! Attitudes are stored as unit quaternions `w, x, y, z` (Hamilton, scalar first, body → lab:
//! the active rotation whose matrix has the body axes as columns, which is scipy's `Rotation`
//! matrix). Every `from_*` checks its rows and returns unit quaternions; every `as_*` takes the
//! unit quaternions the package holds.

use numpy::{PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;

use gyrostat::rotation::{Dcm, Euler, EulerSequence, GimbalPolicy, Mrp, RotationVector};
use gyrostat::{Error, Mat3, Quat, UnitQuat, Vec3};

use crate::{RowError, copy_rows, empty_rows, map_index_into, map_into, map_rows, rows, slots};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(quat_from_quat, m)?)?;
    m.add_function(wrap_pyfunction!(quat_as_quat, m)?)?;
    m.add_function(wrap_pyfunction!(quat_from_euler, m)?)?;
    m.add_function(wrap_pyfunction!(quat_as_euler, m)?)?;
    m.add_function(wrap_pyfunction!(quat_from_rotvec, m)?)?;
    m.add_function(wrap_pyfunction!(quat_as_rotvec, m)?)?;
    m.add_function(wrap_pyfunction!(quat_from_mrp, m)?)?;
    m.add_function(wrap_pyfunction!(quat_as_mrp, m)?)?;
    m.add_function(wrap_pyfunction!(quat_from_matrix, m)?)?;
    m.add_function(wrap_pyfunction!(quat_as_matrix, m)?)?;
    m.add_function(wrap_pyfunction!(quat_compose, m)?)?;
    m.add_function(wrap_pyfunction!(quat_apply, m)?)?;
    m.add_function(wrap_pyfunction!(quat_magnitude, m)?)?;
    Ok(())
}

/// A held attitude (trusted unit quaternion, `w, x, y, z`).
#[inline]
pub(crate) fn held([w, x, y, z]: [f64; 4]) -> UnitQuat<f64> {
    UnitQuat::new_unchecked(Quat::new(w, x, y, z))
}

fn v3([x, y, z]: [f64; 3]) -> Vec3<f64> {
    Vec3::new(x, y, z)
}

fn seq(s: &str) -> Result<EulerSequence, RowError> {
    EulerSequence::try_from_str(s).map_err(|_| {
        RowError::call(format!(
            "seq: expected 3 characters from xyz, all uppercase (intrinsic) or all lowercase \
             (extrinsic), no axis twice in a row, got {s:?}"
        ))
    })
}

/// The text of a rejected component: `NaN or infinite`.
fn non_finite(what: &str) -> String {
    format!("{what} has a NaN or infinite component")
}

/// `(4ε)²`: the smallest squared norm [`quat_from_quat`] normalises without the library.
const FAST_MIN_NORM2: f64 = 16.0 * f64::EPSILON * f64::EPSILON;

/// Quaternions of any finite norm above `ε` (the library's `UnitQuat::MIN_NORM`), normalised (scipy's `from_quat`); rows `x, y, z, w`
/// unless `scalar_first`.
#[pyfunction]
#[pyo3(signature = (quat, scalar_first))]
fn quat_from_quat<'py>(
    py: Python<'py>,
    quat: PyReadonlyArray2<'py, f64>,
    scalar_first: bool,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let q = rows(&quat, 4, "quat")?;
    map_into::<4, 4>(py, &q, |r| {
        let [w, x, y, z] = if scalar_first {
            r
        } else {
            [r[3], r[0], r[1], r[2]]
        };
        // A norm from 4ε (the library rejects ε and below as zero, `UnitQuat::MIN_NORM`) to
        // 1e150: one square root and one division, to 1 ulp of the library's scaled
        // normalisation; beyond it (and for zero or non-finite rows) the library's.
        let n2 = w * w + x * x + y * y + z * z;
        if (FAST_MIN_NORM2..=1e300).contains(&n2) {
            let s = 1.0 / n2.sqrt();
            return Ok([w * s, x * s, y * s, z * s]);
        }
        UnitQuat::try_new(Quat::new(w, x, y, z))
            .map(|u| u.to_array())
            .map_err(|e| match e {
                Error::ZeroNorm => "quaternion has zero norm".to_string(),
                _ => non_finite("quaternion"),
            })
    })
}

/// The held quaternions in scipy's order (`x, y, z, w` unless `scalar_first`), each the
/// representative with `w ≥ 0` when `canonical` (ties: first non-zero of x, y, z positive).
#[pyfunction]
#[pyo3(signature = (quat, scalar_first, canonical))]
fn quat_as_quat<'py>(
    py: Python<'py>,
    quat: PyReadonlyArray2<'py, f64>,
    scalar_first: bool,
    canonical: bool,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let q = rows(&quat, 4, "quat")?;
    if scalar_first && !canonical {
        // The rows as held: a copy.
        return Ok(copy_rows(py, &q, 4));
    }
    Ok(match (canonical, scalar_first) {
        (true, true) => map_rows::<4, 4>(py, &q, |r| held(r).canonical().to_array()),
        (true, false) => map_rows::<4, 4>(py, &q, |r| {
            let [w, x, y, z] = held(r).canonical().to_array();
            [x, y, z, w]
        }),
        (false, _) => map_rows::<4, 4>(py, &q, |[w, x, y, z]| [x, y, z, w]),
    })
}

/// Euler angles (rad, or degrees) in scipy's sequence notation.
#[pyfunction]
#[pyo3(signature = (seq, angles, degrees))]
fn quat_from_euler<'py>(
    py: Python<'py>,
    seq: &str,
    angles: PyReadonlyArray2<'py, f64>,
    degrees: bool,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let s = self::seq(seq)?;
    let a = rows(&angles, 3, "angles")?;
    let k = if degrees {
        core::f64::consts::PI / 180.0
    } else {
        1.0
    };
    map_into::<3, 4>(py, &a, |r| {
        Euler::new(s, r.map(|x| x * k))
            .try_to_unit_quat()
            .map(|q| q.to_array())
            .map_err(|_| non_finite("angles"))
    })
}

/// Euler angles (N, 3) and the gimbal-lock flags (N,).
type EulerRows<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray1<bool>>);

/// Euler angles of held attitudes, and per row whether it is at a gimbal lock (the middle angle
/// within `2·ε` of its pole: the third angle is then set to 0, scipy's choice).
#[pyfunction]
#[pyo3(signature = (quat, seq, degrees))]
fn quat_as_euler<'py>(
    py: Python<'py>,
    quat: PyReadonlyArray2<'py, f64>,
    seq: &str,
    degrees: bool,
) -> PyResult<EulerRows<'py>> {
    let s = self::seq(seq)?;
    let q = rows(&quat, 4, "quat")?;
    let k = if degrees {
        180.0 / core::f64::consts::PI
    } else {
        1.0
    };
    let n = q.len() / 4;
    let angles = empty_rows(py, n, 3);
    // SAFETY: every element is written below before the array is returned.
    let lock = unsafe { PyArray1::<bool>::new(py, [n], false) };
    {
        // SAFETY: both arrays are new; these are their only views.
        let (a, l) = unsafe {
            (
                slots(angles.data(), angles.len()),
                slots(lock.data(), lock.len()),
            )
        };
        py.detach(|| {
            for ((r, a), l) in q
                .chunks_exact(4)
                .zip(a.chunks_exact_mut(3))
                .zip(l.iter_mut())
            {
                let sol = held([r[0], r[1], r[2], r[3]]).to_euler(s, GimbalPolicy::ZeroThird);
                for (a, v) in a.iter_mut().zip(sol.euler.angles) {
                    a.write(v * k);
                }
                l.write(sol.singularity.is_some());
            }
        });
    }
    Ok((angles, lock))
}

/// Rotation vectors (angle × axis; rad, or degrees when `degrees`: the whole vector scaled).
#[pyfunction]
#[pyo3(signature = (rotvec, degrees))]
fn quat_from_rotvec<'py>(
    py: Python<'py>,
    rotvec: PyReadonlyArray2<'py, f64>,
    degrees: bool,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let v = rows(&rotvec, 3, "rotvec")?;
    let k = if degrees {
        core::f64::consts::PI / 180.0
    } else {
        1.0
    };
    map_into::<3, 4>(py, &v, |r| {
        RotationVector::try_new(v3(r.map(|x| x * k)))
            .map(|v| v.to_unit_quat().to_array())
            .map_err(|e| match e {
                Error::NonFinite => non_finite("rotation vector"),
                e => format!("rotation vector: {e} (its length overflows)"),
            })
    })
}

/// Rotation vectors of held attitudes, angle in `[0, π]`.
#[pyfunction]
#[pyo3(signature = (quat, degrees))]
fn quat_as_rotvec<'py>(
    py: Python<'py>,
    quat: PyReadonlyArray2<'py, f64>,
    degrees: bool,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let q = rows(&quat, 4, "quat")?;
    let k = if degrees {
        180.0 / core::f64::consts::PI
    } else {
        1.0
    };
    map_into::<4, 3>(py, &q, |r| {
        Ok(RotationVector::from_unit_quat(held(r))
            .vector()
            .scale(k)
            .to_array())
    })
}

/// Modified Rodrigues parameters `σ = axis·tan(angle/4)`, any finite value (the shadow set is
/// the same rotation).
#[pyfunction]
#[pyo3(signature = (mrp))]
fn quat_from_mrp<'py>(
    py: Python<'py>,
    mrp: PyReadonlyArray2<'py, f64>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let p = rows(&mrp, 3, "mrp")?;
    map_into::<3, 4>(py, &p, |r| {
        Mrp::try_new(v3(r))
            .map(|m| m.to_unit_quat().to_array())
            .map_err(|_| non_finite("MRP"))
    })
}

/// MRPs of held attitudes, `|σ| ≤ 1`.
#[pyfunction]
#[pyo3(signature = (quat))]
fn quat_as_mrp<'py>(
    py: Python<'py>,
    quat: PyReadonlyArray2<'py, f64>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let q = rows(&quat, 4, "quat")?;
    Ok(map_rows::<4, 3>(py, &q, |r| {
        Mrp::from_unit_quat(held(r)).vector().to_array()
    }))
}

/// Rotation matrices, rows of 9 numbers (row-major): a rotation within `1000·ε` is converted
/// directly (Shepperd), any other matrix with positive determinant is replaced by its nearest
/// rotation (the orthogonal polar factor, like scipy's `from_matrix`).
#[pyfunction]
#[pyo3(signature = (matrix))]
fn quat_from_matrix<'py>(
    py: Python<'py>,
    matrix: PyReadonlyArray2<'py, f64>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let m = rows(&matrix, 9, "matrix")?;
    let tol = Dcm::<f64>::default_tolerance();
    map_into::<9, 4>(py, &m, |r| {
        let m = Mat3::from_rows([r[0], r[1], r[2]], [r[3], r[4], r[5]], [r[6], r[7], r[8]]);
        Dcm::try_from_matrix(m, tol)
            .or_else(|_| Dcm::try_from_matrix_orthonormalized(m))
            .map(|d| d.to_unit_quat().to_array())
            .map_err(|e| match e {
                Error::NonFinite => non_finite("matrix"),
                _ => "matrix has no nearest rotation (determinant <= 0, or singular)".to_string(),
            })
    })
}

/// Rotation matrices of held attitudes, rows of 9 numbers (row-major; columns are the body
/// axes).
#[pyfunction]
#[pyo3(signature = (quat))]
fn quat_as_matrix<'py>(
    py: Python<'py>,
    quat: PyReadonlyArray2<'py, f64>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let q = rows(&quat, 4, "quat")?;
    Ok(map_rows::<4, 9>(py, &q, |r| {
        let m = held(r).to_rotation_matrix().m;
        [
            m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2],
        ]
    }))
}

/// The number of rows of a broadcast of `a` and `b` rows (equal, or one of them 1).
fn broadcast(a: usize, b: usize) -> Result<usize, RowError> {
    match (a, b) {
        (a, b) if a == b => Ok(a),
        (1, b) => Ok(b),
        (a, 1) => Ok(a),
        (a, b) => Err(RowError::call(format!(
            "expected equal numbers of rows or one of them 1, got {a} and {b}"
        ))),
    }
}

/// Hamilton products `a ⊗ b` of held attitudes (`b` applied first: scipy's `a * b`), with one
/// row broadcast against many; the product is renormalised.
#[pyfunction]
#[pyo3(signature = (a, b))]
fn quat_compose<'py>(
    py: Python<'py>,
    a: PyReadonlyArray2<'py, f64>,
    b: PyReadonlyArray2<'py, f64>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let (qa, qb) = (rows(&a, 4, "a")?, rows(&b, 4, "b")?);
    let (na, nb) = (qa.len() / 4, qb.len() / 4);
    let n = broadcast(na, nb)?;
    let (qa, qb) = (&*qa, &*qb);
    let row = |q: &[f64], i: usize| held([q[4 * i], q[4 * i + 1], q[4 * i + 2], q[4 * i + 3]]);
    let idx = |i: usize| (if na == 1 { 0 } else { i }, if nb == 1 { 0 } else { i });
    Ok(map_index_into::<4>(py, n, |i| {
        let (ia, ib) = idx(i);
        (row(qa, ia) * row(qb, ib)).renormalize().to_array()
    }))
}

/// `R(q)·v` (or `R(q)ᵀ·v` when `inverse`) for held attitudes and vectors, one row broadcast
/// against many.
#[pyfunction]
#[pyo3(signature = (quat, vectors, inverse))]
fn quat_apply<'py>(
    py: Python<'py>,
    quat: PyReadonlyArray2<'py, f64>,
    vectors: PyReadonlyArray2<'py, f64>,
    inverse: bool,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let (q, v) = (rows(&quat, 4, "quat")?, rows(&vectors, 3, "vectors")?);
    let (nq, nv) = (q.len() / 4, v.len() / 3);
    let n = broadcast(nq, nv)?;
    let (q, v) = (&*q, &*v);
    Ok(map_index_into::<3>(py, n, |i| {
        let (iq, iv) = (if nq == 1 { 0 } else { i }, if nv == 1 { 0 } else { i });
        let a = held([q[4 * iq], q[4 * iq + 1], q[4 * iq + 2], q[4 * iq + 3]]);
        let x = v3([v[3 * iv], v[3 * iv + 1], v[3 * iv + 2]]);
        let y = if inverse {
            a.inverse_rotate(x)
        } else {
            a.rotate(x)
        };
        y.to_array()
    }))
}

/// The rotation angles of held attitudes, in `[0, π]`.
#[pyfunction]
#[pyo3(signature = (quat))]
fn quat_magnitude<'py>(
    py: Python<'py>,
    quat: PyReadonlyArray2<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let q = rows(&quat, 4, "quat")?;
    let out = map_into::<4, 1>(py, &q, |r| Ok([held(r).angle()]))?;
    let n = out.len();
    out.reshape([n])
}
