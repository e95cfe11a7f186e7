//! The fixed-size free bodies against the run-time integrators: the same step to a few ulp,
//! the splitting's invariants over long runs, and the batch and parallel forms.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rotorflow::algebra::{Bivector, Bivector3, Bivector4, Rotor, Rotor4};
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::{FreeBody3, FreeBody4, Integrator, RigidBody, Rkmk4, Splitting};
use rotorflow::inertia::InertiaMap;

/// max |a − b| / (ε max(1, max |b|)).
fn ulps(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(1.0f64, |m, c| m.max(c.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / (f64::EPSILON * scale)
}

/// A random body of N = 3 or 4 (second moments 0.5…3), turned and spinning.
fn body(n: usize, rng: &mut ChaCha8Rng) -> RigidBody {
    let moments: Vec<f64> = (0..n).map(|_| rng.gen_range(0.5..3.0)).collect();
    let inertia = InertiaMap::from_principal_second_moments(&moments).unwrap();
    let k = n * (n - 1) / 2;
    let c: Vec<f64> = (0..k).map(|_| rng.gen_range(-2.0..2.0)).collect();
    let omega = Bivector::from_components(n, &c).unwrap();
    let a: Vec<f64> = (0..k).map(|_| rng.gen_range(-1.0..1.0)).collect();
    let attitude = Bivector::from_components(n, &a).unwrap().exp();
    RigidBody::from_body_velocity(inertia, attitude, &omega).unwrap()
}

fn rotor_coefficients(r: &Rotor) -> Vec<f64> {
    (0u64..1 << r.dim())
        .filter(|m| m.count_ones() % 2 == 0)
        .map(|m| r.coefficient(m))
        .collect()
}

/// (momentum, attitude) of a run-time body.
fn state(b: &RigidBody) -> (Vec<f64>, Vec<f64>) {
    (
        b.momentum().as_slice().to_vec(),
        rotor_coefficients(&b.principal_frame_attitude().to_rotor().unwrap()),
    )
}

#[test]
fn one_step_equals_the_run_time_integrators() {
    let mut rng = ChaCha8Rng::seed_from_u64(51);
    let mut worst = [0.0f64; 4];
    let mut checked = 0;
    for n in [3, 4] {
        for _ in 0..200 {
            let start = body(n, &mut rng);
            let h = rng.gen_range(0.001..0.1);
            for (slot, strang) in [(0, false), (2, true)] {
                let mut rt = start.clone();
                if strang {
                    Splitting::strang().step(&mut rt, 0.0, h, &Free).unwrap();
                } else {
                    Rkmk4.step(&mut rt, 0.0, h, &Free).unwrap();
                }
                let (l, r) = state(&rt);
                let (fl, fr) = if n == 3 {
                    let mut f = FreeBody3::from_rigid_body(&start).unwrap();
                    if strang {
                        f.step_strang(h)
                    } else {
                        f.step_rk4(h)
                    }
                    (
                        f.momentum().to_array().to_vec(),
                        rotor_coefficients(&f.attitude().to_rotor()),
                    )
                } else {
                    let mut f = FreeBody4::from_rigid_body(&start).unwrap();
                    if strang {
                        f.step_strang(h)
                    } else {
                        f.step_rk4(h)
                    }
                    (
                        f.momentum().to_array().to_vec(),
                        rotor_coefficients(&f.attitude().to_rotor()),
                    )
                };
                worst[slot] = worst[slot].max(ulps(&fl, &l));
                worst[slot + 1] = worst[slot + 1].max(ulps(&fr, &r));
                checked += 1;
            }
        }
    }
    eprintln!("ulps (rk4 L, rk4 R, strang L, strang R): {worst:?}");
    // The momentum updates are the same arithmetic; the attitude's product differs in
    // rounding (quaternion against blade products).
    assert_eq!(worst[0], 0.0, "rk4 momentum");
    assert_eq!(worst[2], 0.0, "strang momentum");
    assert!(worst[1] <= 4.0 && worst[3] <= 4.0, "{worst:?}");
    assert_eq!(checked, 800);
}

#[test]
fn strang_keeps_the_invariants_over_long_runs() {
    let mut rng = ChaCha8Rng::seed_from_u64(52);
    let start = body(4, &mut rng);
    let mut f = FreeBody4::from_rigid_body(&start).unwrap();
    let norm = |b: Bivector4| b.norm();
    let (l0, e0) = (norm(f.momentum()), f.energy());
    // The space-frame momentum R L R̃ through the matrices: Q [L] Qᵀ.
    let space = |f: &FreeBody4| {
        let q = f.attitude().to_matrix();
        let l = f.momentum().to_bivector().to_skew_matrix();
        let l = nalgebra::Matrix4::from_column_slice(l.as_slice());
        q * l * q.transpose()
    };
    let s0 = space(&f);
    let mut worst_e = 0.0f64;
    for _ in 0..100_000 {
        f.step_strang(0.01);
        worst_e = worst_e.max((f.energy() - e0).abs() / e0);
    }
    assert!((norm(f.momentum()) - l0).abs() <= 1e-13 * l0);
    assert!((space(&f) - s0).amax() <= 1e-12 * l0);
    assert!(f.attitude().unit_error() <= 1e-14);
    // Bounded, not drifting: the splitting's energy error at h = 0.01 stays small.
    assert!(worst_e < 1e-3, "{worst_e:e}");
}

#[test]
fn batches_and_threads_step_like_one_body() {
    let mut rng = ChaCha8Rng::seed_from_u64(53);
    let bodies: Vec<FreeBody4> = (0..1000)
        .map(|_| FreeBody4::from_rigid_body(&body(4, &mut rng)).unwrap())
        .collect();
    let mut batch = bodies.clone();
    FreeBody4::step_all_rk4(&mut batch, 0.01);
    FreeBody4::step_all_strang(&mut batch, 0.01);
    let mut one = bodies.clone();
    for b in &mut one {
        b.step_rk4(0.01);
        b.step_strang(0.01);
    }
    assert_eq!(batch, one);
    #[cfg(feature = "parallel")]
    {
        let mut par = bodies.clone();
        FreeBody4::par_step_all_rk4(&mut par, 0.01);
        FreeBody4::par_step_all_strang(&mut par, 0.01);
        assert_eq!(par, one);
    }
    let b3: Vec<FreeBody3> = (0..10)
        .map(|_| FreeBody3::from_rigid_body(&body(3, &mut rng)).unwrap())
        .collect();
    let mut s3 = b3.clone();
    FreeBody3::step_all_rk4(&mut s3, 0.01);
    for (a, b) in s3.iter().zip(&b3) {
        let mut b = *b;
        b.step_rk4(0.01);
        assert_eq!(*a, b);
    }
}

#[test]
fn bad_bodies_are_refused() {
    let r = Rotor4::identity();
    let l = Bivector4::zero();
    assert!(FreeBody4::new([1.0, 2.0, 0.0, 1.0, 1.0, 1.0], r, l).is_err());
    assert!(
        FreeBody4::new(
            [1.0; 6],
            r,
            Bivector4::new(f64::NAN, 0.0, 0.0, 0.0, 0.0, 0.0)
        )
        .is_err()
    );
    assert!(FreeBody3::new([1.0, -1.0, 1.0], Default::default(), Bivector3::zero()).is_err());
    let mut rng = ChaCha8Rng::seed_from_u64(54);
    assert!(FreeBody3::from_rigid_body(&body(4, &mut rng)).is_err());
    // Writing back gives the run-time body the fixed-size state.
    let mut b = body(4, &mut rng);
    let mut f = FreeBody4::from_rigid_body(&b).unwrap();
    f.step_rk4(0.05);
    f.write_to(&mut b).unwrap();
    assert_eq!(
        FreeBody4::from_rigid_body(&b).unwrap().momentum(),
        f.momentum()
    );
}
