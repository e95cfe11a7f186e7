//! Bivectors of Euclidean ℝᴺ: planes, angular velocities and momenta.

use super::error::{assert_same_dim, check_finite, check_same_dim, within};
use super::{AlgebraError, MAX_DIM};
use crate::numeric::scaled_norm;
use nalgebra::DMatrix;
use smallvec::SmallVec;

/// Inline storage: the 28 components of a bivector in N = 8 fit without touching the heap.
pub(crate) type BivStorage = SmallVec<[f64; 28]>;

/// Dense scratch for an N×N skew matrix; stays on the stack up to N = 12.
pub(crate) type DenseScratch = SmallVec<[f64; 144]>;

/// A bivector of Euclidean ℝᴺ: B = Σ_(i<j) B_ij eᵢ∧eⱼ, the algebra's object for oriented planes,
/// angular velocities, angular momenta and torques.
///
/// Components are stored in lexicographic order of the pairs (see the Conventions chapter of
/// the rotorflow book): for N = 4, `[B12, B13, B14, B23, B24, B34]`. The skew matrix of B is
/// \[B\] with \[B\]_ij = B_ij, \[B\]_ji = −B_ij. Indices in the API are 0-based (`get(0, 1)`
/// is B₁₂); text is 1-based.
///
/// # Contents
/// - Construction: [`Bivector::zero`], [`Bivector::from_components`],
///   [`Bivector::from_plane`], [`Vector::wedge`](crate::algebra::Vector::wedge), [`Bivector::from_skew_matrix`].
/// - Algebra: `+ − ×scalar`, [`Bivector::commutator`] (the so(N) bracket, O(N³)),
///   [`Bivector::inner`], [`Vector::left_contract`](crate::algebra::Vector::left_contract) (x ⌋ B).
/// - Invariants: [`Bivector::norm`], [`Bivector::square_scalar`],
///   [`Bivector::characteristic_coefficients`], [`Bivector::pfaffian`],
///   [`Bivector::decompose`] (the invariant decomposition).
/// - Rotations: [`Bivector::exp`] gives the rotor e^B.
///
/// ```
/// use rotorflow::algebra::Bivector;
/// let a = Bivector::from_plane(3, 0, 1, 1.0)?; // e₁₂
/// let b = Bivector::from_plane(3, 1, 2, 1.0)?; // e₂₃
/// assert_eq!(a.commutator(&b), Bivector::from_plane(3, 0, 2, 1.0)?); // e₁₂ × e₂₃ = e₁₃
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Bivector {
    dim: usize,
    coeffs: BivStorage,
}

/// Default relative tolerance of [`Bivector::from_skew_matrix`] on the symmetric part of its
/// input: a few thousand ulps, room for the round-off of a matrix computed in floating point.
pub const SKEW_TOLERANCE: f64 = 1e-12;

/// Returns the number of bivector components in dimension `n`, N(N−1)/2.
#[inline]
pub fn bivector_len(n: usize) -> usize {
    n * n.saturating_sub(1) / 2
}

/// Returns the position of the pair (i, j), i < j (0-based), in the lexicographic component
/// order of dimension `n`.
#[inline]
pub const fn pair_index(n: usize, i: usize, j: usize) -> usize {
    debug_assert!(i < j && j < n);
    i * (2 * n - i - 1) / 2 + (j - i - 1)
}

/// Returns the pairs (i, j), i < j (0-based), in the lexicographic component order.
pub fn pairs(n: usize) -> impl Iterator<Item = (usize, usize)> {
    (0..n).flat_map(move |i| (i + 1..n).map(move |j| (i, j)))
}

/// Returns the 1-based name of the plane eᵢ∧eⱼ (0-based i < j) in dimension `n`, as text,
/// tables and `Display` print it: `"12"` for e₁∧e₂, and `"1_10"` from N = 10 on, where the
/// indices need a separator to stay unambiguous.
///
/// ```
/// use rotorflow::algebra::plane_name;
/// assert_eq!(plane_name(4, 0, 1), "12");
/// assert_eq!(plane_name(12, 0, 9), "1_10");
/// ```
pub fn plane_name(n: usize, i: usize, j: usize) -> String {
    crate::algebra::blade::name((1 << i) | (1 << j), n)[1..].to_string()
}

