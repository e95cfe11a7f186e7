//! [`MotionSplitting`]: kicks, free flight, impacts located in time, contacts and joints.

use super::{MotionIntegrator, check_finite, kick, one_by_one, positive_count, sweep};
use crate::algebra::Vector;
use crate::dynamics::DynamicsError;
use crate::dynamics::integrate::{axpy, free_flight};
use crate::dynamics::motion::detect::bodies::Touching;
use crate::dynamics::motion::forques::Anchor;
use crate::dynamics::motion::placement::Placements;
use crate::dynamics::motion::solve::{MAX_SWEEPS, Solver, SolverReport, plane_sweep};
use crate::dynamics::motion::{ContactShape, MotionError, MovingBody, System, Wrench};

/// The symplectic Strang splitting of H = T + V: half a kick by the forques (p += ½h F,
/// L += ½h τ at fixed positions and attitudes), free flight for h (x += h p/m exactly, the
/// rotation by the Lie–Poisson splitting of [`Splitting::strang`], which keeps every
/// Casimir and |L| to round-off, and exactly for an isotropic body: a cube, a ball, a
/// tesseract, whose L stays put in its own axes), half a kick. Order 2.
///
/// For conservative forques (gravity, undamped springs) it is a symplectic map, so the
/// energy error stays bounded over any number of steps instead of drifting; linear and
/// angular momentum are kept to round-off when the forques conserve them. Under uniform
/// gravity alone the centre of mass follows its parabola exactly (the kicks are exact for a
/// constant force), and the rotation is the free rotation of [`Splitting::strang`].
///
/// **Joints** are kept as RATTLE keeps holonomic constraints: the first half kick carries
/// the joint impulses that make the free flight end with every joint closed (solved by
/// Newton's method on the impulses, to 10⁻¹³ of the bodies' size), the second half kick
/// the impulses that make the ends' velocities agree. The scheme stays symplectic and
/// time-reversible on the constrained system, so its energy error stays bounded too.
///
/// **Contacts** with half-spaces are impulses after each half kick (see
/// [`HalfSpace`](crate::dynamics::motion::HalfSpace)): a point in contact (within 10⁻⁹ of the body's radius)
/// may not approach the half-space, friction stays in Coulomb's cone and opposes the slip.
/// A point that was free and would end the step inside a half-space is an impact: the step
/// is cut at the instant it reaches the plane (located by the Anderson–Björck variant of
/// regula falsi to a quarter of that tolerance), the impact is resolved with the plane's
/// restitution e, and the rest of the step follows. Below the approach speed 2h|F|/m that one step of the
/// forques gives, a contact is resting (e = 0), so that bouncing dies out instead of
/// ringing. Resting contacts that sink by the curvature of their path are lifted back onto
/// the plane. An impact of e = 0 is not located but held by a speculative contact: a point
/// within its body's sweep h (|v| + ½h |F|/m + |ω| r) of a plane of e = 0, or of a body when
/// both have e = 0, is a row of the step's solves that lets it close its gap within the
/// flight and no more, which ends the step touching as the located impact would.
///
/// [`Splitting::strang`]: crate::dynamics::Splitting::strang
#[derive(Clone, Debug, Default)]
pub struct MotionSplitting {
    solver: Solver,
    saved: SavedBodies,
    pre_drift: SavedBodies,
    wrenches: Vec<Wrench>,
    resting_speed: Vec<f64>,
    active: Vec<bool>,
    gaps: Vec<Vector>,
    distances: Vec<f64>,
    /// The distances at the contact points between bodies after a trial flight.
    pair_distances: Vec<f64>,
    sharing: Vec<usize>,
    /// Each joint's position impulse of the last step over its length (a force), to start
    /// the next step's position solve from: the solve then needs fewer passes.
    joint_force: Vec<Vector>,
    /// The same of the step before, to extrapolate from.
    joint_force_before: Vec<Vector>,
    /// The position impulses of the current solve, per joint.
    joint_total: Vec<Vector>,
    /// Each joint's point in the principal axes of its body, and the other end: a point in
    /// the principal axes of the other body, or of space.
    joint_ends: Vec<(Vector, Vector)>,
    /// The bodies' own axes and vertices in space, kept while they do not turn.
    placements: Placements,
    /// The system whose start was checked last ([`System::check_contacts`]).
    checked: Option<(u64, u64, usize)>,
    /// Refuse steps whose solves did not converge.
    strict: bool,
    /// The momenta before an implicit closing kick.
    kick_start: SavedBodies,
    /// The bodies' convex shapes and the pairs of bodies found touching.
    touching: Touching,
    /// The pairs of bodies in contact at the start of the substep, sorted, each with its
    /// least signed distance then (−∞ for a pair admitted during the step).
    active_pairs: Vec<((usize, usize), f64)>,
    /// True while an impact is being located.
    locating: bool,
    /// True while the contacts the solves find go unrecorded: in the steps of an `advance`
    /// before its last, whose lists the next step clears unread.
    unrecorded: bool,
    /// The contacts that were not in contact at the start of the step and ended its last
    /// flight deeper than their touching distance: pairs of bodies and candidates against
    /// half-spaces, with their signed distances.
    entering: Vec<Entering>,
    /// The state at the end of a flight, while entering contacts are checked from its start.
    flight_end: SavedBodies,
    /// How far each body's points may move in the flight ahead at the velocities it starts
    /// with ([`Self::set_sweeps`]): contacts of restitution 0 that close within it are
    /// speculative rows of the solve instead of impacts to locate.
    sweeps: Vec<f64>,
    /// The bodies of nonzero restitution: their impacts with other bodies are located.
    bouncing: Vec<bool>,
}

/// A contact entering in a flight: a pair of bodies (a < b) with its signed distance and
/// its relative distance ([`MotionSplitting::pair_penetration`]'s: below −1 it entered),
/// or a candidate against a half-space with its distance over its reach.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Entering {
    Pair(usize, usize, f64, f64),
    Candidate(f64),
}

/// The contact tolerance, relative to a body's radius.
const CONTACT_TOLERANCE: f64 = 1e-9;

/// How far apart (relative to the sum of two polytopes' bounding radii) the points of their
/// contact manifold may be and still be rows of the solve: a corner about to land is held
/// from the step before it would sink.
const MANIFOLD_SLOP: f64 = 1e-2;

/// How many times its touching distance a contact point between bodies may end a flight
/// inside and still be closed by the flight's position step.
const PAIR_POSITION_LIMIT: f64 = 1e3;

/// How far (relative to the sum of their bounding radii) two bodies in contact sink below
/// where they started a flight (or below touching) where a landing of a feature their rows
/// did not hold is located: a flight in which they sink by more than twice this is an
/// impact, located where they have sunk by about this much. A thousandth: the depth the
/// flight's position step still closes for a box pair's rows ([`PAIR_POSITION_LIMIT`]
/// times their touching distance, 10⁻⁶ of the radii).
const SINK_LIMIT: f64 = 1e-3;

/// Fixed-point iterations of an implicit closing kick, at most.
const MAX_KICK_ITERATIONS: usize = 50;

/// How closely (relative to the rest of the step) an impact is located in time when the
/// least gap jumps (another pair becomes the nearest) instead of crossing zero.
const LOCATE_WIDTH: f64 = 1e-6;

/// Tries at most in a bracket narrower than [`LOCATE_WIDTH`].
const MAX_NARROW_TRIES: usize = 8;

/// Impacts located within one step, at most (then the rest of the step is resting contact).
const MAX_EVENTS: usize = 16;

/// A sweep shorter than this (relative to the body's radius) is none: bodies at rest keep
/// theirs, and with them the pairs found and the manifolds kept, from step to step.
const LEAST_SWEEP: f64 = 1e-6;

/// The states of bodies, to come back to: each body's position, momentum, angular
/// momentum and attitude (the rotor's coefficients or the matrix's entries), one body after
/// another in one array. A body's few numbers then lie in one or two cache lines, where
/// vectors with room for eight dimensions would spread them over a dozen. The bodies of a
/// system share their dimension, so each takes the same count of numbers.
#[derive(Clone, Debug, Default)]
struct SavedBodies {
    data: Vec<f64>,
    /// The numbers of one body.
    stride: usize,
}

impl SavedBodies {
    /// Saves the bodies' states over the last ones' room.
    fn save(&mut self, bodies: &[MovingBody]) {
        self.data.clear();
        for b in bodies {
            self.data.extend_from_slice(b.position().as_slice());
            self.data.extend_from_slice(b.linear_momentum().as_slice());
            self.data
                .extend_from_slice(b.rotation().momentum().as_slice());
            self.data
                .extend_from_slice(b.rotation().principal_frame_attitude().entries());
        }
        self.stride = self.data.len() / bodies.len().max(1);
    }

