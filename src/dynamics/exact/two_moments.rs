//! Closed-form free motion of a body whose mass tensor has at most two distinct principal
//! values, in any dimension N, and of steady rotations of any body.
//!
//! # The body
//! In the principal frame J = diag(J₁, …, J_N). Split the axes into two sets: A, where
//! Jᵢ = a, and B, where Jᵢ = b (B may be empty: the isotropic body). The plane moments
//! I(eᵢ∧eⱼ) = Jᵢ + Jⱼ take three values: 2a on planes inside A, 2b
//! inside B, a + b on the mixed planes. This covers the paper's §7.1 (a = b, eqs. 107–108),
//! §7.2 (three equal, one different, eqs. 109–120), §7.3 (two equal pairs, eqs. 121–134),
//! the symmetric top of 3D and all their analogues in any N.
//!
//! # Derivation
//! Write any bivector by blocks, X = X_AA + X_AB + X_BB, where X_AA has only components
//! Xᵢⱼ with i, j ∈ A, X_BB only i, j ∈ B, and X_AB the mixed ones. From
//! \[L\] = J\[ω\] + \[ω\]J,
//!
//! L_AA = 2a ω_AA,   L_BB = 2b ω_BB,   L_AB = (a + b) ω_AB,
//!
//! so that, with α = 1/(a + b) and ν = (b − a)/(a + b),
//!
//! ω = α L + Ω,   Ω = ν (ω_AA − ω_BB) = (ν/2a) L_AA − (ν/2b) L_BB.
//!
//! The commutator of bivectors respects the blocks: \[AA, AA\] ⊂ AA, \[BB, BB\] ⊂ BB,
//! \[AA, BB\] = 0, \[AA, AB\] ⊂ AB, \[BB, AB\] ⊂ AB, \[AB, AB\] ⊂ AA + BB. Euler's equation
//! dL/dt = ω × L = α L × L + Ω × L = Ω × L then has a right-hand side in the AB block only
//! (Ω × L_AA and Ω × L_BB vanish: L_AA commutes with itself and with L_BB). Hence L_AA and
//! L_BB are constant, Ω is constant, and the flow is **linear with a constant generator**:
//!
//! dL/dt = Ω × L   ⟹   L(t) = S(t) L(0) S̃(t),   S(t) = exp(½ t Ω),
//!
//! because d/dt (exp(tB) X exp(−tB)) = BX − XB = 2 B × X. The angular velocity follows as
//! ω(t) = α L(t) + Ω = S(t) ω(0) S̃(t).
//!
//! For the attitude, dR/dt = −½ R ω (the Conventions chapter of the rotorflow book). Put Q = R S. Then
//! dQ/dt = −½ R ω S + ½ R S Ω = −½ Q (S̃ ω S − Ω) = −½ Q (α L(0) + Ω − Ω) = −½ α Q L(0), a
//! constant generator again, so Q(t) = R(0) exp(−½ α t L(0)) and
//!
//! **R(t) = R(0) · exp(−½ α t L(0)) · exp(−½ t Ω)**
//!       = exp(−½ α t L_s) · R(0) · exp(−½ t Ω),   L_s = R(0) L(0) R̃(0).
//!
//! # Which rotor does what
//! - S(t) = exp(½ t Ω) moves the momentum through the **body**: L(t) = S L(0) S̃. Ω rotates
//!   the axes of A among themselves with the rate ν ω_AA and those of B with −ν ω_BB; the
//!   mixed block L_AB is carried along, the blocks L_AA and L_BB stand still. Ω = 0 for the
//!   isotropic body (a = b) and when ω_AA = ω_BB = 0.
//! - exp(−½ α t L_s) turns the body in **space** uniformly about the constant space-frame
//!   momentum L_s, at the rate α = 1/(a + b) per unit of each of its plane magnitudes.
//! - exp(−½ t Ω) (= S̃, applied on the body side) turns the body relative to that uniform
//!   rotation; together: R(t) = exp(−½ α t L_s) R(0) S̃(t).
//!
//! For N = 3 with A = {1, 2} this is the symmetric top: Ω = ν ω₁₂ e₁₂ is the body-frame
//! precession at the classical rate (I₁ − I₃) Ω₃ / I₁, and α L_s the space precession.
//!
//! # Steady rotations of any body
//! When ω(0) × L(0) = 0, L and ω are constant and R(t) = R(0) exp(−½ t ω(0)). This is the
//! same formula with α = 0 and Ω = ω(0). For a body with all Jᵢ distinct it happens exactly
//! when \[ω\]² commutes with J: ω a combination of principal planes with disjoint index pairs
//! (a double rotation in 4D, isoclinic or not), or, for equal rates, any isoclinic rotation
//! inside a 4D coordinate subspace (e.g. e₁₂ + e₃₄ rotated into e₁₃ − e₂₄ within axes 1–4).
//! It works for any inertia map, also one that is not diagonal on the basis planes.
//!
//! # Tolerances
//! - Two principal values are "equal" when they differ by at most [`MOMENT_TOLERANCE`]
//!   (1e-12) times the largest |Jᵢ|. The closed form then solves the body whose moments in
//!   each group are replaced by their mean; the model error grows like
//!   1e-12 · |ω|·t relative.
//! - A diagonal map on the basis planes is of the Jᵢ + Jⱼ form when
//!   |Iᵢⱼ − (Jᵢ + Jⱼ)| ≤ [`MOMENT_TOLERANCE`] · max I for all planes, with
//!   Jᵢ = (Iᵢⱼ + Iᵢₖ − Iⱼₖ)/2 (j, k the first two other axes).
//! - A rotation is steady when |ω × L| ≤ [`STEADY_TOLERANCE`] (64ε ≈ 1.4e-14) · |ω| |L|;
//!   the neglected drift of L is then of the order of that bound times t.

