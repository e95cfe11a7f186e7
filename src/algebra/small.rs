//! Multivectors of N ≤ 5 on the stack, for the closed forms of `versor.rs`: 32 coefficients
//! in a `Copy` array and the geometric product through a sign table built once per
//! signature, so exp and log in those algebras never touch the heap and never recompute a
//! blade sign.
//!
//! The type mirrors the few [`Multivector`] operations the closed forms use (products,
//! grades, reversion, sums and scalings), with the same meaning, so that the formulas read
//! the same on both.

use super::{Multivector, Signature, blade};
use std::ops::{Add, Mul, Sub};
use std::sync::OnceLock;

/// The largest N these multivectors hold.
pub(super) const SMALL_MAX_DIM: usize = 5;
const LEN: usize = 1 << SMALL_MAX_DIM;

/// sign(a, b) · metric(a, b) for every pair of blades of one signature: ±1, or 0 where the
/// product holds a null vector twice.
type SignTable = [[f64; LEN]; LEN];

/// One table per signature with N ≤ 5, indexed by p · 36 + q · 6 + r.
static TABLES: [OnceLock<SignTable>; 216] = [const { OnceLock::new() }; 216];

fn table(sig: Signature) -> &'static SignTable {
    TABLES[sig.p() * 36 + sig.q() * 6 + sig.r()].get_or_init(|| {
        let mut t = [[0.0; LEN]; LEN];
        let n = 1u64 << sig.dim();
        for a in 0..n {
            for b in 0..n {
                t[a as usize][b as usize] = blade::reorder_sign(a, b) * sig.metric_factor(a, b);
            }
        }
        t
    })
}

/// A multivector of Cl(p, q, r) with N ≤ 5, coefficients indexed by blade mask as in
/// [`Multivector`] (the first 2^N of the 32 are used).
#[derive(Clone, Copy, Debug)]
pub(super) struct Small {
    c: [f64; LEN],
    sig: Signature,
}

impl Small {
    /// The zero element (N ≤ 5, checked by the callers).
    pub(super) fn zero(sig: Signature) -> Small {
        debug_assert!(sig.dim() <= SMALL_MAX_DIM);
        Small { c: [0.0; LEN], sig }
    }

    pub(super) fn scalar(sig: Signature, s: f64) -> Small {
        let mut out = Small::zero(sig);
        out.c[0] = s;
        out
    }

    pub(super) fn from_multivector(m: &Multivector) -> Small {
        let mut out = Small::zero(m.signature());
        out.c[..m.as_slice().len()].copy_from_slice(m.as_slice());
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
    pub(super) fn grade(&self, k: usize) -> Small {
        let mut out = *self;
        for (b, c) in out.as_mut_slice().iter_mut().enumerate() {
            if b.count_ones() as usize != k {
                *c = 0.0;
            }
        }
        out
    }

    /// The reverse: grades 2 and 3 (mod 4) change sign.
    pub(super) fn reverse(&self) -> Small {
        let mut out = *self;
        for (b, c) in out.as_mut_slice().iter_mut().enumerate() {
            if matches!((b as u32).count_ones() % 4, 2 | 3) {
                *c = -*c;
            }
        }
        out
    }

    /// The geometric product, over the non-zero terms of both factors.
    pub(super) fn geometric(&self, other: &Small) -> Small {
        let t = table(self.sig);
        let n = self.len();
        let mut idx = [0u8; LEN];
        let mut val = [0.0; LEN];
        let mut m = 0;
        for j in 0..n {
            if other.c[j] != 0.0 {
                idx[m] = j as u8;
                val[m] = other.c[j];
                m += 1;
            }
        }
        let mut out = Small::zero(self.sig);
        let degenerate = self.sig.r() > 0;
        for (i, row) in t.iter().enumerate().take(n) {
            let a = self.c[i];
            if a == 0.0 {
                continue;
            }
            if degenerate {
                // A zero sign must skip the pair: an overflowing a·b times 0 would be NaN.
                for k in 0..m {
                    let j = idx[k] as usize;
                    if row[j] != 0.0 {
                        out.c[i ^ j] += row[j] * (a * val[k]);
                    }
                }
            } else {
                for k in 0..m {
                    let j = idx[k] as usize;
                    out.c[i ^ j] += row[j] * (a * val[k]);
                }
            }
        }
        out
    }
}

impl Add<&Small> for &Small {
    type Output = Small;
    fn add(self, o: &Small) -> Small {
        let mut out = *self;
        for (x, y) in out.c.iter_mut().zip(&o.c) {
            *x += y;
        }
        out
    }
}

impl Sub<&Small> for &Small {
    type Output = Small;
    fn sub(self, o: &Small) -> Small {
        let mut out = *self;
        for (x, y) in out.c.iter_mut().zip(&o.c) {
            *x -= y;
        }
        out
    }
}

impl Mul<f64> for &Small {
    type Output = Small;
    fn mul(self, s: f64) -> Small {
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

    #[test]
    fn products_match_the_multivector_kernel_in_every_signature_up_to_five_dimensions() {
        let mut seed = 3u64;
        let mut r = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        };
        let mut checked = 0;
        for n in 1..=SMALL_MAX_DIM {
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
                    let got = Small::from_multivector(&a)
                        .geometric(&Small::from_multivector(&b))
                        .to_multivector();
                    assert!((&got - &expected).max_abs() <= 1e-14, "{sig}");
                    let rev = Small::from_multivector(&a).reverse().to_multivector();
                    assert_eq!(rev, a.reverse(), "{sig}");
                    let g2 = Small::from_multivector(&a).grade(2).to_multivector();
                    assert_eq!(g2, a.grade(2), "{sig}");
                    checked += 1;
                }
            }
        }
        assert_eq!(checked, 3 + 6 + 10 + 15 + 21);
    }
}
