//! `rotorflow inertia --body SPEC [--json]`: mass properties and the paper's tensors.

use super::error::{CliError, CliResult};
use super::output::{
    Format, emit, matrix_json, plane_names, report_format, to_json_text, vector_json,
};
use super::spec::{ParsedBody, parse_body};
use clap::Args;
use nalgebra::DVector;
use rotorflow::inertia::tensor::{ContractedInertia, ContractionNormalization, RankFourTensor};
use serde_json::{Value, json};
use std::path::PathBuf;

/// Arguments of `inertia`.
#[derive(Args, Debug, Clone)]
pub struct InertiaArgs {
    /// The body, e.g. `tesseract:1,1.2,1.5,2` (the grammar: `rotorflow help bodies`).
    #[arg(long, value_name = "SPEC")]
    pub body: String,
    /// Print JSON. Keys: dim, spec, mass, volume, center_of_mass; mass_tensor (J = ∫ x xᵀ dm,
    /// rows, body's own axes); second_moments (the eigenvalues J₁ ≤ … ≤ J_N of J);
    /// principal_axes (one unit axis per entry, in the order of second_moments);
    /// plane_names, plane_moments (Jᵢᵢ + Jⱼⱼ in the own axes, lexicographic planes);
    /// principal_plane_moments (Jᵢ + Jⱼ, the eigenvalues of the inertia map);
    /// moments_of_inertia (N = 3 only: I₁ = J₂ + J₃, I₂ = J₁ + J₃, I₃ = J₁ + J₂ about the
    /// principal axes, the classical principal moments; null otherwise); inertia_matrix (the
    /// map on bivectors); rank4 (the paper's eq. 22 tensor); contracted and
    /// contracted_factor (𝕀 = c_N (tr J · 1 − J), the paper's eq. 24, with c_N; null for
    /// N = 2); gyration_radii; principal_moments (deprecated: the same values as
    /// second_moments, kept for scripts written against rotorflow 0.1).
    #[arg(long)]
    pub json: bool,
    /// Write to FILE (whole or not at all) instead of standard output. Without --json the
    /// format follows the file name: .json → JSON, .txt, .md or anything else → text (.csv
    /// is refused); --json with a .txt or .md name is refused.
    #[arg(long, value_name = "FILE")]
    pub output: Option<PathBuf>,
}

/// Runs `inertia`.
///
/// # Errors
/// [`CliError::Input`] for a bad SPEC.
pub fn run(args: &InertiaArgs) -> CliResult<()> {
    let flag = args.json.then_some(Format::Json);
    let format = report_format(args.output.as_deref(), flag, false)?;
    let parsed = parse_body(&args.body)?;
    let report = inertia_json(&parsed)?;
    let text = if format == Format::Json {
        to_json_text(&report, true)?
    } else {
        inertia_text(&parsed, &report)
    };
    emit(args.output.as_deref(), &text)
}

/// Returns the JSON report of a body. Quantities a body given only by plane moments does not
/// have (mass tensor, the paper's tensors) are `null`; so are the volume of point sets and
/// shells, for N = 2 the contracted matrix (the paper's eq. 30 needs N ≥ 3), and for N ≠ 3
/// the classical moments of inertia.
///
/// # Errors
/// [`CliError::Runtime`] if a tensor view fails on a valid body (it does not).
pub fn inertia_json(parsed: &ParsedBody) -> CliResult<Value> {
    let n = parsed.dim;
    let inertia_matrix = matrix_json(&parsed.inertia.to_matrix());
    let Some(body) = &parsed.body else {
        return Ok(json!({
            "dim": n,
            "spec": parsed.spec,
            "mass": parsed.mass,
            "volume": Value::Null,
            "center_of_mass": vec![0.0; n],
            "mass_tensor": Value::Null,
            "second_moments": Value::Null,
            "principal_moments": Value::Null,
            "principal_axes": Value::Null,
            "plane_names": plane_names(n),
            "plane_moments": parsed.inertia.plane_moments(),
            "principal_plane_moments": parsed.inertia.plane_moments(),
            "moments_of_inertia": Value::Null,
            "inertia_matrix": inertia_matrix,
            "rank4": Value::Null,
            "contracted": Value::Null,
            "contracted_factor": Value::Null,
            "gyration_radii": Value::Null,
        }));
    };
    let fail = |e: &dyn std::fmt::Display| CliError::runtime(format!("tensor view failed: {e}"));
    let j = body.mass_tensor();
    let rank4 = RankFourTensor::from_mass_tensor(j).map_err(|e| fail(&e))?;
    let c = rank4.components();
    let rank4_json: Vec<Vec<Vec<Vec<f64>>>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|k| {
                    (0..n)
                        .map(|l| (0..n).map(|m| c[((i * n + k) * n + l) * n + m]).collect())
                        .collect()
                })
                .collect()
        })
        .collect();
    let normalization = ContractionNormalization::LeviCivita;
    let (contracted, factor, radii) = if n >= 3 {
        let ci = ContractedInertia::from_mass_tensor(j, normalization).map_err(|e| fail(&e))?;
        let radii = ci.gyration_radii(body.mass()).map_err(|e| fail(&e))?;
        (
            matrix_json(ci.matrix()),
            json!(normalization.factor(n)),
            vector_json(&radii),
        )
    } else {
        (Value::Null, Value::Null, Value::Null)
    };
    // The eigenvalues Jᵢ of the mass tensor (ascending) and the principal axes, the columns
    // of P with J = P diag(Jᵢ) Pᵀ.
    let (second, axes) = body.principal_frame();
    let axes_json: Vec<Vec<f64>> = (0..n)
        .map(|k| axes.column(k).iter().copied().collect())
        .collect();
    Ok(json!({
        "dim": n,
        "spec": parsed.spec,
        "mass": body.mass(),
        "volume": body.volume(),
        "center_of_mass": vector_json(body.center_of_mass()),
        "mass_tensor": matrix_json(j),
        "second_moments": vector_json(&second),
        // The 0.1 name of `second_moments`, kept so that existing scripts keep working; the
        // help and the book call it deprecated (it is not the moments of inertia).
        "principal_moments": vector_json(&second),
        "principal_axes": axes_json,
        "plane_names": plane_names(n),
        "plane_moments": vector_json(&body.plane_moments()),
        "principal_plane_moments": vector_json(&body.principal_plane_moments()),
        "moments_of_inertia": moments_of_inertia(&second),
        "inertia_matrix": inertia_matrix,
        "rank4": rank4_json,
        "contracted": contracted,
        "contracted_factor": factor,
        "gyration_radii": radii,
    }))
}

