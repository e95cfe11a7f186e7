//! The scene file: TOML read into [`Scene`], every key checked, with one-line errors that
//! name the file, the section (`body "cube"`, `plane 2`, …) and the key.

use super::SceneError;
use crate::dynamics::motion::ContactShape;
use crate::dynamics::motion::shape::{CompoundShape, ConvexShape, Piece};
use crate::inertia::spec::{ParsedBody, parse_body, parse_body_with};
use nalgebra::DMatrix;
use serde::Deserialize;
use std::path::Path;
use toml::Value;

/// The integrator of a scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IntegratorKind {
    /// The symplectic Strang splitting (contact and joints).
    Splitting,
    /// Runge–Kutta–Munthe-Kaas of order 4 (forques only).
    Rk4,
    /// The soft step: substeps of soft contacts, a fixed solver cost per step (planes and
    /// contact between bodies, no joints).
    Soft,
}

impl IntegratorKind {
    /// The name in the scene file.
    pub fn name(self) -> &'static str {
        match self {
            IntegratorKind::Splitting => "splitting",
            IntegratorKind::Rk4 => "rk4",
            IntegratorKind::Soft => "soft",
        }
    }
}

/// A body of the scene.
#[derive(Clone, Debug)]
pub struct SceneBody {
    /// Its unique name.
    pub name: String,
    /// Its SPEC, parsed (with `+mass=M` appended when the scene gives a mass).
    pub parsed: ParsedBody,
    /// Its mass.
    pub mass: f64,
    /// The centre of mass at t = 0.
    pub position: Vec<f64>,
    /// The velocity of the centre of mass at t = 0.
    pub velocity: Vec<f64>,
    /// The angular velocity at t = 0, in the body's own axes.
    pub omega: Vec<f64>,
    /// The attitude at t = 0 (own axes → space).
    pub attitude: DMatrix<f64>,
    /// Its friction coefficient against other bodies (None: the other's).
    pub friction: Option<f64>,
    /// Its restitution against other bodies (None: the other's).
    pub restitution: Option<f64>,
    /// True for a body that never moves.
    pub fixed: bool,
    /// False for a body that touches nothing.
    pub collide: bool,
    /// The shape it touches with, when the scene gives one (`contact`) instead of its
    /// SPEC's.
    pub contact: Option<ContactShape>,
}

impl SceneBody {
    /// The shape the body touches with: the scene's `contact`, else its SPEC's
    /// ([`ContactShape::from_geometry`]).
    pub fn contact_shape(&self) -> ContactShape {
        self.contact
            .clone()
            .unwrap_or_else(|| ContactShape::from_geometry(&self.parsed.geometry))
    }
}

/// A plane n·x = d bounding solid world on the side opposite to n.
#[derive(Clone, Debug)]
pub struct ScenePlane {
    /// The normal n (as given).
    pub normal: Vec<f64>,
    /// The offset d.
    pub offset: f64,
    /// Coulomb friction μ ≥ 0.
    pub friction: f64,
    /// Restitution e ∈ [0, 1].
    pub restitution: f64,
}

/// The other end of a spring or a joint.
#[derive(Clone, Debug)]
pub enum SceneAnchor {
    /// A fixed point of space.
    World(Vec<f64>),
    /// A point (own axes) of another body, by index.
    Body(usize, Vec<f64>),
}

/// A Hooke spring with damping.
#[derive(Clone, Debug)]
pub struct SceneSpring {
    /// The body, by index.
    pub body: usize,
    /// The attachment point, own axes.
    pub point: Vec<f64>,
    /// The other end.
    pub anchor: SceneAnchor,
    /// Stiffness k ≥ 0.
    pub stiffness: f64,
    /// Rest length ℓ₀ ≥ 0.
    pub rest_length: f64,
    /// Damping c ≥ 0.
    pub damping: f64,
}

/// A ball joint.
#[derive(Clone, Debug)]
pub struct SceneJoint {
    /// The body, by index.
    pub body: usize,
    /// The jointed point, own axes.
    pub point: Vec<f64>,
    /// What it is held on.
    pub other: SceneAnchor,
}

/// A checked scene.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The file the scene was read from, as messages name it.
    pub file: String,
    /// The dimension N.
    pub dim: usize,
    /// Uniform gravity g.
    pub gravity: Vec<f64>,
    /// The end time.
    pub t_end: f64,
    /// The step.
    pub dt: f64,
    /// The integrator.
    pub integrator: IntegratorKind,
    /// The bodies.
    pub bodies: Vec<SceneBody>,
    /// The planes.
    pub planes: Vec<ScenePlane>,
    /// The springs.
    pub springs: Vec<SceneSpring>,
    /// The ball joints.
    pub joints: Vec<SceneJoint>,
}

