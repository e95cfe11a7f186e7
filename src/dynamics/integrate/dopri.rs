//! Adaptive Dormand–Prince 5(4) on the group, with dense output.

use super::{
    Attempt, ControlledPair, DEXP_INVERSE_5, DynamicsError, advance_controlled, axpy, check_finite,
    check_sample_times, count_step, dexp_inverse_packed, momentum_rate_into, samples_at_zero,
};
use crate::algebra::Bivector;
use crate::dynamics::Attitude;
use crate::dynamics::{RigidBody, Torque};
use smallvec::SmallVec;

// Dormand & Prince, J. Comput. Appl. Math. 6 (1980) 19; dense output of Hairer, Nørsett &
// Wanner, "Solving ODEs I", II.6 (dopri5 "contd5").
const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
const A: [[f64; 6]; 7] = [
    [0.0; 6],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// b − b̂: the error weights of the embedded 4th-order solution.
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];
/// Dense-output weights d₁ … d₇.
const D: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

/// The adaptive embedded Dormand–Prince 5(4) method, applied on Spin(N) × so(N)* in the
/// Runge–Kutta–Munthe-Kaas way: the attitude is R₀ exp(A) with A integrated in the Lie
/// algebra (dA/dt = dexp⁻¹₋A(−½ω), truncated after the terms order 5 needs), the momentum L
/// in its vector space.
///
/// Order 5 (local extrapolation); step-size control on the embedded error of (L, A) with
/// the usual mixed tolerance atol + rtol·|y|; a step that fails is retried smaller. Dense
/// output of order 4 between accepted steps serves [`Dopri5::dense_samples`]. As an
/// [`Integrator`](super::Integrator), one call advances exactly by the requested h with as many internal steps
/// as the tolerance needs ([`Dopri5::accepted_steps`], [`Dopri5::rejected_steps`] report
/// them).
#[derive(Clone, Copy, Debug)]
pub struct Dopri5 {
    rtol: f64,
    atol: f64,
    max_steps: usize,
    h_next: Option<f64>,
    accepted: usize,
    rejected: usize,
}

impl Dopri5 {
    /// Returns the integrator with relative and absolute tolerances (at most 10⁶ internal
    /// steps per call).
    pub fn new(rtol: f64, atol: f64) -> Self {
        Dopri5 {
            rtol,
            atol,
            max_steps: 1_000_000,
            h_next: None,
            accepted: 0,
            rejected: 0,
        }
    }

