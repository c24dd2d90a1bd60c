//! The SVG figure of a run: time histories on the left, the polhode on the angular-momentum
//! sphere on the right (plotters, SVG backend).
//!
//! The polhode panel is the seed's Fig. 6.8.1(c) seen from outside: the unit sphere of
//! directions `Ĵ = J/|J|` in the principal frame, the constant-energy curves where the
//! rotational energy surface (6.8.7) crosses the sphere (equivalently, the constant-energy
//! ellipsoid (6.8.8) meets the constant-`|J|` sphere), the two separatrix great circles through
//! the saddle points on the intermediate axis at azimuth `±γ_B` (6.8.9)–(6.8.10), and the
//! body-frame `Ĵ(t)` of the run. Orthographic projection; the far hemisphere is drawn faint.

use std::path::Path;

use gyrostat::Vec3;
use gyrostat::dynamics::Inertia;
use gyrostat::dynamics::closed_form::analysis::separatrix_angle;
use gyrostat_tools::plot::{COLORS, err};
use plotters::coord::Shift;
use plotters::prelude::*;

/// One curve of a time-history panel, sampled at [`Figure::t`].
pub struct Series {
    /// Legend text.
    pub label: String,
    /// Values, one per time sample.
    pub y: Vec<f64>,
}

impl Series {
    /// A series from a label and values.
    pub fn new(label: impl Into<String>, y: Vec<f64>) -> Self {
        Self {
            label: label.into(),
            y,
        }
    }
}

/// Everything the figure shows.
pub struct Figure {
    /// The title line.
    pub title: String,
    /// Sample times (s).
    pub t: Vec<f64>,
    /// Body rates `ω₁, ω₂, ω₃` (rad/s) per sample.
    pub rates: Vec<[f64; 3]>,
    /// Relative drifts or changes of conserved quantities (log scale; exact zeros break the
    /// curve).
    pub drift: Vec<Series>,
    /// Attitude error (degrees, log scale) against a reference, with the panel caption.
    pub attitude: Option<(String, Vec<Series>)>,
    /// Wheel speeds (rad/s), one series per wheel.
    pub wheels: Vec<Series>,
    /// Body-frame total angular momentum per sample (for the polhode).
    pub momentum: Vec<[f64; 3]>,
    /// The body's inertia (wheels locked): the energy curves and separatrices are the rigid
    /// rotor's.
    pub inertia: Inertia<f64>,
    /// A note under the polhode (what the curves mean for this body), if any.
    pub polhode_note: Option<String>,
}

/// The smallest value drawn on a log axis, below f64's unit roundoff (exact zeros are not drawn:
/// the curve breaks there).
const LOG_FLOOR: f64 = 1e-17;

const WIDTH: u32 = 1500;
const HEIGHT: u32 = 900;
const LEFT: u32 = 900;

/// Polhode colours: front hemisphere, far hemisphere.
const ENERGY_CURVE: (RGBColor, RGBColor) = (RGBColor(120, 120, 120), RGBColor(222, 222, 222));
const SEPARATRIX: (RGBColor, RGBColor) = (RGBColor(200, 30, 30), RGBColor(245, 190, 190));
const TRAJECTORY: (RGBColor, RGBColor) = (RGBColor(20, 90, 200), RGBColor(170, 195, 235));

/// Writes the figure to `path` as SVG.
pub fn write_svg(path: &Path, fig: &Figure) -> Result<(), String> {
    let root = SVGBackend::new(path, (WIDTH, HEIGHT)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let root = root.titled(&fig.title, ("sans-serif", 20)).map_err(err)?;
    let (left, right) = root.split_horizontally(LEFT);
    let n = 2 + usize::from(fig.attitude.is_some()) + usize::from(!fig.wheels.is_empty());
    let panels = left.split_evenly((n, 1));
    let mut panel = panels.iter();
    let rates: Vec<Series> = (0..3)
        .map(|i| {
            Series::new(
                format!("w{}", i + 1),
                fig.rates.iter().map(|w| w[i]).collect(),
            )
        })
        .collect();
    linear_panel(panel.next().unwrap(), "body rates", "rad/s", &fig.t, &rates)?;
    log_panel(
        panel.next().unwrap(),
        "conserved quantities: relative drift (log scale; exact zeros not drawn)",
        "relative",
        &fig.t,
        &fig.drift,
    )?;
    if let Some((caption, series)) = &fig.attitude {
        log_panel(panel.next().unwrap(), caption, "degrees", &fig.t, series)?;
    }
    if !fig.wheels.is_empty() {
        linear_panel(
            panel.next().unwrap(),
            "wheel speeds (relative to the body)",
            "rad/s",
            &fig.t,
            &fig.wheels,
        )?;
    }
    polhode(&right, fig)?;
    root.present().map_err(err)
}

fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if !lo.is_finite() {
        return (-1.0, 1.0);
    }
    let pad = 0.05 * (hi - lo).max(1e-12 * lo.abs().max(1.0));
    (lo - pad, hi + pad)
}

