//! The matrix exponential of skew matrices, for any fixed or run-time size: the rotation
//! matrix of a rotor exponential without the rotor (attitudes above N = 4, N > 16).

use nalgebra::{DMatrix, DefaultAllocator, Dim, DimMin, OMatrix, SMatrix, allocator::Allocator};

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
/// Generic over the size so that fixed sizes run on the stack; for N ≤ 8 known at compile
/// time [`expm_skew_fixed`] solves faster.
pub(crate) fn expm_skew<D: Dim + DimMin<D, Output = D>>(
    a: &OMatrix<f64, D, D>,
    norm1: f64,
) -> Option<OMatrix<f64, D, D>>
where
    DefaultAllocator: Allocator<D, D> + Allocator<D>,
{
    let (u, v) = pade_skew(a, norm1)?;
    (&v - &u).lu().solve(&(&v + &u))
}

/// [`expm_skew`] for a size N known at compile time: the same approximant, and the system
/// q_m(A) X = p_m(A) solved by [`solve_fixed`].
pub(crate) fn expm_skew_fixed<const N: usize>(
    a: &SMatrix<f64, N, N>,
    norm1: f64,
) -> Option<SMatrix<f64, N, N>> {
    let (u, v) = pade_skew(a, norm1)?;
    let mut q = [[0.0f64; N]; N];
    let mut x = [[0.0f64; N]; N];
    for i in 0..N {
        for j in 0..N {
            q[i][j] = v[(i, j)] - u[(i, j)];
            x[i][j] = v[(i, j)] + u[(i, j)];
        }
    }
    solve_fixed(&mut q, &mut x).then(|| SMatrix::from_fn(|i, j| x[i][j]))
}

/// Solves Q X = P in place (`x` holds P on entry, X on return; both row-major) by Gaussian
/// elimination with partial pivoting, what an LU solve does, with every row operation a
/// loop of the fixed length N that the compiler unrolls and vectorises. False when a pivot
/// is zero or not finite.
fn solve_fixed<const N: usize>(q: &mut [[f64; N]; N], x: &mut [[f64; N]; N]) -> bool {
    for k in 0..N {
        let mut pivot = k;
        for i in k + 1..N {
            if q[i][k].abs() > q[pivot][k].abs() {
                pivot = i;
            }
        }
        let d = q[pivot][k];
        if !(d != 0.0 && d.is_finite()) {
            return false;
        }
        q.swap(k, pivot);
        x.swap(k, pivot);
        let (top_q, top_x) = (q[k], x[k]);
        // One division per pivot: the rows' factors and the back substitution multiply.
        let inv = 1.0 / d;
        for i in k + 1..N {
            let f = q[i][k] * inv;
            for j in 0..N {
                q[i][j] -= f * top_q[j];
                x[i][j] -= f * top_x[j];
            }
        }
    }
    for k in (0..N).rev() {
        let mut row = x[k];
        for l in k + 1..N {
            let u = q[k][l];
            for j in 0..N {
                row[j] -= u * x[l][j];
            }
        }
        let inv = 1.0 / q[k][k];
        for r in &mut row {
            *r *= inv;
        }
        x[k] = row;
    }
    true
}

/// A square matrix of size D.
type Square<D> = OMatrix<f64, D, D>;

/// The numerator and denominator parts (U, V) of [`expm_skew`]'s approximant,
/// p_m(A) = V + U and q_m(A) = V − U; None above θ₁₃.
fn pade_skew<D: Dim>(a: &OMatrix<f64, D, D>, norm1: f64) -> Option<(Square<D>, Square<D>)>
where
    DefaultAllocator: Allocator<D, D>,
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
        // U = A Σ_odd b_k A^{k−1}, V = Σ_even b_k A^k, from the powers A², A⁴, … (the first
        // is A² itself: no product with the identity).
        let mut u_inner = &id * b[1];
        let mut v = &id * b[0];
        let mut power = a2.clone();
        for k in (2..b.len()).step_by(2) {
            if k > 2 {
                power = &power * &a2;
            }
            let entries = v.as_mut_slice().iter_mut().zip(u_inner.as_mut_slice());
            for ((x, y), p) in entries.zip(power.as_slice()) {
                *x += b[k] * p;
                *y += b[k + 1] * p;
            }
        }
        (a * u_inner, v)
    } else {
        let a4 = &a2 * &a2;
        let a6 = &a4 * &a2;
        let b = &PADE_13;
        // Each linear combination of the three powers in one pass over the entries, and the
        // products with A⁶ accumulated in place (gemm).
        let comb = |x: f64, y: f64, z: f64| {
            let mut out = a2.clone();
            let powers = a6.as_slice().iter().zip(a4.as_slice());
            for (o, (p, q)) in out.as_mut_slice().iter_mut().zip(powers) {
                *o = x * p + y * q + z * *o;
            }
            out
        };
        let mut u_inner = comb(b[7], b[5], b[3]);
        u_inner.gemm(1.0, &a6, &comb(b[13], b[11], b[9]), 1.0);
        let mut v = comb(b[6], b[4], b[2]);
        v.gemm(1.0, &a6, &comb(b[12], b[10], b[8]), 1.0);
        for d in 0..a.nrows() {
            u_inner[(d, d)] += b[1];
            v[(d, d)] += b[0];
        }
        (a * u_inner, v)
    };
    Some((u, v))
}

