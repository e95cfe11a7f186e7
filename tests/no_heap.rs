//! Vectors and bivectors up to N = 8, rotors in 3D and 4D, and the integrator steps of the
//! splitting, RK4 (plain and Lie–Poisson), midpoint, Dopri5 and Moser–Veselov methods up to
//! N = 8, and the fixed-size bodies' steps and adaptive runs, never touch the heap: a counting
//! global allocator asserts it for construction, the hot kernels and the steps.

use rotorflow::prelude::*;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    // Per thread, so that tests running in parallel do not count each other.
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

// SAFETY: forwards to the system allocator and only counts calls.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.with(|c| c.set(c.get() + 1));
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[path = "no_heap/detect.rs"]
mod detect;

/// Returns how many allocations `f` made.
fn allocations_in(f: impl FnOnce()) -> usize {
    let before = ALLOCATIONS.with(Cell::get);
    f();
    ALLOCATIONS.with(Cell::get) - before
}

#[test]
fn graded_kernels_do_not_allocate_for_small_n() {
    // Inputs are built outside the measured closures.
    for n in 2..=8 {
        let comps: Vec<f64> = (0..n * (n - 1) / 2).map(|k| (k as f64).sin()).collect();
        let xs: Vec<f64> = (0..n).map(|k| (k as f64).cos()).collect();
        let count = allocations_in(|| {
            let a = Bivector::from_components(n, &comps).unwrap();
            let b = &a * 0.5 + &a;
            let c = a.commutator(&b);
            let x = Vector::from_components(&xs).unwrap();
            let v = x.left_contract(&c);
            let w = x.wedge(&v);
            let _ = std::hint::black_box((c.norm(), w.inner(&a), a.pfaffian()));
        });
        assert_eq!(count, 0, "N = {n}: {count} heap allocations");
    }
}

#[test]
fn rotor_kernels_do_not_allocate_in_3d_and_4d() {
    for n in [3, 4] {
        let comps: Vec<f64> = (0..n * (n - 1) / 2).map(|k| 0.3 + k as f64).collect();
        let b = Bivector::from_components(n, &comps).unwrap();
        let x = Vector::basis(n, 0);
        // The first use in each dimension builds cached blade tables once; warm them up.
        let _ = b.exp().compose(&b.exp()).rotate_vector(&x);
        // Warm-up: the per-plane table of the plane rotation is built once per N.
        Rotor::identity(n).rotate_in_plane_mut(0, 1, 0.1);
        let mut q = nalgebra::DMatrix::zeros(n, n);
        let count = allocations_in(|| {
            let r = b.exp();
            let mut s = r.compose(&r);
            s.rotate_in_plane_mut(0, 1, 0.1);
            let y = s.rotate_vector(&x);
            let l = s.log();
            s.matrix_to(&mut q).unwrap();
            let _ = std::hint::black_box((y, l, s.unit_error()));
        });
        assert_eq!(count, 0, "N = {n}: {count} heap allocations");
    }
}

