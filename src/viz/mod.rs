//! Pictures of rotating and moving N-dimensional bodies (feature `viz`).
//!
//! - [`Shape`]: what is drawn of a body (vertices and edges, or a point cloud for solids), in
//!   its own axes about the centre of mass.
//! - [`projection`]: N-D → 3D (perspective from each left-out axis, like the paper's
//!   figures 1–3, or orthographic) and 3D → page; an SVG strip of frames.
//! - [`html`]: a self-contained HTML animation of one body turning, with play/pause, a time
//!   slider, a draggable view and a choice of projection axes.
//! - [`scene`]: the HTML animation of several bodies moving and turning, the planes of
//!   solid world, springs and joints, and the contacts of each frame, in the same
//!   projection.
//! - [`trajectory`]: the animation and the plots of a recorded run of a
//!   [`System`](crate::dynamics::motion::System)
//!   ([`SystemTrajectory`](crate::dynamics::motion::SystemTrajectory)).
//! - [`plot`]: SVG line plots (plotters) with labelled axes and legends.
//!
//! The module only draws: it takes rotation matrices and numbers from the dynamics
//! (`algebra ← inertia ← dynamics ← viz`); the `rotorflow` command is one of its users.
//!
//! ```
//! use rotorflow::prelude::*;
//! use rotorflow::dynamics::motion::forques::Gravity;
//! use rotorflow::dynamics::motion::{HalfSpace, MotionSplitting, MovingBody, System};
//! use rotorflow::inertia::spec::parse_body;
//! // A ball dropped on a floor: the page draws its contacts with the floor.
//! let ball = parse_body("ball:3,0.5+mass=1")?;
//! let up = Vector::from_components(&[0.0, 0.0, 1.0])?;
//! let dropped = MovingBody::from_parsed(
//!     &ball,
//!     Rotor::identity(3),
//!     &Vector::from_components(&[0.0, 0.0, 1.0])?,
//!     &Vector::zero(3),
//!     &Bivector::zero(3),
//! )?;
//! let mut system = System::new(vec![dropped])?;
//! system.add_forque(Gravity(&up * -9.81))?;
//! system.add_half_space(HalfSpace::new(&up, 0.0, 0.5, 0.0)?)?;
//! let times: Vec<f64> = (0..=20).map(|k| 0.1 * k as f64).collect();
//! let run = system.record(&mut MotionSplitting::new(), 0.01, &times)?;
//! assert!(run.contacts.last().is_some_and(|c| !c.is_empty()));
//! let page = rotorflow::viz::trajectory::animation_html(
//!     &run,
//!     &rotorflow::viz::trajectory::Drawing::of_system(&system, "a ball on the floor"),
//! );
//! assert!(page.contains("<canvas"));
//! let svg = rotorflow::viz::trajectory::plot_svg(&run, "a ball on the floor")?;
//! assert!(svg.starts_with("<svg"));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod html;
pub mod plot;
pub mod projection;
pub mod scene;
mod shape;
pub mod trajectory;

pub use plot::PlotError;
pub use projection::Projection;
pub use shape::{MAX_EDGES, MAX_POINTS, Shape};
