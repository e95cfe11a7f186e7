//! The progress file of `sweep --output FILE` (FILE.partial) and `--resume`: a fingerprint of
//! the sweep, then one finished row per line in completion order.

use super::super::error::{CliError, CliResult};
use super::super::output::write_atomic;
use super::table::{Row, row_line};
use super::{GridRun, SweepArgs};
use rotorflow::dynamics::trajectory::ProjectedObservables;
use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Returns the progress file of `--output FILE`: FILE.partial beside it.
pub fn progress_path(csv: &Path) -> PathBuf {
    let mut name = csv.as_os_str().to_owned();
    name.push(".partial");
    PathBuf::from(name)
}

/// The first line of a progress file: what it is, and the fingerprint of the sweep.
fn progress_header(fingerprint: &str) -> String {
    format!(
        "# rotorflow {} sweep progress, fingerprint {fingerprint}: finished rows in completion order; delete this file to start over",
        env!("CARGO_PKG_VERSION")
    )
}

/// FNV-1a, 64 bits: a hash that is the same on every platform and every Rust version.
struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }

    /// Hashes `bytes` and a separator that no UTF-8 text contains.
    fn field(&mut self, bytes: &[u8]) {
        for &b in bytes.iter().chain(&[0xff]) {
            self.0 ^= u64::from(b);
            self.0 = self.0.wrapping_mul(0x0100_0000_01b3);
        }
    }
}

/// Returns the fingerprint of everything that determines the rows of this sweep: the
/// template, each run's parameter values, initial state and stepping, the sample times, the
/// axes, the shard and the version.
pub(super) fn sweep_fingerprint(
    args: &SweepArgs,
    names: &[String],
    times: &[f64],
    axes: [usize; 3],
    (begin, end, total): (usize, usize, usize),
    runs: &[GridRun],
) -> String {
    let mut h = Fnv::new();
    h.field(env!("CARGO_PKG_VERSION").as_bytes());
    h.field(args.body.as_bytes());
    h.field(format!("{:?}", args.initial).as_bytes());
    for name in names {
        h.field(name.as_bytes());
    }
    h.field(format!("{axes:?} {begin} {end} {total} {}", times.len()).as_bytes());
    let mut bits = Vec::with_capacity(8 * times.len());
    for t in times {
        bits.extend_from_slice(&t.to_bits().to_le_bytes());
    }
    h.field(&bits);
    for (run, values, start, stepping) in runs {
        h.field(
            format!(
                "{run} {values:?} {:?} {:?} {stepping:?}",
                start.momentum().as_slice(),
                start.inertia().to_matrix().as_slice()
            )
            .as_bytes(),
        );
    }
    format!("{:016x}", h.0)
}

/// The progress file of a running sweep, appended one finished row at a time.
pub(super) struct ProgressLog {
    file: std::fs::File,
    path: PathBuf,
}

impl ProgressLog {
    /// Writes the header and the rows already finished (atomically), then opens the file
    /// for appending.
    pub(super) fn start<'a>(
        path: &Path,
        fingerprint: &str,
        finished: impl Iterator<Item = &'a Row>,
    ) -> CliResult<Self> {
        let mut text = progress_header(fingerprint);
        text.push('\n');
        for row in finished {
            text.push_str(&row_line(row));
            text.push('\n');
        }
        write_atomic(path, text.as_bytes())?;
        let file = std::fs::OpenOptions::new()
            .append(true)
            .open(path)
            .map_err(|e| CliError::runtime(format!("cannot open `{}`: {e}", path.display())))?;
        Ok(ProgressLog {
            file,
            path: path.to_path_buf(),
        })
    }

    /// Appends one complete line (a single write) and hands it to the operating system.
    pub(super) fn append(&mut self, row: &Row) -> CliResult<()> {
        let mut line = row_line(row);
        line.push('\n');
        self.file
            .write_all(line.as_bytes())
            .and_then(|()| self.file.flush())
            .map_err(|e| CliError::runtime(format!("cannot write `{}`: {e}", self.path.display())))
    }
}

/// Reads the finished rows of a progress file for `--resume`. A missing file gives no rows;
/// a torn last line (no newline: the sweep was killed while writing it) is ignored.
///
/// # Errors
/// [`CliError::Input`] if the file belongs to a different sweep (fingerprint) or a complete
/// line is not a row of this one.
pub(super) fn read_progress(
    path: &Path,
    fingerprint: &str,
    runs: &[GridRun],
    planes: [(usize, usize); 3],
) -> CliResult<BTreeMap<usize, Row>> {
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(BTreeMap::new()),
        Err(e) => {
            return Err(CliError::runtime(format!(
                "cannot read `{}`: {e}",
                path.display()
            )));
        }
    };
    let refuse = |why: String| {
        CliError::input(format!(
            "--resume: `{}` {why}; delete it to start over, or give the same sweep",
            path.display()
        ))
    };
    // Only complete lines count: cut after the last newline.
    let complete = bytes
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(&bytes[..0], |k| &bytes[..=k]);
    let text = std::str::from_utf8(complete)
        .map_err(|_| refuse("is not a progress file of rotorflow sweep".into()))?;
    let mut lines = text.lines();
    if lines.next() != Some(progress_header(fingerprint).as_str()) {
        return Err(refuse(
            "was written by a different sweep (body, grid, initial condition, times, integrator, axes or shard differ)"
                .into(),
        ));
    }
    let index: BTreeMap<usize, &Vec<f64>> = runs.iter().map(|r| (r.0, &r.1)).collect();
    let mut rows = BTreeMap::new();
    for (k, line) in lines.enumerate() {
        let row = parse_row(line, planes)
            .filter(|row| index.get(&row.run).is_some_and(|v| **v == row.values))
            .ok_or_else(|| refuse(format!("line {} is not a row of this sweep", k + 2)))?;
        rows.insert(row.run, row);
    }
    Ok(rows)
}

/// Parses a table row written by [`row_line`]; `None` unless writing it back gives the same
/// text (numbers are written as their shortest round-trip form, so this is exact).
fn parse_row(line: &str, planes: [(usize, usize); 3]) -> Option<Row> {
    let fields: Vec<&str> = line.split(',').collect();
    let n_values = fields.len().checked_sub(1 + 9 + 5)?;
    let float = |s: &str| s.parse::<f64>().ok();
    let at = |k: usize| float(fields[1 + n_values + k]);
    let tail = &fields[1 + n_values + 9..];
    let row = Row {
        run: fields[0].parse().ok()?,
        values: fields[1..=n_values]
            .iter()
            .map(|s| float(s))
            .collect::<Option<_>>()?,
        observables: ProjectedObservables {
            planes,
            frequency: [at(0)?, at(3)?, at(6)?],
            amplitude: [at(1)?, at(4)?, at(7)?],
            mean: [at(2)?, at(5)?, at(8)?],
            flips: tail[1].parse().ok()?,
            first_flip: if tail[2].is_empty() {
                None
            } else {
                Some(float(tail[2])?)
            },
        },
        manakov_drift: float(tail[0])?,
        energy_drift: float(tail[3])?,
        casimir_drift: float(tail[4])?,
    };
    (row_line(&row) == line).then_some(row)
}
