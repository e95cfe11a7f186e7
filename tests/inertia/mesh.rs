//! Simplicial meshes: exact reproduction of the cuboid by the Kuhn triangulation, closed
//! boundary meshes (convex and non-convex, apex inside and outside), and convergence to the
//! ball under refinement.
use crate::common::{EPS, kuhn_triangulation, max_abs, max_abs_diff};
use nalgebra::{DMatrix, DVector};
use rotorflow::inertia::{Body, InertiaError, SimplexOrientation};

fn half_edges(n: usize) -> Vec<f64> {
    (0..n).map(|i| 0.75 + 0.5 * i as f64).collect()
}

/// Kuhn vertices (0/1 patterns) mapped onto the box with the given half-edges, shifted so the
/// box is off-centre (the centre of mass is then a non-trivial output).
fn box_vertices(unit: &[DVector<f64>], half: &[f64], offset: &DVector<f64>) -> Vec<DVector<f64>> {
    unit.iter()
        .map(|v| DVector::from_fn(half.len(), |i, _| (2.0 * v[i] - 1.0) * half[i] + offset[i]))
        .collect()
}

/// Tolerance for the exact Kuhn comparisons: 8 ulp of the largest entry. The Kuhn vertices
/// are box corners, so every simplex's moments are computed from a few exact-ish products;
/// a worst-case rounding bound grows like N! ulp, but the observed error is ≤ 0.1 ulp for
/// N = 2…5 (the sums of N! equal-sized terms round benignly), so 8 ulp leaves margin while
/// still meaning "exact".
fn kuhn_tolerance(_n: usize, scale: f64) -> f64 {
    8.0 * EPS * scale
}

#[test]
fn kuhn_triangulation_reproduces_cuboid_exactly_n2_to_n5() {
    for n in 2..=5 {
        let (unit, simplices, _) = kuhn_triangulation(n);
        let half = half_edges(n);
        let offset = DVector::from_fn(n, |i, _| 0.25 * i as f64 - 0.3);
        let vertices = box_vertices(&unit, &half, &offset);
        let mesh = Body::simplicial_mesh(&vertices, &simplices, 1.3, SimplexOrientation::Unsigned)
            .unwrap();
        let exact = Body::solid_cuboid(&half, 1.3).unwrap();
        let scale = max_abs(exact.mass_tensor());
        let tol = kuhn_tolerance(n, scale);
        let err = max_abs_diff(mesh.mass_tensor(), exact.mass_tensor());
        assert!(err <= tol, "N={n}: J error {err:e} > {tol:e}");
        assert_close!(
            mesh.volume().unwrap(),
            exact.volume().unwrap(),
            kuhn_tolerance(n, exact.volume().unwrap())
        );
        assert_close!(mesh.mass(), exact.mass(), kuhn_tolerance(n, exact.mass()));
        for i in 0..n {
            assert_close!(mesh.center_of_mass()[i], offset[i], kuhn_tolerance(n, 1.0));
        }
    }
}

#[test]
fn kuhn_triangulation_signed_needs_consistent_orientation() {
    for n in 2..=5 {
        let (unit, simplices, signs) = kuhn_triangulation(n);
        let half = half_edges(n);
        let vertices = box_vertices(&unit, &half, &DVector::zeros(n));
        // As listed, half of the Kuhn simplices are negatively oriented (det = sign σ), so
        // their signed volumes cancel exactly.
        let err = Body::simplicial_mesh(&vertices, &simplices, 1.0, SimplexOrientation::Signed)
            .unwrap_err();
        assert!(
            matches!(err, InertiaError::ZeroMeshVolume { .. }),
            "N={n}: {err:?}"
        );
        // Reoriented (swap the last two vertices of each odd simplex): a consistently
        // oriented tiling, which the signed sum handles exactly.
        let oriented: Vec<Vec<usize>> = simplices
            .iter()
            .zip(&signs)
            .map(|(s, &sign)| {
                let mut s = s.clone();
                if sign < 0.0 {
                    s.swap(n - 1, n);
                }
                s
            })
            .collect();
        let mesh =
            Body::simplicial_mesh(&vertices, &oriented, 1.0, SimplexOrientation::Signed).unwrap();
        let exact = Body::solid_cuboid(&half, 1.0).unwrap();
        let err = max_abs_diff(mesh.mass_tensor(), exact.mass_tensor());
        assert!(
            err <= kuhn_tolerance(n, max_abs(exact.mass_tensor())),
            "N={n}: {err:e}"
        );
        // The opposite global orientation is accepted too.
        let reversed: Vec<Vec<usize>> = oriented
            .iter()
            .map(|s| {
                let mut s = s.clone();
                s.swap(0, 1);
                s
            })
            .collect();
        let mesh =
            Body::simplicial_mesh(&vertices, &reversed, 1.0, SimplexOrientation::Signed).unwrap();
        let err = max_abs_diff(mesh.mass_tensor(), exact.mass_tensor());
        assert!(
            err <= kuhn_tolerance(n, max_abs(exact.mass_tensor())),
            "N={n}: {err:e}"
        );
    }
}

