#!/usr/bin/env python3
"""High-precision reference values of exp(B) for bivectors B of Cl(p, q, r).

Writes tests/algebra/data/versor_reference.tsv (read by tests/algebra/versor_reference.rs).

Independent of rotorflow: the geometric product of Cl(p, q, r) on bit-mask blades (rotorflow's
basis order: e1 ... ep square to +1, then q to -1, then r to 0; bit i-1 is e_i) is written
here from its definition with mpmath numbers, and exp(B) is the Taylor series with scaling and
squaring: B is divided by 2^j until its coefficient 1-norm is at most 1/2, the series is summed
until the bound |B/2^j|_1^k / k! of the next term is below 10^-(digits + 10) (the 1-norm is
submultiplicative for blade products, each of which is +-1, 0 times a blade), and the sum is
squared j times. The working precision is WORK_DIGITS plus log10 of the magnitude of B (the
squarings multiply the rounding error by about |B|, and intermediate sums cancel terms as
large as |B|² for null and boost parts, so twice log10 |B| digits are added). Every value is
computed twice, at that precision and 20 + log10 |B| digits more, and the generator refuses to
write a case where the two differ by more than 1e-45 of the largest coefficient or where
V Ṽ differs from 1 by more than 1e-45 · max(1, max |V|²).

Usage: python3 scripts/versor_reference.py [--general] [OUTPUT]   (needs mpmath)
With --general it writes tests/algebra/data/versor_reference_general.tsv: the signatures with
6 <= N that are neither Euclidean nor projective (rotorflow's general route).

Each case is one line: "p q r", family, B, V, L (tab-separated). B is the input bivector as
mask=value pairs (value: the f64's shortest repr, exact); V is the reference exp(B) as
mask=value with 21 significant digits, zero coefficients omitted; L is the principal logarithm
of V expected from Multivector::log: "B" (B itself), "-" (not checked: outside the principal
branch or the input is not a versor rotorflow must take the logarithm of), or mask=value pairs.
"""

import math
import random
import sys

import mpmath
from mpmath import mp, mpf

SEED = 20261125
WORK_DIGITS = 60
CHECK_DIGITS = 45
OUT_DIGITS = 21
DEFAULT_OUTPUT = "tests/algebra/data/versor_reference.tsv"

SIGNATURES = [
    (2, 0, 1), (3, 0, 1), (4, 0, 1), (5, 0, 1),
    (4, 1, 0), (1, 3, 0), (3, 1, 0), (2, 2, 0),
    (3, 0, 0), (4, 0, 0), (5, 0, 0),
]

# With --general: the signatures above N = 5 that are neither Euclidean nor projective
# (conformal GA of 4D and 5D space, other mixed and degenerate metrics), written to
# GENERAL_OUTPUT with their own seed so that the first file does not change.
GENERAL_SIGNATURES = [
    (5, 1, 0), (4, 2, 0), (3, 3, 0), (4, 1, 1), (3, 0, 3), (6, 1, 0),
]
GENERAL_SEED = 20261126
GENERAL_OUTPUT = "tests/algebra/data/versor_reference_general.tsv"


# ---------------------------------------------------------------- the algebra

def square_of(sig, i):
    p, q, _ = sig
    return 1 if i < p else (-1 if i < p + q else 0)


def blade_product(sig, a, b):
    """(sign, mask) of e_a e_b for bit-mask blades a, b."""
    # Reordering sign: each factor of b passes the factors of a with a higher index.
    swaps = 0
    x = a >> 1
    while x:
        swaps += bin(x & b).count("1")
        x >>= 1
    sign = -1 if swaps % 2 else 1
    common = a & b
    i = 0
    while common:
        if common & 1:
            sign *= square_of(sig, i)
        common >>= 1
        i += 1
    return sign, a ^ b


_TABLES = {}


def table(sig):
    if sig not in _TABLES:
        n = sum(sig)
        _TABLES[sig] = [[blade_product(sig, a, b) for b in range(1 << n)] for a in range(1 << n)]
    return _TABLES[sig]


