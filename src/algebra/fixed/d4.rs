//! [`Bivector4`] and [`Rotor4`]: 4D rotation as a pair of quaternions.
//!
//! With I = e₁₂₃₄ (I² = +1, central in the even algebra) and P± = ½(1 ± I), a 4D rotor
//! R = s + Σ b_ij e_ij + p I is Q₊P₊ + Q₋P₋ with
//!
//!   Q₊ = (s + p) + (b₁₂ − b₃₄) i + (b₁₃ + b₂₄) j + (b₁₄ − b₂₃) k,
//!   Q₋ = (s − p) + (b₁₂ + b₃₄) i + (b₁₃ − b₂₄) j − (b₁₄ + b₂₃) k,
//!
//! where on P₊ the units i, j, k are e₁₂, e₁₃, e₁₄ and on P₋ they are e₁₂, e₁₃, −e₁₄: both
//! halves are quaternion algebras (I e₁₂ = −e₃₄, I e₁₃ = e₂₄, I e₁₄ = −e₂₃), and R R̃ = 1 makes
//! Q₊ and Q₋ unit quaternions. A vector x, read as the quaternion ξ = x₁ + x₂i + x₃j + x₄k,
//! turns as ξ ↦ Q̄₋′ ξ Q̄₊ with Q₋′ the quaternion Q₋ with its k component negated (the
//! left and right isoclinic factors of SO(4)).

use super::{
    Real, norm, plane_slot, quat_conj, quat_exp, quat_exp_minus_one, quat_inverse, quat_log,
    quat_mul,
};
use crate::algebra::{AlgebraError, Bivector, Rotor};
use nalgebra::{Matrix4, Vector4};

/// A bivector of 4D space, Σ b_ij e_ij in the lexicographic order of [`Bivector`]:
/// b₁₂, b₁₃, b₁₄, b₂₃, b₂₄, b₃₄.
///
/// ```
/// use rotorflow::algebra::{Bivector4, Rotor4};
/// // An isoclinic rotation: a quarter turn in e12 and in e34 at once.
/// let half_pi = std::f64::consts::FRAC_PI_2;
/// let r = Rotor4::from_rotation_bivector(Bivector4::new(half_pi, 0.0, 0.0, 0.0, 0.0, half_pi));
/// let v = r.rotate_vector(nalgebra::Vector4::new(1.0, 0.0, 1.0, 0.0));
/// assert!((v - nalgebra::Vector4::new(0.0, 1.0, 0.0, 1.0)).amax() < 1e-15);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Bivector4<T = f64> {
    /// The e₁₂ component.
    pub b12: T,
    /// The e₁₃ component.
    pub b13: T,
    /// The e₁₄ component.
    pub b14: T,
    /// The e₂₃ component.
    pub b23: T,
    /// The e₂₄ component.
    pub b24: T,
    /// The e₃₄ component.
    pub b34: T,
}

impl<T: Real> Bivector4<T> {
    /// The bivector with components b₁₂, b₁₃, b₁₄, b₂₃, b₂₄, b₃₄.
    #[inline]
    pub fn new(b12: T, b13: T, b14: T, b23: T, b24: T, b34: T) -> Self {
        Self {
            b12,
            b13,
            b14,
            b23,
            b24,
            b34,
        }
    }

    /// The zero bivector.
    #[inline]
    pub fn zero() -> Self {
        Self::from_array([T::zero(); 6])
    }

    /// The components in lexicographic order.
    #[inline]
    pub fn to_array(self) -> [T; 6] {
        [self.b12, self.b13, self.b14, self.b23, self.b24, self.b34]
    }

    /// The bivector of the components in lexicographic order.
    #[inline]
    pub fn from_array(c: [T; 6]) -> Self {
        Self::new(c[0], c[1], c[2], c[3], c[4], c[5])
    }

    /// |B|² = Σ b_ij².
    #[inline]
    pub fn norm_squared(self) -> T {
        self.to_array().iter().fold(T::zero(), |a, &c| a + c * c)
    }

    /// |B|, without overflow or underflow.
    #[inline]
    pub fn norm(self) -> T {
        norm(self.to_array())
    }

