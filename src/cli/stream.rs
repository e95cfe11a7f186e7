//! The report of `simulate` and `exact` written sample by sample, so that memory stays flat
//! in the number of samples: rows go to a temporary file as they come (one temporary file per
//! JSON column, since JSON lists each column whole), which is renamed onto the output file
//! (or copied to standard output) only when every sample is in. A failure on the way leaves
//! no output file and prints nothing. The text is the same, byte for byte, as that of
//! [`Report`](super::motion::Report)'s `to_json`, `to_csv` and `to_text` (a test checks it).

use super::error::{CliError, CliResult};
use super::motion::{State, csv_header, drift_line, text_header};
use super::output::{Format, number, plane_names};
use rotorflow::algebra::Bivector;
use rotorflow::dynamics::{Attitude, Drift, Invariants, RigidBody};
use std::fs::File;
use std::io::{BufWriter, Seek, Write};
use std::path::{Path, PathBuf};

/// A report being written: feed it the states in time order with [`ReportStream::push`],
/// then [`ReportStream::finish`].
pub struct ReportStream {
    format: Format,
    output: Option<PathBuf>,
    dim: usize,
    times: Vec<f64>,
    count: usize,
    reference: Invariants,
    principal: Attitude,
    principal_reverse: Attitude,
    body: RigidBody,
    drift: Drift,
    manakov_drift: Vec<f64>,
    /// The text (CSV, text) or the whole JSON assembled at the end.
    main: BufWriter<tempfile::NamedTempFile>,
    /// JSON columns in key order: attitude, casimirs, energy, momentum, omega.
    columns: Vec<BufWriter<File>>,
    /// ω per sample, kept only when a plot needs it.
    omega_for_plot: Option<Vec<Bivector>>,
}

/// A complete report not yet published, and the ω kept for a plot.
pub struct Finished {
    file: tempfile::NamedTempFile,
    output: Option<PathBuf>,
    /// The sample times and ω, when the stream kept them.
    pub omega: Option<(Vec<f64>, Vec<Bivector>)>,
}

impl Finished {
    /// Renames the report onto its output file (whole, after a sync) or copies it to standard
    /// output.
    ///
    /// # Errors
    /// [`CliError::Runtime`] when the file cannot be written.
    pub fn publish(mut self) -> CliResult<()> {
        let shown = self
            .output
            .clone()
            .unwrap_or_else(|| PathBuf::from("standard output"));
        let fail = io_fail(&shown);
        match &self.output {
            Some(path) => {
                self.file.as_file().sync_all().map_err(&fail)?;
                self.file.persist(path).map_err(|e| fail(e.error))?;
            }
            None => {
                self.file.as_file_mut().rewind().map_err(&fail)?;
                let mut out = std::io::stdout().lock();
                // A closed pipe (`| head`) is not an error worth a message.
                let _ = std::io::copy(self.file.as_file_mut(), &mut out);
                let _ = out.flush();
            }
        }
        Ok(())
    }
}

/// The JSON columns, in the (alphabetical) key order of [`Report::to_json`].
const COLUMNS: [&str; 5] = ["attitude", "casimirs", "energy", "momentum", "omega"];

fn io_fail(what: &Path) -> impl Fn(std::io::Error) -> CliError + '_ {
    move |e| CliError::runtime(format!("cannot write `{}`: {e}", what.display()))
}

