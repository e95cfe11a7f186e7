//! `rotorflow sweep`: a grid of simulations in parallel, with the observables of the 3D
//! projection of each run. Free 3D and 4D bodies under `rk4` or `strang` step in groups on
//! the fixed-size batch kernels ([`batch`]); every other run integrates alone.

mod batch;
mod resume;
mod table;

use super::error::{CliError, CliResult};
use super::lists::{Param, parse_param, shard_range};
use super::motion::{
    InitialArgs, InitialValue, Report, Stepping, SteppingArgs, initial_body, integrate,
    report_from_states,
};
use super::output::{Progress, check_extension, emit, number, write_atomic};
use super::render::parse_axes;
use super::simulate::TimeArgs;
use super::spec::parse_body;
use clap::Args;
use rayon::prelude::*;
use resume::{ProgressLog, progress_path, read_progress, sweep_fingerprint};
use rotorflow::dynamics::RigidBody;
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::trajectory::{projected_observables, projection_planes};
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Mutex;
use table::{Row, sweep_plot, table_csv};

/// A run of the grid, checked and ready: index, parameter values, body, stepping.
type GridRun = (usize, Vec<f64>, RigidBody, Stepping);

/// Arguments of `sweep`.
#[derive(Args, Debug, Clone)]
pub struct SweepArgs {
    /// The body template: a SPEC in which `{NAME}` is replaced by each value of the parameter
    /// NAME, e.g. `tesseract:1,1,1,{d}` (the grammar: `rotorflow help bodies`).
    #[arg(long, value_name = "TEMPLATE")]
    pub body: String,
    /// A parameter and its values START, START+STEP, … up to STOP inclusive; repeat for a
    /// grid (the first parameter varies slowest).
    #[arg(
        long = "param",
        value_name = "NAME=START:STOP:STEP",
        required = true,
        allow_hyphen_values = true
    )]
    pub params: Vec<String>,
    /// The initial condition (templates too: `{NAME}` is replaced).
    #[command(flatten)]
    pub initial: InitialArgs,
    /// The sample times of every run.
    #[command(flatten)]
    pub time: TimeArgs,
    /// The integrator and its step.
    #[command(flatten)]
    pub stepping: SteppingArgs,
    /// The space axes of the observed 3D projection, 1-based.
    #[arg(long, value_name = "i,j,k", default_value = "1,2,3")]
    pub axes: String,
    /// Run only shard I of N (1 ≤ I ≤ N): a contiguous block of the grid, so that the outputs
    /// of shards 1 … N concatenated in order are the whole sweep (only shard 1 writes the
    /// header).
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,
    /// Write the table (CSV, the only format of a sweep) to FILE (standard output otherwise). FILE appears whole or
    /// not at all; while the sweep runs, each finished run is also appended to the progress
    /// file FILE.partial, which `--resume` reads and which is removed once FILE is written.
    ///
    /// The columns, one row per run in grid order: run (0-based index in the grid); one
    /// column per --param, named by it (its value); then for each plane ab of the 3D
    /// projection (the three planes of --axes, lexicographic, e.g. 12, 13, 23): freq_ab (the
    /// angular frequency of ω_ab about its mean, from its mean crossings; 0 if it does not
    /// oscillate), amp_ab (half its peak-to-peak range), mean_ab (its mean); then
    /// manakov_drift (the largest relative drift of the Manakov integrals over the run, 0
    /// for a body without them: a non-physical inertia map or a gyrostat), flips (sign
    /// changes of the largest of the three components), first_flip (the time of the first,
    /// empty if none), energy_drift and casimir_drift (the largest relative drifts of the
    /// energy and of the Casimirs over the run). Numbers are in shortest round-trip form.
    #[arg(long, value_name = "FILE")]
    pub output: Option<PathBuf>,
    /// Continue an interrupted sweep: the runs recorded in FILE.partial (of `--output FILE`) are
    /// not run again, and FILE comes out byte for byte as an uninterrupted run writes it.
    /// The progress file carries a fingerprint of the sweep (body, grid, initial condition,
    /// times, integrator, axes, shard); one from a different sweep is refused. Without a
    /// progress file every run is done. (Without `--resume` an old progress file is
    /// replaced.)
    #[arg(long, requires = "output")]
    pub resume: bool,
    /// Plot the observed frequencies against the first parameter (SVG).
    #[arg(long, value_name = "FILE.svg")]
    pub plot: Option<PathBuf>,
}

