//! Observables of sampled motions: mean, amplitude and frequency of a component, its sign
//! flips, and these for the three planes of a 3D projection of an N-D motion.

use crate::algebra::{Bivector, pair_index};
use crate::dynamics::DynamicsError;

/// How one sampled component oscillates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Oscillation {
    /// The mean of the samples.
    pub mean: f64,
    /// Half the peak-to-peak range of the samples.
    pub amplitude: f64,
    /// The angular frequency about the mean, π (k − 1)/(t_k − t_1) from the k interpolated
    /// mean crossings t_1 … t_k; 0 when there are fewer than two crossings (no oscillation
    /// within the samples) or the amplitude is negligible.
    pub frequency: f64,
}

/// Returns the mean, amplitude and angular frequency of the samples `values` at `times`
/// (pairs beyond the shorter slice are ignored).
///
/// The frequency counts the crossings of the mean: a sinusoid crosses it twice per period,
/// so k crossings spanning a time S give the angular frequency π (k − 1)/S. Wiggles within
/// 10⁻⁹ of the amplitude and mean are not crossings.
///
/// ```
/// use rotorflow::dynamics::trajectory::{even_times, oscillation};
///
/// // Ten whole periods of sin 3t about 0.5.
/// let t = even_times(20.0 * std::f64::consts::PI / 3.0, 2001);
/// let x: Vec<f64> = t.iter().map(|t| 0.5 + 2.0 * (3.0 * t).sin()).collect();
/// let o = oscillation(&t, &x);
/// assert!((o.frequency - 3.0).abs() < 1e-3);
/// assert!((o.amplitude - 2.0).abs() < 1e-3);
/// ```
pub fn oscillation(times: &[f64], values: &[f64]) -> Oscillation {
    let len = times.len().min(values.len());
    let values = &values[..len];
    let mean = values.iter().sum::<f64>() / len.max(1) as f64;
    let (lo, hi) = values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(*v), b.max(*v))
        });
    let amplitude = if len == 0 { 0.0 } else { 0.5 * (hi - lo) };
    let crossings = crossings(times, values, mean, 1e-9 * (amplitude + mean.abs()));
    let frequency = if crossings.len() >= 2 && amplitude > 1e-12 * (1.0 + mean.abs()) {
        let span = crossings[crossings.len() - 1] - crossings[0];
        std::f64::consts::PI * (crossings.len() - 1) as f64 / span
    } else {
        0.0
    };
    Oscillation {
        mean,
        amplitude,
        frequency: if frequency.is_finite() {
            frequency
        } else {
            0.0
        },
    }
}

/// Returns the times where the samples cross `level`, linearly interpolated between the two
/// samples around each crossing. Samples within `tol` of the level are skipped, so that
/// rounding noise about the level is not counted as crossings.
///
/// ```
/// use rotorflow::dynamics::trajectory::crossings;
///
/// let t = [0.0, 1.0, 2.0, 3.0];
/// let x = [1.0, -1.0, -3.0, 1.0];
/// assert_eq!(crossings(&t, &x, 0.0, 0.0), vec![0.5, 2.75]);
/// ```
pub fn crossings(times: &[f64], values: &[f64], level: f64, tol: f64) -> Vec<f64> {
    let mut out = Vec::new();
    // (time, value − level) of the last sample clear of the level.
    let mut last: Option<(f64, f64)> = None;
    for (&ti, &xi) in times.iter().zip(values) {
        let d = xi - level;
        if d.abs() <= tol {
            continue;
        }
        if let Some((tp, dp)) = last
            && dp.signum() != d.signum()
        {
            out.push(tp + (ti - tp) * dp / (dp - d));
        }
        last = Some((ti, d));
    }
    out
}

