//! Bad input gives a clear error variant, never a panic or NaN; flat bodies are reported
//! with the degenerate direction or plane.
use nalgebra::{DMatrix, DVector};
use rotorflow::inertia::bodies::{pentachoron_vertices, regular_simplex_positions};
use rotorflow::inertia::tolerance::FLATNESS_TOLERANCE;
use rotorflow::inertia::{Body, InertiaError, SimplexOrientation};

fn v(x: &[f64]) -> DVector<f64> {
    DVector::from_vec(x.to_vec())
}

const BAD_NUMBERS: [f64; 5] = [0.0, -1.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY];

/// Asserts a positive-quantity error: NotPositive for 0 and negatives, NonFinite otherwise.
fn assert_bad_number(result: Result<Body, InertiaError>, value: f64, quantity: &str) {
    match result {
        Err(InertiaError::NotPositive {
            quantity: q,
            value: got,
            ..
        }) => {
            assert!(
                value.is_finite() && value <= 0.0,
                "{quantity}: {value} gave NotPositive"
            );
            assert_eq!(q, quantity);
            assert_eq!(got, value);
        }
        Err(InertiaError::NonFinite { quantity: q, .. }) => {
            assert!(!value.is_finite(), "{quantity}: {value} gave NonFinite");
            assert_eq!(q, quantity);
        }
        other => panic!("{quantity} = {value}: unexpected {other:?}"),
    }
}

#[test]
fn point_masses_reject_bad_input() {
    let p = vec![v(&[0.0, 0.0]), v(&[1.0, 0.0])];
    assert_eq!(
        Body::point_masses(&[], &[]),
        Err(InertiaError::Empty {
            quantity: "positions"
        })
    );
    assert!(matches!(
        Body::point_masses(&[1.0], &p),
        Err(InertiaError::LengthMismatch {
            quantity: "masses",
            expected: 2,
            found: 1,
            ..
        })
    ));
    assert!(matches!(
        Body::point_masses(&[1.0, 1.0], &[v(&[0.0, 0.0]), v(&[1.0, 0.0, 0.0])]),
        Err(InertiaError::LengthMismatch {
            quantity: "positions",
            index: Some(1),
            expected: 2,
            found: 3
        })
    ));
    assert!(matches!(
        Body::point_masses(&[1.0], &[DVector::zeros(0)]),
        Err(InertiaError::DimensionTooSmall { dim: 0, min: 1 })
    ));
    for bad in BAD_NUMBERS {
        assert_bad_number(Body::point_masses(&[1.0, bad], &p), bad, "masses");
    }
    for bad in [f64::NAN, f64::INFINITY] {
        assert!(matches!(
            Body::point_masses(&[1.0, 1.0], &[v(&[0.0, 0.0]), v(&[bad, 0.0])]),
            Err(InertiaError::NonFinite {
                quantity: "positions",
                index: Some(1),
                ..
            })
        ));
    }
}

