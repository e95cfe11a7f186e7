//! Projections of N-dimensional points to 3D (like the paper's figures 1–3) and of 3D to the
//! page, and a strip of frames as SVG.

use super::Shape;
use nalgebra::DMatrix;
use std::fmt::Write;

/// How the axes left out of the 3D view are removed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Projection {
    /// Seen from a camera on each left-out axis in turn, at 3 body radii: a point scales by
    /// D/(D − x_w), so the near side of a tesseract looks bigger (the classic "cube in a
    /// cube").
    Perspective,
    /// The left-out coordinates are dropped.
    Orthographic,
}

impl Projection {
    /// Returns the name used on the command line and in the HTML page.
    pub fn name(self) -> &'static str {
        match self {
            Projection::Perspective => "perspective",
            Projection::Orthographic => "orthographic",
        }
    }
}

/// Returns the 3D image of the space point `x` (N coordinates) seen along `axes` (three
/// distinct 0-based axes), for a body of radius `radius`.
pub fn project_to_3d(x: &[f64], axes: [usize; 3], projection: Projection, radius: f64) -> [f64; 3] {
    let mut v = [x[axes[0]], x[axes[1]], x[axes[2]]];
    if projection == Projection::Perspective {
        let distance = 3.0 * radius;
        for (k, w) in x.iter().enumerate() {
            if !axes.contains(&k) {
                let f = distance / (distance - w).max(1e-3 * distance);
                for c in &mut v {
                    *c *= f;
                }
            }
        }
    }
    v
}

/// The fixed view of the SVG strip: yaw and pitch in radians.
const VIEW: (f64, f64) = (0.6, 0.35);

/// Returns the page position (x right, y down) and depth of a 3D point under the view
/// (yaw, pitch), with a mild perspective at 4 body radii.
pub(crate) fn view_to_2d(v: [f64; 3], yaw: f64, pitch: f64, radius: f64) -> (f64, f64, f64) {
    let (sy, cy) = yaw.sin_cos();
    let (sp, cp) = pitch.sin_cos();
    let x1 = cy * v[0] + sy * v[1];
    let y1 = -sy * v[0] + cy * v[1];
    let z1 = v[2];
    // Pitch about the screen's horizontal axis: depth is y1 turned toward z.
    let depth = cp * y1 + sp * z1;
    let up = -sp * y1 + cp * z1;
    let f = 4.0 * radius / (4.0 * radius + depth);
    (x1 * f, -up * f, depth)
}

/// Returns an SVG strip of `matrices.len()` frames of `shape` turned by each rotation matrix
/// (body's own axes → space), projected along `axes`, with the time under each frame.
pub fn svg_strip(
    shape: &Shape,
    matrices: &[DMatrix<f64>],
    times: &[f64],
    axes: [usize; 3],
    projection: Projection,
    title: &str,
) -> String {
    let cell = 220.0;
    let width = cell * matrices.len().max(1) as f64;
    let height = cell + 60.0;
    let radius = shape.radius();
    let scale = 0.42 * cell / (radius * 1.6);
    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="sans-serif">"#
    );
    let _ = writeln!(svg, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        svg,
        r#"<text x="10" y="22" font-size="16">{} — axes {},{},{} ({})</text>"#,
        escape(title),
        axes[0] + 1,
        axes[1] + 1,
        axes[2] + 1,
        projection.name()
    );
    for (k, (q, t)) in matrices.iter().zip(times).enumerate() {
        let cx = cell * (k as f64 + 0.5);
        let cy = 40.0 + cell * 0.5;
        let page: Vec<(f64, f64, f64)> = shape
            .points
            .iter()
            .map(|p| {
                let n = p.len();
                let x: Vec<f64> = (0..n)
                    .map(|r| (0..n).map(|c| q[(r, c)] * p[c]).sum())
                    .collect();
                let v = project_to_3d(&x, axes, projection, radius);
                let (px, py, d) = view_to_2d(v, VIEW.0, VIEW.1, radius);
                (cx + scale * px, cy + scale * py, d)
            })
            .collect();
        let _ = writeln!(
            svg,
            r##"<rect x="{:.1}" y="34" width="{:.1}" height="{:.1}" fill="none" stroke="#ccc"/>"##,
            cx - cell * 0.5 + 3.0,
            cell - 6.0,
            cell + 12.0
        );
        for [a, b] in &shape.edges {
            let (pa, pb) = (page[*a], page[*b]);
            let _ = writeln!(
                svg,
                r##"<line x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}" stroke="#1f4e9c" stroke-width="1.2" stroke-opacity="0.8"/>"##,
                pa.0, pa.1, pb.0, pb.1
            );
        }
        let r = if shape.cloud { 1.2 } else { 3.0 };
        for p in &page {
            let _ = writeln!(
                svg,
                r##"<circle cx="{:.2}" cy="{:.2}" r="{r}" fill="#c0392b"/>"##,
                p.0, p.1
            );
        }
        let _ = writeln!(
            svg,
            r#"<text x="{cx:.1}" y="{:.1}" font-size="14" text-anchor="middle">t = {t:.3}</text>"#,
            40.0 + cell + 4.0
        );
    }
    svg.push_str("</svg>\n");
    svg
}

/// Escapes text for XML and HTML.
pub(crate) fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
