"""Rotor3 against scipy.spatial.transform.Rotation, Rotor4 against the matrix exponential,
both against the run-time multivectors of the algebra."""

import numpy as np
import pytest
import scipy.linalg
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation, Slerp

import rotorflow as rf

RNG = np.random.default_rng(2026)


def rotvecs(m):
    return RNG.normal(size=(m, 3)) * 1.2


def test_rotvec_quat_matrix_agree_with_scipy():
    v = rotvecs(200)
    ours = rf.Rotor3.from_rotvec(v)
    theirs = Rotation.from_rotvec(v)
    np.testing.assert_allclose(ours.as_matrix(), theirs.as_matrix(), atol=1e-15)
    np.testing.assert_allclose(
        ours.as_quat(canonical=True), theirs.as_quat(canonical=True), atol=1e-15
    )
    np.testing.assert_allclose(
        ours.as_quat(scalar_first=True, canonical=True),
        np.roll(theirs.as_quat(canonical=True), 1, axis=1),
        atol=1e-15,
    )
    np.testing.assert_allclose(ours.as_rotvec(), theirs.as_rotvec(), atol=1e-14)
    np.testing.assert_allclose(ours.magnitude(), theirs.magnitude(), atol=1e-14)
    back = rf.Rotor3.from_quat(theirs.as_quat())
    np.testing.assert_allclose(back.as_matrix(), theirs.as_matrix(), atol=1e-15)
    from_m = rf.Rotor3.from_matrix(theirs.as_matrix())
    np.testing.assert_allclose(from_m.as_matrix(), theirs.as_matrix(), atol=1e-15)


def test_apply_compose_inverse_agree_with_scipy():
    v = rotvecs(100)
    x = RNG.normal(size=(100, 3))
    a, b = rf.Rotor3.from_rotvec(v), rf.Rotor3.from_rotvec(v[::-1].copy())
    sa, sb = Rotation.from_rotvec(v), Rotation.from_rotvec(v[::-1].copy())
    np.testing.assert_allclose(a.apply(x), sa.apply(x), atol=1e-14)
    np.testing.assert_allclose(a.apply(x, inverse=True), sa.apply(x, inverse=True), atol=1e-14)
    np.testing.assert_allclose((a * b).as_matrix(), (sa * sb).as_matrix(), atol=1e-14)
    np.testing.assert_allclose(a.inv().as_matrix(), sa.inv().as_matrix(), atol=1e-15)
    # One rotor, many vectors (the crate's batch kernel), and many rotors, one vector.
    one, sone = a[3], sa[3]
    np.testing.assert_allclose(one.apply(x), sone.apply(x), atol=1e-14)
    np.testing.assert_allclose(a.apply(x[0]), sa.apply(x[0]), atol=1e-14)
    assert one.apply(x[0]).shape == (3,)
    assert one.single and not a.single and len(a) == 100 and len(a[10:20]) == 10


def test_slerp_agrees_with_scipy():
    v = rotvecs(2)
    ends = Rotation.from_rotvec(v)
    t = np.linspace(0.0, 1.0, 11)
    theirs = Slerp([0.0, 1.0], ends)(t)
    a, b = rf.Rotor3.from_rotvec(v[0]), rf.Rotor3.from_rotvec(v[1])
    ours = a.slerp(b, t)
    assert len(ours) == 11
    np.testing.assert_allclose(ours.as_matrix(), theirs.as_matrix(), atol=1e-14)


def test_axis_angle_and_bivector_conventions():
    r = rf.Rotor3.from_axis_angle([0, 0, 2.0], np.pi / 2)
    np.testing.assert_allclose(r.apply([1.0, 0, 0]), [0, 1, 0], atol=1e-15)
    # A rotation by theta about e3 is the rotation bivector theta e12, components (theta, 0, 0).
    np.testing.assert_allclose(r.as_bivector(), [np.pi / 2, 0, 0], atol=1e-15)
    alg = rf.Algebra(3)
    mv = r.as_multivector()
    np.testing.assert_allclose(mv.coefficients, alg.bivector([-np.pi / 4, 0, 0]).exp().coefficients, atol=1e-15)


