//! The body grammar: `KIND:ARGS[;mass=M|;density=D]`.
//!
//! | SPEC | body | mass / density |
//! |---|---|---|
//! | `principal:J1,…,JN` | diagonal mass tensor J = diag(J_i) | `mass=M` is reported (default 1), J as given |
//! | `tensor:J11,J12,…,JNN` | full symmetric mass tensor, row-major, in the body's own axes | as `principal` |
//! | `planes:I12,I13,…` | any positive plane moments, lexicographic (physical or not) | as `principal` |
//! | `tesseract:a,b,c,…` | unit point masses at the 2^N vertices (±a, ±b, …) (paper eq. 69) | `mass=M` rescales |
//! | `pentachoron:a,b,c,d` | unit point masses at the paper's eq. (73) points | `mass=M` |
//! | `simplex:N` | regular N-simplex, unit vertex masses, circumradius 1 | `mass=M` |
//! | `cuboid:a,b,…` | solid hyper-cuboid, half-lengths a, b, … | `density=D` (default 1) or `mass=M` |
//! | `ellipsoid:a,b,…` | solid ellipsoid, semi-axes a, b, … | `density=D` or `mass=M` |
//! | `ball:N,R` | solid N-ball of radius R | `density=D` or `mass=M` |
//! | `sphere:N,R` | hollow sphere S^(N−1) of radius R | surface `density=D` or `mass=M` |
//! | `points:FILE.csv` | point masses, one row `m,x1,…,xN` each | `mass=M` |
//! | `mesh:FILE` | uniform solid from a simplicial mesh (format below) | `density=D` or `mass=M` |
//!
//! Mesh files are text, one record per line, `#` starts a comment:
//! `v x1 … xN` is a vertex; `s i0 … iN` an N-simplex by N+1 vertex numbers (1-based, as in
//! OBJ files; any vertex order, the simplices must not overlap); `f i1 … iN` a facet of a
//! closed, consistently oriented boundary (use either `s` or `f` lines, not both).

use super::error::{CliError, CliResult};
use crate::algebra::MULTIVECTOR_MAX_DIM;
use crate::inertia::bodies::SimplexOrientation;
use crate::inertia::{Body, InertiaMap};
use crate::viz::Shape;
use nalgebra::{DMatrix, DVector};
use std::path::Path;

/// The grammar, printed in `--help` and in error messages.
pub const GRAMMAR: &str = "\
Body SPEC grammar: KIND:ARGS[;mass=M|;density=D]  (lengths are half-lengths / semi-axes / radii; density 1 by default)
  principal:J1,...,JN        diagonal mass tensor J (N >= 2)
  tensor:J11,J12,...,JNN     full symmetric mass tensor, row-major, in the body's own axes
  planes:I12,I13,...         any positive plane moments in lexicographic order 12,13,...,1N,23,... (physical or not)
  tesseract:a,b,c,...        unit point masses at the 2^N vertices (+-a, +-b, ...)
  pentachoron:a,b,c,d        unit point masses at the paper's eq. (73) points
  simplex:N                  regular N-simplex, unit vertex masses, circumradius 1
  cuboid:a,b,...             solid hyper-cuboid with half-lengths a, b, ...
  ellipsoid:a,b,...          solid ellipsoid with semi-axes a, b, ...
  ball:N,R                   solid N-ball of radius R
  sphere:N,R                 hollow sphere S^(N-1) of radius R (density per unit area)
  points:FILE.csv            point masses, one row m,x1,...,xN per mass ('#' comments)
  mesh:FILE                  solid simplicial mesh: lines 'v x1 ... xN' (vertex), 's i0 ... iN' (simplex,
                             1-based vertex numbers) or 'f i1 ... iN' (closed oriented boundary facet)
  mass=M rescales the body to total mass M (for principal/tensor/planes it is only reported);
  density=D applies to solids and shells. Examples: tesseract:1,1.2,1.5,2  cuboid:1,2,3,4;mass=5";