    /// The self-dual and anti-self-dual halves (α, β): the pure quaternions of B P₊ and B P₋.
    #[inline(always)]
    fn halves(self) -> ([T; 3], [T; 3]) {
        (
            [
                self.b12 - self.b34,
                self.b13 + self.b24,
                self.b14 - self.b23,
            ],
            [
                self.b12 + self.b34,
                self.b13 - self.b24,
                -(self.b14 + self.b23),
            ],
        )
    }

    /// The bivector of the halves (α, β).
    #[inline(always)]
    fn from_halves(a: [T; 3], b: [T; 3]) -> Self {
        let h = T::lit(0.5);
        Self::new(
            h * (a[0] + b[0]),
            h * (a[1] + b[1]),
            h * (a[2] - b[2]),
            -h * (a[2] + b[2]),
            h * (a[1] - b[1]),
            h * (b[0] - a[0]),
        )
    }

    /// The commutator product A × B = ½(AB − BA) (the Lie bracket of so(4) = so(3) ⊕ so(3)).
    #[inline]
    pub fn commutator(self, other: Self) -> Self {
        let cross = |a: [T; 3], b: [T; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let ((a1, b1), (a2, b2)) = (self.halves(), other.halves());
        Self::from_halves(cross(a1, a2), cross(b1, b2))
    }

    /// exp(B), a unit rotor: the quaternion exponential of each half, exact for isoclinic B.
    #[inline]
    pub fn exp(self) -> Rotor4<T> {
        let (a, b) = self.halves();
        Rotor4 {
            plus: quat_exp(a),
            minus: quat_exp(b),
        }
    }

    /// The run-time [`Bivector`] (N = 4).
    pub fn to_bivector(self) -> Bivector {
        let c = self.to_array().map(Real::to_f64);
        Bivector::from_components(4, &c).expect("six components of a 4D bivector")
    }
}

impl Bivector4<f64> {
    /// The fixed-size form of a run-time bivector.
    ///
    /// # Errors
    /// [`AlgebraError::DimensionMismatch`] unless N = 4.
    pub fn from_bivector(b: &Bivector) -> Result<Self, AlgebraError> {
        let c: [f64; 6] = b
            .as_slice()
            .try_into()
            .map_err(|_| AlgebraError::DimensionMismatch {
                left: 4,
                right: b.dim(),
            })?;
        Ok(Self::from_array(c))
    }

    /// exp(B) − 1 in the run-time rotor's storage order ([`Rotor4::to_even_layout`]): the
    /// increment of [`Self::exp`], without a square root or libm call below the angle π/4
    /// in each half and with the parts near 1 formed as cos θ − 1, for step kernels. The
    /// storage order is linear in the quaternion pair, and 1 is the pair (1, 1), so the
    /// pair minus (1, 1) gives it.
    #[inline(always)]
    pub(crate) fn exp_minus_one_even_layout(self) -> [f64; 8] {
        let (a, b) = self.halves();
        Rotor4 {
            plus: quat_exp_minus_one(a),
            minus: quat_exp_minus_one(b),
        }
        .to_even_layout()
    }
}

/// A rotor of 4D space, s + Σ b_ij e_ij + p e₁₂₃₄ with R R̃ = 1, acting by x ↦ R x R̃, with the
/// conventions of [`Rotor`]; stored as its pair of unit quaternions (module docs).
///
/// ```
/// use rotorflow::algebra::{Bivector4, Rotor4};
/// let a = Rotor4::from_rotation_bivector(Bivector4::new(0.3, -0.2, 0.5, 0.1, 0.4, -0.6));
/// let b = Rotor4::from_rotation_bivector(Bivector4::new(-0.1, 0.4, 0.2, 0.7, -0.3, 0.2));
/// let m = (a * b).to_matrix();
/// assert!((m - a.to_matrix() * b.to_matrix()).amax() < 1e-15);
/// assert!((a.rotation_bivector() - Bivector4::new(0.3, -0.2, 0.5, 0.1, 0.4, -0.6)).norm() < 1e-15);
/// ```
///
/// Laid out as Q₊ then Q₋, four `T` each (`#[repr(C)]`), so that a slice of rotors is an
/// array of 8 `T` per rotor to SIMD kernels.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct Rotor4<T = f64> {
    plus: [T; 4],
    minus: [T; 4],
}

