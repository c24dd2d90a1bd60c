//! The SVG figure of a `characterize` run (plotters, SVG backend): per sensor a log-log panel of
//! the three axes' Allan deviations (points joined), each axis's fitted model (thin), and the
//! three fitted asymptotes of the axis with the largest N (grey dashes: `N/√τ`, the floor
//! `0.664·B`, `K·√(τ/3)`).

use std::path::Path;

use gyrostat_tools::characterization::AxisReport;
use gyrostat_tools::noise::FLICKER_FLOOR;
use gyrostat_tools::plot::{COLORS, err};
use plotters::coord::Shift;
use plotters::prelude::*;

const WIDTH: u32 = 900;
const PANEL_HEIGHT: u32 = 520;

/// Writes the figure to `path`.
pub fn write_svg(
    path: &Path,
    title: &str,
    gyro: &[AxisReport; 3],
    accel: &[AxisReport; 3],
) -> Result<(), String> {
    let root = SVGBackend::new(path, (WIDTH, 40 + 2 * PANEL_HEIGHT)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let root = root.titled(title, ("sans-serif", 16)).map_err(err)?;
    let areas = root.split_evenly((2, 1));
    panel(&areas[0], "gyroscope", "Allan deviation (rad/s)", gyro)?;
    panel(&areas[1], "accelerometer", "Allan deviation (m/s^2)", accel)?;
    root.present().map_err(err)
}

fn panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    caption: &str,
    unit: &str,
    axes: &[AxisReport; 3],
) -> Result<(), String> {
    let points = || axes.iter().flat_map(|a| a.allan.points.iter());
    let (t0, t1) = points().fold((f64::INFINITY, 0.0f64), |(lo, hi), p| {
        (lo.min(p.tau), hi.max(p.tau))
    });
    let (y0, y1) = points()
        .filter(|p| p.adev > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), p| {
            (lo.min(p.adev), hi.max(p.adev))
        });
    if !(t0.is_finite() && y0.is_finite() && t1 > 0.0 && y1 > 0.0) {
        return Ok(());
    }
    let (t0, t1) = (t0 / 1.5, t1 * 1.5);
    let (y0, y1) = (y0 / 3.0, y1 * 2.0);
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 15))
        .margin(10)
        .x_label_area_size(34)
        .y_label_area_size(80)
        .build_cartesian_2d((t0..t1).log_scale(), (y0..y1).log_scale())
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("tau (s)")
        .y_desc(unit)
        .y_label_formatter(&|v| format!("{v:.1e}"))
        .x_label_formatter(&|v| format!("{v:.3}"))
        .draw()
        .map_err(err)?;
    let grid = |n: usize| -> Vec<f64> {
        (0..=n)
            .map(|i| t0 * (t1 / t0).powf(i as f64 / n as f64))
            .collect()
    };
    for (i, (a, name)) in axes.iter().zip(["x", "y", "z"]).enumerate() {
        let color = COLORS[i % COLORS.len()];
        let data: Vec<(f64, f64)> = a
            .allan
            .points
            .iter()
            .filter(|p| p.adev > 0.0)
            .map(|p| (p.tau, p.adev))
            .collect();
        chart
            .draw_series(LineSeries::new(data.clone(), color.stroke_width(2)))
            .map_err(err)?
            .label(format!(
                "{name}: N {:.2e}, B {:.2e}, K {:.2e}",
                a.allan.fit.noise_density,
                a.allan.fit.bias_instability,
                a.allan.fit.rate_random_walk
            ))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color));
        chart
            .draw_series(data.iter().map(|&p| Circle::new(p, 2, color.filled())))
            .map_err(err)?;
        let fit = a.allan.fit;
        let model: Vec<(f64, f64)> = grid(80)
            .into_iter()
            .map(|t| (t, fit.allan_deviation(t)))
            .filter(|&(_, v)| v > y0 && v < y1)
            .collect();
        chart
            .draw_series(LineSeries::new(model, color.mix(0.6).stroke_width(1)))
            .map_err(err)?;
    }
    // The asymptotes of the axis with the largest N.
    let Some(worst) = axes.iter().max_by(|a, b| {
        a.allan
            .fit
            .noise_density
            .total_cmp(&b.allan.fit.noise_density)
    }) else {
        return Ok(());
    };
    let f = worst.allan.fit;
    // Each asymptote as (label, coefficient, exponent of τ): `c·τ^e`.
    let lines = [
        ("N/sqrt(tau)", f.noise_density, -0.5),
        ("0.664 B", FLICKER_FLOOR * f.bias_instability, 0.0),
        ("K sqrt(tau/3)", f.rate_random_walk / 3f64.sqrt(), 0.5),
    ];
    for (label, c, e) in lines {
        let pts: Vec<(f64, f64)> = grid(40)
            .into_iter()
            .map(|t| (t, c * t.powf(e)))
            .filter(|&(_, v)| v > y0 && v < y1)
            .collect();
        if pts.len() < 2 {
            continue;
        }
        let style = RGBColor(120, 120, 120).stroke_width(1);
        chart
            .draw_series(DashedLineSeries::new(pts, 6, 4, style))
            .map_err(err)?
            .label(format!("{label} (largest-N axis)"))
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], style));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(err)
}
