//! The paper's §7 (eqs. 107–134), formula by formula, against the closed form of
//! `two_moments` (itself checked against Dopri5) and against Dopri5 directly.
//!
//! Reading (see `rotorflow::dynamics::exact::paper`): a, b, c, d are half-axes, J ∝ (a², b²,
//! c², d²); the paper's ωᵢⱼ are the crate's components (the book's Conventions chapter). The printed forms are typed in here
//! literally (`printed_*`); the crate holds only the correct ones.
//!
//! Example states: §7.2 κ = 2, ω(0) = (0.3, −0.5, 0.8, 0.4, 0.2, −0.6); §7.3 κ = 1.5,
//! ω(0) = (0.9, 0.1, −0.3, 0.2, 0.5, 0.4) (components 12, 13, 14, 23, 24, 34).
//! Tolerances: 1e-13 for closed form vs closed form, 1e-10 (relative to |ω|) against
//! Dopri5, and "discrepancy" means a difference asserted to its printed value within 1e-9.

use crate::{dopri_reference, rotor_distance};
use rotorflow::dynamics::RigidBody;
use rotorflow::dynamics::exact::paper::{
    ThreeEqualMoments, TwoEqualPairs, frequency_factor, isotropic_omega,
    principal_second_moments_from_half_axes, three_equal_second_moments,
    two_equal_pairs_second_moments,
};
use rotorflow::dynamics::exact::two_moments::{TwoMomentKind, TwoMomentSolution};
use rotorflow::prelude::*;
use std::f64::consts::PI;

const KAPPA_72: f64 = 2.0;
const OMEGA_72: [f64; 6] = [0.3, -0.5, 0.8, 0.4, 0.2, -0.6];
const KAPPA_73: f64 = 1.5;
const OMEGA_73: [f64; 6] = [0.9, 0.1, -0.3, 0.2, 0.5, 0.4];

fn biv(c: &[f64; 6]) -> Bivector {
    Bivector::from_components(4, c).unwrap()
}

fn body(j: &[f64], omega: &Bivector) -> RigidBody {
    RigidBody::from_body_velocity(
        InertiaMap::from_principal_second_moments(j).unwrap(),
        Rotor::identity(4),
        omega,
    )
    .unwrap()
}

