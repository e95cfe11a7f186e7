//! Free rigid bodies of 3D and 4D space on the fixed-size types: [`FreeBody3`] and
//! [`FreeBody4`] hold the principal plane moments, the momentum as a [`Bivector3`] or
//! [`Bivector4`] and the attitude as a [`Rotor3`] (a quaternion) or [`Rotor4`] (a quaternion
//! pair), all `Copy` and on the stack, and step with the same formulas as [`Rkmk4`],
//! [`Splitting::strang`] and its symmetric-part form on a [`RigidBody`]: for a game loop or a
//! swarm of bodies.
//!
//! Which step to use: [`FreeBody4::step_strang_symmetric`] (and its 3D twin) is the step for
//! real-time use. Like [`FreeBody4::step_strang`] it keeps |L|, every Casimir and the
//! space-frame momentum to round-off at any step and the energy bounded (both are
//! symplectic), and it costs about as much as an RK4 step in 3D and a fifth more in 4D,
//! where the plain splitting costs about 1.3 to 1.6 times RK4's (the book's Performance
//! chapter): the attitude's turn about L is one exponential, and two planes fewer remain in
//! the chain of exact rotations. Its error scales with how far the body is from symmetric:
//! on random bodies it is typically tens of times smaller than the plain splitting's at the
//! same step, and the energy error of a long run 30 times smaller (`tests/dynamics/fixed.rs`,
//! `tests/reliability/long_runs.rs`). [`FreeBody4::step_rk4`] is order 4 with the attitude
//! on the group; its energy drifts as O(h⁴ t). All three agree with the run-time integrators
//! to a few ulp per step (`tests/dynamics/fixed.rs`).
//!
//! [`FreeBody4::advance_dop853`] (and its 3D twin) is the adaptive method of [`Dop853`] on
//! these types: the same steps, step sizes and error control, with every stage on the stack,
//! for a trajectory to a given accuracy rather than a fixed step.
//!
//! [`Rkmk4`]: super::Rkmk4
//! [`Splitting::strang`]: super::Splitting::strang
//! [`Dop853`]: super::Dop853

use super::integrate::dop853_tableau::{A, B, BHH, E5, STAGES};
use super::integrate::first_step_estimate;
use super::integrate::{DEXP_INVERSE_8, strang_drift_fixed};
use super::motion::MotionError;
use super::{DynamicsError, RigidBody};
use crate::algebra::{Bivector3, Bivector4, Rotor3, Rotor4, commutator_packed};

/// The counts of one adaptive run ([`FreeBody3::advance_dop853`],
/// [`FreeBody4::advance_dop853`]), as [`Dop853`](super::Dop853) reports them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Dop853Stats {
    /// Accepted internal steps.
    pub accepted: usize,
    /// Rejected internal steps.
    pub rejected: usize,
    /// Right-hand-side evaluations (dL/dt and ω at one state), the starting-step heuristic's
    /// included.
    pub rhs_evaluations: usize,
}

/// The bound on internal steps of one adaptive run (that of [`Dop853::new`](super::Dop853::new)).
const DOP853_MAX_STEPS: usize = 1_000_000;

/// [A × B] on packed components, the adaptive run's kernel: [`commutator_packed`], with the
/// 4D one written out (the unrolled generic kernel multiplies by the zero diagonal too). The
/// sums are the generic kernel's without those zero terms, so the results are the same.
#[inline(always)]
fn commutator<const N: usize, const K: usize>(a: &[f64; K], b: &[f64; K], out: &mut [f64; K]) {
    if N == 4 && K == 6 {
        let [a01, a02, a03, a12, a13, a23] = [a[0], a[1], a[2], a[3], a[4], a[5]];
        let [b01, b02, b03, b12, b13, b23] = [b[0], b[1], b[2], b[3], b[4], b[5]];
        out[0] = (b02 * a12 - a02 * b12) + (b03 * a13 - a03 * b13);
        out[1] = (a01 * b12 - b01 * a12) + (b03 * a23 - a03 * b23);
        out[2] = (a01 * b13 - b01 * a13) + (a02 * b23 - b02 * a23);
        out[3] = (b01 * a02 - a01 * b02) + (b13 * a23 - a13 * b23);
        out[4] = (b01 * a03 - a01 * b03) + (a12 * b23 - b12 * a23);
        out[5] = (b02 * a03 - a02 * b03) + (b12 * a13 - a12 * b13);
    } else {
        commutator_packed(N, a, b, out);
    }
}

