//! The seed equation index (`SEED.md`) cannot rot: every Rust item it cites must still be defined
//! where it says, every test it cites must still exist, and every equation label of seed sections
//! 6.4–6.9 must have a row.
//!
//! Format rules (also stated at the top of `SEED.md`):
//! - a table row whose first cell starts with `6.` lists labels: `6.7.10a–d` (letter range),
//!   `6.4.1–3` (number range) or single labels, separated by `, `;
//! - the implementation cell holds Rust paths in backticks — an optional module path from the
//!   crate root (`dynamics::mass::total_mass_and_center`), then an item or `Type::item`; the item
//!   must be a `fn`, `struct`, `enum`, `trait`, `const` or `type` defined in that module (with
//!   `Type::item`, inside an `impl` block of `Type` — inherent or trait — in a file of that
//!   module) — or, with no path,
//!   starts with one of the markers *definition*, *derivation*, *illustration*, *out of scope*;
//! - the test cell holds `tests/FILE::name` spans: `fn name` in `host-tests/tests/FILE.rs`, FILE
//!   being `AREA/MODULE` (`tests/dynamics/mass::bent_axle_6_5_6`); a row with an implementation
//!   needs at least one;
//! - under `## Misprints`, every bullet cites at least one test, and every cited path is checked.
//!
//! The labels of the seed are embedded below (extracted from the seed text with the scan in
//! [`seed_labels`]); when the seed text is present (`GYROSTAT_SEED_TEXT`, or `../shared/seed/`
//! beside the repository) the test also checks that the embedded list is still exactly the
//! seed's.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// Every label `(6.N.M[a])` and `\tag{6.N.M[a]}` of seed sections 6.4–6.9, references to groups
/// such as `(6.7.11)` included (those are covered by any lettered row `6.7.11a`, …).
const SEED_LABELS: &[&str] = &[
    "6.4.1", "6.4.2", "6.4.3", "6.4.4", "6.4.5a", "6.4.5b", "6.4.5c", "6.4.6", "6.4.7", "6.4.8",
    "6.4.9", "6.4.9a", "6.4.9b", "6.4.10", "6.4.10a", "6.4.10b", "6.4.11", "6.4.12", "6.4.13",
    "6.4.14", "6.4.15a", "6.4.15b", "6.4.16", "6.4.17", "6.4.18", "6.4.19", "6.5.1", "6.5.2",
    "6.5.3", "6.5.4", "6.5.5", "6.5.5a", "6.5.5b", "6.5.6", "6.5.7", "6.5.8", "6.5.9", "6.5.10",
    "6.5.11", "6.5.12", "6.5.13", "6.5.14a", "6.5.14b", "6.5.15", "6.6.1", "6.6.1a", "6.6.1b",
    "6.6.2", "6.6.3", "6.6.4", "6.6.5", "6.6.5a", "6.6.5b", "6.6.5c", "6.6.5d", "6.6.5e", "6.6.6a",
    "6.6.6b", "6.6.6c", "6.6.6d", "6.6.7", "6.6.8a", "6.6.8b", "6.6.8c", "6.6.9", "6.6.10a",
    "6.6.10b", "6.6.11", "6.6.11a", "6.6.11b", "6.6.11c", "6.6.11d", "6.6.12", "6.6.13", "6.6.14",
    "6.6.15", "6.6.15a", "6.6.16", "6.6.16a", "6.6.16b", "6.6.16c", "6.7.1", "6.7.2", "6.7.3",
    "6.7.4", "6.7.5", "6.7.5a", "6.7.5b", "6.7.5c", "6.7.5d", "6.7.5e", "6.7.5f", "6.7.6", "6.7.7",
    "6.7.7a", "6.7.7b", "6.7.8a", "6.7.8b", "6.7.9", "6.7.9a", "6.7.9b", "6.7.10", "6.7.10a",
    "6.7.10b", "6.7.10c", "6.7.10d", "6.7.11", "6.7.11a", "6.7.11b", "6.7.11c", "6.7.11d",
    "6.7.11e", "6.7.11f", "6.7.12", "6.7.13", "6.7.13a", "6.7.13b", "6.7.14a", "6.7.14b",
    "6.7.14c", "6.7.14d", "6.7.15b", "6.7.16", "6.7.17", "6.7.17c", "6.7.18a", "6.7.18b", "6.7.19",
    "6.7.19a", "6.7.19b", "6.7.20", "6.7.20a", "6.7.20b", "6.7.21", "6.7.22", "6.7.22a", "6.7.22b",
    "6.7.23", "6.7.24", "6.7.25", "6.7.25a", "6.7.25b", "6.7.25c", "6.7.25d", "6.7.26", "6.7.27",
    "6.7.27a", "6.7.27b", "6.7.27c", "6.7.28", "6.7.29a", "6.7.29b", "6.7.29c", "6.7.29d",
    "6.7.30", "6.7.30a", "6.7.31", "6.7.32", "6.7.32a", "6.7.32b", "6.7.33", "6.7.34", "6.7.35",
    "6.7.35a", "6.7.35b", "6.7.36", "6.7.37", "6.7.37a", "6.7.37b", "6.7.38", "6.7.39", "6.7.40",
    "6.7.41", "6.7.41a", "6.7.41b", "6.7.42a", "6.7.42b", "6.7.43a", "6.7.43b", "6.7.43c",
    "6.7.43d", "6.7.44", "6.7.45", "6.7.46", "6.7.47", "6.7.48", "6.7.49", "6.7.50", "6.8.1",
    "6.8.2", "6.8.3a", "6.8.3b", "6.8.4a", "6.8.4b", "6.8.5", "6.8.5a", "6.8.5b", "6.8.5d",
    "6.8.6a", "6.8.6b", "6.8.6c", "6.8.7", "6.8.8", "6.8.8a", "6.8.8b", "6.8.9", "6.8.10",
    "6.8.11", "6.8.12", "6.8.13", "6.8.14a", "6.8.14b", "6.8.15", "6.8.16", "6.8.17", "6.8.18",
    "6.8.19", "6.8.20", "6.8.20a", "6.8.20b", "6.8.20c", "6.8.20d", "6.9.1", "6.9.2", "6.9.2a",
    "6.9.2b", "6.9.2c", "6.9.3a", "6.9.3b", "6.9.3c", "6.9.4a", "6.9.4b", "6.9.4c", "6.9.5",
    "6.9.6b", "6.9.7", "6.9.8", "6.9.9", "6.9.10", "6.9.11", "6.9.12",
];

