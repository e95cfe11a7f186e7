//! The paper's stated values for its bodies (eqs. 70–106, plus the tensor definitions of
//! eqs. 22–34 that they depend on), recomputed with the crate and compared.
//!
//! Each test computes the correct value with the crate, then asserts either that the paper's
//! form agrees ("is right") or that it differs ("is wrong"), and, where the paper's number
//! is a different normalisation of the contracted matrix 𝕀, which one it matches. The
//! summary is ERRATA_INERTIA.md.
//!
//! Literal conventions (the book's Conventions chapter): Iⁱʲᵏˡ from eq. (22) with the ½, and 𝕀 from the literal
//! Levi-Civita contraction, 𝕀 = 2 (N − 2)! (tr J · 1 − J). Tolerances are relative 1e-12
//! for closed-form comparisons (a handful of roundings), and "differs" means a relative
//! difference above 1e-3 (the paper's errors are factors of 2 or more, or wrong signs).
use crate::common::{gamma_half, gauss_legendre, rng, simpson, uniform};
use nalgebra::{DMatrix, DVector};
use rotorflow::inertia::Body;
use rotorflow::inertia::bodies::{pentachoron_vertices, unit_ball_volume};
use rotorflow::inertia::tensor::{ContractedInertia, ContractionNormalization, RankFourTensor};
use std::f64::consts::PI;

const A: f64 = 1.1;
const B: f64 = 0.7;
const C: f64 = 1.9;
const D: f64 = 1.3;
const E: f64 = 0.6;

fn same(x: f64, y: f64) -> bool {
    (x - y).abs() <= 1e-12 * x.abs().max(y.abs()).max(1e-300)
}

fn differs(x: f64, y: f64) -> bool {
    (x - y).abs() > 1e-3 * x.abs().max(y.abs())
}

macro_rules! assert_same {
    ($x:expr, $y:expr, $($msg:tt)+) => {{
        let (x, y): (f64, f64) = ($x, $y);
        assert!(same(x, y), "expected equal ({}): {x:e} vs {y:e}", format!($($msg)+));
    }};
}

macro_rules! assert_differs {
    ($x:expr, $y:expr, $($msg:tt)+) => {{
        let (x, y): (f64, f64) = ($x, $y);
        assert!(differs(x, y), "expected a discrepancy ({}): {x:e} vs {y:e}", format!($($msg)+));
    }};
}

fn contracted(body: &Body, n: ContractionNormalization) -> ContractedInertia {
    ContractedInertia::from_mass_tensor(body.mass_tensor(), n).unwrap()
}

use ContractionNormalization::{AxisMoment, LeviCivita, PlaneSum};

/// Squares of (a, b, c, d) and the "sum of the other three" that the paper's diagonal
/// entries are built from: b²+c²+d², a²+c²+d², a²+b²+d², a²+b²+c².
fn others4(p: [f64; 4]) -> [f64; 4] {
    let s: f64 = p.iter().map(|x| x * x).sum();
    [
        s - p[0] * p[0],
        s - p[1] * p[1],
        s - p[2] * p[2],
        s - p[3] * p[3],
    ]
}

const PLANES4: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];

// ---------------------------------------------------------------------------------------
// Tensor definitions the body values depend on (eqs. 22–34)
// ---------------------------------------------------------------------------------------

#[test]
fn paper_eq_23_literal_contraction_is_twice_the_classical_tensor() {
    // 3D box: classical principal moments I_1 = J_2 + J_3 etc.; the literal eq. (23)
    // contraction gives twice that.
    let body = Body::solid_cuboid(&[A, B, C], 1.0).unwrap();
    let literal = RankFourTensor::from_mass_tensor(body.mass_tensor())
        .unwrap()
        .levi_civita_contraction()
        .unwrap();
    let j = body.mass_tensor();
    let classical = [
        j[(1, 1)] + j[(2, 2)],
        j[(0, 0)] + j[(2, 2)],
        j[(0, 0)] + j[(1, 1)],
    ];
    for p in 0..3 {
        assert_same!(literal[(p, p)], 2.0 * classical[p], "p={p}");
    }
}

#[test]
fn paper_eq_26_is_half_of_eq_24_and_its_fourth_line_is_misprinted() {
    let body = Body::solid_ellipsoid(&[A, B, C, D], 1.0).unwrap();
    let t = RankFourTensor::from_mass_tensor(body.mass_tensor()).unwrap();
    let i = |s: usize, tt: usize, k: usize, l: usize| t.get(s - 1, tt - 1, k - 1, l - 1);
    let jd: Vec<f64> = (0..4).map(|k| body.mass_tensor()[(k, k)]).collect();
    // The four lines of eq. (26) exactly as printed: −𝕀_α = sum of six components.
    let printed = [
        -(i(3, 2, 2, 3)
            + i(2, 3, 3, 2)
            + i(4, 2, 2, 4)
            + i(2, 4, 4, 2)
            + i(4, 3, 3, 4)
            + i(3, 4, 4, 3)),
        -(i(3, 1, 1, 3)
            + i(1, 3, 3, 1)
            + i(4, 1, 1, 4)
            + i(1, 4, 4, 1)
            + i(4, 3, 3, 4)
            + i(3, 4, 4, 3)),
        -(i(1, 2, 2, 1)
            + i(2, 1, 1, 2)
            + i(4, 2, 2, 4)
            + i(2, 4, 4, 2)
            + i(4, 1, 1, 4)
            + i(1, 4, 4, 1)),
        -(i(3, 2, 2, 3)
            + i(2, 3, 3, 2)
            + i(1, 2, 2, 1)
            + i(1, 4, 4, 1)
            + i(1, 3, 3, 1)
            + i(3, 1, 1, 3)),
    ];
    let literal = contracted(&body, LeviCivita).axis_values();
    let plane_sum = contracted(&body, PlaneSum).axis_values();
    let tr: f64 = jd.iter().sum();
    for p in 0..3 {
        // Lines I–III: 2 (tr J − J_p) = the PlaneSum normalisation = half of literal eq. (24).
        assert_same!(printed[p], 2.0 * (tr - jd[p]), "line {}", p + 1);
        assert_same!(printed[p], plane_sum[p], "line {}", p + 1);
        assert_same!(2.0 * printed[p], literal[p], "line {}", p + 1);
    }
    // Line IV as printed contains I^{1441} (a plane through axis 4) and only one of the two
    // 12-components; it should read I^{1221} + I^{2112} instead of I^{1221} + I^{1441}.
    assert_differs!(printed[3], plane_sum[3], "line IV as printed");
    let corrected = -(i(3, 2, 2, 3)
        + i(2, 3, 3, 2)
        + i(1, 2, 2, 1)
        + i(2, 1, 1, 2)
        + i(1, 3, 3, 1)
        + i(3, 1, 1, 3));
    assert_same!(corrected, plane_sum[3], "line IV corrected");
}

