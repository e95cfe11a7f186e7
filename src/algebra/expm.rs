//! The matrix exponential of skew matrices, for any fixed or run-time size: the rotation
//! matrix of a rotor exponential without the rotor (attitudes above N = 4, N > 16).

use nalgebra::{DMatrix, DefaultAllocator, Dim, DimMin, OMatrix, allocator::Allocator};

/// Higham's Padé coefficients b₀…b_m (Higham, SIAM J. Matrix Anal. Appl. 26 (2005) 1179,
/// eq. 2.3 / Table 2.2).
const PADE_3: [f64; 4] = [120.0, 60.0, 12.0, 1.0];
const PADE_5: [f64; 6] = [30240.0, 15120.0, 3360.0, 420.0, 30.0, 1.0];
const PADE_7: [f64; 8] = [
    17297280.0, 8648640.0, 1995840.0, 277200.0, 25200.0, 1512.0, 56.0, 1.0,
];
const PADE_9: [f64; 10] = [
    17643225600.0,
    8821612800.0,
    2075673600.0,
    302702400.0,
    30270240.0,
    2162160.0,
    110880.0,
    3960.0,
    90.0,
    1.0,
];
const PADE_13: [f64; 14] = [
    64764752532480000.0,
    32382376266240000.0,
    7771770303897600.0,
    1187353796428800.0,
    129060195264000.0,
    10559470521600.0,
    670442572800.0,
    33522128640.0,
    1323241920.0,
    40840800.0,
    960960.0,
    16380.0,
    182.0,
    1.0,
];
/// The 1-norm bounds θ_m below which the degree-m approximant has backward error ≤ 2⁻⁵³
/// (Higham 2005, Table 2.3).
const THETA: [(usize, f64); 4] = [
    (3, 1.495585217958292e-2),
    (5, 2.53939833006323e-1),
    (7, 9.504178996162932e-1),
    (9, 2.097847961257068),
];
const THETA_13: f64 = 5.371920351148152;

/// The largest ‖A‖₁ that [`expm_skew`] accepts (θ₁₃).
pub(crate) const PADE_MAX_NORM: f64 = THETA_13;

/// Returns expm(A) for a skew matrix A with 1-norm `norm1` (> 0, finite) by the diagonal
/// Padé approximant r_m = q_m(A)⁻¹ p_m(A) of the lowest degree m ∈ {3, 5, 7, 9, 13} whose
/// backward error is below the unit round-off at that norm (Higham 2005, Algorithm 2.3,
/// without its scaling and squaring). For skew A, q_m(A) = p_m(A)ᵀ, so r_m(A) is orthogonal
/// in exact arithmetic and to round-off in practice.
///
/// `None` above ‖A‖₁ = θ₁₃ ≈ 5.37: squaring would multiply the round-off (and the departure
/// from orthogonality) by 2^s ~ ‖A‖, so large rotations go plane by plane through the
/// invariant decomposition (`Bivector::exp_skew_matrix`), which reduces every plane's angle
/// on its own and stays orthogonal to ε at any angle. Also `None` if the denominator is
/// numerically singular (not expected).
///
/// Generic over the size so that fixed sizes (N ≤ 8) run on the stack.
pub(crate) fn expm_skew<D: Dim + DimMin<D, Output = D>>(
    a: &OMatrix<f64, D, D>,
    norm1: f64,
) -> Option<OMatrix<f64, D, D>>
where
    DefaultAllocator: Allocator<D, D> + Allocator<D>,
{
    if norm1 > THETA_13 {
        return None;
    }
    let (rows, cols) = a.shape_generic();
    let id = OMatrix::<f64, D, D>::identity_generic(rows, cols);
    let a2 = a * a;
    let (u, v) = if let Some(&(m, _)) = THETA.iter().find(|(_, t)| norm1 <= *t) {
        let b: &[f64] = match m {
            3 => &PADE_3,
            5 => &PADE_5,
            7 => &PADE_7,
            _ => &PADE_9,
        };
        // U = A Σ_odd b_k A^{k−1}, V = Σ_even b_k A^k.
        let mut u_inner = &id * b[1];
        let mut v = &id * b[0];
        let mut power = id.clone();
        for k in (2..b.len()).step_by(2) {
            power = &power * &a2;
            v += &power * b[k];
            u_inner += &power * b[k + 1];
        }
        (a * u_inner, v)
    } else {
        let a4 = &a2 * &a2;
        let a6 = &a4 * &a2;
        let b = &PADE_13;
        let u_high = &a6 * (&a6 * b[13] + &a4 * b[11] + &a2 * b[9]);
        let u = a * (u_high + &a6 * b[7] + &a4 * b[5] + &a2 * b[3] + &id * b[1]);
        let v_high = &a6 * (&a6 * b[12] + &a4 * b[10] + &a2 * b[8]);
        let v = v_high + &a6 * b[6] + &a4 * b[4] + &a2 * b[2] + &id * b[0];
        (u, v)
    };
    (&v - &u).lu().solve(&(&v + &u))
}

