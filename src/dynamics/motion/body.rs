//! [`MovingBody`]: a rigid body that moves as well as turns.

use super::{ContactShape, MotionError, Wrench};
use crate::algebra::pga::Motor;
use crate::algebra::{Bivector, Vector};
use crate::dynamics::{Attitude, DynamicsError, RigidBody};
use crate::inertia::InertiaMap;
use crate::inertia::spec::ParsedBody;
use crate::numeric::all_finite;
use nalgebra::DMatrix;
use std::sync::Arc;

/// A rigid body in ℝᴺ that moves and turns: its centre of mass x and linear momentum
/// p = m v in space, and its rotation about the centre of mass as a [`RigidBody`] (attitude
/// R and spin L in the principal frame, the inertia map taken about the centre of mass).
///
/// Newton–Euler in N dimensions, with F the total force (space frame) and τ the torque about
/// the centre of mass (principal body frame; a force F at body point r gives r ∧ F):
///
///   dx/dt = p/m,  dp/dt = F,  dL/dt = ω × L + τ,  dR/dt = −½ R ω.
///
/// The translation and the rotation are coupled only through the forques, which read both.
/// Body points are given in the body's own axes (as its vertices are); the body's placement
/// is the rigid motion x_space = x + R_b r R̃_b with R_b =
/// [`RigidBody::body_axes_attitude`], which [`MovingBody::motor`] returns as a motor of
/// projective GA and [`MovingBody::homogeneous_matrix`] as an (N+1) × (N+1) matrix.
///
/// ```
/// use rotorflow::prelude::*;
/// use rotorflow::dynamics::motion::MovingBody;
/// let inertia = InertiaMap::from_principal_second_moments(&[1.0, 2.0, 3.0])?;
/// let body = MovingBody::new(
///     2.0,
///     inertia,
///     Rotor::identity(3),
///     &Vector::from_components(&[0.0, 0.0, 1.0])?,
///     &Vector::from_components(&[1.0, 0.0, 0.0])?,
///     &Bivector::zero(3),
/// )?;
/// assert_eq!(body.linear_momentum().as_slice(), &[2.0, 0.0, 0.0]);
/// assert!((body.kinetic_energy() - 1.0).abs() < 1e-15);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct MovingBody {
    rotation: RigidBody,
    mass: f64,
    position: Vector,
    momentum: Vector,
    /// What the body touches with, shared by its copies (a step's saved states copy
    /// bodies, and a shape of many vertices should not be copied with them).
    shape: Arc<ContactShape>,
    /// Its Coulomb friction coefficient and restitution against other bodies (None: the
    /// other body's, see [`MovingBody::with_friction`]).
    friction: Option<f64>,
    restitution: Option<f64>,
    /// False if it touches nothing.
    collides: bool,
    /// True for a body that never moves (infinite mass and inertia).
    fixed: bool,
}

impl MovingBody {
    /// Returns the body of mass `mass` and inertia `inertia` (about its centre of mass, in
    /// its own axes), placed with attitude `attitude` (own axes → space) and centre of mass
    /// `position`, moving with velocity `velocity` and turning with angular velocity `omega`
    /// (bivector, in its own axes).
    ///
    /// # Errors
    /// [`MotionError::OutOfRange`] for a mass that is not finite and positive,
    /// [`MotionError::WrongDimension`] or [`MotionError::NonFinite`] for vectors of another
    /// dimension than the inertia or not finite; [`DynamicsError::Inertia`] as
    /// [`RigidBody::from_body_velocity`].
    pub fn new(
        mass: f64,
        inertia: InertiaMap,
        attitude: impl Into<Attitude>,
        position: &Vector,
        velocity: &Vector,
        omega: &Bivector,
    ) -> Result<Self, DynamicsError> {
        let rotation = RigidBody::from_body_velocity(inertia, attitude, omega)?;
        Self::from_rigid_body(rotation, mass, position, velocity)
    }

