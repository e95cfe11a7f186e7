//! Exponential and logarithm of bivectors and even versors in any signature Cl(p, q, r).
//!
//! # The invariant decomposition
//! A bivector B of Cl(p, q, r) with N ≤ 5 is a sum B = B₁ + B₂ of at most two commuting
//! simple bivectors whose squares λᵢ = Bᵢ² are scalars: λ < 0 for a rotation, λ > 0 for a
//! boost, λ = 0 for a translation or a light-like generator (Roelfs & De Keninck, "Graded
//! symmetry groups: plane and simple", 2021/2023). Squaring B gives
//! B² = ⟨B²⟩₀ + B∧B = (λ₁ + λ₂) + 2B₁B₂, so the λᵢ are the roots of
//!
//!   λ² − ⟨B²⟩₀ λ + ¼ (B∧B)² = 0,
//!
//! and exp(B) = exp(B₁) exp(B₂) with exp(Bᵢ) = cos √−λᵢ + (sin √−λᵢ / √−λᵢ) Bᵢ,
//! cosh √λᵢ + (sinh √λᵢ / √λᵢ) Bᵢ or 1 + Bᵢ.
//!
//! # Without dividing by λ₁ − λ₂
//! The parts Bᵢ = (λᵢ B − ½ B (B∧B)) / (λᵢ − λⱼ) are ill-conditioned near λ₁ = λ₂
//! (isoclinic rotations, repeated boosts), and the λᵢ may be complex conjugates (in Cl(2, 2));
//! exp(B) is neither. rotorflow therefore never forms the Bᵢ. With W = B∧B (which commutes
//! with B, and W² is a scalar for N ≤ 5), B² = σ + W with σ = ⟨B²⟩₀, and B is a root of
//! (t² − a)(t² − b) with a, b = σ ∓ √(W²) = (x ∓ y)², x = √λ₁, y = √λ₂. Expanding the
//! series Σ Bᵏ/k! = cosh B + sinh B in this commutative algebra gives the exact identity
//!
//!   exp(B) = ½(k(a) + k(b)) + k[a, b] W + ½(h(a) + h(b)) B + h[a, b] B W,
//!
//! with k(t) = cosh √t, h(t) = sinh √t / √t (entire functions of t) and f[a, b] their divided
//! differences. In terms of x and y: ½(k(a) + k(b)) = cosh x cosh y,
//! k[a, b] = ½ sinhc x sinhc y, ½(h(a) + h(b)) = ½(sinhc(x + y) + sinhc(x − y)), and
//! h[a, b] = (sinhc(x + y) − sinhc(x − y)) / (4xy) = (cosh x sinhc y − sinhc x cosh y) /
//! (2(x² − y²)), of which rotorflow takes the form without cancellation (a power series when
//! |x| ≤ 1). Every case (isoclinic, null, complex λ, mixed screws with a grade-4 B²) is the
//! same formula, and B is scaled by a power of two first so that 1e-200 and 1e150 do not
//! underflow or overflow in B² or B W. Complex quotients use Smith's algorithm (no |z|²).
//! At a huge rotation angle the B and B W terms cancel, so V is known only to ~ε |B| (as
//! the angle itself); the result is then projected back onto the versors,
//! V ← (V Ṽ)^(−½) V, computed in the algebra of 1 and the 4-vector part of V Ṽ (for
//! N ≤ 5 an even V with V Ṽ = 1 is a versor), so that V Ṽ = 1 to round-off.
//!
//! # Logarithm
//! An even versor V of N ≤ 5 has grades 0, 2 and 4: V = c + v + Q. The scalar and 4-vector
//! parts form C = c + Q = cosh √(B²), a number in the two-dimensional algebra spanned by 1 and
//! Q (split-complex when Q² > 0, complex when Q² < 0, dual when Q² = 0), and v = sinh √(B²) /
//! √(B²) · B. rotorflow solves cosh ζ = C, sinh ζ = √(v²) in that algebra
//! (ζ = log1p(C − 1 + sinh ζ), with C − 1 = sinh²ζ/(C + 1) where that avoids cancellation)
//! and returns B = v ζ / sinh ζ.
//!
//! # Projective GA in any dimension
//! In Cl(p, 0, 1) write B = A + t e₀ with A Euclidean and t a vector (e₀ the null vector,
//! last). e₀ commutes with the even Euclidean elements and any product with two factors e₀
//! vanishes, so exp(B) = exp(A) (1 + u e₀) exactly, with
//! u = ∫₀¹ exp(−sA) t exp(sA) ds = φ(2\[A\]ᵀ) t, φ(X) = Σ Xᵏ/(k+1)!, applied plane by plane of
//! A's invariant decomposition: (sin α/α) 1 + ((1 − cos α)/α²) X on a plane of A with
//! α = 2θ. The logarithm inverts it: A = log of the Euclidean part (a rotor, through
//! [`super::Rotor::log`], exact for isoclinic rotations) and t = φ⁻¹ u. This route serves
//! every projective log and the projective exp above N = 5.
//!
//! # Dimensions
//! Euclidean signatures Cl(N, 0, 0) go through [`super::Bivector::exp`] and
//! [`super::Rotor::log`], and projective ones Cl(N − 1, 0, 1) through the route above, for
//! every N ≤ [`super::MULTIVECTOR_MAX_DIM`]. Other signatures take the closed form above up
//! to N = [`CLOSED_FORM_MAX_DIM`] = 5, where a bivector has at most two simple parts and W²
//! is a scalar. Above, B∧B∧B appears and these closed forms no longer hold; signatures with
//! 6 ≤ N ≤ [`GENERAL_MAX_DIM`] = 8 (conformal GA of 4D and 5D space, Cl(5, 1, 0) and
//! Cl(6, 1, 0), and every other mixed or degenerate metric) go through the general route of
//! `versor_general.rs`: scaling and squaring for exp, a Krylov space and the principal matrix
//! logarithm for log. Beyond N = 8 they return [`AlgebraError::UnsupportedDimension`].

use super::decompose::{RawPlane, decompose_components};
use super::error::{check_finite, within};
use super::small::{SMALL_MAX_DIM, Small};
use super::versor_general::{GENERAL_MAX_DIM, exp_general_small, exp_general_to, log_general_to};
use super::versor_n4 as n4;
use super::versor_pga3 as pga3;
use super::{AlgebraError, Bivector, Multivector, Rotor};
use nalgebra::Complex;
use smallvec::SmallVec;

type C64 = Complex<f64>;

/// The largest N for which [`Multivector::exp`] and [`Multivector::log`] accept a signature
/// other than Euclidean Cl(N, 0, 0) and projective Cl(N − 1, 0, 1), which go to
/// [`super::MULTIVECTOR_MAX_DIM`].
pub const CLOSED_FORM_MAX_DIM: usize = 5;

/// Default tolerance of [`Multivector::log`] on max |V Ṽ − 1| / max(1, max |Vᵢ|²): far above
/// the round-off of a versor built by products, far below any element worth calling one.
pub const VERSOR_TOLERANCE: f64 = 1e-8;

