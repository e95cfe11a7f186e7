//! The exact torque-free motion of a 3D rigid body with any positive plane moments:
//! [`AsymmetricTop`], and [`EmbeddedTop`] for a 3D motion inside a body of higher dimension
//! (the paper's sets S₁ … S₄, eqs. 59–64).
//!
//! # Notation
//! The body frame is the principal frame, so the plane moments I₁₂, I₁₃, I₂₃ are the
//! diagonal of the inertia map. The construction below is written with the classical
//! angular-momentum vector ℓ = (L₂₃, −L₁₃, L₁₂) and the classical moments
//! (I₁, I₂, I₃) = (I₂₃, I₁₃, I₁₂) (the Conventions chapter of the rotorflow book); gᵢ = 1/Iᵢ. Euler's
//! equations dL/dt = ω × L then read dℓ/dt = ℓ × Ω, e.g. ℓ̇₁ = ℓ₂ℓ₃(g₃ − g₂) and cyclic.
//! Name the axes by their moments: *a* the smallest (largest g), *c* the largest, *b* the
//! middle one, and write, with ℓ = |L| and n = ℓ/|L|,
//!
//! δ_a = Σᵢ nᵢ² (g_a − gᵢ) ≥ 0,  δ_c = Σᵢ nᵢ² (gᵢ − g_c) ≥ 0,  Δ = Σᵢ nᵢ² (gᵢ − g_b) = 2T/|L|² − g_b.
//!
//! (sums of non-negative terms, so δ_a and δ_c are accurate to a few ulp even next to an
//! axis; Δ carries the one unavoidable cancellation, the distance to the separatrix).
//!
//! # Body frame: Jacobi's solution (Landau & Lifshitz, *Mechanics*, §37)
//! For Δ ≠ 0 let k be the axis whose component keeps its sign (k = a above the separatrix,
//! Δ > 0, rotation about the axis of least moment; k = c below it), j the other extreme axis:
//!
//! ℓ_k = s_k |L| α_k dn(u|m),  ℓ_b = s_b |L| α_b sn(u|m),  ℓ_j = |L| α_j cn(u|m),  u = βL t + u₀,
//!
//! α_k² = δ_j/|g_k − g_j|, α_j² = δ_k/|g_k − g_j|, α_b² = δ_k/|g_k − g_b|, β² = δ_j |g_k − g_b|,
//! m = δ_k |g_b − g_j| / (δ_j |g_k − g_b|),  1 − m = |g_k − g_j| |Δ| / (δ_j |g_k − g_b|),
//!
//! with s_k = sign ℓ_k(0) and s_b = ε s_k sign(g_k − g_j), ε = ±1 the parity of the
//! permutation (k, b, j) of (1, 2, 3); these follow by substituting into Euler's equations
//! with sn′ = cn dn, cn′ = −sn dn, dn′ = −m sn cn. The phase u₀ = F(φ₀|m) comes from
//! φ₀ = atan2(sn u₀, cn u₀) of the initial state. The complement 1 − m is formed from Δ,
//! never as 1 − m, so the parameter keeps its relative accuracy next to the separatrix. L(t)
//! has period 4K(m)/(β|L|); times are reduced modulo it.
//!
//! On the separatrix (Δ = 0, m = 1) the same formulas hold with dn = cn = sech u,
//! sn = tanh u (α_b = 1), and both extreme components keep their signs.
//!
//! # Attitude: rotor products
//! Let p = s_k e_k be the body axis of the sign-keeping component, P the principal plane
//! dual to it (e₁ ↔ e₂₃, e₂ ↔ −e₁₃, e₃ ↔ e₁₂), and n(t) = ℓ(t)/|L| the body-frame direction
//! of L. Then
//!
//! R(t) = R_L · E(ψ(t)) · A(t),
//!
//! - A(t) = (1 + p n)/|1 + p n| = (1 + p·n + p∧n)/√(2(1 + p·n)), the geometric product of
//!   two body vectors: the smallest rotation taking n(t) to p, i.e. the momentum plane L̂(t)
//!   to P. Here p·n = α_k dn(u) > 0, so A never degenerates.
//! - E(ψ) = exp(−ψ P/2): the turn by ψ about p (in the plane P), which leaves P fixed.
//! - R_L = R(0) Ã(0): the constant rotor from this "invariable" frame (L along p) to
//!   space; R_L P R̃_L = L̂_space, so R L R̃ = L_space for all t, and R(0) = body.principal_frame_attitude().
//!
//! Substituting into dR/dt = −½ R ω gives, with ω the body angular velocity,
//!
//! ψ̇ = (2T/|L| + ⟨ω, P⟩) / (1 + ⟨L̂, P⟩) = |L| g_k − |L| α_j² (g_k − g_j) / (1 + α_k dn u),
//!
//! (the first form for any pole; the second uses 2T − |L|² g_k = −|L|² α_j² (g_k − g_j)).
//! Writing 1/(1 + α dn) = (1 − α dn)/(α_j² (1 + q sn²)) with q = α_k² m/α_j² =
//! |g_b − g_j|/|g_k − g_b| (a constant of the body), and using du = dn · dφ with φ = am u,
//!
//! ψ(t) = |L| g_k t − ((g_k − g_j)/β) (W(u) − W(u₀)),
//! W(u) = Π(−q; am u | m) − (α_k/r) Φ_r(am u),  r = √(1 + q),
//!
//! where Π is Legendre's incomplete integral of the third kind (characteristic n in the
//! DLMF sign, see [`crate::special`]) and Φ_r(φ) = arctan(r tan φ), continued continuously
//! (φ + atan((r − 1) sin φ cos φ / (cos²φ + r sin²φ))). This is the precession integral of
//! Landau & Lifshitz §37 (there for the Euler angle about L with the pole at an axis) and of
//! Celledoni, Fassò, Säfström & Zanna, SIAM J. Sci. Comput. 30 (2008) 2084, §3, in the
//! pole-aligned form derived above. W gains 2Π(−q|m) − πα_k/r per half-period 2K, so ψ
//! grows by a fixed Δψ per period of L(t): ψ(t) = N·Δψ + ψ(τ) with t = N·T + τ, which keeps
//! the error at t = 10⁶ periods at the level of the rounding of t itself.
//!
//! On the separatrix the integral is elementary:
//! ψ(t) = |L| g_b t + (g_k − g_j)(2α_kα_j/β)(atan(q′ tanh(u/2)) − atan(q′ tanh(u₀/2))),
//! q′ = α_j/(1 + α_k).
//!
//! # Limits without elliptic functions
//! - L = 0: the body rests.
//! - Steady rotation about a principal axis (including the unstable middle one, which is
//!   detected exactly: ℓ_a = ℓ_c = 0) and the isotropic body: ω is constant and
//!   R(t) = R(0) exp(−ωt/2).
//! - Two equal plane moments I_⊥ and a third I_s in the plane P_s (symmetric top, exact
//!   precession): ω = L/I_⊥ + G with G = (1/I_s − 1/I_⊥) L_s P_s constant,
//!   L(t) = exp(Gt/2) L(0) exp(−Gt/2), R(t) = exp(−L_space t/(2I_⊥)) R(0) exp(−Gt/2).
//!
//! Moments that are close but not equal take the elliptic path, where m → 0 (or, for the
//! thin set of states with ℓ almost in the plane of the two close axes, q → ∞), both of
//! which the special functions handle.

