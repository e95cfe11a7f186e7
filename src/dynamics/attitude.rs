//! [`Attitude`]: the rotation body → space, a unit rotor for small N and an SO(N) matrix
//! above.

use crate::algebra::{AlgebraError, Bivector, Rotor, Vector, accumulate_plane_rotor, pairs};
use crate::numeric::{all_finite, orthogonality_error, sin_cos_minus_one};
use nalgebra::{DMatrix, DMatrixView, DMatrixViewMut, SMatrix};
use smallvec::SmallVec;

/// Column-major N×N storage; inline (no heap) up to N = 8.
type MatrixStorage = SmallVec<[f64; 64]>;

/// The attitude of a rigid body: the rotation that takes body coordinates to space
/// coordinates, x_space = R x R̃ = Q x.
///
/// Up to [`Attitude::ROTOR_MAX_DIM`] (N = 4) it is kept as a unit rotor R ∈ Spin(N): there
/// the rotor exponential has a closed form (quaternion, self-dual split) and a rotor product
/// is as cheap as a matrix product. Above, a rotor's 2^(N−1) coefficients cost more than
/// the motion (2^31 at N = 32) and its exponential needs an eigen-decomposition, so the
/// attitude is kept as its rotation matrix Q ∈ SO(N) (inline storage up to N = 8, so steps
/// stay off the heap) and updated by the same exponentials in matrix form
/// ([`Bivector::exp_skew_matrix`]), O(N³) per step, with monomorphised kernels for
/// N = 5 … 8. The rotor is available on demand ([`Attitude::to_rotor`], N ≤ 16) up to its
/// sign, which a matrix does not carry (the sign matters to spinors, not to the body).
///
/// Both forms are updated only by exact rotations (plane rotations and exponentials of
/// bivectors), so neither needs renormalising; [`Attitude::unit_error`] monitors the drift.
///
/// ```
/// use rotorflow::prelude::*;
/// use rotorflow::dynamics::Attitude;
/// let r = Rotor::from_plane_angle(4, 0, 1, std::f64::consts::FRAC_PI_2)?;
/// let attitude = Attitude::from(r);
/// let x = attitude.rotate_vector(&Vector::basis(4, 0));
/// assert!((x.as_slice()[1] - 1.0).abs() < 1e-15); // e1 turned into e2
/// let big = Attitude::identity(32); // a rotation matrix: no rotor needed
/// assert!(big.as_rotor().is_none() && big.unit_error() == 0.0);
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
#[derive(Debug, PartialEq)]
pub struct Attitude {
    repr: Repr,
}

impl Clone for Attitude {
    fn clone(&self) -> Self {
        Attitude {
            repr: self.repr.clone(),
        }
    }

    /// Copies the rotor's or the matrix's entries into the storage already there when both
    /// are of the same kind (a new attitude would move the whole inline matrix buffer).
    fn clone_from(&mut self, source: &Self) {
        match (&mut self.repr, &source.repr) {
            (Repr::Rotor(a), Repr::Rotor(b)) => a.clone_from(b),
            (Repr::Matrix(a), Repr::Matrix(b)) if a.len() == b.len() => a.copy_from_slice(b),
            (repr, other) => *repr = other.clone(),
        }
    }
}

// The matrix variant is large on purpose: inline storage keeps N ≤ 8 steps off the heap.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, PartialEq)]
enum Repr {
    Rotor(Rotor),
    /// Q with x_space = Q x_body (column j is the image of eⱼ), column-major.
    Matrix(MatrixStorage),
}

impl Attitude {
    /// The largest N whose attitude is kept as a rotor; above it is an SO(N) matrix.
    pub const ROTOR_MAX_DIM: usize = 4;

    /// Returns the identity attitude in dimension `n` (body axes = space axes).
    ///
    /// # Panics
    /// If `n` exceeds the bivector limit ([`crate::algebra::MAX_DIM`]).
    pub fn identity(n: usize) -> Self {
        assert!(
            n <= crate::algebra::MAX_DIM,
            "rotorflow: attitudes exist up to N = {}, got {n}",
            crate::algebra::MAX_DIM
        );
        if n <= Self::ROTOR_MAX_DIM {
            Rotor::identity(n).into()
        } else {
            Self::matrix(&DMatrix::identity(n, n))
        }
    }

