"""Type stubs of the extension module (the arithmetic of the Rust crate rotorflow)."""

import os
from typing import Any, Literal, Optional, Union

import numpy as np
import numpy.typing as npt

__version__: str

ArrayLike = npt.ArrayLike
Array = npt.NDArray[np.float64]
Number = Union[float, int]

ProductKind = Literal[
    "geometric",
    "outer",
    "wedge",
    "inner",
    "left_contraction",
    "right_contraction",
    "scalar",
    "commutator",
    "anticommutator",
    "regressive",
]

class Algebra:
    """The Clifford algebra Cl(p, q, r): p basis vectors square to +1, then q to -1, then r
    to 0. Multivectors have 2^N coefficients indexed by blade bit mask (bit i - 1 for e_i);
    N = p + q + r <= 16. Blades are attributes: ``alg.e12``."""

    def __init__(self, p: int, q: int = 0, r: int = 0) -> None: ...
    @staticmethod
    def euclidean(n: int) -> Algebra:
        """Cl(n, 0, 0)."""
    @staticmethod
    def pga(n: int) -> Algebra:
        """Projective GA of R^n: Cl(n, 0, 1), the null vector last."""
    @staticmethod
    def cga(n: int) -> Algebra:
        """Conformal GA of R^n: Cl(n + 1, 1, 0)."""
    @staticmethod
    def spacetime() -> Algebra:
        """The spacetime algebra Cl(1, 3): e1 time, e2 e3 e4 space."""
    @property
    def p(self) -> int: ...
    @property
    def q(self) -> int: ...
    @property
    def r(self) -> int: ...
    @property
    def dim(self) -> int:
        """N = p + q + r."""
    def __len__(self) -> int:
        """2^N."""
    def __getattr__(self, name: str) -> Multivector:
        """The blade named ``name`` (``alg.e12``, ``alg.e123``)."""
    def multivector(self, coefficients: ArrayLike) -> Multivector:
        """The element with these 2^N coefficients (blade bit-mask order)."""
    def scalar(self, s: float = 1.0) -> Multivector: ...
    def vector(self, components: ArrayLike) -> Multivector:
        """Sum c_i e_i from N components."""
    def bivector(self, components: ArrayLike) -> Multivector:
        """Sum c_ij e_ij from N(N-1)/2 components in the order e12, e13, ..., e23, ..."""
    def blade(self, name: str, coefficient: float = 1.0) -> Multivector:
        """``coefficient`` times the blade named ``name`` ("1", "e13", "e1e3", "e31" = -e13)."""
    def basis_blade(self, mask: int) -> Multivector:
        """The basis blade with bit mask ``mask``."""
    def product(self, a: ArrayLike, b: ArrayLike, kind: ProductKind = "geometric") -> Array:
        """The products of two batches of shape (M, 2^N) (or (2^N,), used with every
        element of the other); computed in Rust without the GIL."""
    def sandwich(self, versors: ArrayLike, x: ArrayLike) -> Array:
        """V X V~ for batches of even versors V and elements X, shape (M, 2^N)."""
    def exp(self, bivectors: ArrayLike) -> Array:
        """exp(B) of a batch of bivectors, shape (M, 2^N), in closed form."""
    def log(self, versors: ArrayLike) -> Array:
        """log(V) of a batch of even versors, shape (M, 2^N)."""
    def reverse(self, x: ArrayLike) -> Array:
        """The reverse of every element of a batch."""

Operand = Union[Multivector, float, int]

