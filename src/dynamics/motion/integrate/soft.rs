//! [`SoftStep`]: substeps with soft contacts and a fixed amount of solver work per step.

use super::{MotionIntegrator, check_finite, kick, positive_count, sweep};
use crate::dynamics::DynamicsError;
use crate::dynamics::integrate::{axpy, free_flight};
use crate::dynamics::motion::body::contact_material;
use crate::dynamics::motion::detect::bodies::{Touching, placed_within, relative_placement};
use crate::dynamics::motion::detect::kept::KeptPairs;
use crate::dynamics::motion::placement::Placements;
use crate::dynamics::motion::solve::{FoundPoint, NO_BODY, SoftSolver, Softness, Solver};
use crate::dynamics::motion::{MotionError, System, Wrench};

/// The soft step: each step of h is cut into substeps, and each substep takes the forques'
/// kick, a Gauss–Seidel pass of soft contacts (two in 4D, four in N ≥ 5), the free flight
/// of every body, and as many passes without the contacts' springs (the "relax" passes);
/// restitution is applied once at the end of the step. Contacts are found once per step,
/// as points of the bodies' manifolds within a speculative margin (each body's share: 0.5 %
/// of its bounding radius and how far its points may move in the step at its velocities
/// and under its forces, so that a body falls onto what it meets within the step, and a
/// resting pile lists only the points that touch), and follow the bodies
/// through the substeps without a new detection; a pair of polytopes that moved less than
/// 1e-4 of its size (and turned less than 1e-4 rad) since its manifold was found keeps that
/// manifold's points as material points of the two bodies instead of asking the narrow
/// phase again (a curved body's contact point is not a material point: it rolls).
/// This is the "soft step" solver of Box2D v3 (Catto, 2024), close to Rapier's TGS-soft,
/// in N dimensions; the moving-bodies chapter compares it with
/// [`MotionSplitting`](super::MotionSplitting) and Rapier.
///
/// It does a fixed amount of work per step — the substeps times the passes over the
/// contacts — whatever the contacts do, where [`MotionSplitting`](super::MotionSplitting)
/// solves every contact to 10⁻⁹ of its speed and locates every impact in time. The price:
/// contacts are springs, so a resting body sits inside what it rests on by about
/// g / (2π f)² (f the contact frequency: 5.4e-5 m on a half-space at h = 1/60 s,
/// where the springs against fixed bodies are 60 Hz), friction is Coulomb's disc by
/// projection, impacts are not located in time, the angular momentum of a collision moves
/// by O(h) (the lever arms and inverse inertias are those of the step's start), and the
/// integrator is of order 1. Joints are not held ([`MotionError::NeedsSplitting`]).
///
/// Each step records its contacts ([`System::contacts`], [`System::body_contacts`]): one
/// entry per point that gave an impulse or ends the step overlapping, with the impulses of
/// the step's substeps summed (what the point gave the bodies over the step).
///
/// Measured (`tests/dynamics/soft_step.rs`): towers of six cubes in 3D and of three 4D
/// hypercubes offset by 5 % stand for 10 s at h = 1/60 s and 1e-3 s, the top sinking by
/// the springs' deflection (3.6e-3 for six cubes at h = 1/60 s) and sliding by up to
/// 3.3e-3.
///
/// The free flight is that of [`MotionSplitting`](super::MotionSplitting): positions
/// exactly, rotations by the Lie–Poisson splitting, which keeps a free body's |L| and
/// Casimirs to round-off (an isotropic body, a cube or a ball, turns exactly).
#[derive(Clone, Debug)]
pub struct SoftStep {
    substeps: usize,
    /// Gauss–Seidel passes per substep, with springs and without (None: [`default_passes`]).
    passes: Option<usize>,
    /// The contacts' frequency (None: a fifth of the substep rate).
    contact_hertz: Option<f64>,
    damping_ratio: f64,
    push_out: f64,
    margin: f64,
    /// How far each body may move in the step (see [`SoftStep::new`]), set with the resting
    /// speed from one evaluation of the wrenches.
    sweeps: Vec<f64>,
    solver: SoftSolver,
    detect: Solver,
    touching: Touching,
    placements: Placements,
    wrenches: Vec<Wrench>,
    checked: Option<(u64, u64, usize)>,
    /// The pairs whose manifold is kept from an earlier step, sorted, with the relative
    /// placement it was found at and the system's shapes as key; the next step's list is
    /// built in `next_kept`.
    kept: KeptPairs,
    next_kept: KeptPairs,
    reuse: Vec<(usize, usize)>,
    /// Room for a pair's relative placement.
    placement: Vec<f64>,
}