/// −R: the same rotation as R, on the other sheet of the double cover.
impl<T: Real> std::ops::Neg for Rotor4<T> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self {
            plus: self.plus.map(|c| -c),
            minus: self.minus.map(|c| -c),
        }
    }
}

impl<T: Real> Rotor4<T> {
    /// The identity rotor 1.
    #[inline]
    pub fn identity() -> Self {
        let one = [T::one(), T::zero(), T::zero(), T::zero()];
        Self {
            plus: one,
            minus: one,
        }
    }

    /// The rotation by `angle` (radians) in the plane eᵢ∧eⱼ (0-based indices; x, y, z, w
    /// are 0, 1, 2, 3), turning eᵢ toward eⱼ: cos ½θ − sin ½θ eᵢⱼ, as
    /// [`Rotor::from_plane_angle`]. Swapping i and j reverses the sense. The named forms
    /// [`Rotor4::from_rotation_xy`] … [`Rotor4::from_rotation_zw`] are the six planes with
    /// i < j.
    ///
    /// ```
    /// use rotorflow::algebra::{Rotor4, Vector4};
    /// let r = Rotor4::from_plane_angle(3, 1, std::f64::consts::FRAC_PI_2)?; // w toward y
    /// assert!((r * Vector4::w() - Vector4::y()).amax() < 1e-15);
    /// assert_eq!(r, Rotor4::from_rotation_yw(-std::f64::consts::FRAC_PI_2));
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    ///
    /// # Errors
    /// [`AlgebraError::IndexOutOfRange`] for an index above 3;
    /// [`AlgebraError::RepeatedIndex`] for i = j.
    pub fn from_plane_angle(i: usize, j: usize, angle: T) -> Result<Self, AlgebraError> {
        let (slot, sign) = plane_slot(4, i, j)?;
        let mut b = [T::zero(); 6];
        b[slot] = angle * T::lit(sign);
        Ok(Self::from_rotation_bivector(Bivector4::from_array(b)))
    }

    /// [`Rotor4::from_plane_angle`] for indices known to be valid.
    #[inline(always)]
    fn plane_rotation(i: usize, j: usize, angle: T) -> Self {
        let mut b = [T::zero(); 6];
        b[crate::algebra::pair_index(4, i, j)] = angle;
        Self::from_rotation_bivector(Bivector4::from_array(b))
    }

    /// The rotation by `angle` in the plane e₁∧e₂ (xy), turning e₁ (x) toward e₂ (y):
    /// [`Rotor4::from_plane_angle`]`(0, 1, angle)`.
    #[inline]
    pub fn from_rotation_xy(angle: T) -> Self {
        Self::plane_rotation(0, 1, angle)
    }

    /// The rotation by `angle` in the plane e₁∧e₃ (xz), turning e₁ (x) toward e₃ (z):
    /// [`Rotor4::from_plane_angle`]`(0, 2, angle)`.
    #[inline]
    pub fn from_rotation_xz(angle: T) -> Self {
        Self::plane_rotation(0, 2, angle)
    }

    /// The rotation by `angle` in the plane e₁∧e₄ (xw), turning e₁ (x) toward e₄ (w):
    /// [`Rotor4::from_plane_angle`]`(0, 3, angle)`.
    #[inline]
    pub fn from_rotation_xw(angle: T) -> Self {
        Self::plane_rotation(0, 3, angle)
    }

    /// The rotation by `angle` in the plane e₂∧e₃ (yz), turning e₂ (y) toward e₃ (z):
    /// [`Rotor4::from_plane_angle`]`(1, 2, angle)`.
    #[inline]
    pub fn from_rotation_yz(angle: T) -> Self {
        Self::plane_rotation(1, 2, angle)
    }

    /// The rotation by `angle` in the plane e₂∧e₄ (yw), turning e₂ (y) toward e₄ (w):
    /// [`Rotor4::from_plane_angle`]`(1, 3, angle)`.
    #[inline]
    pub fn from_rotation_yw(angle: T) -> Self {
        Self::plane_rotation(1, 3, angle)
    }

    /// The rotation by `angle` in the plane e₃∧e₄ (zw), turning e₃ (z) toward e₄ (w):
    /// [`Rotor4::from_plane_angle`]`(2, 3, angle)`.
    #[inline]
    pub fn from_rotation_zw(angle: T) -> Self {
        Self::plane_rotation(2, 3, angle)
    }

