//! A self-contained HTML animation of a scene (no network): several bodies that move and
//! turn in N-D, and the planes of solid world, projected to 3D as the single-body page of
//! [`super::html`] does.
//!
//! Each body is its [`Shape`] placed at each frame by its rotation matrix (own axes → space)
//! and its centre of mass. Points are taken relative to the centre of the scene (the middle
//! of the box that holds every body at every frame), so the perspective from each left-out
//! axis is about the scene's centre. A plane n·x = d is drawn as a translucent square: its
//! trace in the three shown coordinates, with the left-out coordinates at the centre's,
//! around the bodies' region. Springs are zigzags from the body point to the other end, ball
//! joints rings at the jointed point, anchors (points of space) small squares; a triad marks
//! the origin of space. An ellipsoid or a ball is drawn as the meridians and parallels of the
//! 3D ellipsoid its projection is (from the semi-axes, [`Shape::ellipsoid`]), not as points.
//! The contact points of each frame are drawn as orange discs in a ring, and the frames
//! with contacts flash the frame's border. Opened with `#selftest` the page reports pixel
//! statistics as the single-body page does, what it drew (`drawn`: the triad's axes, wire
//! frames, springs, joints, anchors) and, over every frame, the contact markers it drew
//! (`contact_markers`, `frames_with_contacts`).

use super::Shape;
use super::html::{page, round};
use nalgebra::DMatrix;
use serde_json::json;

/// One body of the scene and its placement at each frame.
#[derive(Clone, Debug)]
pub struct SceneBodyFrames {
    /// The body's name.
    pub name: String,
    /// Its geometry, in its own axes about the centre of mass.
    pub shape: Shape,
    /// The centre of mass at each frame.
    pub positions: Vec<Vec<f64>>,
    /// The rotation matrix (own axes → space) at each frame.
    pub matrices: Vec<DMatrix<f64>>,
}

/// A spring or a ball joint, drawn between a body point and its other end.
#[derive(Clone, Debug)]
pub struct SceneLink {
    /// True for a spring (a zigzag), false for a ball joint (a ring at the jointed point).
    pub spring: bool,
    /// The body, by index into the bodies.
    pub body: usize,
    /// Its point, own axes.
    pub point: Vec<f64>,
    /// The other end's body (by index), or `None` for a point of space (an anchor).
    pub other: Option<usize>,
    /// The other end: a point of the other body (own axes) or of space.
    pub end: Vec<f64>,
}

/// What the scene page shows.
#[derive(Clone, Debug)]
pub struct SceneAnimation<'a> {
    /// The title.
    pub title: &'a str,
    /// The dimension N of space.
    pub dim: usize,
    /// The frame times.
    pub times: &'a [f64],
    /// The bodies.
    pub bodies: &'a [SceneBodyFrames],
    /// The planes n·x = d as (n, d).
    pub planes: &'a [(Vec<f64>, f64)],
    /// The springs and ball joints.
    pub links: &'a [SceneLink],
    /// The vertical axis (0-based), drawn upwards and always among the axes shown first:
    /// the axis of the gravity, if any.
    pub up: Option<usize>,
    /// The contact points (space, N coordinates) at each frame; empty for none at all.
    pub contacts: &'a [Vec<Vec<f64>>],
}

/// Returns the vertical axis of a scene with gravity `g`: the axis of its largest
/// component, if g is not zero (0-based).
pub fn up_axis(g: &[f64]) -> Option<usize> {
    let (k, m) = g.iter().enumerate().fold((0, 0.0_f64), |(k, m), (i, x)| {
        if x.abs() > m { (i, x.abs()) } else { (k, m) }
    });
    (m > 0.0).then_some(k)
}

