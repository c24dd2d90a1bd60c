//! The crate docs' layer table (`# Layers` in `src/lib.rs`) against the code: every module of
//! the crate is in exactly one row; the layers a row lists under "depends on" are exactly the
//! layers whose modules the row's modules name through `crate::` paths (in `use` lines, groups
//! and inline paths, doc comments excluded; the root re-exports such as `crate::Vec3` count as
//! their module; the crate's `Error` is allowed everywhere); and each of them is in a row above
//! (the layers point down).

extern crate std;

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::string::{String, ToString};
use std::vec::Vec;
use std::{format, fs};

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// One row of the table: layer name, its modules, the layers it depends on.
struct Row {
    layer: String,
    modules: Vec<String>,
    depends: Vec<String>,
}

/// The identifiers written in backticks in a table cell (`[`real`]` and `` `compensated` ``).
fn backticked(cell: &str) -> Vec<String> {
    cell.split('`')
        .skip(1)
        .step_by(2)
        .map(ToString::to_string)
        .collect()
}

fn table(lib: &str) -> Vec<Row> {
    let mut rows = Vec::new();
    let mut inside = false;
    for line in lib.lines() {
        let Some(text) = line.strip_prefix("//! ") else {
            if inside {
                break;
            }
            continue;
        };
        if text.starts_with("| layer | modules |") {
            inside = true;
            continue;
        }
        if !inside {
            continue;
        }
        if !text.starts_with('|') {
            break;
        }
        if text.starts_with("|---") {
            continue;
        }
        let cells: Vec<&str> = text.trim_matches('|').split(" | ").map(str::trim).collect();
        assert_eq!(
            cells.len(),
            4,
            "layer table row with {} cells: {text}",
            cells.len()
        );
        let depends = if cells[3] == "nothing" {
            Vec::new()
        } else {
            cells[3].split(", ").map(ToString::to_string).collect()
        };
        rows.push(Row {
            layer: cells[0].to_string(),
            modules: backticked(cells[1]),
            depends,
        });
    }
    assert!(!rows.is_empty(), "no layer table in src/lib.rs");
    rows
}

/// The crate's top-level modules (`mod x;`, `pub mod x;`), test-only ones left out.
fn crate_modules(lib: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    let mut test_only = false;
    for line in lib.lines() {
        let l = line.trim();
        if l == "#[cfg(test)]" {
            test_only = true;
            continue;
        }
        let name = l
            .strip_prefix("pub mod ")
            .or_else(|| l.strip_prefix("mod "))
            .and_then(|r| r.strip_suffix(';'));
        if let Some(n) = name
            && !test_only
        {
            out.insert(n.to_string());
        }
        test_only = false;
    }
    out
}

/// Root re-exports: `pub use module::{A, B};` and `pub use module::A;` map `A` to `module`.
fn reexports(lib: &str, modules: &BTreeSet<String>) -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    let flat = lib.replace('\n', " ");
    for stmt in flat.split(';') {
        let Some(rest) = stmt.trim().strip_prefix("pub use ") else {
            continue;
        };
        let Some((module, names)) = rest.split_once("::") else {
            continue;
        };
        if !modules.contains(module) {
            continue;
        }
        for n in names
            .trim_matches(|c| c == '{' || c == '}' || c == ' ')
            .split(',')
        {
            let n = n.trim();
            if !n.is_empty() {
                out.insert(n.to_string(), module.to_string());
            }
        }
    }
    out
}

fn rust_files(path: &Path, out: &mut Vec<PathBuf>) {
    if path.is_dir() {
        for e in fs::read_dir(path).unwrap() {
            rust_files(&e.unwrap().path(), out);
        }
    } else if path.extension().is_some_and(|e| e == "rs") {
        out.push(path.to_path_buf());
    }
}

/// The first identifier of each item of a `crate::{...}` group (nested groups skipped).
fn group_heads(group: &str, out: &mut Vec<String>) {
    let mut depth = 0;
    let mut item = String::new();
    let mut push = |item: &mut String| {
        let head: String = item
            .trim()
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        if !head.is_empty() {
            out.push(head);
        }
        item.clear();
    };
    for c in group.chars() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => push(&mut item),
            _ if depth == 0 => item.push(c),
            _ => {}
        }
    }
    push(&mut item);
}

