//! Criterion benches of the fixed-size 3D and 4D rotors (`Rotor3`, `Rotor4`) beside the
//! strongest fair baselines, each pair in one group of the same run:
//!
//! - 3D, f64 and f32: glam's `DQuat`/`Quat` (product, rotating a vector, the rotation matrix,
//!   `from_scaled_axis`/`to_scaled_axis` against `from_rotation_bivector`/
//!   `rotation_bivector`, which compute the same rotation: the axis is the dual of the
//!   plane, and `from_axis_angle` against glam's after normalising the axis), and the
//!   run-time `Rotor` at N = 3; the `Versor::apply` form of the rotation beside
//!   `rotate_vector`.
//! - 4D, f64: a hand-written quaternion-pair product and closed-form exponential (the same
//!   arithmetic written out below), nalgebra's `Matrix4` product and `Matrix4 * Vector4`, and
//!   the run-time `Rotor` at N = 4.
//!
//! Every variant keeps a full rotation (no variant skips the attitude). The setup asserts
//! that each pair computes the same rotation. Run `cargo bench --bench fixed`
//! (`BENCH_QUICK=1` for a shorter run).

use criterion::{Criterion, Throughput, black_box, criterion_group, criterion_main};
use glam::{DMat3, DQuat, DVec3, Mat3, Quat, Vec3};
use nalgebra::{Vector3, Vector4};
use rotorflow::algebra::{Bivector, Bivector3, Bivector4, Rotor3, Vector, Versor};

#[path = "common/configure.rs"]
mod configure;
use configure::configure;

/// The glam axis of a rotation bivector Θ: the rotation in e₁₂ is about e₃.
fn axis(t: Bivector3) -> DVec3 {
    DVec3::new(t.b23, -t.b13, t.b12)
}

