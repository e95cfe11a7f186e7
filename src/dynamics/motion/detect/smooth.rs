//! The exact depth of two overlapping shapes whose cores are smooth: an ellipsoid against
//! an ellipsoid or a point (a ball, whose margin [`super::Penetration`] adds).
//!
//! The depth is the shortest translation that separates the shapes: the least, over unit
//! directions u from A to B, of f(u) = h_A(u) + h_B(−u), where h is a core's support
//! function. For an ellipsoid with centre c, rotation Q and semi-axes a,
//! h(d) = c·d + √(dᵀ M d) with M = Q diag(a²) Qᵀ, smooth and convex: its gradient is the
//! support point s(d) = c + M d / √(dᵀ M d), and its Hessian M/s − (M d)(M d)ᵀ/s³ (radii
//! of curvature of the surface on the plane orthogonal to d). EPA approximates a curved
//! surface by facets only to the square of their width, so its normal on an ellipsoid is
//! inexact; Newton's method on the sphere of directions, started from it, converges to the
//! minimum quadratically. At the minimum u* the support points' difference
//! s_A(u*) − s_B(−u*) is f(u*) u*: the witnesses of the contact.

use super::gjk::PlacedShape;
use crate::dynamics::motion::shape::{ConvexCore, Coords};
use crate::numeric::cholesky_solve;
use crate::numeric::dense::dot;
use crate::numeric::eigen::jacobi_eigen;
use smallvec::SmallVec;

/// Newton steps at most (it takes about five from EPA's normal).
const MAX_NEWTON_STEPS: usize = 64;
/// Halvings of a Newton step at most, while f does not decrease along it.
const MAX_HALVINGS: usize = 40;
/// The step stops when the gradient's part along the sphere is this small, relative to
/// the size of the pair (the round-off of f).
const CONVERGED: f64 = 1e-14;
/// A minimum within this fraction of the pair's size of EPA's lower bound is the least.
const CERTIFIED: f64 = 1e-9;

/// A smooth core, placed: its centre, rotation and squared semi-axes (none for a point).
struct SmoothCore<'a> {
    centre: &'a [f64],
    rotation: &'a [f64],
    squared_axes: Option<Coords>,
}

impl<'a> SmoothCore<'a> {
    /// The core of `shape` if it is smooth (a point or an ellipsoid).
    fn of(shape: &PlacedShape<'a>) -> Option<Self> {
        let squared_axes = match shape.shape().core() {
            ConvexCore::Point => None,
            ConvexCore::Ellipsoid(a) => Some(a.iter().map(|x| x * x).collect()),
            _ => return None,
        };
        Some(SmoothCore {
            centre: shape.position(),
            rotation: shape.rotation(),
            squared_axes,
        })
    }

    /// The largest semi-axis (0 for a point).
    fn radius(&self) -> f64 {
        self.squared_axes
            .as_ref()
            .map_or(0.0, |a| a.iter().fold(0.0f64, |m, x| m.max(*x)).sqrt())
    }

    /// h(σ u), with the support point s(σ u) in `support` and σ times the Hessian of h at
    /// σ u added to `hessian` (n × n, row-major) if given.
    fn support(&self, u: &[f64], sigma: f64, support: &mut [f64], hessian: Option<&mut [f64]>) {
        let n = u.len();
        support.copy_from_slice(self.centre);
        let Some(a2) = &self.squared_axes else {
            return;
        };
        let q = self.rotation;
        // t = diag(a²) Qᵀ d, s = √(dᵀ M d), m = Q t = M d (d = σ u).
        let mut t = Coords::from_elem(0.0, n);
        for (i, ui) in u.iter().enumerate() {
            for (tk, qik) in t.iter_mut().zip(&q[i * n..(i + 1) * n]) {
                *tk += sigma * qik * ui;
            }
        }
        let mut s2 = 0.0;
        for (tk, a2k) in t.iter_mut().zip(a2) {
            s2 += *tk * *tk * a2k;
            *tk *= a2k;
        }
        let s = s2.sqrt();
        let mut m = Coords::from_elem(0.0, n);
        for (i, mi) in m.iter_mut().enumerate() {
            *mi = dot(&q[i * n..(i + 1) * n], &t);
        }
        for (p, mi) in support.iter_mut().zip(&m) {
            *p += mi / s;
        }
        if let Some(h) = hessian {
            // The Hessian of h is even in d, and the chain rule's two factors σ cancel.
            let s3 = s * s2;
            for i in 0..n {
                for j in 0..n {
                    let qq: f64 = (0..n).map(|k| q[i * n + k] * q[j * n + k] * a2[k]).sum();
                    h[i * n + j] += qq / s - m[i] * m[j] / s3;
                }
            }
        }
    }
}

