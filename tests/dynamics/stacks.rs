//! Bodies resting on bodies: towers of boxes and hypercubes stand, and a box on a fixed ramp
//! slides with a = g(sin θ − μ cos θ) or sticks when μ > tan θ, and a box comes to rest on
//! a box in every dimension up to 8.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rotorflow::dynamics::motion::detect::{EpaWorkspace, PlacedShape, penetration_with};
use rotorflow::dynamics::motion::forques::Gravity;
use rotorflow::dynamics::motion::shape::ConvexShape;
use rotorflow::dynamics::motion::{
    ContactShape, HalfSpace, MotionIntegrator, MotionSplitting, MovingBody, SoftStep, System,
};
use rotorflow::inertia::spec::parse_body;
use rotorflow::prelude::*;

const G: f64 = 9.81;

pub(crate) fn axis(n: usize, i: usize, x: f64) -> Vector {
    let mut v = Vector::zero(n);
    v.as_mut_slice()[i] = x;
    v
}

/// A cube of half-length `half` and mass 1 in N dimensions at `x`, at rest.
#[allow(dead_code)]
fn cube(n: usize, half: f64, x: &[f64], friction: f64) -> MovingBody {
    turned_cube(n, half, x, friction, Rotor::identity(n))
}

/// [`cube`] with the attitude `attitude`.
pub(crate) fn turned_cube(
    n: usize,
    half: f64,
    x: &[f64],
    friction: f64,
    attitude: Rotor,
) -> MovingBody {
    moving_cube(
        n,
        half,
        x,
        friction,
        attitude,
        (&Vector::zero(n), &Bivector::zero(n)),
    )
}

/// [`turned_cube`] moving with velocity v and angular velocity ω.
fn moving_cube(
    n: usize,
    half: f64,
    x: &[f64],
    friction: f64,
    attitude: Rotor,
    (v, omega): (&Vector, &Bivector),
) -> MovingBody {
    let lengths = vec![format!("{half}"); n].join(",");
    let parsed = parse_body(&format!("cuboid:{lengths}+mass=1")).unwrap();
    MovingBody::from_parsed(
        &parsed,
        attitude,
        &Vector::from_components(x).unwrap(),
        v,
        omega,
    )
    .unwrap()
    .with_friction(friction)
    .unwrap()
}

/// What a tower did: how far its top box sank and slid from where it started, and its
/// speed at the end.
#[derive(Debug)]
pub(crate) struct Outcome {
    pub sink: f64,
    pub slide: f64,
    pub speed: f64,
}

/// `count` cubes of side 1 stacked on a floor in N dimensions, each shifted by `offset`
/// along the first axis from the one below, turned about the vertical by ±`turn` (radians,
/// alternating) and dropped from `drop` above the one below, run for `seconds` with step h.
/// The top box's sink is measured from its resting height, its slide from where it was
/// dropped.
fn tower(
    n: usize,
    count: usize,
    (offset, turn, drop): (f64, f64, f64),
    h: f64,
    seconds: f64,
) -> Outcome {
    tower_with(
        &mut MotionSplitting::new(),
        n,
        count,
        (offset, turn, drop),
        h,
        seconds,
    )
}

/// [`tower`] stepped by `stepper`.
pub(crate) fn tower_with(
    stepper: &mut dyn MotionIntegrator,
    n: usize,
    count: usize,
    (offset, turn, drop): (f64, f64, f64),
    h: f64,
    seconds: f64,
) -> Outcome {
    let mut s = tower_system(n, count, (offset, turn, drop));
    let mut start = s.bodies()[count - 1].position().clone();
    start.as_mut_slice()[n - 1] = count as f64 - 0.5;
    let steps = (seconds / h).round() as usize;
    stepper.advance(&mut s, 0.0, h, steps).unwrap();
    let top = &s.bodies()[count - 1];
    let moved = top.position() - &start;
    let slide = moved.as_slice()[..n - 1]
        .iter()
        .map(|x| x * x)
        .sum::<f64>()
        .sqrt();
    let speed = s
        .bodies()
        .iter()
        .map(|b| b.velocity().norm() + b.omega().norm())
        .fold(0.0, f64::max);
    Outcome {
        sink: -moved.as_slice()[n - 1],
        slide,
        speed,
    }
}

