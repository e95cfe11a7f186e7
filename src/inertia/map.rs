//! [`InertiaMap`]: the inertia of a rigid body as a linear operator on bivectors.

use super::tolerance::SINGULAR_PLANE_TOLERANCE;
use super::validate::{
    check_finite, check_finite_matrix, check_moments_nonnegative, check_square, check_symmetric,
    singular_plane,
};
use super::{Body, InertiaError};
use crate::algebra::{Bivector, Rotor, bivector_len, pairs};
use nalgebra::{DMatrix, DVector};

/// The inertia of a rigid body: the symmetric positive-definite linear map L = I(ω) from
/// angular velocity to angular momentum, both bivectors in the body frame.
///
/// For a physical body with mass tensor J = ∫ x xᵀ dm (see the Conventions chapter of the rotorflow book):
///
/// I(ω) = ∫ x∧(x⌋ω) dm, i.e. \[I(ω)\] = J\[ω\] + \[ω\]J,
///
/// which in the principal frame of J is diagonal on the basis planes,
/// I(eᵢ∧eⱼ) = (Jᵢ + Jⱼ) eᵢ∧eⱼ. The map also accepts any symmetric positive-definite operator on
/// bivectors ([`InertiaMap::from_matrix`], [`InertiaMap::from_plane_moments`]) for test bodies
/// that no mass distribution has, such as the 3D I = (2, 1, 2/3) (it would need J₁ = −1/6).
///
/// # Why the inverse moments are stored
/// Every step of the dynamics needs ω = I⁻¹(L). The map keeps the principal axes P, the
/// principal second moments Jᵢ and the inverse plane moments 1/(Jᵢ + Jⱼ), so in the principal frame
/// the inverse is a multiplication, and in a general frame it is a rotation to the principal
/// frame, a multiplication and a rotation back (the solution of the Lyapunov equation
/// JΩ + ΩJ = L), never a linear solve. A general map stores its inverse matrix.
///
/// # Contents
/// - Construction: [`InertiaMap::from_mass_tensor`],
///   [`InertiaMap::from_principal_second_moments`] (the eigenvalues Jᵢ of J, any N),
///   [`InertiaMap::from_principal_moments_of_inertia_3d`] (the classical 3D moments of
///   inertia Iᵢ = Jⱼ + Jₖ), [`InertiaMap::from_body`], [`InertiaMap::from_plane_moments`],
///   [`InertiaMap::from_classical_3d`], [`InertiaMap::from_matrix`].
/// - Action: [`InertiaMap::apply`], [`InertiaMap::apply_inverse`],
///   [`InertiaMap::kinetic_energy`], [`InertiaMap::to_matrix`].
/// - Structure: [`InertiaMap::principal_second_moments`], [`InertiaMap::principal_axes`],
///   [`InertiaMap::principal_rotor`], [`InertiaMap::plane_moments`],
///   [`InertiaMap::mass_tensor`], [`InertiaMap::is_physical`].
/// - Frames: [`InertiaMap::rotated`].
///
/// ```
/// use rotorflow::inertia::InertiaMap;
/// use rotorflow::algebra::Bivector;
/// // A 4D body with principal second moments J = (1, 2, 3, 4): plane e12 has moment 1 + 2 = 3.
/// let map = InertiaMap::from_principal_second_moments(&[1.0, 2.0, 3.0, 4.0])?;
/// let w = Bivector::from_plane(4, 0, 1, 0.5)?;
/// let l = map.apply(&w);
/// assert_eq!(l.get(0, 1), 1.5);
/// assert_eq!(map.apply_inverse(&l), w);
/// assert_eq!(map.kinetic_energy(&w), 0.5 * 0.5 * 1.5);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct InertiaMap {
    dim: usize,
    kind: Kind,
}

