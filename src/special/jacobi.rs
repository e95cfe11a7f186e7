//! Jacobi elliptic functions sn, cn, dn and
//! the (unwrapped) amplitude am, for real u and 0 ≤ m ≤ 1.
//!
//! # Algorithm
//! 1. **Reduction.** u = jK + v with j = round(u/K) and
//!    |v| ≤ K/2, where K = K(m) is known to ~106 bits (double-double
//!    AGM, DLMF 19.8.5). v is formed as a double-double v_hi + v_lo
//!    and v_lo enters through a first-order Taylor correction, so even
//!    u = 10¹² or u next to a zero of sn or cn keeps its *relative*
//!    accuracy. The quarter-period shifts (DLMF Table 22.4.3)
//!    sn(v+K) = cd v, cn(v+K) = −k' sd v,
//!    dn(v+K) = k' nd v then give the result from
//!    (sn, cn, dn)(|v|), all of them bounded away
//!    from zero except sn at v = 0.
//! 2. **Halving and Maclaurin series.** w = |v|/2^N ≤ 2⁻⁷; the series
//!    DLMF 22.10.1–22.10.3 to w⁸ give sn w, 1−cn w
//!    and 1−dn w to full relative precision.
//! 3. **Doubling** N times with the duplication formulas (DLMF 22.8.1–22.8.3
//!    rearranged so that no subtraction cancels for |v| ≤ K/2):
//!    with Δ = dn² + m sn²cn² = 1 − m sn⁴,
//!    * sn 2u = 2 sn cn dn/Δ,
//!    * 1−cn 2u = 2 sn²dn²/Δ and
//!      1−dn 2u = 2m sn²cn²/Δ while cn and dn are near 1,
//!    * cn 2u = (cn² − k'sn²)(cn² + k'sn²)/Δ and
//!      dn 2u = (cn²dn² + m₁sn²)/Δ afterwards.
//!
//!    The last two forms use m₁ = 1−m directly, so m within 10⁻¹⁶
//!    of 1 (or given only through m₁) is handled without loss.
//!    The idea (halve, series, double with 1−cn and 1−dn)
//!    is T. Fukushima's (Celest. Mech. Dyn. Astr. 105 (2009) 305; "conditional
//!    duplication", Numer. Math. 123 (2013) 585); the formulas above were
//!    re-derived here, with the cancellation-free second phase added.
//! 4. **Closed forms at the ends.** For m ≤ 10⁻⁸ the first-order
//!    expansion in m (DLMF 22.10.4–22.10.6) and, for m₁² e^(2|v|) ≤ 10⁻¹⁸,
//!    the first-order expansion in m₁ (DLMF 22.10.7–22.10.9) replace steps 2–3.
//!    Their remainders, measured with mpmath, are below 5×10⁻¹⁹ and
//!    ≈ 0.1 m₁²e^(2|v|) ≤ 10⁻¹⁹; they cost fewer roundings than
//!    the ~10–15 doublings otherwise needed there. For m₁ ≤ 10⁻¹¹ this
//!    covers the whole reduced range |v| ≤ K/2.
//! 5. am = jπ/2 + atan2(·,·) of the reduced values,
//!    continuous in u, with am(u + 2K) = am(u) + π.
//!
//! # Error behaviour
//! The doubling steps add a backward error of a few ulp per step to the
//! argument. Since |v| can reach K/2 ≈ ½ ln(4/k'), whose relative
//! condition number for cn and dn is about |v|, the relative error of cn and
//! dn grows mildly as m → 1 in the range not covered by step 4
//! (10⁻¹¹ ≲ m₁ ≲ 10⁻³); see the measured table in the crate docs.

use crate::special::dd::{self, Dd};
use crate::special::error::{EllipticError, check_domain, check_finite};

/// Largest accepted |u|/K (quarter periods) for the general case.
const U_LIMIT_QUARTERS: f64 = 1_125_899_906_842_624.0; // 2^50

/// Threshold below which the Maclaurin series is used directly.
const SERIES_MAX: f64 = 1.0 / 128.0;

