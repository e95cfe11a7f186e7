//! `approx` comparisons (`AbsDiffEq`, `RelativeEq`, `UlpsEq`) for every algebra type,
//! coefficient by coefficient. Elements of different dimension (or signature) are never equal.

use super::{Bivector, Multivector, Rotor, Vector};
use approx::{AbsDiffEq, RelativeEq, UlpsEq};

/// Whether `a` and `b` are alike (`same`: of one dimension or signature) and every pair of
/// their coefficients is `close`.
fn all_close<T>(
    a: &T,
    b: &T,
    same: fn(&T, &T) -> bool,
    coefficients: fn(&T) -> &[f64],
    close: impl Fn(&f64, &f64) -> bool,
) -> bool {
    same(a, b)
        && coefficients(a)
            .iter()
            .zip(coefficients(b))
            .all(|(x, y)| close(x, y))
}

macro_rules! approx_impls {
    ($t:ty, $same:expr) => {
        impl AbsDiffEq for $t {
            type Epsilon = f64;
            fn default_epsilon() -> f64 {
                f64::EPSILON
            }
            fn abs_diff_eq(&self, other: &Self, epsilon: f64) -> bool {
                all_close::<$t>(self, other, $same, <$t>::as_slice, |a, b| {
                    a.abs_diff_eq(b, epsilon)
                })
            }
        }
        impl RelativeEq for $t {
            fn default_max_relative() -> f64 {
                f64::EPSILON
            }
            fn relative_eq(&self, other: &Self, epsilon: f64, max_relative: f64) -> bool {
                all_close::<$t>(self, other, $same, <$t>::as_slice, |a, b| {
                    a.relative_eq(b, epsilon, max_relative)
                })
            }
        }
        impl UlpsEq for $t {
            fn default_max_ulps() -> u32 {
                4
            }
            fn ulps_eq(&self, other: &Self, epsilon: f64, max_ulps: u32) -> bool {
                all_close::<$t>(self, other, $same, <$t>::as_slice, |a, b| {
                    a.ulps_eq(b, epsilon, max_ulps)
                })
            }
        }
    };
}

approx_impls!(Vector, |a, b| a.dim() == b.dim());
approx_impls!(Bivector, |a, b| a.dim() == b.dim());
approx_impls!(Rotor, |a, b| a.dim() == b.dim());
approx_impls!(Multivector, |a, b| a.signature() == b.signature());
