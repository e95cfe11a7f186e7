//! The typed objects of PGA and CGA and the operators every type shares: constructors from
//! components, the inner product `|`, motor composition by `*`, the `Versor` sandwich, the
//! spheres and circles through points, and `Display`; each against plain `Multivector`
//! products, closed forms or brute force, over random inputs and dimensions.

use crate::support::rng;
use proptest::prelude::*;
use rand::Rng;
use rotorflow::algebra::{
    AlgebraError, Bivector, Bivector3, Bivector4, Multivector, Rotor, Rotor3, Rotor4, Signature,
    Vector, Vector3, Vector4, Versor, cga, pga,
};

fn random_signature(r: &mut impl Rng) -> Signature {
    let n = r.gen_range(1..=6);
    let q = r.gen_range(0..=n);
    let z = r.gen_range(0..=n - q);
    Signature::new(n - q - z, q, z).unwrap()
}

fn random_mv(r: &mut impl Rng, sig: Signature) -> Multivector {
    let c: Vec<f64> = (0..1 << sig.dim())
        .map(|_| r.gen_range(-1.0..1.0))
        .collect();
    Multivector::from_coefficients(sig, &c).unwrap()
}

/// `Multivector::vector` and `Multivector::bivector` put component k on the k-th blade of
/// the grade (the bivector's in lexicographic order), in every signature.
#[test]
fn vector_and_bivector_constructors_follow_the_blade_order() {
    let mut r = rng(41);
    let mut cases = 0;
    for _ in 0..100 {
        let sig = random_signature(&mut r);
        let n = sig.dim();
        let v: Vec<f64> = (0..n).map(|_| r.gen_range(-1.0..1.0)).collect();
        let mut want = Multivector::zero(sig);
        for (i, &c) in v.iter().enumerate() {
            want += &(&Multivector::basis_blade(sig, 1 << i) * c);
        }
        assert_eq!(Multivector::vector(sig, &v).unwrap(), want);
        let b: Vec<f64> = (0..n * (n - 1) / 2)
            .map(|_| r.gen_range(-1.0..1.0))
            .collect();
        let mut want = Multivector::zero(sig);
        let mut k = 0;
        for i in 0..n {
            for j in i + 1..n {
                let e = Multivector::basis_blade(sig, 1 << i)
                    .wedge(&Multivector::basis_blade(sig, 1 << j));
                want += &(&e * b[k]);
                k += 1;
            }
        }
        assert_eq!(Multivector::bivector(sig, &b).unwrap(), want);
        if sig.is_euclidean() && n >= 2 {
            let euclid = Multivector::from(&Bivector::from_components(n, &b).unwrap());
            assert_eq!(Multivector::bivector(sig, &b).unwrap(), euclid);
        }
        cases += 1;
    }
    assert_eq!(cases, 100);
    let sig = Signature::new(3, 0, 1).unwrap();
    assert!(matches!(
        Multivector::vector(sig, &[1.0, 2.0]),
        Err(AlgebraError::WrongComponentCount {
            expected: 4,
            found: 2,
            ..
        })
    ));
    assert!(matches!(
        Multivector::bivector(sig, &[1.0; 5]),
        Err(AlgebraError::WrongComponentCount {
            expected: 6,
            found: 5,
            ..
        })
    ));
    assert!(matches!(
        Multivector::vector(sig, &[1.0, f64::NAN, 0.0, 0.0]),
        Err(AlgebraError::NonFinite { .. })
    ));
}

