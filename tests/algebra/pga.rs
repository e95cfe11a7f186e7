//! Projective GA points, planes, join, meet and motors, and spacetime boosts: checked
//! against Euclidean facts computed without the algebra (incidence a·x = d, intersections by
//! a linear solve, homogeneous matrices, the Lorentz matrix).

use crate::support::*;
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;
use rand::Rng;
use rotorflow::algebra::pga::{Line, Motor, Plane, Point, join, meet};
use rotorflow::algebra::sta;
use rotorflow::prelude::*;

fn coords(rng: &mut impl Rng, n: usize) -> Vec<f64> {
    (0..n).map(|_| rng.gen_range(-2.0..2.0)).collect()
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).fold(0.0, |m, (x, y)| m.max((x - y).abs()))
}

/// A random motor built from the exponential of a random bivector of Cl(n, 0, 1), a route
/// independent of the typed constructors.
fn random_motor(rng: &mut impl Rng, n: usize) -> Motor {
    let sig = Signature::new(n, 0, 1).unwrap();
    let mut b = Multivector::zero(sig);
    for i in 0..=n {
        for j in i + 1..=n {
            b.as_mut_slice()[(1 << i) | (1 << j)] = rng.gen_range(-1.5..1.5);
        }
    }
    Motor::new(b.exp().unwrap()).unwrap()
}

#[test]
fn points_round_trip_and_lie_on_their_planes() {
    let mut rng = rng(51);
    for n in 2..=5 {
        for _ in 0..50 {
            let x = coords(&mut rng, n);
            let p = Point::new(&x).unwrap();
            assert!(max_diff(&p.coordinates().unwrap(), &x) < 1e-15);
            let a = coords(&mut rng, n);
            let on = Plane::new(&a, dot(&a, &x)).unwrap();
            let off = Plane::new(&a, dot(&a, &x) + 0.5).unwrap();
            // A point lies on a hyperplane exactly when their outer product vanishes.
            assert!(meet(&on, &p).unwrap().max_abs() < 1e-14, "N = {n}");
            let miss = meet(&off, &p).unwrap().max_abs();
            assert!((miss - 0.5).abs() < 1e-14, "N = {n}: {miss}");
            let (a2, d2) = on.equation();
            assert_eq!(a2, a);
            assert!((d2 - dot(&a, &x)).abs() < 1e-15);
        }
    }
}

#[test]
fn meet_of_hyperplanes_is_their_intersection() {
    let mut rng = rng(52);
    for n in 2..=4 {
        for _ in 0..50 {
            let rows: Vec<Vec<f64>> = (0..n).map(|_| coords(&mut rng, n)).collect();
            let d = coords(&mut rng, n);
            let a = DMatrix::from_fn(n, n, |i, j| rows[i][j]);
            if a.determinant().abs() < 0.1 {
                continue;
            }
            let want = a.lu().solve(&DVector::from_column_slice(&d)).unwrap();
            let mut m = Plane::new(&rows[0], d[0]).unwrap().into_multivector();
            for k in 1..n {
                m = meet(&m, &Plane::new(&rows[k], d[k]).unwrap()).unwrap();
            }
            let x = Point::from_multivector(m).unwrap().coordinates().unwrap();
            assert!(max_diff(&x, want.as_slice()) < 1e-12, "N = {n}");
        }
    }
}

#[test]
fn join_of_points_is_the_hyperplane_through_them() {
    let mut rng = rng(53);
    for n in 2..=4 {
        for _ in 0..50 {
            let pts: Vec<Vec<f64>> = (0..n).map(|_| coords(&mut rng, n)).collect();
            let mut m = Point::new(&pts[0]).unwrap().into_multivector();
            for p in &pts[1..] {
                m = join(&m, &Point::new(p).unwrap()).unwrap();
            }
            let plane = Plane::from_multivector(m).unwrap();
            let (a, d) = plane.equation();
            let scale = dot(&a, &a).sqrt();
            if scale < 1e-3 {
                continue;
            }
            for p in &pts {
                assert!((dot(&a, p) - d).abs() < 1e-13 * scale.max(1.0), "N = {n}");
            }
        }
    }
    // 3D: a line (join of two points) contains both, and a third point on it joins to 0.
    let p = Point::new(&[1.0, 2.0, 3.0]).unwrap();
    let q = Point::new(&[-1.0, 0.5, 2.0]).unwrap();
    let mid = Point::new(&[0.0, 1.25, 2.5]).unwrap();
    let line = join(&p, &q).unwrap();
    assert_eq!(line.grades(), vec![2]);
    assert!(join(&line, &mid).unwrap().max_abs() < 1e-15);
    assert!(
        join(&line, &Point::new(&[0.0, 0.0, 0.0]).unwrap())
            .unwrap()
            .max_abs()
            > 0.1
    );
}

