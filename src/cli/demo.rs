//! `rotorflow demo [--output DIR]`: the paper's cases, end to end.
//!
//! Writes into DIR (default `out/`):
//! - `omega_<case>.svg` and `drift_<case>.svg`: ω components and the drift of the invariants
//!   over time, for every case;
//! - `<case>.html`: an animation of the 3D projection, for every case;
//! - `tesseract_frames.svg`: a strip of frames of the tumbling tesseract;
//! - `sweep.svg` and `sweep.csv`: an observed 3D frequency against the hypothetical 4D
//!   parameter κ (section 7.2), with the paper's eq. (119) frequency beside it;
//! - `<scene>.html` and `energy_<scene>.svg`: five scene files of `scenes/` (a tesseract on
//!   a spring, a 4D ball sliding into rolling, a 5-cell bouncing down a slope, Newton's cradle
//!   in 4D, three stacked 4D hypercubes), each animated and its energy and momenta plotted
//!   over time;
//! - `summary.md`: a table of the cases (numeric vs exact, drifts, timings), of the
//!   integrators on the tesseract, and of the scenes with their measured figures.

use super::error::{CliError, CliResult};
use super::exact::exact_report;
use super::motion::{
    InitialArgs, InitialValue, IntegratorKind, Report, Stepping, initial_body, integrate,
    report_from_states,
};
use super::output::{Progress, number, plane_names, write_atomic};
use super::render::picture;
use super::simulate::{drift_plot, omega_plot};
use super::spec::parse_body;
use super::sweep::observables;
use clap::Args;
use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;
use rotorflow::dynamics::motion::ContactShape;
use rotorflow::dynamics::motion::SystemTrajectory as Record;
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::trajectory::even_times;
use rotorflow::scene::Scene;
use rotorflow::viz::Projection;
use rotorflow::viz::plot::{PlotSpec, Series, line_plot, subscript};
use rotorflow::viz::scene::up_axis;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::Instant;

/// Arguments of `demo`.
#[derive(Args, Debug, Clone)]
pub struct DemoArgs {
    /// The folder to write into (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub output_dir: PathBuf,
}

/// One case of the demo.
struct Case {
    name: &'static str,
    title: &'static str,
    spec: &'static str,
    omega: &'static str,
    t_end: f64,
    samples: usize,
    /// The 3D projection of the animation (0-based axes).
    axes: [usize; 3],
}

const CASES: [Case; 8] = [
    Case {
        name: "tesseract",
        title: "4D tesseract of unit point masses (§4.1)",
        spec: "tesseract:1,1.2,1.5,2",
        omega: "1,0.05,0.02,0.03,0.04,0.7",
        t_end: 60.0,
        samples: 1201,
        axes: [0, 1, 2],
    },
    Case {
        name: "pentachoron",
        title: "4D 5-cell, eq. (73) points (§4.2)",
        spec: "pentachoron:1,1.2,1.5,2",
        omega: "0.8,0.1,0.05,0.3,0.02,0.6",
        t_end: 60.0,
        samples: 1201,
        axes: [0, 1, 2],
    },
    Case {
        name: "cuboid",
        title: "4D solid cuboid (§5)",
        spec: "cuboid:1,1.2,1.5,2",
        omega: "1,0.05,0.02,0.03,0.04,0.7",
        t_end: 60.0,
        samples: 1201,
        axes: [0, 1, 2],
    },
    Case {
        name: "ellipsoid",
        title: "4D solid ellipsoid (§6)",
        spec: "ellipsoid:1,1.2,1.5,2",
        omega: "1,0.05,0.02,0.03,0.04,0.7",
        t_end: 60.0,
        samples: 1201,
        axes: [0, 1, 2],
    },
    Case {
        name: "section_7_1",
        title: "§7.1 all moments equal: ω constant",
        spec: "tesseract:1,1,1,1",
        omega: "0.3,0.4,0.2,0.5,0.1,0.3",
        t_end: 40.0,
        samples: 801,
        axes: [0, 1, 2],
    },
    Case {
        name: "section_7_2",
        title: "§7.2 three equal moments and κ = 1.5",
        spec: "tesseract:1,1,1,1.5",
        omega: "0.3,0.4,0.2,0.5,0.1,0.3",
        t_end: 40.0,
        samples: 801,
        axes: [1, 2, 3],
    },
    Case {
        name: "section_7_3",
        title: "§7.3 two pairs of equal moments, κ = 1.5",
        spec: "tesseract:1,1,1.5,1.5",
        omega: "1,0.2,0.3,0.1,0.25,0.6",
        t_end: 40.0,
        samples: 801,
        axes: [0, 1, 2],
    },
    Case {
        name: "top_3d",
        title: "3D asymmetric top near its intermediate axis",
        spec: "ellipsoid:1,2,3",
        omega: "0.01,1,0.01",
        t_end: 60.0,
        samples: 1201,
        axes: [0, 1, 2],
    },
];