/// The system of [`tower_with`] before its first step.
fn tower_system(n: usize, count: usize, (offset, turn, drop): (f64, f64, f64)) -> System {
    let bodies: Vec<MovingBody> = (0..count)
        .map(|k| {
            let mut x = vec![0.0; n];
            x[0] = offset * k as f64;
            x[n - 1] = 0.5 + k as f64 * (1.0 + drop);
            let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
            let yaw = Rotor::from_plane_angle(n, 0, 1, sign * turn).unwrap();
            turned_cube(n, 0.5, &x, 0.5, yaw)
        })
        .collect();
    let mut s = System::new(bodies).unwrap();
    s.add_forque(Gravity(axis(n, n - 1, -G))).unwrap();
    s.add_half_space(HalfSpace::new(&axis(n, n - 1, 1.0), 0.0, 0.5, 0.0).unwrap())
        .unwrap();
    s
}

/// `MotionSplitting::advance` takes the steps that start with bodies touching each other
/// singly, so a tower that lands and rests moves as under single steps to the bit (joined
/// solves of bodies resting on each other drift into loads the contacts need not carry).
/// Three cubes set on each other offset by 5 % of their size, in 3D and 4D, 120 steps of
/// h = 1/60 s in calls of 40 against single steps: the same positions, velocities and
/// contacts, with each other and with the floor.
#[test]
fn a_tower_advances_as_its_single_steps_to_the_bit() {
    let mut cases = 0;
    for n in [3usize, 4] {
        let (mut single, mut advanced) = (
            tower_system(n, 3, (0.05, 0.0, 0.0)),
            tower_system(n, 3, (0.05, 0.0, 0.0)),
        );
        let (mut a, mut b) = (MotionSplitting::new(), MotionSplitting::new());
        let h = 1.0 / 60.0;
        for call in 0..3 {
            let t = (40 * call) as f64 * h;
            for k in 0..40 {
                a.step(&mut single, t + k as f64 * h, h).unwrap();
            }
            b.advance(&mut advanced, t, h, 40).unwrap();
        }
        for (x, y) in single.bodies().iter().zip(advanced.bodies()) {
            assert_eq!(x.position().as_slice(), y.position().as_slice(), "N = {n}");
            assert_eq!(x.velocity().as_slice(), y.velocity().as_slice(), "N = {n}");
        }
        assert!(
            single.body_contacts().len() >= 2,
            "N = {n}: the cubes rest on each other"
        );
        assert_eq!(single.body_contacts(), advanced.body_contacts(), "N = {n}");
        // The floor's too (`advance` records the contacts of its last step only).
        assert!(!single.contacts().is_empty(), "N = {n}: the tower stands");
        assert_eq!(single.contacts(), advanced.contacts(), "N = {n}");
        cases += 1;
    }
    assert_eq!(cases, 2);
}

/// The top box sinks less than 5e-3 and slides less than 1e-2 of its size and comes to rest:
/// the bounds a stable stack must meet. Measured: sink and slide at most 8e-9, speed at most
/// 4e-9 (h = 1/60 s; below 1e-10 at h = 1e-3 s), so the test holds them to about ten times that.
fn assert_stands(what: &str, o: &Outcome) {
    assert!(
        o.sink < 1e-8 && o.slide < 1e-7 && o.speed < 1e-7,
        "{what}: the top box sank {:e}, slid {:e}, ends at speed {:e}",
        o.sink,
        o.slide,
        o.speed
    );
}

/// Six unit cubes stacked in 3D, turned alternately by ±3° about the vertical and dropped
/// from 1 % of their size onto each other, stand for 10 s at h = 1/60 s and at h = 1e-3 s.
#[test]
fn a_tower_of_six_cubes_stands() {
    for h in [1.0 / 60.0, 1e-3] {
        let o = tower(3, 6, (0.0, 3f64.to_radians(), 0.01), h, 10.0);
        println!("six cubes, h = {h}: {o:?}");
        assert_stands(&format!("six cubes, h = {h}"), &o);
    }
}

