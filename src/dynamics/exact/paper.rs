//! The paper's closed forms of §7 ("Solutions of the Euler Equations in 4D Spaces",
//! eqs. 107–134), checked against [`super::two_moments`] and corrected where needed.
//!
//! # What the paper's parameters mean
//! The paper writes the 4D bodies of §7 as "a = b = c = 1, d = κ" (eq. 109, three equal
//! moments and one different) and "a = b = 1, c = d = κ" (eq. 121, two equal pairs). Its
//! equations (113)–(115) and (124)–(127) carry the plane moments 2 and 1 + κ², and its
//! frequencies (119)–(120), (132)–(134) the factor (κ² − 1)/(κ² + 1). Both hold only if
//! a, b, c, d are **half-axes** (semi-axes of the ellipsoid, half-edges of the cuboid, as in
//! §5–6), so that the mass tensor is J ∝ diag(a², b², c², d²) and the plane moments are
//! Jᵢ + Jⱼ ∝ aᵢ² + aⱼ² (eq. 78):
//!
//! - eq. 109: J ∝ (1, 1, 1, κ²), eq. 121: J ∝ (1, 1, κ², κ²);
//! - the common factor (V/3 for the cuboid, V/6 for the ellipsoid) drops out: Euler's
//!   equations in ω, (Jᵢ + Jⱼ) dωᵢⱼ/dt = (Jⱼ − Jᵢ)(\[ω\]²)ᵢⱼ (the crate's Euler equations), are homogeneous
//!   of degree one in J, so ω(t) does not depend on it.
//!
//! Reading a…d as the principal values of J itself, as the axis moments 𝕀_α of eqs. 24/79,
//! or as the gyration radii 𝕃_α gives other ratios (J₄ − J₁)/(J₄ + J₁) and does not
//! reproduce (119) (test `paper_eq_109_parameters_are_half_axes`).
//!
//! In the closed form of [`super::two_moments`] (A = the axes with Jᵢ = 1, B the others):
//! ν = (b − a)/(a + b) = (κ² − 1)/(κ² + 1) is the paper's factor, and the body-frame
//! generator is Ω = ν(ω_AA − ω_BB). The paper's ωᵢⱼ are read as the crate's components (the
//! Conventions chapter of the rotorflow book): its matrix (47) is \[ω\] conjugated by
//! diag(−1, 1, −1, 1), a rotation that commutes with J, so the component equations are the
//! same; its own 4D equations (53)–(58) carry the crate's sign.
//!
//! # The constants
//! - §7.2: c₁ = ω₂₃, c₂ = ω₁₃, c₃ = ω₁₂ (eqs. 110–112, constant). With v = (ω₁₄, ω₂₄, ω₃₄)
//!   at t = 0, m = (c₁, −c₂, c₃) and s = |m| = √(c₁² + c₂² + c₃²), eqs. 116–118 at t = 0
//!   give c₄ = c₁ (m·v)/s², c₅ = −(c₃ v₂ + c₂ v₃)/s, c₆ = v₁ − c₄. The frequency of (119)
//!   is |ν| s = |Ω|.
//! - §7.3: c₁ = ω₁₂, c₂ = ω₃₄ (eqs. 122–123); eqs. 128–131 at t = 0 give
//!   c₃ = −(ω₁₄ + ω₂₃)/2, c₄ = (ω₁₃ − ω₂₄)/2, c₅ = (ω₁₄ − ω₂₃)/2, c₆ = (ω₁₃ + ω₂₄)/2. The
//!   frequencies (134) ν(c₁ ∓ c₂) are those of Ω = ν(c₁ e₁₂ − c₂ e₃₄) acting on the mixed
//!   block.
//!
//! # What is wrong in the paper
//! The printed linear systems (113)–(115) and (124)–(126) have the opposite sign of the
//! coupling terms (they are Euler's equations run backwards in time), and the printed
//! solutions (116)–(118) and (128)–(131) solve those printed systems; eq. (127) alone has the
//! right sign, so (128)–(131) do not solve the paper's own (127). Eq. (126) names dω₃₄/dt
//! where ω₃₄ is constant (123): it is dω₂₃/dt. Eqs. (117)–(118) divide by c₁ and by
//! c₂² + c₃², both of which can vanish. The functions here give the correct motion: the
//! paper's forms at −t, written without divisions. The book's `errata/section7.md` lists
//! each entry with its test.

