//! Bodies (the SPEC grammar and typed constructors), their inertia reports, and their free or
//! torqued rotation: `simulate` and `exact` return what `rotorflow simulate --json` and
//! `rotorflow exact --json` print, key for key, with the numbers as numpy arrays.
//!
//! The blocks of samples and the report in the body's own axes are the crate's
//! (`rotorflow::dynamics::report`), the code the command runs; a test compares the two
//! outputs number for number.

use crate::arrays::value_error;
use numpy::PyUntypedArrayMethods;
use numpy::{IntoPyArray, PyArrayDyn, ndarray::ArrayD, ndarray::IxDyn};
use pyo3::exceptions::{PyFileNotFoundError, PyRuntimeError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use rotorflow::algebra::{Bivector, bivector_len, pairs, plane_name};
use rotorflow::dynamics::report::{
    Report, ReportError, SampleError, State, Stepper, sample_states,
};
use rotorflow::dynamics::torques::{BodyFrame, Free, LinearDamping, SpaceFrame};
use rotorflow::dynamics::trajectory::even_times;
use rotorflow::dynamics::{
    Attitude, Dop853, Dopri5, DynamicsError, Integrator, LiePoissonRk4, Midpoint, MoserVeselov,
    RigidBody, Rkmk4, Splitting, Torque,
};
use rotorflow::inertia::spec::{Geometry, ParsedBody, SpecError, parse_body_with, parse_number};
use rotorflow::inertia::tensor::{ContractedInertia, ContractionNormalization, RankFourTensor};
use rotorflow::inertia::{Body, InertiaMap};
use rotorflow::nalgebra::{DMatrix, DVector};
use rotorflow::viz::Projection;
use rotorflow::viz::Shape;
use rotorflow::viz::html::{Animation, animation_html};
use std::cell::Cell;
use std::convert::Infallible;
use std::path::Path;

/// Adds the bodies' class and functions to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyBody>()?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(exact, m)?)?;
    m.add_function(wrap_pyfunction!(motion_html, m)?)?;
    Ok(())
}

/// Parses a SPEC; a `points:` or `mesh:` file that does not exist is a `FileNotFoundError`.
fn parse(spec: &str) -> PyResult<ParsedBody> {
    let missing = Cell::new(false);
    let read = |path: &Path| {
        std::fs::read_to_string(path).map_err(|err| {
            missing.set(err.kind() == std::io::ErrorKind::NotFound);
            format!("cannot read `{}`: {err}", path.display())
        })
    };
    parse_body_with(spec, &read).map_err(|e: SpecError| {
        if missing.get() {
            PyFileNotFoundError::new_err(e.to_string())
        } else {
            value_error(e)
        }
    })
}

/// The numbers of a SPEC, each as Rust writes an f64 (the shortest text that reads back to
/// the same number), so that a typed constructor and its SPEC give the same body.
fn numbers(values: &[f64], what: &str) -> PyResult<String> {
    if let Some(x) = values.iter().find(|x| !x.is_finite()) {
        return Err(value_error(format!("{what}: {x} is not a finite number")));
    }
    Ok(values
        .iter()
        .map(|x| format!("{x}"))
        .collect::<Vec<_>>()
        .join(","))
}

fn options(mass: Option<f64>, density: Option<f64>) -> PyResult<String> {
    let mut out = String::new();
    if let Some(m) = mass {
        out.push_str(&format!("+mass={}", numbers(&[m], "mass")?));
    }
    if let Some(d) = density {
        out.push_str(&format!("+density={}", numbers(&[d], "density")?));
    }
    Ok(out)
}