impl ReportStream {
    /// A report of the motion that starts as `start`, sampled at `times`, in `format`, to
    /// `output` (standard output when `None`); with `keep_omega`, ω is also kept for a plot.
    ///
    /// # Errors
    /// [`CliError::Runtime`] when the temporary files cannot be created.
    pub fn new(
        start: &RigidBody,
        times: &[f64],
        format: Format,
        output: Option<&Path>,
        keep_omega: bool,
    ) -> CliResult<Self> {
        let dir = match output.and_then(Path::parent) {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            Some(_) => PathBuf::from("."),
            None => std::env::temp_dir(),
        };
        let shown = output.map_or_else(|| PathBuf::from("standard output"), Path::to_path_buf);
        let fail = io_fail(&shown);
        let mut builder = tempfile::Builder::new();
        builder.prefix(".rotorflow-");
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            builder.permissions(std::fs::Permissions::from_mode(0o644));
        }
        let main = BufWriter::new(builder.tempfile_in(&dir).map_err(&fail)?);
        let columns = if format == Format::Json {
            COLUMNS
                .iter()
                .map(|_| tempfile::tempfile_in(&dir).map(BufWriter::new))
                .collect::<Result<Vec<_>, _>>()
                .map_err(&fail)?
        } else {
            Vec::new()
        };
        let principal = start.principal_frame().clone();
        let reference = Invariants::of(start);
        let manakov_count = reference.manakov.len();
        let mut stream = ReportStream {
            format,
            output: output.map(Path::to_path_buf),
            dim: start.dim(),
            times: times.to_vec(),
            count: 0,
            reference,
            principal_reverse: principal.inverse(),
            principal,
            body: start.clone(),
            drift: Drift::default(),
            manakov_drift: vec![0.0; manakov_count],
            main,
            columns,
            omega_for_plot: keep_omega.then(Vec::new),
        };
        stream.header().map_err(|e| io_fail(&shown)(e))?;
        Ok(stream)
    }

    fn header(&mut self) -> std::io::Result<()> {
        match self.format {
            Format::Csv => write!(self.main, "{}", csv_header(self.dim)),
            Format::Text => write!(self.main, "{}", text_header(self.dim)),
            Format::Json => Ok(()),
        }
    }

    /// Adds the next sample.
    ///
    /// # Errors
    /// [`CliError::Runtime`] if there are more states than times, the state cannot be
    /// evaluated, a number is not finite, or a file cannot be written.
    pub fn push(&mut self, state: State) -> CliResult<()> {
        let k = self.count;
        let Some(&t) = self.times.get(k) else {
            return Err(CliError::runtime("more states than sample times"));
        };
        let (r, l) = state;
        self.body
            .set_state(r, l)
            .map_err(|e| CliError::runtime(format!("the motion cannot be evaluated: {e}")))?;
        let inv = Invariants::of(&self.body);
        self.drift = self.drift.max(inv.drift_from(&self.reference));
        for (worst, m) in self
            .manakov_drift
            .iter_mut()
            .zip(inv.manakov_drifts(&self.reference))
        {
            *worst = worst.max(m);
        }
        let omega = self.principal.rotate_bivector(&self.body.omega());
        let momentum = self.principal.rotate_bivector(self.body.momentum());
        let attitude = self
            .body
            .principal_frame_attitude()
            .compose(&self.principal_reverse)
            .to_matrix();
        let finite = |x: &f64| x.is_finite();
        if !(omega.as_slice().iter().all(finite)
            && momentum.as_slice().iter().all(finite)
            && inv.energy.is_finite()
            && inv.casimirs.iter().all(finite)
            && attitude.iter().all(finite))
        {
            return Err(CliError::runtime("a result is not finite"));
        }
        let shown = self
            .output
            .clone()
            .unwrap_or_else(|| PathBuf::from("standard output"));
        let n = self.dim;
        let written: std::io::Result<()> = (|| {
            match self.format {
                Format::Csv => {
                    let mut row = vec![number(t)];
                    row.extend(omega.as_slice().iter().map(|x| number(*x)));
                    row.extend(momentum.as_slice().iter().map(|x| number(*x)));
                    row.push(number(inv.energy));
                    row.extend(inv.casimirs.iter().map(|x| number(*x)));
                    for r in 0..n {
                        row.extend((0..n).map(|c| number(attitude[(r, c)])));
                    }
                    writeln!(self.main, "{}", row.join(","))?;
                }
                Format::Text => {
                    write!(self.main, "{t:>12.6}")?;
                    for x in omega.as_slice() {
                        write!(self.main, " {x:>12.6}")?;
                    }
                    writeln!(self.main, " {:>14.8}", inv.energy)?;
                }
                Format::Json => {
                    let rows: Vec<Vec<f64>> = (0..n)
                        .map(|r| (0..n).map(|c| attitude[(r, c)]).collect())
                        .collect();
                    let sep = if k == 0 { "" } else { "," };
                    let c = &mut self.columns;
                    write!(c[0], "{sep}")?;
                    serde_json::to_writer(&mut c[0], &rows)?;
                    write!(c[1], "{sep}")?;
                    serde_json::to_writer(&mut c[1], &inv.casimirs)?;
                    write!(c[2], "{sep}")?;
                    serde_json::to_writer(&mut c[2], &inv.energy)?;
                    write!(c[3], "{sep}")?;
                    serde_json::to_writer(&mut c[3], momentum.as_slice())?;
                    write!(c[4], "{sep}")?;
                    serde_json::to_writer(&mut c[4], omega.as_slice())?;
                }
            }
            Ok(())
        })();
        written.map_err(io_fail(&shown))?;
        if let Some(keep) = &mut self.omega_for_plot {
            keep.push(omega);
        }
        self.count += 1;
        Ok(())
    }

    /// Completes the report (the JSON assembled from its columns) without publishing it yet:
    /// [`Finished::publish`] renames it onto the output or copies it to standard output, so
    /// that a plot drawn from the kept ω can be written first.
    ///
    /// # Errors
    /// [`CliError::Runtime`] if fewer states than times came in or a file cannot be written.
    pub fn finish(mut self) -> CliResult<Finished> {
        if self.count != self.times.len() {
            return Err(CliError::runtime("fewer states than sample times"));
        }
        let shown = self
            .output
            .clone()
            .unwrap_or_else(|| PathBuf::from("standard output"));
        let fail = io_fail(&shown);
        match self.format {
            Format::Json => self.assemble_json().map_err(&fail)?,
            Format::Text => write!(self.main, "{}", drift_line(&self.drift)).map_err(&fail)?,
            Format::Csv => {}
        }
        let mut file = self.main.into_inner().map_err(|e| fail(e.into_error()))?;
        file.flush().map_err(&fail)?;
        Ok(Finished {
            file,
            output: self.output,
            omega: self.omega_for_plot.map(|w| (self.times, w)),
        })
    }

    /// `{"attitude":[…],"casimirs":[…],"dim":N,"drift":{…},"energy":[…],"momentum":[…],
    /// "omega":[…],"planes":[…],"times":[…]}` into the main file, copying each column.
    fn assemble_json(&mut self) -> std::io::Result<()> {
        let mut columns = Vec::with_capacity(COLUMNS.len());
        for c in self.columns.drain(..) {
            let mut f = c.into_inner().map_err(|e| e.into_error())?;
            f.rewind()?;
            columns.push(f);
        }
        let main = &mut self.main;
        let copy_column = |main: &mut BufWriter<_>, key: &str, f: &mut File| {
            write!(main, "\"{key}\":[")?;
            std::io::copy(f, main)?;
            write!(main, "]")
        };
        write!(main, "{{")?;
        copy_column(main, COLUMNS[0], &mut columns[0])?;
        write!(main, ",")?;
        copy_column(main, COLUMNS[1], &mut columns[1])?;
        write!(main, ",\"dim\":{},\"drift\":", self.dim)?;
        serde_json::to_writer(
            &mut *main,
            &serde_json::json!({
                "energy": self.drift.energy,
                "casimirs": self.drift.casimirs,
                "manakov": self.manakov_drift,
                "space_momentum": self.drift.space_momentum,
            }),
        )?;
        for k in 2..5 {
            write!(main, ",")?;
            copy_column(main, COLUMNS[k], &mut columns[k])?;
        }
        write!(main, ",\"planes\":")?;
        serde_json::to_writer(&mut *main, &plane_names(self.dim))?;
        write!(main, ",\"times\":")?;
        serde_json::to_writer(&mut *main, &self.times)?;
        writeln!(main, "}}")
    }
}

