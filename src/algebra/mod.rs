//! The Clifford-algebra layer: vectors, bivectors, rotors and multivectors in any dimension
//! chosen at run time.
//!
//! # Types
//! | type | what it is | storage | dimensions |
//! |---|---|---|---|
//! | [`Vector`] | x = Σ xᵢ eᵢ in Euclidean ℝᴺ | N components, inline up to N = 8 | N ≤ [`MAX_DIM`] |
//! | [`Bivector`] | B = Σ_(i<j) B_ij eᵢ∧eⱼ: planes, angular velocity, momentum | N(N−1)/2, inline up to N = 8 | N ≤ [`MAX_DIM`] |
//! | [`Rotor`] | an element of Spin(N), turning by R x R̃ | 2^(N−1) even coefficients, inline up to N = 5 | N ≤ [`MULTIVECTOR_MAX_DIM`] |
//! | [`Multivector`] | any element of Cl(p, q, r) | 2^N coefficients, inline up to N = 4 | N ≤ [`MULTIVECTOR_MAX_DIM`] |
//! | [`Signature`] | the metric Cl(p, q, r) | three small integers | p + q + r ≤ [`MAX_DIM`] |
//! | [`Decomposition`] | a bivector's orthogonal simple planes | planes with magnitudes | as `Bivector` |
//!
//! The graded types ([`Vector`], [`Bivector`], [`Rotor`]) model Euclidean ℝᴺ, the setting of
//! rigid-body rotation: they carry no signature, so their kernels are tight and their API is
//! infallible. Any signature Cl(p, q, r), projective and conformal algebras included, is
//! available through [`Multivector`] (built from components with [`Multivector::vector`] and
//! [`Multivector::bivector`]); the modules [`pga`] (points, lines, planes, motors), [`cga`]
//! (conformal points, spheres, circles, planes and versors) and [`sta`] (Lorentz boosts) add
//! the geometry of the three most used ones.
//!
//! # Conventions
//! The Conventions chapter of the rotorflow book states them in full; in short:
//! - A basis blade is a bit mask: bit i set ⇔ eᵢ₊₁ is a factor (e₁ = 0b1, e₁₃ = 0b101);
//!   [`Multivector::basis_blade`] builds one by mask, [`Multivector::blade_by_name`] by
//!   name (`e13`, `e1e3`, `e₁₃`). Bivector components are stored in
//!   lexicographic order 12, 13, …, 1N, 23, …; indices in the API are 0-based, text is
//!   1-based (`e12` is e₁∧e₂).
//! - \[B\] is the skew matrix with \[B\]_ij = B_ij. The velocity of body point x under angular
//!   velocity ω is x ⌋ ω = \[ω\]ᵀx ([`Vector::left_contract`]).
//! - R = exp(−θ B̂/2) turns by θ in the plane B̂, from its first vector toward its second; its
//!   rotation matrix is expm(\[θB̂\]ᵀ) ([`Rotor::from_rotation_bivector`], [`Rotor::to_matrix`]).
//! - A × B = ½(AB − BA) is the commutator product ([`Bivector::commutator`]).
//!
//! # Operators
//! Each operator has one meaning across the crate: the product of the algebra it names,
//! whatever type it is written between. Operators panic only on mismatched dimensions or
//! signatures; each has a checked method.
//!
//! | expression | meaning | types |
//! |---|---|---|
//! | `a + b`, `a - b`, `-a` | sum, difference, negation | `Vector`, `Bivector`, `Multivector`; the fixed-size bivectors |
//! | `a * s`, `s * a`, `a / s` | scaling by a scalar | `Vector`, `Bivector`, `Multivector`; the fixed-size bivectors |
//! | `a * b` | geometric product a b | `Multivector`; between versors it composes (`Rotor`, `Rotor3`, `Rotor4`, [`pga::Motor`]: `a * b` is b first, then a); a fixed-size rotor times a vector turns it (R x R̃) |
//! | `a ^ b` | outer product a ∧ b | `Multivector`, every typed PGA/CGA object (→ `Multivector`); `&Vector ^ &Vector → Bivector` |
//! | `a & b` | regressive product a ∨ b | `Multivector`, every typed PGA/CGA object (→ `Multivector`) |
//! | `a \| b` | inner product Σ ⟨A_r B_s⟩_\|r−s\| ([`Multivector::inner`]) | `Multivector`, every typed PGA/CGA object (→ `Multivector`); `&Vector \| &Vector → f64` |
//! | `a << b` | left contraction a ⌋ b | `Multivector`; `&Vector << &Bivector → Vector` |
//! | `a >> b` | right contraction a ⌊ b | `Multivector` |
//! | `a += b`, `a -= b`, `a *= s` | in place | `Vector`, `Bivector`, `Multivector` |
//!
//! What ∧ and ∨ do geometrically depends on what a vector stands for, not on the operator.
//! Where blades stand for the subspaces they span (the Euclidean algebra, conformal points:
//! [`cga::Circle::through`] is P₁ ∧ P₂ ∧ P₃), ∧ spans (joins) and ∨ intersects (meets).
//! In plane-based projective GA a vector is a hyperplane, so the same products swap roles:
//! ∧ meets ([`pga::Plane::meet`]) and ∨ joins ([`pga::Point::join`]), as in klein and
//! ganja.js. The operators on typed objects return the plain product; the typed methods
//! say which object results and refuse the special positions where it does not exist.
//!
//! The sandwich X ↦ V X Ṽ of every versor is one trait, [`Versor`]: `V.apply(&x)` for the
//! rotors (on vectors, bivectors and rotors), motors (on points, lines, planes, motors) and
//! conformal versors (on [`cga::Point`], [`cga::Sphere`], [`cga::Circle`] and any
//! multivector).
//!
//! # Example
//! ```
//! use rotorflow::algebra::{Bivector, Rotor, Vector};
//! // A non-simple 4D bivector: rotation by 0.3 in e12 and 1.1 in e34 at once.
//! let theta = Bivector::from_components(4, &[0.3, 0.0, 0.0, 0.0, 0.0, 1.1])?;
//! let r = Rotor::from_rotation_bivector(&theta);
//! assert!(r.unit_error() < 1e-15);
//! assert!((&r.rotation_bivector() - &theta).norm() < 1e-15);
//! // The rotor turns e1 toward e2 by 0.3.
//! let x = r.rotate_vector(&Vector::basis(4, 0));
//! assert!((x[0] - 0.3f64.cos()).abs() < 1e-15 && (x[1] - 0.3f64.sin()).abs() < 1e-15);
//! # Ok::<(), rotorflow::algebra::AlgebraError>(())
//! ```