use super::embedded::EmbeddedTop;
use crate::algebra::{Bivector, Multivector, Rotor, Signature, pairs};
use crate::dynamics::RigidBody;
use crate::dynamics::{DynamicsError, NoClosedFormReason};
use crate::numeric::scaled_norm;
use crate::special::{
    Jacobi, elliptic_f_complement, elliptic_pi_complement, elliptic_pi_inc_complement,
};
use std::f64::consts::{PI, TAU};

/// 4π: the period of a rotor exp(−ψP/2) in its angle ψ.
const FOUR_PI: f64 = 2.0 * TAU;

/// The regime of a free 3D motion, as chosen by [`AsymmetricTop::new`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum TopRegime {
    /// L = 0: the body does not move.
    Rest,
    /// ω is constant: a steady rotation about a principal axis, or any motion of a body
    /// with three equal plane moments.
    Steady,
    /// Exactly two equal plane moments: regular precession, no elliptic functions.
    Symmetric,
    /// Three distinct moments off the separatrix: Jacobi's functions with parameter `m`
    /// (given with its complement `m1 = 1 − m`, formed without cancellation).
    Elliptic {
        /// The parameter m of sn, cn, dn.
        m: f64,
        /// The complementary parameter 1 − m.
        m1: f64,
        /// True above the separatrix (2T·I_mid > |L|², rotation about the axis of least
        /// classical moment), false below it.
        above_separatrix: bool,
    },
    /// On the separatrix (2T·I_mid = |L|² exactly, away from the middle axis): sech and
    /// tanh, asymptotic to the unstable rotation about the middle axis; aperiodic.
    Separatrix,
}

