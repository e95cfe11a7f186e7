//! Helpers shared by every integration-test target: seeded randomness, random algebra
//! elements, distances, and an assertion that prints both values, the tolerance and the
//! difference.
//!
//! Each target includes this file with `#[path = "../support/mod.rs"] mod support;` and uses
//! the part it needs, so not every item is used by every target.
#![allow(dead_code)]

use nalgebra::DMatrix;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rotorflow::algebra::{Bivector, Rotor, Vector};

/// Asserts |a − b| ≤ tol with a message that shows the values, the tolerance and the gap
/// (and an optional formatted context).
#[macro_export]
macro_rules! assert_close {
    ($a:expr, $b:expr, $tol:expr) => {{
        let (a, b, tol): (f64, f64, f64) = ($a, $b, $tol);
        let diff = (a - b).abs();
        assert!(
            diff <= tol,
            "assert_close failed: {} = {a:e}, {} = {b:e}, |diff| = {diff:e} > tol = {tol:e}",
            stringify!($a),
            stringify!($b)
        );
    }};
    ($a:expr, $b:expr, $tol:expr, $($msg:tt)+) => {{
        let (a, b, tol): (f64, f64, f64) = ($a, $b, $tol);
        let diff = (a - b).abs();
        assert!(
            diff <= tol,
            "assert_close failed ({}): {} = {a:e}, {} = {b:e}, |diff| = {diff:e} > tol = {tol:e}",
            format!($($msg)+),
            stringify!($a),
            stringify!($b)
        );
    }};
}

/// Seeded generator (fixed seeds keep every randomized test deterministic).
pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// A bivector of ℝⁿ with components uniform in (−scale, scale).
pub fn random_bivector(rng: &mut impl Rng, n: usize, scale: f64) -> Bivector {
    let c: Vec<f64> = (0..n * (n - 1) / 2)
        .map(|_| scale * rng.gen_range(-1.0..1.0))
        .collect();
    Bivector::from_components(n, &c).unwrap()
}

/// A vector of ℝⁿ with components uniform in (−1, 1).
pub fn random_vector(rng: &mut impl Rng, n: usize) -> Vector {
    let c: Vec<f64> = (0..n).map(|_| rng.gen_range(-1.0..1.0)).collect();
    Vector::from_components(&c).unwrap()
}

/// The rotor exp of a random bivector with components in (−2, 2): angles up to a few π.
pub fn random_rotor(rng: &mut impl Rng, n: usize) -> Rotor {
    Rotor::from_rotation_bivector(&random_bivector(rng, n, 2.0))
}

/// A random rotation matrix (det +1): the matrix of [`random_rotor`].
pub fn random_rotation_matrix(rng: &mut impl Rng, n: usize) -> DMatrix<f64> {
    random_rotor(rng, n).to_matrix()
}

/// A bivector with prescribed plane magnitudes placed in a random orthonormal frame.
pub fn bivector_with_planes(rng: &mut impl Rng, n: usize, mags: &[f64]) -> Bivector {
    let mut b = Bivector::zero(n);
    for (k, &m) in mags.iter().enumerate() {
        b.set(2 * k, 2 * k + 1, m);
    }
    random_rotor(rng, n).rotate_bivector(&b)
}

/// max |x − s·y| over the coefficients of two rotors.
fn signed_distance(a: &Rotor, b: &Rotor, s: f64) -> f64 {
    a.as_slice()
        .iter()
        .zip(b.as_slice())
        .fold(0.0f64, |m, (x, y)| m.max((x - s * y).abs()))
}

/// max |x − y| over the coefficients of two rotors.
pub fn rotor_distance(a: &Rotor, b: &Rotor) -> f64 {
    signed_distance(a, b, 1.0)
}

/// max |x − y| over the coefficients of two rotors, allowing the overall sign ±.
pub fn rotor_distance_up_to_sign(a: &Rotor, b: &Rotor) -> f64 {
    signed_distance(a, b, 1.0).min(signed_distance(a, b, -1.0))
}

/// max |aᵢⱼ − bᵢⱼ| (the shapes must agree).
pub fn max_abs_diff(a: &DMatrix<f64>, b: &DMatrix<f64>) -> f64 {
    assert_eq!(a.shape(), b.shape());
    a.iter()
        .zip(b.iter())
        .fold(0.0_f64, |acc, (x, y)| acc.max((x - y).abs()))
}

/// max |aᵢⱼ|.
pub fn max_abs(a: &DMatrix<f64>) -> f64 {
    a.iter().fold(0.0_f64, |acc, x| acc.max(x.abs()))
}

/// max |QᵀQ − 1|: how far Q is from orthogonal.
pub fn orthogonality(q: &DMatrix<f64>) -> f64 {
    let n = q.nrows();
    max_abs_diff(&(q.transpose() * q), &DMatrix::identity(n, n))
}
