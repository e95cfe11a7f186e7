//! The paper's views of the mass tensor J: the rank-4 inertia tensor of its eq. (22), the
//! Levi-Civita-contracted matrix 𝕀 of eqs. (23), (24), (30) and (31), the gyration radii
//! (Poinsot half-axes) of eq. (27) and the trace of eq. (29).
//!
//! Everything here is a function of J = ∫ x xᵀ dm (see the Conventions chapter of the
//! rotorflow book), so a physical body has
//! only N(N+1)/2 inertia parameters.
//!
//! # The rank-4 tensor (eq. 22, the crate's normalisation)
//!
//! Iⁱʲᵏˡ = ½ (δᵢₖ Jⱼₗ − δᵢₗ Jⱼₖ − δⱼₖ Jᵢₗ + δⱼₗ Jᵢₖ), so Iⁱʲⁱʲ = ½ (Jᵢ + Jⱼ)
//! for i ≠ j in the principal frame, and Lᵢⱼ = Σₖₗ Iⁱʲᵏˡ ωₖₗ (sum over all k, l)
//! gives \[L\] = J\[ω\] + \[ω\]J. It has the symmetries stated under eq. (22):
//! Iⁱʲᵏˡ = −Iʲⁱᵏˡ = −Iⁱʲˡᵏ = Iᵏˡⁱʲ and Iⁱʲᵏˡ + Iⁱᵏˡʲ + Iⁱˡʲᵏ = 0.
//! This is half of Parker's (2024) Kulkarni–Nomizu normalisation (Parker, Int. J. Theor. Phys. 63, 2024, doi:10.1007/s10773-023-05505-7).
//!
//! # The contracted matrix 𝕀 (eqs. 23, 24, 30, 31)
//!
//! Read literally, eq. (31) is 𝕀ᵖᵐ = Σ εₚₛₜᵣ…ₙ εₘᵣ…ₙₖₗ Iˢᵗᵏˡ, summed over
//! s, t, k, l and the N − 3 extra indices r…n (eq. 30); for N = 3 this is eq. (23) and for
//! N = 4 eq. (24). Moving k, l past the N − 3 extra indices is an even permutation, and
//! Σᵣ…ₙ εₚₛₜᵣ…ₙ εₘₖₗᵣ…ₙ = (N − 3)! δᵖˢᵗₘₖₗ, which with eq. (22) gives
//!
//! **𝕀 = 2 (N − 2)! (tr J · 1 − J)**, i.e. 𝕀ᵖᵖ = 2 (N − 2)! Σ Jᵣ (sum over r ≠ p) in the
//! principal frame.
//!
//! tr J · 1 − J is the N-dimensional axis-moment tensor: its entry (p, p) is
//! ∫ (|x|² − xₚ²) dm, the second moment about the axis eₚ; in 3D it is the classical
//! inertia tensor. In terms of plane moments, Σ Jᵣ (r ≠ p) = (1/(N−2)) Σ (Jₛ + Jₜ) over the planes (s, t) ∌ p,
//! so 𝕀ᵖᵖ = 2 (N − 3)! × (sum of the plane moments of the planes orthogonal
//! to eₚ). In 3D the literal eq. (23) is therefore twice the classical inertia tensor, and
//! in 4D eq. (24) is four times the axis-moment tensor.
//!
//! The paper itself uses three different normalisations of 𝕀 (tested in
//! `tests/paper_errata.rs`); [`ContractionNormalization`] offers all three, and the crate's
//! choice is the literal one, [`ContractionNormalization::LeviCivita`]:
//! - eq. (26) (4D) writes −𝕀_I as a sum of six components Iˢᵗᵗˢ, which gives
//!   (N − 2)(tr J − Jₚ) = half of the literal eq. (24): [`ContractionNormalization::PlaneSum`];
//! - the examples in eqs. (79), (80), (87)–(89), (95), (98) and (106) use tr J · 1 − J:
//!   [`ContractionNormalization::AxisMoment`];
//! - eqs. (75), (76) match the literal eq. (24), and eq. (71) matches eq. (26).
//!
//! The gyration radii (Poinsot half-axes) are 𝕀_α = μ L_α², L_α = √(𝕀_α/μ) (eq. 27) and the
//! trace is 𝕀₀ = tr 𝕀 = μ Σ L_α² (eq. 29). They inherit the normalisation of 𝕀.

use super::InertiaError;
use super::validate::{check_finite_matrix, check_positive, check_symmetric, max_abs};
use nalgebra::{DMatrix, DVector};

