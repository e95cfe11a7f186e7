//! Published special values: DLMF closed forms, Abramowitz & Stegun tables,
//! and the test values printed in Carlson (1995), Numer. Algorithms 10, 13–26
//! (arXiv:math/9409227), §3.

// The literals below quote published digits (or 20+ digit reference values)
// on purpose; rustc rounds them to the nearest f64.
#![allow(clippy::excessive_precision)]

use approx::assert_relative_eq;
use rotorflow::special::*;
use std::f64::consts::{FRAC_PI_2, LN_2, PI};

/// K(1/2) = Γ(1/4)² / (4√π), DLMF 19.20.2 / 23.17.3 (lemniscatic case).
const K_HALF: f64 = 1.854_074_677_301_371_918_433_850_347_195_260_046_2;
/// E(1/2) = Γ(1/4)²/(8√π) + π^{3/2}/Γ(1/4)² (Legendre relation at m = 1/2).
const E_HALF: f64 = 1.350_643_881_047_675_502_520_175_001_196_1;

#[test]
fn complete_special_values_dlmf() {
    // DLMF 19.6.1: K(0) = E(0) = π/2, E(1) = 1, K(1) = ∞
    assert_eq!(elliptic_k(0.0).unwrap(), FRAC_PI_2);
    assert_relative_eq!(elliptic_e(0.0).unwrap(), FRAC_PI_2, max_relative = 2.3e-16);
    assert_eq!(elliptic_e(1.0).unwrap(), 1.0);
    assert_eq!(elliptic_k(1.0).unwrap(), f64::INFINITY);
    assert_eq!(elliptic_e_complement(0.0).unwrap(), 1.0);
    // lemniscatic case
    assert_relative_eq!(elliptic_k(0.5).unwrap(), K_HALF, max_relative = 2.3e-16);
    assert_relative_eq!(elliptic_e(0.5).unwrap(), E_HALF, max_relative = 2.3e-16);
    // DLMF 19.6.1: Π(0|m) = K(m); Π(n|0) = π/(2√(1-n)) for n < 1
    assert_relative_eq!(
        elliptic_pi(0.0, 0.5).unwrap(),
        K_HALF,
        max_relative = 2.3e-16
    );
    for n in [-10.0, -0.5, 0.3, 0.9] {
        let want = FRAC_PI_2 / (1.0f64 - n).sqrt();
        assert_relative_eq!(elliptic_pi(n, 0.0).unwrap(), want, max_relative = 4.5e-16);
    }
    // DLMF 19.6.2: Π(m|m) = E(m)/(1-m)
    for m in [0.1, 0.5, 0.9] {
        let want = elliptic_e(m).unwrap() / (1.0 - m);
        assert_relative_eq!(elliptic_pi(m, m).unwrap(), want, max_relative = 1e-15);
    }
    // principal value: Π(n|0) = 0 for n > 1 (DLMF 19.6.5 with m = 0)
    assert_eq!(elliptic_pi(2.0, 0.0).unwrap(), 0.0);
}

/// Abramowitz & Stegun Table 17.1 (15 decimals), m = sin²α.
/// The table is rounded to 15 decimals (±5e-16) and exact in α; in f64,
/// m = sin²α carries a rounding error that K and E amplify by
/// dK/dm ∝ 1/(1-m), hence the looser bound at 80° and 89°.
#[test]
fn abramowitz_stegun_table_17_1() {
    let rows: [(f64, f64, f64, f64); 6] = [
        // α (deg), K, E, tolerance
        (10.0, 1.582_842_804_338_351, 1.558_887_196_601_596, 8e-16),
        (30.0, 1.685_750_354_812_596, 1.467_462_209_339_427, 8e-16),
        (45.0, 1.854_074_677_301_372, 1.350_643_881_047_676, 8e-16),
        (60.0, 2.156_515_647_499_643, 1.211_056_027_568_459, 8e-16),
        (80.0, 3.153_385_251_887_839, 1.040_114_395_706_010, 2e-15),
        (89.0, 5.434_909_829_625_564, 1.000_751_577_701_834, 1e-13),
    ];
    for (deg, k, e, tol) in rows {
        let m = deg.to_radians().sin().powi(2);
        assert_relative_eq!(elliptic_k(m).unwrap(), k, max_relative = tol);
        assert_relative_eq!(elliptic_e(m).unwrap(), e, max_relative = tol);
    }
}

