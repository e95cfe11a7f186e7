//! Bodies that move as well as turn (`rotorflow::dynamics::motion`): Newton–Euler checked
//! against the exact free flight, the rotation-only body, the conserved momenta and the
//! orders of the integrators.

use crate::{attitude_distance, random_body, rng};
use rand::Rng;
use rotorflow::dynamics::motion::forques::{Anchor, AngularDrag, Gravity, LinearDrag, Spring};
use rotorflow::dynamics::motion::{
    MotionIntegrator, MotionRk4, MotionSplitting, MovingBody, System,
};
use rotorflow::dynamics::{Integrator, RigidBody, Splitting};
use rotorflow::prelude::*;

fn vector(c: &[f64]) -> Vector {
    Vector::from_components(c).unwrap()
}

fn random_vector(r: &mut impl Rng, n: usize, scale: f64) -> Vector {
    let c: Vec<f64> = (0..n).map(|_| r.gen_range(-scale..scale)).collect();
    vector(&c)
}

fn moving(rotation: RigidBody, mass: f64, x: Vector, v: Vector) -> MovingBody {
    MovingBody::from_rigid_body(rotation, mass, &x, &v).unwrap()
}

fn run(system: &mut System, integrator: &mut dyn MotionIntegrator, h: f64, steps: usize) {
    for k in 0..steps {
        integrator.step(system, k as f64 * h, h).unwrap();
    }
}

fn rel(a: &Vector, b: &Vector) -> f64 {
    (a - b).max_abs() / b.max_abs().max(1.0)
}

/// Under uniform gravity alone the centre of mass follows x₀ + v₀ t + ½ g t² (the kicks are
/// exact for a constant force) and the rotation is that of the rotation-only body under the
/// same free-rotation integrator, in N = 2 … 6.
#[test]
fn free_flight_follows_the_parabola_and_turns_as_the_rotation_only_body() {
    let mut r = rng(1501);
    for n in 2..=6 {
        let rotation = random_body(&mut r, n);
        let (x0, v0) = (random_vector(&mut r, n, 3.0), random_vector(&mut r, n, 2.0));
        let mut g = Vector::zero(n);
        g.as_mut_slice()[n - 1] = -9.81;
        let mut system =
            System::new(vec![moving(rotation.clone(), 2.5, x0.clone(), v0.clone())]).unwrap();
        system.add_forque(Gravity(g.clone())).unwrap();
        let (h, steps) = (0.01, 1000);
        run(&mut system, &mut MotionSplitting::new(), h, steps);
        let t = h * steps as f64;
        let want = &(&x0 + &(&v0 * t)) + &(&g * (0.5 * t * t));
        let got = system.bodies()[0].position();
        assert!(rel(got, &want) <= 1e-13, "N = {n}: {:e}", rel(got, &want));
        let v_want = &v0 + &(&g * t);
        assert!(rel(&system.bodies()[0].velocity(), &v_want) <= 1e-13);
        // The rotation, stepped alone with the same free-rotation flow.
        let mut alone = rotation.clone();
        let mut strang = Splitting::strang();
        for k in 0..steps {
            strang
                .step(
                    &mut alone,
                    k as f64 * h,
                    h,
                    &rotorflow::dynamics::torques::Free,
                )
                .unwrap();
        }
        let turned = system.bodies()[0].rotation();
        assert!((turned.momentum() - alone.momentum()).max_abs() <= 1e-15);
        assert!(
            attitude_distance(
                turned.principal_frame_attitude(),
                alone.principal_frame_attitude()
            ) <= 1e-15
        );
    }
}

