//! The contact solve of [`SoftStep`](crate::dynamics::motion::SoftStep): soft contacts
//! solved by a fixed number of Gauss–Seidel passes per substep (the "soft step" of Box2D
//! v3, Catto 2024, after Macklin et al., "Small Steps in Physics Simulation", SCA 2019).
//!
//! Each contact point is a row: a normal n from body a to body b (or from a half-space to
//! its body), the offsets r_a and r_b of the point from the centres of mass in space at the
//! start of the step, and their images in the bodies' principal axes, which give the
//! current separation after each substep's flight without a new detection:
//! s = s₀ + n · (Δx_b + Q_b r̂_b − r_b − Δx_a − Q_a r̂_a + r_a).
//!
//! A point's normal velocity answers an impulse λ n linearly: with c = r ∧ n and
//! w = I⁻¹ c (space), n · u = n · v + c · ω, and the impulse changes v by λ n / m and ω by
//! λ w. Each row keeps c and w of both bodies, so that an update costs a few dot products.
//!
//! A penetration s < 0 is pushed out by a damped spring (its stiffness ω² and damping 2ζω
//! per unit of effective mass) solved implicitly over the substep: the bias velocity
//! ω s / (2ζ + hω), the mass scaled by hω(2ζ + hω)/(1 + hω(2ζ + hω)) and the accumulated
//! impulse leaking by 1/(1 + hω(2ζ + hω)) (Catto's "soft constraint"). A gap s > 0 may close
//! within the substep, no more (a speculative contact). Friction keeps the tangential
//! impulse in the disc |J_t| ≤ μλ by projection onto it, with each tangent direction's own
//! effective mass.

use super::body::{AttitudeMatrix, BodyState};
use super::contact_row::{ContactRow, Small, dim, scratch};
use super::run_len;
use crate::algebra::Vector;
use crate::dynamics::motion::contact::ContactLog;
use crate::dynamics::motion::placement::dot;
use crate::dynamics::motion::{MovingBody, Wrench};
use smallvec::SmallVec;

/// No body: the half-space side of a contact with a half-space.
pub(crate) const NO_BODY: usize = usize::MAX;

/// What [`SoftSolver::load`] takes anew: the rows' arms need the bodies' inverse inertia
/// in space at the start of the step, the substeps only their velocities.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Load {
    /// Everything, the inverse inertia in space too.
    Placed,
    /// The velocities after a kick, which turns no body: the frames are the last load's.
    Kicked,
    /// The velocities and the frames after a flight.
    Flown,
}

/// The soft spring of a contact over one substep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Softness {
    pub bias_rate: f64,
    pub mass_scale: f64,
    pub impulse_scale: f64,
}

impl Softness {
    /// The spring of frequency `hertz` and damping ratio `zeta` over a substep `h`.
    pub(crate) fn new(hertz: f64, zeta: f64, h: f64) -> Softness {
        if hertz == 0.0 {
            return Softness {
                bias_rate: 0.0,
                mass_scale: 1.0,
                impulse_scale: 0.0,
            };
        }
        let omega = 2.0 * std::f64::consts::PI * hertz;
        let a1 = 2.0 * zeta + h * omega;
        let a2 = h * omega * a1;
        let a3 = 1.0 / (1.0 + a2);
        Softness {
            bias_rate: omega / a1,
            mass_scale: a2 * a3,
            impulse_scale: a3,
        }
    }
}

/// One contact point of the soft solve (its vectors are in [`SoftSolver::data`] and
/// [`SoftSolver::cold`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct SoftRow {
    /// The two bodies (`a` is [`NO_BODY`] for a half-space).
    pub a: usize,
    pub b: usize,
    /// What makes the point, to find it again in the next step: the features of a pair, or
    /// the half-space and candidate of a body.
    pub key: u64,
    /// The separation at the start of the step (negative: overlap).
    pub gap: f64,
    pub friction: f64,
    pub restitution: f64,
    /// 1 / (nᵀ K n).
    normal_mass: f64,
    /// The normal relative velocity before the first substep (for restitution).
    approach: f64,
    /// The accumulated normal impulse of the current substep, and the largest of the step.
    pub normal_impulse: f64,
    max_normal_impulse: f64,
    /// The normal impulse summed over the step's substeps: what the row gave the bodies.
    total_normal_impulse: f64,
    /// True if the contact is with a fixed body or a half-space (a stiffer spring).
    fixed: bool,
    /// Where the row's numbers start in [`SoftSolver::data`] ([`Layout::len`] of them).
    at: usize,
}

/// Where a row's vectors lie (N = n, M = n(n−1)/2, T = n − 1): what the passes read in
/// [`SoftSolver::data`] ([`Layout::len`] numbers a row), the rest in [`SoftSolver::cold`]
/// (`cold_stride`). The passes then stream only their own numbers: a pile of a thousand
/// bodies has rows of several megabytes, beyond the processor's nearer caches. Body a's
/// arms come last, so that a row with a half-space, which has no body a, stops before
/// them.
#[derive(Clone, Copy, Debug, Default)]
struct Layout {
    n: usize,
    m: usize,
    /// In `data`: n (N), the friction impulse's coordinates on the tangent directions (T,
    /// in a slot of N).
    normal: usize,
    tangent_impulse: usize,
    /// T tangent directions (N each) and their 1/(tᵀ K t) (T).
    tangents: usize,
    tangent_mass: usize,
    /// c_b, w_b of the normal, then of each tangent (2M each); a direction's c_a, w_a lie
    /// `a_arms` further on, after those of every direction.
    arms: usize,
    tangent_arms: usize,
    a_arms: usize,
    stride: usize,
    /// In `cold`: r_a, r_b, r̂_a, r̂_b (N each).
    ra: usize,
    rb: usize,
    own_a: usize,
    own_b: usize,
    /// The normal in the principal axes of body a (for a manifold kept from step to step).
    own_normal: usize,
    /// The friction impulse's coordinates summed over the step's substeps (T).
    total_tangent: usize,
    cold_stride: usize,
}

impl Layout {
    #[inline(always)]
    fn new(n: usize) -> Layout {
        let m = n * (n - 1) / 2;
        let t = n - 1;
        let tangents = 2 * n;
        let tangent_mass = tangents + t * n;
        let arms = tangent_mass + t;
        let a_arms = 2 * m * (1 + t);
        Layout {
            n,
            m,
            normal: 0,
            tangent_impulse: n,
            tangents,
            tangent_mass,
            arms,
            tangent_arms: arms + 2 * m,
            a_arms,
            stride: arms + 2 * a_arms,
            ra: 0,
            rb: n,
            own_a: 2 * n,
            own_b: 3 * n,
            own_normal: 4 * n,
            total_tangent: 5 * n,
            cold_stride: 5 * n + t,
        }
    }

