//! Impulses that keep joints together and bodies out of half-spaces: the velocity-level
//! solve (Signorini's condition with restitution and Coulomb's friction cone at each
//! contact, the ball joints' relative velocity) and the position-level solve of the joints.
//!
//! Each contact or joint acts on body points through impulses J; the point's velocity
//! answers linearly, Δu = K J, with the contact's effective inverse mass
//! K = (1/m) 1 + (r ⌋ I_s⁻¹ (r ∧ ·)) (for a joint between two bodies the sum of both). The
//! solve is projected Gauss–Seidel over the contacts and joints, each solved exactly as a
//! block: the normal impulse is the smallest λ ≥ 0 that stops the approach (or reverses it
//! by e for an impact), and the friction impulse is the one of maximal dissipation in the
//! disc |J_t| ≤ μ λ — the sticking impulse when it fits, else the one on the rim whose
//! remaining slip is exactly opposite to it (a trust-region problem in the (N−1)-dimensional
//! tangent space, solved by Newton's method on its multiplier, Moré–Sorensen). Where bodies
//! are coupled (joints, contacts between bodies), a conjugate-gradient step follows each
//! sweep from the second on ([`Solver::accelerate`]).

use crate::algebra::Vector;
use crate::dynamics::motion::body::contact_material;
use crate::dynamics::motion::contact::ContactLog;
use crate::dynamics::motion::detect::bodies::PairContact;
use crate::dynamics::motion::placement::{Placements, dot, set_vector};
use crate::dynamics::motion::{ContactShape, HalfSpace, MovingBody};
use body::{BodyState, LocalBody, add_inverse_mass};
use contact_row::{
    Linear, RowKey, RowLayout, Small, dim, point_velocity, row_matrices, scratch, sweep_contact,
};
use smallvec::SmallVec;

/// Up to N = 8 the matrices live on the stack.
type Dense = SmallVec<[f64; 64]>;

/// Gauss–Seidel sweeps of the velocity solve, at most, unless the integrator sets its own
/// limit ([`Solver::sweep_limit`]).
pub(crate) const MAX_SWEEPS: usize = 20_000;

/// Sweeps after which a solve whose largest change has not fallen by 1 % stops, unconverged:
/// its rows cycle (Gauss–Seidel with friction; measured on a tilted box landing on a slab,
/// whose change stays at the same value from the 100th sweep to the 20,000th).
pub(crate) const STALLED_SWEEPS: usize = 500;

/// Sweeps without a 1 % fall of the largest change after which a solve looks for a cycle:
/// sweeps that leave the velocities of its bodies where they were.
const CYCLE_AFTER: usize = 20;

/// A cycle: this many sweeps in a row that move no velocity of the solve's bodies by more
/// than [`CYCLE_NET`] of its tolerance (an angular velocity times the longest lever arm of
/// its rows), while their updates still change velocities by more than the tolerance.
/// Gauss–Seidel with friction meets them on faces: the sweeps hand impulses round a face's
/// points (along a direction of its normal impulses that moves no body, friction at the rim
/// of its cone), and in the pile of 100 bodies of the Rapier comparison their velocities
/// stay to within 1e-15 of the contacts' speed for hundreds of sweeps while each update moves
/// them by 1e-8 to 1e-6 of it: more sweeps would change only the impulses' share among the
/// points. The solve stops there, unconverged, with the residual it would have after
/// [`STALLED_SWEEPS`].
const CYCLE_SWEEPS: usize = 3;
const CYCLE_NET: f64 = 1e-3;

/// Where the sweeps of a solve with contacts between bodies stop: a change of every
/// velocity below this fraction of the contacts' speed.
const PAIR_TOLERANCE: f64 = 1e-9;

mod body;
mod contact_row;
mod friction;
mod joint_row;
mod pair_row;
mod soft;

use crate::numeric::cholesky_solve;
pub(crate) use contact_row::ContactRow;
pub(crate) use joint_row::JointRow;
pub(crate) use pair_row::{MassAt, PairRow};
pub(crate) use soft::{FoundPoint, NO_BODY, SoftSolver, Softness};

/// How far beyond its touching distance a body of sweep `sweep` (how far its points may move
/// in the flight) reaches against `plane`: its sweep against a plane of restitution 0, where
/// an impact is held by a speculative contact, or against every plane with `every_plane`;
/// else none (an impact there is located, as restitution acts on its speed).
pub(crate) fn plane_sweep(plane: &HalfSpace, sweep: f64, every_plane: bool) -> f64 {
    if every_plane || plane.restitution() == 0.0 {
        sweep
    } else {
        0.0
    }
}

/// The rows of one face at the start of `rows` (those whose `key` is the first row's: the
/// points of one body on one half-space, or of one pair of bodies) and whether the face is
/// *mixed*: some of its points touch and some are speculative (`speculative`).
///
/// A rigid body's normal speeds at its points are affine in the points' positions, and so
/// are the gaps of a flat face. Targets that close each point's own gap within the flight
/// are therefore met together by one motion of the bodies; touching points held at 0 beside
/// speculative points aimed at their gaps (or past them) are not, where the touching points
/// stand above the plane by a fraction of the touching distance (a body tilted by less than
/// that over its face, common in piles). The solve then has no solution with every point
/// pressing, and Gauss–Seidel with friction hands impulse around the face, changing the
/// velocities by the same amount sweep after sweep, until the stall rule stops it
/// unconverged. On a mixed face every point that is not an impact therefore aims at its own
/// gap: −gap / flight.
/// How many rows at the start of `rows` share the first one's `key` (a body's rows, a
/// pair's).
pub(crate) fn run_len<T, K: PartialEq>(rows: &[T], key: impl Fn(&T) -> K) -> usize {
    let Some(first) = rows.first() else {
        return 0;
    };
    let run = key(first);
    rows.iter().take_while(|r| key(r) == run).count()
}

fn face_run<T, K: PartialEq>(
    rows: &[T],
    key: impl Fn(&T) -> K,
    speculative: impl Fn(&T) -> bool,
) -> (usize, bool) {
    let Some(first) = rows.first() else {
        return (0, false);
    };
    let face = key(first);
    let (mut len, mut some_touch, mut some_speculative) = (0, false, false);
    for row in rows.iter().take_while(|r| key(r) == face) {
        len += 1;
        if speculative(row) {
            some_speculative = true;
        } else {
            some_touch = true;
        }
    }
    (len, some_touch && some_speculative)
}

/// The reusable work space of the solves.
#[derive(Clone, Debug, Default)]
pub(crate) struct Solver {
    pub contacts: Vec<ContactRow>,
    /// Contacts between two bodies.
    pub pairs: Vec<PairRow>,
    /// The rows of the solve before, kept for their room.
    spare_pairs: Vec<PairRow>,
    /// Which of the last solve's pair rows gave their impulses to a new row, and each new
    /// row's source among them.
    taken: Vec<bool>,
    sources: Vec<Option<usize>>,
    /// The serial number of the list of found pairs the pair rows were made from (see
    /// [`Touching::found_serial`](crate::dynamics::motion::detect::bodies::Touching)), and
    /// whether the rows were kept from the solve before (the same points at the same
    /// placement: their K stands).
    pairs_found: Option<u64>,
    pairs_kept: bool,
    /// The bodies' attitudes as the pair rows' K last saw them (see [`AttitudeAnchors`]).
    anchors: AttitudeAnchors,
    pub joints: Vec<JointRow>,
    states: Vec<BodyState>,
    work: Dense,
    rhs: Dense,
    big: Vec<f64>,
    big_rhs: Vec<f64>,
    /// Each joint end's contraction and inverse-inertia matrices (for K).
    end_c: Vec<f64>,
    end_w: Vec<f64>,
    /// The contact rows' matrices ([`RowLayout`]), slot k for row k, and what they were
    /// computed for: a row that touches again at the same placement keeps them.
    row_data: Vec<f64>,
    row_keys: Vec<RowKey>,
    /// The last generation handed to a body's inverse inertia.
    generations: u64,
    /// True while `big` holds the Cholesky factor of the joints' K at the bodies' current
    /// attitudes (the rows' offsets): a velocity solve of joints alone leaves it there, and
    /// the position solve of the same placement reuses it.
    joint_factor: bool,
    pub residuals: Vec<Vector>,
    /// The last solve's impulses of the rows that left their slots, by (body, half-space,
    /// candidate), to start the next solve from (a row that stays in its slot keeps its
    /// own): a resting contact then needs one sweep. Filled by `find_contacts` from the
    /// first slot whose point changes, before it is overwritten.
    warm: Vec<WarmImpulse>,
    /// The length of the kick before the last solve (0: none yet). A resting contact's
    /// impulse is its force times that length, so the next solve starts from the last
    /// impulses scaled by the ratio of the kicks.
    warm_kick: f64,
    /// True to use the kernels of run-time dimension in every dimension, also in 3D and 4D
    /// where the fixed-size kernels do the same arithmetic in the same order, only without
    /// the terms that are exact zeros (so that tests can compare the two).
    pub runtime_kernels: bool,
    /// What the solves met: sweeps, unconverged solves, singular joint systems.
    pub report: SolverReport,
    /// True to solve by Gauss–Seidel sweeps alone, without [`Solver::accelerate`]'s steps
    /// (so that tests can compare the two).
    pub plain_gauss_seidel: bool,
    /// The conjugate-gradient steps of a coupled solve ([`Solver::accelerate`]): for each
    /// row (joints, pairs, contact rows) its impulse before the sweep, then its change over
    /// the sweep, and its direction p, n numbers each.
    momentum: Vec<f64>,
    /// The most sweeps a solve takes (None: [`MAX_SWEEPS`]).
    pub sweep_limit: Option<usize>,
    /// True to stop a solve that does not converge only after [`STALLED_SWEEPS`] sweeps
    /// without progress, never on a cycle (so that tests can compare the two).
    pub stall_only: bool,
    /// The bodies of a solve that looks for a cycle, and their velocities (v, then ω) at
    /// the start of the sweep it checks ([`Solver::cycle_moved`]).
    cycle_bodies: Vec<usize>,
    cycle_velocities: Vec<f64>,
}