/// `a | b` is Σ ⟨A_r B_s⟩_|r−s| over all grade pairs (brute force over the grades), and `&`
/// and `^` are the regressive and outer products, in random signatures.
#[test]
fn operators_have_one_meaning() {
    let mut r = rng(42);
    for _ in 0..100 {
        let sig = random_signature(&mut r);
        let (a, b) = (random_mv(&mut r, sig), random_mv(&mut r, sig));
        let n = sig.dim();
        let mut want = Multivector::zero(sig);
        for ra in 0..=n {
            for sb in 0..=n {
                let prod = a.grade(ra).geometric(&b.grade(sb));
                want += &prod.grade(ra.abs_diff(sb));
            }
        }
        let got = &a | &b;
        assert!((&got - &want).max_abs() < 1e-13, "{sig}");
        assert_eq!(&a & &b, a.regressive(&b));
        assert_eq!(&a ^ &b, a.wedge(&b));
    }
    // Two vectors: the metric's dot product.
    let sig = Signature::new(2, 1, 0).unwrap();
    let x = Multivector::vector(sig, &[1.0, 2.0, 3.0]).unwrap();
    let y = Multivector::vector(sig, &[4.0, 5.0, 6.0]).unwrap();
    assert_eq!(&x | &y, Multivector::scalar(sig, 4.0 + 10.0 - 18.0));
    let (u, v) = (
        Vector::from_components(&[1.0, 2.0]).unwrap(),
        Vector::from_components(&[3.0, -1.0]).unwrap(),
    );
    assert_eq!(&u | &v, 1.0);
    // The typed objects: the same products on their multivectors.
    let p = pga::Point::new(&[1.0, 2.0, 3.0]).unwrap();
    let q = pga::Point::new(&[0.0, -1.0, 2.0]).unwrap();
    let plane = pga::Plane::new(&[0.0, 0.0, 1.0], 1.0).unwrap();
    let line = p.join(&q).unwrap();
    assert_eq!(&p & &q, p.as_multivector().regressive(q.as_multivector()));
    assert_eq!(&p & &q, line.as_multivector().clone());
    assert_eq!(
        &plane ^ &line,
        plane.as_multivector().wedge(line.as_multivector())
    );
    assert_eq!(
        &plane | &p,
        plane.as_multivector().inner(p.as_multivector())
    );
    let cp = cga::Point::new(&[1.0, 0.0]).unwrap();
    let s = cga::Sphere::new(&[0.0, 0.0], 1.0).unwrap();
    assert!((&cp | &s).max_abs() < 1e-15); // the point lies on the circle
}

fn random_motor(r: &mut impl Rng, n: usize) -> pga::Motor {
    let rot = crate::support::random_rotor(r, n);
    let t: Vec<f64> = (0..n).map(|_| r.gen_range(-3.0..3.0)).collect();
    pga::Motor::from_rotation_translation(&rot, &t).unwrap()
}