/// The free motion's right-hand side at the momentum `l`: ω = I⁻¹(L) into `omega` and
/// dL/dt = ω × L into `dl`, for N-dimensional bodies with K = N(N−1)/2 planes.
#[inline(always)]
fn free_rate<const N: usize, const K: usize>(
    inverse: &[f64; K],
    l: &[f64; K],
    dl: &mut [f64; K],
    omega: &mut [f64; K],
) {
    for k in 0..K {
        omega[k] = l[k] * inverse[k];
    }
    commutator::<N, K>(omega, l, dl);
}

/// dA/dt = dexp⁻¹₋A(−½ω) truncated for order 8, on the stack: the series of
/// `dexp_inverse_packed` with `DEXP_INVERSE_8`, term for term.
#[inline(always)]
fn dexp_inverse_8<const N: usize, const K: usize>(
    a: &[f64; K],
    omega: &[f64; K],
    out: &mut [f64; K],
) {
    let mut power: [f64; K] = std::array::from_fn(|k| -0.5 * omega[k]);
    *out = power;
    let mut next = [0.0; K];
    for coefficient in DEXP_INVERSE_8 {
        commutator::<N, K>(a, &power, &mut next);
        power = next;
        if coefficient != 0.0 {
            for k in 0..K {
                out[k] += coefficient * power[k];
            }
        }
    }
}

/// The adaptive Dormand–Prince 8(5,3) run of [`Dop853`](super::Dop853) on a free body at
/// fixed size: advances `momentum` by `duration` and hands every accepted step's algebra
/// increment A (the attitude goes to R exp(A)) to `turn`. The arithmetic is the run-time
/// integrator's, operation for operation, so both take the same steps.
#[inline]
fn dop853_free<const N: usize, const K: usize>(
    inverse: &[f64; K],
    momentum: &mut [f64; K],
    duration: f64,
    rtol: f64,
    atol: f64,
    mut turn: impl FnMut(&[f64; K]) -> bool,
) -> Result<Dop853Stats, DynamicsError> {
    if !(rtol.is_finite() && atol.is_finite() && rtol >= 0.0 && atol >= 0.0) || rtol + atol == 0.0 {
        return Err(DynamicsError::InvalidTolerance { rtol, atol });
    }
    if !duration.is_finite() {
        return Err(DynamicsError::InvalidSampling {
            reason: "the duration must be finite",
        });
    }
    let mut stats = Dop853Stats::default();
    let mut h_next: Option<f64> = None;
    let mut last_rejected = false;
    // f at the start of the step (time, dL/dt, ω): reused after a rejection.
    let mut first: Option<(f64, [f64; K], [f64; K])> = None;
    let (mut kl, mut ka) = ([[0.0; K]; STAGES], [[0.0; K]; STAGES]);
    let t_end = duration;
    let sign = duration.signum();
    let mut time = 0.0;
    let mut count = 0;
    while (t_end - time) * sign > 1e-14 * t_end.abs().max(1.0) {
        count += 1;
        if count > DOP853_MAX_STEPS {
            return Err(DynamicsError::TooManySteps { time, steps: count });
        }
        let l0 = *momentum;
        let (dl0, w0) = match first {
            Some((t_first, dl, w)) if t_first == time => (dl, w),
            _ => {
                let (mut dl, mut w) = ([0.0; K], [0.0; K]);
                free_rate::<N, K>(inverse, &l0, &mut dl, &mut w);
                stats.rhs_evaluations += 1;
                first = Some((time, dl, w));
                (dl, w)
            }
        };
        let h_guess = match h_next {
            Some(h) => h,
            None => {
                stats.rhs_evaluations += 1;
                starting_step::<N, K>(inverse, &l0, &dl0, &w0, sign, rtol, atol)
            }
        };
        let remaining = t_end - time;
        let mut h = h_guess.abs() * sign;
        if h.abs() >= remaining.abs() {
            h = remaining;
        }
        // The twelve stages.
        kl[0] = dl0;
        for k in 0..K {
            ka[0][k] = -0.5 * w0[k];
        }
        let mut omega = [0.0; K];
        for s in 1..STAGES {
            let mut a_stage = [0.0; K];
            let mut l_stage = l0;
            for j in 0..s {
                if A[s][j] != 0.0 {
                    let c = h * A[s][j];
                    for k in 0..K {
                        a_stage[k] += c * ka[j][k];
                    }
                    for k in 0..K {
                        l_stage[k] += c * kl[j][k];
                    }
                }
            }
            free_rate::<N, K>(inverse, &l_stage, &mut kl[s], &mut omega);
            dexp_inverse_8::<N, K>(&a_stage, &omega, &mut ka[s]);
        }
        stats.rhs_evaluations += STAGES - 1;
        let mut l1 = l0;
        let mut a1 = [0.0; K];
        for s in 0..STAGES {
            if B[s] != 0.0 {
                let c = h * B[s];
                for k in 0..K {
                    l1[k] += c * kl[s][k];
                }
                for k in 0..K {
                    a1[k] += c * ka[s][k];
                }
            }
        }
        let err = step_error(&l0, &l1, &a1, &kl, &ka, h, rtol, atol);
        if !err.is_finite() {
            return Err(DynamicsError::NonFinite { time });
        }
        if err > 1.0 {
            stats.rejected += 1;
            let h_new = h * (0.9 * err.powf(-1.0 / 8.0)).max(0.333);
            if h_new.abs() < 1e-14 * time.abs().max(1.0) {
                return Err(DynamicsError::StepTooSmall { time, step: h_new });
            }
            h_next = Some(h_new);
            last_rejected = true;
            continue;
        }
        let mut factor = if err == 0.0 {
            6.0
        } else {
            (0.9 * err.powf(-1.0 / 8.0)).clamp(0.333, 6.0)
        };
        if last_rejected {
            factor = factor.min(1.0);
        }
        last_rejected = false;
        h_next = Some(h * factor);
        stats.accepted += 1;
        // A finite error estimate does not make the state finite: an increment A beyond f64
        // scales its own tolerance to ∞ (the estimate then reads 0).
        if !turn(&a1) || !l1.iter().all(|x| x.is_finite()) {
            return Err(DynamicsError::NonFinite { time });
        }
        *momentum = l1;
        time += h;
    }
    Ok(stats)
}

