//! A sampled run of a [`System`]: the state of every body, the energies, the momenta and the
//! contacts at chosen times ([`System::record`]), as plain data that serialises (feature
//! `serde`: JSON) and writes as one CSV per body.

use super::{MotionIntegrator, System};
use crate::dynamics::DynamicsError;

/// The samples of one body.
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BodyTrack {
    /// The body's name (`body1`, `body2`, … unless set): the CSV file is `<name>.csv`.
    pub name: String,
    /// Its mass.
    pub mass: f64,
    /// The centre of mass per sample (N numbers).
    pub position: Vec<Vec<f64>>,
    /// The velocity of the centre of mass per sample.
    pub velocity: Vec<Vec<f64>>,
    /// The attitude (own axes → space) per sample: N rows of N.
    pub attitude: Vec<Vec<Vec<f64>>>,
    /// The angular velocity in the body's own axes per sample (planes 12, 13, …).
    pub omega: Vec<Vec<f64>>,
}

impl BodyTrack {
    /// Returns the attitude at sample `k` as a matrix (own axes → space).
    ///
    /// # Panics
    /// If there is no sample `k`.
    pub fn attitude_matrix(&self, k: usize) -> nalgebra::DMatrix<f64> {
        let rows = &self.attitude[k];
        nalgebra::DMatrix::from_fn(rows.len(), rows.len(), |r, c| rows[r][c])
    }
}

/// A contact at a sample: a body touching a half-space during the step that ended at the
/// sample, with the impulses the half-space gave it there over that step.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SampleContact {
    /// The body, by index.
    pub body: usize,
    /// The half-space, by index into [`SystemTrajectory::planes`].
    pub half_space: usize,
    /// The contact point in space, at the sample.
    pub point: Vec<f64>,
    /// The unit normal of the half-space (out of the solid, into the body).
    pub normal: Vec<f64>,
    /// The normal impulse (≥ 0) over the step, summed over its velocity solves.
    pub normal_impulse: f64,
    /// The friction impulse over the step (space frame, in the plane).
    pub friction_impulse: Vec<f64>,
    /// The sliding velocity of the point in the plane after the last solve: zero while the
    /// contact sticks or rolls.
    pub slip: Vec<f64>,
}

/// A half-space n·x ≥ d of a recorded system (n a unit vector), as the system holds it.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RecordedPlane {
    /// The unit normal n.
    pub normal: Vec<f64>,
    /// The offset d.
    pub offset: f64,
    /// Coulomb friction μ.
    pub friction: f64,
    /// Restitution e.
    pub restitution: f64,
}

/// What [`System::record`] records at each sample time: the bodies, the energies, the
/// momenta and the contacts.
#[derive(Clone, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SystemTrajectory {
    /// The dimension N.
    pub dim: usize,
    /// The sample times.
    pub times: Vec<f64>,
    /// One track per body, in the order of the system.
    pub bodies: Vec<BodyTrack>,
    /// The energy per sample.
    pub energy: Vec<f64>,
    /// The kinetic energy per sample.
    pub kinetic_energy: Vec<f64>,
    /// The potential energy of the forques per sample.
    pub potential_energy: Vec<f64>,
    /// The linear momentum per sample.
    pub momentum: Vec<Vec<f64>>,
    /// The angular momentum about the origin per sample (planes 12, 13, …).
    pub angular_momentum: Vec<Vec<f64>>,
    /// The contacts of the step that ended at each sample (none at a sample no step ends
    /// at, such as t = 0): one per point of a body touching a half-space, the entries of
    /// the step's velocity solves at that point summed ([`System::contacts`] lists them
    /// one by one).
    pub contacts: Vec<Vec<SampleContact>>,
    /// The system's half-spaces.
    pub planes: Vec<RecordedPlane>,
    /// The number of steps taken.
    pub steps: usize,
}