impl Multivector {
    /// Returns the exponential exp(B) = Σ Bᵏ/k! (geometric product) of a bivector B in any
    /// signature Cl(p, q, r).
    ///
    /// The result is an even versor (V Ṽ = 1): a rotor for a Euclidean signature, a motor
    /// (rigid motion) in projective GA Cl(N, 0, 1), a Lorentz transformation in Cl(1, 3). It
    /// acts by the sandwich X ↦ V X Ṽ. In 3D projective GA with e₄ the null vector (the
    /// projective e₀, last in rotorflow's basis order), the point at x is the trivector
    /// X = e₁₂₃ + x₁ e₂₃₄ − x₂ e₁₃₄ + x₃ e₁₂₄ (the dual of e₄ + x), and
    /// V = exp(−½ (d₁ e₁₄ + d₂ e₂₄ + d₃ e₃₄)) translates it by +d. A rotation generator
    /// exp(−½ θ e₁₂) turns e₁ toward e₂ by θ, as in the Euclidean convention.
    ///
    /// # Method
    /// 3D projective GA Cl(3, 0, 1) has its own fixed-size closed form (ganja.js's and
    /// klein's, written without dividing by the rotation angle), within a factor of about 2
    /// of a hand-written kernel (`cargo bench --bench versors`).
    /// Euclidean signatures use [`Bivector::exp`] (any N ≤ [`super::MULTIVECTOR_MAX_DIM`]).
    /// Other signatures with N ≤ 4 use exp(B) = C(B²) + S(B²) B with the entire functions
    /// C(z) = cosh √z and S(z) = sinh √z / √z, evaluated exactly at B² = α + βI (I the
    /// pseudoscalar) in the complex, split-complex or dual numbers that 1 and I span, on
    /// fixed-size arrays: the decomposition below without forming its parts. Those with
    /// N = 5 (and N ≤ 4 where the squares overflow) use the invariant decomposition
    /// (Roelfs & De Keninck, "Graded symmetry groups: plane and simple", 2021/2023):
    /// B = B₁ + B₂ with commuting simple Bᵢ whose squares λᵢ = Bᵢ² are scalars (negative:
    /// rotation, cos/sin; positive: boost, cosh/sinh; zero: translation or light-like, 1 + Bᵢ)
    /// and roots of λ² − ⟨B²⟩₀ λ + ¼ (B∧B)² = 0, so exp(B) = exp(B₁) exp(B₂). rotorflow
    /// never forms the Bᵢ, whose formula divides by λ₁ − λ₂. With W = B∧B and x, y = √λ₁,
    /// √λ₂ (complex where needed) the product expands to the exact identity
    ///
    ///   exp(B) = cosh x cosh y + ½ sinhc x sinhc y W + ½(sinhc(x + y) + sinhc(x − y)) B
    ///            + H B W,
    ///
    /// with sinhc z = sinh z / z and H = (sinhc(x + y) − sinhc(x − y)) / (4xy)
    /// = (cosh x sinhc y − sinhc x cosh y) / (2(x² − y²)), evaluated in whichever form has no
    /// cancellation (a power series for |x| ≤ 1). One formula covers isoclinic rotations and
    /// repeated boosts (x = ±y), null parts (y = 0: translations, light-like bivectors),
    /// screws (B² with a grade-4 part) and complex root pairs (Cl(2, 2)); B is first scaled
    /// by a power of two, so 1e-200 and 1e150 neither underflow nor overflow in B² or B W.
    ///
    /// Projective GA Cl(p, 0, 1) above N = 5 uses exp(A + t e₀) = exp(A) (1 + u e₀) with A
    /// the Euclidean part, u = ∫₀¹ exp(−sA) t exp(sA) ds in closed form plane by plane, for
    /// any N ≤ 16. Other signatures with 6 ≤ N ≤ [`GENERAL_MAX_DIM`] = 8 (a bivector then
    /// has three or more simple parts and these closed forms no longer apply), conformal GA
    /// of 4D space Cl(5, 1, 0) among them, use scaling and squaring in the algebra, accurate
    /// to a small multiple of ε |B| relative for a normal B (one whose exponential f64 can
    /// resolve: see `Overflow` below); beyond N = 8 they return
    /// [`AlgebraError::UnsupportedDimension`].
    ///
    /// A translation in 3D projective GA:
    /// ```
    /// use rotorflow::algebra::{Multivector, Signature};
    /// let pga = Signature::new(3, 0, 1)?; // e₄² = 0 is the projective e₀
    /// let b = Multivector::blade_by_name(pga, "e14", -0.5 * 2.0)?; // translate by 2 along e₁
    /// let m = b.exp()?; // = 1 − e₁₄, a translator
    /// assert_eq!(m.coefficient(0b1001), -1.0);
    /// let origin = Multivector::blade_by_name(pga, "e123", 1.0)?;
    /// let moved = &(&m * &origin) * &m.reverse();
    /// // the point x = (2, 0, 0): e₁₂₃ + 2 e₂₃₄
    /// assert_eq!(moved.coefficient(0b1110), 2.0);
    /// assert_eq!(moved.coefficient(0b0111), 1.0);
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    ///
    /// A boost of rapidity 0.7 along e₂ in the spacetime algebra Cl(1, 3):
    /// ```
    /// use rotorflow::algebra::{Multivector, Signature};
    /// let sta = Signature::new(1, 3, 0)?; // e₁ is time, e₂ e₃ e₄ space
    /// let v = Multivector::blade_by_name(sta, "e12", 0.35)?.exp()?; // exp(½ · 0.7 e₁₂)
    /// assert!((v.scalar_part() - 0.35f64.cosh()).abs() < 1e-15);
    /// assert!((v.coefficient(0b11) - 0.35f64.sinh()).abs() < 1e-15);
    /// let t = Multivector::basis_blade(sta, 0b1);
    /// let moved = &(&v * &t) * &v.reverse(); // e₁ ↦ cosh 0.7 e₁ − sinh 0.7 e₂
    /// assert!((moved.coefficient(0b1) - 0.7f64.cosh()).abs() < 1e-15);
    /// assert!((moved.coefficient(0b10) + 0.7f64.sinh()).abs() < 1e-15);
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    ///
    /// # Errors
    /// [`AlgebraError::NonFinite`] for NaN or infinite coefficients;
    /// [`AlgebraError::NotABivector`] if other grades are present;
    /// [`AlgebraError::UnsupportedDimension`] for N > 8 in a signature neither Euclidean nor
    /// projective;
    /// [`AlgebraError::AngleTooLarge`] (Euclidean, |B| > `f64::MAX`/2, or such a Euclidean
    /// part of a projective B above N = 5);
    /// [`AlgebraError::Overflow`] when a coefficient of the result exceeds `f64::MAX` (a boost
    /// of rapidity above ≈ 710), or, for N ≥ 6 with two or more null vectors, when the
    /// squarings do (rotation angles of 10¹⁰⁰ and more beside null parts of that size), or,
    /// outside the Euclidean and projective signatures, when the result leaves the group
    /// without overflowing: V Ṽ off 1 by more than 10⁻¹² |B| relative to max |Vᵢ|². For
    /// N ≥ 6 that happens beside components near 10⁹⁰ and for a B far from normal (nearly
    /// null planes of size 10⁶ beside each other), whose exponential grows with a power of
    /// |B| and loses as many digits; for N ≤ 5 where neither the closed form nor scaling and
    /// squaring keeps the group (a rotation of 10¹⁶ and more in a nearly null plane beside
    /// other parts).
    #[inline]
    pub fn exp(&self) -> Result<Multivector, AlgebraError> {
        // 3D PGA on fixed-size arrays; everything else (and every error) below.
        if pga3::is_pga3(self.signature())
            && let Some(v) = pga3::exp(self)
        {
            return Ok(v);
        }
        let mut out = Multivector::zero(self.signature());
        if n4::applies(self.signature()) && n4::exp_to(self, &mut out) {
            return Ok(out);
        }
        self.exp_any_signature(&mut out)?;
        Ok(out)
    }

    /// [`Multivector::exp`] written into `out`, an element of the same algebra whose storage
    /// is reused: no heap allocation for N ≤ 6 in every signature. Every route works there on
    /// stack storage (multivectors of up to 64 coefficients, rotors of up to 32, the invariant
    /// decomposition's matrices up to 8 × 8), so [`Multivector::exp`] allocates only the
    /// result's storage, and only from N = 5 (multivectors keep up to 16 coefficients
    /// inline). Above N = 6 the intermediate multivectors and rotors are on the heap. On an
    /// error `out` is unspecified.
    ///
    /// ```
    /// use rotorflow::algebra::{Multivector, Signature};
    /// let cga3 = Signature::new(4, 1, 0)?; // conformal GA of 3D space
    /// let b = Multivector::blade_by_name(cga3, "e45", 0.3)?; // a dilation generator
    /// let mut v = Multivector::zero(cga3);
    /// b.exp_to(&mut v)?;
    /// assert_eq!(v, b.exp()?);
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    ///
    /// # Errors
    /// [`AlgebraError::SignatureMismatch`] if `out` belongs to another algebra; those of
    /// [`Multivector::exp`].
    pub fn exp_to(&self, out: &mut Multivector) -> Result<(), AlgebraError> {
        check_same_algebra(self, out)?;
        if pga3::is_pga3(self.signature()) && pga3::exp_to(self, out) {
            return Ok(());
        }
        if n4::applies(self.signature()) && n4::exp_to(self, out) {
            return Ok(());
        }
        self.exp_any_signature(out)
    }