/// Hairer's starting step (Solving ODEs I, II.4), as [`Dop853`](super::Dop853) takes it: a
/// step with h‖f‖ ≈ 0.01‖y‖ probes the second derivative, and h⁸ max(‖f‖, ‖f'‖) ≈ 0.01
/// sets the step. One right-hand side.
#[allow(clippy::too_many_arguments)] // the state, its rate and the tolerances
fn starting_step<const N: usize, const K: usize>(
    inverse: &[f64; K],
    l0: &[f64; K],
    dl0: &[f64; K],
    w0: &[f64; K],
    sign: f64,
    rtol: f64,
    atol: f64,
) -> f64 {
    let a0: [f64; K] = std::array::from_fn(|k| w0[k] * -0.5);
    let scale_l = |y: f64| atol + rtol * y.abs();
    let scale_a = atol + rtol;
    let rms = |l: &dyn Fn(usize) -> f64, a: &dyn Fn(usize) -> f64| -> f64 {
        let mut sum = 0.0;
        for (i, y) in l0.iter().enumerate() {
            sum += (l(i) / scale_l(*y)).powi(2);
            sum += (a(i) / scale_a).powi(2);
        }
        (sum / (2 * K).max(1) as f64).sqrt()
    };
    let d0 = rms(&|i| l0[i], &|_| 0.0);
    let d1 = rms(&|i| dl0[i], &|i| a0[i]);
    let h0 = if d0 < 1e-10 || d1 < 1e-10 {
        1e-6
    } else {
        0.01 * d0 / d1
    };
    let mut l1 = *l0;
    for k in 0..K {
        l1[k] += sign * h0 * dl0[k];
    }
    let a1: [f64; K] = std::array::from_fn(|k| a0[k] * (sign * h0));
    let (mut dl1, mut w1, mut da1) = ([0.0; K], [0.0; K], [0.0; K]);
    free_rate::<N, K>(inverse, &l1, &mut dl1, &mut w1);
    dexp_inverse_8::<N, K>(&a1, &w1, &mut da1);
    let d2 = rms(&|i| dl1[i] - dl0[i], &|i| da1[i] - a0[i]) / h0;
    first_step_estimate(h0, d1, d2)
}

