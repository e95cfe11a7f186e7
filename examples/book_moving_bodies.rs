//! The validation tables of the book's chapter "Bodies that move"
//! (`rotorflow::dynamics::motion`): `cargo run --release --example book_moving_bodies`
//! runs every experiment and prints the tables;
//! `cargo run --release --example book_moving_bodies -- --write` also records the figures
//! with the date, the commit, the machine and the compiler in
//! `book/src/generated/moving_bodies.tsv` and renders `book/src/generated/moving_bodies.md`
//! from that file. `tests/book.rs` re-renders the committed data, fails when the committed
//! table differs, and checks the recorded figures against the bounds the chapter states
//! ([`check`]).
//!
//! The experiments are deterministic (the bodies' moments, attitudes and spins come from
//! fixed formulas, the convex pairs from a seeded generator). The figures are recorded with
//! two significant digits.

use rotorflow::dynamics::motion::forques::{Anchor, Gravity, Spring};
use rotorflow::dynamics::motion::{
    BallJoint, ContactShape, HalfSpace, MotionIntegrator, MotionRk4, MotionSplitting, MovingBody,
    System,
};
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::{Integrator, RigidBody, Splitting};
use rotorflow::inertia::spec::parse_body;
use rotorflow::prelude::*;
use std::fmt::Write as _;
use std::path::PathBuf;

// tests/book.rs compiles this file beside step_ratio.rs and bench_table.rs, so it loads
// this module more than once.
#[allow(clippy::duplicate_mod)]
#[path = "support/provenance.rs"]
mod provenance;

type Res<T> = Result<T, Box<dyn std::error::Error>>;

/// Standard gravity, along −e_N.
const G: f64 = 9.81;

/// One table of the data file: its id (the first field of its data lines), its heading and
/// caption in the book, and its column headers.
struct Table {
    id: &'static str,
    title: &'static str,
    caption: &'static str,
    columns: &'static [&'static str],
}

/// The tables, in the order of the book.
const TABLES: &[Table] = &[
    Table {
        id: "free",
        title: "Free flight under gravity",
        caption: "One body thrown under uniform gravity g = 9.81 along −e_N, h = 0.01, \
                  1000 steps of `MotionSplitting` (T = 10). The centre of mass against the \
                  exact parabola x₀ + v₀t + ½gt² (largest component error over the largest \
                  component), and the rotation against the rotation-only `RigidBody` stepped \
                  alone by `Splitting::strang` (largest difference of the principal-frame \
                  momentum and of the attitude matrix).",
        columns: &[
            "N",
            "centre of mass (relative)",
            "velocity (relative)",
            "ΔL against RigidBody",
            "Δ attitude against RigidBody",
        ],
    },
    Table {
        id: "energy",
        title: "Energy error of the splitting over long runs",
        caption: "Conservative systems integrated by `MotionSplitting`: a 4D body hanging \
                  from an undamped spring attached off its centre of mass (k = 30), swinging \
                  and turning, and double pendulums of two bars hung by ball joints and \
                  released horizontally (T = 1000), each for 10⁶ steps. \
                  |E(t) − E(0)| over the largest kinetic energy of the run, evaluated every \
                  10 steps, its largest value in the first and in the second half of the run. \
                  A drift would make the second half larger than the first; a bounded error \
                  keeps them alike. The joint gap is the largest distance between jointed \
                  points over the run.",
        columns: &[
            "system",
            "N",
            "h",
            "steps",
            "max ΔE, first half",
            "max ΔE, second half",
            "second / first",
            "largest joint gap",
        ],
    },
    Table {
        id: "order",
        title: "Measured orders",
        caption: "One 3D body on a spring to a fixed point under gravity (k = 20, ℓ₀ = 0.4, \
                  attachment off the centre of mass), integrated to T = 1; the error is the \
                  largest difference of x, p, L and the attitude matrix from `MotionRk4` with \
                  h = 1/16384. The observed order is log₂ of the ratio of the errors at h and \
                  h/2.",
        columns: &[
            "integrator",
            "h",
            "error at T = 1",
            "observed order (h → h/2)",
        ],
    },
    Table {
        id: "momentum",
        title: "Momentum conservation",
        caption: "No external forque: two bodies joined by an undamped spring between \
                  off-centre points (h = 0.005, 4000 steps), and two bodies joined by a ball \
                  joint (h = 0.002, 5000 steps). The largest change of the total linear \
                  momentum Σp and of the angular momentum about the origin Σ(x ∧ p + L_s), \
                  over max(|p|, |L|, 1). RKMK4 keeps the linear momentum exactly but the \
                  angular momentum, quadratic in the state, only to its order.",
        columns: &[
            "system",
            "N",
            "integrator",
            "Δ linear momentum",
            "Δ angular momentum",
            "largest joint gap",
        ],
    },
    Table {
        id: "rest",
        title: "A dropped body comes to rest",
        caption: "A box released tilted from height 2 with a sideways velocity 0.3 onto the \
                  floor x_N = 0 (friction 0.6, restitution 0.3), h = 0.001, 8000 steps: it \
                  lands on a corner, tips and settles. Penetration is the deepest vertex below \
                  the floor over the run, over the box's radius; the jitter is the spread of \
                  the energy over the last 1000 steps, over |E|.",
        columns: &[
            "body",
            "N",
            "max penetration / radius",
            "energy jitter at rest",
            "final speed",
            "final kinetic energy",
        ],
    },
    Table {
        id: "bounce",
        title: "Elastic bounces",
        caption: "A ball of radius 0.1 dropped from height 3 with a sideways velocity 0.4 onto \
                  a frictionless floor of restitution 1, for 8 s. The impacts are located in \
                  time, so a step that moves the ball by many radii (h = 0.05 and 0.2) still \
                  reverses it on the plane: the clearance is the lowest point of the ball over \
                  the run, sampled at the end of every step, over its radius (negative would be \
                  penetration).",
        columns: &[
            "N",
            "h",
            "fall per step at impact / radius",
            "bounces",
            "max ΔE / E",
            "min clearance / radius",
        ],
    },
    Table {
        id: "rolling",
        title: "Sliding into rolling",
        caption: "A ball of radius 0.5 and mass 1.5 launched at v₀ = 2 without spin on a \
                  floor with friction 0.3, h = 0.001, 1500 steps (it rolls after \
                  (v₀ − v)/(μg), at most 0.34 s). The final velocity against v₀(N+2)/(N+4) for the solid N-ball and \
                  v₀N/(N+2) for the hollow sphere S^(N−1), and the speed of the contact point \
                  at the end over v₀.",
        columns: &[
            "body",
            "N",
            "predicted v/v₀",
            "measured v/v₀",
            "relative error",
            "contact slip / v₀",
        ],
    },
    Table {
        id: "coulomb",
        title: "Coulomb's law at every contact",
        caption: "A spinning box thrown onto a rough floor (friction 0.4, restitution 0.2), \
                  h = 0.001, 4000 steps: it bounces, slides, tumbles and settles. At every \
                  contact of every step, the friction impulse against the cone |J_t| ≤ μλ, and \
                  where the point still slips (faster than 10⁻⁹) after the velocity solve, the \
                  cosine between the friction impulse and the slip (−1 is exactly opposite). \
                  The velocity solve is projected Gauss–Seidel over each body's contacts, \
                  swept until converged.",
        columns: &[
            "body",
            "N",
            "contacts",
            "slipping",
            "max \\|J_t\\| / (μλ) − 1",
            "slipping, not opposite to 1e-9",
            "worst cos + 1 when slipping",
        ],
    },
    Table {
        id: "headon",
        title: "Head-on collisions of two balls",
        caption: "Two frictionless balls of radius 0.5 with restitution 1, centres 1.6 apart \
                  on the first axis, the first thrown at v = 1.3 at the second at rest; h = \
                  0.01 for 1 s of `MotionSplitting`, the impact (at t = 0.6/v) located in \
                  time. The velocities after it against the textbook v₁′ = (m₁ − m₂)/(m₁ + \
                  m₂) v and v₂′ = 2m₁/(m₁ + m₂) v (error over v), the positions at t = 1 \
                  against those of the exact collision.",
        columns: &[
            "N",
            "m₁",
            "m₂",
            "v₁′ error",
            "v₂′ error",
            "position error (m)",
        ],
    },
    Table {
        id: "oblique",
        title: "Oblique collisions of equal balls",
        caption: "A frictionless elastic ball of radius 0.5 thrown at v = 1 along the first \
                  axis past an equal ball at rest, its line offset by b from the other's \
                  centre; h = 0.01 for 4 s. They leave at right angles: the cosine of the \
                  angle between the two velocities after the impact, and the changes of \
                  linear momentum (over |p|) and energy (over E).",
        columns: &[
            "N",
            "offset b",
            "\\|cos\\| of the angle between the velocities",
            "momentum change",
            "energy change",
        ],
    },
    Table {
        id: "rebound",
        title: "A ball dropped on a fixed ball",
        caption: "A ball of radius 0.5 and mass 1 dropped from rest 1 above the top of a \
                  fixed ball of radius 0.5, centre above centre, under g = 9.81 (h = 0.001). \
                  The apex after the bounce (read from the first rising state as z + v²/2g, \
                  the flight being exact) over the drop height, against e².",
        columns: &["N", "e", "rebound / drop", "e²", "error"],
    },
    Table {
        id: "pairs",
        title: "Collisions of spinning convex bodies",
        caption: "Pairs of bodies drawn from boxes, ellipsoids and balls (half-lengths 0.3 … \
                  0.7, masses 0.5 … 2, seeded random attitudes and spins, friction in [0, 1), \
                  restitution in [0, 1)) thrown at each other; h = 0.002 for 2 s. The largest \
                  changes of the linear and the angular momentum over the run (relative to \
                  their size, at least 1), and, for the pairs of cubes and balls (whose free \
                  rotation the splitting follows exactly, so that any energy gained is the \
                  contacts'), the largest energy gained over E(0).",
        columns: &[
            "N",
            "pairs (of them cubes and balls)",
            "pairs that touched",
            "largest momentum change",
            "largest angular momentum change",
            "largest energy gain, cubes and balls",
        ],
    },
    Table {
        id: "ramp",
        title: "A box on a fixed ramp",
        caption: "A unit cube (mass 1) resting on a fixed slab tilted by θ, both with friction \
                  coefficient μ, released under g = 9.81; h = 0.001 for 1 s. The acceleration \
                  down the ramp from the distance slid (2d/t²) against a = g(sin θ − μ cos θ) \
                  when μ < tan θ and 0 when it sticks, and how far the box moved off the \
                  ramp's plane.",
        columns: &[
            "N",
            "θ",
            "μ",
            "a / g predicted",
            "a / g measured",
            "error / g",
            "off the ramp (m)",
        ],
    },
    Table {
        id: "stack",
        title: "Towers that stand",
        caption: "Unit cubes (mass 1, friction 0.5) stacked on a floor, each dropped from 1 % \
                  of its size onto the one below, offset from it by the given fraction of its \
                  size along the first axis and turned alternately by ± the given angle about \
                  the vertical; `MotionSplitting::advance` for 10 s. How far the top cube sank \
                  below its resting height (negative: it rests above it, within the contact \
                  tolerance) and slid from where it was dropped, the largest \
                  speed (|v| + |ω|) of any cube at the end, and the solver's report: velocity \
                  solves, those that stopped unconverged, the most sweeps one took.",
        columns: &[
            "tower",
            "N",
            "h",
            "top sink (m)",
            "top slide (m)",
            "largest speed at the end",
            "solves",
            "unconverged",
            "most sweeps",
        ],
    },
];