/// Taylor degrees for [`expm_skew_taylor`]: (m, s, θ_m) with θ_m the largest ‖A‖₂ at which
/// the truncation error Σ_(k>m) θᵏ/k! ≤ θᵐ⁺¹/(m+1)! / (1 − θ/(m+2)) stays below 2⁻⁵³,
/// and s the Paterson–Stockmeyer block size, so that degree m = s·r costs (s − 1) + (r − 1)
/// products: 3, 4, 5 and 6.
const TAYLOR: [(usize, usize, f64); 4] = [
    (6, 3, 0.01776452568877372),
    (9, 3, 0.11483164143919657),
    (12, 4, 0.33521266165713876),
    (16, 4, 0.8245973807169157),
];

/// 1/k! for k = 0 … 16.
const INV_FACTORIAL: [f64; 17] = {
    let mut t = [1.0; 17];
    let mut k = 1;
    while k < 17 {
        t[k] = t[k - 1] / k as f64;
        k += 1;
    }
    t
};

/// Returns expm(A) for a skew matrix A with 1-norm `norm1` by its Taylor polynomial T_m(A),
/// evaluated by Paterson and Stockmeyer's scheme (Higham, *Functions of Matrices*, 2008,
/// §4.4.3) with products only: no linear solve. `None` when ‖A‖₂ may exceed θ₁₆ ≈ 0.82
/// (use [`expm_skew`] there).
///
/// A skew A is normal, so ‖e^A − T_m(A)‖₂ = maxₖ |e^(iθₖ) − T_m(iθₖ)| ≤ Σ_(k>m) θᵏ/k! with
/// θ = ‖A‖₂ ≤ ρ = min(‖A‖₁, ‖A²‖₁^(1/2)); the degree is the lowest whose bound at ρ is below
/// the unit round-off, so the result is orthogonal to round-off like the Padé form. For the
/// small exponentials of integrator steps this is the cheaper form: at N = 16 the Padé
/// approximant's LU solve cost more than all its products.
pub(crate) fn expm_skew_taylor<D: Dim>(
    a: &OMatrix<f64, D, D>,
    norm1: f64,
) -> Option<OMatrix<f64, D, D>>
where
    DefaultAllocator: Allocator<D, D>,
{
    let n = a.nrows();
    // ‖A²‖₁ ≥ maxⱼ |(A²)ⱼⱼ| = maxⱼ ‖aⱼ‖₂² ≥ (‖A‖₁/√N)², so no degree applies when
    // ‖A‖₁/√N > θ₁₆: known without forming A².
    if norm1 / (n as f64).sqrt() > TAYLOR[TAYLOR.len() - 1].2 {
        return None;
    }
    let mut out = a.clone();
    let done = if D::try_to_usize().is_some() {
        // Fixed sizes (N ≤ 8 in this crate): the scratch stays on the stack.
        let mut scratch: smallvec::SmallVec<[f64; 256]> = smallvec::SmallVec::new();
        scratch.resize(4 * n * n, 0.0);
        taylor_into::<D>(
            n,
            a.as_slice(),
            norm1,
            out.as_mut_slice(),
            &mut scratch,
            n * n,
        )
    } else {
        expm_skew_taylor_dense(n, a.as_slice(), norm1, out.as_mut_slice())
    };
    done.then_some(out)
}

