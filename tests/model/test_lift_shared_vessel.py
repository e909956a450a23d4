"""The load curve with two cranes on one crane vessel (their ropes coupled through her heave,
heel and trim), and each vessel's heel, trim and freeboard limits followed along the curve."""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest
from helpers import EXAMPLES

from liftplan.model import solve
from liftplan.model.lift import EVENT_TOL, load_curve
from liftplan.model.scene.file import load_scene
from liftplan.model.statics.floating import solve_coupled
from liftplan.model.water import WaterSetup, submerged_scene
from liftplan.planner import cli

BARGE = EXAMPLES / "sunken_block_barge.toml"


def _shared(flotation_x, max_heel=3.0):
    """The sunken block with L1 and L2 on one crane barge heading to starboard (-y)
    (``examples/sunken_block_barge.toml``), her flotation centre ``flotation_x`` along the
    block, 45 m to port of it."""
    scene = load_scene(BARGE)
    barge = dataclasses.replace(scene.cranes[0].vessel, flotation=(flotation_x, 45.0), max_heel=max_heel)
    return scene.with_crane("L1", vessel=barge)


def _raised(scene, hoist):
    cranes = tuple(dataclasses.replace(c, boom_height=c.boom_height + hoist) for c in scene.cranes)
    return dataclasses.replace(scene, cranes=cranes)


def _barge_heel(scene, tensions):
    """The barge's heel [deg] from its two hook loads, written out: T y_t / (disp GM_T) with
    y_t = -(x - x_f) to starboard for a barge heading -y."""
    vessel = scene.cranes[0].vessel
    lugs = {g.name: g.at for g in scene.lugs}
    moment = sum(tensions[n] * -(lugs[n][0] - vessel.flotation[0]) for n in ("L1", "L2"))
    return math.degrees(moment / (vessel.displacement * vessel.gm_t))


def test_two_cranes_on_one_vessel_follow_solve_along_the_curve():
    """At hoists on the ground, at lift-off's bracket and hanging: the curve's tensions equal
    solve of the scene with every boom raised by the hoist to 1e-6 W, the barge's heel its
    closed form from the two hook loads; hanging submerged, the in-air Newton on body and vessels
    gives them too; the coupling matters (the same barge copied under each crane gives other
    tensions)."""
    scene = _shared(30.0)
    curve = load_curve(scene, stop=1.0, step=0.25)
    assert not curve.failed and curve.lift_off is not None
    w = scene.body.weight
    states = set()
    for k in range(0, len(curve.hoist), 2):
        eq = solve(_raised(scene, float(curve.hoist[k])), model="hydrostatic")
        assert list(eq.tensions.values()) == pytest.approx(curve.tensions[k], abs=1e-6 * w)
        assert eq.pose.heel == pytest.approx(curve.heel[k], abs=1e-6)
        heel = curve.vessels["Barge"]["heel"][k]
        assert heel == pytest.approx(eq.vessels["Barge"].heel, abs=1e-6)
        assert heel == pytest.approx(_barge_heel(scene, curve.equilibria[k].tensions), abs=1e-9)
        states.add(curve.state[k])
    assert {"grounded", "hanging submerged"} <= states
    # hanging submerged, the hull is a constant force (W - B at its centre): the in-air Newton on
    # the body and the vessels' heave, heel and trim as unknowns (another implementation of the
    # coupling) gives the last hoist's tensions
    last = len(curve.hoist) - 1
    assert curve.state[last] == "hanging submerged"
    hanging = submerged_scene(WaterSetup(_raised(scene, float(curve.hoist[last]))))
    full = solve_coupled(hanging, reduced=False)
    assert "on the ropes' coupled stiffness" not in full.solver.method
    assert list(full.tensions.values()) == pytest.approx(curve.tensions[last], abs=1e-6 * w)
    own = scene.with_crane("L2", vessel=scene.cranes[0].vessel)  # a barge of its own
    apart = load_curve(own, stop=1.0, step=1.0)
    assert abs(apart.tensions[-1] - curve.tensions[-1]).max() > 1e-3 * w


def test_a_heel_limit_broken_midway_is_flagged_where_it_is_first_broken():
    """The barge heels more as the block comes off: |heel| passes max_heel = 0.4 deg while it
    is on the ground. The curve reports the hoist, bisected to 0.1 mm: solve just below it
    is within the limit and just above it beyond; the check fails; the rows say where."""
    scene = _shared(5.0, max_heel=0.4)
    curve = load_curve(scene, stop=1.0, step=0.25)
    (limit,) = [m for m in curve.vessel_limits if m.vessel == "Barge"]
    assert not limit.ok and limit.check == "vessel_heel"
    assert 0.0 < limit.first_broken < 1.0 and limit.tolerance <= EVENT_TOL / 2
    below = solve(_raised(scene, limit.first_broken - limit.tolerance - 1e-5), model="hydrostatic")
    above = solve(_raised(scene, limit.first_broken + limit.tolerance + 1e-5), model="hydrostatic")
    assert abs(below.vessels["Barge"].heel) <= 0.4 < abs(above.vessels["Barge"].heel)
    assert limit.worst == pytest.approx(np.abs(curve.vessels["Barge"]["heel"]).max())
    (check,) = [c for c in curve.checks if c.subject == "Barge"]
    assert not check.ok and check.name == "vessel_heel" and "first broken at hoist" in check.note
    assert all(c.ok for c in curve.checks if c.subject != "Barge")
    within = [row["vessel_within_limits_Barge"] for row in curve.rows()]
    flips = [k for k in range(1, len(within)) if within[k] != within[k - 1]]
    assert len(flips) == 1 and curve.hoist[flips[0] - 1] < limit.first_broken < curve.hoist[flips[0]]
    data = curve.to_json()
    assert data["vessel_limits"][0]["first_broken_hoist"] == limit.first_broken
    assert any(c["name"] == "vessel_heel" and not c["ok"] for c in data["checks"])


def test_the_lift_command_exits_4_on_a_broken_vessel_limit(tmp_path, capsys):
    """`liftplan lift` prints the broken limit with its first hoist (console) and in JSON, and
    exits 4; the same barge within its limit exits 0."""
    text = BARGE.read_text()
    assert "max_heel = 0.4" in text
    for limit, code, json_out in (("0.4", 4, False), ("3.0", 0, True)):
        path = tmp_path / f"barge_{code}.toml"
        path.write_text(text.replace("max_heel = 0.4", f"max_heel = {limit}"))
        argv = [
            "lift",
            str(path),
            "--to",
            "1.0",
            "--step",
            "0.5",
            "--figure",
            str(tmp_path / f"curve_{code}.png"),
        ]
        assert cli.main(argv + (["--json"] if json_out else [])) == code
        out = capsys.readouterr().out
        if json_out:
            data = json.loads(out)
            assert [m["ok"] for m in data["vessel_limits"] if m["vessel"] == "Barge"] == [True]
            assert data["curve"][0]["vessel_within_limits_Barge"] is True
        else:
            assert "FAIL |heel| <= 0.4 deg broken first at hoist 0.37" in out
