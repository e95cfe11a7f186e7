//! Closed forms of the catalogue: point sets against explicit enumeration, textbook 3D
//! moments, simplices, volumes, composites, and structural properties (symmetric PSD J,
//! the 4D plane-moment identity, isotropy of regular polytopes).
use crate::common::{
    EPS, gamma_half, gaussian, kuhn_triangulation, max_abs, max_abs_diff, random_rotation, rng,
};
use nalgebra::{DMatrix, DVector};
use rotorflow::algebra::pairs;
use rotorflow::inertia::bodies::{regular_simplex_positions, unit_ball_volume};
use rotorflow::inertia::{Body, SimplexOrientation};
use std::f64::consts::PI;

/// All 2ᴺ sign patterns (±a₁, …, ±a_N).
fn cuboid_corner_points(half: &[f64]) -> Vec<DVector<f64>> {
    let n = half.len();
    (0..1usize << n)
        .map(|bits| {
            DVector::from_fn(n, |i, _| {
                if (bits >> i) & 1 == 1 {
                    half[i]
                } else {
                    -half[i]
                }
            })
        })
        .collect()
}

/// Rounding budget for sums of k terms of size `scale`: 4 k ulp.
fn sum_tol(k: usize, scale: f64) -> f64 {
    4.0 * k as f64 * EPS * scale
}

#[test]
fn cuboid_vertices_match_explicit_point_cloud_n1_to_n6() {
    for n in 1..=6 {
        let half: Vec<f64> = (0..n).map(|i| 0.4 + 0.35 * i as f64).collect();
        let body = Body::cuboid_vertices(&half, 1.5).unwrap();
        let points = cuboid_corner_points(&half);
        let cloud = Body::point_masses(&vec![1.5; points.len()], &points).unwrap();
        let scale = max_abs(body.mass_tensor());
        assert_matrix_close!(
            *cloud.mass_tensor(),
            *body.mass_tensor(),
            sum_tol(points.len(), scale),
            "N={n}"
        );
        assert_eq!(body.mass(), 1.5 * (1u64 << n) as f64);
        assert!(body.volume().is_none());
        for (i, a) in half.iter().enumerate() {
            assert_close!(body.mass_tensor()[(i, i)], body.mass() * a * a, 0.0);
        }
    }
}

#[test]
fn cross_polytope_vertices_match_explicit_point_cloud_n1_to_n6() {
    for n in 1..=6 {
        let r = 1.7;
        let body = Body::cross_polytope_vertices(n, r, 0.5).unwrap();
        let mut points = Vec::new();
        for i in 0..n {
            for s in [-1.0, 1.0] {
                let mut p = DVector::zeros(n);
                p[i] = s * r;
                points.push(p);
            }
        }
        let cloud = Body::point_masses(&vec![0.5; 2 * n], &points).unwrap();
        assert_matrix_close!(
            *cloud.mass_tensor(),
            *body.mass_tensor(),
            sum_tol(2 * n, r * r),
            "N={n}"
        );
        assert_close!(body.mass(), n as f64, 0.0);
    }
}

#[test]
fn regular_simplex_positions_are_regular_and_centred_n1_to_n7() {
    for n in 1..=7 {
        let r = 1.3;
        let points = regular_simplex_positions(n, r).unwrap();
        assert_eq!(points.len(), n + 1);
        let edge = r * (2.0 * (n as f64 + 1.0) / n as f64).sqrt();
        let centroid = points.iter().fold(DVector::zeros(n), |acc, p| acc + p);
        assert!(
            centroid.norm() <= 16.0 * EPS * r,
            "N={n}: centroid {centroid}"
        );
        for (a, p) in points.iter().enumerate() {
            assert_close!(p.norm(), r, 8.0 * EPS * r, "N={n} |v_{a}|");
            for q in &points[a + 1..] {
                assert_close!((p - q).norm(), edge, 8.0 * EPS * edge, "N={n} edge");
            }
        }
        let body = Body::regular_simplex_vertices(n, r, 2.0).unwrap();
        let cloud = Body::point_masses(&vec![2.0; n + 1], &points).unwrap();
        assert_matrix_close!(
            *cloud.mass_tensor(),
            *body.mass_tensor(),
            sum_tol(4 * (n + 1), r * r),
            "N={n}"
        );
    }
}

