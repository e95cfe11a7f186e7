//! Runge–Kutta–Munthe-Kaas of order 4: classical RK4 on L, the attitude on the group.

use super::{DynamicsError, accept_state, check_state, momentum_rate as rates};
use crate::algebra::{Bivector, commutator_packed, pairs};
use crate::dynamics::torques::Free;
use crate::dynamics::{Attitude, RigidBody};
use nalgebra::{DMatrixView, DMatrixViewMut};

/// Classical RK4 on the momentum with the attitude advanced on Spin(N) by one exponential
/// per step (Runge–Kutta–Munthe-Kaas, Munthe-Kaas, BIT 38 (1998) 92): never plain RK on
/// rotor components, so R stays a rotor (or, for N > 4, an orthogonal matrix).
///
/// The attitude obeys dR/dt = R a with a = −½ω. Writing R(t₀ + h) = R₀ exp(Ω), the
/// classical RK4 tableau with the commutators reduced to their minimum (Munthe-Kaas and
/// Owren, Phil. Trans. R. Soc. A 357 (1999) 957, the order-4 scheme with two commutators;
/// signs here for the right action, \[X, Y\] = 2 X × Y) gives, with aᵢ = −½ωᵢ at the four
/// RK4 stages,
///
/// Ω = h/6 (a₁ + 2a₂ + 2a₃ + a₄) + h²/6 a₁ × a₄,
///
/// and, for torques that read the attitude, the stage attitudes R₀ exp(½h a₁),
/// R₀ exp(½h a₂ + ¼h² a₁ × a₂), R₀ exp(h a₃). Free motion needs five commutators and one
/// exponential per step. Order 4; energy and Casimirs drift like O(h⁴ t). Works with any
/// inertia map; free motion of a body diagonal on the basis planes runs on fixed-size stack
/// arrays for N ≤ 8 (no heap, no bivector temporaries) and on dense matrices above, one
/// matrix product per ω × L (10 products of N×N matrices per step, against 12 for RK4 on the
/// matrix equations).
#[derive(Clone, Copy, Debug, Default)]
pub struct Rkmk4;

impl Rkmk4 {
    /// Returns the integrator (it has no parameters; the same as `Rkmk4::default()`).
    pub const fn new() -> Self {
        Rkmk4
    }
}

impl_integrator!(
    Rkmk4,
    order = |_| 4,
    name = |_| "rk4",
    step = |_, body, t, h, torque| {
        // The packed free step assumes ω = I⁻¹(L); a gyrostat takes the general stages.
        if torque.is_zero() && body.gyrostatic_momentum().is_none() && free_step_packed(body, h) {
            return check_state(body, t);
        }
        let r0 = body.principal_frame_attitude().clone();
        let l0 = body.momentum().clone();
        // Stage attitudes only matter to a torque; free motion skips their exponentials.
        let attitude_dependent = !torque.is_zero();
        let stage = |a: &Bivector| {
            if attitude_dependent {
                r0.times_exp(a)
            } else {
                r0.clone()
            }
        };

        let (dl1, w1) = rates(body, t, &r0, &l0, torque);
        let a1 = w1 * -0.5;

        let r2 = stage(&(&a1 * (0.5 * h)));
        let l2 = &l0 + &(&dl1 * (0.5 * h));
        let (dl2, w2) = rates(body, t + 0.5 * h, &r2, &l2, torque);
        let a2 = w2 * -0.5;

        let r3 = if attitude_dependent {
            let mut u3 = &a2 * (0.5 * h);
            u3 += &(a1.commutator(&a2) * (0.25 * h * h));
            stage(&u3)
        } else {
            r0.clone()
        };
        let l3 = &l0 + &(&dl2 * (0.5 * h));
        let (dl3, w3) = rates(body, t + 0.5 * h, &r3, &l3, torque);
        let a3 = w3 * -0.5;

        let r4 = stage(&(&a3 * h));
        let l4 = &l0 + &(&dl3 * h);
        let (dl4, w4) = rates(body, t + h, &r4, &l4, torque);
        let a4 = w4 * -0.5;

        let u = rkmk4_increment([a1, a2, a3, a4], h);
        let mut dl = dl1 + &(dl2 * 2.0);
        dl += &(dl3 * 2.0);
        dl += &dl4;
        let l = &l0 + &(dl * (h / 6.0));
        accept_state(body, r0.times_exp(&u), l, t)
    }
);

