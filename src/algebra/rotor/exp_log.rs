//! Closed-form exponential and logarithm (never a truncated series).

use super::{
    EvenBuf, Rotor, even_index, even_len, even_product_into, get_4d, multiply_by_simple,
    multiply_even_by_simple,
};
use crate::algebra::bivector::pairs;
use crate::algebra::decompose::{RawPlane, decompose_components, self_dual_join, self_dual_split};
use crate::algebra::error::{assert_same_dim, check_finite, within};
use crate::algebra::{AlgebraError, Bivector, MULTIVECTOR_MAX_DIM, Vector};
use crate::numeric::{Mat8, Vec8};
use nalgebra::DMatrix;
use smallvec::SmallVec;

impl Bivector {
    /// Returns the rotor e^B in closed form, for any N.
    ///
    /// With the invariant decomposition B = Σₖ θₖ Pₖ into commuting unit planes,
    /// e^B = Πₖ (cos θₖ + sin θₖ Pₖ) (Roelfs & De Keninck 2023). N ≤ 3 uses the quaternion
    /// form, N = 4 the self-dual/anti-self-dual split (exact for isoclinic B), N ≥ 5 the
    /// deflation of [`Bivector::decompose`]. The rotor that turns by angle θ in the plane B̂
    /// is `(B̂ * (-θ / 2.0)).exp()`, or [`Rotor::from_rotation_bivector`].
    ///
    /// The result is a unit rotor whenever |B| ≤ `f64::MAX`/2. Beyond, a plane angle (or a
    /// sum in the 4D split) may overflow, and the coefficients are then NaN for N ≥ 3, as
    /// [`Bivector::exp_skew_matrix`]'s entries: an infinite angle has no value mod 2π.
    /// [`Bivector::try_exp`] returns an error there instead.
    ///
    /// # Panics
    /// If N > [`MULTIVECTOR_MAX_DIM`] (rotors store 2^(N−1) coefficients; see
    /// [`Bivector::try_exp`]).
    ///
    /// ```
    /// use rotorflow::algebra::Bivector;
    /// // e^0 = 1, and exp(π/2 e12) = e12.
    /// assert_eq!(Bivector::zero(4).exp().scalar(), 1.0);
    /// let r = Bivector::from_plane(4, 0, 1, std::f64::consts::FRAC_PI_2)?.exp();
    /// assert!((r.coefficient(0b11) - 1.0).abs() < 1e-15);
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    #[track_caller]
    pub fn exp(&self) -> Rotor {
        let n = self.dim();
        assert!(
            n <= MULTIVECTOR_MAX_DIM,
            "rotorflow: rotors are stored densely up to N = {MULTIVECTOR_MAX_DIM}, got {n}"
        );
        let c = self.as_slice();
        let mut r = Rotor::identity(n);
        match n {
            0 | 1 => {}
            2 => {
                let (s, co) = c[0].sin_cos();
                r.coeffs[0] = co;
                r.coeffs[1] = s;
            }
            3 => {
                let theta = self.norm();
                let (s, co) = theta.sin_cos();
                let k = if theta > 0.0 { s / theta } else { 1.0 };
                // Storage order (s, e₁₃, e₂₃, e₁₂).
                r.coeffs
                    .copy_from_slice(&[co, k * c[1], k * c[2], k * c[0]]);
            }
            // The quaternion exponential of each self-dual half.
            4 => {
                let b = crate::algebra::Bivector4::from_array(*super::layout(c));
                r.coeffs.copy_from_slice(&b.exp().to_even_layout());
            }
            _ => r = exp_of_planes(n, &decompose_components(n, c)),
        }
        r
    }

    /// For N = 4: `rotor` ← `rotor` · e^B, and the 4D bivector `c` ← R̃ C R with R = e^B, all
    /// through the quaternion pair of e^B (its angles evaluated once, the products as
    /// quaternion products): the update of a Lie–Poisson integrator, which turns the
    /// attitude and the momentum by one rotation.
    pub(crate) fn times_exp_and_reverse_sandwich_4(&self, rotor: &mut Rotor, c: &mut [f64]) {
        let e = crate::algebra::Bivector4::from_array(*super::layout(self.as_slice())).exp();
        let turned = e.reverse_sandwich(crate::algebra::Bivector4::from_array(*super::layout(c)));
        c.copy_from_slice(&turned.to_array());
        let r = crate::algebra::Rotor4::<f64>::from_even_layout(super::layout(&rotor.coeffs));
        rotor.coeffs.copy_from_slice(&r.compose(e).to_even_layout());
    }