    /// Returns the attitude of the rotation matrix `q` (x_space = Q x_body).
    ///
    /// # Errors
    /// [`AlgebraError::NotSquare`], [`AlgebraError::NonFinite`],
    /// [`AlgebraError::DimensionTooLarge`] (N above [`crate::algebra::MAX_DIM`]),
    /// [`AlgebraError::NotARotation`] if max |QᵀQ − 1| > [`crate::algebra::ROTATION_TOLERANCE`]
    /// or det Q < 0.
    pub fn from_matrix(q: &DMatrix<f64>) -> Result<Self, AlgebraError> {
        let n = q.nrows();
        if n <= Self::ROTOR_MAX_DIM {
            return Ok(Rotor::from_matrix(q)?.into());
        }
        if q.ncols() != n {
            return Err(AlgebraError::NotSquare {
                rows: n,
                cols: q.ncols(),
            });
        }
        AlgebraError::check_dimension("attitude", n, crate::algebra::MAX_DIM)?;
        if q.iter().any(|x| !x.is_finite()) {
            return Err(AlgebraError::NonFinite { what: "matrix" });
        }
        let err = orthogonality_error(q.as_view());
        let det = q.determinant();
        let tolerance = crate::algebra::ROTATION_TOLERANCE;
        if err > tolerance || det < 0.0 {
            return Err(AlgebraError::NotARotation {
                orthogonality_error: err,
                determinant: det,
                tolerance,
            });
        }
        Ok(Self::matrix(q))
    }

    /// Wraps a rotation matrix (unchecked).
    fn matrix(q: &DMatrix<f64>) -> Self {
        Attitude {
            repr: Repr::Matrix(q.as_slice().iter().copied().collect()),
        }
    }