/// A one-dimensional list of numbers of any length, all finite.
fn list(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<f64>> {
    let array = crate::arrays::f64_array(obj, what)?;
    if array.ndim() != 1 {
        return Err(value_error(format!(
            "{what}: expected a list of numbers, got shape {:?}",
            array.shape()
        )));
    }
    let v = array.as_slice().expect("contiguous").to_vec();
    if v.iter().any(|x| !x.is_finite()) {
        return Err(value_error(format!("{what}: NaN or infinite entry")));
    }
    Ok(v)
}

/// A rigid body of any dimension: its mass properties (when it is a real body) and its
/// inertia map in its own axes about the centre of mass.
#[pyclass(name = "Body", module = "rotorflow", frozen)]
pub struct PyBody {
    parsed: ParsedBody,
}

impl PyBody {
    fn of_spec(spec: String) -> PyResult<Self> {
        Ok(PyBody {
            parsed: parse(&spec)?,
        })
    }
}

#[pymethods]
impl PyBody {
    /// The body of a SPEC `KIND:ARGS[+mass=M|+density=D]` (`rotorflow help bodies`).
    #[new]
    fn new(spec: &str) -> PyResult<Self> {
        Self::of_spec(spec.to_string())
    }

    /// A solid hyper-cuboid with these half-lengths (`cuboid:a,b,…`).
    #[staticmethod]
    #[pyo3(signature = (half_lengths, *, mass = None, density = None))]
    fn cuboid(
        half_lengths: &Bound<'_, PyAny>,
        mass: Option<f64>,
        density: Option<f64>,
    ) -> PyResult<Self> {
        let a = list(half_lengths, "half_lengths")?;
        Self::of_spec(format!(
            "cuboid:{}{}",
            numbers(&a, "half_lengths")?,
            options(mass, density)?
        ))
    }

    /// A solid ellipsoid with these semi-axes (`ellipsoid:a,b,…`).
    #[staticmethod]
    #[pyo3(signature = (semi_axes, *, mass = None, density = None))]
    fn ellipsoid(
        semi_axes: &Bound<'_, PyAny>,
        mass: Option<f64>,
        density: Option<f64>,
    ) -> PyResult<Self> {
        let a = list(semi_axes, "semi_axes")?;
        Self::of_spec(format!(
            "ellipsoid:{}{}",
            numbers(&a, "semi_axes")?,
            options(mass, density)?
        ))
    }

    /// Unit point masses at the 2^N vertices (±a, ±b, …) (`tesseract:a,b,…`).
    #[staticmethod]
    #[pyo3(signature = (half_edges, *, mass = None))]
    fn tesseract(half_edges: &Bound<'_, PyAny>, mass: Option<f64>) -> PyResult<Self> {
        let a = list(half_edges, "half_edges")?;
        Self::of_spec(format!(
            "tesseract:{}{}",
            numbers(&a, "half_edges")?,
            options(mass, None)?
        ))
    }

    /// Unit point masses at the points of the paper's eq. (73) (`pentachoron:a,b,c,d`).
    #[staticmethod]
    #[pyo3(signature = (a, b, c, d, *, mass = None))]
    fn pentachoron(a: f64, b: f64, c: f64, d: f64, mass: Option<f64>) -> PyResult<Self> {
        Self::of_spec(format!(
            "pentachoron:{}{}",
            numbers(&[a, b, c, d], "pentachoron")?,
            options(mass, None)?
        ))
    }

    /// The regular N-simplex with unit vertex masses and circumradius 1 (`simplex:N`).
    #[staticmethod]
    #[pyo3(signature = (n, *, mass = None))]
    fn simplex(n: i64, mass: Option<f64>) -> PyResult<Self> {
        Self::of_spec(format!("simplex:{n}{}", options(mass, None)?))
    }

    /// A solid N-ball of radius r (`ball:N,R`).
    #[staticmethod]
    #[pyo3(signature = (n, radius, *, mass = None, density = None))]
    fn ball(n: i64, radius: f64, mass: Option<f64>, density: Option<f64>) -> PyResult<Self> {
        Self::of_spec(format!(
            "ball:{n},{}{}",
            numbers(&[radius], "radius")?,
            options(mass, density)?
        ))
    }

    /// A hollow sphere S^(N−1) of radius r (`sphere:N,R`).
    #[staticmethod]
    #[pyo3(signature = (n, radius, *, mass = None, density = None))]
    fn sphere(n: i64, radius: f64, mass: Option<f64>, density: Option<f64>) -> PyResult<Self> {
        Self::of_spec(format!(
            "sphere:{n},{}{}",
            numbers(&[radius], "radius")?,
            options(mass, density)?
        ))
    }

    /// A diagonal mass tensor with these second moments (`principal:J1,…,JN`).
    #[staticmethod]
    #[pyo3(signature = (second_moments, *, mass = None))]
    fn principal(second_moments: &Bound<'_, PyAny>, mass: Option<f64>) -> PyResult<Self> {
        let j = list(second_moments, "second_moments")?;
        Self::of_spec(format!(
            "principal:{}{}",
            numbers(&j, "second_moments")?,
            options(mass, None)?
        ))
    }

    /// A full symmetric mass tensor (an N × N array) in the body's own axes (`tensor:…`).
    #[staticmethod]
    #[pyo3(signature = (mass_tensor, *, mass = None))]
    fn tensor(mass_tensor: &Bound<'_, PyAny>, mass: Option<f64>) -> PyResult<Self> {
        let array = crate::arrays::f64_array(mass_tensor, "mass_tensor")?;
        let shape = array.shape().to_vec();
        if shape.len() != 2 || shape[0] != shape[1] {
            return Err(value_error(format!(
                "mass_tensor: expected an N × N array, got shape {shape:?}"
            )));
        }
        let v = array.as_slice().expect("contiguous").to_vec();
        Self::of_spec(format!(
            "tensor:{}{}",
            numbers(&v, "mass_tensor")?,
            options(mass, None)?
        ))
    }

    /// Any positive plane moments in the order 12, 13, …, 1N, 23, … (`planes:…`): an
    /// inertia map without a body.
    #[staticmethod]
    fn planes(plane_moments: &Bound<'_, PyAny>) -> PyResult<Self> {
        let v = list(plane_moments, "plane_moments")?;
        Self::of_spec(format!("planes:{}", numbers(&v, "plane_moments")?))
    }

    /// Point masses `masses[k]` at `positions[k]` (an (M, N) array), about their centre of
    /// mass.
    #[staticmethod]
    fn points(masses: &Bound<'_, PyAny>, positions: &Bound<'_, PyAny>) -> PyResult<Self> {
        let m = list(masses, "masses")?;
        let array = crate::arrays::f64_array(positions, "positions")?;
        let shape = array.shape().to_vec();
        if shape.len() != 2 || shape[0] != m.len() {
            return Err(value_error(format!(
                "positions: expected shape ({}, N) for {} masses, got {shape:?}",
                m.len(),
                m.len()
            )));
        }
        let n = shape[1];
        let data = array.as_slice().expect("contiguous");
        if data.iter().any(|x| !x.is_finite()) {
            return Err(value_error("positions: NaN or infinite entry"));
        }
        let points: Vec<DVector<f64>> = data
            .chunks_exact(n.max(1))
            .map(DVector::from_row_slice)
            .collect();
        let body = Body::point_masses(&m, &points).map_err(value_error)?;
        let inertia = InertiaMap::from_body(&body).map_err(value_error)?;
        let com = body.center_of_mass().clone();
        let geometry = Geometry::Points(
            points
                .iter()
                .map(|p| (p - &com).iter().copied().collect())
                .collect(),
        );
        Ok(PyBody {
            parsed: ParsedBody {
                spec: format!("points ({} masses in {n}D)", m.len()),
                dim: n,
                mass: body.mass(),
                body: Some(body),
                inertia,
                geometry,
            },
        })
    }

    /// The SPEC (or a description of a body built from arrays).
    #[getter]
    fn spec(&self) -> String {
        self.parsed.spec.clone()
    }

    /// The dimension N.
    #[getter]
    fn dim(&self) -> usize {
        self.parsed.dim
    }

    /// The mass (reported only, for `planes:`).
    #[getter]
    fn mass(&self) -> f64 {
        self.parsed.mass
    }

    /// The plane moments in the body's own axes (order 12, 13, …).
    fn plane_moments<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
        let v = self.parsed.inertia.plane_moments();
        let n = v.len();
        array(py, v, &[n])
    }

    /// L = I(ω) for a body-frame angular velocity ω (bivector components).
    fn momentum<'py>(
        &self,
        py: Python<'py>,
        omega: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let w = bivector_arg(omega, self.parsed.dim, "omega", false)?;
        let l = self.parsed.inertia.try_apply(&w).map_err(value_error)?;
        Ok(array(
            py,
            l.as_slice().to_vec(),
            &[bivector_len(self.parsed.dim)],
        ))
    }

    /// The mass properties, key for key as `rotorflow inertia --json` prints them.
    fn inertia<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        inertia_report(py, &self.parsed)
    }

    fn __repr__(&self) -> String {
        format!("Body({:?})", self.parsed.spec)
    }
}

