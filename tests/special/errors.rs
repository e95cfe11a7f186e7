//! Domain handling: invalid input gives a typed error, never NaN.

use rotorflow::special::*;

const NAN: f64 = f64::NAN;
const INF: f64 = f64::INFINITY;

#[test]
fn non_finite_inputs_are_errors() {
    for bad in [NAN, INF, -INF] {
        assert!(matches!(
            carlson_rf(bad, 1.0, 1.0),
            Err(EllipticError::NonFinite { name: "x", .. })
        ));
        assert!(matches!(
            carlson_rd(1.0, 1.0, bad),
            Err(EllipticError::NonFinite { name: "z", .. })
        ));
        assert!(matches!(
            carlson_rj(1.0, 1.0, 1.0, bad),
            Err(EllipticError::NonFinite { name: "p", .. })
        ));
        assert!(matches!(
            carlson_rc(1.0, bad),
            Err(EllipticError::NonFinite { name: "y", .. })
        ));
        assert!(matches!(
            elliptic_k(bad),
            Err(EllipticError::NonFinite { name: "m", .. })
        ));
        assert!(matches!(
            elliptic_e_complement(bad),
            Err(EllipticError::NonFinite { name: "m1", .. })
        ));
        assert!(matches!(
            elliptic_pi(bad, 0.5),
            Err(EllipticError::NonFinite { name: "n", .. })
        ));
        assert!(matches!(
            elliptic_f(bad, 0.5),
            Err(EllipticError::NonFinite { name: "phi", .. })
        ));
        assert!(matches!(
            elliptic_pi_inc(0.5, 1.0, bad),
            Err(EllipticError::NonFinite { name: "m", .. })
        ));
        assert!(matches!(
            jacobi_elliptic(bad, 0.5),
            Err(EllipticError::NonFinite { name: "u", .. })
        ));
        assert!(matches!(
            jacobi_elliptic(1.0, bad),
            Err(EllipticError::NonFinite { name: "m", .. })
        ));
        assert!(matches!(
            Jacobi::from_complement(bad),
            Err(EllipticError::NonFinite { name: "m1", .. })
        ));
    }
}

#[test]
fn out_of_domain_inputs_are_errors() {
    assert!(matches!(
        carlson_rf(-1.0, 1.0, 1.0),
        Err(EllipticError::OutOfDomain { name: "x", .. })
    ));
    assert!(matches!(
        carlson_rd(1.0, -1e-300, 1.0),
        Err(EllipticError::OutOfDomain { name: "y", .. })
    ));
    assert!(matches!(
        carlson_rc(-2.0, 1.0),
        Err(EllipticError::OutOfDomain { name: "x", .. })
    ));
    assert!(matches!(
        elliptic_k(1.0 + f64::EPSILON),
        Err(EllipticError::OutOfDomain { name: "m", .. })
    ));
    assert!(matches!(
        elliptic_f(0.3, 2.0),
        Err(EllipticError::OutOfDomain { name: "m", .. })
    ));
    assert!(matches!(
        elliptic_f_complement(0.3, -0.5),
        Err(EllipticError::OutOfDomain { name: "m1", .. })
    ));
    assert!(matches!(
        jacobi_elliptic(1.0, -0.1),
        Err(EllipticError::OutOfDomain { name: "m", .. })
    ));
    assert!(matches!(
        jacobi_elliptic(1.0, 1.1),
        Err(EllipticError::OutOfDomain { name: "m", .. })
    ));
    assert!(matches!(
        jacobi_elliptic_complement(1.0, 1.5),
        Err(EllipticError::OutOfDomain { name: "m1", .. })
    ));
    assert!(matches!(
        carlson_rj(0.0, 0.0, 1.0, -1.0),
        Err(EllipticError::Divergent { .. })
    ));
}