/// For the bodies of the found pairs: each one's attitude (the numbers of its principal
/// frame's rotor or matrix) as it was when it last moved by more than
/// [`pair_row::KEEP_MASS`] in any of them, with its mass, whether it is fixed and its
/// inverse plane moments, and a generation that changes with any of them: a pair row whose
/// K was computed at the generations its bodies still have was computed for the same
/// bodies at attitudes within twice that of theirs now. And whether each body's inverse
/// inertia is the same in every frame (a ball's, a cube's): its part of K does not depend
/// on its attitude. A body whose inertia is not diagonal in its principal frame takes a
/// new generation at every step.
#[derive(Clone, Debug, Default)]
struct AttitudeAnchors {
    /// Per body: the attitude's numbers, then mass, fixed (0 or 1) and the inverse plane
    /// moments (`stride` in all).
    numbers: Vec<f64>,
    stride: usize,
    generation: Vec<u64>,
    /// A generation that changes with the mass, fixedness and moments alone.
    inertia_generation: Vec<u64>,
    isotropic: Vec<bool>,
    /// The serial of the last update that looked at each body.
    seen: Vec<u64>,
    serial: u64,
    last: u64,
}

impl AttitudeAnchors {
    /// Moves the anchor of each body of the `found` pairs that changed past the limits
    /// (all of them when the bodies changed in count or dimension).
    fn update(&mut self, bodies: &[MovingBody], found: &[PairContact]) {
        let Some(first) = found.first().map(|c| &bodies[c.a]) else {
            return;
        };
        let n = first.dim();
        let stride =
            first.rotation().principal_frame_attitude().entries().len() + 2 + n * (n - 1) / 2;
        if self.stride != stride || self.generation.len() != bodies.len() {
            self.stride = stride;
            self.numbers.clear();
            self.numbers.resize(bodies.len() * stride, f64::NAN);
            self.generation.clear();
            self.generation.resize(bodies.len(), 0);
            self.inertia_generation.clone_from(&self.generation);
            self.isotropic.clear();
            self.isotropic.resize(bodies.len(), false);
            self.seen.clear();
            self.seen.resize(bodies.len(), 0);
        }
        self.serial += 1;
        for c in found {
            for i in [c.a, c.b] {
                if self.seen[i] != self.serial {
                    self.seen[i] = self.serial;
                    self.update_body(i, &bodies[i]);
                }
            }
        }
    }

    fn update_body(&mut self, i: usize, b: &MovingBody) {
        let stride = self.stride;
        let attitude = b.rotation().principal_frame_attitude().entries();
        let moments = b.rotation().inertia().diagonal_inverse_plane_moments();
        let anchor = &mut self.numbers[i * stride..(i + 1) * stride];
        let (turn, rest) = anchor.split_at_mut(stride.min(attitude.len()));
        // Compared so that a NaN (a new anchor) counts as changed.
        let same_inertia = moments.is_some_and(|m| attitude.len() + 2 + m.len() == stride)
            && rest[0] == b.mass()
            && rest[1] == f64::from(u8::from(b.is_fixed()))
            && moments.is_some_and(|m| rest[2..] == *m);
        let turned = !attitude
            .iter()
            .zip(turn.iter())
            .all(|(x, y)| (x - y).abs() <= pair_row::KEEP_MASS);
        if same_inertia && !turned {
            return;
        }
        self.last += 1;
        self.generation[i] = self.last;
        if !same_inertia {
            self.inertia_generation[i] = self.last;
        }
        self.isotropic[i] = moments.is_some_and(|m| m.iter().all(|x| *x == m[0]));
        if let Some(m) = moments.filter(|m| attitude.len() + 2 + m.len() == stride) {
            turn.copy_from_slice(attitude);
            rest[0] = b.mass();
            rest[1] = f64::from(u8::from(b.is_fixed()));
            rest[2..].copy_from_slice(m);
        }
    }
}

/// A coupled solve keeps its impulses for the conjugate-gradient steps from this sweep on
/// (the first step, after it, sets the direction; the next moves along it): a solve that
/// converges within this many sweeps (a warm-started resting contact takes one) is plain
/// Gauss–Seidel.
const ACCELERATE_FROM: usize = 2;

/// Why a contact solve's sweeps stopped before its tolerance.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Stop {
    AtLimit,
    Stalled,
    Cycled,
}

/// What the velocity and joint solves of an integrator met since it was made (or since
/// [`MotionSplitting::reset_solver_report`](crate::dynamics::motion::MotionSplitting::reset_solver_report)).
///
/// The projected Gauss–Seidel solve of the contacts stops unconverged at its sweep limit
/// ([`MotionSplitting::with_sweep_limit`](crate::dynamics::motion::MotionSplitting::with_sweep_limit)),
/// when its largest change has not fallen by 1 % in 500 sweeps, or when its sweeps cycle
/// (they leave the bodies' velocities where they were), and a joint system whose matrix
/// cannot be factored is skipped; both go on with the best impulses they have, which is
/// what a simulation wants mid-run, and both are counted here so that they are seen.
/// [`MotionSplitting::strict`](crate::dynamics::motion::MotionSplitting::strict) turns
/// them into errors instead.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SolverReport {
    /// Contact solves (each group of contact rows solved together counts once).
    pub solves: u64,
    /// Those that stopped before converging: at the sweep limit, without progress, or on
    /// a cycle (`at_sweep_limit + stalled + cycled`).
    pub unconverged: u64,
    /// Of the unconverged solves, those stopped at the sweep limit
    /// ([`MotionSplitting::with_sweep_limit`](crate::dynamics::motion::MotionSplitting::with_sweep_limit)).
    pub at_sweep_limit: u64,
    /// Of the unconverged solves, those whose largest change had not fallen by 1 % in 500
    /// sweeps.
    pub stalled: u64,
    /// Of the unconverged solves, those stopped on a cycle: three sweeps in a row that left
    /// the velocities of their bodies where they were (to 10⁻³ of the tolerance) while each
    /// update still moved them, the sweeps handing impulses round a face's points. The
    /// velocities are then those that more sweeps would leave; what is unsettled is how the
    /// face's impulse is shared among its points.
    pub cycled: u64,
    /// The most sweeps one solve took.
    pub max_sweeps: usize,
    /// The sweeps of all solves (over `solves`: the mean work of a solve).
    pub sweeps: u64,
    /// The largest velocity change of the last sweep of an unconverged solve, relative to
    /// the speed of its contacts (0 while every solve converged).
    pub worst_residual: f64,
    /// Joint solves skipped because the joints' matrix was singular (a joint whose two ends
    /// cannot move apart, or joints that hold the same freedom twice).
    pub singular_joint_solves: u64,
}

impl SolverReport {
    /// True if every solve converged and no joint system was singular.
    pub fn converged(&self) -> bool {
        self.unconverged == 0 && self.singular_joint_solves == 0
    }
}

/// Contact rows solved together, and what their solve reads.
struct Group<'a> {
    range: std::ops::Range<usize>,
    /// True if joints couple the rows (then every joint is swept with them).
    coupled: bool,
    half_spaces: &'a [HalfSpace],
    layout: &'a RowLayout,
    /// The factor on the last solve's impulses to start from.
    warm_scale: f64,
    /// The length of the flight the solve's velocities start.
    flight: f64,
}

/// The impulses of the last solve with the place to search them from.
type WarmList<'a> = (&'a [WarmImpulse], &'a mut usize);

/// A contact's impulses kept for the next solve: body, half-space, candidate, normal
/// impulse, friction impulse.
type WarmImpulse = (usize, usize, usize, f64, Linear);

