//! The motions of `synthesize`, each in closed form: the attitude, the body rate, the linear
//! acceleration and the body-frame vibration at any time, exactly (no differences of sampled
//! truth), so that what a sensor measures follows from them exactly.
//!
//! # Timeline
//! A log is a rest phase (`rest` seconds), then `phases` movement phases of `duration` seconds
//! each with a rest phase of `rest` seconds between them. The motion runs on a warped time
//! `s(t)`: `ṡ = 0` at rest, `ṡ = 1` inside a movement phase, and a raised-cosine ramp
//! `ṡ = (1 − cos(π u/ρ))/2` over the first and last `ρ = ramp` seconds of each phase, so
//! rates and accelerations start and stop smoothly. Each phase advances `s` by `duration − ρ`.
//! A motion `Q(s)` with body rate `Ω(s)` per unit `s` gives `q(t) = Q(s(t))` and
//! `ω(t) = ṡ(t)·Ω(s(t))`; a translation `P(s)` gives `a(t) = P''(s)·ṡ² + P'(s)·s̈`.
//!
//! # Rotations
//! - `rest`: `q = q0`.
//! - `spin:WX,WY,WZ`: a constant body rate `W` per unit `s`: `q = q0 ⊗ exp(W s/2)`.
//! - `axes`: phase `i` turns once (360°) about body axis `x`, `y`, `z` (`i mod 3`) at the
//!   constant rate `2π/(duration − ρ)` per unit `s`.
//! - `handheld`: `q = q0 ⊗ Rz(ψ)·Ry(θ)·Rx(φ)` (yaw, pitch, roll), each angle a sum of three
//!   sines with seeded, incommensurate frequencies (0.5–3.5 rad/s) and phases, zero at
//!   `s = 0` (|θ| stays below 70°): smooth and non-repeating, peak rates about 2–4 rad/s. The
//!   body rate is the closed form `(φ' − ψ' sin θ, θ' cos φ + ψ' sin φ cos θ,
//!   −θ' sin φ + ψ' cos φ cos θ)`.
//! - a motion file (`simulate`'s CSV: `t,qw,qx,qy,qz,w1,w2,w3,...`): its rows, uniformly
//!   spaced, are the samples of the single movement phase (its rates are the simulator's exact
//!   `∇H(J)` of each state); between rows (the magnetometer's delay) the attitude is
//!   interpolated by slerp.
//!
//! # Translation and vibration
//! - `translation A`: `P(s)` per earth axis, three sines (amplitudes 0.6 A, 0.3 A, 0.15 A,
//!   frequencies 1–7 rad/s), zero at `s = 0`.
//! - `vibration A,F`: a body-frame acceleration `ṡ(t)·A·sin(2π F cⱼ t + φⱼ)` on axis `j`
//!   (`c = 1, 1.13, 0.89`), on during the movement phases.
//! - `taps A`: every 1.5–3 s of a movement phase (seeded), a body-frame acceleration
//!   `A·d·e^(−u/0.01 s)·sin(2π·60 Hz·u)` for `0 ≤ u < 0.1 s` along a seeded unit direction `d`.

use crate::noise::Rng;

/// A quaternion, scalar first.
pub type Q = [f64; 4];

/// `a ⊗ b`.
pub fn qmul(a: Q, b: Q) -> Q {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

/// `q v q*`: a body vector in the earth frame.
pub fn rotate(q: Q, v: [f64; 3]) -> [f64; 3] {
    let r = qmul(
        qmul(q, [0.0, v[0], v[1], v[2]]),
        [q[0], -q[1], -q[2], -q[3]],
    );
    [r[1], r[2], r[3]]
}

/// `q* v q`: an earth vector in the body frame.
pub fn rotate_inv(q: Q, v: [f64; 3]) -> [f64; 3] {
    rotate([q[0], -q[1], -q[2], -q[3]], v)
}

/// The rotation by `angle` about the unit `axis`.
pub fn axis_angle(axis: [f64; 3], angle: f64) -> Q {
    let (s, c) = (angle / 2.0).sin_cos();
    [c, axis[0] * s, axis[1] * s, axis[2] * s]
}

/// `exp(v/2)`: the rotation by the rotation vector `v`.
pub fn exp_rotvec(v: [f64; 3]) -> Q {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if n == 0.0 {
        return [1.0, 0.0, 0.0, 0.0];
    }
    axis_angle([v[0] / n, v[1] / n, v[2] / n], n)
}

/// The timeline: rest, then movement phases with rests between.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Timeline {
    /// The rest before and between movement phases, s.
    pub rest: f64,
    /// The length of each movement phase, s.
    pub duration: f64,
    /// The number of movement phases.
    pub phases: u32,
    /// The ramp at either end of a phase, s (`2·ramp ≤ duration`).
    pub ramp: f64,
}