/// The RKMK4 increment of the algebra: h/6 (a₁ + 2a₂ + 2a₃ + a₄) + h²/6 [a₁, a₄], from the
/// four stages' a = −½ω (the commutator is the order-4 correction of dexp⁻¹).
fn rkmk4_increment([a1, a2, a3, a4]: [Bivector; 4], h: f64) -> Bivector {
    let correction = a1.commutator(&a4) * (h * h / 6.0);
    let mut u = a1 + &(a2 * 2.0);
    u += &(a3 * 2.0);
    u += &a4;
    u *= h / 6.0;
    u += &correction;
    u
}

/// A Lie–Poisson integrator of order 4 built on RK4: the body momentum moves only by
/// rotations, L₁ = exp(−Ω) L₀ exp(Ω) with the attitude R₁ = R₀ exp(Ω), so it stays on its
/// coadjoint orbit.
///
/// Why that keeps the Casimirs and still has order 4: the exact free motion satisfies
/// L(t₀ + h) = g̃ L₀ g with g = R̃₀R(t₀ + h) (the space-frame momentum R L R̃ is constant), so
/// an order-4 approximation Ω of log g makes an O(h⁵) local error in both L and R, while every
/// Casimir of L (|L|², the Pfaffian in 4D, the traces of even powers of \[L\]) and the
/// space-frame momentum stay at round-off however long the run, in any N. The energy and the
/// other Manakov integrals drift like O(h⁴ t), as for [`Rkmk4`] (the method is not
/// symplectic). Integrators that keep coadjoint orbits this way: Engø and Faltinsen,
/// *Numerical integration of Lie–Poisson systems while preserving coadjoint orbits and
/// energy*, SIAM J. Numer. Anal. 39 (2001) 128.
///
/// How Ω is formed: classical RK4 on L gives L₁ and, with dL/dt at both ends, the cubic
/// Hermite interpolant of L over the step; ω = I⁻¹(L) at the two Gauss–Legendre nodes
/// θ = ½ ∓ √3/6 of it enter the fourth-order Magnus step (Iserles and Nørsett, *On the
/// solution of linear differential equations in Lie groups*, Phil. Trans. R. Soc. A 357
/// (1999) 983) for dR/dt = R a, a = −½ω:
///
/// Ω = h/2 (a₋ + a₊) + (√3/6) h² a₋ × a₊.
///
/// The interpolant is accurate to O(h⁴) at the nodes, so the quadrature keeps order 4. Six
/// right-hand-side commutators per step against RK4's five (dL/dt at the end of the step, and
/// the Magnus commutator instead of RK4's correction), one exponential, and one conjugation
/// of L by it (in 3D a Rodrigues rotation; in 4D each half of L turns by the quaternion of
/// the exponential's pair, so(4) = so(3) ⊕ so(3); above by the increment's matrix).
///
/// Any inertia map, and gyrostats (the total momentum is what the rotation carries). With a
/// torque τ the step takes [`Rkmk4`]'s stages with their attitudes R₀gᵢ, forms Ω from them as
/// [`Rkmk4`] does, the momentum in the frame of the step's start,
/// M₁ = L₀ + h/6 Σ bᵢ gᵢ τᵢ g̃ᵢ, and L₁ = exp(−Ω) M₁ exp(Ω): still order 4, and the Casimirs
/// change only through the torque.
///
/// Free motion of a body diagonal on the basis planes runs on the stack for N ≤ 8 (no heap).
///
/// ```
/// use rotorflow::prelude::*;
/// use rotorflow::dynamics::LiePoissonRk4;
/// let inertia = InertiaMap::from_principal_second_moments(&[0.5, 0.8, 1.3, 2.1])?;
/// let l = Bivector::from_components(4, &[0.9, -0.4, 0.3, 0.7, -0.2, 0.5])?;
/// let mut body = RigidBody::from_body_momentum(inertia, Attitude::identity(4), &l)?;
/// let (norm, pfaffian) = (body.momentum().norm(), body.momentum().pfaffian());
/// let mut lp = LiePoissonRk4::new();
/// for k in 0..1000 {
///     lp.step(&mut body, k as f64 * 0.05, 0.05, &Free)?;
/// }
/// // The Casimirs of L to round-off, whatever the step's accuracy.
/// assert!((body.momentum().norm() - norm).abs() < 1e-13);
/// assert!((body.momentum().pfaffian() - pfaffian).abs() < 1e-13);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct LiePoissonRk4;

