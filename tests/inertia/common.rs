//! Helpers of the inertia tests: random matrices, a matrix closeness assertion, Monte Carlo
//! moment estimators and the Kuhn triangulation. Seeded randomness and `assert_close!` come
//! from the shared test support (`tests/support/mod.rs`) and are re-exported here.

#![allow(dead_code)]

use nalgebra::{DMatrix, DVector};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// Machine epsilon.
pub const EPS: f64 = f64::EPSILON;

pub use crate::support::{max_abs, max_abs_diff, random_bivector, rng};

/// Standard normal deviate by Box–Muller.
pub fn gaussian(rng: &mut ChaCha8Rng) -> f64 {
    let u1: f64 = 1.0 - rng.r#gen::<f64>(); // (0, 1]
    let u2: f64 = rng.r#gen::<f64>();
    (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
}

/// Uniform deviate in [lo, hi).
pub fn uniform(rng: &mut ChaCha8Rng, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * rng.r#gen::<f64>()
}

pub fn random_vector(n: usize, rng: &mut ChaCha8Rng) -> DVector<f64> {
    DVector::from_fn(n, |_, _| gaussian(rng))
}

/// Haar-ish random rotation: QR of a Gaussian matrix with the sign of R's diagonal fixed,
/// then det forced to +1.
pub fn random_rotation(n: usize, rng: &mut ChaCha8Rng) -> DMatrix<f64> {
    let a = DMatrix::from_fn(n, n, |_, _| gaussian(rng));
    let qr = a.qr();
    let mut q = qr.q();
    let r = qr.r();
    for k in 0..n {
        if r[(k, k)] < 0.0 {
            let col = -q.column(k);
            q.set_column(k, &col);
        }
    }
    if q.determinant() < 0.0 {
        let col = -q.column(0);
        q.set_column(0, &col);
    }
    q
}

/// Random symmetric positive definite matrix A Aᵀ + 0.1·1.
pub fn random_spd(n: usize, rng: &mut ChaCha8Rng) -> DMatrix<f64> {
    let a = DMatrix::from_fn(n, n, |_, _| gaussian(rng));
    &a * a.transpose() + DMatrix::identity(n, n) * 0.1
}

/// Random skew matrix.
pub fn random_skew(n: usize, rng: &mut ChaCha8Rng) -> DMatrix<f64> {
    let a = DMatrix::from_fn(n, n, |_, _| gaussian(rng));
    &a - a.transpose()
}

/// Asserts every entry of two matrices agrees within `tol`.
#[macro_export]
macro_rules! assert_matrix_close {
    ($a:expr, $b:expr, $tol:expr, $($msg:tt)+) => {{
        let a: &nalgebra::DMatrix<f64> = &$a;
        let b: &nalgebra::DMatrix<f64> = &$b;
        let tol: f64 = $tol;
        assert_eq!(a.shape(), b.shape(), "shape mismatch ({})", format!($($msg)+));
        let diff = $crate::common::max_abs_diff(a, b);
        assert!(
            diff <= tol,
            "matrices differ ({}): max |diff| = {diff:e} > tol = {tol:e}\nleft = {a}\nright = {b}",
            format!($($msg)+)
        );
    }};
}

/// Accumulates samples y (already relative to the analytic centre of mass) and estimates
/// E[y], E[y yᵀ] with standard errors.
pub struct MomentEstimator {
    n: usize,
    count: usize,
    sum: Vec<f64>,
    sum_sq: Vec<f64>,
    sum_prod: Vec<f64>,
    sum_prod_sq: Vec<f64>,
}

impl MomentEstimator {
    pub fn new(n: usize) -> Self {
        MomentEstimator {
            n,
            count: 0,
            sum: vec![0.0; n],
            sum_sq: vec![0.0; n],
            sum_prod: vec![0.0; n * n],
            sum_prod_sq: vec![0.0; n * n],
        }
    }

    pub fn add(&mut self, y: &[f64]) {
        self.count += 1;
        for i in 0..self.n {
            self.sum[i] += y[i];
            self.sum_sq[i] += y[i] * y[i];
            for j in 0..self.n {
                let p = y[i] * y[j];
                self.sum_prod[i * self.n + j] += p;
                self.sum_prod_sq[i * self.n + j] += p * p;
            }
        }
    }

    pub fn count(&self) -> usize {
        self.count
    }

    /// Checks E[y] = 0 and E[y yᵀ] = `expected` (J/m) within `k` standard errors per
    /// entry (plus 1e-14 absolute for entries with zero variance).
    pub fn check(&self, expected: &DMatrix<f64>, k: f64, label: &str) {
        let c = self.count as f64;
        for i in 0..self.n {
            let mean = self.sum[i] / c;
            let var = (self.sum_sq[i] / c - mean * mean).max(0.0);
            let se = (var / c).sqrt();
            assert!(
                mean.abs() <= k * se + 1e-14,
                "{label}: centre of mass coordinate {i}: MC mean {mean:e} vs 0, {k} SE = {:e}",
                k * se
            );
            for j in 0..self.n {
                let idx = i * self.n + j;
                let mean = self.sum_prod[idx] / c;
                let var = (self.sum_prod_sq[idx] / c - mean * mean).max(0.0);
                let se = (var / c).sqrt();
                let want = expected[(i, j)];
                assert!(
                    (mean - want).abs() <= k * se + 1e-14,
                    "{label}: J/m entry ({i},{j}): MC {mean:e} vs analytic {want:e}, diff {:e} > {k} SE = {:e}",
                    (mean - want).abs(),
                    k * se
                );
            }
        }
    }
}

/// The Kuhn (Freudenthal) triangulation of the unit cube [0,1]^N: N! simplices, one per
/// permutation σ, with vertices v₀ = 0, vₖ = vₖ₋₁ + e_{σ(k)}.
///
/// Returns (vertices as 0/1 bit patterns, simplices as vertex indices, permutation signs).
/// The determinant of simplex σ is sign(σ) (its edge matrix is a permutation matrix), so
/// half of the simplices are negatively oriented as listed.
pub fn kuhn_triangulation(n: usize) -> (Vec<DVector<f64>>, Vec<Vec<usize>>, Vec<f64>) {
    let vertices: Vec<DVector<f64>> = (0..1usize << n)
        .map(|bits| DVector::from_fn(n, |i, _| ((bits >> i) & 1) as f64))
        .collect();
    let mut simplices = Vec::new();
    let mut signs = Vec::new();
    let mut perm: Vec<usize> = (0..n).collect();
    permutations(&mut perm, 0, &mut |p| {
        let mut bits = 0usize;
        let mut simplex = vec![0usize];
        for &axis in p {
            bits |= 1 << axis;
            simplex.push(bits);
        }
        simplices.push(simplex);
        signs.push(permutation_sign(p));
    });
    (vertices, simplices, signs)
}

fn permutations(items: &mut Vec<usize>, k: usize, f: &mut dyn FnMut(&[usize])) {
    if k == items.len() {
        f(items);
        return;
    }
    for i in k..items.len() {
        items.swap(k, i);
        permutations(items, k + 1, f);
        items.swap(k, i);
    }
}

pub fn permutation_sign(p: &[usize]) -> f64 {
    let mut s = 1.0;
    for a in 0..p.len() {
        for b in a + 1..p.len() {
            if p[a] > p[b] {
                s = -s;
            }
        }
    }
    s
}

/// Γ(k/2) for k ≥ 1, from Γ(1/2) = √π, Γ(1) = 1 and Γ(x+1) = xΓ(x) (independent of the
/// crate's V_N recurrence).
pub fn gamma_half(k: usize) -> f64 {
    assert!(k >= 1);
    let (mut x, mut g) = if k.is_multiple_of(2) {
        (1.0, 1.0)
    } else {
        (0.5, std::f64::consts::PI.sqrt())
    };
    let target = k as f64 / 2.0;
    while x < target - 0.25 {
        g *= x;
        x += 1.0;
    }
    g
}

/// Composite Simpson rule on [a, b] with `intervals` (even) sub-intervals.
pub fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, intervals: usize) -> f64 {
    assert!(intervals.is_multiple_of(2));
    let h = (b - a) / intervals as f64;
    let mut s = f(a) + f(b);
    for i in 1..intervals {
        let x = a + i as f64 * h;
        s += if i % 2 == 1 { 4.0 } else { 2.0 } * f(x);
    }
    s * h / 3.0
}

/// Gauss–Legendre nodes and weights on [−1, 1] (Newton iteration on Pₙ from the Chebyshev
/// initial guess; nodes accurate to ~1 ulp for n ≤ 100).
pub fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut nodes = vec![0.0; n];
    let mut weights = vec![0.0; n];
    for i in 0..n {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut derivative = 0.0;
        for _ in 0..100 {
            // P_n(x) and P_n'(x) by the three-term recurrence.
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            let pn = if n == 0 { 1.0 } else { p1 };
            let pn_minus_1 = if n == 1 { 1.0 } else { p0 };
            derivative = n as f64 * (x * pn - pn_minus_1) / (x * x - 1.0);
            let dx = pn / derivative;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        nodes[i] = x;
        weights[i] = 2.0 / ((1.0 - x * x) * derivative * derivative);
    }
    (nodes, weights)
}