fn bench_3d(c: &mut Criterion) {
    let (ta, tb) = (
        Bivector3::new(0.3, -0.7, 0.5),
        Bivector3::new(-0.2, 0.4, 1.1),
    );
    let (a, b) = (
        Rotor3::from_rotation_bivector(ta),
        Rotor3::from_rotation_bivector(tb),
    );
    let (qa, qb) = (
        DQuat::from_scaled_axis(axis(ta)),
        DQuat::from_scaled_axis(axis(tb)),
    );
    let v = Vector3::new(0.3, -1.2, 2.0);
    let dv = DVec3::new(0.3, -1.2, 2.0);
    // Same rotations, same products, same matrices.
    let close = |x: DVec3, y: Vector3<f64>| (x - DVec3::new(y.x, y.y, y.z)).abs().max_element();
    assert!(close(qa * dv, a.rotate_vector(v)) < 1e-14);
    assert!(close((qa * qb) * dv, (a * b).rotate_vector(v)) < 1e-14);
    let m = DMat3::from_quat(qa);
    for i in 0..3 {
        for j in 0..3 {
            assert!((m.col(j)[i] - a.to_matrix()[(i, j)]).abs() < 1e-14);
        }
    }
    assert!(close(qa.to_scaled_axis(), Vector3::new(ta.b23, -ta.b13, ta.b12)) < 1e-14);

    let (ra, rb) = (a.to_rotor(), b.to_rotor());
    let vv = Vector::from_components(&[0.3, -1.2, 2.0]).unwrap();

    let mut g = c.benchmark_group("fixed3_f64_product");
    g.bench_function("glam_dquat", |x| x.iter(|| black_box(qa) * black_box(qb)));
    g.bench_function("rotorflow_rotor3", |x| {
        x.iter(|| black_box(a) * black_box(b))
    });
    g.bench_function("rotorflow_rotor_n3", |x| {
        x.iter(|| black_box(&ra).compose(black_box(&rb)))
    });
    g.finish();
    let mut g = c.benchmark_group("fixed3_f64_rotate_vector");
    g.bench_function("glam_dquat", |x| x.iter(|| black_box(qa) * black_box(dv)));
    g.bench_function("rotorflow_rotor3", |x| {
        x.iter(|| black_box(a).rotate_vector(black_box(v)))
    });
    g.bench_function("rotorflow_rotor_n3", |x| {
        x.iter(|| black_box(&ra).rotate_vector(black_box(&vv)))
    });
    g.bench_function("rotorflow_rotor3_versor_apply", |x| {
        x.iter(|| Versor::apply(&black_box(a), &black_box(v)))
    });
    g.finish();
    // From an axis of any length and an angle: glam's from_axis_angle wants a unit axis,
    // so its fair form normalises first; rotorflow's also checks the input is finite. Its
    // result is taken as a program takes it (`?` or `unwrap`): handing the whole `Result`
    // to `black_box` would time the harness reading the error type's bytes back for its
    // drop check, not the constructor.
    let (axis_in, angle) = (Vector3::new(0.3, -1.2, 2.0), 0.7);
    let daxis = DVec3::new(0.3, -1.2, 2.0);
    let want = DQuat::from_axis_angle(daxis.normalize(), angle) * dv;
    let got = Rotor3::from_axis_angle(axis_in, angle).unwrap() * v;
    assert!(close(want, got) < 1e-14);
    let mut g = c.benchmark_group("fixed3_f64_from_axis_angle");
    g.bench_function("glam_dquat_normalize_then_from_axis_angle", |x| {
        x.iter(|| DQuat::from_axis_angle(black_box(daxis).normalize(), black_box(angle)))
    });
    g.bench_function("rotorflow_rotor3", |x| {
        x.iter(|| Rotor3::from_axis_angle(black_box(axis_in), black_box(angle)).unwrap())
    });
    g.finish();
    let mut g = c.benchmark_group("fixed3_f64_to_matrix");
    g.bench_function("glam_dmat3_from_quat", |x| {
        x.iter(|| DMat3::from_quat(black_box(qa)))
    });
    g.bench_function("rotorflow_rotor3", |x| x.iter(|| black_box(a).to_matrix()));
    g.finish();
    let mut g = c.benchmark_group("fixed3_f64_exp");
    g.bench_function("glam_from_scaled_axis", |x| {
        x.iter(|| DQuat::from_scaled_axis(black_box(axis(ta))))
    });
    g.bench_function("rotorflow_rotor3", |x| {
        x.iter(|| Rotor3::from_rotation_bivector(black_box(ta)))
    });
    g.finish();
    let mut g = c.benchmark_group("fixed3_f64_log");
    g.bench_function("glam_to_scaled_axis", |x| {
        x.iter(|| black_box(qa).to_scaled_axis())
    });
    g.bench_function("rotorflow_rotor3", |x| {
        x.iter(|| black_box(a).rotation_bivector())
    });
    g.finish();

    // f32 against glam's Quat (SIMD on x86-64).
    let (ta32, tb32) = (
        Bivector3::<f32>::new(0.3, -0.7, 0.5),
        Bivector3::<f32>::new(-0.2, 0.4, 1.1),
    );
    let (a32, b32) = (
        Rotor3::from_rotation_bivector(ta32),
        Rotor3::from_rotation_bivector(tb32),
    );
    let ax32 = |t: Bivector3<f32>| Vec3::new(t.b23, -t.b13, t.b12);
    let (qa32, qb32) = (
        Quat::from_scaled_axis(ax32(ta32)),
        Quat::from_scaled_axis(ax32(tb32)),
    );
    let v32 = Vector3::new(0.3f32, -1.2, 2.0);
    let dv32 = Vec3::new(0.3, -1.2, 2.0);
    let w = (a32 * b32).rotate_vector(v32);
    assert!(
        (((qa32 * qb32) * dv32) - Vec3::new(w.x, w.y, w.z))
            .abs()
            .max_element()
            < 1e-6
    );
    let mut g = c.benchmark_group("fixed3_f32_product");
    g.bench_function("glam_quat", |x| {
        x.iter(|| black_box(qa32) * black_box(qb32))
    });
    g.bench_function("rotorflow_rotor3", |x| {
        x.iter(|| black_box(a32) * black_box(b32))
    });
    g.finish();
    let mut g = c.benchmark_group("fixed3_f32_rotate_vector");
    g.bench_function("glam_quat", |x| {
        x.iter(|| black_box(qa32) * black_box(dv32))
    });
    g.bench_function("rotorflow_rotor3", |x| {
        x.iter(|| black_box(a32).rotate_vector(black_box(v32)))
    });
    g.finish();
    let mut g = c.benchmark_group("fixed3_f32_to_matrix");
    g.bench_function("glam_mat3_from_quat", |x| {
        x.iter(|| Mat3::from_quat(black_box(qa32)))
    });
    g.bench_function("rotorflow_rotor3", |x| {
        x.iter(|| black_box(a32).to_matrix())
    });
    g.finish();
    let mut g = c.benchmark_group("fixed3_f32_exp");
    g.bench_function("glam_from_scaled_axis", |x| {
        x.iter(|| Quat::from_scaled_axis(black_box(ax32(ta32))))
    });
    g.bench_function("rotorflow_rotor3", |x| {
        x.iter(|| Rotor3::from_rotation_bivector(black_box(ta32)))
    });
    g.finish();
    let mut g = c.benchmark_group("fixed3_f32_log");
    g.bench_function("glam_to_scaled_axis", |x| {
        x.iter(|| black_box(qa32).to_scaled_axis())
    });
    g.bench_function("rotorflow_rotor3", |x| {
        x.iter(|| black_box(a32).rotation_bivector())
    });
    g.finish();
}

