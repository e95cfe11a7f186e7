//! Fixed-size rotors and bivectors of 3D and 4D Euclidean space: `Copy`, on the stack, in
//! `f64` and `f32`, with the conventions of the run-time [`Rotor`](super::Rotor) and
//! [`Bivector`](super::Bivector).
//!
//! | type | what it is | stored as |
//! |---|---|---|
//! | [`Bivector3`] | b₁₂e₁₂ + b₁₃e₁₃ + b₂₃e₂₃ | its three components |
//! | [`Rotor3`] | s + b₁₂e₁₂ + b₁₃e₁₃ + b₂₃e₂₃ in Spin(3) | the quaternion (w, x, y, z) = (s, −b₂₃, b₁₃, −b₁₂) |
//! | [`Bivector4`] | Σ b_ij e_ij, i < j ≤ 4 | its six components |
//! | [`Rotor4`] | s + Σ b_ij e_ij + p e₁₂₃₄ in Spin(4) | the pair of quaternions of Spin(4) ≅ SU(2) × SU(2) |
//!
//! The 3D rotor *is* a unit quaternion with i = −e₂₃, j = e₁₃, k = −e₁₂ (the map is an algebra
//! isomorphism, so the geometric product is Hamilton's product in the same order): it costs
//! what a quaternion costs. In 4D the pseudoscalar I = e₁₂₃₄ is central in the even algebra
//! and squares to +1, so P± = ½(1 ± I) split every rotor into R = Q₊P₊ + Q₋P₋ with unit
//! quaternions Q± (the self-dual and anti-self-dual halves). A product is two quaternion
//! products (56 flops against 64 multiplications and 56 additions of the 8-coefficient
//! form), and exp and log are the quaternion exp and log of each half, which is why isoclinic
//! rotations (one half the identity) need no special case.
//!
//! In f32 on x86 a `Rotor3` keeps its quaternion in the four lanes of an SSE register and
//! multiplies lane-wise (through the safe wrappers of `safe_arch`), as glam's `Quat` does;
//! elsewhere, and in f64, it is an array and the product the scalar formula.
//!
//! Every operation agrees with the run-time types to a few ulp (`tests/algebra/fixed.rs`);
//! conversions both ways are `to_rotor`/`from_rotor` and `to_bivector`/`from_bivector`.