#[derive(Clone, Debug, PartialEq)]
enum Kind {
    /// I(ω) = J[ω] + [ω]J.
    Physical {
        /// J in the body's axes.
        mass_tensor: DMatrix<f64>,
        /// Principal moments, in the order of the columns of `axes`.
        moments: Vec<f64>,
        /// Principal axes as columns (det +1); the identity when J was given diagonal.
        axes: DMatrix<f64>,
        /// Whether `axes` is the identity (J diagonal in the body's axes): the fast path.
        diagonal: bool,
        /// Jᵢ + Jⱼ in lexicographic plane order of the principal frame.
        plane_moments: Vec<f64>,
        /// 1/(Jᵢ + Jⱼ), same order.
        inverse_plane_moments: Vec<f64>,
    },
    /// A general symmetric positive-definite map on bivectors.
    General {
        /// The k×k matrix in the lexicographic basis.
        matrix: DMatrix<f64>,
        /// Its inverse.
        inverse: DMatrix<f64>,
        /// The diagonal, if the matrix is diagonal (fast path).
        diagonal: Option<Vec<f64>>,
        /// Its reciprocals (the integrators' per-step I⁻¹ without divisions).
        inverse_diagonal: Option<Vec<f64>>,
    },
}

impl InertiaMap {
    /// Returns the inertia map of the mass tensor J (N×N, symmetric positive semi-definite,
    /// about the reference point, usually the centre of mass).
    ///
    /// The checks are those of [`Body::from_mass_properties`] and
    /// [`Body::check_inertia_invertible`], with the tolerances of
    /// [`tolerance`](super::tolerance).
    ///
    /// # Errors
    /// [`InertiaError::WrongShape`], [`InertiaError::NonFinite`],
    /// [`InertiaError::NotSymmetric`] (beyond
    /// [`SYMMETRY_TOLERANCE`](super::tolerance::SYMMETRY_TOLERANCE)),
    /// [`InertiaError::NegativeMoment`] (no body has it), [`InertiaError::DegeneratePlane`] (a
    /// plane moment Jᵢ + Jⱼ at most [`SINGULAR_PLANE_TOLERANCE`] of the largest: the body is
    /// flat in two directions, the map is singular).
    pub fn from_mass_tensor(j: &DMatrix<f64>) -> Result<Self, InertiaError> {
        let n = j.nrows();
        check_square("mass_tensor", j, n.max(2), true)?;
        check_finite_matrix("mass_tensor", j)?;
        check_symmetric("mass_tensor", j)?;
        let j = (j + j.transpose()) * 0.5;
        let off_diagonal = (0..n).any(|r| (0..n).any(|c| r != c && j[(r, c)] != 0.0));
        let (moments, axes) = if off_diagonal {
            let (moments, mut axes) = crate::numeric::sorted_symmetric_eigen(&j);
            let moments: Vec<f64> = moments.iter().copied().collect();
            if axes.determinant() < 0.0 {
                let flipped = -axes.column(n - 1);
                axes.set_column(n - 1, &flipped);
            }
            (moments, axes)
        } else {
            ((0..n).map(|k| j[(k, k)]).collect(), DMatrix::identity(n, n))
        };
        Self::physical(j, moments, axes, !off_diagonal)
    }

    /// Returns the inertia map of a body whose mass tensor is diagonal in its own axes,
    /// J = diag(J₁, …, J_N): the principal *second* moments Jᵢ = ∫ xᵢ² dm, in the principal
    /// frame (axes kept in the given order). The plane eᵢ∧eⱼ has moment Jᵢ + Jⱼ.
    ///
    /// These are not the classical 3D moments of inertia Iᵢ = Jⱼ + Jₖ: for those use
    /// [`InertiaMap::from_principal_moments_of_inertia_3d`]. A solid cuboid with half-sides
    /// (0.5, 1, 1.5) and mass 12 has J = (1, 4, 9) and I = (13, 10, 5).
    ///
    /// ```
    /// use rotorflow::inertia::InertiaMap;
    /// let from_j = InertiaMap::from_principal_second_moments(&[1.0, 4.0, 9.0])?;
    /// let from_i = InertiaMap::from_principal_moments_of_inertia_3d([13.0, 10.0, 5.0])?;
    /// assert_eq!(from_j, from_i);
    /// # Ok::<(), rotorflow::inertia::InertiaError>(())
    /// ```
    ///
    /// # Errors
    /// [`InertiaError::LengthMismatch`] for fewer than 2 moments; otherwise as
    /// [`InertiaMap::from_mass_tensor`].
    pub fn from_principal_second_moments(moments: &[f64]) -> Result<Self, InertiaError> {
        let n = moments.len();
        for (i, &x) in moments.iter().enumerate() {
            check_finite("principal_second_moments", Some(i), x)?;
        }
        if n < 2 {
            return Err(InertiaError::LengthMismatch {
                quantity: "principal second moments",
                index: None,
                expected: 2,
                found: n,
            });
        }
        Self::from_mass_tensor(&DMatrix::from_diagonal(&DVector::from_column_slice(
            moments,
        )))
    }

