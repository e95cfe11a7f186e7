//! The invariants of free rotation and their drift.

use super::RigidBody;
use crate::algebra::Bivector;
use nalgebra::DMatrix;

/// The largest N for which [`Invariants::of`] fills [`Invariants::manakov`]: the expansion
/// costs O(N⁵) per evaluation (0.3 ms at N = 16), too much to pay at every sample above.
pub const MANAKOV_MAX_DIM: usize = 16;

/// The number of Manakov integrals [`manakov_integrals`] returns in dimension `n`:
/// Σ_(k=2…N) ⌊k/2⌋ = (dim so(N) + rank so(N)) / 2, the Casimirs included. That is the
/// number of functionally independent integrals of the Mishchenko–Fomenko family (half of
/// them beyond the ⌊N/2⌋ Casimirs are the ones in involution that make the top
/// Liouville-integrable): 2, 4, 6, 9, 12, 16 for N = 3 … 8.
pub fn manakov_count(n: usize) -> usize {
    (2..=n).map(|k| k / 2).sum()
}

/// The integrals of Manakov's top for a momentum L (principal frame) and principal second
/// moments J: the coefficients c_(k,j) of λʲ in tr (\[L\] + λJ²)ᵏ with an even number
/// k − j = 2m ≥ 2 of factors \[L\], listed for k = 2 … N and m = 1 … ⌊k/2⌋ (j = k − 2m).
///
/// L(λ) = L + λJ² is a Lax matrix of the free body whose inertia is I(ω) = Jω + ωJ (Manakov,
/// 1976): dL(λ)/dt = \[L(λ), Ω + λJ\], so every coefficient is conserved. Coefficients with
/// an odd number of factors \[L\] vanish (\[L\] is skew, J² symmetric), those without any are
/// constants, and k > N adds nothing new (Cayley–Hamilton). The j = 0 entries are the
/// Casimirs tr \[L\]^(2m). In 3D the two integrals are −2|L|² and 3 tr(\[L\]² J²), a
/// combination of |L|² and the energy.
///
/// # Panics
/// If `second_moments` does not have N entries.
pub fn manakov_integrals(l: &Bivector, second_moments: &[f64]) -> Vec<f64> {
    let n = l.dim();
    assert_eq!(
        second_moments.len(),
        n,
        "rotorflow: one second moment per axis"
    );
    let lm = l.to_skew_matrix();
    let a: Vec<f64> = second_moments.iter().map(|j| j * j).collect();
    // P[j] = coefficient of λʲ in (L + λA)ᵏ; A is diagonal, so P[j−1] A scales columns.
    let times_a = |p: &DMatrix<f64>| {
        let mut q = p.clone();
        for (c, &ac) in a.iter().enumerate() {
            q.column_mut(c).scale_mut(ac);
        }
        q
    };
    let mut p: Vec<DMatrix<f64>> = vec![lm.clone(), DMatrix::from_diagonal(&a.clone().into())];
    let mut out = Vec::with_capacity(manakov_count(n));
    for k in 2..=n {
        let mut next: Vec<DMatrix<f64>> = Vec::with_capacity(k + 1);
        for j in 0..=k {
            let mut m = if j < k {
                &p[j] * &lm
            } else {
                DMatrix::zeros(n, n)
            };
            if j >= 1 {
                m += times_a(&p[j - 1]);
            }
            next.push(m);
        }
        p = next;
        for m in 1..=k / 2 {
            out.push(p[k - 2 * m].trace());
        }
    }
    out
}

/// The size [`Invariants::drift_from`] measures each Manakov integral against:
/// C(k, j) (2|L|²)^m (max J²)^j, a bound on |c_(k,j)| (C(k, j) words of 2m factors of norm
/// at most |\[L\]|_F = √2 |L| and j of norm at most max J²).
fn manakov_scales(n: usize, l_squared: f64, second_moments: &[f64]) -> Vec<f64> {
    let amax = second_moments.iter().fold(0.0f64, |m, j| m.max(j * j));
    let mut out = Vec::with_capacity(manakov_count(n));
    for k in 2..=n {
        for m in 1..=k / 2 {
            let j = k - 2 * m;
            let binom = (1..=j).fold(1.0, |b, i| b * (k - j + i) as f64 / i as f64);
            out.push(binom * (2.0 * l_squared).powi(m as i32) * amax.powi(j as i32));
        }
    }
    out
}

