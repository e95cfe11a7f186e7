//! `rotorflow inertia`: every JSON key, and the numbers match the library.

use super::{assert_close, assert_matrix_close, floats, matrix, rotorflow, run_json};
use nalgebra::{DMatrix, DVector};
use rotorflow::inertia::tensor::{ContractedInertia, ContractionNormalization, RankFourTensor};
use rotorflow::inertia::{Body, InertiaMap};

const KEYS: [&str; 15] = [
    "dim",
    "mass",
    "volume",
    "center_of_mass",
    "mass_tensor",
    "second_moments",
    "principal_axes",
    "principal_plane_moments",
    "moments_of_inertia",
    "contracted_factor",
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
    let (second, _) = body.principal_frame();
    assert_close(&floats(&v["second_moments"]), second.as_slice(), 1e-12);
    // Each principal axis p satisfies J p = Jₖ p.
    for (k, p) in matrix(&v["principal_axes"]).iter().enumerate() {
        let p = DVector::from_vec(p.clone());
        assert_close((j * &p).as_slice(), (second[k] * &p).as_slice(), 1e-10);
        assert_close(&[p.norm()], &[1.0], 1e-12);
    }
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
        &Body::pentachoron(1.0, 1.2, 1.5, 2.0).unwrap(),
    );
}

#[test]
fn inertia_solids_match_library() {
    check_against_library(
        "cuboid:1,2,3,4",
        &Body::solid_cuboid(&[1.0, 2.0, 3.0, 4.0], 1.0).unwrap(),
    );
    check_against_library(
        "cuboid:1,2,3+density=2.5",
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
        "sphere:4,1.5+density=3",
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
        "tensor:2,0.5,0.1,0.5,3,0.2,0.1,0.2,4+mass=2",
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
        &format!("mesh:{}+density=2", path.display()),
        "--json",
    ]);
    assert_close(&[v["mass"].as_f64().unwrap()], &[2.0], 1e-12);
    assert_close(&[v["volume"].as_f64().unwrap()], &[1.0], 1e-12);
    assert_close(&floats(&v["center_of_mass"]), &[0.5, 0.5], 1e-12);
    // J = m/12 per axis for a unit square.
    assert_close(
        &floats(&v["second_moments"]),
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
        "second moments",
        "principal plane moments",
        "principal axes",
        "plane moments",
        "gyration radii",
    ] {
        assert!(text.contains(word), "missing {word} in\n{text}");
    }
}

/// The classical 3D moments of inertia and the second moments of a solid cuboid, labelled
/// apart: half-lengths (0.5, 1, 1.5), mass 12 give Jᵢ = m aᵢ²/3 = 1, 4, 9 and
/// I₁ = J₂ + J₃ = 13, I₂ = J₁ + J₃ = 10, I₃ = J₁ + J₂ = 5 (m (b² + c²)/3 with full
/// lengths 2b, 2c: the textbook m (B² + C²)/12).
#[test]
fn moments_of_inertia_and_second_moments_are_told_apart() {
    let v = run_json(&["inertia", "--body", "cuboid:0.5,1,1.5+mass=12", "--json"]);
    // The 0.1 key stays, deprecated, with the values of `second_moments`.
    assert_eq!(v["principal_moments"], v["second_moments"]);
    assert_close(&floats(&v["second_moments"]), &[1.0, 4.0, 9.0], 1e-12);
    assert_close(&floats(&v["moments_of_inertia"]), &[13.0, 10.0, 5.0], 1e-12);
    // The axes are the coordinate axes (up to sign), in the order of the moments.
    let axes = matrix(&v["principal_axes"]);
    for (k, axis) in axes.iter().enumerate() {
        assert_close(&[axis[k].abs()], &[1.0], 1e-12);
    }
    // The contracted matrix is c₃ (tr J · 1 − J) with c₃ = 2: diag 2 (13, 10, 5).
    assert_eq!(v["contracted_factor"].as_f64(), Some(2.0));
    let c = matrix(&v["contracted"]);
    assert_close(&[c[0][0], c[1][1], c[2][2]], &[26.0, 20.0, 10.0], 1e-12);
    // Quoted `;mass=` is the same body.
    let w = run_json(&["inertia", "--body", "cuboid:0.5,1,1.5;mass=12", "--json"]);
    assert_eq!(v["second_moments"], w["second_moments"]);
    // The text names each quantity.
    let out = rotorflow()
        .args(["inertia", "--body", "cuboid:0.5,1,1.5+mass=12"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let row = |label: &str| {
        text.lines()
            .find(|l| l.starts_with(label))
            .unwrap_or_else(|| panic!("no `{label}` in\n{text}"))
            .to_string()
    };
    assert!(
        row("second moments").ends_with("1.000000, 4.000000, 9.000000"),
        "{text}"
    );
    assert!(
        row("moments of inertia").ends_with("13.000000, 10.000000, 5.000000"),
        "{text}"
    );
    assert!(text.contains("c_N = 2"), "{text}");
    // Outside 3D there are no moments about axes.
    let v = run_json(&["inertia", "--body", "cuboid:1,2,3,4", "--json"]);
    assert!(v["moments_of_inertia"].is_null());
}

/// A comma before an option, and an unquoted `;`, which the shell would cut.
#[test]
fn options_after_a_comma_are_refused_with_the_right_form() {
    let out = rotorflow()
        .args(["inertia", "--body", "cuboid:1,2,3,4,mass=5", "--json"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("write `+mass=5` (or a quoted `;mass=5`)"),
        "{err}"
    );
    // `+mass=5` gives mass 5; `1e+0` stays a number.
    let v = run_json(&["inertia", "--body", "cuboid:1e+0,2,3,4+mass=5", "--json"]);
    assert_close(&[v["mass"].as_f64().unwrap()], &[5.0], 1e-12);
}
