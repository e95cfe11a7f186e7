//! Every analytic solid (cuboid, ellipsoid, ball, shell, simplex) against an independent
//! seeded Monte Carlo integration in N = 2…6.
//!
//! Tolerance: each entry of the estimated E[y] and E[y yᵀ] (y = sample − analytic centre)
//! must be within K = 5 standard errors of the analytic value, where the standard error is
//! the sample standard deviation of that entry over √(sample count). For a correct formula a
//! single entry fails with probability 5.7e-7 (two-sided normal tail at 5σ); with about 500
//! entries over all tests the chance of a spurious failure for some seed is below 3e-4, and
//! the seeds are fixed, so the outcome is deterministic. With 100 000 samples, 5 SE is about
//! 1.5 % of a diagonal entry, enough to tell 1/(N+2) from 1/(N+3) in every N tested.
use crate::common::{MomentEstimator, gamma_half, gaussian, rng, uniform};
use nalgebra::{DMatrix, DVector};
use rand::Rng;
use rotorflow::inertia::Body;

const SAMPLES: usize = 100_000;
const K: f64 = 5.0;

fn normalised_j(body: &Body) -> DMatrix<f64> {
    body.mass_tensor() / body.mass()
}

#[test]
fn solid_cuboid_matches_monte_carlo_n2_to_n6() {
    for n in 2..=6 {
        let half: Vec<f64> = (0..n).map(|i| 0.5 + 0.3 * i as f64).collect();
        let body = Body::solid_cuboid(&half, 2.5).unwrap();
        let mut r = rng(100 + n as u64);
        let mut est = MomentEstimator::new(n);
        let mut y = vec![0.0; n];
        for _ in 0..SAMPLES {
            for i in 0..n {
                y[i] = uniform(&mut r, -half[i], half[i]);
            }
            est.add(&y);
        }
        est.check(&normalised_j(&body), K, &format!("cuboid N={n}"));
        let expected_volume: f64 = half.iter().map(|a| 2.0 * a).product();
        assert_close!(
            body.volume().unwrap(),
            expected_volume,
            1e-14 * expected_volume
        );
        assert_close!(body.mass(), 2.5 * expected_volume, 1e-14 * body.mass());
    }
}

/// Rejection sampling from the bounding box: the acceptance rate estimates the volume
/// (binomial standard error), the accepted points estimate J/m.
fn check_ellipsoid_by_rejection(body: &Body, semi_axes: &[f64], seed: u64, label: &str) {
    let n = semi_axes.len();
    let mut r = rng(seed);
    let mut est = MomentEstimator::new(n);
    let mut y = vec![0.0; n];
    let mut drawn = 0usize;
    while est.count() < SAMPLES {
        drawn += 1;
        let mut q = 0.0;
        for i in 0..n {
            y[i] = uniform(&mut r, -semi_axes[i], semi_axes[i]);
            q += (y[i] / semi_axes[i]).powi(2);
        }
        if q <= 1.0 {
            est.add(&y);
        }
    }
    est.check(&normalised_j(body), K, label);
    let box_volume: f64 = semi_axes.iter().map(|a| 2.0 * a).product();
    let p = est.count() as f64 / drawn as f64;
    let volume = p * box_volume;
    let se = box_volume * (p * (1.0 - p) / drawn as f64).sqrt();
    assert_close!(
        body.volume().unwrap(),
        volume,
        K * se,
        "{label}: volume vs MC acceptance"
    );
}

#[test]
fn solid_ellipsoid_matches_monte_carlo_n2_to_n6() {
    for n in 2..=6 {
        let axes: Vec<f64> = (0..n).map(|i| 1.0 + 0.4 * i as f64).collect();
        let body = Body::solid_ellipsoid(&axes, 0.7).unwrap();
        check_ellipsoid_by_rejection(&body, &axes, 200 + n as u64, &format!("ellipsoid N={n}"));
    }
}

#[test]
fn solid_ball_matches_monte_carlo_n2_to_n6() {
    for n in 2..=6 {
        let body = Body::solid_ball(n, 1.3, 1.0).unwrap();
        check_ellipsoid_by_rejection(&body, &vec![1.3; n], 300 + n as u64, &format!("ball N={n}"));
    }
}

