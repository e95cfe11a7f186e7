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
//! Every operation agrees with the run-time types to a few ulp (`tests/algebra/fixed.rs`);
//! conversions both ways are `to_rotor`/`from_rotor` and `to_bivector`/`from_bivector`.

mod batch;
mod d3;
mod d4;

pub use d3::{Bivector3, Rotor3};
pub use d4::{Bivector4, Rotor4};

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
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

/// √(Σ xᵢ²) without overflow or underflow: the plain sum where it is a normal number well
/// inside the range (the run-time types' `scaled_norm` rule), else scaled by the largest.
#[inline(always)]
fn norm<T: Real, const K: usize>(x: [T; K]) -> T {
    let mut s = T::zero();
    for c in x {
        s += c * c;
    }
    // Well inside the range: the squares neither overflow nor lose bits to underflow.
    let (lo, hi) = (T::min_positive().sqrt(), T::max_value().unwrap().sqrt());
    if s > lo && s < hi {
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

/// A unit quaternion's Hamilton product, (w, x, y, z) order.
#[inline(always)]
fn quat_mul<T: Real>(a: [T; 4], b: [T; 4]) -> [T; 4] {
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
