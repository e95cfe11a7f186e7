//! [`Bivector3`] and [`Rotor3`]: 3D rotation at the cost of a quaternion.

use super::sealed::Sealed;
use super::{
    Real, norm, plain_norm_range, plane_slot, quat_conj, quat_exp_minus_one, quat_exp_with_norm,
    quat_inverse, quat_log, quat_mul, quat_unit_error,
};
use crate::algebra::{AlgebraError, Bivector, Rotor};
use nalgebra::{Matrix3, Vector3};

/// A bivector of 3D space, b₁₂e₁₂ + b₁₃e₁₃ + b₂₃e₂₃ (the lexicographic order of
/// [`Bivector`]): a plane with a magnitude, an angular velocity or momentum, the generator
/// of a rotation.
///
/// ```
/// use rotorflow::algebra::{Bivector3, Rotor3};
/// let theta = Bivector3::new(std::f64::consts::FRAC_PI_2, 0.0, 0.0); // a quarter turn in e12
/// let r = Rotor3::from_rotation_bivector(theta);
/// let v = r.rotate_vector(nalgebra::Vector3::new(1.0, 0.0, 0.0));
/// assert!((v - nalgebra::Vector3::new(0.0, 1.0, 0.0)).amax() < 1e-15); // e1 turns toward e2
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Bivector3<T = f64> {
    /// The e₁₂ component.
    pub b12: T,
    /// The e₁₃ component.
    pub b13: T,
    /// The e₂₃ component.
    pub b23: T,
}

impl<T: Real> Bivector3<T> {
    /// The bivector b₁₂e₁₂ + b₁₃e₁₃ + b₂₃e₂₃.
    #[inline]
    pub fn new(b12: T, b13: T, b23: T) -> Self {
        Self { b12, b13, b23 }
    }

    /// The zero bivector.
    #[inline]
    pub fn zero() -> Self {
        Self::new(T::zero(), T::zero(), T::zero())
    }

    /// The components in lexicographic order \[b₁₂, b₁₃, b₂₃\].
    #[inline]
    pub fn to_array(self) -> [T; 3] {
        [self.b12, self.b13, self.b23]
    }

    /// The bivector with components \[b₁₂, b₁₃, b₂₃\].
    #[inline]
    pub fn from_array(c: [T; 3]) -> Self {
        Self::new(c[0], c[1], c[2])
    }

    /// |B|² = Σ b_ij².
    #[inline]
    pub fn norm_squared(self) -> T {
        self.b12 * self.b12 + self.b13 * self.b13 + self.b23 * self.b23
    }

    /// |B|, without overflow or underflow.
    #[inline]
    pub fn norm(self) -> T {
        norm(self.to_array())
    }

    /// The commutator product A × B = ½(AB − BA), a bivector (the Lie bracket of so(3)).
    #[inline]
    pub fn commutator(self, other: Self) -> Self {
        // The quaternion map is an algebra isomorphism and ½(ab − ba) = a × b for pure
        // quaternions a, b.
        let (a, b) = (self.quaternion_vector(), other.quaternion_vector());
        let c = [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ];
        Self::from_quaternion_vector(c)
    }

    /// exp(B) = cos |B| + (sin |B| / |B|) B, a unit rotor (it turns by 2|B|; see
    /// [`Rotor3::from_rotation_bivector`] for the rotation by an angle).
    #[inline]
    pub fn exp(self) -> Rotor3<T> {
        Rotor3::from_q(quat_exp_with_norm(self.quaternion_vector(), self.norm()))
    }

    /// The vector part of the pure quaternion with the same geometric product.
    #[inline(always)]
    fn quaternion_vector(self) -> [T; 3] {
        [-self.b23, self.b13, -self.b12]
    }

    #[inline(always)]
    fn from_quaternion_vector(v: [T; 3]) -> Self {
        Self::new(-v[2], v[1], -v[0])
    }

