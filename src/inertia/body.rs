//! [`Body`]: mass, centre of mass, mass tensor and volume of a rigid body in N dimensions, with
//! the queries and rigid motions every body shares. The named bodies are in the catalogue
//! (`catalogue.rs`), meshes in `mesh.rs`.

use super::InertiaError;
use super::tolerance::{ORTHOGONALITY_TOLERANCE, SINGULAR_PLANE_TOLERANCE};
use super::validate::{
    check_dim, check_finite_matrix, check_moments_nonnegative, check_point, check_points,
    check_positive, check_square, check_symmetric, max_abs, singular_plane, sorted_eigen,
    symmetrize,
};
use crate::algebra::{Rotor, Vector};
use nalgebra::{DMatrix, DVector};

/// A rigid body in N dimensions: mass, centre of mass, mass tensor about the centre of mass,
/// and volume for solids.
///
/// Build one with a constructor from the [table of contents](super::bodies). All constructors
/// validate their input and return [`InertiaError`] instead of panicking or producing NaN.
///
/// Rotations and points can be given as rotorflow's [`Rotor`] and [`Vector`]
/// ([`Body::rotated_by`], [`Body::translated_by`], [`Body::placed_by`],
/// [`Body::point_masses_at`], [`Body::center_of_mass_vector`], [`Body::principal_rotor`]) or as
/// nalgebra matrices and vectors (the methods without the suffix); `DVector::from(&vector)`,
/// `Vector::from(&dvector)`, `rotor.to_matrix()` and `Rotor::from_matrix(&q)` convert between
/// them.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    dim: usize,
    mass: f64,
    center_of_mass: DVector<f64>,
    mass_tensor: DMatrix<f64>,
    volume: Option<f64>,
}

impl Body {
    /// Checks the computed fields for overflow, symmetrizes J and builds the body.
    pub(super) fn new_checked(
        mass: f64,
        center_of_mass: DVector<f64>,
        mass_tensor: DMatrix<f64>,
        volume: Option<f64>,
    ) -> Result<Body, InertiaError> {
        if !mass.is_finite() {
            return Err(InertiaError::NonFiniteResult { quantity: "mass" });
        }
        if center_of_mass.iter().any(|x| !x.is_finite()) {
            return Err(InertiaError::NonFiniteResult {
                quantity: "center_of_mass",
            });
        }
        if mass_tensor.iter().any(|x| !x.is_finite()) {
            return Err(InertiaError::NonFiniteResult {
                quantity: "mass_tensor",
            });
        }
        if let Some(v) = volume
            && !v.is_finite()
        {
            return Err(InertiaError::NonFiniteResult { quantity: "volume" });
        }
        Ok(Body {
            dim: center_of_mass.len(),
            mass,
            mass_tensor: symmetrize(&mass_tensor),
            center_of_mass,
            volume,
        })
    }

    /// Returns the body made of point masses `masses[k]` at `positions[k]`.
    ///
    /// The centre of mass is c = Σ mₖ xₖ / Σ mₖ and J = Σ mₖ (xₖ − c)(xₖ − c)ᵀ
    /// (see the Conventions chapter of the rotorflow book). The volume is `None`.
    ///
    /// # Errors
    /// [`InertiaError::Empty`] for no points, [`InertiaError::LengthMismatch`] if the lists differ in
    /// length or the positions differ in dimension, [`InertiaError::NonFinite`] or
    /// [`InertiaError::NotPositive`] for bad numbers, [`InertiaError::DimensionTooSmall`] for
    /// zero-length positions.
    ///
    /// # Example
    /// ```
    /// use rotorflow::inertia::Body;
    /// use nalgebra::DVector;
    /// let rod = Body::point_masses(
    ///     &[1.0, 1.0],
    ///     &[DVector::from_vec(vec![-1.0, 0.0]), DVector::from_vec(vec![1.0, 0.0])],
    /// )?;
    /// assert_eq!(rod.mass_tensor()[(0, 0)], 2.0);
    /// assert_eq!(rod.mass_tensor()[(1, 1)], 0.0);
    /// # Ok::<(), rotorflow::inertia::InertiaError>(())
    /// ```
    pub fn point_masses(masses: &[f64], positions: &[DVector<f64>]) -> Result<Body, InertiaError> {
        let dim = check_points("positions", positions)?;
        if masses.len() != positions.len() {
            return Err(InertiaError::LengthMismatch {
                quantity: "masses",
                index: None,
                expected: positions.len(),
                found: masses.len(),
            });
        }
        for (i, &m) in masses.iter().enumerate() {
            check_positive("masses", Some(i), m)?;
        }
        // Work relative to the unweighted mean to keep cancellation small.
        let reference =
            positions.iter().fold(DVector::zeros(dim), |acc, p| acc + p) / positions.len() as f64;
        let total: f64 = masses.iter().sum();
        let mut first = DVector::zeros(dim);
        for (m, p) in masses.iter().zip(positions) {
            first += (p - &reference) * *m;
        }
        let shift = first / total;
        let center = &reference + &shift;
        let mut j = DMatrix::zeros(dim, dim);
        for (m, p) in masses.iter().zip(positions) {
            let d = p - &center;
            j.ger(*m, &d, &d, 1.0);
        }
        Body::new_checked(total, center, j, None)
    }

