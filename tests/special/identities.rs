//! Identities checked as property tests (proptest, 256 cases each by default).

use proptest::prelude::*;
use rotorflow::special::*;
use std::f64::consts::{FRAC_PI_2, PI};

/// Parameters in [0, 1): uniform, plus some very close to 0 and to 1.
fn parameter() -> impl Strategy<Value = f64> {
    prop_oneof![
        0.0..1.0f64,
        (-16.0..-1.0f64).prop_map(|e| 10f64.powf(e)),
        (-16.0..-1.0f64).prop_map(|e| 1.0 - 10f64.powf(e)),
    ]
}

proptest! {
    /// DLMF 22.6.1: sn² + cn² = 1 and dn² + m sn² = 1, and sn, cn are the
    /// sine and cosine of am. The bound 1e-14 covers the measured accuracy
    /// near m = 1, where errors grow like (number of doublings) × ε × |v| with
    /// |v| ≤ K/2 ≈ ln(4/k')/2 (see the crate docs).
    #[test]
    fn jacobi_pythagorean_identities(u in -1e4..1e4f64, m in parameter()) {
        let j = jacobi_elliptic(u, m).unwrap();
        prop_assert!((j.sn * j.sn + j.cn * j.cn - 1.0).abs() <= 1e-14, "{j:?}");
        prop_assert!((j.dn * j.dn + m * j.sn * j.sn - 1.0).abs() <= 1e-14, "{j:?}");
        // sin/cos of the amplitude (am reaches 1e4, so allow its ulp)
        let tol = 1e-14 + 4e-16 * j.am.abs();
        prop_assert!((j.am.sin() - j.sn).abs() <= tol, "{j:?}");
        prop_assert!((j.am.cos() - j.cn).abs() <= tol, "{j:?}");
    }

    /// F(am(u|m)|m) = u (DLMF 22.16.1–22.16.2). The error of am is amplified
    /// by dF/dφ = 1/dn ≤ 1/k', so m is kept below 1 - 1e-4 here.
    #[test]
    fn jacobi_amplitude_inverts_f(u in -200.0..200.0f64, m in 0.0..0.9999f64) {
        let j = jacobi_elliptic(u, m).unwrap();
        let back = elliptic_f(j.am, m).unwrap();
        let tol = 4e-15 * u.abs().max(1.0) / (1.0 - m).sqrt();
        prop_assert!((back - u).abs() <= tol, "u={u} m={m} back={back}");
    }

    /// d am/du = dn (DLMF 22.16.2), by a 4th-order central difference.
    #[test]
    fn jacobi_amplitude_derivative_is_dn(u in -50.0..50.0f64, m in 0.0..0.999f64) {
        let h = 1e-3;
        let a = |x: f64| jacobi_elliptic(x, m).unwrap().am;
        let d = (8.0 * (a(u + h) - a(u - h)) - (a(u + 2.0 * h) - a(u - 2.0 * h))) / (12.0 * h);
        let dn = jacobi_elliptic(u, m).unwrap().dn;
        // truncation ~ h^4 |am^(5)|/30, rounding ~ 1e-16 |am| / h
        prop_assert!((d - dn).abs() <= 1e-9 + 1e-12 * u.abs() / (1.0 - m), "u={u} m={m} d={d} dn={dn}");
    }

    /// Addition theorem for sn, DLMF 22.8.1, with the denominator written as
    /// dn²u + m sn²u cn²v (= 1 − m sn²u sn²v) so that the test itself does not
    /// cancel when m → 1.
    #[test]
    fn jacobi_sn_addition_theorem(u in -20.0..20.0f64, v in -20.0..20.0f64, m in parameter()) {
        let a = jacobi_elliptic(u, m).unwrap();
        let b = jacobi_elliptic(v, m).unwrap();
        let s = jacobi_elliptic(u + v, m).unwrap();
        let t1 = a.sn * b.cn * b.dn;
        let t2 = b.sn * a.cn * a.dn;
        let den = a.dn * a.dn + m * a.sn * a.sn * b.cn * b.cn;
        let err = (s.sn * den - (t1 + t2)).abs();
        // relative accuracy of every factor, plus the rounding of u + v
        let scale = t1.abs() + t2.abs() + den * s.sn.abs();
        let tol = 1e-14 * scale + 4e-16 * (u + v).abs() * den;
        prop_assert!(err <= tol, "u={u} v={v} m={m} err={err:e} tol={tol:e}");
    }

    /// Periodicity: sn(u + 4K) = sn u, cn(u + 4K) = cn u, dn(u + 2K) = dn u,
    /// am(u + 2K) = am(u) + π (DLMF 22.4.1, 22.16.4).
    #[test]
    fn jacobi_periods(u in -100.0..100.0f64, m in 0.0..0.99f64) {
        let jac = Jacobi::new(m).unwrap();
        let k = jac.quarter_period();
        let a = jac.eval(u).unwrap();
        let b = jac.eval(u + 4.0 * k).unwrap();
        let c = jac.eval(u + 2.0 * k).unwrap();
        // the shifted arguments are rounded: allow ulp(|u| + 4K)
        let tol = 4.0 * f64::EPSILON * (u.abs() + 4.0 * k + 1.0);
        prop_assert!((a.sn - b.sn).abs() <= tol);
        prop_assert!((a.cn - b.cn).abs() <= tol);
        prop_assert!((a.dn - c.dn).abs() <= tol);
        prop_assert!((c.am - a.am - PI).abs() <= tol);
    }

    /// Legendre's relation, DLMF 19.7.1: E K' + E' K − K K' = π/2.
    #[test]
    fn legendre_relation(m in 1e-12..1.0f64) {
        let k = elliptic_k(m).unwrap();
        let e = elliptic_e(m).unwrap();
        let kc = elliptic_k_complement(m).unwrap(); // K' = K(1 - m)
        let ec = elliptic_e_complement(m).unwrap();
        let lhs = e * kc + ec * k - k * kc;
        // the three terms are each up to ~K K'; relative rounding of each
        let scale = (e * kc).max(k * kc);
        prop_assert!((lhs - FRAC_PI_2).abs() <= 2e-15 * scale, "m={m} lhs={lhs}");
    }

    /// Quasi-periodicity of the incomplete integrals, DLMF 19.2.10.
    #[test]
    fn incomplete_quasi_periodicity(phi in -1.5..1.5f64, j in -50i32..50, m in 0.0..0.99f64, n in -5.0..0.9f64) {
        let shifted = phi + f64::from(j) * PI;
        let jf = f64::from(j);
        let f = elliptic_f(shifted, m).unwrap();
        let f_want = elliptic_f(phi, m).unwrap() + 2.0 * jf * elliptic_k(m).unwrap();
        // shifted is rounded: its error times the integrand (≤ 1/k')
        let tol = 4.0 * f64::EPSILON * (shifted.abs() + 1.0) / (1.0 - m).sqrt();
        prop_assert!((f - f_want).abs() <= tol * 2.0, "F");
        let e = elliptic_e_inc(shifted, m).unwrap();
        let e_want = elliptic_e_inc(phi, m).unwrap() + 2.0 * jf * elliptic_e(m).unwrap();
        prop_assert!((e - e_want).abs() <= tol * 2.0, "E");
        let p = elliptic_pi_inc(n, shifted, m).unwrap();
        let p_want = elliptic_pi_inc(n, phi, m).unwrap() + 2.0 * jf * elliptic_pi(n, m).unwrap();
        prop_assert!((p - p_want).abs() <= tol * 2.0 / (1.0 - n.max(0.0)), "Pi");
    }

    /// Derivatives in φ: dF/dφ = 1/Δ, dE/dφ = Δ, dΠ/dφ = 1/((1 − n sin²φ) Δ)
    /// (DLMF 19.2.4–19.2.7), by 4th-order central differences.
    #[test]
    fn incomplete_derivatives(phi in -6.0..6.0f64, m in -2.0..0.99f64, n in -20.0..0.9f64) {
        let h = 1e-3;
        let d = |g: &dyn Fn(f64) -> f64| {
            (8.0 * (g(phi + h) - g(phi - h)) - (g(phi + 2.0 * h) - g(phi - 2.0 * h))) / (12.0 * h)
        };
        let s2 = phi.sin().powi(2);
        let delta = (1.0 - m * s2).sqrt();
        // 4th-order difference: truncation h^4 |f^(5)| / 30, which grows like
        // (|n| + |m|)^{5/2} and like (1 - m)^{-2} as m -> 1
        let tol = 1e-9 * ((1.0 + n.abs()) * (1.0 + m.abs())).powf(2.5) / (1.0 - m.max(0.0)).powi(2);
        prop_assert!((d(&|x| elliptic_f(x, m).unwrap()) - 1.0 / delta).abs() <= tol);
        prop_assert!((d(&|x| elliptic_e_inc(x, m).unwrap()) - delta).abs() <= tol);
        let want = 1.0 / ((1.0 - n * s2) * delta);
        prop_assert!((d(&|x| elliptic_pi_inc(n, x, m).unwrap()) - want).abs() <= tol / (1.0 - n.max(0.0)).powi(5));
    }

    /// R_F is symmetric; R_D is symmetric in its first two arguments only.
    /// Each evaluation is within ~2.4 ulp, so a permuted pair within ~5 ulp.
    #[test]
    fn carlson_symmetries(x in 0.0..10.0f64, y in 1e-3..10.0f64, z in 1e-3..10.0f64) {
        let a = carlson_rf(x, y, z).unwrap();
        for b in [carlson_rf(y, x, z), carlson_rf(z, y, x), carlson_rf(x, z, y)] {
            prop_assert!((a - b.unwrap()).abs() <= 1.2e-15 * a);
        }
        let d = carlson_rd(x, y, z).unwrap();
        prop_assert!((d - carlson_rd(y, x, z).unwrap()).abs() <= 1.2e-15 * d);
        let j = carlson_rj(x, y, z, 1.3).unwrap();
        prop_assert!((j - carlson_rj(z, x, y, 1.3).unwrap()).abs() <= 1.2e-15 * j);
    }

    /// Homogeneity: R_F(λx,λy,λz) = λ^{-1/2} R_F, R_D and R_J: λ^{-3/2},
    /// R_C: λ^{-1/2} (DLMF 19.16.1–19.16.2).
    #[test]
    fn carlson_homogeneity(x in 0.0..10.0f64, y in 1e-3..10.0f64, z in 1e-3..10.0f64,
                           p in 1e-3..10.0f64, lambda in 1e-3..1e3f64) {
        let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
        let s = lambda.sqrt();
        prop_assert!(rel(carlson_rf(lambda * x, lambda * y, lambda * z).unwrap() * s,
                         carlson_rf(x, y, z).unwrap()) <= 2e-15);
        prop_assert!(rel(carlson_rd(lambda * x, lambda * y, lambda * z).unwrap() * s * lambda,
                         carlson_rd(x, y, z).unwrap()) <= 3e-15);
        prop_assert!(rel(carlson_rj(lambda * x, lambda * y, lambda * z, lambda * p).unwrap() * s * lambda,
                         carlson_rj(x, y, z, p).unwrap()) <= 3e-15);
        prop_assert!(rel(carlson_rc(lambda * x, lambda * y).unwrap() * s,
                         carlson_rc(x, y).unwrap()) <= 2e-15);
    }

    /// R_D(x, y, z) = R_J(x, y, z, z) and R_C(x, y) = R_F(x, y, y) (DLMF 19.2.5, 19.2.17).
    #[test]
    fn carlson_degenerate_cases(x in 0.0..10.0f64, y in 1e-3..10.0f64, z in 1e-3..10.0f64) {
        let d = carlson_rd(x, y, z).unwrap();
        prop_assert!((d - carlson_rj(x, y, z, z).unwrap()).abs() <= 1e-15 * d);
        let c = carlson_rc(x, y).unwrap();
        prop_assert!((c - carlson_rf(x, y, y).unwrap()).abs() <= 1e-15 * c);
    }

    /// The complement entry points agree with the parameter entry points
    /// whenever 1 − m is exact (m ≥ 1/2).
    #[test]
    fn complement_entry_points_agree(u in -30.0..30.0f64, m in 0.5..1.0f64, phi in -4.0..4.0f64) {
        let m1 = 1.0 - m; // exact by Sterbenz
        let a = jacobi_elliptic(u, m).unwrap();
        let b = jacobi_elliptic_complement(u, m1).unwrap();
        prop_assert_eq!(a, b);
        prop_assert_eq!(elliptic_k(m).unwrap(), elliptic_k_complement(m1).unwrap());
        prop_assert_eq!(elliptic_f(phi, m).unwrap(), elliptic_f_complement(phi, m1).unwrap());
        prop_assert_eq!(elliptic_e_inc(phi, m).unwrap(), elliptic_e_inc_complement(phi, m1).unwrap());
        prop_assert_eq!(elliptic_pi_inc(-3.0, phi, m).unwrap(), elliptic_pi_inc_complement(-3.0, phi, m1).unwrap());
    }

    /// Symmetry in u: sn and am are odd, cn and dn even (DLMF 22.4.4–22.4.5).
    #[test]
    fn jacobi_parity(u in -1e3..1e3f64, m in parameter()) {
        let a = jacobi_elliptic(u, m).unwrap();
        let b = jacobi_elliptic(-u, m).unwrap();
        prop_assert_eq!(a.sn, -b.sn);
        prop_assert_eq!(a.cn, b.cn);
        prop_assert_eq!(a.dn, b.dn);
        prop_assert_eq!(a.am, -b.am);
    }
}