/// A parsed body: its inertia (always), and its mass properties when it is a real body.
#[derive(Clone, Debug)]
pub struct ParsedBody {
    /// The SPEC as given.
    pub spec: String,
    /// The dimension N.
    pub dim: usize,
    /// The mass properties (`None` for `planes:`, which gives only an inertia map).
    pub body: Option<Body>,
    /// The reported mass (the body's, or `mass=M`, default 1, for `planes:`).
    pub mass: f64,
    /// The inertia map in the body's own axes about the centre of mass.
    pub inertia: InertiaMap,
    kind: Kind,
}

#[derive(Clone, Debug)]
enum Kind {
    Moments,
    Planes,
    Cuboid(Vec<f64>),
    Points(Vec<Vec<f64>>),
    Solid {
        semi_axes: Vec<f64>,
        surface: bool,
    },
    Mesh {
        vertices: Vec<Vec<f64>>,
        edges: Vec<[usize; 2]>,
    },
    SolidCuboid(Vec<f64>),
}

/// The body kinds and their expected forms, for error messages.
const FORMS: [(&str, &str); 12] = [
    ("principal", "principal:J1,...,JN"),
    ("tensor", "tensor:J11,J12,...,JNN"),
    ("planes", "planes:I12,I13,..."),
    ("tesseract", "tesseract:a,b,c,..."),
    ("pentachoron", "pentachoron:a,b,c,d"),
    ("simplex", "simplex:N"),
    ("cuboid", "cuboid:a,b,..."),
    ("ellipsoid", "ellipsoid:a,b,..."),
    ("ball", "ball:N,R"),
    ("sphere", "sphere:N,R"),
    ("points", "points:FILE.csv"),
    ("mesh", "mesh:FILE"),
];

fn form(kind: &str) -> &'static str {
    FORMS
        .iter()
        .find(|(k, _)| *k == kind)
        .map_or("KIND:ARGS", |(_, f)| f)
}

fn bad(spec: &str, kind: &str, problem: impl std::fmt::Display) -> CliError {
    CliError::input(format!(
        "invalid body `{spec}`: {problem} (expected {}[;mass=M|;density=D])",
        form(kind)
    ))
}

/// Parses one number; rejects NaN and infinities.
pub fn parse_number(text: &str) -> Result<f64, String> {
    let t = text.trim();
    match t.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err(format!("`{t}` is not a finite number")),
        Err(_) if t.is_empty() => Err("a number is missing".to_string()),
        Err(_) => Err(format!("`{t}` is not a number")),
    }
}

/// Parses a comma-separated list of finite numbers.
pub fn parse_list(text: &str) -> Result<Vec<f64>, String> {
    text.split(',').map(parse_number).collect()
}

fn parse_dim(text: &str) -> Result<usize, String> {
    let t = text.trim();
    let n: usize = t
        .parse()
        .map_err(|_| format!("dimension `{t}` is not a whole number"))?;
    check_dim(n)?;
    Ok(n)
}

fn check_dim(n: usize) -> Result<(), String> {
    if !(2..=MULTIVECTOR_MAX_DIM).contains(&n) {
        return Err(format!(
            "dimension {n} is not supported (2 <= N <= {MULTIVECTOR_MAX_DIM})"
        ));
    }
    Ok(())
}

fn positive_list(text: &str, what: &str) -> Result<Vec<f64>, String> {
    let v = parse_list(text)?;
    check_dim(v.len()).map_err(|_| {
        format!(
            "{} {what} given; N = 2 … {MULTIVECTOR_MAX_DIM} are supported",
            v.len()
        )
    })?;
    if let Some(x) = v.iter().find(|x| **x <= 0.0) {
        return Err(format!("{what} must be positive, got {x}"));
    }
    Ok(v)
}

/// Parses a body SPEC, reading `points:` and `mesh:` files from the file system.
///
/// # Errors
/// [`CliError::Input`] naming the problem and the expected form.
pub fn parse_body(spec: &str) -> CliResult<ParsedBody> {
    parse_body_with(spec, &read_text)
}