/// Parameters up to this value use the first-order small-m expansion.
const SMALL_M: f64 = 1e-8;

/// The four Jacobi quantities at one argument, computed together.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JacobiElliptic {
    /// sn(u|m) = sin am(u|m).
    pub sn: f64,
    /// cn(u|m) = cos am(u|m).
    pub cn: f64,
    /// dn(u|m) = √(1 − m sn²(u|m)) (always > 0 for m < 1).
    pub dn: f64,
    /// The amplitude am(u|m), the inverse of F(·|m):
    /// continuous (unwrapped), odd, and am(u + 2K) = am(u) + π.
    /// For m = 1 it is the Gudermannian gd u = arctan sinh u.
    pub am: f64,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    /// m = 0: sin, cos, 1, u.
    Circular,
    /// m = 1: tanh, sech, sech, gd.
    Hyperbolic,
    /// 0 < m < 1.
    General,
}

/// A parameter m ∈ [0, 1] prepared for repeated evaluation of the Jacobi
/// elliptic functions: it caches K(m) to double-double precision and
/// k' = √(1−m).
///
/// Building one costs one double-double AGM; [`Jacobi::eval`] then reuses it.
/// Use it when many arguments share one parameter, as in a rigid-body
/// trajectory.
///
/// # Example
/// ```
/// # use rotorflow::special::Jacobi;
/// let jac = Jacobi::new(0.5)?;
/// let k = jac.quarter_period();
/// let at_k = jac.eval(k)?;
/// assert!((at_k.sn - 1.0).abs() < 1e-15);
/// assert!((at_k.am - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
/// # Ok::<(), rotorflow::special::EllipticError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jacobi {
    m: f64,
    m1: f64,
    kp: f64,
    k: Dd,
    kind: Kind,
    /// Reduced arguments `r <= hyp_max` use the m → 1 expansion.
    hyp_max: f64,
}

impl Jacobi {
    /// Prepares the parameter m (with m₁ = 1 − m formed exactly).
    ///
    /// # Errors
    /// [`EllipticError::NonFinite`], or [`EllipticError::OutOfDomain`] unless
    /// 0 ≤ m ≤ 1.
    pub fn new(m: f64) -> Result<Self, EllipticError> {
        check_domain("m", m, "[0, 1]", |m| (0.0..=1.0).contains(&m))?;
        Ok(Self::build(m, dd::one_minus(m)))
    }

    /// Prepares the parameter from its complement m₁ = 1 − m, which is
    /// taken as exact. Near the separatrix of the rigid body
    /// (m₁ = 10⁻¹⁶ … 10⁻⁶) m₁ is the well-known quantity;
    /// passing m = 1 − m₁ would round it.
    ///
    /// # Errors
    /// [`EllipticError::NonFinite`], or [`EllipticError::OutOfDomain`] unless
    /// 0 ≤ m₁ ≤ 1.
    pub fn from_complement(m1: f64) -> Result<Self, EllipticError> {
        check_domain("m1", m1, "[0, 1]", |m1| (0.0..=1.0).contains(&m1))?;
        Ok(Self::build(1.0 - m1, Dd::from_f64(m1)))
    }

    fn build(m: f64, m1: Dd) -> Self {
        let m1_f = m1.hi + m1.lo;
        if m1_f == 1.0 && m == 0.0 {
            return Jacobi {
                m: 0.0,
                m1: 1.0,
                kp: 1.0,
                k: dd::FRAC_PI_2,
                kind: Kind::Circular,
                hyp_max: f64::NEG_INFINITY,
            };
        }
        if m1_f == 0.0 {
            return Jacobi {
                m: 1.0,
                m1: 0.0,
                kp: 0.0,
                k: Dd::from_f64(f64::INFINITY),
                kind: Kind::Hyperbolic,
                hyp_max: f64::INFINITY,
            };
        }
        Jacobi {
            m,
            m1: m1_f,
            kp: m1.sqrt().hi,
            k: dd::complete_k_dd(m1),
            kind: Kind::General,
            // The first-order m1 expansion (DLMF 22.10.7-22.10.9) has a
            // relative remainder of about 0.1 m1^2 e^{2v} (measured with
            // mpmath); keep it below 1e-19: m1^2 e^{2v} <= 1e-18.
            hyp_max: -m1_f.ln() - 0.5 * 1e18f64.ln(),
        }
    }

