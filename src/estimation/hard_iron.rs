//! Hard iron estimated online: a constant field offset in the sensor frame (a magnet or
//! magnetised steel fixed to the device), found from the field's norm staying constant while
//! the device turns.
//!
//! In a homogeneous field `B_e` the sensor reads `B = Rᵀ B_e + h`: the samples lie on a sphere
//! of radius `|B_e|` about `h`, whatever the attitudes. With `c = |B_e|² − |h|²` the sphere is
//! linear in `x = (h, c)`: `|B|² = 2 Bᵀh + c`. [`HardIron`] is a four-state Kalman filter on
//! that measurement (`z = |B|²`, `H = (2Bᵀ, 1)`), in units of a reference norm `n₀` (the first
//! field's) so that the numbers stay near 1 in f32. Its covariance says what the rotation has
//! made observable: turning about one axis only leaves `h` along that axis unknown, and its
//! variance stays large; a slow random walk (1 % of the norm per `τ_h`) follows a drifting
//! offset. The measurement's noise is measured online: from the innovations `ν` within 2σ
//! while the fit is settled (`HPHᵀ` below 4 R), `R = E[ν²]/0.774 − E[HPHᵀ]` (0.774 the variance
//! of a unit normal truncated at ±2σ), between 0.2 % and 8 % of the squared norm: a fixed `R`
//! that suits one magnetometer is 10–100 times the variance of a quieter one, whose fit then
//! converges slowly and whose innovations cannot show a jump.
//!
//! The regressor is noisy: the sample's white noise `n` (σ per axis, in reference norms) is in
//! `H` as well as in `z`, and `E[H ν] = (4σ²(u − h), 0)` (errors in variables, the algebraic
//! sphere fit's bias): a filter that takes `H` as exact adds `P⁺(4σ²(u − h), 0)/R` to its
//! estimate on every sample, which pulls the centre towards the samples in the directions the
//! recent rotation has not covered, the more the more samples a second it is fed. It is removed
//! while the fit is settled (`HPHᵀ` below 4 R), `x ← x − P⁺(4σ²(u − h), 0)/R` with
//! `4σ²/R = (W/R)/r²`: `r² = c + |h|²` the squared radius, `W` the white part of the noise, half
//! the mean square of the change of `|u − h|²` between consecutive fed samples (the sensor's
//! noise, not the model's slowly varying error that `R` also holds; at most `R`).
//!
//! The fit is judged by its own drift (time in seconds of fed samples, whatever the rates): once
//! every offset component's variance is below the offer's bound the estimate is anchored, and
//! every 4 s a component that moved from the anchor by more than 3 standard deviations of a
//! consistent fit's move, `(h_i − h_a,i)² > 9·max(P_a,ii − P_ii + w, w)` (`P_a − P` what the
//! samples since have taken out of the estimate's variance, `w = (0.01)²·T/τ_h` the random walk
//! over the window), means the samples are not on one sphere (a magnet attached or removed, the
//! field changed in the earth frame, a gradient met while moving): the covariance is reset to
//! the prior and the estimate is not offered until it has converged again. Before the fit has
//! settled the same test runs over 1 s windows (a magnet attached while the fit still
//! converges), and a mean normalised innovation squared (1 s) above 25 resets at any time. A
//! test on the innovations against a level learned from the log would judge a converged fit
//! against the time its noise model was still converging. The fit is fed only while the device
//! turns (the filter's gate): samples of a still sensor differ by noise alone, and a sphere
//! fitted to noise about one point is a small one centred on that point (the regressor's own
//! noise would pass for information).
//!
//! A converged offset is subtracted by the heading update only when it is larger than the field
//! monitor's norm threshold (`field.norm` of the norm; `Estimator`): a smaller one is of the size
//! of the model's other errors (soft iron, a field that varies over the room, the sensor's
//! calibration), which subtracting it would not remove.
//!
//! A field that changes in the earth frame without translation (a stationary magnet seen from
//! one place) is still a sphere, about `h` and of another radius: the fit keeps `h` and only
//! `c` moves; the heading's disturbance monitor ([`super::FieldMonitor`]) keeps rejecting it.