/// The correct dω/dt = I⁻¹(ω × I(ω)) from the crate's Euler equations.
fn omega_rate(j: &[f64], omega: &Bivector) -> Bivector {
    let b = body(j, omega);
    b.inertia()
        .apply_inverse(&b.omega().commutator(b.momentum()))
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

// ---------------------------------------------------------------------------------------
// The printed formulas, literally.
// ---------------------------------------------------------------------------------------

/// Eqs. (116)–(118) with (119)–(120): (ω₁₄, ω₂₄, ω₃₄).
fn printed_116_to_118(c: [f64; 6], kappa: f64, t: f64) -> [f64; 3] {
    let [c1, c2, c3, c4, c5, c6] = c;
    let s = (c1 * c1 + c2 * c2 + c3 * c3).sqrt();
    let k2 = kappa * kappa;
    let arg = (k2 - 1.0) / (k2 + 1.0) * t * s;
    let (cc, ss) = (arg.cos(), arg.sin());
    let d = c2 * c2 + c3 * c3;
    let w14 = c6 * cc + c5 * ss + c4;
    let w24 = (c1 * c2 * c6 - c3 * c5 * s) / d * cc + (c1 * c2 * c5 + c3 * c6 * s) / d * ss
        - c2 * c4 / c1;
    let w34 = -(c1 * c1 * c3 * c6 + c1 * c2 * c5 * s) / (c1 * d) * cc
        + (-c1 * c1 * c3 * c5 + c1 * c2 * c6 * s) / (c1 * d) * ss
        + c3 * c4 / c1;
    [w14, w24, w34]
}

/// The right-hand sides dω/dt of the printed eqs. (113)–(115): (ω₁₄, ω₂₄, ω₃₄).
fn printed_113_to_115(kappa: f64, w: &[f64; 6]) -> [f64; 3] {
    let (c3, c2, w14, c1, w24, w34) = (w[0], w[1], w[2], w[3], w[4], w[5]);
    let k2 = kappa * kappa;
    let f = (1.0 - k2) / (1.0 + k2);
    [
        f * (c3 * w24 + c2 * w34),  // (114)
        -f * (c3 * w14 - c1 * w34), // (113)
        -f * (c2 * w14 + c1 * w24), // (115)
    ]
}

/// Eqs. (128)–(131) with (132)–(134): (ω₁₃, ω₁₄, ω₂₃, ω₂₄).
fn printed_128_to_131(c: [f64; 6], kappa: f64, t: f64) -> [f64; 4] {
    let [c1, c2, c3, c4, c5, c6] = c;
    let k2 = kappa * kappa;
    let nu = (k2 - 1.0) / (k2 + 1.0);
    let (o1, o2) = (nu * (c1 - c2), nu * (c1 + c2));
    let (f1, f2, f3, f4) = (
        (o1 * t).sin(),
        (o1 * t).cos(),
        (o2 * t).sin(),
        (o2 * t).cos(),
    );
    [
        c3 * f1 + c4 * f2 + c5 * f3 + c6 * f4,
        c4 * f1 - c3 * f2 - c6 * f3 + c5 * f4,
        c4 * f1 - c3 * f2 + c6 * f3 - c5 * f4,
        -c3 * f1 - c4 * f2 + c5 * f3 + c6 * f4,
    ]
}

/// The right-hand sides dω/dt of the printed eqs. (124)–(127): (ω₁₃, ω₁₄, "ω₃₄" of (126),
/// ω₂₄).
fn printed_124_to_127(kappa: f64, w: &[f64; 6]) -> [f64; 4] {
    let (c1, w13, w14, w23, w24, c2) = (w[0], w[1], w[2], w[3], w[4], w[5]);
    let k2 = kappa * kappa;
    let f = (k2 - 1.0) / (1.0 + k2);
    [
        -f * (c1 * w23 - c2 * w14),                      // (124)
        -f * (c2 * w13 + c1 * w24),                      // (125)
        f * (c2 * w24 + c1 * w13),                       // (126)
        (1.0 - k2) / (1.0 + k2) * (c1 * w14 - c2 * w23), // (127)
    ]
}

fn constants_72(p: &ThreeEqualMoments) -> [f64; 6] {
    let [c1, c2, c3] = p.constants_c1_to_c3();
    let [c4, c5, c6] = p.constants_c4_to_c6().unwrap();
    [c1, c2, c3, c4, c5, c6]
}

fn constants_73(p: &TwoEqualPairs) -> [f64; 6] {
    let [c1, c2] = p.constants_c1_c2();
    let [c3, c4, c5, c6] = p.constants_c3_to_c6();
    [c1, c2, c3, c4, c5, c6]
}

// ---------------------------------------------------------------------------------------
// The parameterisation (eqs. 107, 109, 121)
// ---------------------------------------------------------------------------------------

#[test]
fn paper_eq_109_parameters_are_half_axes() {
    // The paper's factor ν = (κ² − 1)/(κ² + 1) must be the crate's (J₄ − J₁)/(J₄ + J₁),
    // the ratio of the generator Ω = ν ω_AA to ω_AA. κ = 2: ν = 0.6.
    let k = KAPPA_72;
    let nu_paper = frequency_factor(k).unwrap();
    assert!(close(nu_paper, 0.6, 1e-15));
    let w = biv(&OMEGA_72);
    let nu_of = |j: &[f64]| {
        let s = TwoMomentSolution::new(&body(j, &w)).unwrap();
        s.generator().get(0, 1) / w.get(0, 1)
    };
    // Half-axes: J = (a², b², c², d²) = (1, 1, 1, κ²).
    let j_half = principal_second_moments_from_half_axes(&[1.0, 1.0, 1.0, k]).unwrap();
    assert_eq!(j_half, three_equal_second_moments(k).unwrap().to_vec());
    assert!(close(nu_of(&j_half), nu_paper, 1e-15));
    // a…d as the principal values of J: ν = (κ − 1)/(κ + 1) = 1/3.
    assert!(close(nu_of(&[1.0, 1.0, 1.0, k]), 1.0 / 3.0, 1e-15));
    // a…d as the axis moments 𝕀 = tr J − J (eq. 79, `AxisMoment`): J = tr J − 𝕀 with
    // tr J = Σ𝕀/3 = 5/3 → J = (2/3, 2/3, 2/3, −1/3), ν = −3 (and no body has J₄ < 0).
    let axis = [1.0, 1.0, 1.0, k];
    let tr = axis.iter().sum::<f64>() / 3.0;
    let j_axis: Vec<f64> = axis.iter().map(|x| tr - x).collect();
    assert!(close(
        (j_axis[3] - j_axis[0]) / (j_axis[3] + j_axis[0]),
        -3.0,
        1e-14
    ));
    // a…d as gyration radii 𝕃 (𝕀 ∝ 𝕃² = (1, 1, 1, κ²)): J = (4/3, 4/3, 4/3, −5/3), ν = 9.
    let gyr = [1.0, 1.0, 1.0, k * k];
    let tr = gyr.iter().sum::<f64>() / 3.0;
    let j_gyr: Vec<f64> = gyr.iter().map(|x| tr - x).collect();
    assert!(close(
        (j_gyr[3] - j_gyr[0]) / (j_gyr[3] + j_gyr[0]),
        9.0,
        1e-13
    ));
    // The common factor of J (V/3 cuboid, V/6 ellipsoid) does not change ω(t).
    let scaled: Vec<f64> = j_half.iter().map(|x| 7.3 * x).collect();
    let a = TwoMomentSolution::new(&body(&j_half, &w)).unwrap();
    let b = TwoMomentSolution::new(&body(&scaled, &w)).unwrap();
    for t in [0.7, 13.0] {
        assert!((&a.omega_at(t).unwrap() - &b.omega_at(t).unwrap()).norm() < 1e-14);
    }
    // §7.3: J = (1, 1, κ², κ²) from "a = b = 1, c = d = κ".
    assert_eq!(
        principal_second_moments_from_half_axes(&[1.0, 1.0, KAPPA_73, KAPPA_73]).unwrap(),
        two_equal_pairs_second_moments(KAPPA_73).unwrap().to_vec()
    );
}

// ---------------------------------------------------------------------------------------
// §7.1 (eqs. 107–108)
// ---------------------------------------------------------------------------------------

#[test]
fn paper_eq_108_isotropic_omega_is_constant_in_every_dimension() {
    for n in [3, 4, 5, 6, 8] {
        let c: Vec<f64> = (0..n * (n - 1) / 2)
            .map(|k| (0.9 * k as f64 + 0.2).sin())
            .collect();
        let w = Bivector::from_components(n, &c).unwrap();
        let b = RigidBody::from_body_velocity(
            InertiaMap::from_principal_second_moments(&vec![1.3; n]).unwrap(),
            Rotor::identity(n),
            &w,
        )
        .unwrap();
        let s = TwoMomentSolution::new(&b).unwrap();
        assert_eq!(s.kind(), TwoMomentKind::Isotropic);
        let period = 2.0 * PI / (w.norm());
        let times: Vec<f64> = (1..=4).map(|k| 25.0 * period * k as f64).collect();
        let reference = dopri_reference(&b, &times);
        for (&t, (_, l)) in times.iter().zip(&reference) {
            assert_eq!(isotropic_omega(&w, t).unwrap(), w);
            assert!((&s.omega_at(t).unwrap() - &w).norm() <= 1e-15 * w.norm());
            let dopri = b.inertia().apply_inverse(l);
            assert!((&dopri - &w).norm() <= 1e-12 * w.norm(), "N = {n}");
        }
    }
}

// ---------------------------------------------------------------------------------------
// §7.2 (eqs. 109–120)
// ---------------------------------------------------------------------------------------

#[test]
fn paper_eqs_110_to_112_omega_12_13_23_are_constant() {
    let w = biv(&OMEGA_72);
    let j = three_equal_second_moments(KAPPA_72).unwrap();
    let s = TwoMomentSolution::new(&body(&j, &w)).unwrap();
    let p = ThreeEqualMoments::new(KAPPA_72, &w).unwrap();
    assert_eq!(p.constants_c1_to_c3(), [0.4, -0.5, 0.3]); // (ω₂₃, ω₁₃, ω₁₂)
    let rate = omega_rate(&j, &w);
    for (i, k) in [(0, 1), (0, 2), (1, 2)] {
        assert!(rate.get(i, k).abs() < 1e-16);
        for t in [1.0, 50.0, 777.0] {
            assert!(close(s.omega_at(t).unwrap().get(i, k), w.get(i, k), 1e-14));
            assert_eq!(p.omega_at(t).unwrap().get(i, k), w.get(i, k));
        }
    }
}

#[test]
fn paper_eqs_113_to_115_have_the_coupling_sign_reversed() {
    // κ = 2, ω(0) as above: the crate's (dω₁₄, dω₂₄, dω₃₄)/dt = (0.216, −0.288, 0.192); the
    // printed right-hand sides are exactly their negatives.
    let w = biv(&OMEGA_72);
    let j = three_equal_second_moments(KAPPA_72).unwrap();
    let rate = omega_rate(&j, &w);
    let correct = [rate.get(0, 3), rate.get(1, 3), rate.get(2, 3)];
    let printed = printed_113_to_115(KAPPA_72, &OMEGA_72);
    eprintln!("(113)-(115): correct {correct:?}, printed {printed:?}");
    // Correct: (1+κ²) dω_i4/dt = (κ² − 1) ([ω]²)_i4, i.e. ν = 0.6 times
    // (ω₁₂ω₂₄ + ω₁₃ω₃₄, −ω₁₂ω₁₄ + ω₂₃ω₃₄, −ω₁₃ω₁₄ − ω₂₃ω₂₄) = (0.36, −0.48, 0.32).
    let expected = [0.6 * 0.36, 0.6 * -0.48, 0.6 * 0.32];
    for i in 0..3 {
        assert!(close(correct[i], expected[i], 1e-15), "{i}");
        assert!(close(printed[i], -expected[i], 1e-15), "{i}");
    }
}

#[test]
fn paper_eqs_116_to_118_constants_from_the_initial_state() {
    // c₄ = c₁(m·v)/s², c₅ = −(c₃v₂ + c₂v₃)/s, c₆ = v₁ − c₄ reproduce ω(0) through the
    // printed (116)–(118) at t = 0.
    let p = ThreeEqualMoments::new(KAPPA_72, &biv(&OMEGA_72)).unwrap();
    let c = constants_72(&p);
    let at0 = printed_116_to_118(c, KAPPA_72, 0.0);
    for (x, y) in at0.iter().zip([OMEGA_72[2], OMEGA_72[4], OMEGA_72[5]]) {
        assert!(close(*x, y, 1e-15));
    }
}

#[test]
fn paper_eqs_116_to_118_run_backwards_in_time() {
    // The printed solution solves the printed (113)–(115): it equals the correct motion at
    // −t. At t = 1 (κ = 2, ω(0) as above) the printed (ω₁₄, ω₂₄, ω₃₄) is
    // (0.5365, 0.4830, −0.7203), the correct (0.9557, −0.0759, −0.3477).
    let w = biv(&OMEGA_72);
    let j = three_equal_second_moments(KAPPA_72).unwrap();
    let s = TwoMomentSolution::new(&body(&j, &w)).unwrap();
    let p = ThreeEqualMoments::new(KAPPA_72, &w).unwrap();
    let c = constants_72(&p);
    for t in [0.5, 1.0, 7.0, 200.0] {
        let printed = printed_116_to_118(c, KAPPA_72, t);
        let back = s.omega_at(-t).unwrap();
        let fwd = s.omega_at(t).unwrap();
        let back3 = [back.get(0, 3), back.get(1, 3), back.get(2, 3)];
        let fwd3 = [fwd.get(0, 3), fwd.get(1, 3), fwd.get(2, 3)];
        for i in 0..3 {
            assert!(close(printed[i], back3[i], 1e-13), "t = {t}");
        }
        if t == 1.0 {
            eprintln!("(116)-(118) at t = 1: printed {printed:?}, correct {fwd3:?}");
            assert!(close(printed[0], PRINTED_116_T1, 1e-9));
            assert!(close(fwd3[0], CORRECT_116_T1, 1e-9));
        }
    }
}

const PRINTED_116_T1: f64 = 0.536_517_820_317_119_4;
const CORRECT_116_T1: f64 = 0.955_673_961_679_076_5;

#[test]
fn paper_eqs_117_118_divide_by_c1_and_by_c2_c3() {
    // c₁ = ω₂₃ = 0 or c₂ = c₃ = 0 make the printed ω₂₄, ω₃₄ 0/0; the corrected form stays
    // finite and matches the crate's closed form.
    let j = three_equal_second_moments(KAPPA_72).unwrap();
    for w0 in [
        [0.3, -0.5, 0.8, 0.0, 0.2, -0.6], // c₁ = 0
        [0.0, 0.0, 0.8, 0.4, 0.2, -0.6],  // c₂ = c₃ = 0
    ] {
        let w = biv(&w0);
        let p = ThreeEqualMoments::new(KAPPA_72, &w).unwrap();
        let printed = printed_116_to_118(constants_72(&p), KAPPA_72, 1.0);
        assert!(printed.iter().any(|x| !x.is_finite()), "{printed:?}");
        let s = TwoMomentSolution::new(&body(&j, &w)).unwrap();
        for t in [1.0, 30.0] {
            let a = p.omega_at(t).unwrap();
            assert!(a.as_slice().iter().all(|x| x.is_finite()));
            assert!((&a - &s.omega_at(t).unwrap()).norm() < 1e-13);
        }
    }
}

#[test]
fn paper_eqs_119_120_frequency_is_the_body_frame_rate() {
    // ν s = |Ω| (the crate's generator): after 2π/(ν s) the motion is back.
    let w = biv(&OMEGA_72);
    let j = three_equal_second_moments(KAPPA_72).unwrap();
    let s = TwoMomentSolution::new(&body(&j, &w)).unwrap();
    let p = ThreeEqualMoments::new(KAPPA_72, &w).unwrap();
    let f = p.frequency();
    assert!(close(f, 0.6 * (0.16f64 + 0.25 + 0.09).sqrt(), 1e-15));
    assert!(close(f.abs(), s.generator().norm(), 1e-15));
    let period = 2.0 * PI / f.abs();
    assert!((&p.omega_at(period).unwrap() - &w).norm() < 1e-14);
    assert!((&s.omega_at(period).unwrap() - &w).norm() < 1e-14);
}

#[test]
fn paper_section72_corrected_solution_matches_dopri5() {
    let w = biv(&OMEGA_72);
    let j = three_equal_second_moments(KAPPA_72).unwrap();
    let b = body(&j, &w);
    let p = ThreeEqualMoments::new(KAPPA_72, &w).unwrap();
    let s = TwoMomentSolution::new(&b).unwrap();
    let rate = p.frequency().abs().max(s.alpha() * b.momentum().norm());
    let times: Vec<f64> = (1..=8)
        .map(|k| 100.0 * 2.0 * PI / rate * k as f64 / 8.0)
        .collect();
    let reference = dopri_reference(&b, &times);
    let mut worst = (0.0f64, 0.0f64);
    for (&t, (r, l)) in times.iter().zip(&reference) {
        let dopri = b.inertia().apply_inverse(l);
        worst.0 = worst
            .0
            .max((&p.omega_at(t).unwrap() - &dopri).norm() / w.norm());
        worst.1 = worst.1.max(rotor_distance(&s.attitude_at(t).unwrap(), r));
    }
    eprintln!(
        "§7.2 vs Dopri5 over 100 periods: |Δω|/|ω| = {:.2e}, |ΔR| = {:.2e}",
        worst.0, worst.1
    );
    assert!(worst.0 <= 1e-10 && worst.1 <= 1e-10, "{worst:?}");
}

// ---------------------------------------------------------------------------------------
// §7.3 (eqs. 121–134)
// ---------------------------------------------------------------------------------------

#[test]
fn paper_eqs_122_123_omega_12_34_are_constant() {
    let w = biv(&OMEGA_73);
    let j = two_equal_pairs_second_moments(KAPPA_73).unwrap();
    let rate = omega_rate(&j, &w);
    assert!(rate.get(0, 1).abs() < 1e-16 && rate.get(2, 3).abs() < 1e-16);
    let p = TwoEqualPairs::new(KAPPA_73, &w).unwrap();
    assert_eq!(p.constants_c1_c2(), [0.9, 0.4]);
    let s = TwoMomentSolution::new(&body(&j, &w)).unwrap();
    for t in [1.0, 50.0, 777.0] {
        let o = s.omega_at(t).unwrap();
        assert!(close(o.get(0, 1), 0.9, 1e-14) && close(o.get(2, 3), 0.4, 1e-14));
    }
}

#[test]
fn paper_eqs_124_to_126_have_the_coupling_sign_reversed_and_127_is_right() {
    let w = biv(&OMEGA_73);
    let j = two_equal_pairs_second_moments(KAPPA_73).unwrap();
    let rate = omega_rate(&j, &w);
    let printed = printed_124_to_127(KAPPA_73, &OMEGA_73);
    let correct = [
        rate.get(0, 2),
        rate.get(0, 3),
        rate.get(1, 2),
        rate.get(1, 3),
    ];
    eprintln!("(124)-(127): correct (13, 14, 23, 24) {correct:?}, printed {printed:?}");
    // (124), (125), and (126) read as dω₂₃/dt: exactly the negatives.
    for i in 0..3 {
        assert!(close(printed[i], -correct[i], 1e-15), "{i}");
        assert!(correct[i].abs() > 1e-2);
    }
    // (127) agrees.
    assert!(close(printed[3], correct[3], 1e-15));
}

#[test]
fn paper_eq_126_names_omega_34_for_omega_23() {
    // ω₃₄ is constant (eq. 123), yet (126) gives it a nonzero rate; its right-hand side is
    // (minus) that of ω₂₃.
    let w = biv(&OMEGA_73);
    let j = two_equal_pairs_second_moments(KAPPA_73).unwrap();
    let rate = omega_rate(&j, &w);
    let printed = printed_124_to_127(KAPPA_73, &OMEGA_73)[2];
    assert!(rate.get(2, 3).abs() < 1e-16);
    assert!(printed.abs() > 1e-2);
    assert!(close(printed, -rate.get(1, 2), 1e-15));
}

#[test]
fn paper_eqs_128_to_131_constants_from_the_initial_state() {
    let p = TwoEqualPairs::new(KAPPA_73, &biv(&OMEGA_73)).unwrap();
    let c = constants_73(&p);
    let at0 = printed_128_to_131(c, KAPPA_73, 0.0);
    for (x, y) in at0
        .iter()
        .zip([OMEGA_73[1], OMEGA_73[2], OMEGA_73[3], OMEGA_73[4]])
    {
        assert!(close(*x, y, 1e-15));
    }
}

#[test]
fn paper_eqs_128_to_131_run_backwards_in_time() {
    let w = biv(&OMEGA_73);
    let j = two_equal_pairs_second_moments(KAPPA_73).unwrap();
    let s = TwoMomentSolution::new(&body(&j, &w)).unwrap();
    let p = TwoEqualPairs::new(KAPPA_73, &w).unwrap();
    let c = constants_73(&p);
    let pick = |o: &Bivector| [o.get(0, 2), o.get(0, 3), o.get(1, 2), o.get(1, 3)];
    for t in [0.5, 1.0, 7.0, 200.0] {
        let printed = printed_128_to_131(c, KAPPA_73, t);
        let back = pick(&s.omega_at(-t).unwrap());
        let fwd = pick(&s.omega_at(t).unwrap());
        for i in 0..4 {
            assert!(close(printed[i], back[i], 1e-13), "t = {t}");
        }
        if t == 1.0 {
            eprintln!("(128)-(131) at t = 1: printed {printed:?}, correct {fwd:?}");
            assert!(close(printed[0], PRINTED_128_T1, 1e-9));
            assert!(close(fwd[0], CORRECT_128_T1, 1e-9));
        }
    }
    // The printed solution does not satisfy the paper's own (127): residual at t = 0.
    let h = 1e-6;
    let d24 = (printed_128_to_131(c, KAPPA_73, h)[3] - printed_128_to_131(c, KAPPA_73, -h)[3])
        / (2.0 * h);
    let rhs127 = printed_124_to_127(KAPPA_73, &OMEGA_73)[3];
    eprintln!("(127) residual of (131): dω₂₄/dt = {d24}, (127) demands {rhs127}");
    assert!(close(d24, -rhs127, 1e-8));
    assert!(rhs127.abs() > 1e-2);
}

const PRINTED_128_T1: f64 = -0.043_338_546_895_014_32;
const CORRECT_128_T1: f64 = 0.177_261_767_036_474_9;

#[test]
fn paper_eqs_132_to_134_frequencies_are_right_in_magnitude() {
    // Ω = ν(c₁e₁₂ − c₂e₃₄) (the crate's generator) turns the mixed block with the angular
    // frequencies |ν(c₁ − c₂)| and |ν(c₁ + c₂)|: the corrected form built on (134) matches
    // the crate's closed form over 100 periods.
    let w = biv(&OMEGA_73);
    let j = two_equal_pairs_second_moments(KAPPA_73).unwrap();
    let s = TwoMomentSolution::new(&body(&j, &w)).unwrap();
    let p = TwoEqualPairs::new(KAPPA_73, &w).unwrap();
    let nu = frequency_factor(KAPPA_73).unwrap();
    let g = s.generator();
    assert!(close(g.get(0, 1), nu * 0.9, 1e-15) && close(g.get(2, 3), -nu * 0.4, 1e-15));
    let [o1, o2] = p.frequencies();
    assert!(close(o1, nu * 0.5, 1e-15) && close(o2, nu * 1.3, 1e-15));
    let period = 2.0 * PI / o2.abs();
    for k in 1..=10 {
        let t = 10.0 * period * k as f64 + 0.123;
        assert!((&p.omega_at(t).unwrap() - &s.omega_at(t).unwrap()).norm() < 1e-12);
    }
}

#[test]
fn paper_section73_corrected_solution_matches_dopri5() {
    let w = biv(&OMEGA_73);
    let j = two_equal_pairs_second_moments(KAPPA_73).unwrap();
    let b = body(&j, &w);
    let p = TwoEqualPairs::new(KAPPA_73, &w).unwrap();
    let s = TwoMomentSolution::new(&b).unwrap();
    let [o1, o2] = p.frequencies();
    let rate = o1.abs().max(o2.abs()).max(s.alpha() * b.momentum().norm());
    let times: Vec<f64> = (1..=8)
        .map(|k| 100.0 * 2.0 * PI / rate * k as f64 / 8.0)
        .collect();
    let reference = dopri_reference(&b, &times);
    let mut worst = (0.0f64, 0.0f64);
    for (&t, (r, l)) in times.iter().zip(&reference) {
        let dopri = b.inertia().apply_inverse(l);
        worst.0 = worst
            .0
            .max((&p.omega_at(t).unwrap() - &dopri).norm() / w.norm());
        worst.1 = worst.1.max(rotor_distance(&s.attitude_at(t).unwrap(), r));
    }
    eprintln!(
        "§7.3 vs Dopri5 over 100 periods: |Δω|/|ω| = {:.2e}, |ΔR| = {:.2e}",
        worst.0, worst.1
    );
    assert!(worst.0 <= 1e-10 && worst.1 <= 1e-10, "{worst:?}");
}

#[test]
fn paper_closed_forms_reject_bad_input() {
    use rotorflow::dynamics::{DynamicsError, NoClosedFormReason};
    let w = biv(&OMEGA_72);
    assert!(matches!(
        ThreeEqualMoments::new(f64::NAN, &w),
        Err(DynamicsError::NonFiniteArgument { .. })
    ));
    assert_eq!(
        crate::no_closed_form_reasons(TwoEqualPairs::new(0.0, &w)),
        [NoClosedFormReason::NonPositiveKappa { kappa: 0.0 }]
    );
    let w3 = Bivector::from_components(3, &[1.0, 2.0, 3.0]).unwrap();
    assert!(matches!(
        crate::no_closed_form_reasons(TwoEqualPairs::new(2.0, &w3))[..],
        [NoClosedFormReason::WrongDimension {
            expected: 4,
            found: 3,
            ..
        }]
    ));
    let p = ThreeEqualMoments::new(2.0, &w).unwrap();
    assert!(matches!(
        p.omega_at(f64::INFINITY),
        Err(DynamicsError::NonFiniteArgument { .. })
    ));
    let p = TwoEqualPairs::new(2.0, &w).unwrap();
    assert!(matches!(
        p.omega_at(f64::NAN),
        Err(DynamicsError::NonFiniteArgument { .. })
    ));
    // A huge but finite t · ω₁ is still finite: no NaN.
    let huge = p.omega_at(f64::MAX).unwrap();
    assert!(huge.as_slice().iter().all(|x| x.is_finite()));
    // ω_AA = 0: c₄ … c₆ undefined, the motion constant.
    let p = ThreeEqualMoments::new(2.0, &biv(&[0.0, 0.0, 0.8, 0.0, 0.2, -0.6])).unwrap();
    assert!(p.constants_c4_to_c6().is_err());
    assert_eq!(
        p.omega_at(3.0).unwrap(),
        biv(&[0.0, 0.0, 0.8, 0.0, 0.2, -0.6])
    );
}

#[test]
fn paper_eq_110_does_not_follow_from_the_printed_eq_53() {
    // "(53)…(58) can be simplified to" (110)–(115): taken literally with I^{ijij} = ½(Jᵢ + Jⱼ)
    // and J = (1, 1, 1, κ²), eq. (53) gives dω₁₂/dt = −ν(ω₁₃ω₂₃ + ω₁₄ω₂₄) = 0.024 ≠ 0
    // (κ = 2, ω(0) as above). The §7 systems follow from the correct Euler equations
    // (up to the sign errors above), not from the printed (53)–(58).
    let w = OMEGA_72;
    let j = three_equal_second_moments(KAPPA_72).unwrap();
    let i = |a: usize, b: usize| 0.5 * (j[a] + j[b]);
    let (w13, w14, w23, w24) = (w[1], w[2], w[3], w[4]);
    let printed_53 = (-(i(1, 3) - i(0, 1)) * w13 * w23 + (i(0, 2) - i(2, 3)) * w14 * w24) / i(0, 3);
    assert!(close(printed_53, 0.024, 1e-15), "{printed_53}");
    assert!(omega_rate(&j, &biv(&w)).get(0, 1).abs() < 1e-16);
}
