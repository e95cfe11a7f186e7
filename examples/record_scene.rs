//! A system of moving bodies built in code, recorded, and written as the command writes a
//! scene: JSON, one CSV per body, the HTML animation (contacts marked) and the SVG plots.
//!
//! `cargo run --example record_scene --features viz,serde -- OUT_DIR` (the default features
//! include both); without OUT_DIR the files go to `target/record_scene`.

use rotorflow::dynamics::motion::forques::{Anchor, Gravity, Spring};
use rotorflow::dynamics::motion::{HalfSpace, MotionSplitting, MovingBody, System};
use rotorflow::inertia::spec::parse_body;
use rotorflow::prelude::*;
use rotorflow::viz::scene::SceneLink;
use rotorflow::viz::trajectory::{Drawing, animation_html, plot_svg};
use std::error::Error;
use std::path::Path;

fn main() -> Result<(), Box<dyn Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "target/record_scene".into());
    println!("{}", record(Path::new(&out))?);
    Ok(())
}

/// Builds the system, records it, writes the files into `out` (created if needed) and says
/// what it wrote.
pub fn record(out: &Path) -> Result<String, Box<dyn Error>> {
    std::fs::create_dir_all(out)?;

    // A 4D ball rolling on the floor x₄ = 0 and a tesseract hanging from a spring above it.
    let v = |x: &[f64]| Vector::from_components(x);
    let ball = MovingBody::from_parsed(
        &parse_body("ball:4,0.5+mass=1")?,
        Rotor::identity(4),
        &v(&[0.0, 0.0, 0.0, 0.5])?,
        &v(&[1.5, 0.5, 0.0, 0.0])?,
        &Bivector::zero(4),
    )?;
    let cube = MovingBody::from_parsed(
        &parse_body("cuboid:0.3,0.3,0.3,0.3+mass=2")?,
        Rotor::identity(4),
        &v(&[0.0, 0.0, 0.0, 2.5])?,
        &Vector::zero(4),
        &Bivector::from_components(4, &[0.0, 0.0, 0.0, 1.0, 0.0, 0.5])?,
    )?;
    let mut system = System::new(vec![ball, cube])?;
    let down = v(&[0.0, 0.0, 0.0, -9.81])?;
    system.add_forque(Gravity(down))?;
    system.add_forque(Spring {
        body: 1,
        point: v(&[0.0, 0.0, 0.0, 0.3])?,
        anchor: Anchor::World(v(&[0.0, 0.0, 0.0, 4.0])?),
        stiffness: 60.0,
        rest_length: 0.5,
        damping: 0.0,
    })?;
    system.add_half_space(HalfSpace::new(&v(&[0.0, 0.0, 0.0, 1.0])?, 0.0, 0.4, 0.0)?)?;

    // 121 samples over 3 time units, steps of 0.005; every sample time is hit exactly.
    let times: Vec<f64> = (0..=120).map(|k| 0.025 * k as f64).collect();
    let mut run = system.record(&mut MotionSplitting::new(), 0.005, &times)?;
    run.bodies[0].name = "ball".into();
    run.bodies[1].name = "tesseract".into();

    let touching = run.contacts.iter().filter(|c| !c.is_empty()).count();
    let e0 = run.energy[0];
    let drift = run
        .energy
        .iter()
        .map(|e| (e - e0).abs())
        .fold(0.0, f64::max);
    // A ball launched without spin ends rolling at v₀ (N+2)/(N+4) (the moving-bodies
    // chapter), whatever the friction.
    let speed = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let ball = &run.bodies[0].velocity;
    let (v0, v_end) = (speed(&ball[0]), speed(&ball[ball.len() - 1]));
    let rolling = v0 * 6.0 / 8.0;
    if (v_end - rolling).abs() > 1e-6 * rolling {
        return Err(format!("the ball ends at {v_end}, not rolling at {rolling}").into());
    }
    let summary = format!(
        "{} samples, {} steps; the ball touches the floor at {touching} samples; \
         largest energy change {drift:.3e} (friction takes what rolling does not keep); \
         the ball's final speed {v_end:.6}, rolling predicts v₀ (N+2)/(N+4) = {:.6}",
        run.times.len(),
        run.steps,
        rolling
    );

    std::fs::write(out.join("run.json"), run.to_json()?)?;
    for (name, text) in run.csv_files()? {
        std::fs::write(out.join(name), text)?;
    }
    // The drawing takes the bodies' shapes and joints from the system; springs are forces,
    // so the spring is added as a link, and the axis of gravity is drawn upwards.
    let mut drawing = Drawing::of_system(&system, "a 4D ball and a tesseract on a spring");
    drawing.links.push(SceneLink {
        spring: true,
        body: 1,
        point: vec![0.0, 0.0, 0.0, 0.3],
        other: None,
        end: vec![0.0, 0.0, 0.0, 4.0],
    });
    drawing.up = Some(3);
    std::fs::write(out.join("run.html"), animation_html(&run, &drawing))?;
    std::fs::write(
        out.join("run.svg"),
        plot_svg(&run, "a 4D ball and a tesseract")?,
    )?;
    Ok(format!(
        "{summary}\nwrote run.json, ball.csv, tesseract.csv, system.csv, run.html and run.svg to {}",
        out.display()
    ))
}