const SEED_FILE: &str = "000_1c5581a12831d7e9.txt";
const MARKERS: [&str; 4] = [
    "*definition*",
    "*derivation*",
    "*illustration*",
    "*out of scope*",
];

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The scan that produced [`SEED_LABELS`]: `(` or `{` then `6.N.M` with `N` in 4–9, then an
/// optional letter, directly or after one space, or as the seed's `(6.6.10 \text{ a})`.
fn seed_labels(text: &str) -> BTreeSet<String> {
    let b = text.as_bytes();
    let mut out = BTreeSet::new();
    for i in 0..b.len() {
        if b[i] != b'(' && b[i] != b'{' {
            continue;
        }
        let r = &b[i + 1..];
        if r.len() < 5 || &r[..2] != b"6." || !(b'4'..=b'9').contains(&r[2]) || r[3] != b'.' {
            continue;
        }
        let mut k = 4;
        while k < r.len() && r[k].is_ascii_digit() {
            k += 1;
        }
        if k == 4 {
            continue;
        }
        let mut label = String::from_utf8(r[..k].to_vec()).unwrap();
        let text_letter = b" \\text{ ";
        if k + 1 < r.len() && r[k] == b' ' && r[k + 1].is_ascii_lowercase() {
            label.push(r[k + 1] as char);
        } else if k < r.len() && r[k].is_ascii_lowercase() {
            label.push(r[k] as char);
        } else if r[k..].starts_with(text_letter)
            && r.get(k + text_letter.len())
                .is_some_and(|c| c.is_ascii_lowercase())
            && r.get(k + text_letter.len() + 1) == Some(&b'}')
        {
            label.push(r[k + text_letter.len()] as char);
        }
        out.insert(label);
    }
    out
}

