//! Multivectors of N ≤ 6 on the stack, for the closed forms of `versor.rs` and the general
//! route of `versor_general.rs`: the coefficients in a `Copy` array of L = 16, 32 or 64 (the
//! smallest that holds 2^N), and the geometric product through a sign table built once per
//! signature, so exp and log in those algebras never touch the heap and never recompute a
//! blade sign.
//!
//! The type mirrors the [`Multivector`] operations those routes use (products, grades,
//! reversion, sums and scalings), with the same meaning, so that the formulas read the same
//! on both.

use super::{Multivector, Signature, blade};
use std::ops::{Add, Mul, Sub};
use std::sync::OnceLock;

/// The largest N these multivectors hold.
pub(super) const SMALL_MAX_DIM: usize = 6;
const TABLE_LEN: usize = 1 << SMALL_MAX_DIM;

/// sign(a, b) · metric(a, b) for every pair of blades of one signature: ±1, or 0 where the
/// product holds a null vector twice.
type SignTable = [[f64; TABLE_LEN]; TABLE_LEN];

/// One table per signature with N ≤ 6, indexed by p · 49 + q · 7 + r; built on first use.
static TABLES: [OnceLock<Box<SignTable>>; 343] = [const { OnceLock::new() }; 343];

fn table(sig: Signature) -> &'static SignTable {
    TABLES[sig.p() * 49 + sig.q() * 7 + sig.r()].get_or_init(|| {
        let mut t = Box::new([[0.0; TABLE_LEN]; TABLE_LEN]);
        let n = 1u64 << sig.dim();
        for a in 0..n {
            for b in 0..n {
                t[a as usize][b as usize] = blade::reorder_sign(a, b) * sig.metric_factor(a, b);
            }
        }
        t
    })
}

/// The grade of every blade mask below 2^6 (no population count in the loops).
const GRADE: [u8; TABLE_LEN] = {
    let mut out = [0u8; TABLE_LEN];
    let mut m = 0;
    while m < TABLE_LEN {
        out[m] = (m as u32).count_ones() as u8;
        m += 1;
    }
    out
};

/// A multivector of Cl(p, q, r) with 2^N ≤ L, coefficients indexed by blade mask as in
/// [`Multivector`] (the first 2^N of the L are used).
#[derive(Clone, Copy, Debug)]
pub(super) struct Small<const L: usize> {
    c: [f64; L],
    sig: Signature,
}

impl<const L: usize> Small<L> {
    /// The zero element (2^N ≤ L, checked by the callers).
    pub(super) fn zero(sig: Signature) -> Self {
        debug_assert!(1 << sig.dim() <= L && L <= TABLE_LEN);
        Small { c: [0.0; L], sig }
    }

    pub(super) fn scalar(sig: Signature, s: f64) -> Self {
        let mut out = Self::zero(sig);
        out.c[0] = s;
        out
    }

    pub(super) fn from_multivector(m: &Multivector) -> Self {
        let mut out = Self::zero(m.signature());
        out.c[..m.as_slice().len()].copy_from_slice(m.as_slice());
        out
    }

    /// The same element on storage of M ≥ 2^N coefficients.
    pub(super) fn resized<const M: usize>(&self) -> Small<M> {
        let mut out = Small::<M>::zero(self.sig);
        out.c[..self.len()].copy_from_slice(self.as_slice());
        out
    }

    /// Writes the coefficients into a multivector of the same algebra.
    pub(super) fn write_to(&self, out: &mut Multivector) {
        let n = out.as_slice().len();
        out.as_mut_slice().copy_from_slice(&self.c[..n]);
    }

    #[cfg(test)]
    pub(super) fn to_multivector(self) -> Multivector {
        let mut out = Multivector::zero(self.sig);
        self.write_to(&mut out);
        out
    }

    fn len(&self) -> usize {
        1 << self.sig.dim()
    }

    pub(super) fn signature(&self) -> Signature {
        self.sig
    }

    pub(super) fn as_slice(&self) -> &[f64] {
        &self.c[..self.len()]
    }

    pub(super) fn as_mut_slice(&mut self) -> &mut [f64] {
        let n = self.len();
        &mut self.c[..n]
    }

    pub(super) fn scalar_part(&self) -> f64 {
        self.c[0]
    }

