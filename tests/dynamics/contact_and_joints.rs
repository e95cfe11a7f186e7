//! Contact with half-spaces and ball joints (`rotorflow::dynamics::motion`): resting,
//! bouncing, sliding into rolling at the velocity the N-D moments predict, Coulomb's law at
//! every contact, and joints that hold without storing energy.

use rotorflow::dynamics::DynamicsError;
use rotorflow::dynamics::motion::forques::{Anchor, Gravity};
use rotorflow::dynamics::motion::{
    BallJoint, ContactShape, HalfSpace, MotionError, MotionIntegrator, MotionSplitting, MovingBody,
    SolverReport, System,
};
use rotorflow::inertia::spec::parse_body;
use rotorflow::prelude::*;

fn vector(c: &[f64]) -> Vector {
    Vector::from_components(c).unwrap()
}

fn axis(n: usize, i: usize, x: f64) -> Vector {
    let mut v = Vector::zero(n);
    v.as_mut_slice()[i] = x;
    v
}

/// A body of the SPEC grammar, placed and moving, with its contact shape.
fn body(spec: &str, x: Vector, v: Vector, omega: Bivector) -> (MovingBody, ContactShape) {
    let parsed = parse_body(spec).unwrap();
    let n = parsed.dim;
    let b = MovingBody::new(
        parsed.mass,
        parsed.inertia.clone(),
        Rotor::identity(n),
        &x,
        &v,
        &omega,
    )
    .unwrap();
    (b, ContactShape::from_geometry(&parsed.geometry))
}

/// One body under gravity −g e_N over the floor x_N = 0.
fn on_floor(
    spec: &str,
    x: Vector,
    v: Vector,
    omega: Bivector,
    friction: f64,
    restitution: f64,
) -> System {
    let n = x.dim();
    let (b, shape) = body(spec, x, v, omega);
    let mut s = System::new(vec![b]).unwrap();
    s.set_shape(0, shape).unwrap();
    s.add_forque(Gravity(axis(n, n - 1, -9.81))).unwrap();
    s.add_half_space(HalfSpace::new(&axis(n, n - 1, 1.0), 0.0, friction, restitution).unwrap())
        .unwrap();
    s
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
        _ => unreachable!("no shape"),
    }
}

/// A ball that slides on a rough floor ends rolling. Friction acts at the contact point,
/// gravity and the normal force pass through it, so the angular momentum about the contact
/// point, m a v + I ω in the plane of the motion and the normal, is conserved; rolling
/// means v = a ω. With the plane moment I = 2 m a²/(N+2) of the solid N-ball (each second
/// moment is m a²/(N+2)) and I = 2 m a²/N of the hollow sphere S^(N−1) (m a²/N), a ball
/// launched at v₀ without spin ends at v₀ (N+2)/(N+4) (solid) or v₀ N/(N+2) (hollow):
/// 5/7 and 3/5 in 3D. Checked for N = 2 … 6, to 1e-9 relative (the requirement is 1e-6).
#[test]
fn a_sliding_ball_ends_rolling_at_the_velocity_the_moments_predict() {
    let mut cases = 0;
    for n in 2..=6 {
        for (kind, ratio) in [
            ("ball", (n as f64 + 2.0) / (n as f64 + 4.0)),
            ("sphere", n as f64 / (n as f64 + 2.0)),
        ] {
            let a = 0.5;
            let v0 = 2.0;
            let mut s = on_floor(
                &format!("{kind}:{n},{a}+mass=1.5"),
                axis(n, n - 1, a),
                axis(n, 0, v0),
                Bivector::zero(n),
                0.3,
                0.0,
            );
            let mut stepper = MotionSplitting::new();
            let h = 1e-3;
            for k in 0..1500 {
                stepper.step(&mut s, k as f64 * h, h).unwrap();
            }
            let b = &s.bodies()[0];
            let v = b.velocity();
            let want = v0 * ratio;
            let err = (v.as_slice()[0] - want).abs() / want;
            assert!(
                err <= 1e-9,
                "{kind} N = {n}: v = {}, want {want} ({err:e})",
                v.as_slice()[0]
            );
            // Rolling: the contact point is at rest, the ball neither sinks nor lifts.
            let contact =
                b.point_velocity(&b.attitude().inverse_rotate_vector(&axis(n, n - 1, -a)));
            assert!(
                contact.max_abs() <= 1e-9 * v0,
                "{kind} N = {n}: contact slips {contact:?}"
            );
            assert!((b.position().as_slice()[n - 1] - a).abs() <= 1e-12);
            cases += 1;
        }
    }
    assert_eq!(cases, 10);
}

/// The 3D signs: a ball rolling along +x on the floor z = 0 turns about +y, that is with
/// the bivector component ω₁₃ = −v/a (the plane e₃e₁ is the axial +y).
#[test]
fn a_rolling_ball_turns_with_the_right_sign_in_3d() {
    let mut s = on_floor(
        "ball:3,0.5+mass=1",
        axis(3, 2, 0.5),
        axis(3, 0, 1.4),
        Bivector::zero(3),
        0.5,
        0.0,
    );
    let mut stepper = MotionSplitting::new();
    for k in 0..1000 {
        stepper.step(&mut s, k as f64 * 1e-3, 1e-3).unwrap();
    }
    let b = &s.bodies()[0];
    let v = b.velocity().as_slice()[0];
    let w = b.space_omega();
    assert!((v - 1.4 * 5.0 / 7.0).abs() <= 1e-9);
    assert!(
        (w.as_slice()[1] + v / 0.5).abs() <= 1e-9,
        "ω = {:?}",
        w.as_slice()
    );
    assert!(w.as_slice()[0].abs() <= 1e-12 && w.as_slice()[2].abs() <= 1e-12);
}

