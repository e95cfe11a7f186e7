//! The command-line reference of the book (chapter "Command-line reference"):
//! `cargo run --example book_cli_help` prints it, and
//! `cargo run --example book_cli_help -- --write` rewrites `book/src/generated/cli_help.md`.
//! `tests/book.rs` runs [`render`] and fails when the committed file differs, so the book
//! always shows the help the `rotorflow` binary prints.
//!
//! Everything comes from the code: the help texts from clap (`cli::command()`, rendered
//! exactly as `rotorflow SUBCOMMAND --help` prints them), the files of `demo` from
//! `cli::demo::promised_files()`, and every example command line below is parsed by clap and
//! its body SPEC by `rotorflow::inertia::spec::parse_body` before it is written. The
//! command's modules are private to the binary; this program compiles the same source files.

// Only the clap description and the demo's file list are used here.
#[allow(dead_code)]
#[path = "../src/cli/mod.rs"]
mod cli;

use cli::{command, demo::promised_files, spec::GRAMMAR};
use rotorflow::inertia::spec::parse_body;
use std::error::Error;
use std::fmt::Write as _;

type Res<T> = Result<T, Box<dyn Error>>;

/// Example command lines per subcommand (without the leading `rotorflow`), with a comment.
const EXAMPLES: &[(&str, &[(&str, &str)])] = &[
    (
        "demo",
        &[(
            "the paper's cases, plots, animations and summary.md in out/",
            "demo --output-dir out",
        )],
    ),
    (
        "inertia",
        &[
            (
                "the paper's §4.1 tesseract: mass tensor, plane moments, the paper's tensors",
                "inertia --body tesseract:1,1.2,1.5,2",
            ),
            (
                "a 5D solid ellipsoid of mass 3, as JSON",
                "inertia --body ellipsoid:1,1.5,2,2.5,3+mass=3 --json",
            ),
        ],
    ),
    (
        "simulate",
        &[
            (
                "the first simulation of Getting started, as JSON",
                "simulate --body ellipsoid:1,1.5,2,2.5 --omega 1,0.02,-0.03,0.05,0.01,0.6 --t-end 50 --samples 11 --integrator strang --dt 0.01 --json",
            ),
            (
                "adaptive Dormand–Prince, CSV to a file and a plot of ω",
                "simulate --body cuboid:1,2,3,4 --omega 1,0,0,0,0,0.5 --t-end 20 --samples 201 --integrator dopri5 --rtol 1e-12 --atol 1e-14 --csv --output run.csv --plot omega.svg",
            ),
            (
                "a damped 3D top given by its momentum, at chosen times",
                "simulate --body principal:0.2,0.5,1 --momentum 0.3,-0.6,1 --torque damping:0.05 --times 0,1,2,5,10",
            ),
        ],
    ),
    (
        "exact",
        &[
            (
                "the paper's §7.2 body (half-axes 1, 1, 1, κ = 2) in closed form",
                "exact --body tesseract:1,1,1,2 --omega 0.3,-0.5,0.8,0.4,0.2,-0.6 --t-end 40 --samples 9",
            ),
            (
                "the free asymmetric 3D top (Jacobi functions), as JSON",
                "exact --body ellipsoid:1,2,3 --omega 0.01,1,0.01 --t-end 60 --samples 13 --json",
            ),
        ],
    ),
    (
        "render",
        &[
            (
                "an HTML animation of the tumbling tesseract",
                "render --body tesseract:1,1.2,1.5,2 --omega 1,0.05,0.02,0.03,0.04,0.7 --t-end 20 --output tesseract.html",
            ),
            (
                "a strip of 8 frames, axes 2, 3, 4, orthographic",
                "render --body cuboid:1,1.2,1.5,2 --omega 1,0.05,0.02,0.03,0.04,0.7 --t-end 20 --output strip.svg --axes 2,3,4 --projection orthographic",
            ),
        ],
    ),
    (
        "sweep",
        &[(
            "the §7.2 frequency against κ (the demo's sweep)",
            "sweep --body tesseract:1,1,1,{k} --param k=1.2:3.6:0.1 --omega 0.3,0.4,0.2,0.5,0.1,0.3 --t-end 120 --samples 2401 --integrator yoshida4 --dt 0.005 --axes 2,3,4 --output sweep.csv --plot sweep.svg",
        )],
    ),
    (
        "scene",
        &[
            (
                "a tesseract hanging from a spring under gravity: the summary",
                "scene scenes/tesseract-spring.toml",
            ),
            (
                "the same as JSON, one CSV per body, an animation and a plot of energies, momenta and positions",
                "scene scenes/tesseract-spring.toml --samples 101 --output run.json --csv-dir run-csv --html run.html --plot run.svg",
            ),
        ],
    ),
];

/// Splits a command line at spaces (the examples are written unquoted here; the book shows
/// them quoted, see [`quoted`]).
fn words(line: &str) -> Vec<&str> {
    std::iter::once("rotorflow")
        .chain(line.split_whitespace())
        .collect()
}