/// A number with two significant digits ("0" for zero).
fn sci(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else {
        format!("{x:.1e}")
    }
}

fn vector(c: &[f64]) -> Vector {
    Vector::from_components(c).expect("finite components")
}

fn axis(n: usize, i: usize, x: f64) -> Vector {
    let mut v = Vector::zero(n);
    v.as_mut_slice()[i] = x;
    v
}

/// A deterministic vector of N components in (−scale, scale).
fn wave(n: usize, seed: f64, scale: f64) -> Vector {
    let c: Vec<f64> = (0..n)
        .map(|k| scale * (1.3 * k as f64 + seed).sin())
        .collect();
    vector(&c)
}

/// A deterministic asymmetric body: second moments 0.4 … 1.9, a generic attitude and spin.
fn rigid(n: usize, seed: f64) -> Res<RigidBody> {
    let moments: Vec<f64> = (0..n)
        .map(|k| 0.4 + 1.5 * k as f64 / (n - 1) as f64 + 0.05 * (seed + k as f64).sin())
        .collect();
    let m = n * (n - 1) / 2;
    let tilt: Vec<f64> = (0..m)
        .map(|k| 0.8 * (0.7 * k as f64 + 2.0 * seed).cos())
        .collect();
    let spin: Vec<f64> = (0..m)
        .map(|k| (1.1 * k as f64 + seed + 0.5).sin())
        .collect();
    Ok(RigidBody::from_body_momentum(
        InertiaMap::from_principal_second_moments(&moments)?,
        Rotor::from_rotation_bivector(&Bivector::from_components(n, &tilt)?),
        &Bivector::from_components(n, &spin)?,
    )?)
}

fn moving(rotation: RigidBody, mass: f64, x: &Vector, v: &Vector) -> Res<MovingBody> {
    Ok(MovingBody::from_rigid_body(rotation, mass, x, v)?)
}

fn run(
    system: &mut System,
    integrator: &mut dyn MotionIntegrator,
    h: f64,
    steps: usize,
) -> Res<()> {
    for k in 0..steps {
        integrator.step(system, k as f64 * h, h)?;
    }
    Ok(())
}

/// The largest component difference over the largest component of the reference.
fn rel(a: &Vector, b: &Vector) -> f64 {
    (a - b).max_abs() / b.max_abs().max(1.0)
}

