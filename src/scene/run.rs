//! Running a scene: the [`System`] of its bodies, planes, springs and joints, stepped from 0
//! to t_end with every sample time hit exactly ([`System::record_with`]).

use super::SceneError;
use super::format::{IntegratorKind, Scene, SceneAnchor};
use crate::algebra::{Bivector, Vector};
use crate::dynamics::motion::forques::{Anchor, Gravity, Spring};
use crate::dynamics::motion::{
    BallJoint, HalfSpace, MotionIntegrator, MotionRk4, MotionSplitting, MovingBody, SoftStep,
    System, SystemTrajectory,
};
use crate::dynamics::{Attitude, DynamicsError};

fn vector(x: &[f64]) -> Result<Vector, SceneError> {
    Vector::from_components(x).map_err(|e| SceneError::invalid(e.to_string()))
}

fn anchor(a: &SceneAnchor) -> Result<Anchor, SceneError> {
    Ok(match a {
        SceneAnchor::World(x) => Anchor::World(vector(x)?),
        SceneAnchor::Body(j, p) => Anchor::Body(*j, vector(p)?),
    })
}

/// Returns the system of the scene at t = 0.
///
/// # Errors
/// [`SceneError::Invalid`] naming the body or the part the dynamics refuses.
pub fn build_system(scene: &Scene) -> Result<System, SceneError> {
    let file = scene.file.as_str();
    let n = scene.dim;
    let mut bodies = Vec::with_capacity(scene.bodies.len());
    for b in &scene.bodies {
        let fail = |e: &dyn std::fmt::Display| {
            SceneError::invalid(format!("{file}: body \"{}\": {e}", b.name))
        };
        let attitude = Attitude::from_matrix(&b.attitude).map_err(|e| fail(&e))?;
        let omega = Bivector::from_components(n, &b.omega).map_err(|e| fail(&e))?;
        let shape = b.contact_shape();
        let mut body = if b.fixed {
            MovingBody::fixed(shape, attitude, &vector(&b.position)?)
        } else {
            MovingBody::new(
                b.mass,
                b.parsed.inertia.clone(),
                attitude,
                &vector(&b.position)?,
                &vector(&b.velocity)?,
                &omega,
            )
            .and_then(|m| m.with_shape(shape))
        }
        .map_err(|e| fail(&e))?
        .with_collisions(b.collide);
        if let Some(mu) = b.friction {
            body = body.with_friction(mu).map_err(|e| fail(&e))?;
        }
        if let Some(e) = b.restitution {
            body = body.with_restitution(e).map_err(|e| fail(&e))?;
        }
        bodies.push(body);
    }
    let fail = |what: String, e: &dyn std::fmt::Display| {
        SceneError::invalid(format!("{file}: {what}: {e}"))
    };
    let mut system = System::new(bodies).map_err(|e| fail("scene".into(), &e))?;
    if scene.gravity.iter().any(|g| *g != 0.0) {
        system
            .add_forque(Gravity(vector(&scene.gravity)?))
            .map_err(|e| fail("gravity".into(), &e))?;
    }
    // The error of the k-th (0-based) part of a kind, numbered from 1 as the scene's reader
    // counts.
    let numbered = |what: &str, k: usize| {
        let what = format!("{what} {}", k + 1);
        move |e: DynamicsError| fail(what, &e)
    };
    for (k, s) in scene.springs.iter().enumerate() {
        let (body, point, anchor) = (s.body, vector(&s.point)?, anchor(&s.anchor)?);
        let spring = Spring {
            body,
            point,
            anchor,
            stiffness: s.stiffness,
            rest_length: s.rest_length,
            damping: s.damping,
        };
        system.add_forque(spring).map_err(numbered("spring", k))?;
    }
    for (k, p) in scene.planes.iter().enumerate() {
        let h = HalfSpace::new(&vector(&p.normal)?, p.offset, p.friction, p.restitution)
            .map_err(numbered("plane", k))?;
        system.add_half_space(h).map_err(numbered("plane", k))?;
    }
    for (k, j) in scene.joints.iter().enumerate() {
        let (body, point, other) = (j.body, vector(&j.point)?, anchor(&j.other)?);
        let joint = BallJoint { body, point, other };
        system.add_ball_joint(joint).map_err(numbered("joint", k))?;
    }
    system
        .check_contacts()
        .map_err(|e| SceneError::invalid(format!("{file}: {}", start_problem(scene, &e))))?;
    Ok(system)
}

/// What [`System::check_contacts`] refused, with the scene's names for bodies and planes.
fn start_problem(scene: &Scene, e: &DynamicsError) -> String {
    use crate::dynamics::motion::MotionError;
    let name = |i: usize| format!("body \"{}\"", scene.bodies[i].name);
    match e {
        DynamicsError::Motion(MotionError::StartsInside {
            body,
            half_space,
            depth,
            ..
        }) => format!(
            "{} starts {depth:.3e} inside plane {} (its lowest point below the plane); place it on or above the plane",
            name(*body),
            half_space + 1
        ),
        DynamicsError::Motion(MotionError::StartsOverlapping { a, b, depth, .. }) => format!(
            "{} and {} start overlapping by {depth:.3e}; place them apart, or set collide = false on one",
            name(*a),
            name(*b)
        ),
        other => other.to_string(),
    }
}

/// Steps `system` (the scene's, from [`build_system`]) from 0 to `scene.t_end` by
/// `scene.dt` with the scene's integrator, and records the state at each of `times`
/// (increasing, in [0, t_end]) under the scene's body names; `observe` is called with the
/// number of samples taken after each one.
///
/// # Errors
/// [`SceneError::Invalid`] for bad sample times; [`SceneError::Failed`] when the integrator
/// fails (a state that is no longer finite, say).
pub fn run(
    scene: &Scene,
    system: &mut System,
    times: &[f64],
    observe: &mut dyn FnMut(usize),
) -> Result<SystemTrajectory, SceneError> {
    let mut integrator: Box<dyn MotionIntegrator> = match scene.integrator {
        IntegratorKind::Splitting => Box::new(MotionSplitting::new()),
        IntegratorKind::Rk4 => Box::new(MotionRk4::new()),
        IntegratorKind::Soft => Box::new(SoftStep::new()),
    };
    let mut record = system
        .record_with(integrator.as_mut(), scene.dt, times, scene.t_end, observe)
        .map_err(|e| match e {
            DynamicsError::InvalidSampling { reason } => {
                SceneError::invalid(format!("{}: {reason}", scene.file))
            }
            // The integrators' errors name the time of the step that failed.
            e => {
                let hint = if matches!(e, DynamicsError::NonFinite { .. }) {
                    " (try a smaller dt)"
                } else {
                    ""
                };
                SceneError::failed(format!(
                    "the {} integrator failed: {e}{hint}",
                    scene.integrator.name()
                ))
            }
        })?;
    for (track, body) in record.bodies.iter_mut().zip(&scene.bodies) {
        track.name.clone_from(&body.name);
    }
    Ok(record)
}