    /// Returns the parameter m.
    pub fn parameter(&self) -> f64 {
        self.m
    }

    /// Returns the complementary parameter m₁ = 1 − m.
    pub fn complementary_parameter(&self) -> f64 {
        self.m1
    }

    /// Returns the quarter period K(m) (`+inf` for m = 1), correctly
    /// rounded from a double-double AGM.
    pub fn quarter_period(&self) -> f64 {
        self.k.hi
    }

    /// Returns sn, cn, dn and am at `u`.
    ///
    /// Accuracy: see [`jacobi_elliptic`].
    ///
    /// # Errors
    /// [`EllipticError::NonFinite`] for NaN or infinite `u`;
    /// [`EllipticError::ArgumentTooLarge`] if |u| ≥ 2⁵⁰K(m) for
    /// 0 < m < 1 (the period reduction would have no correct bits left).
    pub fn eval(&self, u: f64) -> Result<JacobiElliptic, EllipticError> {
        check_finite("u", u)?;
        match self.kind {
            Kind::Circular => {
                let (s, c) = u.sin_cos();
                Ok(JacobiElliptic {
                    sn: s,
                    cn: c,
                    dn: 1.0,
                    am: u,
                })
            }
            Kind::Hyperbolic => {
                let sech = 1.0 / u.cosh();
                Ok(JacobiElliptic {
                    sn: u.tanh(),
                    cn: sech,
                    dn: sech,
                    am: u.sinh().atan(),
                })
            }
            Kind::General => self.eval_general(u),
        }
    }

    fn eval_general(&self, u: f64) -> Result<JacobiElliptic, EllipticError> {
        let j = (u / self.k.hi).round();
        if j.abs() >= U_LIMIT_QUARTERS {
            return Err(EllipticError::ArgumentTooLarge {
                name: "u",
                value: u,
                limit: U_LIMIT_QUARTERS * self.k.hi,
            });
        }
        // v = u - j K as a double-double: j K_hi is formed exactly and
        // u - p is exact (Sterbenz).
        let (p, e) = dd::two_prod(j, self.k.hi);
        let (v, v_lo) = dd::two_sum(u - p, -e - j * self.k.lo);
        let r = v.abs();
        let (s, c, d) = self.reduced(r);
        // v is the rounded value of v + v_lo: apply the first-order Taylor
        // correction (sn' = cn dn, cn' = -sn dn, dn' = -m sn cn), otherwise the
        // rounding of v alone costs a relative |v| ε/2 in cn and dn, which
        // reaches 1e-14 for |v| ≈ K/2 near m = 1.
        let dr = if v < 0.0 { -v_lo } else { v_lo };
        let (s, c, d) = (s + c * d * dr, c - s * d * dr, d - self.m * s * c * dr);
        let s_v = if v < 0.0 { -s } else { s };
        let quadrant = (j as i64).rem_euclid(4);
        let (sn, cn, dn, theta) = match quadrant {
            0 => (s_v, c, d, s_v.atan2(c)),
            1 => (
                c / d,
                -self.kp * s_v / d,
                self.kp / d,
                (self.kp * s_v).atan2(c),
            ),
            2 => (-s_v, -c, d, s_v.atan2(c)),
            _ => (
                -c / d,
                self.kp * s_v / d,
                self.kp / d,
                (self.kp * s_v).atan2(c),
            ),
        };
        let am = if j == 0.0 {
            theta
        } else {
            j.mul_add(dd::FRAC_PI_2.hi, j.mul_add(dd::FRAC_PI_2.lo, theta))
        };
        Ok(JacobiElliptic { sn, cn, dn, am })
    }

    /// (sn, cn, dn)(r) for 0 ≤ r ≲ K/2.
    fn reduced(&self, r: f64) -> (f64, f64, f64) {
        if self.m <= SMALL_M {
            return self.circular_expansion(r);
        }
        if r <= self.hyp_max {
            return self.hyperbolic_expansion(r);
        }
        self.halve_and_double(r)
    }

