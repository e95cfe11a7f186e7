//! Conformal GA: points, spheres, planes and the four kinds of conformal versors, checked
//! against the Euclidean maps they should perform (computed without the algebra) and
//! against their exponential and logarithm.

use crate::assert_close;
use crate::support::*;
use proptest::prelude::*;
use rand::Rng;
use rotorflow::algebra::cga;
use rotorflow::prelude::*;

fn coords(rng: &mut impl Rng, n: usize, r: f64) -> Vec<f64> {
    (0..n).map(|_| rng.gen_range(-r..r)).collect()
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).fold(0.0, |m, (x, y)| m.max((x - y).abs()))
}

fn sandwich(v: &Multivector, x: &Multivector) -> Multivector {
    &(v * x) * &v.reverse()
}

/// max |Y/w − up(want)| / (1 + |want|²), with w = −Y · n∞ the weight of Y: zero exactly when
/// Y is a multiple of up(want).
fn distance_to_up(y: &Multivector, want: &[f64]) -> f64 {
    let n = want.len();
    let w = -y.scalar_product(&cga::ninf(n).unwrap());
    let up = cga::up(want).unwrap();
    (&(y * (1.0 / w)) - &up).max_abs() / (1.0 + dot(want, want))
}

/// The special conformal map of the transversion by b.
fn transversion(b: &[f64], x: &[f64]) -> Vec<f64> {
    let den = 1.0 + 2.0 * dot(b, x) + dot(b, b) * dot(x, x);
    x.iter()
        .zip(b)
        .map(|(xi, bi)| (xi + dot(x, x) * bi) / den)
        .collect()
}

/// x ∈ ℝᴺ as a vector of Cl(N + 1, 1, 0).
fn vector(x: &[f64]) -> Multivector {
    let mut m = Multivector::zero(cga::conformal(x.len()).unwrap());
    for (i, &c) in x.iter().enumerate() {
        m.as_mut_slice()[1 << i] = c;
    }
    m
}

fn e_plus(n: usize) -> Multivector {
    Multivector::basis_blade(cga::conformal(n).unwrap(), 1 << n)
}

#[test]
fn null_vectors_and_points_are_pinned() {
    for n in 2..=5 {
        let (o, inf) = (cga::n0(n).unwrap(), cga::ninf(n).unwrap());
        assert_eq!(o.scalar_product(&o), 0.0);
        assert_eq!(inf.scalar_product(&inf), 0.0);
        assert_eq!(o.scalar_product(&inf), -1.0);
        assert_eq!(cga::up(&vec![0.0; n]).unwrap(), o);
        // n₀ = ½(e₋ − e₊), n∞ = e₋ + e₊.
        let (p, m) = (1usize << n, 1usize << (n + 1));
        assert_eq!((o.as_slice()[p], o.as_slice()[m]), (-0.5, 0.5));
        assert_eq!((inf.as_slice()[p], inf.as_slice()[m]), (1.0, 1.0));
    }
    // up(1, 2, 3) = e₁ + 2e₂ + 3e₃ + 6.5 e₊ + 7.5 e₋ (n₀ + 7 n∞ in the e₊, e₋ basis).
    let x = cga::up(&[1.0, 2.0, 3.0]).unwrap();
    let sig = cga::conformal(3).unwrap();
    let mut want = Multivector::zero(sig);
    for (mask, c) in [(1, 1.0), (2, 2.0), (4, 3.0), (8, 6.5), (16, 7.5)] {
        want.as_mut_slice()[mask] = c;
    }
    assert_eq!(x, want);
    assert_eq!(sig, Signature::new(4, 1, 0).unwrap());
    // Points are null, X · Y = −½ |x − y|², and down undoes up at any weight and sign.
    let mut rng = rng(81);
    for n in 2..=5 {
        for _ in 0..50 {
            let (a, b) = (coords(&mut rng, n, 3.0), coords(&mut rng, n, 3.0));
            let (xa, xb) = (cga::up(&a).unwrap(), cga::up(&b).unwrap());
            let scale = 1.0 + dot(&a, &a);
            assert!(xa.scalar_product(&xa).abs() < 1e-14 * scale);
            let d: Vec<f64> = a.iter().zip(&b).map(|(p, q)| p - q).collect();
            assert_close!(xa.scalar_product(&xb), -0.5 * dot(&d, &d), 1e-13 * scale);
            assert!(max_diff(&cga::down(&xa).unwrap(), &a) < 1e-15 * scale);
            let w = rng.gen_range(0.1..10.0) * if rng.r#gen::<bool>() { 1.0 } else { -1.0 };
            assert!(max_diff(&cga::down(&(&xa * w)).unwrap(), &a) < 1e-14 * scale);
        }
    }
}

