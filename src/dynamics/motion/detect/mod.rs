//! Collision detection between bodies: which pairs may touch (the broad phase), whether and
//! how deep two shapes overlap (the narrow phase), and where they touch (contact manifolds).
//!
//! - Narrow phase: [`distance`] and [`intersects`] (GJK with an exact simplex
//!   sub-algorithm, `gjk.rs`; on stack arrays for N = 3 and 4, `fixed.rs`; two boxes in 3
//!   and 4 dimensions by bounded least squares, `boxes.rs`; two balls by their centres, a
//!   ball and a box or a capsule by clamping the centre to the core, two capsules by
//!   their segments' nearest points),
//!   [`penetration`] (EPA in N dimensions and closed forms,
//!   `epa.rs`; the exact depth of ellipsoids by Newton's method on the sphere of
//!   directions, `smooth.rs`, and against a polytope, where that is not shown the least,
//!   by the feet of normals on every face's plane, `face_planes.rs`), on [`PlacedShape`]s of [`super::shape`]; boxes by separating axes
//!   ([`box_box`], `sat.rs`).
//! - Contact manifolds of several points ([`box_manifold`], [`hull_manifold`],
//!   `manifold.rs`) and the broad phase ([`BroadPhase`], `broad.rs`).
//! - Which bodies of a system touch which (`bodies.rs`, used by the integrators), and the
//!   pairs whose contact is kept from step to step while they barely move (`kept.rs`).
//!
//! Shapes are placed by plain data: a centre `position` (N numbers, space) and a `rotation`
//! (N × N, row-major, own axes → space). Normals point from body A to body B, depth > 0
//! means overlap, and witness points are in space.

pub(crate) mod bodies;
mod boxes;
pub mod broad;
mod epa;
mod face_pairs;
mod face_planes;
mod fixed;
mod gjk;
pub(crate) mod kept;
pub mod manifold;
pub mod sat;
mod smooth;

pub use broad::BroadPhase;
pub use epa::{EpaWorkspace, Penetration, penetration, penetration_with};
pub use gjk::{PlacedShape, Separation, distance, distance_general, intersects};
pub use manifold::{
    ContactManifold, ContactPoint, FeatureId, PlacedHull, RegionVertex, box_contact_vertices,
    box_manifold, hull_contact_vertices, hull_manifold,
};
pub use sat::{AxisFeature, BoxPairAxis, PlacedBox, box_box, candidate_axis_count};

/// The hasher of the detection's hash tables, whose keys are packed small indices (body
/// pairs in the broad phase, ridges in EPA): not adversarial, so a fast fixed hasher
/// (splitmix64's finaliser, which carries every bit of the key to the high bits the
/// table uses) serves, and runs stay reproducible.
#[derive(Default)]
pub(crate) struct KeyHasher(u64);

impl std::hash::Hasher for KeyHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(b as u64);
        }
    }
    fn write_u128(&mut self, x: u128) {
        self.write_u64(x as u64);
        self.write_u64((x >> 64) as u64);
    }
    fn write_u64(&mut self, x: u64) {
        let mut z = (self.0 ^ x).wrapping_add(0x9e37_79b9_7f4a_7c15);
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        self.0 = z ^ (z >> 31);
    }
}

/// The indices of the set bits of `mask` below `K`, in increasing order, and their count:
/// the members of a simplex or of an active set kept as a bit mask.
#[inline(always)]
pub(crate) fn set_bits<const K: usize>(mask: u32) -> ([usize; K], usize) {
    let mut index = [0usize; K];
    let mut count = 0;
    for i in 0..K {
        if mask >> i & 1 == 1 {
            index[count] = i;
            count += 1;
        }
    }
    (index, count)
}

/// Set-up shared by the detection modules' tests.
#[cfg(test)]
pub(crate) mod test_support {
    use rand::Rng;

    /// A random rotation (row-major, own axes → space): plane rotations by random angles in
    /// every coordinate plane.
    pub(crate) fn random_rotation(r: &mut impl Rng, n: usize) -> Vec<f64> {
        let mut q: Vec<f64> = (0..n * n)
            .map(|k| if k % (n + 1) == 0 { 1.0 } else { 0.0 })
            .collect();
        for i in 0..n {
            for j in i + 1..n {
                let (s, c) = r.gen_range(-3.2..3.2f64).sin_cos();
                for row in 0..n {
                    let (x, y) = (q[row * n + i], q[row * n + j]);
                    q[row * n + i] = c * x - s * y;
                    q[row * n + j] = s * x + c * y;
                }
            }
        }
        q
    }

    /// Minima of `f` on the unit sphere of ℝᴺ found without derivatives: the best `keep` of
    /// `draws` random directions, each polished by a pattern search (steps along the
    /// coordinate axes, renormalised, halved when none lowers f, down to 1e-11). Upper
    /// bounds of the least of f, independent of the detection's own searches.
    pub(crate) fn polished_minima(
        r: &mut impl Rng,
        n: usize,
        (draws, keep): (usize, usize),
        f: &dyn Fn(&[f64]) -> f64,
    ) -> Vec<f64> {
        let unit = |x: Vec<f64>| {
            let l = x.iter().map(|y| y * y).sum::<f64>().sqrt();
            x.into_iter().map(|y| y / l).collect::<Vec<f64>>()
        };
        let mut starts: Vec<(f64, Vec<f64>)> = (0..draws)
            .map(|_| {
                let u = unit((0..n).map(|_| r.gen_range(-1.0..1.0)).collect());
                (f(&u), u)
            })
            .collect();
        starts.sort_by(|p, q| p.0.total_cmp(&q.0));
        starts
            .into_iter()
            .take(keep)
            .map(|(mut value, mut u)| {
                let mut step = 0.1;
                while step > 1e-11 {
                    let mut moved = false;
                    for i in 0..n {
                        for sign in [1.0, -1.0] {
                            let mut v = u.clone();
                            v[i] += sign * step;
                            let v = unit(v);
                            let fv = f(&v);
                            if fv < value {
                                (value, u, moved) = (fv, v, true);
                            }
                        }
                    }
                    if !moved {
                        step *= 0.5;
                    }
                }
                value
            })
            .collect()
    }

    /// The 2^N corners of the box of half-lengths `h`.
    pub(crate) fn box_corners(h: &[f64]) -> Vec<Vec<f64>> {
        let n = h.len();
        (0..1usize << n)
            .map(|c| {
                (0..n)
                    .map(|i| if c >> i & 1 == 1 { h[i] } else { -h[i] })
                    .collect()
            })
            .collect()
    }
}