/// The box `spec` released tilted from height 2 with a sideways velocity 0.3 over the floor
/// x_N = 0 (friction 0.6, restitution 0.3), under gravity.
fn dropped_box(spec: &str) -> System {
    spun_box(spec, 0.0, 0.3)
}

/// [`dropped_box`] spinning at `spin` in the plane of the last two axes, over a floor of
/// restitution `restitution`.
fn spun_box(spec: &str, spin: f64, restitution: f64) -> System {
    let parsed = parse_body(spec).unwrap();
    let n = parsed.dim;
    let mut tilt = Bivector::zero(n);
    tilt.as_mut_slice()[0] = 0.3;
    tilt.as_mut_slice()[n * (n - 1) / 2 - 1] = -0.2;
    let mut omega = Bivector::zero(n);
    omega.as_mut_slice()[n * (n - 1) / 2 - 1] = spin;
    let b = MovingBody::new(
        parsed.mass,
        parsed.inertia.clone(),
        Rotor::from_rotation_bivector(&tilt),
        &axis(n, n - 1, 2.0),
        &axis(n, 0, 0.3),
        &omega,
    )
    .unwrap();
    let mut s = System::new(vec![b]).unwrap();
    s.set_shape(0, ContactShape::from_geometry(&parsed.geometry))
        .unwrap();
    s.add_forque(Gravity(axis(n, n - 1, -9.81))).unwrap();
    s.add_half_space(HalfSpace::new(&axis(n, n - 1, 1.0), 0.0, 0.6, restitution).unwrap())
        .unwrap();
    s
}

/// A body dropped on the floor comes to rest on it and stays: no sinking beyond 1e-9 of its
/// size and no jitter in its energy, for a tesseract falling tilted (it lands on a corner,
/// tips and settles on a face) and a 3D box.
#[test]
fn a_dropped_body_comes_to_rest_and_stays() {
    for spec in ["cuboid:0.5,0.7,0.9", "cuboid:0.5,0.6,0.7,0.8"] {
        let mut s = dropped_box(spec);
        let size = s.shapes()[0].radius();
        let mut stepper = MotionSplitting::new();
        let h = 1e-3;
        let mut lowest = f64::INFINITY;
        let mut energies = Vec::new();
        for k in 0..8000 {
            stepper.step(&mut s, k as f64 * h, h).unwrap();
            lowest = lowest.min(clearance(&s));
            if k >= 7000 {
                energies.push(s.energy((k + 1) as f64 * h));
            }
        }
        assert!(lowest >= -1e-9 * size, "{spec}: sank to {lowest:e}");
        let (lo, hi) = energies
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), e| {
                (a.min(*e), b.max(*e))
            });
        assert!(
            hi - lo <= 1e-12 * hi.abs().max(1.0),
            "{spec}: energy jitters by {:e}",
            hi - lo
        );
        assert!(
            s.bodies()[0].velocity().max_abs() <= 1e-12,
            "{spec}: still moving"
        );
        assert!(
            s.kinetic_energy() <= 1e-20,
            "{spec}: kinetic energy {:e}",
            s.kinetic_energy()
        );
    }
}

/// A spinning, tilted box dropped on a floor of restitution 0 lands without its impact
/// located: each step takes its opening and closing solve only (a speculative contact holds
/// each corner from the step before it would sink), no corner sinks beyond 1e-9 of the
/// size, and the box comes to rest; on a floor of restitution 0.3 the first impact is
/// located (a step of more solves). N = 3 and 4, h = 1/60 s.
#[test]
fn an_inelastic_landing_is_held_without_locating_it() {
    let mut cases = 0;
    for spec in ["cuboid:0.5,0.7,0.9", "cuboid:0.5,0.6,0.7,0.8"] {
        for (restitution, located) in [(0.0, false), (0.3, true)] {
            let mut s = spun_box(spec, 2.0, restitution);
            let size = s.shapes()[0].radius();
            let mut stepper = MotionSplitting::new();
            let h = 1.0 / 60.0;
            let (mut lowest, mut most) = (f64::INFINITY, 0);
            for k in 0..600 {
                let before = stepper.solver_report().solves;
                stepper.step(&mut s, k as f64 * h, h).unwrap();
                most = most.max(stepper.solver_report().solves - before);
                lowest = lowest.min(clearance(&s));
            }
            println!("{spec}, e = {restitution}: most solves {most}, lowest {lowest:e}");
            assert_eq!(
                most > 2,
                located,
                "{spec}, e = {restitution}: {most} solves"
            );
            assert!(lowest >= -1e-9 * size, "{spec}: sank to {lowest:e}");
            assert!(
                s.bodies()[0].velocity().max_abs() <= 1e-9,
                "{spec}, e = {restitution}: still moving"
            );
            cases += 1;
        }
    }
    assert_eq!(cases, 4);
}

