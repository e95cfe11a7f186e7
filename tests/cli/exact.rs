//! `rotorflow exact`: the closed forms, in the same shape as `simulate`, and their agreement
//! with the integrators.

use super::{assert_close, floats, matrix, rotorflow, run_json};

/// The closed-form cases: N = 3 (any body), and any N with at most two distinct principal
/// moments (the paper's §7.1–7.3 in 4D).
const CASES: [(&str, &str); 5] = [
    ("ellipsoid:1,2,3", "0.01,1,0.01"),
    ("tesseract:1,1,1,1", "0.3,0.4,0.2,0.5,0.1,0.3"),
    ("tesseract:1,1,1,1.5", "0.3,0.4,0.2,0.5,0.1,0.3"),
    ("tesseract:1,1,1.5,1.5", "1,0.2,0.3,0.1,0.25,0.6"),
    (
        "principal:1,1,2,2,2",
        "0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9,1",
    ),
];

#[test]
fn exact_has_the_simulate_shape() {
    let out = rotorflow()
        .args([
            "exact",
            "--body",
            "tesseract:1,1,1,1.5",
            "--omega",
            "0.3,0.4,0.2,0.5,0.1,0.3",
            "--t-end",
            "2",
            "--samples",
            "3",
            "--json",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for k in [
        "dim", "times", "omega", "momentum", "energy", "casimirs", "attitude", "drift",
    ] {
        assert!(v.get(k).is_some(), "key {k} missing");
    }
    assert_eq!(floats(&v["times"]).len(), 3);
}

#[test]
fn exact_refuses_a_body_without_closed_form() {
    let out = rotorflow()
        .args([
            "exact",
            "--body",
            "tesseract:1,1.2,1.5,2",
            "--omega",
            "1,0.5,0,0,0.3,1",
            "--t-end",
            "1",
            "--samples",
            "2",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("no closed-form solution"), "{err}");
    assert!(out.stdout.is_empty());
}

#[test]
fn exact_agrees_with_simulate_on_closed_form_cases() {
    for (body, omega) in CASES {
        let common = [
            "--body",
            body,
            "--omega",
            omega,
            "--t-end",
            "20",
            "--samples",
            "41",
            "--json",
        ];
        let exact = run_json(&[&["exact"][..], &common[..]].concat());
        let numeric = run_json(
            &[
                &["simulate"][..],
                &common[..],
                &[
                    "--integrator",
                    "dopri5",
                    "--rtol",
                    "1e-12",
                    "--atol",
                    "1e-14",
                ][..],
            ]
            .concat(),
        );
        for key in ["omega", "momentum"] {
            let (a, b) = (matrix(&exact[key]), matrix(&numeric[key]));
            for k in 0..a.len() {
                assert_close(&a[k], &b[k], 1e-7);
            }
        }
        assert_close(&floats(&exact["energy"]), &floats(&numeric["energy"]), 1e-9);
        for k in 0..41 {
            let (a, b) = (
                matrix(&exact["attitude"][k]),
                matrix(&numeric["attitude"][k]),
            );
            for r in 0..a.len() {
                assert_close(&a[r], &b[r], 1e-6);
            }
        }
    }
}