#[test]
fn integrator_steps_do_not_allocate() {
    use rotorflow::dynamics::torques::Free;
    use rotorflow::dynamics::{
        Dop853, Dopri5, Integrator, LiePoissonRk4, Midpoint, MoserVeselov, RigidBody, Rkmk4,
        Splitting,
    };
    // Strang and Yoshida work in place on the attitude and momentum: no heap for N ≤ 8.
    // RK4, the midpoint rule, Dopri5 and Dop853 too: rotor attitudes up to N = 4 (inline rotors,
    // closed-form exp), inline matrix attitudes above, up to N = 8.
    for n in 2..=8 {
        let moments: Vec<f64> = (0..n).map(|k| 1.0 + k as f64).collect();
        let l: Vec<f64> = (0..n * (n - 1) / 2).map(|k| (k as f64).cos()).collect();
        let inertia = InertiaMap::from_principal_second_moments(&moments).unwrap();
        let mut body = RigidBody::from_body_momentum(
            inertia,
            Rotor::identity(n),
            &Bivector::from_components(n, &l).unwrap(),
        )
        .unwrap();
        let mut strang = Splitting::strang();
        let mut yoshida = Splitting::yoshida4();
        strang.step(&mut body, 0.0, 0.01, &Free).unwrap(); // warm-up (cached tables)
        let count = allocations_in(|| {
            for k in 0..100 {
                strang
                    .step(&mut body, k as f64 * 0.01, 0.01, &Free)
                    .unwrap();
                yoshida
                    .step(&mut body, k as f64 * 0.01, 0.01, &Free)
                    .unwrap();
            }
        });
        assert_eq!(
            count, 0,
            "splitting, N = {n}: {count} heap allocations in 200 steps"
        );
        let mut lp = LiePoissonRk4;
        lp.step(&mut body, 0.0, 0.01, &Free).unwrap();
        let count = allocations_in(|| {
            for k in 0..100 {
                lp.step(&mut body, k as f64 * 0.01, 0.01, &Free).unwrap();
            }
        });
        assert_eq!(
            count, 0,
            "lie-poisson-rk4, N = {n}: {count} heap allocations in 100 steps"
        );
        let mut rk = Rkmk4;
        rk.step(&mut body, 0.0, 0.01, &Free).unwrap();
        let count = allocations_in(|| {
            for k in 0..100 {
                rk.step(&mut body, k as f64 * 0.01, 0.01, &Free).unwrap();
            }
        });
        assert_eq!(
            count, 0,
            "rk4, N = {n}: {count} heap allocations in 100 steps"
        );
        // The implicit midpoint rule and adaptive Dopri5 (stages inline).
        let mut midpoint = Midpoint::default();
        let mut dopri = Dopri5::new(1e-8, 1e-8);
        midpoint.step(&mut body, 0.0, 0.01, &Free).unwrap();
        dopri.step(&mut body, 0.0, 0.01, &Free).unwrap();
        let count = allocations_in(|| {
            for k in 0..50 {
                midpoint
                    .step(&mut body, k as f64 * 0.01, 0.01, &Free)
                    .unwrap();
                dopri.step(&mut body, k as f64 * 0.01, 0.01, &Free).unwrap();
            }
        });
        assert_eq!(
            count, 0,
            "midpoint and dopri5, N = {n}: {count} heap allocations in 100 steps"
        );
        // Dop853: sixteen stages inline, the dense output's included.
        let mut dop853 = Dop853::new(1e-10, 1e-10).unwrap();
        dop853.step(&mut body, 0.0, 0.01, &Free).unwrap();
        let count = allocations_in(|| {
            for k in 0..50 {
                dop853
                    .step(&mut body, k as f64 * 0.01, 0.01, &Free)
                    .unwrap();
                let (t0, h) = dop853.last_step().unwrap();
                let state = dop853.dense_output(&body, &Free, t0 + 0.5 * h).unwrap();
                assert!(state.0.is_finite());
            }
        });
        assert_eq!(
            count, 0,
            "dop853, N = {n}: {count} heap allocations in 50 steps"
        );
        // Moser–Veselov: the Newton solve on inline matrices (K ≤ 28 unknowns).
        let mut mv = MoserVeselov::new();
        mv.step(&mut body, 0.0, 0.01, &Free).unwrap();
        let count = allocations_in(|| {
            for k in 0..100 {
                mv.step(&mut body, k as f64 * 0.01, 0.01, &Free).unwrap();
            }
        });
        assert_eq!(
            count, 0,
            "moser-veselov, N = {n}: {count} heap allocations in 100 steps"
        );
    }
}

/// Above N = 8 bivectors spill to the heap; a step then allocates a fixed handful (its
/// stage and scratch blocks, the attitude's exponential), never per stage, per iteration
/// or per term: the same count at N = 9, 12 and 16, where the terms and planes grow
/// (measured: Strang 5, Yoshida 13, RK4 9, midpoint 17, Dopri5 18, Dop853 31 per step, the
/// bounds). Moser–Veselov's count is 15 per step at N = 9 and 16 at N = 12 and 16 (its
/// iterative solve differs with N), so it is only bounded.
#[test]
fn integrator_steps_allocate_a_constant_handful_above_n8() {
    use rotorflow::dynamics::torques::Free;
    use rotorflow::dynamics::{
        Dop853, Dopri5, Integrator, Midpoint, MoserVeselov, RigidBody, Rkmk4, Splitting,
    };
    let mut checked = 0;
    let mut per_n: Vec<Vec<(&str, usize)>> = Vec::new();
    for n in [9usize, 12, 16] {
        let mut counts = Vec::new();
        let moments: Vec<f64> = (0..n).map(|k| 1.0 + k as f64).collect();
        let l: Vec<f64> = (0..n * (n - 1) / 2).map(|k| (k as f64).cos()).collect();
        let inertia = InertiaMap::from_principal_second_moments(&moments).unwrap();
        let start = RigidBody::from_body_momentum(
            inertia,
            Rotor::identity(n),
            &Bivector::from_components(n, &l).unwrap(),
        )
        .unwrap();
        let mut all: Vec<(&str, Box<dyn Integrator>, usize)> = vec![
            ("strang", Box::new(Splitting::strang()), 5),
            ("yoshida", Box::new(Splitting::yoshida4()), 13),
            ("rk4", Box::new(Rkmk4), 9),
            ("midpoint", Box::new(Midpoint::default()), 17),
            ("dopri5", Box::new(Dopri5::new(1e-8, 1e-8)), 18),
            ("dop853", Box::new(Dop853::new(1e-10, 1e-10).unwrap()), 31),
            ("moser-veselov", Box::new(MoserVeselov::new()), 16),
        ];
        for (name, integ, handful) in all.iter_mut() {
            let mut body = start.clone();
            integ.step(&mut body, 0.0, 1e-3, &Free).unwrap();
            let steps = 20;
            let count = allocations_in(|| {
                for k in 0..steps {
                    integ.step(&mut body, k as f64 * 1e-3, 1e-3, &Free).unwrap();
                }
            });
            let per_step = count as f64 / steps as f64;
            eprintln!("N = {n}, {name}: {per_step} allocations per step");
            assert!(
                per_step <= *handful as f64,
                "{name}, N = {n}: {per_step} allocations per step"
            );
            if *name != "moser-veselov" {
                counts.push((*name, count));
            }
            checked += 1;
        }
        per_n.push(counts);
    }
    assert_eq!(checked, 21);
    // Constant across N: every integrator but Moser–Veselov allocated as often in its 20
    // steps at N = 12 and 16 as at N = 9.
    assert_eq!(per_n[0].len(), 6);
    for counts in &per_n[1..] {
        assert_eq!(
            counts, &per_n[0],
            "allocations in 20 steps at N = 9 against larger N"
        );
    }
}