    /// Returns the body made of point masses `masses[k]` at the points `positions[k]`, given
    /// as rotorflow [`Vector`]s; otherwise as [`Body::point_masses`].
    ///
    /// # Errors
    /// As [`Body::point_masses`].
    ///
    /// ```
    /// use rotorflow::algebra::Vector;
    /// use rotorflow::inertia::Body;
    /// let rod = Body::point_masses_at(&[1.0, 1.0], &[Vector::basis(2, 0), -Vector::basis(2, 0)])?;
    /// assert_eq!(rod.mass_tensor()[(0, 0)], 2.0);
    /// # Ok::<(), rotorflow::inertia::InertiaError>(())
    /// ```
    pub fn point_masses_at(masses: &[f64], positions: &[Vector]) -> Result<Body, InertiaError> {
        let positions: Vec<DVector<f64>> = positions.iter().map(DVector::from).collect();
        Body::point_masses(masses, &positions)
    }

    /// Returns the union of `parts`, which must not overlap, each already placed (see
    /// [`Body::placed`]).
    ///
    /// Mass Σ mₖ, centre c = Σ mₖ cₖ / M, and J = Σₖ (Jₖ + mₖ dₖ dₖᵀ) with
    /// dₖ = cₖ − c (parallel-axis theorem). The volume is the sum of the
    /// parts' volumes if every part has one, else `None`. Overlaps are not detected: they
    /// count twice.
    ///
    /// # Errors
    /// [`InertiaError::Empty`]; [`InertiaError::LengthMismatch`] if the parts differ in dimension;
    /// [`InertiaError::NonFiniteResult`] on overflow.
    pub fn composite(parts: &[Body]) -> Result<Body, InertiaError> {
        let first = parts
            .first()
            .ok_or(InertiaError::Empty { quantity: "parts" })?;
        let dim = first.dim;
        for (i, p) in parts.iter().enumerate() {
            if p.dim != dim {
                return Err(InertiaError::LengthMismatch {
                    quantity: "parts",
                    index: Some(i),
                    expected: dim,
                    found: p.dim,
                });
            }
        }
        let reference = first.center_of_mass.clone();
        let total: f64 = parts.iter().map(|p| p.mass).sum();
        let mut moment = DVector::zeros(dim);
        for p in parts {
            moment += (&p.center_of_mass - &reference) * p.mass;
        }
        let center = &reference + moment / total;
        let mut j = DMatrix::zeros(dim, dim);
        for p in parts {
            let d = &p.center_of_mass - &center;
            j += &p.mass_tensor;
            j.ger(p.mass, &d, &d, 1.0);
        }
        let volume = parts.iter().map(|p| p.volume).sum::<Option<f64>>();
        Body::new_checked(total, center, j, volume)
    }

