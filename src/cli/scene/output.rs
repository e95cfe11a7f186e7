//! What a scene run writes: JSON, one CSV per body and one for the system, the HTML
//! animation, the SVG plot, and the summary on standard output.

use super::super::error::{CliError, CliResult};
use super::super::output::{matrix_json, number, plane_names, to_json_text};
use super::super::viz::plot::{PlotSpec, Series, stacked_plot, subscript};
use super::super::viz::scene::{SceneAnimation, SceneBodyFrames, SceneLink, scene_html, up_axis};
use super::format::{Scene, SceneAnchor};
use super::run::Record;
use serde_json::{Value, json};

/// Returns the JSON of a run: `dim`, `integrator`, `dt`, `t_end`, `plane_names` (the
/// bivector components), `planes` (the half-spaces), `times`, `bodies` (each with `name`,
/// `shape`, `mass`, `position`, `velocity`, `attitude` as N rows per sample, `omega`),
/// `energy`, `kinetic_energy`, `potential_energy`, `momentum`, `angular_momentum`.
pub fn to_json(scene: &Scene, record: &Record) -> Value {
    let bodies: Vec<Value> = scene
        .bodies
        .iter()
        .zip(&record.bodies)
        .map(|(b, track)| {
            json!({
                "name": b.name,
                "shape": b.parsed.spec,
                "mass": b.mass,
                "position": track.position,
                "velocity": track.velocity,
                "attitude": track.attitude.iter().map(matrix_json).collect::<Vec<_>>(),
                "omega": track.omega,
            })
        })
        .collect();
    let planes: Vec<Value> = scene
        .planes
        .iter()
        .map(|p| {
            json!({
                "normal": p.normal,
                "offset": p.offset,
                "friction": p.friction,
                "restitution": p.restitution,
            })
        })
        .collect();
    json!({
        "dim": scene.dim,
        "integrator": scene.integrator.name(),
        "dt": scene.dt,
        "t_end": scene.t_end,
        "gravity": scene.gravity,
        "plane_names": plane_names(scene.dim),
        "planes": planes,
        "times": record.times,
        "bodies": bodies,
        "energy": record.energy,
        "kinetic_energy": record.kinetic_energy,
        "potential_energy": record.potential_energy,
        "momentum": record.momentum,
        "angular_momentum": record.angular_momentum,
    })
}

/// Returns the JSON text, refusing non-finite numbers.
///
/// # Errors
/// [`CliError::Runtime`] if a number is not finite.
pub fn json_text(scene: &Scene, record: &Record) -> CliResult<String> {
    to_json_text(&to_json(scene, record), false)
}

/// The names of the attitude entries R_rc, row-major (`R11`, …; `R1_10` from N = 10 on).
fn attitude_names(n: usize) -> Vec<String> {
    let mut names = Vec::with_capacity(n * n);
    for r in 1..=n {
        for c in 1..=n {
            names.push(if n < 10 {
                format!("R{r}{c}")
            } else {
                format!("R{r}_{c}")
            });
        }
    }
    names
}

fn csv_row(values: impl IntoIterator<Item = f64>) -> String {
    let mut row = values.into_iter().map(number).collect::<Vec<_>>().join(",");
    row.push('\n');
    row
}

/// Returns the CSV files of a run: `(file name, text)` for each body (`<name>.csv`: t,
/// x1..xN, v1..vN, R11..RNN row-major, w12, …) and `system.csv` (t, energy, p1..pN, L12, …).
///
/// # Errors
/// [`CliError::Runtime`] if a number is not finite.
pub fn csv_files(scene: &Scene, record: &Record) -> CliResult<Vec<(String, String)>> {
    let n = scene.dim;
    let planes = plane_names(n);
    let mut files = Vec::with_capacity(scene.bodies.len() + 1);
    for (b, track) in scene.bodies.iter().zip(&record.bodies) {
        let mut header = vec!["t".to_string()];
        header.extend((1..=n).map(|i| format!("x{i}")));
        header.extend((1..=n).map(|i| format!("v{i}")));
        header.extend(attitude_names(n));
        header.extend(planes.iter().map(|p| format!("w{p}")));
        let mut text = header.join(",") + "\n";
        for (k, t) in record.times.iter().enumerate() {
            let m = &track.attitude[k];
            let row = std::iter::once(*t)
                .chain(track.position[k].iter().copied())
                .chain(track.velocity[k].iter().copied())
                .chain((0..n).flat_map(|r| (0..n).map(move |c| m[(r, c)])))
                .chain(track.omega[k].iter().copied());
            text.push_str(&csv_row(row));
        }
        files.push((format!("{}.csv", b.name), text));
    }
    let mut header = vec!["t".to_string(), "energy".to_string()];
    header.extend((1..=n).map(|i| format!("p{i}")));
    header.extend(planes.iter().map(|p| format!("L{p}")));
    let mut text = header.join(",") + "\n";
    for (k, t) in record.times.iter().enumerate() {
        let row = [*t, record.energy[k]]
            .into_iter()
            .chain(record.momentum[k].iter().copied())
            .chain(record.angular_momentum[k].iter().copied());
        text.push_str(&csv_row(row));
    }
    files.push(("system.csv".to_string(), text));
    if files
        .iter()
        .any(|(_, text)| text.contains("NaN") || text.contains("inf"))
    {
        return Err(CliError::runtime("a result is not finite"));
    }
    Ok(files)
}

