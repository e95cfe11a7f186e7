//! The baseline of the dynamics benches, shared by `benches/dynamics.rs` and the examples
//! that compare against it (`#[path]`-included): RK4 on the matrix equations with nalgebra's
//! dynamic matrices, the paper's tensor formulation.

use nalgebra::DMatrix;

/// One RK4 step on (M, Q): Ω = M ⊘ (Jᵢ + Jⱼ) (`inv` holds 1/(Jᵢ + Jⱼ)), dM = ΩM − MΩ,
/// dQ = QΩᵀ. Plain RK4: Q leaves SO(N) (see `examples/matrix_rk4_drift.rs`).
pub fn dmatrix_rk4(m: &mut DMatrix<f64>, q: &mut DMatrix<f64>, inv: &DMatrix<f64>, h: f64) {
    let f = |m: &DMatrix<f64>, q: &DMatrix<f64>| {
        let w = m.component_mul(inv);
        (&w * m - m * &w, q * w.transpose())
    };
    let (k1m, k1q) = f(m, q);
    let (k2m, k2q) = f(&(&*m + &k1m * (0.5 * h)), &(&*q + &k1q * (0.5 * h)));
    let (k3m, k3q) = f(&(&*m + &k2m * (0.5 * h)), &(&*q + &k2q * (0.5 * h)));
    let (k4m, k4q) = f(&(&*m + &k3m * h), &(&*q + &k3q * h));
    *m += (k1m + k2m * 2.0 + k3m * 2.0 + k4m) * (h / 6.0);
    *q += (k1q + k2q * 2.0 + k3q * 2.0 + k4q) * (h / 6.0);
}

/// 1/(Jᵢ + Jⱼ) off the diagonal, 0 on it.
pub fn inverse_plane_moments(j: &[f64]) -> DMatrix<f64> {
    let n = j.len();
    DMatrix::from_fn(n, n, |a, b| if a == b { 0.0 } else { 1.0 / (j[a] + j[b]) })
}