    /// [`Bivector::exp`], or an error where it would panic or return NaN.
    ///
    /// ```
    /// use rotorflow::algebra::{AlgebraError, Bivector};
    /// let b = Bivector::from_plane(3, 0, 1, 0.5)?;
    /// assert_eq!(b.try_exp()?, b.exp());
    /// let huge = Bivector::from_components(3, &[f64::MAX, f64::MAX, 0.0])?;
    /// assert!(matches!(huge.try_exp(), Err(AlgebraError::AngleTooLarge { .. })));
    /// # Ok::<(), AlgebraError>(())
    /// ```
    ///
    /// # Errors
    /// [`AlgebraError::DimensionTooLarge`] if N > [`MULTIVECTOR_MAX_DIM`];
    /// [`AlgebraError::NonFinite`] for NaN or infinite components;
    /// [`AlgebraError::AngleTooLarge`] if |B| > `f64::MAX`/2.
    pub fn try_exp(&self) -> Result<Rotor, AlgebraError> {
        let n = self.dim();
        AlgebraError::check_dimension("rotor", n, MULTIVECTOR_MAX_DIM)?;
        check_finite(self.as_slice(), "bivector")?;
        let norm = self.norm();
        if !within(norm, f64::MAX / 2.0) {
            return Err(AlgebraError::AngleTooLarge { norm });
        }
        Ok(self.exp())
    }
}

/// e^B = Πₖ (cos θₖ + sin θₖ uₖ vₖ) from the planes θₖ uₖ∧vₖ of B's invariant decomposition
/// (how [`Bivector::exp`] forms it for N ≥ 5), for callers that need the planes too.
#[inline(never)]
pub(crate) fn exp_of_planes(n: usize, planes: &[RawPlane]) -> Rotor {
    let mut r = Rotor::identity(n);
    for p in planes {
        let (s, co) = p.theta.sin_cos();
        // e^{θ u∧v} = cos θ + sin θ u v (u ⟂ v): multiply on the right.
        multiply_by_simple(&mut r, co, s, &p.u, &p.v);
    }
    r
}

/// [`exp_of_planes`] on stack storage (N ≤ 6 without the heap).
fn even_exp_of_planes(n: usize, planes: &[RawPlane]) -> EvenBuf {
    let mut r = even_identity(n);
    for p in planes {
        let (s, co) = p.theta.sin_cos();
        multiply_even_by_simple(n, &mut r, co, s, &p.u, &p.v);
    }
    r
}

/// The even coefficients of 1.
fn even_identity(n: usize) -> EvenBuf {
    let mut r: EvenBuf = SmallVec::from_elem(0.0, even_len(n));
    r[0] = 1.0;
    r
}

/// The even coefficients of e^B for N ≥ 5, exactly those of [`Bivector::try_exp`], on stack
/// storage for N ≤ 6 (rotors keep only N ≤ 5 inline), with its errors.
pub(crate) fn exp_even(b: &Bivector) -> Result<EvenBuf, AlgebraError> {
    let n = b.dim();
    debug_assert!(n >= 5, "the closed forms of N ≤ 4 are Bivector::exp's");
    AlgebraError::check_dimension("rotor", n, MULTIVECTOR_MAX_DIM)?;
    check_finite(b.as_slice(), "bivector")?;
    let norm = b.norm();
    if !within(norm, f64::MAX / 2.0) {
        return Err(AlgebraError::AngleTooLarge { norm });
    }
    Ok(even_exp_of_planes(
        n,
        &decompose_components(n, b.as_slice()),
    ))
}

/// [`Rotor::log`] for N ≥ 5 of the rotor with even coefficients `r` in dimension `n`, on
/// stack storage for N ≤ 6.
pub(crate) fn log_even(n: usize, r: &[f64]) -> Bivector {
    debug_assert!(n >= 5, "the closed forms of N ≤ 4 are Rotor::log's");
    log_general(n, r)
}

