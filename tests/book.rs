//! Mechanical checks of the book (`book/`), run by `cargo test`:
//!
//! - every `{{#include}}` resolves to a file; an included example is one that this test
//!   compiles (through `#[path]`, so it is always the current source) and runs; an included
//!   generated file is one whose generator this test re-runs;
//! - the generated tables and plots equal their generators' output (byte for byte: the
//!   generators print no timings — the timing tables are rendered from their recorded data
//!   files, which carry the date, commit, machine and compiler of the measurement —
//!   and print their numbers with two or three significant digits; `book_closed_form` also
//!   shows round-off-level differences as a bound, "< 1e-13", so that its files do not
//!   depend on the last bits of the platform's libm);
//! - every errata entry names a test, `path::fn_name` or a bare name in the page's default
//!   test file, and every test named anywhere in the book exists as a `#[test] fn` that is
//!   not ignored, in a file that belongs to a test target (so `cargo test` runs it, and the
//!   run passes only if it passes).
//!
//! `mdbook build` and the link check of the built HTML run in `.ci/run`.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

// The examples the book includes or whose output it includes. Each is compiled into this
// test from its source file and run below.
#[allow(dead_code)]
#[path = "../examples/bench_table.rs"]
mod bench_table;
#[allow(dead_code)]
#[cfg(feature = "cli")]
#[path = "../examples/book_cli_help.rs"]
mod book_cli_help;
#[allow(dead_code)]
#[path = "../examples/book_closed_form.rs"]
mod book_closed_form;
#[allow(dead_code)]
#[path = "../examples/book_inertia_tables.rs"]
mod book_inertia_tables;
#[allow(dead_code)]
#[path = "../examples/book_integrators.rs"]
mod book_integrators;
#[allow(dead_code)]
#[path = "../examples/book_literature.rs"]
mod book_literature;
#[allow(dead_code)]
#[path = "../examples/book_long_runs.rs"]
mod book_long_runs;
#[allow(dead_code)]
#[path = "../examples/book_moving_bodies.rs"]
mod book_moving_bodies;
#[allow(dead_code)]
#[path = "../examples/book_peer_versors.rs"]
mod book_peer_versors;
#[path = "../examples/custom_integrator.rs"]
mod custom_integrator;
#[path = "../examples/first_simulation.rs"]
mod first_simulation;
#[path = "../examples/heavy_top_4d.rs"]
mod heavy_top_4d;
#[path = "../examples/mesh_body.rs"]
mod mesh_body;
#[allow(dead_code)]
#[path = "../examples/other_signatures.rs"]
mod other_signatures;
#[path = "../examples/reaction_wheels_4d.rs"]
mod reaction_wheels_4d;
#[allow(dead_code)]
#[cfg(all(feature = "viz", feature = "serde"))]
#[path = "../examples/record_scene.rs"]
mod record_scene;
#[path = "../examples/rolling_ball.rs"]
mod rolling_ball;
#[allow(dead_code)]
#[path = "../examples/step_ratio.rs"]
mod step_ratio;
#[path = "../examples/torque_closure.rs"]
mod torque_closure;

/// The examples run by [`included_examples_run`]; the book may include only these.
const RUN_EXAMPLES: &[&str] = &[
    "bench_table",
    "book_cli_help",
    "book_closed_form",
    "book_inertia_tables",
    "book_integrators",
    "custom_integrator",
    "first_simulation",
    "heavy_top_4d",
    "mesh_body",
    "other_signatures",
    "reaction_wheels_4d",
    "record_scene",
    "rolling_ball",
    "torque_closure",
];

/// The generated files checked against their generators below; the book may include only
/// these from `generated/`.
const GENERATED: &[&str] = &[
    "bench_table.md",
    "cli_help.md",
    "closed_form.md",
    "closed_form_error.svg",
    "inertia_tables.md",
    "integrators.md",
    "integrators_error.svg",
    "literature.md",
    "literature_bruls.svg",
    "literature_free4.svg",
    "literature_free6.svg",
    "literature_free8.svg",
    "literature_hlw.svg",
    "literature_p4.svg",
    "literature_simo_wong.svg",
    "long_runs_cost.md",
    "long_runs_drift.md",
    "long_runs_rhs.md",
    "moving_bodies.md",
    "peer_versors.md",
    "python_bench.md",
    "rapier_bench.md",
    "step_ratio.md",
];