use crate::algebra::Bivector;
use crate::dynamics::{DynamicsError, NoClosedFormReason};

fn finite(name: &'static str, value: f64) -> Result<f64, DynamicsError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(DynamicsError::NonFiniteArgument { name, value })
    }
}

fn check_kappa(kappa: f64) -> Result<f64, DynamicsError> {
    finite("kappa", kappa)?;
    if kappa <= 0.0 {
        return Err(DynamicsError::no_closed_form(
            NoClosedFormReason::NonPositiveKappa { kappa },
        ));
    }
    Ok(kappa)
}

fn check_omega(omega: &Bivector) -> Result<[f64; 6], DynamicsError> {
    DynamicsError::check_closed_form_dim("the paper's §7", 4, omega.dim())?;
    let mut c = [0.0; 6];
    for (out, &x) in c.iter_mut().zip(omega.as_slice()) {
        *out = finite("omega", x)?;
    }
    Ok(c)
}

fn check_t(t: f64) -> Result<f64, DynamicsError> {
    finite("t", t)
}

/// Returns the principal values of the mass tensor of a body with half-axes aᵢ, up to the
/// common factor that drops out of ω(t): Jᵢ = aᵢ² (eq. 78 for the cuboid, where
/// Iⁱʲⁱʲ ∝ aᵢ² + aⱼ²; eqs. 91–94 for the ellipsoid).
///
/// # Errors
/// [`DynamicsError::NonFiniteArgument`] for a non-finite half-axis.
pub fn principal_second_moments_from_half_axes(
    half_axes: &[f64],
) -> Result<Vec<f64>, DynamicsError> {
    half_axes
        .iter()
        .map(|&a| finite("half_axes", a).map(|a| a * a))
        .collect()
}

/// Eq. (109), "a = b = c = 1, d = κ": the principal values J = (1, 1, 1, κ²).
///
/// # Errors
/// [`DynamicsError::NonFiniteArgument`]; [`DynamicsError::NoClosedForm`] for κ ≤ 0.
pub fn three_equal_second_moments(kappa: f64) -> Result<[f64; 4], DynamicsError> {
    let k = check_kappa(kappa)?;
    Ok([1.0, 1.0, 1.0, k * k])
}

/// Eq. (121), "a = b = 1, c = d = κ": the principal values J = (1, 1, κ², κ²).
///
/// # Errors
/// [`DynamicsError::NonFiniteArgument`]; [`DynamicsError::NoClosedForm`] for κ ≤ 0.
pub fn two_equal_pairs_second_moments(kappa: f64) -> Result<[f64; 4], DynamicsError> {
    let k = check_kappa(kappa)?;
    Ok([1.0, 1.0, k * k, k * k])
}

/// The paper's factor ν = (κ² − 1)/(κ² + 1) of eqs. (113)–(120) and (124)–(134):
/// (b − a)/(a + b) for a = 1, b = κ².
///
/// # Errors
/// As [`three_equal_second_moments`].
pub fn frequency_factor(kappa: f64) -> Result<f64, DynamicsError> {
    let k2 = check_kappa(kappa)?.powi(2);
    Ok((k2 - 1.0) / (k2 + 1.0))
}

/// Eq. (108), all moments equal (§7.1): ω(t) = ω(0) in every dimension (right; the body
/// frame never moves relative to L).
///
/// # Errors
/// [`DynamicsError::NonFiniteArgument`] for a non-finite t or ω.
pub fn isotropic_omega(omega0: &Bivector, t: f64) -> Result<Bivector, DynamicsError> {
    check_t(t)?;
    for &x in omega0.as_slice() {
        finite("omega", x)?;
    }
    Ok(omega0.clone())
}

