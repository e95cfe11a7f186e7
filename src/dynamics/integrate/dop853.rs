//! Adaptive Dormand–Prince 8(5,3) on the group, with dense output of order 7.

use super::dop853_tableau::{A, ALL_STAGES, B, BHH, C, D, E5, STAGES};
use super::{
    Attempt, ControlledPair, DEXP_INVERSE_8, DynamicsError, advance_controlled, check_finite,
    check_sample_times, check_state, count_step, dexp_inverse_packed, momentum_rate_into,
    samples_at_zero,
};
use crate::algebra::Bivector;
use crate::dynamics::Attitude;
use crate::dynamics::{RigidBody, Torque};
use smallvec::SmallVec;

/// The stage values of one step, inline (no heap for N ≤ 8, where bivectors are inline too).
type Stages = SmallVec<[Bivector; ALL_STAGES]>;

/// Where a step's stages are evaluated: the body, the torque, the start (t, R₀, L₀) and h.
struct StepStart<'a> {
    body: &'a RigidBody,
    torque: &'a dyn Torque,
    t: f64,
    h: f64,
    r0: &'a Attitude,
    l0: &'a Bivector,
}

/// y ← y + α x.
fn axpy(y: &mut Bivector, alpha: f64, x: &Bivector) {
    super::axpy(y.as_mut_slice(), alpha, x.as_slice());
}

/// Writes dexp⁻¹₋Ω(s·w) truncated for order 8 ([`dexp_inverse_packed`]) into `out`,
/// with the commutator powers on the stack for N ≤ 8 (the stages' hot spot: six
/// commutators each) and in `scratch` above (sized once, then reused).
fn dexp_inverse_8(
    omega_alg: &Bivector,
    w: &Bivector,
    s: f64,
    out: &mut Bivector,
    scratch: &mut Vec<f64>,
) {
    let n = w.dim();
    let len = w.as_slice().len();
    let (alg, w, out) = (omega_alg.as_slice(), w.as_slice(), out.as_mut_slice());
    if len <= 28 {
        let (mut power, mut next) = ([0.0f64; 28], [0.0f64; 28]);
        let pair = (&mut power[..len], &mut next[..len]);
        dexp_inverse_packed(n, alg, w, s, &DEXP_INVERSE_8, out, pair);
    } else {
        scratch.resize(2 * len, 0.0);
        let (power, next) = scratch.split_at_mut(len);
        dexp_inverse_packed(n, alg, w, s, &DEXP_INVERSE_8, out, (power, next));
    }
}

/// The last stage of Hairer's starting-step heuristic for order 8: from the trial step h₀,
/// the scaled size d₁ of the first derivative and d₂ of the second (estimated from an Euler
/// step of h₀), h = min(100 h₀, (0.01 / max(d₁, d₂))^(1/8)).
pub(crate) fn first_step_estimate(h0: f64, d1: f64, d2: f64) -> f64 {
    let d = d1.max(d2);
    let h1 = if d <= 1e-15 {
        (h0 * 1e-3).max(1e-6)
    } else {
        (0.01 / d).powf(1.0 / 8.0)
    };
    (100.0 * h0).min(h1)
}

/// The state at stage s of a step of size h from momentum `l0`: L = L₀ + h Σⱼ aₛⱼ kl_j into
/// `l_stage` and A = h Σⱼ aₛⱼ ka_j into `a_stage`, from the earlier stages.
fn stage_state(
    s: usize,
    h: f64,
    l0: &Bivector,
    kl: &Stages,
    ka: &Stages,
    l_stage: &mut Bivector,
    a_stage: &mut Bivector,
) {
    a_stage.as_mut_slice().fill(0.0);
    l_stage.as_mut_slice().copy_from_slice(l0.as_slice());
    for j in 0..s {
        if A[s][j] != 0.0 {
            axpy(a_stage, h * A[s][j], &ka[j]);
            axpy(l_stage, h * A[s][j], &kl[j]);
        }
    }
}