/// The report's text through [`ReportStream`] from an in-memory [`Report`]'s states: what a
/// test compares with [`Report`]'s own formatting.
#[cfg(test)]
pub(crate) fn stream_text(
    start: &RigidBody,
    times: &[f64],
    states: &[State],
    format: Format,
) -> String {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let path = dir.path().join("report.out");
    let mut s = ReportStream::new(start, times, format, Some(&path), false).expect("stream");
    for st in states {
        s.push(st.clone()).expect("push");
    }
    s.finish().expect("finish").publish().expect("publish");
    std::fs::read_to_string(&path).expect("the report")
}

#[cfg(test)]
mod tests {
    use super::super::motion::{ReportText, report_from_states};
    use super::super::output::to_json_text;
    use super::*;
    use rotorflow::prelude::*;

    #[test]
    fn streamed_reports_equal_the_in_memory_ones() {
        for n in [3, 4, 5] {
            let j: Vec<f64> = (0..n).map(|k| 1.0 + 0.4 * k as f64).collect();
            let k = n * (n - 1) / 2;
            let w: Vec<f64> = (0..k).map(|i| (0.9 * i as f64 + 0.2).sin()).collect();
            let start = RigidBody::from_body_velocity(
                InertiaMap::from_principal_second_moments(&j).unwrap(),
                Rotor::identity(n),
                &Bivector::from_components(n, &w).unwrap(),
            )
            .unwrap();
            let times: Vec<f64> = (0..7).map(|i| 0.3 * i as f64).collect();
            let traj = rotorflow::dynamics::simulate(
                &start,
                &mut rotorflow::dynamics::Rkmk4,
                &rotorflow::dynamics::torques::Free,
                0.01,
                &times,
            )
            .unwrap();
            let states: Vec<State> = traj
                .samples()
                .iter()
                .map(|s| (s.attitude.clone(), s.momentum.clone()))
                .collect();
            let report =
                report_from_states(&start, &times, states.iter().cloned().map(Ok)).unwrap();
            assert_eq!(
                stream_text(&start, &times, &states, Format::Json),
                to_json_text(&report.to_json(), false).unwrap()
            );
            assert_eq!(
                stream_text(&start, &times, &states, Format::Csv),
                report.to_csv()
            );
            assert_eq!(
                stream_text(&start, &times, &states, Format::Text),
                report.to_text()
            );
        }
    }
}
