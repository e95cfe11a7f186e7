"""Bad input raises ValueError naming the problem: never a panic, never a crash."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import rotorflow as rf

A3 = rf.Algebra(3)
PGA = rf.Algebra.pga(3)

# (call, words the message must contain)
CASES = [
    (lambda: rf.Algebra(-1), "p must be >= 0"),
    (lambda: rf.Algebra(17), "dimension"),
    (lambda: rf.Algebra.cga(15), "dimension"),
    (lambda: A3.multivector([1.0] * 7), "expected shape (8)"),
    (lambda: A3.multivector([[1.0] * 8] * 2), "use the batch functions"),
    (lambda: A3.multivector([1.0] * 7 + [math.nan]), "NaN"),
    (lambda: A3.multivector([1.0] * 7 + [math.inf]), "NaN or infinite"),
    (lambda: A3.multivector("abcdefgh"), "coefficients"),
    (lambda: A3.multivector([[1.0, 2.0], [3.0]]), "coefficients"),
    (lambda: A3.vector([1.0, 2.0]), "vector components"),
    (lambda: A3.bivector([1.0, 2.0, math.nan]), "NaN"),
    (lambda: A3.blade("e14"), "e14"),
    (lambda: A3.blade("x"), "x"),
    (lambda: A3.basis_blade(8), "out of range"),
    (lambda: A3.basis_blade(-1), ">= 0"),
    (lambda: A3.e1 * PGA.e1, "Cl(3,0,0)"),
    (lambda: A3.e1 + PGA.e1, "Cl(3,0,1)"),
    (lambda: A3.e1 * math.nan, "NaN"),
    (lambda: A3.e1 + math.inf, "NaN"),
    (lambda: A3.e1 / (1 + A3.e1), "invert"),
    (lambda: 1 / A3.scalar(0.0), "zero"),
    (lambda: A3.e1.exp(), "bivector"),
    (lambda: A3.e1.log(), "even"),
    (lambda: A3.vector([0.0, 0.0, 0.0]).normalized(), "versor"),
    (lambda: PGA.e4.normalized(), "norm 0"),
    (lambda: PGA.e1.dual(), "degenerate"),
    (lambda: A3.e1["e4"], "e4"),
    (lambda: A3.e1[99], "out of range"),
    (lambda: A3.e1.grade(-1), ">= 0"),
    (lambda: A3.product(np.zeros(8), np.zeros(8), kind="dot"), "unknown product"),
    (lambda: A3.product(np.zeros((3, 8)), np.zeros((4, 8))), "different lengths"),
    (lambda: A3.product(np.zeros((3, 7)), np.zeros(8)), "expected shape"),
    (lambda: A3.exp(np.ones((2, 8))), "element 0"),
    (lambda: A3.exp(np.array([[0, 0, 0, 1.0, 0, 0, 0, 0], [0, 0, 0, np.nan, 0, 0, 0, 0]])), "element 1"),
    (lambda: A3.log(np.array([[1.0] * 8])), "versor"),
    (lambda: A3.sandwich(np.zeros(8), np.zeros((2, 3, 8))), "expected shape"),
    (lambda: rf.Rotor3.from_quat([0, 0, 0, 0]), "zero quaternion"),
    (lambda: rf.Rotor3.from_quat([0, 0, 0]), "expected shape (4)"),
    (lambda: rf.Rotor3.from_quat([[0, 0, 0, 1], [0, 0, 0, math.nan]]), "element 1"),
    (lambda: rf.Rotor3.from_matrix(np.eye(3) * 2), "rotation"),
    (lambda: rf.Rotor3.from_matrix(-np.eye(3)), "rotation"),
    (lambda: rf.Rotor3.from_matrix(np.eye(4)), "expected shape (3, 3)"),
    (lambda: rf.Rotor3.from_rotvec([[1, 2, 3]] * 2).apply(np.zeros((3, 3))), "different lengths"),
    (lambda: rf.Rotor3.identity().apply(np.zeros((3, 4))), "expected shape (3)"),
    (lambda: rf.Rotor3.identity().apply([1.0, math.nan, 0.0]), "NaN"),
    (lambda: rf.Rotor3.from_axis_angle([0, 0, 0], 1.0), "zero"),
    (lambda: rf.Rotor3.from_axis_angle([0, 0, 1], math.nan), "angle"),
    (lambda: rf.Rotor3.identity(-2), ">= 0"),
    (lambda: rf.Rotor3.identity().slerp(rf.Rotor3.identity(), math.nan), "NaN"),
    (lambda: rf.Rotor4.from_bivector([1.0] * 5), "expected shape (6)"),
    (lambda: rf.Rotor4.from_matrix(np.ones((4, 4))), "rotation"),
    (lambda: rf.Rotor4.from_plane_angle(0, 4, 1.0), "4"),
    (lambda: rf.Rotor4.from_quaternion_pair([1, 0, 0, 0], [[1, 0, 0, 0]]), "same shape"),
    (lambda: rf.Rotor4.from_quaternion_pair([1, 0, 0, 0], [0, 0, 0, 0]), "zero quaternion"),
]


@pytest.mark.parametrize("call, words", CASES, ids=[w for _, w in CASES])
def test_bad_input_is_a_value_error_naming_the_problem(call, words):
    with pytest.raises(ValueError) as info:
        call()
    message = str(info.value)
    assert words in message, message
    assert "\n" not in message


def test_every_case_ran():
    assert len(CASES) == 54


def test_wrong_types_are_type_errors_not_crashes():
    with pytest.raises(TypeError):
        A3.e1 * "x"
    with pytest.raises(TypeError):
        rf.Rotor3.identity() * A3.e1
    with pytest.raises(TypeError):
        A3.e1[1.5]
    with pytest.raises(TypeError):
        len(rf.Rotor3.identity())
    with pytest.raises(IndexError):
        rf.Rotor3.identity(3)[3]


def test_unknown_attributes_are_attribute_errors():
    assert not hasattr(A3, "e4")
    assert not hasattr(A3, "expand")
    with pytest.raises(AttributeError, match="e14"):
        A3.e14
    with pytest.raises(TypeError):
        hash(A3.e1)


def test_division_by_zero_is_zero_division_error():
    with pytest.raises(ZeroDivisionError):
        A3.e1 / 0.0


@given(st.lists(st.floats(allow_nan=True, allow_infinity=True), min_size=8, max_size=8))
@settings(max_examples=200, deadline=None)
def test_any_floats_give_an_element_or_a_value_error(values):
    try:
        m = A3.multivector(values)
    except ValueError as e:
        assert not all(math.isfinite(v) for v in values), e
        return
    for op in (lambda: m * m, lambda: m.exp(), lambda: m.log(), lambda: m.sqrt(), lambda: m.inverse(), lambda: m.normalized()):
        try:
            op()
        except ValueError:
            pass