/// Returns the 1-norm (largest column sum of |aᵢⱼ|).
pub(crate) fn norm1<D: Dim>(a: &OMatrix<f64, D, D>) -> f64
where
    DefaultAllocator: Allocator<D, D>,
{
    a.column_iter()
        .map(|c| c.iter().map(|x| x.abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

/// expm(A) for skew A from the eigen-decomposition of S = −A² = AᵀA = V diag(θₖ²) Vᵀ:
/// expm(A) = V diag(cos θₖ) Vᵀ + A V diag(sin θₖ/θₖ) Vᵀ (the fallback if the Padé
/// denominator is singular; no eigenvector pairing is needed, since both terms are functions
/// of θₖ²). Orthogonal to ε·max(1, θ): a pair of equal angles comes back as two eigenvalues
/// θ² that differ by ε‖A‖², which is why large rotations go plane by plane instead.
pub(crate) fn expm_spectral(a: &DMatrix<f64>) -> DMatrix<f64> {
    let (eigenvalues, v) = super::symmetric_eigen(a.transpose() * a);
    let mut vc = v.clone();
    let mut vs = v.clone();
    for (k, &lambda) in eigenvalues.iter().enumerate() {
        let lambda = lambda.max(0.0);
        let theta = lambda.sqrt();
        let sinc = if theta < 1e-4 {
            1.0 - lambda / 6.0 + lambda * lambda / 120.0
        } else {
            theta.sin() / theta
        };
        vc.column_mut(k).scale_mut(theta.cos());
        vs.column_mut(k).scale_mut(sinc);
    }
    let vt = v.transpose();
    &vc * &vt + a * (&vs * &vt)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Padé path and the spectral form agree for every degree; beyond θ₁₃ the Padé path
    /// declines.
    #[test]
    fn pade_matches_spectral_for_every_degree() {
        let skew = |scale: f64| {
            let n = 7;
            let mut a = DMatrix::<f64>::zeros(n, n);
            for i in 0..n {
                for j in i + 1..n {
                    let x = scale * ((i * 7 + j * 3) as f64).sin() / n as f64;
                    a[(i, j)] = x;
                    a[(j, i)] = -x;
                }
            }
            a
        };
        let id = DMatrix::<f64>::identity(7, 7);
        for scale in [1e-3, 0.01, 0.1, 0.5, 1.0, 2.0] {
            let a = skew(scale);
            let p = expm_skew(&a, norm1(&a)).expect("within θ₁₃");
            let s = expm_spectral(&a);
            let err = (&p - &s).amax();
            assert!(err < 1e-14, "scale {scale}: {err:e}");
            let orth = (p.transpose() * &p - &id).amax();
            assert!(orth < 1e-14, "scale {scale}: |QᵀQ − 1| = {orth:e}");
        }
        let big = skew(1e6);
        assert!(expm_skew(&big, norm1(&big)).is_none());
    }
}
