//! What is drawn of a body: points in its own axes about the centre of mass, and edges.

use crate::dynamics::motion::ContactShape;
use crate::dynamics::motion::shape::{CompoundShape, ConvexCore, ConvexShape};
use crate::inertia::spec::{Geometry, ParsedBody};
use nalgebra::DMatrix;

/// Geometry to draw for a body: points in the body's own axes, relative to its centre of mass,
/// and edges between them (none for a point cloud).
#[derive(Clone, Debug, PartialEq)]
pub struct Shape {
    /// The dimension N.
    pub dim: usize,
    /// The points, N coordinates each.
    pub points: Vec<Vec<f64>>,
    /// Edges as pairs of indices into `points`.
    pub edges: Vec<[usize; 2]>,
    /// True for a sampled solid or shell (draw small dots), false for a wireframe or a set of
    /// point masses (draw vertex markers).
    pub cloud: bool,
    /// For an ellipsoid or a ball: the N × N matrix whose columns are its semi-axes (own
    /// axes), so that the body is {E u : |u| ≤ 1}. A page draws the surface of its 3D
    /// projection as a wire frame instead of the points.
    pub ellipsoid: Option<DMatrix<f64>>,
}

/// The largest number of points a shape keeps; bigger point sets are thinned evenly.
pub const MAX_POINTS: usize = 4096;

/// The largest number of edges a shape keeps; beyond it only the points are drawn.
pub const MAX_EDGES: usize = 20_000;

impl Shape {
    /// Returns what to draw of a body read from its SPEC, in its own axes about the centre
    /// of mass: a cuboid's edges, up to 12 point masses joined pairwise (more as points), an
    /// ellipsoid's or ball's surface, a mesh's edges; a body given by its mass tensor alone
    /// as the uniform ellipsoid of the same mass tensor.
    pub fn of_body(parsed: &ParsedBody) -> Shape {
        let n = parsed.dim;
        match &parsed.geometry {
            Geometry::Cuboid { half_lengths, .. } => Shape::cuboid(half_lengths),
            Geometry::Points(points) if points.len() <= 12 => Shape::complete_graph(points.clone()),
            Geometry::Points(points) => Shape::cloud(n, points.clone()),
            Geometry::Ellipsoid { semi_axes, surface } => {
                Shape::ellipsoid(semi_axes, None, *surface, 1500)
            }
            Geometry::Mesh { vertices, edges } => {
                Shape::wireframe(n, vertices.clone(), edges.clone())
            }
            Geometry::MassTensor => match &parsed.body {
                // The uniform ellipsoid with the same mass and mass tensor: Jᵢ = m aᵢ²/(N+2).
                Some(body) => {
                    let (moments, axes) = body.principal_frame();
                    let semi: Vec<f64> = moments
                        .iter()
                        .map(|j| ((n as f64 + 2.0) * j.max(0.0) / body.mass()).sqrt())
                        .collect();
                    Shape::ellipsoid(&semi, Some(&axes), false, 1500)
                }
                None => Shape::cross(n, 1.0),
            },
            _ => Shape::cross(n, 1.0),
        }
    }

    /// Returns what to draw of a body of a [`System`](crate::dynamics::motion::System) by
    /// the shape it touches with (in dimension `dim`): an ellipsoid's surface, the vertices
    /// of an axis-aligned box with its edges, other vertices joined pairwise (up to 12) or
    /// as points, and a unit cross for a body without a shape.
    pub fn of_contact_shape(shape: &ContactShape, dim: usize) -> Shape {
        match shape {
            ContactShape::Ellipsoid(a) => Shape::ellipsoid(a, None, false, 1500),
            ContactShape::Vertices(v) => {
                let points: Vec<Vec<f64>> = v.iter().map(|p| p.as_slice().to_vec()).collect();
                Shape::of_vertices(points, dim)
            }
            ContactShape::Convex(c) => Shape::of_convex(c),
            ContactShape::Compound(c) => Shape::of_compound(c),
            _ => Shape::cross(dim, 1.0),
        }
    }