/// The names following `crate::` in a module's files, outside comments.
fn crate_paths(module: &str) -> Vec<(String, PathBuf)> {
    let dir = src().join(module);
    let mut files = Vec::new();
    if dir.is_dir() {
        rust_files(&dir, &mut files);
    } else {
        files.push(src().join(format!("{module}.rs")));
    }
    let mut out = Vec::new();
    for f in files {
        let text = fs::read_to_string(&f).unwrap();
        let code: String = text
            .lines()
            .map(|l| l.split("//").next().unwrap())
            .collect::<Vec<_>>()
            .join("\n");
        let mut rest = code.as_str();
        while let Some(i) = rest.find("crate::") {
            rest = &rest[i + "crate::".len()..];
            let mut heads = Vec::new();
            if let Some(g) = rest.strip_prefix('{') {
                let mut depth = 1;
                let end = g
                    .char_indices()
                    .find(|&(_, c)| {
                        depth += match c {
                            '{' => 1,
                            '}' => -1,
                            _ => 0,
                        };
                        depth == 0
                    })
                    .map(|(k, _)| k)
                    .unwrap();
                group_heads(&g[..end], &mut heads);
            } else {
                heads.push(
                    rest.chars()
                        .take_while(|c| c.is_alphanumeric() || *c == '_')
                        .collect(),
                );
            }
            out.extend(heads.into_iter().map(|h| (h, f.clone())));
        }
    }
    out
}

#[test]
fn layer_table_matches_the_imports() {
    let lib = fs::read_to_string(src().join("lib.rs")).unwrap();
    let rows = table(&lib);
    let modules = crate_modules(&lib);
    let reexported = reexports(&lib, &modules);
    // Every module in exactly one row (the error type is used everywhere and has none).
    let mut layer_of = BTreeMap::new();
    for (k, row) in rows.iter().enumerate() {
        assert!(
            !row.modules.is_empty(),
            "row {:?} names no module",
            row.layer
        );
        for m in &row.modules {
            assert!(
                modules.contains(m),
                "the table names {m:?}, not a module of the crate"
            );
            assert!(layer_of.insert(m.clone(), k).is_none(), "{m:?} in two rows");
        }
    }
    let unlisted: Vec<_> = modules
        .iter()
        .filter(|m| *m != "error" && !layer_of.contains_key(*m))
        .collect();
    assert!(
        unlisted.is_empty(),
        "modules missing from the layer table: {unlisted:?}"
    );
    let mut problems = Vec::new();
    for (k, row) in rows.iter().enumerate() {
        let declared: BTreeSet<&str> = row.depends.iter().map(String::as_str).collect();
        for d in &declared {
            match rows.iter().position(|r| r.layer == *d) {
                Some(j) if j < k => {}
                Some(_) => problems.push(format!(
                    "{}: depends on {d:?}, which is not above it",
                    row.layer
                )),
                None => problems.push(format!("{}: no layer called {d:?}", row.layer)),
            }
        }
        // The layers the row's modules actually name, with one file that does.
        let mut used: BTreeMap<&str, PathBuf> = BTreeMap::new();
        for m in &row.modules {
            for (name, file) in crate_paths(m) {
                let target = if modules.contains(&name) {
                    name.as_str()
                } else if let Some(t) = reexported.get(&name) {
                    t.as_str()
                } else {
                    problems.push(format!(
                        "{}: crate::{name} is neither a module nor a root re-export",
                        file.display()
                    ));
                    continue;
                };
                if target == "error" || row.modules.iter().any(|r| r == target) {
                    continue;
                }
                let layer = rows[layer_of[target]].layer.as_str();
                used.entry(layer).or_insert(file);
            }
        }
        for (layer, file) in &used {
            if !declared.contains(layer) {
                problems.push(format!(
                    "{}: uses {layer:?} ({}) but the table does not list it",
                    row.layer,
                    file.display()
                ));
            }
        }
        for d in &declared {
            if !used.contains_key(d) {
                problems.push(format!(
                    "{}: the table lists {d:?} but no module of the row uses it",
                    row.layer
                ));
            }
        }
    }
    assert!(
        problems.is_empty(),
        "layer table (src/lib.rs) vs the code:\n{}",
        problems.join("\n")
    );
}
