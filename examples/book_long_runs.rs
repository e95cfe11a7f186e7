//! The measured tables of the book's dynamics chapter that take minutes to compute: the
//! fixed steps each method needs on the 4D cuboid P4 for |Δω| ≤ 1e-8 at t = 100, the
//! right-hand sides the adaptive methods and RKMK4 spend on the same problem, and the drift
//! of the integrals over a million Moser–Veselov and Dopri5 steps in 4D … 8D.
//!
//! `cargo run --release --example book_long_runs -- --write` computes them (a few minutes),
//! records the numbers with the date, the commit, the machine and the compiler in
//! `book/src/generated/long_runs.tsv` and renders the three tables
//! `book/src/generated/long_runs_{cost,rhs,drift}.md` from that file; without `--write` it only prints the table rendered from the recorded file.
//! `tests/book.rs` re-renders the committed data and fails when the committed table differs.
//! No timings are recorded: the wall times of these runs are in the Criterion table of the
//! Performance chapter (`cuboid4_to_t10`, `cuboid4_to_t100_at_1e-8`).

use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::{
    Attitude, Dop853, Dopri5, Drift, Integrator, Invariants, LiePoissonRk4, MoserVeselov,
    RigidBody, Rkmk4, Splitting,
};
use rotorflow::inertia::spec::parse_body;
use rotorflow::prelude::*;
use std::fmt::Write as _;
use std::path::PathBuf;

// tests/book.rs compiles this file beside the other generators, so it loads this module more
// than once.
#[allow(clippy::duplicate_mod)]
#[path = "support/provenance.rs"]
mod provenance;

type Error = Box<dyn std::error::Error>;

/// The solid 4D cuboid P4 (`cuboid:1,1.3,1.7,2.2`, mass 1) with
/// ω(0) = (0.3, −0.2, 0.5, 0.1, 0.4, −0.6).
fn p4() -> Result<RigidBody, Error> {
    let parsed = parse_body("cuboid:1,1.3,1.7,2.2+mass=1")?;
    let omega = Bivector::from_components(4, &[0.3, -0.2, 0.5, 0.1, 0.4, -0.6])?;
    Ok(RigidBody::from_body_velocity(
        parsed.inertia,
        Attitude::identity(4),
        &omega,
    )?)
}

/// ω of P4 at t = 100 after one call of `integrator` (adaptive) or `steps` equal steps.
fn p4_omega(integrator: &mut dyn Integrator, steps: usize) -> Result<Bivector, Error> {
    let mut b = p4()?;
    let h = 100.0 / steps as f64;
    for k in 0..steps {
        integrator.step(&mut b, k as f64 * h, h, &Free)?;
    }
    Ok(b.omega())
}

/// The fixed-step methods of the cost table: label, constructor, a step count known to be
/// enough for 1e-8 (the search halves below it).
type Make = fn() -> Box<dyn Integrator>;
const FIXED_STEP: [(&str, Make, usize); 5] = [
    ("RKMK4 (`Rkmk4`)", || Box::new(Rkmk4), 8_000),
    (
        "Lie–Poisson RK4 (`LiePoissonRk4`)",
        || Box::new(LiePoissonRk4),
        8_000,
    ),
    (
        "Yoshida 4 splitting (`Splitting::yoshida4`)",
        || Box::new(Splitting::yoshida4()),
        40_000,
    ),
    (
        "Moser–Veselov, Yoshida 4 (`MoserVeselov::yoshida4`)",
        || Box::new(MoserVeselov::yoshida4()),
        40_000,
    ),
    (
        "Strang splitting (`Splitting::strang`)",
        || Box::new(Splitting::strang()),
        2_000_000,
    ),
];