    /// Returns the number of right-hand sides evaluated so far: seven per attempted step
    /// (the seventh stage is the rate at the new solution; a step does not reuse the last
    /// one, so the count compares directly with [`Dop853::rhs_evaluations`]).
    ///
    /// [`Dop853::rhs_evaluations`]: crate::dynamics::Dop853::rhs_evaluations
    ///
    /// ```
    /// use rotorflow::dynamics::{Dopri5, Integrator, RigidBody, TorqueInput};
    /// use rotorflow::prelude::*;
    /// use std::cell::Cell;
    /// let inertia = InertiaMap::from_principal_second_moments(&[1.0, 2.0, 3.0])?;
    /// let omega = Bivector::from_components(3, &[0.3, 1.0, 0.2])?;
    /// let mut body = RigidBody::from_body_velocity(inertia, Rotor::identity(3), &omega)?;
    /// // A torque evaluated once per right-hand side counts them.
    /// let calls = Cell::new(0);
    /// let damping = |input: &TorqueInput<'_>| {
    ///     calls.set(calls.get() + 1);
    ///     input.omega * -0.1
    /// };
    /// let mut dopri = Dopri5::new(1e-10, 1e-12);
    /// dopri.step(&mut body, 0.0, 1.0, &damping)?;
    /// assert!(dopri.accepted_steps() > 1);
    /// assert_eq!(dopri.rhs_evaluations(), calls.get());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn rhs_evaluations(&self) -> usize {
        7 * (self.accepted + self.rejected)
    }

    /// Integrates from t = 0 and returns the state (attitude, momentum) at every time in
    /// `times` (ascending, ≥ 0) from the dense output, without shortening steps to hit them.
    ///
    /// # Errors
    /// [`DynamicsError::InvalidSampling`], [`DynamicsError::StepTooSmall`],
    /// [`DynamicsError::TooManySteps`], [`DynamicsError::NonFinite`].
    pub fn dense_samples(
        &mut self,
        body: &RigidBody,
        torque: &dyn Torque,
        times: &[f64],
    ) -> Result<Vec<(Attitude, Bivector)>, DynamicsError> {
        check_sample_times(times)?;
        let (mut out, mut next) = samples_at_zero(body, times);
        let mut b = body.clone();
        let mut t = 0.0;
        let t_end = times.last().copied().unwrap_or(0.0);
        let mut count = 0;
        while next < times.len() {
            count_step(&mut count, self.max_steps, t)?;
            let h = self
                .initial_h(&b, t, torque)
                .min(t_end - t)
                .max(f64::MIN_POSITIVE);
            let step = self.try_step(&b, t, h, torque)?;
            let Some(step) = step else { continue };
            let t_new = t + step.h;
            while next < times.len() && times[next] <= t_new {
                let theta = (times[next] - t) / step.h;
                out.push(step.dense(b.principal_frame_attitude(), theta));
                next += 1;
            }
            b.replace_state(step.attitude.clone(), step.momentum.clone());
            t = t_new;
        }
        Ok(out)
    }

    fn initial_h(&self, body: &RigidBody, _t: f64, _torque: &dyn Torque) -> f64 {
        self.h_next.unwrap_or_else(|| {
            // A tenth of the time to turn one radian, scaled by the tolerance.
            let w = body.omega().norm().max(1e-300);
            (0.1 / w) * (self.rtol.max(1e-16) / 1e-6).powf(0.2).min(1.0)
        })
    }

    /// One attempted step of size h; `None` if rejected (h_next is reduced).
    fn try_step(
        &mut self,
        body: &RigidBody,
        t: f64,
        h: f64,
        torque: &dyn Torque,
    ) -> Result<Option<StepResult>, DynamicsError> {
        let r0 = body.principal_frame_attitude();
        let l0 = body.momentum();
        let n = body.dim();
        let len = l0.as_slice().len();
        // The seven stages of L and of A, packed; inline (no heap) for N ≤ 8, one block each
        // above, and every stage sum is written in place.
        let mut kl: Flat = SmallVec::from_elem(0.0, 7 * len);
        let mut ka: Flat = SmallVec::from_elem(0.0, 7 * len);
        let mut scratch: SmallVec<[f64; 2 * 28]> = SmallVec::from_elem(0.0, 2 * len);
        let (power, next) = scratch.split_at_mut(len);
        let mut a_stage = Bivector::zero(n);
        let mut l_stage = l0.clone();
        let (mut dl, mut omega) = (Bivector::zero(n), Bivector::zero(n));
        for s in 0..7 {
            if s > 0 {
                a_stage.as_mut_slice().fill(0.0);
                l_stage.as_mut_slice().copy_from_slice(l0.as_slice());
                for (j, &c) in A[s][..s].iter().enumerate() {
                    if c != 0.0 {
                        let stage = j * len..(j + 1) * len;
                        axpy(a_stage.as_mut_slice(), h * c, &ka[stage.clone()]);
                        axpy(l_stage.as_mut_slice(), h * c, &kl[stage]);
                    }
                }
            }
            // Stage attitudes only matter to a torque; free motion skips their exponentials.
            let turned;
            let r_stage = if torque.is_zero() {
                r0
            } else {
                turned = r0.times_exp(&a_stage);
                &turned
            };
            let time = t + C[s] * h;
            momentum_rate_into(body, time, r_stage, &l_stage, torque, &mut dl, &mut omega);
            let stage = s * len..(s + 1) * len;
            kl[stage.clone()].copy_from_slice(dl.as_slice());
            dexp_inverse_packed(
                n,
                a_stage.as_slice(),
                omega.as_slice(),
                -0.5,
                &DEXP_INVERSE_5,
                &mut ka[stage],
                (&mut *power, &mut *next),
            );
        }
        // Stage 7 was evaluated at the 5th-order solution (FSAL).
        let (a1, l1) = (a_stage, l_stage);
        // The embedded error of each component, Σₛ h Eₛ kₛ, over L and then A.
        let error = |k: &[f64], i: usize| {
            (0..7)
                .filter(|&s| E[s] != 0.0)
                .fold(0.0, |e, s| e + k[s * len + i] * (h * E[s]))
        };
        let mut sum = 0.0;
        let mut count = 0.0f64;
        for (i, (y0, y1)) in l0.as_slice().iter().zip(l1.as_slice()).enumerate() {
            let sc = self.atol + self.rtol * y0.abs().max(y1.abs());
            sum += (error(&kl, i) / sc).powi(2);
            count += 1.0;
        }
        for (i, y1) in a1.as_slice().iter().enumerate() {
            let sc = self.atol + self.rtol * y1.abs().max(1.0);
            sum += (error(&ka, i) / sc).powi(2);
            count += 1.0;
        }
        let err = (sum / count.max(1.0)).sqrt();
        if !err.is_finite() {
            return Err(DynamicsError::NonFinite { time: t });
        }
        let factor = if err == 0.0 {
            5.0
        } else {
            (0.9 * err.powf(-0.2)).clamp(0.2, 5.0)
        };
        if err > 1.0 {
            self.rejected += 1;
            let h_new = h * factor.min(1.0);
            if h_new < 1e-14 * t.abs().max(1.0) {
                return Err(DynamicsError::StepTooSmall {
                    time: t,
                    step: h_new,
                });
            }
            self.h_next = Some(h_new);
            return Ok(None);
        }
        self.accepted += 1;
        self.h_next = Some(h * factor);
        let attitude = r0.times_exp(&a1);
        // A finite error estimate does not make the state finite: an increment A beyond f64
        // scales its own tolerance to ∞ (the estimate then reads 0).
        check_finite(&attitude, &l1, t)?;
        Ok(Some(StepResult {
            h,
            l0: l0.clone(),
            a1,
            kl,
            ka,
            attitude,
            momentum: l1,
        }))
    }
}

