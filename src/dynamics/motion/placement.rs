//! Where the bodies' contact points are: each body's own axes as a matrix, the space
//! offsets of its vertices (or an ellipsoid's support point against each half-space),
//! kept while the body does not turn.
//!
//! A step asks for the contact candidates several times (the contacts in reach before the
//! step, the two velocity solves, the position check of the free flight, the new
//! penetrations, the lift out of the half-spaces), and a body resting on the floor hardly
//! turns from one step to the next: placing its vertices once per attitude, instead of once
//! per question, is most of the work saved.

use super::{ContactShape, HalfSpace, MovingBody};
use crate::algebra::Vector;
use crate::dynamics::Attitude;
use smallvec::SmallVec;

/// Attitudes whose coefficients differ by at most this much place a body alike: its
/// offsets, inverse inertia in space and contact matrices then differ from those of the
/// current attitude by a few units of round-off, and are kept.
pub(crate) const SAME_ATTITUDE: f64 = 1e-15;

/// The entries of two attitudes of one dimension (both rotors or both matrices, as the
/// dimension decides) within [`SAME_ATTITUDE`] of each other.
fn entries_close(x: &[f64], y: &[f64]) -> bool {
    x.len() == y.len() && x.iter().zip(y).all(|(p, q)| (p - q).abs() <= SAME_ATTITUDE)
}

/// An attitude kept to compare later ones with ([`AttitudeKey::close_to`]), or none: its entries
/// (a rotor's coefficients or a matrix's) alone, in the room of a rotor's up to 4D. A
/// body's state keeps one for each thing it placed; a whole attitude, with room for an
/// 8 × 8 matrix inline, would spread those few numbers over many cache lines. A matrix's
/// entries go to the heap at the first `set` and reuse that room after.
#[derive(Clone, Debug, Default)]
pub(crate) struct AttitudeKey {
    entries: SmallVec<[f64; 8]>,
    dim: usize,
}

impl AttitudeKey {
    /// Keeps `attitude`.
    pub(crate) fn set(&mut self, attitude: &Attitude) {
        self.entries.clear();
        self.entries.extend_from_slice(attitude.entries());
        self.dim = attitude.dim();
    }

    /// Keeps none.
    pub(crate) fn clear(&mut self) {
        self.entries.clear();
        self.dim = 0;
    }

    /// True if an attitude is kept.
    pub(crate) fn is_set(&self) -> bool {
        self.dim != 0
    }

    /// True if an attitude is kept and places a body as `attitude` does (see
    /// [`SAME_ATTITUDE`]).
    pub(crate) fn close_to(&self, attitude: &Attitude) -> bool {
        self.dim == attitude.dim() && entries_close(&self.entries, attitude.entries())
    }
}

/// One body's placement: its own axes and its vertices' offsets in space.
#[derive(Clone, Debug, Default)]
pub(crate) struct Placement {
    /// The principal-frame attitude it was computed at (none: not placed).
    attitude: AttitudeKey,
    /// Changes whenever the placement is computed anew.
    pub generation: u64,
    /// The own axes, row-major N × N (column j: the image of eⱼ); inline up to 4D, from 5D
    /// on the heap once (its room kept from placement to placement).
    pub q: SmallVec<[f64; 16]>,
    /// For a shape of vertices, Q r of each vertex r (N numbers each); for an ellipsoid,
    /// Q r of its support point r against each half-space in turn.
    offsets: Vec<f64>,
    /// For an ellipsoid, its support point r in own axes against each half-space.
    supports: Vec<Vector>,
    /// For a shape of vertices, n · (Q r) of each vertex r for the normal n of each
    /// half-space in turn, and for an ellipsoid that of its support point: the candidates'
    /// heights above their centre of mass, which every contact question of a step asks for.
    heights: Vec<f64>,
    /// The shape's radius ([`ContactShape::radius`]), which contact tolerances scale with.
    pub radius: f64,
}

