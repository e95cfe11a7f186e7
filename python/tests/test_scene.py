"""Scenes against the command (`rotorflow scene ... --output`), scenes built in code, and the
inline animation."""

import json
import math
import subprocess
import tempfile
from pathlib import Path

import numpy as np
import pytest

import rotorflow as rf
from test_bodies import ROOT, same

SCENES = sorted((ROOT / "scenes").glob("*.toml"))


def command_scene(path, *flags):
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "run.json"
        subprocess.run(
            ["cargo", "run", "--release", "--quiet", "--", "scene", str(path), "--output", str(out), *flags],
            cwd=ROOT,
            check=True,
            capture_output=True,
        )
        return json.loads(out.read_text())


def test_every_scene_file_is_compared():
    assert len(SCENES) >= 5


@pytest.mark.parametrize("path", SCENES, ids=[p.name for p in SCENES])
def test_scene_equals_the_command(path):
    theirs = command_scene(path, "--samples", "6")
    ours = rf.scene(path, samples=6)
    same(ours, theirs)


def test_default_and_explicit_times_equal_the_command():
    path = ROOT / "scenes" / "tesseract-spring.toml"
    same(rf.scene(path), command_scene(path))
    same(rf.scene(path, times=[0.0, 0.25, 1.0]), command_scene(path, "--times", "0,0.25,1"))


DROP = {
    "dim": 3,
    "gravity": [0, 0, -9.81],
    "t_end": 1.0,
    "dt": 0.01,
    "body": [{"name": "ball", "shape": "ball:3,0.5", "position": [0, 0, 2]}],
}


def test_a_scene_built_in_code():
    scene = rf.Scene.from_dict(DROP)
    assert (scene.dim, scene.t_end) == (3, 1.0)
    run = scene.run(samples=11)
    data = run.data()
    z = data["bodies"][0]["position"][:, 2]
    t = data["times"]
    # Free fall: z = 2 - g t^2 / 2.
    np.testing.assert_allclose(z, 2.0 - 0.5 * 9.81 * t**2, atol=1e-12)
    text = 'dim = 3\ngravity = [0, 0, -9.81]\nt_end = 1.0\ndt = 0.01\n[[body]]\nname = "ball"\nshape = "ball:3,0.5"\nposition = [0, 0, 2]\n'
    same(rf.Scene.from_toml(text).run(samples=11).data(), data)
    assert json.loads(run.json())["times"] == list(t)


def test_the_animation_shows_inline():
    run = rf.Scene.from_dict(DROP).run(samples=5)
    page = run.html(title="drop")
    assert page.lstrip().lower().startswith("<!doctype html")
    assert "drop" in page
    inline = run._repr_html_()
    assert inline.startswith("<iframe srcdoc=")
    assert '"' not in inline[len('<iframe srcdoc="') : inline.index('" style=')]


def test_scene_errors():
    with pytest.raises(FileNotFoundError):
        rf.scene("/nonexistent/scene.toml")
    with pytest.raises(ValueError, match="dt must be > 0"):
        rf.Scene.from_toml("dim = 3\nt_end = 1\ndt = -1\n", "bad.toml")
    with pytest.raises(ValueError, match="bad.toml"):
        rf.Scene.from_toml("dim = 3\nt_end = 1\ndt = 0.1\nwobble = 2\n", "bad.toml")
    with pytest.raises(ValueError, match="scene"):
        rf.Scene.from_dict({"dim": 3, "t_end": math.nan, "dt": 0.1})
    with pytest.raises(ValueError, match="samples"):
        rf.Scene.from_dict(DROP).run(samples=1)
    with pytest.raises(ValueError, match="beyond t_end"):
        rf.Scene.from_dict(DROP).run(times=[0.0, 2.0])


