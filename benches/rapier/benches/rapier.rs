//! rotorflow against Rapier on the same 3D scenes (see the crate's documentation), in one
//! criterion run. Each bench function steps a scene that has already been stepped for a
//! while (outside the timing) by a fixed number of steps per iteration, given as
//! criterion's throughput in elements (steps), so that `table` reports time per step.
//! rotorflow takes its steps with one `advance`, by `MotionSplitting` (function `rotorflow`)
//! and by `SoftStep` (`rotorflow_soft`); Rapier with `PhysicsWorld::step`. On the pile of 100,
//! `MotionSplitting` is also timed with at most 100 sweeps per contact solve
//! (`rotorflow_sweep_limit_100`, [`MotionSplitting::with_sweep_limit`]).
//!
//! [`MotionSplitting::with_sweep_limit`]: rotorflow::dynamics::motion::MotionSplitting::with_sweep_limit
//!
//! Criterion's options apply (`-- --warm-up-time 1 --measurement-time 3`), and a name
//! filter selects scenes: scenes it leaves out are not even set up. The run's arguments, the
//! commit and the load average at its start are written to `criterion/rapier_run.json`
//! beside criterion's own results, for `table`.

use criterion::{Criterion, SamplingMode, Throughput, black_box};
use rotorflow_rapier_bench::{
    Floor, Item, RapierRun, RotorflowRun, Run, pile, pyramid, resting_boxes, resting_boxes_of,
    rolling_balls,
};
use std::path::PathBuf;

/// One scene of the comparison: its criterion group, its bodies, the steps taken before
/// the timing, the steps per timed iteration, whether rotorflow's `MotionSplitting` is
/// timed on it (its `SoftStep` is timed on every scene) and whether it is timed with a limit
/// of 100 sweeps per solve as well.
struct Scene {
    group: &'static str,
    items: fn() -> Vec<Item>,
    settle: usize,
    steps: usize,
    rotorflow: bool,
    limited: bool,
}

const SCENES: &[Scene] = &[
    Scene {
        group: "resting_boxes_1000",
        items: resting_boxes,
        settle: 20,
        steps: 100,
        rotorflow: true,
        limited: false,
    },
    Scene {
        group: "resting_boxes_100",
        items: || resting_boxes_of(100),
        settle: 20,
        steps: 100,
        rotorflow: true,
        limited: false,
    },
    Scene {
        group: "rolling_balls_1000",
        items: rolling_balls,
        settle: 20,
        steps: 100,
        rotorflow: true,
        limited: false,
    },
    Scene {
        group: "pyramid_55",
        items: || pyramid(10),
        settle: 10,
        steps: 10,
        rotorflow: true,
        limited: false,
    },
    Scene {
        group: "pile_100",
        items: || pile(100),
        settle: 120,
        steps: 1,
        rotorflow: true,
        limited: true,
    },
    Scene {
        group: "pile_1000",
        // `MotionSplitting` takes seconds per step on this pile (Gauss–Seidel solves of up
        // to a thousand bodies in contact, to its tolerance): it is not timed here.
        items: || pile(1000),
        settle: 120,
        steps: 1,
        rotorflow: false,
        limited: false,
    },
];

/// The name filters among the command-line arguments (criterion's own options aside).
fn filters() -> Vec<String> {
    let mut out = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        if a.starts_with("--") {
            // Options of criterion that take a value.
            if matches!(
                a.as_str(),
                "--warm-up-time"
                    | "--measurement-time"
                    | "--sample-size"
                    | "--save-baseline"
                    | "--baseline"
                    | "--load-baseline"
                    | "--nresamples"
                    | "--noise-threshold"
                    | "--confidence-level"
                    | "--significance-level"
                    | "--plotting-backend"
                    | "--output-format"
                    | "--profile-time"
                    | "--color"
            ) {
                args.next();
            }
        } else {
            out.push(a);
        }
    }
    out
}

fn bench_run(
    g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    name: &str,
    run: &mut dyn Run,
    steps: usize,
) {
    g.bench_function(name, |b| b.iter(|| run.advance(black_box(steps))));
}

fn criterion_dir() -> PathBuf {
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target"));
    target.join("criterion")
}

fn main() {
    let filters = filters();
    // `cargo test --benches` runs this with `--bench` absent: nothing to time then.
    if !std::env::args().any(|a| a == "--bench") {
        return;
    }
    let dir = criterion_dir();
    std::fs::create_dir_all(&dir).expect("the criterion folder");
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    let git = |args: &[&str]| {
        std::process::Command::new("git")
            .args(args)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
    };
    let record = serde_json::json!({
        "commit": git(&["rev-parse", "--short", "HEAD"]),
        // The code that is measured: the crate and this package (the book's files aside).
        "dirty": git(&[
            "status",
            "--porcelain",
            "--untracked-files=no",
            "--",
            "../../src",
            "../../Cargo.toml",
            "../../Cargo.lock",
            ".",
        ])
        .map(|s| !s.is_empty()),
        "args": std::env::args().skip(1).collect::<Vec<_>>(),
        "loadavg": load.trim(),
        "cpus": std::thread::available_parallelism().map(|n| n.get()).unwrap_or(0),
    });
    std::fs::write(dir.join("rapier_run.json"), record.to_string()).expect("rapier_run.json");

    let mut c = Criterion::default().sample_size(10).configure_from_args();
    for scene in SCENES {
        // A filter names a scene (or part of its name), or one bench of it ("scene/bench").
        let wanted = |f: &String| scene.group.contains(f.as_str()) || f.starts_with(scene.group);
        if !filters.is_empty() && !filters.iter().any(wanted) {
            continue;
        }
        let items = (scene.items)();
        let mut g = c.benchmark_group(scene.group);
        // Flat sampling: every sample takes the same number of iterations, the fewest
        // criterion allows, which the slow scenes need.
        g.sampling_mode(SamplingMode::Flat);
        g.throughput(Throughput::Elements(scene.steps as u64));
        if scene.rotorflow {
            let mut ours = RotorflowRun::new(&items);
            ours.advance(scene.settle);
            bench_run(&mut g, "rotorflow", &mut ours, scene.steps);
        }
        if scene.limited {
            let mut limited = RotorflowRun::with_sweep_limit(&items, 100);
            limited.advance(scene.settle);
            bench_run(
                &mut g,
                "rotorflow_sweep_limit_100",
                &mut limited,
                scene.steps,
            );
        }
        let mut soft = RotorflowRun::soft(&items);
        soft.advance(scene.settle);
        bench_run(&mut g, "rotorflow_soft", &mut soft, scene.steps);
        for (name, floor) in [
            ("rapier_halfspace_floor", Floor::HalfSpace),
            ("rapier_cuboid_floor", Floor::Cuboid),
        ] {
            let mut theirs = RapierRun::new(&items, floor);
            theirs.advance(scene.settle);
            bench_run(&mut g, name, &mut theirs, scene.steps);
        }
        g.finish();
    }
    c.final_summary();
}
