//! The same 3D scenes for rotorflow and for Rapier, and what a run of them measures.
//!
//! A scene is a list of [`Item`]s (boxes and balls of mass 1 with a placement and a
//! velocity) over the floor z = 0 under gravity g = 9.81 along −z, friction μ = 0.5 and no
//! restitution everywhere. [`rotorflow_system`] and [`rapier_world`] build it for each
//! engine; [`Pose`]s read back from either are compared by [`depth`], closed forms in f64
//! that neither engine's collision code enters.

use rapier3d::prelude as rp;
use rotorflow::dynamics::motion::forques::Gravity;
use rotorflow::dynamics::motion::{
    HalfSpace, MotionIntegrator, MotionSplitting, MovingBody, SoftStep, System,
};
use rotorflow::inertia::spec::parse_body;
use rotorflow::prelude::*;

/// The step of both engines, Rapier's default (s).
pub const H: f64 = 1.0 / 60.0;
/// Gravity (m/s²), along −z.
pub const G: f64 = 9.81;
/// The friction coefficient of every body and of the floor.
pub const FRICTION: f64 = 0.5;

/// A convex shape: a box by its half-lengths, or a ball by its radius.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    Cuboid([f64; 3]),
    Ball(f64),
}

/// One body of a scene: mass 1, turned by `yaw` about the vertical (e₁ → (cos, sin, 0)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Item {
    pub shape: Shape,
    pub position: [f64; 3],
    pub velocity: [f64; 3],
    pub yaw: f64,
}

impl Item {
    fn at(shape: Shape, position: [f64; 3]) -> Item {
        Item {
            shape,
            position,
            velocity: [0.0; 3],
            yaw: 0.0,
        }
    }
}

/// The half-lengths of the resting boxes.
pub const RESTING_BOX: [f64; 3] = [0.5, 0.6, 0.7];
/// The radius of the rolling balls and their launch speed along x (without spin).
pub const ROLLING_BALL: (f64, f64) = (0.5, 1.0);

/// 1,000 boxes on a 40 × 25 grid, 2 apart, resting on their largest face.
pub fn resting_boxes() -> Vec<Item> {
    resting_boxes_of(1000)
}

/// The first `count` boxes of [`resting_boxes`]'s grid (rows of 40): the same scene
/// smaller, to see how the time per body grows with the number of bodies.
pub fn resting_boxes_of(count: usize) -> Vec<Item> {
    (0..count)
        .map(|k| {
            let (i, j) = ((k % 40) as f64, (k / 40) as f64);
            Item::at(
                Shape::Cuboid(RESTING_BOX),
                [2.0 * i, 2.0 * j, RESTING_BOX[2]],
            )
        })
        .collect()
}

/// 1,000 balls on a 40 × 25 grid, 2 apart, launched along x without spin: friction spins
/// them up and they roll on at 5/7 of the launch speed. Each row moves along itself at one
/// speed, so no two balls meet.
pub fn rolling_balls() -> Vec<Item> {
    let (radius, speed) = ROLLING_BALL;
    (0..1000)
        .map(|k| {
            let (i, j) = ((k % 40) as f64, (k / 40) as f64);
            Item {
                velocity: [speed, 0.0, 0.0],
                ..Item::at(Shape::Ball(radius), [2.0 * i, 2.0 * j, radius])
            }
        })
        .collect()
}

/// A two-dimensional pyramid of unit cubes in the plane y = 0: `layers` cubes side by side
/// on the floor, each layer one fewer and centred on the gaps of the one below, touching.
/// The last item is the top cube.
pub fn pyramid(layers: usize) -> Vec<Item> {
    let mut items = Vec::new();
    for layer in 0..layers {
        let count = layers - layer;
        for i in 0..count {
            let x = i as f64 - (count - 1) as f64 / 2.0;
            items.push(Item::at(
                Shape::Cuboid([0.5; 3]),
                [x, 0.0, 0.5 + layer as f64],
            ));
        }
    }
    items
}

