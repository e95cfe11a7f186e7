//! Options shared by several subcommands: `--output` (its name and the format its file name
//! implies; the old names are gone), `--axial` in 3D, points files with a header, the sweep's documented columns.

use super::{assert_close, floats, matrix, rotorflow, run_json};

/// Runs `args` in `dir` and returns standard output; the run must succeed.
fn run_in(dir: &std::path::Path, args: &[&str]) -> String {
    let out = rotorflow().current_dir(dir).args(args).output().unwrap();
    assert!(
        out.status.success(),
        "rotorflow {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn output_format_follows_the_file_name() {
    let dir = tempfile::tempdir().unwrap();
    let sim = [
        "simulate",
        "--body",
        "cuboid:1,2,3",
        "--omega",
        "0.1,1,0.2",
        "--t-end",
        "1",
        "--samples",
        "3",
    ];
    for (name, check) in [
        ("r.json", "json"),
        ("r.csv", "csv"),
        ("r.txt", "text"),
        ("r.md", "text"),
        ("r", "text"),
    ] {
        let mut args = sim.to_vec();
        args.extend(["--output", name]);
        assert!(run_in(dir.path(), &args).is_empty());
        let text = std::fs::read_to_string(dir.path().join(name)).unwrap();
        match check {
            "json" => {
                let v: serde_json::Value = serde_json::from_str(&text).unwrap();
                assert_eq!(floats(&v["times"]), vec![0.0, 0.5, 1.0]);
            }
            "csv" => {
                assert!(text.starts_with("t,"), "{text}");
                assert_eq!(text.lines().count(), 4, "{text}");
            }
            _ => {
                assert!(serde_json::from_str::<serde_json::Value>(&text).is_err());
                assert!(!text.starts_with("t,"), "{text}");
            }
        }
    }
    // A flag that agrees with the name, and the inertia report.
    let mut args = sim.to_vec();
    args.extend(["--json", "--output", "a.json"]);
    run_in(dir.path(), &args);
    run_in(
        dir.path(),
        &["inertia", "--body", "cuboid:1,2,3", "--output", "i.json"],
    );
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("i.json")).unwrap()).unwrap();
    assert_eq!(v["dim"].as_u64(), Some(3));
}

#[test]
fn render_takes_output_and_demo_output_dir_without_the_old_names() {
    let help = run_in(std::path::Path::new("."), &["render", "--help"]);
    assert!(help.contains("--output <FILE>"), "{help}");
    let help = run_in(std::path::Path::new("."), &["demo", "--help"]);
    assert!(help.contains("--output-dir <DIR>"), "{help}");
    let dir = tempfile::tempdir().unwrap();
    let render = |flag: &str, name: &str| {
        rotorflow()
            .current_dir(dir.path())
            .args([
                "render",
                "--body",
                "cuboid:1,2,3",
                "--omega",
                "0.1,1,0.2",
                "--t-end",
                "1",
                "--frames",
                "2",
                flag,
                name,
            ])
            .output()
            .unwrap()
    };
    assert!(render("--output", "a.svg").status.success());
    let svg = std::fs::read_to_string(dir.path().join("a.svg")).unwrap();
    assert!(svg.starts_with("<svg"));
    // The old names are gone, not aliases: exit 2, one line, no file.
    let old = [
        vec!["render", "--out", "b.svg"],
        vec!["demo", "--out", "d"],
        vec!["demo", "--output", "d"],
        vec!["scene", "x.toml", "--out", "b.json"],
        vec!["scene", "x.toml", "--csv", "d"],
        vec!["sweep", "--csv", "b.csv"],
    ];
    for args in &old {
        let out = if args[0] == "render" {
            render(args[1], args[2])
        } else {
            rotorflow()
                .current_dir(dir.path())
                .args(args)
                .output()
                .unwrap()
        };
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains("unexpected argument"), "{args:?}: {err}");
    }
    let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(names.len(), 1, "only a.svg is written");
}

