//! Conversions between the fixed-size rotors and glam's types (feature `glam`), in both
//! scalar types: `Quat`/`DQuat` ↔ `Rotor3<f32>`/`Rotor3<f64>`, a pair of quaternions ↔
//! `Rotor4`, rotors times `Vec3`/`DVec3` and `Vec4`/`DVec4`, and rotation matrices
//! `Mat3`/`DMat3` and `Mat4`/`DMat4` both ways.
//!
//! `Rotor3` is the unit quaternion with i = −e₂₃, j = e₁₃, k = −e₁₂, so the conversion is a
//! copy: glam's `Quat` stores (x, y, z, w) where `Rotor3` stores (w, x, y, z), and the two
//! turn every vector the same way (`Quat::from_axis_angle(a, θ)` is
//! [`Rotor3::from_axis_angle`]`(a, θ)`).
//!
//! A 4D rotation is x ↦ l x r on quaternions (the left and right isoclinic factors; van
//! Elfrinkhof, 1897). With glam's reading of a `Vec4` as the quaternion
//! `Quat::from_vec4(v)` (x, y, z the vector part, w the scalar), `Rotor4` converts to and
//! from the pair (l, r) with `Quat::from_vec4(R v R̃) = l · Quat::from_vec4(v) · r`. The pair
//! is the rotor's own quaternion pair (Q₊, Q₋) with components permuted and signed (the
//! rotor reads x₁ as the scalar of a 4-vector where glam reads x₄), so both directions are
//! exact.

use super::{Real, Rotor3, Rotor4};
use crate::algebra::AlgebraError;
use glam::{DMat3, DMat4, DQuat, DVec3, DVec4, Mat3, Mat4, Quat, Vec3, Vec4};
use nalgebra::{Matrix3, Matrix4, Vector3, Vector4};
use std::ops::Mul;

/// The pair (l, r) of glam quaternions, as (x, y, z, w) arrays, of a rotor's pair (Q₊, Q₋).
fn isoclinic_pair<T: Real>(r: Rotor4<T>) -> ([T; 4], [T; 4]) {
    let ([p0, p1, p2, p3], [m0, m1, m2, m3]) = r.to_quaternion_pair();
    // ξ ↦ a ξ b on the rotor's reading ξ = x₁ + x₂i + x₃j + x₄k (a = (m₀, −m₁, −m₂, m₃),
    // b = Q̄₊), and glam's reading is ζ = u ξ̄ v with u = (1 + j)/√2, v = (i + k)/√2: so
    // l = u b̄ ū = u Q₊ ū and r = v̄ ā v, conjugations that permute and sign components.
    ([p3, p2, -p1, p0], [-m3, -m2, m1, m0])
}

/// The rotor of the glam pair (l, r), given as (x, y, z, w) arrays: the inverse of
/// [`isoclinic_pair`].
fn from_isoclinic_pair<T: Real>(l: [T; 4], r: [T; 4]) -> Rotor4<T> {
    let [lx, ly, lz, lw] = l;
    let [rx, ry, rz, rw] = r;
    Rotor4::from_quaternion_pair([lw, -lz, ly, lx], [rw, rz, -ry, -rx])
}

macro_rules! glam_conversions {
    ($t:ty, $quat:ty, $vec3:ty, $vec4:ty, $mat3:ty, $mat4:ty) => {
        impl From<$quat> for Rotor3<$t> {
            /// The rotor of the quaternion, as given (not normalised).
            #[inline]
            fn from(q: $quat) -> Self {
                Rotor3::from_quaternion(q.w, q.x, q.y, q.z)
            }
        }

        impl From<Rotor3<$t>> for $quat {
            /// The rotor's quaternion.
            #[inline]
            fn from(r: Rotor3<$t>) -> Self {
                let [w, x, y, z] = r.to_quaternion();
                <$quat>::from_xyzw(x, y, z, w)
            }
        }

        impl Mul<$vec3> for Rotor3<$t> {
            type Output = $vec3;
            /// R x R̃, as glam's `Quat * Vec3`.
            #[inline]
            fn mul(self, x: $vec3) -> $vec3 {
                let y = self.rotate_vector(Vector3::new(x.x, x.y, x.z));
                <$vec3>::new(y.x, y.y, y.z)
            }
        }

        impl From<Rotor3<$t>> for $mat3 {
            /// The rotation matrix, [`Rotor3::to_matrix`].
            #[inline]
            fn from(r: Rotor3<$t>) -> Self {
                <$mat3>::from_cols_slice(r.to_matrix().as_slice())
            }
        }

        impl TryFrom<$mat3> for Rotor3<$t> {
            type Error = AlgebraError;
            /// The rotor of a rotation matrix, checked as [`Rotor3::from_matrix`].
            fn try_from(m: $mat3) -> Result<Self, AlgebraError> {
                Rotor3::from_matrix(&Matrix3::from_column_slice(&m.to_cols_array()))
            }
        }

        impl From<Rotor4<$t>> for ($quat, $quat) {
            /// The isoclinic pair (l, r) with `Quat::from_vec4(R v R̃) = l · Quat::from_vec4(v) · r`
            /// (module docs).
            #[inline]
            fn from(r: Rotor4<$t>) -> Self {
                let (l, r) = isoclinic_pair(r);
                (<$quat>::from_array(l), <$quat>::from_array(r))
            }
        }

        impl From<($quat, $quat)> for Rotor4<$t> {
            /// The rotor of an isoclinic pair (l, r), the inverse of the conversion to a pair;
            /// (−l, −r) gives −R, the same rotation.
            #[inline]
            fn from((l, r): ($quat, $quat)) -> Self {
                from_isoclinic_pair(l.to_array(), r.to_array())
            }
        }

        impl Mul<$vec4> for Rotor4<$t> {
            type Output = $vec4;
            /// R x R̃ on (x₁, x₂, x₃, x₄) = (x, y, z, w).
            #[inline]
            fn mul(self, x: $vec4) -> $vec4 {
                let y = self.rotate_vector(Vector4::new(x.x, x.y, x.z, x.w));
                <$vec4>::new(y.x, y.y, y.z, y.w)
            }
        }

        impl From<Rotor4<$t>> for $mat4 {
            /// The rotation matrix, [`Rotor4::to_matrix`].
            #[inline]
            fn from(r: Rotor4<$t>) -> Self {
                <$mat4>::from_cols_slice(r.to_matrix().as_slice())
            }
        }

        impl TryFrom<$mat4> for Rotor4<$t> {
            type Error = AlgebraError;
            /// The rotor of a rotation matrix, checked as [`Rotor4::from_matrix`].
            fn try_from(m: $mat4) -> Result<Self, AlgebraError> {
                Rotor4::from_matrix(&Matrix4::from_column_slice(&m.to_cols_array()))
            }
        }
    };
}

glam_conversions!(f32, Quat, Vec3, Vec4, Mat3, Mat4);
glam_conversions!(f64, DQuat, DVec3, DVec4, DMat3, DMat4);
