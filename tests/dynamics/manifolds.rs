//! Box–box separating axes and contact manifolds (`dynamics::motion::detect`), against brute
//! force that shares no code with them (`tests/support/boxes.rs`).

#[path = "../support/boxes.rs"]
mod boxes;

use boxes::*;
use rand::Rng;
use rotorflow::dynamics::motion::detect::manifold::{
    RegionVertex, hull_contact_vertices, manifold_capacity,
};
use rotorflow::dynamics::motion::detect::{
    AxisFeature, ContactManifold, PlacedHull, box_box, box_contact_vertices, box_manifold,
    candidate_axis_count, hull_manifold,
};

#[test]
fn candidate_axes_number_15_in_3d_and_56_in_4d() {
    assert_eq!(candidate_axis_count(2), 4);
    assert_eq!(candidate_axis_count(3), 15);
    assert_eq!(candidate_axis_count(4), 56);
    // C(2N, N − 1) in general (the zonotope of 2N generators has that many facet pairs).
    for n in 2..=10usize {
        let binomial = (0..n - 1).fold(1usize, |acc, i| acc * (2 * n - i) / (i + 1));
        assert_eq!(candidate_axis_count(n), binomial, "N = {n}");
    }
}

/// Every pose kind in N = 2 … 6 against sampled and refined directions, the vertices'
/// projections and the distance by alternating projections.
#[test]
fn box_box_axis_is_the_least_penetration_of_all_directions() {
    let mut r = super::rng(31);
    for n in 2..=6 {
        let per_pose = if n <= 4 { 24 } else { 8 };
        let mut tally = SatTally::default();
        for pose in POSES {
            for _ in 0..per_pose {
                let (a, b) = random_pair(&mut r, n, pose);
                let axis = box_box(&a.placed(), &b.placed()).unwrap();
                check_sat_case(&mut r, &a, &b, &axis, 300, &mut tally);
                match pose {
                    Pose::Touching => {
                        assert!(axis.depth.abs() <= 1e-12 * 4.0, "touching: {axis:?}")
                    }
                    Pose::Coincident => {
                        let least = a.h.iter().copied().fold(f64::INFINITY, f64::min);
                        assert!((axis.depth - 2.0 * least).abs() <= 1e-12, "{axis:?}");
                    }
                    Pose::FaceToFace => assert!(
                        !matches!(axis.feature, AxisFeature::Cells { .. }),
                        "face-to-face gave {axis:?}"
                    ),
                    _ => {}
                }
            }
        }
        println!(
            "N = {n}: {} cases ({} overlapping, {} separated, {} on cell axes, {} against sampled directions), worst undercut {:e}",
            tally.cases,
            tally.overlapping,
            tally.separated,
            tally.cell_axes,
            tally.sampled,
            tally.worst_undercut
        );
        assert_eq!(tally.cases, 5 * per_pose);
        assert!(
            tally.overlapping > 0 && tally.separated > 0,
            "N = {n}: {tally:?}"
        );
        assert!(tally.sampled >= 2 * per_pose, "N = {n}: {tally:?}");
        if n >= 3 {
            assert!(tally.cell_axes > 0, "N = {n}: no cell axis was ever chosen");
        }
    }
}

