//! Contact between moving bodies, checked against the physics of collisions rather than the
//! code's own output: equal balls exchange velocities, unequal ones leave with the
//! textbook velocities, an oblique elastic collision of equal balls leaves at right angles,
//! and collisions of random convex bodies with spin, friction and restitution keep the
//! momenta and never gain energy.

use crate::rng;
use rand::Rng;
use rotorflow::dynamics::motion::{MotionIntegrator, MotionSplitting, MovingBody, System};
use rotorflow::inertia::spec::parse_body;
use rotorflow::prelude::*;

fn vector(c: &[f64]) -> Vector {
    Vector::from_components(c).unwrap()
}

pub(crate) fn padded(n: usize, c: &[f64]) -> Vector {
    let mut v = vec![0.0; n];
    v[..c.len()].copy_from_slice(c);
    vector(&v)
}

/// A ball of radius 0.5 and mass `mass` in N dimensions at `x` with velocity `v`, with the
/// given restitution and no friction.
fn ball(n: usize, mass: f64, x: &[f64], v: &[f64], restitution: f64) -> MovingBody {
    let parsed = parse_body(&format!("ball:{n},0.5+mass={mass}")).unwrap();
    MovingBody::from_parsed(
        &parsed,
        Rotor::identity(n),
        &padded(n, x),
        &padded(n, v),
        &Bivector::zero(n),
    )
    .unwrap()
    .with_restitution(restitution)
    .unwrap()
    .with_friction(0.0)
    .unwrap()
}

fn run(system: &mut System, h: f64, steps: usize) {
    let mut stepper = MotionSplitting::new();
    for k in 0..steps {
        stepper.step(system, k as f64 * h, h).unwrap();
    }
}

/// Head-on elastic collisions in 3D and 4D: equal balls exchange velocities to 1e-9;
/// masses m₁ = 1, m₂ = 3 leave with (m₁ − m₂)/(m₁ + m₂) v and 2m₁/(m₁ + m₂) v; the impact is
/// located in time, so the positions after it are those of the exact collision.
#[test]
fn head_on_elastic_collisions_give_the_textbook_velocities() {
    let mut cases = 0;
    for n in [3, 4] {
        for (m1, m2) in [(1.0, 1.0), (1.0, 3.0), (2.5, 0.7)] {
            let v = 1.3;
            let a = ball(n, m1, &[-1.0], &[v], 1.0);
            let b = ball(n, m2, &[0.6], &[0.0], 1.0);
            let mut s = System::new(vec![a, b]).unwrap();
            // Contact at t_c = (1.6 − 1)/v; run to t = 1.
            let (h, steps) = (1e-2, 100);
            run(&mut s, h, steps);
            let v1 = (m1 - m2) / (m1 + m2) * v;
            let v2 = 2.0 * m1 / (m1 + m2) * v;
            let got1 = s.bodies()[0].velocity().as_slice()[0];
            let got2 = s.bodies()[1].velocity().as_slice()[0];
            assert!(
                (got1 - v1).abs() <= 1e-9 * v && (got2 - v2).abs() <= 1e-9 * v,
                "N = {n}, masses {m1}, {m2}: {got1} {got2} against {v1} {v2}"
            );
            let tc = 0.6 / v;
            let t = h * steps as f64;
            let x1 = -1.0 + v * tc + v1 * (t - tc);
            let x2 = 0.6 + v2 * (t - tc);
            let p1 = s.bodies()[0].position().as_slice()[0];
            let p2 = s.bodies()[1].position().as_slice()[0];
            assert!(
                (p1 - x1).abs() <= 1e-8 && (p2 - x2).abs() <= 1e-8,
                "N = {n}, masses {m1}, {m2}: positions {p1} {p2} against {x1} {x2}"
            );
            // Head on: nothing moves off the line, nothing spins.
            for b in s.bodies() {
                assert!(b.velocity().as_slice()[1..].iter().all(|c| c.abs() < 1e-12));
                assert!(b.omega().max_abs() < 1e-12);
            }
            cases += 1;
        }
    }
    assert_eq!(cases, 6);
}

/// An oblique elastic collision of equal frictionless balls: the one at rest leaves along
/// the line of centres at impact, the other at right angles to it, with the momentum and
/// the energy kept.
#[test]
fn an_oblique_elastic_collision_of_equal_balls_leaves_at_right_angles() {
    for (n, offset) in [(3, 0.3), (3, 0.7), (4, 0.5), (5, 0.2)] {
        let a = ball(n, 1.0, &[-2.0, offset], &[1.0], 1.0);
        let b = ball(n, 1.0, &[0.0], &[0.0], 1.0);
        let mut s = System::new(vec![a, b]).unwrap();
        let (p0, e0) = (s.linear_momentum(), s.energy(0.0));
        run(&mut s, 1e-2, 400);
        let (va, vb) = (s.bodies()[0].velocity(), s.bodies()[1].velocity());
        assert!(vb.norm() > 0.1, "N = {n}: no collision");
        let cosine = va.dot(&vb) / (va.norm() * vb.norm()).max(1e-300);
        assert!(
            cosine.abs() <= 1e-9,
            "N = {n}, offset {offset}: cosine {cosine:e}"
        );
        assert!((&s.linear_momentum() - &p0).max_abs() <= 1e-12);
        assert!((s.energy(0.0) - e0).abs() <= 1e-12 * e0);
    }
}

