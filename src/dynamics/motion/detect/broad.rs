//! The broad phase: which pairs of bodies have overlapping axis-aligned bounding boxes, kept
//! from step to step by sweep and prune on every axis.
//!
//! Each axis keeps the 2n ends of the boxes' intervals sorted. Bodies move little between
//! steps, so the ends are nearly sorted and an insertion sort restores the order in about
//! O(n + swaps); each swap of a lower end with an upper end is the moment two intervals
//! start or stop overlapping on that axis, and only then is the pair looked at: it enters
//! the set when its boxes overlap on every axis, and leaves it when they stop overlapping
//! on one (Baraff, "Dynamic Simulation of Non-Penetrating Rigid Bodies", 1992; Cohen, Lin,
//! Manocha and Ponamgi, "I-COLLIDE", 1995). A step thus costs O(nN + swaps + pairs), with
//! no pair test that a swap did not call for, in any dimension. The first update (and any
//! update after the number of bodies changed) sorts every axis and finds the pairs with a
//! hierarchy of boxes built by median splits along the axis of largest spread, querying
//! each body in it: O(n log n + pairs) for bodies of comparable sizes, where a single sweep
//! would meet every pair overlapping on its axis (about n^(2 − 1/N) at constant density).
//!
//! Intervals are closed: boxes that touch overlap. At equal values lower ends sort before
//! upper ends, so that order and overlap agree exactly.

use crate::dynamics::DynamicsError;
use std::collections::HashSet;
use std::hash::{BuildHasherDefault, Hasher};

/// A multiplicative hasher for pair keys (two body indices packed in a u64): the keys are
/// not adversarial, and a fixed hasher keeps runs reproducible.
#[derive(Default)]
struct PairHasher(u64);

impl Hasher for PairHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(b as u64);
        }
    }
    fn write_u64(&mut self, x: u64) {
        // splitmix64's finaliser: every bit of the key reaches the high bits the table uses.
        let mut z = (self.0 ^ x).wrapping_add(0x9e37_79b9_7f4a_7c15);
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        self.0 = z ^ (z >> 31);
    }
}

type PairSet = HashSet<u64, BuildHasherDefault<PairHasher>>;

/// One end of a body's interval on an axis: the body index times 2, plus 1 for the upper
/// end.
#[derive(Clone, Copy, Debug)]
struct End {
    value: f64,
    tag: u32,
}

impl End {
    #[inline]
    fn body(self) -> usize {
        (self.tag >> 1) as usize
    }
    #[inline]
    fn is_upper(self) -> bool {
        self.tag & 1 == 1
    }
    /// Strict order: by value, lower ends first at equal values.
    #[inline]
    fn after(self, other: End) -> bool {
        self.value > other.value
            || (self.value == other.value && self.is_upper() && !other.is_upper())
    }
}

#[inline]
fn key(i: usize, j: usize) -> u64 {
    let (i, j) = if i < j { (i, j) } else { (j, i) };
    (i as u64) << 32 | j as u64
}

/// Sweep and prune over every axis: the pairs (i < j) of bodies whose axis-aligned boxes
/// overlap, updated incrementally as the boxes move.
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
    lower: Vec<f64>,
    upper: Vec<f64>,
    /// For each axis, the 2n ends in order.
    ends: Vec<Vec<End>>,
    pairs: PairSet,
    excluded: PairSet,
    out: Vec<(usize, usize)>,
    built: bool,
    swaps: usize,
}