class Multivector:
    """An element of a Clifford algebra. Operators: ``*`` geometric, ``^`` outer, ``|``
    inner (sum of the grade |r - s| parts: Dorst's fat dot, kingdon's ``|``), ``&``
    regressive, ``~`` reverse, ``+ - /`` and real numbers."""

    def __init__(self, algebra: Algebra, coefficients: ArrayLike) -> None: ...
    @property
    def algebra(self) -> Algebra: ...
    @property
    def coefficients(self) -> Array:
        """The 2^N coefficients (a new float64 array), blade bit-mask order."""
    @property
    def scalar_part(self) -> float: ...
    def __getitem__(self, blade: Union[str, int]) -> float:
        """The coefficient of a blade by name ("e12") or bit mask (3)."""
    def _repr_latex_(self) -> str: ...
    def __add__(self, other: Operand) -> Multivector: ...
    def __radd__(self, other: float) -> Multivector: ...
    def __sub__(self, other: Operand) -> Multivector: ...
    def __rsub__(self, other: float) -> Multivector: ...
    def __neg__(self) -> Multivector: ...
    def __pos__(self) -> Multivector: ...
    def __mul__(self, other: Operand) -> Multivector: ...
    def __rmul__(self, other: float) -> Multivector: ...
    def __xor__(self, other: Operand) -> Multivector: ...
    def __rxor__(self, other: float) -> Multivector: ...
    def __or__(self, other: Operand) -> Multivector: ...
    def __ror__(self, other: float) -> Multivector: ...
    def __and__(self, other: Operand) -> Multivector: ...
    def __invert__(self) -> Multivector: ...
    def __truediv__(self, other: Operand) -> Multivector: ...
    def __rtruediv__(self, other: float) -> Multivector: ...
    def left_contract(self, other: Operand) -> Multivector: ...
    def right_contract(self, other: Operand) -> Multivector: ...
    def inner(self, other: Operand) -> Multivector: ...
    def outer(self, other: Operand) -> Multivector: ...
    def scalar_product(self, other: Operand) -> float: ...
    def commutator(self, other: Operand) -> Multivector: ...
    def anticommutator(self, other: Operand) -> Multivector: ...
    def regressive(self, other: Operand) -> Multivector: ...
    def sandwich(self, x: Multivector) -> Multivector:
        """V X V~ with this even versor V."""
    def exp(self) -> Multivector:
        """exp(B) of a bivector, in closed form (non-simple bivectors included)."""
    def log(self) -> Multivector:
        """log(V) of an even versor."""
    def sqrt(self) -> Multivector:
        """The square root of an even versor."""
    def normalized(self) -> Multivector:
        """An even element scaled onto its versor group; any other divided by its norm."""
    def grade(self, k: int) -> Multivector: ...
    def grades(self) -> list[int]: ...
    def even(self) -> Multivector: ...
    def odd(self) -> Multivector: ...
    def reverse(self) -> Multivector: ...
    def involute(self) -> Multivector: ...
    def conjugate(self) -> Multivector: ...
    def inverse(self) -> Multivector: ...
    def dual(self) -> Multivector:
        """A I^-1 (non-degenerate signatures)."""
    def hodge(self) -> Multivector: ...
    def norm_squared(self) -> float: ...
    def norm(self) -> float: ...

class Rotor3:
    """One rotation of 3D space or a batch, with the verbs of scipy's ``Rotation``."""

    @staticmethod
    def identity(num: Optional[int] = None) -> Rotor3: ...
    @staticmethod
    def from_quat(quat: ArrayLike, scalar_first: bool = False) -> Rotor3:
        """From quaternions (x, y, z, w) (or (w, x, y, z)), normalised."""
    def as_quat(self, scalar_first: bool = False, canonical: bool = False) -> Array: ...
    @staticmethod
    def from_matrix(matrix: ArrayLike) -> Rotor3:
        """From rotation matrices (3, 3) or (M, 3, 3); non-rotations are refused."""
    def as_matrix(self) -> Array: ...
    @staticmethod
    def from_rotvec(rotvec: ArrayLike) -> Rotor3: ...
    def as_rotvec(self) -> Array:
        """Rotation vectors with angles in [0, pi]."""
    @staticmethod
    def from_bivector(bivector: ArrayLike) -> Rotor3:
        """R = exp(-Theta/2) from rotation bivectors (components 12, 13, 23)."""
    def as_bivector(self) -> Array:
        """Theta = -2 log R (the rotor's own, angle in [0, 2 pi))."""
    @staticmethod
    def from_axis_angle(axis: ArrayLike, angle: float) -> Rotor3: ...
    def apply(self, vectors: ArrayLike, inverse: bool = False) -> Array:
        """R v R~ for vectors of shape (3,) or (M, 3); without the GIL."""
    def inv(self) -> Rotor3: ...
    def __mul__(self, other: Rotor3) -> Rotor3:
        """``a * b`` applies b first, then a."""
    def magnitude(self) -> Union[float, Array]:
        """Rotation angles in [0, pi]."""
    def slerp(self, other: Rotor3, t: ArrayLike) -> Rotor3: ...
    def unit_error(self) -> Union[float, Array]: ...
    def as_multivector(self) -> Multivector: ...
    @property
    def single(self) -> bool: ...
    def __len__(self) -> int: ...
    def __getitem__(self, index: Union[int, slice]) -> Rotor3: ...