fn t_range(t: &[f64]) -> std::ops::Range<f64> {
    let end = t.last().copied().unwrap_or(1.0);
    0.0..if end > 0.0 { end } else { 1.0 }
}

fn linear_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    caption: &str,
    unit: &str,
    t: &[f64],
    series: &[Series],
) -> Result<(), String> {
    let (lo, hi) = range(series.iter().flat_map(|s| s.y.iter().copied()));
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 16))
        .margin(8)
        .x_label_area_size(28)
        .y_label_area_size(70)
        .build_cartesian_2d(t_range(t), lo..hi)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("t (s)")
        .y_desc(unit)
        .light_line_style(WHITE)
        .draw()
        .map_err(err)?;
    for (i, s) in series.iter().enumerate() {
        let color = COLORS[i % COLORS.len()];
        chart
            .draw_series(LineSeries::new(
                t.iter().copied().zip(s.y.iter().copied()),
                color.stroke_width(1),
            ))
            .map_err(err)?
            .label(s.label.as_str())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(err)
}

fn log_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    caption: &str,
    unit: &str,
    t: &[f64],
    series: &[Series],
) -> Result<(), String> {
    let floor = |v: f64| v.max(LOG_FLOOR);
    let hi = series
        .iter()
        .flat_map(|s| s.y.iter().copied())
        .fold(LOG_FLOOR, f64::max);
    let lo = series
        .iter()
        .flat_map(|s| s.y.iter().copied())
        .filter(|&v| v > 0.0)
        .map(floor)
        .fold(hi, f64::min);
    // At least two decades, so the axis has labels.
    let (lo, hi) = (lo.min(hi / 100.0) / 2.0, hi * 2.0);
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 16))
        .margin(8)
        .x_label_area_size(28)
        .y_label_area_size(70)
        .build_cartesian_2d(t_range(t), (lo..hi).log_scale())
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("t (s)")
        .y_desc(unit)
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .light_line_style(WHITE)
        .draw()
        .map_err(err)?;
    for (i, s) in series.iter().enumerate() {
        let color = COLORS[i % COLORS.len()];
        // A log axis cannot show zero: the curve breaks where a value is exactly zero (a
        // quantity conserved to the last bit at that sample).
        let mut runs: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
        for (&t, &v) in t.iter().zip(&s.y) {
            if v > 0.0 {
                runs.last_mut().unwrap().push((t, floor(v)));
            } else if !runs.last().unwrap().is_empty() {
                runs.push(Vec::new());
            }
        }
        let mut labelled = false;
        for run in runs.into_iter().filter(|r| !r.is_empty()) {
            let drawn = chart
                .draw_series(LineSeries::new(run, color.stroke_width(1)))
                .map_err(err)?;
            if !labelled {
                labelled = true;
                drawn
                    .label(s.label.as_str())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color));
            }
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(err)
}

// ---------------------------------------------------------------------------------------------
// The polhode on the momentum sphere

type P3 = [f64; 3];