    /// The stored matrix as a view.
    fn view(q: &MatrixStorage) -> DMatrixView<'_, f64> {
        let n = side(q);
        DMatrixView::from_slice(q, n, n)
    }

    /// Returns the dimension N.
    pub fn dim(&self) -> usize {
        match &self.repr {
            Repr::Rotor(r) => r.dim(),
            Repr::Matrix(q) => side(q),
        }
    }

    /// The numbers the attitude is kept as: the rotor's coefficients or the matrix's
    /// entries (their count is fixed by N).
    pub(crate) fn entries(&self) -> &[f64] {
        match &self.repr {
            Repr::Rotor(r) => r.as_slice(),
            Repr::Matrix(q) => q,
        }
    }

    /// [`Attitude::entries`], to set in place.
    pub(crate) fn entries_mut(&mut self) -> &mut [f64] {
        match &mut self.repr {
            Repr::Rotor(r) => r.as_mut_slice(),
            Repr::Matrix(q) => q,
        }
    }

    /// Returns the rotor when the attitude is kept as one (N ≤ [`Attitude::ROTOR_MAX_DIM`]).
    pub fn as_rotor(&self) -> Option<&Rotor> {
        match &self.repr {
            Repr::Rotor(r) => Some(r),
            Repr::Matrix(_) => None,
        }
    }

    /// The rotor when the attitude is kept as one, to update in place (the 3D and 4D drift
    /// kernels multiply it by their plane rotors' product without a [`PlaneProduct`]).
    pub(crate) fn rotor_mut(&mut self) -> Option<&mut Rotor> {
        match &mut self.repr {
            Repr::Rotor(r) => Some(r),
            Repr::Matrix(_) => None,
        }
    }

    /// Returns the attitude as a rotor. For N ≤ [`Attitude::ROTOR_MAX_DIM`] this is the rotor
    /// itself, with the sign it has carried continuously through the motion; above, it is
    /// the rotor of the matrix with the sign [`Rotor::from_matrix`] chooses (a rotation
    /// matrix does not determine the sign of its rotor).
    ///
    /// # Errors
    /// [`AlgebraError::DimensionTooLarge`] above the rotor limit (N = 16);
    /// [`AlgebraError::NotARotation`] if the matrix drifted beyond the tolerance.
    pub fn to_rotor(&self) -> Result<Rotor, AlgebraError> {
        match &self.repr {
            Repr::Rotor(r) => Ok(r.clone()),
            Repr::Matrix(q) => Rotor::from_matrix(&Self::view(q).into_owned()),
        }
    }

    /// Returns the rotation matrix Q (x_space = Q x_body; column j is the image of eⱼ).
    pub fn to_matrix(&self) -> DMatrix<f64> {
        match &self.repr {
            Repr::Rotor(r) => r.to_matrix(),
            Repr::Matrix(q) => Self::view(q).into_owned(),
        }
    }

    /// Returns the inverse rotation (space → body): R̃, or Qᵀ.
    pub fn inverse(&self) -> Attitude {
        match &self.repr {
            Repr::Rotor(r) => r.reverse().into(),
            Repr::Matrix(q) => {
                let n = side(q);
                let mut t = MatrixStorage::from_elem(0.0, n * n);
                for j in 0..n {
                    for i in 0..n {
                        t[i * n + j] = q[j * n + i];
                    }
                }
                Attitude {
                    repr: Repr::Matrix(t),
                }
            }
        }
    }

    /// Returns the composition `self` ∘ `other` (first `other`, then `self`): R₁R₂, or Q₁Q₂.
    ///
    /// # Panics
    /// If the dimensions differ.
    #[track_caller]
    pub fn compose(&self, other: &Attitude) -> Attitude {
        assert_eq!(self.dim(), other.dim(), "rotorflow: dimension mismatch");
        match (&self.repr, &other.repr) {
            (Repr::Rotor(a), Repr::Rotor(b)) => a.compose(b).into(),
            (Repr::Matrix(a), Repr::Matrix(b)) => {
                let n = side(a);
                // N = 5 … 8: nalgebra's unrolled fixed-size product on views of the storage.
                macro_rules! fixed {
                    ($($d:literal),*) => {
                        match n {
                            $($d => {
                                type View<'a> = nalgebra::MatrixView<'a, f64, nalgebra::Const<$d>, nalgebra::Const<$d>>;
                                let p = View::from_slice(a) * View::from_slice(b);
                                return Attitude {
                                    repr: Repr::Matrix(MatrixStorage::from_slice(p.as_slice())),
                                };
                            })*
                            _ => {}
                        }
                    };
                }
                fixed!(5, 6, 7, 8);
                // Column j of AB is Σₖ A[:, k] B[k, j], column-major, on the stack up to N = 8.
                let mut c = MatrixStorage::from_elem(0.0, n * n);
                for (j, col) in c.chunks_exact_mut(n).enumerate() {
                    for (k, &bkj) in b[j * n..(j + 1) * n].iter().enumerate() {
                        let ak = &a[k * n..(k + 1) * n];
                        col.iter_mut().zip(ak).for_each(|(o, x)| *o += x * bkj);
                    }
                }
                Attitude {
                    repr: Repr::Matrix(c),
                }
            }
            _ => Self::matrix(&(self.to_matrix() * other.to_matrix())),
        }
    }

    /// Writes Q (x_space = Q x_body) into `out`, row-major N × N, without allocating.
    ///
    /// # Panics
    /// If `out` is shorter than N².
    pub(crate) fn write_matrix(&self, out: &mut [f64]) {
        let n = self.dim();
        match &self.repr {
            Repr::Rotor(r) => r.write_matrix_into(out),
            Repr::Matrix(q) => {
                for i in 0..n {
                    for j in 0..n {
                        out[i * n + j] = q[j * n + i];
                    }
                }
            }
        }
    }

    /// Returns the space image of the body vector `x`: R x R̃ = Q x.
    ///
    /// # Panics
    /// If the dimensions differ.
    #[track_caller]
    pub fn rotate_vector(&self, x: &Vector) -> Vector {
        match &self.repr {
            Repr::Rotor(r) => r.rotate_vector(x),
            Repr::Matrix(q) => matrix_times_vector(q, x, false),
        }
    }

    /// Returns the body image of the space vector `x`: R̃ x R = Qᵀ x.
    ///
    /// # Panics
    /// If the dimensions differ.
    #[track_caller]
    pub fn inverse_rotate_vector(&self, x: &Vector) -> Vector {
        match &self.repr {
            Repr::Rotor(r) => r.reverse().rotate_vector(x),
            Repr::Matrix(q) => matrix_times_vector(q, x, true),
        }
    }

    /// Returns the space image of the body bivector `b`: R B R̃, \[·\] = Q \[B\] Qᵀ.
    ///
    /// # Panics
    /// If the dimensions differ.
    #[track_caller]
    pub fn rotate_bivector(&self, b: &Bivector) -> Bivector {
        match &self.repr {
            Repr::Rotor(_) => self.rotor_conjugate(b, false),
            Repr::Matrix(q) => conjugate(q, side(q), b, false),
        }
    }

    /// Returns the body image of the space bivector `b`: R̃ B R, \[·\] = Qᵀ \[B\] Q.
    ///
    /// # Panics
    /// If the dimensions differ.
    #[track_caller]
    pub fn inverse_rotate_bivector(&self, b: &Bivector) -> Bivector {
        match &self.repr {
            Repr::Rotor(_) => self.rotor_conjugate(b, true),
            Repr::Matrix(q) => conjugate(q, side(q), b, true),
        }
    }

    /// R B R̃ (or R̃ B R when `inverse`) for a rotor attitude, through its matrix on the
    /// stack (no heap).
    fn rotor_conjugate(&self, b: &Bivector, inverse: bool) -> Bivector {
        let n = self.dim();
        let mut q = [0.0; 16];
        // Row-major Q is the column-major storage of Qᵀ.
        self.write_matrix(&mut q[..n * n]);
        conjugate(&q[..n * n], n, b, !inverse)
    }

    /// Returns how far the attitude has left the group: |R R̃ − 1| for a rotor
    /// ([`Rotor::unit_error`]), max |QᵀQ − 1| for a matrix.
    pub fn unit_error(&self) -> f64 {
        match &self.repr {
            Repr::Rotor(r) => r.unit_error(),
            Repr::Matrix(q) => orthogonality_error(Self::view(q)),
        }
    }

    /// Returns true if every stored number is finite.
    pub fn is_finite(&self) -> bool {
        match &self.repr {
            Repr::Rotor(r) => all_finite(r.as_slice()),
            Repr::Matrix(q) => all_finite(q),
        }
    }

    /// Returns R e^A for a bivector A (the rotor exponential; in matrix form Q expm(2\[A\])):
    /// the attitude update of every Lie-group integrator. With A = −½hω this is the exact
    /// flow of dR/dt = −½Rω for a constant ω over a step h.
    pub fn times_exp(&self, a: &Bivector) -> Attitude {
        let mut out = self.clone();
        out.times_exp_mut(a);
        out
    }

    /// R ← R e^A in place (no heap for N ≤ 8). A non-finite A poisons the attitude with NaN
    /// (the integrators then report [`crate::dynamics::DynamicsError::NonFinite`]).
    pub(crate) fn times_exp_mut(&mut self, a: &Bivector) {
        if !a.as_slice().iter().all(|x| x.is_finite()) {
            match &mut self.repr {
                Repr::Rotor(r) => *r = r.clone().scaled(f64::NAN),
                Repr::Matrix(q) => q.iter_mut().for_each(|x| *x = f64::NAN),
            }
            return;
        }
        match &mut self.repr {
            Repr::Rotor(r) => *r *= &a.exp(),
            Repr::Matrix(q) => match a.dim() {
                5 => times_exp_fixed!(5, q, a),
                6 => times_exp_fixed!(6, q, a),
                7 => times_exp_fixed!(7, q, a),
                8 => times_exp_fixed!(8, q, a),
                n => {
                    let product = Self::view(q) * (a * 2.0).exp_skew_matrix();
                    debug_assert_eq!(product.nrows(), n);
                    q.copy_from_slice(product.as_slice());
                }
            },
        }
    }

    /// R ← R e^A and, with it, L ← ẽ L e for e = e^A (in matrix form Eᵀ\[L\]E with
    /// E = expm(2\[A\])): the attitude update of a Lie–Poisson integrator, which moves the
    /// body momentum along its coadjoint orbit by the same rotation, so that the space-frame
    /// momentum R L R̃ is unchanged and every Casimir of L is kept to round-off. No heap for
    /// N ≤ 8. A non-finite A poisons both with NaN.
    pub(crate) fn times_exp_coadjoint_mut(&mut self, a: &Bivector, l: &mut Bivector) {
        if !a.as_slice().iter().all(|x| x.is_finite()) {
            self.times_exp_mut(a);
            l.as_mut_slice().iter_mut().for_each(|x| *x = f64::NAN);
            return;
        }
        match &mut self.repr {
            Repr::Rotor(r) if r.dim() == 4 => {
                a.times_exp_and_reverse_sandwich_4(r, l.as_mut_slice());
            }
            Repr::Rotor(r) => {
                *r *= &a.exp();
                coadjoint_small(a.as_slice(), l.as_mut_slice());
            }
            Repr::Matrix(q) => match a.dim() {
                5 => coadjoint_fixed!(5, q, a, l),
                6 => coadjoint_fixed!(6, q, a, l),
                7 => coadjoint_fixed!(7, q, a, l),
                8 => coadjoint_fixed!(8, q, a, l),
                n => {
                    let e = (a * 2.0).exp_skew_matrix();
                    *l = conjugate(e.as_slice(), n, l, true);
                    let product = Self::view(q) * e;
                    q.copy_from_slice(product.as_slice());
                }
            },
        }
    }

    /// R ← R r with r the rotor of the Cayley rotation U = (1 − A)⁻¹(1 + A) of the skew
    /// matrix A (packed components `a`, Aᵢⱼ for i < j), given also as D = U − 1
    /// (column-major N×N, `d`): a matrix attitude takes Q ← Q + Q D (one rounding of each
    /// entry, as [`PlaneProduct::apply_to`]); a rotor takes r = (1 + B + ½B∧B)/|·| with
    /// Bᵢⱼ = Aᵢⱼ, the product of (1 + tan(θₖ/2) Eₖ) over the invariant planes Eₖ of A (N ≤ 4
    /// has at most two, and ½B∧B = Pf(B) e₁₂₃₄). No heap for N ≤ 8.
    pub(crate) fn times_cayley_mut(&mut self, a: &[f64], d: &[f64]) {
        let n = self.dim();
        match &mut self.repr {
            Repr::Rotor(r) => {
                let pf = if n == 4 {
                    a[0] * a[5] - a[1] * a[4] + a[2] * a[3]
                } else {
                    0.0
                };
                let norm = (1.0 + a.iter().map(|x| x * x).sum::<f64>() + pf * pf).sqrt();
                let inc = Rotor::from_blades(n, |blade| {
                    if blade == 0 {
                        1.0 / norm
                    } else if blade == 0b1111 {
                        pf / norm
                    } else {
                        let (lo, hi) = (
                            blade.trailing_zeros() as usize,
                            63 - blade.leading_zeros() as usize,
                        );
                        a[crate::algebra::pair_index(n, lo, hi)] / norm
                    }
                });
                *r *= &inc;
            }
            Repr::Matrix(q) => {
                let q0: MatrixStorage = q.clone();
                for (k, out) in q.chunks_exact_mut(n).enumerate() {
                    for (l, &dlk) in d[k * n..(k + 1) * n].iter().enumerate() {
                        let col = &q0[l * n..(l + 1) * n];
                        out.iter_mut().zip(col).for_each(|(o, x)| *o += x * dlk);
                    }
                }
            }
        }
    }

    /// Q ← Q expm(S) for a dense skew S = 2\[A\] (column-major N×N): [`Attitude::times_exp_mut`]
    /// for integrators that keep their generator dense (RK4 above N = 8). Small S (every
    /// integrator step) takes the Taylor form and one product, with `work` (2N²) as scratch;
    /// anything else goes through the bivector path (Padé, plane by plane, NaN poisoning).
    pub(crate) fn times_expm_dense(&mut self, s: &[f64], work: &mut [f64]) {
        let n = self.dim();
        let nn = n * n;
        let norm = crate::numeric::norm1_slice(n, s);
        if let (Repr::Matrix(q), true) = (&mut self.repr, norm.is_finite()) {
            if norm == 0.0 {
                return;
            }
            let (e, q0) = work.split_at_mut(nn);
            if crate::numeric::expm_skew_taylor_dense(n, s, norm, e) {
                let q0 = &mut q0[..nn];
                q0.copy_from_slice(q);
                DMatrixViewMut::from_slice(q, n, n).gemm(
                    1.0,
                    &DMatrixView::from_slice(q0, n, n),
                    &DMatrixView::from_slice(e, n, n),
                    0.0,
                );
                return;
            }
        }
        let mut a = Bivector::zero(n);
        for ((i, j), c) in pairs(n).zip(a.as_mut_slice()) {
            *c = 0.5 * s[j * n + i];
        }
        self.times_exp_mut(&a);
    }
}