    /// Returns the body turning as `rotation` (whose inertia is about the centre of mass),
    /// with mass `mass`, centre of mass `position` and velocity `velocity`.
    ///
    /// # Errors
    /// As [`MovingBody::new`].
    pub fn from_rigid_body(
        rotation: RigidBody,
        mass: f64,
        position: &Vector,
        velocity: &Vector,
    ) -> Result<Self, DynamicsError> {
        rotation.refuse_gyrostat("a moving body")?;
        MotionError::require(
            mass.is_finite() && mass > 0.0,
            "mass",
            mass,
            "a finite positive number",
        )?;
        let n = rotation.dim();
        for (what, v) in [("position", position), ("velocity", velocity)] {
            check_vector(what, v, n)?;
        }
        let momentum = velocity * mass;
        check_vector("linear momentum", &momentum, n)?;
        Ok(MovingBody {
            rotation,
            mass,
            position: position.clone(),
            momentum,
            shape: Arc::new(ContactShape::None),
            friction: None,
            restitution: None,
            collides: true,
            fixed: false,
        })
    }

    /// Returns a fixed body: solid world of the shape `shape` (own axes), placed with
    /// `attitude` at `position`, that never moves and needs no mass. Other bodies touch it
    /// as they touch a moving one, and its infinite mass and inertia take any impulse
    /// without a change of velocity; forques do not move it (gravity leaves it out). Its
    /// [`MovingBody::mass`] is +∞, its momenta are zero.
    ///
    /// # Errors
    /// [`MotionError`] for a position of another dimension than the shape or not finite, or
    /// a bad shape; [`MotionError::EmptyShape`] for [`ContactShape::None`] (a fixed body
    /// that touches nothing has no effect).
    pub fn fixed(
        shape: ContactShape,
        attitude: impl Into<Attitude>,
        position: &Vector,
    ) -> Result<Self, DynamicsError> {
        let n = position.dim();
        if matches!(shape, ContactShape::None) {
            return Err(MotionError::EmptyShape { what: "fixed body" }.into());
        }
        check_vector("position", position, n)?;
        shape.check(n)?;
        let inertia = InertiaMap::from_principal_second_moments(&vec![1.0; n])?;
        let rotation = RigidBody::from_body_velocity(inertia, attitude, &Bivector::zero(n))?;
        if rotation.dim() != n {
            return Err(MotionError::WrongDimension {
                what: "attitude",
                expected: n,
                found: rotation.dim(),
            }
            .into());
        }
        Ok(MovingBody {
            rotation,
            mass: f64::INFINITY,
            position: position.clone(),
            momentum: Vector::zero(n),
            shape: Arc::new(shape),
            friction: None,
            restitution: None,
            collides: true,
            fixed: true,
        })
    }

    /// Returns true for a body made by [`MovingBody::fixed`].
    pub fn is_fixed(&self) -> bool {
        self.fixed
    }

