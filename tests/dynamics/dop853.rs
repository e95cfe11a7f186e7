//! Dormand–Prince 8(5,3) on the group: its measured order with fixed steps (against the 3D
//! top's closed form and against a fine Yoshida reference), its cost against Dopri5 on the
//! 4D cuboid P4, its invariants, its dense output and its errors.

use crate::{attitude_distance, random_body, rng, run, slope, state_distance as distance};
use rotorflow::dynamics::torques::{Free, Gravity};
use rotorflow::dynamics::{
    Attitude, Dop853, Dopri5, DynamicsError, Integrator, Invariants, RigidBody, Rkmk4, Splitting,
};
use rotorflow::inertia::spec::parse_body;
use rotorflow::prelude::*;

/// `body` turning `k` times faster (L scaled by k): errors of an 8th-order method fall to
/// round-off within a few halvings, so the measurements start from large steps.
fn spun(body: &RigidBody, k: f64) -> RigidBody {
    RigidBody::from_body_momentum(
        body.inertia().clone(),
        body.principal_frame_attitude().clone(),
        &(body.momentum() * k),
    )
    .unwrap()
}

/// Fixed steps of size h up to `t_end`.
fn fixed(
    start: &RigidBody,
    h: f64,
    t_end: f64,
    torque: &dyn rotorflow::dynamics::Torque,
) -> RigidBody {
    let mut b = start.clone();
    run(
        &mut b,
        &mut Dop853::fixed_step(),
        torque,
        h,
        (t_end / h).round() as usize,
    );
    b
}

#[test]
fn eighth_order_against_the_closed_form_of_the_3d_top() {
    let inertia = InertiaMap::from_principal_second_moments(&[0.2, 0.5, 1.0]).unwrap();
    let l = Bivector::from_components(3, &[0.4, -0.9, 1.2]).unwrap();
    let start = RigidBody::from_body_velocity(inertia, Attitude::identity(3), &l).unwrap();
    let t_end = 8.0;
    let exact = start.exact_solution().unwrap().body_at(t_end).unwrap();
    let hs = [0.8, 0.4, 0.2];
    let es: Vec<f64> = hs
        .iter()
        .map(|&h| distance(&fixed(&start, h, t_end, &Free), &exact))
        .collect();
    let p = slope(&hs, &es);
    eprintln!("3D top: errors {es:?}, measured order {p:.2}");
    assert!((p - 8.0).abs() < 0.4, "measured order {p} ({es:?})");
}

#[test]
fn eighth_order_in_4d_and_5d_for_momentum_and_attitude() {
    // The book's 4D body and a 5D one, with momenta large enough that the errors of the
    // larger steps stand well above round-off.
    let cases: [(&[f64], &[f64]); 2] = [
        (&[0.3, 0.7, 1.1, 1.9], &[1.7, -0.9, 2.3, 1.1, -2.6, 3.4]),
        (
            &[0.4, 0.6, 0.9, 1.3, 1.8],
            &[1.1, -0.7, 0.9, 1.4, -1.2, 0.8, 1.9, -0.6, 1.3, 0.5],
        ),
    ];
    for (moments, l) in cases {
        let n = moments.len();
        let start = RigidBody::from_body_momentum(
            InertiaMap::from_principal_second_moments(moments).unwrap(),
            Attitude::identity(n),
            &Bivector::from_components(n, l).unwrap(),
        )
        .unwrap();
        let t_end = 2.0;
        // An independent reference: the fourth-order Yoshida splitting at a far smaller step.
        let mut reference = start.clone();
        run(
            &mut reference,
            &mut Splitting::yoshida4(),
            &Free,
            1e-4,
            20_000,
        );
        let hs = [0.5, 0.25, 0.125];
        let es: Vec<f64> = hs
            .iter()
            .map(|&h| distance(&fixed(&start, h, t_end, &Free), &reference))
            .collect();
        let p = slope(&hs, &es);
        eprintln!("N = {n}: errors {es:?}, measured order {p:.2}");
        // The 5D body's errors still fall a little faster than h⁸ over this range.
        assert!(
            (7.6..8.8).contains(&p),
            "N = {n}: measured order {p} ({es:?})"
        );
    }
}