/// Replaces every `{NAME}` in `template`.
///
/// # Errors
/// [`CliError::Input`] for a `{…}` that names no parameter.
pub fn substitute(template: &str, names: &[String], values: &[f64]) -> CliResult<String> {
    let mut out = template.to_string();
    for (name, v) in names.iter().zip(values) {
        out = out.replace(&format!("{{{name}}}"), &number(*v));
    }
    if let (Some(a), Some(b)) = (out.find('{'), out.find('}'))
        && a < b
    {
        return Err(CliError::input(format!(
            "template `{template}`: `{}` names no --param (expected {{NAME}} for a --param NAME=START:STOP:STEP)",
            &out[a..=b]
        )));
    }
    Ok(out)
}

/// Runs `sweep`.
///
/// # Errors
/// [`CliError::Input`] for bad input (checked for every grid point before any run),
/// [`CliError::Runtime`] if a run fails.
pub fn run(args: &SweepArgs, quiet: bool) -> CliResult<()> {
    if let Some(p) = &args.plot {
        check_extension("--plot", p, &["svg"])?;
    }
    // The table is CSV whatever the name, except a name that says it is something else.
    if let Some(p) = &args.output
        && p.extension().is_some_and(|e| {
            ["json", "svg", "html"].contains(&e.to_string_lossy().to_ascii_lowercase().as_str())
        })
    {
        return Err(CliError::input(format!(
            "--output `{}`: sweep writes its table as CSV; expected a .csv (or .txt) name",
            p.display()
        )));
    }
    let params: Vec<Param> = args
        .params
        .iter()
        .map(|p| parse_param(p).map_err(CliError::input))
        .collect::<CliResult<_>>()?;
    let names: Vec<String> = params.iter().map(|p| p.name.clone()).collect();
    if let Some(dup) = names
        .iter()
        .enumerate()
        .find(|(i, n)| names[..*i].contains(n))
    {
        return Err(CliError::input(format!(
            "--param `{}` is given twice",
            dup.1
        )));
    }
    let total = params
        .iter()
        .try_fold(1usize, |acc, p| acc.checked_mul(p.values.len()))
        .filter(|t| *t <= 10_000_000)
        .ok_or_else(|| CliError::input("the grid has more than 10000000 runs"))?;
    let (begin, end, shard_index) = match &args.shard {
        Some(s) => shard_range(s, total).map_err(CliError::input)?,
        None => (0, total, 1),
    };
    let times = args.time.resolve()?;
    // Check every grid point of this shard before running anything.
    let mut runs = Vec::with_capacity(end - begin);
    for run in begin..end {
        let mut rest = run;
        let mut values = vec![0.0; params.len()];
        for (k, p) in params.iter().enumerate().rev() {
            values[k] = p.values[rest % p.values.len()];
            rest /= p.values.len();
        }
        let label = || {
            names
                .iter()
                .zip(&values)
                .map(|(n, v)| format!("{n}={v}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let in_run = |e: CliError| match e {
            CliError::Input(m) => CliError::input(format!("run {run} ({}): {m}", label())),
            other => other,
        };
        let body = parse_body(&substitute(&args.body, &names, &values)?).map_err(in_run)?;
        let value = InitialValue {
            omega: args
                .initial
                .value
                .omega
                .as_deref()
                .map(|t| substitute(t, &names, &values))
                .transpose()?,
            momentum: args
                .initial
                .value
                .momentum
                .as_deref()
                .map(|t| substitute(t, &names, &values))
                .transpose()?,
        };
        let initial = InitialArgs {
            value,
            axial: args.initial.axial,
        };
        let start = initial_body(&body, &initial).map_err(in_run)?;
        let stepping = args
            .stepping
            .resolve(&start, *times.last().unwrap_or(&0.0))
            .map_err(in_run)?;
        runs.push((run, values, start, stepping));
    }
    let axes = parse_axes(&args.axes, runs.first().map_or(3, |r| r.2.dim()))?;
    if let Some(r) = runs
        .iter()
        .find(|r| r.2.dim() < 3 || axes.iter().any(|&a| a >= r.2.dim()))
    {
        return Err(CliError::input(format!(
            "run {}: the body has N = {}, too few for --axes {}",
            r.0,
            r.2.dim(),
            args.axes
        )));
    }
    let planes = projection_planes(axes);
    let fingerprint = sweep_fingerprint(args, &names, &times, axes, (begin, end, total), &runs);
    let log_path = args.output.as_deref().map(progress_path);
    let mut finished: BTreeMap<usize, Row> = BTreeMap::new();
    if args.resume
        && let Some(path) = &log_path
    {
        finished = read_progress(path, &fingerprint, &runs, planes)?;
        if !quiet {
            eprintln!(
                "rotorflow: resuming: {} of {} runs read from {}",
                finished.len(),
                runs.len(),
                path.display()
            );
        }
    }
    // (Re)start the progress file with the finished rows (dropping a torn last line), then
    // append each run as it finishes: one complete line per write.
    let log = match &log_path {
        Some(path) => Some(Mutex::new(ProgressLog::start(
            path,
            &fingerprint,
            finished.values(),
        )?)),
        None => None,
    };
    let todo: Vec<_> = runs
        .iter()
        .filter(|r| !finished.contains_key(&r.0))
        .collect();
    let progress = Mutex::new(Progress::new(runs.len() as u64, quiet, "sweep"));
    if let Ok(mut p) = progress.lock() {
        p.advance(finished.len() as u64);
    }
    let finish = |run: &GridRun, report: Report| -> CliResult<Row> {
        let row = Row {
            run: run.0,
            values: run.1.clone(),
            observables: observables(&report, axes)?,
            manakov_drift: report.drift.manakov,
            energy_drift: report.drift.energy,
            casimir_drift: report.drift.casimirs,
        };
        if let Some(log) = &log {
            log.lock()
                .map_err(|_| CliError::runtime("the progress file is unusable"))?
                .append(&row)?;
        }
        if let Ok(mut p) = progress.lock() {
            p.advance(1);
        }
        Ok(row)
    };
    // Free 3D and 4D bodies under rk4 or strang step together on the batch kernels, in
    // groups that share the step; every other run integrates alone.
    let (groups, single) = batch_groups(todo);
    let grouped: Vec<Vec<Row>> = groups
        .par_iter()
        .map(|(kernel, group)| {
            let samples = batch::integrate_group(group, *kernel, &times)?;
            group
                .iter()
                .zip(samples)
                .map(|(run, s)| finish(run, s.report(&run.2, &times)?))
                .collect()
        })
        .collect::<CliResult<_>>()?;
    let alone: Vec<Row> = single
        .par_iter()
        .map(|run| {
            let mut silent = Progress::new(0, true, "");
            let (states, _) = integrate(&run.2, &Free, run.3, &times, &mut silent)
                .map_err(|e| CliError::runtime(format!("run {}: {e}", run.0)))?;
            finish(
                run,
                report_from_states(&run.2, &times, states.into_iter().map(Ok))?,
            )
        })
        .collect::<CliResult<_>>()?;
    let new_rows = grouped.into_iter().flatten().chain(alone);
    if let Ok(p) = progress.into_inner() {
        p.finish();
    }
    drop(log);
    let mut rows: Vec<Row> = finished.into_values().chain(new_rows).collect();
    rows.sort_by_key(|r| r.run);
    let header = shard_index == 1;
    let dim = runs.first().map_or(3, |r| r.2.dim());
    let csv = table_csv(&names, dim, axes, &rows, header);
    if let Some(p) = &args.plot {
        let svg = sweep_plot(&names, runs.first().map_or(3, |r| r.2.dim()), &rows)?;
        write_atomic(p, svg.as_bytes())?;
    }
    emit(args.output.as_deref(), &csv)?;
    if let Some(path) = &log_path {
        match std::fs::remove_file(path) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                return Err(CliError::runtime(format!(
                    "cannot remove the progress file `{}`: {e}",
                    path.display()
                )));
            }
            _ => {}
        }
    }
    Ok(())
}

