//! The discrete Moser–Veselov top: an integrable discretisation of the free body in any N.

use super::splitting::kick;
use super::{DynamicsError, Iterations, SplittingOrder};
use crate::algebra::pairs;
use crate::dynamics::{RigidBody, Torque};
use crate::numeric::{lu_apply, lu_factor, lu_solve};
use smallvec::SmallVec;

/// An N×N matrix, column-major; inline (no heap) up to N = 8.
type Mat = SmallVec<[f64; 64]>;
/// The K×K Newton matrix, K = N(N−1)/2; inline up to N = 8 (K = 28).
type Jacobian = SmallVec<[f64; 784]>;
/// K packed skew components; inline up to N = 8.
type Packed = SmallVec<[f64; 28]>;

/// The discrete Moser–Veselov top (Moser and Veselov, *Discrete versions of some classical
/// integrable systems and factorization of matrix polynomials*, Commun. Math. Phys. 139
/// (1991) 217; on SO(N): Lewis and Simo, Fields Inst. Commun. 10 (1996) 121; McLachlan and
/// Zanna, *The discrete Moser–Veselov algorithm for the free rigid body, revisited*, Found.
/// Comput. Math. 5 (2005) 87), for a physical inertia I(ω) = Jω + ωJ in any N.
///
/// In matrix form, with the body momentum M = −\[L\] (so that M = ΩJ + JΩ for the body
/// velocity Ω = −\[ω\] of Q̇ = QΩ, J = diag(Jᵢ) the principal second moments), one step solves
///
/// h Mₖ = Uₖ J − J Uₖᵀ
///
/// for the rotation Uₖ ∈ SO(N) near the identity, then sets Mₖ₊₁ = Uₖᵀ Mₖ Uₖ and
/// Qₖ₊₁ = Qₖ Uₖ. The step is symmetric and of order 2. Why it conserves so much: with
/// B = UₖJ, h Mₖ = B − Bᵀ, and BᵀB = J², the matrix J² − λhMₖ − λ² equals
/// (Bᵀ − λ)(B + λ), whereas Uₖ(J² − λhMₖ₊₁ − λ²)Uₖᵀ equals (B + λ)(Bᵀ − λ): the two have the
/// same spectrum for every λ. So the spectrum of M + μJ² is the same before and after the
/// step, for every μ: every Casimir of L and every Manakov integral
/// ([`manakov_integrals`](crate::dynamics::manakov_integrals)) is conserved, to the solver's
/// tolerance and round-off. The energy is kept as well (in 3D a combination of the two
/// integrals; for N = 3 … 8 its drift is measured at round-off), and the space-frame momentum
/// QMQᵀ because Uₖ is orthogonal.
///
/// The rotation is solved for in the Cayley form U = (1 − A)⁻¹(1 + A), A skew, by Newton's
/// method on the N(N−1)/2 components of A, starting from A = ½h Ω(Mₖ). The Cayley form keeps
/// U orthogonal to round-off whatever the iterate, and U − 1 = 2(1 − A)⁻¹A is formed without
/// cancellation, so the residual h M − (UJ − JUᵀ) is measured relative to hM rather than to
/// J. It reaches a few ulps of hM in two iterations at h|ω| = 0.01 and 3–4 at
/// h|ω| = 0.5 (measured for N = 3 … 5); above N = 5 the Newton matrix is reused between
/// iterations while they contract fast (the chord method), and the iteration goes on until
/// the residual reaches an ulp or stops contracting (a residual of a few ulps left every step
/// biases the integrals by as much, which adds up over 10⁶ steps): three iterations at
/// h|ω| = 0.01 and about four at 0.5 for N = 6 … 8. No heap for N ≤ 8.
///
/// A solution exists only for steps small against the momentum: |hM|_F ≤ 2|J|_F is
/// necessary (|UJ − JUᵀ|_F ≤ 2|J|_F), and Newton's method is required to converge from
/// the start above. A step beyond either returns
/// [`DynamicsError::NoDiscreteSolution`]; one whose iteration stalls above the tolerance
/// returns [`DynamicsError::SolverDidNotConverge`]. Neither leaves NaN in the body.
///
/// With a torque, each step is kick(h/2) · MV(h) · kick(h/2), the kick being the torque's
/// flow with the attitude frozen (midpoint rule), as in [`Splitting`](super::Splitting):
/// order 2 for torques that do not depend on L; the integrals are then no longer invariants
/// of the motion.
///
/// [`MoserVeselov::yoshida4`] composes three steps (Yoshida's triple jump) for order 4, and
/// [`MoserVeselov::composed`] any composition of [`SplittingOrder`] (orders 4, 6 and 8 in
/// any N); each substep conserves the same integrals.
///
/// Needs a physical inertia map (built from a mass tensor or principal second moments);
/// others return [`DynamicsError::NonPhysicalInertia`].
///
/// ```
/// use rotorflow::prelude::*;
/// use rotorflow::dynamics::{Invariants, MoserVeselov};
/// let inertia = InertiaMap::from_principal_second_moments(&[0.5, 0.8, 1.3, 2.1, 2.6])?;
/// let l = Bivector::from_components(5, &[0.9, -0.4, 0.3, 0.7, -0.2, 0.5, 0.1, -0.6, 0.8, 0.2])?;
/// let mut body = RigidBody::from_body_momentum(inertia, Attitude::identity(5), &l)?;
/// let start = Invariants::of(&body);
/// let mut mv = MoserVeselov::new();
/// for k in 0..1000 {
///     mv.step(&mut body, k as f64 * 0.05, 0.05, &Free)?;
/// }
/// // Every Manakov integral (the Casimirs among them) and the energy, to round-off.
/// let drift = Invariants::of(&body).drift_from(&start);
/// assert!(drift.manakov < 1e-13 && drift.energy < 1e-13);
/// assert_eq!(start.manakov.len(), 6);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct MoserVeselov {
    /// The symmetric composition of steps (Strang's single step for the plain map).
    composition: SplittingOrder,
    /// The order of the preprocessed step (modified moments of inertia, 3D): 2 for none.
    preprocessed: u32,
    iterations: Iterations,
}

