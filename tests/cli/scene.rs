//! `rotorflow scene`: free flight under gravity against the exact parabola, a two-body
//! spring keeping the linear momentum, the CSV and HTML files, the example scenes run end to
//! end (a spring, contact with planes, ball joints, and the figures the demo reports), and
//! every kind of bad scene file refused with one line naming the key.

use super::{floats, matrix, rotorflow};
use rotorflow::dynamics::motion::ContactShape;
use rotorflow::inertia::spec::parse_body;
use serde_json::Value;
use std::path::{Path, PathBuf};

/// Writes `text` as `scene.toml` in a new folder.
fn scene_file(text: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.toml");
    std::fs::write(&path, text).unwrap();
    (dir, path)
}

/// Runs `scene` in `dir` and checks that it succeeds.
fn run_ok(dir: &Path, args: &[&str]) -> String {
    let out = rotorflow()
        .current_dir(dir)
        .arg("scene")
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "rotorflow scene {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn read_json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

const FREE_FLIGHT: &str = r#"
dim = 4
gravity = [0.5, 0.0, -1.0, -9.81]
t_end = 2.0
dt = 0.01

[[body]]
name = "cube"
shape = "tesseract:1,1.2,1.5,2"
mass = 3
position = [1.0, -2.0, 0.5, 10.0]
velocity = [1.0, 0.5, 0.0, 2.0]
omega = [1.0, 0.0, 0.2, 0.0, 0.0, 0.5]
"#;

#[test]
fn scene_free_flight_follows_the_parabola() {
    let (dir, _) = scene_file(FREE_FLIGHT);
    run_ok(
        dir.path(),
        &["scene.toml", "--samples", "21", "--output", "run.json"],
    );
    let json = read_json(&dir.path().join("run.json"));
    for key in [
        "dim",
        "times",
        "bodies",
        "energy",
        "momentum",
        "angular_momentum",
        "planes",
    ] {
        assert!(json.get(key).is_some(), "no key {key}");
    }
    assert_eq!(json["dim"], 4);
    let times = floats(&json["times"]);
    assert_eq!(times.len(), 21);
    assert_eq!(times[0], 0.0);
    assert_eq!(*times.last().unwrap(), 2.0);
    let body = &json["bodies"][0];
    let keys: Vec<&String> = body.as_object().unwrap().keys().collect();
    for key in ["name", "position", "velocity", "attitude", "omega"] {
        assert!(body.get(key).is_some(), "body lacks {key}: {keys:?}");
    }
    assert_eq!(body["name"], "cube");
    let (x0, v0, g) = (
        [1.0, -2.0, 0.5, 10.0],
        [1.0, 0.5, 0.0, 2.0],
        [0.5, 0.0, -1.0, -9.81],
    );
    let positions = matrix(&body["position"]);
    let velocities = matrix(&body["velocity"]);
    assert_eq!(positions.len(), 21);
    for (k, t) in times.iter().enumerate() {
        for i in 0..4 {
            let exact = x0[i] + v0[i] * t + 0.5 * g[i] * t * t;
            let got = positions[k][i];
            assert!(
                (got - exact).abs() <= 1e-12 * exact.abs().max(1.0),
                "t = {t}, x{}: {got} vs {exact}",
                i + 1
            );
            let v = v0[i] + g[i] * t;
            assert!((velocities[k][i] - v).abs() <= 1e-12 * v.abs().max(1.0));
        }
        // The attitude is a 4 × 4 rotation, as `simulate` writes it (rows).
        let rows = matrix(&body["attitude"][k]);
        assert_eq!(rows.len(), 4);
        for a in 0..4 {
            for b in 0..4 {
                let dot: f64 = (0..4).map(|c| rows[c][a] * rows[c][b]).sum();
                let want = if a == b { 1.0 } else { 0.0 };
                assert!((dot - want).abs() < 1e-9, "QᵀQ[{a}][{b}] = {dot}");
            }
        }
        assert_eq!(floats(&body["omega"][k]).len(), 6);
    }
    // Energy is kept by the splitting; momentum changes by m g t.
    let energy = floats(&json["energy"]);
    assert!((energy[20] - energy[0]).abs() <= 1e-6 * energy[0].abs());
    let p = matrix(&json["momentum"]);
    for i in 0..4 {
        let want = 3.0 * (v0[i] + g[i] * 2.0);
        assert!((p[20][i] - want).abs() <= 1e-12 * want.abs().max(1.0));
    }
}

#[test]
fn scene_rk4_free_flight_follows_the_parabola() {
    let text = FREE_FLIGHT.replace("dt = 0.01", "dt = 0.01\nintegrator = \"rk4\"");
    let (dir, _) = scene_file(&text);
    run_ok(
        dir.path(),
        &[
            "scene.toml",
            "--times",
            "0,0.5,1.25",
            "--output",
            "run.json",
        ],
    );
    let json = read_json(&dir.path().join("run.json"));
    assert_eq!(floats(&json["times"]), vec![0.0, 0.5, 1.25]);
    let positions = matrix(&json["bodies"][0]["position"]);
    let t = 1.25;
    let exact = 10.0 + 2.0 * t - 0.5 * 9.81 * t * t;
    assert!((positions[2][3] - exact).abs() <= 1e-12 * exact.abs());
}

/// A 4D cube dropped onto a larger one resting on the floor, stepped by the soft step: both
/// come to rest (below 1e-6 m/s), each sitting by the springs' deflection (between 0 and
/// 1e-3) in what holds it, the output names the integrator, and the last sample's contacts
/// carry the step's weights: the floor's (16 + 1) g dt, the base's g dt (1e-6).
#[test]
fn scene_soft_step_stacks_two_cubes() {
    let text = r#"
dim = 4
gravity = [0.0, 0.0, 0.0, -9.81]
t_end = 3.0
dt = 0.01
integrator = "soft"

[[body]]
name = "base"
shape = "cuboid:0.5,0.5,0.5,0.5"
mass = 16
position = [0.0, 0.0, 0.0, 0.5]
friction = 0.5

[[body]]
name = "top"
shape = "cuboid:0.25,0.25,0.25,0.25"
mass = 1
position = [0.05, 0.0, 0.0, 1.5]
friction = 0.5

[[plane]]
normal = [0, 0, 0, 1]
friction = 0.5
"#;
    let (dir, _) = scene_file(text);
    run_ok(
        dir.path(),
        &["scene.toml", "--samples", "4", "--output", "run.json"],
    );
    let json = read_json(&dir.path().join("run.json"));
    assert_eq!(json["integrator"], "soft");
    let base = matrix(&json["bodies"][0]["position"]);
    let top = matrix(&json["bodies"][1]["position"]);
    let base_sink = 0.5 - base[3][3];
    let top_sink = base[3][3] + 0.5 + 0.25 - top[3][3];
    for (what, sink) in [("base", base_sink), ("top", top_sink)] {
        assert!(sink > 0.0 && sink < 1e-3, "the {what} sank {sink:e}");
    }
    for body in 0..2 {
        let v = matrix(&json["bodies"][body]["velocity"]);
        assert!(
            v[3].iter().all(|x| x.abs() < 1e-6),
            "body {body} moves: {:?}",
            v[3]
        );
    }
    let last = |key: &str| -> f64 {
        let samples = json[key].as_array().expect("a contacts key");
        samples[samples.len() - 1]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c["normal_impulse"].as_f64().unwrap())
            .sum()
    };
    let weight = 9.81 * 0.01;
    let (floor, between) = (last("contacts"), last("body_contacts"));
    assert!(
        (floor - 17.0 * weight).abs() <= 1e-6 * 17.0 * weight,
        "floor {floor:e}"
    );
    assert!(
        (between - weight).abs() <= 1e-6 * weight,
        "base {between:e}"
    );
}

