//! Steps the pyramid of 55 cubes (or of 210, `pyramid20`) or the pile of 100 boxes and balls
//! of the Rapier comparison (`benches/rapier/`) and prints, per call of `advance`, the time
//! per step and what the contact solves met: `cargo run --release --example stack_profile --
//! pile 150 1` (scene, steps, steps per call). Under `perf record -g` it shows where a step's
//! time goes.

use rotorflow::dynamics::motion::forques::Gravity;
use rotorflow::dynamics::motion::{
    HalfSpace, MotionIntegrator, MotionSplitting, MovingBody, SoftStep, System,
};
use rotorflow::inertia::spec::parse_body;
use rotorflow::prelude::*;
use std::time::Instant;

const H: f64 = 1.0 / 60.0;

fn v(x: &[f64; 3]) -> Vector {
    Vector::from_components(x).unwrap()
}

struct Item {
    cube: bool,
    pos: [f64; 3],
    yaw: f64,
}

fn pyramid(layers: usize) -> Vec<Item> {
    let mut items = Vec::new();
    for layer in 0..layers {
        let count = layers - layer;
        for i in 0..count {
            let x = i as f64 - (count - 1) as f64 / 2.0;
            items.push(Item {
                cube: true,
                pos: [x, 0.0, 0.5 + layer as f64],
                yaw: 0.0,
            });
        }
    }
    items
}

fn pile(count: usize) -> Vec<Item> {
    let side = (1..).find(|s| s * s * s >= count).unwrap();
    (0..count)
        .map(|k| {
            let (i, j, l) = (k % side, (k / side) % side, k / (side * side));
            let wobble = |a: f64| 0.05 * (a * k as f64 + 0.3).sin();
            Item {
                cube: (i + j + l) % 2 == 0,
                yaw: 4.0 * wobble(1.3),
                pos: [
                    1.2 * i as f64 + wobble(0.7),
                    1.2 * j as f64 + wobble(1.1),
                    0.5 + 1.2 * l as f64,
                ],
            }
        })
        .collect()
}

fn system(items: &[Item], half: f64) -> System {
    let bodies = items
        .iter()
        .map(|it| {
            let spec = if it.cube {
                format!("cuboid:{half},{half},{half}+mass=1")
            } else {
                format!("ball:3,{half}+mass=1")
            };
            let parsed = parse_body(&spec).unwrap();
            let att = Rotor::from_plane_angle(3, 0, 1, it.yaw).unwrap();
            MovingBody::from_parsed(&parsed, att, &v(&it.pos), &v(&[0.0; 3]), &Bivector::zero(3))
                .and_then(|b| b.with_friction(0.5))
                .unwrap()
        })
        .collect();
    let mut s = System::new(bodies).unwrap();
    s.add_forque(Gravity(v(&[0.0, 0.0, -9.81]))).unwrap();
    s.add_half_space(HalfSpace::new(&v(&[0.0, 0.0, 1.0]), 0.0, 0.5, 0.0).unwrap())
        .unwrap();
    s
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let scene = args.get(1).map(String::as_str).unwrap_or("pyramid");
    let steps: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(20);
    let per: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(1);
    let (items, half) = match scene {
        "pyramid" => (pyramid(10), 0.5),
        "pyramid20" => (pyramid(20), 0.5),
        _ => (pile(100), 0.4),
    };
    let mut s = system(&items, half);
    let soft = args.get(4).is_some_and(|a| a == "soft");
    let mut exact = MotionSplitting::new();
    let hz: f64 = std::env::var("HZ")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(30.0);
    let sub: usize = std::env::var("SUB")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(4);
    let mut soft_step = SoftStep::new()
        .with_contact_spring(hz, 10.0)
        .unwrap()
        .with_substeps(sub)
        .unwrap();
    let start = Instant::now();
    let mut t = 0.0;
    let mut k = 0;
    while k < steps {
        let t0 = Instant::now();
        let before = exact.solver_report();
        if soft {
            soft_step.advance(&mut s, t, H, per).unwrap();
        } else {
            exact.advance(&mut s, t, H, per).unwrap();
        }
        let r = exact.solver_report();
        t += per as f64 * H;
        k += per;
        let top_body = s.bodies().last().unwrap().position().as_slice();
        let (top, slide) = (top_body[2], top_body[0].hypot(top_body[1]));
        println!(
            "step {k:4} {:9.2} ms  solves {:6} unconv {} maxsweeps {:6} top z {:.9} slide {:.2e}",
            t0.elapsed().as_secs_f64() * 1e3 / per as f64,
            r.solves - before.solves,
            r.unconverged - before.unconverged,
            r.max_sweeps,
            top,
            slide
        );
    }
    println!(
        "total {:.2} s, {:?}",
        start.elapsed().as_secs_f64(),
        exact.solver_report()
    );
}