/// An elastic ball (restitution 1, no friction) dropped from height H bounces back to H:
/// the impacts are located in time and reversed exactly, so the energy is kept to the
/// location tolerance over ten bounces — and nothing tunnels, even with a step that moves
/// the ball by more than its radius near the floor.
#[test]
fn an_elastic_bounce_keeps_the_energy_and_nothing_tunnels() {
    for (n, h) in [(2, 1e-3), (3, 1e-3), (4, 0.05), (5, 0.2)] {
        let a = 0.1;
        let mut s = on_floor(
            &format!("ball:{n},{a}"),
            axis(n, n - 1, 3.0),
            axis(n, 0, 0.4),
            Bivector::zero(n),
            0.0,
            1.0,
        );
        let e0 = s.energy(0.0);
        let mut stepper = MotionSplitting::new();
        let mut worst = 0.0f64;
        let mut lowest = f64::INFINITY;
        let mut bounces = 0;
        let mut falling = true;
        let steps = (8.0 / h) as usize;
        for k in 0..steps {
            stepper.step(&mut s, k as f64 * h, h).unwrap();
            worst = worst.max((s.energy((k + 1) as f64 * h) - e0).abs() / e0);
            lowest = lowest.min(clearance(&s));
            let up = s.bodies()[0].velocity().as_slice()[n - 1] > 0.0;
            if falling && up {
                bounces += 1;
            }
            falling = !up;
        }
        assert!(bounces >= 5, "N = {n}: {bounces} bounces");
        assert!(
            lowest >= -1e-9 * a,
            "N = {n}, h = {h}: tunnelled to {lowest:e}"
        );
        assert!(worst <= 1e-9, "N = {n}, h = {h}: energy error {worst:e}");
    }
}

/// Coulomb's law at every contact of a tumbling body: a spinning box thrown onto a rough
/// floor (3D and 4D) bounces, slides and settles; at every contact of every step the friction
/// impulse lies in the cone |J_t| ≤ μ λ, and where the point still slips after the impulse
/// the friction is on the rim of the cone and exactly opposite to the slip.
#[test]
fn coulomb_holds_at_every_contact() {
    for (spec, n, v0) in [
        ("cuboid:0.5,0.6,0.7", 3, vector(&[2.0, -1.0, 0.0])),
        ("cuboid:0.5,0.6,0.7,0.8", 4, vector(&[2.0, -1.0, 0.5, 0.0])),
    ] {
        let mu = 0.4;
        let parsed = parse_body(spec).unwrap();
        let mut omega = Bivector::zero(n);
        for (k, w) in omega.as_mut_slice().iter_mut().enumerate() {
            *w = 2.0 * ((k as f64) * 1.7).sin();
        }
        let b = MovingBody::new(
            parsed.mass,
            parsed.inertia.clone(),
            Rotor::identity(n),
            &axis(n, n - 1, 1.5),
            &v0,
            &omega,
        )
        .unwrap();
        let mut s = System::new(vec![b]).unwrap();
        s.set_shape(0, ContactShape::from_geometry(&parsed.geometry))
            .unwrap();
        s.add_forque(Gravity(axis(n, n - 1, -9.81))).unwrap();
        s.add_half_space(HalfSpace::new(&axis(n, n - 1, 1.0), 0.0, mu, 0.2).unwrap())
            .unwrap();
        let mut stepper = MotionSplitting::new();
        let (mut checked, mut slipping) = (0, 0);
        for k in 0..4000 {
            stepper.step(&mut s, k as f64 * 1e-3, 1e-3).unwrap();
            for c in s.contacts() {
                let jt = c.friction_impulse.norm();
                assert!(c.normal_impulse >= 0.0);
                assert!(
                    jt <= mu * c.normal_impulse * (1.0 + 1e-12) + 1e-300,
                    "outside the cone"
                );
                assert!(c.friction_impulse.as_slice()[n - 1].abs() <= 1e-12 * jt.max(1e-300));
                let slip = c.slip.norm();
                if slip > 1e-9 && c.normal_impulse > 0.0 {
                    slipping += 1;
                    assert!(
                        (jt - mu * c.normal_impulse).abs() <= 1e-9 * jt,
                        "slips inside the cone"
                    );
                    let cos = c.friction_impulse.dot(&c.slip) / (jt * slip);
                    assert!(
                        cos <= -1.0 + 1e-9,
                        "friction not opposite to the slip: cos {cos}"
                    );
                }
                checked += 1;
            }
        }
        assert!(
            checked > 1000 && slipping > 10,
            "{checked} contacts, {slipping} slipping"
        );
    }
}

/// Two bodies joined by a ball joint, floating free: the joint holds to 1e-12, no energy
/// is stored in it (the energy error of RATTLE stays bounded and small), and the linear
/// and angular momenta are kept to round-off (the joint's impulses are equal and opposite
/// at one point).
#[test]
fn a_ball_joint_holds_and_keeps_the_momenta() {
    for n in [3, 4, 5] {
        let mut omega = Bivector::zero(n);
        for (k, w) in omega.as_mut_slice().iter_mut().enumerate() {
            *w = (k as f64 + 0.5).cos();
        }
        let (a, _) = body(
            &format!("cuboid:{}", vec!["0.3"; n].join(",")),
            Vector::zero(n),
            axis(n, 1, 0.2),
            omega.clone(),
        );
        let (b, _) = body(
            &format!(
                "ellipsoid:{}",
                (0..n)
                    .map(|i| format!("{}", 0.2 + 0.1 * i as f64))
                    .collect::<Vec<_>>()
                    .join(",")
            ),
            axis(n, 0, 1.0),
            axis(n, 1, -0.3),
            &omega * -0.7,
        );
        let mut s = System::new(vec![a, b]).unwrap();
        s.add_ball_joint(BallJoint {
            body: 0,
            point: axis(n, 0, 0.5),
            other: Anchor::Body(1, axis(n, 0, -0.5)),
        })
        .unwrap();
        // Start consistent: close the joint's velocity by one step, then measure.
        let mut stepper = MotionSplitting::new();
        let h = 2e-3;
        stepper.step(&mut s, 0.0, h).unwrap();
        let (p0, l0, e0) = (s.linear_momentum(), s.angular_momentum(), s.energy(h));
        let mut worst_e = 0.0f64;
        let mut worst_gap = 0.0f64;
        for k in 1..5000 {
            stepper.step(&mut s, k as f64 * h, h).unwrap();
            worst_e = worst_e.max((s.energy((k + 1) as f64 * h) - e0).abs() / e0);
            let gap = &s.bodies()[0].point_position(&axis(n, 0, 0.5))
                - &s.bodies()[1].point_position(&axis(n, 0, -0.5));
            worst_gap = worst_gap.max(gap.max_abs());
        }
        let dp = (&s.linear_momentum() - &p0).max_abs();
        let dl = (&s.angular_momentum() - &l0).max_abs();
        assert!(worst_gap <= 1e-12, "N = {n}: gap {worst_gap:e}");
        assert!(dp <= 1e-13 && dl <= 1e-12, "N = {n}: Δp {dp:e}, ΔL {dl:e}");
        assert!(worst_e <= 1e-4, "N = {n}: energy error {worst_e:e}");
    }
}

