//! The glam-shaped surface of the fixed-size rotors: constructors from axes, angles and
//! planes, inverse, `Display`, operators and the glam conversions, in f32 and f64, each
//! against an independent reference (glam's own quaternions, the run-time types, the
//! multivector inverse, the rotation of basis vectors).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rotorflow::algebra::{
    AlgebraError, Bivector3, Bivector4, Multivector, Rotor, Rotor3, Rotor4, Vector3, Vector4,
};

fn random_axis(rng: &mut ChaCha8Rng) -> [f64; 3] {
    loop {
        let a: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-2.0..2.0));
        if a.iter().map(|c| c * c).sum::<f64>() > 1e-2 {
            return a;
        }
    }
}

fn random_rotor3(rng: &mut ChaCha8Rng) -> Rotor3 {
    Rotor3::from_rotation_bivector(Bivector3::from_array(std::array::from_fn(|_| {
        rng.gen_range(-3.0..3.0)
    })))
}

fn random_rotor4(rng: &mut ChaCha8Rng) -> Rotor4 {
    Rotor4::from_rotation_bivector(Bivector4::from_array(std::array::from_fn(|_| {
        rng.gen_range(-3.0..3.0)
    })))
}

/// The 3D sign convention is glam's: `from_axis_angle` (with any axis length), and
/// `from_rotation_x/y/z`, turn every vector as glam's quaternions do, in f64 and f32.
#[test]
fn axis_angle_and_axis_rotations_turn_vectors_as_glam_does() {
    let mut rng = ChaCha8Rng::seed_from_u64(31);
    let mut cases = 0;
    for _ in 0..500 {
        let a = random_axis(&mut rng);
        let angle = rng.gen_range(-7.0..7.0);
        let v: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-1.0..1.0));
        let gv = glam::DVec3::from_array(v);
        let ga = glam::DVec3::from_array(a).normalize();
        let want = glam::DQuat::from_axis_angle(ga, angle) * gv;
        let r = Rotor3::from_axis_angle(Vector3::from(a), angle).unwrap();
        let got = r * Vector3::from(v);
        assert!(
            (got - Vector3::from(want.to_array())).amax() < 1e-14,
            "{a:?} {angle}"
        );
        // The named axes, each against glam's.
        for (k, (ours, theirs)) in [
            (
                Rotor3::from_rotation_x(angle),
                glam::DQuat::from_rotation_x(angle),
            ),
            (
                Rotor3::from_rotation_y(angle),
                glam::DQuat::from_rotation_y(angle),
            ),
            (
                Rotor3::from_rotation_z(angle),
                glam::DQuat::from_rotation_z(angle),
            ),
        ]
        .into_iter()
        .enumerate()
        {
            let want = Vector3::from((theirs * gv).to_array());
            assert!((ours * Vector3::from(v) - want).amax() < 1e-14, "axis {k}");
        }
        // f32 against glam's Quat.
        let a32 = a.map(|c| c as f32);
        let v32 = v.map(|c| c as f32);
        let want32 =
            glam::Quat::from_axis_angle(glam::Vec3::from_array(a32).normalize(), angle as f32)
                * glam::Vec3::from_array(v32);
        let r32 = Rotor3::<f32>::from_axis_angle(Vector3::from(a32), angle as f32).unwrap();
        let got32 = r32 * Vector3::from(v32);
        assert!((got32 - Vector3::from(want32.to_array())).amax() < 2e-6);
        let z32 = Rotor3::<f32>::from_rotation_z(angle as f32) * Vector3::from(v32);
        let zg = glam::Quat::from_rotation_z(angle as f32) * glam::Vec3::from_array(v32);
        assert!((z32 - Vector3::from(zg.to_array())).amax() < 2e-6);
        cases += 1;
    }
    assert_eq!(cases, 500);
}

