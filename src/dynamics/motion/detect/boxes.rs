//! The distance between two boxes in 3 and 4 dimensions, solved as the bounded
//! least-squares problem it is rather than by GJK.
//!
//! In the frame of box A (half-lengths a, centred at the origin), box B (half-lengths b)
//! has centre c = Q_Aᵀ(p_B − p_A) and axes R = Q_Aᵀ Q_B. A point of A is x with |xᵢ| ≤ aᵢ,
//! a point of B is c + R u with |uⱼ| ≤ bⱼ, and the distance is the least |e| over both,
//! e = c + R u − x: a least-squares problem in 2N variables, each between two bounds. It is
//! solved by the active-set method of Lawson and Hanson ("Solving Least Squares Problems",
//! 1974, ch. 23) with bounds on both sides (Stark and Parker, "Bounded-variable least
//! squares", Comput. Stat. 10, 1995): start at a corner of B and the point of A nearest
//! it, free the variable whose gradient most wants it off its bound, solve the
//! least-squares problem in the free variables, and step back to the first bound met if the
//! solution leaves the box. A free xᵢ zeroes eᵢ, so only the free u need a solve: an
//! L D Lᵀ factorisation of at most N × N, or with one free u (the common case) a division.
//!
//! The answer is then certified the way GJK stops: along v = e (from A to B), the support
//! points give the lower bound v·w / |v| of the distance, and the answer stands only if
//! |v|² − v·w is within GJK's relative gap of |v|² (plus the round-off of e, a few units in
//! the last place of the problem's size, times that size), or if |v| is at GJK's contact
//! tolerance (e joins a point of A to a point of B). Anything else (a near-singular solve
//! on nearly parallel features, more than 4N steps) returns None, and the caller runs GJK:
//! the fast path answers only what passes GJK's own stopping rule.

// Loops over 0..N index several arrays at once, as the formulas do; N is a constant, so
// the compiler unrolls them.
#![allow(clippy::needless_range_loop)]

use super::gjk::{CoreGap, PlacedShape, RELATIVE_GAP, TOUCHING};
use super::set_bits;
use crate::dynamics::motion::shape::ConvexCore;

/// The nearest points of two boxes' cores, in space: the witnesses, v = witness_b −
/// witness_a, |v|², whether they touch or overlap, and the least-squares steps taken.
pub(crate) struct BoxGap<const N: usize> {
    pub witness_a: [f64; N],
    pub witness_b: [f64; N],
    pub v: [f64; N],
    pub vv: f64,
    pub intersecting: bool,
    pub steps: usize,
}

/// A free variable's least-squares pivot below this (the squared sine of the angle between
/// its column and the others') makes the solve singular: the caller runs GJK instead.
const PIVOT: f64 = 1e-20;

/// Σ tᵢ pairwise, (t₀ + t₁) + (t₂ + t₃): the solve is a chain of such sums, each waiting
/// for the last, and pairs halve its depth.
#[inline(always)]
fn sum<const N: usize>(mut t: [f64; N]) -> f64 {
    let mut width = 1;
    while width < N {
        let mut i = 0;
        while i + width < N {
            t[i] += t[i + width];
            i += 2 * width;
        }
        width *= 2;
    }
    t[0]
}

#[inline(always)]
fn dot<const N: usize>(a: &[f64; N], b: &[f64; N]) -> f64 {
    let mut t = [0.0; N];
    for i in 0..N {
        t[i] = a[i] * b[i];
    }
    sum(t)
}

/// The bounded least-squares problem in A's frame.
struct Problem<const N: usize> {
    /// A's half-lengths.
    a: [f64; N],
    /// B's half-lengths.
    b: [f64; N],
    /// B's centre.
    c: [f64; N],
    /// B's axes, `r[i][j]` = (Q_Aᵀ Q_B)ᵢⱼ.
    r: [[f64; N]; N],
}