def gp(sig, x, y):
    """Geometric product of sparse multivectors {mask: mpf}."""
    t = table(sig)
    out = {}
    for a, ca in x.items():
        row = t[a]
        for b, cb in y.items():
            s, m = row[b]
            if s:
                out[m] = out.get(m, 0) + (ca * cb if s > 0 else -(ca * cb))
    return out


def norm1(x):
    return sum(abs(c) for c in x.values())


def mv_exp(sig, bv, digits):
    with mp.workdps(digits):
        b = {m: mpf(c) for m, c in bv.items()}
        l1 = norm1(b)
        j = 0
        while l1 > mpf(1) / 2:
            l1 /= 2
            j += 1
        scale = mpf(2) ** (-j)
        bs = {m: c * scale for m, c in b.items()}
        tol = mpf(10) ** (-(digits + 10))
        total = {0: mpf(1)}
        term = {0: mpf(1)}
        bound = mpf(1)
        k = 0
        while True:
            k += 1
            term = {m: c / k for m, c in gp(sig, term, bs).items()}
            for m, c in term.items():
                total[m] = total.get(m, 0) + c
            bound = bound * l1 / k
            if bound * l1 / (k + 1) < tol:
                break
        for _ in range(j):
            total = gp(sig, total, total)
        return {m: +c for m, c in total.items()}


def reference_exp(sig, bv):
    mag = max([abs(c) for c in bv.values()] + [1.0])
    digits = WORK_DIGITS + 2 * int(math.log10(mag)) + 5
    extra = 20 + int(math.log10(mag))
    v1 = mv_exp(sig, bv, digits)
    v2 = mv_exp(sig, bv, digits + extra)
    with mp.workdps(digits + extra):
        top = max(abs(c) for c in v2.values())
        diff = max(abs(v1.get(m, 0) - v2.get(m, 0)) for m in set(v1) | set(v2))
        assert diff <= top * mpf(10) ** (-CHECK_DIGITS), (sig, bv, diff / top)
        # V Ṽ = 1 (exp of a bivector is a versor)
        rev = {m: (c if bin(m).count("1") % 4 in (0, 1) else -c) for m, c in v2.items()}
        vv = gp(sig, v2, rev)
        vv[0] = vv.get(0, 0) - 1
        dev = max(abs(c) for c in vv.values())
        assert dev <= max(1, top * top) * mpf(10) ** (-CHECK_DIGITS), (sig, bv, dev)
    return v2


# ---------------------------------------------------------------- helpers

def n_of(sig):
    return sum(sig)


def mask(*idx):
    """Mask of e_{i1 i2 ...} with 1-based indices."""
    m = 0
    for i in idx:
        m |= 1 << (i - 1)
    return m


def bivector_masks(n):
    return [mask(i, j) for i in range(1, n + 1) for j in range(i + 1, n + 1)]


def plane_square(sig, m):
    """(e_i e_j)^2 = -e_i^2 e_j^2: -1 rotation, +1 boost, 0 null."""
    s, _ = blade_product(sig, m, m)
    return s


def rotation_planes(sig):
    return [m for m in bivector_masks(n_of(sig)) if plane_square(sig, m) == -1]


def boost_planes(sig):
    return [m for m in bivector_masks(n_of(sig)) if plane_square(sig, m) == 1]


def null_planes(sig):
    return [m for m in bivector_masks(n_of(sig)) if plane_square(sig, m) == 0]


def to_f64(bv):
    return {m: float(c) for m, c in bv.items() if float(c) != 0.0}


def conjugate(sig, r, bv, digits=80):
    """r bv r~ at high precision (r an even versor given as {mask: mpf})."""
    with mp.workdps(digits):
        rev = {m: (c if bin(m).count("1") % 4 in (0, 1) else -c) for m, c in r.items()}
        out = gp(sig, gp(sig, r, {m: mpf(c) for m, c in bv.items()}), rev)
        return {m: c for m, c in out.items() if bin(m).count("1") == 2}


def random_rotor(sig, rng, planes, size=1.0):
    """exp of a random combination of the given planes (a versor of the algebra)."""
    gen = {m: rng.uniform(-size, size) for m in planes}
    return mv_exp(sig, gen, 80)


