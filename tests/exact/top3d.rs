//! The exact free 3D top ([`AsymmetricTop`]) against DOPRI5, its invariants, Euler's
//! equations, and its embedding in 4D ([`EmbeddedTop`]).
//!
//! Every test prints its measured maxima (`cargo test --test exact -- --nocapture`).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rotorflow::dynamics::exact::embedded::EmbeddedTop;
use rotorflow::dynamics::exact::top3d::{AsymmetricTop, TopRegime};
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::{Dopri5, DynamicsError, NoClosedFormReason, RigidBody, simulate};
use rotorflow::prelude::*;

/// A 3D body from classical moments (I₁, I₂, I₃), the classical momentum vector ℓ and a
/// rotation bivector for the attitude.
fn body3(classical: [f64; 3], ell: [f64; 3], attitude: [f64; 3]) -> RigidBody {
    let inertia = InertiaMap::from_classical_3d(classical).unwrap();
    let l = Bivector::from_components(3, &[ell[2], -ell[1], ell[0]]).unwrap();
    let r = Rotor::from_rotation_bivector(&Bivector::from_components(3, &attitude).unwrap());
    RigidBody::from_body_momentum(inertia, r, &l).unwrap()
}

/// The physical test body J = (0.3, 0.7, 1.1): classical moments (1.8, 1.4, 1.0).
const BODY: [f64; 3] = [1.8, 1.4, 1.0];
/// The Hairer–Lubich–Wanner body (not physical: J₁ < 0).
const HLW: [f64; 3] = [2.0, 1.0, 2.0 / 3.0];
const TILT: [f64; 3] = [0.3, -0.5, 0.9];

use crate::{no_closed_form_reasons, rotor_distance};

fn top(body: &RigidBody) -> AsymmetricTop {
    AsymmetricTop::new(body).unwrap()
}

/// Max errors (|ΔL|/|L|, max |ΔR| coefficient) of the exact solution against DOPRI5 at
/// `count + 1` equally spaced times in [0, t_end]. The rotors are compared with their signs:
/// DOPRI5 continues the rotor continuously, so this also checks the sign by continuity.
fn against_dopri5(body: &RigidBody, t_end: f64, count: usize, tol: f64) -> (f64, f64) {
    let exact = top(body);
    let times: Vec<f64> = (0..=count)
        .map(|k| t_end * k as f64 / count as f64)
        .collect();
    let traj = simulate(body, &mut Dopri5::new(tol, tol), &Free, times[1], &times).unwrap();
    let norm = body.momentum().norm();
    let (mut el, mut er) = (0.0f64, 0.0f64);
    for s in traj.samples() {
        let l = exact.momentum_at(s.time).unwrap();
        let r = exact.attitude_at(s.time).unwrap();
        el = el.max((&l - &s.momentum).norm() / norm);
        er = er.max(rotor_distance(&r, &s.attitude));
    }
    (el, er)
}

fn check_dopri5(name: &str, body: &RigidBody, periods: f64, tol_l: f64, tol_r: f64) {
    let exact = top(body);
    let period = exact.period().expect("periodic");
    let count = (10.0 * periods) as usize;
    let (el, er) = against_dopri5(body, periods * period, count, 1e-15);
    println!(
        "{name}: {:?}, {periods} periods of {period:.6}: |ΔL|/|L| = {el:.2e}, |ΔR| = {er:.2e}",
        exact.regime()
    );
    assert!(el <= tol_l, "{name}: L error {el:e} > {tol_l:e}");
    assert!(er <= tol_r, "{name}: R error {er:e} > {tol_r:e}");
}

#[test]
fn matches_dopri5_over_100_periods_above_the_separatrix() {
    let body = body3(BODY, [0.3, 0.2, 1.0], TILT);
    assert!(matches!(
        top(&body).regime(),
        TopRegime::Elliptic {
            above_separatrix: true,
            ..
        }
    ));
    check_dopri5("above", &body, 100.0, 1e-10, 1e-10);
}

#[test]
fn matches_dopri5_over_100_periods_below_the_separatrix() {
    let body = body3(BODY, [1.0, 0.2, 0.3], TILT);
    assert!(matches!(
        top(&body).regime(),
        TopRegime::Elliptic {
            above_separatrix: false,
            ..
        }
    ));
    check_dopri5("below", &body, 100.0, 1e-10, 1e-10);
}

