//! Operator overloads. Every operator panics on mismatched dimensions (documented in the
//! table of [`crate::algebra`]); the checked versions are the `try_` methods.
//!
//! | expression | meaning | types |
//! |---|---|---|
//! | `a + b`, `a - b`, `-a` | sum, difference, negation | `Vector`, `Bivector`, `Multivector` |
//! | `a * s`, `s * a`, `a / s` | scaling by an `f64` | `Vector`, `Bivector`, `Multivector` |
//! | `a * b` | geometric product | `Multivector`; `Rotor` (composition) |
//! | `a ^ b` | outer product a ∧ b | `Multivector`; `Vector ^ Vector → Bivector` |
//! | `a << b` | left contraction a ⌋ b | `Multivector`; `Vector << Bivector → Vector` |
//! | `a >> b` | right contraction a ⌊ b | `Multivector` |
//! | `a & b` | regressive product a ∨ b (meet) | `Multivector` |
//! | `a += b`, `a -= b`, `a *= s` | in place | `Vector`, `Bivector`, `Multivector` |

use super::error::assert_same_dim;
use super::{Bivector, Multivector, Vector};
use std::ops::{
    Add, AddAssign, BitAnd, BitXor, Div, Mul, MulAssign, Neg, Shl, Shr, Sub, SubAssign,
};

/// Implements the linear-space operators (+, −, neg, scaling) for a type with
/// `dim()`/`as_slice()`/`as_mut_slice()`-like storage accessed through two closures.
macro_rules! linear_ops {
    ($t:ty, $dim:ident, $slice:ident, $slice_mut:ident) => {
        impl AddAssign<&$t> for $t {
            #[track_caller]
            fn add_assign(&mut self, rhs: &$t) {
                check_pair(self, rhs);
                self.$slice_mut()
                    .iter_mut()
                    .zip(rhs.$slice())
                    .for_each(|(a, b)| *a += b);
            }
        }
        impl SubAssign<&$t> for $t {
            #[track_caller]
            fn sub_assign(&mut self, rhs: &$t) {
                check_pair(self, rhs);
                self.$slice_mut()
                    .iter_mut()
                    .zip(rhs.$slice())
                    .for_each(|(a, b)| *a -= b);
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
