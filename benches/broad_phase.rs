//! Criterion benches of body–body collision detection (`rotorflow::dynamics::motion::detect`).
//! `BENCH_QUICK=1` shortens the run.
//!
//! - `broad_phase_4d`: 10³, 10⁴ and 10⁵ random 4D boxes at constant density (about 2.4
//!   overlapping neighbours per body), half-sizes in [0.25, 0.5]. `incremental_update` is one
//!   [`BroadPhase::update`] after every body moved by its own constant step, up to 0.005
//!   per axis (1 % of a box's size), 40 updates one way and 40 back, so that bodies leave
//!   their fat boxes and the hierarchy is refitted and rebuilt as in a simulation while the
//!   scene keeps its density (the step is timed with the update; each sample times whole
//!   swings and reports the mean update, since an update's cost depends on its phase);
//!   `full_rebuild` is the same update on a fresh broad phase (the hierarchy built and every
//!   body queried in it), what a non-incremental broad phase pays every step;
//!   `brute_force` tests all n(n − 1)/2 pairs (10³ and 10⁴ only). After the group the bench
//!   prints the growth exponent of the incremental update (the least-squares slope of
//!   log time against log n, from Criterion's medians) and the rebuild/incremental ratios.
//! - `box_box_sat`: [`box_box`] on two overlapping boxes in a random pose, N = 3 and N = 4
//!   (15 and 56 axes); in 3D against `classic_3d`, a fixed-size 15-axis test written for
//!   3D alone (cross products of the edge directions), the usual game-engine form.
//! - `box_manifold_4d`: [`box_manifold`] of two 4D boxes face to face, the upper turned
//!   about the normal and shifted (a 3D contact region clipped from two 3D cubes, reduced
//!   to 8 points); `region_only` enumerates the region's vertices without reducing them.
//! - `hull_manifold`: [`hull_manifold`] of two unit cubes given as hulls of their corners,
//!   the upper resting face to face on the lower and shifted by half its side (a cube of a
//!   pyramid on one below), in 3D (`N=3`, 4 + 4 support points) and 4D (`N=4`, 8 + 8); and
//!   of two 6D hexagonal prisms face to face (`prisms/N=6`, 48 + 48: the region's extremes
//!   by linear programs).

use criterion::{BenchmarkId, Criterion, black_box, criterion_group, criterion_main};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rotorflow::dynamics::motion::detect::{
    BroadPhase, PlacedBox, PlacedHull, box_box, box_contact_vertices, box_manifold, hull_manifold,
};
use std::time::Instant;

#[path = "common/configure.rs"]
mod configure;
use configure::configure;

const SIZES: [usize; 3] = [1_000, 10_000, 100_000];

/// The updates of `incremental_update` in each direction of the bodies' back-and-forth
/// motion: 40 steps of up to 0.005 per axis carry a body 0.2 away, past its fat box's
/// margin (a fifth of the mean half-width, 0.075 here).
const SWING: usize = 40;

/// A 4D scene at constant density, and a second state moved by a small step.
fn scene(bodies: usize) -> [(Vec<f64>, Vec<f64>); 2] {
    let n = 4;
    let mut r = ChaCha8Rng::seed_from_u64(bodies as u64);
    let side = 1.2 * (bodies as f64).powf(0.25);
    let mut lower = Vec::with_capacity(bodies * n);
    let mut upper = Vec::with_capacity(bodies * n);
    for _ in 0..bodies {
        for _ in 0..n {
            let c = r.gen_range(0.0..side);
            let h = r.gen_range(0.25..0.5);
            lower.push(c - h);
            upper.push(c + h);
        }
    }
    let (mut lower2, mut upper2) = (lower.clone(), upper.clone());
    for k in 0..bodies * n {
        let dx = r.gen_range(-0.005..0.005);
        lower2[k] += dx;
        upper2[k] += dx;
    }
    [(lower, upper), (lower2, upper2)]
}

