//! A short tour of rotorflow's algebra layer: `cargo run --release --example tour`.
//!
//! It prints each step with the numbers it checks, so the output doubles as a smoke test.

use rotorflow::prelude::*;
use std::f64::consts::PI;

fn main() -> Result<(), AlgebraError> {
    println!("rotorflow tour: geometric algebra for rotations in any dimension\n");

    // 1. Bivectors are planes. In 3D, e12 is the plane that turns e1 toward e2.
    let w = Bivector::from_components(3, &[0.0, 0.0, 1.0])?; // ω = e23
    let x = Vector::from_components(&[0.0, 1.0, 0.0])?;
    println!("1. angular velocity ω = {w}");
    println!(
        "   velocity of the body point x = {x}: x ⌋ ω = {}",
        x.left_contract(&w)
    );

    // 2. The commutator product is the bracket of Euler's equations, dL/dt = ω × L.
    let l = Bivector::from_components(3, &[1.0, 0.0, 0.0])?;
    println!("2. ω × L for L = {l}: {}", w.commutator(&l));

    // 3. Rotors turn vectors by the sandwich R x R̃.
    let r = Rotor::from_plane_angle(3, 0, 1, PI / 2.0)?;
    println!(
        "3. R = {r:.6} turns e1 into {:.6}",
        r.rotate_vector(&Vector::basis(3, 0))
    );

    // 4. In 4D a rotation can turn two planes at once, at different rates.
    let theta = Bivector::from_components(4, &[0.5, 0.0, 0.0, 0.0, 0.0, 1.5])?;
    let r4 = Rotor::from_rotation_bivector(&theta);
    println!("4. double rotation Θ = {theta}\n   R = exp(−Θ/2) = {r4:.6}");
    println!("   |R R̃ − 1| = {:.1e}", r4.unit_error());
    let expm = theta.to_skew_matrix().transpose().exp();
    println!(
        "   max |matrix(R) − expm([Θ]ᵀ)| = {:.1e} (nalgebra's matrix exponential)",
        (r4.to_matrix() - expm).abs().max()
    );

    // 5. The invariant decomposition splits any bivector into orthogonal planes; it is exact
    //    for isoclinic input, where closed-form formulas divide by zero.
    let iso = Bivector::from_components(4, &[0.7, 0.0, 0.0, 0.0, 0.0, 0.7])?;
    let d = iso.decompose();
    println!(
        "5. isoclinic {iso}: planes with magnitudes {:?}",
        d.magnitudes()
    );
    for p in d.planes() {
        println!("   {:.3} · ({:.3}) ∧ ({:.3})", p.magnitude(), p.u(), p.v());
    }

    // 6. The logarithm recovers the rotation, also near π and in many planes at once.
    let n = 7;
    let mut big = Bivector::zero(n);
    big.set(0, 1, PI - 1e-9);
    big.set(2, 3, 2.0);
    big.set(4, 5, 0.3);
    let r7 = Rotor::from_rotation_bivector(&big);
    let back = r7.rotation_bivector();
    println!(
        "6. 7D rotation by (π − 1e-9, 2, 0.3): log∘exp error = {:.1e}",
        (&back - &big).max_abs()
    );

    // 7. Rotation matrices convert to rotors in any dimension.
    let q = r7.to_matrix();
    let r7b = Rotor::from_matrix(&q)?;
    println!(
        "7. matrix → rotor → matrix in 7D: error {:.1e}",
        (r7b.to_matrix() - q).abs().max()
    );

    // 8. Drifted rotors are projected back onto Spin(N) (dividing by the norm is not enough).
    let mut m = r4.to_multivector();
    m.as_mut_slice()[0b1111] += 1e-6;
    let drifted = Rotor::from_multivector_unchecked(&m);
    println!(
        "8. drift |R R̃ − 1| = {:.1e} → after normalize(): {:.1e}",
        drifted.unit_error(),
        drifted.normalize().unit_error()
    );

    // 9. Invariants of a bivector: characteristic polynomial and Pfaffian.
    let b = Bivector::from_components(4, &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0])?;
    println!(
        "9. B = {b}: det(λ − [B]) coefficients {:?}, Pf = {}",
        b.characteristic_coefficients(),
        b.pfaffian()
    );
    Ok(())
}