/// A quarter turn about e₃ takes e₁ to e₂ (the fixed fact behind the sign convention).
#[test]
fn quarter_turn_about_e3_takes_e1_to_e2() {
    let q = std::f64::consts::FRAC_PI_2;
    let r = Rotor3::from_axis_angle(Vector3::z(), q).unwrap();
    assert!((r * Vector3::x() - Vector3::y()).amax() < 1e-15);
    assert!((Rotor3::from_rotation_x(q) * Vector3::y() - Vector3::z()).amax() < 1e-15);
    assert!((Rotor3::from_rotation_y(q) * Vector3::z() - Vector3::x()).amax() < 1e-15);
}

/// `from_plane_angle(i, j, θ)` is the run-time `Rotor::from_plane_angle`, turns eᵢ toward
/// eⱼ, and is the named constructor of its plane, for every ordered pair in 3D and 4D.
#[test]
fn plane_rotations_match_the_run_time_rotor_and_turn_i_toward_j() {
    let mut rng = ChaCha8Rng::seed_from_u64(32);
    let half_pi = std::f64::consts::FRAC_PI_2;
    let mut pairs = 0;
    for i in 0..4 {
        for j in 0..4 {
            if i == j {
                continue;
            }
            let angle = rng.gen_range(-3.0..3.0);
            let want = Rotor::from_plane_angle(4, i, j, angle).unwrap().to_matrix();
            let r4 = Rotor4::from_plane_angle(i, j, angle).unwrap();
            let got = r4.to_matrix();
            assert!((got - want).amax() < 1e-15, "4D ({i}, {j})");
            let turned = Rotor4::from_plane_angle(i, j, half_pi).unwrap() * Vector4::ith(i, 1.0);
            assert!((turned - Vector4::ith(j, 1.0)).amax() < 1e-15);
            if i < 3 && j < 3 {
                let want = Rotor::from_plane_angle(3, i, j, angle).unwrap().to_matrix();
                let r3 = Rotor3::from_plane_angle(i, j, angle).unwrap();
                assert!((r3.to_matrix() - want).amax() < 1e-15, "3D ({i}, {j})");
                let turned =
                    Rotor3::from_plane_angle(i, j, half_pi).unwrap() * Vector3::ith(i, 1.0);
                assert!((turned - Vector3::ith(j, 1.0)).amax() < 1e-15);
                pairs += 1;
            }
            pairs += 1;
        }
    }
    assert_eq!(pairs, 12 + 6);
    // The named forms are the planes with i < j, exactly.
    type PlaneRotation = fn(f64) -> Rotor4;
    let named: [(PlaneRotation, usize, usize); 6] = [
        (Rotor4::from_rotation_xy, 0, 1),
        (Rotor4::from_rotation_xz, 0, 2),
        (Rotor4::from_rotation_xw, 0, 3),
        (Rotor4::from_rotation_yz, 1, 2),
        (Rotor4::from_rotation_yw, 1, 3),
        (Rotor4::from_rotation_zw, 2, 3),
    ];
    for (f, i, j) in named {
        assert_eq!(f(0.7), Rotor4::from_plane_angle(i, j, 0.7).unwrap());
    }
    assert_eq!(
        Rotor3::from_rotation_x(0.7),
        Rotor3::from_plane_angle(1, 2, 0.7).unwrap()
    );
    let y = Rotor3::from_rotation_y(0.7).to_matrix();
    assert!((y - Rotor3::from_plane_angle(2, 0, 0.7).unwrap().to_matrix()).amax() < 1e-16);
    assert_eq!(
        Rotor3::from_rotation_z(0.7),
        Rotor3::from_plane_angle(0, 1, 0.7).unwrap()
    );
}