/// Constant forques (gravity, a constant force at the centre of mass) are evaluated once,
/// when they join the system; the step they take must be the one the same forces give
/// through the general path (a closure, which the system re-evaluates at each half kick),
/// to the last bit, and the attitude-dependent constant force must not be taken for one.
#[test]
fn constant_forques_step_as_the_same_forces_evaluated_each_kick() {
    use rotorflow::dynamics::motion::forques::{ConstantForce, Frame};
    use rotorflow::dynamics::motion::{Forque, ForqueInput, Wrench};
    let mut r = rng(1502);
    for n in 2..=5 {
        let bodies: Vec<MovingBody> = (0..3)
            .map(|k| {
                let x = random_vector(&mut r, n, 3.0);
                let v = random_vector(&mut r, n, 2.0);
                moving(random_body(&mut r, n), 1.0 + k as f64, x, v)
            })
            .collect();
        let g = random_vector(&mut r, n, 10.0);
        let push = random_vector(&mut r, n, 1.0);
        let at_centre = ConstantForce {
            body: 1,
            force: push.clone(),
            point: Vector::zero(n),
            frame: Frame::World,
        };
        assert!(Gravity(g.clone()).is_constant() && at_centre.is_constant());
        let mut off_centre = at_centre.clone();
        off_centre.point = random_vector(&mut r, n, 0.5);
        assert!(!off_centre.is_constant(), "its torque turns with the body");
        let mut in_body = at_centre.clone();
        in_body.frame = Frame::Body;
        assert!(!in_body.is_constant(), "its direction turns with the body");

        let mut fast = System::new(bodies.clone()).unwrap();
        fast.add_forque(Gravity(g.clone())).unwrap();
        fast.add_forque(at_centre).unwrap();
        let general_start_p1 = bodies[1].linear_momentum().clone();
        let mut general = System::new(bodies).unwrap();
        let (g2, push2) = (g.clone(), push.clone());
        general
            .add_forque(move |input: &ForqueInput<'_>, w: &mut [Wrench]| {
                for (b, w) in input.bodies.iter().zip(w.iter_mut()) {
                    w.force += &(&g2 * b.mass());
                }
                w[1].force += &push2;
            })
            .unwrap();
        let (h, steps) = (0.01, 300);
        run(&mut fast, &mut MotionSplitting::new(), h, steps);
        run(&mut general, &mut MotionSplitting::new(), h, steps);
        for (a, b) in fast.bodies().iter().zip(general.bodies()) {
            assert_eq!(a.position(), b.position(), "N = {n}");
            assert_eq!(a.linear_momentum(), b.linear_momentum(), "N = {n}");
            assert_eq!(a.rotation().momentum(), b.rotation().momentum(), "N = {n}");
            assert_eq!(
                a.rotation().principal_frame_attitude(),
                b.rotation().principal_frame_attitude(),
                "N = {n}"
            );
        }
        // And the forces act: p₁ = p₁(0) + t (m₁ g + F).
        let t = h * steps as f64;
        let mut want = general_start_p1.clone();
        want += &(&(&(&g * 2.0) + &push) * t);
        assert!(
            rel(fast.bodies()[1].linear_momentum(), &want) <= 1e-12,
            "N = {n}"
        );
    }
}

/// Two bodies joined by an undamped spring between off-centre points, no external forque:
/// the total linear momentum and the angular momentum about the origin are conserved to
/// round-off by both integrators (the spring's forces are opposite and along the line of
/// its ends), and the energy error of the symplectic splitting stays bounded.
#[test]
fn two_bodies_on_a_spring_keep_their_momenta() {
    for n in [2, 3, 4, 5] {
        // The same random system for both integrators.
        let build = || {
            let mut r = rng(1502 + n as u64);
            let mut offset = Vector::zero(n);
            offset.as_mut_slice()[0] = 3.0;
            let a = moving(
                random_body(&mut r, n),
                1.5,
                random_vector(&mut r, n, 1.0),
                random_vector(&mut r, n, 0.5),
            );
            let b = moving(
                random_body(&mut r, n),
                0.8,
                &random_vector(&mut r, n, 1.0) + &offset,
                random_vector(&mut r, n, 0.5),
            );
            let mut s = System::new(vec![a, b]).unwrap();
            s.add_forque(Spring {
                body: 0,
                point: random_vector(&mut r, n, 0.5),
                anchor: Anchor::Body(1, random_vector(&mut r, n, 0.5)),
                stiffness: 4.0,
                rest_length: 2.0,
                damping: 0.0,
            })
            .unwrap();
            s
        };
        for integrator in [
            &mut MotionSplitting::new() as &mut dyn MotionIntegrator,
            &mut MotionRk4::new(),
        ] {
            let mut system = build();
            let (p0, l0, e0) = (
                system.linear_momentum(),
                system.angular_momentum(),
                system.energy(0.0),
            );
            let (h, steps) = (0.005, 4000);
            let mut worst_e = 0.0f64;
            for k in 0..steps {
                integrator.step(&mut system, k as f64 * h, h).unwrap();
                worst_e = worst_e.max((system.energy((k + 1) as f64 * h) - e0).abs());
            }
            let dp = (&system.linear_momentum() - &p0).max_abs();
            let dl = (&system.angular_momentum() - &l0).max_abs();
            let scale = p0.max_abs().max(l0.max_abs()).max(1.0);
            // RK4 keeps linear invariants exactly but the angular momentum (quadratic in
            // the state) only to its order: O(h⁴) per unit time.
            let dl_bound = if integrator.order() == 2 { 1e-11 } else { 1e-6 };
            assert!(
                dp <= 1e-12 * scale && dl <= dl_bound * scale,
                "{} N = {n}: Δp {dp:e}, ΔL {dl:e}",
                integrator.name()
            );
            assert!(
                worst_e <= 1e-2 * e0.abs().max(1.0),
                "{} N = {n}: energy error {worst_e:e}",
                integrator.name()
            );
        }
    }
}