impl Default for MoserVeselov {
    /// The second-order step, at most 30 Newton iterations per step.
    fn default() -> Self {
        MoserVeselov {
            composition: SplittingOrder::Strang,
            preprocessed: 2,
            iterations: Iterations::new(30),
        }
    }
}

impl MoserVeselov {
    /// Returns the second-order Moser–Veselov step.
    pub fn new() -> Self {
        Self::default()
    }

    /// Returns Yoshida's fourth-order composition of three Moser–Veselov steps (Yoshida,
    /// Phys. Lett. A 150 (1990) 262).
    pub fn yoshida4() -> Self {
        Self::composed(SplittingOrder::Yoshida4)
    }

    /// Returns the symmetric composition `composition` of Moser–Veselov steps: order 4
    /// ([`SplittingOrder::Yoshida4`], [`SplittingOrder::Suzuki4`]), 6
    /// ([`SplittingOrder::KahanLi6`]) or 8 ([`SplittingOrder::KahanLi8`]) in any N. Every
    /// substep is the integrable map, so the composition keeps every Manakov integral, the
    /// Casimirs and the energy to round-off, as the single step does.
    pub fn composed(composition: SplittingOrder) -> Self {
        MoserVeselov {
            composition,
            ..Self::default()
        }
    }

    /// Returns the preprocessed Moser–Veselov step of order 4 or 6 for bodies in 3D (2 is the
    /// plain step): the same map with modified moments of inertia.
    ///
    /// Why it works: in 3D the discrete step keeps the body's two integrals, so it follows
    /// the exact orbits and differs from the exact flow by its speed along them, a function
    /// of h and the integrals alone; McLachlan and Zanna (*The discrete Moser–Veselov
    /// algorithm for the free rigid body, revisited*, Found. Comput. Math. 5 (2005) 87)
    /// derived that modified flow by backward error analysis and preprocessed the step to
    /// raise its order. Hairer and Vilmart (*Preprocessed discrete Moser–Veselov algorithm for
    /// the full dynamics of a rigid body*, J. Phys. A 39 (2006) 13225) wrote the preprocessing
    /// as modified moments of inertia, a series in h² whose coefficients are functions of the
    /// energy H and of |L|², correct order by order for the momentum and the attitude; the
    /// coefficients of their h² and h⁴ terms are the ones used here:
    /// 1/Ĩₖ = c/Iₖ + d with c = 1 + h²(ΣIₖ/(6ΠIₖ) |L|²/2 − Σ(1/Iₖ) H/3) + O(h⁴) and
    /// d = h²(−|L|²/(6ΠIₖ) + ΣIₖ/(6ΠIₖ) H) + O(h⁴). The measured orders against the closed
    /// form of the 3D top are 4.0 and 6.0. The moments are recomputed each step from the
    /// current L (the step keeps H and |L|², so they stay the same to round-off), and the
    /// step keeps every property of the plain one, with the integrals of the original body.
    ///
    /// # Errors
    /// [`DynamicsError::UnsupportedOption`] for an order other than 2, 4 or 6. Stepping a body
    /// that is not 3D returns the same error.
    pub fn preprocessed(order: u32) -> Result<Self, DynamicsError> {
        if ![2, 4, 6].contains(&order) {
            return Err(DynamicsError::UnsupportedOption {
                integrator: "moser-veselov",
                reason: format!(
                    "no modified moments of order {order}; the preprocessed step has orders 2, 4 and 6"
                ),
            });
        }
        Ok(MoserVeselov {
            preprocessed: order,
            ..Self::default()
        })
    }