/// Parses a body SPEC, reading the text of `points:` and `mesh:` files with `read_file`
/// (which returns the file's text or a one-line message). [`parse_body`] passes the file
/// system; tests and fuzz targets pass text held in memory.
///
/// # Errors
/// [`CliError::Input`] naming the problem and the expected form.
pub fn parse_body_with(
    spec: &str,
    read_file: &dyn Fn(&Path) -> Result<String, String>,
) -> CliResult<ParsedBody> {
    let mut parts = spec.split(';');
    let head = parts.next().unwrap_or("").trim();
    let Some((kind, args)) = head.split_once(':') else {
        return Err(CliError::input(format!(
            "invalid body `{spec}`: missing `KIND:` (expected KIND:ARGS[;mass=M|;density=D], KIND one of {})",
            kind_names()
        )));
    };
    let kind = kind.trim().to_ascii_lowercase();
    if !FORMS.iter().any(|(k, _)| *k == kind) {
        return Err(CliError::input(format!(
            "invalid body `{spec}`: unknown kind `{kind}` (expected one of {})",
            kind_names()
        )));
    }
    let (mut mass, mut density) = (None, None);
    for opt in parts {
        let opt = opt.trim();
        if opt.is_empty() {
            continue;
        }
        let (key, value) = opt
            .split_once('=')
            .ok_or_else(|| bad(spec, &kind, format!("option `{opt}` is not key=value")))?;
        let value = parse_number(value).map_err(|e| bad(spec, &kind, e))?;
        if value <= 0.0 {
            return Err(bad(
                spec,
                &kind,
                format!("{} must be positive, got {value}", key.trim()),
            ));
        }
        match key.trim() {
            "mass" if mass.is_none() => mass = Some(value),
            "density" if density.is_none() => density = Some(value),
            "mass" | "density" => {
                return Err(bad(spec, &kind, format!("`{}` is given twice", key.trim())));
            }
            other => return Err(bad(spec, &kind, format!("unknown option `{other}`"))),
        }
    }
    if mass.is_some() && density.is_some() {
        return Err(bad(spec, &kind, "give mass=M or density=D, not both"));
    }
    let e = |m: String| bad(spec, &kind, m);
    let no_density = |what: &str| -> CliResult<()> {
        if density.is_some() {
            Err(bad(
                spec,
                &kind,
                format!("density applies to solids and shells, not to {what}; use mass=M"),
            ))
        } else {
            Ok(())
        }
    };
    let rho = density.unwrap_or(1.0);
    let (body, kind_data): (Option<Body>, Kind) = match kind.as_str() {
        "principal" => {
            no_density("a given mass tensor")?;
            let j = parse_list(args).map_err(e)?;
            check_dim(j.len()).map_err(e)?;
            if let Some(x) = j.iter().find(|x| **x < 0.0) {
                return Err(e(format!(
                    "principal moments must not be negative, got {x}"
                )));
            }
            let m = mass.unwrap_or(1.0);
            let n = j.len();
            let body = Body::from_mass_properties(
                m,
                DVector::zeros(n),
                DMatrix::from_diagonal(&DVector::from_vec(j)),
                None,
            )
            .map_err(|err| e(err.to_string()))?;
            (Some(body), Kind::Moments)
        }
        "tensor" => {
            no_density("a given mass tensor")?;
            let v = parse_list(args).map_err(e)?;
            let n = (v.len() as f64).sqrt().round() as usize;
            if n * n != v.len() {
                return Err(e(format!(
                    "{} entries is not N*N for any N (row-major N×N matrix)",
                    v.len()
                )));
            }
            check_dim(n).map_err(e)?;
            let j = DMatrix::from_row_slice(n, n, &v);
            let body = Body::from_mass_properties(mass.unwrap_or(1.0), DVector::zeros(n), j, None)
                .map_err(|err| e(err.to_string()))?;
            (Some(body), Kind::Moments)
        }
        "planes" => {
            no_density("plane moments")?;
            let v = parse_list(args).map_err(e)?;
            if let Some(x) = v.iter().find(|x| **x <= 0.0) {
                return Err(e(format!("plane moments must be positive, got {x}")));
            }
            let inertia = InertiaMap::from_plane_moments(&v).map_err(|err| e(err.to_string()))?;
            let n = inertia.dim();
            check_dim(n).map_err(e)?;
            return Ok(ParsedBody {
                spec: spec.to_string(),
                dim: n,
                body: None,
                mass: mass.unwrap_or(1.0),
                inertia,
                kind: Kind::Planes,
            });
        }
        "tesseract" => {
            no_density("point masses")?;
            let a = positive_list(args, "half-edges").map_err(e)?;
            let body = Body::cuboid_vertices(&a, 1.0).map_err(|err| e(err.to_string()))?;
            (Some(body), Kind::Cuboid(a))
        }
        "pentachoron" => {
            no_density("point masses")?;
            let a = positive_list(args, "parameters").map_err(e)?;
            if a.len() != 4 {
                return Err(e(format!("{} parameters given, expected 4", a.len())));
            }
            let points = crate::inertia::bodies::pentachoron_vertices(a[0], a[1], a[2], a[3])
                .map_err(|err| e(err.to_string()))?;
            let body =
                Body::pentachoron(a[0], a[1], a[2], a[3]).map_err(|err| e(err.to_string()))?;
            (
                Some(body),
                Kind::Points(points.iter().map(|p| p.iter().copied().collect()).collect()),
            )
        }
        "simplex" => {
            no_density("point masses")?;
            let n = parse_dim(args).map_err(e)?;
            let points = crate::inertia::bodies::regular_simplex_positions(n, 1.0)
                .map_err(|err| e(err.to_string()))?;
            let body =
                Body::regular_simplex_vertices(n, 1.0, 1.0).map_err(|err| e(err.to_string()))?;
            (
                Some(body),
                Kind::Points(points.iter().map(|p| p.iter().copied().collect()).collect()),
            )
        }
        "cuboid" => {
            let a = positive_list(args, "half-lengths").map_err(e)?;
            let body = Body::solid_cuboid(&a, rho).map_err(|err| e(err.to_string()))?;
            (Some(body), Kind::SolidCuboid(a))
        }
        "ellipsoid" => {
            let a = positive_list(args, "semi-axes").map_err(e)?;
            let body = Body::solid_ellipsoid(&a, rho).map_err(|err| e(err.to_string()))?;
            (
                Some(body),
                Kind::Solid {
                    semi_axes: a,
                    surface: false,
                },
            )
        }
        "ball" | "sphere" => {
            let (n, r) = args
                .split_once(',')
                .ok_or_else(|| e("two arguments N,R are needed".to_string()))?;
            let n = parse_dim(n).map_err(e)?;
            let r = parse_number(r).map_err(e)?;
            if r <= 0.0 {
                return Err(e(format!("the radius must be positive, got {r}")));
            }
            let surface = kind == "sphere";
            let body = if surface {
                Body::hypersphere_shell(n, r, rho)
            } else {
                Body::solid_ball(n, r, rho)
            }
            .map_err(|err| e(err.to_string()))?;
            (
                Some(body),
                Kind::Solid {
                    semi_axes: vec![r; n],
                    surface,
                },
            )
        }
        "points" => {
            no_density("point masses")?;
            let path = Path::new(args.trim());
            let PointMasses { masses, positions } =
                parse_points_text(&read_file(path).map_err(e)?, &path.display().to_string())
                    .map_err(e)?;
            let body = Body::point_masses(&masses, &positions).map_err(|err| e(err.to_string()))?;
            let c = body.center_of_mass().clone();
            let points = positions
                .iter()
                .map(|p| (p - &c).iter().copied().collect())
                .collect();
            (Some(body), Kind::Points(points))
        }
        "mesh" => {
            let path = Path::new(args.trim());
            let mesh = parse_mesh_text(&read_file(path).map_err(e)?, &path.display().to_string())
                .map_err(e)?;
            let body = if mesh.facets {
                Body::closed_boundary_mesh(&mesh.vertices, &mesh.cells, rho)
            } else {
                Body::simplicial_mesh(
                    &mesh.vertices,
                    &mesh.cells,
                    rho,
                    SimplexOrientation::Unsigned,
                )
            }
            .map_err(|err| e(err.to_string()))?;
            let c = body.center_of_mass().clone();
            let vertices = mesh
                .vertices
                .iter()
                .map(|p| (p - &c).iter().copied().collect())
                .collect();
            let mut edges: Vec<[usize; 2]> = mesh
                .cells
                .iter()
                .flat_map(|cell| {
                    let cell = cell.clone();
                    (0..cell.len()).flat_map(move |a| {
                        let cell = cell.clone();
                        (a + 1..cell.len()).map(move |b| {
                            let (x, y) = (cell[a], cell[b]);
                            [x.min(y), x.max(y)]
                        })
                    })
                })
                .collect();
            edges.sort_unstable();
            edges.dedup();
            (Some(body), Kind::Mesh { vertices, edges })
        }
        _ => unreachable!("kinds are checked above"),
    };
    let mut body = body.expect("every physical kind builds a body");
    if let Some(m) = mass
        && !matches!(kind.as_str(), "principal" | "tensor")
    {
        body = body.with_mass(m).map_err(|err| e(err.to_string()))?;
    }
    check_dim(body.dim()).map_err(e)?;
    let inertia = InertiaMap::from_body(&body).map_err(|err| {
        bad(
            spec,
            &kind,
            format!(
                "the body is singular ({err}); a rigid body needs extent in at least N-1 directions"
            ),
        )
    })?;
    Ok(ParsedBody {
        spec: spec.to_string(),
        dim: body.dim(),
        mass: body.mass(),
        body: Some(body),
        inertia,
        kind: kind_data,
    })
}