    /// The numbers of a row in `data`: without body a's arms for a half-space.
    #[inline(always)]
    fn len(&self, a: usize) -> usize {
        if a == NO_BODY {
            self.stride - self.a_arms
        } else {
            self.stride
        }
    }

    /// The b arms (c_b, w_b) of the tangent `t`.
    #[inline(always)]
    fn tangent(&self, t: usize) -> (usize, usize) {
        (
            self.tangents + t * self.n,
            self.tangent_arms + 2 * t * self.m,
        )
    }
}

/// The numbers of `row` in `data`.
#[inline(always)]
fn numbers<'a>(data: &'a [f64], row: &SoftRow, l: &Layout) -> &'a [f64] {
    &data[row.at..row.at + l.len(row.a)]
}

/// The numbers of `row` in `data`, to change.
#[inline(always)]
fn numbers_mut<'a>(data: &'a mut [f64], row: &SoftRow, l: &Layout) -> &'a mut [f64] {
    &mut data[row.at..row.at + l.len(row.a)]
}

/// The loaded bodies' velocities (v, then ω in space) as the passes leave them and as they
/// were loaded, S = N + M numbers each, and their inverse masses, in flat arrays while the
/// passes run: a row update then reads and writes them without going through the states'
/// storage. What the passes gave a body is its change of velocity (times its mass and
/// inertia), so that an update does not sum the impulses as well.
#[derive(Clone, Debug, Default)]
struct Flat {
    vel: Vec<f64>,
    start: Vec<f64>,
    inv_mass: Vec<f64>,
}

/// The layout of `l`'s dimension, built from `N` when it is fixed (as in [`dim`]): its
/// offsets are then constants, and the kernels' slices need no bounds checks.
#[inline(always)]
fn layout<const N: usize>(l: &Layout) -> Layout {
    if N == 0 { *l } else { Layout::new(N) }
}

/// A contact point found by detection, for [`SoftSolver::push`].
pub(crate) struct FoundPoint<'a> {
    pub a: usize,
    pub b: usize,
    pub key: u64,
    pub gap: f64,
    /// The unit normal from a (or the half-space) to b.
    pub normal: &'a [f64],
    /// The point in space.
    pub point: &'a [f64],
    pub friction: f64,
    pub restitution: f64,
}

/// The rows and body states of the soft solve, kept from step to step for their room and
/// for the impulses to start from.
#[derive(Clone, Debug, Default)]
pub(crate) struct SoftSolver {
    rows: Vec<SoftRow>,
    data: Vec<f64>,
    cold: Vec<f64>,
    /// The last step's rows and vectors, to start from (listed by (a, b, key) in `order`).
    old_rows: Vec<SoftRow>,
    old_data: Vec<f64>,
    old_cold: Vec<f64>,
    layout: Layout,
    states: Vec<BodyState>,
    /// Each body's position at the start of the step, and its attitude now (Q, N × N).
    start: Vec<f64>,
    frames: Vec<f64>,
    /// Each body's position now.
    positions: Vec<f64>,
    /// The loaded bodies' velocities during the passes.
    flat: Flat,
    /// Room for a row's tangential impulses, and for a body's change of velocity (and its
    /// angular part in the principal frame).
    scratch: Vec<f64>,
    change: Vec<f64>,
    /// Each row's separation at the bodies' current placement, and the last step's rows'
    /// at its end.
    separations: Vec<f64>,
    old_separations: Vec<f64>,
    order: Vec<usize>,
}

impl SoftSolver {
    /// Starts the rows of a step of bodies in `n` dimensions.
    pub(crate) fn begin(&mut self, bodies: &[MovingBody]) {
        let n = bodies[0].dim();
        if self.layout.n != n {
            *self = SoftSolver {
                layout: Layout::new(n),
                ..SoftSolver::default()
            };
        }
        std::mem::swap(&mut self.rows, &mut self.old_rows);
        std::mem::swap(&mut self.data, &mut self.old_data);
        std::mem::swap(&mut self.cold, &mut self.old_cold);
        std::mem::swap(&mut self.separations, &mut self.old_separations);
        self.old_separations.resize(self.old_rows.len(), 0.0);
        self.old_sort();
        self.rows.clear();
        self.data.clear();
        self.cold.clear();
        self.states
            .resize_with(bodies.len(), || BodyState::empty(n));
        self.start.clear();
        self.frames.clear();
        self.frames.resize(bodies.len() * n * n, 0.0);
        for (i, b) in bodies.iter().enumerate() {
            self.start.extend_from_slice(b.position().as_slice());
            b.rotation()
                .principal_frame_attitude()
                .write_matrix(&mut self.frames[i * n * n..(i + 1) * n * n]);
        }
        self.positions.clone_from(&self.start);
        let stride = n + n * (n - 1) / 2;
        self.flat.vel.resize(bodies.len() * stride, 0.0);
        self.flat.start.resize(bodies.len() * stride, 0.0);
        self.flat.inv_mass.resize(bodies.len(), 0.0);
        // A row's tangential impulses (n), then the sum of its impulses (n + 2m).
        self.scratch.resize(2 * n + n * (n - 1), 0.0);
    }

    /// Adds a contact point (the bodies at the start of the step, as [`Self::begin`] saw
    /// them).
    pub(crate) fn push(&mut self, p: &FoundPoint<'_>) {
        match self.layout.n {
            3 => self.push_n::<3>(p),
            4 => self.push_n::<4>(p),
            _ => self.push_n::<0>(p),
        }
    }

    fn push_n<const N: usize>(&mut self, p: &FoundPoint<'_>) {
        let l = layout::<N>(&self.layout);
        let n = dim::<N>(l.n);
        let start = self.data.len();
        self.data.resize(start + l.len(p.a), 0.0);
        self.data[start + l.normal..start + l.normal + n].copy_from_slice(&p.normal[..n]);
        let at = self.cold.len();
        self.cold.resize(at + l.cold_stride, 0.0);
        let d = &mut self.cold[at..at + l.cold_stride];
        if p.a != NO_BODY {
            let q = &self.frames[p.a * n * n..(p.a + 1) * n * n];
            for k in 0..n {
                d[l.own_normal + k] = (0..n).map(|i| q[i * n + k] * p.normal[i]).sum();
            }
        }
        for (body, offset, own) in [(p.a, l.ra, l.own_a), (p.b, l.rb, l.own_b)] {
            if body == NO_BODY {
                continue;
            }
            let x = &self.start[body * n..(body + 1) * n];
            for k in 0..n {
                d[offset + k] = p.point[k] - x[k];
            }
            // r̂ = Qᵀ r.
            let q = &self.frames[body * n * n..(body + 1) * n * n];
            for k in 0..n {
                d[own + k] = (0..n).map(|i| q[i * n + k] * d[offset + i]).sum();
            }
        }
        self.rows.push(SoftRow {
            a: p.a,
            b: p.b,
            key: p.key,
            gap: p.gap,
            friction: p.friction,
            restitution: p.restitution,
            normal_mass: 0.0,
            approach: 0.0,
            normal_impulse: 0.0,
            max_normal_impulse: 0.0,
            total_normal_impulse: 0.0,
            fixed: false,
            at: start,
        });
    }