/// The accessors of a newtype around a [`Multivector`] (a point, plane, line or motor):
/// `as_multivector`, `into_multivector` and `AsRef<Multivector>`; `$what` names the element
/// in the docs.
macro_rules! multivector_newtype {
    ($t:ident, $what:literal) => {
        impl $t {
            #[doc = concat!("The underlying ", $what, ".")]
            pub fn as_multivector(&self) -> &Multivector {
                &self.0
            }

            #[doc = concat!("The underlying ", $what, ", by value.")]
            pub fn into_multivector(self) -> Multivector {
                self.0
            }
        }

        impl AsRef<Multivector> for $t {
            fn as_ref(&self) -> &Multivector {
                &self.0
            }
        }
    };
}

mod approx_impls;
mod bivector;
pub(crate) mod blade;
pub mod cga;
pub mod decompose;
mod display;
mod error;
mod fixed;
mod multivector;
mod nalgebra;
mod ops;
pub mod pga;
mod product_table;
mod rotor;
#[cfg(feature = "serde")]
mod serde_impls;
mod signature;
mod small;
pub mod sta;
mod vector;
mod versor;
mod versor_general;
mod versor_n4;
mod versor_pga3;
mod versor_sqrt;

pub(crate) use bivector::commutator_packed;
pub(crate) use bivector::pair_index;
pub use bivector::{Bivector, SKEW_TOLERANCE, bivector_len, pairs, plane_name};
pub use decompose::{Decomposition, SimplePlane};
pub use error::AlgebraError;
pub use fixed::{Bivector3, Bivector4, Real, Rotor3, Rotor4};
// nalgebra's fixed-size types that the fixed-size rotors take and return, so that a user
// needs no nalgebra dependency of a matching version (the crate itself is re-exported at the
// crate root).
pub use ::nalgebra::{Matrix3, Matrix4, Vector3, Vector4};
pub use multivector::{INVERSE_TOLERANCE, Multivector, Product};
pub use ops::Versor;
pub use product_table::{PRODUCT_TABLE_MAX_DIM, ProductTable};
pub use rotor::{NORMALIZE_TOLERANCE, ROTATION_TOLERANCE, ROTOR_TOLERANCE, Rotor};
pub(crate) use rotor::{accumulate_plane_rotor, plane_table_const};
pub use signature::Signature;
pub use vector::Vector;
pub use versor::{CLOSED_FORM_MAX_DIM, VERSOR_TOLERANCE};
pub use versor_general::GENERAL_MAX_DIM;
pub use versor_sqrt::VERSOR_NORMALIZE_TOLERANCE;

