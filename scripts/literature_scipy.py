#!/usr/bin/env python3
"""References and scipy's DOP853 for the book's benchmarks from the literature.

    python3 scripts/literature_scipy.py --write

(`--keep-references` reuses the references of the existing data file, `--references`
computes the references alone).

needs numpy, scipy and mpmath (`pip install scipy mpmath`; gmpy2 makes mpmath faster) and
writes book/src/generated/literature_scipy.tsv, which `examples/book_literature.rs` reads:

- `ref` lines: the state at the end of each problem with a reference, from a Taylor series
  method in mpmath at 40 significant digits (every right-hand side here is quadratic in the
  state, so the Taylor coefficients follow from Cauchy products), run twice with different
  steps; the `ref_spread` line records how far the two runs differ (relative);
- `scipy` lines: `scipy.integrate.solve_ivp(method='DOP853')` at a range of tolerances,
  with the number of right-hand sides, the accepted steps, the fastest wall time per solve
  over several repeats, and the state at the end (the Rust example computes every error
  from it, so both sides are measured the same way);
- `overhead` lines: the wall time of a solve that takes one step of a right-hand side
  returning a constant, and of one call of each problem's right-hand side.

The problems (the same definitions as in the Rust example):

- `hlw`: Euler's equations y' = y × I⁻¹y, I = (2, 1, 2/3), y(0) = (cos 1.1, 0, sin 1.1),
  t = 100 (Hairer, Lubich, Wanner, Geometric Numerical Integration); the state is y (the
  body angular momentum).
- `p4`: the free solid 4D cuboid with half-lengths (1, 1.3, 1.7, 2.2) and mass 1, second
  moments Jᵢ = aᵢ²/3, ω(0) = (0.3, −0.2, 0.5, 0.1, 0.4, −0.6), t = 100; the state is ω
  (components 12, 13, 14, 23, 24, 34).
- `simo_wong`: the heavy symmetric top of Simo and Wong (1991): moments of inertia about the
  pivot (5, 5, 1), weight 20 along −e₃, centre of mass at distance 1 on the body's e₃,
  R(0) = exp of the skew matrix of (0.05, 0, 0), body angular velocity (0, 0, 50), t = 2.
- `bruls`: the heavy top of Brüls, Cardona and Arnold (2012): mass 15, inertia about the
  centre of mass diag(0.234375, 0.46875, 0.234375) with the symmetry axis e₂, the centre of
  mass at (0, 1, 0) in the body, so about the pivot diag(15.234375, 0.46875, 15.234375)
  (parallel axes), g = 9.81 along −e₃, R(0) = 1, body angular velocity (0, 150, −4.61538),
  t = 2.
- `free4`, `free6`, `free8`: free N-dimensional bodies with second moments Jₖ = 0.5 + 0.25k
  and body momentum components Lₖ = sin(0.7k + 0.3) (k = 0, 1, …, lexicographic planes),
  t = 20; the state is L (the error is the drift of the Manakov integrals, computed by the
  Rust example from L).

The tops carry the attitude R (row-major, body → space) and the body angular velocity Ω
(classical vectors): R' = R Ω̂, I Ω' = IΩ × Ω + X × Rᵀ(m g); the free bodies carry the
momentum alone.
"""

import math
import os
import platform
import subprocess
import sys
import time
from datetime import datetime, timezone

import mpmath
import numpy as np
import scipy
from scipy.integrate import solve_ivp

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "book", "src", "generated", "literature_scipy.tsv")

mpmath.mp.dps = 40

# ---------------------------------------------------------------------------------------
# The problems: the quadratic right-hand side f(y) = Q(y, y) + A y, written once as a
# bilinear form `quad(u, v)` plus a linear part `lin(u)`, used both by the Taylor reference
# (on mpmath numbers) and, through `rhs`, by scipy (on floats).


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def pairs(n):
    return [(i, j) for i in range(n) for j in range(i + 1, n)]


class Hlw:
    name, t_end = "hlw", 100
    inertia = (2, 1, mpmath.mpf(2) / 3)

    def __init__(self, num):
        self.inv = [num(1) / num(x) for x in self.inertia]

    def start(self, num):
        if num is mpmath.mpf:
            return [mpmath.cos(num(11) / 10), num(0), mpmath.sin(num(11) / 10)]
        return [math.cos(1.1), 0.0, math.sin(1.1)]

    def quad(self, u, v):
        return cross(u, [v[k] * self.inv[k] for k in range(3)])

    def lin(self, u):
        return None

    def output(self, y):
        return list(y)


