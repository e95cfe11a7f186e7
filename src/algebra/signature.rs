//! Metric signatures Cl(p, q, r).

use super::{AlgebraError, MAX_DIM, blade};
use std::fmt;

/// The signature Cl(p, q, r) of a Clifford algebra: `p` basis vectors square to +1, `q` to −1
/// and `r` to 0.
///
/// The basis vectors are ordered positive first, then negative, then null: in Cl(p, q, r),
/// e₁ … e_p square to +1, eₚ₊₁ … e_(p+q) to −1 and the last `r` to 0. (This puts the null
/// vector of projective GA last; re-index if you prefer it first.) The dimension is
/// N = p + q + r ≤ [`MAX_DIM`].
///
/// ```
/// use rotorflow::algebra::Signature;
/// let pga = Signature::new(3, 0, 1)?;
/// assert_eq!(pga.dim(), 4);
/// assert_eq!(pga.square(3), 0.0);
/// assert!(Signature::euclidean(3).is_euclidean());
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Signature {
    p: u8,
    q: u8,
    r: u8,
}

impl Signature {
    /// Returns the signature Cl(p, q, r).
    ///
    /// # Errors
    /// [`AlgebraError::DimensionTooLarge`] if p + q + r exceeds [`MAX_DIM`].
    pub fn new(p: usize, q: usize, r: usize) -> Result<Self, AlgebraError> {
        let dim = p + q + r;
        AlgebraError::check_dimension("signature", dim, MAX_DIM)?;
        Ok(Signature {
            p: p as u8,
            q: q as u8,
            r: r as u8,
        })
    }

    /// Returns the Euclidean signature Cl(n, 0, 0).
    ///
    /// # Panics
    /// If `n` exceeds [`MAX_DIM`] (use [`Signature::new`] for a checked version).
    #[track_caller]
    pub fn euclidean(n: usize) -> Self {
        assert!(
            n <= MAX_DIM,
            "rotorflow: dimension {n} exceeds MAX_DIM = {MAX_DIM}"
        );
        Signature {
            p: n as u8,
            q: 0,
            r: 0,
        }
    }

    /// Returns the dimension N = p + q + r of the underlying vector space.
    #[inline]
    pub fn dim(&self) -> usize {
        self.p as usize + self.q as usize + self.r as usize
    }

    /// Returns the number of basis vectors that square to +1.
    #[inline]
    pub fn p(&self) -> usize {
        self.p as usize
    }

    /// Returns the number of basis vectors that square to −1.
    #[inline]
    pub fn q(&self) -> usize {
        self.q as usize
    }

    /// Returns the number of basis vectors that square to 0.
    #[inline]
    pub fn r(&self) -> usize {
        self.r as usize
    }

    /// Returns true if every basis vector squares to +1.
    #[inline]
    pub fn is_euclidean(&self) -> bool {
        self.q == 0 && self.r == 0
    }

    /// Returns true if no basis vector squares to 0 (the pseudoscalar is invertible).
    #[inline]
    pub fn is_nondegenerate(&self) -> bool {
        self.r == 0
    }

    /// Returns the square e_i² ∈ {+1, −1, 0} of basis vector `i` (0-based).
    ///
    /// # Panics
    /// If `i ≥ dim()`.
    #[track_caller]
    pub fn square(&self, i: usize) -> f64 {
        assert!(
            i < self.dim(),
            "rotorflow: basis index {i} out of range for dimension {}",
            self.dim()
        );
        if i < self.p as usize {
            1.0
        } else if i < (self.p + self.q) as usize {
            -1.0
        } else {
            0.0
        }
    }

    /// Bit mask of the basis vectors that square to −1.
    #[inline]
    pub(crate) fn negative_mask(&self) -> u64 {
        blade::range_mask(self.p as usize, (self.p + self.q) as usize)
    }

    /// Bit mask of the basis vectors that square to 0.
    #[inline]
    pub(crate) fn null_mask(&self) -> u64 {
        blade::range_mask((self.p + self.q) as usize, self.dim())
    }

    /// Returns the product of the squares of the basis vectors that blades `a` and `b` share:
    /// the metric factor of the geometric product e_a e_b (0, +1 or −1).
    #[inline]
    pub(crate) fn metric_factor(&self, a: u64, b: u64) -> f64 {
        let common = a & b;
        if common & self.null_mask() != 0 {
            0.0
        } else if (common & self.negative_mask()).count_ones() % 2 == 1 {
            -1.0
        } else {
            1.0
        }
    }
}

impl fmt::Display for Signature {
    /// Formats as `Cl(p,q,r)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Cl({},{},{})", self.p, self.q, self.r)
    }
}