/// The largest dimension for vectors, bivectors and signatures: a basis blade is a `u64` bit
/// mask, so N ≤ 64 (wedged makes the same trade-off at 31). Vectors and bivectors store N and
/// N(N−1)/2 numbers, so this ceiling costs nothing.
pub const MAX_DIM: usize = 64;

/// The largest dimension for types stored densely over blades: a [`Multivector`] holds 2^N
/// coefficients (512 KiB at N = 16) and a [`Rotor`] 2^(N−1). Products of dense elements cost
/// O(4^N), so this is also where they stop being practical.
pub const MULTIVECTOR_MAX_DIM: usize = 16;

impl From<&Vector> for Multivector {
    /// The vector as a grade-1 multivector of Cl(N, 0, 0).
    ///
    /// # Panics
    /// If N > [`MULTIVECTOR_MAX_DIM`].
    #[track_caller]
    fn from(v: &Vector) -> Self {
        let mut m = Multivector::zero(Signature::euclidean(v.dim()));
        for (i, &c) in v.as_slice().iter().enumerate() {
            m.as_mut_slice()[1 << i] = c;
        }
        m
    }
}

impl From<&Bivector> for Multivector {
    /// The bivector as a grade-2 multivector of Cl(N, 0, 0).
    ///
    /// # Panics
    /// If N > [`MULTIVECTOR_MAX_DIM`].
    #[track_caller]
    fn from(b: &Bivector) -> Self {
        let mut m = Multivector::zero(Signature::euclidean(b.dim()));
        for ((i, j), &c) in pairs(b.dim()).zip(b.as_slice()) {
            m.as_mut_slice()[(1 << i) | (1 << j)] = c;
        }
        m
    }
}

impl From<&Rotor> for Multivector {
    /// The rotor as an even multivector of Cl(N, 0, 0).
    fn from(r: &Rotor) -> Self {
        r.to_multivector()
    }
}

impl TryFrom<&Multivector> for Vector {
    type Error = AlgebraError;
    /// The grade-1 part, if the multivector is Euclidean and has no other grades.
    ///
    /// # Errors
    /// [`AlgebraError::UnsupportedSignature`]; [`AlgebraError::MixedGrades`] when other
    /// grades are present.
    fn try_from(m: &Multivector) -> Result<Self, AlgebraError> {
        graded_check(m, 1, "vector")?;
        let n = m.dim();
        Vector::from_components(&(0..n).map(|i| m.coefficient(1 << i)).collect::<Vec<f64>>())
    }
}

impl TryFrom<&Multivector> for Bivector {
    type Error = AlgebraError;
    /// The grade-2 part, if the multivector is Euclidean and has no other grades.
    ///
    /// # Errors
    /// [`AlgebraError::UnsupportedSignature`]; [`AlgebraError::MixedGrades`] when other
    /// grades are present.
    fn try_from(m: &Multivector) -> Result<Self, AlgebraError> {
        graded_check(m, 2, "bivector")?;
        let n = m.dim();
        let comps: Vec<f64> = pairs(n)
            .map(|(i, j)| m.coefficient((1 << i) | (1 << j)))
            .collect();
        Bivector::from_components(n, &comps)
    }
}

fn graded_check(m: &Multivector, k: usize, what: &'static str) -> Result<(), AlgebraError> {
    if !m.signature().is_euclidean() {
        return Err(AlgebraError::UnsupportedSignature {
            operation: "conversion to a graded type",
            signature: m.signature(),
        });
    }
    check_grade(m, k, what)
}

/// Checks that `m` has no part of a grade other than `k`.
pub(crate) fn check_grade(
    m: &Multivector,
    k: usize,
    what: &'static str,
) -> Result<(), AlgebraError> {
    let others = m.terms().filter(|(b, _)| blade::grade(*b) != k).count();
    if others > 0 {
        return Err(AlgebraError::MixedGrades {
            what,
            grade: k,
            others,
        });
    }
    Ok(())
}
