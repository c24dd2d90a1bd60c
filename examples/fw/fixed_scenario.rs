// The built-in coning scenario of the fixed-point firmware, shared by `include!` with its host
// test so that the host computes exactly what the boards compute:
// - examples/fw_fixed.rs (Cortex-M0/M3/M4F/M33 and RISC-V under QEMU) prints the lines of
//   `run_scenario`;
// - host-tests/tests/fixed/firmware.rs runs the same function on the host, checks that the boards
//   printed the same bits, and checks the numbers against the closed-form coning attitude;
// - tools/tests/tools/fixed.rs feeds the same increments to `propagate --fixed` and checks that
//   it prints the same bits.
//
// Inputs: classical coning (half-cone angle ALPHA, coning rate OMEGA, a frequency that is not a
// fraction of the sample rate with a small denominator: the input does not repeat), the exact
// increments over each gyro interval, computed in IEEE-754 f64 with gyrostat's `Real` for f64
// (the `libm` crate: pure Rust built from correctly rounded basic operations, no fused
// multiply-add and no x87 on any of the targets), then converted to Q1.30 by an
// `IncrementQuantizer` (integer code on the IEEE bits, the remainder carried). So the inputs are
// the same bits on the host and on every board; the firmware also prints a checksum of them
// (`inputs` line), which the host test compares first.
//
// Propagation: the increment stream feeds, in one pass,
// - `CarriedAttitude::coning2_update` (the 2-sample hot path, rounding residuals carried, fast
//   renormalisation folded in), printed every CHECK_EVERY increments;
// - the plain `kernels::coning2_update` on `UnitQuat<Q30>` (no residuals), printed at the end;
// - an `IncrementIntegrator` over a `CarriedAttitude` for each `ConingRule` (fast
//   renormalisation), flushed at the end;
// - the two-speed `ConingAccumulator`, one carried attitude update per TWO_SPEED_GROUP
//   increments;
// then the final carried 2-sample attitude's health value, rotation matrix and rotated body z
// axis. Every number is printed as the hex of its raw Q1.30 integer: bit-identity is string
// equality.

/// Half-cone angle α (rad).
const ALPHA: f64 = 0.05;
/// Coning rate Ω (rad/s): 2.0137 Hz, 198.6 samples per cone period (the input does not repeat).
const OMEGA: f64 = 2.0 * core::f64::consts::PI * 2.0137;
/// Gyro sample interval h (s): 400 Hz.
const H: f64 = 1.0 / 400.0;
/// Number of increments: 6 s, a multiple of 2, 3, 4 and 8 (every rule ends on a full group).
const N_INCREMENTS: usize = 2400;
/// The 2-sample attitude is printed after every this many increments.
const CHECK_EVERY: usize = 240;
/// Increments per attitude update of the two-speed accumulator.
const TWO_SPEED_GROUP: u32 = 8;

/// The exact increment `∫ω dt` of classical coning over `[k h, (k+1) h]`:
/// `(−2 sin α sin(Ω t̄) sin(Ωh/2), 2 sin α cos(Ω t̄) sin(Ωh/2), −Ω(1 − cos α) h)`, `t̄` the
/// interval's midpoint (the product forms of the cosine and sine differences, no cancellation).
fn scenario_increment(k: usize) -> [f64; 3] {
    use gyrostat::Real;
    let (sa, _) = Real::sin_cos(ALPHA);
    let (sh, _) = Real::sin_cos(0.5 * ALPHA);
    let one_minus_ca = 2.0 * sh * sh;
    let (half, _) = Real::sin_cos(0.5 * OMEGA * H);
    let (sm, cm) = Real::sin_cos(OMEGA * H * (k as f64 + 0.5));
    [
        -2.0 * sa * sm * half,
        2.0 * sa * cm * half,
        -OMEGA * one_minus_ca * H,
    ]
}

/// The exact attitude at `t = 0`: `(cos α/2, sin α/2, 0, 0)`.
fn scenario_start() -> [f64; 4] {
    use gyrostat::Real;
    let (s, c) = Real::sin_cos(0.5 * ALPHA);
    [c, s, 0.0, 0.0]
}