def skew(theta, n):
    s = np.zeros((n, n))
    s[np.triu_indices(n, 1)] = theta
    return s - s.T


def test_rotor4_matrix_is_the_matrix_exponential():
    thetas = RNG.normal(size=(50, 6))
    r = rf.Rotor4.from_bivector(thetas)
    for theta, m in zip(thetas, r.as_matrix()):
        np.testing.assert_allclose(m, scipy.linalg.expm(skew(theta, 4).T), atol=1e-14)
    back = rf.Rotor4.from_matrix(r.as_matrix())
    np.testing.assert_allclose(back.as_matrix(), r.as_matrix(), atol=1e-14)
    plus, minus = r.as_quaternion_pair()
    again = rf.Rotor4.from_quaternion_pair(plus, minus)
    np.testing.assert_allclose(again.as_matrix(), r.as_matrix(), atol=1e-15)


def test_rotor4_apply_compose_slerp():
    thetas = RNG.normal(size=(40, 6))
    a = rf.Rotor4.from_bivector(thetas)
    b = rf.Rotor4.from_bivector(thetas[::-1].copy())
    x = RNG.normal(size=(40, 4))
    ma, mb = a.as_matrix(), b.as_matrix()
    np.testing.assert_allclose(a.apply(x), np.einsum("mij,mj->mi", ma, x), atol=1e-14)
    np.testing.assert_allclose(a.apply(x, inverse=True), np.einsum("mji,mj->mi", ma, x), atol=1e-14)
    np.testing.assert_allclose((a * b).as_matrix(), ma @ mb, atol=1e-14)
    np.testing.assert_allclose(a[0].apply(x), x @ ma[0].T, atol=1e-14)
    # Half-way along the slerp from the identity is the square root of the rotor.
    alg = rf.Algebra(4)
    small = rf.Rotor4.from_bivector(thetas[0] * 0.3)
    half = rf.Rotor4.identity().slerp(small, 0.5).as_multivector()
    np.testing.assert_allclose(
        half.coefficients, small.as_multivector().sqrt().coefficients, atol=1e-15
    )
    assert rf.Rotor4.from_plane_angle(0, 1, 0.5).as_bivector().tolist() == pytest.approx(
        [0.5, 0, 0, 0, 0, 0]
    )
    np.testing.assert_allclose(alg.multivector(small.as_multivector().coefficients).norm(), 1.0)


@given(st.lists(st.floats(-4, 4), min_size=3, max_size=3), st.lists(st.floats(-5, 5), min_size=3, max_size=3))
@settings(max_examples=100, deadline=None)
def test_rotor3_agrees_with_scipy_for_any_rotation_vector(rotvec, x):
    ours = rf.Rotor3.from_rotvec(rotvec)
    theirs = Rotation.from_rotvec(rotvec)
    np.testing.assert_allclose(ours.apply(x), theirs.apply(x), atol=1e-13)
    assert ours.unit_error() < 1e-15


