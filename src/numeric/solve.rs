//! Dense linear solves on slices (Golub & Van Loan, *Matrix Computations*, §3.4 and §4.2):
//! LU with partial pivoting for general square matrices, Cholesky for symmetric positive
//! definite ones. The matrices live in caller-provided slices, so callers on stack storage
//! stay allocation-free.

use smallvec::SmallVec;

/// Factors the column-major m × m X in place as P X = L U (Gaussian elimination with partial
/// pivoting; `pivots[c]` is the row swapped with row c; L has a unit diagonal and is stored
/// below it). False if a pivot is zero or not finite.
pub(crate) fn lu_factor(m: usize, x: &mut [f64], pivots: &mut [usize]) -> bool {
    lu_factor_above(m, x, pivots, 0.0)
}

/// [`lu_factor`], false also where a pivot is at most `least` in magnitude: a caller whose
/// matrix is singular to within its own tolerance (nearly parallel features) takes that as
/// no solution rather than a huge one.
pub(crate) fn lu_factor_above(m: usize, x: &mut [f64], pivots: &mut [usize], least: f64) -> bool {
    for col in 0..m {
        let (pivot_row, pivot) = (col..m)
            .map(|r| (r, x[col * m + r].abs()))
            .fold((col, -1.0), |best, c| if c.1 > best.1 { c } else { best });
        if pivot <= least || !pivot.is_finite() {
            return false;
        }
        pivots[col] = pivot_row;
        if pivot_row != col {
            for c in 0..m {
                x.swap(c * m + col, c * m + pivot_row);
            }
        }
        let d = x[col * m + col];
        for r in col + 1..m {
            x[col * m + r] /= d;
        }
        for c in col + 1..m {
            let top = x[c * m + col];
            if top == 0.0 {
                continue;
            }
            for r in col + 1..m {
                x[c * m + r] -= x[col * m + r] * top;
            }
        }
    }
    true
}

/// The determinant of the m × m X (stored either way: det Xᵀ = det X) by [`lu_factor`],
/// which overwrites X: 0 for a singular X, NaN if X holds a number that is not finite.
pub(crate) fn determinant(m: usize, x: &mut [f64]) -> f64 {
    if x.iter().any(|v| !v.is_finite()) {
        return f64::NAN;
    }
    let mut pivots: SmallVec<[usize; 28]> = SmallVec::from_elem(0, m);
    if !lu_factor(m, x, &mut pivots) {
        return 0.0;
    }
    let mut det = 1.0;
    for (col, &p) in pivots.iter().enumerate() {
        det *= x[col * m + col];
        if p != col {
            det = -det;
        }
    }
    det
}

/// Solves with the factors of [`lu_factor`]: B ← X⁻¹B for the first `rhs` columns of the
/// column-major B (m rows). A 0 × 0 system leaves B as it is.
pub(crate) fn lu_apply(m: usize, x: &[f64], pivots: &[usize], b: &mut [f64], rhs: usize) {
    if m == 0 {
        return;
    }
    for y in b.chunks_exact_mut(m).take(rhs) {
        for (col, &p) in pivots.iter().enumerate().take(m) {
            y.swap(col, p);
        }
        // L (unit diagonal), then U.
        for col in 0..m {
            let v = y[col];
            if v != 0.0 {
                for r in col + 1..m {
                    y[r] -= x[col * m + r] * v;
                }
            }
        }
        for col in (0..m).rev() {
            y[col] /= x[col * m + col];
            let v = y[col];
            for r in 0..col {
                y[r] -= x[col * m + r] * v;
            }
        }
    }
}

/// Solves X·Y = B in place (B ← Y) for the column-major m × m X (overwritten by its LU
/// factors) and `rhs` columns of B. False if X is singular to working precision. No heap up
/// to m = 28.
pub(crate) fn lu_solve(m: usize, x: &mut [f64], b: &mut [f64], rhs: usize) -> bool {
    let mut pivots: SmallVec<[usize; 28]> = SmallVec::from_elem(0, m);
    lu_factor(m, x, &mut pivots) && {
        lu_apply(m, x, &pivots, b, rhs);
        true
    }
}

/// Overwrites the lower triangle of the symmetric positive definite n × n `a` (row-major:
/// entry (i, j) at `a[i * n + j]`) by its Cholesky factor L, A = L Lᵀ; the strict upper
/// triangle is not read. False if `a` is not positive definite (a pivot ≤ 0 or NaN).
pub(crate) fn cholesky_factor(a: &mut [f64], n: usize) -> bool {
    cholesky_factor_n::<0>(a, n)
}