    /// DLMF 22.10.4-22.10.6 to first order in m. For m <= 1e-8 and
    /// r <= K/2 the remainder is below 0.005 m^2 <= 5e-19 relative (measured
    /// with mpmath), and the closed form has fewer roundings than doubling.
    fn circular_expansion(&self, r: f64) -> (f64, f64, f64) {
        let m = self.m;
        let (s0, c0) = r.sin_cos();
        let t = 0.25 * m * (r - s0 * c0);
        (s0 - t * c0, c0 + t * s0, 1.0 - 0.5 * m * s0 * s0)
    }

    /// DLMF 22.10.7-22.10.9 to first order in m1, rearranged so that no
    /// intermediate grows like e²ʳ:
    /// sn = tanh + (m1/4)(tanh - r sech^2), cn = sech - (m1/4)(sinh tanh - r tanh sech),
    /// dn = sech + (m1/4)(sinh tanh + r tanh sech).
    fn hyperbolic_expansion(&self, r: f64) -> (f64, f64, f64) {
        let q = 0.25 * self.m1;
        let th = r.tanh();
        let sh = r.sinh();
        let se = 1.0 / r.cosh();
        let r_th_se = r * th * se;
        let sh_th = sh * th;
        (
            th + q * (th - r * se * se),
            se - q * (sh_th - r_th_se),
            se + q * (sh_th + r_th_se),
        )
    }

    /// Halving to the Maclaurin range, then doubling (see the module docs).
    fn halve_and_double(&self, r: f64) -> (f64, f64, f64) {
        let (m, m1, kp) = (self.m, self.m1, self.kp);
        let mut w = r;
        let mut halvings = 0u32;
        while w > SERIES_MAX {
            w *= 0.5;
            halvings += 1;
        }
        // Maclaurin series, DLMF 22.10.1-22.10.3, to w^8 (w^9 for sn is not
        // needed: the w^9 term is below 2e-20 relative for w <= 2^-7).
        let w2 = w * w;
        let m2 = m * m;
        let mut s = w
            * (1.0
                - w2 * ((1.0 + m) / 6.0
                    - w2 * ((1.0 + 14.0 * m + m2) / 120.0
                        - w2 * (1.0 + 135.0 * m + 135.0 * m2 + m2 * m) / 5040.0)));
        // y = 1 - cn, z = 1 - dn
        let mut y = 0.5
            * w2
            * (1.0
                - w2 * ((1.0 + 4.0 * m) / 12.0
                    - w2 * ((1.0 + 44.0 * m + 16.0 * m2) / 360.0
                        - w2 * (1.0 + 408.0 * m + 912.0 * m2 + 64.0 * m2 * m) / 20160.0)));
        let mut z = 0.5
            * m
            * w2
            * (1.0
                - w2 * ((4.0 + m) / 12.0
                    - w2 * ((16.0 + 44.0 * m + m2) / 360.0
                        - w2 * (64.0 + 912.0 * m + 408.0 * m2 + m2 * m) / 20160.0)));
        // Phase 1: track (sn, 1 - cn, 1 - dn) while cn and dn are near 1.
        let mut k = 0;
        while k < halvings && y <= 0.125 {
            let c = 1.0 - y;
            let d = 1.0 - z;
            let s2 = s * s;
            let inv = 1.0 / (d * d + m * s2 * (c * c));
            let two_s2 = 2.0 * s2;
            s = 2.0 * s * c * d * inv;
            y = two_s2 * (d * d) * inv;
            z = two_s2 * m * (c * c) * inv;
            k += 1;
        }
        let mut c = 1.0 - y;
        let mut d = 1.0 - z;
        // Phase 2: track (sn, cn, dn) directly; every numerator is a sum or
        // a product of positive terms for r <= K/2.
        while k < halvings {
            let s2 = s * s;
            let c2 = c * c;
            let d2 = d * d;
            let inv = 1.0 / (d2 + m * s2 * c2);
            let ks2 = kp * s2;
            let s_new = 2.0 * s * c * d * inv;
            let c_new = (c2 - ks2) * (c2 + ks2) * inv;
            let d_new = (c2 * d2 + m1 * s2) * inv;
            s = s_new;
            c = c_new;
            d = d_new;
            k += 1;
        }
        (s, c, d)
    }
}