/// The step of the demo's integrations (Yoshida 4 for the cases).
const DT: f64 = 0.005;

/// Every file the demo writes, relative to DIR.
pub fn promised_files() -> Vec<String> {
    let mut files: Vec<String> = CASES
        .iter()
        .flat_map(|c| {
            [
                format!("omega_{}.svg", c.name),
                format!("drift_{}.svg", c.name),
                format!("{}.html", c.name),
            ]
        })
        .collect();
    files.extend(
        SCENES
            .iter()
            .flat_map(|s| [format!("{}.html", s.name), format!("energy_{}.svg", s.name)]),
    );
    files.extend(
        [
            "tesseract_frames.svg",
            "sweep.svg",
            "sweep.csv",
            "summary.md",
        ]
        .iter()
        .map(|s| s.to_string()),
    );
    files
}

struct CaseResult {
    report: Report,
    steps: usize,
    seconds: f64,
    /// max |ω − ω_exact| over the samples, or why there is no closed form.
    exact: Result<f64, String>,
}

/// Runs `demo`.
///
/// # Errors
/// [`CliError::Runtime`] if DIR cannot be written or a run fails.
pub fn run(args: &DemoArgs, quiet: bool) -> CliResult<()> {
    let clock = Instant::now();
    let dir = &args.output_dir;
    std::fs::create_dir_all(dir)
        .map_err(|e| CliError::runtime(format!("cannot create `{}`: {e}", dir.display())))?;
    let progress = Mutex::new(Progress::new(
        (CASES.len() + SCENES.len() + 2) as u64,
        quiet,
        "demo",
    ));
    let step = || {
        if let Ok(mut p) = progress.lock() {
            p.advance(1);
        }
    };
    // Runs `run` on every item in parallel, counting each one done.
    fn each<T: Sync, R: Send>(
        items: &[T],
        run: impl Fn(&T) -> CliResult<R> + Sync,
        done: &(impl Fn() + Sync),
    ) -> CliResult<Vec<R>> {
        items
            .par_iter()
            .map(|item| {
                let r = run(item);
                done();
                r
            })
            .collect()
    }
    let (results, scenes) = rayon::join(
        || each(&CASES, |case| run_case(case, dir), &step),
        || each(&SCENES, |s| run_scene(s, dir), &step),
    );
    let (results, scenes) = (results?, scenes?);
    let integrators = integrator_table()?;
    step();
    let sweep_text = sweep(dir)?;
    step();
    if let Ok(p) = progress.into_inner() {
        p.finish();
    }
    // Reasons why a case has no exact comparison, as numbered footnotes.
    let mut reasons: Vec<String> = Vec::new();
    let mut md = String::new();
    let _ = writeln!(md, "# rotorflow demo\n");
    let _ = writeln!(
        md,
        "The paper's cases, integrated with the Yoshida-4 Lie–Poisson splitting (step {DT}). ω is \
         given in the body's own axes, components in lexicographic order {}. Drifts are the \
         largest relative drift from t = 0 over all samples.\n",
        plane_names(4).join(", ")
    );
    let _ = writeln!(
        md,
        "| case | body | N | ω(0) | T | steps | energy drift | Casimir drift | time (s) | numeric vs exact: max abs(Δω) | files |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|---|---|---|---|---|");
    for (case, r) in CASES.iter().zip(&results) {
        let exact = match &r.exact {
            Ok(deviation) => format!("{deviation:.2e}"),
            Err(reason) => {
                let k = match reasons.iter().position(|x| x == reason) {
                    Some(k) => k,
                    None => {
                        reasons.push(reason.clone());
                        reasons.len() - 1
                    }
                };
                format!("n/a [{}]", k + 1)
            }
        };
        let _ = writeln!(
            md,
            "| {} | `{}` | {} | ({}) | {} | {} | {:.2e} | {:.2e} | {:.3} | {} | [ω](omega_{n}.svg), [drift](drift_{n}.svg), [animation]({n}.html) |",
            case.title,
            case.spec,
            r.report.dim,
            case.omega,
            case.t_end,
            r.steps,
            r.report.drift.energy,
            r.report.drift.casimirs,
            r.seconds,
            exact,
            n = case.name
        );
    }
    md.push('\n');
    for (k, reason) in reasons.iter().enumerate() {
        let _ = writeln!(md, "\\[{}\\] {reason}  ", k + 1);
    }
    let _ = writeln!(md, "\n## Integrators on the tesseract\n");
    md.push_str(&integrators);
    let _ = writeln!(md, "\n## Sweep\n");
    md.push_str(&sweep_text);
    let _ = writeln!(md, "\n## Scenes\n");
    let _ = writeln!(
        md,
        "Scene files of `scenes/`, run as `rotorflow scene FILE` runs them: bodies that move and \
         turn under gravity, springs and contact with planes (Coulomb friction, restitution), \
         with the symplectic Strang splitting of `dynamics::motion`. The animations show the \
         vertical axis x₄ upwards; the plots show the energy and the momenta over time.\n"
    );
    let _ = writeln!(
        md,
        "| scene | file | T | steps | time (s) | measured | files |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|---|");
    for (s, r) in SCENES.iter().zip(&scenes) {
        let t_end = Scene::from_toml_str(s.text, s.file)
            .map(|sc| number(sc.t_end))
            .unwrap_or_default();
        let _ = writeln!(
            md,
            "| {} | `{}` | {t_end} | {} | {:.3} | {} | [animation]({n}.html), [energy and momenta](energy_{n}.svg) |",
            s.title,
            s.file,
            r.steps,
            r.seconds,
            r.figures,
            n = s.name
        );
    }
    let _ = writeln!(
        md,
        "\nAlso: [tesseract_frames.svg](tesseract_frames.svg), a strip of frames of the tumbling tesseract.\n\nTotal time: {:.1} s.\n",
        clock.elapsed().as_secs_f64()
    );
    write_atomic(&dir.join("summary.md"), md.as_bytes())?;
    if !quiet {
        eprintln!(
            "rotorflow demo: wrote {} files into {} in {:.1} s",
            promised_files().len(),
            dir.display(),
            clock.elapsed().as_secs_f64()
        );
    }
    Ok(())
}

