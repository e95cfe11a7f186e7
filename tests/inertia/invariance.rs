//! Property tests: rotating a body rotates J, translating leaves it alone, the
//! parallel-axis theorem, and J symmetric PSD, for random point clouds and random solids in
//! N = 2…6.
use crate::common::{max_abs, random_rotation, rng};
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;
use rotorflow::inertia::Body;

/// A random point cloud: dimension 2…6, 1…12 points with coordinates in [−10, 10] and
/// masses in [0.1, 10], plus a seed for a random rotation.
fn cloud() -> impl Strategy<Value = (usize, Vec<f64>, Vec<DVector<f64>>, u64)> {
    (2usize..=6).prop_flat_map(|n| {
        (1usize..=12).prop_flat_map(move |count| {
            (
                Just(n),
                prop::collection::vec(0.1f64..10.0, count),
                prop::collection::vec(
                    prop::collection::vec(-10.0f64..10.0, n).prop_map(DVector::from_vec),
                    count,
                ),
                any::<u64>(),
            )
        })
    })
}

/// Direct Σ m (x − o)(x − o)ᵀ.
fn direct_mass_tensor(masses: &[f64], points: &[DVector<f64>], o: &DVector<f64>) -> DMatrix<f64> {
    let n = o.len();
    let mut j = DMatrix::zeros(n, n);
    for (m, p) in masses.iter().zip(points) {
        let d = p - o;
        j += &d * d.transpose() * *m;
    }
    j
}

// Tolerance: entries of J are sums of at most 12 terms m x x of size ≤ 10 · 400; rounding
// and the eigensolver stay below 1e-12 relative to the largest entry (observed ≲ 1e-14).
const REL: f64 = 1e-12;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn rotating_a_body_rotates_its_mass_tensor((n, masses, points, seed) in cloud()) {
        let body = Body::point_masses(&masses, &points).unwrap();
        let q = random_rotation(n, &mut rng(seed));
        let rotated = body.rotated(&q).unwrap();
        // Independent path: rotate the points, then build.
        let moved: Vec<DVector<f64>> = points.iter().map(|p| &q * p).collect();
        let rebuilt = Body::point_masses(&masses, &moved).unwrap();
        let scale = max_abs(body.mass_tensor()).max(1e-300) + body.mass() * 1e-12;
        let expected = &q * body.mass_tensor() * q.transpose();
        prop_assert!(crate::common::max_abs_diff(rotated.mass_tensor(), &expected) <= REL * scale);
        prop_assert!(crate::common::max_abs_diff(rotated.mass_tensor(), rebuilt.mass_tensor()) <= REL * scale * 10.0);
        prop_assert!((rotated.center_of_mass() - rebuilt.center_of_mass()).norm() <= 1e-12 * 10.0);
        let (a, b) = (body.principal_second_moments(), rotated.principal_second_moments());
        for i in 0..n {
            prop_assert!((a[i] - b[i]).abs() <= REL * scale * 10.0);
        }
    }

    #[test]
    fn translating_keeps_j_and_moves_the_centre((n, masses, points, seed) in cloud()) {
        let body = Body::point_masses(&masses, &points).unwrap();
        let d = DVector::from_fn(n, |i, _| (seed >> (i * 8)) as u8 as f64 - 128.0);
        let moved = body.translated(&d).unwrap();
        prop_assert_eq!(moved.mass_tensor(), body.mass_tensor());
        prop_assert!((moved.center_of_mass() - body.center_of_mass() - &d).norm() <= 1e-12 * (1.0 + d.norm()));
    }

    #[test]
    fn parallel_axis_theorem_matches_direct_sum((n, masses, points, seed) in cloud()) {
        let body = Body::point_masses(&masses, &points).unwrap();
        let o = DVector::from_fn(n, |i, _| ((seed >> (i * 8)) as u8 as f64 - 128.0) / 16.0);
        let about = body.mass_tensor_about(&o).unwrap();
        let direct = direct_mass_tensor(&masses, &points, &o);
        prop_assert!(crate::common::max_abs_diff(&about, &direct) <= REL * max_abs(&direct).max(1.0));
        // About the centre of mass the direct sum is J itself.
        let at_cm = direct_mass_tensor(&masses, &points, body.center_of_mass());
        prop_assert!(crate::common::max_abs_diff(&at_cm, body.mass_tensor()) <= REL * max_abs(&at_cm).max(1.0));
    }

    #[test]
    fn mass_tensor_is_symmetric_psd((_n, masses, points, _seed) in cloud()) {
        let body = Body::point_masses(&masses, &points).unwrap();
        let j = body.mass_tensor();
        prop_assert_eq!(j, &j.transpose());
        let moments = body.principal_second_moments();
        prop_assert!(moments[0] >= -REL * max_abs(j).max(1e-300));
    }

    #[test]
    fn rotating_a_solid_keeps_its_principal_moments(n in 2usize..=6, seed in any::<u64>(), a in 0.1f64..3.0) {
        let axes: Vec<f64> = (0..n).map(|i| a + i as f64 * 0.5).collect();
        let body = Body::solid_ellipsoid(&axes, 1.0).unwrap();
        let q = random_rotation(n, &mut rng(seed));
        let rotated = body.rotated(&q).unwrap();
        let (x, y) = (body.principal_second_moments(), rotated.principal_second_moments());
        for i in 0..n {
            prop_assert!((x[i] - y[i]).abs() <= REL * x[n - 1]);
        }
        // Plane moments in the body's own axes change, principal ones do not.
        let (p, r) = (body.principal_plane_moments(), rotated.principal_plane_moments());
        for k in 0..p.len() {
            prop_assert!((p[k] - r[k]).abs() <= REL * x[n - 1] * 2.0);
        }
    }
}