#[test]
fn box_queries_refuse_malformed_boxes() {
    let h = [1.0, 1.0, 1.0];
    let c = [0.0; 3];
    let q = identity(3);
    let good = rotorflow::dynamics::motion::detect::PlacedBox {
        half_lengths: &h,
        position: &c,
        rotation: &q,
    };
    let skew = [1.0, 0.1, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
    let nan = [f64::NAN, 0.0, 0.0];
    let negative = [1.0, -1.0, 1.0];
    let cases = [
        rotorflow::dynamics::motion::detect::PlacedBox {
            rotation: &skew,
            ..good
        },
        rotorflow::dynamics::motion::detect::PlacedBox {
            position: &nan,
            ..good
        },
        rotorflow::dynamics::motion::detect::PlacedBox {
            half_lengths: &negative,
            ..good
        },
        rotorflow::dynamics::motion::detect::PlacedBox {
            position: &c[..2],
            ..good
        },
    ];
    for bad in &cases {
        assert!(box_box(&good, bad).is_err(), "{bad:?}");
        assert!(box_manifold(bad, &good, 0.0).is_err(), "{bad:?}");
    }
    assert!(box_manifold(&good, &good, f64::NAN).is_err());
}

/// Zero half-lengths (a flat box, a segment) give finite answers.
#[test]
fn flat_boxes_give_finite_answers() {
    let mut r = super::rng(5);
    let mut count = 0;
    for n in 2..=5 {
        for _ in 0..20 {
            let (mut a, mut b) = random_pair(&mut r, n, Pose::EdgeToFace);
            a.h[r.gen_range(0..n)] = 0.0;
            b.h[r.gen_range(0..n)] = 0.0;
            let axis = box_box(&a.placed(), &b.placed()).unwrap();
            assert!(axis.depth.is_finite() && axis.normal.iter().all(|x| x.is_finite()));
            if let Some(m) = box_manifold(&a.placed(), &b.placed(), 0.05).unwrap() {
                for p in m.points() {
                    assert!(p.depth.is_finite());
                    assert!(p.point_a.iter().chain(p.point_b).all(|x| x.is_finite()));
                }
            }
            count += 1;
        }
    }
    assert_eq!(count, 80);
}

/// A region vertex: point on A, point on B, plane coordinates, depth.
type Vertex = (Vec<f64>, Vec<f64>, Vec<f64>, f64);

fn region_of(
    a: &TestBox,
    b: &TestBox,
    margin: f64,
) -> (
    Vec<Vertex>,
    rotorflow::dynamics::motion::detect::BoxPairAxis,
) {
    let mut region = Vec::new();
    let axis = box_contact_vertices(&a.placed(), &b.placed(), margin, |v: RegionVertex<'_>| {
        region.push((
            v.point_a.to_vec(),
            v.point_b.to_vec(),
            v.plane.to_vec(),
            v.depth,
        ));
    })
    .unwrap();
    (region, axis)
}

/// The contact region of face contacts has exactly the vertices that brute-force vertex
/// enumeration finds, in N = 3 … 5 (in 4D the faces are 3D cubes and the region a 3D
/// polytope); its witness points lie on the boxes and differ by depth along the normal.
#[test]
fn face_contact_region_has_every_vertex() {
    let mut r = super::rng(77);
    let margin = 0.05;
    for n in 3..=5 {
        let mut cases = 0;
        let mut vertices = 0;
        let mut most = 0;
        while cases < 40 {
            let pose = if r.gen_bool(0.5) {
                Pose::FaceToFace
            } else {
                Pose::EdgeToFace
            };
            let (a, b) = random_pair(&mut r, n, pose);
            let (region, axis) = region_of(&a, &b, margin);
            if matches!(axis.feature, AxisFeature::Cells { .. }) || axis.depth < -margin {
                continue;
            }
            let brute = brute_face_region(&a, &b, &axis, margin);
            let incident = |v: &(Vec<f64>, Vec<f64>, Vec<f64>, f64)| match axis.feature {
                AxisFeature::FaceOfA { .. } => v.1.clone(),
                _ => v.0.clone(),
            };
            let mut distinct: Vec<Vec<f64>> = Vec::new();
            for v in &region {
                let p = incident(v);
                assert!(
                    brute
                        .iter()
                        .any(|(q, depth)| dist(q, &p) < 1e-7 && (depth - v.3).abs() < 1e-7),
                    "N = {n}: vertex {p:?} is not a brute-force vertex {brute:?}"
                );
                if !distinct.iter().any(|q| dist(q, &p) < 1e-7) {
                    distinct.push(p);
                }
                // Witnesses: on the boxes' surfaces, apart by depth along the normal.
                let gap: Vec<f64> = v.0.iter().zip(&v.1).map(|(x, y)| x - y).collect();
                assert!((dot(&gap, &axis.normal) - v.3).abs() < 1e-9);
                assert!(a.outside(&v.0) < 1e-9 + 0.0 || v.3 < 0.0 || a.outside(&v.0) < 1e-9);
                assert!(b.outside(&v.1) < 1e-9 || v.3 < 0.0);
            }
            for (q, _) in &brute {
                assert!(
                    distinct.iter().any(|p| dist(p, q) < 1e-7),
                    "N = {n}: brute-force vertex {q:?} missing from {distinct:?}"
                );
            }
            vertices += distinct.len();
            most = most.max(distinct.len());
            cases += 1;
        }
        println!(
            "N = {n}: {cases} face contacts, {vertices} region vertices, at most {most} in one"
        );
        assert_eq!(cases, 40);
        assert!(vertices > 0);
    }
}