/// With a torque that reads the attitude the stage attitudes R₀ exp(Aₛ) enter the momentum
/// equation; the order stays 8 (reference: the same method at a quarter of the finest step).
#[test]
fn eighth_order_with_an_attitude_dependent_torque() {
    let n = 4;
    let mut r = rng(854);
    let moments: Vec<f64> = (0..n).map(|k| 0.5 + 0.2 * k as f64).collect();
    let start = RigidBody::from_body_momentum(
        InertiaMap::from_principal_second_moments(&moments).unwrap(),
        Attitude::identity(n),
        &crate::random_bivector(&mut r, n, 1.0),
    )
    .unwrap();
    let gravity = Gravity {
        weight: Vector::basis(n, n - 1) * -2.0,
        offset: (Vector::basis(n, 0) + Vector::basis(n, 1)) * 0.7,
    };
    let t_end = 2.0;
    let reference = fixed(&start, 0.5 / 16.0, t_end, &gravity);
    let hs = [0.5, 0.25, 0.125];
    let es: Vec<f64> = hs
        .iter()
        .map(|&h| distance(&fixed(&start, h, t_end, &gravity), &reference))
        .collect();
    let p = slope(&hs, &es);
    eprintln!("heavy 4D top: errors {es:?}, measured order {p:.2}");
    assert!((p - 8.0).abs() < 0.5, "measured order {p} ({es:?})");
}

/// The solid 4D cuboid P4 with mass 1 and ω(0) = (0.3, −0.2, 0.5, 0.1, 0.4, −0.6).
fn p4() -> RigidBody {
    let parsed = parse_body("cuboid:1,1.3,1.7,2.2+mass=1").unwrap();
    let omega = Bivector::from_components(4, &[0.3, -0.2, 0.5, 0.1, 0.4, -0.6]).unwrap();
    RigidBody::from_body_velocity(parsed.inertia, Attitude::identity(4), &omega).unwrap()
}

/// ω at t = 100 with an integrator advancing in one call.
fn omega_at_100(integrator: &mut dyn Integrator) -> Bivector {
    let mut b = p4();
    integrator.step(&mut b, 0.0, 100.0, &Free).unwrap();
    b.omega()
}

#[test]
fn p4_reaches_1e_11_with_far_fewer_right_hand_sides_than_dopri5() {
    // Two references from different methods agree first: Dop853 and Dopri5 at their
    // tightest tolerances.
    let reference = omega_at_100(&mut Dop853::new(1e-15, 1e-16).unwrap());
    let dopri_reference = omega_at_100(&mut Dopri5::new(1e-14, 1e-16));
    let spread = (&reference - &dopri_reference).max_abs();
    eprintln!("P4 at t = 100: |Δω| between the references {spread:.1e}");
    assert!(spread < 2e-12, "references differ by {spread:e}");

    let mut d853 = Dop853::new(1e-12, 1e-14).unwrap();
    let e853 = (&omega_at_100(&mut d853) - &reference).max_abs();
    let rhs853 = d853.rhs_evaluations();
    let mut d5 = Dopri5::new(1e-13, 1e-15);
    let e5 = (&omega_at_100(&mut d5) - &reference).max_abs();
    // Dopri5 evaluates seven stages per attempted step.
    let rhs5 = 7 * (d5.accepted_steps() + d5.rejected_steps());
    eprintln!(
        "P4 at t = 100: dop853 (1e-12) |Δω| {e853:.1e} with {rhs853} right-hand sides \
         ({} accepted, {} rejected); dopri5 (1e-13) |Δω| {e5:.1e} with {rhs5}",
        d853.accepted_steps(),
        d853.rejected_steps()
    );
    assert!(e853 <= 1e-11, "dop853 error {e853:e}");
    assert!(e5 <= 1e-11, "dopri5 error {e5:e}");
    assert!(
        rhs853 * 3 < rhs5,
        "dop853 {rhs853} right-hand sides against dopri5 {rhs5}"
    );
    // Each step starts from f at the previous solution: twelve right-hand sides per
    // accepted step, eleven per rejected one, and one probe for the starting step.
    assert_eq!(
        rhs853,
        12 * d853.accepted_steps() + 11 * d853.rejected_steps() + 1
    );
}

#[test]
fn invariants_drift_within_the_tolerance_and_the_attitude_stays_on_the_group() {
    let mut r = rng(855);
    for n in [3usize, 4, 5, 6] {
        let start = random_body(&mut r, n);
        let before = Invariants::of(&start);
        let mut b = start.clone();
        let mut d = Dop853::new(1e-12, 1e-12).unwrap();
        let mut worst = 0.0f64;
        for k in 0..100 {
            d.step(&mut b, k as f64 * 0.5, 0.5, &Free).unwrap();
            let drift = Invariants::of(&b).drift_from(&before);
            worst = worst.max(drift.energy).max(drift.casimirs);
            assert!(
                drift.attitude < 1e-13,
                "N = {n}: attitude {:e}",
                drift.attitude
            );
        }
        eprintln!("N = {n}: energy/Casimir drift over t = 50 {worst:.1e}");
        assert!(worst < 1e-10, "N = {n}: drift {worst:e}");
    }
}

