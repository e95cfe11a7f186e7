//! `rotorflow sweep`: the grid, shards that concatenate to the whole, observables, plot.

use super::rotorflow;

fn sweep_csv(extra: &[&str]) -> String {
    let mut args = vec![
        "sweep",
        "--body",
        "tesseract:1,1,1,{k}",
        "--param",
        "k=1.2:2:0.2",
        "--omega",
        "0.3,0.4,0.2,0.5,0.1,0.3",
        "--t-end",
        "200",
        "--samples",
        "2001",
        "--axes",
        "2,3,4",
        "--integrator",
        "yoshida4",
        "--dt",
        "0.01",
    ];
    args.extend(extra);
    let out = rotorflow().args(&args).output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn column(csv: &str, name: &str) -> Vec<f64> {
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let k = header
        .iter()
        .position(|h| *h == name)
        .unwrap_or_else(|| panic!("no column {name}"));
    lines
        .map(|l| l.split(',').nth(k).unwrap().parse().unwrap())
        .collect()
}

#[test]
fn sweep_reports_one_row_per_grid_point() {
    let csv = sweep_csv(&[]);
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 1 + 5, "{csv}");
    assert!(lines[0].starts_with("run,k,freq_23,amp_23,mean_23,freq_24"));
    assert!(lines[0].ends_with("flips,first_flip,energy_drift,casimir_drift"));
    assert_eq!(column(&csv, "k"), vec![1.2, 1.4, 1.6, 1.8, 2.0]);
}

#[test]
fn sweep_observed_frequency_follows_section_7_2() {
    // Three equal moments and κ: ω₂₃ is constant, ω₂₄ and ω₃₄ turn at
    // (κ² − 1)/(κ² + 1) · √(ω₁₂² + ω₁₃² + ω₂₃²) (the paper's eq. 119, J ∝ a²).
    let csv = sweep_csv(&[]);
    let c = (0.3f64 * 0.3 + 0.4 * 0.4 + 0.5 * 0.5).sqrt();
    for (k, f) in column(&csv, "k").iter().zip(column(&csv, "freq_24")) {
        let expected = (k * k - 1.0) / (k * k + 1.0) * c;
        assert!(
            (f - expected).abs() < 0.02 * expected,
            "κ = {k}: {f} vs {expected}"
        );
    }
    assert!(column(&csv, "amp_23").iter().all(|a| *a < 1e-9));
}

#[test]
fn sweep_shards_concatenate_to_the_whole() {
    let whole = sweep_csv(&[]);
    let parts: String = (1..=3)
        .map(|i| sweep_csv(&["--shard", &format!("{i}/3")]))
        .collect();
    assert_eq!(parts, whole);
}

#[test]
fn sweep_grid_of_two_parameters_writes_csv_and_plot() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("grid.csv");
    let svg = dir.path().join("grid.svg");
    rotorflow()
        .args([
            "sweep",
            "--body",
            "ellipsoid:1,{b},{c}",
            "--param",
            "b=1.5:2.5:0.5",
            "--param",
            "c=3:4:1",
            "--omega",
            "0.02,1,0.01",
            "--t-end",
            "40",
            "--samples",
            "401",
            "--output",
        ])
        .arg(&csv)
        .arg("--plot")
        .arg(&svg)
        .assert()
        .success();
    let text = std::fs::read_to_string(&csv).unwrap();
    assert_eq!(text.lines().count(), 1 + 6);
    assert_eq!(column(&text, "run"), vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0]);
    assert_eq!(column(&text, "b"), vec![1.5, 1.5, 2.0, 2.0, 2.5, 2.5]);
    assert_eq!(column(&text, "c"), vec![3.0, 4.0, 3.0, 4.0, 3.0, 4.0]);
    // The intermediate axis flips: rotation about e2 (plane 13) is unstable.
    assert!(column(&text, "flips").iter().all(|f| *f >= 1.0), "{text}");
    let plot = std::fs::read_to_string(&svg).unwrap();
    assert!(plot.contains("ω₁₃") && plot.contains("against the parameter b"));
}

#[test]
fn sweep_reports_the_drift_of_the_manakov_integrals() {
    let csv = sweep_csv(&[]);
    let manakov = column(&csv, "manakov_drift");
    assert_eq!(manakov.len(), 5);
    for m in manakov {
        // A physical body has them; the default integrator keeps them to its accuracy.
        assert!(m > 0.0 && m < 1e-6, "manakov_drift {m:e}");
    }
}