impl<const N: usize> Problem<N> {
    /// e = c + R u − x: from the point x of A to the point c + R u of B.
    #[inline(always)]
    fn gap(&self, x: &[f64; N], u: &[f64; N]) -> [f64; N] {
        let mut e = [0.0; N];
        for i in 0..N {
            e[i] = self.c[i] - x[i] + dot(&self.r[i], u);
        }
        e
    }

    /// Rᵀ e.
    #[inline(always)]
    fn turned_back(&self, e: &[f64; N]) -> [f64; N] {
        let mut g = [0.0; N];
        for j in 0..N {
            let mut t = [0.0; N];
            for i in 0..N {
                t[i] = self.r[i][j] * e[i];
            }
            g[j] = sum(t);
        }
        g
    }

    /// The least-squares point with the variables outside `free_x` and `free_u` held at
    /// their values, from the point (x, u) with gap e: the move δ of the free u by the
    /// normal equations over the rows whose x is held (there e + R δ is what remains),
    /// then each free xᵢ where it zeroes eᵢ. None if the free columns are (nearly)
    /// dependent.
    #[inline(always)]
    fn solve(
        &self,
        x: &[f64; N],
        u: &[f64; N],
        e: &[f64; N],
        free_x: u32,
        free_u: u32,
    ) -> Option<([f64; N], [f64; N])> {
        let (cols, k) = set_bits::<N>(free_u);
        let mut delta = [0.0; N];
        if k == 1 {
            // One free column c, the common case: δ = −Σ rᵢ꜀ eᵢ / Σ rᵢ꜀² over the held rows,
            // as the factorisation below gives it.
            let c = cols[0];
            let (mut m, mut rhs) = (0.0, 0.0);
            for i in 0..N {
                if free_x >> i & 1 == 0 {
                    m += self.r[i][c] * self.r[i][c];
                    rhs -= self.r[i][c] * e[i];
                }
            }
            if m.is_nan() || m <= PIVOT {
                return None;
            }
            delta[c] = rhs * (1.0 / m);
        } else if k > 1 {
            let mut m = [[0.0; N]; N];
            let mut rhs = [0.0; N];
            for i in 0..N {
                if free_x >> i & 1 == 0 {
                    let row = &self.r[i];
                    for p in 0..k {
                        let rp = row[cols[p]];
                        for q in 0..=p {
                            m[p][q] += rp * row[cols[q]];
                        }
                        rhs[p] -= rp * e[i];
                    }
                }
            }
            // M = L D Lᵀ, L unit lower triangular below the diagonal of m and D on it: no
            // square roots, and each pivot inverted once. The columns of R have unit
            // length, so the pivots D are squared sines against the earlier columns.
            let mut inv = [0.0; N];
            for p in 0..k {
                for q in 0..p {
                    let mut s = m[p][q];
                    for l in 0..q {
                        s -= m[p][l] * m[q][l] * m[l][l];
                    }
                    m[p][q] = s * inv[q];
                }
                let mut s = m[p][p];
                for l in 0..p {
                    s -= m[p][l] * m[p][l] * m[l][l];
                }
                if s.is_nan() || s <= PIVOT {
                    return None;
                }
                m[p][p] = s;
                inv[p] = 1.0 / s;
            }
            // L y = rhs, then Lᵀ δ = D⁻¹ y.
            for p in 0..k {
                let mut s = rhs[p];
                for l in 0..p {
                    s -= m[p][l] * rhs[l];
                }
                rhs[p] = s;
            }
            for p in (0..k).rev() {
                let mut s = rhs[p] * inv[p];
                for l in p + 1..k {
                    s -= m[l][p] * rhs[l];
                }
                rhs[p] = s;
            }
            for p in 0..k {
                delta[cols[p]] = rhs[p];
            }
        }
        let mut w = *u;
        for j in 0..N {
            w[j] += delta[j];
        }
        let mut y = *x;
        for i in 0..N {
            if free_x >> i & 1 == 1 {
                let mut s = x[i] + e[i];
                for p in 0..k {
                    s += self.r[i][cols[p]] * delta[cols[p]];
                }
                y[i] = s;
            }
        }
        Some((y, w))
    }
}

