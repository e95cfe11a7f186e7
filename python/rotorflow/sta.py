"""The spacetime algebra Cl(1, 3) (e1 time, e2 e3 e4 space): boosts as elements of
``Algebra.spacetime()``."""

from ._rotorflow import sta_boost as boost

__all__ = ["boost"]
