//! [`RigidBody`]: attitude (rotor or rotation matrix) and body-frame angular momentum.

use super::Attitude;
use crate::algebra::Bivector;
use crate::inertia::{InertiaError, InertiaMap};

/// The state of a rotating rigid body in ℝᴺ: its inertia map (in the principal frame), its
/// attitude R (principal frame → space, x_space = R x R̃; a rotor for N ≤ 4, an SO(N) matrix
/// above, see [`Attitude`]) and its angular momentum L in the principal frame.
///
/// The body frame is always the principal frame of the inertia: a map given in other axes is
/// diagonalised on construction and the attitude absorbs the principal rotor, so every step
/// applies I⁻¹ as one multiplication per plane. The body's own axes and the principal axes
/// differ by [`InertiaMap::principal_rotor`]; [`RigidBody::principal_frame`] keeps it.
///
/// Two attitudes, so that neither is misread:
/// - [`RigidBody::principal_frame_attitude`] (principal axes → space) is the state the
///   integrators advance, and the frame of [`RigidBody::momentum`] and [`RigidBody::omega`];
/// - [`RigidBody::body_axes_attitude`] (the body's own axes → space) is the one to render the
///   body with: a vertex with body-axis coordinates x is at
///   `body.body_axes_attitude().rotate_vector(&x)`.
///
/// ```
/// use rotorflow::prelude::*;
/// use rotorflow::dynamics::RigidBody;
/// let inertia = InertiaMap::from_principal_second_moments(&[1.0, 2.0, 3.0, 4.0])?;
/// let omega = Bivector::from_components(4, &[1.0, 0.0, 0.0, 0.0, 0.0, 0.5])?;
/// let body = RigidBody::from_body_velocity(inertia, Rotor::identity(4), &omega)?;
/// assert!((&body.omega() - &omega).norm() < 1e-15);
/// assert!((body.energy() - 0.5 * (3.0 + 0.25 * 7.0)).abs() < 1e-15);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct RigidBody {
    inertia: InertiaMap,
    principal_frame: Attitude,
    attitude: Attitude,
    momentum: Bivector,
    /// The momentum h of internal rotors spinning at a constant rate relative to the body
    /// (a gyrostat), principal frame; `None` for a rigid body.
    gyrostatic: Option<Bivector>,
}

impl RigidBody {
    /// Returns the body with inertia `inertia`, attitude `attitude` (body's own axes → space)
    /// and body-frame angular momentum `momentum` (in the body's own axes).
    ///
    /// The attitude is a [`Rotor`](crate::algebra::Rotor) or an [`Attitude`] (any N; e.g. [`Attitude::identity`]).
    ///
    /// # Errors
    /// [`InertiaError::DimensionMismatch`]; [`InertiaError::NonFinite`] if the momentum, or
    /// the angular velocity ω = I⁻¹(L) it implies, is not finite (overflow);
    /// [`InertiaError::Algebra`] if the principal axes do not form a rotation (not expected
    /// for a physical map).
    pub fn from_body_momentum(
        inertia: InertiaMap,
        attitude: impl Into<Attitude>,
        momentum: &Bivector,
    ) -> Result<Self, InertiaError> {
        let attitude = attitude.into();
        let n = inertia.dim();
        for d in [attitude.dim(), momentum.dim()] {
            check_body_dim("attitude or momentum", n, d)?;
        }
        // Move to the principal frame: R_body = R_P · R_principal-frame.
        let (inertia, principal_frame) = if inertia.is_principal() || !inertia.is_physical() {
            (inertia, Attitude::identity(n))
        } else {
            let axes = inertia
                .principal_axes()
                .expect("a physical map has principal axes");
            let rp = Attitude::from_matrix(axes).map_err(InertiaError::from)?;
            let diag = InertiaMap::from_principal_second_moments(
                inertia
                    .principal_second_moments()
                    .expect("a physical map has principal moments"),
            )?;
            (diag, rp)
        };
        check_finite("angular momentum", momentum)?;
        let momentum = principal_frame.inverse_rotate_bivector(momentum);
        let attitude = attitude.compose(&principal_frame);
        let body = RigidBody {
            inertia,
            principal_frame,
            attitude,
            momentum,
            gyrostatic: None,
        };
        // A finite L can still overflow in the principal frame or in ω = I⁻¹(L) (tiny plane
        // moments): refuse the state rather than hand out a body whose ω is not finite.
        check_finite("angular momentum in the principal frame", &body.momentum)?;
        check_finite("angular velocity I⁻¹(L)", &body.omega())?;
        Ok(body)
    }

