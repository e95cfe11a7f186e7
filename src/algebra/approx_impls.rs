//! `approx` comparisons (`AbsDiffEq`, `RelativeEq`, `UlpsEq`) for every algebra type,
//! coefficient by coefficient. Elements of different dimension (or signature) are never equal.

use super::{Bivector, Multivector, Rotor, Vector};
use approx::{AbsDiffEq, RelativeEq, UlpsEq};

macro_rules! approx_impls {
    ($t:ty, $slice:ident, $same:expr) => {
        impl AbsDiffEq for $t {
            type Epsilon = f64;
            fn default_epsilon() -> f64 {
                f64::EPSILON
            }
            fn abs_diff_eq(&self, other: &Self, epsilon: f64) -> bool {
                let same: fn(&$t, &$t) -> bool = $same;
                same(self, other)
                    && self
                        .$slice()
                        .iter()
                        .zip(other.$slice())
                        .all(|(a, b)| a.abs_diff_eq(b, epsilon))
            }
        }
        impl RelativeEq for $t {
            fn default_max_relative() -> f64 {
                f64::EPSILON
            }
            fn relative_eq(&self, other: &Self, epsilon: f64, max_relative: f64) -> bool {
                let same: fn(&$t, &$t) -> bool = $same;
                same(self, other)
                    && self
                        .$slice()
                        .iter()
                        .zip(other.$slice())
                        .all(|(a, b)| a.relative_eq(b, epsilon, max_relative))
            }
        }
        impl UlpsEq for $t {
            fn default_max_ulps() -> u32 {
                4
            }
            fn ulps_eq(&self, other: &Self, epsilon: f64, max_ulps: u32) -> bool {
                let same: fn(&$t, &$t) -> bool = $same;
                same(self, other)
                    && self
                        .$slice()
                        .iter()
                        .zip(other.$slice())
                        .all(|(a, b)| a.ulps_eq(b, epsilon, max_ulps))
            }
        }
    };
}

approx_impls!(Vector, as_slice, |a, b| a.dim() == b.dim());
approx_impls!(Bivector, as_slice, |a, b| a.dim() == b.dim());
approx_impls!(Rotor, as_slice, |a, b| a.dim() == b.dim());
approx_impls!(Multivector, as_slice, |a, b| a.signature() == b.signature());
