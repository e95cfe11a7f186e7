//! Property tests (proptest) over random dimensions N = 2 … 10 and random elements: the
//! algebraic identities the layer promises (products, involutions, exp and log, rotations).

use crate::support::*;
use proptest::prelude::*;
use rotorflow::prelude::*;

fn mv_strategy(n: usize) -> impl Strategy<Value = Multivector> {
    prop::collection::vec(-1.0f64..1.0, 1 << n)
        .prop_map(move |c| Multivector::from_coefficients(Signature::euclidean(n), &c).unwrap())
}

fn three_mvs() -> impl Strategy<Value = (Multivector, Multivector, Multivector)> {
    (2usize..=6).prop_flat_map(|n| (mv_strategy(n), mv_strategy(n), mv_strategy(n)))
}

fn bivector_strategy() -> impl Strategy<Value = Bivector> {
    (2usize..=10).prop_flat_map(|n| {
        prop::collection::vec(-2.0f64..2.0, n * (n - 1) / 2)
            .prop_map(move |c| Bivector::from_components(n, &c).unwrap())
    })
}

fn vector_pair(n: usize) -> impl Strategy<Value = (Vector, Vector)> {
    (
        prop::collection::vec(-1.0f64..1.0, n),
        prop::collection::vec(-1.0f64..1.0, n),
    )
        .prop_map(|(a, b)| {
            (
                Vector::from_components(&a).unwrap(),
                Vector::from_components(&b).unwrap(),
            )
        })
}

/// Bivector with all rotation angles below π (plane magnitudes < π − 0.05).
fn bounded_rotation() -> impl Strategy<Value = Bivector> {
    (
        2usize..=10,
        any::<u64>(),
        prop::collection::vec(0.0f64..(std::f64::consts::PI - 0.05), 5),
    )
        .prop_map(|(n, seed, mags)| {
            let mut r = rng(seed);
            bivector_with_planes(&mut r, n, &mags[..n / 2])
        })
}

