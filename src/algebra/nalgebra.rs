//! Conversions between the algebra's types and nalgebra's vectors, matrices, quaternions and
//! rotations (all in one place, as nalgebra's own `third_party/` and glam's `features/`).
//!
//! | from | to | how |
//! |---|---|---|
//! | `DVector`, `SVector<f64, D>` | `Vector` | `From` (vectors) |
//! | `Vector` | `DVector` | `From` |
//! | `Bivector` | `DMatrix` (skew \[B\]) | `From`, [`Bivector::to_skew_matrix`] |
//! | `DMatrix`, `SMatrix<f64, D, D>` | `Bivector` | `TryFrom` (checks skewness) |
//! | `Rotor` | `DMatrix` (rotation) | `From`, [`Rotor::to_matrix`] |
//! | `DMatrix`, `SMatrix<f64, D, D>` | `Rotor` | `TryFrom` (checks SO(N)), [`Rotor::from_matrix`] |
//! | `UnitQuaternion`, `Rotation3` | `Rotor` (N = 3) | `From` |
//! | `Rotor` (N = 3) | `UnitQuaternion`, `Rotation3` | `TryFrom` (checks N = 3) |
//!
//! The quaternion convention: nalgebra's q = w + xi + yj + zk turns v into q v q*, a
//! right-handed rotation about (x, y, z). The same rotation as a rotor is
//! R = w − x e₂₃ + y e₁₃ − z e₁₂ (e₁∧e₂ ↔ e₃; see the Conventions chapter of the rotorflow
//! book), so both give the same matrix.

use super::rotor::even_index;
use super::{AlgebraError, Bivector, Rotor, Vector};
use nalgebra::{DMatrix, DVector, Quaternion, Rotation3, SMatrix, SVector, UnitQuaternion};

impl From<&DVector<f64>> for Vector {
    fn from(v: &DVector<f64>) -> Self {
        Vector::from_storage(v.iter().copied().collect())
    }
}

impl From<DVector<f64>> for Vector {
    fn from(v: DVector<f64>) -> Self {
        Vector::from(&v)
    }
}

impl<const D: usize> From<&SVector<f64, D>> for Vector {
    fn from(v: &SVector<f64, D>) -> Self {
        Vector::from_storage(v.iter().copied().collect())
    }
}

impl<const D: usize> From<SVector<f64, D>> for Vector {
    fn from(v: SVector<f64, D>) -> Self {
        Vector::from(&v)
    }
}

impl From<&Vector> for DVector<f64> {
    fn from(v: &Vector) -> Self {
        DVector::from_column_slice(v.as_slice())
    }
}

impl Vector {
    /// Returns the components as an nalgebra `DVector`.
    pub fn to_dvector(&self) -> DVector<f64> {
        DVector::from_column_slice(self.as_slice())
    }

    /// Returns the components as a fixed-size nalgebra vector.
    ///
    /// # Panics
    /// If `D` differs from the vector's dimension.
    #[track_caller]
    pub fn to_svector<const D: usize>(&self) -> SVector<f64, D> {
        super::error::assert_same_dim(D, self.dim());
        SVector::from_fn(|i, _| self[i])
    }
}

impl From<&Bivector> for DMatrix<f64> {
    /// The skew matrix \[B\].
    fn from(b: &Bivector) -> Self {
        b.to_skew_matrix()
    }
}

impl TryFrom<&DMatrix<f64>> for Bivector {
    type Error = AlgebraError;
    /// See [`Bivector::from_skew_matrix`].
    fn try_from(m: &DMatrix<f64>) -> Result<Self, AlgebraError> {
        Bivector::from_skew_matrix(m)
    }
}

impl<const D: usize> TryFrom<&SMatrix<f64, D, D>> for Bivector {
    type Error = AlgebraError;
    /// See [`Bivector::from_skew_matrix`].
    fn try_from(m: &SMatrix<f64, D, D>) -> Result<Self, AlgebraError> {
        Bivector::from_skew_entries(D, D, crate::algebra::SKEW_TOLERANCE, |i, j| m[(i, j)])
    }
}

impl Bivector {
    /// Returns the skew matrix \[B\] as a fixed-size nalgebra matrix.
    ///
    /// # Panics
    /// If `D` differs from the bivector's dimension.
    #[track_caller]
    pub fn to_skew_smatrix<const D: usize>(&self) -> SMatrix<f64, D, D> {
        super::error::assert_same_dim(D, self.dim());
        SMatrix::from_fn(|i, j| self.get(i, j))
    }
}

impl From<&Rotor> for DMatrix<f64> {
    /// The rotation matrix (see [`Rotor::to_matrix`]).
    fn from(r: &Rotor) -> Self {
        r.to_matrix()
    }
}

impl TryFrom<&DMatrix<f64>> for Rotor {
    type Error = AlgebraError;
    /// See [`Rotor::from_matrix`].
    fn try_from(m: &DMatrix<f64>) -> Result<Self, AlgebraError> {
        Rotor::from_matrix(m)
    }
}

impl<const D: usize> TryFrom<&SMatrix<f64, D, D>> for Rotor {
    type Error = AlgebraError;
    /// See [`Rotor::from_matrix`].
    fn try_from(m: &SMatrix<f64, D, D>) -> Result<Self, AlgebraError> {
        Rotor::from_matrix(&DMatrix::from_fn(D, D, |i, j| m[(i, j)]))
    }
}

impl From<UnitQuaternion<f64>> for Rotor {
    /// R = w − x e₂₃ + y e₁₃ − z e₁₂ (same rotation, same matrix).
    fn from(q: UnitQuaternion<f64>) -> Self {
        let q = q.quaternion();
        let mut coeffs: super::rotor::RotorStorage = smallvec::smallvec![0.0; 4];
        coeffs[0] = q.w;
        coeffs[even_index(3, 0b011)] = -q.k;
        coeffs[even_index(3, 0b101)] = q.j;
        coeffs[even_index(3, 0b110)] = -q.i;
        Rotor::from_storage(3, coeffs)
    }
}

impl From<&UnitQuaternion<f64>> for Rotor {
    fn from(q: &UnitQuaternion<f64>) -> Self {
        Rotor::from(*q)
    }
}

impl From<Rotation3<f64>> for Rotor {
    fn from(q: Rotation3<f64>) -> Self {
        Rotor::from(UnitQuaternion::from_rotation_matrix(&q))
    }
}

impl TryFrom<&Rotor> for UnitQuaternion<f64> {
    type Error = AlgebraError;
    /// The unit quaternion of a 3D rotor (normalised).
    ///
    /// # Errors
    /// [`AlgebraError::DimensionMismatch`] unless N = 3.
    fn try_from(r: &Rotor) -> Result<Self, AlgebraError> {
        if r.dim() != 3 {
            return Err(AlgebraError::DimensionMismatch {
                left: r.dim(),
                right: 3,
            });
        }
        let w = r.scalar();
        let x = -r.coefficient(0b110);
        let y = r.coefficient(0b101);
        let z = -r.coefficient(0b011);
        Ok(UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z)))
    }
}

impl TryFrom<&Rotor> for Rotation3<f64> {
    type Error = AlgebraError;
    /// The rotation matrix of a 3D rotor.
    ///
    /// # Errors
    /// [`AlgebraError::DimensionMismatch`] unless N = 3.
    fn try_from(r: &Rotor) -> Result<Self, AlgebraError> {
        Ok(UnitQuaternion::try_from(r)?.to_rotation_matrix())
    }
}
