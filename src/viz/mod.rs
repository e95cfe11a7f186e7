//! Pictures of rotating N-dimensional bodies (feature `cli`).
//!
//! - [`Shape`]: what is drawn of a body (vertices and edges, or a point cloud for solids), in
//!   its own axes about the centre of mass.
//! - [`projection`]: N-D → 3D (perspective from each left-out axis, like the paper's
//!   figures 1–3, or orthographic) and 3D → page; an SVG strip of frames.
//! - [`html`]: a self-contained HTML animation with play/pause, a time slider, a draggable
//!   view and a choice of projection axes.
//! - [`scene`]: the HTML animation of a scene: several bodies moving and turning, and the
//!   planes of solid world, in the same projection.
//! - [`plot`]: SVG line plots (plotters) with labelled axes and legends.
//!
//! The module only draws: it takes rotation matrices and numbers from the dynamics and
//! never imports the command line (`algebra ← inertia ← dynamics ← viz, cli`).

pub mod html;
pub mod plot;
pub mod projection;
pub mod scene;
mod shape;

pub use projection::Projection;
pub use shape::Shape;
