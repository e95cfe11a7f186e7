//! Criterion benches of one integrator step (with attitude), per N, beside
//! (a) a hand-written fixed-size RK4 for N = 3 and 4, the speed limit, and (b) the same RK4 on
//! nalgebra matrices (SMatrix for N ≤ 8, DMatrix for all): L as a skew matrix, the attitude
//! as a rotation matrix; and the two adaptive Dormand–Prince integrators (and Dop853's
//! fixed-size twin, `FreeBody4::advance_dop853`) carrying the 4D cuboid to t = 10 at the
//! tolerances that give both |Δω| ≈ 1e-11 at t = 100; and RK4 beside
//! the Casimir-preserving Lie–Poisson RK4 carrying the same cuboid to t = 100 at the step
//! counts that give each |Δω| ≤ 1e-8 there. `BENCH_QUICK=1` shortens the run.

use criterion::{BenchmarkId, Criterion, black_box, criterion_group, criterion_main};
use nalgebra::{DMatrix, SMatrix};
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::{
    Attitude, Dop853, Dopri5, FreeBody4, Integrator, LiePoissonRk4, Midpoint, RigidBody, Rkmk4,
    Splitting,
};
use rotorflow::prelude::*;

#[path = "common/dmatrix_rk4.rs"]
mod dmatrix_baseline;
use dmatrix_baseline::dmatrix_rk4;

#[path = "common/configure.rs"]
mod configure;
use configure::configure;

fn moments(n: usize) -> Vec<f64> {
    (0..n).map(|k| 0.5 + 0.25 * k as f64).collect()
}

fn body(n: usize) -> RigidBody {
    let l: Vec<f64> = (0..n * (n - 1) / 2)
        .map(|k| (0.7 * k as f64 + 0.3).sin())
        .collect();
    RigidBody::from_body_momentum(
        InertiaMap::from_principal_second_moments(&moments(n)).unwrap(),
        Attitude::identity(n),
        &Bivector::from_components(n, &l).unwrap(),
    )
    .unwrap()
}

/// The same with fixed-size nalgebra matrices.
fn smatrix_rk4<const D: usize>(
    m: &mut SMatrix<f64, D, D>,
    q: &mut SMatrix<f64, D, D>,
    inv: &SMatrix<f64, D, D>,
    h: f64,
) {
    let f = |m: &SMatrix<f64, D, D>, q: &SMatrix<f64, D, D>| {
        let w = m.component_mul(inv);
        (w * m - m * w, q * w.transpose())
    };
    let (k1m, k1q) = f(m, q);
    let (k2m, k2q) = f(&(*m + k1m * (0.5 * h)), &(*q + k1q * (0.5 * h)));
    let (k3m, k3q) = f(&(*m + k2m * (0.5 * h)), &(*q + k2q * (0.5 * h)));
    let (k4m, k4q) = f(&(*m + k3m * h), &(*q + k3q * h));
    *m += (k1m + k2m * 2.0 + k3m * 2.0 + k4m) * (h / 6.0);
    *q += (k1q + k2q * 2.0 + k3q * 2.0 + k4q) * (h / 6.0);
}