/// `x` clamped to [−h, h] by plain comparisons (f64::clamp and min/max pay for NaN
/// rules; a NaN here fails the certificate at the end).
#[inline(always)]
pub(super) fn within(x: f64, h: f64) -> f64 {
    if x > h {
        h
    } else if x < -h {
        -h
    } else {
        x
    }
}

/// The fraction of the way from `z` to `trial`, at most `alpha`, that keeps the free
/// variables within their bounds ±`h`.
#[inline(always)]
fn step<const N: usize>(
    z: &[f64; N],
    trial: &[f64; N],
    h: &[f64; N],
    free: u32,
    alpha: f64,
) -> f64 {
    let mut alpha = alpha;
    for i in 0..N {
        if free >> i & 1 == 1 && trial[i].abs() > h[i] {
            let bound = h[i].copysign(trial[i]);
            let fraction = (bound - z[i]) / (trial[i] - z[i]);
            // Plain comparisons rather than f64::min and max, whose NaN rules cost a
            // handful of instructions each: a NaN fraction counts as 0, as before.
            let fraction = if fraction > 0.0 { fraction } else { 0.0 };
            if fraction < alpha {
                alpha = fraction;
            }
        }
    }
    alpha
}

/// Moves the free variables of `z` the fraction `alpha` of the way to `trial` and holds
/// at its bound each one that reaches it.
#[inline(always)]
fn apply<const N: usize>(
    z: &mut [f64; N],
    trial: &[f64; N],
    h: &[f64; N],
    free: &mut u32,
    alpha: f64,
) {
    for i in 0..N {
        if *free >> i & 1 == 1 {
            let moved = z[i] + alpha * (trial[i] - z[i]);
            if alpha < 1.0 && moved.abs() >= h[i] * (1.0 - 1e-15) {
                z[i] = h[i].copysign(moved);
                *free &= !(1 << i);
            } else {
                z[i] = within(moved, h[i]);
            }
        }
    }
}

