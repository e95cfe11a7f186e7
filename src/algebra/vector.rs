//! Vectors of Euclidean ℝᴺ.

use super::error::{check_finite, check_same_dim};
use super::{AlgebraError, Bivector, MAX_DIM};
use smallvec::SmallVec;

/// Inline storage: vectors up to N = 8 never touch the heap.
pub(crate) type VecStorage = SmallVec<[f64; 8]>;

/// A vector of Euclidean ℝᴺ: x = Σ xᵢ eᵢ, N ≤ [`MAX_DIM`] chosen at run time.
///
/// Components are 0-based in the API (`x\[0\]` is the e₁ component); text output is 1-based.
///
/// ```
/// use rotorflow::algebra::Vector;
/// let x = Vector::from_components(&[1.0, 2.0, 2.0])?;
/// assert_eq!(x.norm(), 3.0);
/// let plane = Vector::basis(3, 0).wedge(&Vector::basis(3, 1)); // e₁ ∧ e₂
/// assert_eq!(plane.to_string(), "1·e12");
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Vector {
    coords: VecStorage,
}

impl Vector {
    /// Returns the zero vector of ℝⁿ.
    ///
    /// # Panics
    /// If `n > MAX_DIM` (see [`Vector::try_zero`]).
    #[track_caller]
    pub fn zero(n: usize) -> Self {
        Self::try_zero(n).unwrap_or_else(|e| panic!("rotorflow: {e}"))
    }

    /// Returns the zero vector of ℝⁿ, or an error if `n` is too large.
    ///
    /// # Errors
    /// [`AlgebraError::DimensionTooLarge`] if `n > MAX_DIM`.
    pub fn try_zero(n: usize) -> Result<Self, AlgebraError> {
        AlgebraError::check_dimension("vector", n, MAX_DIM)?;
        Ok(Vector {
            coords: crate::numeric::zeros(n),
        })
    }

    /// Returns the basis vector eᵢ₊₁ of ℝⁿ (`i` is 0-based).
    ///
    /// # Panics
    /// If `i ≥ n` or `n > MAX_DIM` (see [`Vector::try_basis`]).
    #[track_caller]
    pub fn basis(n: usize, i: usize) -> Self {
        assert!(
            i < n,
            "rotorflow: basis index {i} out of range for dimension {n}"
        );
        let mut v = Self::zero(n);
        v.coords[i] = 1.0;
        v
    }

    /// Returns the basis vector eᵢ₊₁ of ℝⁿ, or an error for a bad index or dimension.
    ///
    /// # Errors
    /// [`AlgebraError::IndexOutOfRange`] if `i ≥ n`; [`AlgebraError::DimensionTooLarge`] if
    /// `n > MAX_DIM`.
    pub fn try_basis(n: usize, i: usize) -> Result<Self, AlgebraError> {
        let mut v = Self::try_zero(n)?;
        if i >= n {
            return Err(AlgebraError::IndexOutOfRange { index: i, dim: n });
        }
        v.coords[i] = 1.0;
        Ok(v)
    }

    /// Builds a vector from its components x₁ … x_N.
    ///
    /// # Errors
    /// [`AlgebraError::NonFinite`] for NaN or infinite components,
    /// [`AlgebraError::DimensionTooLarge`] for more than [`MAX_DIM`] components.
    pub fn from_components(components: &[f64]) -> Result<Self, AlgebraError> {
        AlgebraError::check_dimension("vector", components.len(), MAX_DIM)?;
        check_finite(components, "vector components")?;
        Ok(Vector {
            coords: SmallVec::from_slice(components),
        })
    }

    pub(crate) fn from_storage(coords: VecStorage) -> Self {
        Vector { coords }
    }

    /// Returns the dimension N.
    #[inline]
    pub fn dim(&self) -> usize {
        self.coords.len()
    }

    /// Returns the components as a slice (0-based).
    #[inline]
    pub fn as_slice(&self) -> &[f64] {
        &self.coords
    }

    /// Returns the components as a mutable slice (0-based).
    #[inline]
    pub fn as_mut_slice(&mut self) -> &mut [f64] {
        &mut self.coords
    }

    /// Returns the Euclidean inner product x · y.
    ///
    /// # Panics
    /// If the dimensions differ.
    #[track_caller]
    pub fn dot(&self, other: &Vector) -> f64 {
        super::error::assert_same_dim(self.dim(), other.dim());
        self.coords
            .iter()
            .zip(&other.coords)
            .map(|(a, b)| a * b)
            .sum()
    }