/// The refined contact of two overlapping smooth cores: depth, unit normal from A to B,
/// and the witnesses s_A(u), s_B(−u).
pub(super) struct SmoothContact {
    pub depth: f64,
    pub normal: Coords,
    pub witness_a: Coords,
    pub witness_b: Coords,
}

/// f(u), its gradient s_A(u) − s_B(−u) in `gradient` and, if asked, its Hessian (the
/// support points in `sa`, `sb`).
fn evaluate(
    (a, b): (&SmoothCore, &SmoothCore),
    u: &[f64],
    (sa, sb, gradient): (&mut [f64], &mut [f64], &mut [f64]),
    mut hessian: Option<&mut [f64]>,
) -> f64 {
    if let Some(h) = hessian.as_deref_mut() {
        h.fill(0.0);
    }
    a.support(u, 1.0, sa, hessian.as_deref_mut());
    b.support(u, -1.0, sb, hessian);
    for ((g, x), y) in gradient.iter_mut().zip(sa.iter()).zip(sb.iter()) {
        *g = x - y;
    }
    dot(gradient, u)
}

/// The depth of the overlapping shapes `a` and `b` if both cores are smooth and one is an
/// ellipsoid (else None): Newton's method on the sphere of directions ([`newton`]) from
/// `start`, EPA's unit normal from A to B. `lower` is EPA's depth, a lower bound (its
/// polytope is inscribed in A − B): when the minimum found lies more than 1e-9 of the
/// pair's size above it, another minimum may lie below, and Newton also starts from the
/// direction between the centres and both ways along each ellipsoid's axes, the least
/// minimum taken.
pub(super) fn smooth_depth(
    a: &PlacedShape,
    b: &PlacedShape,
    start: &[f64],
    lower: f64,
) -> Option<SmoothContact> {
    let (ca, cb) = (SmoothCore::of(a)?, SmoothCore::of(b)?);
    if ca.squared_axes.is_none() && cb.squared_axes.is_none() {
        return None;
    }
    let n = start.len();
    let between: Coords = cb
        .centre
        .iter()
        .zip(ca.centre)
        .map(|(x, y)| x - y)
        .collect();
    let size = dot(&between, &between).sqrt() + ca.radius() + cb.radius();
    let cores = (&ca, &cb);
    let mut best = newton(cores, start, size);
    if best.depth - lower <= CERTIFIED * size {
        return Some(best);
    }
    let mut consider = |u: &[f64]| {
        let found = newton(cores, u, size);
        if found.depth < best.depth {
            best = found;
        }
    };
    consider(&between);
    let mut axis = Coords::from_elem(0.0, n);
    for core in [&ca, &cb] {
        if core.squared_axes.is_some() {
            for k in 0..n {
                for sign in [1.0, -1.0] {
                    for (i, x) in axis.iter_mut().enumerate() {
                        *x = sign * core.rotation[i * n + k];
                    }
                    consider(&axis);
                }
            }
        }
    }
    Some(best)
}

