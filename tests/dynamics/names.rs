//! The two attitudes of a body and the attitude error of the invariants.

use super::{attitude_distance, random_bivector, rng, run};
use rotorflow::dynamics::{Attitude, Invariants, RigidBody, Splitting, simulate};
use rotorflow::prelude::*;

/// An ellipsoid whose mass tensor is given in axes turned away from its principal axes, with
/// a given attitude of those axes.
fn tilted_body(n: usize, attitude: Rotor, omega: &Bivector) -> RigidBody {
    let half_axes: Vec<f64> = (0..n).map(|i| 1.0 + 0.7 * i as f64).collect();
    let turn = Rotor::from_plane_angle(n, 0, 1, 0.4)
        .unwrap()
        .compose(&Rotor::from_plane_angle(n, 1, 2, -0.3).unwrap());
    let shape = Body::solid_ellipsoid(&half_axes, 1.0)
        .unwrap()
        .rotated(&turn.to_matrix())
        .unwrap();
    let inertia = InertiaMap::from_body(&shape).unwrap();
    RigidBody::from_body_velocity(inertia, attitude, omega).unwrap()
}

#[test]
fn body_axes_attitude_is_the_attitude_given_and_places_vertices() {
    let mut r = rng(7);
    for n in [3, 4] {
        let start = Rotor::from_rotation_bivector(&random_bivector(&mut r, n, 1.0));
        let body = tilted_body(n, start.clone(), &random_bivector(&mut r, n, 1.0));
        let given = Attitude::from(start.clone());
        // The body's own axes are where the caller put them …
        assert!(attitude_distance(&body.body_axes_attitude(), &given) < 1e-14);
        // … the principal axes are not (the mass tensor was given in turned axes).
        assert!(attitude_distance(body.principal_frame_attitude(), &given) > 0.05);
        // A vertex in body-axis coordinates lands where the rotor the caller gave puts it.
        let vertex = Vector::from_components(&vec![0.5; n]).unwrap();
        let placed = body.body_axes_attitude().rotate_vector(&vertex);
        let expected = start.rotate_vector(&vertex);
        let gap = placed
            .as_slice()
            .iter()
            .zip(expected.as_slice())
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(gap < 1e-14, "N = {n}: {gap:e}");
        // The space-frame momentum uses the principal frame's attitude with the
        // principal-frame momentum: the same physical L whichever frame the caller used.
        let l_space_from_principal = body.space_momentum();
        let l_space_from_axes = body
            .body_axes_attitude()
            .rotate_bivector(&body.principal_frame().rotate_bivector(body.momentum()));
        let diff = (&l_space_from_principal - &l_space_from_axes).norm();
        assert!(
            diff < 1e-13 * l_space_from_principal.norm(),
            "N = {n}: {diff:e} of {:e}",
            l_space_from_principal.norm()
        );
    }
}

#[test]
fn attitude_error_is_a_matrix_error_above_n4() {
    let mut r = rng(8);
    for n in [3, 4, 5, 6] {
        let omega = random_bivector(&mut r, n, 1.0);
        let body = RigidBody::from_body_velocity(
            InertiaMap::from_principal_second_moments(
                &(1..=n).map(|i| i as f64).collect::<Vec<_>>(),
            )
            .unwrap(),
            Attitude::identity(n),
            &omega,
        )
        .unwrap();
        let mut later = body.clone();
        run(&mut later, &mut Splitting::strang(), &Free, 0.01, 200);
        let inv = Invariants::of(&later);
        assert_eq!(
            inv.attitude_error,
            later.principal_frame_attitude().unit_error()
        );
        // A rotor for N ≤ 4, a matrix above: the error is the group's, whichever it is.
        assert_eq!(
            later.principal_frame_attitude().as_rotor().is_some(),
            n <= Attitude::ROTOR_MAX_DIM
        );
        let traj = simulate(
            &body,
            &mut Splitting::strang(),
            &Free,
            0.01,
            &[0.0, 1.0, 2.0],
        )
        .unwrap();
        let d = traj.drift();
        assert!(
            d.attitude > 0.0 && d.attitude < 1e-13,
            "N = {n}: {:e}",
            d.attitude
        );
    }
}
