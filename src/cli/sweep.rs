//! `rotorflow sweep`: a grid of simulations in parallel, with the observables of the 3D
//! projection of each run.

use super::error::{CliError, CliResult};
use super::motion::{InitialArgs, Report, SteppingArgs, initial_body, integrate};
use super::output::{Progress, check_extension, emit, number, plane_name, write_atomic};
use super::render::parse_axes;
use super::simulate::TimeArgs;
use super::spec::{GRAMMAR, parse_body, parse_number};
use crate::dynamics::torques::Free;
use crate::viz::plot::{PlotSpec, Series, line_plot, subscript};
use clap::Args;
use rayon::prelude::*;
use std::path::PathBuf;
use std::sync::Mutex;

/// Arguments of `sweep`.
#[derive(Args, Debug, Clone)]
#[command(after_long_help = GRAMMAR)]
pub struct SweepArgs {
    /// The body template: a SPEC in which `{NAME}` is replaced by each value of the parameter
    /// NAME, e.g. `tesseract:1,1,1,{d}`.
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
    /// Write the table as CSV to FILE (standard output otherwise).
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,
    /// Plot the observed frequencies against the first parameter (SVG).
    #[arg(long, value_name = "FILE.svg")]
    pub plot: Option<PathBuf>,
}

/// One parameter of the grid.
#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    /// The name substituted for `{NAME}`.
    pub name: String,
    /// Its values.
    pub values: Vec<f64>,
}

/// Parses `NAME=START:STOP:STEP`.
///
/// # Errors
/// [`CliError::Input`] naming the problem and the expected form.
pub fn parse_param(text: &str) -> CliResult<Param> {
    let bad = |m: String| {
        CliError::input(format!(
            "--param `{text}`: {m} (expected NAME=START:STOP:STEP, e.g. d=1:2:0.25)"
        ))
    };
    let (name, range) = text
        .split_once('=')
        .ok_or_else(|| bad("missing `=`".into()))?;
    let name = name.trim();
    if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Err(bad("the name must be letters, digits or _".into()));
    }
    let parts: Vec<&str> = range.split(':').collect();
    if parts.len() != 3 {
        return Err(bad(format!("{} fields after `=`", parts.len())));
    }
    let v: Vec<f64> = parts
        .iter()
        .map(|p| parse_number(p).map_err(bad))
        .collect::<CliResult<_>>()?;
    let (start, stop, step) = (v[0], v[1], v[2]);
    if step == 0.0 || (stop - start) * step < 0.0 {
        return Err(bad(
            "STEP must be non-zero and lead from START to STOP".into()
        ));
    }
    // Count in floating point first: a tiny STEP makes the quotient huge (or infinite), and
    // a cast to an integer would saturate and overflow (found by the fuzz target times_list).
    let span = ((stop - start) / step * (1.0 + 1e-12) + 1e-9).floor();
    if span.is_nan() || span >= 100_000.0 {
        return Err(bad(format!(
            "{} values are too many (at most 100000)",
            if span < 1e15 {
                format!("{}", span + 1.0)
            } else {
                format!("{:e}", span + 1.0)
            }
        )));
    }
    let count = span as u64 + 1;
    let values = (0..count)
        .map(|k| {
            let x = start + k as f64 * step;
            // Keep 12 significant digits so that 0.1 steps print as 0.3, not 0.30000000000000004.
            let scale = 10f64.powi(11 - x.abs().max(1e-300).log10().floor() as i32);
            if scale.is_finite() {
                (x * scale).round() / scale
            } else {
                x
            }
        })
        .collect();
    Ok(Param {
        name: name.to_string(),
        values,
    })
}

