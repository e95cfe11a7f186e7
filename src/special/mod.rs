//! Elliptic integrals and Jacobi elliptic functions in `f64`, written for the
//! exact solution of the free asymmetric 3D rigid body (Celledoni, Fassò,
//! Säfström & Zanna, SIAM J. Sci. Comput. 30 (2008) 2084), which needs
//! $\mathrm{sn}, \mathrm{cn}, \mathrm{dn}$, the unwrapped amplitude
//! $\mathrm{am}$ and the incomplete integral of the third kind
//! $\Pi(n;\mathrm{am}(u|m)\,|\,m)$.
//!
//! # Overview
//! | function | value |
//! |---|---|
//! | [`carlson_rf`], [`carlson_rd`], [`carlson_rj`], [`carlson_rc`] | Carlson's symmetric integrals (PV for negative last argument) |
//! | [`elliptic_k`], [`elliptic_e`], [`elliptic_pi`] | complete $K(m)$, $E(m)$, $\Pi(n\,|\,m)$ |
//! | [`elliptic_f`], [`elliptic_e_inc`], [`elliptic_pi_inc`] | incomplete $F(\phi|m)$, $E(\phi|m)$, $\Pi(n;\phi|m)$, any real $\phi$ |
//! | `*_complement` | the same with $m_1 = 1 - m$ as input |
//! | [`jacobi_elliptic`], [`jacobi_elliptic_complement`], [`Jacobi`] | $\mathrm{sn}, \mathrm{cn}, \mathrm{dn}, \mathrm{am}$ together |
//!
//! # Conventions
//! * **Parameter** $m = k^2$ (DLMF §19.1 and §22.1, A&S 17.2 and 16.1, mpmath,
//!   `scipy.special`), never the modulus $k$ or the modular angle.
//!   $m_1 = 1 - m$ is the complementary parameter.
//! * **Characteristic** $n$ of $\Pi$ follows DLMF/mpmath:
//!   $\Pi(n;\phi|m) = \int_0^\phi d\theta / ((1 - n\sin^2\theta)\sqrt{1-m\sin^2\theta})$
//!   (A&S 17.2.14 writes $1 + n\sin^2\theta$).
//! * Divergent integrals of a positive integrand return `+inf` (e.g. $K(1)$);
//!   inputs for which nothing is defined return an [`EllipticError`].
//!   No function returns NaN.
//!
//! # Accuracy
//! Measured against 30-digit mpmath 1.3.0 values at the exact `f64` inputs
//! (5 003 table rows in `tests/data/mpmath_table.rs`, written by
//! `scripts/elliptic_reference.py`; checked by `tests/special/mpmath_reference.rs`).
//! Maximum relative error over the table:
//!
//! | function | max rel. error | where |
//! |---|---|---|
//! | `carlson_rf` / `rd` / `rc` | 5.0e-16 / 5.0e-16 / 2.8e-16 | |
//! | `carlson_rj`, $p > 0$ / PV $p < 0$ | 5.3e-16 / 9.5e-15 | PV: where its terms cancel |
//! | `elliptic_k`, `_complement` | 5.3e-16, 3.1e-16 | $m = 1 - 10^{-9}$ |
//! | `elliptic_e`, `_complement` | 3.3e-16, 3.0e-16 | |
//! | `elliptic_pi` (all $n$, incl. PV) | 4.0e-16 | |
//! | `elliptic_f` / `elliptic_e_inc` | 6.1e-16 / 6.8e-16 | $\phi$ up to $10^{10}$ |
//! | `elliptic_pi_inc`, $n \le 1$ / $n > 1$ | 8.0e-16 / 6.5e-15 | PV: partial cancellation |
//! | sn, cn, dn, am away from zeros | 5.8e-16, 1.9e-15, 1.9e-15, 6.0e-16 | $m_1 = 10^{-6}$ |
//! | sn, cn within $10^{-8}$ of a zero | 9.6e-15, 4.5e-15 | $u = $ fl$(40K)$, abs. error $\approx 10^{-29}$ |
//!
//! Property tests (`tests/identities.rs`) check $\mathrm{sn}^2+\mathrm{cn}^2 = 1$,
//! $\mathrm{dn}^2 + m\,\mathrm{sn}^2 = 1$, $F(\mathrm{am}(u)) = u$,
//! $d\,\mathrm{am}/du = \mathrm{dn}$, the addition theorem, Legendre's relation,
//! periodicity, symmetry and homogeneity of the Carlson integrals, and the
//! derivatives of $F$, $E$, $\Pi$ in $\phi$.
//!
//! # Performance
//! Release build, one core of a shared 2-core VM: `Jacobi::new` ≈ 0.2 µs,
//! `Jacobi::eval` ≈ 0.08–0.16 µs, `carlson_rf` ≈ 40 ns, `carlson_rj` ≈ 0.1 µs,
//! `elliptic_pi_inc` ≈ 0.17 µs for $|\phi| \le \pi/2$ and ≈ 0.4 µs beyond
//! (the complete integral is recomputed on every call).

//! # Supported domains
//! * Carlson: real non-negative $x, y, z$; $R_J$ and $R_C$ also for a negative
//!   last argument (Cauchy principal value).
//! * Legendre integrals: $m \le 1$ (negative $m$ included), any real $n$
//!   ($n > 1$ as principal value), any real $|\phi| < 2^{50}\pi$.
//! * Jacobi functions: $0 \le m \le 1$ only, $|u| < 2^{50}K(m)$.
//!
//! # Not supported
//! $m > 1$, complex arguments, $m < 0$ for the Jacobi functions (use DLMF
//! 22.17.2 / 22.17.4), the Jacobi epsilon and zeta functions.

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