/// Three 4D hypercubes stacked, each offset by 5 % of its size from the one below and
/// dropped from 1 % onto it, stand for 10 s at h = 1/60 s and at h = 1e-3 s; so do they
/// turned alternately by ±3° in the plane of the first two axes.
#[test]
fn three_offset_hypercubes_stand() {
    for (h, turn) in [
        (1.0 / 60.0, 0.0),
        (1e-3, 0.0),
        (1.0 / 60.0, 3.0),
        (1e-3, 3.0),
    ] {
        let o = tower(4, 3, (0.05, f64::to_radians(turn), 0.01), h, 10.0);
        println!("three hypercubes, h = {h}, turned {turn}°: {o:?}");
        assert_stands(&format!("three hypercubes, h = {h}, turned {turn}°"), &o);
    }
}

/// Three hypercubes of 5 to 8 dimensions, each offset by 5 % from the one below, turned
/// alternately by ±3° and dropped from 1 % onto it, stand for 10 s at h = 1/60 s under the
/// splitting, as the 4D ones do. Measured: sink 6.7e-10, slide at most 1.6e-11, speed at
/// most 8.8e-13 m/s.
#[test]
fn offset_towers_stand_in_five_to_eight_dimensions() {
    let mut cases = 0;
    for n in 5..=8 {
        let o = tower(n, 3, (0.05, 3f64.to_radians(), 0.01), 1.0 / 60.0, 10.0);
        println!("three {n}D cubes: {o:?}");
        assert_stands(&format!("three {n}D cubes"), &o);
        cases += 1;
    }
    assert_eq!(cases, 4);
}

/// What a unit cube did in 1 s on a fixed ramp (a fixed box tilted by θ, friction μ)
/// stepped by `stepper` at h = 1e-3 s: its acceleration along the ramp, downhill, and how far
/// it moved off the ramp's plane.
pub(crate) fn ramp_run(
    stepper: &mut dyn MotionIntegrator,
    n: usize,
    theta: f64,
    mu: f64,
) -> (f64, f64) {
    // The ramp: a fixed slab of half-lengths 20 × 0.5 (and 2 in the other axes), its top
    // face through the origin, tilted about the plane (x₁, x_N) by θ.
    let tilt = Rotor::from_plane_angle(n, 0, n - 1, theta).unwrap();
    let down = tilt.rotate_vector(&axis(n, n - 1, -0.5));
    let mut halves = vec![2.0; n];
    halves[0] = 20.0;
    halves[n - 1] = 0.5;
    let corners = (0..1usize << n)
        .map(|bits| {
            let c: Vec<f64> = (0..n)
                .map(|i| {
                    if bits >> i & 1 == 1 {
                        halves[i]
                    } else {
                        -halves[i]
                    }
                })
                .collect();
            Vector::from_components(&c).unwrap()
        })
        .collect();
    let ramp = MovingBody::fixed(ContactShape::Vertices(corners), tilt.clone(), &down)
        .unwrap()
        .with_friction(mu)
        .unwrap();
    let up = tilt.rotate_vector(&axis(n, n - 1, 0.5));
    let block = turned_cube(n, 0.5, up.as_slice(), mu, tilt.clone());
    let mut s = System::new(vec![ramp, block]).unwrap();
    s.add_forque(Gravity(axis(n, n - 1, -G))).unwrap();
    let (h, steps) = (1e-3, 1000);
    stepper.advance(&mut s, 0.0, h, steps).unwrap();
    let t = h * steps as f64;
    // Along the ramp, downhill.
    let mut downhill = tilt.rotate_vector(&axis(n, 0, 1.0));
    if downhill.as_slice()[n - 1] > 0.0 {
        downhill = &downhill * -1.0;
    }
    let moved = s.bodies()[1].position() - &up;
    let normal = tilt.rotate_vector(&axis(n, n - 1, 1.0));
    (2.0 * moved.dot(&downhill) / (t * t), moved.dot(&normal))
}

