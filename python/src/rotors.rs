//! `Rotor3` and `Rotor4`: one or many fixed-size rotors (the crate's `Rotor3` and `Rotor4`),
//! with the verbs of `scipy.spatial.transform.Rotation` (`from_quat`, `as_matrix`, `apply`,
//! `inv`, `*`, `magnitude`, …) on numpy arrays.

use crate::algebra::PyMultivector;
use crate::arrays::{Rows, all_finite, broadcast, empty, fill, output, value_error};
use numpy::PyArrayDyn;
use pyo3::prelude::*;
use pyo3::types::{PySlice, PySliceMethods};
use rotorflow::algebra::{
    AlgebraError, Bivector3, Bivector4, Matrix3, Matrix4, Multivector, Rotor3, Rotor4, Vector3,
    Vector4,
};

/// What the two fixed-size rotors share, so that one set of batch functions serves both.
pub trait Fixed: Copy + Send + Sync + 'static {
    /// The dimension N (vectors of N components, N × N matrices).
    const N: usize;
    /// The number of bivector components.
    const B: usize;
    fn identity() -> Self;
    /// exp(−Θ/2) of the rotation bivector Θ.
    fn from_bivector(c: &[f64]) -> Self;
    /// The rotation bivector Θ = −2 log R.
    fn bivector(self, out: &mut [f64]);
    fn from_matrix(m: &[f64]) -> Result<Self, AlgebraError>;
    /// The rotation matrix, row-major.
    fn matrix(self, out: &mut [f64]);
    fn rotate(self, v: &[f64], out: &mut [f64]);
    /// `out` = Q v for every vector v of `input` (N entries each), Q the row-major N × N
    /// `matrix`; `false` if an entry of `input` is NaN or infinite.
    fn turn_all(matrix: &[f64], input: &[f64], out: &mut [f64]) -> bool;
    /// `out[i]` = Rᵢ vᵢ R̃ᵢ (or R̃ᵢ vᵢ Rᵢ with `inverse`) for `rotors` and `input` of the same
    /// count, or one vector in `input` for every rotor; `false` if an entry of `input` is NaN
    /// or infinite.
    fn rotate_each(rotors: &[Self], input: &[f64], out: &mut [f64], inverse: bool) -> bool {
        let n = Self::N;
        let step = usize::from(input.len() > n);
        let mut ok = true;
        for (i, (r, o)) in rotors.iter().zip(out.chunks_exact_mut(n)).enumerate() {
            let v = &input[i * step * n..(i * step + 1) * n];
            ok &= all_finite(v);
            let r = if inverse { r.inverse() } else { *r };
            r.rotate(v, o);
        }
        ok
    }
    fn compose(self, other: Self) -> Self;
    fn inverse(self) -> Self;
    fn slerp(self, other: Self, t: f64) -> Self;
    /// |Θ|, the norm of the rotation bivector (the angle of a simple rotation).
    fn magnitude(self) -> f64;
    fn unit_error(self) -> f64;
    fn text(self) -> String;
    fn multivector(self) -> Multivector;
}