    /// Returns the body with body-frame angular velocity ω (in the body's own axes).
    ///
    /// # Errors
    /// As [`RigidBody::from_body_momentum`].
    pub fn from_body_velocity(
        inertia: InertiaMap,
        attitude: impl Into<Attitude>,
        omega: &Bivector,
    ) -> Result<Self, InertiaError> {
        let l = inertia.try_apply(omega)?;
        Self::from_body_momentum(inertia, attitude, &l)
    }

    /// Returns the body with space-frame angular momentum L_s: L = R̃ L_s R.
    ///
    /// # Errors
    /// As [`RigidBody::from_body_momentum`].
    pub fn from_space_momentum(
        inertia: InertiaMap,
        attitude: impl Into<Attitude>,
        momentum: &Bivector,
    ) -> Result<Self, InertiaError> {
        let attitude = attitude.into();
        let l = attitude.inverse_rotate_bivector(momentum);
        Self::from_body_momentum(inertia, attitude, &l)
    }

    /// Returns the body with space-frame angular velocity ω_s: ω = R̃ ω_s R.
    ///
    /// # Errors
    /// As [`RigidBody::from_body_momentum`].
    pub fn from_space_velocity(
        inertia: InertiaMap,
        attitude: impl Into<Attitude>,
        omega: &Bivector,
    ) -> Result<Self, InertiaError> {
        let attitude = attitude.into();
        let w = attitude.inverse_rotate_bivector(omega);
        Self::from_body_velocity(inertia, attitude, &w)
    }

    /// Returns the dimension N.
    pub fn dim(&self) -> usize {
        self.inertia.dim()
    }

    /// Returns the inertia map in the principal (body) frame.
    pub fn inertia(&self) -> &InertiaMap {
        &self.inertia
    }

    /// Returns the rotation R_P from the body's own axes to its principal axes, R_P eᵢ R̃_P = pᵢ
    /// (identity when the inertia was given in its principal frame): a vector or bivector in
    /// the body's own axes is `principal_frame().rotate_*` of its principal-frame components.
    pub fn principal_frame(&self) -> &Attitude {
        &self.principal_frame
    }

    /// Returns the attitude of the principal frame, R: principal axes → space. This is the
    /// rotation the integrators advance, and the one that takes the principal-frame
    /// quantities of this type ([`RigidBody::momentum`], [`RigidBody::omega`]) to space,
    /// e.g. L_s = R L R̃.
    ///
    /// To place the body itself (its vertices or mesh, given in the body's own axes), use
    /// [`RigidBody::body_axes_attitude`]; the two agree when the inertia was given in its
    /// principal frame.
    pub fn principal_frame_attitude(&self) -> &Attitude {
        &self.attitude
    }