fn kind_names() -> String {
    FORMS.iter().map(|(k, _)| *k).collect::<Vec<_>>().join(", ")
}

impl ParsedBody {
    /// Returns what to draw of the body, in its own axes about the centre of mass.
    pub fn shape(&self) -> Shape {
        let n = self.dim;
        match &self.kind {
            Kind::Cuboid(a) | Kind::SolidCuboid(a) => Shape::cuboid(a),
            Kind::Points(points) if points.len() <= 12 => Shape::complete_graph(points.clone()),
            Kind::Points(points) => Shape::cloud(n, points.clone()),
            Kind::Solid { semi_axes, surface } => Shape::ellipsoid(semi_axes, None, *surface, 1500),
            Kind::Mesh { vertices, edges } => Shape::wireframe(n, vertices.clone(), edges.clone()),
            Kind::Moments => {
                // The uniform ellipsoid with the same mass and mass tensor: J_i = m a_i²/(N+2).
                let body = self.body.as_ref().expect("moments kinds have a body");
                let (moments, axes) = body.principal_frame();
                let semi: Vec<f64> = moments
                    .iter()
                    .map(|j| ((n as f64 + 2.0) * j.max(0.0) / body.mass()).sqrt())
                    .collect();
                Shape::ellipsoid(&semi, Some(&axes), false, 1500)
            }
            Kind::Planes => Shape::cross(n, 1.0),
        }
    }
}