#[test]
fn far_points_keep_their_precision() {
    // The weight a₋ − a₊ cancels far from the origin; down reads it from X² = 0 instead.
    let mut rng = rng(85);
    for scale in [1e3, 1e6, 1e9, 1e12] {
        for _ in 0..20 {
            let x = coords(&mut rng, 3, scale);
            let y = cga::down(&cga::up(&x).unwrap()).unwrap();
            let err = max_diff(&x, &y) / scale;
            assert!(err < 1e-15, "|x| ~ {scale:e}: {err:e}");
            // A sandwich does use a₋ − a₊: a point moved by a unit-size versor carries an
            // absolute error of about ε |x|², as the module documentation says.
            let t = coords(&mut rng, 3, 1.0);
            let moved = sandwich(&cga::translator(&t).unwrap(), &cga::up(&x).unwrap());
            let want: Vec<f64> = x.iter().zip(&t).map(|(a, b)| a + b).collect();
            let err = max_diff(&cga::down(&moved).unwrap(), &want);
            assert!(
                err < 16.0 * f64::EPSILON * scale * scale,
                "|x| ~ {scale:e}: {err:e}"
            );
        }
    }
}

#[test]
fn versors_are_pinned_in_3d() {
    let origin = cga::up(&[0.0, 0.0, 0.0]).unwrap();
    // A translator by (1, 2, 3) moves the origin to (1, 2, 3), exactly.
    let t = cga::translator(&[1.0, 2.0, 3.0]).unwrap();
    let moved = sandwich(&t, &origin);
    assert_eq!(moved, cga::up(&[1.0, 2.0, 3.0]).unwrap());
    assert_eq!(cga::down(&moved).unwrap(), vec![1.0, 2.0, 3.0]);
    // T = 1 + ½ n∞ t: its e₁e₊ and e₁e₋ coefficients are −½ t₁ (n∞ e₁ = −e₁ n∞).
    assert_eq!(t.scalar_part(), 1.0);
    assert_eq!(t.coefficient(0b01001), -0.5);
    assert_eq!(t.coefficient(0b10001), -0.5);
    // A quarter turn from e₁ toward e₂.
    let r = Rotor::from_plane_angle(3, 0, 1, std::f64::consts::FRAC_PI_2).unwrap();
    let y = sandwich(
        &cga::rotor(&r).unwrap(),
        &cga::up(&[1.0, 0.0, 0.0]).unwrap(),
    );
    assert!(max_diff(&cga::down(&y).unwrap(), &[0.0, 1.0, 0.0]) < 1e-15);
    // A dilator by 2 doubles (1, 2, 3); its sandwich gives up(2x)/2.
    let d = cga::dilator(3, 2.0).unwrap();
    let y = sandwich(&d, &cga::up(&[1.0, 2.0, 3.0]).unwrap());
    assert!(max_diff(&cga::down(&y).unwrap(), &[2.0, 4.0, 6.0]) < 1e-14);
    let half = &cga::up(&[2.0, 4.0, 6.0]).unwrap() * 0.5;
    assert!((&y - &half).max_abs() < 1e-14);
    // The transversion by e₁ takes e₁ to e₁/2: (x + x² b) / (1 + 2 b·x + b² x²) = 2/4.
    let k = cga::transversor(&[1.0, 0.0, 0.0]).unwrap();
    let y = sandwich(&k, &cga::up(&[1.0, 0.0, 0.0]).unwrap());
    assert_eq!(cga::down(&y).unwrap(), vec![0.5, 0.0, 0.0]);
    // It fixes the origin, and sends −b/b² to infinity.
    assert_eq!(cga::down(&sandwich(&k, &origin)).unwrap(), vec![0.0; 3]);
    let lost = sandwich(&k, &cga::up(&[-1.0, 0.0, 0.0]).unwrap());
    assert!(matches!(
        cga::down(&lost),
        Err(AlgebraError::PointAtInfinity { .. })
    ));
    // K = e₊ T_b e₊: the translation seen through the inversion in the unit sphere, which
    // is e₊ up(x) e₊ = −x² up(x/x²).
    let mut rng = rng(82);
    for n in 2..=4 {
        let b = coords(&mut rng, n, 1.0);
        let ep = e_plus(n);
        let conj = &(&ep * &cga::translator(&b).unwrap()) * &ep;
        assert!((&conj - &cga::transversor(&b).unwrap()).max_abs() < 1e-15);
        let x = coords(&mut rng, n, 2.0);
        let inv = &(&ep * &cga::up(&x).unwrap()) * &ep;
        let x2 = dot(&x, &x);
        let want = &cga::up(&x.iter().map(|c| c / x2).collect::<Vec<_>>()).unwrap() * -x2;
        assert!((&inv - &want).max_abs() < 1e-13 * (1.0 + x2));
    }
}

