//! The gyrostat simulation: the scenarios of the `simulate` tool (one definition,
//! `gyrostat_tools::simulation`), the rows of its CSV as arrays.

use numpy::{PyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use gyrostat::Real;
use gyrostat::dynamics::State;
use gyrostat_tools::simulation::{
    self, Config, Fail, Outcome, Spec, TorqueSchedule, WheelSpec, setup, widen,
};
use gyrostat_tools::torque::Schedule;
use gyrostat_tools::with_wheels;

use crate::{RowError, array2, rows};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(default_scenario, m)?)?;
    Ok(())
}

/// `--flag-name` in a message of the shared scenario code as the keyword `flag_name`.
fn keywords(msg: &str) -> String {
    let mut out = String::with_capacity(msg.len());
    let mut rest = msg;
    while let Some(i) = rest.find("--") {
        out.push_str(&rest[..i]);
        let name = &rest[i + 2..];
        let end = name
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '-'))
            .unwrap_or(name.len());
        let word = &name[..end];
        out.push_str(&match word {
            // The flags whose keywords differ in more than the dashes.
            "torque-file" => "torque_schedule".to_string(),
            w => w.replace('-', "_"),
        });
        rest = &name[end..];
    }
    out.push_str(rest);
    out
}

/// The rows of a run, as the CSV of `simulate` holds them (widened to f64 exactly).
#[derive(Default)]
struct Rows {
    t: Vec<f64>,
    q: Vec<f64>,
    omega: Vec<f64>,
    momentum: Vec<f64>,
    energy: Vec<f64>,
    wheels: Vec<f64>,
    n_wheels: usize,
    /// The error that stopped the run (the rows before it are kept).
    error: Option<String>,
    outcome: Option<Outcome>,
}

fn run<T: Real, const N: usize>(cfg: &Config) -> Result<Rows, String> {
    let sim = setup::<T, N>(cfg)?;
    let mut r = Rows {
        n_wheels: N,
        ..Rows::default()
    };
    let result = sim.run(cfg, |k, s: &State<T, N>, _| -> Result<(), ()> {
        if k % cfg.every != 0 {
            return Ok(());
        }
        let t = T::from_f64(k as f64 * cfg.dt);
        r.t.push(t.to_f64());
        r.q.extend(widen(sim.attitude_at(s, t)).to_array());
        r.omega.extend(simulation::f3(sim.omega(s)));
        r.momentum.extend(simulation::f3(s.momentum));
        r.energy.push(sim.energy(s).to_f64());
        r.wheels.extend(s.wheel_speeds.iter().map(|w| w.to_f64()));
        Ok(())
    });
    match result {
        Ok(o) => r.outcome = Some(o),
        Err(Fail::Msg(m)) => r.error = Some(m),
        Err(Fail::Sink(())) => {}
    }
    Ok(r)
}

/// One run of the `simulate` scenario the keywords describe (the Python wrapper documents them);
/// a dict of arrays and the monitors. A step the library rejects ends the run: then `error`
/// holds the reason and the arrays the rows before it.
#[pyfunction]
#[pyo3(signature = (*, inertia=None, inertia_offdiag=None, omega=None, momentum=None, spin=None,
    quartic=None, semi_rigid=None, q0=None, wheels=Vec::new(), wheel_torque=None,
    wheel_speed=None, torque=None, torque_schedule=None, dt=None, steps=None, every=None,
    integrator=None, f32=false, compensated=false))]