/// Newton's method on the unit sphere for the least f(u) = h_A(u) + h_B(−u) near `start`.
/// Each step solves the Riemannian Newton system (P ∇²f P − f P) ξ = −P ∇f on the tangent
/// plane (P = I − u uᵀ); where that Hessian is not positive definite (near a saddle of f,
/// such as the end of an ellipsoid's middle axis) the step takes its eigenvalues' absolute
/// values instead and, at the saddle itself, moves along the direction of negative
/// curvature. ξ is halved until f decreases: the result separates the shapes by no more
/// than `start` does, to round-off.
fn newton(cores: (&SmoothCore, &SmoothCore), start: &[f64], size: f64) -> SmoothContact {
    let n = start.len();
    let zeros = || Coords::from_elem(0.0, n);
    let (mut sa, mut sb, mut g) = (zeros(), zeros(), zeros());
    let square = || -> SmallVec<[f64; 64]> { SmallVec::from_elem(0.0, n * n) };
    let (mut hessian, mut system, mut vectors) = (square(), square(), square());
    let (mut xi, mut trial, mut hu) = (zeros(), zeros(), zeros());
    let (mut ta, mut tb, mut tg) = (zeros(), zeros(), zeros());
    let mut u: Coords = start.iter().copied().collect();
    let length = dot(&u, &u).sqrt();
    if length.is_nan() || length <= 0.0 {
        u.fill(0.0);
        u[0] = 1.0;
    } else {
        u.iter_mut().for_each(|x| *x /= length);
    }
    let mut f = evaluate(cores, &u, (&mut sa, &mut sb, &mut g), Some(&mut hessian));
    let mut steps = 0;
    while steps < MAX_NEWTON_STEPS {
        // The gradient along the sphere, r = P ∇f = ∇f − f u (u·∇f = f: h is of degree 1).
        let mut residual = 0.0;
        for ((x, gi), ui) in xi.iter_mut().zip(&g).zip(&u) {
            *x = -(gi - f * ui);
            residual += *x * *x;
        }
        let residual = residual.sqrt();
        // P H' P + u uᵀ with H' = ∇²f − f I, which is
        // H' − u (H'u)ᵀ − (H'u) uᵀ + (uᵀH'u) u uᵀ + u uᵀ: on the tangent plane the
        // Riemannian Hessian, along u the identity, so that ξ stays orthogonal to u.
        for (i, x) in hu.iter_mut().enumerate() {
            *x = dot(&hessian[i * n..(i + 1) * n], &u) - f * u[i];
        }
        let uhu = dot(&u, &hu);
        let fill = |system: &mut [f64]| {
            for i in 0..n {
                for j in 0..n {
                    let diagonal = if i == j { f } else { 0.0 };
                    system[i * n + j] = hessian[i * n + j] - diagonal - u[i] * hu[j] - hu[i] * u[j]
                        + (uhu + 1.0) * u[i] * u[j];
                }
            }
        };
        fill(&mut system);
        trial.copy_from_slice(&xi);
        if !cholesky_solve(&mut system, n, &mut trial) {
            fill(&mut system);
            jacobi_eigen(&mut system, n, &mut vectors);
            trial.fill(0.0);
            let (mut least, mut at) = (f64::INFINITY, 0);
            for k in 0..n {
                let value = system[k * n + k];
                let along: f64 = (0..n).map(|i| vectors[i * n + k] * xi[i]).sum();
                let scale = along / value.abs().max(1e-9 * size);
                for (t, i) in trial.iter_mut().zip(0..n) {
                    *t += scale * vectors[i * n + k];
                }
                if value < least {
                    (least, at) = (value, k);
                }
            }
            if least < 0.0 && residual <= 1e-8 * size {
                // At a saddle: half a radian along the negative curvature, downhill.
                let along: f64 = (0..n).map(|i| vectors[i * n + at] * xi[i]).sum();
                let sign = if along < 0.0 { -0.5 } else { 0.5 };
                for (t, i) in trial.iter_mut().zip(0..n) {
                    *t = sign * vectors[i * n + at];
                }
            } else if residual <= CONVERGED * size {
                break;
            }
        } else if residual <= CONVERGED * size {
            break;
        }
        std::mem::swap(&mut xi, &mut trial);
        // Halve the step until f decreases.
        let mut scale = 1.0;
        let mut taken = false;
        for _ in 0..MAX_HALVINGS {
            for ((t, ui), x) in trial.iter_mut().zip(&u).zip(&xi) {
                *t = ui + scale * x;
            }
            let l = dot(&trial, &trial).sqrt();
            trial.iter_mut().for_each(|x| *x /= l);
            let ft = evaluate(cores, &trial, (&mut ta, &mut tb, &mut tg), None);
            // A full step near the minimum changes f by less than its round-off.
            if ft < f || (scale == 1.0 && ft <= f + 4.0 * f64::EPSILON * size) {
                taken = true;
                break;
            }
            scale *= 0.5;
        }
        if !taken {
            break;
        }
        steps += 1;
        std::mem::swap(&mut u, &mut trial);
        f = evaluate(cores, &u, (&mut sa, &mut sb, &mut g), Some(&mut hessian));
    }
    SmoothContact {
        depth: f,
        normal: u,
        witness_a: sa,
        witness_b: sb,
    }
}