    /// Returns the body described by `body`, a body of the catalogue parsed from the SPEC
    /// grammar ([`crate::inertia::spec::parse_body`]), with the mass, the inertia and the
    /// contact shape that description gives it (the vertices of boxes, point sets and
    /// meshes, the ellipsoid of `ellipsoid:`, `ball:` and `sphere:`; no shape for `principal:`,
    /// `tensor:` and `planes:`, which describe no surface), placed and moving as in
    /// [`MovingBody::new`]. Mass, inertia and shape come from one description, so they
    /// cannot disagree.
    ///
    /// # Errors
    /// As [`MovingBody::new`].
    ///
    /// ```
    /// use rotorflow::prelude::*;
    /// use rotorflow::dynamics::motion::{ContactShape, MovingBody};
    /// use rotorflow::inertia::spec::parse_body;
    /// let cube = parse_body("cuboid:0.5,0.5,0.5+mass=2")?;
    /// let body = MovingBody::from_parsed(
    ///     &cube,
    ///     Rotor::identity(3),
    ///     &Vector::from_components(&[0.0, 0.0, 0.5])?,
    ///     &Vector::zero(3),
    ///     &Bivector::zero(3),
    /// )?;
    /// assert_eq!(body.mass(), 2.0);
    /// assert!(matches!(body.shape(), ContactShape::Vertices(v) if v.len() == 8));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn from_parsed(
        body: &ParsedBody,
        attitude: impl Into<Attitude>,
        position: &Vector,
        velocity: &Vector,
        omega: &Bivector,
    ) -> Result<Self, DynamicsError> {
        let moving = Self::new(
            body.mass,
            body.inertia.clone(),
            attitude,
            position,
            velocity,
            omega,
        )?;
        moving.with_shape(ContactShape::from_geometry(&body.geometry))
    }

    /// Returns the body with the contact shape `shape` (in its own axes about its centre of
    /// mass) instead of its own.
    ///
    /// # Errors
    /// [`MotionError`] for a shape of another dimension or with bad numbers.
    pub fn with_shape(mut self, shape: ContactShape) -> Result<Self, DynamicsError> {
        shape.check(self.dim())?;
        self.shape = Arc::new(shape);
        Ok(self)
    }

    /// Returns what the body touches with ([`ContactShape::None`] unless it was built from
    /// a catalogue body or given one).
    pub fn shape(&self) -> &ContactShape {
        &self.shape
    }

    /// Returns the body with the Coulomb friction coefficient `friction` (≥ 0) for its
    /// contacts with other bodies. Two bodies touch with μ = √(μ₁ μ₂) when both give one,
    /// with the one given when only one does, and with
    /// [`MovingBody::DEFAULT_FRICTION`] when neither does (the mixing rule of Box2D and
    /// Rapier's default coefficient). Contacts with a half-space use the half-space's.
    ///
    /// # Errors
    /// [`MotionError::OutOfRange`] for a negative or non-finite coefficient.
    pub fn with_friction(mut self, friction: f64) -> Result<Self, DynamicsError> {
        MotionError::require(
            friction.is_finite() && friction >= 0.0,
            "friction",
            friction,
            "a finite number ≥ 0",
        )?;
        self.friction = Some(friction);
        Ok(self)
    }

    /// Returns the body with the restitution `restitution` (in [0, 1]) for its contacts
    /// with other bodies. Two bodies bounce with e = max(e₁, e₂) of those given (so that a
    /// bouncy ball bounces off anything), 0 when neither gives one. Contacts with a
    /// half-space use the half-space's.
    ///
    /// # Errors
    /// [`MotionError::OutOfRange`] for a restitution outside [0, 1].
    pub fn with_restitution(mut self, restitution: f64) -> Result<Self, DynamicsError> {
        MotionError::require(
            (0.0..=1.0).contains(&restitution),
            "restitution",
            restitution,
            "in [0, 1]",
        )?;
        self.restitution = Some(restitution);
        Ok(self)
    }

    /// Returns the body touching nothing (`false`: neither other bodies nor half-spaces; it
    /// keeps its shape, for drawing) or touching with its shape (`true`, the default).
    pub fn with_collisions(mut self, collides: bool) -> Self {
        self.collides = collides;
        self
    }

    /// The friction coefficient of two bodies touching when neither gives one.
    pub const DEFAULT_FRICTION: f64 = 0.5;

    /// Returns the friction coefficient given with [`MovingBody::with_friction`].
    pub fn friction(&self) -> Option<f64> {
        self.friction
    }

    /// Returns the restitution given with [`MovingBody::with_restitution`].
    pub fn restitution(&self) -> Option<f64> {
        self.restitution
    }

    /// Returns false if the body touches nothing.
    pub fn collides(&self) -> bool {
        self.collides
    }

    /// Sets the shape, checked by the caller.
    pub(crate) fn set_shape_checked(&mut self, shape: ContactShape) {
        self.shape = Arc::new(shape);
    }

    /// Returns the body placed by the homogeneous matrix `placement` = [[Q, x], [0, 1]]
    /// (own axes → space: body point r at x + Q r), moving with `velocity` and turning with
    /// `omega` (own axes): the inverse of [`MovingBody::homogeneous_matrix`].
    ///
    /// # Errors
    /// [`DynamicsError::Algebra`] when the matrix is not square, not finite, its last row is
    /// not (0, …, 0, 1) or Q is not a rotation; otherwise as [`MovingBody::new`].
    pub fn from_homogeneous_matrix(
        mass: f64,
        inertia: InertiaMap,
        placement: &DMatrix<f64>,
        velocity: &Vector,
        omega: &Bivector,
    ) -> Result<Self, DynamicsError> {
        let motor = Motor::from_matrix(placement)?;
        Self::from_motor(mass, inertia, &motor, velocity, omega)
    }

    /// Returns the body placed by the motor `placement` of projective GA (the rotation of
    /// the own axes, then the translation to the centre of mass), moving with `velocity` and
    /// turning with `omega` (own axes): the inverse of [`MovingBody::motor`].
    ///
    /// # Errors
    /// As [`MovingBody::new`].
    pub fn from_motor(
        mass: f64,
        inertia: InertiaMap,
        placement: &Motor,
        velocity: &Vector,
        omega: &Bivector,
    ) -> Result<Self, DynamicsError> {
        let position = Vector::from_components(&placement.translation())?;
        Self::new(mass, inertia, placement.rotor(), &position, velocity, omega)
    }

    /// Returns the dimension N.
    pub fn dim(&self) -> usize {
        self.rotation.dim()
    }

    /// Returns the mass m.
    pub fn mass(&self) -> f64 {
        self.mass
    }

    /// Returns the rotation about the centre of mass (attitude, spin, inertia).
    pub fn rotation(&self) -> &RigidBody {
        &self.rotation
    }

    /// Returns the centre of mass x (space frame).
    pub fn position(&self) -> &Vector {
        &self.position
    }

    /// Returns the velocity of the centre of mass, v = p/m.
    pub fn velocity(&self) -> Vector {
        &self.momentum * (1.0 / self.mass)
    }

    /// Returns the linear momentum p = m v.
    pub fn linear_momentum(&self) -> &Vector {
        &self.momentum
    }

    /// Returns the attitude of the body's own axes (own axes → space).
    pub fn attitude(&self) -> Attitude {
        self.rotation.body_axes_attitude()
    }

    /// Returns the angular velocity in the body's own axes.
    pub fn omega(&self) -> Bivector {
        self.rotation
            .principal_frame()
            .rotate_bivector(&self.rotation.omega())
    }

    /// Returns the angular velocity in space, ω_s = R ω R̃.
    pub fn space_omega(&self) -> Bivector {
        self.rotation.space_omega()
    }

    /// Returns the position in space of the body point `point` (own axes):
    /// x + R_b r R̃_b.
    pub fn point_position(&self, point: &Vector) -> Vector {
        &self.position + &self.attitude().rotate_vector(point)
    }

    /// Returns the velocity in space of the body point `point` (own axes): v + r_s ⌋ ω_s,
    /// with r_s its offset from the centre of mass in space (the Conventions chapter's
    /// x ⌋ ω).
    pub fn point_velocity(&self, point: &Vector) -> Vector {
        let r = self.attitude().rotate_vector(point);
        &self.velocity() + &r.left_contract(&self.space_omega())
    }

    /// Returns the wrench of a force `force` (space frame) applied at the body point `point`
    /// (own axes): the force, and the torque r ∧ F about the centre of mass in the principal
    /// frame.
    pub fn wrench_at(&self, point: &Vector, force: &Vector) -> Wrench {
        let r = self.attitude().rotate_vector(point);
        let torque_space = r.wedge(force);
        Wrench {
            force: force.clone(),
            torque: self
                .rotation
                .principal_frame_attitude()
                .inverse_rotate_bivector(&torque_space),
        }
    }

    /// Returns the kinetic energy ½ m v² + ½⟨ω, L⟩.
    pub fn kinetic_energy(&self) -> f64 {
        0.5 * self.momentum.norm_squared() / self.mass + self.rotation.energy()
    }

    /// Returns the angular momentum about the origin of space, x ∧ p + L_s (orbital plus
    /// spin, both bivectors of space).
    pub fn angular_momentum(&self) -> Bivector {
        &self.position.wedge(&self.momentum) + &self.rotation.space_momentum()
    }

    /// Returns the placement as a motor of projective GA Cl(N, 0, 1): the rotation of the
    /// body's own axes followed by the translation to the centre of mass.
    ///
    /// # Errors
    /// [`crate::algebra::AlgebraError`] above the rotor limit (N = 16).
    pub fn motor(&self) -> Result<Motor, DynamicsError> {
        let rotor = self.attitude().to_rotor()?;
        Ok(Motor::from_rotation_translation(
            &rotor,
            self.position.as_slice(),
        )?)
    }

    /// Returns the (N+1) × (N+1) homogeneous matrix [[R, x], [0, 1]] of the placement (body
    /// point r in own axes ↦ x + R r).
    pub fn homogeneous_matrix(&self) -> DMatrix<f64> {
        let n = self.dim();
        let r = self.attitude().to_matrix();
        let mut h = DMatrix::identity(n + 1, n + 1);
        h.view_mut((0, 0), (n, n)).copy_from(&r);
        for i in 0..n {
            h[(i, n)] = self.position.as_slice()[i];
        }
        h
    }

    /// Mutable state for the integrators: position, momentum, rotation.
    pub(crate) fn state_mut(&mut self) -> (&mut Vector, &mut Vector, &mut RigidBody) {
        (&mut self.position, &mut self.momentum, &mut self.rotation)
    }

    /// True if every part of the state is finite.
    pub(crate) fn is_finite(&self) -> bool {
        // Without a branch per number: this runs on every body after every step.
        all_finite(self.position.as_slice())
            & all_finite(self.momentum.as_slice())
            & all_finite(self.rotation.momentum().as_slice())
            & self.rotation.principal_frame_attitude().is_finite()
    }
}