    /// [`Multivector::exp`] in every signature, with the checks, into `out` (same algebra).
    #[inline(never)]
    fn exp_any_signature(&self, out: &mut Multivector) -> Result<(), AlgebraError> {
        check_finite(self.as_slice(), "bivector")?;
        check_bivector(self, "the exponential")?;
        let sig = self.signature();
        // Euclidean signatures take the rotor route: near π it keeps V's bivector part
        // relatively accurate (sin θ times the plane), which the closed form below does not
        // in a generic plane of Cl(5, 0, 0).
        if sig.is_euclidean() {
            let n = self.dim();
            out.as_mut_slice().fill(0.0);
            if n <= 4 {
                let r = euclidean_bivector(self)?.try_exp()?;
                for (k, c) in r.terms() {
                    out.as_mut_slice()[k as usize] = c;
                }
            } else {
                exp_euclidean_wide(self, out)?;
            }
            return Ok(());
        }
        let result = if self.dim() > SMALL_MAX_DIM && is_projective(sig) {
            exp_projective(self)?
        } else if self.dim() > CLOSED_FORM_MAX_DIM && is_projective(sig) {
            let v = exp_projective_small(self)?;
            if !v.as_slice().iter().all(|c| c.is_finite()) {
                return Err(AlgebraError::Overflow {
                    what: "the exponential",
                });
            }
            v.write_to(out);
            return Ok(());
        } else if self.dim() > CLOSED_FORM_MAX_DIM {
            if self.dim() > GENERAL_MAX_DIM {
                return Err(AlgebraError::UnsupportedDimension {
                    operation: "the exponential",
                    signature: sig,
                    max: GENERAL_MAX_DIM,
                });
            }
            let known = exp_general_to(self, out)?;
            // The squarings can leave the group without overflowing: coefficients that
            // underflow beside a huge B, or a B far from normal (nearly null planes of 1e6
            // beside each other in Cl(4, 2)), whose exponential grows with a power of |B| and
            // loses digits with it. V Ṽ = 1 to the accuracy exp has for a normal B (about
            // 2⁻⁵³ |B| relative) is checked, with one product of the grades V Ṽ can have,
            // unless the last pull onto the group left it at round-off (max |V Ṽ − 1| ≤ 16 ε
            // for max |Vᵢ| ≤ 4, where max |Vᵢ|² ≥ 2^(1−N) ≥ 1/128).
            let b_top = self.max_abs().max(1.0);
            if known > 16.0 * f64::EPSILON && versor_defect(out) > 1e-12 * b_top {
                return Err(AlgebraError::Overflow {
                    what: "the exponential",
                });
            }
            return Ok(());
        } else {
            return if self.dim() <= 4 {
                exp_small::<16>(self, out)
            } else {
                exp_small::<32>(self, out)
            };
        };
        if !result.as_slice().iter().all(|c| c.is_finite()) {
            return Err(AlgebraError::Overflow {
                what: "the exponential",
            });
        }
        *out = result;
        Ok(())
    }

    /// Returns a bivector B with exp(B) = V for an even versor V (V Ṽ = 1), in any signature
    /// with N ≤ [`GENERAL_MAX_DIM`] = 8 and in Euclidean and projective (Cl(p, 0, 1))
    /// signatures up to N = [`super::MULTIVECTOR_MAX_DIM`].
    ///
    /// # Method
    /// Euclidean: [`Rotor::log`]. Projective: the log A of the Euclidean part (a rotor) and
    /// the translation part t = φ⁻¹ u that inverts [`Multivector::exp`]'s projective form.
    /// Other signatures (N ≤ 5): V = c + v + Q (grades 0, 2, 4); C = c + Q is cosh √(B²) in
    /// the algebra spanned by 1 and Q (split-complex for Q² > 0, complex for Q² < 0, dual for
    /// Q² = 0), v = (sinh √(B²)/√(B²)) B; solving cosh ζ = C there gives B = v ζ / sinh ζ.
    /// Other signatures with 6 ≤ N ≤ 8: the principal logarithm of the matrix of left
    /// multiplication by V on the algebra V generates (a Krylov space of dimension at most
    /// 2^⌊N/2⌋), polished by Gauss–Newton steps against V itself.
    ///
    /// # Branch
    /// The principal logarithm: every rotation part has angle θ ∈ \[0, π\] in exp(θ P̂)
    /// (the sandwich turns by 2θ), boosts and null parts are unique. Where V's rotation parts
    /// mix in a 4D-like split (two planes sharing the 4-vector part of V, as in Cl(2, 2) or
    /// the Euclidean 4D rotors), the sum of the two angles is at most π, as in
    /// [`Rotor::log`]; for 6 ≤ N ≤ 8 in signatures neither Euclidean nor projective, every
    /// joint angle |±θ₁ ± θ₂ ± …| is below π (the sum of the rotation angles below π). So
    /// log(exp(B)) = B whenever B's rotation angles are inside that domain. Euclidean
    /// signatures return [`Rotor::log`].
    ///
    /// # Angle π
    /// At exactly θ = π (V = −exp(B′) with a rotation by π in a plane V does not determine)
    /// the logarithm is not unique: a Euclidean V gets one of them (as [`Rotor::log`]); in
    /// other signatures this point returns [`AlgebraError::NoLogarithm`]. So does
    /// V = −exp(B′) for a simple boost B′: in Cl(1, 3) it has the logarithms B′ ± π B̂′I (the
    /// dual plane of a boost is a rotation plane commuting with it), both on the cut, and
    /// neither is returned. Near π the logarithm is ill-conditioned: the plane of
    /// a rotation by π − δ is fixed only by a bivector part of V of size ~δ, so the result
    /// (and exp(log V) − V, where two planes share the 4-vector part) carries errors
    /// ~ε/δ; a single plane at π ± 10⁻¹² still gives exp(log V) = V to round-off.
    ///
    /// # Errors
    /// [`AlgebraError::NonFinite`]; [`AlgebraError::NotAVersor`] if V has odd grades or
    /// max |V Ṽ − 1| exceeds [`VERSOR_TOLERANCE`] · max(1, max |Vᵢ|²) (or that bound
    /// overflows); [`AlgebraError::Overflow`] if a projective logarithm exceeds `f64::MAX`;
    /// [`AlgebraError::UnsupportedDimension`] for N > 8 in a signature neither Euclidean nor
    /// projective;
    /// [`AlgebraError::NoLogarithm`] for elements without a real bivector logarithm
    /// (−exp(B) for a boost B in Cl(1, 1), Cl(2, 1) or Cl(1, 2), −(1 + N) for a light-like
    /// N in Cl(1, 3), −exp(t) for a translation t in 2D projective GA) and on the branch cut
    /// at angle π described above (which includes −exp(B) for a boost B in Cl(1, 3));
    /// [`AlgebraError::LogarithmInaccurate`] where V's coefficients span more orders of
    /// magnitude than f64 resolves (boosts of rapidity beyond about 25 beside rotations,
    /// huge null parts beside others with several null vectors, a rotation in a nearly null
    /// plane whose angle is lost in the difference of two large squares): every logarithm
    /// returned outside the Euclidean signatures is checked to give back V through
    /// [`Multivector::exp`], max |exp(log V) − V| ≤ 10⁻¹⁰ · max(1, max |Vᵢ|) ·
    /// max(1, max |(log V)ᵢ|), and refused otherwise, so that no wrong bivector is returned.
    ///
    /// ```
    /// use rotorflow::algebra::{Multivector, Signature};
    /// let pga = Signature::new(3, 0, 1)?;
    /// // A screw: rotation in e12 and translation along e3 (e34).
    /// let b = &Multivector::blade_by_name(pga, "e12", 0.4)?
    ///     + &Multivector::blade_by_name(pga, "e34", -1.5)?;
    /// let back = b.exp()?.log()?;
    /// assert!((&back - &b).max_abs() < 1e-15);
    /// # Ok::<(), rotorflow::algebra::AlgebraError>(())
    /// ```
    #[inline]
    pub fn log(&self) -> Result<Multivector, AlgebraError> {
        // 3D PGA on fixed-size arrays; everything else (and every error) below.
        if pga3::is_pga3(self.signature())
            && let Some(b) = pga3::log(self, VERSOR_TOLERANCE)
        {
            return Ok(b);
        }
        let mut out = Multivector::zero(self.signature());
        self.log_any_signature(&mut out)?;
        Ok(out)
    }