/// The Gauss–Seidel passes per substep in `n` dimensions when none are given: as many as
/// towers of offset cubes need to stand (see [`SoftStep::with_passes`]). The points of a
/// face, up to 4, 8 and 16 in 3D, 4D and 5D on, share their bodies, and each pass of
/// Gauss–Seidel over them carries only part of an impulse from point to point.
fn default_passes(n: usize) -> usize {
    match n {
        ..=3 => 1,
        4 => 2,
        _ => 4,
    }
}

impl Default for SoftStep {
    fn default() -> Self {
        SoftStep {
            substeps: 4,
            passes: None,
            contact_hertz: None,
            damping_ratio: 3.0,
            push_out: 3.0,
            margin: 0.005,
            sweeps: Vec::new(),
            solver: SoftSolver::default(),
            detect: Solver::default(),
            touching: Touching::clipping_tilted_boxes(),
            placements: Placements::default(),
            wrenches: Vec::new(),
            checked: None,
            kept: KeptPairs::default(),
            next_kept: KeptPairs::default(),
            reuse: Vec::new(),
            placement: Vec::new(),
        }
    }
}

/// How far apart (relative to the sum of two polytopes' bounding radii) the points of a
/// contact manifold may be and still be rows.
const MANIFOLD_SLOP: f64 = 5e-2;

/// How far two bodies may move relative to each other (relative to the sum of their
/// bounding radii, and in the entries of their relative rotation) before their contact
/// manifold is found anew: within that, its points are kept as material points of the two
/// bodies (a resting stack asks the narrow phase once, not at every step).
const KEEP_MANIFOLD: f64 = 1e-4;

impl SoftStep {
    /// The soft step with 4 substeps, contacts of a fifth of the substep rate (48 Hz at
    /// h = 1/60 s; a quarter is the stability bound, and springs nearer to it leave tall
    /// towers rocking) with damping ratio 3, overlaps pushed out at most at 3 m/s, and a
    /// speculative margin of 0.5 % of the bodies' bounding radii plus how far they may
    /// move in the step: h (|v| + |ω| r) + h² |F| / m for a body of bounding radius r under
    /// the force F.
    pub fn new() -> Self {
        Self::default()
    }

    /// Returns this integrator with `substeps` substeps per step.
    ///
    /// # Errors
    /// [`MotionError::OutOfRange`] for 0.
    pub fn with_substeps(mut self, substeps: usize) -> Result<Self, MotionError> {
        self.substeps = positive_count("substeps", substeps)?;
        Ok(self)
    }

    /// Returns this integrator with `passes` Gauss–Seidel passes per substep, with the
    /// contacts' springs and as many without (by default 1 in 2D and 3D, where towers stand
    /// with one; 2 in 4D, where a face holds 8 contact points and a tower of three
    /// hypercubes rocks with one; 4 in five and more dimensions, where a face holds 16 and
    /// such a tower rocks with 2 or 3).
    ///
    /// # Errors
    /// [`MotionError::OutOfRange`] for 0.
    pub fn with_passes(mut self, passes: usize) -> Result<Self, MotionError> {
        self.passes = Some(positive_count("passes", passes)?);
        Ok(self)
    }

    /// Returns this integrator with contacts of frequency `hertz` and damping ratio `zeta`
    /// (the frequency is used up to a quarter of the substep rate, where the springs stay
    /// stable; against fixed bodies and half-spaces twice the frequency, up to the same
    /// bound). Box2D's contacts are 30 Hz with damping ratio 10.
    ///
    /// # Errors
    /// [`MotionError::OutOfRange`] for a frequency or damping ratio that is not finite and
    /// positive.
    pub fn with_contact_spring(mut self, hertz: f64, zeta: f64) -> Result<Self, MotionError> {
        for (what, value) in [("contact frequency", hertz), ("damping ratio", zeta)] {
            if !(value.is_finite() && value > 0.0) {
                return Err(MotionError::OutOfRange {
                    what,
                    value,
                    expected: "a finite positive number",
                });
            }
        }
        self.contact_hertz = Some(hertz);
        self.damping_ratio = zeta;
        Ok(self)
    }

    /// The substeps per step.
    pub fn substeps(&self) -> usize {
        self.substeps
    }