/// The product P = G₁G₂⋯ of one drift's plane rotations, kept as its difference from the
/// identity, D = P − 1, and applied to the attitude once: R ← R + R D (or Q ← Q + Q D).
///
/// Why not turn the attitude plane by plane: every plane rotation rounds every stored
/// coefficient, a Strang step makes 2K − 1 of them (K = N(N−1)/2 planes), and |R R̃ − 1|
/// random-walks with the number of roundings (like ε √(steps · K)). Here D is O(h|ω|), so
/// its updates round relative to that small size, and the attitude is rounded once per
/// drift. Each factor's cos − 1 is evaluated directly (no cancellation), so the factor is
/// orthogonal to O(εθ²) rather than ε.
pub(crate) struct PlaneProduct {
    dim: usize,
    /// Even coefficients (rotor attitude) or column-major N×N (matrix attitude) of P − 1.
    d: SmallVec<[f64; 64]>,
    rotor: bool,
}

impl PlaneProduct {
    /// The empty product (D = 0) in the representation of `attitude`. No heap for N ≤ 8.
    #[inline]
    pub(crate) fn identity_for(attitude: &Attitude) -> Self {
        let dim = attitude.dim();
        let (len, rotor) = match &attitude.repr {
            Repr::Rotor(r) => (r.as_slice().len(), true),
            Repr::Matrix(q) => (q.len(), false),
        };
        PlaneProduct {
            dim,
            d: SmallVec::from_elem(0.0, len),
            rotor,
        }
    }