/// The Python examples the book may include, each run by the pytest file beside it.
const PYTHON_EXAMPLES: &[(&str, &str)] = &[("tour.py", "python/tests/test_tour.py")];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Every markdown file under book/src.
fn book_pages() -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![root().join("book/src")];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).expect("book/src") {
            let path = entry.expect("entry").path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "md") {
                out.push(path);
            }
        }
    }
    out.sort();
    assert!(out.len() > 5, "book pages not found");
    out
}

/// The targets of `{{#include …}}`-style directives in a page (path part, before any `:`).
fn includes(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for directive in ["{{#include ", "{{#rustdoc_include ", "{{#playground "] {
        let mut rest = text;
        while let Some(at) = rest.find(directive) {
            rest = &rest[at + directive.len()..];
            let end = rest.find("}}").expect("unterminated include");
            let target = rest[..end].trim();
            out.push(target.split(':').next().unwrap_or(target).to_string());
        }
    }
    out
}

#[test]
fn every_include_is_an_example_or_generated_file_that_tests_check() {
    let mut count = 0;
    for page in book_pages() {
        let text = read(&page);
        for target in includes(&text) {
            count += 1;
            let path = page.parent().unwrap().join(&target);
            assert!(
                path.is_file(),
                "{}: include of missing file {target}",
                page.display()
            );
            let canon = path.canonicalize().unwrap();
            let name = canon.file_name().unwrap().to_string_lossy().to_string();
            if canon.starts_with(root().join("examples")) {
                let stem = name.trim_end_matches(".rs");
                assert!(
                    RUN_EXAMPLES.contains(&stem),
                    "{}: includes example {stem}, which tests/book.rs does not run",
                    page.display()
                );
            } else if canon.starts_with(root().join("python/examples")) {
                let runner = PYTHON_EXAMPLES
                    .iter()
                    .find(|(example, _)| *example == name)
                    .unwrap_or_else(|| {
                        panic!(
                            "{}: includes python/examples/{name}, which no pytest runs",
                            page.display()
                        )
                    });
                assert!(
                    read(&root().join(runner.1)).contains(&name),
                    "{} does not run {name}",
                    runner.1
                );
            } else if canon.starts_with(root().join("book/src/generated")) {
                assert!(
                    GENERATED.contains(&name.as_str()),
                    "{}: includes generated/{name}, which tests/book.rs does not check",
                    page.display()
                );
            } else {
                panic!(
                    "{}: include of {target}: only examples/, python/examples/ and book/src/generated/ may be \
                     included (code and numbers come from the code)",
                    page.display()
                );
            }
        }
    }
    assert!(
        count >= 5,
        "expected the book to include examples, found {count}"
    );
}

#[test]
fn included_examples_run() {
    first_simulation::main().expect("first_simulation");
    heavy_top_4d::main().expect("heavy_top_4d");
    torque_closure::main().expect("torque_closure");
    mesh_body::main().expect("mesh_body");
    custom_integrator::main().expect("custom_integrator");
    other_signatures::main().expect("other_signatures");
    rolling_ball::main().expect("rolling_ball");
    reaction_wheels_4d::main().expect("reaction_wheels_4d");
    book_inertia_tables::render().expect("book_inertia_tables");
    #[cfg(all(feature = "viz", feature = "serde"))]
    {
        let dir = std::env::temp_dir().join(format!("rotorflow-book-{}", std::process::id()));
        let said = record_scene::record(&dir).expect("record_scene");
        for file in [
            "run.json",
            "ball.csv",
            "tesseract.csv",
            "system.csv",
            "run.html",
            "run.svg",
        ] {
            assert!(
                dir.join(file).is_file(),
                "record_scene wrote no {file}: {said}"
            );
        }
        std::fs::remove_dir_all(&dir).expect("remove the example's files");
    }
}

