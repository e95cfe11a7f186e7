//! Ball joints in the solves: their rows, the velocity and position solves of the joints.

use super::body::BodyState;
use super::{Dense, Solver};
use crate::algebra::{Bivector, Vector};
use crate::dynamics::motion::forques::Anchor;
use crate::dynamics::motion::{BallJoint, MovingBody};
use crate::numeric::{cholesky_factor, cholesky_substitute};

/// One ball joint in a solve: the offsets of its two ends.
#[derive(Clone, Debug)]
pub(crate) struct JointRow {
    pub body: usize,
    pub r: Vector,
    pub other: Option<(usize, Vector)>,
    pub impulse: Vector,
    /// The joint's inverse mass K (set when a solve starts).
    pub(super) k: Dense,
}

impl JointRow {
    pub(crate) fn new(joint: &BallJoint, bodies: &[MovingBody]) -> JointRow {
        let r = bodies[joint.body].attitude().rotate_vector(&joint.point);
        let other = match &joint.other {
            Anchor::World(_) => None,
            Anchor::Body(j, p) => Some((*j, bodies[*j].attitude().rotate_vector(p))),
        };
        JointRow {
            body: joint.body,
            r,
            other,
            impulse: Vector::zero(bodies[0].dim()),
            k: Dense::new(),
        }
    }

    /// The relative velocity of the two ends.
    pub(super) fn velocity(&self, states: &[BodyState]) -> Vector {
        let mut u = states[self.body].velocity_at(&self.r);
        if let Some((j, q)) = &self.other {
            u -= &states[*j].velocity_at(q);
        }
        u
    }

    /// Applies the impulse `j` to the first end and −`j` to the second.
    pub(super) fn apply(&self, states: &mut [BodyState], j: &Vector) {
        states[self.body].apply(&self.r, j);
        if let Some((b, q)) = &self.other {
            states[*b].apply(q, &(j * -1.0));
        }
    }

    /// The ends as (body, offset, sign of the impulse there).
    pub(super) fn ends(&self) -> impl Iterator<Item = (usize, &Vector, f64)> {
        std::iter::once((self.body, &self.r, 1.0))
            .chain(self.other.iter().map(|(b, q)| (*b, q, -1.0)))
    }
}

impl Solver {
    /// Sets up the joint rows at the current placement.
    /// The factor of the joints' K is kept if every row is the same as before (the bodies'
    /// attitudes did not change; [`Solver::load`] checks their inertias).
    pub(crate) fn find_joints(&mut self, bodies: &[MovingBody], joints: &[BallJoint]) {
        let mut same = self.joints.len() == joints.len();
        self.joints.truncate(joints.len());
        for (k, joint) in joints.iter().enumerate() {
            let row = JointRow::new(joint, bodies);
            match self.joints.get_mut(k) {
                Some(old) => {
                    same &= old.body == row.body && old.r == row.r && old.other == row.other;
                    old.body = row.body;
                    old.r = row.r;
                    old.other = row.other;
                    old.impulse.as_mut_slice().fill(0.0);
                }
                None => self.joints.push(row),
            }
        }
        if !same {
            self.joint_factor = false;
        }
    }

    /// The position step of the joints at the placement the rows were found at: the
    /// impulses J (one per joint) with Σ_k K_jk J_k = −`residuals`[j]/`per`, given to the
    /// bodies. The bodies' inverse inertias and the factor of K are kept from one call to
    /// the next (the placement does not change between them: only momenta do) until
    /// [`Solver::release`]; a velocity solve of joints alone at the same placement leaves
    /// its factor for the first call.
    /// Each joint's impulse is added to `totals`.
    pub(crate) fn joint_position_step(
        &mut self,
        bodies: &mut [MovingBody],
        residuals: &[Vector],
        per: f64,
        totals: &mut [Vector],
    ) {
        self.load(bodies);
        if !self.joint_factor {
            self.factor_joints();
        }
        if self.joint_factor {
            self.apply_joint_solve(residuals, per, Some(totals));
        }
        self.store_loaded(bodies);
    }

    /// Gives the joints the impulses `impulses` (one per joint, first end; the second
    /// takes the opposite), at the placement the rows were found at; the bodies stay
    /// loaded as for [`Solver::joint_position_step`].
    pub(crate) fn joint_position_impulses(
        &mut self,
        bodies: &mut [MovingBody],
        impulses: &[Vector],
    ) {
        self.load(bodies);
        for (row, j) in self.joints.iter().zip(impulses) {
            row.apply(&mut self.states, j);
        }
        self.store_loaded(bodies);
    }

