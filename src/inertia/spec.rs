//! The body SPEC grammar: a body written as one line of text, `KIND:ARGS[+mass=M|+density=D]`.
//!
//! The `rotorflow` command takes its bodies in this form (`--body`), and scene files can use
//! it too. [`parse_body`] turns a SPEC into the [`Body`] (mass properties) and the
//! [`InertiaMap`] about the centre of mass, in the body's own axes.
//!
//! | SPEC | body | mass / density |
//! |---|---|---|
//! | `principal:J1,…,JN` | diagonal mass tensor J = diag(Jᵢ) | `mass=M` is reported (default 1), J as given |
//! | `tensor:J11,J12,…,JNN` | full symmetric mass tensor, row-major, in the body's own axes | as `principal` |
//! | `planes:I12,I13,…` | any positive plane moments, lexicographic (physical or not) | as `principal` |
//! | `tesseract:a,b,c,…` | unit point masses at the 2ᴺ vertices (±a, ±b, …) (the paper's eq. 69) | `mass=M` rescales |
//! | `pentachoron:a,b,c,d` | unit point masses at the points of the paper's eq. (73) | `mass=M` |
//! | `simplex:N` | regular N-simplex, unit vertex masses, circumradius 1 | `mass=M` |
//! | `cuboid:a,b,…` | solid hyper-cuboid, half-lengths a, b, … | `density=D` (default 1) or `mass=M` |
//! | `ellipsoid:a,b,…` | solid ellipsoid, semi-axes a, b, … | `density=D` or `mass=M` |
//! | `ball:N,R` | solid N-ball of radius R | `density=D` or `mass=M` |
//! | `sphere:N,R` | hollow sphere Sᴺ⁻¹ of radius R | surface `density=D` or `mass=M` |
//! | `points:FILE.csv` | point masses, one row `m,x1,…,xN` each | `mass=M` |
//! | `mesh:FILE` | uniform solid from a simplicial mesh (format below) | `density=D` or `mass=M` |
//!
//! Options follow the arguments, each introduced by `+` (`cuboid:1,2,3,4+mass=5`), a
//! character shells leave alone; `;` works as well (`'cuboid:1,2,3,4;mass=5'`) but must be
//! quoted on a command line, where it ends the command. A `+` inside a number (`1e+3`) is
//! part of the number: only `+` followed by a `key=` starts an option.
//!
//! A `points:` file is CSV: one row `m,x1,…,xN` per point mass, `#` comments and blank lines
//! ignored. A first line of column names (no number in it) is skipped; when its first name is
//! empty (`,m,x,y,z`, as pandas' `DataFrame.to_csv` writes its index column) the first column
//! of every row is dropped. The columns are taken in the order m, x1, …, xN whatever their
//! names.
//!
//! Mesh files are text, one record per line, `#` starts a comment: `v x1 … xN` is a vertex;
//! `s i0 … iN` an N-simplex by N+1 vertex numbers (1-based, as in OBJ files; any vertex
//! order, the simplices must not overlap); `f i1 … iN` a facet of a closed, consistently
//! oriented boundary (use either `s` or `f` lines, not both).
//!
//! ```
//! use rotorflow::inertia::spec::parse_body;
//!
//! let parsed = parse_body("cuboid:0.5,1,1.5+mass=12").unwrap();
//! assert_eq!(parsed.dim, 3);
//! assert!((parsed.mass - 12.0).abs() < 1e-12);
//! // A comma before an option is refused with the right form in the message.
//! let err = parse_body("cuboid:1,2,3,4,mass=5").unwrap_err();
//! assert!(err.to_string().contains("+mass=5"));
//! ```

use super::SimplexOrientation;
use super::bodies;
use super::{Body, InertiaError, InertiaMap};
use crate::algebra::MULTIVECTOR_MAX_DIM;
use nalgebra::{DMatrix, DVector};
use std::path::Path;
use thiserror::Error;

