//! Rotors ↔ rotation matrices, and the projection of a drifted rotor back onto Spin(N).

use super::{Rotor, even_index, get_4d, multiply_by_simple, set_4d};
use crate::algebra::bivector::{bivector_len, pairs};
use crate::algebra::decompose::{Planes, RawPlane, decompose_components};
use crate::algebra::error::within;
use crate::algebra::{AlgebraError, MULTIVECTOR_MAX_DIM};
use crate::numeric::dense::{Mat8, Vec8, dot, norm};
use crate::numeric::orthogonality_error;
use nalgebra::DMatrix;
use smallvec::SmallVec;

/// Default tolerance on max |QᵀQ − 1| for [`Rotor::from_matrix`].
pub const ROTATION_TOLERANCE: f64 = 1e-9;

/// Default tolerance of [`Rotor::try_normalize`] on max |R R̃ − 1|: far above the drift that
/// f64 round-off accumulates over long runs, and above the error of rotors that went through
/// f32 data (~1e-7), but far below any deviation that is not round-off.
pub const NORMALIZE_TOLERANCE: f64 = 1e-6;

impl Rotor {
    /// Returns the N×N rotation matrix Q of R: column j is R eⱼ R̃, so Q x = R x R̃.
    ///
    /// For R = exp(−θ B̂/2) this is expm(\[θB̂\]ᵀ) (see the Conventions chapter of the
    /// rotorflow book). Costs O(N²·2^N).
    pub fn to_matrix(&self) -> DMatrix<f64> {
        let n = self.dim;
        if n == 4 {
            // Moved into the heap matrix whole (no zeroed matrix filled entry by entry: at
            // N = 4 that cost a third of the conversion).
            return DMatrix::from_column_slice(4, 4, matrix_4d(&self.coeffs).as_slice());
        }
        let mut q = DMatrix::zeros(n, n);
        fill_matrix(n, &self.coeffs, |i, j, x| q[(i, j)] = x);
        q
    }

    /// [`Rotor::to_matrix`] written into `out`, an N × N matrix the caller keeps, without
    /// allocating: for a loop that needs the matrix of a run-time rotor every step (at N = 4
    /// the heap allocation of a new matrix costs about as much as the conversion itself).
    ///
    /// ```
    /// use rotorflow::algebra::Bivector;
    /// let r = Bivector::from_components(4, &[0.3, -0.2, 0.5, 0.1, 0.4, -0.6])?.exp();
    /// let mut q = nalgebra::DMatrix::zeros(4, 4);
    /// r.matrix_to(&mut q)?;
    /// assert_eq!(q, r.to_matrix());
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    ///
    /// # Errors
    /// [`AlgebraError::DimensionMismatch`] unless `out` is N × N.
    pub fn matrix_to(&self, out: &mut DMatrix<f64>) -> Result<(), AlgebraError> {
        let n = self.dim;
        if out.shape() != (n, n) {
            return Err(AlgebraError::DimensionMismatch {
                left: n,
                right: if out.nrows() != n {
                    out.nrows()
                } else {
                    out.ncols()
                },
            });
        }
        if n == 4 {
            out.as_mut_slice()
                .copy_from_slice(matrix_4d(&self.coeffs).as_slice());
        } else {
            fill_matrix(n, &self.coeffs, |i, j, x| out[(i, j)] = x);
        }
        Ok(())
    }

    /// Returns the rotor of a rotation matrix (either of ±R; the one with non-negative scalar
    /// part), for any N ≤ [`MULTIVECTOR_MAX_DIM`].
    ///
    /// The matrix must be orthogonal to within [`ROTATION_TOLERANCE`] (max |QᵀQ − 1|) with
    /// determinant +1; see [`Rotor::from_matrix_eps`] to choose the tolerance and
    /// [`Rotor::from_matrix_projected`] to accept any matrix near a rotation.
    ///
    /// # Errors
    /// [`AlgebraError::NotSquare`], [`AlgebraError::NonFinite`],
    /// [`AlgebraError::NotARotation`], [`AlgebraError::DimensionTooLarge`].
    pub fn from_matrix(q: &DMatrix<f64>) -> Result<Rotor, AlgebraError> {
        Self::from_matrix_eps(q, ROTATION_TOLERANCE)
    }

