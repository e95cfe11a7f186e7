//! [`System`]: moving bodies and the forques between them.

use super::MotionError;
use super::contact::{BodyContact, ContactLog, ContactMark};
use super::detect::bodies::convex_of;
use super::detect::{BroadPhase, EpaWorkspace, PlacedShape, penetration_with};
use super::forques::Anchor;
use super::shape::ConvexShape;
use super::{BallJoint, Contact, ContactShape, Forque, ForqueInput, HalfSpace, MovingBody, Wrench};
use crate::algebra::{Bivector, Vector};
use crate::dynamics::DynamicsError;

/// Bodies that move in one space, and the forques on them (gravity, springs, drag, …).
///
/// The system's invariants, which the integrators are measured by:
/// - the energy, kinetic (translation and rotation) plus the potentials of the conservative
///   forques;
/// - the linear momentum Σ p;
/// - the angular momentum about the origin, Σ (x ∧ p + L_s).
///
/// Without external forques the last two are conserved (internal springs pull the two bodies
/// along the line between their attachment points, so their torques cancel about any point).
pub struct System {
    bodies: Vec<MovingBody>,
    forques: Vec<Box<dyn Forque>>,
    shapes: Vec<ContactShape>,
    half_spaces: Vec<HalfSpace>,
    joints: Vec<BallJoint>,
    contacts: ContactLog,
    /// The wrenches when every forque is constant ([`Forque::is_constant`]), evaluated when
    /// a forque joins.
    constant: Option<ConstantWrenches>,
    /// True if a forque reads velocities ([`Forque::reads_velocities`]).
    reads_velocities: bool,
    /// This system among all (for the integrators' caches), and the version of its shapes.
    id: u64,
    shapes_version: u64,
}

/// The wrench on every body under forques that are all constant, and whether any force or
/// any torque is non-zero (a kick without them changes nothing and is skipped).
#[derive(Clone, Debug)]
pub(crate) struct ConstantWrenches {
    pub wrenches: Vec<Wrench>,
    pub any_force: bool,
    pub any_torque: bool,
}

impl std::fmt::Debug for System {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("System")
            .field("bodies", &self.bodies)
            .field("forques", &self.forques.len())
            .field("shapes", &self.shapes)
            .field("half_spaces", &self.half_spaces)
            .field("joints", &self.joints)
            .finish()
    }
}

impl System {
    /// Returns the system of `bodies`, without forques; each body touches with its own
    /// [`MovingBody::shape`].
    ///
    /// # Errors
    /// [`MotionError::NoBody`] if there is no body, [`MotionError::MixedDimensions`] if
    /// the bodies live in spaces of different dimension.
    pub fn new(bodies: Vec<MovingBody>) -> Result<System, DynamicsError> {
        let Some(first) = bodies.first() else {
            return Err(MotionError::NoBody.into());
        };
        let n = first.dim();
        if let Some((body, b)) = bodies.iter().enumerate().find(|(_, b)| b.dim() != n) {
            return Err(MotionError::MixedDimensions {
                body,
                expected: n,
                found: b.dim(),
            }
            .into());
        }
        let mut system = System {
            shapes: bodies.iter().map(touching_shape).collect(),
            bodies,
            forques: Vec::new(),
            half_spaces: Vec::new(),
            joints: Vec::new(),
            contacts: ContactLog::default(),
            constant: None,
            reads_velocities: false,
            id: {
                static SYSTEMS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
                SYSTEMS.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
            },
            shapes_version: 0,
        };
        system.refresh_constant();
        Ok(system)
    }

    /// Evaluates the forques once if they are all constant (no forque at all is constant
    /// too: zero wrenches).
    fn refresh_constant(&mut self) {
        self.reads_velocities = self.forques.iter().any(|f| f.reads_velocities());
        self.constant = None;
        if !self.forques.iter().all(|f| f.is_constant()) {
            return;
        }
        let wrenches = self.wrenches_for(0.0, &self.bodies);
        let nonzero = |x: &[f64]| x.iter().any(|&c| c != 0.0);
        self.constant = Some(ConstantWrenches {
            any_force: wrenches.iter().any(|w| nonzero(w.force.as_slice())),
            any_torque: wrenches.iter().any(|w| nonzero(w.torque.as_slice())),
            wrenches,
        });
    }