/// A pile of `count` boxes (half-length 0.4) and balls (radius 0.4), alternating on a
/// lattice 1.2 apart of side ⌈∛count⌉ (filled layer by layer from the floor), slightly
/// shifted and turned so that nothing lines up, dropped from rest.
pub fn pile(count: usize) -> Vec<Item> {
    let side = (1..).find(|s| s * s * s >= count).unwrap();
    (0..count)
        .map(|k| {
            let (i, j, l) = (k % side, (k / side) % side, k / (side * side));
            let wobble = |a: f64| 0.05 * (a * k as f64 + 0.3).sin();
            let shape = if (i + j + l) % 2 == 0 {
                Shape::Cuboid([0.4; 3])
            } else {
                Shape::Ball(0.4)
            };
            Item {
                yaw: 4.0 * wobble(1.3),
                ..Item::at(
                    shape,
                    [
                        1.2 * i as f64 + wobble(0.7),
                        1.2 * j as f64 + wobble(1.1),
                        0.5 + 1.2 * l as f64,
                    ],
                )
            }
        })
        .collect()
}

/// A rigid placement in f64: x_space = position + rotation · x_own (rotation row-major).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    pub position: [f64; 3],
    pub rotation: [[f64; 3]; 3],
}

fn yaw_matrix(yaw: f64) -> [[f64; 3]; 3] {
    let (s, c) = yaw.sin_cos();
    [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]
}

fn vector(x: &[f64; 3]) -> Vector {
    Vector::from_components(x).expect("three finite numbers")
}

/// The scene as a rotorflow [`System`] over the half-space z ≤ 0.
pub fn rotorflow_system(items: &[Item]) -> System {
    let bodies = items
        .iter()
        .map(|item| {
            let spec = match item.shape {
                Shape::Cuboid([a, b, c]) => format!("cuboid:{a},{b},{c}+mass=1"),
                Shape::Ball(r) => format!("ball:3,{r}+mass=1"),
            };
            let parsed = parse_body(&spec).expect("a valid body");
            // The rotor turning e₁ towards e₂ by the yaw (checked against the matrix by the
            // tests).
            let attitude = Rotor::from_plane_angle(3, 0, 1, item.yaw).expect("a valid plane");
            MovingBody::from_parsed(
                &parsed,
                attitude,
                &vector(&item.position),
                &vector(&item.velocity),
                &Bivector::zero(3),
            )
            .and_then(|b| b.with_friction(FRICTION))
            .expect("a valid body")
        })
        .collect();
    let mut system = System::new(bodies).expect("bodies of one dimension");
    system
        .add_forque(Gravity(vector(&[0.0, 0.0, -G])))
        .expect("gravity in 3D");
    system
        .add_half_space(HalfSpace::new(&vector(&[0.0, 0.0, 1.0]), 0.0, FRICTION, 0.0).unwrap())
        .expect("a floor in 3D");
    system
}

/// Steps a rotorflow system `steps` steps of [`H`] with one [`MotionIntegrator::advance`].
pub fn rotorflow_advance(system: &mut System, integrator: &mut dyn MotionIntegrator, steps: usize) {
    integrator
        .advance(system, 0.0, H, steps)
        .expect("a finite step");
}

/// The placements of a rotorflow system's bodies.
pub fn rotorflow_poses(system: &System) -> Vec<Pose> {
    system
        .bodies()
        .iter()
        .map(|b| {
            let x = b.position().as_slice();
            let q = b.attitude().to_matrix();
            Pose {
                position: [x[0], x[1], x[2]],
                rotation: std::array::from_fn(|i| std::array::from_fn(|j| q[(i, j)])),
            }
        })
        .collect()
}

/// The velocities of a rotorflow system's bodies' centres.
pub fn rotorflow_velocities(system: &System) -> Vec<[f64; 3]> {
    system
        .bodies()
        .iter()
        .map(|b| {
            let v = b.velocity();
            let v = v.as_slice();
            [v[0], v[1], v[2]]
        })
        .collect()
}

/// Rapier's floor: its half-space shape, or a box 2,000 × 2,000 × 2 with its top face at
/// z = 0 (the faster of the two in Rapier).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Floor {
    HalfSpace,
    Cuboid,
}

