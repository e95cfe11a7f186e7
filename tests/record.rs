//! Recorded runs of moving bodies (`System::record`, `SystemTrajectory`): the sample times
//! hit exactly and the step count of the rule, the refused samplings, the contacts of a
//! resting ball against its weight, and the JSON and CSV read back bit for bit.

use rotorflow::dynamics::DynamicsError;
use rotorflow::dynamics::motion::forques::Gravity;
use rotorflow::dynamics::motion::{
    HalfSpace, MotionRk4, MotionSplitting, MovingBody, System, SystemTrajectory,
};
use rotorflow::inertia::spec::parse_body;
use rotorflow::prelude::*;

const G: f64 = 9.81;

fn vector(x: &[f64]) -> Vector {
    Vector::from_components(x).unwrap()
}

/// A 3D box thrown upward under gravity, turning.
fn thrown_box() -> System {
    let cube = parse_body("cuboid:0.5,0.3,0.2+mass=2").unwrap();
    let body = MovingBody::from_parsed(
        &cube,
        Rotor::identity(3),
        &vector(&[1.0, -2.0, 3.0]),
        &vector(&[0.5, 0.25, 4.0]),
        &Bivector::from_components(3, &[0.3, -1.0, 2.0]).unwrap(),
    )
    .unwrap();
    let mut system = System::new(vec![body]).unwrap();
    system.add_forque(Gravity(vector(&[0.0, 0.0, -G]))).unwrap();
    system
}

/// A ball of radius 0.5 and mass 3 resting on the floor z = 0 under gravity.
fn resting_ball() -> System {
    let ball = parse_body("ball:3,0.5+mass=3").unwrap();
    let body = MovingBody::from_parsed(
        &ball,
        Rotor::identity(3),
        &vector(&[0.2, -0.1, 0.5]),
        &Vector::zero(3),
        &Bivector::zero(3),
    )
    .unwrap();
    let mut system = System::new(vec![body]).unwrap();
    system.add_forque(Gravity(vector(&[0.0, 0.0, -G]))).unwrap();
    system
        .add_half_space(HalfSpace::new(&vector(&[0.0, 0.0, 1.0]), 0.0, 0.5, 0.0).unwrap())
        .unwrap();
    system
}

#[test]
fn samples_land_on_the_times_and_follow_the_parabola() {
    let mut system = thrown_box();
    let times = [0.0, 0.25, 0.3, 1.0];
    let run = system
        .record_with(&mut MotionRk4::new(), 0.1, &times, 1.2, &mut |_| {})
        .unwrap();
    assert_eq!(run.times, times);
    assert_eq!(run.dim, 3);
    assert_eq!(run.bodies[0].name, "body1");
    assert_eq!(run.bodies[0].mass, 2.0);
    // The rule: 0.1, 0.2, then 0.05 to 0.25; 0.05 to 0.3; 0.4 … 0.9 (seven steps of 0.1)
    // and 0.1 to 1.0; 1.1 and 1.2 to t_end.
    assert_eq!(run.steps, 3 + 1 + 7 + 2);
    let (x0, v0) = ([1.0, -2.0, 3.0], [0.5, 0.25, 4.0]);
    for (k, t) in times.iter().enumerate() {
        for i in 0..3 {
            let g = if i == 2 { -G } else { 0.0 };
            let x = x0[i] + v0[i] * t + 0.5 * g * t * t;
            let v = v0[i] + g * t;
            assert!((run.bodies[0].position[k][i] - x).abs() < 1e-12, "t = {t}");
            assert!((run.bodies[0].velocity[k][i] - v).abs() < 1e-12, "t = {t}");
        }
        // The attitude is a rotation, as rows.
        let q = run.bodies[0].attitude_matrix(k);
        assert!((q.transpose() * &q - nalgebra::DMatrix::identity(3, 3)).norm() < 1e-12);
        // Free flight under gravity: E and the momenta as the closed form says.
        assert!((run.momentum[k][2] - 2.0 * (v0[2] - G * t)).abs() < 1e-12);
        assert!((run.energy[k] - run.energy[0]).abs() < 1e-6 * run.energy[0].abs());
        assert!(run.contacts[k].is_empty());
    }
    // The system is at t_end after the run, past the last sample.
    let z_end = x0[2] + v0[2] * 1.2 - 0.5 * G * 1.44;
    assert!((system.bodies()[0].position().as_slice()[2] - z_end).abs() < 1e-12);
}

