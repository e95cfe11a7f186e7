//! One contact point between two bodies in a velocity solve: both bodies' effective inverse
//! masses in one K, the normal impulse with restitution and Coulomb's cone of maximal
//! dissipation, as for a half-space but with the relative velocity of the two points.

use super::Dense;
use super::body::{BodyState, add_inverse_mass};
use super::contact_row::{Small, dim, scratch, tangent_block_n};
use super::friction::friction_impulse;
use crate::algebra::Vector;
use crate::dynamics::motion::detect::bodies::PairContact;
use crate::dynamics::motion::placement::{dot, set_vector};
use crate::numeric::symmetric_eigen_rows as symmetric_eigen;
use crate::numeric::{cholesky_factor_n, cholesky_substitute_n, max_abs};
use smallvec::SmallVec;

/// A contact between bodies `a` and `b`: body `b` takes the impulse J at its point, body `a`
/// takes −J at its own. The normal n points from `a` to `b`; the relative velocity is
/// u = u_b − u_a, approaching while n·u < 0.
#[derive(Clone, Debug)]
pub(crate) struct PairRow {
    pub a: usize,
    pub b: usize,
    /// The features that make the point ([`PairContact::feature`]).
    pub feature: u64,
    /// The signed distance at the point when it was found (negative: overlap).
    pub gap: f64,
    /// The gap up to which the point counts as touching; farther points are speculative:
    /// the bodies may approach there by the gap within the next flight, no more.
    pub reach: f64,
    /// The normal impulse of the position step (RATTLE's), which closes the gap by the end
    /// of the flight.
    pub position_impulse: f64,
    /// The unit normal, from `a` to `b`, in space.
    pub normal: Vector,
    /// The offsets of the contact point from the two centres of mass, in space.
    pub ra: Vector,
    pub rb: Vector,
    /// The same offsets in the bodies' principal axes, which the flight carries along.
    pub own_a: Vector,
    pub own_b: Vector,
    pub friction: f64,
    pub restitution: f64,
    /// The normal relative velocity wanted after the impulse (0, or −e u⁻ for an impact).
    pub target: f64,
    pub normal_impulse: f64,
    pub friction_impulse: Vector,
    /// K = K_a + K_b at the two offsets, its tangent block and that block's
    /// eigen-decomposition and inverse on the tangent space, nᵀ K n and its inverse.
    k: Dense,
    kt: Dense,
    values: Dense,
    vectors: Dense,
    kinv: Dense,
    knn: f64,
    inv_knn: f64,
    /// The relative normal speed before the solve, which tolerances scale with.
    pub(super) speed: f64,
    /// What K and its factors were computed for: the offsets and the normal (r_a, r_b, n,
    /// N each) and the two bodies as they were then ([`MassAt`]); and the attitude
    /// generations `own_a`, `own_b` were computed at. A later step's row of the same point
    /// takes them while its geometry stays within [`KEEP_MASS`] of these and its bodies
    /// are the same ([`PairRow::take_mass`]).
    mass_geometry: SmallVec<[f64; 24]>,
    mass_at: (MassAt, MassAt),
    own_at: (u64, u64),
    /// True when K and its factors were taken from the last step's row of the same point:
    /// the step's solves need not set them up.
    pub(super) mass_ready: bool,
}

/// A body as a pair row's K was computed for it: the generations of its attitude and of
/// its inertia (mass, fixedness, moments), and whether its inverse inertia is the same in
/// every frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct MassAt {
    pub generation: u64,
    pub inertia: u64,
    pub isotropic: bool,
}

impl MassAt {
    /// True if a K computed for the body as `self` holds for it as `now`: the same
    /// attitude generation, or the same inertia of a body whose K does not depend on its
    /// attitude.
    fn holds(&self, now: &MassAt) -> bool {
        self.generation == now.generation || now.isotropic && self.inertia == now.inertia
    }
}

