//! What the integrators conserve: Casimirs, space momentum, the rotor's group constraint,
//! bounded energy, time reversibility and frame covariance.

use crate::{random_bivector, random_body, rng, run};
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::{Invariants, RigidBody, Rkmk4, Splitting};
use rotorflow::prelude::*;

#[test]
fn splitting_keeps_casimirs_over_1e5_steps() {
    let mut r = rng(401);
    for n in 3..=6 {
        let mut body = random_body(&mut r, n);
        let start = Invariants::of(&body);
        let mut worst_energy = 0.0f64;
        let mut strang = Splitting::strang();
        for _ in 0..100 {
            run(&mut body, &mut strang, &Free, 0.01, 1000);
            let d = Invariants::of(&body).drift_from(&start);
            worst_energy = worst_energy.max(d.energy);
        }
        let d = Invariants::of(&body).drift_from(&start);
        assert!(d.casimirs <= 1e-12, "n={n}: Casimir drift {:e}", d.casimirs);
        assert!(
            d.space_momentum <= 1e-11,
            "n={n}: space L drift {:e}",
            d.space_momentum
        );
        // The attitude is rounded once per Strang step (the plane rotations are multiplied
        // into a near-identity product first), so |RR̃ − 1| is a random walk of 1e5 roundings:
        // examples/rotor_drift_survey.rs measures at most 3.4e-14 (rotors, N = 3, 4) and
        // 8.6e-14 (matrices, N = 5, 6) over 8 seeds.
        // Bound, with no renormalisation at all:
        assert!(d.attitude <= 1e-13, "n={n}: |RR̃ − 1| = {:e}", d.attitude);
        // Energy error is O(h²) and bounded (no drift over 10⁵ steps): measured worst
        // 2.3e-6 = 0.023·h² (n = 6); bound 3× that.
        assert!(worst_energy < 7e-6, "n={n}: energy error {worst_energy:e}");
        if let (Some(a), Some(b)) = (Invariants::of(&body).pfaffian, start.pfaffian) {
            // The Pfaffian is of degree N/2 in L: on the Casimirs' scale (Drift::casimirs
            // divides c_k by |L|^(2k)) its drift is |ΔPf| / |L|^(N/2). Relative to Pf itself
            // the bound would depend on how close L is to simple (Pf → 0).
            let scale = start.casimirs[0].sqrt().powi(n as i32 / 2);
            let drift = (a - b).abs() / scale;
            assert!(
                drift <= 1e-12,
                "n={n}: Pfaffian drift {drift:e} (Pf = {b:e})"
            );
        }
    }
}

#[test]
fn rk4_keeps_the_rotor_on_spin_n_without_renormalising() {
    let mut r = rng(402);
    for n in 3..=6 {
        let mut body = random_body(&mut r, n);
        run(&mut body, &mut Rkmk4, &Free, 0.01, 10_000);
        assert!(
            body.principal_frame_attitude().unit_error() < 1e-13,
            "n={n}"
        );
    }
}

#[test]
fn steady_rotation_in_a_principal_plane_stays_steady() {
    for n in [3, 4, 5] {
        let j: Vec<f64> = (0..n).map(|k| 1.0 + 0.5 * k as f64).collect();
        let inertia = InertiaMap::from_principal_second_moments(&j).unwrap();
        let w = Bivector::from_plane(n, 0, 1, 2.0).unwrap();
        for integ in [
            &mut Splitting::strang() as &mut dyn rotorflow::dynamics::Integrator,
            &mut Rkmk4,
        ] {
            let mut body =
                RigidBody::from_body_velocity(inertia.clone(), Rotor::identity(n), &w).unwrap();
            run(&mut body, integ, &Free, 0.01, 1000);
            assert!((&body.omega() - &w).max_abs() < 1e-13, "n={n}");
            // the attitude is the rotation by ω t = 20 rad in e12
            let expected = Rotor::from_plane_angle(n, 0, 1, 20.0).unwrap();
            let d = crate::attitude_distance(body.principal_frame_attitude(), &expected.into());
            assert!(d < 1e-11, "n={n}: {d:e}");
        }
    }
}

