//! The time and grid lists: `--times t1,t2,…` (with and without `--t-end`), `--t-end` with
//! `--samples`, and the sweep's `--param NAME=START:STOP:STEP` and `--shard I/N`.
//!
//! Input: one selector byte, then UTF-8 text.
//!
//! Asserts: no panic; accepted times are finite, ≥ 0, strictly increasing and within
//! `--t-end`; an accepted parameter has 1 … 100000 finite values; an accepted shard is a
//! block inside the grid.
#![no_main]

// The command's number lists: the same source file the binary compiles.
#[path = "../../src/cli/lists.rs"]
mod lists;

use libfuzzer_sys::fuzz_target;
use lists::{parse_param, sample_times, shard_range};
use rotorflow::inertia::spec::parse_number;

fn check_times(times: &[f64], t_end: Option<f64>) {
    assert!(!times.is_empty());
    assert!(
        times.iter().all(|t| t.is_finite() && *t >= 0.0),
        "{times:?}"
    );
    assert!(times.windows(2).all(|w| w[0] < w[1]), "{times:?}");
    if let Some(end) = t_end {
        assert!(*times.last().unwrap() <= end, "{times:?} beyond {end}");
    }
}

fuzz_target!(|data: &[u8]| {
    let Some((&selector, rest)) = data.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    match selector % 5 {
        0 => {
            if let Ok(times) = sample_times(None, None, Some(text)) {
                check_times(&times, None);
            }
        }
        1 => {
            // `T;t1,t2,…`: --t-end T --times t1,t2,…
            let (end, list) = text.split_once(';').unwrap_or(("1", text));
            let Ok(end) = parse_number(end) else { return };
            if let Ok(times) = sample_times(Some(end), None, Some(list)) {
                check_times(&times, Some(end));
            }
        }
        2 => {
            // `T;K`: --t-end T --samples K (K limited here to keep runs fast)
            let (end, k) = text.split_once(';').unwrap_or((text, "2"));
            let (Ok(end), Ok(k)) = (parse_number(end), k.trim().parse::<usize>()) else {
                return;
            };
            if let Ok(times) = sample_times(Some(end), Some(k.min(5000)), None) {
                assert_eq!(times.len(), k.min(5000));
                assert_eq!(times[0], 0.0);
                assert!(times.iter().all(|t| t.is_finite()), "{times:?}");
                assert!(times.windows(2).all(|w| w[0] < w[1]), "{times:?}");
            }
        }
        3 => {
            if let Ok(param) = parse_param(text) {
                assert!((1..=100_000).contains(&param.values.len()));
                assert!(param.values.iter().all(|v| v.is_finite()), "{param:?}");
            }
        }
        _ => {
            let (total, shard) = text.split_once(';').unwrap_or(("10", text));
            let Ok(total) = total.trim().parse::<usize>() else {
                return;
            };
            if let Ok((begin, end, index)) = shard_range(shard, total.min(10_000_000)) {
                assert!(begin <= end && end <= total.min(10_000_000) && index >= 1);
            }
        }
    }
});