#[test]
fn fixed_size_body_steps_and_rotor_kernels_do_not_allocate() {
    use rotorflow::algebra::{Bivector3, Bivector4};
    use rotorflow::dynamics::{FreeBody3, FreeBody4};
    let mut b3 = FreeBody3::new(
        [1.0, 2.0, 3.0],
        Bivector3::new(0.1, 0.2, 0.3).exp(),
        Bivector3::new(1.0, -0.5, 0.25),
    )
    .unwrap();
    let mut b4 = FreeBody4::new(
        [1.0, 1.5, 2.0, 2.5, 3.0, 3.5],
        Bivector4::new(0.1, 0.2, 0.3, -0.1, 0.0, 0.4).exp(),
        Bivector4::new(1.0, -0.5, 0.25, 0.3, -0.2, 0.6),
    )
    .unwrap();
    // The splitting's plane tables are built on first use; warm them up.
    b3.step_strang(0.01);
    b4.step_strang(0.01);
    let count = allocations_in(|| {
        for _ in 0..100 {
            b3.step_rk4(0.01);
            b3.step_strang(0.01);
            b4.step_rk4(0.01);
            b4.step_strang(0.01);
            let _ = std::hint::black_box(b3.advance_dop853(0.05, 1e-10, 1e-12));
            let _ = std::hint::black_box(b4.advance_dop853(0.05, 1e-10, 1e-12));
            let r = b4.attitude();
            let _ = std::hint::black_box((r * r).log().exp().to_matrix());
            let mut x = [1.0f64; 8];
            let (a, rest) = x.split_at_mut(2);
            let (b, rest) = rest.split_at_mut(2);
            let (c, d) = rest.split_at_mut(2);
            r.rotate_soa(a, b, c, d);
        }
    });
    assert_eq!(
        count, 0,
        "{count} heap allocations in 100 steps and adaptive runs"
    );
}

/// A bivector of `sig` with every coefficient non-zero.
fn dense_bivector(sig: rotorflow::algebra::Signature) -> Multivector {
    let n = sig.dim();
    let mut b = Multivector::zero(sig);
    let mut k = 0;
    for i in 0..n {
        for j in i + 1..n {
            b.as_mut_slice()[(1usize << i) | (1usize << j)] = 0.1 + 0.07 * k as f64;
            k += 1;
        }
    }
    b
}

/// Heap allocations of one `Multivector::exp` and one `Multivector::log` call (after a
/// warm-up call that builds the cached blade tables).
fn versor_allocations(p: usize, q: usize, r: usize) -> (usize, usize) {
    let sig = rotorflow::algebra::Signature::new(p, q, r).unwrap();
    let b = dense_bivector(sig);
    let v = b.exp().unwrap();
    let _ = v.log().unwrap();
    let exp = allocations_in(|| {
        let _ = std::hint::black_box(std::hint::black_box(&b).exp());
    });
    let log = allocations_in(|| {
        let _ = std::hint::black_box(std::hint::black_box(&v).log());
    });
    (exp, log)
}

#[test]
fn versor_exp_and_log_do_not_allocate_up_to_n4() {
    // Multivector coefficients are stored inline up to N = 4 (16 of them), so up to N = 4
    // even the returned multivector stays off the heap.
    for (p, q, r) in [
        (2, 0, 0),
        (3, 0, 0),
        (4, 0, 0),
        (1, 1, 0),
        (2, 0, 1),
        (3, 0, 1),
        (3, 1, 0),
        (1, 3, 0),
        (2, 2, 0),
        (2, 1, 1),
    ] {
        let (exp, log) = versor_allocations(p, q, r);
        eprintln!("Cl({p}, {q}, {r}): exp {exp}, log {log}");
        assert_eq!(
            (exp, log),
            (0, 0),
            "Cl({p}, {q}, {r}): heap allocations in (exp, log)"
        );
    }
}

/// A bivector of `sig` with every coefficient non-zero whose versor has a logarithm: the
/// dense bivector, or in the two signatures where its joint rotation angles pass π
/// (Cl(6, 0, 0) and Cl(0, 6, 0)) a quarter of it.
fn loggable_bivector(sig: rotorflow::algebra::Signature) -> Multivector {
    let b = dense_bivector(sig);
    if b.exp().unwrap().log().is_ok() {
        b
    } else {
        &b * 0.25
    }
}