def principal_lambdas(sig, bv):
    """Roots λ of λ² − ⟨B²⟩₀ λ + ¼ (B∧B)² = 0 (complex in general), at high precision."""
    with mp.workdps(60):
        b = {m: mpf(c) for m, c in bv.items()}
        b2 = gp(sig, b, b)
        sigma = b2.get(0, mpf(0))
        w = {m: c for m, c in b2.items() if bin(m).count("1") == 4}
        w2 = gp(sig, w, w).get(0, mpf(0)) if w else mpf(0)
        disc = mpmath.sqrt(mpmath.mpc(sigma * sigma - w2))
        return [(sigma + disc) / 2, (sigma - disc) / 2]


def inside_principal_branch(sig, bv):
    """True when every rotation angle is clearly inside the principal branch: the sum of the
    rotation angles θᵢ below π − 0.05 (the joint angles |±θ₁ ± θ₂ ± …| of V stay below π).
    For N ≤ 5 from the roots λ of the quadratic; above, from the eigenvalues of ad_B on
    vectors, which are ±2√λᵢ (and zeros), so Σ|Im| over them is 4 Σ θᵢ. Projective
    signatures above N = 5 take one rotation angle plane by plane (their own route), so only
    their Euclidean part counts there."""
    if n_of(sig) > 5:
        if sig[1] == 0 and sig[2] == 1:
            # Projective: exp(A + t e₀) = exp(A)(1 + u e₀), so the rotation angles are those
            # of the Euclidean part A (the blades without the null vector, the last one).
            p = sig[0]
            euclid = {m: c for m, c in bv.items() if not (m >> p) & 1}
            return inside_principal_branch((p, 0, 0), euclid) if p <= 5 else False
        total = sum(abs(mpmath.im(lam)) for lam in ad_eigenvalues(sig, bv)) / 4
        return total < math.pi - 0.05
    lams = principal_lambdas(sig, bv)
    total = sum(abs(mpmath.im(mpmath.sqrt(lam))) for lam in lams)
    return total < math.pi - 0.05


def ad_eigenvalues(sig, bv):
    """Eigenvalues of X ↦ BX − XB on the vectors, at 60 digits."""
    n = n_of(sig)
    with mp.workdps(60):
        b = {m: mpf(c) for m, c in bv.items()}
        a = mpmath.matrix(n, n)
        for k in range(n):
            e = {1 << k: mpf(1)}
            img = gp(sig, b, e)
            for m, c in gp(sig, e, b).items():
                img[m] = img.get(m, 0) - c
            for i in range(n):
                a[i, k] = img.get(1 << i, mpf(0))
        return mpmath.eig(a, left=False, right=False)


# ---------------------------------------------------------------- families

def fam_random(sig, rng):
    out = []
    masks = bivector_masks(n_of(sig))
    for scale in (0.3, 1.0, 3.0):
        for _ in range(4):
            out.append({m: rng.uniform(-scale, scale) for m in masks})
    return out


def fam_isoclinic(sig, rng):
    """θ(P₁ ± P₂) for two commuting rotation (or boost) planes, exact, and rotated to a
    generic position by a random versor (then isoclinic up to the f64 rounding, ~1e-16)."""
    pairs = commuting_pairs(sig)
    out = []
    for (m1, m2, kind) in pairs[:3]:
        for theta in (0.3, 1.1, 2.9 if kind == "rot" else 2.0):
            for sgn in (1, -1):
                out.append({m1: theta, m2: sgn * theta})
        rot = random_rotor(sig, rng, rotation_planes(sig) or bivector_masks(n_of(sig)), 1.0)
        out.append(to_f64(conjugate(sig, rot, {m1: 0.7, m2: 0.7})))
    return out


def commuting_pairs(sig):
    """Pairs of disjoint coordinate planes of the same kind (both rotation or both boost)."""
    out = []
    for kind, planes in (("rot", rotation_planes(sig)), ("boost", boost_planes(sig))):
        for i, a in enumerate(planes):
            for b in planes[i + 1:]:
                if a & b == 0:
                    out.append((a, b, kind))
    return out


