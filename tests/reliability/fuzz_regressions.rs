//! Regression tests for what the fuzz targets under `fuzz/` found (issue #8 item 2), one per
//! finding, with the crash input inlined. `fuzz/README.md` lists the runs.

/// json_algebra: a long decimal literal parsed one ulp off by serde_json's default float
/// parser, so that an accepted value did not come back bit for bit through its own JSON.
/// Fixed by serde_json's `float_roundtrip` feature (enabled by rotorflow's `cli` feature).
#[cfg(feature = "serde")]
#[test]
fn fuzz_json_round_trip_is_bit_exact_for_long_literals() {
    use rotorflow::algebra::{Bivector, Multivector};
    let input = r#"{"signature":{"p":1,"q":1,"r":1},"coefficients":[177777777777777777777777777777777777777,2,7,4,4,6,888888888888888888888888888888888888888888888888888888888888888888888888888887,8]}"#;
    let m: Multivector = serde_json::from_str(input).unwrap();
    let back: Multivector = serde_json::from_str(&serde_json::to_string(&m).unwrap()).unwrap();
    assert_eq!(back, m);
    let b: Bivector =
        serde_json::from_str(r#"{"dim":3,"components":[8.888888888888889e77,1e-7,0.1]}"#).unwrap();
    assert_eq!(b.as_slice()[0], 8.888888888888889e77);
    let back: Bivector = serde_json::from_str(&serde_json::to_string(&b).unwrap()).unwrap();
    assert_eq!(back, b);
}

/// times_list: `--param d=1:2:2.5e-60` (and any STEP below (STOP − START)/1e5) overflowed the
/// integer count of values; now one bad-input error. The CLI side is in tests/cli/bad_input.rs.
#[cfg(feature = "cli")]
#[test]
fn fuzz_param_with_a_tiny_step_is_an_error_not_a_panic() {
    use rotorflow::cli::sweep::parse_param;
    for text in [
        "d=1:2:0.0000000000000000000000000000000000000000000000000000000000025",
        "d=-1e308:1e308:5e-324",
        "d=0:1e308:1e-308",
    ] {
        let err = parse_param(text).unwrap_err().to_string();
        assert!(err.contains("too many"), "{text}: {err}");
    }
    assert_eq!(parse_param("d=1:2:0.25").unwrap().values.len(), 5);
}

/// exp_log_bits: the invariant decomposition of a subnormal bivector reconstructs it to one
/// subnormal ulp (5e-324), not to 1e-9 relative: subnormals carry fewer digits. Not a bug;
/// the target's tolerance now allows an absolute error below the normal range. This pins the
/// accuracy that was observed.
#[test]
fn fuzz_decomposition_of_a_subnormal_bivector() {
    use rotorflow::algebra::Bivector;
    let b =
        Bivector::from_components(4, &[6.7153e-320, 6.071e-320, 0.0, 0.0, 0.0, 2.37e-322]).unwrap();
    let back = b.decompose().reconstruct();
    let err = (&back - &b).max_abs();
    assert!(err <= 1e-9 * b.max_abs() + f64::MIN_POSITIVE, "{err:e}");
    assert!(back.as_slice().iter().all(|x| x.is_finite()));
}