/// 64 cases per property by default; `PROPTEST_CASES=N` raises it for long runs.
fn config() -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(64);
    ProptestConfig::with_cases(cases)
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn geometric_product_is_associative_and_distributive((a, b, c) in three_mvs()) {
        let left = &(&a * &b) * &c;
        let right = &a * &(&b * &c);
        prop_assert!((left - right).max_abs() < 1e-12);
        let d1 = &a * &(&b + &c);
        let d2 = &(&a * &b) + &(&a * &c);
        prop_assert!((d1 - d2).max_abs() < 1e-12);
    }

    #[test]
    fn reverse_is_an_anti_automorphism((a, b, _c) in three_mvs()) {
        let lhs = (&a * &b).reverse();
        let rhs = &b.reverse() * &a.reverse();
        prop_assert!((lhs - rhs).max_abs() < 1e-12);
    }

    #[test]
    fn wedge_and_contraction_come_from_the_geometric_product(
        (x, y) in (2usize..=10).prop_flat_map(vector_pair)
    ) {
        // a ∧ b = ½(ab − ba), a ⌋ b = ½(ab + ba) for vectors
        let (mx, my) = (Multivector::from(&x), Multivector::from(&y));
        let ab = &mx * &my;
        let ba = &my * &mx;
        let wedge = (&ab - &ba) * 0.5;
        let dot = (&ab + &ba) * 0.5;
        prop_assert!((mx.wedge(&my) - wedge.clone()).max_abs() < 1e-14);
        prop_assert!((mx.left_contract(&my) - dot.clone()).max_abs() < 1e-14);
        prop_assert!((dot.scalar_part() - x.dot(&y)).abs() < 1e-14);
        let w = Bivector::try_from(&wedge).unwrap();
        prop_assert!((&w - &x.wedge(&y)).max_abs() < 1e-14);
    }

    #[test]
    fn rotor_matrix_equals_matrix_exponential(b in bivector_strategy()) {
        let r = Rotor::from_rotation_bivector(&b);
        let expm = b.to_skew_matrix().transpose().exp();
        prop_assert!(max_abs_diff(&r.to_matrix(), &expm) < 1e-13);
        prop_assert!(r.unit_error() < 1e-14);
    }

    #[test]
    fn exp_log_round_trips(b in bounded_rotation()) {
        let r = Rotor::from_rotation_bivector(&b);
        let back = r.rotation_bivector();
        prop_assert!((&back - &b).max_abs() < 1e-13 * b.max_abs().max(1.0));
        prop_assert!(rotor_distance(&Rotor::from_rotation_bivector(&back), &r) < 1e-14);
    }

    #[test]
    fn rotor_matrix_rotor_round_trip(b in bivector_strategy()) {
        let r = Rotor::from_rotation_bivector(&b);
        let back = Rotor::from_matrix(&r.to_matrix()).unwrap();
        prop_assert!(rotor_distance_up_to_sign(&back, &r) < 1e-13);
    }

    #[test]
    fn sandwich_preserves_norms_and_inner_products(
        b in bivector_strategy(), seed in any::<u64>()
    ) {
        let n = b.dim();
        let mut rr = rng(seed);
        let r = Rotor::from_rotation_bivector(&b);
        let (x, y) = (random_vector(&mut rr, n), random_vector(&mut rr, n));
        let (rx, ry) = (r.rotate_vector(&x), r.rotate_vector(&y));
        // each component of R x R̃ sums N·2^(N−1) products: allow √(that)·ε·few
        let tol = 4.0 * f64::EPSILON * ((n << n) as f64).sqrt();
        prop_assert!((rx.dot(&ry) - x.dot(&y)).abs() < tol);
        prop_assert!((rx.norm() - x.norm()).abs() < tol);
        let c = random_bivector(&mut rr, n, 1.0);
        prop_assert!((r.rotate_bivector(&c).norm() - c.norm()).abs() < 1e-13);
    }

    #[test]
    fn decomposition_reconstructs_and_is_orthogonal(b in bivector_strategy()) {
        let d = b.decompose();
        prop_assert!((&d.reconstruct() - &b).max_abs() < 1e-14 * b.max_abs().max(1.0));
        let c = b.characteristic_coefficients();
        let pf = b.pfaffian();
        if b.dim() % 2 == 0 {
            prop_assert!((c[b.dim() / 2] - pf * pf).abs() < 1e-10 * c[b.dim() / 2].abs().max(1.0));
        }
    }

    #[test]
    fn hodge_twice_has_the_right_sign(
        (n, k, seed) in (2usize..=8).prop_flat_map(|n| (Just(n), 0..=n, any::<u64>()))
    ) {
        let mut rr = rng(seed);
        let mut m = Multivector::zero(Signature::euclidean(n));
        for (b, c) in m.as_mut_slice().iter_mut().enumerate() {
            if (b as u64).count_ones() as usize == k {
                *c = rand::Rng::gen_range(&mut rr, -1.0..1.0);
            }
        }
        let sign = if (k * (n - k)) % 2 == 0 { 1.0 } else { -1.0 };
        prop_assert!((m.hodge().hodge() - m.clone() * sign).max_abs() < 1e-15);
    }

    #[test]
    fn commutator_is_a_lie_bracket(
        (a, b, c) in (2usize..=10).prop_flat_map(|n| {
            let s = prop::collection::vec(-1.0f64..1.0, n * (n - 1) / 2);
            (s.clone(), s.clone(), s).prop_map(move |(x, y, z)| (
                Bivector::from_components(n, &x).unwrap(),
                Bivector::from_components(n, &y).unwrap(),
                Bivector::from_components(n, &z).unwrap(),
            ))
        })
    ) {
        prop_assert!((&a.commutator(&b) + &b.commutator(&a)).max_abs() < 1e-15);
        let jac = a.commutator(&b.commutator(&c))
            + b.commutator(&c.commutator(&a))
            + c.commutator(&a.commutator(&b));
        prop_assert!(jac.max_abs() < 1e-13);
    }
}