/// How far (relative to the offsets' size) a point's offsets from the two centres and its
/// normal, and (absolutely) the numbers of its bodies' attitudes, may have moved since its
/// K was computed for the point's row to keep that K: a hundredth of the splitting's
/// contact tolerance, as for a kept box manifold.
pub(crate) const KEEP_MASS: f64 = 1e-11;

impl PairRow {
    /// A row for the contact `c` between bodies `a` and `b` (a point in space with a unit
    /// normal from `a` to `b`), the bodies' centres at `x` and their friction and
    /// restitution combined in `material`.
    pub(crate) fn new(c: &PairContact, x: (&[f64], &[f64]), material: (f64, f64)) -> PairRow {
        let n = c.normal.len();
        let mut row = PairRow {
            a: 0,
            b: 0,
            feature: 0,
            gap: 0.0,
            reach: 0.0,
            position_impulse: 0.0,
            normal: Vector::zero(n),
            ra: Vector::zero(n),
            rb: Vector::zero(n),
            own_a: Vector::zero(n),
            own_b: Vector::zero(n),
            friction: 0.0,
            restitution: 0.0,
            target: 0.0,
            normal_impulse: 0.0,
            friction_impulse: Vector::zero(n),
            k: Dense::new(),
            kt: Dense::new(),
            values: Dense::new(),
            vectors: Dense::new(),
            kinv: Dense::new(),
            knn: 0.0,
            inv_knn: 0.0,
            speed: 0.0,
            mass_geometry: SmallVec::new(),
            mass_at: (MassAt::default(), MassAt::default()),
            own_at: (0, 0),
            mass_ready: false,
        };
        row.set(c, x, material);
        row
    }

    /// Makes this row the one [`PairRow::new`] gives, in its own room: a row is some
    /// kilobytes (room for 8 × 8 matrices), which a new one would be built in and moved.
    pub(crate) fn set(&mut self, c: &PairContact, x: (&[f64], &[f64]), material: (f64, f64)) {
        let n = c.normal.len();
        (self.a, self.b, self.feature) = (c.a, c.b, c.feature);
        self.place(c, x, material);
        for v in [&mut self.own_a, &mut self.own_b, &mut self.friction_impulse] {
            if v.dim() == n {
                v.as_mut_slice().fill(0.0);
            } else {
                *v = Vector::zero(n);
            }
        }
        self.normal_impulse = 0.0;
        self.forget_mass();
    }

    /// The point's geometry from the contact `c` found with the bodies' centres at
    /// `(xa, xb)`, its material, and no target, speed or position impulse yet.
    fn place(
        &mut self,
        c: &PairContact,
        (xa, xb): (&[f64], &[f64]),
        (friction, restitution): (f64, f64),
    ) {
        let (normal, point) = (&c.normal[..], &c.point[..]);
        let n = normal.len();
        let offset = |r: &mut Vector, x: &[f64]| {
            if r.dim() != n {
                *r = Vector::zero(n);
            }
            for ((o, p), c) in r.as_mut_slice().iter_mut().zip(point).zip(x) {
                *o = p - c;
            }
        };
        (self.gap, self.reach, self.position_impulse) = (c.gap, c.reach, 0.0);
        set_vector(&mut self.normal, normal);
        offset(&mut self.ra, xa);
        offset(&mut self.rb, xb);
        (self.friction, self.restitution) = (friction, restitution);
        (self.target, self.speed) = (0.0, 0.0);
    }

    /// No K yet: the solve computes it.
    fn forget_mass(&mut self) {
        for m in [
            &mut self.k,
            &mut self.kt,
            &mut self.values,
            &mut self.vectors,
            &mut self.kinv,
        ] {
            m.clear();
        }
        (self.knn, self.inv_knn) = (0.0, 0.0);
        self.mass_ready = false;
    }

    /// Whether `then`, the offsets and normal a K was computed for, lie within
    /// [`KEEP_MASS`] of this row's (relative to the offsets' size).
    fn near(&self, then: &[f64]) -> bool {
        let n = self.normal.dim();
        let limit = KEEP_MASS * (max_abs(self.ra.as_slice()) + max_abs(self.rb.as_slice()));
        then.len() == 3 * n
            && [&self.ra, &self.rb, &self.normal]
                .iter()
                .flat_map(|v| v.as_slice())
                .zip(then)
                .all(|(x, y)| (x - y).abs() <= limit)
    }