/// The most steps a scene may ask for (t_end / dt).
pub const MAX_STEPS: f64 = 1e8;

// The keys of each table. The fields are read one by one below so that every message names
// its key; serde refuses the keys that are not listed.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    dim: Option<Value>,
    gravity: Option<Value>,
    t_end: Option<Value>,
    dt: Option<Value>,
    integrator: Option<Value>,
    body: Option<Value>,
    plane: Option<Value>,
    spring: Option<Value>,
    joint: Option<Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBody {
    name: Option<Value>,
    shape: Option<Value>,
    mass: Option<Value>,
    position: Option<Value>,
    velocity: Option<Value>,
    omega: Option<Value>,
    attitude: Option<Value>,
    friction: Option<Value>,
    restitution: Option<Value>,
    fixed: Option<Value>,
    collide: Option<Value>,
    contact: Option<Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPlane {
    normal: Option<Value>,
    offset: Option<Value>,
    friction: Option<Value>,
    restitution: Option<Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSpring {
    body: Option<Value>,
    point: Option<Value>,
    anchor: Option<Value>,
    other: Option<Value>,
    other_point: Option<Value>,
    stiffness: Option<Value>,
    rest_length: Option<Value>,
    damping: Option<Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawJoint {
    body: Option<Value>,
    point: Option<Value>,
    anchor: Option<Value>,
    other: Option<Value>,
    other_point: Option<Value>,
}

/// Where a key is: the file and the section, for messages.
struct Place<'a> {
    file: &'a str,
    section: String,
}

impl Place<'_> {
    fn error(&self, message: impl std::fmt::Display) -> SceneError {
        if self.section.is_empty() {
            SceneError::invalid(format!("{}: {message}", self.file))
        } else {
            SceneError::invalid(format!("{}: {}: {message}", self.file, self.section))
        }
    }

    /// Reads a table into its raw struct, refusing unknown keys.
    fn table<T: for<'de> Deserialize<'de>>(
        &self,
        value: &Value,
        what: &str,
    ) -> Result<T, SceneError> {
        if !value.is_table() {
            return Err(self.error(format!(
                "expected a table (`[[{what}]]`), got {}",
                a_type(value)
            )));
        }
        value.clone().try_into::<T>().map_err(|e| {
            let m = one_line(e.message()).replace("unknown field", "unknown key");
            self.error(m)
        })
    }

    fn required<'v>(&self, key: &str, v: &'v Option<Value>) -> Result<&'v Value, SceneError> {
        v.as_ref()
            .ok_or_else(|| self.error(format!("missing key `{key}`")))
    }

    fn number(&self, key: &str, v: &Value) -> Result<f64, SceneError> {
        let x = match v {
            Value::Integer(i) => *i as f64,
            Value::Float(x) => *x,
            other => {
                return Err(self.error(format!("{key} must be a number, got {}", a_type(other))));
            }
        };
        if !x.is_finite() {
            return Err(self.error(format!("{key} is {x}, expected a finite number")));
        }
        Ok(x)
    }

    /// A number with a default, checked by `ok` (which describes the allowed range).
    fn number_in(
        &self,
        key: &str,
        v: &Option<Value>,
        default: Option<f64>,
        range: (&str, fn(f64) -> bool),
    ) -> Result<f64, SceneError> {
        let x = match (v, default) {
            (Some(v), _) => self.number(key, v)?,
            (None, Some(d)) => return Ok(d),
            (None, None) => return Err(self.error(format!("missing key `{key}`"))),
        };
        if !(range.1)(x) {
            return Err(self.error(format!("{key} must be {}, got {x}", range.0)));
        }
        Ok(x)
    }

    fn list(&self, key: &str, v: &Value, expected: &str) -> Result<Vec<f64>, SceneError> {
        let Value::Array(items) = v else {
            return Err(self.error(format!(
                "{key} must be a list of numbers ({expected}), got {}",
                a_type(v)
            )));
        };
        items
            .iter()
            .enumerate()
            .map(|(k, x)| self.number(&format!("{key} component {}", k + 1), x))
            .collect()
    }

    /// A vector of `n` numbers (default zero).
    fn vector(&self, key: &str, v: &Option<Value>, n: usize) -> Result<Vec<f64>, SceneError> {
        let Some(v) = v else {
            return Ok(vec![0.0; n]);
        };
        let x = self.list(key, v, &format!("{n} components"))?;
        if x.len() != n {
            return Err(self.error(format!(
                "{key} has {} components, expected {n} (dim = {n})",
                x.len()
            )));
        }
        Ok(x)
    }

    fn string<'v>(&self, key: &str, v: &'v Value) -> Result<&'v str, SceneError> {
        v.as_str()
            .ok_or_else(|| self.error(format!("{key} must be a string, got {}", a_type(v))))
    }

    /// An array of tables (`[[body]]`), or none. `text` is the file, to find the line of a
    /// single table `[body]` written where `[[body]]` was meant.
    fn tables<'v>(
        &self,
        text: &str,
        key: &str,
        v: &'v Option<Value>,
    ) -> Result<&'v [Value], SceneError> {
        match v {
            None => Ok(&[]),
            Some(Value::Array(a)) => Ok(a),
            Some(Value::Table(_)) => {
                let header = format!("[{key}]");
                let line = text.lines().position(|l| {
                    l.trim_start()
                        .strip_prefix(header.as_str())
                        .map(str::trim_start)
                        .is_some_and(|rest| rest.is_empty() || rest.starts_with('#'))
                });
                let at = line.map_or(String::new(), |l| format!(":{}", l + 1));
                Err(SceneError::invalid(format!(
                    "{}{at}: `[{key}]` is a single table; write `[[{key}]]` (double brackets, one \
                     `[[{key}]]` per {key})",
                    self.file
                )))
            }
            Some(other) => Err(self.error(format!(
                "{key} must be an array of tables (`[[{key}]]`, one per {key}), got {}",
                a_type(other)
            ))),
        }
    }
}