/// Splits a table row on `|` not escaped as `\|`.
fn cells(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut prev = ' ';
    for c in line.trim().trim_start_matches('|').chars() {
        if c == '|' && prev != '\\' {
            out.push(cur.trim().to_string());
            cur.clear();
        } else {
            cur.push(c);
        }
        prev = c;
    }
    if !cur.trim().is_empty() {
        out.push(cur.trim().to_string());
    }
    out
}

fn code_spans(cell: &str) -> Vec<String> {
    cell.split('`')
        .enumerate()
        .filter(|(i, _)| i % 2 == 1)
        .map(|(_, s)| s.to_string())
        .collect()
}

/// `6.7.10a–d`, `6.4.1–3`, `6.6.15a` → labels.
fn expand(item: &str) -> Result<Vec<String>, String> {
    let item = item.trim();
    let (head, tail) = match item.split_once(['–', '-']) {
        Some((h, t)) => (h, Some(t)),
        None => (item, None),
    };
    let parts: Vec<&str> = head.split('.').collect();
    if parts.len() != 3 || parts[0] != "6" {
        return Err(format!("bad label {item:?}"));
    }
    let digits: String = parts[2]
        .chars()
        .take_while(|c| c.is_ascii_digit())
        .collect();
    let letter: String = parts[2].chars().skip(digits.len()).collect();
    if digits.is_empty() || letter.len() > 1 {
        return Err(format!("bad label {item:?}"));
    }
    let base = format!("6.{}.", parts[1]);
    let Some(tail) = tail else {
        return Ok(vec![format!("{base}{digits}{letter}")]);
    };
    if let (Some(a), Some(z)) = (letter.chars().next(), tail.chars().next()) {
        if tail.len() != 1 || z < a {
            return Err(format!("bad letter range {item:?}"));
        }
        return Ok((a..=z).map(|c| format!("{base}{digits}{c}")).collect());
    }
    let (a, z): (u32, u32) = (
        digits.parse().unwrap(),
        tail.parse().map_err(|_| format!("bad range {item:?}"))?,
    );
    if z <= a {
        return Err(format!("bad range {item:?}"));
    }
    Ok((a..=z).map(|n| format!("{base}{n}")).collect())
}

fn is_ident(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// `kw name` appears with `name` ending at a word boundary.
fn defines(content: &str, kw: &str, name: &str) -> bool {
    let pat = format!("{kw} {name}");
    content.match_indices(&pat).any(|(i, _)| {
        let before = content[..i].chars().next_back();
        let after = content[i + pat.len()..].chars().next();
        !before.is_some_and(is_ident) && !after.is_some_and(is_ident)
    })
}

fn defines_item(content: &str, name: &str) -> bool {
    ["fn", "struct", "enum", "trait", "const", "type"]
        .iter()
        .any(|kw| defines(content, kw, name))
}

/// The self type of an `impl` header line: the first identifier after the generics, or after
/// ` for ` in a trait impl (`impl<T> From<A<T>> for B<T>` is an impl of `B`, not of `A`).
fn impl_self_type(header: &str) -> Option<&str> {
    let mut rest = header.trim_start().strip_prefix("impl")?;
    if rest.starts_with('<') {
        let mut depth = 0;
        let end = rest.char_indices().find_map(|(i, c)| {
            match c {
                '<' => depth += 1,
                '>' => depth -= 1,
                _ => {}
            }
            (depth == 0).then_some(i + 1)
        })?;
        rest = &rest[end..];
    } else if !rest.starts_with(' ') {
        return None; // `implements`, …
    }
    let rest = match rest.find(" for ") {
        Some(i) => &rest[i + 5..],
        None => rest,
    };
    let rest = rest.trim_start();
    let len = rest.find(|c: char| !is_ident(c)).unwrap_or(rest.len());
    (len > 0).then(|| &rest[..len])
}

/// `item` is defined inside an `impl` block of the type `ty` in `content` (the block from the
/// header's `{` to its matching `}`).
fn defines_in_impl_of(content: &str, ty: &str, item: &str) -> bool {
    let mut offset = 0;
    for line in content.split_inclusive('\n') {
        let start = offset;
        offset += line.len();
        if impl_self_type(line) != Some(ty) {
            continue;
        }
        let Some(open) = content[start..].find('{').map(|i| start + i) else {
            continue;
        };
        let mut depth = 0;
        let mut end = content.len();
        for (i, c) in content[open..].char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        end = open + i;
                        break;
                    }
                }
                _ => {}
            }
        }
        if defines_item(&content[open..end], item) {
            return true;
        }
    }
    false
}

