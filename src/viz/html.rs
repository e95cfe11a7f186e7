//! A self-contained HTML animation (no network): the body turning in N-D, projected to 3D.
//!
//! The page embeds the shape (points and edges in the body's own axes) and one rotation matrix
//! per frame, and draws on a canvas: play/pause, a time slider, drag to turn the 3D view, a
//! choice of the three projection axes and of perspective or orthographic projection. Opened
//! with `#selftest` in the address it draws the first frame and a later one, and writes pixel
//! statistics and any script errors as JSON into `<pre id="selftest">` (used by the tests with
//! headless Chromium).

use super::Shape;
use super::projection::{Projection, escape};
use nalgebra::DMatrix;
use serde_json::json;

/// What the page shows.
#[derive(Clone, Debug)]
pub struct Animation<'a> {
    /// The title (the body SPEC, say).
    pub title: &'a str,
    /// The body's geometry.
    pub shape: &'a Shape,
    /// The frame times.
    pub times: &'a [f64],
    /// The rotation matrix (body's own axes → space) at each frame time.
    pub matrices: &'a [DMatrix<f64>],
    /// The projection axes shown first (0-based).
    pub axes: [usize; 3],
    /// The projection shown first.
    pub projection: Projection,
}

/// Returns the page's HTML.
pub fn animation_html(a: &Animation<'_>) -> String {
    let n = a.shape.dim;
    let frames: Vec<Vec<f64>> = a
        .matrices
        .iter()
        .map(|m| {
            (0..n)
                .flat_map(|r| (0..n).map(move |c| (r, c)))
                .map(|(r, c)| round(m[(r, c)]))
                .collect()
        })
        .collect();
    let points: Vec<Vec<f64>> = a
        .shape
        .points
        .iter()
        .map(|p| p.iter().map(|x| round(*x)).collect())
        .collect();
    let data = json!({
        "dim": n,
        "title": a.title,
        "points": points,
        "edges": a.shape.edges,
        "cloud": a.shape.cloud,
        "radius": a.shape.radius(),
        "times": a.times,
        "frames": frames,
        "axes": a.axes,
        "projection": a.projection.name(),
    });
    page(TEMPLATE, a.title, &data)
}

/// Rounds a coordinate to 1e-9 for the page (shorter JSON, no visible difference).
pub(super) fn round(x: f64) -> f64 {
    (x * 1e9).round() / 1e9
}

/// Returns the page of `template` with `title`, `data` and the parts every animation page
/// shares: the style, the controls and the player's script (set-up, N-D → 3D → page, playing,
/// dragging and the `#selftest` report). The page's own script defines `draw` between
/// `{{SCRIPT}}`, `{{VIEW}}` (`project` and `view`) and `{{PLAYER}}`.
pub(super) fn page(template: &str, title: &str, data: &serde_json::Value) -> String {
    // `</` must not appear inside a <script> element; `<\/` is the same JSON string.
    let data = data.to_string().replace("</", "<\\/");
    template
        .replace("{{SCRIPT}}", SCRIPT)
        .replace("{{STYLE}}", STYLE)
        .replace("{{CONTROLS}}", CONTROLS)
        .replace("{{SETUP}}", SETUP)
        .replace("{{VIEW}}", VIEW)
        .replace("{{PLAYER}}", PLAYER)
        .replace("{{TITLE}}", &escape(title))
        .replace("{{DATA}}", &data)
}

