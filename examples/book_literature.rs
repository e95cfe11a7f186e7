//! Work–precision benchmarks from the literature (the book's chapter "Euler's equations as
//! rotor flows"): `cargo run --release --example book_literature` measures and prints the
//! tables; `cargo run --release --example book_literature -- --write` also records the
//! measurements with the date, the commit, the machine and the compiler in
//! `book/src/generated/literature.tsv` and renders `book/src/generated/literature.md` and
//! the plots `book/src/generated/literature_*.svg` from that file and from
//! `book/src/generated/literature_scipy.tsv` (written by `python3
//! scripts/literature_scipy.py --write`: scipy's DOP853 on the same problems, and the
//! high-precision references every error here is measured against). `tests/book.rs`
//! re-renders the committed data and fails when the committed files differ. `--errors`
//! skips the timing and prints the errors and counts alone; `--render` rewrites the tables
//! and plots from the recorded data without measuring.
//!
//! The problems (defined once more, with the same numbers, in the Python script):
//!
//! - `hlw`: the free rigid body of Hairer, Lubich and Wanner, moments of inertia
//!   I = (2, 1, 2/3), body momentum y(0) = (cos 1.1, 0, sin 1.1), to t = 100;
//! - `p4`: the free solid 4D cuboid `cuboid:1,1.3,1.7,2.2` of mass 1 from
//!   ω(0) = (0.3, −0.2, 0.5, 0.1, 0.4, −0.6), to t = 100;
//! - `simo_wong`: the heavy symmetric top of Simo and Wong (1991), to t = 2;
//! - `bruls`: the heavy top of Brüls, Cardona and Arnold (2012), to t = 2;
//! - `free4`, `free6`, `free8`: free N-dimensional bodies, to t = 20, where the error is the
//!   drift of all Manakov integrals.
//!
//! Timing follows `examples/step_ratio.rs`: every setting of every method of a problem runs
//! in alternating rounds (a batch of solves of a few milliseconds per round) and keeps its
//! fastest round, so interference that lasts longer than a round hits all alike.

use nalgebra::{Matrix3, SMatrix, Vector3};
use rotorflow::algebra::Vector;
use rotorflow::dynamics::torques::{Free, Gravity};
use rotorflow::dynamics::{
    Attitude, Dop853, Dopri5, FreeBody3, FreeBody4, Integrator, Invariants, LiePoissonRk4,
    Midpoint, MoserVeselov, ProcessedOrder, ProcessedSplitting, RigidBody, Rkmk4, Splitting,
    SplittingOrder, Torque,
};
use rotorflow::inertia::spec::parse_body;
use rotorflow::prelude::*;
use std::collections::BTreeMap;
use std::error::Error;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

// tests/book.rs compiles this file and other examples that load these modules.
#[allow(clippy::duplicate_mod)]
#[path = "support/log_plot.rs"]
mod log_plot;
#[allow(clippy::duplicate_mod)]
#[path = "support/provenance.rs"]
mod provenance;
use log_plot::LogPlot;

type Res<T> = Result<T, Box<dyn Error>>;

/// The problems, in the order of the tables.
pub const PROBLEMS: [&str; 7] = ["hlw", "simo_wong", "bruls", "p4", "free4", "free6", "free8"];

/// The accuracies at which the cost of every method is compared.
const TARGETS: [f64; 4] = [1e-4, 1e-6, 1e-8, 1e-11];

/// Alternating rounds per problem; each setting keeps its fastest.
const ROUNDS: usize = 5;

/// The end time of a problem.
fn t_end(problem: &str) -> f64 {
    match problem {
        "hlw" | "p4" => 100.0,
        "simo_wong" | "bruls" => 2.0,
        _ => 20.0,
    }
}

/// The second moments of the free N-dimensional bodies: Jₖ = 0.5 + 0.25k.
fn free_second_moments(n: usize) -> Vec<f64> {
    (0..n).map(|k| 0.5 + 0.25 * k as f64).collect()
}

/// The 3D bivector of a classical vector: v₁₂ = v₃, v₁₃ = −v₂, v₂₃ = v₁.
fn bivector_of(v: [f64; 3]) -> Res<Bivector> {
    Ok(Bivector::from_components(3, &[v[2], -v[1], v[0]])?)
}

/// The classical vector of a 3D bivector.
fn vector_of(b: &Bivector) -> [f64; 3] {
    [b.get(1, 2), -b.get(0, 2), b.get(0, 1)]
}

/// A heavy top: the inertia about the pivot (moments of inertia), the weight, the centre of
/// mass in the body, the initial attitude's angle about e₁ and the body angular velocity.
struct TopSpec {
    moments: [f64; 3],
    weight: f64,
    offset: [f64; 3],
    tilt: f64,
    omega: [f64; 3],
}

fn top_spec(problem: &str) -> TopSpec {
    if problem == "simo_wong" {
        TopSpec {
            moments: [5.0, 5.0, 1.0],
            weight: 20.0,
            offset: [0.0, 0.0, 1.0],
            tilt: 0.05,
            omega: [0.0, 0.0, 50.0],
        }
    } else {
        // Inertia about the centre of mass diag(0.234375, 0.46875, 0.234375), symmetry axis
        // e₂; the centre of mass at (0, 1, 0) adds m·1² about e₁ and e₃ (parallel axes).
        let m = 15.0;
        TopSpec {
            moments: [0.234375 + m, 0.46875, 0.234375 + m],
            weight: m * 9.81,
            offset: [0.0, 1.0, 0.0],
            tilt: 0.0,
            omega: [0.0, 150.0, -4.61538],
        }
    }
}

/// The body and the torque of a problem.
fn setup(problem: &str) -> Res<(RigidBody, Option<Gravity>)> {
    match problem {
        "hlw" => {
            let inertia = InertiaMap::from_classical_3d([2.0, 1.0, 2.0 / 3.0])?;
            let y0 = bivector_of([1.1f64.cos(), 0.0, 1.1f64.sin()])?;
            Ok((
                RigidBody::from_body_momentum(inertia, Rotor::identity(3), &y0)?,
                None,
            ))
        }
        "p4" => {
            let parsed = parse_body("cuboid:1,1.3,1.7,2.2+mass=1")?;
            let omega = Bivector::from_components(4, &[0.3, -0.2, 0.5, 0.1, 0.4, -0.6])?;
            Ok((
                RigidBody::from_body_velocity(parsed.inertia, Attitude::identity(4), &omega)?,
                None,
            ))
        }
        "simo_wong" | "bruls" => {
            let s = top_spec(problem);
            let inertia = InertiaMap::from_principal_moments_of_inertia_3d(s.moments)?;
            let tilt = Rotor::from_plane_angle(3, 1, 2, s.tilt)?;
            let body = RigidBody::from_body_velocity(inertia, tilt, &bivector_of(s.omega)?)?;
            let frame = body.principal_frame().to_matrix();
            if (frame - nalgebra::DMatrix::identity(3, 3)).abs().max() > 1e-15 {
                return Err("the top's principal frame is not its body frame".into());
            }
            let gravity = Gravity {
                weight: Vector::from_components(&[0.0, 0.0, -s.weight])?,
                offset: Vector::from_components(&s.offset)?,
            };
            Ok((body, Some(gravity)))
        }
        _ => {
            let n: usize = problem.trim_start_matches("free").parse()?;
            let l: Vec<f64> = (0..n * (n - 1) / 2)
                .map(|k| (0.7 * k as f64 + 0.3).sin())
                .collect();
            let inertia = InertiaMap::from_principal_second_moments(&free_second_moments(n))?;
            Ok((
                RigidBody::from_body_momentum(
                    inertia,
                    Attitude::identity(n),
                    &Bivector::from_components(n, &l)?,
                )?,
                None,
            ))
        }
    }
}