#[test]
fn closed_form_bodies_reject_bad_numbers() {
    for bad in BAD_NUMBERS {
        assert_bad_number(Body::solid_cuboid(&[1.0, bad], 1.0), bad, "half_edges");
        assert_bad_number(Body::solid_cuboid(&[1.0, 1.0], bad), bad, "density");
        assert_bad_number(
            Body::solid_ellipsoid(&[bad, 1.0, 1.0], 1.0),
            bad,
            "semi_axes",
        );
        assert_bad_number(Body::solid_ellipsoid(&[1.0, 1.0], bad), bad, "density");
        assert_bad_number(Body::solid_ball(3, bad, 1.0), bad, "radius");
        assert_bad_number(Body::solid_ball(3, 1.0, bad), bad, "density");
        assert_bad_number(Body::hypersphere_shell(3, bad, 1.0), bad, "radius");
        assert_bad_number(Body::hypersphere_shell(3, 1.0, bad), bad, "surface_density");
        assert_bad_number(Body::cuboid_vertices(&[bad, 1.0], 1.0), bad, "half_edges");
        assert_bad_number(Body::cuboid_vertices(&[1.0, 1.0], bad), bad, "vertex_mass");
        assert_bad_number(
            Body::regular_simplex_vertices(3, bad, 1.0),
            bad,
            "circumradius",
        );
        assert_bad_number(
            Body::regular_simplex_vertices(3, 1.0, bad),
            bad,
            "vertex_mass",
        );
        assert_bad_number(Body::cross_polytope_vertices(3, bad, 1.0), bad, "radius");
        assert_bad_number(
            Body::cross_polytope_vertices(3, 1.0, bad),
            bad,
            "vertex_mass",
        );
        assert_bad_number(
            Body::pentachoron(1.0, 1.0, bad, 1.0),
            bad,
            "pentachoron parameters (a, b, c, d)",
        );
        assert!(pentachoron_vertices(bad, 1.0, 1.0, 1.0).is_err());
        assert!(regular_simplex_positions(2, bad).is_err());
    }
    assert_eq!(
        Body::solid_cuboid(&[], 1.0),
        Err(InertiaError::Empty {
            quantity: "half_edges"
        })
    );
    assert_eq!(
        Body::solid_ellipsoid(&[], 1.0),
        Err(InertiaError::Empty {
            quantity: "semi_axes"
        })
    );
    for make in [
        |n| Body::solid_ball(n, 1.0, 1.0),
        |n| Body::hypersphere_shell(n, 1.0, 1.0),
        |n| Body::regular_simplex_vertices(n, 1.0, 1.0),
        |n| Body::cross_polytope_vertices(n, 1.0, 1.0),
    ] {
        assert_eq!(
            make(0),
            Err(InertiaError::DimensionTooSmall { dim: 0, min: 1 })
        );
        assert!(make(1).is_ok());
    }
    // Error index points at the offending element.
    assert!(matches!(
        Body::solid_cuboid(&[1.0, 2.0, -3.0], 1.0),
        Err(InertiaError::NotPositive { index: Some(2), .. })
    ));
}

#[test]
fn overflow_is_reported_not_returned_as_infinity() {
    assert_eq!(
        Body::solid_cuboid(&[1e200, 1e200], 1.0),
        Err(InertiaError::NonFiniteResult { quantity: "mass" })
    );
    assert!(matches!(
        Body::solid_ball(3, 1e150, 1.0),
        Err(InertiaError::NonFiniteResult { .. })
    ));
    assert!(matches!(
        Body::point_masses(&[1e300, 1e300], &[v(&[0.0]), v(&[1e300])]),
        Err(InertiaError::NonFiniteResult { .. })
    ));
}

#[test]
fn simplices_reject_degenerate_and_malformed_input() {
    // Collinear triangle.
    let flat = vec![v(&[0.0, 0.0]), v(&[1.0, 1.0]), v(&[2.0, 2.0])];
    assert!(matches!(
        Body::solid_simplex(&flat, 1.0),
        Err(InertiaError::DegenerateSimplex { simplex: 0, .. })
    ));
    // Nearly flat tetrahedron (relative volume 1e-14) is degenerate too.
    let thin = vec![
        v(&[0.0, 0.0, 0.0]),
        v(&[1.0, 0.0, 0.0]),
        v(&[0.0, 1.0, 0.0]),
        v(&[0.3, 0.3, 1e-14]),
    ];
    assert!(matches!(
        Body::solid_simplex(&thin, 1.0),
        Err(InertiaError::DegenerateSimplex { .. })
    ));
    // Repeated vertex.
    let repeated = vec![v(&[0.0, 0.0]), v(&[0.0, 0.0]), v(&[1.0, 0.0])];
    assert!(matches!(
        Body::solid_simplex(&repeated, 1.0),
        Err(InertiaError::DegenerateSimplex { .. })
    ));
    // Wrong number of vertices: a triangle in 3D is not a solid 3-simplex.
    let triangle3 = vec![
        v(&[0.0, 0.0, 0.0]),
        v(&[1.0, 0.0, 0.0]),
        v(&[0.0, 1.0, 0.0]),
    ];
    assert!(matches!(
        Body::solid_simplex(&triangle3, 1.0),
        Err(InertiaError::LengthMismatch {
            quantity: "vertices",
            expected: 4,
            found: 3,
            ..
        })
    ));
    let good = vec![v(&[0.0, 0.0]), v(&[1.0, 0.0]), v(&[0.0, 1.0])];
    for bad in BAD_NUMBERS {
        assert_bad_number(Body::solid_simplex(&good, bad), bad, "density");
    }
    assert_eq!(
        Body::solid_simplex(&[], 1.0),
        Err(InertiaError::Empty {
            quantity: "vertices"
        })
    );
}

