//! A 4D ball that slides into rolling (book chapter "Bodies that move"):
//! `cargo run --release --example rolling_ball`.
//!
//! A solid ball of radius a is launched at v₀ without spin on a rough floor. Friction slows
//! it and spins it up until it rolls, at v₀ (N+2)/(N+4) = 3/4 v₀ in 4D; its placement is then
//! read as a motor of projective GA.

use rotorflow::dynamics::motion::forques::Gravity;
use rotorflow::dynamics::motion::{
    HalfSpace, MotionIntegrator, MotionSplitting, MovingBody, System,
};
use rotorflow::inertia::spec::parse_body;
use rotorflow::prelude::*;

pub fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (n, a, v0) = (4, 0.5, 2.0);
    // 1. The body: a solid 4D ball of mass 1.5. A catalogue body of the SPEC grammar brings
    //    its mass, its inertia and the shape it touches with (here the ball itself).
    let ball = parse_body("ball:4,0.5+mass=1.5")?;
    let up = Vector::from_components(&[0.0, 0.0, 0.0, 1.0])?;
    let body = MovingBody::from_parsed(
        &ball,
        Rotor::identity(n),
        &(&up * a),                                      // resting on the floor x₄ = 0
        &Vector::from_components(&[v0, 0.0, 0.0, 0.0])?, // sliding along e₁
        &Bivector::zero(n),                              // without spin
    )?;

    // 2. The system: gravity along −e₄ and the floor x₄ ≤ 0 with friction 0.3, no bounce.
    let mut system = System::new(vec![body])?;
    system.add_forque(Gravity(&up * -9.81))?;
    system.add_half_space(HalfSpace::new(&up, 0.0, 0.3, 0.0)?)?;

    // 3. Integrate for 1.5 s with the symplectic splitting, the one integrator that does
    //    contact and joints.
    let mut stepper = MotionSplitting::new();
    let h = 1e-3;
    for k in 0..1500 {
        stepper.step(&mut system, k as f64 * h, h)?;
    }

    // 4. It rolls: v = v₀ (N+2)/(N+4), and the contact point is at rest.
    let b = &system.bodies()[0];
    let v = b.velocity()[0];
    let want = v0 * (n as f64 + 2.0) / (n as f64 + 4.0);
    let bottom = b.attitude().inverse_rotate_vector(&(&up * -a)); // in the ball's own axes
    let slip = b.point_velocity(&bottom).norm();
    println!("v = {v:.12} (predicted {want:.12}), contact point speed {slip:.1e}");
    assert!((v - want).abs() <= 1e-9 * want && slip <= 1e-9 * v0);

    // 5. The placement as a motor of projective GA, and as a homogeneous matrix: both move
    //    a body point to where `point_position` puts it.
    let motor = b.motor()?;
    let h_matrix = b.homogeneous_matrix();
    let top = b.attitude().inverse_rotate_vector(&(&up * a));
    let moved = motor.apply_point(&rotorflow::algebra::pga::Point::new(top.as_slice())?)?;
    let by_matrix = &h_matrix
        * nalgebra::DVector::from_iterator(5, top.as_slice().iter().copied().chain([1.0]));
    println!(
        "top of the ball at {:.6?} (motor), {:.6?} (matrix)",
        moved.coordinates()?,
        &by_matrix.as_slice()[..n]
    );
    let exact = b.point_position(&top);
    for (i, x) in moved.coordinates()?.iter().enumerate() {
        assert!((x - exact[i]).abs() <= 1e-12 && (by_matrix[i] - exact[i]).abs() <= 1e-12);
    }
    Ok(())
}
