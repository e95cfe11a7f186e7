//! Explicit Lie–Poisson splitting: each plane's flow is an exact rotation.

use super::{DynamicsError, Integrator, check_state, momentum_rate};
use crate::algebra::{Bivector, pair_index, pairs};
use crate::dynamics::attitude::PlaneProduct;
use crate::dynamics::{RigidBody, Torque};
use crate::numeric::{sin_cos_minus_one, small_angle_factors};

/// The composition used by [`Splitting`]: Strang's step, or a symmetric composition of
/// Strang steps of sizes γ₁h, …, γₛh (Hairer, Lubich & Wanner, *Geometric Numerical
/// Integration*, V.3). Every one keeps the Casimirs and the space-frame momentum to
/// round-off; the higher orders pay s Strang steps per step for a much smaller error at
/// small h.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SplittingOrder {
    /// Symmetric Strang composition over the planes: order 2.
    Strang,
    /// Yoshida's triple jump of Strang steps (Yoshida, Phys. Lett. A 150 (1990) 262): order 4,
    /// three Strang steps.
    Yoshida4,
    /// Suzuki's five-step composition (Suzuki, Phys. Lett. A 146 (1990) 319): order 4, five
    /// Strang steps with γ = 1/(4 − 4^⅓) (four times) and 1 − 4γ; its error constant is far
    /// below the triple jump's, so it is the cheaper order-4 method at equal accuracy.
    Suzuki4,
    /// Kahan & Li's nine-step composition (Math. Comp. 66 (1997) 1089, method s9odr6a):
    /// order 6.
    KahanLi6,
    /// Kahan & Li's seventeen-step composition (ibid., s17odr8a): order 8.
    KahanLi8,
}

/// Kahan & Li's order-6 weights γ₁ … γ₅ (γ₁₀₋ₖ = γₖ), to 26 digits as published (kept so,
/// to be checked against the source).
#[allow(clippy::excessive_precision)]
const KAHAN_LI_6: [f64; 5] = [
    0.392_161_444_007_314_139_279_250_56,
    0.332_599_136_789_359_438_599_748_64,
    -0.706_246_172_557_639_359_809_964_82,
    0.082_213_596_293_550_800_231_490_45,
    0.798_543_990_934_829_963_398_950_35,
];

/// Kahan & Li's order-8 weights γ₁ … γ₉ (γ₁₈₋ₖ = γₖ), as published.
#[allow(clippy::excessive_precision)]
const KAHAN_LI_8: [f64; 9] = [
    0.130_202_483_088_890_080_878_817_63,
    0.561_162_981_775_108_384_561_964_41,
    -0.389_474_962_644_847_286_408_078_60,
    0.158_841_906_555_155_600_896_210_75,
    -0.395_903_894_133_237_577_336_231_54,
    0.184_539_640_978_315_707_091_832_54,
    0.258_374_387_686_322_047_293_979_11,
    0.295_011_723_609_310_298_870_966_24,
    -0.605_508_533_830_034_511_698_921_08,
];

impl SplittingOrder {
    /// The order of the composed method.
    pub fn order(self) -> u32 {
        match self {
            SplittingOrder::Strang => 2,
            SplittingOrder::Yoshida4 | SplittingOrder::Suzuki4 => 4,
            SplittingOrder::KahanLi6 => 6,
            SplittingOrder::KahanLi8 => 8,
        }
    }

    /// The weights γ₁, …, γₛ of the Strang steps (symmetric, summing to 1).
    pub fn weights(self) -> Vec<f64> {
        let mut w = [0.0; 17];
        let s = self.weights_into(&mut w);
        w[..s].to_vec()
    }

    /// Writes the weights into `w` and returns their number (no heap: the step's hot path).
    pub(crate) fn weights_into(self, w: &mut [f64; 17]) -> usize {
        // A symmetric sequence from its first half and middle.
        fn mirror(half: &[f64], w: &mut [f64; 17]) -> usize {
            let s = 2 * half.len() - 1;
            for (k, &g) in half.iter().enumerate() {
                w[k] = g;
                w[s - 1 - k] = g;
            }
            s
        }
        match self {
            SplittingOrder::Strang => mirror(&[1.0], w),
            SplittingOrder::Yoshida4 => {
                let g = 1.0 / (2.0 - 2f64.cbrt());
                mirror(&[g, 1.0 - 2.0 * g], w)
            }
            SplittingOrder::Suzuki4 => {
                let g = 1.0 / (4.0 - 4f64.cbrt());
                mirror(&[g, g, 1.0 - 4.0 * g], w)
            }
            SplittingOrder::KahanLi6 => mirror(&KAHAN_LI_6, w),
            SplittingOrder::KahanLi8 => mirror(&KAHAN_LI_8, w),
        }
    }
}

