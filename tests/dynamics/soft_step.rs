//! The soft step ([`SoftStep`]): a fixed amount of solver work per step with soft contacts.
//! Checked against physics, not its own output: towers stand within the bounds of a stable
//! stack, a body resting on a half-space sits in it by the spring's static deflection
//! g/(2πf)², a box on a ramp slides with a = g(sin θ − μ cos θ), collisions keep the linear
//! momentum to round-off and never gain energy, a free fall converges at order 1, a fast
//! fall is met within the step, and systems with joints are refused.

use super::body_contact::{padded, random_body};
use super::stacks::{axis, ramp_run, tower_with, turned_cube};
use crate::rng;
use rotorflow::dynamics::DynamicsError;
use rotorflow::dynamics::motion::forques::{Anchor, Gravity};
use rotorflow::dynamics::motion::{
    BallJoint, Forque, ForqueInput, HalfSpace, MotionError, MotionIntegrator, MovingBody, SoftStep,
    System, Wrench,
};
use rotorflow::inertia::spec::parse_body;
use rotorflow::prelude::*;

const G: f64 = 9.81;

/// The floor x_{N−1} = 0, friction 0.5 and restitution `restitution`.
fn floor(n: usize, restitution: f64) -> HalfSpace {
    HalfSpace::new(&axis(n, n - 1, 1.0), 0.0, 0.5, restitution).unwrap()
}

/// `bodies` in N dimensions under gravity G along −x_{N−1}, on the [`floor`].
fn on_floor(n: usize, bodies: Vec<MovingBody>, restitution: f64) -> System {
    let mut s = System::new(bodies).unwrap();
    s.add_forque(Gravity(axis(n, n - 1, -G))).unwrap();
    s.add_half_space(floor(n, restitution)).unwrap();
    s
}

/// Six cubes in 3D and three 4D hypercubes each offset by 5 %, turned by ±3° or not,
/// dropped from 1 % of their size onto each other, stand for 10 s at h = 1/60 s and
/// 1e-3 s: the top box sinks less than 5e-3 (the springs' deflection), ends at rest (below
/// 1e-3 m/s) and slides less than 1e-2. Measured: at most 3.3e-3 (six unturned cubes at
/// h = 1/60 s). A cube landing on a cube tilted by the impact below it must touch along
/// the face: held at the one corner of the edge axis of a slightly wider gap, the turned
/// cubes spun at up to 1 rad/s on landing and the top slid 1.6e-2. With one pass per
/// substep instead of the two it takes in 4D, the hypercubes rock at 1e-2 m/s and slide by
/// 6e-2. Three offset hypercubes of 5 to 8 dimensions stand as well (at h = 1/60 s), where
/// a face holds 16 contact points: with two passes per substep they rocked at 0.04–0.09 m/s
/// and slid by up to 1.4e-2, with three (from 6D on) at 0.04 m/s; with the four they take,
/// speed at most 2.0e-13 m/s, slide 2.3e-4, sink 4.9e-4.
#[test]
fn towers_stand_under_the_soft_step() {
    let mut cases = 0;
    for (n, count, offset, h) in [
        (3, 6, 0.0, 1.0 / 60.0),
        (3, 6, 0.0, 1e-3),
        (4, 3, 0.05, 1.0 / 60.0),
        (4, 3, 0.05, 1e-3),
        (5, 3, 0.05, 1.0 / 60.0),
        (6, 3, 0.05, 1.0 / 60.0),
        (7, 3, 0.05, 1.0 / 60.0),
        (8, 3, 0.05, 1.0 / 60.0),
    ] {
        for turn in [0.0f64, 3.0] {
            let mut stepper = SoftStep::new();
            let o = tower_with(
                &mut stepper,
                n,
                count,
                (offset, turn.to_radians(), 0.01),
                h,
                10.0,
            );
            println!("N = {n}, {count} cubes, h = {h}, turned {turn}°: {o:?}");
            assert!(
                o.sink < 5e-3 && o.slide < 1e-2 && o.speed < 1e-3,
                "N = {n}, h = {h}, turned {turn}°: {o:?}"
            );
            cases += 1;
        }
    }
    assert_eq!(cases, 16);
}