impl Solver {
    /// Finds the contact points of `bodies` within `tolerance` × their radius of a
    /// half-space, plus the body's sweep in `sweeps` where it has one (how far it may move
    /// in the step; against a half-space of restitution 0 only, unless `sweep_bouncing`),
    /// the bodies placed by `placements`. Points farther than the tolerance are
    /// speculative: the solve lets them approach by their gap within the flight.
    pub(crate) fn find_contacts(
        &mut self,
        bodies: &[MovingBody],
        shapes: &[ContactShape],
        half_spaces: &[HalfSpace],
        (tolerance, sweeps, sweep_bouncing): (f64, &[f64], bool),
        placements: &Placements,
    ) {
        // Rows are overwritten in place (a row is large: moving it costs more than its setup).
        let mut used = 0;
        let n = bodies[0].dim();
        self.warm.clear();
        let mut listed = false;
        for (i, (b, shape)) in bodies.iter().zip(shapes).enumerate() {
            if matches!(shape, ContactShape::None) || half_spaces.is_empty() || b.is_fixed() {
                continue;
            }
            let placed = placements.get(i);
            let touching = tolerance * placed.radius;
            let sweep = sweeps.get(i).copied().unwrap_or(0.0);
            for (k, plane) in half_spaces.iter().enumerate() {
                let nrm = plane.normal();
                let base = plane.distance(b.position());
                let reach = touching + plane_sweep(plane, sweep, sweep_bouncing);
                let mut put = |index: usize, p: &Vector, r: &[f64], gap: f64| {
                    // The target is set when the solve starts, from the loaded velocities.
                    let target = 0.0;
                    let stays = self.contacts.get(used).is_some_and(|row| {
                        row.body == i && row.half_space == k && row.index == index
                    });
                    if !stays && !listed {
                        // The points change from this slot on: the rows from here keep their
                        // impulses in the list (in the order of their points) before they are
                        // overwritten.
                        self.warm.extend(self.contacts[used..].iter().map(|row| {
                            (
                                row.body,
                                row.half_space,
                                row.index,
                                row.normal_impulse,
                                row.friction_impulse.clone(),
                            )
                        }));
                        listed = true;
                    }
                    if let Some(row) = self.contacts.get_mut(used) {
                        // The same point in the same slot keeps its impulses of the last
                        // solve, to start from.
                        row.warm = row.body == i && row.half_space == k && row.index == index;
                        if !row.warm {
                            row.normal_impulse = 0.0;
                            row.friction_impulse.as_mut_slice().fill(0.0);
                        }
                        row.body = i;
                        row.half_space = k;
                        row.index = index;
                        // The same point of the same placement is there already.
                        if !(row.warm && row.placed == placed.generation) {
                            row.point.clear();
                            row.point.extend_from_slice(p.as_slice());
                            row.r.clear();
                            row.r.extend_from_slice(r);
                            row.placed = placed.generation;
                        }
                        row.target = target;
                        (row.gap, row.reach) = (gap, touching);
                        row.position_impulse = 0.0;
                        row.knn = 0.0;
                        row.speed = 0.0;
                    } else {
                        self.contacts.push(ContactRow {
                            body: i,
                            half_space: k,
                            index,
                            point: Linear::from_slice(p.as_slice()),
                            r: Linear::from_slice(r),
                            gap,
                            reach: touching,
                            target,
                            normal_impulse: 0.0,
                            friction_impulse: Linear::from_elem(0.0, n),
                            position_impulse: 0.0,
                            knn: 0.0,
                            speed: 0.0,
                            warm: false,
                            placed: placed.generation,
                        });
                    }
                    used += 1;
                };
                if placed.vertex(shape, 1).is_some() {
                    // Vertices: their heights are kept, and only those in reach are read.
                    placed.candidate_heights(shape, (k, nrm), |index, h| {
                        if base + h <= reach
                            && let Some((p, r)) = placed.vertex(shape, index)
                        {
                            put(index, p, r, base + h);
                        }
                    });
                } else {
                    placed.candidates(shape, (k, nrm), |index, p, r| {
                        let gap = base + dot(nrm.as_slice(), r);
                        if gap <= reach {
                            put(index, p, r, gap);
                        }
                    });
                }
            }
        }
        self.contacts.truncate(used);
    }

    /// Loads the bodies the rows act on.
    fn load(&mut self, bodies: &[MovingBody]) {
        let n = bodies[0].dim();
        self.states
            .resize_with(bodies.len(), || BodyState::empty(n));
        let mut work = std::mem::take(&mut self.work);
        let touched = self
            .contacts
            .iter()
            .map(|c| c.body)
            .chain(
                self.joints
                    .iter()
                    .flat_map(|j| std::iter::once(j.body).chain(j.other.iter().map(|(b, _)| *b))),
            )
            .chain(self.pairs.iter().flat_map(|p| [p.a, p.b]));
        let mut placed = false;
        let mut last = usize::MAX;
        for i in touched {
            // A body's contact rows are consecutive: it is looked at once for them.
            if i == last {
                continue;
            }
            last = i;
            if !self.states[i].used && self.states[i].load(&bodies[i], &mut work) {
                placed = true;
                self.generations += 1;
                self.states[i].generation = self.generations;
            }
        }
        self.work = work;
        if placed {
            // A body turned: the joints' K is another.
            self.joint_factor = false;
        }
    }

    /// Hands the impulses of the solve to the bodies.
    fn store(&mut self, bodies: &mut [MovingBody]) {
        for (s, b) in self.states.iter_mut().zip(bodies) {
            if s.used {
                s.store(b);
            }
        }
    }

    /// The velocity solve: impulses such that every joint's ends move together and every
    /// contact point leaves its half-space at its target speed or faster, with friction in
    /// Coulomb's cone. Appends the contacts and their impulses to `record` (if any).
    ///
    /// A contact's target is restitution e for a point approaching faster than
    /// `resting_speed[i]` (body i), none below (a resting contact), and for a speculative
    /// point the approach that closes its gap within the flight of length `flight` that
    /// the velocities start. `kick` is the length of the kick of the forques before the
    /// solve. Speculative points are not recorded.
    pub(crate) fn solve_velocities(
        &mut self,
        bodies: &mut [MovingBody],
        half_spaces: &[HalfSpace],
        resting_speed: &[f64],
        (kick, flight): (f64, f64),
        mut record: Option<&mut ContactLog>,
    ) {
        if self.contacts.is_empty() && self.joints.is_empty() && self.pairs.is_empty() {
            return;
        }
        let warm_scale = if self.warm_kick > 0.0 && kick > 0.0 {
            kick / self.warm_kick
        } else {
            1.0
        };
        self.warm_kick = kick;
        self.load(bodies);
        let n = bodies[0].dim();
        if self.contacts.is_empty() && self.pairs.is_empty() {
            // Equalities only: one dense solve is exact.
            let mut u = std::mem::take(&mut self.residuals);
            u.clear();
            u.extend(self.joints.iter().map(|row| row.velocity(&self.states)));
            self.solve_joints_dense_loaded(&u, 1.0);
            self.residuals = u;
            self.store(bodies);
            return;
        }
        for row in &mut self.joints {
            row.k.clear();
            row.k.resize(n * n, 0.0);
            add_inverse_mass(&self.states[row.body], &row.r, &mut row.k);
            if let Some((j, q)) = &row.other {
                add_inverse_mass(&self.states[*j], q, &mut row.k);
            }
        }
        let layout = RowLayout::new(n);
        let rows = self.contacts.len();
        if self.row_data.len() < rows * layout.stride {
            self.row_data.resize(rows * layout.stride, 0.0);
        }
        if self.row_keys.len() < rows {
            self.row_keys.resize_with(rows, RowKey::default);
        }
        // Bodies that no joint or contact couples are solved apart (their contacts are
        // consecutive), each from setup to record while its rows' matrices are in cache; with
        // joints or contacts between bodies, everything is one problem.
        let coupled = !self.joints.is_empty() || !self.pairs.is_empty();
        // Every row's target is set from the velocities before any warm start: a target
        // read after other rows' starting impulses (an impact's −e u⁻ above all) would
        // return their impulses as energy.
        let (mut face_end, mut mixed) = (0, false);
        for k in 0..self.pairs.len() {
            if k == face_end {
                (face_end, mixed) = face_run(&self.pairs[k..], |r| (r.a, r.b), |r| r.gap > r.reach);
                face_end += k;
            }
            let pair = &mut self.pairs[k];
            let resting = resting_speed[pair.a].max(resting_speed[pair.b]);
            if !self.pairs_kept && !pair.mass_ready {
                pair.prepare_mass(&self.states);
            }
            pair.prepare_target(&self.states, resting, flight, mixed);
            pair.normal_impulse *= warm_scale;
            pair.friction_impulse *= warm_scale;
        }
        if rows == 0 {
            self.warm_start_pairs();
            self.sweep_rows::<0>(0..0, true, half_spaces, &layout);
        }
        let last = std::mem::take(&mut self.warm);
        let mut cursor = 0;
        let mut start = 0;
        while start < rows {
            let end = if coupled {
                rows
            } else {
                start + run_len(&self.contacts[start..], |r| r.body)
            };
            let group = Group {
                range: start..end,
                coupled,
                half_spaces,
                layout: &layout,
                warm_scale,
                flight,
            };
            let warm = (&last[..], &mut cursor);
            match (self.runtime_kernels, n) {
                (false, 3) => {
                    self.solve_group::<3>(&group, resting_speed, warm, record.as_deref_mut())
                }
                (false, 4) => {
                    self.solve_group::<4>(&group, resting_speed, warm, record.as_deref_mut())
                }
                _ => self.solve_group::<0>(&group, resting_speed, warm, record.as_deref_mut()),
            }
            start = end;
        }
        if let Some(log) = record {
            for pair in self.pairs.iter().filter(|p| p.gap <= p.reach) {
                let mut point = pair.ra.clone();
                point += bodies[pair.a].position();
                log.record_pair(
                    (pair.a, pair.b),
                    &point,
                    &pair.normal,
                    pair.normal_impulse,
                    &pair.friction_impulse,
                );
            }
        }
        // Kept for its room: the next `find_contacts` clears it.
        self.warm = last;
        self.store(bodies);
    }