/// Carlson (1995) §3 test values (printed to 14 significant digits), plus
/// their 25-digit values from mpmath for a tight check.
#[test]
fn carlson_1995_test_values() {
    let printed = 5e-14;
    let tight = 4.5e-16;
    // R_F
    assert_relative_eq!(
        carlson_rf(1.0, 2.0, 0.0).unwrap(),
        1.311_028_777_146_1,
        max_relative = printed
    );
    assert_relative_eq!(
        carlson_rf(1.0, 2.0, 0.0).unwrap(),
        1.311_028_777_146_059_905,
        max_relative = tight
    );
    assert_relative_eq!(
        carlson_rf(0.5, 1.0, 0.0).unwrap(),
        1.854_074_677_301_4,
        max_relative = printed
    );
    assert_relative_eq!(
        carlson_rf(2.0, 3.0, 4.0).unwrap(),
        0.584_082_841_677_15,
        max_relative = printed
    );
    assert_relative_eq!(
        carlson_rf(2.0, 3.0, 4.0).unwrap(),
        0.584_082_841_677_151_706_7,
        max_relative = tight
    );
    // R_C
    assert_relative_eq!(carlson_rc(0.0, 0.25).unwrap(), PI, max_relative = tight);
    assert_relative_eq!(carlson_rc(2.25, 2.0).unwrap(), LN_2, max_relative = tight);
    assert_relative_eq!(
        carlson_rc(0.25, -2.0).unwrap(),
        LN_2 / 3.0,
        max_relative = tight
    );
    // R_J
    assert_relative_eq!(
        carlson_rj(0.0, 1.0, 2.0, 3.0).unwrap(),
        0.776_886_237_785_82,
        max_relative = printed
    );
    assert_relative_eq!(
        carlson_rj(0.0, 1.0, 2.0, 3.0).unwrap(),
        0.776_886_237_785_823_320_1,
        max_relative = tight
    );
    assert_relative_eq!(
        carlson_rj(2.0, 3.0, 4.0, 5.0).unwrap(),
        0.142_975_796_671_57,
        max_relative = printed
    );
    assert_relative_eq!(
        carlson_rj(2.0, 3.0, 4.0, 5.0).unwrap(),
        0.142_975_796_671_567_538_3,
        max_relative = tight
    );
    // R_J principal values
    assert_relative_eq!(
        carlson_rj(2.0, 3.0, 4.0, -0.5).unwrap(),
        0.247_238_197_030_52,
        max_relative = printed
    );
    assert_relative_eq!(
        carlson_rj(2.0, 3.0, 4.0, -5.0).unwrap(),
        -0.127_112_300_429_64,
        max_relative = printed
    );
    assert_relative_eq!(
        carlson_rj(2.0, 3.0, 4.0, -5.0).unwrap(),
        -0.127_112_300_429_639_110_118_3,
        max_relative = 2e-15
    );
    // R_D
    assert_relative_eq!(
        carlson_rd(0.0, 2.0, 1.0).unwrap(),
        1.797_210_352_103_4,
        max_relative = printed
    );
    assert_relative_eq!(
        carlson_rd(0.0, 2.0, 1.0).unwrap(),
        1.797_210_352_103_388_311,
        max_relative = tight
    );
    assert_relative_eq!(
        carlson_rd(2.0, 3.0, 4.0).unwrap(),
        0.165_105_272_942_61,
        max_relative = printed
    );
    assert_relative_eq!(
        carlson_rd(2.0, 3.0, 4.0).unwrap(),
        0.165_105_272_942_610_533_5,
        max_relative = tight
    );
}