    /// Adds the last step's rows of the pair (a, b) again, each at the point midway between
    /// its material points of the two bodies at their placement now, the normal turned with
    /// body a, the gap the rows' separation at the end of the last step. Returns false if the
    /// last step had no row of the pair.
    pub(crate) fn push_kept(&mut self, pair: (usize, usize)) -> bool {
        match self.layout.n {
            3 => self.push_kept_n::<3>(pair),
            4 => self.push_kept_n::<4>(pair),
            _ => self.push_kept_n::<0>(pair),
        }
    }

    fn push_kept_n<const N: usize>(&mut self, (a, b): (usize, usize)) -> bool {
        let l = layout::<N>(&self.layout);
        let n = dim::<N>(l.n);
        let rows = &self.old_rows;
        let first = self
            .order
            .partition_point(|&k| (rows[k].a, rows[k].b) < (a, b));
        let count = self.order[first..]
            .iter()
            .take_while(|&&k| (rows[k].a, rows[k].b) == (a, b))
            .count();
        for at in first..first + count {
            let k = self.order[at];
            let old = self.old_rows[k];
            let start = self.data.len();
            self.data
                .extend_from_slice(numbers(&self.old_data, &old, &l));
            let d = &mut self.data[start..];
            let at = self.cold.len();
            self.cold
                .extend_from_slice(&self.old_cold[k * l.cold_stride..(k + 1) * l.cold_stride]);
            let c = &mut self.cold[at..at + l.cold_stride];
            // The point midway between the two material points, as detection gives it: both
            // bodies take the impulse there, so that it exerts no torque about any origin.
            let (xa, xb) = (
                &self.start[a * n..(a + 1) * n],
                &self.start[b * n..(b + 1) * n],
            );
            let (qa, qb) = (
                &self.frames[a * n * n..(a + 1) * n * n],
                &self.frames[b * n * n..(b + 1) * n * n],
            );
            for i in 0..n {
                let pa = xa[i] + dot(&qa[i * n..(i + 1) * n], &c[l.own_a..l.own_a + n]);
                let pb = xb[i] + dot(&qb[i * n..(i + 1) * n], &c[l.own_b..l.own_b + n]);
                let p = 0.5 * (pa + pb);
                c[l.ra + i] = p - xa[i];
                c[l.rb + i] = p - xb[i];
            }
            for (q, offset, own) in [(qa, l.ra, l.own_a), (qb, l.rb, l.own_b)] {
                for k in 0..n {
                    c[own + k] = (0..n).map(|i| q[i * n + k] * c[offset + i]).sum();
                }
            }
            let q = &self.frames[a * n * n..(a + 1) * n * n];
            for i in 0..n {
                d[l.normal + i] = dot(&q[i * n..(i + 1) * n], &c[l.own_normal..l.own_normal + n]);
            }
            self.rows.push(SoftRow {
                gap: self.old_separations[k],
                at: start,
                ..old
            });
        }
        count > 0
    }

    /// Loads every body a row acts on, as `what` says.
    fn load(&mut self, bodies: &[MovingBody], what: Load) {
        match self.layout.n {
            3 => self.load_n::<3>(bodies, what),
            4 => self.load_n::<4>(bodies, what),
            _ => self.load_n::<0>(bodies, what),
        }
    }

    fn load_n<const N: usize>(&mut self, bodies: &[MovingBody], what: Load) {
        let n = dim::<N>(self.layout.n);
        let m = n * (n - 1) / 2;
        let stride = n + m;
        for r in &self.rows {
            for i in [r.a, r.b] {
                if i != NO_BODY && !self.states[i].used {
                    // `frames` holds the bodies' attitudes as they are now: written by
                    // `begin`, then by `moved` after each flight (a kick turns no body).
                    let matrix = &self.frames[i * n * n..(i + 1) * n * n];
                    let st = &mut self.states[i];
                    let vel = &mut self.flat.vel[i * stride..(i + 1) * stride];
                    match what {
                        Load::Placed => {
                            st.load_placed(&bodies[i], AttitudeMatrix::Given(matrix));
                            vel[..n].copy_from_slice(&st.v.as_slice()[..n]);
                            vel[n..].copy_from_slice(&st.w.as_slice()[..m]);
                        }
                        Load::Kicked => st.load_velocities(&bodies[i], None, vel),
                        Load::Flown => st.load_velocities(&bodies[i], Some(matrix), vel),
                    }
                    let here = i * stride..(i + 1) * stride;
                    self.flat.start[here.clone()].copy_from_slice(&self.flat.vel[here]);
                    self.flat.inv_mass[i] = st.inv_mass;
                }
            }
        }
    }

    /// Hands the loaded bodies what the passes did to their velocities (after the passes,
    /// before their flight).
    pub(crate) fn store(&mut self, bodies: &mut [MovingBody]) {
        let stride = self.layout.n + self.layout.m;
        self.change.resize(stride + 2 * self.layout.m, 0.0);
        let (change, work) = self.change.split_at_mut(stride);
        for (i, (st, b)) in self.states.iter_mut().zip(bodies).enumerate() {
            if st.used {
                let here = i * stride..(i + 1) * stride;
                let (now, then) = (&self.flat.vel[here.clone()], &self.flat.start[here]);
                for ((c, x), x0) in change.iter_mut().zip(now).zip(then) {
                    *c = x - x0;
                }
                st.store_velocity_change(b, change, work);
            }
        }
    }

    /// Computes each row's arms, effective masses and tangent directions at the start of
    /// the step and takes the impulses of the same points of the last step.
    pub(crate) fn prepare(&mut self, bodies: &[MovingBody]) {
        self.load(bodies, Load::Placed);
        match self.layout.n {
            3 => self.prepare_n::<3>(bodies),
            4 => self.prepare_n::<4>(bodies),
            _ => self.prepare_n::<0>(bodies),
        }
        self.separations.clear();
        self.separations.extend(self.rows.iter().map(|r| r.gap));
        // The substeps load the bodies again after their kicks.
        for s in &mut self.states {
            s.used = false;
        }
    }