    /// True if a forque reads the bodies' velocities (damping, drag).
    pub(crate) fn reads_velocities(&self) -> bool {
        self.reads_velocities
    }

    /// The bodies, and the wrenches on them if the forques are all constant.
    pub(crate) fn bodies_and_constant_wrenches(
        &mut self,
    ) -> (&mut [MovingBody], Option<&ConstantWrenches>) {
        (&mut self.bodies, self.constant.as_ref())
    }

    /// The wrenches on the bodies if the forques are all constant.
    pub(crate) fn constant_wrenches(&self) -> Option<&[Wrench]> {
        self.constant.as_ref().map(|c| &c.wrenches[..])
    }

    /// Adds a forque.
    ///
    /// # Errors
    /// [`MotionError::NoSuchBody`] if it refers to a body the system does not have.
    pub fn add_forque(&mut self, forque: impl Forque + 'static) -> Result<(), DynamicsError> {
        if let Some(i) = forque
            .bodies()
            .into_iter()
            .find(|&i| i >= self.bodies.len())
        {
            return Err(MotionError::NoSuchBody {
                what: "forque",
                body: i,
                count: self.bodies.len(),
            }
            .into());
        }
        self.forques.push(Box::new(forque));
        self.refresh_constant();
        Ok(())
    }

    /// Checks a body index.
    fn check_body(&self, what: &'static str, i: usize) -> Result<(), DynamicsError> {
        if i < self.bodies.len() {
            return Ok(());
        }
        Err(MotionError::NoSuchBody {
            what,
            body: i,
            count: self.bodies.len(),
        }
        .into())
    }

    /// Gives body `body` the shape it touches with, in place of its own
    /// ([`MovingBody::shape`]).
    ///
    /// # Errors
    /// [`MotionError::NoSuchBody`] for a missing body, [`MotionError`] for a shape of another
    /// dimension or with bad numbers.
    pub fn set_shape(&mut self, body: usize, shape: ContactShape) -> Result<(), DynamicsError> {
        self.check_body("shape", body)?;
        shape.check(self.dim())?;
        self.bodies[body].set_shape_checked(shape);
        self.shapes[body] = touching_shape(&self.bodies[body]);
        self.shapes_version += 1;
        Ok(())
    }

    /// Adds a half-space of solid world (floor, wall, slope) that the bodies' shapes touch.
    ///
    /// # Errors
    /// [`MotionError::WrongDimension`] for a normal of another dimension.
    pub fn add_half_space(&mut self, half_space: HalfSpace) -> Result<(), DynamicsError> {
        super::body::check_vector("normal", half_space.normal(), self.dim())?;
        self.half_spaces.push(half_space);
        Ok(())
    }

    /// Adds a ball joint.
    ///
    /// # Errors
    /// [`MotionError::NoSuchBody`] for a missing body, [`MotionError::JointToItself`],
    /// [`MotionError::WrongDimension`] for points of another dimension.
    pub fn add_ball_joint(&mut self, joint: BallJoint) -> Result<(), DynamicsError> {
        let n = self.dim();
        self.check_body("joint", joint.body)?;
        super::body::check_vector("joint point", &joint.point, n)?;
        match &joint.other {
            Anchor::World(x) => super::body::check_vector("joint anchor", x, n)?,
            Anchor::Body(j, p) => {
                self.check_body("joint", *j)?;
                if *j == joint.body {
                    return Err(MotionError::JointToItself {
                        joint: self.joints.len(),
                        body: *j,
                    }
                    .into());
                }
                super::body::check_vector("joint point", p, n)?;
            }
        }
        self.joints.push(joint);
        Ok(())
    }

