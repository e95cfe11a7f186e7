//! Exact against numeric motion for the book (chapter "Closed-form motion"):
//! `cargo run --example book_closed_form` prints the table, and
//! `cargo run --example book_closed_form -- --write` rewrites
//! `book/src/generated/closed_form.md` and the error-over-time plot
//! `book/src/generated/closed_form_error.svg`. `tests/book.rs` runs [`render`] and fails when
//! the committed files differ.
//!
//! Four free bodies, each started at R₀ = 1 and sampled 161 times up to T = 40: the paper's
//! §7.1 (J = 1), §7.2 (J = (1, 1, 1, κ²), κ = 2) and §7.3 (J = (1, 1, κ², κ²), κ = 1.5) in
//! 4D, and an asymmetric 3D top. For each, the closed form `RigidBody::exact_solution` is
//! compared with `Dopri5` (rtol = atol = 1e-12), `Rkmk4` and `Splitting::strang` (both at
//! h = 0.05), and, for §7.2 and §7.3, with the paper's formulas as corrected
//! (`paper::ThreeEqualMoments`, `paper::TwoEqualPairs`) and as printed (the corrected form
//! at −t, `tests/exact/paper_section7.rs`).
//!
//! The numbers are deterministic (no timings). Errors are printed with two significant
//! digits, and everything below 1e-13 (round-off of the closed forms themselves) as
//! "< 1e-13", so that the committed files do not depend on the last bits of the platform's
//! `sin` and `exp`.

use rotorflow::dynamics::exact::paper::{
    ThreeEqualMoments, TwoEqualPairs, three_equal_second_moments, two_equal_pairs_second_moments,
};
use rotorflow::dynamics::exact::{ExactSolution, top3d::TopRegime, two_moments::TwoMomentKind};
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::trajectory::even_times;
use rotorflow::dynamics::{Attitude, Dopri5, Integrator, RigidBody, Rkmk4, Splitting, simulate};
use rotorflow::prelude::*;
use std::error::Error;
use std::fmt::Write as _;

type Res<T> = Result<T, Box<dyn Error>>;

const T_END: f64 = 40.0;
const SAMPLES: usize = 161;
/// The step of the fixed-step integrators.
const H: f64 = 0.05;
/// The tolerances (rtol = atol) of the adaptive reference.
const DOPRI_TOL: f64 = 1e-12;
/// Differences below this are round-off and are shown as "< 1e-13".
const FLOOR: f64 = 1e-13;

/// One body of the comparison.
struct Case {
    label: &'static str,
    body: &'static str,
    omega: &'static str,
    start: RigidBody,
    /// The paper's corrected ω(t) (§7.2, §7.3 only).
    paper: Option<Box<dyn Fn(f64) -> Res<Bivector>>>,
}

fn cases() -> Res<Vec<Case>> {
    let w71 = [0.3, 0.4, 0.2, 0.5, 0.1, 0.3];
    let w72 = [0.3, -0.5, 0.8, 0.4, 0.2, -0.6];
    let w73 = [0.9, 0.1, -0.3, 0.2, 0.5, 0.4];
    let w3 = [0.4, -0.9, 1.2];
    let velocity = |j: &[f64], w: &[f64]| -> Res<RigidBody> {
        let inertia = InertiaMap::from_principal_second_moments(j)?;
        let omega = Bivector::from_components(j.len(), w)?;
        Ok(RigidBody::from_body_velocity(
            inertia,
            Rotor::identity(j.len()),
            &omega,
        )?)
    };
    let p72 = ThreeEqualMoments::new(2.0, &Bivector::from_components(4, &w72)?)?;
    let p73 = TwoEqualPairs::new(1.5, &Bivector::from_components(4, &w73)?)?;
    Ok(vec![
        Case {
            label: "§7.1 all equal",
            body: "J = (1, 1, 1, 1)",
            omega: "(0.3, 0.4, 0.2, 0.5, 0.1, 0.3)",
            start: velocity(&[1.0; 4], &w71)?,
            paper: None,
        },
        Case {
            label: "§7.2 three equal, κ = 2",
            body: "J = (1, 1, 1, 4)",
            omega: "(0.3, −0.5, 0.8, 0.4, 0.2, −0.6)",
            start: velocity(&three_equal_second_moments(2.0)?, &w72)?,
            paper: Some(Box::new(move |t| Ok(p72.omega_at(t)?))),
        },
        Case {
            label: "§7.3 two pairs, κ = 1.5",
            body: "J = (1, 1, 2.25, 2.25)",
            omega: "(0.9, 0.1, −0.3, 0.2, 0.5, 0.4)",
            start: velocity(&two_equal_pairs_second_moments(1.5)?, &w73)?,
            paper: Some(Box::new(move |t| Ok(p73.omega_at(t)?))),
        },
        Case {
            label: "3D asymmetric top",
            body: "J = (0.2, 0.5, 1)",
            omega: "(0.4, −0.9, 1.2)",
            start: velocity(&[0.2, 0.5, 1.0], &w3)?,
            paper: None,
        },
    ])
}