#[test]
fn record_ends_at_the_last_sample_and_reports_each_one() {
    let mut system = thrown_box();
    let mut seen = Vec::new();
    let run = system
        .record_with(
            &mut MotionSplitting::new(),
            0.1,
            &[0.0, 0.5],
            0.5,
            &mut |k| seen.push(k),
        )
        .unwrap();
    assert_eq!(seen, [1, 2]);
    assert_eq!(run.steps, 5);
    let again = thrown_box()
        .record(&mut MotionSplitting::new(), 0.1, &[0.0, 0.5])
        .unwrap();
    assert_eq!(again, run);
}

#[test]
fn bad_samplings_are_refused() {
    let cases: [(f64, &[f64], f64); 9] = [
        (0.0, &[0.0, 1.0], 1.0),
        (-0.1, &[0.0, 1.0], 1.0),
        (f64::NAN, &[0.0, 1.0], 1.0),
        (f64::INFINITY, &[0.0, 1.0], 1.0),
        (0.1, &[], 1.0),
        (0.1, &[0.0, 0.5, 0.5], 1.0),
        (0.1, &[-0.5, 0.5], 1.0),
        (0.1, &[0.0, f64::NAN], 1.0),
        (0.1, &[0.0, 2.0], 1.0),
    ];
    let mut refused = 0;
    for (dt, times, t_end) in cases {
        let mut system = thrown_box();
        let before = system.bodies()[0].position().clone();
        let result = system.record_with(&mut MotionSplitting::new(), dt, times, t_end, &mut |_| {});
        assert!(
            matches!(result, Err(DynamicsError::InvalidSampling { .. })),
            "dt = {dt}, times = {times:?}: {result:?}"
        );
        // Nothing was stepped.
        assert_eq!(system.bodies()[0].position(), &before);
        refused += 1;
    }
    assert_eq!(refused, cases.len());
}

/// A resting ball: one contact per sample after the first, at the bottom of the ball, with
/// the floor's normal, and a normal impulse over the step that carries the weight m g h.
#[test]
fn contacts_of_a_resting_ball_carry_its_weight() {
    let mut system = resting_ball();
    let h = 0.01;
    let times: Vec<f64> = (0..=20).map(|k| 5.0 * h * k as f64).collect();
    let run = system
        .record(&mut MotionSplitting::new(), h, &times)
        .unwrap();
    assert!(run.contacts[0].is_empty(), "no step ends at t = 0");
    let mut checked = 0;
    for (k, contacts) in run.contacts.iter().enumerate().skip(1) {
        assert_eq!(contacts.len(), 1, "t = {}: {contacts:?}", run.times[k]);
        let c = &contacts[0];
        assert_eq!((c.body, c.half_space), (0, 0));
        assert_eq!(c.normal, [0.0, 0.0, 1.0]);
        let x = &run.bodies[0].position[k];
        let bottom = [x[0], x[1], x[2] - 0.5];
        for i in 0..3 {
            assert!((c.point[i] - bottom[i]).abs() < 1e-9, "{c:?} vs {bottom:?}");
        }
        let weight = 3.0 * G * h;
        assert!(
            (c.normal_impulse - weight).abs() < 1e-9 * weight,
            "t = {}: {} vs m g h = {weight}",
            run.times[k],
            c.normal_impulse
        );
        assert!(c.friction_impulse.iter().all(|f| f.abs() < 1e-12));
        checked += 1;
    }
    assert_eq!(checked, times.len() - 1);
    assert_eq!(run.planes.len(), 1);
    assert_eq!(run.planes[0].normal, [0.0, 0.0, 1.0]);
}

