//! Scene files: any bytes read as the TOML scene of `rotorflow scene FILE`, through the
//! library's scene reader (`rotorflow::scene`, the code the command runs).
//!
//! Input: the file's bytes. Bytes that are not UTF-8 are refused before the reader, as
//! `rotorflow scene` does when it reads the file. `points:` and `mesh:` shapes find no file
//! (the reader is given one that always fails), so nothing outside the input is read.
//!
//! Asserts: no panic; every error is bad input (`SceneError::Invalid`, exit code 2 in the
//! command) in one non-empty line; an accepted scene has 2 ≤ N ≤ 64, 0 < dt < t_end (both
//! finite, at most 10⁸ steps), at least one body, every vector of N components and every
//! number finite, masses > 0, springs and joints that name bodies of the scene, and steps
//! within a tenth of each spring's period.
#![no_main]

use libfuzzer_sys::fuzz_target;
use rotorflow::scene::format::parse;
use rotorflow::scene::{MAX_STEP_PER_PERIOD, MAX_STEPS, SceneAnchor, SceneError};

fn finite(x: &[f64]) -> bool {
    x.iter().all(|v| v.is_finite())
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let no_files = |path: &std::path::Path| {
        Err(format!(
            "cannot read `{}`: no files while fuzzing",
            path.display()
        ))
    };
    let scene = match parse(text, "scene.toml", Some(&no_files)) {
        Ok(scene) => scene,
        Err(err) => {
            let message = err.to_string();
            assert!(matches!(err, SceneError::Invalid(_)), "{message}");
            assert!(!message.trim().is_empty());
            assert!(!message.contains(['\n', '\r']), "not one line: {message:?}");
            return;
        }
    };
    let n = scene.dim;
    assert!((2..=rotorflow::algebra::MAX_DIM).contains(&n), "N = {n}");
    assert!(scene.dt > 0.0 && scene.dt < scene.t_end && scene.t_end.is_finite());
    assert!(scene.t_end / scene.dt <= MAX_STEPS);
    assert!(scene.gravity.len() == n && finite(&scene.gravity));
    assert!(!scene.bodies.is_empty());
    for b in &scene.bodies {
        assert_eq!(b.parsed.dim, n);
        assert!(b.mass.is_finite() && b.mass > 0.0, "mass {}", b.mass);
        assert!(b.position.len() == n && finite(&b.position));
        assert!(b.velocity.len() == n && finite(&b.velocity));
        assert!(b.omega.len() == n * (n - 1) / 2 && finite(&b.omega));
        assert_eq!(b.attitude.shape(), (n, n));
    }
    let body = |k: usize| &scene.bodies[k];
    for p in &scene.planes {
        assert!(p.normal.len() == n && finite(&p.normal) && p.normal.iter().any(|x| *x != 0.0));
        assert!(p.friction >= 0.0 && (0.0..=1.0).contains(&p.restitution));
    }
    for s in &scene.springs {
        assert!(s.stiffness >= 0.0 && s.rest_length >= 0.0 && s.damping >= 0.0);
        let m = body(s.body).mass;
        let m_eff = match &s.anchor {
            SceneAnchor::World(x) => {
                assert_eq!(x.len(), n);
                m
            }
            SceneAnchor::Body(j, x) => {
                assert!(*j != s.body && x.len() == n);
                1.0 / (1.0 / m + 1.0 / body(*j).mass)
            }
        };
        // The reduced mass, from its other form; the two agree to rounding (masses whose
        // reciprocals overflow are left out).
        if s.stiffness > 0.0 && m_eff.is_normal() {
            let period = std::f64::consts::TAU * (m_eff / s.stiffness).sqrt();
            assert!(
                scene.dt <= MAX_STEP_PER_PERIOD * period * (1.0 + 1e-12) || !period.is_finite(),
                "dt = {} for a spring of period {period}",
                scene.dt
            );
        }
    }
    for j in &scene.joints {
        assert!(j.body < scene.bodies.len() && j.point.len() == n);
        if let SceneAnchor::Body(k, _) = j.other {
            assert!(k < scene.bodies.len() && k != j.body);
        }
    }
});