    /// The velocity solve of one group of contact rows (`N` as in [`dim`]): their matrices,
    /// warm start from their own impulses or from `last` (searched from `cursor` on), sweeps
    /// and the record if there is one.
    fn solve_group<const N: usize>(
        &mut self,
        group: &Group<'_>,
        resting_speed: &[f64],
        (last, cursor): WarmList<'_>,
        record: Option<&mut ContactLog>,
    ) {
        // The layout anew, so that in 3D and 4D its offsets are constants of the kernels.
        let layout = &RowLayout::new(dim::<N>(group.layout.n));
        let (range, half_spaces) = (group.range.clone(), group.half_spaces);
        self.prepare_rows::<N>(
            range.clone(),
            half_spaces,
            (resting_speed, group.flight),
            layout,
        );
        if group.coupled {
            // All rows are one group: the contact rows' targets are set, the pairs' were.
            self.warm_start_pairs();
        }
        self.warm_start::<N>(
            range.clone(),
            (last, cursor),
            half_spaces,
            layout,
            (group.coupled, group.warm_scale),
        );
        self.sweep_rows::<N>(range.clone(), group.coupled, half_spaces, layout);
        if let Some(record) = record {
            self.record_rows::<N>(range, half_spaces, layout, record);
        }
    }

    /// Gives the pairs' starting impulses (set by [`PairRow::prepare`]'s caller) to the
    /// loaded states.
    fn warm_start_pairs(&mut self) {
        for pair in &self.pairs {
            pair.apply_accumulated(&mut self.states);
        }
    }

    /// Computes (or keeps) the matrices of the contact rows `range` at the loaded states,
    /// and sets their nᵀ K n, target and speed.
    fn prepare_rows<const N: usize>(
        &mut self,
        range: std::ops::Range<usize>,
        half_spaces: &[HalfSpace],
        (resting_speed, flight): (&[f64], f64),
        layout: &RowLayout,
    ) {
        let n = dim::<N>(layout.n);
        let m = n * (n - 1) / 2;
        let (mut u_fixed, mut u_any) = ([0.0; 4], Small::new());
        let u = scratch::<N>(&mut u_fixed, &mut u_any, n);
        // The velocities of the last row's body (the rows of a body are consecutive).
        let (mut body, mut v, mut w): (usize, &[f64], &[f64]) = (usize::MAX, &[], &[]);
        let (mut face_end, mut mixed) = (range.start, false);
        let end = range.end;
        for k in range {
            if k == face_end {
                (face_end, mixed) = face_run(
                    &self.contacts[k..end],
                    |r| (r.body, r.half_space),
                    |r| r.gap > r.reach,
                );
                face_end += k;
            }
            let row = &mut self.contacts[k];
            let plane = &half_spaces[row.half_space];
            let nrm = plane.normal();
            let st = &self.states[row.body];
            if row.body != body {
                (body, v, w) = (row.body, &st.v.as_slice()[..n], &st.w.as_slice()[..m]);
            }
            let data = &mut self.row_data[k * layout.stride..(k + 1) * layout.stride];
            let key = &mut self.row_keys[k];
            let (r, nv) = (&row.r.as_slice()[..n], &nrm.as_slice()[..n]);
            if !key.is(st.generation, r, nv) {
                row_matrices(st, &row.r, nrm, layout, data);
                key.set(st.generation, r, nv);
            }
            row.knn = data[layout.knn];
            point_velocity::<N>(layout, r, v, w, u);
            let un = dot(nv, u);
            row.target = if row.gap > row.reach {
                // Aimed past the plane by the bend of the point's path over the flight
                // (½ h² |ω|² |r|) and, unless the body touches the plane elsewhere, by the
                // touching distance, so that the flight ends touching or inside, where the
                // position step puts the point on the plane: aimed at the plane itself, a
                // turning body would stop short of it and hover. On a mixed face (see
                // `face_run`) every point aims at its own gap, or the targets would ask
                // for a motion no rigid body has.
                let bend = 0.5 * flight * flight * dot(w, w) * dot(r, r).sqrt();
                let past = if mixed { 0.0 } else { row.reach };
                -(row.gap + past + bend) / flight
            } else if un < -resting_speed[row.body] {
                -plane.restitution() * un
            } else if mixed {
                -row.gap / flight
            } else {
                0.0
            };
            row.speed = u
                .iter()
                .fold(0.0, |m: f64, c| m.max(c.abs()))
                .max(row.target.abs());
        }
    }

    /// Starts the contact rows `range` from the last solve's impulses times `scale` where
    /// the same points touch again: kept in the row when it is in the same slot, else looked
    /// up in `last` (sorted by point, searched from `cursor` on).
    fn warm_start<const N: usize>(
        &mut self,
        range: std::ops::Range<usize>,
        (last, cursor): (&[WarmImpulse], &mut usize),
        half_spaces: &[HalfSpace],
        layout: &RowLayout,
        (coupled, scale): (bool, f64),
    ) {
        let n = dim::<N>(layout.n);
        let (mut jt_fixed, mut jt_any) = ([0.0; 4], Small::new());
        let jt = scratch::<N>(&mut jt_fixed, &mut jt_any, n);
        let (mut total_fixed, mut total_any) = ([0.0; 4], Small::new());
        let total = scratch::<N>(&mut total_fixed, &mut total_any, n);
        // One body in 3D or 4D: the rows' starting impulses are set first, and then applied
        // in the same order to the body's velocities and impulses in locals (the rows that
        // start, one bit each).
        let apart = !coupled && N != 0 && range.len() <= 64;
        let mut started = 0u64;
        for k in range.clone() {
            let row = &mut self.contacts[k];
            let lambda = if row.warm {
                jt.copy_from_slice(&row.friction_impulse.as_slice()[..n]);
                row.normal_impulse
            } else {
                let key = (row.body, row.half_space, row.index);
                let w = &mut *cursor;
                while *w < last.len() && (last[*w].0, last[*w].1, last[*w].2) < key {
                    *w += 1;
                }
                match last.get(*w).filter(|e| (e.0, e.1, e.2) == key) {
                    Some(e) => {
                        jt.copy_from_slice(&e.4.as_slice()[..n]);
                        e.3
                    }
                    None => continue,
                }
            };
            let plane = &half_spaces[row.half_space];
            let nv = &plane.normal().as_slice()[..n];
            // Scaled to this solve's kick, into the friction disc of the normal impulse, and
            // into the plane.
            let lambda = lambda * scale;
            let limit = plane.friction() * lambda;
            let norm = dot(jt, jt).sqrt() * scale;
            let fit = if norm > limit { limit / norm } else { 1.0 };
            for x in jt.iter_mut() {
                *x *= scale * fit;
            }
            let along = dot(nv, jt);
            for ((t, x), nx) in total.iter_mut().zip(jt.iter_mut()).zip(nv) {
                *x -= nx * along;
                *t = nx * lambda + *x;
            }
            row.normal_impulse = lambda;
            row.friction_impulse.as_mut_slice().copy_from_slice(jt);
            if apart {
                started |= 1 << (k - range.start);
                continue;
            }
            let data = &self.row_data[k * layout.stride..(k + 1) * layout.stride];
            self.states[row.body].view::<N>().apply_with::<N>(
                data,
                layout,
                &row.r.as_slice()[..n],
                total,
            );
        }
        if started == 0 {
            return;
        }
        let mut st = self.states[self.contacts[range.start].body].view::<N>();
        let mut local = LocalBody::new(&st);
        let mut view = local.view();
        for k in range.clone() {
            if started & (1 << (k - range.start)) == 0 {
                continue;
            }
            let row = &self.contacts[k];
            let nv = &half_spaces[row.half_space].normal().as_slice()[..n];
            let (lambda, jt) = (row.normal_impulse, &row.friction_impulse.as_slice()[..n]);
            for ((t, x), nx) in total.iter_mut().zip(jt).zip(nv) {
                *t = nx * lambda + *x;
            }
            let data = &self.row_data[k * layout.stride..(k + 1) * layout.stride];
            view.apply_with::<N>(data, layout, &row.r.as_slice()[..n], total);
        }
        local.store(&mut st);
    }