/// The paper's §7.2: three equal principal values and one different, J ∝ (1, 1, 1, κ²)
/// (eq. 109), with its constants c₁ … c₆ and the corrected, division-free solution.
///
/// ```
/// use rotorflow::algebra::Bivector;
/// use rotorflow::dynamics::exact::paper::ThreeEqualMoments;
/// let w0 = Bivector::from_components(4, &[0.3, -0.5, 0.8, 0.4, 0.2, -0.6])?;
/// let p = ThreeEqualMoments::new(2.0, &w0)?;
/// // c₁ = ω₂₃, c₂ = ω₁₃, c₃ = ω₁₂ (eqs. 110–112) stay constant.
/// assert_eq!(p.constants_c1_to_c3(), [0.4, -0.5, 0.3]);
/// let w = p.omega_at(3.0)?;
/// assert_eq!(w.get(1, 2), 0.4);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct ThreeEqualMoments {
    kappa: f64,
    nu: f64,
    omega0: [f64; 6],
}

impl ThreeEqualMoments {
    /// Returns the §7.2 solution for the half-axis κ (eq. 109) and the initial body-frame
    /// angular velocity ω(0) (4D, principal frame).
    ///
    /// # Errors
    /// [`DynamicsError::NonFiniteArgument`]; [`DynamicsError::NoClosedForm`] for κ ≤ 0 or N ≠ 4.
    pub fn new(kappa: f64, omega0: &Bivector) -> Result<Self, DynamicsError> {
        let nu = frequency_factor(kappa)?;
        let omega0 = check_omega(omega0)?;
        Ok(ThreeEqualMoments { kappa, nu, omega0 })
    }

    /// Returns κ.
    pub fn kappa(&self) -> f64 {
        self.kappa
    }

    /// Eqs. (110)–(112): (c₁, c₂, c₃) = (ω₂₃, ω₁₃, ω₁₂), constant in time (right).
    pub fn constants_c1_to_c3(&self) -> [f64; 3] {
        let w = &self.omega0;
        [w[3], w[1], w[0]]
    }

    /// Returns s = √(c₁² + c₂² + c₃²) = |ω_AA|.
    fn s(&self) -> f64 {
        let [c1, c2, c3] = self.constants_c1_to_c3();
        c1.hypot(c2).hypot(c3)
    }

    /// The constants (c₄, c₅, c₆) of eqs. (116)–(118), from their values at t = 0:
    /// c₄ = c₁ (m·v)/s², c₅ = −(c₃ v₂ + c₂ v₃)/s, c₆ = v₁ − c₄, with v = (ω₁₄, ω₂₄, ω₃₄),
    /// m = (c₁, −c₂, c₃), s = |m|. The paper leaves them implicit ("contingent on the
    /// initial conditions").
    ///
    /// # Errors
    /// [`DynamicsError::NoClosedForm`] when s = 0 (ω_AA = 0: then every component is constant
    /// and c₅ is undefined).
    pub fn constants_c4_to_c6(&self) -> Result<[f64; 3], DynamicsError> {
        let [c1, c2, c3] = self.constants_c1_to_c3();
        let s = self.s();
        if s == 0.0 {
            return Err(DynamicsError::no_closed_form(
                NoClosedFormReason::PaperConstantsUndefined,
            ));
        }
        let w = &self.omega0;
        let (v1, v2, v3) = (w[2], w[4], w[5]);
        let c4 = c1 * ((c1 / s) * (v1 / s) - (c2 / s) * (v2 / s) + (c3 / s) * (v3 / s));
        let c5 = -(c3 * v2 + c2 * v3) / s;
        Ok([c4, c5, v1 - c4])
    }

