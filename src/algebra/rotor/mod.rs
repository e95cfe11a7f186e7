//! Rotors: the elements of Spin(N), which turn vectors, bivectors and every multivector by
//! the sandwich R X R̃.
//!
//! Split by role: this file holds the type, composition and the sandwiches;
//! [`exp_log`](self) the closed-form exponential and logarithm; `convert` the conversions to
//! and from rotation matrices and the projection back onto Spin(N).

mod convert;
pub use convert::{NORMALIZE_TOLERANCE, ROTATION_TOLERANCE};
mod exp_log;
pub(crate) use exp_log::{exp_even, exp_of_planes, log_even};

use super::bivector::pairs;
use super::blade;
use super::error::{assert_same_dim, check_finite, check_same_dim, within};
use super::multivector::{Multivector, MvStorage};
use super::{AlgebraError, Bivector, MULTIVECTOR_MAX_DIM, Rotor3, Rotor4, Signature, Vector};
use smallvec::SmallVec;

/// Default tolerance of [`Rotor::from_multivector`]: how far from even, unit and
/// vector-preserving a multivector may be and still be accepted as a rotor.
pub const ROTOR_TOLERANCE: f64 = 1e-10;

/// Inline storage for rotors: the 2^(N−1) = 16 even coefficients of N ≤ 5 stay off the heap.
pub(crate) type RotorStorage = SmallVec<[f64; INLINE_LEN]>;

/// The coefficients a rotor keeps inline (N ≤ 5).
const INLINE_LEN: usize = 16;

/// Even coefficients of N ≤ 6 (32 of them) on the stack: the working storage of the rotor
/// exponential and logarithm for N ≥ 5, so that the versor exp and log of Cl(6, 0, 0) need
/// no heap while [`Rotor`] itself stays small for the hot paths of N ≤ 4.
pub(crate) type EvenBuf = SmallVec<[f64; 32]>;

/// A rotor of Euclidean ℝᴺ: an even, unit element R of the Clifford algebra with
/// R R̃ = 1 and R x R̃ a vector for every vector x, i.e. an element of Spin(N).
///
/// R maps body to space, x_space = R x R̃ (see the Conventions chapter of the rotorflow
/// book). `R = exp(−θ B̂/2)` turns by θ in the plane B̂, from its first vector toward its
/// second; its rotation matrix is expm(\[θB̂\]ᵀ).
/// Rotors compose by the geometric product: `r2 * r1` applies `r1` first.
///
/// The 2^(N−1) even coefficients are stored densely, so N ≤ [`MULTIVECTOR_MAX_DIM`].
/// Rotors cannot be added (the sum of two rotors is not a rotor); the escape hatches are
/// [`Rotor::to_multivector`] and [`Rotor::from_multivector_unchecked`].
///
/// # Contents
/// - Construction: [`Rotor::identity`], [`Rotor::from_plane_angle`],
///   [`Rotor::from_rotation_bivector`], [`Bivector::exp`], [`Rotor::from_matrix`]
///   (`TryFrom<&DMatrix<f64>>`), [`Rotor::from_matrix_projected`],
///   `From<UnitQuaternion<f64>>`, [`Rotor::from_multivector`].
/// - Composition and action: `r1 * r2`, [`Rotor::reverse`], [`Rotor::rotate_vector`],
///   [`Rotor::rotate_bivector`], [`Rotor::rotate_multivector`],
///   [`Rotor::rotate_in_plane_mut`].
/// - Logarithm and interpolation: [`Rotor::log`], [`Rotor::rotation_bivector`],
///   [`Rotor::slerp`] (the shorter arc of the rotation), [`Rotor::slerp_spinor`].
/// - Matrices: [`Rotor::to_matrix`].
/// - Drift: [`Rotor::unit_error`], [`Rotor::normalize`], [`Rotor::try_normalize`].
///
/// ```
/// use rotorflow::algebra::{Rotor, Vector};
/// use std::f64::consts::FRAC_PI_2;
/// // A quarter turn in the e1e2 plane takes e1 to e2.
/// let r = Rotor::from_plane_angle(3, 0, 1, FRAC_PI_2)?;
/// let x = r.rotate_vector(&Vector::basis(3, 0));
/// assert!((x[1] - 1.0).abs() < 1e-15 && x[0].abs() < 1e-15);
/// # Ok::<(), rotorflow::algebra::AlgebraError>(())
/// ```
#[derive(Debug, PartialEq)]
pub struct Rotor {
    dim: usize,
    coeffs: RotorStorage,
}

impl Clone for Rotor {
    fn clone(&self) -> Self {
        Rotor {
            dim: self.dim,
            coeffs: self.coeffs.clone(),
        }
    }

    /// Copies the coefficients into the storage already there (a new rotor would move the
    /// whole inline buffer).
    fn clone_from(&mut self, source: &Self) {
        self.dim = source.dim;
        if self.coeffs.len() == source.coeffs.len() {
            self.coeffs.copy_from_slice(&source.coeffs);
        } else {
            self.coeffs.clone_from(&source.coeffs);
        }
    }
}

/// Number of even blades in dimension `n`: 2^(n−1) (1 for n = 0).
#[inline]
pub(crate) fn even_len(n: usize) -> usize {
    if n == 0 { 1 } else { 1 << (n - 1) }
}

/// The even blade stored at position `idx`: the low n−1 bits are `idx`, the top bit restores
/// even parity.
#[inline]
pub(crate) fn even_blade(n: usize, idx: usize) -> u64 {
    if n == 0 {
        return 0;
    }
    let i = idx as u64;
    i | (((i.count_ones() & 1) as u64) << (n - 1))
}

/// The storage position of even blade `b`.
#[inline]
pub(crate) fn even_index(n: usize, b: u64) -> usize {
    if n == 0 {
        0
    } else {
        (b & ((1u64 << (n - 1)) - 1)) as usize
    }
}

/// The odd blade stored at position `idx` in an odd element (top bit makes the parity odd).
#[inline]
fn odd_blade(n: usize, idx: usize) -> u64 {
    let i = idx as u64;
    i | ((((i.count_ones() & 1) ^ 1) as u64) << (n - 1))
}