impl LiePoissonRk4 {
    /// Returns the integrator (it has no parameters; the same as `LiePoissonRk4::default()`).
    pub const fn new() -> Self {
        LiePoissonRk4
    }
}

impl_integrator!(
    LiePoissonRk4,
    order = |_| 4,
    name = |_| "lie-poisson-rk4",
    step = |_, body, t, h, torque| {
        if torque.is_zero()
            && body.gyrostatic_momentum().is_none()
            && coadjoint_free_step_packed(body, h)
        {
            return check_state(body, t);
        }
        if torque.is_zero() {
            return lie_poisson_free_step(body, t, h);
        }
        let n = body.dim();
        let r0 = body.principal_frame_attitude().clone();
        let l0 = body.momentum().clone();
        // The stage increment gᵢ = exp(uᵢ) and the stage attitude R₀gᵢ.
        let stage = |u: &Bivector| (Attitude::identity(n).times_exp(u), r0.times_exp(u));
        // dL/dt and ω at a stage, and the torque's part of dL/dt (in the stage's frame).
        let rates_at = |t: f64, r: &Attitude, l: &Bivector| {
            let (free, w) = rates(body, t, r, l, &Free);
            let (dl, _) = rates(body, t, r, l, torque);
            let tau = &dl - &free;
            (dl, w, tau)
        };

        let (dl1, w1, tau1) = rates_at(t, &r0, &l0);
        let a1 = w1 * -0.5;
        let (g2, r2) = stage(&(&a1 * (0.5 * h)));
        let l2 = &l0 + &(&dl1 * (0.5 * h));
        let (dl2, w2, tau2) = rates_at(t + 0.5 * h, &r2, &l2);
        let a2 = w2 * -0.5;
        let mut u3 = &a2 * (0.5 * h);
        u3 += &(a1.commutator(&a2) * (0.25 * h * h));
        let (g3, r3) = stage(&u3);
        let l3 = &l0 + &(&dl2 * (0.5 * h));
        let (dl3, w3, tau3) = rates_at(t + 0.5 * h, &r3, &l3);
        let a3 = w3 * -0.5;
        let (g4, r4) = stage(&(&a3 * h));
        let l4 = &l0 + &(&dl3 * h);
        let (_, w4, tau4) = rates_at(t + h, &r4, &l4);
        let a4 = w4 * -0.5;

        let u = rkmk4_increment([a1, a2, a3, a4], h);
        // M₁ = L₀ + h/6 Σ bᵢ gᵢτᵢg̃ᵢ: the torque's impulse in the frame of the step's start.
        let mut impulse = tau1;
        impulse += &(g2.rotate_bivector(&tau2) * 2.0);
        impulse += &(g3.rotate_bivector(&tau3) * 2.0);
        impulse += &g4.rotate_bivector(&tau4);
        let mut m = l0 + &(impulse * (h / 6.0));
        let mut r = r0;
        r.times_exp_coadjoint_mut(&u, &mut m);
        accept_state(body, r, m, t)
    }
);