#[test]
fn strang_is_time_reversible() {
    let mut r = rng(403);
    for n in [3, 4, 6] {
        let start = random_body(&mut r, n);
        let mut body = start.clone();
        let mut s = Splitting::strang();
        run(&mut body, &mut s, &Free, 0.01, 1000);
        run(&mut body, &mut s, &Free, -0.01, 1000);
        assert!(
            (body.momentum() - start.momentum()).max_abs() < 1e-12,
            "n={n}"
        );
        let d = crate::attitude_distance(
            body.principal_frame_attitude(),
            start.principal_frame_attitude(),
        );
        assert!(d < 1e-12, "n={n}: {d:e}");
    }
}

#[test]
fn rotating_the_initial_attitude_rotates_the_trajectory() {
    let mut r = rng(404);
    let n = 4;
    let start = random_body(&mut r, n);
    let q = Rotor::from_rotation_bivector(&random_bivector(&mut r, n, 1.0));
    let turned = RigidBody::from_body_momentum(
        start.inertia().clone(),
        q.compose(start.principal_frame_attitude().as_rotor().unwrap()),
        start.momentum(),
    )
    .unwrap();
    let (mut a, mut b) = (start, turned);
    run(&mut a, &mut Splitting::yoshida4(), &Free, 0.01, 500);
    run(&mut b, &mut Splitting::yoshida4(), &Free, 0.01, 500);
    assert!((a.momentum() - b.momentum()).max_abs() < 1e-13);
    let expected = q.compose(a.principal_frame_attitude().as_rotor().unwrap());
    let d = crate::attitude_distance(b.principal_frame_attitude(), &expected.into());
    assert!(d < 1e-13, "{d:e}");
    assert!((&b.space_momentum() - &q.rotate_bivector(&a.space_momentum())).max_abs() < 1e-12);
}

#[test]
fn implicit_midpoint_conserves_quadratic_invariants_and_reports_its_solve() {
    use rotorflow::dynamics::{DynamicsError, Integrator, Midpoint};
    let mut r = rng(405);
    for n in [3, 4, 5] {
        let mut body = random_body(&mut r, n);
        let start = Invariants::of(&body);
        let mut m = Midpoint::default();
        run(&mut body, &mut m, &Free, 0.01, 10_000);
        let now = Invariants::of(&body);
        let d = now.drift_from(&start);
        assert!(d.energy < 1e-13, "n={n}: energy drift {:e}", d.energy);
        // |L|² (the first Casimir) is quadratic: conserved
        assert!((now.casimirs[0] - start.casimirs[0]).abs() < 1e-13 * start.casimirs[0]);
        if n == 4 {
            // in 4D both Casimirs are quadratic (|L|² and Pf)
            assert!(d.casimirs < 1e-13, "n=4: Casimir drift {:e}", d.casimirs);
        }
        assert!(body.principal_frame_attitude().unit_error() < 1e-13);
        assert!(
            m.mean_iterations() > 1.0 && m.mean_iterations() < 30.0,
            "{}",
            m.mean_iterations()
        );
        assert!(m.last_iterations() <= m.max_iterations());
    }
    // the solve is bounded: with 3 iterations allowed where ~30 are needed, the step fails
    // clearly after exactly 3 and leaves the body untouched
    let mut body = random_body(&mut r, 4);
    let before = body.clone();
    let mut m = Midpoint::with_tolerance(1e-15, 3);
    let err = m.step(&mut body, 0.0, 0.5, &Free).unwrap_err();
    assert!(
        matches!(
            err,
            DynamicsError::SolverDidNotConverge { iterations: 3, .. }
        ),
        "{err}"
    );
    assert_eq!(body, before);
}
