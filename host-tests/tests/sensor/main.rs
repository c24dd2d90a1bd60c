//! Tests of the sensor layer (`gyrostat::sensor`) and of the propagation on unequal intervals,
//! against independent std f64 computations:
//!
//! - [`timing`]: intervals, gaps, repeated and backwards timestamps, the 32-bit µs wrap.
//! - [`calibration`]: the model against plain-array arithmetic, inverse round trips, validation,
//!   f32/f64/Q1.30 agreement.
//! - [`mounting`]: the 24 remaps against the proper signed permutation matrices enumerated
//!   independently, parsing, mounting rotations and attitudes.
//! - [`raw`]: clipping flags and policies, LSB scales in every number format.
//! - [`variance`]: the streaming rest-noise statistics against a two-pass f64 computation.
//! - [`unequal`]: the 2-sample coning rule for unequal sub-intervals and Magnus-4 on unequal
//!   sample times, on jittered clocks against the closed-form coning motion.

mod calibration;
mod mounting;
mod raw;
mod timing;
mod unequal;
mod variance;

/// A small deterministic generator (xorshift64*), uniform in `[0, 1)`: inputs that do not repeat.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    pub fn next_u64(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.uniform()
    }
}
