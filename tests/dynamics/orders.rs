//! Measured convergence orders: error at a fixed time against a fine reference, as the step
//! halves.

use crate::{random_body, rng, run};
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::{Integrator, RigidBody, Rkmk4, Splitting};

/// Error of (L, R) at time `t_end` with step `h`, against `reference`.
fn error(
    start: &RigidBody,
    integ: &mut dyn Integrator,
    t_end: f64,
    h: f64,
    reference: &RigidBody,
) -> f64 {
    let mut b = start.clone();
    let steps = (t_end / h).round() as usize;
    run(&mut b, integ, &Free, h, steps);
    let dl = (b.momentum() - reference.momentum()).max_abs();
    let dr = crate::attitude_distance(
        b.principal_frame_attitude(),
        reference.principal_frame_attitude(),
    );
    dl.max(dr)
}

fn measured_order(integ: &mut dyn Integrator, hs: [f64; 3]) -> f64 {
    let mut r = rng(301);
    let start = random_body(&mut r, 4);
    let t_end = 2.0;
    let mut reference = start.clone();
    run(
        &mut reference,
        &mut Splitting::yoshida4(),
        &Free,
        1e-4,
        20_000,
    );
    let e: Vec<f64> = hs
        .iter()
        .map(|&h| error(&start, integ, t_end, h, &reference))
        .collect();
    // least-squares slope of log e against log h over the three points
    let xs: Vec<f64> = hs.iter().map(|h| h.ln()).collect();
    let ys: Vec<f64> = e.iter().map(|x| x.ln()).collect();
    let (mx, my) = (xs.iter().sum::<f64>() / 3.0, ys.iter().sum::<f64>() / 3.0);
    let num: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let den: f64 = xs.iter().map(|x| (x - mx).powi(2)).sum();
    num / den
}

#[test]
fn rk4_is_fourth_order() {
    let p = measured_order(&mut Rkmk4, [0.04, 0.02, 0.01]);
    assert!((p - 4.0).abs() < 0.15, "measured order {p}");
}

#[test]
fn strang_is_second_order() {
    let p = measured_order(&mut Splitting::strang(), [0.02, 0.01, 0.005]);
    assert!((p - 2.0).abs() < 0.1, "measured order {p}");
}

#[test]
fn yoshida_is_fourth_order() {
    let p = measured_order(&mut Splitting::yoshida4(), [0.04, 0.02, 0.01]);
    assert!((p - 4.0).abs() < 0.15, "measured order {p}");
}

#[test]
fn implicit_midpoint_is_second_order() {
    let p = measured_order(
        &mut rotorflow::dynamics::Midpoint::default(),
        [0.02, 0.01, 0.005],
    );
    assert!((p - 2.0).abs() < 0.1, "measured order {p}");
}

mod adaptive {
    use crate::{random_body, rng, run};
    use rotorflow::dynamics::torques::Free;
    use rotorflow::dynamics::{Dopri5, DynamicsError, Integrator, Splitting};

    fn reference(
        start: &rotorflow::dynamics::RigidBody,
        t_end: f64,
    ) -> rotorflow::dynamics::RigidBody {
        let mut b = start.clone();
        let steps = (t_end / 2e-4).round() as usize;
        run(
            &mut b,
            &mut Splitting::yoshida4(),
            &Free,
            t_end / steps as f64,
            steps,
        );
        b
    }

    #[test]
    fn dopri5_meets_its_tolerance_and_scales_like_order_5() {
        let mut r = rng(311);
        let start = random_body(&mut r, 4);
        let t_end = 10.0;
        let reference = reference(&start, t_end);
        let mut counts = Vec::new();
        for tol in [1e-6, 1e-8, 1e-10] {
            let mut d = Dopri5::new(tol, tol);
            let mut b = start.clone();
            d.step(&mut b, 0.0, t_end, &Free).unwrap();
            let err = (b.momentum() - reference.momentum()).max_abs();
            assert!(err < 100.0 * tol, "tol {tol:e}: error {err:e}");
            assert!(b.principal_frame_attitude().unit_error() < 1e-13);
            counts.push(d.accepted_steps() as f64);
        }
        // N ∝ tol^(−1/5) for order 5: a factor 1e4 in tolerance is 10^(4/5) ≈ 6.3 in steps
        let ratio = counts[2] / counts[0];
        assert!(
            (4.0..10.0).contains(&ratio),
            "step ratio {ratio} ({counts:?})"
        );
    }

