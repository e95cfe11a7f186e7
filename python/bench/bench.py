"""Times the Python package beside numpy, scipy's Rotation, kingdon and clifford.

One run prints a Markdown table and, with ``--output FILE``, writes it there (the book's
"From Python" chapter includes ``book/src/generated/python_bench.md``). kingdon and clifford
are timed where they are installed; the table says which were.

    python3 python/bench/bench.py --output book/src/generated/python_bench.md
    python3 python/bench/bench.py --quick      # fewer repetitions, same cases
"""

import argparse
import datetime
import importlib
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import scipy
import scipy.linalg
from scipy.spatial.transform import Rotation

import rotorflow as rf

ROOT = Path(__file__).resolve().parents[2]


def best(fn, repeat, number):
    """The best time of `repeat` runs of `number` calls, per call (seconds)."""
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(number):
            fn()
        times.append((time.perf_counter() - t0) / number)
    return min(times)


def optional(name):
    try:
        return importlib.import_module(name)
    except ImportError:
        return None


def blade_masks(n, grade):
    return [m for m in range(1 << n) if bin(m).count("1") == grade]


def left_multiplication(alg, b):
    """2^N x 2^N matrix of x -> b x, built from rotorflow's own products of basis blades; the
    reference exponential is scipy's expm of it (scaling and squaring)."""
    size = len(alg)
    eye = np.eye(size)
    return alg.product(b, eye).T


def clifford_order(layout):
    """For each of clifford's blades (ordered by grade), its bit mask in rotorflow's order."""
    return [sum(1 << (i - 1) for i in blade) for blade in layout.bladeTupList]