/// The even blades of dimension `n` in storage order, cached (2^(N−1) masks, 256 KiB at
/// N = 16), so that hot loops do not recompute parities.
pub(crate) fn even_blades(n: usize) -> &'static [u64] {
    use std::sync::OnceLock;
    static LISTS: [OnceLock<Vec<u64>>; MULTIVECTOR_MAX_DIM + 1] =
        [const { OnceLock::new() }; MULTIVECTOR_MAX_DIM + 1];
    LISTS[n].get_or_init(|| (0..even_len(n)).map(|i| even_blade(n, i)).collect())
}

/// The odd blades of dimension `n ≥ 1` in storage order, cached like [`even_blades`].
pub(crate) fn odd_blades(n: usize) -> &'static [u64] {
    use std::sync::OnceLock;
    static LISTS: [OnceLock<Vec<u64>>; MULTIVECTOR_MAX_DIM + 1] =
        [const { OnceLock::new() }; MULTIVECTOR_MAX_DIM + 1];
    LISTS[n].get_or_init(|| (0..even_len(n)).map(|i| odd_blade(n, i)).collect())
}

impl Rotor {
    /// Returns the identity rotor 1 of ℝⁿ.
    ///
    /// # Panics
    /// If `n > MULTIVECTOR_MAX_DIM` (rotors store 2^(N−1) coefficients; see
    /// [`Rotor::try_identity`]).
    #[track_caller]
    pub fn identity(n: usize) -> Self {
        Self::try_identity(n).unwrap_or_else(|e| panic!("rotorflow: {e}"))
    }

    /// Returns the identity rotor 1 of ℝⁿ, or an error if `n` is too large.
    ///
    /// # Errors
    /// [`AlgebraError::DimensionTooLarge`] if `n > MULTIVECTOR_MAX_DIM`.
    pub fn try_identity(n: usize) -> Result<Self, AlgebraError> {
        AlgebraError::check_dimension("rotor", n, MULTIVECTOR_MAX_DIM)?;
        let mut coeffs = crate::numeric::zeros(even_len(n));
        coeffs[0] = 1.0;
        Ok(Rotor { dim: n, coeffs })
    }

    /// Returns the rotor that turns by `angle` radians in the plane eᵢ∧eⱼ, from eᵢ toward eⱼ
    /// (0-based indices): R = exp(−angle/2 · eᵢⱼ) = cos(angle/2) − sin(angle/2) eᵢⱼ.
    ///
    /// # Errors
    /// [`AlgebraError::IndexOutOfRange`], [`AlgebraError::RepeatedIndex`],
    /// [`AlgebraError::NonFinite`], [`AlgebraError::DimensionTooLarge`].
    pub fn from_plane_angle(
        n: usize,
        i: usize,
        j: usize,
        angle: f64,
    ) -> Result<Self, AlgebraError> {
        AlgebraError::check_dimension("rotor", n, MULTIVECTOR_MAX_DIM)?;
        let b = Bivector::from_plane(n, i, j, angle)?;
        Ok(Rotor::from_rotation_bivector(&b))
    }

    /// Builds a rotor from its 2^(N−1) even coefficients without any check (crate-internal).
    pub(crate) fn from_storage(dim: usize, coeffs: RotorStorage) -> Self {
        debug_assert_eq!(coeffs.len(), even_len(dim));
        Rotor { dim, coeffs }
    }

    /// Returns the dimension N.
    #[inline]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Returns the scalar part ⟨R⟩₀ (cos(θ/2) for a single-plane rotation by θ).
    #[inline]
    pub fn scalar(&self) -> f64 {
        self.coeffs[0]
    }

    /// Returns the coefficient of the even basis blade with bit mask `blade` (0 for odd or
    /// out-of-range masks).
    pub fn coefficient(&self, blade: u64) -> f64 {
        if blade::grade(blade) % 2 == 1 || (self.dim < 64 && blade >> self.dim != 0) {
            return 0.0;
        }
        self.coeffs[even_index(self.dim, blade)]
    }

    /// Returns the bivector part ⟨R⟩₂.
    pub fn bivector_part(&self) -> Bivector {
        let n = self.dim;
        let mut b = Bivector::zero(n);
        for (k, (i, j)) in super::bivector::pairs(n).enumerate() {
            b.as_mut_slice()[k] = self.coeffs[even_index(n, (1 << i) | (1 << j))];
        }
        b
    }