/// The exact torque-free motion of a rigid body in 3D with any positive plane moments
/// (physical or not), any angular momentum and any attitude.
///
/// Built once from a [`RigidBody`]; each evaluation then costs one Jacobi evaluation and
/// one incomplete elliptic integral of the third kind (about a microsecond). The module
/// documentation gives the formulas and their sources.
///
/// ```
/// use rotorflow::prelude::*;
/// use rotorflow::dynamics::RigidBody;
/// use rotorflow::dynamics::exact::top3d::AsymmetricTop;
/// let inertia = InertiaMap::from_classical_3d([2.0, 1.0, 2.0 / 3.0])?;
/// let l = Bivector::from_components(3, &[1.1f64.sin(), 0.0, 1.1f64.cos()])?;
/// let body = RigidBody::from_body_momentum(inertia, Rotor::identity(3), &l)?;
/// let top = AsymmetricTop::new(&body)?;
/// let period = top.period().expect("periodic");
/// // The body-frame momentum returns after one period; |L| and the energy are conserved.
/// let l1 = top.momentum_at(period)?;
/// assert!((&l1 - &l).norm() < 1e-13);
/// let r = top.attitude_at(12.5)?;
/// let l_space = r.rotate_bivector(&top.momentum_at(12.5)?);
/// assert!((&l_space - &body.space_momentum()).norm() < 1e-13);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct AsymmetricTop {
    /// R(0), the body's attitude as a rotor.
    r0: Rotor,
    body: RigidBody,
    /// Plane moments (I₁₂, I₁₃, I₂₃).
    moments: [f64; 3],
    motion: Motion,
}

#[derive(Clone, Debug)]
enum Motion {
    Rest,
    Steady {
        /// Unit plane of ω and its magnitude.
        plane: [f64; 3],
        rate: f64,
    },
    Symmetric(Box<Symmetric>),
    Elliptic(Box<Elliptic>),
    Separatrix(Box<Separatrix>),
}

/// Regular precession of a body with two equal plane moments.
#[derive(Clone, Debug)]
struct Symmetric {
    /// Unit space-frame momentum plane L̂_space and the rate |L|/I_⊥ of the turn in it.
    space_plane: [f64; 3],
    space_rate: f64,
    /// The plane P_s of the distinct moment and the body rate g = (1/I_s − 1/I_⊥) L_s.
    body_plane: [f64; 3],
    body_rate: f64,
    /// True when L(t) moves (L has a part outside P_s and g ≠ 0).
    moves: bool,
}

/// What the elliptic and separatrix regimes share: the axes, amplitudes and the pole.
#[derive(Clone, Debug)]
struct Pole {
    /// Classical axes (0-based): k (sign-keeping, pole), b (middle), j (other extreme).
    k: usize,
    b: usize,
    j: usize,
    /// Signed amplitudes of ℓ_k, ℓ_b, ℓ_j (|L| α with the signs s_k, s_b, s_j).
    amp: [f64; 3],
    /// α_k = |amp_k|/|L|: ⟨L̂, P⟩ = α_k dn u.
    alpha_k: f64,
    /// |L|.
    norm: f64,
    /// The pole p = s_k e_k (classical vector) and its dual plane P.
    pole: [f64; 3],
    pole_plane: [f64; 3],
    /// B = β|L|, the rate of u.
    rate: f64,
    /// R_L = R(0) Ã(0).
    frame: Rotor,
}

#[derive(Clone, Debug)]
struct Elliptic {
    pole: Pole,
    jacobi: Jacobi,
    m1: f64,
    u0: f64,
    /// Period T = 4K/B of L(t).
    period: f64,
    /// |L| g_k.
    spin: f64,
    /// (g_k − g_j)/β.
    coefficient: f64,
    /// −q, the characteristic of Π, and r = √(1 + q).
    characteristic: f64,
    r: f64,
    /// W(u₀).
    w0: f64,
    /// The complete Π(−q | m).
    complete_pi: f64,
    /// Δψ per period, reduced modulo 4π.
    turn_per_period: f64,
    above: bool,
}

#[derive(Clone, Debug)]
struct Separatrix {
    pole: Pole,
    u0: f64,
    /// |L| g_b.
    spin: f64,
    /// (g_k − g_j) 2 α_k α_j / β.
    coefficient: f64,
    /// q′ = α_j/(1 + α_k) and atan(q′ tanh(u₀/2)).
    q: f64,
    atan0: f64,
}

