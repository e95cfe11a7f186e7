//! Bodies, inertia reports and motion.

use pyo3::prelude::*;

/// Adds the bodies' classes and functions to the module.
pub fn register(_m: &Bound<'_, PyModule>) -> PyResult<()> {
    Ok(())
}
