//! Elliptic integrals and Jacobi functions (`gyrostat::dynamics::closed_form::elliptic`) against identities,
//! known values and the independent quadrature reference of `host_tests::ref_exact`.
//!
//! Per-type tolerances: f32 results carry the f32 rounding of the argument reduction
//! `u − 2kK` (≈ ε·|u| with |u| ≤ 4K ≈ 33 at m = 1 − 10⁻⁶, ε = 1.2e-7) plus the amplitude
//! recurrence (≈ N steps of 1 ulp); f64 the same with ε = 2.2e-16. The bounds below are the
//! measured worst cases (printed with `--nocapture`) rounded up, and are what the module docs state.

// Reference values are quoted with all the digits of their source.
#![allow(clippy::excessive_precision)]

use gyrostat::Error;
use gyrostat::dynamics::closed_form::elliptic::{
    amplitude, carlson_rf, carlson_rj, complete_k, incomplete_f, incomplete_pi, sn_cn_dn,
};
use host_tests::ref_exact;
use host_tests::tolerance::Tolerance;

const PARAMS: [f64; 9] = [0.0, 1e-6, 0.1, 0.5, 0.8, 0.9, 0.99, 0.9999, 1.0 - 1e-6];

/// sn/cn/dn absolute error bound over |u| ≤ 4K, m ≤ 1 − 1e-6.
fn sncndn_bound<T: Tolerance>() -> f64 {
    T::per_type(4e-6, 5e-13)
}

/// K relative error bound; F relative error bound divided by (1 + its condition number). f64:
/// the quadrature reference's own accuracy near m → 1 (the library is checked to 4e-16 against
/// arbitrary-precision values in `known_values`).
fn rel_bound<T: Tolerance>() -> f64 {
    T::per_type(4e-7, 1e-14)
}

/// Identity residual bound (sn² + cn² − 1, dn² + m sn² − 1).
fn identity_bound<T: Tolerance>() -> f64 {
    T::per_type(5e-7, 1e-15)
}

#[test]
fn known_values() {
    use core::f64::consts::FRAC_PI_2;
    // K(0) = π/2 (A&S 17.3.11); K(1/2) = Γ(1/4)²/(4√π) (lemniscatic case, A&S 17.3.? / DLMF 19.20.2)
    let gamma_quarter = 3.625_609_908_221_908_3_f64;
    let k_half = gamma_quarter * gamma_quarter / (4.0 * core::f64::consts::PI.sqrt());
    assert_eq!(complete_k(0.0f64).unwrap(), FRAC_PI_2);
    // The quadrature reference itself reproduces the closed forms.
    assert!((ref_exact::ell_k(0.5) - k_half).abs() < 1e-15 * k_half);
    assert!((ref_exact::ell_k(0.0) - FRAC_PI_2).abs() < 1e-15);
    assert!((complete_k(0.5f64).unwrap() - k_half).abs() < 4e-16 * k_half);
    assert!((complete_k(0.5f32).unwrap() as f64 - k_half).abs() < 2e-7 * k_half);
    // K(0.9) = 2.5780921133481733 (A&S table 17.1)
    assert!((complete_k(0.9f64).unwrap() - 2.578_092_113_348_173_3).abs() < 1e-15);
    // K(m) at the f64 values of m below, computed with mpmath.ellipk at 30 digits (an
    // arbitrary-precision reference; the quadrature reference is only good to ~1e-14 near m → 1).
    for (m, k) in [
        (0.1, 1.612_441_348_720_219_400_7),
        (0.8, 2.257_205_326_820_853_756),
        (0.99, 3.695_637_362_989_874_238_6),
        (0.9999, 5.991_589_340_507_051_457),
        (1.0 - 1e-6, 8.294_051_463_601_062_201_9),
        (1.0 - 1e-12, 15.201_815_980_070_120_28),
    ] {
        let got: f64 = complete_k(m).unwrap();
        assert!((got - k).abs() <= 4e-16 * k, "K({m}) = {got}, want {k}");
        // f32: m rounds to f32 first; near m → 1 that moves K by ~ δm/(2(1−m)), so compare only
        // where the rounding of m is harmless.
        if m <= 0.99 {
            let got32 = complete_k(m as f32).unwrap() as f64;
            assert!((got32 - k).abs() <= 3e-7 * k, "K32({m}) = {got32}");
        }
    }
    for &m in &PARAMS {
        let k = complete_k(m).unwrap();
        let (s, c, d) = sn_cn_dn(k, m).unwrap();
        assert!(
            (s - 1.0).abs() < 1e-15 && c.abs() < 1e-9 && (d - (1.0 - m).sqrt()).abs() < 1e-12,
            "m={m}: {s} {c} {d}"
        );
        // sn(2K) = 0, cn(2K) = −1, dn(2K) = 1; odd/even symmetry
        let (s2, c2, d2) = sn_cn_dn(2.0 * k, m).unwrap();
        assert!(s2.abs() < 1e-12 && (c2 + 1.0).abs() < 1e-15 && (d2 - 1.0).abs() < 1e-15);
        let (sa, ca, da) = sn_cn_dn(0.3, m).unwrap();
        let (sb, cb, db) = sn_cn_dn(-0.3, m).unwrap();
        assert!(sa == -sb && ca == cb && da == db);
    }
    // m = 0: circular functions; m = 1: hyperbolic.
    for i in -50..=50 {
        let u = i as f64 * 0.37;
        let (s, c, d) = sn_cn_dn(u, 0.0).unwrap();
        assert!(
            (s - u.sin()).abs() < 1e-14 && (c - u.cos()).abs() < 1e-14 && (d - 1.0).abs() < 1e-15
        );
        let (s, c, d) = sn_cn_dn(u, 1.0).unwrap();
        assert!((s - u.tanh()).abs() < 1e-15 && (c - 1.0 / u.cosh()).abs() < 1e-15 && c == d);
    }
}