#[test]
fn translation_moves_the_origin_to_t() {
    let mut rng = rng(54);
    for n in 2..=4 {
        let t = coords(&mut rng, n);
        let m = Motor::from_translation(&t).unwrap();
        let origin = Point::new(&vec![0.0; n]).unwrap();
        let moved = m.apply_point(&origin).unwrap().coordinates().unwrap();
        assert!(max_diff(&moved, &t) < 1e-15, "N = {n}");
        let x = coords(&mut rng, n);
        let moved = m.apply_point(&Point::new(&x).unwrap()).unwrap();
        let want: Vec<f64> = x.iter().zip(&t).map(|(a, b)| a + b).collect();
        assert!(max_diff(&moved.coordinates().unwrap(), &want) < 1e-15);
        // It agrees with exp(−½ t e₀) (the exponential's documented translation).
        let sig = Signature::new(n, 0, 1).unwrap();
        let mut b = Multivector::zero(sig);
        for (i, &ti) in t.iter().enumerate() {
            b.as_mut_slice()[(1 << i) | (1 << n)] = -0.5 * ti;
        }
        assert_eq!(&b.exp().unwrap(), m.as_multivector());
    }
}

#[test]
fn rotation_turns_e1_toward_e2() {
    for n in 2..=4 {
        let theta = 0.3;
        let m = Motor::from_plane_angle(n, 0, 1, theta).unwrap();
        let mut e1 = vec![0.0; n];
        e1[0] = 1.0;
        let x = m
            .apply_point(&Point::new(&e1).unwrap())
            .unwrap()
            .coordinates()
            .unwrap();
        let mut want = vec![0.0; n];
        want[0] = theta.cos();
        want[1] = theta.sin();
        assert!(max_diff(&x, &want) < 1e-15, "N = {n}: {x:?}");
        // The hyperplane x₁ = 1 turns the same way: its normal becomes (cos θ, sin θ, …).
        let (a, d) = m
            .apply_plane(&Plane::new(&e1, 1.0).unwrap())
            .unwrap()
            .equation();
        assert!(max_diff(&a, &want) < 1e-15 && (d - 1.0).abs() < 1e-15);
    }
}

#[test]
fn motor_matrix_matches_the_action_on_points() {
    let mut rng = rng(55);
    for n in 2..=4 {
        let mut worst = 0.0f64;
        for _ in 0..100 {
            let m = random_motor(&mut rng, n);
            let h = m.to_matrix();
            for _ in 0..3 {
                let x = coords(&mut rng, n);
                let xh: Vec<f64> = x.iter().copied().chain([1.0]).collect();
                let want = &h * DVector::from_column_slice(&xh);
                let got = m.apply_point(&Point::new(&x).unwrap()).unwrap();
                worst = worst.max(max_diff(&got.coordinates().unwrap(), &want.as_slice()[..n]));
            }
            assert_eq!(h[(n, n)], 1.0);
        }
        assert!(worst < 1e-14, "N = {n}: {worst:e}");
    }
}

#[test]
fn motor_matrix_round_trips() {
    let mut rng = rng(56);
    for n in 2..=4 {
        for _ in 0..100 {
            // Motor → matrix → motor gives ±M (both signs are the same motion).
            let m = random_motor(&mut rng, n);
            let back = Motor::from_matrix(&m.to_matrix()).unwrap();
            let d = (back.as_multivector() - m.as_multivector())
                .max_abs()
                .min((back.as_multivector() + m.as_multivector()).max_abs());
            assert!(d < 1e-14, "N = {n}: {d:e}");
            // Matrix → motor → matrix.
            let q = random_rotation_matrix(&mut rng, n);
            let t = coords(&mut rng, n);
            let mut h = DMatrix::identity(n + 1, n + 1);
            h.view_mut((0, 0), (n, n)).copy_from(&q);
            for i in 0..n {
                h[(i, n)] = t[i];
            }
            let again = Motor::from_matrix(&h).unwrap().to_matrix();
            assert!(max_abs_diff(&again, &h) < 1e-14);
        }
    }
}

#[test]
fn composition_is_the_matrix_product() {
    let mut rng = rng(57);
    for n in 2..=4 {
        for _ in 0..50 {
            let a = random_motor(&mut rng, n);
            let b = random_motor(&mut rng, n);
            let ab = a.then(&b).unwrap();
            let want = b.to_matrix() * a.to_matrix();
            assert!(max_abs_diff(&ab.to_matrix(), &want) < 1e-13);
            let id = a.then(&a.inverse()).unwrap();
            assert!(max_abs_diff(&id.to_matrix(), &DMatrix::identity(n + 1, n + 1)) < 1e-14);
            // Parts: rotate first, then translate.
            let rebuilt = Motor::from_rotation_translation(&a.rotor(), &a.translation()).unwrap();
            assert!((rebuilt.as_multivector() - a.as_multivector()).max_abs() < 1e-14);
            // Half the motion twice is the motion.
            let h = a.sqrt().unwrap();
            let hh = h.then(&h).unwrap();
            assert!((hh.as_multivector() - a.as_multivector()).max_abs() < 1e-14);
        }
    }
}

