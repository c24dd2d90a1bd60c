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

/// A drawing call's error as the tools report it: one line (the error's message, its lines
/// joined).
pub fn err<E: std::fmt::Display>(e: E) -> String {
    let text = e.to_string();
    let one_line: Vec<&str> = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect();
    format!("drawing the plot: {}", one_line.join(" "))
}

/// Checks, before a run, that the plot `path` can be created: its folder exists and is a
/// folder. The message names the folder.
pub fn check_folder(path: &std::path::Path) -> Result<(), String> {
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => std::path::Path::new("."),
    };
    if folder.is_dir() {
        Ok(())
    } else {
        Err(format!("the folder {} does not exist", folder.display()))
    }
}
