//! What a scene run writes: the JSON of `rotorflow scene --output`, one CSV per body and
//! one for the system, the HTML animation, the SVG plot (feature `viz`), and the summary.

use super::SceneError;
use super::format::Scene;
use crate::dynamics::motion::SystemTrajectory;
use serde_json::{Value, json};

/// Returns the JSON of a run: the keys of [`SystemTrajectory`] (`dim`, `times`, `bodies`
/// (each with `name`, `mass`, `position`, `velocity`, `attitude` as N rows per sample,
/// `omega`), `energy`, `kinetic_energy`, `potential_energy`, `momentum`,
/// `angular_momentum`, `contacts`, `body_contacts`, `steps`) and the scene's: `integrator`, `dt`, `t_end`,
/// `gravity`, `plane_names` (the bivector components), `planes` (the half-spaces as the
/// file gives them) and each body's `shape` (its SPEC).
///
/// # Errors
/// [`SceneError::Failed`] if a number is not finite.
pub fn to_json(scene: &Scene, record: &SystemTrajectory) -> Result<String, SceneError> {
    let not_finite = || SceneError::failed("a result is not finite");
    if record.first_non_finite().is_some() {
        return Err(not_finite());
    }
    let mut value = serde_json::to_value(record).map_err(|_| not_finite())?;
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
    let n = scene.dim;
    let plane_names: Vec<String> = crate::algebra::pairs(n)
        .map(|(i, j)| crate::algebra::plane_name(n, i, j))
        .collect();
    if let Some(object) = value.as_object_mut() {
        object.insert("integrator".into(), json!(scene.integrator.name()));
        object.insert("dt".into(), json!(scene.dt));
        object.insert("t_end".into(), json!(scene.t_end));
        object.insert("gravity".into(), json!(scene.gravity));
        object.insert("plane_names".into(), json!(plane_names));
        object.insert("planes".into(), Value::Array(planes));
    }
    if let Some(bodies) = value.get_mut("bodies").and_then(Value::as_array_mut) {
        for (body, b) in bodies.iter_mut().zip(&scene.bodies) {
            if let Some(object) = body.as_object_mut() {
                object.insert("shape".into(), json!(b.parsed.spec));
            }
        }
    }
    let mut text = serde_json::to_string(&value).map_err(|_| not_finite())?;
    text.push('\n');
    Ok(text)
}

/// Returns the CSV files of a run: `(file name, text)` for each body (`<name>.csv`: t,
/// x1..xN, v1..vN, R11..RNN row-major, w12, …) and `system.csv` (t, energy, p1..pN, L12, …).
///
/// # Errors
/// [`SceneError::Failed`] if a number is not finite.
pub fn csv_files(record: &SystemTrajectory) -> Result<Vec<(String, String)>, SceneError> {
    record
        .csv_files()
        .map_err(|_| SceneError::failed("a result is not finite"))
}

/// Returns the drawing of a scene: each body's shape from its SPEC, the springs and joints,
/// and the axis of the gravity upwards.
#[cfg(feature = "viz")]
pub fn drawing(scene: &Scene, title: &str) -> crate::viz::trajectory::Drawing {
    use super::format::SceneAnchor;
    use crate::viz::scene::{SceneLink, up_axis};
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
    crate::viz::trajectory::Drawing {
        title: title.to_string(),
        shapes: scene
            .bodies
            .iter()
            .map(|b| match &b.contact {
                // A body drawn as the shape it touches with when the scene gives one.
                Some(c) => crate::viz::Shape::of_contact_shape(c, b.parsed.dim),
                None => crate::viz::Shape::of_body(&b.parsed),
            })
            .collect(),
        links,
        up: up_axis(&scene.gravity),
    }
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
pub fn summary(scene: &Scene, record: &SystemTrajectory) -> String {
    let file = &scene.file;
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
    for track in &record.bodies {
        out.push_str(&format!(
            "  {}: ({})\n",
            track.name,
            list(&track.position[last])
        ));
    }
    out
}