fn rust_files(dir: &Path, out: &mut Vec<(PathBuf, String)>) {
    let mut entries: Vec<_> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            let text = fs::read_to_string(&p).unwrap();
            out.push((p, text));
        }
    }
}

/// Checks a cited library path (see the module docs).
fn check_item(path: &str, src: &Path) -> Result<(), String> {
    let segs: Vec<&str> = path.split("::").collect();
    if segs
        .iter()
        .any(|s| s.is_empty() || !s.chars().all(is_ident))
    {
        return Err(format!("`{path}` is not a Rust path"));
    }
    let mut dir = src.to_path_buf();
    let mut scope: Option<PathBuf> = None; // a module file, or a module directory
    let mut i = 0;
    while i + 1 < segs.len() && segs[i].starts_with(|c: char| c.is_ascii_lowercase()) {
        let file = dir.join(format!("{}.rs", segs[i]));
        let sub = dir.join(segs[i]);
        if file.is_file() {
            scope = Some(file);
        } else if sub.join("mod.rs").is_file() {
            scope = Some(sub.clone());
        } else {
            return Err(format!("`{path}`: no module `{}`", segs[i]));
        }
        dir = sub;
        i += 1;
    }
    let mut files = Vec::new();
    match &scope {
        Some(p) if p.is_file() => files.push((p.clone(), fs::read_to_string(p).unwrap())),
        Some(p) => rust_files(p, &mut files),
        None => rust_files(src, &mut files),
    }
    match &segs[i..] {
        [item] => {
            if files.iter().any(|(_, c)| defines_item(c, item)) {
                Ok(())
            } else {
                Err(format!("`{path}`: `{item}` is not defined there"))
            }
        }
        [ty, item] => {
            let mut all = Vec::new();
            rust_files(src, &mut all);
            if !all.iter().any(|(_, c)| defines_item(c, ty)) {
                return Err(format!("`{path}`: no type `{ty}`"));
            }
            if files.iter().any(|(_, c)| defines_in_impl_of(c, ty, item)) {
                Ok(())
            } else {
                Err(format!("`{path}`: no `{item}` in an impl of `{ty}`"))
            }
        }
        _ => Err(format!("`{path}`: expected [module::]item or Type::item")),
    }
}

/// Checks a cited test `tests/FILE::name`.
fn check_test(span: &str) -> Result<(), String> {
    let rest = span
        .strip_prefix("tests/")
        .ok_or_else(|| format!("`{span}`: tests are cited as tests/FILE::name"))?;
    let (file, name) = rest
        .split_once("::")
        .ok_or_else(|| format!("`{span}`: expected tests/FILE::name"))?;
    let path = repo().join("host-tests/tests").join(format!("{file}.rs"));
    let text = fs::read_to_string(&path).map_err(|_| format!("`{span}`: no file {path:?}"))?;
    if defines(&text, "fn", name) {
        Ok(())
    } else {
        Err(format!("`{span}`: no `fn {name}` in {file}.rs"))
    }
}