/// The free step of [`LiePoissonRk4`] on bivectors (any N, any inertia map, gyrostats): the
/// formulas of the stack version, `coadjoint_step_fixed`.
fn lie_poisson_free_step(body: &mut RigidBody, t: f64, h: f64) -> Result<(), DynamicsError> {
    let l0 = body.momentum().clone();
    let rate = |l: &Bivector| rates(body, t, body.principal_frame_attitude(), l, &Free);
    let (dl1, _) = rate(&l0);
    let (dl2, _) = rate(&(&l0 + &(&dl1 * (0.5 * h))));
    let (dl3, _) = rate(&(&l0 + &(&dl2 * (0.5 * h))));
    let (dl4, _) = rate(&(&l0 + &(&dl3 * h)));
    let mut sum = &dl1 + &(dl2 * 2.0);
    sum += &(dl3 * 2.0);
    sum += &dl4;
    let l1 = &l0 + &(sum * (h / 6.0));
    let (dl_end, _) = rate(&l1);
    let node = |(p0, q0, p1, q1): (f64, f64, f64, f64)| {
        let mut l = &l0 * p0;
        l += &(&dl1 * (h * q0));
        l += &(&l1 * p1);
        l += &(&dl_end * (h * q1));
        body.omega_of(&l)
    };
    let minus = node(GAUSS_HERMITE[0]);
    let plus = node(GAUSS_HERMITE[1]);
    let mut generator = minus.commutator(&plus) * (MAGNUS_4 * h * h);
    generator += &((minus + &plus) * (-0.25 * h));
    let mut r = body.principal_frame_attitude().clone();
    let mut l = l0;
    r.times_exp_coadjoint_mut(&generator, &mut l);
    accept_state(body, r, l, t)
}

/// The free-motion step for an inertia diagonal on the basis planes: on stack arrays for
/// 3 ≤ N ≤ 8, on dense matrices above; returns false (doing nothing) otherwise.
fn free_step_packed(body: &mut RigidBody, h: f64) -> bool {
    let n = body.dim();
    match n {
        3 => free_step_fixed::<3>(body, h),
        4 => free_step_fixed::<6>(body, h),
        5 => free_step_fixed::<10>(body, h),
        6 => free_step_fixed::<15>(body, h),
        7 => free_step_fixed::<21>(body, h),
        8 => free_step_fixed::<28>(body, h),
        9.. => free_step_dense(body, h),
        _ => false,
    }
}

/// The coadjoint free step on stack arrays for 3 ≤ N ≤ 8; false (doing nothing) otherwise.
fn coadjoint_free_step_packed(body: &mut RigidBody, h: f64) -> bool {
    match body.dim() {
        3 => coadjoint_step_fixed::<3>(body, h),
        4 => coadjoint_step_fixed::<6>(body, h),
        5 => coadjoint_step_fixed::<10>(body, h),
        6 => coadjoint_step_fixed::<15>(body, h),
        7 => coadjoint_step_fixed::<21>(body, h),
        8 => coadjoint_step_fixed::<28>(body, h),
        _ => false,
    }
}

/// The free step of [`LiePoissonRk4`] with K = N(N−1)/2 packed components.
fn coadjoint_step_fixed<const K: usize>(body: &mut RigidBody, h: f64) -> bool {
    let Some(free) = PackedFree::<K>::of(body) else {
        return false;
    };
    let (n, l0, inverse) = (PackedFree::<K>::N, free.l0, free.inverse);
    let (mut dl, mut w) = ([[0.0; K]; 4], [[0.0; K]; 4]);
    free.rk4_stages(h, &mut dl, &mut w);
    let [dl1, dl2, dl3, dl4] = &dl;
    let l1: [f64; K] =
        std::array::from_fn(|k| l0[k] + h / 6.0 * (dl1[k] + 2.0 * dl2[k] + 2.0 * dl3[k] + dl4[k]));
    let (mut dl_end, mut w_end) = ([0.0; K], [0.0; K]);
    free.rate(&l1, &mut dl_end, &mut w_end);
    // ω at the two Gauss nodes from the cubic Hermite interpolant of L.
    let [(p0, q0, p1, q1), (r0, s0, r1, s1)] = GAUSS_HERMITE;
    let mut minus = [0.0; K];
    let mut plus = [0.0; K];
    for k in 0..K {
        let (a, b, c, d) = (l0[k], h * dl1[k], l1[k], h * dl_end[k]);
        minus[k] = (p0 * a + q0 * b + p1 * c + q1 * d) * inverse[k];
        plus[k] = (r0 * a + s0 * b + r1 * c + s1 * d) * inverse[k];
    }
    let mut correction = [0.0; K];
    commutator_packed(n, &minus, &plus, &mut correction);
    let mut generator = Bivector::zero(n);
    for (k, u) in generator.as_mut_slice().iter_mut().enumerate() {
        *u = -0.25 * h * (minus[k] + plus[k]) + MAGNUS_4 * h * h * correction[k];
    }
    let (attitude, momentum) = body.state_mut();
    attitude.times_exp_coadjoint_mut(&generator, momentum);
    true
}

