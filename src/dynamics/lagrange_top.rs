//! The N-dimensional Lagrange top: a heavy top whose mass is symmetric about the axis through
//! the pivot and the centre of mass, and the integral that symmetry adds.
//!
//! With principal second moments J = (a, …, a, b, a, …, a) (b on the symmetry axis k) the
//! plane moments are 2a on the planes orthogonal to the axis and a + b on the planes that
//! contain it. Split the body-frame momentum as L = L₀ + L₁, L₀ in the planes orthogonal to
//! the axis (a bivector of so(N − 1)), L₁ in the planes e_i ∧ e_k. Then
//! ω = L₀/(2a) + L₁/(a + b) and
//!
//!   ω × L = (1/(a + b) − 1/(2a)) L₀ × L₁,
//!
//! which lies in the planes e_i ∧ e_k (so(N − 1) acts on the axis' complement), and so does the
//! gravity torque r ∧ F with r on the axis. So dL₀/dt = 0: every component of L₀ is
//! conserved, (N − 1)(N − 2)/2 of them. In 3D this is the spin about the symmetry axis, L₁₂
//! for the axis e₃ (Lagrange's case); the energy and the space-frame momentum in the planes
//! orthogonal to gravity, which every heavy top keeps, complete the integrals there.
//!
//! L₀ is linear in L and its rate vanishes identically, so every Runge–Kutta method (RKMK4,
//! Dopri5, Dop853, the implicit midpoint rule) keeps it to round-off; a splitting over the
//! planes does not (the flow of a plane e_i ∧ e_k turns L₀ into L₁), and keeps it only to
//! its order (`tests/dynamics/lagrange_top.rs`).

use super::torques::Gravity;
use super::{DynamicsError, RigidBody};
use crate::algebra::{AlgebraError, Bivector, pairs};

/// Relative tolerance on the equal second moments and on the offset's components off the axis.
const SYMMETRY_TOLERANCE: f64 = 1e-12;

/// A heavy top that is a Lagrange top, and its extra integral.
///
/// ```
/// use rotorflow::algebra::{Bivector, Rotor, Vector};
/// use rotorflow::dynamics::torques::Gravity;
/// use rotorflow::dynamics::{LagrangeTop, RigidBody};
/// use rotorflow::inertia::InertiaMap;
/// // 4D: J = (1, 1, 1, 0.4), symmetric about e₄, the centre of mass 0.3 up the axis.
/// let inertia = InertiaMap::from_principal_second_moments(&[1.0, 1.0, 1.0, 0.4])?;
/// let omega = Bivector::from_components(4, &[0.3, -0.2, 0.5, 0.1, 0.4, -0.6])?;
/// let body = RigidBody::from_body_velocity(inertia, Rotor::identity(4), &omega)?;
/// let gravity = Gravity {
///     weight: Vector::from_components(&[0.0, 0.0, -9.81, 0.0])?,
///     offset: Vector::from_components(&[0.0, 0.0, 0.0, 0.3])?,
/// };
/// let top = LagrangeTop::new(&body, &gravity)?;
/// assert_eq!(top.axis(), 3);
/// // The planes e₁₂, e₁₃ and e₂₃: 2a ω there.
/// assert_eq!(top.spin(&body).as_slice(), &[0.6, -0.4, 0.0, 0.2, 0.0, 0.0]);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LagrangeTop {
    axis: usize,
}

impl LagrangeTop {
    /// Recognises `body` under `gravity` as a Lagrange top: the principal second moments
    /// all equal (to 1e-12 relative) but for the one on axis k, and the centre of mass
    /// (`gravity.offset`, body frame) on that axis. A body with all moments equal is symmetric
    /// about any axis: k is then the axis of the offset.
    ///
    /// # Errors
    /// [`DynamicsError::NotALagrangeTop`] naming what breaks the symmetry;
    /// [`AlgebraError::DimensionMismatch`] if the offset's dimension differs from the body's.
    pub fn new(body: &RigidBody, gravity: &Gravity) -> Result<Self, DynamicsError> {
        let n = body.dim();
        if gravity.offset.dim() != n {
            return Err(AlgebraError::DimensionMismatch {
                left: n,
                right: gravity.offset.dim(),
            }
            .into());
        }
        let refuse = |reason: String| Err(DynamicsError::NotALagrangeTop { reason });
        let Some(j) = body.inertia().principal_second_moments() else {
            return refuse("the inertia map is not physical (no second moments)".into());
        };
        if !body.inertia().is_principal() {
            return refuse("the inertia map is not diagonal in the body frame".into());
        }
        let offset = gravity.offset.as_slice();
        let scale = offset.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if scale == 0.0 || !scale.is_finite() {
            return refuse(format!(
                "the centre of mass offset {offset:?} gives no axis"
            ));
        }
        let axis = (0..n)
            .max_by(|&a, &b| offset[a].abs().total_cmp(&offset[b].abs()))
            .expect("N ≥ 1");
        if let Some(i) = (0..n).find(|&i| i != axis && offset[i].abs() > SYMMETRY_TOLERANCE * scale)
        {
            return refuse(format!(
                "the centre of mass {offset:?} is off the axis e{} (component {} along e{})",
                axis + 1,
                offset[i],
                i + 1
            ));
        }
        let others: Vec<f64> = (0..n).filter(|&i| i != axis).map(|i| j[i]).collect();
        let a = others.first().copied().unwrap_or(j[axis]);
        let size = j.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if let Some(&x) = others
            .iter()
            .find(|&&x| (x - a).abs() > SYMMETRY_TOLERANCE * size)
        {
            return refuse(format!(
                "the second moments {j:?} differ off the axis e{} ({a} and {x})",
                axis + 1
            ));
        }
        Ok(LagrangeTop { axis })
    }

    /// The symmetry axis k (0-based: the body axis e_(k+1)).
    pub fn axis(&self) -> usize {
        self.axis
    }

    /// The conserved body-frame momentum L₀: the components of L in the planes orthogonal to
    /// the axis, the others zero (a bivector of the same dimension as the body's).
    ///
    /// # Panics
    /// If the body's dimension is not the one the top was recognised in (the axis is then
    /// out of range or means something else).
    pub fn spin(&self, body: &RigidBody) -> Bivector {
        let n = body.dim();
        assert!(
            self.axis < n,
            "rotorflow: a Lagrange top of another dimension"
        );
        let mut spin = body.momentum().clone();
        for ((i, j), c) in pairs(n).zip(spin.as_mut_slice()) {
            if i == self.axis || j == self.axis {
                *c = 0.0;
            }
        }
        spin
    }
}
