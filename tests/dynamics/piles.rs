//! A pile of mixed 4D bodies (balls, boxes, ellipsoids, tesseract hulls) poured into a box of
//! planes: contacts between tumbling bodies of every kind at once. Physics checked: the
//! energy never rises above its start (friction, restitution < 1 and resting contact take it
//! away) and no body leaves the box. One step may gain at most what an overlap let out at the
//! resting speed gives (overlaps leave at no more than the speed one step of gravity makes,
//! 2 h g): ½ m (2 h g)².

use rotorflow::dynamics::motion::{MotionIntegrator, MotionSplitting};
use rotorflow::scene::Scene;

/// The scene: `per_kind` bodies of each of the four kinds on a grid above the floor of a
/// 3 × 3 × 3 box, each with its own spin.
fn pile_scene(per_kind: usize, t_end: f64) -> String {
    let kinds = [
        "ball:4,0.3",
        "cuboid:0.3,0.25,0.2,0.3",
        "ellipsoid:0.35,0.25,0.3,0.2",
        "tesseract:0.25,0.25,0.25,0.25",
    ];
    let mut s = format!("dim = 4\ngravity = [0.0, 0.0, 0.0, -9.81]\nt_end = {t_end}\ndt = 0.005\n");
    for k in 0..4 * per_kind {
        // Two layers of a 2 × 2 × 2 grid, nudged off the grid so that nothing is symmetric.
        let (i, j, l, layer) = (k % 2, (k / 2) % 2, (k / 4) % 2, k / 8);
        let f = |c: usize, e: f64| if c == 0 { -0.6 + e } else { 0.6 - e };
        let e = 0.013 * k as f64;
        let w = |m: f64| ((k as f64 + 1.0) * m).sin();
        s += &format!(
            "[[body]]\nname = \"b{k}\"\nshape = \"{}\"\nmass = 1.0\n\
             position = [{}, {}, {}, {}]\n\
             omega = [{}, {}, {}, {}, {}, {}]\nfriction = 0.4\nrestitution = 0.2\n",
            kinds[k % 4],
            f(i, e),
            f(j, 0.5 * e),
            f(l, 0.25 * e),
            1.0 + 0.8 * layer as f64,
            w(1.1),
            w(2.3),
            w(3.7),
            w(5.3),
            w(7.1),
            w(9.7),
        );
    }
    for axis in 0..3 {
        for sign in [1.0, -1.0] {
            let mut normal = [0.0; 4];
            normal[axis] = sign;
            s += &format!("[[plane]]\nnormal = {normal:?}\noffset = -1.5\n");
        }
    }
    s += "[[plane]]\nnormal = [0.0, 0.0, 0.0, 1.0]\noffset = 0.0\n";
    s
}

#[test]
fn a_pile_of_mixed_4d_bodies_loses_energy_and_stays_in_its_box() {
    let scene = Scene::from_toml_str(&pile_scene(2, 1.5), "pile.toml").unwrap();
    let mut system = scene.system().unwrap();
    let mut integrator = MotionSplitting::new();
    let h = scene.dt;
    let steps = (scene.t_end / h).round() as usize;
    let start = system.energy(0.0);
    let (mut before, mut worst_gain, mut highest) = (start, 0.0f64, start);
    for k in 0..steps {
        let t = k as f64 * h;
        integrator.step(&mut system, t, h).unwrap();
        let energy = system.energy(t + h);
        worst_gain = worst_gain.max(energy - before);
        highest = highest.max(energy);
        before = energy;
        for b in system.bodies() {
            let x = b.position().as_slice();
            assert!(
                x[..3].iter().all(|c| c.abs() < 1.5) && x[3] > 0.0,
                "{x:?} left the box"
            );
        }
    }
    let end = system.energy(scene.t_end);
    println!(
        "pile of 8 mixed 4D bodies, {steps} steps: energy {start:.6} -> {end:.6}, highest {highest:.6}, largest gain in one step {worst_gain:.3e}"
    );
    // Every body has mass 1.
    let let_out = 0.5 * (2.0 * h * 9.81f64).powi(2);
    assert!(
        worst_gain < let_out,
        "the energy grew by {worst_gain:e} in one step (bound {let_out:e})"
    );
    assert!(
        highest <= start,
        "the energy rose to {highest} from {start}"
    );
    assert!(end < 0.5 * start, "the pile kept {end} of {start}");
}

/// A body that touches nothing falls on its parabola while a pile beside it settles: a flight
/// is taken for every body also where the pile's position step has not settled its contacts
/// within its iterations (leaving every body where such a flight started put the ball 7.9 m
/// off its parabola here). The pile of [`pile_scene`] without restitution (its landings held
/// by speculative contacts) and a ball that collides with nothing, launched upwards from
/// 50 m: its height after each step is the closed form 50 + 2t − g t²/2 to 1e-9.
#[test]
fn a_free_body_keeps_its_parabola_beside_a_settling_pile() {
    let mut toml = pile_scene(2, 1.5).replace("restitution = 0.2", "restitution = 0.0");
    toml += "[[body]]\nname = \"free\"\nshape = \"ball:4,0.3\"\nmass = 1.0\n\
             position = [0.0, 0.0, 0.0, 50.0]\nvelocity = [0.0, 0.0, 0.0, 2.0]\ncollide = false\n";
    let scene = Scene::from_toml_str(&toml, "pile.toml").unwrap();
    let mut system = scene.system().unwrap();
    let free = system.bodies().len() - 1;
    let mut integrator = MotionSplitting::new();
    let h = scene.dt;
    let steps = (scene.t_end / h).round() as usize;
    let mut worst = 0.0f64;
    for k in 0..steps {
        integrator.step(&mut system, k as f64 * h, h).unwrap();
        let t = (k + 1) as f64 * h;
        let height = 50.0 + 2.0 * t - 0.5 * 9.81 * t * t;
        worst = worst.max((system.bodies()[free].position().as_slice()[3] - height).abs());
    }
    println!("free ball beside a settling pile, {steps} steps: off its parabola by {worst:e}");
    assert!(
        worst <= 1e-9,
        "the free ball is off its parabola by {worst:e}"
    );
}

/// A settling pile's solves converge: the pile of [`pile_scene`] without restitution, 1.5 s.
/// Its faces often rest partly within the touching distance (a body tilted by less than
/// that over its face), and the targets of such a face's points are ones one rigid motion
/// meets (see `a_face_partly_within_the_touching_distance_is_solved_exactly`). Measured:
/// every one of 4,835 solves converges, in at most 52 sweeps (29,089 sweeps in all);
/// with touching points held at 0 beside speculative ones aimed at their gaps, 505 solves
/// cycled and stopped unconverged after up to 542 sweeps (281,344 sweeps in all).
#[test]
fn a_settling_pile_converges_in_every_solve() {
    let toml = pile_scene(2, 1.5).replace("restitution = 0.2", "restitution = 0.0");
    let scene = Scene::from_toml_str(&toml, "pile.toml").unwrap();
    let mut system = scene.system().unwrap();
    let mut integrator = MotionSplitting::new();
    let h = scene.dt;
    let steps = (scene.t_end / h).round() as usize;
    integrator.advance(&mut system, 0.0, h, steps).unwrap();
    let report = integrator.solver_report();
    println!("pile of 8 mixed 4D bodies without restitution, {steps} steps: {report:?}");
    assert_eq!(report.unconverged, 0, "{report:?}");
    assert!(report.max_sweeps <= 100, "{report:?}");
}