    /// Sets the bodies (the ones saved) back to their saved states.
    fn restore(&self, bodies: &mut [MovingBody]) {
        for (b, saved) in bodies
            .iter_mut()
            .zip(self.data.chunks_exact(self.stride.max(1)))
        {
            let (x, p, rotation) = b.state_mut();
            let (attitude, l) = rotation.state_mut();
            let mut at = 0;
            for part in [
                x.as_mut_slice(),
                p.as_mut_slice(),
                l.as_mut_slice(),
                attitude.entries_mut(),
            ] {
                part.copy_from_slice(&saved[at..at + part.len()]);
                at += part.len();
            }
        }
    }

    /// Body `k`'s saved momentum and angular momentum (N and M numbers).
    fn momenta(&self, k: usize, n: usize) -> (&[f64], &[f64]) {
        let p = k * self.stride + n;
        let m = n * (n - 1) / 2;
        (&self.data[p..p + n], &self.data[p + n..p + n + m])
    }
}

impl MotionSplitting {
    /// The Strang splitting with the Strang rotation flow.
    pub fn new() -> Self {
        Self::default()
    }

    /// Free flight of every body for h.
    fn drift(&mut self, bodies: &mut [MovingBody], t: f64, h: f64) -> Result<(), DynamicsError> {
        for b in bodies.iter_mut().filter(|b| !b.is_fixed()) {
            let m = b.mass();
            let (x, p, rotation) = b.state_mut();
            axpy(x.as_mut_slice(), h / m, p.as_slice());
            free_flight(rotation, t, h)?;
        }
        Ok(())
    }

    /// Fills the wrench buffer at time t.
    fn wrenches_at(&mut self, system: &System, t: f64) {
        let mut w = std::mem::take(&mut self.wrenches);
        system.wrenches_into(t, &mut w);
        self.wrenches = w;
    }

    /// The speed below which contacts rest: what one step of the wrenches gives.
    fn set_resting_speeds(
        resting_speed: &mut Vec<f64>,
        bodies: &[MovingBody],
        wrenches: &[Wrench],
        h: f64,
    ) {
        resting_speed.clear();
        resting_speed.extend(
            bodies
                .iter()
                .zip(wrenches)
                .map(|(b, w)| 2.0 * h * w.force.norm() / b.mass() + 1e-12),
        );
    }

    /// Half a kick (½h) by the wrenches at time `t`, after setting the resting speeds of a
    /// substep of length h if `resting`. Constant wrenches are read where the system keeps
    /// them instead of being copied.
    fn half_kick(&mut self, system: &mut System, t: f64, h: f64, resting: bool) {
        if let (bodies, Some(constant)) = system.bodies_and_constant_wrenches() {
            if resting {
                Self::set_resting_speeds(&mut self.resting_speed, bodies, &constant.wrenches, h);
            }
            kick(bodies, &constant.wrenches, 0.5 * h);
            return;
        }
        self.wrenches_at(system, t);
        if resting {
            Self::set_resting_speeds(&mut self.resting_speed, system.bodies(), &self.wrenches, h);
        }
        kick(system.bodies_mut(), &self.wrenches, 0.5 * h);
    }

    /// The closing half kick (½h) at time `t`. Where a forque reads velocities it is
    /// implicit in the momenta, p₁ = p + ½h F(x, p₁) and L₁ = L + ½h τ(x, L₁), the adjoint of
    /// the explicit opening kick: the step is then symmetric, and a symmetric consistent
    /// step is of order 2, with damping and drag as without (explicit closing kicks made it
    /// order 1 there). Solved by fixed-point iteration, which contracts by about
    /// ½h c/m for a damping c and converges to round-off in a few evaluations for steps
    /// that resolve the damping.
    fn closing_kick(&mut self, system: &mut System, t: f64, h: f64) {
        if system.bodies_and_constant_wrenches().1.is_some() || !system.reads_velocities() {
            self.half_kick(system, t, h, false);
            return;
        }
        self.kick_start.save(system.bodies());
        self.wrenches_at(system, t);
        kick(system.bodies_mut(), &self.wrenches, 0.5 * h);
        for _ in 0..MAX_KICK_ITERATIONS {
            self.wrenches_at(system, t);
            let (mut change, mut size) = (0.0f64, 0.0f64);
            for (k, (b, w)) in system
                .bodies_mut()
                .iter_mut()
                .zip(&self.wrenches)
                .enumerate()
            {
                if b.is_fixed() {
                    continue;
                }
                let (p0, l0) = self.kick_start.momenta(k, b.dim());
                let (_, p, rotation) = b.state_mut();
                let (_, l) = rotation.state_mut();
                let parts = [
                    (p.as_mut_slice(), p0, w.force.as_slice()),
                    (l.as_mut_slice(), l0, w.torque.as_slice()),
                ];
                for (now, from, rate) in parts {
                    for ((x, x0), f) in now.iter_mut().zip(from).zip(rate) {
                        let next = x0 + 0.5 * h * f;
                        change = change.max((next - *x).abs());
                        size = size.max(next.abs());
                        *x = next;
                    }
                }
            }
            if change <= 4.0 * f64::EPSILON * size {
                break;
            }
        }
    }

    /// The velocity solve of the contacts and joints at the current placement, after a kick
    /// of length `kick`, for a flight of length `flight`; its contacts are recorded in the
    /// system's list if `record`.
    fn solve_velocities(&mut self, system: &mut System, (kick, flight): (f64, f64), record: bool) {
        self.place(system);
        self.solve_placed(system, (kick, flight), record);
    }

    /// [`Self::solve_velocities`] with the bodies placed already.
    fn solve_placed(&mut self, system: &mut System, (kick, flight): (f64, f64), record: bool) {
        let (bodies, shapes, half_spaces, joints, contacts) = system.parts_mut();
        self.solver.find_contacts(
            bodies,
            shapes,
            half_spaces,
            (CONTACT_TOLERANCE, &self.sweeps, false),
            &self.placements,
        );
        self.solver.find_joints(bodies, joints);
        if self.touching.any_pairs() {
            let (touching, placements) = (&mut self.touching, &self.placements);
            touching.scan(
                bodies,
                |i| &placements.get(i).q,
                CONTACT_TOLERANCE,
                Some(MANIFOLD_SLOP),
            );
            self.solver
                .set_pairs(self.touching.found(), self.touching.found_serial(), bodies);
        } else {
            self.solver.clear_pairs();
        }
        self.solver.solve_velocities(
            bodies,
            half_spaces,
            &self.resting_speed,
            (kick, flight),
            record.then_some(contacts),
        );
    }

    /// Places the bodies that turned since they were last placed.
    fn place(&mut self, system: &System) {
        self.touching.update_shapes(
            system.shapes(),
            system.joints(),
            system.dim(),
            system.shape_key(),
        );
        if !system.half_spaces().is_empty() || self.touching.any_pairs() {
            self.placements.update(
                system.bodies(),
                system.shapes(),
                system.shape_key(),
                system.half_spaces(),
            );
        }
    }

    /// Free flight with the joints closed and the contacts of the step out of their
    /// half-spaces at its end (RATTLE's position step): the first half kick gets the
    /// impulses (joint impulses of any sign, normal contact impulses ≥ 0) that put every
    /// joint's ends together and every contact point on or above its plane after the
    /// flight, found by Newton's method with the Jacobian h K of the impulses.
    fn constrained_drift(
        &mut self,
        system: &mut System,
        t: f64,
        h: f64,
    ) -> Result<(), DynamicsError> {
        let result = self.constrained_drift_loaded(system, t, h);
        self.solver.release();
        result
    }