    /// P ← P G with G the turn by θ in the body plane eᵢ∧eⱼ (from eᵢ toward eⱼ): the rotor
    /// exp(−θ/2 eᵢⱼ), or the Givens rotation on columns i and j. `(s, m)` are sin θ and
    /// cos θ − 1 from `numeric::sin_cos_minus_one`; a rotor evaluates its half angle
    /// the same way, so each factor is orthogonal to O(εθ²).
    #[inline]
    pub(crate) fn rotate_in_plane(&mut self, i: usize, j: usize, theta: f64, (s, m): (f64, f64)) {
        let n = self.dim;
        let sign = if i < j { 1.0 } else { -1.0 };
        let (lo, hi) = (i.min(j), i.max(j));
        if self.rotor {
            let (s_half, m_half) = sin_cos_minus_one(0.5 * theta);
            let s_half = sign * s_half;
            accumulate_plane_rotor(n, &mut self.d, lo, hi, (1.0 + m_half, m_half, s_half));
            return;
        }
        let (s, c) = (sign * s, 1.0 + m);
        // D G: columns lo and hi are contiguous in column-major storage.
        let (head, tail) = self.d.split_at_mut(hi * n);
        let col_lo = &mut head[lo * n..(lo + 1) * n];
        let col_hi = &mut tail[..n];
        for (a, b) in col_lo.iter_mut().zip(col_hi.iter_mut()) {
            let (x, y) = (*a, *b);
            *a = c * x + s * y;
            *b = c * y - s * x;
        }
        // + (G − 1): cos − 1 on the diagonal, ± sin off it.
        self.d[lo * n + lo] += m;
        self.d[hi * n + hi] += m;
        self.d[lo * n + hi] += s;
        self.d[hi * n + lo] -= s;
    }