/// What a problem's error is measured on: y = L for `hlw` (classical vector), ω for `p4`,
/// the classical body angular velocity for the tops, L for the free N-D bodies.
fn observe(problem: &str, body: &RigidBody) -> Vec<f64> {
    match problem {
        "hlw" => vector_of(body.momentum()).to_vec(),
        "p4" => body.omega().as_slice().to_vec(),
        "simo_wong" | "bruls" => vector_of(&body.omega()).to_vec(),
        _ => body.momentum().as_slice().to_vec(),
    }
}

/// The references of the problems that have one, from the scipy data file (`ref` lines):
/// the observed quantity at the end.
fn references(scipy: &str) -> Res<BTreeMap<String, Vec<f64>>> {
    let mut out = BTreeMap::new();
    for line in scipy.lines() {
        let f: Vec<&str> = line.split('\t').collect();
        if f[0] == "ref" && f.len() == 3 {
            let v: Vec<f64> = f[2]
                .split(',')
                .map(|x| x.trim().parse())
                .collect::<Result<_, _>>()?;
            // The tops' references carry R (9) before Ω (3).
            let v = if v.len() == 12 { v[9..].to_vec() } else { v };
            out.insert(f[1].to_string(), v);
        }
    }
    Ok(out)
}

/// The error of an observation: the largest component of the difference from the reference
/// (relative to the reference's largest component for the tops, whose ω is large), or for
/// the free N-D bodies the largest relative drift of the Manakov integrals.
fn error_of(problem: &str, observed: &[f64], refs: &BTreeMap<String, Vec<f64>>) -> Res<f64> {
    if problem.starts_with("free") {
        let (start, _) = setup(problem)?;
        let n = start.dim();
        let end = RigidBody::from_body_momentum(
            start.inertia().clone(),
            Attitude::identity(n),
            &Bivector::from_components(n, observed)?,
        )?;
        let drifts = Invariants::of(&end).manakov_drifts(&Invariants::of(&start));
        if drifts.is_empty() {
            return Err("no Manakov integrals".into());
        }
        return Ok(drifts.into_iter().fold(0.0, f64::max));
    }
    let r = refs
        .get(problem)
        .ok_or_else(|| format!("no reference for {problem}"))?;
    if r.len() != observed.len() {
        return Err(format!("{problem}: reference of length {}", r.len()).into());
    }
    let diff = r
        .iter()
        .zip(observed)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    let scale = if problem == "simo_wong" || problem == "bruls" {
        r.iter().map(|x| x.abs()).fold(0.0, f64::max)
    } else {
        1.0
    };
    Ok(diff / scale)
}

// ---------------------------------------------------------------------------------------
// The baselines written here: plain RK4 on nalgebra's fixed-size types, and RK4 on ω of the
// 4D free body unrolled by hand on arrays.

/// RK4 for y' = f(y) on any state with the vector-space operations.
fn rk4<S>(y: &S, h: f64, f: impl Fn(&S) -> S) -> S
where
    S: Clone + std::ops::Add<Output = S> + std::ops::Mul<f64, Output = S>,
{
    let k1 = f(y);
    let k2 = f(&(y.clone() + k1.clone() * (0.5 * h)));
    let k3 = f(&(y.clone() + k2.clone() * (0.5 * h)));
    let k4 = f(&(y.clone() + k3.clone() * h));
    y.clone() + (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0)
}

/// Euler's equations of the HLW body on a `Vector3`: y' = y × I⁻¹y.
fn nalgebra_hlw(h: f64, steps: usize) -> Vec<f64> {
    let inv = Vector3::new(0.5, 1.0, 1.5);
    let mut y = Vector3::new(1.1f64.cos(), 0.0, 1.1f64.sin());
    for _ in 0..steps {
        y = rk4(&y, h, |y| y.cross(&y.component_mul(&inv)));
    }
    y.as_slice().to_vec()
}

/// The free N-D body on `SMatrix<f64, N, N>`: d[L]/dt = [ω][L] − [L][ω], [ω] = [L] ⊘ P with
/// Pᵢⱼ = Jᵢ + Jⱼ. Returns ω (for `p4`) or L.
fn nalgebra_free<const N: usize>(
    j: &[f64],
    l0: &[f64],
    h: f64,
    steps: usize,
    want_omega: bool,
) -> Vec<f64> {
    let p = SMatrix::<f64, N, N>::from_fn(|r, c| j[r] + j[c]);
    let mut l = SMatrix::<f64, N, N>::zeros();
    let mut k = 0;
    for r in 0..N {
        for c in r + 1..N {
            l[(r, c)] = l0[k];
            l[(c, r)] = -l0[k];
            k += 1;
        }
    }
    let f = |l: &SMatrix<f64, N, N>| {
        let w = l.component_div(&p);
        w * l - l * w
    };
    for _ in 0..steps {
        l = rk4(&l, h, f);
    }
    let out = if want_omega { l.component_div(&p) } else { l };
    let mut v = Vec::with_capacity(N * (N - 1) / 2);
    for r in 0..N {
        for c in r + 1..N {
            v.push(out[(r, c)]);
        }
    }
    v
}

/// A heavy top on `Matrix3` and `Vector3`: R' = R Ω̂, IΩ' = IΩ × Ω + X × Rᵀ(m g).
#[derive(Clone)]
struct TopState(Matrix3<f64>, Vector3<f64>);

impl std::ops::Add for TopState {
    type Output = TopState;
    fn add(self, o: TopState) -> TopState {
        TopState(self.0 + o.0, self.1 + o.1)
    }
}

impl std::ops::Mul<f64> for TopState {
    type Output = TopState;
    fn mul(self, s: f64) -> TopState {
        TopState(self.0 * s, self.1 * s)
    }
}

fn nalgebra_top(problem: &str, h: f64, steps: usize) -> Vec<f64> {
    let s = top_spec(problem);
    let inertia = Vector3::from(s.moments);
    let offset = Vector3::from(s.offset);
    let force = Vector3::new(0.0, 0.0, -s.weight);
    let (c, sn) = (s.tilt.cos(), s.tilt.sin());
    let r0 = Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -sn, 0.0, sn, c);
    let mut y = TopState(r0, Vector3::from(s.omega));
    let f = |y: &TopState| {
        let w = y.1;
        let torque = offset.cross(&(y.0.transpose() * force));
        TopState(
            y.0 * w.cross_matrix(),
            (inertia.component_mul(&w).cross(&w) + torque).component_div(&inertia),
        )
    };
    for _ in 0..steps {
        y = rk4(&y, h, f);
    }
    y.1.as_slice().to_vec()
}