    /// [`Multivector::log`] written into `out`, an element of the same algebra whose storage
    /// is reused: no heap allocation for N ≤ 6 in every signature. The closed forms, the
    /// rotor logarithm (rotation matrix, eigen-decomposition and Newton refinement), the
    /// projective route and the Krylov logarithm of the general route (its basis, the Krylov
    /// matrix of at most 16 × 16, its square roots and logarithm, and the least-squares
    /// polish) all work on stack storage there, so [`Multivector::log`] allocates only the
    /// result's storage, and only from N = 5. Above N = 6 the intermediate multivectors,
    /// rotors and matrices spill to the heap. On an error `out` is unspecified.
    ///
    /// # Errors
    /// [`AlgebraError::SignatureMismatch`] if `out` belongs to another algebra; those of
    /// [`Multivector::log`].
    pub fn log_to(&self, out: &mut Multivector) -> Result<(), AlgebraError> {
        check_same_algebra(self, out)?;
        if pga3::is_pga3(self.signature()) && pga3::log_to(self, VERSOR_TOLERANCE, out) {
            return Ok(());
        }
        self.log_any_signature(out)
    }

    /// [`Multivector::log`] in every signature, with the checks, into `out` (same algebra).
    #[inline(never)]
    fn log_any_signature(&self, out: &mut Multivector) -> Result<(), AlgebraError> {
        check_finite(self.as_slice(), "versor")?;
        let odd = self
            .terms()
            .filter(|(k, _)| k.count_ones() % 2 == 1)
            .fold(0.0f64, |m, (_, c)| m.max(c.abs()));
        if odd != 0.0 {
            return Err(AlgebraError::NotAVersor {
                reason: "it has odd grades",
                deviation: odd,
            });
        }
        let sig = self.signature();
        let deviation = if pga3::is_pga3(sig) {
            pga3::versor_deviation(self)
        } else if self.dim() <= 4 {
            unit_deviation::<16>(self)
        } else if self.dim() <= CLOSED_FORM_MAX_DIM {
            unit_deviation::<32>(self)
        } else if self.dim() <= SMALL_MAX_DIM {
            unit_deviation_64(self)
        } else {
            let mut vv = self.geometric(&self.reverse());
            vv.as_mut_slice()[0] -= 1.0;
            vv.max_abs()
        };
        let scale = self.max_abs().powi(2).max(1.0);
        if !scale.is_finite() {
            return Err(AlgebraError::NotAVersor {
                reason: "V Ṽ overflows f64",
                deviation,
            });
        }
        if !within(deviation, VERSOR_TOLERANCE * scale) {
            return Err(AlgebraError::NotAVersor {
                reason: "V Ṽ is not 1",
                deviation,
            });
        }
        if sig.is_euclidean() && self.dim() == CLOSED_FORM_MAX_DIM {
            // The closed form below (no decomposition, no heap); at angle π, where it
            // returns no logarithm, the rotor route picks one.
            if log_small::<32>(self, out).is_ok() {
                return Ok(());
            }
        }
        if sig.is_euclidean() {
            let n = self.dim();
            let b = if n <= 4 {
                Rotor::from_multivector_unchecked(self).log()
            } else {
                log_euclidean_wide(self)
            };
            out.as_mut_slice().fill(0.0);
            for (i, j) in super::pairs(self.dim()) {
                out.as_mut_slice()[(1usize << i) | (1usize << j)] = b.get(i, j);
            }
            return Ok(());
        }
        if is_projective(sig) {
            log_projective(self, out)?;
            if !out.as_slice().iter().all(|c| c.is_finite()) {
                return Err(AlgebraError::Overflow {
                    what: "the logarithm",
                });
            }
            let residual = if self.dim() <= 4 {
                closed_form_residual::<16>(out, self)
            } else if self.dim() <= CLOSED_FORM_MAX_DIM {
                closed_form_residual::<32>(out, self)
            } else if self.dim() <= SMALL_MAX_DIM {
                exp_projective_small(out).map_or(f64::INFINITY, |e| {
                    (&e - &Small::<64>::from_multivector(self)).max_abs()
                })
            } else {
                exp_projective(out).map_or(f64::INFINITY, |e| (&e - self).max_abs())
            };
            return check_log_residual(residual, self.max_abs(), out.max_abs());
        }
        if self.dim() > CLOSED_FORM_MAX_DIM {
            if self.dim() > GENERAL_MAX_DIM {
                return Err(AlgebraError::UnsupportedDimension {
                    operation: "the logarithm",
                    signature: sig,
                    max: GENERAL_MAX_DIM,
                });
            }
            return log_general_to(self, out);
        }
        if self.dim() <= 4 {
            log_small::<16>(self, out)
        } else {
            log_small::<32>(self, out)
        }
    }
}

/// The closed-form exponential of a finite bivector of N ≤ 5 on stack storage of L ≥ 2^N
/// coefficients, written into `out`.
fn exp_small<const L: usize>(b: &Multivector, out: &mut Multivector) -> Result<(), AlgebraError> {
    exp_small_core(&Small::<L>::from_multivector(b))?.write_to(out);
    Ok(())
}

/// [`exp_small`] on stack storage.
fn exp_small_core<const L: usize>(b: &Small<L>) -> Result<Small<L>, AlgebraError> {
    // A fallback's result is kept only in the group, to the ε |B| that bounds any exp(B).
    let bound = 1e-12 * b.max_abs().max(1.0);
    let in_group = |v: Small<L>| {
        if unit_error(&v) <= bound {
            Ok(v)
        } else {
            Err(AlgebraError::Overflow {
                what: "the exponential",
            })
        }
    };
    let v = exp_closed_form(b);
    if !v.as_slice().iter().all(|c| c.is_finite()) {
        // The closed form's intermediate products can overflow beside null parts of 1e100
        // and more where exp(B) itself is finite; the general route scales the null vectors.
        return in_group(exp_general_small(b)?);
    }
    let (v, defect) = renormalize(v);
    if defect <= 1e-8 {
        return Ok(v);
    }
    // The roots λ of the closed form come from ⟨B²⟩₀ and (B∧B)², whose discriminant cancels
    // for a huge, nearly isoclinic B (|B| ≈ 10⁹ beside a part of size 1): no f64 formula in
    // those two numbers recovers them, and V is then no versor at all. Scaling and squaring
    // needs no roots. Where it overflows (huge null parts beside several null vectors), or
    // leaves the group without overflowing (rotation angles of 1e175 beside boosts of 1e18:
    // the squarings underflow every coefficient), the closed form's V stands if it is in the
    // group to the bound above; where neither is (a rotation of 1e16 in a nearly null
    // plane), the exponential is an error.
    if let Ok(g) = exp_general_small(b) {
        let top = g.max_abs();
        if unit_deviation_of(&g) / (top * top).max(1.0) <= defect {
            return in_group(g);
        }
    }
    in_group(v)
}

/// [`Multivector::exp`] of a finite bivector of N ≤ 5 outside the Euclidean signatures, on
/// stack storage and by the same route (3D PGA's fixed-size form, the fixed-size route of
/// N ≤ 4, the closed form with its fallbacks), or None where it returns an error: the
/// logarithm is checked with it, so that exp(log V) is what was checked.
fn exp_public<const L: usize>(b: &Small<L>) -> Option<Small<L>> {
    let sig = b.signature();
    if sig.dim() <= 4 {
        let mut m = Multivector::zero(sig);
        b.write_to(&mut m);
        if pga3::is_pga3(sig)
            && let Some(v) = pga3::exp(&m)
        {
            return Some(Small::from_multivector(&v));
        }
        let mut e = Multivector::zero(sig);
        if n4::applies(sig) && n4::exp_to(&m, &mut e) {
            return Some(Small::from_multivector(&e));
        }
    }
    exp_small_core(b).ok()
}

/// max |V Ṽ − 1| of an element of N ≤ 5 on stack storage.
fn unit_deviation<const L: usize>(v: &Multivector) -> f64 {
    unit_deviation_of(&Small::<L>::from_multivector(v))
}

