//! Magnetic disturbance detection: the measured field against a learned reference of its norm
//! and dip angle.
//!
//! An undisturbed field has, wherever the sensor turns, the same norm `|B|` and the same dip
//! (the angle below the horizontal, `δ = atan2(−B_up, |B_horizontal|)` in the earth frame; 69°
//! in Berlin). A nearby iron object or magnet changes one or both. The monitor keeps a
//! reference `(|B|_ref, δ_ref)`, learned from the first sample on and followed slowly (first
//! order, time constant `τ_ref`, [`first_order_gain`]) while undisturbed; a sample whose norm differs by more than a
//! fraction `th_B` or whose dip differs by more than `th_δ` is disturbed, and so is every sample
//! until the field has been back within the thresholds for `t_back` seconds.
//!
//! Recovery from a wrong reference (learned in a disturbed spot, or the sensor carried to
//! another place): a *candidate* field is tracked alongside; when a disturbed field keeps the
//! same norm and dip (within the same thresholds) for `t_new` seconds *while the sensor turns*
//! faster than `ω_new` (so that the field is homogeneous, not a magnet turning with the sensor,
//! whose reading would change with the orientation), the candidate becomes the reference.

use super::lowpass::first_order_gain;
use crate::Real;

/// The disturbance monitor's settings, declared with the estimator's parameters.
pub use super::params::FieldThresholds;

/// The state of the disturbance monitor (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FieldMonitor<T> {
    norm: T,
    dip: T,
    undisturbed_for: T,
    disturbed: bool,
    candidate_norm: T,
    candidate_dip: T,
    candidate_for: T,
    confirmed: bool,
    replaced: bool,
}

impl<T: Real> FieldMonitor<T> {
    /// A monitor whose reference is the first field seen (norm, dip in rad).
    pub fn new(norm: T, dip: T) -> Self {
        Self {
            norm,
            dip,
            undisturbed_for: T::ZERO,
            disturbed: false,
            candidate_norm: norm,
            candidate_dip: dip,
            candidate_for: T::ZERO,
            confirmed: false,
            replaced: false,
        }
    }

    /// Whether the last [`FieldMonitor::update`] replaced the reference by the candidate.
    #[inline]
    pub fn replaced(&self) -> bool {
        self.replaced
    }

    /// Whether the reference is confirmed: the field has agreed with it for `t_back` seconds
    /// at least once, or it was replaced by a new homogeneous field seen while turning. A
    /// reference learned from one sample is not (that sample may have been disturbed: every
    /// later sample of the true field then differs from it, and the heading it gave stays
    /// wrong until the reference is replaced).
    #[inline]
    pub fn confirmed(&self) -> bool {
        self.confirmed
    }

    /// The reference norm (input units) and dip (rad).
    #[inline]
    pub fn reference(&self) -> (T, T) {
        (self.norm, self.dip)
    }

    /// Whether the last field was disturbed.
    #[inline]
    pub fn disturbed(&self) -> bool {
        self.disturbed
    }

    /// How far a field of this norm and dip is from the reference: `||B| − |B|_ref|/|B|_ref +
    /// |δ − δ_ref|` (rad).
    pub fn deviation(&self, norm: T, dip: T) -> T {
        (norm - self.norm).abs() / self.norm + (dip - self.dip).abs()
    }

    /// Feeds the field of one sample (`norm`, `dip`), taken `dt` after the previous one while the
    /// sensor turns at `rate` (rad/s); returns whether it is disturbed.
    pub fn update(&mut self, norm: T, dip: T, dt: T, rate: T, th: &FieldThresholds<T>) -> bool {
        self.replaced = false;
        let k = first_order_gain(dt, th.reference_time_constant);
        let within = |n: T, d: T| (norm - n).abs() < th.norm * n && (dip - d).abs() < th.dip;
        if within(self.norm, self.dip) {
            self.undisturbed_for += dt;
            if self.undisturbed_for >= th.min_undisturbed {
                self.disturbed = false;
                self.confirmed = true;
                self.norm += k * (norm - self.norm);
                self.dip += k * (dip - self.dip);
            }
        } else {
            self.undisturbed_for = T::ZERO;
            self.disturbed = true;
        }
        if within(self.candidate_norm, self.candidate_dip) {
            if rate >= th.new_field_min_rate {
                self.candidate_for += dt;
            }
            self.candidate_norm += k * (norm - self.candidate_norm);
            self.candidate_dip += k * (dip - self.candidate_dip);
            if self.disturbed && self.candidate_for >= th.new_field_time {
                self.norm = self.candidate_norm;
                self.dip = self.candidate_dip;
                self.disturbed = false;
                self.confirmed = true;
                self.replaced = true;
                self.undisturbed_for = th.min_undisturbed;
            }
        } else {
            self.candidate_for = T::ZERO;
            self.candidate_norm = norm;
            self.candidate_dip = dip;
        }
        self.disturbed
    }
}