fn array<'py>(py: Python<'py>, data: Vec<f64>, shape: &[usize]) -> Bound<'py, PyArrayDyn<f64>> {
    ArrayD::from_shape_vec(IxDyn(shape), data)
        .expect("the data fills the shape")
        .into_pyarray(py)
}

fn matrix<'py>(py: Python<'py>, m: &DMatrix<f64>) -> Bound<'py, PyArrayDyn<f64>> {
    array(
        py,
        m.transpose().as_slice().to_vec(),
        &[m.nrows(), m.ncols()],
    )
}

fn vector<'py>(py: Python<'py>, v: &DVector<f64>) -> Bound<'py, PyArrayDyn<f64>> {
    array(py, v.as_slice().to_vec(), &[v.len()])
}

/// The names 12, 13, …, of the planes of dimension n.
fn plane_names(n: usize) -> Vec<String> {
    pairs(n).map(|(i, j)| plane_name(n, i, j)).collect()
}

fn inertia_report<'py>(py: Python<'py>, parsed: &ParsedBody) -> PyResult<Bound<'py, PyDict>> {
    let n = parsed.dim;
    let d = PyDict::new(py);
    let none = py.None();
    d.set_item("dim", n)?;
    d.set_item("spec", &parsed.spec)?;
    d.set_item("plane_names", plane_names(n))?;
    d.set_item("inertia_matrix", matrix(py, &parsed.inertia.to_matrix()))?;
    let Some(body) = &parsed.body else {
        let moments = parsed.inertia.plane_moments();
        d.set_item("mass", parsed.mass)?;
        d.set_item("center_of_mass", array(py, vec![0.0; n], &[n]))?;
        d.set_item(
            "plane_moments",
            array(py, moments.clone(), &[moments.len()]),
        )?;
        d.set_item(
            "principal_plane_moments",
            array(py, moments.clone(), &[moments.len()]),
        )?;
        for key in [
            "volume",
            "mass_tensor",
            "second_moments",
            "principal_moments",
            "principal_axes",
            "moments_of_inertia",
            "rank4",
            "contracted",
            "contracted_factor",
            "gyration_radii",
        ] {
            d.set_item(key, &none)?;
        }
        return Ok(d);
    };
    let j = body.mass_tensor();
    let rank4 = RankFourTensor::from_mass_tensor(j).map_err(value_error)?;
    let normalization = ContractionNormalization::LeviCivita;
    if n >= 3 {
        let ci = ContractedInertia::from_mass_tensor(j, normalization).map_err(value_error)?;
        let radii = ci.gyration_radii(body.mass()).map_err(value_error)?;
        d.set_item("contracted", matrix(py, ci.matrix()))?;
        d.set_item("contracted_factor", normalization.factor(n))?;
        d.set_item("gyration_radii", vector(py, &radii))?;
    } else {
        d.set_item("contracted", &none)?;
        d.set_item("contracted_factor", &none)?;
        d.set_item("gyration_radii", &none)?;
    }
    let (second, axes) = body.principal_frame();
    d.set_item("mass", body.mass())?;
    d.set_item("volume", body.volume())?;
    d.set_item("center_of_mass", vector(py, body.center_of_mass()))?;
    d.set_item("mass_tensor", matrix(py, j))?;
    d.set_item("second_moments", vector(py, &second))?;
    d.set_item("principal_moments", vector(py, &second))?;
    // One principal axis per row: the columns of P with J = P diag(Jᵢ) Pᵀ.
    d.set_item("principal_axes", matrix(py, &axes.transpose()))?;
    d.set_item("plane_moments", vector(py, &body.plane_moments()))?;
    d.set_item(
        "principal_plane_moments",
        vector(py, &body.principal_plane_moments()),
    )?;
    match body.principal_moments_of_inertia_3d() {
        Some(m) => d.set_item("moments_of_inertia", array(py, m.to_vec(), &[3]))?,
        None => d.set_item("moments_of_inertia", &none)?,
    }
    d.set_item(
        "rank4",
        array(py, rank4.components().to_vec(), &[n, n, n, n]),
    )?;
    Ok(d)
}