    /// Returns the inertia map of a 3D body from its classical principal moments of inertia
    /// (I₁, I₂, I₃) about e₁, e₂, e₃ (the body frame is the principal frame).
    ///
    /// The second moments are Jᵢ = (Iⱼ + Iₖ − Iᵢ)/2, and the map is the physical one of
    /// [`InertiaMap::from_principal_second_moments`] with those Jᵢ: the plane moments are
    /// I₁₂ = I₃, I₁₃ = I₂, I₂₃ = I₁. Every mass distribution satisfies the triangle
    /// inequalities Iᵢ ≤ Iⱼ + Iₖ (Jᵢ ≥ 0); moments that violate them are refused. A test body
    /// that no mass distribution has, such as I = (2, 1, 2/3), is a general map: use
    /// [`InertiaMap::from_classical_3d`] or [`InertiaMap::from_plane_moments`].
    ///
    /// ```
    /// use rotorflow::inertia::{Body, InertiaMap};
    /// // Solid cuboid, half-sides (0.5, 1, 1.5), mass 12: I = (13, 10, 5), J = (1, 4, 9).
    /// let body = Body::solid_cuboid(&[0.5, 1.0, 1.5], 1.0)?.with_mass(12.0)?;
    /// let map = InertiaMap::from_principal_moments_of_inertia_3d([13.0, 10.0, 5.0])?;
    /// let j = map.principal_second_moments().unwrap();
    /// assert!((j[0] - 1.0).abs() < 1e-12 && (j[1] - 4.0).abs() < 1e-12 && (j[2] - 9.0).abs() < 1e-12);
    /// assert!((&map.to_matrix() - &InertiaMap::from_body(&body)?.to_matrix()).abs().max() < 1e-12);
    /// // No body has I₁ > I₂ + I₃.
    /// assert!(InertiaMap::from_principal_moments_of_inertia_3d([2.0, 1.0, 2.0 / 3.0]).is_err());
    /// # Ok::<(), rotorflow::inertia::InertiaError>(())
    /// ```
    ///
    /// # Errors
    /// [`InertiaError::NonFinite`], [`InertiaError::NotPositive`] for Iᵢ ≤ 0 (a rod, whose
    /// map is singular), [`InertiaError::NotPhysical3d`] when a triangle inequality fails
    /// beyond round-off ([`MASS_TENSOR_TOLERANCE`](super::tolerance::MASS_TENSOR_TOLERANCE)
    /// relative to the largest Iᵢ).
    pub fn from_principal_moments_of_inertia_3d(moments: [f64; 3]) -> Result<Self, InertiaError> {
        for (i, &x) in moments.iter().enumerate() {
            check_finite("moments_of_inertia", Some(i), x)?;
            if x <= 0.0 {
                return Err(InertiaError::NotPositive {
                    quantity: "moments_of_inertia",
                    index: Some(i),
                    value: x,
                });
            }
        }
        let [i1, i2, i3] = moments;
        let j = [
            0.5 * (i2 + i3 - i1),
            0.5 * (i1 + i3 - i2),
            0.5 * (i1 + i2 - i3),
        ];
        let largest = moments.iter().fold(0.0f64, |a, &b| a.max(b));
        let tolerance = super::tolerance::MASS_TENSOR_TOLERANCE * largest;
        if let Some(index) = (0..3).find(|&k| j[k] < -tolerance) {
            return Err(InertiaError::NotPhysical3d { moments, index });
        }
        // Round-off below the tolerance is a flat direction: J = 0 exactly.
        Self::from_principal_second_moments(&j.map(|x| x.max(0.0)))
    }