/// Why a SPEC (or the text of a `points:` or `mesh:` file) was refused. Every message is one
/// line naming the problem and the expected form.
#[derive(Clone, Debug, Error, PartialEq)]
#[non_exhaustive]
pub enum SpecError {
    /// The SPEC has no `KIND:` prefix.
    #[error(
        "invalid body `{spec}`: missing `KIND:` (expected KIND:ARGS[+mass=M|+density=D], KIND one of {})",
        kind_names()
    )]
    MissingKind {
        /// The SPEC as given.
        spec: String,
    },
    /// The kind is not one of the grammar's.
    #[error(
        "invalid body `{spec}`: unknown kind `{kind}` (expected one of {})",
        kind_names()
    )]
    UnknownKind {
        /// The SPEC as given.
        spec: String,
        /// The kind as given (lower case).
        kind: String,
    },
    /// The arguments or options of a known kind are wrong, or they describe no body.
    #[error("invalid body `{spec}`: {problem} (expected {form}[+mass=M|+density=D])")]
    Invalid {
        /// The SPEC as given.
        spec: String,
        /// The expected form of this kind, e.g. `cuboid:a,b,...`.
        form: &'static str,
        /// What is wrong.
        problem: String,
    },
    /// A line of a `points:` or `mesh:` file is malformed (or the file has no records).
    #[error("{}", text_message(file, *line, problem))]
    Text {
        /// The name of the file (as given to the parser).
        file: String,
        /// The 1-based line, when one line is at fault.
        line: Option<usize>,
        /// What is wrong.
        problem: String,
    },
}

fn text_message(file: &str, line: Option<usize>, problem: &str) -> String {
    match line {
        Some(l) => format!("{file}:{l}: {problem}"),
        None => format!("{file}: {problem}"),
    }
}

/// What a parsed body looks like, for drawing it: the data of its kind, in the body's own
/// axes about the centre of mass.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Geometry {
    /// Only a mass tensor is known (`principal:`, `tensor:`).
    MassTensor,
    /// Only plane moments are known (`planes:`): there is no body to draw.
    PlaneMoments,
    /// A box with these half-lengths: the vertices of `tesseract:` or the solid `cuboid:`.
    Cuboid {
        /// The half-lengths.
        half_lengths: Vec<f64>,
        /// Whether the box is solid (`cuboid:`) rather than its vertices (`tesseract:`).
        solid: bool,
    },
    /// Point masses at these positions.
    Points(Vec<Vec<f64>>),
    /// An ellipsoid (solid or a shell) with these semi-axes.
    Ellipsoid {
        /// The semi-axes.
        semi_axes: Vec<f64>,
        /// Whether only the surface carries mass (`sphere:`).
        surface: bool,
    },
    /// A mesh: its vertices and the edges of its cells (0-based vertex pairs).
    Mesh {
        /// The vertices.
        vertices: Vec<Vec<f64>>,
        /// The edges, each pair sorted, without repetitions.
        edges: Vec<[usize; 2]>,
    },
}

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
    /// What the body looks like.
    pub geometry: Geometry,
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

fn kind_names() -> String {
    FORMS.iter().map(|(k, _)| *k).collect::<Vec<_>>().join(", ")
}

/// Parses one number of the grammar: a decimal or scientific literal as Rust's `f64` reads
/// it, surrounded by optional spaces; NaN and infinities are refused.
///
/// # Errors
/// A one-line message naming the text.
pub fn parse_number(text: &str) -> Result<f64, String> {
    let t = text.trim();
    match t.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err(format!("`{t}` is not a finite number")),
        Err(_) if t.is_empty() => Err("a number is missing".to_string()),
        Err(_) => Err(format!("`{t}` is not a number")),
    }
}

/// Parses a comma-separated list of numbers (see [`parse_number`]).
///
/// # Errors
/// A one-line message naming the first bad entry.
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

/// Returns whether `text` starts with `key=` (ASCII letters, optional spaces, `=`).
fn starts_with_key(text: &str) -> bool {
    let t = text.trim_start();
    let letters = t.len()
        - t.trim_start_matches(|c: char| c.is_ascii_alphabetic())
            .len();
    letters > 0 && t[letters..].trim_start().starts_with('=')
}

/// Splits a SPEC into its head `KIND:ARGS` and its options: every `;`, and every `+` that
/// starts a `key=` (so that `1e+3` stays one number), begins an option.
fn split_options(spec: &str) -> (&str, Vec<&str>) {
    let mut cuts = Vec::new();
    for (i, c) in spec.char_indices() {
        if c == ';' || (c == '+' && starts_with_key(&spec[i + 1..])) {
            cuts.push(i);
        }
    }
    let head_end = cuts.first().copied().unwrap_or(spec.len());
    let options = cuts
        .iter()
        .enumerate()
        .map(|(k, &start)| &spec[start + 1..cuts.get(k + 1).copied().unwrap_or(spec.len())])
        .collect();
    (&spec[..head_end], options)
}