impl System {
    /// Steps the system from t = 0 by `dt` and records its state at each of `times`, with
    /// `integrator`: see [`System::record_with`], which this calls with the last sample
    /// time as the end and no observer.
    ///
    /// # Errors
    /// As [`System::record_with`].
    pub fn record(
        &mut self,
        integrator: &mut dyn MotionIntegrator,
        dt: f64,
        times: &[f64],
    ) -> Result<SystemTrajectory, DynamicsError> {
        let end = times.last().copied().unwrap_or(0.0);
        self.record_with(integrator, dt, times, end, &mut |_| {})
    }

    /// Steps the system from t = 0 to `t_end` by `dt` and records its state at each of
    /// `times` (strictly increasing, in [0, `t_end`]); `observe` is called with the number of
    /// samples taken after each one (for a progress bar).
    ///
    /// Every sample time is hit exactly: the steps of `dt` that would pass the next sample
    /// time (or `t_end`) stop short of it and one shorter step ends on it; a remainder below
    /// a millionth of `dt` joins the step before it. The steps of `dt` between two samples
    /// go to [`MotionIntegrator::advance`] together. This is how `rotorflow scene` runs a
    /// scene file.
    ///
    /// # Errors
    /// [`DynamicsError::InvalidSampling`] for a step that is not positive and finite, no
    /// sample times, or times that are not finite, negative, not strictly increasing or
    /// beyond `t_end`; [`DynamicsError::NonFinite`] at the first sample whose energy or
    /// momenta are not finite; any error of the integrator.
    ///
    /// ```
    /// use rotorflow::prelude::*;
    /// use rotorflow::dynamics::motion::forques::Gravity;
    /// use rotorflow::dynamics::motion::{MotionSplitting, MovingBody, System};
    /// let inertia = InertiaMap::from_principal_second_moments(&[0.2, 0.5, 0.9])?;
    /// let thrown = MovingBody::new(
    ///     1.0,
    ///     inertia,
    ///     Rotor::identity(3),
    ///     &Vector::zero(3),
    ///     &Vector::from_components(&[1.0, 0.0, 5.0])?,
    ///     &Bivector::zero(3),
    /// )?;
    /// let mut system = System::new(vec![thrown])?;
    /// system.add_forque(Gravity(Vector::from_components(&[0.0, 0.0, -9.81])?))?;
    /// let run = system.record(&mut MotionSplitting::new(), 0.03, &[0.0, 0.25, 1.0])?;
    /// assert_eq!(run.times, [0.0, 0.25, 1.0]);
    /// // The free flight is exact: the height at t = 0.25 is 5t − g t²/2.
    /// let z = run.bodies[0].position[1][2];
    /// assert!((z - (5.0 * 0.25 - 0.5 * 9.81 * 0.0625)).abs() < 1e-12);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn record_with(
        &mut self,
        integrator: &mut dyn MotionIntegrator,
        dt: f64,
        times: &[f64],
        t_end: f64,
        observe: &mut dyn FnMut(usize),
    ) -> Result<SystemTrajectory, DynamicsError> {
        check_sampling(dt, times, t_end)?;
        let mut run = self.empty_trajectory(times.len());
        let mut t = 0.0;
        let mut targets: Vec<(f64, bool)> = times.iter().map(|&s| (s, true)).collect();
        if times.last().is_none_or(|&last| last < t_end) {
            targets.push((t_end, false));
        }
        for (target, is_sample) in targets {
            if t < target {
                // Steps of dt up to the last one, which ends on the target exactly; a
                // remainder below a millionth of dt joins the step before it.
                let mut full = 0;
                while t + (full + 1) as f64 * dt < target - 1e-6 * dt {
                    full += 1;
                }
                let end = t + full as f64 * dt;
                integrator.advance(self, t, dt, full)?;
                integrator.step(self, end, target - end)?;
                run.steps += full + 1;
                t = target;
            }
            if is_sample {
                self.sample(target, &mut run)?;
                observe(run.times.len());
            }
        }
        Ok(run)
    }

    /// A trajectory of this system with no samples yet, room for `count`.
    fn empty_trajectory(&self, count: usize) -> SystemTrajectory {
        let track = |k: usize| BodyTrack {
            name: format!("body{}", k + 1),
            mass: self.bodies()[k].mass(),
            position: Vec::with_capacity(count),
            velocity: Vec::with_capacity(count),
            attitude: Vec::with_capacity(count),
            omega: Vec::with_capacity(count),
        };
        SystemTrajectory {
            dim: self.dim(),
            times: Vec::with_capacity(count),
            bodies: (0..self.bodies().len()).map(track).collect(),
            energy: Vec::with_capacity(count),
            kinetic_energy: Vec::with_capacity(count),
            potential_energy: Vec::with_capacity(count),
            momentum: Vec::with_capacity(count),
            angular_momentum: Vec::with_capacity(count),
            contacts: Vec::with_capacity(count),
            planes: self
                .half_spaces()
                .iter()
                .map(|h| RecordedPlane {
                    normal: h.normal().as_slice().to_vec(),
                    offset: h.offset(),
                    friction: h.friction(),
                    restitution: h.restitution(),
                })
                .collect(),
            steps: 0,
        }
    }

    /// Appends the state at time `t` to `run`.
    fn sample(&self, t: f64, run: &mut SystemTrajectory) -> Result<(), DynamicsError> {
        let energy = self.energy(t);
        let momentum = self.linear_momentum();
        let angular = self.angular_momentum();
        let finite = |x: &[f64]| x.iter().all(|v| v.is_finite());
        if !(energy.is_finite() && finite(momentum.as_slice()) && finite(angular.as_slice())) {
            return Err(DynamicsError::NonFinite { time: t });
        }
        run.times.push(t);
        for (b, track) in self.bodies().iter().zip(run.bodies.iter_mut()) {
            let r = b.attitude().to_matrix();
            track.position.push(b.position().as_slice().to_vec());
            track.velocity.push(b.velocity().as_slice().to_vec());
            track.attitude.push(
                (0..r.nrows())
                    .map(|i| r.row(i).iter().copied().collect())
                    .collect(),
            );
            track.omega.push(b.omega().as_slice().to_vec());
        }
        run.energy.push(energy);
        run.kinetic_energy.push(self.kinetic_energy());
        run.potential_energy.push(self.potential_energy(t));
        run.momentum.push(momentum.as_slice().to_vec());
        run.angular_momentum.push(angular.as_slice().to_vec());
        run.contacts.push(self.sample_contacts());
        Ok(())
    }

    /// The contacts of the last step, one per touching point: the entries of the velocity
    /// solves at the same point of a body (own axes) on the same half-space are summed.
    fn sample_contacts(&self) -> Vec<SampleContact> {
        let mut out: Vec<(&crate::algebra::Vector, SampleContact)> = Vec::new();
        for c in self.contacts() {
            // A point is the same within round-off of the body's size.
            let tolerance = 1e-9 * self.shapes()[c.body].radius();
            let same = out.iter_mut().find(|(own, s)| {
                s.body == c.body
                    && s.half_space == c.half_space
                    && (*own - &c.point).norm() <= tolerance
            });
            if let Some((_, s)) = same {
                s.normal_impulse += c.normal_impulse;
                for (f, g) in s
                    .friction_impulse
                    .iter_mut()
                    .zip(c.friction_impulse.as_slice())
                {
                    *f += g;
                }
                s.slip = c.slip.as_slice().to_vec();
                continue;
            }
            let contact = SampleContact {
                body: c.body,
                half_space: c.half_space,
                point: self.bodies()[c.body]
                    .point_position(&c.point)
                    .as_slice()
                    .to_vec(),
                normal: self.half_spaces()[c.half_space]
                    .normal()
                    .as_slice()
                    .to_vec(),
                normal_impulse: c.normal_impulse,
                friction_impulse: c.friction_impulse.as_slice().to_vec(),
                slip: c.slip.as_slice().to_vec(),
            };
            out.push((&c.point, contact));
        }
        out.into_iter().map(|(_, s)| s).collect()
    }
}

