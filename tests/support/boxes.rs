//! Independent checks of the box queries of `dynamics::motion::detect`: random poses, and
//! brute force that does not share code or method with the library (projections of the
//! 2^N vertices on sampled and refined directions, alternating projections between the two
//! boxes, vertex enumeration of the contact region over all subsets of its constraints).
#![allow(dead_code)]

use nalgebra::{DMatrix, DVector};
use rand::Rng;
use rotorflow::dynamics::motion::detect::{AxisFeature, BoxPairAxis, PlacedBox};

/// A box with owned data.
#[derive(Clone, Debug)]
pub struct TestBox {
    pub h: Vec<f64>,
    pub c: Vec<f64>,
    /// Row-major, own axes → space.
    pub q: Vec<f64>,
}

impl TestBox {
    pub fn placed(&self) -> PlacedBox<'_> {
        PlacedBox {
            half_lengths: &self.h,
            position: &self.c,
            rotation: &self.q,
        }
    }
    pub fn dim(&self) -> usize {
        self.h.len()
    }
    /// Own axis j in space.
    pub fn axis(&self, j: usize) -> Vec<f64> {
        let n = self.dim();
        (0..n).map(|i| self.q[i * n + j]).collect()
    }
    /// The 2^N corners in space.
    pub fn corners(&self) -> Vec<Vec<f64>> {
        let n = self.dim();
        (0..1usize << n)
            .map(|m| {
                let own: Vec<f64> = (0..n)
                    .map(|j| {
                        if m >> j & 1 == 1 {
                            self.h[j]
                        } else {
                            -self.h[j]
                        }
                    })
                    .collect();
                self.to_space(&own)
            })
            .collect()
    }
    pub fn to_space(&self, own: &[f64]) -> Vec<f64> {
        let n = self.dim();
        (0..n)
            .map(|i| self.c[i] + (0..n).map(|j| self.q[i * n + j] * own[j]).sum::<f64>())
            .collect()
    }
    pub fn to_own(&self, p: &[f64]) -> Vec<f64> {
        let n = self.dim();
        (0..n)
            .map(|j| (0..n).map(|i| self.q[i * n + j] * (p[i] - self.c[i])).sum())
            .collect()
    }
    /// The nearest point of the box.
    pub fn project(&self, p: &[f64]) -> Vec<f64> {
        let own: Vec<f64> = self
            .to_own(p)
            .iter()
            .zip(&self.h)
            .map(|(x, h)| x.clamp(-h, *h))
            .collect();
        self.to_space(&own)
    }
    /// The distance of `p` outside the box (0 inside).
    pub fn outside(&self, p: &[f64]) -> f64 {
        dist(&self.project(p), p)
    }
    pub fn size(&self) -> f64 {
        self.h.iter().copied().fold(0.0, f64::max)
    }
}

pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

pub fn dist(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// A random rotation, row-major: the Q factor of a Gaussian-like matrix, det +1.
pub fn random_rotation(r: &mut impl Rng, n: usize) -> Vec<f64> {
    let m = DMatrix::from_fn(n, n, |_, _| r.gen_range(-1.0..1.0));
    let qr = m.qr();
    let mut q = qr.q();
    if q.determinant() < 0.0 {
        for i in 0..n {
            q[(i, 0)] = -q[(i, 0)];
        }
    }
    (0..n * n).map(|k| q[(k / n, k % n)]).collect()
}

/// The rotation that turns by `angle` in the plane of axes i, j, row-major.
pub fn plane_rotation(n: usize, i: usize, j: usize, angle: f64) -> Vec<f64> {
    let mut q = identity(n);
    let (s, c) = angle.sin_cos();
    q[i * n + i] = c;
    q[j * n + j] = c;
    q[i * n + j] = -s;
    q[j * n + i] = s;
    q
}

pub fn identity(n: usize) -> Vec<f64> {
    (0..n * n)
        .map(|k| if k / n == k % n { 1.0 } else { 0.0 })
        .collect()
}

pub fn matmul(n: usize, a: &[f64], b: &[f64]) -> Vec<f64> {
    (0..n * n)
        .map(|k| (0..n).map(|l| a[(k / n) * n + l] * b[l * n + k % n]).sum())
        .collect()
}

/// The penetration along the unit `u` from the vertices: how far B must move along ±u to
/// clear A (negative: the gap between the projections).
pub fn penetration_along(a: &[Vec<f64>], b: &[Vec<f64>], u: &[f64]) -> f64 {
    let range = |vs: &[Vec<f64>]| {
        vs.iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                let x = dot(v, u);
                (lo.min(x), hi.max(x))
            })
    };
    let (amin, amax) = range(a);
    let (bmin, bmax) = range(b);
    (amax - bmin).min(bmax - amin)
}

