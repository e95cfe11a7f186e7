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
//! update after the number of bodies changed) sorts every axis and sweeps the axis of
//! largest spread of the centres with an active list.
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
    active: Vec<usize>,
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
            active: Vec::new(),
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
        if lower.len() != upper.len() || lower.len() % n != 0 {
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
        // The axis along which the centres spread most.
        let mut widest = 0;
        let mut widest_variance = -1.0;
        for a in 0..n {
            let (mut s, mut s2) = (0.0, 0.0);
            for b in 0..bodies {
                let c = 0.5 * (self.lower[b * n + a] + self.upper[b * n + a]);
                s += c;
                s2 += c * c;
            }
            let m = bodies.max(1) as f64;
            let variance = s2 / m - (s / m) * (s / m);
            if variance > widest_variance {
                widest_variance = variance;
                widest = a;
            }
        }
        // Sweep: a lower end meets every interval still open.
        let mut active = std::mem::take(&mut self.active);
        active.clear();
        let mut slot = vec![usize::MAX; bodies];
        for k in 0..self.ends[widest].len() {
            let e = self.ends[widest][k];
            let b = e.body();
            if e.is_upper() {
                let s = slot[b];
                let last = *active.last().unwrap_or(&b);
                active.swap_remove(s);
                if last != b {
                    slot[last] = s;
                }
            } else {
                for &other in &active {
                    if self.overlap(b, other) {
                        self.pairs.insert(key(b, other));
                    }
                }
                slot[b] = active.len();
                active.push(b);
            }
        }
        self.active = active;
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