fn parse_case(case: &Case) -> CliResult<(super::spec::ParsedBody, rotorflow::dynamics::RigidBody)> {
    let parsed = parse_body(case.spec)?;
    let start = initial_body(
        &parsed,
        &InitialArgs {
            value: InitialValue {
                omega: Some(case.omega.to_string()),
                momentum: None,
            },
            axial: false,
        },
    )?;
    Ok((parsed, start))
}

fn run_case(case: &Case, dir: &Path) -> CliResult<CaseResult> {
    let (parsed, start) = parse_case(case)?;
    let times = even_times(case.t_end, case.samples);
    let clock = Instant::now();
    let stepping = Stepping::Fixed {
        kind: IntegratorKind::Yoshida4,
        dt: DT,
    };
    let mut silent = Progress::new(0, true, "");
    let (states, steps) = integrate(&start, &Free, stepping, &times, &mut silent)?;
    let seconds = clock.elapsed().as_secs_f64();
    let report = report_from_states(&start, &times, states.into_iter().map(Ok))?;
    let title = format!("{} — {}", case.title, case.spec);
    write_atomic(
        &dir.join(format!("omega_{}.svg", case.name)),
        omega_plot(&report, &title)?.as_bytes(),
    )?;
    write_atomic(
        &dir.join(format!("drift_{}.svg", case.name)),
        drift_plot(&report, &title)?.as_bytes(),
    )?;
    let html = picture(&parsed, &report, case.axes, Projection::Perspective, true);
    write_atomic(&dir.join(format!("{}.html", case.name)), html.as_bytes())?;
    if case.name == "tesseract" {
        let picks: Vec<usize> = (0..8).map(|k| k * (case.samples - 1) / 28).collect();
        let sub = Report {
            times: picks.iter().map(|&k| report.times[k]).collect(),
            attitude: picks.iter().map(|&k| report.attitude[k].clone()).collect(),
            ..report.clone()
        };
        let svg = picture(&parsed, &sub, case.axes, Projection::Perspective, false);
        write_atomic(&dir.join("tesseract_frames.svg"), svg.as_bytes())?;
    }
    // The "numeric vs exact" column: the closed form when the body has one, or why not.
    let exact = exact_report(&start, &times)
        .map(|exact| {
            exact
                .omega
                .iter()
                .zip(&report.omega)
                .map(|(a, b)| (a - b).max_abs())
                .fold(0.0f64, f64::max)
        })
        .map_err(|e| e.to_string());
    Ok(CaseResult {
        report,
        steps,
        seconds,
        exact,
    })
}

