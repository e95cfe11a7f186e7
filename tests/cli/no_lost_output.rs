//! No lost output: a command killed at any moment leaves each output file
//! whole or absent, and a killed `sweep` rerun with `--resume` continues from its finished
//! runs and writes the same bytes as an uninterrupted run.

use super::rotorflow;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

fn binary() -> PathBuf {
    assert_cmd::cargo::cargo_bin("rotorflow")
}

/// Starts `rotorflow args` in `dir` (no output on the terminal).
fn spawn(dir: &Path, args: &[&str], threads: Option<usize>) -> Child {
    let mut cmd = Command::new(binary());
    cmd.current_dir(dir)
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::null());
    if let Some(n) = threads {
        cmd.env("RAYON_NUM_THREADS", n.to_string());
    }
    cmd.spawn().expect("rotorflow starts")
}

/// SIGKILL, then reap.
fn kill(mut child: Child) {
    let _ = child.kill();
    let _ = child.wait();
}

/// Polls `ready` every millisecond for up to a minute.
fn wait_until(mut ready: impl FnMut() -> bool) -> bool {
    let start = Instant::now();
    while start.elapsed() < Duration::from_secs(60) {
        if ready() {
            return true;
        }
        std::thread::sleep(Duration::from_millis(1));
    }
    false
}

const SIMULATE: [&str; 14] = [
    "--quiet",
    "simulate",
    "--body",
    "tesseract:1,1.2,1.5,2",
    "--omega",
    "0.3,0.4,0.2,0.5,0.1,0.3",
    "--t-end",
    "100",
    "--samples",
    "20001",
    "--json",
    "--output",
    "out.json",
    "--plot=out.svg",
];

/// Checks that out.json and out.svg in `dir` are absent or complete.
fn outputs_whole_or_absent(dir: &Path, when: &str) -> (bool, bool) {
    let json = dir.join("out.json");
    let json_there = json.exists();
    if json_there {
        let text = std::fs::read(&json).unwrap();
        let value: serde_json::Value = serde_json::from_slice(&text).unwrap_or_else(|e| {
            panic!("{when}: out.json is not whole ({} bytes): {e}", text.len())
        });
        assert_eq!(
            value["times"].as_array().map(Vec::len),
            Some(20001),
            "{when}: out.json lacks samples"
        );
    }
    let svg = dir.join("out.svg");
    let svg_there = svg.exists();
    if svg_there {
        let text = std::fs::read_to_string(&svg).unwrap();
        assert!(
            text.trim_end().ends_with("</svg>"),
            "{when}: out.svg is cut short"
        );
    }
    (json_there, svg_there)
}

/// `simulate` killed at delays spread over its run, and killed the moment its temporary
/// output file appears (mid-write): out.json and out.svg are each absent or whole.
#[test]
fn killed_simulate_leaves_each_output_whole_or_absent() {
    // How long an uninterrupted run takes on this machine and build.
    let dir = tempfile::tempdir().unwrap();
    let start = Instant::now();
    let status = spawn(dir.path(), &SIMULATE, None).wait().unwrap();
    let full = start.elapsed();
    assert!(status.success());
    assert_eq!(
        outputs_whole_or_absent(dir.path(), "uninterrupted"),
        (true, true)
    );

    let mut outcomes = Vec::new();
    for fraction in [0.05, 0.3, 0.6, 0.8, 0.9, 0.95, 1.0, 1.05, 1.2] {
        let dir = tempfile::tempdir().unwrap();
        let child = spawn(dir.path(), &SIMULATE, None);
        std::thread::sleep(full.mul_f64(fraction));
        kill(child);
        let when = format!("killed after {fraction} of a run");
        outcomes.push(outputs_whole_or_absent(dir.path(), &when));
    }
    // Mid-write: kill as soon as a temporary file of the atomic writes shows up: the plot's
    // (written first), then the JSON's (a temporary file once out.svg is there).
    for attempt in 0..6 {
        let dir = tempfile::tempdir().unwrap();
        let child = spawn(dir.path(), &SIMULATE, None);
        let second = attempt % 2 == 1;
        let seen = wait_until(|| {
            let temporary = std::fs::read_dir(dir.path()).unwrap().any(|e| {
                e.unwrap()
                    .file_name()
                    .to_string_lossy()
                    .starts_with(".rotorflow-")
            });
            temporary && (!second || dir.path().join("out.svg").exists())
        });
        kill(child);
        assert!(seen, "no temporary file appeared");
        let outcome =
            outputs_whole_or_absent(dir.path(), &format!("killed mid-write (attempt {attempt})"));
        if second {
            assert!(outcome.1, "the plot was written before the JSON");
        }
        outcomes.push(outcome);
    }
    eprintln!("kill outcomes (out.json there, out.svg there): {outcomes:?}");
    // The early kills leave nothing.
    assert_eq!(outcomes[0], (false, false));
}