    /// The geometry K is to be computed for: this row's offsets and normal, for the
    /// bodies as they are now (`at`).
    fn mass_for_here(&mut self, at: (MassAt, MassAt)) {
        self.mass_geometry.clear();
        for v in [&self.ra, &self.rb, &self.normal] {
            self.mass_geometry.extend_from_slice(v.as_slice());
        }
        self.mass_at = at;
    }

    /// [`Self::set`] and then [`Self::take_mass`] of this row as it was, for the same
    /// point found again (the same bodies; if its features changed, K and the offsets in
    /// the bodies' axes are computed anew): the row updated in place, its impulses
    /// carried, the friction impulse's part along the new normal dropped, as the solve's
    /// matching does with a row rebuilt from its predecessor. Returns whether it kept the
    /// offsets in the bodies' own axes (else the caller computes them).
    pub(crate) fn refresh(
        &mut self,
        c: &PairContact,
        x: (&[f64], &[f64]),
        material: (f64, f64),
        at: (MassAt, MassAt),
    ) -> bool {
        debug_assert!((self.a, self.b) == (c.a, c.b));
        let (last_knn, last_mass_at, last_own_at) = (self.knn, self.mass_at, self.own_at);
        let same = self.feature == c.feature;
        self.feature = c.feature;
        self.place(c, x, material);
        let generations = (at.0.generation, at.1.generation);
        self.own_at = generations;
        let kept = same
            && last_knn != 0.0
            && self.near(&self.mass_geometry)
            && last_mass_at.0.holds(&at.0)
            && last_mass_at.1.holds(&at.1);
        let own = if kept {
            // K, its factors and the geometry they were computed for stay.
            self.mass_ready = true;
            last_own_at == generations
        } else {
            self.forget_mass();
            self.mass_for_here(at);
            false
        };
        self.drop_normal_friction();
        own
    }

    /// Removes from the friction impulse its part along the normal (a normal turned since
    /// the impulse was found), in place.
    pub(crate) fn drop_normal_friction(&mut self) {
        let along = self.normal.dot(&self.friction_impulse);
        let normal = self.normal.as_slice();
        for (f, n) in self.friction_impulse.as_mut_slice().iter_mut().zip(normal) {
            *f -= n * along;
        }
    }

    /// Takes what it can of `last`, the last step's row of the same point, for its bodies
    /// as they are now (`at`): K and its factors if they were computed for offsets and a
    /// normal within [`KEEP_MASS`] of this row's (relative to the offsets' size) and for
    /// the same bodies at attitudes of the same generation (any attitude for a body whose
    /// inverse inertia is the same in every frame); the offsets in the bodies' own axes if
    /// K's geometry holds and they were computed at the attitudes' generations now.
    /// Returns whether it took the offsets (else the caller computes them); K it marks as
    /// ready or to be computed for this row's geometry.
    pub(crate) fn take_mass(&mut self, last: Option<&PairRow>, at: (MassAt, MassAt)) -> bool {
        let last = last.filter(|l| l.knn != 0.0 && self.near(&l.mass_geometry));
        let mass = last.filter(|l| l.mass_at.0.holds(&at.0) && l.mass_at.1.holds(&at.1));
        let generations = (at.0.generation, at.1.generation);
        let Some(last) = mass else {
            self.mass_for_here(at);
            self.own_at = generations;
            return false;
        };
        // Copied as slices: `clone_from` onto the emptied rooms pushes number by number.
        for (to, from) in [
            (&mut self.k, &last.k),
            (&mut self.kt, &last.kt),
            (&mut self.values, &last.values),
            (&mut self.vectors, &last.vectors),
            (&mut self.kinv, &last.kinv),
        ] {
            to.clear();
            to.extend_from_slice(from);
        }
        (self.knn, self.inv_knn) = (last.knn, last.inv_knn);
        self.mass_geometry.clear();
        self.mass_geometry.extend_from_slice(&last.mass_geometry);
        self.mass_at = last.mass_at;
        self.mass_ready = true;
        self.own_at = generations;
        if last.own_at != generations {
            return false;
        }
        set_vector(&mut self.own_a, last.own_a.as_slice());
        set_vector(&mut self.own_b, last.own_b.as_slice());
        true
    }

