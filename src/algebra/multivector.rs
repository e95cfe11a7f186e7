//! General multivectors in any signature: one product kernel, many products.

use super::error::{check_finite, check_same_dim, within};
use super::{AlgebraError, MULTIVECTOR_MAX_DIM, Signature, blade};
use smallvec::SmallVec;

/// Default tolerance of [`Multivector::inverse`] on the residual max |A A⁻¹ − 1| when the
/// inverse comes from solving the linear system: far above its round-off for well-conditioned
/// elements, far below any inverse worth the name.
pub const INVERSE_TOLERANCE: f64 = 1e-8;

/// Inline storage for multivectors: 16 coefficients cover every multivector up to N = 4
/// without touching the heap.
pub(crate) type MvStorage = SmallVec<[f64; 16]>;

/// A general element of the Clifford algebra Cl(p, q, r): a linear combination of all 2^N basis
/// blades.
///
/// Coefficients are stored densely, indexed by the blade's bit mask (bit i set ⇔ eᵢ₊₁ is a
/// factor), so N ≤ [`MULTIVECTOR_MAX_DIM`]. Products skip zero coefficients, so sparse
/// multivectors (a vector, a bivector) multiply in time proportional to the number of non-zero
/// pairs. Use the graded types [`super::Vector`], [`super::Bivector`] and [`super::Rotor`]
/// when you know the grade: they are faster and go to higher N.
///
/// # Contents
/// - Construction: [`Multivector::zero`], [`Multivector::scalar`], [`Multivector::basis_blade`],
///   [`Multivector::from_coefficients`], conversions `From<&Vector>`, `From<&Bivector>`,
///   `From<&Rotor>`.
/// - Products ([`Product`] lists each with its grade filter): [`Multivector::geometric`],
///   [`Multivector::wedge`], [`Multivector::left_contract`], [`Multivector::right_contract`],
///   [`Multivector::scalar_product`], [`Multivector::commutator`],
///   [`Multivector::anticommutator`], [`Multivector::regressive`], and the checked
///   [`Multivector::try_product`].
/// - Involutions: [`Multivector::reverse`], [`Multivector::grade_involution`],
///   [`Multivector::clifford_conjugate`].
/// - Grades: [`Multivector::grade`], [`Multivector::even`], [`Multivector::odd`],
///   [`Multivector::grades`].
/// - Norms and inverse: [`Multivector::norm_squared`], [`Multivector::norm`],
///   [`Multivector::inverse`].
/// - Versors: [`Multivector::exp`] of a bivector and [`Multivector::log`] of an even versor,
///   in every signature up to N = 8 and in Euclidean and projective signatures up to N = 16.
/// - Duals: [`Multivector::dual`], [`Multivector::hodge`], [`Multivector::right_complement`],
///   [`Multivector::left_complement`].
///
/// ```
/// use rotorflow::algebra::{Multivector, Signature};
/// let sig = Signature::euclidean(3);
/// let e1 = Multivector::basis_blade(sig, 0b001);
/// let e2 = Multivector::basis_blade(sig, 0b010);
/// let e12 = &e1 * &e2; // geometric product
/// assert_eq!(e12.coefficient(0b011), 1.0);
/// assert_eq!((&e12 * &e12).scalar_part(), -1.0); // a unit plane squares to −1
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Multivector {
    sig: Signature,
    coeffs: MvStorage,
}

/// The bilinear products of the algebra, each defined by a filter on the grades of the two
/// factors (Dorst, Fontijne & Mann, *Geometric Algebra for Computer Science*, ch. 3 and 6).
///
/// For basis blades a (grade r) and b (grade s):
///
/// | product | keeps | notation |
/// |---|---|---|
/// | `Geometric` | everything | a b |
/// | `Wedge` | grade r + s (disjoint blades) | a ∧ b |
/// | `LeftContraction` | grade s − r (a ⊆ b) | a ⌋ b |
/// | `RightContraction` | grade r − s (b ⊆ a) | a ⌊ b |
/// | `Scalar` | grade 0 | ⟨a b⟩₀ = a ∗ b |
/// | `Commutator` | ½(ab − ba) | a × b |
/// | `Anticommutator` | ½(ab + ba) | |
/// | `Regressive` | grade r + s − N | a ∨ b (meet) |
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Product {
    /// The geometric (Clifford) product a b.
    Geometric,
    /// The outer product a ∧ b: the geometric product filtered to grade r + s.
    Wedge,
    /// The left contraction a ⌋ b: grade s − r, zero when r > s.
    LeftContraction,
    /// The right contraction a ⌊ b: grade r − s, zero when s > r.
    RightContraction,
    /// The scalar product ⟨a b⟩₀.
    Scalar,
    /// The commutator product a × b = ½(ab − ba).
    Commutator,
    /// The anticommutator product ½(ab + ba).
    Anticommutator,
    /// The regressive product a ∨ b, metric-free: the left complement of the outer product
    /// of the right complements.
    Regressive,
}

