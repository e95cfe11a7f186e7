//! `Algebra` and `Multivector`: the crate's `Signature` and `Multivector` with Python
//! operators, and the batched products, sandwiches, exponentials and logarithms on arrays of
//! coefficients.

use crate::arrays::{Rows, all_finite, broadcast, empty, fill, output, value_error, zeros};
use crate::kernels::{DenseSigns, dense_product, product8, product16};
use numpy::PyArrayDyn;
use pyo3::exceptions::{PyTypeError, PyZeroDivisionError};
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use rotorflow::algebra::{
    AlgebraError, MULTIVECTOR_MAX_DIM, Multivector, PRODUCT_TABLE_MAX_DIM, Product, ProductTable,
    Signature, Versor, cga, sta,
};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, PoisonError};

/// The product tables made so far, by signature and product (`None`: the inner product).
type TableKey = (usize, usize, usize, Option<Product>);
static TABLES: Mutex<Option<HashMap<TableKey, Arc<Table>>>> = Mutex::new(None);

/// A product table, and its signs for the products of 8 or 16 coefficients that send each
/// pair of blades to one blade.
struct Table {
    table: ProductTable,
    signs8: Option<DenseSigns<8>>,
    signs16: Option<DenseSigns<16>>,
}

impl Table {
    fn new(table: ProductTable) -> Self {
        let product = |a: &[f64], b: &[f64], out: &mut [f64]| {
            table.apply(a, b, out).expect("blades of the table's size");
        };
        let size = 1usize << table.signature().dim();
        let signs8 = (size == 8).then(|| DenseSigns::new(product)).flatten();
        let signs16 = (size == 16).then(|| DenseSigns::new(product)).flatten();
        Table {
            table,
            signs8,
            signs16,
        }
    }
}

/// The table of `kind` in `sig` (made once), or `None` above [`PRODUCT_TABLE_MAX_DIM`].
fn table(sig: Signature, kind: Option<Product>) -> Option<Arc<Table>> {
    if sig.dim() > PRODUCT_TABLE_MAX_DIM {
        return None;
    }
    let key = (sig.p(), sig.q(), sig.r(), kind);
    let mut tables = TABLES.lock().unwrap_or_else(PoisonError::into_inner);
    let tables = tables.get_or_insert_with(HashMap::new);
    if let Some(t) = tables.get(&key) {
        return Some(t.clone());
    }
    let t = Arc::new(Table::new(match kind {
        Some(kind) => ProductTable::new(sig, kind).ok()?,
        None => ProductTable::inner(sig).ok()?,
    }));
    tables.insert(key, t.clone());
    Some(t)
}

/// The two batched operations of a product table.
#[derive(Clone, Copy)]
enum Batch {
    /// a ∘ b.
    Product,
    /// (a ∘ b) ∘ ã.
    Sandwich,
}

/// Elements per chunk of a batch: a chunk's operands, checked for finiteness, are still in the
/// first-level cache when the kernel reads them, so that each array is read from memory once.
const CHUNK: usize = 64;

/// The batch chunk by chunk, each chunk's operands checked for finiteness (by the AVX-512
/// dense kernels as they load them, else before the chunk); `false` (and `out` partly
/// written) at the first chunk with a NaN or an infinity. `a` and `b` hold M
/// elements of 2ᴺ coefficients, or one element used with every element of the other.
/// Products of 8 and 16 coefficients that send each pair of blades to one blade run through
/// [`dense_product`] (and its AVX-512 form), the others and the sandwiches through the
/// crate's kernels of `t`: the same terms in the same order as the table's list, so the same
/// results to the last bit (up to the sign of a zero).
///
/// On processors with AVX-512 or AVX2 the same code runs compiled for them: the same
/// additions and multiplications in the same order (no fused multiply-add), eight or four
/// lanes at a time instead of two, so the same results bit for bit.
fn batch(
    t: &Table,
    a: &[f64],
    b: &[f64],
    out: &mut [f64],
    op: Batch,
) -> Result<bool, AlgebraError> {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx512f") {
            // SAFETY: the processor supports AVX-512F, the only requirement of `batch_avx512`.
            return unsafe { batch_avx512(t, a, b, out, op) };
        }
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor supports AVX2, the only requirement of `batch_avx2`.
            return unsafe { batch_avx2(t, a, b, out, op) };
        }
    }
    batch_portable(t, a, b, out, op)
}

