//! Attitude propagation over arrays of gyro samples, with the rows of the `propagate` tool.
//!
//! Increments: row `k` is the attitude after increments `0..=k` (time `(k+1)·dt`); a coning
//! rule of `N` samples updates once per `N` increments, and a row inside a group applies the
//! pending increments with the highest-order rule that fits them (not fed back). Rates: row
//! `k` is the attitude at time `k·dt` (row 0 is `q0`). The loops and their checks are
//! `gyrostat_pipeline::propagate`'s, the ones the tool runs, so the same numbers, bit for bit.

use std::fmt::Debug;

use numpy::PyReadonlyArray2;
use pyo3::prelude::*;

use gyrostat::propagation::{CompensatedAttitude, ConingRule, PropagatedAttitude, RateMethod};
use gyrostat::real::Q30;
use gyrostat::{Quat, Real, UnitQuat, Vec3};
use gyrostat_pipeline::propagate::{self, PropagateError};

use crate::{RowError, array2, rows};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(propagate_increments, m)?)?;
    m.add_function(wrap_pyfunction!(propagate_rates, m)?)?;
    Ok(())
}

/// The coning rule of a name (the library's `ConingRule::name`, the `propagate` tool's `--algo`).
fn rule(name: &str) -> Result<ConingRule, RowError> {
    name.parse().map_err(|_| {
        let names = ConingRule::ALL.map(ConingRule::name).join(", ");
        RowError::call(format!("rule: unknown {name:?} ({names})"))
    })
}

/// The rate method of a name (the library's `RateMethod::name`).
fn method(name: &str) -> Result<RateMethod, RowError> {
    name.parse().map_err(|_| {
        let names = RateMethod::ALL.map(RateMethod::name).join(", ");
        RowError::call(format!("method: unknown {name:?} ({names})"))
    })
}

/// The arithmetic of a run.
#[derive(Clone, Copy, PartialEq)]
enum Precision {
    F64,
    F32,
    Q30,
}

fn precision(name: &str) -> Result<Precision, RowError> {
    Ok(match name {
        "f64" => Precision::F64,
        "f32" => Precision::F32,
        "q30" => Precision::Q30,
        other => {
            return Err(RowError::call(format!(
                "precision: unknown {other:?} (f64, f32, q30)"
            )));
        }
    })
}

/// `q0` as the tool takes it: norm within 1e-3 of 1, then normalised exactly.
fn initial<T: Real>(q0: [f64; 4]) -> Result<UnitQuat<T>, RowError> {
    let t = T::from_f64;
    UnitQuat::try_from_near_unit(Quat::new(t(q0[0]), t(q0[1]), t(q0[2]), t(q0[3])), t(1e-3))
        .map_err(|e| RowError::call(format!("q0: {e}: its norm must be within 1e-3 of 1")))
}

/// A row of three numbers in `T`.
fn sample<T: Real>(r: &[f64]) -> Vec3<T> {
    Vec3::new(T::from_f64(r[0]), T::from_f64(r[1]), T::from_f64(r[2]))
}

/// The error of sample `k` that stops a propagation (`gyrostat_pipeline::propagate`).
fn stopped(e: PropagateError, k: usize) -> RowError {
    RowError::at(
        k,
        match e {
            PropagateError::NonFinite => "sample has a NaN or infinite component".to_string(),
            PropagateError::Unresolvable { turn, limit } => format!(
                "the increment turns the body {turn:.3e} rad in one sample: beyond {limit:.2e} rad \
                 the angle itself is not known to 1e-3 rad"
            ),
            PropagateError::Library(e) => e.to_string(),
            PropagateError::Quantize(e) => format!("{e} (Q1.30 holds |value| < 2 rad)"),
            PropagateError::NotUnit(_) => {
                "the attitude is not a finite unit quaternion: the samples are too large for this step"
                    .to_string()
            }
        },
    )
}

fn increments<T: Real + Debug, A: PropagatedAttitude<T> + From<UnitQuat<T>>>(
    input: &[f64],
    q0: [f64; 4],
    rule: ConingRule,
) -> Result<Vec<T>, RowError> {
    let q0 = initial::<T>(q0)?;
    let mut integ = propagate::Increments::<T, A>::new(q0, rule);
    let mut out = Vec::with_capacity(input.len() / 3 * 4);
    for (k, r) in input.chunks_exact(3).enumerate() {
        let q = integ.push(sample(r)).map_err(|e| stopped(e, k))?;
        out.extend(q.to_array());
    }
    Ok(out)
}

fn increments_q30(input: &[f64], q0: [f64; 4], rule: ConingRule) -> Result<Vec<f64>, RowError> {
    let q0 = initial::<f64>(q0)?;
    let q0 = UnitQuat::<Q30>::try_from_f64(q0).map_err(|e| RowError::call(format!("q0: {e}")))?;
    // The tool's `--fixed`: each update carries the low bits its rounding dropped, and each
    // increment's rounding remainder goes into the next one (the firmware's integer code).
    let mut integ = propagate::FixedIncrements::new(q0, rule);
    let mut out = Vec::with_capacity(input.len() / 3 * 4);
    for (k, r) in input.chunks_exact(3).enumerate() {
        let q = integ
            .push(Vec3::new(r[0], r[1], r[2]))
            .map_err(|e| stopped(e, k))?;
        out.extend(q.to_f64().to_array());
    }
    Ok(out)
}