/// The continuous extension against a step landing on the same time: their difference is
/// the extension's error, O(h⁸) locally (order 7), so it falls by ≈ 2⁸ as h halves.
#[test]
fn dense_output_is_of_order_7_against_landing_directly() {
    let mut r = rng(856);
    let start = spun(&random_body(&mut r, 4), 4.0);
    let mut gaps = Vec::new();
    let hs = [0.4, 0.2, 0.1];
    for h in hs {
        let mut d = Dop853::fixed_step();
        let mut b = start.clone();
        d.step(&mut b, 1.0, h, &Free).unwrap();
        assert_eq!(d.last_step(), Some((1.0, h)));
        let mut gap = 0.0f64;
        for theta in [0.0, 0.17, 0.5, 0.83, 1.0] {
            let (rot, l) = d.dense_output(&b, &Free, 1.0 + theta * h).unwrap();
            assert!(rot.unit_error() < 1e-14);
            let mut direct = start.clone();
            if theta > 0.0 {
                Dop853::fixed_step()
                    .step(&mut direct, 1.0, theta * h, &Free)
                    .unwrap();
            }
            let g = (&l - direct.momentum())
                .max_abs()
                .max(attitude_distance(&rot, direct.principal_frame_attitude()));
            if theta == 0.0 || theta == 1.0 {
                // The extension interpolates both ends.
                assert!(g < 1e-14, "h = {h}, θ = {theta}: {g:e}");
            }
            gap = gap.max(g);
        }
        gaps.push(gap);
    }
    let p = slope(&hs, &gaps);
    eprintln!("dense output: gaps {gaps:?}, local order {p:.2}");
    assert!(p > 7.5, "local order {p} ({gaps:?})");
}

#[test]
fn dense_samples_match_landing_exactly() {
    let mut r = rng(857);
    let start = random_body(&mut r, 5);
    let times = [0.0, 0.37, 1.0, 2.5, 4.0, 9.0];
    let mut d = Dop853::new(1e-10, 1e-10).unwrap();
    let dense = d.dense_samples(&start, &Free, &times).unwrap();
    assert_eq!(dense.len(), times.len());
    let mut b = start.clone();
    let mut t = 0.0;
    let mut exact = Dop853::new(1e-13, 1e-13).unwrap();
    for (k, &target) in times.iter().enumerate() {
        if target > t {
            exact.step(&mut b, t, target - t, &Free).unwrap();
            t = target;
        }
        let (rot, l) = &dense[k];
        let dl = (l - b.momentum()).max_abs();
        let dr = attitude_distance(rot, b.principal_frame_attitude());
        assert!(
            dl < 1e-9 && dr < 1e-9,
            "t = {target}: |ΔL| {dl:e}, |ΔR| {dr:e}"
        );
        assert!(rot.unit_error() < 1e-13);
    }
}

#[test]
fn meets_its_tolerance_with_steps_scaling_like_order_8() {
    let mut r = rng(858);
    let start = random_body(&mut r, 4);
    let t_end = 10.0;
    let mut reference = start.clone();
    run(
        &mut reference,
        &mut Splitting::yoshida4(),
        &Free,
        2e-4,
        50_000,
    );
    let mut counts = Vec::new();
    for tol in [1e-6, 1e-8, 1e-10] {
        let mut d = Dop853::new(tol, tol).unwrap();
        let mut b = start.clone();
        d.step(&mut b, 0.0, t_end, &Free).unwrap();
        let err = (b.momentum() - reference.momentum()).max_abs();
        eprintln!(
            "tol {tol:e}: error {err:.1e}, {} accepted, {} rejected",
            d.accepted_steps(),
            d.rejected_steps()
        );
        assert!(err < 100.0 * tol, "tol {tol:e}: error {err:e}");
        counts.push(d.accepted_steps() as f64);
    }
    // Steps ∝ tol^(−1/8): a factor 1e4 in tolerance is 10^(1/2) ≈ 3.2 in steps.
    let ratio = counts[2] / counts[0];
    assert!(
        (2.0..5.0).contains(&ratio),
        "step ratio {ratio} ({counts:?})"
    );
}