use crate::algebra::Bivector;
use crate::dynamics::Attitude;
use crate::dynamics::RigidBody;
use crate::dynamics::{DynamicsError, NoClosedFormReason};

/// Relative tolerance for two principal values Jᵢ, Jⱼ to count as equal, and for a diagonal
/// map to count as having plane moments Jᵢ + Jⱼ (relative to the largest |Jᵢ|, resp. the
/// largest plane moment).
pub const MOMENT_TOLERANCE: f64 = 1e-12;

/// Relative tolerance |ω × L| ≤ tol · |ω| |L| for a rotation to count as steady (64ε).
pub const STEADY_TOLERANCE: f64 = 64.0 * f64::EPSILON;

/// Which closed form a [`TwoMomentSolution`] uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TwoMomentKind {
    /// All principal values equal (paper §7.1): ω and L constant in the body.
    Isotropic,
    /// Exactly two distinct principal values (paper §7.2, §7.3 and their N-D analogues).
    TwoMoments,
    /// Any body, ω(0) × L(0) = 0: ω and L constant, R(t) = R(0) exp(−½ t ω).
    Steady,
}

/// The closed-form torque-free motion of a body with at most two distinct principal values
/// of its mass tensor (any N), or of a steady rotation of any body.
///
/// With α = 1/(a + b), Ω = ν(ω_AA − ω_BB), ν = (b − a)/(a + b) (see the
/// [module documentation](self) for the derivation):
///
/// L(t) = S L(0) S̃,  ω(t) = α L(t) + Ω,  R(t) = R(0) exp(−½ α t L(0)) S̃,  S = exp(½ t Ω).
///
/// ```
/// use rotorflow::prelude::*;
/// use rotorflow::dynamics::RigidBody;
/// use rotorflow::dynamics::exact::two_moments::TwoMomentSolution;
/// // The paper's §7.3 body in 4D: J = (1, 1, 4, 4).
/// let inertia = InertiaMap::from_principal_second_moments(&[1.0, 1.0, 4.0, 4.0])?;
/// let omega = Bivector::from_components(4, &[0.3, 1.0, -0.2, 0.5, 0.7, -0.4])?;
/// let body = RigidBody::from_body_velocity(inertia, Rotor::identity(4), &omega)?;
/// let exact = TwoMomentSolution::new(&body)?;
/// let l = exact.momentum_at(10.0)?;
/// // |L| is a Casimir, and the 12 and 34 components stay constant.
/// assert!((l.norm() - body.momentum().norm()).abs() < 1e-13);
/// assert!((l.get(0, 1) - body.momentum().get(0, 1)).abs() < 1e-13);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct TwoMomentSolution {
    kind: TwoMomentKind,
    body: RigidBody,
    /// α = 1/(a + b) (0 for a steady rotation).
    alpha: f64,
    /// The constant body-frame generator Ω.
    generator: Bivector,
    /// The two principal values (a, b) (a = b when isotropic; NaN-free, (0, 0) when steady).
    values: (f64, f64),
    /// Bit i set when axis i belongs to B.
    in_b: Vec<bool>,
    /// max(α |L|, |Ω|): the largest rate, to bound t·rate.
    rate: f64,
}

