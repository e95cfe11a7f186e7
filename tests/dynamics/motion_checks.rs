//! What a system of moving bodies refuses or reports instead of giving wrong physics: a body
//! that starts inside a plane, half-spaces nothing can touch, solves that do not converge;
//! bodies that bring their contact shapes; structured errors; `System` is `Send`.

use rotorflow::dynamics::DynamicsError;
use rotorflow::dynamics::motion::forques::{Anchor, Gravity};
use rotorflow::dynamics::motion::{
    BallJoint, ContactShape, HalfSpace, MotionError, MotionIntegrator, MotionSplitting, MovingBody,
    System,
};
use rotorflow::inertia::spec::parse_body;
use rotorflow::prelude::*;

fn axis(n: usize, i: usize, x: f64) -> Vector {
    let mut v = Vector::zero(n);
    v.as_mut_slice()[i] = x;
    v
}

/// A catalogue body at height `height` above the floor x_N = 0, under gravity, at rest.
fn on_floor(spec: &str, height: f64) -> System {
    let parsed = parse_body(spec).unwrap();
    let n = parsed.dim;
    let body = MovingBody::from_parsed(
        &parsed,
        Rotor::identity(n),
        &axis(n, n - 1, height),
        &Vector::zero(n),
        &Bivector::zero(n),
    )
    .unwrap();
    let mut s = System::new(vec![body]).unwrap();
    s.add_forque(Gravity(axis(n, n - 1, -9.81))).unwrap();
    s.add_half_space(HalfSpace::new(&axis(n, n - 1, 1.0), 0.0, 0.5, 0.0).unwrap())
        .unwrap();
    s
}

/// The lowest vertex of body 0 above the floor x_N = 0.
fn clearance(s: &System) -> f64 {
    let b = &s.bodies()[0];
    let n = s.dim();
    let ContactShape::Vertices(v) = b.shape() else {
        panic!("a box has vertices");
    };
    v.iter()
        .map(|r| b.point_position(r).as_slice()[n - 1])
        .fold(f64::INFINITY, f64::min)
}

/// A box placed 0.2 into the floor was ejected by the first step; now the step is refused
/// with the body, the half-space and the depth, in 3D and 4D, while a box placed exactly on
/// the floor (round-off of its placement only) steps.
#[test]
fn a_body_that_starts_inside_a_plane_is_refused_with_its_depth() {
    for (spec, n) in [("cuboid:0.5,0.5,0.5", 3), ("cuboid:0.5,0.5,0.5,0.5", 4)] {
        let mut inside = on_floor(spec, 0.3);
        let err = MotionSplitting::new()
            .step(&mut inside, 0.0, 1e-3)
            .unwrap_err();
        match err {
            DynamicsError::Motion(MotionError::StartsInside {
                body,
                half_space,
                depth,
                ..
            }) => {
                assert_eq!((body, half_space), (0, 0), "N = {n}");
                assert!((depth - 0.2).abs() < 1e-12, "N = {n}: depth {depth}");
            }
            other => panic!("N = {n}: {other}"),
        }
        // Nothing moved.
        assert_eq!(inside.bodies()[0].position().as_slice()[n - 1], 0.3);
        let message = MotionSplitting::new()
            .step(&mut inside, 0.0, 1e-3)
            .unwrap_err()
            .to_string();
        assert!(
            message.contains("body 0") && message.contains("half-space 0"),
            "{message}"
        );

        let mut touching = on_floor(spec, 0.5);
        let mut stepper = MotionSplitting::new();
        for k in 0..100 {
            stepper.step(&mut touching, k as f64 * 1e-3, 1e-3).unwrap();
        }
        assert!(clearance(&touching).abs() < 1e-12, "N = {n}");
    }
}