/// Parses `--shard I/N` (1-based) and returns the half-open block of run indices of `total`.
///
/// # Errors
/// [`CliError::Input`] unless 1 ≤ I ≤ N.
pub fn shard_range(text: &str, total: usize) -> CliResult<(usize, usize, usize)> {
    let bad = || {
        CliError::input(format!(
            "--shard `{text}`: expected I/N with whole numbers 1 <= I <= N (e.g. --shard 2/8)"
        ))
    };
    let (i, n) = text.split_once('/').ok_or_else(bad)?;
    let i: usize = i.trim().parse().map_err(|_| bad())?;
    let n: usize = n.trim().parse().map_err(|_| bad())?;
    if n == 0 || i == 0 || i > n {
        return Err(bad());
    }
    Ok((total * (i - 1) / n, total * i / n, i))
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

/// The observables of one run in the 3D projection along three axes.
#[derive(Clone, Debug, PartialEq)]
pub struct Observables {
    /// The three planes (a, b) of the projection, 0-based.
    pub planes: Vec<(usize, usize)>,
    /// Angular frequency of ω_ab about its mean (from its mean crossings; 0 if it does not
    /// oscillate within the run), per plane.
    pub frequency: Vec<f64>,
    /// Half the peak-to-peak range of ω_ab, per plane.
    pub amplitude: Vec<f64>,
    /// Mean of ω_ab, per plane.
    pub mean: Vec<f64>,
    /// Sign changes of the largest of the three components (a flip of the rotation).
    pub flips: usize,
    /// The time of the first flip.
    pub first_flip: Option<f64>,
}

/// Returns the observables of `report` in the 3D projection along `axes`.
pub fn observables(report: &Report, axes: [usize; 3]) -> Observables {
    let n = report.dim;
    let mut sorted = axes;
    sorted.sort_unstable();
    let planes = vec![
        (sorted[0], sorted[1]),
        (sorted[0], sorted[2]),
        (sorted[1], sorted[2]),
    ];
    let series: Vec<Vec<f64>> = planes
        .iter()
        .map(|&(a, b)| {
            let k = crate::algebra::pair_index(n, a, b);
            report.omega.iter().map(|w| w.as_slice()[k]).collect()
        })
        .collect();
    let t = &report.times;
    let mut obs = Observables {
        planes: planes.clone(),
        frequency: Vec::new(),
        amplitude: Vec::new(),
        mean: Vec::new(),
        flips: 0,
        first_flip: None,
    };
    for x in &series {
        let mean = x.iter().sum::<f64>() / x.len().max(1) as f64;
        let (lo, hi) = x
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(*v), b.max(*v))
            });
        let amplitude = 0.5 * (hi - lo);
        let crossings = crossings(t, x, mean, 1e-9 * (amplitude + mean.abs()));
        let frequency = if crossings.len() >= 2 && amplitude > 1e-12 * (1.0 + mean.abs()) {
            let span = crossings[crossings.len() - 1] - crossings[0];
            std::f64::consts::PI * (crossings.len() - 1) as f64 / span
        } else {
            0.0
        };
        obs.frequency.push(if frequency.is_finite() {
            frequency
        } else {
            0.0
        });
        obs.amplitude.push(amplitude);
        obs.mean.push(mean);
    }
    let largest = (0..3)
        .max_by(|&a, &b| {
            let m = |k: usize| series[k].iter().fold(0.0f64, |acc, v| acc.max(v.abs()));
            m(a).total_cmp(&m(b))
        })
        .unwrap_or(0);
    let x = &series[largest];
    let scale = x.iter().fold(0.0f64, |acc, v| acc.max(v.abs()));
    let flips = crossings(t, x, 0.0, 1e-9 * scale);
    obs.flips = flips.len();
    obs.first_flip = flips.first().copied();
    obs
}