    /// Eqs. (119)–(120): the frequency ν s of ℂ(t) = cos(ν s t) and 𝕊(t) = sin(ν s t),
    /// ν = (κ² − 1)/(κ² + 1) (right: |ν| s = |Ω| is the rate of the body-frame rotation).
    pub fn frequency(&self) -> f64 {
        self.nu * self.s()
    }

    /// Returns the body-frame angular velocity ω(t), corrected form of eqs. (116)–(118):
    /// ω₁₂, ω₁₃, ω₂₃ constant and x = (ω₁₄, ω₂₄, ω₃₄) turned by the constant generator,
    ///
    /// x(t) = x + (sin(νst)/s) W x + (2 sin²(νst/2)/s²) W² x,   W = \[ω_AA\] (3×3),
    ///
    /// which is exp(νt W) x (Rodrigues). This equals the paper's (116)–(118) evaluated at
    /// **−t** (the printed solution runs backwards) and has no division by c₁ or c₂² + c₃².
    ///
    /// # Errors
    /// [`DynamicsError::NonFiniteArgument`] for a non-finite t.
    pub fn omega_at(&self, t: f64) -> Result<Bivector, DynamicsError> {
        check_t(t)?;
        let w = &self.omega0;
        // W = [ω_AA] on axes 1, 2, 3: W₁₂ = ω₁₂, W₁₃ = ω₁₃, W₂₃ = ω₂₃.
        let (w12, w13, w23) = (w[0], w[1], w[3]);
        let x = [w[2], w[4], w[5]];
        let apply = |x: [f64; 3]| {
            [
                w12 * x[1] + w13 * x[2],
                -w12 * x[0] + w23 * x[2],
                -w13 * x[0] - w23 * x[1],
            ]
        };
        let wx = apply(x);
        let wwx = apply(wx);
        let s = self.s();
        let tau = self.nu * t;
        let (k1, k2) = if s == 0.0 {
            (0.0, 0.0)
        } else {
            let h = (0.5 * tau * s).sin();
            ((tau * s).sin() / s, 2.0 * (h / s) * h / s)
        };
        if !(k1.is_finite() && k2.is_finite()) {
            return Err(DynamicsError::NonFiniteArgument {
                name: "t",
                value: t,
            });
        }
        let xt: Vec<f64> = (0..3).map(|i| x[i] + k1 * wx[i] + k2 * wwx[i]).collect();
        let c = [w12, w13, xt[0], w23, xt[1], xt[2]];
        Ok(Bivector::from_components(4, &c)?)
    }
}

/// The paper's §7.3: two pairs of equal principal values, J ∝ (1, 1, κ², κ²) (eq. 121),
/// with its constants c₁ … c₆, its frequencies and the corrected solution.
///
/// ```
/// use rotorflow::algebra::Bivector;
/// use rotorflow::dynamics::exact::paper::TwoEqualPairs;
/// let w0 = Bivector::from_components(4, &[0.9, 0.1, -0.3, 0.2, 0.5, 0.4])?;
/// let p = TwoEqualPairs::new(1.5, &w0)?;
/// assert_eq!(p.constants_c1_c2(), [0.9, 0.4]); // c₁ = ω₁₂, c₂ = ω₃₄
/// let w = p.omega_at(0.0)?;
/// assert!((&w - &w0).norm() < 1e-15);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct TwoEqualPairs {
    kappa: f64,
    nu: f64,
    omega0: [f64; 6],
}

impl TwoEqualPairs {
    /// Returns the §7.3 solution for the half-axis κ (eq. 121) and the initial body-frame
    /// angular velocity ω(0) (4D, principal frame).
    ///
    /// # Errors
    /// [`DynamicsError::NonFiniteArgument`]; [`DynamicsError::NoClosedForm`] for κ ≤ 0 or N ≠ 4.
    pub fn new(kappa: f64, omega0: &Bivector) -> Result<Self, DynamicsError> {
        let nu = frequency_factor(kappa)?;
        let omega0 = check_omega(omega0)?;
        Ok(TwoEqualPairs { kappa, nu, omega0 })
    }

    /// Returns κ.
    pub fn kappa(&self) -> f64 {
        self.kappa
    }