    /// The inverse R⁻¹ = R̃ / (R R̃) of a rotor with R R̃ a non-zero scalar (each quaternion
    /// half inverted; the reverse for a unit rotor, up to round-off).
    #[inline]
    pub fn inverse(self) -> Self {
        Self {
            plus: quat_inverse(self.plus),
            minus: quat_inverse(self.minus),
        }
    }

    /// The rotor s + B + p e₁₂₃₄ from its grades, as given (not normalised).
    #[inline]
    pub fn from_parts(s: T, b: Bivector4<T>, p: T) -> Self {
        let (a, m) = b.halves();
        Self {
            plus: [s + p, a[0], a[1], a[2]],
            minus: [s - p, m[0], m[1], m[2]],
        }
    }

    /// The rotor of the quaternion pair (Q₊, Q₋), each (w, x, y, z) (module docs).
    #[inline]
    pub fn from_quaternion_pair(plus: [T; 4], minus: [T; 4]) -> Self {
        Self { plus, minus }
    }

    /// The quaternion pair (Q₊, Q₋).
    #[inline]
    pub fn to_quaternion_pair(self) -> ([T; 4], [T; 4]) {
        (self.plus, self.minus)
    }

    /// The scalar part s.
    #[inline]
    pub fn scalar(self) -> T {
        T::lit(0.5) * (self.plus[0] + self.minus[0])
    }

    /// The e₁₂₃₄ coefficient p.
    #[inline]
    pub fn pseudoscalar(self) -> T {
        T::lit(0.5) * (self.plus[0] - self.minus[0])
    }

    /// The bivector part.
    #[inline]
    pub fn bivector_part(self) -> Bivector4<T> {
        let (p, m) = (self.plus, self.minus);
        Bivector4::from_halves([p[1], p[2], p[3]], [m[1], m[2], m[3]])
    }

    /// The principal logarithm, as [`Rotor::log`] in 4D: the principal quaternion
    /// logarithm of each half (each half-angle in \[0, π\]).
    #[inline]
    pub fn log(self) -> Bivector4<T> {
        Bivector4::from_halves(quat_log(self.plus), quat_log(self.minus))
    }

    /// The reverse R̃ (the inverse of a unit rotor).
    #[inline]
    pub fn reverse(self) -> Self {
        Self {
            plus: quat_conj(self.plus),
            minus: quat_conj(self.minus),
        }
    }

    /// R̃ B R for a bivector B: each half, a pure quaternion, turns as Q̄ α Q, written for a
    /// unit Q = (w, v) as α + w t − v × t with t = 2 α × v (two cross products instead of two
    /// quaternion products).
    #[inline]
    pub(crate) fn reverse_sandwich(self, b: Bivector4<T>) -> Bivector4<T> {
        let (a, m) = b.halves();
        let cross = |x: [T; 3], y: [T; 3]| {
            [
                x[1] * y[2] - x[2] * y[1],
                x[2] * y[0] - x[0] * y[2],
                x[0] * y[1] - x[1] * y[0],
            ]
        };
        let turn = |q: [T; 4], x: [T; 3]| {
            let (w, v) = (q[0], [q[1], q[2], q[3]]);
            let t = cross(x, v).map(|c| c + c);
            let vt = cross(v, t);
            [
                x[0] + w * t[0] - vt[0],
                x[1] + w * t[1] - vt[1],
                x[2] + w * t[2] - vt[2],
            ]
        };
        Bivector4::from_halves(turn(self.plus, a), turn(self.minus, m))
    }

    /// R B R̃: the bivector turned with the space, as [`Rotor::rotate_bivector`].
    #[inline]
    pub fn rotate_bivector(self, b: Bivector4<T>) -> Bivector4<T> {
        self.reverse().reverse_sandwich(b)
    }

    /// The geometric product self · other (two quaternion products).
    #[inline]
    pub fn compose(self, other: Self) -> Self {
        Self {
            plus: quat_mul(self.plus, other.plus),
            minus: quat_mul(self.minus, other.minus),
        }
    }

    /// The factors (a, b) of the vector map ξ ↦ a ξ b.
    #[inline(always)]
    fn isoclinic_factors(self) -> ([T; 4], [T; 4]) {
        let m = self.minus;
        ([m[0], -m[1], -m[2], m[3]], quat_conj(self.plus))
    }