/// A unit cube on a fixed ramp (a fixed box tilted by θ) slides down with acceleration
/// a = g(sin θ − μ cos θ) when μ < tan θ and stays put when μ > tan θ (1e-3 relative to g),
/// in 3D to 6D.
#[test]
fn a_box_on_a_fixed_ramp_slides_with_the_coulomb_acceleration_or_sticks() {
    let mut cases = 0;
    for n in 3..=6 {
        for (theta_deg, mu) in [(30.0f64, 0.3), (30.0, 0.7), (20.0, 0.1), (40.0, 0.5)] {
            let theta = theta_deg.to_radians();
            let (acceleration, off) = ramp_run(&mut MotionSplitting::new(), n, theta, mu);
            let expected = (G * (theta.sin() - mu * theta.cos())).max(0.0);
            println!("N = {n}, θ = {theta_deg}°, μ = {mu}: a = {acceleration} against {expected}");
            assert!(
                (acceleration - expected).abs() <= 1e-3 * G,
                "N = {n}, θ = {theta_deg}°, μ = {mu}: a = {acceleration} against {expected}"
            );
            // It neither sinks into the ramp nor leaves it.
            assert!(off.abs() < 1e-4, "N = {n}: off the ramp by {off}");
            cases += 1;
        }
    }
    assert_eq!(cases, 16);
}

/// An impact without restitution between bodies is not located in time (a bracketing with
/// two solves per try): a unit cube dropped from 1e-3 onto another resting on the floor
/// meets it at √(2 g 1e-3) ≈ 0.14 m/s, and the step's closing solve holds it; dropped from
/// 0.1 it meets it at 1.4 m/s, and the step before its impact lets it close its gap and no
/// more (a speculative contact). Every step takes at most two solves (its opening and its
/// closing one), and the cube comes to rest at 1.5, on the cube below. With restitution
/// 0.5 the impact from 0.1 is located (more solves in its step), and the cube comes to
/// rest there too after its bounces.
#[test]
fn an_impact_between_bodies_is_located_only_where_it_bounces() {
    let h = 1.0 / 60.0;
    let mut cases = 0;
    for (drop, restitution, located) in [(1e-3, 0.0, false), (0.1, 0.0, false), (0.1, 0.5, true)] {
        let bodies = vec![
            cube(3, 0.5, &[0.0, 0.0, 0.5], 0.5),
            cube(3, 0.5, &[0.0, 0.0, 1.5 + drop], 0.5)
                .with_restitution(restitution)
                .unwrap(),
        ];
        let mut s = System::new(bodies).unwrap();
        s.add_forque(Gravity(axis(3, 2, -G))).unwrap();
        s.add_half_space(HalfSpace::new(&axis(3, 2, 1.0), 0.0, 0.5, 0.0).unwrap())
            .unwrap();
        let mut stepper = MotionSplitting::new();
        let mut most = 0;
        for k in 0..60 {
            let before = stepper.solver_report().solves;
            stepper.step(&mut s, k as f64 * h, h).unwrap();
            most = most.max(stepper.solver_report().solves - before);
        }
        let heights: Vec<f64> = s
            .bodies()
            .iter()
            .map(|b| b.position().as_slice()[2])
            .collect();
        let speed = s
            .bodies()
            .iter()
            .map(|b| b.velocity().norm() + b.omega().norm())
            .fold(0.0, f64::max);
        println!(
            "drop {drop}, e = {restitution}: most solves in a step {most}; heights {heights:?}; \
             speed {speed:e}"
        );
        assert_eq!(
            most > 2,
            located,
            "drop {drop}, e = {restitution}: a step took {most} solves"
        );
        assert!(
            (heights[0] - 0.5).abs() < 1e-9,
            "lower cube at {}",
            heights[0]
        );
        assert!(
            (heights[1] - 1.5).abs() < 1e-6,
            "upper cube at {}",
            heights[1]
        );
        assert!(speed < 1e-6, "still moving at {speed:e}");
        cases += 1;
    }
    assert_eq!(cases, 3);
}

/// Two bodies (the lower first) under gravity on a floor of friction 0.5, run for `steps`
/// steps of h = 0.01 s by `SoftStep` (if `soft`) or `MotionSplitting`: the faster body's
/// speed (|v| + |ω|) at the end, the top one's height above the lower one along the last
/// axis, and the points between them of the last step.
fn settle_pair(bodies: Vec<MovingBody>, soft: bool, steps: usize) -> (f64, f64, usize) {
    let n = bodies[0].dim();
    let mut s = System::new(bodies).unwrap();
    s.add_forque(Gravity(axis(n, n - 1, -G))).unwrap();
    s.add_half_space(HalfSpace::new(&axis(n, n - 1, 1.0), 0.0, 0.5, 0.0).unwrap())
        .unwrap();
    let mut stepper: Box<dyn MotionIntegrator> = if soft {
        Box::new(SoftStep::new())
    } else {
        Box::new(MotionSplitting::new())
    };
    stepper.advance(&mut s, 0.0, 0.01, steps).unwrap();
    let (low, top) = (&s.bodies()[0], &s.bodies()[1]);
    let speed = [low, top]
        .iter()
        .map(|b| b.velocity().norm() + b.omega().norm())
        .fold(0.0, f64::max);
    let height = top.position().as_slice()[n - 1] - low.position().as_slice()[n - 1];
    (speed, height, s.body_contacts().len())
}