def fmt_time(seconds):
    if seconds < 1e-6:
        return f"{seconds * 1e9:.0f} ns"
    if seconds < 1e-3:
        return f"{seconds * 1e6:.2f} µs"
    return f"{seconds * 1e3:.2f} ms"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", type=Path)
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    repeat = 3 if args.quick else 7
    load = os.getloadavg()[0]
    kingdon = optional("kingdon")
    clifford = optional("clifford")
    rng = np.random.default_rng(20261129)
    rows = []  # (operation, rotorflow, other, other's time, ratio, note)
    ceilings = []  # (operation, rotorflow, kingdon's time, memory floor of the arrays)

    def row(op, ours, other=None, theirs=None, note=""):
        ratio = f"{theirs / ours:.1f}×" if theirs else ""
        rows.append((op, fmt_time(ours), other or "", fmt_time(theirs) if theirs else "", ratio, note))

    # --- single calls from Python --------------------------------------------------------
    a3 = rf.Algebra(3)
    x, y = (a3.multivector(rng.normal(size=8)) for _ in range(2))
    t_gp = best(lambda: x * y, repeat, 20000)
    r = a3.bivector([0.3, -0.2, 0.5]).exp()
    v = a3.vector([1.0, 2.0, 3.0])
    t_sw = best(lambda: r.sandwich(v), repeat, 20000)
    if kingdon:
        ka = kingdon.Algebra(3)
        kx = ka.multivector(values=x.coefficients, keys=tuple(range(8)))
        ky = ka.multivector(values=y.coefficients, keys=tuple(range(8)))
        row("one geometric product, 3D, full multivectors", t_gp, "kingdon", best(lambda: kx * ky, repeat, 20000))
        kr = ka.bivector([0.3, -0.2, 0.5]).exp()
        kv = ka.vector([1.0, 2.0, 3.0])
        row("one sandwich R v R̃, 3D", t_sw, "kingdon", best(lambda: kr >> kv, repeat, 20000))
    else:
        row("one geometric product, 3D, full multivectors", t_gp)
        row("one sandwich R v R̃, 3D", t_sw)
    if clifford:
        layout, blades = clifford.Cl(3)
        cx = layout.MultiVector(x.coefficients[clifford_order(layout)])
        cy = layout.MultiVector(y.coefficients[clifford_order(layout)])
        row("one geometric product, 3D, full multivectors", t_gp, "clifford", best(lambda: cx * cy, repeat, 20000))
        cr = (0.3 * blades["e12"] - 0.2 * blades["e13"] + 0.5 * blades["e23"]).exp()
        cv = 1.0 * blades["e1"] + 2.0 * blades["e2"] + 3.0 * blades["e3"]
        row("one sandwich R v R̃, 3D", t_sw, "clifford", best(lambda: cr * cv * ~cr, repeat, 20000))
    r3 = rf.Rotor3.from_rotvec([0.1, 0.2, 0.3])
    s3 = Rotation.from_rotvec([0.1, 0.2, 0.3])
    p = np.array([1.0, 2.0, 3.0])
    row("one vector rotation, Rotor3.apply vs Rotation.apply", best(lambda: r3.apply(p), repeat, 20000), "scipy", best(lambda: s3.apply(p), repeat, 20000))

    # --- 10^6 vector rotations ------------------------------------------------------------
    m = 1_000_000
    pts = rng.normal(size=(m, 3))
    t_ours = best(lambda: r3.apply(pts), repeat, 3)
    row("10⁶ 3D vectors, one rotation", t_ours, "scipy", best(lambda: s3.apply(pts), repeat, 3))
    mat = s3.as_matrix()
    row("10⁶ 3D vectors, one rotation", t_ours, "numpy `pts @ Q.T`", best(lambda: pts @ mat.T, repeat, 3))
    many = rng.normal(size=(m, 3))
    r_many = rf.Rotor3.from_rotvec(many)
    s_many = Rotation.from_rotvec(many)
    row("10⁶ 3D vectors, 10⁶ rotations", best(lambda: r_many.apply(pts), repeat, 3), "scipy", best(lambda: s_many.apply(pts), repeat, 3))
    row("compose 10⁶ rotations", best(lambda: r_many * r_many, repeat, 3), "scipy", best(lambda: s_many * s_many, repeat, 3))

    # --- batched products and sandwiches ------------------------------------------------
    # Per element over 10^5 elements, on one core (the kernels use one thread). numpy's own
    # `a + b` on the same arrays reads and writes as much memory as a product does: the floor
    # that memory traffic alone sets. Where a library reads and writes other arrays (kingdon
    # keeps only the non-zero blades of a rotor and a vector), its floor is the bytes of those
    # arrays at the rate of that `a + b`.
    m = 100_000
    rate = None  # seconds per byte read or written by the last `a + b`

    def floor_row(label, ours, what, doubles_in, doubles_out):
        t = rate * 8 * (doubles_in + doubles_out)
        row(label, ours, f"memory floor of {what} ({doubles_in} numbers in, {doubles_out} out)", t)

    for n in (3, 4):
        k = 1 << n
        alg = rf.Algebra(n)
        aa, bb = rng.normal(size=(m, k)), rng.normal(size=(m, k))
        label = f"10⁵ geometric products, {n}D (per element)"
        t_batch = best(lambda: alg.product(aa, bb), repeat, 1) / m
        if kingdon:
            ka = kingdon.Algebra(n)
            kaa = ka.multivector(values=aa.T.copy(), keys=tuple(range(k)))
            kbb = ka.multivector(values=bb.T.copy(), keys=tuple(range(k)))
            kaa * kbb  # generate the code once
            t_k = best(lambda: kaa * kbb, repeat, 1) / m
            row(label, t_batch, "kingdon (numpy arrays)", t_k)
        else:
            t_k = None
            row(label, t_batch)
        if clifford and n == 3:
            layout, _ = clifford.Cl(3)
            order = clifford_order(layout)
            c = 10_000
            cl = [(layout.MultiVector(aa[i][order]), layout.MultiVector(bb[i][order])) for i in range(c)]
            row(label, t_batch, "clifford (loop over 10⁴)", best(lambda: [u * w for u, w in cl], repeat, 1) / c)
        t_floor = best(lambda: aa + bb, repeat, 1) / m
        row(label, t_batch, "numpy `a + b` (memory floor)", t_floor)
        if t_k:
            ceilings.append((label, t_batch, t_k, t_floor))

    # 10^5 rotors applied to 10^5 vectors, 3D and 4D: R v R̃ (rotorflow runs even versors on
    # vectors through a kernel of their non-zero coefficients, as kingdon's generated code does).
    compact = {3: rf.Rotor3, 4: rf.Rotor4}
    for n in (3, 4):
        k = 1 << n
        alg = rf.Algebra(n)
        even = [b for b in range(k) if bin(b).count("1") % 2 == 0]
        odd = blade_masks(n, 1)
        # Rotors R = exp(−Θ/2) of random rotation bivectors Θ (components 12, 13, 23 in 3D;
        # 12, 13, 14, 23, 24, 34 in 4D, the order of `Rotor{n}.from_bivector`).
        planes = [3, 5, 6] if n == 3 else [3, 5, 9, 6, 10, 12]
        theta = rng.normal(size=(m, len(planes)))
        half = np.zeros((m, k))
        half[:, planes] = -0.5 * theta
        rot = alg.exp(half)
        q = rot[:, even]
        vecs = rng.normal(size=(m, n))
        vec = np.zeros((m, k))
        vec[:, odd] = vecs
        label = f"10⁵ sandwiches R v R̃, {n}D (per element)"
        t_sw = best(lambda: alg.sandwich(rot, vec), repeat, 1) / m
        # The same rotors as rotorflow's fixed-size rotors (a quaternion, a quaternion pair),
        # applied to (M, N) arrays of vectors: the compact layout, beside kingdon's.
        fixed = compact[n].from_bivector(theta)
        turned = fixed.apply(vecs)
        np.testing.assert_allclose(turned, alg.sandwich(rot, vec)[:, odd], atol=1e-12)
        t_fixed = best(lambda: fixed.apply(vecs), repeat, 1) / m
        compact_label = f"10⁵ rotations, {n}D, `Rotor{n}.apply` on (M, {n}) (per element)"
        if kingdon:
            ka = kingdon.Algebra(n)
            kr = ka.multivector(values=q.T.copy(), keys=tuple(even))
            kv = ka.multivector(values=vecs.T.copy(), keys=tuple(odd))
            kout = kr >> kv  # generate the code once
            assert tuple(kout.keys()) == tuple(odd)
            np.testing.assert_allclose(np.asarray(kout.values()).T, turned, atol=1e-12)
            t_k = best(lambda: kr >> kv, repeat, 1) / m
            row(label, t_sw, "kingdon (numpy arrays)", t_k)
            row(compact_label, t_fixed, "kingdon (numpy arrays)", t_k)
        else:
            row(label, t_sw)
            row(compact_label, t_fixed)
        if clifford and n == 3:
            layout, _ = clifford.Cl(3)
            order = clifford_order(layout)
            c = 10_000
            cl = [(layout.MultiVector(rot[i][order]), layout.MultiVector(vec[i][order])) for i in range(c)]
            row(label, t_sw, "clifford (loop over 10⁴)", best(lambda: [r * v * ~r for r, v in cl], repeat, 1) / c)
        t_floor = best(lambda: rot + vec, repeat, 1) / m
        rate = t_floor / (3 * k * 8)
        row(label, t_sw, "numpy `a + b` (memory floor)", t_floor)
        # kingdon reads the rotors' even blades and the vectors and writes vectors; a Rotor3
        # holds 4 numbers and a Rotor4 8, as many as the even blades.
        floor_row(label, t_sw, "kingdon's arrays", len(even) + n, n)
        floor_row(compact_label, t_fixed, "kingdon's and `Rotor{n}.apply`'s arrays".format(n=n), len(even) + n, n)
        if kingdon:
            ceilings.append((compact_label, t_fixed, t_k, rate * 8 * (len(even) + 2 * n)))

    # --- batched exp of bivectors, N = 4 ... 8 --------------------------------------------
    exp_rows = []
    for n in range(4, 9):
        alg = rf.Algebra(n)
        count = 100_000 if not args.quick else 20_000
        biv = np.zeros((count, 1 << n))
        masks = blade_masks(n, 2)
        biv[:, masks] = rng.normal(size=(count, len(masks)))
        t_ours = best(lambda: alg.exp(biv), max(2, repeat // 2), 1) / count
        # Accuracy on 20 non-simple bivectors against scipy's expm of the 2^N x 2^N matrix.
        sample = biv[:20]
        ref = np.stack([scipy.linalg.expm(left_multiplication(alg, b))[:, 0] for b in sample])
        err_ours = np.abs(alg.exp(sample) - ref).max()
        note_k, t_k, err_k = "", None, None
        if kingdon:
            ka = kingdon.Algebra(n)
            kb = ka.multivector(values=sample[0], keys=tuple(range(1 << n)))
            try:
                kb.exp()
                note_k = "accepted"
            except NotImplementedError:
                note_k = "refuses non-simple bivectors"
        t_c, err_c = None, None
        if clifford:
            layout, _ = clifford.Cl(n)
            order = clifford_order(layout)
            k = 1000 if n <= 6 else 200
            cl = [layout.MultiVector(biv[i][order]) for i in range(k)]
            t_c = best(lambda: [c.exp() for c in cl], 1, 1) / k
            err_c = max(np.abs(layout.MultiVector(b[order]).exp().value - e[order]).max() for b, e in zip(sample, ref))
        exp_rows.append((n, t_ours, err_ours, t_c, err_c, note_k))

    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    lines = [
        f"Measured at commit `{commit}` on {datetime.date.today().isoformat()} by `python3 python/bench/bench.py`",
        f"(Python {platform.python_version()}, numpy {np.__version__}, scipy {scipy.__version__}, "
        f"kingdon {getattr(kingdon, '__version__', 'installed') if kingdon else 'not installed'}, "
        f"clifford {clifford.__version__ if clifford else 'not installed'}; {os.cpu_count()} cores, "
        f"{platform.machine()}, load average {load:.1f} at the start). Best of {repeat} "
        "runs; ratio = other's time / rotorflow's. Every rotorflow call runs on one core, except",
        "one rotation of many vectors (2¹⁶ or more per core), whose rows are split over the cores",
        "as scipy's BLAS product splits them.",
        "",
        "| operation | rotorflow | other | other's time | ratio |",
        "|---|---:|---|---:|---:|",
    ]
    for op, ours, other, theirs, ratio, _ in rows:
        lines.append(f"| {op} | {ours} | {other} | {theirs} | {ratio} |")
    if ceilings:
        lines += [
            "",
            "No code runs much faster than the memory traffic of its arrays, so the ratio to kingdon",
            "on the same arrays can reach about kingdon's time over their memory floor (the time of",
            "numpy's `a + b` per byte, times the bytes the operation reads and writes; a kernel that",
            "streams its arrays well can beat that estimate by a little):",
            "",
            "| operation | rotorflow | kingdon | ratio | ratio at the memory floor (kingdon / floor) |",
            "|---|---:|---:|---:|---:|",
        ]
        for op, ours, theirs, floor in ceilings:
            lines.append(f"| {op} | {fmt_time(ours)} | {fmt_time(theirs)} | {theirs / ours:.1f}× | {theirs / floor:.1f}× |")
    lines += [
        "",
        "Batched exponential of random (non-simple) bivectors, per element, and the largest error",
        "against scipy's `expm` of the 2ᴺ × 2ᴺ left-multiplication matrix on 20 of them:",
        "",
        "| N | rotorflow | max error | clifford (loop) | max error | ratio | kingdon |",
        "|---:|---:|---:|---:|---:|---:|---|",
    ]
    for n, t_ours, e_ours, t_c, e_c, note_k in exp_rows:
        c_time = fmt_time(t_c) if t_c else "—"
        c_err = f"{e_c:.1e}" if e_c is not None else "—"
        ratio = f"{t_c / t_ours:.0f}×" if t_c else "—"
        lines.append(f"| {n} | {fmt_time(t_ours)} | {e_ours:.1e} | {c_time} | {c_err} | {ratio} | {note_k or '—'} |")
    text = "\n".join(lines) + "\n"
    print(text)
    if args.output:
        args.output.write_text(text, encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