    #[test]
    fn dense_output_matches_landing_exactly() {
        let mut r = rng(312);
        let start = random_body(&mut r, 5);
        let times = [0.0, 0.37, 1.0, 2.5, 4.0];
        let mut d = Dopri5::new(1e-10, 1e-10);
        let dense = d.dense_samples(&start, &Free, &times).unwrap();
        assert_eq!(dense.len(), times.len());
        let mut b = start.clone();
        let mut t = 0.0;
        let mut exact = Dopri5::new(1e-12, 1e-12);
        for (k, &target) in times.iter().enumerate() {
            if target > t {
                exact.step(&mut b, t, target - t, &Free).unwrap();
                t = target;
            }
            let (rot, l) = &dense[k];
            assert!((l - b.momentum()).max_abs() < 1e-8, "t = {target}");
            let dr = crate::attitude_distance(rot, b.principal_frame_attitude());
            assert!(dr < 1e-8, "t = {target}: attitude {dr:e}");
            assert!(rot.unit_error() < 1e-13);
        }
    }

    #[test]
    fn a_stiff_case_errors_clearly_instead_of_looping() {
        // ω ~ 1e6 with an inertia ratio of 1e4: the bound on internal steps ends the attempt.
        let inertia =
            rotorflow::prelude::InertiaMap::from_principal_second_moments(&[1e-4, 1.0, 1.0, 1.0])
                .unwrap();
        let w = rotorflow::prelude::Bivector::from_components(4, &[1e6, 1e3, 0.0, 1e3, 0.0, 1e6])
            .unwrap();
        let mut body = rotorflow::dynamics::RigidBody::from_body_velocity(
            inertia,
            rotorflow::prelude::Rotor::identity(4),
            &w,
        )
        .unwrap();
        let mut d = Dopri5::new(1e-10, 1e-10).with_max_steps(1000);
        let err = d.step(&mut body, 0.0, 1.0, &Free).unwrap_err();
        assert!(matches!(err, DynamicsError::TooManySteps { .. }), "{err}");
    }
}

/// RK4 stays fourth order when the torque reads the attitude (a 4-D heavy top; the stage
/// attitudes carry the ¼h² a₁ × a₂ correction), and also at N = 10 where the attitude is a
/// matrix.
#[test]
fn rk4_is_fourth_order_with_an_attitude_dependent_torque() {
    use rotorflow::dynamics::torques::Gravity;
    use rotorflow::prelude::*;
    for n in [4usize, 10] {
        let mut r = rng(302);
        let moments: Vec<f64> = (0..n).map(|k| 0.5 + 0.2 * k as f64).collect();
        let start = RigidBody::from_body_momentum(
            InertiaMap::from_principal_second_moments(&moments).unwrap(),
            rotorflow::dynamics::Attitude::identity(n),
            &crate::random_bivector(&mut r, n, 1.0),
        )
        .unwrap();
        let gravity = Gravity {
            weight: Vector::basis(n, n - 1) * -2.0,
            offset: (Vector::basis(n, 0) + Vector::basis(n, 1)) * 0.7,
        };
        let state = |h: f64| {
            let mut b = start.clone();
            run(&mut b, &mut Rkmk4, &gravity, h, (2.0 / h).round() as usize);
            b
        };
        let reference = state(0.0025);
        let err = |h: f64| {
            let b = state(h);
            let dq = (b.principal_frame_attitude().to_matrix()
                - reference.principal_frame_attitude().to_matrix())
            .amax();
            (b.momentum() - reference.momentum()).max_abs().max(dq)
        };
        let (e1, e2) = (err(0.04), err(0.02));
        let p = (e1 / e2).log2();
        assert!(
            (p - 4.0).abs() < 0.25,
            "N = {n}: measured order {p} ({e1:e}, {e2:e})"
        );
    }
}
