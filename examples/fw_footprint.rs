//! Firmware: flash and stack footprint of one library capability linked alone (Cortex-M).
//!
//! ```text
//! GYROSTAT_FOOTPRINT=euler cargo build --profile firmware --example fw_footprint --target thumbv6m-none-eabi
//! GYROSTAT_FOOTPRINT=euler GYROSTAT_FOOTPRINT_STACK=1 \
//!     cargo run --profile firmware --example fw_footprint --target thumbv6m-none-eabi
//! bash benches/footprint.sh          # every capability on M0 and M4F, as a table
//! ```
//! `GYROSTAT_FOOTPRINT` (read when the example is compiled) names the one capability the image
//! links, each with its inputs behind `black_box` so that none of it folds away:
//! - `baseline`: nothing; the image is the runtime (cortex-m-rt's reset handler and vector table)
//!   and an idle loop, the cost every other image shares;
//! - `gyro2`: the 2-sample gyro update with the exponential and the fast renormalisation,
//!   `coning2_update(q, θ₁, θ₂)`;
//! - `gyro2_q30`: the same update in Q1.30 fixed point (`coning2_update` on `UnitQuat<Q30>`),
//!   the integer hot path for FPU-less cores;
//! - `euler`: quaternion → Euler angles in one convention, intrinsic ZYX (yaw, pitch, roll) with
//!   the gimbal-lock record, `q.to_euler(ZYX, ZeroThird)`;
//! - `strang`: a rigid body built from principal moments (`Inertia::try_from_principal`,
//!   `Gyrostat::rigid`) and one torque-free Strang splitting step, `body.step(Strang, …)`;
//! - `exact`: the exact free rigid body from principal moments (`Inertia::try_from_principal`,
//!   `FreeRigidBody::try_new`) and `try_state_at(t)`;
//! - `gyro2_euler`: `gyro2` and `euler` together (attitude propagation and reporting);
//! - `estimate`: the attitude estimator (`gyrostat::estimation::Estimator`, default
//!   parameters): `try_new`, the initialising and one full 9D update, `update_9d`, and the
//!   attitude; its state (about 0.5 KiB in f32) lives on the stack, so the stack column holds it;
//! - `estimate_light`: the same in the light mode (`Mode::Light`, known at build time, as a
//!   firmware that fixes its mode has it): the initialising update and one corrected update;
//! - `all` (the default): the four f32 capabilities together (not `gyro2_q30`, not `estimate`). Shared code
//!   (the f32 `sin`/`cos` kernel, the quaternion product, soft-float routines) is linked once,
//!   so a combination costs less than the sum of its parts.
//!
//! All in f32 except `gyro2_q30`. The size image (no `GYROSTAT_FOOTPRINT_STACK`) holds no
//! formatting and no semihosting: only the runtime, `main`, one call of the capability with the
//! typical operands of `CASES`, and an idle loop. It is built to be measured, not run. Its panic
//! handler calls a function that exists nowhere, as in `fw_nopanic`, so the image also proves
//! that the capability alone has no panicking branch.
//!
//! Stack: with `GYROSTAT_FOOTPRINT_STACK=1`, `main` instead measures the stack of one call per
//! case of `CASES` and reports the numbers over semihosting. For each case it reads its own stack
//! pointer, paints the free stack below it with `0xCCCC_CCCC`, calls the capability through one
//! non-inlined function, and scans up from the bottom of the stack (`_stack_end`) to the first
//! word that is no longer paint. The number is the stack pointer before the call minus that
//! address: the capability's own frames and everything they call, nothing of the runtime or of
//! the reporting, which runs after the scan. It is the high-water mark of that path: the cases
//! are chosen to reach the deepest ones (see `CASES`). A capability that stored the paint word
//! itself at its deepest slot would read 4 bytes short.
//!
//! Output of the stack run, one line: `footprint <capability> stack <bytes per case>`; exit
//! status 0.
#![cfg_attr(target_os = "none", no_std, no_main)]

#[cfg(target_os = "none")]
mod firmware {
    use core::hint::black_box;

    mod board {
        include!("fw/board.rs");
    }

    /// The parts a capability can link, one bit each.
    const GYRO2: u8 = 1;
    const EULER: u8 = 2;
    const STRANG: u8 = 4;
    const EXACT: u8 = 8;
    const GYRO2_Q30: u8 = 16;
    const ESTIMATE: u8 = 32;
    const ESTIMATE_LIGHT: u8 = 64;