/// A tilted ellipsoid set down on a rough floor rocks on it without sinking: its lowest
/// point, from the support function c_N − (Σⱼ aⱼ² (Qᵀe_N)ⱼ²)^½ computed here from the
/// attitude matrix, stays on or above the floor to 1e-9 of its size and touches it, and
/// the energy does not grow beyond the first-order error of the contact solve at h = 1e-3
/// (rolling without slipping keeps it; impacts lose some), in 3D and 4D.
#[test]
fn an_ellipsoid_rocks_on_the_floor_without_sinking() {
    for semi in [vec![0.3, 0.5, 0.8], vec![0.3, 0.45, 0.6, 0.9]] {
        let n = semi.len();
        let spec = format!(
            "ellipsoid:{}",
            semi.iter()
                .map(|a| a.to_string())
                .collect::<Vec<_>>()
                .join(",")
        );
        let parsed = parse_body(&spec).unwrap();
        let mut tilt = Bivector::zero(n);
        for (k, w) in tilt.as_mut_slice().iter_mut().enumerate() {
            *w = 0.4 * ((k as f64) * 2.3 + 0.5).sin();
        }
        let attitude = Rotor::from_rotation_bivector(&tilt);
        let lowest = |x: &Vector, q: &nalgebra::DMatrix<f64>| {
            let reach: f64 = (0..n).map(|j| (semi[j] * q[(n - 1, j)]).powi(2)).sum();
            x.as_slice()[n - 1] - reach.sqrt()
        };
        let q0 = Attitude::from(attitude.clone()).to_matrix();
        let height = -lowest(&Vector::zero(n), &q0);
        let b = MovingBody::new(
            parsed.mass,
            parsed.inertia.clone(),
            attitude,
            &axis(n, n - 1, height),
            &Vector::zero(n),
            &Bivector::zero(n),
        )
        .unwrap();
        let mut s = System::new(vec![b]).unwrap();
        s.set_shape(0, ContactShape::from_geometry(&parsed.geometry))
            .unwrap();
        s.add_forque(Gravity(axis(n, n - 1, -9.81))).unwrap();
        s.add_half_space(HalfSpace::new(&axis(n, n - 1, 1.0), 0.0, 1.0, 0.0).unwrap())
            .unwrap();
        let e0 = s.energy(0.0);
        let mut stepper = MotionSplitting::new();
        let h = 1e-3;
        let (mut deepest, mut highest, mut e_max) = (f64::INFINITY, f64::NEG_INFINITY, e0);
        for k in 0..3000 {
            stepper.step(&mut s, k as f64 * h, h).unwrap();
            let b = &s.bodies()[0];
            let low = lowest(b.position(), &b.attitude().to_matrix());
            deepest = deepest.min(low);
            highest = highest.max(low);
            e_max = e_max.max(s.energy((k + 1) as f64 * h));
        }
        let size = semi.iter().copied().fold(0.0, f64::max);
        assert!(deepest >= -1e-9 * size, "N = {n}: sank to {deepest:e}");
        assert!(highest <= 1e-3 * size, "N = {n}: lifted off to {highest:e}");
        assert!(
            e_max - e0 <= 1e-4 * e0.abs(),
            "N = {n}: energy grew by {:e} (relative)",
            (e_max - e0) / e0
        );
        assert!(
            s.bodies()[0].rotation().energy() > 0.0,
            "N = {n}: it should rock"
        );
    }
}

/// Two bars of 1 × 0.1 × 0.1 under gravity in 3D on ball joints: the first hung from the
/// origin by its end (−0.5 e₁ in its axes), the second by that end from the first's other
/// end, both turning a little.
fn double_pendulum() -> System {
    let n = 3;
    let (upper, _) = body(
        "cuboid:0.5,0.05,0.05+mass=1",
        axis(n, 0, 0.5),
        Vector::zero(n),
        Bivector::from_components(3, &[0.0, 0.0, 0.3]).unwrap(),
    );
    let (lower, _) = body(
        "cuboid:0.5,0.05,0.05+mass=1",
        axis(n, 0, 1.5),
        Vector::zero(n),
        Bivector::from_components(3, &[0.0, 0.2, 0.0]).unwrap(),
    );
    let mut s = System::new(vec![upper, lower]).unwrap();
    s.add_forque(Gravity(axis(n, n - 1, -9.81))).unwrap();
    let (inner, outer) = (axis(n, 0, -0.5), axis(n, 0, 0.5));
    s.add_ball_joint(BallJoint {
        body: 0,
        point: inner.clone(),
        other: Anchor::World(Vector::zero(n)),
    })
    .unwrap();
    s.add_ball_joint(BallJoint {
        body: 1,
        point: inner,
        other: Anchor::Body(0, outer),
    })
    .unwrap();
    s
}