/// Hand-written RK4 on plain arrays for fixed N: the speed limit of an RK4 step with a
/// matrix attitude (no library, no allocation, fully unrolled by the compiler).
fn hand_rk4<const D: usize>(
    m: &mut [[f64; D]; D],
    q: &mut [[f64; D]; D],
    inv: &[[f64; D]; D],
    h: f64,
) {
    type Mat<const D: usize> = [[f64; D]; D];
    fn f<const D: usize>(m: &Mat<D>, q: &Mat<D>, inv: &Mat<D>) -> (Mat<D>, Mat<D>) {
        let mut w = [[0.0; D]; D];
        for i in 0..D {
            for j in 0..D {
                w[i][j] = m[i][j] * inv[i][j];
            }
        }
        let mut dm = [[0.0; D]; D];
        let mut dq = [[0.0; D]; D];
        for i in 0..D {
            for j in 0..D {
                let mut s = 0.0;
                let mut t = 0.0;
                for k in 0..D {
                    s += w[i][k] * m[k][j] - m[i][k] * w[k][j];
                    t += q[i][k] * w[j][k];
                }
                dm[i][j] = s;
                dq[i][j] = t;
            }
        }
        (dm, dq)
    }
    fn axpy<const D: usize>(a: &Mat<D>, b: &Mat<D>, s: f64) -> Mat<D> {
        let mut o = *a;
        for i in 0..D {
            for j in 0..D {
                o[i][j] += s * b[i][j];
            }
        }
        o
    }
    let (k1m, k1q) = f(m, q, inv);
    let (k2m, k2q) = f(&axpy(m, &k1m, 0.5 * h), &axpy(q, &k1q, 0.5 * h), inv);
    let (k3m, k3q) = f(&axpy(m, &k2m, 0.5 * h), &axpy(q, &k2q, 0.5 * h), inv);
    let (k4m, k4q) = f(&axpy(m, &k3m, h), &axpy(q, &k3q, h), inv);
    for i in 0..D {
        for j in 0..D {
            m[i][j] += h / 6.0 * (k1m[i][j] + 2.0 * k2m[i][j] + 2.0 * k3m[i][j] + k4m[i][j]);
            q[i][j] += h / 6.0 * (k1q[i][j] + 2.0 * k2q[i][j] + 2.0 * k3q[i][j] + k4q[i][j]);
        }
    }
}

fn inverse_plane_moments(n: usize) -> DMatrix<f64> {
    dmatrix_baseline::inverse_plane_moments(&moments(n))
}

fn bench_steps(c: &mut Criterion) {
    let h = 0.01;
    for n in [3usize, 4, 5, 8, 16, 32] {
        let mut g = c.benchmark_group(format!("step/N={n}"));
        let start = body(n);
        let mut integrators: Vec<Box<dyn Integrator>> = vec![
            Box::new(Rkmk4),
            Box::new(Splitting::strang()),
            Box::new(Splitting::yoshida4()),
            Box::new(Midpoint::default()),
            Box::new(Dopri5::new(1e-8, 1e-8)),
            Box::new(Dop853::new(1e-8, 1e-8).unwrap()),
        ];
        for integ in integrators.iter_mut() {
            let mut b = start.clone();
            g.bench_function(
                BenchmarkId::new(format!("rotorflow_{}", integ.name()), n),
                |bench| bench.iter(|| integ.step(black_box(&mut b), 0.0, h, &Free).unwrap()),
            );
        }
        let inv = inverse_plane_moments(n);
        let mut m = start.momentum().to_skew_matrix();
        let mut q = DMatrix::<f64>::identity(n, n);
        g.bench_function(BenchmarkId::new("nalgebra_dmatrix_rk4", n), |bench| {
            bench.iter(|| dmatrix_rk4(black_box(&mut m), black_box(&mut q), &inv, h))
        });
        macro_rules! fixed {
            ($d:literal) => {{
                let sinv: SMatrix<f64, $d, $d> = SMatrix::from_fn(|a, b| inv[(a, b)]);
                let mut sm: SMatrix<f64, $d, $d> = SMatrix::from_fn(|a, b| m[(a, b)]);
                let mut sq = SMatrix::<f64, $d, $d>::identity();
                g.bench_function(BenchmarkId::new("nalgebra_smatrix_rk4", $d), |bench| {
                    bench.iter(|| smatrix_rk4(black_box(&mut sm), black_box(&mut sq), &sinv, h))
                });
            }};
        }
        macro_rules! hand {
            ($d:literal) => {{
                let ainv: [[f64; $d]; $d] =
                    std::array::from_fn(|a| std::array::from_fn(|b| inv[(a, b)]));
                let mut am: [[f64; $d]; $d] =
                    std::array::from_fn(|a| std::array::from_fn(|b| m[(a, b)]));
                let mut aq: [[f64; $d]; $d] = std::array::from_fn(|a| {
                    std::array::from_fn(|b| if a == b { 1.0 } else { 0.0 })
                });
                g.bench_function(BenchmarkId::new("hand_written_rk4", $d), |bench| {
                    bench.iter(|| hand_rk4::<$d>(black_box(&mut am), black_box(&mut aq), &ainv, h))
                });
            }};
        }
        match n {
            3 => {
                fixed!(3);
                hand!(3);
            }
            4 => {
                fixed!(4);
                hand!(4);
            }
            5 => fixed!(5),
            8 => fixed!(8),
            _ => {}
        }
        g.finish();
    }
}

