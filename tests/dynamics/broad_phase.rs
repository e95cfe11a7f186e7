//! The broad phase (`dynamics::motion::detect::BroadPhase`) against brute-force O(n²)
//! overlap of the boxes, on random scenes in N = 2 … 6 whose bodies move between calls.

use rand::Rng;
use rotorflow::dynamics::motion::detect::BroadPhase;

/// Every pair (i < j) whose boxes overlap on every axis (closed intervals), in order.
fn brute_pairs(n: usize, lower: &[f64], upper: &[f64]) -> Vec<(usize, usize)> {
    let bodies = lower.len() / n;
    let mut out = Vec::new();
    for i in 0..bodies {
        for j in i + 1..bodies {
            if (0..n).all(|a| {
                lower[i * n + a] <= upper[j * n + a] && lower[j * n + a] <= upper[i * n + a]
            }) {
                out.push((i, j));
            }
        }
    }
    out
}

/// A random scene: box centres in a cube of side `side`, half-sizes up to `size`, some
/// boxes flat or touching exactly (equal bounds), to exercise ties.
fn scene(r: &mut impl Rng, n: usize, bodies: usize, side: f64, size: f64) -> (Vec<f64>, Vec<f64>) {
    let mut lower = Vec::with_capacity(bodies * n);
    let mut upper = Vec::with_capacity(bodies * n);
    for b in 0..bodies {
        for _ in 0..n {
            let c = r.gen_range(0.0..side);
            let h = if b % 17 == 0 {
                0.0
            } else {
                r.gen_range(0.0..size)
            };
            lower.push(c - h);
            upper.push(c + h);
        }
    }
    // Touching pairs: a box whose lower bound equals another's upper bound on one axis.
    for b in (1..bodies).step_by(11) {
        let a = b % n;
        let w = upper[b * n + a] - lower[b * n + a];
        lower[b * n + a] = upper[(b - 1) * n + a];
        upper[b * n + a] = lower[b * n + a] + w;
    }
    (lower, upper)
}

/// Moves every body by a small random step, a few by a large jump.
fn move_bodies(
    r: &mut impl Rng,
    n: usize,
    lower: &mut [f64],
    upper: &mut [f64],
    step: f64,
    side: f64,
) {
    let bodies = lower.len() / n;
    for b in 0..bodies {
        let jump = r.gen_bool(0.01);
        for a in 0..n {
            let dx = if jump {
                r.gen_range(-side..side) * 0.5
            } else {
                r.gen_range(-step..step)
            };
            lower[b * n + a] += dx;
            upper[b * n + a] += dx;
        }
    }
}

#[test]
fn broad_phase_finds_exactly_the_overlapping_pairs_as_bodies_move() {
    let mut r = super::rng(2024);
    for n in 2..=6 {
        let bodies = 400;
        let side = 10.0;
        // Sizes for about a few overlaps per body at every N.
        let size = 0.5 * side * (3.0 / bodies as f64).powf(1.0 / n as f64);
        let (mut lower, mut upper) = scene(&mut r, n, bodies, side, size);
        let mut broad = BroadPhase::new(n).unwrap();
        let mut updates = 0;
        let mut pairs_seen = 0;
        let mut swaps = 0;
        for step in 0..40 {
            let got = broad.update(&lower, &upper).unwrap().to_vec();
            let want = brute_pairs(n, &lower, &upper);
            assert_eq!(got, want, "N = {n}, step {step}");
            updates += 1;
            pairs_seen += got.len();
            swaps += broad.last_moved();
            move_bodies(&mut r, n, &mut lower, &mut upper, 0.05 * size, side);
        }
        println!(
            "N = {n}: {updates} updates of {bodies} bodies, {pairs_seen} pairs in all, {swaps} fat boxes renewed"
        );
        assert_eq!(updates, 40);
        assert!(
            pairs_seen > 40,
            "N = {n}: scenes too sparse to test ({pairs_seen} pairs)"
        );
    }
}