/// Returns the (interpolated) times where x crosses `level`, ignoring wiggles within `tol`.
fn crossings(t: &[f64], x: &[f64], level: f64, tol: f64) -> Vec<f64> {
    let mut out = Vec::new();
    let mut last: Option<(f64, f64)> = None; // (time, value − level) of the last clear sample
    for (&ti, &xi) in t.iter().zip(x) {
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

/// One row of the sweep table.
struct Row {
    run: usize,
    values: Vec<f64>,
    observables: Observables,
    energy_drift: f64,
    casimir_drift: f64,
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
    let params: Vec<Param> = args
        .params
        .iter()
        .map(|p| parse_param(p))
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
        Some(s) => shard_range(s, total)?,
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
        let initial = InitialArgs {
            omega: args
                .initial
                .omega
                .as_deref()
                .map(|t| substitute(t, &names, &values))
                .transpose()?,
            momentum: args
                .initial
                .momentum
                .as_deref()
                .map(|t| substitute(t, &names, &values))
                .transpose()?,
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
    let progress = Mutex::new(Progress::new(runs.len() as u64, quiet, "sweep"));
    let rows: Vec<Row> = runs
        .par_iter()
        .map(|(run, values, start, stepping)| {
            let mut silent = Progress::new(0, true, "");
            let (states, _) = integrate(start, &Free, *stepping, &times, &mut silent)
                .map_err(|e| CliError::runtime(format!("run {run}: {e}")))?;
            let report = Report::from_states(start, &times, states.into_iter().map(Ok))?;
            if let Ok(mut p) = progress.lock() {
                p.advance(1);
            }
            Ok(Row {
                run: *run,
                values: values.clone(),
                observables: observables(&report, axes),
                energy_drift: report.drift.energy,
                casimir_drift: report.drift.casimirs,
            })
        })
        .collect::<CliResult<_>>()?;
    if let Ok(p) = progress.into_inner() {
        p.finish();
    }
    let header = shard_index == 1;
    let dim = runs.first().map_or(3, |r| r.2.dim());
    let csv = table_csv(&names, dim, axes, &rows, header);
    if let Some(p) = &args.plot {
        let svg = sweep_plot(&names, runs.first().map_or(3, |r| r.2.dim()), &rows)?;
        write_atomic(p, svg.as_bytes())?;
    }
    emit(args.csv.as_deref(), &csv)
}

fn table_csv(names: &[String], dim: usize, axes: [usize; 3], rows: &[Row], header: bool) -> String {
    let mut out = String::new();
    let mut sorted = axes;
    sorted.sort_unstable();
    if header {
        let mut h = vec!["run".to_string()];
        h.extend(names.iter().cloned());
        let planes = [
            (sorted[0], sorted[1]),
            (sorted[0], sorted[2]),
            (sorted[1], sorted[2]),
        ];
        for (a, b) in planes {
            let p = plane_name(dim, a, b);
            h.push(format!("freq_{p}"));
            h.push(format!("amp_{p}"));
            h.push(format!("mean_{p}"));
        }
        h.extend(
            ["flips", "first_flip", "energy_drift", "casimir_drift"]
                .iter()
                .map(|s| s.to_string()),
        );
        out.push_str(&h.join(","));
        out.push('\n');
    }
    for r in rows {
        let mut row = vec![r.run.to_string()];
        row.extend(r.values.iter().map(|v| number(*v)));
        let o = &r.observables;
        for k in 0..3 {
            row.push(number(o.frequency[k]));
            row.push(number(o.amplitude[k]));
            row.push(number(o.mean[k]));
        }
        row.push(o.flips.to_string());
        row.push(o.first_flip.map(number).unwrap_or_default());
        row.push(number(r.energy_drift));
        row.push(number(r.casimir_drift));
        out.push_str(&row.join(","));
        out.push('\n');
    }
    out
}

fn sweep_plot(names: &[String], dim: usize, rows: &[Row]) -> CliResult<String> {
    let Some(first) = rows.first() else {
        return Err(CliError::input("--plot: this shard has no runs to plot"));
    };
    let mut series: Vec<Series> = first
        .observables
        .planes
        .iter()
        .enumerate()
        .map(|(k, &(a, b))| Series {
            name: format!(
                "observed frequency of ω{}",
                subscript(&plane_name(dim, a, b))
            ),
            points: rows
                .iter()
                .map(|r| (r.values[0], r.observables.frequency[k]))
                .collect(),
        })
        .collect();
    for s in &mut series {
        s.points.sort_by(|p, q| p.0.total_cmp(&q.0));
    }
    line_plot(
        &PlotSpec {
            title: &format!("3D observables against the parameter {}", names[0]),
            x_label: &names[0],
            y_label: "angular frequency (rad per unit time)",
            log_y: false,
            markers: true,
        },
        &series,
    )
    .map_err(|e| CliError::runtime(format!("cannot draw the plot: {e}")))
}