    /// The capabilities `GYROSTAT_FOOTPRINT` can name, with the parts each links (`strang` is
    /// the integrator's own name; `gyro2`, `euler`, … name capabilities, not library enums).
    const CAPABILITIES: [(&str, u8); 10] = [
        ("baseline", 0),
        ("gyro2", GYRO2),
        ("gyro2_q30", GYRO2_Q30),
        ("euler", EULER),
        ("gyro2_euler", GYRO2 | EULER),
        (gyrostat::dynamics::Integrator::Strang.name(), STRANG),
        ("exact", EXACT),
        ("all", GYRO2 | EULER | STRANG | EXACT),
        ("estimate", ESTIMATE),
        ("estimate_light", ESTIMATE_LIGHT),
    ];

    /// The entry of `CAPABILITIES` named `name`; an unknown name stops the build.
    const fn find(name: &str) -> (&'static str, u8) {
        let mut i = 0;
        while i < CAPABILITIES.len() {
            if same(CAPABILITIES[i].0, name) {
                return CAPABILITIES[i];
            }
            i += 1;
        }
        panic!(
            "GYROSTAT_FOOTPRINT must be one of: baseline gyro2 gyro2_q30 euler gyro2_euler strang exact all estimate estimate_light"
        )
    }

    const fn same(a: &str, b: &str) -> bool {
        let (a, b) = (a.as_bytes(), b.as_bytes());
        if a.len() != b.len() {
            return false;
        }
        let mut i = 0;
        while i < a.len() {
            if a[i] != b[i] {
                return false;
            }
            i += 1;
        }
        true
    }

    /// (name, parts) of the capability this image links; `all` when the variable is unset.
    const CAPABILITY: (&str, u8) = find(match option_env!("GYROSTAT_FOOTPRINT") {
        Some(name) => name,
        None => "all",
    });

    /// Whether this image links `part`.
    const fn links(part: u8) -> bool {
        CAPABILITY.1 & part != 0
    }

    /// Stack run (measure and report) rather than size image.
    const STACK_RUN: bool = option_env!("GYROSTAT_FOOTPRINT_STACK").is_some();

    /// Operands of one call of the capability.
    #[derive(Clone, Copy)]
    struct Inputs {
        /// Attitude (unit quaternion, scalar first): the Euler conversion's operand and the
        /// starting attitude of the others.
        attitude: [f32; 4],
        /// Scale of the two gyro increments (rad).
        angle: f32,
        /// `attitude` in Q1.30 (raw integers, truncated), for `gyro2_q30`.
        attitude_q30: [i32; 4],
        /// Scale of the two Q1.30 gyro increments: raw units (2⁻³⁰ rad) per tenth of a unit of
        /// their directions (`DIRECTIONS_Q30`).
        angle_q30: i32,
        /// Strang step (s).
        dt: f32,
        /// Time at which the exact free body is evaluated (s).
        t: f32,
    }

    /// A generic attitude.
    const GENERIC: [f32; 4] = [0.923_381, 0.102_598, -0.307_794, 0.205_196];
    /// The ZYX gimbal lock (pitch +90°).
    const LOCK: [f32; 4] = [
        core::f32::consts::FRAC_1_SQRT_2,
        0.0,
        core::f32::consts::FRAC_1_SQRT_2,
        0.0,
    ];

    /// The raw Q1.30 integers of an attitude (truncated: operands, not results).
    const fn q30_bits(a: [f32; 4]) -> [i32; 4] {
        let scale = (1u32 << 30) as f32;
        [
            (a[0] * scale) as i32,
            (a[1] * scale) as i32,
            (a[2] * scale) as i32,
            (a[3] * scale) as i32,
        ]
    }

    /// The directions of the two Q1.30 increments in tenths: `(1, −2, 0.5)` and
    /// `(1.2, −1.9, 0.6)`, as the f32 increments.
    const DIRECTIONS_Q30: [[i32; 3]; 2] = [[10, -20, 5], [12, -19, 6]];