/// A box of half-lengths 0.5, 0.6, … dropped by 1e-4 onto an equal box dropped as much onto
/// a floor, shifted by 0.05 along the first axis, comes to rest in N = 3 … 8 under both
/// contact integrators (2 s at h = 0.01): both boxes slower than 1e-9 m/s (1e-6 under the
/// soft step's springs), the upper one over the lower by its height (to 1e-5, as the
/// splitting locates the impact to 1e-6 of the radii; to 1e-3 under the soft step's
/// springs), and the pair held by at least 2^(N−1) points up to 5D (a face's corners) and 16
/// from 6D. In 8D `SoftStep`'s boxes rocked at 2e-2 m/s on the 16 points that hold a face of
/// 128 corners with two passes per substep; with the four it takes from 5D on they end at
/// 4.1e-7 m/s. In 5D and 6D the boxes once rocked on each other for ever: the pair's
/// manifold held half of the face (8 of its 16 corners, or 2 of its 32); in 7D and 8D they
/// rested and then, once a step found them a hair apart, the separating axes chose a cell
/// axis of the same gap as the face axis, whose contact is a single point.
#[test]
fn a_box_comes_to_rest_on_a_box_in_every_dimension() {
    let mut cases = 0;
    for n in 3..=8 {
        for soft in [false, true] {
            let half: Vec<f64> = (0..n).map(|i| 0.5 + 0.1 * i as f64).collect();
            let lengths: Vec<String> = half.iter().map(|h| h.to_string()).collect();
            let parsed = parse_body(&format!("cuboid:{}+mass=1", lengths.join(","))).unwrap();
            let bodies: Vec<MovingBody> = [(0.0, 1e-4), (0.05, 1e-4)]
                .iter()
                .enumerate()
                .map(|(k, &(shift, drop))| {
                    let mut x = axis(n, 0, shift);
                    x.as_mut_slice()[n - 1] = half[n - 1] * (1.0 + 2.0 * k as f64) + drop;
                    MovingBody::from_parsed(
                        &parsed,
                        Rotor::identity(n),
                        &x,
                        &Vector::zero(n),
                        &Bivector::zero(n),
                    )
                    .unwrap()
                    .with_friction(0.5)
                    .unwrap()
                })
                .collect();
            let (speed, height, points) = settle_pair(bodies, soft, 200);
            println!(
                "N = {n}, soft {soft}: speed {speed:e}, height {height} of {}, {points} points",
                2.0 * half[n - 1]
            );
            let (still, sink) = if soft { (1e-6, 1e-3) } else { (1e-9, 1e-5) };
            assert!(speed < still, "N = {n}, soft {soft}: speed {speed:e}");
            assert!(
                (height - 2.0 * half[n - 1]).abs() < sink,
                "N = {n}, soft {soft}: height {height}"
            );
            // The splitting lists each point once per velocity solve, two a step.
            let solves = if soft { 1 } else { 2 };
            let corners = (1usize << (n - 1)).min(16);
            assert!(
                points >= solves * corners,
                "N = {n}, soft {soft}: {points} points"
            );
            cases += 1;
        }
    }
    assert_eq!(cases, 12);
}