/// `Fixed` for one of the crate's fixed-size rotors: the crate's own methods under the
/// trait's names; `$magnitude` is |Θ| of a rotor.
macro_rules! impl_fixed {
    ($rotor:ident, $vector:ident, $matrix:ident, $bivector:ident, $n:literal, $b:literal, $magnitude:expr $(, $own:item)*) => {
        impl Fixed for $rotor {
            $($own)*
            const N: usize = $n;
            const B: usize = $b;
            fn identity() -> Self {
                $rotor::identity()
            }
            fn from_bivector(c: &[f64]) -> Self {
                let c: [f64; $b] = c.try_into().expect("B components, checked by the caller");
                $rotor::from_rotation_bivector($bivector::from_array(c))
            }
            fn bivector(self, out: &mut [f64]) {
                out.copy_from_slice(&self.rotation_bivector().to_array());
            }
            fn from_matrix(m: &[f64]) -> Result<Self, AlgebraError> {
                $rotor::from_matrix(&$matrix::from_row_slice(m))
            }
            fn matrix(self, out: &mut [f64]) {
                out.copy_from_slice(self.to_matrix().transpose().as_slice());
            }
            fn rotate(self, v: &[f64], out: &mut [f64]) {
                let x = self.rotate_vector($vector::from_column_slice(v));
                out.copy_from_slice(x.as_slice());
            }
            fn turn_all(matrix: &[f64], input: &[f64], out: &mut [f64]) -> bool {
                let q: [[f64; $n]; $n] = std::array::from_fn(|i| {
                    std::array::from_fn(|j| matrix[i * $n + j])
                });
                crate::kernels::turn_all::<$n>(&q, input, out)
            }
            fn compose(self, other: Self) -> Self {
                $rotor::compose(self, other)
            }
            fn inverse(self) -> Self {
                $rotor::inverse(self)
            }
            fn slerp(self, other: Self, t: f64) -> Self {
                $rotor::slerp(self, other, t)
            }
            fn magnitude(self) -> f64 {
                let magnitude: fn(Self) -> f64 = $magnitude;
                magnitude(self)
            }
            fn unit_error(self) -> f64 {
                $rotor::unit_error(self)
            }
            fn text(self) -> String {
                self.to_string()
            }
            fn multivector(self) -> Multivector {
                Multivector::from(&self.to_rotor())
            }
        }
    };
}

// In 3D the magnitude is the rotation's angle in [0, π], as scipy's (R and −R alike); in
// 4D the norm of the rotor's own rotation bivector.
impl_fixed!(
    Rotor3,
    Vector3,
    Matrix3,
    Bivector3,
    3,
    3,
    |r| canonical(r).rotation_bivector().norm(),
    fn rotate_each(rotors: &[Self], input: &[f64], out: &mut [f64], inverse: bool) -> bool {
        crate::kernels::rotate_each3(rotors, input, out, inverse)
    }
);
impl_fixed!(
    Rotor4,
    Vector4,
    Matrix4,
    Bivector4,
    4,
    6,
    |r| r.rotation_bivector().norm(),
    fn rotate_each(rotors: &[Self], input: &[f64], out: &mut [f64], inverse: bool) -> bool {
        crate::kernels::rotate_each4(rotors, input, out, inverse)
    }
);

/// Rows per core from which one rotation of many vectors splits them over the cores.
const ROWS_PER_CORE: usize = 1 << 16;

/// [`Fixed::turn_all`] of `input` into `out`, the rows split over the processor's cores when
/// there are at least [`ROWS_PER_CORE`] for each: one matrix times many vectors is bound by
/// memory traffic, which one core does not saturate (scipy's `Rotation.apply` runs it as a
/// BLAS matrix product threaded over the cores). Each row is the same sum in any split.
fn turn_all_on_cores<R: Fixed>(q: &[f64], input: &[f64], out: &mut [f64]) -> bool {
    let n = R::N;
    let rows = out.len() / n;
    if rows < 2 * ROWS_PER_CORE {
        return R::turn_all(q, input, out);
    }
    // Asked once: the answer reads the process's CPU limits, some microseconds.
    static CORES: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
    let cores = *CORES.get_or_init(|| std::thread::available_parallelism().map_or(1, usize::from));
    let parts = cores.min(rows / ROWS_PER_CORE).max(1);
    if parts == 1 || input.len() != out.len() {
        return R::turn_all(q, input, out);
    }
    let per = rows.div_ceil(parts) * n;
    std::thread::scope(|scope| {
        let mut pieces = input.chunks(per).zip(out.chunks_mut(per));
        let (first_in, first_out) = pieces.next().expect("at least one part");
        let others: Vec<_> = pieces
            .map(|(i, o)| scope.spawn(move || R::turn_all(q, i, o)))
            .collect();
        let ok = R::turn_all(q, first_in, first_out);
        others
            .into_iter()
            .fold(ok, |ok, h| ok & h.join().unwrap_or(false))
    })
}

