//! A small dense linear program, max cᵀx subject to A x = b, x ≥ 0, by the simplex method on
//! a tableau held inline (no allocation), for the handful of rows and the hundred-odd columns
//! of a contact region's extremes.
//!
//! The two-phase method (Dantzig): phase one takes the artificial basis of the rows (each
//! row's sign made so that b ≥ 0) to a basis of the problem's own columns, or finds the
//! constraints inconsistent; phase two then maximises any number of objectives in turn, each
//! from the optimal basis of the last (the constraints do not change), so that a new
//! objective costs a few pivots. The entering column is Dantzig's (the largest reduced cost)
//! and the leaving row Harris's (among the rows that bind within a small tolerance, the
//! largest pivot: near-degenerate rows otherwise force pivots on tiny entries, and the
//! tableau loses its digits); the pivots of a solve are bounded, so every call returns.

/// Rows at most.
pub(crate) const LP_MAX_ROWS: usize = 12;
/// Columns (variables) at most, besides one artificial per row.
pub(crate) const LP_MAX_COLUMNS: usize = 160;
/// The width of a tableau row that holds every program up to [`LP_MAX_COLUMNS`]: the
/// columns, one artificial per row and the right side. A program of a few columns fits a
/// narrower tableau (`EqualityLp<W>`), whose set-up and moves cost as much less.
pub(crate) const LP_WIDTH: usize = LP_MAX_COLUMNS + LP_MAX_ROWS + 1;

/// Entries below this (relative to 1: the caller scales its rows to about unit size) are
/// zeros to the pivot rules.
const PIVOT: f64 = 1e-9;
/// How far below zero Harris's ratio test lets a basic value go (set back to zero after the
/// pivot), relative to 1.
const FEASIBLE: f64 = 1e-12;

/// max cᵀx subject to A x = b, x ≥ 0, as a tableau kept in canonical form for its basis.
pub(crate) struct EqualityLp<const W: usize> {
    rows: usize,
    columns: usize,
    /// Where the right side is in a row: after the columns and the artificials.
    rhs: usize,
    /// Row i: the entries of the columns, then of the artificials, then the right side
    /// (the rest unused).
    t: [[f64; W]; LP_MAX_ROWS],
    basis: [usize; LP_MAX_ROWS],
    /// Rows that are combinations of the others (their artificial stays basic at zero).
    redundant: [bool; LP_MAX_ROWS],
}

/// How a maximisation ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum LpEnd {
    /// At an optimal vertex.
    Optimal,
    /// The objective grows without bound along an edge.
    Unbounded,
    /// At the pivot bound, at a feasible vertex that may not be optimal.
    Stopped,
}

impl<const W: usize> EqualityLp<W> {
    /// The program with `rows` constraints over `columns` variables, entry (i, j) of A given
    /// by `entry(i, j)` and b by `rhs`, or None if it exceeds [`LP_MAX_ROWS`] or
    /// [`LP_MAX_COLUMNS`] or an entry is not finite.
    pub(crate) fn new(
        rows: usize,
        columns: usize,
        entry: impl Fn(usize, usize) -> f64,
        rhs: &[f64],
    ) -> Option<EqualityLp<W>> {
        if rows > LP_MAX_ROWS
            || columns > LP_MAX_COLUMNS
            || columns + rows + 1 > W
            || rhs.len() != rows
        {
            return None;
        }
        let mut lp = EqualityLp {
            rows,
            columns,
            rhs: columns + rows,
            t: [[0.0; W]; LP_MAX_ROWS],
            basis: [0; LP_MAX_ROWS],
            redundant: [false; LP_MAX_ROWS],
        };
        for (i, &b) in rhs.iter().enumerate() {
            let sign = if b < 0.0 { -1.0 } else { 1.0 };
            let row = &mut lp.t[i];
            for (j, x) in row[..columns].iter_mut().enumerate() {
                *x = sign * entry(i, j);
            }
            row[columns + i] = 1.0;
            row[columns + rows] = sign * b;
            if !row[..=columns + rows].iter().all(|x| x.is_finite()) {
                return None;
            }
            lp.basis[i] = columns + i;
        }
        Some(lp)
    }

