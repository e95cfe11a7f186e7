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
use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};
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
    /// Write the table as CSV to FILE (standard output otherwise). FILE appears whole or
    /// not at all; while the sweep runs, each finished run is also appended to the progress
    /// file FILE.partial, which `--resume` reads and which is removed once FILE is written.
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,
    /// Continue an interrupted sweep: the runs recorded in FILE.partial (of `--csv FILE`) are
    /// not run again, and FILE comes out byte for byte as an uninterrupted run writes it.
    /// The progress file carries a fingerprint of the sweep (body, grid, initial condition,
    /// times, integrator, axes, shard); one from a different sweep is refused. Without a
    /// progress file every run is done. (Without `--resume` an old progress file is
    /// replaced.)
    #[arg(long, requires = "csv")]
    pub resume: bool,
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
    // In 128 bits: total · I overflows a usize for huge I/N (found by the fuzz target
    // times_list); the quotients are at most `total`.
    let at = |k: usize| (total as u128 * k as u128 / n as u128) as usize;
    Ok((at(i - 1), at(i), i))
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
    let planes = projection_planes(axes);
    let fingerprint = sweep_fingerprint(args, &names, &times, axes, (begin, end, total), &runs);
    let log_path = args.csv.as_deref().map(progress_path);
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
    let new_rows: Vec<Row> = todo
        .par_iter()
        .map(|(run, values, start, stepping)| {
            let mut silent = Progress::new(0, true, "");
            let (states, _) = integrate(start, &Free, *stepping, &times, &mut silent)
                .map_err(|e| CliError::runtime(format!("run {run}: {e}")))?;
            let report = Report::from_states(start, &times, states.into_iter().map(Ok))?;
            let row = Row {
                run: *run,
                values: values.clone(),
                observables: observables(&report, axes),
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
        })
        .collect::<CliResult<_>>()?;
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
    emit(args.csv.as_deref(), &csv)?;
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

/// The three planes (a, b) of the projection along `axes`, 0-based, in the table's order.
fn projection_planes(axes: [usize; 3]) -> [(usize, usize); 3] {
    let mut sorted = axes;
    sorted.sort_unstable();
    [
        (sorted[0], sorted[1]),
        (sorted[0], sorted[2]),
        (sorted[1], sorted[2]),
    ]
}

/// Returns the progress file of `--csv FILE`: FILE.partial beside it.
pub fn progress_path(csv: &Path) -> PathBuf {
    let mut name = csv.as_os_str().to_owned();
    name.push(".partial");
    PathBuf::from(name)
}

/// The first line of a progress file: what it is, and the fingerprint of the sweep.
fn progress_header(fingerprint: &str) -> String {
    format!(
        "# rotorflow {} sweep progress, fingerprint {fingerprint}: finished rows in completion order; delete this file to start over",
        env!("CARGO_PKG_VERSION")
    )
}

/// FNV-1a, 64 bits: a hash that is the same on every platform and every Rust version.
struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }

    /// Hashes `bytes` and a separator that no UTF-8 text contains.
    fn field(&mut self, bytes: &[u8]) {
        for &b in bytes.iter().chain(&[0xff]) {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0100_0000_01b3);
        }
    }
}

/// A run of the grid, checked and ready: index, parameter values, body, stepping.
type GridRun = (
    usize,
    Vec<f64>,
    crate::dynamics::RigidBody,
    super::motion::Stepping,
);

/// Returns the fingerprint of everything that determines the rows of this sweep: the
/// template, each run's parameter values, initial state and stepping, the sample times, the
/// axes, the shard and the version.
fn sweep_fingerprint(
    args: &SweepArgs,
    names: &[String],
    times: &[f64],
    axes: [usize; 3],
    (begin, end, total): (usize, usize, usize),
    runs: &[GridRun],
) -> String {
    let mut h = Fnv::new();
    h.field(env!("CARGO_PKG_VERSION").as_bytes());
    h.field(args.body.as_bytes());
    h.field(format!("{:?}", args.initial).as_bytes());
    for name in names {
        h.field(name.as_bytes());
    }
    h.field(format!("{axes:?} {begin} {end} {total} {}", times.len()).as_bytes());
    let mut bits = Vec::with_capacity(8 * times.len());
    for t in times {
        bits.extend_from_slice(&t.to_bits().to_le_bytes());
    }
    h.field(&bits);
    for (run, values, start, stepping) in runs {
        h.field(
            format!(
                "{run} {values:?} {:?} {:?} {stepping:?}",
                start.momentum().as_slice(),
                start.inertia().to_matrix().as_slice()
            )
            .as_bytes(),
        );
    }
    format!("{:016x}", h.0)
}

