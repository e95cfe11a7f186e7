//! The numeric toolbox: dense linear-algebra and scalar kernels that know nothing of
//! geometric algebra.
//!
//! A leaf of the crate: it depends only on nalgebra and smallvec, and `algebra`, `inertia` and `dynamics`
//! build on it (numeric ← algebra ← inertia ← dynamics). Nothing here is public API; the
//! public types re-export what users need (for instance [`crate::algebra::Rotor::to_matrix`]
//! rather than the matrix exponential behind it).
//!
//! - [`dense`]: small dense matrices with inline storage (`Mat8`), for allocation-free
//!   callers up to N = 8;
//! - [`eigen`]: a symmetric eigen-decomposition that never returns NaN for finite input, and
//!   the one cyclic Jacobi kernel;
//! - [`solve`]: LU with partial pivoting and Cholesky, on slices;
//! - [`expm`]: the matrix exponential of skew matrices (scaling and squaring, Padé, Taylor);
//! - [`trig`]: sin x and cos x − 1 without cancellation;
//! - [`householder`]: the complement of two orthonormal vectors by Householder reflections;
//! - [`simplex`]: a small dense linear program by the two-phase simplex method, inline;
//! - [`secular`]: every root of the secular equation of the feet of normals to an
//!   ellipsoid;
//! - the small helpers below (exact scaling by powers of two, scaled norms, max-abs norms,
//!   orthogonality error, Gram–Schmidt against orthonormal rows), each the
//!   one copy the crate uses.

pub(crate) mod dense;
pub(crate) mod eigen;
pub(crate) mod expm;
pub(crate) mod householder;
pub(crate) mod secular;
pub(crate) mod simplex;
pub(crate) mod solve;
pub(crate) mod trig;

pub(crate) use dense::{Dense, Mat8, Vec8};
pub(crate) use eigen::{
    RobustEigen, sorted_symmetric_eigen, symmetric_eigen, symmetric_eigen_rows,
};
pub(crate) use expm::{
    PADE_MAX_NORM, expm_skew, expm_skew_fixed, expm_skew_taylor, expm_skew_taylor_dense,
    expm_spectral, norm1, norm1_slice,
};
pub(crate) use householder::householder_complement;
pub(crate) use solve::{
    cholesky_factor, cholesky_factor_n, cholesky_solve, cholesky_substitute, cholesky_substitute_n,
    determinant, lu_apply, lu_factor, lu_factor_above, lu_solve,
};
pub(crate) use trig::{sin_cos_minus_one, small_angle_factors};

use nalgebra::{DMatrix, DMatrixView};
use smallvec::SmallVec;

/// `len` zeros, inline when they fit: the whole buffer is written at once (smallvec's
/// `from_elem` fills element by element, which costs more than the small products and
/// closed forms it feeds). Meant for inline capacities of a few cache lines.
#[inline(always)]
pub(crate) fn zeros<const K: usize>(len: usize) -> SmallVec<[f64; K]> {
    if len <= K {
        SmallVec::from_buf_and_len([0.0; K], len)
    } else {
        SmallVec::from_vec(vec![0.0; len])
    }
}

/// The dimension of a kernel: `N` when it is fixed at compile time (3 and 4: loops of known
/// length, unrolled), else `n` (`N` = 0).
#[inline(always)]
pub(crate) fn dim<const N: usize>(n: usize) -> usize {
    debug_assert!(
        N == 0 || N == n,
        "rotorflow: kernel of dimension {N} for {n}"
    );
    if N == 0 { n } else { N }
}

/// True when the numbers are all finite: each is multiplied by zero (±0 when finite, NaN
/// for ±∞ and NaN) and the products summed in four lanes, with no branch per number.
#[inline(always)]
pub(crate) fn all_finite(x: &[f64]) -> bool {
    let mut lanes = [0.0; 4];
    let (chunks, rest) = x.as_chunks::<4>();
    for chunk in chunks {
        for (lane, &c) in lanes.iter_mut().zip(chunk) {
            *lane += c * 0.0;
        }
    }
    for (lane, &c) in lanes.iter_mut().zip(rest) {
        *lane += c * 0.0;
    }
    (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]) == 0.0
}

/// Multiplies by 2^e exactly (barring overflow/underflow of the result), also for |e| > 1023.
pub(crate) fn ldexp(mut x: f64, mut e: i32) -> f64 {
    while e > 1000 {
        x *= 2f64.powi(1000);
        e -= 1000;
    }
    while e < -1000 {
        x *= 2f64.powi(-1000);
        e += 1000;
    }
    x * 2f64.powi(e)
}

/// Returns e with 2^e ≤ s < 2^(e+1) for finite s > 0.
pub(crate) fn exponent_of(s: f64) -> i32 {
    let bits = s.to_bits();
    let raw = ((bits >> 52) & 0x7ff) as i32;
    if raw == 0 {
        // Subnormal: normalise first.
        exponent_of(s * 2f64.powi(64)) - 64
    } else {
        raw - 1023
    }
}