/// Runs the tesseract with every integrator and returns a markdown table of drifts and
/// timings.
fn integrator_table() -> CliResult<String> {
    let case = &CASES[0];
    let (_, start) = parse_case(case)?;
    let times = even_times(case.t_end, 121);
    let choices = [
        (
            "rk4",
            Stepping::Fixed {
                kind: IntegratorKind::Rk4,
                dt: DT,
            },
        ),
        (
            "strang",
            Stepping::Fixed {
                kind: IntegratorKind::Strang,
                dt: DT,
            },
        ),
        (
            "yoshida4",
            Stepping::Fixed {
                kind: IntegratorKind::Yoshida4,
                dt: DT,
            },
        ),
        (
            "kahan-li8",
            Stepping::Fixed {
                kind: IntegratorKind::KahanLi8,
                dt: DT,
            },
        ),
        (
            "midpoint",
            Stepping::Fixed {
                kind: IntegratorKind::Midpoint,
                dt: DT,
            },
        ),
        (
            "moser-veselov",
            Stepping::Fixed {
                kind: IntegratorKind::MoserVeselov,
                dt: DT,
            },
        ),
        (
            "dopri5 (rtol 1e-10, atol 1e-12)",
            Stepping::Adaptive {
                rtol: 1e-10,
                atol: 1e-12,
            },
        ),
        (
            "dop853 (rtol 1e-10, atol 1e-12)",
            Stepping::Adaptive8 {
                rtol: 1e-10,
                atol: 1e-12,
            },
        ),
    ];
    let rows: Vec<String> = choices
        .par_iter()
        .map(|(name, stepping)| {
            let clock = Instant::now();
            let mut silent = Progress::new(0, true, "");
            let (states, steps) = integrate(&start, &Free, *stepping, &times, &mut silent)?;
            let seconds = clock.elapsed().as_secs_f64();
            let report = report_from_states(&start, &times, states.into_iter().map(Ok))?;
            Ok(format!(
                "| {name} | {steps} | {:.2e} | {:.2e} | {:.2e} | {:.2e} | {:.4} |",
                report.drift.energy,
                report.drift.casimirs,
                report.drift.manakov,
                report.drift.space_momentum,
                seconds
            ))
        })
        .collect::<CliResult<_>>()?;
    let mut md = format!(
        "`{}`, ω(0) = ({}), T = {}, step {DT} for the fixed-step integrators.\n\n",
        case.spec, case.omega, case.t_end
    );
    md.push_str("| integrator | steps | energy drift | Casimir drift | Manakov drift | space-momentum drift | time (s) |\n|---|---|---|---|---|---|---|\n");
    for r in rows {
        md.push_str(&r);
        md.push('\n');
    }
    Ok(md)
}