#[test]
fn seed_index_is_complete_and_current() {
    let index = fs::read_to_string(repo().join("SEED.md")).expect("SEED.md at the repository root");
    let src = repo().join("src");
    let mut errors = Vec::new();
    let mut rows: BTreeMap<String, usize> = BTreeMap::new();
    let mut section = String::new();
    let mut misprint_bullets: Vec<String> = Vec::new();
    let (mut n_rows, mut n_items, mut n_tests) = (0, 0, 0);
    for (lineno, line) in index.lines().enumerate() {
        let lineno = lineno + 1;
        if line.starts_with('#') {
            section = line.trim_start_matches('#').trim().to_string();
            continue;
        }
        if section.starts_with("Misprints") {
            if line.starts_with("- ") {
                misprint_bullets.push(line.to_string());
            } else if let Some(last) = misprint_bullets.last_mut() {
                last.push(' ');
                last.push_str(line);
            }
            continue;
        }
        if !line.starts_with('|') {
            continue;
        }
        let c = cells(line);
        if c.is_empty() || !c[0].starts_with("6.") {
            continue;
        }
        n_rows += 1;
        if c.len() != 4 {
            errors.push(format!("line {lineno}: expected 4 cells, got {}", c.len()));
            continue;
        }
        for item in c[0].split(", ") {
            match expand(item) {
                Ok(labels) => {
                    for l in labels {
                        if let Some(prev) = rows.insert(l.clone(), lineno) {
                            errors
                                .push(format!("line {lineno}: {l} already indexed at line {prev}"));
                        }
                    }
                }
                Err(e) => errors.push(format!("line {lineno}: {e}")),
            }
        }
        // A marker row explains itself in prose (its code spans are not paths).
        let marker = MARKERS.iter().any(|m| c[2].starts_with(m));
        let items = if marker {
            Vec::new()
        } else {
            code_spans(&c[2])
        };
        let tests = code_spans(&c[3]);
        if items.is_empty() {
            if !marker {
                errors.push(format!(
                    "line {lineno}: no implementation and no marker {MARKERS:?}"
                ));
            }
        } else if tests.is_empty() {
            errors.push(format!("line {lineno}: implementation without a test"));
        }
        for it in &items {
            n_items += 1;
            if let Err(e) = check_item(it, &src) {
                errors.push(format!("line {lineno}: {e}"));
            }
        }
        for t in &tests {
            n_tests += 1;
            if let Err(e) = check_test(t) {
                errors.push(format!("line {lineno}: {e}"));
            }
        }
    }
    assert!(
        !misprint_bullets.is_empty(),
        "SEED.md has no ## Misprints bullets"
    );
    for b in &misprint_bullets {
        let spans = code_spans(b);
        let tests: Vec<&String> = spans.iter().filter(|s| s.starts_with("tests/")).collect();
        if tests.is_empty() {
            errors.push(format!("misprint without a test: {b:.60}"));
        }
        for s in &spans {
            if s.starts_with("tests/") {
                if let Err(e) = check_test(s) {
                    errors.push(format!("misprints: {e}"));
                }
            } else if s.contains("::")
                && s.chars().all(|c| is_ident(c) || c == ':')
                && let Err(e) = check_item(s, &src)
            {
                errors.push(format!("misprints: {e}"));
            }
        }
    }
    // Coverage: every seed label has a row (a group label such as 6.7.11 by its lettered rows);
    // every row is a seed label.
    let seed: BTreeSet<&str> = SEED_LABELS.iter().copied().collect();
    for l in &seed {
        let covered = rows.contains_key(*l)
            || rows.keys().any(|k| {
                k.strip_prefix(*l)
                    .is_some_and(|s| s.len() == 1 && s.chars().all(|c| c.is_ascii_lowercase()))
            });
        if !covered {
            errors.push(format!("seed label {l} has no row"));
        }
    }
    for l in rows.keys() {
        if !seed.contains(l.as_str()) {
            errors.push(format!("row label {l} is not a label of the seed"));
        }
    }
    assert!(errors.is_empty(), "SEED.md:\n{}", errors.join("\n"));
    println!(
        "SEED.md: {n_rows} rows, {} labels, {n_items} item citations, {n_tests} test citations, \
         {} misprints; all {} seed labels covered",
        rows.len(),
        misprint_bullets.len(),
        seed.len()
    );
}

