//! The pictures of a recorded run of a [`System`]: the HTML animation of its bodies, planes,
//! springs, joints and contacts ([`animation_html`]), and the SVG plots of its energies,
//! momenta and positions over time ([`plot_svg`]).

use super::Shape;
use super::plot::{PlotError, PlotSpec, Series, stacked_plot, subscript};
use super::scene::{SceneAnimation, SceneBodyFrames, SceneLink, scene_html};
use crate::dynamics::motion::forques::Anchor;
use crate::dynamics::motion::{System, SystemTrajectory};

/// What the animation of a run draws besides the run itself.
#[derive(Clone, Debug)]
pub struct Drawing {
    /// The title of the page.
    pub title: String,
    /// What is drawn of each body, in the order of the run's bodies.
    pub shapes: Vec<Shape>,
    /// The springs and ball joints.
    pub links: Vec<SceneLink>,
    /// The axis drawn upwards (0-based), e.g. that of gravity
    /// ([`up_axis`](super::scene::up_axis)); `None` shows the axes along which the bodies
    /// move most.
    pub up: Option<usize>,
}

impl Drawing {
    /// Returns the drawing of `system`'s bodies by their contact shapes
    /// ([`Shape::of_contact_shape`]) with its ball joints, titled `title`, no axis upwards.
    pub fn of_system(system: &System, title: &str) -> Drawing {
        let n = system.dim();
        let links = system
            .joints()
            .iter()
            .map(|j| {
                let (other, end) = match &j.other {
                    Anchor::World(x) => (None, x.as_slice().to_vec()),
                    Anchor::Body(k, p) => (Some(*k), p.as_slice().to_vec()),
                };
                SceneLink {
                    spring: false,
                    body: j.body,
                    point: j.point.as_slice().to_vec(),
                    other,
                    end,
                }
            })
            .collect();
        Drawing {
            title: title.to_string(),
            shapes: system
                .shapes()
                .iter()
                .map(|s| Shape::of_contact_shape(s, n))
                .collect(),
            links,
            up: None,
        }
    }
}

/// Returns the self-contained HTML animation of `run` (see [`super::scene`]): each body's
/// shape placed at each sample, the run's planes, the drawing's springs and joints, and the
/// contact points of each sample, marked and flashed. Bodies without a shape in
/// `drawing.shapes` are drawn as a unit cross.
pub fn animation_html(run: &SystemTrajectory, drawing: &Drawing) -> String {
    let n = run.dim;
    let bodies: Vec<SceneBodyFrames> = run
        .bodies
        .iter()
        .enumerate()
        .map(|(k, track)| SceneBodyFrames {
            name: track.name.clone(),
            shape: drawing
                .shapes
                .get(k)
                .cloned()
                .unwrap_or_else(|| Shape::cross(n, 1.0)),
            positions: track.position.clone(),
            matrices: (0..track.attitude.len())
                .map(|k| track.attitude_matrix(k))
                .collect(),
        })
        .collect();
    let planes: Vec<(Vec<f64>, f64)> = run
        .planes
        .iter()
        .map(|p| (p.normal.clone(), p.offset))
        .collect();
    let contacts: Vec<Vec<Vec<f64>>> = run
        .contacts
        .iter()
        .map(|c| c.iter().map(|c| c.point.clone()).collect())
        .collect();
    scene_html(&SceneAnimation {
        title: &drawing.title,
        dim: n,
        times: &run.times,
        bodies: &bodies,
        planes: &planes,
        links: &drawing.links,
        up: drawing.up,
        contacts: &contacts,
    })
}

/// Returns the SVG plot of `run` under `title`: the energies (kinetic, potential, total),
/// the linear and angular momentum (their magnitudes) and the positions of the centres of
/// mass over time, in three panels of one page.
///
/// # Errors
/// [`PlotError`] if a panel has nothing finite to draw.
pub fn plot_svg(run: &SystemTrajectory, title: &str) -> Result<String, PlotError> {
    let over_time = |values: &[f64]| -> Vec<(f64, f64)> {
        run.times
            .iter()
            .copied()
            .zip(values.iter().copied())
            .collect()
    };
    let norms = |rows: &[Vec<f64>]| -> Vec<(f64, f64)> {
        run.times
            .iter()
            .zip(rows)
            .map(|(t, v)| (*t, v.iter().map(|x| x * x).sum::<f64>().sqrt()))
            .collect()
    };
    let series = |name: &str, points| Series {
        name: name.to_string(),
        points,
    };
    let energies = vec![
        series("kinetic T", over_time(&run.kinetic_energy)),
        series("potential V", over_time(&run.potential_energy)),
        series("total E = T + V", over_time(&run.energy)),
    ];
    let momenta = vec![
        series("|p| (linear momentum)", norms(&run.momentum)),
        series(
            "|L| (angular momentum about the origin)",
            norms(&run.angular_momentum),
        ),
    ];
    let mut positions = Vec::with_capacity(run.bodies.len() * run.dim);
    for track in &run.bodies {
        for i in 0..run.dim {
            let points = run
                .times
                .iter()
                .zip(&track.position)
                .map(|(t, x)| (*t, x[i]))
                .collect();
            positions.push(series(
                &format!("{} x{}", track.name, subscript(&(i + 1).to_string())),
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
}
