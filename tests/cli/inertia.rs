//! `rotorflow inertia`: every JSON key, and the numbers match the library.

use super::{assert_close, assert_matrix_close, floats, matrix, rotorflow, run_json};
use nalgebra::{DMatrix, DVector};
use rotorflow::inertia::tensor::{ContractedInertia, ContractionNormalization, RankFourTensor};
use rotorflow::inertia::{Body, InertiaMap};

const KEYS: [&str; 11] = [
    "dim",
    "mass",
    "volume",
    "center_of_mass",
    "mass_tensor",
    "principal_moments",
    "plane_moments",
    "inertia_matrix",
    "rank4",
    "contracted",
    "gyration_radii",
];

/// Checks every reported quantity of `spec` against the library's `body`.
fn check_against_library(spec: &str, body: &Body) {
    let v = run_json(&["inertia", "--body", spec, "--json"]);
    for k in KEYS {
        assert!(v.get(k).is_some(), "{spec}: key {k} missing");
    }
    let n = body.dim();
    assert_eq!(v["dim"].as_u64(), Some(n as u64));
    assert_close(&[v["mass"].as_f64().unwrap()], &[body.mass()], 1e-12);
    match body.volume() {
        Some(vol) => assert_close(&[v["volume"].as_f64().unwrap()], &[vol], 1e-12),
        None => assert!(v["volume"].is_null(), "{spec}: volume should be null"),
    }
    assert_close(
        &floats(&v["center_of_mass"]),
        body.center_of_mass().as_slice(),
        1e-12,
    );
    let j = body.mass_tensor();
    assert_matrix_close(&matrix(&v["mass_tensor"]), j, 1e-12);
    assert_close(
        &floats(&v["principal_moments"]),
        body.principal_moments().as_slice(),
        1e-12,
    );
    assert_close(
        &floats(&v["plane_moments"]),
        body.plane_moments().as_slice(),
        1e-12,
    );
    let map = InertiaMap::from_body(body).unwrap().to_matrix();
    assert_matrix_close(&matrix(&v["inertia_matrix"]), &map, 1e-12);
    let rank4 = RankFourTensor::from_mass_tensor(j).unwrap();
    for (i, a) in v["rank4"].as_array().unwrap().iter().enumerate() {
        for (k, b) in a.as_array().unwrap().iter().enumerate() {
            for (l, c) in b.as_array().unwrap().iter().enumerate() {
                let expected: Vec<f64> = (0..n).map(|m| rank4.get(i, k, l, m)).collect();
                assert_close(&floats(c), &expected, 1e-12);
            }
        }
    }
    let contracted =
        ContractedInertia::from_mass_tensor(j, ContractionNormalization::LeviCivita).unwrap();
    assert_matrix_close(&matrix(&v["contracted"]), contracted.matrix(), 1e-12);
    assert_close(
        &floats(&v["gyration_radii"]),
        contracted.gyration_radii(body.mass()).unwrap().as_slice(),
        1e-12,
    );
}

#[test]
fn inertia_tesseract_matches_library() {
    check_against_library(
        "tesseract:1,1.2,1.5,2",
        &Body::cuboid_vertices(&[1.0, 1.2, 1.5, 2.0], 1.0).unwrap(),
    );
}

#[test]
fn inertia_pentachoron_matches_library() {
    check_against_library(
        "pentachoron:1,1.2,1.5,2",
        &Body::pentachoron_eq73(1.0, 1.2, 1.5, 2.0).unwrap(),
    );
}

#[test]
fn inertia_solids_match_library() {
    check_against_library(
        "cuboid:1,2,3,4",
        &Body::solid_cuboid(&[1.0, 2.0, 3.0, 4.0], 1.0).unwrap(),
    );
    check_against_library(
        "cuboid:1,2,3;density=2.5",
        &Body::solid_cuboid(&[1.0, 2.0, 3.0], 2.5).unwrap(),
    );
    check_against_library(
        "ellipsoid:1,2,3,4,5",
        &Body::solid_ellipsoid(&[1.0, 2.0, 3.0, 4.0, 5.0], 1.0).unwrap(),
    );
    check_against_library(
        "ellipsoid:1,2,3;mass=7",
        &Body::solid_ellipsoid(&[1.0, 2.0, 3.0], 1.0)
            .unwrap()
            .with_mass(7.0)
            .unwrap(),
    );
    check_against_library("ball:5,2", &Body::solid_ball(5, 2.0, 1.0).unwrap());
    check_against_library(
        "sphere:4,1.5;density=3",
        &Body::hypersphere_shell(4, 1.5, 3.0).unwrap(),
    );
    check_against_library(
        "simplex:4",
        &Body::regular_simplex_vertices(4, 1.0, 1.0).unwrap(),
    );
}