/// What the 3D and 4D types share: bivectors add, subtract, negate and scale component by
/// component; rotors compose by `*`, rotate vectors by `*`, act as [`Versor`]s on vectors,
/// bivectors and rotors, convert to and from rotation bivectors, and default to the identity.
///
/// [`Versor`]: crate::algebra::Versor
macro_rules! fixed_size_operators {
    ($bivector:ident, $rotor:ident, $vector:ident) => {
        impl<T: Real> std::ops::Add for $bivector<T> {
            type Output = Self;
            #[inline]
            fn add(self, o: Self) -> Self {
                let (a, b) = (self.to_array(), o.to_array());
                Self::from_array(std::array::from_fn(|i| a[i] + b[i]))
            }
        }

        impl<T: Real> std::ops::Sub for $bivector<T> {
            type Output = Self;
            #[inline]
            fn sub(self, o: Self) -> Self {
                let (a, b) = (self.to_array(), o.to_array());
                Self::from_array(std::array::from_fn(|i| a[i] - b[i]))
            }
        }

        impl<T: Real> std::ops::Neg for $bivector<T> {
            type Output = Self;
            #[inline]
            fn neg(self) -> Self {
                Self::from_array(self.to_array().map(|c| -c))
            }
        }

        impl<T: Real> std::ops::Mul<T> for $bivector<T> {
            type Output = Self;
            #[inline]
            fn mul(self, s: T) -> Self {
                Self::from_array(self.to_array().map(|c| c * s))
            }
        }

        impl<T: Real> Default for $rotor<T> {
            fn default() -> Self {
                Self::identity()
            }
        }

        impl<T: Real> std::ops::Mul for $rotor<T> {
            type Output = Self;
            /// The geometric product, `compose`.
            #[inline]
            fn mul(self, other: Self) -> Self {
                self.compose(other)
            }
        }

        impl<T: Real> std::ops::Mul<$vector<T>> for $rotor<T> {
            type Output = $vector<T>;
            /// `rotate_vector`.
            #[inline]
            fn mul(self, x: $vector<T>) -> $vector<T> {
                self.rotate_vector(x)
            }
        }

        impl<T: Real> $crate::algebra::Versor<$vector<T>> for $rotor<T> {
            type Output = $vector<T>;
            /// `rotate_vector`.
            #[inline]
            fn apply(&self, x: &$vector<T>) -> $vector<T> {
                self.rotate_vector(*x)
            }
        }

        impl<T: Real> $crate::algebra::Versor<$bivector<T>> for $rotor<T> {
            type Output = $bivector<T>;
            /// `rotate_bivector`.
            #[inline]
            fn apply(&self, b: &$bivector<T>) -> $bivector<T> {
                self.rotate_bivector(*b)
            }
        }

        impl<T: Real> $crate::algebra::Versor<$rotor<T>> for $rotor<T> {
            type Output = $rotor<T>;
            /// R S R̃: the rotation S carried by R (the same rotation in the turned frame).
            #[inline]
            fn apply(&self, s: &$rotor<T>) -> $rotor<T> {
                *self * *s * self.reverse()
            }
        }

        impl<T: Real> $rotor<T> {
            /// The rotor exp(−Θ/2) of the rotation bivector Θ: the rotation by |Θ| in the
            /// plane Θ̂, as [`Rotor::from_rotation_bivector`](crate::algebra::Rotor::from_rotation_bivector).
            #[inline]
            pub fn from_rotation_bivector(theta: $bivector<T>) -> Self {
                (theta * T::lit(-0.5)).exp()
            }

            /// Θ = −2 log R, the inverse of `from_rotation_bivector`.
            #[inline]
            pub fn rotation_bivector(self) -> $bivector<T> {
                self.log() * T::lit(-2.0)
            }

            /// The rotation a fraction `t` of the way from `self` to `other` along the
            /// shorter arc, as [`Rotor::slerp`](crate::algebra::Rotor::slerp).
            #[inline]
            pub fn slerp(self, other: Self, t: T) -> Self {
                let delta = self.reverse().compose(other);
                // R and −R are one rotation: ⟨R̃₁R₂⟩₀ < 0 means the other arc is shorter.
                let delta = if delta.scalar() < T::zero() {
                    -delta
                } else {
                    delta
                };
                self.compose((delta.log() * t).exp())
            }
        }
    };
}

mod batch;
mod d3;
mod d4;
#[cfg(feature = "glam")]
mod glam_impls;

pub use d3::{Bivector3, Rotor3};
pub use d4::{Bivector4, Rotor4};

pub(crate) mod sealed {
    /// What differs between the two scalar types beyond [`super::Real`]: how a quaternion
    /// is kept and multiplied. f32 on x86 keeps it in the four lanes of an SSE register and
    /// multiplies lane-wise, as glam's `Quat` does; f64, and f32 elsewhere, keep an array.
    pub trait Sealed: Sized {
        /// A quaternion (w, x, y, z) as this type keeps it.
        type Quat: Copy + core::fmt::Debug + PartialEq + Send + Sync;
        /// The quaternion of the array (w, x, y, z).
        fn quat_lanes(q: [Self; 4]) -> Self::Quat;
        /// The array (w, x, y, z) of the quaternion.
        fn quat_array(q: Self::Quat) -> [Self; 4];
        /// Hamilton's product of two quaternions, (w, x, y, z) order.
        fn quat_mul(a: [Self; 4], b: [Self; 4]) -> [Self; 4];
        /// Hamilton's product of two quaternions as this type keeps them.
        fn quat_product(a: Self::Quat, b: Self::Quat) -> Self::Quat;
    }