/// Largest dimension for which [`RankFourTensor::levi_civita_contraction`] evaluates the
/// literal Levi-Civita sum (cost grows like 6 N! N²; N = 8 takes about 2·10⁷ steps).
pub const MAX_LITERAL_CONTRACTION_DIM: usize = 8;

use super::tolerance::SYMMETRY_TOLERANCE;

fn check_square(quantity: &'static str, m: &DMatrix<f64>) -> Result<usize, InertiaError> {
    if m.nrows() != m.ncols() {
        return Err(InertiaError::NotSquare {
            quantity,
            rows: m.nrows(),
            cols: m.ncols(),
        });
    }
    check_finite_matrix(quantity, m)?;
    Ok(m.nrows())
}

/// Checks that `j` is a finite symmetric square matrix and returns its symmetrized copy.
fn checked_mass_tensor(j: &DMatrix<f64>) -> Result<DMatrix<f64>, InertiaError> {
    check_square("mass_tensor", j)?;
    check_symmetric("mass_tensor", j)?;
    Ok((j + j.transpose()) * 0.5)
}

fn check_skew(omega: &DMatrix<f64>, dim: usize) -> Result<(), InertiaError> {
    let n = check_square("omega", omega)?;
    if n != dim {
        return Err(InertiaError::DimensionMismatch {
            quantity: "omega",
            expected: dim,
            found: n,
        });
    }
    let scale = max_abs(omega);
    if scale > 0.0 {
        let residual = max_abs(&(omega + omega.transpose())) / scale;
        if residual > SYMMETRY_TOLERANCE {
            return Err(InertiaError::NotSkewSymmetric {
                quantity: "omega",
                residual,
            });
        }
    }
    Ok(())
}

/// Sign of a permutation of distinct indices (+1 even, −1 odd), by counting inversions.
fn permutation_sign(p: &[usize]) -> f64 {
    let mut inversions = 0usize;
    for a in 0..p.len() {
        for b in a + 1..p.len() {
            if p[a] > p[b] {
                inversions += 1;
            }
        }
    }
    if inversions.is_multiple_of(2) {
        1.0
    } else {
        -1.0
    }
}

/// Calls `f` on every permutation of `items` (Heap's algorithm, iterative).
fn for_each_permutation(items: &mut [usize], mut f: impl FnMut(&[usize])) {
    let n = items.len();
    let mut c = vec![0usize; n];
    f(items);
    let mut i = 0;
    while i < n {
        if c[i] < i {
            if i % 2 == 0 {
                items.swap(0, i);
            } else {
                items.swap(c[i], i);
            }
            f(items);
            c[i] += 1;
            i = 0;
        } else {
            c[i] = 0;
            i += 1;
        }
    }
}

/// The rank-4 inertia tensor Iⁱʲᵏˡ of the paper's eq. (22), with the crate's
/// normalisation Iⁱʲᵏˡ = ½ (δᵢₖ Jⱼₗ − δᵢₗ Jⱼₖ − δⱼₖ Jᵢₗ + δⱼₗ Jᵢₖ).
///
/// Stored densely as N⁴ numbers. Indices are 0-based; component (i, j, k, l) lives at
/// `components()[((i·N + j)·N + k)·N + l]`.
///
/// # Example
/// In the principal frame Iⁱʲⁱʲ is half the plane moment:
/// ```
/// use rotorflow::inertia::tensor::RankFourTensor;
/// use nalgebra::{DMatrix, DVector};
/// let j = DMatrix::from_diagonal(&DVector::from_vec(vec![1.0, 2.0, 3.0]));
/// let tensor = RankFourTensor::from_mass_tensor(&j)?;
/// assert_eq!(tensor.get(0, 1, 0, 1), 1.5);  // ½(J_1 + J_2), paper eq. (40)
/// assert_eq!(tensor.get(0, 1, 1, 0), -1.5);
/// # Ok::<(), rotorflow::inertia::InertiaError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct RankFourTensor {
    dim: usize,
    components: Vec<f64>,
}