impl Bivector {
    /// Returns the zero bivector of ℝⁿ.
    ///
    /// # Panics
    /// If `n > MAX_DIM` (see [`Bivector::try_zero`]).
    #[track_caller]
    pub fn zero(n: usize) -> Self {
        Self::try_zero(n).unwrap_or_else(|e| panic!("rotorflow: {e}"))
    }

    /// Returns the zero bivector of ℝⁿ, or an error if `n` is too large.
    ///
    /// # Errors
    /// [`AlgebraError::DimensionTooLarge`] if `n > MAX_DIM`.
    pub fn try_zero(n: usize) -> Result<Self, AlgebraError> {
        AlgebraError::check_dimension("bivector", n, MAX_DIM)?;
        Ok(Bivector {
            dim: n,
            coeffs: crate::numeric::zeros(bivector_len(n)),
        })
    }

    /// Builds a bivector of ℝⁿ from its N(N−1)/2 components in lexicographic order
    /// (12, 13, …, 1N, 23, …).
    ///
    /// # Errors
    /// [`AlgebraError::WrongComponentCount`], [`AlgebraError::NonFinite`],
    /// [`AlgebraError::DimensionTooLarge`].
    pub fn from_components(n: usize, components: &[f64]) -> Result<Self, AlgebraError> {
        AlgebraError::check_dimension("bivector", n, MAX_DIM)?;
        if components.len() != bivector_len(n) {
            return Err(AlgebraError::WrongComponentCount {
                what: "bivector",
                expected: bivector_len(n),
                found: components.len(),
            });
        }
        check_finite(components, "bivector components")?;
        Ok(Bivector {
            dim: n,
            coeffs: SmallVec::from_slice(components),
        })
    }

    /// Returns `magnitude · eᵢ∧eⱼ` in ℝⁿ (0-based `i`, `j`; `i > j` flips the sign).
    ///
    /// # Errors
    /// [`AlgebraError::IndexOutOfRange`], [`AlgebraError::RepeatedIndex`],
    /// [`AlgebraError::NonFinite`].
    pub fn from_plane(n: usize, i: usize, j: usize, magnitude: f64) -> Result<Self, AlgebraError> {
        for &k in &[i, j] {
            if k >= n {
                return Err(AlgebraError::IndexOutOfRange { index: k, dim: n });
            }
        }
        if i == j {
            return Err(AlgebraError::RepeatedIndex { index: i });
        }
        check_finite(&[magnitude], "plane magnitude")?;
        let mut b = Bivector::zero(n);
        b.set(i, j, magnitude);
        Ok(b)
    }

    pub(crate) fn from_storage(dim: usize, coeffs: BivStorage) -> Self {
        debug_assert_eq!(coeffs.len(), bivector_len(dim));
        Bivector { dim, coeffs }
    }

    /// Returns the dimension N of the space (not the number of components).
    #[inline]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Returns the N(N−1)/2 components in lexicographic order.
    #[inline]
    pub fn as_slice(&self) -> &[f64] {
        &self.coeffs
    }

    /// Returns the components mutably, in lexicographic order.
    #[inline]
    pub fn as_mut_slice(&mut self) -> &mut [f64] {
        &mut self.coeffs
    }

    /// Returns B_ij = \[B\]_ij (0-based; antisymmetric, 0 on the diagonal).
    ///
    /// # Panics
    /// If an index is out of range.
    #[track_caller]
    pub fn get(&self, i: usize, j: usize) -> f64 {
        let n = self.dim;
        assert!(i < n && j < n, "rotorflow: index out of range");
        match i.cmp(&j) {
            std::cmp::Ordering::Less => self.coeffs[pair_index(n, i, j)],
            std::cmp::Ordering::Greater => -self.coeffs[pair_index(n, j, i)],
            std::cmp::Ordering::Equal => 0.0,
        }
    }

    /// Sets B_ij = value (and so B_ji = −value); 0-based.
    ///
    /// # Panics
    /// If an index is out of range or `i == j`.
    #[track_caller]
    pub fn set(&mut self, i: usize, j: usize, value: f64) {
        let n = self.dim;
        super::error::assert_plane(i, j, n);
        if i < j {
            self.coeffs[pair_index(n, i, j)] = value;
        } else {
            self.coeffs[pair_index(n, j, i)] = -value;
        }
    }

