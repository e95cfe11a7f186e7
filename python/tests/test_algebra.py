"""Algebra and Multivector against an independent reference product, scipy's matrix
exponential, and algebraic identities (hypothesis)."""

import math

import numpy as np
import pytest
import scipy.linalg
from hypothesis import given, settings
from hypothesis import strategies as st

import rotorflow as rf
from conftest import left_multiplication, reference_product

SIGNATURES = [(3, 0, 0), (2, 1, 0), (3, 0, 1), (4, 1, 0), (1, 3, 0), (4, 0, 0), (2, 0, 2)]


def coefficients(size):
    return st.lists(
        st.floats(-10, 10, allow_nan=False, allow_infinity=False), min_size=size, max_size=size
    ).map(np.array)


def grade_of(k):
    return bin(k).count("1")


@pytest.mark.parametrize("sig", SIGNATURES)
def test_basis_vectors_square_to_the_metric(sig):
    alg = rf.Algebra(*sig)
    p, q, r = sig
    expected = [1.0] * p + [-1.0] * q + [0.0] * r
    for i, s in enumerate(expected):
        e = alg.basis_blade(1 << i)
        assert (e * e).coefficients.tolist() == [s] + [0.0] * (len(alg) - 1)


@pytest.mark.parametrize("sig", SIGNATURES)
def test_products_equal_the_reference_rule(sig):
    rng = np.random.default_rng(1)
    alg = rf.Algebra(*sig)
    rules = {
        "geometric": lambda ga, gb, gc: True,
        "outer": lambda ga, gb, gc: gc == ga + gb,
        "left_contraction": lambda ga, gb, gc: gc == gb - ga,
        "right_contraction": lambda ga, gb, gc: gc == ga - gb,
        "inner": lambda ga, gb, gc: gc == abs(ga - gb),
    }
    checked = 0
    for _ in range(5):
        a = rng.normal(size=len(alg))
        b = rng.normal(size=len(alg))
        A, B = alg.multivector(a), alg.multivector(b)
        ops = {
            "geometric": A * B,
            "outer": A ^ B,
            "left_contraction": A.left_contract(B),
            "right_contraction": A.right_contract(B),
            "inner": A | B,
        }
        for name, rule in rules.items():
            expected = reference_product(sig, a, b, rule)
            np.testing.assert_allclose(ops[name].coefficients, expected, atol=1e-12, rtol=1e-12)
            batch = alg.product(a, b, kind=name)
            if name == "inner":
                # The batch sums the inner product in one pass, the element as three products.
                np.testing.assert_allclose(batch, ops[name].coefficients, rtol=1e-15, atol=1e-15)
            else:
                np.testing.assert_array_equal(batch, ops[name].coefficients)
            checked += 1
    assert checked == 25


@given(st.data())
@settings(max_examples=60, deadline=None)
def test_geometric_product_is_associative_and_distributive(data):
    sig = data.draw(st.sampled_from(SIGNATURES))
    alg = rf.Algebra(*sig)
    a, b, c = (alg.multivector(data.draw(coefficients(len(alg)))) for _ in range(3))
    left = ((a * b) * c).coefficients
    right = (a * (b * c)).coefficients
    scale = max(1.0, np.abs(left).max())
    assert np.abs(left - right).max() <= 1e-12 * scale
    np.testing.assert_allclose(
        (a * (b + c)).coefficients, (a * b + a * c).coefficients, atol=1e-11 * scale
    )


@given(st.data())
@settings(max_examples=60, deadline=None)
def test_reverse_is_an_anti_automorphism(data):
    sig = data.draw(st.sampled_from(SIGNATURES))
    alg = rf.Algebra(*sig)
    a, b = (alg.multivector(data.draw(coefficients(len(alg)))) for _ in range(2))
    lhs = (~(a * b)).coefficients
    rhs = ((~b) * (~a)).coefficients
    np.testing.assert_allclose(lhs, rhs, atol=1e-11 * max(1.0, np.abs(lhs).max()))