    /// The non-zero terms as (blade, coefficient).
    pub(super) fn terms(&self) -> impl Iterator<Item = (u64, f64)> + '_ {
        self.as_slice()
            .iter()
            .enumerate()
            .filter(|(_, c)| **c != 0.0)
            .map(|(b, c)| (b as u64, *c))
    }

    pub(super) fn max_abs(&self) -> f64 {
        self.as_slice().iter().fold(0.0f64, |m, c| m.max(c.abs()))
    }

    /// The part of grade k.
    pub(super) fn grade(&self, k: usize) -> Self {
        let mut out = *self;
        for (c, &g) in out.as_mut_slice().iter_mut().zip(&GRADE) {
            if g as usize != k {
                *c = 0.0;
            }
        }
        out
    }

    /// The reverse: grades 2 and 3 (mod 4) change sign.
    pub(super) fn reverse(&self) -> Self {
        let mut out = *self;
        for (c, &g) in out.as_mut_slice().iter_mut().zip(&GRADE) {
            if matches!(g % 4, 2 | 3) {
                *c = -*c;
            }
        }
        out
    }

    /// The grades in `grades` (bit k for grade k) of the geometric product, blade by blade of
    /// the result: the coefficient on blade g is Σᵢ sign(i, i ⊕ g) aᵢ b_(i ⊕ g), so only the
    /// pairs landing on a wanted blade are visited (16 of the 64 of V Ṽ in 4D).
    pub(super) fn geometric_grades(&self, other: &Self, grades: u32) -> Self {
        let t = table(self.sig);
        let n = self.len();
        let (idx, val, m) = self.nonzero();
        let mut out = Self::zero(self.sig);
        for g in 0..n {
            if grades >> GRADE[g & (TABLE_LEN - 1)] & 1 == 0 {
                continue;
            }
            let mut sum = 0.0;
            for (&i, &a) in idx[..m].iter().zip(&val[..m]) {
                // Masks keep every index in range without a bounds check.
                let i = i as usize & (TABLE_LEN - 1);
                let j = (i ^ g) & (L - 1);
                let (sign, b) = (t[i][j & (TABLE_LEN - 1)], other.c[j]);
                // A zero sign or coefficient must skip the pair: an overflowing a·b times
                // 0 would be NaN.
                if sign != 0.0 && b != 0.0 {
                    sum += sign * (a * b);
                }
            }
            out.c[g & (L - 1)] = sum;
        }
        out
    }

    /// ⟨B²⟩₀ and ⟨B²⟩₄ = B∧B of a bivector B: the squares of its planes and the products of
    /// its disjoint planes, without the pairs that only cancel (B² has no grade 2).
    pub(super) fn bivector_square(&self) -> (f64, Self) {
        let t = table(self.sig);
        let (idx, val, m) = self.nonzero();
        let mut out = Self::zero(self.sig);
        let mut scalar = 0.0;
        for a in 0..m {
            let (i, x) = (idx[a] as usize & (TABLE_LEN - 1), val[a]);
            // Zero signs (a plane holding a null vector) must skip the term: an overflowing
            // x² times 0 would be NaN.
            if t[i][i] != 0.0 {
                scalar += t[i][i] * (x * x);
            }
            for b in a + 1..m {
                let (j, y) = (idx[b] as usize & (TABLE_LEN - 1), val[b]);
                let sign = t[i][j] + t[j][i];
                if i & j == 0 && sign != 0.0 {
                    out.c[(i | j) & (L - 1)] += sign * (x * y);
                }
            }
        }
        (scalar, out)
    }

    /// The blades and coefficients of the non-zero terms, and their count.
    fn nonzero(&self) -> ([u8; L], [f64; L], usize) {
        let mut idx = [0u8; L];
        let mut val = [0.0; L];
        let mut m = 0;
        for (j, &c) in self.as_slice().iter().enumerate() {
            if c != 0.0 {
                idx[m] = j as u8;
                val[m] = c;
                m += 1;
            }
        }
        (idx, val, m)
    }

    /// The geometric product, over the non-zero terms of both factors.
    pub(super) fn geometric(&self, other: &Self) -> Self {
        let t = table(self.sig);
        let n = self.len();
        let (idx, val, m) = other.nonzero();
        let mut out = Self::zero(self.sig);
        let degenerate = self.sig.r() > 0;
        for (i, row) in t.iter().enumerate().take(n) {
            let a = self.c[i];
            if a == 0.0 {
                continue;
            }
            // Masks keep every index in range without a bounds check.
            let pairs = idx[..m].iter().zip(&val[..m]);
            if degenerate {
                // A zero sign must skip the pair: an overflowing a·b times 0 would be NaN.
                for (&j, &b) in pairs {
                    let (j, k) = (j as usize & (TABLE_LEN - 1), (i ^ j as usize) & (L - 1));
                    if row[j] != 0.0 {
                        out.c[k] += row[j] * (a * b);
                    }
                }
            } else {
                for (&j, &b) in pairs {
                    let (j, k) = (j as usize & (TABLE_LEN - 1), (i ^ j as usize) & (L - 1));
                    out.c[k] += row[j] * (a * b);
                }
            }
        }
        out
    }
}