impl RankFourTensor {
    /// Returns the eq. (22) tensor of the mass tensor J.
    ///
    /// # Errors
    /// [`InertiaError::NotSquare`], [`InertiaError::NonFinite`] or
    /// [`InertiaError::NotSymmetric`] (beyond [`SYMMETRY_TOLERANCE`]) for a bad J.
    pub fn from_mass_tensor(mass_tensor: &DMatrix<f64>) -> Result<RankFourTensor, InertiaError> {
        let j = checked_mass_tensor(mass_tensor)?;
        let n = j.nrows();
        let delta = |a: usize, b: usize| if a == b { 1.0 } else { 0.0 };
        let mut components = vec![0.0; n * n * n * n];
        for i in 0..n {
            for jj in 0..n {
                for k in 0..n {
                    for l in 0..n {
                        components[((i * n + jj) * n + k) * n + l] = 0.5
                            * (delta(i, k) * j[(jj, l)]
                                - delta(i, l) * j[(jj, k)]
                                - delta(jj, k) * j[(i, l)]
                                + delta(jj, l) * j[(i, k)]);
                    }
                }
            }
        }
        Ok(RankFourTensor { dim: n, components })
    }

    /// Returns the dimension N.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Returns all N⁴ components, (i, j, k, l) at index ((i·N + j)·N + k)·N + l.
    pub fn components(&self) -> &[f64] {
        &self.components
    }

    /// Returns Iⁱʲᵏˡ (0-based indices), or `None` if an index is ≥ N.
    ///
    /// See also [`RankFourTensor::get`], which panics instead.
    pub fn try_get(&self, i: usize, j: usize, k: usize, l: usize) -> Option<f64> {
        let n = self.dim;
        if i < n && j < n && k < n && l < n {
            Some(self.components[((i * n + j) * n + k) * n + l])
        } else {
            None
        }
    }

    /// Returns Iⁱʲᵏˡ (0-based indices).
    ///
    /// # Panics
    /// If an index is ≥ N. See [`RankFourTensor::try_get`] for the non-panicking form.
    #[track_caller]
    pub fn get(&self, i: usize, j: usize, k: usize, l: usize) -> f64 {
        match self.try_get(i, j, k, l) {
            Some(v) => v,
            None => panic!(
                "RankFourTensor::get: index ({i}, {j}, {k}, {l}) out of range for N = {}",
                self.dim
            ),
        }
    }

    /// Returns the angular momentum \[L\] with Lᵢⱼ = Σₖₗ Iⁱʲᵏˡ ωₖₗ, summed over all k
    /// and l (paper eq. 32; see the Conventions chapter of the rotorflow book). It equals J\[ω\] + \[ω\]J.
    ///
    /// # Errors
    /// [`InertiaError::NotSquare`], [`InertiaError::DimensionMismatch`],
    /// [`InertiaError::NonFinite`], [`InertiaError::NotSkewSymmetric`] for a bad \[ω\].
    pub fn apply(&self, omega: &DMatrix<f64>) -> Result<DMatrix<f64>, InertiaError> {
        check_skew(omega, self.dim)?;
        let n = self.dim;
        let mut l = DMatrix::zeros(n, n);
        for i in 0..n {
            for j in 0..n {
                let mut sum = 0.0;
                for k in 0..n {
                    for m in 0..n {
                        sum += self.components[((i * n + j) * n + k) * n + m] * omega[(k, m)];
                    }
                }
                l[(i, j)] = sum;
            }
        }
        Ok(l)
    }

    /// Returns the paper's rotational energy W = ½ Σᵢⱼₖₗ ωᵢⱼ Iⁱʲᵏˡ ωₖₗ of eq. (34),
    /// read literally (all index sums over 1…N).
    ///
    /// With the eq. (22) normalisation this is **twice** the kinetic energy
    /// T = ½ ⟨ω, L⟩ = ½ Σ ωᵢⱼ Lᵢⱼ (sum over i < j) of the crate (see the Conventions chapter of the rotorflow book), because the double sum over i, j
    /// counts every plane twice. See `paper_eq_34_energy_is_twice_kinetic_energy`.
    ///
    /// # Errors
    /// As [`RankFourTensor::apply`].
    pub fn paper_energy(&self, omega: &DMatrix<f64>) -> Result<f64, InertiaError> {
        let l = self.apply(omega)?;
        Ok(0.5 * omega.component_mul(&l).sum())
    }