/// Makes `stages` hold sixteen bivectors of dimension n, keeping them when they already do.
fn ensure_stages(stages: &mut Stages, n: usize) {
    if stages.len() != ALL_STAGES || stages[0].dim() != n {
        stages.clear();
        stages.extend((0..ALL_STAGES).map(|_| Bivector::zero(n)));
    }
}

/// The adaptive Dormand–Prince 8(5,3) method (Hairer, Nørsett & Wanner, "Solving ODEs I",
/// II.5; Hairer's dop853), applied on Spin(N) × so(N)* in the Runge–Kutta–Munthe-Kaas way,
/// as [`Dopri5`](crate::dynamics::Dopri5) is: the attitude is R₀ exp(A) with A integrated in
/// the Lie algebra (dA/dt = dexp⁻¹₋A(−½ω), truncated after the terms order 8 needs), the
/// momentum L in its vector space. The rotor stays on the group to round-off.
///
/// Order 8. The error of a step is the 5th-order estimate, damped by the 3rd-order one as in
/// dop853 (err = ‖e₅‖² / √(‖e₅‖² + 0.01‖e₃‖²)), on (L, A) with the mixed tolerance
/// atol + rtol·|y|; the step size follows h ← h·clamp(0.9 err^(−1/8), 0.333, 6), without
/// growth right after a rejection; the first step comes from Hairer's starting-step
/// heuristic. Twelve right-hand sides per accepted step, eleven per rejected one (the first
/// stage is f at the previous solution and is reused).
///
/// As an [`Integrator`](super::Integrator), one call advances exactly by the requested h with as many internal
/// steps as the tolerance needs; [`Dop853::dense_output`] evaluates the state inside the last
/// internal step (order 7) and [`Dop853::dense_samples`] samples a whole run from it.
/// [`Dop853::fixed_step`] is the same method without step-size control.
#[derive(Clone, Debug)]
pub struct Dop853 {
    rtol: f64,
    atol: f64,
    adaptive: bool,
    max_steps: usize,
    h_next: Option<f64>,
    accepted: usize,
    rejected: usize,
    rhs: usize,
    last_rejected: bool,
    /// f at the start of the next step (time, dL/dt, ω), valid within one call.
    first: Option<(f64, Bivector, Bivector)>,
    last: LastStep,
    /// The commutator powers of dexp⁻¹ above N = 8 (kept, so that steps do not allocate
    /// them).
    scratch: Vec<f64>,
}

/// The last accepted step: what its dense output needs.
#[derive(Clone, Debug)]
struct LastStep {
    valid: bool,
    /// Whether stages 12–15 (the dense output's) are filled for this step.
    extended: bool,
    t: f64,
    h: f64,
    r0: Option<Attitude>,
    l0: Bivector,
    l1: Bivector,
    a1: Bivector,
    kl: Stages,
    ka: Stages,
}

impl Dop853 {
    /// Returns the adaptive integrator with relative and absolute tolerances (at most 10⁶
    /// internal steps per call).
    ///
    /// # Errors
    /// [`DynamicsError::InvalidTolerance`] unless both tolerances are finite and
    /// non-negative and at least one is positive.
    pub fn new(rtol: f64, atol: f64) -> Result<Self, DynamicsError> {
        if !(rtol.is_finite() && atol.is_finite() && rtol >= 0.0 && atol >= 0.0)
            || rtol + atol == 0.0
        {
            return Err(DynamicsError::InvalidTolerance { rtol, atol });
        }
        Ok(Dop853 {
            rtol,
            atol,
            adaptive: true,
            max_steps: 1_000_000,
            h_next: None,
            accepted: 0,
            rejected: 0,
            rhs: 0,
            last_rejected: false,
            first: None,
            last: LastStep {
                valid: false,
                extended: false,
                t: 0.0,
                h: 0.0,
                r0: None,
                l0: Bivector::zero(0),
                l1: Bivector::zero(0),
                a1: Bivector::zero(0),
                kl: SmallVec::new(),
                ka: SmallVec::new(),
            },
            scratch: Vec::new(),
        })
    }