/// Returns the command line as a shell user types it: every body SPEC, and every argument a
/// shell would split or expand, in single quotes.
fn quoted(line: &str) -> String {
    let words: Vec<&str> = line.split_whitespace().collect();
    words
        .iter()
        .enumerate()
        .map(|(k, w)| {
            let after_body = k > 0 && words[k - 1] == "--body";
            if after_body || w.contains(['{', ';', '*', '?', '$', '&', '|']) {
                format!("'{w}'")
            } else {
                w.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// Checks that clap accepts the example and that its body SPEC parses (sweep templates with
/// the first value of the parameter).
fn check_example(line: &str) -> Res<()> {
    let argv = words(line);
    command()
        .try_get_matches_from(&argv)
        .map_err(|e| format!("`rotorflow {line}`: {e}"))?;
    if let Some(at) = argv.iter().position(|w| *w == "--body") {
        let mut spec = argv[at + 1].to_string();
        if let Some(p) = argv.iter().position(|w| *w == "--param") {
            let (name, range) = argv[p + 1].split_once('=').ok_or("bad --param")?;
            let start = range.split(':').next().ok_or("bad --param")?;
            spec = spec.replace(&format!("{{{name}}}"), start);
        }
        parse_body(&spec).map_err(|e| format!("`rotorflow {line}`: {e}"))?;
    }
    if argv[1] == "scene" {
        let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(argv[2]);
        rotorflow::scene::Scene::from_path(&file)
            .map_err(|e| format!("`rotorflow {line}`: {e}"))?;
    }
    Ok(())
}

/// The help `rotorflow ARGS… --help` prints (plain text, clap's fixed width of 100).
fn help(args: &[&str]) -> Res<String> {
    let mut argv = vec!["rotorflow"];
    argv.extend_from_slice(args);
    argv.push("--help");
    match command().try_get_matches_from(&argv) {
        Ok(_) => Err(format!("{argv:?} did not print help").into()),
        Err(e) if e.kind() == clap::error::ErrorKind::DisplayHelp => {
            let text = e.render().to_string();
            // Trailing spaces are clap's padding; markdown does not need them.
            let lines: Vec<&str> = text.lines().map(str::trim_end).collect();
            Ok(lines.join("\n").trim_end().to_string())
        }
        Err(e) => Err(format!("{argv:?}: {e}").into()),
    }
}

/// Returns the generated reference (markdown).
pub fn render() -> Res<String> {
    let mut md = String::new();
    writeln!(
        md,
        "<!-- Generated by `cargo run --example book_cli_help -- --write`; do not edit. -->\n"
    )?;
    writeln!(md, "### rotorflow\n")?;
    writeln!(md, "`rotorflow --help`:\n\n```text\n{}\n```\n", help(&[])?)?;
    writeln!(md, "### rotorflow help bodies\n")?;
    writeln!(
        md,
        "The grammar of a body SPEC (`--body`, and `shape` in a scene file), printed by \
         `rotorflow help bodies` and pointed to by every help that takes a SPEC:\n\n```text\n{}\n```\n",
        GRAMMAR
            .lines()
            .map(str::trim_end)
            .collect::<Vec<_>>()
            .join("\n")
    )?;
    let subcommands: Vec<String> = command()
        .get_subcommands()
        .map(|c| c.get_name().to_string())
        .filter(|n| n != "help")
        .collect();
    for name in &subcommands {
        let examples = EXAMPLES
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, e)| *e)
            .ok_or_else(|| format!("no examples for `{name}` in examples/book_cli_help.rs"))?;
        writeln!(md, "### rotorflow {name}\n")?;
        writeln!(md, "Examples:\n\n```sh")?;
        for (what, line) in examples {
            check_example(line)?;
            writeln!(md, "# {what}\ncargo run --release -- {}", quoted(line))?;
        }
        writeln!(md, "```\n")?;
        let text = help(&[name])?;
        writeln!(md, "`rotorflow {name} --help`:\n\n```text\n{text}\n```\n")?;
    }
    for (name, _) in EXAMPLES {
        if !subcommands.iter().any(|s| s == name) {
            return Err(format!("examples for `{name}`, which is not a subcommand").into());
        }
    }
    writeln!(md, "### The files of `rotorflow demo`\n")?;
    writeln!(
        md,
        "`rotorflow demo --output-dir DIR` writes exactly these files into DIR \
         (`tests/cli/demo.rs` checks that each is written):\n"
    )?;
    let files: Vec<String> = promised_files().iter().map(|f| format!("`{f}`")).collect();
    writeln!(md, "{}", files.join(", "))?;
    Ok(md)
}

/// Prints the reference, or writes it into the book with `--write`.
pub fn main() -> Res<()> {
    let md = render()?;
    if std::env::args().any(|a| a == "--write") {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/book/src/generated/cli_help.md"
        );
        std::fs::write(path, &md)?;
        println!("wrote {path}");
    } else {
        print!("{md}");
    }
    Ok(())
}