/// RK4 on ω of the free 4D body, unrolled by hand: ω̇ᵢⱼ = Σ ωᵢₖωₖⱼ (Iₐ − I_b)/Iᵢⱼ written out
/// for the six planes (12, 13, 14, 23, 24, 34), twelve products per right-hand side.
fn unrolled_rk4_4d(plane: [f64; 6], w0: [f64; 6], h: f64, steps: usize) -> [f64; 6] {
    let i = plane;
    let c = [
        (i[1] - i[3]) / i[0],
        (i[2] - i[4]) / i[0],
        (i[3] - i[0]) / i[1],
        (i[2] - i[5]) / i[1],
        (i[4] - i[0]) / i[2],
        (i[5] - i[1]) / i[2],
        (i[0] - i[1]) / i[3],
        (i[4] - i[5]) / i[3],
        (i[0] - i[2]) / i[4],
        (i[5] - i[3]) / i[4],
        (i[1] - i[2]) / i[5],
        (i[3] - i[4]) / i[5],
    ];
    let f = |w: &[f64; 6]| {
        [
            c[0] * w[1] * w[3] + c[1] * w[2] * w[4],
            c[2] * w[0] * w[3] + c[3] * w[2] * w[5],
            c[4] * w[0] * w[4] + c[5] * w[1] * w[5],
            c[6] * w[0] * w[1] + c[7] * w[4] * w[5],
            c[8] * w[0] * w[2] + c[9] * w[3] * w[5],
            c[10] * w[1] * w[2] + c[11] * w[3] * w[4],
        ]
    };
    let mut w = w0;
    for _ in 0..steps {
        let k1 = f(&w);
        let k2 = f(&std::array::from_fn(|k| w[k] + 0.5 * h * k1[k]));
        let k3 = f(&std::array::from_fn(|k| w[k] + 0.5 * h * k2[k]));
        let k4 = f(&std::array::from_fn(|k| w[k] + h * k3[k]));
        for k in 0..6 {
            w[k] += h / 6.0 * (k1[k] + 2.0 * k2[k] + 2.0 * k3[k] + k4[k]);
        }
    }
    w
}

// ---------------------------------------------------------------------------------------
// The measurements.

/// One solve: the observation, the steps and the right-hand sides (0 where a method has
/// none to count, the splittings).
type Solve = Box<dyn Fn() -> Res<(Vec<f64>, usize, usize)>>;

/// A run that records the largest relative drifts of the energy and the momenta.
type Drifts = Box<dyn Fn() -> Res<(f64, f64)>>;

/// One setting of one method: how to run it, and its label in the data file.
struct Setting {
    method: &'static str,
    setting: String,
    /// Runs one solve; returns the observation, the steps and the right-hand sides (0 where
    /// a method has none to count, the splittings).
    run: Solve,
    /// Records the largest relative drift of the energy (T + V) and of the conserved momenta
    /// over the run, for the heavy tops' fixed steps.
    drifts: Option<Drifts>,
}

/// A fixed-step run of a rotorflow integrator.
fn fixed_run(
    problem: &'static str,
    make: fn() -> Box<dyn Integrator>,
    h: f64,
    stages: usize,
) -> Res<Solve> {
    let steps = (t_end(problem) / h).round() as usize;
    let (start, gravity) = setup(problem)?;
    Ok(Box::new(move || {
        let mut body = start.clone();
        let mut integ = make();
        let torque: &dyn Torque = match &gravity {
            Some(g) => g,
            None => &Free,
        };
        for k in 0..steps {
            integ.step(&mut body, k as f64 * h, h, torque)?;
        }
        Ok((observe(problem, &body), steps, stages * steps))
    }))
}

/// The drifts of T + V and of the two momenta a symmetric heavy top keeps (the space-frame
/// component about the vertical and the body-frame component about the axis of symmetry),
/// step by step, for a fixed-step rotorflow integrator.
fn top_drifts(problem: &'static str, make: fn() -> Box<dyn Integrator>, h: f64) -> Res<Drifts> {
    let steps = (t_end(problem) / h).round() as usize;
    let (start, gravity) = setup(problem)?;
    let gravity = gravity.ok_or("a top needs gravity")?;
    // The symmetry axis: e₃ for Simo–Wong (the plane e₁₂), e₂ for Brüls (the plane e₁₃).
    let axial = if problem == "simo_wong" {
        (0, 1)
    } else {
        (0, 2)
    };
    Ok(Box::new(move || {
        let total =
            |b: &RigidBody| b.energy() + gravity.potential_energy(b.principal_frame_attitude());
        let momenta = |b: &RigidBody| {
            [
                b.space_momentum().get(0, 1),
                b.momentum().get(axial.0, axial.1),
            ]
        };
        let (e0, m0) = (total(&start), momenta(&start));
        let scale = start.momentum().norm();
        let mut body = start.clone();
        let mut integ = make();
        let (mut de, mut dm) = (0.0f64, 0.0f64);
        for k in 0..steps {
            integ.step(&mut body, k as f64 * h, h, &gravity)?;
            de = de.max((total(&body) - e0).abs() / e0.abs());
            let m = momenta(&body);
            dm = dm.max((m[0] - m0[0]).abs().max((m[1] - m0[1]).abs()) / scale);
        }
        Ok((de, dm))
    }))
}

/// An adaptive run.
fn adaptive_run(problem: &'static str, eighth: bool, rtol: f64) -> Res<Solve> {
    let (start, gravity) = setup(problem)?;
    let t = t_end(problem);
    Ok(Box::new(move || {
        let mut body = start.clone();
        let torque: &dyn Torque = match &gravity {
            Some(g) => g,
            None => &Free,
        };
        let (steps, rhs) = if eighth {
            let mut d = Dop853::new(rtol, rtol * 1e-2)?.with_max_steps(10_000_000);
            d.step(&mut body, 0.0, t, torque)?;
            (d.accepted_steps(), d.rhs_evaluations())
        } else {
            let mut d = Dopri5::new(rtol, rtol * 1e-2).with_max_steps(10_000_000);
            d.step(&mut body, 0.0, t, torque)?;
            (d.accepted_steps(), d.rhs_evaluations())
        };
        Ok((observe(problem, &body), steps, rhs))
    }))
}

/// The step sizes of a problem's fixed-step sweeps: halvings from the largest. The
/// sixth- and eighth-order compositions start two and four times larger (on the free
/// bodies their largest steps already reach the tightest accuracies).
fn step_sizes(problem: &str, order: usize) -> Vec<f64> {
    let (largest, count) = match problem {
        "hlw" | "p4" => (0.2, if order >= 4 { 8 } else { 13 }),
        "simo_wong" => (0.01, if order >= 4 { 8 } else { 10 }),
        "bruls" => (0.004, if order >= 4 { 9 } else { 10 }),
        _ => (0.8, if order >= 4 { 9 } else { 12 }),
    };
    let free = !matches!(problem, "hlw" | "p4" | "simo_wong" | "bruls");
    let (largest, count) = match order {
        6 if !free => (2.0 * largest, 7),
        8 if !free => (4.0 * largest, 7),
        6 | 8 => (largest, 6),
        _ => (largest, count),
    };
    (0..count).map(|k| largest / f64::powi(2.0, k)).collect()
}

