//! Running a scene: the [`System`] of its bodies, planes, springs and joints, stepped from 0
//! to t_end with every sample time hit exactly.

use super::super::error::{CliError, CliResult};
use super::super::output::Progress;
use super::format::{IntegratorKind, Scene, SceneAnchor};
use nalgebra::DMatrix;
use rotorflow::algebra::{Bivector, Vector};
use rotorflow::dynamics::motion::forques::{Anchor, Gravity, Spring};
use rotorflow::dynamics::motion::{
    BallJoint, ContactShape, HalfSpace, MotionIntegrator, MotionRk4, MotionSplitting, MovingBody,
    System,
};
use rotorflow::dynamics::{Attitude, DynamicsError};

/// The samples of one body.
#[derive(Clone, Debug, Default)]
pub struct BodyTrack {
    /// Centre of mass per sample.
    pub position: Vec<Vec<f64>>,
    /// Velocity per sample.
    pub velocity: Vec<Vec<f64>>,
    /// Attitude (own axes → space) per sample.
    pub attitude: Vec<DMatrix<f64>>,
    /// Angular velocity in the body's own axes per sample.
    pub omega: Vec<Vec<f64>>,
}

/// What a run of a scene records at the sample times.
#[derive(Clone, Debug)]
pub struct Record {
    /// The sample times.
    pub times: Vec<f64>,
    /// One track per body, in the order of the scene.
    pub bodies: Vec<BodyTrack>,
    /// The energy per sample.
    pub energy: Vec<f64>,
    /// The kinetic energy per sample.
    pub kinetic_energy: Vec<f64>,
    /// The potential energy (gravity and springs) per sample.
    pub potential_energy: Vec<f64>,
    /// The linear momentum per sample.
    pub momentum: Vec<Vec<f64>>,
    /// The angular momentum about the origin per sample.
    pub angular_momentum: Vec<Vec<f64>>,
    /// The number of steps taken.
    pub steps: usize,
}

fn vector(x: &[f64]) -> CliResult<Vector> {
    Vector::from_components(x).map_err(|e| CliError::input(e.to_string()))
}

fn anchor(a: &SceneAnchor) -> CliResult<Anchor> {
    Ok(match a {
        SceneAnchor::World(x) => Anchor::World(vector(x)?),
        SceneAnchor::Body(j, p) => Anchor::Body(*j, vector(p)?),
    })
}