# A 4D box of mass 1 resting on a bigger one of mass 16 on the floor w = 0, integrated by the
# soft step (contacts as stiff springs).
G, DT, M_BASE, M_TOP = 9.81, 0.01, 16.0, 1.0
STACK = {
    "dim": 4,
    "gravity": [0, 0, 0, -G],
    "t_end": 3.0,
    "dt": DT,
    "integrator": "soft",
    "body": [
        {"name": "base", "shape": "cuboid:0.5,0.5,0.5,0.5", "mass": M_BASE, "position": [0, 0, 0, 0.5], "friction": 0.5},
        {"name": "top", "shape": "cuboid:0.25,0.25,0.25,0.25", "mass": M_TOP, "position": [0.05, 0, 0, 1.5], "friction": 0.5},
    ],
    "plane": [{"normal": [0, 0, 0, 1], "friction": 0.5}],
}


def test_soft_step_stacks_two_boxes_at_rest():
    data = rf.Scene.from_dict(STACK).run(samples=4).data()
    assert data["integrator"] == "soft"
    base, top = data["bodies"]
    for body in (base, top):
        speed = np.linalg.norm(body["velocity"][-1])
        assert speed < 1e-6, f"{body['name']} moves at {speed:e}"
    # The springs of the soft contacts give a little: each box sits slightly inside what holds
    # it (the base's half-height is 0.5, the top's 0.25).
    base_sink = 0.5 - base["position"][-1][3]
    top_sink = base["position"][-1][3] + 0.5 + 0.25 - top["position"][-1][3]
    for name, sink in (("base", base_sink), ("top", top_sink)):
        assert 0.0 < sink < 1e-3, f"the {name} sank {sink:e}"
    # At rest, over the step that ended at the last sample, the floor carries the weight of
    # both boxes and the base that of the top: impulses (m g dt).
    floor = data["contacts"][-1]
    between = data["body_contacts"][-1]
    assert len(floor) > 0 and len(between) > 0
    assert all(c["body"] == 0 for c in floor), "only the base touches the floor"
    assert all((c["a"], c["b"]) == (0, 1) for c in between)
    weight = G * DT
    floor_impulse = sum(c["normal_impulse"] for c in floor)
    between_impulse = sum(c["normal_impulse"] for c in between)
    assert floor_impulse == pytest.approx((M_BASE + M_TOP) * weight, rel=1e-6, abs=0)
    assert between_impulse == pytest.approx(M_TOP * weight, rel=1e-6, abs=0)


def test_soft_step_refuses_joints():
    jointed = {
        "dim": 4,
        "t_end": 1.0,
        "dt": 0.1,
        "integrator": "soft",
        "body": [{"name": "cube", "shape": "tesseract:1,1,1,1"}],
        "joint": [{"body": "cube", "anchor": [0, 0, 0, 0]}],
    }
    with pytest.raises(ValueError, match='integrator "soft" holds no joints') as refused:
        rf.Scene.from_dict(jointed)
    assert 'integrator = "splitting"' in str(refused.value)
    # The same scene without the joint is accepted: the joint is what is refused.
    del jointed["joint"]
    assert rf.Scene.from_dict(jointed).dim == 4


def test_bodies_touch_with_their_contact_shape():
    # A body of a ball's inertia touching as a capsule, and a compound of two balls, both of
    # radius 0.2, come to rest on the floor at that radius; a contact of another dimension
    # is a ValueError naming the body.
    scene = {
        "dim": 3,
        "gravity": [0.0, 0.0, -9.81],
        "t_end": 2.0,
        "dt": 0.01,
        "body": [
            {"name": "capsule", "shape": "ball:3,0.3", "contact": "capsule:0.4,0.2", "position": [0.0, 0.0, 0.25]},
            {
                "name": "dumbbell",
                "shape": "ball:3,0.3",
                "contact": ["ball:0.2@-0.5,0,0", "ball:0.2@0.5,0,0"],
                "position": [0.0, 3.0, 0.25],
            },
        ],
        "plane": [{"normal": [0, 0, 1]}],
    }
    data = rf.Scene.from_dict(scene).run(samples=3).data()
    for body in data["bodies"]:
        assert body["position"][-1][2] == pytest.approx(0.2, abs=1e-9), body["name"]
        assert np.linalg.norm(body["velocity"][-1]) < 1e-9, body["name"]
    scene["body"][0]["contact"] = "box:0.2,0.2"
    with pytest.raises(ValueError, match='body "capsule".*a shape in 2 dimensions, expected 3'):
        rf.Scene.from_dict(scene)
