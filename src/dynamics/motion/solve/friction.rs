//! Coulomb's law at one contact: the friction impulse of maximal dissipation.

use super::contact_row::{Small, dim, scratch};
use crate::dynamics::motion::placement::dot;

/// The friction impulse of maximal dissipation: with slip `ut` under the impulse `old`,
/// the sticking impulse old − K_t⁻¹ ut when |·| ≤ `limit`, else the J on the rim |J| = limit
/// with (K_t + σ) J = K_t old − ut for the σ ≥ 0 that puts it there, so that the slip left,
/// K_t (J − old) + ut = −σ J, is exactly opposite to J. K_t = V diag(d) Vᵀ is given by its
/// eigen-decomposition; σ comes from Newton's method on 1/|J(σ)| − 1/limit, which is
/// nearly linear in σ and converges from σ = 0 without overshooting (Moré–Sorensen).
///
/// `N` as in [`dim`]: 3 or 4 for kernels of a fixed dimension, 0 for any.
#[inline(always)]
pub(super) fn friction_impulse<const N: usize>(
    d: &[f64],
    v: &[f64],
    kt: &[f64],
    old: &[f64],
    ut: &[f64],
    limit: f64,
    out: &mut [f64],
) {
    let n = dim::<N>(d.len());
    let (d, v, kt) = (&d[..n], &v[..n * n], &kt[..n * n]);
    // c = Vᵀ b, b = K_t old − ut.
    let (mut b_fixed, mut b_any) = ([0.0; 4], Small::new());
    let b = scratch::<N>(&mut b_fixed, &mut b_any, n);
    for (i, x) in b.iter_mut().enumerate() {
        *x = dot(&kt[i * n..(i + 1) * n], &old[..n]) - ut[i];
    }
    let (mut c_fixed, mut c_any) = ([0.0; 4], Small::new());
    let c = scratch::<N>(&mut c_fixed, &mut c_any, n);
    for (row, bi) in v.chunks_exact(n).zip(b.iter()) {
        for (x, vik) in c.iter_mut().zip(row) {
            *x += vik * bi;
        }
    }
    let size = |sigma: f64| -> (f64, f64) {
        let (mut s2, mut s3) = (0.0, 0.0);
        for k in 0..n {
            let q = c[k] / (d[k] + sigma);
            s2 += q * q;
            s3 += q * q / (d[k] + sigma);
        }
        (s2.sqrt(), s3)
    };
    let (norm0, _) = size(0.0);
    let sigma = if norm0 <= limit {
        0.0
    } else {
        let mut sigma = 0.0f64;
        let mut last = f64::INFINITY;
        for _ in 0..60 {
            let (norm, s3) = size(sigma);
            let psi = 1.0 / norm - 1.0 / limit;
            let step = psi * norm * norm * norm / s3;
            sigma -= step;
            // Converged, or at round-off: Newton's steps shrink until then, and a step no
            // smaller than the last one is noise (waiting for 1e-15 there took all 60).
            if step.abs() <= 1e-15 * sigma.abs() || step.abs() >= last {
                break;
            }
            last = step.abs();
        }
        sigma.max(0.0)
    };
    let (norm, _) = size(sigma);
    let scale = if sigma > 0.0 { limit / norm } else { 1.0 };
    for (k, x) in c.iter_mut().enumerate() {
        *x /= d[k] + sigma;
    }
    for (i, x) in out[..n].iter_mut().enumerate() {
        *x = scale * dot(&v[i * n..(i + 1) * n], c);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Off the disc, the friction impulse is the trust-region step of Coulomb's law: |J| is
    /// the limit and the slip left after it, K_t (J − old) + ut, is −σ J with σ > 0 (exactly
    /// opposite to the friction), for a limit near zero, small and near the sticking size.
    #[test]
    fn rim_impulse_leaves_the_slip_opposite_to_it() {
        let n = 4;
        // K_t = V diag(d) Vᵀ, V a rotation of 4-space (two plane rotations), the normal
        // (the last axis) kept apart with eigenvalue 1 as `tangent_block` keeps it.
        let (c1, s1, c2, s2) = (0.8f64, 0.6f64, 0.28f64, 0.96f64);
        #[rustfmt::skip]
        let v = [
            c1, -s1, 0.0, 0.0,
            s1 * c2, c1 * c2, -s2, 0.0,
            s1 * s2, c1 * s2, c2, 0.0,
            0.0, 0.0, 0.0, 1.0,
        ];
        let d = [0.7, 1.9, 3.1, 1.0];
        let mut kt = [0.0; 16];
        for i in 0..n {
            for j in 0..n {
                kt[i * n + j] = (0..n).map(|k| v[i * n + k] * d[k] * v[j * n + k]).sum();
            }
        }
        let (old, ut) = ([0.3, -0.2, 0.1, 0.0], [1.1, 0.4, -0.7, 0.0]);
        let mut checked = 0;
        for limit in [1e-6, 0.05, 0.4] {
            let mut j = [0.0; 4];
            friction_impulse::<0>(&d, &v, &kt, &old, &ut, limit, &mut j);
            let norm = dot(&j, &j).sqrt();
            assert!(
                (norm - limit).abs() <= 1e-13 * limit,
                "limit {limit}: |J| = {norm}"
            );
            let slip: Vec<f64> = (0..n)
                .map(|i| (0..n).map(|k| kt[i * n + k] * (j[k] - old[k])).sum::<f64>() + ut[i])
                .collect();
            let sigma = -dot(&slip, &j) / (norm * norm);
            assert!(sigma > 0.0, "limit {limit}: σ = {sigma}");
            for i in 0..n {
                assert!(
                    (slip[i] + sigma * j[i]).abs() <= 1e-12 * (1.0 + sigma * limit),
                    "limit {limit}, row {i}: slip {slip:?}, J {j:?}"
                );
            }
            checked += 1;
        }
        assert_eq!(checked, 3);
    }
}
