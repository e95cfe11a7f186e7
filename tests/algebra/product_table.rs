//! `ProductTable` against the products it tabulates: the same coefficients bit for bit (up
//! to the sign of a zero), one pair at a time and in batches of every length around a block.

use rotorflow::algebra::{
    AlgebraError, Multivector, PRODUCT_TABLE_MAX_DIM, Product, ProductTable, Signature,
};

fn coefficients(seed: u64, len: usize) -> Vec<f64> {
    // A small deterministic generator: values in (−2, 2) with some exact zeros.
    let mut x = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (0..len)
        .map(|_| {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let v = ((x >> 11) as f64 / (1u64 << 53) as f64) * 4.0 - 2.0;
            if x.is_multiple_of(7) { 0.0 } else { v }
        })
        .collect()
}

const KINDS: [Product; 8] = [
    Product::Geometric,
    Product::Wedge,
    Product::LeftContraction,
    Product::RightContraction,
    Product::Scalar,
    Product::Commutator,
    Product::Anticommutator,
    Product::Regressive,
];

fn signatures() -> Vec<Signature> {
    [
        (3, 0, 0),
        (2, 1, 0),
        (3, 0, 1),
        (4, 1, 0),
        (1, 3, 0),
        (2, 2, 2),
        (5, 0, 0),
    ]
    .iter()
    .map(|&(p, q, r)| Signature::new(p, q, r).unwrap())
    .collect()
}

#[test]
fn one_pair_equals_the_product_for_every_kind_and_signature() {
    let mut checked = 0;
    for sig in signatures() {
        let size = 1 << sig.dim();
        for (k, kind) in KINDS.iter().enumerate() {
            let table = ProductTable::new(sig, *kind).unwrap();
            assert_eq!(table.signature(), sig);
            for seed in 0..4 {
                let a = coefficients(seed * 31 + k as u64, size);
                let b = coefficients(seed * 17 + 5, size);
                let (ma, mb) = (
                    Multivector::from_coefficients(sig, &a).unwrap(),
                    Multivector::from_coefficients(sig, &b).unwrap(),
                );
                let expected = ma.try_product(&mb, *kind).unwrap();
                let mut out = vec![1.0; size];
                table.apply(&a, &b, &mut out).unwrap();
                if *kind == Product::Regressive {
                    // Summed in the order of a and b rather than of their complements.
                    for (x, y) in out.iter().zip(expected.as_slice()) {
                        assert!((x - y).abs() <= 1e-15 * (1.0 + y.abs()), "{sig} regressive");
                    }
                } else {
                    assert_eq!(out.as_slice(), expected.as_slice(), "{sig} {kind:?}");
                }
                checked += 1;
            }
        }
        let inner = ProductTable::inner(sig).unwrap();
        let a = coefficients(99, size);
        let b = coefficients(98, size);
        let (ma, mb) = (
            Multivector::from_coefficients(sig, &a).unwrap(),
            Multivector::from_coefficients(sig, &b).unwrap(),
        );
        let mut out = vec![0.0; size];
        inner.apply(&a, &b, &mut out).unwrap();
        let expected = ma.inner(&mb);
        for (x, y) in out.iter().zip(expected.as_slice()) {
            assert!((x - y).abs() <= 1e-15 * (1.0 + y.abs()), "{sig} inner");
        }
    }
    assert_eq!(checked, 7 * 8 * 4);
}

#[test]
fn batches_equal_single_pairs_at_every_length_around_a_block() {
    let sig = Signature::new(3, 0, 1).unwrap();
    let table = ProductTable::new(sig, Product::Geometric).unwrap();
    let size = 16;
    for m in [0, 1, 2, 63, 64, 65, 130] {
        let a = coefficients(m as u64, m * size);
        let b = coefficients(m as u64 + 1000, m * size);
        let mut out = vec![7.0; m * size];
        table.apply_batch(&a, &b, &mut out).unwrap();
        for e in 0..m {
            let mut one = vec![0.0; size];
            let r = e * size..(e + 1) * size;
            table.apply(&a[r.clone()], &b[r.clone()], &mut one).unwrap();
            assert_eq!(&out[r], one.as_slice(), "element {e} of {m}");
        }
    }
}

#[test]
fn table_sizes_and_errors() {
    // The geometric product of Cl(3, 0, 1): e_a e_b vanishes exactly when both contain e4.
    let sig = Signature::new(3, 0, 1).unwrap();
    let table = ProductTable::new(sig, Product::Geometric).unwrap();
    assert_eq!(table.len(), 256 - 64);
    assert!(!table.is_empty());
    // The outer product of ℝ³ keeps the 27 pairs of disjoint blades (3 choices per axis).
    let wedge = ProductTable::new(Signature::euclidean(3), Product::Wedge).unwrap();
    assert_eq!(wedge.len(), 27);
    let mut out = [0.0; 8];
    assert!(matches!(
        table.apply(&[0.0; 16], &[0.0; 16], &mut out),
        Err(AlgebraError::WrongComponentCount { .. })
    ));
    assert!(matches!(
        table.apply_batch(&[0.0; 32], &[0.0; 16], &mut [0.0; 32]),
        Err(AlgebraError::WrongComponentCount { .. })
    ));
    assert!(matches!(
        ProductTable::new(
            Signature::euclidean(PRODUCT_TABLE_MAX_DIM + 1),
            Product::Geometric
        ),
        Err(AlgebraError::DimensionTooLarge { .. })
    ));
}