/// Free flight under gravity against the parabola and the rotation-only body.
fn free_flight(out: &mut String) -> Res<()> {
    for n in 2..=6 {
        let rotation = rigid(n, n as f64)?;
        let (x0, v0) = (wave(n, 0.3, 3.0), wave(n, 1.1, 2.0));
        let g = axis(n, n - 1, -G);
        let mut system = System::new(vec![moving(rotation.clone(), 2.5, &x0, &v0)?])?;
        system.add_forque(Gravity(g.clone()))?;
        let (h, steps) = (0.01, 1000);
        run(&mut system, &mut MotionSplitting::new(), h, steps)?;
        let t = h * steps as f64;
        let x_want = &(&x0 + &(&v0 * t)) + &(&g * (0.5 * t * t));
        let v_want = &v0 + &(&g * t);
        let b = &system.bodies()[0];
        let mut alone = rotation;
        let mut strang = Splitting::strang();
        for k in 0..steps {
            strang.step(&mut alone, k as f64 * h, h, &Free)?;
        }
        let dl = (b.rotation().momentum() - alone.momentum()).max_abs();
        let da = (b.rotation().principal_frame_attitude().to_matrix()
            - alone.principal_frame_attitude().to_matrix())
        .amax();
        writeln!(
            out,
            "free\t{n}\t{}\t{}\t{}\t{}",
            sci(rel(b.position(), &x_want)),
            sci(rel(&b.velocity(), &v_want)),
            sci(dl),
            sci(da)
        )?;
    }
    Ok(())
}

/// Tracks |E − E₀| over the first and second half of a run and the largest kinetic energy.
struct EnergyWatch {
    e0: f64,
    steps: usize,
    first: f64,
    second: f64,
    kinetic: f64,
}

impl EnergyWatch {
    fn new(system: &System, steps: usize) -> Self {
        EnergyWatch {
            e0: system.energy(0.0),
            steps,
            first: 0.0,
            second: 0.0,
            kinetic: system.kinetic_energy(),
        }
    }

    fn see(&mut self, system: &System, k: usize, t: f64) {
        let e = (system.energy(t) - self.e0).abs();
        if k < self.steps / 2 {
            self.first = self.first.max(e);
        } else {
            self.second = self.second.max(e);
        }
        self.kinetic = self.kinetic.max(system.kinetic_energy());
    }

    fn row(&self, out: &mut String, what: &str, n: usize, h: f64, gap: &str) -> Res<()> {
        let (a, b) = (self.first / self.kinetic, self.second / self.kinetic);
        writeln!(
            out,
            "energy\t{what}\t{n}\t{h}\t{}\t{}\t{}\t{:.2}\t{gap}",
            self.steps,
            sci(a),
            sci(b),
            b / a
        )?;
        Ok(())
    }
}

/// The long runs evaluate the energy after every this many steps.
const ENERGY_SAMPLING: usize = 10;

/// A 4D body hanging from a spring under gravity, swinging and turning, 10⁶ steps.
fn spring_energy(out: &mut String) -> Res<()> {
    let n = 4;
    let body = moving(
        rigid(n, 0.2)?,
        1.0,
        &vector(&[0.3, 0.1, -0.2, -1.0]),
        &vector(&[0.2, -0.1, 0.3, 0.0]),
    )?;
    let mut system = System::new(vec![body])?;
    system.add_forque(Gravity(axis(n, n - 1, -G)))?;
    system.add_forque(Spring {
        body: 0,
        point: vector(&[0.2, 0.1, 0.0, 0.3]),
        anchor: Anchor::World(Vector::zero(n)),
        stiffness: 30.0,
        rest_length: 0.5,
        damping: 0.0,
    })?;
    let (h, steps) = (0.002, 1_000_000);
    let mut watch = EnergyWatch::new(&system, steps);
    let mut integrator = MotionSplitting::new();
    for k in 0..steps {
        let t = k as f64 * h;
        integrator.step(&mut system, t, h)?;
        if k % ENERGY_SAMPLING == 0 {
            watch.see(&system, k, t + h);
        }
    }
    watch.row(
        out,
        "a body on a spring (off its centre), gravity",
        n,
        h,
        "—",
    )
}

/// The joint points of a bar of half-length ½ along e₁.
fn bar_end(n: usize, sign: f64) -> Vector {
    axis(n, 0, 0.5 * sign)
}

/// A double pendulum of two bars hung from the origin by ball joints, released horizontally.
fn double_pendulum(n: usize) -> Res<System> {
    let spec = format!("cuboid:0.5{}", ",0.05".repeat(n - 1));
    let parsed = parse_body(&spec)?;
    let m = n * (n - 1) / 2;
    // Spins about the bars' own long axis (planes without e₁), which move neither end.
    let mut upper_spin = Bivector::zero(n);
    upper_spin.as_mut_slice()[n - 1] = 0.2; // plane 23
    let mut lower_spin = Bivector::zero(n);
    lower_spin.as_mut_slice()[m - 1] = 0.3; // plane (N−1)N
    let bar = |x: f64, spin: &Bivector| {
        MovingBody::new(
            parsed.mass,
            parsed.inertia.clone(),
            Rotor::identity(n),
            &axis(n, 0, x),
            &Vector::zero(n),
            spin,
        )
    };
    let mut system = System::new(vec![bar(0.5, &upper_spin)?, bar(1.5, &lower_spin)?])?;
    system.add_forque(Gravity(axis(n, n - 1, -G)))?;
    system.add_ball_joint(BallJoint {
        body: 0,
        point: bar_end(n, -1.0),
        other: Anchor::World(Vector::zero(n)),
    })?;
    system.add_ball_joint(BallJoint {
        body: 1,
        point: bar_end(n, -1.0),
        other: Anchor::Body(0, bar_end(n, 1.0)),
    })?;
    Ok(system)
}

/// The largest gap of the double pendulum's joints.
fn pendulum_gap(system: &System) -> f64 {
    let n = system.dim();
    let b = system.bodies();
    let top = b[0].point_position(&bar_end(n, -1.0)).max_abs();
    let middle = (&b[1].point_position(&bar_end(n, -1.0)) - &b[0].point_position(&bar_end(n, 1.0)))
        .max_abs();
    top.max(middle)
}

/// The double pendulum's energy error.
fn pendulum_energy(out: &mut String, n: usize, steps: usize) -> Res<()> {
    let mut system = double_pendulum(n)?;
    let h = 1e-3;
    let mut watch = EnergyWatch::new(&system, steps);
    let mut integrator = MotionSplitting::new();
    let mut gap = 0.0f64;
    for k in 0..steps {
        let t = k as f64 * h;
        integrator.step(&mut system, t, h)?;
        if k % ENERGY_SAMPLING == 0 {
            watch.see(&system, k, t + h);
        }
        gap = gap.max(pendulum_gap(&system));
    }
    watch.row(
        out,
        "double pendulum, two bars on ball joints, gravity",
        n,
        h,
        &sci(gap),
    )
}

/// The 3D body on a spring of the order measurement.
fn order_system() -> Res<System> {
    let mut s = System::new(vec![moving(
        rigid(3, 0.9)?,
        1.2,
        &vector(&[0.5, 0.2, -1.0]),
        &vector(&[0.1, 0.4, 0.0]),
    )?])?;
    s.add_forque(Gravity(axis(3, 2, -G)))?;
    s.add_forque(Spring {
        body: 0,
        point: vector(&[0.3, -0.2, 0.1]),
        anchor: Anchor::World(Vector::zero(3)),
        stiffness: 20.0,
        rest_length: 0.4,
        damping: 0.0,
    })?;
    Ok(s)
}