    fn prepare_n<const N: usize>(&mut self, bodies: &[MovingBody]) {
        let l = layout::<N>(&self.layout);
        let n = dim::<N>(l.n);
        // The rows of one pair are consecutive: the last step's rows of the pair (a, b)
        // are found once, as the range `old_pair` of `order`, and each row's point among
        // them by its key.
        let mut old_pair = (NO_BODY, NO_BODY, 0, 0);
        for (k, row) in self.rows.iter_mut().enumerate() {
            let d = numbers_mut(&mut self.data, row, &l);
            let c = &mut self.cold[k * l.cold_stride..(k + 1) * l.cold_stride];
            // Tangent directions: the columns of the Householder reflection that takes the
            // axis nearest to n onto n, except that one.
            let normal = &d[l.normal..l.normal + n];
            let j = (0..n)
                .max_by(|&x, &y| normal[x].abs().total_cmp(&normal[y].abs()))
                .unwrap_or(0);
            let sign = if normal[j] < 0.0 { -1.0 } else { 1.0 };
            let (mut u_fixed, mut u_any) = ([0.0; 4], Small::new());
            let u = scratch::<N>(&mut u_fixed, &mut u_any, n);
            u.copy_from_slice(normal);
            u[j] -= sign;
            // n = ±e_j exactly: the other axes.
            let uu = dot(u, u);
            let f = if uu > 0.0 { 2.0 / uu } else { 0.0 };
            for (t, c) in (0..n).filter(|&c| c != j).enumerate() {
                let dir = &mut d[l.tangents + t * n..l.tangents + (t + 1) * n];
                for (i, x) in dir.iter_mut().enumerate() {
                    let e = if i == c { 1.0 } else { 0.0 };
                    *x = e - f * u[i] * u[c];
                }
            }
            let fixed_a = row.a == NO_BODY || bodies[row.a].is_fixed();
            row.fixed = fixed_a || bodies[row.b].is_fixed();
            let ends = (row.a, row.b);
            let knn = set_arms::<N>(&self.states, bodies, ends, (d, c), &l, l.normal, l.arms);
            row.normal_mass = if knn > 0.0 { 1.0 / knn } else { 0.0 };
            for t in 0..n - 1 {
                let (dir, arms) = l.tangent(t);
                let ktt = set_arms::<N>(&self.states, bodies, ends, (d, c), &l, dir, arms);
                d[l.tangent_mass + t] = if ktt > 0.0 { 1.0 / ktt } else { 0.0 };
            }
            // The same point in the last step: its impulses, the friction impulse in the
            // new tangent space.
            row.normal_impulse = 0.0;
            d[l.tangent_impulse..l.tangent_impulse + n].fill(0.0);
            let old_rows = &self.old_rows;
            if (old_pair.0, old_pair.1) != (row.a, row.b) {
                let pair = (row.a, row.b);
                let first = self
                    .order
                    .partition_point(|&k| (old_rows[k].a, old_rows[k].b) < pair);
                let count = self.order[first..]
                    .iter()
                    .take_while(|&&k| (old_rows[k].a, old_rows[k].b) == pair)
                    .count();
                old_pair = (row.a, row.b, first, first + count);
            }
            if let Some(&at) = self.order[old_pair.2..old_pair.3]
                .iter()
                .find(|&&k| old_rows[k].key == row.key)
            {
                let old = &self.old_rows[at];
                row.normal_impulse = old.normal_impulse;
                let od = numbers(&self.old_data, old, &l);
                // J_t = Σ τ_t t_t on the old directions, then its coordinates on the new ones
                // (which drops its part along the new normal).
                for t in 0..n - 1 {
                    let dir = &d[l.tangents + t * n..l.tangents + (t + 1) * n];
                    d[l.tangent_impulse + t] = (0..n - 1)
                        .map(|u| {
                            let old_dir = &od[l.tangents + u * n..l.tangents + (u + 1) * n];
                            od[l.tangent_impulse + u] * dot(old_dir, dir)
                        })
                        .sum();
                }
            }
            row.approach = row_velocity::<N>(&self.flat, row, d, &l, (l.normal, l.arms));
            row.max_normal_impulse = 0.0;
            row.total_normal_impulse = 0.0;
            c[l.total_tangent..l.total_tangent + n - 1].fill(0.0);
        }
    }

    /// Lists the last step's rows in the order of their pairs (a, b) in `order`, for the
    /// searches of [`Self::push_kept`] and [`Self::prepare`] (the rows and their vectors
    /// stay where they are: moving them costs more than the searches through the list).
    /// A step lists the rows with half-spaces (a = [`NO_BODY`]) first and then the pairs
    /// of bodies, each part in the order of its pairs: the list is then the pairs' part
    /// followed by the half-spaces', with no sort.
    fn old_sort(&mut self) {
        let rows = &self.old_rows;
        let planes = rows.partition_point(|r| r.a == NO_BODY);
        self.order.clear();
        self.order.extend(planes..rows.len());
        self.order.extend(0..planes);
        let pair = |k: usize| (rows[k].a, rows[k].b);
        if !self.order.windows(2).all(|w| pair(w[0]) <= pair(w[1])) {
            // A stable sort: the points of a pair keep their order.
            self.order.sort_by_key(|&k| pair(k));
        }
    }

    /// One substep of length `h`: the loaded bodies take the accumulated impulses (the warm
    /// start) and `passes` passes of soft updates. With `carried`, the bodies' velocities
    /// are those the last relax passes left loaded (see [`Self::relax`]), with the kick
    /// since given by [`Self::kick_loaded`]; else they are loaded from the bodies.
    pub(crate) fn solve(
        &mut self,
        bodies: &[MovingBody],
        h: f64,
        (soft, push_out): ((Softness, Softness), f64),
        passes: usize,
        carried: bool,
    ) {
        if !carried {
            self.load(bodies, Load::Kicked);
        }
        match self.layout.n {
            3 => self.solve_n::<3>(h, soft, push_out, passes),
            4 => self.solve_n::<4>(h, soft, push_out, passes),
            _ => self.solve_n::<0>(h, soft, push_out, passes),
        }
    }

    fn solve_n<const N: usize>(
        &mut self,
        h: f64,
        soft: (Softness, Softness),
        push_out: f64,
        passes: usize,
    ) {
        let l = layout::<N>(&self.layout);
        let n = dim::<N>(l.n);
        // Each row's impulses summed first, so that its bodies' velocities are read and
        // written once.
        let mut fixed = [0.0; 16];
        for row in &self.rows {
            let d = numbers(&self.data, row, &l);
            let sum = sum_room::<N>(&mut fixed, &mut self.scratch[n..], &l);
            let has_a = row.a != NO_BODY;
            let normal = (l.normal, l.arms);
            let mut any = add_impulse::<N>(sum, d, &l, normal, has_a, row.normal_impulse);
            for t in 0..n - 1 {
                let tangent = l.tangent(t);
                any |= add_impulse::<N>(sum, d, &l, tangent, has_a, d[l.tangent_impulse + t]);
            }
            if any {
                let (e, w) = sum[..n + 2 * l.m].split_at(n);
                Ends::of(&mut self.flat, (row.a, row.b), n + l.m)
                    .give::<N>((e, w.split_at(l.m)), 1.0);
            }
        }
        for _ in 0..passes {
            self.pass::<N>(h, Some(soft), push_out);
        }
    }

