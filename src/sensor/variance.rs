//! Streaming noise statistics of a sensor at rest: a running mean and variance per axis
//! (Welford), and the white noise density from them, in O(1) memory and time per sample.
//!
//! What firmware needs to measure its own sensor's noise without storing the log (a rest phase
//! at power-up, a calibration mode); the full Allan deviation of a log (white noise, bias
//! instability, rate random walk) is the host tools' (`characterize`).
//!
//! # Equations
//!
//! [`RunningVariance`] (Welford 1962; Knuth, TAOCP vol. 2, 4.2.2): after the `n`-th sample `x`,
//!
//! ```text
//! δ = x − μ_{n−1},   μ_n = μ_{n−1} + δ/n,   M_n = M_{n−1} + δ·(x − μ_n)
//! ```
//!
//! with `μ₀ = M₀ = 0`; the mean is `μ_n`, the (unbiased) sample variance `s² = M_n/(n − 1)`.
//! Unlike the textbook `(Σx² − (Σx)²/n)/(n − 1)` it does not cancel catastrophically when the
//! mean is large against the spread (an accelerometer axis at 9.8 m/s² with mm/s² noise in f32).
//!
//! [`RestNoise`] keeps one [`RunningVariance`] per axis and, beside it, the running mean of the
//! squared differences of successive samples, halved:
//!
//! ```text
//! σ_Δ² = ½ · mean_k (x_k − x_{k−1})²
//! ```
//!
//! the Allan variance at one sample (τ = 1/rate). For white noise both equal the per-sample
//! variance; a slow drift (temperature, a bias that wanders) inflates `s²` by its spread over
//! the whole window but `σ_Δ²` only by its change over one sample, so `σ_Δ` is the better
//! white-noise estimate on a long rest. The white noise density of an axis sampled at `rate` Hz
//! is then `N = σ_Δ/√rate` (per-sample standard deviation `N·√rate` for a sample that averages
//! the rate over its interval): unit/√Hz.
//!
//! # Errors
//!
//! A non-finite sample is [`Error::NonFinite`] and leaves the statistics as they were; a
//! statistic that needs more samples than pushed (a mean of none, a variance of one) is
//! [`Error::InvalidArgument`]; a count that would pass `u32::MAX` is [`Error::OutOfRange`]; a
//! rate that is not finite and > 0 is [`Error::InvalidArgument`].
//!
//! ```
//! use gyrostat::Vec3;
//! use gyrostat::sensor::RestNoise;
//!
//! let mut rest = RestNoise::<f32>::new();
//! for k in 0..100 {
//!     let wiggle = if k % 2 == 0 { 1e-3 } else { -1e-3 };
//!     rest.try_push(Vec3::new(0.01 + wiggle, -0.02, 0.0))?;
//! }
//! let mean = rest.mean()?;
//! assert!((mean.x - 0.01).abs() < 1e-6);
//! assert_eq!(rest.variance()?.y, 0.0);
//! # Ok::<(), gyrostat::Error>(())
//! ```

use crate::{Error, Real, Vec3};

/// Running mean and variance of one scalar (Welford; see the module documentation).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunningVariance<T> {
    n: u32,
    mean: T,
    m2: T,
}

impl<T: Real> Default for RunningVariance<T> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Real> RunningVariance<T> {
    /// No samples yet.
    pub const fn new() -> Self {
        Self {
            n: 0,
            mean: T::ZERO,
            m2: T::ZERO,
        }
    }

    /// Adds a sample: `δ = x − μ`, `μ ← μ + δ/n`, `M ← M + δ·(x − μ)`.
    ///
    /// # Errors
    /// [`Error::NonFinite`] for a NaN or infinite `x`, [`Error::OutOfRange`] past `u32::MAX`
    /// samples; the statistics are unchanged then.
    pub fn try_push(&mut self, x: T) -> Result<(), Error> {
        if !x.is_finite() {
            return Err(Error::NonFinite);
        }
        let n = self.n.checked_add(1).ok_or(Error::OutOfRange)?;
        let delta = x - self.mean;
        let mean = self.mean + delta / T::from_f64(f64::from(n));
        let m2 = self.m2 + delta * (x - mean);
        // A finite sample can still overflow the sums (|x| near the type's maximum).
        if !(mean.is_finite() && m2.is_finite()) {
            return Err(Error::NonFinite);
        }
        (self.n, self.mean, self.m2) = (n, mean, m2);
        Ok(())
    }

    /// The number of samples pushed.
    pub fn count(&self) -> u32 {
        self.n
    }

    /// The mean `μ_n`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] before the first sample.
    pub fn mean(&self) -> Result<T, Error> {
        if self.n == 0 {
            return Err(Error::InvalidArgument);
        }
        Ok(self.mean)
    }

