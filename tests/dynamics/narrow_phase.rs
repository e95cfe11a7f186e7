//! The narrow phase (`dynamics::motion::detect`) and the convex shapes it runs on, against
//! independent answers (`narrow_reference.rs`): Wolfe's minimum-norm point for polytope
//! distances, separating axes and brute-force hyperplanes for penetration depths, closed
//! forms and a 1-D root solve for balls, capsules and ellipsoids. Every test prints its
//! counts and asserts that each promised case ran.

#[path = "narrow_reference.rs"]
pub mod reference;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use reference::*;
use rotorflow::dynamics::motion::detect::{
    EpaWorkspace, PlacedShape, distance, intersects, penetration, penetration_with,
};
use rotorflow::dynamics::motion::shape::{CompoundShape, ConvexShape, Piece, ShapeError};

#[test]
fn constructors_refuse_bad_input_with_structured_errors() {
    assert_eq!(
        ConvexShape::cuboid(&[1.0]),
        Err(ShapeError::TooFewDimensions { dim: 1 })
    );
    assert_eq!(
        ConvexShape::cuboid(&[1.0, 0.0, 2.0]),
        Err(ShapeError::NonPositiveLength {
            what: "half-length",
            index: 1,
            value: 0.0
        })
    );
    assert!(matches!(
        ConvexShape::ellipsoid(&[1.0, f64::NAN]),
        Err(ShapeError::NonFinite { .. })
    ));
    assert!(matches!(
        ConvexShape::ball(3, -1.0),
        Err(ShapeError::NonPositiveLength { .. })
    ));
    assert_eq!(
        ConvexShape::hull(&[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0]
        ]),
        Err(ShapeError::FlatHull {
            points: 4,
            rank: 2,
            dim: 3
        })
    );
    assert!(matches!(
        ConvexShape::hull(&[vec![0.0, 0.0], vec![1.0, 0.0, 0.0]]),
        Err(ShapeError::DimensionMismatch { .. })
    ));
    assert!(matches!(
        ConvexShape::cuboid(&[1.0, 1.0]).unwrap().rounded(-0.1),
        Err(ShapeError::NegativeMargin { .. })
    ));
    assert!(matches!(
        ConvexShape::capsule(3, 0.0, 1.0),
        Err(ShapeError::NonPositiveLength { .. })
    ));
    let cube = ConvexShape::cuboid(&[1.0; 3]).unwrap();
    assert!(matches!(
        PlacedShape::new(&cube, &[0.0; 2], &identity(3)),
        Err(ShapeError::DimensionMismatch { .. })
    ));
    assert!(matches!(
        PlacedShape::new(&cube, &[0.0; 3], &identity(2)),
        Err(ShapeError::DimensionMismatch { .. })
    ));
    let square = ConvexShape::cuboid(&[1.0; 2]).unwrap();
    let a = PlacedShape::new(&cube, &[0.0; 3], &[1.0; 9]).unwrap();
    let id2 = identity(2);
    let b = PlacedShape::new(&square, &[0.0; 2], &id2).unwrap();
    assert!(matches!(
        distance(&a, &b),
        Err(ShapeError::DimensionMismatch { .. })
    ));
    let mut out = [0.0; 2];
    assert!(cube.support_own(&[1.0, 0.0], &mut out).is_err());
    // Pieces: a rotation must be one, and a compound needs a piece of one dimension.
    assert!(matches!(
        Piece::new(
            cube.clone(),
            &[0.0; 3],
            &[2.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
        ),
        Err(ShapeError::NotARotation { .. })
    ));
    assert!(matches!(
        Piece::new(
            cube.clone(),
            &[0.0; 3],
            &[-1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
        ),
        Err(ShapeError::NotARotation { .. })
    ));
    assert_eq!(CompoundShape::new(vec![]), Err(ShapeError::EmptyCompound));
    let mixed = vec![
        Piece::translated(cube.clone(), &[0.0; 3]).unwrap(),
        Piece::translated(square, &[0.0; 2]).unwrap(),
    ];
    assert!(matches!(
        CompoundShape::new(mixed),
        Err(ShapeError::DimensionMismatch { .. })
    ));
}

#[test]
fn support_points_and_boxes_match_brute_force() {
    let mut r = ChaCha8Rng::seed_from_u64(11);
    let mut checked = 0;
    for n in 2..=6 {
        for _ in 0..40 {
            let shape = random_polytope(&mut r, n, false);
            let vertices = own_vertices(&shape);
            let d: Vec<f64> = (0..n).map(|_| r.gen_range(-1.0..1.0)).collect();
            let mut s = vec![0.0; n];
            shape.support_own(&d, &mut s).unwrap();
            let best = vertices
                .iter()
                .map(|v| v.iter().zip(&d).map(|(a, b)| a * b).sum::<f64>())
                .fold(f64::NEG_INFINITY, f64::max);
            let got: f64 = s.iter().zip(&d).map(|(a, b)| a * b).sum();
            assert!((got - best).abs() <= 1e-12 * (1.0 + best.abs()));
            // The bounding box of a placement against the placed vertices.
            let posed = Posed {
                rotation: random_rotation(&mut r, n),
                position: (0..n).map(|_| r.gen_range(-1.0..1.0)).collect(),
                shape,
            };
            let (mut lo, mut hi) = (vec![0.0; n], vec![0.0; n]);
            posed
                .shape
                .aabb(&posed.position, &posed.rotation, &mut lo, &mut hi)
                .unwrap();
            let placed_vertices = space_vertices(&posed);
            for i in 0..n {
                let top = placed_vertices
                    .iter()
                    .map(|v| v[i])
                    .fold(f64::NEG_INFINITY, f64::max);
                let bottom = placed_vertices
                    .iter()
                    .map(|v| v[i])
                    .fold(f64::INFINITY, f64::min);
                assert!((hi[i] - top).abs() < 1e-12 && (lo[i] - bottom).abs() < 1e-12);
            }
            checked += 1;
        }
        // Ellipsoid and rounded shapes: the support point is on the surface and no sampled
        // surface point reaches further.
        let a: Vec<f64> = (0..n).map(|_| r.gen_range(0.1..3.0)).collect();
        let ellipsoid = ConvexShape::ellipsoid(&a).unwrap().rounded(0.25).unwrap();
        let d: Vec<f64> = (0..n).map(|_| r.gen_range(-1.0..1.0)).collect();
        let mut s = vec![0.0; n];
        ellipsoid.support_own(&d, &mut s).unwrap();
        let got: f64 = s.iter().zip(&d).map(|(x, y)| x * y).sum();
        for _ in 0..2000 {
            let mut u: Vec<f64> = (0..n).map(|_| r.gen_range(-1.0..1.0)).collect();
            let l = norm(&u);
            u.iter_mut().for_each(|x| *x /= l);
            // A surface point of the rounded ellipsoid: the ellipsoid's point Au plus the
            // margin along its outward normal A⁻¹u/|A⁻¹u|.
            let m: Vec<f64> = u.iter().zip(&a).map(|(x, s)| x / s).collect();
            let lm = norm(&m);
            let x: Vec<f64> = (0..n).map(|i| a[i] * u[i] + 0.25 * m[i] / lm).collect();
            let reach: f64 = x.iter().zip(&d).map(|(p, q)| p * q).sum();
            assert!(reach <= got + 1e-12);
        }
        checked += 1;
    }
    println!("support and bounding boxes: {checked} shapes");
    assert_eq!(checked, 5 * 41);
}

#[test]
fn random_polytope_distances_match_wolfe_in_2_to_6_dimensions() {
    // 10⁴ pairs: boxes, random hulls, simplices and cross-polytopes (hulls alone at N = 6).
    let per_dimension = [3000, 3000, 2000, 1200, 800];
    let mut total = 0;
    for (n, &pairs) in (2..=6).zip(&per_dimension) {
        let [
            overlapping,
            separated,
            wrong,
            nonfinite,
            iterations,
            uncertified,
        ] = polytope_distance_run(100 + n as u64, n, pairs);
        println!(
            "N = {n}: {pairs} pairs, {overlapping} overlapping, {separated} separated, \
             {wrong} wrong beyond 1e-9, {nonfinite} non-finite, at most {iterations} GJK \
             iterations, {uncertified} left unchecked by the reference"
        );
        assert_eq!(overlapping + separated + nonfinite + uncertified, pairs);
        assert_eq!(uncertified, 0);
        assert!(overlapping > pairs / 10 && separated > pairs / 10);
        assert_eq!((wrong, nonfinite), (0, 0));
        total += pairs;
    }
    assert_eq!(total, 10_000);
}

/// A random pair of overlapping cuboids in `n` dimensions.
fn overlapping_boxes(r: &mut impl Rng, n: usize) -> (Posed, Posed) {
    loop {
        let ha: Vec<f64> = (0..n).map(|_| r.gen_range(0.2..2.0)).collect();
        let hb: Vec<f64> = (0..n).map(|_| r.gen_range(0.2..2.0)).collect();
        let (pa, pb) = random_pair(
            r,
            ConvexShape::cuboid(&ha).unwrap(),
            ConvexShape::cuboid(&hb).unwrap(),
        );
        if box_box_sat(&pa, &pb).0 > 1e-6 {
            return (pa, pb);
        }
    }
}

#[test]
fn box_penetration_matches_separating_axes_in_2_to_6_dimensions() {
    let mut r = ChaCha8Rng::seed_from_u64(7);
    let mut workspace = EpaWorkspace::new();
    let mut checked = 0;
    let mut largest_iterations = 0;
    let axes_expected = [0, 0, 4, 15, 56, 210, 792];
    for (n, &axes_promised) in axes_expected.iter().enumerate().skip(2) {
        let cases = if n <= 4 { 300 } else { 60 };
        for _ in 0..cases {
            let (pa, pb) = overlapping_boxes(&mut r, n);
            let (expected, axes) = box_box_sat(&pa, &pb);
            assert_eq!(axes, axes_promised);
            let size = pa.shape.bounding_radius() + pb.shape.bounding_radius();
            let got = penetration_with(&mut workspace, &placed(&pa), &placed(&pb)).unwrap();
            let swapped = penetration_with(&mut workspace, &placed(&pb), &placed(&pa)).unwrap();
            let tolerance = 1e-9 * size;
            assert!(
                (got.depth - expected).abs() <= tolerance,
                "N = {n}: EPA depth {} against separating axes {expected}",
                got.depth
            );
            assert!((swapped.depth - expected).abs() <= tolerance);
            // The normal is a direction of that least overlap, and the witnesses differ by
            // depth · normal.
            let (va, vb) = (space_vertices(&pa), space_vertices(&pb));
            assert!((overlap_along(&va, &vb, got.normal.as_slice()) - expected).abs() <= tolerance);
            for i in 0..n {
                let g = got.witness_a.as_slice()[i] - got.witness_b.as_slice()[i];
                assert!((g - got.depth * got.normal.as_slice()[i]).abs() <= tolerance);
            }
            largest_iterations = largest_iterations.max(got.iterations);
            checked += 1;
        }
    }
    println!("box pairs: {checked} overlapping, at most {largest_iterations} GJK + EPA iterations");
    assert_eq!(checked, 3 * 300 + 2 * 60);
}

#[test]
fn hull_penetration_matches_brute_force_hyperplanes() {
    let mut r = ChaCha8Rng::seed_from_u64(8);
    let mut checked = [0usize; 5];
    for n in 2..=4 {
        let cases = [0, 0, 300, 150, 25][n];
        while checked[n] < cases {
            let make = |r: &mut ChaCha8Rng| loop {
                let count = if n == 4 {
                    n + 1
                } else {
                    n + 1 + r.gen_range(0..3)
                };
                let points: Vec<Vec<f64>> = (0..count)
                    .map(|_| (0..n).map(|_| r.gen_range(-1.5..1.5)).collect())
                    .collect();
                if let Ok(s) = ConvexShape::hull(&points) {
                    break s;
                }
            };
            let (a, b) = (make(&mut r), make(&mut r));
            let (pa, pb) = random_pair(&mut r, a, b);
            let (va, vb) = (space_vertices(&pa), space_vertices(&pb));
            let expected = polytope_depth_brute_force(&va, &vb);
            let size = pa.shape.bounding_radius() + pb.shape.bounding_radius();
            if expected <= 1e-6 * size {
                // Separated or touching: the brute force's least support value is then
                // not a depth.
                continue;
            }
            let got = penetration(&placed(&pa), &placed(&pb)).unwrap();
            assert!(
                (got.depth - expected).abs() <= 1e-9 * size,
                "N = {n}: EPA depth {} against brute force {expected}",
                got.depth
            );
            assert!(
                (overlap_along(&va, &vb, got.normal.as_slice()) - expected).abs() <= 1e-9 * size
            );
            checked[n] += 1;
        }
    }
    println!(
        "overlapping hull pairs checked: N = 2: {}, N = 3: {}, N = 4: {}",
        checked[2], checked[3], checked[4]
    );
    assert_eq!(checked, [0, 0, 300, 150, 25]);
}

#[test]
fn balls_capsules_and_ellipsoids_match_closed_forms() {
    let mut r = ChaCha8Rng::seed_from_u64(9);
    let mut worst_smooth_epa: f64 = 0.0;
    let mut counts = [0usize; 4];
    for n in 2..=6 {
        for _ in 0..200 {
            let (ra, rb) = (r.gen_range(0.1..2.0), r.gen_range(0.1..2.0));
            let (pa, pb) = random_pair(
                &mut r,
                ConvexShape::ball(n, ra).unwrap(),
                ConvexShape::ball(n, rb).unwrap(),
            );
            let gap: Vec<f64> = pb
                .position
                .iter()
                .zip(&pa.position)
                .map(|(p, q)| p - q)
                .collect();
            let expected = ra + rb - norm(&gap);
            let got = penetration(&placed(&pa), &placed(&pb)).unwrap();
            assert!((got.depth - expected).abs() <= 1e-12 * (ra + rb));
            let d = distance(&placed(&pa), &placed(&pb)).unwrap();
            assert!((d.distance - (-expected).max(0.0)).abs() <= 1e-12 * (ra + rb));
            counts[0] += 1;

            // Ball against box: the closed form against Wolfe on the box's vertices and the
            // ball's centre, and against GJK with the ball given as an ellipsoid core.
            let h: Vec<f64> = (0..n).map(|_| r.gen_range(0.2..2.0)).collect();
            let (pbox, pball) = random_pair(
                &mut r,
                ConvexShape::cuboid(&h).unwrap(),
                ConvexShape::ball(n, rb).unwrap(),
            );
            let centre_gap = polytope_distance(
                &space_vertices(&pbox),
                std::slice::from_ref(&pball.position),
            );
            let got = penetration(&placed(&pbox), &placed(&pball)).unwrap();
            let size = norm(&h) + rb;
            if centre_gap > 1e-6 * size {
                let round = ConvexShape::ellipsoid(&vec![rb; n]).unwrap();
                let as_ellipsoid =
                    PlacedShape::new(&round, &pball.position, &pball.rotation).unwrap();
                let general = penetration(&placed(&pbox), &as_ellipsoid).unwrap();
                assert!(
                    (got.depth - (rb - centre_gap)).abs() <= 1e-9 * size,
                    "N = {n}: ball–box depth {} against {} (GJK on an ellipsoid: {})",
                    got.depth,
                    rb - centre_gap,
                    general.depth
                );
                // EPA on a smooth core approaches its boundary by facets (256 at most), so
                // overlapping pairs agree less closely than separated ones, where GJK's
                // relative gap bounds the error.
                let error = (general.depth - got.depth).abs() / size;
                if got.depth < 0.0 {
                    assert!(error <= 1e-9, "N = {n}: GJK off by {error:e} of the size");
                } else {
                    // The expanded polytope lies inside the Minkowski difference, so its
                    // depth is a lower bound of the true one.
                    assert!(
                        general.depth <= got.depth + 1e-9 * size && error <= 0.05,
                        "N = {n}: EPA depth {} against {}",
                        general.depth,
                        got.depth
                    );
                    worst_smooth_epa = worst_smooth_epa.max(error);
                }
            } else {
                // Centre inside (or within 1e-6 of the surface): the depth through the
                // nearest face, by separating axes of the box against a point-sized box
                // at the centre (the ball's own contribution is its radius).
                let probe = Posed {
                    shape: ConvexShape::cuboid(&vec![1e-300; n]).unwrap(),
                    position: pball.position.clone(),
                    rotation: pbox.rotation.clone(),
                };
                let (face_depth, _) = box_box_sat(&pbox, &probe);
                if face_depth > 1e-6 * size {
                    assert!((got.depth - (face_depth + rb)).abs() <= 1e-9 * size);
                }
            }
            let swapped = penetration(&placed(&pball), &placed(&pbox)).unwrap();
            assert!((swapped.depth - got.depth).abs() <= 1e-12 * size);
            counts[1] += 1;

            // Capsule against ball: the segment–point distance minus both radii.
            let (hl, rc) = (r.gen_range(0.1..2.0), r.gen_range(0.1..1.0));
            let (pc, pball) = random_pair(
                &mut r,
                ConvexShape::capsule(n, hl, rc).unwrap(),
                ConvexShape::ball(n, rb).unwrap(),
            );
            let rel: Vec<f64> = pball
                .position
                .iter()
                .zip(&pc.position)
                .map(|(p, q)| p - q)
                .collect();
            let along: f64 = (0..n).map(|i| pc.rotation[i * n] * rel[i]).sum();
            let t = along.clamp(-hl, hl);
            let off: Vec<f64> = (0..n).map(|i| rel[i] - t * pc.rotation[i * n]).collect();
            let expected = rc + rb - norm(&off);
            let got = penetration(&placed(&pc), &placed(&pball)).unwrap();
            assert!(
                (got.depth - expected).abs() <= 1e-9 * (hl + rc + rb),
                "capsule–ball depth {} against {expected}",
                got.depth
            );
            counts[2] += 1;

            // Ellipsoid against ball, separated: distance by the root solve.
            let axes: Vec<f64> = (0..n).map(|_| r.gen_range(0.3..2.0)).collect();
            let (pe, pball) = random_pair(
                &mut r,
                ConvexShape::ellipsoid(&axes).unwrap(),
                ConvexShape::ball(n, rb).unwrap(),
            );
            let rel: Vec<f64> = pball
                .position
                .iter()
                .zip(&pe.position)
                .map(|(p, q)| p - q)
                .collect();
            let own: Vec<f64> = (0..n)
                .map(|j| (0..n).map(|i| pe.rotation[i * n + j] * rel[i]).sum())
                .collect();
            let gap = point_ellipsoid_distance(&own, &axes);
            if gap > rb + 1e-6 {
                let got = distance(&placed(&pe), &placed(&pball)).unwrap();
                assert!(
                    (got.distance - (gap - rb)).abs() <= 1e-9 * (gap + rb + 2.0),
                    "ellipsoid–ball distance {} against {}",
                    got.distance,
                    gap - rb
                );
                counts[3] += 1;
            }
        }
    }
    println!(
        "closed forms: {} ball–ball, {} ball–box, {} capsule–ball, {} separated ellipsoid–ball; \
         EPA with the ball as an ellipsoid core within {worst_smooth_epa:.1e} of the size",
        counts[0], counts[1], counts[2], counts[3]
    );
    assert_eq!(&counts[..3], &[1000, 1000, 1000]);
    assert!(counts[3] > 300);
}

#[test]
fn touching_nested_coincident_and_degenerate_configurations() {
    let mut cases = 0;
    for n in 2..=6 {
        let id = identity(n);
        let cube = ConvexShape::cuboid(&vec![1.0; n]).unwrap();
        let shifted = |x: f64, axis: usize| -> Vec<f64> {
            let mut p = vec![0.0; n];
            p[axis] = x;
            p
        };
        // Face to face, exactly touching: distance 0, depth 0, normal along the axis.
        let p2 = shifted(2.0, n - 1);
        let (a, b) = (
            PlacedShape::new(&cube, &[0.0; 8][..n], &id).unwrap(),
            PlacedShape::new(&cube, &p2, &id).unwrap(),
        );
        let d = distance(&a, &b).unwrap();
        assert!(d.distance <= 1e-12 && d.intersecting);
        let c = penetration(&a, &b).unwrap();
        assert!(
            c.depth.abs() <= 1e-12,
            "N = {n}: touching depth {}",
            c.depth
        );
        assert!((c.normal.as_slice()[n - 1] - 1.0).abs() <= 1e-9);
        cases += 1;
        // Overlapping by 0.1 along one axis with every face aligned: GJK ends on a face of
        // its simplex (the 2-point simplex of box pairs), and EPA must still start.
        let p = shifted(1.9, 0);
        let b = PlacedShape::new(&cube, &p, &id).unwrap();
        let c = penetration(&a, &b).unwrap();
        assert!(
            (c.depth - 0.1).abs() <= 1e-12,
            "N = {n}: aligned depth {}",
            c.depth
        );
        assert!((c.normal.as_slice()[0] - 1.0).abs() <= 1e-12);
        // The same as hulls (box-like hulls of the 2ᴺ corners).
        let corners: Vec<Vec<f64>> = own_vertices(&cube);
        let hull = ConvexShape::hull(&corners).unwrap();
        let ha = PlacedShape::new(&hull, &[0.0; 8][..n], &id).unwrap();
        let hb = PlacedShape::new(&hull, &p, &id).unwrap();
        let c = penetration(&ha, &hb).unwrap();
        assert!(
            (c.depth - 0.1).abs() <= 1e-12,
            "N = {n}: aligned hull depth {}",
            c.depth
        );
        cases += 1;
        // Coincident: identical shapes at the same pose.
        for shape in [
            cube.clone(),
            hull.clone(),
            ConvexShape::simplex(n, 1.0).unwrap(),
        ] {
            let a = PlacedShape::new(&shape, &[0.0; 8][..n], &id).unwrap();
            let c = penetration(&a, &a).unwrap();
            let d = distance(&a, &a).unwrap();
            assert!(d.intersecting && d.distance == 0.0);
            let expected = if matches!(shape.core(), rotorflow::dynamics::motion::shape::ConvexCore::Hull(v) if v.len() == (n + 1) * n)
            {
                // The least width of the regular simplex (Steinhagen's problem), of edge
                // a = R √(2(N+1)/N): a √(2/(N+1)) for odd N, a √(2(N+1)/(N(N+2))) for even N.
                let nf = n as f64;
                let edge = (2.0 * (nf + 1.0) / nf).sqrt();
                if n % 2 == 1 {
                    edge * (2.0 / (nf + 1.0)).sqrt()
                } else {
                    edge * (2.0 * (nf + 1.0) / (nf * (nf + 2.0))).sqrt()
                }
            } else {
                2.0
            };
            if n <= 4 && expected != 2.0 {
                // The simplex's width by brute force too (its difference set is small).
                let v = own_vertices(&shape);
                assert!((polytope_depth_brute_force(&v, &v) - expected).abs() <= 1e-12);
            }
            assert!(
                (c.depth - expected).abs() <= 1e-9,
                "N = {n}: coincident depth {} against {expected}",
                c.depth
            );
            cases += 1;
        }
        // Concentric balls, and a ball centred on a capsule's segment (a flat difference
        // of cores).
        let ball = ConvexShape::ball(n, 0.5).unwrap();
        let a = PlacedShape::new(&ball, &[0.0; 8][..n], &id).unwrap();
        assert!((penetration(&a, &a).unwrap().depth - 1.0).abs() <= 1e-15);
        let capsule = ConvexShape::capsule(n, 2.0, 0.25).unwrap();
        let cap = PlacedShape::new(&capsule, &[0.0; 8][..n], &id).unwrap();
        let on_segment = shifted(0.7, 0);
        let b = PlacedShape::new(&ball, &on_segment, &id).unwrap();
        let c = penetration(&cap, &b).unwrap();
        assert!(
            (c.depth - 0.75).abs() <= 1e-12,
            "N = {n}: capsule–ball depth {}",
            c.depth
        );
        assert!(c.normal.as_slice()[0].abs() <= 1e-12);
        cases += 2;
        // Nested: a small box deep inside a large one; the depth is the way out through
        // the nearest face of the large box.
        let big = ConvexShape::cuboid(&vec![3.0; n]).unwrap();
        let small = ConvexShape::cuboid(&vec![0.5; n]).unwrap();
        let inner = shifted(1.0, n - 1);
        let a = PlacedShape::new(&big, &[0.0; 8][..n], &id).unwrap();
        let b = PlacedShape::new(&small, &inner, &id).unwrap();
        let c = penetration(&a, &b).unwrap();
        assert!(
            (c.depth - 2.5).abs() <= 1e-12,
            "N = {n}: nested depth {}",
            c.depth
        );
        cases += 1;
        // Degenerate: a box 1e-9 thick, touching and crossing a cube.
        let mut h = vec![1.0; n];
        h[0] = 1e-9;
        let sheet = ConvexShape::cuboid(&h).unwrap();
        let across = shifted(0.5, n - 1);
        let b = PlacedShape::new(&sheet, &across, &id).unwrap();
        let c = penetration(&PlacedShape::new(&cube, &[0.0; 8][..n], &id).unwrap(), &b).unwrap();
        // The way out is across the sheet: 1 + 1e-9 (along the last axis it is 1.5).
        assert!(
            (c.depth - (1.0 + 1e-9)).abs() <= 1e-12,
            "N = {n}: sheet depth {}",
            c.depth
        );
        cases += 1;
    }
    println!("special configurations: {cases} cases");
    assert_eq!(cases, 5 * 9);
}

#[test]
fn compound_pieces_place_and_bound() {
    let n = 3;
    let rod = ConvexShape::capsule(n, 1.0, 0.2).unwrap();
    let end = ConvexShape::ball(n, 0.5).unwrap();
    let q = [0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0];
    let dumbbell = CompoundShape::new(vec![
        Piece::new(rod, &[0.0; 3], &q).unwrap(),
        Piece::translated(end.clone(), &[0.0, 1.0, 0.0]).unwrap(),
        Piece::translated(end, &[0.0, -1.0, 0.0]).unwrap(),
    ])
    .unwrap();
    assert_eq!(dumbbell.pieces().len(), 3);
    assert!((dumbbell.bounding_radius() - 1.5).abs() < 1e-15);
    // The rod's axis (its own first axis) is the body's second, and placing the body at
    // x with a quarter turn about e₃ puts it along −e₁ … +e₁.
    let (mut p, mut r) = ([0.0; 3], [0.0; 9]);
    dumbbell.pieces()[0]
        .place(&[5.0, 0.0, 0.0], &q, &mut p, &mut r)
        .unwrap();
    let placed = PlacedShape::new(dumbbell.pieces()[0].shape(), &p, &r).unwrap();
    let probe = ConvexShape::ball(3, 0.1).unwrap();
    let id3 = identity(3);
    let probe = PlacedShape::new(&probe, &[3.0, 0.0, 0.0], &id3).unwrap();
    let d = distance(&placed, &probe).unwrap();
    assert!(
        (d.distance - (2.0 - 1.0 - 0.2 - 0.1)).abs() < 1e-12,
        "{}",
        d.distance
    );
    assert!(intersects(&placed, &placed).unwrap());
}