impl Placement {
    /// The heights n · (Q r) of the vertices of `shape` against half-space `plane`, if
    /// they are kept.
    #[inline]
    fn heights(&self, shape: &ContactShape, plane: usize) -> Option<&[f64]> {
        match shape {
            ContactShape::Vertices(v) => self.heights.get(plane * v.len()..(plane + 1) * v.len()),
            ContactShape::Ellipsoid(_) => self.heights.get(plane..plane + 1),
            _ => None,
        }
    }

    /// Calls `visit(index, height)` for each candidate of `shape` against half-space
    /// `plane` of unit normal `normal`, numbered from 1 as [`ContactShape::candidates`],
    /// with its height n · (Q r) above the centre of mass.
    #[inline]
    pub(crate) fn candidate_heights(
        &self,
        shape: &ContactShape,
        (plane, normal): (usize, &Vector),
        mut visit: impl FnMut(usize, f64),
    ) {
        match self.heights(shape, plane) {
            Some(heights) => {
                for (k, &h) in heights.iter().enumerate() {
                    visit(k + 1, h);
                }
            }
            None => self.candidates(shape, (plane, normal), |k, _, r| {
                visit(k, dot(normal.as_slice(), r))
            }),
        }
    }

    /// Calls `visit(index, r, r_space)` for each candidate of `shape` against half-space
    /// `plane` of unit normal `normal`, as [`ContactShape::candidates`] and numbered from
    /// 1.
    pub(crate) fn candidates(
        &self,
        shape: &ContactShape,
        (plane, normal): (usize, &Vector),
        mut visit: impl FnMut(usize, &Vector, &[f64]),
    ) {
        let n = normal.dim();
        match shape {
            ContactShape::Vertices(v) if self.offsets.len() == v.len() * n => {
                for (k, (r, placed)) in v.iter().zip(self.offsets.chunks_exact(n)).enumerate() {
                    visit(k + 1, r, placed);
                }
            }
            ContactShape::Ellipsoid(_)
                if self.supports.len() > plane && self.offsets.len() == self.supports.len() * n =>
            {
                visit(
                    1,
                    &self.supports[plane],
                    &self.offsets[plane * n..(plane + 1) * n],
                );
            }
            _ => {
                let mut k = 0;
                shape.candidates(&self.q, normal, |r, placed| {
                    k += 1;
                    visit(k, r, placed.as_slice());
                });
            }
        }
    }

    /// Vertex `index` (from 1) of `shape`, in own axes and in space, when it is placed.
    #[inline]
    pub(crate) fn vertex<'a>(
        &'a self,
        shape: &'a ContactShape,
        index: usize,
    ) -> Option<(&'a Vector, &'a [f64])> {
        let ContactShape::Vertices(v) = shape else {
            return None;
        };
        let r = v.get(index.checked_sub(1)?)?;
        let n = r.dim();
        Some((r, self.offsets.get((index - 1) * n..index * n)?))
    }

    /// n · (Q r) for candidate `index` (from 1) of `shape` against half-space `plane` of
    /// unit normal `normal` (+∞ if there is no such candidate).
    pub(crate) fn candidate_height(
        &self,
        shape: &ContactShape,
        (plane, normal): (usize, &Vector),
        index: usize,
    ) -> f64 {
        if let Some(h) = self
            .heights(shape, plane)
            .and_then(|h| h.get(index.checked_sub(1)?))
        {
            return *h;
        }
        let mut out = f64::INFINITY;
        self.candidates(shape, (plane, normal), |k, _, r| {
            if k == index {
                out = dot(normal.as_slice(), r);
            }
        });
        out
    }
}

impl Placement {
    /// Computes the vertices' heights against the normals of `half_spaces`, and for an
    /// ellipsoid its support point against each (as [`ContactShape::candidates`] gives it
    /// at the placement's axes).
    fn set_heights(&mut self, shape: &ContactShape, n: usize, half_spaces: &[HalfSpace]) {
        self.heights.clear();
        if let ContactShape::Ellipsoid(_) = shape {
            let Placement {
                q,
                offsets,
                supports,
                heights,
                ..
            } = self;
            offsets.clear();
            supports.resize_with(half_spaces.len(), || Vector::zero(n));
            for (plane, support) in half_spaces.iter().zip(supports.iter_mut()) {
                shape.candidates(q, plane.normal(), |r, placed| {
                    set_vector(support, r.as_slice());
                    offsets.extend_from_slice(placed.as_slice());
                    heights.push(dot(plane.normal().as_slice(), placed.as_slice()));
                });
            }
            return;
        }
        for plane in half_spaces {
            let normal = plane.normal().as_slice();
            self.heights
                .extend(self.offsets.chunks_exact(n).map(|r| dot(normal, r)));
        }
    }
}

