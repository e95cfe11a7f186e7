//! Writes `book/src/generated/rapier_bench.md`: the time per step of rotorflow (by
//! `MotionSplitting` and by `SoftStep`) and of Rapier from criterion's results of the last
//! `cargo bench` of this package, and how well each engine keeps each scene, from short runs
//! of the same scenes taken here; and the pile of 100 by `MotionSplitting` with a sweep limit.
//!
//! `cargo run --release --manifest-path benches/rapier/Cargo.toml --bin table [-- --output FILE]`

use rapier3d::prelude::IntegrationParameters;
use rotorflow::dynamics::motion::{SoftStep, SolverReport};
use rotorflow_rapier_bench::{
    Floor, H, Item, RESTING_BOX, ROLLING_BALL, RapierRun, RotorflowIntegrator, RotorflowRun, Run,
    floor_depth, max_penetration, pile, pyramid, resting_boxes, rolling_balls,
};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};
use std::time::{Instant, SystemTime};

/// The scenes of the bench, in its order: criterion group, description.
const SCENES: &[(&str, &str)] = &[
    ("resting_boxes_1000", "1,000 boxes resting on the floor"),
    ("resting_boxes_100", "100 of those boxes"),
    ("rolling_balls_1000", "1,000 balls rolling on the floor"),
    ("pyramid_55", "pyramid of 55 cubes (10 layers)"),
    ("pile_100", "pile of 100 boxes and balls"),
    ("pile_1000", "pile of 1,000 boxes and balls"),
];

/// The engines of the bench: criterion function, column title. rotorflow's two
/// integrators first, `MotionSplitting` then `SoftStep`, then Rapier's two floors.
const ENGINES: &[(&str, &str)] = &[
    ("rotorflow", "rotorflow"),
    ("rotorflow_soft", "rotorflow SoftStep"),
    ("rapier_halfspace_floor", "Rapier, half-space floor"),
    ("rapier_cuboid_floor", "Rapier, cuboid floor"),
];

/// The scene and bench function of `MotionSplitting` with a sweep limit, and the limit.
const LIMITED: (&str, &str, usize) = ("pile_100", "rotorflow_sweep_limit_100", 100);

/// The seconds of each stability run (steps of h = 1/60 s).
const STABILITY_SECONDS: f64 = 2.0;

type Error = String;

fn read(path: &Path) -> Result<String, Error> {
    std::fs::read_to_string(path).map_err(|e| format!("cannot read {}: {e}", path.display()))
}

fn json(path: &Path) -> Result<serde_json::Value, Error> {
    serde_json::from_str(&read(path)?).map_err(|e| format!("{} is not JSON: {e}", path.display()))
}

fn modified(path: &Path) -> Result<SystemTime, Error> {
    std::fs::metadata(path)
        .and_then(|m| m.modified())
        .map_err(|e| format!("cannot stat {}: {e}", path.display()))
}

/// The median time per step (seconds) of one bench function of the last run and the steps
/// of one timed iteration (one `advance` call of rotorflow), or `None` when that run did not
/// measure it (results older than the run are not taken).
fn time_per_step(
    dir: &Path,
    group: &str,
    function: &str,
    run_start: SystemTime,
) -> Result<Option<(f64, f64)>, Error> {
    let new = dir.join(group).join(function).join("new");
    let estimates = new.join("estimates.json");
    if !estimates.is_file() || modified(&estimates)? < run_start {
        return Ok(None);
    }
    let median = json(&estimates)?["median"]["point_estimate"]
        .as_f64()
        .ok_or_else(|| format!("{}: no median", estimates.display()))?;
    let benchmark = new.join("benchmark.json");
    let steps = json(&benchmark)?["throughput"]["Elements"]
        .as_f64()
        .ok_or_else(|| format!("{}: no throughput in elements", benchmark.display()))?;
    Ok(Some((median * 1e-9 / steps, steps)))
}

/// The version of a package in this package's Cargo.lock.
fn locked_version(name: &str) -> Result<String, Error> {
    let lock = read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("Cargo.lock"))?;
    let needle = format!("name = \"{name}\"\nversion = \"");
    let start = lock
        .find(&needle)
        .ok_or_else(|| format!("Cargo.lock has no package {name}"))?
        + needle.len();
    Ok(lock[start..].split('"').next().unwrap_or("").to_string())
}