#[test]
fn constructors_refuse_bad_input() {
    assert!(matches!(
        Rotor3::from_plane_angle(1, 1, 0.3),
        Err(AlgebraError::RepeatedIndex { index: 1 })
    ));
    assert!(matches!(
        Rotor3::from_plane_angle(0, 3, 0.3),
        Err(AlgebraError::IndexOutOfRange { index: 3, dim: 3 })
    ));
    assert!(matches!(
        Rotor4::from_plane_angle(4, 0, 0.3),
        Err(AlgebraError::IndexOutOfRange { index: 4, dim: 4 })
    ));
    assert!(matches!(
        Rotor3::from_axis_angle(Vector3::zeros(), 0.3),
        Err(AlgebraError::ZeroLength { .. })
    ));
    assert!(matches!(
        Rotor3::from_axis_angle(Vector3::new(f64::NAN, 0.0, 1.0), 0.3),
        Err(AlgebraError::NonFinite { .. })
    ));
    assert!(matches!(
        Rotor3::<f32>::from_axis_angle(Vector3::x(), f32::INFINITY),
        Err(AlgebraError::NonFinite { .. })
    ));
}

/// `from_axis_angle` is the closed form (cos θ/2, sin θ/2 · a/|a|) with |a| the overflow-safe
/// norm and the sine divided by it before the product, to the bit, for axes of every scale
/// (tiny and huge ones take the scaled norm), and it names the first bad input: the axis
/// before the angle.
#[test]
fn from_axis_angle_is_the_closed_form_to_the_bit_at_every_scale() {
    let mut rng = ChaCha8Rng::seed_from_u64(41);
    let mut checked = 0;
    for scale in [1e-300, 1e-160, 1e-3, 1.0, 1e3, 1e160, 1e300] {
        for _ in 0..50 {
            let a: [f64; 3] = std::array::from_fn(|_| scale * rng.gen_range(-1.0..1.0));
            let angle: f64 = rng.gen_range(-10.0..10.0);
            // |a| scaled by its largest component, so that no square overflows or underflows.
            let m = a.iter().fold(0.0f64, |m, c| m.max(c.abs()));
            let plain = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
            let len = if plain > f64::MIN_POSITIVE.sqrt() && plain < f64::MAX.sqrt() {
                plain.sqrt()
            } else {
                m * a.iter().map(|c| (c / m) * (c / m)).sum::<f64>().sqrt()
            };
            let (s, c) = (angle * 0.5).sin_cos();
            let k = s / len;
            let want = [c, k * a[0], k * a[1], k * a[2]];
            let got = Rotor3::from_axis_angle(Vector3::from(a), angle)
                .unwrap()
                .to_quaternion();
            assert_eq!(
                got.map(f64::to_bits),
                want.map(f64::to_bits),
                "{a:?}, {angle}"
            );
            checked += 1;
        }
    }
    assert_eq!(checked, 350);
    let nan_axis = Vector3::new(f64::NAN, 1.0, 0.0);
    assert!(matches!(
        Rotor3::from_axis_angle(nan_axis, f64::NAN),
        Err(AlgebraError::NonFinite {
            what: "rotation axis"
        })
    ));
    assert!(matches!(
        Rotor3::from_axis_angle(Vector3::x(), f64::NAN),
        Err(AlgebraError::NonFinite {
            what: "rotation angle"
        })
    ));
    assert!(matches!(
        Rotor3::from_axis_angle(Vector3::new(f64::INFINITY, 0.0, 0.0), 0.3),
        Err(AlgebraError::NonFinite {
            what: "rotation axis"
        })
    ));
    assert!(matches!(
        Rotor3::from_axis_angle(Vector3::zeros(), f64::INFINITY),
        Err(AlgebraError::NonFinite {
            what: "rotation angle"
        })
    ));
}

