//! numpy arrays in and out: shape checks, finiteness checks and errors that name the problem.

use numpy::{IntoPyArray, ndarray::ArrayD, ndarray::IxDyn};
use numpy::{PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::fmt::Display;

/// A `ValueError` with the given one-line message.
pub fn value_error(message: impl Display) -> PyErr {
    PyValueError::new_err(message.to_string())
}

/// Reads `obj` as a C-contiguous float64 array: numpy arrays of that kind as they are,
/// anything else (lists, tuples, numbers, other dtypes, strided views) through
/// `numpy.asarray(obj, dtype="float64", order="C")`, which keeps a number zero-dimensional.
///
/// # Errors
/// `ValueError` naming `what` when numpy cannot make an array of floats of it.
pub fn f64_array<'py>(
    obj: &Bound<'py, PyAny>,
    what: &str,
) -> PyResult<PyReadonlyArrayDyn<'py, f64>> {
    if let Ok(a) = obj.cast::<PyArrayDyn<f64>>()
        && a.is_c_contiguous()
    {
        return a
            .try_readonly()
            .map_err(|e| value_error(format!("{what}: {e}")));
    }
    let np = obj.py().import("numpy")?;
    let kwargs = pyo3::types::PyDict::new(obj.py());
    kwargs.set_item("dtype", "float64")?;
    kwargs.set_item("order", "C")?;
    let converted = np
        .call_method("asarray", (obj,), Some(&kwargs))
        .map_err(|e| value_error(format!("{what}: not an array of numbers ({e})")))?;
    let a = converted
        .cast_into::<PyArrayDyn<f64>>()
        .map_err(|e| value_error(format!("{what}: {e}")))?;
    a.try_readonly()
        .map_err(|e| value_error(format!("{what}: {e}")))
}

/// A batch read from an array of shape `tail` (one element) or `(M, *tail)` (M elements).
pub struct Rows<'py> {
    array: PyReadonlyArrayDyn<'py, f64>,
    /// The number of elements M (1 for a single element).
    pub count: usize,
    /// Whether the array was a single element (shape `tail`).
    pub single: bool,
    what: String,
    width: usize,
}

impl<'py> Rows<'py> {
    /// Reads `obj` as elements of shape `tail`, all of them finite.
    ///
    /// # Errors
    /// `ValueError` naming `what`, the expected shape and the one found, or the first
    /// element with a NaN or infinite entry.
    pub fn new(obj: &Bound<'py, PyAny>, tail: &[usize], what: &str) -> PyResult<Self> {
        let rows = Self::unchecked(obj, tail, what)?;
        rows.check_finite()?;
        Ok(rows)
    }

    /// Reads `obj` as elements of shape `tail` without looking at the entries: for the
    /// kernels that check finiteness on the way (see [`all_finite`]), so that large arrays
    /// are read from memory once; [`Rows::check_finite`] then names the element at fault.
    ///
    /// # Errors
    /// `ValueError` naming `what`, the expected shape and the one found.
    pub fn unchecked(obj: &Bound<'py, PyAny>, tail: &[usize], what: &str) -> PyResult<Self> {
        let array = f64_array(obj, what)?;
        let shape = array.shape().to_vec();
        let single = shape == tail;
        let batch = shape.len() == tail.len() + 1 && shape[1..] == *tail;
        if !single && !batch {
            let tail_text: Vec<String> = tail.iter().map(ToString::to_string).collect();
            return Err(value_error(format!(
                "{what}: expected shape ({}) or (M, {}), got {:?}",
                tail_text.join(", "),
                tail_text.join(", "),
                shape
            )));
        }
        let count = if single { 1 } else { shape[0] };
        Ok(Rows {
            array,
            count,
            single,
            what: what.to_owned(),
            width: tail.iter().product(),
        })
    }