/// A catalogue body built with `MovingBody::from_parsed` brings its shape: dropped from 1 m
/// it lands and rests on the floor. The same body built from its mass and inertia alone has
/// no shape, and a system of it with a floor is refused instead of letting it fall through.
#[test]
fn a_catalogue_body_brings_its_contact_shape_and_a_shapeless_one_is_refused() {
    let mut s = on_floor("cuboid:0.5,0.4,0.3", 1.3);
    assert!(matches!(s.bodies()[0].shape(), ContactShape::Vertices(v) if v.len() == 8));
    assert_eq!(s.shapes()[0], *s.bodies()[0].shape());
    let mut stepper = MotionSplitting::new();
    stepper.advance(&mut s, 0.0, 1e-3, 2000).unwrap();
    let c = clearance(&s);
    assert!(c.abs() < 1e-9, "clearance {c}");
    assert!(s.bodies()[0].velocity().norm() < 1e-9);

    let parsed = parse_body("cuboid:0.5,0.4,0.3").unwrap();
    let bare = MovingBody::new(
        parsed.mass,
        parsed.inertia.clone(),
        Rotor::identity(3),
        &axis(3, 2, 1.3),
        &Vector::zero(3),
        &Bivector::zero(3),
    )
    .unwrap();
    assert_eq!(*bare.shape(), ContactShape::None);
    let mut s = System::new(vec![bare]).unwrap();
    s.add_half_space(HalfSpace::new(&axis(3, 2, 1.0), 0.0, 0.5, 0.0).unwrap())
        .unwrap();
    let err = MotionSplitting::new().step(&mut s, 0.0, 1e-3).unwrap_err();
    assert!(
        matches!(
            err,
            DynamicsError::Motion(MotionError::NothingTouches { half_spaces: 1 })
        ),
        "{err}"
    );
    // Giving it the shape afterwards makes the system steppable.
    s.set_shape(0, ContactShape::from_geometry(&parsed.geometry))
        .unwrap();
    assert!(matches!(s.bodies()[0].shape(), ContactShape::Vertices(_)));
    MotionSplitting::new().step(&mut s, 0.0, 1e-3).unwrap();
}

/// The solver counts its solves and sweeps. A resting box converges in every solve; a body
/// held twice at the same point (two joints with one freedom) makes the joints' matrix
/// singular, which the report counts and a strict splitting refuses.
#[test]
fn the_solver_reports_what_it_met_and_a_strict_splitting_refuses_it() {
    let mut s = on_floor("cuboid:0.5,0.5,0.5", 0.5);
    let mut stepper = MotionSplitting::new();
    stepper.advance(&mut s, 0.0, 1e-3, 200).unwrap();
    let report = stepper.solver_report();
    assert!(report.solves >= 200, "{report:?}");
    assert!(report.converged(), "{report:?}");
    assert!(report.max_sweeps >= 1, "{report:?}");
    stepper.reset_solver_report();
    assert_eq!(stepper.solver_report().solves, 0);

    let held_twice = || {
        let parsed = parse_body("cuboid:0.5,0.1,0.1").unwrap();
        let bar = MovingBody::from_parsed(
            &parsed,
            Rotor::identity(3),
            &axis(3, 0, 0.5),
            &Vector::zero(3),
            &Bivector::zero(3),
        )
        .unwrap();
        let mut s = System::new(vec![bar]).unwrap();
        s.add_forque(Gravity(axis(3, 2, -9.81))).unwrap();
        for _ in 0..2 {
            s.add_ball_joint(BallJoint {
                body: 0,
                point: axis(3, 0, -0.5),
                other: Anchor::World(Vector::zero(3)),
            })
            .unwrap();
        }
        s
    };
    let mut s = held_twice();
    let mut lenient = MotionSplitting::new();
    lenient.step(&mut s, 0.0, 1e-3).unwrap();
    let report = lenient.solver_report();
    assert!(report.singular_joint_solves > 0, "{report:?}");
    assert!(!report.converged());

    let mut s = held_twice();
    let err = MotionSplitting::new()
        .strict()
        .step(&mut s, 0.0, 1e-3)
        .unwrap_err();
    assert!(
        matches!(
            err,
            DynamicsError::Motion(MotionError::SingularJoints { .. })
        ),
        "{err}"
    );
}