/// The §7.2 sweep: the tesseract (1, 1, 1, κ) with the paper's initial ω; the frequency of
/// ω₂₄ and ω₃₄ seen in the 2-3-4 projection against κ, with eq. (119)'s
/// Ω = (κ² − 1)/(κ² + 1) · √(c₁² + c₂² + c₃²) (ω₁₂, ω₁₃, ω₂₃ stay constant).
fn sweep(dir: &Path) -> CliResult<String> {
    let omega = [0.3, 0.4, 0.2, 0.5, 0.1, 0.3];
    let omega_text = omega
        .iter()
        .map(|x| number(*x))
        .collect::<Vec<_>>()
        .join(",");
    let kappas: Vec<f64> = (0..=24).map(|k| 1.2 + 0.1 * k as f64).collect();
    let times = even_times(120.0, 2401);
    let axes = [1, 2, 3];
    let rows: Vec<(f64, [f64; 3], f64)> = kappas
        .par_iter()
        .map(|&kappa| {
            let spec = format!("tesseract:1,1,1,{}", number((kappa * 1e9).round() / 1e9));
            let parsed = parse_body(&spec)?;
            let start = initial_body(
                &parsed,
                &InitialArgs {
                    value: InitialValue {
                        omega: Some(omega_text.clone()),
                        momentum: None,
                    },
                    axial: false,
                },
            )?;
            let mut silent = Progress::new(0, true, "");
            let stepping = Stepping::Fixed {
                kind: IntegratorKind::Yoshida4,
                dt: 0.01,
            };
            let (states, _) = integrate(&start, &Free, stepping, &times, &mut silent)?;
            let report = report_from_states(&start, &times, states.into_iter().map(Ok))?;
            let obs = observables(&report, axes)?;
            let c = (omega[0] * omega[0] + omega[1] * omega[1] + omega[3] * omega[3]).sqrt();
            let paper = (kappa * kappa - 1.0) / (kappa * kappa + 1.0) * c;
            Ok((
                kappa,
                [obs.frequency[0], obs.frequency[1], obs.frequency[2]],
                paper,
            ))
        })
        .collect::<CliResult<_>>()?;
    let names = ["23", "24", "34"];
    let mut csv = String::from("kappa,freq_23,freq_24,freq_34,paper_eq119\n");
    for (k, f, p) in &rows {
        let _ = writeln!(
            csv,
            "{},{},{},{},{}",
            number(*k),
            number(f[0]),
            number(f[1]),
            number(f[2]),
            number(*p)
        );
    }
    write_atomic(&dir.join("sweep.csv"), csv.as_bytes())?;
    let mut series: Vec<Series> = (1..3)
        .map(|k| Series {
            name: format!(
                "observed frequency of ω{} (2-3-4 projection)",
                subscript(names[k])
            ),
            points: rows.iter().map(|(kappa, f, _)| (*kappa, f[k])).collect(),
        })
        .collect();
    series.push(Series {
        name: "paper eq. (119): (κ²−1)/(κ²+1)·√(c₁²+c₂²+c₃²)".into(),
        points: rows.iter().map(|(kappa, _, p)| (*kappa, *p)).collect(),
    });
    let svg = line_plot(
        &PlotSpec {
            title: "observed 3D frequency against the 4D parameter κ (tesseract 1,1,1,κ)",
            x_label: "κ (fourth half-edge)",
            y_label: "angular frequency (rad per unit time)",
            log_y: false,
            markers: true,
        },
        &series,
    )
    .map_err(|e| CliError::runtime(format!("cannot draw the sweep: {e}")))?;
    write_atomic(&dir.join("sweep.svg"), svg.as_bytes())?;
    let worst = rows
        .iter()
        .map(|(_, f, p)| ((f[1] - p) / p).abs().max(((f[2] - p) / p).abs()))
        .fold(0.0f64, f64::max);
    Ok(format!(
        "[sweep.svg](sweep.svg), [sweep.csv](sweep.csv): the tesseract `tesseract:1,1,1,κ` for κ = 1.2 … 3.6 \
         with ω(0) = ({omega_text}), T = 120. In the 2-3-4 projection ω₂₃ stays constant while ω₂₄ and ω₃₄ \
         oscillate at the frequency of the paper's eq. (119); the largest relative difference between the \
         observed frequency (from mean crossings) and eq. (119) is {worst:.1e}.\n"
    ))
}