/// The explicit Lie–Poisson splitting of the free body (McLachlan, *Explicit Lie-Poisson
/// integration and the Euler equations*, 1993), in any N.
///
/// The kinetic energy is a sum over the principal planes, T = Σ_p L_p²/(2 I_p). Under one term
/// the plane's momentum L_p is constant and the body turns in that plane by θ = h L_p/I_p:
/// R ← R exp(−θ/2 e_p) and L ← r̃ L r with r = exp(−θ/2 e_p). Both updates are exact
/// rotations, so every Casimir of L and the space-frame momentum are conserved to round-off,
/// and the rotor never leaves Spin(N). Planes are visited in lexicographic order, symmetric
/// about the last one (Strang); the higher orders compose Strang steps symmetrically
/// ([`SplittingOrder`]): Yoshida's three and Suzuki's five for order 4, Kahan & Li's nine and
/// seventeen for orders 6 and 8.
///
/// ```
/// use rotorflow::dynamics::{Invariants, torques::Free};
/// use rotorflow::prelude::*;
/// let inertia = InertiaMap::from_principal_second_moments(&[1.0, 2.0, 3.0, 4.0])?;
/// let l = Bivector::from_components(4, &[0.3, -0.2, 0.5, 0.1, 0.4, -0.6])?;
/// let mut body = RigidBody::from_body_momentum(inertia, Attitude::identity(4), &l)?;
/// let casimirs = Invariants::of(&body);
/// let mut integrator = Splitting::kahan_li6();
/// for k in 0..100 {
///     integrator.step(&mut body, k as f64 * 0.05, 0.05, &Free)?;
/// }
/// assert!(Invariants::of(&body).drift_from(&casimirs).casimirs < 1e-13);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// With a torque, each step is kick(h/2) · drift(h) · kick(h/2), the kick being the torque's
/// flow with the attitude frozen (midpoint rule).
///
/// Needs an inertia diagonal on the basis planes (every physical body, in its principal
/// frame, and diagonal general maps).
#[derive(Clone, Copy, Debug)]
pub struct Splitting {
    order: SplittingOrder,
    /// Whether the kinetic energy's symmetric part is split off ([`Splitting::with_symmetric_part`]).
    symmetric_part: bool,
}

impl Splitting {
    /// Returns the splitting integrator of the given composition order.
    pub fn new(order: SplittingOrder) -> Self {
        Splitting {
            order,
            symmetric_part: false,
        }
    }

    /// The same composition over a splitting with the symmetric part of the kinetic energy
    /// split off: T = |L|²/(2I_K) + Σₚ (1/I_p − 1/I_K) L_p²/2, with K the last plane.
    ///
    /// The first piece is a Casimir: L stays, and the attitude turns about L by the exact
    /// R ← R exp(−h L/(2I_K)), which commutes with every other piece. Without a torque it is
    /// applied once per step; in 3D and 4D it then seeds the planes' rotor increment (its
    /// parts near 1 formed as cos θ − 1), so the attitude keeps its unit norm to round-off
    /// as the plain splitting's does, and elsewhere as RKMK4's does (about an ulp per step).
    /// The fixed-size step
    /// [`FreeBody3::step_strang_symmetric`](crate::dynamics::FreeBody3::step_strang_symmetric)
    /// and its 4D twin are the same step. What remains are the
    /// planes' flows with the differences of the inverse moments as rates, so the splitting
    /// error scales with how far the body is from symmetric (it vanishes for a body with
    /// equal moments) rather than with the moments themselves, one plane fewer. Same order,
    /// same invariants (Casimirs and space-frame momentum to round-off).
    pub fn with_symmetric_part(self) -> Self {
        Splitting {
            symmetric_part: true,
            ..self
        }
    }

    /// Whether the symmetric part is split off ([`Splitting::with_symmetric_part`]).
    pub fn splits_symmetric_part(&self) -> bool {
        self.symmetric_part
    }

    /// Returns the second-order Strang splitting.
    pub fn strang() -> Self {
        Self::new(SplittingOrder::Strang)
    }

    /// Returns the fourth-order Yoshida composition.
    pub fn yoshida4() -> Self {
        Self::new(SplittingOrder::Yoshida4)
    }

    /// Returns Suzuki's fourth-order five-step composition.
    pub fn suzuki4() -> Self {
        Self::new(SplittingOrder::Suzuki4)
    }

    /// Returns Kahan & Li's sixth-order nine-step composition.
    pub fn kahan_li6() -> Self {
        Self::new(SplittingOrder::KahanLi6)
    }

    /// Returns Kahan & Li's eighth-order seventeen-step composition.
    pub fn kahan_li8() -> Self {
        Self::new(SplittingOrder::KahanLi8)
    }

    /// The composition.
    pub fn composition(&self) -> SplittingOrder {
        self.order
    }
}