/// The progress file of a running sweep, appended one finished row at a time.
struct ProgressLog {
    file: std::fs::File,
    path: PathBuf,
}

impl ProgressLog {
    /// Writes the header and the rows already finished (atomically), then opens the file
    /// for appending.
    fn start<'a>(
        path: &Path,
        fingerprint: &str,
        finished: impl Iterator<Item = &'a Row>,
    ) -> CliResult<Self> {
        let mut text = progress_header(fingerprint);
        text.push('\n');
        for row in finished {
            text.push_str(&row_line(row));
            text.push('\n');
        }
        write_atomic(path, text.as_bytes())?;
        let file = std::fs::OpenOptions::new()
            .append(true)
            .open(path)
            .map_err(|e| CliError::runtime(format!("cannot open `{}`: {e}", path.display())))?;
        Ok(ProgressLog {
            file,
            path: path.to_path_buf(),
        })
    }

    /// Appends one complete line (a single write) and hands it to the operating system.
    fn append(&mut self, row: &Row) -> CliResult<()> {
        let mut line = row_line(row);
        line.push('\n');
        self.file
            .write_all(line.as_bytes())
            .and_then(|()| self.file.flush())
            .map_err(|e| CliError::runtime(format!("cannot write `{}`: {e}", self.path.display())))
    }
}

/// Reads the finished rows of a progress file for `--resume`. A missing file gives no rows;
/// a torn last line (no newline: the sweep was killed while writing it) is ignored.
///
/// # Errors
/// [`CliError::Input`] if the file belongs to a different sweep (fingerprint) or a complete
/// line is not a row of this one.
fn read_progress(
    path: &Path,
    fingerprint: &str,
    runs: &[GridRun],
    planes: [(usize, usize); 3],
) -> CliResult<BTreeMap<usize, Row>> {
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(BTreeMap::new()),
        Err(e) => {
            return Err(CliError::runtime(format!(
                "cannot read `{}`: {e}",
                path.display()
            )));
        }
    };
    let refuse = |why: String| {
        CliError::input(format!(
            "--resume: `{}` {why}; delete it to start over, or give the same sweep",
            path.display()
        ))
    };
    // Only complete lines count: cut after the last newline.
    let complete = bytes
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(&bytes[..0], |k| &bytes[..=k]);
    let text = std::str::from_utf8(complete)
        .map_err(|_| refuse("is not a progress file of rotorflow sweep".into()))?;
    let mut lines = text.lines();
    if lines.next() != Some(progress_header(fingerprint).as_str()) {
        return Err(refuse(
            "was written by a different sweep (body, grid, initial condition, times, integrator, axes or shard differ)"
                .into(),
        ));
    }
    let index: BTreeMap<usize, &Vec<f64>> = runs.iter().map(|r| (r.0, &r.1)).collect();
    let mut rows = BTreeMap::new();
    for (k, line) in lines.enumerate() {
        let row = parse_row(line, planes)
            .filter(|row| index.get(&row.run).is_some_and(|v| **v == row.values))
            .ok_or_else(|| refuse(format!("line {} is not a row of this sweep", k + 2)))?;
        rows.insert(row.run, row);
    }
    Ok(rows)
}

/// Parses a table row written by [`row_line`]; `None` unless writing it back gives the same
/// text (numbers are written as their shortest round-trip form, so this is exact).
fn parse_row(line: &str, planes: [(usize, usize); 3]) -> Option<Row> {
    let fields: Vec<&str> = line.split(',').collect();
    let n_values = fields.len().checked_sub(1 + 9 + 4)?;
    let float = |s: &str| s.parse::<f64>().ok();
    let at = |k: usize| float(fields[1 + n_values + k]);
    let tail = &fields[1 + n_values + 9..];
    let row = Row {
        run: fields[0].parse().ok()?,
        values: fields[1..=n_values]
            .iter()
            .map(|s| float(s))
            .collect::<Option<_>>()?,
        observables: Observables {
            planes: planes.to_vec(),
            frequency: vec![at(0)?, at(3)?, at(6)?],
            amplitude: vec![at(1)?, at(4)?, at(7)?],
            mean: vec![at(2)?, at(5)?, at(8)?],
            flips: tail[0].parse().ok()?,
            first_flip: if tail[1].is_empty() {
                None
            } else {
                Some(float(tail[1])?)
            },
        },
        energy_drift: float(tail[2])?,
        casimir_drift: float(tail[3])?,
    };
    (row_line(&row) == line).then_some(row)
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
        out.push_str(&row_line(r));
        out.push('\n');
    }
    out
}

/// One row of the table, without the newline.
fn row_line(r: &Row) -> String {
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
    row.join(",")
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