    /// Returns the body with the given mass properties, after checking them.
    ///
    /// The mass tensor must be symmetric within
    /// [`SYMMETRY_TOLERANCE`](super::tolerance::SYMMETRY_TOLERANCE) and have no eigenvalue
    /// below −[`MASS_TENSOR_TOLERANCE`](super::tolerance::MASS_TENSOR_TOLERANCE) times its
    /// largest: the same checks as [`InertiaMap::from_mass_tensor`](super::InertiaMap::from_mass_tensor).
    ///
    /// # Errors
    /// [`InertiaError::NotPositive`], [`InertiaError::NonFinite`], [`InertiaError::WrongShape`]
    /// when J is not N×N, [`InertiaError::NotSymmetric`] or [`InertiaError::NegativeMoment`].
    pub fn from_mass_properties(
        mass: f64,
        center_of_mass: DVector<f64>,
        mass_tensor: DMatrix<f64>,
        volume: Option<f64>,
    ) -> Result<Body, InertiaError> {
        check_positive("mass", None, mass)?;
        let dim = center_of_mass.len();
        check_dim(dim, 1)?;
        check_point("center_of_mass", None, &center_of_mass, dim)?;
        if let Some(v) = volume {
            check_positive("volume", None, v)?;
        }
        check_square("mass_tensor", &mass_tensor, dim, true)?;
        check_finite_matrix("mass_tensor", &mass_tensor)?;
        check_symmetric("mass_tensor", &mass_tensor)?;
        let j = symmetrize(&mass_tensor);
        check_moments_nonnegative(sorted_eigen(&j).0.as_slice())?;
        Body::new_checked(mass, center_of_mass, j, volume)
    }

    /// Returns the dimension N of the space the body lives in.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Returns the total mass m.
    pub fn mass(&self) -> f64 {
        self.mass
    }

    /// Returns the centre of mass c (length N).
    pub fn center_of_mass(&self) -> &DVector<f64> {
        &self.center_of_mass
    }

    /// Returns the mass tensor J = ∫ (x − c)(x − c)ᵀ dm about the centre of mass (N×N,
    /// symmetric, positive semidefinite).
    pub fn mass_tensor(&self) -> &DMatrix<f64> {
        &self.mass_tensor
    }

    /// Returns the N-volume for solids, `None` for point sets and shells (and composites with
    /// such parts).
    pub fn volume(&self) -> Option<f64> {
        self.volume
    }

    /// Returns the mean density m / Volume, `None` when the body has no volume.
    pub fn density(&self) -> Option<f64> {
        self.volume.map(|v| self.mass / v)
    }

    /// Returns the mass tensor about `point`: J_O = J + m d dᵀ with d = c − O (parallel-axis
    /// theorem).
    ///
    /// # Errors
    /// [`InertiaError::LengthMismatch`] or [`InertiaError::NonFinite`] for a bad point.
    pub fn mass_tensor_about(&self, point: &DVector<f64>) -> Result<DMatrix<f64>, InertiaError> {
        check_point("point", None, point, self.dim)?;
        let d = &self.center_of_mass - point;
        let mut j = self.mass_tensor.clone();
        j.ger(self.mass, &d, &d, 1.0);
        Ok(j)
    }

    /// Returns the principal second moments J₁ ≤ … ≤ J_N: the eigenvalues of the mass tensor
    /// J, ascending, Jᵢ = ∫ xᵢ² dm in the principal frame.
    ///
    /// These are not the 3D moments of inertia Iᵢ = Jⱼ + Jₖ; for those use
    /// [`Body::principal_moments_of_inertia_3d`] (3D) or [`Body::principal_plane_moments`]
    /// (any N: the moment of each principal plane).
    pub fn principal_second_moments(&self) -> DVector<f64> {
        sorted_eigen(&self.mass_tensor).0
    }

    /// Returns the classical principal moments of inertia of a 3D body,
    /// I₁ = J₂ + J₃, I₂ = J₁ + J₃, I₃ = J₁ + J₂, about the principal axes of
    /// [`Body::principal_frame`] (Jᵢ ascending, so I₁ ≥ I₂ ≥ I₃); `None` unless N = 3.
    ///
    /// [`InertiaMap::from_principal_moments_of_inertia_3d`](super::InertiaMap::from_principal_moments_of_inertia_3d)
    /// takes these back.
    ///
    /// ```
    /// use rotorflow::inertia::Body;
    /// // Solid cuboid with half-sides (0.5, 1, 1.5) and mass 12: J = (1, 4, 9).
    /// let cuboid = Body::solid_cuboid(&[0.5, 1.0, 1.5], 1.0)?.with_mass(12.0)?;
    /// let i = cuboid.principal_moments_of_inertia_3d().unwrap();
    /// assert!((i[0] - 13.0).abs() < 1e-12 && (i[1] - 10.0).abs() < 1e-12 && (i[2] - 5.0).abs() < 1e-12);
    /// # Ok::<(), rotorflow::inertia::InertiaError>(())
    /// ```
    pub fn principal_moments_of_inertia_3d(&self) -> Option<[f64; 3]> {
        if self.dim != 3 {
            return None;
        }
        let j = self.principal_second_moments();
        Some([j[1] + j[2], j[0] + j[2], j[0] + j[1]])
    }