#[test]
fn regular_polytopes_have_isotropic_mass_tensor() {
    // The paper (after eq. 29): "for any homogeneous Platonic body, the half-axes of its
    // Poinsot inertia ellipsoid are equal", in all dimensions. Check the point-mass and
    // solid versions of simplex, cross-polytope and cube, built from explicit points.
    for n in 2..=6 {
        let simplex_points = regular_simplex_positions(n, 1.0).unwrap();
        let mut bodies = vec![
            Body::point_masses(&vec![1.0; n + 1], &simplex_points).unwrap(),
            Body::solid_simplex(&simplex_points, 1.0).unwrap(),
            Body::point_masses(&vec![1.0; 1 << n], &cuboid_corner_points(&vec![0.5; n])).unwrap(),
        ];
        let mut cross = Vec::new();
        for i in 0..n {
            for s in [-1.0, 1.0] {
                let mut p = DVector::zeros(n);
                p[i] = s;
                cross.push(p);
            }
        }
        bodies.push(Body::point_masses(&vec![1.0; 2 * n], &cross).unwrap());
        for (k, b) in bodies.iter().enumerate() {
            let j = b.mass_tensor();
            let iso = DMatrix::identity(n, n) * (j.trace() / n as f64);
            assert_matrix_close!(*j, iso, 64.0 * EPS * max_abs(j), "N={n} body {k}");
        }
    }
}

#[test]
fn pentachoron_has_the_diagonal_mass_tensor() {
    let (a, b, c, d) = (1.1, 0.7, 1.9, 1.3);
    let body = Body::pentachoron(a, b, c, d).unwrap();
    let expected = DMatrix::from_diagonal(&DVector::from_vec(vec![
        1.25 * a * a,
        1.25 * b * b,
        1.25 * c * c,
        1.25 * d * d,
    ]));
    assert_matrix_close!(
        *body.mass_tensor(),
        expected,
        8.0 * EPS * 1.25 * d * d * 4.0,
        "eq 73"
    );
    assert_eq!(body.mass(), 5.0);
}

#[test]
fn textbook_3d_principal_moments_via_plane_moments() {
    // plane_moments order: 12, 13, 23, so I_1 = J_2 + J_3 = pm[2], I_2 = pm[1], I_3 = pm[0].
    let classical = |b: &Body| {
        let pm = b.plane_moments();
        (pm[2], pm[1], pm[0])
    };
    // Solid box with edges (2, 3, 4): I_1 = m (3² + 4²)/12 etc.
    let bx = Body::solid_cuboid(&[1.0, 1.5, 2.0], 0.8).unwrap();
    let m = bx.mass();
    assert_close!(m, 0.8 * 24.0, 1e-14 * m);
    let (i1, i2, i3) = classical(&bx);
    assert_close!(i1, m * (9.0 + 16.0) / 12.0, 1e-14 * i1);
    assert_close!(i2, m * (4.0 + 16.0) / 12.0, 1e-14 * i2);
    assert_close!(i3, m * (4.0 + 9.0) / 12.0, 1e-14 * i3);
    // Solid ellipsoid (1, 2, 3): I_1 = m (b² + c²)/5.
    let el = Body::solid_ellipsoid(&[1.0, 2.0, 3.0], 1.0).unwrap();
    let m = el.mass();
    assert_close!(m, 4.0 * PI / 3.0 * 6.0, 1e-14 * m);
    let (i1, i2, i3) = classical(&el);
    assert_close!(i1, m * 13.0 / 5.0, 1e-14 * i1);
    assert_close!(i2, m * 10.0 / 5.0, 1e-14 * i2);
    assert_close!(i3, m * 5.0 / 5.0, 1e-14 * i3);
    // Solid sphere: 2 m R²/5; hollow sphere: 2 m R²/3.
    let r = 1.7;
    let ball = Body::solid_ball(3, r, 2.0).unwrap();
    let (i1, i2, i3) = classical(&ball);
    for i in [i1, i2, i3] {
        assert_close!(i, 0.4 * ball.mass() * r * r, 1e-14 * i);
    }
    let shell = Body::hypersphere_shell(3, r, 2.0).unwrap();
    assert_close!(shell.mass(), 2.0 * 4.0 * PI * r * r, 1e-14 * shell.mass());
    let (i1, _, _) = classical(&shell);
    assert_close!(i1, 2.0 / 3.0 * shell.mass() * r * r, 1e-14 * i1);
    // Thin rod limit: box with half-edges (L/2, ε, ε) → I_⊥ = m L²/12, I_∥ → 0.
    let (len, eps) = (2.5, 1e-7);
    let rod = Body::solid_cuboid(&[len / 2.0, eps, eps], 1.0).unwrap();
    let (i1, i2, i3) = classical(&rod);
    let m = rod.mass();
    assert_close!(i2, m * len * len / 12.0, 1e-13 * i2);
    assert_close!(i3, m * len * len / 12.0, 1e-13 * i3);
    assert!(i1 <= 1e-13 * i2);
    // 2D: disc polar moment m R²/2, ring m R².
    let disc = Body::solid_ball(2, r, 1.0).unwrap();
    assert_close!(
        disc.plane_moments()[0],
        0.5 * disc.mass() * r * r,
        1e-14 * disc.mass()
    );
    let ring = Body::hypersphere_shell(2, r, 1.0).unwrap();
    assert_close!(ring.mass(), 2.0 * PI * r, 1e-14);
    assert_close!(
        ring.plane_moments()[0],
        ring.mass() * r * r,
        1e-14 * ring.mass()
    );
}