use crate::{Real, Vec3};

/// The prior standard deviation of each offset component, in reference norms.
const PRIOR_OFFSET: f64 = 2.0;
/// The prior standard deviation of `c`, in squared reference norms.
const PRIOR_C: f64 = 4.0;
/// Standard deviation of one sample's `|B|²` (squared reference norms) until the fit has
/// measured it: sensor noise and the model's error (soft iron, a field not quite homogeneous,
/// axes sampled at slightly different times in fast rotation), about 4 % of the norm.
const MEASUREMENT_STD: f64 = 0.08;
/// The least standard deviation the measured noise may take (0.1 % of the norm: the model's
/// error is never smaller).
const MEASUREMENT_STD_MIN: f64 = 0.002;
/// Time constant (s of fed samples) of the measured noise.
const NOISE_TIME: f64 = 3.0;
/// The noise is measured from innovations within 2σ …
const NOISE_GATE: f64 = 4.0;
/// … whose mean square is this fraction of the variance (a unit normal variable truncated at
/// ±2σ: `1 − 4φ(2)/(2Φ(2) − 1)`) …
const NOISE_GATE_VARIANCE: f64 = 0.774;
/// … while the fit's own variance `HPHᵀ` is below this multiple of the noise's.
const NOISE_SETTLED: f64 = 4.0;
/// How far (reference norms) the offset may drift within the random-walk time `τ_h`; `c`
/// twice as far.
const DRIFT: f64 = 0.01;
/// Time constant (s) of the mean normalised innovation squared.
const NIS_TIME: f64 = 1.0;
/// A mean normalised innovation squared above this resets the covariance.
const NIS_RESET: f64 = 25.0;
/// The drift test's window (s of fed time): the settled fit's estimate is compared with the
/// one this long before …
const DRIFT_WINDOW: f64 = 4.0;
/// The drift test's window (s of fed time) while the fit has not settled: an offset that
/// changes while the fit is still converging (a magnet attached in the first seconds) is a
/// move of several standard deviations of `P_a − P` within a second …
const DRIFT_WINDOW_UNSETTLED: f64 = 1.0;
/// … and either resets the covariance when a component moved more than this many standard
/// deviations of a consistent fit's move (`P_a − P` plus the random walk).
const DRIFT_K: f64 = 3.0;
/// The estimate is offered when the mean normalised innovation squared is below this …
const NIS_READY: f64 = 3.0;
/// … and each offset component's standard deviation below this (reference norms).
const READY_STD: f64 = 0.01;

/// The hard-iron estimator's state (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HardIron<T> {
    /// The reference norm `n₀` (input units); zero before the first sample.
    scale: T,
    /// `(h_x, h_y, h_z, c)` in units of `n₀` (and `n₀²`).
    x: [T; 4],
    p: [[T; 4]; 4],
    nis: T,
    /// The drift test's anchor: the offset estimate (reference norms) and its per-axis
    /// variances when it was taken, and the fed time since (s); `anchored` false until the fit
    /// has settled (and after each reset).
    anchor: [T; 3],
    anchor_var: [T; 3],
    anchor_time: T,
    anchored: bool,
    /// Whether an anchor is held while the fit has not settled (the 1 s window).
    early: bool,
    /// The previous fed sample (units of `n₀`) and whether it was the previous feed.
    prev: Vec3<T>,
    prev_valid: bool,
    /// The white part of the noise (squared reference norms, squared): half the running mean
    /// square of the change of `|u − h|²` between consecutive fed samples; `white_n` counts
    /// its samples (a plain mean over the first).
    white: T,
    white_n: u8,
    /// The variance of one sample's `|B|²` (squared reference norms, squared) in use.
    r: T,
    /// The running means of `ν²/0.774` and of `HPHᵀ` over the settled samples within 2σ;
    /// `r` is their difference.
    nu2: T,
    hph: T,
}