/// The TOML type of `v` with its article: "an integer", "a string", ….
fn a_type(v: &Value) -> String {
    let t = v.type_str();
    let article = if t.starts_with(['a', 'e', 'i', 'o', 'u']) {
        "an"
    } else {
        "a"
    };
    format!("{article} {t}")
}

fn positive(x: f64) -> bool {
    x > 0.0
}

fn non_negative(x: f64) -> bool {
    x >= 0.0
}

fn unit_interval(x: f64) -> bool {
    (0.0..=1.0).contains(&x)
}

/// Joins a multi-line message into one line.
fn one_line(text: &str) -> String {
    text.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ")
}

/// Returns the 1-based line and column of byte `offset` of `text`.
fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut end = offset.min(text.len());
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    let before = &text[..end];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

/// Reads the scene file `path`, its `points:` and `mesh:` shapes from the file system.
///
/// # Errors
/// [`SceneError::Invalid`] naming the file, the section and the key.
pub fn load(path: &Path) -> Result<Scene, SceneError> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path)
        .map_err(|e| SceneError::invalid(format!("{file}: cannot read the scene file: {e}")))?;
    parse(&text, &file, None)
}

/// The reader of the files a body SPEC names (`points:`, `mesh:`): their text, or a
/// one-line message; `None` reads the file system.
pub type FileReader<'a> = Option<&'a dyn Fn(&Path) -> Result<String, String>>;

/// Parses and checks the scene `text` (read from `file`, named in messages), reading the
/// files of `points:` and `mesh:` shapes with `read_file`.
///
/// # Errors
/// [`SceneError::Invalid`] naming the file, the section and the key, in one line: names and
/// strings quoted from the file have their control characters escaped.
pub fn parse(text: &str, file: &str, read_file: FileReader<'_>) -> Result<Scene, SceneError> {
    read_scene(text, file, read_file).map_err(|e| match e {
        SceneError::Invalid(message) => SceneError::Invalid(printable(&message)),
        other => other,
    })
}

