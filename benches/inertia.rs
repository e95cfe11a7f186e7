//! Criterion benches of the inertia layer: apply and inverse-apply of the map for
//! N = 3, 4, 6, 8 beside a dense nalgebra matrix–vector product of the same size, and mesh
//! inertia throughput in simplices per second (goal ≥ 1e7/s in 4D).
//! `BENCH_QUICK=1` shortens the run.

use criterion::{BenchmarkId, Criterion, Throughput, black_box, criterion_group, criterion_main};
use nalgebra::{DMatrix, DVector};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rotorflow::inertia::SimplexOrientation;
use rotorflow::prelude::*;

#[path = "common/configure.rs"]
mod configure;
use configure::configure;

fn random_spd(rng: &mut impl Rng, n: usize) -> DMatrix<f64> {
    let a = DMatrix::from_fn(n, n, |_, _| rng.gen_range(-1.0..1.0));
    &a * a.transpose() + DMatrix::identity(n, n) * 0.5
}

fn bench_map(c: &mut Criterion) {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    for n in [3usize, 4, 6, 8] {
        let mut g = c.benchmark_group(format!("inertia_map/N={n}"));
        let k = n * (n - 1) / 2;
        let w = Bivector::from_components(
            n,
            &(0..k).map(|_| rng.gen_range(-1.0..1.0)).collect::<Vec<_>>(),
        )
        .unwrap();
        let moments: Vec<f64> = (0..n).map(|i| 1.0 + i as f64).collect();
        let principal = InertiaMap::from_principal_second_moments(&moments).unwrap();
        let general_frame = InertiaMap::from_mass_tensor(&random_spd(&mut rng, n)).unwrap();
        g.bench_function(BenchmarkId::new("rotorflow_apply_principal", n), |b| {
            b.iter(|| black_box(&principal).apply(black_box(&w)))
        });
        g.bench_function(
            BenchmarkId::new("rotorflow_apply_inverse_principal", n),
            |b| b.iter(|| black_box(&principal).apply_inverse(black_box(&w))),
        );
        g.bench_function(BenchmarkId::new("rotorflow_apply_general_frame", n), |b| {
            b.iter(|| black_box(&general_frame).apply(black_box(&w)))
        });
        g.bench_function(
            BenchmarkId::new("rotorflow_apply_inverse_general_frame", n),
            |b| b.iter(|| black_box(&general_frame).apply_inverse(black_box(&w))),
        );
        let m = general_frame.to_matrix();
        let x = DVector::from_column_slice(w.as_slice());
        g.bench_function(BenchmarkId::new("nalgebra_dmatrix_matvec", n), |b| {
            b.iter(|| black_box(&m) * black_box(&x))
        });
        g.finish();
    }
}

/// A grid of `m`^N unit cubes, each cut into N! Kuhn simplices.
fn kuhn_grid(n: usize, m: usize) -> (Vec<DVector<f64>>, Vec<Vec<usize>>) {
    let side = m + 1;
    let count = side.pow(n as u32);
    let vertices: Vec<DVector<f64>> = (0..count)
        .map(|mut idx| {
            DVector::from_fn(n, |_, _| {
                let c = idx % side;
                idx /= side;
                c as f64
            })
        })
        .collect();
    let index = |coords: &[usize]| coords.iter().rev().fold(0, |acc, &c| acc * side + c);
    let mut perms: Vec<Vec<usize>> = vec![vec![]];
    for k in 0..n {
        perms = perms
            .into_iter()
            .flat_map(|p| {
                (0..=k).map(move |pos| {
                    let mut q = p.clone();
                    q.insert(pos, k);
                    q
                })
            })
            .collect();
    }
    let mut simplices = Vec::new();
    for cube in 0..m.pow(n as u32) {
        let mut base = vec![0; n];
        let mut c = cube;
        for b in base.iter_mut() {
            *b = c % m;
            c /= m;
        }
        for p in &perms {
            let mut cur = base.clone();
            let mut s = vec![index(&cur)];
            for &axis in p {
                cur[axis] += 1;
                s.push(index(&cur));
            }
            simplices.push(s);
        }
    }
    (vertices, simplices)
}

fn bench_mesh(c: &mut Criterion) {
    let mut g = c.benchmark_group("mesh_inertia");
    // Simplices as fixed-size index arrays (one flat allocation), the layout a mesh loader
    // produces.
    macro_rules! mesh_case {
        ($n:literal, $m:literal) => {{
            let (vertices, simplices) = kuhn_grid($n, $m);
            let flat: Vec<[usize; $n + 1]> = simplices
                .iter()
                .map(|s| s.as_slice().try_into().unwrap())
                .collect();
            g.throughput(Throughput::Elements(flat.len() as u64));
            g.bench_function(
                BenchmarkId::new(format!("simplices_N={}", $n), flat.len()),
                |b| {
                    b.iter(|| {
                        Body::simplicial_mesh(
                            black_box(&vertices),
                            black_box(&flat),
                            1.0,
                            SimplexOrientation::Unsigned,
                        )
                        .unwrap()
                    })
                },
            );
        }};
    }
    mesh_case!(3, 20);
    mesh_case!(4, 8);
    g.finish();
}

fn benches(_: &mut Criterion) {
    let mut c = configure();
    bench_map(&mut c);
    bench_mesh(&mut c);
}

criterion_group!(inertia, benches);
criterion_main!(inertia);