/// Same work for both: the 4D cuboid `cuboid:1,1.3,1.7,2.2` (mass 1) from ω(0) =
/// (0.3, −0.2, 0.5, 0.1, 0.4, −0.6) to t = 10, each at the tolerance that reaches
/// |Δω| ≤ 1e-11 at t = 100 (tests/dynamics/dop853.rs).
fn bench_tight_tolerance(c: &mut Criterion) {
    let parsed = rotorflow::inertia::spec::parse_body("cuboid:1,1.3,1.7,2.2+mass=1").unwrap();
    let omega = Bivector::from_components(4, &[0.3, -0.2, 0.5, 0.1, 0.4, -0.6]).unwrap();
    let start =
        RigidBody::from_body_velocity(parsed.inertia, Attitude::identity(4), &omega).unwrap();
    let mut g = c.benchmark_group("cuboid4_to_t10");
    let mut integrators: Vec<(&str, Box<dyn Integrator>)> = vec![
        (
            "rotorflow_dopri5_rtol1e-13",
            Box::new(Dopri5::new(1e-13, 1e-15)),
        ),
        (
            "rotorflow_dop853_rtol1e-12",
            Box::new(Dop853::new(1e-12, 1e-14).unwrap()),
        ),
    ];
    for (name, integ) in integrators.iter_mut() {
        g.bench_function(*name, |bench| {
            bench.iter(|| {
                let mut b = start.clone();
                integ.step(black_box(&mut b), 0.0, 10.0, &Free).unwrap();
                b
            })
        });
    }
    // The same steps as Dop853 at rtol 1e-12, on the fixed-size body.
    let fixed = FreeBody4::from_rigid_body(&start).unwrap();
    g.bench_function("rotorflow_fixed_dop853_rtol1e-12", |bench| {
        bench.iter(|| {
            let mut b = black_box(fixed);
            b.advance_dop853(10.0, 1e-12, 1e-14).unwrap();
            b
        })
    });
    g.finish();
}

/// RK4 and the Lie–Poisson RK4 on the 4D cuboid (as above) to t = 100, each with the fewest
/// equal steps (to 1%) that give |Δω| ≤ 1e-8 at t = 100 against Dop853 at rtol 1e-15: the
/// counts of the book's cost table (`examples/book_long_runs.rs`), which
/// `the_book_step_counts_for_1e_8_on_p4_hold` in tests/dynamics/lie_poisson.rs checks.
fn bench_casimir_preserving(c: &mut Criterion) {
    let parsed = rotorflow::inertia::spec::parse_body("cuboid:1,1.3,1.7,2.2+mass=1").unwrap();
    let omega = Bivector::from_components(4, &[0.3, -0.2, 0.5, 0.1, 0.4, -0.6]).unwrap();
    let start =
        RigidBody::from_body_velocity(parsed.inertia, Attitude::identity(4), &omega).unwrap();
    let mut g = c.benchmark_group("cuboid4_to_t100_at_1e-8");
    let mut integrators: Vec<(&str, Box<dyn Integrator>, usize)> = vec![
        ("rotorflow_rk4_2750_steps", Box::new(Rkmk4), 2750),
        (
            "rotorflow_lie_poisson_rk4_3788_steps",
            Box::new(LiePoissonRk4),
            3788,
        ),
    ];
    for (name, integ, steps) in integrators.iter_mut() {
        let h = 100.0 / *steps as f64;
        g.bench_function(*name, |bench| {
            bench.iter(|| {
                let mut b = start.clone();
                for k in 0..*steps {
                    integ
                        .step(black_box(&mut b), k as f64 * h, h, &Free)
                        .unwrap();
                }
                b
            })
        });
    }
    g.finish();
}

fn benches(_: &mut Criterion) {
    let mut c = configure();
    bench_steps(&mut c);
    bench_tight_tolerance(&mut c);
    bench_casimir_preserving(&mut c);
}

criterion_group!(dynamics, benches);
criterion_main!(dynamics);