/// 4D: B = aF + bG (self-dual and anti-self-dual halves, |α| = a, |β| = b) gives
/// e^B = ½(cos 2a + cos 2b) + ½(cos 2b − cos 2a) I + ½ sin 2a F̂ + ½ sin 2b Ĝ, with F̂, Ĝ the unit
/// directions (F̂² = −4P₋, Ĝ² = −4P₊, P± = (1 ± I)/2). No decomposition and no division by
/// a − b.
#[cfg(test)]
pub(super) fn exp_4d(c: &[f64], r: &mut Rotor) {
    let (alpha, beta) = self_dual_split(c);
    let a = crate::numeric::scaled_norm(&alpha);
    let b = crate::numeric::scaled_norm(&beta);
    let (sa, ca) = (2.0 * a).sin_cos();
    let (sb, cb) = (2.0 * b).sin_cos();
    // ½ sin 2a · α/|α| with the a → 0 limit sin(2a)/(2a) → 1.
    let ka = if a > 0.0 { 0.5 * sa / a } else { 1.0 };
    let kb = if b > 0.0 { 0.5 * sb / b } else { 1.0 };
    let f = [ka * alpha[0], ka * alpha[1], ka * alpha[2]];
    let g = [kb * beta[0], kb * beta[1], kb * beta[2]];
    super::set_4d(r, 0.5 * (ca + cb), self_dual_join(f, g), 0.5 * (cb - ca));
}

impl Bivector {
    /// Returns the matrix exponential expm(\[B\]) of the skew matrix of B: a rotation matrix,
    /// in O(N³) for any N (no rotor, so also above the rotor limit).
    ///
    /// Small rotations (‖\[B\]‖₂ ≤ 0.82 by the bound min(‖A‖₁, ‖A²‖₁^½), every integrator
    /// step): the Taylor polynomial of the lowest degree m ∈ {6, 9, 12, 16} whose truncation
    /// error is below the unit round-off, by Paterson–Stockmeyer (3 to 6 products, no solve;
    /// Higham, *Functions of Matrices*, 2008, §4.4.3), a rotation to round-off because the
    /// truncation is. Up to ‖\[B\]‖₁ ≈ 5.37: the diagonal Padé approximant
    /// r_m(A) = q_m(A)⁻¹ p_m(A) of the degree m ∈ {3, 5, 7, 9, 13} that Higham's bound
    /// selects (Higham, SIAM J. Matrix Anal. Appl. 26 (2005) 1179; backward error below the
    /// unit round-off). For skew A,
    /// q_m(A) = p_m(−A) = p_m(A)ᵀ, so r_m(A) is orthogonal in exact arithmetic: a rotation
    /// to round-off, never a truncated series that leaves the group. Larger rotations use
    /// the spectral form expm(A) = V diag(cos θₖ) Vᵀ + A V diag(sin θₖ/θₖ) Vᵀ from the
    /// eigen-decomposition −A² = V diag(θₖ²) Vᵀ, which stays orthogonal to ε at any angle
    /// (scaling and squaring would not). The rotation matrix of the rotor e^A is expm(2\[A\])
    /// (exp(−θB̂/2) ↔ expm(\[θB̂\]ᵀ); see the Conventions chapter of the rotorflow book).
    ///
    /// Finite and orthogonal whenever |B| ≤ `f64::MAX`/2; beyond, a plane angle may overflow
    /// and the entries are then NaN (as for [`Bivector::exp`]).
    ///
    /// ```
    /// use rotorflow::algebra::Bivector;
    /// let b = Bivector::from_components(4, &[0.3, -0.2, 0.5, 0.1, 0.7, -0.4])?;
    /// let q = b.exp_skew_matrix();
    /// let expected = (&b * 0.5).exp().to_matrix(); // the rotor exp(B/2) has matrix expm([B])
    /// assert!((q - expected).amax() < 1e-14);
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    pub fn exp_skew_matrix(&self) -> DMatrix<f64> {
        let n = self.dim();
        // N = 5 … 8 on stack matrices (nalgebra's unrolled fixed-size products, the solve
        // on fixed-length rows); the same forms and the same choices.
        let fixed = match n {
            5 => self.exp_skew_matrix_fixed::<5>(),
            6 => self.exp_skew_matrix_fixed::<6>(),
            7 => self.exp_skew_matrix_fixed::<7>(),
            8 => self.exp_skew_matrix_fixed::<8>(),
            _ => None,
        };
        if let Some(q) = fixed {
            return q;
        }
        let a = self.to_skew_matrix();
        let norm1 = crate::numeric::norm1(&a);
        if norm1 == 0.0 {
            return DMatrix::identity(n, n);
        }
        // ‖[B]‖₁ can overflow while every plane angle is representable: the plane-by-plane
        // form scales, so it takes that case too.
        if !norm1.is_finite() || norm1 > crate::numeric::PADE_MAX_NORM {
            return self.exp_skew_matrix_by_planes();
        }
        // Small rotations (integrator steps): the Taylor form needs no solve.
        if let Some(q) = crate::numeric::expm_skew_taylor(&a, norm1) {
            return q;
        }
        crate::numeric::expm_skew(&a, norm1).unwrap_or_else(|| crate::numeric::expm_spectral(&a))
    }

