//! The `rotorflow` command (feature `cli`, private to the binary): one file per subcommand,
//! the body grammar's help text in [`spec`] (the parser is the library's
//! `rotorflow::inertia::spec`), atomic writes, JSON and CSV in [`output`]. The pictures are
//! the library's `rotorflow::viz`, scene files its `rotorflow::scene`.
//!
//! | subcommand | what it does |
//! |---|---|
//! | `demo` | runs the paper's cases and writes plots, animations, a sweep and `summary.md` |
//! | `inertia` | mass properties, plane moments, the inertia matrix, the paper's tensors |
//! | `simulate` | integrates Euler's equations and reports ω, L, energy, Casimirs, attitude |
//! | `exact` | the closed-form solution, in the same shape as `simulate` |
//! | `render` | an HTML animation or an SVG strip of the body turning in N-D, projected to 3D |
//! | `sweep` | a grid of simulations in parallel, with the observables of the 3D projection |
//! | `scene` | bodies that move and turn together, from a TOML scene file: JSON, CSV, animation |
//! | `help` | the help of a subcommand, or `help bodies`: the body grammar |
//!
//! Bad input (a malformed body SPEC, wrong component counts, non-finite numbers, an unknown
//! integrator, times not increasing, a singular body) ends with one line on standard error
//! naming the problem and the expected form, exit code 2 and no output file. A run that fails
//! after good input exits with code 1.

pub mod demo;
pub mod error;
pub mod exact;
pub mod inertia;
pub mod lists;
pub mod motion;
pub mod output;
pub mod render;
pub mod scene;
pub mod simulate;
pub mod spec;
pub mod stream;
pub mod sweep;

use error::CliResult;

use clap::{Parser, Subcommand};
use std::io::Write as _;
use std::process::ExitCode;

/// Geometric algebra for rotating rigid bodies in N dimensions.
#[derive(Parser, Debug)]
#[command(
    name = "rotorflow",
    version,
    about = "Rotating rigid bodies in N dimensions: inertia, Euler's equations, closed forms, pictures.",
    long_about = "Rotating rigid bodies in N dimensions: inertia, Euler's equations as rotor flows, \
closed-form solutions, plots and animations of the 3D projections.\n\n\
Bivector components (ω, L, torques) are given and printed in lexicographic order of the planes \
12,13,...,1N,23,..., 1-based, in the body's own axes; ω₁₂ > 0 turns e₁ towards e₂. In 3D the \
axial vector (x, y, z) of the right-hand rule is the bivector x e₂∧e₃ + y e₃∧e₁ + z e₁∧e₂: \
(ω₁₂, ω₁₃, ω₂₃) = (z, −y, x), and `--axial` reads --omega, --momentum and constant torques \
as x,y,z.\n\n\
Quote body SPECs on a shell command line (`--body 'cuboid:1,2,3+mass=5'`).",
    after_long_help = spec::GRAMMAR_POINTER,
    disable_help_subcommand = true,
)]
pub struct Cli {
    /// No progress bar.
    #[arg(long, short, global = true)]
    pub quiet: bool,
    /// The subcommand.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Run the paper's cases and the moving-body scenes; write plots, animations, a sweep and summary.md.
    Demo(demo::DemoArgs),
    /// Mass properties, plane moments, inertia matrix and the paper's tensors of a body.
    Inertia(inertia::InertiaArgs),
    /// Integrate Euler's equations; report ω, L, energy, Casimirs, attitude and drifts.
    Simulate(simulate::SimulateArgs),
    /// The closed-form solution (N = 3; two distinct second moments Jᵢ; steady or 3D motions).
    Exact(exact::ExactArgs),
    /// Animate the body turning in N-D, projected to 3D (HTML), or a strip of frames (SVG).
    Render(render::RenderArgs),
    /// Run a grid of simulations in parallel and report the observables of the 3D projection.
    Sweep(sweep::SweepArgs),
    /// Bodies that move and turn together, from a TOML scene file: gravity, springs, planes
    /// and ball joints; JSON, CSV per body and an HTML animation.
    Scene(scene::SceneArgs),
    /// Print the help of a subcommand, or of a topic: `bodies` (the body SPEC grammar).
    Help(HelpArgs),
}

