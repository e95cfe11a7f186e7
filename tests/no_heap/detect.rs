//! Collision detection between bodies (`dynamics::motion::detect`) never touches the heap
//! for N ≤ 8: box–box separating axes, box and hull contact manifolds, box–box distances
//! in 3 and 4 dimensions, and the broad phase's updates after its first call (counted by
//! the allocator of `tests/no_heap.rs`).

use super::allocations_in;
use rotorflow::dynamics::motion::detect::{
    BroadPhase, PlacedBox, PlacedHull, box_box, box_manifold, hull_manifold,
};

/// The rotation by `angle` in the planes (0, 1), (2, 3), …, row-major.
fn turned(n: usize, angle: f64) -> Vec<f64> {
    let mut q: Vec<f64> = (0..n * n)
        .map(|k| if k / n == k % n { 1.0 } else { 0.0 })
        .collect();
    let (s, c) = angle.sin_cos();
    for p in (0..n - 1).step_by(2) {
        q[p * n + p] = c;
        q[(p + 1) * n + p + 1] = c;
        q[p * n + p + 1] = -s;
        q[(p + 1) * n + p] = s;
    }
    q
}

#[test]
fn box_queries_and_manifolds_do_not_allocate_up_to_8d() {
    for n in 2..=8 {
        let ha: Vec<f64> = (0..n).map(|k| 1.0 + 0.1 * k as f64).collect();
        let hb: Vec<f64> = (0..n).map(|k| 0.5 + 0.05 * k as f64).collect();
        let ca = vec![0.0; n];
        let qa = turned(n, 0.0);
        // Face to face (turned about the last axis' normal) and at a random-like pose.
        let mut face = vec![0.1; n];
        face[n - 1] = ha[n - 1] + hb[n - 1] - 0.01;
        let qf = if n >= 3 {
            turned(n - 1, 0.3)
        } else {
            qa.clone()
        };
        // Embed the (N−1)-rotation into N dimensions about the last axis.
        let mut qface = qa.clone();
        if n >= 3 {
            for i in 0..n - 1 {
                for j in 0..n - 1 {
                    qface[i * n + j] = qf[i * (n - 1) + j];
                }
            }
        }
        let tilted: Vec<f64> = (0..n).map(|k| 0.3 + 0.1 * k as f64).collect();
        let qt = turned(n, 0.7);
        let a = PlacedBox {
            half_lengths: &ha,
            position: &ca,
            rotation: &qa,
        };
        let on_face = PlacedBox {
            half_lengths: &hb,
            position: &face,
            rotation: &qface,
        };
        let crossing = PlacedBox {
            half_lengths: &hb,
            position: &tilted,
            rotation: &qt,
        };
        let corners = |h: &[f64]| -> Vec<f64> {
            (0..1usize << n)
                .flat_map(|m| (0..n).map(move |j| if m >> j & 1 == 1 { 1.0 } else { -1.0 }))
                .enumerate()
                .map(|(k, s)| s * h[k % n])
                .collect()
        };
        let (va, vb) = (corners(&ha), corners(&hb));
        let hull_a = PlacedHull {
            vertices: &va,
            position: &ca,
            rotation: &qa,
        };
        let hull_b = PlacedHull {
            vertices: &vb,
            position: &face,
            rotation: &qface,
        };
        let normal = box_box(&a, &on_face).unwrap().normal;
        let mut points = 0;
        let count = allocations_in(|| {
            for b in [&on_face, &crossing] {
                let axis = box_box(&a, b).unwrap();
                std::hint::black_box(axis.depth);
                if let Some(m) = box_manifold(&a, b, 0.01).unwrap() {
                    points += m.len();
                }
            }
            if let Some(m) = hull_manifold(&hull_a, &hull_b, &normal, 0.01).unwrap() {
                points += m.len();
            }
        });
        assert_eq!(count, 0, "N = {n}: {count} heap allocations");
        assert!(points >= 2, "N = {n}: {points} points");
    }
}

#[test]
fn broad_phase_updates_do_not_allocate_after_the_first() {
    for n in 2..=8 {
        let bodies = 500;
        let mut lower = Vec::new();
        let mut upper = Vec::new();
        for b in 0..bodies {
            for a in 0..n {
                let c = ((b * 7919 + a * 104_729) % 1000) as f64 * 0.01;
                lower.push(c - 0.4);
                upper.push(c + 0.4);
            }
        }
        let mut broad = BroadPhase::new(n).unwrap();
        broad.update(&lower, &upper).unwrap();
        // Warm-up: the pair set reaches its size at these motions.
        let mut pairs = 0;
        for step in 0..3 {
            for (k, (lo, hi)) in lower.iter_mut().zip(upper.iter_mut()).enumerate() {
                let dx = 0.01 * (((k * 31 + step * 17) % 7) as f64 - 3.0);
                *lo += dx;
                *hi += dx;
            }
            pairs += broad.update(&lower, &upper).unwrap().len();
        }
        let count = allocations_in(|| {
            for step in 0..3 {
                for (k, (lo, hi)) in lower.iter_mut().zip(upper.iter_mut()).enumerate() {
                    let dx = -0.01 * (((k * 31 + step * 17) % 7) as f64 - 3.0);
                    *lo += dx;
                    *hi += dx;
                }
                pairs += broad.update(&lower, &upper).unwrap().len();
            }
        });
        assert_eq!(count, 0, "N = {n}: {count} heap allocations in 3 updates");
        assert!(pairs > 0, "N = {n}: no pairs");
    }
}

#[test]
fn box_distances_do_not_allocate_in_3_and_4_dimensions() {
    use rotorflow::dynamics::motion::detect::{PlacedShape, distance};
    use rotorflow::dynamics::motion::shape::ConvexShape;
    for n in [3, 4] {
        let ha: Vec<f64> = (0..n).map(|k| 1.0 + 0.1 * k as f64).collect();
        let hb: Vec<f64> = (0..n).map(|k| 0.5 + 0.05 * k as f64).collect();
        let (box_a, box_b) = (
            ConvexShape::cuboid(&ha).unwrap(),
            ConvexShape::cuboid(&hb).unwrap(),
        );
        let (ca, qa, qb) = (vec![0.0; n], turned(n, 0.2), turned(n, 0.9));
        // Separated, then overlapping.
        let far: Vec<f64> = (0..n).map(|k| if k == 0 { 3.0 } else { 0.2 }).collect();
        let near: Vec<f64> = (0..n).map(|k| if k == 0 { 1.2 } else { 0.2 }).collect();
        let a = PlacedShape::new(&box_a, &ca, &qa).unwrap();
        let separated = PlacedShape::new(&box_b, &far, &qb).unwrap();
        let overlapping = PlacedShape::new(&box_b, &near, &qb).unwrap();
        let mut answers = [false; 2];
        let count = allocations_in(|| {
            answers[0] = distance(&a, &separated).unwrap().intersecting;
            answers[1] = distance(&a, &overlapping).unwrap().intersecting;
        });
        assert_eq!(count, 0, "N = {n}: {count} heap allocations");
        assert_eq!(answers, [false, true], "N = {n}");
    }
}