/// A random convex body of the catalogue in N dimensions.
pub(crate) fn random_body(
    r: &mut impl Rng,
    n: usize,
    x: Vector,
    towards: f64,
    isotropic: bool,
) -> MovingBody {
    let mut lengths: Vec<String> = (0..n)
        .map(|_| format!("{:.3}", r.gen_range(0.3..0.7)))
        .collect();
    if isotropic {
        // Cubes and balls: their free rotation is exact, so any energy gained is the
        // contacts'.
        lengths = vec![lengths[0].clone(); n];
    }
    let spec = match r.gen_range(0..3) {
        0 => format!("cuboid:{}", lengths.join(",")),
        1 => format!("ellipsoid:{}", lengths.join(",")),
        _ => format!("ball:{n},{}", lengths[0]),
    };
    let parsed = parse_body(&format!("{spec}+mass={:.3}", r.gen_range(0.5..2.0))).unwrap();
    let mut v: Vec<f64> = (0..n).map(|_| r.gen_range(-0.5..0.5)).collect();
    v[0] += towards;
    let w: Vec<f64> = (0..n * (n - 1) / 2)
        .map(|_| r.gen_range(-2.0..2.0))
        .collect();
    let b: Vec<f64> = (0..n * (n - 1) / 2)
        .map(|_| r.gen_range(-1.0..1.0))
        .collect();
    MovingBody::from_parsed(
        &parsed,
        Rotor::from_rotation_bivector(&Bivector::from_components(n, &b).unwrap()),
        &x,
        &vector(&v),
        &Bivector::from_components(n, &w).unwrap(),
    )
    .unwrap()
    .with_friction(r.gen_range(0.0..1.0))
    .unwrap()
    .with_restitution(r.gen_range(0.0..1.0))
    .unwrap()
}

/// Pairs of random convex bodies (boxes, ellipsoids, balls) in N = 3 … 6, spinning, thrown
/// at each other with friction and restitution: the linear and angular momentum are kept to
/// 1e-9 relative. For cubes and balls, whose free rotation the splitting follows exactly,
/// the energy never grows (the free rotation of other bodies has an energy error of its own
/// that would hide the contacts').
#[test]
fn collisions_of_random_convex_bodies_keep_the_momenta_and_never_gain_energy() {
    let mut r = rng(3030);
    let mut collided = 0;
    for trial in 0..32 {
        let n = 3 + trial % 4;
        let isotropic = trial >= 16;
        let a = random_body(&mut r, n, padded(n, &[-1.2]), 1.5, isotropic);
        let b = random_body(&mut r, n, padded(n, &[1.2, 0.2]), -0.5, isotropic);
        let mut s = System::new(vec![a, b]).unwrap();
        let (p0, l0, e0) = (s.linear_momentum(), s.angular_momentum(), s.energy(0.0));
        let mut stepper = MotionSplitting::new();
        let h = 2e-3;
        let mut emax = e0;
        for k in 0..1000 {
            stepper.step(&mut s, k as f64 * h, h).unwrap();
            emax = emax.max(s.energy(0.0));
        }
        let touched = stepper.solver_report().solves > 0;
        let scale_p = p0.norm().max(1.0);
        let scale_l = l0.norm().max(1.0);
        assert!(
            (&s.linear_momentum() - &p0).max_abs() <= 1e-9 * scale_p,
            "trial {trial}, N = {n}: momentum {:e}",
            (&s.linear_momentum() - &p0).max_abs()
        );
        assert!(
            (&s.angular_momentum() - &l0).max_abs() <= 1e-9 * scale_l,
            "trial {trial}, N = {n}: angular momentum {:e}",
            (&s.angular_momentum() - &l0).max_abs()
        );
        assert!(
            !isotropic || emax <= e0 * (1.0 + 1e-9),
            "trial {trial}, N = {n}: energy grew by {:e}",
            emax / e0 - 1.0
        );
        if touched {
            collided += 1;
        }
    }
    assert!(collided >= 24, "only {collided} of 32 pairs collided");
}

