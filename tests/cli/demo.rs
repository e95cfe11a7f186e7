//! `rotorflow demo`: runs end to end, writes every promised file, and its summary's numbers
//! are within the bounds its method allows (the paper's cases and the five scenes).

use super::rotorflow;
use std::time::Instant;

/// The cases of the demo, each with an ω plot, a drift plot and an animation.
const CASES: [&str; 8] = [
    "tesseract",
    "pentachoron",
    "cuboid",
    "ellipsoid",
    "section_7_1",
    "section_7_2",
    "section_7_3",
    "top_3d",
];

/// The scenes of the demo (files of `scenes/`), each with an animation and a plot of its
/// energy and momenta.
const SCENES: [&str; 5] = [
    "tesseract_spring",
    "ball_rolling",
    "five_cell_slope",
    "newtons_cradle",
    "stacked_hypercubes",
];

/// Every file `demo` promises (its help and the book's CLI chapter list them).
fn promised_files() -> Vec<String> {
    let mut files: Vec<String> = CASES
        .iter()
        .flat_map(|c| {
            [
                format!("omega_{c}.svg"),
                format!("drift_{c}.svg"),
                format!("{c}.html"),
            ]
        })
        .collect();
    for s in SCENES {
        files.push(format!("{s}.html"));
        files.push(format!("energy_{s}.svg"));
    }
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

/// The rows of the summary's case table, as cells keyed by the header's column names.
fn case_table(summary: &str) -> Vec<std::collections::HashMap<String, String>> {
    let cells = |line: &str| -> Vec<String> {
        let inner = line.trim().trim_start_matches('|').trim_end_matches('|');
        inner.split(" | ").map(|c| c.trim().to_string()).collect()
    };
    let mut lines = summary.lines().skip_while(|l| !l.starts_with("| case |"));
    let header = cells(lines.next().expect("the case table"));
    lines
        .skip(1)
        .take_while(|l| l.starts_with('|'))
        .map(|l| header.iter().cloned().zip(cells(l)).collect())
        .collect()
}

#[test]
fn demo_writes_every_promised_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let clock = Instant::now();
    rotorflow()
        .args(["demo", "--output-dir"])
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
    check_numbers(&summary);
    check_scenes(&summary);
    // Nothing but the promised files.
    let count = std::fs::read_dir(&out).unwrap().count();
    assert_eq!(count, promised_files().len());
    // The omega plots use the paper's names.
    let plot = std::fs::read_to_string(out.join("omega_tesseract.svg")).unwrap();
    assert!(plot.contains("ω₁₂") && plot.contains("ω₃₄"));
    let plot = std::fs::read_to_string(out.join("omega_top_3d.svg")).unwrap();
    assert!(plot.contains("ω₂₃"));
}

/// The numbers of the case table. The demo integrates with Yoshida's 4th-order splitting at
/// h = 0.005 (the summary says so); the bounds are derived from that method:
/// - energy: a symplectic method keeps a modified energy, so T stays within O(h⁴) of its
///   start without drift; measured at most 6.4e-12 (the 3D top) = 0.010·h⁴; bound 3× that.
/// - Casimirs: every sub-flow rotates L exactly, so only round-off moves them: at most about
///   one ε per step (measured at most 5.5e-14 over 12 000 steps; bound steps·ε ≈ 2.7e-12).
/// - numeric vs exact (the cases with a closed form): the global error of a 4th-order method,
///   O(h⁴)·t with a constant of the case; measured 6.4e-11 (§7.1), 5.6e-11 (§7.2),
///   1.1e-10 (§7.3), 1.6e-9 (3D top, amplified near its unstable intermediate axis);
///   bounds 3× those. The other cases have no closed form and say why ("n/a [k]").
fn check_numbers(summary: &str) {
    assert!(summary.contains("Yoshida-4") && summary.contains("(step 0.005)"));
    let rows = case_table(summary);
    assert_eq!(rows.len(), CASES.len(), "{summary}");
    let number = |row: &std::collections::HashMap<String, String>, column: &str| -> f64 {
        let cell = row
            .get(column)
            .unwrap_or_else(|| panic!("no column {column}"));
        cell.parse()
            .unwrap_or_else(|_| panic!("{column}: `{cell}` is not a number"))
    };
    let exact_bounds = [
        ("§7.1", 2e-10),
        ("§7.2", 2e-10),
        ("§7.3", 4e-10),
        ("3D asymmetric top", 5e-9),
    ];
    for row in &rows {
        let case = &row["case"];
        let steps = number(row, "steps");
        let energy = number(row, "energy drift");
        assert!(energy < 2e-11, "{case}: energy drift {energy:e}");
        let casimirs = number(row, "Casimir drift");
        assert!(
            casimirs < steps * f64::EPSILON,
            "{case}: Casimir drift {casimirs:e} over {steps} steps"
        );
        let column = "numeric vs exact: max abs(Δω)";
        match exact_bounds.iter().find(|(title, _)| case.contains(title)) {
            Some((_, bound)) => {
                let deviation = number(row, column);
                assert!(
                    deviation < *bound,
                    "{case}: |Δω| = {deviation:e} (bound {bound:e})"
                );
            }
            None => assert!(row[column].starts_with("n/a ["), "{case}: {}", row[column]),
        }
    }
    for (title, _) in exact_bounds {
        assert!(
            rows.iter().any(|r| r["case"].contains(title)),
            "no row {title}"
        );
    }
}

