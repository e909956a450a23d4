"""The tide over the operation: floating cranes and the water rise with it (a tidal lift)."""

from __future__ import annotations

import dataclasses
import json

import pytest
from helpers import EXAMPLES
from support.cli import run

from liftplan.model import solve
from liftplan.model.errors import InvalidScene
from liftplan.model.scene.file import load_scene, loads_scene
from liftplan.model.scene.tide import Tide
from liftplan.model.scene.writer import scene_toml

TIDAL = EXAMPLES / "sunken_block_tide.toml"


def _at(scene, time):
    return dataclasses.replace(scene, tide=dataclasses.replace(scene.tide, time=time))


def test_the_tide_raises_the_floating_tips_and_the_water():
    """At 3 h (0.85 m up) the solve equals the same scene without a tide, its floating cranes'
    boom heights and its water level raised by 0.85 m, to 1e-9 t; a crane without a vessel
    stays where it is."""
    scene = _at(load_scene(TIDAL), 3.0)
    assert scene.tide.rise == pytest.approx(0.85, abs=1e-12)  # 0.5 + (1.2 - 0.5) / 2
    mixed = scene.with_crane("L3", vessel=None)
    for case in (scene, mixed):
        raised = dataclasses.replace(
            case,
            tide=None,
            cranes=tuple(
                dataclasses.replace(c, boom_height=c.boom_height + 0.85) if c.vessel is not None else c
                for c in case.cranes
            ),
            water=dataclasses.replace(case.water, level=case.water.level + 0.85),
        )
        a, b = solve(case), solve(raised)
        assert a.tide.rise == pytest.approx(0.85, abs=1e-12)
        for name in case.lug_names:
            assert a.tensions[name] == pytest.approx(b.tensions[name], abs=1e-9)
    assert solve(mixed).tensions["L3"] != pytest.approx(solve(scene).tensions["L3"], abs=1.0)


def test_tidal_lift():
    """The rising tide lifts the block off the seabed: the ground reaction falls as the water
    rises and is gone by 2 h; from then the block hangs, rising with the tide, its tensions
    unchanged."""
    scene = load_scene(TIDAL)
    states = [solve(_at(scene, t)) for t in (0.0, 1.0, 2.0, 4.0)]
    reactions = [eq.afloat.ground_reaction for eq in states]
    assert reactions[0] > reactions[1] > 0.0 == reactions[2] == reactions[3]
    assert states[0].afloat.state == "grounded" and states[2].afloat.state == "hanging submerged"
    for name in scene.lug_names:
        assert states[3].tensions[name] == pytest.approx(states[2].tensions[name], abs=1e-6)
    assert states[3].pose.lift_height - states[2].pose.lift_height == pytest.approx(1.2 - 0.5, abs=1e-6)


def test_tide_json_refusals_and_writer(tmp_path):
    """solve --json carries the tide; a time outside the table is refused in one line; a scene
    in air with a tide writes and reads back."""
    path = tmp_path / "tide.toml"
    path.write_text(TIDAL.read_text().replace("time = 0.0", "time = 4.0"))
    out = run("solve", str(path), "--json")
    assert out.returncode == 0, out.stderr
    assert json.loads(out.stdout)["tide"] == {"time": 4.0, "level": 1.2, "rise": pytest.approx(1.2)}
    with pytest.raises(InvalidScene, match=r"tide.time = 7.0: outside the table \(0 to 6 h\)"):
        loads_scene(TIDAL.read_text().replace("time = 0.0", "time = 7.0"))
    with pytest.raises(InvalidScene, match="times increasing"):
        Tide(table=((0.0, 0.0), (0.0, 1.0)))
    floating = load_scene(EXAMPLES / "tanker_floating.toml")
    tide = dataclasses.replace(floating, tide=Tide(table=((0.0, 0.0), (6.0, 1.5)), time=2.0))
    assert loads_scene(scene_toml(tide)) == tide
    # every crane floats: the body rises with the tide, its tensions unchanged
    a, b = solve(floating), solve(tide)
    assert b.pose.lift_height - a.pose.lift_height == pytest.approx(0.5, abs=1e-9)
    assert b.tensions == pytest.approx(a.tensions, abs=1e-9)