/// Reads a CSV text back into its header and rows of numbers.
fn read_csv(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut lines = text.lines();
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

#[test]
fn csv_files_read_back_bit_for_bit() {
    let mut run = resting_ball()
        .record(&mut MotionSplitting::new(), 0.01, &[0.0, 0.013, 0.1])
        .unwrap();
    run.bodies[0].name = "ball".into();
    let files = run.csv_files().unwrap();
    let names: Vec<&str> = files.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["ball.csv", "system.csv"]);
    let (header, rows) = read_csv(&files[0].1);
    assert_eq!(header.len(), 1 + 3 + 3 + 9 + 3);
    assert_eq!(header[7], "R11");
    assert_eq!(header[16], "w12");
    assert_eq!(rows.len(), 3);
    let body = &run.bodies[0];
    for (k, row) in rows.iter().enumerate() {
        let expected: Vec<f64> = std::iter::once(run.times[k])
            .chain(body.position[k].iter().copied())
            .chain(body.velocity[k].iter().copied())
            .chain(body.attitude[k].iter().flatten().copied())
            .chain(body.omega[k].iter().copied())
            .collect();
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(row), bits(&expected));
    }
    let (header, rows) = read_csv(&files[1].1);
    assert_eq!(
        header,
        ["t", "energy", "p1", "p2", "p3", "L12", "L13", "L23"]
    );
    for (k, row) in rows.iter().enumerate() {
        assert_eq!(row[1].to_bits(), run.energy[k].to_bits());
    }
    // A number that is not finite is refused, naming its sample.
    run.energy[1] = f64::NAN;
    assert!(matches!(
        run.csv_files(),
        Err(DynamicsError::NonFinite { time }) if time == 0.013
    ));
}

#[cfg(feature = "serde")]
#[test]
fn json_reads_back_bit_for_bit() {
    let run = resting_ball()
        .record(&mut MotionSplitting::new(), 0.01, &[0.0, 0.013, 0.1])
        .unwrap();
    let text = run.to_json().unwrap();
    assert!(text.ends_with("}\n") && text.lines().count() == 1);
    let back: SystemTrajectory = serde_json::from_str(&text).unwrap();
    assert_eq!(back, run);
    let value: serde_json::Value = serde_json::from_str(&text).unwrap();
    let contact = &value["contacts"][1][0];
    for key in [
        "body",
        "half_space",
        "point",
        "normal",
        "normal_impulse",
        "friction_impulse",
        "slip",
    ] {
        assert!(contact.get(key).is_some(), "no {key} in {contact}");
    }
    let mut bad = run.clone();
    bad.bodies[0].position[2][0] = f64::INFINITY;
    assert!(matches!(
        bad.to_json(),
        Err(DynamicsError::NonFinite { time }) if time == 0.1
    ));
}

/// What is drawn of a body is the same whether it comes from its SPEC or from the contact
/// shape a system holds for it.
#[cfg(feature = "viz")]
#[test]
fn drawings_from_specs_and_contact_shapes_agree() {
    use rotorflow::dynamics::motion::ContactShape;
    use rotorflow::viz::Shape;
    let specs = [
        "cuboid:1,2,3",
        "tesseract:1,1.2,1.5,2",
        "cuboid:0.5,0.5",
        "ellipsoid:1,2,3,4",
        "ball:3,0.5",
        "pentachoron:1,1,1,1",
        "simplex:3",
    ];
    for spec in specs {
        let parsed = parse_body(spec).unwrap();
        let contact = ContactShape::from_geometry(&parsed.geometry);
        assert_eq!(
            Shape::of_contact_shape(&contact, parsed.dim),
            Shape::of_body(&parsed),
            "{spec}"
        );
    }
    // A box's drawing has its N 2^(N−1) edges, not every pair of corners.
    let tesseract = Shape::of_contact_shape(
        &ContactShape::from_geometry(&parse_body("cuboid:1,1,1,1").unwrap().geometry),
        4,
    );
    assert_eq!(tesseract.edges.len(), 32);
}