#[cfg(test)]
mod tests {
    use super::super::{EpaWorkspace, PlacedShape, penetration_with};
    use crate::algebra::Bivector;
    use crate::dynamics::Attitude;
    use crate::dynamics::motion::shape::ConvexShape;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A random rotation (row-major, own axes → space) in `n` dimensions.
    fn rotation(r: &mut ChaCha8Rng, n: usize) -> Vec<f64> {
        let turn: Vec<f64> = (0..n * (n - 1) / 2)
            .map(|_| r.gen_range(-3.0..3.0))
            .collect();
        let attitude =
            Attitude::identity(n).times_exp(&Bivector::from_components(n, &turn).unwrap());
        attitude.to_matrix().transpose().as_slice().to_vec()
    }

    /// A ball whose centre lies inside an ellipsoid on its shortest axis, at δ from the
    /// centre, leaves through the end of that axis: depth a_min − |δ| + r (the surface's
    /// radii of curvature there, a_j²/a_min, all exceed a_min), N = 2 … 6, either way
    /// round, through the whole query (GJK, EPA, then Newton).
    #[test]
    fn a_ball_on_the_shortest_axis_of_an_ellipsoid_leaves_through_its_end() {
        let mut r = ChaCha8Rng::seed_from_u64(5);
        let mut workspace = EpaWorkspace::new();
        let mut cases = 0;
        for n in 2..=6usize {
            for _ in 0..200 {
                let mut axes: Vec<f64> = (0..n).map(|_| r.gen_range(0.3..2.0)).collect();
                let shortest = r.gen_range(0..n);
                axes[shortest] = 0.2;
                let ellipsoid = ConvexShape::ellipsoid(&axes).unwrap();
                let radius = r.gen_range(0.05..1.0);
                let ball = ConvexShape::ball(n, radius).unwrap();
                let q = rotation(&mut r, n);
                let centre: Vec<f64> = (0..n).map(|_| r.gen_range(-1.0..1.0)).collect();
                let delta = r.gen_range(0.01..0.18) * if r.gen_bool(0.5) { 1.0 } else { -1.0 };
                let axis: Vec<f64> = (0..n).map(|i| q[i * n + shortest]).collect();
                let inside: Vec<f64> = centre
                    .iter()
                    .zip(&axis)
                    .map(|(c, e)| c + delta * e)
                    .collect();
                let expected = 0.2 - delta.abs() + radius;
                let a = PlacedShape::new(&ellipsoid, &centre, &q).unwrap();
                let b = PlacedShape::new(&ball, &inside, &q).unwrap();
                for (swapped, p) in [
                    (false, penetration_with(&mut workspace, &a, &b).unwrap()),
                    (true, penetration_with(&mut workspace, &b, &a).unwrap()),
                ] {
                    assert!(
                        (p.depth - expected).abs() < 1e-12,
                        "N = {n}: {} against {expected}",
                        p.depth
                    );
                    let sign = if swapped {
                        -delta.signum()
                    } else {
                        delta.signum()
                    };
                    for (m, e) in p.normal.as_slice().iter().zip(&axis) {
                        assert!((m - sign * e).abs() < 1e-7, "N = {n}: normal");
                    }
                    let (wa, wb) = (p.witness_a.as_slice(), p.witness_b.as_slice());
                    for i in 0..n {
                        let gap = wa[i] - wb[i] - p.depth * p.normal.as_slice()[i];
                        assert!(gap.abs() < 1e-12, "N = {n}: witnesses {gap:e}");
                    }
                    cases += 1;
                }
            }
        }
        assert_eq!(cases, 2000);
    }