    /// Returns the inertia map of a body about its centre of mass.
    ///
    /// Every body accepted by [`Body`] is accepted here unless its map is singular, exactly
    /// when [`Body::check_inertia_map`] fails.
    ///
    /// # Errors
    /// [`InertiaError::DegeneratePlane`] for a body flat in two directions.
    pub fn from_body(body: &Body) -> Result<Self, InertiaError> {
        Self::from_mass_tensor(body.mass_tensor())
    }

    /// Returns the map that is diagonal on the basis planes with the given plane moments, in
    /// lexicographic order (I₁₂, I₁₃, …, I₁N, I₂₃, …). Any positive moments are accepted,
    /// physical or not.
    ///
    /// # Errors
    /// [`InertiaError::LengthMismatch`] unless there are N(N−1)/2 moments for some N ≥ 2,
    /// [`InertiaError::NonFinite`], [`InertiaError::NotPositiveDefinite`] for a moment ≤ 0.
    pub fn from_plane_moments(plane_moments: &[f64]) -> Result<Self, InertiaError> {
        let k = plane_moments.len();
        let n = (2..=crate::algebra::MAX_DIM)
            .find(|&n| bivector_len(n) == k)
            .ok_or(InertiaError::LengthMismatch {
                quantity: "plane moments",
                index: None,
                expected: bivector_len(
                    ((1.0 + (1.0 + 8.0 * k as f64).sqrt()) / 2.0).ceil() as usize
                ),
                found: k,
            })?;
        let m = DMatrix::from_diagonal(&DVector::from_column_slice(plane_moments));
        Self::from_matrix(n, &m)
    }

    /// Returns the 3D map with classical principal moments of inertia (I₁, I₂, I₃) about
    /// e₁, e₂, e₃, physical or not: the plane moments are I₁₂ = I₃, I₁₃ = I₂, I₂₃ = I₁ (e₁∧e₂ ↔ e₃; see the Conventions chapter of the rotorflow book).
    ///
    /// A physical body satisfies the triangle inequalities Iᵢ ≤ Iⱼ + Iₖ and gives the same
    /// map as [`InertiaMap::from_principal_moments_of_inertia_3d`]; others (the
    /// Hairer–Lubich–Wanner test body (2, 1, 2/3)) are accepted as general maps. Use
    /// [`InertiaMap::from_principal_moments_of_inertia_3d`] to have such moments refused.
    ///
    /// # Errors
    /// [`InertiaError::NonFinite`], [`InertiaError::NotPositiveDefinite`].
    pub fn from_classical_3d(moments: [f64; 3]) -> Result<Self, InertiaError> {
        let [i1, i2, i3] = moments;
        let is_physical = i1 <= i2 + i3 && i2 <= i1 + i3 && i3 <= i1 + i2;
        if moments.iter().all(|x| x.is_finite() && *x > 0.0) && is_physical {
            // J₁ = (I₂ + I₃ − I₁)/2 and cyclic: a real body.
            let j = [
                0.5 * (i2 + i3 - i1),
                0.5 * (i1 + i3 - i2),
                0.5 * (i1 + i2 - i3),
            ];
            if let Ok(map) = Self::from_principal_second_moments(&j) {
                return Ok(map);
            }
        }
        Self::from_plane_moments(&[i3, i2, i1])
    }