    /// [`Bivector::exp_skew_matrix`] for N = D on the stack; `None` where the run-time route
    /// decides (zero, beyond the Padé range, a singular denominator).
    fn exp_skew_matrix_fixed<const D: usize>(&self) -> Option<DMatrix<f64>> {
        let a = self.to_skew_smatrix::<D>();
        let norm1 = crate::numeric::norm1(&a);
        if norm1 == 0.0 || !norm1.is_finite() || norm1 > crate::numeric::PADE_MAX_NORM {
            return None;
        }
        let q = crate::numeric::expm_skew_taylor(&a, norm1)
            .or_else(|| crate::numeric::expm_skew_fixed(&a, norm1))?;
        Some(DMatrix::from_column_slice(D, D, q.as_slice()))
    }

    /// expm(\[B\]) plane by plane from the invariant decomposition: on each plane θ u∧v
    /// (\[B\] v = θ u) a rotation by θ, Q = 1 + Σ (cos θ − 1)(u uᵀ + v vᵀ) + sin θ (u vᵀ − v uᵀ).
    /// Each angle is reduced on its own, so Q is orthogonal to ε at any angle.
    fn exp_skew_matrix_by_planes(&self) -> DMatrix<f64> {
        let n = self.dim();
        let mut q = DMatrix::identity(n, n);
        for p in decompose_components(n, self.as_slice()) {
            let (s, c) = p.theta.sin_cos();
            for i in 0..n {
                for j in 0..n {
                    q[(i, j)] += (c - 1.0) * (p.u[i] * p.u[j] + p.v[i] * p.v[j])
                        + s * (p.u[i] * p.v[j] - p.v[i] * p.u[j]);
                }
            }
        }
        q
    }
}

impl Rotor {
    /// Returns exp(−Θ/2): the rotor that turns by θₖ in each plane of the rotation bivector
    /// Θ = Σ θₖ Pₖ (the attitude convention of the rotorflow book's Conventions chapter; for
    /// Θ = θ e₁₂ it turns e₁ toward e₂).
    ///
    /// Over a step h with constant body angular velocity ω, the attitude advances as
    /// R ← R · `Rotor::from_rotation_bivector(&(ω * h))`.
    ///
    /// # Panics
    /// If N > [`MULTIVECTOR_MAX_DIM`] (see [`Rotor::try_from_rotation_bivector`]).
    #[track_caller]
    pub fn from_rotation_bivector(theta: &Bivector) -> Rotor {
        (theta * -0.5).exp()
    }

    /// [`Rotor::from_rotation_bivector`], or an error where [`Bivector::try_exp`] gives one.
    ///
    /// # Errors
    /// As [`Bivector::try_exp`] for −Θ/2.
    pub fn try_from_rotation_bivector(theta: &Bivector) -> Result<Rotor, AlgebraError> {
        (theta * -0.5).try_exp()
    }