/// The scaled error of a step: dop853's blend of the 5th- and 3rd-order estimates,
/// err = ‖e₅‖² / √(‖e₅‖² + 0.01‖e₃‖²) with the mixed tolerance on (L, A).
#[allow(clippy::too_many_arguments)] // the step's states, stages and tolerances
#[inline(always)]
fn step_error<const K: usize>(
    l0: &[f64; K],
    l1: &[f64; K],
    a1: &[f64; K],
    kl: &[[f64; K]; STAGES],
    ka: &[[f64; K]; STAGES],
    h: f64,
    rtol: f64,
    atol: f64,
) -> f64 {
    let mut err5 = 0.0;
    let mut err3 = 0.0;
    for i in 0..K {
        let (mut e5l, mut e3l, mut e5a, mut e3a) = (0.0, 0.0, 0.0, 0.0);
        for s in 0..STAGES {
            // Stages 1–4 weigh nothing in either estimate.
            if E5[s] == 0.0 && B[s] == BHH[s] {
                continue;
            }
            let (fl, fa) = (kl[s][i], ka[s][i]);
            e5l += E5[s] * fl;
            e5a += E5[s] * fa;
            e3l += (B[s] - BHH[s]) * fl;
            e3a += (B[s] - BHH[s]) * fa;
        }
        let sl = atol + rtol * l0[i].abs().max(l1[i].abs());
        let sa = atol + rtol * a1[i].abs().max(1.0);
        err5 += (e5l / sl).powi(2) + (e5a / sa).powi(2);
        err3 += (e3l / sl).powi(2) + (e3a / sa).powi(2);
    }
    let mut deno = err5 + 0.01 * err3;
    if deno <= 0.0 {
        deno = 1.0;
    }
    h.abs() * err5 * (1.0 / ((2 * K).max(1) as f64 * deno)).sqrt()
}

