//! The lists of numbers on the command line: sample times (`--t-end`, `--samples`,
//! `--times`), sweep parameters (`--param NAME=START:STOP:STEP`) and shards (`--shard I/N`).
//!
//! Self-contained (it uses only the library), so that the fuzz target `times_list` compiles
//! this same file. Errors are one-line messages; the command reports them as bad input.

use rotorflow::dynamics::trajectory::even_times;
use rotorflow::inertia::spec::{parse_list, parse_number};

fn input(message: impl Into<String>) -> String {
    message.into()
}

/// Returns the sample times: `samples` even times from 0 to `t_end`, or the listed `times`.
///
/// # Errors
/// A one-line message for a missing or non-positive end time, fewer than 2 samples, or
/// times that are negative, not increasing or beyond `t_end`.
pub fn sample_times(
    t_end: Option<f64>,
    samples: Option<usize>,
    times: Option<&str>,
) -> Result<Vec<f64>, String> {
    if let Some(t) = t_end
        && t <= 0.0
    {
        return Err(input(format!(
            "--t-end must be positive, got {t} (expected --t-end T with T > 0)"
        )));
    }
    match (samples, times) {
        (Some(_), Some(_)) => Err(input("give --samples K or --times t1,t2,..., not both")),
        (Some(k), None) => {
            let t = t_end.ok_or_else(|| {
                input("--samples needs --t-end T (expected --t-end T --samples K)")
            })?;
            if !(2..=10_000_000).contains(&k) {
                return Err(input(format!(
                    "--samples must be between 2 and 10000000, got {k} (expected --samples K)"
                )));
            }
            Ok(even_times(t, k))
        }
        (None, Some(list)) => {
            let v = parse_list(list).map_err(|e| {
                input(format!(
                    "--times: {e} (expected --times t1,t2,... increasing, >= 0)"
                ))
            })?;
            if let Some(t) = v.iter().find(|t| **t < 0.0) {
                return Err(input(format!(
                    "--times: {t} is negative (expected --times t1,t2,... increasing, >= 0)"
                )));
            }
            if let Some(w) = v.windows(2).find(|w| w[1] <= w[0]) {
                return Err(input(format!(
                    "--times not increasing: {} then {} (expected --times t1,t2,... strictly increasing, >= 0)",
                    w[0], w[1]
                )));
            }
            if let (Some(end), Some(last)) = (t_end, v.last())
                && *last > end
            {
                return Err(input(format!("--times: {last} is beyond --t-end {end}")));
            }
            Ok(v)
        }
        (None, None) => Err(input(
            "give --samples K (with --t-end T) or --times t1,t2,...",
        )),
    }
}

/// One parameter of the grid.
#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    /// The name substituted for `{NAME}`.
    pub name: String,
    /// Its values.
    pub values: Vec<f64>,
}

/// Parses `NAME=START:STOP:STEP`.
///
/// # Errors
/// A one-line message naming the problem and the expected form.
pub fn parse_param(text: &str) -> Result<Param, String> {
    let bad = |m: String| {
        format!("--param `{text}`: {m} (expected NAME=START:STOP:STEP, e.g. d=1:2:0.25)")
    };
    let (name, range) = text
        .split_once('=')
        .ok_or_else(|| bad("missing `=`".into()))?;
    let name = name.trim();
    if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Err(bad("the name must be letters, digits or _".into()));
    }
    let parts: Vec<&str> = range.split(':').collect();
    if parts.len() != 3 {
        return Err(bad(format!("{} fields after `=`", parts.len())));
    }
    let v: Vec<f64> = parts
        .iter()
        .map(|p| parse_number(p).map_err(bad))
        .collect::<Result<_, String>>()?;
    let (start, stop, step) = (v[0], v[1], v[2]);
    if step == 0.0 || (stop - start) * step < 0.0 {
        return Err(bad(
            "STEP must be non-zero and lead from START to STOP".into()
        ));
    }
    // Count in floating point first: a tiny STEP makes the quotient huge (or infinite), and
    // a cast to an integer would saturate and overflow.
    let span = ((stop - start) / step * (1.0 + 1e-12) + 1e-9).floor();
    if span.is_nan() || span >= 100_000.0 {
        return Err(bad(format!(
            "{} values are too many (at most 100000)",
            if span < 1e15 {
                format!("{}", span + 1.0)
            } else {
                format!("{:e}", span + 1.0)
            }
        )));
    }
    let count = span as u64 + 1;
    let values = (0..count)
        .map(|k| {
            let x = start + k as f64 * step;
            // Keep 12 significant digits so that 0.1 steps print as 0.3, not 0.30000000000000004.
            let scale = 10f64.powi(11 - x.abs().max(1e-300).log10().floor() as i32);
            if scale.is_finite() {
                (x * scale).round() / scale
            } else {
                x
            }
        })
        .collect();
    Ok(Param {
        name: name.to_string(),
        values,
    })
}

/// Parses `--shard I/N` (1-based) and returns the half-open block of run indices of `total`.
///
/// # Errors
/// A one-line message unless 1 ≤ I ≤ N.
pub fn shard_range(text: &str, total: usize) -> Result<(usize, usize, usize), String> {
    let bad = || {
        format!("--shard `{text}`: expected I/N with whole numbers 1 <= I <= N (e.g. --shard 2/8)")
    };
    let (i, n) = text.split_once('/').ok_or_else(bad)?;
    let i: usize = i.trim().parse().map_err(|_| bad())?;
    let n: usize = n.trim().parse().map_err(|_| bad())?;
    if n == 0 || i == 0 || i > n {
        return Err(bad());
    }
    // In 128 bits: total · I overflows a usize for huge I/N; the quotients are at most
    // `total`.
    let at = |k: usize| (total as u128 * k as u128 / n as u128) as usize;
    Ok((at(i - 1), at(i), i))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// times_list: `--param d=1:2:2.5e-60` (and any STEP below (STOP − START)/1e5) overflowed the
    /// integer count of values; now one bad-input error. The command-line side is in tests/cli/bad_input.rs.
    #[test]
    fn fuzz_param_with_a_tiny_step_is_an_error_not_a_panic() {
        for text in [
            "d=1:2:0.0000000000000000000000000000000000000000000000000000000000025",
            "d=-1e308:1e308:5e-324",
            "d=0:1e308:1e-308",
        ] {
            let err = parse_param(text).unwrap_err().to_string();
            assert!(err.contains("too many"), "{text}: {err}");
        }
        assert_eq!(parse_param("d=1:2:0.25").unwrap().values.len(), 5);
    }

    /// times_list: `--shard 8000000000000000026/8000000000000000026` overflowed total · I (a
    /// panic with overflow checks, a wrong block in release). The block is now computed in 128
    /// bits: the last shard of N ends at the grid's end whatever N is.
    #[test]
    fn fuzz_shard_with_huge_numbers() {
        let big = "8000000000000000026/8000000000000000026";
        assert_eq!(shard_range(big, 10).unwrap(), (9, 10, 8000000000000000026));
        assert_eq!(
            shard_range("18446744073709551615/18446744073709551615", 10_000_000).unwrap(),
            (9_999_999, 10_000_000, usize::MAX)
        );
        assert_eq!(
            shard_range("1/18446744073709551615", 10).unwrap(),
            (0, 0, 1)
        );
        assert_eq!(shard_range("2/8", 100).unwrap(), (12, 25, 2));
    }
}