    /// R ← R P = R + R D (or Q ← Q + Q D): one rounding of each stored coefficient.
    pub(crate) fn apply_to(&self, attitude: &mut Attitude) {
        debug_assert_eq!(attitude.dim(), self.dim);
        match &mut attitude.repr {
            Repr::Rotor(r) => r.times_one_plus(&self.d),
            Repr::Matrix(q) => {
                let n = self.dim;
                if n > 8 {
                    let q0 = DMatrix::from_column_slice(n, n, q);
                    let mut out = q0.clone();
                    out.gemm(1.0, &q0, &DMatrixView::from_slice(&self.d, n, n), 1.0);
                    q.copy_from_slice(out.as_slice());
                    return;
                }
                let q0: MatrixStorage = q.clone();
                for (k, out) in q.chunks_exact_mut(n).enumerate() {
                    for (l, &dlk) in self.d[k * n..(k + 1) * n].iter().enumerate() {
                        if dlk != 0.0 {
                            let col = &q0[l * n..(l + 1) * n];
                            out.iter_mut().zip(col).for_each(|(o, x)| *o += x * dlk);
                        }
                    }
                }
            }
        }
    }
}

impl From<Rotor> for Attitude {
    /// Keeps the rotor for N ≤ [`Attitude::ROTOR_MAX_DIM`], its matrix above.
    fn from(r: Rotor) -> Self {
        if r.dim() <= Attitude::ROTOR_MAX_DIM {
            Attitude {
                repr: Repr::Rotor(r),
            }
        } else {
            Attitude::matrix(&r.to_matrix())
        }
    }
}

impl From<&Rotor> for Attitude {
    fn from(r: &Rotor) -> Self {
        r.clone().into()
    }
}

/// L ← Eᵀ\[L\]E with E = expm(2\[A\]) for N ≤ 3 (packed components): in 3D L's dual vector
/// (L₂₃, −L₁₃, L₁₂) turns by the rotation vector 2·(dual of A). Cheaper than forming E.
fn coadjoint_small(a: &[f64], l: &mut [f64]) {
    if let ([a12, a13, a23], [l12, l13, l23]) = (a, &mut *l) {
        let v = rotate3([2.0 * a23, -2.0 * a13, 2.0 * a12], [*l23, -*l13, *l12]);
        (*l12, *l13, *l23) = (v[2], -v[1], v[0]);
    }
    // N ≤ 2: a single plane, which the rotation leaves as it is.
}

