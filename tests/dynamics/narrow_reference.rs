//! Independent answers for the narrow-phase tests: the minimum-norm point of a point
//! set's convex hull by Wolfe's algorithm with its optimality certificate checked by brute
//! force, penetration depths of polytope pairs by the separating-axis test over the
//! generalised axes (ten Bosch, "N-Dimensional Rigid Body Dynamics", 2020) or over every
//! hyperplane through N points of the Minkowski difference, and the distance from a point
//! to an ellipsoid by a 1-D root solve. None of them calls the crate's narrow phase;
//! [`polytope_distance_run`] compares the crate's `distance` with them on random pairs.
#![allow(dead_code)]

use nalgebra::{DMatrix, DVector};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rotorflow::dynamics::motion::detect::{PlacedShape, distance};
use rotorflow::dynamics::motion::shape::{ConvexCore, ConvexShape};

pub fn placed(p: &Posed) -> PlacedShape<'_> {
    PlacedShape::new(&p.shape, &p.position, &p.rotation).unwrap()
}

pub fn norm(x: &[f64]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// A shape with its placement (position, row-major rotation own → space).
pub struct Posed {
    pub shape: ConvexShape,
    pub position: Vec<f64>,
    pub rotation: Vec<f64>,
}

/// A random rotation in `n` dimensions (QR of a random matrix, determinant +1).
pub fn random_rotation(r: &mut impl Rng, n: usize) -> Vec<f64> {
    let m = DMatrix::from_fn(n, n, |_, _| r.gen_range(-1.0..1.0));
    let qr = m.qr();
    let mut q = qr.q();
    if q.determinant() < 0.0 {
        for i in 0..n {
            q[(i, 0)] = -q[(i, 0)];
        }
    }
    let mut out = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..n {
            out[i * n + j] = q[(i, j)];
        }
    }
    out
}

pub fn identity(n: usize) -> Vec<f64> {
    (0..n * n)
        .map(|k| if k % (n + 1) == 0 { 1.0 } else { 0.0 })
        .collect()
}

/// The vertices of a polytope core in own axes (cuboid corners or hull points).
pub fn own_vertices(shape: &ConvexShape) -> Vec<Vec<f64>> {
    let n = shape.dim();
    match shape.core() {
        ConvexCore::Cuboid(h) => (0..1usize << n)
            .map(|mask| {
                (0..n)
                    .map(|i| if mask >> i & 1 == 1 { h[i] } else { -h[i] })
                    .collect()
            })
            .collect(),
        ConvexCore::Hull(v) => v.chunks_exact(n).map(|p| p.to_vec()).collect(),
        ConvexCore::Point => vec![vec![0.0; n]],
        ConvexCore::Segment(h) => {
            let mut a = vec![0.0; n];
            let mut b = vec![0.0; n];
            a[0] = -h;
            b[0] = *h;
            vec![a, b]
        }
        other => panic!("not a polytope core: {other:?}"),
    }
}

/// The vertices of a posed polytope core in space.
pub fn space_vertices(p: &Posed) -> Vec<Vec<f64>> {
    let n = p.shape.dim();
    own_vertices(&p.shape)
        .iter()
        .map(|x| {
            (0..n)
                .map(|i| p.position[i] + (0..n).map(|j| p.rotation[i * n + j] * x[j]).sum::<f64>())
                .collect()
        })
        .collect()
}

