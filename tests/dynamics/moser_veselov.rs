//! The discrete Moser–Veselov top: its order against independent integrators and the closed
//! 3D form, its conservation of every Manakov integral where RK4 drifts, and its refusals.

use crate::{attitude_distance, random_body, rng, run, slope};
use rotorflow::dynamics::torques::{BodyFrame, Free};
use rotorflow::dynamics::{
    Dopri5, DynamicsError, Integrator, Invariants, MoserVeselov, RigidBody, Rkmk4, Torque,
};
use rotorflow::prelude::*;

/// Error of (L, R) at `t_end` with step `h` against `reference`.
fn error(
    start: &RigidBody,
    integ: &mut dyn Integrator,
    torque: &dyn Torque,
    t_end: f64,
    h: f64,
    reference: &RigidBody,
) -> f64 {
    let mut b = start.clone();
    run(&mut b, integ, torque, h, (t_end / h).round() as usize);
    let dl = (b.momentum() - reference.momentum()).max_abs();
    let dr = attitude_distance(
        b.principal_frame_attitude(),
        reference.principal_frame_attitude(),
    );
    dl.max(dr)
}

/// The errors in short scientific notation.
fn show(es: &[f64]) -> String {
    es.iter()
        .map(|e| format!("{e:.2e}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The measured order of `make()` on a random body in dimension `n` at t = 2, against
/// Dopri5 at tolerance 1e-13 (an independent, adaptive integrator).
fn measured_order(
    n: usize,
    seed: u64,
    torque: &dyn Torque,
    hs: &[f64],
    make: impl Fn() -> MoserVeselov,
) -> (f64, Vec<f64>) {
    let start = random_body(&mut rng(seed), n);
    let mut reference = start.clone();
    let mut dopri = Dopri5::new(1e-13, 1e-13);
    run(&mut reference, &mut dopri, torque, 0.01, 200);
    let es: Vec<f64> = hs
        .iter()
        .map(|&h| error(&start, &mut make(), torque, 2.0, h, &reference))
        .collect();
    (slope(hs, &es), es)
}

/// Measured (N = 3, 4, 5, errors at h = 0.04, 0.02, 0.01): slopes 2.00 with error ratios
/// 4.00, and the trajectory agrees with Dopri5 to 1e-6 … 1e-5 at h = 0.01: the matrix
/// conventions (M = −\[L\], Q ← QU) are those of the other integrators.
#[test]
fn is_second_order_in_3d_4d_and_5d() {
    for n in [3, 4, 5] {
        let (p, es) = measured_order(
            n,
            500 + n as u64,
            &Free,
            &[0.04, 0.02, 0.01],
            MoserVeselov::new,
        );
        eprintln!("N = {n}: order {p:.3}, errors {}", show(&es));
        assert!((p - 2.0).abs() < 0.05, "N = {n}: measured order {p}");
        assert!(es[2] < 1e-4, "N = {n}: error {:e} at h = 0.01", es[2]);
    }
}

/// The same order with a constant body-frame torque (kick–MV–kick), and order 4 for the
/// Yoshida composition.
#[test]
fn keeps_order_two_with_a_torque_and_composes_to_order_four() {
    let tau = BodyFrame(Bivector::from_components(4, &[0.3, -0.2, 0.1, 0.4, 0.0, -0.5]).unwrap());
    let (p, es) = measured_order(4, 77, &tau, &[0.04, 0.02, 0.01], MoserVeselov::new);
    eprintln!("torqued N = 4: order {p:.3}, errors {}", show(&es));
    assert!((p - 2.0).abs() < 0.1, "measured order {p}");
    for n in [3, 4, 5] {
        let (p, es) = measured_order(
            n,
            90 + n as u64,
            &Free,
            &[0.08, 0.04, 0.02],
            MoserVeselov::yoshida4,
        );
        eprintln!("yoshida4 N = {n}: order {p:.3}, errors {}", show(&es));
        assert!((p - 4.0).abs() < 0.15, "N = {n}: measured order {p}");
    }
}

/// Against the closed-form 3D top (Jacobi elliptic functions): order 2 again.
#[test]
fn agrees_with_the_exact_3d_top_to_second_order() {
    let inertia = InertiaMap::from_principal_second_moments(&[0.4, 1.1, 1.9]).unwrap();
    let start = RigidBody::from_body_momentum(
        inertia,
        Rotor::from_plane_angle(3, 0, 2, 0.3).unwrap(),
        &Bivector::from_components(3, &[0.8, -0.5, 1.2]).unwrap(),
    )
    .unwrap();
    let exact = start.exact_solution().unwrap();
    assert_eq!(exact.name(), "asymmetric top");
    let reference = exact.body_at(3.0).unwrap();
    let hs = [0.04, 0.02, 0.01];
    let es: Vec<f64> = hs
        .iter()
        .map(|&h| error(&start, &mut MoserVeselov::new(), &Free, 3.0, h, &reference))
        .collect();
    let p = slope(&hs, &es);
    eprintln!("exact 3D top: order {p:.3}, errors {}", show(&es));
    assert!((p - 2.0).abs() < 0.05, "measured order {p}");
}

#[test]
fn preprocessed_steps_reach_orders_four_and_six_against_the_exact_3d_top() {
    let inertia = InertiaMap::from_principal_second_moments(&[0.4, 1.1, 1.9]).unwrap();
    let start = RigidBody::from_body_momentum(
        inertia,
        Rotor::from_plane_angle(3, 0, 2, 0.3).unwrap(),
        &Bivector::from_components(3, &[0.8, -0.5, 1.2]).unwrap(),
    )
    .unwrap();
    let reference = start.exact_solution().unwrap().body_at(3.0).unwrap();
    for (order, hs) in [(4, [0.2, 0.1, 0.05]), (6, [0.3, 0.15, 0.075])] {
        let make = || MoserVeselov::preprocessed(order).unwrap();
        assert_eq!(make().order(), order);
        let es: Vec<f64> = hs
            .iter()
            .map(|&h| error(&start, &mut make(), &Free, 3.0, h, &reference))
            .collect();
        let p = slope(&hs, &es);
        eprintln!(
            "preprocessed, order {order}: measured {p:.3}, errors {}",
            show(&es)
        );
        assert!(
            (p - order as f64).abs() < 0.25,
            "order {order}: measured {p}"
        );
        // Far below the plain step's error at the same step.
        let plain = error(
            &start,
            &mut MoserVeselov::new(),
            &Free,
            3.0,
            hs[2],
            &reference,
        );
        eprintln!("plain step at h = {}: {plain:.2e}", hs[2]);
        assert!(
            es[2] < 1e-2 * plain,
            "order {order}: {} against {plain}",
            es[2]
        );
    }
}

#[test]
fn preprocessing_is_refused_outside_3d_and_for_orders_without_coefficients() {
    for order in [0, 3, 8] {
        let err = MoserVeselov::preprocessed(order).unwrap_err();
        assert!(
            matches!(err, DynamicsError::UnsupportedOption { .. }),
            "{err}"
        );
    }
    let mut body = random_body(&mut rng(951), 4);
    let before = body.clone();
    let err = MoserVeselov::preprocessed(4)
        .unwrap()
        .step(&mut body, 0.0, 0.01, &Free)
        .unwrap_err();
    assert!(err.to_string().contains("3D"), "{err}");
    assert_eq!(body.momentum(), before.momentum());
}

/// The drifts of one run, sampled every `every` steps: the largest of each.
fn sampled_drifts(
    body: &RigidBody,
    integ: &mut dyn Integrator,
    h: f64,
    steps: usize,
    every: usize,
) -> Vec<rotorflow::dynamics::Drift> {
    let mut b = body.clone();
    let start = Invariants::of(&b);
    let mut out = Vec::new();
    for k in 0..steps {
        integ.step(&mut b, k as f64 * h, h, &Free).unwrap();
        if (k + 1) % every == 0 {
            out.push(Invariants::of(&b).drift_from(&start));
        }
    }
    out
}

/// 10⁵ steps of h = 0.05 (t = 5000) in 4D. Measured: every Manakov integral within 2.7e-14
/// relative, the Casimirs 2.7e-14, the energy 2.6e-14 (a random walk of roundings), the rotor
/// within 5.6e-14 of unit, two Newton iterations per step; RK4 at the same step drifts
/// linearly (energy 1.8e-10 at t = 500, 1.6e-9 at t = 5000; Manakov 2.7e-10 → 2.6e-9). The
/// 10⁶-step run is in tests/reliability.
#[test]
fn conserves_every_manakov_integral_over_1e5_steps_where_rk4_drifts() {
    let body = random_body(&mut rng(4242), 4);
    let (h, steps, every) = (0.05, 100_000, 10_000);
    let mut mv = MoserVeselov::new();
    let d = sampled_drifts(&body, &mut mv, h, steps, every);
    let worst = |f: fn(&rotorflow::dynamics::Drift) -> f64| d.iter().map(f).fold(0.0f64, f64::max);
    let (manakov, casimirs, energy, attitude) = (
        worst(|d| d.manakov),
        worst(|d| d.casimirs),
        worst(|d| d.energy),
        worst(|d| d.attitude),
    );
    let rk = sampled_drifts(&body, &mut Rkmk4, h, steps, every);
    eprintln!(
        "MV 10^5 steps: Manakov {manakov:.1e}, Casimirs {casimirs:.1e}, energy {energy:.1e}, \
         attitude {attitude:.1e}, space L {:.1e}, {:.2} Newton iterations per step; \
         RK4: Manakov {:.1e} → {:.1e}, energy {:.1e} → {:.1e}",
        d.last().unwrap().space_momentum,
        mv.mean_iterations(),
        rk[0].manakov,
        rk.last().unwrap().manakov,
        rk[0].energy,
        rk.last().unwrap().energy,
    );
    assert!(
        manakov < 1e-13 && casimirs < 1e-13 && energy < 1e-13,
        "{d:?}"
    );
    assert!(attitude < 1e-12, "attitude {attitude:e}");
    assert!(d.last().unwrap().space_momentum < 1e-12);
    // RK4 drifts, and its drift grows with time.
    let (first, last) = (rk[0], *rk.last().unwrap());
    assert!(
        last.energy > 1e3 * energy.max(f64::EPSILON),
        "RK4 energy {:e}",
        last.energy
    );
    assert!(last.energy > 5.0 * first.energy && last.manakov > 5.0 * first.manakov);
}

/// Rotation matrices in N = 5 … 8 (and 11, beyond the inline storage) stay orthogonal
/// without renormalising, and the integrals and the energy stay at round-off there too.
#[test]
fn keeps_matrix_attitudes_orthogonal_and_the_integrals_in_n5_to_n11() {
    for n in [5, 6, 7, 8, 11] {
        let body = random_body(&mut rng(60 + n as u64), n);
        let d = sampled_drifts(&body, &mut MoserVeselov::new(), 0.02, 5_000, 5_000);
        let d = d[0];
        eprintln!("N = {n}: {d:?}");
        assert!(d.attitude < 1e-13, "N = {n}: {d:?}");
        assert!(
            d.manakov < 1e-13 && d.casimirs < 1e-13 && d.energy < 1e-13,
            "N = {n}: {d:?}"
        );
    }
}

/// Symmetric: a step of −h undoes a step of h (to the solver's round-off).
#[test]
fn is_time_reversible() {
    let start = random_body(&mut rng(31), 5);
    let mut b = start.clone();
    let mut mv = MoserVeselov::new();
    for _ in 0..20 {
        mv.step(&mut b, 0.0, 0.07, &Free).unwrap();
    }
    for _ in 0..20 {
        mv.step(&mut b, 0.0, -0.07, &Free).unwrap();
    }
    let dl = (b.momentum() - start.momentum()).max_abs();
    let dr = attitude_distance(
        b.principal_frame_attitude(),
        start.principal_frame_attitude(),
    );
    assert!(dl < 1e-13 && dr < 1e-13, "{dl:e} {dr:e}");
}

/// A step far too large for the momentum has no solution: a clear error, the body left as
/// it was, never NaN. Across step sizes up to that bound every step either succeeds with a
/// finite state or fails cleanly.
#[test]
fn refuses_a_step_too_large_for_the_momentum() {
    let start = random_body(&mut rng(8), 4);
    let mut b = start.clone();
    let e = MoserVeselov::new()
        .step(&mut b, 1.5, 1e3, &Free)
        .unwrap_err();
    assert!(
        matches!(e, DynamicsError::NoDiscreteSolution { time, step, .. } if time == 1.5 && step == 1e3),
        "{e:?}"
    );
    assert!(e.to_string().contains("reduce the step"), "{e}");
    assert_eq!(b, start);
    for k in 0..200 {
        let h = 0.05 * 1.05f64.powi(k);
        let mut b = start.clone();
        match MoserVeselov::new().step(&mut b, 0.0, h, &Free) {
            Ok(()) => assert!(b.momentum().as_slice().iter().all(|x| x.is_finite())),
            Err(DynamicsError::NoDiscreteSolution { .. })
            | Err(DynamicsError::SolverDidNotConverge { .. }) => assert_eq!(b, start),
            Err(e) => panic!("h = {h}: {e:?}"),
        }
    }
}

/// A map that is not Jω + ωJ (plane moments that no mass tensor has) is refused.
#[test]
fn refuses_an_inertia_that_is_no_body() {
    let map = InertiaMap::from_plane_moments(&[1.0, 1.7, 2.9, 2.2, 3.4, 1.3]).unwrap();
    let w = Bivector::from_components(4, &[0.3, -0.7, 0.5, 0.9, -0.2, 0.4]).unwrap();
    let mut b = RigidBody::from_body_velocity(map, Rotor::identity(4), &w).unwrap();
    let e = MoserVeselov::new()
        .step(&mut b, 0.0, 0.01, &Free)
        .unwrap_err();
    assert_eq!(
        e,
        DynamicsError::NonPhysicalInertia {
            integrator: "moser-veselov"
        }
    );
}
