//! `Display` for every algebra type: a sum of terms such as `0.5·e12 - 1.25·e34`, 1-based,
//! zero terms omitted, the zero element printed as `0`. Precision flags (`{:.3}`) apply to
//! every coefficient.
//!
//! The middle dot keeps every term from reading as a float: `0.5e12` would be 5·10¹¹. The
//! scalar term is printed plain (`0.8 + 0.6·e12`). Blade names read back with
//! [`super::Multivector::blade_by_name`].

use super::{Bivector, Multivector, Rotor, Vector, blade};
use std::fmt;

/// Writes Σ cₖ·nameₖ with signs folded into the separators.
fn write_terms<'a>(
    f: &mut fmt::Formatter<'_>,
    terms: impl Iterator<Item = (f64, String)> + 'a,
) -> fmt::Result {
    let mut first = true;
    for (c, name) in terms {
        if c == 0.0 {
            continue;
        }
        let (sep, mag) = match (first, c < 0.0) {
            (true, false) => ("", c),
            (true, true) => ("-", -c),
            (false, false) => (" + ", c),
            (false, true) => (" - ", -c),
        };
        f.write_str(sep)?;
        match f.precision() {
            Some(p) => write!(f, "{mag:.p$}")?,
            None => write!(f, "{mag}")?,
        }
        if name != "1" {
            f.write_str("·")?;
            f.write_str(&name)?;
        }
        first = false;
    }
    if first {
        f.write_str("0")?;
    }
    Ok(())
}

impl fmt::Display for Vector {
    /// Formats as `1·e1 - 2.5·e3`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let n = self.dim();
        write_terms(
            f,
            self.as_slice()
                .iter()
                .enumerate()
                .map(move |(i, &c)| (c, blade::name(1 << i, n))),
        )
    }
}

impl fmt::Display for Bivector {
    /// Formats as `0.5·e12 - 1.25·e34`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let n = self.dim();
        write_terms(
            f,
            super::bivector::pairs(n)
                .zip(self.as_slice().iter())
                .map(move |((i, j), &c)| (c, blade::name((1 << i) | (1 << j), n))),
        )
    }
}

/// Orders blades by grade, then lexicographically by their index lists.
fn sorted_terms(n: usize, terms: Vec<(u64, f64)>) -> Vec<(f64, String)> {
    let mut t = terms;
    t.sort_by_key(|(b, _)| {
        let idx: Vec<usize> = blade::indices(*b).collect();
        (idx.len(), idx)
    });
    t.into_iter().map(|(b, c)| (c, blade::name(b, n))).collect()
}

impl fmt::Display for Rotor {
    /// Formats as `0.8 + 0.6·e12`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let n = self.dim();
        write_terms(f, sorted_terms(n, self.terms().collect()).into_iter())
    }
}

impl fmt::Display for Multivector {
    /// Formats as `1 + 2·e1 - 0.5·e123`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let n = self.dim();
        write_terms(f, sorted_terms(n, self.terms().collect()).into_iter())
    }
}