#[test]
fn standard_simplex_matches_canonical_covariance() {
    // ∫ x_i x_j dV over conv(0, e_1, …, e_N) = (1 + δ_ij)/(N+2)!.
    for n in 1..=7 {
        let mut vertices = vec![DVector::zeros(n)];
        for i in 0..n {
            let mut e = DVector::zeros(n);
            e[i] = 1.0;
            vertices.push(e);
        }
        let body = Body::solid_simplex(&vertices, 1.0).unwrap();
        let nf: f64 = (1..=n).map(|k| k as f64).product();
        assert_close!(body.volume().unwrap(), 1.0 / nf, 4.0 * EPS / nf);
        let c = nf * (n as f64 + 1.0) * (n as f64 + 2.0);
        let expected = DMatrix::from_fn(n, n, |i, j| if i == j { 2.0 } else { 1.0 } / c);
        let about_origin = body.mass_tensor_about(&DVector::zeros(n)).unwrap();
        assert_matrix_close!(about_origin, expected, 64.0 * EPS / c, "N={n}");
    }
}

#[test]
fn regular_solid_simplex_matches_references_table() {
    // J = m a²/(2(N+1)(N+2)) for edge a : triangle polar moment m a²/12,
    // tetrahedron axis moment m a²/20, 5-cell J = m a²/60 and plane moment m a²/30.
    for n in 2..=6 {
        let r = 0.9;
        let points = regular_simplex_positions(n, r).unwrap();
        let body = Body::solid_simplex(&points, 1.0).unwrap();
        let a2 = r * r * 2.0 * (n as f64 + 1.0) / n as f64;
        let nf = n as f64;
        let want = body.mass() * a2 / (2.0 * (nf + 1.0) * (nf + 2.0));
        for i in 0..n {
            assert_close!(
                body.principal_second_moments()[i],
                want,
                1e-13 * want,
                "N={n}"
            );
        }
        let pm = body.principal_plane_moments()[0];
        match n {
            2 => assert_close!(pm, body.mass() * a2 / 12.0, 1e-13 * pm),
            3 => assert_close!(pm, body.mass() * a2 / 20.0, 1e-13 * pm),
            4 => assert_close!(pm, body.mass() * a2 / 30.0, 1e-13 * pm),
            _ => {}
        }
    }
}

#[test]
fn unit_ball_volume_matches_gamma_formula_and_known_values() {
    // V_N = π^{N/2}/Γ(N/2 + 1) (paper eq. 99) with Γ from the independent half-integer
    // recurrence; and the classical values.
    for n in 0..=12 {
        let want = PI.powf(n as f64 / 2.0) / gamma_half(n + 2);
        assert_close!(unit_ball_volume(n), want, 1e-14 * want, "N={n}");
    }
    let known = [
        1.0,
        2.0,
        PI,
        4.0 * PI / 3.0,
        PI * PI / 2.0,
        8.0 * PI * PI / 15.0,
        PI.powi(3) / 6.0,
    ];
    for (n, v) in known.iter().enumerate() {
        assert_close!(unit_ball_volume(n), *v, 4.0 * EPS * v);
    }
}

