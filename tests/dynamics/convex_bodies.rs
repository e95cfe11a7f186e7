//! Moving bodies that touch with any convex shape of the catalogue
//! (`ContactShape::Convex`): capsules, rounded boxes, balls as a point with a margin,
//! cross-polytopes and simplices, checked against closed forms (resting heights, the
//! velocities of a head-on elastic collision) and conserved quantities.

use super::body_contact::padded;
use super::stacks::axis;
use crate::rng;
use rand::Rng;
use rotorflow::dynamics::DynamicsError;
use rotorflow::dynamics::motion::forques::Gravity;
use rotorflow::dynamics::motion::shape::ConvexShape;
use rotorflow::dynamics::motion::{
    ContactShape, HalfSpace, MotionError, MotionIntegrator, MotionSplitting, MovingBody, SoftStep,
    System,
};
use rotorflow::inertia::spec::parse_body;
use rotorflow::prelude::*;

const G: f64 = 9.81;

/// A body of mass 1 with the inertia of `spec`, touching with `shape`, at `x` with velocity
/// `v` and attitude `attitude`.
fn body(spec: &str, shape: ConvexShape, x: Vector, v: Vector, attitude: Rotor) -> MovingBody {
    let n = x.dim();
    let parsed = parse_body(&format!("{spec}+mass=1")).unwrap();
    MovingBody::from_parsed(&parsed, attitude, &x, &v, &Bivector::zero(n))
        .unwrap()
        .with_shape(ContactShape::Convex(shape))
        .unwrap()
}

/// The shapes that rest on a floor, with the height of their centre above it at rest.
fn resting_shapes(n: usize) -> Vec<(&'static str, ConvexShape, f64)> {
    vec![
        // Lying along e₁, on the sides of its two caps.
        ("capsule", ConvexShape::capsule(n, 0.4, 0.2).unwrap(), 0.2),
        (
            "rounded box",
            ConvexShape::cuboid(&vec![0.3; n])
                .unwrap()
                .rounded(0.1)
                .unwrap(),
            0.4,
        ),
        ("ball", ConvexShape::ball(n, 0.5).unwrap(), 0.5),
        ("box", ConvexShape::cuboid(&vec![0.35; n]).unwrap(), 0.35),
    ]
}

/// Capsules, rounded boxes, balls and boxes dropped from 1e-3 above a floor come to rest
/// with their centre at the height of their support point (the capsule's radius, the box's
/// half-length plus the margin), in 3D and 4D, under both integrators: to 1e-9 under the
/// splitting (impacts located), within the static deflection of the soft contacts (1e-4)
/// under the soft step.
#[test]
fn convex_shapes_come_to_rest_on_a_floor_at_their_support_height() {
    let mut cases = 0;
    for n in [3, 4] {
        for (name, shape, height) in resting_shapes(n) {
            for soft in [false, true] {
                let b = body(
                    "ball:3,0.4".replace('3', &n.to_string()).as_str(),
                    shape.clone(),
                    axis(n, n - 1, height + 1e-3),
                    Vector::zero(n),
                    Rotor::identity(n),
                );
                let mut s = System::new(vec![b.with_friction(0.5).unwrap()]).unwrap();
                s.add_forque(Gravity(axis(n, n - 1, -G))).unwrap();
                s.add_half_space(HalfSpace::new(&axis(n, n - 1, 1.0), 0.0, 0.5, 0.0).unwrap())
                    .unwrap();
                let h = 0.01;
                if soft {
                    SoftStep::new().advance(&mut s, 0.0, h, 200).unwrap();
                } else {
                    MotionSplitting::new().advance(&mut s, 0.0, h, 200).unwrap();
                }
                let b = &s.bodies()[0];
                let z = b.position().as_slice()[n - 1];
                let speed = b.velocity().norm() + b.omega().norm();
                println!(
                    "N = {n}, {name}, soft {soft}: height {z} (expected {height}), speed {speed:e}"
                );
                let (tolerance, still) = if soft { (1e-4, 1e-9) } else { (1e-9, 1e-12) };
                assert!(
                    (z - height).abs() <= tolerance && speed <= still,
                    "N = {n}, {name}, soft {soft}: height {z} against {height}, speed {speed:e}"
                );
                cases += 1;
            }
        }
    }
    assert_eq!(cases, 2 * 4 * 2);
}