    /// Returns the skew matrix \[B\] (N×N, \[B\]_ij = B_ij).
    pub fn to_skew_matrix(&self) -> DMatrix<f64> {
        let n = self.dim;
        let mut m = DMatrix::zeros(n, n);
        for ((i, j), &c) in pairs(n).zip(self.coeffs.iter()) {
            m[(i, j)] = c;
            m[(j, i)] = -c;
        }
        m
    }

    /// Builds the bivector of a skew matrix: B_ij = ½(A_ij − A_ji).
    ///
    /// # Errors
    /// [`AlgebraError::NotSquare`]; [`AlgebraError::NotSkewSymmetric`] if
    /// max |A_ij + A_ji| > [`SKEW_TOLERANCE`] · max |A_ij| (the antisymmetric part is taken
    /// otherwise; [`Bivector::from_skew_matrix_eps`] chooses the tolerance);
    /// [`AlgebraError::NonFinite`].
    pub fn from_skew_matrix(a: &DMatrix<f64>) -> Result<Self, AlgebraError> {
        Self::from_skew_matrix_eps(a, SKEW_TOLERANCE)
    }

    /// Like [`Bivector::from_skew_matrix`] with an explicit relative tolerance on the
    /// symmetric part: max |A_ij + A_ji| ≤ `tolerance` · max |A_ij|.
    ///
    /// # Errors
    /// As [`Bivector::from_skew_matrix`].
    pub fn from_skew_matrix_eps(a: &DMatrix<f64>, tolerance: f64) -> Result<Self, AlgebraError> {
        Self::from_skew_entries(a.nrows(), a.ncols(), tolerance, |i, j| a[(i, j)])
    }

    pub(crate) fn from_skew_entries(
        rows: usize,
        cols: usize,
        relative_tolerance: f64,
        entry: impl Fn(usize, usize) -> f64,
    ) -> Result<Self, AlgebraError> {
        if rows != cols {
            return Err(AlgebraError::NotSquare { rows, cols });
        }
        let n = rows;
        AlgebraError::check_dimension("bivector", n, MAX_DIM)?;
        let mut scale = 0.0f64;
        let mut deviation = 0.0f64;
        for i in 0..n {
            for j in 0..n {
                let x = entry(i, j);
                if !x.is_finite() {
                    return Err(AlgebraError::NonFinite {
                        what: "skew matrix",
                    });
                }
                scale = scale.max(x.abs());
                deviation = deviation.max((x + entry(j, i)).abs());
            }
        }
        let tolerance = relative_tolerance * scale;
        if !within(deviation, tolerance) {
            return Err(AlgebraError::NotSkewSymmetric {
                deviation,
                tolerance,
            });
        }
        let mut b = Bivector::zero(n);
        for (k, (i, j)) in pairs(n).enumerate() {
            b.coeffs[k] = 0.5 * (entry(i, j) - entry(j, i));
        }
        Ok(b)
    }

    /// Returns ⟨A, B⟩ = Σ_(i<j) A_ij B_ij (the pairing of the rotorflow book's Conventions
    /// chapter; kinetic energy is ½⟨ω, L⟩).
    ///
    /// Note ⟨A, B⟩ = −⟨A B⟩₀: the geometric scalar product of two bivectors has the opposite
    /// sign.
    ///
    /// # Panics
    /// If the dimensions differ.
    #[track_caller]
    pub fn inner(&self, other: &Bivector) -> f64 {
        assert_same_dim(self.dim, other.dim);
        self.coeffs
            .iter()
            .zip(&other.coeffs)
            .map(|(a, b)| a * b)
            .sum()
    }

    /// Returns |B|² = Σ_(i<j) B_ij² (= ⟨B B̃⟩₀ = −⟨B²⟩₀).
    #[inline]
    pub fn norm_squared(&self) -> f64 {
        self.coeffs.iter().map(|c| c * c).sum()
    }

