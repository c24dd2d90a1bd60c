//! The SVG figure of an `estimate` run (plotters, SVG backend): the estimate's heading and
//! inclination (and the reference's), the error against the reference, the bias estimate and
//! the per-row flags, each over time.

use std::path::Path;

use gyrostat_tools::plot::{COLORS, err};
use plotters::coord::Shift;
use plotters::prelude::*;

/// One curve, sampled at [`Figure::t`].
pub struct Series {
    /// Legend text.
    pub label: &'static str,
    /// Values, one per time sample.
    pub y: Vec<f64>,
}

/// One panel: a caption, the unit of its axis, its curves.
pub struct Panel {
    /// Caption over the panel.
    pub caption: String,
    /// The unit of the vertical axis.
    pub unit: &'static str,
    /// The curves.
    pub series: Vec<Series>,
}

/// Everything the figure shows.
pub struct Figure {
    /// The title line.
    pub title: String,
    /// Sample times (s).
    pub t: Vec<f64>,
    /// The panels, top to bottom.
    pub panels: Vec<Panel>,
}

const WIDTH: u32 = 1200;
const PANEL_HEIGHT: u32 = 260;

/// Writes the figure to `path` as SVG.
pub fn write_svg(path: &Path, fig: &Figure) -> Result<(), String> {
    let n = fig.panels.len().max(1);
    let height = 40 + PANEL_HEIGHT * u32::try_from(n).unwrap_or(1);
    let root = SVGBackend::new(path, (WIDTH, height)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let root = root.titled(&fig.title, ("sans-serif", 18)).map_err(err)?;
    let areas = root.split_evenly((n, 1));
    for (area, panel) in areas.iter().zip(&fig.panels) {
        linear_panel(area, panel, &fig.t)?;
    }
    root.present().map_err(err)
}

fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        return (-1.0, 1.0);
    }
    let pad = 0.05 * (hi - lo).max(1e-12 * lo.abs().max(1.0));
    (lo - pad, hi + pad)
}

fn linear_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: &Panel,
    t: &[f64],
) -> Result<(), String> {
    let (lo, hi) = range(panel.series.iter().flat_map(|s| s.y.iter().copied()));
    let t0 = t.first().copied().unwrap_or(0.0);
    let t1 = t.last().copied().unwrap_or(1.0);
    let t1 = if t1 > t0 { t1 } else { t0 + 1.0 };
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.caption, ("sans-serif", 15))
        .margin(8)
        .x_label_area_size(28)
        .y_label_area_size(70)
        .build_cartesian_2d(t0..t1, lo..hi)
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("t (s)")
        .y_desc(panel.unit)
        .light_line_style(WHITE)
        .draw()
        .map_err(err)?;
    for (i, s) in panel.series.iter().enumerate() {
        let color = COLORS[i % COLORS.len()];
        // A non-finite value (a row without an estimate or a reference) breaks the curve.
        let mut runs: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
        for (&t, &v) in t.iter().zip(&s.y) {
            if v.is_finite() {
                if let Some(run) = runs.last_mut() {
                    run.push((t, v));
                }
            } else if runs.last().is_some_and(|r| !r.is_empty()) {
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
                    .label(s.label)
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color));
            }
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(err)
}