/// One rotor (`single`) or a batch of them.
#[derive(Clone)]
pub struct Batch<R> {
    rotors: Vec<R>,
    single: bool,
}

impl<R: Fixed> Batch<R> {
    fn one(r: R) -> Self {
        Batch {
            rotors: vec![r],
            single: true,
        }
    }

    /// Reads elements of shape `tail`, each turned into a rotor by `f`.
    fn read(
        obj: &Bound<'_, PyAny>,
        tail: &[usize],
        what: &str,
        f: impl Fn(&[f64]) -> Result<R, String>,
    ) -> PyResult<Self> {
        let rows = Rows::new(obj, tail, what)?;
        let width: usize = tail.iter().product();
        let rotors = rows
            .data()
            .chunks_exact(width)
            .enumerate()
            .map(|(i, row)| {
                f(row).map_err(|e| {
                    value_error(if rows.single {
                        format!("{what}: {e}")
                    } else {
                        format!("{what}: element {i}: {e}")
                    })
                })
            })
            .collect::<PyResult<Vec<R>>>()?;
        Ok(Batch {
            rotors,
            single: rows.single,
        })
    }

    /// Writes `width` numbers per rotor into an array of shape `tail` or (M, *tail).
    fn write<'py>(
        &self,
        py: Python<'py>,
        tail: &[usize],
        f: impl Fn(R, &mut [f64]),
    ) -> Bound<'py, PyArrayDyn<f64>> {
        let width: usize = tail.iter().product();
        let mut data = vec![0.0; self.rotors.len() * width];
        for (r, out) in self.rotors.iter().zip(data.chunks_exact_mut(width)) {
            f(*r, out);
        }
        output(py, data, self.rotors.len(), self.single, tail)
    }

    fn shape(&self) -> (usize, bool) {
        (self.rotors.len(), self.single)
    }

    /// Pairs of rotors of two batches (a single rotor broadcast against a batch).
    fn zip_with(&self, other: &Self, what: &str, f: impl Fn(R, R) -> R) -> PyResult<Self> {
        let (m, single) = broadcast(self.shape(), other.shape(), what)?;
        let at = |b: &Self, i: usize| b.rotors[if b.single { 0 } else { i }];
        Ok(Batch {
            rotors: (0..m).map(|i| f(at(self, i), at(other, i))).collect(),
            single,
        })
    }

    fn from_bivector(obj: &Bound<'_, PyAny>) -> PyResult<Self> {
        Self::read(obj, &[R::B], "rotation bivector", |c| {
            Ok(R::from_bivector(c))
        })
    }

    fn from_matrix(obj: &Bound<'_, PyAny>) -> PyResult<Self> {
        Self::read(obj, &[R::N, R::N], "matrix", |m| {
            R::from_matrix(m).map_err(|e| e.to_string())
        })
    }

    fn identity(num: Option<i64>) -> PyResult<Self> {
        match num {
            None => Ok(Self::one(R::identity())),
            Some(n) => {
                let n = usize::try_from(n)
                    .map_err(|_| value_error(format!("num must be >= 0, got {n}")))?;
                Ok(Batch {
                    rotors: vec![R::identity(); n],
                    single: false,
                })
            }
        }
    }

    /// The rotations of `vectors` (shape (N,) or (M, N)), or their inverses.
    fn apply<'py>(
        &self,
        py: Python<'py>,
        vectors: &Bound<'py, PyAny>,
        inverse: bool,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let n = R::N;
        let rows = Rows::unchecked(vectors, &[n], "vectors")?;
        let (m, single) = broadcast(self.shape(), (rows.count, rows.single), "apply")?;
        let input = rows.data();
        let rotors = &self.rotors;
        let out = empty(py, m, single, &[n]);
        let finite = fill(py, &out, |data| {
            let turn = |r: R| if inverse { r.inverse() } else { r };
            if rotors.len() == 1 {
                // One rotor for every vector: through its matrix.
                let mut q = [0.0; 16];
                turn(rotors[0]).matrix(&mut q[..n * n]);
                turn_all_on_cores::<R>(&q[..n * n], input, data)
            } else {
                R::rotate_each(rotors, input, data, inverse)
            }
        })?;
        if !finite {
            rows.check_finite()?;
        }
        Ok(out)
    }

    fn slerp(&self, other: &Self, t: &Bound<'_, PyAny>) -> PyResult<Self> {
        let ts = Rows::new(t, &[], "t")?;
        let ends = self.zip_with(other, "slerp", |a, _| a)?;
        let (m, single) = broadcast(ends.shape(), (ts.count, ts.single), "slerp")?;
        let (ta, tb, tt) = (self.single, other.single, ts.single);
        let times = ts.data();
        Ok(Batch {
            rotors: (0..m)
                .map(|i| {
                    let a = self.rotors[if ta { 0 } else { i }];
                    let b = other.rotors[if tb { 0 } else { i }];
                    a.slerp(b, times[if tt { 0 } else { i }])
                })
                .collect(),
            single,
        })
    }

    fn get(&self, index: &Bound<'_, PyAny>) -> PyResult<Self> {
        if self.single {
            return Err(pyo3::exceptions::PyTypeError::new_err(
                "a single rotor is not subscriptable",
            ));
        }
        let len = self.rotors.len();
        if let Ok(slice) = index.cast::<PySlice>() {
            let idx = slice.indices(len as isize)?;
            let rotors = (0..idx.slicelength)
                .map(|k| self.rotors[(idx.start + k as isize * idx.step) as usize])
                .collect();
            return Ok(Batch {
                rotors,
                single: false,
            });
        }
        let i: isize = index.extract().map_err(|_| {
            pyo3::exceptions::PyTypeError::new_err("rotors are indexed by an integer or a slice")
        })?;
        let j = if i < 0 { i + len as isize } else { i };
        if j < 0 || j as usize >= len {
            return Err(pyo3::exceptions::PyIndexError::new_err(format!(
                "index {i} out of range for {len} rotors"
            )));
        }
        Ok(Self::one(self.rotors[j as usize]))
    }

    fn len(&self) -> PyResult<usize> {
        if self.single {
            return Err(pyo3::exceptions::PyTypeError::new_err(
                "a single rotor has no len()",
            ));
        }
        Ok(self.rotors.len())
    }

    fn repr(&self, name: &str) -> String {
        if self.single {
            format!("{name}({})", self.rotors[0].text())
        } else if self.rotors.len() <= 4 {
            let items: Vec<String> = self.rotors.iter().map(|r| r.text()).collect();
            format!("{name}([{}])", items.join(", "))
        } else {
            format!("{name}(<{} rotors>)", self.rotors.len())
        }
    }

    fn magnitude<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        let data: Vec<f64> = self.rotors.iter().map(|r| r.magnitude()).collect();
        if self.single {
            return data[0].into_pyobject(py).expect("a float").into_any();
        }
        output(py, data, self.rotors.len(), false, &[]).into_any()
    }

    fn multivector(&self) -> PyResult<PyMultivector> {
        if !self.single {
            return Err(value_error(
                "as_multivector takes a single rotor (index the batch first)",
            ));
        }
        Ok(PyMultivector {
            mv: self.rotors[0].multivector(),
        })
    }
}