#[test]
fn matches_dopri5_over_100_periods_for_the_non_physical_hlw_body() {
    // HLW's test body I = (2, 1, 2/3) with y₀ = (cos 1.1, 0, sin 1.1).
    let body = body3(HLW, [1.1f64.cos(), 0.0, 1.1f64.sin()], [0.0; 3]);
    assert!(!body.inertia().is_physical());
    check_dopri5("hlw", &body, 100.0, 1e-10, 1e-10);
}

#[test]
fn the_remaining_difference_is_the_integrators() {
    // Tightening DOPRI5 from 1e-11 to 1e-12 shrinks the difference about tenfold: the
    // closed form is the more accurate of the two.
    let body = body3(BODY, [1.0, 0.2, 0.3], TILT);
    let p = top(&body).period().unwrap();
    let (l11, r11) = against_dopri5(&body, 10.0 * p, 100, 1e-11);
    let (l12, r12) = against_dopri5(&body, 10.0 * p, 100, 1e-12);
    println!("tolerance 1e-11: {l11:.2e} {r11:.2e}; 1e-12: {l12:.2e} {r12:.2e}");
    assert!(l11 / l12 > 5.0 && r11 / r12 > 5.0);
}

/// A state at distance Δ = 2T/|L|² − g_b from the separatrix of `BODY`, with n₂ = 0.6.
fn near_separatrix(distance: f64) -> RigidBody {
    let g = BODY.map(|i| 1.0 / i);
    // Δ = n₃²(g₃ − g₂) + n₁²(g₁ − g₂), n₁² + n₃² = 0.64.
    let n3sq = (0.64 * (g[1] - g[0]) + distance) / (g[2] - g[0]);
    body3(BODY, [(0.64 - n3sq).sqrt(), 0.6, n3sq.sqrt()], TILT)
}

#[test]
fn matches_dopri5_next_to_the_separatrix() {
    // m1 ≈ 1e-3: 15 periods within 1e-9.
    for distance in [1e-4, -1e-4] {
        let body = near_separatrix(distance);
        let TopRegime::Elliptic { m1, .. } = top(&body).regime() else {
            panic!("expected the elliptic regime")
        };
        assert!(m1 < 1e-3);
        check_dopri5("m1 ≈ 1e-3", &body, 15.0, 1e-9, 1e-9);
    }
    // m1 ≈ 1e-7: every pass by the saddle amplifies the integrator's round-off, and DOPRI5
    // at 1e-14 and at 1e-15 differ from each other by ~1e-7 after 5 periods. The closed
    // form must lie within a few times that spread.
    let body = near_separatrix(1e-8);
    let period = top(&body).period().unwrap();
    let times: Vec<f64> = (0..=50).map(|k| 5.0 * period * k as f64 / 50.0).collect();
    let a = simulate(
        &body,
        &mut Dopri5::new(1e-14, 1e-14),
        &Free,
        times[1],
        &times,
    )
    .unwrap();
    let spread = a
        .samples()
        .iter()
        .zip(
            simulate(
                &body,
                &mut Dopri5::new(1e-15, 1e-15),
                &Free,
                times[1],
                &times,
            )
            .unwrap()
            .samples(),
        )
        .fold(0.0f64, |m, (x, y)| {
            m.max((&x.momentum - &y.momentum).norm())
        })
        / body.momentum().norm();
    let (el, er) = against_dopri5(&body, 5.0 * period, 50, 1e-15);
    println!("m1 ≈ 1e-7, 5 periods: DOPRI5 spread {spread:.2e}, exact vs DOPRI5 {el:.2e} {er:.2e}");
    assert!(el < 5.0 * spread && er < 5.0 * spread);
}

