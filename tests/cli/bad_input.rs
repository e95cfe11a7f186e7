//! Bad input: one line on standard error naming the problem and the expected form, exit code
//! 2, no output file, no panic. One test per case.

use super::rotorflow;

/// Runs `args` in an empty folder (outputs are named relative to it) and checks the refusal.
fn refuses(args: &[&str], needle: &str) {
    let dir = tempfile::tempdir().unwrap();
    let out = rotorflow()
        .current_dir(dir.path())
        .args(args)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "rotorflow {args:?}: {err}");
    assert_eq!(err.lines().count(), 1, "not one line: {err}");
    assert!(err.contains(needle), "{err:?} lacks {needle:?}");
    assert!(
        !err.contains("panicked") && !err.contains("backtrace"),
        "{err}"
    );
    assert!(
        out.stdout.is_empty(),
        "stdout: {}",
        String::from_utf8_lossy(&out.stdout)
    );
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert!(left.is_empty(), "output files written: {left:?}");
}

/// Runs `simulate` with `extra` flags and defaults for the flags `extra` does not give.
fn simulate(body: &str, omega: &str, extra: &[&str], needle: &str) {
    let mut args = vec!["simulate", "--body", body, "--omega", omega, "--json"];
    for (flag, default) in [
        ("--t-end", "1"),
        ("--samples", "3"),
        ("--output", "out.json"),
        ("--plot", "out.svg"),
    ] {
        if !extra.contains(&flag) {
            args.extend([flag, default]);
        }
    }
    args.extend(extra);
    refuses(&args, needle);
}

fn inertia(body: &str, needle: &str) {
    refuses(
        &["inertia", "--body", body, "--json", "--output", "out.json"],
        needle,
    );
}

fn file_with(name: &str, text: &str) -> (tempfile::TempDir, String) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    let p = path.display().to_string();
    (dir, p)
}

