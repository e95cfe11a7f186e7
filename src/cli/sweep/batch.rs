//! Free 3D and 4D bodies under `rk4` or `strang` step on the fixed-size batch kernels
//! ([`FreeBody3::step_all_rk4`] and its siblings): the runs of a group that share the step
//! advance in lockstep, one kernel call per step for the whole group, and each run keeps its
//! samples as fixed-size values until its report. The kernels' momentum is bit for bit the
//! run-time integrators' (`tests/dynamics/fixed.rs`), so the rows are those of the run-time
//! path, which every other run takes.

use super::super::error::{CliError, CliResult};
use super::super::motion::{
    IntegratorKind, Report, State, Stepping, report_from_states, sample_block_len,
};
use super::GridRun;
use rotorflow::algebra::{Bivector3, Bivector4, Rotor3, Rotor4};
use rotorflow::dynamics::{Attitude, FreeBody3, FreeBody4, equal_steps};

/// Runs per group: enough to fill the kernels, few enough that the groups spread over the
/// threads and their samples stay small (one group's samples: 112 bytes per run and time).
pub(super) const GROUP: usize = 8;

/// How a group steps: the integrator and the largest step, which every run of the group
/// shares.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Kernel {
    dim: usize,
    strang: bool,
    dt: f64,
}

impl Kernel {
    /// The kernel as a key: equal keys step alike.
    pub(super) fn key(self) -> (usize, bool, u64) {
        (self.dim, self.strang, self.dt.to_bits())
    }
}

/// The batch kernel `run` can take, or `None` (any other integrator, dimension or inertia).
pub(super) fn kernel(run: &GridRun) -> Option<Kernel> {
    let Stepping::Fixed { kind, dt } = run.3 else {
        return None;
    };
    let strang = match kind {
        IntegratorKind::Rk4 => false,
        IntegratorKind::Strang => true,
        _ => return None,
    };
    let fits = match run.2.dim() {
        3 => FreeBody3::from_rigid_body(&run.2).is_ok(),
        4 => FreeBody4::from_rigid_body(&run.2).is_ok(),
        _ => false,
    };
    fits.then_some(Kernel {
        dim: run.2.dim(),
        strang,
        dt,
    })
}

/// The steps before each sample time: (count, h), those of `motion::integrate_each`
/// (blocks of samples with times relative to the block's start) and of
/// `dynamics::simulate` within a block ([`equal_steps`]), so that the states are the
/// run-time path's.
fn step_plan(times: &[f64], dt: f64) -> Vec<(usize, f64)> {
    let mut plan = Vec::with_capacity(times.len());
    let mut t0 = 0.0;
    for block in times.chunks(sample_block_len(times.len())) {
        let mut t = 0.0;
        for &time in block {
            let target = time - t0;
            plan.push(equal_steps(target - t, dt));
            t = target;
        }
        t0 = *block.last().expect("chunks are not empty");
    }
    plan
}

/// The bodies of a group on the fixed-size types.
enum Swarm {
    D3(Vec<FreeBody3>),
    D4(Vec<FreeBody4>),
}

/// A run's samples: the attitude's and the momentum's fixed-size values.
pub(super) enum Samples {
    D3(Vec<(Rotor3, Bivector3)>),
    D4(Vec<(Rotor4, Bivector4)>),
}

impl Samples {
    fn finite_last(&self) -> bool {
        match self {
            Samples::D3(s) => s.last().is_none_or(|(r, l)| {
                r.to_quaternion()
                    .iter()
                    .chain(&l.to_array())
                    .all(|x| x.is_finite())
            }),
            Samples::D4(s) => s.last().is_none_or(|(r, l)| {
                let (p, m) = r.to_quaternion_pair();
                p.iter()
                    .chain(&m)
                    .chain(&l.to_array())
                    .all(|x| x.is_finite())
            }),
        }
    }

    /// The run's report (from `start`, sampled at `times`): the run-time states, converted
    /// one at a time as the report reads them.
    pub(super) fn report(
        self,
        start: &rotorflow::dynamics::RigidBody,
        times: &[f64],
    ) -> CliResult<Report> {
        report_from_states(start, times, self.states())
    }

    fn states(self) -> Box<dyn Iterator<Item = CliResult<State>>> {
        match self {
            Samples::D3(s) => Box::new(
                s.into_iter()
                    .map(|(r, l)| Ok((Attitude::from(r.to_rotor()), l.to_bivector()))),
            ),
            Samples::D4(s) => Box::new(
                s.into_iter()
                    .map(|(r, l)| Ok((Attitude::from(r.to_rotor()), l.to_bivector()))),
            ),
        }
    }
}