    /// Returns a general symmetric positive-definite map on the bivectors of ℝⁿ from its
    /// k×k matrix (k = N(N−1)/2) in the lexicographic basis: column c is the image of the c-th
    /// basis plane.
    ///
    /// # Errors
    /// [`InertiaError::WrongShape`], [`InertiaError::NonFinite`],
    /// [`InertiaError::NotSymmetric`], [`InertiaError::NotPositiveDefinite`].
    pub fn from_matrix(n: usize, matrix: &DMatrix<f64>) -> Result<Self, InertiaError> {
        let k = bivector_len(n);
        check_square("map_on_bivectors", matrix, k, n >= 2)?;
        check_finite_matrix("map_on_bivectors", matrix)?;
        check_symmetric("map_on_bivectors", matrix)?;
        let m = (matrix + matrix.transpose()) * 0.5;
        let eig = crate::numeric::RobustEigen::new(m.clone());
        let smallest = eig.eigenvalues.iter().fold(f64::INFINITY, |a, &b| a.min(b));
        let largest = eig.eigenvalues.iter().fold(0.0f64, |a, &b| a.max(b));
        if smallest.is_nan() || smallest <= SINGULAR_PLANE_TOLERANCE * largest || smallest <= 0.0 {
            return Err(InertiaError::NotPositiveDefinite { smallest });
        }
        let inverse = m
            .clone()
            .cholesky()
            .ok_or(InertiaError::NotPositiveDefinite { smallest })?
            .inverse();
        let is_diag = (0..k).all(|r| (0..k).all(|c| r == c || m[(r, c)] == 0.0));
        let diagonal: Option<Vec<f64>> = is_diag.then(|| (0..k).map(|i| m[(i, i)]).collect());
        let inverse_diagonal = diagonal
            .as_ref()
            .map(|d| d.iter().map(|x| 1.0 / x).collect());
        Ok(InertiaMap {
            dim: n,
            kind: Kind::General {
                matrix: m,
                inverse,
                diagonal,
                inverse_diagonal,
            },
        })
    }

    fn physical(
        j: DMatrix<f64>,
        moments: Vec<f64>,
        axes: DMatrix<f64>,
        diagonal: bool,
    ) -> Result<Self, InertiaError> {
        let n = moments.len();
        check_moments_nonnegative(&moments)?;
        if let Some((plane, plane_moment, largest)) =
            singular_plane(&moments, SINGULAR_PLANE_TOLERANCE)
        {
            return Err(InertiaError::DegeneratePlane {
                plane,
                first: axes.column(plane.0).into_owned(),
                second: axes.column(plane.1).into_owned(),
                plane_moment,
                largest,
            });
        }
        let plane_moments: Vec<f64> = pairs(n).map(|(a, b)| moments[a] + moments[b]).collect();
        let inverse_plane_moments = plane_moments.iter().map(|m| 1.0 / m).collect();
        Ok(InertiaMap {
            dim: n,
            kind: Kind::Physical {
                mass_tensor: j,
                moments,
                axes,
                diagonal,
                plane_moments,
                inverse_plane_moments,
            },
        })
    }

    /// Returns the dimension N of the space.
    #[inline]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Returns the number of planes k = N(N−1)/2, the size of the map's matrix.
    #[inline]
    pub(crate) fn plane_count(&self) -> usize {
        bivector_len(self.dim)
    }

    /// Returns true if the map comes from a mass tensor (a real body).
    pub fn is_physical(&self) -> bool {
        matches!(self.kind, Kind::Physical { .. })
    }

    /// Returns true if the map is diagonal on the basis planes of the body's own axes (the
    /// body frame is the principal frame), so that apply and its inverse are one
    /// multiplication per plane.
    pub fn is_principal(&self) -> bool {
        match &self.kind {
            Kind::Physical { diagonal, .. } => *diagonal,
            Kind::General { diagonal, .. } => diagonal.is_some(),
        }
    }