/// A body argument: a `Body` or a SPEC string.
#[derive(FromPyObject)]
enum BodyArg<'py> {
    Body(PyRef<'py, PyBody>),
    Spec(String),
}

impl BodyArg<'_> {
    fn parsed(&self) -> PyResult<ParsedBody> {
        match self {
            BodyArg::Body(b) => Ok(b.parsed.clone()),
            BodyArg::Spec(s) => parse(s),
        }
    }
}

/// The bivector of an argument given as N(N−1)/2 components, or (N = 3, `axial`) as the
/// axial vector (x, y, z) = x e23 + y e31 + z e12.
fn bivector_arg(obj: &Bound<'_, PyAny>, n: usize, what: &str, axial: bool) -> PyResult<Bivector> {
    let mut v = list(obj, what)?;
    if axial {
        if n != 3 {
            return Err(value_error(format!(
                "axial needs N = 3, the body has N = {n} (give {what} as {} bivector components)",
                bivector_len(n)
            )));
        }
        if v.len() == 3 {
            v = vec![v[2], -v[1], v[0]];
        }
    }
    if v.len() != bivector_len(n) {
        let expected = if axial {
            "3 components x,y,z (axial vector, body's own axes)".to_string()
        } else {
            format!(
                "{} components {} (N = {n}, lexicographic, body's own axes)",
                bivector_len(n),
                plane_names(n).join(",")
            )
        };
        return Err(value_error(format!(
            "{what}: {} components given; expected {expected}",
            v.len()
        )));
    }
    Bivector::from_components(n, &v).map_err(|e| value_error(format!("{what}: {e}")))
}