    /// The run-time [`Bivector`] (N = 3).
    pub fn to_bivector(self) -> Bivector {
        let c = self.to_array().map(Real::to_f64);
        Bivector::from_components(3, &c).expect("three components of a 3D bivector")
    }
}

impl Bivector3<f64> {
    /// The fixed-size form of a run-time bivector.
    ///
    /// # Errors
    /// [`AlgebraError::DimensionMismatch`] unless N = 3.
    pub fn from_bivector(b: &Bivector) -> Result<Self, AlgebraError> {
        match b.as_slice() {
            &[b12, b13, b23] => Ok(Self::new(b12, b13, b23)),
            _ => Err(AlgebraError::DimensionMismatch {
                left: 3,
                right: b.dim(),
            }),
        }
    }

    /// exp(B) − 1 in the run-time rotor's storage order ([`Rotor3::to_even_layout`]): the
    /// increment of [`Self::exp`], without a square root or libm call below the angle π/4
    /// and with its scalar part cos θ − 1 accurate relative to itself, for step kernels
    /// (an increment R ← R (1 + D) then keeps |R| as well as the plane rotations do).
    #[inline(always)]
    pub(crate) fn exp_minus_one_even_layout(self) -> [f64; 4] {
        Rotor3::from_q(quat_exp_minus_one(self.quaternion_vector())).to_even_layout()
    }
}

/// A rotor of 3D space, s + b₁₂e₁₂ + b₁₃e₁₃ + b₂₃e₂₃ with R R̃ = 1, acting by x ↦ R x R̃;
/// R = exp(−θB̂/2) turns by θ in the plane B̂ from its first vector toward its second (the
/// conventions of [`Rotor`]).
///
/// Stored as the unit quaternion (w, x, y, z) = (s, −b₂₃, b₁₃, −b₁₂), whose Hamilton
/// product is the geometric product: glam's `DQuat`/`Quat` and this type agree
/// operation for operation, with the rotation by θ in e₁₂ the quaternion of the axis e₃.
///
/// ```
/// use rotorflow::algebra::{Bivector3, Rotor3};
/// let a = Rotor3::from_rotation_bivector(Bivector3::new(0.3, -0.2, 0.5));
/// let b = Rotor3::from_rotation_bivector(Bivector3::new(-0.1, 0.4, 0.2));
/// let m = (a * b).to_matrix();
/// assert!((m - a.to_matrix() * b.to_matrix()).amax() < 1e-15);
/// ```
///
/// `#[repr(transparent)]`: laid out as the quaternion storage of `T`, for `f64` the array
/// (w, x, y, z), so that a slice of rotors is 4 numbers per rotor to SIMD kernels.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(transparent)]
pub struct Rotor3<T: Real = f64> {
    /// The quaternion (w, x, y, z), stored as the scalar type keeps quaternions (four SSE
    /// lanes for f32 on x86, an array otherwise).
    lanes: <T as Sealed>::Quat,
}

/// −R: the same rotation as R, on the other sheet of the double cover.
impl<T: Real> std::ops::Neg for Rotor3<T> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self::from_q(self.q().map(|c| -c))
    }
}

impl<T: Real> Rotor3<T> {
    /// The rotor of the quaternion (w, x, y, z).
    #[inline(always)]
    fn from_q(q: [T; 4]) -> Self {
        Self {
            lanes: T::quat_lanes(q),
        }
    }

    /// Its quaternion (w, x, y, z).
    #[inline(always)]
    fn q(self) -> [T; 4] {
        T::quat_array(self.lanes)
    }

    /// The identity rotor 1.
    #[inline]
    pub fn identity() -> Self {
        Self::from_q([T::one(), T::zero(), T::zero(), T::zero()])
    }

