"""Lift off the seabed and through the waterline; the least model equals the fuller one."""

import dataclasses
import json
import subprocess
import sys

import numpy as np
import pytest
from helpers import EXAMPLES, example
from numpy.testing import assert_allclose

from liftplan.model import solve
from liftplan.model.lift import load_curve
from liftplan.model.scene.hull import Hull
from liftplan.model.scene.objects import Body, Scene, Water
from liftplan.model.water import solve_in_water

RHO = 1.025


@pytest.fixture(scope="module")
def curve():
    return load_curve(example("sunken_block_lift"), step=0.5)


def test_load_curve_balances_and_phases(curve):
    """Every step: rope tensions + buoyancy + ground reaction = W + trapped water.
    Grounded first, then hanging submerged (constant loads), piercing the surface, then
    clear of the water where the ropes carry the weight plus the trapped water."""
    scene = example("sunken_block_lift")
    trapped = RHO * 6 * 12 * 2  # the aft tank's water, a weight carried at every hoist
    assert_allclose(curve.trapped_water, trapped, rtol=1e-12)  # sum of one box's volume
    total = curve.tensions.sum(axis=1) + curve.buoyancy + curve.ground_reaction
    # the solves close the forces to 1e-9 W (RESIDUAL_TOL); 1e-9 relative leaves round-off room
    assert_allclose(total, scene.body.weight + trapped, rtol=1e-9)
    assert curve.state[0] == "grounded" and curve.state[-1] == "clear"
    order = ["grounded", "hanging submerged", "piercing the surface", "clear"]
    assert [s for k, s in enumerate(curve.state) if k == 0 or s != curve.state[k - 1]] == order
    assert curve.failed == ()
    steel = scene.body.weight / 7.85  # m3, flooded hull: steel only
    air = 5 * 12 * 2  # the intact fore tank
    submerged = [k for k, s in enumerate(curve.state) if s == "hanging submerged"]
    # submerged, both tanks displace water (the trapped tank's part cancels its weight)
    assert_allclose(curve.buoyancy[submerged], RHO * (steel + air + 6 * 12 * 2), rtol=1e-9)
    clear = [k for k, s in enumerate(curve.state) if s == "clear"]
    assert np.all(curve.buoyancy[clear] == 0.0)
    assert_allclose(curve.tensions[clear].sum(axis=1), scene.body.weight + trapped, rtol=1e-9)
    m = curve.max_load
    assert m.tension == curve.tensions.max()
    assert m.lug == curve.lugs[int(np.argmax(curve.tensions.max(axis=0)))]
    assert len(m.plateau) == 1 and m.plateau[0][0] > 15.0 and m.to_end


def test_lift_cli_writes_figure_and_json(tmp_path):
    figure = tmp_path / "curve.png"
    out = subprocess.run(
        [
            sys.executable,
            "-m",
            "liftplan.planner.cli",
            "lift",
            str(EXAMPLES / "sunken_block_lift.toml"),
            "--step",
            "1",
            "--json",
            "--figure",
            str(figure),
        ],
        capture_output=True,
        text=True,
        check=True,
    )
    data = json.loads(out.stdout)
    assert data["max_load"]["lug"] in data["lugs"] and data["lift_off"] is not None
    assert [e["event"] for e in data["events"]] == ["lift-off", "surface", "clear"]
    assert data["lift_off"] == data["events"][0]["hoist"]
    (plateau,) = data["max_load"]["plateau"]
    assert plateau["from"] < plateau["to"] and "hoist" not in data["max_load"]
    assert data["trapped_water"] > 0 and min(r["buoyancy"] for r in data["curve"]) >= 0.0
    assert figure.stat().st_size > 10_000


def hanging(hoist_height):
    """The sunken block hanging free (no ground) with its hooks at a given height."""
    scene = example("sunken_block_lift")
    cranes = tuple(dataclasses.replace(c, boom_height=hoist_height) for c in scene.cranes)
    return dataclasses.replace(scene, ground=None, cranes=cranes)


def test_least_model_submerged_equals_clipped():
    """Fully submerged and hanging: solve() picks constant buoyancy (the rope model with
    the submerged weight and centre), and it equals the clipped-hull solve."""
    scene = hanging(36.0)
    least = solve(scene)
    full = solve_in_water(scene)
    assert least.model == "submerged" and full.model == "hydrostatic"
    assert_allclose(list(least.tensions.values()), list(full.tensions.values()), rtol=1e-9, atol=1e-8)
    assert_allclose(
        (least.pose.heel, least.pose.trim, least.pose.lift_height),
        (full.pose.heel, full.pose.trim, full.pose.lift_height),
        atol=1e-9,
    )
    assert least.afloat.buoyancy == pytest.approx(full.afloat.buoyancy, rel=1e-12)


@pytest.mark.parametrize("hook", [36.0, 50.0, 52.0, 60.0])
def test_hanging_submerged_piercing_and_clear(hook):
    """Hooks from deep (fully submerged) to high (clear): each solves and balances."""
    eq = solve(hanging(hook))
    a = eq.afloat
    # forces closed to 1e-9 W by the solve's acceptance
    assert_allclose(sum(eq.tensions.values()) + a.buoyancy, eq.weight + a.trapped_water, rtol=1e-9)
    expected = {36.0: "hanging submerged", 50.0: "piercing the surface", 52.0: "clear", 60.0: "clear"}
    assert a.state == expected[hook]


def test_no_water_scene_equals_rope_model_with_water_far_below():
    """No [water]: no hydrostatics. The same scene with the water far below the hull
    (clear) gives the same tensions."""
    scene = hanging(60.0)
    low = dataclasses.replace(scene, water=Water(density=RHO, level=-1000.0))
    dry = dataclasses.replace(scene, water=None, hull=None)
    wet, rope = solve(low), solve(dry)
    assert rope.model == "elastic"
    # the trapped water's weight is carried in the hull scene: add it to the dry body
    trapped = RHO * 6 * 12 * 2
    body = scene.body
    cog = (body.weight * np.array(body.cog) + trapped * np.array([3.0, 0.0, 1.0])) / (body.weight + trapped)
    heavy = solve(dataclasses.replace(dry, body=Body(body.weight + trapped, tuple(cog))))
    assert_allclose(list(wet.tensions.values()), list(heavy.tensions.values()), rtol=1e-9)


def test_deck_awash_floating_box():
    """Weight equal to the whole hull's displacement: it floats with the deck exactly at
    the surface (the volume's derivative jumps there)."""
    box = Hull.box([-5, -2, -1], [5, 2, 1])
    scene = Scene(body=Body(RHO * 80.0, (0.0, 0.0, -0.2)), water=Water(RHO, 0.0), hull=box)
    eq = solve(scene)
    assert eq.pose.lift_height == pytest.approx(-1.0, abs=1e-6)
    assert eq.afloat.displaced_volume == pytest.approx(80.0, rel=1e-6)
    assert eq.afloat.state == "afloat" and eq.afloat.buoyancy == pytest.approx(eq.weight, rel=1e-9)