/// Heap allocations of one `exp_to` and one `log_to` of `b` into reused storage (after a
/// warm-up call that builds the cached tables), with both results checked against `exp` and
/// against `b`, so that the count is of a call that did its work.
fn versor_to_allocations(b: &Multivector) -> (usize, usize) {
    let sig = b.signature();
    let v = b.exp().unwrap();
    let mut out = Multivector::zero(sig);
    b.exp_to(&mut out).unwrap();
    v.log_to(&mut out).unwrap();
    let exp = allocations_in(|| {
        std::hint::black_box(b).exp_to(&mut out).unwrap();
    });
    assert_eq!(out, v, "{sig}: exp_to = exp");
    let log = allocations_in(|| {
        std::hint::black_box(&v).log_to(&mut out).unwrap();
    });
    let scale = b.max_abs().max(1.0);
    assert!(
        (&out - b).max_abs() <= 1e-9 * scale,
        "{sig}: log_to(exp(B)) = B, off by {}",
        (&out - b).max_abs()
    );
    (exp, log)
}

fn signatures(n: usize) -> Vec<rotorflow::algebra::Signature> {
    let mut out = Vec::new();
    for p in 0..=n {
        for q in 0..=n - p {
            out.push(rotorflow::algebra::Signature::new(p, q, n - p - q).unwrap());
        }
    }
    out
}

#[test]
fn versor_exp_to_and_log_to_do_not_allocate_up_to_n6() {
    let mut checked = 0;
    for n in 2..=6 {
        for sig in signatures(n) {
            let b = loggable_bivector(sig);
            let (exp, log) = versor_to_allocations(&b);
            eprintln!("{sig}: exp_to {exp}, log_to {log} heap allocations");
            assert_eq!(
                (exp, log),
                (0, 0),
                "{sig}: heap allocations in (exp_to, log_to)"
            );
            // `exp` and `log` themselves allocate only their result, and only from N = 5
            // (multivectors keep 16 coefficients inline).
            let v = b.exp().unwrap();
            let expected = usize::from(n >= 5);
            let count = allocations_in(|| {
                let _ = std::hint::black_box(std::hint::black_box(&b).exp());
            });
            assert_eq!(count, expected, "{sig}: exp");
            let count = allocations_in(|| {
                let _ = std::hint::black_box(std::hint::black_box(&v).log());
            });
            assert_eq!(count, expected, "{sig}: log");
            checked += 1;
        }
    }
    assert_eq!(checked, 6 + 10 + 15 + 21 + 28);
}

/// A bivector of `sig` from (i, j, coefficient) triples, 1-based like the blade names.
fn bivector_of(sig: rotorflow::algebra::Signature, terms: &[(usize, usize, f64)]) -> Multivector {
    let mut b = Multivector::zero(sig);
    for &(i, j, c) in terms {
        b.as_mut_slice()[(1usize << (i - 1)) | (1usize << (j - 1))] = c;
    }
    b
}

/// The routes the dense bivectors do not reach stay off the heap too: boosts large enough
/// for the general logarithm's versor square roots (one and two halvings), translations
/// large enough for its null-vector scaling, a Euclidean rotation by nearly π at N = 5,
/// Euclidean and projective rotors on the negative sheet (a half-angle above π/2, which the
/// rotor logarithm refines as the logarithm of −R), and a bivector with a single plane.
#[test]
fn versor_exp_to_and_log_to_special_routes_do_not_allocate() {
    use rotorflow::algebra::Signature;
    let pi = std::f64::consts::PI;
    let cases = [
        // Boosts of rapidity 6 and 4 beside a rotation: square roots before the logarithm.
        (
            Signature::new(5, 1, 0).unwrap(),
            vec![(1, 6, 3.0), (2, 3, 0.4), (4, 5, 2.0)],
        ),
        (
            Signature::new(3, 3, 0).unwrap(),
            vec![(1, 4, 2.0), (2, 5, 1.5), (3, 6, 0.3), (1, 2, 0.2)],
        ),
        // Translations of 10⁶ beside rotations, with three null vectors: null scaling.
        (
            Signature::new(3, 0, 3).unwrap(),
            vec![
                (1, 2, 0.7),
                (1, 4, 1e6),
                (2, 5, -3e5),
                (3, 6, 2e6),
                (4, 5, 0.5),
            ],
        ),
        (
            Signature::new(2, 2, 2).unwrap(),
            vec![(1, 5, 1e6), (3, 4, 0.6), (2, 6, -4e5), (1, 3, 0.3)],
        ),
        // A rotation by nearly π (half-angle near π/2), and two half-angles above π/2.
        (
            Signature::new(5, 0, 0).unwrap(),
            vec![(1, 2, 0.5 * pi - 1e-3), (3, 4, 0.4), (2, 5, 0.1)],
        ),
        (
            Signature::new(6, 0, 0).unwrap(),
            vec![(1, 2, 0.5 * pi + 0.3), (3, 4, 1.2), (5, 6, 0.3)],
        ),
        (
            Signature::new(5, 0, 1).unwrap(),
            vec![
                (1, 2, 0.5 * pi + 0.3),
                (3, 4, 1.2),
                (1, 6, 4.0),
                (5, 6, -2.0),
            ],
        ),
        // A single plane in 6D.
        (Signature::new(4, 2, 0).unwrap(), vec![(2, 5, 0.8)]),
    ];
    for (sig, terms) in &cases {
        let b = bivector_of(*sig, terms);
        let (exp, log) = versor_to_allocations(&b);
        eprintln!("{sig} {terms:?}: exp_to {exp}, log_to {log} heap allocations");
        assert_eq!((exp, log), (0, 0), "{sig} {terms:?}");
    }
}