/// A 3D double pendulum of two bars on ball joints (the upper hung from a point of space)
/// under gravity: RATTLE keeps both joints closed to 1e-12 at every step, and its energy
/// error stays bounded over 10⁶ steps — the largest error over the second half is within
/// 1.5 times the largest over the first (a drift would grow it in proportion to time).
#[test]
fn a_double_pendulum_on_ball_joints_keeps_a_bounded_energy_error() {
    let n = 3;
    let mut s = double_pendulum();
    let (inner, outer) = (axis(n, 0, -0.5), axis(n, 0, 0.5));
    let mut stepper = MotionSplitting::new();
    let h = 1e-3;
    // One step makes the joints' velocities consistent; measure from there.
    stepper.step(&mut s, 0.0, h).unwrap();
    let e0 = s.energy(h);
    let steps = 1_000_000;
    let (mut first, mut second, mut gap) = (0.0f64, 0.0f64, 0.0f64);
    for k in 1..=steps {
        stepper.step(&mut s, k as f64 * h, h).unwrap();
        let e = (s.energy((k + 1) as f64 * h) - e0).abs();
        if k <= steps / 2 {
            first = first.max(e);
        } else {
            second = second.max(e);
        }
        let b = s.bodies();
        gap = gap
            .max(b[0].point_position(&inner).max_abs())
            .max((&b[1].point_position(&inner) - &b[0].point_position(&outer)).max_abs());
    }
    assert!(gap <= 1e-12, "joints open by {gap:e}");
    assert!(
        first > 0.0 && second <= 1.5 * first,
        "first half {first:e}, second half {second:e}"
    );
    assert!(first <= 1e-2 * 9.81, "energy error {first:e}");
}

/// The support point (the hook for body–body collision): for a box it is the corner that
/// maximises d·x over all corners, found here by brute force; for an ellipsoid it lies on
/// the surface (Σ (rⱼ/aⱼ)² = 1) and its outward normal A⁻² r is parallel to the direction
/// in own axes, N = 2 … 5 and random attitudes and directions.
#[test]
fn support_points_are_the_furthest_points() {
    let mut cases = 0;
    for n in 2..=5 {
        for trial in 0..10 {
            let mut plane = Bivector::zero(n);
            for (k, w) in plane.as_mut_slice().iter_mut().enumerate() {
                *w = ((k + 7 * trial + n) as f64 * 1.3).sin();
            }
            let attitude = Attitude::from(Rotor::from_rotation_bivector(&plane));
            let d: Vec<f64> = (0..n)
                .map(|i| ((i * 5 + trial) as f64 * 0.9).cos())
                .collect();
            let d = vector(&d);
            let half: Vec<f64> = (0..n).map(|i| 0.4 + 0.1 * i as f64).collect();
            let cuboid = ContactShape::from_geometry(
                &parse_body(&format!(
                    "cuboid:{}",
                    half.iter()
                        .map(|x| x.to_string())
                        .collect::<Vec<_>>()
                        .join(",")
                ))
                .unwrap()
                .geometry,
            );
            let ContactShape::Vertices(corners) = &cuboid else {
                panic!("a box has corners")
            };
            let reach = |p: &Vector| d.dot(&attitude.rotate_vector(p));
            let best = corners.iter().map(reach).fold(f64::NEG_INFINITY, f64::max);
            let got = cuboid.support_point(&attitude, &d).unwrap();
            assert!((reach(&got) - best).abs() <= 1e-14, "N = {n}");
            let ellipsoid = ContactShape::Ellipsoid(half.clone());
            let r = ellipsoid.support_point(&attitude, &d).unwrap();
            let on_surface: f64 = (0..n).map(|j| (r[j] / half[j]).powi(2)).sum();
            assert!(
                (on_surface - 1.0).abs() <= 1e-14,
                "N = {n}: off the surface"
            );
            let normal: Vec<f64> = (0..n).map(|j| r[j] / (half[j] * half[j])).collect();
            let own = attitude.inverse_rotate_vector(&d);
            let cos = vector(&normal).normalize().dot(&own.normalize());
            assert!(
                (cos - 1.0).abs() <= 1e-14,
                "N = {n}: normal not along d ({cos})"
            );
            cases += 1;
        }
    }
    assert_eq!(cases, 40);
    assert!(
        ContactShape::None
            .support_point(&Attitude::identity(3), &vector(&[0.0, 0.0, 1.0]))
            .is_none()
    );
}