/// A ball dropped from rest onto a fixed ball, centre above centre, rebounds straight up to
/// e² of its drop height (the free flight under gravity is exact, so the apex after the
/// bounce is read from any later state as z + v²/2g), in 3D and 4D; the fixed ball never
/// moves.
#[test]
fn a_ball_dropped_on_a_fixed_ball_rebounds_to_e_squared_of_its_drop_height() {
    use rotorflow::dynamics::motion::ContactShape;
    use rotorflow::dynamics::motion::forques::Gravity;
    let g = 9.81;
    let mut cases = 0;
    for n in [3, 4] {
        for e in [1.0, 0.8, 0.5] {
            let mut top = vec![0.0; n];
            top[n - 1] = 1.0;
            let up = vector(&top);
            let base = MovingBody::fixed(
                ContactShape::Ellipsoid(vec![0.5; n]),
                Rotor::identity(n),
                &Vector::zero(n),
            )
            .unwrap();
            let drop = 1.0;
            top[n - 1] = 1.0 + drop;
            let falling = ball(n, 1.0, &top, &[], e);
            let mut s = System::new(vec![base, falling]).unwrap();
            s.add_forque(Gravity(&up * -g)).unwrap();
            let mut stepper = MotionSplitting::new();
            let h = 1e-3;
            let mut apex = None;
            for k in 0..1200 {
                stepper.step(&mut s, k as f64 * h, h).unwrap();
                let b = &s.bodies()[1];
                let vz = b.velocity().as_slice()[n - 1];
                if vz > 0.0 && apex.is_none() {
                    let z = b.position().as_slice()[n - 1];
                    apex = Some(z + vz * vz / (2.0 * g));
                }
            }
            let apex = apex.expect("it bounced");
            let rebound = apex - 1.0;
            assert!(
                (rebound - e * e * drop).abs() <= 1e-6 * drop,
                "N = {n}, e = {e}: rebound {rebound} against {}",
                e * e * drop
            );
            let b = &s.bodies()[1];
            assert!(
                b.velocity().as_slice()[..n - 1]
                    .iter()
                    .all(|c| c.abs() < 1e-12)
            );
            let base = &s.bodies()[0];
            assert_eq!(base.position().max_abs(), 0.0);
            assert_eq!(base.velocity().max_abs(), 0.0);
            cases += 1;
        }
    }
    assert_eq!(cases, 6);
}

/// An impact is located in a few tries even where the least gap over the step is no
/// straight line: a ball 0.1 mm above the floor sinks onto it at 6 cm/s (a tenth of the way
/// into a step of 1/60 s), while another at 5 m/s, 2 cm above it, would end the step 4 cm
/// (10⁸ touching distances) deep. From the step's ends regula falsi alone crawls from the
/// start; the tries' bisections at the bracket's geometric mean and the scaling of a kept
/// end (Anderson–Björck) find the first contact in a handful. Each try is a substep ending
/// with its flight and taking one solve once a contact holds; the step counts its solves.
/// The slow ball then rests (e = 0 below the resting speed) and the fast one rebounds at
/// e = 0.5 of its impact speed (to 1e-6): both impacts were found.
#[test]
fn impacts_are_located_in_a_few_tries() {
    use rotorflow::dynamics::motion::HalfSpace;
    use rotorflow::dynamics::motion::forques::Gravity;
    let mut cases = 0;
    for n in [3, 4] {
        // Along the first axis and the vertical (the last).
        let at = |across: f64, height: f64| {
            let mut x = vec![0.0; n];
            (x[0], x[n - 1]) = (across, height);
            x
        };
        let slow = ball(n, 1.0, &at(-2.0, 0.5001), &at(0.0, -0.06), 0.5);
        let fast = ball(n, 1.0, &at(2.0, 0.52), &at(0.0, -5.0), 0.5);
        // A third ball rests on the floor: every try's opening solve has its contact.
        let resting = ball(n, 1.0, &at(0.0, 0.5), &at(0.0, 0.0), 0.0);
        let mut s = System::new(vec![slow, fast, resting]).unwrap();
        let up = vector(&at(0.0, 1.0));
        s.add_forque(Gravity(&up * -9.81)).unwrap();
        s.add_half_space(HalfSpace::new(&up, 0.0, 0.0, 0.5).unwrap())
            .unwrap();
        let mut stepper = MotionSplitting::new();
        let h = 1.0 / 60.0;
        stepper.step(&mut s, 0.0, h).unwrap();
        let solves = stepper.solver_report().solves;
        // The impact speed: 5 m/s plus what gravity adds over the 2 cm.
        let impact = (25.0 + 2.0 * 9.81 * 0.02f64).sqrt();
        // Rebound at e · impact, then gravity for the rest of the step.
        let t_impact = (impact - 5.0) / 9.81;
        let after = 0.5 * impact - 9.81 * (h - t_impact);
        let (v_slow, v_fast) = (
            s.bodies()[0].velocity().as_slice()[n - 1],
            s.bodies()[1].velocity().as_slice()[n - 1],
        );
        println!(
            "N = {n}: {solves} solves in the step, rebound {v_fast} (expected {after}), resting {v_slow}"
        );
        assert!(
            (v_fast - after).abs() <= 1e-6,
            "N = {n}: rebound {v_fast}, expected {after}"
        );
        assert!(
            v_slow.abs() <= 1e-9,
            "N = {n}: the slow ball moves at {v_slow}"
        );
        assert!(solves <= 60, "N = {n}: {solves} solves");
        cases += 1;
    }
    assert_eq!(cases, 2);
}
