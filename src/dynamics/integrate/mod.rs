//! Integrators of Euler's equations behind one trait.
//!
//! | integrator | order | what it conserves |
//! |---|---|---|
//! | [`Rkmk4`] | 4 | the rotor stays on Spin(N) (updates are rotor exponentials); energy and Casimirs drift like O(h⁴ t) |
//! | [`LiePoissonRk4`] | 4 | as RK4, and every Casimir of L and the space-frame L to round-off (L moves by the step's rotation); energy drifts like O(h⁴ t) |
//! | [`Splitting`] Strang | 2 | every Casimir of L and the space-frame L to round-off; energy error bounded, O(h²), no drift (symplectic) |
//! | [`Splitting`] Yoshida 4 | 4 | as Strang, energy error O(h⁴) |
//! | [`Dopri5`] | 5 (adaptive, error estimate of order 4) | the rotor stays on Spin(N); invariants drift within the tolerance |
//! | [`Dop853`] | 8 (adaptive, error estimates of orders 5 and 3) | as Dopri5; far fewer right-hand sides at tight tolerances |
//! | [`Midpoint`] | 2 | energy and ‖L‖² exactly (solver tolerance); all Casimirs in N ≤ 4; implicit, bounded fixed-point solve |
//! | [`MoserVeselov`] | 2 (4 composed) | every Casimir, every Manakov integral and the energy to round-off, the space-frame L; physical inertia only; implicit, Newton solve |
//!
//! With a torque the splitting and Moser–Veselov integrators use a kick–drift–kick composition (the kick is
//! the torque's flow with the attitude frozen, taken by the midpoint rule), which keeps the
//! order for torques that do not depend on L; the Casimirs are then no longer invariants of
//! the motion.
//!
//! Every integrator is built the same way: `new` takes what it cannot do without (the
//! tolerances of [`Dopri5::new`] and [`Dop853::new`], the composition of [`Splitting::new`]
//! and [`ProcessedSplitting::new`]) and nothing else; an integrator without such parameters
//! ([`Rkmk4::new`], [`LiePoissonRk4::new`], [`Midpoint::new`], [`MoserVeselov::new`]) also
//! implements `Default`, which is the same value. Options beyond that are `with_*` methods
//! on the value ([`Dopri5::with_max_steps`], [`MoserVeselov::with_max_iterations`], …) or
//! named constructors ([`Splitting::strang`], [`MoserVeselov::yoshida4`],
//! [`Midpoint::with_tolerance`]).
//!
//! ```
//! use rotorflow::dynamics::{Dop853, Dopri5, LiePoissonRk4, Midpoint, MoserVeselov, Rkmk4};
//! use rotorflow::dynamics::{Splitting, SplittingOrder};
//! let _ = (Rkmk4::new(), LiePoissonRk4::new(), Midpoint::new(), MoserVeselov::new());
//! let _ = (Dopri5::new(1e-10, 1e-12), Dop853::new(1e-10, 1e-12)?);
//! let _ = Splitting::new(SplittingOrder::Yoshida4);
//! assert_eq!(Midpoint::new().max_iterations(), Midpoint::default().max_iterations());
//! # Ok::<(), rotorflow::dynamics::DynamicsError>(())
//! ```

/// Implements [`Integrator`] for an integrator type, so that the trait's signatures are
/// written once. The order and the name are closures of the integrator, the step a closure
/// of the integrator and the trait's arguments (body, t, h, torque), as in
/// `impl_integrator!(Rkmk4, order = |_| 4, name = |_| "rk4", step = |this, body, t, h, torque| { … })`.
macro_rules! impl_integrator {
    (
        $ty:ty,
        order = |$order_of:pat_param| $order:expr,
        name = |$name_of:pat_param| $name:expr,
        step = |$this:pat_param, $body:ident, $t:ident, $h:ident, $torque:ident| $step:block $(,)?
    ) => {
        impl $crate::dynamics::integrate::Integrator for $ty {
            fn order(&self) -> u32 {
                let $order_of = self;
                $order
            }

            fn name(&self) -> &'static str {
                let $name_of = self;
                $name
            }

            fn step(
                &mut self,
                $body: &mut $crate::dynamics::RigidBody,
                $t: f64,
                $h: f64,
                $torque: &dyn $crate::dynamics::Torque,
            ) -> Result<(), $crate::dynamics::DynamicsError> {
                let $this = self;
                $step
            }
        }
    };
}

