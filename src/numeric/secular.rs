//! Every real root of the secular equation Σᵢ wᵢ / (s − λᵢ)² = 1 (wᵢ ≥ 0), the equation
//! of the feet of the normals from a point to an ellipsoid (Eberly, "Distance from a point
//! to an ellipse, an ellipsoid, or a hyperellipsoid", Geometric Tools, 2013).
//!
//! With the poles λᵢ of positive weight sorted, g(s) = Σ wᵢ / (s − λᵢ)² − 1 rises from −1 to
//! +∞ left of the first pole, falls from +∞ to −1 right of the last, and between two poles
//! is convex with +∞ at both ends: one root on each outer side, and between two poles none
//! or two (one where g only touches 0). So the roots are bracketed, and found by Newton's
//! method kept inside the bracket: between two poles the least of g first, the root of g′
//! (increasing there), and a root on each side of it where g is negative at it.

use smallvec::SmallVec;

/// Steps at most per root (Newton's converge in a few; bisections, each halving the
/// bracket, reach round-off in about 60 from a bracket the width of the poles' spread).
const MAX_STEPS: usize = 200;

/// g's least between two poles within this of 0 (the sum of the terms is 1 there, so this
/// is round-off) is a double root.
const TOUCHING: f64 = 1e-12;

/// The real roots of Σᵢ wᵢ / (s − λᵢ)² = 1 for `poles` λᵢ and `weights` wᵢ ≥ 0, ascending,
/// each to round-off, appended to `roots`. Poles of zero weight are no poles; equal poles
/// act as one of their weights' sum. Where g only touches 0 between two poles (a double
/// root: g's least within round-off of 0), the place of its least is the root. No
/// roots if every weight is zero.
pub(crate) fn secular_roots(poles: &[f64], weights: &[f64], roots: &mut SmallVec<[f64; 16]>) {
    let mut active: SmallVec<[(f64, f64); 8]> = poles
        .iter()
        .zip(weights)
        .filter(|(_, w)| **w > 0.0)
        .map(|(l, w)| (*l, *w))
        .collect();
    if active.is_empty() {
        return;
    }
    active.sort_by(|p, q| p.0.total_cmp(&q.0));
    // Equal poles merged: their terms are one.
    let mut merged: SmallVec<[(f64, f64); 8]> = SmallVec::new();
    for (l, w) in active {
        match merged.last_mut() {
            Some(last) if last.0 == l => last.1 += w,
            _ => merged.push((l, w)),
        }
    }
    // g and its first two derivatives.
    let terms = |s: f64| {
        merged.iter().fold((-1.0, 0.0, 0.0), |(g, d1, d2), (l, w)| {
            let r = 1.0 / (s - l);
            let t = w * r * r;
            (g + t, d1 - 2.0 * t * r, d2 + 6.0 * t * r * r)
        })
    };
    let g = |s: f64| terms(s).0;
    let g_and_slope = |s: f64| {
        let (v, d, _) = terms(s);
        (v, d)
    };
    let slope_and_curvature = |s: f64| {
        let (_, d1, d2) = terms(s);
        (d1, d2)
    };
    // Beyond √(Σ w) of the nearest pole every term is below its share: g < 0 there.
    let reach = merged.iter().map(|(_, w)| w).sum::<f64>().sqrt();
    let (first, last) = (merged[0].0, merged[merged.len() - 1].0);
    let far = |pole: f64, side: f64| {
        let mut s = pole + side * reach * (1.0 + 1e-9);
        while s == pole || g(s) >= 0.0 {
            // Round-off at a reach below the pole's own ulp.
            s = pole + 2.0 * (s - pole) + side * f64::EPSILON * pole.abs().max(f64::MIN_POSITIVE);
        }
        s
    };
    roots.push(solve(&g_and_slope, far(first, -1.0), first));
    for pair in merged.windows(2) {
        let (left, right) = (pair[0].0, pair[1].0);
        // The least of g: where its slope, increasing from −∞ to +∞, is 0.
        let least = solve(&slope_and_curvature, left, right);
        let lowest = g(least);
        if lowest < 0.0 {
            roots.push(solve(&g_and_slope, least, left));
            roots.push(solve(&g_and_slope, least, right));
        } else if lowest <= TOUCHING {
            roots.push(least);
        }
    }
    roots.push(solve(&g_and_slope, far(last, 1.0), last));
}