#[inline(always)]
fn batch_portable(
    t: &Table,
    a: &[f64],
    b: &[f64],
    out: &mut [f64],
    op: Batch,
) -> Result<bool, AlgebraError> {
    let k = 1usize << t.table.signature().dim();
    let step = CHUNK * k;
    // A single element is repeated over one chunk, and checked once.
    let m = out.len() / k;
    let repeat = |d: &[f64]| (d.len() == k).then(|| d.repeat(CHUNK.min(m)));
    let (rep_a, rep_b) = (repeat(a), repeat(b));
    if (rep_a.is_some() && !all_finite(a)) || (rep_b.is_some() && !all_finite(b)) {
        return Ok(false);
    }
    for (c, co) in out.chunks_mut(step).enumerate() {
        let n = co.len();
        let ca = rep_a
            .as_deref()
            .map_or_else(|| &a[c * step..c * step + n], |r| &r[..n]);
        let cb = rep_b
            .as_deref()
            .map_or_else(|| &b[c * step..c * step + n], |r| &r[..n]);
        // The dense kernels check their operands as they load them (with AVX-512), so that
        // each chunk is read from memory by the kernel alone; the others are checked first.
        let dense = match (op, &t.signs8, &t.signs16) {
            (Batch::Product, Some(d), _) => product8(d, ca, cb, co),
            (Batch::Product, _, Some(d)) => product16(d, ca, cb, co),
            _ => None,
        };
        let checked = match dense {
            Some(finite) => finite,
            None => (rep_a.is_some() || all_finite(ca)) & (rep_b.is_some() || all_finite(cb)),
        };
        if !checked {
            return Ok(false);
        }
        if dense.is_none() {
            match (op, &t.signs8, &t.signs16) {
                (Batch::Product, Some(d), _) => dense_product(d, ca, cb, co),
                (Batch::Product, _, Some(d)) => dense_product(d, ca, cb, co),
                (Batch::Product, ..) => t.table.apply_batch(ca, cb, co)?,
                (Batch::Sandwich, ..) => t.table.sandwich_batch(ca, cb, co)?,
            }
        }
    }
    Ok(true)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn batch_avx2(
    t: &Table,
    a: &[f64],
    b: &[f64],
    out: &mut [f64],
    op: Batch,
) -> Result<bool, AlgebraError> {
    batch_portable(t, a, b, out, op)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
fn batch_avx512(
    t: &Table,
    a: &[f64],
    b: &[f64],
    out: &mut [f64],
    op: Batch,
) -> Result<bool, AlgebraError> {
    batch_portable(t, a, b, out, op)
}

/// A Clifford algebra Cl(p, q, r): p basis vectors square to +1, then q to −1, then r to 0.
#[pyclass(name = "Algebra", module = "rotorflow", frozen, eq, hash)]
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct PyAlgebra {
    pub sig: Signature,
}

/// Reads a non-negative integer (a Python int that may be negative, so that a negative one is
/// a `ValueError` rather than an `OverflowError`).
fn count(value: i64, what: &str) -> PyResult<usize> {
    usize::try_from(value).map_err(|_| value_error(format!("{what} must be >= 0, got {value}")))
}

fn algebra_error(e: AlgebraError) -> PyErr {
    value_error(e)
}

impl PyAlgebra {
    /// The algebra of `sig`, refused when its multivectors cannot be stored densely.
    pub fn checked(sig: Signature) -> PyResult<Self> {
        if sig.dim() > MULTIVECTOR_MAX_DIM {
            return Err(algebra_error(AlgebraError::DimensionTooLarge {
                what: "multivector",
                dim: sig.dim(),
                max: MULTIVECTOR_MAX_DIM,
            }));
        }
        Ok(PyAlgebra { sig })
    }

    fn size(&self) -> usize {
        1 << self.sig.dim()
    }

    fn wrap(&self, mv: Multivector) -> PyMultivector {
        PyMultivector { mv }
    }
}

/// The products of [`PyAlgebra::product`] by name.
fn product_kind(name: &str) -> PyResult<Option<Product>> {
    Ok(Some(match name {
        "geometric" => Product::Geometric,
        "outer" | "wedge" => Product::Wedge,
        "left_contraction" => Product::LeftContraction,
        "right_contraction" => Product::RightContraction,
        "scalar" => Product::Scalar,
        "commutator" => Product::Commutator,
        "anticommutator" => Product::Anticommutator,
        "regressive" => Product::Regressive,
        "inner" => return Ok(None),
        other => {
            return Err(value_error(format!(
                "unknown product `{other}` (expected geometric, outer, inner, left_contraction, right_contraction, scalar, commutator, anticommutator or regressive)"
            )));
        }
    }))
}

/// One product of two elements of the same algebra; `None` is the inner product.
fn apply_product(a: &Multivector, b: &Multivector, kind: Option<Product>) -> Multivector {
    match kind {
        Some(kind) => a
            .try_product(b, kind)
            .expect("operands of one algebra, checked by the caller"),
        None => a.inner(b),
    }
}

impl PyAlgebra {
    /// One operation on two batches of elements (arrays of shape (M, 2^N) or (2^N,); a single
    /// element is used with every element of the other): through the product table of
    /// `table_kind` where there is one (`op`), else element by element with `each`.
    fn pairwise<'py>(
        &self,
        py: Python<'py>,
        (a, name_a): (&Bound<'py, PyAny>, &str),
        (b, name_b): (&Bound<'py, PyAny>, &str),
        (what, table_kind, op): (&str, Option<Product>, Batch),
        each: impl Fn(&Multivector, &Multivector) -> Result<Multivector, AlgebraError> + Send + Sync,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let k = self.size();
        let ra = Rows::unchecked(a, &[k], name_a)?;
        let rb = Rows::unchecked(b, &[k], name_b)?;
        let (m, single) = broadcast((ra.count, ra.single), (rb.count, rb.single), what)?;
        let sig = self.sig;
        let (da, db) = (ra.data(), rb.data());
        let out = empty(py, m, single, &[k]);
        match table(sig, table_kind) {
            Some(t) => {
                let finite =
                    fill(py, &out, |dest| batch(&t, da, db, dest, op))?.map_err(value_error)?;
                if !finite {
                    ra.check_finite()?;
                    rb.check_finite()?;
                }
            }
            None => {
                ra.check_finite()?;
                rb.check_finite()?;
                fill(py, &out, |dest| map_pairs(sig, da, db, m, dest, each))??;
            }
        }
        Ok(out)
    }
}

#[pymethods]
impl PyAlgebra {
    /// Cl(p, q, r).
    #[new]
    #[pyo3(signature = (p, q = 0, r = 0))]
    fn new(p: i64, q: i64, r: i64) -> PyResult<Self> {
        let sig = Signature::new(count(p, "p")?, count(q, "q")?, count(r, "r")?)
            .map_err(algebra_error)?;
        Self::checked(sig)
    }

    /// Euclidean space ℝⁿ: Cl(n, 0, 0).
    #[staticmethod]
    fn euclidean(n: i64) -> PyResult<Self> {
        Self::new(n, 0, 0)
    }

    /// Projective GA of ℝⁿ: Cl(n, 0, 1), the null vector last.
    #[staticmethod]
    fn pga(n: i64) -> PyResult<Self> {
        Self::new(n, 0, 1)
    }

    /// Conformal GA of ℝⁿ: Cl(n + 1, 1, 0).
    #[staticmethod]
    fn cga(n: i64) -> PyResult<Self> {
        Self::checked(cga::conformal(count(n, "n")?).map_err(algebra_error)?)
    }

    /// The spacetime algebra Cl(1, 3): e1 time, e2 e3 e4 space.
    #[staticmethod]
    fn spacetime() -> PyResult<Self> {
        Self::checked(sta::spacetime())
    }

    /// The number of basis vectors that square to +1.
    #[getter]
    fn p(&self) -> usize {
        self.sig.p()
    }

    /// The number of basis vectors that square to −1.
    #[getter]
    fn q(&self) -> usize {
        self.sig.q()
    }

    /// The number of basis vectors that square to 0.
    #[getter]
    fn r(&self) -> usize {
        self.sig.r()
    }

    /// N = p + q + r.
    #[getter]
    fn dim(&self) -> usize {
        self.sig.dim()
    }

    /// 2^N, the number of coefficients of a multivector.
    fn __len__(&self) -> usize {
        self.size()
    }

    fn __repr__(&self) -> String {
        format!(
            "Algebra({}, {}, {})",
            self.sig.p(),
            self.sig.q(),
            self.sig.r()
        )
    }

    fn __str__(&self) -> String {
        self.sig.to_string()
    }

    fn __getnewargs__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        PyTuple::new(py, [self.sig.p(), self.sig.q(), self.sig.r()])
    }

    /// The multivector with the given 2^N coefficients, indexed by blade bit mask.
    fn multivector(&self, coefficients: &Bound<'_, PyAny>) -> PyResult<PyMultivector> {
        let rows = Rows::new(coefficients, &[self.size()], "coefficients")?;
        if !rows.single {
            return Err(value_error(format!(
                "coefficients: expected {} numbers, got an array of {} rows (use the batch functions for many)",
                self.size(),
                rows.count
            )));
        }
        Ok(
            self.wrap(
                Multivector::from_coefficients(self.sig, rows.data()).map_err(algebra_error)?,
            ),
        )
    }

    /// The scalar s.
    #[pyo3(signature = (s = 1.0))]
    fn scalar(&self, s: f64) -> PyResult<PyMultivector> {
        if !s.is_finite() {
            return Err(value_error("scalar: NaN or infinite value"));
        }
        Ok(self.wrap(Multivector::try_scalar(self.sig, s).map_err(algebra_error)?))
    }

    /// The vector Σ cᵢ eᵢ from its N components.
    fn vector(&self, components: &Bound<'_, PyAny>) -> PyResult<PyMultivector> {
        let rows = Rows::new(components, &[self.sig.dim()], "vector components")?;
        Ok(self.wrap(Multivector::vector(self.sig, rows.data()).map_err(algebra_error)?))
    }

    /// The bivector Σ cᵢⱼ eᵢⱼ from its N(N − 1)/2 components in the order e12, e13, …, e23, …
    fn bivector(&self, components: &Bound<'_, PyAny>) -> PyResult<PyMultivector> {
        let n = self.sig.dim();
        let rows = Rows::new(
            components,
            &[n * n.saturating_sub(1) / 2],
            "bivector components",
        )?;
        Ok(self.wrap(Multivector::bivector(self.sig, rows.data()).map_err(algebra_error)?))
    }

    /// `coefficient` times the basis blade named `name` ("1", "e13", "e1e3", "e₁₃"; "e31"
    /// is −e13).
    #[pyo3(signature = (name, coefficient = 1.0))]
    fn blade(&self, name: &str, coefficient: f64) -> PyResult<PyMultivector> {
        Ok(self
            .wrap(Multivector::blade_by_name(self.sig, name, coefficient).map_err(algebra_error)?))
    }

    /// The basis blade with bit mask `mask` (bit i − 1 set for eᵢ).
    fn basis_blade(&self, mask: i64) -> PyResult<PyMultivector> {
        let mask = u64::try_from(mask)
            .map_err(|_| value_error(format!("blade mask must be >= 0, got {mask}")))?;
        Ok(self.wrap(Multivector::try_basis_blade(self.sig, mask).map_err(algebra_error)?))
    }

    /// Blades as attributes: `alg.e12` is `alg.blade("e12")`; any other name is an
    /// `AttributeError` (so that `hasattr` and tools that probe attributes keep working).
    fn __getattr__(&self, name: &str) -> PyResult<PyMultivector> {
        let missing = |why: String| {
            pyo3::exceptions::PyAttributeError::new_err(format!(
                "'Algebra' object has no attribute '{name}'{why}"
            ))
        };
        if !name.starts_with('e') || name.len() < 2 {
            return Err(missing(String::new()));
        }
        Multivector::blade_by_name(self.sig, name, 1.0)
            .map(|mv| self.wrap(mv))
            .map_err(|e| missing(format!(" ({e})")))
    }

    // ---- batches: arrays of shape (M, 2^N) -------------------------------------------------

    /// The product of two batches of multivectors (arrays of shape (M, 2^N) or (2^N,); a
    /// single element is used with every element of the other).
    #[pyo3(signature = (a, b, kind = "geometric"))]
    fn product<'py>(
        &self,
        py: Python<'py>,
        a: &Bound<'py, PyAny>,
        b: &Bound<'py, PyAny>,
        kind: &str,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let kind = product_kind(kind)?;
        self.pairwise(
            py,
            (a, "a"),
            (b, "b"),
            ("product", kind, Batch::Product),
            |x, y| Ok(apply_product(x, y, kind)),
        )
    }

    /// The sandwiches V X Ṽ of a batch of even versors V with a batch of elements X.
    fn sandwich<'py>(
        &self,
        py: Python<'py>,
        versors: &Bound<'py, PyAny>,
        x: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        // V X Ṽ as the multivector's sandwich computes it: (V X) Ṽ.
        self.pairwise(
            py,
            (versors, "versors"),
            (x, "x"),
            ("sandwich", Some(Product::Geometric), Batch::Sandwich),
            |v, x| v.apply(x),
        )
    }

    /// exp(B) of every bivector of a batch (shape (M, 2^N)), in closed form.
    fn exp<'py>(
        &self,
        py: Python<'py>,
        bivectors: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        self.map_batch(py, bivectors, "bivectors", Multivector::exp_to)
    }

    /// log(V) of every even versor of a batch (shape (M, 2^N)).
    fn log<'py>(
        &self,
        py: Python<'py>,
        versors: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        self.map_batch(py, versors, "versors", Multivector::log_to)
    }

    /// The reverse of every element of a batch.
    fn reverse<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        self.map_batch(py, x, "x", |m, out| {
            *out = m.reverse();
            Ok(())
        })
    }
}

