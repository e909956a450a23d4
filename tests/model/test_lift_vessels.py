"""The load curve with floating cranes: each rope in series with its vessel at every hoist."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from helpers import EXAMPLES

from liftplan.model import solve
from liftplan.model.errors import InvalidScene
from liftplan.model.lift import load_curve
from liftplan.model.scene.file import load_scene


def _barges():
    """The sunken block on its four crane barges, at the tide table's first time."""
    return dataclasses.replace(load_scene(EXAMPLES / "sunken_block_tide.toml"), tide=None)


def test_the_load_curve_follows_the_crane_vessels():
    """At each hoist s of the curve, solve of the scene with every boom raised by s (the
    hydrostatic model, vessels in series) gives the curve's tensions and pose, and each
    vessel's heel is the closed form T y_t / (disp GM_T); the rows carry the vessels; the
    vessels soften the ropes (the curve differs from the same cranes on land)."""
    scene = _barges()
    curve = load_curve(scene, stop=0.6, step=0.3)
    assert len(curve.hoist) >= 3 and not curve.failed
    for k in (0, len(curve.hoist) - 1):
        s = float(curve.hoist[k])
        raised = dataclasses.replace(
            scene, cranes=tuple(dataclasses.replace(c, boom_height=c.boom_height + s) for c in scene.cranes)
        )
        eq = solve(raised, model="hydrostatic")
        assert list(eq.tensions.values()) == pytest.approx(curve.tensions[k], abs=1e-6 * scene.body.weight)
        assert eq.pose.heel == pytest.approx(curve.heel[k], abs=1e-6)
        for name, state in curve.equilibria[k].vessels.items():
            assert curve.vessels[name]["heel"][k] == pytest.approx(eq.vessels[name].heel, abs=1e-6)
            vessel, (i,) = scene.vessels[name]
            lug = scene.cranes[i].lug
            _, starboard = vessel.axes(tuple(scene.lug_points()[i, :2]))
            t = curve.equilibria[k].tensions[lug]
            assert state.heel == pytest.approx(
                math.degrees((t * starboard + vessel.ballast[0]) / vessel.heel_stiffness), rel=1e-9
            )
    row = curve.rows()[-1]
    name = next(iter(curve.vessels))
    assert row[f"vessel_tip_drop_{name}"] == pytest.approx(curve.vessels[name]["tip_drop"][-1])
    assert "vessel_freeboard_" + name not in row  # no freeboard given
    vessel, (i,) = scene.vessels[name]
    deck = dataclasses.replace(vessel, freeboard=2.0, beam=30.0, length=60.0)
    series = load_curve(scene.with_crane(scene.cranes[i].lug, vessel=deck), stop=0.3, step=0.3).vessels[name]
    corner = 15.0 * np.abs(np.radians(series["heel"])) + 30.0 * np.abs(np.radians(series["trim"]))
    assert series["freeboard"] == pytest.approx(2.0 - series["heave"] - corner, rel=1e-9)
    land = dataclasses.replace(scene, cranes=tuple(dataclasses.replace(c, vessel=None) for c in scene.cranes))
    on_land = load_curve(land, stop=0.6, step=0.3)
    assert abs(on_land.tensions[-1] - curve.tensions[-1]).max() > 1e-3


def test_the_load_curve_refuses_what_it_does_not_follow():
    """A tide or a wind: refused in one line (two cranes on one vessel are followed:
    tests/model/test_lift_shared_vessel.py)."""
    scene = load_scene(EXAMPLES / "sunken_block_tide.toml")
    with pytest.raises(InvalidScene, match=r"lift: \[tide\] is not followed through a load curve"):
        load_curve(scene, stop=0.3, step=0.3)