#[test]
fn on_the_separatrix() {
    // Classical moments (1/16, 1/4, 1) and ℓ = (1, 2, 2): Δ = 12 n₁² − 3 n₃² = 0 exactly.
    let body = body3([0.0625, 0.25, 1.0], [1.0, 2.0, 2.0], TILT);
    let exact = top(&body);
    assert_eq!(exact.regime(), TopRegime::Separatrix);
    assert_eq!(exact.period(), None);
    // The saddle amplifies the integrator's error like e^{λt}: compare while sech u > 1e-3.
    let t_end = 2.0;
    let (el, er) = against_dopri5(&body, t_end, 200, 1e-15);
    println!("separatrix to t = {t_end}: |ΔL|/|L| = {el:.2e}, |ΔR| = {er:.2e}");
    assert!(el < 1e-11 && er < 1e-11);
    // Asymptotically the steady rotation about the middle axis: ℓ → (0, ±3, 0), and the
    // state stays finite for any t.
    for t in [50.0, 1e3, 1e12, -1e3] {
        let l = exact.momentum_at(t).unwrap();
        assert!((l.get(0, 2).abs() - 3.0).abs() < 1e-12, "t = {t}: {l:?}");
        let r = exact.attitude_at(t).unwrap();
        assert!(r.unit_error() < 1e-14);
    }
}

#[test]
fn symmetric_tops_match_dopri5() {
    for (name, moments, periods) in [
        ("prolate", [1.0, 1.0, 0.4], 100.0),
        ("oblate", [1.0, 1.0, 1.7], 20.0),
        ("equal 1 and 3", [1.3, 0.8, 1.3], 20.0),
    ] {
        let body = body3(moments, [0.5, -0.7, 0.6], TILT);
        assert_eq!(top(&body).regime(), TopRegime::Symmetric);
        check_dopri5(name, &body, periods, 1e-10, 1e-10);
    }
}

#[test]
fn near_equal_moments_approach_the_symmetric_top() {
    // Moments 1e-12 apart take the elliptic path (m → 0); they differ from the exactly
    // symmetric solution by O(δ t).
    let ell = [0.5, -0.7, 0.6];
    let sym = top(&body3([1.0, 1.0, 0.4], ell, TILT));
    let mut worst = 0.0f64;
    for delta in [1e-12, -1e-12, f64::EPSILON] {
        let near = top(&body3([1.0 + delta, 1.0, 0.4], ell, TILT));
        assert!(matches!(near.regime(), TopRegime::Elliptic { .. }));
        for k in 0..=100 {
            let t = k as f64;
            let dl = (&near.momentum_at(t).unwrap() - &sym.momentum_at(t).unwrap()).norm();
            let dr = rotor_distance(&near.attitude_at(t).unwrap(), &sym.attitude_at(t).unwrap());
            worst = worst.max(dl).max(dr);
        }
    }
    println!("near-equal vs symmetric, t ≤ 100: {worst:.2e}");
    assert!(worst < 1e-9);
    // The thin set with ℓ almost in the plane of the two close axes (q → ∞) against DOPRI5.
    let body = body3([1.0 + 1e-9, 1.0, 0.4], [0.6, 0.8, 1e-6], TILT);
    let exact = top(&body);
    println!("thin set: {:?}", exact.regime());
    let (el, er) = against_dopri5(&body, 50.0, 100, 1e-15);
    println!("thin set vs DOPRI5, t ≤ 50: {el:.2e} {er:.2e}");
    assert!(el < 1e-11 && er < 1e-11);
    // Moments one ulp apart in the thin set (q ≈ 1e16): still finite and conservative.
    let body = body3([1.0 + f64::EPSILON, 1.0, 0.4], [0.6, 0.8, 1e-9], TILT);
    let exact = top(&body);
    for t in [0.0, 1.0, 1e3] {
        let b = exact.body_at(t).unwrap();
        assert!(
            (&b.space_momentum() - &body.space_momentum()).norm() < 1e-13,
            "t = {t}"
        );
        assert!((b.energy() / body.energy() - 1.0).abs() < 1e-13, "t = {t}");
    }
}