#[allow(clippy::too_many_arguments)]
fn simulate<'py>(
    py: Python<'py>,
    inertia: Option<[f64; 3]>,
    inertia_offdiag: Option<[f64; 3]>,
    omega: Option<[f64; 3]>,
    momentum: Option<[f64; 3]>,
    spin: Option<[f64; 3]>,
    quartic: Option<(String, f64)>,
    semi_rigid: Option<(String, f64, f64, f64)>,
    q0: Option<[f64; 4]>,
    wheels: Vec<Vec<f64>>,
    wheel_torque: Option<Vec<f64>>,
    wheel_speed: Option<Vec<f64>>,
    torque: Option<[f64; 3]>,
    torque_schedule: Option<PyReadonlyArray2<'py, f64>>,
    dt: Option<f64>,
    steps: Option<i64>,
    every: Option<i64>,
    integrator: Option<String>,
    f32: bool,
    compensated: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let call = |m: String| RowError::call(keywords(&m));
    let finite = |name: &str, v: &[f64]| {
        if v.iter().all(|x| x.is_finite()) {
            Ok(())
        } else {
            Err(RowError::call(format!(
                "{name}: every number must be finite"
            )))
        }
    };
    for (name, v) in [
        ("inertia", inertia.as_ref().map(|v| &v[..])),
        ("inertia_offdiag", inertia_offdiag.as_ref().map(|v| &v[..])),
        ("omega", omega.as_ref().map(|v| &v[..])),
        ("momentum", momentum.as_ref().map(|v| &v[..])),
        ("spin", spin.as_ref().map(|v| &v[..])),
        ("q0", q0.as_ref().map(|v| &v[..])),
        ("wheel_torque", wheel_torque.as_deref()),
        ("wheel_speed", wheel_speed.as_deref()),
        ("torque", torque.as_ref().map(|v| &v[..])),
    ] {
        if let Some(v) = v {
            finite(name, v)?;
        }
    }
    let dt = match dt {
        Some(h) if !(h.is_finite() && h > 0.0) => {
            return Err(call(format!("--dt: must be finite and > 0, got {h}")).into());
        }
        h => h,
    };
    let count = |name: &str, v: Option<i64>, min: i64| match v {
        Some(n) if n < min => Err(RowError::call(format!("{name}: must be >= {min}, got {n}"))),
        Some(n) => Ok(Some(n as u64)),
        None => Ok(None),
    };
    let steps = count("steps", steps, 0)?;
    let every = count("every", every, 1)?;
    let quartic = quartic
        .map(|(kind, t)| {
            finite("quartic", &[t])?;
            simulation::quartic("--quartic", &kind, t).map_err(call)
        })
        .transpose()?;
    let semi_rigid = semi_rigid
        .map(|(kind, m, wv, r0)| simulation::semi_rigid("--semi-rigid", &kind, [m, wv, r0]))
        .transpose()
        .map_err(call)?;
    let wheels = wheels
        .iter()
        .enumerate()
        .map(|(i, w)| WheelSpec::try_new(i + 1, w))
        .collect::<Result<Vec<_>, _>>()
        .map_err(call)?;
    let method = integrator
        .map(|name| simulation::integrator("--integrator", &name))
        .transpose()
        .map_err(call)?;
    let torque_schedule = match torque_schedule {
        None => None,
        Some(a) => {
            let flat = rows(&a, 4, "torque_schedule")?;
            let times = flat.chunks_exact(4).map(|r| r[0]).collect();
            let torques = flat.chunks_exact(4).map(|r| [r[1], r[2], r[3]]).collect();
            let s = Schedule::try_new(times, torques)
                .map_err(|e| RowError::call(format!("torque_schedule: {e}")))?;
            Some(TorqueSchedule::Rows(s))
        }
    };
    let cfg = Spec {
        inertia,
        inertia_offdiag,
        omega,
        momentum,
        spin,
        quartic,
        semi_rigid,
        q0,
        wheels,
        wheel_torque,
        wheel_speed,
        torque,
        torque_schedule,
        dt,
        steps,
        every,
        method,
        f32,
        compensated,
    }
    .try_into_config()
    .map_err(call)?;
    let r = py
        .detach(|| {
            if cfg.f32 {
                with_wheels!(cfg.wheels.len(), run::<f32>(&cfg))
            } else {
                with_wheels!(cfg.wheels.len(), run::<f64>(&cfg))
            }
        })
        .map_err(call)?;
    let d = PyDict::new(py);
    d.set_item("t", PyArray1::from_vec(py, r.t))?;
    d.set_item("q", array2(py, r.q, 4)?)?;
    d.set_item("omega", array2(py, r.omega, 3)?)?;
    d.set_item("momentum", array2(py, r.momentum, 3)?)?;
    d.set_item("energy", PyArray1::from_vec(py, r.energy))?;
    let rows_done = d.get_item("t")?.map_or(Ok(0), |t| t.len())?;
    let wheel_rows = if r.n_wheels == 0 {
        numpy::PyArray2::<f64>::zeros(py, [rows_done, 0], false)
    } else {
        array2(py, r.wheels, r.n_wheels)?
    };
    d.set_item("wheel_speeds", wheel_rows)?;
    d.set_item("error", r.error.map(|m| keywords(&m)))?;
    let integ = cfg.method.name();
    d.set_item("integrator", integ)?;
    if let Some(o) = r.outcome {
        let m = PyDict::new(py);
        m.set_item("lab_momentum_start", o.lab0)?;
        m.set_item("lab_momentum_end", o.lab_end)?;
        m.set_item("lab_impulse", o.impulse.lab)?;
        m.set_item("impulse_magnitude", o.impulse.magnitude)?;
        m.set_item("lab_momentum_drift_max", o.lab_drift_max)?;
        m.set_item("momentum_norm_drift_max", o.norm_drift_max)?;
        m.set_item("energy_start", o.energy0)?;
        m.set_item("energy_end", o.energy_end)?;
        d.set_item("monitors", m)?;
    } else {
        d.set_item("monitors", py.None())?;
    }
    Ok(d)
}