    /// Returns the principal second moments (ascending) and the principal axes as the columns
    /// of a rotation matrix P (det P = +1), so that J = P diag(Jᵢ) Pᵀ.
    pub fn principal_frame(&self) -> (DVector<f64>, DMatrix<f64>) {
        let (values, mut axes) = sorted_eigen(&self.mass_tensor);
        if axes.determinant() < 0.0 {
            let last = self.dim - 1;
            let flipped = -axes.column(last);
            axes.set_column(last, &flipped);
        }
        (values, axes)
    }

    /// Returns the plane moments Jᵢᵢ + Jⱼⱼ in the body's own axes, one per plane (i, j),
    /// i < j, in lexicographic order 12, 13, …, 1N, 23, … ([`crate::algebra::pairs`]).
    ///
    /// In the principal frame these are the eigenvalues of the inertia map on bivectors,
    /// I(eᵢ ∧ eⱼ) = (Jᵢ + Jⱼ) eᵢ ∧ eⱼ (see the Conventions chapter of the rotorflow book). In a general frame they
    /// are its diagonal entries ⟨eᵢ∧eⱼ, I(eᵢ∧eⱼ)⟩. Empty for N = 1.
    pub fn plane_moments(&self) -> DVector<f64> {
        let pairs: Vec<(usize, usize)> = crate::algebra::pairs(self.dim).collect();
        DVector::from_iterator(
            pairs.len(),
            pairs
                .iter()
                .map(|&(i, j)| self.mass_tensor[(i, i)] + self.mass_tensor[(j, j)]),
        )
    }

    /// Returns the principal plane moments Jᵢ + Jⱼ (principal second moments ascending, planes in
    /// lexicographic order), the eigenvalues of the inertia map.
    ///
    /// In 4D they satisfy I₁₂ + I₃₄ = I₁₃ + I₂₄ = I₁₄ + I₂₃ = tr J.
    pub fn principal_plane_moments(&self) -> DVector<f64> {
        let moments = self.principal_second_moments();
        let pairs: Vec<(usize, usize)> = crate::algebra::pairs(self.dim).collect();
        DVector::from_iterator(
            pairs.len(),
            pairs.iter().map(|&(i, j)| moments[i] + moments[j]),
        )
    }

    /// Returns the unit directions (principal axes, in the body's axes) along which the body
    /// has no extent: eigenvectors of J with eigenvalue ≤ `rel_tol` · max eigenvalue.
    ///
    /// A body with k flat directions lies in an (N−k)-dimensional affine subspace through its
    /// centre of mass. A single point is flat in every direction. Use
    /// [`FLATNESS_TOLERANCE`](super::tolerance::FLATNESS_TOLERANCE) unless you have a reason not to.
    pub fn flat_directions(&self, rel_tol: f64) -> Vec<DVector<f64>> {
        let (values, vectors) = sorted_eigen(&self.mass_tensor);
        let largest = values[self.dim - 1].max(0.0);
        (0..self.dim)
            .filter(|&k| values[k] <= rel_tol * largest)
            .map(|k| vectors.column(k).into_owned())
            .collect()
    }

    /// Checks that J is non-singular, i.e. the body is not flat in any direction.
    ///
    /// # Errors
    /// [`InertiaError::FlatBody`] naming the flattest direction when its second moment is
    /// ≤ `rel_tol` · the largest.
    pub fn check_full_rank(&self, rel_tol: f64) -> Result<(), InertiaError> {
        let (values, vectors) = sorted_eigen(&self.mass_tensor);
        let largest = values[self.dim - 1].max(0.0);
        if values[0] <= rel_tol * largest {
            return Err(InertiaError::FlatBody {
                direction: vectors.column(0).into_owned(),
                moment: values[0],
                largest_moment: largest,
            });
        }
        Ok(())
    }

