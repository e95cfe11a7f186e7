//! [`MotionError`]: what is wrong with a system of moving bodies, one variant per kind of
//! mistake, each with the numbers that locate it.

use thiserror::Error;

/// Why a moving body, a system or a step of one was refused.
///
/// Reached through [`DynamicsError::Motion`](crate::dynamics::DynamicsError::Motion), so that
/// code which builds a system and integrates it propagates everything with `?`. Every
/// variant names the quantity and, where there is one, the body or half-space by its index
/// in the system (numbered from 0).
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum MotionError {
    /// A number outside its range: a mass or semi-axis that is not positive, a negative
    /// friction coefficient, a restitution outside [0, 1], a non-finite offset.
    ///
    /// How to fix: give the quantity a value in the range the message states.
    #[error("{what} {value} is not {expected}")]
    OutOfRange {
        /// The quantity.
        what: &'static str,
        /// The value given.
        value: f64,
        /// The range it must be in, in words ("a finite positive number", "in [0, 1]").
        expected: &'static str,
    },
    /// A vector of the wrong length for the system's dimension.
    ///
    /// How to fix: give N components (the dimension of the bodies' inertia).
    #[error("{what} has {found} components for a body in {expected} dimensions")]
    WrongDimension {
        /// The quantity.
        what: &'static str,
        /// The dimension N of the bodies.
        expected: usize,
        /// The number of components given.
        found: usize,
    },
    /// A vector with a component that is not finite.
    #[error("{what} has the component {value}, which is not finite")]
    NonFinite {
        /// The quantity.
        what: &'static str,
        /// The first component that is not finite.
        value: f64,
    },
    /// A vector that must have a direction is zero (a half-space's normal).
    #[error("{what} is the zero vector")]
    ZeroVector {
        /// The quantity.
        what: &'static str,
    },
    /// A shape without points (a hull of no vertex).
    #[error("{what} has no point")]
    EmptyShape {
        /// The shape.
        what: &'static str,
    },
    /// A system needs at least one body.
    #[error("a system needs at least one body")]
    NoBody,
    /// Bodies of one system live in spaces of different dimension.
    #[error("body {body} is in {found} dimensions, body 0 in {expected}")]
    MixedDimensions {
        /// The first body of another dimension.
        body: usize,
        /// The dimension of body 0.
        expected: usize,
        /// The dimension of `body`.
        found: usize,
    },
    /// A forque, a joint or a shape refers to a body the system does not have.
    #[error("{what} refers to body {body}, but the system has {count} bodies (numbered from 0)")]
    NoSuchBody {
        /// What refers to it.
        what: &'static str,
        /// The index given.
        body: usize,
        /// How many bodies the system has.
        count: usize,
    },
    /// A joint holds a body to itself.
    #[error("joint {joint} holds body {body} to itself")]
    JointToItself {
        /// The joint, by index.
        joint: usize,
        /// The body.
        body: usize,
    },
    /// A body starts inside a half-space by more than the touching tolerance. Stepping it
    /// would push it out within one step, with the speed that takes (an ejection, not
    /// physics), so it is refused.
    ///
    /// How to fix: place the body on or above the plane (its lowest point at the plane's
    /// height, or higher).
    #[error(
        "body {body} starts {depth:.3e} inside half-space {half_space} (touching allows {tolerance:.1e}); place it on or above the plane"
    )]
    StartsInside {
        /// The body.
        body: usize,
        /// The half-space.
        half_space: usize,
        /// How far its deepest point is below the plane.
        depth: f64,
        /// The depth that still counts as touching.
        tolerance: f64,
    },
    /// Two bodies start overlapping by more than the touching tolerance: the first step
    /// would push them apart at whatever speed that takes.
    ///
    /// How to fix: place the bodies apart (or touching), or hold them by a joint (jointed
    /// bodies do not touch each other), or let one of them touch nothing.
    #[error(
        "bodies {a} and {b} start overlapping by {depth:.3e} (touching allows {tolerance:.1e}); place them apart"
    )]
    StartsOverlapping {
        /// The first body.
        a: usize,
        /// The second body.
        b: usize,
        /// How deep their shapes overlap.
        depth: f64,
        /// The depth that still counts as touching.
        tolerance: f64,
    },
    /// The system has half-spaces but no body has a contact shape: every body would pass
    /// through them.
    ///
    /// How to fix: build the bodies with [`MovingBody::from_parsed`](super::MovingBody::from_parsed)
    /// (a catalogue body brings its shape) or give them shapes with
    /// [`System::set_shape`](super::System::set_shape).
    #[error(
        "the system has {half_spaces} half-space(s) but no body has a contact shape, so nothing would touch them; give the bodies shapes"
    )]
    NothingTouches {
        /// How many half-spaces the system has.
        half_spaces: usize,
    },
    /// The integrator cannot take this system.
    ///
    /// How to fix: step systems with joints or contact by
    /// [`MotionSplitting`](super::MotionSplitting).
    #[error("{integrator} integrates forques only: joints and contact need MotionSplitting")]
    NeedsSplitting {
        /// The integrator.
        integrator: &'static str,
    },
    /// The velocity solve stopped before it converged, and the integrator was asked to
    /// refuse such steps ([`MotionSplitting::strict`](super::MotionSplitting::strict)).
    ///
    /// How to fix: a smaller step, fewer coupled contacts, or the default, which records
    /// the shortfall in [`MotionSplitting::solver_report`](super::MotionSplitting::solver_report)
    /// and goes on.
    #[error(
        "the contact and joint solve at t = {time} did not converge: {sweeps} sweeps, residual {residual:.3e}"
    )]
    SolveNotConverged {
        /// The time of the step.
        time: f64,
        /// The sweeps taken.
        sweeps: usize,
        /// The largest velocity change of the last sweep, relative to the contacts' speed.
        residual: f64,
    },
    /// A joint's equations could not be factored (its effective inverse mass is singular),
    /// and the integrator was asked to refuse such steps.
    #[error("the joints' solve at t = {time} met a singular matrix")]
    SingularJoints {
        /// The time of the step.
        time: f64,
    },
}

impl MotionError {
    /// `Ok` when `in_range` holds, otherwise [`MotionError::OutOfRange`] for `what` = `value`
    /// with the range `expected` in words.
    pub(crate) fn require(
        in_range: bool,
        what: &'static str,
        value: f64,
        expected: &'static str,
    ) -> Result<(), MotionError> {
        let out_of_range = MotionError::OutOfRange {
            what,
            value,
            expected,
        };
        in_range.then_some(()).ok_or(out_of_range)
    }
}