/// The cost lines: for each fixed-step method the fewest equal steps (to 1 %) with
/// |Δω| ≤ 1e-8 at t = 100 against Dop853 at rtol 1e-15, and that error.
fn fixed_step_cost(reference: &Bivector, data: &mut String) -> Result<(), Error> {
    for (label, make, enough) in FIXED_STEP {
        let error = |steps: usize| -> Result<f64, Error> {
            Ok((&p4_omega(&mut *make(), steps)? - reference).max_abs())
        };
        let (mut lo, mut hi) = (enough / 8, enough);
        if error(hi)? > 1e-8 {
            return Err(format!("{label}: {enough} steps are not enough").into());
        }
        while hi - lo > hi / 100 {
            let mid = (lo + hi) / 2;
            if error(mid)? <= 1e-8 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        writeln!(data, "cost\t{label}\t{hi}\t{:.2e}", error(hi)?)?;
    }
    Ok(())
}

/// The right-hand-side lines: Dop853 and Dopri5 at two tolerances each and RKMK4 at two
/// steps, each with |Δω| at t = 100 and the right-hand sides it evaluated.
fn right_hand_sides(reference: &Bivector, data: &mut String) -> Result<(), Error> {
    for rtol in [1e-10, 1e-12] {
        let mut d = Dop853::new(rtol, rtol * 1e-2)?;
        let e = (&p4_omega(&mut d, 1)? - reference).max_abs();
        let rhs = d.rhs_evaluations();
        writeln!(data, "rhs\t`Dop853`\trtol {rtol:.0e}\t{e:.2e}\t{rhs}")?;
    }
    for rtol in [1e-11, 1e-13] {
        let mut d = Dopri5::new(rtol, rtol * 1e-2);
        let e = (&p4_omega(&mut d, 1)? - reference).max_abs();
        let rhs = d.rhs_evaluations();
        writeln!(data, "rhs\t`Dopri5`\trtol {rtol:.0e}\t{e:.2e}\t{rhs}")?;
    }
    for steps in [10_000usize, 20_000] {
        let e = (&p4_omega(&mut Rkmk4, steps)? - reference).max_abs();
        let h = 100.0 / steps as f64;
        writeln!(data, "rhs\t`Rkmk4`\th = {h:.0e}\t{e:.2e}\t{}", 4 * steps)?;
    }
    Ok(())
}

/// The principal second moments of the long runs' bodies (the first N of them).
const LONG_RUN_MOMENTS: [f64; 8] = [0.5, 0.8, 1.3, 2.1, 2.6, 3.2, 3.9, 4.5];
/// The steps of the long runs, and Moser–Veselov's step size (Dopri5 is called with it).
const LONG_RUN_STEPS: usize = 1_000_000;
const LONG_RUN_H: f64 = 0.05;

/// The free body of dimension n of the long runs: identity attitude, L = sin(0.7 k + 0.3).
fn long_run_body(n: usize) -> Result<RigidBody, Error> {
    let l: Vec<f64> = (0..n * (n - 1) / 2)
        .map(|k| (0.7 * k as f64 + 0.3).sin())
        .collect();
    Ok(RigidBody::from_body_momentum(
        InertiaMap::from_principal_second_moments(&LONG_RUN_MOMENTS[..n])?,
        Attitude::identity(n),
        &Bivector::from_components(n, &l)?,
    )?)
}

/// Calls `integ` with steps of [`LONG_RUN_H`] until `count` reaches [`LONG_RUN_STEPS`],
/// sampling the drift of the invariants whenever the count passes a multiple of 10⁴: the
/// largest sampled drift and the number of calls.
fn drift_run<I: Integrator>(
    b0: &RigidBody,
    integ: &mut I,
    count: impl Fn(&I, usize) -> usize,
) -> Result<(Drift, usize), Error> {
    let mut b = b0.clone();
    let start = Invariants::of(&b);
    let mut worst = Drift::default();
    let (mut calls, mut next_sample) = (0, 10_000);
    while count(integ, calls) < LONG_RUN_STEPS {
        integ.step(&mut b, calls as f64 * LONG_RUN_H, LONG_RUN_H, &Free)?;
        calls += 1;
        if count(integ, calls) >= next_sample {
            next_sample += 10_000;
            worst = worst.max(Invariants::of(&b).drift_from(&start));
        }
    }
    Ok((worst.max(Invariants::of(&b).drift_from(&start)), calls))
}

/// The drift lines: N, Moser–Veselov's largest relative drift of the Manakov integrals, the
/// Casimirs and the energy over 10⁶ steps, Dopri5's (rtol 1e-12) over 10⁶ accepted steps,
/// and the time Dopri5 reached.
fn long_run_drift(data: &mut String) -> Result<(), Error> {
    for n in 4..=8 {
        let b0 = long_run_body(n)?;
        let (mv, _) = drift_run(&b0, &mut MoserVeselov::new(), |_, calls| calls)?;
        let mut dopri = Dopri5::new(1e-12, 1e-14);
        let (d5, calls) = drift_run(&b0, &mut dopri, |d, _| d.accepted_steps())?;
        writeln!(
            data,
            "drift\t{n}\t{:.1e}\t{:.1e}\t{:.1e}\t{:.1e}\t{:.1e}\t{:.1e}\t{:.0}",
            mv.manakov,
            mv.casimirs,
            mv.energy,
            d5.manakov,
            d5.casimirs,
            d5.energy,
            calls as f64 * LONG_RUN_H
        )?;
    }
    Ok(())
}

/// The generated files, one table each: the cost of the fixed-step methods, the right-hand
/// sides, and the long runs' drift.
pub const FILES: [&str; 3] = [
    "long_runs_cost.md",
    "long_runs_rhs.md",
    "long_runs_drift.md",
];

/// Renders the markdown tables of [`FILES`] from the data file's text: `# key: value`
/// header lines, then tab-separated lines tagged `cost`, `rhs` and `drift` (see
/// [`fixed_step_cost`], [`right_hand_sides`] and [`long_run_drift`]).
pub fn render(tsv: &str) -> Result<[String; 3], Error> {
    let mut header = String::new();
    writeln!(
        header,
        "<!-- Generated by `cargo run --release --example book_long_runs -- --write` from \
         long_runs.tsv; do not edit. -->\n"
    )?;
    let (mut cost, mut rhs, mut drift) = (Vec::new(), Vec::new(), Vec::new());
    for line in tsv.lines() {
        if let Some(m) = line.strip_prefix("# ") {
            writeln!(header, "- {m}")?;
            continue;
        }
        let f: Vec<&str> = line.split('\t').collect();
        let row = format!("| {} |", f[1..].join(" | "));
        match (f[0], f.len()) {
            ("cost", 4) => cost.push(row),
            ("rhs", 5) => rhs.push(row),
            ("drift", 9) => drift.push(row),
            _ if line.trim().is_empty() => {}
            _ => return Err(format!("bad data line: {line}").into()),
        }
    }
    if cost.is_empty() || rhs.is_empty() || drift.is_empty() {
        return Err("the data file lacks one of its tables".into());
    }
    let tables = [
        (
            "**Fixed steps on P4 for |Δω| ≤ 1e-8 at t = 100** (the fewest equal steps, to 1 %, \
             against Dop853 at rtol 1e-15)",
            "| method | steps | \\|Δω\\| at t = 100 |\n|---|---|---|",
            cost,
        ),
        (
            "**Right-hand sides on P4 to t = 100** (one call for the adaptive methods, \
             atol = rtol/100; four per step for RKMK4)",
            "| method | setting | \\|Δω\\| at t = 100 | right-hand sides |\n|---|---|---|---|",
            rhs,
        ),
        (
            "**Largest relative drift over 10⁶ steps, sampled every 10⁴** (Moser–Veselov at \
             h = 0.05 to t = 5·10⁴; Dopri5 at rtol 1e-12 called with 0.05 until it has taken \
             10⁶ steps, to the t in the last column)",
            "| N | MV: Manakov | MV: Casimirs | MV: energy | Dopri5: Manakov | Dopri5: Casimirs \
             | Dopri5: energy | Dopri5: t reached |\n|---|---|---|---|---|---|---|---|",
            drift,
        ),
    ];
    let mut out: [String; 3] = Default::default();
    for (file, (title, head, rows)) in out.iter_mut().zip(tables) {
        file.push_str(&header);
        writeln!(file, "\n{title}\n\n{head}")?;
        for row in rows {
            writeln!(file, "{row}")?;
        }
    }
    Ok(out)
}

/// The recorded data file.
fn data_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("book/src/generated/long_runs.tsv")
}

/// With `--write`, computes the tables and records the data file and the table; otherwise
/// prints the table rendered from the recorded data.
pub fn main() -> Result<(), Error> {
    let tsv = if std::env::args().any(|a| a == "--write") {
        let reference = {
            let mut reference = Dop853::new(1e-15, 1e-16)?;
            p4_omega(&mut reference, 1)?
        };
        let mut tsv = provenance::header();
        fixed_step_cost(&reference, &mut tsv)?;
        right_hand_sides(&reference, &mut tsv)?;
        long_run_drift(&mut tsv)?;
        std::fs::write(data_path(), &tsv)?;
        tsv
    } else {
        std::fs::read_to_string(data_path())?
    };
    let tables = render(&tsv)?;
    for (name, table) in FILES.iter().zip(&tables) {
        print!("{table}");
        if std::env::args().any(|a| a == "--write") {
            let md = data_path().with_file_name(name);
            std::fs::write(&md, table)?;
            println!("wrote {}", md.display());
        }
    }
    Ok(())
}