/// The nearest points of the cores of two placed cuboids of dimension N by bounded least
/// squares; None if either core is not a cuboid or the answer cannot be certified (the
/// caller runs GJK).
#[inline(always)]
pub(crate) fn box_distance<const N: usize>(a: &PlacedShape, b: &PlacedShape) -> Option<BoxGap<N>> {
    let (ConvexCore::Cuboid(ha), ConvexCore::Cuboid(hb)) = (a.shape().core(), b.shape().core())
    else {
        return None;
    };
    let ha: &[f64; N] = ha.as_slice().try_into().ok()?;
    let hb: &[f64; N] = hb.as_slice().try_into().ok()?;
    let pa: &[f64; N] = a.position().try_into().ok()?;
    let pb: &[f64; N] = b.position().try_into().ok()?;
    // The rotations as N rows of N, so that no index is checked at run time.
    let qa: &[[f64; N]; N] = a.rotation().as_chunks::<N>().0.try_into().ok()?;
    let qb: &[[f64; N]; N] = b.rotation().as_chunks::<N>().0.try_into().ok()?;
    let mut d = [0.0; N];
    for i in 0..N {
        d[i] = pb[i] - pa[i];
    }
    let mut problem = Problem {
        a: *ha,
        b: *hb,
        c: [0.0; N],
        r: [[0.0; N]; N],
    };
    // Row by row, each summed in registers.
    for k in 0..N {
        let (mut row, mut ck) = ([0.0; N], 0.0);
        for i in 0..N {
            ck += qa[i][k] * d[i];
            for j in 0..N {
                row[j] += qa[i][k] * qb[i][j];
            }
        }
        (problem.r[k], problem.c[k]) = (row, ck);
    }
    let scale = dot(ha, ha).sqrt() + dot(hb, hb).sqrt() + dot(&d, &d).sqrt();
    let touching = TOUCHING * scale;
    // Start at B's corner nearest the point of A nearest B's centre, and at the point of A
    // nearest that corner: its coordinates inside A's bounds are free (each zeroes its eᵢ),
    // the others held, which is a least-squares point of its free set, as the method needs.
    let mut x = [0.0; N];
    for i in 0..N {
        x[i] = within(problem.c[i], ha[i]) - problem.c[i];
    }
    let towards = problem.turned_back(&x);
    let mut u = [0.0; N];
    for j in 0..N {
        u[j] = hb[j].copysign(towards[j]);
    }
    let mut e = problem.gap(&[0.0; N], &u);
    let mut free_x = 0u32;
    for i in 0..N {
        if e[i].abs() < ha[i] {
            (x[i], e[i]) = (e[i], 0.0);
            free_x |= 1 << i;
        } else {
            x[i] = ha[i].copysign(e[i]);
            e[i] -= x[i];
        }
    }
    let mut free_u = 0u32;
    let mut steps = 0;
    let mut g;
    loop {
        // The held variable whose bound most resists the descent: −∂/∂xᵢ ½|e|² = eᵢ and
        // −∂/∂uⱼ = −(Rᵀe)ⱼ, wanted towards the inside of the bound.
        g = problem.turned_back(&e);
        let mut best = 1e-15 * scale;
        let mut pick = None;
        for i in 0..N {
            if free_x >> i & 1 == 0 {
                let want = if x[i] > 0.0 { -e[i] } else { e[i] };
                if want > best {
                    (best, pick) = (want, Some(i));
                }
            }
            if free_u >> i & 1 == 0 {
                let want = if u[i] > 0.0 { g[i] } else { -g[i] };
                if want > best {
                    (best, pick) = (want, Some(N + i));
                }
            }
        }
        let Some(pick) = pick else { break };
        if pick < N {
            free_x |= 1 << pick;
        } else {
            free_u |= 1 << (pick - N);
        }
        steps += 1;
        loop {
            if steps > 4 * N {
                return None;
            }
            let (tx, tu) = problem.solve(&x, &u, &e, free_x, free_u)?;
            let alpha = step(&x, &tx, &problem.a, free_x, 1.0);
            let alpha = step(&u, &tu, &problem.b, free_u, alpha);
            apply(&mut x, &tx, &problem.a, &mut free_x, alpha);
            apply(&mut u, &tu, &problem.b, &mut free_u, alpha);
            if alpha >= 1.0 {
                break;
            }
            e = problem.gap(&x, &u);
            steps += 1;
        }
        e = problem.gap(&x, &u);
    }
    let ee = dot(&e, &e);
    let intersecting = ee.sqrt() <= touching;
    if !intersecting {
        // v·w for w the support point of B − A along −e, as GJK's stopping rule (g = Rᵀe
        // from the last pass).
        let mut ew = dot(&e, &problem.c);
        for i in 0..N {
            ew -= problem.a[i] * e[i].abs() + problem.b[i] * g[i].abs();
        }
        // e carries round-off of a few units in the last place of the scale, and the gap
        // e·(e − w) that times the size of B − A: allowed for on top of GJK's relative gap.
        let rounding = 8.0 * N as f64 * f64::EPSILON * scale * scale;
        // Written so that a NaN fails it.
        let certified = ee - ew <= RELATIVE_GAP * ee + rounding;
        if !certified {
            return None;
        }
    }
    // Back to space: the witness x of A, v = Q_A e, and B's witness c + R u as x + e, that
    // is witness_a + v (the same point to round-off of the problem's size, without a
    // third product by a rotation).
    let (mut witness_a, mut witness_b, mut v) = ([0.0; N], [0.0; N], [0.0; N]);
    for i in 0..N {
        let (mut p, mut s) = (pa[i], 0.0);
        for j in 0..N {
            p += qa[i][j] * x[j];
            s += qa[i][j] * e[j];
        }
        (witness_a[i], witness_b[i], v[i]) = (p, p + s, s);
    }
    Some(BoxGap {
        witness_a,
        witness_b,
        v,
        vv: ee,
        intersecting,
        steps,
    })
}