/// A map of ℝᴺ, computed without the algebra.
type PointMap = Box<dyn Fn(&[f64]) -> Vec<f64>>;

/// A versor of one kind in Cl(n + 1, 1, 0) with the Euclidean map it should perform.
fn versor_and_map(kind: u8, n: usize, seed: u64) -> (Multivector, PointMap) {
    let mut rng = rng(seed);
    match kind {
        0 => {
            let t = coords(&mut rng, n, 3.0);
            let v = cga::translator(&t).unwrap();
            (
                v,
                Box::new(move |x| x.iter().zip(&t).map(|(a, b)| a + b).collect()),
            )
        }
        1 => {
            let r = random_rotor(&mut rng, n);
            let v = cga::rotor(&r).unwrap();
            (
                v,
                Box::new(move |x| {
                    r.rotate_vector(&Vector::from_components(x).unwrap())
                        .as_slice()
                        .to_vec()
                }),
            )
        }
        2 => {
            let s = rng.gen_range(0.2f64..5.0);
            let v = cga::dilator(n, s).unwrap();
            (v, Box::new(move |x| x.iter().map(|a| s * a).collect()))
        }
        _ => {
            let b = coords(&mut rng, n, 0.5);
            let v = cga::transversor(&b).unwrap();
            (v, Box::new(move |x| transversion(&b, x)))
        }
    }
}

