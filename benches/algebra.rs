//! Criterion benches of the algebra kernels, each beside nalgebra doing the same job in the
//! same group: exp vs the matrix exponential of the skew matrix, the bivector
//! commutator vs A·B − B·A on skew matrices, the sandwich vs matrix × vector, composition vs
//! matrix × matrix. Run `cargo bench --bench algebra`; `BENCH_QUICK=1` shortens the run.

use criterion::{BenchmarkId, Criterion, black_box, criterion_group, criterion_main};
use nalgebra::{DMatrix, DVector, SMatrix, SVector};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rotorflow::prelude::*;

const DIMS: [usize; 5] = [3, 4, 6, 8, 10];

fn random_bivector(rng: &mut impl Rng, n: usize) -> Bivector {
    let c: Vec<f64> = (0..n * (n - 1) / 2)
        .map(|_| rng.gen_range(-1.0..1.0))
        .collect();
    Bivector::from_components(n, &c).unwrap()
}

fn random_vector(rng: &mut impl Rng, n: usize) -> Vector {
    let c: Vec<f64> = (0..n).map(|_| rng.gen_range(-1.0..1.0)).collect();
    Vector::from_components(&c).unwrap()
}

#[path = "common/configure.rs"]
mod configure;
use configure::configure;

/// Runs `f::<D>()` for the fixed sizes nalgebra's SMatrix baselines need.
macro_rules! for_fixed_dim {
    ($n:expr, $f:ident, $($arg:expr),*) => {
        match $n {
            3 => $f::<3>($($arg),*),
            4 => $f::<4>($($arg),*),
            6 => $f::<6>($($arg),*),
            8 => $f::<8>($($arg),*),
            10 => $f::<10>($($arg),*),
            _ => unreachable!(),
        }
    };
}

/// nalgebra's fixed-size expm needs concrete sizes (its trait bounds do not hold for a
/// generic `D`), so this one is a macro.
macro_rules! exp_smatrix {
    ($g:expr, $b:expr, $($d:literal),*) => {
        match $b.dim() {
            $($d => {
                let m: SMatrix<f64, $d, $d> = $b.to_skew_smatrix::<$d>().transpose();
                $g.bench_function(BenchmarkId::new("nalgebra_smatrix_expm", $d), |bench| {
                    bench.iter(|| black_box(&m).exp())
                });
            })*
            _ => unreachable!(),
        }
    };
}

fn bench_exp(c: &mut Criterion) {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    for n in DIMS {
        let mut g = c.benchmark_group(format!("exp/N={n}"));
        let b = random_bivector(&mut rng, n);
        g.bench_function(BenchmarkId::new("rotorflow_exp", n), |bench| {
            bench.iter(|| black_box(&b).exp())
        });
        let m = b.to_skew_matrix().transpose();
        g.bench_function(BenchmarkId::new("nalgebra_dmatrix_expm", n), |bench| {
            bench.iter(|| black_box(&m).exp())
        });
        exp_smatrix!(g, b, 3, 4, 6, 8, 10);
        g.finish();
    }
}

/// The rotation matrix expm([B]) at N = 5 … 8, where a caller wants the matrix and not the
/// spinor: `Bivector::exp_skew_matrix` against nalgebra's fixed-size `exp` of the same
/// skew matrix (the setup asserts they agree).
fn bench_rotation_matrix_exp(c: &mut Criterion) {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    macro_rules! group {
        ($($d:literal),*) => {$({
            let b = random_bivector(&mut rng, $d);
            let m: SMatrix<f64, $d, $d> = b.to_skew_smatrix::<$d>();
            let ours = b.exp_skew_matrix();
            let theirs = m.exp();
            assert!((0..$d * $d).all(|k| (ours.as_slice()[k] - theirs.as_slice()[k]).abs() < 1e-13));
            let mut g = c.benchmark_group(format!("rotation_matrix_exp/N={}", $d));
            g.bench_function("rotorflow_exp_skew_matrix", |bench| {
                bench.iter(|| black_box(&b).exp_skew_matrix())
            });
            g.bench_function("nalgebra_smatrix_expm", |bench| {
                bench.iter(|| black_box(&m).exp())
            });
            g.finish();
        })*};
    }
    group!(5, 6, 7, 8);
}

fn bench_log(c: &mut Criterion) {
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    for n in DIMS {
        let mut g = c.benchmark_group(format!("log/N={n}"));
        let r = Rotor::from_rotation_bivector(&random_bivector(&mut rng, n));
        g.bench_function(BenchmarkId::new("rotorflow_log", n), |bench| {
            bench.iter(|| black_box(&r).log())
        });
        g.finish();
    }
}

fn commutator_smatrix<const D: usize>(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    a: &Bivector,
    b: &Bivector,
) {
    let (ma, mb) = (a.to_skew_smatrix::<D>(), b.to_skew_smatrix::<D>());
    g.bench_function(
        BenchmarkId::new("nalgebra_smatrix_ab_minus_ba", D),
        |bench| {
            bench.iter(|| {
                let (x, y) = (black_box(&ma), black_box(&mb));
                x * y - y * x
            })
        },
    );
}