    /// The size image calls the capability once with `CASES[0]`; the stack run calls it with
    /// every case, so that its high-water mark covers the deepest path: the small-angle series
    /// and the `sin`/`cos` kernel, the gimbal-lock branch of the Euler conversion, and libm's
    /// `sincosf` fallback beyond the kernel's range (6000 rad). For `gyro2_q30`: the fused
    /// series update, scaling and squaring (≈ 1.4 rad), and the largest increments (components
    /// at the edge of Q1.30, their sum saturating).
    const CASES: [Inputs; 3] = [
        // Typical: a generic attitude, mrad increments, a 10 ms step.
        Inputs {
            attitude: GENERIC,
            angle: 1e-3,
            attitude_q30: q30_bits(GENERIC),
            angle_q30: 107_374, // 1e-4 rad per tenth: the f32 case's 1e-3 rad
            dt: 0.01,
            t: 7.5,
        },
        // ZYX gimbal lock (pitch +90°); increments past the exponential's series, a 1 s step.
        Inputs {
            attitude: LOCK,
            angle: 0.3,
            attitude_q30: q30_bits(LOCK),
            angle_q30: 32_212_255, // 0.03 rad per tenth: 0.3 rad
            dt: 1.0,
            t: 1e3,
        },
        // Angles beyond the f32 `sin`/`cos` kernel's range; the largest Q1.30 increments.
        Inputs {
            attitude: GENERIC,
            angle: 1e4,
            attitude_q30: q30_bits(GENERIC),
            angle_q30: i32::MAX / 20, // 0.1 rad per tenth: components up to 2 rad
            dt: 1e4,
            t: 1e6,
        },
    ];

    /// The capability, called once with `inputs`; results go to `black_box`.
    #[inline(never)]
    fn capability(inputs: &Inputs) {
        use gyrostat::{Quat, UnitQuat, Vec3};
        let [w, x, y, z] = inputs.attitude;
        // The cases hold unit quaternions (to f32 rounding).
        let attitude = UnitQuat::new_unchecked(Quat::new(w, x, y, z));
        if links(GYRO2) {
            use gyrostat::propagation::kernels::coning2_update;
            let t1 = black_box(Vec3::new(1.0f32, -2.0, 0.5)).scale(inputs.angle);
            let t2 = black_box(Vec3::new(1.2f32, -1.9, 0.6)).scale(inputs.angle);
            black_box(coning2_update(attitude, t1, t2));
        }
        if links(GYRO2_Q30) {
            use gyrostat::propagation::kernels::coning2_update;
            use gyrostat::real::Q30;
            let q =
                UnitQuat::new_unchecked(Quat::from_array(inputs.attitude_q30.map(Q30::from_bits)));
            let [d1, d2] = black_box(DIRECTIONS_Q30);
            let inc =
                |d: [i32; 3]| Vec3::from_array(d.map(|c| Q30::from_bits(c * inputs.angle_q30)));
            black_box(coning2_update(q, inc(d1), inc(d2)));
        }
        if links(EULER) {
            use gyrostat::rotation::{EulerSequence, GimbalPolicy};
            black_box(attitude.to_euler(EulerSequence::ZYX, GimbalPolicy::ZeroThird));
        }
        if links(STRANG) {
            use gyrostat::dynamics::{Gyrostat, Inertia, Integrator, State};
            let state = State::new(attitude, black_box(Vec3::new(0.3f32, 4.0, 0.05)));
            if let Ok(inertia) = Inertia::try_from_principal(black_box(Vec3::new(6.0f32, 4.0, 3.0)))
            {
                let body = Gyrostat::rigid(inertia);
                let _ = black_box(body.step(Integrator::Strang, &state, inputs.dt));
            }
        }
        if links(ESTIMATE) {
            use gyrostat::estimation::{Estimator, Params};
            let inv = attitude.inverse();
            let acc = inv.rotate(black_box(Vec3::new(0.0f32, 0.0, 9.81)));
            let mag = inv.rotate(black_box(Vec3::new(0.0f32, 15.8, -40.7)));
            let gyro = black_box(Vec3::new(1.0f32, -2.0, 0.5)).scale(inputs.angle);
            if let Ok(mut f) = Estimator::try_new(black_box(Params::<f32>::default())) {
                let _ = black_box(f.update_9d(gyro, acc, mag, inputs.dt));
                let _ = black_box(f.update_9d(gyro, acc, mag, inputs.dt));
                black_box(f.attitude());
            }
        }
        if links(ESTIMATE_LIGHT) {
            use gyrostat::estimation::{Estimator, Mode, Params};
            let inv = attitude.inverse();
            let acc = inv.rotate(black_box(Vec3::new(0.0f32, 0.0, 9.81)));
            let mag = inv.rotate(black_box(Vec3::new(0.0f32, 15.8, -40.7)));
            let gyro = black_box(Vec3::new(1.0f32, -2.0, 0.5)).scale(inputs.angle);
            // The mode known at build time (the other numbers opaque): what the light mode
            // links when a firmware fixes it; a correction period of one step, so the second
            // update corrects.
            let params = Params {
                mode: Mode::Light {
                    correction_period: inputs.dt,
                },
                ..black_box(Params::<f32>::default())
            };
            if let Ok(mut f) = Estimator::try_new(params) {
                let _ = black_box(f.update_9d(gyro, acc, mag, inputs.dt));
                let _ = black_box(f.update_9d(gyro, acc, mag, inputs.dt));
                black_box(f.attitude());
            }
        }
        if links(EXACT) {
            use gyrostat::dynamics::{FreeRigidBody, Inertia, State};
            let moments = black_box(Vec3::new(6.0f32, 4.0, 3.0));
            let state = State::new(attitude, black_box(Vec3::new(0.3f32, 4.0, 0.05)));
            if let Ok(inertia) = Inertia::try_from_principal(moments)
                && let Ok(body) = FreeRigidBody::try_new(&inertia, &state)
            {
                let _ = black_box(body.try_state_at(inputs.t));
            }
        }
    }

