//! `rotorflow exact`: the closed-form solution, in the same shape as `simulate`.
//!
//! The closed forms live in the dynamics layer; this file only parses the command line and
//! formats the result through [`report_from_states`], exactly as `simulate` does.

use super::error::{CliError, CliResult};
use super::motion::{InitialArgs, Report, State, initial_body, report_from_states};
use super::simulate::{ReportArgs, TimeArgs};
use super::spec::parse_body;
use clap::Args;
use rotorflow::dynamics::RigidBody;

/// Arguments of `exact`.
#[derive(Args, Debug, Clone)]
pub struct ExactArgs {
    /// The body (the grammar: `rotorflow help bodies`). A closed form exists for N = 3 (any body), for any N
    /// with at most two distinct second moments Jᵢ, for steady rotations (ω × L = 0) and for a
    /// momentum in the planes of three principal axes (the 3D top inside N-D).
    #[arg(long, value_name = "SPEC")]
    pub body: String,
    /// The initial condition.
    #[command(flatten)]
    pub initial: InitialArgs,
    /// The sample times.
    #[command(flatten)]
    pub time: TimeArgs,
    /// The output (same as `simulate`).
    #[command(flatten)]
    pub report: ReportArgs,
}

/// Runs `exact`.
///
/// # Errors
/// [`CliError::Input`] for bad input or a body without a closed form.
pub fn run(args: &ExactArgs) -> CliResult<()> {
    args.report.check()?;
    let parsed = parse_body(&args.body)?;
    let start = initial_body(&parsed, &args.initial)?;
    let times = args.time.resolve()?;
    let report = exact_report(&start, &times)?;
    args.report
        .write(&report, &format!("{} (closed form)", parsed.spec))
}

/// Returns the closed-form trajectory of `start` at `times` as a [`Report`].
///
/// The closed form ([`RigidBody::exact_solution`]) is a map t ↦ (R(t), L(t)) (attitude
/// principal frame → space, body-frame momentum in the principal frame);
/// [`report_from_states`] turns it into the same output as `simulate`.
///
/// # Errors
/// [`CliError::Input`] when the body has no closed form (the message says why);
/// [`CliError::Runtime`] if the closed form cannot be evaluated at a time.
pub fn exact_report(start: &RigidBody, times: &[f64]) -> CliResult<Report> {
    let solution = start.exact_solution().map_err(|e| match e {
        rotorflow::dynamics::DynamicsError::NoClosedForm { reasons } => {
            let why: Vec<String> = reasons.iter().map(ToString::to_string).collect();
            CliError::input(format!(
                "no closed-form solution for this body: {}",
                why.join("; ")
            ))
        }
        e => CliError::input(format!("no closed-form solution for this body: {e}")),
    })?;
    let state = |t: f64| -> CliResult<State> {
        let fail = |e: rotorflow::dynamics::DynamicsError| {
            CliError::runtime(format!("closed form at t = {t}: {e}"))
        };
        Ok((
            solution.attitude_at(t).map_err(fail)?,
            solution.momentum_at(t).map_err(fail)?,
        ))
    };
    report_from_states(start, times, times.iter().map(|&t| state(t)))
}