/// The inverse of any non-zero even element (unit or not) against the multivector inverse.
#[test]
fn inverse_is_the_multivector_inverse() {
    let mut rng = ChaCha8Rng::seed_from_u64(33);
    for _ in 0..200 {
        let scale = rng.gen_range(0.2..5.0);
        let r3 = Rotor3::from_quaternion(
            scale * rng.gen_range(-1.0..1.0),
            scale * rng.gen_range(-1.0..1.0),
            scale * rng.gen_range(-1.0..1.0),
            scale * rng.gen_range(-1.0..1.0),
        );
        let want = Multivector::from(&r3.to_rotor()).inverse().unwrap();
        let got = Multivector::from(&r3.inverse().to_rotor());
        assert!((&got - &want).max_abs() < 1e-13 * want.max_abs());
        let r4 = random_rotor4(&mut rng);
        let (p, m) = r4.to_quaternion_pair();
        let (kp, km) = (rng.gen_range(0.2..5.0), rng.gen_range(0.2..5.0));
        let s4 = Rotor4::from_quaternion_pair(p.map(|c| kp * c), m.map(|c| km * c));
        let want = Multivector::from(&s4.to_rotor()).inverse().unwrap();
        let got = Multivector::from(&s4.inverse().to_rotor());
        assert!((&got - &want).max_abs() < 1e-13 * want.max_abs());
        // Unit rotors: the inverse composes to the identity, in f32 too.
        let u = random_rotor3(&mut rng);
        let one = (u * u.inverse()).to_quaternion();
        assert!((one[0] - 1.0).abs() < 1e-15 && one[1..].iter().all(|c| c.abs() < 1e-15));
        let u32 = Rotor3::<f32>::from_rotation_x(rng.gen_range(-3.0..3.0));
        assert!((u32 * u32.inverse()).unit_error() < 1e-6);
        assert!((u32 * u32.inverse()).scalar() > 1.0 - 1e-6);
    }
}

#[test]
fn default_is_the_identity() {
    assert_eq!(Rotor3::<f64>::default(), Rotor3::identity());
    assert_eq!(Rotor3::<f32>::default(), Rotor3::identity());
    assert_eq!(Rotor4::<f64>::default(), Rotor4::identity());
    assert_eq!(Rotor4::<f32>::default(), Rotor4::identity());
    assert_ne!(Rotor3::from_rotation_z(0.1), Rotor3::identity());
}

/// `Display` writes what the run-time types write, and the f32 types their own shortest
/// digits.
#[test]
fn display_matches_the_run_time_types() {
    let r = Rotor3::from_parts(0.5, Bivector3::new(0.5, -0.5, 0.5));
    assert_eq!(r.to_string(), "0.5 + 0.5·e12 - 0.5·e13 + 0.5·e23");
    assert_eq!(Rotor3::<f64>::identity().to_string(), "1");
    let r32 = Rotor3::<f32>::from_parts(0.1, Bivector3::new(0.0, -0.2, 0.0));
    assert_eq!(r32.to_string(), "0.1 - 0.2·e13");
    assert_eq!(
        format!("{:.2}", Bivector3::new(1.0, 0.0, -1.0 / 3.0)),
        "1.00·e12 - 0.33·e23"
    );
    let r4 = Rotor4::from_parts(0.5, Bivector4::new(0.0, 0.0, 0.25, 0.0, 0.0, -0.5), 0.25);
    assert_eq!(r4.to_string(), "0.5 + 0.25·e14 - 0.5·e34 + 0.25·e1234");
    assert_eq!(
        Bivector4::<f32>::new(0.0, 0.0, 0.0, 1.5, 0.0, 0.0).to_string(),
        "1.5·e23"
    );
    let mut rng = ChaCha8Rng::seed_from_u64(34);
    for _ in 0..50 {
        let r3 = random_rotor3(&mut rng);
        assert_eq!(r3.to_string(), r3.to_rotor().to_string());
        assert_eq!(
            r3.bivector_part().to_string(),
            r3.bivector_part().to_bivector().to_string()
        );
        let r4 = random_rotor4(&mut rng);
        assert_eq!(r4.to_string(), r4.to_rotor().to_string());
        assert_eq!(
            r4.bivector_part().to_string(),
            r4.bivector_part().to_bivector().to_string()
        );
    }
}

/// The nalgebra types re-exported by rotorflow are the ones its rotors take.
#[test]
fn reexported_nalgebra_types_are_the_rotors_types() {
    let v: rotorflow::nalgebra::Vector4<f64> = Vector4::new(1.0, 0.0, 0.0, 0.0);
    let m: rotorflow::algebra::Matrix4<f64> = Rotor4::from_rotation_xy(0.3).to_matrix();
    assert!((m * v - Rotor4::from_rotation_xy(0.3) * v).amax() < 1e-16);
    let m3: rotorflow::algebra::Matrix3<f32> = Rotor3::<f32>::from_rotation_z(0.3).to_matrix();
    assert!((m3 * Vector3::x() - Rotor3::<f32>::from_rotation_z(0.3) * Vector3::x()).amax() < 1e-7);
}