    /// Returns |B|, without overflow or underflow for any finite components.
    pub fn norm(&self) -> f64 {
        scaled_norm(&self.coeffs)
    }

    /// Returns the largest absolute component.
    pub fn max_abs(&self) -> f64 {
        self.coeffs.iter().fold(0.0, |m, c| m.max(c.abs()))
    }

    /// Returns the scalar part of the geometric square, ⟨B²⟩₀ = −|B|² (a first invariant).
    pub fn square_scalar(&self) -> f64 {
        -self.norm_squared()
    }

    /// Returns the commutator product A × B = ½(AB − BA), which for bivectors is again a
    /// bivector: the Lie bracket of so(N), \[A × B\] = \[A\]\[B\] − \[B\]\[A\].
    ///
    /// Computed from components in O(N³) without forming a multivector. Euler's equations
    /// read dL/dt = ω × L (see the Conventions chapter of the rotorflow book).
    ///
    /// # Panics
    /// If the dimensions differ (see [`Bivector::try_commutator`]).
    #[track_caller]
    pub fn commutator(&self, other: &Bivector) -> Bivector {
        assert_same_dim(self.dim, other.dim);
        let mut out = Bivector::zero(self.dim);
        commutator_into(self, other, &mut out.coeffs);
        out
    }

    /// Checked version of [`Bivector::commutator`].
    ///
    /// # Errors
    /// [`AlgebraError::DimensionMismatch`].
    pub fn try_commutator(&self, other: &Bivector) -> Result<Bivector, AlgebraError> {
        check_same_dim(self.dim, other.dim)?;
        Ok(self.commutator(other))
    }

    /// Turns the bivector in place by `angle` in the plane eᵢ∧eⱼ (0-based, from eᵢ toward eⱼ):
    /// B ← R B R̃ with R = exp(−angle/2 · eᵢⱼ), i.e. \[B\] ← Q\[B\]Qᵀ with Q a Givens rotation.
    ///
    /// Only the components with one index in {i, j} change, so this costs O(N) and never
    /// allocates: the building block of the splitting integrators.
    ///
    /// # Panics
    /// If `i` or `j` is out of range or `i == j`.
    #[track_caller]
    pub fn rotate_in_plane_mut(&mut self, i: usize, j: usize, angle: f64) {
        let n = self.dim;
        super::error::assert_plane(i, j, n);
        let (s, m) = crate::numeric::sin_cos_minus_one(angle);
        self.rotate_in_plane_sin_cm1(i, j, s, m);
    }

    /// [`Bivector::rotate_in_plane_mut`] given s = sin θ and m = cos θ − 1 (crate-internal:
    /// the splitting shares one evaluation between the momentum and the attitude). `i`, `j`
    /// must be valid and distinct.
    ///
    /// Each pair is updated as x + (m x − s y) rather than c x − s y: with s and m accurate
    /// relative to themselves the rotation is orthogonal to O(εθ²) instead of ε, so millions
    /// of small rotations do not random-walk the Casimirs through c² + s² − 1.
    pub(crate) fn rotate_in_plane_sin_cm1(&mut self, i: usize, j: usize, s: f64, m: f64) {
        let n = self.dim;
        debug_assert!(i < n && j < n && i != j);
        // Turning by θ in eⱼ∧eᵢ is turning by −θ in eᵢ∧eⱼ: work with lo < hi.
        let (lo, hi, s) = if i < j { (i, j, s) } else { (j, i, -s) };
        // B'_lo,k = c B_lo,k − s B_hi,k and B'_hi,k = s B_lo,k + c B_hi,k for every other k
        // (c = 1 + m), read from the packed storage where B_lo,k = ±x and B_hi,k = ±y. Row a
        // holds B_a,k for k > a contiguously from row_start(a); for k < a, B_a,k = −B_k,a
        // sits in row k. The three ranges of k give three sign patterns (derived from
        // x' = c x − s σ y, y' = s σ x + c y with σ the product of the two storage signs).
        let row_start = |a: usize| a * (2 * n - a - 1) / 2;
        let coeffs = &mut self.coeffs[..];
        let mut start_k = 0;
        for k in 0..lo {
            // both stored as B_k,lo and B_k,hi (signs −1, −1: σ = +1)
            let (p, q) = (start_k + lo - k - 1, start_k + hi - k - 1);
            let (x, y) = (coeffs[p], coeffs[q]);
            coeffs[p] = x + (m * x - s * y);
            coeffs[q] = y + (s * x + m * y);
            start_k += n - k - 1;
        }
        let lo_row = row_start(lo);
        for k in lo + 1..hi {
            // B_lo,k stored in row lo (sign +1), B_hi,k as B_k,hi in row k (sign −1): σ = −1
            let p = lo_row + k - lo - 1;
            let q = row_start(k) + hi - k - 1;
            let (x, y) = (coeffs[p], coeffs[q]);
            coeffs[p] = x + (m * x + s * y);
            coeffs[q] = y + (m * y - s * x);
        }
        // k > hi: both rows contiguous (signs +1, +1: σ = +1).
        let count = n - hi - 1;
        let p0 = lo_row + hi - lo;
        let q0 = row_start(hi);
        let (head, tail) = coeffs.split_at_mut(q0);
        for (x, y) in head[p0..p0 + count].iter_mut().zip(&mut tail[..count]) {
            let (a, b) = (*x, *y);
            *x = a + (m * a - s * b);
            *y = b + (s * a + m * b);
        }
    }

