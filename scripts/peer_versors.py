#!/usr/bin/env python3
"""Runs the bivector exponential and the versor logarithm of four peer geometric-algebra
libraries on one set of cases and writes book/src/generated/peer_versors.tsv, from which
`cargo run --example book_peer_versors -- --write` renders the table of the book's chapter
"Other signatures" (section "Where the peers stand"), adding rotorflow's own errors.

Regenerate the data (from the repository root):

    pip install mpmath kingdon clifford
    (cd scripts && npm ci)                    # ganja.js, pinned in scripts/package-lock.json
    python3 scripts/peer_versors.py --write   # needs node, g++ and cargo on the PATH
    cargo run --example book_peer_versors -- --write

Without --write the data file is printed instead of written.

The peers:
- kingdon (PyPI): `MultiVector.exp`; kingdon has no logarithm.
- clifford (PyPI): `MultiVector.exp` (a Taylor series with scaling and squaring); the
  logarithm is `clifford.tools.log_rotor` (documented for simple rotors), and
  `clifford.tools.g3c.rotor_parameterisation.general_logarithm` (conformal rotors) for the
  Cl(4, 1) case.
- ganja.js (npm): `Element.Exp` and `Element.Log`, in Float64Array algebras (its default
  coefficient type is Float32Array), run by scripts/peer_ganja.mjs under node.
- klein (C++, 3D PGA only, single precision): `kln::exp(line)` and `kln::log(motor)`, run
  by scripts/peer_klein.cpp. klein itself is in no package registry, but the crates.io
  package klein-sys vendors its headers; this script fetches that package with
  `cargo metadata` and compiles the driver against them with g++.

Every case's reference exp(B) comes from scripts/versor_reference.py (a Taylor series with
scaling and squaring at 60 + 2 log10 max|B| digits, checked against a second run with more
digits), and is written to the data file with 21 significant digits. Each package's result is
converted to rotorflow's basis (null vector last, blades as bit masks) and measured as
- exp: max_k |exp(B)_k - V_k| / max(1, max_k |V_k|), V the reference;
- log: max_k |log(exp(B))_k - B_k| / max_k |B_k|, the logarithm applied to the package's own
  exp(B) (every B here is inside the principal branch, so the answer is B).
Exceptions, non-finite results and missing functions are recorded as outcomes.

Times are microseconds per call, the best of 5 repeats of a loop that takes at least 20 ms,
beside each package's call overhead (the sum of two 3D PGA bivectors in the same package).
They describe these packages as installed on the recording machine, in their own languages
(Python, JavaScript, C++), not their methods; rotorflow's own speed comes from its criterion
benches (`cargo bench --bench versors`).
"""

import datetime
import json
import math
import multiprocessing
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import timeit

import mpmath
from mpmath import mp, mpf

sys.dont_write_bytecode = True  # no __pycache__ in scripts/
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import versor_reference as ref  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUTPUT = os.path.join(ROOT, "book", "src", "generated", "peer_versors.tsv")
KLEIN_SYS = "0.1.1"
CXXFLAGS = ["-O2", "-std=c++17", "-msse4.1"]


# ---------------------------------------------------------------- the cases

def rf_mask(name):
    """rotorflow's bit mask of a blade named e12, e134, … (1-based indices)."""
    return ref.mask(*(int(c) for c in name[1:]))


def bv(**blades):
    return {rf_mask(k): float(v) for k, v in blades.items()}


NEAR_PI = math.pi - 1e-12
SCREW = dict(e12=0.4, e13=-0.7, e23=0.6, e14=1.3, e24=-0.8, e34=2.1)

