//! The `rotorflow` command: see `rotorflow --help`. The command's code is private to the
//! binary; the library (`rotorflow::…`) is all a program needs.

mod cli;

fn main() -> std::process::ExitCode {
    cli::run()
}