/// One plane's exact flow: L turns by −θ and the drift's rotation by θ, θ = L_p · rate
/// (rate = τ / I_p, precomputed: the planes form a chain of dependent updates, so a division
/// here would sit on the critical path).
#[inline]
fn plane_flow(
    momentum: &mut Bivector,
    turn: &mut PlaneProduct,
    plane: usize,
    (i, j): (usize, usize),
    rate: f64,
) {
    let theta = momentum.as_slice()[plane] * rate;
    // (sin, cos − 1) without cancellation (see `numeric::trig`), so both rotations are
    // orthogonal to O(εθ²); θ for L, θ/2 for the rotor. The two evaluations are independent,
    // and only the first sits on the chain of dependent plane updates (no libm call on it).
    let full = sin_cos_minus_one(theta);
    turn.rotate_in_plane(i, j, theta, full);
    momentum.rotate_in_plane_sin_cm1(i, j, -full.0, full.1);
}

/// The free flow for time `h` by Strang's symmetric composition over the planes. The
/// attitude is turned once, by the product of the planes' rotations (see [`PlaneProduct`]
/// for why: it keeps |R R̃ − 1| at round-off over 10⁷ steps without renormalising).
pub(super) fn strang_drift(body: &mut RigidBody, moments: &[f64], h: f64) {
    let n = body.dim();
    let k = moments.len();
    if k == 0 {
        return;
    }
    match n {
        3 => rotor_drift_3().drift(body, moments, h, None),
        4 => rotor_drift_4().drift(body, moments, h, None),
        _ => strang_drift_planes(body, moments, h),
    }
}

/// exp(`a`) − 1 in the rotor's storage order for N = 3 and 4 (its first 4 or 8 entries,
/// through the fixed-size types, the parts near 1 formed as cos θ − 1): the seed of a
/// drift's rotor increment. None for other N.
fn exp_seed_3d_4d(a: &[f64]) -> Option<([f64; 8], usize)> {
    use crate::algebra::{Bivector3, Bivector4};
    let mut seed = [0.0; 8];
    match *a {
        [b12, b13, b23] => {
            seed[..4].copy_from_slice(&Bivector3::new(b12, b13, b23).exp_minus_one_even_layout());
            Some((seed, 4))
        }
        [b12, b13, b14, b23, b24, b34] => {
            seed = Bivector4::new(b12, b13, b14, b23, b24, b34).exp_minus_one_even_layout();
            Some((seed, 8))
        }
        _ => None,
    }
}

/// The attitude turned by exp(`a`) and then [`strang_drift`]: in 3D and 4D the exponential
/// seeds the planes' rotor increment ([`exp_seed_3d_4d`]), one rotor product for both.
fn strang_drift_after_exp(body: &mut RigidBody, a: &Bivector, moments: &[f64], h: f64) {
    match (exp_seed_3d_4d(a.as_slice()), body.dim()) {
        (Some((seed, len)), 3) => rotor_drift_3().drift(body, moments, h, Some(&seed[..len])),
        (Some((seed, len)), _) => rotor_drift_4().drift(body, moments, h, Some(&seed[..len])),
        (None, _) => {
            let (attitude, _) = body.state_mut();
            attitude.times_exp_mut(a);
            strang_drift(body, moments, h);
        }
    }
}

/// [`strang_drift`] for any N, plane by plane through [`plane_flow`].
fn strang_drift_planes(body: &mut RigidBody, moments: &[f64], h: f64) {
    let n = body.dim();
    let k = moments.len();
    // The rates τ/I_p do not depend on L, so their divisions stay off the critical path.
    let half = 0.5 * h;
    let (attitude, momentum) = body.state_mut();
    let mut turn = PlaneProduct::identity_for(attitude);
    for (p, plane) in pairs(n).enumerate().take(k - 1) {
        plane_flow(momentum, &mut turn, p, plane, half / moments[p]);
    }
    let mut plane = (n - 2, n - 1);
    plane_flow(momentum, &mut turn, k - 1, plane, h / moments[k - 1]);
    // The same planes backwards (the lexicographic predecessor, no list kept).
    for p in (0..k - 1).rev() {
        plane = if plane.1 > plane.0 + 1 {
            (plane.0, plane.1 - 1)
        } else {
            (plane.0 - 1, n - 1)
        };
        plane_flow(momentum, &mut turn, p, plane, half / moments[p]);
    }
    turn.apply_to(attitude);
}

/// The Strang drift of a rotor attitude in 3D and 4D with its index tables in arrays of fixed
/// length, so that the compiler unrolls the planes: the same updates as [`plane_flow`] and
/// [`PlaneProduct`], without their loops over index ranges (the loops, not the arithmetic,
/// dominate a 4D step), and with each plane's angle computed ahead of its L
/// ([`RotorDrift::plane`]): a step is a chain of dependent planes, and its length is what
/// a 3D or 4D step costs.
struct RotorDrift<const K: usize, const LP: usize, const RP: usize> {
    /// For each plane: the pairs (a, b, σ) of L components it mixes,
    /// x ← x + (m x − σ s y), y ← y + (σ s x + m y).
    momentum: [[(usize, usize, f64); LP]; K],
    /// For each plane: the pairs (a, b, s₁, s₂) of rotor coefficients it mixes (the rotor
    /// module's plane table), and the position of its own blade eᵢⱼ.
    rotor: [[(usize, usize, f64, f64); RP]; K],
    blade: [usize; K],
}