fn random_unit(r: &mut impl Rng, n: usize) -> Vec<f64> {
    loop {
        let v: Vec<f64> = (0..n).map(|_| r.gen_range(-1.0..1.0)).collect();
        let l = dot(&v, &v).sqrt();
        if l > 0.1 && l <= 1.0 {
            return v.iter().map(|x| x / l).collect();
        }
    }
}

/// The least penetration found by sampling `samples` directions (and the boxes' axes) and
/// refining the best `refined` by random descent on the sphere.
pub fn sampled_least_penetration(
    r: &mut impl Rng,
    a: &TestBox,
    b: &TestBox,
    samples: usize,
    refined: usize,
) -> f64 {
    let (va, vb) = (a.corners(), b.corners());
    let n = a.dim();
    let mut starts: Vec<(f64, Vec<f64>)> = (0..samples)
        .map(|_| {
            let u = random_unit(r, n);
            (penetration_along(&va, &vb, &u), u)
        })
        .collect();
    // The box axes and their sums as starts too, so that flat minima are found.
    for box_ in [a, b] {
        for j in 0..n {
            let u = box_.axis(j);
            starts.push((penetration_along(&va, &vb, &u), u));
        }
    }
    starts.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut best = f64::INFINITY;
    for (mut f, mut u) in starts.into_iter().take(refined) {
        let mut step = 0.3;
        while step > 1e-9 {
            let mut improved = false;
            for _ in 0..4 * n {
                let w = random_unit(r, n);
                let mut v: Vec<f64> = u.iter().zip(&w).map(|(x, y)| x + step * y).collect();
                let l = dot(&v, &v).sqrt();
                v.iter_mut().for_each(|x| *x /= l);
                let g = penetration_along(&va, &vb, &v);
                if g < f {
                    f = g;
                    u = v;
                    improved = true;
                }
            }
            if !improved {
                step *= 0.5;
            }
        }
        best = best.min(f);
    }
    best
}

/// The distance between the boxes by alternating projections (converges to the distance
/// for disjoint convex sets, to 0 for intersecting ones).
pub fn alternating_distance(a: &TestBox, b: &TestBox, iterations: usize) -> f64 {
    let mut p = a.c.clone();
    let mut q = b.project(&p);
    // Near-parallel faces meeting in a thin sliver make the iteration slow (each round
    // trip shrinks the distance by about cos² of their angle), so it runs in rounds of
    // `iterations` until the distance is negligible or stops decreasing.
    let scale = a.size().max(b.size());
    let mut last = f64::INFINITY;
    for _ in 0..200 {
        for _ in 0..iterations {
            p = a.project(&q);
            q = b.project(&p);
        }
        let d = dist(&p, &q);
        if d <= 1e-8 * scale || d >= last * (1.0 - 1e-9) {
            return d;
        }
        last = d;
    }
    dist(&p, &q)
}

/// The kinds of pose of a random case.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Pose {
    /// Random rotations, centres at random distance.
    Random,
    /// B's face on A's face, aligned or turned about the normal, overlapping by a little.
    FaceToFace,
    /// A turned box pressing a corner or edge into A's face.
    EdgeToFace,
    /// Aligned boxes exactly touching.
    Touching,
    /// The same box twice.
    Coincident,
}

pub const POSES: [Pose; 5] = [
    Pose::Random,
    Pose::FaceToFace,
    Pose::EdgeToFace,
    Pose::Touching,
    Pose::Coincident,
];

fn half_lengths(r: &mut impl Rng, n: usize) -> Vec<f64> {
    (0..n).map(|_| r.gen_range(0.2..1.5)).collect()
}