/// Every refusal of a moving body or system is its own variant with the numbers that
/// locate it.
#[test]
fn motion_errors_are_structured() {
    let inertia = || InertiaMap::from_principal_second_moments(&[1.0, 2.0, 3.0]).unwrap();
    let zero = Vector::zero(3);
    let err = MovingBody::new(
        -1.0,
        inertia(),
        Rotor::identity(3),
        &zero,
        &zero,
        &Bivector::zero(3),
    )
    .unwrap_err();
    assert_eq!(
        err,
        DynamicsError::Motion(MotionError::OutOfRange {
            what: "mass",
            value: -1.0,
            expected: "a finite positive number",
        })
    );
    let err = MovingBody::new(
        1.0,
        inertia(),
        Rotor::identity(3),
        &Vector::zero(4),
        &zero,
        &Bivector::zero(3),
    )
    .unwrap_err();
    assert_eq!(
        err,
        DynamicsError::Motion(MotionError::WrongDimension {
            what: "position",
            expected: 3,
            found: 4,
        })
    );
    let err = HalfSpace::new(&axis(3, 2, 1.0), 0.0, 0.5, 2.0).unwrap_err();
    assert!(matches!(
        err,
        DynamicsError::Motion(MotionError::OutOfRange {
            what: "restitution",
            value: 2.0,
            ..
        })
    ));
    let err = HalfSpace::new(&zero, 0.0, 0.5, 0.5).unwrap_err();
    assert!(matches!(
        err,
        DynamicsError::Motion(MotionError::ZeroVector { what: "normal" })
    ));
    assert_eq!(
        System::new(Vec::new()).unwrap_err(),
        DynamicsError::Motion(MotionError::NoBody)
    );
    let body = MovingBody::new(
        1.0,
        inertia(),
        Rotor::identity(3),
        &zero,
        &zero,
        &Bivector::zero(3),
    )
    .unwrap();
    let mut s = System::new(vec![body.clone()]).unwrap();
    let err = s.set_shape(3, ContactShape::None).unwrap_err();
    assert_eq!(
        err,
        DynamicsError::Motion(MotionError::NoSuchBody {
            what: "shape",
            body: 3,
            count: 1,
        })
    );
    let err = body
        .with_shape(ContactShape::Ellipsoid(vec![1.0, 0.0, 1.0]))
        .unwrap_err();
    assert!(matches!(
        err,
        DynamicsError::Motion(MotionError::OutOfRange {
            what: "semi-axis",
            value: 0.0,
            ..
        })
    ));
}

/// A system, its forques included, can move to another thread.
#[test]
fn a_system_is_send() {
    fn send<T: Send>(_: T) {}
    let s = on_floor("cuboid:0.5,0.5,0.5", 0.5);
    send(s);
    let handle = std::thread::spawn(|| {
        let mut s = on_floor("cuboid:0.5,0.5,0.5", 0.5);
        MotionSplitting::new().step(&mut s, 0.0, 1e-3).unwrap();
        s
    });
    let s = handle.join().unwrap();
    assert!(s.bodies()[0].position().as_slice()[2] > 0.49);
}

/// The start check finds overlapping bodies among many through the broad phase, and agrees
/// with brute force over all pairs by the closed form (two balls overlap when their centres
/// are nearer than the sum of their radii): 1,200 balls of random radii scattered in a 3D or
/// 4D box are refused with the first overlapping pair in order, and the balls kept greedily
/// apart from each other start. Four scatterings in each dimension.
#[test]
fn the_start_check_finds_the_first_overlapping_pair_among_many_balls() {
    use rand::Rng;
    let mut r = super::rng(20261130);
    let mut cases = 0;
    for n in [3, 4] {
        for _ in 0..4 {
            let side = if n == 3 { 14.0 } else { 7.0 };
            let balls: Vec<(Vec<f64>, f64)> = (0..1_200)
                .map(|_| {
                    let x = (0..n).map(|_| r.gen_range(0.0..side)).collect();
                    (x, r.gen_range(0.1..0.3))
                })
                .collect();
            let overlap = |a: &(Vec<f64>, f64), b: &(Vec<f64>, f64)| {
                let d2: f64 = a.0.iter().zip(&b.0).map(|(p, q)| (p - q) * (p - q)).sum();
                d2.sqrt() < a.1 + b.1
            };
            let system = |balls: &[&(Vec<f64>, f64)]| {
                let bodies = balls
                    .iter()
                    .map(|(x, radius)| {
                        let parsed = parse_body(&format!("ball:{n},{radius}+mass=1")).unwrap();
                        MovingBody::from_parsed(
                            &parsed,
                            Rotor::identity(n),
                            &Vector::from_components(x).unwrap(),
                            &Vector::zero(n),
                            &Bivector::zero(n),
                        )
                        .unwrap()
                    })
                    .collect();
                System::new(bodies).unwrap()
            };
            let all: Vec<_> = balls.iter().collect();
            let first = (0..all.len())
                .flat_map(|a| (a + 1..all.len()).map(move |b| (a, b)))
                .find(|&(a, b)| overlap(all[a], all[b]))
                .expect("some scattered balls overlap");
            match system(&all).check_contacts() {
                Err(DynamicsError::Motion(MotionError::StartsOverlapping { a, b, .. })) => {
                    assert_eq!((a, b), first, "N = {n}");
                }
                other => panic!("N = {n}: expected the pair {first:?}, got {other:?}"),
            }
            let mut apart: Vec<&(Vec<f64>, f64)> = Vec::new();
            for ball in &balls {
                if apart.iter().all(|kept| !overlap(kept, ball)) {
                    apart.push(ball);
                }
            }
            assert!(apart.len() > 600, "N = {n}: {} kept", apart.len());
            system(&apart).check_contacts().unwrap();
            cases += 1;
        }
    }
    assert_eq!(cases, 8);
}
