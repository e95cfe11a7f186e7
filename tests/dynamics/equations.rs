//! The equations themselves: 3D signs pinned against the classical Euler equations, the
//! matrix formulation for N = 4, 5, 8, and the principal-frame component form.

use crate::{random_bivector, rng};
use nalgebra::DMatrix;
use rotorflow::dynamics::RigidBody;
use rotorflow::prelude::*;

#[test]
fn euler_3d_matches_classical() {
    // The Conventions chapter of the book: Ω = (ω23, −ω13, ω12), I₁ = J₂ + J₃ (and cyclic); the classical equations
    // I₁ dΩ₁/dt = (I₂ − I₃) Ω₂ Ω₃ and cyclic must equal dω/dt = I⁻¹(ω × L).
    let j = [0.7, 1.1, 1.9];
    let inertia = InertiaMap::from_principal_second_moments(&j).unwrap();
    let (i1, i2, i3) = (j[1] + j[2], j[0] + j[2], j[0] + j[1]);
    let w = Bivector::from_components(3, &[0.4, -1.3, 0.9]).unwrap();
    let body = RigidBody::from_body_velocity(inertia.clone(), Rotor::identity(3), &w).unwrap();
    let l = body.momentum();
    let dw = inertia.apply_inverse(&body.omega().commutator(l));
    let omega = [w.get(1, 2), -w.get(0, 2), w.get(0, 1)];
    let domega = [dw.get(1, 2), -dw.get(0, 2), dw.get(0, 1)];
    let classical = [
        (i2 - i3) * omega[1] * omega[2] / i1,
        (i3 - i1) * omega[2] * omega[0] / i2,
        (i1 - i2) * omega[0] * omega[1] / i3,
    ];
    for k in 0..3 {
        assert!(
            (domega[k] - classical[k]).abs() < 1e-14,
            "component {k}: {} vs {}",
            domega[k],
            classical[k]
        );
    }
}

#[test]
fn right_hand_side_equals_the_matrix_formulation() {
    // [ω × L] = [ω][L] − [L][ω] and the component form (Jᵢ + Jⱼ) dωᵢⱼ/dt = (Jⱼ − Jᵢ)([ω]²)ᵢⱼ.
    let mut r = rng(201);
    for n in [4, 5, 8] {
        let j: Vec<f64> = (0..n).map(|k| 0.5 + 0.3 * k as f64).collect();
        let inertia = InertiaMap::from_principal_second_moments(&j).unwrap();
        let w = random_bivector(&mut r, n, 1.0);
        let l = inertia.apply(&w);
        let rate = w.commutator(&l);
        let (mw, ml) = (w.to_skew_matrix(), l.to_skew_matrix());
        let m: DMatrix<f64> = &mw * &ml - &ml * &mw;
        assert!((rate.to_skew_matrix() - m).abs().max() < 1e-13, "n={n}");
        let dw = inertia.apply_inverse(&rate);
        let w2 = &mw * &mw;
        for (a, b) in rotorflow::algebra::pairs(n) {
            let lhs = (j[a] + j[b]) * dw.get(a, b);
            let rhs = (j[b] - j[a]) * w2[(a, b)];
            assert!((lhs - rhs).abs() < 1e-13, "n={n} ({a},{b}): {lhs} vs {rhs}");
        }
    }
}

#[test]
fn bodies_in_general_axes_move_to_their_principal_frame() {
    let mut r = rng(202);
    let n = 4;
    let a = DMatrix::from_fn(n, n, |_, _| rand::Rng::gen_range(&mut r, -1.0..1.0));
    let j = &a * a.transpose() + DMatrix::identity(n, n);
    let inertia = InertiaMap::from_mass_tensor(&j).unwrap();
    let w = random_bivector(&mut r, n, 1.0);
    let body = RigidBody::from_body_velocity(inertia.clone(), Rotor::identity(n), &w).unwrap();
    assert!(body.inertia().is_principal());
    // same physics: space momentum and energy agree with the map in the body's own axes
    let l_own = inertia.apply(&w);
    assert!((&body.space_momentum() - &l_own).max_abs() < 1e-12);
    assert!((body.energy() - inertia.kinetic_energy(&w)).abs() < 1e-12);
    let own = body.body_axes_attitude();
    assert!(own.unit_error() < 1e-14);
    assert!((&own.rotate_bivector(&w) - &body.space_omega()).max_abs() < 1e-12);
}