    /// The relative velocity u_b − u_a of the two points, written to `u` (`N` as in
    /// [`dim`]).
    #[inline(always)]
    fn relative_velocity_into<const N: usize>(&self, states: &[BodyState], u: &mut [f64]) {
        let n = dim::<N>(u.len());
        let (mut fixed, mut any) = ([0.0; 4], Small::new());
        let ua = scratch::<N>(&mut fixed, &mut any, n);
        states[self.b].velocity_at_into::<N>(self.rb.as_slice(), u);
        states[self.a].velocity_at_into::<N>(self.ra.as_slice(), ua);
        for (x, y) in u[..n].iter_mut().zip(ua.iter()) {
            *x -= y;
        }
    }

    /// The relative velocity's component along the normal (`N` as in [`dim`]).
    #[inline(always)]
    fn normal_velocity<const N: usize>(&self, states: &[BodyState]) -> f64 {
        let n = dim::<N>(self.normal.dim());
        let (mut fixed, mut any) = ([0.0; 4], Small::new());
        let u = scratch::<N>(&mut fixed, &mut any, n);
        self.relative_velocity_into::<N>(states, u);
        dot(&self.normal.as_slice()[..n], u)
    }

    /// K and its inverse on the tangent space, for tests.
    #[cfg(test)]
    pub(crate) fn mass(&self) -> (&[f64], &[f64]) {
        (&self.k, &self.kinv)
    }

    /// nᵀ K n, the inverse of the normal impulse's effect on the normal speed.
    pub(crate) fn knn(&self) -> f64 {
        self.knn
    }

    /// Computes K and its parts at the loaded states.
    pub(crate) fn prepare_mass(&mut self, states: &[BodyState]) {
        match self.normal.dim() {
            3 => self.prepare_mass_n::<3>(states),
            4 => self.prepare_mass_n::<4>(states),
            _ => self.prepare_mass_n::<0>(states),
        }
    }

    /// [`PairRow::prepare_mass`] (`N` as in [`dim`]: with N fixed, the loops and the
    /// Cholesky kernels run with constant bounds).
    #[inline(always)]
    fn prepare_mass_n<const N: usize>(&mut self, states: &[BodyState]) {
        let n = dim::<N>(self.normal.dim());
        self.k.clear();
        self.k.resize(n * n, 0.0);
        add_inverse_mass(&states[self.a], &self.ra, &mut self.k);
        add_inverse_mass(&states[self.b], &self.rb, &mut self.k);
        let nv = &self.normal.as_slice()[..n];
        let k = &self.k[..n * n];
        self.knn = (0..n)
            .map(|i| (0..n).map(|j| nv[i] * k[i * n + j] * nv[j]).sum::<f64>())
            .sum();
        self.inv_knn = 1.0 / self.knn;
        self.kt.clear();
        self.kt.extend_from_slice(&self.k);
        tangent_block_n::<N>(&mut self.kt[..n * n], nv);
        // K_t⁻¹ from the Cholesky factor of K_t (positive definite: K's tangent part, and 1
        // along the normal). The eigen-decomposition is needed only to project a sliding
        // point's impulse onto the friction cone, and is taken when one first slides
        // (`values` empty until then): a resting stack never asks for it.
        self.values.clear();
        self.vectors.clear();
        self.kinv.clear();
        self.kinv.resize(n * n, 0.0);
        let (mut fixed, mut any): ([f64; 16], Dense) = ([0.0; 16], SmallVec::new());
        let factor = if N != 0 {
            &mut fixed[..n * n]
        } else {
            any.resize(n * n, 0.0);
            &mut any[..]
        };
        factor.copy_from_slice(&self.kt[..n * n]);
        if cholesky_factor_n::<N>(factor, n) {
            // Column j of K_t⁻¹ solves K_t x = e_j; K_t⁻¹ is symmetric, so it is row j too.
            for (j, row) in self.kinv.chunks_exact_mut(n).enumerate() {
                row[j] = 1.0;
                cholesky_substitute_n::<N>(factor, n, row);
            }
        } else {
            symmetric_eigen(&self.kt, n, &mut self.values, &mut self.vectors);
            for i in 0..n {
                for j in 0..n {
                    self.kinv[i * n + j] = (0..n)
                        .map(|k| self.vectors[i * n + k] * self.vectors[j * n + k] / self.values[k])
                        .sum();
                }
            }
        }
    }

