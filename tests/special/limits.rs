//! Continuity at the ends of the parameter range: m → 0 and m → 1
//! (the rigid body's separatrix), checked against the asymptotic expansions
//! of DLMF 19.12 and 22.10(ii).

use rotorflow::special::*;
use std::f64::consts::FRAC_PI_2;

/// DLMF 22.10.4–22.10.6 (m → 0): sn = sin u − (m/4)(u − sin u cos u) cos u + O(m²), etc.
#[test]
fn jacobi_small_parameter_expansion() {
    for m in [1e-300, 1e-16, 1e-12, 1e-8] {
        for u in [0.3f64, 1.0, 2.0, 5.0] {
            let j = jacobi_elliptic(u, m).unwrap();
            let (s, c) = u.sin_cos();
            let t = u - s * c;
            let sn = s - 0.25 * m * t * c;
            let cn = c + 0.25 * m * t * s;
            let dn = 1.0 - 0.5 * m * s * s;
            let am = u - 0.25 * m * t;
            // O(m^2 u^2) remainder plus a few ulp
            let tol = 4e-16 + 2.0 * m * m * u * u;
            assert!((j.sn - sn).abs() <= tol, "m={m} u={u} {j:?} sn={sn}");
            assert!((j.cn - cn).abs() <= tol, "m={m} u={u} {j:?} cn={cn}");
            assert!((j.dn - dn).abs() <= tol, "m={m} u={u} {j:?} dn={dn}");
            assert!((j.am - am).abs() <= tol, "m={m} u={u} {j:?} am={am}");
        }
    }
}

/// DLMF 22.10.7–22.10.9 (m → 1): sn = tanh u + (m1/4)(sinh u cosh u − u) sech² u + O(m1²), etc.
#[test]
fn jacobi_near_one_expansion() {
    for m1 in [1e-300, 1e-100, 1e-20, 1e-16, 1e-12, 1e-9] {
        for u in [0.3f64, 1.0, 2.0, 4.0] {
            let j = jacobi_elliptic_complement(u, m1).unwrap();
            let (sh, ch, th) = (u.sinh(), u.cosh(), u.tanh());
            let sech = 1.0 / ch;
            let t = sh * ch - u;
            let sn = th + 0.25 * m1 * t * sech * sech;
            let cn = sech - 0.25 * m1 * t * th * sech;
            let dn = sech + 0.25 * m1 * (sh * ch + u) * th * sech;
            let am = (sh).atan() + 0.25 * m1 * t * sech;
            // remainder O(m1^2 e^{4u}), plus a few ulp (the expected values
            // are themselves rounded f64 expressions)
            let tol = 1e-15 + m1 * m1 * (4.0 * u).exp();
            for (got, want, what) in [(j.sn, sn, "sn"), (j.am, am, "am")] {
                assert!(
                    (got - want).abs() <= tol,
                    "m1={m1} u={u} {what} {got} {want}"
                );
            }
            for (got, want, what) in [(j.cn, cn, "cn"), (j.dn, dn, "dn")] {
                assert!(
                    (got - want).abs() <= tol * want,
                    "m1={m1} u={u} {what} {got} {want}"
                );
            }
        }
    }
}

/// Approaching m = 1 through smaller and smaller m1 (from 1e-12, where
/// K(m) > 2|u| for these u), sn/cn/dn/am at fixed u converge monotonically to
/// the m = 1 values (no jump at the switch to the hyperbolic branch), and the
/// m = 0 branch is approached the same way.
#[test]
fn jacobi_limits_are_continuous() {
    for u in [0.5f64, 3.0, -7.0] {
        let at_one = jacobi_elliptic(u, 1.0).unwrap();
        let mut prev = f64::INFINITY;
        for k in 12..=300 {
            let m1 = 10f64.powi(-k);
            let j = jacobi_elliptic_complement(u, m1).unwrap();
            let dist = (j.sn - at_one.sn).abs()
                + (j.cn - at_one.cn).abs() / at_one.cn
                + (j.dn - at_one.dn).abs() / at_one.dn
                + (j.am - at_one.am).abs();
            assert!(
                dist <= prev.max(2e-15),
                "u={u} m1={m1} dist={dist} prev={prev}"
            );
            prev = dist;
        }
        assert!(prev <= 2e-15, "u={u}: limit gap {prev}");
        let at_zero = jacobi_elliptic(u, 0.0).unwrap();
        let near_zero = jacobi_elliptic(u, 1e-300).unwrap();
        for (a, b) in [
            (at_zero.sn, near_zero.sn),
            (at_zero.cn, near_zero.cn),
            (at_zero.dn, near_zero.dn),
            (at_zero.am, near_zero.am),
        ] {
            assert!((a - b).abs() <= 1e-15, "u={u}: {a} vs {b}");
        }
    }
}

