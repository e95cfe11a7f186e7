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
            if d != n {
                return Err(InertiaError::DimensionMismatch {
                    quantity: "attitude or momentum",
                    expected: n,
                    found: d,
                });
            }
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

    /// Returns the attitude of the principal frame (principal axes → space).
    #[deprecated(
        note = "use `principal_frame_attitude` (principal axes → space) or `body_axes_attitude` (the body's own axes → space, to render it)"
    )]
    pub fn attitude(&self) -> &Attitude {
        self.principal_frame_attitude()
    }

    /// Returns the attitude of the body's own axes.
    #[deprecated(note = "use `body_axes_attitude`")]
    pub fn attitude_of_own_axes(&self) -> Attitude {
        self.body_axes_attitude()
    }

    /// Returns the body-frame angular momentum L (principal frame).
    pub fn momentum(&self) -> &Bivector {
        &self.momentum
    }

    /// Returns the body-frame angular velocity ω = I⁻¹(L) (principal frame).
    pub fn omega(&self) -> Bivector {
        self.inertia.apply_inverse(&self.momentum)
    }

    /// Returns the space-frame angular momentum L_s = R L R̃ (constant without torque).
    pub fn space_momentum(&self) -> Bivector {
        self.attitude.rotate_bivector(&self.momentum)
    }

    /// Returns the space-frame angular velocity ω_s = R ω R̃.
    pub fn space_omega(&self) -> Bivector {
        self.attitude.rotate_bivector(&self.omega())
    }

    /// Returns the kinetic energy T = ½⟨ω, L⟩.
    pub fn energy(&self) -> f64 {
        0.5 * self.omega().inner(&self.momentum)
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
            if d != n {
                return Err(InertiaError::DimensionMismatch {
                    quantity: "attitude or momentum",
                    expected: n,
                    found: d,
                });
            }
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