    /// Checks that the system can start moving: no two bodies overlap by more than
    /// [`System::TOUCHING`] of their radii ([`MotionError::StartsOverlapping`]); if it has
    /// half-spaces, some body has a contact shape ([`MotionError::NothingTouches`]), and no
    /// body starts inside a
    /// half-space by more than [`System::TOUCHING`] of its shape's radius
    /// ([`MotionError::StartsInside`], naming the body, the half-space and the depth).
    /// [`MotionSplitting`](super::MotionSplitting) checks this before its first step of a
    /// system, and again whenever shapes or half-spaces are added.
    ///
    /// # Errors
    /// The two above.
    pub fn check_contacts(&self) -> Result<(), DynamicsError> {
        self.check_overlaps()?;
        if self.half_spaces.is_empty() {
            return Ok(());
        }
        if self.shapes.iter().all(|s| matches!(s, ContactShape::None)) {
            return Err(MotionError::NothingTouches {
                half_spaces: self.half_spaces.len(),
            }
            .into());
        }
        let n = self.dim();
        let mut q = smallvec::SmallVec::<[f64; 64]>::from_elem(0.0, n * n);
        for (body, (b, shape)) in self.bodies.iter().zip(&self.shapes).enumerate() {
            if matches!(shape, ContactShape::None) || b.is_fixed() {
                continue;
            }
            b.attitude().write_matrix(&mut q);
            let tolerance = Self::TOUCHING * shape.radius();
            for (half_space, plane) in self.half_spaces.iter().enumerate() {
                let mut lowest = f64::INFINITY;
                shape.candidates(&q, plane.normal(), |_, r| {
                    lowest = lowest.min(plane.normal().dot(r));
                });
                let depth = -(plane.distance(b.position()) + lowest);
                if depth > tolerance {
                    return Err(MotionError::StartsInside {
                        body,
                        half_space,
                        depth,
                        tolerance,
                    }
                    .into());
                }
            }
        }
        Ok(())
    }

    /// Refuses two bodies that start overlapping by more than [`System::TOUCHING`] of the sum
    /// of their shapes' radii (pairs held by a joint, and two fixed bodies, excepted).
    fn check_overlaps(&self) -> Result<(), DynamicsError> {
        let n = self.dim();
        // The bodies with a convex shape, each with its shape and attitude matrix. A body's
        // constructors refuse a position that is not finite; one left so by a failed step
        // has no bounding box and is passed over here.
        let checked: Vec<(usize, ConvexShape, Vec<f64>)> = self
            .bodies
            .iter()
            .zip(&self.shapes)
            .enumerate()
            .filter(|(_, (b, _))| b.position().as_slice().iter().all(|x| x.is_finite()))
            .filter_map(|(k, (b, s))| {
                let shape = convex_of(s, n)?;
                let mut q = vec![0.0; n * n];
                b.attitude().write_matrix(&mut q);
                Some((k, shape, q))
            })
            .collect();
        if checked.len() < 2 {
            return Ok(());
        }
        let joined = |a: usize, b: usize| {
            self.joints.iter().any(|j| match &j.other {
                Anchor::Body(k, _) => (j.body, *k) == (a, b) || (j.body, *k) == (b, a),
                Anchor::World(_) => false,
            })
        };
        // Candidate pairs from the broad phase over the boxes of the bounding balls, so that
        // the check costs about n log n, not n².
        let mut lower = Vec::with_capacity(checked.len() * n);
        let mut upper = Vec::with_capacity(checked.len() * n);
        for (k, shape, _) in &checked {
            let r = shape.bounding_radius();
            for &x in self.bodies[*k].position().as_slice() {
                lower.push(x - r);
                upper.push(x + r);
            }
        }
        let mut broad = BroadPhase::new(n)?;
        let mut workspace = EpaWorkspace::new();
        for &(i, j) in broad.update(&lower, &upper)? {
            let ((a, ca, qa), (b, cb, qb)) = (&checked[i], &checked[j]);
            let (a, b) = (*a, *b);
            let (ba, bb) = (&self.bodies[a], &self.bodies[b]);
            if ba.is_fixed() && bb.is_fixed() || joined(a, b) {
                continue;
            }
            let apart = ba
                .position()
                .as_slice()
                .iter()
                .zip(bb.position().as_slice());
            let centres = apart.map(|(p, q)| (p - q) * (p - q)).sum::<f64>().sqrt();
            if centres > ca.bounding_radius() + cb.bounding_radius() {
                continue;
            }
            let (Ok(pa), Ok(pb)) = (
                PlacedShape::new(ca, ba.position().as_slice(), qa),
                PlacedShape::new(cb, bb.position().as_slice(), qb),
            ) else {
                continue;
            };
            let Ok(p) = penetration_with(&mut workspace, &pa, &pb) else {
                continue;
            };
            let tolerance = Self::TOUCHING * (ca.bounding_radius() + cb.bounding_radius());
            if p.depth > tolerance {
                return Err(MotionError::StartsOverlapping {
                    a,
                    b,
                    depth: p.depth,
                    tolerance,
                }
                .into());
            }
        }
        Ok(())
    }

