//! Criterion benches of `Multivector::exp` and `Multivector::log` outside the Euclidean
//! signatures, each beside the strongest fair baseline in the same group:
//!
//! - `pga3_exp`, `pga3_log`: the motor of 3D projective GA Cl(3, 0, 1) through rotorflow's
//!   general `Multivector` route versus a hand-written closed form on fixed-size arrays (the
//!   formula klein and ganja.js use, written below). The setup asserts that both return the
//!   same motor (bivector) to 1e-14, so both columns compute the same thing. `exp_to` and
//!   `log_to` write into a multivector the caller keeps (no result to move out).
//! - `general_exp/Cl(p,q,r)`: exp of a bivector in Cl(3, 1, 0) (N = 4), Cl(4, 1, 0) (N = 5),
//!   Cl(5, 0, 1) and Cl(5, 1, 0) (N = 6, projective and conformal) through
//!   `Multivector::exp` versus two matrix exponentials of nalgebra:
//!   - of the N × N matrix of v ↦ Bv − vB = 2 B × v (`DMatrix::exp`, and `SMatrix::exp` at
//!     the fixed size). That is the action of the versor on vectors, v ↦ exp(B) v exp(B)~
//!     (checked in the setup), not the versor itself: it holds N² numbers where the versor
//!     has 2^(N−1), and it cannot act on higher grades or be composed as a versor. It is the
//!     cheapest standard computation that carries the same transformation.
//!   - of the 2^(N−1) × 2^(N−1) matrix of X ↦ B X on the even subalgebra (`SMatrix::exp`),
//!     the regular representation, whose exponential's first column is the versor exp(B)
//!     (checked in the setup): the same output as rotorflow's.
//!
//! - `versor_to/Cl(p,q,r)`: `Multivector::exp_to` and `Multivector::log_to` into reused
//!   storage for N = 5 and 6 in Euclidean, projective, conformal and mixed signatures (no
//!   baseline: these are the allocation-free entry points, measured for their own cost).
//!
//! Run `cargo bench --bench versors`; `BENCH_QUICK=1` shortens the run.

use criterion::{BenchmarkId, Criterion, black_box, criterion_group, criterion_main};
use nalgebra::{DMatrix, SMatrix};
use rotorflow::algebra::{Multivector, Signature};

#[path = "common/configure.rs"]
mod configure;
use configure::configure;

/// A bivector of Cl(3, 0, 1) as `[e₁₂, e₁₃, e₂₃, e₁₄, e₂₄, e₃₄]` (e₄ the null vector).
type PgaBivector = [f64; 6];

/// A motor of Cl(3, 0, 1) as `[1, e₁₂, e₁₃, e₂₃, e₁₄, e₂₄, e₃₄, e₁₂₃₄]`.
type PgaMotor = [f64; 8];

/// Hand-written exp in Cl(3, 0, 1). With B = A + T (A the Euclidean part, T the part
/// holding e₄), B² = −θ² + p I with θ = |A|, I = e₁₂₃₄ and p = 2 (A∧T)₁₂₃₄. Splitting
/// B = (B − αAI) + αAI with α = −p / (2θ²) gives two commuting parts, the first squaring to
/// −θ² and the second to 0, so
///
///   exp(B) = cos θ + (sin θ/θ) B + α (cos θ − sin θ/θ) A I − α θ sin θ I,
///
/// with A I = −a₁₂ e₃₄ + a₁₃ e₂₄ − a₂₃ e₁₄ (ganja.js's `Exp` and klein's `exp`).
#[inline]
fn pga_exp(b: &PgaBivector) -> PgaMotor {
    let [a12, a13, a23, t14, t24, t34] = *b;
    let theta2 = a12 * a12 + a13 * a13 + a23 * a23;
    if theta2 == 0.0 {
        return [1.0, 0.0, 0.0, 0.0, t14, t24, t34, 0.0];
    }
    let theta = theta2.sqrt();
    let (s, c) = theta.sin_cos();
    let sc = s / theta;
    let p = 2.0 * (a12 * t34 - a13 * t24 + a23 * t14);
    let alpha = -p / (2.0 * theta2);
    let k = alpha * (c - sc);
    [
        c,
        sc * a12,
        sc * a13,
        sc * a23,
        sc * t14 - k * a23,
        sc * t24 + k * a13,
        sc * t34 - k * a12,
        -alpha * theta * s,
    ]
}