    /// Finds the contact points of the step (bodies against half-spaces and against each
    /// other, within the speculative margin) and prepares the rows.
    fn detect(&mut self, system: &mut System) {
        let shape_key = system.shape_key();
        self.touching
            .update_shapes(system.shapes(), system.joints(), system.dim(), shape_key);
        let pairs = self.touching.any_pairs();
        let (bodies, shapes, half_spaces, _, _) = system.parts_mut();
        self.solver.begin(bodies);
        if half_spaces.is_empty() && !pairs {
            return;
        }
        self.placements
            .update(bodies, shapes, shape_key, half_spaces);
        if !half_spaces.is_empty() {
            self.detect.find_contacts(
                bodies,
                shapes,
                half_spaces,
                (self.margin, &self.sweeps, true),
                &self.placements,
            );
            let n = bodies[0].dim();
            let mut point = [0.0f64; 8];
            let mut any = Vec::new();
            for row in &self.detect.contacts {
                let plane = &half_spaces[row.half_space];
                let x = bodies[row.body].position().as_slice();
                let r = row.r.as_slice();
                let p: &mut [f64] = if n <= 8 {
                    &mut point[..n]
                } else {
                    any.resize(n, 0.0);
                    &mut any[..]
                };
                for ((p, x), r) in p.iter_mut().zip(x).zip(r) {
                    *p = x + r;
                }
                let normal = plane.normal().as_slice();
                let gap = plane.distance(bodies[row.body].position())
                    + normal.iter().zip(r).map(|(a, b)| a * b).sum::<f64>();
                self.solver.push(&FoundPoint {
                    a: NO_BODY,
                    b: row.body,
                    key: ((row.half_space as u64) << 32) | row.index as u64,
                    gap,
                    normal,
                    point: p,
                    friction: plane.friction(),
                    restitution: plane.restitution(),
                });
            }
        }
        if pairs {
            if self.kept.key != Some(shape_key) {
                self.kept.clear(Some(shape_key));
            }
            let placements = &self.placements;
            let q = |i: usize| &placements.get(i).q[..];
            let x = |i: usize| bodies[i].position().as_slice();
            // The pairs that moved little since their manifold was found keep it.
            self.reuse.clear();
            self.next_kept.clear(Some(shape_key));
            let n = bodies[0].dim();
            let mut now = std::mem::take(&mut self.placement);
            for k in 0..self.kept.len() {
                let (a, b) = self.kept.pair(k);
                if b >= bodies.len() {
                    continue;
                }
                relative_placement((q(a), q(b)), (x(a), x(b)), &mut now);
                let then = self.kept.placement(k, n);
                let reach = KEEP_MANIFOLD * (placements.get(a).radius + placements.get(b).radius);
                if placed_within(&now, then, n, (reach, KEEP_MANIFOLD)) {
                    self.reuse.push((a, b));
                }
            }
            let reuse = &self.reuse;
            self.touching.set_sweeps(&self.sweeps, &[]);
            self.touching
                .scan_except(bodies, q, self.margin, Some(MANIFOLD_SLOP), |p| {
                    reuse.binary_search(&p).is_ok()
                });
            let mut last = None;
            for c in self.touching.found() {
                let (friction, restitution) = contact_material(&bodies[c.a], &bodies[c.b]);
                self.solver.push(&FoundPoint {
                    a: c.a,
                    b: c.b,
                    key: c.feature,
                    gap: c.gap,
                    normal: &c.normal,
                    point: &c.point,
                    friction,
                    restitution,
                });
                // Only polytopes keep their points: a curved body rolls, and the material
                // point of its last contact then leaves the contact (on a ball it lags
                // behind the rolling, and its normal impulse spins the ball up).
                let flat = |i: usize| shapes[i].is_polytope();
                if last != Some((c.a, c.b)) && flat(c.a) && flat(c.b) {
                    last = Some((c.a, c.b));
                    relative_placement((q(c.a), q(c.b)), (x(c.a), x(c.b)), &mut now);
                    self.next_kept.push((c.a, c.b), &now);
                }
            }
            self.placement = now;
            let mut k = 0;
            for &p in &self.reuse {
                if self.solver.push_kept(p) {
                    while self.kept.pair(k) != p {
                        k += 1;
                    }
                    self.next_kept.copy_entry(&self.kept, k);
                }
            }
            self.next_kept.sort();
            std::mem::swap(&mut self.kept, &mut self.next_kept);
        }
        self.solver.prepare(bodies);
    }

    /// The kick of the wrenches at time `t` over `h`.
    fn kick_at(&mut self, system: &mut System, t: f64, h: f64) {
        if let (bodies, Some(constant)) = system.bodies_and_constant_wrenches() {
            kick(bodies, &constant.wrenches, h);
            return;
        }
        let mut w = std::mem::take(&mut self.wrenches);
        system.wrenches_into(t, &mut w);
        kick(system.bodies_mut(), &w, h);
        self.wrenches = w;
    }