thread_local! {
    /// Scratch of [`free_step_dense`], kept between steps: at N = 32 zeroing a fresh buffer
    /// cost 2 µs of a 35 µs step.
    static DENSE_SCRATCH: std::cell::RefCell<Vec<f64>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// The same formulas for N > 8 on dense N×N matrices (column-major), without bivector
/// temporaries (they would allocate ~20 times a step) and without repacking for every
/// product (which cost as much as the products at N = 32).
///
/// Each ω × L is one matrix product. For a physical body, whose L = Jω + ωJ with J diagonal,
/// ω × L = ωL − Lω = ω²J − Jω², so (ω × L)ᵢⱼ = Cᵢⱼ (Jⱼ − Jᵢ) with C = ω²: one product and a
/// scaling that, being linear, is applied to the stage sums at the end. For a general
/// diagonal map, C − Cᵀ with C = ωL (skew ω, L).
fn free_step_dense(body: &mut RigidBody, h: f64) -> bool {
    DENSE_SCRATCH.with(|cell| match cell.try_borrow_mut() {
        Ok(mut scratch) => free_step_dense_in(body, h, &mut scratch),
        Err(_) => free_step_dense_in(body, h, &mut Vec::new()),
    })
}

fn free_step_dense_in(body: &mut RigidBody, h: f64, scratch: &mut Vec<f64>) -> bool {
    let n = body.dim();
    let inertia = body.inertia();
    let Some(inverse) = inertia.diagonal_inverse_plane_moments() else {
        return false;
    };
    // Principal moments of a physical map (diagonal here, since the plane moments are).
    let moments = inertia.principal_second_moments();
    let physical = moments.is_some();
    let nn = n * n;
    // Buffers spaced nn + 24 apart: at N = 32 a spacing of nn puts every buffer at the same
    // address modulo 4096, and the fused passes below stall on 4K aliasing (measured 3×).
    let stride = nn + 24;
    scratch.resize(13 * stride, 0.0);
    let (scratch, work) = scratch.split_at_mut(11 * stride);
    let mut parts = scratch.chunks_exact_mut(stride).map(|part| &mut part[..nn]);
    let mut next = || parts.next().expect("eleven parts");
    let (l0, mask, spread, stage, d) = (next(), next(), next(), next(), next());
    let (w, w1, c, sum_a, sum_b, generator) = (next(), next(), next(), next(), next(), next());
    // Every entry is written below before it is read, except the diagonals.
    for (((i, j), &x), &inv) in pairs(n).zip(body.momentum().as_slice()).zip(inverse) {
        // Entry (i, j) at j n + i.
        l0[j * n + i] = x;
        l0[i * n + j] = -x;
        mask[j * n + i] = inv;
        mask[i * n + j] = inv;
    }
    for k in 0..n {
        (l0[k * n + k], mask[k * n + k]) = (0.0, 0.0);
    }
    if let Some(m) = moments {
        // spread = (Jⱼ − Jᵢ) and, in `d`, (Jⱼ − Jᵢ) ∘ I⁻¹ for the stage ω.
        for (j, column) in spread.chunks_exact_mut(n).enumerate() {
            for (i, x) in column.iter_mut().enumerate() {
                *x = m[j] - m[i];
            }
        }
        for ((x, &s), &m) in d.iter_mut().zip(&*spread).zip(&*mask) {
            *x = s * m;
        }
    }
    let product = |a: &[f64], b: &[f64], c: &mut [f64]| {
        DMatrixViewMut::from_slice(c, n, n).gemm(
            1.0,
            &DMatrixView::from_slice(a, n, n),
            &DMatrixView::from_slice(b, n, n),
            0.0,
        );
    };
    // Stage 1: L₁ = L₀.
    for ((x, &l), &m) in w1.iter_mut().zip(&*l0).zip(&*mask) {
        *x = l * m;
    }
    w.copy_from_slice(w1);
    if !physical {
        // Only the general path multiplies by the stage L.
        stage.copy_from_slice(l0);
    }
    // Stages: the product; then one pass adds the stage's term to A = Σ₁³ (of dLₛ, or of Cₛ
    // for a physical body) and forms the next stage's ω (slices zipped, so that the pass
    // vectorises). B = Σ bₛ(·)ₛ = 2A − (·)₁ + (·)₄ needs no pass of its own: `sum_b` keeps
    // the first term until the end.
    for (s, step) in [0.5 * h, 0.5 * h, h, 0.0].into_iter().enumerate() {
        let last = s == 3;
        if physical {
            // ω_next = ω₁ + c h (C ∘ spread ∘ I⁻¹); `d` holds spread ∘ I⁻¹.
            let c = if s == 0 { &mut *sum_b } else { &mut *c };
            product(w, w, c);
            if last {
                break;
            }
            for ((((&c, a), &w1), w), &f) in c
                .iter()
                .zip(sum_a.iter_mut())
                .zip(&*w1)
                .zip(w.iter_mut())
                .zip(&*d)
            {
                *a = if s == 0 { c } else { *a + c };
                *w = w1 + step * c * f;
            }
        } else {
            product(w, stage, c);
            let dl = if s == 0 { &mut *sum_b } else { &mut *d };
            skew_part(n, c, dl);
            if last {
                break;
            }
            for (((((&d, a), &l), x), w), &m) in dl
                .iter()
                .zip(sum_a.iter_mut())
                .zip(&*l0)
                .zip(stage.iter_mut())
                .zip(w.iter_mut())
                .zip(&*mask)
            {
                *a = if s == 0 { d } else { *a + d };
                *x = l + step * d;
                *w = *x * m;
            }
        }
    }
    // A and B = 2A − (·)₁ + (·)₄ as sums of dLₛ (a physical body's Cₛ scaled by Jⱼ − Jᵢ).
    let last_term: &[f64] = if physical { c } else { d };
    for (((a, b), &t4), &s) in sum_a
        .iter_mut()
        .zip(sum_b.iter_mut())
        .zip(last_term)
        .zip(&*spread)
    {
        let scale = if physical { s } else { 1.0 };
        *b = scale * (2.0 * *a - *b + t4);
        *a *= scale;
    }
    // S = 2Ω = −h/6 Σ bᵢωᵢ + h²/12 [ω₁, ω₄] (see free_step_fixed), with
    // Σ bᵢωᵢ = I⁻¹(Σ bᵢLᵢ) = I⁻¹(6L₀ + h A); `w` holds ω₄.
    product(w1, w, c);
    skew_part(n, c, d);
    for ((((g, &m), &l), &a), &d) in generator
        .iter_mut()
        .zip(&*mask)
        .zip(&*l0)
        .zip(&*sum_a)
        .zip(&*d)
    {
        *g = -h / 6.0 * (m * (6.0 * l + h * a)) + h * h / 12.0 * d;
    }
    let (attitude, momentum) = body.state_mut();
    for ((i, j), l) in pairs(n).zip(momentum.as_mut_slice()) {
        let e = j * n + i;
        *l = l0[e] + h / 6.0 * sum_b[e];
    }
    attitude.times_expm_dense(generator, work);
    true
}

/// out = C − Cᵀ for a column-major N×N C, from the upper triangle.
fn skew_part(n: usize, c: &[f64], out: &mut [f64]) {
    for j in 0..n {
        for i in 0..j {
            let d = c[j * n + i] - c[i * n + j];
            out[j * n + i] = d;
            out[i * n + j] = -d;
        }
        out[j * n + j] = 0.0;
    }
}

/// A free body whose inertia is diagonal on the basis planes, as K = N(N−1)/2 packed
/// components on the stack: the momentum at the step's start and the inverse plane moments.
struct PackedFree<const K: usize> {
    l0: [f64; K],
    inverse: [f64; K],
}

impl<const K: usize> PackedFree<K> {
    /// The dimension N of space, with K = N(N−1)/2: a constant of each instance, so that the
    /// commutator's dispatch on N folds away.
    const N: usize = dimension_of_planes(K);

    /// None unless the body's inertia is diagonal on the basis planes.
    fn of(body: &RigidBody) -> Option<Self> {
        let cached = body.inertia().diagonal_inverse_plane_moments()?;
        let mut inverse = [0.0; K];
        inverse.copy_from_slice(cached);
        let mut l0 = [0.0; K];
        l0.copy_from_slice(body.momentum().as_slice());
        Some(PackedFree { l0, inverse })
    }

    /// dL/dt and ω at momentum l, written into `dl` and `w`: in place, so that the stages,
    /// the whole state of the step, are never copied.
    #[inline(always)]
    fn rate(&self, l: &[f64; K], dl: &mut [f64; K], w: &mut [f64; K]) {
        for k in 0..K {
            w[k] = l[k] * self.inverse[k];
        }
        commutator_packed(Self::N, w, l, dl);
    }

    /// dL/dt and ω at the four stages of classical RK4 from `l0` with step h.
    #[inline(always)]
    fn rk4_stages(&self, h: f64, dl: &mut [[f64; K]; 4], w: &mut [[f64; K]; 4]) {
        let mut l = self.l0;
        for (stage, s) in [0.5 * h, 0.5 * h, h].into_iter().enumerate() {
            self.rate(&l, &mut dl[stage], &mut w[stage]);
            for k in 0..K {
                l[k] = self.l0[k] + s * dl[stage][k];
            }
        }
        self.rate(&l, &mut dl[3], &mut w[3]);
    }
}

/// The N with N(N−1)/2 = K.
const fn dimension_of_planes(k: usize) -> usize {
    let mut n = 1;
    while n * (n - 1) / 2 < k {
        n += 1;
    }
    assert!(n * (n - 1) / 2 == k, "K is not a number of planes");
    n
}

/// The same formulas as [`Rkmk4::step`] with K = N(N−1)/2 packed components.
fn free_step_fixed<const K: usize>(body: &mut RigidBody, h: f64) -> bool {
    let Some(free) = PackedFree::<K>::of(body) else {
        return false;
    };
    let (n, l0) = (PackedFree::<K>::N, free.l0);
    let (mut dl, mut w) = ([[0.0; K]; 4], [[0.0; K]; 4]);
    free.rk4_stages(h, &mut dl, &mut w);
    let ([dl1, dl2, dl3, dl4], [w1, w2, w3, w4]) = (&dl, &w);

    // aᵢ = −½ωᵢ; Ω = h/6 Σ bᵢaᵢ + h²/6 a₁ × a₄ = −h/12 Σ bᵢωᵢ + h²/24 ω₁ × ω₄.
    let mut correction = [0.0; K];
    commutator_packed(n, w1, w4, &mut correction);
    let mut u = [0.0; K];
    let mut l = [0.0; K];
    for k in 0..K {
        u[k] =
            -h / 12.0 * (w1[k] + 2.0 * w2[k] + 2.0 * w3[k] + w4[k]) + h * h / 24.0 * correction[k];
        l[k] = l0[k] + h / 6.0 * (dl1[k] + 2.0 * dl2[k] + 2.0 * dl3[k] + dl4[k]);
    }
    let (attitude, momentum) = body.state_mut();
    momentum.as_mut_slice().copy_from_slice(&l);
    let mut generator = Bivector::zero(n);
    generator.as_mut_slice().copy_from_slice(&u);
    attitude.times_exp_mut(&generator);
    true
}

/// The cubic Hermite basis (h₀₀, h₁₀, h₀₁, h₁₁) at the two Gauss–Legendre nodes
/// θ = ½ ∓ √3/6: L(θh) ≈ h₀₀L₀ + h₁₀ h L̇₀ + h₀₁L₁ + h₁₁ h L̇₁.
const GAUSS_HERMITE: [(f64, f64, f64, f64); 2] = [hermite(GAUSS_MINUS), hermite(GAUSS_PLUS)];
const GAUSS_MINUS: f64 = 0.5 - 0.288_675_134_594_812_9;
const GAUSS_PLUS: f64 = 0.5 + 0.288_675_134_594_812_9;
/// √3/24: the commutator weight of the fourth-order Magnus step in terms of ω (see
/// [`LiePoissonRk4`]).
const MAGNUS_4: f64 = 0.072_168_783_648_703_22;

const fn hermite(t: f64) -> (f64, f64, f64, f64) {
    let (t2, t3) = (t * t, t * t * t);
    (
        2.0 * t3 - 3.0 * t2 + 1.0,
        t3 - 2.0 * t2 + t,
        -2.0 * t3 + 3.0 * t2,
        t3 - t2,
    )
}