    /// Like [`Rotor::from_matrix`] with an explicit tolerance on max |QᵀQ − 1|.
    ///
    /// # Errors
    /// As [`Rotor::from_matrix`].
    pub fn from_matrix_eps(q: &DMatrix<f64>, tolerance: f64) -> Result<Rotor, AlgebraError> {
        check_matrix_shape(q)?;
        let n = q.nrows();
        let err = orthogonality_error(q.as_view());
        let det = if n == 0 { 1.0 } else { q.determinant() };
        if err.is_nan() || err > tolerance || det < 0.0 {
            return Err(AlgebraError::NotARotation {
                orthogonality_error: err,
                determinant: det,
                tolerance,
            });
        }
        Ok(rotor_of_orthogonal(q))
    }

    /// Returns the rotor of the rotation nearest to `m` (the orthogonal polar factor U Vᵀ of
    /// its SVD), for matrices that are rotations only approximately (drift, measurement).
    ///
    /// # Errors
    /// [`AlgebraError::NotARotation`] if the nearest orthogonal matrix is a reflection
    /// (det < 0) or `m` is singular; shape and finiteness errors as [`Rotor::from_matrix`].
    pub fn from_matrix_projected(m: &DMatrix<f64>) -> Result<Rotor, AlgebraError> {
        check_matrix_shape(m)?;
        let q = nearest_orthogonal(m).ok_or(AlgebraError::NotARotation {
            orthogonality_error: orthogonality_error(m.as_view()),
            determinant: m.determinant(),
            tolerance: f64::INFINITY,
        })?;
        let det = q.determinant();
        if det < 0.0 {
            return Err(AlgebraError::NotARotation {
                orthogonality_error: orthogonality_error(m.as_view()),
                determinant: m.determinant(),
                tolerance: f64::INFINITY,
            });
        }
        Ok(rotor_of_orthogonal(&q))
    }

    /// Returns the rotor projected back onto Spin(N), removing the drift of accumulated
    /// round-off. Dividing by the norm is not enough for N ≥ 4 (R R̃ then has grade-4 parts).
    ///
    /// N ≤ 3: division by the norm (exact projection for quaternions). N = 4:
    /// R R̃ = a + bI, and R ← R (a + bI)^(−1/2) in closed form through the idempotents
    /// P± = (1 ± I)/2. N ≥ 5: the orthogonal polar factor of R's (drifted) linear map, lifted
    /// back with the sign nearest to R.
    ///
    /// A rotor that is far from Spin(N) (for example 0) has no meaningful projection; the
    /// result is then the identity's sign-nearest lift of whatever rotation remains.
    /// [`Rotor::try_normalize`] refuses such input instead.
    pub fn normalize(&self) -> Rotor {
        let n = self.dim;
        match n {
            0..=3 => {
                let s = crate::numeric::scaled_norm(&self.coeffs);
                if s > 0.0 {
                    self.clone().scaled(1.0 / s)
                } else {
                    Rotor::identity(n)
                }
            }
            4 => {
                let rr = self.compose(&self.reverse());
                let (a, _, b) = get_4d(&rr);
                let (p, m) = (a + b, a - b);
                if p.is_nan() || m.is_nan() || p <= 0.0 || m <= 0.0 {
                    return Rotor::identity(4);
                }
                let (ip, im) = (1.0 / p.sqrt(), 1.0 / m.sqrt());
                let mut k = Rotor::identity(4);
                set_4d(&mut k, 0.5 * (ip + im), [0.0; 6], 0.5 * (ip - im));
                self.compose(&k)
            }
            _ => {
                let q = self.to_matrix();
                let Some(q) = nearest_orthogonal(&q) else {
                    return Rotor::identity(n);
                };
                let r = rotor_of_orthogonal(&q);
                let d: f64 = r.coeffs.iter().zip(&self.coeffs).map(|(a, b)| a * b).sum();
                if d < 0.0 { r.scaled(-1.0) } else { r }
            }
        }
    }
}

