//! Robustness of every public API family: the adversarial input campaign (`host_tests::campaign`,
//! tables in `ROBUSTNESS.md`), one module per layer, the named regressions and the f32 soak (the
//! whole map is in `host-tests/README.md`):
//!
//! - [`rotation`], [`propagation`], [`dynamics`], [`fixed`], [`sensor`]: the campaign per layer.
//! - [`regressions`]: every case the campaign once found, pinned to its typed error or value.
//! - [`second_campaign`]: the 17 reproducers of the second, independent campaign (issue 19).
//! - [`oracles`]: the oracle campaign: each `Ok` against an independent computation of it.
//! - [`soak`]: long f32 runs of the hot paths, watching the invariants.

mod dynamics;
mod estimation;
mod fixed;
mod oracles;
mod propagation;
mod regressions;
mod rotation;
mod second_campaign;
mod sensor;
mod soak;
mod third_campaign;
