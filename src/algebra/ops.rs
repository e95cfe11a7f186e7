//! Operator overloads and the [`Versor`] trait. Every operator panics on mismatched
//! dimensions or signatures (documented in the table of [`crate::algebra`], which states the
//! one meaning of each operator across the crate); the checked versions are the methods.

use super::error::{assert_same_dim, check_same_dim};
use super::{AlgebraError, Bivector, Multivector, Rotor, Vector, cga, pga};
use std::ops::{
    Add, AddAssign, BitAnd, BitOr, BitXor, Div, Mul, MulAssign, Neg, Shl, Shr, Sub, SubAssign,
};

/// Applies `f` to each coefficient of `a` and the one of `b` at the same place.
fn zip_apply(a: &mut [f64], b: &[f64], f: impl Fn(&mut f64, f64)) {
    a.iter_mut().zip(b).for_each(|(x, &y)| f(x, y));
}

/// Implements the linear-space operators (+, −, neg, scaling) for a type with
/// `dim()`/`as_slice()`/`as_mut_slice()`-like storage accessed through two closures.
macro_rules! linear_ops {
    ($t:ty, $dim:ident, $slice:ident, $slice_mut:ident) => {
        impl AddAssign<&$t> for $t {
            #[track_caller]
            fn add_assign(&mut self, rhs: &$t) {
                check_pair(self, rhs);
                zip_apply(self.$slice_mut(), rhs.$slice(), |a, b| *a += b);
            }
        }
        impl SubAssign<&$t> for $t {
            #[track_caller]
            fn sub_assign(&mut self, rhs: &$t) {
                check_pair(self, rhs);
                zip_apply(self.$slice_mut(), rhs.$slice(), |a, b| *a -= b);
            }
        }
        impl AddAssign<$t> for $t {
            #[track_caller]
            fn add_assign(&mut self, rhs: $t) {
                *self += &rhs;
            }
        }
        impl SubAssign<$t> for $t {
            #[track_caller]
            fn sub_assign(&mut self, rhs: $t) {
                *self -= &rhs;
            }
        }
        impl MulAssign<f64> for $t {
            fn mul_assign(&mut self, s: f64) {
                self.$slice_mut().iter_mut().for_each(|a| *a *= s);
            }
        }
        impl Add<&$t> for &$t {
            type Output = $t;
            #[track_caller]
            fn add(self, rhs: &$t) -> $t {
                let mut out = self.clone();
                out += rhs;
                out
            }
        }
        impl Add<$t> for $t {
            type Output = $t;
            #[track_caller]
            fn add(mut self, rhs: $t) -> $t {
                self += &rhs;
                self
            }
        }
        impl Add<&$t> for $t {
            type Output = $t;
            #[track_caller]
            fn add(mut self, rhs: &$t) -> $t {
                self += rhs;
                self
            }
        }
        impl Sub<&$t> for &$t {
            type Output = $t;
            #[track_caller]
            fn sub(self, rhs: &$t) -> $t {
                let mut out = self.clone();
                out -= rhs;
                out
            }
        }
        impl Sub<$t> for $t {
            type Output = $t;
            #[track_caller]
            fn sub(mut self, rhs: $t) -> $t {
                self -= &rhs;
                self
            }
        }
        impl Sub<&$t> for $t {
            type Output = $t;
            #[track_caller]
            fn sub(mut self, rhs: &$t) -> $t {
                self -= rhs;
                self
            }
        }
        impl Neg for &$t {
            type Output = $t;
            fn neg(self) -> $t {
                self * -1.0
            }
        }
        impl Neg for $t {
            type Output = $t;
            fn neg(mut self) -> $t {
                self *= -1.0;
                self
            }
        }
        impl Mul<f64> for &$t {
            type Output = $t;
            fn mul(self, s: f64) -> $t {
                let mut out = self.clone();
                out *= s;
                out
            }
        }
        impl Mul<f64> for $t {
            type Output = $t;
            fn mul(mut self, s: f64) -> $t {
                self *= s;
                self
            }
        }
        impl Mul<&$t> for f64 {
            type Output = $t;
            fn mul(self, a: &$t) -> $t {
                a * self
            }
        }
        impl Mul<$t> for f64 {
            type Output = $t;
            fn mul(self, a: $t) -> $t {
                a * self
            }
        }
        impl Div<f64> for &$t {
            type Output = $t;
            fn div(self, s: f64) -> $t {
                self * (1.0 / s)
            }
        }
        impl Div<f64> for $t {
            type Output = $t;
            fn div(self, s: f64) -> $t {
                self * (1.0 / s)
            }
        }
    };
}