fn point_strategy() -> impl Strategy<Value = Vec<f64>> {
    (2usize..=4).prop_flat_map(|n| proptest::collection::vec(-2.0f64..2.0, n))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// V up(x) Ṽ is a multiple of up(f(x)) for the map f of each versor, in 2D, 3D and 4D.
    #[test]
    fn sandwiches_are_the_expected_maps(x in point_strategy(), kind in 0u8..4, seed in 0u64..1000) {
        let n = x.len();
        let (v, f) = versor_and_map(kind, n, seed);
        // Even and unit: V Ṽ = 1.
        prop_assert!(v.odd().max_abs() == 0.0);
        let mut vv = &v * &v.reverse();
        vv.as_mut_slice()[0] -= 1.0;
        prop_assert!(vv.max_abs() < 1e-14, "V Ṽ − 1 = {:e}", vv.max_abs());
        let want = f(&x);
        if kind == 3 {
            // Keep away from the point the transversion sends to infinity.
            prop_assume!(dot(&want, &want) < 1e3);
        }
        let y = sandwich(&v, &cga::up(&x).unwrap());
        // A vector up to round-off in grade 3.
        prop_assert!((&y - &y.grade(1)).max_abs() < 1e-14 * y.max_abs());
        let err = distance_to_up(&y, &want);
        prop_assert!(err < 1e-13, "kind {kind}, N = {n}: {err:e}");
        let got = cga::down(&y).unwrap();
        prop_assert!(max_diff(&got, &want) < 1e-12 * (1.0 + dot(&want, &want)));
    }

    /// Versors move spheres and planes with their points: a point on σ moves to a point on
    /// V σ Ṽ (a transversion may turn a plane into a sphere and back).
    #[test]
    fn versors_move_spheres_with_their_points(
        c in point_strategy(),
        radius in 0.3f64..2.0,
        kind in 0u8..4,
        seed in 0u64..1000,
        plane_instead in any::<bool>(),
    ) {
        let n = c.len();
        let mut rng = rng(seed ^ 0x5eed);
        let dir = coords(&mut rng, n, 1.0);
        let len = dot(&dir, &dir).sqrt();
        prop_assume!(len > 0.1);
        let surface = if plane_instead {
            cga::plane(&dir, dot(&dir, &c)).unwrap()
        } else {
            cga::sphere(&c, radius).unwrap()
        };
        // A point on the surface: c + r d̂ on the sphere, c + a vector ⟂ d on the plane.
        let on: Vec<f64> = if plane_instead {
            let u = coords(&mut rng, n, 1.0);
            let t = dot(&u, &dir) / (len * len);
            c.iter().zip(&u).zip(&dir).map(|((ci, ui), di)| ci + ui - t * di).collect()
        } else {
            c.iter().zip(&dir).map(|(ci, di)| ci + radius * di / len).collect()
        };
        prop_assert!(cga::point_on(&surface, &on, 1e-13).unwrap());
        prop_assert!(cga::up(&on).unwrap().scalar_product(&surface).abs() < 1e-13);
        let (v, f) = versor_and_map(kind, n, seed);
        let image = f(&on);
        prop_assume!(dot(&image, &image) < 1e3);
        let moved = sandwich(&v, &surface);
        match cga::signed_distance(&moved, &image) {
            Ok(dist) => prop_assert!(dist.abs() < 1e-11 * (1.0 + dot(&image, &image)), "{dist:e}"),
            // A transversion may send the surface through infinity's neighbourhood into
            // a sphere too large to tell from a plane; that is the only allowed refusal.
            Err(e) => prop_assert!(kind == 3, "{e}"),
        }
    }
}

#[test]
fn exp_of_log_gives_each_versor_back() {
    // Cl(3, 1, 0) and Cl(4, 1, 0) have N ≤ 5 (the closed forms); Cl(5, 1, 0) goes through
    // the general route.
    let mut rng = rng(83);
    let mut checked = 0;
    for n in 2..=4 {
        let (o, inf) = (cga::n0(n).unwrap(), cga::ninf(n).unwrap());
        for _ in 0..50 {
            let t = coords(&mut rng, n, 3.0);
            let b = coords(&mut rng, n, 1.0);
            let s = rng.gen_range(0.1f64..10.0);
            let r = random_rotor(&mut rng, n);
            let (tv, bv) = (vector(&t), vector(&b));
            // Each versor with the generator it is the exponential of.
            let cases = [
                (cga::translator(&t).unwrap(), &inf.wedge(&tv) * 0.5),
                (cga::dilator(n, s).unwrap(), &o.wedge(&inf) * (0.5 * s.ln())),
                (cga::transversor(&b).unwrap(), o.wedge(&bv)),
                (cga::rotor(&r).unwrap(), {
                    let log = Multivector::from(&r.log());
                    let mut m = Multivector::zero(o.signature());
                    for (mask, c) in log.terms() {
                        m.as_mut_slice()[mask as usize] = c;
                    }
                    m
                }),
            ];
            for (k, (v, generator)) in cases.iter().enumerate() {
                let log = v.log().unwrap();
                assert_eq!(log.grades().iter().filter(|&&g| g != 2).count(), 0);
                let back = log.exp().unwrap();
                let err = (&back - v).max_abs() / v.max_abs();
                assert!(err < 1e-14, "N = {n}, versor {k}: {err:e}");
                // The principal logarithm is the generator (the rotor's angles are ≤ π).
                let gen_err = (&log - generator).max_abs() / generator.max_abs().max(1.0);
                assert!(gen_err < 1e-13, "N = {n}, versor {k}: {gen_err:e}");
                assert!((&generator.exp().unwrap() - v).max_abs() < 1e-14 * v.max_abs());
                checked += 1;
            }
        }
    }
    assert_eq!(checked, 3 * 50 * 4);
}