impl Multivector {
    /// Returns the zero multivector of algebra `sig`.
    ///
    /// # Panics
    /// If `sig.dim()` exceeds [`MULTIVECTOR_MAX_DIM`] (see [`Multivector::try_zero`]).
    #[track_caller]
    pub fn zero(sig: Signature) -> Self {
        Self::try_zero(sig).unwrap_or_else(|e| panic!("rotorflow: {e}"))
    }

    /// Returns the zero multivector of algebra `sig`, or an error if the algebra is too large
    /// for dense storage.
    ///
    /// # Errors
    /// [`AlgebraError::DimensionTooLarge`] when `sig.dim() > MULTIVECTOR_MAX_DIM`.
    pub fn try_zero(sig: Signature) -> Result<Self, AlgebraError> {
        let n = sig.dim();
        AlgebraError::check_dimension("multivector", n, MULTIVECTOR_MAX_DIM)?;
        Ok(Multivector {
            sig,
            coeffs: crate::numeric::zeros(1 << n),
        })
    }

    /// Returns the scalar `s` as a multivector of algebra `sig`.
    ///
    /// # Panics
    /// If `sig.dim()` exceeds [`MULTIVECTOR_MAX_DIM`] (see [`Multivector::try_scalar`]).
    #[track_caller]
    pub fn scalar(sig: Signature, s: f64) -> Self {
        let mut m = Self::zero(sig);
        m.coeffs[0] = s;
        m
    }

    /// Returns the scalar `s` as a multivector of algebra `sig`, or an error if the algebra
    /// is too large.
    ///
    /// # Errors
    /// [`AlgebraError::DimensionTooLarge`].
    pub fn try_scalar(sig: Signature, s: f64) -> Result<Self, AlgebraError> {
        let mut m = Self::try_zero(sig)?;
        m.coeffs[0] = s;
        Ok(m)
    }

    /// Returns the basis blade with bit mask `blade` (bit i set ⇔ eᵢ₊₁ is a factor).
    ///
    /// # Panics
    /// If the mask has bits at or above `sig.dim()` (see [`Multivector::try_basis_blade`]).
    #[track_caller]
    pub fn basis_blade(sig: Signature, blade: u64) -> Self {
        Self::try_basis_blade(sig, blade).unwrap_or_else(|_| {
            panic!(
                "rotorflow: blade mask {blade:#b} out of range for dimension {}",
                sig.dim()
            )
        })
    }

    /// Returns the basis blade with bit mask `blade`, or an error if the mask is out of range.
    ///
    /// # Errors
    /// [`AlgebraError::IndexOutOfRange`] if the mask has bits at or above `sig.dim()`;
    /// [`AlgebraError::DimensionTooLarge`] if the algebra is too large.
    pub fn try_basis_blade(sig: Signature, blade: u64) -> Result<Self, AlgebraError> {
        let mut m = Self::try_zero(sig)?;
        if blade as usize >= m.coeffs.len() {
            return Err(AlgebraError::IndexOutOfRange {
                index: 63 - blade.leading_zeros() as usize,
                dim: sig.dim(),
            });
        }
        m.coeffs[blade as usize] = 1.0;
        Ok(m)
    }

