//! Output: atomic file writes, JSON and CSV helpers, and the progress bar.

use super::error::{CliError, CliResult};
use indicatif::{ProgressBar, ProgressStyle};
use nalgebra::{DMatrix, DVector};
use serde_json::{Value, json};
use std::io::{IsTerminal, Write};
use std::path::Path;
use std::time::{Duration, Instant};

/// Writes `bytes` to `path` whole or not at all: into a temporary file in the same folder,
/// synced to disk, then renamed over the target. A process killed meanwhile leaves the old
/// file (or none) and a stray `.rotorflow-*` temporary file, never a partial target.
///
/// # Errors
/// [`CliError::Runtime`] if the folder cannot be written.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> CliResult<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let fail = |err: &dyn std::fmt::Display| {
        CliError::runtime(format!("cannot write `{}`: {err}", path.display()))
    };
    let mut builder = tempfile::Builder::new();
    builder.prefix(".rotorflow-");
    // Temporary files are private (0600); the result is an ordinary file (0644 on Unix).
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o644));
    }
    let mut tmp = builder.tempfile_in(dir).map_err(|e| fail(&e))?;
    tmp.write_all(bytes).map_err(|e| fail(&e))?;
    tmp.flush().map_err(|e| fail(&e))?;
    // On disk before the rename, so that a crash of the machine cannot leave an empty file.
    tmp.as_file().sync_all().map_err(|e| fail(&e))?;
    tmp.persist(path).map_err(|e| fail(&e.error))?;
    Ok(())
}

/// Writes `text` to `path` atomically, or to standard output when `path` is `None`.
///
/// # Errors
/// As [`write_atomic`].
pub fn emit(path: Option<&Path>, text: &str) -> CliResult<()> {
    match path {
        Some(p) => write_atomic(p, text.as_bytes()),
        None => {
            let mut out = std::io::stdout().lock();
            // A closed pipe (`| head`) is not an error worth a message.
            let _ = out.write_all(text.as_bytes());
            let _ = out.flush();
            Ok(())
        }
    }
}

/// Checks that an output file name ends in one of `extensions` (bad input otherwise).
///
/// # Errors
/// [`CliError::Input`] naming the flag and the expected extensions.
pub fn check_extension(flag: &str, path: &Path, extensions: &[&str]) -> CliResult<()> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    if ext.as_deref().is_some_and(|e| extensions.contains(&e)) {
        Ok(())
    } else {
        Err(CliError::input(format!(
            "{flag} `{}`: expected a file name ending in .{}",
            path.display(),
            extensions.join(" or .")
        )))
    }
}

/// The format of a report.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// A text table for people.
    Text,
    /// JSON.
    Json,
    /// CSV, one row per sample.
    Csv,
}

impl Format {
    fn flag(self) -> &'static str {
        match self {
            Format::Text => "the text table",
            Format::Json => "--json",
            Format::Csv => "--csv",
        }
    }
}

/// Returns the format of a report written to `output`: the one a flag asks for (`flag`,
/// `None` without `--json`/`--csv`), else the one the file name says (`.json` → JSON,
/// `.csv` → CSV, `.txt`, `.md`, another or no extension → text). `csv` says whether the
/// command can write CSV at all.
///
/// # Errors
/// [`CliError::Input`] when the flag contradicts the extension (`--json --output r.csv`), or
/// the extension asks for CSV where there is none.
pub fn report_format(output: Option<&Path>, flag: Option<Format>, csv: bool) -> CliResult<Format> {
    let ext = output
        .and_then(|p| p.extension())
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let by_name = match ext.as_deref() {
        Some("json") => Some(Format::Json),
        Some("csv") => Some(Format::Csv),
        Some("txt" | "md") => Some(Format::Text),
        _ => None,
    };
    let path = || output.map_or(String::new(), |p| p.display().to_string());
    if by_name == Some(Format::Csv) && !csv {
        return Err(CliError::input(format!(
            "--output `{}`: this command writes no CSV; use a .json file (or --json) or a .txt file",
            path()
        )));
    }
    match (flag, by_name) {
        (Some(f), Some(n)) if f != n => Err(CliError::input(format!(
            "--output `{}` names a {} file but {} was asked for; make the file name and the flag agree",
            path(),
            ext.as_deref().unwrap_or(""),
            f.flag()
        ))),
        (Some(f), _) => Ok(f),
        (None, Some(n)) => Ok(n),
        (None, None) => Ok(Format::Text),
    }
}

