//! Research probe: the online hard-iron fit over a log (`synthesize`'s CSV or a BROAD trial,
//! `.csv.gz`), default parameters with `NAME=VALUE` changes, printed every `STEP` seconds
//! (environment variable, default 1) keeping every `EVERY`th row (default 1): the offset subtracted,
//! the fit's estimate and standard deviations (µT), its mean normalised innovation squared,
//! its measured noise and whether it offers the offset.
//!
//! ```text
//! cargo run --release -p host-tests --bin hard_iron_probe -- LOG [NAME=VALUE]...
//! ```
use gyrostat::Vec3;
use gyrostat::estimation::{Estimator, Params};
use host_tests::broad::set_param;
fn main() {
    let mut a = std::env::args().skip(1);
    let path = a.next().unwrap();
    let mut p = Params::<f64>::default();
    for s in a {
        let (n, v) = s.split_once('=').unwrap();
        set_param(&mut p, n, v).unwrap();
    }
    type R = (f64, [f64; 3], [f64; 3], Option<[f64; 3]>);
    let rows: Vec<R> = if path.ends_with(".gz") {
        let log =
            host_tests::broad::open_log(std::path::Path::new(&path), host_tests::broad::Units::SI)
                .unwrap();
        log.rows
            .iter()
            .map(|r| (r.t, r.gyro, r.accel, r.mag))
            .collect()
    } else {
        let text = std::fs::read_to_string(&path).unwrap();
        text.lines()
            .skip(1)
            .map(|line| {
                let c: Vec<&str> = line.split(',').collect();
                let n = |i: usize| c[i].parse::<f64>().unwrap();
                (
                    n(0),
                    [n(1), n(2), n(3)],
                    [n(4), n(5), n(6)],
                    (!c[7].is_empty()).then(|| [n(7), n(8), n(9)]),
                )
            })
            .collect()
    };
    let every: usize = std::env::var("EVERY")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    let rows: Vec<R> = rows.into_iter().step_by(every).collect();
    let step: f64 = std::env::var("STEP")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1.0);
    let mut f = Estimator::try_new(p).unwrap();
    let mut prev: Option<f64> = None;
    let mut next = 0.0;
    for &(t, g, a, m) in &rows {
        let dt = prev.map_or(f64::NAN, |p| t - p);
        prev = Some(t);
        let v = |x: [f64; 3]| Vec3::new(x[0], x[1], x[2]);
        let _ = f.update(v(g), v(a), m.map(v), dt);
        if t >= next {
            next = t + step;
            let (ap, fit) = f.hard_iron();
            let (h, sd) = fit.estimate();
            println!(
                "{:5.1} applied {:6.2} {:6.2} {:6.2} | est {:7.2} {:7.2} {:7.2} sd {:6.2} {:6.2} {:6.2} nis {:8.2} r {:.4} ok {}",
                t,
                ap.x,
                ap.y,
                ap.z,
                h.x,
                h.y,
                h.z,
                sd.x,
                sd.y,
                sd.z,
                fit.consistency(),
                fit.noise(),
                fit.offset().is_some()
            );
        }
    }
}