    /// Returns the integrator with a bound on the Newton iterations per step.
    pub fn with_max_iterations(self, max_iterations: usize) -> Self {
        MoserVeselov {
            iterations: Iterations::new(max_iterations),
            ..self
        }
    }

    /// One kick–MV–kick step of size `h`; returns the Newton iterations.
    fn kdk(
        &self,
        body: &mut RigidBody,
        moments: &[f64],
        torque: &dyn Torque,
        t: f64,
        h: f64,
    ) -> Result<usize, DynamicsError> {
        kick(body, torque, t, 0.5 * h);
        let iterations = free_step(body, moments, t, h, self.iterations.max)?;
        kick(body, torque, t + 0.5 * h, 0.5 * h);
        Ok(iterations)
    }
}

iteration_counters!(MoserVeselov, "Newton iterations");

impl_integrator!(
    MoserVeselov,
    order = |this| match this.composition {
        SplittingOrder::Strang => this.preprocessed,
        other => other.order(),
    },
    name = |this| match (this.composition, this.preprocessed) {
        (SplittingOrder::Yoshida4, _) => "mv-yoshida4",
        (SplittingOrder::Suzuki4, _) => "mv-suzuki4",
        (SplittingOrder::KahanLi6, _) => "mv-kahan-li6",
        (SplittingOrder::KahanLi8, _) => "mv-kahan-li8",
        (SplittingOrder::Strang, 4) => "mv-preprocessed4",
        (SplittingOrder::Strang, 6) => "mv-preprocessed6",
        _ => "moser-veselov",
    },
    step = |this, body, t, h, torque| {
        body.refuse_gyrostat("moser-veselov")?;
        let inertia = body.inertia();
        let (Some(moments), Some(_)) = (
            inertia.principal_second_moments(),
            inertia.diagonal_plane_moments(),
        ) else {
            return Err(DynamicsError::NonPhysicalInertia {
                integrator: this.name(),
            });
        };
        let mut moments: SmallVec<[f64; 8]> = moments.iter().copied().collect();
        if this.preprocessed > 2 {
            if moments.len() != 3 {
                return Err(DynamicsError::UnsupportedOption {
                    integrator: this.name(),
                    reason: format!(
                        "the modified moments are those of a body in 3D, this one is in {}D; use MoserVeselov::new",
                        moments.len()
                    ),
                });
            }
            let j = [moments[0], moments[1], moments[2]];
            moments.copy_from_slice(&modified_second_moments(
                j,
                body.momentum().as_slice(),
                h,
                this.preprocessed,
            ));
        }
        // Keep the state (inline for N ≤ 8), so that a failed step leaves the body as it was.
        let saved = (
            body.principal_frame_attitude().clone(),
            body.momentum().clone(),
        );
        let mut weights = [0.0; 17];
        let stages = this.composition.weights_into(&mut weights);
        let mut time = t;
        let mut outcome = Ok(0);
        for &g in &weights[..stages] {
            outcome = outcome.and_then(|sum| {
                let iterations = this.kdk(body, &moments, torque, time, g * h)?;
                Ok(sum + iterations)
            });
            time += g * h;
        }
        let outcome = outcome.and_then(|iterations| {
            if body.momentum().as_slice().iter().all(|x| x.is_finite())
                && body.principal_frame_attitude().is_finite()
            {
                Ok(iterations)
            } else {
                Err(DynamicsError::NonFinite { time: t })
            }
        });
        match outcome {
            Ok(iterations) => {
                this.iterations.record(iterations);
                Ok(())
            }
            Err(e) => {
                body.replace_state(saved.0, saved.1);
                Err(e)
            }
        }
    }
);