    /// Returns the method without step-size control: every [`Integrator::step`](super::Integrator::step) is one
    /// Runge–Kutta step of the requested size (order 8), for fixed-step comparisons.
    pub fn fixed_step() -> Self {
        let mut d = Dop853::new(1.0, 1.0).expect("valid tolerances");
        d.adaptive = false;
        d
    }

    /// Returns the number of right-hand-side evaluations (dL/dt and ω at one state) so far,
    /// the starting-step heuristic and the dense output included.
    pub fn rhs_evaluations(&self) -> usize {
        self.rhs
    }

    /// Returns the start time and the size of the last accepted internal step, if any: the
    /// interval [`Dop853::dense_output`] covers.
    pub fn last_step(&self) -> Option<(f64, f64)> {
        self.last.valid.then_some((self.last.t, self.last.h))
    }

    /// Returns the state (attitude, momentum) at time `t` inside the last accepted internal
    /// step from the continuous extension of order 7, applied to L and to the algebra
    /// increment A, then R = R₀ exp(A(t)). `body` is the body that step advanced (its
    /// inertia is read, not its state) and `torque` the torque it ran under: the extension
    /// costs four more right-hand sides.
    ///
    /// # Errors
    /// [`DynamicsError::InvalidSampling`] without a last step, for a body of another
    /// dimension, or for `t` outside the step; [`DynamicsError::NonFinite`].
    pub fn dense_output(
        &mut self,
        body: &RigidBody,
        torque: &dyn Torque,
        t: f64,
    ) -> Result<(Attitude, Bivector), DynamicsError> {
        let Some((t0, h)) = self.last_step() else {
            return Err(DynamicsError::InvalidSampling {
                reason: "dense output needs a step taken first",
            });
        };
        if body.dim() != self.last.l0.dim() {
            return Err(DynamicsError::InvalidSampling {
                reason: "dense output needs the body the step advanced",
            });
        }
        let theta = (t - t0) / h;
        // A little round-off beyond either end is still the same step.
        if !(-1e-12..=1.0 + 1e-12).contains(&theta) {
            return Err(DynamicsError::InvalidSampling {
                reason: "dense output is defined inside the last step only",
            });
        }
        if !self.last.extended {
            let mut kl = std::mem::take(&mut self.last.kl);
            let mut ka = std::mem::take(&mut self.last.ka);
            self.extend_stages(body, torque, &mut kl, &mut ka);
            self.last.kl = kl;
            self.last.ka = ka;
        }
        let out = self.last.dense(theta);
        if !out.0.is_finite() || !out.1.as_slice().iter().all(|x| x.is_finite()) {
            return Err(DynamicsError::NonFinite { time: t });
        }
        Ok(out)
    }

    /// Integrates from t = 0 and returns the state (attitude, momentum) at every time in
    /// `times` (ascending, ≥ 0) from the dense output, without shortening steps to hit them.
    ///
    /// # Errors
    /// [`DynamicsError::InvalidSampling`] for bad times, or from [`Dop853::fixed_step`],
    /// which has no step size of its own; [`DynamicsError::StepTooSmall`],
    /// [`DynamicsError::TooManySteps`], [`DynamicsError::NonFinite`].
    pub fn dense_samples(
        &mut self,
        body: &RigidBody,
        torque: &dyn Torque,
        times: &[f64],
    ) -> Result<Vec<(Attitude, Bivector)>, DynamicsError> {
        if !self.adaptive {
            return Err(DynamicsError::InvalidSampling {
                reason: "dense samples need the adaptive integrator (Dop853::new)",
            });
        }
        check_sample_times(times)?;
        check_state(body, 0.0)?;
        self.first = None;
        let (mut out, mut next) = samples_at_zero(body, times);
        let mut b = body.clone();
        let mut t = 0.0;
        let t_end = times.last().copied().unwrap_or(0.0);
        let mut count = 0;
        while next < times.len() {
            count_step(&mut count, self.max_steps, t)?;
            let h = self.next_h(&b, t, 1.0, torque).min(t_end - t);
            let Some((attitude, momentum)) = self.try_step(&b, t, h, torque)? else {
                continue;
            };
            let t_new = t + h;
            if next < times.len() && times[next] <= t_new {
                let mut kl = std::mem::take(&mut self.last.kl);
                let mut ka = std::mem::take(&mut self.last.ka);
                // Stage 12 is f at the new solution: the next step's first stage.
                let omega = self.extend_stages(&b, torque, &mut kl, &mut ka);
                self.first = Some((t_new, kl[STAGES].clone(), omega));
                self.last.kl = kl;
                self.last.ka = ka;
                while next < times.len() && times[next] <= t_new {
                    out.push(self.last.dense((times[next] - t) / h));
                    next += 1;
                }
            }
            b.replace_state(attitude, momentum);
            t = t_new;
        }
        Ok(out)
    }