impl TwoMomentSolution {
    /// Returns the closed form for `body` (its state is the state at t = 0).
    ///
    /// Accepted: a body whose inertia is diagonal on the basis planes with plane moments
    /// Jᵢ + Jⱼ and at most two distinct Jᵢ (relative tolerance [`MOMENT_TOLERANCE`]); and any
    /// body in a steady rotation (|ω × L| ≤ [`STEADY_TOLERANCE`] |ω| |L|).
    ///
    /// # Errors
    /// [`DynamicsError::NonFiniteArgument`] for a non-finite state; [`DynamicsError::NoClosedForm`] with
    /// the reason otherwise (more than two distinct principal values, plane moments not of
    /// the Jᵢ + Jⱼ form, a map not diagonal on the basis planes), unless steady.
    pub fn new(body: &RigidBody) -> Result<Self, DynamicsError> {
        body.refuse_gyrostat("the two-moment closed form")?;
        let l = body.momentum();
        if let Some(&x) = l.as_slice().iter().find(|x| !x.is_finite()) {
            return Err(DynamicsError::NonFiniteArgument {
                name: "momentum",
                value: x,
            });
        }
        let n = body.dim();
        let reason = match principal_values(body) {
            Ok(j) => match two_groups(&j) {
                Ok((a, b, in_b)) => return Ok(Self::two_moments(body, a, b, in_b)),
                Err(r) => r,
            },
            Err(r) => r,
        };
        let omega = body.omega();
        let scale = omega.norm() * l.norm();
        if omega.commutator(l).norm() <= STEADY_TOLERANCE * scale {
            let rate = omega.norm();
            return Ok(TwoMomentSolution {
                kind: TwoMomentKind::Steady,
                body: body.clone(),
                alpha: 0.0,
                generator: omega,
                values: (0.0, 0.0),
                in_b: vec![false; n],
                rate,
            });
        }
        Err(DynamicsError::NoClosedForm {
            reasons: vec![
                reason,
                NoClosedFormReason::NotSteady {
                    commutator: omega.commutator(l).norm(),
                    tolerance: STEADY_TOLERANCE,
                },
            ],
        })
    }

