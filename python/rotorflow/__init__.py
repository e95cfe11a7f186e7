"""rotorflow: geometric algebra for rotating bodies in any number of dimensions.

The arithmetic is the Rust crate's (the extension module ``rotorflow._rotorflow``); this
package names it for Python. Bad input raises ``ValueError`` with the crate's one-line
message (``FileNotFoundError`` for a missing file).
"""

from ._rotorflow import (
    Algebra,
    Body,
    Multivector,
    Rotor3,
    Rotor4,
    Scene,
    SceneRun,
    __version__,
    motion_html,
)
from . import cga, pga, sta
from ._motion import Motion, animation_html, exact, simulate
from ._scene import scene

__all__ = [
    "Algebra",
    "Body",
    "Motion",
    "Multivector",
    "Rotor3",
    "Rotor4",
    "Scene",
    "SceneRun",
    "__version__",
    "animation_html",
    "cga",
    "exact",
    "motion_html",
    "pga",
    "scene",
    "simulate",
    "sta",
]