/// Outward-oriented triangulated boundary of the box: each facet xₐ = ±hₐ is an
/// (N−1)-box, Kuhn-triangulated; orientation fixed so the cone from the centre is positive.
fn box_boundary(half: &[f64]) -> (Vec<DVector<f64>>, Vec<Vec<usize>>) {
    let n = half.len();
    let (unit, simplices, _) = kuhn_triangulation(n - 1);
    let mut vertices = Vec::new();
    let mut facets = Vec::new();
    for axis in 0..n {
        for side in [-1.0, 1.0] {
            let base = vertices.len();
            for u in &unit {
                let mut v = DVector::zeros(n);
                let mut k = 0;
                for i in 0..n {
                    if i == axis {
                        v[i] = side * half[i];
                    } else {
                        v[i] = (2.0 * u[k] - 1.0) * half[i];
                        k += 1;
                    }
                }
                vertices.push(v);
            }
            for s in &simplices {
                let mut facet: Vec<usize> = s.iter().map(|&k| base + k).collect();
                let m = DMatrix::from_fn(n, n, |r, c| vertices[facet[c]][r]);
                if m.determinant() < 0.0 {
                    facet.swap(0, 1);
                }
                facets.push(facet);
            }
        }
    }
    (vertices, facets)
}

#[test]
fn closed_box_boundary_reproduces_cuboid_n2_to_n5() {
    for n in 2..=5 {
        let half = half_edges(n);
        let (vertices, facets) = box_boundary(&half);
        let mesh = Body::closed_boundary_mesh(&vertices, &facets, 0.9).unwrap();
        let exact = Body::solid_cuboid(&half, 0.9).unwrap();
        // The boundary has 2N (N−1)! facets; same error budget as the Kuhn test.
        let err = max_abs_diff(mesh.mass_tensor(), exact.mass_tensor());
        assert!(
            err <= kuhn_tolerance(n, max_abs(exact.mass_tensor())),
            "N={n}: {err:e}"
        );
        assert_close!(
            mesh.volume().unwrap(),
            exact.volume().unwrap(),
            kuhn_tolerance(n, exact.volume().unwrap())
        );
    }
}

fn v2(x: f64, y: f64) -> DVector<f64> {
    DVector::from_vec(vec![x, y])
}

fn rectangle(x0: f64, x1: f64, y0: f64, y1: f64) -> Body {
    Body::solid_cuboid(&[(x1 - x0) / 2.0, (y1 - y0) / 2.0], 1.0)
        .unwrap()
        .translated(&v2((x0 + x1) / 2.0, (y0 + y1) / 2.0))
        .unwrap()
}

/// The U-shaped polygon (counter-clockwise); its vertex mean (1.5, 1.75) lies in the notch,
/// outside the polygon, so some cones from the apex are negative.
fn u_polygon() -> Vec<DVector<f64>> {
    vec![
        v2(0.0, 0.0),
        v2(3.0, 0.0),
        v2(3.0, 3.0),
        v2(2.0, 3.0),
        v2(2.0, 1.0),
        v2(1.0, 1.0),
        v2(1.0, 3.0),
        v2(0.0, 3.0),
    ]
}

fn u_as_rectangles() -> Body {
    Body::composite(&[
        rectangle(0.0, 3.0, 0.0, 1.0),
        rectangle(0.0, 1.0, 1.0, 3.0),
        rectangle(2.0, 3.0, 1.0, 3.0),
    ])
    .unwrap()
}

