//! GJK on stack arrays for N = 3 and N = 4: the algorithm of `gjk.rs` step for step (the
//! same first direction, stopping rules and exact simplex sub-algorithm), with every point
//! a `[f64; N]` and the simplex at most five of them, so that the compiler unrolls the
//! loops over coordinates and nothing is sized at run time. [`gjk`](super::gjk::gjk)
//! calls it when N matches; its answers equal the general path's to round-off (the order
//! of some sums differs), which `tests/reliability/narrow_phase.rs` checks over random
//! poses.

use super::gjk::{DEGENERATE, GjkResult, PlacedShape, Simplex, StopRule, TOUCHING, curved};
use super::set_bits;
use crate::dynamics::motion::shape::{ConvexCore, Coords};

/// The simplex's points at most: N + 1 for N ≤ 4.
const SLOTS: usize = 5;

#[inline(always)]
fn dot<const N: usize>(a: &[f64; N], b: &[f64; N]) -> f64 {
    let mut s = 0.0;
    for i in 0..N {
        s += a[i] * b[i];
    }
    s
}

/// The support point of the placed core along the space direction `d`.
#[inline(always)]
fn support<const N: usize>(p: &PlacedShape, d: &[f64; N]) -> [f64; N] {
    let position: &[f64; N] = p.position().try_into().expect("N coordinates");
    if let ConvexCore::Point = p.shape().core() {
        return *position;
    }
    let q = p.rotation();
    let mut own = [0.0; N];
    for i in 0..N {
        for j in 0..N {
            own[j] += q[i * N + j] * d[i];
        }
    }
    let mut s = [0.0; N];
    match p.shape().core() {
        ConvexCore::Cuboid(h) => {
            for j in 0..N {
                s[j] = if own[j] < 0.0 { -h[j] } else { h[j] };
            }
        }
        _ => p.shape().core_support(&own, &mut s),
    }
    let mut out = [0.0; N];
    for i in 0..N {
        let mut x = 0.0;
        for j in 0..N {
            x += q[i * N + j] * s[j];
        }
        out[i] = position[i] + x;
    }
    out
}

/// The simplex: its points w = b − a of K and the support points a, b they came from.
#[derive(Clone, Copy)]
struct Points<const N: usize> {
    count: usize,
    w: [[f64; N]; SLOTS],
    a: [[f64; N]; SLOTS],
    b: [[f64; N]; SLOTS],
    lambda: [f64; SLOTS],
}

/// The nearest point found so far: the face (bit mask), its weights by point, the point.
struct Best<const N: usize> {
    mask: u32,
    lambda: [f64; SLOTS],
    v: [f64; N],
    vv: f64,
}

/// The projection of the origin onto the affine hull of the face `mask` of `points`: the
/// barycentric weights (by point index) and the point; None if the face is degenerate.
/// As `project_onto_face` of `gjk.rs`: Gram–Schmidt twice, then back substitution.
#[inline(always)]
fn project<const N: usize>(
    points: &[[f64; N]; SLOTS],
    mask: u32,
) -> Option<([f64; SLOTS], [f64; N])> {
    let (index, m) = set_bits::<SLOTS>(mask);
    let m1 = m - 1;
    let y0 = &points[index[0]];
    let mut q = [[0.0; N]; SLOTS - 1];
    let mut r = [[0.0; SLOTS - 1]; SLOTS - 1];
    for j in 0..m1 {
        let yj = &points[index[j + 1]];
        let mut e = [0.0; N];
        for k in 0..N {
            e[k] = yj[k] - y0[k];
        }
        let length = dot(&e, &e).sqrt();
        for _ in 0..2 {
            for l in 0..j {
                let c = dot(&q[l], &e);
                r[l][j] += c;
                for k in 0..N {
                    e[k] -= c * q[l][k];
                }
            }
        }
        let rjj = dot(&e, &e).sqrt();
        if rjj.is_nan() || rjj <= DEGENERATE * length {
            return None;
        }
        r[j][j] = rjj;
        for k in 0..N {
            q[j][k] = e[k] / rjj;
        }
    }
    let mut c = [0.0; SLOTS - 1];
    for j in 0..m1 {
        c[j] = -dot(&q[j], y0);
    }
    let mut v = *y0;
    for j in 0..m1 {
        for k in 0..N {
            v[k] += c[j] * q[j][k];
        }
    }
    for j in (0..m1).rev() {
        let mut s = c[j];
        for l in j + 1..m1 {
            s -= r[j][l] * c[l];
        }
        c[j] = s / r[j][j];
    }
    let mut lambda = [0.0; SLOTS];
    lambda[index[0]] = 1.0 - c[..m1].iter().sum::<f64>();
    for j in 0..m1 {
        lambda[index[j + 1]] = c[j];
    }
    Some((lambda, v))
}