# (id, title, (p, q, r), B). In Cl(3, 0, 1) e4 is the null vector (the projective e0); in
# Cl(1, 3, 0) e1 is time; in Cl(4, 1, 0) e5² = −1 and n∞ = e4 + e5.
CASES = [
    ("pga_screw", "3D PGA screw", (3, 0, 1), bv(**SCREW)),
    ("pga_simple", "3D PGA rotation about a line off the origin (simple)", (3, 0, 1),
     bv(e12=0.4, e14=0.4)),
    ("pga_near_pi", "3D PGA simple, angle π − 1e-12 (exp(B) near −1)", (3, 0, 1),
     bv(e12=0.6 * NEAR_PI, e23=0.8 * NEAR_PI, e24=0.5)),
    ("pga_tiny", "3D PGA screw × 1e-200", (3, 0, 1),
     {m: c * 1e-200 for m, c in bv(**SCREW).items()}),
    ("pga_huge_translation", "3D PGA translation by ~1e150", (3, 0, 1),
     bv(e14=1e150, e24=-6e149, e34=8e149)),
    ("pga_huge_screw", "3D PGA rotation 0.3 with translation ~1e150", (3, 0, 1),
     bv(e12=0.3, e14=1e150, e24=-6e149, e34=8e149)),
    ("cl4_isoclinic", "Cl(4) isoclinic 0.7 e12 + 0.7 e34", (4, 0, 0), bv(e12=0.7, e34=0.7)),
    ("cl4_near_isoclinic", "Cl(4) near-isoclinic, gap 1e-12", (4, 0, 0),
     bv(e12=0.7, e34=0.7 + 1e-12)),
    ("e8_isoclinic_pairs", "Cl(8) two isoclinic pairs (0.7, 0.7, 1.3, 1.3)", (8, 0, 0),
     bv(e12=0.7, e34=0.7, e56=1.3, e78=1.3)),
    ("sta_boost_rotation", "Cl(1,3) boost with rotation", (1, 3, 0),
     bv(e12=0.9, e13=-0.4, e23=0.3, e34=0.5)),
    ("cga_motor", "Cl(4,1) rotation with translation (3D conformal)", (4, 1, 0),
     bv(e12=0.6, e34=0.5, e35=0.5, e14=-0.2, e15=-0.2)),
]


# ---------------------------------------------------------------- bases

def labels(package, sig):
    """Each package's name (digit) of rotorflow's basis vectors e1 … eN. kingdon, ganja.js
    and klein put the null vector first as e0; clifford's Cl(3, 0, 1) has it as e1."""
    p, q, r = sig
    n = p + q + r
    assert r in (0, 1)
    if r == 0:
        return [i + 1 for i in range(n)]
    shift = 2 if package == "clifford" else 1
    null = 1 if package == "clifford" else 0
    return [i + shift for i in range(p + q)] + [null]


def parity(seq):
    inv = sum(1 for i in range(len(seq)) for j in range(i + 1, len(seq)) if seq[i] > seq[j])
    return -1 if inv % 2 else 1


def to_package(mask, labs, names):
    """(name, sign) of rotorflow's blade `mask` among a package's blade names: the package's
    coefficient is sign × rotorflow's."""
    rf = [labs[i] for i in range(len(labs)) if (mask >> i) & 1]
    for name in names:
        digits = [] if name in ("", "1", "e") else [int(c) for c in name[1:]]
        if sorted(digits) == sorted(rf):
            return name, parity([digits.index(x) for x in rf])
    raise KeyError(f"no blade for mask {mask} in {names}")


def from_package(coeffs, labs):
    """{mask: value} in rotorflow's basis from a package's {name: value}."""
    index = {lab: i for i, lab in enumerate(labs)}
    out = {}
    for name, value in coeffs.items():
        digits = [] if name in ("", "1", "e") else [int(c) for c in name[1:]]
        idx = [index[d] for d in digits]  # rotorflow's vectors, in the package's order
        mask = sum(1 << i for i in idx)
        out[mask] = out.get(mask, 0.0) + parity(idx) * float(value)
    return out


# ---------------------------------------------------------------- measures

def exp_error(result, v):
    with mp.workdps(60):
        top = max([abs(c) for c in v.values()] + [mpf(1)])
        diff = max(abs(mpf(result.get(m, 0.0)) - v.get(m, 0)) for m in set(v) | set(result))
        return float(diff / top)


def log_error(result, b):
    with mp.workdps(60):
        top = max(abs(mpf(c)) for c in b.values())
        diff = max(abs(mpf(result.get(m, 0.0)) - mpf(b.get(m, 0.0)))
                   for m in set(b) | set(result))
        return float(diff / top)


def non_finite(result):
    bad = [c for c in result.values() if not math.isfinite(c)]
    if not bad:
        return None
    return "NaN in the result" if any(math.isnan(c) for c in bad) else "infinite coefficients"


def summarise(e):
    text = f"{type(e).__name__}: {e}" if isinstance(e, BaseException) else str(e)
    text = " ".join(text.split())
    return text if len(text) <= 140 else text[:137] + "…"


