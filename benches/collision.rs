//! Criterion benches of the narrow phase (`rotorflow::dynamics::motion::detect`).
//! `BENCH_QUICK=1` shortens the run.
//!
//! - `gjk_distance`: [`distance`] between two separated, turned shapes: 3D boxes, 4D
//!   boxes, 4D tesseracts given as hulls of their 16 corners, 4D balls, a 4D ball and box,
//!   4D capsules.
//!   For N = 3 and 4
//!   [`distance`] runs GJK on stack arrays, and two boxes (`box_box/N=3`, `box_box/N=4`)
//!   by bounded least squares, cold (nothing kept between queries), two balls by their
//!   centres (`balls/N=4`), a 4D ball and box by clamping the centre to the box
//!   (`ball_box/N=4`), two 4D capsules by their segments' nearest points
//!   (`capsules/N=4`); `general_*` is the
//!   same query by the dimension-generic GJK ([`distance_general`]), and after the group
//!   the bench prints the ratios general / fast from Criterion's medians.
//!   `box_box_mixed/N=3`, `box_box_mixed/N=4` time [`distance`] on 1,024 pairs of random
//!   boxes taken in turn (random half-lengths and rotations, about two thirds apart), the
//!   cost a simulation meets: from pair to pair the least-squares steps take other
//!   branches, where a single pair repeats the same ones.
//! - `box_overlap`: two overlapping turned boxes in 3D and 4D. `epa_penetration` is
//!   [`penetration_with`] (GJK, then EPA, with a kept workspace); `sat_depth` is the
//!   baseline, the penetration depth by the separating-axis test over the generalised
//!   axes on stack arrays (3D: 15 axes, 4D: 56), exact for boxes and nothing else.
//!   `gjk_intersects` is [`intersects`] on the same pair.
//! - `ellipsoid_depth`: [`penetration_with`] on 256 overlapping pairs of a random
//!   ellipsoid and a random turned box (`box/N=4`, `box/N=6`) or hull of N + 3 random
//!   points (`hull/N=4`, `hull/N=6`), taken in turn: EPA, Newton's method face by face from
//!   its normal and, where that is not shown the least, the feet of normals on every face's
//!   plane. The time is per query, the mean over the pairs.
//!
//! Each answer is read inside the `Result` the query returns ([`kept`]).

use criterion::{Criterion, black_box, criterion_group, criterion_main};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rotorflow::dynamics::motion::detect::{
    EpaWorkspace, Penetration, PlacedShape, Separation, distance, distance_general, intersects,
    penetration_with,
};
use rotorflow::dynamics::motion::shape::ConvexShape;

#[path = "common/configure.rs"]
mod configure;
use configure::configure;

/// A rotation of ℝᴺ (row-major): the product of plane rotations by fixed angles.
fn rotation(n: usize, seed: f64) -> Vec<f64> {
    let mut q: Vec<f64> = (0..n * n)
        .map(|k| if k % (n + 1) == 0 { 1.0 } else { 0.0 })
        .collect();
    for i in 0..n {
        for j in i + 1..n {
            let angle = seed * (1.0 + i as f64 + 2.0 * j as f64);
            let (s, c) = angle.sin_cos();
            for row in 0..n {
                let (x, y) = (q[row * n + i], q[row * n + j]);
                q[row * n + i] = c * x - s * y;
                q[row * n + j] = s * x + c * y;
            }
        }
    }
    q
}

fn corners(h: &[f64]) -> Vec<Vec<f64>> {
    let n = h.len();
    (0..1usize << n)
        .map(|m| {
            (0..n)
                .map(|i| if m >> i & 1 == 1 { h[i] } else { -h[i] })
                .collect()
        })
        .collect()
}

