//! [`DynamicsError`], the one error type of the dynamics layer (integrators, sampled runs and
//! closed forms), and [`NoClosedFormReason`], why a body has no closed-form motion.

use crate::algebra::AlgebraError;
use crate::dynamics::motion::MotionError;
use crate::dynamics::motion::shape::ShapeError;
use crate::inertia::InertiaError;
use crate::special::EllipticError;
use thiserror::Error;

/// Why a step, a sampled run or a closed form could not be computed.
///
/// One type for the whole layer, so that code which integrates a body and compares it with
/// its closed form propagates both with `?`.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum DynamicsError {
    /// The integrator needs an inertia map that is diagonal on the basis planes.
    ///
    /// How to fix: build the body from a physical inertia (it is moved to its principal
    /// frame), or use [`Rkmk4`](crate::dynamics::Rkmk4), which takes any map.
    #[error(
        "{integrator} needs an inertia diagonal on the basis planes (a general SPD map is not)"
    )]
    UnsupportedInertia {
        /// The integrator.
        integrator: &'static str,
    },
    /// The integrator needs a physical inertia map, I(ω) = Jω + ωJ with a mass tensor J.
    ///
    /// How to fix: build the inertia from a body, a mass tensor or principal second moments
    /// (a map given by plane moments or a general SPD matrix has no J), or use
    /// [`Rkmk4`](crate::dynamics::Rkmk4), which takes any map.
    #[error(
        "{integrator} needs a physical inertia map I(ω) = Jω + ωJ (this map has no mass tensor J)"
    )]
    NonPhysicalInertia {
        /// The integrator.
        integrator: &'static str,
    },
    /// The discrete step has no solution near the identity: the step is too large for the
    /// angular momentum (the Moser–Veselov equation hM = UJ − JUᵀ needs |hM|_F ≤ 2|J|_F,
    /// and its Newton iteration diverged or met a singular matrix).
    ///
    /// How to fix: reduce the step (h·|ω| well below 1).
    #[error(
        "{integrator}: no rotation near the identity solves the step at t = {time} (h = {step:e}, residual {residual:e}); reduce the step"
    )]
    NoDiscreteSolution {
        /// The integrator.
        integrator: &'static str,
        /// The time of the step.
        time: f64,
        /// The step size.
        step: f64,
        /// The last absolute residual of the equation (infinite when the necessary bound
        /// already fails).
        residual: f64,
    },
    /// The requested sampling makes no sense.
    ///
    /// How to fix: a positive finite step, and sample times that increase from 0.
    #[error("invalid sampling: {reason}")]
    InvalidSampling {
        /// What is wrong.
        reason: &'static str,
    },
    /// The implicit solve did not converge within its iteration bound.
    ///
    /// How to fix: reduce the step (fixed-point iteration needs h·|ω| ≲ 1) or raise the bound.
    #[error(
        "implicit solve did not converge at t = {time}: {iterations} iterations, residual {residual:e}"
    )]
    SolverDidNotConverge {
        /// The time of the step.
        time: f64,
        /// Iterations taken.
        iterations: usize,
        /// The last relative change of the momentum.
        residual: f64,
    },
    /// The adaptive step size fell below what the arithmetic can resolve.
    ///
    /// How to fix: loosen the tolerances (a stiff problem needs an implicit method).
    #[error("step size {step:e} too small at t = {time}: the tolerance cannot be met")]
    StepTooSmall {
        /// The time reached.
        time: f64,
        /// The step that would be needed.
        step: f64,
    },
    /// The adaptive integrator needed more internal steps than allowed.
    ///
    /// How to fix: raise the bound
    /// ([`Dopri5::with_max_steps`](crate::dynamics::Dopri5::with_max_steps)) or loosen the
    /// tolerances.
    #[error("more than {steps} internal steps needed before t = {time}")]
    TooManySteps {
        /// The time reached.
        time: f64,
        /// The step count.
        steps: usize,
    },
    /// The tolerances of an adaptive integrator cannot be met or make no sense.
    ///
    /// How to fix: finite, non-negative tolerances, at least one of them positive.
    #[error(
        "invalid tolerances rtol = {rtol:e}, atol = {atol:e}: both must be finite and non-negative, one positive"
    )]
    InvalidTolerance {
        /// The relative tolerance given.
        rtol: f64,
        /// The absolute tolerance given.
        atol: f64,
    },
    /// The state became NaN or infinite during a step.
    ///
    /// How to fix: reduce the step; check the torque for singularities.
    #[error("the state is no longer finite at t = {time}")]
    NonFinite {
        /// The time of the step that failed.
        time: f64,
    },
    /// An argument or a state handed to a closed form is not finite (or a time so large that
    /// the phase overflows).
    #[error("non-finite {name}: {value}")]
    NonFiniteArgument {
        /// Which argument.
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// The body has no closed-form motion in rotorflow; `reasons` says, for every form tried,
    /// which condition fails.
    ///
    /// How to fix: integrate numerically ([`Dopri5`](crate::dynamics::Dopri5) at a tight
    /// tolerance).
    #[error("no closed form: {}", join_reasons(reasons))]
    NoClosedForm {
        /// Why each form tried does not apply (at least one).
        reasons: Vec<NoClosedFormReason>,
    },
    /// A special function failed (not expected for valid bodies).
    #[error(transparent)]
    Special(#[from] EllipticError),
    /// An algebra operation failed (e.g. N above the rotor limit).
    #[error(transparent)]
    Algebra(#[from] AlgebraError),
    /// A moving body, a system of them or one of its steps was refused: the variant names
    /// the quantity and the body or half-space.
    #[error(transparent)]
    Motion(#[from] MotionError),
    /// A shape or a detection query was refused.
    #[error(transparent)]
    Shape(#[from] ShapeError),
    /// The integrator or closed form assumes a rigid body and was given a gyrostat.
    ///
    /// How to fix: integrate gyrostats with `Rkmk4`, `Dopri5`, `Dop853` or `Midpoint`.
    #[error(
        "{what} assumes a rigid body without internal rotors; integrate a gyrostat with rk4, dopri5, dop853 or midpoint"
    )]
    Gyrostat {
        /// What refused it.
        what: &'static str,
    },
    /// A heavy top is not a Lagrange top ([`LagrangeTop::new`](crate::dynamics::LagrangeTop::new)).
    ///
    /// How to fix: second moments equal on every body axis but one, and the centre of mass
    /// on that axis.
    #[error("not a Lagrange top: {reason}")]
    NotALagrangeTop {
        /// What breaks the symmetry.
        reason: String,
    },
    /// The rotation part of a moving body could not be built.
    #[error(transparent)]
    Inertia(#[from] InertiaError),
    /// An integrator option that does not apply: a preprocessing order without coefficients,
    /// or a body of a dimension the option is not defined in.
    ///
    /// How to fix: what `reason` says (the preprocessed Moser–Veselov step takes orders 2, 4
    /// and 6 and bodies in 3D; [`MoserVeselov::new`](crate::dynamics::MoserVeselov::new)
    /// takes any N).
    #[error("{integrator}: {reason}")]
    UnsupportedOption {
        /// The integrator.
        integrator: &'static str,
        /// What does not apply, and what would.
        reason: String,
    },
}

impl DynamicsError {
    /// The error for one reason.
    pub(crate) fn no_closed_form(reason: NoClosedFormReason) -> Self {
        DynamicsError::NoClosedForm {
            reasons: vec![reason],
        }
    }

    /// `Err(NoClosedForm(WrongDimension))` unless the dimension `found` is the `expected` one
    /// of the closed form `form`.
    pub(crate) fn check_closed_form_dim(
        form: &'static str,
        expected: usize,
        found: usize,
    ) -> Result<(), Self> {
        let reason = NoClosedFormReason::WrongDimension {
            form,
            expected,
            found,
        };
        if found == expected {
            Ok(())
        } else {
            Err(DynamicsError::no_closed_form(reason))
        }
    }
}

fn join_reasons(reasons: &[NoClosedFormReason]) -> String {
    let texts: Vec<String> = reasons.iter().map(ToString::to_string).collect();
    texts.join("; ")
}

/// Why a closed form does not apply to a body (one of the
/// [`DynamicsError::NoClosedForm`] reasons). Plane and axis indices are 0-based; the messages
/// print them 1-based, as text does everywhere in rotorflow.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum NoClosedFormReason {
    /// The form exists in one dimension only.
    #[error("{form} needs N = {expected}, got N = {found}")]
    WrongDimension {
        /// The closed form ("the asymmetric top", "the paper's §7").
        form: &'static str,
        /// The dimension it needs.
        expected: usize,
        /// The body's dimension.
        found: usize,
    },
    /// The form needs at least `minimum` dimensions.
    #[error("{form} needs N ≥ {minimum}, got N = {found}")]
    DimensionTooSmall {
        /// The closed form.
        form: &'static str,
        /// The smallest dimension it accepts.
        minimum: usize,
        /// The body's dimension.
        found: usize,
    },
    /// The axes of an embedded 3D motion are out of range or repeated.
    #[error(
        "axes {} must be three distinct indices from 1 to N = {dim}",
        one_based(axes)
    )]
    InvalidAxes {
        /// The axes given (0-based).
        axes: [usize; 3],
        /// The body's dimension.
        dim: usize,
    },
    /// The inertia map is not diagonal on the basis planes (a general map with off-diagonal
    /// terms), so neither the principal values nor an invariant subspace can be read off.
    #[error("the inertia map is not diagonal on the basis planes")]
    NotDiagonalOnPlanes,
    /// In N = 2 the single plane moment I₁₂ does not determine J₁ and J₂.
    #[error("N = 2: the split of I₁₂ into J₁ + J₂ is not unique")]
    AmbiguousSplit,
    /// The plane moments are not the sums Jᵢ + Jⱼ of principal values (a map given by plane
    /// moments that no mass distribution has).
    #[error(
        "the plane moments are not of the form Jᵢ + Jⱼ (plane e{}e{}: {moment} vs {pair_sum})",
        plane.0 + 1,
        plane.1 + 1
    )]
    NotPairSums {
        /// The first plane (i, j), 0-based, where I(eᵢ∧eⱼ) ≠ Jᵢ + Jⱼ.
        plane: (usize, usize),
        /// Its plane moment.
        moment: f64,
        /// Jᵢ + Jⱼ from the other planes.
        pair_sum: f64,
    },
    /// The mass tensor has more than two distinct principal values.
    #[error(
        "more than two distinct principal values J = {values:?} (relative tolerance {tolerance:e})"
    )]
    TooManyDistinctValues {
        /// The principal values Jᵢ.
        values: Vec<f64>,
        /// The relative tolerance under which two values count as equal.
        tolerance: f64,
    },
    /// The rotation is not steady: ω × L ≠ 0.
    #[error("the rotation is not steady (|ω × L| = {commutator:.3e} > {tolerance:.1e} |ω| |L|)")]
    NotSteady {
        /// |ω × L|.
        commutator: f64,
        /// The relative tolerance under which the rotation counts as steady.
        tolerance: f64,
    },
    /// L has a component outside the 3-space of the chosen axes.
    #[error(
        "L has the component {component} in the plane e{}e{}, outside the subspace of axes {}",
        plane.0 + 1,
        plane.1 + 1,
        one_based(axes)
    )]
    MomentumOutsideSubspace {
        /// The plane (i, j), 0-based.
        plane: (usize, usize),
        /// L's component in it.
        component: f64,
        /// The axes of the subspace (0-based).
        axes: [usize; 3],
    },
    /// L touches more than three principal axes, so it lies in no invariant 3-space.
    #[error("the momentum spans more than three principal axes (no 3D embedding)")]
    MomentumSpansMoreThanThreeAxes,
    /// The three plane moments of a 3D motion are not all positive and finite.
    #[error("plane moments {moments:?} must be positive and finite")]
    NonPositivePlaneMoments {
        /// The plane moments (I₁₂, I₁₃, I₂₃).
        moments: [f64; 3],
    },
    /// The plane moments of an embedded 3D motion do not make a 3D body.
    #[error("the 3D body of the subspace is refused: {0}")]
    SubspaceBody(InertiaError),
    /// The paper's parameter κ is not a positive half-axis.
    #[error("κ = {kappa} must be a positive half-axis")]
    NonPositiveKappa {
        /// κ as given.
        kappa: f64,
    },
    /// The paper's §7.2 constants c₄ … c₆ (its eqs. 116–118) are undefined: c₁ = c₂ = c₃ = 0,
    /// and then ω is constant.
    #[error("c₁ = c₂ = c₃ = 0: eqs. 116–118 do not define c₄ … c₆ (ω is constant)")]
    PaperConstantsUndefined,
}

fn one_based(axes: &[usize; 3]) -> String {
    format!("({}, {}, {})", axes[0] + 1, axes[1] + 1, axes[2] + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_closed_form_prints_every_reason_on_one_line() {
        let e = DynamicsError::NoClosedForm {
            reasons: vec![
                NoClosedFormReason::TooManyDistinctValues {
                    values: vec![1.0, 2.0, 3.0],
                    tolerance: 1e-12,
                },
                NoClosedFormReason::MomentumSpansMoreThanThreeAxes,
            ],
        };
        let text = e.to_string();
        assert_eq!(
            text,
            "no closed form: more than two distinct principal values J = [1.0, 2.0, 3.0] \
             (relative tolerance 1e-12); the momentum spans more than three principal axes \
             (no 3D embedding)"
        );
        assert!(!text.contains('\n'));
    }

    #[test]
    fn indices_print_one_based() {
        let r = NoClosedFormReason::MomentumOutsideSubspace {
            plane: (0, 3),
            component: 0.5,
            axes: [0, 1, 2],
        };
        assert_eq!(
            r.to_string(),
            "L has the component 0.5 in the plane e1e4, outside the subspace of axes (1, 2, 3)"
        );
    }
}