const TWO_BODIES: &str = r#"
dim = 3
t_end = 3.0
dt = 0.005

[[body]]
name = "a"
shape = "cuboid:0.5,0.3,0.2"
mass = 2.0
position = [-1.0, 0.0, 0.0]
velocity = [0.0, 0.3, 0.1]
omega = [0.4, -0.2, 1.0]

[[body]]
name = "b"
shape = "ellipsoid:0.3,0.4,0.5"
position = [1.5, 0.2, 0.0]
velocity = [-0.2, 0.0, 0.0]
attitude = [0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0]

[[spring]]
body = "a"
point = [0.5, 0.3, 0.2]
other = "b"
other_point = [0.0, 0.0, 0.5]
stiffness = 20.0
rest_length = 1.0
damping = 0.3
"#;

#[test]
fn scene_two_body_spring_keeps_the_linear_momentum() {
    let (dir, _) = scene_file(TWO_BODIES);
    run_ok(dir.path(), &["scene.toml", "--output", "run.json"]);
    let json = read_json(&dir.path().join("run.json"));
    let p = matrix(&json["momentum"]);
    assert!(p.len() > 100);
    for row in &p {
        for i in 0..3 {
            assert!(
                (row[i] - p[0][i]).abs() <= 1e-12 * p[0][i].abs().max(1.0),
                "{row:?} vs {:?}",
                p[0]
            );
        }
    }
    // The spring pulled the bodies: their velocities changed.
    let v = matrix(&json["bodies"][0]["velocity"]);
    assert!((v.last().unwrap()[0] - v[0][0]).abs() > 1e-3);
    // No output file means a summary on standard output.
    let text = run_ok(dir.path(), &["scene.toml", "--samples", "5"]);
    assert!(
        text.contains("energy") && text.contains("final positions"),
        "{text}"
    );
    assert!(text.contains("  a: (") && text.contains("  b: ("), "{text}");
    assert!(!text.contains("NaN"), "{text}");
}

/// Two balls of a scene file meet head on: with `restitution = 1` on one of them (the pair
/// takes the larger) and no friction they exchange velocities, and a fixed ball bounces a
/// third one back; a body with `collide = false` passes through the fixed one.
#[test]
fn scene_bodies_collide_exchange_velocities_and_bounce_off_fixed_bodies() {
    let text = r#"
dim = 3
t_end = 2.0
dt = 0.01

[[body]]
name = "left"
shape = "ball:3,0.5"
mass = 1
position = [-1.5, 0, 0]
velocity = [1, 0, 0]
restitution = 1
friction = 0

[[body]]
name = "right"
shape = "ball:3,0.5"
mass = 1
position = [0, 0, 0]
friction = 0

[[body]]
name = "wall"
shape = "ball:3,0.5"
position = [0, 5, 0]
fixed = true
restitution = 1

[[body]]
name = "thrown"
shape = "ball:3,0.5"
mass = 2
position = [0, 3.5, 0]
velocity = [0, 1, 0]

[[body]]
name = "ghost"
shape = "ball:3,0.5"
mass = 1
position = [3, 5, 0]
velocity = [-2, 0, 0]
collide = false
"#;
    let (dir, _) = scene_file(text);
    run_ok(dir.path(), &["scene.toml", "--output", "run.json"]);
    let json = read_json(&dir.path().join("run.json"));
    let last = |b: usize| {
        matrix(&json["bodies"][b]["velocity"])
            .last()
            .unwrap()
            .clone()
    };
    assert!(last(0)[0].abs() <= 1e-9, "left {:?}", last(0));
    assert!((last(1)[0] - 1.0).abs() <= 1e-9, "right {:?}", last(1));
    // The thrown ball meets the fixed one after 0.5 s and comes back at full speed.
    assert!((last(3)[1] + 1.0).abs() <= 1e-9, "thrown {:?}", last(3));
    let wall = matrix(&json["bodies"][2]["position"]);
    assert_eq!(wall.last().unwrap(), &vec![0.0, 5.0, 0.0]);
    // The ghost keeps its velocity through the wall.
    assert!((last(4)[0] + 2.0).abs() <= 1e-12, "ghost {:?}", last(4));
}

#[test]
fn scene_writes_csv_per_body_and_html() {
    let (dir, _) = scene_file(TWO_BODIES);
    let out = run_ok(
        dir.path(),
        &[
            "scene.toml",
            "--samples",
            "11",
            "--csv-dir",
            "csv",
            "--html",
            "anim.html",
            "--output",
            "run.json",
        ],
    );
    assert!(out.is_empty(), "{out}");
    let json = read_json(&dir.path().join("run.json"));
    let a = std::fs::read_to_string(dir.path().join("csv/a.csv")).unwrap();
    let lines: Vec<&str> = a.lines().collect();
    assert_eq!(lines.len(), 12);
    assert_eq!(
        lines[0],
        "t,x1,x2,x3,v1,v2,v3,R11,R12,R13,R21,R22,R23,R31,R32,R33,w12,w13,w23"
    );
    let last: Vec<f64> = lines[11].split(',').map(|x| x.parse().unwrap()).collect();
    assert_eq!(last[0], 3.0);
    assert_eq!(
        &last[1..4],
        floats(&json["bodies"][0]["position"][10]).as_slice()
    );
    assert!(dir.path().join("csv/b.csv").exists());
    let system = std::fs::read_to_string(dir.path().join("csv/system.csv")).unwrap();
    assert!(
        system.starts_with("t,energy,p1,p2,p3,L12,L13,L23\n"),
        "{system}"
    );
    assert_eq!(system.lines().count(), 12);
    let html = std::fs::read_to_string(dir.path().join("anim.html")).unwrap();
    assert!(html.starts_with("<!DOCTYPE html>"));
    assert!(html.contains("\"bodies\"") && html.contains("\"name\":\"b\""));
    assert!(!html.contains("http://") && !html.contains("https://"));
}