    /// Returns what to draw of a convex shape: a box, an ellipsoid or a ball, or a hull's
    /// vertices as for [`Shape::of_contact_shape`] when that is the whole shape; for a
    /// segment or a margin (capsules, rounded shapes), the cloud of its support points
    /// along directions spread over the sphere (a grid of at most about 1,000 directions
    /// of [−1, 1]ᴺ and the ± axes).
    pub fn of_convex(c: &ConvexShape) -> Shape {
        let n = c.dim();
        match c.core() {
            ConvexCore::Cuboid(h) if c.margin() == 0.0 => Shape::cuboid(h),
            ConvexCore::Ellipsoid(a) if c.margin() == 0.0 => Shape::ellipsoid(a, None, false, 1500),
            ConvexCore::Point => Shape::ellipsoid(&vec![c.margin(); n], None, false, 1500),
            ConvexCore::Hull(v) if c.margin() == 0.0 => {
                Shape::of_vertices(v.chunks_exact(n).map(<[f64]>::to_vec).collect(), n)
            }
            _ => {
                let per_axis = (2..)
                    .take_while(|k: &u32| k.checked_pow(n as u32).is_some_and(|t| t <= 1000))
                    .last()
                    .unwrap_or(2) as usize;
                let mut points = Vec::new();
                let mut d = vec![0.0; n];
                let mut out = vec![0.0; n];
                let mut support = |d: &[f64], points: &mut Vec<Vec<f64>>| {
                    if d.iter().any(|x| *x != 0.0) && c.support_own(d, &mut out).is_ok() {
                        points.push(out.clone());
                    }
                };
                for k in 0..per_axis.pow(n as u32) {
                    let mut rest = k;
                    for x in d.iter_mut() {
                        *x = -1.0 + 2.0 * (rest % per_axis) as f64 / (per_axis - 1) as f64;
                        rest /= per_axis;
                    }
                    support(&d, &mut points);
                }
                for i in 0..n {
                    for sign in [-1.0, 1.0] {
                        d.iter_mut().for_each(|x| *x = 0.0);
                        d[i] = sign;
                        support(&d, &mut points);
                    }
                }
                Shape::cloud(n, points)
            }
        }
    }

    /// Returns what to draw of a compound shape: each piece's drawing ([`Shape::of_convex`])
    /// moved to its place in the body's axes, as points and edges of one drawing.
    pub fn of_compound(c: &CompoundShape) -> Shape {
        let n = c.dim();
        let mut all = Shape {
            dim: n,
            points: Vec::new(),
            edges: Vec::new(),
            cloud: false,
            ellipsoid: None,
        };
        for piece in c.pieces() {
            let drawing = Shape::of_convex(piece.shape());
            let (o, r) = (piece.offset(), piece.rotation());
            let base = all.points.len();
            all.points.extend(drawing.points.iter().map(|p| {
                (0..n)
                    .map(|i| o[i] + (0..n).map(|j| r[i * n + j] * p[j]).sum::<f64>())
                    .collect()
            }));
            all.edges
                .extend(drawing.edges.iter().map(|[a, b]| [a + base, b + base]));
            all.cloud |= drawing.cloud;
        }
        all
    }

    /// The vertices of a polytope: a box's with its edges, up to 12 joined pairwise, more
    /// as points.
    fn of_vertices(points: Vec<Vec<f64>>, dim: usize) -> Shape {
        let half: Vec<f64> = points
            .first()
            .map_or(Vec::new(), |p| p.iter().map(|x| x.abs()).collect());
        let is_box = dim <= 12
            && points.len() == 1 << dim
            && half.len() == dim
            && (0..points.len() as u64).all(|k| points.contains(&cuboid_vertex(&half, k)));
        if is_box {
            Shape::cuboid(&half)
        } else if points.len() <= 12 {
            Shape::complete_graph(points)
        } else {
            Shape::cloud(dim, points)
        }
    }

    /// Returns the vertices (±a₁, …, ±a_N) of a hyper-cuboid with its N·2^(N−1) edges (vertices
    /// that differ in one sign), or a thinned vertex cloud when N is too large to draw.
    pub fn cuboid(half_edges: &[f64]) -> Shape {
        let n = half_edges.len();
        if n > 12 {
            // 2^N vertices are too many to draw: keep an even sample of them.
            let count = MAX_POINTS;
            let total = 1u64 << n;
            let points = (0..count as u64)
                .map(|k| cuboid_vertex(half_edges, k * (total / count as u64)))
                .collect();
            return Shape::cloud(n, points);
        }
        let total = 1usize << n;
        let points = (0..total as u64)
            .map(|k| cuboid_vertex(half_edges, k))
            .collect();
        let mut edges = Vec::new();
        for v in 0..total {
            for bit in 0..n {
                let w = v ^ (1 << bit);
                if v < w {
                    edges.push([v, w]);
                }
            }
        }
        Shape::wireframe(n, points, edges)
    }

