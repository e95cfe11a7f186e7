//! What `simulate`, `exact`, `render` and `sweep` share: initial conditions, sample times,
//! integrators, torques, and the trajectory report (JSON, CSV, text) built from states.

use super::error::{CliError, CliResult};
use super::output::{Progress, number, plane_names};
use super::spec::ParsedBody;
use clap::{Args, ValueEnum};
use rotorflow::algebra::{Bivector, bivector_len};
use rotorflow::dynamics::report::{ReportError, SampleError, Stepper, sample_states};
use rotorflow::dynamics::torques::{BodyFrame, Free, LinearDamping, SpaceFrame};
use rotorflow::dynamics::{
    Attitude, Dop853, Dopri5, Drift, LiePoissonRk4, Midpoint, MoserVeselov, RigidBody, Rkmk4,
    Splitting, Torque,
};
use rotorflow::inertia::spec::{parse_list, parse_number};

/// Parses a finite number for clap (rejects NaN and infinities).
pub fn finite_number(text: &str) -> Result<f64, String> {
    parse_number(text)
}

/// The initial condition: `--omega W` or `--momentum L`, as bivector components or (N = 3,
/// `--axial`) as axial vectors.
#[derive(Args, Clone, Debug)]
pub struct InitialArgs {
    /// `--omega W` or `--momentum L`.
    #[command(flatten)]
    pub value: InitialValue,
    /// N = 3 only: read --omega, --momentum and the constant torques as axial vectors
    /// x,y,z (right-hand rule) instead of bivector components. The axial vector (x, y, z)
    /// is the bivector x e₂∧e₃ + y e₃∧e₁ + z e₁∧e₂, i.e. the components
    /// (ω₁₂, ω₁₃, ω₂₃) = (z, −y, x), and conversely (x, y, z) = (ω₂₃, −ω₁₃, ω₁₂): a spin
    /// about +z is ω₁₂ > 0. The output keeps the bivector components 12,13,23.
    #[arg(long)]
    pub axial: bool,
}

/// The initial angular velocity or momentum, one of the two.
#[derive(Args, Clone, Debug)]
#[group(required = true, multiple = false)]
pub struct InitialValue {
    /// Initial angular velocity ω: N(N−1)/2 bivector components in lexicographic order
    /// 12,13,…,1N,23,… in the body's own axes, comma-separated (e.g. `--omega=1,0,0.1`).
    /// ω₁₂ > 0 turns e₁ towards e₂.
    #[arg(long, value_name = "W", allow_hyphen_values = true)]
    pub omega: Option<String>,
    /// Initial angular momentum L, in the same order and axes as `--omega`.
    #[arg(long, value_name = "L", allow_hyphen_values = true)]
    pub momentum: Option<String>,
}

/// Returns the bivector components (ω₁₂, ω₁₃, ω₂₃) of the 3D axial vector (x, y, z):
/// x e₂∧e₃ + y e₃∧e₁ + z e₁∧e₂ (right-hand rule, e₁∧e₂ ↔ e₃).
pub fn bivector_from_axial([x, y, z]: [f64; 3]) -> [f64; 3] {
    [z, -y, x]
}

/// Returns the bivector components of a list given on the command line: as they are, or, with
/// `axial` (N = 3 only), read as an axial vector.
///
/// # Errors
/// A one-line message when `axial` is asked for with N ≠ 3 or the list is not 3 numbers.
pub fn components(values: Vec<f64>, n: usize, axial: bool) -> Result<Vec<f64>, String> {
    if !axial {
        return Ok(values);
    }
    if n != 3 {
        return Err(format!(
            "--axial needs N = 3 (the body has N = {n}: give the {} bivector components instead)",
            bivector_len(n)
        ));
    }
    match <[f64; 3]>::try_from(values) {
        Ok(v) => Ok(bivector_from_axial(v).to_vec()),
        Err(v) => Err(format!(
            "{} components given; an axial vector is x,y,z",
            v.len()
        )),
    }
}