fn command_line(program: &str, args: &[&str]) -> Result<String, Error> {
    let out = Command::new(program)
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .map_err(|e| format!("cannot run {program}: {e}"))?;
    if !out.status.success() {
        return Err(format!("{program} {} failed", args.join(" ")));
    }
    Ok(String::from_utf8_lossy(&out.stdout).trim().to_string())
}

const DIRTY: &str = " (with uncommitted changes)";

/// The commit of HEAD, marked when the crate's or this package's files differ from it.
fn commit_of() -> Result<String, Error> {
    let commit = command_line("git", &["rev-parse", "--short", "HEAD"])?;
    let changes = command_line(
        "git",
        &[
            "status",
            "--porcelain",
            "--untracked-files=no",
            "--",
            "../../src",
            "../../Cargo.toml",
            "../../Cargo.lock",
            ".",
        ],
    )?;
    Ok(format!(
        "{commit}{}",
        if changes.is_empty() { "" } else { DIRTY }
    ))
}

fn ms(seconds: Option<f64>) -> String {
    match seconds.map(|s| s * 1e3) {
        Some(t) if t >= 100.0 => format!("{t:.0}"),
        Some(t) if t >= 10.0 => format!("{t:.1}"),
        Some(t) if t >= 1.0 => format!("{t:.2}"),
        Some(t) => format!("{t:.3}"),
        None => "—".to_string(),
    }
}

fn ratio(a: Option<f64>, b: Option<f64>) -> String {
    match (a, b) {
        (Some(a), Some(b)) => {
            let r = a / b;
            if r >= 10.0 {
                format!("{r:.0}×")
            } else {
                format!("{r:.2}×")
            }
        }
        _ => "—".to_string(),
    }
}

fn sci(x: f64) -> String {
    format!("{x:.1e}")
}

/// One engine's stability figures for one scene, as table cells.
type Figures = Vec<String>;

fn largest(values: impl Iterator<Item = f64>) -> f64 {
    values.fold(f64::NEG_INFINITY, f64::max)
}