/// The symplectic splitting's energy error on a conservative system (a body hanging from a
/// spring under gravity, swinging and turning) does not grow: over 10⁶ steps its largest
/// value over the second half is within a small factor of its largest value over the first
/// half (a drift would double it), and it stays at the O(h²) size of the first steps.
#[test]
fn the_splitting_keeps_the_energy_error_bounded() {
    let mut r = rng(1504);
    let n = 4;
    let rotation = random_body(&mut r, n);
    let mut system = System::new(vec![moving(
        rotation,
        1.0,
        vector(&[0.3, 0.1, -0.2, -1.0]),
        vector(&[0.2, -0.1, 0.3, 0.0]),
    )])
    .unwrap();
    let mut g = Vector::zero(n);
    g.as_mut_slice()[n - 1] = -9.81;
    system.add_forque(Gravity(g)).unwrap();
    system
        .add_forque(Spring {
            body: 0,
            point: vector(&[0.2, 0.1, 0.0, 0.3]),
            anchor: Anchor::World(Vector::zero(n)),
            stiffness: 30.0,
            rest_length: 0.5,
            damping: 0.0,
        })
        .unwrap();
    let e0 = system.energy(0.0);
    let (h, steps) = (0.002, 1_000_000);
    let mut integrator = MotionSplitting::new();
    let (mut first, mut last) = (0.0f64, 0.0f64);
    for k in 0..steps {
        integrator.step(&mut system, k as f64 * h, h).unwrap();
        let e = (system.energy((k + 1) as f64 * h) - e0).abs();
        if k < steps / 2 {
            first = first.max(e);
        } else {
            last = last.max(e);
        }
    }
    assert!(
        first > 0.0 && last <= 1.5 * first,
        "first half {first:e}, second half {last:e}"
    );
    assert!(first <= 1e-3 * e0.abs(), "{first:e} against E = {e0}");
}

/// Orders measured on a spring system with gravity: halving h divides the error at t = 1 by
/// about 2^p (p = 2 for the splitting, 4 for RK4), against a reference with h/64 of RK4. The
/// same with damping: a damped spring, linear and angular drag (forques that read
/// velocities, where the splitting's closing half kick is implicit to stay of order 2), in
/// 3D and 4D.
#[test]
fn measured_orders() {
    let mut r = rng(1505);
    let mut cases = 0;
    for (n, damped) in [(3, false), (3, true), (4, true)] {
        let rotation = random_body(&mut r, n);
        let build = || {
            let mut x = vec![0.0; n];
            x[..3].copy_from_slice(&[0.5, 0.2, -1.0]);
            let mut v = vec![0.0; n];
            v[..2].copy_from_slice(&[0.1, 0.4]);
            let mut g = vec![0.0; n];
            g[n - 1] = -9.81;
            let mut point = vec![0.0; n];
            point[..3].copy_from_slice(&[0.3, -0.2, 0.1]);
            let mut s =
                System::new(vec![moving(rotation.clone(), 1.2, vector(&x), vector(&v))]).unwrap();
            s.add_forque(Gravity(vector(&g))).unwrap();
            s.add_forque(Spring {
                body: 0,
                point: vector(&point),
                anchor: Anchor::World(Vector::zero(n)),
                stiffness: 20.0,
                rest_length: 0.4,
                damping: if damped { 1.5 } else { 0.0 },
            })
            .unwrap();
            if damped {
                s.add_forque(LinearDrag(0.3)).unwrap();
                s.add_forque(AngularDrag(0.2)).unwrap();
            }
            s
        };
        let state = |s: &System| {
            let b = &s.bodies()[0];
            let mut v: Vec<f64> = b.position().as_slice().to_vec();
            v.extend_from_slice(b.linear_momentum().as_slice());
            v.extend_from_slice(b.rotation().momentum().as_slice());
            v.extend(b.attitude().to_matrix().iter().copied());
            v
        };
        let solve = |integrator: &mut dyn MotionIntegrator, steps: usize| {
            let mut s = build();
            run(&mut s, integrator, 1.0 / steps as f64, steps);
            state(&s)
        };
        let reference = solve(&mut MotionRk4::new(), 64 * 256);
        let err = |x: Vec<f64>| {
            x.iter()
                .zip(&reference)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        };
        for (integrator, order, base) in [
            (
                &mut MotionSplitting::new() as &mut dyn MotionIntegrator,
                2.0,
                200,
            ),
            (&mut MotionRk4::new(), 4.0, 100),
        ] {
            let e1 = err(solve(integrator, base));
            let e2 = err(solve(integrator, 2 * base));
            let measured = (e1 / e2).log2();
            println!(
                "N = {n}, damped {damped}, {}: order {measured:.3} (errors {e1:.3e}, {e2:.3e})",
                integrator.name()
            );
            assert!(
                (measured - order).abs() <= 0.2,
                "N = {n}, damped {damped}, {}: order {measured:.2} (errors {e1:e}, {e2:e})",
                integrator.name()
            );
            cases += 1;
        }
    }
    assert_eq!(cases, 6);
}