/// The tolerances of the adaptive sweeps (atol = rtol/100).
const TOLERANCES: [f64; 11] = [
    1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13,
];

fn settings(problem: &'static str) -> Res<Vec<Setting>> {
    let mut out = Vec::new();
    let tops = problem == "simo_wong" || problem == "bruls";
    let physical = problem != "hlw" && !tops;
    type Make = fn() -> Box<dyn Integrator>;
    let mut fixed: Vec<(&'static str, Make, usize, usize)> = vec![
        ("rk4", || Box::new(Rkmk4), 4, 4),
        ("strang", || Box::new(Splitting::strang()), 0, 2),
        ("yoshida4", || Box::new(Splitting::yoshida4()), 0, 4),
        ("suzuki4", || Box::new(Splitting::suzuki4()), 0, 4),
        ("kahan_li6", || Box::new(Splitting::kahan_li6()), 0, 6),
        ("kahan_li8", || Box::new(Splitting::kahan_li8()), 0, 8),
        (
            "suzuki4_sym",
            || Box::new(Splitting::suzuki4().with_symmetric_part()),
            0,
            4,
        ),
        (
            "kahan_li8_sym",
            || Box::new(Splitting::kahan_li8().with_symmetric_part()),
            0,
            8,
        ),
        ("midpoint", || Box::new(Midpoint::default()), 0, 2),
        ("lprk4", || Box::new(LiePoissonRk4), 4, 4),
    ];
    if physical {
        fixed.push(("mv", || Box::new(MoserVeselov::new()), 0, 2));
        fixed.push(("mv4", || Box::new(MoserVeselov::yoshida4()), 0, 4));
        fixed.push((
            "mv8",
            || Box::new(MoserVeselov::composed(SplittingOrder::KahanLi8)),
            0,
            8,
        ));
    }
    for (method, make, stages, order) in fixed {
        for h in step_sizes(problem, order) {
            out.push(Setting {
                method,
                setting: format!("h={h}"),
                run: fixed_run(problem, make, h, stages)?,
                drifts: if tops {
                    Some(top_drifts(problem, make, h)?)
                } else {
                    None
                },
            });
        }
    }
    // The processed compositions run whole stretches (the processor once before and once
    // after), on the free bodies.
    if !tops {
        for (method, order) in [
            ("processed6", ProcessedOrder::Six),
            ("processed8", ProcessedOrder::Eight),
        ] {
            let method_order = ProcessedSplitting::new(order).order() as usize;
            for h in step_sizes(problem, method_order) {
                let steps = (t_end(problem) / h).round() as usize;
                let (start, _) = setup(problem)?;
                out.push(Setting {
                    method,
                    setting: format!("h={h}"),
                    run: Box::new(move || {
                        let mut body = start.clone();
                        ProcessedSplitting::new(order).advance(&mut body, h, steps)?;
                        Ok((observe(problem, &body), steps, 0))
                    }),
                    drifts: None,
                });
            }
        }
    }
    for (method, eighth) in [("dopri5", false), ("dop853", true)] {
        for rtol in TOLERANCES {
            out.push(Setting {
                method,
                setting: format!("rtol={rtol:e}"),
                run: adaptive_run(problem, eighth, rtol)?,
                drifts: None,
            });
        }
    }
    // The fixed-size free bodies of rotorflow (3D and 4D, stack arrays).
    if problem == "hlw" || problem == "p4" {
        for (method, strang, order) in [("fixed_rk4", false, 4), ("fixed_strang", true, 2)] {
            for h in step_sizes(problem, order) {
                let steps = (t_end(problem) / h).round() as usize;
                let (start, _) = setup(problem)?;
                let run: Solve = if problem == "hlw" {
                    let b0 = FreeBody3::from_rigid_body(&start)?;
                    Box::new(move || {
                        let mut b = b0;
                        for _ in 0..steps {
                            if strang {
                                b.step_strang(h)
                            } else {
                                b.step_rk4(h)
                            }
                        }
                        let l = b.momentum().to_array();
                        Ok((
                            vec![l[2], -l[1], l[0]],
                            steps,
                            if strang { 0 } else { 4 * steps },
                        ))
                    })
                } else {
                    let b0 = FreeBody4::from_rigid_body(&start)?;
                    Box::new(move || {
                        let mut b = b0;
                        for _ in 0..steps {
                            if strang {
                                b.step_strang(h)
                            } else {
                                b.step_rk4(h)
                            }
                        }
                        Ok((
                            b.omega().to_array().to_vec(),
                            steps,
                            if strang { 0 } else { 4 * steps },
                        ))
                    })
                };
                out.push(Setting {
                    method,
                    setting: format!("h={h}"),
                    run,
                    drifts: None,
                });
            }
        }
    }
    // The adaptive Dormand–Prince 8(5,3) on the fixed-size free bodies: Dop853's steps.
    if problem == "hlw" || problem == "p4" {
        let t = t_end(problem);
        let (start, _) = setup(problem)?;
        for rtol in TOLERANCES {
            let run: Solve = if problem == "hlw" {
                let b0 = FreeBody3::from_rigid_body(&start)?;
                Box::new(move || {
                    let mut b = b0;
                    let stats = b.advance_dop853(t, rtol, rtol * 1e-2)?;
                    let l = b.momentum().to_array();
                    Ok((
                        vec![l[2], -l[1], l[0]],
                        stats.accepted,
                        stats.rhs_evaluations,
                    ))
                })
            } else {
                let b0 = FreeBody4::from_rigid_body(&start)?;
                Box::new(move || {
                    let mut b = b0;
                    let stats = b.advance_dop853(t, rtol, rtol * 1e-2)?;
                    Ok((
                        b.omega().to_array().to_vec(),
                        stats.accepted,
                        stats.rhs_evaluations,
                    ))
                })
            };
            out.push(Setting {
                method: "fixed_dop853",
                setting: format!("rtol={rtol:e}"),
                run,
                drifts: None,
            });
        }
    }
    // The baselines of this file.
    for h in step_sizes(problem, 4) {
        let steps = (t_end(problem) / h).round() as usize;
        let run: Solve = match problem {
            "hlw" => Box::new(move || Ok((nalgebra_hlw(h, steps), steps, 4 * steps))),
            "simo_wong" | "bruls" => {
                Box::new(move || Ok((nalgebra_top(problem, h, steps), steps, 4 * steps)))
            }
            "p4" => {
                let (start, _) = setup(problem)?;
                let j = start
                    .inertia()
                    .principal_second_moments()
                    .ok_or("P4 has second moments")?
                    .to_vec();
                let l0 = start.momentum().as_slice().to_vec();
                Box::new(move || {
                    Ok((
                        nalgebra_free::<4>(&j, &l0, h, steps, true),
                        steps,
                        4 * steps,
                    ))
                })
            }
            _ => {
                let (start, _) = setup(problem)?;
                let j = free_second_moments(start.dim());
                let l0 = start.momentum().as_slice().to_vec();
                match start.dim() {
                    4 => Box::new(move || {
                        Ok((
                            nalgebra_free::<4>(&j, &l0, h, steps, false),
                            steps,
                            4 * steps,
                        ))
                    }),
                    6 => Box::new(move || {
                        Ok((
                            nalgebra_free::<6>(&j, &l0, h, steps, false),
                            steps,
                            4 * steps,
                        ))
                    }),
                    _ => Box::new(move || {
                        Ok((
                            nalgebra_free::<8>(&j, &l0, h, steps, false),
                            steps,
                            4 * steps,
                        ))
                    }),
                }
            }
        };
        out.push(Setting {
            method: "nalgebra_rk4",
            setting: format!("h={h}"),
            run,
            drifts: None,
        });
        if problem == "p4" {
            let (start, _) = setup(problem)?;
            let plane: [f64; 6] = start
                .inertia()
                .diagonal_plane_moments()
                .ok_or("P4 is diagonal on its planes")?
                .try_into()
                .map_err(|_| "six planes")?;
            let w0: [f64; 6] = start.omega().as_slice().try_into()?;
            out.push(Setting {
                method: "unrolled_rk4",
                setting: format!("h={h}"),
                run: Box::new(move || {
                    Ok((
                        unrolled_rk4_4d(plane, w0, h, steps).to_vec(),
                        steps,
                        4 * steps,
                    ))
                }),
                drifts: None,
            });
        }
    }
    Ok(out)
}