    /// Assembles the joints' K (all joints together, n × n blocks) in `big` and factors it.
    pub(super) fn factor_joints(&mut self) {
        self.joint_factor = false;
        let Some(n) = self.joints.first().map(|j| j.r.dim()) else {
            return;
        };
        let m = self.joints.len() * n;
        let planes = n * (n - 1) / 2;
        // For each joint end (joint a, end e at offset r of body b): C = (r ⌋ ·) as an
        // n × M matrix and W = I⁻¹ (r ∧ ·) as an M × n matrix; the velocity at an end of
        // joint a per impulse at an end of joint c on the same body is 1/m + C_a W_c.
        let (cs, ws) = (n * planes, planes * n);
        self.end_c.clear();
        self.end_c.resize(self.joints.len() * 2 * cs, 0.0);
        self.end_w.clear();
        self.end_w.resize(self.joints.len() * 2 * ws, 0.0);
        let mut e = Bivector::zero(n);
        for (a, row) in self.joints.iter().enumerate() {
            for (end, (b, r, _)) in row.ends().enumerate() {
                let at = a * 2 + end;
                let c = &mut self.end_c[at * cs..(at + 1) * cs];
                for p in 0..planes {
                    e.as_mut_slice().fill(0.0);
                    e.as_mut_slice()[p] = 1.0;
                    for (i, x) in r.left_contract(&e).as_slice().iter().enumerate() {
                        c[i * planes + p] = *x;
                    }
                }
                let w = &mut self.end_w[at * ws..(at + 1) * ws];
                for col in 0..n {
                    let iw = self.states[b].inverse_inertia(&r.wedge(&Vector::basis(n, col)));
                    for (p, x) in iw.as_slice().iter().enumerate() {
                        w[p * n + col] = *x;
                    }
                }
            }
        }
        self.big.clear();
        self.big.resize(m * m, 0.0);
        for (a, row) in self.joints.iter().enumerate() {
            for (ea, (ba, _, sa)) in row.ends().enumerate() {
                let c = &self.end_c[(a * 2 + ea) * cs..(a * 2 + ea + 1) * cs];
                for (k, other) in self.joints.iter().enumerate() {
                    for (ek, (bk, _, sk)) in other.ends().enumerate() {
                        if ba != bk {
                            continue;
                        }
                        let w = &self.end_w[(k * 2 + ek) * ws..(k * 2 + ek + 1) * ws];
                        let inv_mass = self.states[ba].inv_mass;
                        for i in 0..n {
                            for col in 0..n {
                                let mut x: f64 = (0..planes)
                                    .map(|p| c[i * planes + p] * w[p * n + col])
                                    .sum();
                                if i == col {
                                    x += inv_mass;
                                }
                                self.big[(a * n + i) * m + k * n + col] += sa * sk * x;
                            }
                        }
                    }
                }
            }
        }
        self.joint_factor = cholesky_factor(&mut self.big, m);
        if !self.joint_factor {
            self.report.singular_joint_solves += 1;
        }
    }

    /// With the factor in `big`: the impulses J with K J = −`residuals`/`per`, applied to
    /// the loaded states.
    pub(super) fn apply_joint_solve(
        &mut self,
        residuals: &[Vector],
        per: f64,
        mut totals: Option<&mut [Vector]>,
    ) {
        let Some(n) = residuals.first().map(Vector::dim) else {
            return;
        };
        let m = self.joints.len() * n;
        self.big_rhs.clear();
        for r in residuals {
            self.big_rhs.extend(r.as_slice().iter().map(|x| -x / per));
        }
        cholesky_substitute(&self.big, m, &mut self.big_rhs);
        for a in 0..self.joints.len() {
            let j =
                Vector::from_storage(self.big_rhs[a * n..(a + 1) * n].iter().copied().collect());
            let row = &mut self.joints[a];
            row.apply(&mut self.states, &j);
            if let Some(t) = totals.as_deref_mut() {
                t[a] += &j;
            }
            row.impulse += &j;
        }
    }

    pub(super) fn solve_joints_dense_loaded(&mut self, residuals: &[Vector], per: f64) {
        if !self.joint_factor {
            self.factor_joints();
        }
        if self.joint_factor {
            self.apply_joint_solve(residuals, per, None);
        }
    }
}