/// Arguments of `help`.
#[derive(clap::Args, Debug, Clone)]
pub struct HelpArgs {
    /// `bodies` (the grammar of `--body SPEC` and of a scene's `shape`) or a subcommand;
    /// without it, the help of `rotorflow`.
    #[arg(value_name = "TOPIC")]
    pub topic: Option<String>,
}

/// The help topics that are not subcommands.
pub const HELP_TOPICS: [&str; 1] = ["bodies"];

/// Prints the help of `topic`: the body grammar, a subcommand's `--help`, or `rotorflow`'s.
///
/// # Errors
/// [`error::CliError::Input`] for a topic that is neither a topic nor a subcommand.
pub fn help(topic: Option<&str>) -> CliResult<()> {
    let mut argv = vec!["rotorflow"];
    match topic {
        Some("bodies") => {
            // A closed pipe (`| head`) is not an error worth a message.
            let _ = writeln!(std::io::stdout(), "{}", spec::GRAMMAR);
            return Ok(());
        }
        Some(name) if name != "help" && command().find_subcommand(name).is_some() => {
            argv.push(name);
        }
        Some(other) => {
            let subcommands: Vec<String> = command()
                .get_subcommands()
                .map(|c| c.get_name().to_string())
                .filter(|n| n != "help")
                .collect();
            return Err(error::CliError::input(format!(
                "help: no topic `{other}` (expected {} or a subcommand: {})",
                HELP_TOPICS.join(", "),
                subcommands.join(", ")
            )));
        }
        None => {}
    }
    argv.push("--help");
    if let Err(e) = command().try_get_matches_from(argv) {
        // A closed pipe (`| head`) is not an error worth a message.
        let _ = e.print();
    }
    Ok(())
}

/// Returns the clap description of the `rotorflow` command: every subcommand with its flags
/// and help texts (the body grammar is [`spec::GRAMMAR`], printed by `rotorflow help bodies`). Render it with clap (e.g.
/// `command().render_long_help()`, or `try_get_matches_from(["rotorflow", "simulate",
/// "--help"])` for a subcommand's help exactly as the binary prints it); the book's
/// command-line reference is generated this way (`examples/book_cli_help.rs`).
#[allow(dead_code)] // used by the book's reference generator, which includes this module
pub fn command() -> clap::Command {
    <Cli as clap::CommandFactory>::command()
}

/// Parses the command line, runs the command and returns the exit code: 0 on success, 2 for
/// bad input (one line on standard error), 1 when a run fails.
pub fn run() -> ExitCode {
    // Never show a panic backtrace to a user: one line, exit code 101.
    std::panic::set_hook(Box::new(|info| {
        let message = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown".into());
        eprintln!("rotorflow: internal error: {message} (please report it)");
    }));
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(err) => return clap_error(err),
    };
    match dispatch(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("rotorflow: error: {err}");
            ExitCode::from(err.exit_code())
        }
    }
}

/// Runs a parsed command line.
///
/// # Errors
/// The command's [`CliError`].
pub fn dispatch(cli: Cli) -> CliResult<()> {
    let quiet = cli.quiet;
    match cli.command {
        Command::Demo(a) => demo::run(&a, quiet),
        Command::Inertia(a) => inertia::run(&a),
        Command::Simulate(a) => simulate::run(&a, quiet),
        Command::Exact(a) => exact::run(&a),
        Command::Render(a) => render::run(&a, quiet),
        Command::Sweep(a) => sweep::run(&a, quiet),
        Command::Scene(a) => scene::run(&a, quiet),
        Command::Help(a) => help(a.topic.as_deref()),
    }
}

/// Prints help and version as clap does; squeezes a usage error into one line.
fn clap_error(err: clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    match err.kind() {
        ErrorKind::DisplayHelp
        | ErrorKind::DisplayVersion
        | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = err.print();
            if err.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
                ExitCode::from(2)
            } else {
                ExitCode::SUCCESS
            }
        }
        _ => {
            let text = err.render().to_string();
            let parts: Vec<&str> = text
                .lines()
                .map(str::trim)
                .filter(|l| !l.is_empty() && !l.starts_with("For more information"))
                .collect();
            let line = parts.join("; ").replace("error: ", "").replace(":; ", ": ");
            eprintln!("rotorflow: error: {line}; see --help");
            ExitCode::from(2)
        }
    }
}