/// Returns `text` with its control characters (line breaks among them) escaped.
fn printable(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_control() {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

fn read_scene(text: &str, file: &str, read_file: FileReader<'_>) -> Result<Scene, SceneError> {
    let top = Place {
        file,
        section: String::new(),
    };
    let table: toml::Table = toml::from_str(text).map_err(|e| {
        let at = e.span().map(|s| line_column(text, s.start));
        let message = one_line(e.message());
        match at {
            Some((l, c)) => {
                let line = text.lines().nth(l - 1).unwrap_or("").trim();
                SceneError::invalid(format!(
                    "{file}:{l}:{c}: {message} (in `{line}`; expected TOML)"
                ))
            }
            None => SceneError::invalid(format!("{file}: {message} (expected TOML)")),
        }
    })?;
    let raw: RawScene = top.table(&Value::Table(table), "scene")?;

    let dim_value = top.required("dim", &raw.dim)?;
    let max = crate::algebra::MAX_DIM;
    let dim = match dim_value {
        Value::Integer(d) if (2..=max as i64).contains(d) => *d as usize,
        Value::Integer(d) => {
            return Err(top.error(format!("dim must be an integer from 2 to {max}, got {d}")));
        }
        other => {
            return Err(top.error(format!(
                "dim must be an integer from 2 to {max}, got {}",
                a_type(other)
            )));
        }
    };
    let gravity = top.vector("gravity", &raw.gravity, dim)?;
    let t_end = top.number_in("t_end", &raw.t_end, None, ("> 0", positive))?;
    let dt = top.number_in("dt", &raw.dt, None, ("> 0", positive))?;
    if t_end / dt > MAX_STEPS {
        return Err(top.error(format!(
            "dt = {dt} takes {:.3e} steps to t_end = {t_end}; at most {MAX_STEPS:e} are allowed",
            t_end / dt
        )));
    }
    let integrator = match &raw.integrator {
        None => IntegratorKind::Splitting,
        Some(v) => match top.string("integrator", v)? {
            "splitting" => IntegratorKind::Splitting,
            "rk4" => IntegratorKind::Rk4,
            "soft" => IntegratorKind::Soft,
            other => {
                return Err(top.error(format!(
                    "integrator `{other}` is unknown (expected \"splitting\", \"rk4\" or \"soft\")"
                )));
            }
        },
    };

    let body_tables = top.tables(text, "body", &raw.body)?;
    if body_tables.is_empty() {
        return Err(top.error("no [[body]]: a scene needs at least one body"));
    }
    let mut bodies: Vec<SceneBody> = Vec::with_capacity(body_tables.len());
    for (k, t) in body_tables.iter().enumerate() {
        let body = read_body(file, k, t, dim, read_file)?;
        if bodies.iter().any(|b| b.name == body.name) {
            return Err(SceneError::invalid(format!(
                "{file}: body {}: name \"{}\" is used twice (body names must be unique)",
                k + 1,
                body.name
            )));
        }
        bodies.push(body);
    }
    let names: Vec<&str> = bodies.iter().map(|b| b.name.as_str()).collect();

    let planes = top
        .tables(text, "plane", &raw.plane)?
        .iter()
        .enumerate()
        .map(|(k, t)| read_plane(file, k, t, dim))
        .collect::<Result<Vec<_>, SceneError>>()?;
    let springs = top
        .tables(text, "spring", &raw.spring)?
        .iter()
        .enumerate()
        .map(|(k, t)| read_spring(file, k, t, dim, &names))
        .collect::<Result<Vec<_>, SceneError>>()?;
    let joints = top
        .tables(text, "joint", &raw.joint)?
        .iter()
        .enumerate()
        .map(|(k, t)| read_joint(file, k, t, dim, &names))
        .collect::<Result<Vec<_>, SceneError>>()?;
    check_step(&top, dt, t_end, &bodies, &springs)?;
    if integrator == IntegratorKind::Rk4 && !(planes.is_empty() && joints.is_empty()) {
        return Err(top.error(
            "integrator \"rk4\" integrates forces and springs only; a scene with [[plane]] or \
             [[joint]] needs integrator = \"splitting\"",
        ));
    }
    if integrator == IntegratorKind::Soft && !joints.is_empty() {
        return Err(top.error(
            "integrator \"soft\" holds no joints; a scene with [[joint]] needs integrator = \"splitting\"",
        ));
    }
    Ok(Scene {
        file: file.to_string(),
        dim,
        gravity,
        t_end,
        dt,
        integrator,
        bodies,
        planes,
        springs,
        joints,
    })
}

/// The largest step a scene may take, as a fraction of the period 2π√(m_eff/k) of its
/// stiffest spring. The splitting is stable up to a third of the period (ω dt < 2), but the
/// energy of an undamped spring swings by about (ω dt)²/4 of itself: 10 % at a tenth of the
/// period (ω dt ≈ 0.63); beyond that a run says little about the scene.
pub const MAX_STEP_PER_PERIOD: f64 = 0.1;

/// Refuses a step the scene cannot take: one that reaches `t_end` (the run would be a single
/// step), or one longer than [`MAX_STEP_PER_PERIOD`] of a spring's period. The period is the
/// one of the spring's translational mode, 2π√(m_eff/k) with m_eff the body's mass (a spring
/// to a point of space) or the reduced mass m₁m₂/(m₁ + m₂) of two bodies.
fn check_step(
    top: &Place<'_>,
    dt: f64,
    t_end: f64,
    bodies: &[SceneBody],
    springs: &[SceneSpring],
) -> Result<(), SceneError> {
    if dt >= t_end {
        return Err(top.error(format!(
            "dt = {dt} is not less than t_end = {t_end}: the run would be a single step; \
             take dt < t_end"
        )));
    }
    for (k, s) in springs.iter().enumerate() {
        if s.stiffness <= 0.0 {
            continue;
        }
        let m = bodies[s.body].mass;
        let m_eff = match &s.anchor {
            SceneAnchor::World(_) => m,
            // m₁m₂/(m₁ + m₂), written so that it does not overflow for huge masses.
            SceneAnchor::Body(j, _) => m / (1.0 + m / bodies[*j].mass),
        };
        let period = std::f64::consts::TAU * (m_eff / s.stiffness).sqrt();
        let largest = MAX_STEP_PER_PERIOD * period;
        if dt > largest {
            return Err(SceneError::invalid(format!(
                "{}: spring {}: dt = {dt} is more than 1/{} of the spring's period \
                 2π√(m_eff/k) = {period:.6e} (m_eff = {m_eff}, k = {}); take dt ≤ {largest:.3e}",
                top.file,
                k + 1,
                1.0 / MAX_STEP_PER_PERIOD,
                s.stiffness
            )));
        }
    }
    Ok(())
}

/// True if the SPEC carries a `mass=` option.
fn spec_has_mass(spec: &str) -> bool {
    spec.split(['+', ';']).skip(1).any(|opt| {
        opt.trim_start()
            .strip_prefix("mass")
            .is_some_and(|rest| rest.trim_start().starts_with('='))
    })
}

fn read_body(
    file: &str,
    k: usize,
    t: &Value,
    dim: usize,
    read_file: FileReader<'_>,
) -> Result<SceneBody, SceneError> {
    let mut place = Place {
        file,
        section: format!("body {}", k + 1),
    };
    // Name the body as soon as its name is known.
    if let Some(Value::String(name)) = t.get("name") {
        place.section = format!("body \"{name}\"");
    }
    let raw: RawBody = place.table(t, "body")?;
    let name = place.string("name", place.required("name", &raw.name)?)?;
    if name.is_empty()
        || name.starts_with('.')
        || name
            .chars()
            .any(|c| c == '/' || c == '\\' || c.is_control())
        || name == "system"
    {
        return Err(place.error(format!(
            "name \"{name}\" cannot name a file (expected a non-empty name without '/', '\\' or \
             a leading '.', other than \"system\")"
        )));
    }
    let spec = place.string("shape", place.required("shape", &raw.shape)?)?;
    let mass = match &raw.mass {
        None => None,
        Some(v) => {
            let m = place.number("mass", v)?;
            if m <= 0.0 {
                return Err(place.error(format!("mass must be > 0, got {m}")));
            }
            Some(m)
        }
    };
    let full_spec = match mass {
        Some(m) if spec_has_mass(spec) => {
            return Err(place.error(format!(
                "mass = {m} and shape `{spec}` both give the mass; give one of them"
            )));
        }
        Some(m) => format!("{spec}+mass={m:?}"),
        None => spec.to_string(),
    };
    let parsed = match read_file {
        Some(read) => parse_body_with(&full_spec, read),
        None => parse_body(&full_spec),
    };
    let mut parsed = parsed.map_err(|e| place.error(format!("shape: {e}")))?;
    if parsed.dim != dim {
        return Err(place.error(format!(
            "shape `{spec}` is a body in {} dimensions, expected {dim} (dim = {dim})",
            parsed.dim
        )));
    }
    if let Some(m) = mass {
        // A mass tensor (principal:, tensor:, planes:) is taken as it is: the mass is its own.
        parsed.mass = m;
    }
    let position = place.vector("position", &raw.position, dim)?;
    let velocity = place.vector("velocity", &raw.velocity, dim)?;
    let planes = dim * (dim - 1) / 2;
    let omega = match &raw.omega {
        None => vec![0.0; planes],
        Some(v) => {
            let w = place.list("omega", v, &format!("{planes} plane components"))?;
            if w.len() != planes {
                return Err(place.error(format!(
                    "omega has {} components, expected {planes} (the planes 12,13,... of dim = \
                     {dim})",
                    w.len()
                )));
            }
            w
        }
    };
    let attitude = match &raw.attitude {
        None => DMatrix::identity(dim, dim),
        Some(v) => read_attitude(&place, v, dim)?,
    };
    let optional = |key: &str, v: &Option<Value>, range| match v {
        None => Ok(None),
        Some(_) => place.number_in(key, v, None, range).map(Some),
    };
    let friction = optional("friction", &raw.friction, ("≥ 0", non_negative))?;
    let restitution = optional(
        "restitution",
        &raw.restitution,
        ("in [0, 1]", unit_interval),
    )?;
    let flag = |key: &str, v: &Option<Value>, default: bool| match v {
        None => Ok(default),
        Some(Value::Boolean(b)) => Ok(*b),
        Some(other) => Err(place.error(format!(
            "{key} must be true or false, got {}",
            a_type(other)
        ))),
    };
    let fixed = flag("fixed", &raw.fixed, false)?;
    let collide = flag("collide", &raw.collide, true)?;
    if fixed {
        for (key, given) in [("velocity", &raw.velocity), ("omega", &raw.omega)] {
            if given.is_some() {
                return Err(place.error(format!("a fixed body never moves: remove its {key}")));
            }
        }
        if !collide {
            return Err(place.error(
                "a fixed body that touches nothing has no effect: remove `collide = false` or the body",
            ));
        }
    }
    let contact = match &raw.contact {
        None => None,
        Some(v) => Some(read_contact(&place, v, dim)?),
    };
    if !collide && contact.is_some() {
        return Err(place.error(
            "a body with collide = false touches nothing: remove its contact or `collide = false`",
        ));
    }
    Ok(SceneBody {
        contact,
        name: name.to_string(),
        mass: parsed.mass,
        parsed,
        position,
        velocity,
        omega,
        attitude,
        friction,
        restitution,
        fixed,
        collide,
    })
}

/// The grammar of `contact`, for the messages.
const CONTACT_GRAMMAR: &str = "capsule:H,R, ball:R, box:h1,...,hN, ellipsoid:a1,...,aN, \
     simplex:R or cross:R, each with an optional +margin=M and @x1,...,xN";

/// A `contact`: one convex shape (a string), or a compound of pieces (a list of strings),
/// each `KIND:NUMBERS[+margin=M][@OFFSET]`.
fn read_contact(place: &Place<'_>, v: &Value, dim: usize) -> Result<ContactShape, SceneError> {
    let piece = |text: &str| -> Result<Piece, SceneError> {
        let fail = |problem: String| place.error(format!("contact `{text}`: {problem}"));
        let (shape, offset) = match text.split_once('@') {
            Some((shape, at)) => (shape, Some(at)),
            None => (text, None),
        };
        let mut parts = shape.split('+');
        let base = parts.next().unwrap_or_default().trim();
        let (kind, args) = base
            .split_once(':')
            .ok_or_else(|| fail(format!("expected KIND:NUMBERS ({CONTACT_GRAMMAR})")))?;
        let numbers = |what: &str, list: &str| -> Result<Vec<f64>, SceneError> {
            list.split(',')
                .map(|x| {
                    x.trim()
                        .parse::<f64>()
                        .map_err(|_| fail(format!("{what}: `{}` is not a number", x.trim())))
                })
                .collect()
        };
        let args = numbers(kind.trim(), args)?;
        let one = |name: &str| -> Result<f64, SceneError> {
            match args[..] {
                [x] => Ok(x),
                _ => Err(fail(format!("{name} takes one number, got {}", args.len()))),
            }
        };
        let shape = match kind.trim() {
            "capsule" => match args[..] {
                [h, r] => ConvexShape::capsule(dim, h, r),
                _ => {
                    return Err(fail(format!(
                        "capsule takes H,R, got {} numbers",
                        args.len()
                    )));
                }
            },
            "ball" => ConvexShape::ball(dim, one("ball")?),
            "box" => ConvexShape::cuboid(&args),
            "ellipsoid" => ConvexShape::ellipsoid(&args),
            "simplex" => ConvexShape::simplex(dim, one("simplex")?),
            "cross" => ConvexShape::cross_polytope(dim, one("cross")?),
            other => {
                return Err(fail(format!(
                    "unknown shape `{other}` (expected {CONTACT_GRAMMAR})"
                )));
            }
        }
        .map_err(|e| fail(e.to_string()))?;
        if shape.dim() != dim {
            return Err(fail(format!(
                "a shape in {} dimensions, expected {dim} (dim = {dim})",
                shape.dim()
            )));
        }
        let mut shape = shape;
        for option in parts {
            let margin = option
                .trim()
                .strip_prefix("margin")
                .and_then(|rest| rest.trim_start().strip_prefix('='))
                .ok_or_else(|| {
                    fail(format!(
                        "unknown option `{}` (expected margin=M)",
                        option.trim()
                    ))
                })?;
            let m = numbers("margin", margin)?;
            shape = match m[..] {
                [m] => shape.rounded(m).map_err(|e| fail(e.to_string()))?,
                _ => return Err(fail("margin takes one number".into())),
            };
        }
        let offset = match offset {
            Some(at) => numbers("offset", at)?,
            None => vec![0.0; dim],
        };
        if offset.len() != dim {
            return Err(fail(format!(
                "offset has {} numbers, expected {dim} (dim = {dim})",
                offset.len()
            )));
        }
        Piece::translated(shape, &offset).map_err(|e| fail(e.to_string()))
    };
    match v {
        Value::String(text) if !text.contains('@') => {
            Ok(ContactShape::Convex(piece(text)?.shape().clone()))
        }
        Value::String(text) => compound(place, vec![piece(text)?]),
        Value::Array(items) if !items.is_empty() => {
            let pieces = items
                .iter()
                .map(|item| match item {
                    Value::String(text) => piece(text),
                    other => Err(place.error(format!(
                        "contact: each piece must be a string ({CONTACT_GRAMMAR}), got {}",
                        a_type(other)
                    ))),
                })
                .collect::<Result<Vec<_>, _>>()?;
            compound(place, pieces)
        }
        other => Err(place.error(format!(
            "contact must be a string or a non-empty list of strings ({CONTACT_GRAMMAR}), got {}",
            a_type(other)
        ))),
    }
}

/// The compound of `pieces`.
fn compound(place: &Place<'_>, pieces: Vec<Piece>) -> Result<ContactShape, SceneError> {
    CompoundShape::new(pieces)
        .map(ContactShape::Compound)
        .map_err(|e| place.error(format!("contact: {e}")))
}

/// An attitude: N² numbers row-major or N rows of N; a rotation to 1e-9.
fn read_attitude(place: &Place<'_>, v: &Value, n: usize) -> Result<DMatrix<f64>, SceneError> {
    let expected = format!("{} numbers row-major or {n} rows of {n}", n * n);
    let Value::Array(items) = v else {
        return Err(place.error(format!(
            "attitude must be a list ({expected}), got {}",
            a_type(v)
        )));
    };
    let entries: Vec<f64> = if items.iter().all(Value::is_array) && !items.is_empty() {
        let mut all = Vec::with_capacity(n * n);
        for (r, row) in items.iter().enumerate() {
            let row = place.list(&format!("attitude row {}", r + 1), row, &expected)?;
            if row.len() != n {
                return Err(place.error(format!(
                    "attitude row {} has {} entries, expected {n} (dim = {n})",
                    r + 1,
                    row.len()
                )));
            }
            all.extend(row);
        }
        if items.len() != n {
            return Err(place.error(format!(
                "attitude has {} rows, expected {n} (dim = {n})",
                items.len()
            )));
        }
        all
    } else {
        let all = place.list("attitude", v, &expected)?;
        if all.len() != n * n {
            return Err(place.error(format!(
                "attitude has {} entries, expected {} ({expected}; dim = {n})",
                all.len(),
                n * n
            )));
        }
        all
    };
    let q = DMatrix::from_row_slice(n, n, &entries);
    let err = (q.transpose() * &q - DMatrix::<f64>::identity(n, n))
        .iter()
        .fold(0.0_f64, |m, x| m.max(x.abs()));
    let det = q.determinant();
    if err > 1e-9 {
        return Err(place.error(format!(
            "attitude is not a rotation: max |QᵀQ − 1| = {err:.3e} > 1e-9"
        )));
    }
    if det <= 0.0 {
        return Err(place.error(format!(
            "attitude is not a rotation: det = {det:.6} (a reflection; expected det +1)"
        )));
    }
    Ok(q)
}

fn read_plane(file: &str, k: usize, t: &Value, dim: usize) -> Result<ScenePlane, SceneError> {
    let place = Place {
        file,
        section: format!("plane {}", k + 1),
    };
    let raw: RawPlane = place.table(t, "plane")?;
    let normal = place.vector(
        "normal",
        &Some(place.required("normal", &raw.normal)?.clone()),
        dim,
    )?;
    if normal.iter().all(|x| *x == 0.0) {
        return Err(place.error("normal is zero, expected a non-zero vector"));
    }
    Ok(ScenePlane {
        normal,
        offset: place.number_in("offset", &raw.offset, Some(0.0), ("finite", f64::is_finite))?,
        friction: place.number_in("friction", &raw.friction, Some(0.0), ("≥ 0", non_negative))?,
        restitution: place.number_in(
            "restitution",
            &raw.restitution,
            Some(0.0),
            ("in [0, 1]", unit_interval),
        )?,
    })
}

/// The body named by `key`, by index.
fn body_index(
    place: &Place<'_>,
    key: &str,
    v: &Value,
    names: &[&str],
) -> Result<usize, SceneError> {
    let name = place.string(key, v)?;
    names.iter().position(|n| *n == name).ok_or_else(|| {
        place.error(format!(
            "{key} = \"{name}\" names no body (the bodies are {})",
            names
                .iter()
                .map(|n| format!("\"{n}\""))
                .collect::<Vec<_>>()
                .join(", ")
        ))
    })
}

/// `anchor` (a world point) or `other` with `other_point`: exactly one of the two.
fn read_anchor(
    place: &Place<'_>,
    body: usize,
    anchor: &Option<Value>,
    other: &Option<Value>,
    other_point: &Option<Value>,
    dim: usize,
    names: &[&str],
) -> Result<SceneAnchor, SceneError> {
    match (anchor, other) {
        (Some(_), Some(_)) => {
            Err(place.error("give anchor (a point of space) or other (a body), not both"))
        }
        (None, None) => Err(place
            .error("missing key `anchor` or `other` (the other end: a point of space or a body)")),
        (Some(_), None) => {
            if other_point.is_some() {
                return Err(place.error("other_point needs other (a body); with anchor drop it"));
            }
            Ok(SceneAnchor::World(place.vector("anchor", anchor, dim)?))
        }
        (None, Some(v)) => {
            let j = body_index(place, "other", v, names)?;
            if j == body {
                return Err(place.error(format!(
                    "other = \"{}\" is the body itself; expected another body",
                    names[j]
                )));
            }
            Ok(SceneAnchor::Body(
                j,
                place.vector("other_point", other_point, dim)?,
            ))
        }
    }
}

/// The ends of a spring or a joint, `[body, point, anchor, other, other_point]` as in the
/// file: the body (by index), its point (own axes) and the other end.
fn read_ends(
    place: &Place<'_>,
    [body, point, anchor, other, other_point]: [&Option<Value>; 5],
    dim: usize,
    names: &[&str],
) -> Result<LinkEnds, SceneError> {
    let body = body_index(place, "body", place.required("body", body)?, names)?;
    let point = place.vector("point", point, dim)?;
    let other = read_anchor(place, body, anchor, other, other_point, dim, names)?;
    Ok((body, point, other))
}

/// The keys of a spring or a joint that name its ends.
trait Ends {
    /// `[body, point, anchor, other, other_point]` as in the file.
    fn ends(&self) -> [&Option<Value>; 5];
}

impl Ends for RawSpring {
    fn ends(&self) -> [&Option<Value>; 5] {
        [
            &self.body,
            &self.point,
            &self.anchor,
            &self.other,
            &self.other_point,
        ]
    }
}

impl Ends for RawJoint {
    fn ends(&self) -> [&Option<Value>; 5] {
        [
            &self.body,
            &self.point,
            &self.anchor,
            &self.other,
            &self.other_point,
        ]
    }
}

/// The ends of a spring or a joint: the body (by index), its point and the other end.
type LinkEnds = (usize, Vec<f64>, SceneAnchor);

/// Reads the `k`-th `[[what]]` (a spring or a joint): its place in the file, its keys and
/// its ends.
fn read_linked<'a, T: for<'de> Deserialize<'de> + Ends>(
    file: &'a str,
    what: &str,
    k: usize,
    t: &Value,
    dim: usize,
    names: &[&str],
) -> Result<(Place<'a>, T, LinkEnds), SceneError> {
    let place = Place {
        file,
        section: format!("{what} {}", k + 1),
    };
    let raw: T = place.table(t, what)?;
    let ends = read_ends(&place, raw.ends(), dim, names)?;
    Ok((place, raw, ends))
}

fn read_spring(
    file: &str,
    k: usize,
    t: &Value,
    dim: usize,
    names: &[&str],
) -> Result<SceneSpring, SceneError> {
    let (place, raw, (body, point, anchor)) =
        read_linked::<RawSpring>(file, "spring", k, t, dim, names)?;
    Ok(SceneSpring {
        body,
        point,
        anchor,
        stiffness: place.number_in("stiffness", &raw.stiffness, None, ("≥ 0", non_negative))?,
        rest_length: place.number_in(
            "rest_length",
            &raw.rest_length,
            Some(0.0),
            ("≥ 0", non_negative),
        )?,
        damping: place.number_in("damping", &raw.damping, Some(0.0), ("≥ 0", non_negative))?,
    })
}

fn read_joint(
    file: &str,
    k: usize,
    t: &Value,
    dim: usize,
    names: &[&str],
) -> Result<SceneJoint, SceneError> {
    let (_, _, (body, point, other)) = read_linked::<RawJoint>(file, "joint", k, t, dim, names)?;
    Ok(SceneJoint { body, point, other })
}