    /// Writes the contraction x ⌋ B (out_j = Σᵢ xᵢ B_ij) into `out`.
    pub(crate) fn contract_into(&self, x: &[f64], out: &mut [f64]) {
        let n = self.dim;
        out.iter_mut().for_each(|o| *o = 0.0);
        let mut k = 0;
        for i in 0..n {
            for j in i + 1..n {
                let b = self.coeffs[k];
                out[j] += x[i] * b;
                out[i] -= x[j] * b;
                k += 1;
            }
        }
    }

    /// Returns the coefficients c_k of the characteristic polynomial of the skew matrix,
    /// det(λ − \[B\]) = Σ_k c_k λᴺ⁻²ᵏ, for k = 0 … ⌊N/2⌋ (c₀ = 1; odd powers vanish).
    ///
    /// c_k is the k-th elementary symmetric polynomial of the squared plane magnitudes θᵢ² of
    /// the invariant decomposition; equivalently c_k = |B^(∧k)/k!|². These are the Casimirs of
    /// the free rigid body (c₁ = |B|²; in 4D c₂ = Pf(\[B\])²). Computed from the invariant
    /// decomposition in O(N³).
    pub fn characteristic_coefficients(&self) -> Vec<f64> {
        let thetas = self.decompose().magnitudes();
        let m = self.dim / 2;
        let mut e = vec![0.0; m + 1];
        e[0] = 1.0;
        for t in thetas {
            let t2 = t * t;
            for k in (1..=m).rev() {
                e[k] += e[k - 1] * t2;
            }
        }
        e
    }

    /// Returns the Pfaffian Pf(\[B\]) of the skew matrix (0 in odd N).
    ///
    /// Pf² = det \[B\]; Pf(θ e₁₂) = θ, and in 4D Pf = B₁₂B₃₄ − B₁₃B₂₄ + B₁₄B₂₃. It is the
    /// coefficient of B^(∧N/2)/(N/2)! on the unit pseudoscalar. Computed by the skew
    /// Parlett–Reid elimination with pivoting (Wimmer, ACM TOMS 38 (2012), `pfaffian_LTL`),
    /// O(N³).
    pub fn pfaffian(&self) -> f64 {
        let n = self.dim;
        if n % 2 == 1 {
            return 0.0;
        }
        if n == 0 {
            return 1.0;
        }
        let mut a: DenseScratch = SmallVec::from_elem(0.0, n * n);
        self.fill_dense(&mut a);
        let at = |a: &DenseScratch, i: usize, j: usize| a[i * n + j];
        let mut pf = 1.0;
        let mut k = 0;
        while k + 1 < n {
            // Pivot: the largest entry in column k below the diagonal.
            let mut kp = k + 1;
            let mut best = at(&a, k + 1, k).abs();
            for i in k + 2..n {
                let v = at(&a, i, k).abs();
                if v > best {
                    best = v;
                    kp = i;
                }
            }
            if kp != k + 1 {
                for c in 0..n {
                    a.swap((k + 1) * n + c, kp * n + c);
                }
                for r in 0..n {
                    a.swap(r * n + k + 1, r * n + kp);
                }
                pf = -pf;
            }
            let piv = at(&a, k, k + 1);
            if piv == 0.0 {
                return 0.0;
            }
            pf *= piv;
            if k + 2 < n {
                let tau: SmallVec<[f64; 16]> = (k + 2..n).map(|j| at(&a, k, j) / piv).collect();
                let col: SmallVec<[f64; 16]> = (k + 2..n).map(|i| at(&a, i, k + 1)).collect();
                for (ii, i) in (k + 2..n).enumerate() {
                    for (jj, j) in (k + 2..n).enumerate() {
                        a[i * n + j] += tau[ii] * col[jj] - col[ii] * tau[jj];
                    }
                }
            }
            k += 2;
        }
        pf
    }

