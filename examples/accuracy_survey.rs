//! Accuracy survey of exp, log and the rotor constraint over random bivectors, N = 2 … 10:
//! `cargo run --release --example accuracy_survey`. The figures back the tolerances of the
//! tests in `tests/algebra/` (they sit a factor of 2–5 above the maxima printed here).

use rand::{Rng, SeedableRng};
use rotorflow::prelude::*;
fn main() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(9);
    for n in 2..=10 {
        let (mut e1, mut e2, mut e3) = (0.0f64, 0.0f64, 0.0f64);
        for _ in 0..3000 {
            let c: Vec<f64> = (0..n * (n - 1) / 2)
                .map(|_| rng.gen_range(-1.0..1.0))
                .collect();
            let b = Bivector::from_components(n, &c).unwrap();
            let r = Rotor::from_rotation_bivector(&b);
            let l = r.rotation_bivector();
            let r2 = Rotor::from_rotation_bivector(&l);
            let d = r
                .as_slice()
                .iter()
                .zip(r2.as_slice())
                .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
            e1 = e1.max(d);
            let mags = b.decompose().magnitudes();
            if mags.iter().all(|&m| m < 3.0) {
                e2 = e2.max((&l - &b).max_abs() / b.max_abs());
            }
            e3 = e3.max(r.unit_error());
        }
        println!(
            "n={n}: max|exp(log R) − R| = {e1:.2e}, max rel |log(exp B) − B| = {e2:.2e}, max |RR̃−1| = {e3:.2e}"
        );
    }
}