    /// The bodies' attitudes and positions after a flight, for the rows' separations.
    pub(crate) fn moved(&mut self, bodies: &[MovingBody]) {
        let n = self.layout.n;
        for (i, b) in bodies.iter().enumerate() {
            b.rotation()
                .principal_frame_attitude()
                .write_matrix(&mut self.frames[i * n * n..(i + 1) * n * n]);
            self.positions[i * n..(i + 1) * n].copy_from_slice(b.position().as_slice());
        }
        match n {
            3 => self.separations_n::<3>(),
            4 => self.separations_n::<4>(),
            _ => self.separations_n::<0>(),
        }
    }

    /// Every row's separation ([`Self::separation`]) into `separations`, the dimension
    /// chosen once for all rows.
    fn separations_n<const N: usize>(&mut self) {
        let mut separations = std::mem::take(&mut self.separations);
        for (k, s) in separations.iter_mut().enumerate().take(self.rows.len()) {
            *s = self.separation::<N>(k);
        }
        self.separations = separations;
    }

    /// The relax passes after the flight (no bias but that of speculative gaps), and on
    /// the last substep the restitution pass; then the impulses go to the bodies.
    ///
    /// With `carry`, the bodies keep the velocities the passes leave loaded instead of
    /// taking them: the next substep's kick gives them its change of velocity
    /// ([`Self::kick_loaded`]) and its solve goes on from them, and its store hands the
    /// bodies both solves' changes at once (the bodies do not turn in between, so that is
    /// the same change of momenta, to round-off). Not on the last substep.
    pub(crate) fn relax(
        &mut self,
        bodies: &mut [MovingBody],
        h: f64,
        (restitution_speed, passes): (f64, usize),
        last: bool,
        carry: bool,
    ) {
        self.load(bodies, Load::Flown);
        match self.layout.n {
            3 => self.relax_n::<3>(h, (restitution_speed, passes), last),
            4 => self.relax_n::<4>(h, (restitution_speed, passes), last),
            _ => self.relax_n::<0>(h, (restitution_speed, passes), last),
        }
        if last || !carry {
            self.store(bodies);
        }
    }

    /// Gives the loaded bodies that can move the change of velocity F h / m of a kick by
    /// the forces of `wrenches` (whose torques are zero) over `h`, both in the velocities
    /// the passes move and in those they started from: what the bodies take at the next
    /// store is then the passes' change alone, the kick being in their momenta already.
    pub(crate) fn kick_loaded(&mut self, bodies: &[MovingBody], wrenches: &[Wrench], h: f64) {
        let n = self.layout.n;
        let stride = n + self.layout.m;
        for (i, ((st, b), w)) in self.states.iter().zip(bodies).zip(wrenches).enumerate() {
            if !st.used || b.is_fixed() {
                continue;
            }
            let here = i * stride..i * stride + n;
            let f = w.force.as_slice();
            for (k, (v, v0)) in self.flat.vel[here.clone()]
                .iter_mut()
                .zip(&mut self.flat.start[here])
                .enumerate()
            {
                let dv = h * f[k] * st.inv_mass;
                *v += dv;
                *v0 += dv;
            }
        }
    }

    /// Records the step's contacts in `log`: each row that gave an impulse or ends the
    /// step overlapping, with the impulses summed over the substeps, at the bodies'
    /// placement at the end of the step (as [`Self::moved`] left it). The rows with
    /// half-spaces are the first, in the order of `planes` (which has their points in the
    /// bodies' own axes).
    pub(crate) fn record(&self, planes: &[ContactRow], log: &mut ContactLog) {
        let l = self.layout;
        let n = l.n;
        let mut point = Vector::zero(n);
        let mut normal = Vector::zero(n);
        let mut friction = Vector::zero(n);
        let mut slip = Vector::zero(n);
        for (k, row) in self.rows.iter().enumerate() {
            if row.total_normal_impulse == 0.0 && self.separations[k] > 0.0 {
                continue;
            }
            let d = numbers(&self.data, row, &l);
            let c = &self.cold[k * l.cold_stride..(k + 1) * l.cold_stride];
            let f = friction.as_mut_slice();
            let u = slip.as_mut_slice();
            f.fill(0.0);
            u.fill(0.0);
            for t in 0..n - 1 {
                let (dir, arms) = l.tangent(t);
                let (along, vt) = (
                    c[l.total_tangent + t],
                    row_velocity::<0>(&self.flat, row, d, &l, (dir, arms)),
                );
                for i in 0..n {
                    f[i] += along * d[dir + i];
                    u[i] += vt * d[dir + i];
                }
            }
            let nrm = &d[l.normal..l.normal + n];
            if row.a == NO_BODY {
                let found = &planes[k];
                log.record(
                    (found.body, found.half_space),
                    &found.point.as_slice()[..n],
                    row.total_normal_impulse,
                    f,
                    u,
                    nrm,
                );
                continue;
            }
            // The point midway between the two material points, as detection gives it.
            let p = point.as_mut_slice();
            p.fill(0.0);
            for (body, own) in [(row.a, l.own_a), (row.b, l.own_b)] {
                let q = &self.frames[body * n * n..(body + 1) * n * n];
                let x = &self.positions[body * n..(body + 1) * n];
                for i in 0..n {
                    p[i] += 0.5 * (x[i] + dot(&q[i * n..(i + 1) * n], &c[own..own + n]));
                }
            }
            normal.as_mut_slice().copy_from_slice(nrm);
            log.record_pair(
                (row.a, row.b),
                &point,
                &normal,
                row.total_normal_impulse,
                &friction,
            );
        }
    }

    fn relax_n<const N: usize>(&mut self, h: f64, (speed, passes): (f64, usize), last: bool) {
        for _ in 0..passes {
            self.pass::<N>(h, None, 0.0);
        }
        if last {
            self.restitution::<N>(speed);
        }
        // Each substep gives the bodies its rows' accumulated impulses (the warm start and
        // the passes' changes): the step's impulse of a row is their sum.
        let l = layout::<N>(&self.layout);
        let t = dim::<N>(l.n) - 1;
        for (row, c) in self
            .rows
            .iter_mut()
            .zip(self.cold.chunks_exact_mut(l.cold_stride))
        {
            row.total_normal_impulse += row.normal_impulse;
            let d = &self.data[row.at + l.tangent_impulse..row.at + l.tangent_impulse + t];
            for (total, x) in c[l.total_tangent..l.total_tangent + t].iter_mut().zip(d) {
                *total += x;
            }
        }
    }