/// A ball resting on a half-space sits in it by the static deflection of its contact
/// spring, g/(2πf)² (5 %) with f a quarter of the substep rate (the springs against fixed
/// bodies and half-spaces are twice the default fifth, up to that bound), in 3D to 6D, and
/// comes to rest.
#[test]
fn a_resting_ball_sits_in_the_floor_by_the_static_deflection() {
    for n in 3..=6 {
        for h in [1.0 / 60.0, 1.0 / 240.0] {
            let parsed = parse_body(&format!("ball:{n},0.5+mass=1")).unwrap();
            let ball = MovingBody::from_parsed(
                &parsed,
                Rotor::identity(n),
                &axis(n, n - 1, 0.5),
                &Vector::zero(n),
                &Bivector::zero(n),
            )
            .unwrap();
            let mut s = System::new(vec![ball]).unwrap();
            s.add_forque(Gravity(axis(n, n - 1, -G))).unwrap();
            s.add_half_space(HalfSpace::new(&axis(n, n - 1, 1.0), 0.0, 0.5, 0.0).unwrap())
                .unwrap();
            let mut stepper = SoftStep::new();
            stepper
                .advance(&mut s, 0.0, h, (2.0 / h).round() as usize)
                .unwrap();
            let b = &s.bodies()[0];
            let sink = 0.5 - b.position().as_slice()[n - 1];
            let f = 0.25 * 4.0 / h;
            let expected = G / (2.0 * std::f64::consts::PI * f).powi(2);
            println!("N = {n}, h = {h}: sink {sink:e}, expected {expected:e}");
            assert!(
                (sink - expected).abs() <= 0.05 * expected,
                "N = {n}, h = {h}: sink {sink:e} against {expected:e}"
            );
            assert!(b.velocity().norm() < 1e-9 && b.omega().norm() < 1e-9);
        }
    }
}

/// A unit cube on a fixed ramp slides with a = g(sin θ − μ cos θ) (1e-2 of g: the contact
/// springs' deflection changes the start) or sticks when μ > tan θ, in 3D to 6D.
#[test]
fn a_box_on_a_ramp_slides_with_the_coulomb_acceleration_under_the_soft_step() {
    let mut cases = 0;
    for n in 3..=6 {
        for (theta_deg, mu) in [(30.0f64, 0.3), (30.0, 0.7), (20.0, 0.1), (40.0, 0.5)] {
            let theta = theta_deg.to_radians();
            let (acceleration, _) = ramp_run(&mut SoftStep::new(), n, theta, mu);
            let expected = (G * (theta.sin() - mu * theta.cos())).max(0.0);
            println!("N = {n}, θ = {theta_deg}°, μ = {mu}: a = {acceleration} against {expected}");
            assert!(
                (acceleration - expected).abs() <= 1e-2 * G,
                "N = {n}, θ = {theta_deg}°, μ = {mu}: a = {acceleration} against {expected}"
            );
            cases += 1;
        }
    }
    assert_eq!(cases, 16);
}