/// Returns the rigid body at t = 0 in the identity attitude with the given ω or L.
///
/// # Errors
/// [`CliError::Input`] for a malformed list or the wrong number of components.
pub fn initial_body(parsed: &ParsedBody, initial: &InitialArgs) -> CliResult<RigidBody> {
    let n = parsed.dim;
    let (flag, text) = match (&initial.value.omega, &initial.value.momentum) {
        (Some(w), _) => ("--omega", w),
        (None, Some(l)) => ("--momentum", l),
        (None, None) => {
            return Err(CliError::input(
                "give the initial condition: --omega W or --momentum L",
            ));
        }
    };
    if initial.axial && n != 3 {
        return Err(CliError::input(format!(
            "--axial needs N = 3, the body has N = {n} (give {flag} as {} bivector components)",
            bivector_len(n)
        )));
    }
    let names = plane_names(n);
    let expected = || {
        if initial.axial {
            "3 components x,y,z (axial vector, body's own axes)".to_string()
        } else {
            format!(
                "{} components {} (N = {n}, lexicographic, body's own axes)",
                bivector_len(n),
                names.join(",")
            )
        }
    };
    let values = parse_list(text)
        .map_err(|e| CliError::input(format!("{flag}: {e}; expected {}", expected())))?;
    let values = if initial.axial && values.len() == 3 {
        bivector_from_axial([values[0], values[1], values[2]]).to_vec()
    } else {
        values
    };
    if values.len() != bivector_len(n) {
        return Err(CliError::input(format!(
            "{flag}: {} components given; expected {}",
            values.len(),
            expected()
        )));
    }
    let b = Bivector::from_components(n, &values)
        .map_err(|e| CliError::input(format!("{flag}: {e}")))?;
    let inertia = parsed.inertia.clone();
    let body = if flag == "--omega" {
        RigidBody::from_body_velocity(inertia, Attitude::identity(n), &b)
    } else {
        RigidBody::from_body_momentum(inertia, Attitude::identity(n), &b)
    };
    body.map_err(|e| CliError::input(format!("body `{}`: {e}", parsed.spec)))
}

/// The integrators the command offers.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum IntegratorKind {
    /// Runge–Kutta–Munthe-Kaas, order 4 (any inertia).
    Rk4,
    /// RK4 in Lie–Poisson form, order 4: L moves by the step's rotation, so the Casimirs
    /// and the space-frame momentum hold to round-off (any inertia).
    #[value(alias = "lp-rk4")]
    LiePoissonRk4,
    /// Adaptive Dormand–Prince 5(4) on the group (uses --rtol/--atol).
    Dopri5,
    /// Adaptive Dormand–Prince 8(5,3) on the group (uses --rtol/--atol; tight tolerances).
    Dop853,
    /// Lie–Poisson splitting, Strang (order 2, conserves the Casimirs).
    Strang,
    /// Lie–Poisson splitting, Yoshida (order 4, conserves the Casimirs).
    Yoshida4,
    /// Lie–Poisson splitting, Suzuki's five steps (order 4, a smaller error than yoshida4's
    /// at equal cost; conserves the Casimirs).
    Suzuki4,
    /// Lie–Poisson splitting, Kahan–Li (order 6, conserves the Casimirs).
    #[value(name = "kahan-li6")]
    KahanLi6,
    /// Lie–Poisson splitting, Kahan–Li (order 8, conserves the Casimirs).
    #[value(name = "kahan-li8")]
    KahanLi8,
    /// Implicit midpoint rule (order 2, conserves the energy).
    Midpoint,
    /// Discrete Moser–Veselov top (order 2, conserves the energy, the Casimirs and every
    /// Manakov integral; physical inertia only).
    #[value(alias = "mv")]
    MoserVeselov,
}

impl IntegratorKind {
    /// Returns the name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            IntegratorKind::Rk4 => "rk4",
            IntegratorKind::LiePoissonRk4 => "lie-poisson-rk4",
            IntegratorKind::Dopri5 => "dopri5",
            IntegratorKind::Dop853 => "dop853",
            IntegratorKind::Strang => "strang",
            IntegratorKind::Yoshida4 => "yoshida4",
            IntegratorKind::Suzuki4 => "suzuki4",
            IntegratorKind::KahanLi6 => "kahan-li6",
            IntegratorKind::KahanLi8 => "kahan-li8",
            IntegratorKind::Midpoint => "midpoint",
            IntegratorKind::MoserVeselov => "moser-veselov",
        }
    }
}