/// The built-in scenario of `simulate` (no arguments): the intermediate-axis flip in f32 and
/// f64 and the closed form.
#[pyfunction]
fn default_scenario(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let s = py
        .detach(simulation::default_scenario)
        .map_err(RowError::call)?;
    let (dt, steps, every) = s.run;
    let d = PyDict::new(py);
    d.set_item("dt", dt)?;
    d.set_item("steps", steps)?;
    d.set_item("every", every)?;
    d.set_item("inertia", simulation::DEFAULT_MOMENTS)?;
    d.set_item("omega0", simulation::DEFAULT_OMEGA0)?;
    d.set_item("integrator", simulation::DEFAULT_INTEGRATOR.name())?;
    let t: Vec<f64> = (1..=steps / every)
        .map(|k| (k * every) as f64 * dt)
        .collect();
    d.set_item("t", PyArray1::from_vec(py, t))?;
    d.set_item("flip_interval_closed_form", s.flip_interval)?;
    let flat = |q: &[gyrostat::UnitQuat<f64>]| q.iter().flat_map(|q| q.to_array()).collect();
    d.set_item("q_exact", array2(py, flat(&s.exact), 4)?)?;
    for (name, r) in [
        ("f32", &s.f32),
        ("f32_compensated", &s.f32_compensated),
        ("f64", &s.f64),
    ] {
        let run = PyDict::new(py);
        run.set_item("flips", PyArray1::from_vec(py, r.flips.clone()))?;
        run.set_item(
            "flip_interval",
            simulation::mean_interval(&r.flips).map_or(f64::NAN, |x| x),
        )?;
        run.set_item("energy_drift_max", r.energy_drift)?;
        run.set_item("momentum_norm_drift_max", r.norm_drift)?;
        run.set_item("lab_momentum_drift_max", r.lab_drift)?;
        run.set_item(
            "attitude_error_max_deg",
            simulation::max_angle_deg(&r.attitudes, &s.exact),
        )?;
        run.set_item("q", array2(py, flat(&r.attitudes), 4)?)?;
        let f = |v: &[[f64; 3]]| v.iter().flatten().copied().collect();
        run.set_item("omega", array2(py, f(&r.rates), 3)?)?;
        run.set_item("momentum", array2(py, f(&r.momenta), 3)?)?;
        run.set_item("drift", array2(py, f(&r.drifts), 3)?)?;
        d.set_item(name, run)?;
    }
    Ok(d)
}