fn brute_force(n: usize, lower: &[f64], upper: &[f64], out: &mut Vec<(usize, usize)>) {
    out.clear();
    let bodies = lower.len() / n;
    for i in 0..bodies {
        for j in i + 1..bodies {
            if (0..n).all(|a| {
                lower[i * n + a] <= upper[j * n + a] && lower[j * n + a] <= upper[i * n + a]
            }) {
                out.push((i, j));
            }
        }
    }
}

/// Criterion's median for a bench, in ns, if it has run.
fn median_ns(group: &str, name: &str, size: usize) -> Option<f64> {
    let root = std::env::var("CARGO_TARGET_DIR").unwrap_or_else(|_| "target".into());
    let path = format!("{root}/criterion/{group}/{name}/{size}/new/estimates.json");
    let text = std::fs::read_to_string(path).ok()?;
    let json: serde_json::Value = serde_json::from_str(&text).ok()?;
    json["median"]["point_estimate"].as_f64()
}

fn bench_broad_phase(c: &mut Criterion) {
    let group_name = "broad_phase_4d";
    let mut g = c.benchmark_group(group_name);
    for &bodies in &SIZES {
        let states = scene(bodies);
        let mut broad = BroadPhase::new(4).unwrap();
        let pairs = broad.update(&states[0].0, &states[0].1).unwrap().len();
        broad.update(&states[1].0, &states[1].1).unwrap();
        println!(
            "{bodies} bodies: {pairs} overlapping pairs, {} bodies out of their fat boxes per update",
            broad.last_moved()
        );
        // Constant speeds, the difference of the two states per step, back and forth over
        // `SWING` updates each way: the bodies leave their fat boxes as in a simulation, and
        // the scene keeps its density however many updates Criterion times (a drift one way
        // would spread the small scenes, timed over thousands of updates, far apart, and
        // the growth with n would compare a sparse scene with a dense one).
        let velocity: Vec<f64> = states[1]
            .0
            .iter()
            .zip(&states[0].0)
            .map(|(b, a)| b - a)
            .collect();
        let (mut lower, mut upper) = states[1].clone();
        let mut updates = 0usize;
        if bodies >= 100_000 {
            // A sample of 10⁵ bodies is two seconds of whole swings: Criterion's fewest.
            g.sample_size(10);
        }
        g.bench_with_input(
            BenchmarkId::new("incremental_update", bodies),
            &bodies,
            |bench, _| {
                // The cost of an update depends on where it falls in the swing (how many
                // bodies leave their fat boxes, whether the hierarchy is rebuilt), so that
                // every sample takes whole swings there and back, at least `iters` updates,
                // and reports their mean: a sample of a few updates (10⁵ bodies) would
                // otherwise time whichever phase it met.
                bench.iter_custom(|iters| {
                    let cycle = 2 * SWING;
                    let count = (iters as usize).div_ceil(cycle) * cycle;
                    let start = Instant::now();
                    for _ in 0..count {
                        let way = if (updates / SWING).is_multiple_of(2) {
                            1.0
                        } else {
                            -1.0
                        };
                        updates += 1;
                        for ((lo, hi), v) in lower.iter_mut().zip(upper.iter_mut()).zip(&velocity) {
                            *lo += way * v;
                            *hi += way * v;
                        }
                        black_box(broad.update(&lower, &upper).unwrap().len());
                    }
                    start.elapsed().mul_f64(iters as f64 / count as f64)
                })
            },
        );
        println!(
            "{bodies} bodies after the timing: {} out of their fat boxes at the last update",
            broad.last_moved()
        );
        g.bench_with_input(
            BenchmarkId::new("full_rebuild", bodies),
            &bodies,
            |bench, _| {
                bench.iter(|| {
                    let mut fresh = BroadPhase::new(4).unwrap();
                    black_box(fresh.update(&states[1].0, &states[1].1).unwrap().len())
                })
            },
        );
        if bodies <= 10_000 {
            let mut out = Vec::new();
            g.bench_with_input(
                BenchmarkId::new("brute_force", bodies),
                &bodies,
                |bench, _| {
                    bench.iter(|| {
                        brute_force(4, &states[1].0, &states[1].1, &mut out);
                        black_box(out.len())
                    })
                },
            );
        }
    }
    g.finish();
    // The growth exponent and the ratios, from the medians just measured.
    let times: Vec<(f64, f64)> = SIZES
        .iter()
        .filter_map(|&s| {
            median_ns(group_name, "incremental_update", s).map(|t| ((s as f64).ln(), t.ln()))
        })
        .collect();
    if times.len() == SIZES.len() {
        let k = times.len() as f64;
        let (mx, my) = times
            .iter()
            .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / k, b + y / k));
        let num: f64 = times.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
        let den: f64 = times.iter().map(|(x, _)| (x - mx) * (x - mx)).sum();
        println!(
            "broad_phase_4d: growth exponent of incremental_update = {:.3}",
            num / den
        );
    }
    for &s in &SIZES {
        if let (Some(inc), Some(full)) = (
            median_ns(group_name, "incremental_update", s),
            median_ns(group_name, "full_rebuild", s),
        ) {
            let brute = median_ns(group_name, "brute_force", s)
                .map(|b| format!(", brute force / incremental = {:.1}", b / inc))
                .unwrap_or_default();
            println!(
                "broad_phase_4d/{s}: incremental {:.1} µs, full rebuild / incremental = {:.2}{brute}",
                inc / 1e3,
                full / inc
            );
        }
    }
}