/// A quaternion as (w, x, y, z).
type Quaternion = [f64; 4];

/// Hamilton's product, written out.
#[inline]
fn hamilton(a: Quaternion, b: Quaternion) -> Quaternion {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

/// The hand-written quaternion-pair product of Spin(4) ≅ SU(2) × SU(2).
#[inline]
fn pair_product(
    a: (Quaternion, Quaternion),
    b: (Quaternion, Quaternion),
) -> (Quaternion, Quaternion) {
    (hamilton(a.0, b.0), hamilton(a.1, b.1))
}

/// The hand-written closed-form exponential of a 4D bivector: the quaternion exponential of
/// its self-dual and anti-self-dual halves.
#[inline]
fn pair_exp(b: [f64; 6]) -> (Quaternion, Quaternion) {
    let [b12, b13, b14, b23, b24, b34] = b;
    let half = |v: [f64; 3]| {
        let t = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let (s, c) = t.sin_cos();
        let k = if t > 0.0 { s / t } else { 1.0 };
        [c, k * v[0], k * v[1], k * v[2]]
    };
    (
        half([b12 - b34, b13 + b24, b14 - b23]),
        half([b12 + b34, b13 - b24, -(b14 + b23)]),
    )
}

fn bench_4d(c: &mut Criterion) {
    // Non-simple bivectors (two planes with different angles).
    let (ba, bb) = (
        [0.3, -0.7, 0.5, 0.2, 0.9, -0.4],
        [-0.2, 0.4, 1.1, -0.6, 0.1, 0.3],
    );
    let (a, b) = (
        Bivector4::from_array(ba).exp(),
        Bivector4::from_array(bb).exp(),
    );
    let (pa, pb) = (pair_exp(ba), pair_exp(bb));
    assert_eq!(a.to_quaternion_pair(), pa);
    assert_eq!((a * b).to_quaternion_pair(), pair_product(pa, pb));
    let (ma, mb) = (a.to_matrix(), b.to_matrix());
    assert!(((a * b).to_matrix() - ma * mb).amax() < 1e-14);
    let v = Vector4::new(0.3, -1.2, 2.0, 0.7);
    assert!((a.rotate_vector(v) - ma * v).amax() < 1e-14);
    let (ra, rb) = (a.to_rotor(), b.to_rotor());
    let vv = Vector::from_components(&[0.3, -1.2, 2.0, 0.7]).unwrap();
    let bv = Bivector::from_components(4, &ba).unwrap();

    let mut g = c.benchmark_group("fixed4_f64_product");
    g.bench_function("hand_written_quaternion_pair", |x| {
        x.iter(|| pair_product(black_box(pa), black_box(pb)))
    });
    g.bench_function("rotorflow_rotor4", |x| {
        x.iter(|| black_box(a) * black_box(b))
    });
    g.bench_function("nalgebra_matrix4_product", |x| {
        x.iter(|| black_box(ma) * black_box(mb))
    });
    g.bench_function("rotorflow_rotor_n4", |x| {
        x.iter(|| black_box(&ra).compose(black_box(&rb)))
    });
    g.finish();
    let mut g = c.benchmark_group("fixed4_f64_rotate_vector");
    g.bench_function("nalgebra_matrix4_times_vector4", |x| {
        x.iter(|| black_box(ma) * black_box(v))
    });
    g.bench_function("rotorflow_rotor4", |x| {
        x.iter(|| black_box(a).rotate_vector(black_box(v)))
    });
    g.bench_function("rotorflow_rotor_n4", |x| {
        x.iter(|| black_box(&ra).rotate_vector(black_box(&vv)))
    });
    g.finish();
    let mut g = c.benchmark_group("fixed4_f64_exp");
    g.bench_function("hand_written_closed_form", |x| {
        x.iter(|| pair_exp(black_box(ba)))
    });
    g.bench_function("rotorflow_rotor4", |x| {
        x.iter(|| Bivector4::from_array(black_box(ba)).exp())
    });
    g.bench_function("rotorflow_bivector_n4", |x| x.iter(|| black_box(&bv).exp()));
    g.finish();
    let mut g = c.benchmark_group("fixed4_f64_to_matrix");
    g.bench_function("rotorflow_rotor4", |x| x.iter(|| black_box(a).to_matrix()));
    g.bench_function("rotorflow_rotor_n4", |x| {
        x.iter(|| black_box(&ra).to_matrix())
    });
    // The same conversion into a matrix the caller keeps (no heap allocation per call).
    g.bench_function("rotorflow_rotor_n4_matrix_to", |x| {
        let mut q = nalgebra::DMatrix::zeros(4, 4);
        x.iter(|| {
            black_box(&ra).matrix_to(&mut q).unwrap();
            black_box(&q);
        })
    });
    g.finish();
}

/// Many vectors turned by one rotor, per second: the structure-of-arrays kernels (through the
/// matrix) against glam's quaternion and matrix applied in a loop over `DVec3`/`Vec3`.
fn bench_batch(c: &mut Criterion) {
    const COUNT: usize = 4096;
    let theta = Bivector3::new(0.3, -0.7, 0.5);
    let r = Rotor3::from_rotation_bivector(theta);
    let r32 = Rotor3::from_rotation_bivector(Bivector3::<f32>::new(0.3, -0.7, 0.5));
    let q = DQuat::from_scaled_axis(axis(theta));
    let (q32, m, m32) = (
        q.as_quat(),
        DMat3::from_quat(q),
        Mat3::from_quat(q.as_quat()),
    );
    let coords = |k: usize| -> Vec<f64> {
        (0..COUNT)
            .map(|i| ((i * 7 + k) % 13) as f64 * 0.1 - 0.6)
            .collect()
    };
    let (x, y, z) = (coords(0), coords(1), coords(2));
    let (x32, y32, z32): (Vec<f32>, Vec<f32>, Vec<f32>) = (
        x.iter().map(|&v| v as f32).collect(),
        y.iter().map(|&v| v as f32).collect(),
        z.iter().map(|&v| v as f32).collect(),
    );
    let aos: Vec<Vector3<f64>> = (0..COUNT).map(|i| Vector3::new(x[i], y[i], z[i])).collect();
    let glam: Vec<DVec3> = (0..COUNT).map(|i| DVec3::new(x[i], y[i], z[i])).collect();
    let glam32: Vec<Vec3> = glam.iter().map(|v| v.as_vec3()).collect();
    // The SoA kernel and glam's loop turn the same vectors.
    let (mut a, mut b, mut cc) = (x.clone(), y.clone(), z.clone());
    r.rotate_soa(&mut a, &mut b, &mut cc);
    for i in 0..COUNT {
        assert!(
            (q * glam[i] - DVec3::new(a[i], b[i], cc[i]))
                .abs()
                .max_element()
                < 1e-14
        );
    }

    let mut g = c.benchmark_group("batch3_rotate_vectors");
    g.throughput(Throughput::Elements(COUNT as u64));
    g.bench_function("rotorflow_f64_soa", |bch| {
        let (mut a, mut b, mut cc) = (x.clone(), y.clone(), z.clone());
        bch.iter(|| black_box(r).rotate_soa(&mut a, &mut b, &mut cc))
    });
    g.bench_function("rotorflow_f64_aos", |bch| {
        let mut v = aos.clone();
        bch.iter(|| black_box(r).rotate_vectors(&mut v))
    });
    g.bench_function("glam_dquat_loop", |bch| {
        let mut v = glam.clone();
        bch.iter(|| {
            let q = black_box(q);
            v.iter_mut().for_each(|p| *p = q * *p)
        })
    });
    g.bench_function("glam_dmat3_loop", |bch| {
        let mut v = glam.clone();
        bch.iter(|| {
            let m = black_box(m);
            v.iter_mut().for_each(|p| *p = m * *p)
        })
    });
    g.bench_function("rotorflow_f32_soa", |bch| {
        let (mut a, mut b, mut cc) = (x32.clone(), y32.clone(), z32.clone());
        bch.iter(|| black_box(r32).rotate_soa(&mut a, &mut b, &mut cc))
    });
    g.bench_function("glam_quat_loop", |bch| {
        let mut v = glam32.clone();
        bch.iter(|| {
            let q = black_box(q32);
            v.iter_mut().for_each(|p| *p = q * *p)
        })
    });
    g.bench_function("glam_mat3_loop", |bch| {
        let mut v = glam32.clone();
        bch.iter(|| {
            let m = black_box(m32);
            v.iter_mut().for_each(|p| *p = m * *p)
        })
    });
    g.finish();
}

/// ω × L in 3D on (e₁₂, e₁₃, e₂₃) components, written out.
#[inline]
fn cross3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[2] * b[1] - a[1] * b[2],
        a[0] * b[2] - a[2] * b[0],
        a[1] * b[0] - a[0] * b[1],
    ]
}