    /// The size of the next step: the controller's, or Hairer's starting step in the
    /// direction `sign`.
    fn next_h(&mut self, body: &RigidBody, t: f64, sign: f64, torque: &dyn Torque) -> f64 {
        if !self.adaptive {
            return f64::INFINITY;
        }
        if let Some(h) = self.h_next {
            return h;
        }
        // Hairer's heuristic (Solving ODEs I, II.4): a step with h‖f‖ ≈ 0.01‖y‖ probes the
        // second derivative, and h⁸ max(‖f‖, ‖f'‖) ≈ 0.01 sets the step.
        let (dl0, w0) = self.first_stage(body, t, torque);
        let l0 = body.momentum();
        let a0 = &w0 * -0.5;
        let (atol, rtol) = (self.atol, self.rtol);
        let scale_l = |y: f64| atol + rtol * y.abs();
        let scale_a = atol + rtol;
        let rms = |l: &dyn Fn(usize) -> f64, a: &dyn Fn(usize) -> f64| -> f64 {
            let mut sum = 0.0;
            let len = l0.as_slice().len();
            for i in 0..len {
                sum += (l(i) / scale_l(l0.as_slice()[i])).powi(2);
                sum += (a(i) / scale_a).powi(2);
            }
            (sum / (2 * len).max(1) as f64).sqrt()
        };
        let d0 = rms(&|i| l0.as_slice()[i], &|_| 0.0);
        let d1 = rms(&|i| dl0.as_slice()[i], &|i| a0.as_slice()[i]);
        let h0 = if d0 < 1e-10 || d1 < 1e-10 {
            1e-6
        } else {
            0.01 * d0 / d1
        };
        let mut l1 = l0.clone();
        axpy(&mut l1, sign * h0, &dl0);
        let a1 = &a0 * (sign * h0);
        let (mut dl1, mut w1) = (Bivector::zero(l0.dim()), Bivector::zero(l0.dim()));
        self.rate(
            body,
            t + sign * h0,
            body.principal_frame_attitude(),
            &a1,
            &l1,
            torque,
            &mut dl1,
            &mut w1,
        );
        let mut da1 = Bivector::zero(l0.dim());
        dexp_inverse_8(&a1, &w1, -0.5, &mut da1, &mut self.scratch);
        let d2 = rms(&|i| dl1.as_slice()[i] - dl0.as_slice()[i], &|i| {
            da1.as_slice()[i] - a0.as_slice()[i]
        }) / h0;
        first_step_estimate(h0, d1, d2)
    }

    /// f at the start of a step, from the cache when the previous attempt began there.
    fn first_stage(
        &mut self,
        body: &RigidBody,
        t: f64,
        torque: &dyn Torque,
    ) -> (Bivector, Bivector) {
        if let Some((t_first, dl, w)) = &self.first
            && *t_first == t
        {
            return (dl.clone(), w.clone());
        }
        let zero = Bivector::zero(body.dim());
        let (mut dl, mut w) = (Bivector::zero(body.dim()), Bivector::zero(body.dim()));
        self.rate(
            body,
            t,
            body.principal_frame_attitude(),
            &zero,
            body.momentum(),
            torque,
            &mut dl,
            &mut w,
        );
        self.first = Some((t, dl.clone(), w.clone()));
        (dl, w)
    }