    /// [`Self::constrained_drift`], leaving the solver's bodies loaded.
    fn constrained_drift_loaded(
        &mut self,
        system: &mut System,
        t: f64,
        h: f64,
    ) -> Result<(), DynamicsError> {
        let shape_key = system.shape_key();
        let (bodies, shapes, half_spaces, joints, _) = system.parts_mut();
        if joints.is_empty() && self.solver.contacts.is_empty() && self.solver.pairs.is_empty() {
            return self.drift(bodies, t, h);
        }
        let size = bodies
            .iter()
            .map(|b| b.position().norm())
            .chain(joints.iter().map(|j| j.point.norm()))
            .fold(1.0, f64::max);
        for row in &mut self.solver.contacts {
            row.position_impulse = 0.0;
        }
        for row in &mut self.solver.pairs {
            row.position_impulse = 0.0;
        }
        let n = bodies[0].dim();
        if !joints.is_empty() {
            // In principal axes a joint's end is placed by one rotation, the one the
            // integrators advance.
            let principal = |b: usize, p: &Vector| {
                bodies[b]
                    .rotation()
                    .principal_frame()
                    .inverse_rotate_vector(p)
            };
            self.joint_ends.clear();
            self.joint_ends.extend(joints.iter().map(|j| {
                let other = match &j.other {
                    Anchor::World(x) => x.clone(),
                    Anchor::Body(k, p) => principal(*k, p),
                };
                (principal(j.body, &j.point), other)
            }));
            self.joint_total
                .resize_with(joints.len(), || Vector::zero(n));
            if self.joint_force.len() == joints.len() {
                // Start from the joint forces extrapolated from the last two steps (or the
                // last step's): the gaps left are then of the order of their second
                // difference (or their change) over a step.
                let before = (self.joint_force_before.len() == joints.len())
                    .then_some(&self.joint_force_before);
                for (k, (total, f)) in self
                    .joint_total
                    .iter_mut()
                    .zip(&self.joint_force)
                    .enumerate()
                {
                    let f0 = before.map(|b| b[k].as_slice());
                    for (i, (x, y)) in total
                        .as_mut_slice()
                        .iter_mut()
                        .zip(f.as_slice())
                        .enumerate()
                    {
                        *x = match f0 {
                            Some(f0) => (2.0 * y - f0[i]) * h,
                            None => y * h,
                        };
                    }
                }
                self.solver
                    .joint_position_impulses(bodies, &self.joint_total);
            } else {
                for total in &mut self.joint_total {
                    total.as_mut_slice().fill(0.0);
                }
            }
        }
        self.pre_drift.save(bodies);
        let mut worst_gap = 0.0;
        for _ in 0..50 {
            self.drift(bodies, t, h)?;
            self.gaps.resize_with(joints.len(), || Vector::zero(n));
            for ((gap, j), ends) in self.gaps.iter_mut().zip(joints).zip(&self.joint_ends) {
                joint_gap(j, ends, bodies, gap);
            }
            worst_gap = self.gaps.iter().map(Vector::max_abs).fold(0.0, f64::max);
            self.distances.clear();
            let mut contacts_hold = true;
            if !self.solver.contacts.is_empty() {
                self.placements
                    .update(bodies, shapes, shape_key, half_spaces);
            }
            for row in &self.solver.contacts {
                let shape = &shapes[row.body];
                let plane = &half_spaces[row.half_space];
                let d = plane.distance(bodies[row.body].position())
                    + self.placements.get(row.body).candidate_height(
                        shape,
                        (row.half_space, plane.normal()),
                        row.index,
                    );
                let tolerance = 1e-12 * self.placements.get(row.body).radius;
                contacts_hold &= d >= -tolerance && (row.position_impulse == 0.0 || d <= tolerance);
                self.distances.push(d);
            }
            self.pair_distances.clear();
            for row in &self.solver.pairs {
                // A point that starts the flight overlapping (beyond touching) is let out by
                // the velocity solve at the resting speed; the position step only keeps it
                // from going deeper. Closing it here would throw the bodies apart at
                // depth / h, and h is as short as a located impact makes it.
                let floor = if row.gap < -row.reach { row.gap } else { 0.0 };
                let d = pair_distance(row, bodies) - floor;
                // Points within the pair's touching distance hold: a gap of round-off size
                // left by the last step is not pushed on again.
                let tolerance = row.reach;
                // A point that a flight took deeper than this was missed by the velocity
                // solve (a corner outside the manifold, a fast turn): closing it here would
                // throw the bodies apart at depth / h. It is left to the next step, whose
                // rows hold it and let it out at the resting speed.
                let d = if d < -PAIR_POSITION_LIMIT * tolerance {
                    f64::INFINITY
                } else {
                    d
                };
                contacts_hold &= d == f64::INFINITY
                    || d >= -tolerance && (row.position_impulse == 0.0 || d <= tolerance);
                self.pair_distances.push(d);
            }
            if worst_gap <= 1e-13 * size && contacts_hold {
                self.keep_joint_forces(h);
                return Ok(());
            }
            self.pre_drift.restore(bodies);
            if !joints.is_empty() {
                // The start placement again: the rows and K of the velocity solve hold.
                self.solver
                    .joint_position_step(bodies, &self.gaps, h, &mut self.joint_total);
            }
            // Contacts: one Newton step each, shared among the contacts of a body that push.
            self.sharing.clear();
            self.sharing.resize(bodies.len(), 0);
            for (row, d) in self.solver.contacts.iter().zip(&self.distances) {
                if *d < 0.0 || row.position_impulse > 0.0 {
                    self.sharing[row.body] += 1;
                }
            }
            for (row, d) in self.solver.pairs.iter().zip(&self.pair_distances) {
                if *d < 0.0 || row.position_impulse > 0.0 {
                    self.sharing[row.a] += 1;
                    self.sharing[row.b] += 1;
                }
            }
            for (row, &d) in self.solver.pairs.iter_mut().zip(&self.pair_distances) {
                if d >= 0.0 && row.position_impulse == 0.0 || d == f64::INFINITY {
                    continue;
                }
                let sharing = self.sharing[row.a].max(self.sharing[row.b]) as f64;
                let want = (row.position_impulse - d / (h * row.knn() * sharing)).max(0.0);
                if !want.is_finite() {
                    // A flight too short to close anything in (an impact located at its
                    // start): the gap is left to the next flight.
                    continue;
                }
                let dl = want - row.position_impulse;
                row.position_impulse = want;
                let j = &row.normal * dl;
                if !bodies[row.b].is_fixed() {
                    push(&mut bodies[row.b], &row.rb, &j);
                }
                if !bodies[row.a].is_fixed() {
                    push(&mut bodies[row.a], &row.ra, &(j * -1.0));
                }
            }
            for (row, &d) in self.solver.contacts.iter_mut().zip(&self.distances) {
                if d >= 0.0 && row.position_impulse == 0.0 {
                    continue;
                }
                let sharing = self.sharing[row.body] as f64;
                let want = (row.position_impulse - d / (h * row.knn * sharing)).max(0.0);
                let dl = want - row.position_impulse;
                row.position_impulse = want;
                let nrm = half_spaces[row.half_space].normal();
                let r = Vector::from_storage(row.r.iter().copied().collect());
                push(&mut bodies[row.body], &r, &(nrm * dl));
            }
            self.pre_drift.save(bodies);
        }
        if worst_gap <= 1e-13 * size {
            // Contacts that did not settle within the iterations are lifted out after the
            // flight, taken with the last impulses (the loop left the bodies at its start).
            self.drift(bodies, t, h)?;
            self.keep_joint_forces(h);
            return Ok(());
        }
        Err(DynamicsError::SolverDidNotConverge {
            time: t,
            iterations: 50,
            residual: worst_gap / size,
        })
    }

    /// Keeps the joints' position impulses of the step, as forces, for the next step.
    fn keep_joint_forces(&mut self, h: f64) {
        // Room for the joints in both, so that the swaps of the next steps do not allocate.
        let joints = self.joint_total.len();
        for forces in [&mut self.joint_force, &mut self.joint_force_before] {
            forces.reserve(joints.saturating_sub(forces.len()));
        }
        std::mem::swap(&mut self.joint_force, &mut self.joint_force_before);
        self.joint_force
            .resize_with(self.joint_total.len(), || Vector::zero(0));
        for (f, total) in self.joint_force.iter_mut().zip(&self.joint_total) {
            f.clone_from(total);
            *f *= 1.0 / h;
        }
    }

    /// Sets each body's sweep for a flight of h (none without h): how far its points move in the flight at
    /// its velocities now after the opening half kick, h (|v| + ½h |F|/m + |ω| r) (r its
    /// bounding radius, |ω| the norm of the bivector; F the constant force, or the last
    /// one evaluated), rounded up to a power of two, so that a body whose speed barely
    /// changes keeps it (and with it the pairs found and the manifolds kept); none below
    /// [`LEAST_SWEEP`] of its radius or for a fixed body. A body of nonzero restitution
    /// sweeps against the planes (whose own restitution acts there) but not against other
    /// bodies: its impacts with them are located, as restitution acts on their speed.
    fn set_sweeps(&mut self, system: &System, h: Option<f64>) {
        self.sweeps.clear();
        self.bouncing.clear();
        let pairs = self.touching.any_pairs();
        let Some(h) = h.filter(|_| pairs || !system.half_spaces().is_empty()) else {
            // No sweeps asked for, or nothing to touch (and nothing placed).
            if pairs {
                self.touching.set_sweeps(&[], &[]);
            }
            return;
        };
        let bodies = system.bodies();
        let forces = system
            .constant_wrenches()
            .or((self.wrenches.len() == bodies.len()).then_some(&self.wrenches[..]));
        for (i, (b, shape)) in bodies.iter().zip(system.shapes()).enumerate() {
            self.bouncing.push(b.restitution().is_some_and(|e| e > 0.0));
            if b.is_fixed() || matches!(shape, ContactShape::None) {
                self.sweeps.push(0.0);
                continue;
            }
            let r = self.placements.get(i).radius;
            let force = forces.map_or(0.0, |w| w[i].force.norm());
            let sweep = sweep(b, r, force, (h, 0.5 * h));
            self.sweeps
                .push(if sweep.is_finite() && sweep > LEAST_SWEEP * r {
                    power_of_two_above(sweep)
                } else {
                    0.0
                });
        }
        if pairs {
            self.touching.set_sweeps(&self.sweeps, &self.bouncing);
        }
    }