/// A body pulled by a spring anchored at the origin: the force points from the attachment
/// point to the anchor when stretched, and the torque turns the body toward it (sign pinned
/// in 3D).
#[test]
fn spring_force_and_torque_signs_in_3d() {
    let inertia = InertiaMap::from_principal_second_moments(&[1.0, 1.0, 1.0]).unwrap();
    let body = MovingBody::new(
        1.0,
        inertia,
        Rotor::identity(3),
        &vector(&[2.0, 0.0, 0.0]),
        &Vector::zero(3),
        &Bivector::zero(3),
    )
    .unwrap();
    let mut system = System::new(vec![body]).unwrap();
    system
        .add_forque(Spring {
            body: 0,
            point: vector(&[0.0, 1.0, 0.0]),
            anchor: Anchor::World(vector(&[2.0, 1.0, -3.0])),
            stiffness: 2.0,
            rest_length: 1.0,
            damping: 0.0,
        })
        .unwrap();
    let w = &system.wrenches(0.0)[0];
    // The point (2, 1, 0) is 3 from the anchor (2, 1, −3): stretched by 2, pulled down by 4.
    assert!((w.force.as_slice()[2] + 4.0).abs() < 1e-15, "{:?}", w.force);
    // Torque r ∧ F = e₂ ∧ (−4 e₃) = −4 e₂₃ (principal frame = space here).
    assert!((w.torque.get(1, 2) + 4.0).abs() < 1e-15, "{:?}", w.torque);
    // A spring to a missing body is refused.
    assert!(
        system
            .add_forque(Spring {
                body: 0,
                point: Vector::zero(3),
                anchor: Anchor::Body(3, Vector::zero(3)),
                stiffness: 1.0,
                rest_length: 0.0,
                damping: 0.0,
            })
            .is_err()
    );
}

/// The placement converts both ways: the homogeneous matrix maps a body point (r, 1) to its
/// space position (x + Q r, 1), the motor moves the point as the matrix does, and building
/// the body back from either gives the same position and attitude, N = 2 … 6.
#[test]
fn placements_convert_to_and_from_matrices_and_motors() {
    let mut r = rng(1505);
    for n in 2..=6 {
        let rotation = random_body(&mut r, n);
        let (x, v) = (random_vector(&mut r, n, 2.0), random_vector(&mut r, n, 1.0));
        let body = moving(rotation.clone(), 1.7, x.clone(), v.clone());
        let h = body.homogeneous_matrix();
        let point = random_vector(&mut r, n, 1.0);
        let mut column = nalgebra::DVector::zeros(n + 1);
        column.as_mut_slice()[..n].copy_from_slice(point.as_slice());
        column[n] = 1.0;
        let moved = &h * column;
        let want = body.point_position(&point);
        for i in 0..n {
            assert!((moved[i] - want.as_slice()[i]).abs() <= 1e-14, "N = {n}");
        }
        assert!((moved[n] - 1.0).abs() == 0.0);
        let motor = body.motor().unwrap();
        assert!(
            (motor.to_matrix() - &h).abs().max() <= 1e-14,
            "N = {n}: motor ≠ matrix"
        );
        let omega = body.omega();
        let inertia = rotation.inertia().clone();
        for back in [
            MovingBody::from_homogeneous_matrix(1.7, inertia.clone(), &h, &v, &omega).unwrap(),
            MovingBody::from_motor(1.7, inertia.clone(), &motor, &v, &omega).unwrap(),
        ] {
            assert!(rel(back.position(), &x) <= 1e-15, "N = {n}");
            assert!(
                (back.homogeneous_matrix() - &h).abs().max() <= 1e-14,
                "N = {n}"
            );
            assert!((&back.omega() - &omega).max_abs() <= 1e-14, "N = {n}");
            assert!(rel(&back.velocity(), &v) <= 1e-15, "N = {n}");
        }
    }
    // A matrix that is not a placement is refused.
    let mut bad = nalgebra::DMatrix::identity(4, 4);
    bad[(3, 0)] = 0.5;
    let inertia = InertiaMap::from_principal_second_moments(&[1.0, 2.0, 3.0]).unwrap();
    assert!(
        MovingBody::from_homogeneous_matrix(
            1.0,
            inertia,
            &bad,
            &Vector::zero(3),
            &Bivector::zero(3)
        )
        .is_err()
    );
}