#[test]
fn hypersphere_shell_matches_monte_carlo_n2_to_n6() {
    for n in 2..=6 {
        let radius = 0.8;
        let body = Body::hypersphere_shell(n, radius, 3.0).unwrap();
        // Uniform points on S^{N−1}: normalised Gaussian vectors (rotation invariance).
        let mut r = rng(400 + n as u64);
        let mut est = MomentEstimator::new(n);
        let mut y = vec![0.0; n];
        for _ in 0..SAMPLES {
            let mut norm2 = 0.0;
            for yi in y.iter_mut() {
                *yi = gaussian(&mut r);
                norm2 += *yi * *yi;
            }
            let scale = radius / norm2.sqrt();
            for yi in y.iter_mut() {
                *yi *= scale;
            }
            est.add(&y);
        }
        est.check(&normalised_j(&body), K, &format!("shell N={n}"));
        // Area by the independent gamma form 2π^{N/2}/Γ(N/2) R^{N−1} (exact).
        let area = 2.0 * std::f64::consts::PI.powf(n as f64 / 2.0) / gamma_half(n)
            * radius.powi(n as i32 - 1);
        assert_close!(
            body.mass(),
            3.0 * area,
            1e-13 * body.mass(),
            "shell N={n} area"
        );
        assert!(body.volume().is_none());
    }
}

#[test]
fn solid_simplex_matches_monte_carlo_n2_to_n6() {
    for n in 2..=6 {
        let mut r = rng(500 + n as u64);
        let vertices: Vec<DVector<f64>> = (0..=n)
            .map(|_| DVector::from_fn(n, |_, _| gaussian(&mut r) + 0.5))
            .collect();
        let body = Body::solid_simplex(&vertices, 1.7).unwrap();
        let center = body.center_of_mass().clone();
        // Uniform points in a simplex: barycentric weights ~ Dirichlet(1, …, 1), i.e.
        // normalised exponential variates.
        let mut est = MomentEstimator::new(n);
        let mut y = vec![0.0; n];
        let mut w = vec![0.0; n + 1];
        for _ in 0..SAMPLES {
            let mut total = 0.0;
            for wk in w.iter_mut() {
                *wk = -(1.0 - r.r#gen::<f64>()).ln();
                total += *wk;
            }
            for (i, yi) in y.iter_mut().enumerate() {
                let mut x = 0.0;
                for (k, v) in vertices.iter().enumerate() {
                    x += w[k] / total * v[i];
                }
                *yi = x - center[i];
            }
            est.add(&y);
        }
        est.check(&normalised_j(&body), K, &format!("simplex N={n}"));
    }
}

/// The simplex volume |det|/N! against rejection sampling in the bounding box (N = 2…4;
/// beyond that the acceptance rate is too small for a quick test, and the Kuhn tests in
/// `mesh.rs` check the volume exactly in N = 2…5).
#[test]
fn solid_simplex_volume_matches_rejection_sampling_n2_to_n4() {
    for n in 2..=4 {
        let mut r = rng(600 + n as u64);
        let vertices: Vec<DVector<f64>> = (0..=n)
            .map(|_| DVector::from_fn(n, |_, _| gaussian(&mut r)))
            .collect();
        let body = Body::solid_simplex(&vertices, 1.0).unwrap();
        let lo: Vec<f64> = (0..n)
            .map(|i| vertices.iter().map(|v| v[i]).fold(f64::INFINITY, f64::min))
            .collect();
        let hi: Vec<f64> = (0..n)
            .map(|i| {
                vertices
                    .iter()
                    .map(|v| v[i])
                    .fold(f64::NEG_INFINITY, f64::max)
            })
            .collect();
        let edges = DMatrix::from_fn(n, n, |i, k| vertices[k + 1][i] - vertices[0][i]);
        let inverse = edges.try_inverse().unwrap();
        let inv: Vec<Vec<f64>> = (0..n)
            .map(|i| (0..n).map(|k| inverse[(i, k)]).collect())
            .collect();
        let draws = 400_000usize;
        let mut inside = 0usize;
        let mut x = vec![0.0; n];
        for _ in 0..draws {
            for (i, xi) in x.iter_mut().enumerate() {
                *xi = uniform(&mut r, lo[i], hi[i]) - vertices[0][i];
            }
            // Barycentric coordinates λ = E⁻¹ (x − v_0); inside iff λ ≥ 0 and Σλ ≤ 1.
            let mut total = 0.0;
            let mut ok = true;
            for row in &inv {
                let l: f64 = row.iter().zip(&x).map(|(a, b)| a * b).sum();
                total += l;
                ok &= l >= 0.0;
            }
            if ok && total <= 1.0 {
                inside += 1;
            }
        }
        let box_volume: f64 = (0..n).map(|i| hi[i] - lo[i]).product();
        let p = inside as f64 / draws as f64;
        let se = box_volume * (p * (1.0 - p) / draws as f64).sqrt();
        assert_close!(
            body.volume().unwrap(),
            p * box_volume,
            K * se,
            "simplex N={n}"
        );
    }
}