    /// Gauss–Seidel sweeps over the contact rows `range` (and every joint when `coupled`)
    /// until no impulse changes one of their velocities by more than 1e-12 of their speeds
    /// (1e-9 with pairs), or the largest change has not fallen by 1 % in [`STALLED_SWEEPS`]
    /// sweeps or the sweeps cycle ([`CYCLE_SWEEPS`]) or reach the sweep limit (unconverged,
    /// and reported).
    fn sweep_rows<const N: usize>(
        &mut self,
        range: std::ops::Range<usize>,
        coupled: bool,
        half_spaces: &[HalfSpace],
        layout: &RowLayout,
    ) {
        let n = layout.n;
        let (start, end) = (range.start, range.end);
        let speed = self.contacts[range]
            .iter()
            .map(|r| r.speed)
            .chain(self.pairs.iter().map(|p| p.speed.max(p.target.abs())))
            .fold(0.0, f64::max);
        // Several points of one face contact hold the same freedom more than once: Gauss–Seidel
        // then moves impulses among them that leave the velocities as they are, and the
        // change of each update falls only linearly there. With contacts between bodies the
        // sweeps stop at 1e-9 of the contacts' speed (over 10 s of a resting stack that is
        // under 1e-9 of the body's size), else at 1e-12.
        let relative = if self.pairs.is_empty() {
            1e-12
        } else {
            PAIR_TOLERANCE
        };
        let tolerance = relative * speed.max(1e-300);
        self.report.solves += 1;
        let mut sweeps = 0;
        let mut change = 0.0f64;
        // |Δ|² of the last accelerated sweep (none yet: the first one takes no step).
        let mut last = f64::INFINITY;
        // The least change so far, and the sweep that brought it 1 % below the one before.
        let (mut least, mut least_at) = (f64::INFINITY, 0);
        // The lever arm that turns the bodies' angular velocities into speeds of points
        // (set when a cycle is first looked for), and the sweeps in a row that left the
        // velocities where they were.
        let (mut lever, mut still) = (None, 0);
        let limit = self.sweep_limit.unwrap_or(MAX_SWEEPS);
        // Why the sweeps stopped, should the solve end unconverged.
        let mut stop = Stop::AtLimit;
        while sweeps < limit {
            sweeps += 1;
            change = 0.0;
            let check = !self.stall_only && sweeps > least_at + CYCLE_AFTER;
            if check && lever.is_none() {
                lever = Some(self.cycle_bodies_of(start..end, coupled));
            }
            if check {
                self.cycle_keep();
            } else {
                still = 0;
            }
            let accelerated = coupled && !self.plain_gauss_seidel && sweeps >= ACCELERATE_FROM;
            if accelerated {
                self.keep_impulses(start..end, half_spaces, n, sweeps == ACCELERATE_FROM);
            }
            if coupled {
                for row in &mut self.joints {
                    let u = row.velocity(&self.states);
                    self.work.clear();
                    self.work.extend_from_slice(&row.k);
                    self.rhs.clear();
                    self.rhs.extend(u.as_slice().iter().map(|x| -x));
                    if !cholesky_solve(&mut self.work, n, &mut self.rhs) {
                        self.report.singular_joint_solves += 1;
                        continue;
                    }
                    let dj = Vector::from_storage(self.rhs.iter().copied().collect());
                    row.apply(&mut self.states, &dj);
                    row.impulse += &dj;
                    change = change.max(u.max_abs());
                }
            }
            if coupled {
                for pair in &mut self.pairs {
                    change = change.max(pair.sweep(&mut self.states));
                }
                for (k, row) in self.contacts[start..end].iter_mut().enumerate() {
                    let at = (start + k) * layout.stride;
                    let data = &self.row_data[at..at + layout.stride];
                    let mut st = self.states[row.body].view::<N>();
                    let plane = &half_spaces[row.half_space];
                    change = change.max(sweep_contact::<N>(row, data, layout, plane, &mut st));
                }
            } else if N != 0 {
                // One body in 3D or 4D: its velocities and impulses in locals.
                let mut st = self.states[self.contacts[start].body].view::<N>();
                let mut local = LocalBody::new(&st);
                let mut view = local.view();
                for (k, row) in self.contacts[start..end].iter_mut().enumerate() {
                    let at = (start + k) * layout.stride;
                    let data = &self.row_data[at..at + layout.stride];
                    let plane = &half_spaces[row.half_space];
                    let c = sweep_contact::<N>(row, data, layout, plane, &mut view);
                    change = change.max(c);
                }
                local.store(&mut st);
            } else {
                // One body: its view serves every row.
                let mut st = self.states[self.contacts[start].body].view::<N>();
                for (k, row) in self.contacts[start..end].iter_mut().enumerate() {
                    let at = (start + k) * layout.stride;
                    let data = &self.row_data[at..at + layout.stride];
                    let plane = &half_spaces[row.half_space];
                    change = change.max(sweep_contact::<N>(row, data, layout, plane, &mut st));
                }
            }
            if change <= tolerance {
                break;
            }
            if change < 0.99 * least {
                (least, least_at) = (change, sweeps);
            } else if sweeps - least_at >= STALLED_SWEEPS {
                // Rows that hand an impulse back and forth: the sweeps repeat a cycle.
                stop = Stop::Stalled;
                break;
            }
            if accelerated && sweeps < limit {
                last = self.accelerate::<N>(start..end, half_spaces, layout, last);
            }
            if let (true, Some(lever)) = (check, lever) {
                // Rows that hand impulses round a face (a null direction of its points'
                // normal impulses, friction at the rim of its cone) leave the bodies'
                // velocities as they were, to round-off, sweep after sweep, while each
                // update still changes them by the same amount: more sweeps change
                // nothing but the impulses' share among the points.
                let moved = self.cycle_moved(lever);
                still = if moved <= CYCLE_NET * tolerance {
                    still + 1
                } else {
                    0
                };
                if still >= CYCLE_SWEEPS {
                    stop = Stop::Cycled;
                    break;
                }
            }
        }
        self.report.max_sweeps = self.report.max_sweeps.max(sweeps);
        self.report.sweeps += sweeps as u64;
        if change > tolerance {
            self.report.unconverged += 1;
            *match stop {
                Stop::AtLimit => &mut self.report.at_sweep_limit,
                Stop::Stalled => &mut self.report.stalled,
                Stop::Cycled => &mut self.report.cycled,
            } += 1;
            let residual = change / speed.max(1e-300);
            self.report.worst_residual = self.report.worst_residual.max(residual);
        }
    }

    /// Lists the bodies of the contact rows `range` (and of the pairs and joints when
    /// `coupled`) for [`Self::cycle_keep`], and returns the longest lever arm of their rows.
    fn cycle_bodies_of(&mut self, range: std::ops::Range<usize>, coupled: bool) -> f64 {
        let mut lever = 0.0f64;
        let bodies = &mut self.cycle_bodies;
        bodies.clear();
        for row in &self.contacts[range] {
            bodies.push(row.body);
            lever = lever.max(crate::numeric::dense::norm(&row.r));
        }
        if coupled {
            for row in &self.pairs {
                bodies.extend([row.a, row.b]);
                lever = lever.max(row.ra.norm()).max(row.rb.norm());
            }
            for row in &self.joints {
                bodies.push(row.body);
                lever = lever.max(row.r.norm());
                if let Some((other, r)) = &row.other {
                    bodies.push(*other);
                    lever = lever.max(r.norm());
                }
            }
        }
        bodies.sort_unstable();
        bodies.dedup();
        lever
    }

    /// Keeps the velocities of [`Self::cycle_bodies`] as they are now.
    fn cycle_keep(&mut self) {
        self.cycle_velocities.clear();
        for &i in &self.cycle_bodies {
            let st = &self.states[i];
            self.cycle_velocities.extend(st.v.iter().chain(st.w.iter()));
        }
    }

    /// The largest change of a velocity of [`Self::cycle_bodies`] since
    /// [`Self::cycle_keep`], an angular one times `lever` (a speed of a point).
    fn cycle_moved(&self, lever: f64) -> f64 {
        let mut kept = self.cycle_velocities.iter();
        let mut moved = 0.0f64;
        for &i in &self.cycle_bodies {
            let st = &self.states[i];
            for (x, y) in st.v.iter().zip(kept.by_ref()) {
                moved = moved.max((x - y).abs());
            }
            for (x, y) in st.w.iter().zip(kept.by_ref()) {
                moved = moved.max((x - y).abs() * lever);
            }
        }
        moved
    }

    /// Keeps each row's accumulated impulse as one vector (joints, pairs, then the contact
    /// rows `range`) for [`Solver::accelerate`]; `start` also clears the directions.
    fn keep_impulses(
        &mut self,
        range: std::ops::Range<usize>,
        half_spaces: &[HalfSpace],
        n: usize,
        start: bool,
    ) {
        let slots = self.joints.len() + self.pairs.len() + range.len();
        if self.momentum.len() < 2 * n * slots {
            self.momentum.resize(2 * n * slots, 0.0);
        }
        let mut slot = self.momentum.chunks_exact_mut(2 * n);
        for row in &self.joints {
            let s = slot.next().expect("a slot per row");
            s[..n].copy_from_slice(&row.impulse.as_slice()[..n]);
            if start {
                s[n..].fill(0.0);
            }
        }
        for pair in &self.pairs {
            let s = slot.next().expect("a slot per row");
            pair.total_impulse(&mut s[..n]);
            if start {
                s[n..].fill(0.0);
            }
        }
        for row in &self.contacts[range] {
            let s = slot.next().expect("a slot per row");
            contact_impulse(row, half_spaces, &mut s[..n]);
            if start {
                s[n..].fill(0.0);
            }
        }
    }