#[test]
fn embedded_labels_are_the_seeds() {
    let path = std::env::var_os("GYROSTAT_SEED_TEXT")
        .map(PathBuf::from)
        .unwrap_or_else(|| repo().join("../shared/seed").join(SEED_FILE));
    let Ok(text) = fs::read_to_string(&path) else {
        println!("seed text not found at {path:?}: checked against the embedded label list only");
        return;
    };
    let found = seed_labels(&text);
    let embedded: BTreeSet<String> = SEED_LABELS.iter().map(|s| s.to_string()).collect();
    let missing: Vec<&String> = found.difference(&embedded).collect();
    let extra: Vec<&String> = embedded.difference(&found).collect();
    assert!(
        missing.is_empty() && extra.is_empty(),
        "labels in the seed but not embedded: {missing:?}; embedded but not in the seed: {extra:?}"
    );
    println!(
        "embedded labels = the seed's {} labels ({path:?})",
        found.len()
    );
}

#[test]
fn parser_self_checks() {
    assert_eq!(
        expand("6.7.10a–d").unwrap(),
        ["6.7.10a", "6.7.10b", "6.7.10c", "6.7.10d"]
    );
    assert_eq!(expand("6.4.1–3").unwrap(), ["6.4.1", "6.4.2", "6.4.3"]);
    assert_eq!(expand("6.6.15a").unwrap(), ["6.6.15a"]);
    assert!(expand("6.7.10d–a").is_err() && expand("7.1.1").is_err());
    assert_eq!(
        cells(r"| 6.4.8 | `v = ω × r`, \|J\| | `a::b` | x |").len(),
        4
    );
    assert!(check_item("dynamics::mass::total_mass_and_center", &repo().join("src")).is_ok());
    assert!(check_item("dynamics::mass::no_such_fn", &repo().join("src")).is_err());
    assert!(
        check_item(
            "dynamics::closed_form::analysis::inertia_from_point_masses",
            &repo().join("src")
        )
        .is_err()
    );
    assert!(check_item("Euler::rates_to_body_matrix", &repo().join("src")).is_ok());
    assert!(check_item("Euler::no_such_method", &repo().join("src")).is_err());
    // `impl From<BodyHamiltonian<T>> for Gyrostat<T>` is an impl of Gyrostat, not of
    // BodyHamiltonian: the step methods are Gyrostat's.
    assert!(check_item("Gyrostat::step_with", &repo().join("src")).is_ok());
    assert!(check_item("BodyHamiltonian::step_with", &repo().join("src")).is_err());
    assert_eq!(
        impl_self_type("impl<T: Real> From<BodyHamiltonian<T>> for Gyrostat<T> {"),
        Some("Gyrostat")
    );
    assert_eq!(impl_self_type("impl Format for Error {"), Some("Error"));
    assert_eq!(
        impl_self_type("impl<T: Real, const N: usize> Gyrostat<T, N> {"),
        Some("Gyrostat")
    );
    assert!(check_test("tests/dynamics/seed_index::parser_self_checks").is_ok());
    assert!(check_test("tests/dynamics/seed_index::no_such_test").is_err());
    let labels = seed_labels(
        "(6.6.10 a) \\tag{6.4.1} (6.7.27)x (6.3.1) Fig. 6.8.2 (6.7.5c-d) (6.6.10 \\text{ b})",
    );
    let want: BTreeSet<String> = ["6.6.10a", "6.4.1", "6.7.27", "6.7.5c", "6.6.10b"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    assert_eq!(labels, want);
}