/// The options of a SPEC.
#[derive(Clone, Copy, Debug, Default)]
struct Options {
    mass: Option<f64>,
    density: Option<f64>,
}

impl Options {
    fn parse(options: &[&str]) -> Result<Options, String> {
        let mut o = Options::default();
        for opt in options {
            let opt = opt.trim();
            if opt.is_empty() {
                continue;
            }
            let (key, value) = opt
                .split_once('=')
                .ok_or_else(|| format!("option `{opt}` is not key=value"))?;
            let key = key.trim();
            let slot = match key {
                "mass" => &mut o.mass,
                "density" => &mut o.density,
                other => {
                    return Err(format!(
                        "unknown option `{other}` (the options are mass=M and density=D)"
                    ));
                }
            };
            if slot.is_some() {
                return Err(format!("`{key}` is given twice"));
            }
            let value = parse_number(value)?;
            if value <= 0.0 {
                return Err(format!("{key} must be positive, got {value}"));
            }
            *slot = Some(value);
        }
        if o.mass.is_some() && o.density.is_some() {
            return Err("give mass=M or density=D, not both".into());
        }
        Ok(o)
    }

    /// Refuses a density for bodies that are not solids or shells.
    fn no_density(&self, what: &str) -> Result<(), String> {
        match self.density {
            Some(_) => Err(format!(
                "density applies to solids and shells, not to {what}; use +mass=M"
            )),
            None => Ok(()),
        }
    }

    fn density(&self) -> f64 {
        self.density.unwrap_or(1.0)
    }
}

/// Refuses an option written after a comma (`cuboid:1,2,3,4,mass=5`), naming the right form.
fn check_no_option_in_args(args: &str) -> Result<(), String> {
    match args.split(',').find(|item| starts_with_key(item)) {
        Some(item) => {
            let item = item.trim();
            Err(format!(
                "`{item}` follows a comma, but options are not arguments: write `+{item}` (or a quoted `;{item}`)"
            ))
        }
        None => Ok(()),
    }
}

/// Parses a body SPEC, reading `points:` and `mesh:` files from the file system.
///
/// # Errors
/// [`SpecError`] naming the problem and the expected form.
pub fn parse_body(spec: &str) -> Result<ParsedBody, SpecError> {
    parse_body_with(spec, &read_text)
}

fn read_text(path: &Path) -> Result<String, String> {
    std::fs::read_to_string(path).map_err(|err| format!("cannot read `{}`: {err}", path.display()))
}

/// Parses a body SPEC, reading the text of `points:` and `mesh:` files with `read_file`
/// (which returns the file's text or a one-line message). [`parse_body`] passes the file
/// system; tests and fuzz targets pass text held in memory.
///
/// # Errors
/// [`SpecError`] naming the problem and the expected form.
pub fn parse_body_with(
    spec: &str,
    read_file: &dyn Fn(&Path) -> Result<String, String>,
) -> Result<ParsedBody, SpecError> {
    let (head, options) = split_options(spec);
    let Some((kind, args)) = head.trim().split_once(':') else {
        return Err(SpecError::MissingKind { spec: spec.into() });
    };
    let kind = kind.trim().to_ascii_lowercase();
    let Some(&(kind, form)) = FORMS.iter().find(|(k, _)| *k == kind) else {
        return Err(SpecError::UnknownKind {
            spec: spec.into(),
            kind,
        });
    };
    let invalid = |problem: String| SpecError::Invalid {
        spec: spec.into(),
        form,
        problem,
    };
    check_no_option_in_args(args).map_err(invalid)?;
    let options = Options::parse(&options).map_err(invalid)?;
    if kind == "planes" {
        options.no_density("plane moments").map_err(invalid)?;
        let inertia = planes(args).map_err(invalid)?;
        return Ok(ParsedBody {
            spec: spec.into(),
            dim: inertia.dim(),
            body: None,
            mass: options.mass.unwrap_or(1.0),
            inertia,
            geometry: Geometry::PlaneMoments,
        });
    }
    let (body, geometry) = match kind {
        "principal" => principal(args, &options),
        "tensor" => tensor(args, &options),
        "tesseract" => tesseract(args, &options),
        "pentachoron" => pentachoron(args, &options),
        "simplex" => simplex(args, &options),
        "cuboid" => cuboid(args, &options),
        "ellipsoid" => ellipsoid(args, &options),
        "ball" | "sphere" => ball_or_sphere(args, &options, kind == "sphere"),
        "points" => points(args, &options, read_file),
        "mesh" => mesh(args, &options, read_file),
        _ => unreachable!("the kinds are those of FORMS"),
    }
    .map_err(invalid)?;
    let body = match options.mass {
        // A given mass tensor is taken as it is; its mass is only reported.
        Some(m) if !matches!(kind, "principal" | "tensor") => {
            body.with_mass(m).map_err(|err| invalid(err.to_string()))?
        }
        _ => body,
    };
    check_dim(body.dim()).map_err(invalid)?;
    let inertia = InertiaMap::from_body(&body).map_err(|err| {
        invalid(format!(
            "the body is singular ({err}); a rigid body needs extent in at least N-1 directions"
        ))
    })?;
    Ok(ParsedBody {
        spec: spec.into(),
        dim: body.dim(),
        mass: body.mass(),
        body: Some(body),
        inertia,
        geometry,
    })
}