#[test]
fn motors_keep_incidence() {
    let mut rng = rng(58);
    for n in 2..=4 {
        for _ in 0..30 {
            let m = random_motor(&mut rng, n);
            let x = coords(&mut rng, n);
            let a = coords(&mut rng, n);
            let plane = Plane::new(&a, dot(&a, &x)).unwrap();
            let p2 = m.apply_point(&Point::new(&x).unwrap()).unwrap();
            let pl2 = m.apply_plane(&plane).unwrap();
            assert!(meet(&pl2, &p2).unwrap().max_abs() < 1e-13);
        }
    }
}

#[test]
fn bad_input_is_refused() {
    assert!(matches!(
        Point::new(&[1.0, f64::NAN]),
        Err(AlgebraError::NonFinite { .. })
    ));
    assert!(Point::new(&[1.0]).is_err());
    assert!(Plane::new(&[0.0, 0.0], 1.0).is_err());
    // Parallel lines in 2D meet at infinity.
    let l1 = Plane::new(&[1.0, 0.0], 0.0).unwrap();
    let l2 = Plane::new(&[1.0, 0.0], 1.0).unwrap();
    let ideal = Point::from_multivector(meet(&l1, &l2).unwrap()).unwrap();
    assert!(matches!(
        ideal.coordinates(),
        Err(AlgebraError::PointAtInfinity { .. })
    ));
    let pga = Signature::new(3, 0, 1).unwrap();
    assert!(matches!(
        Motor::new(Multivector::scalar(pga, 2.0)),
        Err(AlgebraError::NotAVersor { .. })
    ));
    assert!(matches!(
        Motor::new(Multivector::scalar(Signature::euclidean(3), 1.0)),
        Err(AlgebraError::WrongSignature { .. })
    ));
    let mut h = DMatrix::<f64>::identity(4, 4);
    h[(3, 0)] = 0.5;
    assert!(matches!(
        Motor::from_matrix(&h),
        Err(AlgebraError::NotHomogeneous { .. })
    ));
    h[(3, 0)] = 0.0;
    h[(0, 0)] = -1.0; // a reflection
    assert!(Motor::from_matrix(&h).is_err());
    assert!(Motor::from_matrix(&DMatrix::<f64>::identity(3, 4)).is_err());
}

/// The Lorentz matrix of the boost of rapidity φ along n̂ (components t, x, y, z).
fn lorentz(phi: f64, n: &[f64; 3]) -> DMatrix<f64> {
    let (c, s) = (phi.cosh(), phi.sinh());
    let mut l = DMatrix::identity(4, 4);
    l[(0, 0)] = c;
    for i in 0..3 {
        l[(0, i + 1)] = s * n[i];
        l[(i + 1, 0)] = s * n[i];
        for j in 0..3 {
            l[(i + 1, j + 1)] += (c - 1.0) * n[i] * n[j];
        }
    }
    l
}

#[test]
fn boosts_match_the_lorentz_matrix() {
    let mut rng = rng(59);
    let st = sta::spacetime();
    for _ in 0..200 {
        let phi = rng.gen_range(-3.0..3.0);
        let raw = [
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
            rng.gen_range(-1.0..1.0),
        ];
        let len = dot(&raw, &raw).sqrt();
        let n = [raw[0] / len, raw[1] / len, raw[2] / len];
        let v = sta::boost(phi, &raw).unwrap();
        let l = lorentz(phi, &n);
        let x: Vec<f64> = (0..4).map(|_| rng.gen_range(-1.0..1.0)).collect();
        let mut xm = Multivector::zero(st);
        for (k, &c) in x.iter().enumerate() {
            xm.as_mut_slice()[1 << k] = c;
        }
        let moved = &(&v * &xm) * &v.reverse();
        let want = &l * DVector::from_column_slice(&x);
        let got: Vec<f64> = (0..4).map(|k| moved.coefficient(1 << k)).collect();
        let scale = phi.cosh();
        assert!(max_diff(&got, want.as_slice()) < 1e-14 * scale, "φ = {phi}");
        let others = (&moved - &moved.grade(1)).max_abs();
        assert!(others < 1e-14 * scale * scale, "φ = {phi}: {others:e}");
        // It is the exponential of ½ φ n̂ e₁.
        let mut b = Multivector::zero(st);
        for (k, nk) in n.iter().enumerate() {
            b.as_mut_slice()[1 | (1 << (k + 1))] = -0.5 * phi * nk;
        }
        assert!((&b.exp().unwrap() - &v).max_abs() < 1e-14 * scale);
    }
    // Composition of collinear boosts adds rapidities.
    let a = sta::boost(0.4, &[0.0, 1.0, 0.0]).unwrap();
    let b = sta::boost(0.9, &[0.0, 2.0, 0.0]).unwrap();
    assert!((&(&a * &b) - &sta::boost(1.3, &[0.0, 1.0, 0.0]).unwrap()).max_abs() < 1e-15);
    assert!(sta::boost(1.0, &[0.0, 0.0, 0.0]).is_err());
    assert!(sta::boost(f64::NAN, &[1.0, 0.0, 0.0]).is_err());
    assert!(sta::boost(1.0, &[1.0, 0.0]).is_err());
    assert!(matches!(
        sta::boost(5000.0, &[1.0, 0.0, 0.0]),
        Err(AlgebraError::Overflow { .. })
    ));
}