/// The public counters of an implicit integrator's solve, read from its `iterations` field
/// (an [`Iterations`]); `$what` names what is counted in the docs.
macro_rules! iteration_counters {
    ($ty:ty, $what:literal) => {
        impl $ty {
            #[doc = concat!("Returns the bound on the ", $what, " per step.")]
            pub fn max_iterations(&self) -> usize {
                self.iterations.max
            }

            #[doc = concat!("Returns the ", $what, " of the last step (of all its substeps for a composition).")]
            pub fn last_iterations(&self) -> usize {
                self.iterations.last
            }

            #[doc = concat!("Returns the ", $what, " of all steps so far.")]
            pub fn total_iterations(&self) -> usize {
                self.iterations.total
            }

            #[doc = concat!("Returns the mean ", $what, " per step so far.")]
            pub fn mean_iterations(&self) -> f64 {
                self.iterations.total as f64 / self.iterations.steps.max(1) as f64
            }
        }
    };
}

/// The step-count accessors of an adaptive integrator with fields `max_steps`, `accepted`
/// and `rejected`.
macro_rules! step_counters {
    ($ty:ty) => {
        impl $ty {
            /// Sets the bound on internal steps per call.
            pub fn with_max_steps(mut self, max_steps: usize) -> Self {
                self.max_steps = max_steps.max(1);
                self
            }

            /// Returns the number of accepted internal steps so far.
            pub fn accepted_steps(&self) -> usize {
                self.accepted
            }

            /// Returns the number of rejected internal steps so far.
            pub fn rejected_steps(&self) -> usize {
                self.rejected
            }
        }
    };
}

mod dop853;
pub(crate) use dop853::first_step_estimate;
pub(crate) mod dop853_tableau;
mod dopri;
mod midpoint;
mod moser_veselov;
mod processed;
mod rkmk;
mod splitting;
pub(crate) use splitting::{free_flight, strang_drift_fixed};

pub use dop853::Dop853;
pub use dopri::Dopri5;
pub use midpoint::Midpoint;
pub use moser_veselov::MoserVeselov;
pub use processed::{ProcessedOrder, ProcessedSplitting};
pub use rkmk::{LiePoissonRk4, Rkmk4};
pub use splitting::{Splitting, SplittingOrder};

use super::{Attitude, RigidBody, Torque, TorqueInput};
use crate::algebra::{Bivector, commutator_packed};
#[doc(no_inline)]
pub use crate::dynamics::DynamicsError;

/// The series of [`dexp_inverse_packed`] with bivector operations, term by term: the
/// reference the packed form is tested against.
#[cfg(test)]
pub(crate) fn dexp_inverse(omega_alg: &Bivector, a: &Bivector, order: u32) -> Bivector {
    let c1 = omega_alg.commutator(a);
    let c2 = omega_alg.commutator(&c1);
    let mut out = a + &c1;
    out += &(&c2 * (1.0 / 3.0));
    if order >= 5 {
        let c4 = omega_alg.commutator(&omega_alg.commutator(&c2));
        if order >= 7 {
            let c6 = omega_alg.commutator(&omega_alg.commutator(&c4));
            out += &(c6 * (2.0 / 945.0));
        }
        out += &(c4 * (-1.0 / 45.0));
    }
    out
}