    /// Returns an iterator over the non-zero terms as (blade mask, coefficient).
    pub fn terms(&self) -> impl Iterator<Item = (u64, f64)> + '_ {
        let n = self.dim;
        self.coeffs
            .iter()
            .enumerate()
            .filter(|(_, c)| **c != 0.0)
            .map(move |(i, c)| (even_blade(n, i), *c))
    }

    /// Returns the rotor as a general multivector of Cl(N, 0, 0).
    pub fn to_multivector(&self) -> Multivector {
        let n = self.dim;
        let mut m: MvStorage = crate::numeric::zeros(1 << n);
        for (b, c) in self.terms() {
            m[b as usize] = c;
        }
        Multivector::from_storage(Signature::euclidean(n), m)
    }

    /// Returns the rotor held by a multivector, checking that it is one: Euclidean signature,
    /// even, R R̃ = 1 and R x R̃ a vector for every basis vector x, each to within
    /// [`ROTOR_TOLERANCE`] (the odd part relative to the largest coefficient);
    /// [`Rotor::from_multivector_eps`] chooses the tolerance.
    ///
    /// # Errors
    /// [`AlgebraError::UnsupportedSignature`], [`AlgebraError::NotARotor`],
    /// [`AlgebraError::NonFinite`].
    pub fn from_multivector(m: &Multivector) -> Result<Self, AlgebraError> {
        Self::from_multivector_eps(m, ROTOR_TOLERANCE)
    }

    /// Like [`Rotor::from_multivector`] with an explicit tolerance on each of its three
    /// checks.
    ///
    /// # Errors
    /// As [`Rotor::from_multivector`].
    pub fn from_multivector_eps(m: &Multivector, tolerance: f64) -> Result<Self, AlgebraError> {
        if !m.signature().is_euclidean() {
            return Err(AlgebraError::UnsupportedSignature {
                operation: "Rotor::from_multivector",
                signature: m.signature(),
            });
        }
        check_finite(m.as_slice(), "multivector coefficients")?;
        let scale = m.max_abs().max(1.0);
        let odd = m.odd().max_abs();
        if !within(odd, tolerance * scale) {
            return Err(AlgebraError::NotARotor {
                reason: "it has odd-grade parts",
                deviation: odd,
            });
        }
        let r = Rotor::from_multivector_unchecked(m);
        let unit = r.unit_error();
        if !within(unit, tolerance) {
            return Err(AlgebraError::NotARotor {
                reason: "R R̃ ≠ 1",
                deviation: unit,
            });
        }
        let mv = r.to_multivector();
        let rev = mv.reverse();
        for i in 0..r.dim {
            let x = Multivector::basis_blade(mv.signature(), 1 << i);
            let y = mv.geometric(&x).geometric(&rev);
            let non_vector = y
                .terms()
                .filter(|(b, _)| blade::grade(*b) != 1)
                .fold(0.0f64, |s, (_, c)| s.max(c.abs()));
            if !within(non_vector, tolerance) {
                return Err(AlgebraError::NotARotor {
                    reason: "R x R̃ is not a vector",
                    deviation: non_vector,
                });
            }
        }
        Ok(r)
    }

    /// The rotor of Spin(n) whose coefficient on each even blade (bit mask) is `f(blade)`,
    /// unchecked: for data the crate has just computed, without an intermediate multivector.
    pub(crate) fn from_blades(n: usize, f: impl Fn(u64) -> f64) -> Self {
        let coeffs = (0..even_len(n)).map(|i| f(even_blade(n, i))).collect();
        Rotor { dim: n, coeffs }
    }

    /// Returns the even part of `m` as a rotor without checking that it is one.
    ///
    /// Use this to rebuild a rotor from data you trust; the result is only meaningful if `m`
    /// is in Spin(N) (see [`Rotor::from_multivector`] for the checked version).
    pub fn from_multivector_unchecked(m: &Multivector) -> Self {
        let n = m.dim();
        let coeffs = (0..even_len(n))
            .map(|i| m.coefficient(even_blade(n, i)))
            .collect();
        Rotor { dim: n, coeffs }
    }

    /// Returns the reverse R̃, which is also the inverse of a unit rotor.
    pub fn reverse(&self) -> Self {
        let n = self.dim;
        let coeffs = self
            .coeffs
            .iter()
            .enumerate()
            .map(|(i, &c)| c * blade::reverse_sign(blade::grade(even_blade(n, i))))
            .collect();
        Rotor { dim: n, coeffs }
    }

    /// Returns the inverse R⁻¹ = R̃ (exact for unit rotors).
    pub fn inverse(&self) -> Self {
        self.reverse()
    }

    /// Returns the composition `self · other` (apply `other` first, then `self`).
    ///
    /// # Panics
    /// If the dimensions differ (see [`Rotor::try_compose`]).
    #[track_caller]
    pub fn compose(&self, other: &Rotor) -> Rotor {
        assert_same_dim(self.dim, other.dim);
        let len = self.coeffs.len();
        // N = 3, 4: the product in an array of its own length, copied into the inline
        // storage (zeroing and moving a buffer of the whole inline length, or a copy of a
        // length known only at run time, cost more than a 3D product).
        match self.dim {
            3 => {
                let p = Rotor3::<f64>::from_even_layout(layout(&self.coeffs))
                    * Rotor3::<f64>::from_even_layout(layout(&other.coeffs));
                return Rotor {
                    dim: 3,
                    coeffs: SmallVec::from_slice(&p.to_even_layout()),
                };
            }
            4 => {
                let mut p = [0.0; 8];
                even_product_fixed(&self.coeffs, &other.coeffs, &mut p, &EVEN_SIGNS_4);
                return Rotor {
                    dim: 4,
                    coeffs: SmallVec::from_slice(&p),
                };
            }
            _ => {}
        }
        if len <= INLINE_LEN {
            // Formed in a stack buffer that becomes the inline storage whole.
            let mut buf = [0.0; INLINE_LEN];
            even_product_into(self.dim, &self.coeffs, &other.coeffs, &mut buf[..len]);
            return Rotor {
                dim: self.dim,
                coeffs: SmallVec::from_buf_and_len(buf, len),
            };
        }
        let mut out = Rotor {
            dim: self.dim,
            coeffs: crate::numeric::zeros(len),
        };
        even_product_into(self.dim, &self.coeffs, &other.coeffs, &mut out.coeffs);
        out
    }

    /// Checked version of [`Rotor::compose`].
    ///
    /// # Errors
    /// [`AlgebraError::DimensionMismatch`].
    pub fn try_compose(&self, other: &Rotor) -> Result<Rotor, AlgebraError> {
        check_same_dim(self.dim, other.dim)?;
        Ok(self.compose(other))
    }

    /// Returns max |R R̃ − 1| over all coefficients: 0 for an exact rotor, the drift otherwise.
    pub fn unit_error(&self) -> f64 {
        let rr = self.compose(&self.reverse());
        let mut err = (rr.coeffs[0] - 1.0).abs();
        for &c in &rr.coeffs[1..] {
            err = err.max(c.abs());
        }
        err
    }

    /// Returns the rotated vector R x R̃.
    ///
    /// Costs O(N·2^N); to turn many vectors, build [`Rotor::to_matrix`] once (O(N²) per
    /// vector).
    ///
    /// # Panics
    /// If the dimensions differ.
    #[track_caller]
    pub fn rotate_vector(&self, x: &Vector) -> Vector {
        assert_same_dim(self.dim, x.dim());
        let n = self.dim;
        // N = 3, 4: as in `compose`, an array of the vector's own length.
        match n {
            3 => {
                let y = Rotor3::sandwich_even_layout(layout(&self.coeffs), layout(x.as_slice()));
                return Vector::from_storage(SmallVec::from_slice(&y));
            }
            4 => {
                let y = Rotor4::<f64>::from_even_layout(layout(&self.coeffs))
                    .rotate_vector(nalgebra::Vector4::from(*layout::<4>(x.as_slice())));
                return Vector::from_storage(SmallVec::from_slice(&[y.x, y.y, y.z, y.w]));
            }
            _ => {}
        }
        if n <= 8 {
            // Formed in a stack buffer that becomes the inline storage whole.
            let mut buf = [0.0; 8];
            self.sandwich_vector_into(x.as_slice(), &mut buf[..n]);
            return Vector::from_storage(SmallVec::from_buf_and_len(buf, n));
        }
        let mut out = Vector::zero(n);
        self.sandwich_vector_into(x.as_slice(), out.as_mut_slice());
        out
    }

    /// Writes the matrix of x ↦ R x R̃ into `out` (row-major N × N, column j the image of
    /// eⱼ): in 3D and 4D with the fixed-size rotor read once for all N columns, each column
    /// the same arithmetic as [`Rotor::sandwich_vector_into`] of eⱼ.
    ///
    /// # Panics
    /// If `out` is shorter than N², or N > 16.
    pub(crate) fn write_matrix_into(&self, out: &mut [f64]) {
        let n = self.dim;
        match n {
            3 => {
                let c = layout::<4>(&self.coeffs);
                for j in 0..3 {
                    let mut e = [0.0; 3];
                    e[j] = 1.0;
                    let y = Rotor3::sandwich_even_layout(c, &e);
                    for i in 0..3 {
                        out[i * 3 + j] = y[i];
                    }
                }
            }
            4 => {
                let r = Rotor4::<f64>::from_even_layout(layout(&self.coeffs));
                for j in 0..4 {
                    let mut e = nalgebra::Vector4::zeros();
                    e[j] = 1.0;
                    let y = r.rotate_vector(e);
                    for i in 0..4 {
                        out[i * 4 + j] = y[i];
                    }
                }
            }
            _ => {
                let (mut e, mut col) = ([0.0; 16], [0.0; 16]);
                for j in 0..n {
                    e[..n].fill(0.0);
                    e[j] = 1.0;
                    self.sandwich_vector_into(&e[..n], &mut col[..n]);
                    for i in 0..n {
                        out[i * n + j] = col[i];
                    }
                }
            }
        }
    }

    /// Writes R x R̃ into `out` (both of length N).
    pub(crate) fn sandwich_vector_into(&self, x: &[f64], out: &mut [f64]) {
        let n = self.dim;
        match n {
            3 => {
                let y = Rotor3::sandwich_even_layout(layout(&self.coeffs), layout(x));
                out.copy_from_slice(&y);
                return;
            }
            4 => {
                let y = Rotor4::<f64>::from_even_layout(layout(&self.coeffs))
                    .rotate_vector(nalgebra::Vector4::from(*layout::<4>(x)));
                out.copy_from_slice(y.as_slice());
                return;
            }
            _ => {}
        }
        self.sandwich_vector_tables(x, out);
    }

    /// [`Rotor::sandwich_vector_into`] through the blade loops, any N.
    fn sandwich_vector_tables(&self, x: &[f64], out: &mut [f64]) {
        let n = self.dim;
        out.iter_mut().for_each(|o| *o = 0.0);
        if n == 0 {
            return;
        }
        // t = R x (odd), stored at the odd index of each blade. The sign of e_a eᵢ is bit i
        // of suffix_parity(a).
        let mask = (1u64 << (n - 1)) - 1;
        let t = even_times_vector(n, &self.coeffs, x);
        // out_k = Σ_c t_c · R̃_d · sign(e_c e_d), d = c ^ e_k. With p = suffix_parity(c), the
        // reorder parity of (c, c ^ e_k) is parity(p & c) ^ bit k of p; the reverse sign of d
        // depends on whether e_k removes or adds a vector.
        for (&tc, &c) in t.iter().zip(odd_blades(n)) {
            if tc == 0.0 {
                continue;
            }
            let p = blade::suffix_parity(c);
            let base = (p & c).count_ones() & 1;
            let g = c.count_ones() as usize;
            let (rev_down, rev_up) = (
                blade::reverse_sign(g - 1) * tc,
                blade::reverse_sign(g + 1) * tc,
            );
            for (k, o) in out.iter_mut().enumerate() {
                let d = c ^ (1 << k);
                let rd = self.coeffs[(d & mask) as usize];
                let w = if c >> k & 1 == 1 { rev_down } else { rev_up };
                let flip = base ^ ((p >> k) & 1) as u32;
                *o += if flip == 0 { w * rd } else { -w * rd };
            }
        }
    }

    /// Returns the rotated bivector R B R̃, computed as Q \[B\] Qᵀ with Q the rotation matrix.
    ///
    /// # Panics
    /// If the dimensions differ.
    #[track_caller]
    pub fn rotate_bivector(&self, b: &Bivector) -> Bivector {
        assert_same_dim(self.dim, b.dim());
        let q = self.to_matrix();
        let m = &q * b.to_skew_matrix() * q.transpose();
        let n = self.dim;
        let mut out = Bivector::zero(n);
        for (k, (i, j)) in super::bivector::pairs(n).enumerate() {
            out.as_mut_slice()[k] = 0.5 * (m[(i, j)] - m[(j, i)]);
        }
        out
    }

    /// Returns the rotated multivector R M R̃ (any grades; the general sandwich).
    ///
    /// # Errors
    /// [`AlgebraError::DimensionMismatch`], or [`AlgebraError::UnsupportedSignature`] when `m`
    /// is not Euclidean.
    pub fn rotate_multivector(&self, m: &Multivector) -> Result<Multivector, AlgebraError> {
        check_same_dim(self.dim, m.dim())?;
        if !m.signature().is_euclidean() {
            return Err(AlgebraError::UnsupportedSignature {
                operation: "Rotor::rotate_multivector",
                signature: m.signature(),
            });
        }
        let r = self.to_multivector();
        Ok(r.geometric(m).geometric(&r.reverse()))
    }

    /// Multiplies in place on the right by the plane rotor exp(−angle/2 · eᵢⱼ) (0-based,
    /// i ≠ j): R ← R exp(−angle/2 eᵢⱼ), a rotation by `angle` in the body-frame plane eᵢ∧eⱼ.
    ///
    /// Costs O(2^N) and never allocates. (The splitting integrators do not call it per plane:
    /// they multiply a step's plane rotors into one near-identity product first, so that the
    /// attitude is rounded once per step; see `dynamics::attitude::PlaneProduct`.)
    ///
    /// # Panics
    /// If `i` or `j` is out of range or `i == j`.
    #[track_caller]
    pub fn rotate_in_plane_mut(&mut self, i: usize, j: usize, angle: f64) {
        let n = self.dim;
        crate::algebra::error::assert_plane(i, j, n);
        let (lo, hi, sign) = if i < j { (i, j, 1.0) } else { (j, i, -1.0) };
        let (s, c) = (0.5 * angle * sign).sin_cos();
        rotate_even_in_plane(n, &mut self.coeffs, lo, hi, c, s);
    }

    /// R ← R (1 + D) for an even element D given by its 2^(N−1) coefficients in storage
    /// order (crate-internal: how the splitting applies the product of a drift's plane rotors,
    /// kept as its difference from 1, see `dynamics::attitude::PlaneProduct`). Each
    /// coefficient of R is rounded once. No allocation for N ≤ 5.
    pub(crate) fn times_one_plus(&mut self, d: &[f64]) {
        debug_assert_eq!(d.len(), self.coeffs.len());
        let len = self.coeffs.len();
        if len <= INLINE_LEN {
            let mut rd = [0.0; INLINE_LEN];
            even_product_into(self.dim, &self.coeffs, d, &mut rd[..len]);
            self.coeffs.iter_mut().zip(&rd).for_each(|(r, x)| *r += x);
            return;
        }
        let mut rd: RotorStorage = crate::numeric::zeros(len);
        even_product_into(self.dim, &self.coeffs, d, &mut rd);
        self.coeffs.iter_mut().zip(&rd).for_each(|(r, x)| *r += x);
    }

    /// Returns the largest absolute coefficient.
    pub fn max_abs(&self) -> f64 {
        self.coeffs.iter().fold(0.0, |m, c| m.max(c.abs()))
    }

    /// Returns the 2^(N−1) even coefficients in storage order (crate-internal layout: position
    /// `i` holds the even blade whose low N−1 bits are `i`).
    pub fn as_slice(&self) -> &[f64] {
        &self.coeffs
    }

    /// The coefficients of [`Rotor::as_slice`], to set in place (crate-internal: a saved
    /// state written back).
    pub(crate) fn as_mut_slice(&mut self) -> &mut [f64] {
        &mut self.coeffs
    }

    /// Multiplies by a scalar (crate-internal: used by normalisation and sign flips).
    pub(crate) fn scaled(mut self, s: f64) -> Self {
        self.coeffs.iter_mut().for_each(|c| *c *= s);
        self
    }
}

