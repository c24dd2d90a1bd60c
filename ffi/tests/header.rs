//! The committed header `include/gyrostat.h` is what cbindgen generates from `src/lib.rs` now,
//! with the items `src/lib.rs` makes by macro (the estimator's parameter structs, from the
//! library's parameter table) given to cbindgen as their source text (cbindgen does not expand
//! macros). `GYROSTAT_BLESS=1` rewrites it instead of comparing.

use std::path::Path;

#[test]
fn committed_header_matches_the_code() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(dir.join("cbindgen.toml")).expect("cbindgen.toml");
    let expanded = Path::new(env!("CARGO_TARGET_TMPDIR")).join("gyrostat_ffi_macro_items.rs");
    let items = [
        gyrostat_ffi::ESTIMATOR_PARAMS_F32_SOURCE,
        gyrostat_ffi::ESTIMATOR_PARAMS_F64_SOURCE,
    ];
    std::fs::write(&expanded, items.join("\n")).expect("write the macro items' source");
    let mut generated = Vec::new();
    cbindgen::Builder::new()
        .with_src(&expanded)
        .with_crate(dir)
        .with_config(config)
        .generate()
        .expect("cbindgen parses src/lib.rs")
        .write(&mut generated);
    let generated = String::from_utf8(generated).expect("UTF-8 header");
    let path = dir.join("include/gyrostat.h");
    if std::env::var_os("GYROSTAT_BLESS").is_some() {
        std::fs::write(&path, &generated).expect("write include/gyrostat.h");
        return;
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == generated,
        "include/gyrostat.h differs from what cbindgen generates from src/lib.rs; regenerate with \
         GYROSTAT_BLESS=1 cargo test --release -p gyrostat-ffi --test header"
    );
}