#[test]
fn paper_eq_34_energy_is_twice_kinetic_energy() {
    // Rotation Ω in the plane e1∧e2 of a 3D body: the kinetic energy is ½ (J_1 + J_2) Ω²
    // = ½ I_3 Ω². The literal eq. (34) gives (J_1 + J_2) Ω².
    let body = Body::solid_ellipsoid(&[A, B, C], 1.0).unwrap();
    let t = RankFourTensor::from_mass_tensor(body.mass_tensor()).unwrap();
    let omega_rate = 0.8;
    let mut omega = DMatrix::zeros(3, 3);
    omega[(0, 1)] = omega_rate;
    omega[(1, 0)] = -omega_rate;
    let j = body.mass_tensor();
    let kinetic = 0.5 * (j[(0, 0)] + j[(1, 1)]) * omega_rate * omega_rate;
    let w = t.paper_energy(&omega).unwrap();
    assert_same!(w, 2.0 * kinetic, "eq 34");
    assert_differs!(w, kinetic, "eq 34");
}

#[test]
fn paper_eq_42_last_component_sign_is_misprinted() {
    // Eq. (42): "I^{2323} = I^{3232} = −I^{2332} = I^{3223}"; the last should be −I^{3223}.
    let body = Body::solid_ellipsoid(&[A, B, C], 1.0).unwrap();
    let t = RankFourTensor::from_mass_tensor(body.mass_tensor()).unwrap();
    let v = t.get(1, 2, 1, 2);
    assert_same!(v, t.get(2, 1, 2, 1), "I3232");
    assert_same!(v, -t.get(1, 2, 2, 1), "−I2332");
    assert_same!(v, -t.get(2, 1, 1, 2), "−I3223");
    assert_differs!(v, t.get(2, 1, 1, 2), "I3223 as printed");
    // And eq. (42)'s value ½ 𝕀_I with the classical 𝕀_I = J_2 + J_3 is right.
    let j = body.mass_tensor();
    assert_same!(v, 0.5 * (j[(1, 1)] + j[(2, 2)]), "½ I_1");
}

// ---------------------------------------------------------------------------------------
// §4.1 tesseract of unit point masses (eqs. 69–72)
// ---------------------------------------------------------------------------------------

#[test]
fn paper_eq_70_tesseract_rank4_components_are_wrong() {
    let p = [A, B, C, D];
    // Reading 1 (used throughout): vertices (±a, ±b, ±c, ±d), half-edges a…d as in §5.
    let body = Body::cuboid_vertices(&p, 1.0).unwrap();
    let t = RankFourTensor::from_mass_tensor(body.mass_tensor()).unwrap();
    // Reading 2: edges a…d, vertices (±a/2, …).
    let halves: Vec<f64> = p.iter().map(|x| x / 2.0).collect();
    let t2 = RankFourTensor::from_mass_tensor(
        Body::cuboid_vertices(&halves, 1.0).unwrap().mass_tensor(),
    )
    .unwrap();
    for &(x, y) in &PLANES4 {
        let paper = 4.0 * (p[x] * p[x] + p[y] * p[y]);
        let correct = t.get(x, y, x, y);
        assert_same!(
            correct,
            8.0 * (p[x] * p[x] + p[y] * p[y]),
            "I^{}{}{}{}",
            x + 1,
            y + 1,
            x + 1,
            y + 1
        );
        assert_same!(correct, 2.0 * paper, "plane {x}{y}");
        // Neither reading of the missing eq. (69) gives the paper's value.
        assert_same!(
            t2.get(x, y, x, y),
            0.5 * paper,
            "edge reading, plane {x}{y}"
        );
    }
    // Sign misprint: "I^{2424} = … = −4(b² + d²)"; the component is positive.
    assert!(t.get(1, 3, 1, 3) > 0.0);
    // Index misprint: "I^{1414} = −I^{4114} = −I^{1441} = I^{4114}"; I^{4114} cannot be
    // both; the last term is I^{4141}.
    assert_same!(t.get(3, 0, 0, 3), -t.get(0, 3, 0, 3), "I4114");
    assert_same!(t.get(3, 0, 3, 0), t.get(0, 3, 0, 3), "I4141");
}