/// The second moments J̃ of the modified moments of inertia of
/// [`MoserVeselov::preprocessed`] for a 3D body with second moments `j`, momentum `l`
/// (L₁₂, L₁₃, L₂₃) and step h, to the given order (4 or 6).
fn modified_second_moments(j: [f64; 3], l: &[f64], h: f64, order: u32) -> [f64; 3] {
    // Moments of inertia about the axes: I₁ = J₂ + J₃ (the plane e₂₃), and m = (L₂₃, L₁₃, L₁₂)
    // up to signs, which only enter squared.
    let i = [j[1] + j[2], j[0] + j[2], j[0] + j[1]];
    let m2 = [l[2] * l[2], l[1] * l[1], l[0] * l[0]];
    let h2 = h * h;
    // ½h²|L|² and h²H, the series' variables.
    let norm = 0.5 * h2 * (m2[0] + m2[1] + m2[2]);
    let energy = 0.5 * h2 * (m2[0] / i[0] + m2[1] / i[1] + m2[2] / i[2]);
    let det = i[0] * i[1] * i[2];
    let s1 = i[0] + i[1] + i[2];
    let s2 = i[0] * i[0] + i[1] * i[1] + i[2] * i[2];
    let inv1 = 1.0 / i[0] + 1.0 / i[1] + 1.0 / i[2];
    let inv2 = 1.0 / (i[0] * i[0]) + 1.0 / (i[1] * i[1]) + 1.0 / (i[2] * i[2]);
    let ratios = (i[0] + i[1]) / i[2] + (i[1] + i[2]) / i[0] + (i[2] + i[0]) / i[1];
    let mut c = 1.0 + s1 / (6.0 * det) * norm - inv1 / 3.0 * energy;
    let mut d = -norm / (3.0 * det) + s1 / (6.0 * det) * energy;
    if order >= 6 {
        c += (s2 / det - inv1) / (30.0 * det) * norm * norm
            + (1.0 - ratios) / (30.0 * det) * norm * energy
            + (3.0 * s1 / det + 2.0 * inv2) / 60.0 * energy * energy;
        d += -s1 / (det * det) / 60.0 * norm * norm
            + (inv1 / det / 10.0 - s2 / (det * det) / 60.0) * norm * energy
            - (9.0 + ratios) / det / 60.0 * energy * energy;
    }
    let modified = i.map(|ik| 1.0 / (c / ik + d));
    // Back to second moments: J̃₁ = (Ĩ₂ + Ĩ₃ − Ĩ₁)/2, …
    [
        0.5 * (modified[1] + modified[2] - modified[0]),
        0.5 * (modified[0] + modified[2] - modified[1]),
        0.5 * (modified[0] + modified[1] - modified[2]),
    ]
}

/// The outcome of [`solve`]: C = (1 − A)⁻¹A, so that U = 1 + 2C, and the Cayley parameter A
/// (packed), with the Newton iterations taken.
struct Solution {
    c: Mat,
    a: Packed,
    iterations: usize,
}