#[test]
fn inertia_given_tensors_match_library() {
    check_against_library(
        "principal:1,2,3,4",
        &Body::from_mass_properties(
            1.0,
            DVector::zeros(4),
            DMatrix::from_diagonal(&DVector::from_vec(vec![1.0, 2.0, 3.0, 4.0])),
            None,
        )
        .unwrap(),
    );
    let j = DMatrix::from_row_slice(3, 3, &[2.0, 0.5, 0.1, 0.5, 3.0, 0.2, 0.1, 0.2, 4.0]);
    check_against_library(
        "tensor:2,0.5,0.1,0.5,3,0.2,0.1,0.2,4;mass=2",
        &Body::from_mass_properties(2.0, DVector::zeros(3), j, None).unwrap(),
    );
}

#[test]
fn inertia_points_file_matches_library() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("points.csv");
    std::fs::write(
        &path,
        "# m,x,y,z,w\n1,1,0,0,0\n2,0,1,0,0\n1,0,0,1,0\n3,0,0,0,1\n1,1,1,1,1\n",
    )
    .unwrap();
    let positions: Vec<DVector<f64>> = [
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 0.0, 1.0],
        [1.0, 1.0, 1.0, 1.0],
    ]
    .iter()
    .map(|p| DVector::from_column_slice(p))
    .collect();
    let body = Body::point_masses(&[1.0, 2.0, 1.0, 3.0, 1.0], &positions).unwrap();
    check_against_library(&format!("points:{}", path.display()), &body);
}

#[test]
fn inertia_mesh_file_matches_library() {
    // The unit square [0,1]² as two triangles (1-based vertex numbers).
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("square.mesh");
    std::fs::write(
        &path,
        "# unit square\nv 0 0\nv 1 0\nv 1 1\nv 0 1\ns 1 2 3\ns 1 3 4\n",
    )
    .unwrap();
    let v = run_json(&[
        "inertia",
        "--body",
        &format!("mesh:{};density=2", path.display()),
        "--json",
    ]);
    assert_close(&[v["mass"].as_f64().unwrap()], &[2.0], 1e-12);
    assert_close(&[v["volume"].as_f64().unwrap()], &[1.0], 1e-12);
    assert_close(&floats(&v["center_of_mass"]), &[0.5, 0.5], 1e-12);
    // J = m/12 per axis for a unit square.
    assert_close(
        &floats(&v["principal_moments"]),
        &[2.0 / 12.0, 2.0 / 12.0],
        1e-12,
    );
    assert!(v["contracted"].is_null(), "no contracted matrix in 2D");
}

#[test]
fn inertia_planes_has_only_the_map() {
    let v = run_json(&[
        "inertia",
        "--body",
        "planes:2,1,0.6666666666666666",
        "--json",
    ]);
    assert_eq!(v["dim"].as_u64(), Some(3));
    assert_close(&floats(&v["plane_moments"]), &[2.0, 1.0, 2.0 / 3.0], 1e-15);
    assert!(v["mass_tensor"].is_null());
    assert!(v["rank4"].is_null());
    assert!(v["volume"].is_null());
    assert_eq!(matrix(&v["inertia_matrix"])[0], vec![2.0, 0.0, 0.0]);
}

#[test]
fn inertia_text_output_names_the_quantities() {
    let out = rotorflow()
        .args(["inertia", "--body", "tesseract:1,1.2,1.5,2"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    for word in [
        "mass",
        "principal moments",
        "plane moments",
        "gyration radii",
    ] {
        assert!(text.contains(word), "missing {word} in\n{text}");
    }
}