    /// Returns the matrix 𝕀ᵖᵐ = Σ εₚₛₜᵣ…ₙ εₘᵣ…ₙₖₗ Iˢᵗᵏˡ of eqs. (23), (24),
    /// (30) and (31), evaluated literally as a sum over all index values.
    ///
    /// Only index tuples where both Levi-Civita symbols are non-zero are visited: (p, s, t,
    /// r…n) runs over all N! permutations and (m, k, l) over the 3! orderings of the three
    /// indices not in r…n; each sign is computed by counting inversions. The result equals
    /// the closed form 2 (N − 2)! (tr J · 1 − J) of [`ContractedInertia`] with
    /// [`ContractionNormalization::LeviCivita`] (see the module docs and the test
    /// `literal_levi_civita_sum_matches_closed_form`).
    ///
    /// # Errors
    /// [`InertiaError::UnsupportedDimension`] unless 3 ≤ N ≤ [`MAX_LITERAL_CONTRACTION_DIM`].
    pub fn levi_civita_contraction(&self) -> Result<DMatrix<f64>, InertiaError> {
        let n = self.dim;
        if !(3..=MAX_LITERAL_CONTRACTION_DIM).contains(&n) {
            return Err(InertiaError::UnsupportedDimension {
                dim: n,
                min: 3,
                max: MAX_LITERAL_CONTRACTION_DIM,
            });
        }
        let mut out = DMatrix::zeros(n, n);
        let mut items: Vec<usize> = (0..n).collect();
        let mut second = vec![0usize; n];
        const ORDERINGS: [[usize; 3]; 6] = [
            [0, 1, 2],
            [0, 2, 1],
            [1, 0, 2],
            [1, 2, 0],
            [2, 0, 1],
            [2, 1, 0],
        ];
        for_each_permutation(&mut items, |perm| {
            let first_sign = permutation_sign(perm);
            let (p, s, t) = (perm[0], perm[1], perm[2]);
            let rest = &perm[3..];
            let triple = [p, s, t];
            for ordering in ORDERINGS {
                let (m, k, l) = (
                    triple[ordering[0]],
                    triple[ordering[1]],
                    triple[ordering[2]],
                );
                // ε_{m r…n k l}
                second[0] = m;
                second[1..1 + rest.len()].copy_from_slice(rest);
                second[n - 2] = k;
                second[n - 1] = l;
                let second_sign = permutation_sign(&second);
                out[(p, m)] +=
                    first_sign * second_sign * self.components[((s * n + t) * n + k) * n + l];
            }
        });
        Ok(out)
    }
}

/// Which normalisation of the contracted matrix 𝕀 to use; all are c_N (tr J · 1 − J).
///
/// See the module docs for where the paper uses each one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContractionNormalization {
    /// The literal Levi-Civita contraction of eqs. (23), (24), (30), (31) with the eq. (22)
    /// tensor: c_N = 2 (N − 2)! (2 in 3D, 4 in 4D, 12 in 5D). The crate's choice.
    LeviCivita,
    /// The sum of plane moments over the planes orthogonal to each axis, as eq. (26) writes
    /// it in 4D: c_N = N − 2 (1 in 3D, 2 in 4D). Equals the literal contraction divided by
    /// 2 (N − 3)!.
    PlaneSum,
    /// The axis-moment tensor tr J · 1 − J, whose entry (p, p) is ∫ (|x|² − xₚ²) dm, the
    /// classical inertia tensor in 3D: c_N = 1. The normalisation of the paper's examples
    /// in eqs. (79), (80), (87)–(89), (95), (98), (106).
    AxisMoment,
}

impl ContractionNormalization {
    /// Returns the factor c_N with 𝕀 = c_N (tr J · 1 − J) in dimension N (N ≥ 3).
    pub fn factor(self, dim: usize) -> f64 {
        match self {
            ContractionNormalization::LeviCivita => {
                2.0 * (1..=dim.saturating_sub(2)).fold(1.0, |acc, k| acc * k as f64)
            }
            ContractionNormalization::PlaneSum => dim as f64 - 2.0,
            ContractionNormalization::AxisMoment => 1.0,
        }
    }
}

/// The contracted inertia matrix 𝕀 of eqs. (23)–(31), symmetric N×N, with its principal
/// values (eq. 25), gyration radii (eq. 27) and trace (eq. 29).
///
/// 𝕀 = c_N (tr J · 1 − J) with c_N from [`ContractionNormalization::factor`]. Its
/// eigenvectors are those of J; in the principal frame 𝕀_α = c_N Σ Jᵣ (sum over r ≠ α).
///
/// # Example
/// The paper's 5-cell (eq. 73) with a = b = c = d = 1 has J = 5/4 · 1, so the literal
/// eq. (24) gives 𝕀_α = 4 · 3 · 5/4 = 15 = 5 (b² + c² + d²), as in eq. (75):
/// ```
/// use rotorflow::inertia::Body;
/// use rotorflow::inertia::tensor::{ContractedInertia, ContractionNormalization};
/// let cell = Body::pentachoron(1.0, 1.0, 1.0, 1.0)?;
/// let inertia = ContractedInertia::from_mass_tensor(
///     cell.mass_tensor(),
///     ContractionNormalization::LeviCivita,
/// )?;
/// assert!((inertia.axis_values()[0] - 15.0).abs() < 1e-13);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ContractedInertia {
    normalization: ContractionNormalization,
    matrix: DMatrix<f64>,
}