    /// (dL/dt, ω) at the stage state (R₀ exp(a), l) into `dl` and `omega`, counted.
    #[allow(clippy::too_many_arguments)] // the stage state and its two outputs
    fn rate(
        &mut self,
        body: &RigidBody,
        t: f64,
        r0: &Attitude,
        a: &Bivector,
        l: &Bivector,
        torque: &dyn Torque,
        dl: &mut Bivector,
        omega: &mut Bivector,
    ) {
        self.rhs += 1;
        // Stage attitudes only matter to a torque; free motion skips their exponentials.
        if torque.is_zero() {
            momentum_rate_into(body, t, r0, l, torque, dl, omega);
        } else {
            momentum_rate_into(body, t, &r0.times_exp(a), l, torque, dl, omega);
        }
    }

    /// One attempted step of size h from (t, body's state); `None` if rejected (h_next is
    /// reduced). On acceptance the stages are kept for the dense output and the new state
    /// is returned.
    fn try_step(
        &mut self,
        body: &RigidBody,
        t: f64,
        h: f64,
        torque: &dyn Torque,
    ) -> Result<Option<(Attitude, Bivector)>, DynamicsError> {
        let r0 = body.principal_frame_attitude();
        let l0 = body.momentum();
        let n = body.dim();
        self.last.valid = false;
        self.last.extended = false;
        // The stages are written in place: no bivector moves in the loop.
        let mut kl = std::mem::take(&mut self.last.kl);
        let mut ka = std::mem::take(&mut self.last.ka);
        ensure_stages(&mut kl, n);
        ensure_stages(&mut ka, n);
        let (dl, w) = self.first_stage(body, t, torque);
        kl[0].clone_from(&dl);
        for (o, x) in ka[0].as_mut_slice().iter_mut().zip(w.as_slice()) {
            *o = -0.5 * x;
        }
        let start = StepStart {
            body,
            torque,
            t,
            h,
            r0,
            l0,
        };
        let mut stage = (Bivector::zero(n), l0.clone());
        self.stages(&start, 1..STAGES, &mut kl, &mut ka, &mut stage);
        let mut l1 = l0.clone();
        let mut a1 = Bivector::zero(n);
        for s in 0..STAGES {
            if B[s] != 0.0 {
                axpy(&mut l1, h * B[s], &kl[s]);
                axpy(&mut a1, h * B[s], &ka[s]);
            }
        }
        if self.adaptive {
            let err = self.error(l0, &l1, &a1, &kl[..STAGES], &ka[..STAGES], h);
            if !err.is_finite() {
                return Err(DynamicsError::NonFinite { time: t });
            }
            if err > 1.0 {
                self.rejected += 1;
                let factor = (0.9 * err.powf(-1.0 / 8.0)).max(0.333);
                let h_new = h * factor;
                self.last.kl = kl;
                self.last.ka = ka;
                if h_new.abs() < 1e-14 * t.abs().max(1.0) {
                    return Err(DynamicsError::StepTooSmall {
                        time: t,
                        step: h_new,
                    });
                }
                self.h_next = Some(h_new);
                self.last_rejected = true;
                return Ok(None);
            }
            let mut factor = if err == 0.0 {
                6.0
            } else {
                (0.9 * err.powf(-1.0 / 8.0)).clamp(0.333, 6.0)
            };
            if self.last_rejected {
                factor = factor.min(1.0);
            }
            self.last_rejected = false;
            self.h_next = Some(h * factor);
        }
        self.accepted += 1;
        let attitude = r0.times_exp(&a1);
        // A finite error estimate does not make the state finite: an increment A beyond f64
        // scales its own tolerance to ∞ (the estimate then reads 0).
        check_finite(&attitude, &l1, t)?;
        let last = &mut self.last;
        last.valid = true;
        last.t = t;
        last.h = h;
        match &mut last.r0 {
            Some(r) if r.dim() == n => r.clone_from(r0),
            slot => *slot = Some(r0.clone()),
        }
        last.l0.clone_from(l0);
        last.l1.clone_from(&l1);
        last.a1.clone_from(&a1);
        last.kl = kl;
        last.ka = ka;
        Ok(Some((attitude, l1)))
    }

