//! The crate's typed objects of projective, conformal and spacetime algebra, as elements of
//! `Algebra.pga(n)`, `Algebra.cga(n)` and `Algebra.spacetime()` (Python: the modules
//! `rotorflow.pga`, `rotorflow.cga` and `rotorflow.sta`).

use crate::algebra::PyMultivector;
use crate::arrays::value_error;
use numpy::{IntoPyArray, PyArrayDyn, PyUntypedArrayMethods, ndarray::ArrayD, ndarray::IxDyn};
use pyo3::prelude::*;
use rotorflow::algebra::{cga, pga, sta};
use rotorflow::nalgebra::DMatrix;

fn numbers(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<f64>> {
    let array = crate::arrays::f64_array(obj, what)?;
    if array.ndim() != 1 {
        return Err(value_error(format!(
            "{what}: expected a list of numbers, got shape {:?}",
            array.shape()
        )));
    }
    Ok(array.as_slice().expect("contiguous").to_vec())
}

fn element(mv: rotorflow::algebra::Multivector) -> PyMultivector {
    PyMultivector { mv }
}

fn index(k: i64, what: &str) -> PyResult<usize> {
    usize::try_from(k).map_err(|_| value_error(format!("{what} must be >= 0, got {k}")))
}

fn array1(py: Python<'_>, v: Vec<f64>) -> Bound<'_, PyArrayDyn<f64>> {
    let n = v.len();
    ArrayD::from_shape_vec(IxDyn(&[n]), v)
        .expect("the data fills the shape")
        .into_pyarray(py)
}

/// The PGA point at Euclidean coordinates x (an element of `Algebra.pga(len(x))`).
#[pyfunction]
fn pga_point(x: &Bound<'_, PyAny>) -> PyResult<PyMultivector> {
    let p = pga::Point::new(&numbers(x, "point")?).map_err(value_error)?;
    Ok(element(p.into_multivector()))
}

/// The PGA point at infinity in direction d.
#[pyfunction]
fn pga_ideal_point(d: &Bound<'_, PyAny>) -> PyResult<PyMultivector> {
    let p = pga::Point::ideal(&numbers(d, "direction")?).map_err(value_error)?;
    Ok(element(p.into_multivector()))
}

/// The Euclidean coordinates of a finite PGA point.
#[pyfunction]
fn pga_coordinates<'py>(
    py: Python<'py>,
    point: PyRef<'py, PyMultivector>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let p = pga::Point::from_multivector(point.mv.clone()).map_err(value_error)?;
    Ok(array1(py, p.coordinates().map_err(value_error)?))
}

/// The PGA hyperplane n · x = d.
#[pyfunction]
fn pga_plane(normal: &Bound<'_, PyAny>, d: f64) -> PyResult<PyMultivector> {
    let p = pga::Plane::new(&numbers(normal, "normal")?, d).map_err(value_error)?;
    Ok(element(p.into_multivector()))
}

/// The PGA line through the points at coordinates p and q.
#[pyfunction]
fn pga_line(p: &Bound<'_, PyAny>, q: &Bound<'_, PyAny>) -> PyResult<PyMultivector> {
    let a = pga::Point::new(&numbers(p, "p")?).map_err(value_error)?;
    let b = pga::Point::new(&numbers(q, "q")?).map_err(value_error)?;
    Ok(element(
        pga::Line::through(&a, &b)
            .map_err(value_error)?
            .into_multivector(),
    ))
}

/// The PGA motor of the translation by t.
#[pyfunction]
fn pga_translator(t: &Bound<'_, PyAny>) -> PyResult<PyMultivector> {
    let m = pga::Motor::from_translation(&numbers(t, "translation")?).map_err(value_error)?;
    Ok(element(m.into_multivector()))
}

/// The PGA motor of the rotation by `angle` in the plane of axes i, j (0-based) of ℝⁿ.
#[pyfunction]
fn pga_rotor(n: i64, i: i64, j: i64, angle: f64) -> PyResult<PyMultivector> {
    let m = pga::Motor::from_plane_angle(index(n, "n")?, index(i, "i")?, index(j, "j")?, angle)
        .map_err(value_error)?;
    Ok(element(m.into_multivector()))
}

/// The homogeneous (N + 1) × (N + 1) matrix of a PGA motor (checked to be a motor).
#[pyfunction]
fn pga_motor_matrix<'py>(
    py: Python<'py>,
    motor: PyRef<'py, PyMultivector>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let m = pga::Motor::new(motor.mv.clone()).map_err(value_error)?;
    let h = m.to_matrix();
    let (r, c) = (h.nrows(), h.ncols());
    Ok(
        ArrayD::from_shape_vec(IxDyn(&[r, c]), h.transpose().as_slice().to_vec())
            .expect("the data fills the shape")
            .into_pyarray(py),
    )
}