/// [`unit_deviation`] of an element already on stack storage.
fn unit_deviation_of<const L: usize>(v: &Small<L>) -> f64 {
    let mut vv = v.geometric(&v.reverse());
    vv.as_mut_slice()[0] -= 1.0;
    vv.max_abs()
}

/// [`unit_deviation`] for N = 6, out of line so that its 64-coefficient products do not
/// enlarge the stack frame of the smaller signatures' route.
#[inline(never)]
fn unit_deviation_64(v: &Multivector) -> f64 {
    unit_deviation::<64>(v)
}

/// max |exp(B) − V| with exp by the closed form, for N ≤ 5.
fn closed_form_residual<const L: usize>(b: &Multivector, v: &Multivector) -> f64 {
    let e = exp_closed_form(&Small::<L>::from_multivector(b));
    (&e - &Small::<L>::from_multivector(v)).max_abs()
}

/// The closed-form logarithm of a checked even versor of N ≤ 5, refined and verified,
/// written into `out`.
fn log_small<const L: usize>(v: &Multivector, out: &mut Multivector) -> Result<(), AlgebraError> {
    let v_given = v;
    let given = Small::<L>::from_multivector(v);
    // Near the angle π the closed form reads the plane from a bivector part of size sin θ,
    // where a defect V Ṽ − 1 of a few ε already turns it by ε / sin θ: the logarithm is
    // taken of the versor nearest V (no change beyond round-off), and checked against V.
    let v = renormalize_exactly(given);
    let b = log_closed_form(&v)?;
    if b.as_slice().iter().all(|c| c.is_finite()) {
        let (b, _) = refine(&v, b);
        // Every logarithm returned is checked with the exponential `exp` takes here, so that
        // exp(log V) is what was checked: the refinement's closed form and the general
        // route's scaling and squaring differ from it where L is ill-conditioned (a rotation
        // in a nearly null plane, whose angle is the difference of two large squares).
        let check = |l: &Small<L>| {
            let residual = exp_public(l).map_or(f64::INFINITY, |e| (&e - &given).max_abs());
            check_log_residual(residual, given.max_abs(), l.max_abs())
        };
        if let Err(e) = check(&b) {
            // The closed form's roots can be lost where the general route, which needs none,
            // still finds the logarithm.
            if log_general_to(v_given, out).is_err() {
                return Err(e);
            }
            return check(&Small::<L>::from_multivector(out)).map_err(|_| e);
        }
        b.write_to(out);
        Ok(())
    } else {
        Err(AlgebraError::NoLogarithm {
            reason: "a rotation by π in a plane the versor does not determine",
        })
    }
}

/// Err(SignatureMismatch) unless `out` belongs to the algebra of `m`.
fn check_same_algebra(m: &Multivector, out: &Multivector) -> Result<(), AlgebraError> {
    if m.signature() == out.signature() {
        Ok(())
    } else {
        Err(AlgebraError::SignatureMismatch {
            left: m.signature(),
            right: out.signature(),
        })
    }
}

/// The bivector of a grade-2 element of Cl(N, 0, 0), built in place (no temporary list).
fn euclidean_bivector(m: &Multivector) -> Result<Bivector, AlgebraError> {
    let n = m.dim();
    let mut b = Bivector::try_zero(n)?;
    for i in 0..n {
        for j in i + 1..n {
            b.set(i, j, m.coefficient((1 << i) | (1 << j)));
        }
    }
    Ok(b)
}

/// Projective GA Cl(p, 0, 1): one null vector, the last.
fn is_projective(sig: super::Signature) -> bool {
    sig.q() == 0 && sig.r() == 1
}

/// Coordinates of a vector of the Euclidean part of Cl(p, 0, 1), inline for p ≤ 16.
type Coords = SmallVec<[f64; 16]>;

/// The Euclidean part A (blades without the null vector e₀) and the translation part t
/// (B = A + t e₀) of a bivector of Cl(p, 0, 1).
fn split_projective(b: &Multivector) -> Result<(Bivector, Coords), AlgebraError> {
    let p = b.dim() - 1;
    let null = 1u64 << p;
    let mut a = Bivector::try_zero(p)?;
    for i in 0..p {
        for j in i + 1..p {
            a.set(i, j, b.coefficient((1 << i) | (1 << j)));
        }
    }
    let t = (0..p).map(|i| b.coefficient((1 << i) | null)).collect();
    Ok((a, t))
}

/// Applies φ(X) = Σ Xᵏ/(k+1)! = ∫₀¹ expm(sX) ds, X = 2\[A\]ᵀ, to t (or its inverse), plane by
/// plane: on the plane of θ u∧v (α = 2θ) φ = (sin α/α) 1 + ((1 − cos α)/α²) X, and the
/// identity on the complement. For p ≤ 3, A is a single plane (or zero) and its projector is
/// formed directly, without the general decomposition.
fn phi_projective(a: &Bivector, t: &[f64], inverse: bool) -> Result<Coords, AlgebraError> {
    let mut out: Coords = SmallVec::from_slice(t);
    let tv = super::Vector::from_components(t)?;
    if t.len() <= 3 {
        let theta = a.norm();
        if theta == 0.0 {
            return Ok(out);
        }
        let mut tk: Coords = SmallVec::from_slice(t);
        if t.len() == 3 {
            // The unit normal n̂ of A's plane (its Euclidean dual); tk = t − (t·n̂) n̂.
            let n = [
                a.get(1, 2) / theta,
                -a.get(0, 2) / theta,
                a.get(0, 1) / theta,
            ];
            let tn = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
            for i in 0..3 {
                tk[i] -= tn * n[i];
            }
        }
        // t⌋A = tk⌋A: the normal component contracts to zero.
        let xt = tv.left_contract(a);
        apply_plane(&mut out, &tk, xt.as_slice(), 2.0 * theta, inverse)?;
        return Ok(out);
    }
    phi_of_planes(&decompose_components(a.dim(), a.as_slice()), t, inverse)
}

/// [`phi_projective`] for p ≥ 4 from the planes of A's invariant decomposition.
fn phi_of_planes(planes: &[RawPlane], t: &[f64], inverse: bool) -> Result<Coords, AlgebraError> {
    let mut out: Coords = SmallVec::from_slice(t);
    for plane in planes {
        let (theta, u, v) = (plane.theta, &plane.u, &plane.v);
        let dot = |x: &[f64]| t.iter().zip(x).map(|(a, b)| a * b).sum::<f64>();
        let (cu, cv) = (dot(u), dot(v));
        // tk = (t·u) u + (t·v) v and tk⌋(θ u∧v) = θ ((tk·u) v − (tk·v) u).
        let tk: Coords = (0..t.len()).map(|i| cu * u[i] + cv * v[i]).collect();
        let xt: Coords = (0..t.len())
            .map(|i| theta * (cu * v[i] - cv * u[i]))
            .collect();
        apply_plane(&mut out, &tk, &xt, 2.0 * theta, inverse)?;
    }
    Ok(out)
}

/// Adds (φ − 1) tk to `out` on one plane of angle α, with tk the part of t in the plane and
/// xt = tk⌋(θ u∧v) (or the inverse of φ there).
fn apply_plane(
    out: &mut [f64],
    tk: &[f64],
    xt: &[f64],
    alpha: f64,
    inverse: bool,
) -> Result<(), AlgebraError> {
    let half = 0.5 * alpha;
    let ca = alpha.sin() / alpha;
    let cb = 2.0 * (half.sin() / alpha).powi(2);
    let (ka, kb) = if inverse {
        let den = ca * ca + cb * cb * alpha * alpha;
        if den.is_nan() || den <= 1e-30 {
            return Err(AlgebraError::NoLogarithm {
                reason: "a rotation by π in a plane the versor does not determine",
            });
        }
        (ca / den, -cb / den)
    } else {
        (ca, cb)
    };
    for i in 0..out.len() {
        out[i] += (ka - 1.0) * tk[i] + kb * 2.0 * xt[i];
    }
    Ok(())
}