/// A random pair of boxes in the given pose.
pub fn random_pair(r: &mut impl Rng, n: usize, pose: Pose) -> (TestBox, TestBox) {
    let a = TestBox {
        h: half_lengths(r, n),
        c: (0..n).map(|_| r.gen_range(-2.0..2.0)).collect(),
        q: random_rotation(r, n),
    };
    let face = r.gen_range(0..n);
    let side = if r.gen_bool(0.5) { 1.0 } else { -1.0 };
    let normal: Vec<f64> = a.axis(face).iter().map(|x| side * x).collect();
    let b = match pose {
        Pose::Random => TestBox {
            h: half_lengths(r, n),
            c: a.c.iter().map(|x| x + r.gen_range(-2.5..2.5)).collect(),
            q: random_rotation(r, n),
        },
        Pose::FaceToFace | Pose::Touching => {
            // B's own axis `face` along A's, turned about the normal (not in Touching).
            let h = half_lengths(r, n);
            let mut turn = identity(n);
            if pose == Pose::FaceToFace && n >= 3 && r.gen_bool(0.7) {
                let (i, j) = loop {
                    let i = r.gen_range(0..n);
                    let j = r.gen_range(0..n);
                    if i != j && i != face && j != face {
                        break (i, j);
                    }
                };
                turn = plane_rotation(n, i, j, r.gen_range(-1.5..1.5));
            }
            let q = matmul(n, &a.q, &turn);
            let overlap = if pose == Pose::Touching {
                0.0
            } else {
                r.gen_range(0.0..0.2)
            };
            let reach = a.h[face] + h[face] - overlap;
            let mut c: Vec<f64> =
                a.c.iter()
                    .zip(&normal)
                    .map(|(x, m)| x + reach * m)
                    .collect();
            // A lateral offset along the face, within the sizes.
            for (t, ht) in h.iter().enumerate() {
                if t != face {
                    let shift = r.gen_range(-0.8..0.8) * a.h[t].min(*ht);
                    let ax = a.axis(t);
                    c.iter_mut().zip(&ax).for_each(|(x, y)| *x += shift * y);
                }
            }
            TestBox { h, c, q }
        }
        Pose::EdgeToFace => {
            let h = half_lengths(r, n);
            let q = random_rotation(r, n);
            let b0 = TestBox {
                h: h.clone(),
                c: vec![0.0; n],
                q: q.clone(),
            };
            // The lowest reach of B along −normal, so that its deepest point enters A's face.
            let reach = b0
                .corners()
                .iter()
                .map(|v| -dot(v, &normal))
                .fold(f64::NEG_INFINITY, f64::max);
            let overlap = r.gen_range(0.0..0.1);
            let along = a.h[face] + reach - overlap;
            let c =
                a.c.iter()
                    .zip(&normal)
                    .map(|(x, m)| x + along * m)
                    .collect();
            TestBox { h, c, q }
        }
        Pose::Coincident => a.clone(),
    };
    (a, b)
}

/// What one SAT case showed.
#[derive(Debug, Default, Clone, Copy)]
pub struct SatTally {
    pub cases: usize,
    pub overlapping: usize,
    pub separated: usize,
    pub cell_axes: usize,
    /// Cases checked against sampled directions.
    pub sampled: usize,
    /// The largest amount by which a sampled direction beat the SAT's least depth (≤ 0
    /// means SAT is the least).
    pub worst_undercut: f64,
}

