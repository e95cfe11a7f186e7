//! rotorflow's versor exp and log beside the peer libraries, for the book (chapter "Other
//! signatures", section "Where the peers stand").
//!
//! 1. `python3 scripts/peer_versors.py --write` runs kingdon, clifford, ganja.js and klein on
//!    a fixed set of bivectors and records, in `book/src/generated/peer_versors.tsv`, each
//!    case's input B (mask=f64 pairs), its high-precision exp(B), each peer's errors or
//!    outcomes and its times, with the date, the commit, the machine and the package
//!    versions.
//! 2. `cargo run --example book_peer_versors -- --write` reads that file, computes
//!    rotorflow's errors on the same cases with the same measures, and renders
//!    `book/src/generated/peer_versors.md`. Without `--write` it prints the table.
//!
//! `tests/book.rs` re-renders the committed data and fails when the committed table differs,
//! and asserts that rotorflow's errors are at most 1e-14 on every case.
//!
//! The table gives rotorflow's accuracy only: its speed comes from the criterion benches
//! (`cargo bench --bench versors`), not from a loop here. The peers' times are those the
//! script measured, in each package's own language, beside its call overhead. rotorflow's
//! errors below 1e-15 are shown as "< 1e-15", so that the committed table does not depend on
//! the last bits of the platform's `sin` and `cos`.

use rotorflow::algebra::{Multivector, Signature};
use std::error::Error;
use std::fmt::Write as _;
use std::path::PathBuf;

type Res<T> = Result<T, Box<dyn Error>>;

/// Errors below this are round-off and are shown as "< 1e-15".
const FLOOR: f64 = 1e-15;

/// Recorded outcomes longer than this (exception messages, mostly) are shown as a note
/// letter, with the text once under the tables.
const INLINE_OUTCOME: usize = 24;

/// One case of the data file.
#[derive(Clone, Debug)]
pub struct Case {
    /// Identifier, e.g. `pga_screw`.
    pub id: String,
    /// (p, q, r).
    pub sig: (usize, usize, usize),
    /// The bivector B.
    pub b: Multivector,
    /// The reference exp(B), rounded to f64.
    pub v: Multivector,
    /// A short description.
    pub title: String,
}

/// rotorflow's errors on one case, with the measures of the peers' columns.
#[derive(Clone, Debug)]
pub struct Errors {
    /// Case identifier.
    pub id: String,
    /// max_k |exp(B)_k − V_k| / max(1, max_k |V_k|).
    pub exp: f64,
    /// max_k |log(exp(B))_k − B_k| / max_k |B_k|.
    pub log: f64,
}

/// A peer library: name, version, how it was run, its exp and log functions.
struct Peer {
    name: String,
    version: String,
    how: String,
    exp: String,
    log: String,
    overhead: String,
}

/// A peer's recorded result on one case: exp and log cells (an error or an outcome) and
/// times in µs ("-" when not run).
struct Outcome {
    exp: String,
    log: String,
    exp_us: String,
    log_us: String,
}

struct Data {
    meta: Vec<String>,
    cases: Vec<Case>,
    peers: Vec<Peer>,
    results: Vec<(String, String, Outcome)>,
}

fn parse_pairs(sig: Signature, text: &str) -> Res<Multivector> {
    let mut m = Multivector::try_zero(sig)?;
    for pair in text.split(',') {
        let (mask, value) = pair
            .split_once('=')
            .ok_or_else(|| format!("bad pair {pair:?}"))?;
        let mask: usize = mask.parse()?;
        let slot = m
            .as_mut_slice()
            .get_mut(mask)
            .ok_or_else(|| format!("mask {mask} outside the algebra"))?;
        *slot = value.parse()?;
    }
    Ok(m)
}

