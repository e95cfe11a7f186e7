//! The Criterion settings every bench shares (`#[path]`-included by each `benches/*.rs`), so
//! that their numbers are measured the same way. `BENCH_QUICK=1` shortens the run.

use criterion::Criterion;
use std::time::Duration;

/// Criterion with the command-line options applied, no plots, and the shared warm-up,
/// measurement time and sample size (shorter under `BENCH_QUICK`).
pub fn configure() -> Criterion {
    let quick = std::env::var_os("BENCH_QUICK").is_some();
    Criterion::default()
        .configure_from_args()
        .without_plots()
        .warm_up_time(Duration::from_millis(if quick { 200 } else { 500 }))
        .measurement_time(Duration::from_millis(if quick { 500 } else { 1500 }))
        .sample_size(if quick { 20 } else { 40 })
}