/// The rigid body at t = 0 in the identity attitude with the given ω or L.
fn initial_body(
    parsed: &ParsedBody,
    omega: Option<&Bound<'_, PyAny>>,
    momentum: Option<&Bound<'_, PyAny>>,
    axial: bool,
) -> PyResult<RigidBody> {
    let n = parsed.dim;
    let (what, value) = match (omega, momentum) {
        (Some(w), None) => ("omega", w),
        (None, Some(l)) => ("momentum", l),
        (Some(_), Some(_)) => return Err(value_error("give omega or momentum, not both")),
        (None, None) => {
            return Err(value_error(
                "give the initial condition: omega=W or momentum=L",
            ));
        }
    };
    let b = bivector_arg(value, n, what, axial)?;
    let inertia = parsed.inertia.clone();
    let body = if what == "omega" {
        RigidBody::from_body_velocity(inertia, Attitude::identity(n), &b)
    } else {
        RigidBody::from_body_momentum(inertia, Attitude::identity(n), &b)
    };
    body.map_err(|e| value_error(format!("body `{}`: {e}", parsed.spec)))
}

/// The sample times: `times`, or `samples` evenly spaced from 0 to `t_end`.
pub fn sample_times(
    times: Option<&Bound<'_, PyAny>>,
    t_end: Option<f64>,
    samples: Option<i64>,
) -> PyResult<Vec<f64>> {
    if let Some(t) = t_end
        && !(t.is_finite() && t > 0.0)
    {
        return Err(value_error(format!(
            "t_end must be positive and finite, got {t}"
        )));
    }
    match (samples, times) {
        (Some(_), Some(_)) => Err(value_error(
            "give samples=K or times=[t1, t2, ...], not both",
        )),
        (Some(k), None) => {
            let t = t_end
                .ok_or_else(|| value_error("samples needs t_end (give t_end=T, samples=K)"))?;
            if !(2..=10_000_000).contains(&k) {
                return Err(value_error(format!(
                    "samples must be between 2 and 10000000, got {k}"
                )));
            }
            Ok(even_times(t, k as usize))
        }
        (None, Some(obj)) => {
            let v = list(obj, "times")?;
            if v.is_empty() {
                return Err(value_error("times: no sample times given"));
            }
            if let Some(t) = v.iter().find(|t| **t < 0.0) {
                return Err(value_error(format!(
                    "times: {t} is negative (expected increasing times >= 0)"
                )));
            }
            if let Some(w) = v.windows(2).find(|w| w[1] <= w[0]) {
                return Err(value_error(format!(
                    "times not increasing: {} then {} (expected strictly increasing times >= 0)",
                    w[0], w[1]
                )));
            }
            if let (Some(end), Some(last)) = (t_end, v.last())
                && *last > end
            {
                return Err(value_error(format!("times: {last} is beyond t_end {end}")));
            }
            Ok(v)
        }
        (None, None) => Err(value_error(
            "give samples=K (with t_end=T) or times=[t1, t2, ...]",
        )),
    }
}

