//! Integration tests of the `rotorflow` command: each test runs the binary, as a user would.
#![cfg(feature = "cli")]

mod bad_input;
mod demo;
mod exact;
mod inertia;
mod memory;
mod no_lost_output;
mod options;
mod render;
mod scene;
mod scene_library;
mod simulate;
mod sweep;

use assert_cmd::Command;
use serde_json::Value;

/// Returns the command, quiet (no progress bar).
pub fn rotorflow() -> Command {
    let mut cmd = Command::cargo_bin("rotorflow").expect("the rotorflow binary is built");
    cmd.arg("--quiet");
    cmd
}

/// Runs the command, checks it succeeds, and parses standard output as JSON.
pub fn run_json(args: &[&str]) -> Value {
    let out = rotorflow().args(args).output().expect("rotorflow runs");
    assert!(
        out.status.success(),
        "rotorflow {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("stdout is JSON")
}

/// Returns the numbers of a JSON array.
pub fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap_or_else(|| panic!("not an array: {v}"))
        .iter()
        .map(|x| x.as_f64().unwrap_or_else(|| panic!("not a number: {x}")))
        .collect()
}

/// Returns the rows of a JSON matrix.
pub fn matrix(v: &Value) -> Vec<Vec<f64>> {
    v.as_array()
        .unwrap_or_else(|| panic!("not an array: {v}"))
        .iter()
        .map(floats)
        .collect()
}

/// Asserts |a − b| ≤ tol · max(1, |b|) element by element.
#[track_caller]
pub fn assert_close(a: &[f64], b: &[f64], tol: f64) {
    assert_eq!(a.len(), b.len(), "lengths differ: {a:?} vs {b:?}");
    for (k, (x, y)) in a.iter().zip(b).enumerate() {
        assert!(
            (x - y).abs() <= tol * y.abs().max(1.0),
            "element {k}: {x} vs {y} (tolerance {tol})\n{a:?}\n{b:?}"
        );
    }
}

/// Asserts that the JSON rows `rows` equal the matrix `m` within `tol` (relative to max(1, |m|)).
#[track_caller]
pub fn assert_matrix_close(rows: &[Vec<f64>], m: &nalgebra::DMatrix<f64>, tol: f64) {
    assert_eq!(rows.len(), m.nrows(), "row counts differ");
    for (r, row) in rows.iter().enumerate() {
        assert_close(row, &m.row(r).iter().copied().collect::<Vec<_>>(), tol);
    }
}