/// One scene of the demo: a scene file of `scenes/`, embedded so that the demo runs from any
/// folder.
struct DemoScene {
    /// The stem of its files: `<name>.html` and `energy_<name>.svg`.
    name: &'static str,
    title: &'static str,
    /// The file in the repository, for the summary.
    file: &'static str,
    text: &'static str,
    samples: usize,
    /// The measured figures, for the summary.
    figures: fn(&Scene, &Record) -> String,
}

const SCENES: [DemoScene; 5] = [
    DemoScene {
        name: "tesseract_spring",
        title: "4D tesseract hanging by a corner from a spring",
        file: "scenes/tesseract-spring.toml",
        text: include_str!("../../scenes/tesseract-spring.toml"),
        samples: 501,
        figures: spring_figures,
    },
    DemoScene {
        name: "ball_rolling",
        title: "solid 4D ball sliding into rolling",
        file: "scenes/ball-rolling-4d.toml",
        text: include_str!("../../scenes/ball-rolling-4d.toml"),
        samples: 151,
        figures: rolling_figures,
    },
    DemoScene {
        name: "five_cell_slope",
        title: "5-cell bouncing down a slope",
        file: "scenes/five-cell-slope.toml",
        text: include_str!("../../scenes/five-cell-slope.toml"),
        samples: 251,
        figures: slope_figures,
    },
    DemoScene {
        name: "newtons_cradle",
        title: "Newton's cradle in 4D",
        file: "scenes/newtons-cradle-4d.toml",
        text: include_str!("../../scenes/newtons-cradle-4d.toml"),
        samples: 301,
        figures: cradle_figures,
    },
    DemoScene {
        name: "stacked_hypercubes",
        title: "three 4D hypercubes stacked",
        file: "scenes/stacked-hypercubes-4d.toml",
        text: include_str!("../../scenes/stacked-hypercubes-4d.toml"),
        samples: 101,
        figures: stack_figures,
    },
];

/// The result of a scene of the demo.
struct SceneResult {
    steps: usize,
    seconds: f64,
    figures: String,
}