/// Refuses a vector of the wrong dimension or with a non-finite component.
pub(crate) fn check_vector(what: &'static str, v: &Vector, n: usize) -> Result<(), DynamicsError> {
    check_slice(what, v.as_slice(), n)
}

/// Refuses components of the wrong count or not finite.
pub(crate) fn check_slice(what: &'static str, v: &[f64], n: usize) -> Result<(), DynamicsError> {
    if v.len() != n {
        return Err(MotionError::WrongDimension {
            what,
            expected: n,
            found: v.len(),
        }
        .into());
    }
    if let Some(&value) = v.iter().find(|x| !x.is_finite()) {
        return Err(MotionError::NonFinite { what, value }.into());
    }
    Ok(())
}

/// The friction coefficient and restitution of a contact between bodies `a` and `b`: see
/// [`MovingBody::with_friction`] and [`MovingBody::with_restitution`].
pub(crate) fn contact_material(a: &MovingBody, b: &MovingBody) -> (f64, f64) {
    let friction = match (a.friction, b.friction) {
        (Some(x), Some(y)) => (x * y).sqrt(),
        (Some(x), None) | (None, Some(x)) => x,
        (None, None) => MovingBody::DEFAULT_FRICTION,
    };
    let restitution = a
        .restitution
        .unwrap_or(0.0)
        .max(b.restitution.unwrap_or(0.0));
    (friction, restitution)
}