    /// The current separation of row `k` from the bodies' positions and attitudes.
    #[inline(always)]
    fn separation<const N: usize>(&self, k: usize) -> f64 {
        let l = layout::<N>(&self.layout);
        let n = dim::<N>(l.n);
        let row = &self.rows[k];
        let nrm = &self.data[row.at + l.normal..row.at + l.normal + n];
        let c = &self.cold[k * l.cold_stride..(k + 1) * l.cold_stride];
        let mut s = row.gap;
        for (sign, body, offset, own) in [(-1.0, row.a, l.ra, l.own_a), (1.0, row.b, l.rb, l.own_b)]
        {
            if body == NO_BODY {
                continue;
            }
            let q = &self.frames[body * n * n..(body + 1) * n * n];
            let x0 = &self.start[body * n..(body + 1) * n];
            let x = &self.positions[body * n..(body + 1) * n];
            let (own, offset) = (&c[own..own + n], &c[offset..offset + n]);
            let mut moved = 0.0;
            for i in 0..n {
                let r_now: f64 = dot(&q[i * n..(i + 1) * n], own);
                moved += nrm[i] * (x[i] - x0[i] + r_now - offset[i]);
            }
            s += sign * moved;
        }
        s
    }

    /// One Gauss–Seidel pass over the rows: with `soft` the springs push overlaps out (at
    /// most at `push_out`), without only speculative gaps bias the velocities.
    fn pass<const N: usize>(&mut self, h: f64, soft: Option<(Softness, Softness)>, push_out: f64) {
        // The points of one manifold (consecutive rows of one pair) update copies of the
        // pair's two velocities, written back once: each update waits for the last one's,
        // and in 3D and 4D the copies are arrays the compiler keeps in registers, with no
        // store and load between two updates.
        let bias = (h, soft, push_out);
        match N {
            3 => self.pass_with::<N, [f64; 6]>(bias, || [0.0; 6]),
            4 => self.pass_with::<N, [f64; 10]>(bias, || [0.0; 10]),
            _ => {
                let stride = self.layout.n + self.layout.m;
                self.pass_with::<N, SmallVec<[f64; 36]>>(bias, || SmallVec::from_elem(0.0, stride))
            }
        }
    }

    /// [`Self::pass`] with the pair's velocities in copies made by `room` (N + M each).
    #[inline(always)]
    fn pass_with<const N: usize, V: AsRef<[f64]> + AsMut<[f64]>>(
        &mut self,
        bias: (f64, Option<(Softness, Softness)>, f64),
        room: impl Fn() -> V,
    ) {
        let l = layout::<N>(&self.layout);
        let stride = dim::<N>(l.n) + l.m;
        let SoftSolver {
            rows,
            data,
            flat,
            scratch,
            separations,
            ..
        } = self;
        // The points of a manifold take their normal impulses first and then their
        // friction, as in Box2D: friction then answers the normal impulses of the whole
        // face, not of the points before it.
        let mut start = 0;
        while start < rows.len() {
            let end = run_end(rows, start);
            let first = (rows[start].a, rows[start].b);
            // Each update waits on the last one's velocities: with the next manifold when
            // they share no body (two boxes on the floor, say), the two are updated in
            // turn, point by point, so that the processor works on both chains at once. As
            // their bodies differ, the result is that of one manifold after the other, to
            // the bit.
            let second = (end < rows.len())
                .then(|| (rows[end].a, rows[end].b))
                .filter(|&p| apart(first, p));
            let end2 = second.map_or(end, |_| run_end(rows, end));
            let mut one = Ends::copy(flat, first, stride, (room(), room()));
            let mut two = second.map(|p| Ends::copy(flat, p, stride, (room(), room())));
            let longer = (end - start).max(end2 - end);
            for i in 0..longer {
                let (k, k2) = (start + i, end + i);
                if k < end {
                    let d = numbers(data, &rows[k], &l);
                    normal_update::<N, V>(&mut rows[k], d, &l, &mut one, separations[k], bias);
                }
                if let (true, Some(two)) = (k2 < end2, two.as_mut()) {
                    let d = numbers(data, &rows[k2], &l);
                    normal_update::<N, V>(&mut rows[k2], d, &l, two, separations[k2], bias);
                }
            }
            for i in 0..longer {
                let (k, k2) = (start + i, end + i);
                if k < end {
                    let d = numbers_mut(data, &rows[k], &l);
                    friction_update::<N, V>(&rows[k], d, &l, &mut one, scratch);
                }
                if let (true, Some(two)) = (k2 < end2, two.as_mut()) {
                    let d = numbers_mut(data, &rows[k2], &l);
                    friction_update::<N, V>(&rows[k2], d, &l, two, scratch);
                }
            }
            one.write_back(flat, first);
            if let (Some(two), Some(second)) = (&two, second) {
                two.write_back(flat, second);
            }
            start = end2;
        }
    }

    /// Restitution: each row that approached faster than `threshold` before the step and
    /// carried an impulse leaves at e times its approach speed (or faster).
    fn restitution<const N: usize>(&mut self, threshold: f64) {
        let l = layout::<N>(&self.layout);
        for k in 0..self.rows.len() {
            let row = &mut self.rows[k];
            if row.restitution == 0.0 || row.approach > -threshold || row.max_normal_impulse == 0.0
            {
                continue;
            }
            let d = numbers(&self.data, row, &l);
            let mut pair = Ends::of(&mut self.flat, (row.a, row.b), l.n + l.m);
            let vn = pair.velocity::<N>(d, &l, l.normal, l.arms);
            let impulse = -row.normal_mass * (vn + row.restitution * row.approach);
            let new = (row.normal_impulse + impulse).max(0.0);
            let change = new - row.normal_impulse;
            row.normal_impulse = new;
            pair.apply::<N>(d, &l, l.normal, l.arms, change);
        }
    }
}

/// The end of the run of rows of the pair of the row `start` (a manifold).
#[inline(always)]
fn run_end(rows: &[SoftRow], start: usize) -> usize {
    start + run_len(&rows[start..], |r| (r.a, r.b))
}

/// True if the rows of the pairs `p` and `q` move no body in common (a half-space,
/// [`NO_BODY`], is none).
#[inline(always)]
fn apart(p: (usize, usize), q: (usize, usize)) -> bool {
    let shared = |i: usize| i != NO_BODY && (i == q.0 || i == q.1);
    !shared(p.0) && !shared(p.1)
}