    /// The rotation by `angle` (radians) about `axis`, right-handed: glam's
    /// `Quat::from_axis_angle` and nalgebra's `UnitQuaternion::from_axis_angle`, whose
    /// quaternion it is, (cos ½θ, sin ½θ â). About e₃ it turns e₁ toward e₂, about e₁ it
    /// turns e₂ toward e₃, about e₂ it turns e₃ toward e₁. The axis need not be a unit
    /// vector; it is normalised here.
    ///
    /// ```
    /// use rotorflow::algebra::{Rotor3, Vector3};
    /// // nalgebra itself, re-exported: no second nalgebra dependency to keep in step.
    /// use rotorflow::nalgebra::{Unit, UnitQuaternion};
    /// let r = Rotor3::from_axis_angle(Vector3::new(0.0, 0.0, 2.0), std::f64::consts::FRAC_PI_2)?;
    /// assert!((r * Vector3::x() - Vector3::y()).amax() < 1e-15);
    /// let axis = Unit::new_normalize(Vector3::new(1.0, -2.0, 0.5));
    /// let q = UnitQuaternion::from_axis_angle(&axis, 0.7);
    /// let v = Vector3::new(0.3, 0.1, -0.4);
    /// let r = Rotor3::from_axis_angle(axis.into_inner(), 0.7)?;
    /// assert!((r * v - q * v).amax() < 1e-15);
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    ///
    /// # Errors
    /// [`AlgebraError::NonFinite`] for a NaN or infinite axis or angle;
    /// [`AlgebraError::ZeroLength`] for a zero axis.
    #[inline]
    pub fn from_axis_angle(axis: Vector3<T>, angle: T) -> Result<Self, AlgebraError> {
        let a = [axis.x, axis.y, axis.z];
        // One test covers the common input: |a|² well inside the range (so every component is
        // finite and non-zero as a whole, and |a| is the plain root, as `norm` takes it) and a
        // finite angle. The checks that name the problem, and the scaled norm, stand apart.
        let squares = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
        let len = if plain_norm_range(squares) && angle.is_finite() {
            squares.sqrt()
        } else {
            checked_axis_length(a, angle)?
        };
        let (s, c) = (angle * T::lit(0.5)).sin_cos();
        let k = s / len;
        Ok(Self::from_q([c, k * a[0], k * a[1], k * a[2]]))
    }

    /// The rotation by `angle` about e₁ (x), turning e₂ toward e₃ (glam's
    /// `Quat::from_rotation_x`).
    #[inline]
    pub fn from_rotation_x(angle: T) -> Self {
        let (s, c) = (angle * T::lit(0.5)).sin_cos();
        Self::from_q([c, s, T::zero(), T::zero()])
    }

    /// The rotation by `angle` about e₂ (y), turning e₃ toward e₁ (glam's
    /// `Quat::from_rotation_y`).
    #[inline]
    pub fn from_rotation_y(angle: T) -> Self {
        let (s, c) = (angle * T::lit(0.5)).sin_cos();
        Self::from_q([c, T::zero(), s, T::zero()])
    }

    /// The rotation by `angle` about e₃ (z), turning e₁ toward e₂ (glam's
    /// `Quat::from_rotation_z`).
    #[inline]
    pub fn from_rotation_z(angle: T) -> Self {
        let (s, c) = (angle * T::lit(0.5)).sin_cos();
        Self::from_q([c, T::zero(), T::zero(), s])
    }

    /// The rotation by `angle` in the plane eᵢ∧eⱼ (0-based indices), turning eᵢ toward eⱼ:
    /// cos ½θ − sin ½θ eᵢⱼ, as [`Rotor::from_plane_angle`]. Swapping i and j reverses the
    /// sense, so `from_plane_angle(2, 0, θ)` is [`Rotor3::from_rotation_y`]`(θ)`.
    ///
    /// # Errors
    /// [`AlgebraError::IndexOutOfRange`] for an index above 2;
    /// [`AlgebraError::RepeatedIndex`] for i = j.
    pub fn from_plane_angle(i: usize, j: usize, angle: T) -> Result<Self, AlgebraError> {
        let (slot, sign) = plane_slot(3, i, j)?;
        let mut b = [T::zero(); 3];
        b[slot] = angle * T::lit(sign);
        Ok(Self::from_rotation_bivector(Bivector3::from_array(b)))
    }