/// The manifold keeps at most 2^(N−1) points (4 in 3D, 8 in 4D), each a region vertex, the
/// deepest among them when it is markedly deeper, and distinct feature ids.
#[test]
fn manifolds_are_bounded_and_keep_the_deepest_point() {
    let mut r = super::rng(8);
    for n in 2..=6 {
        let mut cases = 0;
        while cases < 40 {
            let pose = [Pose::FaceToFace, Pose::EdgeToFace, Pose::Random][r.gen_range(0..3)];
            let (a, b) = random_pair(&mut r, n, pose);
            let Some(m) = box_manifold(&a.placed(), &b.placed(), 0.02).unwrap() else {
                continue;
            };
            let (region, axis) = region_of(&a, &b, 0.02);
            assert!(
                !m.is_empty() && m.len() <= manifold_capacity(n),
                "N = {n}: {} points",
                m.len()
            );
            assert_eq!(m.normal(), &axis.normal[..]);
            let deepest = region.iter().map(|v| v.3).fold(f64::NEG_INFINITY, f64::max);
            let shallowest = region.iter().map(|v| v.3).fold(f64::INFINITY, f64::min);
            assert!(
                m.max_depth() >= deepest - 0.25 * (deepest - shallowest) - 1e-9,
                "N = {n}"
            );
            for (k, p) in m.points().enumerate() {
                assert!(
                    region
                        .iter()
                        .any(|v| dist(&v.0, p.point_a) < 1e-12 && dist(&v.1, p.point_b) < 1e-12)
                );
                assert!(m.points().skip(k + 1).all(|q| q.id != p.id), "repeated id");
            }
            cases += 1;
        }
        println!(
            "N = {n}: {cases} manifolds checked (capacity {})",
            manifold_capacity(n)
        );
        assert_eq!(cases, 40);
    }
    assert_eq!(manifold_capacity(3), 4);
    assert_eq!(manifold_capacity(4), 8);
}