/// A hexagonal prism (a hexagon of radius 1/2 times a cube of side 1 in the other axes)
/// resting on another, offset by 5 % along the first axis, in 3D to 6D, under the splitting
/// and the soft step: after 3 s at h = 0.01 s both are at rest and the top one sits one
/// side above the lower one. Their faces have 6, 12, 24 and 48 vertices, more than the
/// brute force over a support set's subsets takes (4, 8, 8, 8): they are held by the
/// extremes of the contact region found by linear programs over every vertex of both
/// faces. When the support sets kept the vertices nearest the plane, round-off chose among
/// those of the flat face, and the prisms rocked in 3D and 4D (2e-2 and 8e-3 m/s under the
/// soft step) and fell over in 5D; when they kept eight spread-out vertices, the 6D prisms
/// still moved at 0.2 and 0.09 m/s after 3 s.
#[test]
fn a_prism_rests_on_a_prism_whose_faces_hold_more_vertices_than_a_support_set() {
    assert_eq!(prisms_rest(3..=6), 8);
}

/// [`a_prism_rests_on_a_prism_whose_faces_hold_more_vertices_than_a_support_set`] in 7D
/// and 8D, where the faces have 96 and 192 vertices and the linear programs take 64 of them
/// spread out over the face. About three minutes.
#[test]
#[ignore = "about three minutes: cargo test --release --test dynamics -- --ignored prisms"]
fn prisms_rest_on_prisms_in_seven_and_eight_dimensions() {
    assert_eq!(prisms_rest(7..=8), 4);
}

/// Settles a prism on a prism in each dimension of `dims` under both integrators and checks
/// that they rest one side apart; returns the cases run.
fn prisms_rest(dims: std::ops::RangeInclusive<usize>) -> usize {
    let mut cases = 0;
    for n in dims {
        for soft in [false, true] {
            let half = 0.5;
            let mut corners: Vec<Vector> = Vec::new();
            for k in 0..6 {
                let angle = std::f64::consts::PI / 3.0 * k as f64;
                for m in 0..1usize << (n - 2) {
                    let mut c = vec![half * angle.cos(), half * angle.sin()];
                    c.extend((0..n - 2).map(|i| if m >> i & 1 == 1 { half } else { -half }));
                    corners.push(Vector::from_components(&c).unwrap());
                }
            }
            let bodies: Vec<MovingBody> = [0.0, 0.05]
                .iter()
                .enumerate()
                .map(|(k, &shift)| {
                    let mut x = axis(n, 0, shift);
                    x.as_mut_slice()[n - 1] = half * (1.0 + 2.0 * k as f64) + 1e-4;
                    // A cube's mass and inertia: the test is about the contact.
                    turned_cube(n, half, x.as_slice(), 0.5, Rotor::identity(n))
                        .with_shape(ContactShape::Vertices(corners.clone()))
                        .unwrap()
                })
                .collect();
            let (speed, height, points) = settle_pair(bodies, soft, 300);
            println!("N = {n}, soft {soft}: speed {speed:e}, height {height}, {points} points");
            let (still, sink) = if soft { (1e-6, 1e-3) } else { (1e-8, 1e-5) };
            assert!(speed < still, "N = {n}, soft {soft}: speed {speed:e}");
            assert!(
                (height - 2.0 * half).abs() < sink,
                "N = {n}, soft {soft}: height {height}"
            );
            cases += 1;
        }
    }
    cases
}

/// The deepest overlap of the cubes of half-length `half` in `s`, each pair's by the
/// narrow phase's penetration query.
fn deepest_cube_overlap(s: &System, half: f64, workspace: &mut EpaWorkspace) -> f64 {
    let n = s.bodies()[0].dim();
    let cube = ConvexShape::cuboid(&vec![half; n]).unwrap();
    let placed: Vec<(Vec<f64>, Vec<f64>)> = s
        .bodies()
        .iter()
        .map(|b| {
            // Row-major, as `PlacedShape` takes it.
            let q = b.attitude().to_matrix().transpose();
            (b.position().as_slice().to_vec(), q.as_slice().to_vec())
        })
        .collect();
    let mut deepest = 0.0f64;
    for (i, (xa, qa)) in placed.iter().enumerate() {
        for (xb, qb) in &placed[i + 1..] {
            let a = PlacedShape::new(&cube, xa, qa).unwrap();
            let b = PlacedShape::new(&cube, xb, qb).unwrap();
            deepest = deepest.max(penetration_with(workspace, &a, &b).unwrap().depth);
        }
    }
    deepest
}