    /// The depth inside a half-space, relative to the radius of the body's shape, that
    /// still counts as touching when a system starts: round-off of placing a body on a
    /// plane is far below it, a body placed inside by mistake far above.
    pub const TOUCHING: f64 = 1e-6;

    /// What [`System::check_contacts`] depends on: the system, its shapes' version and its
    /// number of half-spaces.
    pub(crate) fn contacts_key(&self) -> (u64, u64, usize) {
        (self.id, self.shapes_version, self.half_spaces.len())
    }

    /// Names this system and the version of its shapes: the integrators keep the bodies'
    /// placements for as long as both stay the same.
    pub(crate) fn shape_key(&self) -> (u64, u64) {
        (self.id, self.shapes_version)
    }

    /// Returns the shapes the bodies touch with, in the order of the bodies: each body's
    /// [`MovingBody::shape`], or [`ContactShape::None`] for a body that touches nothing
    /// ([`MovingBody::with_collisions`]).
    pub fn shapes(&self) -> &[ContactShape] {
        &self.shapes
    }

    /// Returns the half-spaces.
    pub fn half_spaces(&self) -> &[HalfSpace] {
        &self.half_spaces
    }

    /// Returns the ball joints.
    pub fn joints(&self) -> &[BallJoint] {
        &self.joints
    }

    /// Returns the contacts of the last step, with their impulses: one entry per touching
    /// point and velocity solve. [`MotionSplitting`](super::MotionSplitting) solves after
    /// each half kick, so a resting point appears twice a step (more where the step is cut
    /// at an impact), and the impulses of a point's entries add up to what the velocity
    /// solves gave it over the step. Impulses that only keep a point from ending the free
    /// flight inside its half-space (the position step of a contact that would sink) are
    /// not among them. [`SoftStep`](super::SoftStep) lists each point once per step, with
    /// the impulses of its substeps summed.
    pub fn contacts(&self) -> &[Contact] {
        self.contacts.as_slice()
    }

    /// Returns the contacts between bodies of the last step, with their impulses: one entry
    /// per touching point per velocity solve (the points of a face resting on a face are
    /// the corners of their contact region), as [`System::contacts`] lists the contacts with
    /// half-spaces (once per step under [`SoftStep`](super::SoftStep)).
    pub fn body_contacts(&self) -> &[BodyContact] {
        self.contacts.pairs()
    }

    /// Returns the dimension N.
    pub fn dim(&self) -> usize {
        self.bodies[0].dim()
    }

    /// Returns the bodies.
    pub fn bodies(&self) -> &[MovingBody] {
        &self.bodies
    }

    /// Mutable bodies, for the integrators.
    pub(crate) fn bodies_mut(&mut self) -> &mut [MovingBody] {
        &mut self.bodies
    }