/// Two equal capsules on one line along their axes, one thrown at the other without
/// friction and with restitution 1: their caps meet centre on centre, so the impulse passes
/// through both centres of mass and they exchange velocities (1e-9), at the time of the
/// exact collision (positions after it to 1e-8), with no spin; in 3D, 4D and 5D.
#[test]
fn capsules_meeting_cap_on_cap_exchange_velocities() {
    let mut cases = 0;
    for n in [3, 4, 5] {
        let capsule = |x: f64, v: f64| {
            body(
                &format!("ellipsoid:0.6{}", ",0.2".repeat(n - 1)),
                ConvexShape::capsule(n, 0.4, 0.2).unwrap(),
                padded(n, &[x]),
                padded(n, &[v]),
                Rotor::identity(n),
            )
            .with_friction(0.0)
            .unwrap()
            .with_restitution(1.0)
            .unwrap()
        };
        let v = 1.1;
        let mut s = System::new(vec![capsule(-1.0, v), capsule(0.5, 0.0)]).unwrap();
        let (h, steps) = (1e-2, 100);
        MotionSplitting::new()
            .advance(&mut s, 0.0, h, steps)
            .unwrap();
        let (v1, v2) = (
            s.bodies()[0].velocity().as_slice()[0],
            s.bodies()[1].velocity().as_slice()[0],
        );
        assert!(
            v1.abs() <= 1e-9 * v && (v2 - v).abs() <= 1e-9 * v,
            "N = {n}: {v1} {v2}"
        );
        // They touch when the centres are 2 (h + r) = 1.2 apart: at t_c = 0.3 / v.
        let (tc, t) = (0.3 / v, h * steps as f64);
        let p1 = s.bodies()[0].position().as_slice()[0];
        let p2 = s.bodies()[1].position().as_slice()[0];
        assert!(
            (p1 - (-1.0 + v * tc)).abs() <= 1e-8 && (p2 - (0.5 + v * (t - tc))).abs() <= 1e-8,
            "N = {n}: positions {p1} {p2}"
        );
        for b in s.bodies() {
            assert!(b.omega().max_abs() < 1e-12, "N = {n}: spin");
        }
        cases += 1;
    }
    assert_eq!(cases, 3);
}

/// A random shape of those `ContactShape::Convex` adds to the SPEC's: a capsule, a rounded
/// box, a cross-polytope, a simplex, a rounded simplex.
fn random_shape(r: &mut impl Rng, n: usize) -> ConvexShape {
    let size = r.gen_range(0.3..0.6);
    match r.gen_range(0..5) {
        0 => ConvexShape::capsule(n, size, 0.5 * size).unwrap(),
        1 => ConvexShape::cuboid(&vec![0.7 * size; n])
            .unwrap()
            .rounded(0.3 * size)
            .unwrap(),
        2 => ConvexShape::cross_polytope(n, size).unwrap(),
        3 => ConvexShape::simplex(n, size).unwrap(),
        _ => ConvexShape::simplex(n, 0.7 * size)
            .unwrap()
            .rounded(0.3 * size)
            .unwrap(),
    }
}

/// Pairs of random convex shapes in N = 3 … 5, spinning, turned, thrown at each other with
/// friction and restitution: the linear and angular momentum are kept to 1e-9 relative, and
/// the energy never grows (the bodies have a ball's inertia, whose free rotation the
/// splitting follows exactly, so any energy gained would be the contacts').
#[test]
fn collisions_of_convex_shapes_keep_the_momenta_and_never_gain_energy() {
    let mut r = rng(4242);
    let mut collided = 0;
    let trials = 24;
    for trial in 0..trials {
        let n = 3 + trial % 3;
        let planes = n * (n - 1) / 2;
        let mut make = |x: f64, towards: f64| {
            let shape = random_shape(&mut r, n);
            let b: Vec<f64> = (0..planes).map(|_| r.gen_range(-1.0..1.0)).collect();
            let w: Vec<f64> = (0..planes).map(|_| r.gen_range(-2.0..2.0)).collect();
            let mut v: Vec<f64> = (0..n).map(|_| r.gen_range(-0.3..0.3)).collect();
            v[0] += towards;
            let parsed =
                parse_body(&format!("ball:{n},0.4+mass={:.3}", r.gen_range(0.5..2.0))).unwrap();
            MovingBody::from_parsed(
                &parsed,
                Rotor::from_rotation_bivector(&Bivector::from_components(n, &b).unwrap()),
                &padded(n, &[x, 0.1 * towards]),
                &Vector::from_components(&v).unwrap(),
                &Bivector::from_components(n, &w).unwrap(),
            )
            .unwrap()
            .with_shape(ContactShape::Convex(shape))
            .unwrap()
            .with_friction(r.gen_range(0.0..1.0))
            .unwrap()
            .with_restitution(r.gen_range(0.0..1.0))
            .unwrap()
        };
        let a = make(-1.0, 1.5);
        let b = make(1.0, -0.5);
        let mut s = System::new(vec![a, b]).unwrap();
        let (p0, l0, e0) = (s.linear_momentum(), s.angular_momentum(), s.energy(0.0));
        let mut stepper = MotionSplitting::new();
        let h = 2e-3;
        let mut emax = e0;
        for k in 0..1000 {
            stepper.step(&mut s, k as f64 * h, h).unwrap();
            emax = emax.max(s.energy(0.0));
        }
        let dp = (&s.linear_momentum() - &p0).max_abs();
        let dl = (&s.angular_momentum() - &l0).max_abs();
        assert!(
            dp <= 1e-9 * p0.norm().max(1.0),
            "trial {trial}, N = {n}: momentum {dp:e}"
        );
        assert!(
            dl <= 1e-9 * l0.norm().max(1.0),
            "trial {trial}, N = {n}: angular momentum {dl:e}"
        );
        assert!(
            emax <= e0 * (1.0 + 1e-9),
            "trial {trial}, N = {n}: energy grew by {:e}",
            emax / e0 - 1.0
        );
        if stepper.solver_report().solves > 0 {
            collided += 1;
        }
    }
    assert!(collided >= 18, "only {collided} of {trials} pairs collided");
}