#[test]
fn planes_are_lexicographic() {
    let planes = |n| pairs(n).collect::<Vec<_>>();
    assert_eq!(
        planes(4),
        vec![(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]
    );
    assert_eq!(planes(3), vec![(0, 1), (0, 2), (1, 2)]);
    assert_eq!(planes(5).len(), 10);
    assert!(planes(1).is_empty());
}

/// A varied set of bodies in dimension n, all in general position (rotated and moved).
fn assorted_bodies(n: usize, seed: u64) -> Vec<Body> {
    let mut r = rng(seed);
    let q = random_rotation(n, &mut r);
    let d = DVector::from_fn(n, |_, _| gaussian(&mut r));
    let half: Vec<f64> = (0..n).map(|i| 0.3 + 0.2 * i as f64).collect();
    let simplex: Vec<DVector<f64>> = (0..=n)
        .map(|_| DVector::from_fn(n, |_, _| gaussian(&mut r)))
        .collect();
    let cloud: Vec<DVector<f64>> = (0..7)
        .map(|_| DVector::from_fn(n, |_, _| 2.0 * gaussian(&mut r)))
        .collect();
    let masses: Vec<f64> = (0..7).map(|k| 0.5 + k as f64).collect();
    let (unit, kuhn, _) = kuhn_triangulation(n);
    let mesh_vertices: Vec<DVector<f64>> = unit.iter().map(|v| &q * v + &d).collect();
    let bodies = vec![
        Body::point_masses(&masses, &cloud).unwrap(),
        Body::cuboid_vertices(&half, 1.0).unwrap(),
        Body::regular_simplex_vertices(n, 1.0, 1.0).unwrap(),
        Body::cross_polytope_vertices(n, 1.0, 1.0).unwrap(),
        Body::solid_cuboid(&half, 1.0).unwrap(),
        Body::solid_ellipsoid(&half, 1.0).unwrap(),
        Body::solid_ball(n, 1.0, 1.0).unwrap(),
        Body::hypersphere_shell(n, 1.0, 1.0).unwrap(),
        Body::solid_simplex(&simplex, 1.0).unwrap(),
        Body::simplicial_mesh(&mesh_vertices, &kuhn, 1.0, SimplexOrientation::Unsigned).unwrap(),
    ];
    bodies
        .into_iter()
        .map(|b| b.placed(&q, &d).unwrap())
        .collect()
}

#[test]
fn mass_tensors_are_symmetric_positive_semidefinite() {
    for n in 2..=6 {
        for (k, b) in assorted_bodies(n, 40 + n as u64).iter().enumerate() {
            let j = b.mass_tensor();
            assert_eq!(*j, j.transpose(), "N={n} body {k}: not exactly symmetric");
            let moments = b.principal_second_moments();
            assert!(
                moments[0] >= -1e-14 * moments[n - 1],
                "N={n} body {k}: eigenvalue {}",
                moments[0]
            );
            assert!(b.mass() > 0.0);
        }
    }
    let pentachoron = Body::pentachoron(1.0, 2.0, 3.0, 4.0).unwrap();
    assert!(pentachoron.principal_second_moments()[0] > 0.0);
}

#[test]
fn four_d_principal_plane_moments_satisfy_the_weyl_identity() {
    // I12 + I34 = I13 + I24 = I14 + I23 = tr J (Parker 2024).
    for (k, b) in assorted_bodies(4, 7).iter().enumerate() {
        let pm = b.principal_plane_moments(); // 12, 13, 14, 23, 24, 34
        let tr = b.mass_tensor().trace();
        let tol = 1e-13 * tr;
        assert_close!(pm[0] + pm[5], tr, tol, "body {k}: I12 + I34");
        assert_close!(pm[1] + pm[4], tr, tol, "body {k}: I13 + I24");
        assert_close!(pm[2] + pm[3], tr, tol, "body {k}: I14 + I23");
    }
}

#[test]
fn principal_frame_diagonalises_j_with_a_rotation() {
    for n in 2..=6 {
        for b in assorted_bodies(n, 90 + n as u64) {
            let (moments, axes) = b.principal_frame();
            assert_close!(axes.determinant(), 1.0, 1e-12);
            let back = &axes * DMatrix::from_diagonal(&moments) * axes.transpose();
            assert_matrix_close!(
                back,
                *b.mass_tensor(),
                1e-12 * max_abs(b.mass_tensor()),
                "N={n}"
            );
            for i in 1..n {
                assert!(moments[i - 1] <= moments[i]);
            }
        }
    }
}

#[test]
fn with_mass_rescales_j_and_density() {
    let b = Body::solid_ellipsoid(&[1.0, 2.0, 0.5, 1.5], 3.0).unwrap();
    let heavier = b.with_mass(2.0 * b.mass()).unwrap();
    assert_close!(heavier.mass(), 2.0 * b.mass(), 0.0);
    assert_matrix_close!(*heavier.mass_tensor(), b.mass_tensor() * 2.0, 0.0, "J");
    assert_eq!(heavier.volume(), b.volume());
    assert_close!(heavier.density().unwrap(), 6.0, 1e-14);
    assert_eq!(b.center_of_mass(), heavier.center_of_mass());
}

#[test]
fn composite_of_two_halves_is_the_whole_box() {
    for n in 2..=5 {
        let half: Vec<f64> = (0..n).map(|i| 0.5 + 0.25 * i as f64).collect();
        let mut halved = half.clone();
        halved[0] /= 2.0;
        let piece = Body::solid_cuboid(&halved, 1.1).unwrap();
        let ident = DMatrix::identity(n, n);
        let mut left = DVector::zeros(n);
        left[0] = -halved[0];
        let right = -&left;
        let whole = Body::composite(&[
            piece.placed(&ident, &left).unwrap(),
            piece.placed(&ident, &right).unwrap(),
        ])
        .unwrap();
        let exact = Body::solid_cuboid(&half, 1.1).unwrap();
        assert_matrix_close!(
            *whole.mass_tensor(),
            *exact.mass_tensor(),
            8.0 * EPS * max_abs(exact.mass_tensor()),
            "N={n}"
        );
        assert_close!(
            whole.volume().unwrap(),
            exact.volume().unwrap(),
            4.0 * EPS * whole.volume().unwrap()
        );
        assert!(whole.center_of_mass().norm() <= 4.0 * EPS);
    }
}

#[test]
fn composite_of_orthant_cubes_is_the_big_cube() {
    for n in 2..=5 {
        let small = Body::solid_cuboid(&vec![0.5; n], 1.0).unwrap();
        let ident = DMatrix::identity(n, n);
        let parts: Vec<Body> = (0..1usize << n)
            .map(|bits| {
                let offset =
                    DVector::from_fn(n, |i, _| if (bits >> i) & 1 == 1 { 0.5 } else { -0.5 });
                small.placed(&ident, &offset).unwrap()
            })
            .collect();
        let whole = Body::composite(&parts).unwrap();
        let exact = Body::solid_cuboid(&vec![1.0; n], 1.0).unwrap();
        assert_matrix_close!(
            *whole.mass_tensor(),
            *exact.mass_tensor(),
            sum_tol(1 << n, max_abs(exact.mass_tensor())),
            "N={n}"
        );
    }
}

#[test]
fn composite_with_rotated_parts_matches_mesh_of_rotated_vertices() {
    // Place two boxes with random rotations and offsets; compare with the Kuhn meshes of the
    // transformed box corners, which never call `rotated`.
    for n in 2..=5 {
        let mut r = rng(70 + n as u64);
        let (unit, kuhn, _) = kuhn_triangulation(n);
        let mut parts = Vec::new();
        let mut vertices = Vec::new();
        let mut simplices = Vec::new();
        for p in 0..2 {
            let half: Vec<f64> = (0..n).map(|i| 0.3 + 0.1 * (i + p) as f64).collect();
            let q = random_rotation(n, &mut r);
            let d = DVector::from_fn(n, |_, _| 3.0 * gaussian(&mut r));
            parts.push(
                Body::solid_cuboid(&half, 1.0)
                    .unwrap()
                    .placed(&q, &d)
                    .unwrap(),
            );
            let base = vertices.len();
            for v in &unit {
                let local = DVector::from_fn(n, |i, _| (2.0 * v[i] - 1.0) * half[i]);
                vertices.push(&q * local + &d);
            }
            for s in &kuhn {
                simplices.push(s.iter().map(|&k| base + k).collect::<Vec<usize>>());
            }
        }
        let composite = Body::composite(&parts).unwrap();
        let mesh = Body::simplicial_mesh(&vertices, &simplices, 1.0, SimplexOrientation::Unsigned)
            .unwrap();
        let scale = max_abs(composite.mass_tensor());
        let diff = max_abs_diff(composite.mass_tensor(), mesh.mass_tensor());
        assert!(diff <= 1e-12 * scale, "N={n}: {diff:e}");
        assert!((composite.center_of_mass() - mesh.center_of_mass()).norm() <= 1e-12);
        assert_close!(composite.volume().unwrap(), mesh.volume().unwrap(), 1e-13);
    }
}

#[test]
fn composite_with_a_shell_has_no_volume() {
    let shell = Body::hypersphere_shell(3, 1.0, 1.0).unwrap();
    let ball = Body::solid_ball(3, 0.5, 1.0).unwrap();
    let both = Body::composite(&[shell.clone(), ball.clone()]).unwrap();
    assert!(both.volume().is_none());
    assert_close!(both.mass(), shell.mass() + ball.mass(), 1e-14);
}
