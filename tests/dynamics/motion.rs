//! Trajectories, kinematics (eqs. 18–21) and stability of steady rotations.

use crate::random_bivector;
use rotorflow::algebra::Vector;
use rotorflow::dynamics::kinematics::{
    centrifugal_acceleration, coriolis_acceleration, point_velocity,
};
use rotorflow::dynamics::stability::{growth_rate, transverse_modes};
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::trajectory::even_times;
use rotorflow::dynamics::{DynamicsError, RigidBody, Splitting, simulate};
use rotorflow::prelude::*;

#[test]
fn growth_rates_match_the_reference_values_in_4d() {
    // J = (1, 2, 3, 4), L_pq = 1: λ(13) = 0.064550, λ(14) = 0.066667, λ(24) = 0.028172;
    // planes 12, 23, 34 are linearly stable. The values are the eigenvalues of the Jacobian
    // of the 4D Euler flow at the steady rotation, computed independently of the formula.
    let j = [1.0, 2.0, 3.0, 4.0];
    let rate = |p: usize, q: usize| growth_rate(&j, p, q, 1.0 / (j[p] + j[q]));
    assert!((rate(0, 2) - 0.064550).abs() < 1e-6);
    assert!((rate(0, 3) - 0.066667).abs() < 1e-6);
    assert!((rate(1, 3) - 0.028172).abs() < 1e-6);
    for (p, q) in [(0, 1), (1, 2), (2, 3)] {
        assert_eq!(rate(p, q), 0.0, "plane ({p},{q})");
    }
    // 3D: only the intermediate axis (plane e1e3 for J1 < J2 < J3) is unstable
    let j3 = [1.0, 2.0, 3.0];
    assert!(growth_rate(&j3, 0, 2, 1.0) > 0.0);
    assert_eq!(growth_rate(&j3, 0, 1, 1.0), 0.0);
    assert_eq!(growth_rate(&j3, 1, 2, 1.0), 0.0);
    assert_eq!(transverse_modes(&j, 0, 2, 0.25).len(), 2);
}

/// Measures the growth rate of a perturbed steady rotation in plane (p, q) by simulation.
fn measured_growth(j: &[f64], p: usize, q: usize) -> (f64, f64) {
    let n = j.len();
    let inertia = InertiaMap::from_principal_second_moments(j).unwrap();
    let mut l = Bivector::zero(n);
    l.set(p, q, 1.0);
    let mut perturbed = l.clone();
    for r in (0..n).filter(|&r| r != p && r != q) {
        perturbed.set(p, r, 1e-10);
        perturbed.set(q, r, 1e-10);
    }
    let body = RigidBody::from_body_momentum(inertia, Rotor::identity(n), &perturbed).unwrap();
    let expected = growth_rate(j, p, q, 1.0 / (j[p] + j[q]));
    let t_end = 12.0 / expected;
    let times = [0.6 * t_end, t_end];
    let traj = simulate(&body, &mut Splitting::yoshida4(), &Free, 0.02, &times).unwrap();
    let off = |m: &Bivector| (m - &(l.clone() * m.get(p, q))).norm();
    let (a, b) = (&traj.samples()[0], &traj.samples()[1]);
    let slope = (off(&b.momentum).ln() - off(&a.momentum).ln()) / (b.time - a.time);
    (slope, expected)
}

#[test]
fn intermediate_axis_flip_grows_at_the_predicted_rate() {
    // 3D (the Dzhanibekov effect) and its 4D analogues, within 1 %.
    for (j, p, q) in [
        (vec![1.0, 2.0, 3.0], 0, 2),
        (vec![1.0, 2.0, 3.0, 4.0], 0, 2),
        (vec![1.0, 2.0, 3.0, 4.0], 0, 3),
    ] {
        let (measured, expected) = measured_growth(&j, p, q);
        assert!(
            (measured / expected - 1.0).abs() < 0.01,
            "J = {j:?}, plane ({p},{q}): measured {measured}, predicted {expected}"
        );
    }
}