fn order_state(s: &System) -> Vec<f64> {
    let b = &s.bodies()[0];
    let mut v: Vec<f64> = b.position().as_slice().to_vec();
    v.extend_from_slice(b.linear_momentum().as_slice());
    v.extend_from_slice(b.rotation().momentum().as_slice());
    v.extend(b.attitude().to_matrix().iter().copied());
    v
}

fn orders(out: &mut String) -> Res<()> {
    let solve = |integrator: &mut dyn MotionIntegrator, steps: usize| -> Res<Vec<f64>> {
        let mut s = order_system()?;
        run(&mut s, integrator, 1.0 / steps as f64, steps)?;
        Ok(order_state(&s))
    };
    let reference = solve(&mut MotionRk4::new(), 16384)?;
    let err = |x: Vec<f64>| {
        x.iter()
            .zip(&reference)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
    };
    for (name, integrator) in [
        (
            "`MotionSplitting`",
            &mut MotionSplitting::new() as &mut dyn MotionIntegrator,
        ),
        ("`MotionRk4`", &mut MotionRk4::new()),
    ] {
        let steps = [50, 100, 200, 400];
        let errors: Vec<f64> = steps
            .iter()
            .map(|&s| solve(integrator, s).map(err))
            .collect::<Res<_>>()?;
        for (k, (&s, &e)) in steps.iter().zip(&errors).enumerate() {
            let order = match errors.get(k + 1) {
                Some(&next) => format!("{:.2}", (e / next).log2()),
                None => "—".into(),
            };
            writeln!(out, "order\t{name}\t1/{s}\t{}\t{order}", sci(e))?;
        }
    }
    Ok(())
}

/// Two bodies on a spring, and two bodies on a ball joint: the momenta.
fn momenta(out: &mut String) -> Res<()> {
    for n in [2, 3, 4, 5] {
        let build = || -> Res<System> {
            let seed = n as f64;
            let a = moving(
                rigid(n, seed)?,
                1.5,
                &wave(n, seed, 1.0),
                &wave(n, seed + 1.0, 0.5),
            )?;
            let b = moving(
                rigid(n, seed + 2.0)?,
                0.8,
                &(&wave(n, seed + 3.0, 1.0) + &axis(n, 0, 3.0)),
                &wave(n, seed + 4.0, 0.5),
            )?;
            let mut s = System::new(vec![a, b])?;
            s.add_forque(Spring {
                body: 0,
                point: wave(n, seed + 5.0, 0.5),
                anchor: Anchor::Body(1, wave(n, seed + 6.0, 0.5)),
                stiffness: 4.0,
                rest_length: 2.0,
                damping: 0.0,
            })?;
            Ok(s)
        };
        for (name, integrator) in [
            (
                "`MotionSplitting`",
                &mut MotionSplitting::new() as &mut dyn MotionIntegrator,
            ),
            ("`MotionRk4`", &mut MotionRk4::new()),
        ] {
            let mut s = build()?;
            let (p0, l0) = (s.linear_momentum(), s.angular_momentum());
            run(&mut s, integrator, 0.005, 4000)?;
            let scale = p0.max_abs().max(l0.max_abs()).max(1.0);
            let dp = (&s.linear_momentum() - &p0).max_abs() / scale;
            let dl = (&s.angular_momentum() - &l0).max_abs() / scale;
            writeln!(
                out,
                "momentum\ttwo bodies on a spring\t{n}\t{name}\t{}\t{}\t—",
                sci(dp),
                sci(dl)
            )?;
        }
    }
    for n in [3, 4, 5] {
        let mut omega = Bivector::zero(n);
        for (k, w) in omega.as_mut_slice().iter_mut().enumerate() {
            *w = (k as f64 + 0.5).cos();
        }
        let cube = parse_body(&format!("cuboid:0.3{}", ",0.3".repeat(n - 1)))?;
        let semi: Vec<String> = (0..n)
            .map(|i| format!("{}", 0.2 + 0.1 * i as f64))
            .collect();
        let ellipsoid = parse_body(&format!("ellipsoid:{}", semi.join(",")))?;
        let a = MovingBody::new(
            cube.mass,
            cube.inertia.clone(),
            Rotor::identity(n),
            &Vector::zero(n),
            &axis(n, 1, 0.2),
            &omega,
        )?;
        let b = MovingBody::new(
            ellipsoid.mass,
            ellipsoid.inertia.clone(),
            Rotor::identity(n),
            &axis(n, 0, 1.0),
            &axis(n, 1, -0.3),
            &(&omega * -0.7),
        )?;
        let mut s = System::new(vec![a, b])?;
        s.add_ball_joint(BallJoint {
            body: 0,
            point: axis(n, 0, 0.5),
            other: Anchor::Body(1, axis(n, 0, -0.5)),
        })?;
        // The first step makes the joint's velocities agree; measure from there.
        let mut stepper = MotionSplitting::new();
        let h = 2e-3;
        stepper.step(&mut s, 0.0, h)?;
        let (p0, l0) = (s.linear_momentum(), s.angular_momentum());
        let mut gap = 0.0f64;
        for k in 1..5000 {
            stepper.step(&mut s, k as f64 * h, h)?;
            let d = &s.bodies()[0].point_position(&axis(n, 0, 0.5))
                - &s.bodies()[1].point_position(&axis(n, 0, -0.5));
            gap = gap.max(d.max_abs());
        }
        let scale = p0.max_abs().max(l0.max_abs()).max(1.0);
        let dp = (&s.linear_momentum() - &p0).max_abs() / scale;
        let dl = (&s.angular_momentum() - &l0).max_abs() / scale;
        writeln!(
            out,
            "momentum\ttwo bodies on a ball joint\t{n}\t`MotionSplitting`\t{}\t{}\t{}",
            sci(dp),
            sci(dl),
            sci(gap)
        )?;
    }
    Ok(())
}

/// One body of the SPEC grammar over the floor x_N = 0 under gravity.
fn on_floor(
    spec: &str,
    attitude: Rotor,
    x: &Vector,
    v: &Vector,
    omega: &Bivector,
    friction: f64,
    restitution: f64,
) -> Res<System> {
    let parsed = parse_body(spec)?;
    let n = parsed.dim;
    let b = MovingBody::new(parsed.mass, parsed.inertia.clone(), attitude, x, v, omega)?;
    let mut s = System::new(vec![b])?;
    s.set_shape(0, ContactShape::from_geometry(&parsed.geometry))?;
    s.add_forque(Gravity(axis(n, n - 1, -G)))?;
    s.add_half_space(HalfSpace::new(
        &axis(n, n - 1, 1.0),
        0.0,
        friction,
        restitution,
    )?)?;
    Ok(s)
}

/// The lowest point of body 0 above the floor x_N = 0.
fn clearance(s: &System) -> f64 {
    let b = &s.bodies()[0];
    let n = s.dim();
    match &s.shapes()[0] {
        ContactShape::Vertices(v) => v
            .iter()
            .map(|p| b.point_position(p).as_slice()[n - 1])
            .fold(f64::INFINITY, f64::min),
        ContactShape::Ellipsoid(a) => b.position().as_slice()[n - 1] - a[0],
        _ => f64::INFINITY,
    }
}