/// Runs a scene of the demo and writes its animation and its plot of the energy and the
/// momenta.
fn run_scene(s: &DemoScene, dir: &Path) -> CliResult<SceneResult> {
    let scene = Scene::from_toml_str(s.text, s.file)?;
    let times = even_times(scene.t_end, s.samples);
    let clock = Instant::now();
    let record = scene.record(&times)?;
    let seconds = clock.elapsed().as_secs_f64();
    let html = scene.animation_html(&record, s.title);
    write_atomic(&dir.join(format!("{}.html", s.name)), html.as_bytes())?;
    let svg = scene.plot_svg(&record, &format!("{} ({})", s.title, s.file))?;
    write_atomic(&dir.join(format!("energy_{}.svg", s.name)), svg.as_bytes())?;
    Ok(SceneResult {
        steps: record.steps,
        seconds,
        figures: (s.figures)(&scene, &record),
    })
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// The largest relative change of the energy from t = 0 over the samples.
fn energy_error(record: &Record) -> f64 {
    let e0 = record.energy[0];
    record
        .energy
        .iter()
        .map(|e| (e - e0).abs() / e0.abs().max(f64::MIN_POSITIVE))
        .fold(0.0, f64::max)
}

/// The planes (i, j), i < j, in the order of the bivector components.
fn planes_of(n: usize) -> Vec<(usize, usize)> {
    (0..n)
        .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
        .collect()
}

/// The angular velocity ω (own-axes components) as the space-frame matrix R Ω Rᵀ, where
/// Ω e_i = ω_ij e_j for i < j (ω₁₂ > 0 turns e₁ towards e₂).
fn space_omega(omega: &[f64], attitude: &DMatrix<f64>) -> DMatrix<f64> {
    let n = attitude.nrows();
    let mut w = DMatrix::zeros(n, n);
    for ((i, j), x) in planes_of(n).into_iter().zip(omega) {
        w[(j, i)] = *x;
        w[(i, j)] = -*x;
    }
    attitude * w * attitude.transpose()
}

/// The lowest point of every body over every plane and sample, as the smallest signed
/// distance divided by the body's radius (negative: inside the solid).
fn lowest_gap(scene: &Scene, record: &Record) -> f64 {
    let mut lowest = f64::INFINITY;
    for (b, track) in scene.bodies.iter().zip(&record.bodies) {
        let shape = b.contact_shape();
        let radius = shape.radius();
        if radius == 0.0 {
            continue;
        }
        for p in &scene.planes {
            let s = norm(&p.normal);
            let n: Vec<f64> = p.normal.iter().map(|x| x / s).collect();
            let d = p.offset / s;
            for (k, x) in track.position.iter().enumerate() {
                let q = track.attitude_matrix(k);
                let centre: f64 = n.iter().zip(x).map(|(a, b)| a * b).sum::<f64>() - d;
                // m = Qᵀ n: the normal in own axes.
                let m: Vec<f64> = (0..n.len())
                    .map(|j| (0..n.len()).map(|i| q[(i, j)] * n[i]).sum())
                    .collect();
                let depth = match &shape {
                    ContactShape::Vertices(v) => v
                        .iter()
                        .map(|r| r.as_slice().iter().zip(&m).map(|(a, b)| a * b).sum::<f64>())
                        .fold(f64::INFINITY, f64::min),
                    ContactShape::Ellipsoid(a) => {
                        -norm(&a.iter().zip(&m).map(|(a, m)| a * m).collect::<Vec<_>>())
                    }
                    ContactShape::Convex(c) => {
                        let minus: Vec<f64> = m.iter().map(|x| -x).collect();
                        let mut p = vec![0.0; m.len()];
                        if c.support_own(&minus, &mut p).is_err() {
                            continue;
                        }
                        p.iter().zip(&m).map(|(a, b)| a * b).sum::<f64>()
                    }
                    _ => continue,
                };
                lowest = lowest.min((centre + depth) / radius);
            }
        }
    }
    lowest
}

/// The tesseract on a spring: the energy error (bounded, no damping) and the momenta.
fn spring_figures(scene: &Scene, record: &Record) -> String {
    let last = record.times.len() - 1;
    let up = up_axis(&scene.gravity);
    // The spring pulls towards its anchor and gravity is vertical, so the angular momentum
    // about the anchor (the origin) is kept in the planes without the vertical axis.
    let kept: Vec<usize> = planes_of(scene.dim)
        .into_iter()
        .enumerate()
        .filter(|(_, (i, j))| Some(*i) != up && Some(*j) != up)
        .map(|(k, _)| k)
        .collect();
    let names = plane_names(scene.dim);
    let l0 = &record.angular_momentum[0];
    let dl = record
        .angular_momentum
        .iter()
        .flat_map(|l| kept.iter().map(move |&k| (l[k] - l0[k]).abs()))
        .fold(0.0, f64::max);
    let p_range = record
        .momentum
        .iter()
        .map(|p| norm(p))
        .fold((f64::INFINITY, 0.0_f64), |(a, b), x| (a.min(x), b.max(x)));
    format!(
        "energy error max abs(ΔE)/abs(E(0)) = {:.2e} (bounded, no drift); angular momentum about \
         the anchor in the planes {} (gravity vertical, spring central): max change {:.1e}; \
         abs(p) between {:.3} and {:.3}, abs(L) {:.3} → {:.3}",
        energy_error(record),
        kept.iter()
            .map(|&k| subscript(&names[k]))
            .map(|s| format!("L{s}"))
            .collect::<Vec<_>>()
            .join(", "),
        dl,
        p_range.0,
        p_range.1,
        norm(l0),
        norm(&record.angular_momentum[last]),
    )
}

/// The rolling speed of a ball launched without spin on a floor: v0 (N + 2)/(N + 4).
fn rolling_prediction(scene: &Scene) -> f64 {
    let n = scene.dim as f64;
    norm(&scene.bodies[0].velocity) * (n + 2.0) / (n + 4.0)
}

/// The ball sliding into rolling: the final speed against v0 (N + 2)/(N + 4).
fn rolling_figures(scene: &Scene, record: &Record) -> String {
    let track = &record.bodies[0];
    let last = record.times.len() - 1;
    let predicted = rolling_prediction(scene);
    let measured = norm(&track.velocity[last]);
    // The contact point: R below the centre, along minus the floor's normal.
    let radius = scene.bodies[0].contact_shape().radius();
    let floor = &scene.planes[0].normal;
    let s = norm(floor);
    let slip_at = |k: usize| {
        let w = space_omega(&track.omega[k], &track.attitude_matrix(k));
        let r = DVector::from_iterator(floor.len(), floor.iter().map(|x| -radius * x / s));
        let v = DVector::from_column_slice(&track.velocity[k]) + w * r;
        v.norm()
    };
    let v0 = norm(&track.velocity[0]);
    let rolls_from = (0..=last)
        .find(|&k| (k..=last).all(|j| slip_at(j) <= 1e-9 * v0))
        .map_or("never".to_string(), |k| format!("t = {}", record.times[k]));
    format!(
        "rolling speed {measured:.12} against v0·(N+2)/(N+4) = {predicted}: relative error \
         {:.1e}; contact point slip at the end {:.1e}; rolling from {rolls_from} (predicted \
         2 v0/((N+4) μ g) = {:.4}); lowest point {:.1e} R from the floor",
        (measured - predicted).abs() / predicted,
        slip_at(last),
        2.0 * v0 / ((scene.dim as f64 + 4.0) * scene.planes[0].friction * norm(&scene.gravity)),
        lowest_gap(scene, record),
    )
}

/// The 5-cell bouncing down a slope: the energy lost and the deepest point.
/// The cradle: at the first sample after the row of impacts, the last ball's speed and the
/// largest speed of the others (the first ball came in at 1 m/s), and the energy kept.
fn cradle_figures(_: &Scene, record: &Record) -> String {
    let balls = record.bodies.len();
    let speed = |b: usize, k: usize| norm(&record.bodies[b].velocity[k]);
    let after = (0..record.times.len()).find(|&k| speed(balls - 1, k) > 0.5);
    let Some(k) = after else {
        return "the last ball never left".to_string();
    };
    let others = (0..balls - 1).map(|b| speed(b, k)).fold(0.0, f64::max);
    format!(
        "at t = {:.3} the last ball leaves at {:.6} m/s (the first came in at 1 m/s and climbs \
         from the bottom), the other balls move at {others:.1e} m/s at most; energy kept to \
         {:.1e} over the run",
        record.times[k],
        speed(balls - 1, k),
        energy_error(record),
    )
}

/// The stack: where the top hypercube ends against where it rests (its centre at x₁ = 0.1,
/// x₄ = 2.5), and the largest speed at the end.
fn stack_figures(_: &Scene, record: &Record) -> String {
    let last = record.times.len() - 1;
    let top = &record.bodies[record.bodies.len() - 1].position[last];
    let n = top.len();
    let sink = 2.5 - top[n - 1];
    let slide = norm(&[top[0] - 0.1, top[1], top[2]]);
    let fastest = record
        .bodies
        .iter()
        .map(|b| norm(&b.velocity[last]))
        .fold(0.0, f64::max);
    format!(
        "the top hypercube ends {sink:.1e} below and {slide:.1e} aside of its resting place; \
         the fastest body moves at {fastest:.1e} m/s at the end"
    )
}

fn slope_figures(scene: &Scene, record: &Record) -> String {
    let last = record.times.len() - 1;
    let (e0, e1) = (record.energy[0], record.energy[last]);
    let lowest = lowest_gap(scene, record);
    let verdict = if lowest >= -1e-9 {
        "never deeper than the contact tolerance 1e-9"
    } else {
        "deeper than the contact tolerance 1e-9"
    };
    format!(
        "energy {e0:.3} → {e1:.3} (zero on the floor): {:.1} % lost in the impacts and the \
         friction; lowest vertex over all samples {lowest:.1e} of the radius from the planes \
         ({verdict}); final speed {:.1e}",
        100.0 * (e0 - e1) / e0,
        norm(&record.bodies[0].velocity[last]),
    )
}