    /// The translation of B along u that separates two ellipses, h_A(u) + h_B(−u), from
    /// the support function's closed form h(d) = c·d + |diag(a) Qᵀ d|.
    fn translation(e: [(&[f64], &[f64], &[f64]); 2], u: [f64; 2]) -> f64 {
        let h = |(c, q, a): (&[f64], &[f64], &[f64]), d: [f64; 2]| {
            let own = [q[0] * d[0] + q[2] * d[1], q[1] * d[0] + q[3] * d[1]];
            c[0] * d[0] + c[1] * d[1] + ((a[0] * own[0]).powi(2) + (a[1] * own[1]).powi(2)).sqrt()
        };
        h(e[0], u) + h(e[1], [-u[0], -u[1]])
    }

    /// Overlapping ellipses: the depth is the least translation over directions, found by
    /// brute force (the best of 3,600 angles, narrowed by golden sections around the best
    /// ten), to 1e-10 of the pair's size.
    #[test]
    fn overlapping_ellipses_take_the_least_translation_over_all_angles() {
        let mut r = ChaCha8Rng::seed_from_u64(9);
        let mut workspace = EpaWorkspace::new();
        let mut overlapping = 0;
        for _ in 0..400 {
            let axes: Vec<[f64; 2]> = (0..2)
                .map(|_| [r.gen_range(0.1..2.0), r.gen_range(0.1..2.0)])
                .collect();
            let shapes: Vec<ConvexShape> = axes
                .iter()
                .map(|a| ConvexShape::ellipsoid(a).unwrap())
                .collect();
            let q = [rotation(&mut r, 2), rotation(&mut r, 2)];
            let c = [[0.0, 0.0], [r.gen_range(-1.5..1.5), r.gen_range(-1.5..1.5)]];
            let a = PlacedShape::new(&shapes[0], &c[0], &q[0]).unwrap();
            let b = PlacedShape::new(&shapes[1], &c[1], &q[1]).unwrap();
            let p = penetration_with(&mut workspace, &a, &b).unwrap();
            if p.depth <= 0.0 {
                continue;
            }
            overlapping += 1;
            let pair = [
                (&c[0][..], &q[0][..], &axes[0][..]),
                (&c[1][..], &q[1][..], &axes[1][..]),
            ];
            let f = |t: f64| translation(pair, [t.cos(), t.sin()]);
            let step = std::f64::consts::TAU / 3600.0;
            let mut angles: Vec<f64> = (0..3600).map(|k| k as f64 * step).collect();
            angles.sort_by(|x, y| f(*x).total_cmp(&f(*y)));
            let mut best = f64::INFINITY;
            for &t in &angles[..10] {
                let (mut lo, mut hi) = (t - step, t + step);
                let g = (5f64.sqrt() - 1.0) / 2.0;
                for _ in 0..80 {
                    let (x, y) = (hi - g * (hi - lo), lo + g * (hi - lo));
                    if f(x) < f(y) {
                        hi = y;
                    } else {
                        lo = x;
                    }
                }
                best = best.min(f(0.5 * (lo + hi)));
            }
            let size = 4.0 + c[1][0].hypot(c[1][1]);
            assert!(
                (p.depth - best).abs() < 1e-10 * size,
                "{} against {best}",
                p.depth
            );
        }
        assert!(overlapping > 200, "{overlapping} overlapping pairs");
    }
}
