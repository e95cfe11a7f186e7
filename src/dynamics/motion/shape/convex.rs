//! [`ConvexShape`]: the convex pieces bodies collide with, each known by its support
//! function in its own axes.

use super::ShapeError;
use crate::numeric::orthogonalize_twice;
use smallvec::SmallVec;

/// Inline storage of one vector (no heap up to N = 8).
pub(crate) type Coords = SmallVec<[f64; 8]>;

/// The part of a [`ConvexShape`] without its margin: what the support function of the
/// core returns, in the shape's own axes (the shape's centre is the origin of them).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum ConvexCore {
    /// The centre alone (a ball is a point with a margin).
    Point,
    /// A solid ellipsoid with these semi-axes along the own axes.
    Ellipsoid(Coords),
    /// A solid box with these half-lengths along the own axes.
    Cuboid(Coords),
    /// The segment from −h e₁ to +h e₁ along the first own axis, h > 0 (a capsule is a
    /// segment with a margin).
    Segment(f64),
    /// The convex hull of these points, row-major (N numbers per point), spanning N
    /// dimensions.
    Hull(Vec<f64>),
}

/// A convex shape in N dimensions: a core (point, ellipsoid, box, segment, convex hull of
/// points) and a margin r ≥ 0 around it, the set of points within r of the core.
///
/// The shape answers the one question collision detection asks, the support point
/// s(d) = argmax_{x ∈ shape} d·x, in O(N) for the closed forms (box: sign(dᵢ)hᵢ; ellipsoid:
/// A²d/|Ad| with A = diag(semi-axes)) and in O(N × vertices) for hulls; a margin adds
/// r d/|d|. Balls and capsules are a point and a segment with a margin, so that
/// distance queries are exact for them (the query runs on the cores and subtracts the
/// margins). A hollow sphere touches with its outer surface, so its contact shape is its
/// ball ([`ConvexShape::sphere`]).
///
/// ```
/// use rotorflow::dynamics::motion::shape::ConvexShape;
/// let tesseract = ConvexShape::cuboid(&[1.0; 4])?;
/// let mut s = [0.0; 4];
/// tesseract.support_own(&[0.3, -2.0, 0.0, 1.0], &mut s)?;
/// assert_eq!(s, [1.0, -1.0, 1.0, 1.0]);
/// assert!(ConvexShape::cuboid(&[1.0, 0.0]).is_err());
/// # Ok::<(), rotorflow::dynamics::motion::shape::ShapeError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct ConvexShape {
    dim: usize,
    core: ConvexCore,
    margin: f64,
}

fn check_dim(dim: usize) -> Result<(), ShapeError> {
    if dim < 2 {
        Err(ShapeError::TooFewDimensions { dim })
    } else {
        Ok(())
    }
}

fn check_finite(what: &'static str, x: &[f64]) -> Result<(), ShapeError> {
    match x.iter().find(|v| !v.is_finite()) {
        Some(&value) => Err(ShapeError::NonFinite { what, value }),
        None => Ok(()),
    }
}

fn check_positive(what: &'static str, x: &[f64]) -> Result<(), ShapeError> {
    check_finite(what, x)?;
    match x.iter().position(|v| *v <= 0.0) {
        Some(index) => Err(ShapeError::NonPositiveLength {
            what,
            index,
            value: x[index],
        }),
        None => Ok(()),
    }
}

/// Checks that `position` has `n` finite numbers and `rotation` n × n.
pub(crate) fn check_placement(
    n: usize,
    position: &[f64],
    rotation: &[f64],
) -> Result<(), ShapeError> {
    if position.len() != n {
        return Err(ShapeError::DimensionMismatch {
            what: "position",
            expected: n,
            found: position.len(),
        });
    }
    if rotation.len() != n * n {
        return Err(ShapeError::DimensionMismatch {
            what: "rotation",
            expected: n * n,
            found: rotation.len(),
        });
    }
    check_finite("position", position)?;
    check_finite("rotation", rotation)
}