proptest! {
    /// Motor composition by `*` is the geometric product, `a * b` is `b.then(&a)`, and the
    /// sandwich of the product is the sandwich of the factors, over N = 2 … 5.
    #[test]
    fn motor_product_and_sandwich_agree_with_multivector_products(n in 2usize..=5, seed in any::<u64>()) {
        let mut r = rng(seed);
        let (a, b) = (random_motor(&mut r, n), random_motor(&mut r, n));
        let ab = &a * &b;
        prop_assert_eq!(ab.as_multivector(), &a.as_multivector().geometric(b.as_multivector()));
        prop_assert_eq!(&ab, &b.then(&a).unwrap());
        prop_assert_eq!(a.clone() * b.clone(), ab.clone());
        let x: Vec<f64> = (0..n).map(|_| r.gen_range(-2.0..2.0)).collect();
        let p = pga::Point::new(&x).unwrap();
        let both = ab.apply(&p).unwrap().coordinates().unwrap();
        let one_by_one = a.apply(&b.apply(&p).unwrap()).unwrap().coordinates().unwrap();
        for (u, v) in both.iter().zip(&one_by_one) {
            prop_assert!((u - v).abs() < 1e-12);
        }
        // The typed sandwich is the multivector sandwich M X M̃ graded.
        let m = a.as_multivector();
        let raw = m.geometric(p.as_multivector()).geometric(&m.reverse());
        let typed = a.apply(&p).unwrap();
        prop_assert!((typed.as_multivector() - &raw.grade(n)).max_abs() < 1e-13);
        let plane = pga::Plane::new(&x, 0.5).unwrap();
        let raw = m.geometric(plane.as_multivector()).geometric(&m.reverse());
        prop_assert!((a.apply(&plane).unwrap().as_multivector() - &raw.grade(1)).max_abs() < 1e-12);
        let carried = a.apply(&b).unwrap();
        let raw = m.geometric(b.as_multivector()).geometric(&m.reverse());
        prop_assert!((carried.as_multivector() - &raw).max_abs() < 1e-12);
        prop_assert!(a.apply(&pga::Point::new(&vec![0.0; n + 1]).unwrap()).is_err());
    }

    /// The fixed-size rotors' sandwiches are the run-time rotor's, on vectors, bivectors and
    /// rotors, in 3D and 4D.
    #[test]
    fn fixed_rotor_sandwiches_agree_with_the_run_time_rotor(seed in any::<u64>()) {
        let mut r = rng(seed);
        let mut comps = |k: usize| -> Vec<f64> { (0..k).map(|_| r.gen_range(-3.0..3.0)).collect() };
        let (r3, s3, b3, v3) = (
            Rotor3::from_rotation_bivector(Bivector3::from_array(comps(3).try_into().unwrap())),
            Rotor3::from_rotation_bivector(Bivector3::from_array(comps(3).try_into().unwrap())),
            Bivector3::from_array(comps(3).try_into().unwrap()),
            Vector3::from_row_slice(&comps(3)),
        );
        let rt = r3.to_rotor();
        let want_v = rt.apply(&Vector::from_components(v3.as_slice()).unwrap()).unwrap();
        prop_assert!((r3.apply(&v3) - Vector3::from_row_slice(want_v.as_slice())).amax() < 1e-14);
        let want_b = rt.apply(&b3.to_bivector()).unwrap();
        prop_assert!((&r3.apply(&b3).to_bivector() - &want_b).norm() < 1e-13);
        let want_r = rt.apply(&s3.to_rotor()).unwrap();
        prop_assert!(Multivector::from(&r3.apply(&s3).to_rotor()).as_slice().iter()
            .zip(Multivector::from(&want_r).as_slice()).all(|(a, b)| (a - b).abs() < 1e-14));
        let (r4, s4, b4, v4) = (
            Rotor4::from_rotation_bivector(Bivector4::from_array(comps(6).try_into().unwrap())),
            Rotor4::from_rotation_bivector(Bivector4::from_array(comps(6).try_into().unwrap())),
            Bivector4::from_array(comps(6).try_into().unwrap()),
            Vector4::from_row_slice(&comps(4)),
        );
        let rt = r4.to_rotor();
        let want_v = rt.apply(&Vector::from_components(v4.as_slice()).unwrap()).unwrap();
        prop_assert!((r4.apply(&v4) - Vector4::from_row_slice(want_v.as_slice())).amax() < 1e-14);
        let want_b = rt.apply(&b4.to_bivector()).unwrap();
        prop_assert!((&r4.apply(&b4).to_bivector() - &want_b).norm() < 1e-13);
        let want_r = Multivector::from(&rt).geometric(&Multivector::from(&s4.to_rotor()))
            .geometric(&Multivector::from(&rt.reverse()));
        prop_assert!((&Multivector::from(&r4.apply(&s4).to_rotor()) - &want_r).max_abs() < 1e-14);
        // f32 agrees to single precision.
        let r32 = Rotor3::<f32>::from_rotation_x(0.7) * Rotor3::<f32>::from_rotation_y(-1.2);
        let r64 = Rotor3::<f64>::from_rotation_x(0.7) * Rotor3::<f64>::from_rotation_y(-1.2);
        let b32 = r32.apply(&Bivector3::new(0.5f32, -1.0, 2.0));
        let b64 = r64.apply(&Bivector3::new(0.5, -1.0, 2.0));
        prop_assert!((f64::from(b32.b13) - b64.b13).abs() < 1e-5);
    }
}

#[test]
fn run_time_sandwiches_refuse_other_dimensions() {
    let r = Rotor::from_plane_angle(3, 0, 1, 0.4).unwrap();
    assert!(matches!(
        r.apply(&Vector::from_components(&[1.0, 0.0]).unwrap()),
        Err(AlgebraError::DimensionMismatch { left: 3, right: 2 })
    ));
    assert!(matches!(
        r.apply(&Rotor::from_plane_angle(4, 0, 1, 0.4).unwrap()),
        Err(AlgebraError::DimensionMismatch { .. })
    ));
    let t = cga::translator(&[1.0, 2.0]).unwrap();
    assert!(matches!(
        t.apply(&cga::Point::new(&[1.0, 2.0, 3.0]).unwrap()),
        Err(AlgebraError::DimensionMismatch { left: 4, right: 5 })
    ));
}

