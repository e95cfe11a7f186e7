//! Criterion benches of the closed-form free motions: one evaluation of L(t) and
//! of R(t) at a time, beside one Rkmk4 step of the same body. `BENCH_QUICK=1` shortens the
//! run. Groups: `two_moments/N=4`, `two_moments/N=5` and `top3d/N=3`.

use criterion::{BenchmarkId, Criterion, black_box, criterion_group, criterion_main};
use rotorflow::dynamics::exact::top3d::AsymmetricTop;
use rotorflow::dynamics::exact::two_moments::TwoMomentSolution;
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::{Integrator, RigidBody, Rkmk4};
use rotorflow::prelude::*;

#[path = "common/configure.rs"]
mod configure;
use configure::configure;

/// A body with two principal values: 1 on the first ⌈N/2⌉ axes, 2.5 on the others.
fn body(n: usize) -> RigidBody {
    let j: Vec<f64> = (0..n)
        .map(|i| if i < n.div_ceil(2) { 1.0 } else { 2.5 })
        .collect();
    let l: Vec<f64> = (0..n * (n - 1) / 2)
        .map(|k| (0.7 * k as f64 + 0.3).sin())
        .collect();
    RigidBody::from_body_momentum(
        InertiaMap::from_principal_second_moments(&j).unwrap(),
        Rotor::from_rotation_bivector(&Bivector::from_components(n, &l).unwrap()),
        &Bivector::from_components(n, &l).unwrap(),
    )
    .unwrap()
}

fn bench_two_moments(c: &mut Criterion) {
    for n in [4usize, 5] {
        let mut g = c.benchmark_group(format!("two_moments/N={n}"));
        let start = body(n);
        let exact = TwoMomentSolution::new(&start).unwrap();
        let t = 12.345;
        g.bench_function(BenchmarkId::new("momentum_at", n), |b| {
            b.iter(|| exact.momentum_at(black_box(t)).unwrap())
        });
        g.bench_function(BenchmarkId::new("attitude_at", n), |b| {
            b.iter(|| exact.attitude_at(black_box(t)).unwrap())
        });
        g.bench_function(BenchmarkId::new("new", n), |b| {
            b.iter(|| TwoMomentSolution::new(black_box(&start)).unwrap())
        });
        let mut body = start.clone();
        let mut rk = Rkmk4;
        g.bench_function(BenchmarkId::new("rkmk4_step", n), |b| {
            b.iter(|| rk.step(black_box(&mut body), 0.0, 0.01, &Free).unwrap())
        });
        g.finish();
    }
}

/// The free 3D top: L and R at one time (one Jacobi evaluation and one Π), L alone, and
/// building the solution, beside one Rkmk4 step of the same body.
fn bench_top3d(c: &mut Criterion) {
    let inertia = InertiaMap::from_classical_3d([1.8, 1.4, 1.0]).unwrap();
    let l = Bivector::from_components(3, &[1.0, -0.2, 0.3]).unwrap();
    let r =
        Rotor::from_rotation_bivector(&Bivector::from_components(3, &[0.3, -0.5, 0.9]).unwrap());
    let start = RigidBody::from_body_momentum(inertia, r, &l).unwrap();
    let top = AsymmetricTop::new(&start).unwrap();
    let mut g = c.benchmark_group("top3d/N=3");
    let t = 12.345;
    g.bench_function("state_at", |b| {
        b.iter(|| top.state_at(black_box(t)).unwrap())
    });
    g.bench_function("momentum_at", |b| {
        b.iter(|| top.momentum_at(black_box(t)).unwrap())
    });
    g.bench_function("new", |b| {
        b.iter(|| AsymmetricTop::new(black_box(&start)).unwrap())
    });
    let mut body = start.clone();
    let mut rk = Rkmk4;
    g.bench_function("rkmk4_step", |b| {
        b.iter(|| rk.step(black_box(&mut body), 0.0, 0.01, &Free).unwrap())
    });
    g.finish();
}

fn benches(_: &mut Criterion) {
    let mut c = configure();
    bench_two_moments(&mut c);
    bench_top3d(&mut c);
}

criterion_group!(exact, benches);
criterion_main!(exact);