class FreeN:
    """d[L]/dt = [ω][L] − [L][ω] with [ω]ᵢⱼ = Lᵢⱼ/(Jᵢ + Jⱼ) (rotorflow's conventions)."""

    def __init__(self, name, n, second_moments, t_end, state_is_omega):
        self.name, self.n, self.t_end = name, n, t_end
        self.j = second_moments
        self.p = pairs(n)
        self.index = {pq: k for k, pq in enumerate(self.p)}
        self.plane = [second_moments[i] + second_moments[j] for (i, j) in self.p]
        self.state_is_omega = state_is_omega

    def skew(self, v, i, j):
        if i == j:
            return 0
        if i < j:
            return v[self.index[(i, j)]]
        return -v[self.index[(j, i)]]

    def quad(self, u, v):
        # u, v: the state (ω or L); returns the rate of the state from ω(u) and L(v).
        n = self.n
        if self.state_is_omega:
            w, l = u, [v[k] * self.plane[k] for k in range(len(v))]
        else:
            w, l = [u[k] / self.plane[k] for k in range(len(u))], v
        out = []
        for k, (i, j) in enumerate(self.p):
            s = 0
            for m in range(n):
                if m == i or m == j:
                    continue
                s += self.skew(w, i, m) * self.skew(l, m, j) - self.skew(l, i, m) * self.skew(w, m, j)
            out.append(s / self.plane[k] if self.state_is_omega else s)
        return out

    def lin(self, u):
        return None

    def output(self, y):
        return list(y)


class Top:
    """R' = R Ω̂, I Ω' = IΩ × Ω + X × Rᵀ(−W e₃); y = (R row-major, Ω)."""

    def __init__(self, name, inertia, weight, offset, r0, omega0, t_end):
        self.name, self.inertia, self.weight, self.offset = name, inertia, weight, offset
        self.r0, self.omega0, self.t_end = r0, omega0, t_end

    def start(self, num):
        return [num(x) for x in self.r0] + [num(x) for x in self.omega0]

    def quad(self, u, v):
        r, w = v[:9], u[9:]
        # (R Ω̂)ᵢⱼ = Σₖ Rᵢₖ Ω̂ₖⱼ, Ω̂ = [[0, −w3, w2], [w3, 0, −w1], [−w2, w1, 0]].
        dr = []
        for i in range(3):
            r0, r1, r2 = r[3 * i], r[3 * i + 1], r[3 * i + 2]
            dr += [r1 * w[2] - r2 * w[1], r2 * w[0] - r0 * w[2], r0 * w[1] - r1 * w[0]]
        wv = v[9:]
        lw = [self.inertia[k] * w[k] for k in range(3)]
        dw = cross(lw, wv)
        return dr + [dw[k] / self.inertia[k] for k in range(3)]

    def lin(self, u):
        # Torque X × Rᵀ(−W e₃): Rᵀe₃ is the third row of R.
        r = u[:9]
        down = [-self.weight * r[6], -self.weight * r[7], -self.weight * r[8]]
        t = cross(self.offset, down)
        return [0] * 9 + [t[k] / self.inertia[k] for k in range(3)]

    def output(self, y):
        return list(y)


def rot_x(angle):
    c, s = math.cos(angle), math.sin(angle)
    return [1, 0, 0, 0, c, -s, 0, s, c]


def rot_x_mp(angle):
    c, s = mpmath.cos(angle), mpmath.sin(angle)
    return [1, 0, 0, 0, c, -s, 0, s, c]


