//! The API contracts of the inertia layer: the names say which moments they take (second
//! moments Jᵢ or 3D moments of inertia Iᵢ), bodies speak rotors and vectors, one tolerance
//! policy across `Body` and `InertiaMap`, and closed boundary meshes refuse flipped facets.

use crate::common::{max_abs_diff, random_rotation, rng};
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;
use rotorflow::algebra::{Bivector, Rotor, Vector};
use rotorflow::inertia::tolerance::{MASS_TENSOR_TOLERANCE, SINGULAR_PLANE_TOLERANCE};
use rotorflow::inertia::{Body, InertiaError, InertiaMap};

fn v(x: &[f64]) -> DVector<f64> {
    DVector::from_column_slice(x)
}

/// The solid cuboid with half-sides (0.5, 1, 1.5) and mass 12: by hand, Jᵢ = m aᵢ²/3 =
/// 4 aᵢ² = (1, 4, 9), and the moments of inertia I₁ = J₂ + J₃ = 13, I₂ = 10, I₃ = 5
/// (the textbook m(b² + c²)/12 with full sides (1, 2, 3): 12·(4 + 9)/12 = 13).
fn cuboid_12() -> Body {
    Body::solid_cuboid(&[0.5, 1.0, 1.5], 1.0)
        .unwrap()
        .with_mass(12.0)
        .unwrap()
}

#[test]
fn solid_cuboid_has_second_moments_1_4_9_and_moments_of_inertia_13_10_5() {
    let body = cuboid_12();
    assert!((body.mass() - 12.0).abs() < 1e-13);
    let j = body.principal_second_moments();
    for (got, want) in j.iter().zip([1.0, 4.0, 9.0]) {
        assert!((got - want).abs() < 1e-13, "J = {j}");
    }
    let i = body.principal_moments_of_inertia_3d().unwrap();
    for (got, want) in i.iter().zip([13.0, 10.0, 5.0]) {
        assert!((got - want).abs() < 1e-13, "I = {i:?}");
    }
    // Only 3D bodies have three classical moments of inertia.
    assert!(
        Body::solid_ball(4, 1.0, 1.0)
            .unwrap()
            .principal_moments_of_inertia_3d()
            .is_none()
    );
}

#[test]
fn moments_of_inertia_13_10_5_give_the_cuboid_map() {
    let body = cuboid_12();
    let from_body = InertiaMap::from_body(&body).unwrap();
    let from_i = InertiaMap::from_principal_moments_of_inertia_3d([13.0, 10.0, 5.0]).unwrap();
    let from_j = InertiaMap::from_principal_second_moments(&[1.0, 4.0, 9.0]).unwrap();
    assert!(from_i.is_physical());
    assert_eq!(from_i, from_j);
    assert!(max_abs_diff(&from_i.to_matrix(), &from_body.to_matrix()) < 1e-12);
    // The plane moments are the moments of inertia: e₁∧e₂ ↔ e₃ (I₃ = 5), e₁∧e₃ ↔ e₂
    // (I₂ = 10), e₂∧e₃ ↔ e₁ (I₁ = 13).
    let planes = from_i.diagonal_plane_moments().unwrap();
    assert_eq!(planes, &[5.0, 10.0, 13.0]);
    // The classical constructor agrees for physical moments.
    let classical = InertiaMap::from_classical_3d([13.0, 10.0, 5.0]).unwrap();
    assert!(max_abs_diff(&classical.to_matrix(), &from_i.to_matrix()) < 1e-12);
    // The trap the names avoid: (13, 10, 5) read as second moments is another body.
    let wrong = InertiaMap::from_principal_second_moments(&[13.0, 10.0, 5.0]).unwrap();
    assert!(max_abs_diff(&wrong.to_matrix(), &from_body.to_matrix()) > 1.0);
}