/// How to integrate: the integrator and its step or tolerances.
#[derive(Args, Clone, Debug)]
pub struct SteppingArgs {
    /// The integrator.
    #[arg(long, value_enum, default_value = "rk4", value_name = "NAME")]
    pub integrator: IntegratorKind,
    /// Largest step for the fixed-step integrators (default 0.01/max(1, |ω|)).
    #[arg(long, value_name = "H", value_parser = finite_number, allow_hyphen_values = true)]
    pub dt: Option<f64>,
    /// Relative tolerance of dopri5 and dop853 (default 1e-10).
    #[arg(long, value_name = "R", value_parser = finite_number, allow_hyphen_values = true)]
    pub rtol: Option<f64>,
    /// Absolute tolerance of dopri5 and dop853 (default 1e-12).
    #[arg(long, value_name = "A", value_parser = finite_number, allow_hyphen_values = true)]
    pub atol: Option<f64>,
}

impl Default for SteppingArgs {
    fn default() -> Self {
        SteppingArgs {
            integrator: IntegratorKind::Rk4,
            dt: None,
            rtol: None,
            atol: None,
        }
    }
}

/// A validated stepping choice.
#[derive(Clone, Copy, Debug)]
pub enum Stepping {
    /// A fixed-step integrator with largest step `dt`.
    Fixed {
        /// The integrator.
        kind: IntegratorKind,
        /// The largest step.
        dt: f64,
    },
    /// Adaptive Dormand–Prince 5(4).
    Adaptive {
        /// Relative tolerance.
        rtol: f64,
        /// Absolute tolerance.
        atol: f64,
    },
    /// Adaptive Dormand–Prince 8(5,3).
    Adaptive8 {
        /// Relative tolerance.
        rtol: f64,
        /// Absolute tolerance.
        atol: f64,
    },
}

/// The most steps one run may take.
pub const MAX_STEPS: f64 = 2e8;

impl SteppingArgs {
    /// Checks the flags against the integrator and returns the stepping for `body` up to
    /// `t_end`.
    ///
    /// # Errors
    /// [`CliError::Input`] for flags that do not apply, non-positive values, or more than
    /// [`MAX_STEPS`] steps.
    pub fn resolve(&self, body: &RigidBody, t_end: f64) -> CliResult<Stepping> {
        let positive = |flag: &str, v: Option<f64>| -> CliResult<()> {
            match v {
                Some(x) if x <= 0.0 => {
                    Err(CliError::input(format!("{flag} must be positive, got {x}")))
                }
                _ => Ok(()),
            }
        };
        positive("--dt", self.dt)?;
        positive("--rtol", self.rtol)?;
        positive("--atol", self.atol)?;
        if matches!(
            self.integrator,
            IntegratorKind::Dopri5 | IntegratorKind::Dop853
        ) {
            if self.dt.is_some() {
                return Err(CliError::input(format!(
                    "--dt applies to the fixed-step integrators; {} takes --rtol R --atol A",
                    self.integrator.name()
                )));
            }
            let rtol = self.rtol.unwrap_or(1e-10);
            let atol = self.atol.unwrap_or(1e-12);
            if rtol < 1e-15 {
                return Err(CliError::input(format!(
                    "--rtol {rtol} is below what f64 arithmetic can meet (expected R >= 1e-15)"
                )));
            }
            return Ok(if self.integrator == IntegratorKind::Dop853 {
                Stepping::Adaptive8 { rtol, atol }
            } else {
                Stepping::Adaptive { rtol, atol }
            });
        }
        if self.rtol.is_some() || self.atol.is_some() {
            return Err(CliError::input(format!(
                "--rtol/--atol apply to dopri5 and dop853; {} takes --dt H",
                self.integrator.name()
            )));
        }
        let dt = self
            .dt
            .unwrap_or_else(|| 0.01 / body.omega().max_abs().max(1.0));
        if t_end / dt > MAX_STEPS {
            return Err(CliError::input(format!(
                "--t-end {t_end} with --dt {dt} needs more than {MAX_STEPS:e} steps; raise --dt or shorten --t-end"
            )));
        }
        Ok(Stepping::Fixed {
            kind: self.integrator,
            dt,
        })
    }
}

/// The torque grammar, for help and errors.
pub const TORQUE_FORMS: &str = "none | body:T12,T13,... (constant, body's own axes) | space:T12,T13,... (constant, space frame) | damping:C (tau = -C omega)";