/// Writes scalar, bivector (lexicographic) and pseudoscalar parts into a 4D rotor.
pub(super) fn set_4d(r: &mut Rotor, s: f64, b: [f64; 6], p: f64) {
    r.coeffs[0] = s;
    for ((i, j), &x) in pairs(4).zip(b.iter()) {
        r.coeffs[even_index(4, (1 << i) | (1 << j))] = x;
    }
    r.coeffs[even_index(4, 0b1111)] = p;
}

/// Reads scalar, bivector (lexicographic) and pseudoscalar parts of a 4D rotor.
pub(super) fn get_4d(r: &Rotor) -> (f64, [f64; 6], f64) {
    let mut b = [0.0; 6];
    for ((i, j), x) in pairs(4).zip(b.iter_mut()) {
        *x = r.coeffs[even_index(4, (1 << i) | (1 << j))];
    }
    (r.coeffs[0], b, r.coeffs[even_index(4, 0b1111)])
}

/// R ← R (c + s u v) for orthonormal u ⟂ v: two vector multiplications, O(N 2^N).
///
/// The sign of e_a eᵢ is bit i of `suffix_parity(a)`, computed once per blade.
pub(crate) fn multiply_by_simple(r: &mut Rotor, c: f64, s: f64, u: &[f64], v: &[f64]) {
    multiply_even_by_simple(r.dim, &mut r.coeffs, c, s, u, v);
}

