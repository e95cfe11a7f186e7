//! Closed-form torque-free motion: the references every integrator is measured against.
//!
//! | body | module | what is exact |
//! |---|---|---|
//! | any N, at most two distinct principal values Jᵢ (isotropic; the paper's §7.1, §7.2, §7.3; the symmetric top) | [`two_moments`] | L(t) = S L₀ S̃, R(t) = R₀ exp(−½αtL₀) exp(−½tΩ): conjugations and products of exponentials of constant bivectors |
//! | any body in a steady rotation (ω × L = 0: disjoint principal planes, the 4D double rotation, isoclinic or not) | [`two_moments`] | R(t) = R₀ exp(−½tω) |
//! | N = 3, any body (the free asymmetric top) | [`top3d`] | L(t) by Jacobi sn, cn, dn on both sides of the separatrix and on it; R(t) through Π(n; am u \| m) |
//! | N ≥ 4, L in the span of three principal axes (the paper's S sets, eqs. 59–64) | [`embedded::EmbeddedTop`] | the 3D top with the body's plane moments |
//! | the paper's printed §7 formulas (eqs. 107–134) | [`paper`] | checked against the above; errata in `book/src/errata/section7.md` |
//!
//! [`ExactSolution::new`] (or [`RigidBody::exact_solution`]) picks the right one, or says why
//! there is none.

use crate::algebra::Bivector;
use crate::dynamics::{Attitude, DynamicsError, NoClosedFormReason, RigidBody};

pub mod embedded;
pub mod paper;
pub mod top3d;
pub mod two_moments;

use embedded::EmbeddedTop;
use top3d::AsymmetricTop;
use two_moments::TwoMomentSolution;

/// The closed-form free motion of a body, whichever form applies.
///
/// ```
/// use rotorflow::prelude::*;
/// use rotorflow::dynamics::RigidBody;
/// // The paper's §7.2 body in 4D: three equal principal values, one different.
/// let inertia = InertiaMap::from_principal_second_moments(&[1.0, 1.0, 1.0, 4.0])?;
/// let omega = Bivector::from_components(4, &[0.3, -0.5, 0.8, 0.4, 0.2, -0.6])?;
/// let body = RigidBody::from_body_velocity(inertia, Rotor::identity(4), &omega)?;
/// let exact = body.exact_solution()?;
/// let later = exact.body_at(10.0)?;
/// assert!((later.energy() - body.energy()).abs() < 1e-14);
/// assert!((&later.space_momentum() - &body.space_momentum()).max_abs() < 1e-13);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
#[non_exhaustive]
pub enum ExactSolution {
    /// At most two distinct principal values (any N), or a steady rotation.
    TwoMoments(Box<TwoMomentSolution>),
    /// The free 3D top.
    AsymmetricTop(Box<AsymmetricTop>),
    /// A 3D motion inside an N-dimensional body.
    Embedded(Box<EmbeddedTop>),
}

impl ExactSolution {
    /// Returns the closed form of the free motion of `body`.
    ///
    /// Tried in order: N = 3 → the asymmetric top; at most two distinct principal values or
    /// a steady rotation → [`TwoMomentSolution`]; L in the span of at most three principal
    /// axes (exact zeros elsewhere) → the embedded 3D top.
    ///
    /// # Errors
    /// [`DynamicsError::NoClosedForm`] with the reasons of every form tried.
    pub fn new(body: &RigidBody) -> Result<Self, DynamicsError> {
        body.refuse_gyrostat("the closed-form motion")?;
        let mut reasons = Vec::new();
        if body.dim() == 3 {
            match AsymmetricTop::new(body) {
                Ok(top) => return Ok(ExactSolution::AsymmetricTop(Box::new(top))),
                Err(DynamicsError::NoClosedForm { reasons: why }) => reasons.extend(why),
                Err(e) => return Err(e),
            }
        }
        match TwoMomentSolution::new(body) {
            Ok(s) => return Ok(ExactSolution::TwoMoments(Box::new(s))),
            Err(DynamicsError::NoClosedForm { reasons: why }) => reasons.extend(why),
            Err(e) => return Err(e),
        }
        if body.dim() > 3 {
            match support_axes(body.momentum()) {
                Some(axes) => match AsymmetricTop::embedded(body, axes) {
                    Ok(top) => return Ok(ExactSolution::Embedded(Box::new(top))),
                    Err(DynamicsError::NoClosedForm { reasons: why }) => reasons.extend(why),
                    Err(e) => return Err(e),
                },
                None => reasons.push(NoClosedFormReason::MomentumSpansMoreThanThreeAxes),
            }
        }
        Err(DynamicsError::NoClosedForm { reasons })
    }