    /// The inverse R⁻¹ = R̃ / (R R̃), for any non-zero R (the reverse for a unit rotor, up to
    /// round-off; glam's `inverse` is the conjugate alone).
    #[inline]
    pub fn inverse(self) -> Self {
        Self::from_q(quat_inverse(self.q()))
    }

    /// The rotor s + B from its scalar and bivector parts, as given (not normalised).
    #[inline]
    pub fn from_parts(s: T, b: Bivector3<T>) -> Self {
        Self::from_q([s, -b.b23, b.b13, -b.b12])
    }

    /// The rotor of the unit quaternion (w, x, y, z) (w + xi + yj + zk with i = −e₂₃,
    /// j = e₁₃, k = −e₁₂), as given.
    #[inline]
    pub fn from_quaternion(w: T, x: T, y: T, z: T) -> Self {
        Self::from_q([w, x, y, z])
    }

    /// The quaternion (w, x, y, z) of this rotor.
    #[inline]
    pub fn to_quaternion(self) -> [T; 4] {
        self.q()
    }

    /// The scalar part s.
    #[inline]
    pub fn scalar(self) -> T {
        self.q()[0]
    }

    /// The bivector part.
    #[inline]
    pub fn bivector_part(self) -> Bivector3<T> {
        Bivector3::new(-self.q()[3], self.q()[2], -self.q()[1])
    }

    /// The principal logarithm (half-angle in \[0, π\]), as [`Rotor::log`]: R = −1 gives π e₁₂.
    #[inline]
    pub fn log(self) -> Bivector3<T> {
        Bivector3::from_quaternion_vector(quat_log(self.q()))
    }

    /// The reverse R̃ (the inverse of a unit rotor).
    #[inline]
    pub fn reverse(self) -> Self {
        Self::from_q(quat_conj(self.q()))
    }

    /// The geometric product self · other: the rotation `other` first, then `self`.
    #[inline]
    pub fn compose(self, other: Self) -> Self {
        Self {
            lanes: T::quat_product(self.lanes, other.lanes),
        }
    }

    /// R x R̃.
    #[inline]
    pub fn rotate_vector(self, x: Vector3<T>) -> Vector3<T> {
        // v + 2w (u × v) + 2 u × (u × v) with u the quaternion's vector part.
        let [w, ux, uy, uz] = self.q();
        let two = T::lit(2.0);
        let tx = two * (uy * x.z - uz * x.y);
        let ty = two * (uz * x.x - ux * x.z);
        let tz = two * (ux * x.y - uy * x.x);
        Vector3::new(
            x.x + w * tx + (uy * tz - uz * ty),
            x.y + w * ty + (uz * tx - ux * tz),
            x.z + w * tz + (ux * ty - uy * tx),
        )
    }

    /// R B R̃: the bivector turned with the space (an angular velocity or a plane seen in
    /// the turned frame), as [`Rotor::rotate_bivector`].
    #[inline]
    pub fn rotate_bivector(self, b: Bivector3<T>) -> Bivector3<T> {
        // Under the quaternion map B is the pure quaternion u and R B R̃ is q u q̄, the
        // formula of `rotate_vector` on u's components.
        let u = b.quaternion_vector();
        let v = self.rotate_vector(Vector3::new(u[0], u[1], u[2]));
        Bivector3::from_quaternion_vector([v.x, v.y, v.z])
    }