    /// The scaled error of a step: dop853's blend of the 5th- and 3rd-order estimates.
    fn error(
        &self,
        l0: &Bivector,
        l1: &Bivector,
        a1: &Bivector,
        kl: &[Bivector],
        ka: &[Bivector],
        h: f64,
    ) -> f64 {
        let mut err5 = 0.0;
        let mut err3 = 0.0;
        let mut count = 0usize;
        let len = l0.as_slice().len();
        for i in 0..len {
            let (mut e5l, mut e3l, mut e5a, mut e3a) = (0.0, 0.0, 0.0, 0.0);
            for s in 0..STAGES {
                let (fl, fa) = (kl[s].as_slice()[i], ka[s].as_slice()[i]);
                e5l += E5[s] * fl;
                e5a += E5[s] * fa;
                e3l += (B[s] - BHH[s]) * fl;
                e3a += (B[s] - BHH[s]) * fa;
            }
            let sl = self.atol + self.rtol * l0.as_slice()[i].abs().max(l1.as_slice()[i].abs());
            let sa = self.atol + self.rtol * a1.as_slice()[i].abs().max(1.0);
            err5 += (e5l / sl).powi(2) + (e5a / sa).powi(2);
            err3 += (e3l / sl).powi(2) + (e3a / sa).powi(2);
            count += 2;
        }
        let mut deno = err5 + 0.01 * err3;
        if deno <= 0.0 {
            deno = 1.0;
        }
        h.abs() * err5 * (1.0 / (count.max(1) as f64 * deno)).sqrt()
    }

    /// Adds stages 12–15 (f at the solution and the three extra stages) to an accepted
    /// step's twelve; returns ω at the solution.
    fn extend_stages(
        &mut self,
        body: &RigidBody,
        torque: &dyn Torque,
        kl: &mut Stages,
        ka: &mut Stages,
    ) -> Bivector {
        let r0 = self
            .last
            .r0
            .clone()
            .expect("an accepted step has its attitude");
        let l0 = self.last.l0.clone();
        let start = StepStart {
            body,
            torque,
            t: self.last.t,
            h: self.last.h,
            r0: &r0,
            l0: &l0,
        };
        // Stage 12 is f at the solution (A₁, L₁) itself.
        let mut stage = (self.last.a1.clone(), self.last.l1.clone());
        let omega_end = self.stages(&start, STAGES..ALL_STAGES, kl, ka, &mut stage);
        self.last.extended = true;
        omega_end.expect("the range holds stage 12")
    }

    /// Evaluates the stages `range` of the step from `start`: each stage's state (A, L) into
    /// `stage` from the earlier stages (stage 12, the solution, is taken as `stage` holds
    /// it), then its rates dL/dt into `kl[s]` and dA/dt = dexp⁻¹ into `ka[s]`. Returns ω at
    /// stage 12 when the range holds it.
    fn stages(
        &mut self,
        start: &StepStart,
        range: std::ops::Range<usize>,
        kl: &mut Stages,
        ka: &mut Stages,
        stage: &mut (Bivector, Bivector),
    ) -> Option<Bivector> {
        let (a_stage, l_stage) = stage;
        let mut omega = Bivector::zero(start.l0.dim());
        let mut omega_end = None;
        for s in range {
            if s != STAGES {
                stage_state(s, start.h, start.l0, kl, ka, l_stage, a_stage);
            }
            let (dl_s, ka_s) = (&mut kl[s], &mut ka[s]);
            self.rate(
                start.body,
                start.t + C[s] * start.h,
                start.r0,
                a_stage,
                l_stage,
                start.torque,
                dl_s,
                &mut omega,
            );
            dexp_inverse_8(a_stage, &omega, -0.5, ka_s, &mut self.scratch);
            if s == STAGES {
                omega_end = Some(omega.clone());
            }
        }
        omega_end
    }
}

