//! Criterion benches of moving bodies (`rotorflow::dynamics::motion`). `BENCH_QUICK=1`
//! shortens the run.
//!
//! - `motion_step/N=3`, `motion_step/N=4`: one step of one free body, attitude included.
//!   `moving_body_strang` is [`MotionSplitting::step`] on a one-body [`System`] under
//!   gravity (kick, free flight of the centre of mass and the rotation, kick);
//!   `rotation_only_strang` is [`Splitting::strang`] on the same body's rotation alone (a
//!   [`RigidBody`], torque-free). `moving_body_rk4` and `rotation_only_rkmk4` are the same
//!   pair for [`MotionRk4`] and [`Rkmk4`]. Both sides keep and advance the attitude; the
//!   moving body adds its position, its momentum and the forques.
//! - `floor_contact/N=4`: `1000_cuboids_resting` is one [`MotionSplitting`] step of 1,000
//!   solid 4D cuboids (`cuboid:0.5,0.6,0.7,0.8`, half-lengths) resting on the floor x₄ = 0
//!   under gravity with friction μ = 0.5, each touching it with a face of 8 vertices (no
//!   body–body contact). They are set down on the floor turning about the vertical (which
//!   friction stops) and stepped for 0.2 s before the timing starts; the bench checks that
//!   every body is in contact. `1000_cuboids_resting_advance_by_10` and `…_by_100` take the
//!   same steps with [`MotionIntegrator::advance`] in calls of 10 and of 100 steps (one
//!   velocity solve per step instead of two, the first and last step of each call aside); the
//!   time they report is per step all the same. Body-steps per second are 1,000 over the
//!   median.
//! - `pile_contact/N=4`: `1000_bodies_soft_step` is one [`SoftStep`] step (h = 1/60 s) of a
//!   pile of 1,000 4D bodies, cubes of half-length 0.25 and balls of radius 0.25 in turn,
//!   poured from 8 layers of 5 × 5 × 5 into a box of planes (a floor and walls 3.4 apart in
//!   each horizontal axis) with friction 0.5 and restitution 0.2, after 3 s of falling and
//!   settling outside the timing; the bench checks that they have landed.
//!   Body-steps per second are 1,000 over the median.

use criterion::{BenchmarkId, Criterion, black_box, criterion_group, criterion_main};
use rotorflow::dynamics::motion::forques::Gravity;
use rotorflow::dynamics::motion::{
    ContactShape, HalfSpace, MotionIntegrator, MotionRk4, MotionSplitting, MovingBody, SoftStep,
    System,
};
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::{Integrator, Rkmk4, Splitting};
use rotorflow::inertia::spec::parse_body;
use rotorflow::prelude::*;
use std::time::Instant;

#[path = "common/configure.rs"]
mod configure;
use configure::configure;

fn axis(n: usize, i: usize, x: f64) -> Vector {
    let mut v = Vector::zero(n);
    v.as_mut_slice()[i] = x;
    v
}

/// A solid cuboid in N = 3 or 4, placed at `x`, moving with `v` and turning with `omega`
/// (own axes), with its contact shape.
fn cuboid(n: usize, x: Vector, v: Vector, omega: &Bivector) -> (MovingBody, ContactShape) {
    let spec = if n == 3 {
        "cuboid:0.5,0.6,0.7"
    } else {
        "cuboid:0.5,0.6,0.7,0.8"
    };
    let parsed = parse_body(spec).unwrap();
    let body = MovingBody::new(
        parsed.mass,
        parsed.inertia.clone(),
        Rotor::identity(n),
        &x,
        &v,
        omega,
    )
    .unwrap();
    (body, ContactShape::from_geometry(&parsed.geometry))
}

fn spin(n: usize) -> Bivector {
    let w: Vec<f64> = (0..n * (n - 1) / 2)
        .map(|k| (0.7 * k as f64 + 0.3).sin())
        .collect();
    Bivector::from_components(n, &w).unwrap()
}

