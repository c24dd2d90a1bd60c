//! What the tools' SVG plots share (`simulate --plot`, `estimate --plot`): the series colours and
//! the error of a drawing call.

use plotters::style::RGBColor;

/// Series colours (the "tab10" palette), in the order the series are drawn.
pub const COLORS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
];

/// A drawing call's error as the tools report it.
pub fn err<E: std::fmt::Debug>(e: E) -> String {
    format!("drawing the plot: {e:?}")
}
