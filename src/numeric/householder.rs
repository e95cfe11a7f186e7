//! Householder reflections (Golub & Van Loan, *Matrix Computations*, §5.1): an orthonormal
//! basis of the complement of two orthonormal vectors, stable even when they are near basis
//! vectors.

use super::dense::{Mat8, Vec8, dot};
use smallvec::SmallVec;

/// Returns an m × (m − 2) matrix whose orthonormal columns span the complement of the
/// orthonormal pair (w, u), from two Householder reflections (stable even when w and u are
/// near basis vectors). Inline, with no allocation, up to m = 9.
pub(crate) fn householder_complement(w: &[f64], u: &[f64]) -> Mat8 {
    let m = w.len();
    debug_assert!(m >= 2 && u.len() == m);
    // H1 maps w to ±e1.
    let h1 = householder(w, 0);
    // H2 acts on coordinates 1.. and maps (H1 u)[1..] to ±e2.
    let mut hu: Vec8 = SmallVec::from_slice(u);
    apply_householder(&h1, &mut hu);
    let h2 = householder(&hu, 1);
    // Q = H1 H2: apply H2 then H1 to each column of the identity; keep columns 2...
    let mut q = Mat8::zeros(m, m - 2);
    for c in 2..m {
        let col = q.column_mut(c - 2);
        col[c] = 1.0;
        apply_householder(&h2, col);
        apply_householder(&h1, col);
    }
    q
}

/// The unit vector h of the reflection I − 2 h hᵀ (h zero before `start`) that maps x to a
/// multiple of e_start; zero (the identity) if x vanishes from `start` on.
fn householder(x: &[f64], start: usize) -> Vec8 {
    let m = x.len();
    let mut h: Vec8 = SmallVec::from_elem(0.0, m);
    let tail_norm = x[start..].iter().map(|a| a * a).sum::<f64>().sqrt();
    if tail_norm == 0.0 {
        return h;
    }
    // h ∝ x − σ|x| e_start with σ = −sign(x_start), avoiding cancellation.
    let sigma = if x[start] >= 0.0 { -1.0 } else { 1.0 };
    h[start..].copy_from_slice(&x[start..]);
    h[start] -= sigma * tail_norm;
    let hn = h.iter().map(|a| a * a).sum::<f64>().sqrt();
    if hn > 0.0 {
        h.iter_mut().for_each(|a| *a /= hn);
    }
    h
}

/// x ← (I − 2 h hᵀ) x.
fn apply_householder(h: &[f64], x: &mut [f64]) {
    let d = dot(h, x);
    if d != 0.0 {
        x.iter_mut().zip(h).for_each(|(xi, hi)| *xi -= 2.0 * d * hi);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DMatrix;

    /// The columns are orthonormal and orthogonal to w and u (checked with nalgebra's
    /// products), also when w and u are basis vectors, where a naive reflection divides by
    /// zero; sizes 3 … 12, inline and spilled.
    #[test]
    fn complement_is_orthonormal_and_orthogonal_to_the_pair() {
        let c = std::f64::consts::FRAC_1_SQRT_2;
        let mut checked = 0;
        for m in 3..=12 {
            let e = |k: usize| -> Vec8 { (0..m).map(|i| f64::from(u8::from(i == k))).collect() };
            let w: Vec8 = (0..m).map(|_| 1.0 / (m as f64).sqrt()).collect();
            let mut u: Vec8 = SmallVec::from_elem(0.0, m);
            u[0] = c;
            u[1] = -c;
            for (w, u) in [(w, u), (e(0), e(1)), (e(m - 3), e(m - 1))] {
                let q = householder_complement(&w, &u);
                assert_eq!((q.nrows(), q.ncols()), (m, m - 2));
                let q = DMatrix::from_column_slice(m, m - 2, q.as_slice());
                let gram = q.transpose() * &q;
                let identity = DMatrix::<f64>::identity(m - 2, m - 2);
                assert!((gram - identity).amax() < 1e-15, "m = {m}");
                let pair = DMatrix::from_fn(m, 2, |i, j| if j == 0 { w[i] } else { u[i] });
                assert!((q.transpose() * pair).amax() < 1e-15, "m = {m}");
                checked += 1;
            }
        }
        assert_eq!(checked, 30);
    }
}