/// The result of one kind's parser: the body (before `mass=M` is applied) and its geometry.
type Built = Result<(Body, Geometry), String>;

fn principal(args: &str, options: &Options) -> Built {
    options.no_density("a given mass tensor")?;
    let j = parse_list(args)?;
    check_dim(j.len())?;
    if let Some(x) = j.iter().find(|x| **x < 0.0) {
        return Err(format!(
            "second moments (mass-tensor eigenvalues) must not be negative, got {x}"
        ));
    }
    let n = j.len();
    let body = Body::from_mass_properties(
        options.mass.unwrap_or(1.0),
        DVector::zeros(n),
        DMatrix::from_diagonal(&DVector::from_vec(j)),
        None,
    )
    .map_err(|err| err.to_string())?;
    Ok((body, Geometry::MassTensor))
}

fn tensor(args: &str, options: &Options) -> Built {
    options.no_density("a given mass tensor")?;
    let v = parse_list(args)?;
    let n = (v.len() as f64).sqrt().round() as usize;
    if n * n != v.len() {
        return Err(format!(
            "{} entries is not N*N for any N (row-major N×N matrix)",
            v.len()
        ));
    }
    check_dim(n)?;
    let j = DMatrix::from_row_slice(n, n, &v);
    let body = Body::from_mass_properties(options.mass.unwrap_or(1.0), DVector::zeros(n), j, None)
        .map_err(|err| err.to_string())?;
    Ok((body, Geometry::MassTensor))
}

fn planes(args: &str) -> Result<InertiaMap, String> {
    let v = parse_list(args)?;
    if let Some(x) = v.iter().find(|x| **x <= 0.0) {
        return Err(format!("plane moments must be positive, got {x}"));
    }
    let inertia = InertiaMap::from_plane_moments(&v).map_err(|err| err.to_string())?;
    check_dim(inertia.dim())?;
    Ok(inertia)
}

fn tesseract(args: &str, options: &Options) -> Built {
    options.no_density("point masses")?;
    let a = positive_list(args, "half-edges")?;
    let body = Body::cuboid_vertices(&a, 1.0).map_err(|err| err.to_string())?;
    Ok((
        body,
        Geometry::Cuboid {
            half_lengths: a,
            solid: false,
        },
    ))
}

fn points_geometry(points: &[DVector<f64>]) -> Geometry {
    Geometry::Points(points.iter().map(|p| p.iter().copied().collect()).collect())
}

fn pentachoron(args: &str, options: &Options) -> Built {
    options.no_density("point masses")?;
    let a = positive_list(args, "parameters")?;
    if a.len() != 4 {
        return Err(format!("{} parameters given, expected 4", a.len()));
    }
    let points =
        bodies::pentachoron_vertices(a[0], a[1], a[2], a[3]).map_err(|err| err.to_string())?;
    let body = Body::pentachoron(a[0], a[1], a[2], a[3]).map_err(|err| err.to_string())?;
    Ok((body, points_geometry(&points)))
}

fn simplex(args: &str, options: &Options) -> Built {
    options.no_density("point masses")?;
    let n = parse_dim(args)?;
    let points = bodies::regular_simplex_positions(n, 1.0).map_err(|err| err.to_string())?;
    let body = Body::regular_simplex_vertices(n, 1.0, 1.0).map_err(|err| err.to_string())?;
    Ok((body, points_geometry(&points)))
}