/// The classical moments of inertia about the principal axes for N = 3, I₁ = J₂ + J₃,
/// I₂ = J₁ + J₃, I₃ = J₁ + J₂ (the plane moment of the plane orthogonal to each axis), in
/// the order of the axes; `null` in other dimensions, where a rotation has planes, not axes.
fn moments_of_inertia(second: &DVector<f64>) -> Value {
    if second.len() != 3 {
        return Value::Null;
    }
    json!([
        second[1] + second[2],
        second[0] + second[2],
        second[0] + second[1]
    ])
}

fn inertia_text(parsed: &ParsedBody, report: &Value) -> String {
    let n = parsed.dim;
    let mut out = format!("body {} (N = {n})\n", parsed.spec);
    let line = |v: &Value| -> String {
        match v {
            Value::Null => "—".to_string(),
            Value::Array(a) => a
                .iter()
                .map(|x| match x.as_f64() {
                    Some(f) => format!("{f:.6}"),
                    None => x.to_string(),
                })
                .collect::<Vec<_>>()
                .join(", "),
            other => other.to_string(),
        }
    };
    let rows = |out: &mut String, title: &str, v: &Value| {
        if let Value::Array(rows) = v {
            out.push_str(title);
            out.push('\n');
            for r in rows {
                out.push_str(&format!("  [{}]\n", line(r)));
            }
        }
    };
    let field = |out: &mut String, label: &str, v: &Value| {
        out.push_str(&format!("{label:<54} {}\n", line(v)));
    };
    field(&mut out, "mass", &report["mass"]);
    field(&mut out, "volume", &report["volume"]);
    field(&mut out, "centre of mass", &report["center_of_mass"]);
    field(
        &mut out,
        "second moments J₁ ≤ … ≤ J_N (eigenvalues of J)",
        &report["second_moments"],
    );
    if !report["moments_of_inertia"].is_null() {
        field(
            &mut out,
            "moments of inertia I₁ = J₂+J₃, I₂ = J₁+J₃, I₃ = J₁+J₂",
            &report["moments_of_inertia"],
        );
    }
    field(
        &mut out,
        "principal plane moments Jᵢ + Jⱼ (planes ij)",
        &report["principal_plane_moments"],
    );
    field(
        &mut out,
        &format!("plane moments, own axes ({})", plane_names(n).join(",")),
        &report["plane_moments"],
    );
    rows(
        &mut out,
        "principal axes (one per row, in the order of J₁ … J_N; own axes)",
        &report["principal_axes"],
    );
    rows(
        &mut out,
        "mass tensor J = ∫ x xᵀ dm (body's own axes)",
        &report["mass_tensor"],
    );
    rows(
        &mut out,
        "inertia map on bivectors (lexicographic planes)",
        &report["inertia_matrix"],
    );
    if let Some(c) = report["contracted_factor"].as_f64() {
        rows(
            &mut out,
            &format!(
                "contracted matrix 𝕀 = c_N (tr J · 1 − J), c_N = {c} (the paper's eq. 24, Levi-Civita contraction)"
            ),
            &report["contracted"],
        );
    }
    field(&mut out, "gyration radii", &report["gyration_radii"]);
    out.push_str("(the rank-4 tensor of the paper's eq. 22 is in the --json output, key rank4)\n");
    out
}