fn bench_commutator(c: &mut Criterion) {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for n in DIMS {
        let mut g = c.benchmark_group(format!("commutator/N={n}"));
        let a = random_bivector(&mut rng, n);
        let b = random_bivector(&mut rng, n);
        g.bench_function(BenchmarkId::new("rotorflow_commutator", n), |bench| {
            bench.iter(|| black_box(&a).commutator(black_box(&b)))
        });
        let (ma, mb) = (a.to_skew_matrix(), b.to_skew_matrix());
        g.bench_function(
            BenchmarkId::new("nalgebra_dmatrix_ab_minus_ba", n),
            |bench| {
                bench.iter(|| {
                    let (x, y) = (black_box(&ma), black_box(&mb));
                    x * y - y * x
                })
            },
        );
        for_fixed_dim!(n, commutator_smatrix, &mut g, &a, &b);
        g.finish();
    }
}

fn sandwich_smatrix<const D: usize>(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    q: &DMatrix<f64>,
    x: &Vector,
) {
    let qs: SMatrix<f64, D, D> = SMatrix::from_fn(|i, j| q[(i, j)]);
    let xs: SVector<f64, D> = SVector::from_fn(|i, _| x[i]);
    g.bench_function(BenchmarkId::new("nalgebra_smatrix_matvec", D), |bench| {
        bench.iter(|| black_box(&qs) * black_box(&xs))
    });
}

fn bench_sandwich(c: &mut Criterion) {
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    for n in DIMS {
        let mut g = c.benchmark_group(format!("sandwich_vector/N={n}"));
        let r = Rotor::from_rotation_bivector(&random_bivector(&mut rng, n));
        let x = random_vector(&mut rng, n);
        g.bench_function(BenchmarkId::new("rotorflow_rotate_vector", n), |bench| {
            bench.iter(|| black_box(&r).rotate_vector(black_box(&x)))
        });
        let q = r.to_matrix();
        let xv = DVector::from_column_slice(x.as_slice());
        g.bench_function(BenchmarkId::new("nalgebra_dmatrix_matvec", n), |bench| {
            bench.iter(|| black_box(&q) * black_box(&xv))
        });
        for_fixed_dim!(n, sandwich_smatrix, &mut g, &q, &x);
        g.finish();
    }
}

fn bench_to_matrix(c: &mut Criterion) {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for n in DIMS {
        let mut g = c.benchmark_group(format!("rotor_to_matrix/N={n}"));
        let r = Rotor::from_rotation_bivector(&random_bivector(&mut rng, n));
        g.bench_function(BenchmarkId::new("rotorflow_to_matrix", n), |bench| {
            bench.iter(|| black_box(&r).to_matrix())
        });
        let q = r.to_matrix();
        g.bench_function(BenchmarkId::new("rotorflow_from_matrix", n), |bench| {
            bench.iter(|| Rotor::from_matrix(black_box(&q)).unwrap())
        });
        g.finish();
    }
}

fn compose_smatrix<const D: usize>(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    qa: &DMatrix<f64>,
    qb: &DMatrix<f64>,
) {
    let a: SMatrix<f64, D, D> = SMatrix::from_fn(|i, j| qa[(i, j)]);
    let b: SMatrix<f64, D, D> = SMatrix::from_fn(|i, j| qb[(i, j)]);
    g.bench_function(BenchmarkId::new("nalgebra_smatrix_matmul", D), |bench| {
        bench.iter(|| black_box(&a) * black_box(&b))
    });
}

fn bench_geometric_product(c: &mut Criterion) {
    let mut rng = ChaCha8Rng::seed_from_u64(6);
    for n in DIMS {
        let mut g = c.benchmark_group(format!("geometric_product/N={n}"));
        let ra = Rotor::from_rotation_bivector(&random_bivector(&mut rng, n));
        let rb = Rotor::from_rotation_bivector(&random_bivector(&mut rng, n));
        g.bench_function(BenchmarkId::new("rotorflow_rotor_compose", n), |bench| {
            bench.iter(|| black_box(&ra).compose(black_box(&rb)))
        });
        let (ma, mb) = (ra.to_multivector(), rb.to_multivector());
        g.bench_function(BenchmarkId::new("rotorflow_multivector_even", n), |bench| {
            bench.iter(|| black_box(&ma).geometric(black_box(&mb)))
        });
        let (qa, qb) = (ra.to_matrix(), rb.to_matrix());
        g.bench_function(BenchmarkId::new("nalgebra_dmatrix_matmul", n), |bench| {
            bench.iter(|| black_box(&qa) * black_box(&qb))
        });
        for_fixed_dim!(n, compose_smatrix, &mut g, &qa, &qb);
        // The composition of attitudes, which are rotation matrices above N = 4: what a caller
        // who does not need the spinor pays.
        let (aa, ab) = (Attitude::from(&ra), Attitude::from(&rb));
        g.bench_function(BenchmarkId::new("rotorflow_attitude_compose", n), |bench| {
            bench.iter(|| black_box(&aa).compose(black_box(&ab)))
        });
        g.finish();
    }
}

fn benches(c: &mut Criterion) {
    let _ = c;
    let mut c = configure();
    bench_exp(&mut c);
    bench_rotation_matrix_exp(&mut c);
    bench_log(&mut c);
    bench_commutator(&mut c);
    bench_sandwich(&mut c);
    bench_to_matrix(&mut c);
    bench_geometric_product(&mut c);
}

criterion_group!(algebra, benches);
criterion_main!(algebra);