    /// Returns `coefficient` times the basis blade named `name`: `1` for the scalar, `e13`,
    /// `e1e3` or `e₁₃` for e₁∧e₃ (1-based, as [`Display`](std::fmt::Display) writes blades;
    /// from dimension 10 on, `e1_10`). Indices in another order give the reordered blade's
    /// sign: `e31` is −e₁₃.
    ///
    /// ```
    /// use rotorflow::algebra::{Multivector, Signature};
    /// let sig = Signature::euclidean(3);
    /// let b = Multivector::blade_by_name(sig, "e13", 0.5)?;
    /// assert_eq!(b, Multivector::basis_blade(sig, 0b101) * 0.5);
    /// assert_eq!(Multivector::blade_by_name(sig, "e₃₁", 1.0)?.coefficient(0b101), -1.0);
    /// assert!(Multivector::blade_by_name(sig, "e14", 1.0).is_err()); // no e₄ in ℝ³
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    ///
    /// # Errors
    /// [`AlgebraError::InvalidBladeName`] for a malformed name or an index out of range;
    /// [`AlgebraError::NonFinite`]; [`AlgebraError::DimensionTooLarge`].
    pub fn blade_by_name(
        sig: Signature,
        name: &str,
        coefficient: f64,
    ) -> Result<Self, AlgebraError> {
        let (sign, mask) = blade::parse_name(name, sig.dim())?;
        check_finite(&[coefficient], "blade coefficient")?;
        let mut m = Self::try_zero(sig)?;
        m.coeffs[mask as usize] = sign * coefficient;
        Ok(m)
    }

    /// Builds a multivector from its 2^N coefficients, indexed by blade bit mask.
    ///
    /// # Errors
    /// [`AlgebraError::WrongComponentCount`], [`AlgebraError::NonFinite`],
    /// [`AlgebraError::DimensionTooLarge`].
    pub fn from_coefficients(sig: Signature, coefficients: &[f64]) -> Result<Self, AlgebraError> {
        let mut m = Self::try_zero(sig)?;
        if coefficients.len() != m.coeffs.len() {
            return Err(AlgebraError::WrongComponentCount {
                what: "multivector",
                expected: m.coeffs.len(),
                found: coefficients.len(),
            });
        }
        check_finite(coefficients, "multivector coefficients")?;
        m.coeffs.copy_from_slice(coefficients);
        Ok(m)
    }

    /// The vector Σ cᵢ eᵢ₊₁ of the algebra `sig` from its N components (the basis order of
    /// the signature: positive, negative, then null vectors).
    ///
    /// ```
    /// use rotorflow::algebra::{Multivector, Signature};
    /// let pga3 = Signature::new(3, 0, 1)?;
    /// let plane = Multivector::vector(pga3, &[0.0, 0.0, 1.0, 2.0])?; // e₃ + 2e₄
    /// assert_eq!(plane.coefficient(0b0100), 1.0);
    /// assert_eq!(plane.coefficient(0b1000), 2.0);
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    ///
    /// # Errors
    /// [`AlgebraError::WrongComponentCount`] unless there are N components;
    /// [`AlgebraError::NonFinite`]; [`AlgebraError::DimensionTooLarge`].
    pub fn vector(sig: Signature, components: &[f64]) -> Result<Self, AlgebraError> {
        let n = sig.dim();
        let mut m = Self::graded(sig, components, n, "vector")?;
        for (i, &c) in components.iter().enumerate() {
            m.coeffs[1 << i] = c;
        }
        Ok(m)
    }

    /// The bivector Σ cᵢⱼ eᵢⱼ of the algebra `sig` from its N(N − 1)/2 components in the
    /// lexicographic order of [`super::Bivector`]: e₁₂, e₁₃, …, e₁N, e₂₃, …
    ///
    /// ```
    /// use rotorflow::algebra::{Multivector, Signature};
    /// let b = Multivector::bivector(Signature::new(2, 1, 0)?, &[1.0, 0.0, 3.0])?;
    /// assert_eq!(b.to_string(), "1·e12 + 3·e23");
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    ///
    /// # Errors
    /// [`AlgebraError::WrongComponentCount`] unless there are N(N − 1)/2 components;
    /// [`AlgebraError::NonFinite`]; [`AlgebraError::DimensionTooLarge`].
    pub fn bivector(sig: Signature, components: &[f64]) -> Result<Self, AlgebraError> {
        let n = sig.dim();
        let mut m = Self::graded(sig, components, n * n.saturating_sub(1) / 2, "bivector")?;
        for ((i, j), &c) in super::bivector::pairs(n).zip(components) {
            m.coeffs[(1 << i) | (1 << j)] = c;
        }
        Ok(m)
    }