    /// Checks that the inertia map I(ω) = J\[ω\] + \[ω\]J is invertible, i.e. every principal
    /// plane moment Jₖ + Jₗ exceeds `rel_tol` times the largest plane moment. This fails
    /// exactly when the body is flat in at least two directions (or N ≥ 2 and the body is a
    /// point).
    ///
    /// With `rel_tol` = [`SINGULAR_PLANE_TOLERANCE`](super::tolerance::SINGULAR_PLANE_TOLERANCE)
    /// this is the check [`InertiaMap::from_body`](super::InertiaMap::from_body) makes: it
    /// passes exactly when that constructor succeeds.
    ///
    /// In 1D there are no planes and the check passes.
    ///
    /// # Errors
    /// [`InertiaError::DegeneratePlane`] naming the principal plane with the smallest moment.
    pub fn check_inertia_invertible(&self, rel_tol: f64) -> Result<(), InertiaError> {
        if self.dim < 2 {
            return Ok(());
        }
        let (values, vectors) = sorted_eigen(&self.mass_tensor);
        match singular_plane(values.as_slice(), rel_tol) {
            None => Ok(()),
            Some((plane, plane_moment, largest)) => Err(InertiaError::DegeneratePlane {
                plane,
                first: vectors.column(plane.0).into_owned(),
                second: vectors.column(plane.1).into_owned(),
                plane_moment,
                largest,
            }),
        }
    }

    /// Checks [`Body::check_inertia_invertible`] with the tolerance of the inertia map,
    /// [`SINGULAR_PLANE_TOLERANCE`](super::tolerance::SINGULAR_PLANE_TOLERANCE).
    ///
    /// # Errors
    /// [`InertiaError::DegeneratePlane`].
    pub fn check_inertia_map(&self) -> Result<(), InertiaError> {
        self.check_inertia_invertible(SINGULAR_PLANE_TOLERANCE)
    }

    /// Returns the same body with total mass `mass` (J scaled by mass/m, same centre of mass
    /// and volume, so the density scales too).
    ///
    /// # Errors
    /// [`InertiaError::NonFinite`], [`InertiaError::NotPositive`], [`InertiaError::NonFiniteResult`].
    pub fn with_mass(&self, mass: f64) -> Result<Body, InertiaError> {
        check_positive("mass", None, mass)?;
        let factor = mass / self.mass;
        Body::new_checked(
            mass,
            self.center_of_mass.clone(),
            &self.mass_tensor * factor,
            self.volume,
        )
    }

    /// Returns the body turned by the rotation matrix Q about the origin of coordinates:
    /// c' = Q c and J' = Q J Qᵀ. For rotors use [`Body::rotated_by`].
    ///
    /// Q must be a rotation: orthogonal within [`ORTHOGONALITY_TOLERANCE`] (the tolerance of
    /// [`Rotor::from_matrix`]) with det Q > 0. A mirror image is
    /// [`Body::orthogonally_transformed`].
    ///
    /// # Errors
    /// [`InertiaError::WrongShape`] if Q is not N×N, [`InertiaError::NonFinite`],
    /// [`InertiaError::NotOrthogonal`] if max |QᵀQ − 1| > [`ORTHOGONALITY_TOLERANCE`],
    /// [`InertiaError::Reflection`] if det Q < 0.
    pub fn rotated(&self, rotation: &DMatrix<f64>) -> Result<Body, InertiaError> {
        check_orthogonal(rotation, self.dim)?;
        let determinant = rotation.determinant();
        if determinant < 0.0 {
            return Err(InertiaError::Reflection { determinant });
        }
        self.transform_unchecked(rotation)
    }

    /// Returns the body mapped by the orthogonal matrix Q (a rotation or a reflection) about
    /// the origin of coordinates: c' = Q c and J' = Q J Qᵀ. The mass tensor of a mirror image
    /// follows the same formula.
    ///
    /// # Errors
    /// As [`Body::rotated`], without the refusal of reflections.
    pub fn orthogonally_transformed(&self, q: &DMatrix<f64>) -> Result<Body, InertiaError> {
        check_orthogonal(q, self.dim)?;
        self.transform_unchecked(q)
    }

    fn transform_unchecked(&self, q: &DMatrix<f64>) -> Result<Body, InertiaError> {
        let j = q * &self.mass_tensor * q.transpose();
        Body::new_checked(self.mass, q * &self.center_of_mass, j, self.volume)
    }

