//! `gyrostat._gyrostat`: the Rust extension module of the Python package `gyrostat`.
//!
//! Every function takes and returns numpy arrays of rows (one attitude, sample or state per
//! row) and loops over them in Rust with the GIL released, so that a Python thread pool runs
//! several calls on several cores. A bad row raises [`GyrostatError`] (a `ValueError`) whose
//! message starts with `row N: ` (0-based, the numpy index) and whose `row` attribute is `N`.
//!
//! The Python package (`python/gyrostat/__init__.py`) wraps these functions in scipy's names
//! (`Rotation.from_quat`, `as_euler`, ...), checks shapes and keyword values, and documents the
//! conventions; the functions here trust what the wrapper guarantees (C-contiguous float64 rows
//! of the stated width; unit quaternions where an attitude is expected) and never panic on
//! anything else.

use std::borrow::Cow;

use numpy::{
    PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods,
};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

mod estimation;
mod propagation;
mod rotation;
mod simulation;

pyo3::create_exception!(
    _gyrostat,
    GyrostatError,
    PyValueError,
    "A row of the input was rejected: the message starts with `row N: ` and the attribute \
     `row` holds N (0-based), or None for a problem of the arguments as a whole."
);

/// A problem of one input row (`row`, 0-based) or, with `row == None`, of the call.
#[derive(Debug)]
pub(crate) struct RowError {
    pub row: Option<usize>,
    pub msg: String,
}

impl RowError {
    pub fn at(row: usize, msg: impl Into<String>) -> Self {
        Self {
            row: Some(row),
            msg: msg.into(),
        }
    }

    pub fn call(msg: impl Into<String>) -> Self {
        Self {
            row: None,
            msg: msg.into(),
        }
    }
}

impl From<RowError> for PyErr {
    fn from(e: RowError) -> PyErr {
        Python::attach(|py| {
            let text = match e.row {
                Some(r) => format!("row {r}: {}", e.msg),
                None => e.msg,
            };
            let err = GyrostatError::new_err(text);
            // Setting an attribute on a fresh exception instance cannot fail short of memory
            // exhaustion; the message names the row either way.
            let _ = err.value(py).setattr("row", e.row);
            err
        })
    }
}

/// The rows of a 2-D float64 array of `width` columns, flat and row-major (borrowed when the
/// array is C-contiguous, copied otherwise).
pub(crate) fn rows<'a>(
    a: &'a PyReadonlyArray2<'_, f64>,
    width: usize,
    what: &str,
) -> Result<Cow<'a, [f64]>, RowError> {
    let shape = a.shape();
    if shape[1] != width {
        return Err(RowError::call(format!(
            "{what}: expected rows of {width} numbers, got shape ({}, {})",
            shape[0], shape[1]
        )));
    }
    Ok(match a.as_slice() {
        Ok(s) => Cow::Borrowed(s),
        Err(_) => Cow::Owned(a.as_array().iter().copied().collect()),
    })
}

/// The values of a 1-D float64 array (borrowed when contiguous).
pub(crate) fn values<'a>(a: &'a PyReadonlyArray1<'_, f64>) -> Cow<'a, [f64]> {
    match a.as_slice() {
        Ok(s) => Cow::Borrowed(s),
        Err(_) => Cow::Owned(a.as_array().iter().copied().collect()),
    }
}

/// A flat row-major vector as a 2-D array of `width` columns (no copy: numpy takes the vector's
/// memory).
pub(crate) fn array2<'py, T: numpy::Element>(
    py: Python<'py>,
    data: Vec<T>,
    width: usize,
) -> PyResult<Bound<'py, PyArray2<T>>> {
    let n = data.len().checked_div(width).unwrap_or(0);
    PyArray1::from_vec(py, data).reshape([n, width])
}

/// Maps every row of `input` (`I` numbers) to a row of `O` numbers in a new numpy array, filled
/// with the GIL released; stops at the first row `f` rejects.
///
/// The array is numpy's own allocation (zeroed lazily by the system; on Linux numpy asks for
/// huge pages for large arrays), which for 10⁶ rows costs a fraction of the page faults a
/// vector of the same size would take to fill (measured: 56 ms against 14 ms for 72 MB).
pub(crate) fn map_into<'py, const I: usize, const O: usize>(
    py: Python<'py>,
    input: &[f64],
    f: impl Fn([f64; I]) -> Result<[f64; O], String> + Send + Sync,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let n = input.len() / I;
    let out = PyArray2::<f64>::zeros(py, [n, O], false);
    {
        let mut rw = out.readwrite();
        let slots = rw
            .as_slice_mut()
            .map_err(|e| RowError::call(format!("output array: {e}")))?;
        py.detach(|| {
            for (i, (row, slot)) in input
                .chunks_exact(I)
                .zip(slots.chunks_exact_mut(O))
                .enumerate()
            {
                let mut a = [0.0; I];
                a.copy_from_slice(row);
                slot.copy_from_slice(&f(a).map_err(|m| RowError::at(i, m))?);
            }
            Ok::<(), RowError>(())
        })?;
    }
    Ok(out)
}

/// A new numpy array of `n` rows of `O` numbers, row `i` being `f(i)`, filled with the GIL
/// released (see [`map_into`]).
pub(crate) fn map_index_into<'py, const O: usize>(
    py: Python<'py>,
    n: usize,
    f: impl Fn(usize) -> [f64; O] + Send + Sync,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let out = PyArray2::<f64>::zeros(py, [n, O], false);
    {
        let mut rw = out.readwrite();
        let slots = rw
            .as_slice_mut()
            .map_err(|e| RowError::call(format!("output array: {e}")))?;
        py.detach(|| {
            for (i, slot) in slots.chunks_exact_mut(O).enumerate() {
                slot.copy_from_slice(&f(i));
            }
        });
    }
    Ok(out)
}

/// The extension module.
#[pymodule]
fn _gyrostat(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("GyrostatError", m.py().get_type::<GyrostatError>())?;
    rotation::register(m)?;
    propagation::register(m)?;
    simulation::register(m)?;
    estimation::register(m)?;
    Ok(())
}