/// Sets the arms c = r ∧ e and w = I⁻¹ c of both ends of a row for the direction at `dir`
/// in its vectors `d` (c_b, w_b at `arms`, c_a, w_a [`Layout::a_arms`] further on), its
/// offsets r in `cold`, and returns eᵀ K e.
#[inline(always)]
fn set_arms<const N: usize>(
    states: &[BodyState],
    bodies: &[MovingBody],
    (a, b): (usize, usize),
    (d, cold): (&mut [f64], &[f64]),
    l: &Layout,
    dir: usize,
    arms: usize,
) -> f64 {
    let n = dim::<N>(l.n);
    let m = n * (n - 1) / 2;
    let mut kk = 0.0;
    for (side, body, offset) in [(0, a, l.ra), (1, b, l.rb)] {
        if body == NO_BODY || bodies[body].is_fixed() {
            continue;
        }
        let st = &states[body];
        let c = if side == 0 { arms + l.a_arms } else { arms };
        let w = c + m;
        // c = r ∧ e, in the order of the planes (i < j), and w = I⁻¹ c.
        let mut p = c;
        for i in 0..n {
            for j in i + 1..n {
                d[p] = cold[offset + i] * d[dir + j] - cold[offset + j] * d[dir + i];
                p += 1;
            }
        }
        for (i, row) in st.inv_inertia[..m * m].chunks_exact(m).enumerate() {
            d[w + i] = dot(row, &d[c..c + m]);
        }
        kk += st.inv_mass + dot(&d[c..c + m], &d[w..w + m]);
    }
    kk
}

/// The normal update of a row with vectors `d` and separation `s` (see
/// [`SoftSolver::pass`]): `(h, soft, push_out)` as there.
#[inline(always)]
fn normal_update<const N: usize, V: AsRef<[f64]> + AsMut<[f64]>>(
    row: &mut SoftRow,
    d: &[f64],
    l: &Layout,
    pair: &mut Ends<V>,
    s: f64,
    (h, soft, push_out): (f64, Option<(Softness, Softness)>, f64),
) {
    let (mut bias, mut mass_scale, mut impulse_scale) = (0.0, 1.0, 0.0);
    if s > 0.0 {
        bias = s / h;
    } else if let Some((between, against_fixed)) = soft {
        let sp = if row.fixed { against_fixed } else { between };
        bias = (sp.bias_rate * s).max(-push_out);
        mass_scale = sp.mass_scale;
        impulse_scale = sp.impulse_scale;
    }
    let vn = pair.velocity::<N>(d, l, l.normal, l.arms);
    let impulse = -row.normal_mass * mass_scale * (vn + bias) - impulse_scale * row.normal_impulse;
    let new = (row.normal_impulse + impulse).max(0.0);
    let change = new - row.normal_impulse;
    row.normal_impulse = new;
    row.max_normal_impulse = row.max_normal_impulse.max(new);
    pair.apply::<N>(d, l, l.normal, l.arms, change);
}

/// The friction update of a row with vectors `d`: each tangent direction's sticking
/// update, then the projection onto the disc |J_t| ≤ μλ (`scratch` as
/// [`SoftSolver::scratch`]).
#[inline(always)]
fn friction_update<const N: usize, V: AsRef<[f64]> + AsMut<[f64]>>(
    row: &SoftRow,
    d: &mut [f64],
    l: &Layout,
    pair: &mut Ends<V>,
    scratch: &mut [f64],
) {
    let n = dim::<N>(l.n);
    let limit = row.friction * row.normal_impulse;
    let (total, rest) = scratch.split_at_mut(n);
    if limit == 0.0 {
        // A point without normal impulse (a speculative point, or no friction) holds no
        // friction: its velocities and the disc's square root and division are not needed.
        total[..n - 1].fill(0.0);
    } else {
        for t in 0..n - 1 {
            let (dir, arms) = l.tangent(t);
            let vt = pair.velocity::<N>(d, l, dir, arms);
            total[t] = d[l.tangent_impulse + t] - d[l.tangent_mass + t] * vt;
        }
        // The square root only for a point that slides (a sticking point stays inside).
        let squared = total[..n - 1].iter().map(|x| x * x).sum::<f64>();
        if squared > limit * limit {
            let scale = limit / squared.sqrt();
            total[..n - 1].iter_mut().for_each(|x| *x *= scale);
        }
    }
    // The changes along the tangents summed, then given to the bodies at once.
    let mut fixed = [0.0; 16];
    let sum = sum_room::<N>(&mut fixed, rest, l);
    let mut any = false;
    for t in 0..n - 1 {
        let change = total[t] - d[l.tangent_impulse + t];
        any |= add_impulse::<N>(sum, d, l, l.tangent(t), pair.has_a, change);
        d[l.tangent_impulse + t] = total[t];
    }
    if any {
        let m = n * (n - 1) / 2;
        let (e, w) = sum[..n + 2 * m].split_at(n);
        pair.give::<N>((e, w.split_at(m)), 1.0);
    }
}

/// Room for the sum of a row's impulses ([`add_impulse`]): the impulse in space (N), then
/// the changes of the two ends' angular velocities (M each), zeroed. On the stack in 3D and
/// 4D, else in `any`; `N` as in [`dim`].
#[inline(always)]
fn sum_room<'a, const N: usize>(
    fixed: &'a mut [f64; 16],
    any: &'a mut [f64],
    l: &Layout,
) -> &'a mut [f64] {
    let n = dim::<N>(l.n);
    let len = n + n * (n - 1);
    let room = if N != 0 {
        &mut fixed[..len]
    } else {
        &mut any[..len]
    };
    room.fill(0.0);
    room
}

/// Adds the impulse λ e (e at `dir` in the row's vectors `d`, its b arms at `arms`) to
/// `sum` ([`sum_room`]): λ e, then λ w_a (if the row has a body a) and λ w_b. Returns
/// whether λ ≠ 0.
#[inline(always)]
fn add_impulse<const N: usize>(
    sum: &mut [f64],
    d: &[f64],
    l: &Layout,
    (dir, arms): (usize, usize),
    has_a: bool,
    lambda: f64,
) -> bool {
    if lambda == 0.0 {
        return false;
    }
    let n = dim::<N>(l.n);
    let m = n * (n - 1) / 2;
    let (linear, angular) = sum[..n + 2 * m].split_at_mut(n);
    for (s, e) in linear.iter_mut().zip(&d[dir..dir + n]) {
        *s += lambda * e;
    }
    let (to_a, to_b) = angular.split_at_mut(m);
    for (s, w) in to_b.iter_mut().zip(&d[arms + m..arms + 2 * m]) {
        *s += lambda * w;
    }
    if has_a {
        let wa = arms + l.a_arms + m;
        for (s, w) in to_a.iter_mut().zip(&d[wa..wa + m]) {
            *s += lambda * w;
        }
    }
    true
}

