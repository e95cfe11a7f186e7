//! Basis blades as bit masks.
//!
//! The basis blade e_(i₁ i₂ … i_k) (i₁ < i₂ < … < i_k, 0-based) is the bit mask with bits
//! i₁ … i_k set, as in kingdon and geometric_algebra: e₁ = 0b1, e₂ = 0b10, e₁₂ = 0b11. The
//! product of two basis blades is, up to sign and metric, the blade `a ^ b` (exclusive or);
//! the sign counts the transpositions needed to sort the concatenated indices. A `u64` mask
//! caps the dimension at 64, which is [`super::MAX_DIM`].

use super::AlgebraError;

/// Returns the grade (number of basis vectors) of blade `a`.
#[inline]
pub fn grade(a: u64) -> usize {
    a.count_ones() as usize
}

/// Returns the sign (+1 or −1) of reordering e_a e_b into the canonical order of e_(a^b),
/// ignoring the metric.
///
/// The number of transpositions is Σ_(j ∈ b) #{i ∈ a : i > j}; its parity is the parity of
/// `suffix_parity(a) & b`, so the sign costs a handful of bit operations for any N ≤ 64.
#[inline]
pub fn reorder_sign(a: u64, b: u64) -> f64 {
    parity_sign(suffix_parity(a) & b)
}

/// Returns the mask whose bit j is the parity of the bits of `a` strictly above j (a prefix
/// XOR from the top, in six shift steps).
#[inline]
pub fn suffix_parity(a: u64) -> u64 {
    let mut x = a >> 1;
    x ^= x >> 1;
    x ^= x >> 2;
    x ^= x >> 4;
    x ^= x >> 8;
    x ^= x >> 16;
    x ^= x >> 32;
    x
}

/// Returns +1 if `x` has an even number of set bits, −1 otherwise.
#[inline]
pub fn parity_sign(x: u64) -> f64 {
    if x.count_ones() & 1 == 0 { 1.0 } else { -1.0 }
}

/// Returns the sign (−1)^(k(k−1)/2) that the reverse puts on a blade of grade `k`.
#[inline]
pub fn reverse_sign(k: usize) -> f64 {
    if (k / 2).is_multiple_of(2) { 1.0 } else { -1.0 }
}

/// Returns the sign (−1)^k that the grade involution puts on a blade of grade `k`.
#[inline]
pub fn involution_sign(k: usize) -> f64 {
    if k.is_multiple_of(2) { 1.0 } else { -1.0 }
}

/// Returns the sign (−1)^(k(k+1)/2) that the Clifford conjugate puts on a blade of grade `k`.
#[inline]
pub fn conjugate_sign(k: usize) -> f64 {
    reverse_sign(k) * involution_sign(k)
}

/// Returns the mask with bits `lo..hi` set.
#[inline]
pub fn range_mask(lo: usize, hi: usize) -> u64 {
    full_mask(hi) & !full_mask(lo)
}

/// Returns the mask with the lowest `n` bits set (the pseudoscalar of dimension `n`).
#[inline]
pub fn full_mask(n: usize) -> u64 {
    if n >= 64 { u64::MAX } else { (1u64 << n) - 1 }
}

/// Returns the 0-based indices of the basis vectors in blade `a`, ascending.
pub fn indices(a: u64) -> impl Iterator<Item = usize> {
    (0..64).filter(move |i| a >> i & 1 == 1)
}

/// Returns the user-facing name of blade `a` in dimension `n`: `1` for the scalar, `e12` for
/// e₁∧e₂ (1-based). In dimension 10 and above the indices are separated by `_` (`e1_10`) so
/// that names stay unambiguous.
pub fn name(a: u64, n: usize) -> String {
    if a == 0 {
        return "1".to_string();
    }
    let parts: Vec<String> = indices(a).map(|i| (i + 1).to_string()).collect();
    if n >= 10 {
        format!("e{}", parts.join("_"))
    } else {
        format!("e{}", parts.concat())
    }
}

/// Reads a blade name in dimension `n`: `1` for the scalar; `e` followed by 1-based indices
/// written as digits (`e13`), as subscripts (`e₁₃`), separated by `_` (`e1_3`) or each with
/// its own `e` (`e1e3`). Below dimension 10 a run of digits is one index per digit (`e13` is
/// e₁∧e₃); from dimension 10 on a run is one index (`e10`, `e1_10`), as [`name`] writes
/// them. Indices in any order are sorted, with the sign of the permutation (`e31` = −e₁₃).
///
/// Returns (sign, mask).
pub(crate) fn parse_name(text: &str, n: usize) -> Result<(f64, u64), AlgebraError> {
    let bad = |reason: &'static str| AlgebraError::InvalidBladeName {
        name: text.to_string(),
        reason,
    };
    let t = text.trim();
    if t == "1" {
        return Ok((1.0, 0));
    }
    let Some(rest) = t.strip_prefix('e') else {
        return Err(bad("a blade name is `1` or starts with `e`, as in e13"));
    };
    // Split into runs of digits (ASCII or subscript) separated by `_` or `e`.
    let mut runs: Vec<String> = vec![String::new()];
    for ch in rest.chars() {
        match ch {
            '0'..='9' => runs.last_mut().unwrap().push(ch),
            '₀'..='₉' => {
                let d = ch as u32 - '₀' as u32;
                runs.last_mut()
                    .unwrap()
                    .push(char::from_digit(d, 10).unwrap());
            }
            '_' | 'e' => runs.push(String::new()),
            _ => {
                return Err(bad(
                    "only digits, subscript digits, `_` and `e` may follow `e`",
                ));
            }
        }
    }
    if runs.iter().any(|r| r.is_empty()) {
        return Err(bad("every `e` or `_` must be followed by an index"));
    }
    let mut indices: Vec<usize> = Vec::new();
    for run in &runs {
        if n < 10 {
            indices.extend(run.bytes().map(|b| (b - b'0') as usize));
        } else {
            indices.push(run.parse().map_err(|_| bad("index too large"))?);
        }
    }
    let mut mask = 0u64;
    let mut sign = 1.0;
    for &i in &indices {
        if i == 0 || i > n {
            return Err(bad("indices are 1-based and at most the dimension"));
        }
        let bit = 1u64 << (i - 1);
        if mask & bit != 0 {
            return Err(bad("an index is repeated"));
        }
        // e_mask eᵢ = ± e_{mask|i}: eᵢ moves left past the factors with larger indices.
        sign *= reorder_sign(mask, bit);
        mask |= bit;
    }
    Ok((sign, mask))
}