impl AsymmetricTop {
    /// Prepares the exact solution for `body`: N = 3, an inertia map diagonal on the basis
    /// planes (every physical body, after [`RigidBody`] moved it to its principal frame, and
    /// any map from [`crate::inertia::InertiaMap::from_plane_moments`] or
    /// [`crate::inertia::InertiaMap::from_classical_3d`]), any angular momentum (also 0) and
    /// any attitude.
    ///
    /// # Errors
    /// [`DynamicsError::NoClosedForm`] for N ≠ 3 (see [`AsymmetricTop::embedded`] for a 3D
    /// motion inside a larger body) or a general map that is not diagonal on the basis
    /// planes; [`DynamicsError::NonFiniteArgument`] for a non-finite momentum; [`DynamicsError::Special`]
    /// if an elliptic function fails (not expected for valid input).
    pub fn new(body: &RigidBody) -> Result<Self, DynamicsError> {
        body.refuse_gyrostat("the closed-form 3D top")?;
        DynamicsError::check_closed_form_dim("the asymmetric top", 3, body.dim())?;
        let moments = plane_moments_3d(body)?;
        let l0 = body.momentum();
        for &v in l0.as_slice() {
            if !v.is_finite() {
                return Err(DynamicsError::NonFiniteArgument {
                    name: "momentum",
                    value: v,
                });
            }
        }
        // N = 3: the attitude is a rotor.
        let r0 = body.principal_frame_attitude().to_rotor()?;
        let motion = build_motion(&moments, &r0, l0)?;
        Ok(AsymmetricTop {
            r0,
            body: body.clone(),
            moments,
            motion,
        })
    }

    /// Returns the 3D exact solution of a body of any dimension N ≥ 3 whose angular
    /// momentum lies in the 3-space spanned by the principal axes `axes` (0-based, distinct;
    /// the paper's S sets: S₄ = `[0, 1, 2]`, S₁ = `[1, 2, 3]`, eqs. 59–64). With an inertia
    /// diagonal on the basis planes that subspace is invariant: ω × L never leaves it, and
    /// the motion is the 3D one with the plane moments (I(a₀a₁), I(a₀a₂), I(a₁a₂)).
    ///
    /// # Errors
    /// [`DynamicsError::NoClosedForm`] if N < 3, the axes are out of range or repeated, the
    /// inertia map is not diagonal on the basis planes, or L has a non-zero component in a
    /// plane outside the subspace (exact zeros are required); the errors of
    /// [`AsymmetricTop::new`].
    pub fn embedded(body: &RigidBody, axes: [usize; 3]) -> Result<EmbeddedTop, DynamicsError> {
        body.refuse_gyrostat("the closed-form 3D top")?;
        EmbeddedTop::new(body, axes)
    }

    /// Returns the regime the solution uses.
    pub fn regime(&self) -> TopRegime {
        match &self.motion {
            Motion::Rest => TopRegime::Rest,
            Motion::Steady { .. } => TopRegime::Steady,
            Motion::Symmetric(_) => TopRegime::Symmetric,
            Motion::Elliptic(e) => TopRegime::Elliptic {
                m: e.jacobi.parameter(),
                m1: e.m1,
                above_separatrix: e.above,
            },
            Motion::Separatrix(_) => TopRegime::Separatrix,
        }
    }

    /// Returns the plane moments (I₁₂, I₁₃, I₂₃) of the principal frame.
    pub fn plane_moments(&self) -> [f64; 3] {
        self.moments
    }

    /// Returns the body at t = 0.
    pub fn initial(&self) -> &RigidBody {
        &self.body
    }

    /// Returns the body-frame angular momentum L(t), in the principal frame of the body.
    ///
    /// # Errors
    /// [`DynamicsError::NonFiniteArgument`] for a non-finite `t` (or a result that overflows);
    /// [`DynamicsError::Special`] if an elliptic function fails.
    pub fn momentum_at(&self, t: f64) -> Result<Bivector, DynamicsError> {
        check_time(t)?;
        let l0 = self.body.momentum();
        let l = match &self.motion {
            Motion::Rest | Motion::Steady { .. } => l0.clone(),
            Motion::Symmetric(s) => turn(&s.body_plane, s.body_rate * t)
                .reverse()
                .rotate_bivector(l0),
            Motion::Elliptic(e) => from_classical(e.momentum(e.reduce(t).1)?.0),
            Motion::Separatrix(s) => from_classical(s.momentum(t).0),
        };
        finite(l, t)
    }

    /// Returns the body-frame angular velocity ω(t) = I⁻¹(L(t)).
    ///
    /// # Errors
    /// As [`AsymmetricTop::momentum_at`].
    pub fn omega_at(&self, t: f64) -> Result<Bivector, DynamicsError> {
        let mut l = self.momentum_at(t)?;
        for (x, m) in l.as_mut_slice().iter_mut().zip(self.moments) {
            *x /= m;
        }
        Ok(l)
    }