/// How to integrate.
#[derive(Clone, Copy)]
enum Stepping {
    Fixed { kind: &'static str, dt: f64 },
    Dopri5 { rtol: f64, atol: f64 },
    Dop853 { rtol: f64, atol: f64 },
}

/// The integrators by their command-line names (and aliases).
const INTEGRATORS: [&str; 11] = [
    "rk4",
    "lie-poisson-rk4",
    "dopri5",
    "dop853",
    "strang",
    "yoshida4",
    "suzuki4",
    "kahan-li6",
    "kahan-li8",
    "midpoint",
    "moser-veselov",
];

/// The most steps one run may take (as the command).
const MAX_STEPS: f64 = 2e8;

fn stepping(
    name: &str,
    dt: Option<f64>,
    rtol: Option<f64>,
    atol: Option<f64>,
    body: &RigidBody,
    t_end: f64,
) -> PyResult<Stepping> {
    let kind = match name {
        "lp-rk4" => "lie-poisson-rk4",
        "mv" => "moser-veselov",
        other => INTEGRATORS
            .iter()
            .copied()
            .find(|k| *k == other)
            .ok_or_else(|| {
                value_error(format!(
                    "unknown integrator `{other}` (expected one of {})",
                    INTEGRATORS.join(", ")
                ))
            })?,
    };
    for (what, v) in [("dt", dt), ("rtol", rtol), ("atol", atol)] {
        if let Some(x) = v
            && !(x.is_finite() && x > 0.0)
        {
            return Err(value_error(format!(
                "{what} must be positive and finite, got {x}"
            )));
        }
    }
    if kind == "dopri5" || kind == "dop853" {
        if dt.is_some() {
            return Err(value_error(format!(
                "dt applies to the fixed-step integrators; {kind} takes rtol and atol"
            )));
        }
        let rtol = rtol.unwrap_or(1e-10);
        let atol = atol.unwrap_or(1e-12);
        if rtol < 1e-15 {
            return Err(value_error(format!(
                "rtol {rtol} is below what f64 arithmetic can meet (expected rtol >= 1e-15)"
            )));
        }
        return Ok(if kind == "dop853" {
            Stepping::Dop853 { rtol, atol }
        } else {
            Stepping::Dopri5 { rtol, atol }
        });
    }
    if rtol.is_some() || atol.is_some() {
        return Err(value_error(format!(
            "rtol/atol apply to dopri5 and dop853; {kind} takes dt"
        )));
    }
    let dt = dt.unwrap_or_else(|| 0.01 / body.omega().max_abs().max(1.0));
    if t_end / dt > MAX_STEPS {
        return Err(value_error(format!(
            "t_end {t_end} with dt {dt} needs more than {MAX_STEPS:e} steps; raise dt or shorten t_end"
        )));
    }
    Ok(Stepping::Fixed { kind, dt })
}

/// The torque of a spec `none | body:T12,… | space:T12,… | damping:C`.
fn torque(text: Option<&str>, body: &RigidBody, axial: bool) -> PyResult<Box<dyn Torque + Sync>> {
    const FORMS: &str = "none | body:T12,T13,... (constant, body's own axes) | space:T12,T13,... (constant, space frame) | damping:C (tau = -C omega)";
    let n = body.dim();
    let Some(text) = text else {
        return Ok(Box::new(Free));
    };
    let bad = |m: String| value_error(format!("torque `{text}`: {m} (expected {FORMS})"));
    let (kind, args) = text.split_once(':').unwrap_or((text, ""));
    let bivector = |args: &str| -> PyResult<Bivector> {
        let mut v = rotorflow::inertia::spec::parse_list(args).map_err(bad)?;
        if axial {
            if n != 3 {
                return Err(bad(format!("axial needs N = 3, the body has N = {n}")));
            }
            if v.len() == 3 {
                v = vec![v[2], -v[1], v[0]];
            }
        }
        if v.len() != bivector_len(n) {
            return Err(bad(format!(
                "{} components given, N = {n} needs {}",
                v.len(),
                bivector_len(n)
            )));
        }
        Bivector::from_components(n, &v).map_err(|e| bad(e.to_string()))
    };
    match kind.trim() {
        "none" if args.is_empty() => Ok(Box::new(Free)),
        // The integrators work in the principal frame: the body-axes torque is turned in.
        "body" => Ok(Box::new(BodyFrame(
            body.principal_frame()
                .inverse_rotate_bivector(&bivector(args)?),
        ))),
        "space" => Ok(Box::new(SpaceFrame(bivector(args)?))),
        "damping" => {
            let c = parse_number(args).map_err(bad)?;
            if c < 0.0 {
                return Err(bad(format!("the damping must not be negative, got {c}")));
            }
            Ok(Box::new(LinearDamping(c)))
        }
        other => Err(bad(format!("unknown torque `{other}`"))),
    }
}

/// A failure of a run: bad input (`ValueError`) or a failure of the integration.
enum RunError {
    Input(String),
    Runtime(String),
}

impl std::fmt::Display for RunError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RunError::Input(m) | RunError::Runtime(m) => f.write_str(m),
        }
    }
}

impl From<RunError> for PyErr {
    fn from(e: RunError) -> PyErr {
        match e {
            RunError::Input(m) => value_error(m),
            RunError::Runtime(m) => PyRuntimeError::new_err(m),
        }
    }
}