#[test]
fn paper_eq_71_tesseract_contracted_matrix_is_half_of_eq_24() {
    let p = [A, B, C, D];
    let body = Body::cuboid_vertices(&p, 1.0).unwrap();
    let literal = contracted(&body, LeviCivita).axis_values();
    let plane_sum = contracted(&body, PlaneSum).axis_values();
    let o = others4(p);
    for k in 0..4 {
        let paper = 32.0 * o[k];
        assert_same!(literal[k], 64.0 * o[k], "literal k={k}");
        assert_differs!(literal[k], paper, "k={k}");
        // The paper's value is the eq. (26) normalisation.
        assert_same!(plane_sum[k], paper, "plane sum k={k}");
    }
}

#[test]
fn paper_eq_72_tesseract_mass_is_16_not_32() {
    let p = [A, B, C, D];
    let body = Body::cuboid_vertices(&p, 1.0).unwrap();
    assert_eq!(body.mass(), 16.0);
    assert_differs!(body.mass(), 32.0, "μ");
    let o = others4(p);
    let literal = contracted(&body, LeviCivita)
        .gyration_radii(body.mass())
        .unwrap();
    let axis = contracted(&body, AxisMoment)
        .gyration_radii(body.mass())
        .unwrap();
    for k in 0..4 {
        let paper = o[k];
        assert_same!(literal[k].powi(2), 4.0 * o[k], "literal L² k={k}");
        assert_differs!(literal[k].powi(2), paper, "k={k}");
        // With the true mass, the paper's L² is the axis-moment gyration radius.
        assert_same!(axis[k].powi(2), paper, "axis L² k={k}");
    }
}

// ---------------------------------------------------------------------------------------
// §4.2 the 5-cell (eqs. 73–76)
// ---------------------------------------------------------------------------------------

#[test]
fn paper_eq_73_five_cell_is_centred_and_regular_only_for_equal_parameters() {
    // Centred for every a, b, c, d.
    let points = pentachoron_vertices(A, B, C, D).unwrap();
    let centroid = points.iter().fold(DVector::zeros(4), |acc, p| acc + p) / 5.0;
    assert!(centroid.norm() <= 1e-15, "centroid {centroid}");
    // Not regular for unequal parameters: the ten edges differ.
    let edges = |pts: &[DVector<f64>]| {
        let mut e = Vec::new();
        for i in 0..5 {
            for j in i + 1..5 {
                e.push((&pts[i] - &pts[j]).norm());
            }
        }
        e
    };
    let e = edges(&points);
    let (lo, hi) = e
        .iter()
        .fold((f64::INFINITY, 0.0_f64), |(l, h), &x| (l.min(x), h.max(x)));
    assert_differs!(lo, hi, "edges of the a≠b≠c≠d 5-cell");
    // Regular for a = b = c = d = r: circumradius r, edge r √(5/2).
    let r = 1.3;
    let regular = pentachoron_vertices(r, r, r, r).unwrap();
    for p in &regular {
        assert_same!(p.norm(), r, "circumradius");
    }
    for x in edges(&regular) {
        assert_same!(x, r * 2.5f64.sqrt(), "edge");
    }
    // J = (5/4) diag(a², b², c², d²), mass 5.
    let body = Body::pentachoron(A, B, C, D).unwrap();
    for (k, x) in [A, B, C, D].iter().enumerate() {
        assert_same!(body.mass_tensor()[(k, k)], 1.25 * x * x, "J_{k}");
    }
    assert_eq!(body.mass(), 5.0);
}

#[test]
fn paper_eq_74_five_cell_rank4_components_are_right() {
    let p = [A, B, C, D];
    let body = Body::pentachoron(A, B, C, D).unwrap();
    let t = RankFourTensor::from_mass_tensor(body.mass_tensor()).unwrap();
    for &(x, y) in &PLANES4 {
        let paper = 5.0 / 8.0 * (p[x] * p[x] + p[y] * p[y]);
        assert_same!(
            t.get(x, y, x, y),
            paper,
            "I^{}{}{}{}",
            x + 1,
            y + 1,
            x + 1,
            y + 1
        );
    }
    // The paper lists I^{4141} (= I^{1414}, right) and omits I^{2323} = (5/8)(b² + c²).
    assert_same!(t.get(3, 0, 3, 0), 5.0 / 8.0 * (A * A + D * D), "I4141");
    assert_same!(t.get(1, 2, 1, 2), 5.0 / 8.0 * (B * B + C * C), "I2323");
}

#[test]
fn paper_eq_75_five_cell_contracted_matrix_matches_literal_eq_24() {
    let p = [A, B, C, D];
    let body = Body::pentachoron(A, B, C, D).unwrap();
    let literal = contracted(&body, LeviCivita).axis_values();
    let plane_sum = contracted(&body, PlaneSum).axis_values();
    let o = others4(p);
    for k in 0..4 {
        let paper = 5.0 * o[k];
        assert_same!(literal[k], paper, "k={k}");
        // … which is NOT the normalisation of eq. (71) (PlaneSum) for the tesseract.
        assert_differs!(plane_sum[k], paper, "k={k}");
    }
}

#[test]
fn paper_eq_76_five_cell_gyration_radii_match_literal_eq_24() {
    let p = [A, B, C, D];
    let body = Body::pentachoron(A, B, C, D).unwrap();
    assert_eq!(body.mass(), 5.0);
    let radii = contracted(&body, LeviCivita).gyration_radii(5.0).unwrap();
    let o = others4(p);
    for k in 0..4 {
        assert_same!(radii[k].powi(2), o[k], "L² k={k}");
    }
}