    /// Returns |x|², the sum of squared components.
    #[inline]
    pub fn norm_squared(&self) -> f64 {
        self.coords.iter().map(|a| a * a).sum()
    }

    /// Returns |x|, computed without overflow or underflow for any finite components.
    pub fn norm(&self) -> f64 {
        crate::numeric::scaled_norm(&self.coords)
    }

    /// Returns x / |x|, or `None` for the zero vector.
    ///
    /// See also [`Vector::normalize`].
    pub fn try_normalize(&self) -> Option<Vector> {
        let n = self.norm();
        if n > 0.0 && n.is_finite() {
            Some(self * (1.0 / n))
        } else {
            None
        }
    }

    /// Returns x / |x|.
    ///
    /// # Panics
    /// For the zero vector (see [`Vector::try_normalize`]).
    #[track_caller]
    pub fn normalize(&self) -> Vector {
        self.try_normalize()
            .expect("rotorflow: cannot normalise the zero vector")
    }

    /// Returns the outer product x ∧ y as a bivector: (x∧y)_ij = xᵢyⱼ − xⱼyᵢ.
    ///
    /// Finite input never gives NaN: if a product overflows, the components are recomputed
    /// from the vectors scaled into [−1, 1], so that x ∧ x is 0 however large x is and a
    /// component too large for an f64 is ±∞.
    ///
    /// # Panics
    /// If the dimensions differ.
    #[track_caller]
    pub fn wedge(&self, other: &Vector) -> Bivector {
        super::error::assert_same_dim(self.dim(), other.dim());
        let (x, y) = (&self.coords, &other.coords);
        // Division by 1 is exact: this is xᵢyⱼ − xⱼyᵢ.
        let mut b = wedge_scaled(x, y, 1.0, 1.0);
        if b.as_slice().iter().any(|c| c.is_nan()) {
            // ∞ − ∞ from an overflowing product of finite components:
            // scale both factors into [−1, 1], then scale the (finite) result back.
            let (sx, sy) = (self.max_abs(), other.max_abs());
            if sx.is_finite() && sy.is_finite() && sx > 0.0 && sy > 0.0 {
                b = wedge_scaled(x, y, sx, sy);
                for c in b.as_mut_slice() {
                    *c = *c * sx * sy;
                }
            }
        }
        b
    }

    /// Returns the contraction x ⌋ B of this vector onto a bivector: the vector
    /// (x⌋B)ⱼ = Σᵢ xᵢ B_ij, i.e. \[B\]ᵀ x.
    ///
    /// This is how a bivector acts on a vector: with ω the angular velocity, x ⌋ ω is the
    /// velocity of the body point x (see the Conventions chapter of the rotorflow book), and
    /// e₁ ⌋ e₁₂ = e₂.
    ///
    /// # Panics
    /// If the dimensions differ.
    #[track_caller]
    pub fn left_contract(&self, b: &Bivector) -> Vector {
        super::error::assert_same_dim(self.dim(), b.dim());
        let n = self.dim();
        let mut out = Vector::zero(n);
        b.contract_into(&self.coords, &mut out.coords);
        out
    }

    /// Checked version of [`Vector::left_contract`].
    ///
    /// # Errors
    /// [`AlgebraError::DimensionMismatch`].
    pub fn try_left_contract(&self, b: &Bivector) -> Result<Vector, AlgebraError> {
        check_same_dim(self.dim(), b.dim())?;
        Ok(self.left_contract(b))
    }

    /// Returns the largest absolute component.
    pub fn max_abs(&self) -> f64 {
        self.coords.iter().fold(0.0, |m, c| m.max(c.abs()))
    }
}

impl std::ops::Index<usize> for Vector {
    type Output = f64;
    #[track_caller]
    fn index(&self, i: usize) -> &f64 {
        &self.coords[i]
    }
}

impl std::ops::IndexMut<usize> for Vector {
    #[track_caller]
    fn index_mut(&mut self, i: usize) -> &mut f64 {
        &mut self.coords[i]
    }
}

/// (x/sx) ∧ (y/sy), component by component ([`Vector::wedge`] with sx = sy = 1, and its
/// overflow path).
fn wedge_scaled(x: &[f64], y: &[f64], sx: f64, sy: f64) -> Bivector {
    let n = x.len();
    let mut b = Bivector::zero(n);
    let c = b.as_mut_slice();
    let mut k = 0;
    for i in 0..n {
        for j in i + 1..n {
            c[k] = (x[i] / sx) * (y[j] / sy) - (x[j] / sx) * (y[i] / sy);
            k += 1;
        }
    }
    b
}