fn dot(a: P3, b: P3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn unit(a: P3) -> P3 {
    let n = dot(a, a).sqrt();
    [a[0] / n, a[1] / n, a[2] / n]
}

fn cross(a: P3, b: P3) -> P3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// An orthographic view of the unit sphere: the direction towards the viewer and the screen
/// axes, all in principal coordinates.
struct View {
    toward: P3,
    right: P3,
    up: P3,
}

impl View {
    fn new() -> Self {
        // Looking from the first octant, mostly along principal axis 2, axis 3 up: the saddle at
        // +axis 2 (where the separatrices cross) faces the viewer, +axis 1 to the left.
        let toward = unit([0.5, 1.0, 0.42]);
        let z = [0.0, 0.0, 1.0];
        let d = dot(z, toward);
        let up = unit([
            z[0] - d * toward[0],
            z[1] - d * toward[1],
            z[2] - d * toward[2],
        ]);
        let right = cross(up, toward);
        Self { toward, right, up }
    }

    fn screen(&self, p: P3) -> (f64, f64) {
        (dot(p, self.right), dot(p, self.up))
    }

    fn front(&self, p: P3) -> bool {
        dot(p, self.toward) >= 0.0
    }
}

/// Splits a curve on the sphere into runs on the near and far hemispheres: `(front?, points)`.
fn split_by_side(view: &View, curve: &[P3]) -> Vec<(bool, Vec<(f64, f64)>)> {
    let mut runs: Vec<(bool, Vec<(f64, f64)>)> = Vec::new();
    for &p in curve {
        let side = view.front(p);
        let s = view.screen(p);
        match runs.last_mut() {
            Some((f, pts)) if *f == side => pts.push(s),
            Some((_, pts)) => {
                // Continue the new run from the last point so the curve has no gap.
                let last = *pts.last().unwrap();
                runs.push((side, vec![last, s]));
            }
            None => runs.push((side, vec![s])),
        }
    }
    runs
}

/// Constant-energy curves of the rigid rotor on the unit sphere, in principal coordinates.
///
/// On `|Ĵ| = 1` the energy (6.8.7) is `2E/J² = ε = Σ Ĵᵢ²/Iᵢ`. With `a, b, c` the axes of the
/// largest, middle and smallest moment, a level `1/I_a < ε < 1/I_b` circles the `±a` poles: from
/// `Ĵ_a² = 1 − Ĵ_b² − Ĵ_c²`, `Ĵ_b²(1/I_b − 1/I_a) + Ĵ_c²(1/I_c − 1/I_a) = ε − 1/I_a`, an ellipse
/// in `(Ĵ_b, Ĵ_c)` lifted to both caps; a level `1/I_b < ε < 1/I_c` circles `±c` likewise.
fn energy_curves(moments: P3) -> Vec<Vec<P3>> {
    let mut idx = [0usize, 1, 2];
    idx.sort_by(|&i, &j| moments[j].total_cmp(&moments[i]));
    let [a, b, c] = idx;
    let inv = moments.map(|m| 1.0 / m);
    let mut curves = Vec::new();
    // Distinct moments only (a symmetric axis pair has no curves about it).
    let distinct = |x: f64, y: f64| (x - y).abs() > 1e-9 * x.abs().max(y.abs());
    let levels = [0.12, 0.3, 0.5, 0.7, 0.88];
    let mut lift = |pole: usize, r: [(usize, f64); 2]| {
        for sign in [1.0, -1.0] {
            let curve: Vec<P3> = (0..=180)
                .map(|k| {
                    let phi = k as f64 * std::f64::consts::TAU / 180.0;
                    let mut p = [0.0; 3];
                    p[r[0].0] = r[0].1 * phi.cos();
                    p[r[1].0] = r[1].1 * phi.sin();
                    let rest = 1.0 - p[r[0].0].powi(2) - p[r[1].0].powi(2);
                    p[pole] = sign * rest.max(0.0).sqrt();
                    p
                })
                .collect();
            curves.push(curve);
        }
    };
    if distinct(inv[a], inv[b]) {
        for f in levels {
            let e = f * (inv[b] - inv[a]); // ε − 1/I_a
            lift(
                a,
                [
                    (b, (e / (inv[b] - inv[a])).sqrt()),
                    (c, (e / (inv[c] - inv[a])).sqrt()),
                ],
            );
        }
    }
    if distinct(inv[b], inv[c]) {
        for f in levels {
            let e = f * (inv[c] - inv[b]); // 1/I_c − ε
            lift(
                c,
                [
                    (b, (e / (inv[c] - inv[b])).sqrt()),
                    (a, (e / (inv[c] - inv[a])).sqrt()),
                ],
            );
        }
    }
    curves
}

/// The separatrices: the great circles through the intermediate axis `±b` in the planes at
/// azimuth `±γ_B` about it, measured from the smallest-moment axis `c` towards the largest `a`
/// (6.8.10, `γ_B` from the library's [`separatrix_angle`]). `None` for a symmetric body.
fn separatrices(moments: P3) -> Option<(f64, Vec<Vec<P3>>)> {
    let mut idx = [0usize, 1, 2];
    idx.sort_by(|&i, &j| moments[j].total_cmp(&moments[i]));
    let [a, b, c] = idx;
    let ordered =
        Inertia::try_from_principal(Vec3::new(moments[a], moments[b], moments[c])).ok()?;
    let gamma = separatrix_angle(&ordered).ok()?;
    let circles = [gamma, -gamma]
        .iter()
        .map(|&g| {
            (0..=360)
                .map(|k| {
                    let s = k as f64 * std::f64::consts::TAU / 360.0;
                    let mut p = [0.0; 3];
                    p[b] = s.cos();
                    p[c] = s.sin() * g.cos();
                    p[a] = s.sin() * g.sin();
                    p
                })
                .collect()
        })
        .collect();
    Some((gamma, circles))
}

fn polhode<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, fig: &Figure) -> Result<(), String> {
    let (sphere_area, notes) = area.split_vertically(HEIGHT.min(WIDTH - LEFT) - 10);
    let moments = fig.inertia.principal_moments().to_array();
    let axes = fig.inertia.principal_axes().m; // columns: principal axes in body coordinates
    let view = View::new();
    let mut chart = ChartBuilder::on(&sphere_area)
        .caption(
            "polhode: J/|J| on the angular-momentum sphere",
            ("sans-serif", 16),
        )
        .margin(10)
        .build_cartesian_2d(-1.3f64..1.3, -1.3f64..1.3)
        .map_err(err)?;
    let outline: Vec<(f64, f64)> = (0..=360)
        .map(|k| {
            let a = k as f64 * std::f64::consts::TAU / 360.0;
            (a.cos(), a.sin())
        })
        .collect();
    chart
        .draw_series(LineSeries::new(outline, BLACK.stroke_width(1)))
        .map_err(err)?;
    // Far-side runs are drawn faint and thin.
    let mut draw = |curve: &[P3], (front, back): (RGBColor, RGBColor), width: u32| {
        for (is_front, pts) in split_by_side(&view, curve) {
            let style = if is_front {
                front.stroke_width(width)
            } else {
                back.stroke_width(1)
            };
            chart
                .draw_series(LineSeries::new(pts, style))
                .map_err(err)?;
        }
        Ok::<(), String>(())
    };
    for curve in energy_curves(moments) {
        draw(&curve, ENERGY_CURVE, 1)?;
    }
    let sep = separatrices(moments);
    if let Some((_, circles)) = &sep {
        for c in circles {
            draw(c, SEPARATRIX, 3)?;
        }
    }
    // The run's body-frame direction of J in principal coordinates: p_i = (column i) · Ĵ.
    let track: Vec<P3> = fig
        .momentum
        .iter()
        .filter_map(|j| {
            let n = dot(*j, *j).sqrt();
            (n > 0.0).then(|| {
                let u = [j[0] / n, j[1] / n, j[2] / n];
                [0, 1, 2].map(|i| axes[0][i] * u[0] + axes[1][i] * u[1] + axes[2][i] * u[2])
            })
        })
        .collect();
    draw(&track, TRAJECTORY, 2)?;
    if let Some(&p0) = track.first() {
        let color = if view.front(p0) {
            TRAJECTORY.0
        } else {
            TRAJECTORY.1
        };
        chart
            .draw_series(std::iter::once(Circle::new(
                view.screen(p0),
                5,
                color.filled(),
            )))
            .map_err(err)?;
    }
    // Principal axes: a stub outside the sphere and a label.
    for (i, m) in moments.iter().enumerate() {
        for sign in [1.0, -1.0] {
            let mut e = [0.0; 3];
            e[i] = sign;
            if !view.front(e) {
                continue;
            }
            let tip = e.map(|x| 1.18 * x);
            chart
                .draw_series(LineSeries::new(
                    [view.screen(e), view.screen(tip)],
                    BLACK.stroke_width(1),
                ))
                .map_err(err)?;
            let (x, y) = view.screen(e.map(|x| 1.24 * x));
            let s = if sign > 0.0 { "+" } else { "-" };
            chart
                .draw_series(std::iter::once(Text::new(
                    format!("{s}J{} (I = {m})", i + 1),
                    (x - 0.08, y),
                    ("sans-serif", 13),
                )))
                .map_err(err)?;
        }
    }
    let mut lines = vec![
        "principal frame, seen from outside; faint: the far hemisphere".to_string(),
        "grey: constant-energy curves E(J) = const on |J| = const (6.8.7), (6.8.8)".to_string(),
    ];
    match &sep {
        Some((g, _)) => lines.push(format!(
            "red: separatrices through the intermediate-axis saddles, gamma_B = {:.1} deg (6.8.10)",
            g.to_degrees()
        )),
        None => lines.push("no separatrix: two principal moments are equal".to_string()),
    }
    lines.push("blue: this run's body-frame J/|J| (dot: start)".to_string());
    if let Some(note) = &fig.polhode_note {
        lines.push(note.clone());
    }
    for (k, line) in lines.iter().enumerate() {
        notes
            .draw(&Text::new(
                line.as_str(),
                (12, 8 + 20 * k as i32),
                ("sans-serif", 13),
            ))
            .map_err(err)?;
    }
    Ok(())
}
