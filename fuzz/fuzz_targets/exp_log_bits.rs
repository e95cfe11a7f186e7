//! exp, log, the invariant decomposition and matrix → rotor on raw f64 bit patterns.
//!
//! Input: one byte choosing N = 2 … 10, then little-endian f64 bit patterns (missing ones
//! are 0): N(N−1)/2 bivector components, then N×N matrix entries (row-major).
//!
//! Asserts:
//! - `Bivector::from_components` rejects exactly the inputs with a NaN or infinity;
//! - for an accepted B with |B| ≤ f64::MAX/2 (beyond, angles may overflow and the results
//!   are NaN by contract, only checked not to panic): `exp` is a finite unit
//!   rotor and exp(log R) = ±R; the decomposition
//!   is finite and reconstructs B to 1e-9 of max |B_ij| (plus the smallest normal number, for
//!   subnormal input); `exp_skew_matrix` is finite and
//!   orthogonal, and `Rotor::from_matrix` accepts it and gives back the same matrix;
//! - on the raw matrix: `Rotor::from_matrix`, `Rotor::from_matrix_projected` and
//!   `Attitude::from_matrix` never panic, reject non-finite entries, and an accepted matrix
//!   gives a finite rotor (attitude) whose matrix is the (projected) input to 1e-6.
#![no_main]

use libfuzzer_sys::fuzz_target;
use nalgebra::DMatrix;
use rotorflow::algebra::{Bivector, Rotor, bivector_len};
use rotorflow::dynamics::Attitude;

fn finite(xs: &[f64]) -> bool {
    xs.iter().all(|x| x.is_finite())
}

fn max_abs(m: &DMatrix<f64>) -> f64 {
    m.iter().fold(0.0f64, |a, x| a.max(x.abs()))
}

fn orthogonality_error(q: &DMatrix<f64>) -> f64 {
    let n = q.nrows();
    max_abs(&(q.transpose() * q - DMatrix::identity(n, n)))
}

/// max |R − S| over the coefficients, up to the overall sign.
fn rotor_distance(r: &Rotor, s: &Rotor) -> f64 {
    let (a, b) = (r.as_slice(), s.as_slice());
    let plus = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    let minus = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x + y).abs()));
    plus.min(minus)
}

fuzz_target!(|data: &[u8]| {
    let Some((&selector, rest)) = data.split_first() else {
        return;
    };
    let n = 2 + (selector as usize) % 9;
    let mut words = rest
        .chunks(8)
        .map(|c| {
            let mut b = [0u8; 8];
            b[..c.len()].copy_from_slice(c);
            f64::from_le_bytes(b)
        })
        .chain(std::iter::repeat(0.0));
    let components: Vec<f64> = words.by_ref().take(bivector_len(n)).collect();
    let entries: Vec<f64> = words.take(n * n).collect();

    match Bivector::from_components(n, &components) {
        Err(_) => assert!(
            !finite(&components),
            "finite components rejected: {components:?}"
        ),
        Ok(b) => {
            assert!(
                finite(&components),
                "non-finite components accepted: {components:?}"
            );
            check_bivector(&b);
        }
    }
    let m = DMatrix::from_row_slice(n, n, &entries);
    check_matrix(&m, finite(&entries));
});

fn check_bivector(b: &Bivector) {
    let scale = b.max_abs();
    let norm = b.norm();
    if norm.is_nan() || norm > f64::MAX / 2.0 {
        // |B| beyond f64::MAX/2: angles may overflow, and exp, decompose and exp_skew_matrix
        // then report it with NaN/∞ (documented on Bivector::exp). Only: no panic.
        let _ = (b.exp(), b.decompose().reconstruct(), b.exp_skew_matrix());
        return;
    }
    let r = b.exp();
    assert!(finite(r.as_slice()), "exp {b:?} = {r:?}");
    assert!(
        r.unit_error() < 1e-12,
        "exp {b:?}: unit error {:e}",
        r.unit_error()
    );
    let log = r.log();
    assert!(finite(log.as_slice()), "log {r:?} = {log:?}");
    let again = log.exp();
    let d = rotor_distance(&again, &r);
    assert!(d < 1e-12, "exp(log R) ≠ ±R by {d:e} for R = exp {b:?}");

    let decomposition = b.decompose();
    let back = decomposition.reconstruct();
    assert!(
        finite(back.as_slice()),
        "decomposition of {b:?}: {decomposition:?}"
    );
    let err = (&back - b).max_abs();
    assert!(
        // Subnormal components carry fewer digits: allow an absolute error below the normal
        // range (a run found 1 subnormal ulp on B ~ 1e-320).
        err <= 1e-9 * scale + f64::MIN_POSITIVE,
        "decompose {b:?}: reconstruction off by {err:e} (max |B| = {scale:e})"
    );

    let q = b.exp_skew_matrix();
    assert!(finite(q.as_slice()), "exp_skew_matrix {b:?} = {q}");
    let e = orthogonality_error(&q);
    assert!(
        e < 1e-12,
        "exp_skew_matrix {b:?}: orthogonality error {e:e}"
    );
    match Rotor::from_matrix(&q) {
        Ok(rq) => {
            let d = max_abs(&(rq.to_matrix() - &q));
            assert!(
                d < 1e-9,
                "from_matrix(exp [B]) round trip off by {d:e} for {b:?}"
            );
        }
        Err(err) => panic!("from_matrix rejects exp [B] of {b:?}: {err}"),
    }
}

fn check_matrix(m: &DMatrix<f64>, entries_finite: bool) {
    if let Ok(r) = Rotor::from_matrix(m) {
        assert!(entries_finite, "from_matrix accepted non-finite {m}");
        assert!(finite(r.as_slice()), "from_matrix {m} = {r:?}");
        let d = max_abs(&(r.to_matrix() - m));
        assert!(
            d < 1e-6,
            "from_matrix {m}: matrix of the rotor off by {d:e}"
        );
    }
    if let Ok(r) = Rotor::from_matrix_projected(m) {
        assert!(
            entries_finite,
            "from_matrix_projected accepted non-finite {m}"
        );
        assert!(finite(r.as_slice()), "from_matrix_projected {m} = {r:?}");
        assert!(
            r.unit_error() < 1e-9,
            "from_matrix_projected {m}: unit error {:e}",
            r.unit_error()
        );
    }
    if let Ok(a) = Attitude::from_matrix(m) {
        assert!(
            entries_finite,
            "Attitude::from_matrix accepted non-finite {m}"
        );
        assert!(a.is_finite(), "Attitude::from_matrix {m} = {a:?}");
        let d = max_abs(&(a.to_matrix() - m));
        assert!(d < 1e-6, "Attitude::from_matrix {m}: matrix off by {d:e}");
    }
}
