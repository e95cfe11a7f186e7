//! The Python module `rotorflow._rotorflow`, re-exported by the package `rotorflow`.
//!
//! Every function here converts its arguments, calls the crate and converts the answer back:
//! the arithmetic is the crate's. Errors of the crate become `ValueError` with the crate's
//! one-line message; nothing here panics on user input (the crate's panicking conveniences,
//! such as the operators, are never called with operands that have not been checked first).

use pyo3::prelude::*;

mod algebra;
mod arrays;
mod bodies;
mod geometry;
mod kernels;
mod rotors;
mod scene;

/// The module: the algebra, the fixed-size rotors and the bodies.
#[pymodule]
fn _rotorflow(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<algebra::PyAlgebra>()?;
    m.add_class::<algebra::PyMultivector>()?;
    m.add_class::<rotors::PyRotor3>()?;
    m.add_class::<rotors::PyRotor4>()?;
    bodies::register(m)?;
    geometry::register(m)?;
    scene::register(m)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
