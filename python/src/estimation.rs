//! The attitude-and-bias estimator (`gyrostat::estimation::Estimator`) over arrays of samples
//! with their time stamps.
//!
//! The loop is `gyrostat_pipeline::estimate::Run`, the one the `estimate` tool and the BROAD
//! runner of host-tests run: sample `k` is propagated over `t[k] − t[k−1]` (the previous good
//! sample's time stamp); the first sample has no step and is given NaN (the library's
//! first-sample rule, `Estimator::update`: until the attitude is initialised no sample
//! propagates and `dt` is neither used nor checked, so a record that starts while the sensor
//! turns fast is accepted); a time stamp not after the previous one or a step over 1000 s is an
//! error; `skip_errors` is the tool's `--skip-bad-rows` (a non-finite time stamp or gyroscope
//! value becomes a gap).

use numpy::{PyArray1, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use gyrostat::Real;
use gyrostat::estimation::{EarthFrame, Gains, Mode, Params, RateRule, SensorUse};
use gyrostat_pipeline::estimate::{Options, RowError as RowError_, Run, Sample, Step};

use crate::{RowError, array2, rows, values};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(estimate, m)?)?;
    m.add_function(wrap_pyfunction!(estimator_defaults, m)?)?;
    Ok(())
}

/// The estimator's default parameters (SI units, angles in rad) by name, and the default rate
/// rule of `mode` (`full` or `light`) under `rate_rule` (its name): `Params::defaults_of`, what
/// `estimate` starts from.
#[pyfunction]
#[pyo3(signature = (mode = "full"))]
fn estimator_defaults<'py>(py: Python<'py>, mode: &str) -> PyResult<Bound<'py, PyDict>> {
    let mode = mode_of(mode)?;
    let p = Params::<f64>::defaults_of(EarthFrame::Enu, mode);
    let d = PyDict::new(py);
    for (name, v) in Params::<f64>::FLAT_NAMES.iter().zip(p.values()) {
        d.set_item(name, v)?;
    }
    d.set_item("rate_rule", p.rate_rule.name())?;
    Ok(d)
}

/// The mode of its name, `full` or `light` (the light mode's default correction period).
fn mode_of<T: Real>(mode: &str) -> Result<Mode<T>, RowError> {
    match mode.parse::<Mode<f64>>() {
        Ok(Mode::Full) => Ok(Mode::Full),
        Ok(_) => Ok(Mode::light()),
        Err(_) => Err(RowError::call(format!(
            "mode: unknown {mode:?} (full, light)"
        ))),
    }
}

/// The parameters in `T`: the defaults of `frame` and `mode` (`Params::defaults_of`) with the
/// parameter file's text (`gyrostat::estimation::params_text`), then the rate rule (`None`:
/// the file's, else the defaults'), fixed gains and `overrides` applied.
fn params<T: Real>(
    frame: EarthFrame,
    mode: Mode<T>,
    rate_rule: Option<RateRule>,
    heading_time_constant: Option<f64>,
    params_text: Option<&str>,
    overrides: &[(String, f64)],
) -> Result<Params<T>, RowError> {
    let mut p = Params::<T>::defaults_of(frame, mode);
    if let Some(text) = params_text {
        p.set_from_text(text)
            .map_err(|e| RowError::call(format!("params_file: {e}")))?;
    }
    if let Some(rule) = rate_rule {
        p.rate_rule = rule;
    }
    if let Some(tau) = heading_time_constant {
        p.gains = Gains::Fixed {
            heading_time_constant: T::from_f64(tau),
        };
    }
    for (name, v) in overrides {
        *p.flat_parameter_mut(name).ok_or_else(|| {
            RowError::call(format!(
                "unknown estimator parameter {name:?} (estimator_defaults() lists them)"
            ))
        })? = T::from_f64(*v);
    }
    Ok(p)
}

/// What `estimate` returns per sample, in f64.
struct Track {
    q: Vec<f64>,
    bias: Vec<f64>,
    accel_used: Vec<bool>,
    mag_used: Vec<bool>,
    at_rest: Vec<bool>,
    std: Vec<f64>,
    initialized: Vec<bool>,
    skipped: Vec<bool>,
}

fn run<T: Real + std::fmt::Debug>(
    params: Params<T>,
    t: &[f64],
    gyro: &[f64],
    accel: &[f64],
    mag: Option<&[f64]>,
    skip_errors: bool,
) -> Result<Track, RowError> {
    let options = Options {
        skip_bad_rows: skip_errors,
        ..Options::default()
    };
    let mut run = Run::try_new(params, options).map_err(|e| {
        RowError::call(format!(
            "estimator parameters: {e} (a noise, time or threshold is NaN, negative or zero)"
        ))
    })?;
    let n = t.len();
    let v = |a: &[f64], k: usize| [a[3 * k], a[3 * k + 1], a[3 * k + 2]];
    let mut tr = Track {
        q: Vec::with_capacity(4 * n),
        bias: Vec::with_capacity(3 * n),
        accel_used: Vec::with_capacity(n),
        mag_used: Vec::with_capacity(n),
        at_rest: Vec::with_capacity(n),
        std: Vec::with_capacity(2 * n),
        initialized: Vec::with_capacity(n),
        skipped: Vec::with_capacity(n),
    };
    for (k, &tk) in t.iter().enumerate() {
        let sample = Sample {
            t: tk,
            gyro: v(gyro, k),
            accel: v(accel, k),
            mag: mag.map(|m| v(m, k)),
        };
        match run.push(&sample) {
            Ok(Step::Updated(o)) => {
                tr.accel_used.push(o.accel == SensorUse::Used);
                tr.mag_used.push(o.mag == SensorUse::Used);
                tr.at_rest.push(o.at_rest);
                tr.skipped.push(false);
            }
            Ok(Step::Skipped) => {
                tr.accel_used.push(false);
                tr.mag_used.push(false);
                tr.at_rest.push(false);
                tr.skipped.push(true);
            }
            Err(RowError_::Rejected { error, dt }) => {
                return Err(RowError::at(
                    k,
                    format!(
                        "{error} (time step {dt:e} s from the time stamps; a step must be finite, \
                         > 0 and <= 1000 s, the gyroscope sample finite and turning less than \
                         half a turn in it)"
                    ),
                ));
            }
            Err(RowError_::NonFinite) => {
                return Err(RowError::at(
                    k,
                    format!(
                        "{} (a time stamp or gyroscope value; skip_errors=True makes such a \
                         sample a gap)",
                        gyrostat::Error::NonFinite
                    ),
                ));
            }
            Err(e) => {
                return Err(RowError::at(k, e.message(&format!("{tk:e}"))));
            }
        }
        let f = run.estimator();
        tr.q.extend(f.attitude().to_array().map(Real::to_f64));
        tr.bias.extend(f.bias().to_array().map(Real::to_f64));
        let (h, i) = f.attitude_std();
        tr.std.extend([h.to_f64(), i.to_f64()]);
        tr.initialized.push(f.is_initialized());
    }
    Ok(tr)
}