/// Parses `--torque SPEC` for `body`; with `axial` (N = 3) the constant torques are axial
/// vectors x,y,z.
///
/// # Errors
/// [`CliError::Input`] naming the problem and the expected forms.
pub fn parse_torque(
    text: Option<&str>,
    body: &RigidBody,
    axial: bool,
) -> CliResult<Box<dyn Torque + Sync>> {
    let n = body.dim();
    let Some(text) = text else {
        return Ok(Box::new(Free));
    };
    let bad =
        |m: String| CliError::input(format!("--torque `{text}`: {m} (expected {TORQUE_FORMS})"));
    let (kind, args) = text.split_once(':').unwrap_or((text, ""));
    let bivector = |args: &str| -> CliResult<Bivector> {
        let v = components(parse_list(args).map_err(bad)?, n, axial).map_err(bad)?;
        if v.len() != bivector_len(n) {
            return Err(bad(format!(
                "{} components given, N = {n} needs {}",
                v.len(),
                bivector_len(n)
            )));
        }
        Bivector::from_components(n, &v).map_err(|e| bad(e.to_string()))
    };
    match kind.trim() {
        "none" if args.is_empty() => Ok(Box::new(Free)),
        // The integrators work in the principal frame: rotate the user's body-axes torque in.
        "body" => Ok(Box::new(BodyFrame(
            body.principal_frame()
                .inverse_rotate_bivector(&bivector(args)?),
        ))),
        "space" => Ok(Box::new(SpaceFrame(bivector(args)?))),
        "damping" => {
            let c = parse_number(args).map_err(bad)?;
            if c < 0.0 {
                return Err(bad(format!("the damping must not be negative, got {c}")));
            }
            Ok(Box::new(LinearDamping(c)))
        }
        other => Err(bad(format!("unknown torque `{other}`"))),
    }
}

pub use rotorflow::dynamics::report::{State, sample_block_len};

/// Integrates `body` under `torque` and returns the state at every time in `times`, with the
/// number of steps taken.
///
/// # Errors
/// [`CliError::Runtime`] when the integrator fails.
pub fn integrate(
    body: &RigidBody,
    torque: &dyn Torque,
    stepping: Stepping,
    times: &[f64],
    progress: &mut Progress,
) -> CliResult<(Vec<State>, usize)> {
    let mut states: Vec<State> = Vec::with_capacity(times.len());
    let steps = integrate_each(body, torque, stepping, times, progress, &mut |s| {
        states.push(s);
        Ok(())
    })?;
    Ok((states, steps))
}

/// [`integrate`] handing each state to `sink` in time order instead of keeping them, and
/// returning the number of steps taken.
///
/// # Errors
/// [`CliError::Runtime`] when the integrator fails or the state stops being finite; the
/// errors of `sink`.
pub fn integrate_each(
    body: &RigidBody,
    torque: &dyn Torque,
    stepping: Stepping,
    times: &[f64],
    progress: &mut Progress,
    sink: &mut dyn FnMut(State) -> CliResult<()>,
) -> CliResult<usize> {
    let fail = |e: rotorflow::dynamics::DynamicsError| {
        use rotorflow::dynamics::DynamicsError as E;
        // The body or --dt the user chose does not suit the integrator: bad input, not a
        // failure of the run.
        match e {
            E::NonPhysicalInertia { .. } | E::NoDiscreteSolution { .. } => {
                CliError::input(format!("integration failed: {e}"))
            }
            _ => CliError::runtime(format!("integration failed: {e}")),
        }
    };
    let mut stepper = match stepping {
        Stepping::Fixed { kind, dt } => Stepper::Fixed {
            integrator: match kind {
                IntegratorKind::Rk4 => Box::new(Rkmk4),
                IntegratorKind::LiePoissonRk4 => Box::new(LiePoissonRk4),
                IntegratorKind::Strang => Box::new(Splitting::strang()),
                IntegratorKind::Yoshida4 => Box::new(Splitting::yoshida4()),
                IntegratorKind::Suzuki4 => Box::new(Splitting::suzuki4()),
                IntegratorKind::KahanLi6 => Box::new(Splitting::kahan_li6()),
                IntegratorKind::KahanLi8 => Box::new(Splitting::kahan_li8()),
                IntegratorKind::Midpoint => Box::new(Midpoint::default()),
                IntegratorKind::MoserVeselov => Box::new(MoserVeselov::new()),
                IntegratorKind::Dopri5 | IntegratorKind::Dop853 => {
                    unreachable!("dopri5 and dop853 are adaptive")
                }
            },
            dt,
        },
        Stepping::Adaptive { rtol, atol } => Stepper::Dopri5(Dopri5::new(rtol, atol)),
        Stepping::Adaptive8 { rtol, atol } => {
            Stepper::Dop853(Box::new(Dop853::new(rtol, atol).map_err(fail)?))
        }
    };
    let mut each_block = |states: Vec<State>| -> CliResult<()> {
        let count = states.len() as u64;
        for s in states {
            sink(s)?;
        }
        progress.advance(count);
        Ok(())
    };
    sample_states(body, torque, &mut stepper, times, &mut each_block).map_err(|e| match e {
        SampleError::Integration(e) => fail(e),
        SampleError::NotFinite => {
            CliError::runtime("integration failed: the state is no longer finite; reduce --dt")
        }
        SampleError::Sink(e) => e,
    })
}