fn cuboid(args: &str, options: &Options) -> Built {
    solid_of_axes(args, "half-lengths", options, Body::solid_cuboid, |a| {
        Geometry::Cuboid {
            half_lengths: a,
            solid: true,
        }
    })
}

fn ellipsoid(args: &str, options: &Options) -> Built {
    solid_of_axes(args, "semi-axes", options, Body::solid_ellipsoid, |a| {
        Geometry::Ellipsoid {
            semi_axes: a,
            surface: false,
        }
    })
}

/// A solid of uniform density given by a positive length per axis (`what` in messages).
fn solid_of_axes(
    args: &str,
    what: &str,
    options: &Options,
    body: fn(&[f64], f64) -> Result<Body, InertiaError>,
    geometry: fn(Vec<f64>) -> Geometry,
) -> Built {
    let a = positive_list(args, what)?;
    let body = body(&a, options.density()).map_err(|err| err.to_string())?;
    Ok((body, geometry(a)))
}

fn ball_or_sphere(args: &str, options: &Options, surface: bool) -> Built {
    let (n, r) = args
        .split_once(',')
        .ok_or_else(|| "two arguments N,R are needed".to_string())?;
    let n = parse_dim(n)?;
    let r = parse_number(r)?;
    if r <= 0.0 {
        return Err(format!("the radius must be positive, got {r}"));
    }
    let body = if surface {
        Body::hypersphere_shell(n, r, options.density())
    } else {
        Body::solid_ball(n, r, options.density())
    }
    .map_err(|err| err.to_string())?;
    Ok((
        body,
        Geometry::Ellipsoid {
            semi_axes: vec![r; n],
            surface,
        },
    ))
}

/// Returns `positions` relative to `center`, as plain coordinate lists.
fn centred(positions: &[DVector<f64>], center: &DVector<f64>) -> Vec<Vec<f64>> {
    positions
        .iter()
        .map(|p| (p - center).iter().copied().collect())
        .collect()
}

fn points(
    args: &str,
    options: &Options,
    read_file: &dyn Fn(&Path) -> Result<String, String>,
) -> Built {
    options.no_density("point masses")?;
    let path = Path::new(args.trim());
    let PointMasses { masses, positions } =
        parse_points_text(&read_file(path)?, &path.display().to_string())
            .map_err(|err| err.to_string())?;
    let body = Body::point_masses(&masses, &positions).map_err(|err| err.to_string())?;
    let points = centred(&positions, body.center_of_mass());
    Ok((body, Geometry::Points(points)))
}