/// The estimator run over a record: time stamps `t` (s), gyroscope (rad/s), accelerometer
/// (m/s²) and optionally magnetometer (any unit) rows, sensor frame. Returns a dict of arrays:
/// `q` (sensor → earth, `w, x, y, z`), `bias` (rad/s), `accel_used`, `mag_used`, `at_rest`,
/// `attitude_std` (heading, inclination; rad), `initialized` (the attitude is initialised
/// after the sample), `skipped` (a bad sample skipped as a gap, `skip_errors`). `mode`: `full` or `light`
/// (`gyrostat::estimation::Mode`). `rate_rule`: `trapezoid`, `magnus4`, `cf4`
/// (`gyrostat::estimation::RateRule`), or `None` for the parameter file's or the defaults'.
#[pyfunction]
#[pyo3(signature = (t, gyro, accel, mag, frame, precision, mode, rate_rule, heading_time_constant, params_text, params, skip_errors))]
#[allow(clippy::too_many_arguments)]
fn estimate<'py>(
    py: Python<'py>,
    t: PyReadonlyArray1<'py, f64>,
    gyro: PyReadonlyArray2<'py, f64>,
    accel: PyReadonlyArray2<'py, f64>,
    mag: Option<PyReadonlyArray2<'py, f64>>,
    frame: &str,
    precision: &str,
    mode: &str,
    rate_rule: Option<&str>,
    heading_time_constant: Option<f64>,
    params_text: Option<String>,
    params: Vec<(String, f64)>,
    skip_errors: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let t = values(&t);
    let g = rows(&gyro, 3, "gyro")?;
    let a = rows(&accel, 3, "accel")?;
    let m = match &mag {
        Some(m) => Some(rows(m, 3, "mag")?),
        None => None,
    };
    let n = t.len();
    for (name, len) in [("gyro", g.len()), ("accel", a.len())]
        .into_iter()
        .chain(m.as_ref().map(|m| ("mag", m.len())))
    {
        if len != 3 * n {
            return Err(
                RowError::call(format!("{name}: {} rows for {n} time stamps", len / 3)).into(),
            );
        }
    }
    let frame: EarthFrame = frame
        .parse()
        .map_err(|_| RowError::call(format!("frame: unknown {frame:?} (enu, ned)")))?;
    let light = mode_of::<f64>(mode)? != Mode::Full;
    let rate_rule = match rate_rule {
        None => None,
        Some(name) => Some(name.parse::<RateRule>().map_err(|_| {
            let names: Vec<&str> = RateRule::ALL.iter().map(|r| r.name()).collect();
            RowError::call(format!(
                "rate_rule: unknown {name:?} ({})",
                names.join(", ")
            ))
        })?),
    };
    let tr = match precision {
        "f64" => {
            let p = self::params::<f64>(
                frame,
                if light { Mode::light() } else { Mode::Full },
                rate_rule,
                heading_time_constant,
                params_text.as_deref(),
                &params,
            )?;
            py.detach(|| run(p, &t, &g, &a, m.as_deref(), skip_errors))?
        }
        "f32" => {
            let p = self::params::<f32>(
                frame,
                if light { Mode::light() } else { Mode::Full },
                rate_rule,
                heading_time_constant,
                params_text.as_deref(),
                &params,
            )?;
            py.detach(|| run(p, &t, &g, &a, m.as_deref(), skip_errors))?
        }
        other => {
            return Err(RowError::call(format!("precision: unknown {other:?} (f64, f32)")).into());
        }
    };
    let d = PyDict::new(py);
    d.set_item("q", array2(py, tr.q, 4)?)?;
    d.set_item("bias", array2(py, tr.bias, 3)?)?;
    d.set_item("accel_used", PyArray1::from_vec(py, tr.accel_used))?;
    d.set_item("mag_used", PyArray1::from_vec(py, tr.mag_used))?;
    d.set_item("at_rest", PyArray1::from_vec(py, tr.at_rest))?;
    d.set_item("attitude_std", array2(py, tr.std, 2)?)?;
    d.set_item("initialized", PyArray1::from_vec(py, tr.initialized))?;
    d.set_item("skipped", PyArray1::from_vec(py, tr.skipped))?;
    Ok(d)
}