/// [`expm_skew_taylor`] for a run-time size on column-major slices: writes expm(A) into `out`
/// and returns true, or returns false (`out` unspecified) when ‖A‖₂ may exceed θ₁₆. The
/// scratch is reused between calls (an integrator takes one exponential per step), its parts
/// spaced off multiples of 4096 bytes (4K aliasing).
pub(crate) fn expm_skew_taylor_dense(n: usize, a: &[f64], norm1: f64, out: &mut [f64]) -> bool {
    thread_local! {
        static SCRATCH: std::cell::RefCell<Vec<f64>> = const { std::cell::RefCell::new(Vec::new()) };
    }
    let stride = n * n + 24;
    let mut run = |scratch: &mut Vec<f64>| {
        scratch.resize(4 * stride, 0.0);
        taylor_into::<nalgebra::Dyn>(n, a, norm1, out, scratch, stride)
    };
    SCRATCH.with(|cell| match cell.try_borrow_mut() {
        Ok(mut scratch) => run(&mut scratch),
        Err(_) => run(&mut Vec::new()),
    })
}

/// The body of [`expm_skew_taylor`] on column-major slices: writes T_m(A) into `out` and
/// returns true, or returns false when ρ > θ₁₆. `scratch` holds four N×N parts `stride`
/// apart: A², A³, A⁴ and a product.
fn taylor_into<D: Dim>(
    n: usize,
    a: &[f64],
    norm1: f64,
    out: &mut [f64],
    scratch: &mut [f64],
    stride: usize,
) -> bool
where
    DefaultAllocator: Allocator<D, D>,
{
    let nn = n * n;
    let mut parts = scratch.chunks_mut(stride).map(|part| &mut part[..nn]);
    let (Some(a2), Some(a3), Some(a4), Some(product)) =
        (parts.next(), parts.next(), parts.next(), parts.next())
    else {
        unreachable!("four parts");
    };
    mul::<D>(n, a, a, a2);
    let rho = norm1.min(norm1_slice(n, a2).sqrt());
    let Some(&(m, s, _)) = TAYLOR.iter().find(|&&(_, _, theta)| rho <= theta) else {
        return false;
    };
    if s >= 3 {
        mul::<D>(n, a2, a, a3);
    }
    if s >= 4 {
        mul::<D>(n, a3, a, a4);
    }
    let powers: [&[f64]; 4] = [a, a2, a3, a4];
    // T = Σⱼ (Aˢ)ʲ Bⱼ with Bⱼ = Σ_{i<s} c_{js+i} Aⁱ; B_r = c_m I, so Horner starts from
    // c_m Aˢ + B_{r−1}.
    let add_block = |p: &mut [f64], j: usize| {
        for d in 0..n {
            p[d * n + d] += INV_FACTORIAL[j * s];
        }
        for (i, power) in powers.iter().enumerate().take(s - 1) {
            let c = INV_FACTORIAL[j * s + i + 1];
            p.iter_mut().zip(*power).for_each(|(x, y)| *x += c * y);
        }
    };
    let r = m / s;
    let a_s = powers[s - 1];
    out.iter_mut()
        .zip(a_s)
        .for_each(|(o, x)| *o = INV_FACTORIAL[m] * x);
    add_block(out, r - 1);
    for j in (0..r - 1).rev() {
        mul::<D>(n, a_s, out, product);
        out.copy_from_slice(product);
        add_block(out, j);
    }
    true
}

/// out = x y for column-major N×N slices. Fixed sizes use nalgebra's unrolled product on
/// the stack (faster than its gemm at N ≤ 8); run-time sizes its gemm (matrixmultiply) on
/// views, writing into `out` without allocating.
#[inline]
fn mul<D: Dim>(n: usize, x: &[f64], y: &[f64], out: &mut [f64])
where
    DefaultAllocator: Allocator<D, D>,
{
    if D::try_to_usize().is_some() {
        let d = D::from_usize(n);
        let xv = nalgebra::MatrixView::<f64, D, D>::from_slice_generic(x, d, d);
        let yv = nalgebra::MatrixView::<f64, D, D>::from_slice_generic(y, d, d);
        out.copy_from_slice((xv * yv).as_slice());
    } else {
        nalgebra::DMatrixViewMut::from_slice(out, n, n).gemm(
            1.0,
            &nalgebra::DMatrixView::from_slice(x, n, n),
            &nalgebra::DMatrixView::from_slice(y, n, n),
            0.0,
        );
    }
}