/// The relative velocity of a row's two points along the direction at `dir` in its vectors
/// `d`, whose b arms start at `arms` (c_b, w_b; c_a, w_a [`Layout::a_arms`] further on),
/// given the bodies' velocities (v,
/// then ω in space; none for a half-space); `N` as in [`dim`].
#[inline(always)]
fn point_velocity<const N: usize>(
    (xa, xb): (Option<&[f64]>, &[f64]),
    d: &[f64],
    l: &Layout,
    (dir, arms): (usize, usize),
) -> f64 {
    let n = dim::<N>(l.n);
    let m = n * (n - 1) / 2;
    let e = &d[dir..dir + n];
    let xb = &xb[..n + m];
    let mut u = dot(e, &xb[..n]) + dot(&d[arms..arms + m], &xb[n..]);
    if let Some(xa) = xa {
        let xa = &xa[..n + m];
        let ca = arms + l.a_arms;
        u -= dot(e, &xa[..n]) + dot(&d[ca..ca + m], &xa[n..]);
    }
    u
}

/// [`point_velocity`] of row `row` with the bodies' velocities in `flat`.
fn row_velocity<const N: usize>(
    flat: &Flat,
    row: &SoftRow,
    d: &[f64],
    l: &Layout,
    at: (usize, usize),
) -> f64 {
    let stride = l.n + l.m;
    let body = |i: usize| &flat.vel[i * stride..(i + 1) * stride];
    let xa = (row.a != NO_BODY).then(|| body(row.a));
    point_velocity::<N>((xa, body(row.b)), d, l, at)
}

/// The velocities (v, then ω in space: N + M each) of a row's two bodies, as its updates
/// read and change them (slices of [`Flat`], or copies of them), and the bodies' inverse
/// masses (0 for a half-space or a fixed body, which take no impulse).
struct Ends<V> {
    a: V,
    b: V,
    has_a: bool,
    inv_mass: (f64, f64),
}

impl<'a> Ends<&'a mut [f64]> {
    /// The bodies `(a, b)`'s velocities in `flat` itself (`stride` = N + M).
    fn of(flat: &'a mut Flat, (a, b): (usize, usize), stride: usize) -> Self {
        let inv_mass = (
            if a == NO_BODY { 0.0 } else { flat.inv_mass[a] },
            flat.inv_mass[b],
        );
        let vel = &mut flat.vel[..];
        let (va, vb): (&mut [f64], &mut [f64]) = if a == NO_BODY {
            (&mut [], &mut vel[b * stride..(b + 1) * stride])
        } else if a < b {
            let (low, high) = vel.split_at_mut(b * stride);
            (&mut low[a * stride..(a + 1) * stride], &mut high[..stride])
        } else {
            let (low, high) = vel.split_at_mut(a * stride);
            (&mut high[..stride], &mut low[b * stride..(b + 1) * stride])
        };
        Ends {
            a: va,
            b: vb,
            has_a: a != NO_BODY,
            inv_mass,
        }
    }
}

impl<V: AsRef<[f64]> + AsMut<[f64]>> Ends<V> {
    /// Copies of the bodies `(a, b)`'s velocities in `room` (`stride` = N + M each), to
    /// write back with [`Ends::write_back`].
    #[inline(always)]
    fn copy(flat: &Flat, (a, b): (usize, usize), stride: usize, mut room: (V, V)) -> Self {
        if a != NO_BODY {
            room.0
                .as_mut()
                .copy_from_slice(&flat.vel[a * stride..(a + 1) * stride]);
        }
        room.1
            .as_mut()
            .copy_from_slice(&flat.vel[b * stride..(b + 1) * stride]);
        Ends {
            a: room.0,
            b: room.1,
            has_a: a != NO_BODY,
            inv_mass: (
                if a == NO_BODY { 0.0 } else { flat.inv_mass[a] },
                flat.inv_mass[b],
            ),
        }
    }

    /// Writes the copies of [`Ends::copy`] back to the bodies that can move.
    #[inline(always)]
    fn write_back(&self, flat: &mut Flat, (a, b): (usize, usize)) {
        let stride = self.b.as_ref().len();
        if self.inv_mass.0 != 0.0 {
            flat.vel[a * stride..(a + 1) * stride].copy_from_slice(self.a.as_ref());
        }
        if self.inv_mass.1 != 0.0 {
            flat.vel[b * stride..(b + 1) * stride].copy_from_slice(self.b.as_ref());
        }
    }

    /// The relative velocity of the row's two points along the direction at `dir` in its
    /// vectors `d`, whose b arms start at `arms`; `N` as in [`dim`].
    #[inline(always)]
    fn velocity<const N: usize>(&self, d: &[f64], l: &Layout, dir: usize, arms: usize) -> f64 {
        let xa = self.has_a.then_some(self.a.as_ref());
        point_velocity::<N>((xa, self.b.as_ref()), d, l, (dir, arms))
    }

    /// Gives body b the impulse λ e at its point and body a the opposite (e at `dir` in
    /// the row's vectors `d`, its b arms at `arms`); `N` as in [`dim`].
    #[inline(always)]
    fn apply<const N: usize>(
        &mut self,
        d: &[f64],
        l: &Layout,
        dir: usize,
        arms: usize,
        lambda: f64,
    ) {
        if lambda == 0.0 {
            return;
        }
        let n = dim::<N>(l.n);
        let m = n * (n - 1) / 2;
        let wb = &d[arms + m..arms + 2 * m];
        // A half-space's row has no a arms (and no body a to give them to).
        let wa = if self.has_a {
            &d[arms + l.a_arms + m..arms + l.a_arms + 2 * m]
        } else {
            &[]
        };
        self.give::<N>((&d[dir..dir + n], (wa, wb)), lambda);
    }

    /// Gives body b the impulse λ e and the angular velocities λ w_b, body a the opposite
    /// (`e` and `w` = (w_a, w_b), M each; w_a is read only if body a moves); `N` as in
    /// [`dim`].
    #[inline(always)]
    fn give<const N: usize>(&mut self, (e, (wa, wb)): (&[f64], (&[f64], &[f64])), lambda: f64) {
        let n = e.len();
        let n = dim::<N>(n);
        let m = n * (n - 1) / 2;
        for (sign, vel, inv_mass, w) in [
            (-1.0, self.a.as_mut(), self.inv_mass.0, wa),
            (1.0, self.b.as_mut(), self.inv_mass.1, wb),
        ] {
            if inv_mass == 0.0 {
                continue;
            }
            let j = sign * lambda;
            let scaled = j * inv_mass;
            let w = &w[..m];
            let vel = &mut vel[..n + m];
            for i in 0..n {
                vel[i] += scaled * e[i];
            }
            for i in 0..m {
                vel[n + i] += j * w[i];
            }
        }
    }
}
