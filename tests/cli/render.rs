//! `rotorflow render`: a self-contained HTML animation (checked in headless Chromium) and an
//! SVG strip of frames.

use super::rotorflow;
use std::path::{Path, PathBuf};
use std::process::Command;

fn render(dir: &Path, name: &str, extra: &[&str]) -> PathBuf {
    let out = dir.join(name);
    let mut cmd = rotorflow();
    cmd.args([
        "render",
        "--body",
        "tesseract:1,1.2,1.5,2",
        "--omega",
        "1,0.05,0.02,0.03,0.04,0.7",
        "--t-end",
        "20",
        "--output",
    ])
    .arg(&out)
    .args(extra);
    cmd.assert().success();
    out
}

#[test]
fn render_html_is_self_contained_with_controls() {
    let dir = tempfile::tempdir().unwrap();
    let page = std::fs::read_to_string(render(dir.path(), "a.html", &[])).unwrap();
    assert!(page.starts_with("<!DOCTYPE html>"));
    for needle in [
        "<canvas",
        "id=\"play\"",
        "type=\"range\"",
        "id=\"axes\"",
        "id=\"projection\"",
        "pointermove",
    ] {
        assert!(page.contains(needle), "page lacks {needle}");
    }
    // Nothing is loaded from the network.
    for needle in ["http://", "https://", "<link", "src="] {
        assert!(!page.contains(needle), "page refers to {needle}");
    }
}

#[test]
fn render_svg_is_a_strip_of_frames() {
    let dir = tempfile::tempdir().unwrap();
    let svg = std::fs::read_to_string(render(
        dir.path(),
        "a.svg",
        &[
            "--frames",
            "5",
            "--projection",
            "orthographic",
            "--axes",
            "2,3,4",
        ],
    ))
    .unwrap();
    assert!(svg.starts_with("<svg"));
    assert_eq!(svg.matches("t = ").count(), 5);
    // 16 vertices and 32 edges per frame.
    assert_eq!(svg.matches("<circle").count(), 5 * 16);
    assert_eq!(svg.matches("<line").count(), 5 * 32);
    assert!(svg.contains("axes 2,3,4 (orthographic)"));
}

#[test]
fn render_solids_and_2d_bodies() {
    let dir = tempfile::tempdir().unwrap();
    for (i, (body, omega)) in [
        ("ellipsoid:1,2,3,4", "1,0,0,0,0,1"),
        ("sphere:3,1", "0,0,1"),
        ("cuboid:1,2", "1"),
        ("planes:1,2,3", "1,0,0"),
    ]
    .iter()
    .enumerate()
    {
        let out = dir.path().join(format!("{i}.html"));
        rotorflow()
            .args([
                "render", "--body", body, "--omega", omega, "--t-end", "3", "--frames", "20",
                "--output",
            ])
            .arg(&out)
            .assert()
            .success();
        assert!(std::fs::metadata(&out).unwrap().len() > 1000);
    }
}

/// Returns a Chromium that runs, or None (with a loud message) when there is none and the run
/// is local. Under CI (the `CI` variable set and not "false", as every CI service sets it) a
/// missing browser is a failure: the check this test exists for would otherwise pass unseen.
pub fn chromium() -> Option<String> {
    let candidates = [
        std::env::var("ROTORFLOW_CHROMIUM").unwrap_or_default(),
        "chromium".into(),
        "chromium-browser".into(),
        "google-chrome".into(),
    ];
    for c in candidates.iter().filter(|c| !c.is_empty()) {
        if Command::new(c)
            .arg("--version")
            .output()
            .is_ok_and(|o| o.status.success())
        {
            return Some(c.clone());
        }
    }
    let under_ci = std::env::var("CI").is_ok_and(|v| !v.is_empty() && v != "false" && v != "0");
    assert!(
        !under_ci,
        "no runnable Chromium under CI (tried {candidates:?}): install Debian's `chromium` \
         (.ci/run does) or point ROTORFLOW_CHROMIUM at a browser"
    );
    eprintln!(
        "\n!!!!!!!! SKIPPED (local run, CI unset): no runnable Chromium (install Debian's \
         `chromium`; .ci/run does) — the HTML animation was NOT checked in a browser !!!!!!!!\n"
    );
    None
}

pub fn chromium_command(browser: &str, profile: &Path) -> Command {
    let mut cmd = Command::new(browser);
    cmd.args([
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--hide-scrollbars",
        "--no-first-run",
        "--window-size=800,760",
        "--virtual-time-budget=3000",
    ])
    .arg(format!("--user-data-dir={}", profile.display()));
    cmd
}