mod moving_bodies {
    use super::allocations_in;
    use rotorflow::dynamics::motion::forques::{Anchor, Gravity, Spring};
    use rotorflow::dynamics::motion::{
        BallJoint, ContactShape, HalfSpace, MotionIntegrator, MotionRk4, MotionSplitting,
        MovingBody, SoftStep, System,
    };
    use rotorflow::inertia::spec::parse_body;
    use rotorflow::prelude::*;

    fn axis(n: usize, i: usize, x: f64) -> Vector {
        let mut v = Vector::zero(n);
        v.as_mut_slice()[i] = x;
        v
    }

    /// A solid cuboid in N dimensions (half-lengths 0.5, 0.6, …) at `x`, moving with `v` and
    /// turning with `omega` (own axes), with its contact shape.
    fn cuboid(n: usize, x: Vector, v: Vector, omega: f64) -> (MovingBody, ContactShape) {
        let half: Vec<String> = (0..n)
            .map(|k| format!("{}", 0.5 + 0.1 * k as f64))
            .collect();
        let parsed = parse_body(&format!("cuboid:{}", half.join(","))).unwrap();
        let w: Vec<f64> = (0..n * (n - 1) / 2)
            .map(|k| omega * (0.7 * k as f64 + 0.3).sin())
            .collect();
        let body = MovingBody::new(
            parsed.mass,
            parsed.inertia.clone(),
            Rotor::identity(n),
            &x,
            &v,
            &Bivector::from_components(n, &w).unwrap(),
        )
        .unwrap();
        (body, ContactShape::from_geometry(&parsed.geometry))
    }

    /// A turning body under gravity, hung from a point of space by a damped spring attached
    /// off its centre of mass.
    fn sprung(n: usize) -> System {
        let (b, _) = cuboid(n, axis(n, 0, 0.3), axis(n, 1, 0.5), 1.0);
        let mut s = System::new(vec![b]).unwrap();
        s.add_forque(Gravity(axis(n, n - 1, -9.81))).unwrap();
        s.add_forque(Spring {
            body: 0,
            point: axis(n, 0, 0.4),
            anchor: Anchor::World(axis(n, n - 1, 2.0)),
            stiffness: 30.0,
            rest_length: 1.0,
            damping: 0.1,
        })
        .unwrap();
        s
    }

    /// The bodies with their contact shapes under gravity along −x_N, on the floor x_N = 0
    /// with friction 0.5.
    fn on_floor(n: usize, bodies: Vec<MovingBody>, shapes: Vec<ContactShape>) -> System {
        let mut system = System::new(bodies).unwrap();
        for (i, shape) in shapes.into_iter().enumerate() {
            system.set_shape(i, shape).unwrap();
        }
        system.add_forque(Gravity(axis(n, n - 1, -9.81))).unwrap();
        system
            .add_half_space(HalfSpace::new(&axis(n, n - 1, 1.0), 0.0, 0.5, 0.0).unwrap())
            .unwrap();
        system
    }

    /// Heap allocations of `steps` steps of `integrator` on `system`, after one warm-up step
    /// (which sizes the integrator's buffers).
    fn step_allocations(
        integrator: &mut dyn MotionIntegrator,
        system: &mut System,
        h: f64,
        steps: usize,
    ) -> usize {
        integrator.step(system, 0.0, h).unwrap();
        allocations_in(|| {
            for k in 1..=steps {
                integrator.step(system, k as f64 * h, h).unwrap();
            }
        })
    }

    #[test]
    fn motion_splitting_free_flight_does_not_allocate() {
        for n in 2..=8 {
            let mut system = sprung(n);
            let count = step_allocations(&mut MotionSplitting::new(), &mut system, 0.01, 50);
            assert_eq!(count, 0, "N = {n}: {count} heap allocations in 50 steps");
        }
    }

    #[test]
    fn motion_rk4_does_not_allocate() {
        for n in 2..=8 {
            let mut system = sprung(n);
            let count = step_allocations(&mut MotionRk4::new(), &mut system, 0.01, 50);
            assert_eq!(count, 0, "N = {n}: {count} heap allocations in 50 steps");
        }
    }

