#!/usr/bin/env python3
"""Times and checks the bivector exponential of two Python geometric-algebra packages,
kingdon and clifford, on the cases of `benches/versors.rs`.

Usage: pip install kingdon clifford; scripts/peer_versors.py

Cases:
- a 3D PGA screw (rotation and translation not commuting as one simple bivector), and a
  simple 3D PGA bivector (a rotation about a line off the origin, B² a scalar);
- the isoclinic Cl(4, 0, 0) bivector 0.7 e₁₂ + 0.7 e₃₄ and the near-isoclinic
  0.7 e₁₂ + (0.7 + 10⁻¹²) e₃₄.

Reference values are closed forms in double precision: for a Cl(4, 0, 0) bivector
a e₁₂ + b e₃₄, exp = (cos a + sin a e₁₂)(cos b + sin b e₃₄) (the two planes commute); for
3D PGA, the formula klein and ganja.js use (the same as `pga_exp` in `benches/versors.rs`,
whose setup asserts agreement with rotorflow's `Multivector::exp` to 1e-14).

Each package's call overhead is stated by timing a trivial call in the same package (the
sum of two bivectors). Per-call times are the best of several repeats of a timing loop.
These numbers describe the packages as installed here, not a property of their methods.
"""

import math
import timeit

import numpy as np


def best_time(f, number=2000, repeat=5):
    """Best per-call time of f() in microseconds."""
    return min(timeit.repeat(f, number=number, repeat=repeat)) / number * 1e6


def pga_exp(b):
    """exp of [e12, e13, e23, e14, e24, e34] in Cl(3, 0, 1), e4 null (rotorflow's order);
    returns {blade: coefficient} with blades named in that order."""
    a12, a13, a23, t14, t24, t34 = b
    theta2 = a12 * a12 + a13 * a13 + a23 * a23
    theta = math.sqrt(theta2)
    s, c = math.sin(theta), math.cos(theta)
    sc = s / theta
    p = 2.0 * (a12 * t34 - a13 * t24 + a23 * t14)
    alpha = -p / (2.0 * theta2)
    k = alpha * (c - sc)
    return {
        "1": c,
        "e12": sc * a12,
        "e13": sc * a13,
        "e23": sc * a23,
        "e14": sc * t14 - k * a23,
        "e24": sc * t24 + k * a13,
        "e34": sc * t34 - k * a12,
        "e1234": -alpha * theta * s,
    }


def cl4_exp(a, b):
    """exp(a e12 + b e34) in Cl(4, 0, 0)."""
    return {
        "1": math.cos(a) * math.cos(b),
        "e12": math.sin(a) * math.cos(b),
        "e34": math.cos(a) * math.sin(b),
        "e1234": math.sin(a) * math.sin(b),
    }


# Blade names of rotorflow's order (e4 the null vector of PGA) in each package, with the
# sign of the reordering. kingdon's PGA has the null vector e0 first, clifford's Cl(3, 0, 1)
# has it as e1 (sig [0, 1, 1, 1]).
KINGDON_PGA = {
    "1": ("e", 1), "e12": ("e12", 1), "e13": ("e13", 1), "e23": ("e23", 1),
    "e14": ("e01", -1), "e24": ("e02", -1), "e34": ("e03", -1), "e1234": ("e0123", -1),
}
CLIFFORD_PGA = {
    "1": ("", 1), "e12": ("e23", 1), "e13": ("e24", 1), "e23": ("e34", 1),
    "e14": ("e12", -1), "e24": ("e13", -1), "e34": ("e14", -1), "e1234": ("e1234", -1),
}
SAME4 = {k: (("" if k == "1" else k), 1) for k in ["1", "e12", "e34", "e1234"]}


def max_error(expected, get):
    return max(abs(get(k) - v) for k, v in expected.items())