def test_batched_apply_equals_the_single_applies_at_every_length():
    # The batched loops run 2, 4 or 8 rows at a time: lengths around those widths, every row
    # against the rotation of that row alone: through the same matrix to the last bit (one
    # rotor for all), to round-off (a rotor per row, whose loop turns by the quaternion
    # formula instead), and all of them against scipy.
    rng = np.random.default_rng(11)
    checked = 0
    for m in (1, 2, 3, 7, 8, 9, 15, 16, 17, 1003):
        x = rng.normal(size=(m, 3))
        rv = rng.normal(size=(m, 3))
        one = rf.Rotor3.from_rotvec(rv[0])
        many = rf.Rotor3.from_rotvec(rv)
        for inverse in (False, True):
            by_one = one.apply(x, inverse=inverse)
            by_many = many.apply(x, inverse=inverse)
            for i in range(m):
                np.testing.assert_array_equal(by_one[i], one.apply(x[i], inverse=inverse))
                alone = many[i].apply(x[i], inverse=inverse)
                np.testing.assert_allclose(by_many[i], alone, rtol=0, atol=4e-15 * np.abs(x[i]).max())
                checked += 1
            np.testing.assert_allclose(by_one, Rotation.from_rotvec(rv[0]).apply(x, inverse=inverse), atol=1e-14)
            np.testing.assert_allclose(by_many, Rotation.from_rotvec(rv).apply(x, inverse=inverse), atol=1e-14)
        four = rf.Rotor4.from_bivector(rng.normal(size=6))
        fours = rf.Rotor4.from_bivector(rng.normal(size=(m, 6)))
        y = rng.normal(size=(m, 4))
        np.testing.assert_allclose(four.apply(y), y @ four.as_matrix().T, atol=1e-14)
        mats = fours.as_matrix()
        np.testing.assert_allclose(fours.apply(y), np.einsum("mij,mj->mi", mats, y), atol=1e-14)
        np.testing.assert_allclose(fours.apply(y, inverse=True), np.einsum("mji,mj->mi", mats, y), atol=1e-14)
    assert checked == 2 * (1 + 2 + 3 + 7 + 8 + 9 + 15 + 16 + 17 + 1003)


def test_batched_apply_is_the_row_formula_to_the_last_bit():
    # A batch of rotations, a rotor per vector, runs blocks of 8 rows together (AVX-512 where
    # the processor has it) and the rows after the last block one at a time: every row of a
    # block equals the same rotor and vector turned as the last row, alone, to the last bit.
    rng = np.random.default_rng(12)
    m = 9
    checked = 0
    for rotor, planes, n in ((rf.Rotor3, 3, 3), (rf.Rotor4, 6, 4)):
        biv = rng.normal(size=(m, planes))
        x = rng.normal(size=(m, n)) * 10.0 ** rng.integers(-3, 4, size=(m, 1))
        for inverse in (False, True):
            by_many = rotor.from_bivector(biv).apply(x, inverse=inverse)
            for i in range(m):
                order = np.r_[[k for k in range(m) if k != i], i]
                alone = rotor.from_bivector(biv[order]).apply(x[order], inverse=inverse)[-1]
                np.testing.assert_array_equal(by_many[i], alone, err_msg=f"N = {n}, row {i}")
                checked += 1
    assert checked == 2 * 2 * m


def test_one_rotation_of_many_vectors_split_over_the_cores_is_the_same_to_the_last_bit():
    # One rotation of 2^16 vectors or more per core splits the rows over the cores: the same
    # numbers as the rows turned in pieces too small to split, and a bad entry in a later
    # part named by its element.
    rng = np.random.default_rng(14)
    m = 300_000
    for rotor, n in ((rf.Rotor3.from_rotvec(rng.normal(size=3)), 3), (rf.Rotor4.from_bivector(rng.normal(size=6)), 4)):
        x = rng.normal(size=(m, n))
        for inverse in (False, True):
            whole = rotor.apply(x, inverse=inverse)
            pieces = np.concatenate([rotor.apply(x[k : k + 50_000], inverse=inverse) for k in range(0, m, 50_000)])
            np.testing.assert_array_equal(whole, pieces)
        x[250_001, n - 1] = np.nan
        with pytest.raises(ValueError, match="element 250001"):
            rotor.apply(x)


def test_batched_apply_names_the_first_bad_vector():
    x = np.ones((1000, 3))
    x[637, 1] = np.nan
    x[900, 0] = np.inf
    for rotors in (rf.Rotor3.identity(), rf.Rotor3.identity(1000)):
        for inverse in (False, True):
            with pytest.raises(ValueError, match="vectors: NaN or infinite entry in element 637"):
                rotors.apply(x, inverse=inverse)
    with pytest.raises(ValueError, match="element 637"):
        rf.Rotor4.identity(1000).apply(np.concatenate([x, np.ones((1000, 1))], axis=1))
    with pytest.raises(ValueError, match="element 637"):
        rf.Rotor4.identity(1000).apply(np.concatenate([x, np.ones((1000, 1))], axis=1), inverse=True)
