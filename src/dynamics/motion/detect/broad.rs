//! The broad phase: which pairs of bodies have overlapping axis-aligned bounding boxes, kept
//! from step to step with enlarged ("fat") boxes in a hierarchy of boxes.
//!
//! Each body is given a fat box: its box grown by a margin on every side. The hierarchy
//! (median splits along the axis of largest spread of the centres, leaves of a few bodies)
//! is built over the fat boxes, and the broad phase keeps the pairs whose fat boxes overlap,
//! as a sorted list. At an update, a body whose box still lies inside its fat box changes nothing;
//! a body that left it gets a new fat box, the hierarchy's boxes are refitted bottom-up, and
//! only the bodies that moved out are queried for new pairs. Pairs whose fat boxes parted
//! are dropped, and the pairs returned are those of the set whose actual boxes overlap. A
//! step thus costs O(nN) for the containment checks and the refit, O(log n + pairs) per body
//! that left its fat box, O(f log f) to sort the f pairs those queries find and O(pairs) to
//! merge them into the list (which is then the pairs returned, in order, with no sort);
//! the hierarchy is rebuilt, O(n log n), once [`REBUILD_AFTER`] fat boxes per body have
//! been renewed since it was built, so that its boxes stay tight (the dynamic trees of
//! Box2D and Bullet; van den Bergen, "Efficient Collision Detection of Complex Deformable
//! Models using AABB Trees", 1997, for refitting).
//!
//! Memory, not arithmetic, sets the cost at 10⁵ bodies: the fat boxes are also kept in the
//! hierarchy's leaf order, so that a leaf's bodies lie together for refits and queries;
//! the bodies that left their fat boxes are queried in that order (neighbours walk the
//! same nodes in turn); a pair is checked again only if one of its bodies left its fat box;
//! and the box tests have no branch on the boxes' values, so that the processor fetches
//! the scattered boxes of many pairs at once instead of waiting on each.
//!
//! Sweep and prune, the other classic choice, re-sorts the ends of the boxes' intervals on
//! each axis every step; in N dimensions the ends crowd on an axis (n^(1 − 1/N) of them
//! within a box's width), so that a fixed motion crosses that many ends per body: about 10⁷
//! swaps per step for 10⁵ 4D bodies moving 1 % of their size.
//!
//! Intervals are closed: boxes that touch overlap.

use super::KeyHasher;
use crate::dynamics::DynamicsError;
use crate::dynamics::motion::shape::ShapeError;
use std::collections::HashSet;
use std::hash::BuildHasherDefault;

/// The margin of the fat boxes, relative to the bodies' mean half-width at the last
/// rebuild.
pub const FAT_MARGIN: f64 = 0.2;

/// The hierarchy is rebuilt once this many fat boxes per body have been renewed since it
/// was built (refitted node boxes grow as bodies drift apart from their leaf mates; a
/// rebuild costs about as much as renewing every body's box once).
pub const REBUILD_AFTER: usize = 8;

type PairSet = HashSet<u64, BuildHasherDefault<KeyHasher>>;

#[inline]
fn key(i: usize, j: usize) -> u64 {
    let (i, j) = if i < j { (i, j) } else { (j, i) };
    (i as u64) << 32 | j as u64
}

/// The pairs (i < j) of bodies whose axis-aligned boxes overlap, updated incrementally as
/// the boxes move.
///
/// ```
/// use rotorflow::dynamics::motion::detect::BroadPhase;
/// // Three 2D boxes: 0 and 1 overlap, 2 is apart.
/// let lower = [0.0, 0.0, 0.5, 0.5, 5.0, 5.0];
/// let upper = [1.0, 1.0, 1.5, 1.5, 6.0, 6.0];
/// let mut broad = BroadPhase::new(2)?;
/// assert_eq!(broad.update(&lower, &upper)?, &[(0, 1)]);
/// broad.exclude_pair(0, 1)?; // say, two bodies held by a joint
/// assert!(broad.update(&lower, &upper)?.is_empty());
/// # Ok::<(), rotorflow::dynamics::DynamicsError>(())
/// ```
#[derive(Clone, Debug)]
pub struct BroadPhase {
    dim: usize,
    bodies: usize,
    /// The fat boxes.
    fat_lower: Vec<f64>,
    fat_upper: Vec<f64>,
    margin: f64,
    tree: Hierarchy,
    /// The bodies in the hierarchy's leaf order, and each body's place in it.
    order: Vec<u32>,
    rank: Vec<u32>,
    /// The fat boxes in leaf order (N lower bounds, then N upper bounds, per place): a
    /// leaf's bodies lie together, so that refits and queries read them from a few cache
    /// lines, where by body index they would be scattered over all the bodies' boxes.
    leaf_bounds: Vec<f64>,
    stack: Vec<u32>,
    /// The bodies that left their fat boxes at the last update, in leaf order (queries of
    /// neighbours then walk the same nodes one after another), and a flag per body.
    moved: Vec<u32>,
    left: Vec<bool>,
    /// Fat boxes renewed since the hierarchy was built.
    renewed: usize,
    /// Box tests of the last update's queries.
    box_tests: usize,
    /// The pairs whose fat boxes overlap, as keys (i < j, `key`), sorted and distinct; the
    /// pairs the queries of an update find, and room for the merge of the two.
    pairs: Vec<u64>,
    found: Vec<u64>,
    merged: Vec<u64>,
    excluded: PairSet,
    out: Vec<(usize, usize)>,
    built: bool,
}