    /// Returns the attitude R(t) (principal body frame → space): R(0) = `body.principal_frame_attitude()`,
    /// continuous in t (the sign of the rotor included), and R(t) L(t) R̃(t) = L_space.
    ///
    /// # Errors
    /// As [`AsymmetricTop::momentum_at`].
    pub fn attitude_at(&self, t: f64) -> Result<Rotor, DynamicsError> {
        Ok(self.state_at(t)?.0)
    }

    /// Returns the attitude R(t) and the body-frame momentum L(t) together, with one
    /// evaluation of the Jacobi functions (cheaper than [`AsymmetricTop::attitude_at`] and
    /// [`AsymmetricTop::momentum_at`] apart).
    ///
    /// # Errors
    /// As [`AsymmetricTop::momentum_at`].
    pub fn state_at(&self, t: f64) -> Result<(Rotor, Bivector), DynamicsError> {
        check_time(t)?;
        let r0 = &self.r0;
        let (r, l) = match &self.motion {
            Motion::Rest => (r0.clone(), self.body.momentum().clone()),
            Motion::Steady { plane, rate } => (
                r0.compose(&turn(plane, rate * t)),
                self.body.momentum().clone(),
            ),
            Motion::Symmetric(s) => {
                let outer = turn(&s.space_plane, s.space_rate * t);
                let inner = turn(&s.body_plane, s.body_rate * t);
                let l = inner.reverse().rotate_bivector(self.body.momentum());
                (outer.compose(r0).compose(&inner), l)
            }
            Motion::Elliptic(e) => {
                let (ell, r) = e.state(t)?;
                (r, from_classical(ell))
            }
            Motion::Separatrix(s) => {
                let (ell, r) = s.state(t);
                (r, from_classical(ell))
            }
        };
        if r.as_slice().iter().all(|c| c.is_finite()) {
            Ok((r, finite(l, t)?))
        } else {
            Err(DynamicsError::NonFiniteArgument {
                name: "t",
                value: t,
            })
        }
    }

    /// Returns the body (inertia, attitude, momentum) at time t.
    ///
    /// # Errors
    /// As [`AsymmetricTop::momentum_at`].
    pub fn body_at(&self, t: f64) -> Result<RigidBody, DynamicsError> {
        let (r, l) = self.state_at(t)?;
        let mut b = self.body.clone();
        b.replace_state(r.into(), l);
        Ok(b)
    }

    /// Returns the period of the body-frame motion L(t): 4K(m)/(β|L|) in the elliptic
    /// regime, 2π/|g| for a symmetric top whose L moves; `None` when L(t) is constant (rest,
    /// steady rotation, isotropic body) or aperiodic (separatrix).
    pub fn period(&self) -> Option<f64> {
        match &self.motion {
            Motion::Elliptic(e) => Some(e.period),
            Motion::Symmetric(s) if s.moves => Some(TAU / s.body_rate.abs()),
            _ => None,
        }
    }
}

// ---------------------------------------------------------------------------------------
// Construction.

fn plane_moments_3d(body: &RigidBody) -> Result<[f64; 3], DynamicsError> {
    let d = body
        .inertia()
        .diagonal_plane_moments()
        .ok_or_else(|| DynamicsError::no_closed_form(NoClosedFormReason::NotDiagonalOnPlanes))?;
    let m = [d[0], d[1], d[2]];
    if m.iter().any(|x| !(x.is_finite() && *x > 0.0)) {
        return Err(DynamicsError::no_closed_form(
            NoClosedFormReason::NonPositivePlaneMoments { moments: m },
        ));
    }
    Ok(m)
}