    #[test]
    fn motion_splitting_resting_contact_does_not_allocate() {
        for n in 3..=8 {
            // A cuboid set down on the floor x_N = 0 with friction, settled before counting.
            let h_n = 0.5 + 0.1 * (n - 1) as f64;
            let (b, shape) = cuboid(n, axis(n, n - 1, h_n + 1e-3), Vector::zero(n), 0.05);
            let mut system = System::new(vec![b]).unwrap();
            system.set_shape(0, shape).unwrap();
            system.add_forque(Gravity(axis(n, n - 1, -9.81))).unwrap();
            system
                .add_half_space(HalfSpace::new(&axis(n, n - 1, 1.0), 0.0, 0.5, 0.0).unwrap())
                .unwrap();
            let mut integrator = MotionSplitting::new();
            for k in 0..100 {
                integrator.step(&mut system, k as f64 * 0.01, 0.01).unwrap();
            }
            assert!(!system.contacts().is_empty(), "N = {n}: the body rests");
            let count = step_allocations(&mut integrator, &mut system, 0.01, 50);
            assert!(!system.contacts().is_empty(), "N = {n}: the body rests");
            assert_eq!(count, 0, "N = {n}: {count} heap allocations in 50 steps");
        }
    }

    #[test]
    fn motion_splitting_floor_of_resting_bodies_does_not_allocate() {
        for n in 3..=8 {
            // A row of cuboids set down on the floor x_N = 0 turning about the vertical (as
            // the floor bench's), settled before counting.
            let h_n = 0.5 + 0.1 * (n - 1) as f64;
            let mut bodies = Vec::new();
            let mut shapes = Vec::new();
            for k in 0..10 {
                let mut x = axis(n, 0, 2.5 * k as f64);
                x.as_mut_slice()[n - 1] = h_n;
                let mut w = Bivector::zero(n);
                w.as_mut_slice()[0] = 0.5 * (k as f64 * 0.37).sin();
                let (mut b, shape) = cuboid(n, x.clone(), Vector::zero(n), 0.0);
                b = MovingBody::new(
                    b.mass(),
                    b.rotation().inertia().clone(),
                    Rotor::identity(n),
                    &x,
                    &Vector::zero(n),
                    &w,
                )
                .unwrap();
                bodies.push(b);
                shapes.push(shape);
            }
            let mut system = on_floor(n, bodies, shapes);
            let mut integrator = MotionSplitting::new();
            for k in 0..50 {
                integrator.step(&mut system, k as f64 * 0.01, 0.01).unwrap();
            }
            let count = step_allocations(&mut integrator, &mut system, 0.01, 20);
            let mut touching = [false; 10];
            for c in system.contacts() {
                touching[c.body] = true;
            }
            assert!(touching.iter().all(|&t| t), "N = {n}: every body rests");
            assert_eq!(count, 0, "N = {n}: {count} heap allocations in 20 steps");
            // The same steps taken together (one velocity solve per step).
            let count = allocations_in(|| {
                integrator.advance(&mut system, 0.0, 0.01, 20).unwrap();
            });
            assert_eq!(
                count, 0,
                "N = {n}: {count} heap allocations in advance by 20 steps"
            );
        }
    }

    /// Two cuboids stacked on the floor x_N = 0, the upper one offset by 5 % along the
    /// first axis.
    fn box_on_a_box(n: usize) -> System {
        let h_n = 0.5 + 0.1 * (n - 1) as f64;
        let mut bodies = Vec::new();
        let mut shapes = Vec::new();
        for (k, shift) in [(0, 0.0), (1, 0.05)] {
            let mut x = axis(n, 0, shift);
            x.as_mut_slice()[n - 1] = h_n * (1.0 + 2.0 * k as f64) + 1e-4;
            let (b, shape) = cuboid(n, x, Vector::zero(n), 0.0);
            bodies.push(b);
            shapes.push(shape);
        }
        on_floor(n, bodies, shapes)
    }

    #[test]
    fn motion_splitting_box_resting_on_a_box_does_not_allocate() {
        for n in 3..=6 {
            // Settled before counting: contact rows between bodies, their manifold points
            // and warm starts.
            let mut system = box_on_a_box(n);
            let mut integrator = MotionSplitting::new();
            // The contact log keeps every contact of a step, one set per solve (the
            // located impacts of a step each solve), and grows to the busiest step met.
            for k in 0..100 {
                integrator.step(&mut system, k as f64 * 0.01, 0.01).unwrap();
            }
            let count = step_allocations(&mut integrator, &mut system, 0.01, 20);
            assert!(
                system.body_contacts().len() >= 4,
                "N = {n}: the boxes rest on each other ({} points)",
                system.body_contacts().len()
            );
            assert_eq!(count, 0, "N = {n}: {count} heap allocations in 20 steps");
            let count = allocations_in(|| {
                integrator.advance(&mut system, 0.0, 0.01, 20).unwrap();
            });
            assert_eq!(
                count, 0,
                "N = {n}: {count} heap allocations in advance by 20 steps"
            );
        }
    }