/// The odd product R x of the even element with coefficients `r` (dimension n ≥ 1) and the
/// vector x, stored at the low bits of each odd blade. The sign of e_a eᵢ is bit i of
/// suffix_parity(a).
fn even_times_vector(n: usize, r: &[f64], x: &[f64]) -> SmallVec<[f64; 32]> {
    let mask = (1u64 << (n - 1)) - 1;
    let mut t: SmallVec<[f64; 32]> = SmallVec::from_elem(0.0, even_len(n));
    for (&ra, &a) in r.iter().zip(even_blades(n)) {
        if ra == 0.0 {
            continue;
        }
        let sp = blade::suffix_parity(a);
        for (i, &xi) in x.iter().enumerate() {
            let sign = if sp >> i & 1 == 0 { ra } else { -ra };
            t[((a ^ (1 << i)) & mask) as usize] += sign * xi;
        }
    }
    t
}

/// [`multiply_by_simple`] on the 2^(N−1) even coefficients of dimension `n`.
pub(crate) fn multiply_even_by_simple(
    n: usize,
    r: &mut [f64],
    c: f64,
    s: f64,
    u: &[f64],
    v: &[f64],
) {
    let mask = (1u64 << (n - 1)) - 1;
    // t = R u (odd, indexed by low bits).
    let t = even_times_vector(n, r, u);
    // R ← c R + s (t v).
    r.iter_mut().for_each(|x| *x *= c);
    for (&tb, &b) in t.iter().zip(odd_blades(n)) {
        if tb == 0.0 {
            continue;
        }
        let sp = blade::suffix_parity(b);
        let stb = s * tb;
        for (i, &vi) in v.iter().enumerate() {
            let sign = if sp >> i & 1 == 0 { stb } else { -stb };
            r[((b ^ (1 << i)) & mask) as usize] += sign * vi;
        }
    }
}

