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