/// The deepest overlap (relative to the sum of the bounding radii) of each of `drops`
/// drops per dimension in `dims` of a tilted, spinning, drifting cube onto a cube resting
/// on the floor (random from `seed`), after every one of 90 steps of 1/60 s by
/// `MotionSplitting`, friction 0.5, restitution 0.
fn tumbling_drops(seed: u64, dims: &[usize], drops: usize) -> Vec<(usize, f64)> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut workspace = EpaWorkspace::new();
    let mut out = Vec::new();
    for &n in dims {
        for _ in 0..drops {
            let half = 0.5;
            let radii = 2.0 * half * (n as f64).sqrt();
            let tilt = Rotor::from_plane_angle(n, 0, n - 1, rng.gen_range(0.2..0.6))
                .unwrap()
                .compose(&Rotor::from_plane_angle(n, 1, n - 1, rng.gen_range(-0.5..0.5)).unwrap());
            let mut top = vec![0.0; n];
            top[0] = rng.gen_range(-0.2..0.2);
            top[n - 1] = 1.0 + half * (n as f64).sqrt() + 0.05;
            let lower = turned_cube(
                n,
                half,
                axis(n, n - 1, half).as_slice(),
                0.5,
                Rotor::identity(n),
            );
            let mut omega = Bivector::zero(n);
            for c in omega.as_mut_slice() {
                *c = rng.gen_range(-3.0..3.0);
            }
            let drift = axis(n, 0, rng.gen_range(-0.5..0.5));
            let upper = moving_cube(n, half, &top, 0.5, tilt, (&drift, &omega));
            let mut s = System::new(vec![lower, upper]).unwrap();
            s.add_forque(Gravity(axis(n, n - 1, -G))).unwrap();
            s.add_half_space(HalfSpace::new(&axis(n, n - 1, 1.0), 0.0, 0.5, 0.0).unwrap())
                .unwrap();
            let mut stepper = MotionSplitting::new();
            let mut deepest = 0.0f64;
            for k in 0..90 {
                stepper.step(&mut s, k as f64 / 60.0, 1.0 / 60.0).unwrap();
                deepest = deepest.max(deepest_cube_overlap(&s, half, &mut workspace));
            }
            out.push((n, deepest / radii));
        }
    }
    out
}

/// The largest of `drops`' overlaps in each dimension, printed with the count above
/// `mark`; returns the largest of all.
fn report_drops(drops: &[(usize, f64)], mark: f64) -> f64 {
    let mut dims: Vec<usize> = drops.iter().map(|d| d.0).collect();
    dims.dedup();
    for n in dims {
        let of_n = drops.iter().filter(|d| d.0 == n).map(|d| d.1);
        let deepest = of_n.clone().fold(0.0f64, f64::max);
        let above = of_n.filter(|d| *d > mark).count();
        println!(
            "N = {n}: deepest overlap {deepest:.3e} of the radii, {above} drops above {mark:e}"
        );
    }
    drops.iter().map(|d| d.1).fold(0.0, f64::max)
}

/// A cube tumbling onto a cube that rests on the floor lands a corner or an edge, then
/// turns onto others that the pair's contact points at the start of the step did not hold
/// (farther than the manifold's slop, or an edge sliding along an edge): the splitting sees
/// the pair sink below where it started the flight and locates that as an impact, at a
/// sink of about 10⁻³ of the radii, so that the next substep's manifold holds the new
/// feature. 120 drops ([`tumbling_drops`], seed 5, 40 each in 3D, 4D and 5D): after every
/// step no two cubes overlap by more than 10⁻² of the sum of their bounding radii (the
/// narrow phase's penetration depth). Measured: at most 4.0 × 10⁻³, 5.8 × 10⁻³ and
/// 5.8 × 10⁻³ in 3D, 4D and 5D (8 drops above 5 × 10⁻³); without the sinking located,
/// 3.6 × 10⁻², 4.0 × 10⁻² and 4.1 × 10⁻² (112 drops above 5 × 10⁻³).
#[test]
fn a_tumbling_cube_lands_its_corners_on_a_cube_without_sinking_into_it() {
    let drops = tumbling_drops(5, &[3, 4, 5], 40);
    let worst = report_drops(&drops, 5e-3);
    assert_eq!(drops.len(), 120);
    assert!(worst <= 1e-2, "deepest overlap {worst:e} of the radii");
}