/// [`cholesky_factor`] with n = `N` when `N` ≠ 0: the loops of a 3 × 3 or 4 × 4 block then
/// run with constant bounds (the same arithmetic).
#[inline(always)]
pub(crate) fn cholesky_factor_n<const N: usize>(a: &mut [f64], n: usize) -> bool {
    let n = if N == 0 { n } else { N };
    let a = &mut a[..n * n];
    for j in 0..n {
        let mut d = a[j * n + j];
        for k in 0..j {
            d -= a[j * n + k] * a[j * n + k];
        }
        if d.is_nan() || d <= 0.0 {
            return false;
        }
        let d = d.sqrt();
        a[j * n + j] = d;
        for i in j + 1..n {
            let mut s = a[i * n + j];
            for k in 0..j {
                s -= a[i * n + k] * a[j * n + k];
            }
            a[i * n + j] = s / d;
        }
    }
    true
}

/// Solves L Lᵀ x = b in place, L the factor [`cholesky_factor`] left in `l`.
pub(crate) fn cholesky_substitute(l: &[f64], n: usize, b: &mut [f64]) {
    cholesky_substitute_n::<0>(l, n, b);
}

/// [`cholesky_substitute`] with n = `N` when `N` ≠ 0 (as [`cholesky_factor_n`]).
#[inline(always)]
pub(crate) fn cholesky_substitute_n<const N: usize>(l: &[f64], n: usize, b: &mut [f64]) {
    let n = if N == 0 { n } else { N };
    let (l, b) = (&l[..n * n], &mut b[..n]);
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= l[i * n + k] * b[k];
        }
        b[i] = s / l[i * n + i];
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= l[k * n + i] * b[k];
        }
        b[i] = s / l[i * n + i];
    }
}