/// Pairs of random convex bodies in N = 3 … 6, spinning, thrown at each other with friction
/// and restitution: the impulses are equal and opposite, so the linear momentum is kept to
/// round-off (1e-12 relative); the angular momentum moves by the distance the two
/// centres travel during the step times the impulse, and by the angle the bodies turn
/// times their angular impulse (the rows' lever arms and inverse inertias are those of the
/// step's start), which the test bounds by 1e-2 relative at h = 1e-3 and checks to shrink
/// at least two-fold when h is divided by 4 (measured: at most 1.4e-3, at least 2.15-fold).
#[test]
fn soft_collisions_keep_the_linear_momentum_and_converge_in_angular_momentum() {
    let mut r = rng(3131);
    let mut collided = 0;
    let (mut worst, mut ratio) = (0.0f64, f64::INFINITY);
    for trial in 0..24 {
        let n = 3 + trial % 4;
        let a = random_body(&mut r, n, padded(n, &[-1.2]), 1.5, false);
        let b = random_body(&mut r, n, padded(n, &[1.2, 0.2]), -0.5, false);
        let mut errors = [0.0f64; 2];
        for (k, h) in [1e-3, 2.5e-4].into_iter().enumerate() {
            let mut s = System::new(vec![a.clone(), b.clone()]).unwrap();
            let (p0, l0) = (s.linear_momentum(), s.angular_momentum());
            let mut stepper = SoftStep::new();
            let steps = (2.0 / h) as usize;
            stepper.advance(&mut s, 0.0, h, steps).unwrap();
            let scale_p = p0.norm().max(1.0);
            let scale_l = l0.norm().max(1.0);
            let dp = (&s.linear_momentum() - &p0).max_abs();
            assert!(
                dp <= 1e-12 * scale_p,
                "trial {trial}, N = {n}, h = {h}: momentum {dp:e}"
            );
            errors[k] = (&s.angular_momentum() - &l0).max_abs() / scale_l;
        }
        println!("trial {trial}, N = {n}: angular momentum errors {errors:?}");
        if errors[0] > 1e-12 {
            collided += 1;
            worst = worst.max(errors[0]);
            ratio = ratio.min(errors[0] / errors[1]);
        }
    }
    println!("worst {worst:e}, least ratio {ratio}");
    assert!(collided >= 16, "only {collided} of 24 pairs collided");
    assert!(
        worst <= 1e-2 && ratio >= 2.0,
        "worst {worst:e}, least ratio {ratio}"
    );
}

/// Equal balls in a head-on elastic collision exchange their velocities, to 1e-2 of v (the
/// restitution pass acts once per step, on the approach speed of the step's start); the
/// momentum is kept to round-off and the energy does not grow.
#[test]
fn equal_balls_exchange_velocities_under_the_soft_step() {
    for n in [3, 4, 5] {
        let ball = |x: f64, v: f64| {
            let parsed = parse_body(&format!("ball:{n},0.5+mass=1")).unwrap();
            MovingBody::from_parsed(
                &parsed,
                Rotor::identity(n),
                &axis(n, 0, x),
                &axis(n, 0, v),
                &Bivector::zero(n),
            )
            .unwrap()
            .with_restitution(1.0)
            .unwrap()
            .with_friction(0.0)
            .unwrap()
        };
        let mut s = System::new(vec![ball(-1.0, 1.0), ball(1.0, 0.0)]).unwrap();
        let e0 = s.energy(0.0);
        let mut stepper = SoftStep::new();
        stepper.advance(&mut s, 0.0, 1.0 / 60.0, 120).unwrap();
        let (va, vb) = (s.bodies()[0].velocity(), s.bodies()[1].velocity());
        println!("N = {n}: {va:?} {vb:?}");
        assert!(va.norm() <= 1e-2 && (vb.as_slice()[0] - 1.0).abs() <= 1e-2);
        assert!(s.energy(0.0) <= e0 * (1.0 + 1e-12));
        assert!((s.linear_momentum().as_slice()[0] - 1.0).abs() <= 1e-14);
    }
}

/// Without contacts the soft step is the symplectic Euler splitting of its substeps: a body
/// thrown under gravity follows the parabola with an error proportional to h (halving h
/// halves it, to 1 %).
#[test]
fn a_free_fall_converges_at_order_one() {
    let n = 3;
    let parsed = parse_body("cuboid:0.3,0.4,0.5+mass=2").unwrap();
    let errors: Vec<f64> = [1e-2, 5e-3, 2.5e-3]
        .iter()
        .map(|&h| {
            let body = MovingBody::from_parsed(
                &parsed,
                Rotor::identity(n),
                &Vector::zero(n),
                &Vector::from_components(&[1.0, 0.0, 3.0]).unwrap(),
                &Bivector::zero(n),
            )
            .unwrap();
            let mut s = System::new(vec![body]).unwrap();
            s.add_forque(Gravity(axis(n, 2, -G))).unwrap();
            let mut stepper = SoftStep::new();
            stepper
                .advance(&mut s, 0.0, h, (1.0 / h).round() as usize)
                .unwrap();
            let z = s.bodies()[0].position().as_slice()[2];
            (z - (3.0 - 0.5 * G)).abs()
        })
        .collect();
    println!("free-fall errors {errors:?}");
    for w in errors.windows(2) {
        assert!((w[0] / w[1] - 2.0).abs() < 0.02, "{errors:?}");
    }
}