/// Runs the scenario and hands each output line to `out`.
fn run_scenario(
    out: &mut dyn FnMut(core::fmt::Arguments<'_>),
) -> Result<(), gyrostat::Error> {
    use gyrostat::fixed::IncrementQuantizer;
    use gyrostat::propagation::CarriedAttitude;
    use gyrostat::real::Q30;
    use gyrostat::propagation::kernels::coning2_update;
    use gyrostat::propagation::normalization::norm_squared_deviation;
    use gyrostat::propagation::{ConingAccumulator, ConingRule, IncrementIntegrator, Normalization};
    use gyrostat::{Quat, Ring, UnitQuat, Vec3};

    let hex = |x: Q30| x.to_bits() as u32;
    let s = scenario_start();
    let q0 = UnitQuat::<Q30>::try_from_f64(UnitQuat::new_unchecked(Quat::from_array(s)))?;
    let fast = Normalization::Fast;
    let mut quantizer = IncrementQuantizer::<30>::new();
    let mut q2 = CarriedAttitude::new(q0);
    let mut q2_plain = q0;
    let mut pending: Option<Vec3<Q30>> = None;
    let mut rules = ConingRule::ALL.map(|r| IncrementIntegrator::new(CarriedAttitude::new(q0), r, fast));
    let mut acc = ConingAccumulator::<Q30>::new();
    let mut q_two_speed = CarriedAttitude::new(q0);
    let (mut sum, mut hash) = (0i64, 0u32);
    for k in 0..N_INCREMENTS {
        let d = quantizer.try_quantize(Vec3::from_array(scenario_increment(k)))?;
        for c in d.to_array() {
            sum += i64::from(c.to_bits());
            hash = hash.rotate_left(5) ^ (c.to_bits() as u32);
        }
        match pending.take() {
            None => pending = Some(d),
            Some(first) => {
                q2 = q2.coning2_update(first, d);
                q2_plain = coning2_update(q2_plain, first, d);
            }
        }
        for integ in rules.iter_mut() {
            integ.push(d)?;
        }
        acc.push_unchecked(d);
        if acc.count() == TWO_SPEED_GROUP {
            q_two_speed = q_two_speed.mul_exp_unchecked(acc.take(), fast);
        }
        if (k + 1) % CHECK_EVERY == 0 {
            let [w, x, y, z] = q2.attitude().to_array().map(hex);
            out(format_args!("coning2 {} {w:08x} {x:08x} {y:08x} {z:08x}", k + 1));
        }
    }
    out(format_args!("inputs {N_INCREMENTS} {sum:016x} {hash:08x}"));
    for (rule, integ) in ConingRule::ALL.iter().zip(rules.iter_mut()) {
        let [w, x, y, z] = integ.flush().to_array().map(hex);
        out(format_args!("rule {rule:?} {w:08x} {x:08x} {y:08x} {z:08x}"));
    }
    let [w, x, y, z] = q_two_speed.attitude().to_array().map(hex);
    out(format_args!("twospeed {w:08x} {x:08x} {y:08x} {z:08x}"));
    let [w, x, y, z] = q2_plain.to_array().map(hex);
    out(format_args!("plain2 {w:08x} {x:08x} {y:08x} {z:08x}"));
    let q2 = q2.attitude();
    out(format_args!("health {:08x}", hex(norm_squared_deviation(q2))));
    let m = q2.to_rotation_matrix().m;
    out(format_args!(
        "matrix {:08x} {:08x} {:08x} {:08x} {:08x} {:08x} {:08x} {:08x} {:08x}",
        hex(m[0][0]),
        hex(m[0][1]),
        hex(m[0][2]),
        hex(m[1][0]),
        hex(m[1][1]),
        hex(m[1][2]),
        hex(m[2][0]),
        hex(m[2][1]),
        hex(m[2][2])
    ));
    let v = q2.rotate(Vec3::new(Q30::ZERO, Q30::ZERO, Q30::ONE));
    out(format_args!(
        "rotate {:08x} {:08x} {:08x}",
        hex(v.x),
        hex(v.y),
        hex(v.z)
    ));
    Ok(())
}
