//! Conserved-quantity monitors: the energy, the Casimir `|J|` and the lab-frame angular momentum
//! of torque-free motion, and the worst drift of each over a run.
//!
//! Torque-free motion conserves the energy `H(J)` (wheels coasting), the Casimir `|J|` of every
//! body-frame flow `J̇ = J × ∇H`, and the lab momentum `q ⊗ J ⊗ q*` (6.8.2). A numerical
//! integrator keeps them only approximately: the splittings conserve `|J|` and the lab momentum
//! to rounding with a bounded energy error, RK4 lets all three drift with time. [`DriftMonitor`]
//! records the worst relative drift of each over a run.
//!
//! ```
//! use gyrostat::dynamics::{DriftMonitor, Gyrostat, Inertia, Integrator, State};
//! use gyrostat::{UnitQuat, Vec3};
//! let body = Gyrostat::rigid(Inertia::try_from_principal(Vec3::new(6.0f64, 4.0, 3.0))?);
//! let mut s = State::new(UnitQuat::IDENTITY, Vec3::new(0.3, 4.0, 0.05));
//! let mut monitor = DriftMonitor::new(body.invariants(&s));
//! for _ in 0..1000 {
//!     s = body.step(Integrator::Yoshida4, &s, 0.01)?;
//!     monitor.record(&body.invariants(&s));
//! }
//! let worst = monitor.worst();
//! assert!(worst.momentum_norm < 1e-13 && worst.lab_momentum < 1e-12);
//! assert!(worst.energy < 1e-6);
//! # Ok::<(), gyrostat::Error>(())
//! ```

use crate::{Real, UnitQuat, Vec3};

/// The Casimir `|J|`: conserved by every torque-free body-frame flow `J̇ = J × ∇H`.
#[inline]
pub fn momentum_norm<T: Real>(j: Vec3<T>) -> T {
    j.norm()
}

/// The lab-frame angular momentum `q ⊗ J ⊗ q*` (6.8.2): constant for torque-free motion.
#[inline]
pub fn lab_momentum<T: Real>(attitude: UnitQuat<T>, j_body: Vec3<T>) -> Vec3<T> {
    attitude.rotate(j_body)
}

/// The quantities torque-free motion conserves, at one state (see
/// [`crate::dynamics::Gyrostat::invariants`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Invariants<T> {
    /// The body Hamiltonian `H(J)`.
    pub energy: T,
    /// `|J|`.
    pub momentum_norm: T,
    /// The lab-frame momentum `q ⊗ J ⊗ q*`.
    pub lab_momentum: Vec3<T>,
}

/// Relative drifts of the [`Invariants`] from their initial values `E₀`, `|J₀|`, `L₀`:
/// `|E − E₀|/|E₀|`, `||J| − |J₀||/|J₀|` and `|L − L₀|/|J₀|`. An initial value of zero (a body
/// at rest), or one so small that the relative drift overflows the type, makes the
/// corresponding drift absolute instead of relative. Domain: invariants below `MAX/2` in
/// magnitude (each component), so that their differences are representable; then every drift is
/// finite (the lab drift is formed without forming `|L − L₀|`, which can exceed `MAX`), except an
/// absolute lab drift (`|J₀|` zero or tiny) whose value itself exceeds `MAX`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Drift<T> {
    /// `|E − E₀|/|E₀|`.
    pub energy: T,
    /// `||J| − |J₀||/|J₀|`.
    pub momentum_norm: T,
    /// `|L − L₀|/|J₀|`.
    pub lab_momentum: T,
}

impl<T: Real> Drift<T> {
    /// The drifts of `now` from `initial`.
    pub fn between(initial: &Invariants<T>, now: &Invariants<T>) -> Self {
        // |difference| relative to |reference|, or absolute where that is zero or the quotient
        // overflows.
        let relative = |diff: T, reference: T| {
            let r = diff / reference.abs();
            if reference != T::ZERO && r.is_finite() {
                r
            } else {
                diff
            }
        };
        let n0 = initial.momentum_norm;
        Self {
            energy: relative((now.energy - initial.energy).abs(), initial.energy),
            momentum_norm: relative((now.momentum_norm - initial.momentum_norm).abs(), n0),
            lab_momentum: relative_norm(now.lab_momentum - initial.lab_momentum, n0),
        }
    }

    /// The component-wise larger of two drifts.
    pub fn max(self, other: Self) -> Self {
        Self {
            energy: self.energy.max(other.energy),
            momentum_norm: self.momentum_norm.max(other.momentum_norm),
            lab_momentum: self.lab_momentum.max(other.lab_momentum),
        }
    }
}

/// `|v|/|reference|` (absolute `|v|` where the reference is zero or the quotient overflows),
/// without forming `|v|` itself: `|v| = m·|v/m|` with `m = max |vᵢ|`, and the quotient is
/// `|v/m|·(m/|reference|)`. The plain `√(v·v)` overflows once a component passes `√MAX`, and
/// `|v|` itself once it passes `MAX/√3`, although the relative drift is representable.
fn relative_norm<T: Real>(v: Vec3<T>, reference: T) -> T {
    let m = v.x.abs().max(v.y.abs()).max(v.z.abs());
    if m == T::ZERO || !m.is_finite() {
        return m;
    }
    let unit = (v / m).norm();
    let r = unit * (m / reference.abs());
    if reference != T::ZERO && r.is_finite() {
        r
    } else {
        unit * m
    }
}

/// The worst [`Drift`] of the invariants over a run: plain data, fed one state at a time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DriftMonitor<T> {
    initial: Invariants<T>,
    worst: Drift<T>,
}

impl<T: Real> DriftMonitor<T> {
    /// Starts at the invariants of the initial state, with no drift.
    pub fn new(initial: Invariants<T>) -> Self {
        Self {
            initial,
            worst: Drift {
                energy: T::ZERO,
                momentum_norm: T::ZERO,
                lab_momentum: T::ZERO,
            },
        }
    }

    /// Records the invariants of one more state; returns their drift.
    pub fn record(&mut self, now: &Invariants<T>) -> Drift<T> {
        let d = Drift::between(&self.initial, now);
        self.worst = self.worst.max(d);
        d
    }

    /// The initial invariants.
    pub fn initial(&self) -> &Invariants<T> {
        &self.initial
    }

    /// The worst drift recorded so far (zero before the first [`DriftMonitor::record`]).
    pub fn worst(&self) -> Drift<T> {
        self.worst
    }
}
