//! Integrators for systems of moving bodies.

use super::{MovingBody, System, Wrench};
use crate::algebra::{Bivector, Vector};
use crate::dynamics::torques::Free;
use crate::dynamics::{Attitude, DynamicsError, Integrator, Splitting};

/// An integrator of Newton–Euler for a [`System`]: advances every body by one step.
pub trait MotionIntegrator {
    /// Returns the order of accuracy.
    fn order(&self) -> u32;

    /// Returns a short name.
    fn name(&self) -> &'static str;

    /// Advances `system` from time `t` by a step `h`.
    ///
    /// # Errors
    /// [`DynamicsError::NonFinite`] if the state leaves f64; the errors of the rotation
    /// integrator.
    fn step(&mut self, system: &mut System, t: f64, h: f64) -> Result<(), DynamicsError>;
}

/// The symplectic Strang splitting of H = T + V: half a kick by the forques (p += ½h F,
/// L += ½h τ at fixed positions and attitudes), free flight for h (x += h p/m exactly, the
/// rotation by the Lie–Poisson splitting of [`Splitting::strang`], which keeps every Casimir
/// and |L| to round-off), half a kick. Order 2.
///
/// For conservative forques (gravity, undamped springs) it is a symplectic map, so the
/// energy error stays bounded over any number of steps instead of drifting; linear and
/// angular momentum are kept to round-off when the forques conserve them. Under uniform
/// gravity alone the centre of mass follows its parabola exactly (the kicks are exact for a
/// constant force), and the rotation is the free rotation of [`Splitting::strang`].
#[derive(Clone, Debug)]
pub struct MotionSplitting {
    rotation: Splitting,
}

impl Default for MotionSplitting {
    fn default() -> Self {
        MotionSplitting {
            rotation: Splitting::strang(),
        }
    }
}

impl MotionSplitting {
    /// The Strang splitting with the Strang rotation flow.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds ½h of each wrench to the momenta.
    fn kick(system: &mut System, wrenches: &[Wrench], h: f64) {
        for (b, w) in system.bodies_mut().iter_mut().zip(wrenches) {
            let (_, p, rotation) = b.state_mut();
            *p += &(&w.force * h);
            let (_, l) = rotation.state_mut();
            *l += &(&w.torque * h);
        }
    }
}

impl MotionIntegrator for MotionSplitting {
    fn order(&self) -> u32 {
        2
    }

    fn name(&self) -> &'static str {
        "strang"
    }

    fn step(&mut self, system: &mut System, t: f64, h: f64) -> Result<(), DynamicsError> {
        if !system.joints().is_empty() || !system.half_spaces().is_empty() {
            return Err(DynamicsError::InvalidMotion {
                what: "integrator",
                reason: "joints and contact are not yet integrated".into(),
            });
        }
        let w = system.wrenches(t);
        Self::kick(system, &w, 0.5 * h);
        for b in system.bodies_mut() {
            let m = b.mass();
            let (x, p, rotation) = b.state_mut();
            *x += &(&*p * (h / m));
            self.rotation.step(rotation, t, h, &Free)?;
        }
        let w = system.wrenches(t + h);
        Self::kick(system, &w, 0.5 * h);
        check_finite(system, t)
    }
}

/// Runge–Kutta–Munthe-Kaas of order 4 on the whole state: classical RK4 on the positions and
/// momenta, the attitudes advanced on Spin(N) (or SO(N)) by one exponential per step with
/// the commutator correction of [`crate::dynamics::Rkmk4`], so that each attitude stays on
/// its group. Any forques, dissipative ones included.
#[derive(Clone, Copy, Debug, Default)]
pub struct MotionRk4;

/// The rates of one body: dx/dt, dp/dt, dL/dt and a = −½ω (the attitude's generator).
struct Rates {
    dx: Vector,
    dp: Vector,
    dl: Bivector,
    a: Bivector,
}

fn rates(bodies: &[MovingBody], wrenches: &[Wrench]) -> Vec<Rates> {
    bodies
        .iter()
        .zip(wrenches)
        .map(|(b, w)| {
            let l = b.rotation().momentum();
            let omega = b.rotation().inertia().apply_inverse(l);
            let mut dl = omega.commutator(l);
            dl += &w.torque;
            Rates {
                dx: b.linear_momentum() * (1.0 / b.mass()),
                dp: w.force.clone(),
                dl,
                a: omega * -0.5,
            }
        })
        .collect()
}

/// The bodies at a stage: x₀ + c dx, p₀ + c dp, L₀ + c dL, R₀ exp(u).
fn stage(
    start: &[MovingBody],
    k: &[Rates],
    c: f64,
    attitude_steps: &[Bivector],
) -> Vec<MovingBody> {
    start
        .iter()
        .zip(k)
        .zip(attitude_steps)
        .map(|((b0, k), u)| {
            let mut b = b0.clone();
            let (x, p, rotation) = b.state_mut();
            *x += &(&k.dx * c);
            *p += &(&k.dp * c);
            let r = rotation.principal_frame_attitude().times_exp(u);
            let l = rotation.momentum() + &(&k.dl * c);
            rotation.replace_state(r, l);
            b
        })
        .collect()
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
            return Err(DynamicsError::InvalidMotion {
                what: "integrator",
                reason: "RKMK4 integrates forques only: joints and contact need the splitting"
                    .into(),
            });
        }
        let b0: Vec<MovingBody> = system.bodies().to_vec();
        let k1 = rates(&b0, &system.wrenches_for(t, &b0));
        let u2: Vec<Bivector> = k1.iter().map(|k| &k.a * (0.5 * h)).collect();
        let b2 = stage(&b0, &k1, 0.5 * h, &u2);
        let k2 = rates(&b2, &system.wrenches_for(t + 0.5 * h, &b2));
        let u3: Vec<Bivector> = k1
            .iter()
            .zip(&k2)
            .map(|(k1, k2)| &(&k2.a * (0.5 * h)) + &(k1.a.commutator(&k2.a) * (0.25 * h * h)))
            .collect();
        let b3 = stage(&b0, &k2, 0.5 * h, &u3);
        let k3 = rates(&b3, &system.wrenches_for(t + 0.5 * h, &b3));
        let u4: Vec<Bivector> = k3.iter().map(|k| &k.a * h).collect();
        let b4 = stage(&b0, &k3, h, &u4);
        let k4 = rates(&b4, &system.wrenches_for(t + h, &b4));
        for (i, b) in system.bodies_mut().iter_mut().enumerate() {
            let (x, p, rotation) = b.state_mut();
            let sum = |f: &dyn Fn(&Rates) -> Vector| -> Vector {
                let mut s = f(&k1[i]);
                s += &(&f(&k2[i]) * 2.0);
                s += &(&f(&k3[i]) * 2.0);
                s += &f(&k4[i]);
                s
            };
            *x += &(&sum(&|k: &Rates| k.dx.clone()) * (h / 6.0));
            *p += &(&sum(&|k: &Rates| k.dp.clone()) * (h / 6.0));
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
            let r: Attitude = rotation.principal_frame_attitude().times_exp(&u);
            let l = rotation.momentum() + &(&dl * (h / 6.0));
            rotation.replace_state(r, l);
        }
        check_finite(system, t)
    }
}

fn check_finite(system: &System, t: f64) -> Result<(), DynamicsError> {
    if system.bodies().iter().all(MovingBody::is_finite) {
        Ok(())
    } else {
        Err(DynamicsError::NonFinite { time: t })
    }
}