fn build_motion(moments: &[f64; 3], r0: &Rotor, l0: &Bivector) -> Result<Motion, DynamicsError> {
    let ell = classical(l0);
    let norm = scaled_norm(&ell);
    if norm == 0.0 {
        return Ok(Motion::Rest);
    }
    // Classical moments I = (I₂₃, I₁₃, I₁₂).
    let inertia = [moments[2], moments[1], moments[0]];
    let distinct = [
        inertia[0] != inertia[1],
        inertia[0] != inertia[2],
        inertia[1] != inertia[2],
    ];
    if distinct.iter().all(|d| !d) {
        return Ok(steady(l0, moments));
    }
    if distinct.iter().filter(|d| !**d).count() == 1 {
        return Ok(symmetric(moments, r0, l0));
    }
    let n = ell.map(|x| x / norm);
    // Axes by moment: a smallest, c largest.
    let mut order = [0usize, 1, 2];
    order.sort_by(|&x, &y| inertia[x].total_cmp(&inertia[y]));
    let [a, b, c] = order;
    // g_x − g_y = (I_y − I_x)/(I_x I_y): the difference of the moments is exact when they
    // are close.
    let dg = |x: usize, y: usize| (inertia[y] - inertia[x]) / (inertia[x] * inertia[y]);
    let delta = |k: usize| -> f64 {
        (0..3)
            .filter(|&i| i != k)
            .map(|i| n[i] * n[i] * dg(k, i).abs())
            .sum()
    };
    let distance = n[a] * n[a] * dg(a, b) + n[c] * n[c] * dg(c, b);
    let above = distance > 0.0;
    let (k, j) = if distance >= 0.0 { (a, c) } else { (c, a) };
    let (dk, dj) = (delta(k), delta(j));
    if dk == 0.0 || (distance == 0.0 && n[k] == 0.0 && n[j] == 0.0) {
        return Ok(steady(l0, moments));
    }
    let gkj = dg(k, j).abs();
    let gkb = dg(k, b).abs();
    let gbj = dg(b, j).abs();
    let alpha_k = (dj / gkj).sqrt();
    let alpha_j = (dk / gkj).sqrt();
    let beta = (dj * gkb).sqrt();
    let rate = norm * beta;
    // Parity of (k, b, j) as a permutation of (0, 1, 2).
    let eps = if (k + 1) % 3 == b { 1.0 } else { -1.0 };
    let sign_kj = dg(k, j).signum();
    let pole_for = |sk: f64, alpha_b: f64, sj: f64| -> Pole {
        let sb = eps * sk * sj * sign_kj;
        let mut amp = [0.0; 3];
        amp[k] = sk * norm * alpha_k;
        amp[b] = sb * norm * alpha_b;
        amp[j] = sj * norm * alpha_j;
        let mut pole = [0.0; 3];
        pole[k] = sk;
        Pole {
            k,
            b,
            j,
            amp,
            alpha_k,
            norm,
            pole,
            pole_plane: [pole[2], -pole[1], pole[0]],
            rate,
            frame: Rotor::identity(3),
        }
    };
    let sk = if n[k] < 0.0 { -1.0 } else { 1.0 };
    let m1 = (gkj * distance.abs() / (dj * gkb)).min(1.0);
    if distance == 0.0 || m1 == 0.0 {
        // The separatrix: ℓ_k, ℓ_j ∝ sech u keep their signs; ℓ_b = ±|L| tanh u.
        let sj = if n[j] < 0.0 { -1.0 } else { 1.0 };
        let mut pole = pole_for(sk, 1.0, sj);
        let sb = pole.amp[b].signum();
        let sech0 = n[k].hypot(n[j]);
        let u0 = (sb * n[b] / sech0).asinh();
        pole.frame = r0.compose(&pole.alignment_from(ell, sk * n[k]).reverse());
        let g = |x: usize| 1.0 / inertia[x];
        let q = alpha_j / (1.0 + alpha_k);
        return Ok(Motion::Separatrix(Box::new(Separatrix {
            pole,
            u0,
            spin: norm * g(b),
            coefficient: dg(k, j) * 2.0 * alpha_k * alpha_j / beta,
            q,
            atan0: (q * (0.5 * u0).tanh()).atan(),
        })));
    }
    let alpha_b = (dk / gkb).sqrt();
    let mut pole = pole_for(sk, alpha_b, 1.0);
    let sb = pole.amp[b].signum();
    let jacobi = Jacobi::from_complement(m1)?;
    let kk = jacobi.quarter_period();
    let sn0 = sb * n[b] / alpha_b;
    let cn0 = n[j] / alpha_j;
    let phi0 = sn0.atan2(cn0);
    let u0 = elliptic_f_complement(phi0, m1)?;
    let q = gbj / gkb;
    let r = (1.0 + q).sqrt();
    let characteristic = -q;
    let (s0, c0) = phi0.sin_cos();
    let w0 = elliptic_pi_inc_complement(characteristic, phi0, m1)?
        - alpha_k / r * phi_r(r, phi0, s0, c0);
    let big_pi = elliptic_pi_complement(characteristic, m1)?;
    let coefficient = dg(k, j) / beta;
    let spin = norm / inertia[k];
    let turn_per_period = (4.0 * kk / (beta * inertia[k])
        - 2.0 * coefficient * (2.0 * big_pi - PI * alpha_k / r))
        .rem_euclid(FOUR_PI);
    pole.frame = r0.compose(&pole.alignment_from(ell, sk * n[k]).reverse());
    Ok(Motion::Elliptic(Box::new(Elliptic {
        pole,
        jacobi,
        m1,
        u0,
        period: 4.0 * kk / rate,
        spin,
        coefficient,
        characteristic,
        r,
        w0,
        complete_pi: big_pi,
        turn_per_period,
        above,
    })))
}