impl BroadPhase {
    /// Returns an empty broad phase for boxes in `dim` dimensions.
    ///
    /// # Errors
    /// [`DynamicsError::InvalidMotion`] if `dim` is 0.
    pub fn new(dim: usize) -> Result<BroadPhase, DynamicsError> {
        if dim == 0 {
            return Err(DynamicsError::InvalidMotion {
                what: "broad phase dimension",
                reason: "0: boxes need at least one axis".into(),
            });
        }
        Ok(BroadPhase {
            dim,
            bodies: 0,
            lower: Vec::new(),
            upper: Vec::new(),
            ends: vec![Vec::new(); dim],
            pairs: PairSet::default(),
            excluded: PairSet::default(),
            out: Vec::new(),
            built: false,
            swaps: 0,
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
    /// [`DynamicsError::InvalidMotion`] if i = j or an index does not fit in 32 bits.
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

    /// The number of end swaps of the last update (the work the motion called for).
    pub fn last_swaps(&self) -> usize {
        self.swaps
    }

    /// Takes the boxes of all bodies, `lower` and `upper` (n × N numbers each, body after
    /// body), and returns the pairs (i, j), i < j, whose boxes overlap (touching counts), in
    /// increasing order, less the excluded pairs. After the first call, bodies that moved
    /// a little cost a few swaps each; the same number of bodies must be passed each time
    /// for that (another number starts afresh).
    ///
    /// # Errors
    /// [`DynamicsError::InvalidMotion`] if the lengths are not equal multiples of N, a
    /// bound is not finite, a lower bound exceeds its upper bound, or there are 2³¹ bodies
    /// or more.
    pub fn update(
        &mut self,
        lower: &[f64],
        upper: &[f64],
    ) -> Result<&[(usize, usize)], DynamicsError> {
        let n = self.dim;
        let bad =
            |what: &'static str, reason: String| Err(DynamicsError::InvalidMotion { what, reason });
        if lower.len() != upper.len() || !lower.len().is_multiple_of(n) {
            return bad(
                "bounding boxes",
                format!(
                    "{} lower and {} upper numbers for boxes in {n} dimensions",
                    lower.len(),
                    upper.len()
                ),
            );
        }
        let bodies = lower.len() / n;
        if bodies >= 1 << 31 {
            return bad(
                "bounding boxes",
                format!("{bodies} bodies: at most 2³¹ − 1"),
            );
        }
        for (k, (lo, hi)) in lower.iter().zip(upper).enumerate() {
            if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
                return bad(
                    "bounding box",
                    format!(
                        "body {}, axis {}: [{lo}, {hi}] is not a finite interval",
                        k / n,
                        k % n
                    ),
                );
            }
        }
        self.lower.clear();
        self.lower.extend_from_slice(lower);
        self.upper.clear();
        self.upper.extend_from_slice(upper);
        if !self.built || bodies != self.bodies {
            self.rebuild(bodies);
        } else {
            self.sort_incrementally();
        }
        self.out.clear();
        let excluded = &self.excluded;
        self.out.extend(
            self.pairs
                .iter()
                .filter(|k| !excluded.contains(k))
                .map(|&k| ((k >> 32) as usize, (k & 0xffff_ffff) as usize)),
        );
        self.out.sort_unstable();
        Ok(&self.out)
    }

    /// True if the boxes of bodies i and j overlap on every axis.
    #[inline]
    fn overlap(&self, i: usize, j: usize) -> bool {
        let n = self.dim;
        (0..n).all(|a| {
            self.lower[i * n + a] <= self.upper[j * n + a]
                && self.lower[j * n + a] <= self.upper[i * n + a]
        })
    }

    /// Sorts every axis afresh and finds the pairs by sweeping the axis of largest spread.
    fn rebuild(&mut self, bodies: usize) {
        let n = self.dim;
        self.bodies = bodies;
        self.built = true;
        self.swaps = 0;
        self.pairs.clear();
        for (a, ends) in self.ends.iter_mut().enumerate() {
            ends.clear();
            for b in 0..bodies {
                ends.push(End {
                    value: self.lower[b * n + a],
                    tag: (2 * b) as u32,
                });
                ends.push(End {
                    value: self.upper[b * n + a],
                    tag: (2 * b + 1) as u32,
                });
            }
            ends.sort_unstable_by(|x, y| {
                x.value
                    .total_cmp(&y.value)
                    .then((x.is_upper() as u8).cmp(&(y.is_upper() as u8)))
            });
        }
        // The pairs: a hierarchy of boxes by median splits, each body queried in it.
        let mut order: Vec<u32> = (0..bodies as u32).collect();
        let mut tree = Hierarchy::default();
        tree.build(n, &self.lower, &self.upper, &mut order);
        let mut stack = Vec::new();
        for b in 0..bodies {
            tree.query(
                n,
                &self.lower,
                &self.upper,
                &order,
                b,
                &mut stack,
                |other| {
                    if other > b {
                        self.pairs.insert(key(b, other));
                    }
                },
            );
        }
    }

    /// Restores the order of every axis by insertion sort, updating the pairs at each swap
    /// of a lower end with an upper end.
    fn sort_incrementally(&mut self) {
        let n = self.dim;
        let mut swaps = 0;
        let mut ends = std::mem::take(&mut self.ends);
        for (a, axis) in ends.iter_mut().enumerate() {
            for e in axis.iter_mut() {
                let b = e.body();
                e.value = if e.is_upper() {
                    self.upper[b * n + a]
                } else {
                    self.lower[b * n + a]
                };
            }
            for k in 1..axis.len() {
                let x = axis[k];
                let mut j = k;
                while j > 0 && axis[j - 1].after(x) {
                    let y = axis[j - 1];
                    swaps += 1;
                    if !x.is_upper() && y.is_upper() {
                        // x's lower end passes below y's upper end: they may start to overlap.
                        if self.overlap(x.body(), y.body()) {
                            self.pairs.insert(key(x.body(), y.body()));
                        }
                    } else if x.is_upper() && !y.is_upper() {
                        // x's upper end passes below y's lower end: they stop overlapping.
                        self.pairs.remove(&key(x.body(), y.body()));
                    }
                    axis[j] = y;
                    j -= 1;
                }
                axis[j] = x;
            }
        }
        self.ends = ends;
        self.swaps = swaps;
    }
}

fn checked_key(i: usize, j: usize) -> Result<u64, DynamicsError> {
    if i == j || i >= 1 << 31 || j >= 1 << 31 {
        return Err(DynamicsError::InvalidMotion {
            what: "body pair",
            reason: format!("({i}, {j}): two distinct body indices below 2³¹ are needed"),
        });
    }
    Ok(key(i, j))
}

/// A bounding-volume hierarchy over the bodies, for the first update: nodes split at the
/// median centre along the axis of largest spread, leaves of at most [`LEAF`] bodies.
#[derive(Default)]
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
        let mut spread_lo = vec![f64::INFINITY; n];
        let mut spread_hi = vec![f64::NEG_INFINITY; n];
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

    /// Calls `visit(j)` for every body j ≠ b whose box overlaps body b's.
    #[allow(clippy::too_many_arguments)]
    fn query(
        &self,
        n: usize,
        lower: &[f64],
        upper: &[f64],
        order: &[u32],
        b: usize,
        stack: &mut Vec<u32>,
        mut visit: impl FnMut(usize),
    ) {
        if self.nodes.is_empty() {
            return;
        }
        let (lo, hi) = (&lower[b * n..(b + 1) * n], &upper[b * n..(b + 1) * n]);
        stack.clear();
        stack.push(0);
        while let Some(k) = stack.pop() {
            let k = k as usize;
            let bounds = &self.bounds[2 * n * k..2 * n * (k + 1)];
            if (0..n).any(|a| bounds[a] > hi[a] || lo[a] > bounds[n + a]) {
                continue;
            }
            let (start, end, l, r) = self.nodes[k];
            if l == 0 {
                for &j in &order[start as usize..end as usize] {
                    let j = j as usize;
                    if j != b
                        && (0..n).all(|a| lower[j * n + a] <= hi[a] && lo[a] <= upper[j * n + a])
                    {
                        visit(j);
                    }
                }
            } else {
                stack.push(l);
                stack.push(r);
            }
        }
    }
}