/// The 3D tables, built at compile time so that every index and sign is a constant in the
/// unrolled kernel.
const DRIFT_3: RotorDrift<3, 1, 2> = RotorDrift::build(3);

/// The 4D tables.
const DRIFT_4: RotorDrift<6, 2, 4> = RotorDrift::build(4);

fn rotor_drift_3() -> &'static RotorDrift<3, 1, 2> {
    &DRIFT_3
}

fn rotor_drift_4() -> &'static RotorDrift<6, 2, 4> {
    &DRIFT_4
}

impl<const K: usize, const LP: usize, const RP: usize> RotorDrift<K, LP, RP> {
    /// The tables for dimension `n` (K = n(n−1)/2 planes, LP = n − 2, RP = 2^(n−2)).
    const fn build(n: usize) -> Self {
        let mut t = RotorDrift {
            momentum: [[(0, 0, 0.0); LP]; K],
            rotor: [[(0, 0, 0.0, 0.0); RP]; K],
            blade: [0; K],
        };
        // B_a,k as stored: the component of the ordered pair and its sign.
        const fn stored(n: usize, a: usize, k: usize) -> (usize, f64) {
            if a < k {
                (pair_index(n, a, k), 1.0)
            } else {
                (pair_index(n, k, a), -1.0)
            }
        }
        let mut p = 0;
        let mut lo = 0;
        while lo < n {
            let mut hi = lo + 1;
            while hi < n {
                let (mut k, mut slot) = (0, 0);
                while k < n {
                    if k != lo && k != hi {
                        let ((a, sa), (b, sb)) = (stored(n, lo, k), stored(n, hi, k));
                        t.momentum[p][slot] = (a, b, sa * sb);
                        slot += 1;
                    }
                    k += 1;
                }
                t.rotor[p] = crate::algebra::plane_table_const::<RP>(n, lo, hi);
                // e_lo e_hi is stored at the index of its low N−1 bits.
                t.blade[p] = ((1usize << lo) | (1 << hi)) & ((1 << (n - 1)) - 1);
                p += 1;
                hi += 1;
            }
            lo += 1;
        }
        t
    }

    /// One plane: L turns by −θ, the rotor increment D by θ. Returns the angle of the plane
    /// after it, `next` = (q, rate_q), θ_q = L_q · rate_q. The planes form a chain of
    /// dependent updates, and only θ_q sits on it: for small angles it is turned on its own
    /// from the scaled rate_q L, with sin θ = θ P_s(θ²) and cos θ − 1 = θ² P_c(θ²) and the
    /// products by θ and θ² formed while the polynomials are evaluated. That is rate_q
    /// times the turned L_q up to rounding, ready a few operations sooner.
    #[inline(always)]
    fn plane(
        &self,
        l: &mut [f64],
        d: &mut [f64],
        p: usize,
        theta: f64,
        next: Option<(usize, f64)>,
    ) -> f64 {
        let mut theta_next = None;
        let (s, m) = match small_angle_factors(theta) {
            Some((t2, ps, pc)) => {
                if let Some((q, rate)) = next
                    && let Some(&(a, b, sigma)) =
                        self.momentum[p].iter().find(|&&(a, b, _)| a == q || b == q)
                {
                    // θ_q from rate_q L turned: x + (m x + σ s y) or y + (m y − σ s x).
                    let (x, y) = (rate * l[a], rate * l[b]);
                    theta_next = Some(if q == a {
                        x + ((t2 * x) * pc + sigma * ((theta * y) * ps))
                    } else {
                        y + ((t2 * y) * pc - sigma * ((theta * x) * ps))
                    });
                }
                (theta * ps, t2 * pc)
            }
            None => sin_cos_minus_one(theta),
        };
        for &(a, b, sigma) in &self.momentum[p] {
            // L turns by −θ: sin → −sin.
            let (x, y, ss) = (l[a], l[b], -sigma * s);
            l[a] = x + (m * x - ss * y);
            l[b] = y + (ss * x + m * y);
        }
        let (s_half, m_half) = sin_cos_minus_one(0.5 * theta);
        let c_half = 1.0 + m_half;
        for &(a, b, s1, s2) in &self.rotor[p] {
            let (x, y) = (d[a], d[b]);
            d[a] = c_half * x - s_half * s1 * y;
            d[b] = c_half * y - s_half * s2 * x;
        }
        d[0] += m_half;
        d[self.blade[p]] -= s_half;
        match (theta_next, next) {
            (Some(t), _) => t,
            (None, Some((q, rate))) => l[q] * rate,
            (None, None) => 0.0,
        }
    }

    /// The Strang drift for time `h` ([`strang_drift`]), the rotor increment starting from
    /// `start` (0 if none).
    fn drift(&self, body: &mut RigidBody, moments: &[f64], h: f64, start: Option<&[f64]>) {
        let inverse: [f64; K] = std::array::from_fn(|p| 1.0 / moments[p]);
        self.drift_inverse(body, &inverse, h, start);
    }

