//! The `mesh:FILE` reader: `parse_mesh_text` on arbitrary UTF-8, then the body it describes
//! (`parse_body_with("mesh:…")`, plain, with `+density=2` and with `;density=2`).
//!
//! Asserts: no panic; accepted records have vertices of one dimension, finite coordinates
//! and at least one cell; an accepted body has a finite inertia map and a positive mass.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rotorflow::inertia::spec::{parse_body_with, parse_mesh_text};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(mesh) = parse_mesh_text(text, "fuzz.mesh") {
        assert!(!mesh.vertices.is_empty() && !mesh.cells.is_empty());
        let n = mesh.vertices[0].len();
        assert!(mesh.vertices.iter().all(|v| v.len() == n));
        assert!(
            mesh.vertices
                .iter()
                .all(|v| v.iter().all(|x| x.is_finite()))
        );
    }
    for spec in [
        "mesh:fuzz.mesh",
        "mesh:fuzz.mesh+density=2",
        "mesh:fuzz.mesh;density=2",
    ] {
        if let Ok(parsed) = parse_body_with(spec, &|_| Ok(text.to_string())) {
            assert!(parsed.mass.is_finite() && parsed.mass > 0.0);
            assert!(parsed.inertia.to_matrix().iter().all(|x| x.is_finite()));
            assert_eq!(parsed.dim, parsed.inertia.dim());
        }
    }
});