/// Joints are held by the splitting only: the soft step refuses a system with one.
#[test]
fn the_soft_step_refuses_joints() {
    let parsed = parse_body("ball:3,0.5+mass=1").unwrap();
    let body = |x: f64| {
        MovingBody::from_parsed(
            &parsed,
            Rotor::identity(3),
            &axis(3, 0, x),
            &Vector::zero(3),
            &Bivector::zero(3),
        )
        .unwrap()
    };
    let mut s = System::new(vec![body(0.0), body(2.0)]).unwrap();
    s.add_ball_joint(BallJoint {
        body: 0,
        point: axis(3, 0, 1.0),
        other: Anchor::Body(1, axis(3, 0, -1.0)),
    })
    .unwrap();
    let err = SoftStep::new().step(&mut s, 0.0, 0.01).unwrap_err();
    assert!(
        matches!(
            err,
            DynamicsError::Motion(MotionError::NeedsSplitting { .. })
        ),
        "{err}"
    );
    assert!(SoftStep::new().with_substeps(0).is_err());
    assert!(SoftStep::new().with_passes(0).is_err());
    assert!(SoftStep::new().with_contact_spring(-1.0, 10.0).is_err());
    assert!(SoftStep::new().with_contact_spring(30.0, f64::NAN).is_err());
}

/// The contacts a step records are what held the bodies: two boxes resting on each other
/// on a floor (3D to 5D, the upper one offset by 10 % and turned 20° in 3D and 4D, so that
/// the points and their own axes differ from the principal ones) take per step the floor's
/// impulse (m₁ + m₂) g h and the lower box's m₂ g h along the vertical (1e-6), with
/// normals from the lower body to the upper one, total impulses (normal and friction)
/// with no sideways part, no slip at rest, and points on the contact faces.
#[test]
fn the_soft_step_records_the_impulses_that_hold_the_bodies() {
    let mut cases = 0;
    for n in 3..=5 {
        let h = 1.0 / 60.0;
        let turn = if n <= 4 { 20f64.to_radians() } else { 0.0 };
        let yaw = Rotor::from_plane_angle(n, 0, 1, turn).unwrap();
        let mut low = vec![0.0; n];
        low[n - 1] = 0.5;
        let mut high = vec![0.0; n];
        high[0] = 0.1;
        high[n - 1] = 1.5;
        let bodies = vec![
            turned_cube(n, 0.5, &low, 0.5, Rotor::identity(n)),
            turned_cube(n, 0.5, &high, 0.5, yaw),
        ];
        let mut s = on_floor(n, bodies, 0.0);
        let mut stepper = SoftStep::new();
        stepper.advance(&mut s, 0.0, h, 240).unwrap();
        let floor: f64 = s.contacts().iter().map(|c| c.normal_impulse).sum();
        let between: f64 = s.body_contacts().iter().map(|c| c.normal_impulse).sum();
        println!(
            "N = {n}: {} floor points, {} points between the boxes, impulses {floor:e}, {between:e}",
            s.contacts().len(),
            s.body_contacts().len()
        );
        let weight = G * h;
        assert!(
            (floor - 2.0 * weight).abs() <= 2e-6 * weight,
            "N = {n}: floor {floor:e}"
        );
        assert!(
            (between - weight).abs() <= 1e-6 * weight,
            "N = {n}: between {between:e}"
        );
        assert!(s.contacts().len() >= 1 << (n - 1) && s.body_contacts().len() >= 4);
        for c in s.contacts() {
            assert_eq!((c.body, c.half_space), (0, 0));
            let at = s.bodies()[0].point_position(&c.point);
            assert!(
                at.as_slice()[n - 1].abs() < 1e-2,
                "N = {n}: floor point {at:?}"
            );
            assert!(c.slip.norm() < 1e-6, "N = {n}: {c:?}");
        }
        for c in s.body_contacts() {
            assert_eq!((c.a, c.b), (0, 1));
            assert!(
                (c.normal.as_slice()[n - 1] - 1.0).abs() < 1e-9,
                "N = {n}: {c:?}"
            );
            assert!(
                (c.point.as_slice()[n - 1] - 1.0).abs() < 1e-2,
                "N = {n}: {c:?}"
            );
        }
        // At rest the impulses push no body sideways: the sideways parts of each set
        // (friction, and the normals tilted as the soft contacts let the boxes tilt) cancel.
        let mut sums = (Vector::zero(n), Vector::zero(n));
        for c in s.contacts() {
            sums.0 += &c.friction_impulse;
        }
        for c in s.body_contacts() {
            sums.1 += &c.friction_impulse;
            sums.1 += &(&c.normal * c.normal_impulse);
        }
        let sideways = |v: &Vector| {
            v.as_slice()[..n - 1]
                .iter()
                .map(|x| x * x)
                .sum::<f64>()
                .sqrt()
        };
        assert!(
            sideways(&sums.0) <= 1e-6 * weight && sideways(&sums.1) <= 1e-6 * weight,
            "N = {n}: impulse sums {sums:?}"
        );
        cases += 1;
    }
    assert_eq!(cases, 3);
}