impl PyAlgebra {
    /// Applies `f` (writing into a reused element) to every element of a batch.
    fn map_batch<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
        what: &str,
        f: impl Fn(&Multivector, &mut Multivector) -> Result<(), AlgebraError> + Send + Sync,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let k = self.size();
        let rows = Rows::new(x, &[k], what)?;
        let sig = self.sig;
        let input = rows.data();
        let count = rows.count;
        let out = zeros(py, count, rows.single, &[k]);
        fill(py, &out, |data| -> Result<(), String> {
            let mut element = Multivector::zero(sig);
            let mut result = Multivector::zero(sig);
            for (i, (row, dest)) in input
                .chunks_exact(k)
                .zip(data.chunks_exact_mut(k))
                .enumerate()
            {
                element.as_mut_slice().copy_from_slice(row);
                f(&element, &mut result).map_err(|e| element_error(i, count, e))?;
                dest.copy_from_slice(result.as_slice());
            }
            Ok(())
        })?
        .map_err(value_error)?;
        Ok(out)
    }
}

/// The message of an error at element `i` of a batch of `count`.
fn element_error(i: usize, count: usize, e: AlgebraError) -> String {
    if count == 1 {
        e.to_string()
    } else {
        format!("element {i}: {e}")
    }
}

/// `f` of the pairs of a batch of `m` (rows of a single-element side repeat), into `out`.
fn map_pairs(
    sig: Signature,
    a: &[f64],
    b: &[f64],
    m: usize,
    out: &mut [f64],
    f: impl Fn(&Multivector, &Multivector) -> Result<Multivector, AlgebraError>,
) -> PyResult<()> {
    let k = 1usize << sig.dim();
    let mut x = Multivector::zero(sig);
    let mut y = Multivector::zero(sig);
    let (step_a, step_b) = (usize::from(a.len() > k), usize::from(b.len() > k));
    for (i, dest) in out.chunks_exact_mut(k).enumerate() {
        x.as_mut_slice()
            .copy_from_slice(&a[i * step_a * k..(i * step_a + 1) * k]);
        y.as_mut_slice()
            .copy_from_slice(&b[i * step_b * k..(i * step_b + 1) * k]);
        let z = f(&x, &y).map_err(|e| value_error(element_error(i, m, e)))?;
        dest.copy_from_slice(z.as_slice());
    }
    Ok(())
}