    /// Returns the attitude of the body's own axes (the axes its shape, vertices and inertia
    /// were given in): R · R̃_P, with R the [principal frame's
    /// attitude](RigidBody::principal_frame_attitude) and R_P the [`principal
    /// frame`](RigidBody::principal_frame).
    ///
    /// This is the rotation to render the body with: a vertex with body-axis coordinates x
    /// is at `body_axes_attitude().rotate_vector(&x)` in space (plus the position of the
    /// centre of mass).
    ///
    /// ```
    /// use rotorflow::prelude::*;
    /// // An ellipsoid whose inertia is given in axes that are not its principal axes.
    /// let turn = Rotor::from_plane_angle(3, 0, 1, 0.3)?;
    /// let shape = Body::solid_ellipsoid(&[1.0, 2.0, 3.0], 1.0)?.rotated(&turn.to_matrix())?;
    /// let tilted = InertiaMap::from_body(&shape)?;
    /// let omega = Bivector::from_components(3, &[0.0, 0.0, 1.0])?;
    /// let body = RigidBody::from_body_velocity(tilted, Rotor::identity(3), &omega)?;
    /// // At t = 0 the body's own axes coincide with space; its principal axes do not.
    /// let vertex = Vector::from_components(&[1.0, 2.0, 3.0])?;
    /// let placed = body.body_axes_attitude().rotate_vector(&vertex);
    /// let distance = |v: &Vector| {
    ///     let d: Vec<f64> = v.as_slice().iter().zip(vertex.as_slice()).map(|(a, b)| a - b).collect();
    ///     Vector::from_components(&d).map(|d| d.norm())
    /// };
    /// assert!(distance(&placed)? < 1e-14);
    /// // The principal frame's attitude would put the vertex elsewhere.
    /// let misplaced = body.principal_frame_attitude().rotate_vector(&vertex);
    /// assert!(distance(&misplaced)? > 0.1);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn body_axes_attitude(&self) -> Attitude {
        self.attitude.compose(&self.principal_frame.inverse())
    }

    /// Returns the body-frame angular momentum L (principal frame).
    pub fn momentum(&self) -> &Bivector {
        &self.momentum
    }

    /// Returns the body-frame angular velocity ω = I⁻¹(L) (principal frame).
    pub fn omega(&self) -> Bivector {
        self.omega_of(&self.momentum)
    }

    /// ω = I⁻¹(L − h) for a body-frame momentum `l` (h the gyrostatic momentum, if any).
    pub(crate) fn omega_of(&self, l: &Bivector) -> Bivector {
        match &self.gyrostatic {
            None => self.inertia.apply_inverse(l),
            Some(h) => self.inertia.apply_inverse(&(l - h)),
        }
    }

    /// Makes the body a gyrostat: it carries internal rotors (flywheels, reaction wheels)
    /// whose angular momentum relative to the body is the constant bivector `h`, given in
    /// the body's own axes. The body's momentum [`RigidBody::momentum`] is then the total
    /// L = I(ω) + h, and Euler's equations become dL/dt = ω × L with ω = I⁻¹(L − h)
    /// (Zhukovsky and Volterra's free gyrostat: the Casimirs of L and the energy
    /// ½⟨ω, I(ω)⟩ are its integrals). The state keeps the total momentum (ω changes).
    ///
    /// [`Rkmk4`](crate::dynamics::Rkmk4), [`Dopri5`](crate::dynamics::Dopri5),
    /// [`Dop853`](crate::dynamics::Dop853) and [`Midpoint`](crate::dynamics::Midpoint)
    /// integrate gyrostats; the splittings, the Moser–Veselov map, the fixed-size bodies, the
    /// moving bodies and the closed forms, whose formulas assume h = 0, refuse them with
    /// [`DynamicsError::Gyrostat`](crate::dynamics::DynamicsError::Gyrostat). A zero `h`
    /// makes an ordinary rigid body.
    ///
    /// # Errors
    /// [`InertiaError::DimensionMismatch`] or [`InertiaError::NonFinite`] for a bivector of
    /// another dimension or with a non-finite component, or if ω becomes non-finite.
    pub fn with_gyrostatic_momentum(mut self, h: &Bivector) -> Result<Self, InertiaError> {
        self.set_gyrostatic_momentum(h)?;
        Ok(self)
    }

    /// Changes the gyrostatic momentum h (body's own axes) between steps, keeping the
    /// total momentum L: what a reaction-wheel controller does when it spins its wheels up
    /// or down (the body's ω = I⁻¹(L − h) takes the difference). See
    /// [`RigidBody::with_gyrostatic_momentum`].
    ///
    /// # Errors
    /// As [`RigidBody::with_gyrostatic_momentum`]; the body is then unchanged.
    pub fn set_gyrostatic_momentum(&mut self, h: &Bivector) -> Result<(), InertiaError> {
        let n = self.dim();
        check_body_dim("gyrostatic momentum", n, h.dim())?;
        check_finite("gyrostatic momentum", h)?;
        let h = self.principal_frame.inverse_rotate_bivector(h);
        let before = std::mem::replace(&mut self.gyrostatic, (h.max_abs() > 0.0).then_some(h));
        if let Err(e) = check_finite("angular velocity I⁻¹(L − h)", &self.omega()) {
            self.gyrostatic = before;
            return Err(e);
        }
        Ok(())
    }

    /// The gyrostatic momentum h in the principal frame (the frame of
    /// [`RigidBody::momentum`]); `None` for a rigid body.
    pub fn gyrostatic_momentum(&self) -> Option<&Bivector> {
        self.gyrostatic.as_ref()
    }

    /// Refuses a gyrostat where `what` assumes h = 0.
    pub(crate) fn refuse_gyrostat(&self, what: &'static str) -> Result<(), super::DynamicsError> {
        match self.gyrostatic {
            None => Ok(()),
            Some(_) => Err(super::DynamicsError::Gyrostat { what }),
        }
    }

    /// Returns the space-frame angular momentum L_s = R L R̃ (constant without torque).
    pub fn space_momentum(&self) -> Bivector {
        self.attitude.rotate_bivector(&self.momentum)
    }

    /// Returns the space-frame angular velocity ω_s = R ω R̃.
    pub fn space_omega(&self) -> Bivector {
        self.attitude.rotate_bivector(&self.omega())
    }

    /// Returns the kinetic energy T = ½⟨ω, L⟩ (of a gyrostat, ½⟨ω, L − h⟩ = ½⟨ω, I(ω)⟩,
    /// which with |L|² is conserved in free motion).
    pub fn energy(&self) -> f64 {
        match &self.gyrostatic {
            None => 0.5 * self.omega().inner(&self.momentum),
            Some(h) => 0.5 * self.omega().inner(&(&self.momentum - h)),
        }
    }

    /// Returns mutable access to the state for integrators (attitude, momentum).
    pub(crate) fn state_mut(&mut self) -> (&mut Attitude, &mut Bivector) {
        (&mut self.attitude, &mut self.momentum)
    }

    /// Replaces the state: the attitude (principal frame → space) and the body-frame momentum
    /// in the principal frame, as an integrator written outside the crate produces them.
    ///
    /// # Errors
    /// [`InertiaError::DimensionMismatch`]; [`InertiaError::NonFinite`] if the momentum or
    /// the attitude is not finite (the state is then left unchanged).
    pub fn set_state(
        &mut self,
        attitude: impl Into<Attitude>,
        momentum: Bivector,
    ) -> Result<(), InertiaError> {
        let attitude = attitude.into();
        let n = self.dim();
        for d in [attitude.dim(), momentum.dim()] {
            check_body_dim("attitude or momentum", n, d)?;
        }
        if !attitude.is_finite() {
            return Err(InertiaError::NonFinite {
                quantity: "attitude",
                index: None,
                value: f64::NAN,
            });
        }
        check_finite("angular momentum", &momentum)?;
        self.replace_state(attitude, momentum);
        Ok(())
    }

    /// Replaces the state without checks (integrators, exact solutions).
    pub(crate) fn replace_state(&mut self, attitude: Attitude, momentum: Bivector) {
        self.attitude = attitude;
        self.momentum = momentum;
    }
}

/// Refuses a bivector with a non-finite component, naming the first one.
/// Fails with [`InertiaError::DimensionMismatch`] for a `quantity` of dimension `found` given
/// to a body of dimension `expected`.
fn check_body_dim(
    quantity: &'static str,
    expected: usize,
    found: usize,
) -> Result<(), InertiaError> {
    if found == expected {
        return Ok(());
    }
    Err(InertiaError::DimensionMismatch {
        quantity,
        expected,
        found,
    })
}

fn check_finite(quantity: &'static str, b: &Bivector) -> Result<(), InertiaError> {
    match b.as_slice().iter().position(|x| !x.is_finite()) {
        Some(index) => Err(InertiaError::NonFinite {
            quantity,
            index: Some(index),
            value: b.as_slice()[index],
        }),
        None => Ok(()),
    }
}