    /// Sets the bodies' sweeps for a flight of h ([`Self::sweeps`]; none without h) and
    /// marks the contact candidates within the contact tolerance now, or within the sweep
    /// for those whose impacts are not located.
    fn mark_active(&mut self, system: &System, h: Option<f64>) {
        self.place(system);
        self.mark_placed_active(system, h);
    }

    /// [`Self::mark_active`] with the bodies placed already.
    fn mark_placed_active(&mut self, system: &System, h: Option<f64>) {
        self.set_sweeps(system, h);
        self.active.clear();
        let mut active = std::mem::take(&mut self.active);
        for_each_candidate(
            system,
            &self.placements,
            &self.sweeps,
            |_, d, reach, sweep| active.push(d <= reach + sweep),
        );
        self.active = active;
        self.active_pairs.clear();
        if self.touching.any_pairs() {
            let placements = &self.placements;
            self.touching.scan(
                system.bodies(),
                |i| &placements.get(i).q,
                CONTACT_TOLERANCE,
                None,
            );
            self.active_pairs
                .extend(self.touching.found().iter().map(|c| ((c.a, c.b), c.gap)));
            // The pieces of compound bodies give a pair several gaps: the least stays.
            self.active_pairs
                .sort_unstable_by(|x, y| x.0.cmp(&y.0).then(x.1.total_cmp(&y.1)));
            self.active_pairs.dedup_by_key(|x| x.0);
        }
    }

    /// The least relative gap of the pairs of bodies (+∞ if there are none), below −1 where
    /// one entered: for a pair that was not in contact at the start of the step and comes
    /// within the bodies' radii, its gap over its reach; for a pair in contact then, 1 plus
    /// how far it sank below where it started (or below touching) over [`SINK_LIMIT`]'s
    /// depth: below −1 once it sank by twice that depth, and the impact located where it
    /// has sunk by about that depth.
    fn pair_penetration(&mut self, system: &System) -> f64 {
        if !self.touching.any_pairs() {
            return f64::INFINITY;
        }
        // Pairs within their radii of each other are asked while an impact is located (its
        // regula falsi needs the gaps on the near side too); otherwise only touching and
        // overlapping pairs, which the broad phase's bounds settle for most pairs unasked.
        let factor = if self.locating {
            1.0
        } else {
            CONTACT_TOLERANCE
        };
        let placements = &self.placements;
        self.touching
            .scan(system.bodies(), |i| &placements.get(i).q, factor, None);
        let mut worst = f64::INFINITY;
        for c in self.touching.found() {
            let relative = match self.active_pairs.binary_search_by_key(&(c.a, c.b), |x| x.0) {
                Err(_) => c.gap / self.touching.touching_reach((c.a, c.b), CONTACT_TOLERANCE),
                // A pair in contact sinks where a feature its rows did not hold lands (a
                // corner of a turning or sliding box beyond the manifold's slop, an edge
                // sliding along an edge), or where a turning body misses a speculative
                // row's aim: an impact too, located where it has sunk by about SINK_LIMIT's
                // depth; the next substep's manifold holds the feature from there.
                Ok(k) => {
                    let start = self.active_pairs[k].1.min(0.0);
                    1.0 + (c.gap - start) / self.touching.touching_reach((c.a, c.b), SINK_LIMIT)
                }
            };
            worst = worst.min(relative);
            if relative < -1.0 {
                self.entering
                    .push(Entering::Pair(c.a, c.b, c.gap, relative));
            }
        }
        worst
    }

    /// The least distance, relative to the reach, of the candidates that were not in
    /// contact at the start of the step (+∞ if there are none).
    fn new_penetration(&mut self, system: &System) -> f64 {
        self.place(system);
        self.placed_penetration(system)
    }

    /// [`Self::new_penetration`] with the bodies placed already.
    fn placed_penetration(&mut self, system: &System) -> f64 {
        let mut worst = f64::INFINITY;
        self.entering.clear();
        for_each_candidate(system, &self.placements, &[], |k, d, reach, _| {
            if !self.active[k] {
                worst = worst.min(d / reach);
                if d < -reach {
                    self.entering.push(Entering::Candidate(d / reach));
                }
            }
        });
        worst.min(self.pair_penetration(system))
    }

    /// One kick–drift–kick step of length h with the contact and joint impulses, from the
    /// current state, without its closing half kick and solve if `close` is false. Returns
    /// the least relative distance of the candidates not in contact at its start, before
    /// they are lifted back.
    fn substep(
        &mut self,
        system: &mut System,
        t: f64,
        h: f64,
        close: bool,
    ) -> Result<f64, DynamicsError> {
        self.half_kick(system, t, h, true);
        // A try of an impact's location drops what it recorded: it records nothing.
        let record = !self.unrecorded && !self.locating;
        self.solve_velocities(system, (0.5 * h, h), record);
        let fresh = self.flight(system, t, h)?;
        if close {
            self.close(system, t + h, h);
        }
        Ok(fresh)
    }

    /// The constrained free flight of a substep and the lift back onto the planes; returns
    /// the least relative distance of the fresh candidates before the lift.
    fn flight(&mut self, system: &mut System, t: f64, h: f64) -> Result<f64, DynamicsError> {
        self.constrained_drift(system, t, h)?;
        // Where there were contacts to check, the flight has placed the bodies at its end.
        let fresh = if self.solver.contacts.is_empty() {
            self.new_penetration(system)
        } else {
            self.placed_penetration(system)
        };
        lift_out(system, &self.placements);
        Ok(fresh)
    }

    /// The closing half kick (at the end `t` of a substep of length h) and velocity solve.
    fn close(&mut self, system: &mut System, t: f64, h: f64) {
        self.closing_kick(system, t, h);
        self.solve_velocities(system, (0.5 * h, h), !self.unrecorded);
    }

    /// A step with contacts and joints: substeps cut at the impacts. With `leave_open`, the
    /// last substep's closing half kick and solve are left to the caller, and the substep's
    /// length is returned (None when the step was closed).
    fn constrained_step(
        &mut self,
        system: &mut System,
        t: f64,
        h: f64,
        leave_open: bool,
    ) -> Result<Option<f64>, DynamicsError> {
        system.clear_contacts();
        self.locating = false;
        let (mut t, mut remaining) = (t, h);
        for events in 0..=MAX_EVENTS {
            self.mark_active(system, Some(remaining));
            let mut saved = std::mem::take(&mut self.saved);
            saved.save(system.bodies());
            let mut f_end = self.substep(system, t, remaining, false)?;
            if f_end < -1.0 && events < MAX_EVENTS {
                // Contacts that close slowly count as in contact from the start, so that only
                // the others are located; the closing solve holds them (and lets their
                // overlap out).
                let mut end = std::mem::take(&mut self.flight_end);
                end.save(system.bodies());
                let fast = self.admit_entering(system, &saved, h);
                if fast >= -1.0 {
                    // Nothing to locate: the flight stands.
                    end.restore(system.bodies_mut());
                }
                self.flight_end = end;
                f_end = fast;
            }
            if f_end >= -1.0 || events == MAX_EVENTS {
                self.saved = saved;
                if leave_open {
                    return Ok(Some(remaining));
                }
                self.close(system, t + remaining, remaining);
                return Ok(None);
            }
            // An impact inside the step: find where the fresh candidates reach the plane.
            self.locating = true;
            let (mut a, mut fa) = (0.0, {
                saved.restore(system.bodies_mut());
                self.new_penetration(system)
            });
            let (mut b, mut fb) = (remaining, f_end);
            // The gap at b as found (fb is scaled by the method), and the tries made in a
            // bracket narrower than LOCATE_WIDTH.
            let (mut gap_at_b, mut narrow) = (f_end, 0);
            let mut side = 0i8;
            let mut s = remaining;
            // The bracket's width at the last third try (or the start).
            let mut width = remaining;
            for iteration in 0..100 {
                // Regula falsi (Anderson–Björck), and every third try a bisection unless the
                // two tries before have halved the bracket: with several bodies the least
                // gap jumps where another pair becomes the nearest, and there the bracket
                // must still shrink. The gap at the step's end may be millions of times the
                // touching distance deep, and regula falsi's first tries then land next to
                // the start: where the bracket spans more than a factor 4, it is bisected
                // at its geometric mean, which crosses its decades in a few tries.
                s = (a * fb - b * fa) / (fb - fa);
                if !(s > a && s < b) || iteration % 3 == 2 && b - a > 0.5 * width {
                    s = if a > 0.0 && b > 4.0 * a {
                        (a * b).sqrt()
                    } else {
                        0.5 * (a + b)
                    };
                }
                if iteration % 3 == 2 {
                    width = b - a;
                }
                if b - a <= LOCATE_WIDTH * remaining {
                    // The impact is located to within this; the substep ends where the
                    // bodies have just met: at once if they are within their touching
                    // distance there, else after a few more tries, which close in on a
                    // steep crossing and stop at a jump (where another pair becomes the
                    // nearest).
                    if gap_at_b >= -1.0 || narrow == MAX_NARROW_TRIES {
                        s = b;
                        break;
                    }
                    narrow += 1;
                }
                if s <= 1e-9 * remaining {
                    // Entering at once (an overlap that the step's own contacts push a body
                    // into): nothing to locate; the rest of the step is taken whole and the
                    // new contact is held from the next step on.
                    s = remaining;
                    break;
                }
                saved.restore(system.bodies_mut());
                let contacts_before = system.contact_mark();
                // A try needs the gaps at the end of its flight only: its closing kick and
                // solve would be thrown away with it, and each next try's opening solve
                // then starts from impulses of the same instant, not of the try's end.
                let f = self.substep(system, t, s, false)?;
                system.truncate_contacts(contacts_before);
                if f.abs() <= 0.25 {
                    break;
                }
                // An end kept for the second try running has its gap scaled by
                // 1 − f / f_last, f and f_last the new and the replaced gap at the other end
                // (Anderson and Björck 1973; by a half where that is not positive): where
                // the other end barely moves, the next try leaves it.
                if f > 0.0 {
                    if side == 1 {
                        let m = 1.0 - f / fa;
                        fb *= if m > 0.0 { m } else { 0.5 };
                    }
                    (a, fa) = (s, f);
                    side = 1;
                } else {
                    if side == -1 {
                        let m = 1.0 - f / fb;
                        fa *= if m > 0.0 { m } else { 0.5 };
                    }
                    (b, fb, gap_at_b) = (s, f, f);
                    side = -1;
                }
            }
            self.locating = false;
            // Take the located substep for real, recording its contacts.
            saved.restore(system.bodies_mut());
            self.substep(system, t, s, true)?;
            self.saved = saved;
            t += s;
            remaining -= s;
            if remaining <= 1e-14 * h {
                return Ok(None);
            }
        }
        Ok(None)
    }