/// An element of a Clifford algebra: 2^N coefficients indexed by blade bit mask.
#[pyclass(name = "Multivector", module = "rotorflow", frozen)]
#[derive(Clone)]
pub struct PyMultivector {
    pub mv: Multivector,
}

/// The right operand of an arithmetic operator: a multivector or a real number.
#[derive(FromPyObject)]
pub enum Operand<'py> {
    Element(PyRef<'py, PyMultivector>),
    Number(f64),
}

impl PyMultivector {
    fn same_algebra<'a>(&self, other: &'a Multivector) -> PyResult<&'a Multivector> {
        if self.mv.signature() != other.signature() {
            return Err(algebra_error(AlgebraError::SignatureMismatch {
                left: self.mv.signature(),
                right: other.signature(),
            }));
        }
        Ok(other)
    }

    fn wrap(mv: Multivector) -> PyResult<Self> {
        Ok(PyMultivector { mv })
    }

    fn scalar(&self, s: f64) -> PyResult<Multivector> {
        if !s.is_finite() {
            return Err(value_error("scalar operand: NaN or infinite value"));
        }
        Ok(Multivector::scalar(self.mv.signature(), s))
    }

    fn operand(&self, other: &Operand<'_>) -> PyResult<Multivector> {
        match other {
            Operand::Element(m) => Ok(self.same_algebra(&m.mv)?.clone()),
            Operand::Number(s) => self.scalar(*s),
        }
    }

    fn product(&self, other: &Operand<'_>, kind: Option<Product>) -> PyResult<Self> {
        let b = self.operand(other)?;
        Self::wrap(apply_product(&self.mv, &b, kind))
    }

    fn rproduct(&self, other: f64, kind: Option<Product>) -> PyResult<Self> {
        let a = self.scalar(other)?;
        Self::wrap(apply_product(&a, &self.mv, kind))
    }

    fn algebra(&self) -> PyAlgebra {
        PyAlgebra {
            sig: self.mv.signature(),
        }
    }

    /// The LaTeX of the element: `1 + 2 e_{12} - 0.5 e_{123}` (terms in the order of `str`).
    fn latex(&self) -> String {
        let n = self.mv.dim();
        let mut terms: Vec<(u64, f64)> = self.mv.terms().collect();
        let indices = |mask: u64| -> Vec<usize> {
            (0..n)
                .filter(|i| mask >> i & 1 == 1)
                .map(|i| i + 1)
                .collect()
        };
        terms.sort_by_key(|&(mask, _)| (mask.count_ones(), indices(mask)));
        let mut out = String::new();
        for (k, (mask, c)) in terms.iter().enumerate() {
            let sign = if *c < 0.0 { "-" } else { "+" };
            if k == 0 {
                if *c < 0.0 {
                    out.push('-');
                }
            } else {
                out.push_str(&format!(" {sign} "));
            }
            out.push_str(&format!("{}", c.abs()));
            if *mask != 0 {
                let sep = if n >= 10 { "," } else { "" };
                let names: Vec<String> = indices(*mask).iter().map(ToString::to_string).collect();
                out.push_str(&format!("\\,e_{{{}}}", names.join(sep)));
            }
        }
        if terms.is_empty() {
            out.push('0');
        }
        out
    }
}