impl BroadPhase {
    /// Returns an empty broad phase for boxes in `dim` dimensions.
    ///
    /// # Errors
    /// [`ShapeError::ZeroDimension`] if `dim` is 0.
    pub fn new(dim: usize) -> Result<BroadPhase, DynamicsError> {
        if dim == 0 {
            return Err(ShapeError::ZeroDimension {
                what: "the broad phase",
            }
            .into());
        }
        Ok(BroadPhase {
            dim,
            bodies: 0,
            fat_lower: Vec::new(),
            fat_upper: Vec::new(),
            margin: 0.0,
            tree: Hierarchy::default(),
            order: Vec::new(),
            rank: Vec::new(),
            leaf_bounds: Vec::new(),
            stack: Vec::new(),
            moved: Vec::new(),
            left: Vec::new(),
            renewed: 0,
            box_tests: 0,
            pairs: Vec::new(),
            found: Vec::new(),
            merged: Vec::new(),
            excluded: PairSet::default(),
            out: Vec::new(),
            built: false,
        })
    }

    /// The dimension.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Leaves the pair (i, j) out of the result from now on (bodies that do not collide,
    /// bodies held by a joint).
    ///
    /// # Errors
    /// [`ShapeError::InvalidBodyPair`] if i = j or an index does not fit in 31 bits.
    pub fn exclude_pair(&mut self, i: usize, j: usize) -> Result<(), DynamicsError> {
        self.excluded.insert(checked_key(i, j)?);
        Ok(())
    }

    /// Takes the pair (i, j) back into the result.
    ///
    /// # Errors
    /// As [`BroadPhase::exclude_pair`].
    pub fn include_pair(&mut self, i: usize, j: usize) -> Result<(), DynamicsError> {
        self.excluded.remove(&checked_key(i, j)?);
        Ok(())
    }

    /// The number of bodies that left their fat boxes at the last update (all of them at a
    /// rebuild): the work the motion called for.
    pub fn last_moved(&self) -> usize {
        self.moved.len()
    }

    /// The box–box overlap tests the last update's hierarchy queries made (node boxes and
    /// bodies' fat boxes): the query work, which grows as (bodies moved) × log n at a
    /// fixed density, against n² for all pairs.
    pub fn last_box_tests(&self) -> usize {
        self.box_tests
    }