    /// Returns the body turned by the rotor R about the origin of coordinates:
    /// c' = R c R̃ and J' = Q J Qᵀ with Q the rotation matrix of R.
    ///
    /// # Errors
    /// [`InertiaError::DimensionMismatch`] if R is not of the body's dimension.
    ///
    /// ```
    /// use rotorflow::algebra::{Bivector, Vector};
    /// use rotorflow::inertia::Body;
    /// let body = Body::solid_cuboid(&[1.0, 2.0, 3.0], 1.0)?;
    /// let quarter = Bivector::from_plane(3, 0, 1, std::f64::consts::FRAC_PI_4)?.exp();
    /// let turned = body.rotated_by(&quarter)?.translated_by(&Vector::basis(3, 2))?;
    /// assert!((turned.mass_tensor()[(0, 0)] - body.mass_tensor()[(1, 1)]).abs() < 1e-12);
    /// assert!((turned.center_of_mass_vector().as_slice()[2] - 1.0).abs() < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn rotated_by(&self, rotor: &Rotor) -> Result<Body, InertiaError> {
        if rotor.dim() != self.dim {
            return Err(InertiaError::DimensionMismatch {
                quantity: "rotor",
                expected: self.dim,
                found: rotor.dim(),
            });
        }
        self.transform_unchecked(&rotor.to_matrix())
    }

    /// Returns the body moved by the vector `offset`: c' = c + offset, J unchanged.
    ///
    /// # Errors
    /// [`InertiaError::LengthMismatch`] or [`InertiaError::NonFinite`] for a bad offset.
    pub fn translated_by(&self, offset: &Vector) -> Result<Body, InertiaError> {
        self.translated(&DVector::from(offset))
    }

    /// Returns the body turned by the rotor R about the origin and then moved by `offset`;
    /// the usual way to place a part before [`Body::composite`].
    ///
    /// # Errors
    /// As [`Body::rotated_by`] and [`Body::translated_by`].
    pub fn placed_by(&self, rotor: &Rotor, offset: &Vector) -> Result<Body, InertiaError> {
        self.rotated_by(rotor)?.translated_by(offset)
    }

    /// Returns the centre of mass as a [`Vector`] (see [`Body::center_of_mass`] for the
    /// nalgebra vector).
    pub fn center_of_mass_vector(&self) -> Vector {
        Vector::from(&self.center_of_mass)
    }

    /// Returns the rotor R_P that takes the body's axes to its principal axes,
    /// R_P eᵢ R̃_P = pᵢ, the columns of the matrix of [`Body::principal_frame`].
    ///
    /// # Errors
    /// [`InertiaError::Algebra`] if N exceeds the rotor limit
    /// ([`crate::algebra::MULTIVECTOR_MAX_DIM`]).
    pub fn principal_rotor(&self) -> Result<Rotor, InertiaError> {
        Ok(Rotor::from_matrix(&self.principal_frame().1)?)
    }

    /// Returns the body moved by `offset`: c' = c + offset, J unchanged.
    ///
    /// # Errors
    /// [`InertiaError::LengthMismatch`] or [`InertiaError::NonFinite`] for a bad offset.
    pub fn translated(&self, offset: &DVector<f64>) -> Result<Body, InertiaError> {
        check_point("offset", None, offset, self.dim)?;
        Body::new_checked(
            self.mass,
            &self.center_of_mass + offset,
            self.mass_tensor.clone(),
            self.volume,
        )
    }

    /// Returns the body rotated by the rotation matrix Q about the origin and then moved by
    /// `offset` (`self.rotated(rotation)?.translated(offset)`); see [`Body::placed_by`] for
    /// rotors and vectors.
    ///
    /// # Errors
    /// As [`Body::rotated`] and [`Body::translated`].
    pub fn placed(
        &self,
        rotation: &DMatrix<f64>,
        offset: &DVector<f64>,
    ) -> Result<Body, InertiaError> {
        self.rotated(rotation)?.translated(offset)
    }
}

fn check_orthogonal(rotation: &DMatrix<f64>, dim: usize) -> Result<(), InertiaError> {
    check_square("rotation", rotation, dim, true)?;
    check_finite_matrix("rotation", rotation)?;
    let deviation = max_abs(&(rotation.transpose() * rotation - DMatrix::identity(dim, dim)));
    if deviation > ORTHOGONALITY_TOLERANCE {
        return Err(InertiaError::NotOrthogonal {
            deviation,
            tolerance: ORTHOGONALITY_TOLERANCE,
        });
    }
    Ok(())
}