/// ω constant: R(t) = R(0) exp(−ωt/2).
fn steady(l0: &Bivector, moments: &[f64; 3]) -> Motion {
    let mut omega = l0.clone();
    for (x, m) in omega.as_mut_slice().iter_mut().zip(moments) {
        *x /= m;
    }
    let (plane, rate) = unit(&omega);
    Motion::Steady { plane, rate }
}

/// Two equal plane moments (exactly one pair equal).
fn symmetric(moments: &[f64; 3], r0: &Rotor, l0: &Bivector) -> Motion {
    // The distinct plane s and the common moment I_⊥.
    let s = if moments[1] == moments[2] {
        0
    } else if moments[0] == moments[2] {
        1
    } else {
        2
    };
    let i_perp = moments[(s + 1) % 3];
    let l_s = l0.as_slice()[s];
    let mut body_plane = [0.0; 3];
    body_plane[s] = 1.0;
    let body_rate = (1.0 / moments[s] - 1.0 / i_perp) * l_s;
    let (space_plane, norm) = unit(&r0.rotate_bivector(l0));
    let outside = l0
        .as_slice()
        .iter()
        .enumerate()
        .any(|(i, &v)| i != s && v != 0.0);
    Motion::Symmetric(Box::new(Symmetric {
        space_plane,
        space_rate: norm / i_perp,
        body_plane,
        body_rate,
        moves: outside && body_rate != 0.0,
    }))
}

// ---------------------------------------------------------------------------------------
// Evaluation.

impl Pole {
    /// A = (1 + p n)/|1 + p n| for n = ℓ/|L| with p·n = `pn` (≥ 0): the smallest rotation
    /// taking n to the pole p.
    fn alignment_from(&self, ell: [f64; 3], pn: f64) -> Rotor {
        let n = ell.map(|x| x / self.norm);
        let p = self.pole;
        // p ∧ n in the lexicographic order 12, 13, 23.
        let wedge = [
            p[0] * n[1] - p[1] * n[0],
            p[0] * n[2] - p[2] * n[0],
            p[1] * n[2] - p[2] * n[1],
        ];
        let s = 1.0 + pn;
        let scale = 1.0 / (2.0 * s).sqrt();
        let mut c = [0.0; 4];
        c[0] = s * scale;
        for (slot, w) in wedge.iter().enumerate() {
            c[slot + 1] = w * scale;
        }
        rotor3(c)
    }

    fn attitude(&self, ell: [f64; 3], pn: f64, psi: f64) -> Rotor {
        let a = self.alignment_from(ell, pn);
        self.frame.compose(&turn(&self.pole_plane, psi)).compose(&a)
    }
}

impl Elliptic {
    /// t = N·T + τ with 0 ≤ τ < T.
    fn reduce(&self, t: f64) -> (f64, f64) {
        let mut cycles = (t / self.period).floor();
        let mut tau = (-cycles).mul_add(self.period, t);
        if tau < 0.0 {
            tau += self.period;
            cycles -= 1.0;
        } else if tau >= self.period {
            tau -= self.period;
            cycles += 1.0;
        }
        (cycles, tau.max(0.0))
    }

    /// ℓ(τ) and the Jacobi values at u = Bτ + u₀.
    fn momentum(
        &self,
        tau: f64,
    ) -> Result<([f64; 3], crate::special::JacobiElliptic), DynamicsError> {
        let u = self.pole.rate.mul_add(tau, self.u0);
        let je = self.jacobi.eval(u)?;
        let p = &self.pole;
        let mut ell = [0.0; 3];
        ell[p.k] = p.amp[p.k] * je.dn;
        ell[p.b] = p.amp[p.b] * je.sn;
        ell[p.j] = p.amp[p.j] * je.cn;
        Ok((ell, je))
    }

    /// ℓ(t) and R(t).
    fn state(&self, t: f64) -> Result<([f64; 3], Rotor), DynamicsError> {
        let (cycles, tau) = self.reduce(t);
        let (ell, je) = self.momentum(tau)?;
        // Π(n; jπ + θ) = 2jΠ(n) + Π(n; θ) with |θ| ≤ π/2 (the integrand has period π in φ);
        // this spares the special function recomputing the complete integral on every call.
        let half_turns = (je.am / PI).round();
        let theta = (-half_turns).mul_add(PI, je.am);
        let pi_inc = 2.0 * half_turns * self.complete_pi
            + elliptic_pi_inc_complement(self.characteristic, theta, self.m1)?;
        let w = pi_inc - self.pole.alpha_k / self.r * phi_r(self.r, je.am, je.sn, je.cn);
        let psi = (cycles * self.turn_per_period).rem_euclid(FOUR_PI) + self.spin * tau
            - self.coefficient * (w - self.w0);
        let r = self
            .pole
            .attitude(ell, self.pole.alpha_k * je.dn, psi.rem_euclid(FOUR_PI));
        Ok((ell, r))
    }
}