#[test]
fn isotropic_body_and_steady_rotations() {
    // Isotropic: R(t) = R₀ exp(−ωt/2) with ω = L/I.
    let body = body3([1.5, 1.5, 1.5], [0.5, -0.7, 0.6], TILT);
    let exact = top(&body);
    assert_eq!(exact.regime(), TopRegime::Steady);
    let omega = body.omega();
    for t in [0.0, 0.7, 123.4] {
        let expected = body
            .principal_frame_attitude()
            .compose(&Rotor::from_rotation_bivector(&(&omega * t)).into());
        assert!(rotor_distance(&exact.attitude_at(t).unwrap(), &expected) < 1e-13);
        assert_eq!(exact.momentum_at(t).unwrap(), *body.momentum());
    }
    // Steady rotation about each principal axis, the unstable middle one included: L stays
    // exactly constant and R turns uniformly.
    for axis in 0..3 {
        let mut ell = [0.0; 3];
        ell[axis] = 1.3;
        let body = body3(BODY, ell, TILT);
        let exact = top(&body);
        assert_eq!(exact.regime(), TopRegime::Steady, "axis {axis}");
        let omega = body.omega();
        for t in [1.0, 1e3, 1e6] {
            assert_eq!(exact.momentum_at(t).unwrap(), *body.momentum());
            let expected = body
                .principal_frame_attitude()
                .compose(&Rotor::from_rotation_bivector(&(&omega * t)).into());
            let err = rotor_distance(&exact.attitude_at(t).unwrap(), &expected);
            assert!(
                err < 1e-15 * t.max(1.0) * 10.0,
                "axis {axis}, t = {t}: {err:e}"
            );
        }
    }
    // At rest.
    let body = body3(BODY, [0.0; 3], TILT);
    let exact = top(&body);
    assert_eq!(exact.regime(), TopRegime::Rest);
    assert_eq!(
        exact.attitude_at(5.0).unwrap(),
        body.principal_frame_attitude().to_rotor().unwrap()
    );
}

/// The bodies most tests run on: both sides, near the separatrix, HLW, symmetric.
fn sample_bodies() -> Vec<(&'static str, RigidBody)> {
    vec![
        ("above", body3(BODY, [0.3, 0.2, 1.0], TILT)),
        ("below", body3(BODY, [1.0, 0.2, 0.3], TILT)),
        ("near separatrix", near_separatrix(1e-6)),
        (
            "separatrix",
            body3([0.0625, 0.25, 1.0], [1.0, 2.0, 2.0], TILT),
        ),
        ("hlw", body3(HLW, [1.1f64.cos(), 0.0, 1.1f64.sin()], TILT)),
        ("symmetric", body3([1.0, 1.0, 0.4], [0.5, -0.7, 0.6], TILT)),
        ("big L", body3(BODY, [3e5, -2e5, 1e5], TILT)),
    ]
}

#[test]
fn the_closed_form_conserves_energy_casimir_and_space_momentum() {
    let (mut de, mut dc, mut ds, mut du) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for (name, body) in sample_bodies() {
        let exact = top(&body);
        let (e0, c0, s0) = (
            body.energy(),
            body.momentum().norm_squared(),
            body.space_momentum(),
        );
        let scale = s0.norm();
        let mut times: Vec<f64> = (0..200).map(|k| 0.37 * k as f64).collect();
        times.extend([1e4, 1e6 + 0.1, -55.5]);
        for t in times {
            let b = exact.body_at(t).unwrap();
            let e = (b.energy() - e0).abs() / e0;
            let c = (b.momentum().norm_squared() - c0).abs() / c0;
            let s = (&b.space_momentum() - &s0).norm() / scale;
            assert!(
                e < 1e-13 && c < 1e-13 && s < 1e-13,
                "{name}, t = {t}: {e:e} {c:e} {s:e}"
            );
            de = de.max(e);
            dc = dc.max(c);
            ds = ds.max(s);
            du = du.max(b.principal_frame_attitude().unit_error());
        }
    }
    println!("conservation: energy {de:.1e}, |L|² {dc:.1e}, L_space {ds:.1e}, |RR̃−1| {du:.1e}");
    assert!(du < 1e-14);
}

#[test]
fn the_initial_state_is_reproduced() {
    let mut worst = (0.0f64, 0.0f64);
    for (name, body) in sample_bodies() {
        let exact = top(&body);
        let dl =
            (&exact.momentum_at(0.0).unwrap() - body.momentum()).norm() / body.momentum().norm();
        let dr = rotor_distance(
            &exact.attitude_at(0.0).unwrap(),
            body.principal_frame_attitude(),
        );
        assert!(dl < 1e-15 && dr < 1e-15, "{name}: {dl:e} {dr:e}");
        worst = (worst.0.max(dl), worst.1.max(dr));
        // state_at agrees exactly with attitude_at and momentum_at.
        for t in [0.0, 2.5, -7.0, 1e5] {
            let (r, l) = exact.state_at(t).unwrap();
            assert_eq!(r, exact.attitude_at(t).unwrap());
            assert_eq!(l, exact.momentum_at(t).unwrap());
        }
    }
    println!("t = 0: |ΔL|/|L| ≤ {:.1e}, |ΔR| ≤ {:.1e}", worst.0, worst.1);
}

