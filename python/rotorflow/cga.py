"""Conformal geometric algebra Cl(N + 1, 1, 0): points, spheres, planes and the translator,
dilator and transversor versors as elements of ``Algebra.cga(n)``."""

from ._rotorflow import cga_dilator as dilator
from ._rotorflow import cga_down as down
from ._rotorflow import cga_plane as plane
from ._rotorflow import cga_sphere as sphere
from ._rotorflow import cga_translator as translator
from ._rotorflow import cga_transversor as transversor
from ._rotorflow import cga_up as up

__all__ = ["dilator", "down", "plane", "sphere", "translator", "transversor", "up"]