/// exp in Cl(p, 0, 1), any p: with B = A + t e₀ (e₀ commutes with the even Euclidean part,
/// and any product with two factors e₀ vanishes), exp(B) = exp(A) (1 + u e₀) with
/// u = ∫₀¹ exp(−sA) t exp(sA) ds = φ(2\[A\]ᵀ) t.
fn exp_projective(b: &Multivector) -> Result<Multivector, AlgebraError> {
    let sig = b.signature();
    let p = b.dim() - 1;
    let null = 1u64 << p;
    let (a, t) = split_projective(b)?;
    let r = a.try_exp()?;
    let u = phi_projective(&a, &t, false)?;
    let mut rm = Multivector::zero(sig);
    for (k, c) in r.terms() {
        rm.as_mut_slice()[k as usize] = c;
    }
    let mut um = Multivector::zero(sig);
    for (i, c) in u.iter().enumerate() {
        um.as_mut_slice()[((1u64 << i) | null) as usize] = *c;
    }
    Ok(&rm + &rm.geometric(&um))
}

/// The Euclidean exp above N = 4 into `out` (zeroed), with the rotor's coefficients on the
/// stack up to N = 6 (a Rotor keeps only N ≤ 5 inline). Out of line, so that its buffers do
/// not enlarge the stack frame of the small signatures' route.
#[inline(never)]
fn exp_euclidean_wide(b: &Multivector, out: &mut Multivector) -> Result<(), AlgebraError> {
    let n = b.dim();
    let r = super::rotor::exp_even(&euclidean_bivector(b)?)?;
    for (i, &c) in r.iter().enumerate() {
        out.as_mut_slice()[super::rotor::even_blade(n, i) as usize] = c;
    }
    Ok(())
}

/// The Euclidean log above N = 4, with the rotor's coefficients on the stack up to N = 6. Out
/// of line, for the reason of [`exp_euclidean_wide`].
#[inline(never)]
fn log_euclidean_wide(v: &Multivector) -> Bivector {
    let n = v.dim();
    let r: super::rotor::EvenBuf = (0..super::rotor::even_len(n))
        .map(|i| v.coefficient(super::rotor::even_blade(n, i)))
        .collect();
    super::rotor::log_even(n, &r)
}

/// [`exp_projective`] on the stack, for N ≤ 6. Out of line, for the reason of
/// [`exp_euclidean_wide`].
#[inline(never)]
fn exp_projective_small(b: &Multivector) -> Result<Small<64>, AlgebraError> {
    let sig = b.signature();
    let p = b.dim() - 1;
    let null = 1u64 << p;
    let (a, t) = split_projective(b)?;
    let (r, u) = if p >= 5 {
        // exp(A) and φ share A's invariant decomposition (Bivector::exp's route for p ≥ 5),
        // formed once; the checks are those of Bivector::try_exp (A is finite here).
        let norm = a.norm();
        if !within(norm, f64::MAX / 2.0) {
            return Err(AlgebraError::AngleTooLarge { norm });
        }
        let planes = decompose_components(p, a.as_slice());
        (
            super::rotor::exp_of_planes(p, &planes),
            phi_of_planes(&planes, &t, false)?,
        )
    } else {
        (a.try_exp()?, phi_projective(&a, &t, false)?)
    };
    let mut rm = Small::<64>::zero(sig);
    for (k, c) in r.terms() {
        rm.as_mut_slice()[k as usize] = c;
    }
    let mut um = Small::<64>::zero(sig);
    for (i, c) in u.iter().enumerate() {
        um.as_mut_slice()[((1u64 << i) | null) as usize] = *c;
    }
    Ok(&rm + &rm.geometric(&um))
}

/// log in Cl(p, 0, 1), any p: V = R + R U with R the Euclidean part (a rotor) and U = u e₀;
/// A = log R ([`Rotor::log`]) and t = φ(2\[A\]ᵀ)⁻¹ u.
fn log_projective(v: &Multivector, out: &mut Multivector) -> Result<(), AlgebraError> {
    let p = v.dim() - 1;
    let null = 1u64 << p;
    let x = v.as_slice();
    let r = Rotor::from_blades(p, |k| x[k as usize]);
    let a = r.log();
    // u e₀ = R̃ (V − R): only the products of R̃'s blades with the blades of V that hold e₀,
    // landing on a vector times e₀. Both factors are Euclidean apart from e₀ (the last
    // vector, so it never reorders), and every metric factor is +1.
    let mut u: Coords = SmallVec::from_elem(0.0, p);
    for (kr, cr) in r.terms() {
        let cr = cr * super::blade::reverse_sign(kr.count_ones() as usize);
        for (kv, cv) in v.terms().filter(|(k, _)| k & null != 0) {
            let e = kr ^ (kv & !null);
            if e.count_ones() == 1 {
                let i = e.trailing_zeros() as usize;
                u[i] += super::blade::reorder_sign(kr, kv & !null) * cr * cv;
            }
        }
    }
    let t = phi_projective(&a, &u, true)?;
    out.as_mut_slice().fill(0.0);
    for (i, j) in super::pairs(p) {
        out.as_mut_slice()[((1u64 << i) | (1u64 << j)) as usize] = a.get(i, j);
    }
    for (i, c) in t.iter().enumerate() {
        out.as_mut_slice()[((1u64 << i) | null) as usize] = *c;
    }
    Ok(())
}

/// Err(NotABivector) naming the grades other than 2.
fn check_bivector(m: &Multivector, operation: &'static str) -> Result<(), AlgebraError> {
    if m.terms().all(|(k, _)| k.count_ones() == 2) {
        return Ok(());
    }
    let grades: Vec<usize> = m.grades().into_iter().filter(|&k| k != 2).collect();
    if grades.is_empty() {
        Ok(())
    } else {
        Err(AlgebraError::NotABivector { operation, grades })
    }
}

/// a / b by Smith's algorithm: no intermediate |b|² (num-complex's `/` forms it, which
/// overflows for |b| ≳ 1e154 and underflows to a division by zero for |b| ≲ 1e-154).
fn cdiv(a: C64, b: C64) -> C64 {
    if b.re.abs() >= b.im.abs() {
        let r = b.im / b.re;
        let d = b.re + b.im * r;
        C64::new((a.re + a.im * r) / d, (a.im - a.re * r) / d)
    } else {
        let r = b.re / b.im;
        let d = b.re * r + b.im;
        C64::new((a.re * r + a.im) / d, (a.im * r - a.re) / d)
    }
}

/// sinh(s z′)/z′ = s · sinhc(s z′), with the limit s at z′ = 0.
fn shs(z: C64, s: f64) -> C64 {
    if z == C64::new(0.0, 0.0) {
        C64::new(s, 0.0)
    } else {
        cdiv((z * s).sinh(), z)
    }
}

/// m scaled by 2^e coefficient by coefficient (exact barring overflow and underflow).
fn scaled<const L: usize>(m: &Small<L>, e: i32) -> Small<L> {
    let mut out = *m;
    for c in out.as_mut_slice() {
        *c = crate::numeric::ldexp(*c, e);
    }
    out
}

/// The closed form for the fixed-size routes' tests.
#[cfg(test)]
pub(super) fn exp_closed_form_for_tests(b: &Multivector) -> Multivector {
    renormalize(exp_closed_form(&Small::<32>::from_multivector(b)))
        .0
        .to_multivector()
}

/// The closed-form logarithm for the fixed-size routes' tests.
#[cfg(test)]
pub(super) fn log_closed_form_for_tests(v: &Multivector) -> Multivector {
    let v = Small::<32>::from_multivector(v);
    refine(&v, log_closed_form(&v).expect("a logarithm"))
        .0
        .to_multivector()
}

/// 1/(2k + 1)! for k = 1 … 16.
const INV_ODD_FACTORIALS: [f64; 16] = {
    let mut out = [0.0; 16];
    let mut fact = 6.0;
    let mut k = 0;
    while k < 16 {
        out[k] = 1.0 / fact;
        let m = (2 * k + 4) as f64;
        fact *= m * (m + 1.0);
        k += 1;
    }
    out
};