/// DLMF 19.12.1–19.12.2: K ≈ ln(4/k') + (m1/4)(ln(4/k') − 1), E ≈ 1 + (m1/2)(ln(4/k') − 1/2).
#[test]
fn complete_integrals_near_one() {
    for m1 in [1e-300f64, 1e-100, 1e-30, 1e-16, 1e-12, 1e-8] {
        let l = (4.0 / m1.sqrt()).ln();
        let k = l + 0.25 * m1 * (l - 1.0);
        let e = 1.0 + 0.5 * m1 * (l - 0.5);
        let tol = 4e-16 + m1 * m1 * l * l;
        let got_k = elliptic_k_complement(m1).unwrap();
        let got_e = elliptic_e_complement(m1).unwrap();
        assert!((got_k - k).abs() <= tol * k, "m1={m1}: K {got_k} vs {k}");
        assert!((got_e - e).abs() <= tol, "m1={m1}: E {got_e} vs {e}");
    }
    // the ends themselves
    assert_eq!(elliptic_k_complement(0.0).unwrap(), f64::INFINITY);
    assert_eq!(elliptic_e_complement(0.0).unwrap(), 1.0);
    assert_eq!(elliptic_e_complement(5e-324).unwrap(), 1.0);
}

/// DLMF 19.5.1–19.5.2 (m → 0): K = (π/2)(1 + m/4 + 9m²/64 + …), E = (π/2)(1 − m/4 − 3m²/64 − …).
#[test]
fn complete_integrals_near_zero() {
    for m in [-1e-8, -1e-300, 0.0, 1e-300, 1e-16, 1e-8] {
        let k = FRAC_PI_2 * (1.0 + m / 4.0 + 9.0 * m * m / 64.0);
        let e = FRAC_PI_2 * (1.0 - m / 4.0 - 3.0 * m * m / 64.0);
        assert!((elliptic_k(m).unwrap() - k).abs() <= 4.5e-16 * k, "K({m})");
        assert!((elliptic_e(m).unwrap() - e).abs() <= 4.5e-16 * e, "E({m})");
    }
}

/// Incomplete integrals near m = 1 for φ < π/2:
/// F → artanh(sin φ), E → sin φ, with O(m1 ln m1) corrections.
#[test]
fn incomplete_integrals_near_one() {
    for phi in [0.2f64, 1.0, 1.5, FRAC_PI_2 - 1e-6] {
        let f1 = elliptic_f(phi, 1.0).unwrap();
        let e1 = elliptic_e_inc(phi, 1.0).unwrap();
        // asinh(tan φ) = artanh(sin φ), but without artanh's loss near 1
        assert!((f1 - phi.tan().asinh()).abs() <= 1e-15 * f1);
        assert!((e1 - phi.sin()).abs() <= 4e-16);
        let mut prev_f = f64::INFINITY;
        for k in 2..=300 {
            let m1 = 10f64.powi(-k);
            let f = elliptic_f_complement(phi, m1).unwrap();
            let e = elliptic_e_inc_complement(phi, m1).unwrap();
            let gap = (f - f1).abs();
            assert!(gap <= prev_f.max(4e-15 * f1), "phi={phi} m1={m1}");
            prev_f = gap;
            assert!(
                (e - e1).abs() <= 1e-15 + m1 * 10.0 / phi.cos(),
                "phi={phi} m1={m1}"
            );
        }
        assert!(prev_f <= 4e-15 * f1);
    }
    // F(φ|m) at φ = fl(π/2): finite and equal to asinh(tan φ) for m = 1
    let f = elliptic_f(FRAC_PI_2, 1.0).unwrap();
    assert!((f - FRAC_PI_2.tan().asinh()).abs() <= 1e-15 * f, "{f}");
}

/// Π(n; φ|m) for n → −∞ (the rigid body rotating almost about its major axis):
/// √(−n) Π(n|m) → π/2, since the integrand concentrates at θ = 0 where Δ = 1;
/// the next term is O(K(m)/√(−n)).
#[test]
fn pi_for_very_negative_n() {
    for m in [0.0, 0.5, 0.99] {
        for n in [-1e4, -1e8, -1e12, -1e16] {
            let p = elliptic_pi(n, m).unwrap();
            let scaled = p * (-n).sqrt();
            // leading correction is O(1/√(-n))
            let k = elliptic_k(m).unwrap();
            let tol = 2.0 * (1.0 + k) / (-n).sqrt() + 1e-15;
            assert!((scaled - FRAC_PI_2).abs() <= tol, "m={m} n={n} {scaled}");
            assert!(p > 0.0);
        }
    }
}