/// Every b − a.
pub fn difference_points(a: &[Vec<f64>], b: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let mut out = Vec::with_capacity(a.len() * b.len());
    for q in b {
        for p in a {
            out.push(q.iter().zip(p).map(|(x, y)| x - y).collect());
        }
    }
    out
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The point of conv(points) nearest the origin by Wolfe's algorithm ("Finding the
/// nearest point in a polytope", Math. Programming 11, 1976), asserting its certificate
/// (see [`certified_min_norm_point`]).
pub fn min_norm_point(points: &[Vec<f64>]) -> Vec<f64> {
    certified_min_norm_point(points).unwrap_or_else(|(x, lower)| {
        panic!(
            "Wolfe's answer fails its certificate: |x|² = {}, min x·p = {lower}",
            dot(&x, &x)
        )
    })
}

/// The point of conv(points) nearest the origin by Wolfe's algorithm: major cycles add the
/// point of least x·p, minor cycles move to the affine minimum of the corral or back along
/// the segment to it. Returns the point if it meets the optimality certificate
/// min_p x·p ≥ |x|² − tol (checked by brute force), else the point and min_p x·p: a
/// reference that cannot certify its own answer checks nothing. Asserts that the weights
/// are a convex combination.
pub fn certified_min_norm_point(points: &[Vec<f64>]) -> Result<Vec<f64>, (Vec<f64>, f64)> {
    let n = points[0].len();
    let size = points
        .iter()
        .map(|p| dot(p, p).sqrt())
        .fold(0.0, f64::max)
        .max(1e-300);
    let start = (0..points.len())
        .min_by(|&i, &j| dot(&points[i], &points[i]).total_cmp(&dot(&points[j], &points[j])))
        .unwrap();
    let mut set = vec![start];
    let mut weights = vec![1.0];
    let mut x = points[start].clone();
    for _major in 0..1000 {
        let j = (0..points.len())
            .min_by(|&i, &k| dot(&x, &points[i]).total_cmp(&dot(&x, &points[k])))
            .unwrap();
        if dot(&x, &x) - dot(&x, &points[j]) <= 1e-15 * size * size || set.contains(&j) {
            break;
        }
        set.push(j);
        weights.push(0.0);
        for _minor in 0..1000 {
            // The affine minimum: y = p₀ + E μ with |y| least (SVD least squares).
            let k = set.len();
            let p0 = &points[set[0]];
            let alpha: Vec<f64> = if k == 1 {
                vec![1.0]
            } else {
                let e = DMatrix::from_fn(n, k - 1, |i, c| points[set[c + 1]][i] - p0[i]);
                let rhs = DVector::from_iterator(n, p0.iter().map(|v| -v));
                let mu = e.svd(true, true).solve(&rhs, 1e-14).unwrap();
                let mut a = vec![1.0 - mu.sum()];
                a.extend(mu.iter());
                a
            };
            if alpha.iter().all(|a| *a > 1e-14) {
                weights = alpha;
                break;
            }
            let mut theta: f64 = 1.0;
            for (l, a) in weights.iter().zip(&alpha) {
                if *a <= 1e-14 && l - a > 0.0 {
                    theta = theta.min(l / (l - a));
                }
            }
            for (l, a) in weights.iter_mut().zip(&alpha) {
                *l += theta * (a - *l);
            }
            let mut keep_set = Vec::new();
            let mut keep_w = Vec::new();
            for (s, l) in set.iter().zip(&weights) {
                if *l > 1e-14 {
                    keep_set.push(*s);
                    keep_w.push(*l);
                }
            }
            set = keep_set;
            let total: f64 = keep_w.iter().sum();
            weights = keep_w.iter().map(|l| l / total).collect();
        }
        x = vec![0.0; n];
        for (s, l) in set.iter().zip(&weights) {
            for i in 0..n {
                x[i] += l * points[*s][i];
            }
        }
    }
    assert!(weights.iter().all(|l| *l >= 0.0));
    assert!((weights.iter().sum::<f64>() - 1.0).abs() < 1e-12);
    let lower = points
        .iter()
        .map(|p| dot(&x, p))
        .fold(f64::INFINITY, f64::min);
    // Near the origin the certificate's lower bound min x·p / |x| says little; there the
    // answer is certified as "within 1e-8 of the size from touching".
    if dot(&x, &x) - lower <= 1e-11 * size * size || dot(&x, &x).sqrt() <= 1e-8 * size {
        Ok(x)
    } else {
        Err((x, lower))
    }
}

/// The distance between two polytopes given by vertices.
pub fn polytope_distance(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    let x = min_norm_point(&difference_points(a, b));
    dot(&x, &x).sqrt()
}

/// The unit vector orthogonal to n − 1 vectors of ℝⁿ (the dual of their wedge, by
/// cofactors), None if they are dependent.
pub fn orthogonal_complement(vectors: &[Vec<f64>], n: usize) -> Option<Vec<f64>> {
    let m = DMatrix::from_fn(n - 1, n, |i, j| vectors[i][j]);
    let mut u = vec![0.0; n];
    for (col, x) in u.iter_mut().enumerate() {
        let minor = m.clone().remove_column(col);
        let sign = if col % 2 == 0 { 1.0 } else { -1.0 };
        *x = sign * if n == 1 { 1.0 } else { minor.determinant() };
    }
    let length = dot(&u, &u).sqrt();
    let scale: f64 = vectors.iter().map(|v| dot(v, v).sqrt()).product();
    if length <= 1e-9 * scale {
        return None;
    }
    Some(u.iter().map(|x| x / length).collect())
}

/// The overlap of two vertex sets along the unit direction u from A to B:
/// max_a u·a − min_b u·b (> 0 overlap).
pub fn overlap_along(a: &[Vec<f64>], b: &[Vec<f64>], u: &[f64]) -> f64 {
    let top_a = a
        .iter()
        .map(|p| dot(u, p))
        .fold(f64::NEG_INFINITY, f64::max);
    let bottom_b = b.iter().map(|p| dot(u, p)).fold(f64::INFINITY, f64::min);
    top_a - bottom_b
}

/// The least overlap over the unit direction and its opposite.
fn least_overlap(a: &[Vec<f64>], b: &[Vec<f64>], u: &[f64]) -> f64 {
    let minus: Vec<f64> = u.iter().map(|x| -x).collect();
    overlap_along(a, b, u).min(overlap_along(a, b, &minus))
}

/// All k-subsets of 0..m.
pub fn subsets(m: usize, k: usize) -> Vec<Vec<usize>> {
    let mut out = Vec::new();
    let mut current = Vec::new();
    fn go(start: usize, m: usize, k: usize, current: &mut Vec<usize>, out: &mut Vec<Vec<usize>>) {
        if current.len() == k {
            out.push(current.clone());
            return;
        }
        for i in start..m {
            current.push(i);
            go(i + 1, m, k, current, out);
            current.pop();
        }
    }
    go(0, m, k, &mut current, &mut out);
    out
}

/// The penetration depth of two posed cuboids by the separating-axis test over the
/// generalised axes: for every m_a-subset of A's axes and (N − 1 − m_a)-subset of B's,
/// the direction orthogonal to them (two 4D boxes: 56 axes, 3D: 15). Returns the least
/// overlap over them and the number of axes tried (> 0 overlap; the separation is not
/// exact for separated boxes).
pub fn box_box_sat(a: &Posed, b: &Posed) -> (f64, usize) {
    let n = a.shape.dim();
    let axes = |p: &Posed| -> Vec<Vec<f64>> {
        (0..n)
            .map(|j| (0..n).map(|i| p.rotation[i * n + j]).collect())
            .collect()
    };
    let (xa, xb) = (axes(a), axes(b));
    let (va, vb) = (space_vertices(a), space_vertices(b));
    let mut best = f64::INFINITY;
    let mut tried = 0;
    for ma in 0..n {
        let mb = n - 1 - ma;
        for sa in subsets(n, ma) {
            for sb in subsets(n, mb) {
                let mut vectors: Vec<Vec<f64>> = sa.iter().map(|&i| xa[i].clone()).collect();
                vectors.extend(sb.iter().map(|&i| xb[i].clone()));
                tried += 1;
                if let Some(u) = orthogonal_complement(&vectors, n) {
                    best = best.min(least_overlap(&va, &vb, &u));
                }
            }
        }
    }
    (best, tried)
}

/// The penetration depth of two polytopes by brute force over every hyperplane through N
/// affinely independent points of the Minkowski difference B − A: the least support
/// value over their normals (the facet normals are among them).
pub fn polytope_depth_brute_force(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    let n = a[0].len();
    let points = difference_points(a, b);
    let mut best = f64::INFINITY;
    for subset in subsets(points.len(), n) {
        let p0 = &points[subset[0]];
        let vectors: Vec<Vec<f64>> = subset[1..]
            .iter()
            .map(|&k| points[k].iter().zip(p0).map(|(x, y)| x - y).collect())
            .collect();
        if let Some(u) = orthogonal_complement(&vectors, n) {
            best = best.min(least_overlap(a, b, &u));
        }
    }
    best
}

/// The distance from `p` (own axes) to the solid ellipsoid of semi-axes `a`: the nearest
/// point is xᵢ = pᵢaᵢ²/(aᵢ² + t) with t ≥ 0 the root of Σ(pᵢaᵢ/(aᵢ² + t))² = 1, found by
/// bisection (the sum decreases in t).
pub fn point_ellipsoid_distance(p: &[f64], a: &[f64]) -> f64 {
    let f = |t: f64| -> f64 {
        p.iter()
            .zip(a)
            .map(|(x, s)| (x * s / (s * s + t)).powi(2))
            .sum::<f64>()
            - 1.0
    };
    if f(0.0) <= 0.0 {
        return 0.0;
    }
    let (mut lo, mut hi) = (0.0, 1.0);
    while f(hi) > 0.0 {
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let t = 0.5 * (lo + hi);
    p.iter()
        .zip(a)
        .map(|(x, s)| {
            let y = x * s * s / (s * s + t);
            (x - y) * (x - y)
        })
        .sum::<f64>()
        .sqrt()
}

/// A random polytope in `n` dimensions: a cuboid, a hull of N + 1 … N + 5 random points,
/// a regular simplex or a cross-polytope, of size about 0.2 … 2.
pub fn random_polytope(r: &mut impl Rng, n: usize, hulls_only: bool) -> ConvexShape {
    let kind = if hulls_only { 1 } else { r.gen_range(0..4) };
    match kind {
        0 => {
            let h: Vec<f64> = (0..n).map(|_| r.gen_range(0.2..2.0)).collect();
            ConvexShape::cuboid(&h).unwrap()
        }
        1 => loop {
            let count = n + 1 + r.gen_range(0..5);
            let points: Vec<Vec<f64>> = (0..count)
                .map(|_| (0..n).map(|_| r.gen_range(-1.5..1.5)).collect())
                .collect();
            if let Ok(s) = ConvexShape::hull(&points) {
                break s;
            }
        },
        2 => ConvexShape::simplex(n, r.gen_range(0.3..2.0)).unwrap(),
        _ => ConvexShape::cross_polytope(n, r.gen_range(0.3..2.0)).unwrap(),
    }
}

/// A random placement of B about A at a distance that makes about half the pairs overlap.
pub fn random_pair(r: &mut impl Rng, a: ConvexShape, b: ConvexShape) -> (Posed, Posed) {
    let n = a.dim();
    let reach = a.bounding_radius() + b.bounding_radius();
    let mut dir: Vec<f64> = (0..n).map(|_| r.gen_range(-1.0..1.0)).collect();
    let length = dot(&dir, &dir).sqrt().max(1e-12);
    let d = r.gen_range(0.0..1.1) * reach;
    dir.iter_mut().for_each(|x| *x *= d / length);
    let pa: Vec<f64> = (0..n).map(|_| r.gen_range(-1.0..1.0)).collect();
    let pb: Vec<f64> = pa.iter().zip(&dir).map(|(x, y)| x + y).collect();
    (
        Posed {
            rotation: random_rotation(r, n),
            shape: a,
            position: pa,
        },
        Posed {
            rotation: random_rotation(r, n),
            shape: b,
            position: pb,
        },
    )
}

/// Runs `pairs` random polytope pairs in `n` dimensions through `distance` and checks
/// each against Wolfe's minimum-norm point; returns (overlapping, separated, wrong,
/// non-finite, largest iteration count, pairs the reference could not certify).
pub fn polytope_distance_run(seed: u64, n: usize, pairs: usize) -> [usize; 6] {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    let mut counts = [0usize; 6];
    for k in 0..pairs {
        let hulls_only = n >= 6;
        let a = random_polytope(&mut r, n, hulls_only);
        let b = random_polytope(&mut r, n, hulls_only);
        let (pa, pb) = random_pair(&mut r, a, b);
        let size = pa.shape.bounding_radius() + pb.shape.bounding_radius();
        let Ok(x) = certified_min_norm_point(&difference_points(
            &space_vertices(&pa),
            &space_vertices(&pb),
        )) else {
            // Wolfe's reference could not certify its answer: the pair is not checked, and
            // counted apart so that a run shows how many were left out.
            counts[5] += 1;
            continue;
        };
        let expected = dot(&x, &x).sqrt();
        let got = distance(&placed(&pa), &placed(&pb)).unwrap();
        let swapped = distance(&placed(&pb), &placed(&pa)).unwrap();
        let finite = got.distance.is_finite()
            && got.normal.as_slice().iter().all(|x| x.is_finite())
            && got.witness_a.as_slice().iter().all(|x| x.is_finite())
            && got.witness_b.as_slice().iter().all(|x| x.is_finite());
        if !finite {
            counts[3] += 1;
            continue;
        }
        let tolerance = 1e-9 * (expected + size);
        // The witnesses are as far apart as the distance, along the normal.
        let gap: Vec<f64> = got
            .witness_b
            .as_slice()
            .iter()
            .zip(got.witness_a.as_slice())
            .map(|(p, q)| p - q)
            .collect();
        let consistent = (norm(&gap) - got.distance).abs() <= tolerance
            && gap
                .iter()
                .zip(got.normal.as_slice())
                .all(|(g, m)| (g - got.distance * m).abs() <= tolerance);
        let wrong = (got.distance - expected).abs() > tolerance
            || (swapped.distance - expected).abs() > tolerance
            || !consistent;
        if wrong {
            counts[2] += 1;
            eprintln!(
                "N = {n}, pair {k}: distance {} (swapped {}), Wolfe {expected}",
                got.distance, swapped.distance
            );
        }
        counts[if got.intersecting { 0 } else { 1 }] += 1;
        counts[4] = counts[4].max(got.iterations).max(swapped.iterations);
    }
    counts
}