#[test]
fn exp_and_log_stop_above_6d_cga() {
    // Cl(7, 1, 0) (N = 8) is the largest conformal algebra of the general route.
    let t = cga::translator(&[1.0, 0.0, 0.0, 0.0, 0.5, 0.0]).unwrap();
    let l = t.log().unwrap();
    assert!((&l.exp().unwrap() - &t).max_abs() < 1e-15);
    let t7 = cga::translator(&[1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]).unwrap();
    assert!(matches!(
        t7.log(),
        Err(AlgebraError::UnsupportedDimension { max: 8, .. })
    ));
    let b = &cga::n0(7).unwrap().wedge(&cga::ninf(7).unwrap()) * 0.3;
    assert!(matches!(
        b.exp(),
        Err(AlgebraError::UnsupportedDimension { max: 8, .. })
    ));
    // The constructors and sandwiches need neither.
    let y = sandwich(&t7, &cga::up(&[0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0]).unwrap());
    assert!(
        max_diff(
            &cga::down(&y).unwrap(),
            &[1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0]
        ) < 1e-15
    );
}

#[test]
fn spheres_and_planes_measure_distances() {
    let mut rng = rng(84);
    for n in 2..=4 {
        for _ in 0..50 {
            let c = coords(&mut rng, n, 3.0);
            let r = rng.gen_range(0.1..3.0);
            let s = cga::sphere(&c, r).unwrap();
            // σ² = r², −σ · n∞ = 1, and X · σ = ½ (r² − |x − c|²).
            assert_close!(s.scalar_product(&s), r * r, 1e-13 * (1.0 + dot(&c, &c)));
            assert_close!(-s.scalar_product(&cga::ninf(n).unwrap()), 1.0, 1e-15);
            let x = coords(&mut rng, n, 3.0);
            let d: Vec<f64> = x.iter().zip(&c).map(|(a, b)| a - b).collect();
            let dist = dot(&d, &d).sqrt();
            let scale = 1.0 + dot(&c, &c) + dot(&x, &x);
            let inner = cga::up(&x).unwrap().scalar_product(&s);
            assert_close!(inner, 0.5 * (r * r - dist * dist), 1e-13 * scale);
            // The signed distance ignores the sphere's weight and sign.
            for w in [1.0, 3.5, -0.25] {
                let got = cga::signed_distance(&(&s * w), &x).unwrap();
                assert_close!(got, dist - r, 1e-13 * scale);
            }
            assert_eq!(cga::contains(&s, &x).unwrap(), dist <= r);
            assert_eq!(
                cga::point_on(&s, &x, 1e-9).unwrap(),
                (dist - r).abs() <= 1e-9
            );
            // Planes: signed distance along the unit normal, X · π equals it.
            let a = coords(&mut rng, n, 2.0);
            if dot(&a, &a) < 0.01 {
                continue;
            }
            let delta = rng.gen_range(-2.0..2.0);
            let p = cga::plane(&a, delta).unwrap();
            let want = (dot(&a, &x) - delta) / dot(&a, &a).sqrt();
            assert_close!(cga::signed_distance(&p, &x).unwrap(), want, 1e-13 * scale);
            assert_close!(cga::up(&x).unwrap().scalar_product(&p), want, 1e-13 * scale);
            assert_eq!(cga::contains(&p, &x).unwrap(), want <= 0.0);
        }
    }
    // Pinned: the unit sphere about (1, 0, 0) and the plane x₃ = 1.
    let s = cga::sphere(&[1.0, 0.0, 0.0], 1.0).unwrap();
    assert!(cga::point_on(&s, &[2.0, 0.0, 0.0], 0.0).unwrap());
    assert!(cga::point_on(&s, &[1.0, 1.0, 0.0], 0.0).unwrap());
    assert!(cga::contains(&s, &[1.0, 0.0, 0.0]).unwrap());
    assert!(!cga::contains(&s, &[-0.5, 0.0, 0.0]).unwrap());
    let p = cga::plane(&[0.0, 0.0, 3.0], 3.0).unwrap();
    assert_eq!(cga::signed_distance(&p, &[7.0, -2.0, 4.0]).unwrap(), 3.0);
    assert!(cga::contains(&p, &[0.0, 0.0, 0.0]).unwrap());
    assert!(!cga::contains(&p, &[0.0, 0.0, 2.0]).unwrap());
    // A dilation by 3 scales the radius; a translation moves the centre.
    let d = cga::dilator(3, 3.0).unwrap();
    let big = sandwich(&d, &s);
    assert_close!(
        cga::signed_distance(&big, &[0.0, 0.0, 0.0]).unwrap(),
        0.0,
        1e-14
    );
    assert_close!(
        cga::signed_distance(&big, &[3.0, 0.0, 0.0]).unwrap(),
        -3.0,
        1e-14
    );
    let t = cga::translator(&[0.0, 5.0, 0.0]).unwrap();
    let far = sandwich(&t, &s);
    assert_close!(
        cga::signed_distance(&far, &[1.0, 5.0, 0.0]).unwrap(),
        -1.0,
        1e-14
    );
}