fn read_text(path: &Path) -> Result<String, String> {
    std::fs::read_to_string(path).map_err(|err| format!("cannot read `{}`: {err}", path.display()))
}

/// The point masses of a `points:` file.
#[derive(Clone, Debug, PartialEq)]
pub struct PointMasses {
    /// The masses, one per row.
    pub masses: Vec<f64>,
    /// The positions x1 … xN, one per row, all of the same dimension N ≥ 2.
    pub positions: Vec<DVector<f64>>,
}

/// Parses the text of a `points:` CSV: rows `m,x1,…,xN` with the same N ≥ 2, `#` comments
/// and blank lines ignored. `source` names the file in error messages (`source:line: …`).
/// The numbers are only checked to be finite here; [`Body::point_masses`] checks the rest.
///
/// # Errors
/// A one-line message naming the line and the problem.
pub fn parse_points_text(text: &str, source: &str) -> Result<PointMasses, String> {
    let mut masses = Vec::new();
    let mut positions = Vec::new();
    let mut width = None;
    for (line_no, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let row = parse_list(line).map_err(|err| format!("{source}:{}: {err}", line_no + 1))?;
        if row.len() < 3 || width.is_some_and(|w| w != row.len()) {
            return Err(format!(
                "{source}:{}: a row has {} values; every row must be m,x1,...,xN with the same N >= 2",
                line_no + 1,
                row.len()
            ));
        }
        width = Some(row.len());
        masses.push(row[0]);
        positions.push(DVector::from_column_slice(&row[1..]));
    }
    if masses.is_empty() {
        return Err(format!("{source} has no rows m,x1,...,xN"));
    }
    Ok(PointMasses { masses, positions })
}