/// DLMF 19.20.1–19.20.2 and 19.20.4–19.20.5 closed forms.
#[test]
fn carlson_closed_forms_dlmf() {
    // R_F(x, x, x) = x^{-1/2}; R_F(0, y, y) = π/(2√y); R_F(0,1,2) lemniscate
    assert_relative_eq!(
        carlson_rf(4.0, 4.0, 4.0).unwrap(),
        0.5,
        max_relative = 2.3e-16
    );
    assert_relative_eq!(
        carlson_rf(0.0, 9.0, 9.0).unwrap(),
        PI / 6.0,
        max_relative = 4.5e-16
    );
    assert_relative_eq!(
        carlson_rf(0.0, 1.0, 2.0).unwrap(),
        1.311_028_777_146_059_905,
        max_relative = 2.3e-16
    );
    // R_D(x, x, x) = x^{-3/2}; R_D(0, y, y) = 3π/(4 y^{3/2})
    assert_relative_eq!(
        carlson_rd(4.0, 4.0, 4.0).unwrap(),
        0.125,
        max_relative = 2.3e-16
    );
    assert_relative_eq!(
        carlson_rd(0.0, 4.0, 4.0).unwrap(),
        3.0 * PI / 32.0,
        max_relative = 4.5e-16
    );
    // R_J(x, x, x, x) = x^{-3/2}; R_J(0, y, y, p) = 3π/(2(y√p + p√y))
    assert_relative_eq!(
        carlson_rj(4.0, 4.0, 4.0, 4.0).unwrap(),
        0.125,
        max_relative = 2.3e-16
    );
    let (y, p) = (2.0f64, 3.0f64);
    assert_relative_eq!(
        carlson_rj(0.0, y, y, p).unwrap(),
        3.0 * PI / (2.0 * (y * p.sqrt() + p * y.sqrt())),
        max_relative = 6.7e-16
    );
    // R_C(x, x) = x^{-1/2}; R_C(0, y) = π/(2√y); R_C(x, 0) = ∞; R_C(0, y<0) = 0
    assert_eq!(carlson_rc(4.0, 4.0).unwrap(), 0.5);
    assert_relative_eq!(
        carlson_rc(0.0, 4.0).unwrap(),
        PI / 4.0,
        max_relative = 2.3e-16
    );
    assert_eq!(carlson_rc(1.0, 0.0).unwrap(), f64::INFINITY);
    assert_eq!(carlson_rc(0.0, -3.0).unwrap(), 0.0);
    // divergent cases
    assert_eq!(carlson_rf(0.0, 0.0, 1.0).unwrap(), f64::INFINITY);
    assert_eq!(carlson_rd(1.0, 2.0, 0.0).unwrap(), f64::INFINITY);
    assert_eq!(carlson_rj(1.0, 2.0, 3.0, 0.0).unwrap(), f64::INFINITY);
}

/// Legendre's relation at m = 1/2 (lemniscatic, K = K'): 2EK − K² = π/2.
#[test]
fn legendre_relation_lemniscatic() {
    let k = elliptic_k(0.5).unwrap();
    let e = elliptic_e(0.5).unwrap();
    assert_relative_eq!(2.0 * e * k - k * k, FRAC_PI_2, max_relative = 1e-15);
}

