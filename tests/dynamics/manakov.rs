//! Manakov's integrals of the N-D top: their number, their conservation by independent
//! integrators, and their failure for a map that is not a physical body's.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rotorflow::algebra::{Bivector, Rotor};
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::{
    Dopri5, Integrator, Invariants, RigidBody, Rkmk4, Splitting, manakov_count, manakov_integrals,
};
use rotorflow::inertia::InertiaMap;

fn body(n: usize, seed: u64) -> RigidBody {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let j: Vec<f64> = (0..n).map(|_| rng.gen_range(0.5..3.0)).collect();
    let k = n * (n - 1) / 2;
    let w: Vec<f64> = (0..k).map(|_| rng.gen_range(-1.0..1.0)).collect();
    RigidBody::from_body_velocity(
        InertiaMap::from_principal_second_moments(&j).unwrap(),
        Rotor::identity(n),
        &Bivector::from_components(n, &w).unwrap(),
    )
    .unwrap()
}

#[test]
fn their_number_is_half_of_dim_plus_rank() {
    for n in 2..=12 {
        let dim = n * (n - 1) / 2;
        let rank = n / 2;
        assert_eq!(manakov_count(n), (dim + rank) / 2, "N = {n}");
        let b = body(n, n as u64);
        let inv = Invariants::of(&b);
        assert_eq!(inv.manakov.len(), manakov_count(n));
        assert_eq!(inv.manakov_scales.len(), manakov_count(n));
    }
    assert_eq!(
        (3..=8).map(manakov_count).collect::<Vec<_>>(),
        [2, 4, 6, 9, 12, 16]
    );
}

#[test]
fn they_include_the_casimirs_and_match_a_direct_3d_evaluation() {
    let b = body(5, 7);
    let inv = Invariants::of(&b);
    // j = 0, m = 1 (k = 2) is tr [L]² = −2|L|² = −2 c₁.
    assert!((inv.manakov[0] + 2.0 * inv.casimirs[0]).abs() <= 1e-13 * inv.casimirs[0]);
    // 3D: 3 tr([L]² J²) = −3 Σ L_ik² (J_i² + J_k²), the same numbers another way.
    let b = body(3, 8);
    let j = b.inertia().principal_second_moments().unwrap().to_vec();
    let l = b.momentum().as_slice().to_vec();
    let direct = -3.0
        * (l[0] * l[0] * (j[0] * j[0] + j[1] * j[1])
            + l[1] * l[1] * (j[0] * j[0] + j[2] * j[2])
            + l[2] * l[2] * (j[1] * j[1] + j[2] * j[2]));
    let m = Invariants::of(&b).manakov;
    assert!(
        (m[1] - direct).abs() <= 1e-13 * direct.abs(),
        "{} vs {direct}",
        m[1]
    );
}

/// Largest relative drift of the Manakov integrals over a run.
fn run_drift(mut b: RigidBody, integrator: &mut dyn Integrator, h: f64, steps: usize) -> f64 {
    let reference = Invariants::of(&b);
    let mut worst = 0.0f64;
    for k in 0..steps {
        integrator.step(&mut b, k as f64 * h, h, &Free).unwrap();
        if k % 50 == 0 || k + 1 == steps {
            worst = worst.max(Invariants::of(&b).drift_from(&reference).manakov);
        }
    }
    worst
}

#[test]
fn dopri5_and_the_splitting_conserve_them_in_n4_to_n8() {
    for n in 4..=8 {
        let b = body(n, 100 + n as u64);
        // Dopri5 at rtol 1e-12 over t = 100: within 1e-10. Its steps' errors add up
        // linearly in time (the 10⁶-step long run of the reliability tests reaches a few
        // 1e-10), so the bound holds for runs of a few hundred time units.
        let mut dopri = Dopri5::new(1e-12, 1e-12);
        let d = run_drift(b.clone(), &mut dopri, 0.05, 2_000);
        // The splitting keeps the Casimirs exactly but the other integrals only to O(h²):
        // bounded, small at h = 1e-3.
        let s = run_drift(b.clone(), &mut Splitting::strang(), 1e-3, 2000);
        // RK4 at h = 1e-2: O(h⁴).
        let r = run_drift(b.clone(), &mut Rkmk4, 1e-2, 1000);
        eprintln!("N = {n}: Manakov drift dopri5 {d:.1e}, strang {s:.1e}, rk4 {r:.1e}");
        assert!(d <= 1e-10, "N = {n}: dopri5 {d:e}");
        assert!(s <= 1e-5, "N = {n}: strang {s:e}");
        assert!(r <= 1e-7, "N = {n}: rk4 {r:e}");
    }
}

#[test]
fn they_are_not_conserved_for_a_map_that_is_no_body() {
    // A diagonal map on the planes whose moments are not J_i + J_j: Euler's equations still
    // conserve energy and the Casimirs, but L + λJ² is no Lax matrix for any J.
    let n = 4;
    let plane_moments = [1.0, 1.7, 2.9, 2.2, 3.4, 1.3];
    let map = InertiaMap::from_plane_moments(&plane_moments).unwrap();
    let w = Bivector::from_components(n, &[0.3, -0.7, 0.5, 0.9, -0.2, 0.4]).unwrap();
    let mut b = RigidBody::from_body_velocity(map, Rotor::identity(n), &w).unwrap();
    let j = [0.5, 1.0, 1.5, 2.0];
    let start = manakov_integrals(b.momentum(), &j);
    let reference = Invariants::of(&b);
    let mut dopri = Dopri5::new(1e-12, 1e-12);
    for k in 0..200 {
        dopri.step(&mut b, k as f64 * 0.05, 0.05, &Free).unwrap();
    }
    let now = manakov_integrals(b.momentum(), &j);
    let worst = start
        .iter()
        .zip(&now)
        .map(|(a, c)| (a - c).abs() / a.abs().max(1e-300))
        .filter(|d| d.is_finite())
        .fold(0.0f64, f64::max);
    assert!(worst > 1e-3, "{worst:e}");
    // The energy and Casimirs are still conserved, so the run itself is accurate.
    let d = Invariants::of(&b).drift_from(&reference);
    assert!(d.energy < 1e-10 && d.casimirs < 1e-10);
    // A general map has no J: Invariants lists no Manakov integrals.
    assert!(reference.manakov.is_empty());
}