/// A ball dropped by 1 % of its radius onto the middle of a box resting on a floor stays
/// there in 3D and 4D (10 s at h = 1/60 s): it moves less than 1e-3 sideways and ends
/// slower than 1e-4 m/s. A ball's contact points are found anew each step: kept as
/// material points they lag behind its rolling, and their impulses spun it up until it
/// rolled off the box (3D: 1.1e-2 in 10 s and speeding up).
#[test]
fn a_ball_resting_on_a_box_stays_on_it() {
    let mut cases = 0;
    for n in [3, 4] {
        let h = 1.0 / 60.0;
        let mut low = vec![0.0; n];
        low[n - 1] = 0.5;
        let parsed = parse_body(&format!("ball:{n},0.25+mass=1")).unwrap();
        let ball = MovingBody::from_parsed(
            &parsed,
            Rotor::identity(n),
            &axis(n, n - 1, 1.2525),
            &Vector::zero(n),
            &Bivector::zero(n),
        )
        .unwrap()
        .with_friction(0.5)
        .unwrap();
        let bodies = vec![turned_cube(n, 0.5, &low, 0.5, Rotor::identity(n)), ball];
        let mut s = on_floor(n, bodies, 0.0);
        SoftStep::new().advance(&mut s, 0.0, h, 600).unwrap();
        let ball = &s.bodies()[1];
        let x = ball.position().as_slice();
        let aside = x[..n - 1].iter().map(|x| x * x).sum::<f64>().sqrt();
        let speed = ball.velocity().norm();
        println!(
            "N = {n}: the ball moved {aside:e} sideways, speed {speed:e}, height {}",
            x[n - 1]
        );
        assert!(
            aside < 1e-3 && speed < 1e-4,
            "N = {n}: {aside:e}, {speed:e}"
        );
        assert!(
            (x[n - 1] - 1.25).abs() < 1e-3,
            "N = {n}: height {}",
            x[n - 1]
        );
        cases += 1;
    }
    assert_eq!(cases, 2);
}