    /// Returns the plane moments when the map is diagonal on the basis planes of the body's
    /// axes ([`InertiaMap::is_principal`]), in lexicographic order; `None` otherwise. This is
    /// what the splitting integrators need: the energy is then a sum over planes.
    pub fn diagonal_plane_moments(&self) -> Option<&[f64]> {
        match &self.kind {
            Kind::Physical {
                diagonal: true,
                plane_moments,
                ..
            } => Some(plane_moments),
            Kind::Physical { .. } => None,
            Kind::General { diagonal, .. } => diagonal.as_deref(),
        }
    }

    /// The reciprocals of [`InertiaMap::diagonal_plane_moments`], cached at construction.
    pub(crate) fn diagonal_inverse_plane_moments(&self) -> Option<&[f64]> {
        match &self.kind {
            Kind::Physical {
                diagonal,
                inverse_plane_moments,
                ..
            } => diagonal.then_some(inverse_plane_moments.as_slice()),
            Kind::General {
                inverse_diagonal, ..
            } => inverse_diagonal.as_deref(),
        }
    }

    /// Returns the mass tensor J of a physical map (`None` for a general map).
    pub fn mass_tensor(&self) -> Option<&DMatrix<f64>> {
        match &self.kind {
            Kind::Physical { mass_tensor, .. } => Some(mass_tensor),
            Kind::General { .. } => None,
        }
    }

    /// Returns the principal second moments Jᵢ (eigenvalues of J) in the order of
    /// [`InertiaMap::principal_axes`]: ascending, or the given order when J was diagonal.
    /// `None` for a general map. In 3D the moments of inertia are Iᵢ = Jⱼ + Jₖ.
    pub fn principal_second_moments(&self) -> Option<&[f64]> {
        match &self.kind {
            Kind::Physical { moments, .. } => Some(moments),
            Kind::General { .. } => None,
        }
    }

    /// Returns the principal axes as the columns of a rotation matrix P (det +1), with
    /// J = P diag(Jᵢ) Pᵀ. `None` for a general map.
    pub fn principal_axes(&self) -> Option<&DMatrix<f64>> {
        match &self.kind {
            Kind::Physical { axes, .. } => Some(axes),
            Kind::General { .. } => None,
        }
    }

    /// Returns the rotor R_P that takes the body's axes to its principal axes,
    /// R_P eᵢ R̃_P = pᵢ, so that I(ω) = R_P D(R̃_P ω R_P) R̃_P with D diagonal on the basis planes.
    /// `None` for a general map.
    ///
    /// # Errors
    /// [`InertiaError::Algebra`] if N exceeds the rotor limit
    /// ([`crate::algebra::MULTIVECTOR_MAX_DIM`]).
    pub fn principal_rotor(&self) -> Result<Option<Rotor>, InertiaError> {
        match &self.kind {
            Kind::Physical { axes, .. } => Ok(Some(Rotor::from_matrix(axes)?)),
            Kind::General { .. } => Ok(None),
        }
    }

    /// Returns the principal plane moments: Jᵢ + Jⱼ in lexicographic order of the principal
    /// planes for a physical map; the eigenvalues (ascending) of the matrix for a general
    /// one. These are the eigenvalues of the map.
    pub fn plane_moments(&self) -> Vec<f64> {
        match &self.kind {
            Kind::Physical { plane_moments, .. } => plane_moments.clone(),
            Kind::General {
                matrix, diagonal, ..
            } => match diagonal {
                Some(d) => d.clone(),
                None => crate::numeric::sorted_symmetric_eigen(matrix)
                    .0
                    .iter()
                    .copied()
                    .collect(),
            },
        }
    }

    /// Returns the angular momentum L = I(ω).
    ///
    /// # Panics
    /// If ω's dimension differs from the map's (see [`InertiaMap::try_apply`]).
    #[track_caller]
    pub fn apply(&self, omega: &Bivector) -> Bivector {
        self.map_bivector(omega, Self::apply_into)
    }

    /// Checked version of [`InertiaMap::apply`].
    ///
    /// # Errors
    /// [`InertiaError::DimensionMismatch`].
    pub fn try_apply(&self, omega: &Bivector) -> Result<Bivector, InertiaError> {
        check_dims(self.dim, omega.dim()).map(|()| self.apply(omega))
    }