    #[test]
    fn soft_step_box_resting_on_a_box_does_not_allocate() {
        let mut cases = 0;
        for n in 3..=8 {
            // Settled before counting: rows against the floor and between the bodies, their
            // manifold points and the impulses kept from step to step.
            let mut system = box_on_a_box(n);
            let mut integrator = SoftStep::new();
            for k in 0..100 {
                integrator.step(&mut system, k as f64 * 0.01, 0.01).unwrap();
            }
            let count = step_allocations(&mut integrator, &mut system, 0.01, 20);
            assert_eq!(count, 0, "N = {n}: {count} heap allocations in 20 steps");
            cases += 1;
        }
        assert_eq!(cases, 6);
    }

    /// A body touching with `shape` at rest on a box on the floor (both placed 1e-4 above
    /// their resting heights, `height` the body's above the box's top), settled for 1 s under
    /// each integrator: asserts that it rests on the box and that 20 more steps allocate
    /// nothing; returns the number of integrators run.
    fn resting_on_a_box_allocations(n: usize, shape: ContactShape, height: f64) -> usize {
        let h_n = 0.5 + 0.1 * (n - 1) as f64;
        let integrators: [Box<dyn MotionIntegrator>; 2] =
            [Box::new(MotionSplitting::new()), Box::new(SoftStep::new())];
        let mut cases = 0;
        for mut integrator in integrators {
            let (base, base_shape) = cuboid(n, axis(n, n - 1, h_n + 1e-4), Vector::zero(n), 0.0);
            let (top, _) = cuboid(
                n,
                axis(n, n - 1, 2.0 * h_n + height + 2e-4),
                Vector::zero(n),
                0.0,
            );
            let mut system = on_floor(n, vec![base, top], vec![base_shape, shape.clone()]);
            for k in 0..100 {
                integrator.step(&mut system, k as f64 * 0.01, 0.01).unwrap();
            }
            let count = step_allocations(integrator.as_mut(), &mut system, 0.01, 20);
            assert!(
                system.body_contacts().len() >= 2,
                "N = {n}, {}: it rests on the box ({} points)",
                integrator.name(),
                system.body_contacts().len()
            );
            assert_eq!(
                count,
                0,
                "N = {n}, {}: {count} heap allocations in 20 steps",
                integrator.name()
            );
            cases += 1;
        }
        cases
    }

    /// A capsule lying on a box (N even) or a rounded box on a box (N odd) on the floor,
    /// placed 1e-4 above their resting heights: shapes with a margin, which touch by the
    /// manifold of their cores.
    #[test]
    fn rounded_shapes_resting_on_a_box_do_not_allocate() {
        use rotorflow::dynamics::motion::shape::ConvexShape;
        let mut cases = 0;
        for n in 3..=8 {
            let (rounded, height) = if n % 2 == 0 {
                (ConvexShape::capsule(n, 0.4, 0.2).unwrap(), 0.2)
            } else {
                let c = ConvexShape::cuboid(&vec![0.3; n]).unwrap();
                (c.rounded(0.1).unwrap(), 0.4)
            };
            cases += resting_on_a_box_allocations(n, ContactShape::Convex(rounded), height);
        }
        assert_eq!(cases, 12);
    }

    /// A compound of two boxes side by side (N odd) or a dumbbell of two balls (N even)
    /// resting on a box on the floor, placed 1e-4 above its resting height: the pieces meet
    /// the box piece by piece.
    #[test]
    fn compound_bodies_resting_on_a_box_do_not_allocate() {
        use rotorflow::dynamics::motion::shape::{CompoundShape, ConvexShape, Piece};
        let mut cases = 0;
        for n in 3..=8 {
            let at = |x: f64| {
                let mut v = vec![0.0; n];
                v[0] = x;
                v
            };
            let (pieces, height) = if n % 2 == 0 {
                let ball = ConvexShape::ball(n, 0.2).unwrap();
                let p = |x| Piece::translated(ball.clone(), &at(x)).unwrap();
                (vec![p(-0.4), p(0.4)], 0.2)
            } else {
                let cube = ConvexShape::cuboid(&vec![0.2; n]).unwrap();
                let p = |x| Piece::translated(cube.clone(), &at(x)).unwrap();
                (vec![p(-0.2), p(0.2)], 0.2)
            };
            let compound = CompoundShape::new(pieces).unwrap();
            cases += resting_on_a_box_allocations(n, ContactShape::Compound(compound), height);
        }
        assert_eq!(cases, 12);
    }