/// The number after `label` in `text` (up to the next space, `;` or `)`).
fn number_after(text: &str, label: &str) -> f64 {
    let start = text
        .find(label)
        .unwrap_or_else(|| panic!("no `{label}` in {text}"))
        + label.len();
    let rest = text[start..].trim_start();
    let end = rest.find([' ', ';', ')']).unwrap_or(rest.len());
    rest[..end]
        .parse()
        .unwrap_or_else(|_| panic!("`{}` after `{label}` is not a number", &rest[..end]))
}

/// The scene table: one row per scene with its measured figures.
/// - the tesseract on a spring: the splitting's energy error is bounded (measured 1.05e-4
///   at dt = 0.002), and the angular momentum about the anchor in the horizontal planes is
///   kept to round-off;
/// - the ball: the rolling speed v0 (N + 2)/(N + 4) to 1e-6 (measured 1.5e-15);
/// - the 5-cell: most of the energy lost, no vertex below a plane beyond the contact
///   tolerance;
/// - Newton's cradle: the last ball leaves at nearly the first one's speed (measured
///   0.9907 m/s) while the others stay (measured 5.8e-5 m/s), the energy kept to 2e-2
///   (measured 9.2e-3: the impacts of balls held by joints lose a little);
/// - the stacked hypercubes: the top one ends within 1e-6 of its resting place, at rest.
fn check_scenes(summary: &str) {
    let section = &summary[summary.find("## Scenes").expect("a section Scenes")..];
    let row = |title: &str| -> &str {
        section
            .lines()
            .find(|l| l.starts_with(&format!("| {title}")))
            .unwrap_or_else(|| panic!("no row {title}:\n{section}"))
    };
    let spring = row("4D tesseract hanging by a corner from a spring");
    assert!(spring.contains("scenes/tesseract-spring.toml"), "{spring}");
    assert!(
        number_after(spring, "abs(ΔE)/abs(E(0)) =") < 2e-4,
        "{spring}"
    );
    assert!(number_after(spring, "max change") < 1e-12, "{spring}");
    let ball = row("solid 4D ball sliding into rolling");
    assert!(ball.contains("v0·(N+2)/(N+4) = 1.5"), "{ball}");
    assert!(number_after(ball, "relative error") < 1e-6, "{ball}");
    let slope = row("5-cell bouncing down a slope");
    let lost = number_after(slope, "(zero on the floor):");
    assert!(lost > 50.0 && lost < 100.0, "{slope}");
    assert!(
        number_after(slope, "lowest vertex over all samples") >= -1e-9,
        "{slope}"
    );
    assert!(
        slope.contains("never deeper than the contact tolerance"),
        "{slope}"
    );
    let cradle = row("Newton's cradle in 4D");
    let leaves = number_after(cradle, "the last ball leaves at");
    assert!(leaves > 0.98 && leaves <= 1.0, "{cradle}");
    assert!(
        number_after(cradle, "the other balls move at") < 6e-4,
        "{cradle}"
    );
    assert!(number_after(cradle, "energy kept to") < 2e-2, "{cradle}");
    let stack = row("three 4D hypercubes stacked");
    assert!(
        number_after(stack, "the top hypercube ends").abs() < 1e-6,
        "{stack}"
    );
    assert!(number_after(stack, "below and").abs() < 1e-6, "{stack}");
    assert!(
        number_after(stack, "the fastest body moves at") < 1e-6,
        "{stack}"
    );
    for s in SCENES {
        assert!(section.contains(&format!("({s}.html)")), "{s}");
        assert!(section.contains(&format!("(energy_{s}.svg)")), "{s}");
    }
}