impl<T: Real> HardIron<T> {
    /// Starts on the first field sample `b` (input units): no offset, the prior covariance.
    pub fn new(b: Vec3<T>) -> Self {
        let n = b.norm();
        let mut s = Self {
            // A reference norm that is zero, subnormal or not finite is no scale: the fit
            // waits for a usable sample.
            scale: if n.is_finite() && n > T::EPSILON {
                n
            } else {
                T::ZERO
            },
            ..Self::default()
        };
        s.x = [T::ZERO, T::ZERO, T::ZERO, T::ONE];
        s.r = T::from_f64(MEASUREMENT_STD * MEASUREMENT_STD);
        s.nu2 = s.r;
        s.reset();
        s
    }

    fn reset(&mut self) {
        let po = T::from_f64(PRIOR_OFFSET * PRIOR_OFFSET);
        let pc = T::from_f64(PRIOR_C * PRIOR_C);
        self.p = [[T::ZERO; 4]; 4];
        for i in 0..3 {
            if let Some(row) = self.p.get_mut(i)
                && let Some(v) = row.get_mut(i)
            {
                *v = po;
            }
        }
        self.p[3][3] = pc;
        self.nis = T::ZERO;
        self.anchored = false;
        self.early = false;
        self.prev_valid = false;
    }

    /// A feed not taken (the device not turning): the next sample does not follow the last
    /// one fed, and their difference is not used for the white noise.
    pub fn idle(&mut self) {
        self.prev_valid = false;
    }

    /// One field sample `b` (input units) standing for `dt` seconds of samples; `tau` (s) the
    /// random-walk time of the offset (it may drift by 1 % of the norm over `tau`).
    pub fn update(&mut self, b: Vec3<T>, dt: T, tau: T) {
        self.step(b, dt, tau, true);
    }

    /// [`HardIron::update`] without the white-noise statistics and the regressor-noise bias
    /// removal (module docs): the light mode saves their cost on a soft-float core, and its fit
    /// keeps the algebraic fit's bias (it still passes the hard-iron tests of
    /// `tools/tests/tools/synthesize.rs`).
    pub(crate) fn update_fit_only(&mut self, b: Vec3<T>, dt: T, tau: T) {
        self.step(b, dt, tau, false);
    }

