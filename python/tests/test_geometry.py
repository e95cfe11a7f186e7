"""Projective, conformal and spacetime objects: what they mean, checked by their actions."""

import numpy as np
import pytest
import scipy.linalg

import rotorflow as rf
from rotorflow import cga, pga, sta


def test_pga_translator_and_rotor_move_points():
    x = [1.0, 2.0, 3.0]
    p = pga.point(x)
    assert p.algebra == rf.Algebra.pga(3)
    moved = pga.translator([0.5, -1.0, 2.0]).sandwich(p)
    np.testing.assert_allclose(pga.coordinates(moved), [1.5, 1.0, 5.0], atol=1e-15)
    quarter = pga.rotor(3, 0, 1, np.pi / 2)  # turns e1 toward e2
    np.testing.assert_allclose(pga.coordinates(quarter.sandwich(pga.point([1.0, 0, 0]))), [0, 1, 0], atol=1e-15)
    # The homogeneous matrix does to coordinates what the sandwich does to points.
    motor = pga.translator([0.5, -1.0, 2.0]) * quarter
    h = pga.motor_matrix(motor)
    np.testing.assert_allclose((h @ np.r_[x, 1.0])[:3], pga.coordinates(motor.sandwich(p)), atol=1e-14)
    back = pga.motor_from_matrix(h)
    np.testing.assert_allclose(pga.motor_matrix(back), h, atol=1e-14)


def test_pga_line_and_plane_meet_where_expected():
    line = pga.line([0.0, 0.0, 0.0], [1.0, 1.0, 1.0])
    plane = pga.plane([0.0, 0.0, 1.0], 2.0)  # z = 2
    meet = line ^ plane  # in PGA the outer product of a line and a plane is their meeting point
    np.testing.assert_allclose(pga.coordinates(meet), [2.0, 2.0, 2.0], atol=1e-14)


def test_cga_points_and_versors():
    x = np.array([0.3, -1.2, 2.0])
    up = cga.up(x)
    np.testing.assert_allclose(cga.down(up), x, atol=1e-15)
    assert abs((up | up).scalar_part) < 1e-14  # conformal points are null
    moved = cga.translator([1.0, 1.0, 1.0]).sandwich(up)
    np.testing.assert_allclose(cga.down(moved), x + 1.0, atol=1e-14)
    scaled = cga.dilator(3, 2.0).sandwich(up)
    np.testing.assert_allclose(cga.down(scaled), 2.0 * x, atol=1e-14)
    sphere = cga.sphere([0.0, 0.0, 0.0], 2.0)
    on = cga.up([2.0, 0.0, 0.0])
    assert abs((on | sphere).scalar_part) < 1e-14  # a point on the sphere


def test_sta_boost_is_a_lorentz_transformation():
    v = sta.boost(0.7, [1.0, 0.0, 0.0])
    e1 = rf.Algebra.spacetime().e1
    moved = v.sandwich(e1)
    np.testing.assert_allclose([moved["e1"], moved["e2"]], [np.cosh(0.7), np.sinh(0.7)], atol=1e-15)
    k = np.zeros((4, 4))
    k[0, 1] = k[1, 0] = 0.7
    lorentz = scipy.linalg.expm(k)
    np.testing.assert_allclose([moved["e1"], moved["e2"]], lorentz[:2, 0], atol=1e-15)


@pytest.mark.parametrize(
    "call, words",
    [
        (lambda: pga.point([1.0, np.nan]), "non-finite"),
        (lambda: pga.coordinates(rf.Algebra(3).e1), "Cl(3,0,0)"),
        (lambda: pga.rotor(3, 0, 3, 1.0), "3"),
        (lambda: pga.motor_from_matrix(np.ones((4, 4))), "homogeneous"),
        (lambda: cga.sphere([0.0, 0.0], -1.0), "radius"),
        (lambda: cga.dilator(3, 0.0), "dilation factor"),
        (lambda: sta.boost(0.5, [0.0, 0.0, 0.0]), "zero"),
        (lambda: sta.boost(0.5, [1.0, 0.0]), "3"),
    ],
)
def test_geometry_errors(call, words):
    with pytest.raises(ValueError) as info:
        call()
    assert words in str(info.value), str(info.value)