/// The observables of a motion seen in the 3D projection along three space axes: for each
/// of the three planes of those axes, how the body-frame angular velocity component ω_ab
/// oscillates, and the sign flips of the largest of the three (the rotation turning over, as
/// in the intermediate-axis flip).
#[derive(Clone, Debug, PartialEq)]
pub struct ProjectedObservables {
    /// The three planes (a, b) of the projection, 0-based, a < b, in lexicographic order.
    pub planes: [(usize, usize); 3],
    /// The angular frequency of ω_ab about its mean, per plane (see [`Oscillation`]).
    pub frequency: [f64; 3],
    /// Half the peak-to-peak range of ω_ab, per plane.
    pub amplitude: [f64; 3],
    /// The mean of ω_ab, per plane.
    pub mean: [f64; 3],
    /// The sign changes of the component with the largest magnitude.
    pub flips: usize,
    /// The (interpolated) time of the first sign change, if any.
    pub first_flip: Option<f64>,
}

/// Returns the three planes (a, b), a < b, of the space axes `axes` (0-based), in
/// lexicographic order.
pub fn projection_planes(axes: [usize; 3]) -> [(usize, usize); 3] {
    let mut s = axes;
    s.sort_unstable();
    [(s[0], s[1]), (s[0], s[2]), (s[1], s[2])]
}