fn box_spec(n: usize) -> String {
    let half: Vec<String> = (0..n)
        .map(|i| format!("{}", 0.5 + 0.1 * i as f64))
        .collect();
    format!("cuboid:{}", half.join(","))
}

/// Boxes dropped tilted onto the floor: penetration, rest, energy jitter.
fn resting(out: &mut String) -> Res<()> {
    for n in [3, 4] {
        let spec = box_spec(n);
        let mut tilt = Bivector::zero(n);
        tilt.as_mut_slice()[0] = 0.3;
        tilt.as_mut_slice()[n * (n - 1) / 2 - 1] = -0.2;
        let mut s = on_floor(
            &spec,
            Rotor::from_rotation_bivector(&tilt),
            &axis(n, n - 1, 2.0),
            &axis(n, 0, 0.3),
            &Bivector::zero(n),
            0.6,
            0.3,
        )?;
        let radius = s.shapes()[0].radius();
        let mut stepper = MotionSplitting::new();
        let h = 1e-3;
        let mut lowest = f64::INFINITY;
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for k in 0..8000 {
            stepper.step(&mut s, k as f64 * h, h)?;
            lowest = lowest.min(clearance(&s));
            if k >= 7000 {
                let e = s.energy((k + 1) as f64 * h);
                (lo, hi) = (lo.min(e), hi.max(e));
            }
        }
        writeln!(
            out,
            "rest\t`{spec}`\t{n}\t{}\t{}\t{}\t{}",
            sci((-lowest).max(0.0) / radius),
            sci((hi - lo) / hi.abs().max(1e-300)),
            sci(s.bodies()[0].velocity().norm()),
            sci(s.kinetic_energy())
        )?;
    }
    Ok(())
}

/// Elastic balls bouncing: energy, clearance, bounces.
fn bouncing(out: &mut String) -> Res<()> {
    for (n, h) in [(2, 1e-3), (3, 1e-3), (4, 0.05), (5, 0.2)] {
        let a = 0.1;
        let mut s = on_floor(
            &format!("ball:{n},{a}"),
            Rotor::identity(n),
            &axis(n, n - 1, 3.0),
            &axis(n, 0, 0.4),
            &Bivector::zero(n),
            0.0,
            1.0,
        )?;
        let e0 = s.energy(0.0);
        let mut stepper = MotionSplitting::new();
        let (mut worst, mut lowest) = (0.0f64, f64::INFINITY);
        let (mut bounces, mut falling) = (0, true);
        for k in 0..(8.0 / h) as usize {
            stepper.step(&mut s, k as f64 * h, h)?;
            worst = worst.max((s.energy((k + 1) as f64 * h) - e0).abs() / e0);
            lowest = lowest.min(clearance(&s));
            let up = s.bodies()[0].velocity().as_slice()[n - 1] > 0.0;
            if falling && up {
                bounces += 1;
            }
            falling = !up;
        }
        let impact_speed = (2.0 * G * (3.0 - a)).sqrt();
        writeln!(
            out,
            "bounce\t{n}\t{h}\t{:.2}\t{bounces}\t{}\t{}",
            impact_speed * h / a,
            sci(worst),
            sci(lowest / a)
        )?;
    }
    Ok(())
}

/// Balls sliding into rolling: the final velocity against the moments' prediction.
fn rolling(out: &mut String) -> Res<()> {
    for (kind, label) in [("ball", "solid N-ball"), ("sphere", "hollow sphere")] {
        for n in 2..=6 {
            let nf = n as f64;
            let ratio = if kind == "ball" {
                (nf + 2.0) / (nf + 4.0)
            } else {
                nf / (nf + 2.0)
            };
            let (a, v0) = (0.5, 2.0);
            let mut s = on_floor(
                &format!("{kind}:{n},{a}+mass=1.5"),
                Rotor::identity(n),
                &axis(n, n - 1, a),
                &axis(n, 0, v0),
                &Bivector::zero(n),
                0.3,
                0.0,
            )?;
            run(&mut s, &mut MotionSplitting::new(), 1e-3, 1500)?;
            let b = &s.bodies()[0];
            let v = b.velocity().as_slice()[0] / v0;
            let contact =
                b.point_velocity(&b.attitude().inverse_rotate_vector(&axis(n, n - 1, -a)));
            writeln!(
                out,
                "rolling\t{label}\t{n}\t{ratio:.6}\t{v:.6}\t{}\t{}",
                sci((v - ratio).abs() / ratio),
                sci(contact.norm() / v0)
            )?;
        }
    }
    Ok(())
}

/// Spinning boxes thrown onto a rough floor: Coulomb's cone and maximal dissipation.
fn coulomb(out: &mut String) -> Res<()> {
    let mu = 0.4;
    for n in [3, 4, 5] {
        let spec = box_spec(n);
        let mut omega = Bivector::zero(n);
        for (k, w) in omega.as_mut_slice().iter_mut().enumerate() {
            *w = 2.0 * ((k as f64) * 1.7).sin();
        }
        let mut v = wave(n, 0.4, 2.0);
        v.as_mut_slice()[n - 1] = 0.0;
        let mut s = on_floor(
            &spec,
            Rotor::identity(n),
            &axis(n, n - 1, 1.5),
            &v,
            &omega,
            mu,
            0.2,
        )?;
        let mut stepper = MotionSplitting::new();
        let (mut checked, mut slipping) = (0usize, 0usize);
        let (mut cone, mut cos) = (0.0f64, -1.0f64);
        let mut off = 0usize;
        for k in 0..4000 {
            stepper.step(&mut s, k as f64 * 1e-3, 1e-3)?;
            for c in s.contacts() {
                checked += 1;
                let jt = c.friction_impulse.norm();
                if c.normal_impulse > 0.0 {
                    cone = cone.max(jt / (mu * c.normal_impulse));
                }
                let slip = c.slip.norm();
                if slip > 1e-9 && c.normal_impulse > 0.0 {
                    slipping += 1;
                    let cs = c.friction_impulse.dot(&c.slip) / (jt * slip);
                    if cs > -1.0 + 1e-9 {
                        off += 1;
                    }
                    cos = cos.max(cs);
                }
            }
        }
        writeln!(
            out,
            "coulomb\t`{spec}`\t{n}\t{checked}\t{slipping}\t{}\t{off}\t{}",
            sci(cone - 1.0),
            sci(cos + 1.0)
        )?;
    }
    Ok(())
}

/// A frictionless ball of radius 0.5 and mass `mass` at `x` with velocity `v` (both padded
/// with zeros to N components) and restitution `restitution`.
fn ball(n: usize, mass: f64, x: &[f64], v: &[f64], restitution: f64) -> Res<MovingBody> {
    let parsed = parse_body(&format!("ball:{n},0.5+mass={mass}"))?;
    let pad = |c: &[f64]| {
        let mut p = vec![0.0; n];
        p[..c.len()].copy_from_slice(c);
        vector(&p)
    };
    let b = MovingBody::from_parsed(
        &parsed,
        Rotor::identity(n),
        &pad(x),
        &pad(v),
        &Bivector::zero(n),
    )?;
    Ok(b.with_restitution(restitution)?.with_friction(0.0)?)
}