    /// R x R̃, as two quaternion products.
    #[inline]
    pub fn rotate_vector(self, x: Vector4<T>) -> Vector4<T> {
        let (a, b) = self.isoclinic_factors();
        let y = quat_mul(quat_mul(a, [x.x, x.y, x.z, x.w]), b);
        Vector4::new(y[0], y[1], y[2], y[3])
    }

    /// The rotation matrix Q (Q x = R x R̃), as [`Rotor::to_matrix`]: the product of the
    /// left-isoclinic and right-isoclinic matrices, on the stack.
    #[inline]
    pub fn to_matrix(self) -> Matrix4<T> {
        let ([a0, a1, a2, a3], [b0, b1, b2, b3]) = self.isoclinic_factors();
        // L(a): ξ ↦ a ξ; R(b): ξ ↦ ξ b; Q = L(a) R(b).
        let l = [
            [a0, -a1, -a2, -a3],
            [a1, a0, -a3, a2],
            [a2, a3, a0, -a1],
            [a3, -a2, a1, a0],
        ];
        let r = [
            [b0, -b1, -b2, -b3],
            [b1, b0, b3, -b2],
            [b2, -b3, b0, b1],
            [b3, b2, -b1, b0],
        ];
        // Written out on arrays (each entry a sum of four products, paired): nalgebra's
        // generic product of two Matrix4 values ran about three times slower here.
        let q = |i: usize, j: usize| {
            (l[i][0] * r[0][j] + l[i][1] * r[1][j]) + (l[i][2] * r[2][j] + l[i][3] * r[3][j])
        };
        Matrix4::from_fn(q)
    }

    /// The rotor (scalar part ≥ 0) of a 4D rotation matrix, checked as [`Rotor::from_matrix`].
    ///
    /// For Q = L(a) R(b) the associate matrix A = ¼ Σ Q_rc (e_i e_c e_j)_r equals a bᵀ (the
    /// sixteen L(e_i) R(e_j) are orthogonal with squared norm 4); a and b are read from its
    /// largest row and column, so no small number is divided by.
    ///
    /// # Errors
    /// [`AlgebraError::NonFinite`] for NaN or infinite entries; [`AlgebraError::NotARotation`]
    /// if max |QᵀQ − 1| exceeds [`crate::algebra::ROTATION_TOLERANCE`] or det Q < 0.
    pub fn from_matrix(q: &Matrix4<T>) -> Result<Self, AlgebraError> {
        super::check_rotation(q.iter().copied(), || {
            (
                (q.transpose() * q - Matrix4::identity()).amax(),
                q.determinant(),
            )
        })?;
        let unit = |i: usize| {
            let mut e = [T::zero(); 4];
            e[i] = T::one();
            e
        };
        let mut assoc = [[T::zero(); 4]; 4];
        for (i, row) in assoc.iter_mut().enumerate() {
            for (j, cell) in row.iter_mut().enumerate() {
                let mut acc = T::zero();
                for c in 0..4 {
                    let e = quat_mul(quat_mul(unit(i), unit(c)), unit(j));
                    for (r, &er) in e.iter().enumerate() {
                        acc += q[(r, c)] * er;
                    }
                }
                *cell = T::lit(0.25) * acc;
            }
        }
        // The largest entry |a_i b_j| fixes the row i and column j with |a_i|, |b_j| large.
        let (mut bi, mut bj) = (0, 0);
        for i in 0..4 {
            for j in 0..4 {
                if assoc[i][j].abs() > assoc[bi][bj].abs() {
                    (bi, bj) = (i, j);
                }
            }
        }
        // b ∝ row bi, a ∝ column bj; each a unit quaternion.
        let b = normalized(assoc[bi]);
        let a = normalized(std::array::from_fn(|i| assoc[i][bj]));
        // a ξ b = (−a) ξ (−b): pick the sign that makes a b_j agree with the associate entry.
        let sign = if a[bi] * b[bj] * assoc[bi][bj] < T::zero() {
            -T::one()
        } else {
            T::one()
        };
        let a = a.map(|c| c * sign);
        // Invert isoclinic_factors: a = (m₀, −m₁, −m₂, m₃), b = Q̄₊.
        let r = Self {
            plus: quat_conj(b),
            minus: [a[0], -a[1], -a[2], a[3]],
        };
        Ok(if r.scalar() < T::zero() {
            Self {
                plus: r.plus.map(|c| -c),
                minus: r.minus.map(|c| -c),
            }
        } else {
            r
        })
    }