#[test]
fn domain_errors() {
    assert_eq!(complete_k(1.0f64), Err(Error::InvalidArgument));
    assert_eq!(complete_k(-0.1f32), Err(Error::InvalidArgument));
    assert_eq!(complete_k(f64::NAN), Err(Error::NonFinite));
    assert_eq!(sn_cn_dn(1.0f64, 1.5), Err(Error::InvalidArgument));
    assert_eq!(sn_cn_dn(f32::INFINITY, 0.5), Err(Error::NonFinite));
    assert_eq!(sn_cn_dn(1.0f64, f64::NAN), Err(Error::NonFinite));
    assert_eq!(incomplete_pi(1.0f64, 0.3, 0.5), Err(Error::InvalidArgument));
    assert_eq!(carlson_rf(0.0f64, 0.0, 1.0), Err(Error::InvalidArgument));
    assert_eq!(
        carlson_rj(1.0f64, 1.0, 1.0, 0.0),
        Err(Error::InvalidArgument)
    );
    assert_eq!(amplitude(1.0f64, 1.0), Err(Error::InvalidArgument));
}

host_tests::per_type! {
    /// The Jacobi identities `sn² + cn² = 1`, `dn² + m sn² = 1` and `dn > 0` over
    /// |u| ≤ 35, every parameter of `PARAMS` (bound: `identity_bound`).
    #[test]
    fn jacobi_identities() {
        let mut worst: f64 = 0.0;
        for &m in &PARAMS {
            for i in -200..=200 {
                let u = i as f64 * 0.173;
                let (s, c, d) = sn_cn_dn(T::from_f64(u), T::from_f64(m)).unwrap();
                let (s, c, d) = (s.to_f64(), c.to_f64(), d.to_f64());
                let mm = T::from_f64(m).to_f64();
                worst = worst.max((s * s + c * c - 1.0).abs());
                worst = worst.max((d * d + mm * s * s - 1.0).abs());
                assert!(d > 0.0);
            }
        }
        println!("{}: identity residual {worst:.2e}", T::NAME);
        assert!(worst <= identity_bound::<T>(), "{worst}");
    }

    /// `K`, `sn, cn, dn` and `F` against the quadrature reference (bounds: `rel_bound`,
    /// `sncndn_bound`).
    #[test]
    fn against_quadrature_reference() {
        let (mut ek, mut esn, mut ef): (f64, f64, f64) = (0.0, 0.0, 0.0);
        for &m in &PARAMS {
            let mt = T::from_f64(m).to_f64();
            let k_ref = ref_exact::ell_k(mt);
            let k = complete_k(T::from_f64(m)).unwrap().to_f64();
            ek = ek.max((k - k_ref).abs() / k_ref);
            for i in -40..=40 {
                let u = T::from_f64(i as f64 / 10.0 * k_ref).to_f64();
                let (s, c, d) = sn_cn_dn(T::from_f64(u), T::from_f64(m)).unwrap();
                let (sr, cr, dr) = ref_exact::sn_cn_dn(u, mt);
                esn = esn
                    .max((s.to_f64() - sr).abs())
                    .max((c.to_f64() - cr).abs())
                    .max((d.to_f64() - dr).abs());
            }
            for i in -12..=12 {
                let phi = T::from_f64(i as f64 * 0.31).to_f64();
                let f = incomplete_f(T::from_f64(phi), T::from_f64(m))
                    .unwrap()
                    .to_f64();
                let f_ref = ref_exact::ell_f(phi, mt);
                if f_ref != 0.0 {
                    // Relative error divided by (1 + condition number |φ F'(φ)/F|): the reduction
                    // φ − kπ and the rounding of φ itself are amplified by that much (up to ~250
                    // near φ = π/2 + kπ for m = 1 − 10⁻⁶) in any implementation.
                    let dn = (1.0 - mt * phi.sin().powi(2)).sqrt();
                    let cond = (phi / dn / f_ref).abs();
                    ef = ef.max((f - f_ref).abs() / f_ref.abs() / (1.0 + cond));
                }
            }
        }
        println!(
            "{}: K rel {ek:.2e}, sn/cn/dn abs {esn:.2e}, F rel {ef:.2e}",
            T::NAME
        );
        assert!(ek <= rel_bound::<T>(), "K {ek}");
        assert!(ef <= rel_bound::<T>(), "F {ef}");
        assert!(esn <= sncndn_bound::<T>(), "sncndn {esn}");
    }
}