impl LastStep {
    /// The state at t₀ + θh (θ ∈ [0, 1]) from the continuous extension of order 7, applied
    /// to L and to the algebra increment A (A(0) = 0); needs all sixteen stages.
    fn dense(&self, theta: f64) -> (Attitude, Bivector) {
        let h = self.h;
        let interp = |y0: &Bivector, y1: &Bivector, k: &[Bivector]| -> Bivector {
            // y(θ) = r₁ + θ(r₂ + (1−θ)(r₃ + θ(r₄ + (1−θ)(r₅ + θ(r₆ + (1−θ)(r₇ + θ r₈))))))
            let r2 = y1 - y0;
            let mut r3 = &k[0] * h;
            r3 -= &r2;
            let mut r4 = r2.clone();
            axpy(&mut r4, -h, &k[STAGES]);
            r4 -= &r3;
            let mut acc = Bivector::zero(y0.dim());
            for (row, weight) in D.iter().enumerate().rev() {
                // acc ← r₅₊row + w·acc, with w alternately θ and 1 − θ from the inside out.
                let w = if row % 2 == 0 { theta } else { 1.0 - theta };
                acc *= w;
                for (ks, d) in k.iter().zip(weight) {
                    if *d != 0.0 {
                        axpy(&mut acc, h * d, ks);
                    }
                }
            }
            acc *= 1.0 - theta;
            acc += &r4;
            acc *= theta;
            acc += &r3;
            acc *= 1.0 - theta;
            acc += &r2;
            acc *= theta;
            acc += y0;
            acc
        };
        let l = interp(&self.l0, &self.l1, &self.kl);
        let zero = Bivector::zero(self.l0.dim());
        let a = interp(&zero, &self.a1, &self.ka);
        let r0 = self.r0.as_ref().expect("an accepted step has its attitude");
        (r0.times_exp(&a), l)
    }
}

step_counters!(Dop853);

impl_integrator!(
    Dop853,
    order = |_| 8,
    name = |_| "dop853",
    // Advances exactly by h: one step without step-size control
    // ([`Dop853::fixed_step`]), otherwise internal adaptive steps (the last one shortened).
    step = |this, body, t, h, torque| {
        if !h.is_finite() || !t.is_finite() {
            return Err(DynamicsError::InvalidSampling {
                reason: "the time and the step must be finite",
            });
        }
        check_state(body, t)?;
        this.first = None;
        if !this.adaptive {
            let (attitude, momentum) = this
                .try_step(body, t, h, torque)?
                .expect("a step without control is always accepted");
            body.replace_state(attitude, momentum);
            return Ok(());
        }
        advance_controlled(this, body, t, h, torque)
    }
);

impl ControlledPair for Dop853 {
    fn proposed_step(&mut self, body: &RigidBody, t: f64, sign: f64, torque: &dyn Torque) -> f64 {
        self.next_h(body, t, sign, torque)
    }

    fn attempt(&mut self, body: &RigidBody, t: f64, h: f64, torque: &dyn Torque) -> Attempt {
        self.try_step(body, t, h, torque)
    }

    fn control(&mut self) -> (&mut Option<f64>, usize) {
        (&mut self.h_next, self.max_steps)
    }
}

#[cfg(test)]
mod tests {
    use super::super::dexp_inverse;
    use super::*;

    /// The stack version is the series of `dexp_inverse`, term for term.
    #[test]
    fn dexp_inverse_8_is_dexp_inverse_of_order_8() {
        for n in [3usize, 4, 5, 8, 9] {
            let len = n * (n - 1) / 2;
            let omega: Vec<f64> = (0..len).map(|k| 0.3 * (k as f64 + 0.5).sin()).collect();
            let w: Vec<f64> = (0..len).map(|k| (1.7 * k as f64).cos()).collect();
            let omega = Bivector::from_components(n, &omega).unwrap();
            let w = Bivector::from_components(n, &w).unwrap();
            let mut fast = Bivector::zero(n);
            dexp_inverse_8(&omega, &w, -0.5, &mut fast, &mut Vec::new());
            let series = dexp_inverse(&omega, &(&w * -0.5), 8);
            let gap = (&fast - &series).max_abs();
            assert!(gap < 1e-15, "N = {n}: {gap:e}");
        }
    }
}