#[test]
fn moments_of_inertia_3d_refuse_what_no_body_has() {
    // The common 3D test body I = (2, 1, 2/3) violates I₁ ≤ I₂ + I₃ (J₁ = −1/6).
    let test_body = [2.0, 1.0, 2.0 / 3.0];
    match InertiaMap::from_principal_moments_of_inertia_3d(test_body) {
        Err(e @ InertiaError::NotPhysical3d { index: 0, .. }) => {
            let message = e.to_string();
            assert!(message.contains("from_classical_3d"), "{message}");
            assert!(message.contains("from_plane_moments"), "{message}");
        }
        other => panic!("{other:?}"),
    }
    // It stays expressible as a general map.
    let general = InertiaMap::from_classical_3d(test_body).unwrap();
    assert!(!general.is_physical());
    assert_eq!(
        InertiaMap::from_plane_moments(&[2.0 / 3.0, 1.0, 2.0])
            .unwrap()
            .to_matrix(),
        general.to_matrix()
    );
    for bad in [[0.0, 1.0, 1.0], [-1.0, 1.0, 1.0]] {
        assert!(matches!(
            InertiaMap::from_principal_moments_of_inertia_3d(bad),
            Err(InertiaError::NotPositive { index: Some(0), .. })
        ));
    }
    assert!(matches!(
        InertiaMap::from_principal_moments_of_inertia_3d([f64::NAN, 1.0, 1.0]),
        Err(InertiaError::NonFinite { .. })
    ));
    // The equality case is a flat plate (J₃ = 0): physical, invertible.
    let plate = InertiaMap::from_principal_moments_of_inertia_3d([1.0, 2.0, 3.0]).unwrap();
    assert_eq!(plate.principal_second_moments().unwrap(), &[2.0, 1.0, 0.0]);
    // A rod (I₁ = 0, J₂ = J₃ = 0) has a singular map: refused by its zero moment.
    assert!(matches!(
        InertiaMap::from_principal_moments_of_inertia_3d([0.0, 1.0, 1.0]),
        Err(InertiaError::NotPositive { index: Some(0), .. })
    ));
    // Just inside the triangle inequality: a thin plate, J₃ = 5e-4.
    let thin = InertiaMap::from_principal_moments_of_inertia_3d([1.0, 1.0, 2.0 - 1e-3]).unwrap();
    assert!((thin.principal_second_moments().unwrap()[2] - 5e-4).abs() < 1e-15);
    // Just outside: refused, naming I₃.
    assert!(matches!(
        InertiaMap::from_principal_moments_of_inertia_3d([1.0, 1.0, 2.0 + 1e-6]),
        Err(InertiaError::NotPhysical3d { index: 2, .. })
    ));
}

#[test]
fn body_takes_rotors_and_vectors_like_matrices() {
    let body = Body::solid_cuboid(&[1.0, 2.0, 3.0], 0.7)
        .unwrap()
        .translated(&v(&[0.3, -0.2, 0.5]))
        .unwrap();
    let rotor = Bivector::from_components(3, &[0.3, -0.7, 1.1])
        .unwrap()
        .exp();
    let offset = Vector::from_components(&[1.0, 2.0, -3.0]).unwrap();
    let by_rotor = body.placed_by(&rotor, &offset).unwrap();
    let by_matrix = body
        .placed(&rotor.to_matrix(), &DVector::from(&offset))
        .unwrap();
    assert!(max_abs_diff(by_rotor.mass_tensor(), by_matrix.mass_tensor()) < 1e-13);
    assert!((by_rotor.center_of_mass() - by_matrix.center_of_mass()).amax() < 1e-14);
    // The centre of mass as a Vector is R c R̃ + offset.
    let expected = rotor.rotate_vector(&body.center_of_mass_vector());
    for k in 0..3 {
        let want = expected.as_slice()[k] + offset.as_slice()[k];
        assert!((by_rotor.center_of_mass_vector().as_slice()[k] - want).abs() < 1e-14);
    }
    // The principal rotor turns the body's axes to its principal axes.
    let turned = body.rotated_by(&rotor).unwrap();
    let rp = turned.principal_rotor().unwrap();
    let (moments, axes) = turned.principal_frame();
    assert!(max_abs_diff(&rp.to_matrix(), &axes) < 1e-12);
    let back = turned.rotated_by(&rp.reverse()).unwrap();
    assert!(max_abs_diff(back.mass_tensor(), &DMatrix::from_diagonal(&moments)) < 1e-12);
    assert!(matches!(
        body.rotated_by(&Rotor::identity(4)),
        Err(InertiaError::DimensionMismatch {
            expected: 3,
            found: 4,
            ..
        })
    ));
}