def test_operators_with_scalars():
    alg = rf.Algebra(3)
    e1, e2 = alg.e1, alg.e2
    assert (2 * e1 + 1).coefficients.tolist() == [1, 2, 0, 0, 0, 0, 0, 0]
    assert (1 - e1).coefficients.tolist() == [1, -1, 0, 0, 0, 0, 0, 0]
    assert (e1 * 3.0 / 2.0)[1] == 1.5
    assert (e1 / e1).coefficients.tolist() == [1, 0, 0, 0, 0, 0, 0, 0]
    assert (2.0 / e1).coefficients.tolist() == [0, 2, 0, 0, 0, 0, 0, 0]
    assert (-e1)["e1"] == -1.0
    assert (e2 * e1)["e12"] == -1.0
    assert (e2 * e1)["e21"] == 1.0
    assert (e1 ^ e2) == alg.e12
    assert (e1 | e1).scalar_part == 1.0
    assert (alg.e12 & alg.e23) == alg.e2  # the planes e12 and e23 meet in the e2 axis
    assert alg.blade("e31", 2.0)["e13"] == -2.0


def test_repr_and_latex():
    alg = rf.Algebra(3)
    m = alg.multivector([1, 0, 0, -0.5, 0, 0, 0, 2])
    assert str(m) == "1 - 0.5·e12 + 2·e123"
    assert repr(m) == "Multivector(Cl(3,0,0), 1 - 0.5·e12 + 2·e123)"
    assert m._repr_latex_() == "$1 - 0.5\\,e_{12} + 2\\,e_{123}$"
    assert alg.multivector([0.0] * 8)._repr_latex_() == "$0$"
    assert repr(rf.Algebra.pga(3)) == "Algebra(3, 0, 1)"


def test_shortcut_algebras():
    assert (rf.Algebra.pga(3).p, rf.Algebra.pga(3).q, rf.Algebra.pga(3).r) == (3, 0, 1)
    assert (rf.Algebra.cga(3).p, rf.Algebra.cga(3).q, rf.Algebra.cga(3).r) == (4, 1, 0)
    sta = rf.Algebra.spacetime()
    assert (sta.p, sta.q, sta.r) == (1, 3, 0)
    assert rf.Algebra.euclidean(4) == rf.Algebra(4)