/// The point of the bracket where `f` changes from below 0 at `below` to above 0 towards
/// `above` (either side), by Newton's method on `f` and its derivative (`f_and_slope`)
/// kept inside the bracket: a step that would leave it, or that would not halve the step
/// before it, is a bisection instead (Numerical Recipes' `rtsafe`). It ends where the step
/// falls to round-off or the bracket to adjacent doubles. An end where `f` is not finite
/// (a pole) is never evaluated.
fn solve(f_and_slope: &impl Fn(f64) -> (f64, f64), mut below: f64, mut above: f64) -> f64 {
    let mut x = 0.5 * (below + above);
    let (mut step, mut step_before) = ((above - below).abs(), (above - below).abs());
    for _ in 0..MAX_STEPS {
        let (value, slope) = f_and_slope(x);
        if value == 0.0 {
            return x;
        }
        if value < 0.0 {
            below = x;
        } else {
            above = x;
        }
        let (low, high) = (below.min(above), below.max(above));
        let newton = x - value / slope;
        let next =
            if newton > low && newton < high && 2.0 * value.abs() < (step_before * slope).abs() {
                newton
            } else {
                0.5 * (below + above)
            };
        step_before = step;
        step = (next - x).abs();
        if next == x || step <= 2.0 * f64::EPSILON * x.abs() {
            return next;
        }
        let mid = 0.5 * (below + above);
        if mid == below || mid == above {
            return below;
        }
        x = next;
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn g(poles: &[f64], weights: &[f64], s: f64) -> f64 {
        poles
            .iter()
            .zip(weights)
            .map(|(l, w)| w / ((s - l) * (s - l)))
            .sum::<f64>()
            - 1.0
    }

    /// Sign changes of g on a fine grid that steps over the poles: a count of the roots
    /// independent of the brackets (double roots excepted, which random weights avoid).
    fn sign_changes(poles: &[f64], weights: &[f64]) -> usize {
        let lo = poles.iter().fold(f64::INFINITY, |m, x| m.min(*x)) - 10.0;
        let hi = poles.iter().fold(f64::NEG_INFINITY, |m, x| m.max(*x)) + 10.0;
        let steps = 2_000_000;
        let mut count = 0;
        let mut last: Option<f64> = None;
        for k in 0..=steps {
            let s = lo + (hi - lo) * k as f64 / steps as f64;
            let v = g(poles, weights, s);
            if !v.is_finite() {
                last = None;
                continue;
            }
            if let Some(p) = last
                && (p < 0.0) != (v < 0.0)
            {
                count += 1;
            }
            last = Some(v);
        }
        count
    }

    /// Random poles and weights in 1 … 6 terms: as many roots as a fine grid finds sign
    /// changes, each a root to round-off (g changes sign across it), ascending.
    #[test]
    fn finds_every_root_of_random_secular_equations() {
        let mut r = ChaCha8Rng::seed_from_u64(5);
        let mut checked = 0;
        for _ in 0..200 {
            let m = r.gen_range(1..=6);
            let poles: Vec<f64> = (0..m).map(|_| r.gen_range(0.01..4.0)).collect();
            let weights: Vec<f64> = (0..m).map(|_| r.gen_range(0.0..0.5f64).powi(3)).collect();
            let mut roots = SmallVec::new();
            secular_roots(&poles, &weights, &mut roots);
            assert_eq!(
                roots.len(),
                sign_changes(&poles, &weights),
                "{poles:?} {weights:?}"
            );
            for pair in roots.windows(2) {
                assert!(pair[0] <= pair[1]);
            }
            for &s in &roots {
                let step = 4.0 * f64::EPSILON * s.abs().max(1.0);
                let (before, after) =
                    (g(&poles, &weights, s - step), g(&poles, &weights, s + step));
                assert!(before * after <= 0.0, "{s} {before} {after}");
            }
            checked += 1;
        }
        assert_eq!(checked, 200);
    }

    /// The feet of the normals from a point inside an ellipse to it: four for a point near
    /// the centre of a long ellipse, at the closed form's places for a point on an axis.
    #[test]
    fn the_feet_on_an_axis_are_the_closed_form() {
        // Ellipse x²/9 + y² = 1, point (1, 0): poles 9 and 1, weights λ z² = (9, 0).
        // Roots s = 9 ± 3 (feet (±3, 0) seen from the point); the zero weight's pole is
        // no pole, so (x, ±y) with s = 1 is the caller's.
        let mut roots = SmallVec::new();
        secular_roots(&[9.0, 1.0], &[9.0, 0.0], &mut roots);
        assert_eq!(roots.len(), 2);
        assert!((roots[0] - 6.0).abs() < 1e-14 && (roots[1] - 12.0).abs() < 1e-14);
        // Equal poles act as one.
        roots.clear();
        secular_roots(&[2.0, 2.0], &[1.0, 3.0], &mut roots);
        assert_eq!(roots.len(), 2);
        assert!((roots[0] - 0.0).abs() < 1e-15 && (roots[1] - 4.0).abs() < 1e-14);
        roots.clear();
        secular_roots(&[1.0], &[0.0], &mut roots);
        assert!(roots.is_empty());
    }
}