fn rates<T: Real + Debug, A: PropagatedAttitude<T> + From<UnitQuat<T>>>(
    input: &[f64],
    q0: [f64; 4],
    method: RateMethod,
    dt: f64,
) -> Result<Vec<T>, RowError> {
    let q0 = initial::<T>(q0)?;
    let step = T::from_f64(dt);
    if !(step.is_finite() && step > T::ZERO) {
        return Err(RowError::call(format!(
            "dt: {dt:?} is not a positive finite number of this precision"
        )));
    }
    let mut integ = propagate::Rates::<T, A>::try_new(q0, method, dt)
        .map_err(|e| RowError::call(format!("dt: {e}")))?;
    let n = input.len() / 3;
    let mut out = Vec::with_capacity(n * 4);
    let mut reached = 0;
    for (k, r) in input.chunks_exact(3).enumerate() {
        let qs = integ.push(sample(r)).map_err(|e| stopped(e, k))?;
        for q in qs {
            out.extend(q.map_err(|e| stopped(e, reached))?.to_array());
            reached += 1;
        }
    }
    for q in integ.finish() {
        out.extend(q.map_err(|e| stopped(e, reached))?.to_array());
        reached += 1;
    }
    Ok(out)
}

/// Attitudes from gyro increments (rad, body frame, one per row), the `propagate` tool's
/// `--input increments`; float32 rows for `precision="f32"`, float64 otherwise.
#[pyfunction]
#[pyo3(signature = (increments, rule, q0, precision, compensated))]
fn propagate_increments<'py>(
    py: Python<'py>,
    increments: PyReadonlyArray2<'py, f64>,
    rule: &str,
    q0: [f64; 4],
    precision: &str,
    compensated: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let input = rows(&increments, 3, "increments")?;
    let rule = self::rule(rule)?;
    let p = self::precision(precision)?;
    if p == Precision::Q30 && compensated {
        return Err(RowError::call(
            "compensated needs floating point (f64 or f32), not q30: the fixed-point path \
             rounds to the same bits as the firmware",
        )
        .into());
    }
    Ok(match (p, compensated) {
        (Precision::F64, false) => {
            let out = py.detach(|| self::increments::<f64, UnitQuat<f64>>(&input, q0, rule))?;
            array2(py, out, 4)?.into_any()
        }
        (Precision::F64, true) => {
            let out =
                py.detach(|| self::increments::<f64, CompensatedAttitude<f64>>(&input, q0, rule))?;
            array2(py, out, 4)?.into_any()
        }
        (Precision::F32, false) => {
            let out = py.detach(|| self::increments::<f32, UnitQuat<f32>>(&input, q0, rule))?;
            array2(py, out, 4)?.into_any()
        }
        (Precision::F32, true) => {
            let out =
                py.detach(|| self::increments::<f32, CompensatedAttitude<f32>>(&input, q0, rule))?;
            array2(py, out, 4)?.into_any()
        }
        (Precision::Q30, _) => {
            let out = py.detach(|| increments_q30(&input, q0, rule))?;
            array2(py, out, 4)?.into_any()
        }
    })
}

/// Attitudes from rate samples (rad/s, body frame, sample `k` at time `k·dt`), the
/// `propagate` tool's `--input rates`.
#[pyfunction]
#[pyo3(signature = (rates, dt, method, q0, precision, compensated))]
fn propagate_rates<'py>(
    py: Python<'py>,
    rates: PyReadonlyArray2<'py, f64>,
    dt: f64,
    method: &str,
    q0: [f64; 4],
    precision: &str,
    compensated: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let input = rows(&rates, 3, "rates")?;
    let m = self::method(method)?;
    Ok(match (self::precision(precision)?, compensated) {
        (Precision::F64, false) => {
            let out = py.detach(|| self::rates::<f64, UnitQuat<f64>>(&input, q0, m, dt))?;
            array2(py, out, 4)?.into_any()
        }
        (Precision::F64, true) => {
            let out =
                py.detach(|| self::rates::<f64, CompensatedAttitude<f64>>(&input, q0, m, dt))?;
            array2(py, out, 4)?.into_any()
        }
        (Precision::F32, false) => {
            let out = py.detach(|| self::rates::<f32, UnitQuat<f32>>(&input, q0, m, dt))?;
            array2(py, out, 4)?.into_any()
        }
        (Precision::F32, true) => {
            let out =
                py.detach(|| self::rates::<f32, CompensatedAttitude<f32>>(&input, q0, m, dt))?;
            array2(py, out, 4)?.into_any()
        }
        (Precision::Q30, _) => {
            return Err(RowError::call(
                "precision q30 takes increments only (propagate_increments)",
            )
            .into());
        }
    })
}
