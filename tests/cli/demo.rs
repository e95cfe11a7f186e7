//! `rotorflow demo`: runs end to end and writes every promised file.

use super::rotorflow;
use std::time::Instant;

#[test]
fn demo_writes_every_promised_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let clock = Instant::now();
    rotorflow()
        .args(["demo", "--out"])
        .arg(&out)
        .assert()
        .success();
    eprintln!(
        "demo took {:.1} s (test profile)",
        clock.elapsed().as_secs_f64()
    );
    for file in promised_files() {
        let path = out.join(&file);
        let meta = std::fs::metadata(&path).unwrap_or_else(|_| panic!("{file} missing"));
        assert!(meta.len() > 200, "{file} is nearly empty");
        let text = std::fs::read_to_string(&path).unwrap();
        if file.ends_with(".svg") {
            assert!(text.starts_with("<svg"), "{file} is not SVG");
        }
        if file.ends_with(".html") {
            assert!(
                text.contains("<canvas") && !text.contains("https://"),
                "{file}"
            );
        }
    }
    let summary = std::fs::read_to_string(out.join("summary.md")).unwrap();
    for needle in [
        "tesseract",
        "5-cell",
        "solid cuboid",
        "solid ellipsoid",
        "§7.1",
        "§7.2",
        "§7.3",
        "3D asymmetric top",
        "numeric vs exact",
        "energy drift",
        "time (s)",
        "dopri5",
        "sweep.svg",
    ] {
        assert!(
            summary.contains(needle),
            "summary lacks {needle}:\n{summary}"
        );
    }
    // Nothing but the promised files.
    let count = std::fs::read_dir(&out).unwrap().count();
    assert_eq!(count, promised_files().len());
    // The omega plots use the paper's names.
    let plot = std::fs::read_to_string(out.join("omega_tesseract.svg")).unwrap();
    assert!(plot.contains("ω₁₂") && plot.contains("ω₃₄"));
    let plot = std::fs::read_to_string(out.join("omega_top_3d.svg")).unwrap();
    assert!(plot.contains("ω₂₃"));
}

/// The files `rotorflow demo` promises (its help and the book's reference list them).
fn promised_files() -> Vec<String> {
    let cases = [
        "tesseract",
        "pentachoron",
        "cuboid",
        "ellipsoid",
        "section_7_1",
        "section_7_2",
        "section_7_3",
        "top_3d",
    ];
    let mut files: Vec<String> = cases
        .iter()
        .flat_map(|c| {
            [
                format!("omega_{c}.svg"),
                format!("drift_{c}.svg"),
                format!("{c}.html"),
            ]
        })
        .collect();
    for f in [
        "tesseract_frames.svg",
        "sweep.svg",
        "sweep.csv",
        "summary.md",
    ] {
        files.push(f.to_string());
    }
    files
}