/// One free Moser–Veselov step of size `h`; returns the Newton iterations.
fn free_step(
    body: &mut RigidBody,
    moments: &[f64],
    t: f64,
    h: f64,
    max_iterations: usize,
) -> Result<usize, DynamicsError> {
    if h == 0.0 {
        return Ok(0);
    }
    let n = body.dim();
    let nn = n * n;
    // hM = −h[L], column-major: hM(i, j) = −h lᵢⱼ for i < j.
    let mut hm: Mat = SmallVec::from_elem(0.0, nn);
    for ((i, j), &l) in pairs(n).zip(body.momentum().as_slice()) {
        hm[j * n + i] = -h * l;
        hm[i * n + j] = h * l;
    }
    let Solution { c, a, iterations } =
        solve(n, moments, &hm, max_iterations).map_err(|failure| match failure {
            Failure::NoSolution { residual } => DynamicsError::NoDiscreteSolution {
                integrator: "moser-veselov",
                time: t,
                step: h,
                residual,
            },
            Failure::Stalled {
                iterations,
                residual,
            } => DynamicsError::SolverDidNotConverge {
                time: t,
                iterations,
                residual,
            },
        })?;
    // M' = UᵀMU with U = 1 + 2C: M + 2(CᵀM + MC) + 4CᵀMC, the increment formed apart from M
    // (it is O(h|ω|) of it). Only the upper triangle is needed: M' is skew.
    let mut mc: Mat = SmallVec::from_elem(0.0, nn);
    matmul(n, &hm, &c, &mut mc);
    let (_, momentum) = body.state_mut();
    for ((i, j), l) in pairs(n).zip(momentum.as_mut_slice()) {
        // (CᵀX)(i, j) = column i of C dotted with column j of X.
        let dot = |x: &[f64], col_a: usize, y: &[f64], col_b: usize| -> f64 {
            x[col_a * n..(col_a + 1) * n]
                .iter()
                .zip(&y[col_b * n..(col_b + 1) * n])
                .map(|(p, q)| p * q)
                .sum()
        };
        let ct_hm = dot(&c, i, &hm, j);
        let hm_c = mc[j * n + i];
        let ct_hm_c = dot(&c, i, &mc, j);
        // The same for (j, i), to take the skew part exactly.
        let ct_hm_ji = dot(&c, j, &hm, i);
        let hm_c_ji = mc[i * n + j];
        let ct_hm_c_ji = dot(&c, j, &mc, i);
        let upper = 2.0 * (ct_hm + hm_c) + 4.0 * ct_hm_c;
        let lower = 2.0 * (ct_hm_ji + hm_c_ji) + 4.0 * ct_hm_c_ji;
        // l' = −M'(i, j)/h = l − (upper − lower)/(2h).
        *l -= 0.5 * (upper - lower) / h;
    }
    let (attitude, _) = body.state_mut();
    // U − 1 = 2C.
    let d: Mat = c.iter().map(|x| 2.0 * x).collect();
    attitude.times_cayley_mut(&a, &d);
    Ok(iterations)
}

/// Why [`solve`] found no rotation.
enum Failure {
    /// No solution near the identity: |hM|_F > 2|J|_F, a singular Newton matrix, or a
    /// diverging iteration.
    NoSolution { residual: f64 },
    /// The iteration bound was reached above the tolerance.
    Stalled { iterations: usize, residual: f64 },
}