fn bench_free_step(c: &mut Criterion) {
    let h = 0.01;
    for n in [3usize, 4] {
        let mut g = c.benchmark_group(format!("motion_step/N={n}"));
        let (body, _) = cuboid(n, Vector::zero(n), axis(n, 0, 1.0), &spin(n));
        let rotation = body.rotation().clone();
        let mut system = System::new(vec![body]).unwrap();
        system.add_forque(Gravity(axis(n, n - 1, -9.81))).unwrap();

        let mut rigid = rotation.clone();
        let mut strang = Splitting::strang();
        g.bench_function(BenchmarkId::new("rotation_only_strang", n), |b| {
            b.iter(|| strang.step(black_box(&mut rigid), 0.0, h, &Free).unwrap())
        });
        let mut s = System::new(system.bodies().to_vec()).unwrap();
        s.add_forque(Gravity(axis(n, n - 1, -9.81))).unwrap();
        let mut motion = MotionSplitting::new();
        g.bench_function(BenchmarkId::new("moving_body_strang", n), |b| {
            b.iter(|| motion.step(black_box(&mut s), 0.0, h).unwrap())
        });
        let mut rigid = rotation.clone();
        let mut rk = Rkmk4;
        g.bench_function(BenchmarkId::new("rotation_only_rkmk4", n), |b| {
            b.iter(|| rk.step(black_box(&mut rigid), 0.0, h, &Free).unwrap())
        });
        let mut s = System::new(system.bodies().to_vec()).unwrap();
        s.add_forque(Gravity(axis(n, n - 1, -9.81))).unwrap();
        let mut motion = MotionRk4::default();
        g.bench_function(BenchmarkId::new("moving_body_rk4", n), |b| {
            b.iter(|| motion.step(black_box(&mut s), 0.0, h).unwrap())
        });
        g.finish();
    }
}

/// 1,000 solid 4D cuboids on a 40 × 25 grid on the floor x₄ = 0, stepped `settle` steps
/// of `h`.
fn floor_scene(h: f64, settle: usize) -> (System, MotionSplitting) {
    let n = 4;
    let mut bodies = Vec::new();
    let mut shapes = Vec::new();
    for k in 0..1000 {
        let (i, j) = (k % 40, k / 40);
        // Set down on the face x₄ = −0.8, turning about the vertical (friction stops it).
        let x = Vector::from_components(&[2.0 * i as f64, 2.0 * j as f64, 0.0, 0.8]).unwrap();
        let spin = 0.5 * (k as f64 * 0.37).sin();
        let omega = Bivector::from_components(n, &[spin, 0.0, 0.0, 0.0, 0.0, 0.0]).unwrap();
        let (b, shape) = cuboid(n, x, Vector::zero(n), &omega);
        bodies.push(b);
        shapes.push(shape);
    }
    let mut system = System::new(bodies).unwrap();
    for (i, shape) in shapes.into_iter().enumerate() {
        system.set_shape(i, shape).unwrap();
    }
    system.add_forque(Gravity(axis(n, n - 1, -9.81))).unwrap();
    system
        .add_half_space(HalfSpace::new(&axis(n, n - 1, 1.0), 0.0, 0.5, 0.0).unwrap())
        .unwrap();
    let mut integrator = MotionSplitting::new();
    for k in 0..settle {
        integrator.step(&mut system, k as f64 * h, h).unwrap();
    }
    (system, integrator)
}