    /// Computes the target at the loaded states: −e u⁻ for a touching point approaching
    /// faster than `resting` (an impact), 0 below (resting), and for a point still `gap`
    /// apart the approach that closes it within a flight of `flight`. On a `mixed` face
    /// (see `face_run` in the solve) a touching point that is not an impact closes
    /// its own gap within the flight as well: −gap / flight.
    pub(crate) fn prepare_target(
        &mut self,
        states: &[BodyState],
        resting: f64,
        flight: f64,
        mixed: bool,
    ) {
        let un = match self.normal.dim() {
            3 => self.normal_velocity::<3>(states),
            4 => self.normal_velocity::<4>(states),
            _ => self.normal_velocity::<0>(states),
        };
        self.speed = un.abs();
        self.target = if self.gap > self.reach {
            -self.gap / flight
        } else {
            let target = if un < -resting {
                -self.restitution * un
            } else if mixed && self.gap >= -self.reach {
                -self.gap / flight
            } else {
                0.0
            };
            if self.gap < -self.reach {
                // Overlapping by more than the touching distance (a contact that sank while
                // others held it, or bodies placed so): leave at the speed that closes the
                // overlap within the flight, so that the position step starts from a
                // solution of its linearisation, but no faster than one step of the forques
                // would make it approach (a short flight gets no kick out of proportion).
                target.max((-self.gap / flight).min(resting))
            } else {
                target
            }
        };
    }

    /// Gives body `b` the impulse `j` at its point and body `a` the opposite (`N` as in
    /// [`dim`]).
    #[inline(always)]
    fn apply<const N: usize>(&self, states: &mut [BodyState], j: &[f64]) {
        states[self.b].apply_scaled::<N>(self.rb.as_slice(), j, 1.0);
        states[self.a].apply_scaled::<N>(self.ra.as_slice(), j, -1.0);
    }

    /// Gives the accumulated impulses to the loaded states (a warm start).
    pub(crate) fn apply_accumulated(&self, states: &mut [BodyState]) {
        match self.normal.dim() {
            3 => self.apply_accumulated_n::<3>(states),
            4 => self.apply_accumulated_n::<4>(states),
            _ => self.apply_accumulated_n::<0>(states),
        }
    }

    /// [`Self::apply_accumulated`] with the kernels of dimension `N` (as in [`dim`]), J in
    /// room on the stack.
    fn apply_accumulated_n<const N: usize>(&self, states: &mut [BodyState]) {
        let n = dim::<N>(self.normal.dim());
        let (mut fixed, mut any) = ([0.0; 4], Small::new());
        let j = scratch::<N>(&mut fixed, &mut any, n);
        self.total_impulse(j);
        if max_abs(j) > 0.0 {
            self.apply::<N>(states, j);
        }
    }

    /// The accumulated impulse as one vector, J = λ n + J_t, written to `j`.
    pub(super) fn total_impulse(&self, j: &mut [f64]) {
        let nv = self.normal.as_slice();
        for ((x, y), t) in j.iter_mut().zip(nv).zip(self.friction_impulse.as_slice()) {
            *x = y * self.normal_impulse + t;
        }
    }