/// Returns the sign s with e_a ∧ (s e_ā) = e₁…ₙ, where ā is the complement of `a`
/// (the right complement of Lengyel's exterior algebra; metric-free).
#[inline]
pub fn right_complement_sign(a: u64, n: usize) -> f64 {
    reorder_sign(a, full_mask(n) & !a)
}

/// Returns the sign s with (s e_ā) ∧ e_a = e₁…ₙ (the left complement; it undoes the
/// right complement).
#[inline]
pub fn left_complement_sign(a: u64, n: usize) -> f64 {
    reorder_sign(full_mask(n) & !a, a)
}

/// Returns the bit masks of all blades of grade `k` in dimension `n`, in lexicographic order of
/// their index lists (e12, e13, …, e1n, e23, …).
#[cfg(test)]
pub fn blades_of_grade(n: usize, k: usize) -> Vec<u64> {
    let mut out = Vec::new();
    let mut idx: Vec<usize> = (0..k).collect();
    if k > n {
        return out;
    }
    loop {
        out.push(idx.iter().fold(0u64, |m, &i| m | 1 << i));
        // Advance to the next combination in lexicographic order.
        let mut pos = k;
        loop {
            if pos == 0 {
                return out;
            }
            pos -= 1;
            if idx[pos] < n - k + pos {
                idx[pos] += 1;
                for j in pos + 1..k {
                    idx[j] = idx[j - 1] + 1;
                }
                break;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every name that `name` writes reads back to its mask, in every dimension up to 12.
    #[test]
    fn parse_name_inverts_name() {
        for n in 1..=12 {
            for k in 0..=n.min(4) {
                for b in blades_of_grade(n, k) {
                    assert_eq!(parse_name(&name(b, n), n), Ok((1.0, b)), "n = {n}");
                }
            }
        }
    }

    #[test]
    fn parse_name_accepts_the_other_spellings_and_refuses_bad_names() {
        for s in ["e13", "e1e3", "e1_3", "e₁₃", "e₁e₃"] {
            assert_eq!(parse_name(s, 4), Ok((1.0, 0b101)), "{s}");
        }
        assert_eq!(parse_name("e31", 4), Ok((-1.0, 0b101)));
        assert_eq!(parse_name("e321", 4), Ok((-1.0, 0b111)));
        assert_eq!(parse_name("e2e1e3", 4), Ok((-1.0, 0b111)));
        assert_eq!(parse_name("e10", 12), Ok((1.0, 1 << 9)));
        assert_eq!(parse_name("e1_10", 12), Ok((1.0, 1 | 1 << 9)));
        for bad in [
            "", "e", "x12", "e1_", "e15", "e0", "e11", "e1.5", "13", "e_1",
        ] {
            assert!(
                matches!(
                    parse_name(bad, 4),
                    Err(AlgebraError::InvalidBladeName { .. })
                ),
                "{bad:?} accepted"
            );
        }
    }

    #[test]
    fn reorder_sign_of_small_products() {
        // e1 e2 = e12, e2 e1 = -e12, e12 e13 -> e1 e2 e1 e3 = -e23 (sign -1, metric +1).
        assert_eq!(reorder_sign(0b01, 0b10), 1.0);
        assert_eq!(reorder_sign(0b10, 0b01), -1.0);
        assert_eq!(reorder_sign(0b011, 0b101), -1.0);
    }

    #[test]
    fn fast_reorder_sign_matches_counting_transpositions() {
        fn slow(a: u64, b: u64) -> f64 {
            let mut swaps = 0u32;
            for j in 0..64 {
                if b >> j & 1 == 1 {
                    swaps += a.checked_shr(j + 1).unwrap_or(0).count_ones();
                }
            }
            if swaps.is_multiple_of(2) { 1.0 } else { -1.0 }
        }
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        for _ in 0..10_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let (a, b) = (x, x.rotate_left(29) ^ 0xA5A5);
            assert_eq!(reorder_sign(a, b), slow(a, b));
            assert_eq!(reorder_sign(a & 0xff, b & 0xff), slow(a & 0xff, b & 0xff));
        }
    }

    #[test]
    fn blades_of_grade_are_lexicographic() {
        let names: Vec<String> = blades_of_grade(4, 2).iter().map(|&b| name(b, 4)).collect();
        assert_eq!(names, ["e12", "e13", "e14", "e23", "e24", "e34"]);
        assert_eq!(blades_of_grade(3, 0), vec![0]);
        assert_eq!(blades_of_grade(3, 3), vec![0b111]);
        assert!(blades_of_grade(2, 3).is_empty());
    }

    #[test]
    fn complements_invert_each_other() {
        for n in 1..6 {
            for a in 0..(1u64 << n) {
                let c = full_mask(n) & !a;
                // left complement of the right complement gives back e_a with sign +1.
                let s = right_complement_sign(a, n) * left_complement_sign(c, n);
                assert_eq!(s, 1.0, "n={n} a={a:b}");
            }
        }
    }
}