#[test]
fn trajectory_samples_and_drift() {
    let mut r = crate::rng(601);
    let body = crate::random_body(&mut r, 4);
    let times = even_times(10.0, 11);
    let traj = simulate(&body, &mut Splitting::strang(), &Free, 0.01, &times).unwrap();
    assert_eq!(traj.samples().len(), 11);
    assert_eq!(traj.samples()[0].momentum, *body.momentum());
    assert!((traj.samples()[10].time - 10.0).abs() < 1e-12);
    assert_eq!(traj.steps(), 1000);
    assert!(traj.drift().casimirs < 1e-13);
    // Strang: |ΔT|/T = O(h²), measured 4.1e-6 = 0.041·h²; bound 3× that.
    assert!(traj.drift().energy < 1.3e-5, "{:e}", traj.drift().energy);
    // a sample time between steps is hit exactly (the step is shortened)
    let t = simulate(&body, &mut Splitting::strang(), &Free, 0.3, &[0.0, 0.45]).unwrap();
    assert_eq!(t.samples()[1].time, 0.45);
    assert!(matches!(
        simulate(&body, &mut Splitting::strang(), &Free, 0.01, &[1.0, 0.5]),
        Err(DynamicsError::InvalidSampling { .. })
    ));
    assert!(matches!(
        simulate(&body, &mut Splitting::strang(), &Free, 0.0, &[1.0]),
        Err(DynamicsError::InvalidSampling { .. })
    ));
}

#[test]
fn kinematics_in_3d_are_the_textbook_cross_products() {
    let w = Bivector::from_components(3, &[0.3, -0.7, 1.1]).unwrap();
    let omega = nalgebra::Vector3::new(w.get(1, 2), -w.get(0, 2), w.get(0, 1));
    let y = Vector::from_components(&[0.4, -1.2, 0.5]).unwrap();
    let v = Vector::from_components(&[2.0, 0.1, -0.3]).unwrap();
    let (yn, vn) = (
        nalgebra::Vector3::new(y[0], y[1], y[2]),
        nalgebra::Vector3::new(v[0], v[1], v[2]),
    );
    let vel = point_velocity(&w, &y);
    let cor = coriolis_acceleration(&w, &v);
    let cf = centrifugal_acceleration(&w, &y);
    let (evel, ecor, ecf) = (
        omega.cross(&yn),
        -2.0 * omega.cross(&vn),
        -omega.cross(&omega.cross(&yn)),
    );
    for k in 0..3 {
        assert!((vel[k] - evel[k]).abs() < 1e-15);
        assert!((cor[k] - ecor[k]).abs() < 1e-15);
        assert!((cf[k] - ecf[k]).abs() < 1e-15);
    }
}

#[test]
fn a_free_particle_seen_from_a_rotating_frame_feels_coriolis_and_centrifugal() {
    // x_s(t) = x₀ + v t; the frame turns with constant ω (N = 4, double rotation); the
    // rotating-frame coordinates y(t) = R̃ x_s R must satisfy ÿ = −2ẏ⌋ω − (y⌋ω)⌋ω.
    let n = 4;
    let mut r = crate::rng(602);
    let w = random_bivector(&mut r, n, 1.0);
    let x0 = Vector::from_components(&[0.3, -0.2, 0.9, 0.1]).unwrap();
    let v = Vector::from_components(&[0.5, 0.4, -0.1, 0.2]).unwrap();
    let y_at = |t: f64| {
        let rot = Rotor::from_rotation_bivector(&(&w * t));
        rot.reverse().rotate_vector(&(&x0 + &(&v * t)))
    };
    let (t, h) = (0.7, 1e-4);
    let (ym, y0, yp) = (y_at(t - h), y_at(t), y_at(t + h));
    let ydot = (&yp - &ym) * (0.5 / h);
    let yddot = (&(&yp - &(&y0 * 2.0)) + &ym) * (1.0 / (h * h));
    let predicted = coriolis_acceleration(&w, &ydot) + centrifugal_acceleration(&w, &y0);
    for k in 0..n {
        assert!(
            (yddot[k] - predicted[k]).abs() < 1e-6,
            "{k}: {} vs {}",
            yddot[k],
            predicted[k]
        );
    }
}
