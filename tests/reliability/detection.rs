//! Box–box separating axes and manifolds over 10⁵ random poses (N = 2 … 6), each against
//! brute force (`tests/support/boxes.rs`): ignored by default, run by `.ci/run` in release.
//! The always-on version is `tests/dynamics/manifolds.rs`.

#[path = "../support/boxes.rs"]
mod boxes;

use boxes::*;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rotorflow::dynamics::motion::detect::manifold::manifold_capacity;
use rotorflow::dynamics::motion::detect::{box_box, box_manifold};

#[test]
#[ignore = "long run: cargo test --release --test reliability -- --ignored"]
fn hundred_thousand_box_pairs_against_brute_force() {
    let mut r = ChaCha8Rng::seed_from_u64(20261128);
    let per_dim = 20_000;
    let mut total = 0;
    for n in 2..=6 {
        let mut tally = SatTally::default();
        let mut points = 0;
        for k in 0..per_dim {
            let pose = POSES[k % POSES.len()];
            let (a, b) = random_pair(&mut r, n, pose);
            let axis = box_box(&a.placed(), &b.placed()).unwrap();
            check_sat_case(&mut r, &a, &b, &axis, 40, &mut tally);
            if let Some(m) = box_manifold(&a.placed(), &b.placed(), 0.01).unwrap() {
                assert!(m.len() <= manifold_capacity(n));
                for p in m.points() {
                    assert!(
                        p.depth.is_finite()
                            && p.point_a.iter().chain(p.point_b).all(|x| x.is_finite())
                    );
                    let gap: Vec<f64> = p
                        .point_a
                        .iter()
                        .zip(p.point_b)
                        .map(|(x, y)| x - y)
                        .collect();
                    assert!((dot(&gap, m.normal()) - p.depth).abs() < 1e-9);
                }
                points += m.len();
            }
        }
        println!(
            "N = {n}: {} cases ({} overlapping, {} separated, {} cell axes, {} sampled), {points} manifold points, worst undercut {:e}",
            tally.cases,
            tally.overlapping,
            tally.separated,
            tally.cell_axes,
            tally.sampled,
            tally.worst_undercut
        );
        assert_eq!(tally.cases, per_dim);
        total += tally.cases;
    }
    assert_eq!(total, 100_000);
}