    fn two_moments(body: &RigidBody, a: f64, b: f64, in_b: Vec<bool>) -> Self {
        let n = body.dim();
        let omega = body.omega();
        let alpha = 1.0 / (a + b);
        let nu = (b - a) / (a + b);
        // Ω = ν (ω_AA − ω_BB): the mixed block drops out.
        let mut generator = Bivector::zero(n);
        for i in 0..n {
            for j in i + 1..n {
                let w = omega.get(i, j);
                match (in_b[i], in_b[j]) {
                    (false, false) => generator.set(i, j, nu * w),
                    (true, true) => generator.set(i, j, -nu * w),
                    _ => {}
                }
            }
        }
        let kind = if in_b.iter().all(|&x| x) || in_b.iter().all(|&x| !x) {
            TwoMomentKind::Isotropic
        } else {
            TwoMomentKind::TwoMoments
        };
        let rate = (alpha * body.momentum().norm()).max(generator.norm());
        TwoMomentSolution {
            kind,
            body: body.clone(),
            alpha,
            generator,
            values: (a, b),
            in_b,
            rate,
        }
    }

    /// Returns which closed form is used.
    pub fn kind(&self) -> TwoMomentKind {
        self.kind
    }

    /// Returns the initial state.
    pub fn initial(&self) -> &RigidBody {
        &self.body
    }

    /// Returns the principal values (a, b): a on the axes of A (those with
    /// [`TwoMomentSolution::in_b`] false), b on B. For [`TwoMomentKind::Isotropic`] a = b;
    /// for [`TwoMomentKind::Steady`] they are not used and reported as (0, 0).
    pub fn values(&self) -> (f64, f64) {
        self.values
    }

    /// Returns, for every axis, whether it belongs to the set B (principal value b).
    pub fn in_b(&self) -> &[bool] {
        &self.in_b
    }

    /// Returns α = 1/(a + b), the rate of the uniform space-frame rotation about L_s
    /// (0 for a steady rotation).
    pub fn alpha(&self) -> f64 {
        self.alpha
    }

    /// Returns the constant body-frame generator Ω = ν(ω_AA − ω_BB), ν = (b − a)/(a + b)
    /// (ω(0) itself for a steady rotation): dL/dt = Ω × L and ω = α L + Ω.
    pub fn generator(&self) -> &Bivector {
        &self.generator
    }

    fn check(&self, t: f64) -> Result<(), DynamicsError> {
        if !t.is_finite() {
            return Err(DynamicsError::NonFiniteArgument {
                name: "t",
                value: t,
            });
        }
        if !(t * self.rate).is_finite() {
            return Err(DynamicsError::NonFiniteArgument {
                name: "t · rate",
                value: t * self.rate,
            });
        }
        Ok(())
    }

    /// S(t) = exp(½ t Ω), as a rotor (N ≤ 4) or its rotation matrix (any N).
    fn body_rotor(&self, t: f64) -> Attitude {
        let mut s = Attitude::identity(self.body.dim());
        s.times_exp_mut(&(&self.generator * (0.5 * t)));
        s
    }

    /// Returns the body-frame angular momentum L(t) = S L(0) S̃, S = exp(½ t Ω).
    ///
    /// # Errors
    /// [`DynamicsError::NonFiniteArgument`] for a non-finite t (or t so large that t times the rate
    /// overflows).
    pub fn momentum_at(&self, t: f64) -> Result<Bivector, DynamicsError> {
        self.check(t)?;
        if self.kind != TwoMomentKind::TwoMoments || self.generator.max_abs() == 0.0 {
            return Ok(self.body.momentum().clone());
        }
        Ok(self.body_rotor(t).rotate_bivector(self.body.momentum()))
    }

    /// Returns the body-frame angular velocity ω(t) = α L(t) + Ω (constant when isotropic
    /// or steady).
    ///
    /// # Errors
    /// As [`TwoMomentSolution::momentum_at`].
    pub fn omega_at(&self, t: f64) -> Result<Bivector, DynamicsError> {
        let l = self.momentum_at(t)?;
        Ok(match self.kind {
            TwoMomentKind::Steady => self.generator.clone(),
            _ => &(&l * self.alpha) + &self.generator,
        })
    }