fn speed(v: &[f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn steps(seconds: f64) -> usize {
    (seconds / H).round() as usize
}

/// Resting boxes: how far the deepest sinks below its resting height, and the fastest.
fn resting(run: &mut dyn Run, items: &[Item]) -> Figures {
    run.advance(steps(STABILITY_SECONDS));
    let poses = run.poses();
    let sink = largest(poses.iter().map(|p| RESTING_BOX[2] - p.position[2]));
    let fastest = largest(run.velocities().iter().map(speed));
    let _ = items;
    vec![sci(sink), sci(fastest)]
}

/// Rolling balls: the largest error of the speed against 5/7 of the launch speed
/// (relative), and the deepest reach into the floor.
fn rolling(run: &mut dyn Run, items: &[Item]) -> Figures {
    run.advance(steps(STABILITY_SECONDS));
    let v = ROLLING_BALL.1 * 5.0 / 7.0;
    let error = largest(run.velocities().iter().map(|u| (speed(u) - v).abs() / v));
    let poses = run.poses();
    let floor = largest(
        items
            .iter()
            .zip(&poses)
            .map(|(i, p)| floor_depth(&i.shape, p)),
    );
    vec![sci(error), sci(floor)]
}

/// The pyramid: the top cube's sink and slide from where it started, and the deepest
/// penetration at the end.
fn standing(run: &mut dyn Run, items: &[Item]) -> Figures {
    let top = items.last().expect("a pyramid").position;
    run.advance(steps(STABILITY_SECONDS));
    let poses = run.poses();
    let end = poses.last().expect("a pyramid").position;
    let slide = ((end[0] - top[0]).powi(2) + (end[1] - top[1]).powi(2)).sqrt();
    vec![
        sci(top[2] - end[2]),
        sci(slide),
        sci(max_penetration(items, &poses)),
    ]
}

/// The pile: the deepest penetration seen after any step, the fastest body at the end, and
/// the longest time one step took (wall clock, a single run: how uneven the cost is while
/// the pile lands).
fn piled(run: &mut dyn Run, items: &[Item]) -> Figures {
    let mut deepest = f64::NEG_INFINITY;
    let mut slowest = 0.0f64;
    for _ in 0..steps(STABILITY_SECONDS) {
        let start = Instant::now();
        run.advance(1);
        slowest = slowest.max(start.elapsed().as_secs_f64());
        deepest = deepest.max(max_penetration(items, &run.poses()));
    }
    let fastest = largest(run.velocities().iter().map(speed));
    vec![sci(deepest), sci(fastest), sci(slowest)]
}

struct StabilityScene {
    group: &'static str,
    items: fn() -> Vec<Item>,
    measures: &'static [&'static str],
    run: fn(&mut dyn Run, &[Item]) -> Figures,
}

const STABILITY: &[StabilityScene] = &[
    StabilityScene {
        group: "resting_boxes_1000",
        items: resting_boxes,
        measures: &[
            "deepest sink below resting height (m)",
            "fastest body at the end (m/s)",
        ],
        run: resting,
    },
    StabilityScene {
        group: "rolling_balls_1000",
        items: rolling_balls,
        measures: &[
            "largest speed error against 5/7 v₀ (relative)",
            "deepest reach into the floor (m)",
        ],
        run: rolling,
    },
    StabilityScene {
        group: "pyramid_55",
        items: || pyramid(10),
        measures: &[
            "top cube's sink (m)",
            "top cube's slide (m)",
            "deepest penetration at the end (m)",
        ],
        run: standing,
    },
    StabilityScene {
        group: "pile_100",
        items: || pile(100),
        measures: &[
            "deepest penetration after any step (m)",
            "fastest body at the end (m/s)",
            "slowest step (s)",
        ],
        run: piled,
    },
];

/// The sweep limit of a run by `MotionSplitting`, and what its contact solves did.
fn splitting_report(run: &RotorflowRun) -> (usize, SolverReport) {
    let RotorflowIntegrator::Splitting(splitting) = &run.integrator else {
        unreachable!("a RotorflowRun of MotionSplitting")
    };
    (splitting.sweep_limit(), splitting.solver_report())
}

/// `MotionSplitting`'s stability figures of a scene, with its sweep limit and solves.
type SplittingRun = (Figures, usize, SolverReport);

/// The stability table's rows, and a line per scene of what `MotionSplitting`'s contact
/// solves did in its run; returns that run of the scene of [`LIMITED`].
fn stability_rows(out: &mut String, solves: &mut String) -> Option<SplittingRun> {
    let mut limited_scene = None;
    for scene in STABILITY {
        let items = (scene.items)();
        let description = SCENES.iter().find(|s| s.0 == scene.group).unwrap().1;
        eprintln!("stability: {description}");
        let mut columns: Vec<Figures> = Vec::new();
        let mut ours = RotorflowRun::new(&items);
        columns.push((scene.run)(&mut ours, &items));
        let (limit, report) = splitting_report(&ours);
        if scene.group == LIMITED.0 {
            limited_scene = Some((columns[0].clone(), limit, report));
        }
        let _ = writeln!(
            solves,
            "| {description} | {} | {} | {:.2} | {} | {} |",
            report.solves,
            report.unconverged,
            report.sweeps as f64 / report.solves.max(1) as f64,
            report.max_sweeps,
            sci(report.worst_residual),
        );
        for floor in [Floor::HalfSpace, Floor::Cuboid] {
            columns.push((scene.run)(&mut RapierRun::new(&items, floor), &items));
        }
        columns.push((scene.run)(&mut RotorflowRun::soft(&items), &items));
        for (k, measure) in scene.measures.iter().enumerate() {
            let _ = writeln!(
                out,
                "| {description} | {measure} | {} | {} | {} | {} |",
                columns[0][k], columns[1][k], columns[2][k], columns[3][k]
            );
        }
    }
    limited_scene
}

/// The pile of 100 by `MotionSplitting` with its default sweep limit (`default`: its
/// stability run of the table above, and its time among `times` with Rapier's two floors')
/// and with at most [`LIMITED`]'s sweeps per solve (its time `limited`, and a stability run
/// of its own).
fn sweep_limit_section(
    limited: Option<f64>,
    times: [Option<f64>; 3],
    default: Option<SplittingRun>,
) -> String {
    let (group, function, sweeps) = LIMITED;
    let description = SCENES.iter().find(|s| s.0 == group).unwrap().1;
    let [default_time, half_space, cuboid] = times;
    let mut text = String::new();
    let _ = writeln!(
        text,
        "\n`MotionSplitting` on the {description} with its default sweep limit and with at most \
         {sweeps} sweeps per contact solve (`MotionSplitting::with_sweep_limit({sweeps})`, bench \
         function `{function}`), where a solve that reaches the limit stops with the impulses it \
         has, counted unconverged; stability and solves from runs of {STABILITY_SECONDS} s from \
         the start, as above.\n"
    );
    let _ = writeln!(
        text,
        "| sweep limit | ms/step | ratio to half-space floor | ratio to cuboid floor | \
         deepest penetration after any step (m) | fastest body at the end (m/s) | slowest step (s) | \
         solves | unconverged | mean sweeps | worst residual |"
    );
    let _ = writeln!(
        text,
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    eprintln!("stability: {description}, sweep limit {sweeps}");
    let items = pile(100);
    let mut run = RotorflowRun::with_sweep_limit(&items, sweeps);
    let figures = piled(&mut run, &items);
    let (limit, report) = splitting_report(&run);
    let rows = default
        .map(|(figures, limit, report)| (figures, limit, report, default_time, " (default)"))
        .into_iter()
        .chain([(figures, limit, report, limited, "")]);
    for (figures, limit, report, time, note) in rows {
        let _ = writeln!(
            text,
            "| {limit}{note} | {} | {} | {} | {} | {} | {} | {} | {} | {:.2} | {} |",
            ms(time),
            ratio(time, half_space),
            ratio(time, cuboid),
            figures[0],
            figures[1],
            figures[2],
            report.solves,
            report.unconverged,
            report.sweeps as f64 / report.solves.max(1) as f64,
            sci(report.worst_residual),
        );
    }
    text
}

fn run() -> Result<(), Error> {
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let mut output = manifest.join("../../book/src/generated/rapier_bench.md");
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--output" => {
                output = PathBuf::from(args.next().ok_or("--output needs a file name")?);
            }
            other => return Err(format!("unknown argument `{other}` (only --output FILE)")),
        }
    }
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| manifest.join("target"));
    let dir = target.join("criterion");
    let record_path = dir.join("rapier_run.json");
    let record = json(&record_path)
        .map_err(|e| format!("{e} (run `cargo bench` in benches/rapier first)"))?;
    let run_start = modified(&record_path)?;
    let bench_args: Vec<String> = record["args"]
        .as_array()
        .map(|a| {
            a.iter()
                .filter_map(|s| s.as_str())
                .filter(|s| *s != "--bench")
                .map(String::from)
                .collect()
        })
        .unwrap_or_default();
    let load = record["loadavg"]
        .as_str()
        .unwrap_or("")
        .split_whitespace()
        .next()
        .unwrap_or("?")
        .to_string();
    let cpus = record["cpus"].as_u64().unwrap_or(0);

    let mut speed = String::new();
    let mut missing = Vec::new();
    // The ratios to Rapier's two floors of `MotionSplitting` and of `SoftStep`.
    let mut ratios = [Vec::new(), Vec::new()];
    // The pile of 100's times (`MotionSplitting`, Rapier's two floors), for the sweep limit.
    let mut pile_times = [None; 3];
    for (group, description) in SCENES {
        let (mut times, mut per_call) = (Vec::new(), None);
        for (function, _) in ENGINES {
            let t = time_per_step(&dir, group, function, run_start)?;
            if t.is_none() {
                missing.push(format!("{group}/{function}"));
            }
            // Every engine of a scene takes the scene's steps per iteration.
            per_call = per_call.or(t.map(|(_, steps)| steps));
            times.push(t.map(|(time, _)| time));
        }
        let [splitting, soft, half_space, cuboid] = times[..] else {
            unreachable!("four engines")
        };
        if *group == LIMITED.0 {
            pile_times = [splitting, half_space, cuboid];
        }
        for (ours, list) in [splitting, soft].into_iter().zip(&mut ratios) {
            for rapier in [half_space, cuboid] {
                if let (Some(a), Some(b)) = (ours, rapier) {
                    list.push(a / b);
                }
            }
        }
        let per_call = per_call.map_or("—".into(), |k| format!("{k:.0}"));
        let _ = writeln!(
            speed,
            "| {description} | {per_call} | {} | {} | {} | {} | {} | {} | {} | {} |",
            ms(splitting),
            ms(half_space),
            ratio(splitting, half_space),
            ms(cuboid),
            ratio(splitting, cuboid),
            ms(soft),
            ratio(soft, half_space),
            ratio(soft, cuboid),
        );
    }
    let limited = time_per_step(&dir, LIMITED.0, LIMITED.1, run_start)?.map(|(t, _)| t);
    if limited.is_none() {
        missing.push(format!("{}/{}", LIMITED.0, LIMITED.1));
    }
    if missing.len() == SCENES.len() * ENGINES.len() + 1 {
        return Err(format!(
            "no results of the last bench run under {}",
            dir.display()
        ));
    }

    let mut stability = String::new();
    let mut solves = String::new();
    let default_pile = stability_rows(&mut stability, &mut solves);

    // The code that is measured: the crate and this package (the book's files aside).
    let here = commit_of()?;
    let timed = format!(
        "{}{}",
        record["commit"].as_str().unwrap_or("unknown"),
        if record["dirty"].as_bool().unwrap_or(true) {
            DIRTY
        } else {
            ""
        }
    );
    let measured = if timed == here {
        format!("Measured at commit `{here}`")
    } else {
        format!("Measured at commit `{here}` (the times at commit `{timed}`)")
    };
    let date = command_line("date", &["-u", "+%Y-%m-%d"])?;
    let rustc = command_line("rustc", &["--version"])?;
    let p = IntegrationParameters::default();
    // SoftStep's contact frequencies follow from its substep rate: a fifth of it, and
    // against fixed bodies and half-spaces twice that up to a quarter of it.
    let soft = SoftStep::new();
    let substep_rate = soft.substeps() as f64 / H;
    let hertz = substep_rate / 5.0;
    let fixed_hertz = (2.0 * hertz).min(substep_rate / 4.0);
    let mut text = String::new();
    let _ = writeln!(
        text,
        "<!-- Generated by `cargo run --release --manifest-path benches/rapier/Cargo.toml --bin table` after `cargo bench` in benches/rapier; do not edit. -->\n"
    );
    let _ = writeln!(
        text,
        "{measured} on {date} by `cargo bench --manifest-path benches/rapier/Cargo.toml -- {}` \
         ({rustc}; {cpus} cores, load average {load} at the start). rotorflow {} (f64) against rapier3d {} \
         (f32, default features) with criterion {}: sample size 10, flat sampling, the median time per step.\n",
        bench_args.join(" "),
        locked_version("rotorflow")?,
        locked_version("rapier3d")?,
        locked_version("criterion")?,
    );
    let _ = writeln!(
        text,
        "Both engines take steps of h = {:.6} s (1/60), rotorflow those of a timed iteration in one `advance` call \
         (the steps per call in the table). rotorflow (the first columns): `MotionSplitting`, where no bodies touch \
         each other one velocity solve per step (the closing solve of a step joined with the opening solve of the \
         next) and two more per call (its first step's opening solve, and its last step taken whole so that its \
         contacts are its own), else two per step, its contacts solved by Gauss–Seidel to its tolerance (without restitution, its impacts are speculative contacts, not located in time). rotorflow SoftStep (the last columns): `SoftStep` with its \
         defaults, a fixed solver cost per step: {} substeps, each with 1 Gauss–Seidel pass over soft contacts \
         (springs) and 1 relax pass without the springs (in 3D), contacts of {:.0} Hz (a fifth of the substep rate) \
         and {:.0} Hz against fixed bodies and the floor (twice that, up to a quarter of the substep rate), damping \
         ratio 3, overlaps pushed out at most at 3 m/s, a speculative margin of 0.5 % of each body's bounding radius and how far its points may move in the step, \
         contacts found once per step and restitution applied once per step. Rapier: `PhysicsWorld::step` with its \
         default integration parameters (soft TGS: {} substeps, each of {} velocity and {} stabilization iteration, \
         warm start {}), sleeping off, continuous collision detection off; SoftStep and Rapier thus do comparable \
         solver work per step. Each scene is stepped for a while before the timing (the piles for 2 s, so that they \
         have landed). Ratio = rotorflow's time / Rapier's, for each of rotorflow's integrators and each of \
         Rapier's floors.\n",
        H,
        soft.substeps(),
        hertz,
        fixed_hertz,
        p.num_solver_iterations,
        p.num_internal_pgs_iterations,
        p.num_internal_stabilization_iterations,
        p.warmstart_coefficient,
    );
    let _ = writeln!(
        text,
        "| scene | steps per call | rotorflow (ms/step) | Rapier, half-space floor (ms/step) | ratio | Rapier, cuboid floor (ms/step) | ratio \
         | rotorflow SoftStep (ms/step) | ratio to half-space floor | ratio to cuboid floor |"
    );
    let _ = writeln!(text, "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    text.push_str(&speed);
    let _ = writeln!(
        text,
        "\n`MotionSplitting` is not timed on the pile of 1,000, which would take it far longer than the minutes of \
         the rest of the run (its slowest step on the pile of 100 is in the stability table)."
    );
    missing.retain(|m| m != "pile_1000/rotorflow");
    let ranges: Vec<String> = ["`MotionSplitting`", "`SoftStep`"]
        .iter()
        .zip(&ratios)
        .filter(|(_, r)| !r.is_empty())
        .map(|(name, r)| {
            let low = r.iter().copied().fold(f64::INFINITY, f64::min);
            let high = r.iter().copied().fold(0.0, f64::max);
            format!(
                "{} to {} with {name}",
                ratio(Some(low), Some(1.0)),
                ratio(Some(high), Some(1.0)),
            )
        })
        .collect();
    if !ranges.is_empty() {
        let _ = writeln!(
            text,
            "\nrotorflow's time per step, as a multiple of Rapier's on these scenes: {}.",
            ranges.join(", ")
        );
    }
    if !missing.is_empty() {
        let _ = writeln!(text, "\nNot measured in this run: {}.", missing.join(", "));
    }
    let _ = writeln!(
        text,
        "\nStability, from runs of {STABILITY_SECONDS} s from the start of each scene (outside the timing), \
         rotorflow by `MotionSplitting` (the column rotorflow) and by `SoftStep`. Penetrations are measured on the \
         placements each engine reports, in closed form (balls by their centres, boxes by their 15 separating axes), \
         the same way for all.\n"
    );
    let _ = writeln!(
        text,
        "| scene | measure | rotorflow | Rapier, half-space floor | Rapier, cuboid floor | rotorflow SoftStep |"
    );
    let _ = writeln!(text, "|---|---|---:|---:|---:|---:|");
    text.push_str(&stability);
    let _ = writeln!(
        text,
        "\n`MotionSplitting`'s contact solves in those runs (`MotionSplitting::solver_report`): the solves, those that \
         stopped unconverged (at the sweep limit, when their largest change had not fallen by 1 % in 500 sweeps, or on a cycle: sweeps that left the velocities where they were), the mean and the most sweeps one took and the worst residual \
         left.\n"
    );
    let _ = writeln!(
        text,
        "| scene | solves | unconverged | mean sweeps | most sweeps | worst residual |"
    );
    let _ = writeln!(text, "|---|---:|---:|---:|---:|---:|");
    text.push_str(&solves);
    text.push_str(&sweep_limit_section(limited, pile_times, default_pile));
    std::fs::write(&output, text).map_err(|e| format!("cannot write {}: {e}", output.display()))?;
    eprintln!("wrote {}", output.display());
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