/// The warped time at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Warp {
    /// `s`.
    pub s: f64,
    /// `ṡ`.
    pub ds: f64,
    /// `s̈`.
    pub dds: f64,
    /// Inside a movement phase.
    pub moving: bool,
    /// The current movement phase, or the last one before `t` (0 before the first).
    pub phase: u32,
}

impl Timeline {
    /// The length of the log, s.
    pub fn total(&self) -> f64 {
        self.rest
            + f64::from(self.phases) * self.duration
            + f64::from(self.phases.saturating_sub(1)) * self.rest
    }

    /// The start of movement phase `i`, s.
    pub fn phase_start(&self, i: u32) -> f64 {
        self.rest + f64::from(i) * (self.duration + self.rest)
    }

    /// How far `s` advances in one phase.
    pub fn per_phase(&self) -> f64 {
        self.duration - self.ramp
    }

    /// `s`, `ṡ`, `s̈` at time `t`.
    pub fn warp(&self, t: f64) -> Warp {
        let (d, r) = (self.duration, self.ramp);
        let period = d + self.rest;
        let rel = t - self.rest;
        let rest = |s: f64, phase: u32| Warp {
            s,
            ds: 0.0,
            dds: 0.0,
            moving: false,
            phase,
        };
        if rel < 0.0 || self.phases == 0 {
            return rest(0.0, 0);
        }
        let i = ((rel / period).floor() as u32).min(self.phases - 1);
        let u = rel - f64::from(i) * period;
        let before = f64::from(i) * self.per_phase();
        if u > d {
            return rest(before + self.per_phase(), i);
        }
        let pi = std::f64::consts::PI;
        let (s, ds, dds) = if r > 0.0 && u < r {
            let x = pi * u / r;
            (
                u / 2.0 - r / (2.0 * pi) * x.sin(),
                (1.0 - x.cos()) / 2.0,
                pi / (2.0 * r) * x.sin(),
            )
        } else if r > 0.0 && u > d - r {
            let v = d - u;
            let x = pi * v / r;
            (
                (d - r) - (v / 2.0 - r / (2.0 * pi) * x.sin()),
                (1.0 - x.cos()) / 2.0,
                -pi / (2.0 * r) * x.sin(),
            )
        } else {
            (r / 2.0 + (u - r), 1.0, 0.0)
        };
        Warp {
            s: before + s,
            ds,
            dds,
            moving: true,
            phase: i,
        }
    }
}

/// Three sines per component: `Σ A (sin(ν s + φ) − sin φ)` and its first two derivatives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sines {
    /// Amplitude, angular frequency (per unit `s`), phase of each term.
    pub terms: [[f64; 3]; 3],
}

impl Sines {
    fn seeded(rng: &mut Rng, amplitudes: [f64; 3], bands: [[f64; 2]; 3]) -> Self {
        let mut terms = [[0.0; 3]; 3];
        for (t, (a, b)) in terms.iter_mut().zip(amplitudes.iter().zip(bands)) {
            let nu = b[0] + (b[1] - b[0]) * rng.uniform();
            let phase = 2.0 * std::f64::consts::PI * rng.uniform();
            *t = [*a, nu, phase];
        }
        Self { terms }
    }

    /// Value, first and second derivative at `s`.
    pub fn eval(&self, s: f64) -> [f64; 3] {
        let mut out = [0.0; 3];
        for [a, nu, ph] in self.terms {
            let (sn, cs) = (nu * s + ph).sin_cos();
            out[0] += a * (sn - ph.sin());
            out[1] += a * nu * cs;
            out[2] -= a * nu * nu * sn;
        }
        out
    }
}

