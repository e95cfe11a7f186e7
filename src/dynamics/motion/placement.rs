//! Where the bodies' contact points are: each body's own axes as a matrix and the space
//! offsets of its vertices, kept while the body does not turn.
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

/// True if the two attitudes place a body alike (see [`SAME_ATTITUDE`]).
pub(crate) fn attitudes_close(a: &Attitude, b: &Attitude) -> bool {
    if a.dim() != b.dim() {
        return false;
    }
    let close = |x: &[f64], y: &[f64]| {
        x.len() == y.len() && x.iter().zip(y).all(|(p, q)| (p - q).abs() <= SAME_ATTITUDE)
    };
    match (a.as_rotor(), b.as_rotor()) {
        (Some(x), Some(y)) => close(x.as_slice(), y.as_slice()),
        (None, None) => {
            let n = a.dim();
            let mut qa = SmallVec::<[f64; 64]>::from_elem(0.0, n * n);
            let mut qb = SmallVec::<[f64; 64]>::from_elem(0.0, n * n);
            a.write_matrix(&mut qa);
            b.write_matrix(&mut qb);
            close(&qa, &qb)
        }
        _ => false,
    }
}

/// One body's placement: its own axes and its vertices' offsets in space.
#[derive(Clone, Debug, Default)]
pub(crate) struct Placement {
    /// The principal-frame attitude it was computed at (None: not placed).
    attitude: Option<Attitude>,
    /// Changes whenever the placement is computed anew.
    pub generation: u64,
    /// The own axes, row-major N × N (column j: the image of eⱼ).
    pub q: SmallVec<[f64; 64]>,
    /// For a shape of vertices, Q r of each vertex r (N numbers each).
    offsets: Vec<f64>,
    /// For a shape of vertices, n · (Q r) of each vertex r for the normal n of each
    /// half-space in turn: the candidates' heights above their centre of mass, which every
    /// contact question of a step asks for.
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
        (_, normal): (usize, &Vector),
        mut visit: impl FnMut(usize, &Vector, &[f64]),
    ) {
        let n = normal.dim();
        match shape {
            ContactShape::Vertices(v) if self.offsets.len() == v.len() * n => {
                for (k, (r, placed)) in v.iter().zip(self.offsets.chunks_exact(n)).enumerate() {
                    visit(k + 1, r, placed);
                }
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
    /// Computes the vertices' heights against the normals of `half_spaces`.
    fn set_heights(&mut self, n: usize, half_spaces: &[HalfSpace]) {
        self.heights.clear();
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
        if self.owner != Some(owner) || self.bodies.len() != bodies.len() {
            self.owner = Some(owner);
            self.bodies.resize_with(bodies.len(), Placement::default);
            for (p, shape) in self.bodies.iter_mut().zip(shapes) {
                p.attitude = None;
                p.radius = shape.radius();
            }
        }
        for ((p, b), shape) in self.bodies.iter_mut().zip(bodies).zip(shapes) {
            if matches!(shape, ContactShape::None) {
                continue;
            }
            let attitude = b.rotation().principal_frame_attitude();
            if p.attitude
                .as_ref()
                .is_some_and(|a| attitudes_close(a, attitude))
            {
                if let ContactShape::Vertices(v) = shape
                    && p.heights.len() != v.len() * half_spaces.len()
                {
                    // A half-space joined since.
                    p.set_heights(b.dim(), half_spaces);
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
            p.set_heights(n, half_spaces);
            match &mut p.attitude {
                Some(a) => a.clone_from(attitude),
                None => p.attitude = Some(attitude.clone()),
            }
            self.next += 1;
            p.generation = self.next;
        }
    }

    /// The placement of body `i` (as of the last [`Placements::update`]).
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
            assert!(attitudes_close(&base, &base.clone()), "N = {n}");
            assert!(attitudes_close(&base, &turned(1e-17)), "N = {n}");
            assert!(!attitudes_close(&base, &turned(1e-13)), "N = {n}");
            assert!(
                !attitudes_close(&base, &Attitude::identity(n + 1)),
                "N = {n}"
            );
        }
    }
}
