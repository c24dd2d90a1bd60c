//! Empty: this package (`gyrostat-benches`) holds only bench targets (`Cargo.toml`), whose
//! dependencies are dev-dependencies so that `cargo test` builds none of them. `no_std`, so that
//! the root's commands for bare-metal targets (this package is a default member) build it too.
#![no_std]
