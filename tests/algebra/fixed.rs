//! The fixed-size rotors and bivectors of N = 3 and 4 against the run-time types: every
//! operation to a few ulp on random and hard inputs (isoclinic, angle π, tiny, huge), and
//! the `f32` types against the `f64` ones.

use nalgebra::{DMatrix, Matrix3, Matrix4, Vector3, Vector4};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rotorflow::algebra::{Bivector, Bivector3, Bivector4, Rotor, Rotor3, Rotor4};

const EPS: f64 = f64::EPSILON;

/// max |a − b| in units of ε · max(1, max |b|).
fn ulps(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().fold(1.0f64, |m, c| m.max(c.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / (EPS * scale)
}

fn rotor_coefficients(r: &Rotor) -> Vec<f64> {
    let n = r.dim();
    (0u64..1 << n)
        .filter(|m| m.count_ones() % 2 == 0)
        .map(|m| r.coefficient(m))
        .collect()
}

/// [`ulps`] up to the sign of the rotor (R and −R are the same rotation, and a matrix
/// fixes only the rotation: at a scalar part of ~0 either sign may come back).
fn ulps_up_to_sign(a: &[f64], b: &[f64]) -> f64 {
    let neg: Vec<f64> = a.iter().map(|x| -x).collect();
    ulps(a, b).min(ulps(&neg, b))
}

fn matrix_entries(m: &DMatrix<f64>) -> Vec<f64> {
    m.iter().copied().collect()
}

/// Random bivector components at a random scale, plus the hard families.
fn samples(k: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut out = Vec::new();
    for scale in [1e-9, 1e-3, 0.3, 1.0, 1.5, 3.0] {
        for _ in 0..200 {
            out.push((0..k).map(|_| scale * rng.gen_range(-1.0..1.0)).collect());
        }
    }
    // Simple planes near the half-angle π/2 (rotation angle π) and tiny and huge ones.
    let half_pi = std::f64::consts::FRAC_PI_2;
    for x in [
        half_pi,
        half_pi - 1e-12,
        half_pi + 1e-12,
        1e-200,
        1e-30,
        1e8,
    ] {
        let mut b = vec![0.0; k];
        b[0] = x;
        out.push(b.clone());
        b[k - 1] = 0.5 * x;
        out.push(b);
    }
    if k == 6 {
        // Isoclinic (equal angles in e12 and e34, both signs) and nearly so.
        for (a, c) in [
            (0.7, 0.7),
            (0.7, -0.7),
            (1.2, 1.2 + 1e-12),
            (half_pi, half_pi),
        ] {
            out.push(vec![a, 0.0, 0.0, 0.0, 0.0, c]);
        }
    }
    out
}

#[test]
fn rotor3_equals_the_run_time_rotor() {
    let cases = samples(3, 31);
    let mut worst = [0.0f64; 7];
    let mut rng = ChaCha8Rng::seed_from_u64(32);
    for (k, c) in cases.iter().enumerate() {
        let b = Bivector::from_components(3, c).unwrap();
        let bf = Bivector3::from_bivector(&b).unwrap();
        assert_eq!(bf.to_bivector(), b);
        let (r, rf) = (b.exp(), bf.exp());
        worst[0] = worst[0].max(ulps(
            &rotor_coefficients(&rf.to_rotor()),
            &rotor_coefficients(&r),
        ));
        let other = &cases[(k * 7 + 3) % cases.len()];
        let o = Bivector::from_components(3, other).unwrap();
        let (s, sf) = (o.exp(), Bivector3::from_bivector(&o).unwrap().exp());
        worst[1] = worst[1].max(ulps(
            &rotor_coefficients(&(rf * sf).to_rotor()),
            &rotor_coefficients(&r.compose(&s)),
        ));
        let x: Vec<f64> = (0..3).map(|_| rng.gen_range(-2.0..2.0)).collect();
        let xv = rotorflow::algebra::Vector::from_components(&x).unwrap();
        let y = rf.rotate_vector(Vector3::from_column_slice(&x));
        worst[2] = worst[2].max(ulps(y.as_slice(), r.rotate_vector(&xv).as_slice()));
        let m = rf.to_matrix();
        worst[3] = worst[3].max(ulps(m.as_slice(), &matrix_entries(&r.to_matrix())));
        worst[4] = worst[4].max(ulps(&rf.log().to_array(), r.log().as_slice()));
        // Both recover the rotor from its matrix; the fixed-size one at least as closely.
        let back = Rotor3::from_matrix(&m).unwrap();
        let back_rt = Rotor::from_matrix(&r.to_matrix()).unwrap();
        let (fixed, general) = (
            ulps_up_to_sign(
                &rotor_coefficients(&back.to_rotor()),
                &rotor_coefficients(&r),
            ),
            ulps_up_to_sign(&rotor_coefficients(&back_rt), &rotor_coefficients(&r)),
        );
        worst[5] = worst[5].max(fixed - general.max(4.0) + 4.0);
        let t = 0.37;
        worst[6] = worst[6].max(ulps(
            &rotor_coefficients(&rf.slerp(sf, t).to_rotor()),
            &rotor_coefficients(&r.slerp(&s, t)),
        ));
        let comm = bf.commutator(Bivector3::from_bivector(&o).unwrap());
        assert!(ulps(&comm.to_array(), b.commutator(&o).as_slice()) <= 4.0);
        let rt = Rotor3::from_rotor(&r).unwrap();
        assert!(ulps(&rotor_coefficients(&rt.to_rotor()), &rotor_coefficients(&r)) == 0.0);
    }
    eprintln!("3D ulps (exp, compose, rotate, matrix, log, from_matrix, slerp): {worst:?}");
    for (name, w) in [
        "exp",
        "compose",
        "rotate",
        "to_matrix",
        "log",
        "from_matrix",
        "slerp",
    ]
    .iter()
    .zip(worst)
    {
        assert!(w <= 4.0, "3D {name}: {w} ulp");
    }
    assert_eq!(cases.len(), 1200 + 12);
}

#[test]
fn rotor4_equals_the_run_time_rotor() {
    let cases = samples(6, 41);
    let mut worst = [0.0f64; 7];
    let mut rng = ChaCha8Rng::seed_from_u64(42);
    for (k, c) in cases.iter().enumerate() {
        let b = Bivector::from_components(4, c).unwrap();
        let bf = Bivector4::from_bivector(&b).unwrap();
        assert_eq!(bf.to_bivector(), b);
        let (r, rf) = (b.exp(), bf.exp());
        worst[0] = worst[0].max(ulps(
            &rotor_coefficients(&rf.to_rotor()),
            &rotor_coefficients(&r),
        ));
        let other = &cases[(k * 7 + 3) % cases.len()];
        let o = Bivector::from_components(4, other).unwrap();
        let (s, sf) = (o.exp(), Bivector4::from_bivector(&o).unwrap().exp());
        worst[1] = worst[1].max(ulps(
            &rotor_coefficients(&(rf * sf).to_rotor()),
            &rotor_coefficients(&r.compose(&s)),
        ));
        let x: Vec<f64> = (0..4).map(|_| rng.gen_range(-2.0..2.0)).collect();
        let xv = rotorflow::algebra::Vector::from_components(&x).unwrap();
        let y = rf.rotate_vector(Vector4::from_column_slice(&x));
        worst[2] = worst[2].max(ulps(y.as_slice(), r.rotate_vector(&xv).as_slice()));
        let m = rf.to_matrix();
        worst[3] = worst[3].max(ulps(m.as_slice(), &matrix_entries(&r.to_matrix())));
        // The logarithm: exp(log R) = R always; log(exp B) = B inside the principal domain.
        let l = rf.log();
        worst[4] = worst[4].max(ulps(
            &rotor_coefficients(&l.exp().to_rotor()),
            &rotor_coefficients(&r),
        ));
        // Both recover the rotor from its matrix; the fixed-size one at least as closely.
        let back = Rotor4::from_matrix(&m).unwrap();
        let back_rt = Rotor::from_matrix(&r.to_matrix()).unwrap();
        let (fixed, general) = (
            ulps_up_to_sign(
                &rotor_coefficients(&back.to_rotor()),
                &rotor_coefficients(&r),
            ),
            ulps_up_to_sign(&rotor_coefficients(&back_rt), &rotor_coefficients(&r)),
        );
        worst[5] = worst[5].max(fixed - general.max(4.0) + 4.0);
        let t = 0.37;
        worst[6] = worst[6].max(ulps(
            &rotor_coefficients(&rf.slerp(sf, t).to_rotor()),
            &rotor_coefficients(&r.slerp(&s, t)),
        ));
        let comm = bf.commutator(Bivector4::from_bivector(&o).unwrap());
        assert!(ulps(&comm.to_array(), b.commutator(&o).as_slice()) <= 8.0);
        let rt = Rotor4::from_rotor(&r).unwrap();
        assert!(ulps(&rotor_coefficients(&rt.to_rotor()), &rotor_coefficients(&r)) <= 2.0);
    }
    eprintln!("4D ulps (exp, compose, rotate, matrix, exp(log), from_matrix, slerp): {worst:?}");
    for (name, w) in [
        "exp",
        "compose",
        "rotate",
        "to_matrix",
        "exp(log)",
        "from_matrix",
        "slerp",
    ]
    .iter()
    .zip(worst)
    {
        assert!(w <= 4.0, "4D {name}: {w} ulp");
    }
    assert_eq!(cases.len(), 1200 + 12 + 4);
}

#[test]
fn log4_inverts_exp_inside_the_principal_domain() {
    let mut rng = ChaCha8Rng::seed_from_u64(43);
    let mut checked = 0;
    for _ in 0..500 {
        let c: [f64; 6] = std::array::from_fn(|_| rng.gen_range(-0.5..0.5));
        let b = Bivector4::from_array(c);
        let back = b.exp().log();
        assert!((back - b).norm() <= 8.0 * EPS * b.norm().max(1.0), "{b:?}");
        let rt = b.to_bivector().exp().log();
        assert!(ulps(&back.to_array(), rt.as_slice()) <= 8.0);
        checked += 1;
    }
    assert_eq!(checked, 500);
}

#[test]
fn f32_types_agree_with_f64_to_single_precision() {
    let mut rng = ChaCha8Rng::seed_from_u64(44);
    let tol = 8.0 * f64::from(f32::EPSILON);
    let mut products = 0;
    for _ in 0..500 {
        let c: [f64; 6] = std::array::from_fn(|_| rng.gen_range(-2.0..2.0));
        let c32 = c.map(|x| x as f32);
        let c = c32.map(f64::from);
        let (r, r32) = (
            Bivector4::from_array(c).exp(),
            Bivector4::from_array(c32).exp(),
        );
        let (m, m32) = (r.to_matrix(), r32.to_matrix());
        assert!((m - m32.cast::<f64>()).amax() <= tol);
        let b3 = Bivector3::new(c[0], c[1], c[2]);
        let b3f = Bivector3::new(c32[0], c32[1], c32[2]);
        let (q, q32) = (b3.exp().to_matrix(), b3f.exp().to_matrix());
        assert!((q - q32.cast::<f64>()).amax() <= tol);
        let v = Vector4::new(0.3f32, -1.1, 0.7, 2.0);
        let err = (r.rotate_vector(v.cast()) - r32.rotate_vector(v).cast::<f64>()).amax();
        assert!(err <= 4.0 * tol);
        // The f32 product (SSE lanes on x86) against the f64 product of the same rotors:
        // within a few ulp of f32, and the identity leaves a rotor exactly as it is.
        let a32 = Bivector3::new(c32[3], c32[4], c32[5]).exp();
        let (p32, p) = (
            b3f.exp() * a32,
            b3f.exp().to_rotor3_f64() * a32.to_rotor3_f64(),
        );
        let worst = p32
            .to_quaternion()
            .iter()
            .zip(p.to_quaternion())
            .map(|(x, y)| (f64::from(*x) - y).abs())
            .fold(0.0, f64::max);
        assert!(worst <= 4.0 * f64::from(f32::EPSILON), "{worst:e}");
        assert_eq!(Rotor3::<f32>::identity() * a32, a32);
        assert_eq!(a32 * Rotor3::<f32>::identity(), a32);
        products += 1;
    }
    assert_eq!(products, 500);
}

/// The f64 rotor of an f32 one (every f32 is an f64 exactly).
trait ToF64 {
    fn to_rotor3_f64(self) -> Rotor3<f64>;
}

impl ToF64 for Rotor3<f32> {
    fn to_rotor3_f64(self) -> Rotor3<f64> {
        let [w, x, y, z] = self.to_quaternion().map(f64::from);
        Rotor3::from_quaternion(w, x, y, z)
    }
}

/// −R is the rotation R (the same matrix), and slerp takes the shorter arc whichever sign
/// the target has: `slerp(a, b, t)` and `slerp(a, −b, t)` are the same rotation, ending at b.
#[test]
fn negated_rotors_are_the_same_rotation_and_slerp_ignores_the_sign() {
    let mut rng = ChaCha8Rng::seed_from_u64(46);
    let mut cases = 0;
    for _ in 0..200 {
        let a = Bivector4::from_array(std::array::from_fn(|_| rng.gen_range(-3.0..3.0))).exp();
        let b = Bivector4::from_array(std::array::from_fn(|_| rng.gen_range(-3.0..3.0))).exp();
        assert_eq!((-a).to_matrix(), a.to_matrix());
        let a3 = Bivector3::new(rng.gen_range(-3.0..3.0), 0.2, -1.0).exp();
        let b3 = Bivector3::new(0.4, rng.gen_range(-3.0..3.0), 1.5).exp();
        assert_eq!((-a3).to_matrix(), a3.to_matrix());
        for t in [0.0, 0.3, 1.0] {
            let (p, q) = (a.slerp(b, t), a.slerp(-b, t));
            assert!((p.to_matrix() - q.to_matrix()).amax() < 1e-13);
            let (p3, q3) = (a3.slerp(b3, t), a3.slerp(-b3, t));
            assert!((p3.to_matrix() - q3.to_matrix()).amax() < 1e-13);
            cases += 1;
        }
        assert!((a.slerp(b, 1.0).to_matrix() - b.to_matrix()).amax() < 1e-13);
        assert!((a3.slerp(-b3, 1.0).to_matrix() - b3.to_matrix()).amax() < 1e-13);
    }
    assert_eq!(cases, 600);
}

#[test]
fn rotate_vector_is_the_matrix_and_matrices_compose() {
    let mut rng = ChaCha8Rng::seed_from_u64(45);
    for _ in 0..200 {
        let a = Bivector4::from_array(std::array::from_fn(|_| rng.gen_range(-3.0..3.0))).exp();
        let b = Bivector4::from_array(std::array::from_fn(|_| rng.gen_range(-3.0..3.0))).exp();
        let x = Vector4::new(1.0, -2.0, 0.5, 0.25);
        assert!((a.rotate_vector(x) - a.to_matrix() * x).amax() < 1e-14);
        assert!(((a * b).to_matrix() - a.to_matrix() * b.to_matrix()).amax() < 1e-14);
        assert!(a.to_matrix().determinant() > 0.0);
        let (p, q) = (a.unit_error(), (a * b).unit_error());
        assert!(p < 1e-15 && q < 1e-15);
        let a3 = Bivector3::new(rng.gen_range(-3.0..3.0), 0.2, -1.0).exp();
        let y = Vector3::new(1.0, -2.0, 0.5);
        assert!((a3.rotate_vector(y) - a3.to_matrix() * y).amax() < 1e-14);
    }
    // Bad matrices are refused.
    assert!(Rotor3::from_matrix(&Matrix3::from_diagonal_element(2.0)).is_err());
    assert!(
        Rotor4::from_matrix(&Matrix4::from_diagonal(&Vector4::new(1.0, 1.0, 1.0, -1.0))).is_err()
    );
    assert!(Rotor4::from_matrix(&Matrix4::from_element(f64::NAN)).is_err());
}

#[test]
fn batch_kernels_equal_one_at_a_time() {
    let mut rng = ChaCha8Rng::seed_from_u64(46);
    let count = 40_000; // above the parallel chunk, so the threads split it
    let r3 = Bivector3::new(0.4, -1.1, 0.3).exp();
    let r4 = Bivector4::new(0.4, -1.1, 0.3, 0.9, -0.2, 0.5).exp();
    let mut coords: Vec<Vec<f64>> = (0..4)
        .map(|_| (0..count).map(|_| rng.gen_range(-3.0..3.0)).collect())
        .collect();
    let original = coords.clone();
    let [x, y, z, w] = &mut coords[..] else {
        unreachable!()
    };
    r4.rotate_soa(x, y, z, w);
    let mut aos: Vec<Vector4<f64>> = (0..count)
        .map(|i| {
            Vector4::new(
                original[0][i],
                original[1][i],
                original[2][i],
                original[3][i],
            )
        })
        .collect();
    r4.rotate_vectors(&mut aos);
    for i in 0..count {
        let one = r4.rotate_vector(Vector4::new(
            original[0][i],
            original[1][i],
            original[2][i],
            original[3][i],
        ));
        let soa = Vector4::new(x[i], y[i], z[i], w[i]);
        assert!((one - soa).amax() <= 1e-14 && (one - aos[i]).amax() <= 1e-14);
    }
    let (mut a, mut b, mut c) = (
        original[0].clone(),
        original[1].clone(),
        original[2].clone(),
    );
    r3.rotate_soa(&mut a, &mut b, &mut c);
    let mut v3: Vec<Vector3<f64>> = (0..count)
        .map(|i| Vector3::new(original[0][i], original[1][i], original[2][i]))
        .collect();
    r3.rotate_vectors(&mut v3);
    for i in 0..count {
        let one = r3.rotate_vector(Vector3::new(original[0][i], original[1][i], original[2][i]));
        assert!((one - Vector3::new(a[i], b[i], c[i])).amax() <= 1e-14);
        assert!((one - v3[i]).amax() <= 1e-14);
    }
    #[cfg(feature = "parallel")]
    {
        let (mut pa, mut pb, mut pc) = (
            original[0].clone(),
            original[1].clone(),
            original[2].clone(),
        );
        r3.par_rotate_soa(&mut pa, &mut pb, &mut pc);
        assert_eq!((pa, pb, pc), (a, b, c));
        let mut p: Vec<Vec<f64>> = original.clone();
        let [px, py, pz, pw] = &mut p[..] else {
            unreachable!()
        };
        r4.par_rotate_soa(px, py, pz, pw);
        assert_eq!(&p, &coords);
    }
    let mut rotors: Vec<Rotor4> = (0..100)
        .map(|k| Bivector4::new(0.01 * k as f64, 0.3, -0.2, 0.1, 0.0, 0.7).exp())
        .collect();
    let before = rotors.clone();
    r4.compose_all(&mut rotors);
    for (after, b) in rotors.iter().zip(&before) {
        assert_eq!(*after, r4 * *b);
    }
    let mut rotors3: Vec<Rotor3> = before
        .iter()
        .map(|_| Bivector3::new(0.2, 0.1, -0.3).exp())
        .collect();
    let b3 = rotors3.clone();
    r3.compose_all(&mut rotors3);
    assert!(rotors3.iter().zip(&b3).all(|(a, b)| *a == r3 * *b));
}

#[test]
#[should_panic(expected = "coordinate slices of different lengths")]
fn batch_kernels_refuse_ragged_slices() {
    let r = Rotor3::<f64>::identity();
    r.rotate_soa(&mut [0.0; 3], &mut [0.0; 3], &mut [0.0; 2]);
}