    /// The zero element of `sig`, after checking `components` (`expected` of them, finite).
    fn graded(
        sig: Signature,
        components: &[f64],
        expected: usize,
        what: &'static str,
    ) -> Result<Self, AlgebraError> {
        if components.len() != expected {
            return Err(AlgebraError::WrongComponentCount {
                what,
                expected,
                found: components.len(),
            });
        }
        check_finite(components, what)?;
        Self::try_zero(sig)
    }

    /// Builds from raw storage without checks (crate-internal).
    pub(crate) fn from_storage(sig: Signature, coeffs: MvStorage) -> Self {
        debug_assert_eq!(coeffs.len(), 1 << sig.dim());
        Multivector { sig, coeffs }
    }

    /// Returns the signature of the algebra this element belongs to.
    #[inline]
    pub fn signature(&self) -> Signature {
        self.sig
    }

    /// Returns the dimension N of the underlying vector space.
    #[inline]
    pub fn dim(&self) -> usize {
        self.sig.dim()
    }

    /// Returns all 2^N coefficients, indexed by blade bit mask.
    #[inline]
    pub fn as_slice(&self) -> &[f64] {
        &self.coeffs
    }

    /// Returns the coefficients mutably, indexed by blade bit mask.
    #[inline]
    pub fn as_mut_slice(&mut self) -> &mut [f64] {
        &mut self.coeffs
    }

    /// Returns the coefficient of basis blade `blade` (0 if the mask is out of range).
    #[inline]
    pub fn coefficient(&self, blade: u64) -> f64 {
        self.coeffs.get(blade as usize).copied().unwrap_or(0.0)
    }

    /// Returns the scalar part ⟨A⟩₀.
    #[inline]
    pub fn scalar_part(&self) -> f64 {
        self.coeffs[0]
    }

