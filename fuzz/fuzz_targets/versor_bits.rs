//! `Multivector::exp` and `Multivector::log` in every signature Cl(p, q, r) with N ≤ 6, on
//! raw f64 bit patterns.
//!
//! Input: three bytes choosing the signature (N = 2 … 6 from the first, q from the second, r
//! from the third, p the rest), a fourth byte that may add a component of another grade (its
//! bit 0 set: the blade is the rest of the byte modulo 2ᴺ), then little-endian f64 bit
//! patterns (missing ones are 0): the N(N−1)/2 bivector components in ascending mask order,
//! then the coefficient of that extra blade.
//!
//! Asserts:
//! - a NaN or infinite coefficient: exp and log return `NonFinite`;
//! - a component of another grade: exp returns `NotABivector`;
//! - otherwise exp returns either a documented error (`UnsupportedDimension` for a
//!   signature neither Euclidean nor projective above N = 8 (not reached here), `AngleTooLarge` for a Euclidean |B| > f64::MAX/2 or such a
//!   Euclidean part of a projective B above N = 5, `Overflow`) or
//!   finite coefficients with V Ṽ = 1 to 1e-12 · max(1, |B|) relative to max |Vᵢ|², |B| the
//!   largest coefficient of B (exp is accurate to about 2⁻⁵³ |B| relative: a rotation angle
//!   of 10¹⁶ is not known to within a radian; in the N = 5 non-Euclidean signatures
//!   V Ṽ − 1 is then about 10⁻¹⁶ |B| too, so beyond |B| ≈ 10¹² the check says little);
//! - log(V) of that V returns either an error (`NoLogarithm` on a branch cut, `NotAVersor`,
//!   `LogarithmInaccurate` where V's coefficients span more orders of magnitude than f64
//!   resolves, `Overflow` where checking the logarithm needs an exponential that overflows)
//!   or a finite bivector L with exp(L) = V to
//!   1e-9 · max(1, max |Vᵢ|) · max(1, max |Lᵢ|), or exp(L) = `Overflow` as for B itself;
//! - log of the raw input never panics, and an accepted one is a finite bivector.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rotorflow::algebra::{AlgebraError, Multivector, Signature};

fn finite(xs: &[f64]) -> bool {
    xs.iter().all(|x| x.is_finite())
}

fn bivector_masks(n: usize) -> Vec<usize> {
    let mut out = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            out.push((1 << i) | (1 << j));
        }
    }
    out
}

/// max |V Ṽ − 1| / max |Vᵢ|², computed on V / max |Vᵢ| so that nothing overflows.
fn unit_error(v: &Multivector) -> f64 {
    let top = v.max_abs();
    let w = v * (1.0 / top);
    let mut ww = &w * &w.reverse();
    ww.as_mut_slice()[0] -= (1.0 / top) * (1.0 / top);
    ww.max_abs()
}

fn is_bivector(m: &Multivector) -> bool {
    m.terms()
        .all(|(blade, c)| c == 0.0 || blade.count_ones() == 2)
}