fn bench_floor(c: &mut Criterion) {
    let h = 0.01;
    let (mut system, mut integrator) = floor_scene(h, 20);
    let mut touching = vec![0usize; system.bodies().len()];
    for contact in system.contacts() {
        touching[contact.body] += 1;
    }
    assert!(
        touching.iter().all(|&k| k >= 1),
        "every body rests on the floor"
    );
    let mut g = c.benchmark_group("floor_contact/N=4");
    g.throughput(criterion::Throughput::Elements(1000));
    g.bench_function("1000_cuboids_resting", |b| {
        b.iter(|| integrator.step(black_box(&mut system), 0.0, h).unwrap())
    });
    for batch in [10u64, 100] {
        // Criterion's iterations are steps: they are taken in whole calls of `batch` steps,
        // and the time is scaled back to the number of iterations asked for.
        g.bench_function(format!("1000_cuboids_resting_advance_by_{batch}"), |b| {
            b.iter_custom(|iters| {
                let calls = iters.div_ceil(batch);
                let start = Instant::now();
                for _ in 0..calls {
                    integrator
                        .advance(black_box(&mut system), 0.0, h, batch as usize)
                        .unwrap();
                }
                start
                    .elapsed()
                    .mul_f64(iters as f64 / (calls * batch) as f64)
            })
        });
    }
    g.finish();
}

/// The pile of `pile_contact/N=4` after `settle` steps of h = 1/60 s.
fn pile_scene(settle: usize) -> (System, SoftStep) {
    let n = 4;
    let bodies = (0..1000)
        .map(|k| {
            // Layers of 5 × 5 × 5 in the three horizontal axes, 8 of them.
            let (i, j, m, l) = (k % 5, (k / 5) % 5, (k / 25) % 5, k / 125);
            let wobble = |a: f64| 0.03 * (a * k as f64 + 0.3).sin();
            let x = [
                0.6 * i as f64 - 1.2 + wobble(0.7),
                0.6 * j as f64 - 1.2 + wobble(1.1),
                0.6 * m as f64 - 1.2 + wobble(1.7),
                0.4 + 0.6 * l as f64,
            ];
            let spec = if k % 2 == 0 {
                "cuboid:0.25,0.25,0.25,0.25+mass=1"
            } else {
                "ball:4,0.25+mass=1"
            };
            let parsed = parse_body(spec).unwrap();
            MovingBody::from_parsed(
                &parsed,
                Rotor::from_plane_angle(n, 0, 1, wobble(2.3) * 10.0).unwrap(),
                &Vector::from_components(&x).unwrap(),
                &Vector::zero(n),
                &Bivector::zero(n),
            )
            .unwrap()
            .with_friction(0.5)
            .unwrap()
            .with_restitution(0.2)
            .unwrap()
        })
        .collect();
    let mut system = System::new(bodies).unwrap();
    system.add_forque(Gravity(axis(n, n - 1, -9.81))).unwrap();
    let mut wall = |normal: Vector, offset: f64| {
        system
            .add_half_space(HalfSpace::new(&normal, offset, 0.5, 0.2).unwrap())
            .unwrap();
    };
    wall(axis(n, n - 1, 1.0), 0.0);
    for i in 0..n - 1 {
        // Walls 3.4 apart: the bodies pile up about seven layers deep.
        wall(axis(n, i, 1.0), -1.7);
        wall(axis(n, i, -1.0), -1.7);
    }
    let mut integrator = SoftStep::new();
    integrator
        .advance(&mut system, 0.0, 1.0 / 60.0, settle)
        .unwrap();
    (system, integrator)
}

fn bench_pile(c: &mut Criterion) {
    let h = 1.0 / 60.0;
    let (mut system, mut integrator) = pile_scene(180);
    let top = system
        .bodies()
        .iter()
        .map(|b| b.position().as_slice()[3])
        .fold(0.0, f64::max);
    assert!(top < 4.0, "the bodies have landed (highest at {top})");
    let mut g = c.benchmark_group("pile_contact/N=4");
    g.throughput(criterion::Throughput::Elements(1000));
    g.bench_function("1000_bodies_soft_step", |b| {
        b.iter(|| integrator.step(black_box(&mut system), 0.0, h).unwrap())
    });
    g.finish();
}

fn benches(_: &mut Criterion) {
    let mut c = configure();
    bench_free_step(&mut c);
    bench_floor(&mut c);
    bench_pile(&mut c);
}

criterion_group!(motion, benches);
criterion_main!(motion);