def random_bivector(alg, rng, scale=1.0):
    n = alg.dim
    return alg.bivector(rng.normal(scale=scale, size=n * (n - 1) // 2))


@pytest.mark.parametrize("sig", [(3, 0, 0), (4, 0, 0), (5, 0, 0), (6, 0, 0), (3, 0, 1), (4, 1, 0), (1, 3, 0), (2, 2, 0)])
def test_exp_equals_the_matrix_exponential(sig):
    # exp(B) = expm(L_B) 1 with L_B the matrix of left multiplication by B: an independent
    # route (scaling and squaring of a 2^N x 2^N matrix) to the crate's closed forms.
    rng = np.random.default_rng(7)
    alg = rf.Algebra(*sig)
    for _ in range(4):
        b = random_bivector(alg, rng)
        expected = scipy.linalg.expm(left_multiplication(sig, b.coefficients))[:, 0]
        np.testing.assert_allclose(b.exp().coefficients, expected, atol=1e-12, rtol=1e-12)


@pytest.mark.parametrize("n", [4, 5, 6, 7, 8])
def test_batched_exp_and_log_in_n_dimensions(n):
    rng = np.random.default_rng(n)
    alg = rf.Algebra(n)
    bivectors = np.stack([random_bivector(alg, rng, 0.5).coefficients for _ in range(20)])
    rotors = alg.exp(bivectors)
    assert rotors.shape == (20, 1 << n)
    for b, r in zip(bivectors, rotors):
        np.testing.assert_array_equal(r, alg.multivector(b).exp().coefficients)
    # R R~ = 1, exp undoes log, and log undoes exp where every plane angle is below pi.
    unit = alg.product(rotors, alg.reverse(rotors))
    np.testing.assert_allclose(unit[:, 0], 1.0, atol=1e-14)
    np.testing.assert_allclose(unit[:, 1:], 0.0, atol=1e-14)
    np.testing.assert_allclose(alg.exp(alg.log(rotors)), rotors, atol=1e-14)
    small = bivectors * (0.5 / np.abs(bivectors).sum(axis=1, keepdims=True))
    np.testing.assert_allclose(alg.log(alg.exp(small)), small, atol=1e-15)


def test_sandwich_rotates_vectors_like_the_rotation_matrix():
    rng = np.random.default_rng(3)
    alg = rf.Algebra(4)
    theta = rng.normal(size=6)
    r = alg.bivector(theta * -0.5).exp()  # R = exp(-Theta/2)
    skew = np.zeros((4, 4))
    skew[np.triu_indices(4, 1)] = theta
    skew = skew - skew.T
    q = scipy.linalg.expm(skew.T)
    x = rng.normal(size=(50, 4))
    xs = np.zeros((50, 16))
    for i in range(4):
        xs[:, 1 << i] = x[:, i]
    turned = alg.sandwich(r.coefficients, xs)
    np.testing.assert_allclose(turned[:, [1, 2, 4, 8]], x @ q.T, atol=1e-14)
    assert np.abs(np.delete(turned, [1, 2, 4, 8], axis=1)).max() < 1e-14
    # The batch runs a rotor on a vector through its non-zero terms: the same vector part as
    # the single sandwich to the last bit, and an exact zero where the single one keeps round-off.
    single = r.sandwich(alg.multivector(xs[5])).coefficients
    np.testing.assert_array_equal(turned[5, [1, 2, 4, 8]], single[[1, 2, 4, 8]])
    assert not np.delete(turned, [1, 2, 4, 8], axis=1).any()
    assert np.abs(np.delete(single, [1, 2, 4, 8])).max() < 1e-14


@given(st.lists(st.floats(-3, 3), min_size=6, max_size=6))
@settings(max_examples=80, deadline=None)
def test_sqrt_squares_back_and_normalized_is_unit(components):
    alg = rf.Algebra(4)
    v = alg.bivector(components).exp()
    s = v.sqrt()
    np.testing.assert_allclose((s * s).coefficients, v.coefficients, atol=1e-13)
    drifted = v * 1.001
    unit = drifted.normalized()
    np.testing.assert_allclose((unit * ~unit).coefficients, np.eye(16)[0], atol=1e-14)


def test_grades_dual_and_norm():
    alg = rf.Algebra(3)
    m = alg.multivector(np.arange(1.0, 9.0))
    assert m.grade(1) == alg.multivector([0, 2, 3, 0, 5, 0, 0, 0])
    assert m.grades() == [0, 1, 2, 3]
    assert (m.even() + m.odd()) == m
    assert alg.e12.dual() == alg.e12 * alg.e123.inverse()
    assert alg.e3.dual() == -alg.e12  # e3 (e123)^-1 = -e3 e123 = -e12
    assert math.isclose(alg.vector([3, 4, 0]).norm(), 5.0)
    np.testing.assert_allclose(
        alg.vector([3, 4, 0]).normalized().coefficients, [0, 0.6, 0.8, 0, 0, 0, 0, 0], rtol=1e-15
    )


def test_pickle_and_equality():
    import pickle

    alg = rf.Algebra(2, 1)
    m = alg.multivector(np.arange(8.0))
    assert pickle.loads(pickle.dumps(m)) == m
    assert pickle.loads(pickle.dumps(alg)) == alg
    assert m != rf.Algebra(3).multivector(np.arange(8.0))
    assert m != 3


def test_batched_products_by_chunks_equal_the_single_products():
    # The batch runs in chunks of 64 elements, checked for finiteness on the way: lengths
    # around a chunk, a single element broadcast on either side, every element against the
    # product of that pair alone, and a NaN past the first chunk named by its element.
    rng = np.random.default_rng(12)
    checked = 0
    for n in (2, 3, 4, 5):
        alg = rf.Algebra(n)
        k = len(alg)
        for m in (1, 63, 64, 65, 130):
            a, b = rng.normal(size=(m, k)), rng.normal(size=(m, k))
            cases = [(a, b, alg.product(a, b)), (a[0], b, alg.product(a[0], b)), (a, b[0], alg.product(a, b[0]))]
            for x, y, batch in cases:
                for i in range(m):
                    xi, yi = (x if x.ndim == 1 else x[i]), (y if y.ndim == 1 else y[i])
                    np.testing.assert_array_equal(batch[i], (alg.multivector(xi) * alg.multivector(yi)).coefficients)
                    checked += 1
        bad = rng.normal(size=(200, k))
        bad[150, k - 1] = np.inf
        with pytest.raises(ValueError, match="b: NaN or infinite entry in element 150"):
            alg.product(rng.normal(size=(200, k)), bad)
        with pytest.raises(ValueError, match="versors: NaN or infinite entry"):
            alg.sandwich(bad[150], bad[:10])
    assert checked == 4 * 3 * (1 + 63 + 64 + 65 + 130)


def test_batched_products_of_8_and_16_coefficients_in_every_signature():
    # Products of 8 and 16 coefficients run through a kernel of their own signs (read off the
    # table's basis products, with the blade offset of the regressive product): every product
    # in every signature of that size, against one element at a time through the multivector.
    rng = np.random.default_rng(13)
    exact = {
        "geometric": lambda x, y: x * y,
        "outer": lambda x, y: x ^ y,
        "left_contraction": lambda x, y: x.left_contract(y),
        "right_contraction": lambda x, y: x.right_contract(y),
        "commutator": lambda x, y: x.commutator(y),
        "anticommutator": lambda x, y: x.anticommutator(y),
    }
    # Summed by the multivector in another order: to round-off.
    close = {"inner": lambda x, y: x | y, "regressive": lambda x, y: x.regressive(y)}
    sigs = [(3, 0, 0), (2, 1, 0), (1, 2, 0), (2, 0, 1), (4, 0, 0), (3, 1, 0), (1, 3, 0), (3, 0, 1), (2, 1, 1)]
    checked = 0
    for sig in sigs:
        alg = rf.Algebra(*sig)
        a, b = rng.normal(size=(70, len(alg))), rng.normal(size=(70, len(alg)))
        for name, f in {**exact, **close}.items():
            batch = alg.product(a, b, kind=name)
            for i in range(len(a)):
                one = f(alg.multivector(a[i]), alg.multivector(b[i])).coefficients
                if name in exact:
                    np.testing.assert_array_equal(batch[i], one, err_msg=f"{sig} {name} {i}")
                else:
                    np.testing.assert_allclose(batch[i], one, rtol=0, atol=1e-14, err_msg=f"{sig} {name} {i}")
                checked += 1
    assert checked == len(sigs) * 8 * 70


def test_batched_sandwiches_equal_the_single_sandwiches():
    # The batched sandwich runs each chunk of 64 as two products: rotors on vectors (whose
    # vector part and exact zeros elsewhere are those of the sandwich through the non-zero
    # terms) and general elements, every element against V X Ṽ of that pair alone.
    rng = np.random.default_rng(14)
    checked = 0
    for sig in [(3, 0, 0), (2, 1, 0), (4, 0, 0), (3, 1, 0), (3, 0, 1)]:
        alg = rf.Algebra(*sig)
        k, n = len(alg), alg.dim
        even = [b for b in range(k) if bin(b).count("1") % 2 == 0]
        vec = [1 << i for i in range(n)]
        rot, x = np.zeros((100, k)), np.zeros((100, k))
        rot[:, even] = rng.normal(size=(100, len(even)))
        x[:, vec] = rng.normal(size=(100, n))
        general = rng.normal(size=(100, k)), rng.normal(size=(100, k))
        for a, b in [(rot, x), general]:
            batch = alg.sandwich(a, b)
            for i in range(100):
                one = alg.multivector(a[i]).sandwich(alg.multivector(b[i])).coefficients
                if a is rot:
                    np.testing.assert_array_equal(batch[i, vec], one[vec], err_msg=f"{sig} {i}")
                    assert not np.delete(batch[i], vec).any()
                else:
                    np.testing.assert_array_equal(batch[i], one, err_msg=f"{sig} {i}")
                checked += 1
    assert checked == 5 * 2 * 100


def test_batched_products_of_8_and_16_coefficients_refuse_any_bad_entry():
    # The kernels of 8 and 16 coefficients check their operands as they load them: a NaN or
    # an infinity in either operand, at any element of a chunk and any coefficient, is
    # refused with its element named, and a batch of finite numbers is accepted.
    rng = np.random.default_rng(15)
    checked = 0
    for n in (3, 4):
        alg = rf.Algebra(n)
        k = len(alg)
        a, b = rng.normal(size=(200, k)), rng.normal(size=(200, k))
        alg.product(a, b)
        for name in ("a", "b"):
            for value in (np.nan, np.inf, -np.inf):
                for element in (0, 63, 64, 130, 199):
                    for coefficient in (0, k // 2 + 1, k - 1):
                        x, y = a.copy(), b.copy()
                        (x if name == "a" else y)[element, coefficient] = value
                        with pytest.raises(ValueError, match=f"{name}: NaN or infinite entry in element {element}"):
                            alg.product(x, y)
                        checked += 1
    assert checked == 2 * 2 * 3 * 5 * 3