/// Checks one pair against the brute force; panics with the pose on a failure.
pub fn check_sat_case(
    r: &mut impl Rng,
    a: &TestBox,
    b: &TestBox,
    axis: &BoxPairAxis,
    samples: usize,
    tally: &mut SatTally,
) {
    let n = a.dim();
    let scale = a.size().max(b.size());
    let tol = 1e-9 * scale;
    let context = || format!("N = {n}, A = {a:?}, B = {b:?}, axis = {axis:?}");
    let (va, vb) = (a.corners(), b.corners());
    // A unit normal from A towards B.
    assert!(
        (dot(&axis.normal, &axis.normal).sqrt() - 1.0).abs() < 1e-12,
        "{}",
        context()
    );
    let towards: Vec<f64> = b.c.iter().zip(&a.c).map(|(x, y)| x - y).collect();
    assert!(
        dot(&axis.normal, &towards) >= -tol,
        "normal points from B to A: {}",
        context()
    );
    // Its depth is the penetration along it, from the vertices.
    let along = penetration_along(&va, &vb, &axis.normal);
    assert!(
        (along - axis.depth).abs() <= tol,
        "depth {} vs vertices {along}: {}",
        axis.depth,
        context()
    );
    assert!(axis.least_depth <= axis.depth + tol, "{}", context());
    // The face preference costs at most its bias.
    assert!(
        axis.least_depth >= 0.95 * axis.depth - 2e-3 * scale - tol || axis.depth < 0.0,
        "{}",
        context()
    );
    // When every candidate axis overlaps, no direction penetrates less than the least of
    // them (were an axis missing, a sampled direction would undercut it, or find a gap).
    // Apart, the largest gap over all directions is the distance, which bounds the gap of
    // the candidate axes from above (checked below).
    if axis.least_depth > 0.0 {
        let sampled = sampled_least_penetration(r, a, b, samples, 1 + samples / 40);
        tally.worst_undercut = tally.worst_undercut.max(axis.least_depth - sampled);
        tally.sampled += 1;
        assert!(
            sampled >= axis.least_depth - 1e-7 * scale,
            "a direction penetrates {sampled} < least axis {}: {}",
            axis.least_depth,
            context()
        );
    }
    // Overlap or separation agrees with the distance of the boxes.
    let distance = alternating_distance(a, b, 1000);
    // (Overlapping: the iteration creeps towards a common point through thin slivers, so
    // it is asked to come within 10 % of the depth; a pair SAT wrongly calls overlapping
    // would show a separating direction to the sampled search above.)
    if axis.depth > 1e-3 * scale {
        assert!(
            distance < 1e-6 * scale || distance < 0.1 * axis.depth,
            "overlap {} but distance {distance}: {}",
            axis.depth,
            context()
        );
        tally.overlapping += 1;
    } else if axis.depth < -1e-6 * scale {
        assert!(
            distance >= -axis.depth - 1e-6 * scale,
            "gap {} > distance {distance}: {}",
            -axis.depth,
            context()
        );
        tally.separated += 1;
    }
    if matches!(axis.feature, AxisFeature::Cells { .. }) {
        tally.cell_axes += 1;
    }
    tally.cases += 1;
}