#[test]
fn paper_remark_after_eq_76_inertia_factor_reading() {
    // Reading Θ := tr J / (μ R²) for point sets whose vertices are all at distance R from
    // the centre of mass: Θ = 1 (the remark's claim). Checked for the tesseract (any a…d),
    // the regular 5-cell of eq. (73), the cross-polytope and the regular simplex.
    let r2 = A * A + B * B + C * C + D * D;
    let tess = Body::cuboid_vertices(&[A, B, C, D], 1.0).unwrap();
    assert_same!(
        tess.mass_tensor().trace() / (tess.mass() * r2),
        1.0,
        "tesseract"
    );
    let cell = Body::pentachoron(D, D, D, D).unwrap();
    assert_same!(
        cell.mass_tensor().trace() / (cell.mass() * D * D),
        1.0,
        "5-cell"
    );
    for n in 2..=6 {
        let cross = Body::cross_polytope_vertices(n, C, 1.0).unwrap();
        assert_same!(
            cross.mass_tensor().trace() / (cross.mass() * C * C),
            1.0,
            "cross N={n}"
        );
        let simplex = Body::regular_simplex_vertices(n, C, 1.0).unwrap();
        assert_same!(
            simplex.mass_tensor().trace() / (simplex.mass() * C * C),
            1.0,
            "simplex N={n}"
        );
    }
    // The eq. (73) points with unequal parameters are not equidistant from the centre, so
    // the remark does not apply to the body the paper actually tabulates.
    let pts = pentachoron_vertices(A, B, C, D).unwrap();
    assert_differs!(pts[0].norm(), pts[4].norm(), "vertex distances");
}

// ---------------------------------------------------------------------------------------
// §5 cuboids (eqs. 77–82)
// ---------------------------------------------------------------------------------------

#[test]
fn paper_eq_77_and_81_cuboid_volumes_are_right() {
    let v4 = Body::solid_cuboid(&[A, B, C, D], 1.0)
        .unwrap()
        .volume()
        .unwrap();
    assert_same!(v4, 16.0 * A * B * C * D, "eq 77");
    let v5 = Body::solid_cuboid(&[A, B, C, D, E], 1.0)
        .unwrap()
        .volume()
        .unwrap();
    assert_same!(v5, 32.0 * A * B * C * D * E, "eq 81");
}

#[test]
fn paper_eq_78_4d_cuboid_rank4_components_are_twice_eq_22() {
    let p = [A, B, C, D];
    let body = Body::solid_cuboid(&p, 1.0).unwrap();
    let v = body.volume().unwrap();
    let t = RankFourTensor::from_mass_tensor(body.mass_tensor()).unwrap();
    for &(x, y) in &PLANES4 {
        let paper = v / 3.0 * (p[x] * p[x] + p[y] * p[y]);
        let correct = t.get(x, y, x, y);
        assert_same!(
            correct,
            v / 6.0 * (p[x] * p[x] + p[y] * p[y]),
            "plane {x}{y}"
        );
        assert_differs!(correct, paper, "plane {x}{y}");
        // The paper's value is the plane moment J_x + J_y (Parker's normalisation).
        let pm = body.mass_tensor()[(x, x)] + body.mass_tensor()[(y, y)];
        assert_same!(pm, paper, "plane moment {x}{y}");
    }
    // Same index misprint as eq. (70): "… = I^{4114}" should be I^{4141}.
    assert_same!(t.get(3, 0, 3, 0), t.get(0, 3, 0, 3), "I4141");
    assert_same!(t.get(3, 0, 0, 3), -t.get(0, 3, 0, 3), "I4114");
}

#[test]
fn paper_eq_79_4d_cuboid_contracted_matrix_uses_axis_moments() {
    let p = [A, B, C, D];
    let body = Body::solid_cuboid(&p, 1.0).unwrap();
    let v = body.volume().unwrap();
    let o = others4(p);
    let literal = contracted(&body, LeviCivita).axis_values();
    let axis = contracted(&body, AxisMoment).axis_values();
    for k in 0..4 {
        let paper = v / 3.0 * o[k];
        assert_same!(literal[k], 4.0 * v / 3.0 * o[k], "literal k={k}");
        assert_differs!(literal[k], paper, "k={k}");
        assert_same!(axis[k], paper, "axis k={k}");
    }
}

#[test]
fn paper_eq_80_4d_cuboid_gyration_radii_use_axis_moments() {
    let p = [A, B, C, D];
    let body = Body::solid_cuboid(&p, 1.0).unwrap();
    let mu = body.mass();
    assert_same!(mu, body.volume().unwrap(), "μ = V");
    let o = others4(p);
    let literal = contracted(&body, LeviCivita).gyration_radii(mu).unwrap();
    let axis = contracted(&body, AxisMoment).gyration_radii(mu).unwrap();
    for k in 0..4 {
        let paper = o[k] / 3.0;
        assert_same!(literal[k].powi(2), 4.0 * o[k] / 3.0, "literal k={k}");
        assert_differs!(literal[k].powi(2), paper, "k={k}");
        assert_same!(axis[k].powi(2), paper, "axis k={k}");
    }
}