/// The closed form used, in words.
fn form(exact: &ExactSolution) -> String {
    match exact {
        ExactSolution::TwoMoments(s) => match s.kind() {
            TwoMomentKind::Isotropic => "two moments (isotropic: ω constant)".into(),
            TwoMomentKind::TwoMoments => "two moments: L = S L₀ S̃, S = exp(½tΩ)".into(),
            TwoMomentKind::Steady => "steady rotation".into(),
        },
        ExactSolution::AsymmetricTop(top) => match top.regime() {
            TopRegime::Elliptic {
                m,
                above_separatrix,
                ..
            } => format!(
                "asymmetric top, Jacobi sn/cn/dn with m = {m:.3}, {} the separatrix",
                if above_separatrix { "above" } else { "below" }
            ),
            other => format!("asymmetric top ({other:?})"),
        },
        other => other.name().into(),
    }
}

/// One method's error against the closed form, sampled over time.
struct Series {
    method: &'static str,
    /// |ΔL|/|L| at each sample.
    momentum: Vec<f64>,
    /// max |ΔQ| over the rotation-matrix entries at each sample (None: ω only).
    attitude: Option<Vec<f64>>,
}

impl Series {
    /// The error at each sample: the larger of the two.
    fn combined(&self) -> Vec<f64> {
        match &self.attitude {
            Some(a) => self
                .momentum
                .iter()
                .zip(a)
                .map(|(l, r)| l.max(*r))
                .collect(),
            None => self.momentum.clone(),
        }
    }
}

fn max(v: &[f64]) -> f64 {
    v.iter().copied().fold(0.0, f64::max)
}

fn distance(a: &Attitude, b: &Attitude) -> f64 {
    (a.to_matrix() - b.to_matrix()).amax()
}