/// Head-on elastic collisions against the textbook velocities.
fn head_on(out: &mut String) -> Res<()> {
    for n in [3, 4] {
        for (m1, m2) in [(1.0, 1.0), (1.0, 3.0), (2.5, 0.7)] {
            let v = 1.3;
            let a = ball(n, m1, &[-1.0], &[v], 1.0)?;
            let b = ball(n, m2, &[0.6], &[0.0], 1.0)?;
            let mut s = System::new(vec![a, b])?;
            let (h, steps) = (1e-2, 100);
            run(&mut s, &mut MotionSplitting::new(), h, steps)?;
            let v1 = (m1 - m2) / (m1 + m2) * v;
            let v2 = 2.0 * m1 / (m1 + m2) * v;
            let got = |k: usize| s.bodies()[k].velocity().as_slice()[0];
            let (tc, t) = (0.6 / v, h * steps as f64);
            let x1 = -1.0 + v * tc + v1 * (t - tc);
            let x2 = 0.6 + v2 * (t - tc);
            let at = |k: usize| s.bodies()[k].position().as_slice()[0];
            writeln!(
                out,
                "headon\t{n}\t{m1}\t{m2}\t{}\t{}\t{}",
                sci((got(0) - v1).abs() / v),
                sci((got(1) - v2).abs() / v),
                sci((at(0) - x1).abs().max((at(1) - x2).abs()))
            )?;
        }
    }
    Ok(())
}

/// Oblique elastic collisions of equal balls: right angles, momentum and energy kept.
fn oblique(out: &mut String) -> Res<()> {
    for (n, offset) in [(3, 0.3), (3, 0.7), (4, 0.5), (5, 0.2)] {
        let a = ball(n, 1.0, &[-2.0, offset], &[1.0], 1.0)?;
        let b = ball(n, 1.0, &[0.0], &[0.0], 1.0)?;
        let mut s = System::new(vec![a, b])?;
        let (p0, e0) = (s.linear_momentum(), s.energy(0.0));
        run(&mut s, &mut MotionSplitting::new(), 1e-2, 400)?;
        let (va, vb) = (s.bodies()[0].velocity(), s.bodies()[1].velocity());
        if vb.norm() < 0.1 {
            return Err(format!("N = {n}, offset {offset}: the balls missed").into());
        }
        let cosine = va.dot(&vb) / (va.norm() * vb.norm());
        writeln!(
            out,
            "oblique\t{n}\t{offset}\t{}\t{}\t{}",
            sci(cosine.abs()),
            sci((&s.linear_momentum() - &p0).norm() / p0.norm()),
            sci((s.energy(0.0) - e0).abs() / e0)
        )?;
    }
    Ok(())
}

/// A ball dropped on a fixed ball rebounds to e² of its drop height.
fn rebound(out: &mut String) -> Res<()> {
    for n in [3, 4] {
        for e in [1.0, 0.8, 0.5] {
            let base = MovingBody::fixed(
                ContactShape::Ellipsoid(vec![0.5; n]),
                Rotor::identity(n),
                &Vector::zero(n),
            )?;
            let drop = 1.0;
            let mut top = vec![0.0; n];
            top[n - 1] = 1.0 + drop;
            let mut s = System::new(vec![base, ball(n, 1.0, &top, &[], e)?])?;
            s.add_forque(Gravity(axis(n, n - 1, -G)))?;
            let mut stepper = MotionSplitting::new();
            let h = 1e-3;
            let mut apex = None;
            for k in 0..1200 {
                stepper.step(&mut s, k as f64 * h, h)?;
                let b = &s.bodies()[1];
                let vz = b.velocity().as_slice()[n - 1];
                if vz > 0.0 && apex.is_none() {
                    apex = Some(b.position().as_slice()[n - 1] + vz * vz / (2.0 * G));
                }
            }
            let ratio = (apex.ok_or("the ball did not bounce")? - 1.0) / drop;
            writeln!(
                out,
                "rebound\t{n}\t{e}\t{ratio:.6}\t{:.6}\t{}",
                e * e,
                sci((ratio - e * e).abs())
            )?;
        }
    }
    Ok(())
}

/// A seeded random convex body of the catalogue (cube or ball when `isotropic`).
fn random_convex(
    r: &mut impl rand::Rng,
    n: usize,
    x: &Vector,
    towards: f64,
    isotropic: bool,
) -> Res<MovingBody> {
    let mut lengths: Vec<String> = (0..n)
        .map(|_| format!("{:.3}", r.gen_range(0.3..0.7)))
        .collect();
    if isotropic {
        lengths = vec![lengths[0].clone(); n];
    }
    let spec = match r.gen_range(0..3) {
        0 => format!("cuboid:{}", lengths.join(",")),
        1 => format!("ellipsoid:{}", lengths.join(",")),
        _ => format!("ball:{n},{}", lengths[0]),
    };
    let parsed = parse_body(&format!("{spec}+mass={:.3}", r.gen_range(0.5..2.0)))?;
    let mut v: Vec<f64> = (0..n).map(|_| r.gen_range(-0.5..0.5)).collect();
    v[0] += towards;
    let m = n * (n - 1) / 2;
    let w: Vec<f64> = (0..m).map(|_| r.gen_range(-2.0..2.0)).collect();
    let b: Vec<f64> = (0..m).map(|_| r.gen_range(-1.0..1.0)).collect();
    let body = MovingBody::from_parsed(
        &parsed,
        Rotor::from_rotation_bivector(&Bivector::from_components(n, &b)?),
        x,
        &vector(&v),
        &Bivector::from_components(n, &w)?,
    )?;
    Ok(body
        .with_friction(r.gen_range(0.0..1.0))?
        .with_restitution(r.gen_range(0.0..1.0))?)
}

/// Pairs of spinning convex bodies: momenta kept, no energy gained.
fn convex_pairs(out: &mut String) -> Res<()> {
    use rand::SeedableRng;
    let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(3030);
    for n in 3..=6 {
        let (pairs, isotropic_pairs) = (12, 6);
        let (mut touched, mut dp, mut dl, mut gain) = (0, 0.0f64, 0.0f64, 0.0f64);
        for k in 0..pairs {
            let isotropic = k >= pairs - isotropic_pairs;
            let mut x = vec![0.0; n];
            x[0] = -1.2;
            let a = random_convex(&mut r, n, &vector(&x), 1.5, isotropic)?;
            x[0] = 1.2;
            x[1] = 0.2;
            let b = random_convex(&mut r, n, &vector(&x), -0.5, isotropic)?;
            let mut s = System::new(vec![a, b])?;
            let (p0, l0, e0) = (s.linear_momentum(), s.angular_momentum(), s.energy(0.0));
            let mut stepper = MotionSplitting::new();
            let h = 2e-3;
            for step in 0..1000 {
                stepper.step(&mut s, step as f64 * h, h)?;
                dp = dp.max((&s.linear_momentum() - &p0).max_abs() / p0.norm().max(1.0));
                dl = dl.max((&s.angular_momentum() - &l0).max_abs() / l0.norm().max(1.0));
                if isotropic {
                    gain = gain.max((s.energy(0.0) - e0) / e0);
                }
            }
            if stepper.solver_report().solves > 0 {
                touched += 1;
            }
        }
        writeln!(
            out,
            "pairs\t{n}\t{pairs} ({isotropic_pairs})\t{touched}\t{}\t{}\t{}",
            sci(dp),
            sci(dl),
            sci(gain.max(0.0))
        )?;
    }
    Ok(())
}

