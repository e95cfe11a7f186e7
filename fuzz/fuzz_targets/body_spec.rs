//! The body SPEC grammar end to end: `parse_body_with` on arbitrary UTF-8, then a rigid body
//! with the initial angular velocity, as `rotorflow simulate --body SPEC --omega W` builds it.
//!
//! Input: `SPEC\nOMEGA\nFILE TEXT…` (missing lines are empty); `points:` and `mesh:` read the
//! file text from the input instead of the file system.
//!
//! Asserts: no panic; an accepted body has 2 ≤ N ≤ 16, a positive finite mass and a finite
//! inertia map; an accepted initial condition has finite ω and L.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rotorflow::algebra::Bivector;
use rotorflow::algebra::MULTIVECTOR_MAX_DIM;
use rotorflow::dynamics::{Attitude, RigidBody};
use rotorflow::inertia::spec::{parse_body_with, parse_list};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let mut lines = text.splitn(3, '\n');
    let spec = lines.next().unwrap_or("");
    let omega = lines.next().unwrap_or("").to_string();
    let file = lines.next().unwrap_or("").to_string();
    let Ok(parsed) = parse_body_with(spec, &|_| Ok(file.clone())) else {
        return;
    };
    assert!(
        (2..=MULTIVECTOR_MAX_DIM).contains(&parsed.dim),
        "N = {}",
        parsed.dim
    );
    assert!(
        parsed.mass.is_finite() && parsed.mass > 0.0,
        "mass {}",
        parsed.mass
    );
    let matrix = parsed.inertia.to_matrix();
    assert!(matrix.iter().all(|x| x.is_finite()), "inertia {matrix}");
    let Ok(values) = parse_list(&omega) else {
        return;
    };
    let Ok(w) = Bivector::from_components(parsed.dim, &values) else {
        return;
    };
    let start =
        RigidBody::from_body_velocity(parsed.inertia.clone(), Attitude::identity(parsed.dim), &w);
    if let Ok(body) = start {
        assert!(body.omega().as_slice().iter().all(|x| x.is_finite()));
        assert!(body.momentum().as_slice().iter().all(|x| x.is_finite()));
    }
});