    /// Writes the dense row-major skew matrix into `a` (length N²).
    pub(crate) fn fill_dense(&self, a: &mut [f64]) {
        fill_dense_packed(self.dim, &self.coeffs, a);
    }
}

/// Above this N the commutator is one dense matrix product (heap-allocated scratch).
const COMMUTATOR_GEMM_MIN_DIM: usize = 12;

/// Writes the dense row-major skew matrix of packed components `c` (dimension `n`) into `a`.
fn fill_dense_packed(n: usize, c: &[f64], a: &mut [f64]) {
    let mut k = 0;
    for i in 0..n {
        a[i * n + i] = 0.0;
        for j in i + 1..n {
            a[i * n + j] = c[k];
            a[j * n + i] = -c[k];
            k += 1;
        }
    }
}

/// \[A × B\] = \[A\]\[B\] − \[B\]\[A\], upper triangle only: c_ij = Σ_k (B_ik A_jk − A_ik B_jk), where both
/// sums run along contiguous rows of the dense skew matrices.
pub(crate) fn commutator_into(a: &Bivector, b: &Bivector, out: &mut [f64]) {
    commutator_packed(a.dim, &a.coeffs, &b.coeffs, out);
}

/// [`commutator_into`] on packed component slices of dimension `n`. The integrators'
/// fixed-size kernels call it on stack arrays with a constant `n`: this dispatch is always
/// inlined so that the constant selects its kernel at compile time. The large-N branches
/// live in [`commutator_large`], which keeps the inlined part small.
#[inline(always)]
pub(crate) fn commutator_packed(n: usize, a: &[f64], b: &[f64], out: &mut [f64]) {
    match n {
        3 => {
            // e12, e13, e23 ↔ cross product of the dual vectors; written out by hand.
            let (a12, a13, a23) = (a[0], a[1], a[2]);
            let (b12, b13, b23) = (b[0], b[1], b[2]);
            out[0] = a23 * b13 - a13 * b23;
            out[1] = a12 * b23 - a23 * b12;
            out[2] = a13 * b12 - a12 * b13;
        }
        4 => commutator_fixed::<4>(a, b, out),
        5 => commutator_fixed::<5>(a, b, out),
        6 => commutator_fixed::<6>(a, b, out),
        7 => commutator_fixed::<7>(a, b, out),
        8 => commutator_fixed::<8>(a, b, out),
        _ => commutator_large(n, a, b, out),
    }
}