/// Returns the three axes (0-based) a scene's page shows first: the vertical axis `up` (if
/// any) and the axes of the widest `extent` (the size of the box the bodies' centres sweep
/// along each axis) after it, ties to the lower axis; the vertical axis last (drawn
/// upwards), the others in increasing order. With N ≤ 3: 0, 1, 2, with `up` last.
pub(crate) fn default_axes(extent: &[f64], up: Option<usize>) -> [usize; 3] {
    let n = extent.len().max(3);
    let up = up.filter(|&u| u < n);
    let mut others: Vec<usize> = (0..n).filter(|&k| Some(k) != up).collect();
    // Widest first; the sort is stable, so ties keep the lower axis first.
    others.sort_by(|&a, &b| {
        let (ea, eb) = (
            extent.get(a).copied().unwrap_or(0.0),
            extent.get(b).copied().unwrap_or(0.0),
        );
        eb.partial_cmp(&ea).unwrap_or(std::cmp::Ordering::Equal)
    });
    let mut chosen: Vec<usize> = others
        .into_iter()
        .take(if up.is_some() { 2 } else { 3 })
        .collect();
    chosen.sort_unstable();
    if let Some(u) = up {
        chosen.push(u);
    }
    [chosen[0], chosen[1], chosen[2]]
}

/// Embeds a point of dimension `n` < 3 in 3D (zeros after).
fn pad(p: &[f64], dim: usize) -> Vec<f64> {
    let mut v: Vec<f64> = p.iter().map(|x| round(*x)).collect();
    v.resize(dim, 0.0);
    v
}

/// Returns the page's HTML.
pub fn scene_html(a: &SceneAnimation<'_>) -> String {
    let n = a.dim;
    // A 2D scene is drawn in the plane z = 0 of 3D space.
    let shown = n.max(3);
    // The box that holds every body at every frame.
    let mut lo = vec![f64::INFINITY; shown];
    let mut hi = vec![f64::NEG_INFINITY; shown];
    let mut body_radius: f64 = 0.0;
    for b in a.bodies {
        let r = b.shape.radius();
        body_radius = body_radius.max(r);
        for x in &b.positions {
            for k in 0..shown {
                let c = x.get(k).copied().unwrap_or(0.0);
                lo[k] = lo[k].min(c - r);
                hi[k] = hi[k].max(c + r);
            }
        }
    }
    if lo.iter().any(|x| !x.is_finite()) {
        lo = vec![-1.0; shown];
        hi = vec![1.0; shown];
    }
    let centre: Vec<f64> = lo
        .iter()
        .zip(&hi)
        .map(|(l, h)| round(0.5 * (l + h)))
        .collect();
    let radius = lo
        .iter()
        .zip(&hi)
        .map(|(l, h)| 0.5 * (h - l))
        .map(|x| x * x)
        .sum::<f64>()
        .sqrt()
        .max(body_radius)
        .max(1e-9);
    let bodies: Vec<_> = a
        .bodies
        .iter()
        .map(|b| {
            let frames: Vec<Vec<f64>> = b
                .matrices
                .iter()
                .map(|m| {
                    let mut q = vec![0.0; shown * shown];
                    for r in 0..shown {
                        for c in 0..shown {
                            q[r * shown + c] = if r < n && c < n {
                                round(m[(r, c)])
                            } else if r == c {
                                1.0
                            } else {
                                0.0
                            };
                        }
                    }
                    q
                })
                .collect();
            // The semi-axes as columns, padded like the points: the page draws the surface of
            // the projected ellipsoid.
            let ellipsoid = b.shape.ellipsoid.as_ref().map(|e| {
                let mut flat = vec![0.0; shown * shown];
                for r in 0..n.min(e.nrows()) {
                    for c in 0..n.min(e.ncols()) {
                        flat[r * shown + c] = round(e[(r, c)]);
                    }
                }
                flat
            });
            json!({
                "name": b.name,
                "ellipsoid": ellipsoid,
                "points": b.shape.points.iter().map(|p| pad(p, shown)).collect::<Vec<_>>(),
                "edges": b.shape.edges,
                "cloud": b.shape.cloud,
                "frames": frames,
                "positions": b.positions.iter().map(|p| pad(p, shown)).collect::<Vec<_>>(),
            })
        })
        .collect();
    // How far the centres of mass move along each axis.
    let extent: Vec<f64> = (0..shown)
        .map(|k| {
            let (l, h) = a
                .bodies
                .iter()
                .flat_map(|b| b.positions.iter())
                .map(|x| x.get(k).copied().unwrap_or(0.0))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), c| {
                    (l.min(c), h.max(c))
                });
            if h >= l { round(h - l) } else { 0.0 }
        })
        .collect();
    let axes = default_axes(&extent, a.up);
    let planes: Vec<_> = a
        .planes
        .iter()
        .map(|(normal, offset)| json!({ "normal": pad(normal, shown), "offset": round(*offset) }))
        .collect();
    let links: Vec<_> = a
        .links
        .iter()
        .map(|l| {
            json!({
                "spring": l.spring,
                "body": l.body,
                "point": pad(&l.point, shown),
                "other": l.other,
                "end": pad(&l.end, shown),
            })
        })
        .collect();
    let contacts: Vec<Vec<Vec<f64>>> = (0..a.times.len())
        .map(|k| {
            a.contacts
                .get(k)
                .map_or(Vec::new(), |c| c.iter().map(|p| pad(p, shown)).collect())
        })
        .collect();
    let data = json!({
        "contacts": contacts,
        "links": links,
        "dim": shown,
        "title": a.title,
        "times": a.times,
        "centre": centre,
        "radius": round(radius),
        "bodies": bodies,
        "planes": planes,
        "axes": axes,
        "projection": "orthographic",
        "up": a.up.filter(|&u| u < shown),
    });
    page(TEMPLATE, a.title, &data)
}

