//! Linear stability of steady rotations in a principal plane.

/// One transverse mode of a steady rotation: the other principal axis r and the square of its
/// growth rate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mode {
    /// The third principal axis r ∉ {p, q} (0-based) whose planes (p, r), (q, r) perturb.
    pub axis: usize,
    /// λ_r²: positive means exponential growth at rate λ_r, negative means oscillation at
    /// frequency √(−λ_r²).
    pub rate_squared: f64,
}

/// Returns the transverse modes of the steady rotation with angular velocity ω_pq in the
/// principal plane (p, q) of a body with principal moments J (derived by linearising Euler's
/// equations about the steady rotation; the 3D case is the intermediate-axis theorem):
///
/// λ_r² = ω_pq² (J_p − J_r)(J_r − J_q) / ((J_p + J_r)(J_q + J_r)).
///
/// The perturbations decouple into the pairs (L_pr, L_qr); components in planes that meet
/// neither p nor q are neutral at first order. A rotation is unstable exactly when some J_r
/// lies strictly between J_p and J_q (in 3D: the intermediate axis). Note that in N ≥ 4 a
/// plane with a middle plane moment can still be stable.
///
/// # Panics
/// If p or q is out of range or p == q.
#[track_caller]
pub fn transverse_modes(moments: &[f64], p: usize, q: usize, omega_pq: f64) -> Vec<Mode> {
    let n = moments.len();
    assert!(
        p < n && q < n && p != q,
        "rotorflow: invalid plane ({p}, {q})"
    );
    let (jp, jq) = (moments[p], moments[q]);
    (0..n)
        .filter(|&r| r != p && r != q)
        .map(|r| {
            let jr = moments[r];
            Mode {
                axis: r,
                rate_squared: omega_pq * omega_pq * (jp - jr) * (jr - jq) / ((jp + jr) * (jq + jr)),
            }
        })
        .collect()
}

/// Returns the largest exponential growth rate max_r λ_r of the steady rotation (0 when
/// linearly stable). See [`transverse_modes`].
///
/// # Panics
/// As [`transverse_modes`].
#[track_caller]
pub fn growth_rate(moments: &[f64], p: usize, q: usize, omega_pq: f64) -> f64 {
    transverse_modes(moments, p, q, omega_pq)
        .iter()
        .map(|m| m.rate_squared.max(0.0).sqrt())
        .fold(0.0, f64::max)
}