/// The integrator keeps each body's placed vertices and contact matrices while the body
/// does not turn; they must follow a new shape and another system. A 4D box resting on the
/// floor is given a larger shape (half-lengths doubled): the next step is refused, as the
/// new vertices start inside the floor; given a smaller one, it falls and rests on the
/// floor by the new vertices, not the old. And one integrator stepping two systems in turn
/// (a resting box, and a box twice as heavy resting lower) must keep each on its own floor.
#[test]
fn kept_placements_follow_new_shapes_and_other_systems() {
    let n = 4;
    let spec = "cuboid:0.5,0.6,0.7,0.8";
    let settle = |s: &mut System, stepper: &mut MotionSplitting, steps: usize| {
        for k in 0..steps {
            stepper.step(s, k as f64 * 0.01, 0.01).unwrap();
        }
    };
    let mut s = on_floor(
        spec,
        axis(n, n - 1, 0.8),
        Vector::zero(n),
        Bivector::zero(n),
        0.5,
        0.0,
    );
    let mut stepper = MotionSplitting::new();
    settle(&mut s, &mut stepper, 50);
    assert!(clearance(&s).abs() <= 1e-12, "rests: {:e}", clearance(&s));
    let bigger = ContactShape::from_geometry(&parse_body("cuboid:1,1.2,1.4,1.6").unwrap().geometry);
    s.set_shape(0, bigger).unwrap();
    assert!(
        clearance(&s) < -0.7,
        "the new shape starts inside the floor"
    );
    // A shape that puts the body inside the floor is refused before the step, with the
    // depth of the new vertices (the old ones would give none).
    match stepper.step(&mut s, 0.5, 0.01).unwrap_err() {
        DynamicsError::Motion(MotionError::StartsInside { depth, .. }) => {
            assert!((depth - 0.8).abs() <= 1e-9, "depth {depth}")
        }
        other => panic!("{other}"),
    }
    // A smaller shape: the box falls onto the floor and rests on its new vertices.
    let smaller =
        ContactShape::from_geometry(&parse_body("cuboid:0.25,0.3,0.35,0.4").unwrap().geometry);
    s.set_shape(0, smaller).unwrap();
    assert!(clearance(&s) > 0.39);
    settle(&mut s, &mut stepper, 100);
    assert!(
        clearance(&s).abs() <= 1e-9,
        "rests on the new vertices: {:e}",
        clearance(&s)
    );
    assert!((s.bodies()[0].position().as_slice()[n - 1] - 0.4).abs() <= 1e-9);

    // Two systems, one integrator: the second floor is at x₄ = −1.
    let mut high = on_floor(
        spec,
        axis(n, n - 1, 0.8),
        Vector::zero(n),
        Bivector::zero(n),
        0.5,
        0.0,
    );
    let (b, shape) = body(
        &format!("{spec}+mass=2"),
        axis(n, n - 1, -0.2),
        Vector::zero(n),
        Bivector::zero(n),
    );
    let mut low = System::new(vec![b]).unwrap();
    low.set_shape(0, shape).unwrap();
    low.add_forque(Gravity(axis(n, n - 1, -9.81))).unwrap();
    low.add_half_space(HalfSpace::new(&axis(n, n - 1, 1.0), -1.0, 0.5, 0.0).unwrap())
        .unwrap();
    let mut shared = MotionSplitting::new();
    for k in 0..100 {
        shared.step(&mut high, k as f64 * 0.01, 0.01).unwrap();
        shared.step(&mut low, k as f64 * 0.01, 0.01).unwrap();
    }
    let height = |s: &System| s.bodies()[0].position().as_slice()[n - 1];
    assert!((height(&high) - 0.8).abs() <= 1e-12, "{}", height(&high));
    assert!((height(&low) + 0.2).abs() <= 1e-12, "{}", height(&low));
    for s in [&high, &low] {
        assert!(s.bodies()[0].velocity().max_abs() <= 1e-12);
        let total: f64 = s.contacts().iter().map(|c| c.normal_impulse).sum();
        let weight = s.bodies()[0].mass() * 9.81 * 0.01;
        // Two velocity solves per step, each taking half a step of the weight.
        assert!((total - weight).abs() <= 1e-9 * weight, "{total} {weight}");
    }
}

/// The largest difference of position, velocity and angular velocity between two systems of
/// the same bodies.
fn state_difference(a: &System, b: &System) -> f64 {
    a.bodies()
        .iter()
        .zip(b.bodies())
        .map(|(x, y)| {
            (x.position() - y.position())
                .max_abs()
                .max((x.velocity() - y.velocity()).max_abs())
                .max((x.omega() - y.omega()).max_abs())
        })
        .fold(0.0, f64::max)
}

/// Runs `steps` single steps of h on one copy of a system and the same steps in calls of
/// `MotionSplitting::advance` by `batch` on another; returns the largest state difference at
/// the ends of the batches, and both systems.
fn single_and_joined(
    make: impl Fn() -> System,
    h: f64,
    steps: usize,
    batch: usize,
) -> (f64, System, System) {
    let (mut single, mut joined) = (make(), make());
    let (mut a, mut b) = (MotionSplitting::new(), MotionSplitting::new());
    let mut worst = 0.0f64;
    for c in 0..steps / batch {
        let t = (c * batch) as f64 * h;
        for k in 0..batch {
            a.step(&mut single, t + k as f64 * h, h).unwrap();
        }
        b.advance(&mut joined, t, h, batch).unwrap();
        worst = worst.max(state_difference(&single, &joined));
    }
    (worst, single, joined)
}