/// X ← X (c − s e_lo e_hi) for an even element X stored by even index (lo < hi): the right
/// product by a plane rotor with c = cos(θ/2), s = sin(θ/2). O(2^N), no allocation.
pub(crate) fn rotate_even_in_plane(n: usize, x: &mut [f64], lo: usize, hi: usize, c: f64, s: f64) {
    if n <= PLANE_TABLE_MAX_DIM {
        // Small N: the coefficient pairs and their signs come from a table.
        let table = &plane_tables(n)[super::bivector::pair_index(n, lo, hi)];
        for &(ib, ib2, s1, s2) in table {
            let (xb, xb2) = (x[ib as usize], x[ib2 as usize]);
            x[ib as usize] = c * xb - s * s1 * xb2;
            x[ib2 as usize] = c * xb2 - s * s2 * xb;
        }
        return;
    }
    let m: u64 = (1 << lo) | (1 << hi);
    // new[b] = c X[b] − s · sign(e_{b^m} e_m) X[b^m]; pairs (b, b^m) update together.
    for ib in 0..x.len() {
        let b = even_blade(n, ib);
        let b2 = b ^ m;
        let ib2 = even_index(n, b2);
        if ib2 < ib {
            continue;
        }
        let (xb, xb2) = (x[ib], x[ib2]);
        x[ib] = c * xb - s * blade::reorder_sign(b2, m) * xb2;
        x[ib2] = c * xb2 - s * blade::reorder_sign(b, m) * xb;
    }
}

/// D ← D g + (g − 1) with g = c − s e_lo e_hi (lo < hi): the update of D = P − 1 when the
/// product of plane rotors P is multiplied on the right by g. `c_minus_1` is cos(θ/2) − 1
/// computed without cancellation, so that g − 1 is accurate to relative round-off even when
/// the angle is small (see `dynamics::attitude::PlaneProduct`).
pub(crate) fn accumulate_plane_rotor(
    n: usize,
    d: &mut [f64],
    lo: usize,
    hi: usize,
    (c, c_minus_1, s): (f64, f64, f64),
) {
    rotate_even_in_plane(n, d, lo, hi, c, s);
    d[0] += c_minus_1;
    d[even_index(n, (1 << lo) | (1 << hi))] -= s;
}

/// Up to this N, [`Rotor::rotate_in_plane_mut`] reads its coefficient pairs from a table.
const PLANE_TABLE_MAX_DIM: usize = 6;

/// For each plane (lo, hi) in lexicographic order, the pairs (ib, ib2, s1, s2) of even
/// indices that the right product by exp(−θ/2 e_lo,hi) mixes: new[ib] = c R[ib] − s s1 R[ib2],
/// new[ib2] = c R[ib2] − s s2 R[ib] (the same formula as the general loop, tabulated).
#[allow(clippy::type_complexity)]
pub(crate) fn plane_tables(n: usize) -> &'static [Vec<(u8, u8, f64, f64)>] {
    use std::sync::OnceLock;
    static TABLES: [OnceLock<Vec<Vec<(u8, u8, f64, f64)>>>; PLANE_TABLE_MAX_DIM + 1] =
        [const { OnceLock::new() }; PLANE_TABLE_MAX_DIM + 1];
    TABLES[n].get_or_init(|| {
        super::bivector::pairs(n)
            .map(|(lo, hi)| {
                let m: u64 = (1 << lo) | (1 << hi);
                (0..even_len(n))
                    .filter_map(|ib| {
                        let b = even_blade(n, ib);
                        let b2 = b ^ m;
                        let ib2 = even_index(n, b2);
                        (ib2 > ib).then(|| {
                            (
                                ib as u8,
                                ib2 as u8,
                                blade::reorder_sign(b2, m),
                                blade::reorder_sign(b, m),
                            )
                        })
                    })
                    .collect()
            })
            .collect()
    })
}

/// out = a · b for even elements stored by even index (Euclidean signature). O(4^(N−1)):
/// every pair of even blades meets once; the sign's suffix parity is computed once per row.
/// N ≤ 5 runs a kernel unrolled at compile time from a constant sign table (the general loop
/// spends most of its time on the signs).
pub(crate) fn even_product_into(n: usize, a: &[f64], b: &[f64], out: &mut [f64]) {
    // N = 3: Hamilton's product (the layout is the quaternion up to signs and order, so
    // this is exact where the tables are: R · 1 = R). N = 4 stays on the sign table: the
    // quaternion pair would round s ± p on the way in and out.
    if n == 3 {
        let p =
            Rotor3::<f64>::from_even_layout(layout(a)) * Rotor3::<f64>::from_even_layout(layout(b));
        out.copy_from_slice(&p.to_even_layout());
    } else {
        even_product_tables(n, a, b, out);
    }
}

/// The coefficients of an even element of length L as an array (the caller's dimension fixes
/// the length).
#[inline(always)]
pub(crate) fn layout<const L: usize>(c: &[f64]) -> &[f64; L] {
    c.try_into().expect("even element length")
}

/// [`even_product_into`] through the sign tables (N ≤ 5) or the blade loop.
fn even_product_tables(n: usize, a: &[f64], b: &[f64], out: &mut [f64]) {
    match n {
        2 => return even_product_fixed(a, b, out, &EVEN_SIGNS_2),
        3 => return even_product_fixed(a, b, out, &EVEN_SIGNS_3),
        4 => return even_product_fixed(a, b, out, &EVEN_SIGNS_4),
        5 => return even_product_fixed(a, b, out, &EVEN_SIGNS_5),
        _ => {}
    }
    out.iter_mut().for_each(|o| *o = 0.0);
    let mask = if n == 0 { 0 } else { (1u64 << (n - 1)) - 1 };
    let blades = even_blades(n);
    for (&ca, &ba) in a.iter().zip(blades) {
        if ca == 0.0 {
            continue;
        }
        let pa = blade::suffix_parity(ba);
        for (&cb, &bb) in b.iter().zip(blades) {
            let s = blade::parity_sign(pa & bb);
            out[((ba ^ bb) & mask) as usize] += s * ca * cb;
        }
    }
}