fn parse(tsv: &str) -> Res<Data> {
    let mut data = Data {
        meta: Vec::new(),
        cases: Vec::new(),
        peers: Vec::new(),
        results: Vec::new(),
    };
    for line in tsv.lines() {
        if let Some(m) = line.strip_prefix("# ") {
            let key = m.split(':').next().unwrap_or("");
            if [
                "date", "commit", "machine", "python", "node", "compiler", "command",
            ]
            .contains(&key)
            {
                data.meta.push(m.to_string());
            }
            continue;
        }
        if line.trim().is_empty() || line.starts_with('#') {
            continue;
        }
        let f: Vec<&str> = line.split('\t').collect();
        let bad = || format!("bad data line: {line}");
        match (f[0], f.len()) {
            ("case", 6) => {
                let pqr: Vec<usize> = f[2].split(' ').map(str::parse).collect::<Result<_, _>>()?;
                let [p, q, r] = pqr[..] else {
                    return Err(bad().into());
                };
                let sig = Signature::new(p, q, r)?;
                data.cases.push(Case {
                    id: f[1].into(),
                    sig: (p, q, r),
                    b: parse_pairs(sig, f[3])?,
                    v: parse_pairs(sig, f[4])?,
                    title: f[5].into(),
                });
            }
            ("peer", 6) => data.peers.push(Peer {
                name: f[1].into(),
                version: f[2].into(),
                how: f[3].into(),
                exp: f[4].into(),
                log: f[5].into(),
                overhead: "-".into(),
            }),
            ("overhead", 3) => {
                let peer = data
                    .peers
                    .iter_mut()
                    .find(|p| p.name == f[1])
                    .ok_or_else(bad)?;
                peer.overhead = f[2].into();
            }
            ("result", 7) => data.results.push((
                f[1].into(),
                f[2].into(),
                Outcome {
                    exp: f[3].into(),
                    log: f[4].into(),
                    exp_us: f[5].into(),
                    log_us: f[6].into(),
                },
            )),
            _ => return Err(bad().into()),
        }
    }
    if data.cases.is_empty() || data.peers.is_empty() {
        return Err("no cases or no peers in the data file".into());
    }
    Ok(data)
}