/// Every number of the CSV files is the shortest text that reads back exactly: it equals the
/// JSON's number bit for bit (serde_json writes and reads floats exactly), and has at most 17
/// significant digits.
#[test]
fn scene_csv_numbers_are_short_and_read_back_exactly() {
    let (dir, _) = scene_file(TWO_BODIES);
    run_ok(
        dir.path(),
        &[
            "scene.toml",
            "--samples",
            "31",
            "--csv-dir",
            "csv",
            "--output",
            "run.json",
        ],
    );
    let json = read_json(&dir.path().join("run.json"));
    let rows = |name: &str| -> Vec<Vec<String>> {
        let text = std::fs::read_to_string(dir.path().join("csv").join(name)).unwrap();
        text.lines()
            .skip(1)
            .map(|l| l.split(',').map(str::to_string).collect())
            .collect()
    };
    let mut compared = 0;
    let mut same = |field: &str, expected: f64| {
        let x: f64 = field.parse().unwrap();
        assert_eq!(
            x.to_bits(),
            expected.to_bits(),
            "{field} against {expected:e}"
        );
        let mantissa = field.trim_start_matches('-').split('e').next().unwrap();
        let digits: String = mantissa.chars().filter(char::is_ascii_digit).collect();
        assert!(digits.trim_start_matches('0').len() <= 17, "{field}");
        // Plain only where that is short: no runs of leading zeros, no padding to the point.
        assert!(
            field.contains('e') || x == 0.0 || (1e-5..1e16).contains(&x.abs()),
            "{field} is not in its shortest form"
        );
        compared += 1;
    };
    for (b, name) in ["a.csv", "b.csv"].into_iter().enumerate() {
        let body = &json["bodies"][b];
        for (k, row) in rows(name).iter().enumerate() {
            same(&row[0], json["times"][k].as_f64().unwrap());
            for i in 0..3 {
                same(&row[1 + i], body["position"][k][i].as_f64().unwrap());
                same(&row[4 + i], body["velocity"][k][i].as_f64().unwrap());
                same(&row[16 + i], body["omega"][k][i].as_f64().unwrap());
            }
            for r in 0..3 {
                for c in 0..3 {
                    same(
                        &row[7 + 3 * r + c],
                        body["attitude"][k][r][c].as_f64().unwrap(),
                    );
                }
            }
        }
    }
    for (k, row) in rows("system.csv").iter().enumerate() {
        same(&row[1], json["energy"][k].as_f64().unwrap());
        for i in 0..3 {
            same(&row[2 + i], json["momentum"][k][i].as_f64().unwrap());
            same(
                &row[5 + i],
                json["angular_momentum"][k][i].as_f64().unwrap(),
            );
        }
    }
    // 31 rows of 19 numbers for each body, 31 of 7 for the system.
    assert_eq!(compared, 31 * 19 * 2 + 31 * 7);
}

/// `--plot`: one SVG with the energies, the momenta and the positions, each series named,
/// and no non-finite number drawn; the energies add up in the JSON it is drawn from.
#[test]
fn scene_plot_draws_energies_momenta_and_positions() {
    let (dir, _) = scene_file(TWO_BODIES);
    let out = run_ok(
        dir.path(),
        &[
            "scene.toml",
            "--samples",
            "61",
            "--plot",
            "run.svg",
            "--output",
            "run.json",
        ],
    );
    assert!(out.is_empty(), "{out}");
    let svg = std::fs::read_to_string(dir.path().join("run.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    for series in [
        "kinetic T",
        "potential V",
        "total E = T + V",
        "|p| (linear momentum)",
        "|L| (angular momentum about the origin)",
        "a x₁",
        "a x₃",
        "b x₂",
    ] {
        assert!(svg.contains(series), "the plot lacks {series}");
    }
    assert!(!svg.contains("NaN") && !svg.contains("inf"));
    let json = read_json(&dir.path().join("run.json"));
    let (t, v, e) = (
        floats(&json["kinetic_energy"]),
        floats(&json["potential_energy"]),
        floats(&json["energy"]),
    );
    assert_eq!(e.len(), 61);
    for k in 0..61 {
        assert!((t[k] + v[k] - e[k]).abs() <= 1e-12 * e[k].abs().max(1.0));
        assert!(t[k] >= 0.0);
    }
    // The two bodies exchange energy through the spring: V is not constant.
    assert!(v.iter().any(|x| (x - v[0]).abs() > 1e-3));
}

#[test]
fn scene_accepts_a_step_within_a_tenth_of_the_spring_period() {
    // 2π√(16/600) = 1.026: ten steps of 0.1 fit in it.
    let (dir, _) = scene_file(&format!(
        "{HEAD}{CUBE}[[spring]]\nbody = \"cube\"\nanchor = [0,0,0,1]\nstiffness = 600\n"
    ));
    let out = run_ok(dir.path(), &["scene.toml", "--check"]);
    assert!(out.contains("1 spring"), "{out}");
}

#[test]
fn scene_check_accepts_planes_and_writes_nothing() {
    let text = TWO_BODIES.to_string() + "\n[[plane]]\nnormal = [0, 0, 1]\noffset = -2\n";
    let (dir, _) = scene_file(&text);
    // `--check` reads the planes, builds the system and writes nothing.
    let out = run_ok(dir.path(), &["scene.toml", "--check"]);
    assert!(out.contains("1 plane"), "{out}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

#[test]
fn scene_example_files_are_valid() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut count = 0;
    for entry in std::fs::read_dir(&root).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let out = rotorflow()
                .args(["scene", "--check"])
                .arg(&path)
                .output()
                .unwrap();
            assert!(
                out.status.success(),
                "{}: {}",
                path.display(),
                String::from_utf8_lossy(&out.stderr)
            );
            count += 1;
        }
    }
    assert!(count >= 5, "only {count} example scenes");
}