impl<const N: usize> BoxGap<N> {
    /// The gap as the separation takes it; returned only when its stopping rule holds
    /// (else GJK answers).
    #[inline(always)]
    pub(crate) fn core_gap(&self) -> CoreGap<'_> {
        CoreGap {
            witness_a: &self.witness_a,
            witness_b: &self.witness_b,
            v: &self.v,
            vv: self.vv,
            intersecting: self.intersecting,
            iterations: self.steps,
            certified: true,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::fixed::gjk_fixed;
    use super::super::test_support::random_rotation as rotation;
    use super::*;
    use crate::dynamics::motion::shape::ConvexShape;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Runs `pairs` random box pairs (with one rotation for both if `parallel`) through
    /// the least-squares path and GJK on arrays: the answers must agree; returns how many
    /// were separated, overlapping, and left to GJK.
    fn run<const N: usize>(seed: u64, pairs: usize, parallel: bool) -> [usize; 3] {
        let mut r = ChaCha8Rng::seed_from_u64(seed);
        // Separated, overlapping, left to GJK.
        let mut counts = [0usize; 3];
        for _ in 0..pairs {
            let ha: Vec<f64> = (0..N).map(|_| r.gen_range(0.2..2.0)).collect();
            let hb: Vec<f64> = (0..N).map(|_| r.gen_range(0.2..2.0)).collect();
            let (sa, sb) = (
                ConvexShape::cuboid(&ha).unwrap(),
                ConvexShape::cuboid(&hb).unwrap(),
            );
            let qa = rotation(&mut r, N);
            let qb = if parallel {
                qa.clone()
            } else {
                rotation(&mut r, N)
            };
            let pa: Vec<f64> = (0..N).map(|_| r.gen_range(-1.0..1.0)).collect();
            let pb: Vec<f64> = (0..N).map(|_| r.gen_range(-4.0..4.0)).collect();
            let a = PlacedShape::new(&sa, &pa, &qa).unwrap();
            let b = PlacedShape::new(&sb, &pb, &qb).unwrap();
            let Some(fast) = box_distance::<N>(&a, &b) else {
                counts[2] += 1;
                continue;
            };
            let gjk = gjk_fixed::<N>(&a, &b);
            if gjk.intersecting {
                assert!(fast.intersecting);
                counts[1] += 1;
            } else {
                // Both answers carry round-off of a few units in the last place of the size.
                let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
                let centres: Vec<f64> = pb.iter().zip(&pa).map(|(p, q)| p - q).collect();
                let tolerance =
                    1e-12 * gjk.vv.sqrt() + 1e-14 * (norm(&ha) + norm(&hb) + norm(&centres));
                let (d, e) = (fast.vv.sqrt(), gjk.vv.sqrt());
                let gap: f64 = (0..N)
                    .map(|i| (fast.witness_b[i] - fast.witness_a[i] - fast.v[i]).powi(2))
                    .sum();
                assert!(gap.sqrt() <= tolerance, "{gap} {e}");
                assert!(!fast.intersecting && (d - e).abs() <= tolerance, "{d} {e}");
                counts[0] += 1;
            }
        }
        counts
    }

    /// The least-squares path answers nearly every box pair in general position itself
    /// (GJK takes over only when it cannot certify), and its answers are GJK's; boxes with
    /// parallel faces agree too, whichever path answers them.
    #[test]
    fn least_squares_answers_general_box_pairs_as_gjk_does() {
        // (pairs, parallel faces, the most left to GJK per pair)
        for (pairs, parallel, left) in [(20_000, false, 1e-3), (5_000, true, 1e-2)] {
            let seed = if parallel { 5 } else { 3 };
            for (n, counts) in [
                (3, run::<3>(seed, pairs, parallel)),
                (4, run::<4>(seed + 1, pairs, parallel)),
            ] {
                println!(
                    "N = {n}, parallel faces {parallel}: {counts:?} (separated, overlapping, left to GJK)"
                );
                assert_eq!(counts.iter().sum::<usize>(), pairs);
                assert!(
                    counts[0] >= pairs / 4 && counts[1] >= pairs / 20,
                    "{counts:?}"
                );
                assert!(
                    counts[2] as f64 <= left * pairs as f64,
                    "N = {n}: {counts:?}"
                );
            }
        }
    }
}
