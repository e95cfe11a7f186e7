"""Bodies, simulate and exact against the command itself (`rotorflow ... --json`), and the
motion against conserved quantities and scipy's ODE solver."""

import json
import math
import os
import pickle
import subprocess
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import rotorflow as rf

ROOT = Path(__file__).resolve().parents[2]


def command(*args):
    """The JSON the `rotorflow` command prints (built from this checkout)."""
    out = subprocess.run(
        ["cargo", "run", "--release", "--quiet", "--", *args],
        cwd=ROOT,
        check=True,
        capture_output=True,
        text=True,
        env={**os.environ, "NO_COLOR": "1"},
    )
    return json.loads(out.stdout)


def same(ours, theirs, path="report"):
    """Equal keys, and numbers equal to the last bit (the same library calls in the same order)."""
    if isinstance(theirs, dict):
        assert isinstance(ours, dict), path
        assert sorted(ours) == sorted(theirs), path
        for key in theirs:
            same(ours[key], theirs[key], f"{path}.{key}")
    elif theirs is None:
        assert ours is None, path
    elif isinstance(theirs, str) or (isinstance(theirs, list) and theirs and isinstance(theirs[0], str)):
        assert ours == theirs, path
    elif isinstance(theirs, list) and not numeric(theirs):
        assert isinstance(ours, list) and len(ours) == len(theirs), path
        for k, (a, b) in enumerate(zip(ours, theirs)):
            same(a, b, f"{path}[{k}]")
    else:
        np.testing.assert_array_equal(np.asarray(ours, dtype=float), np.asarray(theirs, dtype=float), err_msg=path)


def numeric(value):
    """Whether a parsed JSON list is a rectangular array of numbers."""
    try:
        np.asarray(value, dtype=float)
        return True
    except (TypeError, ValueError):
        return False


SIMULATIONS = [
    ("tesseract:1,1.2,1.5,2", "1,0.05,0.02,0.03,0.04,0.7", ["--t-end", "6", "--samples", "301", "--integrator", "yoshida4"], dict(t_end=6, samples=301, integrator="yoshida4")),
    ("ellipsoid:1,2,3", "0.01,1,0.01", ["--t-end", "20", "--samples", "7"], dict(t_end=20, samples=7)),
    ("cuboid:1,2,3,4+mass=5", "0.3,0.2,0.1,0.4,0.5,0.6", ["--times", "0,0.5,2,3.25", "--integrator", "dopri5", "--rtol", "1e-9"], dict(times=[0, 0.5, 2, 3.25], integrator="dopri5", rtol=1e-9)),
    ("pentachoron:1,1.2,1.5,2", "0.8,0.1,0.05,0.3,0.02,0.6", ["--t-end", "5", "--samples", "11", "--integrator", "dop853"], dict(t_end=5, samples=11, integrator="dop853")),
    ("ellipsoid:1,1.5,2,2.5,3", "0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9,1.0", ["--t-end", "2", "--samples", "5", "--integrator", "moser-veselov", "--dt", "0.005"], dict(t_end=2, samples=5, integrator="moser-veselov", dt=0.005)),
    ("ellipsoid:1,2,3", "0.2,1,0.1", ["--t-end", "3", "--samples", "4", "--integrator", "midpoint", "--torque", "damping:0.1"], dict(t_end=3, samples=4, integrator="midpoint", torque="damping:0.1")),
    ("cuboid:1,2,3", "0.2,1,0.1", ["--t-end", "3", "--samples", "4", "--torque", "body:0.1,0,0.2"], dict(t_end=3, samples=4, torque="body:0.1,0,0.2")),
    ("tensor:2,0.1,0,0.1,3,0.2,0,0.2,4", "0.2,1,0.1", ["--t-end", "3", "--samples", "4", "--torque", "space:0,0.3,0", "--integrator", "lie-poisson-rk4"], dict(t_end=3, samples=4, torque="space:0,0.3,0", integrator="lie-poisson-rk4")),
]


@pytest.mark.parametrize("spec, omega, flags, kwargs", SIMULATIONS, ids=[s[0] for s in SIMULATIONS])
def test_simulate_equals_the_command(spec, omega, flags, kwargs):
    theirs = command("simulate", "--body", spec, "--omega", omega, *flags, "--json")
    ours = rf.simulate(spec, omega=[float(x) for x in omega.split(",")], **kwargs)
    same(ours, theirs)


def test_momentum_and_axial_equal_the_command():
    theirs = command("simulate", "--body", "ellipsoid:1,2,3", "--momentum", "0.3,-0.2,0.9", "--axial", "--t-end", "4", "--samples", "5", "--json")
    ours = rf.simulate(rf.Body.ellipsoid([1, 2, 3]), momentum=[0.3, -0.2, 0.9], axial=True, t_end=4, samples=5)
    same(ours, theirs)


EXACT = [
    ("tesseract:1,1,1,1.5", "0.3,0.4,0.2,0.5,0.1,0.3", ["--t-end", "40", "--samples", "9"]),
    ("ellipsoid:1,2,3", "0.01,1,0.01", ["--t-end", "60", "--samples", "7"]),
]