/// Solves A x = b in place for the symmetric positive definite n × n `a` (row-major,
/// overwritten by its Cholesky factor). False if `a` is not positive definite.
pub(crate) fn cholesky_solve(a: &mut [f64], n: usize, b: &mut [f64]) -> bool {
    if !cholesky_factor(a, n) {
        return false;
    }
    cholesky_substitute(a, n, b);
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::tests::random;
    use nalgebra::{DMatrix, DVector};

    /// LU solves match nalgebra's LU on random systems of sizes 1 … 12 with three right-hand
    /// sides, and the factors rebuild P X; a singular matrix is refused.
    #[test]
    fn lu_matches_nalgebra_and_rebuilds_the_matrix() {
        let mut seed = 11u64;
        let mut checked = 0;
        for m in 1..=12 {
            let x = DMatrix::from_fn(m, m, |_, _| random(&mut seed));
            let b = DMatrix::from_fn(m, 3, |_, _| random(&mut seed));
            let want = x.clone().lu().solve(&b).unwrap();
            let (mut f, mut y) = (x.clone(), b.clone());
            assert!(lu_solve(m, f.as_mut_slice(), y.as_mut_slice(), 3));
            let scale = want.amax().max(1.0);
            assert!((&y - &want).amax() < 1e-11 * scale, "m = {m}");
            // L U = P X, with P the recorded swaps applied in order.
            let mut f = x.clone();
            let mut pivots = vec![0; m];
            assert!(lu_factor(m, f.as_mut_slice(), &mut pivots));
            let l = DMatrix::from_fn(m, m, |i, j| match i.cmp(&j) {
                std::cmp::Ordering::Greater => f[(i, j)],
                std::cmp::Ordering::Equal => 1.0,
                std::cmp::Ordering::Less => 0.0,
            });
            let u = DMatrix::from_fn(m, m, |i, j| if i <= j { f[(i, j)] } else { 0.0 });
            let mut px = x.clone();
            for (c, &p) in pivots.iter().enumerate() {
                px.swap_rows(c, p);
            }
            assert!((l * u - px).amax() < 1e-14, "m = {m}");
            checked += 1;
        }
        assert_eq!(checked, 12);
        let mut singular =
            DMatrix::from_row_slice(3, 3, &[1.0, 2.0, 3.0, 2.0, 4.0, 6.0, 0.0, 1.0, 1.0]);
        let mut rhs = vec![1.0; 3];
        assert!(!lu_solve(3, singular.as_mut_slice(), &mut rhs, 1));
    }

    /// Cholesky solves match nalgebra's on random SPD systems of sizes 1 … 12, the factor
    /// rebuilds A, and an indefinite matrix is refused.
    /// The determinant matches nalgebra's on random matrices of sizes 1 … 10 in either
    /// storage order (its sign follows the row swaps), is 0 for a matrix with two equal
    /// rows and NaN for one with a NaN; a pivot at `least` is refused by
    /// `lu_factor_above`, one just above it is taken.
    #[test]
    fn determinant_matches_nalgebra_and_small_pivots_are_refused() {
        let mut seed = 23u64;
        let mut checked = 0;
        for m in 1..=10 {
            for _ in 0..5 {
                let x = DMatrix::from_fn(m, m, |_, _| random(&mut seed));
                let expected = x.determinant();
                for stored in [x.clone(), x.transpose()] {
                    let mut data = stored.as_slice().to_vec();
                    let det = determinant(m, &mut data);
                    assert!(
                        (det - expected).abs() <= 1e-12 * (1.0 + expected.abs()),
                        "m = {m}: {det} vs {expected}"
                    );
                    checked += 1;
                }
            }
            if m > 1 {
                let mut x = DMatrix::from_fn(m, m, |_, _| random(&mut seed));
                let row = x.row(0).into_owned();
                x.set_row(m - 1, &row);
                assert_eq!(determinant(m, &mut x.as_slice().to_vec()), 0.0, "m = {m}");
            }
            let mut x = vec![1.0; m * m];
            x[m * m / 2] = f64::NAN;
            assert!(determinant(m, &mut x).is_nan());
        }
        assert_eq!(checked, 100);
        // The 0 × 0 system: the empty product, and nothing to solve.
        assert_eq!(determinant(0, &mut []), 1.0);
        let mut b = [7.0];
        lu_apply(0, &[], &[], &mut b, 1);
        assert_eq!(b, [7.0]);
        // diag(1, 1e-10): the second pivot is 1e-10.
        let diagonal = [1.0, 0.0, 0.0, 1e-10];
        let mut pivots = [0; 2];
        assert!(!lu_factor_above(
            2,
            &mut diagonal.clone(),
            &mut pivots,
            1e-10
        ));
        assert!(lu_factor_above(
            2,
            &mut diagonal.clone(),
            &mut pivots,
            0.99e-10
        ));
    }

    #[test]
    fn cholesky_matches_nalgebra_and_rebuilds_the_matrix() {
        let mut seed = 5u64;
        let mut checked = 0;
        for n in 1..=12 {
            let g = DMatrix::from_fn(n, n, |_, _| random(&mut seed));
            let a = &g * g.transpose() + DMatrix::<f64>::identity(n, n) * 0.1;
            let b = DVector::from_fn(n, |_, _| random(&mut seed));
            let want = a.clone().cholesky().unwrap().solve(&b);
            // Row-major storage of a symmetric matrix is its column-major storage.
            let (mut f, mut x) = (a.clone(), b.clone());
            assert!(cholesky_solve(f.as_mut_slice(), n, x.as_mut_slice()));
            assert!(
                (&x - &want).amax() < 1e-10 * want.amax().max(1.0),
                "n = {n}"
            );
            let l = DMatrix::from_fn(n, n, |i, j| if j <= i { f[(j, i)] } else { 0.0 });
            assert!(
                (&l * l.transpose() - &a).amax() < 1e-13 * a.amax(),
                "n = {n}"
            );
            checked += 1;
        }
        assert_eq!(checked, 12);
        let mut indefinite = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 2.0, 1.0]);
        assert!(!cholesky_factor(indefinite.as_mut_slice(), 2));
    }

    /// The fixed-size kernels (N = 3, 4) give the generic ones' factor and solution to the
    /// bit on random SPD systems, and refuse what they refuse.
    #[test]
    fn fixed_size_cholesky_is_the_generic_one_to_the_bit() {
        fn check<const N: usize>(seed: &mut u64) {
            let g = DMatrix::from_fn(N, N, |_, _| random(seed));
            let a = &g * g.transpose() + DMatrix::<f64>::identity(N, N) * 0.1;
            let b: Vec<f64> = (0..N).map(|_| random(seed)).collect();
            let (mut f0, mut f1) = (a.as_slice().to_vec(), a.as_slice().to_vec());
            assert!(cholesky_factor(&mut f0, N) && cholesky_factor_n::<N>(&mut f1, N));
            let (mut x0, mut x1) = (b.clone(), b);
            cholesky_substitute(&f0, N, &mut x0);
            cholesky_substitute_n::<N>(&f1, N, &mut x1);
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!((bits(&f0), bits(&x0)), (bits(&f1), bits(&x1)));
            let mut negative = a.as_slice().to_vec();
            negative[0] = -1.0;
            assert!(!cholesky_factor_n::<N>(&mut negative, N));
        }
        let mut seed = 17u64;
        for _ in 0..100 {
            check::<3>(&mut seed);
            check::<4>(&mut seed);
        }
    }
}