impl Rotor {
    /// [`Rotor::normalize`], refusing a rotor whose distance max |R R̃ − 1| from Spin(N)
    /// ([`Rotor::unit_error`]) exceeds [`NORMALIZE_TOLERANCE`]: projecting removes drift, it
    /// does not turn an arbitrary even element into a meaningful rotation.
    ///
    /// ```
    /// use rotorflow::algebra::{AlgebraError, Bivector, Rotor};
    /// let r = Bivector::from_plane(4, 0, 1, 0.3)?.exp();
    /// let drifted = &r * &Rotor::identity(4); // any product accumulates round-off
    /// assert!(drifted.try_normalize()?.unit_error() < 1e-15);
    /// // Twice a rotor is 1 away from Spin(N) (R R̃ = 4): refused, with the distance.
    /// let far = Rotor::from_multivector_unchecked(&(r.to_multivector() * 2.0));
    /// match far.try_normalize() {
    ///     Err(AlgebraError::FarFromGroup { distance, .. }) => assert!((distance - 3.0).abs() < 1e-14),
    ///     other => panic!("{other:?}"),
    /// }
    /// # Ok::<(), AlgebraError>(())
    /// ```
    ///
    /// # Errors
    /// [`AlgebraError::FarFromGroup`] with the measured distance (NaN for non-finite input).
    pub fn try_normalize(&self) -> Result<Rotor, AlgebraError> {
        self.try_normalize_eps(NORMALIZE_TOLERANCE)
    }

    /// Like [`Rotor::try_normalize`] with an explicit tolerance on max |R R̃ − 1|.
    ///
    /// # Errors
    /// [`AlgebraError::FarFromGroup`].
    pub fn try_normalize_eps(&self, tolerance: f64) -> Result<Rotor, AlgebraError> {
        let distance = if self.coeffs.iter().all(|c| c.is_finite()) {
            self.unit_error()
        } else {
            f64::NAN
        };
        if !within(distance, tolerance) {
            return Err(AlgebraError::FarFromGroup {
                distance,
                tolerance,
            });
        }
        Ok(self.normalize())
    }
}

/// σ(i, j, a) < 0 for the matrix entry formula: σ = sign(eᵢ e_a) · sign(e_(i⊕a) eⱼ) (the
/// reverse of the last factor and its square cancel in a Euclidean signature).
fn matrix_sign_negative(a: u64, i: usize, j: usize) -> bool {
    let s1 = crate::algebra::blade::reorder_sign(1 << i, a);
    let s2 = crate::algebra::blade::reorder_sign((1 << i) ^ a, 1 << j);
    s1 * s2 < 0.0
}

/// Largest N whose sign table is cached (N²·2^(N−1) booleans: 288 KiB at N = 12).
const SIGN_TABLE_MAX_DIM: usize = 12;

/// The cached sign table of dimension `n`, indexed by (i·N + j)·2^(N−1) + a.
fn matrix_sign_table(n: usize) -> Option<&'static [bool]> {
    use std::sync::OnceLock;
    static TABLES: [OnceLock<Vec<bool>>; SIGN_TABLE_MAX_DIM + 1] =
        [const { OnceLock::new() }; SIGN_TABLE_MAX_DIM + 1];
    if n > SIGN_TABLE_MAX_DIM {
        return None;
    }
    let table = TABLES[n].get_or_init(|| {
        let len = super::even_len(n);
        let mut t = Vec::with_capacity(n * n * len);
        for i in 0..n {
            for j in 0..n {
                for ia in 0..len {
                    t.push(matrix_sign_negative(super::even_blade(n, ia), i, j));
                }
            }
        }
        t
    });
    Some(table.as_slice())
}

fn check_matrix_shape(q: &DMatrix<f64>) -> Result<(), AlgebraError> {
    if q.nrows() != q.ncols() {
        return Err(AlgebraError::NotSquare {
            rows: q.nrows(),
            cols: q.ncols(),
        });
    }
    AlgebraError::check_dimension("rotor", q.nrows(), MULTIVECTOR_MAX_DIM)?;
    if q.iter().any(|x| !x.is_finite()) {
        return Err(AlgebraError::NonFinite { what: "matrix" });
    }
    Ok(())
}

