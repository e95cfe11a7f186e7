"""Projective geometric algebra Cl(N, 0, 1) (the null vector last): the crate's typed points,
planes, lines and motors as elements of ``Algebra.pga(n)``. A motor M moves X by
``M.sandwich(X)``."""

from ._rotorflow import pga_coordinates as coordinates
from ._rotorflow import pga_ideal_point as ideal_point
from ._rotorflow import pga_line as line
from ._rotorflow import pga_motor_from_matrix as motor_from_matrix
from ._rotorflow import pga_motor_matrix as motor_matrix
from ._rotorflow import pga_plane as plane
from ._rotorflow import pga_point as point
from ._rotorflow import pga_rotor as rotor
from ._rotorflow import pga_translator as translator

__all__ = [
    "coordinates",
    "ideal_point",
    "line",
    "motor_from_matrix",
    "motor_matrix",
    "plane",
    "point",
    "rotor",
    "translator",
]