/// Measures every setting of every problem: the data lines of the data file.
fn measure(refs: &BTreeMap<String, Vec<f64>>, rounds: usize) -> Res<String> {
    let mut data = String::new();
    for problem in PROBLEMS {
        let settings = settings(problem)?;
        // One untimed solve each: the observation, the counts, and how many solves make a
        // round of about 2 ms.
        let mut rows = Vec::new();
        let mut kept = Vec::new();
        for s in settings {
            let clock = Instant::now();
            // A step too large for a method (Moser–Veselov's discrete equation has no
            // solution, Newton diverges) drops that setting.
            let (obs, steps, rhs) = match (s.run)() {
                Ok(r) => r,
                Err(e) => {
                    eprintln!("{problem} {} {}: {e}", s.method, s.setting);
                    continue;
                }
            };
            let once = clock.elapsed().as_secs_f64();
            let batch = ((2e-3 / once.max(1e-9)).ceil() as usize).clamp(1, 10_000);
            let error = error_of(problem, &obs, refs)?;
            let drifts = match &s.drifts {
                Some(d) => Some(d()?),
                None => None,
            };
            rows.push((steps, rhs, error, batch, f64::MAX, drifts));
            kept.push(s);
        }
        let settings = kept;
        for _ in 0..rounds {
            for (s, row) in settings.iter().zip(rows.iter_mut()) {
                let clock = Instant::now();
                for _ in 0..row.3 {
                    std::hint::black_box((s.run)()?);
                }
                let per = clock.elapsed().as_secs_f64() / row.3 as f64;
                row.4 = row.4.min(per);
            }
        }
        for (s, (steps, rhs, error, _, mut seconds, drifts)) in settings.iter().zip(rows) {
            if rounds == 0 {
                seconds = f64::NAN;
            }
            let (de, dm) = match drifts {
                Some((de, dm)) => (format!("{de:.3e}"), format!("{dm:.3e}")),
                None => ("-".to_string(), "-".to_string()),
            };
            writeln!(
                data,
                "{problem}\t{}\t{}\t{steps}\t{rhs}\t{error:.3e}\t{:.4e}\t{de}\t{dm}",
                s.method,
                s.setting,
                seconds * 1e9
            )?;
        }
        eprintln!("measured {problem}");
    }
    Ok(data)
}

// ---------------------------------------------------------------------------------------
// Rendering from the data files.

/// One measured point.
#[derive(Clone, Debug)]
struct Point {
    method: String,
    setting: String,
    steps: usize,
    rhs: usize,
    error: f64,
    ns: f64,
    drifts: Option<(f64, f64)>,
}

/// The display name of a method.
fn display(method: &str, problem: &str) -> String {
    let fixed = if problem == "hlw" {
        "FreeBody3"
    } else {
        "FreeBody4"
    };
    match method {
        "rk4" => "RKMK4 (`Rkmk4`)".into(),
        "strang" => "Strang (`Splitting::strang`)".into(),
        "yoshida4" => "Yoshida 4 (`Splitting::yoshida4`)".into(),
        "suzuki4" => "Suzuki 4 (`Splitting::suzuki4`)".into(),
        "kahan_li6" => "Kahan–Li 6 (`Splitting::kahan_li6`)".into(),
        "kahan_li8" => "Kahan–Li 8 (`Splitting::kahan_li8`)".into(),
        "suzuki4_sym" => "Suzuki 4, symmetric part split off (`with_symmetric_part`)".into(),
        "kahan_li8_sym" => "Kahan–Li 8, symmetric part split off (`with_symmetric_part`)".into(),
        "midpoint" => "implicit midpoint (`Midpoint`)".into(),
        "lprk4" => "Lie–Poisson RK4 (`LiePoissonRk4`)".into(),
        "mv" => "Moser–Veselov (`MoserVeselov`)".into(),
        "mv4" => "Moser–Veselov, Yoshida 4 (`MoserVeselov::yoshida4`)".into(),
        "mv8" => "Moser–Veselov, Kahan–Li 8 (`MoserVeselov::composed`)".into(),
        "processed6" => "processed, order 6 (`ProcessedSplitting`)".into(),
        "processed8" => "processed, order 8 (`ProcessedSplitting`)".into(),
        "dopri5" => "`Dopri5`".into(),
        "dop853" => "`Dop853`".into(),
        "fixed_rk4" => format!("`{fixed}::step_rk4`"),
        "fixed_strang" => format!("`{fixed}::step_strang`"),
        "fixed_dop853" => format!("`{fixed}::advance_dop853`"),
        "nalgebra_rk4" => "RK4 on nalgebra fixed-size types (baseline)".into(),
        "unrolled_rk4" => "RK4 on ω, unrolled by hand (baseline)".into(),
        "scipy" => "scipy DOP853 (`solve_ivp`)".into(),
        other => other.into(),
    }
}

/// Whether a method is rotorflow's (rather than a baseline).
fn is_rotorflow(method: &str) -> bool {
    !matches!(method, "nalgebra_rk4" | "unrolled_rk4" | "scipy")
}

/// Whether a method keeps the Casimirs of a free body to round-off.
fn keeps_casimirs(method: &str, problem: &str) -> bool {
    matches!(
        method,
        "strang"
            | "yoshida4"
            | "suzuki4"
            | "kahan_li6"
            | "kahan_li8"
            | "suzuki4_sym"
            | "kahan_li8_sym"
            | "mv"
            | "mv4"
            | "mv8"
            | "processed6"
            | "processed8"
            | "fixed_strang"
            | "lprk4"
    ) || (method == "midpoint" && (problem == "p4" || problem == "hlw" || problem == "free4"))
}

