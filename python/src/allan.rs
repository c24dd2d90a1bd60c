//! The Allan deviation and the noise characterisation of `characterize` (one definition,
//! `gyrostat_tools::allan`), numpy in and out.

use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use gyrostat_tools::allan::{self, Spacing};

use crate::{RowError, values};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(allan_deviation, m)?)?;
    m.add_function(wrap_pyfunction!(allan_characterize, m)?)?;
    Ok(())
}

fn spacing(per_decade: Option<u32>) -> Spacing {
    per_decade.map_or(Spacing::Octave, Spacing::PerDecade)
}

/// `(taus, adev, terms, edf)` of the samples `x` at `rate` Hz for the averaging factors
/// `factors` (None: the grid of `per_decade`, octaves without it).
#[pyfunction]
#[pyo3(signature = (x, rate, factors=None, per_decade=None))]
#[allow(clippy::type_complexity)]
fn allan_deviation<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    rate: f64,
    factors: Option<Vec<usize>>,
    per_decade: Option<u32>,
) -> PyResult<(
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<u64>>,
    Bound<'py, PyArray1<f64>>,
)> {
    let y = values(&x);
    let ms = factors.unwrap_or_else(|| allan::factors(y.len(), spacing(per_decade)));
    let points = py
        .detach(|| allan::overlapping(&y, rate, &ms))
        .map_err(|e| RowError::call(e.to_string()))?;
    Ok((
        PyArray1::from_iter(py, points.iter().map(|p| p.tau)),
        PyArray1::from_iter(py, points.iter().map(|p| p.adev)),
        PyArray1::from_iter(py, points.iter().map(|p| p.terms as u64)),
        PyArray1::from_iter(py, points.iter().map(|p| p.edf)),
    ))
}

/// The fit of one axis: a dict of the curve (`taus`, `adev`, `terms`, `edf` for the fitted
/// dominant noise) and the coefficients (`noise_density`, `bias_instability`,
/// `rate_random_walk`, `floor_bound`, `floor_tau`, `chi2_per_dof`).
#[pyfunction]
#[pyo3(signature = (x, rate, fit_from=0.0, per_decade=None))]
fn allan_characterize<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    rate: f64,
    fit_from: f64,
    per_decade: Option<u32>,
) -> PyResult<Bound<'py, PyDict>> {
    let y = values(&x);
    let c = py
        .detach(|| allan::characterize(&y, rate, spacing(per_decade), fit_from))
        .map_err(|e| RowError::call(e.to_string()))?;
    let d = PyDict::new(py);
    d.set_item(
        "taus",
        PyArray1::from_iter(py, c.points.iter().map(|p| p.tau)),
    )?;
    d.set_item(
        "adev",
        PyArray1::from_iter(py, c.points.iter().map(|p| p.adev)),
    )?;
    d.set_item(
        "terms",
        PyArray1::from_iter(py, c.points.iter().map(|p| p.terms as u64)),
    )?;
    d.set_item(
        "edf",
        PyArray1::from_iter(py, c.points.iter().map(|p| p.edf)),
    )?;
    let f = c.fit;
    d.set_item("noise_density", f.noise_density)?;
    d.set_item("bias_instability", f.bias_instability)?;
    d.set_item("rate_random_walk", f.rate_random_walk)?;
    d.set_item("floor_bound", f.floor_bound)?;
    d.set_item("floor_tau", f.floor_tau)?;
    d.set_item("chi2_per_dof", f.chi2_per_dof)?;
    Ok(d)
}