fuzz_target!(|data: &[u8]| {
    if data.len() < 4 {
        return;
    }
    let n = 2 + (data[0] as usize) % 5;
    let q = (data[1] as usize) % (n + 1);
    let r = (data[2] as usize) % (n - q + 1);
    let p = n - q - r;
    let extra = data[3];
    let Ok(sig) = Signature::new(p, q, r) else {
        panic!("Cl({p}, {q}, {r}) refused");
    };
    let mut words = data[4..]
        .chunks(8)
        .map(|c| {
            let mut b = [0u8; 8];
            b[..c.len()].copy_from_slice(c);
            f64::from_le_bytes(b)
        })
        .chain(std::iter::repeat(0.0));
    let mut b = Multivector::zero(sig);
    for mask in bivector_masks(n) {
        b.as_mut_slice()[mask] = words.next().unwrap();
    }
    let mut other_grade = false;
    if extra & 1 == 1 {
        let blade = ((extra >> 1) as usize) % (1 << n);
        let c = words.next().unwrap();
        if blade.count_ones() != 2 {
            b.as_mut_slice()[blade] = c;
            other_grade = c != 0.0;
        }
    }
    let all_finite = finite(b.as_slice());

    // log of the raw input: any answer but a panic; an accepted one is a finite bivector.
    match b.log() {
        Ok(l) => {
            assert!(all_finite, "log accepted non-finite {b:?}");
            assert!(finite(l.as_slice()), "log {b:?} = {l:?}");
            assert!(is_bivector(&l), "log {b:?} = {l:?} is not a bivector");
        }
        Err(AlgebraError::NonFinite { .. }) => assert!(!all_finite, "NonFinite for {b:?}"),
        Err(_) => assert!(all_finite, "non-finite {b:?} not reported as such"),
    }

    let v = match b.exp() {
        Ok(v) => v,
        Err(AlgebraError::NonFinite { .. }) => {
            assert!(!all_finite, "exp: NonFinite for finite {b:?}");
            return;
        }
        Err(AlgebraError::NotABivector { .. }) => {
            assert!(all_finite && other_grade, "exp: NotABivector for {b:?}");
            return;
        }
        Err(AlgebraError::UnsupportedDimension { max, .. }) => {
            assert!(
                all_finite && !other_grade && !sig.is_euclidean() && n > max,
                "exp: UnsupportedDimension for {b:?}"
            );
            return;
        }
        Err(AlgebraError::AngleTooLarge { .. }) => {
            // Euclidean, or the Euclidean part of a projective B above N = 5.
            let projective = sig.q() == 0 && sig.r() == 1 && n > 5;
            assert!(
                all_finite && !other_grade && (sig.is_euclidean() || projective),
                "exp: AngleTooLarge for {b:?}"
            );
            return;
        }
        Err(AlgebraError::Overflow { .. }) => {
            assert!(all_finite && !other_grade, "exp: Overflow for {b:?}");
            return;
        }
        Err(e) => panic!("exp {b:?}: unexpected error {e}"),
    };
    assert!(all_finite, "exp accepted non-finite {b:?}");
    assert!(!other_grade, "exp accepted a non-bivector {b:?}");
    assert!(finite(v.as_slice()), "exp {b:?} = {v:?}");
    let e = unit_error(&v);
    let tol = 1e-12 * b.max_abs().max(1.0);
    assert!(e <= tol, "exp {b:?} = {v:?}: V Ṽ − 1 = {e:e} > {tol:e}");

    match v.log() {
        Ok(l) => {
            assert!(finite(l.as_slice()), "log {v:?} = {l:?}");
            assert!(is_bivector(&l), "log {v:?} = {l:?} is not a bivector");
            let back = match l.exp() {
                Ok(back) => back,
                // As for B itself above: at extreme magnitudes in a degenerate signature,
                // the rounding noise of log V makes it no longer exactly nilpotent, and
                // scaling and squaring then overflows where the result would be finite.
                // That is an honest error, not a wrong answer.
                Err(AlgebraError::Overflow { .. }) => return,
                Err(e) => panic!("exp(log V) for V = exp {b:?} = {v:?}, log V = {l:?}: {e}"),
            };
            // exp at L is accurate to about 2⁻⁵³ |L| relative (see above); relative, so that
            // the bound cannot overflow to ∞.
            let d = (&back - &v).max_abs() / v.max_abs().max(1.0) / l.max_abs().max(1.0);
            assert!(
                d <= 1e-9,
                "exp(log V) ≠ V by {d:e} (relative) for V = exp {b:?}"
            );
        }
        Err(
            AlgebraError::NoLogarithm { .. }
            | AlgebraError::NotAVersor { .. }
            | AlgebraError::LogarithmInaccurate { .. }
            // The check of a logarithm of such a size needs its exponential (see above).
            | AlgebraError::Overflow { .. },
        ) => {}
        Err(e) => panic!("log(exp {b:?}): unexpected error {e}"),
    }
});