/// Returns the JSON array of a vector.
pub fn vector_json(v: &DVector<f64>) -> Value {
    json!(v.iter().copied().collect::<Vec<f64>>())
}

/// Returns the JSON array of rows of a matrix.
pub fn matrix_json(m: &DMatrix<f64>) -> Value {
    json!(
        (0..m.nrows())
            .map(|r| (0..m.ncols()).map(|c| m[(r, c)]).collect::<Vec<f64>>())
            .collect::<Vec<_>>()
    )
}

/// Serialises `value` as JSON (indented when `pretty`), refusing non-finite numbers
/// (serde_json would print them as `null`).
///
/// # Errors
/// [`CliError::Runtime`] if a number is not finite.
pub fn to_json_text(value: &Value, pretty: bool) -> CliResult<String> {
    fn finite(v: &Value) -> bool {
        match v {
            Value::Number(n) => n.as_f64().is_none_or(f64::is_finite),
            Value::Array(a) => a.iter().all(finite),
            Value::Object(o) => o.values().all(finite),
            _ => true,
        }
    }
    if !finite(value) {
        return Err(CliError::runtime("a result is not finite"));
    }
    let text = if pretty {
        serde_json::to_string_pretty(value)
    } else {
        serde_json::to_string(value)
    };
    let mut text = text.map_err(|e| CliError::runtime(format!("cannot serialise JSON: {e}")))?;
    text.push('\n');
    Ok(text)
}

/// Formats a number for CSV and text output: the shortest digits that read back exactly.
pub use rotorflow::dynamics::motion::csv_number as number;

/// Returns the 1-based plane names of dimension `n` in lexicographic order ("12", "13", …).
pub fn plane_names(n: usize) -> Vec<String> {
    rotorflow::algebra::pairs(n)
        .map(|(i, j)| rotorflow::algebra::plane_name(n, i, j))
        .collect()
}

/// A progress bar on standard error that appears only when the run has taken longer than a
/// second, standard error is a terminal, and `--quiet` was not given.
pub struct Progress {
    total: u64,
    done: u64,
    start: Instant,
    enabled: bool,
    bar: Option<ProgressBar>,
    message: String,
}

impl Progress {
    /// Returns a progress tracker for `total` units of work labelled `message`.
    pub fn new(total: u64, quiet: bool, message: &str) -> Self {
        Progress {
            total,
            done: 0,
            start: Instant::now(),
            enabled: !quiet && std::io::stderr().is_terminal(),
            bar: None,
            message: message.to_string(),
        }
    }

    /// Records `units` more units of work done.
    pub fn advance(&mut self, units: u64) {
        self.done += units;
        if !self.enabled {
            return;
        }
        if self.bar.is_none() && self.start.elapsed() >= Duration::from_secs(1) {
            let bar = ProgressBar::new(self.total);
            if let Ok(style) = ProgressStyle::with_template(
                "{msg} [{elapsed_precise}] {wide_bar} {pos}/{len} (eta {eta})",
            ) {
                bar.set_style(style);
            }
            bar.set_message(self.message.clone());
            self.bar = Some(bar);
        }
        if let Some(bar) = &self.bar {
            bar.set_position(self.done);
        }
    }

    /// Removes the bar, if one was shown.
    pub fn finish(self) {
        if let Some(bar) = self.bar {
            bar.finish_and_clear();
        }
    }
}