#[test]
fn paper_eq_82_5d_cuboid_components_have_wrong_factor_and_signs() {
    let p = [A, B, C, D, E];
    let body = Body::solid_cuboid(&p, 1.0).unwrap();
    let v = body.volume().unwrap();
    let t = RankFourTensor::from_mass_tensor(body.mass_tensor()).unwrap();
    for x in 0..5 {
        for y in x + 1..5 {
            let s = p[x] * p[x] + p[y] * p[y];
            // The paper prints V/3 · (−a² − c²) for 13 and V/3 · (−b² − d²) for 24.
            let sign = if (x, y) == (0, 2) || (x, y) == (1, 3) {
                -1.0
            } else {
                1.0
            };
            let paper = sign * v / 3.0 * s;
            let correct = t.get(x, y, x, y);
            assert_same!(correct, v / 6.0 * s, "plane {x}{y}");
            assert!(correct > 0.0);
            assert_differs!(correct, paper, "plane {x}{y}");
        }
    }
}

// ---------------------------------------------------------------------------------------
// §6.1–6.2 ellipsoids (eqs. 83–98)
// ---------------------------------------------------------------------------------------

/// ∫₋ₕʰ f(t) dt with t = h sin θ (removes the square-root endpoint behaviour of the
/// nested ellipsoid bounds), then 40-point Gauss–Legendre in θ. After the substitution the
/// integrands are analytic in θ, so the rule converges exponentially; nested three or four
/// deep it reproduces the closed forms to ~1e-15 relative.
fn integrate_sym(h: f64, f: impl Fn(f64) -> f64) -> f64 {
    if h <= 0.0 {
        return 0.0;
    }
    let (nodes, weights) = gauss_legendre(40);
    let half_pi = PI / 2.0;
    nodes
        .iter()
        .zip(&weights)
        .map(|(&u, &w)| {
            let th = half_pi * u;
            w * f(h * th.sin()) * h * th.cos() * half_pi
        })
        .sum()
}

/// The 3D integrals of eqs. (83)–(86) with the printed bounds (literal: the z bound uses
/// (y/a)²) or corrected ((y/b)²), for the weight x^px y^py z^pz.
fn ellipsoid3_integral(a: f64, b: f64, c: f64, literal: bool, pw: [i32; 3]) -> f64 {
    integrate_sym(a, |x| {
        let sx = 1.0 - (x / a).powi(2);
        integrate_sym(b * sx.max(0.0).sqrt(), |y| {
            let ydiv = if literal { a } else { b };
            let rz = (sx - (y / ydiv).powi(2)).max(0.0);
            integrate_sym(c * rz.sqrt(), |z| {
                x.powi(pw[0]) * y.powi(pw[1]) * z.powi(pw[2])
            })
        })
    })
}

/// The 4D volume integral of eq. (90) with the printed bounds (literal: the z bound uses
/// (y/a)², the w bound (y/a)² and (z/c)²) or corrected ((y/b)², (z/c)²).
fn ellipsoid4_volume(a: f64, b: f64, c: f64, d: f64, literal: bool) -> f64 {
    let ydiv = if literal { a } else { b };
    integrate_sym(a, |x| {
        let sx = 1.0 - (x / a).powi(2);
        integrate_sym(b * sx.max(0.0).sqrt(), |y| {
            let sy = (sx - (y / ydiv).powi(2)).max(0.0);
            integrate_sym(c * sy.sqrt(), |z| {
                let sz = (sy - (z / c).powi(2)).max(0.0);
                2.0 * d * sz.sqrt()
            })
        })
    })
}

#[test]
fn paper_eqs_83_to_94_integration_limits_have_typos() {
    // b < a so that the printed bounds are real. The printed z bound c√(1 − (x/a)² − (y/a)²)
    // should be c√(1 − (x/a)² − (y/b)²); with it, the stated results follow, while the
    // printed integrals give different numbers. Quadrature error of the nested
    // Gauss–Legendre rule with the sine substitution is ~1e-15 relative; we allow 1e-9.
    let (a, b, c, d) = (1.2, 0.8, 0.9, 1.1);
    let stated_v3 = 4.0 * PI / 3.0 * a * b * c;
    let stated_i11 = 4.0 * PI / 15.0 * a.powi(3) * b * c;
    let fixed_v3 = ellipsoid3_integral(a, b, c, false, [0, 0, 0]);
    let fixed_i11 = ellipsoid3_integral(a, b, c, false, [2, 0, 0]);
    assert!((fixed_v3 - stated_v3).abs() < 1e-9 * stated_v3);
    assert!((fixed_i11 - stated_i11).abs() < 1e-9 * stated_i11);
    let printed_v3 = ellipsoid3_integral(a, b, c, true, [0, 0, 0]);
    let printed_i11 = ellipsoid3_integral(a, b, c, true, [2, 0, 0]);
    assert_differs!(printed_v3, stated_v3, "eq 83 as printed");
    assert_differs!(printed_i11, stated_i11, "eq 84 as printed");
    // Closed form of the printed eq. (84) integral, β = b/a:
    // (8/15) a⁴ c (β√(1−β²) + arcsin β).
    let beta = b / a;
    let closed = 8.0 / 15.0 * a.powi(4) * c * (beta * (1.0 - beta * beta).sqrt() + beta.asin());
    assert!((printed_i11 - closed).abs() < 1e-9 * closed);
    // 4D, eq. (90): same typo in the z and w bounds.
    let stated_v4 = PI * PI / 2.0 * a * b * c * d;
    let fixed_v4 = ellipsoid4_volume(a, b, c, d, false);
    assert!((fixed_v4 - stated_v4).abs() < 1e-9 * stated_v4);
    let printed_v4 = ellipsoid4_volume(a, b, c, d, true);
    assert_differs!(printed_v4, stated_v4, "eq 90 as printed");
    // Closed form of the printed eq. (90) integral: (3π²/4) abcd (1 − β²/3).
    let closed4 = 0.75 * PI * PI * a * b * c * d * (1.0 - beta * beta / 3.0);
    assert!((printed_v4 - closed4).abs() < 1e-9 * closed4);
}