#[test]
fn broad_phase_leaves_out_excluded_pairs_and_restarts_on_new_body_counts() {
    let mut r = super::rng(7);
    let n = 3;
    let (lower, upper) = scene(&mut r, n, 200, 5.0, 0.6);
    let mut broad = BroadPhase::new(n).unwrap();
    let all = broad.update(&lower, &upper).unwrap().to_vec();
    assert!(all.len() >= 4, "{} pairs", all.len());
    let (i, j) = all[all.len() / 2];
    broad.exclude_pair(j, i).unwrap();
    let without = broad.update(&lower, &upper).unwrap().to_vec();
    assert_eq!(without.len(), all.len() - 1);
    assert!(!without.contains(&(i, j)));
    broad.include_pair(i, j).unwrap();
    assert_eq!(broad.update(&lower, &upper).unwrap(), &all[..]);
    // Fewer bodies: a fresh start, still exact.
    let k = 150 * n;
    assert_eq!(
        broad.update(&lower[..k], &upper[..k]).unwrap(),
        &brute_pairs(n, &lower[..k], &upper[..k])[..]
    );
    assert!(broad.exclude_pair(3, 3).is_err());
    assert!(broad.update(&lower[..5], &upper[..6]).is_err());
    let mut flipped = lower.clone();
    flipped[0] = upper[0] + 1.0;
    assert!(broad.update(&flipped, &upper).is_err());
    let mut nan = lower.clone();
    nan[4] = f64::NAN;
    assert!(broad.update(&nan, &upper).is_err());
    assert!(BroadPhase::new(0).is_err());
}

/// The broad phase's query work at 10³, 10⁴ and 10⁵ 4D bodies at a fixed density (about
/// two overlapping neighbours per body): box tests per body queried grow like log n, so
/// the least-squares exponent of the total over n must be near 1 (n log n gives about 1.1
/// here), far from the 2 of testing all pairs. Both a build (every body queried) and an
/// update after every body left its fat box are measured; the counts are deterministic.
#[test]
fn broad_phase_work_grows_like_n_log_n() {
    let n = 4;
    let mut r = super::rng(11);
    let sizes = [1_000usize, 10_000, 100_000];
    let mut points = Vec::new();
    for &bodies in &sizes {
        let side = 1.2 * (bodies as f64).powf(0.25);
        let (lower, upper) = scene(&mut r, n, bodies, side, 0.5);
        let mut broad = BroadPhase::new(n).unwrap();
        let pairs = broad.update(&lower, &upper).unwrap().len();
        let build = broad.last_box_tests();
        assert_eq!(broad.last_moved(), bodies);
        // Every body moves by a full box width: all leave their fat boxes.
        let shifted_lower: Vec<f64> = lower.iter().map(|x| x + 1.0).collect();
        let shifted_upper: Vec<f64> = upper.iter().map(|x| x + 1.0).collect();
        broad.update(&shifted_lower, &shifted_upper).unwrap();
        let update = broad.last_box_tests();
        println!(
            "{bodies} bodies: {pairs} pairs, {build} box tests to build ({:.1} per body), {update} after all moved ({} moved)",
            build as f64 / bodies as f64,
            broad.last_moved()
        );
        points.push((
            (bodies as f64).ln(),
            (build as f64).ln(),
            (update as f64).ln(),
        ));
    }
    let slope = |f: fn(&(f64, f64, f64)) -> f64| {
        let k = points.len() as f64;
        let mx = points.iter().map(|p| p.0).sum::<f64>() / k;
        let my = points.iter().map(f).sum::<f64>() / k;
        let num: f64 = points.iter().map(|p| (p.0 - mx) * (f(p) - my)).sum();
        let den: f64 = points.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
        num / den
    };
    let (build, update) = (slope(|p| p.1), slope(|p| p.2));
    println!("growth exponent of the box tests: build {build:.3}, update {update:.3}");
    for e in [build, update] {
        assert!((0.95..1.25).contains(&e), "exponent {e}");
    }
}