/// Refuses a step or sample times [`System::record_with`] cannot take.
fn check_sampling(dt: f64, times: &[f64], t_end: f64) -> Result<(), DynamicsError> {
    let refuse = |reason| Err(DynamicsError::InvalidSampling { reason });
    if !(dt.is_finite() && dt > 0.0) {
        return refuse("the step must be positive and finite");
    }
    if times.is_empty() {
        return refuse("no sample times");
    }
    if times.iter().any(|t| !t.is_finite() || *t < 0.0) || times.windows(2).any(|w| w[1] <= w[0]) {
        return refuse("sample times must be finite, non-negative and strictly increasing");
    }
    if !t_end.is_finite() || times.last().is_some_and(|&last| last > t_end) {
        return refuse("the end time must be finite and not before the last sample time");
    }
    Ok(())
}

impl SystemTrajectory {
    /// Returns the first sample time at which a recorded number is not finite, if any (a
    /// trajectory read back or edited may hold one; [`System::record`] never returns one).
    pub fn first_non_finite(&self) -> Option<f64> {
        let bad = |x: &[f64]| x.iter().any(|v| !v.is_finite());
        (0..self.times.len())
            .find(|&k| {
                !self.times[k].is_finite()
                    || [&self.energy, &self.kinetic_energy, &self.potential_energy]
                        .iter()
                        .any(|s| s.get(k).is_some_and(|v| !v.is_finite()))
                    || self.momentum.get(k).is_some_and(|v| bad(v))
                    || self.angular_momentum.get(k).is_some_and(|v| bad(v))
                    || self.bodies.iter().any(|b| {
                        [&b.position, &b.velocity, &b.omega]
                            .iter()
                            .any(|s| s.get(k).is_some_and(|v| bad(v)))
                            || b.attitude.get(k).is_some_and(|m| m.iter().any(|r| bad(r)))
                    })
                    || self.contacts.get(k).is_some_and(|cs| {
                        cs.iter().any(|c| {
                            !c.normal_impulse.is_finite()
                                || bad(&c.point)
                                || bad(&c.friction_impulse)
                                || bad(&c.slip)
                        })
                    })
            })
            .map(|k| self.times[k])
    }