/// The vertices of the contact region of a face contact, by brute force: the incident face
/// (of the other box, most anti-parallel to the reference face) as y ∈ [−1, 1]^(N−1), cut by
/// the reference face's side slabs, every (N−1)-subset of the 4(N−1) constraints solved and
/// the feasible solutions kept, with depth ≥ −margin. Returns the points on the incident
/// face, in space, and their depths.
pub fn brute_face_region(
    a: &TestBox,
    b: &TestBox,
    axis: &BoxPairAxis,
    margin: f64,
) -> Vec<(Vec<f64>, f64)> {
    let n = a.dim();
    let d = n - 1;
    let (reference, incident, ref_normal, face) = match axis.feature {
        AxisFeature::FaceOfA { axis: i } => (a, b, axis.normal.to_vec(), i),
        AxisFeature::FaceOfB { axis: j } => (b, a, axis.normal.iter().map(|x| -x).collect(), j),
        AxisFeature::Cells { .. } => panic!("not a face contact"),
    };
    let s = dot(&reference.axis(face), &ref_normal).signum();
    let face_height = reference.h[face];
    // The incident face.
    let (ji, cj) = (0..n)
        .map(|j| (j, dot(&incident.axis(j), &ref_normal)))
        .max_by(|x, y| x.1.abs().total_cmp(&y.1.abs()))
        .unwrap();
    let si = -cj.signum();
    let inc_axes: Vec<usize> = (0..n).filter(|&u| u != ji).collect();
    let sides: Vec<usize> = (0..n).filter(|&t| t != face).collect();
    let point = |y: &[f64]| -> Vec<f64> {
        let mut own = vec![0.0; n];
        own[ji] = si * incident.h[ji];
        for (c, &u) in inc_axes.iter().enumerate() {
            own[u] = y[c] * incident.h[u];
        }
        incident.to_space(&own)
    };
    // Constraints row · y ≤ rhs: the cube and the side slabs (affine in y).
    let origin = point(&vec![0.0; d]);
    let mut rows: Vec<(Vec<f64>, f64)> = Vec::new();
    for c in 0..d {
        let mut e = vec![0.0; d];
        e[c] = 1.0;
        rows.push((e.clone(), 1.0));
        rows.push((e.iter().map(|x| -x).collect(), 1.0));
    }
    for &t in &sides {
        let at = reference.axis(t);
        let g = dot(&at, &origin) - dot(&at, &reference.c);
        let coef: Vec<f64> = inc_axes
            .iter()
            .map(|&u| incident.h[u] * dot(&at, &incident.axis(u)))
            .collect();
        rows.push((coef.clone(), reference.h[t] - g));
        rows.push((coef.iter().map(|x| -x).collect(), reference.h[t] + g));
    }
    let m = rows.len();
    let mut found: Vec<(Vec<f64>, f64)> = Vec::new();
    let mut subset: Vec<usize> = (0..d).collect();
    loop {
        let mat = DMatrix::from_fn(d, d, |i, j| rows[subset[i]].0[j]);
        let rhs = DVector::from_fn(d, |i, _| rows[subset[i]].1);
        if mat.determinant().abs() > 1e-10
            && let Some(y) = mat.lu().solve(&rhs)
        {
            {
                let feasible = rows
                    .iter()
                    .all(|(row, r)| dot(row, y.as_slice()) <= r + 1e-9);
                if feasible {
                    let p = point(y.as_slice());
                    let depth = face_height
                        - s * (dot(&reference.axis(face), &p)
                            - dot(&reference.axis(face), &reference.c));
                    if depth >= -margin && !found.iter().any(|(q, _)| dist(q, &p) < 1e-9) {
                        found.push((p, depth));
                    }
                }
            }
        }
        // Next subset.
        let mut k = d;
        while k > 0 && subset[k - 1] == m - d + k - 1 {
            k -= 1;
        }
        if k == 0 {
            break;
        }
        subset[k - 1] += 1;
        for l in k..d {
            subset[l] = subset[l - 1] + 1;
        }
    }
    found
}

/// True if `c` lies in the convex hull of `points` (all in d dimensions, the hull
/// full-dimensional), to `tol`: no hyperplane through d of the points has all points on one
/// side and `c` beyond it.
pub fn in_hull(points: &[Vec<f64>], c: &[f64], tol: f64) -> bool {
    let d = c.len();
    let k = points.len();
    if k < d + 1 {
        return false;
    }
    let mut subset: Vec<usize> = (0..d).collect();
    loop {
        // The hyperplane through the subset: its normal is the null vector of the differences.
        let base = &points[subset[0]];
        let diffs = DMatrix::from_fn(d.max(1) - 1 + 1, d, |i, j| {
            if i + 1 < d {
                points[subset[i + 1]][j] - base[j]
            } else {
                0.0
            }
        });
        let svd = diffs.svd(true, true);
        if let Some(vt) = svd.v_t {
            // The singular vector of the smallest singular value.
            let (idx, _) = svd
                .singular_values
                .iter()
                .enumerate()
                .min_by(|x, y| x.1.total_cmp(y.1))
                .unwrap();
            let second_smallest = svd
                .singular_values
                .iter()
                .enumerate()
                .filter(|(i, _)| *i != idx)
                .map(|(_, s)| *s)
                .fold(f64::INFINITY, f64::min);
            if d == 1 || second_smallest > 1e-9 {
                let normal: Vec<f64> = (0..d).map(|j| vt[(idx, j)]).collect();
                let off = dot(&normal, base);
                let sides: Vec<f64> = points.iter().map(|p| dot(&normal, p) - off).collect();
                let above = sides.iter().all(|s| *s >= -1e-9);
                let below = sides.iter().all(|s| *s <= 1e-9);
                let at_c = dot(&normal, c) - off;
                if (above && at_c < -tol) || (below && at_c > tol) {
                    return false;
                }
            }
        }
        let mut kk = d;
        while kk > 0 && subset[kk - 1] == k - d + kk - 1 {
            kk -= 1;
        }
        if kk == 0 {
            break;
        }
        subset[kk - 1] += 1;
        for l in kk..d {
            subset[l] = subset[l - 1] + 1;
        }
    }
    true
}