    /// The speed below which a contact does not bounce: what one step of the wrenches
    /// gives a body. Sets each body's sweep over the step of h: how far its points may
    /// move in it, h (|v| + |ω| r) + h² |F| / m (r its bounding radius, |ω| the norm of
    /// the bivector, at least the largest speed it gives a point at unit distance).
    fn resting_speed_and_sweeps(&mut self, system: &System, t: f64, h: f64) -> f64 {
        let mut w = std::mem::take(&mut self.wrenches);
        system.wrenches_into(t, &mut w);
        let bodies = system.bodies();
        // The bounding radii the placements keep for the system's shapes (found once for
        // them, not at every step).
        self.placements.own(system.shapes(), system.shape_key());
        let placements = &self.placements;
        self.sweeps.clear();
        self.sweeps
            .extend(bodies.iter().enumerate().zip(&w).map(|((i, b), w)| {
                if b.is_fixed() {
                    return 0.0;
                }
                sweep(b, placements.get(i).radius, w.force.norm(), (h, h))
            }));
        let speed = bodies
            .iter()
            .zip(&w)
            .filter(|(b, _)| !b.is_fixed())
            .map(|(b, w)| 2.0 * h * w.force.norm() / b.mass())
            .fold(1e-12, f64::max);
        self.wrenches = w;
        speed
    }
}

impl MotionIntegrator for SoftStep {
    fn order(&self) -> u32 {
        1
    }

    fn name(&self) -> &'static str {
        "soft step"
    }

    fn step(&mut self, system: &mut System, t: f64, h: f64) -> Result<(), DynamicsError> {
        self.step_recording(system, t, h, true)
    }

    /// `steps` calls of [`MotionIntegrator::step`], except that only the last step writes
    /// [`System::contacts`] and [`System::body_contacts`]: the others' would be overwritten
    /// unread. The motion is that of the calls to the last bit.
    fn advance(
        &mut self,
        system: &mut System,
        t: f64,
        h: f64,
        steps: usize,
    ) -> Result<(), DynamicsError> {
        for k in 0..steps {
            self.step_recording(system, t + k as f64 * h, h, k + 1 == steps)?;
        }
        Ok(())
    }
}

impl SoftStep {
    /// [`MotionIntegrator::step`], the contacts recorded only if `record`.
    fn step_recording(
        &mut self,
        system: &mut System,
        t: f64,
        h: f64,
        record: bool,
    ) -> Result<(), DynamicsError> {
        let key = system.contacts_key();
        if self.checked != Some(key) {
            system.check_contacts()?;
            self.checked = Some(key);
        }
        if !system.joints().is_empty() {
            return Err(MotionError::NeedsSplitting {
                integrator: "SoftStep",
            }
            .into());
        }
        system.clear_contacts();
        let resting = self.resting_speed_and_sweeps(system, t, h);
        self.detect(system);
        let sub = h / self.substeps as f64;
        let rate = 0.25 / sub;
        let hertz = self.contact_hertz.unwrap_or(0.2 / sub).min(rate);
        let soft = (
            Softness::new(hertz, self.damping_ratio, sub),
            Softness::new((2.0 * hertz).min(rate), self.damping_ratio, sub),
        );
        let passes = self.passes.unwrap_or(default_passes(system.dim()));
        // Under constant forces without torques a kick changes the velocities by F h / m
        // alone: the relax passes' velocities then stay loaded into the next substep's
        // solve, which saves a store and a load of every body in contact per substep.
        let carry = system
            .bodies_and_constant_wrenches()
            .1
            .is_some_and(|c| !c.any_torque);
        for s in 0..self.substeps {
            let at = t + s as f64 * sub;
            self.kick_at(system, at, sub);
            let carried = carry && s > 0;
            if carried {
                let (bodies, Some(constant)) = system.bodies_and_constant_wrenches() else {
                    unreachable!("carried only under constant wrenches")
                };
                self.solver.kick_loaded(bodies, &constant.wrenches, sub);
            }
            let bodies = system.bodies_mut();
            self.solver
                .solve(bodies, sub, (soft, self.push_out), passes, carried);
            self.solver.store(bodies);
            for b in bodies.iter_mut().filter(|b| !b.is_fixed()) {
                let m = b.mass();
                let (x, p, rotation) = b.state_mut();
                axpy(x.as_mut_slice(), sub / m, p.as_slice());
                free_flight(rotation, at, sub)?;
            }
            self.solver.moved(bodies);
            self.solver.relax(
                bodies,
                sub,
                (resting, passes),
                s + 1 == self.substeps,
                carry,
            );
        }
        if record {
            let (_, _, _, _, log) = system.parts_mut();
            self.solver.record(&self.detect.contacts, log);
        }
        check_finite(system, t)
    }
}