/// The separating-axis penetration depth of two boxes (half-lengths, centre, rotation
/// row-major own → space) in N = 3 or 4: the least overlap over the face normals and the
/// directions orthogonal to N − 1 axes taken from both boxes.
fn sat_depth<const N: usize>(
    ha: &[f64; N],
    pa: &[f64; N],
    qa: &[f64],
    hb: &[f64; N],
    pb: &[f64; N],
    qb: &[f64],
) -> f64 {
    let mut axes = [[0.0; N]; 8];
    for j in 0..N {
        for i in 0..N {
            axes[j][i] = qa[i * N + j];
            axes[N + j][i] = qb[i * N + j];
        }
    }
    let mut d = [0.0; N];
    for i in 0..N {
        d[i] = pb[i] - pa[i];
    }
    let mut best = f64::INFINITY;
    let mut test = |u: &[f64; N]| {
        let length = u.iter().map(|x| x * x).sum::<f64>().sqrt();
        if length < 1e-12 {
            return;
        }
        let dot = |a: &[f64; N], b: &[f64; N]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        let mut reach = 0.0;
        for k in 0..N {
            reach += ha[k] * dot(u, &axes[k]).abs() + hb[k] * dot(u, &axes[N + k]).abs();
        }
        let overlap = (reach - dot(u, &d).abs()) / length;
        if overlap < best {
            best = overlap;
        }
    };
    for axis in axes.iter().take(2 * N) {
        test(axis);
    }
    // The complement of N − 1 axes by cofactors (3D: the cross product).
    let complement = |v: &[[f64; N]]| -> [f64; N] {
        let mut u = [0.0; N];
        if N == 3 {
            let (a, b) = (&v[0], &v[1]);
            u[0] = a[1] * b[2] - a[2] * b[1];
            u[1] = a[2] * b[0] - a[0] * b[2];
            u[2] = a[0] * b[1] - a[1] * b[0];
        } else {
            for (col, x) in u.iter_mut().enumerate() {
                let mut m = [[0.0; 3]; 3];
                for (r, row) in v.iter().enumerate().take(3) {
                    let mut c = 0;
                    for (k, value) in row.iter().enumerate() {
                        if k != col {
                            m[r][c] = *value;
                            c += 1;
                        }
                    }
                }
                let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                    - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                    + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
                *x = if col % 2 == 0 { det } else { -det };
            }
        }
        u
    };
    let mut v = [[0.0; N]; 3];
    if N == 3 {
        for i in 0..3 {
            for j in 0..3 {
                v[0] = axes[i];
                v[1] = axes[3 + j];
                test(&complement(&v[..2]));
            }
        }
    } else {
        for i in 0..4 {
            for j in 0..4 {
                for k in j + 1..4 {
                    // One axis of A with two of B, and two of A with one of B.
                    v[0] = axes[i];
                    v[1] = axes[4 + j];
                    v[2] = axes[4 + k];
                    test(&complement(&v));
                    v[0] = axes[4 + i];
                    v[1] = axes[j];
                    v[2] = axes[k];
                    test(&complement(&v));
                }
            }
        }
    }
    best
}

/// The answer kept as a whole where the query left it, its distance or depth handed to
/// Criterion. Criterion's `black_box` on stable reads the value it is given byte by byte
/// through volatile loads, after a copy: for a 240-byte `Separation` that costs about a
/// fifth of a 3D box query, which no caller pays. `std::hint::black_box` on a reference
/// makes the compiler hold every field in memory without reading it back. The answer is
/// read inside its `Result`: moving it out first (`unwrap` into a value) adds a 240-byte
/// copy, a `memcpy` call of about a tenth of a 4D box query, that a caller who matches the
/// `Result` by reference does not make.
#[inline(always)]
fn kept<T: Answer, E: std::fmt::Debug>(answer: Result<T, E>) -> f64 {
    std::hint::black_box(&answer);
    answer.as_ref().unwrap().value()
}

/// The number of an answer given to Criterion by [`kept`].
trait Answer {
    fn value(&self) -> f64;
}

impl Answer for Separation {
    fn value(&self) -> f64 {
        self.distance
    }
}

impl Answer for Penetration {
    fn value(&self) -> f64 {
        self.depth
    }
}

/// `box_box_mixed/N=n`: [`distance`] on 1,024 random box pairs in turn, each answer
/// checked against the dimension-generic GJK first.
fn bench_mixed_boxes(
    group: &mut criterion::BenchmarkGroup<criterion::measurement::WallTime>,
    n: usize,
) {
    let mut r = ChaCha8Rng::seed_from_u64(7);
    let count = 1024;
    let mut shapes = Vec::with_capacity(2 * count);
    let mut poses = Vec::with_capacity(count);
    for _ in 0..count {
        for _ in 0..2 {
            let h: Vec<f64> = (0..n).map(|_| r.gen_range(0.2..2.0)).collect();
            shapes.push(ConvexShape::cuboid(&h).unwrap());
        }
        let direction: Vec<f64> = (0..n).map(|_| r.gen_range(-1.0..1.0)).collect();
        let length = direction.iter().map(|x| x * x).sum::<f64>().sqrt();
        let reach = r.gen_range(1.5..6.0);
        let pb: Vec<f64> = direction.iter().map(|x| x * reach / length).collect();
        let (qa, qb) = (
            rotation(n, r.gen_range(0.0..10.0)),
            rotation(n, r.gen_range(0.0..10.0)),
        );
        poses.push((vec![0.0; n], qa, pb, qb));
    }
    let pairs: Vec<(PlacedShape, PlacedShape)> = poses
        .iter()
        .enumerate()
        .map(|(k, (pa, qa, pb, qb))| {
            (
                PlacedShape::new(&shapes[2 * k], pa, qa).unwrap(),
                PlacedShape::new(&shapes[2 * k + 1], pb, qb).unwrap(),
            )
        })
        .collect();
    let (mut apart, mut steps) = (0, 0);
    for (a, b) in &pairs {
        let (fast, general) = (distance(a, b).unwrap(), distance_general(a, b).unwrap());
        assert_eq!(fast.intersecting, general.intersecting);
        assert!((fast.distance - general.distance).abs() <= 1e-9 * (1.0 + general.distance));
        apart += usize::from(!fast.intersecting);
        steps += fast.iterations;
    }
    println!(
        "mixed boxes, N = {n}: {apart} of {count} pairs apart, {:.2} least-squares steps on average",
        steps as f64 / count as f64
    );
    let mut k = 0;
    group.bench_function(format!("box_box_mixed/N={n}"), |bench| {
        bench.iter(|| {
            let (a, b) = &pairs[k % count];
            k += 1;
            kept(distance(black_box(a), black_box(b)))
        })
    });
}