#[test]
fn paper_eqs_84_to_86_3d_ellipsoid_second_moments_are_right() {
    let body = Body::solid_ellipsoid(&[A, B, C], 1.0).unwrap();
    let j = body.mass_tensor();
    let k = 4.0 * PI / 15.0;
    assert_same!(j[(0, 0)], k * A.powi(3) * B * C, "eq 84");
    assert_same!(j[(1, 1)], k * B.powi(3) * A * C, "eq 85");
    assert_same!(j[(2, 2)], k * C.powi(3) * A * B, "eq 86");
    // And by direct quadrature with the corrected bounds (needs b ≤ a for nothing here).
    let q = ellipsoid3_integral(A, B, C, false, [0, 2, 0]);
    assert!((q - j[(1, 1)]).abs() < 1e-9 * q);
}

#[test]
fn paper_eq_87_3d_ellipsoid_contracted_matrix_is_the_classical_tensor() {
    let p = [A, B, C];
    let body = Body::solid_ellipsoid(&p, 1.0).unwrap();
    let v = body.volume().unwrap();
    let others = [B * B + C * C, A * A + C * C, A * A + B * B];
    let literal = contracted(&body, LeviCivita).axis_values();
    let axis = contracted(&body, AxisMoment).axis_values();
    for k in 0..3 {
        let paper = 4.0 * PI / 15.0 * A * B * C * others[k];
        assert_same!(paper, v / 5.0 * others[k], "the two forms of eq 87");
        assert_same!(literal[k], 2.0 * paper, "literal eq 23 k={k}");
        assert_differs!(literal[k], paper, "k={k}");
        assert_same!(axis[k], paper, "classical k={k}");
    }
}

#[test]
fn paper_eq_88_3d_ellipsoid_gyration_radii_are_classical() {
    let body = Body::solid_ellipsoid(&[A, B, C], 1.0).unwrap();
    let mu = body.mass();
    assert_same!(mu, body.volume().unwrap(), "μ = V");
    let others = [B * B + C * C, A * A + C * C, A * A + B * B];
    let literal = contracted(&body, LeviCivita).gyration_radii(mu).unwrap();
    let axis = contracted(&body, AxisMoment).gyration_radii(mu).unwrap();
    for k in 0..3 {
        assert_same!(axis[k].powi(2), others[k] / 5.0, "k={k}");
        assert_same!(literal[k].powi(2), 2.0 * others[k] / 5.0, "literal k={k}");
    }
}

#[test]
fn paper_eq_89_sphere_gyration_radius_is_wrong() {
    let r = D;
    let body = Body::solid_ball(3, r, 1.0).unwrap();
    let mu = body.mass();
    assert_same!(mu, 4.0 * PI / 3.0 * r.powi(3), "μ");
    let axis = contracted(&body, AxisMoment);
    // 𝕀_αα = (2/5) μ R² is right (classical) …
    assert_same!(axis.axis_values()[0], 0.4 * mu * r * r, "𝕀_αα");
    // … but then eq. (27) gives L² = 𝕀/μ = 2R²/5, not the printed R²/5.
    let l2 = axis.gyration_radii(mu).unwrap()[0].powi(2);
    assert_same!(l2, 0.4 * r * r, "L²");
    assert_differs!(l2, 0.2 * r * r, "printed L²");
    // Literal eq. (23): L² = 4R²/5.
    let lit = contracted(&body, LeviCivita).gyration_radii(mu).unwrap()[0].powi(2);
    assert_same!(lit, 0.8 * r * r, "literal L²");
}

#[test]
fn paper_eq_90_4d_ellipsoid_volume_is_right() {
    let v = Body::solid_ellipsoid(&[A, B, C, D], 1.0)
        .unwrap()
        .volume()
        .unwrap();
    assert_same!(v, PI * PI / 2.0 * A * B * C * D, "eq 90");
}

#[test]
fn paper_eqs_91_to_94_4d_ellipsoid_second_moments() {
    let body = Body::solid_ellipsoid(&[A, B, C, D], 1.0).unwrap();
    let j = body.mass_tensor();
    let k = PI * PI / 12.0;
    assert_same!(j[(0, 0)], k * A.powi(3) * B * C * D, "eq 91");
    assert_same!(j[(1, 1)], k * B.powi(3) * A * C * D, "eq 92");
    // Eq. (93) prints c³acd (a typo: c twice, b missing); the value is c³abd.
    assert_same!(j[(2, 2)], k * C.powi(3) * A * B * D, "eq 93 corrected");
    assert_differs!(j[(2, 2)], k * C.powi(3) * A * C * D, "eq 93 as printed");
    assert_same!(j[(3, 3)], k * D.powi(3) * A * B * C, "eq 94");
}

#[test]
fn paper_eq_95_4d_ellipsoid_contracted_matrix_uses_axis_moments() {
    let p = [A, B, C, D];
    let body = Body::solid_ellipsoid(&p, 1.0).unwrap();
    let o = others4(p);
    let literal = contracted(&body, LeviCivita).axis_values();
    let axis = contracted(&body, AxisMoment).axis_values();
    for k in 0..4 {
        let paper = PI * PI / 2.0 * A * B * C * D * o[k] / 6.0;
        assert_same!(axis[k], paper, "axis k={k}");
        assert_same!(literal[k], 4.0 * paper, "literal k={k}");
        assert_differs!(literal[k], paper, "k={k}");
    }
}

