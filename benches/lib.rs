//! Empty: this package (`gyrostat-benches`) holds only bench targets (`Cargo.toml`), whose
//! dependencies are dev-dependencies so that `cargo test` builds none of them.