/// The orthogonal polar factor U Vᵀ, or None if the SVD fails or the matrix is singular.
///
/// nalgebra's SVD can turn to NaN on finite entries of extreme range, and its ordered form
/// then panics while sorting the singular values (entries from 1e-319 to 5e226 do it). So:
/// the unordered SVD (U Vᵀ needs no order), NaN checked here; and, since the factor does not change when `m` is scaled, on m / max |m_ij| with
/// entries below 1e-150 of the largest set to 0 (far below round-off), so that no square
/// overflows or falls into the subnormal range.
fn nearest_orthogonal(m: &DMatrix<f64>) -> Option<DMatrix<f64>> {
    let scale = m.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    if !scale.is_finite() || scale <= 0.0 {
        return None;
    }
    let scaled = m.map(|x| {
        let y = x / scale;
        if y.abs() < 1e-150 { 0.0 } else { y }
    });
    // Unordered: the ordered SVD sorts with `partial_cmp(..).expect(..)`, a panic on NaN.
    let svd = scaled.try_svd_unordered(true, true, f64::EPSILON, 200)?;
    // (f64::min skips NaN, so NaN is looked for on its own.)
    let values = &svd.singular_values;
    if values.iter().any(|s| s.is_nan()) || values.iter().any(|&s| s <= 0.0) {
        return None;
    }
    let q = svd.u? * svd.v_t?;
    q.iter().all(|x| x.is_finite()).then_some(q)
}

/// The 4D rotation matrix of the even coefficients: the product of the left- and
/// right-isoclinic matrices of the quaternion pair.
#[inline]
fn matrix_4d(coeffs: &[f64]) -> nalgebra::Matrix4<f64> {
    crate::algebra::Rotor4::<f64>::from_even_layout(super::layout(coeffs)).to_matrix()
}

/// Calls `set(i, j, Qᵢⱼ)` for every entry of the rotation matrix of the rotor with even
/// coefficients `coeffs` in dimension `n`.
pub(crate) fn fill_matrix(n: usize, coeffs: &[f64], mut set: impl FnMut(usize, usize, f64)) {
    match n {
        0 => {}
        1 => set(0, 0, 1.0),
        4 => {
            let q = matrix_4d(coeffs);
            for j in 0..4 {
                for i in 0..4 {
                    set(i, j, q[(i, j)]);
                }
            }
        }
        3 => {
            // Quaternion formula with q = w − x e23 + y e13 − z e12 (see nalgebra.rs).
            let w = coeffs[0];
            let (e12, e13, e23) = (
                coeffs[even_index(3, 0b011)],
                coeffs[even_index(3, 0b101)],
                coeffs[even_index(3, 0b110)],
            );
            let (x, y, z) = (-e23, e13, -e12);
            let m = [
                [
                    w * w + x * x - y * y - z * z,
                    2.0 * (x * y - w * z),
                    2.0 * (x * z + w * y),
                ],
                [
                    2.0 * (x * y + w * z),
                    w * w - x * x + y * y - z * z,
                    2.0 * (y * z - w * x),
                ],
                [
                    2.0 * (x * z - w * y),
                    2.0 * (y * z + w * x),
                    w * w - x * x - y * y + z * z,
                ],
            ];
            for (i, row) in m.iter().enumerate() {
                for (j, &x) in row.iter().enumerate() {
                    set(i, j, x);
                }
            }
        }
        _ => fill_matrix_blades(n, coeffs, set),
    }
}