    /// Eqs. (122)–(123): (c₁, c₂) = (ω₁₂, ω₃₄), constant in time (right).
    pub fn constants_c1_c2(&self) -> [f64; 2] {
        [self.omega0[0], self.omega0[5]]
    }

    /// The constants (c₃, c₄, c₅, c₆) of eqs. (128)–(131), from their values at t = 0:
    /// c₃ = −(ω₁₄ + ω₂₃)/2, c₄ = (ω₁₃ − ω₂₄)/2, c₅ = (ω₁₄ − ω₂₃)/2, c₆ = (ω₁₃ + ω₂₄)/2
    /// (right; always defined).
    pub fn constants_c3_to_c6(&self) -> [f64; 4] {
        let w = &self.omega0;
        let (w13, w14, w23, w24) = (w[1], w[2], w[3], w[4]);
        [
            -0.5 * (w14 + w23),
            0.5 * (w13 - w24),
            0.5 * (w14 - w23),
            0.5 * (w13 + w24),
        ]
    }

    /// Eqs. (132)–(134): (ω₁, ω₂) = (ν(c₁ − c₂), ν(c₁ + c₂)), ν = (κ² − 1)/(κ² + 1), the
    /// frequencies of 𝔽₁ … 𝔽₄. Right as the angular frequencies of the motion (|ω₁|, |ω₂|);
    /// the correct motion is (128)–(131) with (ω₁, ω₂) → (−ω₁, −ω₂).
    pub fn frequencies(&self) -> [f64; 2] {
        let [c1, c2] = self.constants_c1_c2();
        [self.nu * (c1 - c2), self.nu * (c1 + c2)]
    }

    /// Returns the body-frame angular velocity ω(t), corrected form of eqs. (128)–(131):
    /// with 𝔽₁ = −sin(ω₁t), 𝔽₂ = cos(ω₁t), 𝔽₃ = −sin(ω₂t), 𝔽₄ = cos(ω₂t) (the paper's
    /// functions at −t),
    ///
    /// ω₁₃ = c₃𝔽₁ + c₄𝔽₂ + c₅𝔽₃ + c₆𝔽₄, ω₁₄ = c₄𝔽₁ − c₃𝔽₂ − c₆𝔽₃ + c₅𝔽₄,
    /// ω₂₃ = c₄𝔽₁ − c₃𝔽₂ + c₆𝔽₃ − c₅𝔽₄, ω₂₄ = −c₃𝔽₁ − c₄𝔽₂ + c₅𝔽₃ + c₆𝔽₄,
    ///
    /// and ω₁₂ = c₁, ω₃₄ = c₂.
    ///
    /// # Errors
    /// [`DynamicsError::NonFiniteArgument`] for a non-finite t (or t·ωₖ overflowing).
    pub fn omega_at(&self, t: f64) -> Result<Bivector, DynamicsError> {
        check_t(t)?;
        let [c1, c2] = self.constants_c1_c2();
        let [c3, c4, c5, c6] = self.constants_c3_to_c6();
        let [o1, o2] = self.frequencies();
        let (a1, a2) = (o1 * t, o2 * t);
        if !(a1.is_finite() && a2.is_finite()) {
            return Err(DynamicsError::NonFiniteArgument {
                name: "t",
                value: t,
            });
        }
        let (s1, f2) = a1.sin_cos();
        let (s2, f4) = a2.sin_cos();
        let (f1, f3) = (-s1, -s2);
        let w13 = c3 * f1 + c4 * f2 + c5 * f3 + c6 * f4;
        let w14 = c4 * f1 - c3 * f2 - c6 * f3 + c5 * f4;
        let w23 = c4 * f1 - c3 * f2 + c6 * f3 - c5 * f4;
        let w24 = -c3 * f1 - c4 * f2 + c5 * f3 + c6 * f4;
        Ok(Bivector::from_components(4, &[c1, w13, w14, w23, w24, c2])?)
    }
}