/// A unit cube of mass 1 at `x` with the attitude `attitude` and friction `mu`, at rest.
fn unit_cube(n: usize, x: &Vector, attitude: Rotor, mu: f64) -> Res<MovingBody> {
    let parsed = parse_body(&format!("cuboid:{}+mass=1", vec!["0.5"; n].join(",")))?;
    let b = MovingBody::from_parsed(&parsed, attitude, x, &Vector::zero(n), &Bivector::zero(n))?;
    Ok(b.with_friction(mu)?)
}

/// A box on a fixed ramp: Coulomb's acceleration, or sticking.
fn ramp(out: &mut String) -> Res<()> {
    for n in [3, 4] {
        for (theta_deg, mu) in [(30.0f64, 0.3), (30.0, 0.7), (20.0, 0.1), (40.0, 0.5)] {
            let theta = theta_deg.to_radians();
            // A fixed slab of half-lengths 20 × 0.5 (2 in the other axes), its top face
            // through the origin, tilted in the plane (x₁, x_N) by θ.
            let tilt = Rotor::from_plane_angle(n, 0, n - 1, theta)?;
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
                    vector(&c)
                })
                .collect();
            let below = tilt.rotate_vector(&axis(n, n - 1, -0.5));
            let slab = MovingBody::fixed(ContactShape::Vertices(corners), tilt.clone(), &below)?
                .with_friction(mu)?;
            let start = tilt.rotate_vector(&axis(n, n - 1, 0.5));
            let block = unit_cube(n, &start, tilt.clone(), mu)?;
            let mut s = System::new(vec![slab, block])?;
            s.add_forque(Gravity(axis(n, n - 1, -G)))?;
            let (h, steps) = (1e-3, 1000);
            MotionSplitting::new().advance(&mut s, 0.0, h, steps)?;
            let t = h * steps as f64;
            let mut downhill = tilt.rotate_vector(&axis(n, 0, 1.0));
            if downhill.as_slice()[n - 1] > 0.0 {
                downhill = &downhill * -1.0;
            }
            let moved = s.bodies()[1].position() - &start;
            let measured = 2.0 * moved.dot(&downhill) / (t * t) / G;
            let predicted = (theta.sin() - mu * theta.cos()).max(0.0);
            let normal = tilt.rotate_vector(&axis(n, n - 1, 1.0));
            writeln!(
                out,
                "ramp\t{n}\t{theta_deg}°\t{mu}\t{predicted:.6}\t{measured:.6}\t{}\t{}",
                sci((measured - predicted).abs()),
                sci(moved.dot(&normal).abs())
            )?;
        }
    }
    Ok(())
}

/// Towers of cubes on a floor: the top cube's sink and slide, rest, the solver's effort.
fn towers(out: &mut String) -> Res<()> {
    let cases = [
        ("six cubes, turned ±3°", 3, 6, 0.0, 3.0),
        ("three hypercubes, offset 5 %", 4, 3, 0.05, 0.0),
        ("three hypercubes, offset 5 %, turned ±3°", 4, 3, 0.05, 3.0),
    ];
    for (label, n, count, offset, turn_deg) in cases {
        for (h, h_label) in [(1.0 / 60.0, "1/60"), (1e-3, "0.001")] {
            let drop = 0.01;
            let bodies = (0..count)
                .map(|k| {
                    let mut x = vec![0.0; n];
                    x[0] = offset * k as f64;
                    x[n - 1] = 0.5 + k as f64 * (1.0 + drop);
                    let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
                    let yaw = Rotor::from_plane_angle(n, 0, 1, sign * f64::to_radians(turn_deg))?;
                    unit_cube(n, &vector(&x), yaw, 0.5)
                })
                .collect::<Res<Vec<_>>>()?;
            let mut s = System::new(bodies)?;
            s.add_forque(Gravity(axis(n, n - 1, -G)))?;
            s.add_half_space(HalfSpace::new(&axis(n, n - 1, 1.0), 0.0, 0.5, 0.0)?)?;
            let mut start = s.bodies()[count - 1].position().clone();
            start.as_mut_slice()[n - 1] = count as f64 - 0.5;
            let mut stepper = MotionSplitting::new();
            stepper.advance(&mut s, 0.0, h, (10.0 / h).round() as usize)?;
            let moved = s.bodies()[count - 1].position() - &start;
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
            let report = stepper.solver_report();
            writeln!(
                out,
                "stack\t{label}\t{n}\t{h_label}\t{}\t{}\t{}\t{}\t{}\t{}",
                sci(-moved.as_slice()[n - 1]),
                sci(slide),
                sci(speed),
                report.solves,
                report.unconverged,
                report.max_sweeps
            )?;
        }
    }
    Ok(())
}

/// Runs every experiment: the data lines of the data file. `double_pendulum_steps` is the
/// length of the double pendulums' runs.
fn measure(double_pendulum_steps: usize) -> Res<String> {
    let mut data = String::new();
    let mut clock = std::time::Instant::now();
    let mut lap = |what: &str| {
        eprintln!("{what}: {:.1} s", clock.elapsed().as_secs_f64());
        clock = std::time::Instant::now();
    };
    free_flight(&mut data)?;
    lap("free flight");
    spring_energy(&mut data)?;
    lap("spring");
    for n in [3, 4] {
        pendulum_energy(&mut data, n, double_pendulum_steps)?;
        lap("double pendulum");
    }
    orders(&mut data)?;
    lap("orders");
    momenta(&mut data)?;
    lap("momenta");
    resting(&mut data)?;
    lap("rest");
    bouncing(&mut data)?;
    lap("bounce");
    rolling(&mut data)?;
    lap("rolling");
    coulomb(&mut data)?;
    lap("coulomb");
    head_on(&mut data)?;
    oblique(&mut data)?;
    rebound(&mut data)?;
    lap("collisions of balls");
    convex_pairs(&mut data)?;
    lap("convex pairs");
    ramp(&mut data)?;
    lap("ramp");
    towers(&mut data)?;
    lap("towers");
    Ok(data)
}

/// The data lines of table `id`, split into fields (the id dropped).
fn rows<'a>(tsv: &'a str, id: &str) -> Vec<Vec<&'a str>> {
    tsv.lines()
        .filter(|l| !l.starts_with('#'))
        .filter_map(|l| l.split_once('\t'))
        .filter(|(head, _)| *head == id)
        .map(|(_, rest)| rest.split('\t').collect())
        .collect()
}