#[test]
fn rotation_tolerance_is_the_rotors() {
    // The same matrix is a rotation for Body::rotated exactly when Rotor::from_matrix takes it.
    let body = Body::solid_cuboid(&[1.0, 2.0, 3.0], 1.0).unwrap();
    let mut g = rng(11);
    let q = random_rotation(3, &mut g);
    let q = if q.determinant() < 0.0 { -q } else { q };
    for scale in [0.0, 1e-12, 1e-10, 1e-9, 3e-9, 1e-8, 1e-6] {
        let mut perturbed = q.clone();
        perturbed[(0, 0)] += scale;
        assert_eq!(
            body.rotated(&perturbed).is_ok(),
            Rotor::from_matrix(&perturbed).is_ok(),
            "perturbation {scale:e}"
        );
    }
}

#[test]
fn symmetry_and_negative_moment_checks_agree_between_body_and_map() {
    let c = v(&[0.0, 0.0, 0.0]);
    for (asym, neg) in [
        (0.0, 0.0),
        (1e-11, 0.0),
        (1e-9, 0.0),
        (0.0, -1e-10),
        (0.0, -1e-8),
        (0.0, -MASS_TENSOR_TOLERANCE * 0.5),
        (0.0, -MASS_TENSOR_TOLERANCE * 2.0),
    ] {
        let mut j = DMatrix::from_diagonal(&v(&[neg, 1.0, 2.0]));
        j[(1, 2)] += asym;
        let body = Body::from_mass_properties(1.0, c.clone(), j.clone(), None);
        let map = InertiaMap::from_mass_tensor(&j);
        assert_eq!(
            body.is_ok(),
            map.is_ok(),
            "asymmetry {asym:e}, moment {neg:e}: {body:?} vs {map:?}"
        );
    }
}

/// A random body: point masses in N dimensions, squeezed along `flat` random directions by
/// `squeeze` (so that nearly flat bodies reach the singular-plane tolerance), rotated.
fn random_body(n: usize, points: usize, flat: usize, squeeze: f64, seed: u64) -> Body {
    let mut g = rng(seed);
    let q = random_rotation(n, &mut g);
    let masses: Vec<f64> = (0..points)
        .map(|_| 0.1 + crate::common::uniform(&mut g, 0.0, 2.0))
        .collect();
    let positions: Vec<DVector<f64>> = (0..points)
        .map(|_| {
            let mut x = crate::common::random_vector(n, &mut g);
            for k in 0..flat.min(n) {
                x[k] *= squeeze;
            }
            &q * x
        })
        .collect();
    Body::point_masses(&masses, &positions).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// A body accepted by `Body` is accepted by `InertiaMap::from_body` exactly when its map is
    /// invertible by `Body`'s own check with the map's tolerance; the two name the same plane.
    #[test]
    fn body_and_map_agree_on_every_body(
        n in 2usize..=6,
        extra in 0usize..6,
        flat in 0usize..=3,
        exponent in -9.0f64..0.0,
        seed in any::<u64>(),
    ) {
        // Squeezes from 1e-9 down to 1e-0 of the extent: the plane moment of two squeezed
        // directions is ~squeeze² of the largest, around SINGULAR_PLANE_TOLERANCE (1.4e-14)
        // for squeeze ~1e-7.
        let squeeze = 10f64.powf(exponent);
        let body = random_body(n, n + 1 + extra, flat, squeeze, seed);
        let by_body = body.check_inertia_invertible(SINGULAR_PLANE_TOLERANCE);
        let by_map = InertiaMap::from_body(&body);
        prop_assert_eq!(by_body.is_ok(), by_map.is_ok(), "{:?} vs {:?}", by_body, by_map.as_ref().err());
        prop_assert_eq!(body.check_inertia_map().is_ok(), by_map.is_ok());
        if let (Err(InertiaError::DegeneratePlane { plane: p1, .. }),
                Err(InertiaError::DegeneratePlane { plane: p2, .. })) = (&by_body, &by_map) {
            prop_assert_eq!(p1, p2);
        }
    }
}

#[test]
fn nearly_flat_bodies_straddle_the_singular_plane_tolerance() {
    // The property above must see both answers: bodies squeezed in two directions by 1e-9
    // have a singular map, bodies squeezed by 1e-3 an invertible one.
    let flat = random_body(4, 9, 2, 1e-9, 1);
    assert!(matches!(
        InertiaMap::from_body(&flat),
        Err(InertiaError::DegeneratePlane { .. })
    ));
    assert!(flat.check_inertia_map().is_err());
    let thin = random_body(4, 9, 2, 1e-3, 1);
    assert!(InertiaMap::from_body(&thin).is_ok());
    assert!(thin.check_inertia_map().is_ok());
}

