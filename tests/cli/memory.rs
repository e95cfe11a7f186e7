//! `simulate` streams its samples to the output: its peak memory does not grow with the
//! number of samples (read from the kernel's high-water mark of the process, Linux only).

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Duration;

/// Peak resident memory (VmHWM, kB) of `rotorflow simulate` with `samples` samples of an
/// 8D body, one step per sample, written as `format` to a file in `dir`.
#[cfg(target_os = "linux")]
fn peak_kb(dir: &Path, samples: usize, format: &str) -> u64 {
    let spec = "cuboid:1,1.1,1.2,1.3,1.4,1.5,1.6,1.7";
    let omega: Vec<String> = (0..28)
        .map(|k| format!("{:.3}", (0.7 * k as f64 + 0.3).sin()))
        .collect();
    let out = dir.join(format!("out.{format}"));
    let mut child = Command::new(env!("CARGO_BIN_EXE_rotorflow"))
        .args([
            "--quiet",
            "simulate",
            "--body",
            spec,
            &format!("--omega={}", omega.join(",")),
            "--t-end",
            "1",
            "--samples",
            &samples.to_string(),
            "--dt",
            "1",
            "--integrator",
            "strang",
            "--output",
        ])
        .arg(&out)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("rotorflow runs");
    let status_file = format!("/proc/{}/status", child.id());
    let mut peak = 0;
    loop {
        // The high-water mark only grows; the last reading before exit is the peak up to
        // a few milliseconds.
        if let Ok(text) = std::fs::read_to_string(&status_file) {
            for line in text.lines() {
                if let Some(v) = line.strip_prefix("VmHWM:") {
                    let kb: u64 = v.trim().trim_end_matches("kB").trim().parse().unwrap_or(0);
                    peak = peak.max(kb);
                }
            }
        }
        if let Some(status) = child.try_wait().expect("wait") {
            assert!(status.success(), "simulate with {samples} samples failed");
            break;
        }
        std::thread::sleep(Duration::from_micros(100));
    }
    assert!(out.exists(), "the report was written");
    peak
}

/// [`peak_kb`], repeated until a reading shows the loaded program (a run that ends between
/// two readings can leave only the reading taken before the binary was mapped), at most
/// five times.
#[cfg(target_os = "linux")]
fn loaded_peak_kb(dir: &Path, samples: usize, format: &str) -> u64 {
    for _ in 0..5 {
        let kb = peak_kb(dir, samples, format);
        if kb >= 1000 {
            return kb;
        }
    }
    panic!("no reading of the running program with {samples} samples");
}

#[test]
#[cfg(target_os = "linux")]
fn simulate_memory_does_not_grow_with_the_samples() {
    let dir = tempfile::tempdir().unwrap();
    for format in ["json", "csv"] {
        // 200 samples: as flat as 2, and long enough to be read while it runs.
        let small = loaded_peak_kb(dir.path(), 200, format);
        let large = loaded_peak_kb(dir.path(), 20_000, format);
        eprintln!("{format}: peak {small} kB with 200 samples, {large} kB with 20,000");
        // Kept in memory, 20,000 8D samples would take ~15 MB as numbers and several times
        // that as JSON text.
        assert!(
            large <= 2 * small,
            "{format}: {large} kB with 20,000 samples against {small} kB with 200"
        );
    }
}