    /// Quaternions kept as arrays and multiplied by the scalar formula.
    macro_rules! array_quaternions {
        ($t:ty) => {
            impl Sealed for $t {
                type Quat = [$t; 4];
                #[inline(always)]
                fn quat_lanes(q: [$t; 4]) -> [$t; 4] {
                    q
                }
                #[inline(always)]
                fn quat_array(q: [$t; 4]) -> [$t; 4] {
                    q
                }
                #[inline(always)]
                fn quat_mul(a: [$t; 4], b: [$t; 4]) -> [$t; 4] {
                    super::quat_mul_scalar(a, b)
                }
                #[inline(always)]
                fn quat_product(a: [$t; 4], b: [$t; 4]) -> [$t; 4] {
                    super::quat_mul_scalar(a, b)
                }
            }
        };
    }

    array_quaternions!(f64);

    #[cfg(all(
        any(target_arch = "x86", target_arch = "x86_64"),
        target_feature = "sse"
    ))]
    impl Sealed for f32 {
        type Quat = super::lanes::Lanes;
        #[inline(always)]
        fn quat_lanes(q: [f32; 4]) -> Self::Quat {
            super::lanes::Lanes::new(q)
        }
        #[inline(always)]
        fn quat_array(q: Self::Quat) -> [f32; 4] {
            q.array()
        }
        #[inline(always)]
        fn quat_mul(a: [f32; 4], b: [f32; 4]) -> [f32; 4] {
            super::lanes::Lanes::new(a)
                .product(super::lanes::Lanes::new(b))
                .array()
        }
        #[inline(always)]
        fn quat_product(a: Self::Quat, b: Self::Quat) -> Self::Quat {
            a.product(b)
        }
    }

    #[cfg(not(all(
        any(target_arch = "x86", target_arch = "x86_64"),
        target_feature = "sse"
    )))]
    array_quaternions!(f32);
}

/// An f32 quaternion in the four lanes of an SSE register.
#[cfg(all(
    any(target_arch = "x86", target_arch = "x86_64"),
    target_feature = "sse"
))]
mod lanes {
    use safe_arch::{add_m128, m128, mul_m128, shuffle_abi_f32_all_m128 as shuffle};

    /// The quaternion (w, x, y, z) in lanes 0 … 3.
    #[derive(Clone, Copy)]
    pub struct Lanes(m128);

    impl Lanes {
        #[inline(always)]
        pub fn new(q: [f32; 4]) -> Lanes {
            Lanes(m128::from_array(q))
        }

        #[inline(always)]
        pub fn array(self) -> [f32; 4] {
            self.0.to_array()
        }

        /// Hamilton's product: a's four coefficients, each splat across the lanes, times b
        /// with its coefficients permuted and signed so that lane k collects the terms of
        /// coefficient k, (w₁b + x₁b′) + (y₁b″ + z₁b‴). It is glam's formulation for its
        /// `Quat`; the sum's order differs from the scalar formula's, so the two agree to a
        /// few ulp.
        #[inline(always)]
        pub fn product(self, other: Lanes) -> Lanes {
            let (a, b) = (self.0, other.0);
            // Lane k of shuffle::<M>(x, x) is x[(M >> 2k) & 3]: splats 0b00.., 0b01.., …;
            // b′ = (x, w, z, y), b″ = (y, z, w, x), b‴ = (z, y, x, w).
            let (aw, ax) = (
                shuffle::<0b00_00_00_00>(a, a),
                shuffle::<0b01_01_01_01>(a, a),
            );
            let (ay, az) = (
                shuffle::<0b10_10_10_10>(a, a),
                shuffle::<0b11_11_11_11>(a, a),
            );
            let b1 = mul_m128(
                shuffle::<0b10_11_00_01>(b, b),
                m128::from_array([-1.0, 1.0, -1.0, 1.0]),
            );
            let b2 = mul_m128(
                shuffle::<0b01_00_11_10>(b, b),
                m128::from_array([-1.0, 1.0, 1.0, -1.0]),
            );
            let b3 = mul_m128(
                shuffle::<0b00_01_10_11>(b, b),
                m128::from_array([-1.0, -1.0, 1.0, 1.0]),
            );
            let first = add_m128(mul_m128(aw, b), mul_m128(ax, b1));
            let second = add_m128(mul_m128(ay, b2), mul_m128(az, b3));
            Lanes(add_m128(first, second))
        }
    }