    /// The wrench on every body at time `t` for the given states.
    pub(crate) fn wrenches_for(&self, t: f64, bodies: &[MovingBody]) -> Vec<Wrench> {
        let mut w = vec![Wrench::zero(self.dim()); bodies.len()];
        let input = ForqueInput { time: t, bodies };
        for f in &self.forques {
            f.apply(&input, &mut w);
        }
        w
    }

    /// Writes the wrench on every body at time `t` into `out` (reused storage).
    pub(crate) fn wrenches_into(&self, t: f64, out: &mut Vec<Wrench>) {
        self.wrenches_for_into(t, &self.bodies, out);
    }

    /// Writes the wrench on every body at time `t` for the given states into `out` (reused
    /// storage).
    pub(crate) fn wrenches_for_into(&self, t: f64, bodies: &[MovingBody], out: &mut Vec<Wrench>) {
        if let Some(c) = &self.constant {
            out.clone_from(&c.wrenches);
            return;
        }
        let n = self.dim();
        if out.len() != bodies.len() {
            out.resize(bodies.len(), Wrench::zero(n));
        }
        for w in out.iter_mut() {
            w.force.as_mut_slice().fill(0.0);
            w.torque.as_mut_slice().fill(0.0);
        }
        let input = ForqueInput { time: t, bodies };
        for f in &self.forques {
            f.apply(&input, out);
        }
    }

    /// The parts the integrators change and read together.
    #[allow(clippy::type_complexity)]
    pub(crate) fn parts_mut(
        &mut self,
    ) -> (
        &mut [MovingBody],
        &[ContactShape],
        &[HalfSpace],
        &[BallJoint],
        &mut ContactLog,
    ) {
        (
            &mut self.bodies,
            &self.shapes,
            &self.half_spaces,
            &self.joints,
            &mut self.contacts,
        )
    }

    pub(crate) fn clear_contacts(&mut self) {
        self.contacts.clear();
    }

    /// How many contacts of each kind the last step has recorded so far.
    pub(crate) fn contact_mark(&self) -> ContactMark {
        self.contacts.mark()
    }

    pub(crate) fn truncate_contacts(&mut self, mark: ContactMark) {
        self.contacts.truncate(mark);
    }

    /// Returns the wrench on every body at time `t`.
    pub fn wrenches(&self, t: f64) -> Vec<Wrench> {
        self.wrenches_for(t, &self.bodies)
    }

    /// Returns the kinetic energy of all bodies.
    pub fn kinetic_energy(&self) -> f64 {
        self.bodies.iter().map(MovingBody::kinetic_energy).sum()
    }

    /// Returns the potential energy of the conservative forques at time `t`.
    pub fn potential_energy(&self, t: f64) -> f64 {
        let input = ForqueInput {
            time: t,
            bodies: &self.bodies,
        };
        self.forques
            .iter()
            .filter_map(|f| f.potential_energy(&input))
            .sum()
    }

    /// Returns the energy: kinetic plus the potentials of the conservative forques.
    pub fn energy(&self, t: f64) -> f64 {
        self.kinetic_energy() + self.potential_energy(t)
    }

    /// Returns the total linear momentum Σ p.
    pub fn linear_momentum(&self) -> Vector {
        let mut p = Vector::zero(self.dim());
        for b in &self.bodies {
            p += b.linear_momentum();
        }
        p
    }

    /// Returns the total angular momentum about the origin, Σ (x ∧ p + L_s).
    pub fn angular_momentum(&self) -> Bivector {
        let mut l = Bivector::zero(self.dim());
        for b in &self.bodies {
            l += &b.angular_momentum();
        }
        l
    }
}

/// The shape `body` touches with: its own, or none if it touches nothing.
fn touching_shape(body: &MovingBody) -> ContactShape {
    if body.collides() {
        body.shape().clone()
    } else {
        ContactShape::None
    }
}