    /// Returns the name of the form used ("two moments", "asymmetric top", "embedded 3D top").
    pub fn name(&self) -> &'static str {
        match self {
            ExactSolution::TwoMoments(_) => "two moments",
            ExactSolution::AsymmetricTop(_) => "asymmetric top",
            ExactSolution::Embedded(_) => "embedded 3D top",
        }
    }

    /// Returns the body-frame angular momentum L(t) (principal frame).
    ///
    /// # Errors
    /// [`DynamicsError::NonFiniteArgument`] for a non-finite t (or one so large that the phase
    /// overflows).
    pub fn momentum_at(&self, t: f64) -> Result<Bivector, DynamicsError> {
        match self {
            ExactSolution::TwoMoments(s) => s.momentum_at(t),
            ExactSolution::AsymmetricTop(s) => s.momentum_at(t),
            ExactSolution::Embedded(s) => s.momentum_at(t),
        }
    }

    /// Returns the body-frame angular velocity ω(t) (principal frame).
    ///
    /// # Errors
    /// As [`ExactSolution::momentum_at`].
    pub fn omega_at(&self, t: f64) -> Result<Bivector, DynamicsError> {
        match self {
            ExactSolution::TwoMoments(s) => s.omega_at(t),
            ExactSolution::AsymmetricTop(s) => s.omega_at(t),
            ExactSolution::Embedded(s) => s.omega_at(t),
        }
    }

    /// Returns the attitude R(t) (principal frame → space), equal to the body's at t = 0.
    ///
    /// # Errors
    /// As [`ExactSolution::momentum_at`].
    pub fn attitude_at(&self, t: f64) -> Result<Attitude, DynamicsError> {
        match self {
            ExactSolution::TwoMoments(s) => s.attitude_at(t),
            ExactSolution::AsymmetricTop(s) => Ok(s.attitude_at(t)?.into()),
            ExactSolution::Embedded(s) => s.attitude_at(t),
        }
    }

    /// Returns the body (same inertia) at time t.
    ///
    /// # Errors
    /// As [`ExactSolution::momentum_at`].
    pub fn body_at(&self, t: f64) -> Result<RigidBody, DynamicsError> {
        match self {
            ExactSolution::TwoMoments(s) => s.body_at(t),
            ExactSolution::AsymmetricTop(s) => s.body_at(t),
            ExactSolution::Embedded(s) => s.body_at(t),
        }
    }
}

impl RigidBody {
    /// Returns the closed-form free motion of this body when it has one (see
    /// [`ExactSolution::new`]).
    ///
    /// # Errors
    /// [`DynamicsError::NoClosedForm`] saying why none exists.
    pub fn exact_solution(&self) -> Result<ExactSolution, DynamicsError> {
        ExactSolution::new(self)
    }
}

/// The (at most three, padded to three) axes that the non-zero components of `l` touch.
fn support_axes(l: &Bivector) -> Option<[usize; 3]> {
    let n = l.dim();
    let mut used = vec![false; n];
    for (k, (i, j)) in crate::algebra::pairs(n).enumerate() {
        if l.as_slice()[k] != 0.0 {
            used[i] = true;
            used[j] = true;
        }
    }
    let mut axes: Vec<usize> = (0..n).filter(|&i| used[i]).collect();
    if axes.len() > 3 {
        return None;
    }
    let missing = 3 - axes.len();
    axes.extend((0..n).filter(|&i| !used[i]).take(missing));
    axes.sort_unstable();
    Some([axes[0], axes[1], axes[2]])
}