    /// Adds the impulse `j` to the accumulated one, split into its normal and tangent
    /// parts, and gives it to the bodies (`N` as in [`dim`]). Either part may leave its
    /// cone: the next sweep projects it back.
    #[inline(always)]
    pub(super) fn add_impulse<const N: usize>(&mut self, states: &mut [BodyState], j: &[f64]) {
        let n = dim::<N>(self.normal.dim());
        let nv = &self.normal.as_slice()[..n];
        let along = dot(nv, &j[..n]);
        self.normal_impulse += along;
        for ((t, x), y) in self.friction_impulse.as_mut_slice()[..n]
            .iter_mut()
            .zip(&j[..n])
            .zip(nv)
        {
            *t += x - along * y;
        }
        self.apply::<N>(states, &j[..n]);
    }

    /// One Gauss–Seidel update: the normal impulse (the smallest accumulated λ ≥ 0 that
    /// reaches the target), then the friction impulse of maximal dissipation in the disc
    /// |J_t| ≤ μλ. Returns the largest velocity change it made.
    pub(crate) fn sweep(&mut self, states: &mut [BodyState]) -> f64 {
        match self.normal.dim() {
            3 => self.sweep_n::<3>(states),
            4 => self.sweep_n::<4>(states),
            _ => self.sweep_n::<0>(states),
        }
    }

    /// [`PairRow::sweep`] (`N` as in [`dim`]). The relative velocity is read once: the
    /// normal impulse's change moves it by K n Δλ, so the slip is known without reading
    /// the bodies again, and the normal and friction changes reach them as one impulse.
    #[inline(always)]
    fn sweep_n<const N: usize>(&mut self, states: &mut [BodyState]) -> f64 {
        let n = dim::<N>(self.normal.dim());
        let nv = &self.normal.as_slice()[..n];
        let (mut u_fixed, mut u_any) = ([0.0; 4], Small::new());
        let u = scratch::<N>(&mut u_fixed, &mut u_any, n);
        self.relative_velocity_into::<N>(states, u);
        let un = dot(nv, u);
        let lambda = (self.normal_impulse + (self.target - un) * self.inv_knn).max(0.0);
        let dl = lambda - self.normal_impulse;
        self.normal_impulse = lambda;
        let mut change = (dl * self.knn).abs();
        if dl != 0.0 {
            for (x, k) in u.iter_mut().zip(self.k.chunks_exact(n)) {
                *x += dl * dot(k, nv);
            }
        }
        let limit = self.friction * self.normal_impulse;
        // The slip: the relative velocity's tangent part.
        let along = dot(nv, u);
        for (x, y) in u.iter_mut().zip(nv) {
            *x -= along * y;
        }
        let old = &self.friction_impulse.as_slice()[..n];
        let (mut new_fixed, mut new_any) = ([0.0; 4], Small::new());
        let new = scratch::<N>(&mut new_fixed, &mut new_any, n);
        for ((x, o), k) in new.iter_mut().zip(old).zip(self.kinv.chunks_exact(n)) {
            *x = o - dot(k, u);
        }
        if limit <= 0.0 {
            new.fill(0.0);
        } else if dot(new, new) > limit * limit {
            if self.values.is_empty() {
                symmetric_eigen(&self.kt, n, &mut self.values, &mut self.vectors);
            }
            friction_impulse::<N>(&self.values, &self.vectors, &self.kt, old, u, limit, new);
        }
        // The impulse of the update: Δλ n and the friction impulse's change.
        let (mut dj_fixed, mut dj_any) = ([0.0; 4], Small::new());
        let dj = scratch::<N>(&mut dj_fixed, &mut dj_any, n);
        let mut largest = 0.0f64;
        for (((d, x), y), m) in dj.iter_mut().zip(new.iter()).zip(old).zip(nv) {
            let t = x - y;
            largest = largest.max(t.abs());
            *d = t + dl * m;
        }
        if largest > 0.0 {
            self.friction_impulse.as_mut_slice().copy_from_slice(new);
            change = change.max(largest * self.knn);
        }
        if largest > 0.0 || dl != 0.0 {
            self.apply::<N>(states, dj);
        }
        change
    }
}