macro_rules! cases {
    ($($name:ident => $body:block)*) => { $( #[test] fn $name() $body )* };
}

cases! {
    option_after_a_comma => { inertia("cuboid:1,2,3,4,mass=5", "write `+mass=5` (or a quoted `;mass=5`)") }
    output_json_flag_against_csv_name => { simulate("cuboid:1,2,3", "1,0,0", &["--output", "r.csv"], "names a csv file but --json was asked for") }
    output_csv_flag_against_json_name => {
        refuses(&["simulate", "--body", "cuboid:1,2,3", "--omega", "1,0,0", "--t-end", "1", "--samples", "2", "--csv", "--output", "r.json"], "names a json file but --csv was asked for")
    }
    output_json_flag_against_text_name => {
        refuses(&["inertia", "--body", "cuboid:1,2,3", "--json", "--output", "r.txt"], "names a txt file but --json was asked for")
    }
    inertia_has_no_csv => {
        refuses(&["inertia", "--body", "cuboid:1,2,3", "--output", "r.csv"], "this command writes no CSV")
    }
    axial_outside_3d => { simulate("cuboid:1,2,3,4", "1,0,0", &["--axial"], "--axial needs N = 3, the body has N = 4") }
    axial_with_too_many_components => { simulate("cuboid:1,2,3", "1,0,0,0", &["--axial"], "expected 3 components x,y,z (axial vector") }
    axial_torque_outside_3d => {
        refuses(&["simulate", "--body", "cuboid:1,2,3,4", "--axial", "--omega", "1,0,0", "--t-end", "1", "--samples", "2"], "--axial needs N = 3")
    }
    malformed_spec_without_kind => { inertia("cuboid1,2", "missing `KIND:`") }
    malformed_spec_unknown_kind => { inertia("hypercube:1,2", "unknown kind `hypercube`") }
    malformed_spec_bad_number => { inertia("cuboid:1,x,3", "`x` is not a number") }
    malformed_spec_empty_number => { inertia("cuboid:1,,3", "a number is missing") }
    malformed_spec_unknown_option => { inertia("cuboid:1,2+colour=3", "unknown option `colour`") }
    malformed_spec_mass_and_density => { inertia("cuboid:1,2+mass=1+density=2", "not both") }
    malformed_spec_density_of_point_masses => { inertia("tesseract:1,2+density=2", "density applies to solids") }
    wrong_count_pentachoron => { inertia("pentachoron:1,2,3", "expected 4") }
    wrong_count_tensor => { inertia("tensor:1,2,3", "not N*N") }
    wrong_count_planes => { inertia("planes:1,2", "plane moments has 2 entries") }
    wrong_count_omega => { simulate("cuboid:1,2,3", "1,2", &[], "2 components given; expected 3 components 12,13,23") }
    wrong_count_momentum => {
        refuses(&["simulate", "--body", "tesseract:1,2,3,4", "--momentum", "1,2,3", "--t-end", "1", "--samples", "2"], "expected 6 components 12,13,14,23,24,34")
    }
    wrong_count_torque => { simulate("cuboid:1,2,3", "1,2,3", &["--torque", "body:1"], "1 components given, N = 3 needs 3") }
    wrong_count_axes => {
        refuses(&["render", "--body", "cuboid:1,2,3,4", "--omega", "1,0,0,0,0,0", "--t-end", "1", "--output", "a.html", "--axes", "1,2"], "2 axes given")
    }
    negative_half_length => { inertia("cuboid:1,-2,3", "must be positive, got -2") }
    negative_radius => { inertia("ball:3,-1", "radius must be positive") }
    negative_principal_moment => { inertia("principal:1,-2,3", "must not be negative") }
    negative_mass => { inertia("cuboid:1,2+mass=-1", "mass must be positive") }
    dimension_too_small => { inertia("simplex:1", "dimension 1 is not supported") }
    non_finite_size => { inertia("ellipsoid:1,inf,2", "`inf` is not a finite number") }
    non_finite_omega => { simulate("cuboid:1,2,3", "1,nan,0", &[], "`nan` is not a finite number") }
    non_finite_t_end => {
        refuses(&["simulate", "--body", "cuboid:1,2,3", "--omega", "1,0,0", "--t-end", "NaN", "--samples", "3"], "not a finite number")
    }
    non_positive_t_end => { simulate("cuboid:1,2,3", "1,0,0", &["--t-end", "0"], "--t-end must be positive") }
    unknown_integrator => { simulate("cuboid:1,2,3", "1,0,0", &["--integrator", "euler"], "possible values: rk4, lie-poisson-rk4, dopri5, dop853, strang, yoshida4, suzuki4, kahan-li6, kahan-li8, midpoint, moser-veselov") }
    moser_veselov_needs_a_physical_body => {
        simulate("planes:0.6666666666666666,1,2", "0.3,0.2,1", &["--integrator", "mv", "--t-end", "1", "--samples", "2"], "needs a physical inertia map")
    }
    moser_veselov_step_too_large => {
        simulate("principal:1,2,3", "30,20,10", &["--integrator", "moser-veselov", "--t-end", "10", "--samples", "2", "--dt", "5"], "reduce the step")
    }
    times_not_increasing => {
        refuses(&["simulate", "--body", "cuboid:1,2,3", "--omega", "1,0,0", "--times", "0,2,1", "--output", "o.json"], "--times not increasing: 2 then 1")
    }
    times_negative => {
        refuses(&["simulate", "--body", "cuboid:1,2,3", "--omega", "1,0,0", "--times", "-1,2", "--output", "o.json"], "is negative")
    }
    times_and_samples => {
        refuses(&["simulate", "--body", "cuboid:1,2,3", "--omega", "1,0,0", "--t-end", "2", "--times", "0,1", "--samples", "3"], "not both")
    }
    too_few_samples => { simulate("cuboid:1,2,3", "1,0,0", &["--samples", "1"], "--samples must be between 2") }
    negative_step => { simulate("cuboid:1,2,3", "1,0,0", &["--dt", "-0.1"], "--dt must be positive") }
    step_with_dopri5 => { simulate("cuboid:1,2,3", "1,0,0", &["--integrator", "dopri5", "--dt", "0.1"], "dopri5 takes --rtol") }
    step_with_dop853 => { simulate("cuboid:1,2,3", "1,0,0", &["--integrator", "dop853", "--dt", "0.1"], "dop853 takes --rtol") }
    tolerance_with_rk4 => { simulate("cuboid:1,2,3", "1,0,0", &["--rtol", "1e-8"], "apply to dopri5") }
    too_many_steps => { simulate("cuboid:1,2,3", "1,0,0", &["--t-end", "1e9", "--dt", "1e-3"], "steps") }
    singular_body_moments => { simulate("principal:0,0,1", "1,0,0", &[], "singular") }
    singular_body_rod => {
        let (_keep, path) = file_with("rod.csv", "1,0,0,0\n1,1,0,0\n1,2,0,0\n");
        simulate(&format!("points:{path}"), "1,0,0", &[], "singular")
    }
    not_symmetric_tensor => { inertia("tensor:1,2,3,4", "not a valid mass tensor") }
    missing_points_file => { inertia("points:no-such-file.csv", "cannot read `no-such-file.csv`") }
    malformed_points_file => {
        let (_keep, path) = file_with("p.csv", "1,0,0\n1,1\n");
        inertia(&format!("points:{path}"), ":2: a row has 2 values")
    }
    malformed_mesh_file => {
        let (_keep, path) = file_with("m.mesh", "v 0 0\nv 1 0\nq 1 2\n");
        inertia(&format!("mesh:{path}"), "unknown record `q`")
    }
    mesh_vertex_out_of_range => {
        let (_keep, path) = file_with("m.mesh", "v 0 0\nv 1 0\nv 0 1\ns 1 2 9\n");
        inertia(&format!("mesh:{path}"), "refers to vertex")
    }
    unknown_torque => { simulate("cuboid:1,2,3", "1,0,0", &["--torque", "magnetic:1"], "unknown torque") }
    missing_initial_condition => {
        refuses(&["simulate", "--body", "cuboid:1,2,3", "--t-end", "1", "--samples", "3"], "--omega")
    }
    omega_and_momentum => {
        refuses(&["simulate", "--body", "cuboid:1,2,3", "--omega", "1,0,0", "--momentum", "1,0,0", "--t-end", "1", "--samples", "3"], "cannot be used with")
    }
    plot_not_svg => { simulate("cuboid:1,2,3", "1,0,0", &["--plot", "x.png"], "--plot `x.png`: expected a file name ending in .svg") }
    render_output_not_html_or_svg => {
        refuses(&["render", "--body", "cuboid:1,2,3", "--omega", "1,0,0", "--t-end", "1", "--output", "a.png"], "ending in .html or .svg")
    }
    render_repeated_axes => {
        refuses(&["render", "--body", "cuboid:1,2,3,4", "--omega", "1,0,0,0,0,0", "--t-end", "1", "--output", "a.html", "--axes", "1,1,2"], "the axes repeat")
    }
    render_axis_out_of_range => {
        refuses(&["render", "--body", "cuboid:1,2,3", "--omega", "1,0,0", "--t-end", "1", "--output", "a.html", "--axes", "1,2,4"], "out of range")
    }
    sweep_bad_shard => {
        refuses(&["sweep", "--body", "cuboid:1,2,{a}", "--param", "a=1:2:1", "--omega", "1,0,0", "--t-end", "1", "--samples", "3", "--shard", "4/3", "--output", "o.csv"], "expected I/N")
    }
    sweep_bad_param => {
        refuses(&["sweep", "--body", "cuboid:1,2,{a}", "--param", "a=1:2", "--omega", "1,0,0", "--t-end", "1", "--samples", "3", "--output", "o.csv"], "expected NAME=START:STOP:STEP")
    }
    sweep_unknown_template_name => {
        refuses(&["sweep", "--body", "cuboid:1,2,{b}", "--param", "a=1:2:1", "--omega", "1,0,0", "--t-end", "1", "--samples", "3", "--output", "o.csv"], "`{b}` names no --param")
    }
    sweep_bad_grid_point => {
        refuses(&["sweep", "--body", "cuboid:1,2,{a}", "--param", "a=-1:1:1", "--omega", "1,0,0", "--t-end", "1", "--samples", "3", "--output", "o.csv", "--plot", "o.svg"], "run 0 (a=-1)")
    }
    exact_bad_body => {
        refuses(&["exact", "--body", "cuboid:1,-2,3", "--omega", "1,0,0", "--t-end", "1", "--samples", "3", "--output", "o.json"], "must be positive")
    }
    unknown_subcommand => { refuses(&["integrate"], "unrecognized subcommand") }
    // Fuzz finding (target times_list): a STEP so small that the count of values overflowed
    // an integer (a panic in debug builds, an empty grid and a division by zero in release).
    fuzz_sweep_param_tiny_step => {
        refuses(&["sweep", "--body", "cuboid:1,2,{a}", "--param", "a=1:2:0.0000000000000000000000000000000000000000000000000000000000025", "--omega", "1,0,0", "--t-end", "1", "--samples", "3", "--output", "o.csv"], "values are too many (at most 100000)")
    }
    fuzz_sweep_param_step_below_the_smallest_double => {
        refuses(&["sweep", "--body", "cuboid:1,2,{a}", "--param", "a=-1e308:1e308:5e-324", "--omega", "1,0,0", "--t-end", "1", "--samples", "3", "--output", "o.csv"], "values are too many")
    }
    sweep_resume_without_csv => {
        refuses(&["sweep", "--body", "cuboid:1,2,{a}", "--param", "a=1:2:1", "--omega", "1,0,0", "--t-end", "1", "--samples", "3", "--resume"], "--output")
    }
}

#[test]
fn help_documents_every_option_and_points_to_the_grammar_once() {
    let help = |args: &[&str]| {
        let out = rotorflow().args(args).output().unwrap();
        assert!(out.status.success(), "{args:?}");
        String::from_utf8(out.stdout).unwrap()
    };
    let grammar = |text: &str| text.contains("tesseract:a,b,c") && text.contains("mesh:FILE");
    let mut checked = 0;
    for (sub, options) in [
        (
            "simulate",
            &[
                "--body",
                "--omega",
                "--momentum",
                "--torque",
                "--t-end",
                "--samples",
                "--times",
                "--integrator",
                "--dt",
                "--rtol",
                "--atol",
                "--json",
                "--csv",
                "--output",
                "--plot",
            ][..],
        ),
        (
            "exact",
            &[
                "--body",
                "--omega",
                "--momentum",
                "--samples",
                "--t-end",
                "--times",
                "--json",
                "--csv",
                "--output",
            ][..],
        ),
        ("inertia", &["--body", "--json", "--output"][..]),
        (
            "render",
            &[
                "--body",
                "--omega",
                "--t-end",
                "--output",
                "--projection",
                "--axes",
            ][..],
        ),
        (
            "sweep",
            &[
                "--body", "--param", "--shard", "--output", "--plot", "--resume",
            ][..],
        ),
        (
            "scene",
            &["--output", "--csv-dir", "--html", "--plot", "--check"][..],
        ),
        ("demo", &["--output-dir"][..]),
    ] {
        let text = help(&[sub, "--help"]);
        for o in options {
            assert!(text.contains(o), "`{sub} --help` lacks {o}");
        }
        // The grammar is printed by `help bodies` alone; a help that takes a body points there.
        assert!(!grammar(&text), "`{sub} --help` repeats the grammar");
        if options.contains(&"--body") || sub == "scene" {
            assert!(
                text.contains("rotorflow help bodies"),
                "`{sub} --help` does not point to the grammar"
            );
        }
        // `help SUB` prints the same as `SUB --help`.
        assert_eq!(help(&["help", sub]), text, "help {sub}");
        checked += 1;
    }
    assert_eq!(checked, 7);
    assert!(grammar(&help(&["help", "bodies"])));
    let top = help(&["--help"]);
    assert!(
        !grammar(&top) && top.contains("rotorflow help bodies"),
        "{top}"
    );
    refuses(
        &["help", "bodie"],
        "no topic `bodie` (expected bodies or a subcommand",
    );
}

/// One name means one thing in every subcommand: `--output` is a file, a folder option says
/// that it is one (`--output-dir`, `--csv-dir`), and `--csv` is the flag that asks for CSV.
#[test]
fn one_option_name_has_one_meaning_across_subcommands() {
    let subcommands = [
        "demo", "inertia", "simulate", "exact", "render", "sweep", "scene",
    ];
    let (mut outputs, mut csv_flags, mut dirs) = (0, 0, 0);
    for sub in subcommands {
        let out = rotorflow().args([sub, "--help"]).output().unwrap();
        let text = String::from_utf8(out.stdout).unwrap();
        for line in text.lines().map(str::trim_start) {
            let Some(rest) = line.strip_prefix("--") else {
                continue;
            };
            let name = rest.split([' ', '=']).next().unwrap();
            let value = rest[name.len()..]
                .trim_start()
                .strip_prefix('<')
                .map(|v| v.split('>').next().unwrap().to_string());
            match name {
                "output" => {
                    let v = value.clone().unwrap_or_default();
                    assert!(
                        v.starts_with("FILE"),
                        "`{sub} --output <{v}>` is not a file"
                    );
                    outputs += 1;
                }
                "csv" => {
                    assert_eq!(value, None, "`{sub} --csv` takes a value");
                    csv_flags += 1;
                }
                _ => {}
            }
            if value.as_deref() == Some("DIR") {
                assert!(
                    name.ends_with("-dir"),
                    "`{sub} --{name} <DIR>` does not say it is a folder"
                );
                dirs += 1;
            }
        }
    }
    // --output in inertia, simulate, exact, render, sweep and scene; --csv in simulate and
    // exact; folders in demo and scene.
    assert_eq!((outputs, csv_flags, dirs), (6, 2, 2));
}