/// The coefficients of (Ω×)ᵏ, k = 1, 2, …, in [`dexp_inverse_packed`] for an integrator of
/// order 5 and of order 8.
pub(crate) const DEXP_INVERSE_5: [f64; 4] = [1.0, 1.0 / 3.0, 0.0, -1.0 / 45.0];
pub(crate) const DEXP_INVERSE_8: [f64; 6] = [1.0, 1.0 / 3.0, 0.0, -1.0 / 45.0, 0.0, 2.0 / 945.0];

/// Writes dexp⁻¹₋Ω(s·w) into `out` on packed components of an N-dimensional bivector: with
/// a = s·w, the Lie-algebra velocity of R = R₀ exp(Ω) under dR/dt = R a, the Bernoulli
/// series a + Ω×a + ⅓ Ω×(Ω×a) − (1/45)(Ω×)⁴a + (2/945)(Ω×)⁶a − … ([X, Y] = 2 X×Y, so the
/// coefficient of (Ω×)ᵏ is 2ᵏ|Bₖ|/k! with the signs of the series of x/(eˣ − 1) at −Ω),
/// truncated after the terms an integrator of order p needs: (Ω×)ᵏa with k ≤ p − 1 (odd Bₖ
/// vanish beyond B₁, so order 4 stops after the second term, order 5 adds the fourth,
/// order 8 the sixth). `coefficients` lists those of (Ω×)ᵏ, k = 1, 2, …; `scratch` is two
/// slices of the bivector's length, so nothing is allocated.
pub(crate) fn dexp_inverse_packed(
    n: usize,
    omega_alg: &[f64],
    w: &[f64],
    s: f64,
    coefficients: &[f64],
    out: &mut [f64],
    (power, next): (&mut [f64], &mut [f64]),
) {
    for ((o, p), x) in out.iter_mut().zip(power.iter_mut()).zip(w) {
        *o = s * x;
        *p = s * x;
    }
    let (mut power, mut next) = (power, next);
    for &coefficient in coefficients {
        commutator_packed(n, omega_alg, power, next);
        std::mem::swap(&mut power, &mut next);
        if coefficient != 0.0 {
            for (o, p) in out.iter_mut().zip(power.iter()) {
                *o += coefficient * p;
            }
        }
    }
}

/// y ← y + α x on packed components.
#[inline]
pub(crate) fn axpy(y: &mut [f64], alpha: f64, x: &[f64]) {
    for (a, b) in y.iter_mut().zip(x) {
        *a += alpha * b;
    }
}

/// Returns (dL/dt, ω) = (ω × L + τ, I⁻¹(L)) at time `t` for the momentum `l` and attitude
/// `attitude`: the right-hand side every integrator evaluates.
pub(crate) fn momentum_rate(
    body: &RigidBody,
    t: f64,
    attitude: &Attitude,
    l: &Bivector,
    torque: &dyn Torque,
) -> (Bivector, Bivector) {
    let n = l.dim();
    let (mut dl, mut omega) = (Bivector::zero(n), Bivector::zero(n));
    momentum_rate_into(body, t, attitude, l, torque, &mut dl, &mut omega);
    (dl, omega)
}

/// [`momentum_rate`] written into `dl` and `omega` (of the body's dimension), without
/// temporaries for free motion.
pub(crate) fn momentum_rate_into(
    body: &RigidBody,
    t: f64,
    attitude: &Attitude,
    l: &Bivector,
    torque: &dyn Torque,
    dl: &mut Bivector,
    omega: &mut Bivector,
) {
    match body.gyrostatic_momentum() {
        None => body
            .inertia()
            .apply_inverse_into(l.as_slice(), omega.as_mut_slice()),
        // A gyrostat: ω = I⁻¹(L − h), and the total L turns (dl = ω × L).
        Some(h) => {
            omega.as_mut_slice().copy_from_slice(l.as_slice());
            *omega -= h;
            let own = omega.clone();
            body.inertia()
                .apply_inverse_into(own.as_slice(), omega.as_mut_slice());
        }
    }
    commutator_packed(l.dim(), omega.as_slice(), l.as_slice(), dl.as_mut_slice());
    if !torque.is_zero() {
        *dl += &torque.torque(&TorqueInput {
            time: t,
            attitude,
            momentum: l,
            omega,
        });
    }
}

