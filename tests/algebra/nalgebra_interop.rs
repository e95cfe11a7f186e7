//! Interop with nalgebra: quaternions and rotation matrices in 3D (sign conventions pinned),
//! vectors and matrices in any N.

use crate::assert_close;
use crate::support::*;
use nalgebra::{DMatrix, DVector, Rotation3, SVector, Unit, UnitQuaternion, Vector3};
use rotorflow::prelude::*;

#[test]
fn quaternion_and_rotor_give_the_same_rotation() {
    let mut r = rng(41);
    for _ in 0..50 {
        let axis = Unit::new_normalize(Vector3::new(
            rand::Rng::gen_range(&mut r, -1.0..1.0),
            rand::Rng::gen_range(&mut r, -1.0..1.0),
            rand::Rng::gen_range(&mut r, -1.0..1.0),
        ));
        let angle = rand::Rng::gen_range(&mut r, -6.0..6.0);
        let q = UnitQuaternion::from_axis_angle(&axis, angle);
        let rot = Rotor::from(q);
        let m = q.to_rotation_matrix();
        let qr = rot.to_matrix();
        for i in 0..3 {
            for j in 0..3 {
                assert_close!(qr[(i, j)], m[(i, j)], 1e-15);
            }
        }
        // back to a quaternion: identical (same sign)
        let q2 = UnitQuaternion::try_from(&rot).unwrap();
        assert!((q2.coords - q.coords).norm() < 1e-15);
        // Rotation3 round trip
        let rot3 = Rotation3::try_from(&rot).unwrap();
        assert!((rot3.matrix() - m.matrix()).abs().max() < 1e-15);
        assert!(rotor_distance_up_to_sign(&Rotor::from(m), &rot) < 1e-15);
    }
}

#[test]
fn right_hand_rule_pins_the_signs() {
    // A positive rotation about e3 (right hand) turns e1 toward e2: the plane e12, and the
    // rotor cos(θ/2) − sin(θ/2) e12.
    let theta = 0.8;
    let q = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), theta);
    let rot = Rotor::from(q);
    assert_close!(rot.scalar(), (theta / 2.0).cos(), 1e-15);
    assert_close!(rot.coefficient(0b011), -(theta / 2.0).sin(), 1e-15);
    assert_eq!(rot, Rotor::from_plane_angle(3, 0, 1, theta).unwrap());
    // about e1: turns e2 toward e3 (plane e23); about e2: turns e3 toward e1 (plane e31)
    let qx = Rotor::from(UnitQuaternion::from_axis_angle(&Vector3::x_axis(), theta));
    assert!(rotor_distance(&qx, &Rotor::from_plane_angle(3, 1, 2, theta).unwrap()) < 1e-16);
    let qy = Rotor::from(UnitQuaternion::from_axis_angle(&Vector3::y_axis(), theta));
    assert!(rotor_distance(&qy, &Rotor::from_plane_angle(3, 2, 0, theta).unwrap()) < 1e-16);
    // the angular-velocity dual of the book's Conventions chapter: Ω = (ω23, −ω13, ω12)
    let w = Bivector::from_components(3, &[0.3, -0.2, 0.7]).unwrap();
    let omega = Vector3::new(w.get(1, 2), -w.get(0, 2), w.get(0, 1));
    let x = Vector3::new(0.5, -1.0, 2.0);
    let v_classic = omega.cross(&x);
    let v_ga = Vector::from(SVector::<f64, 3>::from(x)).left_contract(&w);
    for i in 0..3 {
        assert_close!(v_ga[i], v_classic[i], 1e-15);
    }
    // and the rotor of the rotation vector Ω·t is the quaternion exp
    let t = 0.9;
    let rot = Rotor::from_rotation_bivector(&(&w * t));
    let q = UnitQuaternion::from_scaled_axis(omega * t);
    assert!(rotor_distance(&rot, &Rotor::from(q)) < 1e-15);
}

#[test]
fn vectors_and_matrices_convert_both_ways() {
    let v = DVector::from_vec(vec![1.0, 2.0, 3.0, 4.0]);
    let x = Vector::from(&v);
    assert_eq!(DVector::from(&x), v);
    assert_eq!(
        Vector::from(SVector::<f64, 2>::new(1.0, 2.0)).as_slice(),
        &[1.0, 2.0]
    );
    let b = Bivector::from_components(3, &[1.0, 2.0, 3.0]).unwrap();
    let m = DMatrix::from(&b);
    assert_eq!(m[(0, 1)], 1.0);
    assert_eq!(m[(1, 0)], -1.0);
    assert_eq!(m[(1, 2)], 3.0);
    assert_eq!(Bivector::try_from(&m).unwrap(), b);
    let mut r = rng(42);
    let rot = random_rotor(&mut r, 5);
    let q = DMatrix::from(&rot);
    assert!(rotor_distance_up_to_sign(&Rotor::try_from(&q).unwrap(), &rot) < 1e-13);
    let s: nalgebra::SMatrix<f64, 5, 5> = nalgebra::SMatrix::from_fn(|i, j| q[(i, j)]);
    assert!(rotor_distance_up_to_sign(&Rotor::try_from(&s).unwrap(), &rot) < 1e-13);
    assert!(UnitQuaternion::try_from(&rot).is_err());
}

#[test]
fn approx_traits_compare_coefficients() {
    use approx::{assert_relative_eq, relative_ne};
    let a = Bivector::from_components(3, &[1.0, 2.0, 3.0]).unwrap();
    let b = &a * (1.0 + 1e-15);
    assert_relative_eq!(a, b, max_relative = 1e-14);
    assert!(relative_ne!(a, Bivector::zero(4)));
    let r = Rotor::from_plane_angle(4, 0, 1, 0.3).unwrap();
    assert_relative_eq!(r, r.normalize(), epsilon = 1e-15);
    let x = Vector::basis(3, 1);
    assert_relative_eq!(x.clone(), x, epsilon = 0.0);
}

#[cfg(feature = "serde")]
#[test]
fn serde_round_trips_and_validates() {
    let b = Bivector::from_components(4, &[0.5, 0.0, 0.0, 0.0, 0.0, -1.25]).unwrap();
    let s = serde_json::to_string(&b).unwrap();
    assert_eq!(serde_json::from_str::<Bivector>(&s).unwrap(), b);
    assert!(serde_json::from_str::<Bivector>(r#"{"dim":4,"components":[1,2]}"#).is_err());
    let r = Rotor::from_rotation_bivector(&b);
    let s = serde_json::to_string(&r).unwrap();
    let back: Rotor = serde_json::from_str(&s).unwrap();
    assert!(rotor_distance(&back, &r) == 0.0);
    // a scaled "rotor" is rejected
    let bad = serde_json::to_string(&(r.to_multivector() * 2.0)).unwrap();
    let v: serde_json::Value = serde_json::from_str(&bad).unwrap();
    let coeffs = v["coefficients"].clone();
    let txt = format!(r#"{{"dim":4,"components":{coeffs}}}"#);
    assert!(serde_json::from_str::<Rotor>(&txt).is_err());
    let m = Multivector::scalar(Signature::new(3, 0, 1).unwrap(), 2.0);
    let s = serde_json::to_string(&m).unwrap();
    assert_eq!(serde_json::from_str::<Multivector>(&s).unwrap(), m);
    let v = Vector::basis(3, 2);
    assert_eq!(
        serde_json::from_str::<Vector>(&serde_json::to_string(&v).unwrap()).unwrap(),
        v
    );
}
