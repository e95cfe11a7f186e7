//! The implicit midpoint rule: energy-conserving, second order.

use super::{DynamicsError, Iterations, accept_state, axpy, momentum_rate_into};
use crate::algebra::Bivector;

/// The implicit midpoint rule on the momentum, L₁ = L₀ + h f((L₀ + L₁)/2) with
/// f(L) = I⁻¹(L) × L + τ, and the attitude advanced on the group, R₁ = R₀ exp(−½ h ω_mid).
///
/// Order 2 and symmetric. It conserves every quadratic first integral of the free body
/// exactly (up to the solver tolerance): the energy and |L|², and in 4D also the Pfaffian,
/// hence all Casimirs; in N ≥ 5 the quartic Casimir tr L⁴ is not conserved (Austin,
/// Krishnaprasad and Wang, *Almost Poisson integration of rigid body systems*, 1993).
///
/// The nonlinear equation is solved by fixed-point iteration, which converges when
/// h·|ω| ≲ 1; the number of iterations is bounded by [`Midpoint::max_iterations`] and
/// reported ([`Midpoint::last_iterations`], [`Midpoint::total_iterations`]). A step whose
/// iteration does not converge returns [`DynamicsError::SolverDidNotConverge`].
#[derive(Clone, Copy, Debug)]
pub struct Midpoint {
    tolerance: f64,
    iterations: Iterations,
}

impl Default for Midpoint {
    /// Relative tolerance 4ε on the momentum, at most 100 iterations per step.
    fn default() -> Self {
        Midpoint {
            tolerance: 4.0 * f64::EPSILON,
            iterations: Iterations::new(100),
        }
    }
}

impl Midpoint {
    /// Returns the integrator with relative tolerance 4ε on the momentum and at most 100
    /// iterations per step (the same as `Midpoint::default()`).
    pub fn new() -> Self {
        Self::default()
    }

    /// Returns the integrator with a relative tolerance on the momentum and an iteration
    /// bound per step.
    pub fn with_tolerance(tolerance: f64, max_iterations: usize) -> Self {
        Midpoint {
            tolerance,
            iterations: Iterations::new(max_iterations),
        }
    }
}

iteration_counters!(Midpoint, "fixed-point iterations");

impl_integrator!(
    Midpoint,
    order = |_| 2,
    name = |_| "midpoint",
    step = |this, body, t, h, torque| {
        let n = body.dim();
        let l0 = body.momentum().clone();
        let r0 = body.principal_frame_attitude().clone();
        let scale = l0.max_abs().max(f64::MIN_POSITIVE);
        // The iteration works in place on these (no allocation per iteration for free
        // motion at any N).
        let (mut f, mut omega, mut mid) = (Bivector::zero(n), Bivector::zero(n), l0.clone());
        // The torque sees the attitude at the half step, R₀ exp(−¼ h ω_mid).
        let rate = |l_mid: &Bivector, f: &mut Bivector, omega: &mut Bivector| {
            if torque.is_zero() {
                momentum_rate_into(body, t + 0.5 * h, &r0, l_mid, torque, f, omega);
            } else {
                let r_mid = r0.times_exp(&(&body.omega_of(l_mid) * (-0.25 * h)));
                momentum_rate_into(body, t + 0.5 * h, &r_mid, l_mid, torque, f, omega);
            }
        };
        // Explicit Euler start, then fixed-point iteration on L₁.
        rate(&l0, &mut f, &mut omega);
        let mut l1 = l0.clone();
        axpy(l1.as_mut_slice(), h, f.as_slice());
        let mut iterations = 0;
        let mut residual = f64::INFINITY;
        while iterations < this.iterations.max {
            iterations += 1;
            for ((m, a), b) in mid
                .as_mut_slice()
                .iter_mut()
                .zip(l0.as_slice())
                .zip(l1.as_slice())
            {
                *m = (a + b) * 0.5;
            }
            rate(&mid, &mut f, &mut omega);
            // L₁ ← L₀ + h f, and the largest change (a NaN is skipped here, as by max_abs:
            // the state is checked below).
            let mut change = 0.0f64;
            for ((x, a), d) in l1
                .as_mut_slice()
                .iter_mut()
                .zip(l0.as_slice())
                .zip(f.as_slice())
            {
                let next = a + d * h;
                change = change.max((next - *x).abs());
                *x = next;
            }
            residual = change / scale;
            if residual <= this.tolerance {
                break;
            }
        }
        this.iterations.record(iterations);
        if !residual.is_finite() || residual > this.tolerance {
            return Err(DynamicsError::SolverDidNotConverge {
                time: t,
                iterations,
                residual,
            });
        }
        let mid = (&l0 + &l1) * 0.5;
        let omega_mid = body.omega_of(&mid);
        let r1 = r0.times_exp(&(omega_mid * (-0.5 * h)));
        // The residual's max ignores NaN, so the state itself is checked.
        accept_state(body, r1, l1, t)
    }
);