/// Returns the HTML animation of a run; the axis of the gravity is drawn upwards.
pub fn html(scene: &Scene, record: &Record, title: &str) -> String {
    let bodies: Vec<SceneBodyFrames> = scene
        .bodies
        .iter()
        .zip(&record.bodies)
        .map(|(b, track)| SceneBodyFrames {
            name: b.name.clone(),
            shape: super::super::spec::shape(&b.parsed),
            positions: track.position.clone(),
            matrices: track.attitude.clone(),
        })
        .collect();
    let planes: Vec<(Vec<f64>, f64)> = scene
        .planes
        .iter()
        .map(|p| (p.normal.clone(), p.offset))
        .collect();
    let ends = |a: &SceneAnchor| match a {
        SceneAnchor::World(x) => (None, x.clone()),
        SceneAnchor::Body(j, p) => (Some(*j), p.clone()),
    };
    let springs = scene
        .springs
        .iter()
        .map(|s| (true, s.body, &s.point, &s.anchor));
    let joints = scene
        .joints
        .iter()
        .map(|j| (false, j.body, &j.point, &j.other));
    let links: Vec<SceneLink> = springs
        .chain(joints)
        .map(|(spring, body, point, anchor)| {
            let (other, end) = ends(anchor);
            SceneLink {
                spring,
                body,
                point: point.clone(),
                other,
                end,
            }
        })
        .collect();
    scene_html(&SceneAnimation {
        title,
        dim: scene.dim,
        times: &record.times,
        bodies: &bodies,
        planes: &planes,
        links: &links,
        up: up_axis(&scene.gravity),
    })
}

/// Returns the SVG plot of a run: the energies (kinetic, potential, total), the linear and
/// angular momentum (their magnitudes) and the positions of the centres of mass over time,
/// in three panels of one page.
///
/// # Errors
/// [`CliError::Runtime`] if a panel has nothing finite to draw.
pub fn plot(scene: &Scene, record: &Record, title: &str) -> CliResult<String> {
    let over_time = |values: &[f64]| -> Vec<(f64, f64)> {
        record
            .times
            .iter()
            .copied()
            .zip(values.iter().copied())
            .collect()
    };
    let norms = |rows: &[Vec<f64>]| -> Vec<(f64, f64)> {
        record
            .times
            .iter()
            .zip(rows)
            .map(|(t, v)| (*t, norm(v)))
            .collect()
    };
    let series = |name: &str, points| Series {
        name: name.to_string(),
        points,
    };
    let energies = vec![
        series("kinetic T", over_time(&record.kinetic_energy)),
        series("potential V", over_time(&record.potential_energy)),
        series("total E = T + V", over_time(&record.energy)),
    ];
    let momenta = vec![
        series("|p| (linear momentum)", norms(&record.momentum)),
        series(
            "|L| (angular momentum about the origin)",
            norms(&record.angular_momentum),
        ),
    ];
    let mut positions = Vec::with_capacity(scene.bodies.len() * scene.dim);
    for (b, track) in scene.bodies.iter().zip(&record.bodies) {
        for i in 0..scene.dim {
            let points = record
                .times
                .iter()
                .zip(&track.position)
                .map(|(t, x)| (*t, x[i]))
                .collect();
            positions.push(series(
                &format!("{} x{}", b.name, subscript(&(i + 1).to_string())),
                points,
            ));
        }
    }
    let panel = |title, y_label| PlotSpec {
        title,
        x_label: "time t",
        y_label,
        log_y: false,
        markers: false,
    };
    stacked_plot(
        title,
        &[
            (panel("energy", "T, V, E"), energies),
            (panel("momentum", "|p|, |L|"), momenta),
            (panel("centre of mass of each body", "xᵢ"), positions),
        ],
    )
    .map_err(|e| CliError::runtime(format!("cannot draw the plot: {e}")))
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn diff(a: &[f64], b: &[f64]) -> Vec<f64> {
    a.iter().zip(b).map(|(x, y)| x - y).collect()
}

fn list(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x:.6}"))
        .collect::<Vec<_>>()
        .join(", ")
}

fn count(k: usize, one: &str, many: &str) -> String {
    format!("{k} {}", if k == 1 { one } else { many })
}

/// Returns what a scene holds, in one line.
pub fn contents(scene: &Scene) -> String {
    format!(
        "{} in {} dimensions, {}, {}, {}; {} integrator, dt = {}, t_end = {}",
        count(scene.bodies.len(), "body", "bodies"),
        scene.dim,
        count(scene.planes.len(), "plane", "planes"),
        count(scene.springs.len(), "spring", "springs"),
        count(scene.joints.len(), "joint", "joints"),
        scene.integrator.name(),
        scene.dt,
        scene.t_end
    )
}

/// Returns the summary for people: the run, the energy drift, the momentum changes and the
/// final positions.
pub fn summary(scene: &Scene, record: &Record, file: &str) -> String {
    let last = record.times.len().saturating_sub(1);
    let mut out = format!(
        "scene {file}: {}; {} steps\n",
        contents(scene),
        record.steps
    );
    if record.times.is_empty() {
        return out;
    }
    let t_last = record.times[last];
    let (e0, e1) = (record.energy[0], record.energy[last]);
    out.push_str(&format!(
        "energy: {e0:.9} at t = {} → {e1:.9} at t = {t_last} (relative change {:.3e})\n",
        record.times[0],
        (e1 - e0).abs() / e0.abs().max(f64::MIN_POSITIVE)
    ));
    out.push_str(&format!(
        "linear momentum change |Δp| = {:.3e}; angular momentum change |ΔL| = {:.3e}\n",
        norm(&diff(&record.momentum[last], &record.momentum[0])),
        norm(&diff(
            &record.angular_momentum[last],
            &record.angular_momentum[0]
        ))
    ));
    out.push_str(&format!("final positions (t = {t_last}):\n"));
    for (b, track) in scene.bodies.iter().zip(&record.bodies) {
        out.push_str(&format!(
            "  {}: ({})\n",
            b.name,
            list(&track.position[last])
        ));
    }
    out
}