@pytest.mark.parametrize("spec, omega, flags", EXACT, ids=[e[0] for e in EXACT])
def test_exact_equals_the_command(spec, omega, flags):
    theirs = command("exact", "--body", spec, "--omega", omega, *flags, "--json")
    ours = rf.exact(spec, omega=[float(x) for x in omega.split(",")], t_end=float(flags[1]), samples=int(flags[3]))
    same(ours, theirs)


@pytest.mark.parametrize("spec", ["tesseract:1,1.2,1.5,2", "ellipsoid:1,2,3", "planes:1,2,3,4,5,6", "ball:5,1.5+mass=2", "principal:1,2"])
def test_inertia_equals_the_command(spec):
    theirs = command("inertia", "--body", spec, "--json")
    ours = rf.Body(spec).inertia()
    same(ours, theirs)


def test_typed_constructors_equal_their_specs():
    pairs = [
        (rf.Body.cuboid([1, 2, 3, 4], mass=5), "cuboid:1,2,3,4+mass=5"),
        (rf.Body.ellipsoid([0.1, 0.2, 0.3], density=2.5), "ellipsoid:0.1,0.2,0.3+density=2.5"),
        (rf.Body.tesseract([1, 1.2, 1.5, 2]), "tesseract:1,1.2,1.5,2"),
        (rf.Body.pentachoron(1, 1.2, 1.5, 2), "pentachoron:1,1.2,1.5,2"),
        (rf.Body.simplex(4), "simplex:4"),
        (rf.Body.ball(4, 2.0), "ball:4,2"),
        (rf.Body.sphere(3, 1.0, mass=2), "sphere:3,1+mass=2"),
        (rf.Body.principal([1, 2, 3]), "principal:1,2,3"),
        (rf.Body.tensor(np.diag([1.0, 2.0, 3.0])), "tensor:1,0,0,0,2,0,0,0,3"),
        (rf.Body.planes([1, 2, 3]), "planes:1,2,3"),
    ]
    for body, spec in pairs:
        assert body.spec == spec
        same(body.inertia(), rf.Body(spec).inertia())
    assert len(pairs) == 10


def test_point_masses_equal_the_tesseract():
    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-2, 2) for z in (-3, 3)], dtype=float)
    ours = rf.Body.points(np.ones(8), corners + 10.0).inertia()
    theirs = rf.Body("tesseract:1,2,3").inertia()
    np.testing.assert_allclose(ours["center_of_mass"], [10, 10, 10])
    np.testing.assert_allclose(ours["second_moments"], theirs["second_moments"], rtol=1e-13)
    np.testing.assert_allclose(ours["plane_moments"], theirs["plane_moments"], rtol=1e-13)


def test_free_3d_top_against_scipy_solve_ivp():
    # Euler's equations of the classical top, I dOmega/dt = (I Omega) x Omega, integrated by
    # scipy's DOP853 from the axial vector Omega = (w23, -w13, w12).
    moments = rf.Body("ellipsoid:1,2,3").inertia()["moments_of_inertia"]
    w0 = np.array([0.2, 1.0, 0.1])  # bivector components 12, 13, 23
    axial = np.array([w0[2], -w0[1], w0[0]])

    def euler(t, w):
        return np.cross(moments * w, w) / moments

    times = np.linspace(0.0, 10.0, 11)
    ref = solve_ivp(euler, (0, 10), axial, t_eval=times, rtol=1e-12, atol=1e-14, method="DOP853")
    ours = rf.simulate("ellipsoid:1,2,3", omega=w0, times=times, integrator="dop853", rtol=1e-12, atol=1e-14)
    omega_axial = np.stack([ours["omega"][:, 2], -ours["omega"][:, 1], ours["omega"][:, 0]], axis=1)
    np.testing.assert_allclose(omega_axial, ref.y.T, atol=1e-9)
    closed = rf.exact("ellipsoid:1,2,3", omega=w0, times=times)
    np.testing.assert_allclose(closed["omega"], ours["omega"], atol=1e-9)


def test_splitting_keeps_the_casimirs_and_momentum():
    r = rf.simulate("tesseract:1,1.2,1.5,2", omega=[1, 0.05, 0.02, 0.03, 0.04, 0.7], t_end=20, samples=41, integrator="kahan-li6")
    assert r["drift"]["casimirs"] < 1e-12
    assert r["drift"]["space_momentum"] < 1e-12
    attitude = r["attitude"]
    np.testing.assert_allclose(attitude @ attitude.transpose(0, 2, 1), np.broadcast_to(np.eye(4), attitude.shape), atol=1e-12)