const TEMPLATE: &str = r##"<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>rotorflow scene: {{TITLE}}</title>
<style>
{{STYLE}}
  #legend span { margin-right: 12px; font-size: 13px; }
</style>
</head>
<body>
<h3 id="heading">rotorflow scene: {{TITLE}}</h3>
{{CONTROLS}}
<div id="legend"></div>
<canvas id="view" width="720" height="540"></canvas>
<p style="font-size:13px;color:#555">Drag to turn the 3D view. The vertical axis (that of gravity) is drawn upwards; the triad x<sub>i</sub> is at the origin of space.
Round bodies are the wire frames of their 3D projections; springs are zigzags, ball joints rings, anchors squares. Planes are the translucent squares: each plane's
trace in the three shown coordinates, the others held at the scene's centre. Contacts are orange discs in a ring; the border flashes orange while a body touches. The N−3 axes left out are dropped
(orthographic) or removed by a perspective from each of them in turn about the scene's centre.</p>
{{SCRIPT}}
  const colours = ["#1f4e9c", "#c0392b", "#27864a", "#8e44ad", "#d35400", "#16a085", "#7f8c8d", "#b7950b"];
  const legend = document.getElementById("legend");
  D.bodies.forEach(function (b, i) {
    const s = document.createElement("span");
    s.style.color = colours[i % colours.length];
    s.textContent = "■ " + b.name;
    legend.appendChild(s);
  });
{{VIEW}}
  // The square patch of a plane in the shown coordinates, relative to the centre (3D).
  function patch(p) {
    const a = state.axes;
    const m = [p.normal[a[0]], p.normal[a[1]], p.normal[a[2]]];
    const mm = m[0] * m[0] + m[1] * m[1] + m[2] * m[2];
    if (mm < 1e-12) return null;
    // n·(c + y) = d with the left-out y = 0: m·y3 = d − n·c.
    let d = p.offset;
    for (let k = 0; k < n; k++) d -= p.normal[k] * D.centre[k];
    const base = [m[0] * d / mm, m[1] * d / mm, m[2] * d / mm];
    const len = Math.sqrt(mm);
    const u0 = [m[0] / len, m[1] / len, m[2] / len];
    const helper = Math.abs(u0[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0];
    let t1 = [u0[1] * helper[2] - u0[2] * helper[1], u0[2] * helper[0] - u0[0] * helper[2], u0[0] * helper[1] - u0[1] * helper[0]];
    const l1 = Math.hypot(t1[0], t1[1], t1[2]);
    t1 = [t1[0] / l1, t1[1] / l1, t1[2] / l1];
    const t2 = [u0[1] * t1[2] - u0[2] * t1[1], u0[2] * t1[0] - u0[0] * t1[2], u0[0] * t1[1] - u0[1] * t1[0]];
    const s = 1.2 * D.radius;
    return [[1, 1], [1, -1], [-1, -1], [-1, 1]].map(function (c) {
      return [base[0] + s * (c[0] * t1[0] + c[1] * t2[0]),
              base[1] + s * (c[0] * t1[1] + c[1] * t2[1]),
              base[2] + s * (c[0] * t1[2] + c[1] * t2[2])];
    });
  }
  function draw() {
    const w = canvas.width, h = canvas.height;
    ctx.fillStyle = "#ffffff";
    ctx.fillRect(0, 0, w, h);
    if (count === 0) return;
    const scale = 0.36 * Math.min(w, h) / D.radius;
    const page = function (s) { return [w / 2 + scale * s[0], h / 2 + scale * s[1], s[2]]; };
    for (const p of D.planes) {
      const corners = patch(p);
      if (!corners) continue;
      const q = corners.map(function (c) { return page(view(c)); });
      ctx.fillStyle = "rgba(120, 140, 160, 0.22)";
      ctx.strokeStyle = "rgba(90, 100, 120, 0.6)";
      ctx.lineWidth = 1;
      ctx.beginPath(); ctx.moveTo(q[0][0], q[0][1]);
      for (let i = 1; i < 4; i++) ctx.lineTo(q[i][0], q[i][1]);
      ctx.closePath(); ctx.fill(); ctx.stroke();
    }
    const f = state.frame;
    const drawn = { triad: 0, wireframes: 0, springs: 0, joints: 0, anchors: 0 };
    // A point of body b (own axes) at this frame, in space relative to the centre.
    function placed(b, p) {
      const q = b.frames[f], x = b.positions[f], y = new Array(n).fill(0);
      for (let r = 0; r < n; r++) {
        let s = x[r] - D.centre[r];
        for (let c = 0; c < n; c++) s += q[r * n + c] * p[c];
        y[r] = s;
      }
      return y;
    }
    const onPage = function (y) { return page(view(project(y))); };
    function line(a, b) { ctx.beginPath(); ctx.moveTo(a[0], a[1]); ctx.lineTo(b[0], b[1]); ctx.stroke(); }
    // The coordinate triad at the origin of space: the three shown axes, labelled.
    const origin = D.centre.map(function (c) { return -c; });
    const o = onPage(origin);
    ctx.lineWidth = 2;
    ["#d33", "#3a3", "#33d"].forEach(function (col, k) {
      const e = origin.slice(); e[state.axes[k]] += 0.4 * D.radius;
      const t = onPage(e);
      ctx.strokeStyle = col; line(o, t);
      ctx.fillStyle = col; ctx.font = "13px sans-serif";
      ctx.fillText("x" + (state.axes[k] + 1), t[0] + 3, t[1]);
      drawn.triad++;
    });
    D.bodies.forEach(function (b, i) {
      const colour = colours[i % colours.length];
      ctx.strokeStyle = colour; ctx.fillStyle = colour;
      ctx.lineWidth = 1.4; ctx.globalAlpha = 0.85;
      if (b.ellipsoid) {
        // The projection of {x + Q E u : |u| ≤ 1} on the shown axes is the 3D ellipsoid
        // {c + L v : |v| ≤ 1} with L Lᵀ = M Mᵀ, M the shown rows of Q E (Cholesky, with
        // a flat direction kept flat): its meridians and parallels.
        const q = b.frames[f], a = state.axes, c = placed(b, new Array(n).fill(0));
        const M = a.map(function (r) {
          const row = new Array(n).fill(0);
          for (let k = 0; k < n; k++) for (let m = 0; m < n; m++) row[m] += q[r * n + k] * b.ellipsoid[k * n + m];
          return row;
        });
        const S = M.map(function (u) { return M.map(function (v) { let s = 0; for (let k = 0; k < n; k++) s += u[k] * v[k]; return s; }); });
        const L = [[0, 0, 0], [0, 0, 0], [0, 0, 0]];
        const tiny = 1e-24 * (S[0][0] + S[1][1] + S[2][2]);
        for (let j = 0; j < 3; j++) {
          let d = S[j][j];
          for (let k = 0; k < j; k++) d -= L[j][k] * L[j][k];
          L[j][j] = d > tiny ? Math.sqrt(d) : 0;
          for (let r = j + 1; r < 3; r++) {
            let s = S[r][j];
            for (let k = 0; k < j; k++) s -= L[r][k] * L[j][k];
            L[r][j] = L[j][j] > 0 ? s / L[j][j] : 0;
          }
        }
        const at = function (v) {
          const y = c.slice();
          for (let r = 0; r < 3; r++) y[a[r]] += L[r][0] * v[0] + L[r][1] * v[1] + L[r][2] * v[2];
          return onPage(y);
        };
        const ring = function (point) {
          ctx.beginPath();
          for (let s = 0; s <= 48; s++) {
            const p = at(point(2 * Math.PI * s / 48));
            if (s === 0) ctx.moveTo(p[0], p[1]); else ctx.lineTo(p[0], p[1]);
          }
          ctx.stroke();
        };
        for (let m = 0; m < 6; m++) {
          const phi = Math.PI * m / 6;
          ring(function (t) { return [Math.cos(phi) * Math.sin(t), Math.sin(phi) * Math.sin(t), Math.cos(t)]; });
        }
        for (const z of [-0.8660254, -0.5, 0, 0.5, 0.8660254]) {
          const rho = Math.sqrt(1 - z * z);
          ring(function (t) { return [rho * Math.cos(t), rho * Math.sin(t), z]; });
        }
        drawn.wireframes++;
        ctx.globalAlpha = 1;
        return;
      }
      const pts = b.points.map(function (p) { return onPage(placed(b, p)); });
      for (const e of b.edges) line(pts[e[0]], pts[e[1]]);
      ctx.globalAlpha = 1;
      const rad = b.cloud ? 1.4 : 3;
      for (const p of pts) { ctx.beginPath(); ctx.arc(p[0], p[1], rad, 0, 2 * Math.PI); ctx.fill(); }
    });
    // Springs as zigzags, ball joints as rings at the jointed point, anchors (points of
    // space) as small squares.
    ctx.globalAlpha = 1;
    for (const l of D.links) {
      const p = onPage(placed(D.bodies[l.body], l.point));
      const e = l.other === null ? l.end.map(function (v, k) { return v - D.centre[k]; })
                                 : placed(D.bodies[l.other], l.end);
      const r = onPage(e);
      ctx.strokeStyle = "#333"; ctx.fillStyle = "#333"; ctx.lineWidth = 1.2;
      if (l.spring) {
        const dx = r[0] - p[0], dy = r[1] - p[1], len = Math.hypot(dx, dy) || 1;
        const nx = -dy / len * 5, ny = dx / len * 5;
        ctx.beginPath(); ctx.moveTo(p[0], p[1]);
        for (let s = 1; s < 16; s++) {
          const t = s / 16, side = s % 2 === 0 ? -1 : 1;
          ctx.lineTo(p[0] + t * dx + side * nx, p[1] + t * dy + side * ny);
        }
        ctx.lineTo(r[0], r[1]); ctx.stroke();
        drawn.springs++;
      } else {
        line(p, r);
        ctx.beginPath(); ctx.arc(p[0], p[1], 5, 0, 2 * Math.PI); ctx.stroke();
        drawn.joints++;
      }
      if (l.other === null) { ctx.fillRect(r[0] - 4, r[1] - 4, 8, 8); drawn.anchors++; }
    }
    // The contacts of this frame: orange discs in a ring, and a flash of the border.
    const touching = D.contacts[f] || [];
    for (const c of touching) {
      const p = onPage(c.map(function (v, k) { return v - D.centre[k]; }));
      ctx.fillStyle = "#ff8c00"; ctx.strokeStyle = "#b35900"; ctx.lineWidth = 2;
      ctx.beginPath(); ctx.arc(p[0], p[1], 5, 0, 2 * Math.PI); ctx.fill();
      ctx.beginPath(); ctx.arc(p[0], p[1], 9, 0, 2 * Math.PI); ctx.stroke();
    }
    if (touching.length > 0) {
      ctx.strokeStyle = "#ff8c00"; ctx.lineWidth = 6;
      ctx.strokeRect(3, 3, w - 6, h - 6);
    }
    state.contactsDrawn = touching.length;
    state.drawn = drawn;
    slider.value = String(state.frame);
    timeLabel.textContent = "t = " + D.times[state.frame].toFixed(3);
  }
  // For the self-test: every frame drawn once, counting the contact markers.
  function selftestExtra() {
    let markers = 0, frames = 0;
    for (let k = 0; k < count; k++) {
      state.frame = k; draw();
      markers += state.contactsDrawn;
      if (state.contactsDrawn > 0) frames++;
    }
    return { contact_markers: markers, frames_with_contacts: frames };
  }
{{PLAYER}}
})();
</script>
</body>
</html>
"##;