    /// A step of nonsmooth nonlinear conjugate gradients after a Gauss–Seidel sweep
    /// (Silcowitz, Niebe and Erleben, "A nonsmooth nonlinear conjugate gradient method for
    /// interactive contact force problems", The Visual Computer 26, 2010). The sweep is a
    /// step along the negative gradient of the solve's merit function, Δ = the impulses'
    /// change over it; with β = |Δ|² / |Δ_last|² (Fletcher–Reeves), each row's impulse
    /// takes β p more and the bodies with it, and p becomes β p + Δ. Where β > 1 the
    /// directions start again (p = Δ at the next sweep). Gauss–Seidel alone gains a digit
    /// in hundreds of sweeps on a stack started cold (its impulses travel one body per
    /// sweep); these steps carry them on. The next sweep projects what the step left
    /// outside its cone, and the solve stops only after a sweep, so its answer is always
    /// one. Returns |Δ|².
    fn accelerate<const N: usize>(
        &mut self,
        range: std::ops::Range<usize>,
        half_spaces: &[HalfSpace],
        layout: &RowLayout,
        last: f64,
    ) -> f64 {
        let n = layout.n;
        let (mut now_fixed, mut now_any) = ([0.0; 4], Small::new());
        let now = scratch::<N>(&mut now_fixed, &mut now_any, n);
        // Δ in place of the kept impulses.
        let mut squares = 0.0;
        {
            let mut slot = self.momentum.chunks_exact_mut(2 * n);
            let mut change = |s: &mut [f64], now: &[f64]| {
                for (d, x) in s[..n].iter_mut().zip(now) {
                    *d = x - *d;
                    squares += *d * *d;
                }
            };
            for row in &self.joints {
                change(slot.next().expect("a slot"), &row.impulse.as_slice()[..n]);
            }
            for pair in &self.pairs {
                pair.total_impulse(now);
                change(slot.next().expect("a slot"), now);
            }
            for row in &self.contacts[range.clone()] {
                contact_impulse(row, half_spaces, now);
                change(slot.next().expect("a slot"), now);
            }
        }
        let beta = squares / last;
        let mut slot = self.momentum.chunks_exact_mut(2 * n);
        if beta.is_nan() || beta > 1.0 {
            for s in slot {
                s[n..].fill(0.0);
            }
            return squares;
        }
        // step = β p (into `now`), then p = step + Δ.
        let turn = |s: &mut [f64], now: &mut [f64]| {
            let (delta, p) = s.split_at_mut(n);
            for ((x, q), d) in now.iter_mut().zip(p.iter_mut()).zip(delta.iter()) {
                *x = beta * *q;
                *q = *x + d;
            }
        };
        let states = &mut self.states;
        for row in &mut self.joints {
            turn(slot.next().expect("a slot"), now);
            if beta > 0.0 {
                let step = Vector::from_storage(now.iter().copied().collect());
                row.apply(states, &step);
                row.impulse += &step;
            }
        }
        for pair in &mut self.pairs {
            turn(slot.next().expect("a slot"), now);
            if beta > 0.0 {
                pair.add_impulse::<N>(states, now);
            }
        }
        for (k, row) in self.contacts[range.clone()].iter_mut().enumerate() {
            turn(slot.next().expect("a slot"), now);
            if beta > 0.0 {
                let nv = &half_spaces[row.half_space].normal().as_slice()[..n];
                let along = dot(nv, now);
                row.normal_impulse += along;
                for ((t, x), y) in row.friction_impulse.as_mut_slice()[..n]
                    .iter_mut()
                    .zip(now.iter())
                    .zip(nv)
                {
                    *t += x - along * y;
                }
                let at = (range.start + k) * layout.stride;
                let data = &self.row_data[at..at + layout.stride];
                states[row.body].view::<N>().apply_with::<N>(
                    data,
                    layout,
                    &row.r.as_slice()[..n],
                    now,
                );
            }
        }
        squares
    }

    /// Records the contact rows `range` with their impulses and the velocities the solve
    /// leaves at their points.
    fn record_rows<const N: usize>(
        &self,
        range: std::ops::Range<usize>,
        half_spaces: &[HalfSpace],
        layout: &RowLayout,
        record: &mut ContactLog,
    ) {
        let n = dim::<N>(layout.n);
        let m = n * (n - 1) / 2;
        let (mut u_fixed, mut u_any) = ([0.0; 4], Small::new());
        let u = scratch::<N>(&mut u_fixed, &mut u_any, n);
        // The velocities of the last row's body (the rows of a body are consecutive).
        let (mut body, mut v, mut w): (usize, &[f64], &[f64]) = (usize::MAX, &[], &[]);
        for k in range {
            let row = &self.contacts[k];
            if row.gap > row.reach {
                continue;
            }
            let nrm = half_spaces[row.half_space].normal();
            if row.body != body {
                let st = &self.states[row.body];
                (body, v, w) = (row.body, &st.v.as_slice()[..n], &st.w.as_slice()[..m]);
            }
            point_velocity::<N>(layout, &row.r.as_slice()[..n], v, w, u);
            record.record(
                (row.body, row.half_space),
                &row.point.as_slice()[..n],
                row.normal_impulse,
                &row.friction_impulse.as_slice()[..n],
                u,
                &nrm.as_slice()[..n],
            );
        }
    }

    /// Hands the impulses so far to the bodies, keeping them loaded.
    fn store_loaded(&mut self, bodies: &mut [MovingBody]) {
        for (s, b) in self.states.iter_mut().zip(bodies.iter_mut()) {
            if s.used {
                s.store(b);
                // Stay loaded for the next call.
                s.used = true;
                s.dp.as_mut_slice().fill(0.0);
                s.dl.as_mut_slice().fill(0.0);
            }
        }
    }

    /// Forgets the loaded bodies and the joints' factor (the placement is about to change).
    /// Takes the contacts between bodies that detection found, starting each from the
    /// impulses of the last solve's point of the same pair made by the same features (a
    /// point of a manifold kept from step to step), or else of the same pair's point nearest
    /// to it that no other point took: each of the last solve's impulses goes to one point
    /// at most, so that a manifold whose features changed keeps its total impulse.
    ///
    /// `serial` is the found list's serial number: the same list as the last solve's (a
    /// solve again at the same placement) keeps the rows, their K and their impulses, as
    /// matching them point by point would give them.
    pub(crate) fn set_pairs(&mut self, found: &[PairContact], serial: u64, bodies: &[MovingBody]) {
        self.pairs_kept = self.pairs_found == Some(serial);
        if self.pairs_kept {
            for row in &mut self.pairs {
                row.drop_normal_friction();
            }
            return;
        }
        self.pairs_found = Some(serial);
        self.anchors.update(bodies, found);
        let anchors = &self.anchors;
        let at = |i: usize| MassAt {
            generation: anchors.generation[i],
            inertia: anchors.inertia_generation[i],
            isotropic: anchors.isotropic[i],
        };
        let own = |i: usize, r: &crate::algebra::Vector| {
            bodies[i]
                .rotation()
                .principal_frame_attitude()
                .inverse_rotate_vector(r)
        };
        // Bodies at rest find the same points again, in the same order: each row is then
        // updated in place, as the matching below would rebuild it from itself.
        if found_again(&self.pairs, found) {
            for (row, c) in self.pairs.iter_mut().zip(found) {
                let (a, b) = (c.a, c.b);
                let x = (
                    bodies[a].position().as_slice(),
                    bodies[b].position().as_slice(),
                );
                let material = contact_material(&bodies[a], &bodies[b]);
                if !row.refresh(c, x, material, (at(a), at(b))) {
                    row.own_a = own(a, &row.ra);
                    row.own_b = own(b, &row.rb);
                }
            }
            return;
        }
        let old = std::mem::take(&mut self.pairs);
        // The rows of the solve before last, rewritten in their own room.
        let mut rows = std::mem::take(&mut self.spare_pairs);
        let mut used = 0;
        self.taken.clear();
        self.taken.resize(old.len(), false);
        self.sources.clear();
        // The points made by the same features first, so that a point whose features
        // changed takes none of their impulses.
        let mut cursor = 0;
        for c in found {
            let (a, b) = (c.a, c.b);
            let x = (
                bodies[a].position().as_slice(),
                bodies[b].position().as_slice(),
            );
            let material = contact_material(&bodies[a], &bodies[b]);
            if used < rows.len() {
                rows[used].set(c, x, material);
            } else {
                rows.push(PairRow::new(c, x, material));
            }
            let row = &mut rows[used];
            used += 1;
            // Detection lists the points in about the order of the last solve: the search
            // starts where the last match was, so that matching stays linear in the rows.
            let matches = |r: &PairRow| r.a == a && r.b == b && r.feature == c.feature;
            let same = (cursor..old.len())
                .chain(0..cursor.min(old.len()))
                .find(|&k| matches(&old[k]) && !self.taken[k]);
            if let Some(k) = same {
                cursor = k + 1;
                self.taken[k] = true;
            }
            self.sources.push(same);
            // A point that barely moved keeps its K and its offsets in the bodies' axes.
            if row.take_mass(same.map(|k| &old[k]), (at(a), at(b))) {
                continue;
            }
            row.own_a = own(a, &row.ra);
            row.own_b = own(b, &row.rb);
        }
        rows.truncate(used);
        for (row, source) in rows.iter_mut().zip(&mut self.sources) {
            if source.is_none() {
                // A point of the pair whose features changed (or a curved pair's single
                // point).
                *source = old
                    .iter()
                    .enumerate()
                    .filter(|(k, r)| r.a == row.a && r.b == row.b && !self.taken[*k])
                    .min_by(|(_, r), (_, s)| {
                        let far = |x: &PairRow| (&x.ra - &row.ra).norm_squared();
                        far(r).total_cmp(&far(s))
                    })
                    .map(|(k, _)| k);
                if let Some(k) = *source {
                    self.taken[k] = true;
                }
            }
            if let Some(k) = *source {
                let last = &old[k];
                // The normal turns little between solves: keep the impulse along the new one
                // and the tangent part of the old friction impulse.
                row.normal_impulse = last.normal_impulse;
                set_vector(&mut row.friction_impulse, last.friction_impulse.as_slice());
                row.drop_normal_friction();
            }
        }
        self.pairs = rows;
        self.spare_pairs = old;
    }