#[test]
fn meshes_reject_malformed_input() {
    let square = vec![
        v(&[0.0, 0.0]),
        v(&[1.0, 0.0]),
        v(&[1.0, 1.0]),
        v(&[0.0, 1.0]),
    ];
    let ok: Vec<[usize; 3]> = vec![[0, 1, 2], [0, 2, 3]];
    assert!(Body::simplicial_mesh(&square, &ok, 1.0, SimplexOrientation::Signed).is_ok());
    let none: Vec<[usize; 3]> = vec![];
    assert_eq!(
        Body::simplicial_mesh(&square, &none, 1.0, SimplexOrientation::Signed),
        Err(InertiaError::Empty {
            quantity: "simplices"
        })
    );
    assert_eq!(
        Body::simplicial_mesh(&square, &[vec![0, 1]], 1.0, SimplexOrientation::Signed),
        Err(InertiaError::WrongSimplexSize {
            simplex: 0,
            expected: 3,
            found: 2
        })
    );
    assert_eq!(
        Body::simplicial_mesh(
            &square,
            &[[0, 1, 2], [0, 2, 4]],
            1.0,
            SimplexOrientation::Signed
        ),
        Err(InertiaError::VertexIndexOutOfRange {
            simplex: 1,
            vertex: 4,
            vertex_count: 4
        })
    );
    // All simplices degenerate: zero volume.
    assert!(matches!(
        Body::simplicial_mesh(
            &square,
            &[[0, 0, 1], [2, 2, 3]],
            1.0,
            SimplexOrientation::Unsigned
        ),
        Err(InertiaError::ZeroMeshVolume { .. })
    ));
    // Oppositely oriented copies of one triangle cancel.
    assert!(matches!(
        Body::simplicial_mesh(
            &square,
            &[[0, 1, 2], [0, 2, 1]],
            1.0,
            SimplexOrientation::Signed
        ),
        Err(InertiaError::ZeroMeshVolume { .. })
    ));
    // Inconsistent orientation that does not cancel: a positive triangle near the origin
    // minus a smaller triangle far away gives a net positive volume but a negative second
    // moment, which no mass distribution has.
    let pts = vec![
        v(&[0.0, 0.0]),
        v(&[1.0, 0.0]),
        v(&[0.0, 1.0]),
        v(&[10.0, 0.0]),
        v(&[10.0, 0.05]),
    ];
    assert!(matches!(
        Body::simplicial_mesh(
            &pts,
            &[[0, 1, 2], [0, 4, 3]],
            1.0,
            SimplexOrientation::Signed
        ),
        Err(InertiaError::InconsistentMesh { .. })
    ));
    // Bad vertex data.
    let mut nan = square.clone();
    nan[2] = v(&[f64::NAN, 0.0]);
    assert!(matches!(
        Body::simplicial_mesh(&nan, &ok, 1.0, SimplexOrientation::Signed),
        Err(InertiaError::NonFinite {
            quantity: "vertices",
            index: Some(2),
            ..
        })
    ));
    for bad in BAD_NUMBERS {
        assert_bad_number(
            Body::simplicial_mesh(&square, &ok, bad, SimplexOrientation::Signed),
            bad,
            "density",
        );
    }
    // Boundary meshes: facets of N indices, N ≥ 2.
    assert_eq!(
        Body::closed_boundary_mesh(&square, &[[0, 1, 2]], 1.0),
        Err(InertiaError::WrongSimplexSize {
            simplex: 0,
            expected: 2,
            found: 3
        })
    );
    assert_eq!(
        Body::closed_boundary_mesh(&[v(&[0.0]), v(&[1.0])], &[[0], [1]], 1.0),
        Err(InertiaError::DimensionTooSmall { dim: 1, min: 2 })
    );
    // Whether a boundary is closed is not checked (the cones of an open boundary still
    // enclose a region; see the Signed documentation). A boundary whose cones all have zero
    // area, such as a single edge through the apex, is reported.
    assert!(matches!(
        Body::closed_boundary_mesh(&[v(&[0.0, 0.0]), v(&[1.0, 0.0])], &[[0, 1]], 1.0),
        Err(InertiaError::ZeroMeshVolume { .. })
    ));
}

