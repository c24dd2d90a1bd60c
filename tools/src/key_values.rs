//! The line syntax shared by the tools' text files (the calibration file of `propagate` and
//! `estimate`, the sensor spec of `synthesize` and `characterize`):
//!
//! ```text
//! # comments run from '#' to the end of the line; blank lines are skipped
//! key = 1.0, -2.5, 3        # a key and its comma-separated numbers
//! ```
//!
//! Every key has a fixed count of numbers; an unknown key, a key given twice, a line without
//! `=`, a wrong count or a non-finite number is an error naming its line (`line N: reason`).

/// One value read from a file: the line it stood on (from 1) and its numbers.
pub type Entry = (usize, Vec<f64>);

/// Reads `text` against `keys` (name, count of numbers). Returns one slot per key, in the order
/// of `keys` (`None` where the file does not give it). `check(key index, number, its text)`
/// may reject a number with a reason (the message then reads `line N: key: reason`).
pub fn parse(
    text: &str,
    keys: &[(&str, usize)],
    check: impl Fn(usize, f64, &str) -> Result<(), String>,
) -> Result<Vec<Option<Entry>>, String> {
    let mut values: Vec<Option<Entry>> = vec![None; keys.len()];
    for (i, raw_line) in text.lines().enumerate() {
        let n = i + 1;
        let line = raw_line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let (key, rest) = line
            .split_once('=')
            .ok_or_else(|| format!("line {n}: expected 'key = numbers', found '{line}'"))?;
        let key = key.trim();
        let Some(p) = keys.iter().position(|(k, _)| *k == key) else {
            let names: Vec<&str> = keys.iter().map(|k| k.0).collect();
            return Err(format!(
                "line {n}: unknown key '{key}' (one of {})",
                names.join(", ")
            ));
        };
        let count = keys[p].1;
        if let Some((first, _)) = &values[p] {
            return Err(format!(
                "line {n}: '{key}' given twice (first on line {first})"
            ));
        }
        let mut nums = Vec::with_capacity(count);
        for part in rest.split(',') {
            let part = part.trim();
            let x: f64 = part
                .parse()
                .map_err(|_| format!("line {n}: {key}: invalid number '{part}'"))?;
            if !x.is_finite() {
                return Err(format!("line {n}: {key}: not a finite number '{part}'"));
            }
            check(p, x, part).map_err(|reason| format!("line {n}: {key}: {reason}"))?;
            nums.push(x);
        }
        if nums.len() != count {
            return Err(format!(
                "line {n}: {key}: expected {count} comma-separated number{}, found {}",
                if count == 1 { "" } else { "s" },
                nums.len()
            ));
        }
        values[p] = Some((n, nums));
    }
    Ok(values)
}