/// The axial vector (x, y, z) is x e₂∧e₃ + y e₃∧e₁ + z e₁∧e₂: the components 12, 13, 23 are
/// (z, −y, x). A spin about +z is ω₁₂ > 0, which turns e₁ towards e₂ (right-hand rule).
#[test]
fn axial_vectors_in_3d_follow_the_right_hand_rule() {
    let base = [
        "simulate",
        "--body",
        "cuboid:1,2,3",
        "--t-end",
        "0.1",
        "--samples",
        "2",
        "--json",
    ];
    let run = |extra: &[&str]| {
        let mut args = base.to_vec();
        args.extend(extra);
        run_json(&args)
    };
    let v = run(&["--axial", "--omega", "0,0,1"]);
    assert_close(&matrix(&v["omega"])[0], &[1.0, 0.0, 0.0], 0.0);
    // A spin about +z (principal axis, so it stays steady) for t = 0.1 turns e₁ by +0.1
    // towards e₂: the attitude's column 1 is (cos 0.1, sin 0.1, 0).
    let attitude = matrix(&v["attitude"][1]);
    let e1 = [attitude[0][0], attitude[1][0], attitude[2][0]];
    assert_close(&e1, &[0.1f64.cos(), 0.1f64.sin(), 0.0], 1e-9);
    // A general vector, and the momentum: L = (x, y, z) axial is (z, −y, x).
    let v = run(&["--axial", "--omega", "0.3,-0.5,0.7"]);
    assert_close(&matrix(&v["omega"])[0], &[0.7, 0.5, 0.3], 1e-15);
    let v = run(&["--axial", "--momentum", "1,2,3"]);
    assert_close(&matrix(&v["momentum"])[0], &[3.0, -2.0, 1.0], 1e-15);
    // A constant body torque about +x (axial) is τ₂₃ = 1: from rest the body turns about
    // +x alone, ω₂₃(t) = t τ₂₃ / I₁ with I₁ = J₂ + J₃ = m (2² + 3²)/3 = 208 (m = 48).
    let v = run(&["--axial", "--omega", "0,0,0", "--torque", "body:1,0,0"]);
    let w = matrix(&v["omega"])[1].clone();
    assert_close(&w, &[0.0, 0.0, 0.1 / 208.0], 1e-12);
    // The help says how the two relate.
    let help = run_in(std::path::Path::new("."), &["simulate", "--help"]);
    assert!(help.contains("(ω₁₂, ω₁₃, ω₂₃) = (z, −y, x)"), "{help}");
}

#[test]
fn points_files_may_have_a_header_and_an_index_column() {
    let dir = tempfile::tempdir().unwrap();
    let plain = "1,1,0,0\n1,-1,0,0\n2,0,1,0\n2,0,-1,0\n1,0,0,2\n1,0,0,-2\n";
    let pandas = ",m,x,y,z\n0,1,1,0,0\n1,1,-1,0,0\n2,2,0,1,0\n3,2,0,-1,0\n4,1,0,0,2\n5,1,0,0,-2\n";
    let named = format!("m,x,y,z\n{plain}");
    let mut reports = Vec::new();
    for (name, text) in [
        ("plain.csv", plain),
        ("pandas.csv", pandas),
        ("named.csv", named.as_str()),
    ] {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        let spec = format!("points:{}", path.display());
        reports.push(run_json(&["inertia", "--body", &spec, "--json"]));
    }
    // J = Σ m x xᵀ = diag(2, 4, 8).
    assert_close(
        &floats(&reports[0]["second_moments"]),
        &[2.0, 4.0, 8.0],
        1e-12,
    );
    for r in &reports[1..] {
        assert_eq!(r["mass_tensor"], reports[0]["mass_tensor"]);
        assert_eq!(r["mass"], reports[0]["mass"]);
    }
}

#[test]
fn sweep_help_lists_the_csv_columns() {
    let help = run_in(std::path::Path::new("."), &["sweep", "--help"]);
    for column in [
        "run",
        "freq_ab",
        "amp_ab",
        "mean_ab",
        "flips",
        "first_flip",
        "energy_drift",
        "casimir_drift",
    ] {
        assert!(help.contains(column), "sweep --help lacks {column}");
    }
}
