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
use std::mem::MaybeUninit;

use numpy::{
    PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods,
};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

mod allan;
mod estimation;
mod propagation;
mod rotation;
mod simulation;
mod synthesis;

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

/// A new C-ordered `n × width` float64 array, uninitialised (numpy's `empty`): numpy's own
/// allocation, which for large arrays asks Linux for huge pages. A zeroed array (`calloc`) or a
/// vector handed to numpy takes a page fault per 4 KiB page while it is filled: measured while
/// writing this module, 56 ms against 14 ms for 72 MB (a vector), and the plain copy of 10⁶
/// quaternions ran at 175 M/s into a zeroed array, 270 M/s (scipy's copy) into an empty one.
pub(crate) fn empty_rows<'py>(
    py: Python<'py>,
    n: usize,
    width: usize,
) -> Bound<'py, PyArray2<f64>> {
    // SAFETY: every caller writes every element (through `slots`) before the array is returned
    // to Python; on an error return the array is dropped unread.
    unsafe { PyArray2::<f64>::new(py, [n, width], false) }
}

/// The `len` elements at `data`, a new array's ([`empty_rows`], or `PyArray::new`), to be
/// written once each.
///
/// # Safety
/// `data` and `len` are a new array's (C-contiguous, shared with no Python object or other
/// reference yet), and the slice is its one view until the array is returned (`'a` ends there).
pub(crate) unsafe fn slots<'a, T>(data: *mut T, len: usize) -> &'a mut [MaybeUninit<T>] {
    // SAFETY: by the caller's promise `data` holds `len` elements viewed only through this
    // slice; `MaybeUninit` makes no claim about the contents.
    unsafe { std::slice::from_raw_parts_mut(data.cast::<MaybeUninit<T>>(), len) }
}

/// Writes `values` into `slot`, element by element.
#[inline(always)]
fn put<const O: usize>(slot: &mut [MaybeUninit<f64>], values: [f64; O]) {
    for (s, v) in slot.iter_mut().zip(values) {
        s.write(v);
    }
}

/// Maps every row of `input` (`I` numbers) to a row of `O` numbers in a new numpy array
/// ([`empty_rows`]), filled with the GIL released; stops at the first row `f` rejects.
pub(crate) fn map_into<'py, const I: usize, const O: usize>(
    py: Python<'py>,
    input: &[f64],
    f: impl Fn([f64; I]) -> Result<[f64; O], String> + Send + Sync,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let n = input.len() / I;
    let out = empty_rows(py, n, O);
    // SAFETY: `out` is new; this is its only view.
    let slots = unsafe { slots(out.data(), out.len()) };
    py.detach(|| {
        for (i, (row, slot)) in input
            .chunks_exact(I)
            .zip(slots.chunks_exact_mut(O))
            .enumerate()
        {
            let mut a = [0.0; I];
            a.copy_from_slice(row);
            put(slot, f(a).map_err(|m| RowError::at(i, m))?);
        }
        Ok::<(), RowError>(())
    })?;
    Ok(out)
}

/// [`map_into`] for a conversion that cannot fail: no per-row error path.
pub(crate) fn map_rows<'py, const I: usize, const O: usize>(
    py: Python<'py>,
    input: &[f64],
    f: impl Fn([f64; I]) -> [f64; O] + Send + Sync,
) -> Bound<'py, PyArray2<f64>> {
    let n = input.len() / I;
    let out = empty_rows(py, n, O);
    // SAFETY: `out` is new; this is its only view.
    let slots = unsafe { slots(out.data(), out.len()) };
    py.detach(|| {
        for (row, slot) in input.chunks_exact(I).zip(slots.chunks_exact_mut(O)) {
            let mut a = [0.0; I];
            a.copy_from_slice(row);
            put(slot, f(a));
        }
    });
    out
}

/// A new numpy array of `n` rows of `O` numbers, row `i` being `f(i)`, filled with the GIL
/// released (see [`map_into`]).
pub(crate) fn map_index_into<'py, const O: usize>(
    py: Python<'py>,
    n: usize,
    f: impl Fn(usize) -> [f64; O] + Send + Sync,
) -> Bound<'py, PyArray2<f64>> {
    let out = empty_rows(py, n, O);
    // SAFETY: `out` is new; this is its only view.
    let slots = unsafe { slots(out.data(), out.len()) };
    py.detach(|| {
        for (i, slot) in slots.chunks_exact_mut(O).enumerate() {
            put(slot, f(i));
        }
    });
    out
}

/// A copy of `input` as a new `width`-column array ([`empty_rows`]).
pub(crate) fn copy_rows<'py>(
    py: Python<'py>,
    input: &[f64],
    width: usize,
) -> Bound<'py, PyArray2<f64>> {
    let out = empty_rows(py, input.len() / width, width);
    // SAFETY: `out` is new; this is its only view.
    let slots = unsafe { slots(out.data(), out.len()) };
    py.detach(|| {
        for (s, &v) in slots.iter_mut().zip(input) {
            s.write(v);
        }
    });
    out
}

/// The extension module.
#[pymodule]
fn _gyrostat(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("GyrostatError", m.py().get_type::<GyrostatError>())?;
    rotation::register(m)?;
    propagation::register(m)?;
    simulation::register(m)?;
    estimation::register(m)?;
    synthesis::register(m)?;
    allan::register(m)?;
    Ok(())
}