/// The conserved quantities of free rotation at one instant: kinetic energy, the Casimirs of
/// L (the coefficients of the characteristic polynomial of \[L\], |L|² first, and the
/// Pfaffian in even N), the space-frame momentum, and the attitude's distance from its group
/// (Spin(N) for a rotor, SO(N) for a matrix). Why these are conserved: Leyvraz, *Understanding rigid
/// body motion in arbitrary dimensions*, 2015 (the book's References chapter).
#[derive(Clone, Debug, PartialEq)]
pub struct Invariants {
    /// T = ½⟨ω, L⟩.
    pub energy: f64,
    /// c_k of det(λ − \[L\]) = Σ c_k λ^(N−2k), k = 1 … ⌊N/2⌋ (c₁ = |L|²).
    pub casimirs: Vec<f64>,
    /// Pf(\[L\]) in even N (its square is the last Casimir; its sign is conserved too).
    pub pfaffian: Option<f64>,
    /// L_s = R L R̃.
    pub space_momentum: Bivector,
    /// How far the attitude has left its group ([`crate::dynamics::Attitude::unit_error`]):
    /// max |R R̃ − 1| for a rotor (N ≤ 4), max |QᵀQ − 1| for a matrix (N > 4).
    pub attitude_error: f64,
    /// The integrals of Manakov's top ([`manakov_integrals`]) for a physical inertia map
    /// with N ≤ [`MANAKOV_MAX_DIM`]; empty otherwise (a general map has no J).
    pub manakov: Vec<f64>,
    /// The size each entry of [`Invariants::manakov`] is measured against in its drift.
    pub manakov_scales: Vec<f64>,
}

impl Invariants {
    /// Returns the invariants of `body` now.
    pub fn of(body: &RigidBody) -> Self {
        let l = body.momentum();
        let c = l.characteristic_coefficients();
        let attitude_error = body.principal_frame_attitude().unit_error();
        let n = body.dim();
        // A gyrostat's flow does not keep Manakov's integrals.
        let rigid = body.gyrostatic_momentum().is_none();
        let (manakov, manakov_scales) = match body.inertia().principal_second_moments() {
            Some(j) if rigid && n <= MANAKOV_MAX_DIM => (
                manakov_integrals(l, j),
                manakov_scales(n, l.norm_squared(), j),
            ),
            _ => (Vec::new(), Vec::new()),
        };
        Invariants {
            energy: body.energy(),
            casimirs: c[1..].to_vec(),
            pfaffian: n.is_multiple_of(2).then(|| l.pfaffian()),
            space_momentum: body.space_momentum(),
            attitude_error,
            manakov,
            manakov_scales,
        }
    }

    /// The relative drift of each Manakov integral from `reference`:
    /// |c − c₀| / (the reference's scale of that integral); empty when either has none.
    pub fn manakov_drifts(&self, reference: &Invariants) -> Vec<f64> {
        self.manakov
            .iter()
            .zip(&reference.manakov)
            .zip(&reference.manakov_scales)
            .map(|((a, b), s)| (a - b).abs() / s.max(f64::MIN_POSITIVE))
            .collect()
    }

    /// Returns the largest relative drifts from `reference`: (energy, Casimirs, space
    /// momentum), each |x − x₀| / |x₀| (the Casimir c_k scaled by |L|^(2k) so that vanishing
    /// invariants of a degenerate L do not divide by zero), and the attitude's current
    /// distance from its group.
    pub fn drift_from(&self, reference: &Invariants) -> Drift {
        let energy = rel(self.energy, reference.energy);
        let l2 = reference.casimirs.first().copied().unwrap_or(0.0);
        let casimirs = self
            .casimirs
            .iter()
            .zip(&reference.casimirs)
            .enumerate()
            .map(|(k, (a, b))| (a - b).abs() / l2.powi(k as i32 + 1).max(f64::MIN_POSITIVE))
            .fold(0.0f64, f64::max);
        let scale = reference.space_momentum.norm().max(f64::MIN_POSITIVE);
        let space_momentum = (&self.space_momentum - &reference.space_momentum).norm() / scale;
        let manakov = self
            .manakov_drifts(reference)
            .into_iter()
            .fold(0.0f64, f64::max);
        Drift::new(energy, casimirs, space_momentum, self.attitude_error).with_manakov(manakov)
    }
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(f64::MIN_POSITIVE)
}

/// Relative drifts of the invariants (see [`Invariants::drift_from`]).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Drift {
    /// |ΔT|/T.
    pub energy: f64,
    /// max_k |Δc_k| / |L|^(2k).
    pub casimirs: f64,
    /// |ΔL_s| / |L_s|.
    pub space_momentum: f64,
    /// The attitude's distance from its group ([`crate::dynamics::Attitude::unit_error`]):
    /// max |R R̃ − 1| for a rotor (N ≤ 4), max |QᵀQ − 1| for a matrix (N > 4).
    pub attitude: f64,
    /// The largest relative drift of the Manakov integrals ([`Invariants::manakov_drifts`]);
    /// 0 where there are none.
    pub manakov: f64,
}

impl Drift {
    /// Returns the drifts with these values.
    pub(crate) fn new(energy: f64, casimirs: f64, space_momentum: f64, attitude: f64) -> Self {
        Drift {
            energy,
            casimirs,
            space_momentum,
            attitude,
            manakov: 0.0,
        }
    }

    /// The same drifts with the Manakov integrals' largest drift set to `manakov`.
    pub(crate) fn with_manakov(mut self, manakov: f64) -> Self {
        self.manakov = manakov;
        self
    }

    /// Returns the larger of each drift in `self` and `other` (the worst over two instants).
    pub fn max(self, other: Drift) -> Drift {
        Drift::new(
            self.energy.max(other.energy),
            self.casimirs.max(other.casimirs),
            self.space_momentum.max(other.space_momentum),
            self.attitude.max(other.attitude),
        )
        .with_manakov(self.manakov.max(other.manakov))
    }
}
