//! `rotorflow simulate`: integrate Euler's equations and report the trajectory.

use super::error::{CliError, CliResult};
use super::lists::sample_times;
use super::motion::{
    InitialArgs, Report, ReportText, SteppingArgs, finite_number, initial_body, integrate_each,
    parse_torque,
};
use super::output::{
    Format, Progress, check_extension, emit, plane_names, report_format, to_json_text, write_atomic,
};
use super::spec::parse_body;
use super::stream::ReportStream;
use clap::Args;
use rotorflow::algebra::Bivector;
use rotorflow::viz::plot::{PlotSpec, Series, line_plot, subscript};
use std::path::{Path, PathBuf};

/// Sample times: `--t-end T` with `--samples K`, or `--times t1,t2,…`.
#[derive(Args, Debug, Clone)]
pub struct TimeArgs {
    /// End time T (the samples run from 0 to T).
    #[arg(long, value_name = "T", value_parser = finite_number, allow_hyphen_values = true)]
    pub t_end: Option<f64>,
    /// Number of evenly spaced samples from 0 to T inclusive (K ≥ 2).
    #[arg(long, value_name = "K")]
    pub samples: Option<usize>,
    /// Explicit sample times, comma-separated, strictly increasing, ≥ 0.
    #[arg(long, value_name = "t1,t2,...", allow_hyphen_values = true)]
    pub times: Option<String>,
}

impl TimeArgs {
    /// Returns the sample times.
    ///
    /// # Errors
    /// As [`sample_times`].
    pub fn resolve(&self) -> CliResult<Vec<f64>> {
        sample_times(self.t_end, self.samples, self.times.as_deref()).map_err(CliError::input)
    }
}

/// How a trajectory is written: `--json`, `--csv` or a text table; to FILE or standard
/// output; and an optional plot of ω.
#[derive(Args, Debug, Clone)]
pub struct ReportArgs {
    /// Print JSON with keys dim, times, omega, momentum, energy, casimirs, attitude, drift.
    #[arg(long, conflicts_with = "csv")]
    pub json: bool,
    /// Print CSV: t, ω, L, energy, Casimirs, attitude matrix (row-major).
    #[arg(long)]
    pub csv: bool,
    /// Write to FILE (whole or not at all) instead of standard output. Without --json or
    /// --csv the format follows the file name: .json → JSON, .csv → CSV, .txt, .md or
    /// anything else → the text table; a flag that contradicts the name is refused.
    #[arg(long, value_name = "FILE")]
    pub output: Option<PathBuf>,
    /// Also draw the ω components over time as an SVG plot.
    #[arg(long, value_name = "FILE.svg")]
    pub plot: Option<PathBuf>,
}

impl ReportArgs {
    /// Checks the output file names before any work is done.
    ///
    /// # Errors
    /// [`CliError::Input`] for a plot file that is not `.svg`, or an output file name that
    /// contradicts `--json`/`--csv`.
    pub fn check(&self) -> CliResult<()> {
        if let Some(p) = &self.plot {
            check_extension("--plot", p, &["svg"])?;
        }
        self.format()?;
        Ok(())
    }

    /// Returns the format of the report (see [`report_format`]).
    ///
    /// # Errors
    /// As [`report_format`].
    pub fn format(&self) -> CliResult<Format> {
        let flag = if self.json {
            Some(Format::Json)
        } else if self.csv {
            Some(Format::Csv)
        } else {
            None
        };
        report_format(self.output.as_deref(), flag, true)
    }

    /// Writes the report and the plot.
    ///
    /// # Errors
    /// [`CliError::Runtime`] when a file cannot be written.
    pub fn write(&self, report: &Report, title: &str) -> CliResult<()> {
        let text = match self.format()? {
            Format::Json => to_json_text(&report.to_json(), false)?,
            Format::Csv => report.to_csv(),
            Format::Text => report.to_text(),
        };
        if let Some(p) = &self.plot {
            write_omega_plot(p, report, title)?;
        }
        emit(self.output.as_deref(), &text)
    }
}

/// Arguments of `simulate`.
#[derive(Args, Debug, Clone)]
pub struct SimulateArgs {
    /// The body, e.g. `ellipsoid:1,1.5,2,2.5` (the grammar: `rotorflow help bodies`).
    #[arg(long, value_name = "SPEC")]
    pub body: String,
    /// The initial condition.
    #[command(flatten)]
    pub initial: InitialArgs,
    /// External torque: none | body:T12,... | space:T12,... | damping:C (with --axial,
    /// body:x,y,z and space:x,y,z are axial vectors).
    #[arg(long, value_name = "SPEC", allow_hyphen_values = true)]
    pub torque: Option<String>,
    /// The sample times.
    #[command(flatten)]
    pub time: TimeArgs,
    /// The integrator and its step.
    #[command(flatten)]
    pub stepping: SteppingArgs,
    /// The output.
    #[command(flatten)]
    pub report: ReportArgs,
}