#[test]
fn paper_eq_98_4_ball_values_use_axis_moments() {
    let r = C;
    let body = Body::solid_ball(4, r, 1.0).unwrap();
    let mu = body.mass();
    assert_same!(mu, PI * PI / 2.0 * r.powi(4), "μ");
    let axis = contracted(&body, AxisMoment);
    assert_same!(
        axis.gyration_radii(mu).unwrap()[0].powi(2),
        0.5 * r * r,
        "L²"
    );
    assert_same!(axis.axis_values()[0], 0.5 * mu * r * r, "𝕀_αα");
    let literal = contracted(&body, LeviCivita);
    assert_same!(
        literal.gyration_radii(mu).unwrap()[0].powi(2),
        2.0 * r * r,
        "literal L²"
    );
    assert_differs!(literal.axis_values()[0], 0.5 * mu * r * r, "literal 𝕀_αα");
}

// ---------------------------------------------------------------------------------------
// §6.3 hyperspheres (eqs. 99–106)
// ---------------------------------------------------------------------------------------

/// Monte Carlo estimate of ∫_{ball R} g(x) dV (rejection sampling in the cube), with its
/// standard error.
fn ball_integral(n: usize, r: f64, seed: u64, g: impl Fn(&[f64]) -> f64) -> (f64, f64) {
    let mut rg = rng(seed);
    let draws = 100_000usize;
    let (mut s, mut s2) = (0.0, 0.0);
    let mut x = vec![0.0; n];
    for _ in 0..draws {
        let mut q = 0.0;
        for xi in x.iter_mut() {
            *xi = uniform(&mut rg, -r, r);
            q += *xi * *xi;
        }
        let v = if q <= r * r { g(&x) } else { 0.0 };
        s += v;
        s2 += v * v;
    }
    let cube = (2.0 * r).powi(n as i32);
    let mean = s / draws as f64;
    let var = (s2 / draws as f64 - mean * mean).max(0.0);
    (cube * mean, cube * (var / draws as f64).sqrt())
}

#[test]
fn paper_eq_99_ball_volume_and_sphere_area_are_right() {
    let r: f64 = 1.3;
    for n in 1..=8 {
        let paper_v = PI.powf(n as f64 / 2.0) / gamma_half(n + 2) * r.powi(n as i32);
        let paper_s = paper_v * n as f64 / r;
        let ball = Body::solid_ball(n, r, 1.0).unwrap();
        assert_same!(ball.volume().unwrap(), paper_v, "V_{n}");
        assert_same!(unit_ball_volume(n) * r.powi(n as i32), paper_v, "V_{n}");
        let shell = Body::hypersphere_shell(n, r, 1.0).unwrap();
        assert_same!(shell.mass(), paper_s, "∂V_{n}");
        // ∂V = dV/dR (central difference; error O(h²) ≈ 1e-10).
        let h = 1e-5;
        let dv = (Body::solid_ball(n, r + h, 1.0).unwrap().volume().unwrap()
            - Body::solid_ball(n, r - h, 1.0).unwrap().volume().unwrap())
            / (2.0 * h);
        assert!(
            (dv - paper_s).abs() < 1e-8 * paper_s,
            "N={n}: {dv} vs {paper_s}"
        );
    }
}

#[test]
fn paper_eqs_100_to_102_polar_moments_are_right() {
    let r: f64 = 1.1;
    for n in 2..=6 {
        let v = unit_ball_volume(n) * r.powi(n as i32);
        // Eq. (101)/(102), p = 2: ∫|x|² dV = tr J for unit density.
        let ball = Body::solid_ball(n, r, 1.0).unwrap();
        let nf = n as f64;
        let paper_101 =
            nf * PI.powf(nf / 2.0) / gamma_half(n + 2) * r.powi(n as i32 + 2) / (nf + 2.0);
        assert_same!(ball.mass_tensor().trace(), paper_101, "eq 101 N={n}");
        assert_same!(
            ball.mass_tensor().trace() / v,
            nf / (nf + 2.0) * r * r,
            "eq 102 N={n}"
        );
        // Eq. (100) for other p, against Monte Carlo (5 standard errors).
        for p in [1i32, 3, 4] {
            let paper_100 =
                PI.powf(nf / 2.0) / gamma_half(n + 2) * nf / (nf + p as f64) * r.powi(n as i32 + p);
            let (mc, se) = ball_integral(n, r, 10 * n as u64 + p as u64, |x| {
                x.iter().map(|t| t * t).sum::<f64>().powf(p as f64 / 2.0)
            });
            assert!(
                (mc - paper_100).abs() <= 5.0 * se,
                "eq 100 N={n} p={p}: {mc} ± {se} vs {paper_100}"
            );
        }
    }
}

/// φ(μ) = ∫_0^(π/2) sin^μ x dx (eq. 103) by Simpson's rule.
fn wallis(mu: usize) -> f64 {
    simpson(|x| x.sin().powi(mu as i32), 0.0, PI / 2.0, 20_000)
}

#[test]
fn paper_eq_103_wallis_integral_is_right() {
    for mu in 0..=12 {
        let paper = PI.sqrt() / 2.0 * gamma_half(mu + 1) / gamma_half(mu + 2);
        assert!((wallis(mu) - paper).abs() < 1e-12, "μ={mu}");
        // Also ∫ cos^μ = ∫ sin^μ.
        let cos = simpson(|x| x.cos().powi(mu as i32), 0.0, PI / 2.0, 20_000);
        assert!((cos - paper).abs() < 1e-12);
    }
}

