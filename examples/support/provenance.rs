//! Where and when a measurement was taken: the `# key: value` header lines of the book's
//! recorded timing data (`examples/bench_table.rs`, `examples/step_ratio.rs`).

use std::process::Command;

fn command_output(cmd: &str, args: &[&str]) -> String {
    Command::new(cmd)
        .args(args)
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_default()
}

/// The commit the measured code is at: the short hash of HEAD, with "dirty" when tracked
/// files outside `book/src/generated/` differ from it (the recorded data themselves do not
/// make the measured code dirty), or "unknown" outside a git checkout.
pub fn commit() -> String {
    let hash = command_output("git", &["rev-parse", "--short", "HEAD"]);
    if hash.is_empty() {
        return "unknown (not a git checkout)".into();
    }
    let changes = command_output(
        "git",
        &[
            "status",
            "--porcelain",
            "--untracked-files=no",
            "--",
            ".",
            ":(exclude)book/src/generated",
        ],
    );
    if changes.is_empty() {
        hash
    } else {
        format!("{hash} dirty (uncommitted changes to tracked files)")
    }
}

/// The processor, the number of cores and the operating system.
pub fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, v)| v.trim().to_string())
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string());
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    format!("{cpu}, {cores} cores, {}", std::env::consts::OS)
}

/// The header lines `# date:`, `# commit:`, `# machine:` and `# compiler:`, each ending in a
/// newline.
pub fn header() -> String {
    format!(
        "# date: {}\n# commit: {}\n# machine: {}\n# compiler: {}\n",
        command_output("date", &["-u", "+%Y-%m-%d"]),
        commit(),
        machine(),
        command_output("rustc", &["-V"])
    )
}