    /// The unbiased sample variance `M_n/(n − 1)`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] with fewer than two samples.
    pub fn variance(&self) -> Result<T, Error> {
        if self.n < 2 {
            return Err(Error::InvalidArgument);
        }
        Ok(self.m2 / T::from_f64(f64::from(self.n - 1)))
    }

    /// The sample standard deviation `√(M_n/(n − 1))`.
    ///
    /// # Errors
    /// As [`Self::variance`].
    pub fn std_dev(&self) -> Result<T, Error> {
        Ok(self.variance()?.sqrt())
    }
}

/// The rest-noise statistics of a three-axis sensor: per axis the mean, the variance and the
/// successive-difference variance `σ_Δ²` (see the module documentation).
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RestNoise<T> {
    axes: [RunningVariance<T>; 3],
    last: Option<Vec3<T>>,
    /// Running mean of `½(x_k − x_{k−1})²` per axis.
    diff_mean: [T; 3],
    diffs: u32,
}

impl<T: Real> Default for RestNoise<T> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Real> RestNoise<T> {
    /// No samples yet.
    pub const fn new() -> Self {
        Self {
            axes: [RunningVariance::new(); 3],
            last: None,
            diff_mean: [T::ZERO; 3],
            diffs: 0,
        }
    }

    /// Adds a sample of the three axes.
    ///
    /// # Errors
    /// [`Error::NonFinite`] when an axis is NaN or infinite (or a sum overflows),
    /// [`Error::OutOfRange`] past `u32::MAX` samples; the statistics are unchanged then.
    pub fn try_push(&mut self, v: Vec3<T>) -> Result<(), Error> {
        let x = [v.x, v.y, v.z];
        let mut axes = self.axes;
        for (a, &xi) in axes.iter_mut().zip(&x) {
            a.try_push(xi)?;
        }
        let (mut diff_mean, mut diffs) = (self.diff_mean, self.diffs);
        if let Some(last) = self.last {
            diffs = diffs.checked_add(1).ok_or(Error::OutOfRange)?;
            let k = T::from_f64(f64::from(diffs));
            for ((m, &xi), li) in diff_mean.iter_mut().zip(&x).zip([last.x, last.y, last.z]) {
                let d = xi - li;
                let half_sq = T::HALF * d * d;
                *m += (half_sq - *m) / k;
                if !m.is_finite() {
                    return Err(Error::NonFinite);
                }
            }
        }
        (self.axes, self.diff_mean, self.diffs, self.last) = (axes, diff_mean, diffs, Some(v));
        Ok(())
    }

    /// Forgets every sample (a new rest phase).
    pub fn reset(&mut self) {
        *self = Self::new();
    }

    /// The number of samples pushed.
    pub fn count(&self) -> u32 {
        self.axes[0].count()
    }

    /// The per-axis running statistics.
    pub fn axes(&self) -> &[RunningVariance<T>; 3] {
        &self.axes
    }

    /// The mean of each axis (a gyro's: its bias at rest).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] before the first sample.
    pub fn mean(&self) -> Result<Vec3<T>, Error> {
        let [x, y, z] = &self.axes;
        Ok(Vec3::new(x.mean()?, y.mean()?, z.mean()?))
    }

    /// The sample variance of each axis.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] with fewer than two samples.
    pub fn variance(&self) -> Result<Vec3<T>, Error> {
        let [x, y, z] = &self.axes;
        Ok(Vec3::new(x.variance()?, y.variance()?, z.variance()?))
    }

    /// The sample standard deviation of each axis.
    ///
    /// # Errors
    /// As [`Self::variance`].
    pub fn std_dev(&self) -> Result<Vec3<T>, Error> {
        let v = self.variance()?;
        Ok(Vec3::new(v.x.sqrt(), v.y.sqrt(), v.z.sqrt()))
    }

    /// The successive-difference variance `σ_Δ² = ½·mean (x_k − x_{k−1})²` of each axis (the
    /// Allan variance at one sample).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] with fewer than two samples.
    pub fn difference_variance(&self) -> Result<Vec3<T>, Error> {
        if self.diffs == 0 {
            return Err(Error::InvalidArgument);
        }
        let [x, y, z] = self.diff_mean;
        Ok(Vec3::new(x, y, z))
    }

    /// The white noise density of each axis sampled at `rate` Hz, `N = σ_Δ/√rate`
    /// (unit/√Hz: rad/s/√Hz for a gyro in rad/s).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] with fewer than two samples or a rate that is not finite and
    /// > 0.
    pub fn noise_density(&self, rate: T) -> Result<Vec3<T>, Error> {
        if !(rate.is_finite() && rate > T::ZERO) {
            return Err(Error::InvalidArgument);
        }
        let v = self.difference_variance()?;
        Ok(Vec3::new(
            (v.x / rate).sqrt(),
            (v.y / rate).sqrt(),
            (v.z / rate).sqrt(),
        ))
    }
}
