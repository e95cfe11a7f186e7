"""Shared helpers of the tests: an independent reference of the Clifford product."""

import itertools

import numpy as np


def reorder_sign(a: int, b: int) -> float:
    """The sign of e_a e_b brought to canonical order (count of swaps)."""
    a >>= 1
    swaps = 0
    while a:
        swaps += bin(a & b).count("1")
        a >>= 1
    return -1.0 if swaps % 2 else 1.0


def metric(sig, blade: int) -> float:
    """The product of the squares of the basis vectors of `blade` in Cl(p, q, r)."""
    p, q, r = sig
    out = 1.0
    for i in range(p + q + r):
        if blade >> i & 1:
            out *= 1.0 if i < p else (-1.0 if i < p + q else 0.0)
    return out


def reference_product(sig, a, b, keep=lambda ga, gb, gc: True):
    """The product of coefficient arrays a and b by the textbook rule on basis blades,
    keeping the pairs `keep(grade a, grade b, grade result)` accepts."""
    n = sum(sig)
    out = np.zeros(1 << n)
    for i, j in itertools.product(range(1 << n), repeat=2):
        if a[i] == 0.0 or b[j] == 0.0:
            continue
        k = i ^ j
        if not keep(bin(i).count("1"), bin(j).count("1"), bin(k).count("1")):
            continue
        out[k] += a[i] * b[j] * reorder_sign(i, j) * metric(sig, i & j)
    return out


def left_multiplication(sig, a):
    """The 2^N x 2^N matrix of x -> a x."""
    n = sum(sig)
    size = 1 << n
    m = np.zeros((size, size))
    for j in range(size):
        e = np.zeros(size)
        e[j] = 1.0
        m[:, j] = reference_product(sig, a, e)
    return m
