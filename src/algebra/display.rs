//! `Display` for every algebra type: a sum of terms such as `0.5·e12 - 1.25·e34`, 1-based,
//! zero terms omitted, the zero element printed as `0`. Precision flags (`{:.3}`) apply to
//! every coefficient.
//!
//! The middle dot keeps every term from reading as a float: `0.5e12` would be 5·10¹¹. The
//! scalar term is printed plain (`0.8 + 0.6·e12`). Blade names read back with
//! [`super::Multivector::blade_by_name`].

use super::{
    Bivector, Bivector3, Bivector4, Multivector, Real, Rotor, Rotor3, Rotor4, Vector, blade, cga,
    pga,
};
use std::fmt;

/// Writes Σ cₖ·nameₖ with signs folded into the separators, for coefficients of either
/// scalar type (an f32 prints as its own shortest form, not as the f64 it widens to).
fn write_terms<'a, C>(
    f: &mut fmt::Formatter<'_>,
    terms: impl Iterator<Item = (C, String)> + 'a,
) -> fmt::Result
where
    C: Copy + PartialOrd + Default + std::ops::Neg<Output = C> + fmt::Display,
{
    let zero = C::default();
    let mut first = true;
    for (c, name) in terms {
        if c == zero {
            continue;
        }
        let (sep, mag) = match (first, c < zero) {
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

/// The named terms of a fixed-size element, (coefficient, 0-based basis indices) in the
/// order of the run-time types' `Display` (by grade, then lexicographically).
fn fixed_terms<T: Real>(n: usize, terms: &[(T, u64)]) -> impl Iterator<Item = (T, String)> + '_ {
    terms
        .iter()
        .map(move |&(c, mask)| (c, blade::name(mask, n)))
}

impl<T: Real + Default + fmt::Display> fmt::Display for Bivector3<T> {
    /// Formats as [`Bivector`] does: `0.5·e12 - 1.25·e23`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let terms = [(self.b12, 0b011), (self.b13, 0b101), (self.b23, 0b110)];
        write_terms(f, fixed_terms(3, &terms))
    }
}

impl<T: Real + Default + fmt::Display> fmt::Display for Rotor3<T> {
    /// Formats as [`Rotor`] does: `0.8 + 0.6·e12`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let b = self.bivector_part();
        let terms = [
            (self.scalar(), 0),
            (b.b12, 0b011),
            (b.b13, 0b101),
            (b.b23, 0b110),
        ];
        write_terms(f, fixed_terms(3, &terms))
    }
}

/// The six planes of 4D with their masks, in lexicographic order.
fn planes4<T: Real>(b: Bivector4<T>) -> [(T, u64); 6] {
    [
        (b.b12, 0b0011),
        (b.b13, 0b0101),
        (b.b14, 0b1001),
        (b.b23, 0b0110),
        (b.b24, 0b1010),
        (b.b34, 0b1100),
    ]
}

impl<T: Real + Default + fmt::Display> fmt::Display for Bivector4<T> {
    /// Formats as [`Bivector`] does: `0.5·e12 - 1.25·e34`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_terms(f, fixed_terms(4, &planes4(*self)))
    }
}

impl<T: Real + Default + fmt::Display> fmt::Display for Rotor4<T> {
    /// Formats as [`Rotor`] does: `0.8 + 0.6·e12 + 0.1·e1234`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut terms = [(T::zero(), 0); 8];
        terms[0] = (self.scalar(), 0);
        terms[1..7].copy_from_slice(&planes4(self.bivector_part()));
        terms[7] = (self.pseudoscalar(), 0b1111);
        write_terms(f, fixed_terms(4, &terms))
    }
}

/// Writes the numbers as a tuple `(1, 2, 3)`, with the formatter's precision.
fn write_tuple(f: &mut fmt::Formatter<'_>, x: &[f64]) -> fmt::Result {
    f.write_str("(")?;
    for (k, c) in x.iter().enumerate() {
        if k > 0 {
            f.write_str(", ")?;
        }
        // + 0.0 prints a −0.0 of a sign flip as 0.
        write_number(f, c + 0.0)?;
    }
    f.write_str(")")
}

/// Writes `name(x₁, x₂, …)`.
fn write_named_tuple(f: &mut fmt::Formatter<'_>, name: &str, x: &[f64]) -> fmt::Result {
    f.write_str(name)?;
    write_tuple(f, x)
}

fn write_number(f: &mut fmt::Formatter<'_>, c: f64) -> fmt::Result {
    match f.precision() {
        Some(p) => write!(f, "{c:.p$}"),
        None => write!(f, "{c}"),
    }
}

impl fmt::Display for pga::Point {
    /// Formats as `point(1, 2, 3)`, or `direction(0, 0, 1)` for an ideal point.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.coordinates() {
            Ok(x) => write_named_tuple(f, "point", &x),
            Err(_) => write_named_tuple(f, "direction", &self.direction()),
        }
    }
}

impl fmt::Display for pga::Plane {
    /// Formats as `plane((0, 0, 1)·x = 2)`: the equation a·x = d as stored.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (a, d) = self.equation();
        f.write_str("plane(")?;
        write_tuple(f, &a)?;
        f.write_str("·x = ")?;
        write_number(f, d + 0.0)?;
        f.write_str(")")
    }
}

impl fmt::Display for pga::Line {
    /// Formats as `line(through (1, 2, 0), direction (0, 0, 1))`, through the point nearest
    /// the origin.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("line(through ")?;
        write_tuple(f, &self.point_nearest_origin())?;
        f.write_str(", direction ")?;
        write_tuple(f, &self.direction())?;
        f.write_str(")")
    }
}

impl fmt::Display for pga::Motor {
    /// Formats as `motor(rotation 0.8 - 0.6·e12, translation (1, 0, 2))`: the motion
    /// x ↦ Q x + t with R the rotor of Q.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("motor(rotation ")?;
        fmt::Display::fmt(&self.rotor(), f)?;
        f.write_str(", translation ")?;
        write_tuple(f, &self.translation())?;
        f.write_str(")")
    }
}

impl fmt::Display for cga::Point {
    /// Formats as `point(1, 2, 3)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.coordinates() {
            Ok(x) => write_named_tuple(f, "point", &x),
            Err(_) => f.write_str("point at infinity"),
        }
    }
}

/// Writes `name(centre (…), radius r)`.
fn write_round(f: &mut fmt::Formatter<'_>, name: &str, centre: &[f64], radius: f64) -> fmt::Result {
    write!(f, "{name}(centre ")?;
    write_tuple(f, centre)?;
    f.write_str(", radius ")?;
    write_number(f, radius)?;
    f.write_str(")")
}

impl fmt::Display for cga::Sphere {
    /// Formats as `sphere(centre (1, 2, 3), radius 2)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_round(f, "sphere", self.centre(), self.radius())
    }
}

impl fmt::Display for cga::Circle {
    /// Formats as `circle(centre (0, 0, 5), radius 2)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_round(f, "circle", self.centre(), self.radius())
    }
}