#[test]
fn blade_signs_in_3d_are_pinned() {
    // The point and plane of the module table, blade by blade (e₄ is the projective e₀).
    let p = Point::new(&[2.0, 3.0, 5.0]).unwrap();
    let m = p.as_multivector();
    assert_eq!(m.coefficient(0b0111), 1.0);
    assert_eq!(m.coefficient(0b1110), 2.0);
    assert_eq!(m.coefficient(0b1101), -3.0);
    assert_eq!(m.coefficient(0b1011), 5.0);
    let plane = Plane::new(&[1.0, 0.0, 0.0], 4.0).unwrap();
    assert_eq!(plane.as_multivector().coefficient(0b1000), 4.0);
    // Translation by (0, 0, 1): T = 1 − ½ e₃₄.
    let t = Motor::from_translation(&[0.0, 0.0, 1.0]).unwrap();
    assert_eq!(t.as_multivector().coefficient(0b1100), -0.5);
    let x = t.apply_point(&p).unwrap().coordinates().unwrap();
    assert_eq!(x, vec![2.0, 3.0, 6.0]);
}

#[test]
fn rotation_about_an_axis_off_the_origin() {
    let mut rng = rng(60);
    // 2D: about a point c, x ↦ c + Rot(θ)(x − c), counter-clockwise.
    for _ in 0..50 {
        let c = coords(&mut rng, 2);
        let x = coords(&mut rng, 2);
        let theta = rng.gen_range(-3.0..3.0);
        let w = rng.gen_range(0.5..2.0); // the weight does not matter
        let axis = Point::new(&c).unwrap().as_multivector() * w;
        let m = Motor::from_axis_angle(&axis, theta).unwrap();
        let got = m
            .apply_point(&Point::new(&x).unwrap())
            .unwrap()
            .coordinates()
            .unwrap();
        let (s, co) = theta.sin_cos();
        let d = [x[0] - c[0], x[1] - c[1]];
        let want = [c[0] + co * d[0] - s * d[1], c[1] + s * d[0] + co * d[1]];
        assert!(max_diff(&got, &want) < 1e-14);
    }
    // 3D: about the line through (1, 2, 0) parallel to e₃ (the meet of x₁ = 1 and x₂ = 2),
    // oriented so that it turns e₁ toward e₂.
    let line = meet(
        &Plane::new(&[1.0, 0.0, 0.0], 1.0).unwrap(),
        &Plane::new(&[0.0, 1.0, 0.0], 2.0).unwrap(),
    )
    .unwrap();
    assert!(line.coefficient(0b011) > 0.0);
    let m = Motor::from_axis_angle(&line, 0.4).unwrap();
    let got = m
        .apply_point(&Point::new(&[2.0, 2.0, 5.0]).unwrap())
        .unwrap()
        .coordinates()
        .unwrap();
    let want = [1.0 + 0.4f64.cos(), 2.0 + 0.4f64.sin(), 5.0];
    assert!(max_diff(&got, &want) < 1e-15, "{got:?}");
    // A screw axis, a translation and a vector are refused.
    let pga = Signature::new(3, 0, 1).unwrap();
    let screw = Multivector::blade_by_name(pga, "e12", 1.0).unwrap()
        + Multivector::blade_by_name(pga, "e34", 1.0).unwrap();
    assert!(matches!(
        Motor::from_axis_angle(&screw, 1.0),
        Err(AlgebraError::NotAnAxis { .. })
    ));
    let shift = Multivector::blade_by_name(pga, "e14", 1.0).unwrap();
    assert!(matches!(
        Motor::from_axis_angle(&shift, 1.0),
        Err(AlgebraError::NotAnAxis { .. })
    ));
    let e1 = Multivector::basis_blade(pga, 1);
    assert!(Motor::from_axis_angle(&e1, 1.0).is_err());
}