    /// Returns an iterator over the non-zero terms as (blade mask, coefficient).
    pub fn terms(&self) -> impl Iterator<Item = (u64, f64)> + '_ {
        self.coeffs
            .iter()
            .enumerate()
            .filter(|(_, c)| **c != 0.0)
            .map(|(b, c)| (b as u64, *c))
    }

    /// Returns the checked product of `self` and `other` of the given kind.
    ///
    /// # Errors
    /// [`AlgebraError::SignatureMismatch`] (or dimension mismatch) when the operands belong to
    /// different algebras.
    pub fn try_product(&self, other: &Self, kind: Product) -> Result<Self, AlgebraError> {
        check_same_dim(self.dim(), other.dim())?;
        if self.sig != other.sig {
            return Err(AlgebraError::SignatureMismatch {
                left: self.sig,
                right: other.sig,
            });
        }
        Ok(match kind {
            Product::Regressive => {
                let a = self.right_complement();
                let b = other.right_complement();
                product_kernel(&a, &b, Product::Wedge).left_complement()
            }
            _ => product_kernel(self, other, kind),
        })
    }

    #[track_caller]
    fn product(&self, other: &Self, kind: Product) -> Self {
        self.try_product(other, kind)
            .unwrap_or_else(|e| panic!("rotorflow: {e}"))
    }

    /// Returns the geometric product `self · other`.
    ///
    /// # Panics
    /// If the operands belong to different algebras (see [`Multivector::try_product`]).
    #[track_caller]
    pub fn geometric(&self, other: &Self) -> Self {
        self.product(other, Product::Geometric)
    }

    /// Returns the outer product `self ∧ other` (keeps grade r + s).
    ///
    /// # Panics
    /// If the operands belong to different algebras.
    #[track_caller]
    pub fn wedge(&self, other: &Self) -> Self {
        self.product(other, Product::Wedge)
    }

    /// Returns the left contraction `self ⌋ other` (keeps grade s − r).
    ///
    /// # Panics
    /// If the operands belong to different algebras.
    #[track_caller]
    pub fn left_contract(&self, other: &Self) -> Self {
        self.product(other, Product::LeftContraction)
    }

    /// Returns the right contraction `self ⌊ other` (keeps grade r − s).
    ///
    /// # Panics
    /// If the operands belong to different algebras.
    #[track_caller]
    pub fn right_contract(&self, other: &Self) -> Self {
        self.product(other, Product::RightContraction)
    }

    /// Returns the scalar product ⟨self · other⟩₀.
    ///
    /// # Panics
    /// If the operands belong to different algebras.
    #[track_caller]
    pub fn scalar_product(&self, other: &Self) -> f64 {
        self.product(other, Product::Scalar).scalar_part()
    }

    /// Returns the inner product `self · other` = Σ ⟨A_r B_s⟩_|r−s| over the grades of both
    /// (Dorst's "fat dot", kingdon's `|`), the operator `|`: the left contraction where
    /// r ≤ s, the right one where r ≥ s, so A · B = A ⌋ B + A ⌊ B − ⟨A B⟩₀. For two vectors
    /// it is the metric's dot product.
    ///
    /// # Panics
    /// If the operands belong to different algebras.
    #[track_caller]
    pub fn inner(&self, other: &Self) -> Self {
        let mut m = self.left_contract(other);
        m += &self.right_contract(other);
        m.coeffs[0] -= self.scalar_product(other);
        m
    }

    /// Returns the commutator product `self × other = ½(self·other − other·self)`.
    ///
    /// # Panics
    /// If the operands belong to different algebras.
    #[track_caller]
    pub fn commutator(&self, other: &Self) -> Self {
        self.product(other, Product::Commutator)
    }

    /// Returns the anticommutator product `½(self·other + other·self)`.
    ///
    /// # Panics
    /// If the operands belong to different algebras.
    #[track_caller]
    pub fn anticommutator(&self, other: &Self) -> Self {
        self.product(other, Product::Anticommutator)
    }

    /// Returns the regressive product `self ∨ other` (keeps grade r + s − N), the operator
    /// `&`: it intersects blades read as the subspaces they span (and joins them in
    /// projective GA, where vectors are hyperplanes; see the operator table of
    /// [`crate::algebra`]).
    ///
    /// Metric-free: `A ∨ B = lc(rc(A) ∧ rc(B))` with the right and left complements. In 3D,
    /// `e12 ∨ e23 = e2`: the planes e₁₂ and e₂₃ through the origin intersect in the e₂ axis.
    ///
    /// # Panics
    /// If the operands belong to different algebras.
    #[track_caller]
    pub fn regressive(&self, other: &Self) -> Self {
        self.product(other, Product::Regressive)
    }

    /// Returns the grade-`k` part ⟨A⟩_k.
    pub fn grade(&self, k: usize) -> Self {
        self.map_blades(|b, c| if blade::grade(b) == k { c } else { 0.0 })
    }

    /// Returns the even part (grades 0, 2, 4, …).
    pub fn even(&self) -> Self {
        self.map_blades(|b, c| {
            if blade::grade(b).is_multiple_of(2) {
                c
            } else {
                0.0
            }
        })
    }

    /// Returns the odd part (grades 1, 3, 5, …).
    pub fn odd(&self) -> Self {
        self.map_blades(|b, c| if blade::grade(b) % 2 == 1 { c } else { 0.0 })
    }

    /// Returns the grades that have a non-zero coefficient, ascending.
    pub fn grades(&self) -> Vec<usize> {
        let mut present = vec![false; self.dim() + 1];
        for (b, _) in self.terms() {
            present[blade::grade(b)] = true;
        }
        (0..=self.dim()).filter(|&k| present[k]).collect()
    }

    /// Returns the reverse Ã: each grade-k part times (−1)^(k(k−1)/2).
    pub fn reverse(&self) -> Self {
        self.map_blades(|b, c| c * blade::reverse_sign(blade::grade(b)))
    }

    /// Returns the grade involution Â: each grade-k part times (−1)^k.
    pub fn grade_involution(&self) -> Self {
        self.map_blades(|b, c| c * blade::involution_sign(blade::grade(b)))
    }

    /// Returns the Clifford conjugate Ā: each grade-k part times (−1)^(k(k+1)/2).
    pub fn clifford_conjugate(&self) -> Self {
        self.map_blades(|b, c| c * blade::conjugate_sign(blade::grade(b)))
    }

    /// Returns the squared norm ⟨A Ã⟩₀.
    ///
    /// In a Euclidean signature this is the sum of squared coefficients (never negative); in
    /// other signatures it can be negative or zero for non-zero elements.
    pub fn norm_squared(&self) -> f64 {
        self.terms()
            .map(|(b, c)| {
                c * c * blade::reverse_sign(blade::grade(b)) * self.sig.metric_factor(b, b)
                    // e_b e_b = reorder_sign(b,b) * metric; reverse makes it positive in ℝᴺ.
                    * blade::reorder_sign(b, b)
            })
            .sum()
    }

    /// Returns the norm √|⟨A Ã⟩₀|.
    pub fn norm(&self) -> f64 {
        self.norm_squared().abs().sqrt()
    }

    /// Returns the inverse A⁻¹ with A A⁻¹ = A⁻¹ A = 1.
    ///
    /// Versors (products of invertible vectors) use A⁻¹ = Ã / (A Ã); other elements solve the
    /// 2^N × 2^N linear system of left multiplication, whose cost grows like 8^N (practical to
    /// N ≈ 10).
    ///
    /// The linear system's answer is accepted when the residual max |A A⁻¹ − 1| is at most
    /// [`INVERSE_TOLERANCE`]; [`Multivector::inverse_eps`] chooses the tolerance.
    ///
    /// # Errors
    /// [`AlgebraError::NotInvertible`] if the element is singular (a null vector, a zero
    /// divisor such as 1 + e₁ in ℝ³, anything in a null direction of a degenerate metric).
    pub fn inverse(&self) -> Result<Self, AlgebraError> {
        self.inverse_eps(INVERSE_TOLERANCE)
    }

    /// Like [`Multivector::inverse`] with an explicit tolerance on the residual
    /// max |A A⁻¹ − 1| of the linear-system path.
    ///
    /// # Errors
    /// As [`Multivector::inverse`].
    pub fn inverse_eps(&self, tolerance: f64) -> Result<Self, AlgebraError> {
        let rev = self.reverse();
        let prod = self.geometric(&rev);
        let s = prod.scalar_part();
        let scale = self.coeffs.iter().fold(0.0f64, |m, c| m.max(c.abs()));
        if scale == 0.0 {
            return Err(AlgebraError::NotInvertible {
                reason: "the zero multivector",
            });
        }
        let tol = 64.0 * f64::EPSILON * scale * scale;
        let off_scalar = prod
            .terms()
            .filter(|(b, _)| *b != 0)
            .fold(0.0f64, |m, (_, c)| m.max(c.abs()));
        if off_scalar <= tol && s.abs() > tol {
            return Ok(rev * (1.0 / s));
        }
        // General case: solve L x = 1 where L is the matrix of left multiplication by self.
        let n = 1usize << self.dim();
        let mut l = nalgebra::DMatrix::<f64>::zeros(n, n);
        for (a, ca) in self.terms() {
            for col in 0..n as u64 {
                let s = blade::reorder_sign(a, col) * self.sig.metric_factor(a, col);
                if s != 0.0 {
                    l[((a ^ col) as usize, col as usize)] += s * ca;
                }
            }
        }
        let mut rhs = nalgebra::DVector::<f64>::zeros(n);
        rhs[0] = 1.0;
        let lu = l.clone().lu();
        let x = lu.solve(&rhs).ok_or(AlgebraError::NotInvertible {
            reason: "left multiplication is singular",
        })?;
        let inv = Multivector::from_storage(self.sig, x.iter().copied().collect());
        // Reject numerically singular systems: the residual must be small.
        let check = self.geometric(&inv);
        let mut err = (check.scalar_part() - 1.0).abs();
        for (b, c) in check.terms() {
            if b != 0 {
                err = err.max(c.abs());
            }
        }
        if !within(err, tolerance) {
            return Err(AlgebraError::NotInvertible {
                reason: "left multiplication is singular",
            });
        }
        Ok(inv)
    }

    /// Returns the right complement: e_a ↦ s e_ā with e_a ∧ (s e_ā) = e₁…N (metric-free).
    pub fn right_complement(&self) -> Self {
        let n = self.dim();
        let full = blade::full_mask(n);
        let mut out = Multivector::zero(self.sig);
        for (b, c) in self.terms() {
            out.coeffs[(full & !b) as usize] = c * blade::right_complement_sign(b, n);
        }
        out
    }

    /// Returns the left complement: e_a ↦ s e_ā with (s e_ā) ∧ e_a = e₁…N; it undoes
    /// [`Multivector::right_complement`].
    pub fn left_complement(&self) -> Self {
        let n = self.dim();
        let full = blade::full_mask(n);
        let mut out = Multivector::zero(self.sig);
        for (b, c) in self.terms() {
            out.coeffs[(full & !b) as usize] = c * blade::left_complement_sign(b, n);
        }
        out
    }

    /// Returns the Hodge dual ⋆A, defined by B ∧ ⋆A = ⟨B, A⟩ e₁…N for every B of A's grade,
    /// where ⟨e_a, e_a⟩ is the product of the squares of a's basis vectors.
    ///
    /// On basis blades ⋆e_a = ⟨e_a, e_a⟩ s e_ā (s the right-complement sign). Applying it twice
    /// gives ⋆⋆A = (−1)ᵏ⁽ᴺ⁻ᵏ⁾ (−1)^q A on grade k in Cl(p, q, 0), and 0 on blades that meet a
    /// null direction. In 3D, ⋆e₁₂ = e₃: the paper's Levi-Civita contractions such as
    /// Ω_k = ½ ε_ijk ω_ij are exactly this map (book, chapter "The mapping").
    pub fn hodge(&self) -> Self {
        let n = self.dim();
        let full = blade::full_mask(n);
        let mut out = Multivector::zero(self.sig);
        for (b, c) in self.terms() {
            let metric = self.sig.metric_factor(b, b);
            out.coeffs[(full & !b) as usize] = c * metric * blade::right_complement_sign(b, n);
        }
        out
    }

    /// Returns the dual A I⁻¹, with I = e₁…N the unit pseudoscalar.
    ///
    /// # Errors
    /// [`AlgebraError::NotInvertible`] in a degenerate signature (the pseudoscalar is null);
    /// use [`Multivector::hodge`] or [`Multivector::right_complement`] there.
    pub fn dual(&self) -> Result<Self, AlgebraError> {
        if !self.sig.is_nondegenerate() {
            return Err(AlgebraError::NotInvertible {
                reason: "the pseudoscalar of a degenerate signature is null",
            });
        }
        let i = Multivector::basis_blade(self.sig, blade::full_mask(self.dim()));
        let i_inv = i.inverse()?;
        Ok(self.geometric(&i_inv))
    }

    /// Returns the maximum absolute coefficient (a cheap size measure).
    pub fn max_abs(&self) -> f64 {
        self.coeffs.iter().fold(0.0, |m, c| m.max(c.abs()))
    }

    fn map_blades(&self, f: impl Fn(u64, f64) -> f64) -> Self {
        Multivector {
            sig: self.sig,
            coeffs: self
                .coeffs
                .iter()
                .enumerate()
                .map(|(b, &c)| if c == 0.0 { 0.0 } else { f(b as u64, c) })
                .collect(),
        }
    }
}