/// A convex shape of another dimension than the body's is refused with the dimensions.
#[test]
fn a_convex_shape_of_another_dimension_is_refused() {
    let parsed = parse_body("ball:3,0.5").unwrap();
    let b = MovingBody::from_parsed(
        &parsed,
        Rotor::identity(3),
        &Vector::zero(3),
        &Vector::zero(3),
        &Bivector::zero(3),
    )
    .unwrap();
    let err = b
        .with_shape(ContactShape::Convex(ConvexShape::ball(4, 0.5).unwrap()))
        .unwrap_err();
    assert!(
        matches!(
            err,
            DynamicsError::Motion(MotionError::WrongDimension {
                expected: 3,
                found: 4,
                ..
            })
        ),
        "{err}"
    );
}

/// A capsule lying on a box and a rounded box on a box (3D and 4D, 10 s at h = 1/60) come to
/// rest at the height of the box's top plus their support height: they touch by the
/// manifold of their cores (the segment's two ends, the rounded box's face), moved out by
/// their margins; one point at the pair's nearest points would let them rock for ever
/// (0.07–0.1 m/s). Under the splitting at rest to 1e-9 m/s and at their height to 1e-5
/// (impacts are located to 1e-6 of the radii); under the soft step within 1e-3 of the
/// height and the place they were dropped, slower than 1e-4 m/s.
#[test]
fn a_capsule_and_a_rounded_box_rest_on_a_box() {
    let mut cases = 0;
    for n in [3, 4] {
        let shapes = [
            ("capsule", ConvexShape::capsule(n, 0.4, 0.2).unwrap(), 0.2),
            (
                "rounded box",
                ConvexShape::cuboid(&vec![0.25; n])
                    .unwrap()
                    .rounded(0.05)
                    .unwrap(),
                0.3,
            ),
        ];
        for (name, shape, height) in shapes {
            for soft in [false, true] {
                let base = body(
                    &format!("cuboid:{}", vec!["0.5"; n].join(",")),
                    ConvexShape::cuboid(&vec![0.5; n]).unwrap(),
                    axis(n, n - 1, 0.5),
                    Vector::zero(n),
                    Rotor::identity(n),
                );
                let top = body(
                    &format!("ellipsoid:0.6{}", ",0.2".repeat(n - 1)),
                    shape.clone(),
                    axis(n, n - 1, 1.0 + height + 1e-3),
                    Vector::zero(n),
                    Rotor::identity(n),
                );
                let bodies = vec![
                    base.with_friction(0.5).unwrap(),
                    top.with_friction(0.5).unwrap(),
                ];
                let mut s = System::new(bodies).unwrap();
                s.add_forque(Gravity(axis(n, n - 1, -G))).unwrap();
                s.add_half_space(HalfSpace::new(&axis(n, n - 1, 1.0), 0.0, 0.5, 0.0).unwrap())
                    .unwrap();
                let h = 1.0 / 60.0;
                if soft {
                    SoftStep::new().advance(&mut s, 0.0, h, 600).unwrap();
                } else {
                    MotionSplitting::new().advance(&mut s, 0.0, h, 600).unwrap();
                }
                let b = &s.bodies()[1];
                let x = b.position().as_slice();
                let aside = x[..n - 1].iter().map(|x| x * x).sum::<f64>().sqrt();
                let z = x[n - 1] - 1.0;
                let speed = b.velocity().norm() + b.omega().norm();
                println!(
                    "N = {n}, {name} on a box, soft {soft}: height {z} (expected {height}), aside {aside:e}, speed {speed:e}"
                );
                let (tolerance, still) = if soft { (1e-3, 1e-4) } else { (1e-5, 1e-9) };
                assert!(
                    (z - height).abs() <= tolerance && aside <= tolerance && speed <= still,
                    "N = {n}, {name}, soft {soft}: height {z}, aside {aside:e}, speed {speed:e}"
                );
                cases += 1;
            }
        }
    }
    assert_eq!(cases, 2 * 2 * 2);
}