/// A box resting on another, turned about the normal and shifted, whose centre of mass is
/// over the contact region: the kept points must hold the centre of mass's projection, so
/// that the box does not tip. When the upper box's face lies wholly on the lower box's, or
/// wholly covers it, the region is centrally symmetric about the centre of mass's
/// projection and the opposite directions of the reduction hold it in every case; when
/// the upper box overhangs an edge, the region is a clipped polygon (polytope) and the
/// kept extremes hold the centre of mass in most poses, not all: the count is printed and
/// bounded below. N = 3 … 7 (from 6D the reduction keeps 16 of a face's 32 or 64 corners).
#[test]
fn resting_box_is_held_under_its_centre_of_mass() {
    let mut r = super::rng(13);
    for n in 3..=7 {
        let d = n - 1;
        let (mut symmetric, mut overhanging, mut overhanging_held) = (0, 0, 0);
        let mut tries = 0;
        while symmetric < 40 || overhanging < 40 {
            tries += 1;
            assert!(tries < 20_000, "N = {n}: too few stable poses");
            let lower = TestBox {
                h: (0..n).map(|_| r.gen_range(0.3..1.5)).collect(),
                c: vec![0.0; n],
                q: identity(n),
            };
            // Half the poses a small box well inside the top face (symmetric regions).
            let small = r.gen_bool(0.5);
            let mut h: Vec<f64> = (0..n)
                .map(|_| {
                    if small {
                        r.gen_range(0.05..0.2)
                    } else {
                        r.gen_range(0.2..1.5)
                    }
                })
                .collect();
            h[d] = r.gen_range(0.2..1.0);
            let (i, j) = (r.gen_range(0..d), r.gen_range(0..d));
            let turn = if i != j && r.gen_bool(0.7) {
                plane_rotation(n, i, j, r.gen_range(-1.0..1.0))
            } else {
                identity(n)
            };
            let sink = 1e-3;
            let mut c: Vec<f64> = (0..d)
                .map(|t| r.gen_range(-1.0..1.0) * if small { lower.h[t] - 0.3 } else { lower.h[t] })
                .collect();
            c.push(lower.h[d] + h[d] - sink);
            let upper = TestBox { h, c, q: turn };
            // Stable: the centre of mass over the top face of the lower box, with a margin.
            let com: Vec<f64> = upper.c[..d].to_vec();
            if (0..d).any(|t| com[t].abs() > 0.9 * lower.h[t]) {
                continue;
            }
            let axis = box_box(&lower.placed(), &upper.placed()).unwrap();
            assert!(
                !matches!(axis.feature, AxisFeature::Cells { .. }),
                "a resting pose chose a cell axis"
            );
            let m = box_manifold(&lower.placed(), &upper.placed(), 0.0)
                .unwrap()
                .expect("in contact");
            assert!(
                m.points().all(|p| (p.depth - sink).abs() < 1e-9),
                "N = {n}: depths"
            );
            let kept: Vec<Vec<f64>> = m.points().map(|p| p.point_b[..d].to_vec()).collect();
            let held = in_hull(&kept, &com, 1e-9);
            // Symmetric: every corner of the upper bottom face over the lower top face, or
            // every corner of the lower top face under the upper box.
            let top = |p: &[f64]| (0..d).all(|t| p[t].abs() <= lower.h[t]);
            let upper_on_lower = upper.corners().iter().all(|p| top(p));
            let lower_under_upper = lower.corners().iter().all(|p| {
                let mut q = p.clone();
                q[d] = upper.c[d];
                upper.outside(&q) < 1e-12
            });
            if upper_on_lower || lower_under_upper {
                assert!(
                    held,
                    "N = {n}: centre of mass {com:?} outside the kept points {kept:?}"
                );
                symmetric += 1;
            } else {
                overhanging += 1;
                overhanging_held += held as usize;
            }
        }
        println!(
            "N = {n}: {symmetric} symmetric resting poses held; overhanging: {overhanging_held} of {overhanging} held ({tries} drawn)"
        );
        assert!(symmetric >= 40 && overhanging >= 40);
        // Measured: every overhanging pose held up to 5D (all corners of a face are
        // directions), 32 of 40 in 6D and 25 of 40 in 7D (16 of 32 or 64 corners).
        let least = match n {
            ..=5 => 8,
            6 => 7,
            _ => 5,
        };
        assert!(
            overhanging_held * 10 >= overhanging * least,
            "N = {n}: {overhanging_held}/{overhanging}"
        );
    }
}