    /// Phase one: a basis of the problem's own columns. False if A x = b, x ≥ 0 has no
    /// solution (the artificials cannot all leave within `tol`) or the pivot bound is met.
    pub(crate) fn find_feasible(&mut self, tol: f64) -> bool {
        let (m, c) = (self.rows, self.columns);
        let mut cost = [0.0; W];
        cost[c..c + m].iter_mut().for_each(|x| *x = -1.0);
        if self.maximize_over(&cost, c + m) != LpEnd::Optimal {
            return false;
        }
        let infeasibility: f64 = (0..m)
            .filter(|&i| self.basis[i] >= c)
            .map(|i| self.t[i][self.rhs].abs())
            .sum();
        if infeasibility.is_nan() || infeasibility > tol {
            return false;
        }
        // Artificials still basic (at zero) leave for any column of their row; a row with
        // none is a combination of the others.
        for i in 0..m {
            if self.basis[i] < c {
                continue;
            }
            let largest = (0..c).max_by(|&a, &b| self.t[i][a].abs().total_cmp(&self.t[i][b].abs()));
            match largest {
                Some(j) if self.t[i][j].abs() > PIVOT => {
                    self.t[i][self.rhs] = 0.0;
                    self.pivot(i, j);
                }
                _ => self.redundant[i] = true,
            }
        }
        true
    }

    /// Phase two: maximises cᵀx (c over the problem's columns) from the current feasible
    /// basis, which [`Self::find_feasible`] must have found.
    pub(crate) fn maximize(&mut self, c: &[f64]) -> LpEnd {
        let mut cost = [0.0; W];
        cost[..self.columns].copy_from_slice(&c[..self.columns]);
        self.maximize_over(&cost, self.columns)
    }

    /// Writes the current basic solution (the problem's columns) into `x`.
    pub(crate) fn solution(&self, x: &mut [f64]) {
        x[..self.columns].iter_mut().for_each(|v| *v = 0.0);
        for i in 0..self.rows {
            if self.basis[i] < self.columns {
                // Round-off can leave a basic value a hair below zero.
                x[self.basis[i]] = self.t[i][self.rhs].max(0.0);
            }
        }
    }

    /// The simplex iterations for the objective `cost` (over all columns), entering only
    /// columns below `enter_below`.
    fn maximize_over(&mut self, cost: &[f64; W], enter_below: usize) -> LpEnd {
        let m = self.rows;
        let scale = cost[..enter_below]
            .iter()
            .fold(0.0f64, |s, x| s.max(x.abs()))
            .max(f64::MIN_POSITIVE);
        let bound = 50 * (m + enter_below);
        for _ in 0..bound {
            // Dantzig: the column of the largest reduced cost c_j − c_B·T_j.
            let mut entering = None;
            let mut best = PIVOT * scale;
            for j in 0..enter_below {
                let mut r = cost[j];
                for i in 0..m {
                    r -= cost[self.basis[i]] * self.t[i][j];
                }
                if r > best {
                    (best, entering) = (r, Some(j));
                }
            }
            let Some(j) = entering else {
                return LpEnd::Optimal;
            };
            // Harris's ratio test: the largest step that keeps every basic value above
            // −FEASIBLE, then among the rows that bind within it the largest pivot, so that
            // near-degenerate rows do not force a pivot on a tiny entry.
            let mut room = f64::INFINITY;
            for i in 0..m {
                let a = self.t[i][j];
                if !self.redundant[i] && a > PIVOT {
                    room = room.min((self.t[i][self.rhs].max(0.0) + FEASIBLE) / a);
                }
            }
            if room == f64::INFINITY {
                return LpEnd::Unbounded;
            }
            let mut leave: Option<(usize, f64)> = None;
            for i in 0..m {
                let a = self.t[i][j];
                if self.redundant[i] || a <= PIVOT || self.t[i][self.rhs].max(0.0) / a > room {
                    continue;
                }
                if leave.is_none_or(|(_, largest)| a > largest) {
                    leave = Some((i, a));
                }
            }
            let Some((i, _)) = leave else {
                return LpEnd::Unbounded;
            };
            self.pivot(i, j);
        }
        LpEnd::Stopped
    }