#[test]
fn nonconvex_polygon_with_apex_outside_matches_rectangles() {
    let vertices = u_polygon();
    let edges: Vec<[usize; 2]> = (0..8).map(|k| [k, (k + 1) % 8]).collect();
    let mesh = Body::closed_boundary_mesh(&vertices, &edges, 1.0).unwrap();
    let exact = u_as_rectangles();
    assert_close!(mesh.volume().unwrap(), 7.0, 1e-14);
    assert_matrix_close!(
        *mesh.mass_tensor(),
        *exact.mass_tensor(),
        1e-13,
        "U polygon"
    );
    assert_close!(mesh.center_of_mass()[0], 1.5, 1e-14);
    assert_close!(mesh.center_of_mass()[1], exact.center_of_mass()[1], 1e-14);
    // Clockwise listing (the other global orientation) gives the same body.
    let reversed: Vec<[usize; 2]> = edges.iter().map(|e| [e[1], e[0]]).collect();
    let mesh2 = Body::closed_boundary_mesh(&vertices, &reversed, 1.0).unwrap();
    assert_matrix_close!(
        *mesh2.mass_tensor(),
        *exact.mass_tensor(),
        1e-13,
        "U reversed"
    );
}

#[test]
fn nonconvex_prism_with_apex_outside_matches_boxes() {
    // The U polygon extruded to z ∈ [0, 2]. Top/bottom faces are triangulated through the
    // polygon's own vertices; sides are two triangles per edge. Outward orientation.
    let poly = u_polygon();
    let mut vertices = Vec::new();
    for z in [0.0, 2.0] {
        for p in &poly {
            vertices.push(DVector::from_vec(vec![p[0], p[1], z]));
        }
    }
    let top_triangles: [[usize; 3]; 6] = [
        [0, 1, 4],
        [1, 2, 4],
        [2, 3, 4],
        [0, 4, 5],
        [0, 5, 7],
        [5, 6, 7],
    ];
    // Check the polygon triangulation covers area 7 with positive triangles only.
    let mut area = 0.0;
    for t in &top_triangles {
        let (a, b, c) = (&poly[t[0]], &poly[t[1]], &poly[t[2]]);
        let signed = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
        area += signed;
        assert!(signed >= 0.0, "triangle {t:?} is clockwise");
    }
    assert_close!(area, 7.0, 1e-14);
    let mut facets: Vec<[usize; 3]> = Vec::new();
    for t in &top_triangles {
        facets.push([t[0] + 8, t[1] + 8, t[2] + 8]); // top, normal +z
        facets.push([t[0], t[2], t[1]]); // bottom, normal −z
    }
    for k in 0..8 {
        let (p, q) = (k, (k + 1) % 8);
        facets.push([p, q, q + 8]);
        facets.push([p, q + 8, p + 8]);
    }
    let mesh = Body::closed_boundary_mesh(&vertices, &facets, 1.0).unwrap();
    let boxes: Vec<Body> = [
        (0.0, 3.0, 0.0, 1.0),
        (0.0, 1.0, 1.0, 3.0),
        (2.0, 3.0, 1.0, 3.0),
    ]
    .iter()
    .map(|&(x0, x1, y0, y1)| {
        Body::solid_cuboid(&[(x1 - x0) / 2.0, (y1 - y0) / 2.0, 1.0], 1.0)
            .unwrap()
            .translated(&DVector::from_vec(vec![
                (x0 + x1) / 2.0,
                (y0 + y1) / 2.0,
                1.0,
            ]))
            .unwrap()
    })
    .collect();
    let exact = Body::composite(&boxes).unwrap();
    assert_close!(mesh.volume().unwrap(), 14.0, 1e-13);
    assert_matrix_close!(*mesh.mass_tensor(), *exact.mass_tensor(), 1e-12, "U prism");
    for i in 0..3 {
        assert_close!(mesh.center_of_mass()[i], exact.center_of_mass()[i], 1e-13);
    }
}