def best_time(f):
    """Best of 5 repeats of a loop of at least 20 ms, in microseconds per call."""
    timer = timeit.Timer(f)
    number = 1
    while True:
        if timer.timeit(number) >= 0.02 or number >= 1 << 24:
            break
        number *= 2
    return min(timer.repeat(repeat=5, number=number)) / number * 1e6


class Outcome:
    """One package on one case: exp and log cells (an error or a text) and their times."""

    def __init__(self, exp="-", log="-", exp_us=None, log_us=None):
        self.exp, self.log, self.exp_us, self.log_us = exp, log, exp_us, log_us


def measure(case, v, exp_result, log_result, exp_us, log_us, no_log=None):
    """Outcome from a package's results in rotorflow's basis (dicts) or error texts."""
    _, _, _, b = case
    if isinstance(exp_result, str):
        return Outcome(exp=exp_result, log=no_log or "not run: exp failed")
    bad = non_finite(exp_result)
    if bad:
        return Outcome(exp=bad, log=no_log or "not run: exp not finite", exp_us=exp_us)
    out = Outcome(exp=exp_error(exp_result, v), exp_us=exp_us)
    if no_log:
        out.log = no_log
    elif isinstance(log_result, str):
        out.log = log_result
    else:
        bad = non_finite(log_result)
        out.log = bad if bad else log_error(log_result, b)
        out.log_us = log_us
    return out


# ---------------------------------------------------------------- isolation

TIMEOUT_S = 60


def isolated(work, case, refs, no_log=None):
    """Runs work(emit) in a forked child and returns the case's Outcome. The child reports
    emit("exp", result, µs) and emit("log", result, µs), results being {mask: value} or an
    error text. A call that does not return within TIMEOUT_S or kills the process is
    recorded as such (clifford 1.5.1's exp does not return on the 1e150 cases: its
    power-of-two scaling counts in a 64-bit integer, which overflows); the child's standard
    output (clifford.tools.log_rotor prints its argument when it is not simple) is
    discarded."""
    ctx = multiprocessing.get_context("fork")
    recv, send = ctx.Pipe(duplex=False)

    def child():
        os.dup2(os.open(os.devnull, os.O_WRONLY), 1)
        work(lambda kind, result, us: send.send((kind, result, us)))
        send.send(("done", None, None))

    proc = ctx.Process(target=child)
    proc.start()
    got = {}
    stalled = None
    while True:
        if not recv.poll(TIMEOUT_S):
            stalled = f"no result within {TIMEOUT_S} s (stopped)"
            break
        try:
            kind, result, us = recv.recv()
        except EOFError:
            stalled = f"the process died (exit code {proc.exitcode})"
            break
        if kind == "done":
            break
        got[kind] = (result, us)
    if proc.is_alive():
        proc.kill()
    proc.join()
    if "exp" not in got:
        return Outcome(exp=stalled, log=no_log or "not run: exp failed")
    if "log" not in got and no_log is None:
        got["log"] = (stalled, None)
    (e, te), (lg, tl) = got["exp"], got.get("log", (None, None))
    return measure(case, refs[case[0]], e, lg, te, tl, no_log=no_log)


# ---------------------------------------------------------------- kingdon

def run_kingdon(cases, refs):
    import kingdon
    from kingdon import Algebra

    algebras = {}

    def algebra(sig):
        if sig not in algebras:
            algebras[sig] = Algebra(*sig)
        return algebras[sig]

    def names_of(alg):
        return [alg.bin2canon[k] for k in sorted(alg.bin2canon)]

    def build(sig, b):
        alg = algebra(sig)
        labs, names = labels("kingdon", sig), names_of(alg)
        kw = {}
        for m, c in b.items():
            name, sign = to_package(m, labs, names)
            kw[name] = sign * c
        return alg.bivector(**kw)

    def read(sig, mv):
        alg = algebra(sig)
        coeffs = {alg.bin2canon[k]: v for k, v in zip(mv.keys(), mv.values())}
        return from_package(coeffs, labels("kingdon", sig))

    pga = (3, 0, 1)
    x, y = build(pga, bv(**SCREW)), build(pga, bv(e12=0.1, e13=0.2, e23=0.3))
    overhead = best_time(lambda: x + y)
    rows = {}
    no_log = f"no logarithm in kingdon {kingdon.__version__}"
    for case in cases:
        cid, _, sig, b = case

        def work(emit, sig=sig, b=b):
            mv = build(sig, b)
            try:
                e = read(sig, mv.exp())
                emit("exp", e, best_time(lambda: mv.exp()))
            except Exception as err:  # recorded, not raised
                emit("exp", summarise(err), None)

        rows[cid] = isolated(work, case, refs, no_log=no_log)
    return kingdon.__version__, overhead, rows