/// Integrates a group of runs that share `kernel` and returns each run's samples, in the
/// group's order (the reports are made one at a time from them: a report holds much more
/// per sample).
///
/// # Errors
/// [`CliError::Runtime`] naming the first run whose state stops being finite.
pub(super) fn integrate_group(
    group: &[&GridRun],
    kernel: Kernel,
    times: &[f64],
) -> CliResult<Vec<Samples>> {
    let convert = |e: rotorflow::dynamics::DynamicsError| CliError::runtime(e.to_string());
    let mut swarm = match kernel.dim {
        3 => Swarm::D3(
            group
                .iter()
                .map(|r| FreeBody3::from_rigid_body(&r.2))
                .collect::<Result<_, _>>()
                .map_err(convert)?,
        ),
        _ => Swarm::D4(
            group
                .iter()
                .map(|r| FreeBody4::from_rigid_body(&r.2))
                .collect::<Result<_, _>>()
                .map_err(convert)?,
        ),
    };
    let mut samples: Vec<Samples> = group
        .iter()
        .map(|_| match kernel.dim {
            3 => Samples::D3(Vec::with_capacity(times.len())),
            _ => Samples::D4(Vec::with_capacity(times.len())),
        })
        .collect();
    for (count, h) in step_plan(times, kernel.dt) {
        for _ in 0..count {
            match (&mut swarm, kernel.strang) {
                (Swarm::D3(b), false) => FreeBody3::step_all_rk4(b, h),
                (Swarm::D3(b), true) => FreeBody3::step_all_strang(b, h),
                (Swarm::D4(b), false) => FreeBody4::step_all_rk4(b, h),
                (Swarm::D4(b), true) => FreeBody4::step_all_strang(b, h),
            }
        }
        for (k, s) in samples.iter_mut().enumerate() {
            match (&swarm, s) {
                (Swarm::D3(b), Samples::D3(s)) => s.push((b[k].attitude(), b[k].momentum())),
                (Swarm::D4(b), Samples::D4(s)) => s.push((b[k].attitude(), b[k].momentum())),
                _ => unreachable!("one dimension per group"),
            }
        }
        if let Some(k) = samples.iter().position(|s| !s.finite_last()) {
            return Err(CliError::runtime(format!(
                "run {}: integration failed: the state is no longer finite; reduce --dt",
                group[k].0
            )));
        }
    }
    Ok(samples)
}

#[cfg(test)]
mod tests {
    use super::super::super::motion::integrate;
    use super::super::super::output::Progress;
    use super::*;
    use rotorflow::algebra::Bivector;
    use rotorflow::dynamics::RigidBody;
    use rotorflow::dynamics::torques::Free;
    use rotorflow::inertia::InertiaMap;

    fn grid_run(run: usize, n: usize, kind: IntegratorKind, dt: f64) -> GridRun {
        let moments: Vec<f64> = (0..n)
            .map(|i| 0.6 + 0.35 * i as f64 + 0.01 * run as f64)
            .collect();
        let omega: Vec<f64> = (0..n * (n - 1) / 2)
            .map(|k| (0.9 * k as f64 + 0.4 * run as f64).sin())
            .collect();
        let body = RigidBody::from_body_velocity(
            InertiaMap::from_principal_second_moments(&moments).unwrap(),
            Attitude::identity(n),
            &Bivector::from_components(n, &omega).unwrap(),
        )
        .unwrap();
        (run, vec![run as f64], body, Stepping::Fixed { kind, dt })
    }

    /// The batch kernels give the run-time path's rows: the same ω at every sample and the
    /// same drifts, bit for bit, over several sampling blocks and uneven sample spacing.
    #[test]
    fn batch_reports_are_the_run_time_reports() {
        // 301 samples: three blocks of at most 100 samples each; uneven spans.
        let times: Vec<f64> = (1..=301)
            .map(|k| 0.05 * k as f64 + 1e-3 * (k % 7) as f64)
            .collect();
        let mut checked = 0;
        for n in [3, 4] {
            for kind in [IntegratorKind::Rk4, IntegratorKind::Strang] {
                let runs: Vec<GridRun> = (0..5).map(|r| grid_run(r, n, kind, 0.013)).collect();
                let group: Vec<&GridRun> = runs.iter().collect();
                let k = kernel(&runs[0]).expect("a free 3D/4D body under rk4 or strang");
                assert!(runs.iter().all(|r| kernel(r) == Some(k)));
                let batch = integrate_group(&group, k, &times).unwrap();
                for (run, samples) in runs.iter().zip(batch) {
                    let fast = samples.report(&run.2, &times).unwrap();
                    let (states, _) = integrate(
                        &run.2,
                        &Free,
                        run.3,
                        &times,
                        &mut Progress::new(0, true, ""),
                    )
                    .unwrap();
                    let slow =
                        report_from_states(&run.2, &times, states.into_iter().map(Ok)).unwrap();
                    assert_eq!(fast.omega, slow.omega, "N = {n}, {kind:?}, run {}", run.0);
                    assert_eq!(fast.drift.energy, slow.drift.energy);
                    assert_eq!(fast.drift.casimirs, slow.drift.casimirs);
                    assert_eq!(fast.drift.manakov, slow.drift.manakov);
                    checked += 1;
                }
            }
        }
        assert_eq!(checked, 20);
    }

    /// Other integrators, dimensions and inertia maps take the run-time path.
    #[test]
    fn only_free_3d_and_4d_bodies_under_rk4_or_strang_are_batched() {
        assert!(kernel(&grid_run(0, 3, IntegratorKind::Rk4, 0.01)).is_some());
        assert!(kernel(&grid_run(0, 4, IntegratorKind::Strang, 0.01)).is_some());
        assert!(kernel(&grid_run(0, 5, IntegratorKind::Rk4, 0.01)).is_none());
        assert!(kernel(&grid_run(0, 4, IntegratorKind::Yoshida4, 0.01)).is_none());
        assert!(kernel(&grid_run(0, 3, IntegratorKind::MoserVeselov, 0.01)).is_none());
        let adaptive = (
            0,
            vec![],
            grid_run(0, 3, IntegratorKind::Rk4, 0.01).2,
            Stepping::Adaptive {
                rtol: 1e-8,
                atol: 1e-10,
            },
        );
        assert!(kernel(&adaptive).is_none());
    }
}