    impl core::fmt::Debug for Lanes {
        fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
            self.array().fmt(f)
        }
    }

    impl PartialEq for Lanes {
        fn eq(&self, other: &Lanes) -> bool {
            self.array() == other.array()
        }
    }
}

/// The scalar types of the fixed-size rotors: `f64` and `f32` (sealed).
pub trait Real: nalgebra::RealField + Copy + sealed::Sealed {
    /// The literal `x` in this type.
    fn lit(x: f64) -> Self;
    /// The value as `f64` (exact for both types).
    fn to_f64(self) -> f64;
    /// The smallest positive normal number.
    fn min_positive() -> Self;
}

impl Real for f64 {
    #[inline(always)]
    fn lit(x: f64) -> f64 {
        x
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline(always)]
    fn min_positive() -> f64 {
        f64::MIN_POSITIVE
    }
}

impl Real for f32 {
    #[inline(always)]
    fn lit(x: f64) -> f32 {
        x as f32
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        f64::from(self)
    }
    #[inline(always)]
    fn min_positive() -> f32 {
        f32::MIN_POSITIVE
    }
}

/// True for a sum of squares Σ xᵢ² well inside the range, where √(Σ xᵢ²) is the norm: the
/// squares neither overflowed nor lost bits to underflow (false for NaN and ∞).
#[inline(always)]
fn plain_norm_range<T: Real>(s: T) -> bool {
    let (lo, hi) = (T::min_positive().sqrt(), T::max_value().unwrap().sqrt());
    s > lo && s < hi
}

/// √(Σ xᵢ²) without overflow or underflow: the plain sum where it is a normal number well
/// inside the range (the run-time types' `scaled_norm` rule), else scaled by the largest.
#[inline(always)]
fn norm<T: Real, const K: usize>(x: [T; K]) -> T {
    let mut s = T::zero();
    for c in x {
        s += c * c;
    }
    if plain_norm_range(s) {
        return s.sqrt();
    }
    let m = x.iter().fold(T::zero(), |m, c| m.max(c.abs()));
    if m == T::zero() || !m.is_finite() {
        return m;
    }
    let mut t = T::zero();
    for c in x {
        t += (c / m) * (c / m);
    }
    m * t.sqrt()
}

/// Ok for a finite matrix (its `entries`) whose (max |QᵀQ − 1|, det Q) from `measure` make
/// it a rotation within [`super::ROTATION_TOLERANCE`], as the run-time `Rotor::from_matrix`
/// requires.
fn check_rotation<T: Real>(
    mut entries: impl Iterator<Item = T>,
    measure: impl FnOnce() -> (T, T),
) -> Result<(), super::AlgebraError> {
    if !entries.all(|c| c.is_finite()) {
        return Err(super::AlgebraError::NonFinite { what: "matrix" });
    }
    let (error, det) = measure();
    let (error, det) = (error.to_f64(), det.to_f64());
    if !(error <= super::ROTATION_TOLERANCE && det > 0.0) {
        return Err(super::AlgebraError::NotARotation {
            orthogonality_error: error,
            determinant: det,
            tolerance: super::ROTATION_TOLERANCE,
        });
    }
    Ok(())
}