/// Solves hM = UJ − JUᵀ for U = cay(A) near the identity by Newton's method on A.
fn solve(n: usize, j: &[f64], hm: &[f64], max_iterations: usize) -> Result<Solution, Failure> {
    let nn = n * n;
    let k = n * (n - 1) / 2;
    // |UJ − JUᵀ|_F ≤ 2|J|_F for every orthogonal U.
    let hm_norm = hm.iter().map(|x| x * x).sum::<f64>().sqrt();
    let j_norm = j.iter().map(|x| x * x).sum::<f64>().sqrt();
    if hm_norm.is_nan() || hm_norm > 2.0 * j_norm {
        return Err(Failure::NoSolution {
            residual: f64::INFINITY,
        });
    }
    // Start: U ≈ exp(hΩ) ≈ cay(½hΩ), Ωᵢⱼ = Mᵢⱼ/(Jᵢ + Jⱼ).
    let mut a: Packed = pairs(n)
        .map(|(p, q)| 0.5 * hm[q * n + p] / (j[p] + j[q]))
        .collect();
    let mut c: Mat = SmallVec::from_elem(0.0, nn);
    let mut p_mat: Mat = SmallVec::from_elem(0.0, nn);
    let mut pj: Mat = SmallVec::from_elem(0.0, nn);
    let mut f: Packed = SmallVec::from_elem(0.0, k);
    let mut jac: Jacobian = SmallVec::from_elem(0.0, k * k);
    let mut pivots: SmallVec<[usize; 28]> = SmallVec::from_elem(0, k);
    let mut first_residual = f64::INFINITY;
    let mut previous_residual = f64::INFINITY;
    let mut residual = f64::INFINITY;
    for iteration in 0..=max_iterations {
        // C = (1 − A)⁻¹A by Gaussian elimination on [1 − A | A].
        if !cayley_increment(n, &a, &mut c, &mut p_mat) {
            return Err(Failure::NoSolution { residual });
        }
        // F = 2(CJ − JCᵀ) − hM on the upper triangle, and the size of its terms (for the
        // round-off floor of the test).
        let mut size = 0.0f64;
        residual = 0.0;
        for (fq, (p, q)) in f.iter_mut().zip(pairs(n)) {
            let x = 2.0 * c[q * n + p] * j[q];
            let y = 2.0 * j[p] * c[p * n + q];
            let m = hm[q * n + p];
            *fq = x - y - m;
            residual = residual.max(fq.abs());
            size = size.max(x.abs() + y.abs() + m.abs());
        }
        if !residual.is_finite() {
            return Err(Failure::NoSolution { residual });
        }
        // A chord correction (N > 5) contracts the residual only linearly, so its first
        // residual under the round-off bound may still be a few ulps: a bias of that size
        // every step adds up over 10⁶ steps (1.5e-12 in the Manakov integrals at N = 6). It
        // is accepted only once it reaches an ulp or stops contracting; Newton's (N ≤ 5)
        // lands far below at once.
        let floor = residual <= 4.0 * f64::EPSILON * size;
        let settled = k <= 10
            || residual <= f64::EPSILON * size
            || residual > 0.25 * previous_residual
            || iteration == max_iterations;
        if floor && settled {
            return Ok(Solution {
                c,
                a,
                iterations: iteration,
            });
        }
        if iteration == 0 {
            first_residual = residual;
        } else if residual > 1e3 * first_residual {
            return Err(Failure::NoSolution { residual });
        }
        if iteration == max_iterations {
            break;
        }
        // Above N = 5 the chord method: the Newton matrix (K×K, its factorisation O(K³)) is
        // rebuilt only when the last correction contracted the residual by less than 100×
        // (always at the start), so near the solution one factorisation serves every
        // correction of the step. Up to N = 5 the factorisation costs less than the extra
        // iteration the chord method takes.
        if k <= 10 || iteration == 0 || residual > 0.01 * previous_residual {
            // dU[δ] = P δ (1 + U) = 2 P δ P with P = (1 − A)⁻¹ = 1 + C; dF[δ] = G − Gᵀ with
            // G = dU J = 2 P δ (PJ). For δ = eₛeₜᵀ − eₜeₛᵀ: G(a, b) = 2(P(a, s)(PJ)(t, b) −
            // P(a, t)(PJ)(s, b)).
            for col in 0..n {
                for row in 0..n {
                    let v = c[col * n + row] + if row == col { 1.0 } else { 0.0 };
                    p_mat[col * n + row] = v;
                    pj[col * n + row] = v * j[col];
                }
            }
            let g = |a: usize, b: usize, s: usize, t: usize| {
                2.0 * (p_mat[s * n + a] * pj[b * n + t] - p_mat[t * n + a] * pj[b * n + s])
            };
            for (col, (s, t)) in pairs(n).enumerate() {
                for (row, (a, b)) in pairs(n).enumerate() {
                    jac[col * k + row] = g(a, b, s, t) - g(b, a, s, t);
                }
            }
            if !lu_factor(k, &mut jac, &mut pivots) {
                return Err(Failure::NoSolution { residual });
            }
        }
        previous_residual = residual;
        // Solve Jac δ = −F; A += δ.
        for x in f.iter_mut() {
            *x = -*x;
        }
        lu_apply(k, &jac, &pivots, &mut f, 1);
        for (x, d) in a.iter_mut().zip(&f) {
            *x += d;
        }
    }
    Err(Failure::Stalled {
        iterations: max_iterations,
        residual: residual / hm_norm.max(f64::MIN_POSITIVE),
    })
}

/// C = (1 − A)⁻¹A for the skew A with packed components `a`; `work` is N×N scratch. False if
/// 1 − A is singular (not for a real skew A, but a non-finite iterate gets here).
fn cayley_increment(n: usize, a: &[f64], c: &mut Mat, work: &mut Mat) -> bool {
    work.iter_mut().for_each(|x| *x = 0.0);
    c.iter_mut().for_each(|x| *x = 0.0);
    for ((p, q), &v) in pairs(n).zip(a) {
        // 1 − A in `work`, A in `c` (the right-hand sides).
        work[q * n + p] = -v;
        work[p * n + q] = v;
        c[q * n + p] = v;
        c[p * n + q] = -v;
    }
    for d in 0..n {
        work[d * n + d] = 1.0;
    }
    lu_solve(n, work, c, n)
}