    /// Makes column j basic in row i. A basic value that the step leaves below zero by
    /// round-off or by Harris's tolerance is set to zero.
    fn pivot(&mut self, i: usize, j: usize) {
        let width = self.rhs + 1;
        // The pivot row borrowed beside the others rather than copied (a row is 1.4 KB).
        let (before, rest) = self.t[..self.rows].split_at_mut(i);
        let (row, after) = rest.split_at_mut(1);
        let row = &mut row[0][..width];
        let p = 1.0 / row[j];
        row.iter_mut().for_each(|x| *x *= p);
        row[j] = 1.0;
        for other in before.iter_mut().chain(after.iter_mut()) {
            let f = other[j];
            if f == 0.0 {
                continue;
            }
            other[..width]
                .iter_mut()
                .zip(row.iter())
                .for_each(|(x, r)| *x -= f * r);
            other[j] = 0.0;
        }
        for other in &mut self.t[..self.rows] {
            if other[self.rhs] < 0.0 {
                other[self.rhs] = 0.0;
            }
        }
        self.basis[i] = j;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// max x + y over the square 0 ≤ x, y ≤ 1 (slacks s, t: x + s = 1, y + t = 1) is 2 at
    /// (1, 1); min x + y (max −x − y) is 0 at the origin.
    #[test]
    fn a_square_has_its_corners_as_optima() {
        let a = [[1.0, 0.0, 1.0, 0.0], [0.0, 1.0, 0.0, 1.0]];
        let mut lp = EqualityLp::<LP_WIDTH>::new(2, 4, |i, j| a[i][j], &[1.0, 1.0]).unwrap();
        assert!(lp.find_feasible(1e-12));
        let mut x = [0.0; 4];
        assert_eq!(lp.maximize(&[1.0, 1.0, 0.0, 0.0]), LpEnd::Optimal);
        lp.solution(&mut x);
        assert_eq!(&x[..2], &[1.0, 1.0]);
        assert_eq!(lp.maximize(&[-1.0, -1.0, 0.0, 0.0]), LpEnd::Optimal);
        lp.solution(&mut x);
        assert_eq!(&x[..2], &[0.0, 0.0]);
    }

    /// x + y = 1 and x + y = 2 have no common point; x ≥ 0 alone is unbounded above.
    #[test]
    fn inconsistent_and_unbounded_programs_are_told() {
        let mut lp = EqualityLp::<LP_WIDTH>::new(2, 2, |_, _| 1.0, &[1.0, 2.0]).unwrap();
        assert!(!lp.find_feasible(1e-12));
        // x − y = 0: max x grows along x = y.
        let mut lp = EqualityLp::<LP_WIDTH>::new(1, 2, |_, j| [1.0, -1.0][j], &[0.0]).unwrap();
        assert!(lp.find_feasible(1e-12));
        assert_eq!(lp.maximize(&[1.0, 0.0]), LpEnd::Unbounded);
        assert!(
            EqualityLp::<LP_WIDTH>::new(LP_MAX_ROWS + 1, 1, |_, _| 1.0, &[1.0; LP_MAX_ROWS + 1])
                .is_none()
        );
    }

    /// A redundant row (the sum of the others) is set aside, and the optimum stands.
    #[test]
    fn a_redundant_row_is_set_aside() {
        // x + s = 1, y + t = 1, x + y + s + t = 2.
        let a = [
            [1.0, 0.0, 1.0, 0.0],
            [0.0, 1.0, 0.0, 1.0],
            [1.0, 1.0, 1.0, 1.0],
        ];
        let mut lp = EqualityLp::<LP_WIDTH>::new(3, 4, |i, j| a[i][j], &[1.0, 1.0, 2.0]).unwrap();
        assert!(lp.find_feasible(1e-12));
        assert_eq!(lp.maximize(&[2.0, 1.0, 0.0, 0.0]), LpEnd::Optimal);
        let mut x = [0.0; 4];
        lp.solution(&mut x);
        assert!((x[0] - 1.0).abs() < 1e-12 && (x[1] - 1.0).abs() < 1e-12);
    }

    /// A x − b at the current solution, the largest entry.
    fn residual<const W: usize>(
        lp: &EqualityLp<W>,
        a: &dyn Fn(usize, usize) -> f64,
        b: &[f64],
    ) -> f64 {
        let mut x = [0.0; LP_MAX_COLUMNS];
        lp.solution(&mut x);
        (0..lp.rows)
            .map(|i| ((0..lp.columns).map(|j| a(i, j) * x[j]).sum::<f64>() - b[i]).abs())
            .fold(0.0, f64::max)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]
        /// Over the intersection of two hulls of points on a grid (degenerate: shared
        /// coordinates, points on each other's faces), every optimum in a series of
        /// objectives is a solution of the constraints to 1e-12.
        #[test]
        fn optima_over_degenerate_intersections_solve_the_constraints(
            d in 1usize..7,
            pa in proptest::collection::vec(proptest::collection::vec(-2i32..3, 7), 1..30),
            pb in proptest::collection::vec(proptest::collection::vec(-2i32..3, 7), 1..30),
            objectives in proptest::collection::vec(proptest::collection::vec(-3i32..4, 7), 1..20),
        ) {
            let (ka, kb) = (pa.len(), pb.len());
            // Both hulls hold the origin: each set gets the point 0.
            let point = |set: &Vec<Vec<i32>>, k: usize, i: usize| -> f64 {
                if k == 0 { 0.0 } else { 0.5 * set[k][i] as f64 }
            };
            let entry = |i: usize, j: usize| -> f64 {
                if i < d {
                    if j < ka { point(&pa, j, i) } else { -point(&pb, j - ka, i) }
                } else if i == d {
                    f64::from(u8::from(j < ka))
                } else {
                    f64::from(u8::from(j >= ka))
                }
            };
            let mut rhs = vec![0.0; d + 2];
            (rhs[d], rhs[d + 1]) = (1.0, 1.0);
            let mut lp = EqualityLp::<LP_WIDTH>::new(d + 2, ka + kb, entry, &rhs).unwrap();
            // The same program in a tableau just wide enough, where it fits: the same
            // arithmetic, so the same optima to the bit.
            let mut narrow = EqualityLp::<48>::new(d + 2, ka + kb, entry, &rhs);
            prop_assert_eq!(narrow.is_some(), ka + kb + d + 3 <= 48);
            prop_assert!(lp.find_feasible(1e-9));
            if let Some(narrow) = &mut narrow {
                prop_assert!(narrow.find_feasible(1e-9));
            }
            prop_assert!(residual(&lp, &entry, &rhs) <= 1e-12);
            let (mut x, mut y) = (vec![0.0; ka + kb], vec![0.0; ka + kb]);
            for o in &objectives {
                let cost: Vec<f64> = (0..ka + kb)
                    .map(|j| if j < ka { (0..d).map(|i| o[i] as f64 * point(&pa, j, i)).sum() } else { 0.0 })
                    .collect();
                prop_assert_eq!(lp.maximize(&cost), LpEnd::Optimal);
                let r = residual(&lp, &entry, &rhs);
                prop_assert!(r <= 1e-12, "residual {}", r);
                if let Some(narrow) = &mut narrow {
                    prop_assert_eq!(narrow.maximize(&cost), LpEnd::Optimal);
                    lp.solution(&mut x);
                    narrow.solution(&mut y);
                    prop_assert_eq!(&x, &y);
                }
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]
        /// The optimum of a linear objective over the convex hull of random points
        /// (x = Σ λ_k p_k, Σ λ_k = 1, λ ≥ 0) is the best of the points, in 1 to 7
        /// dimensions with up to 40 points: against the brute force over the points.
        #[test]
        fn the_optimum_over_a_hull_is_its_best_vertex(
            d in 1usize..8,
            points in proptest::collection::vec(proptest::collection::vec(-1.0f64..1.0, 7), 1..40),
            c in proptest::collection::vec(-1.0f64..1.0, 7),
        ) {
            // Variables: λ (k of them), then x⁺ and x⁻ (x = x⁺ − x⁻, free); rows: the d
            // coordinates Σ λ p − x⁺ + x⁻ = 0, then Σ λ = 1.
            let k = points.len();
            let entry = |i: usize, j: usize| -> f64 {
                if i < d {
                    if j < k { points[j][i] } else if j == k + i { -1.0 } else if j == k + d + i { 1.0 } else { 0.0 }
                } else if j < k { 1.0 } else { 0.0 }
            };
            let mut rhs = vec![0.0; d + 1];
            rhs[d] = 1.0;
            let mut lp = EqualityLp::<LP_WIDTH>::new(d + 1, k + 2 * d, entry, &rhs).unwrap();
            prop_assert!(lp.find_feasible(1e-9));
            let mut cost = vec![0.0; k + 2 * d];
            for i in 0..d {
                cost[k + i] = c[i];
                cost[k + d + i] = -c[i];
            }
            prop_assert_eq!(lp.maximize(&cost), LpEnd::Optimal);
            let mut x = vec![0.0; k + 2 * d];
            lp.solution(&mut x);
            let value: f64 = (0..d).map(|i| c[i] * (x[k + i] - x[k + d + i])).sum();
            let best = points
                .iter()
                .map(|p| (0..d).map(|i| c[i] * p[i]).sum::<f64>())
                .fold(f64::NEG_INFINITY, f64::max);
            prop_assert!((value - best).abs() <= 1e-9, "{} against {}", value, best);
            let weights: f64 = x[..k].iter().sum();
            prop_assert!((weights - 1.0).abs() <= 1e-9);
        }
    }
}