fn mesh(
    args: &str,
    options: &Options,
    read_file: &dyn Fn(&Path) -> Result<String, String>,
) -> Built {
    let path = Path::new(args.trim());
    let mesh = parse_mesh_text(&read_file(path)?, &path.display().to_string())
        .map_err(|err| err.to_string())?;
    let rho = options.density();
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
    .map_err(|err| err.to_string())?;
    let vertices = centred(&mesh.vertices, body.center_of_mass());
    let mut edges: Vec<[usize; 2]> = Vec::new();
    for cell in &mesh.cells {
        for (a, &x) in cell.iter().enumerate() {
            for &y in &cell[a + 1..] {
                edges.push([x.min(y), x.max(y)]);
            }
        }
    }
    edges.sort_unstable();
    edges.dedup();
    Ok((body, Geometry::Mesh { vertices, edges }))
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
/// and blank lines ignored, an optional header line of column names (see the module docs;
/// an empty first name marks an index column, which is dropped). `file` names the file in
/// error messages (`file:line: …`). The numbers are only checked to be finite here;
/// [`Body::point_masses`] checks the rest.
///
/// # Errors
/// [`SpecError::Text`] naming the line and the problem.
pub fn parse_points_text(text: &str, file: &str) -> Result<PointMasses, SpecError> {
    let at = |line: usize, problem: String| SpecError::Text {
        file: file.into(),
        line: Some(line),
        problem,
    };
    let mut masses = Vec::new();
    let mut positions = Vec::new();
    let mut width = None;
    // Whether the first column is an index to drop (decided by the header).
    let mut skip_first = false;
    let mut first_line = true;
    for (line_no, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        if std::mem::take(&mut first_line) && is_header(line) {
            skip_first = line.split(',').next().is_some_and(|f| f.trim().is_empty());
            let names = line.split(',').count() - usize::from(skip_first);
            width = Some(names);
            continue;
        }
        let fields: Vec<&str> = line.split(',').skip(usize::from(skip_first)).collect();
        let row = fields
            .iter()
            .map(|f| parse_number(f))
            .collect::<Result<Vec<f64>, String>>()
            .map_err(|err| at(line_no + 1, err))?;
        if row.len() < 3 || width.is_some_and(|w| w != row.len()) {
            return Err(at(
                line_no + 1,
                format!(
                    "a row has {} values; every row must be m,x1,...,xN with the same N >= 2 (and as many as the header names)",
                    row.len()
                ),
            ));
        }
        width = Some(row.len());
        masses.push(row[0]);
        positions.push(DVector::from_column_slice(&row[1..]));
    }
    if masses.is_empty() {
        return Err(SpecError::Text {
            file: file.into(),
            line: None,
            problem: "no rows m,x1,...,xN".into(),
        });
    }
    Ok(PointMasses { masses, positions })
}

/// Whether a CSV line is a header: none of its fields is a number.
fn is_header(line: &str) -> bool {
    line.split(',').all(|f| f.trim().parse::<f64>().is_err())
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

/// Parses the text of a `mesh:` file (the format of the module docs). `file` names the file
/// in error messages (`file:line: …`). Only the records are checked here (numbers finite,
/// vertex numbers whole and ≥ 1, one record kind); the body constructors check the geometry
/// and that vertex numbers exist.
///
/// # Errors
/// [`SpecError::Text`] naming the line and the problem.
pub fn parse_mesh_text(text: &str, file: &str) -> Result<MeshRecords, SpecError> {
    let mut vertices: Vec<DVector<f64>> = Vec::new();
    let mut cells = Vec::new();
    let (mut simplices, mut facets) = (false, false);
    for (line_no, line) in text.lines().enumerate() {
        let at = |problem: String| SpecError::Text {
            file: file.into(),
            line: Some(line_no + 1),
            problem,
        };
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
                    .map_err(at)?;
                if vertices.first().is_some_and(|f| f.len() != v.len()) || v.is_empty() {
                    return Err(at("every vertex needs the same N coordinates".into()));
                }
                vertices.push(DVector::from_vec(v));
            }
            "s" | "f" => {
                if tag == "s" {
                    simplices = true;
                } else {
                    facets = true;
                }
                let cell = rest
                    .iter()
                    .map(|w| match w.parse::<usize>() {
                        Ok(k) if k >= 1 => Ok(k - 1),
                        _ => Err(at(format!(
                            "`{w}` is not a vertex number (1-based whole number)"
                        ))),
                    })
                    .collect::<Result<Vec<usize>, SpecError>>()?;
                cells.push(cell);
            }
            other => {
                return Err(at(format!(
                    "unknown record `{other}` (expected `v x1 ... xN`, `s i0 ... iN` or `f i1 ... iN`)"
                )));
            }
        }
    }
    let whole = |problem: &str| SpecError::Text {
        file: file.into(),
        line: None,
        problem: problem.into(),
    };
    if simplices && facets {
        return Err(whole("mixes `s` and `f` records; use one kind"));
    }
    if vertices.is_empty() || cells.is_empty() {
        return Err(whole("needs `v` and `s` (or `f`) records"));
    }
    Ok(MeshRecords {
        vertices,
        cells,
        facets,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mass_tensor_diagonal(spec: &str) -> Vec<f64> {
        let parsed = parse_body(spec).unwrap();
        let j = parsed.body.unwrap().mass_tensor().clone();
        (0..parsed.dim).map(|i| j[(i, i)]).collect()
    }

    #[test]
    fn plus_and_quoted_semicolon_give_the_same_body() {
        // A solid cuboid with half-lengths a has Jᵢ = m aᵢ²/3.
        for spec in ["cuboid:0.5,1,1.5+mass=12", "cuboid:0.5,1,1.5;mass=12"] {
            let j = mass_tensor_diagonal(spec);
            for (got, want) in j.iter().zip([1.0, 4.0, 9.0]) {
                assert!((got - want).abs() < 1e-12, "{spec}: {j:?}");
            }
        }
        // density D: mass = D · volume = 2 · (2·3·4)·... for half-lengths 1, 1.5, 2.
        let p = parse_body("cuboid:1,1.5,2+density=2").unwrap();
        assert!((p.mass - 2.0 * 2.0 * 3.0 * 4.0).abs() < 1e-12, "{}", p.mass);
    }

    #[test]
    fn a_plus_inside_a_number_is_part_of_the_number() {
        let p = parse_body("cuboid:1e+0,1.5,2+density=2").unwrap();
        assert!((p.mass - 48.0).abs() < 1e-12);
        let j = mass_tensor_diagonal("principal:1e+0,+2,3");
        assert_eq!(j, vec![1.0, 2.0, 3.0]);
    }

    #[test]
    fn an_option_after_a_comma_names_the_right_form() {
        let err = parse_body("cuboid:1,2,3,4,mass=5").unwrap_err().to_string();
        assert!(
            err.contains("`+mass=5`") && err.contains("`;mass=5`"),
            "{err}"
        );
        let err = parse_body("ball:3,1, density=2").unwrap_err().to_string();
        assert!(err.contains("`+density=2`"), "{err}");
    }

    #[test]
    fn bad_options_are_refused() {
        let cases = [
            ("cuboid:1,2+mass=1+density=2", "not both"),
            ("cuboid:1,2+mass=1;mass=2", "given twice"),
            ("cuboid:1,2+mas=1", "unknown option `mas`"),
            ("cuboid:1,2+mass=-1", "mass must be positive"),
            ("tesseract:1,2+density=2", "density applies to solids"),
            ("cuboid:1,2;mass", "not key=value"),
        ];
        for (spec, want) in cases {
            let err = parse_body(spec).unwrap_err();
            assert!(matches!(err, SpecError::Invalid { .. }), "{spec}: {err:?}");
            assert!(err.to_string().contains(want), "{spec}: {err}");
        }
        assert!(matches!(
            parse_body("cube:1,2"),
            Err(SpecError::UnknownKind { .. })
        ));
        assert!(matches!(
            parse_body("1,2"),
            Err(SpecError::MissingKind { .. })
        ));
    }

    #[test]
    fn points_with_a_header_and_an_index_column() {
        let plain = "1,1,0,0\n1,-1,0,0\n2,0,1,0\n2,0,-1,0\n";
        let named = format!("m,x,y,z\n{plain}");
        let pandas = ",m,x,y,z\n0,1,1,0,0\n1,1,-1,0,0\n2,2,0,1,0\n3,2,0,-1,0\n";
        let want = parse_points_text(plain, "p.csv").unwrap();
        assert_eq!(want.masses, vec![1.0, 1.0, 2.0, 2.0]);
        assert_eq!(parse_points_text(&named, "p.csv").unwrap(), want);
        assert_eq!(parse_points_text(pandas, "p.csv").unwrap(), want);
        // A row that does not match the header's width, and a bad number after a header.
        let err = parse_points_text("m,x,y\n1,0,0,0\n", "p.csv").unwrap_err();
        assert!(
            matches!(err, SpecError::Text { line: Some(2), .. }),
            "{err}"
        );
        let err = parse_points_text("m,x,y\n1,0,zz\n", "p.csv").unwrap_err();
        assert!(err.to_string().starts_with("p.csv:2: `zz`"), "{err}");
        // A first row with a number in it is data, not a header.
        assert!(parse_points_text("1,2,x\n1,0,0\n", "p.csv").is_err());
        assert!(parse_points_text("m,x,y\n", "p.csv").is_err());
    }

    #[test]
    fn mesh_records() {
        let text = "v 0 0\nv 1 0\nv 0 1\ns 1 2 3 # one triangle\n";
        let m = parse_mesh_text(text, "t.mesh").unwrap();
        assert_eq!(m.cells, vec![vec![0, 1, 2]]);
        assert!(!m.facets);
        let err = parse_mesh_text("v 0 0\ns 0 1 2\n", "t.mesh").unwrap_err();
        assert_eq!(
            err.to_string(),
            "t.mesh:2: `0` is not a vertex number (1-based whole number)"
        );
        let body = parse_body_with("mesh:t.mesh+density=2", &|_| Ok(text.into())).unwrap();
        assert!((body.mass - 1.0).abs() < 1e-12, "{}", body.mass);
        match body.geometry {
            Geometry::Mesh { edges, .. } => assert_eq!(edges, vec![[0, 1], [0, 2], [1, 2]]),
            other => panic!("{other:?}"),
        }
    }
}
