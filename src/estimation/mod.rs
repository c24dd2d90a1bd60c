//! Attitude estimation from a real IMU: the gyroscope propagation corrected by the
//! accelerometer (inclination) and the magnetometer (heading only), with the gyroscope bias
//! estimated online.
//!
//! ```
//! use gyrostat::estimation::{Estimator, Params};
//! use gyrostat::Vec3;
//! let mut f = Estimator::<f32>::try_new(Params::default())?;
//! // One sample: body rate (rad/s), specific force (m/s²), field (any unit), step (s).
//! let out = f.update_9d(
//!     Vec3::new(0.01, -0.02, 0.0),
//!     Vec3::new(0.0, 0.0, 9.81),
//!     Vec3::new(0.0, 15.8, -40.7),
//!     0.0035,
//! )?;
//! assert!(out.initialized); // the first sample sets the attitude (TRIAD)
//! let q = f.attitude(); // sensor → earth (ENU: x east, y magnetic north, z up)
//! assert!(q.rotate(Vec3::Z).z > 0.999);
//! # Ok::<(), gyrostat::Error>(())
//! ```
//!
//! # The filter
//! Frames: the attitude `q̂` maps the sensor frame to the earth frame (ENU by default, NED with
//! [`EarthFrame::Ned`]); it is kept as `q̂ = q_c ⊗ q_g`, where `q_g` (sensor → an almost
//! inertial "gyroscope frame") is the bias-corrected strapdown attitude and `q_c` (gyroscope
//! frame → earth) collects every correction.
//!
//! 1. **Prediction** — the propagation core: `q_g ← q_g ⊗ exp(φ)`
//!    ([`crate::UnitQuat::mul_exp_unchecked`], the update kernel of [`crate::propagation`], with
//!    the fast renormalisation), `φ` the step's rotation (bias removed) over the per-sample `Δt`
//!    of the time stamps. Rate samples take [`Params::rate_rule`] ([`RateRule`]): by default
//!    (both modes) the propagation module's unequal-interval Magnus-4, the rates at the step's
//!    Gauss nodes from the backward cubic interpolant through the last four samples at their
//!    own times ([`crate::propagation::kernels::magnus4_step_unequal`]'s interpolation; order
//!    4 on a jittered clock), falling back to the linear interpolant at the start, after a
//!    saturated sample and across a gap; CF4 or the trapezoid (`ω̄ = (ω_prev + ω)/2`, order 2)
//!    on request. An increment, [`Estimator::update_increment`], is a
//!    mean already, and takes the one-plus-previous coning rule of
//!    [`crate::propagation::coning`] with the previous
//!    increment. The samples' checks are the shared ones: the step limit of
//!    [`crate::step_limit`] (at most half a turn per step) and the clip policy of
//!    [`crate::sensor::raw`] (the gyroscope saturated at [`Params::gyro_range`],
//!    [`crate::sensor::ClipPolicy::Saturate`]). The
//!    output, [`Estimator::attitude`], is carried forward by the gyroscope's own delay
//!    ([`Params::gyro_delay`]) at the rate extrapolated to the middle of that delay from the
//!    last two samples (the carried rotation `∫ω` to second order). The strapdown attitude is
//!    a plain [`crate::UnitQuat`] ([`Estimator::try_new`]) or, for an f32 filter propagating
//!    for long between corrections, the [`crate::propagation::CompensatedAttitude`]
//!    ([`Estimator::try_new_compensated`]: the updates' rounding carried).
//! 2. **Error covariance** — an error-state (multiplicative) Kalman filter over
//!    `x = (δθ, δb)`: `δθ` the attitude error in the earth frame (`q = exp(δθ) ⊗ q̂`), `δb` the
//!    bias error. Its closed-form transition over a step is `Φ = [[I, −R̂Δt], [0, I]]` (an
//!    earth-frame error is not turned by the motion; a bias error turns the estimate by
//!    `−R̂ δb Δt`) and `Q = diag((σ_g² + (s|ω|)²)Δt·I, σ_b²Δt/τ_b·I)`: white rate noise plus a
//!    rate-proportional term for scale-factor and misalignment errors ([`covariance`]); that
//!    term is formed from the step's rotation `θ = |ω|Δt` as `θ²·min(s²/Δt, 1)` (no overflow
//!    where `|ω|` is huge and `Δt` tiny; at most an error the size of the rotation). The
//!    updates keep `P` symmetric and positive semi-definite in floating point (Joseph form for
//!    the measured component's row and column, [`Covariance::update_component`]), and every
//!    predict bounds the attitude variances by π² and the bias variances by the clip
//!    ([`Covariance::bound`]); a measurement whose variance is infinite (a subnormal `Δt` in
//!    `σ²·τ/Δt`) carries no information and is skipped.
//! 3. **Inclination** — the specific force is rotated into the gyroscope frame and low-passed
//!    there ([`LowPass`], time constant `τ_a`): in an inertial frame the non-gravitational
//!    acceleration of any bounded motion integrates to a change of velocity, so it averages out
//!    (translation, vibration, taps), while gravity stays. The tilt between the filtered
//!    vector (mapped to the earth frame by `q_c`) and the vertical is the measurement of
//!    `(δθ_x, δθ_y)`; two scalar Kalman updates apply it (and, through the cross covariance,
//!    correct the bias in motion). Its variance `σ_a²·τ_c/Δt` is the continuous-time
//!    measurement of spectral density `σ_a²·τ_c` (an error correlated over `τ_c` counts as one
//!    independent measurement per `τ_c`, whatever the rate), and the low-pass gains are exact
//!    for each step ([`first_order_gain`]). A filtered vector whose norm still differs
//!    from gravity by more than [`Params::accel_reject`] (a sustained acceleration) is not used.
//!    The first `τ_a` after initialisation the low-pass holds the running mean of the samples
//!    ([`LowPass::mean_update`]; also after a restart) and the inclination is taken from it in
//!    full: the initial attitude came from one sample, whose noise `σ_n·√(f/2)` grows with the
//!    sample rate `f`, and the mean shares its offset with less of its noise (a tactical IMU at
//!    1 kHz: 0.31° from the first sample, 0.18° left when moving starts 5 s later without it).
//! 4. **Rest** — [`RestDetector`]: at rest the mean rate is a direct measurement of the bias
//!    (three scalar updates of `δb`). A steady turn slower than the largest bias is not rest:
//!    the specific force (or the field's horizontal direction) drifts, the detector then calls
//!    it a turn, and what that rest taught the bias is undone when the gyroscope, relative to
//!    the bias before the rest, turned by half the detector's angle (a magnet passing a still
//!    sensor turns the field's direction but not the gyroscope). A tilt or heading innovation
//!    that persists beyond three standard deviations raises its variance (a tilt learned from
//!    a sustained acceleration, a heading from another field, is then corrected at once).
//! 5. **Heading** (9D) — the field in the earth frame, `m = R̂ B`, gives the heading error
//!    `ψ = atan2(m_x, m_y)`. The measurement model `ψ = δθ_z + tan(dip)·δθ_y` includes the
//!    heading error a tilt error causes (the field's vertical part turned into the horizontal
//!    plane), but the gain acts on `δθ_z` alone and the correction is a turn about the earth
//!    vertical: a magnetic disturbance can never tilt the estimate or move the bias
//!    ([`Covariance::update_heading`]). [`FieldMonitor`] compares the field's norm and dip with
//!    a learned reference; a disturbed field is rejected, or with
//!    [`Params::mag_disturbance_weight`] `> 0` used with its variance raised by the size of the
//!    disturbance, so that a long disturbance (whose gyroscope-only heading uncertainty keeps
//!    growing) is eventually weighed against it rather than cut off; a new homogeneous field
//!    seen while turning replaces the reference (recovery).
//! 6. **Initialisation** — the first usable sample: [`attitude_from_gravity_and_field`]
//!    (TRIAD) or, without a field, [`attitude_from_gravity`].
//!
//! Bad input: a non-finite gyroscope sample, a step that is not finite and positive, or a rate
//! turning by more than half a turn in a step is an `Err` and leaves the state untouched; a
//! non-finite, saturated ([`Params::accel_range`]) or zero accelerometer or magnetometer sample
//! is skipped and reported in the [`Outcome`]; a saturated gyroscope sample is clipped and its
//! uncertainty added. The state never becomes NaN.
//!
//! # How the design was chosen
//! Every choice below was kept only when it won on all of: the 16 shared BROAD trials at
//! their 285.7 Hz, the same trials decimated (every 2nd, 3rd and 6th row, nothing else
//! changed: 142.9, 95.2, 47.6 Hz; `broad_estimate --every N`, VQF on the same rows with
//! `benches/broad/run_peers.py --every N`), both halves of the split A = 01 05 09 14 21 26 30
//! 34 and B = 03 07 11 16 24 28 32 36, and the synthetic grid (`benches/synthetic/grid.py`:
//! rate × sensor grade × disturbance × seed, logs with exact truth). Scores: mean total RMSE
//! (°, BROAD's metric, online from the first sample, 9D).
//!
//! **The structure** (an MEKF fed the inertial-frame low-passed accelerometer, a tilt-coupled
//! heading update, the field monitor) was chosen earlier on the full-rate trials: against a raw
//! per-sample accelerometer (5.88) and fixed complementary gains (1.796) it gave 1.750; the
//! inertial-frame low-pass removes most non-gravitational acceleration before the update, and
//! the covariance lets the heading lean on the magnetometer in fast motion and on the gyroscope
//! in slow motion.
//!
//! **Rate independence** (each row adds one change; all 16 trials at 285.7 / 142.9 / 95.2 /
//! 47.6 Hz; VQF 2.1.2 on the same rows: 2.370 / 2.313 / 2.389 / 3.143):
//!
//! | design | 285.7 Hz | 142.9 Hz | 95.2 Hz | 47.6 Hz |
//! |---|---|---|---|---|
//! | before: gains `Δt/(τ + Δt)`, delay candidates 0–7 samples, rate at the step's end | 1.559 | 1.529 | 1.699 | 2.618 |
//! | exact gains `1 − exp(−Δt/τ)`, delay history on a time grid (candidates 0–50 ms) | 1.555 | 1.533 | 1.700 | 2.673 |
//! | trapezoid: the mean of the two rate samples over a step | 1.691 | 1.692 | 1.741 | 2.073 |
//! | output carried forward by the gyroscope's delay, 2.9 ms (datasheet) | 1.356 | 1.356 | 1.406 | 1.796 |
//! | hard iron estimated online (below) | 1.223 | 1.238 | 1.279 | 1.671 |
//! | Magnus-4 on the Gauss-node rates ([`RateRule`], issue 27; the row above re-measured: 1.215 / 1.235 / 1.271 / 1.664) | **1.216** | **1.231** | **1.238** | **1.290** |
//!
//! The cause of the rate dependence, found by experiment: the estimated magnetometer delay grew
//! with the step (about 13 ms at 285.7 Hz, 22 ms at 47.6 Hz), by half a step. A rate sample
//! applied over the step that *ends* at it (the exponential map with the end sample) puts the
//! strapdown attitude half a step ahead of the motion; the field, compared with it, looks half
//! a step late. With the trapezoid the estimated delay is 10–14 ms at every rate, and the
//! inclination error at 47.6 Hz drops from 1.494° to 1.171°. Half a step ahead had, at
//! 285.7 Hz, hidden the gyroscope's own delay behind BROAD's optical reference (the trapezoid
//! alone loses there, 1.555 → 1.691): carrying the output forward by `d_g` at the last rate
//! (`broad_estimate --lead`, a research flag) finds the best `d_g` at 4–5 ms at 285.7 Hz *and*
//! at 47.6 Hz (1.315 / 1.741 at 5 ms), a delay in seconds, as a sensor's group delay is. The
//! default is the datasheet's 2.9 ms ([`Params`]), not the 4.5 ms that fits BROAD (1.303 at
//! full rate; a user with BROAD's sensor would set it). The exact gains and the time grid
//! change little at these rates (they matter where `Δt/τ` is large) but make the filter the
//! same at every rate by construction. On the synthetic grid (consumer and industrial presets,
//! none / translation / vibration / passing magnet / fixed magnet, 2 seeds, 25–1000 Hz) the
//! new filter equals the old one from 100 Hz up and gains at 25–50 Hz (industrial, no
//! disturbance: 1.99 → 1.44 at 25 Hz, inclination 0.58° → 0.21°); `gyro_delay` = 0 and 2.9 ms
//! are within 0.01° there (its logs have no gyroscope delay); VQF leads on undisturbed
//! industrial logs from 100 Hz up (1.26–1.29 against 1.35–1.39) and trails everywhere else.
//!
//! **Per half** (final design, mean total at 285.7 / 142.9 / 95.2 / 47.6 Hz): A 1.227 /
//! 1.225 / 1.254 / 1.679, B 1.219 / 1.252 / 1.304 / 1.663; VQF A 2.118 / 2.013 / 1.919 /
//! 2.700, B 2.622 / 2.613 / 2.859 / 3.587. The gyroscope delay and the hard iron each win on
//! both halves at every rate; the trapezoid alone loses on both halves at 285.7 and 142.9 Hz,
//! splits at 95.2 Hz and wins on both at 47.6 Hz; it is kept for the cause it removes (and
//! with it the best gyroscope delay is the same at every rate). Magnus-4 in its place (a mean
//! centred on the step as the trapezoid's, with the step's own truncation removed) ties at
//! 285.7 and 142.9 Hz and wins on both halves at 95.2 and 47.6 Hz (A / B 1.220 / 1.212, 1.224
//! / 1.238, 1.215 / 1.261, 1.260 / 1.321; BENCHMARKS.md, "The estimator's rate rule").
//!
//! **Inclination** (mean over 16 trials, 285.7 / 142.9 / 95.2 / 47.6 Hz): 0.572 / 0.598 /
//! 0.614 / 0.840°, VQF 0.754 / 0.676 / 0.749 / 1.521° (its 9D and 6D inclination are the
//! same). Before the trapezoid and the delay it was 0.762 / 0.669 / 0.736 / 1.494°: worse than
//! VQF at 142.9 Hz. What made the difference is the time alignment of the gyroscope, not the
//! low-pass or the gate (`accel_time_constant` halved / doubled: 1.816 / 1.814 before).
//!
//! # The magnetometer's delay, estimated online
//! The strapdown attitudes `q_g` are kept on a time grid of step [`MAG_HISTORY_STEP`] (10 ms)
//! covering [`MAG_DELAY_MAX`] (50 ms), whatever the rate: each step pushes the attitudes at
//! the grid times it passes (linear between its two ends, renormalised), and the attitude at
//! any delay is linear between two grid attitudes (or the newest one and now). Memory: 6
//! attitudes and 6 candidates' statistics, 192 bytes in f32 (384 in f64), on the M0 and the
//! M4F alike (before: 8 attitudes and statistics per sample, 256 bytes, 0–25 ms at 285.7 Hz).
//! With [`Params::mag_delay_estimation_time`] `τ_d > 0` the delay is estimated from the sensor
//! data alone: in an undisturbed field the earth-frame field is constant, so the field sample
//! mapped by the attitude of `d` earlier is constant when `d` is the delay and wobbles with the
//! rotation when it is not. For each candidate `d = 0, 10, …, 50 ms` the filter keeps the mean
//! of the mapped field (first order, 1 s) and the mean of `sin²` of its heading deviation from
//! that mean (first order, `τ_d`), fed every 20 ms while turning faster than
//! [`FieldThresholds::new_field_min_rate`] in an undisturbed field. After `τ_d` of such
//! samples the delay is the candidate of least deviation, refined by the parabola through it
//! and its neighbours (the deviation grows as the square of the delay error); before that it is
//! [`Params::mag_delay`]. On synthetic data with delays of 0, 10 and 25 ms (point-sampled
//! rates) the estimate comes within 0.2 ms (host-tests `magnetometer_delay_is_estimated`
//! requires 1.5 ms). BROAD's trials settle at 10–14 ms (one at 5 ms) at every rate.
//!
//! # Hard iron, estimated online
//! [`hard_iron`]: a four-state Kalman sphere fit in the sensor frame (`|B|² = 2Bᵀh + c`), fed
//! every 20 ms while turning, its covariance the rotation's diversity, reset when the samples
//! stop lying on one sphere. A converged offset (1 % of the norm per axis) larger than the
//! monitor's norm threshold ([`FieldThresholds::norm`]) is subtracted from a sample when that
//! brings the field closer to the monitor's reference; the monitor still rejects a field that
//! changes in the earth frame. BROAD's attached magnets (1, 3, 5 cm): 1.648 / 1.362 / 2.066 →
//! 0.789 / 0.926 / 1.265 (VQF 7.67 / 3.35 / 2.39); the 13 other trials are unchanged (no
//! offset above the threshold: the fit finds 0.3–3 µT of model error there). Trial 32's magnet,
//! attached from 35 s to 95 s, is found as (−7, −1, 57) µT ± 0.1 µT within 10 s of turning
//! and dropped within 5 s of its removal. On the synthetic grid's fixed magnet (27 µT attached
//! a third into the first phase) it changes little (5.80 → 5.74° consumer at 25 Hz, other
//! cells equal; BENCHMARKS), which was not investigated further. The fit's measurement
//! variance is per sample (it is fed single samples, not averages); counted per 10 ms it
//! made the fit depend on how often it is fed (1.252 against 1.223). Without the threshold (every converged offset
//! used) trials 24, 26, 28 lost up to 0.5° and half A lost; with the choice "only where the
//! raw field is rejected" trial 36 lost (the raw field, 13 % off, was accepted after the
//! monitor recovered).
//!
//! Cost: 3009 M4F instructions per 9D f32 update (`fw_icount_estimation`; 1941 6D; 137018 /
//! 93816 on the soft-float M0), after the robustness work of issue 29 (6980 / 4042 M4F before
//! the norms of the checked vectors became one square root each and the scalar covariance
//! update was written over the blocks directly: BENCHMARKS, "Where the instructions go"); reading
//! [`Estimator::attitude`] adds the exponential of the delay step. Memory: the hard-iron fit
//! 88 bytes in f32 and its offsets 28. f32 runs within 0.001° of f64 on every trial.

pub mod covariance;
pub mod field;
pub mod filter;
pub mod hard_iron;
pub mod init;
pub mod lowpass;
pub mod params;
pub mod params_text;
mod rate_window;
pub mod rest;

pub use covariance::Covariance;
pub use field::FieldMonitor;
pub use filter::{
    Estimator, MAG_DELAY_MAX, MAG_HISTORY, MAG_HISTORY_STEP, MAG_INTERVAL_MAX, MAX_STEP, Outcome,
    SensorUse,
};
pub use hard_iron::HardIron;
pub use init::{attitude_from_gravity, attitude_from_gravity_and_field};
pub use lowpass::{LowPass, first_order_gain};
pub use params::{
    Domain, EarthFrame, FieldThresholds, Gains, Mode, Params, RateRule, RestThresholds,
};
pub use params_text::{ParamsTextError, ParamsTextErrorKind};
pub use rest::RestDetector;