def kingdon_cases():
    from kingdon import Algebra

    out = []
    pga = Algebra(3, 0, 1)
    cl4 = Algebra(4, 0, 0)

    def kget(mv, table):
        def get(k):
            name, sign = table[k]
            if name == "e":
                return sign * mv.e
            return sign * getattr(mv, name, 0.0)
        return get

    def pga_biv(b):
        # rotorflow e_i e4 = −kingdon e0i
        return pga.bivector(e12=b[0], e13=b[1], e23=b[2], e01=-b[3], e02=-b[4], e03=-b[5])

    x = pga_biv([0.4, -0.7, 0.6, 1.3, -0.8, 2.1])
    y = pga_biv([0.1, 0.2, 0.3, 0.0, 0.0, 0.0])
    out.append(("call overhead (bivector sum)", best_time(lambda: x + y), "-"))
    cases = [
        ("PGA screw", [0.4, -0.7, 0.6, 1.3, -0.8, 2.1]),
        # A rotation about the e3 axis through (0, 1, 0): A∧T = 0, B² scalar.
        ("PGA simple (line off origin)", [0.4, 0.0, 0.0, 0.4, 0.0, 0.0]),
    ]
    for name, b in cases:
        mv = pga_biv(b)
        out.append(run(name, lambda mv=mv: mv.exp(), pga_exp(b),
                       lambda r: kget(r, KINGDON_PGA)))
    for name, (a, bb) in [("Cl(4) isoclinic", (0.7, 0.7)),
                          ("Cl(4) near-isoclinic 1e-12", (0.7, 0.7 + 1e-12))]:
        mv = cl4.bivector(e12=a, e34=bb)
        out.append(run(name, lambda mv=mv: mv.exp(), cl4_exp(a, bb),
                       lambda r: kget(r, SAME4)))
    return out


def clifford_cases():
    import clifford

    out = []
    pl, pb = clifford.Cl(3, 0, 1)  # e1 null
    cl, cb = clifford.Cl(4)

    def pga_biv(b):
        return (b[0] * pb["e23"] + b[1] * pb["e24"] + b[2] * pb["e34"]
                - b[3] * pb["e12"] - b[4] * pb["e13"] - b[5] * pb["e14"])

    def coeff(mv, layout, name, sign):
        i = layout.bladeTupList.index(tuple(int(c) for c in name[1:])) if name else 0
        return sign * mv.value[i]

    def get_for(mv, layout, table):
        return lambda k: coeff(mv, layout, *table[k])

    x = pga_biv([0.4, -0.7, 0.6, 1.3, -0.8, 2.1])
    y = pga_biv([0.1, 0.2, 0.3, 0.0, 0.0, 0.0])
    out.append(("call overhead (bivector sum)", best_time(lambda: x + y), "-"))
    x.exp()  # numba compilation on the first call
    for name, b in [("PGA screw", [0.4, -0.7, 0.6, 1.3, -0.8, 2.1]),
                    ("PGA simple (line off origin)", [0.4, 0.0, 0.0, 0.4, 0.0, 0.0])]:
        mv = pga_biv(b)
        out.append(run(name, lambda mv=mv: mv.exp(), pga_exp(b),
                       lambda r: get_for(r, pl, CLIFFORD_PGA)))
    for name, (a, bb) in [("Cl(4) isoclinic", (0.7, 0.7)),
                          ("Cl(4) near-isoclinic 1e-12", (0.7, 0.7 + 1e-12))]:
        mv = a * cb["e12"] + bb * cb["e34"]
        mv.exp()
        out.append(run(name, lambda mv=mv: mv.exp(), cl4_exp(a, bb),
                       lambda r: get_for(r, cl, SAME4)))
    return out


def run(name, f, expected, getter):
    try:
        r = f()
    except Exception as e:  # report, do not stop
        return (name, float("nan"), f"{type(e).__name__}: {e}")
    err = max_error(expected, getter(r))
    if not np.isfinite(err):
        return (name, best_time(f), "non-finite result")
    return (name, best_time(f), f"max abs error {err:.1e}")


def main():
    for pkg, cases in [("kingdon", kingdon_cases), ("clifford", clifford_cases)]:
        try:
            rows = cases()
        except ImportError as e:
            print(f"{pkg}: not installed ({e})")
            continue
        print(pkg)
        for name, t, result in rows:
            ts = "   -    " if math.isnan(t) else f"{t:8.2f} µs"
            print(f"  {name:32s} {ts}  {result}")


if __name__ == "__main__":
    main()
