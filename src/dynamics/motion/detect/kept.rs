//! Pairs of bodies whose contact was found at some placement of one relative to the other,
//! kept for the steps after: while a pair has moved little since ([`placed_within`]), what
//! was found for it holds, and neither the detection (a box manifold, clipped once in many
//! steps) nor `SoftStep` (the points of a manifold, kept as material points) finds it anew.
//!
//! [`placed_within`]: super::bodies::placed_within

/// Pairs of bodies (a < b), each with the numbers kept for it: first the placement at which
/// its contact was found ([`relative_placement`]: b's centre and axes in a's axes, N + N²
/// numbers), then what its keeper adds (a box manifold's normal and points), and the
/// features of its points. The entries are small and sort cheaply; their numbers stay where
/// they were written.
///
/// [`relative_placement`]: super::bodies::relative_placement
#[derive(Clone, Debug, Default)]
pub(crate) struct KeptPairs {
    /// What the entries were found for (a scan's factor and slop, the system's shapes):
    /// entries found for another key do not hold.
    pub key: Option<(u64, u64)>,
    entries: Vec<Entry>,
    data: Vec<f64>,
    features: Vec<u64>,
}

/// A pair, where its numbers and features start in [`KeptPairs`] and how many there are.
#[derive(Clone, Copy, Debug)]
struct Entry {
    pair: (usize, usize),
    start: usize,
    len: usize,
    first: usize,
    count: usize,
}

impl KeptPairs {
    /// Forgets every entry; those added from now on are found for `key`.
    pub fn clear(&mut self, key: Option<(u64, u64)>) {
        self.key = key;
        self.entries.clear();
        self.data.clear();
        self.features.clear();
    }

    /// The number of pairs kept.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// The pair of entry `at`.
    pub fn pair(&self, at: usize) -> (usize, usize) {
        self.entries[at].pair
    }

    /// Starts the entry of `pair`, found at `placement`.
    pub fn push(&mut self, pair: (usize, usize), placement: &[f64]) {
        self.entries.push(Entry {
            pair,
            start: self.data.len(),
            len: placement.len(),
            first: self.features.len(),
            count: 0,
        });
        self.data.extend_from_slice(placement);
    }

    /// Adds `numbers` to the last entry.
    pub fn extend(&mut self, numbers: impl IntoIterator<Item = f64>) {
        debug_assert!(!self.entries.is_empty(), "numbers added before any entry");
        let before = self.data.len();
        self.data.extend(numbers);
        if let Some(last) = self.entries.last_mut() {
            last.len += self.data.len() - before;
        }
    }

    /// Adds a point's `feature` to the last entry.
    pub fn push_feature(&mut self, feature: u64) {
        debug_assert!(!self.entries.is_empty(), "a feature added before any entry");
        self.features.push(feature);
        if let Some(last) = self.entries.last_mut() {
            last.count += 1;
        }
    }

    /// Adds the entry `at` of `from`.
    pub fn copy_entry(&mut self, from: &KeptPairs, at: usize) {
        let e = from.entries[at];
        self.entries.push(Entry {
            start: self.data.len(),
            first: self.features.len(),
            ..e
        });
        self.data.extend_from_slice(from.numbers(at));
        self.features.extend_from_slice(from.features(at));
    }

    /// Sorts the entries by pair, for [`KeptPairs::find`].
    pub fn sort(&mut self) {
        self.entries.sort_unstable_by_key(|e| e.pair);
    }

    /// Where the pair's entry is, if it has one (the entries sorted by pair).
    pub fn find(&self, pair: (usize, usize)) -> Option<usize> {
        let at = self.entries.partition_point(|e| e.pair < pair);
        (self.entries.get(at).is_some_and(|e| e.pair == pair)).then_some(at)
    }

    /// The numbers of entry `at`: its placement, then what its keeper added.
    pub fn numbers(&self, at: usize) -> &[f64] {
        let e = &self.entries[at];
        &self.data[e.start..e.start + e.len]
    }

    /// The placement of entry `at` in `n` dimensions (its first N + N² numbers).
    pub fn placement(&self, at: usize, n: usize) -> &[f64] {
        &self.numbers(at)[..n + n * n]
    }

    /// The features of entry `at`.
    pub fn features(&self, at: usize) -> &[u64] {
        let e = &self.entries[at];
        &self.features[e.first..e.first + e.count]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Entries pushed out of order are found by pair after sorting, each with its own
    /// numbers and features, and copied whole into another list.
    #[test]
    fn entries_keep_their_numbers_through_sorting_and_copying() {
        let mut kept = KeptPairs::default();
        kept.clear(Some((1, 2)));
        kept.push((3, 4), &[1.0, 2.0]);
        kept.extend([3.0]);
        kept.push_feature(7);
        kept.push((0, 5), &[4.0, 5.0]);
        kept.push((0, 1), &[6.0, 7.0]);
        kept.extend([8.0, 9.0]);
        kept.push_feature(8);
        kept.push_feature(9);
        kept.sort();
        let pairs: Vec<_> = (0..kept.len()).map(|k| kept.pair(k)).collect();
        assert_eq!(pairs, [(0, 1), (0, 5), (3, 4)]);
        let at = kept.find((0, 1)).unwrap();
        assert_eq!(kept.numbers(at), [6.0, 7.0, 8.0, 9.0]);
        assert_eq!(kept.features(at), [8, 9]);
        let at = kept.find((3, 4)).unwrap();
        assert_eq!(
            (kept.numbers(at), kept.features(at)),
            (&[1.0, 2.0, 3.0][..], &[7][..])
        );
        assert_eq!(kept.find((0, 2)), None);
        assert_eq!(kept.find((9, 9)), None);
        let mut copy = KeptPairs::default();
        copy.clear(kept.key);
        for k in [2, 0] {
            copy.copy_entry(&kept, k);
        }
        assert_eq!(copy.key, Some((1, 2)));
        assert_eq!(copy.numbers(0), [1.0, 2.0, 3.0]);
        assert_eq!(copy.features(0), [7]);
        assert_eq!(copy.numbers(1), [6.0, 7.0, 8.0, 9.0]);
        assert_eq!(copy.placement(1, 1), [6.0, 7.0]);
        assert_eq!(copy.features(1), [8, 9]);
    }
}
