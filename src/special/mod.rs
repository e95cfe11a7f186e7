//! Elliptic integrals and Jacobi elliptic functions in `f64`, written for the exact solution
//! of the free asymmetric 3D rigid body (Celledoni, Fassò, Säfström & Zanna, *The exact
//! computation of the free rigid body motion and its use in splitting methods*, SIAM J. Sci.
//! Comput. 30 (2008) 2084), which needs sn, cn, dn, the unwrapped amplitude am and the
//! incomplete integral of the third kind Π(n; am(u|m) | m).
//!
//! # Overview
//! | function | value |
//! |---|---|
//! | [`carlson_rf`], [`carlson_rd`], [`carlson_rj`], [`carlson_rc`] | Carlson's symmetric integrals (principal value for a negative last argument) |
//! | [`elliptic_k`], [`elliptic_e`], [`elliptic_pi`] | complete K(m), E(m), Π(n\|m) |
//! | [`elliptic_f`], [`elliptic_e_inc`], [`elliptic_pi_inc`] | incomplete F(φ\|m), E(φ\|m), Π(n; φ\|m), any real φ |
//! | `*_complement` | the same with m₁ = 1 − m as input |
//! | [`jacobi_elliptic`], [`jacobi_elliptic_complement`], [`Jacobi`] | sn, cn, dn, am together |
//!
//! # Conventions
//! * **Parameter** m = k² (DLMF §19.1 and §22.1, A&S 17.2 and 16.1, mpmath,
//!   `scipy.special`), never the modulus k or the modular angle. m₁ = 1 − m is the
//!   complementary parameter.
//! * **Characteristic** n of Π follows DLMF/mpmath:
//!   Π(n; φ|m) = ∫₀^φ dθ / ((1 − n sin²θ) √(1 − m sin²θ))
//!   (A&S 17.2.14 writes 1 + n sin²θ).
//! * Divergent integrals of a positive integrand return `+inf` (e.g. K(1)); inputs for which
//!   nothing is defined return an [`EllipticError`]. No function returns NaN.
//!
//! # Accuracy
//! Measured against 30-digit mpmath 1.3.0 values at the exact `f64` inputs (5 003 table rows
//! in `tests/special/data/mpmath_table.rs`, written by `scripts/elliptic_reference.py`;
//! checked by `tests/special/mpmath_reference.rs`). Maximum relative error over the table:
//!
//! | function | max rel. error | where |
//! |---|---|---|
//! | `carlson_rf` / `rd` / `rc` | 5.0e-16 / 5.0e-16 / 2.8e-16 | |
//! | `carlson_rj`, p > 0 / principal value p < 0 | 5.3e-16 / 9.5e-15 | PV: where its terms cancel |
//! | `elliptic_k`, `_complement` | 5.3e-16, 3.1e-16 | m = 1 − 10⁻⁹ |
//! | `elliptic_e`, `_complement` | 3.3e-16, 3.0e-16 | |
//! | `elliptic_pi` (all n, incl. PV) | 4.0e-16 | |
//! | `elliptic_f` / `elliptic_e_inc` | 6.1e-16 / 6.8e-16 | φ up to 10¹⁰ |
//! | `elliptic_pi_inc`, n ≤ 1 / n > 1 | 8.0e-16 / 6.5e-15 | PV: partial cancellation |
//! | sn, cn, dn, am away from zeros | 5.8e-16, 1.9e-15, 1.9e-15, 6.0e-16 | m₁ = 10⁻⁶ |
//! | sn, cn within 10⁻⁸ of a zero | 9.6e-15, 4.5e-15 | u = fl(40K), abs. error ≈ 10⁻²⁹ |
//!
//! Property tests (`tests/special/identities.rs`) check sn² + cn² = 1, dn² + m sn² = 1,
//! F(am(u)) = u, d am/du = dn, the addition theorem, Legendre's relation, periodicity,
//! symmetry and homogeneity of the Carlson integrals, and the derivatives of F, E, Π in φ.
//!
//! # Cost
//! `elliptic_pi_inc` recomputes the complete integral on every call, so beyond |φ| ≤ π/2 it
//! costs about twice as much; [`Jacobi`] precomputes what depends on m alone, so that
//! evaluating at many u is cheap.
//!
//! # Supported domains
//! * Carlson: real non-negative x, y, z; R_J and R_C also for a negative last argument
//!   (Cauchy principal value).
//! * Legendre integrals: m ≤ 1 (negative m included), any real n (n > 1 as principal
//!   value), any real |φ| < 2⁵⁰π.
//! * Jacobi functions: 0 ≤ m ≤ 1 only, |u| < 2⁵⁰K(m).
//!
//! # Not supported
//! m > 1, complex arguments, m < 0 for the Jacobi functions (use DLMF 22.17.2 / 22.17.4), the
//! Jacobi epsilon and zeta functions.

mod carlson;
mod dd;
mod error;
mod jacobi;
mod legendre;

pub use carlson::{carlson_rc, carlson_rd, carlson_rf, carlson_rj};
pub use error::EllipticError;
pub use jacobi::{Jacobi, JacobiElliptic, jacobi_elliptic, jacobi_elliptic_complement};
pub use legendre::{
    elliptic_e, elliptic_e_complement, elliptic_e_inc, elliptic_e_inc_complement, elliptic_f,
    elliptic_f_complement, elliptic_k, elliptic_k_complement, elliptic_pi, elliptic_pi_complement,
    elliptic_pi_inc, elliptic_pi_inc_complement,
};