    /// [`Self::drift`] given the planes' inverse moments (or rates 1/I_p − 1/I_K).
    fn drift_inverse(&self, body: &mut RigidBody, inverse: &[f64], h: f64, start: Option<&[f64]>) {
        let (attitude, momentum) = body.state_mut();
        let rotor = attitude.rotor_mut().expect("a rotor attitude for N ≤ 4");
        let mut increment = [0.0; 8];
        let d = &mut increment[..rotor.as_slice().len()];
        if let Some(start) = start {
            d.copy_from_slice(start);
        }
        self.drift_slices(momentum.as_mut_slice(), d, inverse, h);
        rotor.times_one_plus(d);
    }

    /// The drift on the momentum `l` and the rotor increment `d` (the attitude's update is
    /// R ← R (1 + D); the planes' rotations multiply 1 + D on the right), given the planes'
    /// inverse moments (a division would delay the first plane).
    #[inline(always)]
    fn drift_slices(&self, l: &mut [f64], d: &mut [f64], inverse: &[f64], h: f64) {
        let half = 0.5 * h;
        let rates: [f64; K] = std::array::from_fn(|p| half * inverse[p]);
        // The planes as literals, each handed the next one's rate, so that every table index
        // is a constant of the unrolled kernel.
        macro_rules! chain {
            (@go $th:ident; ($p:literal, $r:expr), ($q:literal, $rq:expr) $(, $rest:tt)*) => {
                $th = self.plane(l, d, $p, $th, Some(($q, $rq)));
                chain!(@go $th; ($q, $rq) $(, $rest)*);
            };
            (@go $th:ident; ($p:literal, $r:expr)) => {
                self.plane(l, d, $p, $th, None);
            };
            (($p:literal, $r:expr) $(, $rest:tt)*) => {{
                let mut theta = l[$p] * $r;
                chain!(@go theta; ($p, $r) $(, $rest)*);
            }};
        }
        let r: &[f64] = &rates;
        if inverse[K - 1] == 0.0 {
            // The last plane's flow is the identity (the symmetric part split off, see
            // `Splitting::with_symmetric_part`): its two neighbours' halves are one flow,
            // and the chain is two planes shorter.
            match K {
                3 => chain!((0, r[0]), (1, 2.0 * r[1]), (0, r[0])),
                6 => chain! {
                    (0, r[0]), (1, r[1]), (2, r[2]), (3, r[3]),
                    (4, 2.0 * r[4]),
                    (3, r[3]), (2, r[2]), (1, r[1]), (0, r[0])
                },
                _ => unreachable!("the unrolled drift is built for N = 3 and 4"),
            }
            return;
        }
        match K {
            3 => chain!((0, r[0]), (1, r[1]), (2, 2.0 * r[2]), (1, r[1]), (0, r[0])),
            6 => chain! {
                (0, r[0]), (1, r[1]), (2, r[2]), (3, r[3]), (4, r[4]),
                (5, 2.0 * r[5]),
                (4, r[4]), (3, r[3]), (2, r[2]), (1, r[1]), (0, r[0])
            },
            _ => unreachable!("the unrolled drift is built for N = 3 and 4"),
        }
    }
}

/// The Strang drift of the fixed-size free body of 3D (K = 3 planes, D = 4 rotor
/// coefficients) or 4D (K = 6, D = 8) with inverse plane moments `inverse` (1/I_p): `l`
/// updated, the attitude increment D (rotor storage order) returned, the same updates as
/// [`Splitting::strang`]'s. D starts from `start` (the increment of an update applied before
/// the planes, 0 for none): 1 + D is then (1 + start) times the planes' rotations. A last
/// inverse moment of 0 is the symmetric part split off ([`Splitting::with_symmetric_part`]:
/// that plane's flow is the identity).
#[inline]
pub(crate) fn strang_drift_fixed<const K: usize, const D: usize>(
    l: &mut [f64; K],
    inverse: &[f64; K],
    h: f64,
    start: [f64; D],
) -> [f64; D] {
    const { assert!(K == 3 && D == 4 || K == 6 && D == 8) };
    let mut d = start;
    if K == 3 {
        rotor_drift_3().drift_slices(l, &mut d, inverse, h);
    } else {
        rotor_drift_4().drift_slices(l, &mut d, inverse, h);
    }
    d
}

/// The torque's flow for time `h` with the attitude frozen, by the midpoint rule.
pub(super) fn kick(body: &mut RigidBody, torque: &dyn Torque, t: f64, h: f64) {
    if torque.is_zero() {
        return;
    }
    // The torque alone (without ω × L): the rate minus the free part.
    let eval = |body: &RigidBody, l: &Bivector, time: f64| -> Bivector {
        let (dl, omega) = momentum_rate(body, time, body.principal_frame_attitude(), l, torque);
        dl - omega.commutator(l)
    };
    let l0 = body.momentum().clone();
    let tau1 = eval(body, &l0, t);
    let l_mid = &l0 + &(tau1 * (0.5 * h));
    let tau2 = eval(body, &l_mid, t + 0.5 * h);
    let (_, momentum) = body.state_mut();
    *momentum += &(tau2 * h);
}