impl Separatrix {
    /// ℓ(t) and sech u.
    fn momentum(&self, t: f64) -> ([f64; 3], f64) {
        let u = self.pole.rate.mul_add(t, self.u0);
        let sech = 1.0 / u.cosh();
        let p = &self.pole;
        let mut ell = [0.0; 3];
        ell[p.k] = p.amp[p.k] * sech;
        ell[p.b] = p.amp[p.b] * u.tanh();
        ell[p.j] = p.amp[p.j] * sech;
        (ell, sech)
    }

    /// ℓ(t) and R(t).
    fn state(&self, t: f64) -> ([f64; 3], Rotor) {
        let (ell, sech) = self.momentum(t);
        let u = self.pole.rate.mul_add(t, self.u0);
        let psi = (self.spin * t).rem_euclid(FOUR_PI)
            + self.coefficient * ((self.q * (0.5 * u).tanh()).atan() - self.atan0);
        let r = self
            .pole
            .attitude(ell, self.pole.alpha_k * sech, psi.rem_euclid(FOUR_PI));
        (ell, r)
    }
}

/// Φ_r(φ) = arctan(r tan φ), continued continuously: φ + atan((r−1) sc/(c² + r s²)).
fn phi_r(r: f64, phi: f64, s: f64, c: f64) -> f64 {
    phi + ((r - 1.0) * s * c / (c * c + r * s * s)).atan()
}

// ---------------------------------------------------------------------------------------
// Helpers.

fn check_time(t: f64) -> Result<(), DynamicsError> {
    if t.is_finite() {
        Ok(())
    } else {
        Err(DynamicsError::NonFiniteArgument {
            name: "t",
            value: t,
        })
    }
}

fn finite(b: Bivector, t: f64) -> Result<Bivector, DynamicsError> {
    if b.as_slice().iter().all(|x| x.is_finite()) {
        Ok(b)
    } else {
        Err(DynamicsError::NonFiniteArgument {
            name: "t",
            value: t,
        })
    }
}

/// ℓ = (L₂₃, −L₁₃, L₁₂).
fn classical(l: &Bivector) -> [f64; 3] {
    let c = l.as_slice();
    [c[2], -c[1], c[0]]
}

/// L = (ℓ₃, −ℓ₂, ℓ₁) in the order 12, 13, 23.
fn from_classical(v: [f64; 3]) -> Bivector {
    let mut b = Bivector::zero(3);
    b.as_mut_slice().copy_from_slice(&[v[2], -v[1], v[0]]);
    b
}

/// The unit plane and magnitude of a 3D bivector (zero plane for zero).
fn unit(b: &Bivector) -> ([f64; 3], f64) {
    let c = b.as_slice();
    let v = [c[0], c[1], c[2]];
    let norm = scaled_norm(&v);
    if norm == 0.0 {
        return ([0.0; 3], 0.0);
    }
    (v.map(|x| x / norm), norm)
}

/// exp(−angle·P/2) = cos(angle/2) − sin(angle/2) P for a unit 3D plane P, with the angle
/// reduced modulo 4π (the rotor's period) first.
fn turn(p: &[f64; 3], angle: f64) -> Rotor {
    let (s, c) = (0.5 * angle.rem_euclid(FOUR_PI)).sin_cos();
    rotor3([c, -s * p[0], -s * p[1], -s * p[2]])
}

/// The 3D rotor with scalar part c₀ and bivector part (c₁, c₂, c₃) on e₁₂, e₁₃, e₂₃.
fn rotor3(c: [f64; 4]) -> Rotor {
    let mut b = Bivector::zero(3);
    b.as_mut_slice().copy_from_slice(&c[1..]);
    // N = 3 is below every storage limit.
    rotor_from_parts(c[0], &b).unwrap_or_else(|_| Rotor::identity(3))
}

/// The even element s + B as a rotor (no check that it is one).
pub(super) fn rotor_from_parts(scalar: f64, b: &Bivector) -> Result<Rotor, DynamicsError> {
    let n = b.dim();
    let mut m = Multivector::try_zero(Signature::euclidean(n))?;
    let c = m.as_mut_slice();
    c[0] = scalar;
    for (k, (i, j)) in pairs(n).enumerate() {
        c[(1usize << i) | (1usize << j)] = b.as_slice()[k];
    }
    Ok(Rotor::from_multivector_unchecked(&m))
}