/// Returns the observables of the angular velocities `omega` sampled at `times` (body
/// frame, any basis in which the planes of `axes` are basis planes) in the 3D projection
/// along `axes` (0-based).
///
/// ```
/// use rotorflow::algebra::Bivector;
/// use rotorflow::dynamics::trajectory::{even_times, projected_observables};
///
/// // In 4D, ω₁₂ = cos 2t turns over (five whole periods); ω₁₃ and ω₂₃ are constant.
/// let t = even_times(5.0 * std::f64::consts::PI, 2001);
/// let omega: Vec<Bivector> = t
///     .iter()
///     .map(|t| Bivector::from_components(4, &[(2.0 * t).cos(), 0.1, 0.0, 0.2, 0.0, 0.0]).unwrap())
///     .collect();
/// let o = projected_observables(&t, &omega, [0, 1, 2]).unwrap();
/// assert!((o.frequency[0] - 2.0).abs() < 1e-3);
/// assert_eq!(o.flips, 10); // cos 2t changes sign at t = π/4 + kπ/2 < 5π
/// assert!((o.first_flip.unwrap() - std::f64::consts::FRAC_PI_4).abs() < 1e-3);
/// ```
///
/// # Errors
/// [`DynamicsError::InvalidSampling`] when `times` and `omega` differ in length, the
/// bivectors are not all of one dimension N ≥ 3, or `axes` are not three distinct axes
/// below N.
pub fn projected_observables(
    times: &[f64],
    omega: &[Bivector],
    axes: [usize; 3],
) -> Result<ProjectedObservables, DynamicsError> {
    let invalid = |reason| DynamicsError::InvalidSampling { reason };
    if times.len() != omega.len() {
        return Err(invalid(
            "as many sample times as angular velocities are needed",
        ));
    }
    let n = omega.first().map_or(3, Bivector::dim);
    if n < 3 || omega.iter().any(|w| w.dim() != n) {
        return Err(invalid(
            "the angular velocities must share one dimension N ≥ 3",
        ));
    }
    let planes = projection_planes(axes);
    if planes.iter().any(|&(a, b)| a == b || b >= n) {
        return Err(invalid("the projection needs three distinct axes below N"));
    }
    let series: Vec<Vec<f64>> = planes
        .iter()
        .map(|&(a, b)| {
            let k = pair_index(n, a, b);
            omega.iter().map(|w| w.as_slice()[k]).collect()
        })
        .collect();
    let mut out = ProjectedObservables {
        planes,
        frequency: [0.0; 3],
        amplitude: [0.0; 3],
        mean: [0.0; 3],
        flips: 0,
        first_flip: None,
    };
    for (k, x) in series.iter().enumerate() {
        let o = oscillation(times, x);
        out.frequency[k] = o.frequency;
        out.amplitude[k] = o.amplitude;
        out.mean[k] = o.mean;
    }
    let peak = |x: &[f64]| x.iter().fold(0.0f64, |acc, v| acc.max(v.abs()));
    let largest = (0..3)
        .max_by(|&a, &b| peak(&series[a]).total_cmp(&peak(&series[b])))
        .unwrap_or(0);
    let x = &series[largest];
    let flips = crossings(times, x, 0.0, 1e-9 * peak(x));
    out.flips = flips.len();
    out.first_flip = flips.first().copied();
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::trajectory::even_times;

    #[test]
    fn oscillation_of_a_shifted_sinusoid() {
        let t = even_times(30.0, 3001);
        for (w, a, m) in [(0.7, 1.5, -0.2), (2.5, 0.01, 3.0), (5.0, 2.0, 0.0)] {
            let x: Vec<f64> = t.iter().map(|t| m + a * (w * t + 0.3).cos()).collect();
            let o = oscillation(&t, &x);
            assert!((o.frequency - w).abs() < 2e-3 * w, "{w}: {o:?}");
            assert!((o.amplitude - a).abs() < 1e-3 * a, "{a}: {o:?}");
            // The mean of the samples includes the partial last period: |error| ≤ a/(w T).
            assert!((o.mean - m).abs() <= a / (w * 30.0), "{m}: {o:?}");
        }
    }

    #[test]
    fn a_constant_or_monotone_signal_has_no_frequency() {
        let t = even_times(5.0, 101);
        let c = vec![2.0; t.len()];
        let o = oscillation(&t, &c);
        assert_eq!((o.frequency, o.amplitude, o.mean), (0.0, 0.0, 2.0));
        // A ramp crosses its mean once: no period.
        assert_eq!(oscillation(&t, &t).frequency, 0.0);
        assert_eq!(oscillation(&[], &[]).amplitude, 0.0);
    }

    #[test]
    fn crossings_skip_noise_at_the_level() {
        let t = [0.0, 1.0, 2.0, 3.0, 4.0];
        // A sample at the level (within tol) is skipped: one crossing between t = 1 and 3.
        let x = [1.0, 1.0, 1e-12, -1.0, -1.0];
        assert_eq!(crossings(&t, &x, 0.0, 1e-9), vec![2.0]);
        // Without a tolerance the crossing is interpolated from the tiny sample.
        let c = crossings(&t, &x, 0.0, 0.0);
        assert!(c.len() == 1 && (c[0] - 2.0).abs() < 1e-11, "{c:?}");
        assert!(crossings(&t, &[1.0; 5], 0.0, 0.0).is_empty());
    }

    #[test]
    fn projected_observables_pick_the_planes_of_the_axes() {
        // N = 4, axes (4, 2, 3) 1-based = planes 23, 24, 34; components are set by plane.
        // Eight whole periods of sin 1.5t, so that the sample mean is the true mean.
        let t = even_times(16.0 * std::f64::consts::PI / 1.5, 4001);
        let omega: Vec<Bivector> = t
            .iter()
            .map(|&s| {
                // order 12, 13, 14, 23, 24, 34
                Bivector::from_components(4, &[9.0, 9.0, 9.0, 0.5, (1.5 * s).sin(), -3.0]).unwrap()
            })
            .collect();
        let o = projected_observables(&t, &omega, [3, 1, 2]).unwrap();
        assert_eq!(o.planes, [(1, 2), (1, 3), (2, 3)]);
        assert_eq!(o.frequency[0], 0.0);
        assert!((o.frequency[1] - 1.5).abs() < 1e-4, "{o:?}");
        assert_eq!(o.mean[2], -3.0);
        // The largest component (−3) never changes sign.
        assert_eq!((o.flips, o.first_flip), (0, None));
    }

    #[test]
    fn projected_observables_refuse_bad_input() {
        let w = Bivector::from_components(3, &[1.0, 0.0, 0.0]).unwrap();
        let omega = vec![w.clone(), w];
        assert!(projected_observables(&[0.0], &omega, [0, 1, 2]).is_err());
        assert!(projected_observables(&[0.0, 1.0], &omega, [0, 1, 1]).is_err());
        assert!(projected_observables(&[0.0, 1.0], &omega, [0, 1, 3]).is_err());
        let w2 = Bivector::from_components(2, &[1.0]).unwrap();
        assert!(projected_observables(&[0.0], &[w2], [0, 1, 2]).is_err());
    }
}
