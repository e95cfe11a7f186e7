//! [`MotionRk4`]: Runge–Kutta–Munthe-Kaas of order 4 on the whole state.

use super::{MotionIntegrator, check_finite};
use crate::algebra::{Bivector, Vector};
use crate::dynamics::DynamicsError;
use crate::dynamics::motion::{MotionError, MovingBody, System, Wrench};

/// Runge–Kutta–Munthe-Kaas of order 4 on the whole state: classical RK4 on the positions and
/// momenta, the attitudes advanced on Spin(N) (or SO(N)) by one exponential per step with
/// the commutator correction of [`crate::dynamics::Rkmk4`], so that each attitude stays on
/// its group. Any forques, dissipative ones included.
///
/// It keeps the stage states and rates between steps, so that after the first step a step
/// does not touch the heap (N ≤ 8); make one with [`MotionRk4::new`] (or `default()`) and
/// reuse it.
#[derive(Clone, Debug, Default)]
pub struct MotionRk4 {
    /// The bodies at the current stage (their mass and inertia are the system's).
    stage: Vec<MovingBody>,
    /// The rates k₁ … k₄ of every body.
    k: [Vec<Rates>; 4],
    wrenches: Vec<Wrench>,
}

/// The rates of one body: dx/dt, dp/dt, dL/dt and a = −½ω (the attitude's generator).
#[derive(Clone, Debug)]
struct Rates {
    dx: Vector,
    dp: Vector,
    dl: Bivector,
    a: Bivector,
}

impl Rates {
    fn zero(n: usize) -> Rates {
        Rates {
            dx: Vector::zero(n),
            dp: Vector::zero(n),
            dl: Bivector::zero(n),
            a: Bivector::zero(n),
        }
    }
}

/// Writes the rates of `bodies` under `wrenches` into `out`.
fn rates_into(bodies: &[MovingBody], wrenches: &[Wrench], out: &mut Vec<Rates>) {
    let n = bodies[0].dim();
    out.resize_with(bodies.len(), || Rates::zero(n));
    for ((b, w), k) in bodies.iter().zip(wrenches).zip(out.iter_mut()) {
        if b.is_fixed() {
            *k = Rates::zero(n);
            continue;
        }
        let l = b.rotation().momentum();
        let omega = b.rotation().inertia().apply_inverse(l);
        let mut dl = omega.commutator(l);
        dl += &w.torque;
        k.dx = b.linear_momentum() * (1.0 / b.mass());
        k.dp.clone_from(&w.force);
        k.dl = dl;
        k.a = omega * -0.5;
    }
}

/// Sets the bodies `out` at a stage: x₀ + c dx, p₀ + c dp, L₀ + c dL, R₀ exp(u(i)).
fn set_stage(
    start: &[MovingBody],
    k: &[Rates],
    c: f64,
    attitude_step: impl Fn(usize) -> Bivector,
    out: &mut [MovingBody],
) {
    for (i, ((b0, k), b)) in start.iter().zip(k).zip(out.iter_mut()).enumerate() {
        let (x, p, rotation) = b.state_mut();
        x.clone_from(b0.position());
        *x += &(&k.dx * c);
        p.clone_from(b0.linear_momentum());
        *p += &(&k.dp * c);
        let (r, l) = rotation.state_mut();
        r.clone_from(b0.rotation().principal_frame_attitude());
        r.times_exp_mut(&attitude_step(i));
        l.clone_from(b0.rotation().momentum());
        *l += &(&k.dl * c);
    }
}

impl MotionRk4 {
    /// Returns the integrator, with empty buffers (the first step sizes them).
    pub fn new() -> Self {
        Self::default()
    }

    /// Makes the stage bodies copies of `bodies` (mass, inertia and frames; the state is set
    /// at each stage), cloning only when they are not already.
    fn prepare(&mut self, bodies: &[MovingBody]) {
        let same = self.stage.len() == bodies.len()
            && self.stage.iter().zip(bodies).all(|(s, b)| {
                s.mass() == b.mass()
                    && s.rotation().inertia() == b.rotation().inertia()
                    && s.rotation().principal_frame() == b.rotation().principal_frame()
            });
        if !same {
            self.stage.clear();
            self.stage.extend_from_slice(bodies);
        }
    }
}

impl MotionIntegrator for MotionRk4 {
    fn order(&self) -> u32 {
        4
    }

    fn name(&self) -> &'static str {
        "rk4"
    }

    fn step(&mut self, system: &mut System, t: f64, h: f64) -> Result<(), DynamicsError> {
        if !system.joints().is_empty() || !system.half_spaces().is_empty() {
            return Err(MotionError::NeedsSplitting {
                integrator: "MotionRk4",
            }
            .into());
        }
        self.prepare(system.bodies());
        let MotionRk4 { stage, k, wrenches } = self;
        let [k1, k2, k3, k4] = k;
        let b0 = system.bodies();
        system.wrenches_for_into(t, b0, wrenches);
        rates_into(b0, wrenches, k1);
        set_stage(b0, k1, 0.5 * h, |i| &k1[i].a * (0.5 * h), stage);
        system.wrenches_for_into(t + 0.5 * h, stage, wrenches);
        rates_into(stage, wrenches, k2);
        set_stage(
            b0,
            k2,
            0.5 * h,
            |i| &(&k2[i].a * (0.5 * h)) + &(k1[i].a.commutator(&k2[i].a) * (0.25 * h * h)),
            stage,
        );
        system.wrenches_for_into(t + 0.5 * h, stage, wrenches);
        rates_into(stage, wrenches, k3);
        set_stage(b0, k3, h, |i| &k3[i].a * h, stage);
        system.wrenches_for_into(t + h, stage, wrenches);
        rates_into(stage, wrenches, k4);
        for (i, b) in system.bodies_mut().iter_mut().enumerate() {
            let (x, p, rotation) = b.state_mut();
            let sum = |f: &dyn Fn(&Rates) -> &Vector| -> Vector {
                let mut s = f(&k1[i]).clone();
                s += &(f(&k2[i]) * 2.0);
                s += &(f(&k3[i]) * 2.0);
                s += f(&k4[i]);
                s
            };
            *x += &(&sum(&|k: &Rates| &k.dx) * (h / 6.0));
            *p += &(&sum(&|k: &Rates| &k.dp) * (h / 6.0));
            let mut dl = k1[i].dl.clone();
            dl += &(&k2[i].dl * 2.0);
            dl += &(&k3[i].dl * 2.0);
            dl += &k4[i].dl;
            let mut u = k1[i].a.clone();
            u += &(&k2[i].a * 2.0);
            u += &(&k3[i].a * 2.0);
            u += &k4[i].a;
            u *= h / 6.0;
            u += &(k1[i].a.commutator(&k4[i].a) * (h * h / 6.0));
            let (r, l) = rotation.state_mut();
            r.times_exp_mut(&u);
            *l += &(&dl * (h / 6.0));
        }
        check_finite(system, t)
    }
}