/// R or −R, whichever has the scalar part ≥ 0: the same rotation, with the rotation angle
/// in [0, π] (scipy's rotation vectors and magnitudes are those of this sign).
fn canonical(r: Rotor3) -> Rotor3 {
    let [w, x, y, z] = r.to_quaternion();
    if w < 0.0 {
        Rotor3::from_quaternion(-w, -x, -y, -z)
    } else {
        r
    }
}

/// Checks a quaternion (w, x, y, z) for length and returns it normalised, as scipy does.
fn unit_quaternion(q: [f64; 4]) -> Result<Rotor3, String> {
    let r = Rotor3::from_quaternion(q[0], q[1], q[2], q[3]);
    let unit = r.normalize();
    if !unit.to_quaternion().iter().all(|c| c.is_finite()) {
        return Err("a zero quaternion is no rotation".into());
    }
    Ok(unit)
}

/// The `#[pymethods]` of a rotor class: its own methods (`$own`) and those that the two
/// classes share through [`Batch`]. PyO3 takes one `#[pymethods]` block per class, hence a
/// macro rather than a second block. The literals are the docstrings that name the shapes.
macro_rules! rotor_methods {
    (
        $class:ident, $rotor:ident, $name:literal,
        bivector: $bivector_doc:literal,
        apply: $apply_doc:literal,
        magnitude: $magnitude_doc:literal,
        multivector: $multivector_doc:literal,
        { $($own:tt)* }
    ) => {
        #[pymethods]
        impl $class {
            $($own)*

            /// The identity, or `num` identities.
            #[staticmethod]
            #[pyo3(signature = (num = None))]
            fn identity(num: Option<i64>) -> PyResult<Self> {
                Ok(Self {
                    batch: Batch::identity(num)?,
                })
            }

            #[doc = $bivector_doc]
            #[staticmethod]
            fn from_bivector(bivector: &Bound<'_, PyAny>) -> PyResult<Self> {
                Ok(Self {
                    batch: Batch::from_bivector(bivector)?,
                })
            }

            /// The rotation bivectors Θ = −2 log R.
            fn as_bivector<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
                self.batch.write(py, &[<$rotor as Fixed>::B], |r, out| r.bivector(out))
            }

            /// From rotation matrices (N, N) or (M, N, N), checked to be rotations.
            #[staticmethod]
            fn from_matrix(matrix: &Bound<'_, PyAny>) -> PyResult<Self> {
                Ok(Self {
                    batch: Batch::from_matrix(matrix)?,
                })
            }

            /// The rotation matrices Q (Q x = R x R̃).
            fn as_matrix<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
                let n = <$rotor as Fixed>::N;
                self.batch.write(py, &[n, n], |r, out| r.matrix(out))
            }

            #[doc = $apply_doc]
            #[pyo3(signature = (vectors, inverse = false))]
            fn apply<'py>(
                &self,
                py: Python<'py>,
                vectors: &Bound<'py, PyAny>,
                inverse: bool,
            ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
                self.batch.apply(py, vectors, inverse)
            }

            /// The inverse rotations.
            fn inv(&self) -> Self {
                let mut batch = self.batch.clone();
                batch.rotors.iter_mut().for_each(|r| *r = r.inverse());
                Self { batch }
            }

            /// The composition `self * other`: `other` first, then `self`.
            fn __mul__(&self, other: PyRef<'_, Self>) -> PyResult<Self> {
                Ok(Self {
                    batch: self
                        .batch
                        .zip_with(&other.batch, "compose", $rotor::compose)?,
                })
            }

            #[doc = $magnitude_doc]
            fn magnitude<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
                self.batch.magnitude(py)
            }

            /// The rotations a fraction `t` of the way from `self` to `other` along the
            /// shorter arc; `t` a number or an array of M, rotors single or M.
            fn slerp(&self, other: PyRef<'_, Self>, t: &Bound<'_, PyAny>) -> PyResult<Self> {
                Ok(Self {
                    batch: self.batch.slerp(&other.batch, t)?,
                })
            }

            /// max |R R̃ − 1| of each rotor.
            fn unit_error<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
                self.batch.write(py, &[], |r, out| out[0] = r.unit_error())
            }

            #[doc = $multivector_doc]
            fn as_multivector(&self) -> PyResult<PyMultivector> {
                self.batch.multivector()
            }

            /// Whether this is one rotor (not a batch).
            #[getter]
            fn single(&self) -> bool {
                self.batch.single
            }

            fn __len__(&self) -> PyResult<usize> {
                self.batch.len()
            }

            fn __getitem__(&self, index: &Bound<'_, PyAny>) -> PyResult<Self> {
                Ok(Self {
                    batch: self.batch.get(index)?,
                })
            }

            fn __repr__(&self) -> String {
                self.batch.repr($name)
            }
        }
    };
}