    /// Returns the angular velocity ω = I⁻¹(L).
    ///
    /// # Panics
    /// If L's dimension differs from the map's (see [`InertiaMap::try_apply_inverse`]).
    #[track_caller]
    pub fn apply_inverse(&self, momentum: &Bivector) -> Bivector {
        self.map_bivector(momentum, Self::apply_inverse_into)
    }

    /// Checked version of [`InertiaMap::apply_inverse`].
    ///
    /// # Errors
    /// [`InertiaError::DimensionMismatch`].
    pub fn try_apply_inverse(&self, momentum: &Bivector) -> Result<Bivector, InertiaError> {
        check_dims(self.dim, momentum.dim()).map(|()| self.apply_inverse(momentum))
    }

    /// `kernel` (one of the `_into` maps) on a bivector of the map's dimension.
    #[track_caller]
    fn map_bivector(&self, b: &Bivector, kernel: fn(&Self, &[f64], &mut [f64])) -> Bivector {
        assert_dims(self.dim, b.dim());
        let mut out = Bivector::zero(self.dim);
        kernel(self, b.as_slice(), out.as_mut_slice());
        out
    }

    /// Writes I(ω) into `out` (packed lexicographic components); no allocation when the map
    /// is principal or N ≤ 16.
    pub fn apply_into(&self, omega: &[f64], out: &mut [f64]) {
        if let Some(moments) = self.diagonal_plane_moments() {
            zip_into(out, omega, moments, |w, m| w * m);
            return;
        }
        match &self.kind {
            Kind::Physical { mass_tensor, .. } => jw_plus_wj(self.dim, mass_tensor, omega, out),
            Kind::General { matrix, .. } => mat_vec(matrix, omega, out),
        }
    }

    /// Writes I⁻¹(L) into `out` (packed lexicographic components).
    pub fn apply_inverse_into(&self, momentum: &[f64], out: &mut [f64]) {
        match &self.kind {
            Kind::General {
                diagonal: Some(d), ..
            } => zip_into(out, momentum, d, |l, m| l / m),
            Kind::General { inverse, .. } => mat_vec(inverse, momentum, out),
            Kind::Physical {
                diagonal: true,
                inverse_plane_moments,
                ..
            } => zip_into(out, momentum, inverse_plane_moments, |l, m| l * m),
            Kind::Physical {
                axes,
                inverse_plane_moments,
                ..
            } => {
                // Pᵀ[L]P, divide by Jᵢ + Jⱼ, rotate back: the Lyapunov solution.
                let l = packed_to_dense(self.dim, momentum);
                let lp = axes.transpose() * l * axes;
                let mut w = DMatrix::<f64>::zeros(self.dim, self.dim);
                for ((i, j), inv) in pairs(self.dim).zip(inverse_plane_moments) {
                    let x = lp[(i, j)] * inv;
                    w[(i, j)] = x;
                    w[(j, i)] = -x;
                }
                let back = axes * w * axes.transpose();
                for ((i, j), o) in pairs(self.dim).zip(out.iter_mut()) {
                    *o = 0.5 * (back[(i, j)] - back[(j, i)]);
                }
            }
        }
    }

    /// Returns the kinetic energy T = ½⟨ω, I(ω)⟩ (see the Conventions chapter of the rotorflow book; the paper's eq. 34 is 2T).
    ///
    /// # Panics
    /// If the dimensions differ.
    #[track_caller]
    pub fn kinetic_energy(&self, omega: &Bivector) -> f64 {
        0.5 * omega.inner(&self.apply(omega))
    }

    /// Returns the k×k matrix of the map in the lexicographic basis of planes (column c is
    /// the image of the c-th basis plane); symmetric positive definite.
    pub fn to_matrix(&self) -> DMatrix<f64> {
        if let Kind::General { matrix, .. } = &self.kind {
            return matrix.clone();
        }
        let k = self.plane_count();
        let mut m = DMatrix::zeros(k, k);
        let mut e = vec![0.0; k];
        let mut col = vec![0.0; k];
        for c in 0..k {
            e.iter_mut().for_each(|x| *x = 0.0);
            e[c] = 1.0;
            self.apply_into(&e, &mut col);
            m.column_mut(c).copy_from_slice(&col);
        }
        m
    }