/// Rapier's world for a scene: its default integration parameters (TGS soft, 4 substeps)
/// at the step [`H`], sleeping off, the same masses, friction and floor height. The bodies
/// are inserted in the scene's order, so `world.bodies` iterates them in that order.
pub fn rapier_world(items: &[Item], floor: Floor) -> (rp::PhysicsWorld, Vec<rp::RigidBodyHandle>) {
    let mut world = rp::PhysicsWorld::new();
    world.gravity = rp::Vector::new(0.0, 0.0, -G as f32);
    world.integration_parameters.dt = H as f32;
    let ground = match floor {
        Floor::HalfSpace => rp::ColliderBuilder::new(rp::SharedShape::halfspace(rp::Vector::Z)),
        Floor::Cuboid => rp::ColliderBuilder::cuboid(1000.0, 1000.0, 1.0)
            .translation(rp::Vector::new(0.0, 0.0, -1.0)),
    };
    world.insert(
        rp::RigidBodyBuilder::fixed(),
        ground.friction(FRICTION as f32).restitution(0.0),
    );
    let handles = items
        .iter()
        .map(|item| {
            let [x, y, z] = item.position.map(|c| c as f32);
            let [u, v, w] = item.velocity.map(|c| c as f32);
            let body = rp::RigidBodyBuilder::dynamic()
                .translation(rp::Vector::new(x, y, z))
                .rotation(rp::Vector::new(0.0, 0.0, item.yaw as f32))
                .linvel(rp::Vector::new(u, v, w))
                .can_sleep(false);
            let collider = match item.shape {
                Shape::Cuboid([a, b, c]) => {
                    rp::ColliderBuilder::cuboid(a as f32, b as f32, c as f32)
                }
                Shape::Ball(r) => rp::ColliderBuilder::ball(r as f32),
            };
            world
                .insert(
                    body,
                    collider
                        .mass(1.0)
                        .friction(FRICTION as f32)
                        .restitution(0.0),
                )
                .0
        })
        .collect();
    (world, handles)
}

/// Steps a Rapier world `steps` steps.
pub fn rapier_advance(world: &mut rp::PhysicsWorld, steps: usize) {
    for _ in 0..steps {
        world.step();
    }
}

/// The placements of the bodies `handles` of a Rapier world.
pub fn rapier_poses(world: &rp::PhysicsWorld, handles: &[rp::RigidBodyHandle]) -> Vec<Pose> {
    handles
        .iter()
        .map(|&h| {
            let body = &world.bodies[h];
            let x = body.translation();
            let m = rp::Mat3::from_quat(*body.rotation());
            Pose {
                position: [x.x, x.y, x.z].map(f64::from),
                // glam's matrices are column-major: row i, column j is col(j)[i].
                rotation: std::array::from_fn(|i| std::array::from_fn(|j| f64::from(m.col(j)[i]))),
            }
        })
        .collect()
}

/// The velocities of the centres of the bodies `handles` of a Rapier world.
pub fn rapier_velocities(
    world: &rp::PhysicsWorld,
    handles: &[rp::RigidBodyHandle],
) -> Vec<[f64; 3]> {
    handles
        .iter()
        .map(|&h| {
            let v = world.bodies[h].linvel();
            [v.x, v.y, v.z].map(f64::from)
        })
        .collect()
}

