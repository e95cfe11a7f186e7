//! Reliability: numerically hostile inputs with asserted bounds, adversarial
//! magnitudes, and long runs (ignored by default; `.ci/run` runs them with a time bound).

mod adversarial;
mod detection;
mod fuzz_regressions;
mod hostile;
mod long_runs;
mod narrow_phase;
