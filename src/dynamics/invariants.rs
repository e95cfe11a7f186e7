//! The invariants of free rotation and their drift.

use super::RigidBody;
use crate::algebra::Bivector;

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
    /// The same value as [`Invariants::attitude_error`], under its former name.
    #[deprecated(note = "use `attitude_error` (above N = 4 it is a matrix error, not a rotor's)")]
    pub rotor_error: f64,
}

impl Invariants {
    /// Returns the invariants of `body` now.
    pub fn of(body: &RigidBody) -> Self {
        let l = body.momentum();
        let c = l.characteristic_coefficients();
        let attitude_error = body.principal_frame_attitude().unit_error();
        #[allow(deprecated)] // the former name stays filled for existing readers
        Invariants {
            energy: body.energy(),
            casimirs: c[1..].to_vec(),
            pfaffian: body.dim().is_multiple_of(2).then(|| l.pfaffian()),
            space_momentum: body.space_momentum(),
            attitude_error,
            rotor_error: attitude_error,
        }
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
        Drift::new(energy, casimirs, space_momentum, self.attitude_error)
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
    /// The same value as [`Drift::attitude`], under its former name.
    #[deprecated(note = "use `attitude` (above N = 4 it is a matrix error, not a rotor's)")]
    pub rotor: f64,
}

impl Drift {
    /// Returns the drifts with these values (the deprecated `rotor` field mirrors `attitude`).
    pub fn new(energy: f64, casimirs: f64, space_momentum: f64, attitude: f64) -> Self {
        #[allow(deprecated)] // the former name stays filled for existing readers
        Drift {
            energy,
            casimirs,
            space_momentum,
            attitude,
            rotor: attitude,
        }
    }

    /// Returns the larger of each drift in `self` and `other` (the worst over two instants).
    pub fn max(self, other: Drift) -> Drift {
        Drift::new(
            self.energy.max(other.energy),
            self.casimirs.max(other.casimirs),
            self.space_momentum.max(other.space_momentum),
            self.attitude.max(other.attitude),
        )
    }
}
