//! Synthetic IMU logs: the `synthesize` tool's logs as arrays (one definition,
//! `gyrostat_tools::synthesis`).

use numpy::{PyArray1, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use gyrostat_tools::motion::MotionFile;
use gyrostat_tools::sensor_spec;
use gyrostat_tools::synthesis::{MotionChoice, Options, RunError};

use crate::{RowError, array2, rows, values};

pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(synthesize, m)?)?;
    m.add_function(wrap_pyfunction!(sensor_text, m)?)?;
    Ok(())
}

/// `--flag-name` in a message of the shared code as the keyword `flag_name`.
fn keywords(msg: &str) -> String {
    let mut out = String::with_capacity(msg.len());
    let mut rest = msg;
    while let Some(i) = rest.find("--") {
        out.push_str(&rest[..i]);
        let name = &rest[i + 2..];
        let end = name
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '-'))
            .unwrap_or(name.len());
        out.push_str(&name[..end].replace('-', "_"));
        rest = &name[end..];
    }
    out.push_str(rest);
    out
}

/// The text of a sensor preset or spec file (`synthesize --print-sensor`).
#[pyfunction]
fn sensor_text(sensor: &str) -> PyResult<String> {
    let (_, text) = sensor_spec::read("sensor", sensor).map_err(RowError::call)?;
    Ok(text)
}

/// One synthetic log (the Python wrapper documents the keywords): a dict of arrays.
#[pyfunction]
#[pyo3(signature = (*, motion="handheld".to_string(), motion_t=None, motion_q=None,
    motion_omega=None, sensor="ideal".to_string(), rate=None, duration=None, rest=None,
    phases=None, ramp=None, q0=None, translation=None, vibration=None, taps=None,
    magnet_pass=None, magnet_fixed=None, steel=None, seed=0))]
#[allow(clippy::too_many_arguments)]
fn synthesize<'py>(
    py: Python<'py>,
    motion: String,
    motion_t: Option<PyReadonlyArray1<'py, f64>>,
    motion_q: Option<PyReadonlyArray2<'py, f64>>,
    motion_omega: Option<PyReadonlyArray2<'py, f64>>,
    sensor: String,
    rate: Option<f64>,
    duration: Option<f64>,
    rest: Option<f64>,
    phases: Option<i64>,
    ramp: Option<f64>,
    q0: Option<[f64; 4]>,
    translation: Option<f64>,
    vibration: Option<[f64; 2]>,
    taps: Option<f64>,
    magnet_pass: Option<[f64; 3]>,
    magnet_fixed: Option<Vec<f64>>,
    steel: Option<[f64; 3]>,
    seed: u64,
) -> PyResult<Bound<'py, PyDict>> {
    let call = |m: String| RowError::call(keywords(&m));
    let motion = match (motion.as_str(), motion_t, motion_q, motion_omega) {
        ("rows", Some(t), Some(q), Some(w)) => {
            let t = values(&t);
            let q = rows(&q, 4, "motion_q")?;
            let w = rows(&w, 3, "motion_omega")?;
            let q: Vec<[f64; 4]> = q
                .chunks_exact(4)
                .map(|r| [r[0], r[1], r[2], r[3]])
                .collect();
            let w: Vec<[f64; 3]> = w.chunks_exact(3).map(|r| [r[0], r[1], r[2]]).collect();
            MotionChoice::File(
                MotionFile::try_new(&t, &q, w).map_err(|(row, e)| match row {
                    Some(r) => RowError::at(r, e),
                    None => RowError::call(format!("motion: {e}")),
                })?,
            )
        }
        ("rows", ..) => {
            return Err(
                RowError::call("motion='rows' needs motion_t, motion_q and motion_omega").into(),
            );
        }
        (_, None, None, None) => match MotionChoice::named(&motion).ok_or(motion.as_str()) {
            Ok(named) => named,
            Err(other) => {
                let w = other
                    .strip_prefix("spin:")
                    .map(|v| {
                        v.split(',')
                            .map(|x| x.trim().parse::<f64>())
                            .collect::<Result<Vec<f64>, _>>()
                    })
                    .and_then(Result::ok)
                    .filter(|v| v.len() == 3)
                    .ok_or_else(|| {
                        RowError::call(format!(
                            "motion: handheld, axes, rest, spin:WX,WY,WZ or rows, got {other:?}"
                        ))
                    })?;
                MotionChoice::Spin([w[0], w[1], w[2]])
            }
        },
        _ => {
            return Err(
                RowError::call("motion_t, motion_q, motion_omega need motion='rows'").into(),
            );
        }
    };
    let (spec, _) = sensor_spec::read("--sensor", &sensor).map_err(call)?;
    let phases = match phases {
        Some(n) if n < 0 => {
            return Err(RowError::call(format!("phases: must be >= 0, got {n}")).into());
        }
        n => n.map(|n| n as u64),
    };
    let synth = Options {
        motion,
        sensor: spec,
        rate,
        duration,
        rest,
        phases,
        ramp,
        q0,
        translation,
        vibration,
        taps,
        magnet_pass,
        magnet_fixed,
        steel,
        seed,
    }
    .build()
    .map_err(call)?;
    #[derive(Default)]
    struct Cols {
        t: Vec<f64>,
        t_true: Vec<f64>,
        gyr: Vec<f64>,
        acc: Vec<f64>,
        mag: Vec<f64>,
        q: Vec<f64>,
        movement: Vec<bool>,
        rate: Vec<f64>,
        pos: Vec<f64>,
        lin_acc: Vec<f64>,
        body_acc: Vec<f64>,
    }
    let c = py.detach(|| {
        let mut c = Cols::default();
        synth
            .run(|s| -> Result<(), ()> {
                c.t.push(s.stamp);
                c.t_true.push(s.t);
                c.gyr.extend(s.gyr);
                c.acc.extend(s.acc);
                c.mag.extend(s.mag.unwrap_or([f64::NAN; 3]));
                c.q.extend(s.q);
                c.movement.push(s.moving);
                c.rate.extend(s.kin.w);
                c.pos.extend(s.kin.p);
                c.lin_acc.extend(s.kin.a);
                c.body_acc.extend(s.kin.a_body);
                Ok(())
            })
            .map(|()| c)
    });
    let c = match c {
        Ok(c) => c,
        Err(RunError::Noise(e)) => return Err(RowError::call(format!("sensor: {e}")).into()),
        Err(RunError::Sink(())) => return Err(RowError::call("internal error").into()),
    };
    let d = PyDict::new(py);
    d.set_item("t", PyArray1::from_vec(py, c.t))?;
    d.set_item("t_true", PyArray1::from_vec(py, c.t_true))?;
    d.set_item("gyr", array2(py, c.gyr, 3)?)?;
    d.set_item("acc", array2(py, c.acc, 3)?)?;
    d.set_item("mag", array2(py, c.mag, 3)?)?;
    d.set_item("q", array2(py, c.q, 4)?)?;
    d.set_item("movement", PyArray1::from_vec(py, c.movement))?;
    d.set_item("rate", array2(py, c.rate, 3)?)?;
    d.set_item("pos", array2(py, c.pos, 3)?)?;
    d.set_item("lin_acc", array2(py, c.lin_acc, 3)?)?;
    d.set_item("body_acc", array2(py, c.body_acc, 3)?)?;
    Ok(d)
}