fn assert_current(file: &str, generated: &str, command: &str) {
    let path = root().join("book/src/generated").join(file);
    let committed = read(&path);
    assert!(
        committed == generated,
        "book/src/generated/{file} is stale: regenerate it with `{command}`"
    );
}

#[test]
fn generated_inertia_tables_are_current() {
    let text = book_inertia_tables::render().expect("render");
    assert_current(
        "inertia_tables.md",
        &text,
        "cargo run --example book_inertia_tables -- --write",
    );
}

#[test]
fn generated_integrator_survey_is_current() {
    let (md, svg) = book_integrators::render().expect("render");
    let command = "cargo run --example book_integrators -- --write";
    assert_current("integrators.md", &md, command);
    assert_current("integrators_error.svg", &svg, command);
}

#[test]
fn generated_closed_form_comparison_is_current() {
    let (md, svg) = book_closed_form::render().expect("render");
    let command = "cargo run --example book_closed_form -- --write";
    assert_current("closed_form.md", &md, command);
    assert_current("closed_form_error.svg", &svg, command);
}

/// The command-line reference: the help of every subcommand as the binary prints it, the
/// example command lines (each parsed by clap, its body SPEC by the grammar) and the files
/// of `demo`. Needs the `cli` feature (on by default and in `--all-features`).
#[cfg(feature = "cli")]
#[test]
fn generated_cli_reference_is_current() {
    let md = book_cli_help::render().expect("render");
    assert_current(
        "cli_help.md",
        &md,
        "cargo run --example book_cli_help -- --write",
    );
}

#[test]
fn generated_bench_table_is_rendered_from_its_data() {
    let data = read(&root().join("book/src/generated/bench_data.tsv"));
    let table = bench_table::render(&data).expect("render");
    assert_current(
        "bench_table.md",
        &table,
        "cargo run --release --example bench_table -- --write (after cargo bench)",
    );
    for key in ["# date: ", "# commit: ", "# machine: ", "# compiler: "] {
        assert!(data.contains(key), "bench_data.tsv lacks `{key}`");
    }
}

/// The Python benchmark is a measurement (python/bench/bench.py writes it whole): it must say
/// where, when and by which command it was measured, and hold both of its tables.
#[test]
fn generated_python_bench_says_where_it_was_measured() {
    let text = read(&root().join("book/src/generated/python_bench.md"));
    for key in [
        "Measured at commit `",
        "by `python3 python/bench/bench.py`",
        "| operation | rotorflow | other | other's time | ratio |",
        "| N | rotorflow | max error |",
    ] {
        assert!(text.contains(key), "python_bench.md lacks `{key}`");
    }
}

/// The Rapier comparison is a measurement (benches/rapier's `table` writes it whole, from
/// its bench run and its own stability runs): it must say where, when and by which command it
/// was measured, with which versions, and hold its three tables.
#[test]
fn generated_rapier_bench_says_where_it_was_measured() {
    let text = read(&root().join("book/src/generated/rapier_bench.md"));
    for key in [
        "Measured at commit `",
        "by `cargo bench --manifest-path benches/rapier/Cargo.toml",
        "against rapier3d ",
        "| scene | steps per call | rotorflow (ms/step) | Rapier, half-space floor (ms/step) | ratio | Rapier, cuboid floor (ms/step) | ratio |",
        "| scene | measure | rotorflow | Rapier, half-space floor | Rapier, cuboid floor |",
        "| scene | solves | unconverged | mean sweeps | most sweeps | worst residual |",
        "rotorflow SoftStep (ms/step)",
        "| rotorflow SoftStep |",
    ] {
        assert!(text.contains(key), "rapier_bench.md lacks `{key}`");
    }
}