/// The iterations of an implicit integrator's solve: the bound per step, the last step's
/// count, and the totals over all steps.
#[derive(Clone, Copy, Debug)]
struct Iterations {
    max: usize,
    last: usize,
    total: usize,
    steps: usize,
}

impl Iterations {
    /// No step taken yet, at most `max` iterations per step (at least one).
    const fn new(max: usize) -> Self {
        Iterations {
            max: if max == 0 { 1 } else { max },
            last: 0,
            total: 0,
            steps: 0,
        }
    }

    /// Counts one step that took `iterations`.
    fn record(&mut self, iterations: usize) {
        self.last = iterations;
        self.total += iterations;
        self.steps += 1;
    }
}

/// Checks the times of a dense-output run: finite, non-negative and strictly increasing.
fn check_sample_times(times: &[f64]) -> Result<(), DynamicsError> {
    if times.iter().any(|t| !t.is_finite() || *t < 0.0) || times.windows(2).any(|w| w[1] <= w[0]) {
        return Err(DynamicsError::InvalidSampling {
            reason: "sample times must be finite, non-negative and strictly increasing",
        });
    }
    Ok(())
}

/// The samples at t = 0 of a dense-output run (the body's state, once per such time) and
/// the index of the first later time.
fn samples_at_zero(body: &RigidBody, times: &[f64]) -> (Vec<(Attitude, Bivector)>, usize) {
    let zeros = times.iter().take_while(|&&t| t == 0.0).count();
    let mut out = Vec::with_capacity(times.len());
    let state = (body.principal_frame_attitude(), body.momentum());
    out.extend((0..zeros).map(|_| (state.0.clone(), state.1.clone())));
    (out, zeros)
}

/// Fails with [`DynamicsError::NonFinite`] at time `t` unless the attitude and the
/// momentum are finite. (An angle h L_p / I_p that overflows can leave L finite but not
/// the attitude, and an error estimate can read 0 for an increment beyond f64: each step
/// checks the state itself.)
fn check_finite(attitude: &Attitude, momentum: &Bivector, t: f64) -> Result<(), DynamicsError> {
    if momentum.as_slice().iter().all(|x| x.is_finite()) && attitude.is_finite() {
        Ok(())
    } else {
        Err(DynamicsError::NonFinite { time: t })
    }
}

/// Fails with [`DynamicsError::NonFinite`] unless the body's state is finite.
fn check_state(body: &RigidBody, t: f64) -> Result<(), DynamicsError> {
    check_finite(body.principal_frame_attitude(), body.momentum(), t)
}

/// Makes (attitude, momentum) the body's state if both are finite; otherwise leaves the
/// body as it was and fails with [`DynamicsError::NonFinite`] at time `t`.
fn accept_state(
    body: &mut RigidBody,
    attitude: Attitude,
    momentum: Bivector,
    t: f64,
) -> Result<(), DynamicsError> {
    check_finite(&attitude, &momentum, t)?;
    body.replace_state(attitude, momentum);
    Ok(())
}

/// Counts one more internal step of a call at `time`, refusing more than `max_steps`.
fn count_step(count: &mut usize, max_steps: usize, time: f64) -> Result<(), DynamicsError> {
    *count += 1;
    if *count > max_steps {
        return Err(DynamicsError::TooManySteps {
            time,
            steps: *count,
        });
    }
    Ok(())
}

