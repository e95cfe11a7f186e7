//! The body grammar on the command line: the help text, and the SPEC parser of the library
//! (`rotorflow::inertia::spec`) with its error turned into a one-line bad-input message.

use super::error::{CliError, CliResult};
use rotorflow::inertia::spec;
pub use rotorflow::inertia::spec::ParsedBody;

/// The grammar, printed by `rotorflow help bodies` (and nowhere else: the helps that take a
/// SPEC point to it with [`GRAMMAR_POINTER`]).
pub const GRAMMAR: &str = "\
Body SPEC grammar: KIND:ARGS[+mass=M|+density=D]  (lengths are half-lengths / semi-axes / radii; density 1 by default)
  principal:J1,...,JN        diagonal mass tensor J, i.e. its eigenvalues, the second moments (N >= 2)
  tensor:J11,J12,...,JNN     full symmetric mass tensor, row-major, in the body's own axes
  planes:I12,I13,...         any positive plane moments in lexicographic order 12,13,...,1N,23,... (physical or not)
  tesseract:a,b,c,...        unit point masses at the 2^N vertices (+-a, +-b, ...)
  pentachoron:a,b,c,d        unit point masses at the points of the paper's eq. (73)
  simplex:N                  regular N-simplex, unit vertex masses, circumradius 1
  cuboid:a,b,...             solid hyper-cuboid with half-lengths a, b, ...
  ellipsoid:a,b,...          solid ellipsoid with semi-axes a, b, ...
  ball:N,R                   solid N-ball of radius R
  sphere:N,R                 hollow sphere S^(N-1) of radius R (density per unit area)
  points:FILE.csv            point masses, one row m,x1,...,xN per mass ('#' comments; an optional
                             header line of column names; an empty first name marks an index column)
  mesh:FILE                  solid simplicial mesh: lines 'v x1 ... xN' (vertex), 's i0 ... iN' (simplex,
                             1-based vertex numbers) or 'f i1 ... iN' (closed oriented boundary facet)
  +mass=M rescales the body to total mass M (for principal/tensor/planes it is only reported);
  +density=D applies to solids and shells. ';' also separates options, but the shell ends the
  command at an unquoted ';': quote the SPEC then. Examples: 'tesseract:1,1.2,1.5,2'
  'cuboid:1,2,3,4+mass=5'  'cuboid:1,2,3,4;mass=5'";

/// The one line with which a help points to the grammar.
pub const GRAMMAR_POINTER: &str =
    "Body SPEC grammar (--body, a scene's shape): rotorflow help bodies";

/// Parses a body SPEC, reading `points:` and `mesh:` files from the file system.
///
/// # Errors
/// [`CliError::Input`] naming the problem and the expected form.
pub fn parse_body(text: &str) -> CliResult<ParsedBody> {
    spec::parse_body(text).map_err(|err| CliError::input(err.to_string()))
}