/// A random rotation, row-major (Gram–Schmidt of a random matrix).
fn rotation(r: &mut impl Rng, n: usize) -> Vec<f64> {
    let mut q: Vec<f64> = (0..n * n).map(|_| r.gen_range(-1.0..1.0)).collect();
    for j in 0..n {
        for _ in 0..2 {
            for k in 0..j {
                let p: f64 = (0..n).map(|i| q[i * n + j] * q[i * n + k]).sum();
                for i in 0..n {
                    q[i * n + j] -= p * q[i * n + k];
                }
            }
        }
        let l: f64 = (0..n)
            .map(|i| q[i * n + j] * q[i * n + j])
            .sum::<f64>()
            .sqrt();
        for i in 0..n {
            q[i * n + j] /= l;
        }
    }
    q
}

/// The classic 3D box–box test: 3 + 3 face axes and the 9 cross products of the edge
/// directions, least overlap with the same face preference as the library's.
fn classic_3d(
    ha: &[f64; 3],
    ca: &[f64; 3],
    qa: &[f64; 9],
    hb: &[f64; 3],
    cb: &[f64; 3],
    qb: &[f64; 9],
) -> (f64, [f64; 3]) {
    let col = |q: &[f64; 9], j: usize| [q[j], q[3 + j], q[6 + j]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let d = [cb[0] - ca[0], cb[1] - ca[1], cb[2] - ca[2]];
    let (aa, bb) = (
        [col(qa, 0), col(qa, 1), col(qa, 2)],
        [col(qb, 0), col(qb, 1), col(qb, 2)],
    );
    let overlap = |u: [f64; 3]| {
        let ra: f64 = (0..3).map(|i| ha[i] * dot(aa[i], u).abs()).sum();
        let rb: f64 = (0..3).map(|i| hb[i] * dot(bb[i], u).abs()).sum();
        ra + rb - dot(d, u).abs()
    };
    let mut best = (f64::INFINITY, [0.0; 3]);
    for u in aa.iter().chain(&bb) {
        let o = overlap(*u);
        if o < best.0 {
            best = (o, *u);
        }
    }
    let face = best.0;
    for x in &aa {
        for y in &bb {
            let u = [
                x[1] * y[2] - x[2] * y[1],
                x[2] * y[0] - x[0] * y[2],
                x[0] * y[1] - x[1] * y[0],
            ];
            let l = dot(u, u).sqrt();
            if l < 1e-6 {
                continue;
            }
            let u = [u[0] / l, u[1] / l, u[2] / l];
            let o = overlap(u);
            if o < 0.95 * face - 1e-3 && o < best.0 {
                best = (o, u);
            }
        }
    }
    best
}

fn bench_sat(c: &mut Criterion) {
    let mut g = c.benchmark_group("box_box_sat");
    let mut r = ChaCha8Rng::seed_from_u64(3);
    for n in [3usize, 4] {
        let (ha, hb): (Vec<f64>, Vec<f64>) = (
            (0..n).map(|_| r.gen_range(0.5..1.0)).collect(),
            (0..n).map(|_| r.gen_range(0.5..1.0)).collect(),
        );
        let (qa, qb) = (rotation(&mut r, n), rotation(&mut r, n));
        let ca = vec![0.0; n];
        let cb: Vec<f64> = (0..n).map(|_| r.gen_range(0.3..0.6)).collect();
        let a = PlacedBox {
            half_lengths: &ha,
            position: &ca,
            rotation: &qa,
        };
        let b = PlacedBox {
            half_lengths: &hb,
            position: &cb,
            rotation: &qb,
        };
        assert!(box_box(&a, &b).unwrap().depth > 0.0);
        g.bench_function(BenchmarkId::new("rotorflow", format!("N={n}")), |bench| {
            bench.iter(|| black_box(box_box(black_box(&a), black_box(&b)).unwrap().depth))
        });
        if n == 3 {
            let arr = |v: &[f64]| -> [f64; 3] { [v[0], v[1], v[2]] };
            let m9 = |v: &[f64]| -> [f64; 9] { std::array::from_fn(|k| v[k]) };
            let (ha3, ca3, qa3, hb3, cb3, qb3) =
                (arr(&ha), arr(&ca), m9(&qa), arr(&hb), arr(&cb), m9(&qb));
            let ours = box_box(&a, &b).unwrap().depth;
            let theirs = classic_3d(&ha3, &ca3, &qa3, &hb3, &cb3, &qb3).0;
            assert!((ours - theirs).abs() < 1e-12, "{ours} vs {theirs}");
            g.bench_function(BenchmarkId::new("classic_3d", "N=3"), |bench| {
                bench
                    .iter(|| black_box(classic_3d(black_box(&ha3), &ca3, &qa3, &hb3, &cb3, &qb3).0))
            });
        }
    }
    g.finish();
}

fn bench_manifold(c: &mut Criterion) {
    let mut g = c.benchmark_group("box_manifold_4d");
    let n = 4;
    let ha = vec![1.0, 0.9, 1.1, 0.5];
    let hb = vec![0.6, 0.7, 0.5, 0.4];
    let ca = vec![0.0; n];
    let qa: Vec<f64> = (0..16)
        .map(|k| if k / 4 == k % 4 { 1.0 } else { 0.0 })
        .collect();
    // B turned by 0.4 in the x₁x₂ plane and 0.3 in x₂x₃ (about the normal x₄), shifted.
    let (s1, c1) = 0.4f64.sin_cos();
    let (s2, c2) = 0.3f64.sin_cos();
    let qb = vec![
        c1,
        -s1 * c2,
        s1 * s2,
        0.0,
        s1,
        c1 * c2,
        -c1 * s2,
        0.0,
        0.0,
        s2,
        c2,
        0.0,
        0.0,
        0.0,
        0.0,
        1.0,
    ];
    let cb = vec![0.5, -0.3, 0.6, 0.5 + 0.4 - 0.01];
    let a = PlacedBox {
        half_lengths: &ha,
        position: &ca,
        rotation: &qa,
    };
    let b = PlacedBox {
        half_lengths: &hb,
        position: &cb,
        rotation: &qb,
    };
    let m = box_manifold(&a, &b, 0.0).unwrap().unwrap();
    let mut region = 0;
    box_contact_vertices(&a, &b, 0.0, |_| region += 1).unwrap();
    println!(
        "box_manifold_4d: {region} region vertices, {} kept",
        m.len()
    );
    g.bench_function("box_manifold", |bench| {
        bench.iter(|| {
            black_box(
                box_manifold(black_box(&a), black_box(&b), 0.0)
                    .unwrap()
                    .map(|m| m.len()),
            )
        })
    });
    g.bench_function("region_only", |bench| {
        bench.iter(|| {
            let mut count = 0;
            box_contact_vertices(black_box(&a), black_box(&b), 0.0, |_| count += 1).unwrap();
            black_box(count)
        })
    });
    g.finish();
}

fn bench_hull_manifold(c: &mut Criterion) {
    let mut g = c.benchmark_group("hull_manifold");
    for n in [3usize, 4] {
        let corners: Vec<f64> = (0..1usize << n)
            .flat_map(|m| (0..n).map(move |i| if m >> i & 1 == 1 { 0.5 } else { -0.5 }))
            .collect();
        let identity: Vec<f64> = (0..n * n)
            .map(|k| if k / n == k % n { 1.0 } else { 0.0 })
            .collect();
        let lower = vec![0.0; n];
        let mut upper = vec![0.0; n];
        upper[0] = 0.5;
        upper[n - 1] = 1.0;
        let a = PlacedHull {
            vertices: &corners,
            position: &lower,
            rotation: &identity,
        };
        let b = PlacedHull {
            vertices: &corners,
            position: &upper,
            rotation: &identity,
        };
        let mut normal = vec![0.0; n];
        normal[n - 1] = 1.0;
        let m = hull_manifold(&a, &b, &normal, 1e-3).unwrap().unwrap();
        assert_eq!(m.len(), 1 << (n - 1));
        g.bench_function(format!("N={n}"), |bench| {
            bench.iter(|| {
                black_box(
                    hull_manifold(black_box(&a), black_box(&b), &normal, 1e-3)
                        .unwrap()
                        .map(|m| m.len()),
                )
            })
        });
    }
    // Hexagonal prisms (a hexagon of radius 1/2 times a cube of side 1) face to face in 6D,
    // the upper shifted by 5 % along the hexagon's axis: faces of 48 vertices, held by the
    // linear programs of the region's extremes.
    let n = 6;
    let mut prism = Vec::new();
    for k in 0..6 {
        let angle = std::f64::consts::PI / 3.0 * k as f64;
        for m in 0..1usize << (n - 2) {
            prism.extend([0.5 * angle.cos(), 0.5 * angle.sin()]);
            prism.extend((0..n - 2).map(|i| if m >> i & 1 == 1 { 0.5 } else { -0.5 }));
        }
    }
    let identity: Vec<f64> = (0..n * n)
        .map(|k| if k / n == k % n { 1.0 } else { 0.0 })
        .collect();
    let lower = vec![0.0; n];
    let mut upper = vec![0.0; n];
    (upper[0], upper[n - 1]) = (0.05, 1.0);
    let a = PlacedHull {
        vertices: &prism,
        position: &lower,
        rotation: &identity,
    };
    let b = PlacedHull {
        vertices: &prism,
        position: &upper,
        rotation: &identity,
    };
    let mut normal = vec![0.0; n];
    normal[n - 1] = 1.0;
    let m = hull_manifold(&a, &b, &normal, 1e-3).unwrap().unwrap();
    assert_eq!(m.len(), 16);
    g.bench_function("prisms/N=6", |bench| {
        bench.iter(|| {
            black_box(
                hull_manifold(black_box(&a), black_box(&b), &normal, 1e-3)
                    .unwrap()
                    .map(|m| m.len()),
            )
        })
    });
    g.finish();
}

criterion_group! {
    name = benches;
    config = configure();
    targets = bench_broad_phase, bench_sat, bench_manifold, bench_hull_manifold
}
criterion_main!(benches);