/// The seven stage values of one step, packed (7 × 28 inline: N ≤ 8).
type Flat = SmallVec<[f64; 7 * 28]>;

/// An accepted step with what its dense output needs.
struct StepResult {
    h: f64,
    l0: Bivector,
    a1: Bivector,
    kl: Flat,
    ka: Flat,
    attitude: Attitude,
    /// L at the end of the step.
    momentum: Bivector,
}

impl StepResult {
    /// The state at t₀ + θh (θ ∈ [0, 1]) from Hairer's 4th-order continuous extension,
    /// applied to L and to the algebra increment A (A(0) = 0).
    fn dense(&self, r0: &Attitude, theta: f64) -> (Attitude, Bivector) {
        let len = self.l0.as_slice().len();
        // One component of y(θ) = r1 + θ(r2 + (1−θ)(r3 + θ(r4 + (1−θ) r5))).
        let interp = |y0: f64, y1: f64, k: &[f64], i: usize| -> f64 {
            let h = self.h;
            let r1 = y0;
            let r2 = y1 - y0;
            let r3 = k[i] * h - r2;
            let r4 = (r2 - k[6 * len + i] * h) - r3;
            let r5 = (0..7)
                .filter(|&s| D[s] != 0.0)
                .fold(0.0, |acc, s| acc + k[s * len + i] * (h * D[s]));
            let inner = r4 + r5 * (1.0 - theta);
            let inner = r3 + inner * theta;
            let inner = r2 + inner * (1.0 - theta);
            r1 + inner * theta
        };
        let n = self.l0.dim();
        let mut l = Bivector::zero(n);
        let mut a = Bivector::zero(n);
        let pairs = self.l0.as_slice().iter().zip(self.momentum.as_slice());
        for (i, (out, (y0, y1))) in l.as_mut_slice().iter_mut().zip(pairs).enumerate() {
            *out = interp(*y0, *y1, &self.kl, i);
        }
        for (i, (out, y1)) in a
            .as_mut_slice()
            .iter_mut()
            .zip(self.a1.as_slice())
            .enumerate()
        {
            *out = interp(0.0, *y1, &self.ka, i);
        }
        (r0.times_exp(&a), l)
    }
}

step_counters!(Dopri5);

impl_integrator!(
    Dopri5,
    order = |_| 5,
    name = |_| "dopri5",
    // Advances exactly by h, with internal adaptive steps (the last one shortened).
    step = |this, body, t, h, torque| { advance_controlled(this, body, t, h, torque) }
);

impl ControlledPair for Dopri5 {
    fn proposed_step(&mut self, body: &RigidBody, t: f64, _sign: f64, torque: &dyn Torque) -> f64 {
        self.initial_h(body, t, torque)
    }

    fn attempt(&mut self, body: &RigidBody, t: f64, h: f64, torque: &dyn Torque) -> Attempt {
        let step = self.try_step(body, t, h, torque)?;
        Ok(step.map(|s| (s.attitude, s.momentum)))
    }

    fn control(&mut self) -> (&mut Option<f64>, usize) {
        (&mut self.h_next, self.max_steps)
    }
}