    /// Marks as in contact the contacts between bodies entering in the flight just taken (a
    /// substep of a step of length `step`, from the state `saved`) that closed their
    /// distance no faster on average than the forques make bodies approach in one step (the resting
    /// speed of a whole step): located, they would be resolved without restitution, as they
    /// are in the closing solve, and locating each (a bracketing of its own, with two solves
    /// per try) would cost far more than the step. Pairs that were in contact and sank are
    /// never admitted so. Returns the least relative distance at
    /// the end of the flight of the others (+∞ if none), and leaves the bodies at `saved`.
    fn admit_entering(&mut self, system: &mut System, saved: &SavedBodies, step: f64) -> f64 {
        let entering = std::mem::take(&mut self.entering);
        saved.restore(system.bodies_mut());
        // The pairs within their radii of each other at the start.
        self.place(system);
        if self.touching.any_pairs() {
            let placements = &self.placements;
            self.touching
                .scan(system.bodies(), |i| &placements.get(i).q, 1.0, None);
        }
        let mut fast = f64::INFINITY;
        for e in &entering {
            let Entering::Pair(a, b, end, relative) = *e else {
                // A half-space lifts what sinks into it out along its normal, which would
                // add the lift's potential energy: its impacts are all located.
                if let Entering::Candidate(relative) = *e {
                    fast = fast.min(relative);
                }
                continue;
            };
            let start = self
                .touching
                .found()
                .iter()
                .find(|c| (c.a, c.b) == (a, b))
                .map_or(f64::INFINITY, |c| c.gap);
            // The resting speeds were set for the substep, of length h: over the whole step
            // they are step / h times as large, and the bound on the average approach over
            // the substep is that times h.
            let speed = self.resting_speed[a].max(self.resting_speed[b]);
            // A pair in contact that sank is located however slowly it sank: admitting it
            // would change nothing, and the feature that sinks would go on unheld.
            let active = self.active_pairs.binary_search_by_key(&(a, b), |x| x.0);
            if start - end > speed * step || active.is_ok() {
                fast = fast.min(relative);
                continue;
            }
            if let Err(at) = active {
                self.active_pairs.insert(at, ((a, b), f64::NEG_INFINITY));
            }
        }
        self.entering = entering;
        fast
    }

    /// `steps` steps of h from t with contacts or joints under constant forques, in leapfrog
    /// form: the closing half kick and solve of a step and the opening ones of the next are
    /// one kick of h and one solve. Both half kicks are the same constant wrench at the same
    /// placement, and a solve at a placement is a projection of the velocities (linear and
    /// idempotent while the contacts rest or stick and for joints), so joining them changes
    /// the result only at round-off there. A step in which a fresh candidate would enter a
    /// half-space (an impact) is taken back and taken by [`Self::constrained_step`], which
    /// locates the impact; so is the last step, so that the contacts listed are those of a
    /// single step.
    fn joined_steps(
        &mut self,
        system: &mut System,
        t: f64,
        h: f64,
        steps: usize,
    ) -> Result<(), DynamicsError> {
        // The length of the substep whose closing half kick and solve are pending.
        let mut open: Option<f64> = None;
        for k in 0..steps {
            let (tk, last) = (t + k as f64 * h, k + 1 == steps);
            // Each step clears the contacts of the step before: only the last one's are
            // recorded (the pending close below belongs to the step before).
            self.unrecorded = !last;
            if let Some(before) = open {
                // Bodies that touch each other take their steps singly (see `advance`).
                let touching = !self.solver.pairs.is_empty();
                if !last && !touching && self.joined_step(system, tk, before, h)? {
                    check_finite(system, tk)?;
                    open = Some(h);
                    continue;
                }
                self.close(system, tk, before);
            }
            open = self.constrained_step(system, tk, h, !last)?;
            check_finite(system, tk)?;
        }
        Ok(())
    }

    /// The closing half kick and solve of the substep of length `before` that ended at t,
    /// joined with the opening ones of the step of h from t, and that step's flight. Returns
    /// false, with the state as it was, if a fresh candidate would enter a half-space.
    fn joined_step(
        &mut self,
        system: &mut System,
        t: f64,
        before: f64,
        h: f64,
    ) -> Result<bool, DynamicsError> {
        system.clear_contacts();
        // The step before ended with its flight, which placed the bodies, and the kick turns
        // none of them: the placements hold until this step's flight.
        // Without sweeps: a step with an impact is taken again by `constrained_step`, which
        // holds a speculative contact without locating it (bodies at rest, the joined steps'
        // case, would only pay for their sweeps).
        self.mark_placed_active(system, None);
        let mut saved = std::mem::take(&mut self.saved);
        saved.save(system.bodies());
        self.joined_kick(system, before, h);
        // The step's contacts are not recorded: only the last step's are listed, and the
        // last step is a single one.
        self.solve_placed(system, (0.5 * (before + h), h), false);
        let fresh = self.flight(system, t, h)?;
        if fresh < -1.0 {
            saved.restore(system.bodies_mut());
        }
        self.saved = saved;
        Ok(fresh >= -1.0)
    }

    /// The closing half kick of a substep of length `before` and the opening half kick of
    /// one of length h as one kick (constant wrenches), setting the resting speeds for h.
    fn joined_kick(&mut self, system: &mut System, before: f64, h: f64) {
        let (bodies, Some(constant)) = system.bodies_and_constant_wrenches() else {
            unreachable!("joined steps run under constant wrenches only")
        };
        Self::set_resting_speeds(&mut self.resting_speed, bodies, &constant.wrenches, h);
        kick(bodies, &constant.wrenches, 0.5 * (before + h));
    }
}

/// Calls `visit(k, distance, reach, sweep)` for every contact candidate of every body
/// against every half-space, k numbering them in a fixed order, the bodies placed by
/// `placements`; the sweep is the body's in `sweeps` (0 if it has none there) against a
/// half-space of restitution 0, else 0.
fn for_each_candidate(
    system: &System,
    placements: &Placements,
    sweeps: &[f64],
    mut visit: impl FnMut(usize, f64, f64, f64),
) {
    if system.half_spaces().is_empty() {
        // Nothing to touch, and nothing placed (placements are kept for contacts).
        return;
    }
    let mut k = 0;
    for (i, (b, shape)) in system.bodies().iter().zip(system.shapes()).enumerate() {
        if matches!(shape, ContactShape::None) || b.is_fixed() {
            continue;
        }
        let placed = placements.get(i);
        let reach = CONTACT_TOLERANCE * placed.radius;
        let body_sweep = sweeps.get(i).copied().unwrap_or(0.0);
        for (j, plane) in system.half_spaces().iter().enumerate() {
            let base = plane.distance(b.position());
            let sweep = plane_sweep(plane, body_sweep, false);
            placed.candidate_heights(shape, (j, plane.normal()), |_, h| {
                visit(k, base + h, reach, sweep);
                k += 1;
            });
        }
    }
}

/// The least power of two at or above `x` (positive, finite and normal).
fn power_of_two_above(x: f64) -> f64 {
    const FRACTION: u64 = (1 << 52) - 1;
    let bits = x.to_bits();
    if bits & FRACTION == 0 {
        x
    } else {
        // The exponent one up, the fraction cleared.
        f64::from_bits((bits & !FRACTION) + (1 << 52))
    }
}