/// The paper's eq. (104) closed form and the corrected one (Γ((N+p+2)/2) in the
/// denominator instead of Γ((N+p+1)/2)).
fn diameter_moment(n: usize, p: usize, r: f64, corrected: bool) -> f64 {
    let denominator = if corrected {
        gamma_half(n + p + 2)
    } else {
        gamma_half(n + p + 1)
    };
    PI.powf(n as f64 / 2.0) / gamma_half(n - 1) * gamma_half(n + p - 1) / denominator
        * r.powi((n + p) as i32)
}

#[test]
fn paper_eq_104_diameter_moment_gamma_is_wrong() {
    let r = 1.2;
    for n in 2..=6 {
        // p = 2 from the crate: ∫ (|x|² − x_1²) dV = tr J − J_11 (unit density).
        let ball = Body::solid_ball(n, r, 1.0).unwrap();
        let j = ball.mass_tensor();
        let exact = j.trace() - j[(0, 0)];
        assert_same!(diameter_moment(n, 2, r, true), exact, "corrected N={n} p=2");
        assert_differs!(diameter_moment(n, 2, r, false), exact, "paper N={n} p=2");
        // p = 1, 3, 4 by Monte Carlo.
        for p in [1usize, 3, 4] {
            let (mc, se) = ball_integral(n, r, 100 * n as u64 + p as u64, |x| {
                (x.iter().map(|t| t * t).sum::<f64>() - x[0] * x[0]).powf(p as f64 / 2.0)
            });
            let fixed = diameter_moment(n, p, r, true);
            let paper = diameter_moment(n, p, r, false);
            assert!(
                (mc - fixed).abs() <= 5.0 * se,
                "N={n} p={p}: {mc} ± {se} vs {fixed}"
            );
            assert!(
                (mc - paper).abs() > 20.0 * se,
                "N={n} p={p}: paper {paper} too close to {mc}"
            );
        }
    }
}

#[test]
fn paper_eq_105_ratio_of_wallis_integrals_is_right() {
    // I^D = Φ(N, p) I^P with Φ = φ(N+p−2)/φ(N−2): check with the crate for p = 2 and with
    // Monte Carlo for p = 4.
    let r = 0.9;
    for n in 2..=6 {
        let ball = Body::solid_ball(n, r, 1.0).unwrap();
        let j = ball.mass_tensor();
        let phi2 = wallis(n) / wallis(n - 2);
        assert!(
            ((j.trace() - j[(0, 0)]) - phi2 * j.trace()).abs() < 1e-11 * j.trace(),
            "N={n}"
        );
        let nf = n as f64;
        let polar4 = PI.powf(nf / 2.0) / gamma_half(n + 2) * nf / (nf + 4.0) * r.powi(n as i32 + 4);
        let phi4 = wallis(n + 2) / wallis(n - 2);
        let (mc, se) = ball_integral(n, r, 500 + n as u64, |x| {
            (x.iter().map(|t| t * t).sum::<f64>() - x[0] * x[0]).powi(2)
        });
        assert!(
            (mc - phi4 * polar4).abs() <= 5.0 * se,
            "N={n}: {mc} ± {se} vs {}",
            phi4 * polar4
        );
    }
}

#[test]
fn paper_eq_106_hypersphere_gyration_radius_is_right_for_axis_moments() {
    let r = 1.4;
    for n in 2..=8 {
        let ball = Body::solid_ball(n, r, 1.0).unwrap();
        let mu = ball.mass();
        let nf = n as f64;
        let paper_l2 = (nf - 1.0) / (nf + 2.0) * r * r;
        let j = ball.mass_tensor();
        // I^D/V = ∫(|x|² − x_1²) dm / m.
        assert_same!((j.trace() - j[(0, 0)]) / mu, paper_l2, "I^D/V N={n}");
        if n >= 3 {
            let axis = contracted(&ball, AxisMoment);
            assert_same!(
                axis.gyration_radii(mu).unwrap()[0].powi(2),
                paper_l2,
                "L² N={n}"
            );
            assert_same!(axis.axis_values()[0], paper_l2 * mu, "𝕀_αα N={n}");
            let literal = contracted(&ball, LeviCivita);
            let factor = LeviCivita.factor(n);
            assert_same!(
                literal.gyration_radii(mu).unwrap()[0].powi(2),
                factor * paper_l2,
                "literal N={n}"
            );
        }
    }
}

#[test]
fn paper_claim_after_eq_29_platonic_bodies_have_equal_half_axes() {
    // "For any homogeneous Platonic body, the half-axes of its Poinsot 4D-inertia ellipsoid
    // are equal … in all spaces". Gyration radii of eq. (27) for the regular simplex
    // (points and solid), cross-polytope and cube, N = 3…6.
    for n in 3..=6 {
        let pts = rotorflow::inertia::bodies::regular_simplex_positions(n, 1.0).unwrap();
        for body in [
            Body::regular_simplex_vertices(n, 1.0, 1.0).unwrap(),
            Body::solid_simplex(&pts, 1.0).unwrap(),
            Body::cross_polytope_vertices(n, 1.0, 1.0).unwrap(),
            Body::solid_cuboid(&vec![1.0; n], 1.0).unwrap(),
        ] {
            let radii = contracted(&body, LeviCivita)
                .principal_gyration_radii(body.mass())
                .unwrap();
            for k in 1..n {
                assert!(
                    (radii[k] - radii[0]).abs() <= 1e-12 * radii[0],
                    "N={n}: {radii}"
                );
            }
        }
    }
}
