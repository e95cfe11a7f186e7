//! Projective GA points, planes, join, meet and motors, and spacetime boosts: checked
//! against Euclidean facts computed without the algebra (incidence a·x = d, intersections by
//! a linear solve, homogeneous matrices, the Lorentz matrix).

use crate::support::*;
use nalgebra::{DMatrix, DVector};
use rand::Rng;
use rotorflow::algebra::pga::{Motor, Plane, Point, join, meet};
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
