//! The invariants of free rotation and their drift.

use super::RigidBody;
use crate::algebra::Bivector;

/// The conserved quantities of free rotation at one instant (REFERENCES §2): kinetic energy,
/// the Casimirs of L (the coefficients of the characteristic polynomial of \[L\], |L|² first,
/// and the Pfaffian in even N), the space-frame momentum, and the rotor's distance from
/// Spin(N).
#[derive(Clone, Debug, PartialEq)]
pub struct Invariants {
    /// T = ½⟨ω, L⟩.
    pub energy: f64,
    /// c_k of det(λ − \[L\]) = Σ c_k λ^{N−2k}, k = 1 … ⌊N/2⌋ (c₁ = |L|²).
    pub casimirs: Vec<f64>,
    /// Pf(\[L\]) in even N (its square is the last Casimir; its sign is conserved too).
    pub pfaffian: Option<f64>,
    /// L_s = R L R̃.
    pub space_momentum: Bivector,
    /// How far the attitude has left the group ([`crate::dynamics::Attitude::unit_error`]):
    /// max |R R̃ − 1| for a rotor, max |QᵀQ − 1| for a matrix (N > 8).
    pub rotor_error: f64,
}

impl Invariants {
    /// Returns the invariants of `body` now.
    pub fn of(body: &RigidBody) -> Self {
        let l = body.momentum();
        let c = l.characteristic_coefficients();
        Invariants {
            energy: body.energy(),
            casimirs: c[1..].to_vec(),
            pfaffian: body.dim().is_multiple_of(2).then(|| l.pfaffian()),
            space_momentum: body.space_momentum(),
            rotor_error: body.attitude().unit_error(),
        }
    }

    /// Returns the largest relative drifts from `reference`: (energy, Casimirs, space
    /// momentum), each |x − x₀| / |x₀| (the Casimir c_k scaled by |L|^{2k} so that vanishing
    /// invariants of a degenerate L do not divide by zero).
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
        Drift {
            energy,
            casimirs,
            space_momentum,
            rotor: self.rotor_error,
        }
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
    /// max_k |Δc_k| / |L|^{2k}.
    pub casimirs: f64,
    /// |ΔL_s| / |L_s|.
    pub space_momentum: f64,
    /// max |R R̃ − 1| now.
    pub rotor: f64,
}