# ---------------------------------------------------------------- clifford

def run_clifford(cases, refs):
    import clifford
    from clifford.tools import log_rotor

    layouts = {}

    def layout(sig):
        if sig not in layouts:
            if sig == (4, 1, 0):
                # g3c's layout is Cl(4, 1) in rotorflow's order; general_logarithm needs it.
                from clifford import g3c
                layouts[sig] = g3c.layout
            else:
                layouts[sig] = clifford.Cl(*sig)[0]
        return layouts[sig]

    def names_of(lay):
        return list(lay.names)

    def build(sig, b):
        lay = layout(sig)
        labs, names = labels("clifford", sig), names_of(lay)
        value = [0.0] * len(names)
        for m, c in b.items():
            name, sign = to_package(m, labs, names)
            value[names.index(name)] = sign * c
        return lay.MultiVector(value=value)

    def read(sig, mv):
        lay = layout(sig)
        names = names_of(lay)
        coeffs = {names[i]: float(c) for i, c in enumerate(mv.value) if c != 0}
        return from_package(coeffs, labels("clifford", sig))

    pga = (3, 0, 1)
    x, y = build(pga, bv(**SCREW)), build(pga, bv(e12=0.1, e13=0.2, e23=0.3))
    overhead = best_time(lambda: x + y)
    rows = {}
    for case in cases:
        cid, _, sig, b = case
        if sig == (4, 1, 0):
            from clifford.tools.g3c.rotor_parameterisation import general_logarithm as log_fn
        else:
            log_fn = log_rotor

        def work(emit, sig=sig, b=b, log_fn=log_fn):
            mv = build(sig, b)
            try:
                ev = mv.exp()  # the first call compiles (numba)
                emit("exp", read(sig, ev), best_time(lambda: mv.exp()))
            except Exception as err:  # recorded, not raised
                emit("exp", summarise(err), None)
                return
            try:
                lg = read(sig, log_fn(ev))
                emit("log", lg, best_time(lambda: log_fn(ev)))
            except Exception as err:  # recorded, not raised
                emit("log", summarise(err), None)

        rows[cid] = isolated(work, case, refs)
    return clifford.__version__, overhead, rows


# ---------------------------------------------------------------- ganja.js

def run_ganja(cases, refs):
    script = os.path.join(ROOT, "scripts", "peer_ganja.mjs")
    if not os.path.isdir(os.path.join(ROOT, "scripts", "node_modules", "ganja.js")):
        raise RuntimeError("ganja.js is not installed: run `npm ci` in scripts/")
    payload = {"cases": []}
    for cid, _, sig, b in cases:
        labs = labels("ganja", sig)
        names = ganja_basis(sig)
        blades = {}
        for m, c in b.items():
            name, sign = to_package(m, labs, names)
            blades[name] = sign * c
        payload["cases"].append({"id": cid, "p": sig[0], "q": sig[1], "r": sig[2], "b": blades})
    out = subprocess.run(["node", script], input=json.dumps(payload), capture_output=True,
                         text=True, check=True, cwd=os.path.join(ROOT, "scripts"))
    data = json.loads(out.stdout)
    rows = {}
    for case, res in zip(cases, data["cases"]):
        cid, _, sig, _ = case
        assert res["id"] == cid
        labs = labels("ganja", sig)

        def conv(x):
            if isinstance(x, str):
                return summarise(x)
            return from_package({k: float(v) for k, v in x.items()}, labs)

        e = conv(res["exp"])
        lg = conv(res["log"]) if res["log"] is not None else None
        rows[cid] = measure(case, refs[cid], e, lg, res["exp_us"], res["log_us"])
    return data["version"], data["overhead_us"], rows