/// x turned by the angle |v| about the axis v (right-handed; Rodrigues' formula with
/// cos θ − 1 evaluated without cancellation, so the turn is orthogonal to O(εθ²)).
fn rotate3(v: [f64; 3], x: [f64; 3]) -> [f64; 3] {
    let theta2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    if theta2 == 0.0 {
        return x;
    }
    let theta = theta2.sqrt();
    let (s, m) = sin_cos_minus_one(theta);
    let (sv, mv) = (s / theta, m / theta2);
    let cross = [
        v[1] * x[2] - v[2] * x[1],
        v[2] * x[0] - v[0] * x[2],
        v[0] * x[1] - v[1] * x[0],
    ];
    let dot = v[0] * x[0] + v[1] * x[1] + v[2] * x[2];
    std::array::from_fn(|i| x[i] + sv * cross[i] + m * x[i] - mv * v[i] * dot)
}

/// The side N of the stored N×N matrix.
#[inline]
fn side(q: &MatrixStorage) -> usize {
    q.len().isqrt()
}

/// Q x (or Qᵀ x when `transposed`) for the stored column-major Q, without a heap matrix.
#[track_caller]
fn matrix_times_vector(q: &MatrixStorage, x: &Vector, transposed: bool) -> Vector {
    let n = side(q);
    assert_eq!(n, x.dim(), "rotorflow: dimension mismatch");
    let mut y = Vector::zero(n);
    let (xs, ys) = (x.as_slice(), y.as_mut_slice());
    if transposed {
        // (Qᵀ x)ᵢ is column i of Q dotted with x.
        for (i, yi) in ys.iter_mut().enumerate() {
            *yi = q[i * n..(i + 1) * n]
                .iter()
                .zip(xs)
                .map(|(a, b)| a * b)
                .sum();
        }
    } else {
        for (j, &xj) in xs.iter().enumerate() {
            let col = &q[j * n..(j + 1) * n];
            ys.iter_mut().zip(col).for_each(|(y, a)| *y += a * xj);
        }
    }
    y
}

/// Q \[B\] Qᵀ (or Qᵀ \[B\] Q when `transposed`) as a bivector, for the stored column-major
/// Q (on the stack up to N = 8).
#[track_caller]
fn conjugate(q: &[f64], n: usize, b: &Bivector, transposed: bool) -> Bivector {
    assert_eq!(n, b.dim(), "rotorflow: dimension mismatch");
    // Q[r, c] (or Qᵀ[r, c]) of the column-major storage.
    let at = |r: usize, c: usize| {
        if transposed {
            q[r * n + c]
        } else {
            q[c * n + r]
        }
    };
    let mut skew = MatrixStorage::from_elem(0.0, n * n);
    for ((i, j), &c) in pairs(n).zip(b.as_slice()) {
        skew[i * n + j] = c;
        skew[j * n + i] = -c;
    }
    // T = [B] Pᵀ with P = Q (or Qᵀ), row-major: T[a, j] = Σ_c [B][a, c] P[j, c].
    let mut t = MatrixStorage::from_elem(0.0, n * n);
    for a in 0..n {
        for j in 0..n {
            t[a * n + j] = (0..n).map(|c| skew[a * n + c] * at(j, c)).sum();
        }
    }
    let mut out = Bivector::zero(n);
    for (k, (i, j)) in pairs(n).enumerate() {
        // M = P T; the antisymmetric part of M (exactly skew up to round-off).
        let mij: f64 = (0..n).map(|a| at(i, a) * t[a * n + j]).sum();
        let mji: f64 = (0..n).map(|a| at(j, a) * t[a * n + i]).sum();
        out.as_mut_slice()[k] = 0.5 * (mij - mji);
    }
    out
}

/// expm(2\[A\]) for a literal N, on the stack; `None` for A = 0.
macro_rules! expm_fixed {
    ($n:literal, $a:expr) => {{
        let a: &Bivector = $a;
        let mut s = SMatrix::<f64, $n, $n>::zeros();
        for ((i, j), &c) in pairs($n).zip(a.as_slice()) {
            s[(i, j)] = 2.0 * c;
            s[(j, i)] = -2.0 * c;
        }
        let norm = crate::numeric::norm1(&s);
        if norm != 0.0 {
            Some(
                match crate::numeric::expm_skew_taylor(&s, norm)
                    .or_else(|| crate::numeric::expm_skew_fixed(&s, norm))
                {
                    Some(e) => e,
                    None => SMatrix::from_column_slice((a * 2.0).exp_skew_matrix().as_slice()),
                },
            )
        } else {
            None
        }
    }};
}
use expm_fixed;