/// An embedded Runge–Kutta pair with step-size control, as [`advance_controlled`] drives it.
trait ControlledPair {
    /// The size of the next attempt from `t` in the direction `sign` (its magnitude is used).
    fn proposed_step(&mut self, body: &RigidBody, t: f64, sign: f64, torque: &dyn Torque) -> f64;
    /// One attempt of size h from (t, body's state).
    fn attempt(&mut self, body: &RigidBody, t: f64, h: f64, torque: &dyn Torque) -> Attempt;
    /// The controller's next step (`None` before the first accepted one) and the most
    /// internal steps one call may take.
    fn control(&mut self) -> (&mut Option<f64>, usize);
}

/// An attempted step: the new (attitude, momentum), or `None` if the error test rejected it
/// (the next proposed step is then smaller).
type Attempt = Result<Option<(Attitude, Bivector)>, DynamicsError>;

/// Advances `body` from t exactly by h in the pair's adaptive steps, the last one shortened
/// to land on t + h.
fn advance_controlled(
    pair: &mut impl ControlledPair,
    body: &mut RigidBody,
    t: f64,
    h: f64,
    torque: &dyn Torque,
) -> Result<(), DynamicsError> {
    let t_end = t + h;
    let mut time = t;
    let mut count = 0;
    let sign = h.signum();
    while (t_end - time) * sign > 1e-14 * t_end.abs().max(1.0) {
        count_step(&mut count, pair.control().1, time)?;
        let remaining = t_end - time;
        let mut try_h = pair.proposed_step(body, time, sign, torque).abs() * sign;
        if try_h.abs() >= remaining.abs() {
            try_h = remaining;
        }
        let saved = *pair.control().0;
        if let Some((attitude, momentum)) = pair.attempt(body, time, try_h, torque)? {
            body.replace_state(attitude, momentum);
            time += try_h;
            if try_h == remaining {
                // Do not let the shortened last step shrink the next call's first step.
                let next = pair.control().0;
                *next = saved.map(|s| s.max(next.unwrap_or(s)));
            }
        }
    }
    Ok(())
}

/// An integrator of the rigid-body equations: advances a [`RigidBody`] by one step.
pub trait Integrator {
    /// Returns the integrator's order of accuracy.
    fn order(&self) -> u32;

    /// Returns a short name ("rk4", "strang", …).
    fn name(&self) -> &'static str;

    /// Advances `body` from time `t` by a step `h` under `torque`.
    ///
    /// # Errors
    /// [`DynamicsError`] when the step cannot be taken (unsupported inertia, non-finite state).
    fn step(
        &mut self,
        body: &mut RigidBody,
        t: f64,
        h: f64,
        torque: &dyn Torque,
    ) -> Result<(), DynamicsError>;
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The packed series equals the bivector one for orders 5 and 8, inline and above N = 8.
    #[test]
    fn packed_dexp_inverse_is_the_series() {
        let mut checked = 0;
        for n in [3usize, 4, 5, 8, 9, 12] {
            let len = n * (n - 1) / 2;
            let omega: Vec<f64> = (0..len).map(|k| 0.3 * (k as f64 + 0.5).sin()).collect();
            let w: Vec<f64> = (0..len).map(|k| (1.7 * k as f64).cos()).collect();
            let omega = Bivector::from_components(n, &omega).unwrap();
            let w = Bivector::from_components(n, &w).unwrap();
            for (order, coefficients) in [(5, &DEXP_INVERSE_5[..]), (8, &DEXP_INVERSE_8[..])] {
                let (mut out, mut power, mut next) =
                    (vec![0.0; len], vec![0.0; len], vec![0.0; len]);
                let pair = (&mut power[..], &mut next[..]);
                dexp_inverse_packed(
                    n,
                    omega.as_slice(),
                    w.as_slice(),
                    -0.5,
                    coefficients,
                    &mut out,
                    pair,
                );
                let series = dexp_inverse(&omega, &(&w * -0.5), order);
                let gap = out
                    .iter()
                    .zip(series.as_slice())
                    .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
                assert!(gap < 1e-15, "N = {n}, order {order}: {gap:e}");
                checked += 1;
            }
        }
        assert_eq!(checked, 12);
    }
}