    /// Returns the map of the same body turned by the rotor R: I′(ω) = R I(R̃ ω R) R̃. For a
    /// physical body this is the map of J′ = Q J Qᵀ (Q the rotation matrix of R).
    ///
    /// # Errors
    /// [`InertiaError::DimensionMismatch`].
    pub fn rotated(&self, rotor: &Rotor) -> Result<Self, InertiaError> {
        check_dims(self.dim, rotor.dim())?;
        let q = rotor.to_matrix();
        match &self.kind {
            Kind::Physical { mass_tensor, .. } => {
                Self::from_mass_tensor(&(&q * mass_tensor * q.transpose()))
            }
            Kind::General { matrix, .. } => {
                // [R]₂: the k×k matrix of B ↦ R B R̃.
                let k = self.plane_count();
                let mut r2 = DMatrix::zeros(k, k);
                for c in 0..k {
                    let mut b = Bivector::zero(self.dim);
                    b.as_mut_slice()[c] = 1.0;
                    let rb = rotor.rotate_bivector(&b);
                    r2.column_mut(c).copy_from_slice(rb.as_slice());
                }
                Self::from_matrix(self.dim, &(&r2 * matrix * r2.transpose()))
            }
        }
    }
}

#[track_caller]
/// `out[k] = f(x[k], y[k])` for every component.
#[inline]
fn zip_into(out: &mut [f64], x: &[f64], y: &[f64], f: impl Fn(f64, f64) -> f64) {
    for ((o, a), b) in out.iter_mut().zip(x).zip(y) {
        *o = f(*a, *b);
    }
}

fn assert_dims(map: usize, argument: usize) {
    assert!(
        map == argument,
        "rotorflow: dimension mismatch: map has dimension {map}, argument has dimension {argument}"
    );
}

fn check_dims(map: usize, argument: usize) -> Result<(), InertiaError> {
    if map == argument {
        Ok(())
    } else {
        Err(InertiaError::DimensionMismatch {
            quantity: "argument",
            expected: map,
            found: argument,
        })
    }
}

fn mat_vec(m: &DMatrix<f64>, x: &[f64], out: &mut [f64]) {
    for (r, o) in out.iter_mut().enumerate() {
        *o = (0..x.len()).map(|c| m[(r, c)] * x[c]).sum();
    }
}

fn packed_to_dense(n: usize, packed: &[f64]) -> DMatrix<f64> {
    let mut m = DMatrix::zeros(n, n);
    for ((i, j), &c) in pairs(n).zip(packed) {
        m[(i, j)] = c;
        m[(j, i)] = -c;
    }
    m
}

/// out = packed([J][ω] + [ω][J]) for i < j: Σₖ Jᵢₖ ωₖⱼ + ωᵢₖ Jₖⱼ, from dense rows on the
/// stack (N ≤ 16).
fn jw_plus_wj(n: usize, j: &DMatrix<f64>, omega: &[f64], out: &mut [f64]) {
    let mut stack = [0.0f64; 256];
    let mut heap = Vec::new();
    let w: &mut [f64] = if n <= 16 {
        &mut stack[..n * n]
    } else {
        heap.resize(n * n, 0.0);
        &mut heap
    };
    for ((i, jj), &c) in pairs(n).zip(omega) {
        w[i * n + jj] = c;
        w[jj * n + i] = -c;
    }
    for ((i, jj), o) in pairs(n).zip(out.iter_mut()) {
        let mut s = 0.0;
        for k in 0..n {
            // J is symmetric: J_ik = J_ki, and ω_kj = −ω_jk.
            s += j[(i, k)] * w[k * n + jj] + w[i * n + k] * j[(k, jj)];
        }
        *o = s;
    }
}
