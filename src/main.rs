//! The `rotorflow` command: see `rotorflow --help` and the `rotorflow::cli` module.

fn main() -> std::process::ExitCode {
    rotorflow::cli::run()
}