#[test]
fn lorentz_matrix_of_versors() {
    let mut rng = rng(61);
    let st = sta::spacetime();
    // The metric diag(1, −1, −1, −1) is preserved: Λᵀ η Λ = η.
    let eta = DMatrix::from_diagonal(&DVector::from_vec(vec![1.0, -1.0, -1.0, -1.0]));
    for _ in 0..100 {
        let phi = rng.gen_range(-2.0..2.0);
        let raw = coords(&mut rng, 3);
        let len = dot(&raw, &raw).sqrt();
        let n = [raw[0] / len, raw[1] / len, raw[2] / len];
        let boost = sta::boost(phi, &raw).unwrap();
        let l = sta::lorentz_matrix(&boost).unwrap();
        assert!(max_abs_diff(&l, &lorentz(phi, &n)) < 1e-14 * phi.cosh());
        // A general Lorentz versor: boost times rotation, matrices multiply.
        let mut b = Multivector::zero(st);
        for (mask, c) in [(0b0110u64, 1.0), (0b1010, -0.4), (0b1100, 0.7)] {
            b.as_mut_slice()[mask as usize] = c * rng.gen_range(-1.0..1.0);
        }
        let rot = b.exp().unwrap();
        let both = sta::lorentz_matrix(&(&boost * &rot)).unwrap();
        let prod = &l * sta::lorentz_matrix(&rot).unwrap();
        assert!(max_abs_diff(&both, &prod) < 1e-13 * phi.cosh());
        assert!(
            max_abs_diff(&(both.transpose() * &eta * &both), &eta) < 1e-13 * phi.cosh().powi(2)
        );
    }
    let pga = Signature::new(3, 0, 1).unwrap();
    assert!(sta::lorentz_matrix(&Multivector::scalar(pga, 1.0)).is_err());
    assert!(sta::lorentz_matrix(&Multivector::scalar(st, 2.0)).is_err());
    // V Ṽ overflows: refused, not accepted against an infinite tolerance.
    let huge = Multivector::scalar(st, 1e200);
    assert!(sta::lorentz_matrix(&huge).is_err());
    assert!(Motor::new(Multivector::scalar(pga, 1e200)).is_err());
}