    /// Takes the boxes of all bodies, `lower` and `upper` (n × N numbers each, body after
    /// body), and returns the pairs (i, j), i < j, whose boxes overlap (touching counts), in
    /// increasing order, less the excluded pairs. After the first call, a body that moved
    /// within its fat box costs a containment check; the same number of bodies must be
    /// passed each time for that (another number starts afresh).
    ///
    /// # Errors
    /// [`ShapeError::DimensionMismatch`] if the lengths differ,
    /// [`ShapeError::NotAMultiple`] if they are not multiples of N,
    /// [`ShapeError::TooManyBodies`] for 2³¹ bodies or more, [`ShapeError::NonFinite`]
    /// for a bound that is not finite and [`ShapeError::InvertedBounds`] for a lower bound
    /// above its upper bound.
    pub fn update(
        &mut self,
        lower: &[f64],
        upper: &[f64],
    ) -> Result<&[(usize, usize)], DynamicsError> {
        let n = self.dim;
        if lower.len() != upper.len() {
            return Err(ShapeError::DimensionMismatch {
                what: "upper bounds",
                expected: lower.len(),
                found: upper.len(),
            }
            .into());
        }
        if !lower.len().is_multiple_of(n) {
            return Err(ShapeError::NotAMultiple {
                what: "bounding boxes",
                numbers: lower.len(),
                dim: n,
            }
            .into());
        }
        let bodies = lower.len() / n;
        if bodies >= 1 << 31 {
            return Err(ShapeError::TooManyBodies {
                bodies,
                max: (1 << 31) - 1,
            }
            .into());
        }
        for (k, (&lo, &hi)) in lower.iter().zip(upper).enumerate() {
            for (what, value) in [("lower bound", lo), ("upper bound", hi)] {
                if !value.is_finite() {
                    return Err(ShapeError::NonFinite { what, value }.into());
                }
            }
            if lo > hi {
                return Err(ShapeError::InvertedBounds {
                    body: k / n,
                    axis: k % n,
                    lower: lo,
                    upper: hi,
                }
                .into());
            }
        }
        self.box_tests = 0;
        if !self.built || bodies != self.bodies || self.renewed >= REBUILD_AFTER * bodies.max(1) {
            self.rebuild(bodies, lower, upper);
        } else {
            self.refresh(lower, upper);
        }
        self.out.clear();
        let excluded = &self.excluded;
        // The keys are in order, and so are the pairs (i, j) they hold. The second bodies'
        // boxes are scattered over all the boxes: the test has no branch, so that the
        // processor fetches the boxes of many pairs at once instead of waiting for each.
        let pairs = &self.pairs;
        let out = &mut self.out;
        out.resize(pairs.len(), (0, 0));
        let mut kept = 0;
        for &k in pairs {
            let (i, j) = ((k >> 32) as usize, (k & 0xffff_ffff) as usize);
            out[kept] = (i, j);
            let keep =
                overlap(n, lower, upper, i, j) & (excluded.is_empty() || !excluded.contains(&k));
            kept += usize::from(keep);
        }
        out.truncate(kept);
        Ok(&self.out)
    }

    /// Fat boxes for all bodies, the hierarchy over them, and all their pairs.
    fn rebuild(&mut self, bodies: usize, lower: &[f64], upper: &[f64]) {
        let n = self.dim;
        self.bodies = bodies;
        self.built = true;
        self.renewed = 0;
        let widths: f64 = lower.iter().zip(upper).map(|(l, u)| u - l).sum();
        self.margin = FAT_MARGIN * 0.5 * widths / (bodies * n).max(1) as f64;
        let m = self.margin;
        self.fat_lower.clear();
        self.fat_upper.clear();
        self.fat_lower.extend(lower.iter().map(|x| x - m));
        self.fat_upper.extend(upper.iter().map(|x| x + m));
        self.order.clear();
        self.order.extend(0..bodies as u32);
        self.tree
            .build(n, &self.fat_lower, &self.fat_upper, &mut self.order);
        self.rank.clear();
        self.rank.resize(bodies, 0);
        self.leaf_bounds.clear();
        for (place, &b) in self.order.iter().enumerate() {
            let b = b as usize;
            self.rank[b] = place as u32;
            self.leaf_bounds
                .extend_from_slice(&self.fat_lower[b * n..(b + 1) * n]);
            self.leaf_bounds
                .extend_from_slice(&self.fat_upper[b * n..(b + 1) * n]);
        }
        self.left.clear();
        self.left.resize(bodies, true);
        self.pairs.clear();
        self.moved.clear();
        self.moved.extend_from_slice(&self.order);
        self.query_moved();
    }

    /// Renews the fat boxes the bodies left, refits the hierarchy, drops the pairs whose
    /// fat boxes parted and finds the new ones.
    fn refresh(&mut self, lower: &[f64], upper: &[f64]) {
        let n = self.dim;
        let m = self.margin;
        self.moved.clear();
        for b in 0..self.bodies {
            let mut inside = true;
            for k in b * n..(b + 1) * n {
                inside &= (self.fat_lower[k] <= lower[k]) & (upper[k] <= self.fat_upper[k]);
            }
            self.left[b] = !inside;
            if !inside {
                let place = self.rank[b] as usize;
                let leaf = &mut self.leaf_bounds[2 * n * place..2 * n * (place + 1)];
                for a in 0..n {
                    let k = b * n + a;
                    self.fat_lower[k] = lower[k] - m;
                    self.fat_upper[k] = upper[k] + m;
                    leaf[a] = self.fat_lower[k];
                    leaf[n + a] = self.fat_upper[k];
                }
                self.moved.push(self.rank[b]);
            }
        }
        if self.moved.is_empty() {
            return;
        }
        self.renewed += self.moved.len();
        // Leaf order: each body's queries then find the nodes its neighbours' left cached.
        self.moved.sort_unstable();
        for place in &mut self.moved {
            *place = self.order[*place as usize];
        }
        self.tree.refit(n, &self.leaf_bounds);
        // Only a pair with a body whose fat box was renewed can have parted.
        let (fl, fu, left) = (&self.fat_lower, &self.fat_upper, &self.left);
        self.pairs.retain(|&k| {
            let (i, j) = ((k >> 32) as usize, (k & 0xffff_ffff) as usize);
            !(left[i] || left[j]) || overlap(n, fl, fu, i, j)
        });
        self.query_moved();
    }