/// The unit cube [0, 1]³ as 12 outward-oriented triangles.
fn cube_facets() -> (Vec<DVector<f64>>, Vec<[usize; 3]>) {
    let vertices: Vec<DVector<f64>> = (0..8)
        .map(|k| v(&[(k & 1) as f64, ((k >> 1) & 1) as f64, ((k >> 2) & 1) as f64]))
        .collect();
    // Faces as quads (counter-clockwise seen from outside), split into two triangles each.
    let quads = [
        [0, 2, 3, 1], // z = 0
        [4, 5, 7, 6], // z = 1
        [0, 1, 5, 4], // y = 0
        [2, 6, 7, 3], // y = 1
        [0, 4, 6, 2], // x = 0
        [1, 3, 7, 5], // x = 1
    ];
    let facets = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    (vertices, facets)
}

#[test]
fn closed_boundary_mesh_of_the_cube_is_exact() {
    let (vertices, facets) = cube_facets();
    let body = Body::closed_boundary_mesh(&vertices, &facets, 1.0).unwrap();
    assert!((body.volume().unwrap() - 1.0).abs() < 1e-14);
    let exact = Body::solid_cuboid(&[0.5, 0.5, 0.5], 1.0).unwrap();
    assert!(max_abs_diff(body.mass_tensor(), exact.mass_tensor()) < 1e-14);
}

#[test]
fn a_flipped_facet_is_refused_by_name() {
    // Without the orientation check the cube with one flipped triangle came out with the
    // wrong volume (the facet's cone is subtracted instead of added).
    let (vertices, facets) = cube_facets();
    for flipped in 0..facets.len() {
        let mut bad = facets.clone();
        bad[flipped].swap(1, 2);
        match Body::closed_boundary_mesh(&vertices, &bad, 1.0) {
            Err(
                e @ InertiaError::InconsistentOrientation {
                    facet, neighbour, ..
                },
            ) => {
                assert_eq!(facet, flipped);
                assert_ne!(neighbour, flipped);
                assert!(
                    e.to_string()
                        .contains(&format!("facet {flipped} is flipped"))
                );
            }
            other => panic!("flipped facet {flipped}: {other:?}"),
        }
    }
    // Either global orientation is accepted.
    let mut inward = facets.clone();
    for f in &mut inward {
        f.swap(1, 2);
    }
    let body = Body::closed_boundary_mesh(&vertices, &inward, 1.0).unwrap();
    assert!((body.volume().unwrap() - 1.0).abs() < 1e-14);
}

#[test]
fn a_flipped_tetrahedron_face_and_polygon_edge_are_refused() {
    // Tetrahedron: four outward triangles; flip the last.
    let vertices = vec![
        v(&[0.0, 0.0, 0.0]),
        v(&[1.0, 0.0, 0.0]),
        v(&[0.0, 1.0, 0.0]),
        v(&[0.0, 0.0, 1.0]),
    ];
    let good = vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
    let body = Body::closed_boundary_mesh(&vertices, &good, 6.0).unwrap();
    assert!((body.volume().unwrap() - 1.0 / 6.0).abs() < 1e-15);
    let mut bad = good.clone();
    bad[3] = [1, 3, 2];
    assert!(matches!(
        Body::closed_boundary_mesh(&vertices, &bad, 6.0),
        Err(InertiaError::InconsistentOrientation { facet: 3, .. })
    ));
    // 2D: a square whose third edge runs the wrong way.
    let square = vec![
        v(&[0.0, 0.0]),
        v(&[1.0, 0.0]),
        v(&[1.0, 1.0]),
        v(&[0.0, 1.0]),
    ];
    let edges = vec![[0, 1], [1, 2], [3, 2], [3, 0]];
    assert!(matches!(
        Body::closed_boundary_mesh(&square, &edges, 1.0),
        Err(InertiaError::InconsistentOrientation { facet: 2, .. })
    ));
}

#[test]
fn the_triangle_inequality_error_explains_itself() {
    let e = InertiaMap::from_principal_moments_of_inertia_3d([1.0, 4.0, 2.0]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "moments of inertia (1, 4, 2) violate the triangle inequality: I2 = 4 exceeds I1 + I3 = 3, \
         so no body has them (they are not second moments either: for those use \
         InertiaMap::from_principal_second_moments); for a test body use \
         InertiaMap::from_classical_3d or InertiaMap::from_plane_moments"
    );
}
