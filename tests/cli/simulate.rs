//! `rotorflow simulate`: JSON shape, agreement with the library, integrators, CSV, files.

use super::{assert_close, assert_matrix_close, floats, matrix, rotorflow, run_json};
use nalgebra::DMatrix;
use rotorflow::algebra::{Bivector, Rotor};
use rotorflow::dynamics::{RigidBody, Rkmk4, simulate, torques::Free};
use rotorflow::inertia::InertiaMap;

const KEYS: [&str; 8] = [
    "dim", "times", "omega", "momentum", "energy", "casimirs", "attitude", "drift",
];

#[test]
fn simulate_json_has_every_key_and_shape() {
    let v = run_json(&[
        "simulate",
        "--body",
        "tesseract:1,1.2,1.5,2",
        "--omega",
        "1,0.05,0.02,0.03,0.04,0.7",
        "--t-end",
        "5",
        "--samples",
        "11",
        "--json",
    ]);
    for k in KEYS {
        assert!(v.get(k).is_some(), "key {k} missing");
    }
    assert_eq!(v["dim"].as_u64(), Some(4));
    let times = floats(&v["times"]);
    assert_eq!(times.len(), 11);
    assert_eq!(times[0], 0.0);
    assert_eq!(times[10], 5.0);
    for key in ["omega", "momentum"] {
        let rows = matrix(&v[key]);
        assert_eq!(rows.len(), 11);
        assert!(rows.iter().all(|r| r.len() == 6));
    }
    assert_close(
        &matrix(&v["omega"])[0],
        &[1.0, 0.05, 0.02, 0.03, 0.04, 0.7],
        1e-14,
    );
    assert_eq!(floats(&v["energy"]).len(), 11);
    let casimirs = v["casimirs"].as_array().unwrap();
    assert!(casimirs.iter().all(|c| floats(c).len() == 2));
    // Each attitude is a rotation matrix, the identity at t = 0.
    for (k, q) in v["attitude"].as_array().unwrap().iter().enumerate() {
        let rows = matrix(q);
        let m = DMatrix::from_fn(4, 4, |r, c| rows[r][c]);
        let err = (m.transpose() * &m - DMatrix::identity(4, 4)).abs().max();
        assert!(err < 1e-10, "attitude {k} not orthogonal: {err}");
        if k == 0 {
            assert!((m - DMatrix::identity(4, 4)).abs().max() < 1e-15);
        }
    }
    let drift = &v["drift"];
    assert!(drift["energy"].as_f64().unwrap() < 1e-8);
    assert!(drift["casimirs"].as_f64().unwrap() < 1e-8);
}

#[test]
fn simulate_matches_library_in_the_bodys_own_axes() {
    // A mass tensor that is not diagonal: the CLI must report ω and L in the given axes.
    let j = DMatrix::from_row_slice(3, 3, &[2.0, 0.5, 0.1, 0.5, 3.0, 0.2, 0.1, 0.2, 4.0]);
    let map = InertiaMap::from_mass_tensor(&j).unwrap();
    let w0 = Bivector::from_components(3, &[0.3, -1.0, 0.2]).unwrap();
    let start = RigidBody::from_body_velocity(map.clone(), Rotor::identity(3), &w0).unwrap();
    let times: Vec<f64> = (0..=10).map(|k| k as f64).collect();
    let traj = simulate(&start, &mut Rkmk4, &Free, 0.01, &times).unwrap();
    let v = run_json(&[
        "simulate",
        "--body",
        "tensor:2,0.5,0.1,0.5,3,0.2,0.1,0.2,4",
        "--omega=0.3,-1,0.2",
        "--times",
        "0,1,2,3,4,5,6,7,8,9,10",
        "--integrator",
        "rk4",
        "--dt",
        "0.01",
        "--json",
    ]);
    let omega = matrix(&v["omega"]);
    let momentum = matrix(&v["momentum"]);
    let rp = start.principal_frame();
    for (k, s) in traj.samples().iter().enumerate() {
        let w_own = rp.rotate_bivector(&s.omega);
        let l_own = rp.rotate_bivector(&s.momentum);
        assert_close(&omega[k], w_own.as_slice(), 1e-9);
        assert_close(&momentum[k], l_own.as_slice(), 1e-9);
        // L = I(ω) in the body's own axes.
        assert_close(
            &momentum[k],
            map.apply(&Bivector::from_components(3, &omega[k]).unwrap())
                .as_slice(),
            1e-9,
        );
        let q = s.attitude.compose(&rp.inverse()).to_matrix();
        assert_matrix_close(&matrix(&v["attitude"][k]), &q, 1e-9);
    }
    assert_close(&omega[0], &[0.3, -1.0, 0.2], 1e-13);
}