/// A box that moves a little keeps the ids of its points.
#[test]
fn feature_ids_persist_under_small_motion() {
    let mut r = super::rng(21);
    for n in 3..=4 {
        let mut matched = 0;
        let mut total = 0;
        for _ in 0..30 {
            let (a, b) = random_pair(&mut r, n, Pose::FaceToFace);
            let Some(m0) = box_manifold(&a.placed(), &b.placed(), 0.0).unwrap() else {
                continue;
            };
            let mut b1 = b.clone();
            b1.c.iter_mut()
                .for_each(|x| *x += 1e-6 * r.gen_range(-1.0..1.0));
            let m1: ContactManifold = box_manifold(&a.placed(), &b1.placed(), 0.0)
                .unwrap()
                .unwrap();
            for p in m0.points() {
                total += 1;
                if let Some(q) = m1.points().find(|q| q.id == p.id) {
                    assert!(dist(p.point_b, q.point_b) < 1e-4, "same id, far point");
                    matched += 1;
                }
            }
        }
        println!("N = {n}: {matched} of {total} points kept their id after a 1e-6 move");
        assert!(total > 0 && matched == total, "N = {n}: {matched}/{total}");
    }
}

/// Cell contacts (edge–edge in 3D, edge–face-2 and 2-face–edge in 4D): one point, on both
/// boxes, at the depth of the axis.
#[test]
fn cell_contact_is_one_point_at_the_crossing() {
    let mut r = super::rng(4);
    for n in 3..=4 {
        let mut checked = 0;
        let mut drawn = 0;
        while checked < 20 {
            drawn += 1;
            assert!(drawn < 20_000, "N = {n}: too few cell contacts");
            let (a, b) = random_pair(&mut r, n, Pose::Random);
            let axis = box_box(&a.placed(), &b.placed()).unwrap();
            if !matches!(axis.feature, AxisFeature::Cells { .. }) || axis.depth < 0.0 {
                continue;
            }
            let m = box_manifold(&a.placed(), &b.placed(), 0.0)
                .unwrap()
                .unwrap();
            assert_eq!(m.len(), 1);
            let p = m.point(0);
            assert!(
                (p.depth - axis.depth).abs() < 1e-9,
                "{} vs {}",
                p.depth,
                axis.depth
            );
            assert!(a.outside(p.point_a) < 1e-9 && b.outside(p.point_b) < 1e-9);
            let gap: Vec<f64> = p
                .point_a
                .iter()
                .zip(p.point_b)
                .map(|(x, y)| x - y)
                .collect();
            assert!((dot(&gap, &axis.normal) - p.depth).abs() < 1e-9);
            checked += 1;
        }
        println!("N = {n}: {checked} cell contacts ({drawn} poses drawn)");
    }
}

fn hull_of(b: &TestBox) -> Vec<f64> {
    let n = b.dim();
    (0..1usize << n)
        .flat_map(|m| (0..n).map(move |j| if m >> j & 1 == 1 { 1.0 } else { -1.0 }))
        .enumerate()
        .map(|(k, s)| s * b.h[k % n])
        .collect()
}