/// One kick–drift–kick Strang step, the attitude turned first by exp(`turn`) if given.
fn kdk(
    body: &mut RigidBody,
    moments: &Moments,
    torque: &dyn Torque,
    (t, h): (f64, f64),
    turn: Option<Bivector>,
) {
    kick(body, torque, t, 0.5 * h);
    match (moments, turn) {
        (Moments::Planes(m), None) => strang_drift(body, m, h),
        (Moments::Planes(m), Some(a)) => strang_drift_after_exp(body, &a, m, h),
        (Moments::SymmetricPart { differences, last }, _) => {
            // Under a torque: the Casimir piece first (it commutes with the planes), then
            // the planes with the differences of their rates; the last plane's rate is 0.
            let a = body.momentum() * (-0.5 * h / last);
            strang_drift_after_exp(body, &a, differences, h);
        }
    }
    kick(body, torque, t + 0.5 * h, 0.5 * h);
}

/// The planes' moments as the drift takes them: the plain splitting's, or with the
/// symmetric part split off, the "moments" 1/(1/I_p − 1/I_K) of the remaining flows
/// (infinite for the last plane: its flow is then the identity) and I_K.
enum Moments {
    Planes(smallvec::SmallVec<[f64; 28]>),
    SymmetricPart {
        differences: smallvec::SmallVec<[f64; 28]>,
        last: f64,
    },
}

impl Moments {
    fn new(moments: &[f64], symmetric_part: bool) -> Self {
        match moments.last() {
            Some(&last) if symmetric_part => Moments::SymmetricPart {
                differences: moments
                    .iter()
                    .map(|&m| 1.0 / (1.0 / m - 1.0 / last))
                    .collect(),
                last,
            },
            _ => Moments::Planes(moments.iter().copied().collect()),
        }
    }
}

impl_integrator!(
    Splitting,
    order = |this| this.order.order(),
    name = |this| match (this.order, this.symmetric_part) {
        (SplittingOrder::Strang, false) => "strang",
        (SplittingOrder::Yoshida4, false) => "yoshida4",
        (SplittingOrder::Suzuki4, false) => "suzuki4",
        (SplittingOrder::KahanLi6, false) => "kahan-li6",
        (SplittingOrder::KahanLi8, false) => "kahan-li8",
        (SplittingOrder::Strang, true) => "strang-symmetric",
        (SplittingOrder::Yoshida4, true) => "yoshida4-symmetric",
        (SplittingOrder::Suzuki4, true) => "suzuki4-symmetric",
        (SplittingOrder::KahanLi6, true) => "kahan-li6-symmetric",
        (SplittingOrder::KahanLi8, true) => "kahan-li8-symmetric",
    },
    step = |this, body, t, h, torque| {
        body.refuse_gyrostat(this.name())?;
        let Some(moments) = body.inertia().diagonal_plane_moments() else {
            return Err(DynamicsError::UnsupportedInertia {
                integrator: this.name(),
            });
        };
        if this.symmetric_part && torque.is_zero() && matches!(body.dim(), 3 | 4) {
            // The rates 1/I_p − 1/I_K from the inverse moments, the last exactly 0.
            let k = moments.len();
            let last = 1.0 / moments[k - 1];
            let mut rates = [0.0; 6];
            for (x, m) in rates.iter_mut().zip(moments) {
                *x = 1.0 / m - last;
            }
            this.free_symmetric_part_3d_4d(body, &rates[..k], last, h);
            return check_state(body, t);
        }
        // The moments live in the map; copy them (k ≤ 28 stays on the stack).
        let mut moments = Moments::new(moments, this.symmetric_part);
        // Without a torque the Casimir piece commutes with every substep, so the step turns
        // the attitude about L once, by the whole step (one exponential per step, as RKMK4's),
        // before the first substep's planes.
        let mut turn = None;
        if let (Moments::SymmetricPart { differences, last }, true) = (&moments, torque.is_zero()) {
            turn = Some(body.momentum() * (-0.5 * h / last));
            moments = Moments::Planes(differences.clone());
        }
        let mut weights = [0.0; 17];
        let stages = this.order.weights_into(&mut weights);
        let mut time = t;
        for &g in &weights[..stages] {
            kdk(body, &moments, torque, (time, g * h), turn.take());
            time += g * h;
        }
        check_state(body, t)
    }
);

impl Splitting {
    /// A torque-free step with the symmetric part split off in 3D and 4D, the arithmetic of
    /// `FreeBody3::step_strang_symmetric` and `FreeBody4::step_strang_symmetric` for every
    /// composition: the planes' `rates` 1/I_p − 1/I_K (the last 0; `last` = 1/I_K), and the
    /// Casimir turn exp(−h L/(2I_K)) seeding the first substep's rotor increment.
    fn free_symmetric_part_3d_4d(&self, body: &mut RigidBody, rates: &[f64], last: f64, h: f64) {
        let k = rates.len();
        let turn = body.momentum() * (-0.5 * h * last);
        let (start, len) = exp_seed_3d_4d(turn.as_slice()).expect("N = 3 or 4");
        let mut weights = [0.0; 17];
        let stages = self.order.weights_into(&mut weights);
        for (i, &g) in weights[..stages].iter().enumerate() {
            let seed = (i == 0).then_some(&start[..len]);
            if k == 3 {
                rotor_drift_3().drift_inverse(body, rates, g * h, seed);
            } else {
                rotor_drift_4().drift_inverse(body, rates, g * h, seed);
            }
        }
    }
}