fn cross(a: &[f64], b: &[f64]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn sub(a: &[f64], b: &[f64]) -> Vec<f64> {
    a.iter().zip(b).map(|(x, y)| x - y).collect()
}

/// The distance from x to the line through p with direction d, by projection.
fn distance_by_projection(x: &[f64], p: &[f64], d: &[f64]) -> f64 {
    let v = sub(x, p);
    let t = dot(&v, d) / dot(d, d);
    let perp: Vec<f64> = v.iter().zip(d).map(|(a, b)| a - t * b).collect();
    dot(&perp, &perp).sqrt()
}

#[test]
fn line_signs_in_3d_are_pinned() {
    // The line through the origin and (1, 0, 0) has direction +e₁ and is the blade e₂₃.
    let o = Point::new(&[0.0, 0.0, 0.0]).unwrap();
    let x1 = Point::new(&[1.0, 0.0, 0.0]).unwrap();
    let l = o.join(&x1).unwrap();
    assert_eq!(l.direction(), vec![1.0, 0.0, 0.0]);
    assert_eq!(l.moment().as_slice(), &[0.0, 0.0, 0.0]);
    let e23 = Multivector::blade_by_name(Signature::new(3, 0, 1).unwrap(), "e23", 1.0).unwrap();
    assert_eq!(l.as_multivector(), &e23);
    // Reversing the points reverses the line.
    assert_eq!(x1.join(&o).unwrap().direction(), vec![-1.0, 0.0, 0.0]);
    // The line of the type documentation, blade by blade: through (1, 2, 3) and (2, 2, 5),
    // d = (1, 0, 2), p ∧ d = (M₁₂, M₁₃, M₂₃) = (−2, −1, 4).
    let l = Line::through(
        &Point::new(&[1.0, 2.0, 3.0]).unwrap(),
        &Point::new(&[2.0, 2.0, 5.0]).unwrap(),
    )
    .unwrap();
    let m = l.as_multivector();
    for (name, want) in [
        ("e23", 1.0),
        ("e13", 0.0),
        ("e12", 2.0),
        ("e14", 4.0),
        ("e24", 1.0),
        ("e34", -2.0),
    ] {
        let blade = Multivector::blade_by_name(m.signature(), name, 1.0).unwrap();
        let mask = blade.terms().next().unwrap().0;
        assert_eq!(m.coefficient(mask), want, "{name}");
    }
    assert_eq!(l.moment().as_slice(), &[-2.0, -1.0, 4.0]);
    assert!(max_diff(&l.point_nearest_origin(), &[-0.4, 2.0, 0.2]) < 1e-15);
    // The translator by (1, 2, 3) moves the origin to (1, 2, 3), and the e₁ axis to the line
    // through (1, 2, 3) along e₁.
    let t = Motor::from_translation(&[1.0, 2.0, 3.0]).unwrap();
    assert_eq!(
        t.apply_point(&o).unwrap().coordinates().unwrap(),
        vec![1.0, 2.0, 3.0]
    );
    let moved = t.apply_line(&o.join(&x1).unwrap()).unwrap();
    assert_eq!(moved.direction(), vec![1.0, 0.0, 0.0]);
    assert_eq!(moved.point_nearest_origin(), vec![0.0, 2.0, 3.0]);
    // Planes x₁ = 1 and x₂ = 2 meet in the line along e₁ × e₂ = e₃ through (1, 2, 0).
    let a = Plane::new(&[1.0, 0.0, 0.0], 1.0).unwrap();
    let b = Plane::new(&[0.0, 1.0, 0.0], 2.0).unwrap();
    let l = a.meet(&b).unwrap();
    assert_eq!(l.direction(), vec![0.0, 0.0, 1.0]);
    assert_eq!(l.point_nearest_origin(), vec![1.0, 2.0, 0.0]);
    assert_eq!(b.meet(&a).unwrap().direction(), vec![0.0, 0.0, -1.0]);
    // The typed meet is the untyped one.
    assert_eq!(l.as_multivector(), &meet(&a, &b).unwrap());
    // A quarter turn about that line (right-handed about +e₃) takes (2, 2, 5) to (1, 3, 5).
    let q = Motor::from_axis_angle(&l, std::f64::consts::FRAC_PI_2).unwrap();
    let x = q
        .apply_point(&Point::new(&[2.0, 2.0, 5.0]).unwrap())
        .unwrap()
        .coordinates()
        .unwrap();
    assert!(max_diff(&x, &[1.0, 3.0, 5.0]) < 1e-15, "{x:?}");
    // The e₁ axis and the point (0, 1, 0) span the plane with normal e₁ × e₂ = e₃.
    let plane = o
        .join(&x1)
        .unwrap()
        .join_point(&Point::new(&[0.0, 1.0, 0.0]).unwrap());
    assert_eq!(plane.unwrap().equation(), (vec![0.0, 0.0, 1.0], 0.0));
}

#[test]
fn lines_through_points_carry_plucker_coordinates() {
    let mut rng = rng(62);
    for n in 2..=5 {
        for _ in 0..50 {
            let p = coords(&mut rng, n);
            let q = coords(&mut rng, n);
            let l = Line::through(&Point::new(&p).unwrap(), &Point::new(&q).unwrap()).unwrap();
            assert_eq!(l.dim(), n);
            assert_eq!(l.as_multivector().grades(), vec![n - 1]);
            let d = sub(&q, &p);
            assert!(max_diff(&l.direction(), &d) < 1e-15, "N = {n}");
            let pv = Vector::from_components(&p).unwrap();
            let qv = Vector::from_components(&q).unwrap();
            let m = pv.wedge(&qv);
            assert!(max_diff(l.moment().as_slice(), m.as_slice()) < 1e-14);
            // The same line from a point and a direction.
            let l2 = Line::from_point_direction(&p, &d).unwrap();
            assert!((l2.as_multivector() - l.as_multivector()).max_abs() < 1e-14);
            // The nearest point to the origin lies on the line, perpendicular to d.
            let foot = l.point_nearest_origin();
            assert!(dot(&foot, &d).abs() < 1e-13);
            assert!(distance_by_projection(&foot, &p, &d) < 1e-13);
            // Distances agree with the projection formula; points on the line are at 0.
            let x = coords(&mut rng, n);
            let got = l.distance_to_point(&Point::new(&x).unwrap()).unwrap();
            let want = distance_by_projection(&x, &p, &d);
            assert!(
                (got - want).abs() < 1e-13 * (1.0 + want),
                "N = {n}: {got} vs {want}"
            );
            let t = rng.gen_range(-2.0..2.0);
            let on: Vec<f64> = p.iter().zip(&d).map(|(a, b)| a + t * b).collect();
            assert!(l.distance_to_point(&Point::new(&on).unwrap()).unwrap() < 1e-14);
            // The line round-trips through its multivector.
            let back = Line::from_multivector(l.as_multivector().clone()).unwrap();
            assert_eq!(back, l);
        }
    }
}

#[test]
fn lines_meet_planes_in_their_intersection() {
    let mut rng = rng(63);
    for n in 2..=5 {
        for _ in 0..50 {
            let p = coords(&mut rng, n);
            let d = coords(&mut rng, n);
            let a = coords(&mut rng, n);
            let delta = rng.gen_range(-2.0..2.0);
            if dot(&a, &d).abs() < 0.1 {
                continue;
            }
            let l = Line::from_point_direction(&p, &d).unwrap();
            let x = l
                .meet_plane(&Plane::new(&a, delta).unwrap())
                .unwrap()
                .coordinates()
                .unwrap();
            // x = p + t d with a·x = δ.
            let t = (delta - dot(&a, &p)) / dot(&a, &d);
            let want: Vec<f64> = p.iter().zip(&d).map(|(pi, di)| pi + t * di).collect();
            assert!(max_diff(&x, &want) < 1e-12 * (1.0 + t.abs()), "N = {n}");
        }
        // Parallel: the ideal point of the line's direction. In the plane: refused.
        let mut d = vec![0.0; n];
        d[0] = 1.0;
        let mut normal = vec![0.0; n];
        normal[1] = 1.0;
        let l = Line::from_point_direction(&vec![0.5; n], &d).unwrap();
        let ideal = l.meet_plane(&Plane::new(&normal, 3.0).unwrap()).unwrap();
        assert_eq!(ideal.weight(), 0.0);
        assert!(matches!(
            ideal.coordinates(),
            Err(AlgebraError::PointAtInfinity { .. })
        ));
        // The ideal point is the line's direction: joined with a point it gives a parallel.
        let parallel = Point::new(&vec![0.0; n]).unwrap().join(&ideal).unwrap();
        let pd = parallel.direction();
        assert!(pd[0] != 0.0 && pd[1..].iter().all(|&c| c == 0.0), "{pd:?}");
        assert!(matches!(
            l.meet_plane(&Plane::new(&normal, 0.5).unwrap()),
            Err(AlgebraError::Degenerate { .. })
        ));
    }
}

#[test]
fn planes_meet_and_lines_join_in_3d() {
    let mut rng = rng(64);
    for _ in 0..100 {
        let a = coords(&mut rng, 3);
        let b = coords(&mut rng, 3);
        let (da, db) = (rng.gen_range(-2.0..2.0), rng.gen_range(-2.0..2.0));
        let axb = cross(&a, &b);
        if dot(&axb, &axb) < 0.01 {
            continue;
        }
        let l = Plane::new(&a, da)
            .unwrap()
            .meet(&Plane::new(&b, db).unwrap())
            .unwrap();
        assert!(max_diff(&l.direction(), &axb) < 1e-14);
        // Its points satisfy both plane equations.
        let p = l.point_nearest_origin();
        let s = 1.0 + p.iter().fold(0.0f64, |m, c| m.max(c.abs()));
        assert!((dot(&a, &p) - da).abs() < 1e-13 * s && (dot(&b, &p) - db).abs() < 1e-13 * s);
        // The plane through the line and a point contains both.
        let x = coords(&mut rng, 3);
        if l.distance_to_point(&Point::new(&x).unwrap()).unwrap() < 0.1 {
            continue;
        }
        let plane = l.join_point(&Point::new(&x).unwrap()).unwrap();
        let (normal, delta) = plane.equation();
        let scale = dot(&normal, &normal).sqrt();
        let q: Vec<f64> = p.iter().zip(&axb).map(|(pi, di)| pi + 0.7 * di).collect();
        for y in [&x, &p, &q] {
            assert!((dot(&normal, y) - delta).abs() < 1e-12 * scale * s);
        }
        // Its normal is d × (x − p).
        let want = cross(&axb, &sub(&x, &p));
        assert!(max_diff(&normal, &want) < 1e-12 * scale);
    }
    // Parallel planes, a point on the line, wrong dimensions.
    let a = Plane::new(&[1.0, 2.0, 0.0], 1.0).unwrap();
    let b = Plane::new(&[2.0, 4.0, 0.0], 5.0).unwrap();
    assert!(matches!(a.meet(&b), Err(AlgebraError::Degenerate { .. })));
    assert!(matches!(a.meet(&a), Err(AlgebraError::Degenerate { .. })));
    let l = Line::from_point_direction(&[1.0, 2.0, 3.0], &[0.0, 1.0, 0.0]).unwrap();
    let on = Point::new(&[1.0, 7.0, 3.0]).unwrap();
    assert!(matches!(
        l.join_point(&on),
        Err(AlgebraError::Degenerate { .. })
    ));
    assert!(matches!(
        l.join_point(&Point::ideal(&[0.0, 2.0, 0.0]).unwrap()),
        Err(AlgebraError::Degenerate { .. })
    ));
    // An ideal point not along the line spans the plane through the line parallel to it.
    let (normal, d) = l
        .join_point(&Point::ideal(&[1.0, 0.0, 0.0]).unwrap())
        .unwrap()
        .equation();
    assert!(normal[0] == 0.0 && normal[1] == 0.0 && (d / normal[2] - 3.0).abs() < 1e-15);
    let p2 = Plane::new(&[1.0, 0.0], 0.0).unwrap();
    assert!(matches!(
        p2.meet(&Plane::new(&[0.0, 1.0], 0.0).unwrap()),
        Err(AlgebraError::WrongSignature { .. })
    ));
    let l4 = Line::from_point_direction(&[0.0; 4], &[1.0, 0.0, 0.0, 0.0]).unwrap();
    assert!(matches!(
        l4.join_point(&Point::new(&[0.0, 1.0, 0.0, 0.0]).unwrap()),
        Err(AlgebraError::WrongSignature { .. })
    ));
    assert!(
        a.meet(&Plane::new(&[1.0, 0.0, 0.0, 0.0], 0.0).unwrap())
            .is_err()
    );
}

#[test]
fn bad_lines_are_refused() {
    let p = Point::new(&[1.0, 2.0, 3.0]).unwrap();
    assert!(matches!(
        Line::through(&p, &p),
        Err(AlgebraError::Degenerate { .. })
    ));
    let u = Point::ideal(&[1.0, 0.0, 0.0]).unwrap();
    let v = Point::ideal(&[0.0, 1.0, 0.0]).unwrap();
    assert!(matches!(
        Line::through(&u, &v),
        Err(AlgebraError::Degenerate { .. })
    ));
    assert!(matches!(
        Point::ideal(&[0.0, 0.0, 0.0]),
        Err(AlgebraError::ZeroLength { .. })
    ));
    assert!(matches!(
        Line::from_point_direction(&[1.0, 2.0, 3.0], &[0.0; 3]),
        Err(AlgebraError::ZeroLength { .. })
    ));
    assert!(matches!(
        Line::from_point_direction(&[1.0, 2.0, 3.0], &[1.0, 0.0]),
        Err(AlgebraError::DimensionMismatch { .. })
    ));
    assert!(matches!(
        Line::from_point_direction(&[f64::NAN, 2.0, 3.0], &[1.0, 0.0, 0.0]),
        Err(AlgebraError::NonFinite { .. })
    ));
    // A point joined with an ideal point: the line through it along that direction.
    let l = p.join(&u).unwrap();
    assert_eq!(l.direction(), vec![1.0, 0.0, 0.0]);
    assert_eq!(l.distance_to_point(&p).unwrap(), 0.0);
    assert!(matches!(
        l.distance_to_point(&u),
        Err(AlgebraError::PointAtInfinity { .. })
    ));
    let pga = Signature::new(3, 0, 1).unwrap();
    let name = |s: &str| Multivector::blade_by_name(pga, s, 1.0).unwrap();
    // Not a blade (a screw axis), at infinity, zero, wrong grade, wrong algebra.
    for (m, what) in [
        (&name("e12") + &name("e34"), "screw"),
        (name("e14"), "ideal"),
        (Multivector::zero(pga), "zero"),
    ] {
        assert!(
            matches!(
                Line::from_multivector(m),
                Err(AlgebraError::NotALine { .. })
            ),
            "{what}"
        );
    }
    assert!(matches!(
        Line::from_multivector(name("e1")),
        Err(AlgebraError::MixedGrades { .. })
    ));
    let e12 = Multivector::blade_by_name(Signature::euclidean(3), "e12", 1.0).unwrap();
    assert!(matches!(
        Line::from_multivector(e12),
        Err(AlgebraError::WrongSignature { .. })
    ));
    // Different dimensions.
    let q2 = Point::new(&[1.0, 2.0]).unwrap();
    assert!(Line::through(&p, &q2).is_err());
    assert!(l.distance_to_point(&q2).is_err());
}

fn point_strategy(n: usize) -> impl Strategy<Value = Vec<f64>> {
    proptest::collection::vec(-3.0f64..3.0, n)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Motors move lines as they move points: M (P ∨ Q) M̃ = (M P M̃) ∨ (M Q M̃).
    #[test]
    fn motors_move_lines_with_their_points(
        (p, q) in (2usize..=4).prop_flat_map(|n| (point_strategy(n), point_strategy(n))),
        seed in 0u64..1000,
    ) {
        let n = p.len();
        prop_assume!(max_diff(&p, &q) > 1e-3);
        let m = random_motor(&mut rng(seed), n);
        let (pp, qq) = (Point::new(&p).unwrap(), Point::new(&q).unwrap());
        let moved = m.apply_line(&pp.join(&qq).unwrap()).unwrap();
        let want = m.apply_point(&pp).unwrap().join(&m.apply_point(&qq).unwrap()).unwrap();
        let err = (moved.as_multivector() - want.as_multivector()).max_abs();
        prop_assert!(err < 1e-12 * want.as_multivector().max_abs().max(1.0), "{err:e}");
        // The moved direction is the rotated direction.
        let d = m.rotor().rotate_vector(&Vector::from_components(&sub(&q, &p)).unwrap());
        prop_assert!(max_diff(&moved.direction(), d.as_slice()) < 1e-12);
    }

    /// A rotation about a 3D line keeps the line's points and turns the others about it by
    /// the angle: distances to the line are kept, and a quarter turn moves a point by √2 r.
    #[test]
    fn rotations_about_lines_fix_the_line(
        p in point_strategy(3),
        d in point_strategy(3),
        x in point_strategy(3),
        angle in -3.0f64..3.0,
    ) {
        prop_assume!(dot(&d, &d) > 0.01);
        let l = Line::from_point_direction(&p, &d).unwrap();
        let m = Motor::from_axis_angle(&l, angle).unwrap();
        let on: Vec<f64> = p.iter().zip(&d).map(|(a, b)| a + 0.3 * b).collect();
        let fixed = m.apply_point(&Point::new(&on).unwrap()).unwrap().coordinates().unwrap();
        prop_assert!(max_diff(&fixed, &on) < 1e-13);
        let xp = Point::new(&x).unwrap();
        let moved = m.apply_point(&xp).unwrap();
        let r = l.distance_to_point(&xp).unwrap();
        prop_assert!((l.distance_to_point(&moved).unwrap() - r).abs() < 1e-12);
        let chord = 2.0 * r * (0.5 * angle).sin().abs();
        let y = moved.coordinates().unwrap();
        prop_assert!((dot(&sub(&y, &x), &sub(&y, &x)).sqrt() - chord).abs() < 1e-12);
        // Right-handed about d: (x − foot) turns toward d × (x − foot).
        let v = sub(&x, &l.point_nearest_origin());
        let v_perp: Vec<f64> = {
            let t = dot(&v, &d) / dot(&d, &d);
            v.iter().zip(&d).map(|(a, b)| a - t * b).collect()
        };
        prop_assume!(r > 0.1);
        let turn = dot(&sub(&y, &x), &cross(&d, &v_perp));
        prop_assert!(turn * angle.sin() >= -1e-12, "{turn} at {angle}");
    }
}