    /// Returns the points with every pair joined (a simplex's edges).
    pub fn complete_graph(points: Vec<Vec<f64>>) -> Shape {
        let dim = points.first().map_or(0, Vec::len);
        let mut edges = Vec::new();
        for a in 0..points.len() {
            for b in a + 1..points.len() {
                edges.push([a, b]);
            }
        }
        Shape::wireframe(dim, points, edges)
    }

    /// Returns a wireframe (edges beyond [`MAX_EDGES`] are dropped and only points drawn).
    pub fn wireframe(dim: usize, points: Vec<Vec<f64>>, edges: Vec<[usize; 2]>) -> Shape {
        if edges.len() > MAX_EDGES || points.len() > MAX_POINTS {
            return Shape::cloud(dim, points);
        }
        Shape {
            dim,
            points,
            edges,
            cloud: false,
            ellipsoid: None,
        }
    }

    /// Returns isolated points (thinned evenly to at most [`MAX_POINTS`]).
    pub fn cloud(dim: usize, points: Vec<Vec<f64>>) -> Shape {
        let points = if points.len() > MAX_POINTS {
            let stride = points.len().div_ceil(MAX_POINTS);
            points.into_iter().step_by(stride).collect()
        } else {
            points
        };
        Shape {
            dim,
            points,
            edges: Vec::new(),
            cloud: true,
            ellipsoid: None,
        }
    }

    /// Returns `count` deterministic points filling the ellipsoid Σ (x_i/a_i)² ≤ 1 (or on its
    /// surface when `surface`), with the semi-axes along the columns of `axes` (the body's own
    /// axes when `None`).
    pub fn ellipsoid(
        semi_axes: &[f64],
        axes: Option<&DMatrix<f64>>,
        surface: bool,
        count: usize,
    ) -> Shape {
        let n = semi_axes.len();
        let mut rng = SplitMix(0x5eed_1234_abcd_0001);
        let points = (0..count)
            .map(|_| {
                // A Gaussian direction (Box–Muller), then radius U^(1/N) for a uniform ball.
                let mut g: Vec<f64> = (0..n).map(|_| rng.normal()).collect();
                let norm = g.iter().map(|x| x * x).sum::<f64>().sqrt().max(1e-300);
                let r = if surface {
                    1.0
                } else {
                    rng.uniform().powf(1.0 / n as f64)
                };
                for (x, a) in g.iter_mut().zip(semi_axes) {
                    *x = *x / norm * r * a;
                }
                match axes {
                    Some(p) => (0..n)
                        .map(|row| (0..n).map(|col| p[(row, col)] * g[col]).sum())
                        .collect(),
                    None => g,
                }
            })
            .collect();
        let semi = DMatrix::from_diagonal(&nalgebra::DVector::from_column_slice(semi_axes));
        Shape {
            ellipsoid: Some(match axes {
                Some(p) => p * semi,
                None => semi,
            }),
            ..Shape::cloud(n, points)
        }
    }

    /// Returns the 2N points ±r e_i joined like a cross-polytope (every pair but antipodes).
    pub fn cross(dim: usize, radius: f64) -> Shape {
        let mut points = Vec::with_capacity(2 * dim);
        for i in 0..dim {
            for sign in [1.0, -1.0] {
                let mut p = vec![0.0; dim];
                p[i] = sign * radius;
                points.push(p);
            }
        }
        let mut edges = Vec::new();
        for a in 0..points.len() {
            for b in a + 1..points.len() {
                if a / 2 != b / 2 {
                    edges.push([a, b]);
                }
            }
        }
        Shape::wireframe(dim, points, edges)
    }

    /// Returns the largest distance of a point from the origin (1 for an empty shape).
    pub fn radius(&self) -> f64 {
        let r = self
            .points
            .iter()
            .map(|p| p.iter().map(|x| x * x).sum::<f64>().sqrt())
            .fold(0.0, f64::max);
        if r > 0.0 && r.is_finite() { r } else { 1.0 }
    }
}

fn cuboid_vertex(half_edges: &[f64], k: u64) -> Vec<f64> {
    half_edges
        .iter()
        .enumerate()
        .map(|(i, a)| if k >> i & 1 == 1 { *a } else { -*a })
        .collect()
}

/// A small deterministic generator (SplitMix64) so that drawings are reproducible.
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn uniform(&mut self) -> f64 {
        ((self.next() >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }

    fn normal(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
    }
}