    /// Returns the rotation bivector Θ = −2 log R, so that
    /// `Rotor::from_rotation_bivector(&r.rotation_bivector()) == r`; its plane magnitudes are
    /// the rotation angles (in \[0, 2π\], at most one above π).
    pub fn rotation_bivector(&self) -> Bivector {
        self.log() * -2.0
    }

    /// Returns the principal logarithm: the bivector B of least norm with e^B = R.
    ///
    /// Every plane's half-angle lies in \[0, π/2\], except that one plane (the largest) lies in
    /// (π/2, π] when R is on the "negative sheet" of Spin(N) over SO(N). So log(e^B) = B
    /// whenever every plane magnitude of B is below π/2, i.e. every rotation angle of
    /// `exp(−Θ/2)` is below π. At exactly isoclinic rotations by π the logarithm is not
    /// unique and one is returned.
    ///
    /// N ≤ 3: quaternion logarithm; N = 4: the logarithms of the two SU(2) factors of
    /// Spin(4) (the self-dual split); N ≥ 5: the planes of the rotation matrix, found
    /// separately in the subspaces turned by less and by more than π/2 so that angles near π
    /// stay exact, then the sign of the rotor fixes the branch. The matrix carries the planes
    /// with absolute precision only (small angles, rotors near −1), so that estimate is
    /// refined by Newton steps against the rotor itself (the residual e^(−B/2) R e^(−B/2)
    /// and the inverse of the symmetric dexp in the frame of B's invariant decomposition),
    /// which restores relative precision at every scale.
    ///
    /// # Accuracy
    /// exp(log R) = R to a few ulp for every rotor. log(exp B) = B to ~1e-15 relative, except
    /// near isoclinic rotations by π where the logarithm itself is ill-conditioned (condition
    /// number ~ 1/δ for two angles π − δ): there any logarithm returned still satisfies
    /// exp(log R) = R.
    pub fn log(&self) -> Bivector {
        let n = self.dim;
        let mut out = Bivector::zero(n);
        match n {
            0 | 1 => {}
            2 => out.as_mut_slice()[0] = self.coeffs[1].atan2(self.coeffs[0]),
            3 => {
                let b = self.bivector_part();
                let nb = b.norm();
                let phi = nb.atan2(self.coeffs[0]);
                if nb > 0.0 {
                    out = b * (phi / nb);
                } else if self.coeffs[0] < 0.0 {
                    // R = −1: any plane at half-angle π.
                    out.as_mut_slice()[0] = std::f64::consts::PI;
                }
            }
            4 => out = log_4d(self),
            _ => out = log_general(n, &self.coeffs),
        }
        out
    }

    /// Returns the rotation a fraction `t` of the way from `self` to `other` along the
    /// shorter arc: R and −R are the same rotation, so `other` is first given the sign that
    /// makes ⟨R̃₁R₂⟩₀ ≥ 0, and then the path is [`Rotor::slerp_spinor`]. Every rotation angle
    /// of the path's generator is then at most π, and `slerp(a, b, t)` and `slerp(a, −b, t)`
    /// are the same rotor. `t = 0` gives `self`; `t = 1` gives `other` or `−other` (the same
    /// rotation).
    ///
    /// ```
    /// use rotorflow::algebra::{Bivector, Rotor};
    /// let a = Rotor::identity(3);
    /// let b = Bivector::from_plane(3, 0, 1, 0.4)?.exp(); // turns by −0.8 in e12
    /// let minus_b = Rotor::from_multivector_unchecked(&(b.to_multivector() * -1.0));
    /// let (m1, m2) = (a.slerp(&b, 0.5), a.slerp(&minus_b, 0.5));
    /// assert!((m1.to_matrix() - m2.to_matrix()).amax() < 1e-15);
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    ///
    /// # Panics
    /// If the dimensions differ.
    #[track_caller]
    pub fn slerp(&self, other: &Rotor, t: f64) -> Rotor {
        assert_same_dim(self.dim, other.dim);
        // ⟨R̃₁R₂⟩₀ is the plain dot product of the coefficients in a Euclidean signature.
        let d: f64 = self
            .coeffs
            .iter()
            .zip(&other.coeffs)
            .map(|(a, b)| a * b)
            .sum();
        if d < 0.0 {
            self.slerp_spinor(&other.clone().scaled(-1.0), t)
        } else {
            self.slerp_spinor(other, t)
        }
    }