impl ContractedInertia {
    /// Returns 𝕀 = c_N (tr J · 1 − J) for the mass tensor J (closed form; see the module
    /// docs for the derivation from eq. 31).
    ///
    /// # Errors
    /// [`InertiaError::UnsupportedDimension`] for N < 3 (eq. 30 needs N − 3 ≥ 0 extra
    /// indices); [`InertiaError::NotSquare`], [`InertiaError::NonFinite`],
    /// [`InertiaError::NotSymmetric`] for a bad J.
    pub fn from_mass_tensor(
        mass_tensor: &DMatrix<f64>,
        normalization: ContractionNormalization,
    ) -> Result<ContractedInertia, InertiaError> {
        let j = checked_mass_tensor(mass_tensor)?;
        let n = j.nrows();
        if n < 3 {
            return Err(InertiaError::UnsupportedDimension {
                dim: n,
                min: 3,
                max: usize::MAX,
            });
        }
        let axis = DMatrix::identity(n, n) * j.trace() - j;
        Ok(ContractedInertia {
            normalization,
            matrix: axis * normalization.factor(n),
        })
    }

    /// Returns the normalisation this matrix was built with.
    pub fn normalization(&self) -> ContractionNormalization {
        self.normalization
    }

    /// Returns the dimension N.
    pub fn dim(&self) -> usize {
        self.matrix.nrows()
    }

    /// Returns the matrix 𝕀ᵖᵐ.
    pub fn matrix(&self) -> &DMatrix<f64> {
        &self.matrix
    }

    /// Returns the diagonal 𝕀ᵖᵖ in the frame of J. When J is given in its principal frame
    /// (as for every catalogue body) these are the 𝕀_I, 𝕀_II, … of eq. (25), in axis order.
    pub fn axis_values(&self) -> DVector<f64> {
        self.matrix.diagonal()
    }

    /// Returns the eigenvalues of 𝕀 in ascending order (eq. 25, frame-independent).
    pub fn principal_values(&self) -> DVector<f64> {
        crate::numeric::sorted_symmetric_eigen(&self.matrix).0
    }

    /// Returns the trace 𝕀₀ = tr 𝕀 = c_N (N − 1) tr J (eq. 29).
    pub fn trace(&self) -> f64 {
        self.matrix.trace()
    }

    /// Returns the gyration radii L_α = √(𝕀^(αα)/μ) of eq. (27) from [`axis_values`]
    /// (axis order; the Poinsot half-axes when J is principal).
    ///
    /// [`axis_values`]: ContractedInertia::axis_values
    ///
    /// # Errors
    /// [`InertiaError::NotPositive`] or [`InertiaError::NonFinite`]; [`InertiaError::NegativeValue`] if a diagonal entry
    /// is negative (J not positive semidefinite).
    pub fn gyration_radii(&self, mass: f64) -> Result<DVector<f64>, InertiaError> {
        radii(&self.axis_values(), mass)
    }

    /// Returns the gyration radii L_α = √(𝕀_α/μ) of eq. (27) from the eigenvalues of 𝕀
    /// (ascending), independent of the frame.
    ///
    /// # Errors
    /// As [`ContractedInertia::gyration_radii`].
    pub fn principal_gyration_radii(&self, mass: f64) -> Result<DVector<f64>, InertiaError> {
        radii(&self.principal_values(), mass)
    }
}

fn radii(values: &DVector<f64>, mass: f64) -> Result<DVector<f64>, InertiaError> {
    check_positive("mass", None, mass)?;
    let scale = values.iter().fold(0.0_f64, |acc, v| acc.max(v.abs()));
    let mut out = DVector::zeros(values.len());
    for (index, &value) in values.iter().enumerate() {
        // Eigenvalues of a PSD-derived matrix may come out at −1e-16·scale; clamp those.
        if value < -SYMMETRY_TOLERANCE * scale {
            return Err(InertiaError::NegativeValue { index, value });
        }
        out[index] = (value.max(0.0) / mass).sqrt();
    }
    Ok(out)
}
