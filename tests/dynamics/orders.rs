//! Measured convergence orders: error at a fixed time against a fine reference, as the step
//! halves.

use crate::{random_body, rng, run};
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::{Integrator, RigidBody, Rkmk4, Splitting};

/// Error of (L, R) at time `t_end` with step `h`, against `reference`.
fn error(
    start: &RigidBody,
    integ: &mut dyn Integrator,
    t_end: f64,
    h: f64,
    reference: &RigidBody,
) -> f64 {
    let mut b = start.clone();
    let steps = (t_end / h).round() as usize;
    run(&mut b, integ, &Free, h, steps);
    let dl = (b.momentum() - reference.momentum()).max_abs();
    let dr = b
        .attitude()
        .raw_coefficients()
        .iter()
        .zip(reference.attitude().raw_coefficients())
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    dl.max(dr)
}

fn measured_order(integ: &mut dyn Integrator, hs: [f64; 3]) -> f64 {
    let mut r = rng(301);
    let start = random_body(&mut r, 4);
    let t_end = 2.0;
    let mut reference = start.clone();
    run(
        &mut reference,
        &mut Splitting::yoshida4(),
        &Free,
        1e-4,
        20_000,
    );
    let e: Vec<f64> = hs
        .iter()
        .map(|&h| error(&start, integ, t_end, h, &reference))
        .collect();
    // least-squares slope of log e against log h over the three points
    let xs: Vec<f64> = hs.iter().map(|h| h.ln()).collect();
    let ys: Vec<f64> = e.iter().map(|x| x.ln()).collect();
    let (mx, my) = (xs.iter().sum::<f64>() / 3.0, ys.iter().sum::<f64>() / 3.0);
    let num: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let den: f64 = xs.iter().map(|x| (x - mx).powi(2)).sum();
    num / den
}

#[test]
fn rk4_is_fourth_order() {
    let p = measured_order(&mut Rkmk4, [0.04, 0.02, 0.01]);
    assert!((p - 4.0).abs() < 0.15, "measured order {p}");
}

#[test]
fn strang_is_second_order() {
    let p = measured_order(&mut Splitting::strang(), [0.02, 0.01, 0.005]);
    assert!((p - 2.0).abs() < 0.1, "measured order {p}");
}

#[test]
fn yoshida_is_fourth_order() {
    let p = measured_order(&mut Splitting::yoshida4(), [0.04, 0.02, 0.01]);
    assert!((p - 4.0).abs() < 0.15, "measured order {p}");
}

#[test]
fn implicit_midpoint_is_second_order() {
    let p = measured_order(
        &mut rotorflow::dynamics::Midpoint::default(),
        [0.02, 0.01, 0.005],
    );
    assert!((p - 2.0).abs() < 0.1, "measured order {p}");
}