    /// The word painted over the free stack before each measured call.
    const PAINT: u32 = 0xCCCC_CCCC;

    unsafe extern "C" {
        /// Lowest address of the stack (cortex-m-rt's linker script): the stack grows down
        /// towards it.
        static _stack_end: u32;
    }

    #[inline(always)]
    fn stack_pointer() -> usize {
        let sp: usize;
        // SAFETY: reads the stack pointer into a register; no memory access.
        unsafe { core::arch::asm!("mov {}, sp", out(reg) sp, options(nomem, nostack)) };
        sp
    }

    /// Paints the free stack, from its bottom (`_stack_end`) up to `top`, the stack pointer of
    /// the caller. Only volatile word stores in a loop (never a call, whose own frame would be
    /// painted over); everything it writes lies below the live frames.
    #[inline(always)]
    fn paint(top: usize) {
        let mut p = core::ptr::addr_of!(_stack_end) as usize;
        while p < top {
            // SAFETY: [_stack_end, top) is free stack, word-aligned, used by nothing live.
            unsafe { core::ptr::write_volatile(p as *mut u32, PAINT) };
            p += 4;
        }
    }

    /// Lowest stack address below `top` that no longer holds the paint.
    #[inline(always)]
    fn deepest_use(top: usize) -> usize {
        let mut p = core::ptr::addr_of!(_stack_end) as usize;
        // SAFETY: [_stack_end, top) is the part of the stack below the live frames, painted by
        // `paint` and word-aligned; nothing else writes it concurrently.
        while p < top && unsafe { core::ptr::read_volatile(p as *const u32) } == PAINT {
            p += 4;
        }
        p
    }

    /// `n` in decimal into `buf`, returning the digits (no formatting machinery).
    fn decimal(mut n: usize, buf: &mut [u8; 10]) -> &[u8] {
        let mut i = buf.len();
        loop {
            i -= 1;
            buf[i] = b'0' + (n % 10) as u8;
            n /= 10;
            if n == 0 || i == 0 {
                break;
            }
        }
        &buf[i..]
    }

    #[board::entry]
    fn main() -> ! {
        let top = stack_pointer();
        if STACK_RUN {
            let mut used = [0usize; CASES.len()];
            for (inputs, used) in CASES.iter().zip(used.iter_mut()) {
                paint(top);
                capability(black_box(inputs));
                *used = top - deepest_use(top);
            }
            let written = match cortex_m_semihosting::hio::hstdout() {
                Ok(mut out) => {
                    let mut ok = out.write_all(b"footprint ").is_ok()
                        && out.write_all(CAPABILITY.0.as_bytes()).is_ok()
                        && out.write_all(b" stack").is_ok();
                    for n in used {
                        let mut buf = [0u8; 10];
                        ok &= out.write_all(b" ").is_ok()
                            && out.write_all(decimal(n, &mut buf)).is_ok();
                    }
                    ok && out.write_all(b"\n").is_ok()
                }
                Err(()) => false,
            };
            board::exit(written)
        }
        capability(black_box(&CASES[0]));
        loop {
            cortex_m::asm::wfi();
        }
    }

    #[panic_handler]
    fn panic(_: &core::panic::PanicInfo) -> ! {
        unsafe extern "C" {
            fn gyrostat_footprint_capability_contains_a_panicking_branch() -> !;
        }
        // SAFETY: the symbol does not exist; reaching this line at link time is the failure.
        unsafe { gyrostat_footprint_capability_contains_a_panicking_branch() }
    }
}

#[cfg(not(target_os = "none"))]
fn main() {}