class Rotor4:
    """One rotation of 4D space or a batch: the quaternion pair of Spin(4)."""

    @staticmethod
    def identity(num: Optional[int] = None) -> Rotor4: ...
    @staticmethod
    def from_bivector(bivector: ArrayLike) -> Rotor4:
        """R = exp(-Theta/2) from rotation bivectors (components 12, 13, 14, 23, 24, 34)."""
    def as_bivector(self) -> Array: ...
    @staticmethod
    def from_matrix(matrix: ArrayLike) -> Rotor4: ...
    def as_matrix(self) -> Array: ...
    @staticmethod
    def from_quaternion_pair(plus: ArrayLike, minus: ArrayLike) -> Rotor4: ...
    def as_quaternion_pair(self) -> tuple[Array, Array]: ...
    @staticmethod
    def from_plane_angle(i: int, j: int, angle: float) -> Rotor4: ...
    def apply(self, vectors: ArrayLike, inverse: bool = False) -> Array: ...
    def inv(self) -> Rotor4: ...
    def __mul__(self, other: Rotor4) -> Rotor4: ...
    def magnitude(self) -> Union[float, Array]:
        """Norms of the rotation bivectors."""
    def slerp(self, other: Rotor4, t: ArrayLike) -> Rotor4: ...
    def unit_error(self) -> Union[float, Array]: ...
    def as_multivector(self) -> Multivector: ...
    @property
    def single(self) -> bool: ...
    def __len__(self) -> int: ...
    def __getitem__(self, index: Union[int, slice]) -> Rotor4: ...

class Body:
    """A rigid body of any dimension (the SPEC grammar: ``rotorflow help bodies``)."""

    def __init__(self, spec: str) -> None: ...
    @staticmethod
    def cuboid(half_lengths: ArrayLike, *, mass: Optional[float] = None, density: Optional[float] = None) -> Body: ...
    @staticmethod
    def ellipsoid(semi_axes: ArrayLike, *, mass: Optional[float] = None, density: Optional[float] = None) -> Body: ...
    @staticmethod
    def tesseract(half_edges: ArrayLike, *, mass: Optional[float] = None) -> Body: ...
    @staticmethod
    def pentachoron(a: float, b: float, c: float, d: float, *, mass: Optional[float] = None) -> Body: ...
    @staticmethod
    def simplex(n: int, *, mass: Optional[float] = None) -> Body: ...
    @staticmethod
    def ball(n: int, radius: float, *, mass: Optional[float] = None, density: Optional[float] = None) -> Body: ...
    @staticmethod
    def sphere(n: int, radius: float, *, mass: Optional[float] = None, density: Optional[float] = None) -> Body: ...
    @staticmethod
    def principal(second_moments: ArrayLike, *, mass: Optional[float] = None) -> Body: ...
    @staticmethod
    def tensor(mass_tensor: ArrayLike, *, mass: Optional[float] = None) -> Body: ...
    @staticmethod
    def planes(plane_moments: ArrayLike) -> Body: ...
    @staticmethod
    def points(masses: ArrayLike, positions: ArrayLike) -> Body: ...
    @property
    def spec(self) -> str: ...
    @property
    def dim(self) -> int: ...
    @property
    def mass(self) -> float: ...
    def plane_moments(self) -> Array: ...
    def momentum(self, omega: ArrayLike) -> Array:
        """L = I(omega)."""
    def inertia(self) -> dict[str, Any]:
        """The keys of ``rotorflow inertia --json``."""

Integrator = Literal[
    "rk4",
    "lie-poisson-rk4",
    "lp-rk4",
    "dopri5",
    "dop853",
    "strang",
    "yoshida4",
    "suzuki4",
    "kahan-li6",
    "kahan-li8",
    "midpoint",
    "moser-veselov",
    "mv",
]