/// `SoftStep::advance` records only the last step's contacts, and must move the bodies
/// exactly as that many calls of `step` do: two turned cubes falling onto each other and a
/// floor in 3D and 4D, every state compared to the last bit (their `Debug` text) after each
/// of several advances, and the contacts of the last step compared too.
#[test]
fn the_soft_step_advances_as_its_steps_do() {
    let mut cases = 0;
    for n in 3..=4 {
        let h = 1.0 / 60.0;
        let yaw = Rotor::from_plane_angle(n, 0, 1, 20f64.to_radians()).unwrap();
        let mut low = vec![0.0; n];
        low[n - 1] = 0.51;
        let mut high = vec![0.0; n];
        high[0] = 0.1;
        high[n - 1] = 1.6;
        let system = || {
            let bodies = vec![
                turned_cube(n, 0.5, &low, 0.5, Rotor::identity(n)),
                turned_cube(n, 0.5, &high, 0.5, yaw.clone()),
            ];
            on_floor(n, bodies, 0.3)
        };
        let (mut by_steps, mut by_advance) = (system(), system());
        let (mut stepper, mut advancer) = (SoftStep::new(), SoftStep::new());
        let mut t = 0.0;
        for steps in [1, 7, 30, 45] {
            for k in 0..steps {
                stepper.step(&mut by_steps, t + k as f64 * h, h).unwrap();
            }
            advancer.advance(&mut by_advance, t, h, steps).unwrap();
            t += steps as f64 * h;
            assert_eq!(
                format!("{:?}", by_steps.bodies()),
                format!("{:?}", by_advance.bodies()),
                "N = {n}, after {steps} more steps"
            );
            assert_eq!(
                format!("{:?} {:?}", by_steps.contacts(), by_steps.body_contacts()),
                format!(
                    "{:?} {:?}",
                    by_advance.contacts(),
                    by_advance.body_contacts()
                ),
                "N = {n}, after {steps} more steps"
            );
        }
        assert!(!by_advance.contacts().is_empty() && !by_advance.body_contacts().is_empty());
        cases += 1;
    }
    assert_eq!(cases, 2);
}

/// Contacts are found once per step, so a body must be met within the step by what it
/// reaches in it: each body's speculative margin holds how far it may move in the step. A
/// ball falling at 12 m/s, 10 cm above a cube resting on the floor, and a cube falling at
/// 12 m/s, 10 cm above the floor, each cover 20 cm in the first step of 1/60 s: far beyond
/// a margin of 5 % of the radii (5.6 cm between the ball and the 3D cube).
/// Each ends that step on what it fell on, not in it (depth below 1e-3; measured: at most
/// 3.4e-5), and rests on it after 2 s (depth below 1e-3, speed along the fall below 1e-3
/// m/s). With a margin of 5 % of the radii each ended the step 10 cm deep.
#[test]
fn a_fast_fall_is_met_within_the_step() {
    let h = 1.0 / 60.0;
    let mut cases = 0;
    for n in [3, 4] {
        let down = |x: f64| axis(n, n - 1, x);
        let mut low = vec![0.0; n];
        low[n - 1] = 0.5;
        // A ball onto a cube (a pair), and a cube onto the floor (a half-space).
        for onto_cube in [true, false] {
            let (spec, height) = if onto_cube {
                (format!("ball:{n},0.25+mass=1"), 1.35)
            } else {
                (format!("cuboid:{}+mass=1", vec!["0.5"; n].join(",")), 0.6)
            };
            let falling = MovingBody::from_parsed(
                &parse_body(&spec).unwrap(),
                Rotor::identity(n),
                &down(height),
                &down(-12.0),
                &Bivector::zero(n),
            )
            .unwrap();
            let mut bodies = vec![falling];
            if onto_cube {
                bodies.push(turned_cube(n, 0.5, &low, 0.5, Rotor::identity(n)));
            }
            let mut s = on_floor(n, bodies, 0.0);
            let mut stepper = SoftStep::new();
            // The falling body's lowest point against the top of what it falls on.
            let bottom = if onto_cube { 0.25 } else { 0.5 };
            let top = |s: &System| match s.bodies().get(1) {
                Some(cube) => cube.position().as_slice()[n - 1] + 0.5,
                None => 0.0,
            };
            let depth = |s: &System| top(s) - (s.bodies()[0].position().as_slice()[n - 1] - bottom);
            stepper.step(&mut s, 0.0, h).unwrap();
            let first = depth(&s);
            stepper.advance(&mut s, h, h, 119).unwrap();
            let rest = depth(&s);
            // Along the fall: a ball on a cube may roll (nothing stops a rolling ball).
            let sinking = s.bodies()[0].velocity().as_slice()[n - 1].abs();
            println!(
                "N = {n}, onto the cube {onto_cube}: depth {first:.2e} after the first step, \
                 {rest:.2e} after 2 s, speed along the fall {sinking:.1e}"
            );
            assert!(first < 1e-3, "N = {n}, onto the cube {onto_cube}: {first}");
            assert!(
                rest.abs() < 1e-3 && sinking < 1e-3,
                "N = {n}, onto the cube {onto_cube}: {rest}, {sinking}"
            );
            cases += 1;
        }
    }
    assert_eq!(cases, 4);
}