/// The end of every page's body up to its own script: the self-test report, the data and
/// the opening of the script with the shared set-up.
const SCRIPT: &str = r##"<pre id="selftest"></pre>
<script type="application/json" id="data">{{DATA}}</script>
<script>
"use strict";
(function () {
{{SETUP}}"##;

const STYLE: &str = r##"  body { font-family: sans-serif; margin: 12px; background: #f4f5f7; color: #222; }
  #controls { display: flex; flex-wrap: wrap; gap: 10px; align-items: center; margin: 8px 0; }
  #controls label { font-size: 14px; }
  canvas { background: #ffffff; border: 1px solid #bbb; cursor: grab; touch-action: none; max-width: 100%; }
  #time { font-variant-numeric: tabular-nums; min-width: 8em; display: inline-block; }
  #slider { width: 320px; }
  #selftest { display: none; }"##;

const CONTROLS: &str = r##"<div id="controls">
  <button id="play" type="button">Pause</button>
  <input id="slider" type="range" min="0" max="0" value="0" aria-label="time">
  <span id="time"></span>
  <label>axes <select id="axes"></select></label>
  <label>projection <select id="projection">
    <option value="perspective">perspective</option>
    <option value="orthographic">orthographic</option>
  </select></label>
  <label>speed <select id="speed">
    <option value="0.5">0.5×</option><option value="1" selected>1×</option><option value="2">2×</option><option value="4">4×</option>
  </select></label>
</div>"##;

// The data's `dim`, `times`, `axes` (0-based), `projection` and optional `up` (the axis drawn
// upwards, last among the shown ones).
const SETUP: &str = r##"  const errors = [];
  window.addEventListener("error", function (e) { errors.push(String(e.message)); });
  const D = JSON.parse(document.getElementById("data").textContent);
  const n = D.dim;
  const canvas = document.getElementById("view");
  const selftest = window.location.hash === "#selftest";
  const ctx = canvas.getContext("2d", { willReadFrequently: selftest });
  const slider = document.getElementById("slider");
  const timeLabel = document.getElementById("time");
  const playButton = document.getElementById("play");
  const axesSelect = document.getElementById("axes");
  const projSelect = document.getElementById("projection");
  const speedSelect = document.getElementById("speed");
  const state = { frame: 0, playing: true, yaw: 0.6, pitch: 0.35, axes: D.axes.slice(),
                  perspective: D.projection === "perspective", last: null, acc: 0 };
  const count = D.times.length;
  slider.max = String(Math.max(0, count - 1));
  projSelect.value = D.projection;
  // Every triple of axes i < j < k, 1-based in the menu.
  for (let i = 0; i < n; i++) for (let j = i + 1; j < n; j++) for (let k = j + 1; k < n; k++) {
    const o = document.createElement("option");
    o.value = i + "," + j + "," + k;
    o.textContent = (i + 1) + "-" + (j + 1) + "-" + (k + 1);
    if (state.axes.slice().sort(function (x, y) { return x - y; }).join(",") === o.value) o.selected = true;
    axesSelect.appendChild(o);
  }
  // The vertical axis, when shown, is drawn upwards (last).
  function upLast(a) {
    if (D.up == null || a.indexOf(D.up) < 0) return a;
    return a.filter(function (k) { return k !== D.up; }).concat([D.up]);
  }"##;

const VIEW: &str = r##"  // A point of space (N coordinates, about the page's centre) → 3D: the shown coordinates,
  // scaled by a perspective from each left-out axis in turn, or not (orthographic).
  function project(y) {
    const a = state.axes;
    let v = [y[a[0]], y[a[1]], y[a[2]]];
    if (state.perspective) {
      const dist = 3 * D.radius;
      for (let k = 0; k < n; k++) {
        if (k === a[0] || k === a[1] || k === a[2]) continue;
        const f = dist / Math.max(dist - y[k], 1e-3 * dist);
        v = [v[0] * f, v[1] * f, v[2] * f];
      }
    }
    return v;
  }
  // 3D → the page: turned by the drag's yaw and pitch, with a mild perspective.
  function view(v) {
    const sy = Math.sin(state.yaw), cy = Math.cos(state.yaw);
    const sp = Math.sin(state.pitch), cp = Math.cos(state.pitch);
    const x1 = cy * v[0] + sy * v[1], y1 = -sy * v[0] + cy * v[1], z1 = v[2];
    const depth = cp * y1 + sp * z1, up = -sp * y1 + cp * z1;
    const f = 4 * D.radius / (4 * D.radius + depth);
    return [x1 * f, -up * f, depth];
  }"##;

const PLAYER: &str = r##"  function tick(now) {
    if (state.playing && count > 1) {
      if (state.last !== null) {
        state.acc += (now - state.last) / 1000 * 30 * Number(speedSelect.value);
        const steps = Math.floor(state.acc);
        if (steps > 0) { state.acc -= steps; state.frame = (state.frame + steps) % count; draw(); }
      }
      state.last = now;
    } else { state.last = null; }
    window.requestAnimationFrame(tick);
  }
  playButton.addEventListener("click", function () {
    state.playing = !state.playing;
    playButton.textContent = state.playing ? "Pause" : "Play";
  });
  slider.addEventListener("input", function () { state.frame = Number(slider.value); draw(); });
  axesSelect.addEventListener("change", function () { state.axes = upLast(axesSelect.value.split(",").map(Number)); draw(); });
  projSelect.addEventListener("change", function () { state.perspective = projSelect.value === "perspective"; draw(); });
  let drag = null;
  canvas.addEventListener("pointerdown", function (e) { drag = [e.clientX, e.clientY]; canvas.setPointerCapture(e.pointerId); });
  canvas.addEventListener("pointermove", function (e) {
    if (!drag) return;
    state.yaw += (e.clientX - drag[0]) * 0.01;
    state.pitch = Math.max(-1.5, Math.min(1.5, state.pitch + (e.clientY - drag[1]) * 0.01));
    drag = [e.clientX, e.clientY];
    draw();
  });
  canvas.addEventListener("pointerup", function () { drag = null; });
  function pixels() { return ctx.getImageData(0, 0, canvas.width, canvas.height).data; }
  function nonBlank(d) {
    let c = 0;
    for (let i = 0; i < d.length; i += 4) if (d[i] < 250 || d[i + 1] < 250 || d[i + 2] < 250) c++;
    return c;
  }
  if (selftest) {
    state.playing = false;
    state.frame = 0; draw();
    const first = pixels();
    state.frame = Math.floor((count - 1) / 2); draw();
    const later = pixels();
    let changed = 0;
    for (let i = 0; i < first.length; i += 4) {
      if (first[i] !== later[i] || first[i + 1] !== later[i + 1] || first[i + 2] !== later[i + 2]) changed++;
    }
    const report = { frames: count, nonblank_first: nonBlank(first), nonblank_later: nonBlank(later),
                     changed: changed, later_frame: state.frame, errors: errors, drawn: state.drawn };
    // A page may add what only it draws (the scene page: its contact markers).
    if (typeof selftestExtra === "function") Object.assign(report, selftestExtra());
    const pre = document.getElementById("selftest");
    pre.textContent = JSON.stringify(report);
    pre.style.display = "block";
  } else {
    draw();
    window.requestAnimationFrame(tick);
  }"##;

const TEMPLATE: &str = r##"<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>rotorflow: {{TITLE}}</title>
<style>
{{STYLE}}
</style>
</head>
<body>
<h3 id="heading">rotorflow: {{TITLE}}</h3>
{{CONTROLS}}
<canvas id="view" width="720" height="540"></canvas>
<p style="font-size:13px;color:#555">Drag to turn the 3D view. Edges are coloured by depth; the N−3 axes left out are
removed by a perspective from each of them in turn (the paper's figures 1–3) or dropped (orthographic).</p>
{{SCRIPT}}
  // The body point p (own axes) turned by q into space.
  function turned(q, p) {
    const x = new Array(n).fill(0);
    for (let r = 0; r < n; r++) { let s = 0; for (let c = 0; c < n; c++) s += q[r * n + c] * p[c]; x[r] = s; }
    return x;
  }
{{VIEW}}
  function draw() {
    const w = canvas.width, h = canvas.height;
    ctx.fillStyle = "#ffffff";
    ctx.fillRect(0, 0, w, h);
    if (count === 0) return;
    const q = D.frames[state.frame];
    const scale = 0.36 * Math.min(w, h) / D.radius;
    const pts = D.points.map(function (p) {
      const s = view(project(turned(q, p)));
      return [w / 2 + scale * s[0], h / 2 + scale * s[1], s[2]];
    });
    // Space axes of the view, faint.
    ctx.lineWidth = 1;
    ["#d33", "#3a3", "#33d"].forEach(function (col, k) {
      const e = [0, 0, 0]; e[k] = 1.3 * D.radius;
      const o = view([0, 0, 0]), t = view(e);
      ctx.strokeStyle = col; ctx.globalAlpha = 0.35;
      ctx.beginPath(); ctx.moveTo(w / 2 + scale * o[0], h / 2 + scale * o[1]);
      ctx.lineTo(w / 2 + scale * t[0], h / 2 + scale * t[1]); ctx.stroke();
      ctx.globalAlpha = 1;
      ctx.fillStyle = col; ctx.font = "13px sans-serif";
      ctx.fillText(String(state.axes[k] + 1), w / 2 + scale * t[0] + 3, h / 2 + scale * t[1]);
    });
    const r = D.radius;
    ctx.lineWidth = 1.6;
    for (const e of D.edges) {
      const a = pts[e[0]], b = pts[e[1]];
      const t = Math.min(1, Math.max(0, 0.5 - (a[2] + b[2]) / (4 * r)));
      ctx.strokeStyle = "rgb(" + Math.round(40 + 120 * (1 - t)) + "," + Math.round(70 + 60 * (1 - t)) + "," + Math.round(120 + 120 * t) + ")";
      ctx.beginPath(); ctx.moveTo(a[0], a[1]); ctx.lineTo(b[0], b[1]); ctx.stroke();
    }
    const rad = D.cloud ? 1.6 : 4;
    ctx.fillStyle = "#c0392b";
    for (const p of pts) { ctx.beginPath(); ctx.arc(p[0], p[1], rad, 0, 2 * Math.PI); ctx.fill(); }
    slider.value = String(state.frame);
    timeLabel.textContent = "t = " + D.times[state.frame].toFixed(3);
  }
{{PLAYER}}
})();
</script>
</body>
</html>
"##;