/// What the body does, as a function of warped time.
#[derive(Clone, Debug, PartialEq)]
pub enum Rotation {
    /// At rest.
    Rest,
    /// A constant body rate per unit `s`.
    Spin([f64; 3]),
    /// One turn per phase about body x, y, z in turn.
    Axes,
    /// Yaw, pitch, roll as sums of sines.
    Handheld([Sines; 3]),
    /// The rows of a motion file.
    File(MotionFile),
}

/// A motion file: uniformly spaced attitudes and body rates.
#[derive(Clone, Debug, PartialEq)]
pub struct MotionFile {
    /// The spacing of the rows, s.
    pub step: f64,
    /// The attitude of each row.
    pub attitudes: Vec<Q>,
    /// The body rate of each row, rad/s.
    pub rates: Vec<[f64; 3]>,
}

impl MotionFile {
    /// Reads `t,qw,qx,qy,qz,w1,w2,w3[,...]` rows (a header naming these columns first; `simulate`'s
    /// output). Errors read `line N: reason`.
    pub fn parse(text: &str) -> Result<Self, String> {
        let mut lines = text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty());
        let (_, header) = lines.next().ok_or("line 1: empty motion file")?;
        let names: Vec<&str> = header.split(',').map(str::trim).collect();
        let col = |n: &str| {
            names
                .iter()
                .position(|h| *h == n)
                .ok_or_else(|| format!("line 1: the header has no column '{n}' (t,qw,qx,qy,qz,w1,w2,w3: simulate's CSV)"))
        };
        let cols: Vec<usize> = ["t", "qw", "qx", "qy", "qz", "w1", "w2", "w3"]
            .iter()
            .map(|n| col(n))
            .collect::<Result<_, _>>()?;
        let (mut times, mut attitudes, mut rates) = (Vec::new(), Vec::new(), Vec::new());
        for (i, line) in lines {
            let n = i + 1;
            let fields: Vec<&str> = line.split(',').map(str::trim).collect();
            if fields.len() != names.len() {
                return Err(format!(
                    "line {n}: {} fields, the header has {}",
                    fields.len(),
                    names.len()
                ));
            }
            let mut v = [0.0; 8];
            for (x, &c) in v.iter_mut().zip(&cols) {
                *x = fields[c]
                    .parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| format!("line {n}: '{}' is not a finite number", fields[c]))?;
            }
            let q = [v[1], v[2], v[3], v[4]];
            let norm = q.iter().map(|x| x * x).sum::<f64>().sqrt();
            if (norm - 1.0).abs() > 1e-6 {
                return Err(format!("line {n}: the attitude's norm is {norm}, not 1"));
            }
            if let Some(&last) = times.last()
                && v[0] <= last
            {
                return Err(format!("line {n}: the time {} is not after {last}", v[0]));
            }
            times.push(v[0]);
            attitudes.push(q.map(|x| x / norm));
            rates.push([v[5], v[6], v[7]]);
        }
        if times.len() < 2 {
            return Err("the motion file has fewer than two rows".into());
        }
        let step = (times[times.len() - 1] - times[0]) / (times.len() - 1) as f64;
        for (k, w) in times.windows(2).enumerate() {
            if ((w[1] - w[0]) - step).abs() > 1e-6 * step {
                return Err(format!(
                    "the motion file's rows are not uniformly spaced (rows {} and {}: {} s, the mean step is {step} s)",
                    k + 1,
                    k + 2,
                    w[1] - w[0]
                ));
            }
        }
        Ok(Self {
            step,
            attitudes,
            rates,
        })
    }

    /// The attitude at row position `x` (fractional: slerp between rows), clamped to the rows.
    fn attitude(&self, x: f64) -> Q {
        let last = self.attitudes.len() - 1;
        let x = x.clamp(0.0, last as f64);
        let i = (x.floor() as usize).min(last);
        let f = x - i as f64;
        if f < 1e-9 || i == last {
            return self.attitudes[i];
        }
        let (a, mut b) = (self.attitudes[i], self.attitudes[i + 1]);
        let mut dot: f64 = a.iter().zip(&b).map(|(x, y)| x * y).sum();
        if dot < 0.0 {
            b = b.map(|x| -x);
            dot = -dot;
        }
        let th = dot.min(1.0).acos();
        let (wa, wb) = if th < 1e-12 {
            (1.0 - f, f)
        } else {
            (((1.0 - f) * th).sin() / th.sin(), (f * th).sin() / th.sin())
        };
        let q: Q = core::array::from_fn(|k| wa * a[k] + wb * b[k]);
        let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
        q.map(|x| x / n)
    }
}