    fn step(&mut self, b: Vec3<T>, dt: T, tau: T, bias_removal: bool) {
        if self.scale <= T::ZERO {
            *self = Self::new(b);
            return;
        }
        let u = b.scale(T::ONE / self.scale);
        if !(u.norm_squared().is_finite()) {
            // A field far beyond the reference (garbage): not a sample of the sphere.
            return;
        }
        // The random walk.
        let grow = dt / tau;
        let po = T::from_f64(DRIFT * DRIFT) * grow;
        for i in 0..3 {
            self.p[i][i] += po;
        }
        self.p[3][3] += T::from_f64(4.0 * DRIFT * DRIFT) * grow;
        // z = |u|² = 2uᵀh + c.
        let hv = [u.x + u.x, u.y + u.y, u.z + u.z, T::ONE];
        let z = u.norm_squared();
        let pred = hv[0] * self.x[0] + hv[1] * self.x[1] + hv[2] * self.x[2] + self.x[3];
        let innov = z - pred;
        let mut ph = [T::ZERO; 4];
        for (phi, row) in ph.iter_mut().zip(self.p.iter()) {
            *phi = row[0] * hv[0] + row[1] * hv[1] + row[2] * hv[2] + row[3] * hv[3];
        }
        // One raw sample's error, however long the time it stands for: the fit sees single
        // samples, not averages.
        let hph = hv[0] * ph[0] + hv[1] * ph[1] + hv[2] * ph[2] + hv[3] * ph[3];
        let s = hph + self.r;
        if !(s > T::ZERO && s.is_finite() && innov.is_finite()) {
            self.reset();
            return;
        }
        let nis = innov * innov / s;
        let settled = hph < T::from_f64(NOISE_SETTLED) * self.r;
        // The white noise, from consecutive samples: both lie on the sphere, so the change of
        // `|u − h|²` between them is their noises' radial parts (`E[d²] = 2·4σ²r²`) and the
        // model's error over one feed step, which changes slowly with the attitude. A change
        // beyond `2√(2R)` is a jump, not noise; only while the fit is settled.
        if bias_removal {
            let h = Vec3::new(self.x[0], self.x[1], self.x[2]);
            if self.prev_valid && settled {
                let d = (u - h).norm_squared() - (self.prev - h).norm_squared();
                let d2 = d * d;
                if d2 < T::from_f64(8.0) * self.r {
                    let n = T::from_f64(f64::from(self.white_n) + 1.0);
                    let k = super::lowpass::first_order_gain(dt, T::from_f64(NOISE_TIME))
                        .max(T::ONE / n);
                    self.white += k * (d2 * T::HALF - self.white);
                    self.white_n = self.white_n.saturating_add(1);
                }
            }
            self.prev = u;
            self.prev_valid = true;
        }
        // The noise: E[ν²] = HPHᵀ + R.
        if settled && nis < T::from_f64(NOISE_GATE) {
            let k = super::lowpass::first_order_gain(dt, T::from_f64(NOISE_TIME));
            self.nu2 += k * (innov * innov / T::from_f64(NOISE_GATE_VARIANCE) - self.nu2);
            self.hph += k * (hph - self.hph);
            let lo = T::from_f64(MEASUREMENT_STD_MIN * MEASUREMENT_STD_MIN);
            let hi = T::from_f64(MEASUREMENT_STD * MEASUREMENT_STD);
            self.r = (self.nu2 - self.hph).max(lo).min(hi);
        }
        let k_nis = super::lowpass::first_order_gain(dt, T::from_f64(NIS_TIME));
        self.nis += k_nis * (nis - self.nis);
        if self.nis > T::from_f64(NIS_RESET) {
            self.reset();
            return;
        }
        // The regressor's own noise: `H` holds the sample's noise as `z` does, so each update
        // pulls the centre towards the sample by `P⁺·4σ²(u − h)/R` (the algebraic sphere fit's
        // bias); with `4σ²/R = (W/R)/r²` (`W` the white part of the noise, at most `R`; `r` the
        // sphere's radius) it is removed while the fit is settled.
        let w = if settled && bias_removal && self.r > T::ZERO {
            let radius2 =
                self.x[3] + self.x[0] * self.x[0] + self.x[1] * self.x[1] + self.x[2] * self.x[2];
            let ratio = (self.white / self.r).min(T::ONE);
            ratio / radius2.max(T::from_f64(0.25))
        } else {
            T::ZERO
        };
        // Formed with the offset before the update; only when it is removed.
        let g = (w > T::ZERO).then(|| {
            [
                w * (u.x - self.x[0]),
                w * (u.y - self.x[1]),
                w * (u.z - self.x[2]),
            ]
        });
        let inv = T::ONE / s;
        for (xi, &phi) in self.x.iter_mut().zip(ph.iter()) {
            *xi += phi * inv * innov;
        }
        // P ← P − (Ph)(Ph)ᵀ/s, the upper triangle computed and mirrored (symmetric by
        // construction).
        // Index loops over constant ranges: the bounds are visible to the optimiser at every
        // level (an `enumerate().skip(i)` left a bounds check in the size-optimised M0 build).
        #[allow(clippy::needless_range_loop)]
        for i in 0..4 {
            let ki = ph[i] * inv;
            for j in i..4 {
                let v = self.p[i][j] - ki * ph[j];
                self.p[i][j] = v;
                self.p[j][i] = v;
            }
        }
        if let Some(g) = g {
            for (xi, row) in self.x.iter_mut().zip(self.p.iter()) {
                *xi -= row[0] * g[0] + row[1] * g[1] + row[2] * g[2];
            }
        }
        self.drift_test(dt, tau);
    }

