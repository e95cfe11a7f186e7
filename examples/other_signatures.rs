//! Versors outside Euclidean space: a screw motion in 3D projective geometric algebra, a
//! Lorentz boost in the spacetime algebra, exponentials where eigenvalue methods break
//! down (equal rotation planes, a light-like generator), a projective line, and conformal
//! maps of points and spheres. The rotorflow book's chapter "Other signatures" includes this
//! file; `cargo test` runs it (tests/book.rs).
//!
//! `cargo run --example other_signatures`

use rotorflow::algebra::pga::{Motor, Plane, Point};
use rotorflow::algebra::{AlgebraError, Multivector, Signature, cga, sta};

/// Largest coefficient of a − b.
fn distance(a: &Multivector, b: &Multivector) -> f64 {
    (a - b).max_abs()
}

pub fn main() -> Result<(), AlgebraError> {
    // 1. A screw in 3D PGA, Cl(3, 0, 1): e₄ is the null vector (the field's e₀). Turning by
    //    θ in the e₁e₂ plane while advancing d along e₃ is exp(−½(θ e₁₂ + d e₃₄)); the two
    //    parts commute, and B² = −θ²/4 + (θd/2) e₁₂₃₄ has a grade-4 part.
    let (theta, d) = (0.8, 1.5);
    let pga = Signature::new(3, 0, 1)?;
    let generator = &Multivector::blade_by_name(pga, "e12", -0.5 * theta)?
        + &Multivector::blade_by_name(pga, "e34", -0.5 * d)?;
    let screw = Motor::new(generator.exp()?)?;
    let moved = screw
        .apply_point(&Point::new(&[1.0, 0.0, 0.0])?)?
        .coordinates()?;
    println!(
        "screw: (1, 0, 0) ↦ ({:.6}, {:.6}, {:.6})",
        moved[0], moved[1], moved[2]
    );
    let expected = [theta.cos(), theta.sin(), d];
    for (x, e) in moved.iter().zip(expected) {
        assert!((x - e).abs() < 1e-15, "{moved:?} vs {expected:?}");
    }
    // The same motion as a 4×4 homogeneous matrix, and back.
    let h = screw.to_matrix();
    println!("homogeneous matrix:\n{h:.6}");
    assert!((h[(0, 0)] - theta.cos()).abs() < 1e-15 && (h[(2, 3)] - d).abs() < 1e-15);
    let back = Motor::from_matrix(&h)?;
    let err = distance(back.as_multivector(), screw.as_multivector())
        .min(distance(&-back.as_multivector(), screw.as_multivector()));
    assert!(err < 1e-15, "matrix round trip off by {err:e}");
    // The logarithm gives the generator back, and the square root is half the screw.
    let log = screw.as_multivector().log()?;
    println!("log of the screw: {log}");
    assert!(distance(&log, &generator) < 1e-15);
    let half = screw.as_multivector().sqrt()?;
    assert!(distance(&(&half * &half), screw.as_multivector()) < 1e-15);

    // 2. A boost in the spacetime algebra Cl(1, 3) (e₁ time, e₂ e₃ e₄ space): rapidity 0.7
    //    along e₂ takes the time axis e₁ to cosh 0.7 e₁ + sinh 0.7 e₂.
    let boost = sta::boost(0.7, &[1.0, 0.0, 0.0])?;
    let time = Multivector::blade_by_name(sta::spacetime(), "e1", 1.0)?;
    let four_velocity = &(&boost * &time) * &boost.reverse();
    println!("boosted time axis: {four_velocity}");
    assert!((four_velocity.coefficient(0b01) - 0.7f64.cosh()).abs() < 1e-15);
    assert!((four_velocity.coefficient(0b10) - 0.7f64.sinh()).abs() < 1e-15);
    assert!(distance(&boost.log()?.exp()?, &boost) < 1e-15);

    // 3. A light-like generator: B = e₁₂ + e₂₃ squares to zero in Cl(1, 3), so exp(B) = 1 + B
    //    exactly (a null rotation), where an eigen-decomposition sees a defective matrix.
    let sta = sta::spacetime();
    let null = &Multivector::blade_by_name(sta, "e12", 1.0)?
        + &Multivector::blade_by_name(sta, "e23", 1.0)?;
    assert_eq!((&null * &null).max_abs(), 0.0);
    let exp_null = null.exp()?;
    assert!(distance(&exp_null, &(&Multivector::scalar(sta, 1.0) + &null)) < 1e-15);
    println!("exp(e12 + e23) in Cl(1, 3) = {exp_null}");

    // 4. Equal rotation planes (an isoclinic rotation of ℝ⁴) and the same generator in the
    //    split signature Cl(2, 2): the closed form never divides by a difference of the
    //    planes' squares, so both come out exactly.
    for sig in [Signature::new(4, 0, 0)?, Signature::new(2, 2, 0)?] {
        let b = &Multivector::blade_by_name(sig, "e12", 0.7)?
            + &Multivector::blade_by_name(sig, "e34", 0.7)?;
        let v = b.exp()?;
        let back = v.log()?;
        let err = distance(&back, &b);
        println!(
            "Cl({}, {}, {}): log(exp(0.7 e12 + 0.7 e34)) off by {err:.1e}",
            sig.p(),
            sig.q(),
            sig.r()
        );
        assert!(err < 1e-15);
    }

    // 5. A line in 3D PGA: the join of two points, its Plücker coordinates, where it meets
    //    a plane, and the quarter turn about it.
    let line = Point::new(&[1.0, 0.0, 0.0])?.join(&Point::new(&[1.0, 0.0, 2.0])?)?;
    println!(
        "line: direction {:?}, moment {:?} (M12, M13, M23)",
        line.direction(),
        line.moment().as_slice()
    );
    assert_eq!(line.direction(), vec![0.0, 0.0, 2.0]);
    let hit = line
        .meet_plane(&Plane::new(&[0.0, 0.0, 1.0], 5.0)?)?
        .coordinates()?;
    assert_eq!(hit, vec![1.0, 0.0, 5.0]);
    let turn = Motor::from_axis_angle(&line, std::f64::consts::FRAC_PI_2)?;
    let turned = turn
        .apply_point(&Point::new(&[2.0, 0.0, 0.0])?)?
        .coordinates()?;
    println!(
        "quarter turn about it: (2, 0, 0) ↦ ({:.6}, {:.6}, {:.6})",
        turned[0], turned[1], turned[2]
    );
    assert!(distance_slices(&turned, &[1.0, 1.0, 0.0]) < 1e-15);

    // 6. Conformal GA Cl(4, 1, 0): points are null vectors up(x), and translations,
    //    rotations, dilations and transversions are versors. Here a dilation by 3 about the
    //    origin, then a translation by (1, 0, 0), of a point and of a sphere through it.
    let v = &cga::translator(&[1.0, 0.0, 0.0])? * &cga::dilator(3, 3.0)?;
    let sandwich = |x: &Multivector| &(&v * x) * &v.reverse();
    let image = cga::down(&sandwich(&cga::up(&[0.0, 1.0, 0.0])?))?;
    println!(
        "conformal: (0, 1, 0) ↦ ({:.6}, {:.6}, {:.6})",
        image[0], image[1], image[2]
    );
    assert!(distance_slices(&image, &[1.0, 3.0, 0.0]) < 1e-14);
    let sphere = sandwich(&cga::sphere(&[0.0, 0.0, 0.0], 1.0)?);
    assert!(cga::point_on(&sphere, &image, 1e-14)?);
    assert!((cga::signed_distance(&sphere, &[1.0, 0.0, 0.0])? + 3.0).abs() < 1e-14);
    assert!(distance(&v.log()?.exp()?, &v) < 1e-15);
    Ok(())
}

/// Largest difference of two coordinate lists.
fn distance_slices(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).fold(0.0, |m, (x, y)| m.max((x - y).abs()))
}