#[test]
fn simulate_momentum_and_omega_give_the_same_motion() {
    let w = run_json(&[
        "simulate",
        "--body",
        "cuboid:1,2,3",
        "--omega",
        "0.1,1,0.2",
        "--t-end",
        "3",
        "--samples",
        "4",
        "--json",
    ]);
    let l0 = matrix(&w["momentum"])[0]
        .iter()
        .map(|x| x.to_string())
        .collect::<Vec<_>>()
        .join(",");
    let l = run_json(&[
        "simulate",
        "--body",
        "cuboid:1,2,3",
        "--momentum",
        &l0,
        "--t-end",
        "3",
        "--samples",
        "4",
        "--json",
    ]);
    for k in 0..4 {
        assert_close(&matrix(&l["omega"])[k], &matrix(&w["omega"])[k], 1e-12);
    }
}

#[test]
fn simulate_every_integrator_conserves_the_invariants() {
    for (integrator, extra) in [
        ("rk4", vec!["--dt", "0.005"]),
        ("lie-poisson-rk4", vec!["--dt", "0.005"]),
        ("lp-rk4", vec!["--dt", "0.005"]),
        ("dopri5", vec!["--rtol", "1e-10", "--atol", "1e-12"]),
        ("dop853", vec!["--rtol", "1e-10", "--atol", "1e-12"]),
        ("strang", vec!["--dt", "0.002"]),
        ("yoshida4", vec!["--dt", "0.005"]),
        ("suzuki4", vec!["--dt", "0.005"]),
        ("kahan-li6", vec!["--dt", "0.01"]),
        ("kahan-li8", vec!["--dt", "0.02"]),
        ("midpoint", vec!["--dt", "0.002"]),
        ("moser-veselov", vec!["--dt", "0.01"]),
        ("mv", vec!["--dt", "0.01"]),
    ] {
        let mut args = vec![
            "simulate",
            "--body",
            "pentachoron:1,1.2,1.5,2",
            "--omega",
            "0.8,0.1,0.05,0.3,0.02,0.6",
            "--t-end",
            "10",
            "--samples",
            "21",
            "--json",
            "--integrator",
            integrator,
        ];
        args.extend(extra);
        let v = run_json(&args);
        let e = v["drift"]["energy"].as_f64().unwrap();
        let c = v["drift"]["casimirs"].as_f64().unwrap();
        // Bounds from each method (measured in parentheses): 3× the measured truncation error,
        // or steps·ε where only round-off moves the invariant.
        let round_off = |h: f64| 10.0 / h * f64::EPSILON;
        let (energy_bound, casimir_bound) = match integrator {
            // h = 0.005: the O(h⁴) truncation (9.5e-15) is below round-off.
            "rk4" => (round_off(0.005), round_off(0.005)),
            // As RK4 for the energy; L is only rotated, exactly.
            "lie-poisson-rk4" | "lp-rk4" => (round_off(0.005), round_off(0.005)),
            // The global error follows the tolerance (2.0e-11, 2.1e-11 = 0.2·rtol).
            "dopri5" => (6.3e-11, 6.3e-11),
            // Below the tolerance at the same rtol (3.8e-13, 4.1e-13).
            "dop853" => (1.2e-12, 1.2e-12),
            // A modified energy, O(h²) (4.4e-8 = 0.011·h²); L is only rotated, exactly.
            "strang" => (1.3e-7, round_off(0.002)),
            // O(h⁴) (2.1e-12 = 0.0033·h⁴); L is only rotated, exactly.
            "yoshida4" => (6.2e-12, round_off(0.005)),
            // The truncation is below round-off at these steps (energy 3.7e-14, 2.1e-14,
            // 2.4e-14); L is only rotated, exactly.
            "suzuki4" => (round_off(0.005), round_off(0.005)),
            "kahan-li6" => (round_off(0.01), round_off(0.01)),
            "kahan-li8" => (round_off(0.02), round_off(0.02)),
            // Every Manakov integral, hence energy and Casimirs, only moved by round-off.
            "moser-veselov" | "mv" => (round_off(0.01), round_off(0.01)),
            // Quadratic invariants are kept exactly by the midpoint rule (1.3e-14, 1.2e-14).
            _ => (round_off(0.002), round_off(0.002)),
        };
        assert!(
            e < energy_bound && c < casimir_bound,
            "{integrator}: drifts {e:e} {c:e} (bounds {energy_bound:e} {casimir_bound:e})"
        );
    }
}