    /// Returns the rotor a fraction `t` of the way from `self` to `other` along the geodesic
    /// of Spin(N): self · exp(t · log(self⁻¹ · other)). `t = 0` gives `self`, `t = 1` gives
    /// `other` exactly as given.
    ///
    /// This interpolates spinors, not rotations: from R₁ to −R₁ (the same rotation) it turns
    /// by 2π, and from R₁ to −R₂ it takes the longer arc of the rotation. Use it where the
    /// sign of the rotor matters (spinor transport); [`Rotor::slerp`] is the rotation
    /// interpolation.
    ///
    /// # Panics
    /// If the dimensions differ.
    #[track_caller]
    pub fn slerp_spinor(&self, other: &Rotor, t: f64) -> Rotor {
        let delta = self.reverse().compose(other);
        self.compose(&(delta.log() * t).exp())
    }
}

/// 4D logarithm through Spin(4) ≅ SU(2) × SU(2): with R = s + b + pI, the two factors have
/// scalar parts s ∓ p and vector parts the (anti-)self-dual coordinates of b.
fn log_4d(r: &Rotor) -> Bivector {
    let (s, b, p) = get_4d(r);
    let (alpha, beta) = self_dual_split(&b);
    let na = crate::numeric::scaled_norm(&alpha);
    let nb = crate::numeric::scaled_norm(&beta);
    // 2a = atan2(2|α|, s − p), 2b = atan2(2|β|, s + p); then B's halves are a α̂ and b β̂.
    let a2 = (2.0 * na).atan2(s - p);
    let b2 = (2.0 * nb).atan2(s + p);
    let scale = |x: [f64; 3], nx: f64, half_angle2: f64| -> [f64; 3] {
        if nx > 0.0 {
            let k = 0.5 * half_angle2 / nx;
            [k * x[0], k * x[1], k * x[2]]
        } else {
            // No direction: the factor is ±1; −1 needs any unit direction at angle π.
            [0.5 * half_angle2, 0.0, 0.0]
        }
    };
    let f = scale(alpha, na, a2);
    let g = scale(beta, nb, b2);
    Bivector::from_storage(4, SmallVec::from_slice(&self_dual_join(f, g)))
}

/// General logarithm: the planes of the rotation matrix give a first estimate, which
/// [`refine_log`] then corrects against the rotor itself.
///
/// On the negative sheet (R = −e^B′ with every half-angle of B′ in \[0, π/2\]) B′ is refined
/// as the logarithm of −R, where the planes are well conditioned (a rotor near −1 is −e^B′
/// with B′ small), and only then is its largest plane moved from φ to φ − π, so that a plane
/// at half-angle π − η keeps its direction to relative precision.
// Kept out of line: its inline matrices would enlarge the stack frame of every Rotor::log.
#[inline(never)]
fn log_general(n: usize, r: &[f64]) -> Bivector {
    let (b0, negative) = log_from_matrix(n, r);
    if !negative {
        return refine_log(n, r, b0);
    }
    let minus_r: EvenBuf = r.iter().map(|c| c * -1.0).collect();
    let b = refine_log(n, &minus_r, b0);
    let planes = decompose_components(n, b.as_slice());
    let Some(p) = planes.iter().max_by(|a, c| a.theta.total_cmp(&c.theta)) else {
        // R = −1: any plane at half-angle π.
        let mut out = Bivector::zero(n);
        out.as_mut_slice()[0] = std::f64::consts::PI;
        return out;
    };
    // The plane θ u∧v of B′ becomes (θ − π) u∧v, which costs the least norm.
    let u = Vector::from_storage(p.u.clone());
    let v = Vector::from_storage(p.v.clone());
    &b + &(u.wedge(&v) * -std::f64::consts::PI)
}