#[test]
fn bad_input_is_refused() {
    let inf = cga::ninf(3).unwrap();
    assert!(matches!(
        cga::down(&inf),
        Err(AlgebraError::PointAtInfinity { .. })
    ));
    let s = cga::sphere(&[1.0, 2.0, 3.0], 0.5).unwrap();
    assert!(matches!(cga::down(&s), Err(AlgebraError::NotAPoint { .. })));
    let p = cga::plane(&[1.0, 0.0, 0.0], 1.0).unwrap();
    assert!(matches!(cga::down(&p), Err(AlgebraError::NotAPoint { .. })));
    assert!(matches!(
        cga::down(&Multivector::zero(inf.signature())),
        Err(AlgebraError::PointAtInfinity { .. })
    ));
    let biv = cga::n0(3).unwrap().wedge(&inf);
    assert!(matches!(
        cga::down(&biv),
        Err(AlgebraError::MixedGrades { .. })
    ));
    let pga = Multivector::basis_blade(Signature::new(3, 0, 1).unwrap(), 1);
    assert!(matches!(
        cga::down(&pga),
        Err(AlgebraError::WrongSignature { .. })
    ));
    let mut nan = cga::up(&[1.0, 2.0, 3.0]).unwrap();
    nan.as_mut_slice()[1] = f64::NAN;
    assert!(matches!(
        cga::down(&nan),
        Err(AlgebraError::NonFinite { .. })
    ));
    for scale in [0.0, -1.0] {
        assert!(matches!(
            cga::dilator(3, scale),
            Err(AlgebraError::NotPositive { .. })
        ));
    }
    assert!(matches!(
        cga::dilator(3, f64::INFINITY),
        Err(AlgebraError::NonFinite { .. })
    ));
    assert!(matches!(
        cga::sphere(&[0.0, 0.0], 0.0),
        Err(AlgebraError::NotPositive { .. })
    ));
    assert!(matches!(
        cga::plane(&[0.0, 0.0], 1.0),
        Err(AlgebraError::ZeroLength { .. })
    ));
    assert!(matches!(
        cga::up(&[1.0, f64::NAN]),
        Err(AlgebraError::NonFinite { .. })
    ));
    assert!(matches!(
        cga::up(&[1e200, 0.0]),
        Err(AlgebraError::Overflow { .. })
    ));
    assert!(matches!(
        cga::up(&[1.0]),
        Err(AlgebraError::WrongSignature { .. })
    ));
    assert!(matches!(
        cga::conformal(15),
        Err(AlgebraError::DimensionTooLarge { .. })
    ));
    assert!(cga::conformal(14).is_ok());
    // A point, an imaginary sphere and n∞ are not surfaces; lengths must match.
    let x = cga::up(&[1.0, 2.0, 3.0]).unwrap();
    let imaginary = &x + &(&inf * 2.0);
    for (m, what) in [(x, "point"), (imaginary, "imaginary"), (inf, "n∞")] {
        assert!(
            matches!(
                cga::signed_distance(&m, &[0.0; 3]),
                Err(AlgebraError::NotASphere { .. })
            ),
            "{what}"
        );
    }
    assert!(matches!(
        cga::signed_distance(&s, &[0.0; 2]),
        Err(AlgebraError::DimensionMismatch { .. })
    ));
    assert!(cga::point_on(&s, &[0.0; 3], f64::NAN).is_err());
    let r2 = Rotor::identity(2);
    assert!(cga::rotor(&r2).is_ok());
    assert!(cga::rotor(&Rotor::identity(1)).is_err());
}