macro_rules! free_body {
    ($name:ident, $n:literal, $k:literal, $biv:ident, $rotor:ident, $drift:ident, $doc:literal) => {
        #[doc = $doc]
        ///
        /// The body frame is the principal frame: the plane moments are the inertia map's
        /// eigenvalues on the basis planes, the momentum L and ω = I⁻¹(L) are in that frame,
        /// and the attitude turns it to space (x_space = R x R̃).
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct $name {
            moments: [f64; $k],
            inverse: [f64; $k],
            momentum: [f64; $k],
            attitude: $rotor,
        }

        impl $name {
            /// The body with principal plane moments `moments` (lexicographic planes),
            /// attitude `attitude` (principal frame → space) and principal-frame momentum
            /// `momentum`.
            ///
            /// # Errors
            /// [`MotionError::OutOfRange`] for a moment that is not positive and finite,
            /// [`DynamicsError::NonFiniteArgument`] for a momentum or attitude that is not
            /// finite.
            pub fn new(
                moments: [f64; $k],
                attitude: $rotor,
                momentum: $biv,
            ) -> Result<Self, DynamicsError> {
                for &m in &moments {
                    MotionError::require(
                        m.is_finite() && m > 0.0,
                        "plane moment",
                        m,
                        "a finite positive number",
                    )?;
                }
                let momentum = momentum.to_array();
                if let Some(&x) = momentum.iter().find(|x| !x.is_finite()) {
                    return Err(DynamicsError::NonFiniteArgument {
                        name: "momentum",
                        value: x,
                    });
                }
                let unit_error = attitude.unit_error();
                if !unit_error.is_finite() {
                    return Err(DynamicsError::NonFiniteArgument {
                        name: "attitude",
                        value: unit_error,
                    });
                }
                Ok(Self {
                    moments,
                    inverse: moments.map(|m| 1.0 / m),
                    momentum,
                    attitude,
                })
            }

            /// The fixed-size copy of a run-time body's state.
            ///
            /// # Errors
            /// [`DynamicsError::Algebra`] unless the body has this dimension;
            /// [`DynamicsError::UnsupportedInertia`] unless its inertia map is diagonal on the
            /// principal planes (every physical body).
            pub fn from_rigid_body(body: &RigidBody) -> Result<Self, DynamicsError> {
                body.refuse_gyrostat(stringify!($name))?;
                if body.dim() != $n {
                    return Err(crate::algebra::AlgebraError::DimensionMismatch {
                        left: $n,
                        right: body.dim(),
                    }
                    .into());
                }
                let unsupported = DynamicsError::UnsupportedInertia {
                    integrator: stringify!($name),
                };
                let moments: [f64; $k] = body
                    .inertia()
                    .diagonal_plane_moments()
                    .ok_or(unsupported)?
                    .try_into()
                    .expect("one moment per plane");
                let attitude = $rotor::from_rotor(&body.principal_frame_attitude().to_rotor()?)?;
                let momentum = $biv::from_bivector(body.momentum())?;
                Self::new(moments, attitude, momentum)
            }

            /// Writes this state into a run-time body of the same inertia.
            ///
            /// # Errors
            /// As [`RigidBody::set_state`].
            pub fn write_to(&self, body: &mut RigidBody) -> Result<(), DynamicsError> {
                body.set_state(self.attitude.to_rotor(), self.momentum().to_bivector())?;
                Ok(())
            }

            /// The principal plane moments.
            pub fn moments(&self) -> [f64; $k] {
                self.moments
            }

            /// The angular momentum L in the principal frame.
            pub fn momentum(&self) -> $biv {
                $biv::from_array(self.momentum)
            }

            /// The angular velocity ω = I⁻¹(L) in the principal frame.
            pub fn omega(&self) -> $biv {
                $biv::from_array(std::array::from_fn(|k| self.momentum[k] * self.inverse[k]))
            }

            /// The attitude (principal frame → space).
            pub fn attitude(&self) -> $rotor {
                self.attitude
            }

            /// The kinetic energy ½⟨ω, L⟩.
            pub fn energy(&self) -> f64 {
                let mut e = 0.0;
                for k in 0..$k {
                    e += self.momentum[k] * self.momentum[k] * self.inverse[k];
                }
                0.5 * e
            }

            /// One step of RKMK4 (order 4), the formulas of [`super::Rkmk4`]'s free step.
            #[inline]
            pub fn step_rk4(&mut self, h: f64) {
                let inverse = self.inverse;
                let rate = |l: &[f64; $k]| {
                    let w: [f64; $k] = std::array::from_fn(|k| l[k] * inverse[k]);
                    let mut dl = [0.0; $k];
                    commutator_packed($n, &w, l, &mut dl);
                    (dl, w)
                };
                let axpy =
                    |x: &[f64; $k], y: &[f64; $k], s: f64| std::array::from_fn(|k| x[k] + s * y[k]);
                let l0 = self.momentum;
                let (dl1, w1) = rate(&l0);
                let (dl2, w2) = rate(&axpy(&l0, &dl1, 0.5 * h));
                let (dl3, w3) = rate(&axpy(&l0, &dl2, 0.5 * h));
                let (dl4, w4) = rate(&axpy(&l0, &dl3, h));
                let mut correction = [0.0; $k];
                commutator_packed($n, &w1, &w4, &mut correction);
                let mut u = [0.0; $k];
                for k in 0..$k {
                    u[k] = -h / 12.0 * (w1[k] + 2.0 * w2[k] + 2.0 * w3[k] + w4[k])
                        + h * h / 24.0 * correction[k];
                    self.momentum[k] =
                        l0[k] + h / 6.0 * (dl1[k] + 2.0 * dl2[k] + 2.0 * dl3[k] + dl4[k]);
                }
                self.attitude = self.attitude * $biv::from_array(u).exp();
            }

            /// One Strang step of the Lie–Poisson splitting over the planes, the updates of
            /// [`super::Splitting::strang`]: every plane's flow is an exact rotation.
            #[inline]
            pub fn step_strang(&mut self, h: f64) {
                let d = $drift(&mut self.momentum, &self.inverse, h, Default::default());
                self.attitude = self.attitude.plus_product($rotor::from_even_layout(&d));
            }

            /// One Strang step of the splitting with the symmetric part split off, the updates
            /// of `Splitting::strang().with_symmetric_part()`
            /// ([`super::Splitting::with_symmetric_part`]): the attitude turns about L by
            /// the exact R ← R exp(−h L/(2I_K)) (K the last plane), and the other planes
            /// flow with the differences 1/I_p − 1/I_K of the inverse moments as their
            /// rates. Same order and invariants as [`Self::step_strang`] (|L|, every
            /// Casimir and the space-frame momentum to round-off, the energy bounded), a
            /// chain two planes shorter, and an error that scales with how far the body is
            /// from symmetric instead of with its moments (typically tens of times smaller
            /// on random bodies, though not on every body; see the module documentation):
            /// the step to pick for a game loop.
            #[inline]
            pub fn step_strang_symmetric(&mut self, h: f64) {
                let last = self.inverse[$k - 1];
                // The Casimir piece commutes with the planes: turned first, from the L at
                // the start, it is computed beside their chain, and it seeds the planes'
                // increment (one rotor product per step, as for the plain splitting).
                let scale = -0.5 * h * last;
                let start =
                    $biv::from_array(self.momentum.map(|x| x * scale)).exp_minus_one_even_layout();
                let rates: [f64; $k] = std::array::from_fn(|p| self.inverse[p] - last);
                let d = $drift(&mut self.momentum, &rates, h, start);
                self.attitude = self.attitude.plus_product($rotor::from_even_layout(&d));
            }

            /// Advances the body by `duration` (either sign) with the adaptive Dormand–Prince
            /// 8(5,3) method of [`Dop853`](super::Dop853) on this body's stack arrays, with
            /// relative and absolute tolerances `rtol` and `atol`, and returns the step counts.
            /// The algorithm is the run-time one: RKMK on the group (the attitude R₀ exp(A),
            /// A integrated in the Lie algebra), the blended 5th/3rd-order error on (L, A)
            /// with the mixed tolerance atol + rtol·|y|, the same step-size control and
            /// Hairer's starting step. It takes the steps `Dop853::new(rtol, atol)` takes in
            /// one [`Integrator::step`](super::Integrator::step) of `duration` on the
            /// run-time body, and ends exactly at `duration`. Every call starts with the
            /// starting-step heuristic, so advance over a whole interval in one call.
            ///
            /// Cost: twelve right-hand sides per accepted step and eleven per rejected one,
            /// each one commutator for dL/dt and six for dexp⁻¹, all on the stack (no heap).
            /// From about 10⁻⁸ down it beats [`Self::step_rk4`] at the step that accuracy
            /// needs (on the 4D cuboid of the book's benchmarks to t = 100, about 1.7 times
            /// at 10⁻⁸ and 4.5 times at 10⁻¹¹).
            ///
            /// # Errors
            /// [`DynamicsError::InvalidTolerance`] unless both tolerances are finite and
            /// non-negative and at least one is positive; [`DynamicsError::InvalidSampling`]
            /// for a duration that is not finite; [`DynamicsError::TooManySteps`] beyond 10⁶
            /// internal steps; [`DynamicsError::StepTooSmall`] and
            /// [`DynamicsError::NonFinite`] when the motion leaves f64. On an error the body is
            /// unchanged.
            pub fn advance_dop853(
                &mut self,
                duration: f64,
                rtol: f64,
                atol: f64,
            ) -> Result<Dop853Stats, DynamicsError> {
                let mut momentum = self.momentum;
                let mut attitude = self.attitude;
                let stats = dop853_free::<$n, $k>(
                    &self.inverse,
                    &mut momentum,
                    duration,
                    rtol,
                    atol,
                    |a| {
                        attitude = attitude * $biv::from_array(*a).exp();
                        attitude.unit_error().is_finite()
                    },
                )?;
                self.momentum = momentum;
                self.attitude = attitude;
                Ok(stats)
            }

            /// [`Self::step_rk4`] on every body.
            pub fn step_all_rk4(bodies: &mut [Self], h: f64) {
                bodies.iter_mut().for_each(|b| b.step_rk4(h));
            }

            /// [`Self::step_strang`] on every body.
            pub fn step_all_strang(bodies: &mut [Self], h: f64) {
                bodies.iter_mut().for_each(|b| b.step_strang(h));
            }

            /// [`Self::step_strang_symmetric`] on every body.
            pub fn step_all_strang_symmetric(bodies: &mut [Self], h: f64) {
                bodies.iter_mut().for_each(|b| b.step_strang_symmetric(h));
            }

            /// [`Self::step_rk4`] on every body across rayon's threads (feature `parallel`).
            #[cfg(feature = "parallel")]
            pub fn par_step_all_rk4(bodies: &mut [Self], h: f64) {
                use rayon::prelude::*;
                bodies
                    .par_chunks_mut(PAR_CHUNK)
                    .for_each(|c| Self::step_all_rk4(c, h));
            }

            /// [`Self::step_strang`] on every body across rayon's threads (feature `parallel`).
            #[cfg(feature = "parallel")]
            pub fn par_step_all_strang(bodies: &mut [Self], h: f64) {
                use rayon::prelude::*;
                bodies
                    .par_chunks_mut(PAR_CHUNK)
                    .for_each(|c| Self::step_all_strang(c, h));
            }

            /// [`Self::step_strang_symmetric`] on every body across rayon's threads (feature
            /// `parallel`).
            #[cfg(feature = "parallel")]
            pub fn par_step_all_strang_symmetric(bodies: &mut [Self], h: f64) {
                use rayon::prelude::*;
                bodies
                    .par_chunks_mut(PAR_CHUNK)
                    .for_each(|c| Self::step_all_strang_symmetric(c, h));
            }
        }
    };
}