#[test]
fn transformations_reject_bad_input() {
    let b = Body::solid_cuboid(&[1.0, 2.0, 3.0], 1.0).unwrap();
    assert!(matches!(
        b.rotated(&DMatrix::identity(2, 2)),
        Err(InertiaError::WrongShape {
            quantity: "rotation",
            expected: 3,
            rows: 2,
            ..
        })
    ));
    let mut skewed = DMatrix::identity(3, 3);
    skewed[(0, 1)] = 0.1;
    assert!(matches!(
        b.rotated(&skewed),
        Err(InertiaError::NotOrthogonal { .. })
    ));
    assert!(matches!(
        b.rotated(&(DMatrix::identity(3, 3) * 2.0)),
        Err(InertiaError::NotOrthogonal { .. })
    ));
    let mut nan = DMatrix::identity(3, 3);
    nan[(1, 1)] = f64::NAN;
    assert!(matches!(
        b.rotated(&nan),
        Err(InertiaError::NonFinite {
            quantity: "rotation",
            ..
        })
    ));
    // A reflection is orthogonal but not a rotation: `rotated` refuses it, and
    // `orthogonally_transformed` gives the mirror image.
    let mirror = DMatrix::from_diagonal(&v(&[-1.0, 1.0, 1.0]));
    assert!(matches!(
        b.rotated(&mirror),
        Err(InertiaError::Reflection { determinant }) if (determinant + 1.0).abs() < 1e-15
    ));
    assert!(matches!(
        b.placed(&mirror, &v(&[0.0, 0.0, 0.0])),
        Err(InertiaError::Reflection { .. })
    ));
    let image = b.orthogonally_transformed(&mirror).unwrap();
    assert_eq!(image.mass_tensor(), b.mass_tensor());
    assert!(matches!(
        b.translated(&v(&[1.0, 2.0])),
        Err(InertiaError::LengthMismatch {
            quantity: "offset",
            ..
        })
    ));
    assert!(matches!(
        b.translated(&v(&[1.0, f64::INFINITY, 0.0])),
        Err(InertiaError::NonFinite {
            quantity: "offset",
            ..
        })
    ));
    assert!(matches!(
        b.mass_tensor_about(&v(&[1.0])),
        Err(InertiaError::LengthMismatch {
            quantity: "point",
            ..
        })
    ));
    for bad in BAD_NUMBERS {
        assert_bad_number(b.with_mass(bad), bad, "mass");
    }
    let other = Body::solid_ball(2, 1.0, 1.0).unwrap();
    assert!(matches!(
        Body::composite(&[b.clone(), other]),
        Err(InertiaError::LengthMismatch {
            quantity: "parts",
            index: Some(1),
            expected: 3,
            found: 2
        })
    ));
    assert_eq!(
        Body::composite(&[]),
        Err(InertiaError::Empty { quantity: "parts" })
    );
}

#[test]
fn from_mass_properties_checks_the_tensor() {
    let c = DVector::zeros(2);
    assert!(Body::from_mass_properties(1.0, c.clone(), DMatrix::identity(2, 2), None).is_ok());
    assert!(matches!(
        Body::from_mass_properties(1.0, c.clone(), DMatrix::identity(3, 3), None),
        Err(InertiaError::WrongShape {
            quantity: "mass_tensor",
            expected: 2,
            rows: 3,
            cols: 3,
        })
    ));
    let asym = DMatrix::from_row_slice(2, 2, &[1.0, 0.5, 0.0, 1.0]);
    assert!(matches!(
        Body::from_mass_properties(1.0, c.clone(), asym, None),
        Err(InertiaError::NotSymmetric {
            quantity: "mass_tensor",
            ..
        })
    ));
    let indefinite = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 2.0, 1.0]);
    assert!(matches!(
        Body::from_mass_properties(1.0, c.clone(), indefinite, None),
        Err(InertiaError::NegativeMoment { index: 0, .. })
    ));
    assert!(matches!(
        Body::from_mass_properties(0.0, c.clone(), DMatrix::identity(2, 2), None),
        Err(InertiaError::NotPositive {
            quantity: "mass",
            ..
        })
    ));
    assert!(matches!(
        Body::from_mass_properties(1.0, c, DMatrix::identity(2, 2), Some(-1.0)),
        Err(InertiaError::NotPositive {
            quantity: "volume",
            ..
        })
    ));
}