/// The long runs of the dynamics chapter: its three tables are the rendering of the
/// recorded data, which says where and when it was computed.
#[test]
fn generated_long_runs_are_rendered_from_their_data() {
    let data = read(&root().join("book/src/generated/long_runs.tsv"));
    let tables = book_long_runs::render(&data).expect("render");
    for (file, table) in book_long_runs::FILES.iter().zip(&tables) {
        assert_current(
            file,
            table,
            "cargo run --release --example book_long_runs -- --write",
        );
    }
    for key in ["# date: ", "# commit: ", "# machine: ", "# compiler: "] {
        assert!(data.contains(key), "long_runs.tsv lacks `{key}`");
    }
}

#[test]
fn generated_step_ratios_are_rendered_from_their_data() {
    let data = read(&root().join("book/src/generated/step_ratio.tsv"));
    let table = step_ratio::render(&data).expect("render");
    assert_current(
        "step_ratio.md",
        &table,
        "cargo run --release --example step_ratio -- --write",
    );
    for key in ["# date: ", "# commit: ", "# machine: ", "# compiler: "] {
        assert!(data.contains(key), "step_ratio.tsv lacks `{key}`");
    }
}

/// The benchmarks from the literature: the tables and plots are the rendering of the
/// recorded data (rotorflow's and scipy's), both say where and when they were measured, and
/// the references they are measured against are recorded with their spread.
#[test]
fn generated_literature_benchmarks_are_rendered_from_their_data() {
    let rust = read(&root().join("book/src/generated/literature.tsv"));
    let scipy = read(&root().join("book/src/generated/literature_scipy.tsv"));
    let (md, plots) = book_literature::render(&rust, &scipy).expect("render");
    let command = "cargo run --release --example book_literature -- --write (after python3 \
                   scripts/literature_scipy.py --write for new scipy data or references)";
    assert_current("literature.md", &md, command);
    assert_eq!(plots.len(), book_literature::PROBLEMS.len());
    for (name, svg) in &plots {
        assert!(
            GENERATED.contains(&name.as_str()),
            "{name} is not in GENERATED"
        );
        assert_current(name, svg, command);
    }
    for key in ["# date: ", "# commit: ", "# machine: ", "# compiler: "] {
        assert!(rust.contains(key), "literature.tsv lacks `{key}`");
    }
    for key in ["# date: ", "# commit: ", "# machine: ", "# python: "] {
        assert!(scipy.contains(key), "literature_scipy.tsv lacks `{key}`");
    }
    for problem in ["hlw", "p4", "simo_wong", "bruls"] {
        assert!(
            scipy.contains(&format!("ref\t{problem}\t")),
            "literature_scipy.tsv has no reference for {problem}"
        );
    }
    // Each reference's two Taylor runs agree far beyond the errors measured against it.
    let spreads: Vec<f64> = scipy
        .lines()
        .filter_map(|l| l.strip_prefix("ref_spread\t"))
        .map(|l| {
            l.split('\t')
                .nth(1)
                .expect("spread")
                .parse()
                .expect("a number")
        })
        .collect();
    assert_eq!(spreads.len(), 4, "one spread per reference");
    assert!(spreads.iter().all(|s| *s < 1e-20), "spreads {spreads:?}");
    // The Taylor-series reference of the HLW body against rotorflow's closed form.
    let gap = book_literature::hlw_closed_form_gap(&scipy).expect("closed form");
    assert!(
        gap < 1e-12,
        "HLW reference and closed form differ by {gap:e}"
    );
}