impl<const L: usize> Small<L> {
    /// `self` with `f(x, y)` applied to each coefficient x and the matching one y of `o`.
    fn zip_with(&self, o: &Small<L>, f: impl Fn(&mut f64, f64)) -> Small<L> {
        let mut out = *self;
        for (x, y) in out.c.iter_mut().zip(&o.c) {
            f(x, *y);
        }
        out
    }
}

impl<const L: usize> Add<&Small<L>> for &Small<L> {
    type Output = Small<L>;
    fn add(self, o: &Small<L>) -> Small<L> {
        self.zip_with(o, |x, y| *x += y)
    }
}

impl<const L: usize> Sub<&Small<L>> for &Small<L> {
    type Output = Small<L>;
    fn sub(self, o: &Small<L>) -> Small<L> {
        self.zip_with(o, |x, y| *x -= y)
    }
}

impl<const L: usize> Mul<f64> for &Small<L> {
    type Output = Small<L>;
    fn mul(self, s: f64) -> Small<L> {
        let mut out = *self;
        for x in out.as_mut_slice() {
            *x *= s;
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check<const L: usize>(n: usize, r: &mut impl FnMut() -> f64) -> usize {
        let mut checked = 0;
        for p in 0..=n {
            for q in 0..=n - p {
                let sig = Signature::new(p, q, n - p - q).unwrap();
                let mut a = Multivector::zero(sig);
                let mut b = Multivector::zero(sig);
                for k in 0..1 << n {
                    a.as_mut_slice()[k] = r();
                    b.as_mut_slice()[k] = if k % 3 == 0 { 0.0 } else { r() };
                }
                let expected = a.geometric(&b);
                let got = Small::<L>::from_multivector(&a)
                    .geometric(&Small::<L>::from_multivector(&b))
                    .to_multivector();
                assert!((&got - &expected).max_abs() <= 1e-13, "{sig}");
                // The grade-filtered product, for grades {0, 2} and {0, 4}.
                for (grades, keep) in [(0b101u32, [0usize, 2]), (0b10001, [0, 4])] {
                    let got = Small::<L>::from_multivector(&a)
                        .geometric_grades(&Small::<L>::from_multivector(&b), grades)
                        .to_multivector();
                    let want = &expected.grade(keep[0]) + &expected.grade(keep[1]);
                    assert!(
                        (&got - &want).max_abs() <= 1e-13,
                        "{sig}: grades {grades:b}"
                    );
                }
                let biv = a.grade(2);
                let (s0, s4) = Small::<L>::from_multivector(&biv).bivector_square();
                let square = biv.geometric(&biv);
                assert!((s0 - square.scalar_part()).abs() <= 1e-13, "{sig}");
                assert!(
                    (&s4.to_multivector() - &square.grade(4)).max_abs() <= 1e-13,
                    "{sig}"
                );
                let rev = Small::<L>::from_multivector(&a).reverse().to_multivector();
                assert_eq!(rev, a.reverse(), "{sig}");
                let g2 = Small::<L>::from_multivector(&a).grade(2).to_multivector();
                assert_eq!(g2, a.grade(2), "{sig}");
                checked += 1;
            }
        }
        checked
    }

    #[test]
    fn products_match_the_multivector_kernel_in_every_signature_up_to_six_dimensions() {
        let mut seed = 3u64;
        let mut r = move || crate::numeric::tests::random(&mut seed);
        let mut checked = 0;
        for n in 1..=4 {
            checked += check::<16>(n, &mut r);
        }
        checked += check::<32>(5, &mut r);
        checked += check::<64>(5, &mut r);
        checked += check::<64>(6, &mut r);
        assert_eq!(checked, 3 + 6 + 10 + 15 + 21 + 21 + 28);
    }
}