/// The closed form of the module documentation, for a non-zero bivector of N ≤ 5.
fn exp_closed_form<const L: usize>(b: &Small<L>) -> Small<L> {
    let sig = b.signature();
    // The scale: in Cl(p, q, 1) only the blades without the null vector enter B², B∧B's
    // square and B (B∧B) quadratically (a product of two blades that both hold the null
    // vector vanishes), so a huge translation must not set the scale of a small rotation.
    let m = if sig.r() == 1 {
        let null = 1u64 << (sig.dim() - 1);
        b.terms()
            .filter(|(k, _)| k & null == 0)
            .fold(0.0f64, |m, (_, c)| m.max(c.abs()))
    } else {
        b.max_abs()
    };
    if m == 0.0 {
        // Every term holds the null vector (or B = 0): B² = 0.
        return &Small::<L>::scalar(sig, 1.0) + b;
    }
    // B = s B′ with s = 2^e and max |B′| in [1, 2) over the blades above, but no smaller
    // than keeps the null parts of B′ finite (beside subnormal non-null parts, B′² then
    // underflows harmlessly: exp(B) = 1 + B to round-off).
    let mut e = crate::numeric::exponent_of(m);
    if sig.r() == 1 {
        let top = b.max_abs();
        if top > m {
            e = e.max(crate::numeric::exponent_of(top) - 1000);
        }
    }
    let s = crate::numeric::ldexp(1.0, e);
    let bp = scaled(b, -e);
    let (sigma, w) = bp.bivector_square();
    let w2 = w.geometric_grades(&w, 1).scalar_part();
    let delta2 = 0.25 * w2;
    // Roots λ′ of λ² − σλ + δ² (scaled by s²), the larger first, without squaring σ/2 or
    // δ (which could underflow).
    let h = 0.5 * sigma;
    let d = delta2.abs().sqrt();
    let lambda1 = if delta2 < 0.0 {
        let r = h.hypot(d);
        C64::new(h + r.copysign(h), 0.0)
    } else if h.abs() >= d {
        let r = (h.abs() - d).sqrt() * (h.abs() + d).sqrt();
        C64::new(h + r.copysign(h), 0.0)
    } else {
        C64::new(h, (d - h.abs()).sqrt() * (d + h.abs()).sqrt())
    };
    let delta = C64::new(delta2, 0.0).sqrt();
    let x = lambda1.sqrt();
    // x y = δ fixes the pairing (the formula is even in y).
    let y = if x == C64::new(0.0, 0.0) {
        C64::new(0.0, 0.0)
    } else {
        cdiv(delta, x)
    };
    let (xu, yu) = (x * s, y * s);
    let cterm = (xu.cosh() * yu.cosh()).re;
    let wterm = 0.5 * (shs(x, s) * shs(y, s)).re;
    let fterm = 0.5 * (shs(x + y, s) + shs(x - y, s)).re;
    // H s³ with H = h[a, b], in the form without cancellation.
    let hterm = if xu.norm() <= 1.0 {
        // Series: h[a, b] = Σ_{k≥1} h_{k−1}(a, b)/(2k+1)!, hₘ the complete homogeneous
        // polynomials: h₀ = 1, h₁ = a + b, hₘ = (a + b) hₘ₋₁ − ab hₘ₋₂.
        let su = sigma * s * s;
        let e1 = 2.0 * su;
        let e2 = su * su - 4.0 * delta2 * s * s * s * s;
        // |a|, |b| ≤ 4 here, so |hₘ| ≤ (m + 1) 4^m and the terms beyond k = 16 are below
        // 10⁻²⁴ of the first (1/6).
        let (mut hm2, mut hm1) = (0.0, 1.0);
        let mut sum = 0.0;
        for inv_fact in INV_ODD_FACTORIALS {
            sum += hm1 * inv_fact;
            let next = e1 * hm1 - e2 * hm2;
            hm2 = hm1;
            hm1 = next;
        }
        // multiplied by s³ below, stepwise
        C64::new(sum, 0.0)
    } else if yu.norm() <= 0.5 * xu.norm() {
        cdiv(
            xu.cosh() * shs(y, s) - shs(x, s) * yu.cosh(),
            (x * x - y * y) * 2.0,
        )
    } else {
        cdiv(shs(x + y, s) - shs(x - y, s), x * y * 4.0)
    };
    let series = xu.norm() <= 1.0;
    let mut out = Small::<L>::scalar(sig, cterm);
    out = &out + &(&w * wterm);
    out = &out + &(&bp * fterm);
    let bw = bp.geometric(&w).grade(2);
    if bw.max_abs() != 0.0 {
        // H s³ B′W′, scaled stepwise so that no intermediate overflows when the result
        // does not.
        let mut t = &bw * hterm.re;
        if series {
            for _ in 0..3 {
                t = &t * s;
            }
        }
        out = &out + &t;
    }
    out
}

/// V (V Ṽ)^(−½) for an even V of N ≤ 5 near a versor with max |Vᵢ| ≤ 4: V Ṽ = n + Q
/// (grades 0 and 4, Q² a scalar, so (n + Q)^(−½) lives in the algebra of 1 and Q) and
/// the result has V′ Ṽ′ = 1 to round-off. The closed form loses accuracy like ε |B| at a
/// huge rotation angle (cancellation between the B and B W terms), which is honest for V
/// but not for V Ṽ: a versor must stay a versor. For larger |Vᵢ| (boosts) V Ṽ − 1 carries
/// round-off ~ε |V|², as good as any product, and V is returned unchanged.
fn renormalize<const L: usize>(v: Small<L>) -> (Small<L>, f64) {
    // At a few ε the correction cannot do better than the product that applies it.
    project_onto_versors(v, 16.0 * f64::EPSILON)
}

/// [`renormalize`] down to any defect: for the logarithm, whose plane near π moves with the
/// last ε of V Ṽ.
fn renormalize_exactly<const L: usize>(v: Small<L>) -> Small<L> {
    project_onto_versors(v, 0.0).0
}

/// V (V Ṽ)^(−½) when max |V Ṽ − 1| lies in (floor, 10⁻²] and max |Vᵢ| ≤ 4, else V; and the
/// defect max |V Ṽ − 1| / max(1, max |Vᵢ|²) of the V given.
fn project_onto_versors<const L: usize>(v: Small<L>, floor: f64) -> (Small<L>, f64) {
    let top = v.max_abs();
    // V Ṽ has grades 0 and 4 only (for N ≤ 5 an even V with V Ṽ = 1 is a versor).
    let nn = v.geometric_grades(&v.reverse(), 1 | 1 << 4);
    let n0 = nn.scalar_part();
    let q = nn.grade(4);
    let dev = (n0 - 1.0).abs().max(q.max_abs());
    let defect = dev / (top * top).max(1.0);
    if top > 4.0 || dev <= floor || dev > 1e-2 {
        return (v, defect);
    }
    let kappa = q.geometric_grades(&q, 1).scalar_part();
    // (n + Q)^(−½) = α + β Q.
    let (alpha, beta) = if kappa > 0.0 {
        let p = kappa.sqrt();
        let (fp, fm) = ((n0 + p).sqrt().recip(), (n0 - p).sqrt().recip());
        (0.5 * (fp + fm), 0.5 * (fp - fm) / p)
    } else if kappa < 0.0 {
        let p = (-kappa).sqrt();
        let f = C64::new(n0, p).sqrt().inv();
        (f.re, f.im / p)
    } else {
        let r = n0.sqrt().recip();
        (r, -0.5 * r / n0)
    };
    if !(alpha.is_finite() && beta.is_finite()) {
        return (v, defect);
    }
    let f = &Small::<L>::scalar(v.signature(), alpha) + &(&q * beta);
    (f.geometric(&v), defect)
}