/// `MotionSplitting::advance` joins the closing half kick and velocity solve of a step with
/// the opening ones of the next under constant forques: one solve per step instead of two.
/// A solve is a projection of the velocities, linear and idempotent while contacts rest,
/// stick or slide one way and for joints, so the trajectories are those of single steps to
/// round-off there; through bounces and stick–slip transitions they agree to the solver's
/// tolerance (the impacts are still located: a step with one is taken singly). Measured
/// (printed with `--nocapture`): sliding balls 6e-15 (3D) and 4e-14 (4D), elastic bounces
/// 8e-14 and 5e-13, a tilted box dropped with friction and restitution 2e-8 (3D) and
/// 3e-13 (4D), the double pendulum 2e-10 over 5,000 steps (a chaotic motion). The last
/// step's contacts are listed as after single steps.
#[test]
fn advancing_by_many_steps_matches_single_steps() {
    let mut cases = 0;
    for n in [3usize, 4] {
        let spec = if n == 3 {
            "cuboid:0.5,0.7,0.9"
        } else {
            "cuboid:0.5,0.6,0.7,0.8"
        };
        let dropped = || dropped_box(spec);
        let sliding = || {
            on_floor(
                &format!("ball:{n},0.5+mass=1.5"),
                axis(n, n - 1, 0.5),
                axis(n, 0, 2.0),
                Bivector::zero(n),
                0.3,
                0.0,
            )
        };
        let elastic = || {
            on_floor(
                &format!("ball:{n},0.1"),
                axis(n, n - 1, 3.0),
                axis(n, 0, 0.4),
                Bivector::zero(n),
                0.0,
                1.0,
            )
        };
        // Bounds at most about ten times the worst measured over N = 3, 4: 2.2e-8, 3.8e-14,
        // 5.4e-13.
        let cases_n: [(&str, &dyn Fn() -> System, usize, f64); 3] = [
            ("dropped box", &dropped, 8000, 1e-7),
            ("sliding ball", &sliding, 1500, 4e-13),
            ("elastic ball", &elastic, 8000, 5e-12),
        ];
        for (name, make, steps, bound) in cases_n {
            let (worst, single, joined) = single_and_joined(make, 1e-3, steps, 100);
            eprintln!("{name}, N = {n}: joined against single steps {worst:.1e}");
            assert!(worst <= bound, "{name}, N = {n}: {worst:e}");
            assert!(
                clearance(&joined) >= -1e-9 * joined.shapes()[0].radius(),
                "{name}, N = {n}: sank to {:e}",
                clearance(&joined)
            );
            // The same points; their total impulse (the share of each point of a resting
            // face is not unique, the total is).
            let (a, b) = (single.contacts(), joined.contacts());
            assert_eq!(a.len(), b.len(), "{name}, N = {n}: contacts");
            // The box and the sliding ball rest on the floor at the end: the comparison has
            // points to compare (the elastic ball may be in flight).
            assert!(
                name == "elastic ball" || !a.is_empty(),
                "{name}, N = {n}: no contact to compare"
            );
            for (x, y) in a.iter().zip(b) {
                assert_eq!((x.body, x.half_space), (y.body, y.half_space));
                assert!((&x.point - &y.point).max_abs() <= 1e-9, "{name}, N = {n}");
            }
            let total = |c: &[rotorflow::dynamics::motion::Contact]| {
                c.iter().map(|x| x.normal_impulse).sum::<f64>()
            };
            assert!(
                (total(a) - total(b)).abs() <= 1e-9 * total(a).max(1e-3),
                "{name}, N = {n}: impulses {} and {}",
                total(a),
                total(b)
            );
            cases += 1;
        }
    }
    // Ball joints: the double pendulum of the energy test.
    let (worst, _, _) = single_and_joined(double_pendulum, 1e-3, 5000, 100);
    eprintln!("double pendulum: joined against single steps {worst:.1e}");
    // Measured 1.6e-10.
    assert!(worst <= 2e-9, "double pendulum: {worst:e}");
    cases += 1;
    assert_eq!(cases, 7);
}

/// A box whose bottom face is tilted by less than the touching distance over its length:
/// some of its bottom corners touch the support and the others stand just beyond the
/// touching distance, held as speculative contacts. On the floor (touching within 1e-9 of
/// the box's radius) friction 0.5 is loaded by a pull along the floor at 0.3 of the
/// sticking limit; on a fixed slab (a pair of boxes, touching within 1e-6 of the two
/// radii's sum) the box is frictionless. The targets of a face's points must be ones one
/// rigid motion meets: held at 0 at the touching corners and aimed at (or past) their gaps
/// at the others, they asked for a motion no box has. Measured so: on the floor in 3D
/// Gauss–Seidel handed impulse around the face until the stall rule stopped it (526
/// sweeps, unconverged); on the slab in 3D a solve took 259 sweeps and the box hovered
/// 1.9e-7 above the slab, held there by its touching corners. In 3D and 4D, on both
/// supports, every solve now converges within 50 sweeps, the box lands (its lowest corner
/// within 1e-9 of its radius of the support, never deeper) and does not slide (its centre
/// moves less than 1e-9 along the support after landing).
#[test]
fn a_face_partly_within_the_touching_distance_is_solved_exactly() {
    let mut cases = 0;
    for spec in ["cuboid:0.5,0.5,0.5", "cuboid:0.5,0.5,0.5,0.5"] {
        for on_slab in [false, true] {
            let support = if on_slab { "a fixed slab" } else { "the floor" };
            // Friction on the floor, none on the slab (see below).
            let friction = if on_slab { 0.0 } else { 0.5 };
            let run = tilted_face_run(spec, on_slab, friction);
            let (report, radius) = (&run.report, run.radius);
            println!("{spec} on {support}: {run:?}");
            assert_eq!(report.unconverged, 0, "{spec} on {support}: {report:?}");
            assert!(report.max_sweeps <= 50, "{spec} on {support}: {report:?}");
            assert!(run.lowest >= -1e-9 * radius, "{spec} on {support}: {run:?}");
            assert!(
                run.last <= 1e-9 * radius,
                "{spec} on {support}: hovers, {run:?}"
            );
            assert!(run.slid <= 1e-9, "{spec} on {support}: slides, {run:?}");
            cases += 1;
        }
    }
    assert_eq!(cases, 4);
}