fn sweep_args<'a>(range: &'a str, csv: &'a str) -> Vec<&'a str> {
    vec![
        "sweep",
        "--body",
        "tesseract:1,1,1,{k}",
        "--param",
        range,
        "--omega",
        "0.3,0.4,0.2,0.5,0.1,0.3",
        "--t-end",
        "30",
        "--samples",
        "301",
        "--axes",
        "2,3,4",
        "--integrator",
        "yoshida4",
        "--dt",
        "0.01",
        "--output",
        csv,
    ]
}

const GRID: &str = "k=1.2:3:0.05"; // 37 runs

/// The complete lines after the header of a progress file.
fn finished_rows(path: &Path) -> usize {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    text.matches('\n').count().saturating_sub(1)
}

/// Kills a one-thread sweep after it has finished a few runs; returns the progress file.
fn interrupted_sweep(dir: &Path) -> PathBuf {
    let partial = dir.join("sweep.csv.partial");
    let mut args = vec!["--quiet"];
    args.extend(sweep_args(GRID, "sweep.csv"));
    let child = spawn(dir, &args, Some(1));
    let started = wait_until(|| finished_rows(&partial) >= 3);
    kill(child);
    assert!(started, "the sweep recorded no runs");
    assert!(
        !dir.join("sweep.csv").exists(),
        "the sweep finished before it was killed"
    );
    partial
}

/// A sweep killed mid-way (and its progress file torn in a last line) and rerun with
/// `--resume` runs only the missing points and writes the same bytes as an uninterrupted
/// run; the progress file is then gone.
#[test]
fn killed_sweep_resumed_gives_the_same_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = rotorflow()
        .current_dir(dir.path())
        .args(sweep_args(GRID, "full.csv"))
        .output()
        .unwrap();
    assert!(out.status.success());
    let full = std::fs::read(dir.path().join("full.csv")).unwrap();
    assert_eq!(full.iter().filter(|b| **b == b'\n').count(), 1 + 37);
    assert!(!dir.path().join("full.csv.partial").exists());

    let partial = interrupted_sweep(dir.path());
    let done = finished_rows(&partial);
    assert!((3..37).contains(&done), "{done} runs recorded");
    // A torn line, as if the kill had hit a write.
    let mut torn = std::fs::read(&partial).unwrap();
    torn.extend_from_slice(b"36,3,0.27");
    std::fs::write(&partial, &torn).unwrap();

    // Without --quiet: the command says how many runs it took over.
    let out = Command::new(binary())
        .current_dir(dir.path())
        .args(sweep_args(GRID, "sweep.csv"))
        .arg("--resume")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(
        err.contains(&format!("resuming: {done} of 37 runs")),
        "{err}"
    );
    let resumed = std::fs::read(dir.path().join("sweep.csv")).unwrap();
    assert!(
        resumed == full,
        "the resumed file differs from an uninterrupted run"
    );
    assert!(!partial.exists(), "the progress file is left behind");
}

