//! `rotorflow render`: the body turning in N-D, projected to 3D, as an HTML animation or an
//! SVG strip of frames.

use super::error::{CliError, CliResult};
use super::motion::{
    InitialArgs, Report, SteppingArgs, finite_number, initial_body, integrate, report_from_states,
};
use super::output::{Progress, check_extension, write_atomic};
use super::spec::{ParsedBody, parse_body};
use clap::{Args, ValueEnum};
use nalgebra::DMatrix;
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::trajectory::even_times;
use rotorflow::viz::html::{Animation, animation_html};
use rotorflow::viz::projection::svg_strip;
use rotorflow::viz::{Projection, Shape};
use std::path::PathBuf;

/// The projection of the left-out axes, on the command line.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProjectionArg {
    /// Perspective from each left-out axis (the paper's figures).
    Perspective,
    /// Drop the left-out coordinates.
    Orthographic,
}

impl From<ProjectionArg> for Projection {
    fn from(p: ProjectionArg) -> Self {
        match p {
            ProjectionArg::Perspective => Projection::Perspective,
            ProjectionArg::Orthographic => Projection::Orthographic,
        }
    }
}

/// Arguments of `render`.
#[derive(Args, Debug, Clone)]
pub struct RenderArgs {
    /// The body, e.g. `tesseract:1,1.2,1.5,2` (the grammar: `rotorflow help bodies`).
    #[arg(long, value_name = "SPEC")]
    pub body: String,
    /// The initial condition.
    #[command(flatten)]
    pub initial: InitialArgs,
    /// End time T of the animation.
    #[arg(long, value_name = "T", value_parser = finite_number, allow_hyphen_values = true)]
    pub t_end: f64,
    /// The output: FILE.html (animation) or FILE.svg (a strip of frames).
    #[arg(long, value_name = "FILE")]
    pub output: PathBuf,
    /// How the axes left out of the 3D view are removed.
    #[arg(long, value_enum, default_value = "perspective")]
    pub projection: ProjectionArg,
    /// The three space axes shown, 1-based (the page lets you change them).
    #[arg(long, value_name = "i,j,k", default_value = "1,2,3")]
    pub axes: String,
    /// Number of frames (default 300 for HTML, 8 for SVG).
    #[arg(long, value_name = "K")]
    pub frames: Option<usize>,
    /// The integrator and its step.
    #[command(flatten)]
    pub stepping: SteppingArgs,
}

/// Parses `--axes i,j,k` (1-based, distinct, at most N) into 0-based axes.
///
/// # Errors
/// [`CliError::Input`] naming the problem and the expected form.
pub fn parse_axes(text: &str, n: usize) -> CliResult<[usize; 3]> {
    let bad = |m: String| {
        CliError::input(format!(
            "--axes `{text}`: {m} (expected three distinct axes i,j,k between 1 and {})",
            n.max(3)
        ))
    };
    let v: Vec<usize> = text
        .split(',')
        .map(|w| {
            w.trim()
                .parse::<usize>()
                .map_err(|_| bad(format!("`{}` is not a whole number", w.trim())))
        })
        .collect::<CliResult<_>>()?;
    if v.len() != 3 {
        return Err(bad(format!("{} axes given", v.len())));
    }
    if v.iter().any(|&a| a == 0 || a > n.max(3)) {
        return Err(bad("an axis is out of range".into()));
    }
    if v[0] == v[1] || v[0] == v[2] || v[1] == v[2] {
        return Err(bad("the axes repeat".into()));
    }
    Ok([v[0] - 1, v[1] - 1, v[2] - 1])
}

/// Runs `render`.
///
/// # Errors
/// [`CliError::Input`] for bad input, [`CliError::Runtime`] if the integration fails.
pub fn run(args: &RenderArgs, quiet: bool) -> CliResult<()> {
    check_extension("--output", &args.output, &["html", "svg"])?;
    let html = args
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("html"));
    let parsed = parse_body(&args.body)?;
    let axes = parse_axes(&args.axes, parsed.dim)?;
    if args.t_end <= 0.0 {
        return Err(CliError::input(format!(
            "--t-end must be positive, got {} (expected --t-end T with T > 0)",
            args.t_end
        )));
    }
    let frames = args.frames.unwrap_or(if html { 300 } else { 8 });
    if !(2..=20_000).contains(&frames) {
        return Err(CliError::input(format!(
            "--frames must be between 2 and 20000, got {frames}"
        )));
    }
    let start = initial_body(&parsed, &args.initial)?;
    let times = even_times(args.t_end, frames);
    let stepping = args.stepping.resolve(&start, args.t_end)?;
    let mut progress = Progress::new(times.len() as u64, quiet, "render");
    let (states, _) = integrate(&start, &Free, stepping, &times, &mut progress)?;
    progress.finish();
    let report = report_from_states(&start, &times, states.into_iter().map(Ok))?;
    let text = picture(&parsed, &report, axes, args.projection.into(), html);
    write_atomic(&args.output, text.as_bytes())
}

/// Returns the HTML page (or SVG strip) of the trajectory `report` of the body `parsed`.
pub fn picture(
    parsed: &ParsedBody,
    report: &Report,
    axes: [usize; 3],
    projection: Projection,
    html: bool,
) -> String {
    let (shape, matrices) = embed_3d(Shape::of_body(parsed), &report.attitude);
    if html {
        animation_html(&Animation {
            title: &parsed.spec,
            shape: &shape,
            times: &report.times,
            matrices: &matrices,
            axes,
            projection,
        })
    } else {
        svg_strip(
            &shape,
            &matrices,
            &report.times,
            axes,
            projection,
            &parsed.spec,
        )
    }
}

/// A 2D body is drawn in the plane z = 0 of 3D space.
fn embed_3d(shape: Shape, matrices: &[DMatrix<f64>]) -> (Shape, Vec<DMatrix<f64>>) {
    if shape.dim >= 3 {
        return (shape, matrices.to_vec());
    }
    let points = shape.points.iter().map(|p| vec![p[0], p[1], 0.0]).collect();
    let shape = Shape {
        dim: 3,
        points,
        ..shape
    };
    let matrices = matrices
        .iter()
        .map(|m| {
            let mut q = DMatrix::identity(3, 3);
            q.view_mut((0, 0), (2, 2)).copy_from(m);
            q
        })
        .collect();
    (shape, matrices)
}
