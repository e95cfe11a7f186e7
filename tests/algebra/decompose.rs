//! The invariant decomposition on every hard family: isoclinic, near-isoclinic, zero,
//! rank-deficient, tiny and huge scales, N = 2 … 12.

use crate::support::*;
use rotorflow::prelude::*;

/// Checks the decomposition of `b`: reconstruction, orthonormality, magnitudes.
fn check(b: &Bivector, expected_mags: Option<&[f64]>, rel_tol: f64) -> Decomposition {
    let d = b.decompose();
    let scale = b.max_abs().max(f64::MIN_POSITIVE);
    let recon = (&d.reconstruct() - b).max_abs() / scale;
    assert!(recon <= rel_tol, "reconstruction error {recon:e} for {b}");
    assert!(d.len() <= b.dim() / 2);
    // all plane vectors orthonormal to one another
    let mut vecs: Vec<&Vector> = Vec::new();
    for p in d.planes() {
        vecs.push(p.u());
        vecs.push(p.v());
        assert!(p.magnitude() > 0.0 && p.magnitude().is_finite());
    }
    for (i, x) in vecs.iter().enumerate() {
        for (j, y) in vecs.iter().enumerate() {
            let target = if i == j { 1.0 } else { 0.0 };
            let g = x.dot(y);
            assert!((g - target).abs() < 1e-13, "gram[{i}][{j}] = {g}");
        }
    }
    // components commute pairwise (orthogonal planes)
    let parts: Vec<Bivector> = d.planes().iter().map(|p| p.bivector()).collect();
    for a in &parts {
        for c in &parts {
            assert!(a.commutator(c).max_abs() <= 1e-13 * scale.max(a.max_abs() * c.max_abs()));
        }
    }
    if let Some(m) = expected_mags {
        let got = d.magnitudes();
        assert_eq!(got.len(), m.len(), "magnitudes {got:?} vs {m:?}");
        for (g, e) in got.iter().zip(m) {
            assert!(
                (g - e).abs() <= rel_tol * e.abs().max(scale),
                "magnitude {g:e} vs {e:e}"
            );
        }
    }
    d
}

#[test]
fn isoclinic_bivector_07_e12_plus_e34() {
    let b = Bivector::from_components(4, &[0.7, 0.0, 0.0, 0.0, 0.0, 0.7]).unwrap();
    check(&b, Some(&[0.7, 0.7]), 1e-15);
    let anti = Bivector::from_components(4, &[0.7, 0.0, 0.0, 0.0, 0.0, -0.7]).unwrap();
    check(&anti, Some(&[0.7, 0.7]), 1e-15);
}

#[test]
fn isoclinic_in_random_frames_n_4_to_10() {
    let mut r = rng(11);
    for n in 4..=10 {
        for k in 2..=n / 2 {
            let mags = vec![1.3; k];
            let b = bivector_with_planes(&mut r, n, &mags);
            check(&b, Some(&mags), 1e-13);
        }
        // two isoclinic pairs with different magnitudes
        if n >= 8 {
            let mags = [2.0, 2.0, 0.5, 0.5];
            let b = bivector_with_planes(&mut r, n, &mags);
            check(&b, Some(&mags), 1e-13);
        }
    }
}

#[test]
fn near_isoclinic_gaps_from_1e_12_to_1e_3() {
    let mut r = rng(12);
    for n in [4, 5, 6, 8] {
        for gap in [1e-12, 1e-10, 1e-8, 1e-6, 1e-4, 1e-3] {
            let mags = [1.0 + gap, 1.0];
            let b = bivector_with_planes(&mut r, n, &mags);
            let d = check(&b, None, 2e-15 * n as f64);
            let m = d.magnitudes();
            // the magnitudes are determined to ~eps absolutely (their gap may be below that)
            assert!(
                (m[0] - (1.0 + gap)).abs() < 1e-14 && (m[1] - 1.0).abs() < 1e-14,
                "{m:?}"
            );
        }
    }
}

#[test]
fn zero_and_rank_deficient_bivectors() {
    let mut r = rng(13);
    for n in 2..=10 {
        assert!(Bivector::zero(n).decompose().is_empty());
        // simple bivector in a random frame: exactly one plane
        let b = bivector_with_planes(&mut r, n, &[0.9]);
        check(&b, Some(&[0.9]), 1e-14);
        // a wedge of two random vectors is simple
        let w = random_vector(&mut r, n).wedge(&random_vector(&mut r, n));
        let d = check(&w, None, 1e-14);
        assert_eq!(d.len(), 1);
        assert!(w.is_simple(1e-12));
        if n >= 6 {
            let b = bivector_with_planes(&mut r, n, &[1.0, 0.25]);
            check(&b, Some(&[1.0, 0.25]), 1e-14);
        }
    }
}

#[test]
fn tiny_and_huge_scales() {
    let mut r = rng(14);
    for n in [3, 4, 5, 7, 8] {
        let unit = random_bivector(&mut r, n, 1.0);
        let base = unit.decompose().magnitudes();
        for scale in [1e-300, 1e-200, 1e150, 1e200, 5e-320] {
            let b = &unit * scale;
            let d = check(&b, None, 1e-14);
            let m = d.magnitudes();
            assert_eq!(m.len(), base.len(), "scale {scale:e}");
            for (x, y) in m.iter().zip(&base) {
                // subnormal inputs have lost digits already; compare to the input's precision
                let tol = if scale < 1e-307 { 1e-3 } else { 1e-13 };
                assert!(
                    (x / scale - y).abs() <= tol * y,
                    "{x:e} vs {y:e} at {scale:e}"
                );
            }
        }
    }
}

#[test]
fn mixed_magnitudes_keep_small_planes_accurate() {
    // Planes of very different size: the deflation rescales each level.
    let mut r = rng(15);
    for n in [6, 8, 10] {
        let mags: Vec<f64> = (0..n / 2).map(|k| 10f64.powi(-4 * k as i32)).collect();
        let b = bivector_with_planes(&mut r, n, &mags);
        let d = check(&b, None, 1e-14);
        // absolute accuracy of every magnitude ~ eps · max
        for (g, e) in d.magnitudes().iter().zip(&mags) {
            assert!((g - e).abs() < 1e-14, "{g:e} vs {e:e}");
        }
    }
}

#[test]
fn decomposition_in_2d_and_3d_is_the_plane_itself() {
    let b = Bivector::from_plane(2, 0, 1, -2.0).unwrap();
    let d = check(&b, Some(&[2.0]), 1e-16);
    assert_eq!(d.planes()[0].bivector(), b);
    let b3 = Bivector::from_components(3, &[0.0, 3.0, 4.0]).unwrap();
    check(&b3, Some(&[5.0]), 1e-15);
}

#[test]
fn decomposition_up_to_n_12() {
    let mut r = rng(16);
    for n in 11..=12 {
        let b = random_bivector(&mut r, n, 1.0);
        check(&b, None, 1e-13);
    }
}