    /// Adds the pairs of every body in `moved` with every body whose fat box meets its own,
    /// keeping the list sorted and distinct.
    fn query_moved(&mut self) {
        let n = self.dim;
        let found = &mut self.found;
        found.clear();
        for &b in &self.moved {
            let b = b as usize;
            let place = self.rank[b] as usize;
            self.box_tests += self.tree.query(
                n,
                (&self.leaf_bounds, &self.order),
                (b, place),
                &mut self.stack,
                found,
            );
        }
        found.sort_unstable();
        found.dedup();
        // Merge the two sorted lists, each key once.
        let (old, new) = (&self.pairs, &self.found);
        let merged = &mut self.merged;
        merged.clear();
        let (mut i, mut j) = (0, 0);
        while i < old.len() && j < new.len() {
            let (a, b) = (old[i], new[j]);
            merged.push(a.min(b));
            i += usize::from(a <= b);
            j += usize::from(b <= a);
        }
        merged.extend_from_slice(&old[i..]);
        merged.extend_from_slice(&new[j..]);
        std::mem::swap(&mut self.pairs, &mut self.merged);
    }
}

/// True if the boxes of bodies i and j overlap on every axis; every axis is tested (no
/// branch on the boxes' values).
#[inline(always)]
fn overlap(n: usize, lower: &[f64], upper: &[f64], i: usize, j: usize) -> bool {
    let (lo_i, hi_i) = (&lower[i * n..(i + 1) * n], &upper[i * n..(i + 1) * n]);
    let (lo_j, hi_j) = (&lower[j * n..(j + 1) * n], &upper[j * n..(j + 1) * n]);
    let mut all = true;
    for a in 0..n {
        all &= (lo_i[a] <= hi_j[a]) & (lo_j[a] <= hi_i[a]);
    }
    all
}

fn checked_key(i: usize, j: usize) -> Result<u64, DynamicsError> {
    if i == j || i >= 1 << 31 || j >= 1 << 31 {
        return Err(ShapeError::InvalidBodyPair { i, j }.into());
    }
    Ok(key(i, j))
}

/// A bounding-volume hierarchy over the bodies' fat boxes: nodes split at the median centre
/// along the axis of largest spread, leaves of at most [`LEAF`] bodies, children after their
/// parent in `nodes` (so that a backward pass refits).
#[derive(Clone, Debug, Default)]
struct Hierarchy {
    /// Per node: the box (N lower bounds, then N upper bounds).
    bounds: Vec<f64>,
    /// Per node: the range of `order` it holds, and its children (0 for a leaf).
    nodes: Vec<(u32, u32, u32, u32)>,
}

const LEAF: usize = 8;

impl Hierarchy {
    fn build(&mut self, n: usize, lower: &[f64], upper: &[f64], order: &mut [u32]) {
        self.bounds.clear();
        self.nodes.clear();
        if !order.is_empty() {
            self.node(n, lower, upper, order, 0);
        }
    }