/// g(ζ) = ζ / sinh ζ and g′ = dg/d(cosh ζ) = (sinh ζ − ζ cosh ζ)/sinh³ζ for cosh ζ = c and
/// sinh²ζ = s2, on the principal branch (Re ζ ≥ 0 after the sign choice, Im ζ ∈ (−π, π]).
fn log_factor(c: C64, s2: C64) -> (C64, C64) {
    let one = C64::new(1.0, 0.0);
    let mut s = s2.sqrt();
    if (c.conj() * s).re < 0.0 {
        s = -s;
    }
    // C − 1 = sinh²ζ/(C + 1) where C + 1 is not small.
    let cm1 = if c.re >= 0.0 {
        cdiv(s2, c + one)
    } else {
        c - one
    };
    let w = cm1 + s; // exp(ζ) − 1
    let zeta = C64::new(
        0.5 * (2.0 * w.re + w.norm_sqr()).ln_1p(),
        w.im.atan2(1.0 + w.re),
    );
    let z = zeta * zeta;
    if zeta.norm() < 1e-4 {
        let g = one - z / 6.0 + z * z * (7.0 / 360.0);
        let gp = C64::new(-1.0 / 3.0, 0.0) + z * (2.0 / 15.0) - z * z * (2.0 / 63.0);
        return (g, gp);
    }
    let g = cdiv(zeta, s);
    let num = if zeta.norm() < 1.0 {
        // sinh ζ − ζ cosh ζ = −Σ_{k≥1} 2k ζ^(2k+1)/(2k+1)!
        let mut term = zeta;
        let mut fact = 1.0;
        let mut sum = C64::new(0.0, 0.0);
        for k in 1..=14 {
            term *= z;
            fact *= ((2 * k) * (2 * k + 1)) as f64;
            sum -= term * (2.0 * k as f64 / fact);
        }
        sum
    } else {
        s - zeta * c
    };
    (g, cdiv(cdiv(cdiv(num, s), s), s))
}

/// One correction step B ← B + ⟨exp(B)~ V⟩₂, kept only if it lowers the residual
/// max |exp(B) − V|. The closed form's error lies mostly in the commutative algebra of B (the
/// directions v and Q v), where exp(B + δ) = exp(B) exp(δ) and the step removes it.
/// Returns the bivector and its residual max |exp(B) − V| (∞ if exp(B) overflows).
fn refine<const L: usize>(v: &Small<L>, b: Small<L>) -> (Small<L>, f64) {
    let Ok(e0) = exp_nonzero(&b) else {
        return (b, f64::INFINITY);
    };
    let r0 = (&e0 - v).max_abs();
    if r0 == 0.0 {
        return (b, r0);
    }
    let delta = e0.reverse().geometric(v).grade(2);
    let b1 = &b + &delta;
    match exp_nonzero(&b1) {
        Ok(e1) if (&e1 - v).max_abs() < r0 => (b1, (&e1 - v).max_abs()),
        _ => (b, r0),
    }
}

/// Bound on max |exp(log V) − V| / (max(1, |V|) · max(1, |log V|)) for a logarithm to be
/// returned: far above the round-off of an accurate logarithm (a few ε times the
/// conditioning of exp), far below a wrong one.
const LOG_RESIDUAL_TOLERANCE: f64 = 1e-10;

/// Ok if a logarithm of size `b_size` reproduces V of size `v_size` to `residual`.
fn check_log_residual(residual: f64, v_size: f64, b_size: f64) -> Result<(), AlgebraError> {
    let scale = v_size.max(1.0);
    // Relative, so that a huge V or B cannot make the bound infinite.
    if within(residual / scale / b_size.max(1.0), LOG_RESIDUAL_TOLERANCE) {
        Ok(())
    } else {
        Err(AlgebraError::LogarithmInaccurate {
            residual: residual / scale,
        })
    }
}

/// exp for the refinement: the closed form, or an error on overflow. Up to N = 4 the
/// fixed-size route of `versor_n4.rs`, which stays exact where the general closed form's
/// scaling loses digits (a subnormal rotation beside a translation in Cl(p, q, 1)).
fn exp_nonzero<const L: usize>(b: &Small<L>) -> Result<Small<L>, ()> {
    if n4::applies(b.signature()) {
        let mut m = Multivector::zero(b.signature());
        b.write_to(&mut m);
        let mut e = Multivector::zero(b.signature());
        if n4::exp_to(&m, &mut e) {
            return Ok(Small::from_multivector(&e));
        }
    }
    let e = exp_closed_form(b);
    if e.as_slice().iter().all(|c| c.is_finite()) {
        Ok(e)
    } else {
        Err(())
    }
}

/// Returns Err unless g is real (to round-off).
fn real_factor(g: C64) -> Result<f64, AlgebraError> {
    if g.re.is_finite() && g.im.abs() <= 1e-10 * g.re.abs().max(1.0) {
        Ok(g.re)
    } else if !g.re.is_finite() || !g.im.is_finite() {
        Err(AlgebraError::NoLogarithm {
            reason: "a rotation by π in a plane the versor does not determine",
        })
    } else {
        Err(AlgebraError::NoLogarithm {
            reason: "it is −exp(B) for a boost or null B",
        })
    }
}

/// The logarithm of an even versor of N ≤ 5 in a non-Euclidean signature.
fn log_closed_form<const L: usize>(v: &Small<L>) -> Result<Small<L>, AlgebraError> {
    let c = v.scalar_part();
    let bv = v.grade(2);
    let q = v.grade(4);
    let qq: f64 = q.as_slice().iter().map(|x| x * x).sum();
    let kappa = q.geometric(&q).scalar_part();
    // Q² = 0 up to the round-off of forming Q² (a few ε qq): the dual case; J = Q/√|κ|
    // would be noise otherwise (a null W beside a large boost).
    if qq == 0.0 || kappa.abs() <= 64.0 * f64::EPSILON * qq {
        // Dual numbers (Q² = 0): B = g(c) v + g′(c) Q v.
        let s2 = bv.geometric(&bv).scalar_part();
        let (g, gp) = log_factor(C64::new(c, 0.0), C64::new(s2, 0.0));
        let g = real_factor(g)?;
        let mut out = &bv * g;
        if qq != 0.0 {
            let gp = real_factor(gp)?;
            out = &out + &(&q.geometric(&bv).grade(2) * gp);
        }
        return Ok(out);
    }
    let p = kappa.abs().sqrt();
    let j = &q * (1.0 / p);
    let vj = bv.geometric(&j).grade(2);
    if kappa > 0.0 {
        // Split-complex: the idempotents (1 ± J)/2 give two real factors.
        let vp = &(&bv + &vj) * 0.5;
        let vm = &(&bv - &vj) * 0.5;
        let sp = 2.0 * vp.geometric(&vp).scalar_part();
        let sm = 2.0 * vm.geometric(&vm).scalar_part();
        let gp = real_factor(log_factor(C64::new(c + p, 0.0), C64::new(sp, 0.0)).0)?;
        let gm = real_factor(log_factor(C64::new(c - p, 0.0), C64::new(sm, 0.0)).0)?;
        Ok(&(&vp * gp) + &(&vm * gm))
    } else {
        // Complex: J² = −1 plays i.
        let v2 = bv.geometric(&bv);
        let beta = -v2.grade(4).geometric(&j).scalar_part();
        let (g, _) = log_factor(C64::new(c, p), C64::new(v2.scalar_part(), beta));
        if !(g.re.is_finite() && g.im.is_finite()) {
            return Err(AlgebraError::NoLogarithm {
                reason: "a rotation by π in a plane the versor does not determine",
            });
        }
        Ok(&(&bv * g.re) + &(&vj * g.im))
    }
}

/// max |V Ṽ − 1| / max |Vᵢ|² of an even V of N ≤ 6 on stack storage, on V / max |Vᵢ| so
/// that nothing overflows (the grades 0 and 4 of V Ṽ, the only ones it has). Infinite when V
/// is zero or not finite.
fn unit_error<const L: usize>(v: &Small<L>) -> f64 {
    let top = v.max_abs();
    if !(top.is_finite() && top > 0.0) {
        return f64::INFINITY;
    }
    let w = v * (1.0 / top);
    let mut ww = w.geometric_grades(&w.reverse(), 1 | 1 << 4);
    ww.as_mut_slice()[0] -= (1.0 / top) / top;
    ww.max_abs()
}

/// [`unit_error`] of an even V of N ≥ 6 (for N = 7, 8 on the heap, with the grade 8 of
/// V Ṽ). Out of line, so that its 64-coefficient product does not enlarge the stack frame of
/// the smaller signatures' route.
#[inline(never)]
fn versor_defect(v: &Multivector) -> f64 {
    if v.dim() <= SMALL_MAX_DIM {
        return unit_error(&Small::<64>::from_multivector(v));
    }
    let top = v.max_abs();
    if !(top.is_finite() && top > 0.0) {
        return f64::INFINITY;
    }
    let w = v * (1.0 / top);
    let mut ww = &w * &w.reverse();
    ww.as_mut_slice()[0] -= (1.0 / top) / top;
    ww.max_abs()
}