#[test]
fn the_closed_form_solves_eulers_equations() {
    // Fourth-order central differences (h = 1e-3/|ω|, error ~(h|ω|)⁴): dL/dt = ω × L and
    // dR/dt = −½ R ω.
    let mut worst = 0.0f64;
    for (name, body) in sample_bodies() {
        let exact = top(&body);
        let scale = body.momentum().norm() * body.omega().norm();
        let h = 1e-3 / body.omega().norm();
        for k in 0..25 {
            let t = 0.731 * k as f64 * (h * 1e3);
            let at = |s: f64| exact.momentum_at(t + s).unwrap();
            let dl = (&(&at(-2.0 * h) - &at(2.0 * h)) + &((&at(h) - &at(-h)) * 8.0))
                * (1.0 / (12.0 * h));
            let l = exact.momentum_at(t).unwrap();
            let w = exact.omega_at(t).unwrap();
            let err_l = (&dl - &w.commutator(&l)).norm() / scale;
            let rt = |s: f64| exact.attitude_at(t + s).unwrap().to_multivector();
            let dr = (&(&rt(-2.0 * h) - &rt(2.0 * h)) + &((&rt(h) - &rt(-h)) * 8.0))
                * (1.0 / (12.0 * h));
            let rhs = exact
                .attitude_at(t)
                .unwrap()
                .to_multivector()
                .geometric(&Multivector::from(&w))
                * -0.5;
            let err_r = (&dr - &rhs).max_abs() / body.omega().norm();
            assert!(
                err_l < 1e-9 && err_r < 1e-9,
                "{name}, t = {t}: {err_l:e} {err_r:e}"
            );
            worst = worst.max(err_l).max(err_r);
        }
    }
    println!("Euler's equations by finite differences: {worst:.1e}");
}

#[test]
fn period_and_continuity() {
    for (name, body) in sample_bodies() {
        let exact = top(&body);
        let Some(period) = exact.period() else {
            continue;
        };
        for k in [1.0, 2.0, 37.0] {
            let dl = (&exact.momentum_at(k * period + 0.3).unwrap()
                - &exact.momentum_at(0.3).unwrap())
                .norm();
            assert!(dl < 1e-11 * body.momentum().norm(), "{name}: {dl:e}");
            // Across the period boundary the attitude (rotor sign included) is continuous.
            let eps = 1e-9 * period;
            let a = exact.attitude_at(k * period - eps).unwrap();
            let b = exact.attitude_at(k * period + eps).unwrap();
            let rate = body.omega().norm();
            assert!(
                rotor_distance(&a, &b) < 2.0 * eps * rate + 1e-14,
                "{name}, k = {k}"
            );
        }
    }
}

#[test]
fn a_million_periods_later() {
    // At t = 10⁶ periods the phase carries the rounding of t (~1e-16·t·|ω|); the solution
    // must stay consistent with itself: restarting from the state at t₁ reproduces t₁ + s.
    for (name, body) in sample_bodies() {
        let exact = top(&body);
        let Some(period) = exact.period() else {
            continue;
        };
        let t1 = 1e6 * period + 0.123;
        let restart = top(&exact.body_at(t1).unwrap());
        let mut worst = 0.0f64;
        for s in [0.0, 0.5 * period, 3.3 * period] {
            let r1 = exact.attitude_at(t1 + s).unwrap();
            let r2 = restart.attitude_at(s).unwrap();
            let l1 = exact.momentum_at(t1 + s).unwrap();
            let l2 = restart.momentum_at(s).unwrap();
            worst = worst
                .max(rotor_distance(&r1, &r2))
                .max((&l1 - &l2).norm() / body.momentum().norm());
            assert!(r1.unit_error() < 1e-14);
        }
        println!("{name}: 1e6 periods, restart consistency {worst:.1e}");
        assert!(worst < 1e-8, "{name}: {worst:e}");
    }
}

