"""The same cases in kingdon and clifford, where they are installed (optional: the tests of
this file are reported as skipped without them)."""

import numpy as np
import pytest

import rotorflow as rf

# Signatures without null vectors: kingdon puts a null vector first (e0), rotorflow last.
SIGNATURES = [(3, 0, 0), (4, 0, 0), (2, 1, 0), (4, 1, 0)]
RNG = np.random.default_rng(11)


def cases(sig, count=5):
    size = 1 << sum(sig)
    return [(RNG.normal(size=size), RNG.normal(size=size)) for _ in range(count)]


@pytest.mark.parametrize("sig", SIGNATURES)
def test_products_equal_kingdon(sig):
    kingdon = pytest.importorskip("kingdon")
    alg = rf.Algebra(*sig)
    kalg = kingdon.Algebra(*sig)
    keys = tuple(range(len(alg)))
    for a, b in cases(sig):
        ka = kalg.multivector(values=a, keys=keys)
        kb = kalg.multivector(values=b, keys=keys)
        A, B = alg.multivector(a), alg.multivector(b)
        for ours, theirs in [(A * B, ka * kb), (A ^ B, ka ^ kb), (A | B, ka | kb), (~A, ~ka)]:
            got = np.zeros(len(alg))
            for key, value in zip(theirs.keys(), theirs.values()):
                got[key] = value
            np.testing.assert_allclose(ours.coefficients, got, atol=1e-12)


def clifford_order(layout):
    return [sum(1 << (i - 1) for i in blade) for blade in layout.bladeTupList]


@pytest.mark.parametrize("sig", [(3, 0, 0), (4, 0, 0), (4, 1, 0)])
def test_products_equal_clifford(sig):
    clifford = pytest.importorskip("clifford")
    p, q, _ = sig
    layout, _ = clifford.Cl(p, q)
    order = clifford_order(layout)
    alg = rf.Algebra(*sig)
    for a, b in cases(sig):
        ca, cb = layout.MultiVector(a[order]), layout.MultiVector(b[order])
        A, B = alg.multivector(a), alg.multivector(b)
        for ours, theirs in [(A * B, ca * cb), (A ^ B, ca ^ cb), (~A, ~ca)]:
            np.testing.assert_allclose(ours.coefficients[order], theirs.value, atol=1e-12)


@pytest.mark.parametrize("n", [3, 4, 5])
def test_simple_bivector_exponential_equals_kingdon_and_clifford(n):
    # A simple bivector (one plane): both libraries have a closed form for it. Small integers
    # keep B B exactly scalar, which kingdon checks without a tolerance.
    alg = rf.Algebra(n)
    u, v = RNG.integers(-3, 4, size=n) * 0.25, RNG.integers(-3, 4, size=n) * 0.25
    b = alg.vector(u) ^ alg.vector(v)
    ours = b.exp().coefficients
    checked = 0
    kingdon = pytest.importorskip("kingdon")
    kalg = kingdon.Algebra(n)
    kb = kalg.vector(u) ^ kalg.vector(v)
    kexp = kb.exp()
    got = np.zeros(len(alg))
    for key, value in zip(kexp.keys(), kexp.values()):
        got[key] = value
    np.testing.assert_allclose(ours, got, atol=1e-13)
    checked += 1
    clifford = pytest.importorskip("clifford")
    layout, _ = clifford.Cl(n)
    order = clifford_order(layout)
    cexp = layout.MultiVector(b.coefficients[order]).exp()
    np.testing.assert_allclose(ours[order], cexp.value, atol=1e-13)
    checked += 1
    assert checked == 2
