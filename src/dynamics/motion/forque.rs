//! Forces and torques on moving bodies: the [`Forque`] trait and the built-in [`forques`].

use super::MovingBody;
use crate::algebra::{Bivector, Vector};

/// A force (space frame) and a torque about the centre of mass (principal body frame, as
/// [`crate::dynamics::RigidBody::momentum`]) acting on one body: the two halves of a
/// "forque" (Dorst & De Keninck, "May the Forque Be With You", 2022).
#[derive(Clone, Debug, PartialEq)]
pub struct Wrench {
    /// The total force, space frame.
    pub force: Vector,
    /// The torque about the centre of mass, principal body frame.
    pub torque: Bivector,
}

impl Wrench {
    /// No force and no torque in N dimensions.
    pub fn zero(n: usize) -> Wrench {
        Wrench {
            force: Vector::zero(n),
            torque: Bivector::zero(n),
        }
    }

    /// Adds another wrench on the same body.
    pub fn add(&mut self, other: &Wrench) {
        self.force += &other.force;
        self.torque += &other.torque;
    }
}

/// What a forque may depend on: the time and the state of every body.
#[derive(Clone, Copy, Debug)]
pub struct ForqueInput<'a> {
    /// Time t.
    pub time: f64,
    /// The bodies, in the order of the system.
    pub bodies: &'a [MovingBody],
}