trait SameSpace {
    fn space_check(&self, other: &Self);
}
impl SameSpace for Vector {
    #[track_caller]
    fn space_check(&self, other: &Self) {
        assert_same_dim(self.dim(), other.dim());
    }
}
impl SameSpace for Bivector {
    #[track_caller]
    fn space_check(&self, other: &Self) {
        assert_same_dim(self.dim(), other.dim());
    }
}
impl SameSpace for Multivector {
    #[track_caller]
    fn space_check(&self, other: &Self) {
        assert_same_dim(self.dim(), other.dim());
        assert!(
            self.signature() == other.signature(),
            "rotorflow: signature mismatch: {} vs {}",
            self.signature(),
            other.signature()
        );
    }
}
#[track_caller]
fn check_pair<T: SameSpace>(a: &T, b: &T) {
    a.space_check(b);
}

linear_ops!(Vector, dim, as_slice, as_mut_slice);
linear_ops!(Bivector, dim, as_slice, as_mut_slice);
linear_ops!(Multivector, dim, as_slice, as_mut_slice);

/// Implements a product operator on `&Multivector` and `Multivector` from a method.
macro_rules! mv_product_op {
    ($tr:ident, $f:ident, $method:ident) => {
        impl $tr<&Multivector> for &Multivector {
            type Output = Multivector;
            #[track_caller]
            fn $f(self, rhs: &Multivector) -> Multivector {
                self.$method(rhs)
            }
        }
        impl $tr<Multivector> for Multivector {
            type Output = Multivector;
            #[track_caller]
            fn $f(self, rhs: Multivector) -> Multivector {
                self.$method(&rhs)
            }
        }
        impl $tr<&Multivector> for Multivector {
            type Output = Multivector;
            #[track_caller]
            fn $f(self, rhs: &Multivector) -> Multivector {
                self.$method(rhs)
            }
        }
        impl $tr<Multivector> for &Multivector {
            type Output = Multivector;
            #[track_caller]
            fn $f(self, rhs: Multivector) -> Multivector {
                self.$method(&rhs)
            }
        }
    };
}

mv_product_op!(Mul, mul, geometric);
mv_product_op!(BitXor, bitxor, wedge);
mv_product_op!(Shl, shl, left_contract);
mv_product_op!(Shr, shr, right_contract);
mv_product_op!(BitAnd, bitand, regressive);
mv_product_op!(BitOr, bitor, inner);

/// The algebra's products on the multivectors under typed geometric objects: `&`, `^` and
/// `|` mean what they mean for [`Multivector`] and return one (which geometric object comes
/// out, and whether it exists, is what the typed methods such as [`pga::Point::join`] and
/// [`cga::Sphere::through`] decide).
macro_rules! typed_products {
    ($($t:ty),*) => {$(
        impl<B: AsRef<Multivector>> BitAnd<&B> for &$t {
            type Output = Multivector;
            /// The regressive product ∨ of the underlying multivectors.
            #[track_caller]
            fn bitand(self, rhs: &B) -> Multivector {
                self.as_ref().regressive(rhs.as_ref())
            }
        }
        impl<B: AsRef<Multivector>> BitXor<&B> for &$t {
            type Output = Multivector;
            /// The outer product ∧ of the underlying multivectors.
            #[track_caller]
            fn bitxor(self, rhs: &B) -> Multivector {
                self.as_ref().wedge(rhs.as_ref())
            }
        }
        impl<B: AsRef<Multivector>> BitOr<&B> for &$t {
            type Output = Multivector;
            /// The inner product of the underlying multivectors ([`Multivector::inner`]).
            #[track_caller]
            fn bitor(self, rhs: &B) -> Multivector {
                self.as_ref().inner(rhs.as_ref())
            }
        }
    )*};
}

typed_products!(
    pga::Point,
    pga::Line,
    pga::Plane,
    pga::Motor,
    cga::Point,
    cga::Sphere,
    cga::Circle
);

impl Mul<&pga::Motor> for &pga::Motor {
    type Output = pga::Motor;
    /// The composition `self · rhs`: the motion `rhs` first, then `self`
    /// (`a * b` is `b.then(&a)`).
    ///
    /// # Panics
    /// If the motors move spaces of different dimensions ([`pga::Motor::then`] returns the
    /// error instead).
    #[track_caller]
    fn mul(self, rhs: &pga::Motor) -> pga::Motor {
        pga::Motor::product(self, rhs)
    }
}