/// Hand-written log in Cl(3, 0, 1), the inverse of [`pga_exp`]: θ = atan2(|b|, cos θ) from
/// the scalar and the Euclidean bivector b = (sin θ/θ) A, then p from the e₁₂₃₄ coefficient
/// q = p sin θ / (2θ) and T from the e₄ part.
#[inline]
fn pga_log(m: &PgaMotor) -> PgaBivector {
    let [c, b12, b13, b23, m14, m24, m34, q] = *m;
    let bn2 = b12 * b12 + b13 * b13 + b23 * b23;
    if bn2 == 0.0 {
        return [0.0, 0.0, 0.0, m14 / c, m24 / c, m34 / c];
    }
    let bn = bn2.sqrt();
    let theta = bn.atan2(c);
    let s = bn;
    let f = theta / s; // θ / sin θ
    let (a12, a13, a23) = (f * b12, f * b13, f * b23);
    let alpha = -q / (theta * s); // −p/(2θ²) with p = 2θq/sin θ
    let k = alpha * (c - s / theta);
    [
        a12,
        a13,
        a23,
        f * (m14 + k * a23),
        f * (m24 - k * a13),
        f * (m34 + k * a12),
    ]
}

const PGA_BLADES: [u64; 6] = [0b0011, 0b0101, 0b0110, 0b1001, 0b1010, 0b1100];
const MOTOR_BLADES: [u64; 8] = [0, 0b0011, 0b0101, 0b0110, 0b1001, 0b1010, 0b1100, 0b1111];

fn pga_multivector(sig: Signature, b: &PgaBivector) -> Multivector {
    let mut m = Multivector::zero(sig);
    for (k, c) in PGA_BLADES.iter().zip(b) {
        m.as_mut_slice()[*k as usize] = *c;
    }
    m
}

fn bench_pga3(c: &mut Criterion) {
    let sig = Signature::new(3, 0, 1).unwrap();
    // A screw with all six coefficients non-zero and a rotation angle θ ≈ 1.1.
    let b: PgaBivector = [0.4, -0.7, 0.6, 1.3, -0.8, 2.1];
    let bm = pga_multivector(sig, &b);
    let m = pga_exp(&b);
    let mm = bm.exp().unwrap();
    for (k, c) in MOTOR_BLADES.iter().zip(&m) {
        assert!((mm.coefficient(*k) - c).abs() <= 1e-14, "exp, blade {k:#b}");
    }
    let l = pga_log(&m);
    let lm = mm.log().unwrap();
    for ((k, c), orig) in PGA_BLADES.iter().zip(&l).zip(&b) {
        assert!((lm.coefficient(*k) - c).abs() <= 1e-14, "log, blade {k:#b}");
        assert!(
            (orig - c).abs() <= 1e-14,
            "hand-written log(exp), blade {k:#b}"
        );
    }

    let mut g = c.benchmark_group("pga3_exp");
    g.bench_function("rotorflow_multivector_exp", |bench| {
        bench.iter(|| black_box(&bm).exp().unwrap())
    });
    g.bench_function("rotorflow_multivector_exp_to", |bench| {
        let mut out = Multivector::zero(sig);
        bench.iter(|| black_box(&bm).exp_to(black_box(&mut out)).unwrap())
    });
    g.bench_function("hand_written_closed_form", |bench| {
        bench.iter(|| pga_exp(black_box(&b)))
    });
    g.finish();

    let mut g = c.benchmark_group("pga3_log");
    g.bench_function("rotorflow_multivector_log", |bench| {
        bench.iter(|| black_box(&mm).log().unwrap())
    });
    g.bench_function("rotorflow_multivector_log_to", |bench| {
        let mut out = Multivector::zero(sig);
        bench.iter(|| black_box(&mm).log_to(black_box(&mut out)).unwrap())
    });
    g.bench_function("hand_written_closed_form", |bench| {
        bench.iter(|| pga_log(black_box(&m)))
    });
    g.finish();
}

/// A bivector of `sig` with every coefficient non-zero (deterministic, magnitudes ≈ 0.1–0.6).
fn dense_bivector(sig: Signature) -> Multivector {
    let n = sig.dim();
    let mut b = Multivector::zero(sig);
    let mut k = 0;
    for i in 0..n {
        for j in i + 1..n {
            let c = 0.1 + 0.5 * ((k as f64) * 1.7 + 0.3).sin().abs();
            b.as_mut_slice()[(1usize << i) | (1usize << j)] = if k % 3 == 1 { -c } else { c };
            k += 1;
        }
    }
    b
}

/// The N × N matrix of v ↦ Bv − vB = 2 B × v on vectors (column j: the image of eⱼ).
fn action_matrix(b: &Multivector) -> DMatrix<f64> {
    let n = b.dim();
    let sig = b.signature();
    DMatrix::from_fn(n, n, |i, j| {
        let e = Multivector::basis_blade(sig, 1 << j);
        (b.commutator(&e) * 2.0).coefficient(1 << i)
    })
}