/// The slot of the plane eᵢ∧eⱼ among the lexicographic components of dimension `n`, and
/// the sign of eᵢⱼ there (−1 when i > j: eᵢⱼ = −eⱼᵢ).
fn plane_slot(n: usize, i: usize, j: usize) -> Result<(usize, f64), super::AlgebraError> {
    for k in [i, j] {
        if k >= n {
            return Err(super::AlgebraError::IndexOutOfRange { index: k, dim: n });
        }
    }
    match i.cmp(&j) {
        std::cmp::Ordering::Less => Ok((super::pair_index(n, i, j), 1.0)),
        std::cmp::Ordering::Greater => Ok((super::pair_index(n, j, i), -1.0)),
        std::cmp::Ordering::Equal => Err(super::AlgebraError::RepeatedIndex { index: i }),
    }
}

/// The inverse q̄ / |q|² of a quaternion (q̄ itself for a unit one, up to round-off).
#[inline(always)]
fn quat_inverse<T: Real>(q: [T; 4]) -> [T; 4] {
    let k = T::one() / (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    quat_conj(q).map(|c| c * k)
}

/// A unit quaternion's Hamilton product, (w, x, y, z) order: in f32 on x86 with SSE four
/// lanes at once, else the scalar formula.
#[inline(always)]
fn quat_mul<T: Real>(a: [T; 4], b: [T; 4]) -> [T; 4] {
    <T as sealed::Sealed>::quat_mul(a, b)
}

/// [`quat_mul`] written out.
#[inline(always)]
fn quat_mul_scalar<T: Real>(a: [T; 4], b: [T; 4]) -> [T; 4] {
    let [w1, x1, y1, z1] = a;
    let [w2, x2, y2, z2] = b;
    [
        w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
        w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
        w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
        w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
    ]
}

/// exp of the pure quaternion v: cos |v| + (sin |v| / |v|) v.
#[inline(always)]
fn quat_exp<T: Real>(v: [T; 3]) -> [T; 4] {
    quat_exp_with_norm(v, norm(v))
}

/// [`quat_exp`] with θ = |v| given (summed in the caller's order: at large angles one ulp of
/// θ moves sin θ by far more than one ulp, so the run-time types' order is kept).
#[inline(always)]
fn quat_exp_with_norm<T: Real>(v: [T; 3], theta: T) -> [T; 4] {
    let (s, c) = theta.sin_cos();
    let k = if theta > T::zero() {
        s / theta
    } else {
        T::one()
    };
    [c, k * v[0], k * v[1], k * v[2]]
}

/// [`quat_exp`] minus 1 in f64, with cos θ − 1 and sin θ/θ from θ²
/// ([`cos_minus_one_sinc_of_square`]): no square root or libm call at the small angles of a
/// step, and no rounding of 1 + (cos θ − 1) to take back.
///
/// [`cos_minus_one_sinc_of_square`]: crate::numeric::trig::cos_minus_one_sinc_of_square
#[inline(always)]
fn quat_exp_minus_one(v: [f64; 3]) -> [f64; 4] {
    let y = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    let (m, k) = crate::numeric::trig::cos_minus_one_sinc_of_square(y);
    [m, k * v[0], k * v[1], k * v[2]]
}

/// The principal log of a unit quaternion: atan2(|v|, w) v/|v| (angle in [0, π]; −1 gives
/// π along the first axis).
#[inline(always)]
fn quat_log<T: Real>(q: [T; 4]) -> [T; 3] {
    let v = [q[1], q[2], q[3]];
    let nv = norm(v);
    if nv > T::zero() {
        let k = nv.atan2(q[0]) / nv;
        [k * v[0], k * v[1], k * v[2]]
    } else if q[0] < T::zero() {
        [T::pi(), T::zero(), T::zero()]
    } else {
        [T::zero(); 3]
    }
}

/// The conjugate (reverse) of a quaternion.
#[inline(always)]
fn quat_conj<T: Real>(q: [T; 4]) -> [T; 4] {
    [q[0], -q[1], -q[2], -q[3]]
}

/// max |q q̄ − 1| of a quaternion.
#[inline(always)]
fn quat_unit_error<T: Real>(q: [T; 4]) -> T {
    (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] - T::one()).abs()
}