/// The validation of moving bodies (chapter "Bodies that move"): the tables are the rendering
/// of the recorded data, the data say where and when they were measured, and every recorded
/// figure meets the bound the chapter states for it.
#[test]
fn generated_moving_body_validation_is_rendered_from_its_data() {
    let data = read(&root().join("book/src/generated/moving_bodies.tsv"));
    let table = book_moving_bodies::render(&data).expect("render");
    assert_current(
        "moving_bodies.md",
        &table,
        "cargo run --release --example book_moving_bodies -- --write",
    );
    for key in ["# date: ", "# commit: ", "# machine: ", "# compiler: "] {
        assert!(data.contains(key), "moving_bodies.tsv lacks `{key}`");
    }
    let failures = book_moving_bodies::check(&data).expect("the recorded figures");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The peer comparison of versor exp and log: the table is the rendering of the recorded
/// data, and rotorflow's own column, computed here from the recorded cases and their
/// high-precision references, stays within 1e-14 on every case.
#[test]
fn generated_peer_comparison_is_rendered_from_its_data() {
    let data = read(&root().join("book/src/generated/peer_versors.tsv"));
    let table = book_peer_versors::render(&data).expect("render");
    assert_current(
        "peer_versors.md",
        &table,
        "cargo run --example book_peer_versors -- --write (after python3 scripts/peer_versors.py \
         --write for new peer data)",
    );
    for key in [
        "# date: ",
        "# commit: ",
        "# machine: ",
        "# python: ",
        "# node: ",
    ] {
        assert!(data.contains(key), "peer_versors.tsv lacks `{key}`");
    }
    let cases = data.lines().filter(|l| l.starts_with("case\t")).count();
    let errors = book_peer_versors::rotorflow_errors(&data).expect("rotorflow's errors");
    assert!(
        cases >= 10 && errors.len() == cases,
        "checked {} of {cases} cases",
        errors.len()
    );
    let failures: Vec<String> = errors
        .iter()
        .filter(|e| !(e.exp <= 1e-14 && e.log <= 1e-14))
        .map(|e| format!("{}: exp error {:.1e}, log error {:.1e}", e.id, e.exp, e.log))
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A reference to a test: the file (relative to the repository) and the function name.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct TestRef {
    file: String,
    name: String,
}

/// The backticked tokens of a string.
fn backticked(text: &str) -> Vec<String> {
    text.split('`')
        .enumerate()
        .filter(|(k, _)| k % 2 == 1)
        .map(|(_, s)| s.to_string())
        .collect()
}

fn is_fn_name(s: &str) -> bool {
    s.contains('_')
        && s.chars().next().is_some_and(|c| c.is_ascii_lowercase())
        && s.chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
}

/// A `tests/…/file.rs::fn_name` token.
fn full_ref(token: &str) -> Option<TestRef> {
    let (file, name) = token.split_once("::")?;
    (file.starts_with("tests/") && file.ends_with(".rs") && is_fn_name(name)).then(|| TestRef {
        file: file.into(),
        name: name.into(),
    })
}

/// Test references in one table cell. A bare name resolves to the file of the last full
/// reference before it in the same cell, else to `default` (the page's default test file).
fn refs_in_cell(cell: &str, default: Option<&str>) -> Vec<TestRef> {
    let mut file = default.map(str::to_string);
    let mut out = Vec::new();
    for token in backticked(cell) {
        if let Some(r) = full_ref(&token) {
            file = Some(r.file.clone());
            out.push(r);
        } else if is_fn_name(&token) {
            let file = file
                .clone()
                .unwrap_or_else(|| panic!("bare test name `{token}` but no default file"));
            out.push(TestRef { file, name: token });
        }
    }
    out
}

/// Checks that `name` is a `#[test] fn` in `file`, not ignored, in a test target.
fn check_test_exists(r: &TestRef) -> Result<(), String> {
    let path = root().join(&r.file);
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", r.file))?;
    let needle = format!("fn {}(", r.name);
    let at = text
        .find(&needle)
        .ok_or_else(|| format!("{}: no fn {}", r.file, r.name))?;
    // The attributes directly above the function.
    let before: Vec<&str> = text[..at].lines().rev().skip(1).collect();
    let mut attrs = Vec::new();
    for line in before {
        let l = line.trim();
        if l.starts_with("#[") || l.starts_with("///") || l.starts_with("//") {
            attrs.push(l);
        } else {
            break;
        }
    }
    let line = text[..at].lines().last().unwrap_or("").trim();
    if !attrs.contains(&"#[test]") && !line.starts_with("#[test]") {
        return Err(format!("{}::{} is not a #[test] fn", r.file, r.name));
    }
    if attrs.iter().any(|a| a.starts_with("#[ignore")) {
        return Err(format!("{}::{} is #[ignore]d", r.file, r.name));
    }
    // The file must belong to a test target.
    let rel = Path::new(&r.file);
    let parts: Vec<_> = rel.components().collect();
    if parts.len() == 3 {
        let dir = root().join("tests").join(parts[1].as_os_str());
        let main = std::fs::read_to_string(dir.join("main.rs"))
            .map_err(|_| format!("{}: no tests/{:?}/main.rs", r.file, parts[1]))?;
        let module = rel.file_stem().unwrap().to_string_lossy();
        if !main.contains(&format!("mod {module};")) {
            return Err(format!("{}: not a module of its test target", r.file));
        }
    } else if parts.len() != 2 {
        return Err(format!("{}: not a test target file", r.file));
    }
    Ok(())
}

#[test]
fn every_errata_entry_names_a_passing_test() {
    let dir = root().join("book/src/errata");
    let mut pages: Vec<_> = std::fs::read_dir(&dir)
        .expect("book/src/errata")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "md") && !p.ends_with("index.md"))
        .collect();
    pages.sort();
    assert!(!pages.is_empty());
    let mut failures = Vec::new();
    let mut entries = 0;
    for page in &pages {
        let text = read(page);
        let default = text.find("All tests live in").and_then(|at| {
            backticked(&text[at..])
                .into_iter()
                .find(|t| t.starts_with("tests/") && t.ends_with(".rs"))
        });
        let mut columns: Option<(usize, Option<usize>)> = None;
        let mut previous: Vec<TestRef> = Vec::new();
        for line in text.lines() {
            if !line.starts_with('|') {
                columns = None;
                continue;
            }
            let cells: Vec<&str> = split_row(line);
            if cells
                .iter()
                .all(|c| c.chars().all(|ch| ch == '-' || ch == ':' || ch == ' '))
            {
                continue;
            }
            let Some((test_col, verdict_col)) = columns else {
                let test_col = cells.iter().position(|c| c.trim() == "test");
                let verdict_col = cells.iter().position(|c| c.trim() == "verdict");
                columns = test_col.map(|t| (t, verdict_col));
                continue;
            };
            entries += 1;
            let cell = cells.get(test_col).copied().unwrap_or("").trim();
            let verdict = verdict_col
                .and_then(|v| cells.get(v))
                .copied()
                .unwrap_or("");
            let refs = if cell == "same test" || cell == "same" {
                previous.clone()
            } else if cell == "—" && verdict.contains("not checkable") {
                Vec::new()
            } else {
                refs_in_cell(cell, default.as_deref())
            };
            if refs.is_empty() && !verdict.contains("not checkable") {
                failures.push(format!("{}: entry names no test: {line}", page.display()));
            }
            for r in &refs {
                if let Err(e) = check_test_exists(r) {
                    failures.push(format!("{}: {e}", page.display()));
                }
            }
            previous = refs;
        }
    }
    assert!(entries >= 40, "only {entries} errata entries found");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Splits a markdown table row into cells, honouring `\|` escapes and backticks.
fn split_row(line: &str) -> Vec<&str> {
    let mut cells = Vec::new();
    let bytes = line.as_bytes();
    let (mut start, mut in_code) = (1, false);
    for (k, &b) in bytes.iter().enumerate().skip(1) {
        match b {
            b'`' => in_code = !in_code,
            b'|' if !in_code && bytes[k - 1] != b'\\' => {
                cells.push(&line[start..k]);
                start = k + 1;
            }
            _ => {}
        }
    }
    cells
}

#[test]
fn every_test_named_in_the_book_exists() {
    let mut named = BTreeSet::new();
    for page in book_pages() {
        for token in backticked(&read(&page)) {
            if let Some(r) = full_ref(&token) {
                named.insert(r);
            }
        }
    }
    assert!(
        named.len() >= 10,
        "only {} test references found",
        named.len()
    );
    let failures: Vec<String> = named
        .iter()
        .filter_map(|r| check_test_exists(r).err())
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