/// ω × L in 4D through the self-dual halves: (α, β) of each, the cross product per half.
#[inline]
fn cross4(a: [f64; 6], b: [f64; 6]) -> [f64; 6] {
    let halves = |c: [f64; 6]| {
        let [b12, b13, b14, b23, b24, b34] = c;
        (
            [b12 - b34, b13 + b24, b14 - b23],
            [b12 + b34, b13 - b24, -(b14 + b23)],
        )
    };
    let x = |u: [f64; 3], v: [f64; 3]| {
        [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ]
    };
    let ((aa, ab), (ba, bb)) = (halves(a), halves(b));
    let (p, m) = (x(aa, ba), x(ab, bb));
    [
        0.5 * (p[0] + m[0]),
        0.5 * (p[1] + m[1]),
        0.5 * (p[2] - m[2]),
        -0.5 * (p[2] + m[2]),
        0.5 * (p[1] - m[1]),
        0.5 * (m[0] - p[0]),
    ]
}

/// A hand-written RKMK4 free step on plain arrays: momentum `l`, attitude `q` (a quaternion
/// in 3D, the quaternion pair in 4D, advanced by `advance` with the step's generator), the
/// same scheme as `FreeBody3::step_rk4`/`FreeBody4::step_rk4`.
#[inline]
fn hand_rkmk4<const K: usize>(
    l: &mut [f64; K],
    inv: &[f64; K],
    h: f64,
    cross: impl Fn([f64; K], [f64; K]) -> [f64; K],
) -> [f64; K] {
    let rate = |l: [f64; K]| {
        let w: [f64; K] = std::array::from_fn(|k| l[k] * inv[k]);
        (cross(w, l), w)
    };
    let axpy =
        |x: [f64; K], y: [f64; K], s: f64| -> [f64; K] { std::array::from_fn(|k| x[k] + s * y[k]) };
    let l0 = *l;
    let (d1, w1) = rate(l0);
    let (d2, w2) = rate(axpy(l0, d1, 0.5 * h));
    let (d3, w3) = rate(axpy(l0, d2, 0.5 * h));
    let (d4, w4) = rate(axpy(l0, d3, h));
    let c = cross(w1, w4);
    for k in 0..K {
        l[k] = l0[k] + h / 6.0 * (d1[k] + 2.0 * d2[k] + 2.0 * d3[k] + d4[k]);
    }
    std::array::from_fn(|k| {
        -h / 12.0 * (w1[k] + 2.0 * w2[k] + 2.0 * w3[k] + w4[k]) + h * h / 24.0 * c[k]
    })
}