fn bench_distance(c: &mut Criterion) {
    let mut group = c.benchmark_group("gjk_distance");
    for n in [3usize, 4] {
        let h: Vec<f64> = (0..n).map(|k| 0.5 + 0.1 * k as f64).collect();
        let boxes = ConvexShape::cuboid(&h).unwrap();
        let (qa, qb) = (rotation(n, 0.3), rotation(n, 0.7));
        let pa = vec![0.0; n];
        let mut pb = vec![0.4; n];
        pb[0] = 2.5;
        let a = PlacedShape::new(&boxes, &pa, &qa).unwrap();
        let b = PlacedShape::new(&boxes, &pb, &qb).unwrap();
        let s = distance(&a, &b).unwrap();
        let general = distance_general(&a, &b).unwrap();
        assert!(!s.intersecting);
        assert!((s.distance - general.distance).abs() <= 1e-12 * general.distance);
        println!(
            "boxes, N = {n}: distance {:.6}, {} least-squares steps, {} GJK iterations",
            s.distance, s.iterations, general.iterations
        );
        group.bench_function(format!("box_box/N={n}"), |bench| {
            bench.iter(|| kept(distance(black_box(&a), black_box(&b))))
        });
        group.bench_function(format!("general_boxes/N={n}"), |bench| {
            bench.iter(|| kept(distance_general(black_box(&a), black_box(&b))))
        });
        bench_mixed_boxes(&mut group, n);
    }
    let n = 4;
    let tesseract = ConvexShape::hull(&corners(&[0.5; 4])).unwrap();
    let ball = ConvexShape::ball(4, 0.5).unwrap();
    let boxes = ConvexShape::cuboid(&[0.5, 0.6, 0.7, 0.8]).unwrap();
    let capsule = ConvexShape::capsule(4, 0.6, 0.3).unwrap();
    let (qa, qb) = (rotation(n, 0.3), rotation(n, 0.7));
    let (pa, pb) = (vec![0.0; 4], vec![1.9, 0.4, 0.4, 0.4]);
    for (name, sa, sb) in [
        ("tesseract_hulls/N=4", &tesseract, &tesseract),
        ("balls/N=4", &ball, &ball),
        ("ball_box/N=4", &boxes, &ball),
        ("capsules/N=4", &capsule, &capsule),
    ] {
        let a = PlacedShape::new(sa, &pa, &qa).unwrap();
        let b = PlacedShape::new(sb, &pb, &qb).unwrap();
        assert!(!distance(&a, &b).unwrap().intersecting);
        group.bench_function(name, |bench| {
            bench.iter(|| kept(distance(black_box(&a), black_box(&b))))
        });
        group.bench_function(format!("general_{name}"), |bench| {
            bench.iter(|| kept(distance_general(black_box(&a), black_box(&b))))
        });
    }
    group.finish();
    for (name, general) in [
        ("box_box/N=3", "general_boxes/N=3"),
        ("box_box/N=4", "general_boxes/N=4"),
        ("tesseract_hulls/N=4", "general_tesseract_hulls/N=4"),
        ("balls/N=4", "general_balls/N=4"),
        ("ball_box/N=4", "general_ball_box/N=4"),
        ("capsules/N=4", "general_capsules/N=4"),
    ] {
        if let (Some(fixed), Some(general)) = (
            median_ns("gjk_distance", name),
            median_ns("gjk_distance", general),
        ) {
            println!(
                "gjk_distance/{name}: {fixed:.1} ns, {general:.1} ns general, general / fast = {:.2}",
                general / fixed
            );
        }
    }
}