/// Renders the markdown tables from the data file's text (`# key: value` header lines,
/// then tab-separated data lines whose first field names their table).
pub fn render(tsv: &str) -> Res<String> {
    let mut out = String::new();
    writeln!(
        out,
        "<!-- Generated by `cargo run --release --example book_moving_bodies -- --write` from \
         moving_bodies.tsv; do not edit. -->\n"
    )?;
    for line in tsv.lines() {
        if let Some(m) = line.strip_prefix("# ") {
            writeln!(out, "- {m}")?;
        }
    }
    for line in tsv.lines().filter(|l| !l.starts_with('#') && !l.is_empty()) {
        let id = line.split('\t').next().unwrap_or("");
        if !TABLES.iter().any(|t| t.id == id) {
            return Err(format!("data line of no table: {line}").into());
        }
    }
    for table in TABLES {
        let rows = rows(tsv, table.id);
        if rows.is_empty() {
            return Err(format!("no data for the table {}", table.id).into());
        }
        writeln!(out, "\n### {}\n\n{}\n", table.title, table.caption)?;
        writeln!(out, "| {} |", table.columns.join(" | "))?;
        writeln!(out, "|{}", "---|".repeat(table.columns.len()))?;
        for row in rows {
            if row.len() != table.columns.len() {
                return Err(format!("{}: {} fields in {row:?}", table.id, row.len()).into());
            }
            writeln!(out, "| {} |", row.join(" | "))?;
        }
    }
    Ok(out)
}

/// The bounds the chapter states, checked on the recorded figures: returns the figures
/// that break them (empty when all hold).
pub fn check(tsv: &str) -> Res<Vec<String>> {
    let mut failures = Vec::new();
    let num = |s: &str| -> Res<f64> { Ok(s.trim().parse::<f64>()?) };
    let mut bound = |table: &str, row: &[&str], col: usize, ok: &dyn Fn(f64) -> bool| -> Res<()> {
        if !ok(num(row[col])?) {
            failures.push(format!("{table}: {} in {row:?}", row[col]));
        }
        Ok(())
    };
    let expect = |id: &str, count: usize| -> Res<Vec<Vec<&str>>> {
        let r = rows(tsv, id);
        if r.len() < count {
            return Err(format!("{id}: {} rows, expected {count}", r.len()).into());
        }
        Ok(r)
    };
    for row in expect("free", 5)? {
        bound("free flight", &row, 1, &|x| x <= 1e-13)?;
        bound("free flight", &row, 2, &|x| x <= 1e-13)?;
        bound("free flight", &row, 3, &|x| x <= 1e-15)?;
        bound("free flight", &row, 4, &|x| x <= 1e-15)?;
    }
    for row in expect("energy", 3)? {
        bound("energy", &row, 3, &|x| x >= 1e6)?;
        bound("energy", &row, 4, &|x| x > 0.0 && x <= 1e-2)?;
        bound("energy", &row, 6, &|x| x <= 1.5)?;
    }
    for row in expect("order", 8)? {
        if row[3].trim() != "—" {
            let want = if row[0].contains("Rk4") { 4.0 } else { 2.0 };
            bound("order", &row, 3, &|x| (x - want).abs() <= 0.25)?;
        }
    }
    for row in expect("momentum", 11)? {
        let rk4 = row[2].contains("Rk4");
        bound("momentum", &row, 3, &|x| x <= 1e-12)?;
        bound("momentum", &row, 4, &|x| {
            x <= if rk4 { 1e-6 } else { 1e-11 }
        })?;
        if row[5].trim() != "—" {
            bound("momentum", &row, 5, &|x| x <= 1e-12)?;
        }
    }
    for row in expect("rest", 2)? {
        bound("rest", &row, 2, &|x| x <= 1e-9)?;
        bound("rest", &row, 3, &|x| x <= 1e-12)?;
        bound("rest", &row, 4, &|x| x <= 1e-12)?;
    }
    for row in expect("bounce", 4)? {
        bound("bounce", &row, 3, &|x| x >= 5.0)?;
        bound("bounce", &row, 4, &|x| x <= 1e-9)?;
        bound("bounce", &row, 5, &|x| x >= -1e-9)?;
    }
    for row in expect("rolling", 10)? {
        bound("rolling", &row, 4, &|x| x <= 1e-6)?;
        bound("rolling", &row, 5, &|x| x <= 1e-9)?;
    }
    for row in expect("coulomb", 3)? {
        bound("coulomb", &row, 3, &|x| x >= 1000.0)?;
        bound("coulomb", &row, 4, &|x| x <= 1e-12)?;
        // Every slipping contact ends with the slip opposite to the friction.
        bound("coulomb", &row, 5, &|x| x == 0.0)?;
    }
    for row in expect("headon", 6)? {
        bound("headon", &row, 3, &|x| x <= 1e-9)?;
        bound("headon", &row, 4, &|x| x <= 1e-9)?;
        bound("headon", &row, 5, &|x| x <= 1e-8)?;
    }
    for row in expect("oblique", 4)? {
        bound("oblique", &row, 2, &|x| x <= 1e-9)?;
        bound("oblique", &row, 3, &|x| x <= 1e-12)?;
        bound("oblique", &row, 4, &|x| x <= 1e-12)?;
    }
    for row in expect("rebound", 6)? {
        bound("rebound", &row, 4, &|x| x <= 1e-6)?;
    }
    for row in expect("pairs", 4)? {
        // Most pairs meet (their paths cross with spread velocities).
        bound("pairs", &row, 2, &|x| x >= 8.0)?;
        bound("pairs", &row, 3, &|x| x <= 1e-9)?;
        bound("pairs", &row, 4, &|x| x <= 1e-9)?;
        bound("pairs", &row, 5, &|x| x <= 1e-9)?;
    }
    for row in expect("ramp", 8)? {
        bound("ramp", &row, 5, &|x| x <= 1e-3)?;
        bound("ramp", &row, 6, &|x| x <= 1e-4)?;
    }
    for row in expect("stack", 6)? {
        bound("stack", &row, 3, &|x| x < 5e-3)?;
        bound("stack", &row, 4, &|x| x < 1e-2)?;
        bound("stack", &row, 5, &|x| x < 1e-6)?;
        bound("stack", &row, 7, &|x| x == 0.0)?;
    }
    Ok(failures)
}

/// The double pendulums' steps, as many as the spring's.
const DOUBLE_PENDULUM_STEPS: usize = 1_000_000;

/// Measures and prints the tables; with `--write`, records the data file and the tables.
pub fn main() -> Res<()> {
    let start = std::time::Instant::now();
    let mut tsv = provenance::header();
    writeln!(
        tsv,
        "# method: deterministic runs, release build; figures with two significant digits"
    )?;
    tsv.push_str(&measure(DOUBLE_PENDULUM_STEPS)?);
    let table = render(&tsv)?;
    print!("{table}");
    let failures = check(&tsv)?;
    for f in &failures {
        eprintln!("bound broken: {f}");
    }
    eprintln!("measured in {:.1} s", start.elapsed().as_secs_f64());
    if std::env::args().any(|a| a == "--write") {
        let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("book/src/generated");
        std::fs::write(dir.join("moving_bodies.tsv"), &tsv)?;
        std::fs::write(dir.join("moving_bodies.md"), &table)?;
        println!("wrote {}", dir.join("moving_bodies.md").display());
    }
    Ok(())
}