/// Splits the runs into groups for the batch kernels (at most [`batch::GROUP`] runs that
/// share a kernel and its step) and the runs that integrate alone.
fn batch_groups(runs: Vec<&GridRun>) -> (Vec<(batch::Kernel, Vec<&GridRun>)>, Vec<&GridRun>) {
    let mut groups: Vec<(batch::Kernel, Vec<&GridRun>)> = Vec::new();
    let mut single = Vec::new();
    // The group still filling for each kernel.
    let mut open: std::collections::HashMap<_, usize> = std::collections::HashMap::new();
    for run in runs {
        let Some(kernel) = batch::kernel(run) else {
            single.push(run);
            continue;
        };
        match open.get_mut(&kernel.key()) {
            Some(g) if groups[*g].1.len() < batch::GROUP => groups[*g].1.push(run),
            Some(g) => {
                *g = groups.len();
                groups.push((kernel, vec![run]));
            }
            None => {
                open.insert(kernel.key(), groups.len());
                groups.push((kernel, vec![run]));
            }
        }
    }
    (groups, single)
}

/// Returns the observables of `report` in the 3D projection along `axes` (0-based).
///
/// # Errors
/// [`CliError::Input`] if the axes are not three distinct axes of the body.
pub fn observables(
    report: &Report,
    axes: [usize; 3],
) -> CliResult<rotorflow::dynamics::trajectory::ProjectedObservables> {
    projected_observables(&report.times, &report.omega, axes)
        .map_err(|e| CliError::input(format!("--axes: {e}")))
}