/// The dimension of the affine hull of `points` (row-major, `n` numbers per point), by
/// Gram–Schmidt on the differences from the first point with a tolerance relative to the
/// point set's extent.
pub(crate) fn affine_rank(points: &[f64], n: usize) -> usize {
    let count = points.len() / n;
    if count < 2 {
        return 0;
    }
    let p0 = &points[..n];
    let extent = points
        .chunks_exact(n)
        .map(|p| {
            p.iter()
                .zip(p0)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max);
    if extent == 0.0 {
        return 0;
    }
    let tolerance = 1e-10 * extent;
    let mut basis: Vec<f64> = Vec::with_capacity(n * n);
    let mut rank = 0;
    for p in points.chunks_exact(n).skip(1) {
        if rank == n {
            break;
        }
        let mut r: Vec<f64> = p.iter().zip(p0).map(|(a, b)| (a - b) / extent).collect();
        orthogonalize_twice(&mut r, &basis, basis.len() / n);
        let norm = r.iter().map(|x| x * x).sum::<f64>().sqrt();
        if norm > tolerance / extent {
            basis.extend(r.iter().map(|x| x / norm));
            rank += 1;
        }
    }
    rank
}

impl ConvexShape {
    /// Returns the solid ball of radius `radius` in `dim` dimensions.
    ///
    /// # Errors
    /// [`ShapeError::TooFewDimensions`] below 2, [`ShapeError::NonFinite`] or
    /// [`ShapeError::NonPositiveLength`] for the radius.
    pub fn ball(dim: usize, radius: f64) -> Result<Self, ShapeError> {
        check_dim(dim)?;
        check_positive("radius", &[radius])?;
        Ok(ConvexShape {
            dim,
            core: ConvexCore::Point,
            margin: radius,
        })
    }

    /// Returns the contact shape of a hollow sphere of radius `radius`: its ball, since a
    /// body touches with its outer surface (the mass distribution differs, the shape
    /// that touches does not).
    ///
    /// # Errors
    /// As [`ConvexShape::ball`].
    pub fn sphere(dim: usize, radius: f64) -> Result<Self, ShapeError> {
        Self::ball(dim, radius)
    }

    /// Returns the solid ellipsoid with these semi-axes along the own axes (N numbers).
    ///
    /// # Errors
    /// [`ShapeError::TooFewDimensions`] for fewer than 2 semi-axes,
    /// [`ShapeError::NonFinite`] or [`ShapeError::NonPositiveLength`] for a semi-axis.
    pub fn ellipsoid(semi_axes: &[f64]) -> Result<Self, ShapeError> {
        check_dim(semi_axes.len())?;
        check_positive("semi-axis", semi_axes)?;
        Ok(ConvexShape {
            dim: semi_axes.len(),
            core: ConvexCore::Ellipsoid(Coords::from_slice(semi_axes)),
            margin: 0.0,
        })
    }

    /// Returns the solid box with these half-lengths along the own axes (N numbers).
    ///
    /// # Errors
    /// [`ShapeError::TooFewDimensions`] for fewer than 2 half-lengths,
    /// [`ShapeError::NonFinite`] or [`ShapeError::NonPositiveLength`] for a half-length.
    pub fn cuboid(half_lengths: &[f64]) -> Result<Self, ShapeError> {
        check_dim(half_lengths.len())?;
        check_positive("half-length", half_lengths)?;
        Ok(ConvexShape {
            dim: half_lengths.len(),
            core: ConvexCore::Cuboid(Coords::from_slice(half_lengths)),
            margin: 0.0,
        })
    }

    /// Returns the convex hull of `points` (each N numbers, own axes).
    ///
    /// # Errors
    /// [`ShapeError::TooFewDimensions`], [`ShapeError::DimensionMismatch`] if the points
    /// differ in dimension, [`ShapeError::NonFinite`], and [`ShapeError::FlatHull`] (with
    /// the rank found) if they do not span N dimensions.
    pub fn hull<P: AsRef<[f64]>>(points: &[P]) -> Result<Self, ShapeError> {
        let dim = points.first().map_or(0, |p| p.as_ref().len());
        check_dim(dim)?;
        let mut flat = Vec::with_capacity(points.len() * dim);
        for p in points {
            let p = p.as_ref();
            if p.len() != dim {
                return Err(ShapeError::DimensionMismatch {
                    what: "hull point",
                    expected: dim,
                    found: p.len(),
                });
            }
            check_finite("hull point", p)?;
            flat.extend_from_slice(p);
        }
        let rank = affine_rank(&flat, dim);
        if rank < dim {
            return Err(ShapeError::FlatHull {
                points: points.len(),
                rank,
                dim,
            });
        }
        Ok(ConvexShape {
            dim,
            core: ConvexCore::Hull(flat),
            margin: 0.0,
        })
    }

    /// The hull of `points` (row-major, `dim` numbers each, finite) without the rank check:
    /// a body's contact shape of vertices may be flat (the vertices of a plane figure), and
    /// GJK and EPA answer for flat hulls too.
    pub(crate) fn hull_unchecked(points: Vec<f64>, dim: usize) -> Self {
        ConvexShape {
            dim,
            core: ConvexCore::Hull(points),
            margin: 0.0,
        }
    }

    /// Returns the regular simplex (N + 1 vertices: the triangle, the tetrahedron, the
    /// paper's 5-cell in 4D) centred on the origin with circumradius `circumradius`.
    ///
    /// # Errors
    /// [`ShapeError::TooFewDimensions`], [`ShapeError::NonFinite`] or
    /// [`ShapeError::NonPositiveLength`].
    pub fn simplex(dim: usize, circumradius: f64) -> Result<Self, ShapeError> {
        check_dim(dim)?;
        check_positive("circumradius", &[circumradius])?;
        // e₁ … e_N and t(1, …, 1) with t = (1 − √(N+1))/N are N + 1 points at mutual
        // distance √2; centre them and scale to the circumradius.
        let nf = dim as f64;
        let t = (1.0 - (nf + 1.0).sqrt()) / nf;
        let mut points: Vec<Vec<f64>> = (0..dim)
            .map(|i| (0..dim).map(|j| if i == j { 1.0 } else { 0.0 }).collect())
            .collect();
        points.push(vec![t; dim]);
        let centre: Vec<f64> = (0..dim)
            .map(|j| points.iter().map(|p| p[j]).sum::<f64>() / (nf + 1.0))
            .collect();
        let radius = points[0]
            .iter()
            .zip(&centre)
            .map(|(a, c)| (a - c) * (a - c))
            .sum::<f64>()
            .sqrt();
        for p in &mut points {
            for (x, c) in p.iter_mut().zip(&centre) {
                *x = (*x - c) * circumradius / radius;
            }
        }
        Self::hull(&points)
    }

    /// Returns the cross-polytope (the 2N vertices ±r eᵢ: the square turned by 45°, the
    /// octahedron, the 16-cell) of circumradius `radius`.
    ///
    /// # Errors
    /// [`ShapeError::TooFewDimensions`], [`ShapeError::NonFinite`] or
    /// [`ShapeError::NonPositiveLength`].
    pub fn cross_polytope(dim: usize, radius: f64) -> Result<Self, ShapeError> {
        check_dim(dim)?;
        check_positive("radius", &[radius])?;
        let points: Vec<Vec<f64>> = (0..2 * dim)
            .map(|k| {
                let mut p = vec![0.0; dim];
                p[k / 2] = if k % 2 == 0 { radius } else { -radius };
                p
            })
            .collect();
        Self::hull(&points)
    }

    /// Returns the capsule: the segment from −h e₁ to +h e₁ (h = `half_length`) swept by
    /// a ball of radius `radius`.
    ///
    /// # Errors
    /// [`ShapeError::TooFewDimensions`], [`ShapeError::NonFinite`] or
    /// [`ShapeError::NonPositiveLength`] for either length.
    pub fn capsule(dim: usize, half_length: f64, radius: f64) -> Result<Self, ShapeError> {
        check_dim(dim)?;
        check_positive("half-length", &[half_length])?;
        check_positive("radius", &[radius])?;
        Ok(ConvexShape {
            dim,
            core: ConvexCore::Segment(half_length),
            margin: radius,
        })
    }

    /// Returns the shape grown by `margin`: the points within `margin` of it (a rounded
    /// box, a thick hull). Margins add up.
    ///
    /// # Errors
    /// [`ShapeError::NonFinite`] or [`ShapeError::NegativeMargin`].
    pub fn rounded(mut self, margin: f64) -> Result<Self, ShapeError> {
        check_finite("margin", &[margin])?;
        if margin < 0.0 {
            return Err(ShapeError::NegativeMargin { margin });
        }
        self.margin += margin;
        Ok(self)
    }

    /// Returns the dimension N.
    #[inline]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Returns the core (the shape without its margin).
    #[inline]
    pub fn core(&self) -> &ConvexCore {
        &self.core
    }

    /// Returns the margin: the radius of a ball or a capsule, plus any `.rounded` margin.
    #[inline]
    pub fn margin(&self) -> f64 {
        self.margin
    }

    /// Returns the radius of the smallest ball about the own origin that holds the core.
    pub fn core_radius(&self) -> f64 {
        match &self.core {
            ConvexCore::Point => 0.0,
            ConvexCore::Ellipsoid(a) => a.iter().copied().fold(0.0, f64::max),
            ConvexCore::Cuboid(h) => h.iter().map(|x| x * x).sum::<f64>().sqrt(),
            ConvexCore::Segment(h) => *h,
            ConvexCore::Hull(v) => v
                .chunks_exact(self.dim)
                .map(|p| p.iter().map(|x| x * x).sum::<f64>().sqrt())
                .fold(0.0, f64::max),
        }
    }

    /// Returns the radius of the smallest ball about the own origin that holds the shape.
    pub fn bounding_radius(&self) -> f64 {
        self.core_radius() + self.margin
    }

    /// Writes into `out` the support point of the core in own axes along `d` (own axes):
    /// a point of the core maximising d·x. A zero direction gives a point of the core.
    /// No checks: `d` and `out` have N numbers.
    #[inline]
    pub(crate) fn core_support(&self, d: &[f64], out: &mut [f64]) {
        match &self.core {
            ConvexCore::Point => out.iter_mut().for_each(|x| *x = 0.0),
            ConvexCore::Cuboid(h) => {
                for ((o, di), hi) in out.iter_mut().zip(d).zip(h) {
                    *o = if *di < 0.0 { -hi } else { *hi };
                }
            }
            ConvexCore::Ellipsoid(a) => {
                // A²d/|Ad|, with d scaled by its largest entry so that |Ad| neither
                // overflows nor underflows.
                let scale = d.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                if !(scale > 0.0 && scale.is_finite()) {
                    out.iter_mut().for_each(|x| *x = 0.0);
                    return;
                }
                let mut norm = 0.0;
                for ((o, di), ai) in out.iter_mut().zip(d).zip(a) {
                    let ad = ai * (di / scale);
                    norm += ad * ad;
                    *o = ai * ad;
                }
                let inv = 1.0 / norm.sqrt();
                out.iter_mut().for_each(|x| *x *= inv);
            }
            ConvexCore::Segment(h) => {
                out.iter_mut().for_each(|x| *x = 0.0);
                out[0] = if d[0] < 0.0 { -h } else { *h };
            }
            ConvexCore::Hull(v) => {
                let n = self.dim;
                let mut best = 0;
                let mut reach = f64::NEG_INFINITY;
                for (k, p) in v.chunks_exact(n).enumerate() {
                    let r: f64 = p.iter().zip(d).map(|(a, b)| a * b).sum();
                    if r > reach {
                        reach = r;
                        best = k;
                    }
                }
                out.copy_from_slice(&v[best * n..(best + 1) * n]);
            }
        }
    }

    /// Writes into `out` the support point of the shape (margin included) in own axes
    /// along the own-axes direction `direction`: the point of the shape that reaches
    /// furthest along it. A zero direction gives a point of the core.
    ///
    /// # Errors
    /// [`ShapeError::DimensionMismatch`] unless both have N numbers,
    /// [`ShapeError::NonFinite`] for a non-finite direction.
    pub fn support_own(&self, direction: &[f64], out: &mut [f64]) -> Result<(), ShapeError> {
        let n = self.dim;
        for (what, x) in [("direction", direction.len()), ("output", out.len())] {
            if x != n {
                return Err(ShapeError::DimensionMismatch {
                    what,
                    expected: n,
                    found: x,
                });
            }
        }
        check_finite("direction", direction)?;
        self.core_support(direction, out);
        if self.margin > 0.0 {
            let scale = direction.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            if scale > 0.0 {
                let norm = direction
                    .iter()
                    .map(|x| (x / scale) * (x / scale))
                    .sum::<f64>()
                    .sqrt();
                for (o, d) in out.iter_mut().zip(direction) {
                    *o += self.margin * (d / scale) / norm;
                }
            }
        }
        Ok(())
    }

    /// Returns the support value h(d) = max_{x ∈ shape} d·x of the shape in own axes.
    fn support_value_own(&self, d: &[f64]) -> f64 {
        let mut s = Coords::from_elem(0.0, self.dim);
        self.core_support(d, &mut s);
        let norm = d.iter().map(|x| x * x).sum::<f64>().sqrt();
        s.iter().zip(d).map(|(a, b)| a * b).sum::<f64>() + self.margin * norm
    }

    /// Writes the axis-aligned bounding box of the shape placed at `position` with
    /// `rotation` (row-major N × N, own axes → space: x = position + Q x_own) into
    /// `lower` and `upper`. The box is tight: each face touches the shape.
    ///
    /// # Errors
    /// [`ShapeError::DimensionMismatch`] or [`ShapeError::NonFinite`] for the placement.
    pub fn aabb(
        &self,
        position: &[f64],
        rotation: &[f64],
        lower: &mut [f64],
        upper: &mut [f64],
    ) -> Result<(), ShapeError> {
        let n = self.dim;
        check_placement(n, position, rotation)?;
        for (what, x) in [("lower", lower.len()), ("upper", upper.len())] {
            if x != n {
                return Err(ShapeError::DimensionMismatch {
                    what,
                    expected: n,
                    found: x,
                });
            }
        }
        let mut d = Coords::from_elem(0.0, n);
        for i in 0..n {
            // Space axis i in own axes is row i of Q.
            d.copy_from_slice(&rotation[i * n..(i + 1) * n]);
            let up = self.support_value_own(&d);
            d.iter_mut().for_each(|x| *x = -*x);
            let down = self.support_value_own(&d);
            upper[i] = position[i] + up;
            lower[i] = position[i] - down;
        }
        Ok(())
    }
}