#[test]
fn amplitude_inverts_f_and_pi_matches_quadrature() {
    let mut worst_pi: f64 = 0.0;
    for &m in &[0.0, 0.3, 0.9, 0.999] {
        for i in -30..=30 {
            let u = i as f64 * 0.29;
            let phi = amplitude(u, m).unwrap();
            let back = incomplete_f(phi, m).unwrap();
            assert!(
                (back - u).abs() < 1e-13 * (1.0 + u.abs()),
                "m={m} u={u}: {back}"
            );
        }
        for &n in &[-30.0, -2.0, -0.5, 0.0, 0.5, 0.9, 0.999] {
            for i in -10..=10 {
                let phi = i as f64 * 0.45;
                let p = incomplete_pi(n, phi, m).unwrap();
                let r = ref_exact::ell_pi(n, phi, m);
                let e = (p - r).abs() / r.abs().max(1e-300);
                if phi != 0.0 {
                    worst_pi = worst_pi.max(e);
                }
            }
        }
    }
    println!("Π relative error {worst_pi:.2e}");
    assert!(worst_pi < 1e-14, "{worst_pi}");
    // f32 Π: relative 1e-6 budget (a handful of f32 roundings in the Carlson sums).
    let p = incomplete_pi(0.5f32, 1.2, 0.7).unwrap() as f64;
    let r = ref_exact::ell_pi(0.5, 1.2f32 as f64, 0.7f32 as f64);
    assert!((p - r).abs() < 1e-6 * r, "{p} {r}");
}

#[test]
fn carlson_special_values() {
    // R_F(0, 1, 2) = 1.3110287771461 (Carlson 1995 test value); R_F(x,x,x) = 1/√x;
    // R_J(x,x,x,x) = x^{-3/2}; R_J(0,1,2,3) = 0.77688623778582 (Carlson 1995).
    assert!((carlson_rf(0.0f64, 1.0, 2.0).unwrap() - 1.311_028_777_146_1).abs() < 1e-13);
    assert!((carlson_rf(4.0f64, 4.0, 4.0).unwrap() - 0.5).abs() < 1e-16);
    assert!((carlson_rj(4.0f64, 4.0, 4.0, 4.0).unwrap() - 0.125).abs() < 1e-16);
    assert!((carlson_rj(0.0f64, 1.0, 2.0, 3.0).unwrap() - 0.776_886_237_785_82).abs() < 1e-13);
    assert!((carlson_rf(0.0f32, 1.0, 2.0).unwrap() as f64 - 1.311_028_777_146_1).abs() < 3e-7);
}

mod properties {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Identities and the addition-free symmetries for arbitrary (u, m): sn² + cn² = 1,
        /// dn² + m sn² = 1, sn(−u) = −sn u, and the quarter-period shift sn(u + K) = cd u
        /// (A&S 16.8.1), in f64.
        #[test]
        fn jacobi_laws(u in -60.0f64..60.0, m in 0.0f64..0.999_999) {
            let (s, c, d) = sn_cn_dn(u, m).unwrap();
            prop_assert!((s * s + c * c - 1.0).abs() < 1e-15);
            prop_assert!((d * d + m * s * s - 1.0).abs() < 1e-15);
            let (s2, c2, d2) = sn_cn_dn(-u, m).unwrap();
            prop_assert!(s2 == -s && c2 == c && d2 == d);
            let k = complete_k(m).unwrap();
            let (sk, _, _) = sn_cn_dn(u + k, m).unwrap();
            // Slope of sn ≤ 1, so the reduction rounding of |u| ≤ 60 + K bounds the difference.
            prop_assert!((sk - c / d).abs() < 1e-13 * (1.0 + u.abs()) / (1.0 - m).sqrt().max(1e-3), "{sk} vs {}", c / d);
        }
    }
}