    /// The rotation matrix Q (Q x = R x R̃), as [`Rotor::to_matrix`].
    #[inline]
    pub fn to_matrix(self) -> Matrix3<T> {
        let [w, x, y, z] = self.q();
        let two = T::lit(2.0);
        Matrix3::new(
            w * w + x * x - y * y - z * z,
            two * (x * y - w * z),
            two * (x * z + w * y),
            two * (x * y + w * z),
            w * w - x * x + y * y - z * z,
            two * (y * z - w * x),
            two * (x * z - w * y),
            two * (y * z + w * x),
            w * w - x * x - y * y + z * z,
        )
    }

    /// The rotor (scalar part ≥ 0) of a rotation matrix, by Shepperd's method as
    /// [`Rotor::from_matrix`], which also checks the matrix.
    ///
    /// # Errors
    /// [`AlgebraError::NonFinite`] for NaN or infinite entries; [`AlgebraError::NotARotation`]
    /// if max |QᵀQ − 1| exceeds [`crate::algebra::ROTATION_TOLERANCE`] or det Q < 0.
    pub fn from_matrix(m: &Matrix3<T>) -> Result<Self, AlgebraError> {
        super::check_rotation(m.iter().copied(), || {
            (
                (m.transpose() * m - Matrix3::identity()).amax(),
                m.determinant(),
            )
        })?;
        Ok(Self::from_matrix_unchecked(m))
    }

    /// Shepperd's method without the checks: the largest of w², x², y², z² from the trace and
    /// diagonal, so no square root of a small number is taken.
    pub fn from_matrix_unchecked(q: &Matrix3<T>) -> Self {
        let (one, two, quarter) = (T::one(), T::lit(2.0), T::lit(0.25));
        let (m00, m11, m22) = (q[(0, 0)], q[(1, 1)], q[(2, 2)]);
        let tr = m00 + m11 + m22;
        let root = |x: T| two * x.max(T::zero()).sqrt();
        let (w, x, y, z);
        if tr >= m00 && tr >= m11 && tr >= m22 {
            let s = root(one + tr);
            w = quarter * s;
            x = (q[(2, 1)] - q[(1, 2)]) / s;
            y = (q[(0, 2)] - q[(2, 0)]) / s;
            z = (q[(1, 0)] - q[(0, 1)]) / s;
        } else if m00 >= m11 && m00 >= m22 {
            let s = root(one + m00 - m11 - m22);
            w = (q[(2, 1)] - q[(1, 2)]) / s;
            x = quarter * s;
            y = (q[(0, 1)] + q[(1, 0)]) / s;
            z = (q[(0, 2)] + q[(2, 0)]) / s;
        } else if m11 >= m22 {
            let s = root(one + m11 - m00 - m22);
            w = (q[(0, 2)] - q[(2, 0)]) / s;
            x = (q[(0, 1)] + q[(1, 0)]) / s;
            y = quarter * s;
            z = (q[(1, 2)] + q[(2, 1)]) / s;
        } else {
            let s = root(one + m22 - m00 - m11);
            w = (q[(1, 0)] - q[(0, 1)]) / s;
            x = (q[(0, 2)] + q[(2, 0)]) / s;
            y = (q[(1, 2)] + q[(2, 1)]) / s;
            z = quarter * s;
        }
        let sign = if w < T::zero() { -one } else { one };
        let k = sign / (w * w + x * x + y * y + z * z).sqrt();
        Self::from_q([k * w, k * x, k * y, k * z])
    }

    /// R / |R|: back onto the group after drift.
    #[inline]
    pub fn normalize(self) -> Self {
        let k = T::one() / norm(self.q());
        Self::from_q(self.q().map(|c| c * k))
    }

    /// max |R R̃ − 1|, as [`Rotor::unit_error`].
    #[inline]
    pub fn unit_error(self) -> T {
        quat_unit_error(self.q())
    }