/// Writes into `gap` the gap between the two ends of `joint` (zero when it holds), its
/// points given by `ends` as in `MotionSplitting::joint_ends`.
fn joint_gap(
    joint: &crate::dynamics::motion::BallJoint,
    (point, other): &(Vector, Vector),
    bodies: &[MovingBody],
    gap: &mut Vector,
) {
    let place = |b: &MovingBody, r: &Vector| {
        let mut x = b.rotation().principal_frame_attitude().rotate_vector(r);
        x += b.position();
        x
    };
    *gap = place(&bodies[joint.body], point);
    match &joint.other {
        Anchor::World(_) => *gap -= other,
        Anchor::Body(k, _) => *gap -= &place(&bodies[*k], other),
    }
}

/// The signed distance at the contact point of `row` with the bodies where they are now:
/// its gap when found, plus how far the flight has moved the point of body b away from that
/// of body a along the normal (both points start at the contact point and move with their
/// bodies).
fn pair_distance(row: &crate::dynamics::motion::solve::PairRow, bodies: &[MovingBody]) -> f64 {
    let end = |i: usize, own: &Vector| {
        let b = &bodies[i];
        let mut x = b.rotation().principal_frame_attitude().rotate_vector(own);
        x += b.position();
        x
    };
    let mut moved = end(row.b, &row.own_b);
    moved -= &end(row.a, &row.own_a);
    row.gap + row.normal.dot(&moved)
}

/// Gives body `b` the impulse `j` (space) at offset `r` (space) from its centre of mass.
fn push(b: &mut MovingBody, r: &Vector, j: &Vector) {
    let (_, p, rotation) = b.state_mut();
    *p += j;
    let dl = rotation
        .principal_frame_attitude()
        .inverse_rotate_bivector(&r.wedge(j));
    let (_, l) = rotation.state_mut();
    *l += &dl;
}

