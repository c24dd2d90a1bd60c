//! `propagate --fixed` against the fixed-point firmware: fed the increments of the firmware's
//! built-in coning scenario (`examples/fw/fixed_scenario.rs`, included here and run on the host;
//! `host-tests/tests/fixed/firmware.rs` checks that the five boards print the same bits as the
//! host), the tool prints the firmware's attitudes bit for bit.

use std::io::Write;
use std::process::{Command, Stdio};

include!("../../../examples/fw/fixed_scenario.rs");

/// The scenario's lines as computed on the host.
fn host_lines() -> Vec<String> {
    let mut lines = Vec::new();
    run_scenario(&mut |a| lines.push(a.to_string())).expect("scenario runs");
    lines
}

/// The first line starting with `prefix`.
fn find<'a>(lines: &'a [String], prefix: &str) -> &'a str {
    lines
        .iter()
        .find(|l| l.starts_with(prefix))
        .unwrap_or_else(|| panic!("no line starting with {prefix:?}"))
}

/// `propagate --fixed`, fed the scenario's increments as decimal f64 text (shortest round-trip
/// form), prints exactly the firmware's attitudes: the 2-sample checkpoints and every rule's final
/// attitude, compared as raw Q1.30 integers.
#[test]
fn propagate_fixed_reproduces_the_firmware_bit_for_bit() {
    let lines = host_lines();
    let bin = crate::cli::tool("propagate");
    let s = scenario_start();
    let input: String = (0..N_INCREMENTS)
        .map(|k| {
            let [x, y, z] = scenario_increment(k);
            format!("{x:?},{y:?},{z:?}\n")
        })
        .collect();
    let raw = |x: &str| -> i32 {
        let v: f64 = x.parse().unwrap();
        let r = v * 2f64.powi(30);
        assert_eq!(r, r.round(), "{x} is not a multiple of 2^-30");
        r as i32
    };
    for (algo, prefix) in [
        ("exp", "rule Exp "),
        ("coning1", "rule OnePlusPrevious "),
        ("coning2", "rule TwoSample "),
        ("coning3", "rule ThreeSample "),
        ("coning4", "rule FourSample "),
    ] {
        let q0 = format!("{:?},{:?},{:?},{:?}", s[0], s[1], s[2], s[3]);
        let mut child = Command::new(&bin)
            .args(["--input", "increments", "--algo", algo, "--dt"])
            .arg(format!("{H:?}"))
            .args(["--q0", &q0, "--fixed"])
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .expect("propagate runs");
        // Written from a thread: the output pipe would fill while the input is still being fed.
        let mut stdin = child.stdin.take().unwrap();
        let feed = input.clone();
        let writer = std::thread::spawn(move || stdin.write_all(feed.as_bytes()));
        let out = child.wait_with_output().unwrap();
        writer.join().unwrap().unwrap();
        assert!(out.status.success(), "{algo}");
        let text = String::from_utf8(out.stdout).unwrap();
        let rows: Vec<Vec<&str>> = text.lines().map(|l| l.split(',').collect()).collect();
        assert_eq!(rows.len(), N_INCREMENTS, "{algo}: one row per increment");
        let bits = |row: &[&str]| -> Vec<i32> { row[1..5].iter().map(|x| raw(x)).collect() };
        let fw_bits = |line: &str, skip: usize| -> Vec<i32> {
            line.split_whitespace()
                .skip(skip)
                .map(|h| u32::from_str_radix(h, 16).unwrap() as i32)
                .collect()
        };
        let last = &rows[N_INCREMENTS - 1];
        let skip = prefix.split_whitespace().count();
        assert_eq!(
            bits(last),
            fw_bits(find(&lines, prefix), skip),
            "{algo}: final attitude"
        );
        if algo == "coning2" {
            for line in lines.iter().filter(|l| l.starts_with("coning2 ")) {
                let consumed: usize = line.split_whitespace().nth(1).unwrap().parse().unwrap();
                assert_eq!(bits(&rows[consumed - 1]), fw_bits(line, 2), "{line}");
            }
        }
    }
    println!("propagate --fixed: every rule's attitude equals the firmware's bits");
}

/// Black box, on inputs that do not repeat: the 3° cone at 19.37 Hz (1 kHz, 20 s) and a constant
/// rate from a base attitude (60 s, its increment not a multiple of 2⁻³⁰), started on the motion
/// and at the identity,
/// every rule, against the closed form (`host_tests::ref_propagation::Coning`; the constant rate's
/// `q₀ ⊗ exp(ω t)`): `--fixed` ends no farther from the exact attitude than `--f32` (or, where
/// the rule's own error is above f32's by chance, within 5 % of the f64 run), and for the
/// one-plus-previous and 2-sample rules on the cone its drift is within 5 % of the f64 run's.
#[test]
fn propagate_fixed_has_no_rounding_bias() {
    use host_tests::ref_propagation::Coning;
    use host_tests::reference::{qconj, qmul, quat_angle};
    let h = 1e-3;
    let cone = Coning {
        alpha: 3f64.to_radians(),
        omega_c: 2.0 * std::f64::consts::PI * 19.37,
    };
    let w: [f64; 3] = [0.3, -0.2, 0.5];
    let wn = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
    let (sb, cb) = 0.4f64.sin_cos();
    let base = [cb, 0.6 * sb, 0.8 * sb, 0.0];
    let rate = move |t: f64| {
        let (s, c) = (0.5 * wn * t).sin_cos();
        qmul(base, [c, s * w[0] / wn, s * w[1] / wn, s * w[2] / wn])
    };
    type Truth<'a> = &'a dyn Fn(f64) -> [f64; 4];
    type Increments<'a> = Box<dyn Fn(usize) -> [f64; 3] + 'a>;
    let motions: [(&str, usize, Truth, Increments); 2] = [
        (
            "cone 3° 19.37 Hz",
            20_000,
            &|t| cone.attitude(t),
            Box::new(|k| cone.increment(k as f64 * h, (k + 1) as f64 * h)),
        ),
        (
            "constant rate",
            60_000,
            &rate,
            Box::new(move |_| w.map(|x| x * h)),
        ),
    ];
    for (name, n, truth, inc) in &motions {
        let input: String = (0..*n)
            .map(|k| {
                let [x, y, z] = inc(k);
                format!("{x:?},{y:?},{z:?}\n")
            })
            .collect();
        let t_end = *n as f64 * h;
        for identity in [false, true] {
            let (q0, pre) = if identity {
                ([1.0, 0.0, 0.0, 0.0], qconj(truth(0.0)))
            } else {
                (truth(0.0), [1.0, 0.0, 0.0, 0.0])
            };
            let exact = qmul(pre, truth(t_end));
            for algo in ["exp", "coning1", "coning2", "coning3", "coning4"] {
                let e = |arith: &[&str]| {
                    quat_angle(exact, crate::cli::final_attitude(algo, arith, q0, &input))
                };
                let (fixed, f32, f64) = (e(&["--fixed"]), e(&["--f32"]), e(&[]));
                println!(
                    "{name:<17} identity={identity:<5} {algo:<8} --fixed {fixed:.3e}  --f32 {f32:.3e}  f64 {f64:.3e}"
                );
                assert!(
                    fixed <= f32 || fixed <= 1.05 * f64,
                    "{name} {algo}: --fixed {fixed:e}, --f32 {f32:e}, f64 {f64:e}"
                );
                if *name != "constant rate" && (algo == "coning1" || algo == "coning2") {
                    assert!((fixed / f64 - 1.0).abs() < 0.05, "{name} {algo}");
                }
            }
        }
    }
}