/// Parses both data files into the points of every problem.
fn points(rust: &str, scipy: &str) -> Res<BTreeMap<String, Vec<Point>>> {
    let refs = references(scipy)?;
    let mut out: BTreeMap<String, Vec<Point>> = BTreeMap::new();
    for line in rust.lines() {
        if line.starts_with('#') || line.trim().is_empty() || line.starts_with("problem\t") {
            continue;
        }
        let f: Vec<&str> = line.split('\t').collect();
        if f.len() != 9 {
            return Err(format!("bad data line: {line}").into());
        }
        let drifts = if f[7] == "-" {
            None
        } else {
            Some((f[7].parse()?, f[8].parse()?))
        };
        out.entry(f[0].to_string()).or_default().push(Point {
            method: f[1].to_string(),
            setting: f[2].to_string(),
            steps: f[3].parse()?,
            rhs: f[4].parse()?,
            error: f[5].parse()?,
            ns: f[6].parse()?,
            drifts,
        });
    }
    for line in scipy.lines() {
        let f: Vec<&str> = line.split('\t').collect();
        if f[0] != "scipy" {
            continue;
        }
        if f.len() != 8 {
            return Err(format!("bad scipy line: {line}").into());
        }
        let problem = f[1];
        let observed: Vec<f64> = f[7]
            .split(',')
            .map(|x| x.trim().parse())
            .collect::<Result<_, _>>()?;
        let observed = if observed.len() == 12 {
            observed[9..].to_vec()
        } else {
            observed
        };
        out.entry(problem.to_string()).or_default().push(Point {
            method: "scipy".into(),
            setting: format!("rtol={}", f[2]),
            steps: f[5].parse()?,
            rhs: f[4].parse()?,
            error: error_of(problem, &observed, &refs)?,
            ns: f[6].parse::<f64>()? * 1e9,
            drifts: None,
        });
    }
    Ok(out)
}

/// The methods of a problem's points, in order of first appearance.
fn methods(points: &[Point]) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for p in points {
        if !out.contains(&p.method) {
            out.push(p.method.clone());
        }
    }
    out
}

/// The cost of reaching `target` with `method`: log-log interpolation of time against error
/// along the method's work–precision front (the settings that are more accurate than every
/// cheaper one). `None` when no setting reaches the target; the cheapest setting's time when
/// it is already more accurate.
fn cost_at(points: &[Point], method: &str, target: f64) -> Option<f64> {
    let mut pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.method == method && p.error.is_finite() && p.error > 0.0)
        .map(|p| (p.ns, p.error))
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut front: Vec<(f64, f64)> = Vec::new();
    for p in pts {
        if front.last().is_none_or(|l| p.1 < l.1) {
            front.push(p);
        }
    }
    let first = front.first()?;
    if first.1 <= target {
        return Some(first.0);
    }
    for w in front.windows(2) {
        let ((t0, e0), (t1, e1)) = (w[0], w[1]);
        if e1 <= target {
            let s = (target.ln() - e0.ln()) / (e1.ln() - e0.ln());
            return Some((t0.ln() + s * (t1.ln() - t0.ln())).exp());
        }
    }
    None
}

/// Whether the cheapest setting of `method` is already more accurate than `target`: its
/// cost there is then an upper bound (a coarser setting might do).
fn bounded(points: &[Point], method: &str, target: f64) -> bool {
    points
        .iter()
        .filter(|p| p.method == method && p.error.is_finite())
        .min_by(|a, b| a.ns.total_cmp(&b.ns))
        .is_some_and(|p| p.error <= target)
}

fn time(ns: f64) -> String {
    if ns >= 1e9 {
        format!("{:.2} s", ns * 1e-9)
    } else if ns >= 1e6 {
        format!("{:.3} ms", ns * 1e-6)
    } else {
        format!("{:.1} µs", ns * 1e-3)
    }
}

fn sci(x: f64) -> String {
    format!("{x:.1e}")
}

/// The title of a problem's table.
fn title(problem: &str) -> &'static str {
    match problem {
        "hlw" => "Free rigid body of Hairer, Lubich and Wanner (3D), error of y(100)",
        "simo_wong" => "Heavy symmetric top of Simo and Wong (1991), relative error of ω(2)",
        "bruls" => "Heavy top of Brüls, Cardona and Arnold (2012), relative error of ω(2)",
        "p4" => "Free 4D cuboid P4, error of ω(100)",
        "free4" => "Free 4D body, drift of all Manakov integrals at t = 20",
        "free6" => "Free 6D body, drift of all Manakov integrals at t = 20",
        _ => "Free 8D body, drift of all Manakov integrals at t = 20",
    }
}

/// A problem's name in the summary table.
fn short_title(problem: &str) -> &'static str {
    match problem {
        "hlw" => "HLW free body (3D)",
        "simo_wong" => "Simo–Wong top",
        "bruls" => "Brüls–Cardona–Arnold top",
        "p4" => "P4 (4D)",
        "free4" => "free 4D body (Manakov)",
        "free6" => "free 6D body (Manakov)",
        _ => "free 8D body (Manakov)",
    }
}

/// The best rotorflow time and scipy's at `target`, if both reach it.
fn versus_scipy(points: &[Point], target: f64) -> Option<(String, f64, f64)> {
    let scipy = cost_at(points, "scipy", target)?;
    let (best, t) = methods(points)
        .into_iter()
        .filter(|m| is_rotorflow(m))
        .filter_map(|m| cost_at(points, &m, target).map(|t| (m, t)))
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    Some((best, t, scipy))
}

/// The largest difference between the recorded HLW reference y(100) and rotorflow's closed
/// form of the free 3D top (elliptic functions): two independent references.
pub fn hlw_closed_form_gap(scipy: &str) -> Res<f64> {
    let refs = references(scipy)?;
    let r = refs.get("hlw").ok_or("no HLW reference")?;
    let (body, _) = setup("hlw")?;
    let y = vector_of(&body.exact_solution()?.momentum_at(t_end("hlw"))?);
    Ok(r.iter()
        .zip(y)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max))
}