/// Lifts every body that sinks into a half-space back onto its plane, along the normal
/// (the bodies placed by `placements`; lifting does not turn them).
fn lift_out(system: &mut System, placements: &Placements) {
    let (bodies, shapes, half_spaces, _, _) = system.parts_mut();
    if half_spaces.is_empty() {
        // Nothing to lift out of, and nothing placed (placements are kept for contacts).
        return;
    }
    for (i, (b, shape)) in bodies.iter_mut().zip(shapes.iter()).enumerate() {
        if matches!(shape, ContactShape::None) || b.is_fixed() {
            continue;
        }
        let placed = placements.get(i);
        for (j, plane) in half_spaces.iter().enumerate() {
            let n = plane.normal();
            let mut deepest = f64::INFINITY;
            placed.candidate_heights(shape, (j, n), |_, h| deepest = deepest.min(h));
            let d = plane.distance(b.position()) + deepest;
            if d < 0.0 {
                let (x, _, _) = b.state_mut();
                *x += &(n * -d);
            }
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
        self.check_start(system)?;
        let before = self.solver.report;
        self.step_checked(system, t, h)?;
        self.check_solves(&before, t)
    }

    /// Under constant forques (gravity, constant forces and torques) with contacts or
    /// joints, consecutive steps share a velocity solve: the closing half kick and solve of
    /// one step and the opening ones of the next are one kick and one solve, the leapfrog
    /// form of the same splitting (one solve per step instead of two). A solve is a
    /// projection of the velocities, linear and idempotent while the contacts rest, stick
    /// or slide one way and for joints, so the result is that of `steps` calls of
    /// [`MotionIntegrator::step`] to round-off there; through bounces and stick–slip
    /// transitions the two agree to the solver's tolerance. A step with an impact, and the
    /// last step, are taken singly, so the impacts are located and [`System::contacts`]
    /// lists what it lists after [`MotionIntegrator::step`]. So are the steps that start
    /// with bodies touching each other: then the motion is that of single steps to the bit.
    /// Other systems take their steps one by one.
    ///
    /// Why bodies in contact take single steps: where they rest on each other, the impulses
    /// that hold them are not unique (a cube on two others, cubes side by side), and each
    /// solve stops within its tolerance somewhere in that family. Single steps solve twice
    /// at each placement with the same kick, and the second solve starts where the first
    /// stopped; joined solves start from impulses scaled by the ratio of two kicks, and
    /// their small misfits drift through the family (points that single steps leave
    /// unloaded take up load), which later solves take thousands of sweeps to undo: on a
    /// pyramid of 55 cubes nine times as long as single steps (the moving-bodies chapter
    /// gives the measurement).
    fn advance(
        &mut self,
        system: &mut System,
        t: f64,
        h: f64,
        steps: usize,
    ) -> Result<(), DynamicsError> {
        self.check_start(system)?;
        if self.constrained(system)
            && steps > 1
            && system.bodies_and_constant_wrenches().1.is_some()
        {
            let before = self.solver.report;
            self.joined_steps(system, t, h, steps)?;
            return self.check_solves(&before, t);
        }
        one_by_one(self, system, (t, h), steps)
    }
}

impl MotionSplitting {
    /// Returns this splitting refusing every step whose contact solve stops unconverged or
    /// whose joint system is singular ([`MotionError::SolveNotConverged`],
    /// [`MotionError::SingularJoints`]) instead of going on and counting it in
    /// [`MotionSplitting::solver_report`].
    pub fn strict(mut self) -> Self {
        self.strict = true;
        self
    }

    /// Returns this splitting with at most `sweeps` Gauss–Seidel sweeps per contact solve
    /// (20,000 by default): a solve that has not converged by then stops with the impulses it
    /// has and is counted as unconverged in [`MotionSplitting::solver_report`], with its
    /// residual (an error under [`MotionSplitting::strict`]). A resting stack takes one
    /// sweep per solve and is not slowed by a limit; a pile whose contacts keep changing
    /// spends most of its time in the few solves that take thousands of sweeps to reach the
    /// tolerance, which a limit cuts short. Every impulse acts on both bodies of its pair,
    /// so momentum is kept whatever the limit.
    ///
    /// # Errors
    /// [`MotionError::OutOfRange`] for 0.
    pub fn with_sweep_limit(mut self, sweeps: usize) -> Result<Self, MotionError> {
        self.solver.sweep_limit = Some(positive_count("sweep limit", sweeps)?);
        Ok(self)
    }

    /// The most Gauss–Seidel sweeps a contact solve takes
    /// ([`MotionSplitting::with_sweep_limit`]).
    pub fn sweep_limit(&self) -> usize {
        self.solver.sweep_limit.unwrap_or(MAX_SWEEPS)
    }

    /// Returns what the velocity and joint solves met since this integrator was made or its
    /// report reset: solves, those that stopped unconverged and their worst residual, the
    /// most sweeps one took, singular joint systems.
    pub fn solver_report(&self) -> SolverReport {
        self.solver.report
    }

    /// Starts the counts of [`MotionSplitting::solver_report`] anew.
    pub fn reset_solver_report(&mut self) {
        self.solver.report = SolverReport::default();
    }

    /// Checks the system before its first step, and again after shapes or half-spaces were
    /// added ([`System::check_contacts`]).
    fn check_start(&mut self, system: &System) -> Result<(), DynamicsError> {
        let key = system.contacts_key();
        if self.checked != Some(key) {
            system.check_contacts()?;
            self.checked = Some(key);
        }
        Ok(())
    }

    /// Under [`MotionSplitting::strict`], refuses a step whose solves did worse than the
    /// report `before` it says.
    fn check_solves(&self, before: &SolverReport, t: f64) -> Result<(), DynamicsError> {
        let now = &self.solver.report;
        if !self.strict {
            return Ok(());
        }
        if now.singular_joint_solves > before.singular_joint_solves {
            return Err(MotionError::SingularJoints { time: t }.into());
        }
        if now.unconverged > before.unconverged {
            return Err(MotionError::SolveNotConverged {
                time: t,
                sweeps: now.max_sweeps,
                residual: now.worst_residual,
            }
            .into());
        }
        Ok(())
    }

    /// True if the system has joints, half-spaces or bodies that can touch each other.
    fn constrained(&mut self, system: &System) -> bool {
        self.touching.update_shapes(
            system.shapes(),
            system.joints(),
            system.dim(),
            system.shape_key(),
        );
        !system.joints().is_empty() || !system.half_spaces().is_empty() || self.touching.any_pairs()
    }

    /// One step, the system checked.
    fn step_checked(&mut self, system: &mut System, t: f64, h: f64) -> Result<(), DynamicsError> {
        // A single step lists its contacts (also after an `advance` that stopped early).
        self.unrecorded = false;
        if self.constrained(system) {
            self.constrained_step(system, t, h, false)?;
            return check_finite(system, t);
        }
        if let (bodies, Some(constant)) = system.bodies_and_constant_wrenches() {
            // Constant forques (gravity): both half kicks are one wrench, evaluated when the
            // forques joined the system; the halves that are zero change nothing.
            let kick = |bodies: &mut [MovingBody]| {
                for (b, w) in bodies.iter_mut().zip(&constant.wrenches) {
                    if b.is_fixed() {
                        continue;
                    }
                    let (_, p, rotation) = b.state_mut();
                    if constant.any_force {
                        axpy(p.as_mut_slice(), 0.5 * h, w.force.as_slice());
                    }
                    if constant.any_torque {
                        let (_, l) = rotation.state_mut();
                        axpy(l.as_mut_slice(), 0.5 * h, w.torque.as_slice());
                    }
                }
            };
            kick(bodies);
            self.drift(bodies, t, h)?;
            kick(bodies);
            // The rotation step has checked the attitude and L; after it only the kick
            // changed p (and L under a constant torque).
            let finite = |x: &[f64]| x.iter().all(|c| c.is_finite());
            let ok = bodies.iter().all(|b| {
                finite(b.position().as_slice())
                    && finite(b.linear_momentum().as_slice())
                    && (!constant.any_torque || finite(b.rotation().momentum().as_slice()))
            });
            return if ok {
                Ok(())
            } else {
                Err(DynamicsError::NonFinite { time: t })
            };
        }
        self.wrenches_at(system, t);
        kick(system.bodies_mut(), &self.wrenches, 0.5 * h);
        self.drift(system.bodies_mut(), t, h)?;
        self.closing_kick(system, t + h, h);
        check_finite(system, t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::{Bivector, Rotor};
    use crate::dynamics::motion::HalfSpace;
    use crate::dynamics::motion::forques::Gravity;
    use crate::inertia::spec::parse_body;

    fn axis(n: usize, i: usize, x: f64) -> Vector {
        let mut v = Vector::zero(n);
        v.as_mut_slice()[i] = x;
        v
    }

    /// Cuboids in N dimensions dropped and thrown onto the floor x_N = 0 beside a slope,
    /// turning: impacts, sliding and rolling over happen within 60 steps.
    fn scene(n: usize) -> System {
        let half: Vec<String> = (0..n)
            .map(|k| format!("{}", 0.5 + 0.1 * k as f64))
            .collect();
        let parsed = parse_body(&format!("cuboid:{}", half.join(","))).unwrap();
        let mut bodies = Vec::new();
        for k in 0..4 {
            let mut x = axis(n, 0, 3.0 * k as f64);
            x.as_mut_slice()[n - 1] = 1.2 + 0.3 * k as f64;
            let w: Vec<f64> = (0..n * (n - 1) / 2)
                .map(|p| (0.7 * (p + k) as f64 + 0.3).sin() * (1.0 + 0.3 * k as f64))
                .collect();
            let v = axis(n, 0, 1.5 - k as f64);
            bodies.push(
                MovingBody::new(
                    parsed.mass,
                    parsed.inertia.clone(),
                    Rotor::identity(n),
                    &x,
                    &v,
                    &Bivector::from_components(n, &w).unwrap(),
                )
                .unwrap(),
            );
        }
        let mut system = System::new(bodies).unwrap();
        for i in 0..4 {
            system
                .set_shape(i, ContactShape::from_geometry(&parsed.geometry))
                .unwrap();
        }
        system.add_forque(Gravity(axis(n, n - 1, -9.81))).unwrap();
        system
            .add_half_space(HalfSpace::new(&axis(n, n - 1, 1.0), 0.0, 0.5, 0.0).unwrap())
            .unwrap();
        let mut slope = axis(n, n - 1, 1.0);
        slope.as_mut_slice()[0] = -0.3;
        system
            .add_half_space(HalfSpace::new(&slope, -4.0, 0.3, 0.5).unwrap())
            .unwrap();
        system
    }

    #[test]
    fn power_of_two_above_is_the_least_power_at_or_above() {
        let mut cases = 0;
        for x in [1e-6, 0.3, 1.0, 1.5, 2.0, 3.0, 1e3, 1024.0, 1025.0, 7.3e-12] {
            let p = power_of_two_above(x);
            assert_eq!(p, 2f64.powi(x.log2().ceil() as i32), "{x}");
            assert!(p >= x && p < 2.0 * x, "{x}");
            cases += 1;
        }
        assert_eq!(cases, 10);
    }

    /// The fixed-size contact kernels of 3D and 4D take the steps of the run-time ones: the
    /// two agree to round-off over a scene of impacts, sliding and resting contact.
    #[test]
    fn fixed_size_contact_kernels_match_the_runtime_ones() {
        for n in [3usize, 4] {
            let (mut fast, mut general) = (scene(n), scene(n));
            let mut a = MotionSplitting::new();
            let mut b = MotionSplitting::new();
            b.solver.runtime_kernels = true;
            let h = 0.01;
            let mut touched = 0;
            for k in 0..60 {
                a.step(&mut fast, k as f64 * h, h).unwrap();
                b.step(&mut general, k as f64 * h, h).unwrap();
                touched += fast.contacts().len();
                assert_eq!(fast.contacts().len(), general.contacts().len(), "N = {n}");
            }
            assert!(
                touched > 100,
                "N = {n}: the bodies touch the floor ({touched})"
            );
            for (x, y) in fast.bodies().iter().zip(general.bodies()) {
                let close = |p: &[f64], q: &[f64]| {
                    p.iter()
                        .zip(q)
                        .all(|(u, v)| (u - v).abs() <= 1e-12 * (1.0 + v.abs()))
                };
                assert!(
                    close(x.position().as_slice(), y.position().as_slice()),
                    "N = {n}"
                );
                assert!(
                    close(
                        x.linear_momentum().as_slice(),
                        y.linear_momentum().as_slice()
                    ),
                    "N = {n}"
                );
                assert!(
                    close(
                        x.rotation().momentum().as_slice(),
                        y.rotation().momentum().as_slice()
                    ),
                    "N = {n}"
                );
                let (ra, rb) = (x.attitude().to_matrix(), y.attitude().to_matrix());
                assert!((ra - rb).abs().max() <= 1e-12, "N = {n}");
            }
        }
    }

    /// A pyramid of `layers` unit cubes in N dimensions (its rows along the first axis, a
    /// hundredth apart), resting on the floor x_N = 0 and on each other, at rest.
    fn pyramid(n: usize, layers: usize) -> System {
        let parsed = parse_body(&format!("cuboid:{}+mass=1", vec!["0.5"; n].join(","))).unwrap();
        let mut bodies = Vec::new();
        for layer in 0..layers {
            for k in 0..layers - layer {
                let mut x = axis(n, 0, 1.01 * (k as f64 + 0.5 * layer as f64));
                x.as_mut_slice()[n - 1] = 0.5 + layer as f64;
                bodies.push(
                    MovingBody::from_parsed(
                        &parsed,
                        Rotor::identity(n),
                        &x,
                        &Vector::zero(n),
                        &Bivector::zero(n),
                    )
                    .unwrap(),
                );
            }
        }
        let mut system = System::new(bodies).unwrap();
        system.add_forque(Gravity(axis(n, n - 1, -9.81))).unwrap();
        system
            .add_half_space(HalfSpace::new(&axis(n, n - 1, 1.0), 0.0, 0.5, 0.0).unwrap())
            .unwrap();
        system
    }

    /// A box whose bottom face is tilted by less than the touching distance lands on a
    /// fixed slab with friction, pulled along it: Gauss–Seidel hands the friction impulse
    /// round the face's corners, one solve cycles, and its sweeps leave the velocities as
    /// they were while each update still moves them. The solve stops on the cycle within
    /// tens of sweeps instead of after 500 without progress, with the same residual and the
    /// same motion.
    #[test]
    fn a_cycling_solve_stops_at_the_velocities_more_sweeps_would_leave() {
        let n = 3;
        let parsed = parse_body("cuboid:0.5,0.5,0.5").unwrap();
        let slab = ContactShape::from_geometry(&parse_body("cuboid:2,2,0.5").unwrap().geometry);
        let touching = 1e-6 * (0.75f64.sqrt() + slab.radius());
        let mut tilt = Bivector::zero(n);
        // The planes (0, 2) and (1, 2), by 0.75 and 0.6 of the touching distance.
        tilt.as_mut_slice()[1] = 0.75 * touching;
        tilt.as_mut_slice()[2] = 0.6 * touching;
        let placed = |height: f64| {
            MovingBody::from_parsed(
                &parsed,
                Rotor::from_rotation_bivector(&tilt),
                &axis(n, n - 1, height),
                &Vector::zero(n),
                &Bivector::zero(n),
            )
            .unwrap()
            .with_friction(0.5)
            .unwrap()
        };
        // The lowest corner at 0.05 of the touching distance above the slab.
        let lowest = (0..8)
            .map(|k| {
                let corner: Vec<f64> = (0..n)
                    .map(|i| if k >> i & 1 == 1 { 0.5 } else { -0.5 })
                    .collect();
                placed(0.0)
                    .point_position(&Vector::from_components(&corner).unwrap())
                    .as_slice()[n - 1]
            })
            .fold(f64::INFINITY, f64::min);
        let mut runs = Vec::new();
        for stall_only in [false, true] {
            let slab = MovingBody::fixed(slab.clone(), Rotor::identity(n), &axis(n, n - 1, -0.5))
                .unwrap()
                .with_friction(0.5)
                .unwrap();
            let mut system = System::new(vec![placed(0.05 * touching - lowest), slab]).unwrap();
            let mut g = axis(n, n - 1, -9.81);
            g.as_mut_slice()[0] = 0.3 * 0.5 * 9.81;
            system.add_forque(Gravity(g)).unwrap();
            let mut stepper = MotionSplitting::new();
            stepper.solver.stall_only = stall_only;
            for k in 0..30 {
                stepper
                    .step(&mut system, k as f64 / 60.0, 1.0 / 60.0)
                    .unwrap();
            }
            runs.push((stepper.solver_report(), system));
        }
        let ((cycle, a), (stall, b)) = (&runs[0], &runs[1]);
        println!("stopped on the cycle: {cycle:?}\nafter the stall: {stall:?}");
        assert!(
            stall.unconverged > 0
                && stall.max_sweeps > crate::dynamics::motion::solve::STALLED_SWEEPS,
            "{stall:?}"
        );
        assert_eq!(cycle.unconverged, stall.unconverged);
        // Each run names why its solve stopped: the cycle, or the stall rule alone.
        assert_eq!(cycle.cycled, cycle.unconverged, "{cycle:?}");
        assert_eq!(stall.stalled, stall.unconverged, "{stall:?}");
        assert_eq!((cycle.stalled, stall.cycled), (0, 0));
        assert!(cycle.max_sweeps < 100, "{cycle:?}");
        assert!((cycle.worst_residual - stall.worst_residual).abs() <= 1e-3 * stall.worst_residual);
        let (x, y) = (&a.bodies()[0], &b.bodies()[0]);
        let close = |p: &[f64], q: &[f64], scale: f64| {
            p.iter().zip(q).all(|(u, v)| (u - v).abs() <= 1e-12 * scale)
        };
        assert!(close(x.position().as_slice(), y.position().as_slice(), 1.0));
        assert!(close(
            x.linear_momentum().as_slice(),
            y.linear_momentum().as_slice(),
            1.0
        ));
        assert!(close(
            x.rotation().momentum().as_slice(),
            y.rotation().momentum().as_slice(),
            1.0
        ));
    }

    /// A sweep limit bounds every contact solve: a pyramid started cold (a solve of about
    /// a thousand sweeps to the tolerance) stops at the limit, counted unconverged, and
    /// under `strict` the step is refused; a limit of zero is refused.
    #[test]
    fn a_sweep_limit_stops_every_solve_there_and_counts_it() {
        assert_eq!(MotionSplitting::new().sweep_limit(), MAX_SWEEPS);
        assert!(matches!(
            MotionSplitting::new().with_sweep_limit(0),
            Err(MotionError::OutOfRange { .. })
        ));
        let mut cases = 0;
        for (n, layers) in [(3usize, 6usize), (4, 4)] {
            for limit in [1, 5, 40] {
                let mut system = pyramid(n, layers);
                let mut stepper = MotionSplitting::new().with_sweep_limit(limit).unwrap();
                assert_eq!(stepper.sweep_limit(), limit);
                stepper.step(&mut system, 0.0, 1.0 / 60.0).unwrap();
                let report = stepper.solver_report();
                assert_eq!(report.max_sweeps, limit, "N = {n}: {report:?}");
                assert!(
                    report.unconverged > 0 && report.worst_residual > 0.0,
                    "N = {n}: {report:?}"
                );
                // Every unconverged solve is named by why it stopped: here the limit (a
                // cold pyramid's sweeps do not cycle, and no limit reaches the 500 of a
                // stall).
                assert_eq!(
                    report.at_sweep_limit, report.unconverged,
                    "N = {n}: {report:?}"
                );
                assert_eq!(
                    (report.stalled, report.cycled),
                    (0, 0),
                    "N = {n}: {report:?}"
                );
                let mut strict = MotionSplitting::new()
                    .with_sweep_limit(limit)
                    .unwrap()
                    .strict();
                let refused = strict.step(&mut pyramid(n, layers), 0.0, 1.0 / 60.0);
                assert!(
                    matches!(
                        refused,
                        Err(DynamicsError::Motion(MotionError::SolveNotConverged { sweeps, .. }))
                            if sweeps == limit
                    ),
                    "N = {n}: {refused:?}"
                );
                cases += 1;
            }
        }
        assert_eq!(cases, 6);
    }

    /// Solves cut short by a sweep limit still keep momentum: each pair impulse acts on
    /// both bodies, equal and opposite. Boxes thrown together in free space, turning (no
    /// forques, no planes), collide for a second with every solve limited to one sweep and
    /// to five, and unlimited: total momentum and angular momentum stay to 1e-12 of their
    /// scale, and the limited solves are counted unconverged.
    #[test]
    fn a_sweep_limit_keeps_momentum_in_collisions() {
        let mut cases = 0;
        for n in [3usize, 4] {
            for limit in [Some(1), Some(5), None] {
                let parsed =
                    parse_body(&format!("cuboid:{}+mass=1", vec!["0.5"; n].join(","))).unwrap();
                let bodies = (0..4)
                    .map(|k| {
                        let mut x = axis(n, 0, 1.2 * k as f64);
                        x.as_mut_slice()[1] = 0.1 * (k as f64 - 1.5);
                        let v = axis(n, 0, 1.5 - k as f64);
                        let w: Vec<f64> = (0..n * (n - 1) / 2)
                            .map(|p| 0.5 * (0.9 * (p + 2 * k) as f64 + 0.4).sin())
                            .collect();
                        MovingBody::from_parsed(
                            &parsed,
                            Rotor::identity(n),
                            &x,
                            &v,
                            &Bivector::from_components(n, &w).unwrap(),
                        )
                        .unwrap()
                        .with_friction(0.5)
                        .unwrap()
                    })
                    .collect();
                let mut system = System::new(bodies).unwrap();
                let (p0, l0) = (system.linear_momentum(), system.angular_momentum());
                let scale = system
                    .bodies()
                    .iter()
                    .map(|b| b.linear_momentum().norm() * (1.0 + b.position().norm()))
                    .sum::<f64>();
                let mut stepper = match limit {
                    Some(k) => MotionSplitting::new().with_sweep_limit(k).unwrap(),
                    None => MotionSplitting::new(),
                };
                for k in 0..60 {
                    stepper
                        .step(&mut system, k as f64 / 60.0, 1.0 / 60.0)
                        .unwrap();
                }
                let report = stepper.solver_report();
                let dp = (&system.linear_momentum() - &p0).max_abs();
                let dl = (&system.angular_momentum() - &l0).max_abs();
                println!("N = {n}, limit {limit:?}: {report:?}, Δp {dp:.1e}, ΔL {dl:.1e}");
                if limit.is_some() {
                    assert!(report.unconverged > 0, "N = {n}: {report:?}");
                }
                assert!(report.solves > 0, "N = {n}: the boxes touched");
                assert!(dp <= 1e-12 * scale && dl <= 1e-12 * scale, "N = {n}");
                cases += 1;
            }
        }
        assert_eq!(cases, 6);
    }

    /// The conjugate-gradient steps of a coupled solve reach the answer of Gauss–Seidel
    /// alone in a fraction of its sweeps: a pyramid started with no impulses to warm it
    /// (the solve's hardest case: Gauss–Seidel carries the weight down one layer a sweep)
    /// takes one step of h = 1/60 s by both, and both leave every body at rest to their
    /// tolerance.
    #[test]
    fn conjugate_gradient_steps_solve_a_cold_pyramid_in_fewer_sweeps() {
        for (n, layers) in [(3usize, 6usize), (4, 4)] {
            let mut sweeps = [0usize; 2];
            let mut speeds = [0.0f64; 2];
            for (plain, (sweeps, speed)) in sweeps.iter_mut().zip(&mut speeds).enumerate() {
                let mut system = pyramid(n, layers);
                let mut stepper = MotionSplitting::new();
                stepper.solver.plain_gauss_seidel = plain == 1;
                stepper.step(&mut system, 0.0, 1.0 / 60.0).unwrap();
                let report = stepper.solver_report();
                assert!(report.converged(), "N = {n}: {report:?}");
                *sweeps = report.max_sweeps;
                *speed = system
                    .bodies()
                    .iter()
                    .map(|b| b.velocity().max_abs())
                    .fold(0.0, f64::max);
            }
            println!("N = {n}, {layers} layers: sweeps {sweeps:?}, fastest body {speeds:?}");
            assert!(3 * sweeps[0] <= sweeps[1], "N = {n}: sweeps {sweeps:?}");
            assert!(
                speeds[0] <= 1e-8 && speeds[1] <= 1e-8,
                "N = {n}: {speeds:?}"
            );
        }
    }
}