#[test]
fn huge_arguments_are_errors() {
    assert!(matches!(
        elliptic_f(1e300, 0.5),
        Err(EllipticError::ArgumentTooLarge { name: "phi", .. })
    ));
    assert!(matches!(
        jacobi_elliptic(1e300, 0.5),
        Err(EllipticError::ArgumentTooLarge { name: "u", .. })
    ));
    // the circular and hyperbolic cases have no period reduction of their own
    assert!(jacobi_elliptic(1e300, 0.0).is_ok());
    assert!(jacobi_elliptic(1e300, 1.0).is_ok());
    // just below the limit still works
    assert!(jacobi_elliptic(1e14, 0.5).is_ok());
    assert!(elliptic_f(1e14, 0.5).is_ok());
}

#[test]
fn error_messages_name_the_argument() {
    let e = elliptic_k(3.0).unwrap_err();
    let msg = e.to_string();
    assert!(msg.contains("`m`") && msg.contains('3'), "{msg}");
    let e = jacobi_elliptic(NAN, 0.5).unwrap_err();
    assert!(e.to_string().contains("`u`"), "{e}");
}

/// A sweep over edge values (subnormals, ±0, 1 ± ulp, 1e±300): every call
/// either returns a typed error or a non-NaN value.
#[test]
fn no_nan_on_edge_values() {
    let edges = [
        0.0,
        -0.0,
        5e-324,
        1e-300,
        1e-16,
        0.5,
        1.0 - f64::EPSILON / 2.0,
        1.0,
        1.0 + f64::EPSILON,
        2.0,
        std::f64::consts::FRAC_PI_2,
        std::f64::consts::PI,
        -1.0,
        -1e10,
        1e10,
        1e300,
    ];
    // Overflow is allowed only when the arguments span more than the f64
    // range can hold after scaling (a subnormal next to a number ~1).
    let overflows = std::cell::Cell::new(0usize);
    let ok = |r: Result<f64, EllipticError>, what: &str| match r {
        Ok(v) => assert!(!v.is_nan(), "{what} gave NaN"),
        Err(EllipticError::Overflow { .. }) => {
            assert!(what.contains("5e-324"), "unexpected overflow: {what}");
            println!("overflow (subnormal argument): {what}");
            overflows.set(overflows.get() + 1);
        }
        Err(_) => {}
    };
    for &a in &edges {
        for &b in &edges {
            ok(carlson_rc(a, b), &format!("rc({a:e},{b:e})"));
            ok(elliptic_pi(a, b), &format!("pi({a:e},{b:e})"));
            ok(elliptic_f(a, b), &format!("f({a:e},{b:e})"));
            ok(elliptic_f_complement(a, b), &format!("fc({a:e},{b:e})"));
            ok(elliptic_e_inc(a, b), &format!("e({a:e},{b:e})"));
            ok(elliptic_e_inc_complement(a, b), &format!("ec({a:e},{b:e})"));
            if let Ok(j) = jacobi_elliptic(a, b) {
                assert!(
                    !(j.sn.is_nan() || j.cn.is_nan() || j.dn.is_nan() || j.am.is_nan()),
                    "jacobi({a:e},{b:e})"
                );
            }
            if let Ok(j) = jacobi_elliptic_complement(a, b) {
                assert!(
                    !(j.sn.is_nan() || j.cn.is_nan() || j.dn.is_nan() || j.am.is_nan()),
                    "jacobi_c({a:e},{b:e})"
                );
            }
            for &c in &edges {
                ok(carlson_rf(a, b, c), &format!("rf({a:e},{b:e},{c:e})"));
                ok(carlson_rd(a, b, c), &format!("rd({a:e},{b:e},{c:e})"));
                ok(
                    elliptic_pi_inc(a, b, c),
                    &format!("pi_inc({a:e},{b:e},{c:e})"),
                );
                ok(
                    elliptic_pi_inc_complement(a, b, c),
                    &format!("pi_inc_c({a:e},{b:e},{c:e})"),
                );
                for &d in &[-1.0, 0.0, 1e-300, 1.0, 1e300] {
                    ok(
                        carlson_rj(a, b, c, d),
                        &format!("rj({a:e},{b:e},{c:e},{d:e})"),
                    );
                }
            }
        }
    }
    // the Overflow variant is a rare safety net
    assert!(overflows.get() <= 6, "{} overflows", overflows.get());
}