def fam_near_isoclinic(sig, rng):
    pairs = commuting_pairs(sig)
    out = []
    for (m1, m2, kind) in pairs[:2]:
        for gap in (1e-15, 1e-12, 1e-9, 1e-6):
            theta = rng.uniform(0.2, 1.4)
            b = {m1: theta, m2: theta * (1 + gap)}
            out.append(b)
            rot = random_rotor(sig, rng, rotation_planes(sig), 1.0)
            out.append(to_f64(conjugate(sig, rot, b)))
    return out


def fam_translation(sig, rng):
    """Pure translations of projective GA: Σ tᵢ eᵢ∧e₀ with e₀ the null vector."""
    out = []
    nulls = null_planes(sig)
    for mag in (1e-200, 1e-8, 0.5, 3.0, 1e5, 1e150):
        out.append({m: mag * rng.uniform(-1, 1) for m in nulls})
    # a translation along one axis, exact
    out.append({nulls[0]: 2.5})
    return out


def fam_light_like(sig, rng):
    """Null bivectors (k ∧ u with k light-like, u ⊥ k): B² = 0, exp(B) = 1 + B."""
    p, q, _ = sig
    n = n_of(sig)
    # a null vector k = e_t + e_s with e_t² = −e_s², and u any other basis vector
    if p == 1:
        t, spaces = 1, list(range(2, n + 1))
    else:
        t, spaces = n, list(range(1, n))
    out = []
    for s in spaces:
        for u in spaces:
            if u == s:
                continue
            mag = rng.choice([1e-200, 1e-3, 0.7, 4.0, 1e6, 1e150])
            c = mag * rng.choice([1, -1])
            # (e_t + e_s) ∧ e_u = e_t∧e_u + e_s∧e_u (signs of the masks: ascending order)
            b = {}
            b[mask(min(t, u), max(t, u))] = c if t < u else -c
            b[mask(min(s, u), max(s, u))] = c if s < u else -c
            out.append(b)
    # generic position (null up to the f64 rounding)
    for _ in range(4):
        b = out[rng.randrange(len(out))]
        b = {m: c / max(abs(x) for x in b.values()) for m, c in b.items()}
        rot = random_rotor(sig, rng, bivector_masks(n), 0.5)
        out.append(to_f64(conjugate(sig, rot, b)))
    return out[:16]


def fam_rapidity(sig, rng):
    """Boosts of rapidity φ up to 20, alone, with a commuting rotation, in generic planes."""
    out = []
    boosts = boost_planes(sig)
    rots = rotation_planes(sig)
    for phi in (0.5, 2.0, 7.0, 13.0, 20.0):
        m = boosts[rng.randrange(len(boosts))]
        out.append({m: phi * rng.choice([1, -1])})
        commuting = [r for r in rots if r & m == 0]
        if commuting:
            out.append({m: phi, commuting[0]: rng.uniform(-3, 3)})
        # a generic boost direction: rotated by a random rotation (keeps the rapidity)
        if rots:
            rot = random_rotor(sig, rng, rots, 2.0)
            out.append(to_f64(conjugate(sig, rot, {m: phi})))
    return out


def fam_near_pi(sig, rng):
    """Rotations by π ± 1e-12 (and ± 1e-9) in a coordinate and a generic rotation plane."""
    out = []
    rots = rotation_planes(sig)
    for delta in (1e-12, -1e-12, 1e-9, -1e-9):
        theta = math.pi + delta
        m = rots[rng.randrange(len(rots))]
        out.append({m: theta})
        if len(rots) > 1:
            rot = random_rotor(sig, rng, rots, 2.0)
            b = to_f64(conjugate(sig, rot, {m: 1.0}))
            with mp.workdps(60):
                norm = mpmath.sqrt(sum(mpf(c) ** 2 for c in b.values()))
                out.append({k: float(mpf(c) * mpf(theta) / norm) for k, c in b.items()})
    return out