/// Criterion's median for a bench (`name` as given to it, `/` for its folder), in ns, if it
/// has run.
fn median_ns(group: &str, name: &str) -> Option<f64> {
    let root = std::env::var("CARGO_TARGET_DIR").unwrap_or_else(|_| "target".into());
    let folder = name.replace('/', "_");
    let path = format!("{root}/criterion/{group}/{folder}/new/estimates.json");
    let text = std::fs::read_to_string(path).ok()?;
    let json: serde_json::Value = serde_json::from_str(&text).ok()?;
    json["median"]["point_estimate"].as_f64()
}

fn bench_overlap(c: &mut Criterion) {
    let mut group = c.benchmark_group("box_overlap");
    let mut workspace = EpaWorkspace::new();
    macro_rules! pair {
        ($n:literal) => {{
            let h: [f64; $n] = std::array::from_fn(|k| 0.5 + 0.1 * k as f64);
            let boxes = ConvexShape::cuboid(&h).unwrap();
            let (qa, qb) = (rotation($n, 0.3), rotation($n, 0.7));
            let pa = [0.0; $n];
            let mut pb = [0.1; $n];
            pb[0] = 0.9;
            let a = PlacedShape::new(&boxes, &pa, &qa).unwrap();
            let b = PlacedShape::new(&boxes, &pb, &qb).unwrap();
            let epa = penetration_with(&mut workspace, &a, &b).unwrap();
            let sat = sat_depth::<$n>(&h, &pa, &qa, &h, &pb, &qb);
            assert!(
                (epa.depth - sat).abs() < 1e-9,
                "EPA {} against SAT {}",
                epa.depth,
                sat
            );
            group.bench_function(concat!("epa_penetration/N=", $n), |bench| {
                bench.iter(|| {
                    kept(penetration_with(
                        &mut workspace,
                        black_box(&a),
                        black_box(&b),
                    ))
                })
            });
            group.bench_function(concat!("sat_depth/N=", $n), |bench| {
                bench.iter(|| {
                    sat_depth::<$n>(
                        black_box(&h),
                        black_box(&pa),
                        black_box(&qa),
                        black_box(&h),
                        black_box(&pb),
                        black_box(&qb),
                    )
                })
            });
            group.bench_function(concat!("gjk_intersects/N=", $n), |bench| {
                bench.iter(|| intersects(black_box(&a), black_box(&b)).unwrap())
            });
        }};
    }
    pair!(3);
    pair!(4);
    group.finish();
}

fn bench_ellipsoid_depth(c: &mut Criterion) {
    let mut group = c.benchmark_group("ellipsoid_depth");
    let mut workspace = EpaWorkspace::new();
    for n in [4, 6] {
        for kind in ["box", "hull"] {
            let mut r = ChaCha8Rng::seed_from_u64(29 + n as u64);
            // Shapes, then placements: (ellipsoid, polytope, centre, rotations).
            let mut pairs = Vec::new();
            while pairs.len() < 256 {
                let axes: Vec<f64> = (0..n).map(|_| r.gen_range(0.2..2.0)).collect();
                let ellipsoid = ConvexShape::ellipsoid(&axes).unwrap();
                let polytope = if kind == "box" {
                    let h: Vec<f64> = (0..n).map(|_| r.gen_range(0.2..2.0)).collect();
                    ConvexShape::cuboid(&h).unwrap()
                } else {
                    let points: Vec<Vec<f64>> = (0..n + 3)
                        .map(|_| (0..n).map(|_| r.gen_range(-1.5..1.5)).collect())
                        .collect();
                    match ConvexShape::hull(&points) {
                        Ok(s) => s,
                        Err(_) => continue,
                    }
                };
                let centre: Vec<f64> = (0..n).map(|_| r.gen_range(-0.8..0.8)).collect();
                let (qa, qb) = (
                    rotation(n, r.gen_range(0.0..3.0)),
                    rotation(n, r.gen_range(0.0..3.0)),
                );
                pairs.push((ellipsoid, polytope, centre, qa, qb));
            }
            let zero = vec![0.0; n];
            let placed: Vec<(PlacedShape, PlacedShape)> = pairs
                .iter()
                .map(|(e, p, c, qa, qb)| {
                    (
                        PlacedShape::new(e, &zero, qa).unwrap(),
                        PlacedShape::new(p, c, qb).unwrap(),
                    )
                })
                .filter(|(a, b)| intersects(a, b).unwrap())
                .collect();
            assert!(placed.len() >= 128, "{} overlapping pairs", placed.len());
            let mut k = 0;
            group.bench_function(format!("{kind}/N={n}"), |bench| {
                bench.iter(|| {
                    k = (k + 1) % placed.len();
                    let (a, b) = &placed[k];
                    kept(penetration_with(&mut workspace, black_box(a), black_box(b)))
                })
            });
        }
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = configure();
    targets = bench_distance, bench_overlap, bench_ellipsoid_depth
}
criterion_main!(benches);