    /// Returns the attitude R(t) = R(0) exp(−½ α t L(0)) exp(−½ t Ω) (principal frame →
    /// space; R(0) = `body.principal_frame_attitude()`; a rotor for N ≤ 4, an SO(N) matrix above, see
    /// [`Attitude`]).
    ///
    /// # Errors
    /// As [`TwoMomentSolution::momentum_at`].
    pub fn attitude_at(&self, t: f64) -> Result<Attitude, DynamicsError> {
        self.check(t)?;
        let mut r = self.body.principal_frame_attitude().clone();
        if self.alpha != 0.0 {
            r.times_exp_mut(&(self.body.momentum() * (-0.5 * self.alpha * t)));
        }
        r.times_exp_mut(&(&self.generator * (-0.5 * t)));
        Ok(r)
    }

    /// Returns the body at time t: attitude R(t) and momentum L(t), same inertia.
    ///
    /// # Errors
    /// As [`TwoMomentSolution::momentum_at`].
    pub fn body_at(&self, t: f64) -> Result<RigidBody, DynamicsError> {
        let l = self.momentum_at(t)?;
        let r = self.attitude_at(t)?;
        let mut body = self.body.clone();
        body.replace_state(r, l);
        Ok(body)
    }
}

/// The principal values Jᵢ of a map diagonal on the basis planes, recovered from its plane
/// moments, or the reason why there are none.
fn principal_values(body: &RigidBody) -> Result<Vec<f64>, NoClosedFormReason> {
    let n = body.dim();
    let Some(p) = body.inertia().diagonal_plane_moments() else {
        return Err(NoClosedFormReason::NotDiagonalOnPlanes);
    };
    let moment = |i: usize, j: usize| {
        let (i, j) = if i < j { (i, j) } else { (j, i) };
        p[crate::algebra::pair_index(n, i, j)]
    };
    if n < 3 {
        return Err(NoClosedFormReason::AmbiguousSplit);
    }
    let j: Vec<f64> = (0..n)
        .map(|i| {
            let mut others = (0..n).filter(|&k| k != i);
            let (a, b) = (others.next().unwrap_or(0), others.next().unwrap_or(0));
            0.5 * (moment(i, a) + moment(i, b) - moment(a, b))
        })
        .collect();
    let max = p.iter().fold(0.0f64, |m, &x| m.max(x.abs()));
    for i in 0..n {
        for k in i + 1..n {
            let err = (moment(i, k) - (j[i] + j[k])).abs();
            if err > MOMENT_TOLERANCE * max {
                return Err(NoClosedFormReason::NotPairSums {
                    plane: (i, k),
                    moment: moment(i, k),
                    pair_sum: j[i] + j[k],
                });
            }
        }
    }
    Ok(j)
}

/// Groups the principal values into at most two clusters (values a and b, membership of B).
fn two_groups(j: &[f64]) -> Result<(f64, f64, Vec<bool>), NoClosedFormReason> {
    let max = j.iter().fold(0.0f64, |m, &x| m.max(x.abs()));
    let tol = MOMENT_TOLERANCE * max;
    let first = j[0];
    let mut second: Option<f64> = None;
    let mut in_b = vec![false; j.len()];
    for (k, &x) in j.iter().enumerate() {
        if (x - first).abs() <= tol {
            continue;
        }
        match second {
            None => second = Some(x),
            Some(s) if (x - s).abs() <= tol => {}
            Some(_) => {
                return Err(NoClosedFormReason::TooManyDistinctValues {
                    values: j.to_vec(),
                    tolerance: MOMENT_TOLERANCE,
                });
            }
        }
        in_b[k] = true;
    }
    let mean = |sel: bool| {
        let (s, c) = j
            .iter()
            .zip(&in_b)
            .filter(|(_, b)| **b == sel)
            .fold((0.0, 0usize), |(s, c), (x, _)| (s + x, c + 1));
        if c == 0 { None } else { Some(s / c as f64) }
    };
    let a = mean(false).unwrap_or(first);
    let b = mean(true).unwrap_or(a);
    Ok((a, b, in_b))
}
