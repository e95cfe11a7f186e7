//! The distance between two boxes in 3 and 4 dimensions, which `distance` solves as a
//! bounded least-squares problem rather than by GJK, against three independent answers:
//! the dimension-generic GJK (`distance_general`), Wolfe's minimum-norm point of the
//! corners' differences (`narrow_reference.rs`), and, for boxes whose axes are parallel,
//! the closed form √Σ max(0, |cᵢ| − aᵢ − bᵢ)² in A's axes.

use super::narrow_phase::reference::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rotorflow::dynamics::motion::detect::{Separation, distance, distance_general};
use rotorflow::dynamics::motion::shape::{ConvexCore, ConvexShape};

const CONFIGURATIONS: [&str; 6] = [
    "random",
    "touching",
    "overlapping",
    "parallel faces",
    "parallel, axes exchanged",
    "identical at one pose",
];

fn random_box(r: &mut impl Rng, n: usize, rounded: bool) -> ConvexShape {
    let h: Vec<f64> = (0..n).map(|_| r.gen_range(0.2..2.0)).collect();
    let shape = ConvexShape::cuboid(&h).unwrap();
    if rounded {
        shape.rounded(r.gen_range(0.01..0.3)).unwrap()
    } else {
        shape
    }
}

/// How far the space point `x` lies outside the posed box's core (0 inside).
fn outside(p: &Posed, x: &[f64]) -> f64 {
    let n = p.shape.dim();
    let ConvexCore::Cuboid(h) = p.shape.core() else {
        panic!("not a box")
    };
    let mut excess = 0.0;
    for j in 0..n {
        let own: f64 = (0..n)
            .map(|i| p.rotation[i * n + j] * (x[i] - p.position[i]))
            .sum();
        excess += (own.abs() - h[j]).max(0.0).powi(2);
    }
    excess.sqrt()
}

/// Checks one answer: against the general path, the witnesses in their shapes and as far
/// apart as the distance along the normal; returns the difference from `expected` in units
/// of the size.
fn check(pa: &Posed, pb: &Posed, got: &Separation, expected: f64, what: &str) -> f64 {
    let size = pa.shape.bounding_radius() + pb.shape.bounding_radius();
    let general = distance_general(&placed(pa), &placed(pb)).unwrap();
    assert!(
        (got.distance - general.distance).abs() <= 1e-9 * general.distance + 1e-12 * size,
        "{what}: distance {} against general GJK {}",
        got.distance,
        general.distance
    );
    assert_eq!(got.intersecting, got.distance == 0.0, "{what}");
    if general.distance > 1e-9 * size {
        let turn: f64 = got
            .normal
            .as_slice()
            .iter()
            .zip(general.normal.as_slice())
            .map(|(x, y)| x * y)
            .sum();
        assert!(turn >= 1.0 - 1e-9, "{what}: normals turn by {turn}");
        let gap: Vec<f64> = got
            .witness_b
            .as_slice()
            .iter()
            .zip(got.witness_a.as_slice())
            .map(|(p, q)| p - q)
            .collect();
        assert!((norm(&gap) - got.distance).abs() <= 1e-9 * size, "{what}");
        for (g, m) in gap.iter().zip(got.normal.as_slice()) {
            assert!((g - got.distance * m).abs() <= 1e-9 * size, "{what}");
        }
    }
    // The witnesses lie on their shapes: within the margin of the core.
    let (ra, rb) = (pa.shape.margin(), pb.shape.margin());
    let (wa, wb) = (got.witness_a.as_slice(), got.witness_b.as_slice());
    assert!(outside(pa, wa) <= ra + 1e-9 * size, "{what}: witness off A");
    assert!(outside(pb, wb) <= rb + 1e-9 * size, "{what}: witness off B");
    (got.distance - expected).abs() / size
}

/// A rotation that permutes A's axes with signs: B's axes parallel to A's, exchanged.
fn signed_permutation(r: &mut impl Rng, n: usize) -> (Vec<f64>, Vec<usize>, Vec<f64>) {
    let mut order: Vec<usize> = (0..n).collect();
    for i in (1..n).rev() {
        order.swap(i, r.gen_range(0..=i));
    }
    let signs: Vec<f64> = (0..n)
        .map(|_| if r.gen_bool(0.5) { 1.0 } else { -1.0 })
        .collect();
    let mut p = vec![0.0; n * n];
    for j in 0..n {
        p[order[j] * n + j] = signs[j];
    }
    (p, order, signs)
}