/// [`fill_matrix`] through the even blades, any N ≥ 2.
pub(super) fn fill_matrix_blades(n: usize, coeffs: &[f64], mut set: impl FnMut(usize, usize, f64)) {
    // Q_ij = ⟨eᵢ R eⱼ R̃⟩₀ = Σ_a σ(i, j, a) R_a R_{a ⊕ eᵢ ⊕ eⱼ}: one pass over the
    // even blades per entry, with the signs σ from a cached bit table.
    let mask = (1u64 << (n - 1)) - 1;
    let len = super::even_len(n);
    let table = matrix_sign_table(n);
    let blades = super::even_blades(n);
    for i in 0..n {
        for j in 0..n {
            let m = (1u64 << i) ^ (1u64 << j);
            let mut acc = 0.0;
            for (ia, (&ra, &a)) in coeffs.iter().zip(blades).enumerate() {
                if ra == 0.0 {
                    continue;
                }
                let rb = coeffs[((a ^ m) & mask) as usize];
                let negative = match &table {
                    Some(t) => t[(i * n + j) * len + ia],
                    None => matrix_sign_negative(a, i, j),
                };
                acc += if negative { -ra * rb } else { ra * rb };
            }
            set(i, j, acc);
        }
    }
}

/// The rotor of an orthogonal matrix with det +1 (non-negative scalar part).
fn rotor_of_orthogonal(q: &DMatrix<f64>) -> Rotor {
    let n = q.nrows();
    match n {
        0 | 1 => Rotor::identity(n),
        2 => {
            let mut r = Rotor::identity(2);
            // Q = [[c, −s], [s, c]] turns e1 toward e2 by θ = atan2(s, c): R = cos θ/2 − sin θ/2 e12.
            let theta = q[(1, 0)].atan2(q[(0, 0)]);
            let (s, c) = (0.5 * theta).sin_cos();
            r.coeffs[0] = c;
            r.coeffs[1] = -s;
            r
        }
        3 => rotor_of_matrix_3d(q),
        _ => {
            let mut r = Rotor::identity(n);
            for p in planes_of_rotation(&Mat8::from_fn(n, n, |i, j| q[(i, j)])) {
                let (s, c) = (0.5 * p.theta).sin_cos();
                multiply_by_simple(&mut r, c, s, &p.u, &p.v);
            }
            r
        }
    }
}

/// Shepperd's method: pick the largest of w², x², y², z² from the trace and diagonal, so no
/// square root of a small number is taken (Shepperd, J. Guidance Control 1 (1978) 223).
fn rotor_of_matrix_3d(q: &DMatrix<f64>) -> Rotor {
    let (m00, m11, m22) = (q[(0, 0)], q[(1, 1)], q[(2, 2)]);
    let tr = m00 + m11 + m22;
    let (w, x, y, z);
    if tr >= m00 && tr >= m11 && tr >= m22 {
        let s = 2.0 * (1.0 + tr).max(0.0).sqrt();
        w = 0.25 * s;
        x = (q[(2, 1)] - q[(1, 2)]) / s;
        y = (q[(0, 2)] - q[(2, 0)]) / s;
        z = (q[(1, 0)] - q[(0, 1)]) / s;
    } else if m00 >= m11 && m00 >= m22 {
        let s = 2.0 * (1.0 + m00 - m11 - m22).max(0.0).sqrt();
        w = (q[(2, 1)] - q[(1, 2)]) / s;
        x = 0.25 * s;
        y = (q[(0, 1)] + q[(1, 0)]) / s;
        z = (q[(0, 2)] + q[(2, 0)]) / s;
    } else if m11 >= m22 {
        let s = 2.0 * (1.0 + m11 - m00 - m22).max(0.0).sqrt();
        w = (q[(0, 2)] - q[(2, 0)]) / s;
        x = (q[(0, 1)] + q[(1, 0)]) / s;
        y = 0.25 * s;
        z = (q[(1, 2)] + q[(2, 1)]) / s;
    } else {
        let s = 2.0 * (1.0 + m22 - m00 - m11).max(0.0).sqrt();
        w = (q[(1, 0)] - q[(0, 1)]) / s;
        x = (q[(0, 2)] + q[(2, 0)]) / s;
        y = (q[(1, 2)] + q[(2, 1)]) / s;
        z = 0.25 * s;
    }
    let sign = if w < 0.0 { -1.0 } else { 1.0 };
    let norm = (w * w + x * x + y * y + z * z).sqrt();
    let k = sign / norm;
    let mut r = Rotor::identity(3);
    r.coeffs[0] = k * w;
    r.coeffs[even_index(3, 0b110)] = -k * x;
    r.coeffs[even_index(3, 0b101)] = k * y;
    r.coeffs[even_index(3, 0b011)] = -k * z;
    r
}