def simulate(
    body: Union[Body, str],
    *,
    omega: Optional[ArrayLike] = None,
    momentum: Optional[ArrayLike] = None,
    times: Optional[ArrayLike] = None,
    t_end: Optional[float] = None,
    samples: Optional[int] = None,
    integrator: Integrator = "rk4",
    dt: Optional[float] = None,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
    torque: Optional[str] = None,
    axial: bool = False,
) -> dict[str, Any]:
    """The keys of ``rotorflow simulate --json``: dim, planes, times, omega, momentum,
    energy, casimirs, attitude, drift; numbers as arrays of shape (samples, ...)."""

def exact(
    body: Union[Body, str],
    *,
    omega: Optional[ArrayLike] = None,
    momentum: Optional[ArrayLike] = None,
    times: Optional[ArrayLike] = None,
    t_end: Optional[float] = None,
    samples: Optional[int] = None,
    axial: bool = False,
) -> dict[str, Any]:
    """The closed-form motion, with the keys of ``rotorflow exact --json``."""

def motion_html(
    body: Union[Body, str],
    times: ArrayLike,
    attitude: ArrayLike,
    *,
    title: Optional[str] = None,
) -> str:
    """The HTML animation of ``body`` turning through K rotation matrices (K, N, N) at K
    times (the page of ``rotorflow render --output FILE.html``)."""

# Projective GA (rotorflow.pga): elements of Algebra.pga(n).
def pga_point(x: ArrayLike) -> Multivector:
    """The point at Euclidean coordinates x."""
def pga_ideal_point(d: ArrayLike) -> Multivector:
    """The point at infinity in direction d."""
def pga_coordinates(point: Multivector) -> Array:
    """The Euclidean coordinates of a finite point."""
def pga_plane(normal: ArrayLike, d: float) -> Multivector:
    """The hyperplane n . x = d."""
def pga_line(p: ArrayLike, q: ArrayLike) -> Multivector:
    """The line through the points at p and q."""
def pga_translator(t: ArrayLike) -> Multivector:
    """The motor of the translation by t."""
def pga_rotor(n: int, i: int, j: int, angle: float) -> Multivector:
    """The motor of the rotation by angle in the plane of axes i, j (0-based) of R^n."""
def pga_motor_matrix(motor: Multivector) -> Array:
    """The homogeneous (N + 1) x (N + 1) matrix of a motor."""
def pga_motor_from_matrix(matrix: ArrayLike) -> Multivector:
    """The motor of a homogeneous rigid-motion matrix."""

# Conformal GA (rotorflow.cga): elements of Algebra.cga(n).
def cga_up(x: ArrayLike) -> Multivector:
    """The conformal point n0 + x + x^2/2 ninf."""
def cga_down(point: Multivector) -> Array:
    """The Euclidean coordinates of a conformal point."""
def cga_sphere(center: ArrayLike, radius: float) -> Multivector: ...
def cga_plane(normal: ArrayLike, d: float) -> Multivector: ...
def cga_translator(t: ArrayLike) -> Multivector: ...
def cga_dilator(n: int, scale: float) -> Multivector: ...
def cga_transversor(b: ArrayLike) -> Multivector: ...

# Spacetime algebra (rotorflow.sta): elements of Algebra.spacetime().
def sta_boost(rapidity: float, direction: ArrayLike) -> Multivector:
    """The boost of rapidity phi along a spatial direction (e2, e3, e4)."""

class Scene:
    """Bodies that move and turn together (the book's chapter "Scene files")."""

    def __init__(self, path: Union[str, "os.PathLike[str]"]) -> None: ...
    @staticmethod
    def from_toml(text: str, name: str = "scene.toml") -> Scene: ...
    @staticmethod
    def from_dict(scene: dict[str, Any], name: str = "scene.toml") -> Scene:
        """A scene from a dict with the keys of a scene file."""
    @property
    def dim(self) -> int: ...
    @property
    def t_end(self) -> float: ...
    def default_times(self) -> Array: ...
    def run(self, *, samples: Optional[int] = None, times: Optional[ArrayLike] = None) -> SceneRun:
        """Runs the scene (without the GIL) and records it."""

class SceneRun:
    """A recorded run of a scene; notebooks show its animation."""

    def json(self) -> str:
        """The JSON of ``rotorflow scene --output``."""
    def data(self) -> dict[str, Any]:
        """The keys of ``rotorflow scene --output``, numbers as arrays."""
    def html(self, title: Optional[str] = None) -> str:
        """The self-contained HTML animation."""
    def _repr_html_(self) -> str: ...
    @property
    def times(self) -> Array: ...