/// a · b.
#[inline(always)]
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Sets `v` to the components `x`, in place when the dimensions agree (a copy instead of a
/// new vector).
#[inline(always)]
pub(crate) fn set_vector(v: &mut Vector, x: &[f64]) {
    if v.dim() == x.len() {
        v.as_mut_slice().copy_from_slice(x);
    } else {
        *v = Vector::from_storage(SmallVec::from_slice(x));
    }
}

/// The placements of all bodies of one system.
#[derive(Clone, Debug, Default)]
pub(crate) struct Placements {
    /// The system and the version of its shapes they are of.
    owner: Option<(u64, u64)>,
    /// The last generation handed out.
    next: u64,
    bodies: Vec<Placement>,
}

impl Placements {
    /// Places every body with a shape whose attitude moved since it was last placed
    /// (beyond [`SAME_ATTITUDE`]), with its vertices' heights against `half_spaces`.
    /// `owner` names the system and its shapes' version: for another, everything is placed
    /// anew.
    pub(crate) fn update(
        &mut self,
        bodies: &[MovingBody],
        shapes: &[ContactShape],
        owner: (u64, u64),
        half_spaces: &[HalfSpace],
    ) {
        self.own(shapes, owner);
        for ((p, b), shape) in self.bodies.iter_mut().zip(bodies).zip(shapes) {
            if matches!(shape, ContactShape::None) {
                continue;
            }
            let attitude = b.rotation().principal_frame_attitude();
            if p.attitude.close_to(attitude) {
                let kept = match shape {
                    ContactShape::Vertices(v) => v.len() * half_spaces.len(),
                    ContactShape::Ellipsoid(_) => half_spaces.len(),
                    _ => p.heights.len(),
                };
                if p.heights.len() != kept {
                    // A half-space joined since.
                    p.set_heights(shape, b.dim(), half_spaces);
                }
                continue;
            }
            let n = b.dim();
            p.q.clear();
            p.q.resize(n * n, 0.0);
            b.attitude().write_matrix(&mut p.q);
            p.offsets.clear();
            if let ContactShape::Vertices(v) = shape {
                for r in v {
                    let r = r.as_slice();
                    for i in 0..n {
                        p.offsets.push(dot(&p.q[i * n..(i + 1) * n], r));
                    }
                }
            }
            p.set_heights(shape, n, half_spaces);
            p.attitude.set(attitude);
            self.next += 1;
            p.generation = self.next;
        }
    }

    /// The placement of body `i` (as of the last [`Placements::update`]).
    /// Makes these the placements of the shapes `shapes` of the system `owner` (see
    /// [`Self::update`]): for other shapes than before, every body is to be placed anew,
    /// with its bounding radius.
    pub(crate) fn own(&mut self, shapes: &[ContactShape], owner: (u64, u64)) {
        if self.owner != Some(owner) || self.bodies.len() != shapes.len() {
            self.owner = Some(owner);
            self.bodies.resize_with(shapes.len(), Placement::default);
            for (p, shape) in self.bodies.iter_mut().zip(shapes) {
                p.attitude.clear();
                p.radius = shape.radius();
            }
        }
    }

    pub(crate) fn get(&self, i: usize) -> &Placement {
        &self.bodies[i]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::{Bivector, Rotor};

    /// Rotors (N ≤ 4) and rotation matrices (N > 4) alike: an attitude turned by 1e-17 rad
    /// places a body as before, one turned by 1e-13 rad does not, nor one of another
    /// dimension.
    #[test]
    fn attitudes_are_close_within_round_off_only() {
        for n in [3usize, 4, 5, 6] {
            let planes = n * (n - 1) / 2;
            let b: Vec<f64> = (0..planes).map(|k| 0.3 + 0.1 * k as f64).collect();
            let base = Attitude::from(Rotor::from_rotation_bivector(
                &Bivector::from_components(n, &b).unwrap(),
            ));
            let turned = |angle: f64| {
                let mut a = base.clone();
                let mut w = Bivector::zero(n);
                w.as_mut_slice()[0] = angle;
                a.times_exp_mut(&w);
                a
            };
            let mut key = AttitudeKey::default();
            assert!(!key.is_set() && !key.close_to(&base), "N = {n}");
            key.set(&base);
            assert!(key.close_to(&base.clone()), "N = {n}");
            assert!(key.close_to(&turned(1e-17)), "N = {n}");
            assert!(!key.close_to(&turned(1e-13)), "N = {n}");
            assert!(!key.close_to(&Attitude::identity(n + 1)), "N = {n}");
            key.clear();
            assert!(!key.close_to(&base), "N = {n}");
        }
    }

    /// An ellipsoid's support points against each half-space are kept with its placement:
    /// what `candidates` and the heights read is what the shape gives at the placement's
    /// axes, to the bit, for balls and general ellipsoids in 3D and 4D, also for a
    /// half-space that joins after the placement.
    #[test]
    fn an_ellipsoid_keeps_its_support_points_per_half_space() {
        use crate::dynamics::motion::{HalfSpace, System};
        use crate::inertia::spec::parse_body;
        let mut checked = 0;
        for (spec, n) in [
            ("ball:3,0.5", 3),
            ("ellipsoid:1,2,3", 3),
            ("ball:4,0.7", 4),
            ("ellipsoid:1,1.2,1.5,2", 4),
        ] {
            let parsed = parse_body(&format!("{spec}+mass=1")).unwrap();
            let planes = n * (n - 1) / 2;
            let b: Vec<f64> = (0..planes).map(|k| 0.4 + 0.3 * k as f64).collect();
            let attitude =
                Rotor::from_rotation_bivector(&Bivector::from_components(n, &b).unwrap());
            let body = MovingBody::from_parsed(
                &parsed,
                attitude,
                &Vector::zero(n),
                &Vector::zero(n),
                &Bivector::zero(n),
            )
            .unwrap();
            let mut system = System::new(vec![body]).unwrap();
            let unit = |v: Vec<f64>| {
                let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
                Vector::from_components(&v.iter().map(|x| x / norm).collect::<Vec<_>>()).unwrap()
            };
            let normals = [
                unit((0..n).map(|i| if i == n - 1 { 1.0 } else { 0.0 }).collect()),
                unit((0..n).map(|i| 0.3 - 0.2 * i as f64).collect()),
            ];
            let mut placements = Placements::default();
            for normal in &normals {
                system
                    .add_half_space(HalfSpace::new(normal, -5.0, 0.5, 0.0).unwrap())
                    .unwrap();
                placements.update(
                    system.bodies(),
                    system.shapes(),
                    system.shape_key(),
                    system.half_spaces(),
                );
                let placed = placements.get(0);
                let shape = &system.shapes()[0];
                for (plane, half_space) in system.half_spaces().iter().enumerate() {
                    let normal = half_space.normal();
                    let mut kept = Vec::new();
                    placed.candidates(shape, (plane, normal), |index, r, x| {
                        kept.push((index, r.clone(), x.to_vec()))
                    });
                    let mut fresh = Vec::new();
                    shape.candidates(&placed.q, normal, |r, x| {
                        fresh.push((fresh.len() + 1, r.clone(), x.as_slice().to_vec()))
                    });
                    assert_eq!(kept.len(), 1, "{spec}");
                    assert_eq!(kept, fresh, "{spec}, plane {plane}");
                    let height = placed.candidate_height(shape, (plane, normal), 1);
                    assert_eq!(
                        height.to_bits(),
                        dot(normal.as_slice(), &fresh[0].2).to_bits()
                    );
                    checked += 1;
                }
            }
        }
        assert_eq!(checked, 12);
    }
}