fn max_diff(a: &Multivector, b: &Multivector) -> f64 {
    a.as_slice()
        .iter()
        .zip(b.as_slice())
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

/// rotorflow's errors on one case.
fn errors(c: &Case) -> Res<Errors> {
    let e = c.b.exp()?;
    let l = e.log()?;
    Ok(Errors {
        id: c.id.clone(),
        exp: max_diff(&e, &c.v) / c.v.max_abs().max(1.0),
        log: max_diff(&l, &c.b) / c.b.max_abs(),
    })
}

/// rotorflow's errors on every case of the data file's text.
pub fn rotorflow_errors(tsv: &str) -> Res<Vec<Errors>> {
    parse(tsv)?.cases.iter().map(errors).collect()
}

/// Exact zeros print like the rest of the round-off: which cases come out exact depends on
/// the order of operations, not on the method.
fn rotorflow_cell(e: f64) -> String {
    if e < FLOOR {
        "< 1e-15".into()
    } else {
        format!("{e:.1e}")
    }
}

/// A recorded cell, safe inside a markdown table.
fn escape(text: &str) -> String {
    text.replace('|', "\\|")
}

fn signature_cell(sig: (usize, usize, usize)) -> String {
    format!("{},{},{}", sig.0, sig.1, sig.2)
}

/// The notes of long outcomes: each distinct text once, lettered in order of appearance.
#[derive(Default)]
struct Notes(Vec<String>);

impl Notes {
    /// A recorded cell: an error as recorded, a short outcome as it is, a long one as its
    /// note letter.
    fn cell(&mut self, text: &str) -> String {
        if text.parse::<f64>().is_ok() || text.chars().count() <= INLINE_OUTCOME {
            return escape(text);
        }
        let k = match self.0.iter().position(|t| t == text) {
            Some(k) => k,
            None => {
                self.0.push(text.to_string());
                self.0.len() - 1
            }
        };
        format!("({})", letter(k))
    }
}

fn letter(k: usize) -> char {
    char::from(b'a' + u8::try_from(k % 26).unwrap_or(0))
}

/// Renders the markdown of the book from the data file's text.
pub fn render(tsv: &str) -> Res<String> {
    let data = parse(tsv)?;
    let outcome = |peer: &str, id: &str| -> Res<&Outcome> {
        data.results
            .iter()
            .find(|(p, c, _)| p == peer && c == id)
            .map(|r| &r.2)
            .ok_or_else(|| format!("no result for {peer} on {id}").into())
    };
    let mut out = String::new();
    writeln!(
        out,
        "<!-- Generated by `cargo run --example book_peer_versors -- --write` from \
         peer_versors.tsv (written by `python3 scripts/peer_versors.py --write`); do not \
         edit. -->\n"
    )?;
    writeln!(out, "Where and when the peers were run:\n")?;
    for m in &data.meta {
        writeln!(out, "- {}", escape(m))?;
    }
    writeln!(
        out,
        "\n| library | version | run as | exp | log | call overhead (µs) |"
    )?;
    writeln!(out, "|---|---|---|---|---|---|")?;
    for p in &data.peers {
        writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} |",
            p.name,
            p.version,
            escape(&p.how),
            escape(&p.exp),
            escape(&p.log),
            p.overhead
        )?;
    }
    let header = |out: &mut String, first: &str| -> Res<()> {
        write!(out, "\n| case | Cl(p,q,r) |{first}")?;
        for p in &data.peers {
            write!(out, " {} |", p.name)?;
        }
        write!(
            out,
            "\n|---|---|{}",
            if first.is_empty() { "" } else { "---|" }
        )?;
        for _ in &data.peers {
            write!(out, "---|")?;
        }
        writeln!(out)?;
        Ok(())
    };
    let mut ours = Vec::new();
    for c in &data.cases {
        ours.push(errors(c)?);
    }
    let mut notes = Notes::default();

    writeln!(
        out,
        "\n**exp(B)**: max |exp(B) − V| / max(1, max |V|) over the coefficients, against the \
         high-precision V. rotorflow's column is `Multivector::exp` of this checkout, computed \
         when the table is rendered."
    )?;
    header(&mut out, " rotorflow |")?;
    for (c, e) in data.cases.iter().zip(&ours) {
        write!(
            out,
            "| {} | {} | {} |",
            escape(&c.title),
            signature_cell(c.sig),
            rotorflow_cell(e.exp)
        )?;
        for p in &data.peers {
            write!(out, " {} |", notes.cell(&outcome(&p.name, &c.id)?.exp))?;
        }
        writeln!(out)?;
    }

    writeln!(
        out,
        "\n**log(exp(B))**: max |log(exp(B)) − B| / max |B| over the coefficients, each \
         library's logarithm of its own exp(B) (every B is inside the principal branch)."
    )?;
    header(&mut out, " rotorflow |")?;
    for (c, e) in data.cases.iter().zip(&ours) {
        write!(
            out,
            "| {} | {} | {} |",
            escape(&c.title),
            signature_cell(c.sig),
            rotorflow_cell(e.log)
        )?;
        for p in &data.peers {
            write!(out, " {} |", notes.cell(&outcome(&p.name, &c.id)?.log))?;
        }
        writeln!(out)?;
    }
    if !notes.0.is_empty() {
        writeln!(out, "\nOutcomes, as recorded:\n")?;
        for (k, text) in notes.0.iter().enumerate() {
            writeln!(out, "- ({}) {}", letter(k), escape(text))?;
        }
    }

    writeln!(
        out,
        "\n**Time per call** in µs, exp / log, as the script measured it in each library's own \
         language (best of 5 loops of at least 20 ms; compare with the call overhead above). \
         rotorflow's times come from its criterion benches: `cargo bench --bench versors`."
    )?;
    header(&mut out, "")?;
    for c in &data.cases {
        write!(out, "| {} | {} |", escape(&c.title), signature_cell(c.sig))?;
        for p in &data.peers {
            let o = outcome(&p.name, &c.id)?;
            write!(out, " {} / {} |", o.exp_us, o.log_us)?;
        }
        writeln!(out)?;
    }
    Ok(out)
}

/// Writes the table rendered from the committed data file, or prints it.
pub fn main() -> Res<()> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let data = root.join("book/src/generated/peer_versors.tsv");
    let table = root.join("book/src/generated/peer_versors.md");
    let md = render(&std::fs::read_to_string(&data)?)?;
    if std::env::args().any(|a| a == "--write") {
        std::fs::write(&table, &md)?;
        println!("wrote {}", table.display());
    } else {
        print!("{md}");
    }
    Ok(())
}