    /// The even element in the run-time rotor's storage order (s, e₁₃, e₂₃, e₁₂), any
    /// values (not only unit rotors).
    #[inline(always)]
    pub(crate) fn from_even_layout(c: &[f64; 4]) -> Self
    where
        T: From<f64>,
    {
        Self::from_parts(
            T::from(c[0]),
            Bivector3::new(T::from(c[3]), T::from(c[1]), T::from(c[2])),
        )
    }

    /// The even element in the run-time rotor's storage order, the inverse of
    /// [`Rotor3::from_even_layout`].
    #[inline(always)]
    pub(crate) fn to_even_layout(self) -> [f64; 4] {
        let [w, x, y, z] = self.q().map(Real::to_f64);
        [w, y, -x, -z]
    }

    /// self + self · d, the update R ← R (1 + D) of an increment D.
    #[inline]
    pub(crate) fn plus_product(self, d: Self) -> Self {
        let p = quat_mul(self.q(), d.q());
        Self::from_q(std::array::from_fn(|i| self.q()[i] + p[i]))
    }

    /// The run-time [`Rotor`] (N = 3).
    pub fn to_rotor(self) -> Rotor {
        let b = self.bivector_part();
        let mut m = crate::algebra::Multivector::zero(crate::algebra::Signature::euclidean(3));
        let c = m.as_mut_slice();
        c[0] = self.scalar().to_f64();
        c[0b011] = b.b12.to_f64();
        c[0b101] = b.b13.to_f64();
        c[0b110] = b.b23.to_f64();
        Rotor::from_multivector_unchecked(&m)
    }
}

impl Rotor3<f64> {
    /// R x R̃ for an even element R in the run-time layout, unit or not: with q = (w, u),
    /// (w² − u·u) x + 2(u·x) u + 2w u × x, which is the sandwich for every quaternion (the
    /// unit-only form v + 2w u × v + 2u × (u × v) is not).
    #[inline(always)]
    pub(crate) fn sandwich_even_layout(c: &[f64; 4], x: &[f64; 3]) -> [f64; 3] {
        let (w, u) = (c[0], [-c[2], c[1], -c[3]]);
        let d = w * w - (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        let ux = 2.0 * (u[0] * x[0] + u[1] * x[1] + u[2] * x[2]);
        let w2 = 2.0 * w;
        let cross = [
            u[1] * x[2] - u[2] * x[1],
            u[2] * x[0] - u[0] * x[2],
            u[0] * x[1] - u[1] * x[0],
        ];
        std::array::from_fn(|i| d * x[i] + ux * u[i] + w2 * cross[i])
    }

    /// The fixed-size form of a run-time rotor.
    ///
    /// # Errors
    /// [`AlgebraError::DimensionMismatch`] unless N = 3.
    pub fn from_rotor(r: &Rotor) -> Result<Self, AlgebraError> {
        if r.dim() != 3 {
            return Err(AlgebraError::DimensionMismatch {
                left: 3,
                right: r.dim(),
            });
        }
        Ok(Self::from_parts(
            r.scalar(),
            Bivector3::new(
                r.coefficient(0b011),
                r.coefficient(0b101),
                r.coefficient(0b110),
            ),
        ))
    }
}

fixed_size_operators!(Bivector3, Rotor3, Vector3);

/// |a| for [`Rotor3::from_axis_angle`] outside its common case: the errors for a non-finite
/// axis or angle and a zero axis, in that order, and the scaled norm of a tiny or huge axis.
#[cold]
#[inline(never)]
fn checked_axis_length<T: Real>(a: [T; 3], angle: T) -> Result<T, AlgebraError> {
    if !a.iter().all(|c| c.is_finite()) {
        return Err(AlgebraError::NonFinite {
            what: "rotation axis",
        });
    }
    if !angle.is_finite() {
        return Err(AlgebraError::NonFinite {
            what: "rotation angle",
        });
    }
    let len = norm(a);
    if len == T::zero() {
        return Err(AlgebraError::ZeroLength {
            what: "rotation axis",
        });
    }
    Ok(len)
}