/// Runs `simulate`.
///
/// # Errors
/// [`CliError::Input`] for bad input, [`CliError::Runtime`] if the integration fails.
pub fn run(args: &SimulateArgs, quiet: bool) -> CliResult<()> {
    args.report.check()?;
    let parsed = parse_body(&args.body)?;
    let start = initial_body(&parsed, &args.initial)?;
    let times = args.time.resolve()?;
    let torque = parse_torque(args.torque.as_deref(), &start, args.initial.axial)?;
    let t_end = times.last().copied().unwrap_or(0.0);
    let stepping = args.stepping.resolve(&start, t_end)?;
    let mut progress = Progress::new(times.len() as u64, quiet, "simulate");
    // Samples go to the output as they come (memory flat in their number); ω is kept only
    // for a plot.
    let format = args.report.format()?;
    let plot = args.report.plot.as_deref();
    let mut stream = ReportStream::new(
        &start,
        &times,
        format,
        args.report.output.as_deref(),
        plot.is_some(),
    )?;
    integrate_each(
        &start,
        torque.as_ref(),
        stepping,
        &times,
        &mut progress,
        &mut |s| stream.push(s),
    )?;
    progress.finish();
    let finished = stream.finish()?;
    // The plot first, then the report: each file appears whole or not at all.
    if let (Some(path), Some((times, omega))) = (plot, &finished.omega) {
        let svg = omega_series_plot(start.dim(), times, omega, &parsed.spec)?;
        write_atomic(path, svg.as_bytes())?;
    }
    finished.publish()
}

/// Writes the plot of the ω components of `report` to `path`.
///
/// # Errors
/// [`CliError::Runtime`] when the plot cannot be drawn or written.
pub fn write_omega_plot(path: &Path, report: &Report, title: &str) -> CliResult<()> {
    let svg = omega_plot(report, title)?;
    write_atomic(path, svg.as_bytes())
}

/// Returns the SVG plot of the ω components of `report`.
///
/// # Errors
/// [`CliError::Runtime`] when the plot cannot be drawn.
pub fn omega_plot(report: &Report, title: &str) -> CliResult<String> {
    omega_series_plot(report.dim, &report.times, &report.omega, title)
}

/// Returns the SVG plot of the ω components `omega` (dimension `dim`) at `times`.
///
/// # Errors
/// [`CliError::Runtime`] when the plot cannot be drawn.
pub fn omega_series_plot(
    dim: usize,
    times: &[f64],
    omega: &[Bivector],
    title: &str,
) -> CliResult<String> {
    let series: Vec<Series> = plane_names(dim)
        .iter()
        .enumerate()
        .map(|(k, p)| Series {
            name: format!("ω{}", subscript(p)),
            points: times
                .iter()
                .zip(omega)
                .map(|(t, w)| (*t, w.as_slice()[k]))
                .collect(),
        })
        .collect();
    line_plot(
        &PlotSpec {
            title: &format!("angular velocity (body's own axes): {title}"),
            x_label: "time t",
            y_label: "ω_ij (rad per unit time)",
            log_y: false,
            markers: false,
        },
        &series,
    )
    .map_err(|e| CliError::runtime(format!("cannot draw the plot: {e}")))
}

/// Returns the SVG plot of the relative drift of the energy and the Casimirs over time.
///
/// # Errors
/// [`CliError::Runtime`] when the plot cannot be drawn.
pub fn drift_plot(report: &Report, title: &str) -> CliResult<String> {
    let series = vec![
        Series {
            name: "|ΔT|/T (energy)".into(),
            points: report
                .times
                .iter()
                .copied()
                .zip(report.energy_drift.iter().copied())
                .collect(),
        },
        Series {
            name: "max_k |Δc_k|/|L|^2k (Casimirs)".into(),
            points: report
                .times
                .iter()
                .copied()
                .zip(report.casimir_drift.iter().copied())
                .collect(),
        },
    ];
    line_plot(
        &PlotSpec {
            title: &format!("drift of the invariants: {title}"),
            x_label: "time t",
            y_label: "relative drift",
            log_y: true,
            markers: false,
        },
        &series,
    )
    .map_err(|e| CliError::runtime(format!("cannot draw the plot: {e}")))
}
