//! [`System`]: moving bodies and the forques between them.

use super::{Forque, ForqueInput, MovingBody, Wrench};
use crate::algebra::{Bivector, Vector};
use crate::dynamics::DynamicsError;

/// Bodies that move in one space, and the forques on them (gravity, springs, drag, …).
///
/// The system's invariants, which the integrators are measured by:
/// - the energy, kinetic (translation and rotation) plus the potentials of the conservative
///   forques;
/// - the linear momentum Σ p;
/// - the angular momentum about the origin, Σ (x ∧ p + L_s).
///
/// Without external forques the last two are conserved (internal springs pull the two bodies
/// along the line between their attachment points, so their torques cancel about any point).
pub struct System {
    bodies: Vec<MovingBody>,
    forques: Vec<Box<dyn Forque>>,
}

impl std::fmt::Debug for System {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("System")
            .field("bodies", &self.bodies)
            .field("forques", &self.forques.len())
            .finish()
    }
}

impl System {
    /// Returns the system of `bodies`, without forques.
    ///
    /// # Errors
    /// [`DynamicsError::InvalidMotion`] if there is no body or the bodies live in spaces of
    /// different dimension.
    pub fn new(bodies: Vec<MovingBody>) -> Result<System, DynamicsError> {
        let Some(first) = bodies.first() else {
            return Err(DynamicsError::InvalidMotion {
                what: "system",
                reason: "no body".into(),
            });
        };
        let n = first.dim();
        if let Some(b) = bodies.iter().find(|b| b.dim() != n) {
            return Err(DynamicsError::InvalidMotion {
                what: "system",
                reason: format!("a body in {} dimensions beside one in {n}", b.dim()),
            });
        }
        Ok(System {
            bodies,
            forques: Vec::new(),
        })
    }

    /// Adds a forque.
    ///
    /// # Errors
    /// [`DynamicsError::InvalidMotion`] if it refers to a body the system does not have.
    pub fn add_forque(&mut self, forque: impl Forque + 'static) -> Result<(), DynamicsError> {
        if let Some(i) = forque
            .bodies()
            .into_iter()
            .find(|&i| i >= self.bodies.len())
        {
            return Err(DynamicsError::InvalidMotion {
                what: "forque",
                reason: format!(
                    "body {i} does not exist (the system has {} bodies, numbered from 0)",
                    self.bodies.len()
                ),
            });
        }
        self.forques.push(Box::new(forque));
        Ok(())
    }

    /// Returns the dimension N.
    pub fn dim(&self) -> usize {
        self.bodies[0].dim()
    }

    /// Returns the bodies.
    pub fn bodies(&self) -> &[MovingBody] {
        &self.bodies
    }

    /// Mutable bodies, for the integrators.
    pub(crate) fn bodies_mut(&mut self) -> &mut [MovingBody] {
        &mut self.bodies
    }

    /// The wrench on every body at time `t` for the given states.
    pub(crate) fn wrenches_for(&self, t: f64, bodies: &[MovingBody]) -> Vec<Wrench> {
        let mut w = vec![Wrench::zero(self.dim()); bodies.len()];
        let input = ForqueInput { time: t, bodies };
        for f in &self.forques {
            f.apply(&input, &mut w);
        }
        w
    }

    /// Returns the wrench on every body at time `t`.
    pub fn wrenches(&self, t: f64) -> Vec<Wrench> {
        self.wrenches_for(t, &self.bodies)
    }

    /// Returns the kinetic energy of all bodies.
    pub fn kinetic_energy(&self) -> f64 {
        self.bodies.iter().map(MovingBody::kinetic_energy).sum()
    }

    /// Returns the potential energy of the conservative forques at time `t`.
    pub fn potential_energy(&self, t: f64) -> f64 {
        let input = ForqueInput {
            time: t,
            bodies: &self.bodies,
        };
        self.forques
            .iter()
            .filter_map(|f| f.potential_energy(&input))
            .sum()
    }

    /// Returns the energy: kinetic plus the potentials of the conservative forques.
    pub fn energy(&self, t: f64) -> f64 {
        self.kinetic_energy() + self.potential_energy(t)
    }

    /// Returns the total linear momentum Σ p.
    pub fn linear_momentum(&self) -> Vector {
        let mut p = Vector::zero(self.dim());
        for b in &self.bodies {
            p += b.linear_momentum();
        }
        p
    }

    /// Returns the total angular momentum about the origin, Σ (x ∧ p + L_s).
    pub fn angular_momentum(&self) -> Bivector {
        let mut l = Bivector::zero(self.dim());
        for b in &self.bodies {
            l += &b.angular_momentum();
        }
        l
    }
}