/// The body-frame tap impulses of a run: (start time, unit direction).
pub type Taps = Vec<(f64, [f64; 3])>;

/// A complete motion: the timeline, the start attitude, the rotation and the linear parts.
#[derive(Clone, Debug, PartialEq)]
pub struct Motion {
    /// The timeline.
    pub timeline: Timeline,
    /// The attitude at `s = 0`.
    pub q0: Q,
    /// The rotation.
    pub rotation: Rotation,
    /// The translation `P(s)` per earth axis, m.
    pub translation: Option<[Sines; 3]>,
    /// Vibration: amplitude (m/s²), frequency (Hz), phase per axis.
    pub vibration: Option<(f64, f64, [f64; 3])>,
    /// Taps: amplitude (m/s²) and the taps.
    pub taps: Option<(f64, Taps)>,
}

/// What the motion is at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Kinematics {
    /// Attitude, body → earth.
    pub q: Q,
    /// Body rate, body frame, rad/s.
    pub w: [f64; 3],
    /// Position, earth frame, m.
    pub p: [f64; 3],
    /// Linear acceleration, earth frame, m/s².
    pub a: [f64; 3],
    /// Extra body-frame acceleration (vibration, taps), m/s².
    pub a_body: [f64; 3],
    /// Inside a movement phase.
    pub moving: bool,
}

/// The handheld rotation's amplitudes (rad) and frequency bands (rad per unit `s`).
const HANDHELD: [([f64; 3], [[f64; 2]; 3]); 3] = [
    ([1.05, 0.52, 0.26], [[0.5, 1.0], [1.2, 2.0], [2.2, 3.5]]),
    ([0.35, 0.17, 0.087], [[0.5, 1.0], [1.2, 2.0], [2.2, 3.5]]),
    ([0.44, 0.21, 0.10], [[0.5, 1.0], [1.2, 2.0], [2.2, 3.5]]),
];

impl Rotation {
    /// The seeded hand-held rotation.
    pub fn handheld(rng: &mut Rng) -> Self {
        Rotation::Handheld(HANDHELD.map(|(a, b)| Sines::seeded(rng, a, b)))
    }
}

/// The seeded translation of amplitude scale `a` (m).
pub fn translation(rng: &mut Rng, a: f64) -> [Sines; 3] {
    let bands = [[1.0, 2.0], [2.5, 4.0], [4.5, 7.0]];
    [(); 3].map(|()| Sines::seeded(rng, [0.6 * a, 0.3 * a, 0.15 * a], bands))
}

/// The seeded tap times and directions over the movement phases of `tl`.
pub fn taps(rng: &mut Rng, tl: &Timeline) -> Taps {
    let mut out = Vec::new();
    for i in 0..tl.phases {
        let (start, end) = (
            tl.phase_start(i) + tl.ramp,
            tl.phase_start(i) + tl.duration - tl.ramp,
        );
        let mut t = start + 0.5 + rng.uniform();
        while t < end - 0.1 {
            let d = [rng.normal(), rng.normal(), rng.normal()];
            let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(1e-12);
            out.push((t, d.map(|x| x / n)));
            t += 1.5 + 1.5 * rng.uniform();
        }
    }
    out
}

/// The vibration's frequency ratios per body axis.
pub const VIBRATION_RATIOS: [f64; 3] = [1.0, 1.13, 0.89];
/// A tap's decay time (s), frequency (Hz) and length (s).
pub const TAP: (f64, f64, f64) = (0.01, 60.0, 0.1);

impl Motion {
    /// The number of rest samples before a motion file's rows at `step`.
    pub fn file_rest_samples(&self) -> u64 {
        match &self.rotation {
            Rotation::File(f) => (self.timeline.rest / f.step).round() as u64,
            _ => 0,
        }
    }