/// [`commutator_packed`] for N ≤ 2 and N > 8.
fn commutator_large(n: usize, a: &[f64], b: &[f64], out: &mut [f64]) {
    match n {
        0..=2 => out.iter_mut().for_each(|o| *o = 0.0),
        // Up to N = 16 the product on the stack, in 16 × 16 arrays padded with zeros so that
        // every row operation has a fixed length the compiler unrolls and vectorises (gemm
        // would allocate its packing buffers on every call).
        _ if n > COMMUTATOR_GEMM_MIN_DIM && n <= 16 => {
            let (mut da, mut db) = ([[0.0f64; 16]; 16], [[0.0f64; 16]; 16]);
            for ((i, j), (&x, &y)) in pairs(n).zip(a.iter().zip(b)) {
                (da[i][j], da[j][i]) = (x, -x);
                (db[i][j], db[j][i]) = (y, -y);
            }
            // C = AB by rows, then [A × B] = C − Cᵀ as in `commutator_gemm`.
            let mut dc = [[0.0f64; 16]; 16];
            for (row, ai) in dc.iter_mut().zip(&da).take(n) {
                for (x, bt) in ai.iter().zip(&db).take(n) {
                    for (c, y) in row.iter_mut().zip(bt) {
                        *c += x * y;
                    }
                }
            }
            for ((i, j), o) in pairs(n).zip(out.iter_mut()) {
                *o = dc[i][j] - dc[j][i];
            }
        }
        _ if n > COMMUTATOR_GEMM_MIN_DIM => {
            let mut scratch = vec![0.0; 3 * n * n];
            commutator_gemm(n, a, b, out, &mut scratch);
        }
        _ => {
            // Dense rows on the stack up to N = 16, on the heap beyond.
            let mut stack_a = [0.0f64; 256];
            let mut stack_b = [0.0f64; 256];
            let mut heap_a = Vec::new();
            let mut heap_b = Vec::new();
            let (da, db): (&mut [f64], &mut [f64]) = if n <= 16 {
                (&mut stack_a[..n * n], &mut stack_b[..n * n])
            } else {
                heap_a.resize(n * n, 0.0);
                heap_b.resize(n * n, 0.0);
                (&mut heap_a[..], &mut heap_b[..])
            };
            fill_dense_packed(n, a, da);
            fill_dense_packed(n, b, db);
            let mut k = 0;
            for i in 0..n {
                let ai = &da[i * n..(i + 1) * n];
                let bi = &db[i * n..(i + 1) * n];
                for j in i + 1..n {
                    let aj = &da[j * n..(j + 1) * n];
                    let bj = &db[j * n..(j + 1) * n];
                    let mut s = 0.0;
                    for t in 0..n {
                        s += bi[t] * aj[t] - ai[t] * bj[t];
                    }
                    out[k] = s;
                    k += 1;
                }
            }
        }
    }
}

/// [`commutator_packed`] as one dense matrix product, with a scratch of 3N². For skew A, B, BA = (AB)ᵀ, so
/// \[A × B\] = C − Cᵀ with C = AB; nalgebra's gemm (matrixmultiply) vectorises where a row
/// loop cannot (an f64 reduction is not reassociated), 5–7× faster at N = 32.
fn commutator_gemm(n: usize, a: &[f64], b: &[f64], out: &mut [f64], scratch: &mut [f64]) {
    let (da, rest) = scratch.split_at_mut(n * n);
    let (db, dc) = rest.split_at_mut(n * n);
    fill_dense_packed(n, a, da);
    fill_dense_packed(n, b, db);
    // Row-major buffers read as column-major are the transposes −A and −B, whose product is
    // AB again.
    let mut c = nalgebra::DMatrixViewMut::from_slice(&mut dc[..n * n], n, n);
    c.gemm(
        1.0,
        &nalgebra::DMatrixView::from_slice(da, n, n),
        &nalgebra::DMatrixView::from_slice(db, n, n),
        0.0,
    );
    // Column-major: C(i, j) = dc[j n + i].
    let mut k = 0;
    for i in 0..n {
        for j in i + 1..n {
            out[k] = dc[j * n + i] - dc[i * n + j];
            k += 1;
        }
    }
}

/// The commutator for a fixed N, on stack arrays the compiler can unroll.
#[inline]
fn commutator_fixed<const N: usize>(a: &[f64], b: &[f64], out: &mut [f64]) {
    let mut da = [[0.0f64; N]; N];
    let mut db = [[0.0f64; N]; N];
    let mut k = 0;
    for i in 0..N {
        for j in i + 1..N {
            da[i][j] = a[k];
            da[j][i] = -a[k];
            db[i][j] = b[k];
            db[j][i] = -b[k];
            k += 1;
        }
    }
    let mut k = 0;
    for i in 0..N {
        for j in i + 1..N {
            let mut s = 0.0;
            for t in 0..N {
                s += db[i][t] * da[j][t] - da[i][t] * db[j][t];
            }
            out[k] = s;
            k += 1;
        }
    }
}
