//! Shared helpers: random elements, and an assertion that prints both values, the tolerance
//! and the difference.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rotorflow::prelude::*;

/// Asserts |a − b| ≤ tol with a message that shows the values, the tolerance and the gap.
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
}

pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

pub fn random_bivector(rng: &mut impl Rng, n: usize, scale: f64) -> Bivector {
    let c: Vec<f64> = (0..n * (n - 1) / 2)
        .map(|_| scale * rng.gen_range(-1.0..1.0))
        .collect();
    Bivector::from_components(n, &c).unwrap()
}

pub fn random_vector(rng: &mut impl Rng, n: usize) -> Vector {
    let c: Vec<f64> = (0..n).map(|_| rng.gen_range(-1.0..1.0)).collect();
    Vector::from_components(&c).unwrap()
}

pub fn random_rotor(rng: &mut impl Rng, n: usize) -> Rotor {
    Rotor::from_rotation_bivector(&random_bivector(rng, n, 2.0))
}

/// A random orthogonal n×n matrix with det +1 (QR of a Gaussian-ish matrix, signs fixed).
pub fn random_rotation_matrix(rng: &mut impl Rng, n: usize) -> nalgebra::DMatrix<f64> {
    random_rotor(rng, n).to_matrix()
}

/// Bivector with prescribed plane magnitudes placed in a random orthonormal frame.
pub fn bivector_with_planes(rng: &mut impl Rng, n: usize, mags: &[f64]) -> Bivector {
    let mut b = Bivector::zero(n);
    for (k, &m) in mags.iter().enumerate() {
        b.set(2 * k, 2 * k + 1, m);
    }
    let r = random_rotor(rng, n);
    r.rotate_bivector(&b)
}

/// max |x − y| over the coefficients of two rotors, allowing the overall sign ±.
pub fn rotor_distance_up_to_sign(a: &Rotor, b: &Rotor) -> f64 {
    let plus = a
        .raw_coefficients()
        .iter()
        .zip(b.raw_coefficients())
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    let minus = a
        .raw_coefficients()
        .iter()
        .zip(b.raw_coefficients())
        .fold(0.0f64, |m, (x, y)| m.max((x + y).abs()));
    plus.min(minus)
}

pub fn rotor_distance(a: &Rotor, b: &Rotor) -> f64 {
    a.raw_coefficients()
        .iter()
        .zip(b.raw_coefficients())
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

pub fn max_abs_diff(a: &nalgebra::DMatrix<f64>, b: &nalgebra::DMatrix<f64>) -> f64 {
    (a - b).abs().max()
}

/// max |QᵀQ − 1|.
pub fn orthogonality(q: &nalgebra::DMatrix<f64>) -> f64 {
    let n = q.nrows();
    max_abs_diff(&(q.transpose() * q), &nalgebra::DMatrix::identity(n, n))
}