/// One torque-free step of `body` for the free flight of moving bodies. An isotropic body
/// in 3D or 4D (every plane moment the same I: a cube, a ball, a tesseract) moves exactly
/// ([`isotropic_flight`]). Any other body takes
/// `Splitting::strang().step(body, t, h, &Free)`, the same arithmetic; in 3D and 4D it reads
/// the inverse plane moments the inertia map keeps instead of copying the moments and
/// dividing, which matters where every body of a system takes such a step each step.
pub(crate) fn free_flight(body: &mut RigidBody, t: f64, h: f64) -> Result<(), DynamicsError> {
    let n = body.dim();
    let inverse = match body.inertia().diagonal_inverse_plane_moments() {
        Some(inv) if (n == 3 || n == 4) && body.gyrostatic_momentum().is_none() => {
            let mut copy = [0.0; 6];
            copy[..inv.len()].copy_from_slice(inv);
            copy
        }
        _ => {
            return Splitting::strang().step(body, t, h, &crate::dynamics::torques::Free);
        }
    };
    let k = n * (n - 1) / 2;
    if inverse[..k].iter().all(|&x| x == inverse[0]) {
        isotropic_flight(body, inverse[0], h);
    } else if n == 3 {
        rotor_drift_3().drift_inverse(body, &inverse[..3], h, None);
    } else {
        rotor_drift_4().drift_inverse(body, &inverse, h, None);
    }
    check_state(body, t)
}