fn sub(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: &[f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// The body's own axis `i` in space (column `i` of the rotation).
fn axis(pose: &Pose, i: usize) -> [f64; 3] {
    std::array::from_fn(|k| pose.rotation[k][i])
}

/// The bounding radius of a shape.
pub fn radius(shape: &Shape) -> f64 {
    match shape {
        Shape::Cuboid(h) => norm(h),
        Shape::Ball(r) => *r,
    }
}

/// How deep a placed shape reaches below the floor z = 0 (negative: its height above it).
pub fn floor_depth(shape: &Shape, pose: &Pose) -> f64 {
    match shape {
        Shape::Ball(r) => r - pose.position[2],
        Shape::Cuboid(h) => {
            (0..3)
                .map(|i| h[i] * pose.rotation[2][i].abs())
                .sum::<f64>()
                - pose.position[2]
        }
    }
}

/// The penetration depth of two placed shapes (the shortest translation that separates
/// them; negative or zero when they are apart), in closed form: balls by their centres, a
/// box and a ball by the point of the box nearest the centre, two boxes by the smallest
/// overlap over the 15 separating axes (3 face normals each and 9 edge pairs), which is the
/// penetration depth of two convex polyhedra. Apart, only the sign is meaningful for boxes.
pub fn depth(a: (&Shape, &Pose), b: (&Shape, &Pose)) -> f64 {
    match (a.0, b.0) {
        (Shape::Ball(ra), Shape::Ball(rb)) => ra + rb - norm(&sub(&a.1.position, &b.1.position)),
        (Shape::Cuboid(h), Shape::Ball(r)) => box_ball(h, a.1, *r, &b.1.position),
        (Shape::Ball(r), Shape::Cuboid(h)) => box_ball(h, b.1, *r, &a.1.position),
        (Shape::Cuboid(ha), Shape::Cuboid(hb)) => box_box(ha, a.1, hb, b.1),
    }
}

fn box_ball(h: &[f64; 3], pose: &Pose, r: f64, centre: &[f64; 3]) -> f64 {
    let d = sub(centre, &pose.position);
    let own: [f64; 3] = std::array::from_fn(|i| dot(&axis(pose, i), &d));
    let inside = (0..3).all(|i| own[i].abs() <= h[i]);
    if inside {
        r + (0..3)
            .map(|i| h[i] - own[i].abs())
            .fold(f64::INFINITY, f64::min)
    } else {
        let gap: [f64; 3] = std::array::from_fn(|i| own[i] - own[i].clamp(-h[i], h[i]));
        r - norm(&gap)
    }
}

fn box_box(ha: &[f64; 3], a: &Pose, hb: &[f64; 3], b: &Pose) -> f64 {
    let d = sub(&b.position, &a.position);
    let (ea, eb): (Vec<[f64; 3]>, Vec<[f64; 3]>) = (
        (0..3).map(|i| axis(a, i)).collect(),
        (0..3).map(|i| axis(b, i)).collect(),
    );
    let mut axes: Vec<[f64; 3]> = ea.iter().chain(&eb).copied().collect();
    for u in &ea {
        for v in &eb {
            let c = cross(u, v);
            let n = norm(&c);
            // Parallel edges add no axis the face normals do not already give.
            if n > 1e-9 {
                axes.push(c.map(|x| x / n));
            }
        }
    }
    axes.iter()
        .map(|l| {
            let extent = |h: &[f64; 3], e: &[[f64; 3]]| {
                (0..3).map(|i| h[i] * dot(&e[i], l).abs()).sum::<f64>()
            };
            extent(ha, &ea) + extent(hb, &eb) - dot(l, &d).abs()
        })
        .fold(f64::INFINITY, f64::min)
}

/// The deepest penetration of any body into the floor or into another body.
pub fn max_penetration(items: &[Item], poses: &[Pose]) -> f64 {
    let mut deepest = f64::NEG_INFINITY;
    for (i, (a, pa)) in items.iter().zip(poses).enumerate() {
        deepest = deepest.max(floor_depth(&a.shape, pa));
        for (b, pb) in items[i + 1..].iter().zip(&poses[i + 1..]) {
            // Bodies farther apart than their bounding spheres cannot touch.
            if norm(&sub(&pa.position, &pb.position)) < radius(&a.shape) + radius(&b.shape) {
                deepest = deepest.max(depth((&a.shape, pa), (&b.shape, pb)));
            }
        }
    }
    deepest
}

/// An engine's run of a scene, stepped from its start.
pub trait Run {
    fn advance(&mut self, steps: usize);
    fn poses(&self) -> Vec<Pose>;
    fn velocities(&self) -> Vec<[f64; 3]>;
}

/// The integrator of a rotorflow run.
#[derive(Clone, Debug)]
pub enum RotorflowIntegrator {
    /// `MotionSplitting`: contacts solved to its tolerance, impacts without restitution held
    /// by speculative contacts (those with restitution are located in time).
    Splitting(Box<MotionSplitting>),
    /// `SoftStep` with its defaults: substeps of soft contacts, a fixed solver cost per step.
    Soft(Box<SoftStep>),
}

impl RotorflowIntegrator {
    /// The integrator as a [`MotionIntegrator`].
    pub fn as_dyn(&mut self) -> &mut dyn MotionIntegrator {
        match self {
            RotorflowIntegrator::Splitting(i) => i.as_mut(),
            RotorflowIntegrator::Soft(i) => i.as_mut(),
        }
    }
}

/// A scene run by rotorflow, with `MotionSplitting` ([`RotorflowRun::new`]) or `SoftStep`
/// ([`RotorflowRun::soft`]).
pub struct RotorflowRun {
    pub system: System,
    pub integrator: RotorflowIntegrator,
}

impl RotorflowRun {
    /// The scene run by `MotionSplitting`.
    pub fn new(items: &[Item]) -> Self {
        RotorflowRun {
            system: rotorflow_system(items),
            integrator: RotorflowIntegrator::Splitting(Box::new(MotionSplitting::new())),
        }
    }

    /// The scene run by `MotionSplitting` with at most `sweeps` Gauss–Seidel sweeps per
    /// contact solve.
    pub fn with_sweep_limit(items: &[Item], sweeps: usize) -> Self {
        let splitting = MotionSplitting::new()
            .with_sweep_limit(sweeps)
            .expect("a positive sweep limit");
        RotorflowRun {
            system: rotorflow_system(items),
            integrator: RotorflowIntegrator::Splitting(Box::new(splitting)),
        }
    }

    /// The scene run by `SoftStep` with its default settings.
    pub fn soft(items: &[Item]) -> Self {
        RotorflowRun {
            system: rotorflow_system(items),
            integrator: RotorflowIntegrator::Soft(Box::new(SoftStep::new())),
        }
    }
}

impl Run for RotorflowRun {
    fn advance(&mut self, steps: usize) {
        rotorflow_advance(&mut self.system, self.integrator.as_dyn(), steps);
    }
    fn poses(&self) -> Vec<Pose> {
        rotorflow_poses(&self.system)
    }
    fn velocities(&self) -> Vec<[f64; 3]> {
        rotorflow_velocities(&self.system)
    }
}

/// A scene run by Rapier.
pub struct RapierRun {
    pub world: rp::PhysicsWorld,
    pub handles: Vec<rp::RigidBodyHandle>,
}

impl RapierRun {
    pub fn new(items: &[Item], floor: Floor) -> Self {
        let (world, handles) = rapier_world(items, floor);
        RapierRun { world, handles }
    }
}

impl Run for RapierRun {
    fn advance(&mut self, steps: usize) {
        rapier_advance(&mut self.world, steps);
    }
    fn poses(&self) -> Vec<Pose> {
        rapier_poses(&self.world, &self.handles)
    }
    fn velocities(&self) -> Vec<[f64; 3]> {
        rapier_velocities(&self.world, &self.handles)
    }
}

/// The yaw rotation matrix of an item, for the tests.
pub fn item_rotation(item: &Item) -> [[f64; 3]; 3] {
    yaw_matrix(item.yaw)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pose(position: [f64; 3], yaw: f64) -> Pose {
        Pose {
            position,
            rotation: yaw_matrix(yaw),
        }
    }

    #[test]
    fn both_engines_start_from_the_same_placements() {
        let items = pile(27);
        let ours = rotorflow_poses(&rotorflow_system(&items));
        let (world, handles) = rapier_world(&items, Floor::HalfSpace);
        let theirs = rapier_poses(&world, &handles);
        assert_eq!(ours.len(), 27);
        for ((item, a), b) in items.iter().zip(&ours).zip(&theirs) {
            let expected = item_rotation(item);
            for (i, row) in expected.iter().enumerate() {
                assert!((a.position[i] - item.position[i]).abs() < 1e-15);
                assert!((b.position[i] - item.position[i]).abs() < 1e-5);
                for (j, e) in row.iter().enumerate() {
                    assert!((a.rotation[i][j] - e).abs() < 1e-14, "{a:?}");
                    assert!((b.rotation[i][j] - e).abs() < 1e-6, "{b:?}");
                }
            }
        }
    }

    #[test]
    fn depths_match_hand_computed_cases() {
        let ball = Shape::Ball(0.5);
        let cube = Shape::Cuboid([0.5; 3]);
        let at = |x: f64, y: f64, z: f64| pose([x, y, z], 0.0);
        // Balls: 1 − 0.9.
        assert!(
            (depth((&ball, &at(0.0, 0.0, 0.0)), (&ball, &at(0.9, 0.0, 0.0))) - 0.1).abs() < 1e-15
        );
        // A ball over a face, and off an edge: 0.5 − √2·0.1.
        assert!(
            (depth((&cube, &at(0.0, 0.0, 0.0)), (&ball, &at(0.0, 0.0, 0.95))) - 0.05).abs() < 1e-15
        );
        let edge = depth((&ball, &at(0.6, 0.6, 0.0)), (&cube, &at(0.0, 0.0, 0.0)));
        assert!((edge - (0.5 - 0.02f64.sqrt())).abs() < 1e-15);
        // A ball centre inside the box: radius plus the distance to the nearest face.
        assert!(
            (depth((&cube, &at(0.0, 0.0, 0.0)), (&ball, &at(0.0, 0.0, 0.3))) - 0.7).abs() < 1e-15
        );
        // Cubes face to face, overlapping by 0.02 along z.
        assert!(
            (depth((&cube, &at(0.0, 0.0, 0.0)), (&cube, &at(0.1, 0.2, 0.98))) - 0.02).abs() < 1e-14
        );
        // A cube turned by 45° about z next to an upright one: its edge reaches √2/2 from
        // its centre, so at 1.1 apart along x they overlap by 0.5 + √2/2 − 1.1.
        let turned = pose([1.1, 0.0, 0.0], std::f64::consts::FRAC_PI_4);
        let d = depth((&cube, &at(0.0, 0.0, 0.0)), (&cube, &turned));
        assert!((d - (0.5 + 0.5f64.sqrt() - 1.1)).abs() < 1e-14, "{d}");
        // Apart.
        assert!(depth((&cube, &at(0.0, 0.0, 0.0)), (&cube, &at(0.0, 0.0, 1.1))) < 0.0);
        // Floor.
        assert!((floor_depth(&cube, &at(0.0, 0.0, 0.49)) - 0.01).abs() < 1e-15);
        assert!((floor_depth(&ball, &at(0.0, 0.0, 0.5))).abs() < 1e-15);
    }

    /// A rotation by `angle` about the unit axis `u` (Rodrigues).
    fn rotation(u: [f64; 3], angle: f64) -> [[f64; 3]; 3] {
        let (s, c) = angle.sin_cos();
        std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                let k = [[0.0, -u[2], u[1]], [u[2], 0.0, -u[0]], [-u[1], u[0], 0.0]];
                let kk: f64 = (0..3).map(|m| k[i][m] * k[m][j]).sum();
                f64::from(u8::from(i == j)) + s * k[i][j] + (1.0 - c) * kk
            })
        })
    }

    /// The closed forms against rotorflow's GJK and EPA on the support functions alone,
    /// on pseudo-random overlapping pairs of turned boxes and balls of the scenes' sizes.
    #[test]
    fn depths_agree_with_gjk_and_epa_on_random_pairs() {
        use rotorflow::dynamics::motion::detect::{PlacedShape, penetration};
        use rotorflow::dynamics::motion::shape::ConvexShape;
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut uniform = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut compared = [0usize; 3];
        for case in 0..3000 {
            let mut placed = Vec::new();
            for side in 0..2 {
                let shape = if (case + side * (case / 3)) % 3 == 0 {
                    Shape::Ball(0.3 + 0.3 * uniform())
                } else {
                    Shape::Cuboid([
                        0.2 + 0.5 * uniform(),
                        0.2 + 0.5 * uniform(),
                        0.2 + 0.5 * uniform(),
                    ])
                };
                let z = 2.0 * uniform() - 1.0;
                let phi = std::f64::consts::TAU * uniform();
                let r = (1.0 - z * z).sqrt();
                let pose = Pose {
                    position: [0.0, 1.0, 2.0].map(|_| 0.9 * side as f64 * (2.0 * uniform() - 1.0)),
                    rotation: rotation([r * phi.cos(), r * phi.sin(), z], 6.0 * uniform()),
                };
                placed.push((shape, pose));
            }
            let ours = depth((&placed[0].0, &placed[0].1), (&placed[1].0, &placed[1].1));
            let convex: Vec<ConvexShape> = placed
                .iter()
                .map(|(s, _)| match s {
                    Shape::Ball(r) => ConvexShape::ball(3, *r).unwrap(),
                    Shape::Cuboid(h) => ConvexShape::cuboid(h).unwrap(),
                })
                .collect();
            let rows: Vec<Vec<f64>> = placed.iter().map(|(_, p)| p.rotation.concat()).collect();
            let a = PlacedShape::new(&convex[0], &placed[0].1.position, &rows[0]).unwrap();
            let b = PlacedShape::new(&convex[1], &placed[1].1.position, &rows[1]).unwrap();
            let theirs = penetration(&a, &b).unwrap().depth;
            if theirs > 1e-6 {
                assert!(
                    (ours - theirs).abs() < 1e-7,
                    "{placed:?}: closed form {ours}, EPA {theirs}"
                );
                let kind = match (placed[0].0, placed[1].0) {
                    (Shape::Ball(_), Shape::Ball(_)) => 0,
                    (Shape::Cuboid(_), Shape::Cuboid(_)) => 2,
                    _ => 1,
                };
                compared[kind] += 1;
            } else {
                assert!(ours <= 1e-7, "{placed:?}: closed form {ours}, EPA {theirs}");
            }
        }
        // Overlapping pairs of each kind: ball–ball, box–ball, box–box.
        println!("overlapping pairs compared (ball–ball, box–ball, box–box): {compared:?}");
        assert!(compared.iter().all(|&k| k >= 100), "{compared:?}");
    }

    /// `SoftStep` steps every scene of the bench: the integrator is the soft step, nothing
    /// overlaps by more than the contact springs give (on the floor g / (2π · 60 Hz)² =
    /// 6.9e-5 m; the pyramid's bottom contacts carry up to ten cubes and are 48 Hz between
    /// cubes, so a centimetre bounds them; the piles have not landed yet), and the bodies of
    /// the piles above the lowest layer, still falling freely, have g t of speed downwards
    /// and none across.
    #[test]
    fn the_soft_step_runs_every_scene() {
        const STEPS: usize = 3;
        let scenes: [(&str, Vec<Item>, f64); 5] = [
            ("resting boxes", resting_boxes(), 1e-4),
            ("rolling balls", rolling_balls(), 1e-4),
            ("pyramid", pyramid(10), 1e-2),
            ("pile of 100", pile(100), 0.0),
            ("pile of 1000", pile(1000), 0.0),
        ];
        let mut falling = 0;
        for (name, items, bound) in &scenes {
            let mut run = RotorflowRun::soft(items);
            assert_eq!(run.integrator.as_dyn().name(), "soft step");
            run.advance(STEPS);
            let poses = run.poses();
            let velocities = run.velocities();
            assert_eq!(poses.len(), items.len(), "{name}");
            let deepest = max_penetration(items, &poses);
            println!("{name}: deepest penetration {deepest:.2e}");
            assert!(deepest < *bound, "{name}: penetration {deepest}");
            for (item, v) in items.iter().zip(&velocities) {
                assert!(v.iter().all(|c| c.is_finite()), "{name}: {v:?}");
                if name.starts_with("pile") && item.position[2] > 1.0 {
                    let expected = -G * STEPS as f64 * H;
                    assert!((v[2] - expected).abs() < 1e-12, "{name}: {v:?}");
                    assert!(v[0].abs() + v[1].abs() < 1e-12, "{name}: {v:?}");
                    falling += 1;
                }
            }
        }
        // Above the lowest layer: 100 − 25 and 1000 − 100 bodies.
        assert_eq!(falling, 75 + 900);
    }

    #[test]
    fn scenes_have_the_sizes_asked_for_and_start_apart() {
        assert_eq!(resting_boxes().len(), 1000);
        assert_eq!(resting_boxes_of(100)[..], resting_boxes()[..100]);
        assert_eq!(rolling_balls().len(), 1000);
        assert_eq!(pyramid(10).len(), 55);
        for count in [100, 1000] {
            let items = pile(count);
            assert_eq!(items.len(), count);
            let poses: Vec<Pose> = items.iter().map(|it| pose(it.position, it.yaw)).collect();
            assert!(
                max_penetration(&items, &poses) < -0.05,
                "the pile starts apart"
            );
        }
        // The pyramid's cubes touch without overlapping, and rest on the floor.
        let items = pyramid(10);
        let poses: Vec<Pose> = items.iter().map(|it| pose(it.position, 0.0)).collect();
        assert!(max_penetration(&items, &poses).abs() < 1e-12);
    }
}