/// out = x·y for column-major N×N matrices.
fn matmul(n: usize, x: &[f64], y: &[f64], out: &mut [f64]) {
    for (col, o) in out.chunks_exact_mut(n).enumerate() {
        o.iter_mut().for_each(|v| *v = 0.0);
        for (q, &yq) in y[col * n..(col + 1) * n].iter().enumerate() {
            o.iter_mut()
                .zip(&x[q * n..(q + 1) * n])
                .for_each(|(v, xv)| *v += xv * yq);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::Attitude;
    use nalgebra::DMatrix;

    /// Packed components of a test skew matrix.
    fn packed(n: usize, scale: f64) -> Packed {
        (0..n * (n - 1) / 2)
            .map(|k| scale * (0.9 * k as f64 + 0.4).sin())
            .collect()
    }

    /// The Cayley rotation as nalgebra computes it: (1 − A)⁻¹(1 + A).
    fn cayley(n: usize, a: &[f64]) -> DMatrix<f64> {
        let mut s = DMatrix::zeros(n, n);
        for ((i, j), &v) in pairs(n).zip(a) {
            s[(i, j)] = v;
            s[(j, i)] = -v;
        }
        let id = DMatrix::<f64>::identity(n, n);
        (&id - &s).try_inverse().unwrap() * (&id + &s)
    }

    /// The rotor built from the Cayley parameter (1 + B + Pf(B) e₁₂₃₄, normalised) and the
    /// matrix update Q + Q(U − 1) both give nalgebra's Cayley rotation, in 2D … 6D.
    #[test]
    fn the_cayley_update_is_the_cayley_rotation_in_both_forms() {
        for n in 2..=6 {
            for scale in [1e-3, 0.3, 2.0] {
                let a = packed(n, scale);
                let u = cayley(n, &a);
                let mut c: Mat = SmallVec::from_elem(0.0, n * n);
                let mut work: Mat = SmallVec::from_elem(0.0, n * n);
                assert!(cayley_increment(n, &a, &mut c, &mut work));
                let d: Mat = c.iter().map(|x| 2.0 * x).collect();
                let mut attitude = Attitude::identity(n);
                attitude.times_cayley_mut(&a, &d);
                let err = (attitude.to_matrix() - &u).amax();
                assert!(err < 1e-14, "N = {n}, scale {scale}: {err:e}");
                let unit = attitude.unit_error();
                assert!(unit < 1e-14, "N = {n}, scale {scale}: {unit:e}");
            }
        }
    }

    /// Newton's solution satisfies hM = UJ − JUᵀ to a few ulps of hM, checked with U formed
    /// by nalgebra from the returned parameter.
    #[test]
    fn the_solve_meets_the_equation_to_round_off() {
        for n in [3usize, 4, 6, 8] {
            let j: Vec<f64> = (0..n).map(|k| 0.4 + 0.35 * k as f64).collect();
            for h in [1e-4, 1e-2, 0.2] {
                let l = packed(n, 1.0);
                let mut hm = vec![0.0; n * n];
                for ((p, q), &v) in pairs(n).zip(&l) {
                    hm[q * n + p] = -h * v;
                    hm[p * n + q] = h * v;
                }
                let s = solve(n, &j, &hm, 30).ok().expect("a solution");
                let u = cayley(n, &s.a);
                let jm = DMatrix::from_diagonal(&nalgebra::DVector::from_column_slice(&j));
                let r = &u * &jm - &jm * u.transpose() - DMatrix::from_column_slice(n, n, &hm);
                let scale = hm.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                let rel = r.amax() / scale;
                assert!(
                    rel < 1e-13,
                    "N = {n}, h = {h}: relative residual {rel:e} ({} iterations)",
                    s.iterations
                );
                // Above N = 5 the chord iteration may take one more correction to settle
                // at an ulp (see `solve`).
                let bound = if n > 5 { 6 } else { 5 };
                assert!(s.iterations <= bound, "N = {n}, h = {h}: {}", s.iterations);
            }
        }
    }
}