/// Renders the markdown and the plots (file name, SVG) from the two data files.
pub fn render(rust: &str, scipy: &str) -> Res<(String, Vec<(String, String)>)> {
    let all = points(rust, scipy)?;
    let mut md = String::new();
    writeln!(
        md,
        "<!-- Generated by `cargo run --release --example book_literature -- --write` from \
         literature.tsv and literature_scipy.tsv; do not edit. -->\n"
    )?;
    writeln!(md, "rotorflow's measurements:\n")?;
    for line in rust.lines() {
        if let Some(m) = line.strip_prefix("# ") {
            writeln!(md, "- {m}")?;
        }
    }
    writeln!(md, "\nscipy's measurements and the references:\n")?;
    for line in scipy.lines() {
        if let Some(m) = line.strip_prefix("# ") {
            writeln!(md, "- {m}")?;
        }
    }
    let mut overhead = BTreeMap::new();
    let mut spreads = Vec::new();
    for line in scipy.lines() {
        let f: Vec<&str> = line.split('\t').collect();
        if f[0] == "overhead" && f.len() == 3 {
            overhead.insert(f[1].to_string(), f[2].parse::<f64>()? * 1e9);
        }
        if f[0] == "ref_spread" && f.len() == 3 {
            spreads.push(format!("{} {}", f[1], f[2]));
        }
    }
    writeln!(
        md,
        "- the references' relative spread between two Taylor runs (order 32 and 28, \
         different steps): {}",
        spreads.join(", ")
    )?;
    if let Some(o) = overhead.get("solve_ivp") {
        writeln!(
            md,
            "- scipy's fixed cost: a `solve_ivp` call of one step of a constant right-hand side \
             takes {}; one call of the right-hand side takes {} (`hlw`) to {} (`free8`)",
            time(*o),
            time(overhead.get("rhs_hlw").copied().unwrap_or(f64::NAN)),
            time(overhead.get("rhs_free8").copied().unwrap_or(f64::NAN)),
        )?;
    }

    // Headline: rotorflow's best against scipy at every target.
    writeln!(
        md,
        "\n### Equal accuracy: rotorflow's fastest method against scipy's DOP853\n\n\
         Wall time per solve at the accuracy of the row, interpolated in log-log between \
         the measured settings (\"–\": not reached by the settings measured; \"≤\": the \
         cheapest setting measured is already more accurate, so its time is an upper bound, and \
         a ratio of two such bounds is marked \"≈\").\n"
    )?;
    writeln!(
        md,
        "| problem | accuracy | rotorflow's fastest | its time | scipy DOP853 | scipy / rotorflow |"
    )?;
    writeln!(md, "|---|---|---|---|---|---|")?;
    for problem in PROBLEMS {
        let Some(points) = all.get(problem) else {
            continue;
        };
        for target in TARGETS {
            if let Some((best, t, s)) = versus_scipy(points, target) {
                // Either time may be an upper bound; the ratio is then bounded on one side,
                // or on neither when both are.
                let (ours, theirs) = (
                    bounded(points, &best, target),
                    bounded(points, "scipy", target),
                );
                let le = if ours { "≤ " } else { "" };
                let sle = if theirs { "≤ " } else { "" };
                let ge = match (ours, theirs) {
                    (true, false) => "≥ ",
                    (false, true) => "≤ ",
                    (true, true) => "≈ ",
                    (false, false) => "",
                };
                writeln!(
                    md,
                    "| {} | {} | {} | {le}{} | {sle}{} | {ge}{:.0}× |",
                    short_title(problem),
                    sci(target),
                    display(&best, problem),
                    time(t),
                    time(s),
                    s / t
                )?;
            }
        }
    }

    for problem in PROBLEMS {
        let Some(points) = all.get(problem) else {
            continue;
        };
        writeln!(md, "\n### {}\n", title(problem))?;
        writeln!(
            md,
            "![Error against wall time per solve: {}](generated/literature_{problem}.svg)\n",
            title(problem)
        )?;
        writeln!(
            md,
            "Time per solve to reach the accuracy of each column (interpolated as above; the \
             plot shows every measured setting):\n"
        )?;
        let mut head = "| method |".to_string();
        let mut rule = "|---|".to_string();
        for target in TARGETS {
            write!(head, " {} |", sci(target))?;
            rule.push_str("---|");
        }
        writeln!(md, "{head} most accurate setting |\n{rule}---|")?;
        for method in methods(points) {
            let mut row = format!("| {} |", display(&method, problem));
            for target in TARGETS {
                match cost_at(points, &method, target) {
                    Some(t) if bounded(points, &method, target) => write!(row, " ≤ {} |", time(t))?,
                    Some(t) => write!(row, " {} |", time(t))?,
                    None => row.push_str(" – |"),
                }
            }
            let best = points
                .iter()
                .filter(|p| p.method == method)
                .min_by(|a, b| a.error.total_cmp(&b.error))
                .ok_or("no points")?;
            let rhs = if best.rhs > 0 {
                format!(", {} right-hand sides", best.rhs)
            } else {
                String::new()
            };
            write!(
                row,
                " {}: error {}, {} steps{rhs}, {} |",
                best.setting,
                sci(best.error),
                best.steps,
                time(best.ns)
            )?;
            writeln!(md, "{row}")?;
        }
        if problem == "p4" {
            p4_summary(&mut md, points)?;
        }
        if problem == "simo_wong" || problem == "bruls" {
            drift_table(&mut md, problem, points)?;
        }
        if problem == "bruls" {
            order_table(&mut md, points)?;
        }
    }
    let plots = PROBLEMS
        .iter()
        .filter_map(|p| all.get(*p).map(|pts| (p, pts)))
        .map(|(p, pts)| (format!("literature_{p}.svg"), plot(p, pts)))
        .collect();
    Ok((md, plots))
}