    /// The fit's consistency judged by its own drift (module docs): once settled (each offset
    /// component's variance below the offer's bound) the estimate is anchored; each time `T_w`
    /// of fed time has passed, a component that moved further than a consistent fit's move
    /// allows, `(h_i − h_a,i)² > k²·max(P_a,ii − P_ii + w, w)` with `w = DRIFT²·T_w/τ_h`, resets
    /// the covariance, else the anchor moves to the estimate. Before the fit has settled, the
    /// same over `T_w` = 1 s from an anchor taken at the first sample after a reset.
    fn drift_test(&mut self, dt: T, tau: T) {
        let p = [self.p[0][0], self.p[1][1], self.p[2][2]];
        if !self.anchored {
            let settle = T::from_f64(READY_STD * READY_STD);
            if p[0] < settle && p[1] < settle && p[2] < settle {
                self.anchor_at(p);
                self.anchored = true;
                return;
            }
            if !self.early {
                self.anchor_at(p);
                self.early = true;
                return;
            }
            self.anchor_time += dt;
            if self.anchor_time < T::from_f64(DRIFT_WINDOW_UNSETTLED) {
                return;
            }
        } else {
            self.anchor_time += dt;
            if self.anchor_time < T::from_f64(DRIFT_WINDOW) {
                return;
            }
        }
        let walk = T::from_f64(DRIFT * DRIFT) * self.anchor_time / tau;
        let k2 = T::from_f64(DRIFT_K * DRIFT_K);
        let mut moved = false;
        for (((&xi, &ai), &vi), &pi) in self
            .x
            .iter()
            .zip(self.anchor.iter())
            .zip(self.anchor_var.iter())
            .zip(p.iter())
        {
            let d = xi - ai;
            let var = (vi + walk - pi).max(walk);
            if d * d > k2 * var {
                moved = true;
            }
        }
        if moved {
            self.reset();
        } else {
            self.anchor_at(p);
        }
    }

    /// The drift test's anchor moved to the current estimate, its per-axis variances `p`.
    fn anchor_at(&mut self, p: [T; 3]) {
        self.anchor = [self.x[0], self.x[1], self.x[2]];
        self.anchor_var = p;
        self.anchor_time = T::ZERO;
    }

    /// The offset (input units), when the fit has converged: each component's standard
    /// deviation below 1 % of the reference norm and the samples consistent with one sphere.
    pub fn offset(&self) -> Option<Vec3<T>> {
        let ready = T::from_f64(READY_STD * READY_STD);
        let ok = self.scale > T::ZERO
            && self.nis < T::from_f64(NIS_READY)
            && self.p[0][0] < ready
            && self.p[1][1] < ready
            && self.p[2][2] < ready;
        ok.then(|| Vec3::new(self.x[0], self.x[1], self.x[2]).scale(self.scale))
    }

    /// The mean normalised innovation squared of the recent samples (about 1 when they lie on
    /// one sphere as the noise model says; time constant 1 s).
    pub fn consistency(&self) -> T {
        self.nis
    }

    /// The standard deviation of one sample's `|B|²` as measured by the fit, relative to the
    /// squared reference norm (about `2σ/|B|` for white noise of `σ` per axis).
    pub fn noise(&self) -> T {
        self.r.max(T::ZERO).sqrt()
    }

    /// The offset estimate (input units) and each component's standard deviation, converged
    /// or not.
    pub fn estimate(&self) -> (Vec3<T>, Vec3<T>) {
        let sd = |v: T| v.max(T::ZERO).sqrt() * self.scale;
        (
            Vec3::new(self.x[0], self.x[1], self.x[2]).scale(self.scale),
            Vec3::new(sd(self.p[0][0]), sd(self.p[1][1]), sd(self.p[2][2])),
        )
    }
}