#[test]
fn simulate_csv_has_a_header_and_a_row_per_time() {
    let out = rotorflow()
        .args([
            "simulate",
            "--body",
            "ellipsoid:1,2,3",
            "--omega",
            "0.01,1,0.01",
            "--t-end",
            "2",
            "--samples",
            "5",
            "--csv",
        ])
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 6);
    assert!(lines[0].starts_with("t,omega_12,omega_13,omega_23,momentum_12"));
    assert!(lines[0].contains("energy,casimir_1,R_1_1"));
    let width = lines[0].split(',').count();
    assert!(lines[1..].iter().all(|l| l.split(',').count() == width));
}

#[test]
fn simulate_writes_output_and_plot_files() {
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("run.json");
    let svg = dir.path().join("omega.svg");
    rotorflow()
        .args([
            "simulate",
            "--body",
            "tesseract:1,1.2,1.5,2",
            "--omega",
            "1,0,0,0,0,0.5",
            "--t-end",
            "4",
            "--samples",
            "41",
            "--json",
            "--output",
        ])
        .arg(&json)
        .arg("--plot")
        .arg(&svg)
        .assert()
        .success()
        .stdout("");
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    assert_eq!(floats(&v["times"]).len(), 41);
    let plot = std::fs::read_to_string(&svg).unwrap();
    assert!(plot.starts_with("<svg"));
    for label in ["ω₁₂", "ω₃₄", "time t"] {
        assert!(plot.contains(label), "plot lacks {label}");
    }
    // No temporary files are left behind.
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names.len(), 2, "{names:?}");
}

#[test]
fn simulate_damping_torque_drains_energy() {
    let v = run_json(&[
        "simulate",
        "--body",
        "cuboid:1,2,3",
        "--omega",
        "0.5,1,0.2",
        "--torque",
        "damping:0.5",
        "--t-end",
        "5",
        "--samples",
        "6",
        "--json",
    ]);
    let e = floats(&v["energy"]);
    assert!(
        e.windows(2).all(|w| w[1] < w[0]),
        "energy not decreasing: {e:?}"
    );
}

#[test]
fn simulate_constant_body_torque_spins_up() {
    // τ = e12 on a body at rest, with I₁₂ = J₁ + J₂: ω₁₂ = t/I₁₂.
    let v = run_json(&[
        "simulate",
        "--body",
        "principal:1,2,3",
        "--omega",
        "0,0,0",
        "--torque",
        "body:1,0,0",
        "--t-end",
        "2",
        "--samples",
        "3",
        "--json",
    ]);
    let omega = matrix(&v["omega"]);
    assert_close(&omega[2], &[2.0 / 3.0, 0.0, 0.0], 1e-10);
}

#[test]
fn simulate_accepts_non_physical_plane_moments() {
    // The common 3D test body I = (2, 1, 2/3), which no mass distribution has.
    let v = run_json(&[
        "simulate",
        "--body",
        "planes:0.6666666666666666,1,2",
        "--omega",
        "0.3,0.2,1",
        "--t-end",
        "10",
        "--samples",
        "11",
        "--integrator",
        "yoshida4",
        "--dt",
        "0.01",
        "--json",
    ]);
    assert!(v["drift"]["casimirs"].as_f64().unwrap() < 1e-12);
    assert!(v["drift"]["energy"].as_f64().unwrap() < 1e-6);
}
