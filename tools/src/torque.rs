//! External body torque: none, constant, or a schedule read from a CSV file and held between its
//! rows (zero-order hold).

use std::io::{self, Read};

use crate::stream::Lines;

/// The external body-frame torque of a run.
#[derive(Debug, Clone, PartialEq)]
pub enum ExternalTorque {
    /// Torque-free.
    None,
    /// `--torque TX,TY,TZ`: the same torque at every time.
    Constant([f64; 3]),
    /// `--torque-file FILE`: rows `t,tx,ty,tz`, each held from its time to the next row's.
    Schedule(Schedule),
}

/// A zero-order-hold torque schedule: torque `torques[i]` on `[times[i], times[i + 1])`, the last
/// row held for ever, zero before the first row.
#[derive(Debug, Clone, PartialEq)]
pub struct Schedule {
    times: Vec<f64>,
    torques: Vec<[f64; 3]>,
}

impl Schedule {
    /// Parses the CSV lines of a torque file: the header `t,tx,ty,tz`, then one row per line,
    /// times strictly ascending; blank lines are skipped (but counted). The error is
    /// `line N: reason` with N 1-based (a line that is not UTF-8 text is one).
    pub fn parse<R: Read>(mut lines: Lines<R>) -> Result<Self, String> {
        let io = |e: io::Error| format!("reading: {e}");
        let header = match lines.next_line().map_err(io)? {
            None => String::new(),
            Some((_, line)) => line.map_err(|e| format!("line 1: {e}"))?.to_string(),
        };
        let fields: Vec<&str> = header.split(',').map(str::trim).collect();
        if fields != ["t", "tx", "ty", "tz"] {
            return Err(format!(
                "line 1: expected the header t,tx,ty,tz, got {:?}",
                header.trim()
            ));
        }
        let (mut times, mut torques) = (Vec::new(), Vec::<[f64; 3]>::new());
        while let Some((n, line)) = lines.next_line().map_err(io)? {
            let line = line.map_err(|e| format!("line {n}: {e}"))?;
            if line.trim().is_empty() {
                continue;
            }
            let parts: Vec<&str> = line.split(',').map(str::trim).collect();
            if parts.len() != 4 {
                return Err(format!(
                    "line {n}: expected 4 comma-separated numbers t,tx,ty,tz, found {}",
                    parts.len()
                ));
            }
            let mut v = [0.0; 4];
            for (slot, p) in v.iter_mut().zip(&parts) {
                let x: f64 = p
                    .parse()
                    .map_err(|_| format!("line {n}: invalid number {p:?}"))?;
                if !x.is_finite() {
                    return Err(format!("line {n}: non-finite value {p:?}"));
                }
                *slot = x;
            }
            if let Some(&prev) = times.last()
                && v[0] <= prev
            {
                return Err(format!(
                    "line {n}: time {} is not after the previous row's {prev}",
                    v[0]
                ));
            }
            times.push(v[0]);
            torques.push([v[1], v[2], v[3]]);
        }
        if times.is_empty() {
            return Err("no data rows after the header".into());
        }
        Ok(Self { times, torques })
    }

    /// A schedule of rows `(t, torque)`: at least one row, every number finite, times strictly
    /// ascending.
    ///
    /// # Errors
    /// `row N: reason` (0-based) for the first row that breaks a rule, or `no rows`.
    pub fn try_new(times: Vec<f64>, torques: Vec<[f64; 3]>) -> Result<Self, String> {
        if times.is_empty() || times.len() != torques.len() {
            return Err("no rows (or times and torques of different lengths)".into());
        }
        for (i, (t, tau)) in times.iter().zip(&torques).enumerate() {
            if !(t.is_finite() && tau.iter().all(|x| x.is_finite())) {
                return Err(format!("row {i}: non-finite value"));
            }
            if i > 0 && *t <= times[i - 1] {
                return Err(format!(
                    "row {i}: time {t} is not after the previous row's {}",
                    times[i - 1]
                ));
            }
        }
        Ok(Self { times, torques })
    }

    /// The torque held at time `t`.
    pub fn at(&self, t: f64) -> [f64; 3] {
        // Rows with time <= t; the last of them holds.
        let after = self.times.partition_point(|&ti| ti <= t);
        if after == 0 {
            [0.0; 3]
        } else {
            self.torques[after - 1]
        }
    }

    /// The switching times strictly inside `(a, b)`, ignoring those within `guard` of either
    /// end (a switch that close to a step boundary is taken at the boundary).
    pub fn switches_in(&self, a: f64, b: f64, guard: f64) -> impl Iterator<Item = f64> + '_ {
        let start = self.times.partition_point(|&ti| ti <= a + guard);
        self.times[start..]
            .iter()
            .copied()
            .take_while(move |&ti| ti < b - guard)
    }
}

impl ExternalTorque {
    /// `true` unless torque-free.
    pub fn is_some(&self) -> bool {
        !matches!(self, ExternalTorque::None)
    }

    /// The sub-intervals of the step `[a, b]` over which the torque is constant, each with its
    /// torque: one interval unless a schedule switches inside the step.
    pub fn pieces(&self, a: f64, b: f64) -> Vec<(f64, f64, [f64; 3])> {
        match self {
            ExternalTorque::None => vec![(a, b, [0.0; 3])],
            ExternalTorque::Constant(tau) => vec![(a, b, *tau)],
            ExternalTorque::Schedule(s) => {
                // A switch within a billionth of a step of a boundary is a rounding of a time on
                // the step grid (0.3 vs 30 × 0.01): no sliver sub-step for it.
                let guard = 1e-9 * (b - a);
                let mut cuts = vec![a];
                cuts.extend(s.switches_in(a, b, guard));
                cuts.push(b);
                cuts.windows(2)
                    .map(|w| (w[0], w[1], s.at(0.5 * (w[0] + w[1]))))
                    .collect()
            }
        }
    }
}