/// The one product kernel: loops over pairs of non-zero terms, applies the sign and the
/// metric, and lets `kind` decide which pairs count (kingdon's `codegen_product`, here
/// interpreted rather than generated).
fn product_kernel(a: &Multivector, b: &Multivector, kind: Product) -> Multivector {
    let sig = a.sig;
    let mut out: MvStorage = crate::numeric::zeros(a.coeffs.len());
    let b_terms: SmallVec<[(u64, f64); 32]> = b.terms().collect();
    for (ba, ca) in a.terms() {
        for &(bb, cb) in &b_terms {
            let keep = match kind {
                Product::Geometric => 1.0,
                Product::Wedge => {
                    if ba & bb == 0 {
                        1.0
                    } else {
                        0.0
                    }
                }
                Product::LeftContraction => {
                    if ba & !bb == 0 {
                        1.0
                    } else {
                        0.0
                    }
                }
                Product::RightContraction => {
                    if bb & !ba == 0 {
                        1.0
                    } else {
                        0.0
                    }
                }
                Product::Scalar => {
                    if ba == bb {
                        1.0
                    } else {
                        0.0
                    }
                }
                Product::Commutator => {
                    0.5 * (1.0 - blade::reorder_sign(bb, ba) * blade::reorder_sign(ba, bb))
                }
                Product::Anticommutator => {
                    0.5 * (1.0 + blade::reorder_sign(bb, ba) * blade::reorder_sign(ba, bb))
                }
                Product::Regressive => unreachable!("handled through complements"),
            };
            if keep == 0.0 {
                continue;
            }
            let s = blade::reorder_sign(ba, bb) * sig.metric_factor(ba, bb);
            if s != 0.0 {
                out[(ba ^ bb) as usize] += keep * s * ca * cb;
            }
        }
    }
    Multivector { sig, coeffs: out }
}