/// The sign of e_A e_B for the even blades stored at positions i and j in dimension `n`
/// (their product is stored at i ^ j): the parity of the transpositions that sort the
/// concatenated indices (the same rule as `blade::reorder_sign`, in a const fn).
const fn even_signs<const L: usize>(n: usize) -> [[f64; L]; L] {
    let mut table = [[0.0; L]; L];
    let mut i = 0;
    while i < L {
        let mut j = 0;
        while j < L {
            table[i][j] = reorder_sign_const(n, even_blade_const(n, i), even_blade_const(n, j));
            j += 1;
        }
        i += 1;
    }
    table
}

/// The sign of e_A e_B against the sorted blade e_(A⊕B) (up to the metric): each basis vector
/// of B passes every vector of A with a larger index (`blade::reorder_sign` as a const fn, for
/// blades of dimension `n`).
pub(crate) const fn reorder_sign_const(n: usize, a: u64, b: u64) -> f64 {
    let mut swaps = 0u32;
    let mut k = 0;
    while k < n {
        if b & (1 << k) != 0 {
            swaps += (a >> (k + 1)).count_ones();
        }
        k += 1;
    }
    if swaps.is_multiple_of(2) { 1.0 } else { -1.0 }
}

/// [`plane_tables`] for one plane (lo, hi) as a const fn with RP = 2^(n−2) entries.
pub(crate) const fn plane_table_const<const RP: usize>(
    n: usize,
    lo: usize,
    hi: usize,
) -> [(usize, usize, f64, f64); RP] {
    let mut out = [(0, 0, 0.0, 0.0); RP];
    let m: u64 = (1 << lo) | (1 << hi);
    let mask = (1u64 << (n - 1)) - 1;
    let (mut ib, mut slot) = (0, 0);
    while ib < 1 << (n - 1) {
        let b = even_blade_const(n, ib);
        let b2 = b ^ m;
        let ib2 = (b2 & mask) as usize;
        if ib2 > ib {
            out[slot] = (
                ib,
                ib2,
                reorder_sign_const(n, b2, m),
                reorder_sign_const(n, b, m),
            );
            slot += 1;
        }
        ib += 1;
    }
    out
}

/// [`even_blade`] as a const fn.
const fn even_blade_const(n: usize, idx: usize) -> u64 {
    let i = idx as u64;
    i | (((i.count_ones() & 1) as u64) << (n - 1))
}

const EVEN_SIGNS_2: [[f64; 2]; 2] = even_signs(2);
const EVEN_SIGNS_3: [[f64; 4]; 4] = even_signs(3);
const EVEN_SIGNS_4: [[f64; 8]; 8] = even_signs(4);
const EVEN_SIGNS_5: [[f64; 16]; 16] = even_signs(5);

/// The product of two even elements of L = 2^(N−1) coefficients with the signs of
/// `signs`: constant bounds, so the compiler unrolls it and folds the ±1.
#[inline(always)]
fn even_product_fixed<const L: usize>(
    a: &[f64],
    b: &[f64],
    out: &mut [f64],
    signs: &[[f64; L]; L],
) {
    let (a, b): (&[f64; L], &[f64; L]) = (
        a.try_into().expect("even element length"),
        b.try_into().expect("even element length"),
    );
    // out[k] = Σᵢ ± a[i] b[i ^ k]: one dot product per output, no scattered writes, summed
    // pairwise (log₂ L additions deep instead of L, so the outputs' sums overlap in the
    // pipeline). Only the term with b's scalar survives a product with 1: R · 1 = R exactly.
    let acc: [f64; L] = std::array::from_fn(|k| {
        let mut terms: [f64; L] = std::array::from_fn(|i| signs[i][i ^ k] * a[i] * b[i ^ k]);
        let mut width = L;
        while width > 1 {
            width /= 2;
            for i in 0..width {
                terms[i] = terms[2 * i] + terms[2 * i + 1];
            }
        }
        terms[0]
    });
    out.copy_from_slice(&acc);
}

impl std::ops::MulAssign<&Rotor> for Rotor {
    /// In-place composition: `r *= s` sets r ← r s (apply `s` first). No allocation for
    /// N ≤ 5: the product is formed on the stack and copied back.
    #[track_caller]
    fn mul_assign(&mut self, rhs: &Rotor) {
        assert_same_dim(self.dim, rhs.dim);
        let mut out: RotorStorage = crate::numeric::zeros(self.coeffs.len());
        even_product_into(self.dim, &self.coeffs, &rhs.coeffs, &mut out);
        self.coeffs.copy_from_slice(&out);
    }
}

impl std::ops::Mul<&Rotor> for &Rotor {
    type Output = Rotor;
    /// Composition: `a * b` applies `b` first, then `a`.
    #[track_caller]
    fn mul(self, rhs: &Rotor) -> Rotor {
        self.compose(rhs)
    }
}

impl std::ops::Mul<Rotor> for Rotor {
    type Output = Rotor;
    /// Composition: `a * b` applies `b` first, then `a`.
    #[track_caller]
    fn mul(self, rhs: Rotor) -> Rotor {
        self.compose(&rhs)
    }
}

impl std::ops::Mul<&Rotor> for Rotor {
    type Output = Rotor;
    /// Composition: `a * b` applies `b` first, then `a`.
    #[track_caller]
    fn mul(self, rhs: &Rotor) -> Rotor {
        self.compose(rhs)
    }
}