#[pymethods]
impl PyMultivector {
    /// The multivector of `algebra` with the given 2^N coefficients.
    #[new]
    fn new(algebra: &PyAlgebra, coefficients: &Bound<'_, PyAny>) -> PyResult<Self> {
        algebra.multivector(coefficients)
    }

    /// The algebra this element belongs to.
    #[getter(algebra)]
    fn get_algebra(&self) -> PyAlgebra {
        self.algebra()
    }

    /// The 2^N coefficients (a new float64 array), indexed by blade bit mask.
    #[getter]
    fn coefficients<'py>(&self, py: Python<'py>) -> Bound<'py, PyArrayDyn<f64>> {
        let k = self.mv.as_slice().len();
        output(py, self.mv.as_slice().to_vec(), 1, true, &[k])
    }

    /// The coefficient of a blade, by name ("e12") or bit mask (3).
    fn __getitem__(&self, blade: &Bound<'_, PyAny>) -> PyResult<f64> {
        if let Ok(name) = blade.extract::<String>() {
            let unit = Multivector::blade_by_name(self.mv.signature(), &name, 1.0)
                .map_err(algebra_error)?;
            let (mask, sign) = unit.terms().next().expect("a blade has one term");
            return Ok(sign * self.mv.coefficient(mask));
        }
        let mask: i64 = blade.extract().map_err(|_| {
            PyTypeError::new_err("a blade is given by name (\"e12\") or bit mask (3)")
        })?;
        match usize::try_from(mask) {
            Ok(m) if m < self.mv.as_slice().len() => Ok(self.mv.as_slice()[m]),
            _ => Err(value_error(format!(
                "blade mask {mask} out of range for dimension {}",
                self.mv.dim()
            ))),
        }
    }

    /// The scalar part ⟨A⟩₀.
    #[getter]
    fn scalar_part(&self) -> f64 {
        self.mv.scalar_part()
    }

    fn __repr__(&self) -> String {
        format!("Multivector({}, {})", self.mv.signature(), self.mv)
    }

    fn __str__(&self) -> String {
        self.mv.to_string()
    }

    fn _repr_latex_(&self) -> String {
        format!("${}$", self.latex())
    }

    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let cls = py.get_type::<PyMultivector>();
        let args = (self.algebra(), self.coefficients(py));
        PyTuple::new(py, [cls.into_any(), args.into_pyobject(py)?.into_any()])
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        match other.cast::<PyMultivector>() {
            Ok(o) => self.mv == o.get().mv,
            Err(_) => false,
        }
    }

    // ---- operators --------------------------------------------------------------------------

    /// A + B.
    fn __add__(&self, other: Operand<'_>) -> PyResult<Self> {
        let b = self.operand(&other)?;
        Self::wrap(&self.mv + &b)
    }

    fn __radd__(&self, other: f64) -> PyResult<Self> {
        let a = self.scalar(other)?;
        Self::wrap(&a + &self.mv)
    }

    /// A − B.
    fn __sub__(&self, other: Operand<'_>) -> PyResult<Self> {
        let b = self.operand(&other)?;
        Self::wrap(&self.mv - &b)
    }

    fn __rsub__(&self, other: f64) -> PyResult<Self> {
        let a = self.scalar(other)?;
        Self::wrap(&a - &self.mv)
    }

    fn __neg__(&self) -> PyResult<Self> {
        Self::wrap(-&self.mv)
    }

    fn __pos__(&self) -> PyResult<Self> {
        Self::wrap(self.mv.clone())
    }

    /// The geometric product A B.
    fn __mul__(&self, other: Operand<'_>) -> PyResult<Self> {
        if let Operand::Number(s) = other {
            self.scalar(s)?;
            return Self::wrap(&self.mv * s);
        }
        self.product(&other, Some(Product::Geometric))
    }

    fn __rmul__(&self, other: f64) -> PyResult<Self> {
        self.scalar(other)?;
        Self::wrap(&self.mv * other)
    }

    /// The outer product A ∧ B.
    fn __xor__(&self, other: Operand<'_>) -> PyResult<Self> {
        self.product(&other, Some(Product::Wedge))
    }

    fn __rxor__(&self, other: f64) -> PyResult<Self> {
        self.rproduct(other, Some(Product::Wedge))
    }

    /// The inner product A · B = Σ ⟨A_r B_s⟩_|r−s| (Dorst's "fat dot", kingdon's `|`).
    fn __or__(&self, other: Operand<'_>) -> PyResult<Self> {
        self.product(&other, None)
    }

    fn __ror__(&self, other: f64) -> PyResult<Self> {
        self.rproduct(other, None)
    }

    /// The regressive product A ∨ B.
    fn __and__(&self, other: Operand<'_>) -> PyResult<Self> {
        self.product(&other, Some(Product::Regressive))
    }

    /// The reverse Ã.
    fn __invert__(&self) -> PyResult<Self> {
        Self::wrap(self.mv.reverse())
    }

    /// A B⁻¹, or A / s.
    fn __truediv__(&self, other: Operand<'_>) -> PyResult<Self> {
        match other {
            Operand::Number(s) => {
                self.scalar(s)?;
                if s == 0.0 {
                    return Err(PyZeroDivisionError::new_err("multivector division by zero"));
                }
                Self::wrap(&self.mv * (1.0 / s))
            }
            Operand::Element(b) => {
                let b = self.same_algebra(&b.mv)?;
                let inv = b.inverse().map_err(algebra_error)?;
                Self::wrap(apply_product(&self.mv, &inv, Some(Product::Geometric)))
            }
        }
    }

    /// s A⁻¹.
    fn __rtruediv__(&self, other: f64) -> PyResult<Self> {
        let a = self.scalar(other)?;
        let inv = self.mv.inverse().map_err(algebra_error)?;
        Self::wrap(apply_product(&a, &inv, Some(Product::Geometric)))
    }

    // ---- methods ----------------------------------------------------------------------------

    /// The left contraction A ⌋ B.
    fn left_contract(&self, other: Operand<'_>) -> PyResult<Self> {
        self.product(&other, Some(Product::LeftContraction))
    }

    /// The right contraction A ⌊ B.
    fn right_contract(&self, other: Operand<'_>) -> PyResult<Self> {
        self.product(&other, Some(Product::RightContraction))
    }

    /// The inner product (the operator `|`).
    fn inner(&self, other: Operand<'_>) -> PyResult<Self> {
        self.product(&other, None)
    }

    /// The outer product (the operator `^`).
    fn outer(&self, other: Operand<'_>) -> PyResult<Self> {
        self.product(&other, Some(Product::Wedge))
    }

    /// The scalar product ⟨A B⟩₀.
    fn scalar_product(&self, other: Operand<'_>) -> PyResult<f64> {
        Ok(self
            .product(&other, Some(Product::Scalar))?
            .mv
            .scalar_part())
    }

    /// The commutator product A × B = ½(AB − BA).
    fn commutator(&self, other: Operand<'_>) -> PyResult<Self> {
        self.product(&other, Some(Product::Commutator))
    }

    /// The anticommutator product ½(AB + BA).
    fn anticommutator(&self, other: Operand<'_>) -> PyResult<Self> {
        self.product(&other, Some(Product::Anticommutator))
    }

    /// The regressive product A ∨ B (the operator `&`).
    fn regressive(&self, other: Operand<'_>) -> PyResult<Self> {
        self.product(&other, Some(Product::Regressive))
    }

    /// The sandwich V X Ṽ of this even versor V with X.
    fn sandwich(&self, x: PyRef<'_, PyMultivector>) -> PyResult<Self> {
        let x = self.same_algebra(&x.mv)?;
        Self::wrap(self.mv.apply(x).map_err(algebra_error)?)
    }

    /// exp(B) of a bivector, in closed form.
    fn exp(&self) -> PyResult<Self> {
        Self::wrap(self.mv.exp().map_err(algebra_error)?)
    }

    /// log(V) of an even versor: the bivector B with exp(B) = V.
    fn log(&self) -> PyResult<Self> {
        Self::wrap(self.mv.log().map_err(algebra_error)?)
    }

    /// The square root of an even versor (half the motion).
    fn sqrt(&self) -> PyResult<Self> {
        Self::wrap(self.mv.sqrt().map_err(algebra_error)?)
    }

    /// An even element scaled onto its versor group (V Ṽ = 1); any other element divided by
    /// its norm √|⟨A Ã⟩₀|.
    fn normalized(&self) -> PyResult<Self> {
        if self.mv.grades().iter().all(|g| g % 2 == 0) {
            return Self::wrap(self.mv.normalize_versor().map_err(algebra_error)?);
        }
        let norm = self.mv.norm();
        if norm == 0.0 || !norm.is_finite() {
            return Err(value_error(format!(
                "cannot normalise an element of norm {norm}"
            )));
        }
        Self::wrap(&self.mv * (1.0 / norm))
    }

    /// The grade-k part ⟨A⟩ₖ.
    fn grade(&self, k: i64) -> PyResult<Self> {
        Self::wrap(self.mv.grade(count(k, "grade")?))
    }

    /// The grades present.
    fn grades(&self) -> Vec<usize> {
        self.mv.grades()
    }

    /// The even part.
    fn even(&self) -> PyResult<Self> {
        Self::wrap(self.mv.even())
    }

    /// The odd part.
    fn odd(&self) -> PyResult<Self> {
        Self::wrap(self.mv.odd())
    }

    /// The reverse Ã (also `~A`).
    fn reverse(&self) -> PyResult<Self> {
        Self::wrap(self.mv.reverse())
    }

    /// The grade involution Â.
    fn involute(&self) -> PyResult<Self> {
        Self::wrap(self.mv.grade_involution())
    }

    /// The Clifford conjugate Ā.
    fn conjugate(&self) -> PyResult<Self> {
        Self::wrap(self.mv.clifford_conjugate())
    }

    /// The inverse A⁻¹.
    fn inverse(&self) -> PyResult<Self> {
        Self::wrap(self.mv.inverse().map_err(algebra_error)?)
    }

    /// The dual A I⁻¹ (non-degenerate signatures; use `hodge` in PGA).
    fn dual(&self) -> PyResult<Self> {
        Self::wrap(self.mv.dual().map_err(algebra_error)?)
    }

    /// The Hodge dual ⋆A.
    fn hodge(&self) -> PyResult<Self> {
        Self::wrap(self.mv.hodge())
    }

    /// ⟨A Ã⟩₀.
    fn norm_squared(&self) -> f64 {
        self.mv.norm_squared()
    }

    /// √|⟨A Ã⟩₀|.
    fn norm(&self) -> f64 {
        self.mv.norm()
    }
}