/// Boxes given as vertex lists: the hull manifold's region is the box region (faces parallel
/// within the support tolerance), in 3D and 4D.
#[test]
fn hull_region_matches_box_region_for_parallel_faces() {
    let mut r = super::rng(99);
    for n in 3..=4 {
        let mut cases = 0;
        while cases < 30 {
            let (a, b) = random_pair(&mut r, n, Pose::FaceToFace);
            let (region, axis) = region_of(&a, &b, 0.0);
            if region.is_empty() || matches!(axis.feature, AxisFeature::Cells { .. }) {
                continue;
            }
            // Only faces that are parallel (a side face of A against a turned B is not).
            let parallel = |x: &TestBox| {
                (0..n).any(|j| (dot(&x.axis(j), &axis.normal).abs() - 1.0).abs() < 1e-12)
            };
            if !(parallel(&a) && parallel(&b)) {
                continue;
            }
            let (va, vb) = (hull_of(&a), hull_of(&b));
            let ha = PlacedHull {
                vertices: &va,
                position: &a.c,
                rotation: &a.q,
            };
            let hb = PlacedHull {
                vertices: &vb,
                position: &b.c,
                rotation: &b.q,
            };
            let mut hull_points: Vec<(Vec<f64>, f64)> = Vec::new();
            hull_contact_vertices(&ha, &hb, &axis.normal, 0.0, |v| {
                hull_points.push((v.point_b.to_vec(), v.depth))
            })
            .unwrap();
            for (_, pb, _, depth) in &region {
                assert!(
                    hull_points
                        .iter()
                        .any(|(q, e)| dist(q, pb) < 1e-7 && (e - depth).abs() < 1e-7),
                    "N = {n}: box vertex {pb:?} not in the hull region"
                );
            }
            // Crossings of simplices that are not faces (diagonals) give points inside the
            // region too: on both boxes, apart by depth along the normal.
            let mut hull_all: Vec<(Vec<f64>, Vec<f64>, f64)> = Vec::new();
            hull_contact_vertices(&ha, &hb, &axis.normal, 0.0, |v| {
                hull_all.push((v.point_a.to_vec(), v.point_b.to_vec(), v.depth))
            })
            .unwrap();
            for (pa, pb, depth) in &hull_all {
                assert!(
                    a.outside(pa) < 1e-9 && b.outside(pb) < 1e-9,
                    "N = {n}: {pa:?}, {pb:?}"
                );
                assert!(
                    b.outside(pa) < 1e-9 && a.outside(pb) < 1e-9,
                    "N = {n}: {pa:?}, {pb:?}"
                );
                let gap: Vec<f64> = pa.iter().zip(pb).map(|(x, y)| x - y).collect();
                assert!((dot(&gap, &axis.normal) - depth).abs() < 1e-9);
            }
            let m = hull_manifold(&ha, &hb, &axis.normal, 0.0).unwrap().unwrap();
            assert!(!m.is_empty() && m.len() <= manifold_capacity(n));
            cases += 1;
        }
        println!("N = {n}: {cases} hull regions equal the box regions");
    }
}

/// Two boxes face on face a hair apart (1e-13 … 1e-8 of their size, each turned by up to
/// 3e-9 rad in random planes, the upper one shifted), in N = 3 … 8: the separating axes
/// give the face axis, not an edge or cell axis of a slightly wider gap, so that the
/// manifold holds the face by its corners (at least 2^(N−1) points up to 5D, 16 beyond).
/// Without the face preference for boxes apart this fails in 3D already; the single cell
/// point it gave kicked a resting 7D box into rocking.
#[test]
fn boxes_a_hair_apart_face_on_face_keep_their_face() {
    let mut r = super::rng(29);
    let mut cases = 0;
    for n in 3..=8 {
        let d = n - 1;
        for _ in 0..500 {
            let turn = |r: &mut rand_chacha::ChaCha8Rng| {
                let mut q = identity(n);
                for _ in 0..3 {
                    let (i, j) = (r.gen_range(0..n), r.gen_range(0..n));
                    if i != j {
                        q = matmul(n, &q, &plane_rotation(n, i, j, r.gen_range(-1e-9..1e-9)));
                    }
                }
                q
            };
            let lower = TestBox {
                h: (0..n).map(|i| 0.5 + 0.1 * i as f64).collect(),
                c: vec![0.0; n],
                q: turn(&mut r),
            };
            let gap = 10f64.powf(r.gen_range(-13.0..-8.0)) * lower.size();
            let q = turn(&mut r);
            let mut c: Vec<f64> = (0..d).map(|_| r.gen_range(-0.1..0.1)).collect();
            c.push(2.0 * lower.h[d] + gap);
            let upper = TestBox {
                h: lower.h.clone(),
                c,
                q,
            };
            let axis = box_box(&lower.placed(), &upper.placed()).unwrap();
            assert!(
                !matches!(axis.feature, AxisFeature::Cells { .. }),
                "N = {n}, gap {gap:e}: a cell axis {:?} (depth {:e})",
                axis.feature,
                axis.depth
            );
            let m = box_manifold(&lower.placed(), &upper.placed(), 1e-6)
                .unwrap()
                .expect("within the margin");
            let corners = (1usize << d).min(16);
            assert!(m.len() >= corners, "N = {n}: {} points", m.len());
            cases += 1;
        }
    }
    assert_eq!(cases, 3000);
}