/// Returns sn, cn, dn and am of
/// u for the parameter m, defined through the amplitude
/// u = ∫₀^am(u|m) dθ/√(1 − m sin²θ),
/// sn = sin am, cn = cos am,
/// dn = √(1−m sn²).
///
/// Domain: finite u (with |u| < 2⁵⁰K(m)), 0 ≤ m ≤ 1.
/// m = 0 gives (sin u, cos u, 1, u); m = 1 gives
/// (tanh u, sech u, sech u, gd u).
///
/// Accuracy against 30-digit mpmath values (644 arguments, |u| ≤ 10⁶,
/// m from 0 to 1 and m₁ down to 10⁻³⁰⁰), as relative error:
/// * away from zeros (|f| ≥ 10⁻⁸): sn ≤ 5.8e-16, cn ≤ 1.9e-15,
///   dn ≤ 1.9e-15, am ≤ 6.0e-16 (the largest values at m₁ = 10⁻⁶,
///   where 10 doubling steps are needed);
/// * at the f64 neighbours of the zeros u = jK (j ≤ 40): sn ≤ 9.6e-15,
///   cn ≤ 4.5e-15. This is an absolute error of ~|u| · 10⁻³², the
///   precision of the double-double K used in the reduction.
///
/// Source: DLMF §22.2, §22.16(i) (definitions), Table 22.4.3 (quarter-period
/// shifts), §22.8 (duplication), 22.10.1–22.10.9 (series and limiting forms),
/// 19.8.5 (K by AGM).
///
/// This rebuilds a [`Jacobi`] (one AGM) on every call; keep a [`Jacobi`] to
/// evaluate many arguments with one parameter.
///
/// # Errors
/// [`EllipticError::NonFinite`]; [`EllipticError::OutOfDomain`] unless
/// 0 ≤ m ≤ 1; [`EllipticError::ArgumentTooLarge`].
///
/// # Example
/// ```
/// # use rotorflow::special::jacobi_elliptic;
/// let j = jacobi_elliptic(0.7, 0.3)?;
/// assert!((j.sn * j.sn + j.cn * j.cn - 1.0).abs() < 1e-15);
/// assert!((j.dn * j.dn + 0.3 * j.sn * j.sn - 1.0).abs() < 1e-15);
/// # Ok::<(), rotorflow::special::EllipticError>(())
/// ```
pub fn jacobi_elliptic(u: f64, m: f64) -> Result<JacobiElliptic, EllipticError> {
    check_finite("u", u)?;
    Jacobi::new(m)?.eval(u)
}

/// Returns sn, cn, dn, am of u
/// for the parameter m = 1 − m₁, with the complementary parameter
/// 0 ≤ m₁ ≤ 1 taken as exact; see [`jacobi_elliptic`].
///
/// Use this near the rigid body's separatrix, where m₁ is known to full
/// relative precision but 1 − m₁ is not representable.
///
/// # Errors
/// [`EllipticError::NonFinite`]; [`EllipticError::OutOfDomain`] unless
/// 0 ≤ m₁ ≤ 1; [`EllipticError::ArgumentTooLarge`].
///
/// # Example
/// ```
/// # use rotorflow::special::jacobi_elliptic_complement;
/// // m1 = 1e-20: indistinguishable from tanh/sech at u = 1 to f64 precision
/// let j = jacobi_elliptic_complement(1.0, 1e-20)?;
/// assert!((j.sn - 1f64.tanh()).abs() < 4e-16);
/// # Ok::<(), rotorflow::special::EllipticError>(())
/// ```
pub fn jacobi_elliptic_complement(u: f64, m1: f64) -> Result<JacobiElliptic, EllipticError> {
    check_finite("u", u)?;
    Jacobi::from_complement(m1)?.eval(u)
}