    fn check_finite(&self) -> Result<(), DynamicsError> {
        match self.first_non_finite() {
            Some(time) => Err(DynamicsError::NonFinite { time }),
            None => Ok(()),
        }
    }

    /// Returns the CSV files of the run: `(file name, text)` for each body (`<name>.csv`:
    /// t, x1..xN, v1..vN, R11..RNN row-major, w12, …) and `system.csv` (t, energy, p1..pN,
    /// L12, …), every number as [`csv_number`] writes it.
    ///
    /// # Errors
    /// [`DynamicsError::NonFinite`] at the first sample with a number that is not finite.
    pub fn csv_files(&self) -> Result<Vec<(String, String)>, DynamicsError> {
        self.check_finite()?;
        let n = self.dim;
        let planes: Vec<String> = crate::algebra::pairs(n)
            .map(|(i, j)| crate::algebra::plane_name(n, i, j))
            .collect();
        let mut files = Vec::with_capacity(self.bodies.len() + 1);
        for track in &self.bodies {
            let mut header = vec!["t".to_string()];
            header.extend((1..=n).map(|i| format!("x{i}")));
            header.extend((1..=n).map(|i| format!("v{i}")));
            header.extend(attitude_names(n));
            header.extend(planes.iter().map(|p| format!("w{p}")));
            let mut text = header.join(",") + "\n";
            for (k, t) in self.times.iter().enumerate() {
                let row = std::iter::once(*t)
                    .chain(track.position[k].iter().copied())
                    .chain(track.velocity[k].iter().copied())
                    .chain(track.attitude[k].iter().flatten().copied())
                    .chain(track.omega[k].iter().copied());
                text.push_str(&csv_row(row));
            }
            files.push((format!("{}.csv", track.name), text));
        }
        let mut header = vec!["t".to_string(), "energy".to_string()];
        header.extend((1..=n).map(|i| format!("p{i}")));
        header.extend(planes.iter().map(|p| format!("L{p}")));
        let mut text = header.join(",") + "\n";
        for (k, t) in self.times.iter().enumerate() {
            let row = [*t, self.energy[k]]
                .into_iter()
                .chain(self.momentum[k].iter().copied())
                .chain(self.angular_momentum[k].iter().copied());
            text.push_str(&csv_row(row));
        }
        files.push(("system.csv".to_string(), text));
        Ok(files)
    }