/// One rotation of 3D space or many: the unit quaternion of the crate's `Rotor3`.
///
/// Verbs of `scipy.spatial.transform.Rotation`: `from_quat`/`as_quat` (scalar last unless
/// `scalar_first=True`), `from_matrix`/`as_matrix`, `from_rotvec`/`as_rotvec`, `apply`,
/// `inv`, `*` (composition: `a * b` applies b first), `magnitude`, and `slerp`.
#[pyclass(name = "Rotor3", module = "rotorflow", frozen)]
#[derive(Clone)]
pub struct PyRotor3 {
    pub batch: Batch<Rotor3>,
}

rotor_methods!(
    PyRotor3,
    Rotor3,
    "Rotor3",
    bivector: "From rotation bivectors Θ (components 12, 13, 23): R = exp(−Θ/2).",
    apply: "The rotated vectors R v R̃ (or R̃ v R with `inverse=True`) of shape (3,) or (M, 3).",
    magnitude: "The rotation angles in [0, π] (a float for a single rotor).",
    multivector: "The rotor as an element of `Algebra(3)`.",
    {
        /// From quaternions (x, y, z, w), or (w, x, y, z) with `scalar_first=True`; normalised.
        #[staticmethod]
        #[pyo3(signature = (quat, scalar_first = false))]
        fn from_quat(quat: &Bound<'_, PyAny>, scalar_first: bool) -> PyResult<Self> {
            let batch = Batch::read(quat, &[4], "quaternion", |q| {
                unit_quaternion(if scalar_first {
                    [q[0], q[1], q[2], q[3]]
                } else {
                    [q[3], q[0], q[1], q[2]]
                })
            })?;
            Ok(Self { batch })
        }

        /// The quaternions (x, y, z, w), or (w, x, y, z) with `scalar_first=True`; with
        /// `canonical=True` the sign with w ≥ 0.
        #[pyo3(signature = (scalar_first = false, canonical = false))]
        fn as_quat<'py>(
            &self,
            py: Python<'py>,
            scalar_first: bool,
            canonical: bool,
        ) -> Bound<'py, PyArrayDyn<f64>> {
            self.batch.write(py, &[4], |r, out| {
                let q = if canonical {
                    self::canonical(r).to_quaternion()
                } else {
                    r.to_quaternion()
                };
                if scalar_first {
                    out.copy_from_slice(&q);
                } else {
                    out.copy_from_slice(&[q[1], q[2], q[3], q[0]]);
                }
            })
        }

        /// From rotation vectors θ â (right-handed about the axis â).
        #[staticmethod]
        fn from_rotvec(rotvec: &Bound<'_, PyAny>) -> PyResult<Self> {
            // The axial vector (x, y, z) is the bivector x e23 + y e31 + z e12.
            let batch = Batch::read(rotvec, &[3], "rotation vector", |v| {
                Ok(Rotor3::from_bivector(&[v[2], -v[1], v[0]]))
            })?;
            Ok(Self { batch })
        }

        /// The rotation vectors θ â, with θ in [0, π] (of R or −R, the same rotation).
        fn as_rotvec<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
            self.batch.write(py, &[3], |r, out| {
                let [b12, b13, b23] = canonical(r).rotation_bivector().to_array();
                out.copy_from_slice(&[b23, -b13, b12]);
            })
        }

        /// The rotation by `angle` about `axis` (right-handed; the axis is normalised).
        #[staticmethod]
        fn from_axis_angle(axis: &Bound<'_, PyAny>, angle: f64) -> PyResult<Self> {
            if !angle.is_finite() {
                return Err(value_error("angle: NaN or infinite value"));
            }
            let batch = Batch::read(axis, &[3], "axis", |a| {
                Rotor3::from_axis_angle(Vector3::new(a[0], a[1], a[2]), angle)
                    .map_err(|e| e.to_string())
            })?;
            Ok(Self { batch })
        }
    }
);