fn fixed_integrator(kind: &str) -> Box<dyn Integrator> {
    match kind {
        "rk4" => Box::new(Rkmk4),
        "lie-poisson-rk4" => Box::new(LiePoissonRk4),
        "strang" => Box::new(Splitting::strang()),
        "yoshida4" => Box::new(Splitting::yoshida4()),
        "suzuki4" => Box::new(Splitting::suzuki4()),
        "kahan-li6" => Box::new(Splitting::kahan_li6()),
        "kahan-li8" => Box::new(Splitting::kahan_li8()),
        "midpoint" => Box::new(Midpoint::default()),
        _ => Box::new(MoserVeselov::new()),
    }
}

/// The crate's report of the states at `times` of the motion that starts as `start` (the
/// command's own code path).
fn report(
    start: &RigidBody,
    times: &[f64],
    states: impl IntoIterator<Item = Result<State, RunError>>,
) -> Result<Report, RunError> {
    Report::from_states(start, times, states).map_err(|e| match e {
        ReportError::State(e) => e,
        other => RunError::Runtime(other.to_string()),
    })
}

/// The report of `body` integrated under `torque` to every time of `times`, through the
/// crate's blocks of samples (as the command).
fn integrate_report(
    body: &RigidBody,
    torque: &dyn Torque,
    stepping: Stepping,
    times: &[f64],
) -> Result<Report, RunError> {
    let fail = |e: DynamicsError| match e {
        DynamicsError::NonPhysicalInertia { .. } | DynamicsError::NoDiscreteSolution { .. } => {
            RunError::Input(format!("integration failed: {e}"))
        }
        _ => RunError::Runtime(format!("integration failed: {e}")),
    };
    let mut stepper = match stepping {
        Stepping::Fixed { kind, dt } => Stepper::Fixed {
            integrator: fixed_integrator(kind),
            dt,
        },
        Stepping::Dopri5 { rtol, atol } => Stepper::Dopri5(Dopri5::new(rtol, atol)),
        Stepping::Dop853 { rtol, atol } => {
            Stepper::Dop853(Box::new(Dop853::new(rtol, atol).map_err(fail)?))
        }
    };
    let mut states = Vec::with_capacity(times.len());
    sample_states(body, torque, &mut stepper, times, &mut |block| {
        states.extend(block);
        Ok::<(), Infallible>(())
    })
    .map_err(|e| match e {
        SampleError::Integration(e) => fail(e),
        SampleError::NotFinite => {
            RunError::Runtime("integration failed: the state is no longer finite; reduce dt".into())
        }
        SampleError::Sink(never) => match never {},
    })?;
    report(body, times, states.into_iter().map(Ok))
}

/// The report as a dict with the keys of the command's JSON, the numbers as arrays.
fn report_dict<'py>(py: Python<'py>, r: &Report) -> PyResult<Bound<'py, PyDict>> {
    let (n, k) = (r.dim, r.times.len());
    let b = bivector_len(n);
    let flat = |v: &[Bivector]| -> Vec<f64> {
        v.iter()
            .flat_map(|x| x.as_slice().iter().copied())
            .collect()
    };
    let d = PyDict::new(py);
    d.set_item("dim", n)?;
    d.set_item("planes", PyList::new(py, r.planes())?)?;
    d.set_item("times", array(py, r.times.clone(), &[k]))?;
    d.set_item("omega", array(py, flat(&r.omega), &[k, b]))?;
    d.set_item("momentum", array(py, flat(&r.momentum), &[k, b]))?;
    d.set_item("energy", array(py, r.energy.clone(), &[k]))?;
    d.set_item("casimirs", array(py, r.casimirs.concat(), &[k, n / 2]))?;
    // Row-major matrices: the transposes' column-major entries.
    let attitude: Vec<f64> = r
        .attitude
        .iter()
        .flat_map(|m| m.transpose().as_slice().to_vec())
        .collect();
    d.set_item("attitude", array(py, attitude, &[k, n, n]))?;
    let drift = PyDict::new(py);
    drift.set_item("energy", r.drift.energy)?;
    drift.set_item("casimirs", r.drift.casimirs)?;
    drift.set_item(
        "manakov",
        array(py, r.manakov_drift.clone(), &[r.manakov_drift.len()]),
    )?;
    drift.set_item("space_momentum", r.drift.space_momentum)?;
    d.set_item("drift", drift)?;
    Ok(d)
}