def fam_magnitude(sig, rng):
    """Random bivectors of magnitude 1e-200 … 1e150. Above 1 only the rotation and null
    planes (a boost of such rapidity overflows f64)."""
    out = []
    masks = bivector_masks(n_of(sig))
    bounded = [m for m in masks if plane_square(sig, m) <= 0]
    for mag in (1e-200, 1e-100, 1e-20, 1e-8, 1e8, 1e20, 1e100, 1e150):
        use = masks if mag < 1 else bounded
        out.append({m: mag * rng.uniform(-1, 1) for m in use})
    return out


def families(sig):
    p, q, r = sig
    fams = [("random", fam_random), ("magnitude", fam_magnitude), ("near_pi", fam_near_pi)]
    if commuting_pairs(sig):
        fams += [("isoclinic", fam_isoclinic), ("near_isoclinic", fam_near_isoclinic)]
    if r == 1:
        fams.append(("translation", fam_translation))
    if (p, q, r) in ((1, 3, 0), (3, 1, 0)) or (n_of(sig) > 5 and r == 0 and 1 in (p, q)):
        fams.append(("light_like", fam_light_like))
    if boost_planes(sig):
        fams.append(("rapidity", fam_rapidity))
    return fams


# ---------------------------------------------------------------- logarithm targets

def log_target(sig, fam, bv):
    if fam == "near_pi":
        with mp.workdps(60):
            norm = mpmath.sqrt(sum(mpf(c) ** 2 for c in bv.values()))
            if norm <= mpmath.pi:
                return "B"
            # simple rotation beyond π: the principal one turns the other way by 2π − θ
            f = 1 - 2 * mpmath.pi / norm
            return fmt_pairs({m: mpf(c) * f for m, c in bv.items()}, OUT_DIGITS)
    return "B" if inside_principal_branch(sig, bv) else "-"


# ---------------------------------------------------------------- output

def fmt_pairs(x, digits):
    items = []
    for m in sorted(x):
        c = x[m]
        if c == 0:
            continue
        items.append(f"{m}={mpmath.nstr(c, digits, min_fixed=1, max_fixed=0)}")
    return ",".join(items) if items else "0=0"


def fmt_input(bv):
    return ",".join(f"{m}={repr(float(c))}" for m, c in sorted(bv.items())) or "0=0.0"


def main():
    args = sys.argv[1:]
    general = "--general" in args
    args = [a for a in args if a != "--general"]
    out_path = args[0] if args else (GENERAL_OUTPUT if general else DEFAULT_OUTPUT)
    rng = random.Random(GENERAL_SEED if general else SEED)
    lines = []
    for sig in GENERAL_SIGNATURES if general else SIGNATURES:
        for fam, gen in families(sig):
            for bv in gen(sig, rng):
                bv = {m: float(c) for m, c in bv.items() if float(c) != 0.0}
                v = reference_exp(sig, bv)
                lines.append("\t".join([
                    " ".join(map(str, sig)), fam, fmt_input(bv), fmt_pairs(v, OUT_DIGITS),
                    log_target(sig, fam, bv)]))
        print(f"Cl{sig}: {len(lines)} cases so far", file=sys.stderr)
    flag = " --general" if general else ""
    header = [
        "# exp(B) of bivectors of Cl(p, q, r) at high precision: reference values for",
        "# tests/algebra/versor_reference.rs. Generated by",
        f"#   python3 scripts/versor_reference.py{flag} {out_path}",
        f"# Python {sys.version.split()[0]}, mpmath {mpmath.__version__}, "
        f"seed {GENERAL_SEED if general else SEED}, working "
        f"precision {WORK_DIGITS} + 2 log10 max|B| digits;",
        f"# recomputed with 20 + log10 max|B| digits more: the two agree to {CHECK_DIGITS} digits "
        f"and V Ṽ = 1 to {CHECK_DIGITS} digits.",
        f"# Values to {OUT_DIGITS} significant digits.",
        "# Columns (tab-separated): p q r, family, B (mask=f64), exp(B) (mask=value),",
        "# principal log expected (B: B itself; -: not checked; else mask=value).",
    ]
    with open(out_path, "w") as f:
        f.write("\n".join(header + lines) + "\n")
    print(f"{len(lines)} cases written to {out_path}", file=sys.stderr)


if __name__ == "__main__":
    main()