def problems(num):
    """The problems on numbers of type `num` (mpmath.mpf or float)."""
    third = num(1) / 3
    p4_half = [num(1), num(13) / 10, num(17) / 10, num(22) / 10]
    p4 = FreeN("p4", 4, [a * a * third for a in p4_half], 100, True)
    p4.initial = [num(3) / 10, num(-2) / 10, num(5) / 10, num(1) / 10, num(4) / 10, num(-6) / 10]
    out = [Hlw(num), p4]
    if num is mpmath.mpf:
        r0 = rot_x_mp(num(5) / 100)
    else:
        r0 = rot_x(0.05)
    sw = Top("simo_wong", [num(5), num(5), num(1)], num(20), [num(0), num(0), num(1)], r0,
             [num(0), num(0), num(50)], 2)
    jc = [num("0.234375"), num("0.46875"), num("0.234375")]
    m = num(15)
    # Parallel axes: the offset (0, 1, 0) adds m·1² about e₁ and e₃.
    jp = [jc[0] + m, jc[1], jc[2] + m]
    br = Top("bruls", jp, m * num("9.81"), [num(0), num(1), num(0)],
             [1, 0, 0, 0, 1, 0, 0, 0, 1], [num(0), num(150), num("-4.61538")], 2)
    out += [sw, br]
    for n in (4, 6, 8):
        j = [num(1) / 2 + num(k) / 4 for k in range(n)]
        f = FreeN(f"free{n}", n, j, 20, False)
        f.initial = [mpmath.sin(num(7) * k / 10 + num(3) / 10) if num is mpmath.mpf
                     else math.sin(0.7 * k + 0.3) for k in range(n * (n - 1) // 2)]
        out.append(f)
    return out


def initial(problem, num):
    if hasattr(problem, "initial"):
        return list(problem.initial)
    return problem.start(num)


# ---------------------------------------------------------------------------------------
# The Taylor series reference.


def taylor_step(problem, y, h, order):
    """One step of the Taylor series method of the given order."""
    coeffs = [list(y)]
    dim = len(y)
    for k in range(order):
        acc = [mpmath.mpf(0)] * dim
        for i in range(k + 1):
            q = problem.quad(coeffs[i], coeffs[k - i])
            acc = [a + b for a, b in zip(acc, q)]
        lin = problem.lin(coeffs[k])
        if lin is not None:
            acc = [a + b for a, b in zip(acc, lin)]
        coeffs.append([a / (k + 1) for a in acc])
    # Horner in h.
    out = list(coeffs[order])
    for k in range(order - 1, -1, -1):
        out = [c + h * o for c, o in zip(coeffs[k], out)]
    return out


def taylor_solve(problem, steps, order):
    y = initial(problem, mpmath.mpf)
    h = mpmath.mpf(problem.t_end) / steps
    for _ in range(steps):
        y = taylor_step(problem, y, h, order)
    return problem.output(y)


# The steps per unit time of each reference, chosen so that h·(fastest rate) ≈ 0.1 at
# order 32 (about 1e-32 per step).
REFERENCE_RATE = {"hlw": 15, "p4": 15, "simo_wong": 600, "bruls": 1600}
ORDER = 32


def references(log):
    out = {}
    for problem in problems(mpmath.mpf):
        if problem.name not in REFERENCE_RATE:
            continue
        steps = REFERENCE_RATE[problem.name] * problem.t_end
        clock = time.time()
        a = taylor_solve(problem, steps, ORDER)
        b = taylor_solve(problem, (steps * 3) // 2, ORDER - 4)
        scale = max(abs(x) for x in a)
        spread = max(abs(x - z) for x, z in zip(a, b)) / scale
        log(f"{problem.name}: reference in {time.time() - clock:.0f} s, spread {mpmath.nstr(spread, 3)}")
        out[problem.name] = (a, spread)
    return out


# ---------------------------------------------------------------------------------------
# scipy.


def rhs(problem):
    def f(_t, y):
        q = problem.quad(y, y)
        lin = problem.lin(y)
        if lin is not None:
            q = [a + b for a, b in zip(q, lin)]
        return np.array(q)

    return f


def rhs_numpy(problem):
    """The same right-hand sides written with numpy, as a scipy user would."""
    if isinstance(problem, Hlw):
        inv = np.array([float(x) for x in problem.inv])

        def f(_t, y):
            return np.cross(y, inv * y)

        return f
    if isinstance(problem, Top):
        inertia = np.array([float(x) for x in problem.inertia])
        offset = np.array([float(x) for x in problem.offset])
        weight = float(problem.weight)

        def f(_t, y):
            r = y[:9].reshape(3, 3)
            w = y[9:]
            hat = np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])
            torque = np.cross(offset, -weight * r[2])
            dw = (np.cross(inertia * w, w) + torque) / inertia
            return np.concatenate(((r @ hat).ravel(), dw))

        return f
    n = problem.n
    iu = np.triu_indices(n, 1)
    plane = np.array([float(x) for x in problem.plane])

    def f(_t, y):
        if problem.state_is_omega:
            w, l = y, y * plane
        else:
            w, l = y / plane, y
        wm = np.zeros((n, n))
        lm = np.zeros((n, n))
        wm[iu] = w
        lm[iu] = l
        wm -= wm.T
        lm -= lm.T
        d = (wm @ lm - lm @ wm)[iu]
        return d / plane if problem.state_is_omega else d

    return f


TOLERANCES = [10.0 ** -k for k in range(3, 14)]
REPEATS_SECONDS = 1.0


def best_time(run, min_repeats=3, budget=REPEATS_SECONDS):
    best = math.inf
    spent, count = 0.0, 0
    while count < min_repeats or spent < budget:
        clock = time.perf_counter()
        run()
        dt = time.perf_counter() - clock
        best = min(best, dt)
        spent += dt
        count += 1
        if count >= 50:
            break
    return best


def scipy_runs(log):
    lines = []
    for problem in problems(float):
        f = rhs_numpy(problem)
        y0 = np.array([float(x) for x in initial(problem, float)])
        # The two right-hand sides agree (the numpy one is the one timed).
        assert np.max(np.abs(f(0, y0) - rhs(problem)(0, list(y0)))) < 1e-12 * (1 + np.max(np.abs(y0)))
        for rtol in TOLERANCES:
            atol = rtol * 1e-2

            def run():
                return solve_ivp(f, (0.0, problem.t_end), y0, method="DOP853", rtol=rtol, atol=atol)

            sol = run()
            if not sol.success:
                log(f"{problem.name} rtol {rtol:g}: {sol.message}")
                continue
            # Accepted steps: the solver's output grid, one point per accepted step.
            steps = len(sol.t) - 1
            seconds = best_time(run)
            final = ",".join(repr(float(x)) for x in problem.output(sol.y[:, -1]))
            lines.append(f"scipy\t{problem.name}\t{rtol:.0e}\t{atol:.0e}\t{sol.nfev}\t{steps}\t{seconds:.6e}\t{final}")
            log(f"{problem.name} rtol {rtol:.0e}: nfev {sol.nfev}, {seconds * 1e3:.2f} ms")
    return lines


def overheads():
    y0 = np.zeros(3)
    zero = np.zeros(3)

    def call():
        return solve_ivp(lambda t, y: zero, (0.0, 1e-9), y0, method="DOP853", rtol=1e-3, atol=1e-6)

    lines = [f"overhead\tsolve_ivp\t{best_time(call, 20, 0.5):.6e}"]
    for problem in problems(float):
        f = rhs_numpy(problem)
        y0 = np.array([float(x) for x in initial(problem, float)])
        calls = 2000

        def many():
            for _ in range(calls):
                f(0.0, y0)

        lines.append(f"overhead\trhs_{problem.name}\t{best_time(many, 5, 0.3) / calls:.6e}")
    return lines


def command(*args):
    try:
        return subprocess.run(args, cwd=ROOT, capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return ""


def header():
    commit = command("git", "rev-parse", "--short", "HEAD") or "unknown (not a git checkout)"
    dirty = command("git", "status", "--porcelain", "--untracked-files=no", "--", ".",
                    ":(exclude)book/src/generated")
    if dirty:
        commit += " dirty (uncommitted changes to tracked files)"
    cpu = platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return (
        f"# date: {datetime.now(timezone.utc):%Y-%m-%d}\n"
        f"# commit: {commit}\n"
        f"# machine: {cpu}, {os.cpu_count()} cores, {sys.platform}\n"
        f"# python: {platform.python_version()}, scipy {scipy.__version__}, numpy {np.__version__}, "
        f"mpmath {mpmath.__version__}\n"
        f"# method: solve_ivp(method='DOP853', rtol, atol = rtol/100), fastest wall time of "
        f"repeated solves (until {REPEATS_SECONDS:g} s, at least 3 and at most 50 solves); references by a Taylor "
        f"series method of order {ORDER} in mpmath at {mpmath.mp.dps} digits\n"
    )


def main():
    log = lambda s: print(s, file=sys.stderr, flush=True)  # noqa: E731
    only_refs = "--references" in sys.argv
    lines = []
    if "--keep-references" in sys.argv:
        # The references of the existing data file (they take minutes to compute).
        with open(OUT) as f:
            lines = [ln.rstrip("\n") for ln in f if ln.startswith(("ref\t", "ref_spread\t"))]
        if not lines:
            sys.exit(f"{OUT} has no references")
    else:
        for name, (values, spread) in references(log).items():
            lines.append(f"ref\t{name}\t{','.join(mpmath.nstr(x, 25, strip_zeros=False) for x in values)}")
            lines.append(f"ref_spread\t{name}\t{mpmath.nstr(spread, 3)}")
    if not only_refs:
        lines += overheads()
        lines += scipy_runs(log)
    text = header() + "\n".join(lines) + "\n"
    if "--write" in sys.argv:
        with open(OUT, "w") as f:
            f.write(text)
        log(f"wrote {OUT}")
    else:
        print(text)


if __name__ == "__main__":
    main()