    #[test]
    fn motion_splitting_ball_joint_does_not_allocate() {
        for n in 3..=8 {
            // A pendulum: the body hangs from a point of space by a corner, and a second body
            // hangs from the first.
            let (a, _) = cuboid(n, Vector::zero(n), axis(n, 0, 0.2), 0.5);
            let (b, _) = cuboid(n, axis(n, 0, 1.0), Vector::zero(n), 0.3);
            let mut system = System::new(vec![a, b]).unwrap();
            system.add_forque(Gravity(axis(n, n - 1, -9.81))).unwrap();
            system
                .add_ball_joint(BallJoint {
                    body: 0,
                    point: axis(n, 0, -0.5),
                    other: Anchor::World(axis(n, 0, -0.5)),
                })
                .unwrap();
            system
                .add_ball_joint(BallJoint {
                    body: 0,
                    point: axis(n, 0, 0.5),
                    other: Anchor::Body(1, axis(n, 0, -0.5)),
                })
                .unwrap();
            let mut integrator = MotionSplitting::new();
            let count = step_allocations(&mut integrator, &mut system, 0.01, 50);
            assert_eq!(count, 0, "N = {n}: {count} heap allocations in 50 steps");
            let count = allocations_in(|| {
                integrator.advance(&mut system, 0.0, 0.01, 20).unwrap();
            });
            assert_eq!(
                count, 0,
                "N = {n}: {count} heap allocations in advance by 20 steps"
            );
        }
    }
}

#[test]
fn preprocessed_moser_veselov_steps_do_not_allocate() {
    use rotorflow::dynamics::torques::Free;
    use rotorflow::dynamics::{Integrator, MoserVeselov, RigidBody};
    let inertia = InertiaMap::from_principal_second_moments(&[0.4, 1.1, 1.9]).unwrap();
    let mut body = RigidBody::from_body_momentum(
        inertia,
        Rotor::identity(3),
        &Bivector::from_components(3, &[0.8, -0.5, 1.2]).unwrap(),
    )
    .unwrap();
    let mut mv = MoserVeselov::preprocessed(6).unwrap();
    mv.step(&mut body, 0.0, 0.01, &Free).unwrap();
    let count = allocations_in(|| {
        for k in 0..100 {
            mv.step(&mut body, k as f64 * 0.01, 0.01, &Free).unwrap();
        }
    });
    assert_eq!(
        count, 0,
        "{count} heap allocations in 100 steps and adaptive runs"
    );
}

/// The narrow phase: GJK distances of turned boxes, hulls, ellipsoids and capsules up to
/// N = 8, and EPA penetrations of overlapping ones up to N = 5, with a workspace that has
/// grown on the same pair once.
#[test]
fn narrow_phase_queries_do_not_allocate_up_to_n8() {
    use rotorflow::dynamics::motion::detect::{
        EpaWorkspace, PlacedShape, distance, penetration_with,
    };
    use rotorflow::dynamics::motion::shape::ConvexShape;
    let mut checked = 0;
    for n in 2..=8 {
        // A turn in every coordinate plane.
        let mut q: Vec<f64> = (0..n * n)
            .map(|k| if k % (n + 1) == 0 { 1.0 } else { 0.0 })
            .collect();
        for i in 0..n {
            for j in i + 1..n {
                let (s, c) = (0.3 + 0.1 * (i + j) as f64).sin_cos();
                for row in 0..n {
                    let (x, y) = (q[row * n + i], q[row * n + j]);
                    q[row * n + i] = c * x - s * y;
                    q[row * n + j] = s * x + c * y;
                }
            }
        }
        let corners: Vec<Vec<f64>> = (0..1usize << n)
            .map(|m| {
                (0..n)
                    .map(|i| if m >> i & 1 == 1 { 0.5 } else { -0.4 })
                    .collect()
            })
            .collect();
        let shapes = [
            ConvexShape::cuboid(&vec![0.5; n]).unwrap(),
            ConvexShape::hull(&corners).unwrap(),
            ConvexShape::ellipsoid(&(0..n).map(|k| 0.3 + 0.1 * k as f64).collect::<Vec<_>>())
                .unwrap(),
            ConvexShape::capsule(n, 0.4, 0.2).unwrap(),
        ];
        let pa = vec![0.0; n];
        let mut workspace = EpaWorkspace::new();
        for sa in &shapes {
            for sb in &shapes {
                for gap in [0.5, 1.5] {
                    let mut pb = vec![0.05; n];
                    pb[0] = gap;
                    let a = PlacedShape::new(sa, &pa, &q).unwrap();
                    let b = PlacedShape::new(sb, &pb, &q).unwrap();
                    let with_epa = n <= 5 || gap > 1.0;
                    if with_epa {
                        let _ = penetration_with(&mut workspace, &a, &b).unwrap();
                    }
                    let count = allocations_in(|| {
                        let d = distance(&a, &b).unwrap();
                        if with_epa {
                            let p = penetration_with(&mut workspace, &a, &b).unwrap();
                            std::hint::black_box(p);
                        }
                        std::hint::black_box(d);
                    });
                    assert_eq!(count, 0, "N = {n}: {count} heap allocations");
                    checked += 1;
                }
            }
        }
    }
    println!("narrow-phase pairs without allocation: {checked}");
    assert_eq!(checked, 7 * 4 * 4 * 2);
}
