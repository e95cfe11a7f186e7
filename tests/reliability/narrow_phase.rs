//! The narrow phase on 10⁶ random polytope pairs (boxes, random hulls, simplices and
//! cross-polytopes, N = 2 … 6): GJK's distance against Wolfe's minimum-norm point with its
//! optimality certificate (`tests/dynamics/narrow_reference.rs`). Reports wrong answers
//! beyond 1e-9 of (distance + size), non-finite answers, panics and the largest iteration
//! count; all three counts must be 0. Pairs whose reference answer fails its own optimality
//! certificate are not checked; they are counted and must stay below 10⁻⁴ of the pairs. The
//! normal suite runs 10⁴ of these pairs (`tests/dynamics/narrow_phase.rs`).

#[path = "../dynamics/narrow_reference.rs"]
mod reference;

use reference::polytope_distance_run;
use std::panic::{AssertUnwindSafe, catch_unwind};

/// Runs `chunks` chunks of `per_chunk` pairs per dimension on two threads; returns
/// (pairs, overlapping, wrong, non-finite, panics, largest iterations, unchecked).
fn run(chunks: u64, per_chunk: usize) -> [usize; 7] {
    let totals = std::sync::Mutex::new([0usize; 7]);
    std::thread::scope(|scope| {
        for thread in 0..2u64 {
            let totals = &totals;
            scope.spawn(move || {
                for chunk in (thread..chunks).step_by(2) {
                    for n in 2..=6 {
                        let seed = 1_000_000 + chunk * 10 + n as u64;
                        let outcome = catch_unwind(AssertUnwindSafe(|| {
                            polytope_distance_run(seed, n, per_chunk)
                        }));
                        let mut t = totals.lock().unwrap();
                        match outcome {
                            Ok(
                                [
                                    overlapping,
                                    separated,
                                    wrong,
                                    nonfinite,
                                    iterations,
                                    unchecked,
                                ],
                            ) => {
                                t[0] += overlapping + separated + nonfinite + unchecked;
                                t[6] += unchecked;
                                t[1] += overlapping;
                                t[2] += wrong;
                                t[3] += nonfinite;
                                t[5] = t[5].max(iterations);
                            }
                            Err(_) => {
                                t[0] += per_chunk;
                                t[4] += 1;
                            }
                        }
                    }
                }
            });
        }
    });
    totals.into_inner().unwrap()
}

fn report(counts: [usize; 7]) {
    let [
        pairs,
        overlapping,
        wrong,
        nonfinite,
        panics,
        iterations,
        unchecked,
    ] = counts;
    println!(
        "narrow phase: {pairs} random pairs ({overlapping} overlapping), {wrong} wrong beyond \
         1e-9, {nonfinite} non-finite, {panics} chunks panicked, at most {iterations} GJK \
         iterations, {unchecked} pairs the reference could not certify (not checked)"
    );
    assert_eq!((wrong, nonfinite, panics), (0, 0, 0));
    assert!(
        unchecked * 10_000 <= pairs,
        "{unchecked} of {pairs} pairs unchecked"
    );
}

#[test]
#[ignore = "10⁶ pairs: about a minute in release; CI runs it"]
fn a_million_random_polytope_pairs() {
    // 200 chunks × 5 dimensions × 1000 pairs.
    let counts = run(200, 1000);
    assert_eq!(counts[0], 1_000_000);
    report(counts);
}