    /// The motion at time `t` (s; before 0 it is the rest before the first phase).
    pub fn at(&self, t: f64) -> Kinematics {
        let tl = &self.timeline;
        let wp = tl.warp(t);
        let (rel_q, rate_per_s): (Q, [f64; 3]) = match &self.rotation {
            Rotation::Rest => ([1.0, 0.0, 0.0, 0.0], [0.0; 3]),
            Rotation::Spin(w) => (exp_rotvec(w.map(|x| x * wp.s)), *w),
            Rotation::Axes => {
                let rate = 2.0 * std::f64::consts::PI / tl.per_phase();
                let mut axis = [0.0; 3];
                axis[(wp.phase % 3) as usize] = 1.0;
                let local = wp.s - f64::from(wp.phase) * tl.per_phase();
                (axis_angle(axis, rate * local), axis.map(|x| x * rate))
            }
            Rotation::Handheld([yaw, pitch, roll]) => {
                let ([psi, dpsi, _], [th, dth, _], [ph, dph, _]) =
                    (yaw.eval(wp.s), pitch.eval(wp.s), roll.eval(wp.s));
                let q = qmul(
                    qmul(
                        axis_angle([0.0, 0.0, 1.0], psi),
                        axis_angle([0.0, 1.0, 0.0], th),
                    ),
                    axis_angle([1.0, 0.0, 0.0], ph),
                );
                let (sth, cth) = th.sin_cos();
                let (sph, cph) = ph.sin_cos();
                (
                    q,
                    [
                        dph - dpsi * sth,
                        dth * cph + dpsi * sph * cth,
                        -dth * sph + dpsi * cph * cth,
                    ],
                )
            }
            Rotation::File(f) => {
                let x = (t - tl.rest) / f.step;
                let q = f.attitude(x);
                let near = x.round();
                let rate = if x >= 0.0 && (x - near).abs() < 1e-6 && (near as usize) < f.rates.len()
                {
                    f.rates[near as usize]
                } else {
                    [0.0; 3]
                };
                // A file's rows are its rates at ṡ = 1; the rest before has none.
                return self.linear(t, &wp, q, if x < -1e-6 { [0.0; 3] } else { rate });
            }
        };
        let q = qmul(self.q0, rel_q);
        self.linear(t, &wp, q, rate_per_s.map(|x| x * wp.ds))
    }

    fn linear(&self, t: f64, wp: &Warp, q: Q, w: [f64; 3]) -> Kinematics {
        let (mut p, mut a) = ([0.0; 3], [0.0; 3]);
        if let Some(tr) = &self.translation {
            for k in 0..3 {
                let [x, dx, ddx] = tr[k].eval(wp.s);
                p[k] = x;
                a[k] = ddx * wp.ds * wp.ds + dx * wp.dds;
            }
        }
        let mut a_body = [0.0; 3];
        if let Some((amp, f, phase)) = self.vibration {
            for k in 0..3 {
                let arg = 2.0 * std::f64::consts::PI * f * VIBRATION_RATIOS[k] * t + phase[k];
                a_body[k] += wp.ds * amp * arg.sin();
            }
        }
        if let Some((amp, taps)) = &self.taps {
            let (tau, f, len) = TAP;
            for (t0, d) in taps {
                let u = t - t0;
                if (0.0..len).contains(&u) {
                    let g = amp * (-u / tau).exp() * (2.0 * std::f64::consts::PI * f * u).sin();
                    for k in 0..3 {
                        a_body[k] += g * d[k];
                    }
                }
            }
        }
        Kinematics {
            q,
            w,
            p,
            a,
            a_body,
            moving: wp.moving,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn warp_is_continuous_and_its_derivatives_match() {
        let tl = Timeline {
            rest: 2.0,
            duration: 5.0,
            phases: 2,
            ramp: 0.7,
        };
        let h = 1e-5;
        let mut t = 0.013;
        while t < tl.total() + 1.0 {
            let (a, b, c) = (tl.warp(t - h), tl.warp(t), tl.warp(t + h));
            assert!(((c.s - a.s) / (2.0 * h) - b.ds).abs() < 1e-6, "ṡ at {t}");
            assert!(((c.ds - a.ds) / (2.0 * h) - b.dds).abs() < 1e-4, "s̈ at {t}");
            t += 0.0731;
        }
        assert_eq!(tl.warp(tl.total() + 5.0).s, 2.0 * tl.per_phase());
    }
}