/// The P4 comparisons: the fastest method against RKMK4 and the hand-unrolled RK4 at 1e-11,
/// and the fastest Casimir-keeping method against RKMK4 at 1e-8.
fn p4_summary(md: &mut String, points: &[Point]) -> Res<()> {
    let fastest = |target: f64, filter: &dyn Fn(&str) -> bool| {
        methods(points)
            .into_iter()
            .filter(|m| filter(m))
            .filter_map(|m| cost_at(points, &m, target).map(|t| (m, t)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
    };
    writeln!(md, "\nOn P4:\n")?;
    if let (Some((best, t)), Some(rk4), Some(unrolled)) = (
        fastest(1e-11, &|m: &str| is_rotorflow(m)),
        cost_at(points, "rk4", 1e-11),
        cost_at(points, "unrolled_rk4", 1e-11),
    ) {
        writeln!(
            md,
            "- at 1e-11 the fastest rotorflow method, {}, takes {}: {:.1}× faster than \
             `Rkmk4` ({}); the hand-unrolled RK4 on ω (which carries no attitude) takes {}, \
             {:.2}× the time of {};",
            display(&best, "p4"),
            time(t),
            rk4 / t,
            time(rk4),
            time(unrolled),
            unrolled / t,
            display(&best, "p4"),
        )?;
    }
    if let (Some((best, t)), Some(rk4)) = (
        fastest(1e-8, &|m: &str| keeps_casimirs(m, "p4")),
        cost_at(points, "rk4", 1e-8),
    ) {
        writeln!(
            md,
            "- at 1e-8 the fastest method that keeps the Casimirs, {}, takes {}, {:.1}× the \
             time of `Rkmk4` ({}).",
            display(&best, "p4"),
            time(t),
            t / rk4,
            time(rk4)
        )?;
    }
    Ok(())
}

/// The heavy top's drifts against the step size, for every fixed-step rotorflow method.
fn drift_table(md: &mut String, problem: &str, points: &[Point]) -> Res<()> {
    writeln!(
        md,
        "\nLargest relative drift over the run of the total energy T + V and of the two \
         momenta a symmetric top keeps (the vertical component of the space-frame L and the \
         axial component of the body-frame L, relative to |L|):\n"
    )?;
    let with: Vec<&Point> = points.iter().filter(|p| p.drifts.is_some()).collect();
    let mut hs: Vec<String> = Vec::new();
    for p in &with {
        if !hs.contains(&p.setting) {
            hs.push(p.setting.clone());
        }
    }
    // Largest step first (the compositions of higher order add larger steps).
    let step = |s: &String| s.trim_start_matches("h=").parse::<f64>().unwrap_or(0.0);
    hs.sort_by(|a, b| step(b).total_cmp(&step(a)));
    let mut head = "| method | drift |".to_string();
    let mut rule = "|---|---|".to_string();
    for h in &hs {
        write!(head, " {} |", h.replace("h=", "h = "))?;
        rule.push_str("---|");
    }
    writeln!(md, "{head}\n{rule}")?;
    for method in methods(&with.iter().map(|p| (*p).clone()).collect::<Vec<_>>()) {
        for (label, pick) in [("T + V", 0), ("momenta", 1)] {
            let mut row = format!("| {} | {label} |", display(&method, problem));
            for h in &hs {
                match with.iter().find(|p| p.method == method && &p.setting == h) {
                    Some(p) => {
                        let (de, dm) = p.drifts.ok_or("drifts")?;
                        write!(row, " {} |", sci(if pick == 0 { de } else { dm }))?;
                    }
                    None => row.push_str(" |"),
                }
            }
            writeln!(md, "{row}")?;
        }
    }
    Ok(())
}

/// The error below which the order is not measured: the relative round-off of ω(2) on the
/// Brüls top after 10⁵ steps is about 1e-13.
const ORDER_FLOOR: f64 = 1e-11;

/// The measured orders on the Brüls top: the slope of log error against log h over the
/// two smallest step sizes of each fixed-step method whose errors are above
/// [`ORDER_FLOOR`].
fn order_table(md: &mut String, points: &[Point]) -> Res<()> {
    writeln!(
        md,
        "\nMeasured order on this top (slope of log error against log h between the two \
         smallest steps whose errors are above {ORDER_FLOOR:e}, where round-off does not \
         yet show):\n"
    )?;
    writeln!(md, "| method | steps h | errors | measured order |")?;
    writeln!(md, "|---|---|---|---|")?;
    for method in methods(points) {
        let mut fixed: Vec<(f64, f64)> = points
            .iter()
            .filter(|p| p.method == method)
            .filter_map(|p| {
                p.setting
                    .strip_prefix("h=")
                    .and_then(|h| h.parse().ok())
                    .map(|h| (h, p.error))
            })
            .collect();
        if fixed.len() < 2 {
            continue;
        }
        fixed.sort_by(|a, b| a.0.total_cmp(&b.0));
        // Below about 1e-11 the errors reach round-off and stop falling with h.
        let Some(k) = (0..fixed.len() - 1).find(|&k| fixed[k].1 > ORDER_FLOOR) else {
            continue;
        };
        let ((h0, e0), (h1, e1)) = (fixed[k], fixed[k + 1]);
        let order = (e1 / e0).ln() / (h1 / h0).ln();
        writeln!(
            md,
            "| {} | {h1}, {h0} | {}, {} | {order:.2} |",
            display(&method, "bruls"),
            sci(e1),
            sci(e0)
        )?;
    }
    Ok(())
}

/// A log-log plot of error against time per solve, one line per method (rotorflow's solid,
/// the baselines dashed).
fn plot(problem: &str, points: &[Point]) -> String {
    let finite: Vec<&Point> = points
        .iter()
        .filter(|p| p.error.is_finite() && p.error > 0.0)
        .collect();
    let lo_t = finite.iter().map(|p| p.ns).fold(f64::MAX, f64::min);
    let hi_t = finite.iter().map(|p| p.ns).fold(0.0, f64::max);
    let (x0, x1) = (lo_t.log10().floor(), hi_t.log10().ceil());
    let mut plot = LogPlot::new(
        (800.0, 400.0),
        (70.0, 340.0, 20.0, 50.0),
        (x0, x1),
        (-16.0, 0.0),
        11,
    );
    plot.y_grid((-16..=0).step_by(2));
    // The axis is in nanoseconds; the labels in seconds.
    plot.x_grid((x0 as i32..=x1 as i32).map(|k| (10f64.powi(k), format!("1e{}", k - 9))));
    plot.titles("wall time per solve (s)", "error");
    let colours = [
        "#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#7f7f7f",
        "#bcbd22", "#17becf", "#393b79", "#637939", "#000000", "#e6550d",
    ];
    for (k, method) in methods(points).iter().enumerate() {
        let mut pts: Vec<(f64, f64)> = finite
            .iter()
            .filter(|p| &p.method == method)
            .map(|p| (p.ns, p.error))
            .collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let name = display(method, problem).replace('`', "");
        plot.line(
            &pts,
            colours[k % colours.len()],
            !is_rotorflow(method),
            &name,
        );
    }
    plot.finish()
}

/// Measures (with `--write`: records) and prints the tables.
pub fn main() -> Res<()> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("book/src/generated");
    let scipy = std::fs::read_to_string(dir.join("literature_scipy.tsv")).map_err(|e| {
        format!("literature_scipy.tsv ({e}): run python3 scripts/literature_scipy.py --write first")
    })?;
    // `--render` re-renders the tables and plots from the recorded data, measuring nothing.
    if std::env::args().any(|a| a == "--render") {
        let tsv = std::fs::read_to_string(dir.join("literature.tsv"))?;
        let (md, plots) = render(&tsv, &scipy)?;
        std::fs::write(dir.join("literature.md"), &md)?;
        for (name, svg) in &plots {
            std::fs::write(dir.join(name), svg)?;
        }
        println!("wrote {}", dir.join("literature.md").display());
        return Ok(());
    }
    let refs = references(&scipy)?;
    let mut tsv = provenance::header();
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    writeln!(
        tsv,
        "# method: fastest of {ROUNDS} alternating rounds (batches of about 2 ms) per setting, \
         wall time per solve, release build; load average before the run {}",
        load.split_whitespace()
            .take(3)
            .collect::<Vec<_>>()
            .join(" ")
    )?;
    writeln!(
        tsv,
        "problem\tmethod\tsetting\tsteps\trhs\terror\tns_per_solve\tenergy_drift\tmomentum_drift"
    )?;
    // `--errors` skips the timing: a quick look at the errors and counts.
    let rounds = if std::env::args().any(|a| a == "--errors") {
        0
    } else {
        ROUNDS
    };
    tsv.push_str(&measure(&refs, rounds)?);
    let (md, plots) = render(&tsv, &scipy)?;
    print!("{md}");
    if rounds > 0 && std::env::args().any(|a| a == "--write") {
        std::fs::write(dir.join("literature.tsv"), &tsv)?;
        std::fs::write(dir.join("literature.md"), &md)?;
        for (name, svg) in &plots {
            std::fs::write(dir.join(name), svg)?;
        }
        println!("wrote {}", dir.join("literature.md").display());
    }
    Ok(())
}
