//! `rotorflow scene` and the library's `rotorflow::scene` are one code path: the command's
//! JSON and CSV are the library's to the byte for every example scene, and a bad scene file
//! fails in both with the same one-line message (exit code 2 in the command).

use super::rotorflow;
use rotorflow::dynamics::trajectory::even_times;
use rotorflow::scene::{Scene, SceneError};
use std::path::Path;

fn example_scenes() -> Vec<std::path::PathBuf> {
    let mut files: Vec<_> = std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    files
}

#[test]
fn the_command_writes_what_the_library_records() {
    let files = example_scenes();
    assert_eq!(files.len(), 10, "{files:?}");
    for file in &files {
        let dir = tempfile::tempdir().unwrap();
        rotorflow()
            .current_dir(dir.path())
            .arg("scene")
            .arg(file)
            .args([
                "--samples",
                "21",
                "--output",
                "run.json",
                "--csv-dir",
                "csv",
            ])
            .assert()
            .success();
        let scene = Scene::from_path(file).unwrap();
        let run = scene.record(&even_times(scene.t_end, 21)).unwrap();
        let json = std::fs::read_to_string(dir.path().join("run.json")).unwrap();
        assert!(json == scene.to_json(&run).unwrap(), "{}", file.display());
        let csv = run.csv_files().unwrap();
        assert_eq!(csv.len(), scene.bodies.len() + 1);
        for (name, text) in csv {
            let written = std::fs::read_to_string(dir.path().join("csv").join(&name)).unwrap();
            assert!(written == text, "{}: {name}", file.display());
        }
        // The new key holds one list per sample; the old keys are all there.
        let value: serde_json::Value = serde_json::from_str(&json).unwrap();
        assert_eq!(value["contacts"].as_array().map(Vec::len), Some(21));
        for key in [
            "dim",
            "integrator",
            "dt",
            "t_end",
            "gravity",
            "plane_names",
            "planes",
            "times",
            "bodies",
            "energy",
            "kinetic_energy",
            "potential_energy",
            "momentum",
            "angular_momentum",
        ] {
            assert!(value.get(key).is_some(), "{}: no {key}", file.display());
        }
    }
}

#[test]
fn bad_scenes_fail_with_the_same_line_in_both() {
    let cases = [
        "dim = 3\nt_end = 1\ndt = 0.1\n",
        "dim = 3\nt_end = 1\ndt = 0.1\n[[body]]\nname = \"a\"\nshape = \"ball:3,1\"\nposition = [0, 0]\n",
        "dim = 3\nt_end = 1\ndt = 2\n[[body]]\nname = \"a\"\nshape = \"ball:3,1\"\n",
        "dim = 3\nt_end = 1\ndt = 0.1\n[[body]]\nname = \"a\"\nshape = \"ball:3,1\"\nposition = [0, 0, 0.5]\n[[plane]]\nnormal = [0, 0, 1]\n",
        "dim = 3\nt_end = 1\ndt = 0.1\n[body]\nname = \"a\"\n",
        "dim = 3\nt_end = 1\ndt = 0.1\nspeed = 3\n",
    ];
    let mut checked = 0;
    for text in cases {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("scene.toml"), text).unwrap();
        let out = rotorflow()
            .current_dir(dir.path())
            .args(["scene", "scene.toml"])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{text}");
        let stderr = String::from_utf8(out.stderr).unwrap();
        // Reading and building the system are where a scene is refused.
        let error = Scene::from_toml_str(text, "scene.toml")
            .and_then(|scene| scene.system().map(|_| ()))
            .unwrap_err();
        assert!(matches!(error, SceneError::Invalid(_)), "{error:?}");
        assert_eq!(stderr, format!("rotorflow: error: {error}\n"), "{text}");
        checked += 1;
    }
    assert_eq!(checked, cases.len());
}