/// Incomplete integrals: DLMF 19.6.8–19.6.11 special values.
#[test]
fn incomplete_special_values_dlmf() {
    let phi = 0.9f64;
    // F(φ|0) = E(φ|0) = φ; F(φ|1) = artanh(sin φ) = gd⁻¹ φ; E(φ|1) = sin φ
    assert_relative_eq!(elliptic_f(phi, 0.0).unwrap(), phi, max_relative = 2.3e-16);
    assert_relative_eq!(
        elliptic_e_inc(phi, 0.0).unwrap(),
        phi,
        max_relative = 2.3e-16
    );
    assert_relative_eq!(
        elliptic_f(phi, 1.0).unwrap(),
        phi.sin().atanh(),
        max_relative = 4.5e-16
    );
    assert_relative_eq!(
        elliptic_e_inc(phi, 1.0).unwrap(),
        phi.sin(),
        max_relative = 2.3e-16
    );
    // F(π/2|m) = K(m), E(π/2|m) = E(m), Π(n; π/2|m) = Π(n|m) (to the rounding of π/2)
    for m in [0.2, 0.7] {
        assert_relative_eq!(
            elliptic_f(FRAC_PI_2, m).unwrap(),
            elliptic_k(m).unwrap(),
            max_relative = 4.5e-16
        );
        assert_relative_eq!(
            elliptic_e_inc(FRAC_PI_2, m).unwrap(),
            elliptic_e(m).unwrap(),
            max_relative = 4.5e-16
        );
        assert_relative_eq!(
            elliptic_pi_inc(-2.0, FRAC_PI_2, m).unwrap(),
            elliptic_pi(-2.0, m).unwrap(),
            max_relative = 6.7e-16
        );
    }
    // Π(n; φ|0) = artan(√(1-n) tan φ)/√(1-n) for n < 1 (DLMF 19.6.11 family)
    for n in [-5.0f64, 0.5] {
        let r = (1.0 - n).sqrt();
        let want = (r * phi.tan()).atan() / r;
        assert_relative_eq!(
            elliptic_pi_inc(n, phi, 0.0).unwrap(),
            want,
            max_relative = 6.7e-16
        );
    }
    // F(φ|1) diverges at π/2 and beyond
    assert_eq!(elliptic_f(2.0, 1.0).unwrap(), f64::INFINITY);
    assert_eq!(elliptic_f(-2.0, 1.0).unwrap(), f64::NEG_INFINITY);
}

/// Jacobi functions at quarter periods: DLMF Table 22.5.1 and 22.5.2
/// (values at K and K/2).
#[test]
fn jacobi_quarter_and_half_quarter_values() {
    for m in [0.1, 0.5, 0.9, 1.0 - 1e-9] {
        let jac = Jacobi::new(m).unwrap();
        let k = jac.quarter_period();
        let kp = (1.0 - m).sqrt();
        // at u = K: sn = 1, cn = 0, dn = k', am = π/2. fl(K) differs from K by
        // up to half an ulp, so cn is only ~ulp(K) k' in absolute value.
        let at_k = jac.eval(k).unwrap();
        assert_relative_eq!(at_k.sn, 1.0, max_relative = 2.3e-16);
        assert!(at_k.cn.abs() <= 2.0 * f64::EPSILON * k * kp, "{at_k:?}");
        assert_relative_eq!(at_k.dn, kp, max_relative = 4.5e-16);
        assert_relative_eq!(at_k.am, FRAC_PI_2, max_relative = 2.3e-16);
        // at u = K/2: sn = (1+k')^{-1/2}, cn = (k'/(1+k'))^{1/2}, dn = k'^{1/2}
        let half = jac.eval(0.5 * k).unwrap();
        assert_relative_eq!(half.sn, 1.0 / (1.0 + kp).sqrt(), max_relative = 1e-15);
        assert_relative_eq!(half.cn, (kp / (1.0 + kp)).sqrt(), max_relative = 1e-15);
        assert_relative_eq!(half.dn, kp.sqrt(), max_relative = 1e-15);
        // am(2K) = π, am(-3K) = -3π/2 (2 fl(K) is off 2K by up to ulp(K))
        assert_relative_eq!(jac.eval(2.0 * k).unwrap().am, PI, max_relative = 6.7e-16);
        assert_relative_eq!(
            jac.eval(-3.0 * k).unwrap().am,
            -1.5 * PI,
            max_relative = 6.7e-16
        );
    }
}

/// m = 0 and m = 1 degenerate to circular and hyperbolic functions (DLMF 22.5.3–22.5.4).
#[test]
fn jacobi_degenerate_parameters() {
    for u in [-3.0f64, -0.2, 0.0, 0.4, 2.5, 40.0] {
        let c = jacobi_elliptic(u, 0.0).unwrap();
        assert_eq!((c.sn, c.cn, c.dn, c.am), (u.sin(), u.cos(), 1.0, u));
        let h = jacobi_elliptic(u, 1.0).unwrap();
        assert_eq!(h.sn, u.tanh());
        assert_eq!(h.cn, 1.0 / u.cosh());
        assert_eq!(h.dn, 1.0 / u.cosh());
        assert_relative_eq!(
            h.am,
            (2.0 * (0.5 * u).tanh().atan()),
            max_relative = 4.5e-16
        );
    }
}