/// Polytope inscribed in the sphere of radius R: the boundary of the cube [−1, 1]^N, each
/// facet cut into kᴺ⁻¹ cells and each cell Kuhn-triangulated, with all vertices pushed
/// radially onto the sphere; the N-simplices are the cones from the origin. Returns the
/// unsigned-volume mesh body.
fn inscribed_polytope(n: usize, k: usize, radius: f64) -> Body {
    let (unit, cells, _) = kuhn_triangulation(n - 1);
    let mut vertices = vec![DVector::zeros(n)];
    let mut simplices: Vec<Vec<usize>> = Vec::new();
    let grid = |idx: &[usize]| -> Vec<f64> {
        idx.iter()
            .map(|&i| -1.0 + 2.0 * i as f64 / k as f64)
            .collect()
    };
    let cell_count = k.pow((n - 1) as u32);
    for axis in 0..n {
        for side in [-1.0, 1.0] {
            for cell in 0..cell_count {
                let mut corner = vec![0usize; n - 1];
                let mut c = cell;
                for x in corner.iter_mut() {
                    *x = c % k;
                    c /= k;
                }
                for s in &cells {
                    let mut simplex = vec![0usize];
                    for &u in s {
                        let idx: Vec<usize> = (0..n - 1)
                            .map(|d| corner[d] + unit[u][d] as usize)
                            .collect();
                        let g = grid(&idx);
                        let mut v = DVector::zeros(n);
                        let mut m = 0;
                        for i in 0..n {
                            if i == axis {
                                v[i] = side;
                            } else {
                                v[i] = g[m];
                                m += 1;
                            }
                        }
                        let v = &v * (radius / v.norm());
                        vertices.push(v);
                        simplex.push(vertices.len() - 1);
                    }
                    simplices.push(simplex);
                }
            }
        }
    }
    Body::simplicial_mesh(&vertices, &simplices, 1.0, SimplexOrientation::Unsigned).unwrap()
}

#[test]
fn inscribed_polytope_converges_to_ball_n2_to_n5() {
    let radius = 1.2;
    // (N, refinement levels, bound on the final relative J error = the observed error of the
    // finest level rounded up, required error ratio on the last refinement step). The
    // observed last ratios are 3.99, 3.93, 3.59 and 2.55: N = 5 at k = 2 → 4 is still
    // pre-asymptotic (k = 4 → 8 gives 3.47 with 10⁶ simplices; see the ignored test below).
    for (n, levels, bound, last_ratio) in [
        (2usize, 6u32, 1e-3, 3.0),
        (3, 5, 1e-2, 3.0),
        (4, 4, 6e-2, 3.0),
        (5, 3, 0.3, 2.0),
    ] {
        let ball = Body::solid_ball(n, radius, 1.0).unwrap();
        let mut previous: Option<(f64, f64)> = None;
        for level in 0..levels {
            let k = 1usize << level;
            let mesh = inscribed_polytope(n, k, radius);
            let j_err =
                max_abs_diff(mesh.mass_tensor(), ball.mass_tensor()) / max_abs(ball.mass_tensor());
            let v_err =
                (mesh.volume().unwrap() - ball.volume().unwrap()).abs() / ball.volume().unwrap();
            // The inscribed polytope is inside the ball: its volume is smaller.
            assert!(mesh.volume().unwrap() < ball.volume().unwrap());
            eprintln!("N={n} k={k}: J error {j_err:e}, volume error {v_err:e}");
            if let Some((pj, pv)) = previous {
                // Second-order convergence in the mesh size h ~ 1/k: asymptotically each
                // halving of h cuts the error by 4. Require a cut by at least 1.5 on every
                // step and by `last_ratio` on the last (the coarse levels are
                // pre-asymptotic, more so in higher N).
                let need = if level + 1 == levels { last_ratio } else { 1.5 };
                assert!(
                    pj / j_err >= need && pv / v_err >= need,
                    "N={n} k={k}: J error {pj:e} -> {j_err:e}, volume error {pv:e} -> {v_err:e}"
                );
            }
            previous = Some((j_err, v_err));
        }
        let (j_err, _) = previous.unwrap();
        assert!(j_err < bound, "N={n}: final J error {j_err:e}");
    }
}

/// N = 5 one level further (983 040 simplices): the ratio k = 4 → 8 is 3.47, approaching
/// the asymptotic 4. Ignored by `cargo test` (about 10 s in the test profile, opt-level 2);
/// `.ci/run` runs it with `cargo test --all-features --test inertia -- --ignored`.
#[test]
#[ignore = "slow: 10^6 simplices"]
fn inscribed_polytope_converges_to_ball_n5_fine() {
    let ball = Body::solid_ball(5, 1.0, 1.0).unwrap();
    let err = |k| {
        let mesh = inscribed_polytope(5, k, 1.0);
        max_abs_diff(mesh.mass_tensor(), ball.mass_tensor()) / max_abs(ball.mass_tensor())
    };
    let (coarse, fine) = (err(4), err(8));
    eprintln!("N=5: k=4 {coarse:e}, k=8 {fine:e}, ratio {}", coarse / fine);
    assert!(coarse / fine >= 3.0);
}