/// The 2^(N−1) × 2^(N−1) matrix of X ↦ B X on the even subalgebra (column j: B times the
/// j-th even blade, in mask order): the regular representation, whose matrix exponential
/// applied to 1 (its first column) is the versor exp(B) itself.
fn even_left_multiplication(b: &Multivector) -> DMatrix<f64> {
    let sig = b.signature();
    let even: Vec<u64> = (0..1u64 << b.dim())
        .filter(|m| m.count_ones() % 2 == 0)
        .collect();
    DMatrix::from_fn(even.len(), even.len(), |i, j| {
        (b * &Multivector::basis_blade(sig, even[j])).coefficient(even[i])
    })
}

macro_rules! general_exp {
    ($c:expr, $(($p:literal, $q:literal, $r:literal, $n:literal, $e:literal)),*) => {$({
        let sig = Signature::new($p, $q, $r).unwrap();
        let b = dense_bivector(sig);
        let m = action_matrix(&b);
        let v = b.exp().unwrap();
        // The matrix exponential is the versor's action on vectors.
        let em = m.exp();
        for j in 0..$n {
            let e = Multivector::basis_blade(sig, 1 << j);
            let image = &(&v * &e) * &v.reverse();
            for i in 0..$n {
                let d = (image.coefficient(1 << i) - em[(i, j)]).abs();
                assert!(d <= 1e-12 * em.amax().max(1.0), "{sig:?}: ({i}, {j}) differs by {d}");
            }
        }
        let sm: SMatrix<f64, $n, $n> = SMatrix::from_iterator(m.iter().copied());
        // The regular representation gives the versor itself: its first column is exp(B).
        let l = even_left_multiplication(&b);
        let sl: SMatrix<f64, $e, $e> = SMatrix::from_iterator(l.iter().copied());
        let el = sl.exp();
        let even: Vec<u64> = (0..1u64 << $n).filter(|m| m.count_ones() % 2 == 0).collect();
        for (i, m) in even.iter().enumerate() {
            let d = (el[(i, 0)] - v.coefficient(*m)).abs();
            assert!(d <= 1e-12 * v.max_abs().max(1.0), "{sig:?}: regular representation, blade {m:#b}");
        }
        let mut g = $c.benchmark_group(format!("general_exp/Cl({},{},{})", $p, $q, $r));
        g.bench_function(BenchmarkId::new("rotorflow_multivector_exp", $n), |bench| {
            bench.iter(|| black_box(&b).exp().unwrap())
        });
        g.bench_function(BenchmarkId::new("nalgebra_dmatrix_expm", $n), |bench| {
            bench.iter(|| black_box(&m).exp())
        });
        g.bench_function(BenchmarkId::new("nalgebra_smatrix_expm", $n), |bench| {
            bench.iter(|| black_box(&sm).exp())
        });
        g.bench_function(BenchmarkId::new("nalgebra_smatrix_expm_regular_representation", $n), |bench| {
            bench.iter(|| black_box(&sl).exp())
        });
        g.finish();
    })*};
}

fn bench_general(c: &mut Criterion) {
    general_exp!(
        c,
        (3, 1, 0, 4, 8),
        (4, 1, 0, 5, 16),
        (5, 0, 1, 6, 32),
        (5, 1, 0, 6, 32)
    );
}

/// A bivector of `sig` whose log exists on the principal branch: the dense bivector scaled so
/// that the sum of its rotation angles stays below π in every signature.
fn moderate_bivector(sig: Signature) -> Multivector {
    let b = dense_bivector(sig);
    &b * 0.3
}

fn bench_versor_to(c: &mut Criterion) {
    for (p, q, r) in [
        (5, 0, 0),
        (4, 1, 0),
        (6, 0, 0),
        (5, 0, 1),
        (5, 1, 0),
        (3, 3, 0),
    ] {
        let sig = Signature::new(p, q, r).unwrap();
        let b = moderate_bivector(sig);
        let v = b.exp().unwrap();
        let back = v.log().unwrap();
        assert!((&back - &b).max_abs() <= 1e-12, "{sig:?}: log(exp(B)) = B");
        let mut out = Multivector::zero(sig);
        let mut g = c.benchmark_group(format!("versor_to/Cl({p},{q},{r})"));
        g.bench_function("exp_to", |bench| {
            bench.iter(|| black_box(&b).exp_to(&mut out).unwrap())
        });
        g.bench_function("log_to", |bench| {
            bench.iter(|| black_box(&v).log_to(&mut out).unwrap())
        });
        g.finish();
    }
}

criterion_group! {
    name = benches;
    config = configure();
    targets = bench_pga3, bench_general, bench_versor_to
}
criterion_main!(benches);