/// `--resume` with the progress file of another sweep (a different grid, or a file that is
/// not a progress file) is refused: exit code 2, one line, the progress file untouched.
#[test]
fn resume_refuses_the_progress_of_another_sweep() {
    let dir = tempfile::tempdir().unwrap();
    let partial = interrupted_sweep(dir.path());
    let before = std::fs::read(&partial).unwrap();
    for (range, why) in [
        ("k=1.2:3:0.1", "different sweep"),
        ("k=1.2:3.05:0.05", "different sweep"),
    ] {
        let err = refused_resume(dir.path(), &sweep_args(range, "sweep.csv"));
        assert!(
            err.contains(why) && err.contains("sweep.csv.partial"),
            "{err}"
        );
        assert_eq!(std::fs::read(&partial).unwrap(), before);
        assert!(!dir.path().join("sweep.csv").exists());
    }
    // The same sweep, but a complete line altered: not a row of this sweep.
    let text = String::from_utf8(before.clone()).unwrap();
    let mut lines: Vec<&str> = text.lines().collect();
    let altered = lines[1].replacen(',', ",9", 2);
    lines[1] = &altered;
    std::fs::write(&partial, lines.join("\n") + "\n").unwrap();
    let err = refused_resume(dir.path(), &sweep_args(GRID, "sweep.csv"));
    assert!(err.contains("line 2 is not a row of this sweep"), "{err}");
    // Something that is not a progress file at all.
    std::fs::write(&partial, "run,k\n1,2\n").unwrap();
    refused_resume(dir.path(), &sweep_args(GRID, "sweep.csv"));
    // --resume needs --output.
    refused_resume(dir.path(), &sweep_args(GRID, "x.csv")[..17]);
}

/// Runs `rotorflow ARGS --resume` in `dir`, asserts the refusal (exit 2, exactly one stderr
/// line) and returns that line.
fn refused_resume<S: AsRef<std::ffi::OsStr>>(dir: &std::path::Path, args: &[S]) -> String {
    let out = rotorflow()
        .current_dir(dir)
        .args(args)
        .arg("--resume")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    err
}

/// `--resume` without a progress file runs everything, and a sweep that finishes removes
/// its progress file.
#[test]
fn resume_without_progress_runs_everything() {
    let dir = tempfile::tempdir().unwrap();
    for (csv, extra) in [("a.csv", None), ("b.csv", Some("--resume"))] {
        let out = rotorflow()
            .current_dir(dir.path())
            .args(sweep_args("k=1.2:1.6:0.2", csv))
            .args(extra)
            .output()
            .unwrap();
        assert!(out.status.success());
    }
    let a = std::fs::read(dir.path().join("a.csv")).unwrap();
    assert_eq!(a, std::fs::read(dir.path().join("b.csv")).unwrap());
    let names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.len(), 2, "{names:?}");
}

/// `sweep --output` killed around the moment it writes the table (right after its last run),
/// and at delays over its run: the CSV is absent or equal to an uninterrupted run's.
#[test]
fn killed_sweep_leaves_its_table_whole_or_absent() {
    const SMALL: &str = "k=1.2:2:0.2"; // 5 runs
    let dir = tempfile::tempdir().unwrap();
    let start = Instant::now();
    let out = rotorflow()
        .current_dir(dir.path())
        .args(sweep_args(SMALL, "full.csv"))
        .output()
        .unwrap();
    let run = start.elapsed();
    assert!(out.status.success());
    let full = std::fs::read(dir.path().join("full.csv")).unwrap();
    let check = |dir: &Path, when: &str| -> bool {
        let csv = dir.join("s.csv");
        if csv.exists() {
            assert!(
                std::fs::read(&csv).unwrap() == full,
                "{when}: s.csv is not whole"
            );
            true
        } else {
            false
        }
    };
    let mut args = vec!["--quiet"];
    args.extend(sweep_args(SMALL, "s.csv"));
    let mut outcomes = Vec::new();
    for fraction in [0.1, 0.5, 0.9, 1.0, 1.1] {
        let dir = tempfile::tempdir().unwrap();
        let child = spawn(dir.path(), &args, None);
        std::thread::sleep(run.mul_f64(fraction));
        kill(child);
        outcomes.push(check(
            dir.path(),
            &format!("killed after {fraction} of a run"),
        ));
    }
    // Around the final write: kill as soon as the last run is recorded (the table is written
    // within the next moments; the kill lands before, during or after it).
    for attempt in 0..4 {
        let dir = tempfile::tempdir().unwrap();
        let partial = dir.path().join("s.csv.partial");
        let csv = dir.path().join("s.csv");
        let child = spawn(dir.path(), &args, None);
        let seen = wait_until(|| finished_rows(&partial) == 5 || csv.exists());
        kill(child);
        assert!(seen, "the sweep did not finish its runs");
        let there = check(
            dir.path(),
            &format!("killed at the final write ({attempt})"),
        );
        // The progress file goes only after the table is there.
        assert!(there || finished_rows(&partial) == 5);
        outcomes.push(there);
    }
    eprintln!("kill outcomes (s.csv there): {outcomes:?}");
    assert!(!outcomes[0]);
}