def ganja_basis(sig):
    """ganja.js's default basis names (peer_ganja.mjs checks them against the library)."""
    p, q, r = sig
    n = p + q + r
    low = 0 if r else 1
    names = ["".join(str(low + i) for i in range(n) if (m >> i) & 1) for m in range(1 << n)]
    names.sort(key=lambda s: (len(s), s))
    return ["e" + s if s else "1" for s in names]


# ---------------------------------------------------------------- klein

KLEIN_LINE = ["e01", "e02", "e03", "e23", "e31", "e12"]
KLEIN_MOTOR = ["1", "e23", "e31", "e12", "e01", "e02", "e03", "e0123"]


def klein_headers():
    """The include directory of klein's headers, from the crates.io package klein-sys."""
    work = os.path.join(ROOT, "target", "peer_klein", "fetch")
    os.makedirs(os.path.join(work, "src"), exist_ok=True)
    with open(os.path.join(work, "Cargo.toml"), "w") as f:
        f.write('[package]\nname = "klein-headers"\nversion = "0.0.0"\nedition = "2021"\n\n'
                f'[dependencies]\nklein-sys = "={KLEIN_SYS}"\n\n[workspace]\n')
    open(os.path.join(work, "src", "lib.rs"), "a").close()
    host = next(line.split()[1] for line in run_text(["rustc", "-vV"]).splitlines()
                if line.startswith("host:"))
    meta = json.loads(run_text(["cargo", "metadata", "--format-version", "1",
                                "--filter-platform", host, "--manifest-path",
                                os.path.join(work, "Cargo.toml")]))
    pkg = next(p for p in meta["packages"] if p["name"] == "klein-sys")
    base = os.path.join(os.path.dirname(pkg["manifest_path"]), "Klein")
    version = "?"
    with open(os.path.join(base, "CMakeLists.txt")) as f:
        for line in f:
            if line.startswith("project(klein VERSION"):
                version = line.split()[2]
    return os.path.join(base, "public"), version


def run_klein(cases, refs):
    include, version = klein_headers()
    exe = os.path.join(ROOT, "target", "peer_klein", "peer_klein")
    subprocess.run(["g++", *CXXFLAGS, "-I", include,
                    os.path.join(ROOT, "scripts", "peer_klein.cpp"), "-o", exe], check=True)
    sig = (3, 0, 1)
    labs = labels("klein", sig)
    lines = []
    for cid, _, s, b in cases:
        if s != sig:
            continue
        coeffs = [0.0] * 6
        for m, c in b.items():
            name, sign = to_package(m, labs, KLEIN_LINE)
            coeffs[KLEIN_LINE.index(name)] = sign * c
        lines.append(" ".join([cid] + [repr(c) for c in coeffs]))
    out = run_text([exe], "\n".join(lines) + "\n")
    rows = {}
    overhead = None
    by_id = {c[0]: c for c in cases}
    for line in out.splitlines():
        f = line.split()
        if f[0] == "overhead":
            overhead = float(f[1])
            continue
        cid = f[1]
        e = dict(zip(KLEIN_MOTOR, map(float, f[3:11])))
        lg = dict(zip(KLEIN_LINE, map(float, f[12:18])))
        e = from_package(e, labs)
        lg = from_package(lg, labs)
        rows[cid] = measure(by_id[cid], refs[cid], e, lg, float(f[19]), float(f[20]))
    for cid, _, s, _ in cases:
        if s != sig:
            rows[cid] = Outcome(exp="n/a: 3D PGA only", log="n/a: 3D PGA only")
    return version, overhead, rows


# ---------------------------------------------------------------- output

def run_text(cmd, stdin=None):
    return subprocess.run(cmd, input=stdin, capture_output=True, text=True, check=True,
                          cwd=ROOT).stdout


def commit():
    """Short hash of HEAD, "dirty" when tracked files outside book/src/generated differ (as
    examples/support/provenance.rs)."""
    try:
        h = run_text(["git", "rev-parse", "--short", "HEAD"]).strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown (not a git checkout)"
    changes = run_text(["git", "status", "--porcelain", "--untracked-files=no", "--", ".",
                        ":(exclude)book/src/generated"]).strip()
    return f"{h} dirty (uncommitted changes to tracked files)" if changes else h


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown processor"


def cell(x):
    if isinstance(x, float):
        return "0" if x == 0 else f"{x:.1e}"
    return summarise(x).replace("\t", " ")