BAD = [
    (lambda: rf.Body("cube:1,2"), ValueError, "unknown kind"),
    (lambda: rf.Body("cuboid:1,-2"), ValueError, "cuboid"),
    (lambda: rf.Body("points:/nonexistent/file.csv"), FileNotFoundError, "nonexistent"),
    (lambda: rf.Body.cuboid([1, math.nan]), ValueError, "half_lengths"),
    (lambda: rf.Body.points([1, 1], np.zeros((3, 2))), ValueError, "positions"),
    (lambda: rf.Body.tensor(np.ones((2, 3))), ValueError, "N × N"),
    (lambda: rf.simulate("ellipsoid:1,2,3", omega=[1, 2], t_end=1, samples=3), ValueError, "2 components given"),
    (lambda: rf.simulate("ellipsoid:1,2,3", omega=[1, 2, math.nan], t_end=1, samples=3), ValueError, "NaN"),
    (lambda: rf.simulate("ellipsoid:1,2,3", t_end=1, samples=3), ValueError, "omega=W or momentum=L"),
    (lambda: rf.simulate("ellipsoid:1,2,3", omega=[1, 2, 3], t_end=-1, samples=3), ValueError, "t_end"),
    (lambda: rf.simulate("ellipsoid:1,2,3", omega=[1, 2, 3], t_end=1, samples=1), ValueError, "samples"),
    (lambda: rf.simulate("ellipsoid:1,2,3", omega=[1, 2, 3], times=[0, 2, 1]), ValueError, "not increasing"),
    (lambda: rf.simulate("ellipsoid:1,2,3", omega=[1, 2, 3], times=[0, 1], integrator="euler"), ValueError, "unknown integrator"),
    (lambda: rf.simulate("ellipsoid:1,2,3", omega=[1, 2, 3], times=[0, 1], integrator="rk4", rtol=1e-6), ValueError, "rtol"),
    (lambda: rf.simulate("ellipsoid:1,2,3", omega=[1, 2, 3], times=[0, 1], dt=0.0), ValueError, "dt"),
    (lambda: rf.simulate("ellipsoid:1,2,3", omega=[1, 2, 3], times=[0, 1], torque="gravity:1"), ValueError, "unknown torque"),
    (lambda: rf.simulate("ellipsoid:1,2,3,4", omega=[1, 2, 3], axial=True, times=[0, 1]), ValueError, "axial needs N = 3"),
    (lambda: rf.exact("ellipsoid:1,2,3,4", omega=[1, 2, 3, 4, 5, 6], times=[0, 1]), ValueError, "no closed-form"),
]


@pytest.mark.parametrize("call, kind, words", BAD, ids=[b[2] for b in BAD])
def test_bad_bodies_and_runs(call, kind, words):
    with pytest.raises(kind) as info:
        call()
    assert words in str(info.value), str(info.value)


KEYS = {"dim", "planes", "times", "omega", "momentum", "energy", "casimirs", "attitude", "drift"}


def page_data(page):
    """The JSON the animation page draws from."""
    start = page.index('<script type="application/json" id="data">') + len('<script type="application/json" id="data">')
    return json.loads(page[start : page.index("</script>", start)])


def test_simulate_results_show_as_the_animation_of_the_body():
    body = rf.Body.cuboid([1, 2, 3])
    result = rf.simulate(body, omega=[0.1, 1.0, 0.2], t_end=2.0, samples=5)
    assert isinstance(result, dict) and set(result) == KEYS
    page = result.html()
    assert page.lstrip().lower().startswith("<!doctype html")
    assert '<canvas id="view"' in page
    data = page_data(page)
    # The cuboid's 8 corners and 12 edges, one frame per sample: the reported attitudes.
    assert (len(data["points"]), len(data["edges"]), data["dim"]) == (8, 12, 3)
    assert data["times"] == result["times"].tolist()
    np.testing.assert_allclose(np.reshape(data["frames"], (5, 3, 3)), result["attitude"], atol=1e-9)
    inline = result._repr_html_()
    assert inline.startswith('<iframe srcdoc="') and "&lt;canvas id=&quot;view&quot;" in inline
    assert '"' not in inline[len('<iframe srcdoc="') : inline.index('" style=')]
    # A closed form from a SPEC; a plain dict with the body given; a 2D body drawn in 3D.
    exact = rf.exact("cuboid:1,2,3", omega=[0.1, 1.0, 0.2], t_end=2.0, samples=5)
    assert set(exact) == KEYS
    assert rf.animation_html(dict(exact), "cuboid:1,2,3", title="t") == exact.html(title="t")
    with pytest.raises(ValueError, match="give the body"):
        rf.animation_html(dict(exact))
    with pytest.raises(ValueError, match="attitude"):
        rf.motion_html(body, exact["times"][:3], exact["attitude"])
    flat = rf.simulate(rf.Body.cuboid([1, 2]), omega=[1.0], t_end=1.0, samples=3)
    assert len(page_data(flat.html())["frames"][0]) == 9
    # Pickled: with its SPEC, or as the plain dict of numbers when the body is an object.
    again = pickle.loads(pickle.dumps(exact))
    assert type(again) is rf.Motion and again.body == "cuboid:1,2,3" and again.html() == exact.html()
    plain = pickle.loads(pickle.dumps(result))
    assert type(plain) is dict and set(plain) == KEYS
    np.testing.assert_array_equal(plain["attitude"], result["attitude"])