    /// No contacts between bodies.
    pub(crate) fn clear_pairs(&mut self) {
        self.pairs.clear();
        self.pairs_found = None;
    }

    pub(crate) fn release(&mut self) {
        self.joint_factor = false;
        for s in &mut self.states {
            s.used = false;
        }
    }
}

/// Whether `found` lists the points of `rows` again in their order: the same pairs with as
/// many points each, each point made by the same features but at most one of a pair, whose
/// features are new to the pair (a corner on an edge of the other body's face, made by
/// one edge or another from step to step). The matching of [`Solver::set_pairs`] then
/// rebuilds each row from the row at its place: its own, or for the point whose features
/// changed, the one row of its pair left.
fn found_again(rows: &[PairRow], found: &[PairContact]) -> bool {
    if rows.len() != found.len() {
        return false;
    }
    let mut start = 0;
    while start < rows.len() {
        let pair = (rows[start].a, rows[start].b);
        let end = start + run_len(&rows[start..], |r| (r.a, r.b));
        let (old, new) = (&rows[start..end], &found[start..end]);
        let mut changed = None;
        for (k, (r, c)) in old.iter().zip(new).enumerate() {
            if (c.a, c.b) != pair {
                return false;
            }
            if r.feature != c.feature {
                if changed.is_some() {
                    return false;
                }
                changed = Some(k);
            }
        }
        if let Some(k) = changed {
            let (was, now) = (old[k].feature, new[k].feature);
            if old.iter().any(|r| r.feature == now) || new.iter().any(|c| c.feature == was) {
                return false;
            }
        }
        start = end;
    }
    true
}