def time_cell(t):
    if t is None:
        return "-"
    return f"{t:.0f}" if t >= 100 else f"{t:.3g}"


def main():
    write = "--write" in sys.argv[1:]
    refs = {}
    for cid, _, sig, b in CASES:
        refs[cid] = ref.reference_exp(sig, b)
        print(f"reference {cid}", file=sys.stderr)

    peers = []
    for name, runner in [("kingdon", run_kingdon), ("clifford", run_clifford),
                         ("ganja.js", run_ganja), ("klein", run_klein)]:
        print(f"running {name}", file=sys.stderr)
        version, overhead, rows = runner(CASES, refs)
        peers.append((name, version, overhead, rows))

    import numpy
    import numba
    gxx = run_text(["g++", "--version"]).splitlines()[0]
    node = run_text(["node", "--version"]).strip()
    lines = [
        "# Peer libraries' bivector exp and versor log against a high-precision reference.",
        "# Rendered with rotorflow's own errors by examples/book_peer_versors.rs into "
        "peer_versors.md.",
        "# command: python3 scripts/peer_versors.py --write (docstring: how to install the peers)",
        f"# date: {datetime.datetime.now(datetime.timezone.utc).date().isoformat()}",
        f"# commit: {commit()}",
        f"# machine: {platform.machine()}, {cpu_model()}, {os.cpu_count()} cores, "
        f"{platform.system()}",
        f"# python: {platform.python_version()} (mpmath {mpmath.__version__}, numpy "
        f"{numpy.__version__}, numba {numba.__version__})",
        f"# node: {node}",
        f"# compiler: {gxx}, {' '.join(CXXFLAGS)}",
        "# reference: exp(B) from scripts/versor_reference.py (Taylor series with scaling and "
        "squaring at 60 + 2 log10 max|B| digits, agreeing with a run at more digits to 45), "
        "21 significant digits here",
        "# exp error: max_k |exp(B)_k - V_k| / max(1, max_k |V_k|), V the reference",
        "# log error: max_k |log(exp(B))_k - B_k| / max_k |B_k|, log applied to the package's "
        "own exp(B); every B is inside the principal branch",
        "# times: microseconds per call, best of 5 repeats of a loop of at least 20 ms; "
        "overhead: the sum of two 3D PGA bivectors in the same package",
        "# rows: case id, p q r, B (mask=f64), V (mask=value), title",
        "#       peer name, version, how it was run, exp function, log function",
        "#       overhead peer, microseconds",
        "#       result peer, case id, exp error or outcome, log error or outcome, exp µs, "
        "log µs",
    ]
    for cid, title, sig, b in CASES:
        lines.append("\t".join(["case", cid, " ".join(map(str, sig)), ref.fmt_input(b),
                                ref.fmt_pairs(refs[cid], ref.OUT_DIGITS), title]))
    describe = {
        "kingdon": ("Python, float64", "MultiVector.exp", "none"),
        "clifford": ("Python, float64", "MultiVector.exp (Taylor series, scaling and squaring)",
                     "clifford.tools.log_rotor; Cl(4,1): "
                     "clifford.tools.g3c.rotor_parameterisation.general_logarithm"),
        "ganja.js": (f"node {node}, Float64Array", "Element.Exp", "Element.Log"),
        "klein": (f"C++ (headers vendored in crates.io klein-sys {KLEIN_SYS}), float32 SSE",
                  "kln::exp(line)", "kln::log(motor)"),
    }
    for name, version, overhead, rows in peers:
        how, fexp, flog = describe[name]
        lines.append("\t".join(["peer", name, version, how, fexp, flog]))
        lines.append("\t".join(["overhead", name, time_cell(overhead)]))
    for name, version, overhead, rows in peers:
        for cid, _, _, _ in CASES:
            o = rows[cid]
            lines.append("\t".join(["result", name, cid, cell(o.exp), cell(o.log),
                                    time_cell(o.exp_us), time_cell(o.log_us)]))
    text = "\n".join(lines) + "\n"
    if write:
        with open(OUTPUT, "w") as f:
            f.write(text)
        print(f"wrote {OUTPUT}", file=sys.stderr)
    else:
        sys.stdout.write(text)


if __name__ == "__main__":
    main()