/// One rotation of 4D space or many: the quaternion pair of the crate's `Rotor4`.
#[pyclass(name = "Rotor4", module = "rotorflow", frozen)]
#[derive(Clone)]
pub struct PyRotor4 {
    pub batch: Batch<Rotor4>,
}

/// Checks a quaternion pair for length and returns it with each half normalised.
fn unit_pair(plus: &[f64], minus: &[f64]) -> Result<Rotor4, String> {
    let p = [plus[0], plus[1], plus[2], plus[3]];
    let m = [minus[0], minus[1], minus[2], minus[3]];
    let r = Rotor4::from_quaternion_pair(p, m).normalize();
    let (a, b) = r.to_quaternion_pair();
    if !a.iter().chain(b.iter()).all(|c| c.is_finite()) {
        return Err("a zero quaternion in the pair is no rotation".into());
    }
    Ok(r)
}

rotor_methods!(
    PyRotor4,
    Rotor4,
    "Rotor4",
    bivector: "From rotation bivectors Θ (components 12, 13, 14, 23, 24, 34): R = exp(−Θ/2).",
    apply: "The rotated vectors R v R̃ (or R̃ v R with `inverse=True`) of shape (4,) or (M, 4).",
    magnitude: "The norms |Θ| of the rotation bivectors (a float for a single rotor).",
    multivector: "The rotor as an element of `Algebra(4)`.",
    {
        /// From the quaternion pairs (Q₊, Q₋), each (w, x, y, z); each half normalised.
        #[staticmethod]
        fn from_quaternion_pair(plus: &Bound<'_, PyAny>, minus: &Bound<'_, PyAny>) -> PyResult<Self> {
            let p = Rows::new(plus, &[4], "plus")?;
            let m = Rows::new(minus, &[4], "minus")?;
            if (p.count, p.single) != (m.count, m.single) {
                return Err(value_error(
                    "plus and minus: expected arrays of the same shape",
                ));
            }
            let rotors = p
                .data()
                .chunks_exact(4)
                .zip(m.data().chunks_exact(4))
                .enumerate()
                .map(|(i, (a, b))| {
                    unit_pair(a, b).map_err(|e| value_error(format!("quaternion pair {i}: {e}")))
                })
                .collect::<PyResult<Vec<_>>>()?;
            Ok(Self {
                batch: Batch {
                    rotors,
                    single: p.single,
                },
            })
        }

        /// The quaternion pairs (Q₊, Q₋), two arrays of shape (4,) or (M, 4).
        fn as_quaternion_pair<'py>(
            &self,
            py: Python<'py>,
        ) -> (Bound<'py, PyArrayDyn<f64>>, Bound<'py, PyArrayDyn<f64>>) {
            (
                self.batch.write(py, &[4], |r, out| {
                    out.copy_from_slice(&r.to_quaternion_pair().0)
                }),
                self.batch.write(py, &[4], |r, out| {
                    out.copy_from_slice(&r.to_quaternion_pair().1)
                }),
            )
        }

        /// The rotation by `angle` in the plane of axes i and j (0-based), turning eᵢ toward eⱼ.
        #[staticmethod]
        fn from_plane_angle(i: i64, j: i64, angle: f64) -> PyResult<Self> {
            if !angle.is_finite() {
                return Err(value_error("angle: NaN or infinite value"));
            }
            let index = |k: i64| {
                usize::try_from(k).map_err(|_| value_error(format!("axis index must be >= 0, got {k}")))
            };
            let r = Rotor4::from_plane_angle(index(i)?, index(j)?, angle).map_err(value_error)?;
            Ok(Self {
                batch: Batch::one(r),
            })
        }
    }
);
