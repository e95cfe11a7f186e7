//! `ProductTable` against the products it tabulates: the same coefficients bit for bit (up
//! to the sign of a zero), one pair at a time and in batches of every length around a block
//! (up to N = 4 through the dense kernels, above through the list of entries), and batched
//! sandwiches against the multivector's own V X Ṽ.

use rotorflow::algebra::{
    AlgebraError, Multivector, PRODUCT_TABLE_MAX_DIM, Product, ProductTable, Signature, Versor,
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

/// Every signature of dimension 0 to 4 (and two of 5, past the dense kernels).
fn small_signatures() -> Vec<Signature> {
    let mut sigs = Vec::new();
    for n in 0..=4 {
        for p in 0..=n {
            for q in 0..=n - p {
                sigs.push(Signature::new(p, q, n - p - q).unwrap());
            }
        }
    }
    sigs.push(Signature::new(4, 1, 0).unwrap());
    sigs.push(Signature::new(3, 0, 2).unwrap());
    sigs
}

#[test]
fn batches_equal_single_pairs_for_every_kind_and_small_signature() {
    let mut checked = 0;
    for sig in small_signatures() {
        let size = 1 << sig.dim();
        let mut tables: Vec<ProductTable> = KINDS
            .iter()
            .map(|&kind| ProductTable::new(sig, kind).unwrap())
            .collect();
        tables.push(ProductTable::inner(sig).unwrap());
        for (t, table) in tables.iter().enumerate() {
            // Lengths around the dense kernel's block of 8 and the table's block of 64.
            for m in [1, 7, 8, 9, 17, 65] {
                let a = coefficients((m * 13 + t) as u64, m * size);
                let b = coefficients((m * 7 + t) as u64 + 500, m * size);
                let mut out = vec![7.0; m * size];
                table.apply_batch(&a, &b, &mut out).unwrap();
                let mut one = vec![0.0; size];
                for e in 0..m {
                    let r = e * size..(e + 1) * size;
                    table.apply(&a[r.clone()], &b[r.clone()], &mut one).unwrap();
                    assert_eq!(
                        &out[r],
                        one.as_slice(),
                        "{sig} table {t} element {e} of {m}"
                    );
                    checked += 1;
                }
            }
        }
    }
    // 35 signatures up to N = 4 and two of N = 5; 9 tables each; 107 elements per table.
    assert_eq!(checked, 37 * 9 * 107);
}

#[test]
fn batched_sandwiches_equal_the_multivector_sandwich() {
    let mut checked = 0;
    for sig in small_signatures() {
        let size = 1 << sig.dim();
        let table = ProductTable::new(sig, Product::Geometric).unwrap();
        for m in [1, 8, 11, 70] {
            let v = coefficients(m as u64 + 40, m * size);
            let x = coefficients(m as u64 + 80, m * size);
            let mut out = vec![7.0; m * size];
            table.sandwich_batch(&v, &x, &mut out).unwrap();
            for e in 0..m {
                let r = e * size..(e + 1) * size;
                let mv = Multivector::from_coefficients(sig, &v[r.clone()]).unwrap();
                let mx = Multivector::from_coefficients(sig, &x[r.clone()]).unwrap();
                let expected = mv.apply(&mx).unwrap();
                assert_eq!(&out[r], expected.as_slice(), "{sig} element {e} of {m}");
                checked += 1;
            }
        }
    }
    assert_eq!(checked, 37 * 90);
    let table = ProductTable::new(Signature::euclidean(3), Product::Geometric).unwrap();
    assert!(matches!(
        table.sandwich_batch(&[0.0; 16], &[0.0; 8], &mut [0.0; 16]),
        Err(AlgebraError::WrongComponentCount { .. })
    ));
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

/// Even elements (`vector` false) or vectors: the batch's coefficients with every other blade
/// set to exactly zero.
fn with_grades(mut c: Vec<f64>, size: usize, vector: bool) -> Vec<f64> {
    for (n, v) in c.iter_mut().enumerate() {
        let g = (n % size).count_ones();
        let keep = if vector { g == 1 } else { g.is_multiple_of(2) };
        if !keep {
            *v = 0.0;
        }
    }
    c
}

fn norm(c: &[f64]) -> f64 {
    c.iter().map(|v| v * v).sum::<f64>().sqrt()
}

#[test]
fn sandwiches_of_even_elements_on_vectors_equal_the_dense_sums() {
    // Every signature of dimension 3 and 4: 10 + 15.
    let sigs: Vec<Signature> = small_signatures()
        .into_iter()
        .filter(|s| matches!(s.dim(), 3 | 4))
        .collect();
    assert_eq!(sigs.len(), 25);
    let lengths = [1, 63, 64, 65, 200];
    let (mut checked, mut dense_round_off) = (0, 0);
    for sig in sigs {
        let size = 1usize << sig.dim();
        let table = ProductTable::new(sig, Product::Geometric).unwrap();
        // A full element: a batch that holds one runs its block through the dense sums.
        let spoiler = coefficients(7, size);
        for m in lengths {
            let v = with_grades(coefficients(m as u64 + 300, m * size), size, false);
            let x = with_grades(coefficients(m as u64 + 600, m * size), size, true);
            let mut out = vec![7.0; m * size];
            table.sandwich_batch(&v, &x, &mut out).unwrap();
            for e in 0..m {
                let r = e * size..(e + 1) * size;
                // The dense sums of the same element, in a batch with the spoiler.
                let pair = |c: &[f64]| [c, spoiler.as_slice()].concat();
                let mut dense = vec![7.0; 2 * size];
                table
                    .sandwich_batch(&pair(&v[r.clone()]), &pair(&x[r.clone()]), &mut dense)
                    .unwrap();
                let dense = &dense[..size];
                let expected = Multivector::from_coefficients(sig, &v[r.clone()])
                    .unwrap()
                    .apply(&Multivector::from_coefficients(sig, &x[r.clone()]).unwrap())
                    .unwrap();
                assert_eq!(dense, expected.as_slice(), "{sig} dense element {e} of {m}");
                let scale = norm(&v[r.clone()]).powi(2) * norm(&x[r.clone()]);
                for (blade, (&fast, &slow)) in out[r.clone()].iter().zip(dense).enumerate() {
                    if blade.count_ones() == 1 {
                        assert_eq!(fast, slow, "{sig} blade {blade} element {e} of {m}");
                    } else {
                        // Zero exactly, where the dense sums keep round-off.
                        assert_eq!(fast, 0.0, "{sig} blade {blade} element {e} of {m}");
                        assert!(slow.abs() <= 1e-15 * scale, "{sig} {slow} vs {scale}");
                        dense_round_off += usize::from(slow != 0.0);
                    }
                }
                checked += 1;
            }
        }
    }
    assert_eq!(checked, 25 * lengths.iter().sum::<usize>());
    // The two paths differ where the dense sums leave round-off: both were run.
    assert!(dense_round_off > 100, "{dense_round_off}");
}

#[test]
fn a_block_that_is_not_a_rotor_on_a_vector_keeps_the_dense_sums() {
    // 200 elements in four blocks of 64; one full element in the second block sends that
    // block alone through the dense sums.
    let mut checked = 0;
    for n in [3, 4] {
        let sig = Signature::euclidean(n);
        let size = 1usize << n;
        let table = ProductTable::new(sig, Product::Geometric).unwrap();
        let m = 200;
        let mut v = with_grades(coefficients(11, m * size), size, false);
        let x = with_grades(coefficients(12, m * size), size, true);
        v[100 * size + 1] = 0.5;
        let mut out = vec![7.0; m * size];
        table.sandwich_batch(&v, &x, &mut out).unwrap();
        for e in 0..m {
            let r = e * size..(e + 1) * size;
            let expected = Multivector::from_coefficients(sig, &v[r.clone()])
                .unwrap()
                .apply(&Multivector::from_coefficients(sig, &x[r.clone()]).unwrap())
                .unwrap();
            for (blade, (&got, &want)) in out[r].iter().zip(expected.as_slice()).enumerate() {
                if (64..128).contains(&e) || blade.count_ones() == 1 {
                    assert_eq!(got, want, "{n}D blade {blade} element {e}");
                } else {
                    assert_eq!(got, 0.0, "{n}D blade {blade} element {e}");
                }
            }
            checked += 1;
        }
    }
    assert_eq!(checked, 2 * 200);
}