/// Runs the example scene `scenes/<file>` with `--output run.json` and `extra` options and
/// returns the JSON.
fn run_example(file: &str, extra: &[&str]) -> Value {
    let dir = tempfile::tempdir().unwrap();
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(file);
    let out = rotorflow()
        .current_dir(dir.path())
        .arg("scene")
        .arg(&path)
        .args(["--output", "run.json"])
        .args(extra)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{file}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    read_json(&dir.path().join("run.json"))
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

/// R r: the attitude (rows, own axes → space) applied to a vector of own axes.
fn turn(rows: &[Vec<f64>], r: &[f64]) -> Vec<f64> {
    rows.iter().map(|row| dot(row, r)).collect()
}

/// The body point `r` (own axes) of body `b` in space at sample `k`: x + R r.
fn place(json: &Value, b: usize, k: usize, r: &[f64]) -> Vec<f64> {
    let body = &json["bodies"][b];
    let x = floats(&body["position"][k]);
    let offset = turn(&matrix(&body["attitude"][k]), r);
    x.iter().zip(&offset).map(|(a, b)| a + b).collect()
}

/// The velocity of the point at offset `d` (space) from body `b`'s centre at sample `k`:
/// v + W d, with W = R Ω Rᵀ and Ω e_i = ω_ij e_j for i < j (ω₁₂ > 0 turns e₁ to e₂).
fn point_velocity(json: &Value, b: usize, k: usize, d: &[f64]) -> Vec<f64> {
    let body = &json["bodies"][b];
    let n = d.len();
    let omega = floats(&body["omega"][k]);
    let rows = matrix(&body["attitude"][k]);
    // Rᵀ d in own axes, Ω on it, R back to space.
    let own: Vec<f64> = (0..n)
        .map(|j| (0..n).map(|i| rows[i][j] * d[i]).sum())
        .collect();
    let mut spun = vec![0.0; n];
    let mut c = 0;
    for i in 0..n {
        for j in i + 1..n {
            spun[j] += omega[c] * own[i];
            spun[i] -= omega[c] * own[j];
            c += 1;
        }
    }
    let v = floats(&body["velocity"][k]);
    v.iter()
        .zip(turn(&rows, &spun))
        .map(|(a, b)| a + b)
        .collect()
}

/// The smallest signed distance from a plane of any point of any body over all samples,
/// divided by the body's radius (negative: inside the solid), from the JSON's positions and
/// attitudes and each body's contact shape.
fn lowest_gap(json: &Value) -> f64 {
    let planes = json["planes"].as_array().unwrap();
    let mut lowest = f64::INFINITY;
    for (b, body) in json["bodies"].as_array().unwrap().iter().enumerate() {
        let parsed = parse_body(body["shape"].as_str().unwrap()).unwrap();
        let shape = ContactShape::from_geometry(&parsed.geometry);
        let radius = shape.radius();
        for plane in planes {
            let normal = floats(&plane["normal"]);
            let s = norm(&normal);
            let n: Vec<f64> = normal.iter().map(|x| x / s).collect();
            let d = plane["offset"].as_f64().unwrap() / s;
            for k in 0..json["times"].as_array().unwrap().len() {
                let gap = match &shape {
                    ContactShape::Vertices(v) => v
                        .iter()
                        .map(|r| dot(&n, &place(json, b, k, r.as_slice())) - d)
                        .fold(f64::INFINITY, f64::min),
                    ContactShape::Ellipsoid(a) => {
                        // The support point along −n: −A²m/|Am|, m = Rᵀn.
                        let rows = matrix(&body["attitude"][k]);
                        let m: Vec<f64> = (0..n.len())
                            .map(|j| (0..n.len()).map(|i| rows[i][j] * n[i]).sum())
                            .collect();
                        let am: Vec<f64> = a.iter().zip(&m).map(|(a, m)| a * m).collect();
                        let length = norm(&am);
                        let r: Vec<f64> = a.iter().zip(&am).map(|(a, x)| -a * x / length).collect();
                        dot(&n, &place(json, b, k, &r)) - d
                    }
                    _ => continue,
                };
                lowest = lowest.min(gap / radius);
            }
        }
    }
    lowest
}

/// The largest |E − E(0)| over the samples.
fn energy_change(json: &Value) -> f64 {
    let energy = floats(&json["energy"]);
    energy
        .iter()
        .map(|e| (e - energy[0]).abs())
        .fold(0.0, f64::max)
}

#[test]
fn scene_example_with_springs_runs() {
    let json = run_example("tesseract-spring.toml", &["--samples", "501"]);
    let energy = floats(&json["energy"]);
    // The undamped spring and gravity are conservative: the splitting keeps the energy to a
    // bounded error of order dt² (measured 1.05e-4 of E(0) at dt = 0.002).
    let error = energy_change(&json) / energy[0].abs();
    assert!(error < 2e-4, "relative energy error {error:e}");
    // The spring pulls towards its anchor at the origin and gravity is along x4: the
    // angular momentum about the origin is kept in the planes 12, 13, 23 (components 0, 1,
    // 3), to round-off; the others change.
    let l = matrix(&json["angular_momentum"]);
    for row in &l {
        for c in [0, 1, 3] {
            assert!((row[c] - l[0][c]).abs() < 1e-12, "{row:?} vs {:?}", l[0]);
        }
    }
    assert!((l.last().unwrap()[2] - l[0][2]).abs() > 1e-2);
}

#[test]
fn scene_ball_on_floor_never_sinks_and_ends_rolling() {
    let json = run_example("ball-on-floor.toml", &["--samples", "801"]);
    // Neither the ball nor the box's corners go below the floor by more than the contact
    // tolerance (1e-9 of the radius).
    let lowest = lowest_gap(&json);
    assert!(lowest >= -1e-9, "lowest point {lowest:e} of the radius");
    let x = matrix(&json["bodies"][0]["position"]);
    let radius = 0.5;
    for (k, p) in x.iter().enumerate() {
        assert!(p[3] - radius >= -1e-9 * radius, "sample {k}: x4 = {}", p[3]);
    }
    // The ball lands, bounces and then rolls: at the end it touches the floor and its
    // contact point does not move, while the ball still moves.
    let last = x.len() - 1;
    assert!(
        (x[last][3] - radius).abs() <= 1e-9 * radius,
        "{:?}",
        x[last]
    );
    let v = floats(&json["bodies"][0]["velocity"][last]);
    let slip = norm(&point_velocity(&json, 0, last, &[0.0, 0.0, 0.0, -radius]));
    assert!(norm(&v) > 0.1, "{v:?}");
    assert!(slip <= 1e-9 * norm(&v), "contact point velocity {slip:e}");
    // The floor took energy: the bounces (e = 0.5) and the slide.
    let energy = floats(&json["energy"]);
    assert!(
        energy[last] < 0.5 * energy[0],
        "{} → {}",
        energy[0],
        energy[last]
    );
}

#[test]
fn scene_double_pendulum_joints_hold_and_energy_is_bounded() {
    let json = run_example("double-pendulum-4d.toml", &["--samples", "1001"]);
    let count = json["times"].as_array().unwrap().len();
    assert_eq!(count, 1001);
    let (inner, outer) = ([-0.5, 0.0, 0.0, 0.0], [0.5, 0.0, 0.0, 0.0]);
    for k in 0..count {
        // Joint 1: the upper bar's inner end on the origin.
        let a = place(&json, 0, k, &inner);
        assert!(
            norm(&a) <= 1e-9,
            "sample {k}: joint 1 open by {:e}",
            norm(&a)
        );
        // Joint 2: the lower bar's inner end on the upper bar's outer end.
        let b = place(&json, 1, k, &inner);
        let c = place(&json, 0, k, &outer);
        let gap: Vec<f64> = b.iter().zip(&c).map(|(x, y)| x - y).collect();
        assert!(
            norm(&gap) <= 1e-9,
            "sample {k}: joint 2 open by {:e}",
            norm(&gap)
        );
    }
    // The pendulum swings: the lower bar falls by a good part of its reach.
    let lowest = matrix(&json["bodies"][1]["position"])
        .iter()
        .map(|p| p[3])
        .fold(f64::INFINITY, f64::min);
    assert!(lowest < -0.5, "{lowest}");
    // Joints do no work and gravity is conservative: the energy error stays bounded, small
    // against the energy exchanged (m g times the drop, ≈ 2 · 9.81 · 1).
    let scale = 2.0 * 9.81;
    let change = energy_change(&json);
    assert!(change < 1e-3 * scale, "energy change {change:e}");
}

/// The demo's three scenes (the figures `rotorflow demo` reports in summary.md).
#[test]
fn scene_ball_rolling_reaches_the_rolling_speed() {
    let json = run_example("ball-rolling-4d.toml", &["--samples", "151"]);
    // A solid N-ball has plane moment 2 m R²/(N + 2); the angular momentum about the
    // contact point is kept through the slide, so it rolls at v0 (N + 2)/(N + 4).
    let (v0, n) = (2.0, 4.0);
    let predicted = v0 * (n + 2.0) / (n + 4.0);
    let v = matrix(&json["bodies"][0]["velocity"]);
    let last = v.len() - 1;
    let measured = norm(&v[last]);
    assert!(
        (measured - predicted).abs() <= 1e-6 * predicted,
        "{measured} vs {predicted}"
    );
    // Rolling from t = 2 v0/((N + 4) μ g) = 0.17 on: the contact point stands still.
    let times = floats(&json["times"]);
    let roll = 2.0 * v0 / ((n + 4.0) * 0.3 * 9.81);
    for (k, t) in times.iter().enumerate() {
        let slip = norm(&point_velocity(&json, 0, k, &[0.0, 0.0, 0.0, -0.5]));
        if *t > roll + 0.011 {
            assert!(slip <= 1e-9 * predicted, "t = {t}: slip {slip:e}");
        } else if *t < roll - 0.011 {
            assert!(slip > 1e-3, "t = {t}: already rolling");
        }
    }
    assert!(lowest_gap(&json) >= -1e-9);
}

#[test]
fn scene_five_cell_bounces_down_the_slope_without_sinking() {
    let json = run_example("five-cell-slope.toml", &["--samples", "501"]);
    // No vertex goes into the slope or the floor beyond the contact tolerance.
    let lowest = lowest_gap(&json);
    assert!(lowest >= -1e-9, "lowest vertex {lowest:e} of the radius");
    // It bounces down the slope and comes to rest on the floor past the slope's foot
    // (x1 = 3), on a face: the centre at the inradius 1/4 above the floor.
    let x = matrix(&json["bodies"][0]["position"]);
    let last = x.len() - 1;
    assert!(x[last][0] > 3.0, "{:?}", x[last]);
    assert!((x[last][3] - 0.25).abs() < 1e-6, "{:?}", x[last]);
    assert!(norm(&floats(&json["bodies"][0]["velocity"][last])) < 1e-6);
    // It tumbled: its attitude turned by more than a right angle.
    let rows = matrix(&json["bodies"][0]["attitude"][last]);
    let trace: f64 = (0..4).map(|i| rows[i][i]).sum();
    assert!(trace < 3.0, "trace {trace}");
    // The impacts (e = 0.5) and the friction took most of the energy: what is left is the
    // potential m g h of the 5-cell at rest, 5 · 9.81 · 0.25.
    let energy = floats(&json["energy"]);
    assert!(
        (energy[last] - 5.0 * 9.81 * 0.25).abs() < 1e-6,
        "{}",
        energy[last]
    );
    assert!(
        energy[last] < 0.1 * energy[0],
        "{} → {}",
        energy[0],
        energy[last]
    );
    // The energy never rises (beyond round-off): contact only takes energy away.
    for w in energy.windows(2) {
        assert!(w[1] <= w[0] + 1e-9 * energy[0], "{w:?}");
    }
}

/// Runs `scene` on `text` with every output asked for and checks the refusal: exit code 2,
/// one line on standard error holding each of `needles`, nothing written.
fn refuses(text: &str, needles: &[&str]) {
    let (dir, _) = scene_file(text);
    let out = rotorflow()
        .current_dir(dir.path())
        .args([
            "scene",
            "scene.toml",
            "--output",
            "run.json",
            "--csv-dir",
            "csv",
            "--html",
            "run.html",
            "--plot",
            "run.svg",
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{text}\n{err}");
    assert_eq!(err.lines().count(), 1, "not one line: {err}");
    for needle in needles {
        assert!(err.contains(needle), "{err:?} lacks {needle:?}");
    }
    assert!(!err.contains("panicked"), "{err}");
    assert!(out.stdout.is_empty());
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .filter(|n| n != "scene.toml")
        .collect();
    assert!(left.is_empty(), "files written: {left:?}");
}

const HEAD: &str = "dim = 4\nt_end = 1.0\ndt = 0.1\n";
const CUBE: &str = "[[body]]\nname = \"cube\"\nshape = \"tesseract:1,1,1,1\"\n";

macro_rules! bad_scenes {
    ($($name:ident => ($text:expr, [$($needle:expr),+]))*) => {
        $( #[test] fn $name() { refuses(&$text, &[$($needle),+]); } )*
    };
}

bad_scenes! {
    scene_refuses_unknown_top_key => (format!("{HEAD}colour = 1\n{CUBE}"), ["scene.toml", "unknown key `colour`"])
    scene_refuses_unknown_body_key => (format!("{HEAD}{CUBE}colour = 1\n"), ["body \"cube\"", "unknown key `colour`"])
    scene_refuses_unknown_plane_key => (format!("{HEAD}{CUBE}[[plane]]\nnormal = [0,0,0,1]\nheight = 2\n"), ["plane 1", "unknown key `height`"])
    scene_refuses_unknown_spring_key => (format!("{HEAD}{CUBE}[[spring]]\nbody = \"cube\"\nanchor = [0,0,0,0]\nstiffness = 1\nk = 2\n"), ["spring 1", "unknown key `k`"])
    scene_refuses_unknown_joint_key => (format!("{HEAD}{CUBE}[[joint]]\nbody = \"cube\"\nanchor = [0,0,0,0]\nstiff = true\n"), ["joint 1", "unknown key `stiff`"])
    scene_refuses_wrong_position_length => (format!("{HEAD}{CUBE}position = [1, 2, 3]\n"), ["body \"cube\": position has 3 components, expected 4 (dim = 4)"])
    scene_refuses_wrong_velocity_length => (format!("{HEAD}{CUBE}velocity = [1, 2, 3, 4, 5]\n"), ["body \"cube\"", "velocity has 5 components, expected 4"])
    scene_refuses_wrong_omega_length => (format!("{HEAD}{CUBE}omega = [1, 2, 3, 4]\n"), ["body \"cube\"", "omega has 4 components, expected 6"])
    scene_refuses_wrong_gravity_length => (format!("{HEAD}gravity = [0, -9.81]\n{CUBE}"), ["gravity has 2 components, expected 4"])
    scene_refuses_wrong_anchor_length => (format!("{HEAD}{CUBE}[[spring]]\nbody = \"cube\"\nanchor = [0,0]\nstiffness = 1\n"), ["spring 1", "anchor has 2 components"])
    scene_refuses_zero_mass => (format!("{HEAD}{CUBE}mass = 0\n"), ["body \"cube\"", "mass must be > 0"])
    scene_refuses_negative_mass => (format!("{HEAD}{CUBE}mass = -2.5\n"), ["body \"cube\"", "mass must be > 0, got -2.5"])
    scene_refuses_mass_twice => (format!("{HEAD}[[body]]\nname = \"cube\"\nshape = \"cuboid:1,1,1,1+mass=2\"\nmass = 3\n"), ["body \"cube\"", "mass"])
    scene_refuses_spring_to_a_missing_body => (format!("{HEAD}{CUBE}[[spring]]\nbody = \"ball\"\nanchor = [0,0,0,0]\nstiffness = 1\n"), ["spring 1", "body = \"ball\" names no body"])
    scene_refuses_spring_to_a_missing_other_body => (format!("{HEAD}{CUBE}[[spring]]\nbody = \"cube\"\nother = \"ball\"\nstiffness = 1\n"), ["spring 1", "other = \"ball\" names no body"])
    scene_refuses_joint_to_a_missing_body => (format!("{HEAD}{CUBE}[[joint]]\nbody = \"cube\"\nother = \"bar\"\n"), ["joint 1", "other = \"bar\" names no body"])
    scene_refuses_joint_with_anchor_and_other => (format!("{HEAD}{CUBE}[[body]]\nname = \"bar\"\nshape = \"cuboid:1,1,1,1\"\n[[joint]]\nbody = \"cube\"\nother = \"bar\"\nanchor = [0,0,0,0]\n"), ["joint 1", "anchor", "other"])
    scene_refuses_spring_without_other_end => (format!("{HEAD}{CUBE}[[spring]]\nbody = \"cube\"\nstiffness = 1\n"), ["spring 1", "missing key `anchor` or `other`"])
    scene_refuses_nan => (format!("{HEAD}{CUBE}velocity = [nan, 0, 0, 0]\n"), ["body \"cube\"", "velocity component 1 is NaN"])
    scene_refuses_infinite_dt => ("dim = 4\nt_end = 1.0\ndt = inf\n".to_string() + CUBE, ["dt is inf"])
    scene_refuses_nan_stiffness => (format!("{HEAD}{CUBE}[[spring]]\nbody = \"cube\"\nanchor = [0,0,0,0]\nstiffness = nan\n"), ["spring 1", "stiffness is NaN"])
    scene_refuses_missing_dim => ("t_end = 1.0\ndt = 0.1\n".to_string() + CUBE, ["missing key `dim`"])
    scene_refuses_missing_t_end => ("dim = 4\ndt = 0.1\n".to_string() + CUBE, ["missing key `t_end`"])
    scene_refuses_missing_dt => ("dim = 4\nt_end = 1\n".to_string() + CUBE, ["missing key `dt`"])
    scene_refuses_missing_shape => (format!("{HEAD}[[body]]\nname = \"cube\"\n"), ["body \"cube\"", "missing key `shape`"])
    scene_refuses_missing_name => (format!("{HEAD}[[body]]\nshape = \"tesseract:1,1,1,1\"\n"), ["body 1", "missing key `name`"])
    scene_refuses_missing_stiffness => (format!("{HEAD}{CUBE}[[spring]]\nbody = \"cube\"\nanchor = [0,0,0,0]\n"), ["spring 1", "missing key `stiffness`"])
    scene_refuses_missing_plane_normal => (format!("{HEAD}{CUBE}[[plane]]\noffset = 1\n"), ["plane 1", "missing key `normal`"])
    scene_refuses_no_body => (format!("{HEAD}"), ["no [[body]]"])
    scene_refuses_bad_spec => (format!("{HEAD}[[body]]\nname = \"cube\"\nshape = \"blob:1,2\"\n"), ["body \"cube\"", "shape", "unknown kind `blob`"])
    scene_refuses_spec_of_another_dimension => (format!("{HEAD}[[body]]\nname = \"cube\"\nshape = \"cuboid:1,2,3\"\n"), ["body \"cube\"", "shape", "3 dimensions, expected 4"])
    scene_refuses_duplicate_names => (format!("{HEAD}{CUBE}{CUBE}"), ["body 2", "\"cube\" is used twice"])
    scene_refuses_reflection_attitude => (format!("{HEAD}{CUBE}attitude = [[0,1,0,0],[1,0,0,0],[0,0,1,0],[0,0,0,1]]\n"), ["body \"cube\"", "attitude is not a rotation", "det"])
    scene_refuses_skewed_attitude => (format!("{HEAD}{CUBE}attitude = [1,0.1,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]\n"), ["body \"cube\"", "attitude is not a rotation"])
    scene_refuses_attitude_of_wrong_size => (format!("{HEAD}{CUBE}attitude = [1,0,0, 0,1,0, 0,0,1]\n"), ["body \"cube\"", "attitude has 9 entries, expected 16"])
    scene_refuses_zero_normal => (format!("{HEAD}{CUBE}[[plane]]\nnormal = [0,0,0,0]\n"), ["plane 1", "normal is zero"])
    scene_refuses_restitution_above_one => (format!("{HEAD}{CUBE}[[plane]]\nnormal = [0,0,0,1]\nrestitution = 1.5\n"), ["plane 1", "restitution must be in [0, 1]"])
    scene_refuses_negative_friction => (format!("{HEAD}{CUBE}[[plane]]\nnormal = [0,0,0,1]\nfriction = -1\n"), ["plane 1", "friction must be ≥ 0"])
    scene_refuses_negative_damping => (format!("{HEAD}{CUBE}[[spring]]\nbody = \"cube\"\nanchor = [0,0,0,0]\nstiffness = 1\ndamping = -1\n"), ["spring 1", "damping must be ≥ 0"])
    scene_refuses_negative_t_end => ("dim = 4\nt_end = -1\ndt = 0.1\n".to_string() + CUBE, ["t_end must be > 0"])
    scene_refuses_small_dim => ("dim = 1\nt_end = 1\ndt = 0.1\n".to_string() + CUBE, ["dim must be an integer from 2"])
    scene_refuses_unknown_integrator => (format!("{HEAD}integrator = \"euler\"\n{CUBE}"), ["integrator `euler` is unknown"])
    scene_refuses_rk4_with_joints => (format!("{HEAD}integrator = \"rk4\"\n{CUBE}[[joint]]\nbody = \"cube\"\nanchor = [0,0,0,0]\n"), ["rk4", "splitting"])
    scene_refuses_soft_with_joints => (format!("{HEAD}integrator = \"soft\"\n{CUBE}[[joint]]\nbody = \"cube\"\nanchor = [0,0,0,0]\n"), ["integrator \"soft\" holds no joints", "splitting"])
    scene_refuses_wrong_type => (format!("{HEAD}{CUBE}position = \"up\"\n"), ["body \"cube\"", "position must be a list of numbers"])
    scene_refuses_toml_syntax_errors => (format!("{HEAD}{CUBE}position = [1, 2\n"), ["scene.toml:"])
    scene_refuses_a_single_body_table => (format!("{HEAD}[body]\nname = \"cube\"\nshape = \"tesseract:1,1,1,1\"\n"), ["scene.toml:4: `[body]` is a single table; write `[[body]]`"])
    scene_refuses_a_single_plane_table => (format!("{HEAD}{CUBE}[plane]  # the floor\nnormal = [0,0,0,1]\n"), ["scene.toml:7: `[plane]` is a single table; write `[[plane]]`"])
    scene_refuses_a_single_spring_table => (format!("{HEAD}{CUBE}[spring]\nbody = \"cube\"\nanchor = [0,0,0,0]\nstiffness = 1\n"), ["scene.toml:7: `[spring]` is a single table; write `[[spring]]`"])
    scene_refuses_a_single_joint_table => (format!("{HEAD}{CUBE}[joint]\nbody = \"cube\"\nanchor = [0,0,0,0]\n"), ["scene.toml:7: `[joint]` is a single table; write `[[joint]]`"])
    scene_refuses_a_body_that_is_not_a_table => (format!("{HEAD}body = 3\n"), ["body must be an array of tables (`[[body]]`, one per body), got an integer"])
    scene_refuses_a_step_as_long_as_the_run => ("dim = 4\nt_end = 1.0\ndt = 1.0\n".to_string() + CUBE, ["dt = 1 is not less than t_end = 1", "a single step"])
    scene_refuses_a_step_longer_than_the_run => ("dim = 4\nt_end = 1.0\ndt = 2.5\n".to_string() + CUBE, ["dt = 2.5 is not less than t_end = 1"])
    // tesseract:1,1,1,1 is 16 unit masses: the period 2π√(16/1000) = 0.795 is less than ten
    // steps of 0.1.
    scene_refuses_a_step_too_long_for_a_spring => (format!("{HEAD}{CUBE}[[spring]]\nbody = \"cube\"\nanchor = [0,0,0,1]\nstiffness = 1000\n"), ["spring 1: dt = 0.1 is more than 1/10 of the spring's period 2π√(m_eff/k) = 7.947" , "m_eff = 16, k = 1000", "take dt ≤ 7.948e-2"])
    // Between two bodies of 16 the reduced mass is 8: 2π√(8/400) = 0.889 < 10 dt, though
    // 2π√(16/400) = 1.257 would pass.
    scene_refuses_a_step_too_long_for_a_spring_between_bodies => (format!("{HEAD}{CUBE}[[body]]\nname = \"bar\"\nshape = \"tesseract:1,1,1,1\"\nposition = [3,0,0,0]\n[[spring]]\nbody = \"cube\"\nother = \"bar\"\nstiffness = 400\n"), ["spring 1", "m_eff = 8, k = 400", "period 2π√(m_eff/k) = 8.885"])
    scene_refuses_a_body_inside_a_plane => (format!("{HEAD}{CUBE}[[plane]]\nnormal = [0,0,0,1]\n"), ["body \"cube\" starts 1.000e0 inside plane 1", "on or above the plane"])
    scene_refuses_overlapping_bodies => (format!("{HEAD}{CUBE}[[body]]\nname = \"bar\"\nshape = \"cuboid:1,1,1,1\"\nposition = [0.5,0,0,0]\n"), ["body \"cube\" and body \"bar\" start overlapping by", "place them apart"])
    scene_refuses_a_fixed_body_with_velocity => (format!("{HEAD}{CUBE}fixed = true\nvelocity = [1,0,0,0]\n"), ["body \"cube\"", "a fixed body never moves: remove its velocity"])
    scene_refuses_a_fixed_body_that_touches_nothing => (format!("{HEAD}{CUBE}fixed = true\ncollide = false\n"), ["body \"cube\"", "touches nothing"])
    scene_refuses_a_fixed_flag_that_is_not_a_boolean => (format!("{HEAD}{CUBE}fixed = 1\n"), ["body \"cube\"", "fixed must be true or false"])
    scene_refuses_negative_body_friction => (format!("{HEAD}{CUBE}friction = -0.5\n"), ["body \"cube\"", "friction must be ≥ 0"])
    scene_refuses_body_restitution_above_one => (format!("{HEAD}{CUBE}restitution = 2\n"), ["body \"cube\"", "restitution must be in [0, 1]"])
    scene_refuses_an_unknown_contact_shape => (format!("{HEAD}{CUBE}contact = \"cone:1\"\n"), ["body \"cube\"", "contact `cone:1`: unknown shape `cone`", "capsule:H,R"])
    scene_refuses_a_contact_of_another_dimension => (format!("{HEAD}{CUBE}contact = \"box:1,1,1\"\n"), ["body \"cube\"", "contact `box:1,1,1`: a shape in 3 dimensions, expected 4"])
    scene_refuses_a_contact_offset_of_another_dimension => (format!("{HEAD}{CUBE}contact = [\"ball:0.5@1,0\"]\n"), ["body \"cube\"", "contact `ball:0.5@1,0`: offset has 2 numbers, expected 4"])
    scene_refuses_a_contact_with_a_negative_margin => (format!("{HEAD}{CUBE}contact = \"ball:0.5+margin=-1\"\n"), ["body \"cube\"", "contact `ball:0.5+margin=-1`"])
    scene_refuses_a_contact_that_is_not_a_shape => (format!("{HEAD}{CUBE}contact = 3\n"), ["body \"cube\"", "contact must be a string or a non-empty list of strings"])
    scene_refuses_a_contact_number_that_is_not_one => (format!("{HEAD}{CUBE}contact = \"capsule:1,x\"\n"), ["body \"cube\"", "contact `capsule:1,x`: capsule: `x` is not a number"])
    scene_refuses_a_contact_on_a_body_that_touches_nothing => (format!("{HEAD}{CUBE}collide = false\ncontact = \"ball:1\"\n"), ["body \"cube\"", "a body with collide = false touches nothing"])
    scene_refuses_a_body_jointed_to_itself => (format!("{HEAD}{CUBE}[[joint]]\nbody = \"cube\"\nother = \"cube\"\n"), ["joint 1", "the body itself"])
}

/// Bodies given a `contact` shape: a capsule (a body of a ball's inertia touching as a
/// capsule of radius 0.2) and a dumbbell of two balls of radius 0.2 (a compound) dropped on
/// the floor come to rest on it at the height of their radius, 0.2 (not the 0.3 of their
/// SPEC's ball), in 4D; the HTML draws them.
#[test]
fn scene_bodies_touch_with_their_contact_shape() {
    let text = r#"
dim = 4
gravity = [0.0, 0.0, 0.0, -9.81]
t_end = 2.0
dt = 0.01

[[body]]
name = "capsule"
shape = "ball:4,0.3"
contact = "capsule:0.4,0.2"
position = [0.0, 0.0, 0.0, 0.25]
friction = 0.5

[[body]]
name = "dumbbell"
shape = "ball:4,0.3"
contact = ["ball:0.2@-0.5,0,0,0", "ball:0.2@0.5,0,0,0"]
position = [0.0, 3.0, 0.0, 0.25]
friction = 0.5

[[plane]]
normal = [0, 0, 0, 1]
friction = 0.5
"#;
    let (dir, _) = scene_file(text);
    run_ok(
        dir.path(),
        &[
            "scene.toml",
            "--samples",
            "3",
            "--output",
            "run.json",
            "--html",
            "run.html",
        ],
    );
    let json = read_json(&dir.path().join("run.json"));
    for body in 0..2 {
        let x = matrix(&json["bodies"][body]["position"]);
        let v = matrix(&json["bodies"][body]["velocity"]);
        let z = x[2][3];
        assert!((z - 0.2).abs() < 1e-9, "body {body} rests at {z}");
        assert!(
            v[2].iter().all(|c| c.abs() < 1e-9),
            "body {body} moves: {:?}",
            v[2]
        );
    }
    let html = std::fs::read_to_string(dir.path().join("run.html")).unwrap();
    assert!(html.contains("capsule") && html.contains("dumbbell"));
}

#[test]
fn scene_refuses_bad_options_before_running() {
    let (dir, _) = scene_file(&format!("{HEAD}{CUBE}"));
    for (args, needle) in [
        (
            vec!["--output", "run.txt"],
            "--output `run.txt`: expected a file name ending in .json",
        ),
        (vec!["--html", "run.svg"], "--html `run.svg`"),
        (
            vec!["--plot", "run.png"],
            "--plot `run.png`: expected a file name ending in .svg",
        ),
        (vec!["--times", "0,2"], "beyond t_end 1"),
        (vec!["--samples", "1"], "--samples must be between 2"),
    ] {
        let out = rotorflow()
            .current_dir(dir.path())
            .args(["scene", "scene.toml"])
            .args(&args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(needle), "{err:?} lacks {needle:?}");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }
    let out = rotorflow()
        .arg("scene")
        .arg(dir.path().join("missing.toml"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot read the scene file"));
}

#[test]
fn scene_failed_run_exits_1_and_writes_nothing() {
    // A spring whose period 2π√(8/1) = 17.8 allows dt = 1, but whose damping is far too
    // strong for the step (c dt/m = 1250: each step turns the velocity round and multiplies
    // it): the run blows up.
    let text = "dim = 3\nt_end = 1000\ndt = 1\n[[body]]\nname = \"a\"\nshape = \"cuboid:1,1,1\"\n\
         position = [3, 0, 0]\n[[spring]]\nbody = \"a\"\nanchor = [0, 0, 0]\nstiffness = 1\n\
         damping = 1e4\n";
    let (dir, _) = scene_file(text);
    let out = rotorflow()
        .current_dir(dir.path())
        .args([
            "scene",
            "scene.toml",
            "--output",
            "run.json",
            "--csv-dir",
            "csv",
            "--html",
            "a.html",
            "--plot",
            "a.svg",
        ])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(!err.contains("NaN"), "{err}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

#[test]
fn scene_html_draws_and_animates_in_headless_chromium() {
    let Some(browser) = super::render::chromium() else {
        return;
    };
    let (dir, _) = scene_file(TWO_BODIES);
    run_ok(
        dir.path(),
        &["scene.toml", "--samples", "31", "--html", "a.html"],
    );
    let url = format!("file://{}#selftest", dir.path().join("a.html").display());
    let out = super::render::chromium_command(&browser, &dir.path().join("profile"))
        .arg("--dump-dom")
        .arg(url)
        .output()
        .expect("chromium runs");
    let dom = String::from_utf8_lossy(&out.stdout);
    let start = dom
        .find("<pre id=\"selftest\"")
        .unwrap_or_else(|| panic!("no selftest in DOM:\n{dom}"));
    let json_start = start + dom[start..].find('>').unwrap() + 1;
    let json_end = json_start + dom[json_start..].find("</pre>").unwrap();
    let report: Value = serde_json::from_str(&dom[json_start..json_end])
        .unwrap_or_else(|e| panic!("selftest did not run ({e}): {}", &dom[start..json_end]));
    assert_eq!(report["frames"].as_u64(), Some(31), "{report}");
    assert!(report["nonblank_first"].as_u64().unwrap() > 500, "{report}");
    assert!(report["changed"].as_u64().unwrap() > 100, "{report}");
    assert_eq!(report["errors"], serde_json::json!([]), "{report}");
}

/// The scene page draws the triad at the origin, the springs, the ball joints and their
/// anchors, and round bodies as wire frames; the page's self-test counts what it drew.
#[test]
fn scene_html_draws_springs_joints_anchors_triad_and_wire_frames() {
    // Under CI `chromium()` fails when there is no browser; locally it says it skips.
    let Some(browser) = super::render::chromium() else {
        return;
    };
    let text = format!(
        "{TWO_BODIES}\n[[spring]]\nbody = \"b\"\nanchor = [0, 0, 2]\nstiffness = 5\n\
         [[joint]]\nbody = \"a\"\npoint = [-0.5, 0, 0]\nanchor = [-1.5, 0, 0]\n"
    );
    let (dir, _) = scene_file(&text);
    run_ok(
        dir.path(),
        &["scene.toml", "--samples", "11", "--html", "a.html"],
    );
    let url = format!("file://{}#selftest", dir.path().join("a.html").display());
    let out = super::render::chromium_command(&browser, &dir.path().join("profile"))
        .arg("--dump-dom")
        .arg(url)
        .output()
        .expect("chromium runs");
    let dom = String::from_utf8_lossy(&out.stdout);
    let start = dom.find("<pre id=\"selftest\"").expect("a selftest report");
    let json_start = start + dom[start..].find('>').unwrap() + 1;
    let json_end = json_start + dom[json_start..].find("</pre>").unwrap();
    let report: Value = serde_json::from_str(&dom[json_start..json_end]).unwrap();
    assert_eq!(report["errors"], serde_json::json!([]), "{report}");
    // Two springs (a to b, b to its anchor), one joint, two anchors, one ellipsoid (b).
    assert_eq!(
        report["drawn"],
        serde_json::json!({ "triad": 3, "wireframes": 1, "springs": 2, "joints": 1, "anchors": 2 }),
        "{report}"
    );
}
