//! `rotorflow inertia --body SPEC [--json]`: mass properties and the paper's tensors.

use super::error::{CliError, CliResult};
use super::output::{
    Format, emit, matrix_json, plane_names, report_format, to_json_text, vector_json,
};
use super::spec::{GRAMMAR, ParsedBody, parse_body};
use clap::Args;
use nalgebra::DVector;
use rotorflow::inertia::tensor::{ContractedInertia, ContractionNormalization, RankFourTensor};
use serde_json::{Value, json};
use std::path::PathBuf;

/// Arguments of `inertia`.
#[derive(Args, Debug, Clone)]
#[command(after_long_help = GRAMMAR)]
pub struct InertiaArgs {
    /// The body (see the grammar below), e.g. `tesseract:1,1.2,1.5,2`.
    #[arg(long, value_name = "SPEC")]
    pub body: String,
    /// Print JSON with keys dim, mass, volume, center_of_mass, mass_tensor, principal_moments,
    /// plane_moments, inertia_matrix, rank4, contracted, gyration_radii.
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
/// shells and, for N = 2, the contracted matrix (eq. 30 needs N ≥ 3).
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
            "principal_moments": Value::Null,
            "plane_names": plane_names(n),
            "plane_moments": parsed.inertia.plane_moments(),
            "principal_plane_moments": parsed.inertia.plane_moments(),
            "inertia_matrix": inertia_matrix,
            "rank4": Value::Null,
            "contracted": Value::Null,
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
    let (contracted, radii) = if n >= 3 {
        let ci = ContractedInertia::from_mass_tensor(j, ContractionNormalization::LeviCivita)
            .map_err(|e| fail(&e))?;
        let radii = ci.gyration_radii(body.mass()).map_err(|e| fail(&e))?;
        (matrix_json(ci.matrix()), vector_json(&radii))
    } else {
        (Value::Null, Value::Null)
    };
    let principal: DVector<f64> = body.principal_moments();
    Ok(json!({
        "dim": n,
        "spec": parsed.spec,
        "mass": body.mass(),
        "volume": body.volume(),
        "center_of_mass": vector_json(body.center_of_mass()),
        "mass_tensor": matrix_json(j),
        "principal_moments": vector_json(&principal),
        "plane_names": plane_names(n),
        "plane_moments": vector_json(&body.plane_moments()),
        "principal_plane_moments": vector_json(&body.principal_plane_moments()),
        "inertia_matrix": inertia_matrix,
        "rank4": rank4_json,
        "contracted": contracted,
        "gyration_radii": radii,
    }))
}

fn inertia_text(parsed: &ParsedBody, report: &Value) -> String {
    let mut out = format!("body {} (N = {})\n", parsed.spec, parsed.dim);
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
    out.push_str(&format!("mass                 {}\n", line(&report["mass"])));
    out.push_str(&format!(
        "volume               {}\n",
        line(&report["volume"])
    ));
    out.push_str(&format!(
        "centre of mass       {}\n",
        line(&report["center_of_mass"])
    ));
    out.push_str(&format!(
        "principal moments J  {}\n",
        line(&report["principal_moments"])
    ));
    out.push_str(&format!(
        "plane moments ({})  {}\n",
        plane_names(parsed.dim).join(","),
        line(&report["plane_moments"])
    ));
    if let Value::Array(rows) = &report["mass_tensor"] {
        out.push_str("mass tensor J (body's own axes)\n");
        for r in rows {
            out.push_str(&format!("  [{}]\n", line(r)));
        }
    }
    out.push_str("inertia matrix on bivectors (lexicographic planes)\n");
    if let Value::Array(rows) = &report["inertia_matrix"] {
        for r in rows {
            out.push_str(&format!("  [{}]\n", line(r)));
        }
    }
    if let Value::Array(rows) = &report["contracted"] {
        out.push_str("contracted matrix (paper eq. 24, Levi-Civita normalisation)\n");
        for r in rows {
            out.push_str(&format!("  [{}]\n", line(r)));
        }
    }
    out.push_str(&format!(
        "gyration radii       {}\n",
        line(&report["gyration_radii"])
    ));
    out.push_str("(the rank-4 tensor of eq. 22 is in the --json output, key rank4)\n");
    out
}