/// The records of a `mesh:` file.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshRecords {
    /// The vertices (`v` records), all of the same dimension.
    pub vertices: Vec<DVector<f64>>,
    /// The cells, 0-based vertex numbers: N-simplices (`s`) or boundary facets (`f`).
    pub cells: Vec<Vec<usize>>,
    /// Whether the cells are boundary facets (`f`) rather than simplices (`s`).
    pub facets: bool,
}

/// Parses the text of a `mesh:` file (the format of the module docs). `source` names the
/// file in error messages (`source:line: …`). Only the records are checked here (numbers
/// finite, vertex numbers whole and ≥ 1, one record kind); the body constructors check
/// the geometry and that vertex numbers exist.
///
/// # Errors
/// A one-line message naming the line and the problem.
pub fn parse_mesh_text(text: &str, source: &str) -> Result<MeshRecords, String> {
    let mut vertices: Vec<DVector<f64>> = Vec::new();
    let mut cells = Vec::new();
    let mut tags = (false, false);
    for (line_no, line) in text.lines().enumerate() {
        let at = || format!("{source}:{}", line_no + 1);
        let line = line.split('#').next().unwrap_or("").trim();
        let mut words = line.split_whitespace();
        let Some(tag) = words.next() else { continue };
        let rest: Vec<&str> = words.collect();
        match tag {
            "v" => {
                let v = rest
                    .iter()
                    .map(|w| parse_number(w))
                    .collect::<Result<Vec<f64>, String>>()
                    .map_err(|err| format!("{}: {err}", at()))?;
                if vertices.first().is_some_and(|f| f.len() != v.len()) || v.is_empty() {
                    return Err(format!(
                        "{}: every vertex needs the same N coordinates",
                        at()
                    ));
                }
                vertices.push(DVector::from_vec(v));
            }
            "s" | "f" => {
                if tag == "s" {
                    tags.0 = true;
                } else {
                    tags.1 = true;
                }
                let cell = rest
                    .iter()
                    .map(|w| match w.parse::<usize>() {
                        Ok(k) if k >= 1 => Ok(k - 1),
                        _ => Err(format!(
                            "{}: `{w}` is not a vertex number (1-based whole number)",
                            at()
                        )),
                    })
                    .collect::<Result<Vec<usize>, String>>()?;
                cells.push(cell);
            }
            other => {
                return Err(format!(
                    "{}: unknown record `{other}` (expected `v x1 ... xN`, `s i0 ... iN` or `f i1 ... iN`)",
                    at()
                ));
            }
        }
    }
    if tags.0 && tags.1 {
        return Err(format!("{source} mixes `s` and `f` records; use one kind"));
    }
    if vertices.is_empty() || cells.is_empty() {
        return Err(format!("{source} needs `v` and `s` (or `f`) records"));
    }
    Ok(MeshRecords {
        vertices,
        cells,
        facets: tags.1,
    })
}
