//! [`EmbeddedTop`]: the exact motion of a body of dimension N ≥ 3 whose angular momentum
//! stays in the 3-space of three principal axes (the paper's sets S₁ … S₄, eqs. 59–64),
//! built on the 3D [`AsymmetricTop`].

use super::top3d::{AsymmetricTop, rotor_from_parts};
use crate::algebra::{Bivector, Rotor, pair_index, pairs};
use crate::dynamics::{Attitude, DynamicsError, NoClosedFormReason, RigidBody};
use nalgebra::DMatrix;

/// A 3D exact motion inside a body of dimension N ≥ 3 (see [`AsymmetricTop::embedded`]).
///
/// L(t) is the embedded 3D momentum, and R(t) = R(0) · U(t) with U(t) ∈ Spin(3) the 3D
/// attitude (started at the identity) mapped into the subalgebra of the three axes.
#[derive(Clone, Debug)]
pub struct EmbeddedTop {
    top: AsymmetricTop,
    axes: [usize; 3],
    body: RigidBody,
}

impl EmbeddedTop {
    pub(super) fn new(body: &RigidBody, axes: [usize; 3]) -> Result<Self, DynamicsError> {
        let n = body.dim();
        if n < 3 {
            return Err(DynamicsError::no_closed_form(
                NoClosedFormReason::DimensionTooSmall {
                    form: "a 3D subspace",
                    minimum: 3,
                    found: n,
                },
            ));
        }
        if axes.iter().any(|&a| a >= n)
            || axes[0] == axes[1]
            || axes[0] == axes[2]
            || axes[1] == axes[2]
        {
            return Err(DynamicsError::no_closed_form(
                NoClosedFormReason::InvalidAxes { axes, dim: n },
            ));
        }
        let diag = body.inertia().diagonal_plane_moments().ok_or_else(|| {
            DynamicsError::no_closed_form(NoClosedFormReason::NotDiagonalOnPlanes)
        })?;
        let l = body.momentum();
        let inside = |i: usize, j: usize| axes.contains(&i) && axes.contains(&j);
        for (k, (i, j)) in pairs(n).enumerate() {
            let v = l.as_slice()[k];
            if !inside(i, j) && v != 0.0 {
                return Err(DynamicsError::no_closed_form(
                    NoClosedFormReason::MomentumOutsideSubspace {
                        plane: (i, j),
                        component: v,
                        axes,
                    },
                ));
            }
        }
        let sub = [(0, 1), (0, 2), (1, 2)];
        let mut moments = [0.0; 3];
        let mut l3 = [0.0; 3];
        for (slot, &(p, q)) in sub.iter().enumerate() {
            let (a, b) = (axes[p], axes[q]);
            moments[slot] = diag[pair_index(n, a.min(b), a.max(b))];
            l3[slot] = l.get(a, b);
        }
        let inertia = crate::inertia::InertiaMap::from_plane_moments(&moments)
            .map_err(|e| DynamicsError::no_closed_form(NoClosedFormReason::SubspaceBody(e)))?;
        let l3 = Bivector::from_components(3, &l3)?;
        let body3 = RigidBody::from_body_momentum(inertia, Rotor::identity(3), &l3)
            .map_err(|e| DynamicsError::no_closed_form(NoClosedFormReason::SubspaceBody(e)))?;
        Ok(EmbeddedTop {
            top: AsymmetricTop::new(&body3)?,
            axes,
            body: body.clone(),
        })
    }

    /// Returns the 3D solution (plane moments (I(a₀a₁), I(a₀a₂), I(a₁a₂)), identity
    /// attitude at t = 0).
    pub fn top3d(&self) -> &AsymmetricTop {
        &self.top
    }

    /// Returns the axes of the subspace.
    pub fn axes(&self) -> [usize; 3] {
        self.axes
    }

    /// Returns the N-dimensional body-frame momentum L(t) (zero outside the subspace).
    ///
    /// # Errors
    /// As [`AsymmetricTop::momentum_at`].
    pub fn momentum_at(&self, t: f64) -> Result<Bivector, DynamicsError> {
        Ok(self.embed_bivector(&self.top.momentum_at(t)?))
    }

    /// Returns the N-dimensional body-frame angular velocity ω(t).
    ///
    /// # Errors
    /// As [`AsymmetricTop::momentum_at`].
    pub fn omega_at(&self, t: f64) -> Result<Bivector, DynamicsError> {
        Ok(self.embed_bivector(&self.top.omega_at(t)?))
    }

    /// Returns the attitude R(t) = R(0) · U(t), continuous in t, with R(0) the body's (a
    /// rotor for N ≤ 4, an SO(N) matrix above; see [`Attitude`]).
    ///
    /// # Errors
    /// As [`AsymmetricTop::attitude_at`].
    pub fn attitude_at(&self, t: f64) -> Result<Attitude, DynamicsError> {
        self.embed_rotor(&self.top.attitude_at(t)?)
    }

    /// R(0) · U with the 3D rotor U mapped into the subalgebra (or, for N > 4, the matrix
    /// block) of the axes.
    fn embed_rotor(&self, u: &Rotor) -> Result<Attitude, DynamicsError> {
        let n = self.body.dim();
        let factor = if n <= Attitude::ROTOR_MAX_DIM {
            let b = self.embed_bivector(&u.bivector_part());
            Attitude::from(rotor_from_parts(u.scalar(), &b)?)
        } else {
            let q3 = u.to_matrix();
            let mut q = DMatrix::identity(n, n);
            for (r, &ar) in self.axes.iter().enumerate() {
                for (c, &ac) in self.axes.iter().enumerate() {
                    q[(ar, ac)] = q3[(r, c)];
                }
            }
            Attitude::from_matrix(&q)?
        };
        Ok(self.body.principal_frame_attitude().compose(&factor))
    }

    /// Returns the N-dimensional body at time t.
    ///
    /// # Errors
    /// As [`EmbeddedTop::attitude_at`].
    pub fn body_at(&self, t: f64) -> Result<RigidBody, DynamicsError> {
        let (u, l) = self.top.state_at(t)?;
        let mut b = self.body.clone();
        b.replace_state(self.embed_rotor(&u)?, self.embed_bivector(&l));
        Ok(b)
    }

    /// Returns the period of L(t), as [`AsymmetricTop::period`].
    pub fn period(&self) -> Option<f64> {
        self.top.period()
    }

    /// Maps a 3D bivector (12, 13, 23) onto the planes of the axes.
    fn embed_bivector(&self, b3: &Bivector) -> Bivector {
        let n = self.body.dim();
        let mut out = Bivector::zero(n);
        let [a0, a1, a2] = self.axes;
        let c = b3.as_slice();
        out.set(a0, a1, c[0]);
        out.set(a0, a2, c[1]);
        out.set(a1, a2, c[2]);
        out
    }
}