/// Newton refinement of a logarithm estimate B of R.
///
/// The matrix route carries the planes with absolute precision only (the skew part of
/// Q = I + O(θ) for small angles, the skew part of Q ≈ −I on a plane turned by nearly π), so
/// B is corrected with the rotor: the residual M = e^(−B/2) R e^(−B/2) = e^(g(ad_B) Δ) is near
/// 1, its bivector part δ = ⟨M⟩₂ carries the error with relative precision, and
/// Δ = g(ad_B)⁻¹ δ with g(x) = sinh(x/2)/(x/2) (the symmetric form of dexp), applied in the
/// frame of B's invariant decomposition where ad_B is block diagonal with eigenvalues
/// ±2i(θₖ ± θₗ) and ±2iθₖ. A step is kept only if it lowers |δ|.
fn refine_log(n: usize, r: &[f64], b0: Bivector) -> Bivector {
    let residual = |b: &Bivector| -> Option<(Bivector, f64)> {
        // e^B for N ≥ 5, as Bivector::exp forms it.
        let h = even_exp_of_planes(n, &decompose_components(n, (b * -0.5).as_slice()));
        let mut hr: EvenBuf = SmallVec::from_elem(0.0, r.len());
        even_product_into(n, &h, r, &mut hr);
        let mut m: EvenBuf = SmallVec::from_elem(0.0, r.len());
        even_product_into(n, &hr, &h, &mut m);
        if m[0] <= 0.0 {
            return None;
        }
        let mut d = Bivector::zero(n);
        for (k, (i, j)) in pairs(n).enumerate() {
            d.as_mut_slice()[k] = m[even_index(n, (1 << i) | (1 << j))];
        }
        let nd = d.norm();
        nd.is_finite().then_some((d, nd))
    };
    let mut b = b0;
    let Some((mut delta, mut nd)) = residual(&b) else {
        return b;
    };
    for _ in 0..8 {
        if nd == 0.0 {
            break;
        }
        let cand = &b + &inverse_symmetric_dexp(&b, &delta);
        match residual(&cand) {
            Some((d, n)) if n < nd => {
                b = cand;
                delta = d;
                nd = n;
            }
            _ => break,
        }
    }
    b
}

/// Returns g(ad_B)⁻¹ δ, g(x) = sinh(x/2)/(x/2), through the invariant decomposition of B:
/// in its orthonormal frame (uₖ, vₖ per plane, then a complement) the 2×2 block of δ between
/// planes k and l splits into the part commuting with the plane's J (factor
/// sin(θₖ − θₗ)/(θₖ − θₗ)) and the part anticommuting (sin(θₖ + θₗ)/(θₖ + θₗ)); between plane
/// k and the complement the factor is sin θₖ/θₖ. Factors near a zero (an isoclinic pair at
/// π, where the logarithm is ill-conditioned) are clamped.
fn inverse_symmetric_dexp(b: &Bivector, delta: &Bivector) -> Bivector {
    let n = b.dim();
    let planes = decompose_components(n, b.as_slice());
    // Frame columns and, per column, its plane (index) or None for the complement.
    let mut frame = Mat8::zeros(n, n);
    let mut role: SmallVec<[Option<usize>; 8]> = SmallVec::new();
    for (k, p) in planes.iter().enumerate() {
        frame.column_mut(role.len()).copy_from_slice(&p.u);
        role.push(Some(k));
        frame.column_mut(role.len()).copy_from_slice(&p.v);
        role.push(Some(k));
    }
    for i in 0..n {
        if role.len() == n {
            break;
        }
        let mut x: Vec8 = SmallVec::from_elem(0.0, n);
        x[i] = 1.0;
        for _ in 0..2 {
            for f in 0..role.len() {
                let col = frame.column(f);
                let d: f64 = col.iter().zip(&x).map(|(a, c)| a * c).sum();
                for (xi, fi) in x.iter_mut().zip(col) {
                    *xi -= d * fi;
                }
            }
        }
        let nx = x.iter().map(|c| c * c).sum::<f64>().sqrt();
        if nx > 0.5 {
            x.iter_mut().for_each(|c| *c /= nx);
            frame.column_mut(role.len()).copy_from_slice(&x);
            role.push(None);
        }
    }
    let m = role.len();
    let f = Mat8::from_fn(n, m, |i, j| frame[(i, j)]);
    let mut a = Mat8::zeros(n, n);
    for ((i, j), &c) in pairs(n).zip(delta.as_slice()) {
        a[(i, j)] = c;
        a[(j, i)] = -c;
    }
    let x = f.transpose().mul(&a).mul(&f);
    // sin φ / φ, clamped away from zero.
    let inv = |phi: f64| -> f64 {
        let g = if phi == 0.0 { 1.0 } else { phi.sin() / phi };
        if g.abs() < 0.05 { 1.0 } else { 1.0 / g }
    };
    let mut y = Mat8::zeros(m, m);
    for i in 0..m {
        for j in (i + 1)..m {
            y[(i, j)] = match (role[i], role[j]) {
                (Some(k), Some(l)) if k == l => x[(i, j)],
                (Some(k), Some(l)) => {
                    // Handled block-wise from the block's top-left entry.
                    if i % 2 != 0 || j % 2 != 0 {
                        continue;
                    }
                    let (tk, tl) = (planes[k].theta, planes[l].theta);
                    let (uu, uv, vu, vv) =
                        (x[(i, j)], x[(i, j + 1)], x[(i + 1, j)], x[(i + 1, j + 1)]);
                    let fp = inv(tk - tl);
                    let fm = inv(tk + tl);
                    let (pa, pb) = (0.5 * (uu + vv) * fp, 0.5 * (uv - vu) * fp);
                    let (mc, md) = (0.5 * (uu - vv) * fm, 0.5 * (uv + vu) * fm);
                    y[(i, j + 1)] = pb + md;
                    y[(i + 1, j)] = -pb + md;
                    y[(i + 1, j + 1)] = pa - mc;
                    pa + mc
                }
                (Some(k), None) => x[(i, j)] * inv(planes[k].theta),
                (None, Some(l)) => x[(i, j)] * inv(planes[l].theta),
                (None, None) => x[(i, j)],
            };
        }
    }
    for i in 0..m {
        for j in (i + 1)..m {
            y[(j, i)] = -y[(i, j)];
        }
    }
    let s = f.mul(&y).mul(&f.transpose());
    let mut out = Bivector::zero(n);
    for ((i, j), c) in pairs(n).zip(out.as_mut_slice().iter_mut()) {
        *c = 0.5 * (s[(i, j)] - s[(j, i)]);
    }
    out
}