/// The PGA motor of a homogeneous rigid-motion matrix.
#[pyfunction]
fn pga_motor_from_matrix(matrix: &Bound<'_, PyAny>) -> PyResult<PyMultivector> {
    let array = crate::arrays::f64_array(matrix, "matrix")?;
    let shape = array.shape().to_vec();
    if shape.len() != 2 || shape[0] != shape[1] {
        return Err(value_error(format!(
            "matrix: expected an (N + 1) × (N + 1) array, got shape {shape:?}"
        )));
    }
    let h = DMatrix::from_row_slice(shape[0], shape[1], array.as_slice().expect("contiguous"));
    Ok(element(
        pga::Motor::from_matrix(&h)
            .map_err(value_error)?
            .into_multivector(),
    ))
}

/// The conformal point of x: up(x) = n₀ + x + ½x² n∞ in `Algebra.cga(len(x))`.
#[pyfunction]
fn cga_up(x: &Bound<'_, PyAny>) -> PyResult<PyMultivector> {
    Ok(element(
        cga::up(&numbers(x, "point")?).map_err(value_error)?,
    ))
}

/// The Euclidean coordinates of a conformal point.
#[pyfunction]
fn cga_down<'py>(
    py: Python<'py>,
    point: PyRef<'py, PyMultivector>,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    Ok(array1(py, cga::down(&point.mv).map_err(value_error)?))
}

/// The sphere of centre c and radius r (a conformal vector).
#[pyfunction]
fn cga_sphere(center: &Bound<'_, PyAny>, radius: f64) -> PyResult<PyMultivector> {
    Ok(element(
        cga::sphere(&numbers(center, "center")?, radius).map_err(value_error)?,
    ))
}

/// The hyperplane n · x = d (a conformal vector).
#[pyfunction]
fn cga_plane(normal: &Bound<'_, PyAny>, d: f64) -> PyResult<PyMultivector> {
    Ok(element(
        cga::plane(&numbers(normal, "normal")?, d).map_err(value_error)?,
    ))
}

/// The translator by t.
#[pyfunction]
fn cga_translator(t: &Bound<'_, PyAny>) -> PyResult<PyMultivector> {
    Ok(element(
        cga::translator(&numbers(t, "translation")?).map_err(value_error)?,
    ))
}

/// The dilator by `scale` about the origin of ℝⁿ.
#[pyfunction]
fn cga_dilator(n: i64, scale: f64) -> PyResult<PyMultivector> {
    Ok(element(
        cga::dilator(index(n, "n")?, scale).map_err(value_error)?,
    ))
}

/// The transversor of b.
#[pyfunction]
fn cga_transversor(b: &Bound<'_, PyAny>) -> PyResult<PyMultivector> {
    Ok(element(
        cga::transversor(&numbers(b, "transversion")?).map_err(value_error)?,
    ))
}

/// The boost of rapidity φ along a spatial direction (e2, e3, e4) of the spacetime algebra.
#[pyfunction]
fn sta_boost(rapidity: f64, direction: &Bound<'_, PyAny>) -> PyResult<PyMultivector> {
    Ok(element(
        sta::boost(rapidity, &numbers(direction, "direction")?).map_err(value_error)?,
    ))
}

/// Adds the functions to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(pga_point, m)?)?;
    m.add_function(wrap_pyfunction!(pga_ideal_point, m)?)?;
    m.add_function(wrap_pyfunction!(pga_coordinates, m)?)?;
    m.add_function(wrap_pyfunction!(pga_plane, m)?)?;
    m.add_function(wrap_pyfunction!(pga_line, m)?)?;
    m.add_function(wrap_pyfunction!(pga_translator, m)?)?;
    m.add_function(wrap_pyfunction!(pga_rotor, m)?)?;
    m.add_function(wrap_pyfunction!(pga_motor_matrix, m)?)?;
    m.add_function(wrap_pyfunction!(pga_motor_from_matrix, m)?)?;
    m.add_function(wrap_pyfunction!(cga_up, m)?)?;
    m.add_function(wrap_pyfunction!(cga_down, m)?)?;
    m.add_function(wrap_pyfunction!(cga_sphere, m)?)?;
    m.add_function(wrap_pyfunction!(cga_plane, m)?)?;
    m.add_function(wrap_pyfunction!(cga_translator, m)?)?;
    m.add_function(wrap_pyfunction!(cga_dilator, m)?)?;
    m.add_function(wrap_pyfunction!(cga_transversor, m)?)?;
    m.add_function(wrap_pyfunction!(sta_boost, m)?)?;
    Ok(())
}