fn multiply(a: &[f64], b: &[f64], n: usize) -> Vec<f64> {
    (0..n * n)
        .map(|k| (0..n).map(|l| a[k / n * n + l] * b[l * n + k % n]).sum())
        .collect()
}

#[test]
fn box_pairs_match_general_gjk_wolfe_and_closed_forms_in_3_and_4_dimensions() {
    let mut r = ChaCha8Rng::seed_from_u64(20261130);
    let pairs = 400;
    // Per dimension and configuration: pairs, separated, against Wolfe, left unchecked by
    // Wolfe's certificate.
    let mut counts = [[[0usize; 4]; 6]; 2];
    let mut worst = 0.0f64;
    for n in [3usize, 4] {
        let t = &mut counts[n - 3];
        for k in 0..pairs {
            let rounded = k % 4 == 3;
            let (a, b) = (
                random_box(&mut r, n, rounded),
                random_box(&mut r, n, rounded),
            );
            let (pa, mut pb) = random_pair(&mut r, a, b);
            let size = pa.shape.bounding_radius() + pb.shape.bounding_radius();
            // Random, then touching (B moved onto A along the normal), then overlapping (a
            // further 0.2 of the size): Wolfe for the cores when not rounded.
            for (c, pose) in ["random", "touching", "overlapping"].iter().enumerate() {
                let first = distance(&placed(&pa), &placed(&pb)).unwrap();
                if c == 1 && first.intersecting {
                    continue;
                }
                if c > 0 {
                    let by = if c == 1 { first.distance } else { 0.2 * size };
                    for (x, m) in pb.position.iter_mut().zip(first.normal.as_slice()) {
                        *x -= by * m;
                    }
                }
                let got = distance(&placed(&pa), &placed(&pb)).unwrap();
                let what = format!("N = {n}, pair {k}, {pose}");
                let general = distance_general(&placed(&pa), &placed(&pb)).unwrap();
                let mut expected = general.distance;
                if !rounded {
                    let cores = difference_points(&space_vertices(&pa), &space_vertices(&pb));
                    match certified_min_norm_point(&cores) {
                        Ok(x) => {
                            expected = norm(&x);
                            t[c][2] += 1;
                        }
                        Err(_) => t[c][3] += 1,
                    }
                }
                let error = check(&pa, &pb, &got, expected, &what);
                assert!(error <= 1e-9, "{what}: {} against {expected}", got.distance);
                worst = worst.max(error);
                t[c][0] += 1;
                t[c][1] += usize::from(!got.intersecting);
            }
        }
        // Parallel axes: one rotation for both (faces parallel), then B's axes a signed
        // permutation of A's; the closed form in A's axes.
        for k in 0..2 * pairs {
            let exchanged = k % 2 == 1;
            let c = 3 + usize::from(exchanged);
            let h: Vec<Vec<f64>> = (0..2)
                .map(|_| (0..n).map(|_| r.gen_range(0.2..2.0)).collect())
                .collect();
            let q = random_rotation(&mut r, n);
            let (p, order, _) = signed_permutation(&mut r, n);
            let qb = if exchanged {
                multiply(&q, &p, n)
            } else {
                q.clone()
            };
            // B's half-lengths along A's axes.
            let mut hb_in_a = vec![0.0; n];
            for j in 0..n {
                hb_in_a[if exchanged { order[j] } else { j }] = h[1][j];
            }
            // Face on face along one axis at a gap of −0.1 … 0.3 (a fifth exactly touching),
            // shifted across by less than the faces' extent or, for some, past a corner.
            let axis = r.gen_range(0..n);
            let mut own = vec![0.0; n];
            for i in 0..n {
                let reach = h[0][i] + hb_in_a[i];
                own[i] = if i == axis {
                    let gap = if k % 5 == 0 {
                        0.0
                    } else {
                        r.gen_range(-0.1..0.3)
                    };
                    reach + gap
                } else if k % 3 == 0 {
                    reach + r.gen_range(0.0..0.5)
                } else {
                    r.gen_range(-1.0..1.0) * reach
                };
                if r.gen_bool(0.5) {
                    own[i] = -own[i];
                }
            }
            let pa_position: Vec<f64> = (0..n).map(|_| r.gen_range(-1.0..1.0)).collect();
            let position: Vec<f64> = (0..n)
                .map(|i| pa_position[i] + (0..n).map(|j| q[i * n + j] * own[j]).sum::<f64>())
                .collect();
            let expected = (0..n)
                .map(|i| (own[i].abs() - h[0][i] - hb_in_a[i]).max(0.0).powi(2))
                .sum::<f64>()
                .sqrt();
            let pa = Posed {
                shape: ConvexShape::cuboid(&h[0]).unwrap(),
                position: pa_position,
                rotation: q,
            };
            let pb = Posed {
                shape: ConvexShape::cuboid(&h[1]).unwrap(),
                position,
                rotation: qb,
            };
            let got = distance(&placed(&pa), &placed(&pb)).unwrap();
            let what = format!("N = {n}, parallel pair {k}");
            let error = check(&pa, &pb, &got, expected, &what);
            assert!(error <= 1e-9, "{what}: {} against {expected}", got.distance);
            worst = worst.max(error);
            counts[n - 3][c][0] += 1;
            counts[n - 3][c][1] += usize::from(!got.intersecting);
        }
        // Identical boxes at one pose, rounded or not.
        for k in 0..pairs / 4 {
            let shape = random_box(&mut r, n, k % 2 == 1);
            let pose = Posed {
                rotation: random_rotation(&mut r, n),
                position: (0..n).map(|_| r.gen_range(-1.0..1.0)).collect(),
                shape,
            };
            let got = distance(&placed(&pose), &placed(&pose)).unwrap();
            check(&pose, &pose, &got, 0.0, &format!("N = {n}, identical {k}"));
            assert!(got.intersecting && got.distance == 0.0);
            counts[n - 3][5][0] += 1;
        }
    }
    println!("box–box distance: largest difference {worst:e} of the size");
    for (n, t) in [3, 4].iter().zip(&counts) {
        println!(
            "box–box distance, N = {n}: {}",
            CONFIGURATIONS
                .iter()
                .zip(t)
                .map(|(name, [p, s, w, u])| format!(
                    "{name} {p} ({s} separated, {w} against Wolfe, {u} not certified by it)"
                ))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    for t in &counts {
        assert_eq!(t[0][0], pairs);
        assert_eq!(t[2][0], pairs);
        assert_eq!(t[3][0], pairs);
        assert_eq!(t[4][0], pairs);
        assert_eq!(t[5][0], pairs / 4);
        // Every configuration that can be both separated and overlapping was both.
        for c in [0, 3, 4] {
            assert!(
                t[c][1] >= pairs / 5 && t[c][1] <= pairs - pairs / 10,
                "{t:?}"
            );
        }
        assert!(t[1][0] >= pairs / 5, "{t:?}");
        // Wolfe checked most of the plain (not rounded) pairs.
        assert!(t[0][2] >= pairs / 2 && t[1][2] >= pairs / 5, "{t:?}");
    }
}

/// Two more kinds of pose for the least-squares path: B nested inside A (contact, distance
/// 0), and both boxes on the coordinate axes exactly (identity rotations, so that B's axes
/// in A's frame are exact unit vectors and many gradients vanish exactly), apart, a
/// hair apart, exactly face on face, or overlapping, against the closed form and the
/// general GJK.
#[test]
fn nested_and_axis_aligned_box_pairs_match_general_gjk_and_closed_forms() {
    let mut r = ChaCha8Rng::seed_from_u64(20261129);
    let pairs = 400;
    // Per dimension: nested, axis-aligned, of them separated, of them exactly face on face.
    let mut counts = [[0usize; 4]; 2];
    let mut worst = 0.0f64;
    for n in [3usize, 4] {
        let identity: Vec<f64> = (0..n * n)
            .map(|k| if k % (n + 1) == 0 { 1.0 } else { 0.0 })
            .collect();
        for k in 0..pairs {
            let ha: Vec<f64> = (0..n).map(|_| r.gen_range(0.5..2.0)).collect();
            let least = ha.iter().copied().fold(f64::INFINITY, f64::min);
            let hb: Vec<f64> = (0..n).map(|_| r.gen_range(0.05..0.3) * least).collect();
            let pa = Posed {
                shape: ConvexShape::cuboid(&ha).unwrap(),
                rotation: random_rotation(&mut r, n),
                position: (0..n).map(|_| r.gen_range(-1.0..1.0)).collect(),
            };
            // B's centre within 0.3 of A's half-lengths of A's: B inside A whatever its turn.
            let own: Vec<f64> = ha.iter().map(|h| r.gen_range(-0.3..0.3) * h).collect();
            let position: Vec<f64> = (0..n)
                .map(|i| {
                    pa.position[i] + (0..n).map(|j| pa.rotation[i * n + j] * own[j]).sum::<f64>()
                })
                .collect();
            let pb = Posed {
                shape: ConvexShape::cuboid(&hb).unwrap(),
                rotation: random_rotation(&mut r, n),
                position,
            };
            let got = distance(&placed(&pa), &placed(&pb)).unwrap();
            check(&pa, &pb, &got, 0.0, &format!("N = {n}, nested {k}"));
            assert!(
                got.intersecting && got.distance == 0.0,
                "N = {n}, nested {k}"
            );
            counts[n - 3][0] += 1;
        }
        for k in 0..pairs {
            let h: Vec<Vec<f64>> = (0..2)
                .map(|_| (0..n).map(|_| r.gen_range(0.2..2.0)).collect())
                .collect();
            // In turn: exactly face on face along one axis, 1e-9 apart along it, apart
            // along some axes (faces, edges, corners), overlapping along all.
            let mode = k % 4;
            let axis = r.gen_range(0..n);
            let position: Vec<f64> = (0..n)
                .map(|i| {
                    let reach = h[0][i] + h[1][i];
                    let offset = match mode {
                        0 | 1 if i == axis => reach + if mode == 0 { 0.0 } else { 1e-9 },
                        2 if i == axis || r.gen_bool(0.5) => reach + r.gen_range(0.0..0.5),
                        _ => r.gen_range(-0.9..0.9) * reach,
                    };
                    if r.gen_bool(0.5) { -offset } else { offset }
                })
                .collect();
            let expected = (0..n)
                .map(|i| (position[i].abs() - h[0][i] - h[1][i]).max(0.0).powi(2))
                .sum::<f64>()
                .sqrt();
            let pa = Posed {
                shape: ConvexShape::cuboid(&h[0]).unwrap(),
                position: vec![0.0; n],
                rotation: identity.clone(),
            };
            let pb = Posed {
                shape: ConvexShape::cuboid(&h[1]).unwrap(),
                position,
                rotation: identity.clone(),
            };
            let got = distance(&placed(&pa), &placed(&pb)).unwrap();
            let what = format!("N = {n}, axis-aligned {k}");
            let error = check(&pa, &pb, &got, expected, &what);
            assert!(error <= 1e-9, "{what}: {} against {expected}", got.distance);
            worst = worst.max(error);
            counts[n - 3][1] += 1;
            counts[n - 3][2] += usize::from(!got.intersecting);
            if mode == 0 {
                assert!(got.intersecting, "{what}: face on face");
                counts[n - 3][3] += 1;
            }
        }
    }
    println!(
        "box–box distance, nested and axis-aligned: N = 3 {:?}, N = 4 {:?} (nested, axis-aligned, of them separated, exactly touching); largest difference {worst:e} of the size",
        counts[0], counts[1]
    );
    for t in &counts {
        assert_eq!(t[0], pairs);
        assert_eq!(t[1], pairs);
        // 1e-9 apart and apart: half of them.
        assert_eq!(t[2], pairs / 2, "{t:?}");
        assert_eq!(t[3], pairs / 4, "{t:?}");
    }
}