/// A unit vector of ℝⁿ, uniform on the sphere.
fn random_unit(r: &mut impl Rng, n: usize) -> Vec<f64> {
    loop {
        let v: Vec<f64> = (0..n).map(|_| r.gen_range(-1.0..1.0)).collect();
        let len = v.iter().map(|c| c * c).sum::<f64>().sqrt();
        if (0.2..=1.0).contains(&len) {
            return v.iter().map(|c| c / len).collect();
        }
    }
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

/// Random points on a known sphere (N = 2 … 5) give back its centre and radius.
#[test]
fn sphere_through_points_on_a_known_sphere() {
    let mut r = rng(43);
    let mut cases = [0usize; 6];
    let mut worst = 0.0f64;
    let mut thin = 0;
    for _ in 0..800 {
        let n = r.gen_range(2..=5);
        let centre: Vec<f64> = (0..n).map(|_| r.gen_range(-2.0..2.0)).collect();
        let radius = r.gen_range(0.3..3.0);
        let points: Vec<cga::Point> = (0..=n)
            .map(|_| {
                let u = random_unit(&mut r, n);
                let x: Vec<f64> = centre.iter().zip(&u).map(|(c, u)| c + radius * u).collect();
                cga::Point::new(&x).unwrap()
            })
            .collect();
        // The centre of a thin simplex's sphere moves by 1/σ_min times any perturbation of
        // the points (σ_min the smallest singular value of the edges from the first point,
        // over the radius): such inputs are counted apart, and the promise is for the rest.
        let coords: Vec<Vec<f64>> = points.iter().map(|p| p.coordinates().unwrap()).collect();
        let edges =
            nalgebra::DMatrix::from_fn(n, n, |i, j| (coords[i + 1][j] - coords[0][j]) / radius);
        if edges.singular_values().min() < 0.1 {
            thin += 1;
            continue;
        }
        let s = cga::Sphere::through(&points).unwrap();
        let err = max_diff(s.centre(), &centre).max((s.radius() - radius).abs());
        worst = worst.max(err);
        assert!(err < 1e-12, "N = {n}: error {err:e}");
        // The sphere is the one of `Sphere::new`, and every point lies on it.
        for p in &points {
            let d = s.signed_distance(&p.coordinates().unwrap()).unwrap();
            assert!(d.abs() < 1e-12 * (1.0 + radius), "{d:e}");
        }
        cases[n] += 1;
    }
    let total: usize = cases.iter().sum();
    assert_eq!(total + thin, 800);
    assert!(cases[2..].iter().all(|&c| c > 100), "{cases:?}");
    println!(
        "spheres through points: {cases:?} per N ({thin} thin simplices set apart), worst error {worst:e}"
    );
}

/// Random points on a known circle in a random plane of ℝᴺ (N = 2 … 5) give back its
/// centre and radius.
#[test]
fn circle_through_points_on_a_known_circle() {
    let mut r = rng(44);
    let mut cases = 0;
    for _ in 0..400 {
        let n = r.gen_range(2..=5);
        let centre: Vec<f64> = (0..n).map(|_| r.gen_range(-2.0..2.0)).collect();
        let radius = r.gen_range(0.3..3.0);
        // An orthonormal pair (u, v) spanning the circle's plane.
        let u = random_unit(&mut r, n);
        let w = random_unit(&mut r, n);
        let uw: f64 = u.iter().zip(&w).map(|(a, b)| a * b).sum();
        let v: Vec<f64> = w.iter().zip(&u).map(|(w, u)| w - uw * u).collect();
        let len = v.iter().map(|c| c * c).sum::<f64>().sqrt();
        if len < 0.1 {
            continue;
        }
        let v: Vec<f64> = v.iter().map(|c| c / len).collect();
        // Three angles at least 0.3 apart, so the points are well separated.
        let mut angles: Vec<f64> = (0..3)
            .map(|_| r.gen_range(0.0..std::f64::consts::TAU))
            .collect();
        angles.sort_by(f64::total_cmp);
        if angles[1] - angles[0] < 0.3
            || angles[2] - angles[1] < 0.3
            || angles[0] + std::f64::consts::TAU - angles[2] < 0.3
        {
            continue;
        }
        let p: Vec<cga::Point> = angles
            .iter()
            .map(|t| {
                let x: Vec<f64> = (0..n)
                    .map(|k| centre[k] + radius * (t.cos() * u[k] + t.sin() * v[k]))
                    .collect();
                cga::Point::new(&x).unwrap()
            })
            .collect();
        let c = cga::Circle::through(&p[0], &p[1], &p[2]).unwrap();
        let err = max_diff(c.centre(), &centre).max((c.radius() - radius).abs());
        assert!(err < 1e-12, "N = {n}: error {err:e}");
        cases += 1;
    }
    assert!(cases > 200, "{cases}");
}

#[test]
fn rounds_through_special_positions_are_refused() {
    let p = |x: &[f64]| cga::Point::new(x).unwrap();
    let collinear = cga::Circle::through(
        &p(&[0.0, 0.0, 0.0]),
        &p(&[1.0, 1.0, 1.0]),
        &p(&[2.0, 2.0, 2.0]),
    );
    assert!(
        matches!(collinear, Err(AlgebraError::Degenerate { .. })),
        "{collinear:?}"
    );
    let twice = cga::Circle::through(&p(&[0.0, 0.0]), &p(&[1.0, 0.0]), &p(&[1.0, 0.0]));
    assert!(
        matches!(twice, Err(AlgebraError::Degenerate { .. })),
        "{twice:?}"
    );
    let coplanar = cga::Sphere::through(&[
        p(&[0.0, 0.0, 1.0]),
        p(&[1.0, 0.0, 1.0]),
        p(&[0.0, 1.0, 1.0]),
        p(&[3.0, 2.0, 1.0]),
    ]);
    assert!(
        matches!(coplanar, Err(AlgebraError::Degenerate { .. })),
        "{coplanar:?}"
    );
    assert!(matches!(
        cga::Sphere::through(&[p(&[0.0, 0.0]), p(&[1.0, 0.0])]),
        Err(AlgebraError::WrongComponentCount {
            expected: 3,
            found: 2,
            ..
        })
    ));
    assert!(matches!(
        cga::Sphere::through(&[p(&[0.0, 0.0]), p(&[1.0, 0.0]), p(&[0.0, 1.0, 0.0])]),
        Err(AlgebraError::DimensionMismatch { .. })
    ));
    assert!(cga::Sphere::from_multivector(&cga::plane(&[0.0, 1.0], 2.0).unwrap()).is_err());
}

/// Conformal versors move the typed objects as their closed forms say: a translation moves
/// centres, a dilation scales radii, a rotation turns centres.
#[test]
fn conformal_versors_move_points_spheres_and_circles() {
    let mut r = rng(45);
    for _ in 0..100 {
        let t: Vec<f64> = (0..3).map(|_| r.gen_range(-2.0..2.0)).collect();
        let x: Vec<f64> = (0..3).map(|_| r.gen_range(-2.0..2.0)).collect();
        let radius = r.gen_range(0.5..2.0);
        let scale = r.gen_range(0.5..2.0);
        let tr = cga::translator(&t).unwrap();
        let moved = tr
            .apply(&cga::Point::new(&x).unwrap())
            .unwrap()
            .coordinates()
            .unwrap();
        let want: Vec<f64> = x.iter().zip(&t).map(|(a, b)| a + b).collect();
        assert!(max_diff(&moved, &want) < 1e-13);
        let s = cga::Sphere::new(&x, radius).unwrap();
        let st = tr.apply(&s).unwrap();
        assert!(max_diff(st.centre(), &want) < 1e-13 && (st.radius() - radius).abs() < 1e-13);
        let d = cga::dilator(3, scale).unwrap();
        let sd = d.apply(&s).unwrap();
        let scaled: Vec<f64> = x.iter().map(|c| c * scale).collect();
        assert!(max_diff(sd.centre(), &scaled) < 1e-13);
        assert!((sd.radius() - radius * scale).abs() < 1e-13);
        let rot = Rotor::from_plane_angle(3, 0, 1, r.gen_range(-3.0..3.0)).unwrap();
        let c = cga::Circle::through(
            &cga::Point::new(&[x[0] + radius, x[1], x[2]]).unwrap(),
            &cga::Point::new(&[x[0], x[1] + radius, x[2]]).unwrap(),
            &cga::Point::new(&[x[0] - radius, x[1], x[2]]).unwrap(),
        )
        .unwrap();
        let rc = cga::rotor(&rot).unwrap().apply(&c).unwrap();
        let want = rot.rotate_vector(&Vector::from_components(&x).unwrap());
        assert!(max_diff(rc.centre(), want.as_slice()) < 1e-13);
        assert!((rc.radius() - radius).abs() < 1e-13);
    }
}

#[test]
fn display_of_typed_objects() {
    let p = pga::Point::new(&[1.0, 2.0, 3.0]).unwrap();
    assert_eq!(p.to_string(), "point(1, 2, 3)");
    assert_eq!(
        pga::Point::ideal(&[0.0, 0.0, 1.0]).unwrap().to_string(),
        "direction(0, 0, 1)"
    );
    assert_eq!(
        pga::Plane::new(&[0.0, 0.0, 1.0], 2.0).unwrap().to_string(),
        "plane((0, 0, 1)·x = 2)"
    );
    let l = pga::Line::from_point_direction(&[1.0, 2.0, 3.0], &[0.0, 0.0, 2.0]).unwrap();
    assert_eq!(
        l.to_string(),
        "line(through (1, 2, 0), direction (0, 0, 2))"
    );
    let m = pga::Motor::from_translation(&[1.0, 0.0, 2.0]).unwrap();
    assert_eq!(m.to_string(), "motor(rotation 1, translation (1, 0, 2))");
    let q = pga::Motor::from_plane_angle(2, 0, 1, std::f64::consts::FRAC_PI_2).unwrap();
    assert_eq!(
        format!("{q:.3}"),
        "motor(rotation 0.707 - 0.707·e12, translation (0.000, 0.000))"
    );
    assert_eq!(
        format!("{:.3}", cga::Point::new(&[0.5, -1.0]).unwrap()),
        "point(0.500, -1.000)"
    );
    assert_eq!(
        cga::Sphere::new(&[1.0, 2.0, 3.0], 2.0).unwrap().to_string(),
        "sphere(centre (1, 2, 3), radius 2)"
    );
    let c = cga::Circle::through(
        &cga::Point::new(&[2.0, 0.0]).unwrap(),
        &cga::Point::new(&[0.0, 2.0]).unwrap(),
        &cga::Point::new(&[-2.0, 0.0]).unwrap(),
    )
    .unwrap();
    let text = format!("{c:.6}");
    assert!(
        text.starts_with("circle(centre (") && text.ends_with("), radius 2.000000)"),
        "{text}"
    );
    let centre: Vec<f64> = text["circle(centre (".len()..text.find(')').unwrap()]
        .split(", ")
        .map(|x| x.parse().unwrap())
        .collect();
    assert_eq!(centre, vec![0.0, 0.0]);
}

/// A spacetime boost's `apply` is the closed-form Lorentz boost: e₁ ↦ cosh φ e₁ + sinh φ n̂,
/// n̂ ↦ sinh φ e₁ + cosh φ n̂, the directions across n̂ fixed.
#[test]
fn boosts_apply_as_lorentz_transformations() {
    let mut r = rng(46);
    for _ in 0..100 {
        let phi = r.gen_range(-2.0..2.0);
        let n = random_unit(&mut r, 3);
        let x: Vec<f64> = (0..4).map(|_| r.gen_range(-1.0..1.0)).collect();
        let v = rotorflow::algebra::sta::boost(phi, &n).unwrap();
        let moved = v
            .apply(&Multivector::vector(v.signature(), &x).unwrap())
            .unwrap();
        let s: f64 = (0..3).map(|k| n[k] * x[k + 1]).sum();
        let (c, h) = (phi.cosh(), phi.sinh());
        let mut want = vec![c * x[0] + h * s];
        for k in 0..3 {
            want.push(x[k + 1] + (h * x[0] + (c - 1.0) * s) * n[k]);
        }
        let got: Vec<f64> = (0..4).map(|i| moved.coefficient(1 << i)).collect();
        assert!(max_diff(&got, &want) < 1e-13, "{got:?} {want:?}");
        assert!((&moved - &moved.grade(1)).max_abs() < 1e-13);
    }
}