#[test]
fn random_bodies_match_dopri5() {
    // Seeded random moments (physical and not), momenta and attitudes; 3 periods each.
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let mut worst = 0.0f64;
    for _ in 0..12 {
        let moments = [(); 3].map(|_| rng.gen_range(0.3..2.0));
        let ell = [(); 3].map(|_| rng.gen_range(-1.0..1.0));
        let tilt = [(); 3].map(|_| rng.gen_range(-2.0..2.0));
        let body = body3(moments, ell, tilt);
        let exact = top(&body);
        let t_end = 3.0 * exact.period().unwrap_or(10.0);
        let (el, er) = against_dopri5(&body, t_end, 60, 1e-14);
        assert!(
            el < 1e-10 && er < 1e-10,
            "{moments:?} {ell:?}: {el:e} {er:e}"
        );
        worst = worst.max(el).max(er);
    }
    println!("random bodies, 3 periods: {worst:.1e}");
}

#[test]
fn bad_input_gives_errors() {
    let inertia = InertiaMap::from_principal_second_moments(&[1.0, 2.0, 3.0, 4.0]).unwrap();
    let l = Bivector::from_components(4, &[1.0, 0.0, 0.2, 0.5, 0.0, 0.0]).unwrap();
    let body4 = RigidBody::from_body_momentum(inertia, Rotor::identity(4), &l).unwrap();
    assert!(matches!(
        no_closed_form_reasons(AsymmetricTop::new(&body4))[..],
        [NoClosedFormReason::WrongDimension {
            expected: 3,
            found: 4,
            ..
        }]
    ));
    // A general 3D map with off-diagonal terms is not supported.
    let m = nalgebra::DMatrix::from_row_slice(3, 3, &[2.0, 0.3, 0.0, 0.3, 1.5, 0.0, 0.0, 0.0, 1.0]);
    let general = InertiaMap::from_matrix(3, &m).unwrap();
    let l3 = Bivector::from_components(3, &[0.1, 0.2, 0.3]).unwrap();
    let body = RigidBody::from_body_momentum(general, Rotor::identity(3), &l3).unwrap();
    assert_eq!(
        no_closed_form_reasons(AsymmetricTop::new(&body)),
        [NoClosedFormReason::NotDiagonalOnPlanes]
    );
    // Non-finite times.
    let exact = top(&body3(BODY, [0.3, 0.2, 1.0], TILT));
    for t in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert!(matches!(
            exact.momentum_at(t),
            Err(DynamicsError::NonFiniteArgument { name: "t", .. })
        ));
        assert!(matches!(
            exact.attitude_at(t),
            Err(DynamicsError::NonFiniteArgument { name: "t", .. })
        ));
        assert!(matches!(
            exact.omega_at(t),
            Err(DynamicsError::NonFiniteArgument { .. })
        ));
    }
    // Extreme but finite times never give NaN.
    for (_, body) in sample_bodies() {
        let exact = top(&body);
        for t in [1e15, -1e15, f64::MAX, f64::MIN_POSITIVE] {
            if let Ok(r) = exact.attitude_at(t) {
                assert!(r.as_slice().iter().all(|c| c.is_finite()));
            }
            if let Ok(l) = exact.momentum_at(t) {
                assert!(l.as_slice().iter().all(|c| c.is_finite()));
            }
        }
    }
    // Tiny and huge momenta.
    for scale in [1e-200, 1e200] {
        let body = body3(BODY, [0.3 * scale, 0.2 * scale, scale], TILT);
        let exact = top(&body);
        let period = exact.period().unwrap();
        let l = exact.momentum_at(period).unwrap();
        assert!((&l - body.momentum()).norm() < 1e-13 * body.momentum().norm());
        let r = exact.attitude_at(0.3 * period).unwrap();
        assert!(r.unit_error() < 1e-14);
    }
    // Embedding: L outside the subspace, repeated axes, axes out of range.
    assert_eq!(
        no_closed_form_reasons(AsymmetricTop::embedded(&body4, [0, 1, 2])),
        [NoClosedFormReason::MomentumOutsideSubspace {
            plane: (0, 3),
            component: 0.2,
            axes: [0, 1, 2]
        }]
    );
    assert_eq!(
        no_closed_form_reasons(AsymmetricTop::embedded(&body4, [0, 1, 1])),
        [NoClosedFormReason::InvalidAxes {
            axes: [0, 1, 1],
            dim: 4
        }]
    );
    assert_eq!(
        no_closed_form_reasons(AsymmetricTop::embedded(&body4, [0, 1, 4])),
        [NoClosedFormReason::InvalidAxes {
            axes: [0, 1, 4],
            dim: 4
        }]
    );
}