/// A contact row's accumulated impulse as one vector, J = λ n + J_t, written to `j`.
fn contact_impulse(row: &ContactRow, half_spaces: &[HalfSpace], j: &mut [f64]) {
    let nv = half_spaces[row.half_space].normal().as_slice();
    for ((x, y), t) in j.iter_mut().zip(nv).zip(row.friction_impulse.as_slice()) {
        *x = y * row.normal_impulse + t;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::{Bivector, Rotor};
    use crate::inertia::spec::parse_body;
    use smallvec::smallvec;

    /// Points of a pair whose features all changed start from the last solve's impulses of
    /// the nearest points, each of those given once: two new points nearest to the same old
    /// point take its impulse and the other's, so that the pair's total impulse is kept.
    #[test]
    fn points_whose_features_changed_share_out_the_last_impulses_once_each() {
        let parsed = parse_body("cuboid:0.5,0.5,0.5+mass=1").unwrap();
        let body = |z: f64| {
            MovingBody::new(
                parsed.mass,
                parsed.inertia.clone(),
                Rotor::identity(3),
                &Vector::from_components(&[0.0, 0.0, z]).unwrap(),
                &Vector::zero(3),
                &Bivector::zero(3),
            )
            .unwrap()
        };
        let bodies = [body(0.5), body(1.5)];
        let contact = |feature: u64, x: f64| PairContact {
            a: 0,
            b: 1,
            feature,
            gap: 0.0,
            reach: 1e-9,
            normal: smallvec![0.0, 0.0, 1.0],
            point: smallvec![x, 0.0, 1.0],
        };
        let mut solver = Solver::default();
        solver.set_pairs(&[contact(1, -0.5), contact(2, 0.5)], 1, &bodies);
        solver.pairs[0].normal_impulse = 1.0;
        solver.pairs[1].normal_impulse = 2.0;
        // Both new points lie nearer to the first old one.
        solver.set_pairs(&[contact(3, -0.4), contact(4, -0.3)], 2, &bodies);
        let impulses: Vec<f64> = solver.pairs.iter().map(|p| p.normal_impulse).collect();
        assert_eq!(impulses, [1.0, 2.0]);
        // A point of the same features takes its own impulse, the other the one left.
        solver.set_pairs(&[contact(9, 0.5), contact(4, -0.3)], 3, &bodies);
        let impulses: Vec<f64> = solver.pairs.iter().map(|p| p.normal_impulse).collect();
        assert_eq!(impulses, [1.0, 2.0]);
    }

    /// Two 3D bodies of `spec` at rest, one above the other, turned by 0.2 and −0.3 rad in
    /// the plane of the first axis and the axis `k`.
    fn stacked(spec: &str, k: usize) -> [MovingBody; 2] {
        let parsed = parse_body(spec).unwrap();
        let body = |z: f64, angle: f64| {
            MovingBody::new(
                parsed.mass,
                parsed.inertia.clone(),
                Rotor::from_plane_angle(3, 0, k, angle).unwrap(),
                &Vector::from_components(&[0.1, 0.0, z]).unwrap(),
                &Vector::zero(3),
                &Bivector::zero(3),
            )
            .unwrap()
        };
        [body(0.5, 0.2), body(1.5, -0.3)]
    }

    /// The same list of found pairs again (a solve at the same placement) keeps the rows as
    /// they are, which is what making them anew and matching each point by its features
    /// gives: the same points, impulses and friction impulses to the bit.
    #[test]
    fn the_same_found_pairs_keep_their_rows_as_matching_would_make_them() {
        let bodies = stacked("cuboid:0.5,0.5,0.5+mass=1", 1);
        let s = 0.6f64.sqrt();
        let found: Vec<PairContact> = (0..4u64)
            .map(|k| PairContact {
                a: 0,
                b: 1,
                feature: 10 + k,
                gap: -1e-3 * k as f64,
                reach: 1e-9,
                normal: smallvec![0.2 * s, -0.1, (1.0 - 0.04 * 0.6 - 0.01f64).sqrt()],
                point: smallvec![0.3 * k as f64 - 0.4, 0.1 * k as f64, 1.0],
            })
            .collect();
        let mut kept = Solver::default();
        kept.set_pairs(&found, 7, &bodies);
        for (k, row) in kept.pairs.iter_mut().enumerate() {
            row.normal_impulse = 0.3 + k as f64;
            // Not quite tangent, as a solve leaves it to round-off.
            row.friction_impulse =
                Vector::from_components(&[0.01, -0.02 * k as f64, 1e-17]).unwrap();
        }
        let mut made = kept.clone();
        kept.set_pairs(&found, 7, &bodies);
        made.set_pairs(&found, 8, &bodies);
        assert!(kept.pairs_kept && !made.pairs_kept);
        assert_eq!(kept.pairs.len(), 4);
        for (x, y) in kept.pairs.iter().zip(&made.pairs) {
            assert_eq!(x.feature, y.feature);
            assert_eq!(x.normal_impulse.to_bits(), y.normal_impulse.to_bits());
            assert_eq!(x.friction_impulse.as_slice(), y.friction_impulse.as_slice());
            assert_eq!(x.ra.as_slice(), y.ra.as_slice());
            assert_eq!(x.rb.as_slice(), y.rb.as_slice());
            assert_eq!(x.own_a.as_slice(), y.own_a.as_slice());
            assert_eq!(x.own_b.as_slice(), y.own_b.as_slice());
            assert_eq!(x.normal.as_slice(), y.normal.as_slice());
        }
    }

    /// The same points found again in the same order (bodies at rest), one of them made
    /// by other features, update their rows in place; the rows are those the matching by
    /// features builds from the last ones (here from the same points listed the other way
    /// round): the same impulses, the friction impulse's part along the turned normal
    /// dropped, the same offsets, to the bit.
    #[test]
    fn rows_found_again_in_order_are_updated_as_matching_rebuilds_them() {
        let bodies = stacked("cuboid:0.5,0.3,0.2+mass=1", 2);
        let points = |tilt: f64, shift: f64| -> Vec<PairContact> {
            (0..4u64)
                .map(|k| PairContact {
                    a: 0,
                    b: 1,
                    feature: 10 + k,
                    gap: -1e-3 * k as f64 + shift,
                    reach: 1e-9,
                    normal: smallvec![tilt, -0.1, (1.0 - tilt * tilt - 0.01f64).sqrt()],
                    point: smallvec![0.3 * k as f64 - 0.4 + shift, 0.1 * k as f64, 1.0],
                })
                .collect()
        };
        let mut last = Solver::default();
        last.set_pairs(&points(0.2, 0.0), 1, &bodies);
        for (k, row) in last.pairs.iter_mut().enumerate() {
            row.normal_impulse = 0.3 + k as f64;
            row.friction_impulse =
                Vector::from_components(&[0.01, -0.02 * k as f64, 1e-3]).unwrap();
        }
        let mut moved = points(0.21, 1e-4);
        // One point made by other features now (a corner on an edge).
        moved[2].feature = 99;
        let mut in_place = last.clone();
        in_place.set_pairs(&moved, 2, &bodies);
        let mut rebuilt = last.clone();
        let reversed: Vec<PairContact> = moved.iter().rev().cloned().collect();
        rebuilt.set_pairs(&reversed, 2, &bodies);
        assert_eq!((in_place.pairs.len(), rebuilt.pairs.len()), (4, 4));
        let mut compared = 0;
        for x in &in_place.pairs {
            let y = rebuilt
                .pairs
                .iter()
                .find(|y| y.feature == x.feature)
                .unwrap();
            let bits = |v: &Vector| v.as_slice().iter().map(|c| c.to_bits()).collect::<Vec<_>>();
            assert_eq!(x.normal_impulse.to_bits(), y.normal_impulse.to_bits());
            assert!(x.normal_impulse > 0.0);
            for (u, v) in [
                (&x.friction_impulse, &y.friction_impulse),
                (&x.ra, &y.ra),
                (&x.rb, &y.rb),
                (&x.own_a, &y.own_a),
                (&x.own_b, &y.own_b),
                (&x.normal, &y.normal),
            ] {
                assert_eq!(bits(u), bits(v));
            }
            assert!(x.normal.dot(&x.friction_impulse).abs() < 1e-17);
            assert_eq!((x.gap, x.mass_ready), (y.gap, y.mass_ready));
            compared += 1;
        }
        assert_eq!(compared, 4);
        // What the matching would not rebuild in place: two points of the pair made by
        // other features, two points that swapped theirs, a point of another pair, a
        // point fewer.
        assert!(found_again(&last.pairs, &moved));
        let mut two = moved.clone();
        two[0].feature = 98;
        let mut swapped = points(0.21, 1e-4);
        swapped.swap(1, 2);
        let mut other = points(0.21, 1e-4);
        other[3].b = 0;
        for list in [two, swapped, other, moved[..3].to_vec()] {
            assert!(!found_again(&last.pairs, &list));
        }
    }

    /// A pair row keeps the last step's K and offsets in its bodies' axes while its point
    /// and normal move less than `KEEP_MASS` of its size since they were computed and
    /// (unless its inverse inertia is the same in every frame) its bodies turn less; what
    /// it keeps is then within 1e-9 of what it would compute (K relative to its size, the
    /// offsets to theirs), and a larger turn or shift makes it compute them anew. Bodies
    /// of both kinds (a cube, and a box of three different lengths whose K depends on its
    /// attitude), turning by 4e-12 rad per step, then once by 1e-6 rad.
    #[test]
    fn a_pair_row_keeps_its_mass_while_its_point_and_bodies_barely_move() {
        let flat = parse_body("cuboid:0.5,0.3,0.2+mass=1").unwrap();
        let cube = parse_body("cuboid:0.5,0.5,0.5+mass=2").unwrap();
        let heavier = parse_body("cuboid:0.5,0.5,0.5+mass=5").unwrap();
        let placed = |parsed: &crate::inertia::spec::ParsedBody, x: [f64; 3], angle: f64| {
            MovingBody::new(
                parsed.mass,
                parsed.inertia.clone(),
                Rotor::from_plane_angle(3, 0, 1, angle).unwrap(),
                &Vector::from_components(&x).unwrap(),
                &Vector::zero(3),
                &Bivector::zero(3),
            )
            .unwrap()
        };
        // The last point is on the axis of the turn: it does not move, but the box's K
        // there turns with the box.
        let own_points = [
            [0.4, 0.25, -0.2],
            [-0.4, 0.25, -0.2],
            [0.0, -0.25, -0.2],
            [0.0, 0.0, -0.2],
        ];
        let (mut checked, mut kept) = (0, 0);
        let mut anew = Vec::new();
        let mut solver = Solver::default();
        let turns: Vec<f64> = (0..12)
            .map(|k| 4e-12 * k as f64)
            .chain([1e-6, 1e-6 + 4e-12, 1e-6 + 4e-12])
            .collect();
        for (step, &turn) in turns.iter().enumerate() {
            // Body 1 (the top of each pair) turns about the normal; bodies 0 and 2 rest.
            // The third pair's points stay put in space while its top turns (as a rolling
            // body's do): its K stands, its offsets in the top's axes turn.
            let bodies = [
                placed(&flat, [0.0, 0.0, 0.2], 0.3),
                placed(&flat, [0.05, 0.0, 0.6], 0.1 + turn),
                placed(&cube, [3.0, 0.0, 0.5], 0.0),
                // At the last step another body takes its place (heavier, at rest there).
                placed(
                    if step == 14 { &heavier } else { &cube },
                    [3.05, 0.0, 1.5],
                    0.2 + turn,
                ),
                placed(&cube, [6.0, 0.0, 0.5], 0.0),
                placed(&cube, [6.05, 0.0, 1.5], 0.2 + turn),
            ];
            let mut found = Vec::new();
            for (a, b) in [(0usize, 1usize), (2, 3), (4, 5)] {
                let top = &bodies[b];
                for (k, p) in own_points.iter().enumerate() {
                    let p = Vector::from_components(p).unwrap();
                    let p = if b == 5 {
                        p
                    } else {
                        top.rotation().principal_frame_attitude().rotate_vector(&p)
                    };
                    let point: SmallVec<[f64; 8]> = p
                        .as_slice()
                        .iter()
                        .zip(top.position().as_slice())
                        .map(|(x, c)| x + c)
                        .collect();
                    found.push(PairContact {
                        a,
                        b,
                        feature: k as u64,
                        gap: 0.0,
                        reach: 1e-9,
                        normal: smallvec![0.0, 0.0, 1.0],
                        point,
                    });
                }
            }
            solver.set_pairs(&found, step as u64, &bodies);
            solver.release();
            solver.load(&bodies);
            anew.push(0);
            for row in &mut solver.pairs {
                if row.mass_ready {
                    kept += 1;
                } else {
                    row.prepare_mass(&solver.states);
                    anew[step] += 1;
                }
            }
            for row in &solver.pairs {
                let mut fresh = row.clone();
                fresh.prepare_mass(&solver.states);
                let ((k, kinv), (k_fresh, kinv_fresh)) = (row.mass(), fresh.mass());
                for (got, want) in [(k, k_fresh), (kinv, kinv_fresh)] {
                    let size = crate::numeric::max_abs(want);
                    let off = got
                        .iter()
                        .zip(want)
                        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
                    assert!(off <= 1e-9 * size, "step {step}: K off by {off:e}");
                }
                for (own, r, body) in [(&row.own_a, &row.ra, row.a), (&row.own_b, &row.rb, row.b)] {
                    let want = bodies[body]
                        .rotation()
                        .principal_frame_attitude()
                        .inverse_rotate_vector(r);
                    let off = (own - &want).norm();
                    assert!(
                        off <= 1e-9 * r.norm(),
                        "step {step}: offsets off by {off:e}"
                    );
                }
                checked += 1;
            }
        }
        assert_eq!(checked, turns.len() * 12);
        // The first step computes every K, the jump those of the first two pairs but the
        // cube's on the axis of the turn (its point did not move, and a cube's K does not
        // depend on its attitude), the step after the jump none, the heavier body's pair
        // all four; the slow turn renews each of the first two pairs' rows at least once,
        // and most steps keep them.
        println!("rows whose K was computed anew at each step: {anew:?}");
        assert_eq!(
            (anew[0], anew[12], anew[13], anew[14]),
            (12, 7, 0, 4),
            "{anew:?}"
        );
        assert!(anew[1..12].iter().sum::<usize>() >= 6, "{anew:?}");
        assert!(kept >= checked / 2, "kept {kept} of {checked}");
    }
}