/// The closed form and every method on one case.
fn compare(case: &Case) -> Res<(String, Vec<Series>)> {
    let exact = case.start.exact_solution()?;
    let times = even_times(T_END, SAMPLES);
    let truth: Vec<(Attitude, Bivector)> = times
        .iter()
        .map(|&t| Ok((exact.attitude_at(t)?, exact.momentum_at(t)?)))
        .collect::<Res<_>>()?;
    let scale = case.start.momentum().norm();
    let mut out = Vec::new();
    let runs: [(&'static str, f64, Box<dyn Integrator>); 3] = [
        (
            "Dopri5 (1e-12)",
            T_END,
            Box::new(Dopri5::new(DOPRI_TOL, DOPRI_TOL)),
        ),
        ("RKMK4 (h = 0.05)", H, Box::new(Rkmk4)),
        ("Strang (h = 0.05)", H, Box::new(Splitting::strang())),
    ];
    for (method, h, mut integrator) in runs {
        // Dopri5 steps adaptively inside each sample interval (one `step` call per interval).
        let traj = simulate(&case.start, integrator.as_mut(), &Free, h, &times)?;
        let (mut momentum, mut attitude) = (Vec::new(), Vec::new());
        for (s, (r, l)) in traj.samples().iter().zip(&truth) {
            momentum.push((&s.momentum - l).norm() / scale);
            attitude.push(distance(&s.attitude, r));
        }
        out.push(Series {
            method,
            momentum,
            attitude: Some(attitude),
        });
    }
    if let Some(paper) = &case.paper {
        let inertia = case.start.inertia();
        for (method, sign) in [("paper, corrected", 1.0), ("paper, as printed", -1.0)] {
            let momentum = times
                .iter()
                .zip(&truth)
                .map(|(&t, (_, l))| {
                    let w = paper(sign * t)?;
                    Ok((&inertia.apply(&w) - l).norm() / scale)
                })
                .collect::<Res<_>>()?;
            out.push(Series {
                method,
                momentum,
                attitude: None,
            });
        }
    }
    Ok((form(&exact), out))
}

/// An error with two significant digits, or "< 1e-13" below the round-off floor.
fn err(x: f64) -> String {
    if x < FLOOR {
        "< 1e-13".into()
    } else {
        format!("{x:.1e}")
    }
}

/// Rounds to two significant digits (what the plot draws, for stable files).
fn round2(x: f64) -> f64 {
    if x <= 0.0 || !x.is_finite() {
        return 0.0;
    }
    let e = x.log10().floor();
    let scale = 10f64.powf(e - 1.0);
    (x / scale).round() * scale
}

/// Returns (the markdown table, the SVG plot).
pub fn render() -> Res<(String, String)> {
    let cases = cases()?;
    let mut results = Vec::new();
    for case in &cases {
        results.push(compare(case)?);
    }
    let mut md = String::new();
    writeln!(
        md,
        "<!-- Generated by `cargo run --example book_closed_form -- --write`; do not edit. -->\n"
    )?;
    writeln!(
        md,
        "Free bodies started at R₀ = 1 with the given ω(0) (components 12, 13, 14, 23, 24, 34; \
         12, 13, 23 in 3D), sampled {SAMPLES} times on [0, {T_END}]. Each method is compared \
         with `RigidBody::exact_solution()` at every sample: |ΔL|/|L| for the body-frame \
         momentum, max |ΔQ| over the entries of the attitude's rotation matrix. `Dopri5` runs \
         at rtol = atol = {DOPRI_TOL:e} and lands on every sample; RKMK4 and Strang take steps \
         h = {H}. The paper's ω(t) of §7.2/§7.3 is turned into L = I(ω); \"as printed\" is \
         eqs. (116)–(118) and (128)–(131) as the paper prints them, which equal the corrected \
         forms at −t. Differences below {FLOOR:e} are round-off and shown as \"< 1e-13\".\n"
    )?;
    writeln!(
        md,
        "| case | body | ω(0) | closed form used | compared with | max \\|ΔL\\|/\\|L\\| | max \\|ΔQ\\| | \\|ΔL\\|/\\|L\\| at T |"
    )?;
    writeln!(md, "|---|---|---|---|---|---|---|---|")?;
    for (case, (form, series)) in cases.iter().zip(&results) {
        for (k, s) in series.iter().enumerate() {
            let (label, body, omega, form) = if k == 0 {
                (case.label, case.body, case.omega, form.as_str())
            } else {
                ("", "", "", "")
            };
            let attitude = s.attitude.as_ref().map_or("—".to_string(), |a| err(max(a)));
            writeln!(
                md,
                "| {label} | {body} | {omega} | {form} | {} | {} | {attitude} | {} |",
                s.method,
                err(max(&s.momentum)),
                err(*s.momentum.last().ok_or("no samples")?),
            )?;
        }
    }
    let svg = plot(&cases, &results);
    Ok((md, svg))
}

/// Four panels (one per case): the error against the closed form over time, log scale.
fn plot(cases: &[Case], results: &[(String, Vec<Series>)]) -> String {
    let (pw, ph) = (330.0, 230.0);
    let (w, h) = (2.0 * pw, 2.0 * ph + 50.0);
    let (left, right, top, bottom) = (52.0, 12.0, 26.0, 34.0);
    let (y0, y1) = (-14.0f64, 1.0f64);
    let colours = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#8c564b"];
    let dashes = ["", "", "", "", "6,3"];
    let times = even_times(T_END, SAMPLES);
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="11">"#
    );
    let _ = writeln!(
        s,
        r#"<rect x="0" y="0" width="{w}" height="{h}" fill="white"/>"#
    );
    for (k, (case, (_, series))) in cases.iter().zip(results).enumerate() {
        let (ox, oy) = ((k % 2) as f64 * pw, (k / 2) as f64 * ph);
        let px = |t: f64| ox + left + t / T_END * (pw - left - right);
        let py = |e: f64| {
            let e = if e <= 0.0 {
                y0
            } else {
                e.log10().clamp(y0, y1)
            };
            oy + top + (y1 - e) / (y1 - y0) * (ph - top - bottom)
        };
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="middle" font-weight="bold">{}</text>"#,
            ox + (left + pw - right) / 2.0,
            oy + 16.0,
            case.label
        );
        for e in (y0 as i32..=y1 as i32).step_by(2) {
            let y = py(10f64.powi(e));
            let _ = writeln!(
                s,
                r##"<line x1="{:.1}" y1="{y:.1}" x2="{:.1}" y2="{y:.1}" stroke="#ddd"/><text x="{:.1}" y="{:.1}" text-anchor="end">1e{e}</text>"##,
                ox + left,
                ox + pw - right,
                ox + left - 4.0,
                y + 4.0
            );
        }
        for t in [0.0, 10.0, 20.0, 30.0, 40.0] {
            let x = px(t);
            let _ = writeln!(
                s,
                r##"<line x1="{x:.1}" y1="{:.1}" x2="{x:.1}" y2="{:.1}" stroke="#ddd"/><text x="{x:.1}" y="{:.1}" text-anchor="middle">{t}</text>"##,
                oy + top,
                oy + ph - bottom,
                oy + ph - bottom + 14.0
            );
        }
        for (j, series) in series.iter().enumerate() {
            // The first sample is the initial state (error 0): start at the second.
            let points: Vec<String> = times
                .iter()
                .zip(series.combined())
                .skip(1)
                .map(|(&t, e)| {
                    let e = if e < FLOOR { FLOOR } else { round2(e) };
                    format!("{:.1},{:.1}", px(t), py(e))
                })
                .collect();
            let dash = if dashes[j].is_empty() {
                String::new()
            } else {
                format!(r#" stroke-dasharray="{}""#, dashes[j])
            };
            let _ = writeln!(
                s,
                r#"<polyline points="{}" fill="none" stroke="{}" stroke-width="1.5"{dash}/>"#,
                points.join(" "),
                colours[j]
            );
        }
    }
    // One legend for all panels (the methods are the same, the paper's only in §7.2, §7.3).
    let methods = [
        "Dopri5, rtol 1e-12",
        "RKMK4, h = 0.05",
        "Strang, h = 0.05",
        "paper §7, corrected",
        "paper §7, as printed",
    ];
    let ly = 2.0 * ph + 14.0;
    for (j, name) in methods.iter().enumerate() {
        let x = 20.0 + j as f64 * 130.0;
        let dash = if dashes[j].is_empty() {
            String::new()
        } else {
            format!(r#" stroke-dasharray="{}""#, dashes[j])
        };
        let _ = writeln!(
            s,
            r#"<line x1="{x:.1}" y1="{ly:.1}" x2="{:.1}" y2="{ly:.1}" stroke="{}" stroke-width="2"{dash}/><text x="{:.1}" y="{:.1}">{name}</text>"#,
            x + 18.0,
            colours[j],
            x + 22.0,
            ly + 4.0
        );
    }
    let _ = writeln!(
        s,
        r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">error against the closed form (max of |ΔL|/|L| and |ΔQ|; floor 1e-13) over t</text>"#,
        w / 2.0,
        h - 8.0
    );
    s.push_str("</svg>\n");
    s
}

/// Prints the table, or writes the table and the plot into the book with `--write`.
pub fn main() -> Res<()> {
    let (md, svg) = render()?;
    if std::env::args().any(|a| a == "--write") {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/book/src/generated");
        std::fs::write(format!("{dir}/closed_form.md"), &md)?;
        std::fs::write(format!("{dir}/closed_form_error.svg"), &svg)?;
        println!("wrote {dir}/closed_form.md and closed_form_error.svg");
    } else {
        print!("{md}");
    }
    Ok(())
}