/// Euclidean norm of a slice that neither overflows nor underflows (scaled by the largest
/// magnitude first, as LAPACK's `dnrm2`).
pub(crate) fn scaled_norm(x: &[f64]) -> f64 {
    let m = max_abs(x);
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    if (1e-150..1e150).contains(&m) {
        return x.iter().map(|c| c * c).sum::<f64>().sqrt();
    }
    let s: f64 = x.iter().map(|c| (c / m) * (c / m)).sum();
    m * s.sqrt()
}

/// max |xᵢ| over a slice (0 for an empty one; NaN entries are skipped, as `f64::max` does).
pub(crate) fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0f64, |m, c| m.max(c.abs()))
}

/// max |Mᵢⱼ| over a matrix.
pub(crate) fn max_abs_matrix(m: &DMatrix<f64>) -> f64 {
    max_abs(m.as_slice())
}

/// max |(QᵀQ − 1)ᵢⱼ|: how far a square matrix is from orthogonal.
pub(crate) fn orthogonality_error(q: DMatrixView<'_, f64>) -> f64 {
    let g = q.tr_mul(&q);
    let n = g.nrows();
    let mut err = 0.0f64;
    for i in 0..n {
        for j in 0..n {
            let target = if i == j { 1.0 } else { 0.0 };
            err = err.max((g[(i, j)] - target).abs());
        }
    }
    err
}

/// Removes from `x` its components along the first `rank` rows of `basis` (orthonormal rows
/// of length `x.len()`, stored one after another), twice: one pass of classical
/// Gram–Schmidt leaves components of size ε·cond, the second brings them to round-off.
pub(crate) fn orthogonalize_twice(x: &mut [f64], basis: &[f64], rank: usize) {
    let n = x.len();
    for _ in 0..2 {
        for row in basis[..rank * n].chunks_exact(n) {
            let c: f64 = row.iter().zip(x.iter()).map(|(p, q)| p * q).sum();
            x.iter_mut().zip(row).for_each(|(y, r)| *y -= c * r);
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A uniform number in [−1, 1) from a xorshift generator: reproducible test matrices.
    pub(crate) fn random(seed: &mut u64) -> f64 {
        *seed ^= *seed << 13;
        *seed ^= *seed >> 7;
        *seed ^= *seed << 17;
        (*seed >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    /// Against `f64::is_finite` number by number: every length up to 11 (all lanes and
    /// remainders), a non-finite number at every place, and finite numbers whose sum would
    /// overflow (which must still count as finite).
    #[test]
    fn all_finite_is_is_finite_of_every_number() {
        let mut cases = 0;
        for len in 0..12 {
            let big = vec![f64::MAX; len];
            assert!(all_finite(&big));
            let mut x: Vec<f64> = (0..len).map(|i| -(i as f64) * 1e300).collect();
            assert!(all_finite(&x));
            for at in 0..len {
                for bad in [f64::INFINITY, f64::NEG_INFINITY, f64::NAN] {
                    let keep = x[at];
                    x[at] = bad;
                    assert!(!all_finite(&x), "{bad} at {at} of {len}");
                    x[at] = keep;
                    cases += 1;
                }
            }
        }
        assert_eq!(cases, 3 * (0..12).sum::<usize>());
    }

    /// Against the plain formula where it cannot overflow, and against the exact value where
    /// it would.
    #[test]
    fn scaled_norm_matches_plain_and_survives_extremes() {
        assert_eq!(scaled_norm(&[3.0, 4.0]), 5.0);
        // The squares would overflow (underflow); the scaled form is good to a few ulps.
        let close = |x: f64, y: f64| (x - y).abs() <= 4.0 * f64::EPSILON * y;
        assert!(close(scaled_norm(&[3e200, 4e200]), 5e200));
        assert!(close(scaled_norm(&[3e-200, 4e-200]), 5e-200));
        assert!(close(scaled_norm(&[1e308, 1e308]), 1e308 * 2f64.sqrt()));
        assert_eq!(scaled_norm(&[]), 0.0);
        assert_eq!(scaled_norm(&[f64::INFINITY, 1.0]), f64::INFINITY);
    }

    /// ldexp is exact across the whole exponent range, and exponent_of brackets its input.
    #[test]
    fn ldexp_and_exponent_of() {
        assert_eq!(ldexp(1.5, 1500), 1.5 * 2f64.powi(1000) * 2f64.powi(500));
        assert_eq!(ldexp(ldexp(3.0, -1070), 1070), 3.0);
        for s in [1.0, 0.75, 3e300, 5e-324, 1e-310, f64::MAX] {
            let e = exponent_of(s);
            assert!(ldexp(1.0, e) <= s && s < ldexp(2.0, e), "{s:e}");
        }
    }

    #[test]
    fn max_abs_and_orthogonality_error() {
        assert_eq!(max_abs(&[1.0, -3.0, 2.0]), 3.0);
        let (s, c) = 0.3f64.sin_cos();
        let q = DMatrix::from_row_slice(2, 2, &[c, -s, s, c]);
        assert!(orthogonality_error(q.as_view()) < 1e-15);
        let m = DMatrix::from_row_slice(2, 2, &[2.0, 0.0, 0.0, 1.0]);
        assert_eq!(orthogonality_error(m.as_view()), 3.0);
        assert_eq!(max_abs_matrix(&m), 2.0);
    }
}