/// The search of `gjk.rs`'s `search` over the faces of the simplex: a face whose
/// projection has all weights > 0 is a candidate, else the facets opposite the vertices of
/// weight ≤ 0 are searched (all facets of a degenerate face).
fn search<const N: usize>(
    points: &[[f64; N]; SLOTS],
    mask: u32,
    best: &mut Best<N>,
    visited: &mut u32,
) {
    if *visited >> mask & 1 == 1 {
        return;
    }
    *visited |= 1 << mask;
    if mask.count_ones() == 1 {
        let i = mask.trailing_zeros() as usize;
        let vv = dot(&points[i], &points[i]);
        if vv < best.vv {
            best.mask = mask;
            best.lambda = [0.0; SLOTS];
            best.lambda[i] = 1.0;
            best.v = points[i];
            best.vv = vv;
        }
        return;
    }
    match project(points, mask) {
        None => {
            for i in 0..SLOTS {
                if mask >> i & 1 == 1 {
                    search(points, mask & !(1 << i), best, visited);
                }
            }
        }
        Some((lambda, v)) => {
            let inside = (0..SLOTS).all(|i| mask >> i & 1 == 0 || lambda[i] > 0.0);
            if inside {
                let vv = dot(&v, &v);
                if vv < best.vv {
                    best.mask = mask;
                    best.lambda = lambda;
                    best.v = v;
                    best.vv = vv;
                }
                return;
            }
            for (i, l) in lambda.iter().enumerate() {
                if mask >> i & 1 == 1 && *l <= 0.0 {
                    search(points, mask & !(1 << i), best, visited);
                }
            }
        }
    }
}

/// GJK on the cores of `a` and `b`, both of dimension N (3 or 4): the same iterations as
/// the general `gjk`, on arrays.
pub(crate) fn gjk_fixed<const N: usize>(a: &PlacedShape, b: &PlacedShape) -> GjkResult {
    debug_assert!(N < SLOTS && a.shape().dim() == N && b.shape().dim() == N);
    let pa: &[f64; N] = a.position().try_into().expect("N coordinates");
    let pb: &[f64; N] = b.position().try_into().expect("N coordinates");
    let mut d = [0.0; N];
    for i in 0..N {
        d[i] = pb[i] - pa[i];
    }
    let centres = dot(&d, &d).sqrt();
    let scale = a.shape().core_radius() + b.shape().core_radius() + centres;
    let touching = TOUCHING * scale;
    if centres == 0.0 {
        d[0] = 1.0;
    }
    let support_difference = |d: &[f64; N]| {
        let mut minus = *d;
        for x in minus.iter_mut() {
            *x = -*x;
        }
        let sa = support(a, &minus);
        let sb = support(b, d);
        let mut w = [0.0; N];
        for i in 0..N {
            w[i] = sb[i] - sa[i];
        }
        (w, sa, sb)
    };
    let mut simplex = Points {
        count: 1,
        w: [[0.0; N]; SLOTS],
        a: [[0.0; N]; SLOTS],
        b: [[0.0; N]; SLOTS],
        lambda: [0.0; SLOTS],
    };
    for x in d.iter_mut() {
        *x = -*x;
    }
    let (w, sa, sb) = support_difference(&d);
    (simplex.w[0], simplex.a[0], simplex.b[0]) = (w, sa, sb);
    simplex.lambda[0] = 1.0;
    let mut v = w;
    let mut vv = dot(&v, &v);
    let mut iterations = 0;
    let mut intersecting = false;
    let mut rule = StopRule::new(curved(a, b), scale);
    let mut certified = true;
    loop {
        if vv.sqrt() <= touching {
            intersecting = true;
            break;
        }
        if !rule.may_continue(iterations) {
            certified = rule.certified(vv);
            break;
        }
        iterations += 1;
        for i in 0..N {
            d[i] = -v[i];
        }
        let (w, sa, sb) = support_difference(&d);
        let vw = dot(&v, &w);
        if rule.closed(iterations, vv, vw) {
            break;
        }
        let repeated = (0..simplex.count)
            .any(|k| (0..N).all(|i| (simplex.w[k][i] - w[i]).abs() <= 1e-15 * scale));
        if repeated {
            certified = rule.certified_when_stuck(vv, vw);
            break;
        }
        let mut next = simplex;
        let k = next.count;
        (next.w[k], next.a[k], next.b[k]) = (w, sa, sb);
        next.count += 1;
        let mut best = Best {
            mask: 0,
            lambda: [0.0; SLOTS],
            v: [0.0; N],
            vv: f64::INFINITY,
        };
        let mut visited = 0u32;
        search(&next.w, (1 << next.count) - 1, &mut best, &mut visited);
        if best.vv >= vv {
            // The new point did not bring the simplex nearer; keep the old one.
            certified = rule.certified_when_no_nearer(vv, vw);
            break;
        }
        let full = best.mask.count_ones() as usize == N + 1;
        // Keep the points of the face, in order, with their weights.
        let mut kept = 0;
        for i in 0..next.count {
            if best.mask >> i & 1 == 1 {
                next.w[kept] = next.w[i];
                next.a[kept] = next.a[i];
                next.b[kept] = next.b[i];
                next.lambda[kept] = best.lambda[i];
                kept += 1;
            }
        }
        next.count = kept;
        simplex = next;
        v = best.v;
        vv = best.vv;
        if full {
            intersecting = true;
            break;
        }
    }
    if vv.sqrt() <= touching {
        intersecting = true;
    }
    if !intersecting && rule.undecided_contact(vv) {
        intersecting = true;
    }
    let mut general = Simplex::new(N);
    for k in 0..simplex.count {
        general.push(&simplex.w[k], &simplex.a[k], &simplex.b[k]);
        general.lambda[k] = simplex.lambda[k];
    }
    GjkResult {
        simplex: general,
        v: Coords::from_slice(&v),
        vv,
        intersecting,
        iterations,
        certified,
        scale,
        undecided: !intersecting && rule.stuck_beside_origin(vv),
        stalled: !intersecting && rule.stalled_beside_origin(),
    }
}