    /// # Errors
    /// `ValueError` naming the first element with a NaN or infinite entry.
    pub fn check_finite(&self) -> PyResult<()> {
        if self.width == 0 || all_finite(self.data()) {
            return Ok(());
        }
        let what = &self.what;
        let bad = self
            .data()
            .chunks_exact(self.width)
            .position(|row| row.iter().any(|x| !x.is_finite()))
            .unwrap_or(0);
        Err(value_error(if self.single {
            format!("{what}: NaN or infinite entry")
        } else {
            format!("{what}: NaN or infinite entry in element {bad}")
        }))
    }

    /// The entries, element after element.
    pub fn data(&self) -> &[f64] {
        self.array
            .as_slice()
            .expect("f64_array returns C-contiguous arrays")
    }
}

/// Whether every entry is finite: one pass that the compiler vectorises.
#[inline(always)]
pub fn all_finite(x: &[f64]) -> bool {
    x.iter().fold(true, |ok, x| ok & x.is_finite())
}

/// The number of elements of two batches taken together: equal counts, or one single
/// element broadcast against the other batch.
///
/// # Errors
/// `ValueError` when both are batches of different lengths.
pub fn broadcast(a: (usize, bool), b: (usize, bool), what: &str) -> PyResult<(usize, bool)> {
    match (a, b) {
        ((_, true), (_, true)) => Ok((1, true)),
        ((_, true), (m, false)) | ((m, false), (_, true)) => Ok((m, false)),
        ((m, false), (k, false)) if m == k => Ok((m, false)),
        ((m, false), (k, false)) => Err(value_error(format!(
            "{what}: batches of different lengths {m} and {k} (give equal lengths or one single element)"
        ))),
    }
}

/// `tail` (when `single`) or `(count, *tail)`: the shape of a batch's output.
fn batch_shape(count: usize, single: bool, tail: &[usize]) -> Vec<usize> {
    let mut shape = Vec::with_capacity(tail.len() + 1);
    if !single {
        shape.push(count);
    }
    shape.extend_from_slice(tail);
    shape
}

/// A new numpy array of zeros of shape `tail` (when `single`) or `(M, *tail)`, to be filled
/// in place: numpy's allocator serves large arrays from huge pages where the system offers
/// them, so that filling a fresh array of millions of entries does not fault page by page.
pub fn zeros<'py>(
    py: Python<'py>,
    count: usize,
    single: bool,
    tail: &[usize],
) -> Bound<'py, PyArrayDyn<f64>> {
    let shape = batch_shape(count, single, tail);
    PyArrayDyn::zeros(py, IxDyn(&shape), false)
}

/// A new numpy array of shape `tail` (when `single`) or `(M, *tail)` whose entries are left
/// unset (numpy's `empty`), for kernels that write every entry: zeroing first would write the
/// whole output once more.
pub fn empty<'py>(
    py: Python<'py>,
    count: usize,
    single: bool,
    tail: &[usize],
) -> Bound<'py, PyArrayDyn<f64>> {
    let shape = batch_shape(count, single, tail);
    // SAFETY: f64 has no invalid bit patterns; every caller writes every entry before the
    // array is returned to Python, and drops it on an error.
    unsafe { PyArrayDyn::new(py, IxDyn(&shape), false) }
}

/// Runs `f` without the GIL on the entries of `array`, a fresh C-contiguous array.
pub fn fill<T: Send>(
    py: Python<'_>,
    array: &Bound<'_, PyArrayDyn<f64>>,
    f: impl FnOnce(&mut [f64]) -> T + Send,
) -> PyResult<T> {
    let mut view = array.try_readwrite().map_err(value_error)?;
    let slice = view.as_slice_mut().map_err(value_error)?;
    Ok(py.detach(|| f(slice)))
}

/// The array of shape `tail` (when `single`) or `(M, *tail)` holding `data`.
pub fn output<'py>(
    py: Python<'py>,
    data: Vec<f64>,
    count: usize,
    single: bool,
    tail: &[usize],
) -> Bound<'py, PyArrayDyn<f64>> {
    let shape = batch_shape(count, single, tail);
    ArrayD::from_shape_vec(IxDyn(&shape), data)
        .expect("the data fills the shape")
        .into_pyarray(py)
}