/// A 4D body with mass tensor diag(J) and L in the planes of `axes`.
fn body4(j: [f64; 4], axes: [usize; 3], l3: [f64; 3], tilt: &[f64; 6]) -> RigidBody {
    let inertia = InertiaMap::from_principal_second_moments(&j).unwrap();
    let mut l = Bivector::zero(4);
    l.set(axes[0], axes[1], l3[0]);
    l.set(axes[0], axes[2], l3[1]);
    l.set(axes[1], axes[2], l3[2]);
    let r = Rotor::from_rotation_bivector(&Bivector::from_components(4, tilt).unwrap());
    RigidBody::from_body_momentum(inertia, r, &l).unwrap()
}

#[test]
fn embedded_in_4d_matches_dopri5() {
    // The paper's S₄ = {ω₁₄ = ω₂₄ = ω₃₄ = 0} (axes 1, 2, 3) and S₁ = {ω₁₂ = ω₁₃ = ω₁₄ = 0}
    // (axes 2, 3, 4), eqs. 59–64, plus an unordered choice of axes.
    let j = [0.3, 0.7, 1.1, 1.9];
    let tilt = [0.3, -0.2, 0.5, 0.1, -0.4, 0.7];
    for axes in [[0, 1, 2], [1, 2, 3], [3, 0, 2]] {
        let body = body4(j, axes, [0.4, -0.9, 0.3], &tilt);
        let emb: EmbeddedTop = AsymmetricTop::embedded(&body, axes).unwrap();
        // The 3D plane moments are the 4D ones, Jᵢ + Jⱼ.
        let pm = emb.top3d().plane_moments();
        assert_eq!(pm[0], j[axes[0]] + j[axes[1]]);
        assert_eq!(pm[2], j[axes[1]] + j[axes[2]]);
        let period = emb.period().unwrap();
        let times: Vec<f64> = (0..=200)
            .map(|k| 20.0 * period * k as f64 / 200.0)
            .collect();
        let traj = simulate(
            &body,
            &mut Dopri5::new(1e-15, 1e-15),
            &Free,
            times[1],
            &times,
        )
        .unwrap();
        let (mut el, mut er) = (0.0f64, 0.0f64);
        for s in traj.samples() {
            let l = emb.momentum_at(s.time).unwrap();
            let r = emb.attitude_at(s.time).unwrap();
            // The motion stays in the subspace, in both solutions.
            for (k, (a, b)) in rotorflow::algebra::pairs(4).enumerate() {
                if !(axes.contains(&a) && axes.contains(&b)) {
                    assert_eq!(l.as_slice()[k], 0.0);
                    assert_eq!(s.momentum.as_slice()[k], 0.0);
                }
            }
            el = el.max((&l - &s.momentum).norm() / body.momentum().norm());
            er = er.max(rotor_distance(&r, &s.attitude));
            let w = emb.omega_at(s.time).unwrap();
            assert!((&w - &body.inertia().apply_inverse(&l)).norm() < 1e-15);
        }
        println!("4D, axes {axes:?}, 20 periods: |ΔL|/|L| = {el:.2e}, |ΔR| = {er:.2e}");
        assert!(el < 1e-10 && er < 1e-10, "axes {axes:?}: {el:e} {er:e}");
        // R(0) and the space-frame momentum.
        assert!(
            rotor_distance(
                &emb.attitude_at(0.0).unwrap(),
                body.principal_frame_attitude()
            ) < 1e-15
        );
        let b = emb.body_at(7.7).unwrap();
        assert!((&b.space_momentum() - &body.space_momentum()).norm() < 1e-13);
    }
}