/// Under constant forces without torques the soft step keeps a substep's relax velocities
/// loaded into the next substep's solve, the kick added to them as F h / m, and hands the
/// bodies both solves' changes in one store; under any other forques it stores and loads
/// around each kick. The two must move the bodies alike: a cube resting on the floor, a
/// turned cube dropped onto it off centre and a ball thrown at both, in 3D and 4D, under
/// uniform gravity (constant) and under the same gravity as a closure (not constant), for
/// 30 steps of 1/60 s with impacts, sliding and rest. Positions and velocities agree to
/// 1e-9 (measured: at most 1.1e-12, in 4D; round-off grown over the impacts, as the two
/// sum the same changes in another order). Without the kick on the carried velocities they
/// part by 0.14.
#[test]
fn the_carried_relax_velocities_move_the_bodies_as_stores_and_loads_do() {
    let h = 1.0 / 60.0;
    let mut cases = 0;
    for n in [3, 4] {
        let run = |constant: bool| {
            let mut low = vec![0.0; n];
            low[n - 1] = 0.5;
            let mut high = vec![0.0; n];
            (high[0], high[n - 1]) = (0.3, 1.6);
            let turn = Rotor::from_plane_angle(n, 0, 1, 0.2).unwrap();
            let parsed = parse_body(&format!("ball:{n},0.25+mass=2")).unwrap();
            let ball = MovingBody::from_parsed(
                &parsed,
                Rotor::identity(n),
                &(padded(n, &[-1.5, 0.1]) + axis(n, n - 1, 0.6)),
                &(padded(n, &[4.0]) + axis(n, n - 1, 1.0)),
                &Bivector::zero(n),
            )
            .unwrap()
            .with_friction(0.5)
            .unwrap()
            .with_restitution(0.3)
            .unwrap();
            let bodies = vec![
                turned_cube(n, 0.5, &low, 0.5, Rotor::identity(n)),
                turned_cube(n, 0.5, &high, 0.5, turn),
                ball,
            ];
            let mut s = System::new(bodies).unwrap();
            let g = Gravity(axis(n, n - 1, -G));
            if constant {
                s.add_forque(g).unwrap();
            } else {
                s.add_forque(move |input: &ForqueInput<'_>, w: &mut [Wrench]| g.apply(input, w))
                    .unwrap();
            }
            s.add_half_space(floor(n, 0.0)).unwrap();
            SoftStep::new().advance(&mut s, 0.0, h, 30).unwrap();
            s
        };
        let (carried, stored) = (run(true), run(false));
        let mut worst = 0.0f64;
        for (a, b) in carried.bodies().iter().zip(stored.bodies()) {
            for (x, y) in [(a.position(), b.position()), (&a.velocity(), &b.velocity())] {
                worst = worst.max((x - y).norm());
            }
        }
        let moved = (carried.bodies()[1].position() - &axis(n, n - 1, 1.6)).norm();
        println!("N = {n}: largest difference {worst:e}; the dropped cube moved {moved:.3}");
        assert!(moved > 0.1, "N = {n}: the scene must move ({moved})");
        assert!(worst <= 1e-9, "N = {n}: {worst:e}");
        cases += 1;
    }
    assert_eq!(cases, 2);
}