/// Q ← Q expm(2\[A\]) for a literal N, on the stack.
macro_rules! times_exp_fixed {
    ($n:literal, $q:expr, $a:expr) => {{
        let (q, a): (&mut [f64], &Bivector) = ($q, $a);
        if let Some(e) = expm_fixed!($n, a) {
            let product = SMatrix::<f64, $n, $n>::from_column_slice(q) * e;
            q.copy_from_slice(product.as_slice());
        }
    }};
}
use times_exp_fixed;

/// Q ← Q E and L ← Eᵀ\[L\]E with E = expm(2\[A\]) for a literal N, on the stack.
macro_rules! coadjoint_fixed {
    ($n:literal, $q:expr, $a:expr, $l:expr) => {{
        let (q, a, l): (&mut [f64], &Bivector, &mut Bivector) = ($q, $a, $l);
        if let Some(e) = expm_fixed!($n, a) {
            *l = conjugate(e.as_slice(), $n, l, true);
            let product = SMatrix::<f64, $n, $n>::from_column_slice(q) * e;
            q.copy_from_slice(product.as_slice());
        }
    }};
}
use coadjoint_fixed;

#[cfg(test)]
mod tests {
    use super::*;

    /// `clone_from` in place gives what `clone` gives, between rotors and matrices of any
    /// of the dimensions and in either direction.
    #[test]
    fn clone_from_equals_clone_between_every_kind_and_dimension() {
        let attitudes: Vec<Attitude> = [2usize, 3, 4, 5, 8]
            .iter()
            .map(|&n| {
                let b: Vec<f64> = (0..n * (n - 1) / 2)
                    .map(|k| (0.3 + k as f64).sin())
                    .collect();
                let b = Bivector::from_components(n, &b).unwrap();
                Attitude::identity(n).times_exp(&b)
            })
            .collect();
        assert!(attitudes.iter().any(|a| a.as_rotor().is_some()));
        assert!(attitudes.iter().any(|a| a.as_rotor().is_none()));
        let mut cases = 0;
        for source in &attitudes {
            for start in &attitudes {
                let mut target = start.clone();
                target.clone_from(source);
                assert_eq!(&target, source);
                let mut rotor = source
                    .as_rotor()
                    .cloned()
                    .unwrap_or_else(|| Rotor::identity(3));
                if let Some(r) = start.as_rotor() {
                    rotor.clone_from(r);
                    assert_eq!(Some(&rotor), start.as_rotor());
                }
                cases += 1;
            }
        }
        assert_eq!(cases, 25);
    }

    /// The 3D and 4D closed forms of the coadjoint update agree with the matrix conjugation,
    /// for small and large turns and for A = 0, and the attitude update with the rotor
    /// exponential.
    #[test]
    fn coadjoint_update_is_the_conjugation_by_the_increment() {
        for n in [3, 4] {
            let k = n * (n - 1) / 2;
            for scale in [0.0, 1e-9, 0.03, 1.7] {
                let a_comps: Vec<f64> = (0..k).map(|i| scale * (0.7 + i as f64).sin()).collect();
                let l_comps: Vec<f64> = (0..k).map(|i| (1.3 * i as f64 + 0.2).cos()).collect();
                let a = Bivector::from_components(n, &a_comps).unwrap();
                let l = Bivector::from_components(n, &l_comps).unwrap();
                let e = (&a * 2.0).exp_skew_matrix();
                let expected = conjugate(e.as_slice(), n, &l, true);
                let mut got = l.clone();
                let start = Attitude::identity(n).times_exp(&(&l * 0.4));
                let mut attitude = start.clone();
                attitude.times_exp_coadjoint_mut(&a, &mut got);
                let err = (&got - &expected).max_abs();
                assert!(err < 1e-14, "N = {n}, |A| ~ {scale}: {err:e}");
                let expected_attitude = start.times_exp(&a);
                let (x, y) = (
                    attitude.as_rotor().unwrap(),
                    expected_attitude.as_rotor().unwrap(),
                );
                let gap = x
                    .as_slice()
                    .iter()
                    .zip(y.as_slice())
                    .fold(0.0f64, |m, (p, q)| m.max((p - q).abs()));
                assert!(gap < 1e-15, "N = {n}, |A| ~ {scale}: attitude {gap:e}");
            }
        }
    }
}
