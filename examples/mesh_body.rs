//! A custom body from a simplicial mesh (book chapter "Extending rotorflow"):
//! `cargo run --release --example mesh_body`.
//!
//! A 4D "house": the box [0, 2] × [0, 1.5] × [0, 1] × [0, 1] cut into 4! = 24 simplices
//! (Kuhn's triangulation), with a pyramid on its top facet x₄ = 1 (a cone over the facet's
//! 3! = 6 tetrahedra). The box alone must reproduce the catalogue's solid cuboid.

use nalgebra::DVector;
use rotorflow::dynamics::torques::Free;
use rotorflow::dynamics::trajectory::even_times;
use rotorflow::dynamics::{RigidBody, Splitting, simulate};
use rotorflow::inertia::SimplexOrientation;
use rotorflow::prelude::*;

/// All permutations of 0..n (Heap's algorithm would do; n ≤ 4 here).
fn permutations(n: usize) -> Vec<Vec<usize>> {
    if n == 0 {
        return vec![vec![]];
    }
    let mut out = Vec::new();
    for p in permutations(n - 1) {
        for at in 0..=p.len() {
            let mut q = p.clone();
            q.insert(at, n - 1);
            out.push(q);
        }
    }
    out
}

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    let edges = [2.0, 1.5, 1.0, 1.0];
    let n = edges.len();
    // Vertices: the 2^N box corners (bit i of the index set ⇔ coordinate i = edge i), then
    // the apex of the pyramid.
    let mut vertices: Vec<DVector<f64>> = (0..1usize << n)
        .map(|mask| DVector::from_fn(n, |i, _| if mask >> i & 1 == 1 { edges[i] } else { 0.0 }))
        .collect();
    let apex = vertices.len();
    vertices.push(DVector::from_vec(vec![1.0, 0.75, 0.5, 1.8]));

    // Kuhn's triangulation of the box: one simplex per order of the N axes.
    let box_simplices: Vec<Vec<usize>> = permutations(n)
        .into_iter()
        .map(|order| {
            let mut mask = 0usize;
            let mut simplex = vec![0];
            for axis in order {
                mask |= 1 << axis;
                simplex.push(mask);
            }
            simplex
        })
        .collect();
    // The pyramid: the top facet x₄ = edge₄ (bit 3 set) triangulated in 3D, coned to the apex.
    let roof: Vec<Vec<usize>> = permutations(n - 1)
        .into_iter()
        .map(|order| {
            let mut mask = 1usize << (n - 1);
            let mut simplex = vec![apex, mask];
            for axis in order {
                mask |= 1 << axis;
                simplex.push(mask);
            }
            simplex
        })
        .collect();

    let unsigned = SimplexOrientation::Unsigned;
    let box_only = Body::simplicial_mesh(&vertices, &box_simplices, 1.0, unsigned)?;
    let half: Vec<f64> = edges.iter().map(|e| e / 2.0).collect();
    let reference = Body::solid_cuboid(&half, 1.0)?;
    let difference = (box_only.mass_tensor() - reference.mass_tensor())
        .abs()
        .max();
    println!(
        "box from {} simplices: mass {:.6}, |J − J_cuboid| = {difference:.1e}",
        box_simplices.len(),
        box_only.mass()
    );
    assert!(difference < 1e-12);

    let all: Vec<Vec<usize>> = box_simplices.into_iter().chain(roof).collect();
    let house = Body::simplicial_mesh(&vertices, &all, 1.0, unsigned)?;
    let list = |v: &DVector<f64>| {
        let parts: Vec<String> = v.iter().map(|x| format!("{x:.5}")).collect();
        format!("({})", parts.join(", "))
    };
    println!(
        "house: mass {:.6}, centre of mass {}",
        house.mass(),
        list(house.center_of_mass())
    );
    println!(
        "principal moments J: {}",
        list(&house.principal_second_moments())
    );

    // The inertia map about the centre of mass; the rigid body moves to the principal frame.
    let inertia = InertiaMap::from_body(&house)?;
    let omega = Bivector::from_components(4, &[0.0, 0.0, 1.0, 0.0, 0.2, 0.0])?;
    let body = RigidBody::from_body_velocity(inertia, Rotor::identity(4), &omega)?;
    let run = simulate(
        &body,
        &mut Splitting::yoshida4(),
        &Free,
        0.01,
        &even_times(10.0, 3),
    )?;
    println!(
        "tumbling for t = 10: energy drift {:.1e}, Casimir drift {:.1e}",
        run.drift().energy,
        run.drift().casimirs
    );
    Ok(())
}