    /// Builds the node over `order[start..start + len]` (passed as the slice) and returns
    /// its index.
    fn node(
        &mut self,
        n: usize,
        lower: &[f64],
        upper: &[f64],
        order: &mut [u32],
        start: usize,
    ) -> u32 {
        let index = self.nodes.len();
        self.nodes
            .push((start as u32, (start + order.len()) as u32, 0, 0));
        let base = self.bounds.len();
        self.bounds.extend(std::iter::repeat_n(f64::INFINITY, n));
        self.bounds
            .extend(std::iter::repeat_n(f64::NEG_INFINITY, n));
        let mut spread_lo: smallvec::SmallVec<[f64; 8]> = smallvec::smallvec![f64::INFINITY; n];
        let mut spread_hi: smallvec::SmallVec<[f64; 8]> = smallvec::smallvec![f64::NEG_INFINITY; n];
        for &b in order.iter() {
            let b = b as usize;
            for a in 0..n {
                self.bounds[base + a] = self.bounds[base + a].min(lower[b * n + a]);
                self.bounds[base + n + a] = self.bounds[base + n + a].max(upper[b * n + a]);
                let c = lower[b * n + a] + upper[b * n + a];
                spread_lo[a] = spread_lo[a].min(c);
                spread_hi[a] = spread_hi[a].max(c);
            }
        }
        if order.len() <= LEAF {
            return index as u32;
        }
        let axis = (0..n)
            .max_by(|&x, &y| {
                (spread_hi[x] - spread_lo[x]).total_cmp(&(spread_hi[y] - spread_lo[y]))
            })
            .unwrap_or(0);
        let mid = order.len() / 2;
        let centre = |b: &u32| lower[*b as usize * n + axis] + upper[*b as usize * n + axis];
        order.select_nth_unstable_by(mid, |x, y| centre(x).total_cmp(&centre(y)));
        let (left, right) = order.split_at_mut(mid);
        let l = self.node(n, lower, upper, left, start);
        let r = self.node(n, lower, upper, right, start + mid);
        self.nodes[index].2 = l;
        self.nodes[index].3 = r;
        index as u32
    }

    /// Recomputes every node's box from the bodies' boxes (`leaf_bounds`, in leaf order),
    /// children before parents.
    fn refit(&mut self, n: usize, leaf_bounds: &[f64]) {
        for k in (0..self.nodes.len()).rev() {
            let (start, end, l, r) = self.nodes[k];
            let tail = &mut self.bounds[2 * n * k..];
            if l == 0 {
                tail[..n].fill(f64::INFINITY);
                tail[n..2 * n].fill(f64::NEG_INFINITY);
                let leaf = &leaf_bounds[2 * n * start as usize..2 * n * end as usize];
                for body in leaf.chunks_exact(2 * n) {
                    for a in 0..n {
                        tail[a] = tail[a].min(body[a]);
                        tail[n + a] = tail[n + a].max(body[n + a]);
                    }
                }
            } else {
                // Children come after their parent: their boxes are at offsets from k.
                let (l, r) = (2 * n * (l as usize - k), 2 * n * (r as usize - k));
                for a in 0..n {
                    tail[a] = tail[l + a].min(tail[r + a]);
                    tail[n + a] = tail[l + n + a].max(tail[r + n + a]);
                }
            }
        }
    }

    /// Adds to `found` the pair of body b, at `place` in leaf order, with every other body
    /// whose box overlaps its own (`leaf_bounds` and `order` as in [`BroadPhase`]); returns
    /// the box tests made (nodes and bodies).
    fn query(
        &self,
        n: usize,
        (leaf_bounds, order): (&[f64], &[u32]),
        (b, place): (usize, usize),
        stack: &mut Vec<u32>,
        found: &mut Vec<u64>,
    ) -> usize {
        if self.nodes.is_empty() {
            return 0;
        }
        let mut tests = 0;
        let own = &leaf_bounds[2 * n * place..2 * n * (place + 1)];
        let (lo, hi) = own.split_at(n);
        stack.clear();
        stack.push(0);
        while let Some(k) = stack.pop() {
            let k = k as usize;
            tests += 1;
            let bounds = &self.bounds[2 * n * k..2 * n * (k + 1)];
            // Every axis tested, then one branch (not one per axis).
            let mut meets = true;
            for a in 0..n {
                meets &= (bounds[a] <= hi[a]) & (lo[a] <= bounds[n + a]);
            }
            if !meets {
                continue;
            }
            let (start, end, l, r) = self.nodes[k];
            if l == 0 {
                let (start, end) = (start as usize, end as usize);
                tests += end - start;
                let leaf = &leaf_bounds[2 * n * start..2 * n * end];
                // Each body written and kept if it overlaps, with no branch on the boxes'
                // values (which a processor cannot predict).
                let mut kept = found.len();
                found.resize(kept + end - start, 0);
                for (p, body) in (start..end).zip(leaf.chunks_exact(2 * n)) {
                    let mut meets = p != place;
                    for a in 0..n {
                        meets &= (body[a] <= hi[a]) & (lo[a] <= body[n + a]);
                    }
                    found[kept] = key(b, order[p] as usize);
                    kept += usize::from(meets);
                }
                found.truncate(kept);
            } else {
                stack.push(l);
                stack.push(r);
            }
        }
        tests
    }
}