    /// Returns the JSON text of the run (one line and a line break): the fields of
    /// [`SystemTrajectory`] as keys, numbers in their shortest round-trip form.
    ///
    /// # Errors
    /// [`DynamicsError::NonFinite`] at the first sample with a number that is not finite
    /// (JSON has no such numbers).
    #[cfg(feature = "serde")]
    pub fn to_json(&self) -> Result<String, DynamicsError> {
        self.check_finite()?;
        // serde_json fails only on maps with non-string keys, which a trajectory has none
        // of, and writes non-finite numbers as null, which the check above refuses.
        let mut text =
            serde_json::to_string(self).map_err(|_| DynamicsError::NonFinite { time: f64::NAN })?;
        text.push('\n');
        Ok(text)
    }
}

/// The names of the attitude entries R_rc, row-major (`R11`, …; `R1_10` from N = 10 on).
fn attitude_names(n: usize) -> Vec<String> {
    let mut names = Vec::with_capacity(n * n);
    for r in 1..=n {
        for c in 1..=n {
            names.push(if n < 10 {
                format!("R{r}{c}")
            } else {
                format!("R{r}_{c}")
            });
        }
    }
    names
}

fn csv_row(values: impl IntoIterator<Item = f64>) -> String {
    let mut row = values
        .into_iter()
        .map(csv_number)
        .collect::<Vec<_>>()
        .join(",");
    row.push('\n');
    row
}

/// Formats a number for CSV and text: the shortest digits that read back as exactly `x`,
/// written plainly for 10⁻⁵ ≤ |x| < 10¹⁶ (and 0) and in exponent form otherwise
/// (`2.220446049250313e-16`, not 32 decimals; `1e300`, not 301 digits), as `ryu` chooses.
/// Rust's `{}` and `{:e}` both print the shortest round-trip digits; only the layout differs.
pub fn csv_number(x: f64) -> String {
    let a = x.abs();
    if a == 0.0 || (1e-5..1e16).contains(&a) || !a.is_finite() {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}
#[cfg(test)]
mod tests {
    use super::csv_number as number;
    use proptest::prelude::*;

    #[test]
    fn numbers_are_short_and_exact() {
        for (x, text) in [
            (f64::EPSILON, "2.220446049250313e-16"),
            (0.1, "0.1"),
            (-0.5, "-0.5"),
            (1.0, "1"),
            (0.0, "0"),
            (1e-5, "0.00001"),
            (9.99e-6, "9.99e-6"),
            (1e16, "1e16"),
            (123456789.125, "123456789.125"),
            (f64::MAX, "1.7976931348623157e308"),
            (f64::MIN_POSITIVE, "2.2250738585072014e-308"),
            (5e-324, "5e-324"),
        ] {
            assert_eq!(number(x), text);
            assert_eq!(text.parse::<f64>().unwrap().to_bits(), x.to_bits());
        }
        assert_eq!(number(f64::NAN), "NaN");
        assert_eq!(number(f64::INFINITY), "inf");
    }

    proptest! {
        /// Every finite f64, whatever its exponent, reads back bit for bit, in at most 17
        /// significant digits and without runs of padding zeros.
        #[test]
        fn every_finite_number_round_trips(bits in any::<u64>()) {
            let x = f64::from_bits(bits);
            prop_assume!(x.is_finite());
            let text = number(x);
            prop_assert_eq!(text.parse::<f64>().unwrap().to_bits(), x.to_bits(), "{}", text);
            let digits: String = text
                .split('e')
                .next()
                .unwrap()
                .chars()
                .filter(char::is_ascii_digit)
                .collect();
            let significant = digits.trim_start_matches('0').len();
            prop_assert!(significant <= 17, "{}", text);
            prop_assert!(text.len() <= 24, "{}", text);
        }
    }
}