/// Returns the system of the scene at t = 0.
///
/// # Errors
/// [`CliError::Input`] naming the body or the part the dynamics refuses.
pub fn build_system(scene: &Scene, file: &str) -> CliResult<System> {
    let n = scene.dim;
    let mut bodies = Vec::with_capacity(scene.bodies.len());
    for b in &scene.bodies {
        let fail = |e: &dyn std::fmt::Display| {
            CliError::input(format!("{file}: body \"{}\": {e}", b.name))
        };
        let attitude = Attitude::from_matrix(&b.attitude).map_err(|e| fail(&e))?;
        let omega = Bivector::from_components(n, &b.omega).map_err(|e| fail(&e))?;
        let shape = ContactShape::from_geometry(&b.parsed.geometry);
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
    let fail =
        |what: String, e: &dyn std::fmt::Display| CliError::input(format!("{file}: {what}: {e}"));
    let mut system = System::new(bodies).map_err(|e| fail("scene".into(), &e))?;
    if scene.gravity.iter().any(|g| *g != 0.0) {
        system
            .add_forque(Gravity(vector(&scene.gravity)?))
            .map_err(|e| fail("gravity".into(), &e))?;
    }
    for (k, s) in scene.springs.iter().enumerate() {
        system
            .add_forque(Spring {
                body: s.body,
                point: vector(&s.point)?,
                anchor: anchor(&s.anchor)?,
                stiffness: s.stiffness,
                rest_length: s.rest_length,
                damping: s.damping,
            })
            .map_err(|e| fail(format!("spring {}", k + 1), &e))?;
    }
    for (k, p) in scene.planes.iter().enumerate() {
        let h = HalfSpace::new(&vector(&p.normal)?, p.offset, p.friction, p.restitution)
            .map_err(|e| fail(format!("plane {}", k + 1), &e))?;
        system
            .add_half_space(h)
            .map_err(|e| fail(format!("plane {}", k + 1), &e))?;
    }
    for (k, j) in scene.joints.iter().enumerate() {
        system
            .add_ball_joint(BallJoint {
                body: j.body,
                point: vector(&j.point)?,
                other: anchor(&j.other)?,
            })
            .map_err(|e| fail(format!("joint {}", k + 1), &e))?;
    }
    system
        .check_contacts()
        .map_err(|e| CliError::input(format!("{file}: {}", start_problem(scene, &e))))?;
    Ok(system)
}

/// What [`System::check_contacts`] refused, with the scene's names for bodies and planes.
fn start_problem(scene: &Scene, e: &rotorflow::dynamics::DynamicsError) -> String {
    use rotorflow::dynamics::DynamicsError;
    use rotorflow::dynamics::motion::MotionError;
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

/// Appends the state of `system` at time `t` to `record`.
fn sample(system: &System, t: f64, record: &mut Record) {
    record.times.push(t);
    for (b, track) in system.bodies().iter().zip(record.bodies.iter_mut()) {
        track.position.push(b.position().as_slice().to_vec());
        track.velocity.push(b.velocity().as_slice().to_vec());
        track.attitude.push(b.attitude().to_matrix());
        track.omega.push(b.omega().as_slice().to_vec());
    }
    record.energy.push(system.energy(t));
    record.kinetic_energy.push(system.kinetic_energy());
    record.potential_energy.push(system.potential_energy(t));
    record
        .momentum
        .push(system.linear_momentum().as_slice().to_vec());
    record
        .angular_momentum
        .push(system.angular_momentum().as_slice().to_vec());
}

/// Steps `system` from 0 to `scene.t_end` by `scene.dt`, shortening the steps that would
/// pass a sample time (or t_end), and records the state at each of `times` (increasing, in
/// [0, t_end]).
///
/// # Errors
/// [`CliError::Runtime`] when the integrator fails (a state that is no longer finite, say).
pub fn run(
    scene: &Scene,
    system: &mut System,
    times: &[f64],
    progress: &mut Progress,
) -> CliResult<Record> {
    let mut integrator: Box<dyn MotionIntegrator> = match scene.integrator {
        IntegratorKind::Splitting => Box::new(MotionSplitting::new()),
        IntegratorKind::Rk4 => Box::new(MotionRk4::new()),
    };
    let mut record = Record {
        times: Vec::with_capacity(times.len()),
        bodies: vec![BodyTrack::default(); scene.bodies.len()],
        energy: Vec::with_capacity(times.len()),
        kinetic_energy: Vec::with_capacity(times.len()),
        potential_energy: Vec::with_capacity(times.len()),
        momentum: Vec::with_capacity(times.len()),
        angular_momentum: Vec::with_capacity(times.len()),
        steps: 0,
    };
    let dt = scene.dt;
    let mut t = 0.0;
    let mut targets: Vec<(f64, bool)> = times.iter().map(|&s| (s, true)).collect();
    if times.last().is_none_or(|&last| last < scene.t_end) {
        targets.push((scene.t_end, false));
    }
    // The integrators' errors name the time of the step that failed.
    let failed = |e: DynamicsError| {
        let hint = if matches!(e, DynamicsError::NonFinite { .. }) {
            " (try a smaller dt)"
        } else {
            ""
        };
        CliError::runtime(format!(
            "the {} integrator failed: {e}{hint}",
            scene.integrator.name()
        ))
    };
    for (target, is_sample) in targets {
        if t < target {
            // Steps of dt up to the last one, which ends on the target exactly; a remainder
            // below a millionth of dt joins the step before it. The steps of dt are taken
            // together, so that the integrator can share work between them.
            let mut full = 0;
            while t + (full + 1) as f64 * dt < target - 1e-6 * dt {
                full += 1;
            }
            let end = t + full as f64 * dt;
            integrator.advance(system, t, dt, full).map_err(failed)?;
            integrator.step(system, end, target - end).map_err(failed)?;
            record.steps += full + 1;
            t = target;
        }
        if is_sample {
            sample(system, target, &mut record);
            progress.advance(1);
        }
    }
    let finite = record.energy.iter().all(|x| x.is_finite())
        && record.momentum.iter().flatten().all(|x| x.is_finite())
        && record
            .angular_momentum
            .iter()
            .flatten()
            .all(|x| x.is_finite());
    if !finite {
        return Err(CliError::runtime(
            "the motion is no longer finite (try a smaller dt)",
        ));
    }
    Ok(record)
}