/// The exact free flow for time `h` of a 3D or 4D body whose plane moments all equal
/// 1/`inverse`. Its energy |L|²/(2I) is a function of the Casimirs, so L stays put in the
/// body's axes ([L, ω] = [L, L/I] = 0) and the body turns uniformly, by the rotor
/// exp(−h L/(2I)) applied in its own axes. The splitting's plane rotations compose to this
/// only up to O(h³) per step; here one exponential (one quaternion exponential in 3D, two in
/// 4D) replaces their five or eleven.
fn isotropic_flight(body: &mut RigidBody, inverse: f64, h: f64) {
    let (attitude, momentum) = body.state_mut();
    let l = momentum.as_slice();
    let mut turn = [0.0; 6];
    for (a, &x) in turn.iter_mut().zip(l) {
        *a = -0.5 * h * inverse * x;
    }
    let (seed, len) = exp_seed_3d_4d(&turn[..l.len()]).expect("N = 3 or 4");
    attitude
        .rotor_mut()
        .expect("a rotor attitude for N ≤ 4")
        .times_one_plus(&seed[..len]);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::Rotor;
    use crate::inertia::InertiaMap;

    /// The free flight of a body whose plane moments differ is `Splitting::strang`'s step
    /// bit for bit, N = 2 … 6 (its own path in 3D and 4D, the splitting's elsewhere).
    #[test]
    fn free_flight_of_an_anisotropic_body_is_the_splittings_step() {
        for n in 2..=6usize {
            let moments: Vec<f64> = (0..n).map(|k| 0.4 + 0.3 * k as f64).collect();
            let l: Vec<f64> = (0..n * (n - 1) / 2)
                .map(|k| (1.3 * k as f64).cos())
                .collect();
            let body = RigidBody::from_body_momentum(
                InertiaMap::from_principal_second_moments(&moments).unwrap(),
                crate::dynamics::Attitude::identity(n),
                &Bivector::from_components(n, &l).unwrap(),
            )
            .unwrap();
            let (mut a, mut b) = (body.clone(), body);
            for k in 0..20 {
                let t = k as f64 * 0.05;
                free_flight(&mut a, t, 0.05).unwrap();
                Splitting::strang()
                    .step(&mut b, t, 0.05, &crate::dynamics::torques::Free)
                    .unwrap();
            }
            assert_eq!(a.momentum(), b.momentum(), "N = {n}");
            assert_eq!(
                a.principal_frame_attitude(),
                b.principal_frame_attitude(),
                "N = {n}"
            );
        }
    }

    /// An isotropic body (a cube, a tesseract) in free flight keeps L in its own axes and
    /// turns uniformly: after k steps its attitude is R₀ exp(−k h L/(2I)) by the algebra's
    /// exponential, to round-off, and Strang's splitting at a 100 times smaller step
    /// converges to the same motion (its error O(h²) over the run).
    #[test]
    fn free_flight_of_an_isotropic_body_is_the_exact_uniform_turn() {
        let mut cases = 0;
        for n in [3usize, 4] {
            let m = n * (n - 1) / 2;
            let inertia = InertiaMap::from_principal_second_moments(&vec![0.3; n]).unwrap();
            let plane_moment = 0.6;
            let l: Vec<f64> = (0..m).map(|k| 0.9 * (1.7 * k as f64 + 0.4).sin()).collect();
            let l = Bivector::from_components(n, &l).unwrap();
            let start = crate::dynamics::Attitude::identity(n)
                .times_exp(&Bivector::from_components(n, &vec![0.2; m]).unwrap());
            let body = RigidBody::from_body_momentum(inertia, start.clone(), &l).unwrap();
            let (steps, h) = (200, 0.01);
            let mut exact = body.clone();
            for k in 0..steps {
                free_flight(&mut exact, k as f64 * h, h).unwrap();
            }
            let t = steps as f64 * h;
            let expected = start
                .times_exp(&(&l * (-0.5 * t / plane_moment)))
                .to_matrix();
            let got = exact.principal_frame_attitude().to_matrix();
            assert!(
                (&got - &expected).amax() < 1e-13,
                "N = {n}: {}",
                (&got - &expected).amax()
            );
            assert_eq!(exact.momentum(), &l, "N = {n}: L moved in the body's axes");
            let mut split = body;
            for k in 0..100 * steps {
                Splitting::strang()
                    .step(
                        &mut split,
                        k as f64 * h / 100.0,
                        h / 100.0,
                        &crate::dynamics::torques::Free,
                    )
                    .unwrap();
            }
            let gap = (split.principal_frame_attitude().to_matrix() - &expected).amax();
            assert!(
                gap > 0.0 && gap < 1e-6,
                "N = {n}: Strang at h/100 is {gap} away"
            );
            cases += 1;
        }
        assert_eq!(cases, 2);
    }

    /// The sign of the isotropic turn in 3D: L = e₁₂ in the body's axes turns e₁ toward e₂
    /// by the angle t |L| / I, as the angular velocity ω = L/I says.
    #[test]
    fn an_isotropic_body_with_momentum_in_e12_turns_e1_toward_e2() {
        let inertia = InertiaMap::from_principal_second_moments(&[0.5; 3]).unwrap();
        let l = Bivector::from_components(3, &[2.0, 0.0, 0.0]).unwrap();
        let mut body =
            RigidBody::from_body_momentum(inertia, crate::dynamics::Attitude::identity(3), &l)
                .unwrap();
        for k in 0..10 {
            free_flight(&mut body, 0.01 * k as f64, 0.01).unwrap();
        }
        // Plane moment I = 0.5 + 0.5, angle 0.1 · 2 / 1.
        let q = body.principal_frame_attitude().to_matrix();
        let angle: f64 = 0.2;
        assert!((q[(0, 0)] - angle.cos()).abs() < 1e-15);
        assert!((q[(1, 0)] - angle.sin()).abs() < 1e-15);
        assert!(q[(2, 0)].abs() < 1e-15);
    }

    /// The unrolled 3D/4D drift performs the same updates as the general one.
    #[test]
    fn unrolled_drift_equals_the_general_drift() {
        for n in [3usize, 4] {
            let moments: Vec<f64> = (0..n).map(|k| 0.4 + 0.3 * k as f64).collect();
            let l: Vec<f64> = (0..n * (n - 1) / 2)
                .map(|k| (1.3 * k as f64).cos())
                .collect();
            let attitude =
                Rotor::from_rotation_bivector(&(Bivector::from_components(n, &l).unwrap() * 0.4));
            let body = RigidBody::from_body_momentum(
                InertiaMap::from_principal_second_moments(&moments).unwrap(),
                attitude,
                &Bivector::from_components(n, &l).unwrap(),
            )
            .unwrap();
            let plane_moments = body.inertia().diagonal_plane_moments().unwrap().to_vec();
            // The plain planes, and the symmetric part split off (the last plane's flow the
            // identity, which the unrolled kernel leaves out of its chain).
            let Moments::SymmetricPart { differences, .. } = Moments::new(&plane_moments, true)
            else {
                unreachable!("the symmetric part is split off")
            };
            assert_eq!(differences.last(), Some(&f64::INFINITY));
            for moments in [&plane_moments[..], &differences[..]] {
                let (mut fast, mut general) = (body.clone(), body.clone());
                for _ in 0..50 {
                    strang_drift(&mut fast, moments, 0.05);
                    strang_drift_planes(&mut general, moments, 0.05);
                }
                // The unrolled kernel turns the next plane's angle on its own (see
                // `RotorDrift::plane`), so the two agree to round-off; a wrong index, sign or
                // order would differ by O(h).
                let dl = (fast.momentum() - general.momentum()).norm();
                let da = (fast.principal_frame_attitude().to_matrix()
                    - general.principal_frame_attitude().to_matrix())
                .amax();
                assert!(
                    dl < 1e-14 && da < 1e-14,
                    "N = {n}: L {dl:e}, attitude {da:e}"
                );
                assert_ne!(fast.momentum(), body.momentum());
            }
        }
    }
}