#[test]
fn bad_tolerances_and_bad_states_are_errors() {
    for (rtol, atol) in [
        (f64::NAN, 1e-8),
        (1e-8, f64::INFINITY),
        (-1e-8, 1e-8),
        (1e-8, -1.0),
        (0.0, 0.0),
    ] {
        let err = Dop853::new(rtol, atol).unwrap_err();
        assert!(
            matches!(err, DynamicsError::InvalidTolerance { .. }),
            "({rtol}, {atol}): {err}"
        );
    }
    // A state that overflows within a step (as in the adversarial Dopri5 regression).
    let inertia =
        InertiaMap::from_principal_second_moments(&[3.281159545697099e-222, 0.0]).unwrap();
    let l = Bivector::from_components(2, &[-4.9729193217462704e86]).unwrap();
    let mut body = RigidBody::from_body_momentum(inertia, Attitude::identity(2), &l).unwrap();
    let result = Dop853::new(1e-8, 1e-8)
        .unwrap()
        .with_max_steps(2_000)
        .step(&mut body, 0.0, 10.0, &Free);
    assert!(
        matches!(result, Err(DynamicsError::NonFinite { .. })),
        "{result:?}"
    );
    let mut body = random_body(&mut rng(859), 4);
    let mut d = Dop853::new(1e-8, 1e-8).unwrap();
    assert!(matches!(
        d.dense_output(&body, &Free, 0.0),
        Err(DynamicsError::InvalidSampling { .. })
    ));
    for h in [f64::NAN, f64::INFINITY] {
        assert!(matches!(
            d.step(&mut body, 0.0, h, &Free),
            Err(DynamicsError::InvalidSampling { .. })
        ));
    }
    d.step(&mut body, 0.0, 0.5, &Free).unwrap();
    let (t0, h) = d.last_step().unwrap();
    assert!(matches!(
        d.dense_output(&body, &Free, t0 + 2.0 * h),
        Err(DynamicsError::InvalidSampling { .. })
    ));
    assert!(matches!(
        d.dense_samples(&body, &Free, &[0.0, f64::NAN]),
        Err(DynamicsError::InvalidSampling { .. })
    ));
    assert!(matches!(
        Dop853::fixed_step().dense_samples(&body, &Free, &[0.0, 1.0]),
        Err(DynamicsError::InvalidSampling { .. })
    ));
    // A stiff case ends on the step bound instead of looping.
    let inertia = InertiaMap::from_principal_second_moments(&[1e-4, 1.0, 1.0, 1.0]).unwrap();
    let w = Bivector::from_components(4, &[1e6, 1e3, 0.0, 1e3, 0.0, 1e6]).unwrap();
    let mut stiff = RigidBody::from_body_velocity(inertia, Rotor::identity(4), &w).unwrap();
    let err = Dop853::new(1e-10, 1e-10)
        .unwrap()
        .with_max_steps(1000)
        .step(&mut stiff, 0.0, 1.0, &Free)
        .unwrap_err();
    assert!(matches!(err, DynamicsError::TooManySteps { .. }), "{err}");
}

/// The book's table of right-hand sides on P4 (`book/src/generated/long_runs.tsv`, written
/// by `examples/book_long_runs.rs`) holds for the code as it is: each adaptive run evaluates
/// exactly the recorded number of right-hand sides, and every row reaches the recorded
/// |Δω| at t = 100 (to 1%).
#[test]
fn the_book_right_hand_side_counts_on_p4_hold() {
    let reference = omega_at_100(&mut Dop853::new(1e-15, 1e-16).unwrap());
    let data = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/book/src/generated/long_runs.tsv"
    ))
    .unwrap();
    let mut checked = 0;
    for line in data.lines().filter(|l| l.starts_with("rhs\t")) {
        let fields: Vec<&str> = line.split('\t').collect();
        let (method, setting) = (fields[1], fields[2]);
        let recorded: f64 = fields[3].parse().unwrap();
        let rhs: usize = fields[4].parse().unwrap();
        let value: f64 = setting.rsplit(' ').next().unwrap().parse().unwrap();
        let (omega, counted) = match method {
            "`Dop853`" => {
                let mut d = Dop853::new(value, value * 1e-2).unwrap();
                (omega_at_100(&mut d), d.rhs_evaluations())
            }
            "`Dopri5`" => {
                let mut d = Dopri5::new(value, value * 1e-2);
                (omega_at_100(&mut d), d.rhs_evaluations())
            }
            "`Rkmk4`" => {
                let steps = (100.0 / value).round() as usize;
                let mut b = p4();
                run(&mut b, &mut Rkmk4, &Free, value, steps);
                (b.omega(), 4 * steps)
            }
            other => panic!("no integrator for {other}"),
        };
        let e = (&omega - &reference).max_abs();
        assert_eq!(counted, rhs, "{method} {setting}");
        assert!(
            (e - recorded).abs() <= 0.01 * recorded,
            "{method} {setting}: {e:e} against the recorded {recorded:e}"
        );
        checked += 1;
    }
    assert_eq!(checked, 6);
}

#[test]
fn a_negative_step_runs_back_to_the_start() {
    let start = p4();
    let mut b = start.clone();
    let mut d = Dop853::new(1e-12, 1e-14).unwrap();
    d.step(&mut b, 0.0, 10.0, &Free).unwrap();
    let mut back = Dop853::new(1e-12, 1e-14).unwrap();
    back.step(&mut b, 10.0, -10.0, &Free).unwrap();
    let gap = distance(&b, &start);
    assert!(gap < 1e-10, "{gap:e}");
}