/// Bodies per rayon task: enough work (tens of µs) to pay for the split.
#[cfg(feature = "parallel")]
const PAR_CHUNK: usize = 256;

free_body!(
    FreeBody3,
    3,
    3,
    Bivector3,
    Rotor3,
    strang_drift_fixed,
    "A free rigid body of 3D space on the fixed-size types (quaternion attitude)."
);
free_body!(
    FreeBody4,
    4,
    6,
    Bivector4,
    Rotor4,
    strang_drift_fixed,
    "A free rigid body of 4D space on the fixed-size types (quaternion-pair attitude)."
);

#[cfg(test)]
mod tests {
    use super::super::integrate::dexp_inverse_packed;
    use super::*;

    /// The written-out 4D commutator and the stack dexp⁻¹ are the generic kernels' sums,
    /// bit for bit.
    #[test]
    fn written_out_kernels_are_the_generic_ones() {
        for seed in 0..50 {
            let a: [f64; 6] = std::array::from_fn(|k| (1.3 * (seed * 6 + k) as f64).sin());
            let b: [f64; 6] = std::array::from_fn(|k| 2.0 * (0.7 * (seed * 6 + k) as f64).cos());
            let (mut fast, mut generic) = ([0.0; 6], [0.0; 6]);
            commutator::<4, 6>(&a, &b, &mut fast);
            commutator_packed(4, &a, &b, &mut generic);
            assert_eq!(fast, generic);
            dexp_inverse_8::<4, 6>(&a, &b, &mut fast);
            assert_eq!(fast, generic_dexp_inverse_8(4, &a, &b));
            let (a3, b3) = ([a[0], a[1], a[2]], [b[0], b[1], b[2]]);
            let mut fast3 = [0.0; 3];
            dexp_inverse_8::<3, 3>(&a3, &b3, &mut fast3);
            assert_eq!(fast3, generic_dexp_inverse_8(3, &a3, &b3));
        }
    }

    /// The generic kernel's dexp⁻¹₋a(−½ b) of order 8 in dimension n, K = n(n−1)/2.
    fn generic_dexp_inverse_8<const K: usize>(n: usize, a: &[f64; K], b: &[f64; K]) -> [f64; K] {
        let (mut out, mut power, mut next) = ([0.0; K], [0.0; K], [0.0; K]);
        let pair = (&mut power[..], &mut next[..]);
        dexp_inverse_packed(n, a, b, -0.5, &DEXP_INVERSE_8, &mut out, pair);
        out
    }
}