    /// Each half divided by its norm: back onto the group after drift.
    #[inline]
    pub fn normalize(self) -> Self {
        Self {
            plus: normalized(self.plus),
            minus: normalized(self.minus),
        }
    }

    /// max |R R̃ − 1|, as [`Rotor::unit_error`]: R R̃ = ½(|Q₊|² + |Q₋|²) + ½(|Q₊|² − |Q₋|²) I.
    #[inline]
    pub fn unit_error(self) -> T {
        let sq = |q: [T; 4]| q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
        let (p, m) = (sq(self.plus), sq(self.minus));
        let h = T::lit(0.5);
        (h * (p + m) - T::one()).abs().max((h * (p - m)).abs())
    }

    /// The even element in the run-time rotor's storage order (s, e₁₄, e₂₄, e₁₂, e₃₄, e₁₃,
    /// e₂₃, e₁₂₃₄), any values (not only unit rotors).
    #[inline(always)]
    pub(crate) fn from_even_layout(c: &[f64; 8]) -> Self
    where
        T: From<f64>,
    {
        let t = |k: usize| T::from(c[k]);
        Self::from_parts(
            t(0),
            Bivector4::new(t(3), t(5), t(1), t(6), t(2), t(4)),
            t(7),
        )
    }

    /// The even element in the run-time rotor's storage order, the inverse of
    /// [`Rotor4::from_even_layout`].
    #[inline(always)]
    pub(crate) fn to_even_layout(self) -> [f64; 8] {
        let b = self.bivector_part();
        let t = |x: T| x.to_f64();
        [
            t(self.scalar()),
            t(b.b14),
            t(b.b24),
            t(b.b12),
            t(b.b34),
            t(b.b13),
            t(b.b23),
            t(self.pseudoscalar()),
        ]
    }

    /// self + self · d, the update R ← R (1 + D) of an increment D.
    #[inline]
    pub(crate) fn plus_product(self, d: Self) -> Self {
        let (p, m) = (quat_mul(self.plus, d.plus), quat_mul(self.minus, d.minus));
        Self {
            plus: std::array::from_fn(|i| self.plus[i] + p[i]),
            minus: std::array::from_fn(|i| self.minus[i] + m[i]),
        }
    }

    /// The run-time [`Rotor`] (N = 4).
    pub fn to_rotor(self) -> Rotor {
        let b = self.bivector_part();
        let mut m = crate::algebra::Multivector::zero(crate::algebra::Signature::euclidean(4));
        let c = m.as_mut_slice();
        c[0] = self.scalar().to_f64();
        c[0b1111] = self.pseudoscalar().to_f64();
        for (mask, v) in [
            (0b0011, b.b12),
            (0b0101, b.b13),
            (0b1001, b.b14),
            (0b0110, b.b23),
            (0b1010, b.b24),
            (0b1100, b.b34),
        ] {
            c[mask] = v.to_f64();
        }
        Rotor::from_multivector_unchecked(&m)
    }
}

impl Rotor4<f64> {
    /// The fixed-size form of a run-time rotor.
    ///
    /// # Errors
    /// [`AlgebraError::DimensionMismatch`] unless N = 4.
    pub fn from_rotor(r: &Rotor) -> Result<Self, AlgebraError> {
        if r.dim() != 4 {
            return Err(AlgebraError::DimensionMismatch {
                left: 4,
                right: r.dim(),
            });
        }
        let c = |m: u64| r.coefficient(m);
        Ok(Self::from_parts(
            r.scalar(),
            Bivector4::new(
                c(0b0011),
                c(0b0101),
                c(0b1001),
                c(0b0110),
                c(0b1010),
                c(0b1100),
            ),
            c(0b1111),
        ))
    }
}

/// q / |q|.
#[inline(always)]
fn normalized<T: Real>(q: [T; 4]) -> [T; 4] {
    let k = T::one() / norm(q);
    q.map(|c| c * k)
}

fixed_size_operators!(Bivector4, Rotor4, Vector4);