/// Forces and torques on the bodies of a system: gravity, springs, drag, user closures.
///
/// [`Forque::apply`] adds the forque's wrench on each body to `wrenches` (one per body, in
/// the system's order). A conservative forque also returns its potential energy, which the
/// system's energy includes. Any closure `Fn(&ForqueInput, &mut [Wrench])` is a forque
/// (without a potential).
///
/// Forques are `Send + Sync`, so that a [`System`](super::System) can move to another
/// thread (a batch of scenes stepped by a thread pool, a simulation behind a GUI).
pub trait Forque: Send + Sync {
    /// Adds this forque's force and torque on every body to `wrenches`.
    fn apply(&self, input: &ForqueInput<'_>, wrenches: &mut [Wrench]);

    /// The potential energy, for a conservative forque (None otherwise).
    fn potential_energy(&self, _input: &ForqueInput<'_>) -> Option<f64> {
        None
    }

    /// The bodies this forque refers to by index (checked when it joins a system).
    fn bodies(&self) -> Vec<usize> {
        Vec::new()
    }

    /// True if the wrenches depend on neither the time nor the bodies' positions, momenta
    /// and attitudes (only on their masses and inertias, which never change), as for
    /// uniform gravity. A system whose forques are all constant evaluates them once, when
    /// they join it, instead of twice per step. False by default.
    fn is_constant(&self) -> bool {
        false
    }

    /// True if the wrenches depend on the bodies' velocities or angular velocities (damping,
    /// drag). [`MotionSplitting`](super::MotionSplitting) then takes its closing half kick
    /// implicitly, so that the step stays of order 2. True by default, which is always
    /// correct: a forque that reads only positions and attitudes costs one more evaluation
    /// per step if it says so.
    fn reads_velocities(&self) -> bool {
        true
    }
}

impl<F> Forque for F
where
    F: Fn(&ForqueInput<'_>, &mut [Wrench]) + Send + Sync,
{
    fn apply(&self, input: &ForqueInput<'_>, wrenches: &mut [Wrench]) {
        self(input, wrenches)
    }
}

/// The built-in forques.
pub mod forques {
    use super::*;

    /// Uniform gravity: the force m g on every body at its centre of mass (no torque), with
    /// the potential energy −Σ m g·x.
    #[derive(Clone, Debug)]
    pub struct Gravity(pub Vector);

    impl Forque for Gravity {
        fn reads_velocities(&self) -> bool {
            false
        }
        fn apply(&self, input: &ForqueInput<'_>, wrenches: &mut [Wrench]) {
            for (b, w) in input.bodies.iter().zip(wrenches.iter_mut()) {
                if b.is_fixed() {
                    continue;
                }
                let m = b.mass();
                for (f, g) in w.force.as_mut_slice().iter_mut().zip(self.0.as_slice()) {
                    *f += m * g;
                }
            }
        }
        fn potential_energy(&self, input: &ForqueInput<'_>) -> Option<f64> {
            Some(
                input
                    .bodies
                    .iter()
                    .filter(|b| !b.is_fixed())
                    .map(|b| -b.mass() * self.0.dot(b.position()))
                    .sum(),
            )
        }
        fn is_constant(&self) -> bool {
            true
        }
    }

    /// Where the other end of a spring is.
    #[derive(Clone, Debug)]
    pub enum Anchor {
        /// A fixed point of space.
        World(Vector),
        /// A point (own axes) of another body of the system, by index.
        Body(usize, Vector),
    }

    /// A Hooke spring with damping between a body point and an anchor: the force
    /// −(k (ℓ − ℓ₀) + c ℓ̇) û on the body point, û the unit vector from the anchor to it and
    /// ℓ its length, and the opposite force on an anchoring body. The potential energy is
    /// ½ k (ℓ − ℓ₀)² (the damping dissipates).
    #[derive(Clone, Debug)]
    pub struct Spring {
        /// The body, by index.
        pub body: usize,
        /// The attachment point, in the body's own axes.
        pub point: Vector,
        /// The other end.
        pub anchor: Anchor,
        /// The stiffness k.
        pub stiffness: f64,
        /// The rest length ℓ₀.
        pub rest_length: f64,
        /// The damping c (force per unit of length rate).
        pub damping: f64,
    }

    impl Spring {
        /// The two ends in space and their velocities.
        fn ends(&self, bodies: &[MovingBody]) -> (Vector, Vector, Vector, Vector) {
            let b = &bodies[self.body];
            let (a, va) = match &self.anchor {
                Anchor::World(x) => (x.clone(), Vector::zero(x.dim())),
                Anchor::Body(j, p) => (bodies[*j].point_position(p), bodies[*j].point_velocity(p)),
            };
            (
                b.point_position(&self.point),
                b.point_velocity(&self.point),
                a,
                va,
            )
        }
    }

    impl Forque for Spring {
        fn reads_velocities(&self) -> bool {
            self.damping != 0.0
        }
        fn apply(&self, input: &ForqueInput<'_>, wrenches: &mut [Wrench]) {
            let (x, v, a, va) = self.ends(input.bodies);
            let d = &x - &a;
            let len = d.norm();
            if len == 0.0 {
                // Coincident ends: no direction, and a zero-length spring pulls with no
                // force there.
                return;
            }
            let u = &d * (1.0 / len);
            let rate = u.dot(&(&v - &va));
            let f = &u * -(self.stiffness * (len - self.rest_length) + self.damping * rate);
            let on_body = input.bodies[self.body].wrench_at(&self.point, &f);
            wrenches[self.body].add(&on_body);
            if let Anchor::Body(j, p) = &self.anchor {
                let on_other = input.bodies[*j].wrench_at(p, &(&f * -1.0));
                wrenches[*j].add(&on_other);
            }
        }
        fn potential_energy(&self, input: &ForqueInput<'_>) -> Option<f64> {
            let (x, _, a, _) = self.ends(input.bodies);
            let stretch = (&x - &a).norm() - self.rest_length;
            Some(0.5 * self.stiffness * stretch * stretch)
        }
        fn bodies(&self) -> Vec<usize> {
            match &self.anchor {
                Anchor::World(_) => vec![self.body],
                Anchor::Body(j, _) => vec![self.body, *j],
            }
        }
    }

    /// Linear drag on every body: the force −c v at the centre of mass.
    #[derive(Clone, Copy, Debug)]
    pub struct LinearDrag(pub f64);

    impl Forque for LinearDrag {
        fn apply(&self, input: &ForqueInput<'_>, wrenches: &mut [Wrench]) {
            for (b, w) in input.bodies.iter().zip(wrenches.iter_mut()) {
                w.force += &(&b.velocity() * -self.0);
            }
        }
    }

    /// Angular drag on every body: the torque −c ω.
    #[derive(Clone, Copy, Debug)]
    pub struct AngularDrag(pub f64);

    impl Forque for AngularDrag {
        fn apply(&self, input: &ForqueInput<'_>, wrenches: &mut [Wrench]) {
            for (b, w) in input.bodies.iter().zip(wrenches.iter_mut()) {
                w.torque += &(&b.rotation().omega() * -self.0);
            }
        }
    }

    /// The frame a constant force or torque is fixed in.
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    pub enum Frame {
        /// Fixed in space.
        World,
        /// Turning with the body (its own axes).
        Body,
    }

    /// A constant force on one body, at a body point (own axes), fixed in space or in the
    /// body.
    #[derive(Clone, Debug)]
    pub struct ConstantForce {
        /// The body, by index.
        pub body: usize,
        /// The force.
        pub force: Vector,
        /// Where it acts, in the body's own axes (the centre of mass is the origin).
        pub point: Vector,
        /// The frame the force is fixed in.
        pub frame: Frame,
    }

    impl Forque for ConstantForce {
        fn reads_velocities(&self) -> bool {
            false
        }
        fn apply(&self, input: &ForqueInput<'_>, wrenches: &mut [Wrench]) {
            let b = &input.bodies[self.body];
            let f = match self.frame {
                Frame::World => self.force.clone(),
                Frame::Body => b.attitude().rotate_vector(&self.force),
            };
            wrenches[self.body].add(&b.wrench_at(&self.point, &f));
        }
        fn bodies(&self) -> Vec<usize> {
            vec![self.body]
        }
        fn is_constant(&self) -> bool {
            // Fixed in space and at the centre of mass: no torque, whatever the attitude.
            self.frame == Frame::World && self.point.as_slice().iter().all(|&x| x == 0.0)
        }
    }

    /// A constant torque on one body, fixed in space or in the body.
    #[derive(Clone, Debug)]
    pub struct ConstantTorque {
        /// The body, by index.
        pub body: usize,
        /// The torque bivector.
        pub torque: Bivector,
        /// The frame the torque is fixed in.
        pub frame: Frame,
    }

    impl Forque for ConstantTorque {
        fn reads_velocities(&self) -> bool {
            false
        }
        fn apply(&self, input: &ForqueInput<'_>, wrenches: &mut [Wrench]) {
            let b = &input.bodies[self.body];
            let space = match self.frame {
                Frame::World => self.torque.clone(),
                Frame::Body => b.attitude().rotate_bivector(&self.torque),
            };
            wrenches[self.body].torque += &b
                .rotation()
                .principal_frame_attitude()
                .inverse_rotate_bivector(&space);
        }
        fn bodies(&self) -> Vec<usize> {
            vec![self.body]
        }
    }
}