/// Decomposes a rotation matrix into planes: each [`RawPlane`] turns `v` toward `u` by
/// `theta` ∈ (0, π] (so its rotor is exp((θ/2) u∧v) = cos θ/2 + sin θ/2 · u v).
///
/// The space splits by the sign of cos θ (eigenvectors of the symmetric part). On the part
/// turned by at most π/2 the planes come from the skew part of Q; on the part turned by more
/// than π/2 they come from the skew part of −Q, which turns by π − θ < π/2. Either way the
/// plane information is read from a well-conditioned rotation; directions left over in the
/// second part are rotations by exactly π and are paired arbitrarily.
pub(crate) fn planes_of_rotation(q: &Mat8) -> Planes {
    let n = q.nrows();
    let y = Mat8::from_fn(n, n, |i, j| (q[(i, j)] + q[(j, i)]) * 0.5);
    let (eigenvalues, eigenvectors) = y.symmetric_eigen();
    let mut plus: SmallVec<[usize; 8]> = SmallVec::new();
    let mut minus: SmallVec<[usize; 8]> = SmallVec::new();
    for (k, &lambda) in eigenvalues.iter().enumerate() {
        if lambda >= 0.0 {
            plus.push(k);
        } else {
            minus.push(k);
        }
    }
    let mut out = Planes::new();
    for (columns, flip) in [(plus, false), (minus, true)] {
        let m = columns.len();
        if m < 2 {
            continue;
        }
        let v = Mat8::from_fn(n, m, |i, k| eigenvectors[(i, columns[k])]);
        let mut qs = v.transpose().mul(q).mul(&v);
        if flip {
            qs = qs.scaled(-1.0);
        }
        // Skew part → bivector components in the subspace basis.
        let comps: SmallVec<[f64; 28]> = pairs(m)
            .map(|(i, j)| 0.5 * (qs[(i, j)] - qs[(j, i)]))
            .collect();
        debug_assert_eq!(comps.len(), bivector_len(m));
        let local = decompose_components(m, &comps);
        let mut covered: SmallVec<[Vec8; 8]> = SmallVec::new();
        for p in &local {
            // qs turns v toward u by δ. sin δ is the plane's magnitude in the skew part (read
            // there, not as uᵀ qs v − vᵀ qs u, where the unit diagonal swamps tiny angles);
            // cos δ comes from the symmetric part.
            let s = p.theta;
            let c = 0.5 * (dot(&p.u, &qs.mul_vec(&p.u)) + dot(&p.v, &qs.mul_vec(&p.v)));
            let delta = s.atan2(c);
            let (theta, pu, pv) = if flip {
                // Q = −qs turns v toward u by π + δ, i.e. u toward v by π − δ.
                (std::f64::consts::PI - delta, &p.v, &p.u)
            } else {
                (delta, &p.u, &p.v)
            };
            covered.push(p.u.clone());
            covered.push(p.v.clone());
            out.push(RawPlane {
                theta,
                u: v.mul_vec(pu),
                v: v.mul_vec(pv),
            });
        }
        if flip {
            // Directions of the −1 eigenspace not covered: rotations by exactly π.
            let mut rest: SmallVec<[Vec8; 8]> = SmallVec::new();
            for k in 0..m {
                let mut x: Vec8 = SmallVec::from_elem(0.0, m);
                x[k] = 1.0;
                for _ in 0..2 {
                    for b in covered.iter().chain(rest.iter()) {
                        let d = dot(b, &x);
                        x.iter_mut().zip(b).for_each(|(xi, bi)| *xi -= bi * d);
                    }
                }
                let nx = norm(&x);
                if nx > 0.5 {
                    x.iter_mut().for_each(|xi| *xi /= nx);
                    rest.push(x);
                }
            }
            for pair in rest.chunks_exact(2) {
                out.push(RawPlane {
                    theta: std::f64::consts::PI,
                    u: v.mul_vec(&pair[0]),
                    v: v.mul_vec(&pair[1]),
                });
            }
        }
    }
    out
}
