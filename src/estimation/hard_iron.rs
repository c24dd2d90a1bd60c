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
//! converges slowly and whose innovations cannot show a jump. A mean normalised innovation
//! squared (1 s) above 25, or above 4 times its long-run mean (30 s) and above 1, means the
//! samples are not on one sphere (a magnet attached or removed, the field changed in the earth
//! frame, a gradient met while moving): the covariance is reset to the prior and the estimate
//! is not offered until it has converged again. The fit is fed only while the device turns
//! (the filter's gate): samples of a still sensor differ by noise alone, and a sphere fitted to noise about one point is a
//! small one centred on that point (the regressor's own noise would pass for information).
//!
//! Whether a converged offset is worth subtracting is tested on the data
//! ([`HardIron::explains_norm`]): over the last 30 s of fed samples, the variance of the squared
//! norm corrected by the offset the fit held *before* each sample (a prediction, not a fit to
//! the sample) against the raw squared norm's variance. An offset that removes more than half
//! of the variation is the main reason the norm changes as the device turns; one that removes
//! less is of the size of the model's other errors (soft iron, a field that varies over the
//! room, the sensor's calibration) and subtracting it does not make the field one sphere.
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
/// A mean normalised innovation squared above this resets the covariance …
const NIS_RESET: f64 = 25.0;
/// … and so does one above this multiple of its long-run mean (the noise model's `σ` fits no
/// sensor exactly: a quiet magnetometer's innovations are far below it, and a jump of the
/// offset must be judged against the sensor's own level) …
const NIS_RESET_RATIO: f64 = 4.0;
/// … when it is above this (a ratio of two small numbers is no evidence).
const NIS_RESET_MIN: f64 = 1.0;
/// Time constant (s of fed samples) of the long-run mean normalised innovation squared.
const NIS_BASE_TIME: f64 = 30.0;
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
    /// The long-run mean normalised innovation squared (time constant 30 s; 0 before the
    /// first sample).
    nis_base: T,
    /// The variance of one sample's `|B|²` (squared reference norms, squared) in use.
    r: T,
    /// The running means of `ν²/0.774` and of `HPHᵀ` over the settled samples within 2σ;
    /// `r` is their difference.
    nu2: T,
    hph: T,
    /// Running means and variances (time constant [`NIS_BASE_TIME`] of fed samples) of the
    /// squared norm `|u|²` and of the corrected one `|u − h|²` with the offset *before* the
    /// sample (a prediction): the norm's variation with and without the offset.
    raw_mean: T,
    raw_var: T,
    corr_mean: T,
    corr_var: T,
    /// Whether the means above have their first sample.
    steadiness_started: bool,
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
    }

    /// One field sample `b` (input units) standing for `dt` seconds of samples; `tau` (s) the
    /// random-walk time of the offset (it may drift by 1 % of the norm over `tau`).
    pub fn update(&mut self, b: Vec3<T>, dt: T, tau: T) {
        self.step(b, dt, tau, true);
    }

    /// [`HardIron::update`] without the norm's steadiness statistics
    /// ([`HardIron::norm_variances`] stay as they were): the light mode, which does not use
    /// them, saves their cost on a soft-float core.
    pub(crate) fn update_fit_only(&mut self, b: Vec3<T>, dt: T, tau: T) {
        self.step(b, dt, tau, false);
    }

    fn step(&mut self, b: Vec3<T>, dt: T, tau: T, steadiness: bool) {
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
        let k_base = super::lowpass::first_order_gain(dt, T::from_f64(NIS_BASE_TIME));
        // The norm's steadiness with and without the offset (out of sample: `h` before this
        // sample).
        if steadiness {
            let h = Vec3::new(self.x[0], self.x[1], self.x[2]);
            let corr = (u - h).norm_squared();
            if self.steadiness_started {
                let k = k_base;
                let (dr, dc) = (z - self.raw_mean, corr - self.corr_mean);
                self.raw_mean += k * dr;
                self.raw_var += k * (dr * dr - self.raw_var);
                self.corr_mean += k * dc;
                self.corr_var += k * (dc * dc - self.corr_var);
            } else {
                self.raw_mean = z;
                self.corr_mean = corr;
                self.steadiness_started = true;
            }
        }
        // The noise: E[ν²] = HPHᵀ + R.
        if hph < T::from_f64(NOISE_SETTLED) * self.r && nis < T::from_f64(NOISE_GATE) {
            let k = super::lowpass::first_order_gain(dt, T::from_f64(NOISE_TIME));
            self.nu2 += k * (innov * innov / T::from_f64(NOISE_GATE_VARIANCE) - self.nu2);
            self.hph += k * (hph - self.hph);
            let lo = T::from_f64(MEASUREMENT_STD_MIN * MEASUREMENT_STD_MIN);
            let hi = T::from_f64(MEASUREMENT_STD * MEASUREMENT_STD);
            self.r = (self.nu2 - self.hph).max(lo).min(hi);
        }
        let k_nis = super::lowpass::first_order_gain(dt, T::from_f64(NIS_TIME));
        self.nis += k_nis * (nis - self.nis);
        let base = self.nis_base;
        if self.nis > T::from_f64(NIS_RESET)
            || (base > T::ZERO
                && self.nis > T::from_f64(NIS_RESET_MIN)
                && self.nis > T::from_f64(NIS_RESET_RATIO) * base)
        {
            self.reset();
            return;
        }
        // The long-run level, from the samples the fit accepts (a jump resets before it can
        // raise the level much).
        self.nis_base = if base > T::ZERO {
            base + k_base * (nis - base)
        } else {
            nis
        };
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

    /// The variances (squared reference norms, squared) of the squared norm of the fed samples
    /// without and with the offset subtracted (running over 30 s of fed samples,
    /// the offset before each sample).
    pub fn norm_variances(&self) -> (T, T) {
        (self.raw_var, self.corr_var)
    }

    /// Whether the offset explains the norm's variation: the corrected squared norm's variance
    /// below half the raw one's (the offset removes most of the variation the rotation shows).
    pub fn explains_norm(&self) -> bool {
        let (raw, corr) = self.norm_variances();
        corr + corr < raw
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
