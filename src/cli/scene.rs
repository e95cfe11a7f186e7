//! `rotorflow scene FILE`: bodies that move and turn together, read from a TOML scene file
//! by the library's `rotorflow::scene` (which builds, runs and writes it), drawn by
//! `rotorflow::viz`; this file adds the options, the progress bar and atomic writes.

use super::error::{CliError, CliResult};
use super::lists::sample_times;
use super::output::{Progress, check_extension, write_atomic};
use clap::Args;
use rotorflow::scene::{Scene, output, run as scene_run};
use std::path::{Path, PathBuf};

/// Arguments of `scene`.
#[derive(Args, Debug, Clone)]
#[command(after_long_help = SCENE_HELP)]
pub struct SceneArgs {
    /// The scene file (TOML; see the book's chapter "Scene files").
    #[arg(value_name = "FILE")]
    pub file: PathBuf,
    /// Number of evenly spaced samples from 0 to t_end inclusive (K ≥ 2; default 201, or
    /// one per step for runs of fewer than 200 steps).
    #[arg(long, value_name = "K", conflicts_with = "times")]
    pub samples: Option<usize>,
    /// Explicit sample times, comma-separated, strictly increasing, in [0, t_end].
    #[arg(long, value_name = "t1,t2,...", allow_hyphen_values = true)]
    pub times: Option<String>,
    /// Write the samples as JSON to FILE.json (keys dim, times, bodies, energy,
    /// kinetic_energy, potential_energy, momentum, angular_momentum, planes, contacts).
    #[arg(long, value_name = "FILE.json")]
    pub output: Option<PathBuf>,
    /// Write one CSV per body (DIR/<name>.csv) and DIR/system.csv into the folder DIR,
    /// created if needed.
    #[arg(long, value_name = "DIR")]
    pub csv_dir: Option<PathBuf>,
    /// Write the HTML animation of the bodies and planes to FILE.html.
    #[arg(long, value_name = "FILE.html")]
    pub html: Option<PathBuf>,
    /// Plot the energies (kinetic, potential, total), the linear and angular momentum and
    /// the positions over time, in one SVG.
    #[arg(long, value_name = "FILE.svg")]
    pub plot: Option<PathBuf>,
    /// Only check the scene file (every key, the bodies, springs, planes and joints, the
    /// step) and say what it holds; run nothing and write nothing.
    #[arg(long, conflicts_with_all = ["output", "csv_dir", "html", "plot"])]
    pub check: bool,
}

/// The help text after the options: the scene keys in brief.
pub const SCENE_HELP: &str = "\
Scene file keys (TOML; unknown keys are errors):
  dim = N (required), gravity = [g1,...,gN], t_end = T (required), dt = h (required),
  integrator = \"splitting\" (default: symplectic, contact and joints) | \"rk4\" (forces only)
  [[body]]   name, shape (body SPEC: rotorflow help bodies), mass, position, velocity,
             omega (own axes, planes 12,13,...), attitude (N*N numbers row-major or N rows;
             a rotation), friction, restitution (against other bodies: mu = sqrt(mu1 mu2),
             e = max(e1, e2)), fixed (never moves), collide (false: touches nothing),
             contact (the shape it touches with: capsule:H,R | ball:R | box:h1,...,hN |
             ellipsoid:a1,...,aN | simplex:R | cross:R [+margin=M][@x1,...,xN], or a list of
             them: a compound body)
  [[plane]]  normal, offset (the plane normal.x = offset, solid opposite the normal), friction,
             restitution
  [[spring]] body, point (own axes), anchor (a point of space) | other (a body) + other_point,
             stiffness, rest_length, damping
  [[joint]]  body, point, anchor | other + other_point  (ball joint)
  (one [[body]] per body, double brackets; every pair of bodies collides but jointed ones;
  dt < t_end and at most a tenth of each spring's period 2π√(m_eff/k))
Without --output, --csv-dir, --html or --plot a summary is printed: energy drift, momentum
change, final positions. Outputs are written only after a run succeeds, each whole or not at
all.";

/// Returns the sample times of a scene.
///
/// # Errors
/// [`CliError::Input`] for bad `--samples` or `--times`.
pub fn times(args: &SceneArgs, scene: &Scene) -> CliResult<Vec<f64>> {
    if args.samples.is_none() && args.times.is_none() {
        return Ok(scene.default_times());
    }
    sample_times(Some(scene.t_end), args.samples, args.times.as_deref())
        .map_err(|e| CliError::input(e.replace("--t-end", "t_end")))
}

/// Runs `scene`.
///
/// # Errors
/// [`CliError::Input`] for bad input, [`CliError::Runtime`] if the run or a write fails.
pub fn run(args: &SceneArgs, quiet: bool) -> CliResult<()> {
    if let Some(p) = &args.output {
        check_extension("--output", p, &["json"])?;
    }
    if let Some(p) = &args.html {
        check_extension("--html", p, &["html"])?;
    }
    if let Some(p) = &args.plot {
        check_extension("--plot", p, &["svg"])?;
    }
    if let Some(d) = &args.csv_dir
        && d.exists()
        && !d.is_dir()
    {
        return Err(CliError::input(format!(
            "--csv-dir `{}` is a file, expected a folder",
            d.display()
        )));
    }
    let file = args.file.display().to_string();
    let scene = Scene::from_path(&args.file)?;
    let times = times(args, &scene)?;
    let mut system = scene.system()?;
    if args.check {
        println!("{}: ok: {}", file, output::contents(&scene));
        return Ok(());
    }
    let mut progress = Progress::new(times.len() as u64, quiet, "scene");
    let record = scene_run::run(&scene, &mut system, &times, &mut |_| progress.advance(1))?;
    progress.finish();

    // Everything is rendered before the first file is written.
    let json = match &args.output {
        Some(_) => Some(scene.to_json(&record)?),
        None => None,
    };
    let csv = match &args.csv_dir {
        Some(_) => Some(output::csv_files(&record)?),
        None => None,
    };
    let title = args
        .file
        .file_name()
        .map_or(file.clone(), |n| n.to_string_lossy().into_owned());
    let html = args
        .html
        .as_ref()
        .map(|_| scene.animation_html(&record, &title));
    let plot = match &args.plot {
        Some(_) => Some(scene.plot_svg(&record, &title)?),
        None => None,
    };
    if let (Some(p), Some(text)) = (&args.output, &json) {
        write_atomic(p, text.as_bytes())?;
    }
    if let (Some(dir), Some(files)) = (&args.csv_dir, &csv) {
        write_csv_dir(dir, files)?;
    }
    if let (Some(p), Some(text)) = (&args.html, &html) {
        write_atomic(p, text.as_bytes())?;
    }
    if let (Some(p), Some(text)) = (&args.plot, &plot) {
        write_atomic(p, text.as_bytes())?;
    }
    if args.output.is_none() && args.csv_dir.is_none() && args.html.is_none() && args.plot.is_none()
    {
        print!("{}", output::summary(&scene, &record));
    }
    Ok(())
}

/// Creates `dir` if needed and writes each file into it atomically.
fn write_csv_dir(dir: &Path, files: &[(String, String)]) -> CliResult<()> {
    std::fs::create_dir_all(dir).map_err(|e| {
        CliError::runtime(format!("cannot create the folder `{}`: {e}", dir.display()))
    })?;
    for (name, text) in files {
        write_atomic(&dir.join(name), text.as_bytes())?;
    }
    Ok(())
}
