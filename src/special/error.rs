//! The error type shared by every function of the crate.

/// Why an elliptic integral or an elliptic function could not be evaluated.
///
/// No function of this crate returns NaN: an input for which no value is
/// defined (or supported) gives one of these variants instead. Integrals that
/// diverge because their integrand is positive (e.g. K(1)) are *not* errors:
/// they return `f64::INFINITY`, which is the value of the integral.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum EllipticError {
    /// An argument is NaN or infinite.
    ///
    /// # How to fix
    /// Check the computation that produced the argument; every argument of
    /// this crate must be finite.
    #[error("argument `{name}` must be finite, got {value}")]
    NonFinite {
        /// Name of the offending argument, as spelled in the function signature.
        name: &'static str,
        /// The value that was passed.
        value: f64,
    },

    /// An argument is finite but outside the supported domain.
    ///
    /// # How to fix
    /// `domain` states the accepted range. For a parameter m > 1 use the
    /// reciprocal-modulus transformation (DLMF 19.7.4, 22.17.4) before calling.
    #[error("argument `{name}` = {value} is outside the supported domain {domain}")]
    OutOfDomain {
        /// Name of the offending argument.
        name: &'static str,
        /// The value that was passed.
        value: f64,
        /// Human-readable description of the supported domain.
        domain: &'static str,
    },

    /// The argument is so large that reducing it modulo the period would
    /// leave no correct digits.
    ///
    /// # How to fix
    /// Reduce the argument yourself with the exact period of your problem, or
    /// keep `|argument| / period` below `limit`.
    #[error(
        "argument `{name}` = {value} is too large for an accurate period reduction (|{name}| must be below {limit})"
    )]
    ArgumentTooLarge {
        /// Name of the offending argument.
        name: &'static str,
        /// The value that was passed.
        value: f64,
        /// The largest accepted magnitude for this call.
        limit: f64,
    },

    /// The integral has no value, not even as a Cauchy principal value.
    ///
    /// This happens only for R_J(x, y, z, p) with p < 0 and two of
    /// x, y, z equal to zero, where the integrand has a non-integrable
    /// singularity of both signs.
    ///
    /// # How to fix
    /// Do not ask for this integral; it is undefined.
    #[error("{function} diverges and has no principal value for these arguments")]
    Divergent {
        /// Name of the function that was called.
        function: &'static str,
    },

    /// Intermediate quantities over- or underflowed `f64`, so no meaningful
    /// value could be formed. This needs extreme inputs, such as Carlson
    /// arguments whose ratio exceeds ~10²⁵⁰ or |m| > 10²⁵⁰.
    ///
    /// # How to fix
    /// Rescale the problem (Carlson integrals are homogeneous) or use an
    /// asymptotic form for such extreme parameters.
    #[error("{function}: intermediate over- or underflow for these extreme arguments")]
    Overflow {
        /// Name of the function that was called.
        function: &'static str,
    },
}

/// Passes a computed value through, turning a NaN (which can only arise from
/// over- or underflow of intermediate quantities) into an error.
pub(crate) fn finish(function: &'static str, value: f64) -> Result<f64, EllipticError> {
    if value.is_nan() {
        Err(EllipticError::Overflow { function })
    } else {
        Ok(value)
    }
}

/// Returns `Err(NonFinite)` unless `value` is finite, then `Err(OutOfDomain)` with the
/// stated `domain` unless `inside(value)`.
pub(crate) fn check_domain(
    name: &'static str,
    value: f64,
    domain: &'static str,
    inside: impl FnOnce(f64) -> bool,
) -> Result<(), EllipticError> {
    check_finite(name, value)?;
    if inside(value) {
        Ok(())
    } else {
        Err(EllipticError::OutOfDomain {
            name,
            value,
            domain,
        })
    }
}

/// Returns `Err(NonFinite)` unless `value` is finite.
pub(crate) fn check_finite(name: &'static str, value: f64) -> Result<(), EllipticError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(EllipticError::NonFinite { name, value })
    }
}