/// Logarithm through the planes of the rotation matrix (absolute precision): B with every
/// half-angle in \[0, π/2\] and whether R = −e^B (else R = e^B).
fn log_from_matrix(n: usize, r: &[f64]) -> (Bivector, bool) {
    let mut q = Mat8::zeros(n, n);
    super::convert::fill_matrix(n, r, |i, j, x| q[(i, j)] = x);
    let planes = super::convert::planes_of_rotation(&q);
    // Candidate: half-angle θ/2 on each plane x→y, i.e. B = Σ (θ/2) y∧x.
    let mut cand = even_identity(n);
    for p in &planes {
        let (s, c) = (0.5 * p.theta).sin_cos();
        // exp((θ/2) y∧x) = cos + sin · y x.
        multiply_even_by_simple(n, &mut cand, c, s, &p.u, &p.v);
    }
    // ⟨R̃′ R⟩₀ is the plain dot product of the coefficients in a Euclidean signature.
    let d: f64 = cand.iter().zip(r.iter()).map(|(a, b)| a * b).sum();
    // Every half-angle in [0, π/2]: R = ±e^B with the sign of d.
    let mut out = Bivector::zero(n);
    for p in &planes {
        // (θ/2)(y∧x) with y = p.u, x = p.v.
        let y = Vector::from_storage(p.u.clone());
        let x = Vector::from_storage(p.v.clone());
        out += &(y.wedge(&x) * (0.5 * p.theta));
    }
    (out, d < 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exp_4d_matches_product_of_plane_rotors() {
        let b = Bivector::from_components(4, &[0.3, -0.2, 0.5, 0.1, 0.7, -0.4]).unwrap();
        let r = b.exp();
        let mut g = Rotor::identity(4);
        for p in decompose_components(4, b.as_slice()) {
            let (s, c) = p.theta.sin_cos();
            multiply_by_simple(&mut g, c, s, &p.u, &p.v);
        }
        for i in 0..8 {
            assert!((r.coeffs[i] - g.coeffs[i]).abs() < 1e-15, "{r:?} vs {g:?}");
        }
    }
}