#[test]
fn render_html_draws_and_animates_in_headless_chromium() {
    let Some(browser) = chromium() else { return };
    let dir = tempfile::tempdir().unwrap();
    let page = render(dir.path(), "tesseract.html", &[]);
    let url = format!("file://{}", page.display());
    let (report, log) = selftest(&browser, &page, &dir.path().join("profile-dom"));
    assert_eq!(report["frames"].as_u64(), Some(300));
    assert!(
        report["nonblank_first"].as_u64().unwrap() > 1000,
        "{report}"
    );
    assert!(
        report["nonblank_later"].as_u64().unwrap() > 1000,
        "{report}"
    );
    assert!(
        report["changed"].as_u64().unwrap() > 100,
        "frames do not differ: {report}"
    );
    assert_eq!(
        report["errors"].as_array().map(Vec::len),
        Some(0),
        "{report}"
    );
    for line in log.lines() {
        assert!(!line.contains("Uncaught"), "script error: {line}");
        assert!(
            !(line.contains("CONSOLE") && (line.contains("ERROR") || line.contains("WARNING"))),
            "console message: {line}"
        );
    }
    // A screenshot of the running animation, kept as a CI artefact.
    let artefacts = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/cli-artifacts");
    std::fs::create_dir_all(&artefacts).unwrap();
    let shot = artefacts.join("animation.png");
    let _ = std::fs::remove_file(&shot);
    let status = chromium_command(&browser, &dir.path().join("profile-shot"))
        .arg(format!("--screenshot={}", shot.display()))
        .arg(&url)
        .output()
        .expect("chromium runs");
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
    let png = std::fs::read(&shot).expect("screenshot written");
    assert!(
        png.len() > 5000 && png.starts_with(b"\x89PNG"),
        "bad screenshot"
    );
}

/// The selftest report of the page `page` opened in headless Chromium, and the browser's
/// log.
fn selftest(browser: &str, page: &Path, profile: &Path) -> (serde_json::Value, String) {
    let out = chromium_command(browser, profile)
        .args(["--enable-logging=stderr", "--v=0", "--dump-dom"])
        .arg(format!("file://{}#selftest", page.display()))
        .output()
        .expect("chromium runs");
    let dom = String::from_utf8_lossy(&out.stdout);
    let log = String::from_utf8_lossy(&out.stderr).into_owned();
    let start = dom
        .find("<pre id=\"selftest\"")
        .unwrap_or_else(|| panic!("no selftest in DOM:\n{dom}\n{log}"));
    let json_start = start + dom[start..].find('>').unwrap() + 1;
    let json_end = json_start + dom[json_start..].find("</pre>").unwrap();
    let report = serde_json::from_str(&dom[json_start..json_end]).unwrap_or_else(|e| {
        panic!(
            "selftest did not run ({e}):\n{}\n{log}",
            &dom[start..json_end]
        )
    });
    (report, log)
}

/// A ball dropped on a floor (`z0` its height) and a box flying past, as a scene file.
fn dropped_ball(z0: f64) -> String {
    format!(
        "dim = 3\ngravity = [0, 0, -9.81]\nt_end = 1.5\ndt = 0.005\n\
         [[body]]\nname = \"ball\"\nshape = \"ball:3,0.3\"\nposition = [0, 0, {z0}]\n\
         velocity = [0.5, 0, 0]\n\
         [[body]]\nname = \"box\"\nshape = \"cuboid:0.2,0.2,0.2\"\nposition = [-2, 0, 30]\n\
         velocity = [1, 0, 0]\ncollide = false\n\
         [[plane]]\nnormal = [0, 0, 1]\noffset = 0\nfriction = 0.3\nrestitution = 0.5\n"
    )
}

/// The scene page marks every contact the run recorded: the markers the browser drew over
/// all frames are the contacts of the JSON written by the same run, and a run without
/// contacts draws none.
#[test]
fn scene_html_marks_the_contacts_of_a_colliding_scene_in_headless_chromium() {
    let Some(browser) = chromium() else { return };
    let mut checked = 0;
    for (z0, colliding) in [(1.0, true), (20.0, false)] {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("scene.toml"), dropped_ball(z0)).unwrap();
        rotorflow()
            .current_dir(dir.path())
            .args(["scene", "scene.toml", "--samples", "61"])
            .args(["--output", "run.json", "--html", "run.html"])
            .assert()
            .success();
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.path().join("run.json")).unwrap())
                .unwrap();
        let contacts = json["contacts"].as_array().expect("a contacts key");
        assert_eq!(contacts.len(), 61);
        let total: usize = contacts.iter().map(|c| c.as_array().unwrap().len()).sum();
        let frames = contacts
            .iter()
            .filter(|c| !c.as_array().unwrap().is_empty())
            .count();
        // The ball lands at t = √(2 · 0.7 / 9.81) ≈ 0.38 and settles on the floor.
        assert_eq!(frames > 10, colliding, "{frames} frames with contacts");
        let (report, log) = selftest(
            &browser,
            &dir.path().join("run.html"),
            &dir.path().join("profile"),
        );
        assert_eq!(report["errors"], serde_json::json!([]), "{report}");
        assert!(!log.contains("Uncaught"), "script error: {log}");
        assert_eq!(report["frames"].as_u64(), Some(61), "{report}");
        assert_eq!(
            report["contact_markers"].as_u64(),
            Some(total as u64),
            "{report}"
        );
        assert_eq!(
            report["frames_with_contacts"].as_u64(),
            Some(frames as u64),
            "{report}"
        );
        checked += 1;
    }
    assert_eq!(checked, 2);
}