/// The quaternion exponential of the pure quaternion v, written out.
#[inline]
fn quat_exp(v: [f64; 3]) -> Quaternion {
    let t = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let (s, c) = t.sin_cos();
    let k = if t > 0.0 { s / t } else { 1.0 };
    [c, k * v[0], k * v[1], k * v[2]]
}

fn bench_bodies(c: &mut Criterion) {
    use rotorflow::dynamics::torques::Free;
    use rotorflow::dynamics::{FreeBody3, FreeBody4, Integrator, RigidBody, Rkmk4, Splitting};
    use rotorflow::inertia::InertiaMap;
    let h = 0.01;
    let rigid = |n: usize| {
        let j: Vec<f64> = (0..n).map(|k| 0.5 + 0.25 * k as f64).collect();
        let k = n * (n - 1) / 2;
        let l: Vec<f64> = (0..k).map(|i| (0.7 * i as f64 + 0.3).sin()).collect();
        let a: Vec<f64> = (0..k).map(|i| 0.1 * i as f64 - 0.2).collect();
        RigidBody::from_body_momentum(
            InertiaMap::from_principal_second_moments(&j).unwrap(),
            Bivector::from_components(n, &a).unwrap().exp(),
            &Bivector::from_components(n, &l).unwrap(),
        )
        .unwrap()
    };
    // 3D.
    let r3 = rigid(3);
    let f3 = FreeBody3::from_rigid_body(&r3).unwrap();
    let inv3 = f3.moments().map(|m| 1.0 / m);
    let (mut hl3, hq3) = (f3.momentum().to_array(), f3.attitude().to_quaternion());
    let u = hand_rkmk4(&mut hl3, &inv3, h, cross3);
    // The generator's quaternion vector is (−u₂₃, u₁₃, −u₁₂).
    let hq3 = hamilton(hq3, quat_exp([-u[2], u[1], -u[0]]));
    let mut check = f3;
    check.step_rk4(h);
    assert_eq!(check.momentum().to_array(), hl3);
    let cq = check.attitude().to_quaternion();
    assert!((0..4).all(|i| (cq[i] - hq3[i]).abs() < 1e-15));
    let mut g = c.benchmark_group("fixed_body_step/N=3");
    g.bench_function("hand_written_rkmk4_quaternion", |b| {
        let (mut l, mut q) = (f3.momentum().to_array(), f3.attitude().to_quaternion());
        b.iter(|| {
            let u = hand_rkmk4(black_box(&mut l), &inv3, h, cross3);
            q = hamilton(q, quat_exp([-u[2], u[1], -u[0]]));
        })
    });
    g.bench_function("rotorflow_freebody3_rk4", |b| {
        let mut f = f3;
        b.iter(|| black_box(&mut f).step_rk4(h))
    });
    g.bench_function("rotorflow_freebody3_strang", |b| {
        let mut f = f3;
        b.iter(|| black_box(&mut f).step_strang(h))
    });
    g.bench_function("rotorflow_freebody3_strang_symmetric", |b| {
        let mut f = f3;
        b.iter(|| black_box(&mut f).step_strang_symmetric(h))
    });
    g.bench_function("rotorflow_rigidbody_rkmk4", |b| {
        let mut r = r3.clone();
        b.iter(|| Rkmk4.step(black_box(&mut r), 0.0, h, &Free).unwrap())
    });
    g.bench_function("rotorflow_rigidbody_strang", |b| {
        let (mut r, mut s) = (r3.clone(), Splitting::strang());
        b.iter(|| s.step(black_box(&mut r), 0.0, h, &Free).unwrap())
    });
    g.bench_function("rotorflow_rigidbody_strang_symmetric", |b| {
        let (mut r, mut s) = (r3.clone(), Splitting::strang().with_symmetric_part());
        b.iter(|| s.step(black_box(&mut r), 0.0, h, &Free).unwrap())
    });
    g.finish();
    // 4D.
    let r4 = rigid(4);
    let f4 = FreeBody4::from_rigid_body(&r4).unwrap();
    let inv4 = f4.moments().map(|m| 1.0 / m);
    let pair_step = |l: &mut [f64; 6], q: &mut (Quaternion, Quaternion)| {
        let u = hand_rkmk4(l, &inv4, h, cross4);
        *q = pair_product(*q, pair_exp(u));
    };
    let (mut hl4, mut hq4) = (f4.momentum().to_array(), f4.attitude().to_quaternion_pair());
    pair_step(&mut hl4, &mut hq4);
    let mut check = f4;
    check.step_rk4(h);
    let cl = check.momentum().to_array();
    assert!((0..6).all(|i| (cl[i] - hl4[i]).abs() < 1e-15));
    let (cp, cm) = check.attitude().to_quaternion_pair();
    assert!((0..4).all(|i| (cp[i] - hq4.0[i]).abs() < 1e-15 && (cm[i] - hq4.1[i]).abs() < 1e-15));
    let mut g = c.benchmark_group("fixed_body_step/N=4");
    g.bench_function("hand_written_rkmk4_quaternion_pair", |b| {
        let (mut l, mut q) = (f4.momentum().to_array(), f4.attitude().to_quaternion_pair());
        b.iter(|| pair_step(black_box(&mut l), &mut q))
    });
    g.bench_function("rotorflow_freebody4_rk4", |b| {
        let mut f = f4;
        b.iter(|| black_box(&mut f).step_rk4(h))
    });
    g.bench_function("rotorflow_freebody4_strang", |b| {
        let mut f = f4;
        b.iter(|| black_box(&mut f).step_strang(h))
    });
    g.bench_function("rotorflow_freebody4_strang_symmetric", |b| {
        let mut f = f4;
        b.iter(|| black_box(&mut f).step_strang_symmetric(h))
    });
    g.bench_function("rotorflow_rigidbody_rkmk4", |b| {
        let mut r = r4.clone();
        b.iter(|| Rkmk4.step(black_box(&mut r), 0.0, h, &Free).unwrap())
    });
    g.bench_function("rotorflow_rigidbody_strang", |b| {
        let (mut r, mut s) = (r4.clone(), Splitting::strang());
        b.iter(|| s.step(black_box(&mut r), 0.0, h, &Free).unwrap())
    });
    g.bench_function("rotorflow_rigidbody_strang_symmetric", |b| {
        let (mut r, mut s) = (r4.clone(), Splitting::strang().with_symmetric_part());
        b.iter(|| s.step(black_box(&mut r), 0.0, h, &Free).unwrap())
    });
    g.finish();
    // Many 4D bodies: one thread, and both cores with the `parallel` feature.
    const BODIES: usize = 20_000;
    let swarm: Vec<FreeBody4> = vec![f4; BODIES];
    let mut g = c.benchmark_group("fixed_body_swarm/N=4");
    g.throughput(Throughput::Elements(BODIES as u64));
    g.bench_function("rk4_one_thread", |b| {
        let mut s = swarm.clone();
        b.iter(|| FreeBody4::step_all_rk4(black_box(&mut s), h))
    });
    g.bench_function("strang_one_thread", |b| {
        let mut s = swarm.clone();
        b.iter(|| FreeBody4::step_all_strang(black_box(&mut s), h))
    });
    #[cfg(feature = "parallel")]
    {
        g.bench_function("rk4_parallel", |b| {
            let mut s = swarm.clone();
            b.iter(|| FreeBody4::par_step_all_rk4(black_box(&mut s), h))
        });
        g.bench_function("strang_parallel", |b| {
            let mut s = swarm.clone();
            b.iter(|| FreeBody4::par_step_all_strang(black_box(&mut s), h))
        });
    }
    g.finish();
}

criterion_group! {
    name = benches;
    config = configure();
    targets = bench_3d, bench_4d, bench_batch, bench_bodies
}
criterion_main!(benches);