/// The CSV report's header line (with its newline): t, ω_ij, L_ij, energy, the Casimirs and
/// the attitude row-major.
pub fn csv_header(n: usize) -> String {
    let names = plane_names(n);
    let mut header = vec!["t".to_string()];
    header.extend(names.iter().map(|p| format!("omega_{p}")));
    header.extend(names.iter().map(|p| format!("momentum_{p}")));
    header.push("energy".into());
    header.extend((1..=n / 2).map(|k| format!("casimir_{k}")));
    for r in 1..=n {
        header.extend((1..=n).map(|c| format!("R_{r}_{c}")));
    }
    let mut out = header.join(",");
    out.push('\n');
    out
}

/// The text report's header line (with its newline): t, the ω components and the energy.
pub fn text_header(n: usize) -> String {
    let mut out = format!("{:>12}", "t");
    for p in &plane_names(n) {
        out.push_str(&format!(" {:>12}", format!("ω{p}")));
    }
    out.push_str(&format!(" {:>14}\n", "energy"));
    out
}

/// The text report's last line: the largest relative drifts.
pub fn drift_line(d: &Drift) -> String {
    format!(
        "largest relative drift: energy {:.3e}, Casimirs {:.3e}, Manakov integrals {:.3e}, space momentum {:.3e}\n",
        d.energy, d.casimirs, d.manakov, d.space_momentum
    )
}

/// A trajectory as reported: everything in the body's own axes.
pub use rotorflow::dynamics::report::Report;

/// Builds the report from the states (principal frame) at `times` of the motion that starts
/// as `start` ([`Report::from_states`]); `states` may fail (an exact solution that cannot be
/// evaluated).
///
/// # Errors
/// The first error of `states`; [`CliError::Runtime`] when the report cannot be built.
pub fn report_from_states(
    start: &RigidBody,
    times: &[f64],
    states: impl IntoIterator<Item = CliResult<State>>,
) -> CliResult<Report> {
    Report::from_states(start, times, states).map_err(|e| match e {
        ReportError::State(e) => e,
        other => CliError::runtime(other.to_string()),
    })
}

/// The command's text forms of a [`Report`] (its JSON is [`Report::to_json`]).
pub trait ReportText {
    /// Returns the CSV: one row per time with t, ω_ij, L_ij, energy, the Casimirs and the
    /// attitude matrix row-major (R_r_c).
    fn to_csv(&self) -> String;

    /// Returns a readable table of t, ω and energy, and a drift line.
    fn to_text(&self) -> String;
}

impl ReportText for Report {
    fn to_csv(&self) -> String {
        let n = self.dim;
        let mut out = csv_header(n);
        for k in 0..self.times.len() {
            let mut row = vec![number(self.times[k])];
            row.extend(self.omega[k].as_slice().iter().map(|x| number(*x)));
            row.extend(self.momentum[k].as_slice().iter().map(|x| number(*x)));
            row.push(number(self.energy[k]));
            row.extend(self.casimirs[k].iter().map(|x| number(*x)));
            let m = &self.attitude[k];
            for r in 0..n {
                row.extend((0..n).map(|c| number(m[(r, c)])));
            }
            out.push_str(&row.join(","));
            out.push('\n');
        }
        out
    }

    fn to_text(&self) -> String {
        let mut out = text_header(self.dim);
        for k in 0..self.times.len() {
            out.push_str(&format!("{:>12.6}", self.times[k]));
            for x in self.omega[k].as_slice() {
                out.push_str(&format!(" {x:>12.6}"));
            }
            out.push_str(&format!(" {:>14.8}\n", self.energy[k]));
        }
        out.push_str(&drift_line(&self.drift));
        out
    }
}
