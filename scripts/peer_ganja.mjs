// Runs ganja.js's bivector exponential and versor logarithm on the cases that
// scripts/peer_versors.py sends on standard input, and prints the results as JSON.
//
// Not meant to be run alone: `python3 scripts/peer_versors.py` installs nothing, but expects
// `npm ci` to have been run in scripts/ (ganja.js is pinned in scripts/package-lock.json).
//
// Input: {"cases": [{"id", "p", "q", "r", "b": {name: value}}]}, blade names in ganja.js's
// own basis (null vector e0 first, then e1 … in rotorflow's order of the rest).
// Output: {"version", "overhead_us", "cases": [{"id", "exp", "log", "exp_us", "log_us"}]}, with
// "exp" and "log" either {name: value} over ganja.js's basis (non-finite values as strings) or
// an error string.

import { createRequire } from "node:module";
import { readFileSync } from "node:fs";

const require = createRequire(import.meta.url);
const Algebra = require("ganja.js");
const version = require("ganja.js/package.json").version;

// ganja.js stores coefficients in a Float32Array unless told otherwise; every comparison
// here is in double precision, so the flat algebras get Float64Array. The graded
// implementation (used from 7 dimensions on) stores plain JS numbers (doubles) anyway.
function algebra(p, q, r) {
  return Algebra({ p, q, r, baseType: Float64Array });
}

// The basis names of ganja.js's default basis (the code of its Algebra(): every subset of the
// basis vectors, named from e0 when there is a null vector and from e1 otherwise, sorted by
// grade and then as strings). The flat algebras also give them through describe(), which is
// checked; the graded ones (7 dimensions and more) have no working describe().
function basisOf(A, p, q, r) {
  const tot = p + q + r;
  const low = r !== 0 ? 0 : 1;
  const names = [];
  for (let m = 0; m < 1 << tot; m++) {
    let s = "";
    for (let i = 0; i < tot; i++) if (m & (1 << i)) s += String(low + i);
    names.push(s);
  }
  names.sort((a, b) =>
    a.length === b.length ? (a > b ? 1 : b > a ? -1 : 0) : a.length - b.length,
  );
  const basis = names.map((s) => (s ? "e" + s : "1"));
  if (tot <= 6) {
    const described = A.describe().basis;
    if (described.join() !== basis.join()) throw new Error(`unexpected basis ${described}`);
  }
  return basis;
}

function gradeStarts(basis) {
  const starts = [];
  basis.forEach((name, i) => {
    const g = name === "1" ? 0 : name.length - 1;
    if (starts[g] === undefined) starts[g] = i;
  });
  return starts;
}

function build(A, basis, blades) {
  const args = [];
  for (const [name, value] of Object.entries(blades)) {
    const i = basis.indexOf(name);
    if (i < 0) throw new Error(`no blade ${name} in ganja.js's basis`);
    args.push(i, value);
  }
  return A.Coeff(...args);
}

// {name: value} of the non-zero coefficients, for the flat and the graded layouts.
function read(el, basis, starts) {
  const out = {};
  const graded = !(ArrayBuffer.isView(el));
  basis.forEach((name, i) => {
    let v;
    if (graded) {
      const g = name === "1" ? 0 : name.length - 1;
      v = el[g] ? el[g][i - starts[g]] : undefined;
    } else {
      v = el[i];
    }
    if (v === undefined || v === 0) return;
    // JSON has no NaN or infinity: those go as the strings "NaN", "Infinity", "-Infinity".
    out[name] = Number.isFinite(v) ? v : String(v);
  });
  return out;
}

// Best of 5 repeats of a loop sized to take at least 20 ms, in microseconds per call.
function bestTime(f) {
  let n = 1;
  for (;;) {
    const t0 = process.hrtime.bigint();
    for (let i = 0; i < n; i++) f();
    const dt = Number(process.hrtime.bigint() - t0) / 1e3;
    if (dt >= 20000 || n >= 1 << 24) break;
    n *= 2;
  }
  let best = Infinity;
  for (let k = 0; k < 5; k++) {
    const t0 = process.hrtime.bigint();
    for (let i = 0; i < n; i++) f();
    best = Math.min(best, Number(process.hrtime.bigint() - t0) / 1e3 / n);
  }
  return best;
}

function message(e) {
  return `${e && e.name ? e.name : "Error"}: ${e && e.message ? e.message : String(e)}`;
}

const input = JSON.parse(readFileSync(0, "utf8"));

// Call overhead: the sum of two bivectors of 3D PGA.
const pga = algebra(3, 0, 1);
const pgaBasis = basisOf(pga, 3, 0, 1);
const x = build(pga, pgaBasis, { e12: 0.4, e13: -0.7, e23: 0.6, e01: -1.3 });
const y = build(pga, pgaBasis, { e12: 0.1, e13: 0.2, e23: 0.3 });
const overhead = bestTime(() => x.Add(y));

const cases = [];
for (const c of input.cases) {
  const A = algebra(c.p, c.q, c.r);
  const basis = basisOf(A, c.p, c.q, c.r);
  const starts = gradeStarts(basis);
  const b = build(A, basis, c.b);
  const out = { id: c.id, exp: null, log: null, exp_us: null, log_us: null };
  let v = null;
  try {
    v = b.Exp();
    out.exp = read(v, basis, starts);
    out.exp_us = bestTime(() => b.Exp());
  } catch (e) {
    out.exp = message(e);
  }
  if (v !== null) {
    try {
      const l = v.Log();
      if (l === undefined) throw new Error("Log returned undefined");
      out.log = read(l, basis, starts);
      out.log_us = bestTime(() => v.Log());
    } catch (e) {
      out.log = message(e);
    }
  }
  cases.push(out);
}

process.stdout.write(JSON.stringify({ version, overhead_us: overhead, cases }) + "\n");