impl std::ops::Mul<Rotor> for &Rotor {
    type Output = Rotor;
    /// Composition: `a * b` applies `b` first, then `a`.
    #[track_caller]
    fn mul(self, rhs: Rotor) -> Rotor {
        self.compose(&rhs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The compile-time sign tables agree with the run-time rule `blade::reorder_sign`.
    #[test]
    fn const_sign_tables_match_reorder_sign() {
        fn check<const L: usize>(n: usize, table: &[[f64; L]; L]) {
            for (i, row) in table.iter().enumerate() {
                for (j, &sign) in row.iter().enumerate() {
                    let (a, b) = (even_blade(n, i), even_blade(n, j));
                    assert_eq!(sign, blade::reorder_sign(a, b), "n={n} ({a:b})({b:b})");
                    assert_eq!(even_index(n, a ^ b), i ^ j);
                }
            }
        }
        check(2, &EVEN_SIGNS_2);
        check(3, &EVEN_SIGNS_3);
        check(4, &EVEN_SIGNS_4);
        check(5, &EVEN_SIGNS_5);
    }

    /// The compile-time plane tables of the splittings equal the run-time ones.
    #[test]
    fn const_plane_tables_match_the_run_time_tables() {
        fn check<const RP: usize>(n: usize) -> usize {
            let mut planes = 0;
            for (p, (lo, hi)) in super::super::bivector::pairs(n).enumerate() {
                let c = plane_table_const::<RP>(n, lo, hi);
                let r: Vec<(usize, usize, f64, f64)> = plane_tables(n)[p]
                    .iter()
                    .map(|&(a, b, s1, s2)| (a as usize, b as usize, s1, s2))
                    .collect();
                assert_eq!(c.as_slice(), r.as_slice(), "n = {n}, plane ({lo}, {hi})");
                planes += 1;
            }
            planes
        }
        assert_eq!(
            check::<1>(2) + check::<2>(3) + check::<4>(4) + check::<8>(5),
            1 + 3 + 6 + 10
        );
    }

    /// max |a − b| in units of ε · max(1, max |b|).
    fn ulps(a: &[f64], b: &[f64]) -> f64 {
        let scale = b.iter().fold(1.0f64, |m, c| m.max(c.abs()));
        let d = a
            .iter()
            .zip(b)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        d / (f64::EPSILON * scale)
    }

    /// The N = 3, 4 routes through the fixed-size rotors (3D product, sandwich, rotation
    /// matrix, 4D exponential) equal the blade and sign-table routes to 4 ulp, on random
    /// bivectors of every size and on the hard ones: isoclinic and near-isoclinic 4D
    /// rotations, angles at π, tiny and huge components.
    #[test]
    fn fixed_size_routes_equal_the_blade_routes() {
        let mut s = 0x9e37_79b9_7f4a_7c15u64;
        let mut r = move || crate::numeric::tests::random(&mut s);
        let mut cases = 0;
        let mut worst = [0.0f64; 4];
        for n in [3usize, 4] {
            let m = n * (n - 1) / 2;
            let mut inputs: Vec<Vec<f64>> = Vec::new();
            for scale in [1e-200, 1e-8, 0.3, 1.0, 3.0, 1e6, 1e150] {
                for _ in 0..40 {
                    inputs.push((0..m).map(|_| scale * r()).collect());
                }
            }
            let pi = std::f64::consts::PI;
            if n == 4 {
                // (b12, b13, b14, b23, b24, b34): isoclinic b12 = ±b34, then gaps.
                for gap in [0.0, 1e-15, 1e-9, 1e-6] {
                    for a in [0.4, 1.5, pi / 2.0 - 1e-12] {
                        inputs.push(vec![a, 0.0, 0.0, 0.0, 0.0, a + gap]);
                        inputs.push(vec![a, 0.1, -0.2, 0.2, 0.1, -a - gap]);
                    }
                }
            }
            // Rotation angle π ± 1e-12 in the e₁₂ plane (the rotor's angle is half of it).
            for d in [-1e-12, 0.0, 1e-12] {
                let mut b = vec![0.0; m];
                b[0] = pi / 2.0 + d;
                inputs.push(b);
            }
            let x: Vec<f64> = (0..n).map(|_| r()).collect();
            for pair in inputs.windows(2) {
                let a = Bivector::from_components(n, &pair[0]).unwrap();
                let b = Bivector::from_components(n, &pair[1]).unwrap();
                let (ra, rb) = (a.exp(), b.exp());
                let len = ra.coeffs.len();
                let (mut fast, mut general) = (vec![0.0; len], vec![0.0; len]);
                even_product_into(n, &ra.coeffs, &rb.coeffs, &mut fast);
                even_product_tables(n, &ra.coeffs, &rb.coeffs, &mut general);
                worst[0] = worst[0].max(ulps(&fast, &general));
                let (mut y, mut yg) = (vec![0.0; n], vec![0.0; n]);
                ra.sandwich_vector_into(&x, &mut y);
                ra.sandwich_vector_tables(&x, &mut yg);
                worst[1] = worst[1].max(ulps(&y, &yg));
                let (mut q, mut qg) = (vec![0.0; n * n], vec![0.0; n * n]);
                convert::fill_matrix(n, &ra.coeffs, |i, j, v| q[i * n + j] = v);
                convert::fill_matrix_blades(n, &ra.coeffs, |i, j, v| qg[i * n + j] = v);
                worst[2] = worst[2].max(ulps(&q, &qg));
                // Above 2⁵³ the half sums b₁₂ ± b₃₄ round by more than 2π, so neither route
                // determines the rotor there (each is exact for its own rounding).
                if n == 4 && a.max_abs() < 1e15 {
                    let mut rg = Rotor::identity(4);
                    exp_log::exp_4d(a.as_slice(), &mut rg);
                    worst[3] = worst[3].max(ulps(&ra.coeffs, &rg.coeffs));
                }
                cases += 1;
            }
        }
        eprintln!("ulps (product, sandwich, matrix, 4D exp): {worst:?}");
        assert!(worst.iter().all(|&w| w <= 4.0), "{worst:?}");
        assert_eq!(cases, 282 + 306);
    }
}
