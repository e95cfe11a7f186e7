//! The `points:FILE.csv` reader: `parse_points_text` on arbitrary UTF-8, then the body it
//! describes (`parse_body_with("points:…")`, plain, with `+mass=2` and with `;mass=2`).
//!
//! Asserts: no panic; accepted rows are non-empty, all of one dimension N ≥ 2, all finite;
//! an accepted body has a finite inertia map and mass.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rotorflow::inertia::spec::{parse_body_with, parse_points_text};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(points) = parse_points_text(text, "fuzz.csv") {
        assert!(!points.masses.is_empty());
        assert_eq!(points.masses.len(), points.positions.len());
        let n = points.positions[0].len();
        assert!(n >= 2);
        assert!(points.positions.iter().all(|p| p.len() == n));
        assert!(points.masses.iter().all(|m| m.is_finite()));
        assert!(
            points
                .positions
                .iter()
                .all(|p| p.iter().all(|x| x.is_finite()))
        );
    }
    for spec in [
        "points:fuzz.csv",
        "points:fuzz.csv+mass=2",
        "points:fuzz.csv;mass=2",
    ] {
        if let Ok(parsed) = parse_body_with(spec, &|_| Ok(text.to_string())) {
            assert!(parsed.mass.is_finite() && parsed.mass > 0.0);
            assert!(parsed.inertia.to_matrix().iter().all(|x| x.is_finite()));
            assert_eq!(parsed.dim, parsed.inertia.dim());
        }
    }
});
