//! Tests of the special functions: published values, a 30-digit mpmath table, identities,
//! limits and error handling.

mod errors;
mod identities;
mod limits;
mod mpmath_reference;
mod published_values;