#[cfg(feature = "glam")]
mod glam_conversions {
    use super::*;
    use glam::{DMat3, DMat4, DQuat, DVec3, DVec4, Mat3, Quat, Vec4};

    #[test]
    fn quaternions_convert_both_ways_and_turn_alike() {
        let mut rng = ChaCha8Rng::seed_from_u64(35);
        for _ in 0..200 {
            let r = random_rotor3(&mut rng);
            let q = DQuat::from(r);
            assert_eq!(Rotor3::from(q), r);
            let [w, x, y, z] = r.to_quaternion();
            assert_eq!(q.to_array(), [x, y, z, w]);
            let v = DVec3::new(
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
            );
            assert!((r * v - q * v).abs().max_element() < 1e-15);
            let m = DMat3::from(r);
            assert!((m * v - q * v).abs().max_element() < 1e-15);
            assert!(DMat3::from_quat(q).abs_diff_eq(m, 1e-15));
            let back = Rotor3::try_from(m).unwrap();
            let sign = if back.scalar() * r.scalar() < 0.0 {
                -1.0
            } else {
                1.0
            };
            let (a, b) = (back.to_quaternion(), r.to_quaternion());
            assert!((0..4).all(|k| (sign * a[k] - b[k]).abs() < 1e-14));
            // f32.
            let r32 = Rotor3::<f32>::from_axis_angle(Vector3::new(0.3, -1.0, 0.5), 1.2).unwrap();
            let q32 = Quat::from(r32);
            assert_eq!(Rotor3::from(q32), r32);
            let v32 = v.as_vec3();
            assert!((r32 * v32 - q32 * v32).abs().max_element() < 1e-6);
            assert!(Mat3::from_quat(q32).abs_diff_eq(Mat3::from(r32), 1e-6));
        }
        assert!(matches!(
            Rotor3::try_from(DMat3::from_diagonal(DVec3::new(1.0, 1.0, -1.0))),
            Err(AlgebraError::NotARotation { .. })
        ));
    }

    /// The isoclinic pair turns glam's quaternion of a 4-vector as the rotor turns the
    /// vector, and converts back to the same rotor.
    #[test]
    fn rotor4_is_a_pair_of_glam_quaternions() {
        let mut rng = ChaCha8Rng::seed_from_u64(36);
        for _ in 0..200 {
            let r = random_rotor4(&mut rng);
            let (l, rr) = <(DQuat, DQuat)>::from(r);
            assert_eq!(Rotor4::from((l, rr)), r);
            let v = DVec4::new(
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
            );
            let want = r * v;
            let got = DVec4::from(l * DQuat::from_vec4(v) * rr);
            assert!((got - want).abs().max_element() < 1e-14, "{got} {want}");
            let nal = r * Vector4::new(v.x, v.y, v.z, v.w);
            assert!(
                (want - DVec4::new(nal.x, nal.y, nal.z, nal.w))
                    .abs()
                    .max_element()
                    < 1e-16
            );
            let m = DMat4::from(r);
            assert!((m * v - want).abs().max_element() < 1e-14);
            let back = Rotor4::try_from(m).unwrap();
            assert!((back.to_matrix() - r.to_matrix()).amax() < 1e-14);
            // f32.
            let r32 = Rotor4::<f32>::from_rotation_xw(0.4) * Rotor4::<f32>::from_rotation_yz(-1.1);
            let (l32, q32) = <(Quat, Quat)>::from(r32);
            let v32 = v.as_vec4();
            let got32 = Vec4::from(l32 * Quat::from_vec4(v32) * q32);
            assert!((got32 - r32 * v32).abs().max_element() < 1e-6);
        }
    }
}