impl Mul<pga::Motor> for pga::Motor {
    type Output = pga::Motor;
    /// As `&a * &b`.
    #[track_caller]
    fn mul(self, rhs: pga::Motor) -> pga::Motor {
        &self * &rhs
    }
}

impl BitOr<&Vector> for &Vector {
    type Output = f64;
    /// `a | b` is the inner product a · b (a scalar for two vectors).
    #[track_caller]
    fn bitor(self, rhs: &Vector) -> f64 {
        self.dot(rhs)
    }
}

impl BitXor<&Vector> for &Vector {
    type Output = Bivector;
    /// `a ^ b` is the outer product a ∧ b.
    #[track_caller]
    fn bitxor(self, rhs: &Vector) -> Bivector {
        self.wedge(rhs)
    }
}

impl Shl<&Bivector> for &Vector {
    type Output = Vector;
    /// `x << b` is the left contraction x ⌋ B.
    #[track_caller]
    fn shl(self, rhs: &Bivector) -> Vector {
        self.left_contract(rhs)
    }
}

/// A versor V acting on the elements of its algebra by the sandwich X ↦ V X Ṽ (V X V⁻¹ for a
/// unit versor, as every rotor, motor and CGA versor built by rotorflow is): the rotors turn,
/// motors move rigidly, CGA versors map conformally. `V.apply(&x)` returns the element of
/// the same kind, and a `Result` only where the operands can come from different spaces
/// (the run-time types); the fixed-size rotors cannot fail.
///
/// ```
/// use rotorflow::algebra::pga::{Motor, Point};
/// use rotorflow::algebra::{Rotor3, Vector3, Versor};
/// let r = Rotor3::from_rotation_z(std::f64::consts::FRAC_PI_2);
/// assert!((r.apply(&Vector3::x()) - Vector3::y()).amax() < 1e-15);
/// let m = Motor::from_translation(&[1.0, 2.0, 3.0])?;
/// let p = m.apply(&Point::new(&[0.0, 0.0, 0.0])?)?;
/// assert_eq!(p.coordinates()?, vec![1.0, 2.0, 3.0]);
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
pub trait Versor<X: ?Sized> {
    /// The moved element (in a `Result` where the sandwich can fail).
    type Output;
    /// The sandwich V X Ṽ.
    fn apply(&self, x: &X) -> Self::Output;
}

impl Versor<Vector> for Rotor {
    type Output = Result<Vector, AlgebraError>;
    /// [`Rotor::rotate_vector`], checked.
    ///
    /// # Errors
    /// [`AlgebraError::DimensionMismatch`].
    fn apply(&self, x: &Vector) -> Self::Output {
        check_same_dim(self.dim(), x.dim())?;
        Ok(self.rotate_vector(x))
    }
}

impl Versor<Bivector> for Rotor {
    type Output = Result<Bivector, AlgebraError>;
    /// [`Rotor::rotate_bivector`], checked.
    ///
    /// # Errors
    /// [`AlgebraError::DimensionMismatch`].
    fn apply(&self, b: &Bivector) -> Self::Output {
        check_same_dim(self.dim(), b.dim())?;
        Ok(self.rotate_bivector(b))
    }
}

impl Versor<Rotor> for Rotor {
    type Output = Result<Rotor, AlgebraError>;
    /// R S R̃, checked.
    ///
    /// # Errors
    /// [`AlgebraError::DimensionMismatch`].
    fn apply(&self, s: &Rotor) -> Self::Output {
        check_same_dim(self.dim(), s.dim())?;
        Ok(self.compose(s).compose(&self.reverse()))
    }
}

impl Versor<Multivector> for Rotor {
    type Output = Result<Multivector, AlgebraError>;
    /// [`Rotor::rotate_multivector`].
    ///
    /// # Errors
    /// As [`Rotor::rotate_multivector`].
    fn apply(&self, m: &Multivector) -> Self::Output {
        self.rotate_multivector(m)
    }
}

impl Versor<Multivector> for Multivector {
    type Output = Result<Multivector, AlgebraError>;
    /// V X Ṽ for an even versor V of any signature (a CGA translator, dilator or
    /// transversor, a boost of the spacetime algebra, a motor as a plain multivector).
    ///
    /// # Errors
    /// [`AlgebraError::SignatureMismatch`].
    fn apply(&self, x: &Multivector) -> Self::Output {
        let vx = self.try_product(x, super::Product::Geometric)?;
        Ok(vx.geometric(&self.reverse()))
    }
}