#[test]
fn flat_bodies_name_the_degenerate_direction_and_plane() {
    // A square of points in the plane x_3 = 5 in 3D: flat along ±e_3; the inertia map is
    // still invertible (only one flat direction).
    let square = Body::point_masses(
        &[1.0; 4],
        &[
            v(&[0.0, 0.0, 5.0]),
            v(&[1.0, 0.0, 5.0]),
            v(&[1.0, 2.0, 5.0]),
            v(&[0.0, 2.0, 5.0]),
        ],
    )
    .unwrap();
    let flat = square.flat_directions(FLATNESS_TOLERANCE);
    assert_eq!(flat.len(), 1);
    assert!((flat[0][2].abs() - 1.0).abs() < 1e-12);
    match square.check_full_rank(FLATNESS_TOLERANCE) {
        Err(InertiaError::FlatBody {
            direction,
            moment,
            largest_moment,
        }) => {
            assert!((direction[2].abs() - 1.0).abs() < 1e-12);
            assert!(moment.abs() <= 1e-15 * largest_moment);
        }
        other => panic!("{other:?}"),
    }
    assert!(square.check_inertia_invertible(FLATNESS_TOLERANCE).is_ok());

    // A rod of points along e_1 in 3D: flat along e_2 and e_3, so the plane e_2∧e_3 has
    // zero plane moment and the inertia map is singular.
    let rod = Body::point_masses(
        &[1.0, 2.0, 1.0],
        &[
            v(&[-1.0, 0.0, 0.0]),
            v(&[0.0, 0.0, 0.0]),
            v(&[3.0, 0.0, 0.0]),
        ],
    )
    .unwrap();
    assert_eq!(rod.flat_directions(FLATNESS_TOLERANCE).len(), 2);
    match rod.check_inertia_invertible(FLATNESS_TOLERANCE) {
        Err(InertiaError::DegeneratePlane {
            first,
            second,
            plane_moment,
            ..
        }) => {
            assert!(first[0].abs() < 1e-12 && second[0].abs() < 1e-12);
            assert!((first.dot(&second)).abs() < 1e-12);
            assert_eq!(plane_moment, 0.0);
        }
        other => panic!("{other:?}"),
    }

    // A single point is flat in every direction.
    let point = Body::point_masses(&[2.0], &[v(&[1.0, 2.0])]).unwrap();
    assert_eq!(point.flat_directions(FLATNESS_TOLERANCE).len(), 2);
    assert!(point.check_full_rank(FLATNESS_TOLERANCE).is_err());
    assert!(point.check_inertia_invertible(FLATNESS_TOLERANCE).is_err());

    // A disc in 4D (flat in two directions) is singular; a 3-ball in 4D is only flat once.
    let disc4 = Body::solid_ball(2, 1.0, 1.0).unwrap();
    let disc_j = DMatrix::from_fn(4, 4, |i, j| {
        if i < 2 && j < 2 {
            disc4.mass_tensor()[(i, j)]
        } else {
            0.0
        }
    });
    let disc4 = Body::from_mass_properties(disc4.mass(), DVector::zeros(4), disc_j, None).unwrap();
    assert!(matches!(
        disc4.check_inertia_invertible(FLATNESS_TOLERANCE),
        Err(InertiaError::DegeneratePlane { .. })
    ));
    // Solid bodies are never flat.
    for b in [
        Body::solid_ball(4, 1.0, 1.0).unwrap(),
        Body::solid_cuboid(&[1e-2, 1.0, 1e2], 1.0).unwrap(),
    ] {
        assert!(b.flat_directions(FLATNESS_TOLERANCE).is_empty());
        assert!(b.check_full_rank(FLATNESS_TOLERANCE).is_ok());
        assert!(b.check_inertia_invertible(FLATNESS_TOLERANCE).is_ok());
    }
    // 1D has no planes.
    let seg = Body::solid_cuboid(&[1.0], 1.0).unwrap();
    assert!(seg.check_inertia_invertible(FLATNESS_TOLERANCE).is_ok());
}

#[test]
fn error_messages_are_sentences() {
    let e = Body::solid_cuboid(&[1.0, -2.0], 1.0).unwrap_err();
    assert_eq!(e.to_string(), "`half_edges`[1] must be positive, got -2");
    let e = Body::point_masses(&[1.0], &[v(&[0.0]), v(&[1.0])]).unwrap_err();
    assert_eq!(e.to_string(), "`masses` has length 1, expected 2");
    let e =
        Body::solid_simplex(&[v(&[0.0, 0.0]), v(&[1.0, 1.0]), v(&[2.0, 2.0])], 1.0).unwrap_err();
    assert!(e.to_string().starts_with("simplex 0 is degenerate"));
}