/// Gauss–Seidel with friction can cycle: its largest change the same from one sweep to the
/// next, above the tolerance, while impulses creep around a face and the bodies' velocities
/// stay where they are. Such a solve stops on the cycle (three sweeps in a row that leave
/// the velocities where they were, to 1e-3 of the tolerance, after 20 without a 1 % fall of
/// the change), or once its change has not fallen by 1 % in 500 sweeps, and is counted
/// unconverged with its residual, instead of sweeping to the limit of 20,000. Measured on
/// the landing of the tilted 3D box of [`tilted_face_run`] on a fixed slab with friction
/// 0.5: one solve stops on its cycle after 44 sweeps (521 by the 500-sweep rule alone, which
/// leaves the same residual, 7.1e-9 of the contacts' speed; without either it sweeps to
/// 20,000).
#[test]
fn a_cycling_solve_stops_early_and_is_counted() {
    let run = tilted_face_run("cuboid:0.5,0.5,0.5", true, 0.5);
    let report = &run.report;
    println!("a tilted box landing on a fixed slab with friction: {run:?}");
    assert!(report.unconverged > 0, "no solve cycled: {report:?}");
    // Stopped on the cycle (its sweeps leave the velocities where they were), not after
    // 500 sweeps without progress, and reported so.
    assert!(report.max_sweeps < 100, "{report:?}");
    assert_eq!(report.cycled, report.unconverged, "{report:?}");
    assert_eq!(
        (report.at_sweep_limit, report.stalled),
        (0, 0),
        "{report:?}"
    );
    assert!(report.worst_residual < 1e-6, "{report:?}");
}

/// What [`tilted_face_run`] measured: the solves, the least clearance of the box's
/// corners over the support after any step and at the end, how far its centre moved along
/// the support after landing (from the fifth step on), and its radius.
#[derive(Debug)]
struct TiltedFace {
    report: SolverReport,
    lowest: f64,
    last: f64,
    slid: f64,
    radius: f64,
}

/// 30 steps of h = 1/60 s of a box whose bottom face is tilted by less than the touching
/// distance over its length (by 0.75 and 0.6 of it over a unit length, in the planes of the
/// first two axes with the vertical), its lowest corner placed at 0.05 of it: on the floor
/// (`on_slab` false, touching within 1e-9 of the box's radius) or on a fixed slab (a pair
/// of boxes, touching within 1e-6 of the two radii's sum). `friction` on both sides, loaded
/// by a pull along the support at 0.3 of the sticking limit.
fn tilted_face_run(spec: &str, on_slab: bool, friction: f64) -> TiltedFace {
    let parsed = parse_body(spec).unwrap();
    let n = parsed.dim;
    let shape = ContactShape::from_geometry(&parsed.geometry);
    let ContactShape::Vertices(corners) = &shape else {
        unreachable!("a box has vertices")
    };
    // The slab: half-lengths 2 along the floor, 0.5 across.
    let mut halves = vec!["2"; n];
    halves[n - 1] = "0.5";
    let slab_shape = ContactShape::from_geometry(
        &parse_body(&format!("cuboid:{}", halves.join(",")))
            .unwrap()
            .geometry,
    );
    let radius = shape.radius();
    let touching = if on_slab {
        1e-6 * (radius + slab_shape.radius())
    } else {
        1e-9 * radius
    };
    // Tilted in the planes of the first two axes with the vertical, by 0.75 and 0.6 of
    // the touching distance over the face's unit length.
    let mut tilt = Bivector::zero(n);
    // The index of the plane (i, N − 1) among the planes (a < b) in order.
    let vertical = |i: usize| (0..i).map(|a| n - 1 - a).sum::<usize>() + (n - 2 - i);
    tilt.as_mut_slice()[vertical(0)] = 0.75 * touching;
    tilt.as_mut_slice()[vertical(1)] = 0.6 * touching;
    let placed = |height: f64| {
        MovingBody::new(
            parsed.mass,
            parsed.inertia.clone(),
            Rotor::from_rotation_bivector(&tilt),
            &axis(n, n - 1, height),
            &Vector::zero(n),
            &Bivector::zero(n),
        )
        .unwrap()
        .with_friction(friction)
        .unwrap()
    };
    // Lifted so that the lowest corner stands at 0.05 of the touching distance.
    let heights: Vec<f64> = corners
        .iter()
        .map(|p| placed(0.0).point_position(p).as_slice()[n - 1])
        .collect();
    let lift = 0.05 * touching - heights.iter().copied().fold(f64::INFINITY, f64::min);
    let bottom: Vec<f64> = heights
        .iter()
        .map(|h| h + lift)
        .filter(|&h| h < 10.0 * touching)
        .collect();
    let near = bottom.iter().filter(|&&h| h <= touching).count();
    assert!(
        near > 0 && near < bottom.len(),
        "{spec}: the bottom corners stand at {bottom:?} (touching within {touching:e})"
    );
    let mut bodies = vec![placed(lift)];
    if on_slab {
        let slab = MovingBody::fixed(slab_shape, Rotor::identity(n), &axis(n, n - 1, -0.5))
            .unwrap()
            .with_friction(friction)
            .unwrap();
        bodies.push(slab);
    }
    let mut s = System::new(bodies).unwrap();
    s.set_shape(0, shape.clone()).unwrap();
    let mut g = axis(n, n - 1, -9.81);
    g.as_mut_slice()[0] = 0.3 * friction * 9.81;
    s.add_forque(Gravity(g)).unwrap();
    if !on_slab {
        s.add_half_space(HalfSpace::new(&axis(n, n - 1, 1.0), 0.0, friction, 0.0).unwrap())
            .unwrap();
    }
    let mut stepper = MotionSplitting::new();
    let h = 1.0 / 60.0;
    let (mut lowest, mut landed_at) = (f64::INFINITY, 0.0);
    for k in 0..30 {
        stepper.step(&mut s, k as f64 * h, h).unwrap();
        lowest = lowest.min(clearance(&s));
        if k == 4 {
            landed_at = s.bodies()[0].position().as_slice()[0];
        }
    }
    TiltedFace {
        report: stepper.solver_report(),
        lowest,
        last: clearance(&s),
        slid: (s.bodies()[0].position().as_slice()[0] - landed_at).abs(),
        radius,
    }
}