/// Integrates the rotation of a body and returns the keys of `rotorflow simulate --json`:
/// dim, planes, times, omega, momentum, energy, casimirs, attitude and drift.
#[pyfunction]
#[pyo3(signature = (body, *, omega = None, momentum = None, times = None, t_end = None, samples = None, integrator = "rk4", dt = None, rtol = None, atol = None, torque = None, axial = false))]
#[allow(clippy::too_many_arguments)]
fn simulate<'py>(
    py: Python<'py>,
    body: BodyArg<'py>,
    omega: Option<&Bound<'py, PyAny>>,
    momentum: Option<&Bound<'py, PyAny>>,
    times: Option<&Bound<'py, PyAny>>,
    t_end: Option<f64>,
    samples: Option<i64>,
    integrator: &str,
    dt: Option<f64>,
    rtol: Option<f64>,
    atol: Option<f64>,
    torque: Option<&str>,
    axial: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let parsed = body.parsed()?;
    let start = initial_body(&parsed, omega, momentum, axial)?;
    let times = sample_times(times, t_end, samples)?;
    let torque = self::torque(torque, &start, axial)?;
    let end = times.last().copied().unwrap_or(0.0);
    let stepping = stepping(integrator, dt, rtol, atol, &start, end)?;
    let result = py.detach(|| integrate_report(&start, torque.as_ref(), stepping, &times))?;
    report_dict(py, &result)
}

/// The closed-form motion of a body, with the keys of `rotorflow exact --json` (those of
/// `simulate`); a `ValueError` says why a body has none.
#[pyfunction]
#[pyo3(signature = (body, *, omega = None, momentum = None, times = None, t_end = None, samples = None, axial = false))]
#[allow(clippy::too_many_arguments)]
fn exact<'py>(
    py: Python<'py>,
    body: BodyArg<'py>,
    omega: Option<&Bound<'py, PyAny>>,
    momentum: Option<&Bound<'py, PyAny>>,
    times: Option<&Bound<'py, PyAny>>,
    t_end: Option<f64>,
    samples: Option<i64>,
    axial: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let parsed = body.parsed()?;
    let start = initial_body(&parsed, omega, momentum, axial)?;
    let times = sample_times(times, t_end, samples)?;
    let solution = start.exact_solution().map_err(|e| match e {
        DynamicsError::NoClosedForm { reasons } => {
            let why: Vec<String> = reasons.iter().map(ToString::to_string).collect();
            value_error(format!(
                "no closed-form solution for this body: {}",
                why.join("; ")
            ))
        }
        e => value_error(format!("no closed-form solution for this body: {e}")),
    })?;
    let result = py.detach(|| {
        let states = times.iter().map(|&t| {
            let fail = |e: DynamicsError| RunError::Runtime(format!("closed form at t = {t}: {e}"));
            Ok((
                solution.attitude_at(t).map_err(fail)?,
                solution.momentum_at(t).map_err(fail)?,
            ))
        });
        report(&start, &times, states)
    })?;
    report_dict(py, &result)
}

/// The crate's self-contained HTML animation (`rotorflow::viz::html`, the page of
/// `rotorflow render --output FILE.html`) of `body` turning through `attitude` (K rotation
/// matrices, body's own axes → space, row-major as in the reports) at `times`.
#[pyfunction]
#[pyo3(signature = (body, times, attitude, *, title = None))]
fn motion_html(
    body: BodyArg<'_>,
    times: &Bound<'_, PyAny>,
    attitude: &Bound<'_, PyAny>,
    title: Option<&str>,
) -> PyResult<String> {
    let parsed = body.parsed()?;
    let n = parsed.dim;
    let times = list(times, "times")?;
    let rows = crate::arrays::Rows::new(attitude, &[n, n], "attitude")?;
    if rows.count != times.len() || rows.single {
        return Err(value_error(format!(
            "attitude: expected {} matrices of {n} × {n} (one per time), got {}",
            times.len(),
            if rows.single { 1 } else { rows.count }
        )));
    }
    let mut shape = Shape::of_body(&parsed);
    let mut matrices: Vec<DMatrix<f64>> = rows
        .data()
        .chunks_exact(n * n)
        .map(|m| DMatrix::from_row_slice(n, n, m))
        .collect();
    if n < 3 {
        // A body of fewer than three dimensions is drawn in the first axes of 3D space.
        shape.points = shape
            .points
            .iter()
            .map(|p| {
                let mut q = p.clone();
                q.resize(3, 0.0);
                q
            })
            .collect();
        shape.dim = 3;
        matrices = matrices
            .iter()
            .map(|m| {
                let mut e = DMatrix::identity(3, 3);
                e.view_mut((0, 0), (n, n)).copy_from(m);
                e
            })
            .collect();
    }
    Ok(animation_html(&Animation {
        title: title.unwrap_or(&parsed.spec),
        shape: &shape,
        times: &times,
        matrices: &matrices,
        axes: [0, 1, 2],
        projection: Projection::Perspective,
    }))
}