/// A convex shape with a margin is drawn by its support points: every point of a capsule's
/// drawing lies on its surface (at the radius from its segment), the drawing reaches its
/// ends (h + r along ±e₁), a ball as a point with a margin is drawn as the ball, and a
/// compound as its pieces' drawings moved to their places.
#[cfg(feature = "viz")]
#[test]
fn convex_shapes_are_drawn_on_their_surface() {
    use rotorflow::dynamics::motion::ContactShape;
    use rotorflow::dynamics::motion::shape::{CompoundShape, ConvexShape, Piece};
    use rotorflow::viz::Shape;
    for n in [3, 4, 5] {
        let (h, r) = (0.4, 0.2);
        let capsule = ContactShape::Convex(ConvexShape::capsule(n, h, r).unwrap());
        let drawing = Shape::of_contact_shape(&capsule, n);
        assert!(drawing.points.len() >= 2 * n, "N = {n}");
        let mut reach = 0.0f64;
        for p in &drawing.points {
            let along = p[0].clamp(-h, h);
            let d = ((p[0] - along).powi(2) + p[1..].iter().map(|x| x * x).sum::<f64>()).sqrt();
            assert!(
                (d - r).abs() < 1e-12,
                "N = {n}: {p:?} at {d} from the segment"
            );
            reach = reach.max(p[0].abs());
        }
        assert!((reach - (h + r)).abs() < 1e-12, "N = {n}: reach {reach}");
        let ball = ContactShape::Convex(ConvexShape::ball(n, 0.5).unwrap());
        assert_eq!(
            Shape::of_contact_shape(&ball, n),
            Shape::of_contact_shape(&ContactShape::Ellipsoid(vec![0.5; n]), n)
        );
        // A compound of the capsule and a box beside it: both drawings, the box's moved.
        let mut offset = vec![0.0; n];
        offset[1] = 2.0;
        let box_piece = ConvexShape::cuboid(&vec![0.5; n]).unwrap();
        let compound = ContactShape::Compound(
            CompoundShape::new(vec![
                Piece::translated(ConvexShape::capsule(n, h, r).unwrap(), &vec![0.0; n]).unwrap(),
                Piece::translated(box_piece.clone(), &offset).unwrap(),
            ])
            .unwrap(),
        );
        let both = Shape::of_contact_shape(&compound, n);
        let cube = Shape::of_convex(&box_piece);
        assert_eq!(both.points.len(), drawing.points.len() + cube.points.len());
        assert_eq!(both.edges.len(), cube.edges.len(), "N = {n}");
        for (p, q) in both.points[drawing.points.len()..].iter().zip(&cube.points) {
            assert!((p[1] - q[1] - 2.0).abs() < 1e-15 && p[0] == q[0], "N = {n}");
        }
    }
}

/// The animation of a run carries the run's contacts frame by frame.
#[cfg(feature = "viz")]
#[test]
fn the_animation_holds_the_contacts_of_each_frame() {
    use rotorflow::viz::trajectory::{Drawing, animation_html, plot_svg};
    let mut system = resting_ball();
    let times = [0.0, 0.05, 0.1];
    let run = system
        .record(&mut MotionSplitting::new(), 0.01, &times)
        .unwrap();
    let page = animation_html(&run, &Drawing::of_system(&system, "resting"));
    let start = page
        .find(r#"<script type="application/json" id="data">"#)
        .unwrap();
    let data = &page[start..];
    let data = &data[data.find('>').unwrap() + 1..data.find("</script>").unwrap()];
    let value: serde_json::Value = serde_json::from_str(data).unwrap();
    let contacts = value["contacts"].as_array().unwrap();
    assert_eq!(contacts.len(), times.len());
    assert_eq!(contacts[0], serde_json::json!([]));
    for (k, frame) in contacts.iter().enumerate().skip(1) {
        let point: Vec<f64> = frame[0]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        for (drawn, recorded) in point.iter().zip(&run.contacts[k][0].point) {
            assert!((drawn - recorded).abs() <= 1e-9);
        }
    }
    let svg = plot_svg(&run, "resting").unwrap();
    assert!(
        svg.contains("body1 x"),
        "the positions' legend names the body"
    );
}