/// The 1-norm of a column-major N×N slice.
pub(crate) fn norm1_slice(n: usize, x: &[f64]) -> f64 {
    x.chunks_exact(n.max(1))
        .map(|c| c.iter().map(|v| v.abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

/// Returns the 1-norm (largest column sum of |aᵢⱼ|).
pub(crate) fn norm1<D: Dim>(a: &OMatrix<f64, D, D>) -> f64
where
    DefaultAllocator: Allocator<D, D>,
{
    // Column slices of the contiguous storage (nalgebra's strided iterators do not vectorise).
    a.as_slice()
        .chunks_exact(a.nrows().max(1))
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

    /// The fixed-size solve gives the LU solve's exponential, orthogonal, at every degree
    /// and every fixed N (5 … 8), and the solve itself matches nalgebra's LU on a matrix
    /// that needs pivoting.
    #[test]
    fn fixed_size_solve_matches_the_lu_solve() {
        fn check<const N: usize>(checked: &mut usize) {
            for scale in [1e-3, 0.1, 1.0, 2.0, 4.0, 5.3] {
                let mut a = SMatrix::<f64, N, N>::zeros();
                for i in 0..N {
                    for j in i + 1..N {
                        let x = ((i * 7 + j * 3) as f64).sin();
                        a[(i, j)] = x;
                        a[(j, i)] = -x;
                    }
                }
                let a = a * (scale / norm1(&a));
                let fixed = expm_skew_fixed(&a, norm1(&a)).expect("within θ₁₃");
                let dense = DMatrix::from_column_slice(N, N, a.as_slice());
                let lu = expm_skew(&dense, norm1(&dense)).expect("within θ₁₃");
                let err = (DMatrix::from_column_slice(N, N, fixed.as_slice()) - lu).amax();
                assert!(err < 1e-15, "N = {N}, ‖A‖₁ = {scale}: {err:e}");
                let orth = (fixed.transpose() * fixed - SMatrix::<f64, N, N>::identity()).amax();
                assert!(orth < 1e-14, "N = {N}: |QᵀQ − 1| = {orth:e}");
                *checked += 1;
            }
            // A zero leading entry forces a row exchange.
            let q = SMatrix::<f64, N, N>::from_fn(|i, j| {
                if i == j && i == 0 {
                    0.0
                } else {
                    ((i * N + j) as f64 * 0.61).cos() + if i == j { 3.0 } else { 0.0 }
                }
            });
            let p = SMatrix::<f64, N, N>::from_fn(|i, j| ((i + 2 * j) as f64).sin());
            let (mut qr, mut x) = ([[0.0; N]; N], [[0.0; N]; N]);
            for i in 0..N {
                for j in 0..N {
                    (qr[i][j], x[i][j]) = (q[(i, j)], p[(i, j)]);
                }
            }
            assert!(solve_fixed(&mut qr, &mut x));
            let dense = |m: &SMatrix<f64, N, N>| DMatrix::from_column_slice(N, N, m.as_slice());
            let want = dense(&q).lu().solve(&dense(&p)).unwrap();
            let got = SMatrix::<f64, N, N>::from_fn(|i, j| x[i][j]);
            let err = (dense(&got) - want).amax();
            assert!(err < 1e-13, "N = {N}: solve off by {err:e}");
            *checked += 1;
        }
        let mut checked = 0;
        check::<5>(&mut checked);
        check::<6>(&mut checked);
        check::<7>(&mut checked);
        check::<8>(&mut checked);
        assert_eq!(checked, 28);
    }

    /// The Taylor form agrees with the spectral form at every degree, is orthogonal, and
    /// declines above θ₁₆.
    #[test]
    fn taylor_matches_spectral_for_every_degree() {
        let n = 9;
        let id = DMatrix::<f64>::identity(n, n);
        let skew = |scale: f64| {
            DMatrix::from_fn(n, n, |i, j| {
                let x = scale * ((i * 5 + j * 11) as f64).cos() / n as f64;
                if i < j {
                    x
                } else if i > j {
                    -scale * ((j * 5 + i * 11) as f64).cos() / n as f64
                } else {
                    0.0
                }
            })
        };
        let mut degrees = Vec::new();
        for scale in [1e-6, 1e-3, 0.01, 0.05, 0.1, 0.3, 0.6, 1.0] {
            let a = skew(scale);
            let a2 = &a * &a;
            let rho = norm1(&a).min(norm1(&a2).sqrt());
            let Some(t) = expm_skew_taylor(&a, norm1(&a)) else {
                assert!(rho > TAYLOR[3].2, "declined at ρ = {rho}");
                continue;
            };
            degrees.push(TAYLOR.iter().find(|d| rho <= d.2).unwrap().0);
            let err = (&t - &expm_spectral(&a)).amax();
            assert!(err < 2e-15, "scale {scale}: {err:e}");
            let orth = (t.transpose() * &t - &id).amax();
            assert!(orth < 2e-15, "scale {scale}: |QᵀQ − 1| = {orth:e}");
        }
        degrees.dedup();
        assert_eq!(degrees, [6, 9, 12, 16], "every degree exercised");
        assert!(expm_skew_taylor(&skew(3.0), norm1(&skew(3.0))).is_none());
    }
}
