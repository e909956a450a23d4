"""Sling plans check the hull girder too (they ignored ``[strength]`` silently).

The two-crane block (examples/block_sling_plan.toml) and the three-crane block on 2-leg slings
hinged about their pairs (examples/block_three_slings_plan.toml), each given a weight curve and
allowables: the plan's worst |M| and |Q| over the states it holds (its rigging scene solved at
every CG vertex x tilt along the hook line; x the tolerance box grid for three cranes) become
checks, equal ``solve`` of the plan's scene posed at the worst state, fail (exit 4) when an
allowable is too low, and are in the JSON and the written plan scene.

Weight curves: linear over the block's 16 m (x = -8..8 m), w(x) = W / L + 12 W x_G x / L^3, whose
integral is W and centroid x_G exactly: 180 t at x_G = 0.4 m -> 9.5625 .. 12.9375 t/m; 150 t at
x_G = 0.5 m -> 7.6171875 .. 11.1328125 t/m.
"""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest
from helpers import EXAMPLES
from support.cli import run

from liftplan.model import solve
from liftplan.model.errors import EquilibriumNotFound, InvalidScene
from liftplan.model.scene.file import loads_scene
from liftplan.model.scene.objects import Body, curve_totals
from liftplan.model.strength import strength_checks
from liftplan.planner import plan
from liftplan.planner.output.console.summary import summary
from liftplan.planner.output.report.slings import plan_scene_toml
from liftplan.planner.plans.girder import moved_body
from liftplan.planner.plans.slings import ApexSlingPlan
from liftplan.planner.plans.slings import lift as sling_lift
from liftplan.planner.problem.file import loads_problem

TWO_CURVE = "[[-8.0, 9.5625], [8.0, 12.9375]]"
THREE_CURVE = "[[-8.0, 7.6171875], [8.0, 11.1328125]]"
BODY_LINE = "cog = [{x}, 0.0, 1.3]          # m, body frame: x forward, y to port, z up (block bottom z = 0)"


def planning_text(example, cog_x, curve, bending=300.0, shear=100.0):
    """An example planning file with a weight curve and constant allowables [t m, t]."""
    text = (EXAMPLES / example).read_text(encoding="utf-8")
    line = BODY_LINE.format(x=cog_x)
    assert line in text
    text = text.replace(line, f"{line}\nweight_curve = {curve}")
    return (
        text
        + f"\n[strength]\nbending_moment = [[-8.0, {bending}], [8.0, {bending}]]\n"
        + f"shear_force = [[-8.0, {shear}], [8.0, {shear}]]\n"
    )


@pytest.fixture(scope="module")
def two():
    return plan(loads_problem(planning_text("block_sling_plan.toml", 0.4, TWO_CURVE)))


@pytest.fixture(scope="module")
def three():
    return plan(loads_problem(planning_text("block_three_slings_plan.toml", 0.5, THREE_CURVE)))


def _posed(result, cog_offset, boom_shifts):
    """The plan's rigging scene with the CG moved (its curve with it) and each boom tip raised."""
    scene = result.scene
    cranes = tuple(
        dataclasses.replace(c, boom_height=c.boom_height + d, tip=(c.tip[0], c.tip[1], c.tip[2] + d))
        for c, d in zip(scene.cranes, boom_shifts)
    )
    return dataclasses.replace(scene, body=moved_body(scene.body, cog_offset), cranes=cranes)


def _solved(result, worst):
    """solve's girder checks of the plan's scene at a GirderWorst's state, and the solve."""
    s = worst.scenario
    scene = _posed(result, s.cog_offset, s.boom_shifts)
    eq = solve(scene)
    return {c.name: c for c in strength_checks(scene, eq)}, eq


def _agrees_with_solve(result):
    """Each worst equals solve's check at its state: the same loads integrated the same way,
    so to rounding (rel 1e-9); the state's heel and trim are that solve's pose."""
    assert [w.name for w in result.girder] == ["bending_moment", "shear_force"]
    for worst in result.girder:
        solved, eq = _solved(result, worst)
        check = solved[worst.name]
        assert check.value == pytest.approx(worst.value, rel=1e-9)
        assert check.limit == pytest.approx(worst.allowable, rel=1e-12)
        assert eq.pose.heel == pytest.approx(worst.scenario.heel, abs=1e-9)
        assert eq.pose.trim == pytest.approx(worst.scenario.trim, abs=1e-9)
    return {w.name: w for w in result.girder}


def test_two_crane_sling_plan_checks_the_girder_as_solve_does(two):
    names = [c.name for c in two.checks]
    assert names.count("bending_moment") == 1 and names.count("shear_force") == 1
    worst = _agrees_with_solve(two)
    # measured: |M| 270.9 t m (90 %) at x = 0.33 m, |Q| 85.7 t (86 %) at the fwd lugs x = 7 m,
    # both with the CG at (+0.3, +0.2, -0.2) m off nominal, tilted 2 deg along the hook line
    # and rolled 1.14 deg about it
    bending, shear = worst["bending_moment"], worst["shear_force"]
    assert bending.value == pytest.approx(270.90, abs=0.01) and shear.value == pytest.approx(85.75, abs=0.01)
    assert shear.x == pytest.approx(7.0, abs=1e-9)
    assert bending.scenario.cog_offset == pytest.approx((0.3, 0.2, -0.2))
    assert abs(bending.scenario.trim) == pytest.approx(2.0, abs=0.05)
    assert all(c.ok for c in two.checks)


def test_two_crane_worst_is_the_largest_over_the_tilts_and_vertices(two):
    """Another construction of each state (crane 1 alone raised by the span x tan(tilt), as
    tests/planner/test_sling_legs_posed.py does): the same attitudes, so the largest |M| and
    |Q| of those 27 solves equal the plan's (rel 1e-9; the hooks 0.24 m higher, the same
    equilibrium: 1e-15 measured)."""
    tilt = two.tolerances[0]
    span = float(np.linalg.norm(two.chosen.apex[1, :2] - two.chosen.apex[0, :2]))
    largest = {"bending_moment": 0.0, "shear_force": 0.0}
    for offset in two.problem.cog_envelope.offsets():
        for angle in (-tilt, 0.0, tilt):
            scene = _posed(two, offset, (span * np.tan(np.radians(angle)), 0.0))
            for check in strength_checks(scene, solve(scene)):
                largest[check.name] = max(largest[check.name], check.value)
    for worst in two.girder:
        assert largest[worst.name] == pytest.approx(worst.value, rel=1e-9)


def test_apex_sling_plan_checks_the_girder_as_solve_does(three):
    assert type(three).__name__ == "ApexSlingPlan"
    assert {"bending_moment", "shear_force"} <= {c.name for c in three.checks}
    worst = _agrees_with_solve(three)
    # measured: |M| 177.3 t m (59 %) at x = -0.6 m, |Q| 57.6 t (58 %) at the aft lugs x = -7 m,
    # the CG at (-0.3, -0.2, -0.2) m off nominal, trim about +2 deg
    assert worst["bending_moment"].value == pytest.approx(177.3, abs=0.1)
    assert worst["shear_force"].value == pytest.approx(57.6, abs=0.1)
    states = len(three.hung)
    assert states == 81 * len(three.problem.cog_envelope.offsets())  # the worst legs' grid
    assert all(h.error is None for h in three.hung)


def test_apex_worst_is_not_exceeded_by_its_states(three):
    """Twelve of the plan's states solved on their own: none has a larger |M| or |Q|."""
    poses = list(three.held_poses)
    rng = np.random.default_rng(11)
    worst = {w.name: w.value for w in three.girder}
    for k in rng.choice(len(poses), 12, replace=False):
        scene = _posed(three, *poses[k])
        for check in strength_checks(scene, solve(scene)):
            assert check.value <= worst[check.name] * (1 + 1e-9)


def test_written_plan_scene_carries_the_curve_and_the_allowables(two):
    """plan_scene.toml solved: its girder is the plan's level, nominal-CG state's."""
    scene = loads_scene(plan_scene_toml(two))
    assert scene.body.weight_curve is not None and scene.strength == two.problem.strength
    level = next(h for h in two.hung if not any(h.state.cog_offset) and not any(h.state.boom_shifts))
    mine = strength_checks(level.scene, level.eq)
    written = strength_checks(scene, solve(scene))
    for a, b in zip(mine, written):
        assert a.name == b.name and a.value == pytest.approx(b.value, rel=1e-6)


def test_too_low_allowable_fails_exit_4_and_json_has_the_girder(tmp_path):
    path = tmp_path / "block.toml"
    path.write_text(planning_text("block_sling_plan.toml", 0.4, TWO_CURVE, bending=200.0), encoding="utf-8")
    out = run("plan", str(path), "--json")
    assert out.returncode == 4, out.stderr
    data = json.loads(out.stdout)
    girder = {g["check"]: g for g in data["girder"]}
    assert girder["bending_moment"]["value"] == pytest.approx(270.90, abs=0.01)
    assert girder["bending_moment"]["ratio"] > 1.0 and girder["shear_force"]["ratio"] < 1.0
    assert set(girder["bending_moment"]["at"]["boom_shifts"]) == {"Crawler FWD", "Crawler AFT"}
    failed = [c for c in data["checks"] if not c["ok"]]
    assert [c["name"] for c in failed] == ["bending_moment"]
    text = summary(plan(loads_problem(path.read_text(encoding="utf-8"))))  # what plan prints
    line = next(x for x in text.splitlines() if "bending moment |M|" in x)
    assert "270.9 t m" in line and "(135 %) FAIL" in line


def test_moved_body_moves_the_centroid_and_keeps_the_weight():
    body = Body(180.0, (0.4, 0.0, 1.3), weight_curve=((-8.0, 9.5625), (0.0, 11.25), (8.0, 12.9375)))
    moved = moved_body(body, (0.3, -0.2, 0.1))
    area, first = curve_totals(*moved.weight_curve_arrays)
    assert area == pytest.approx(180.0, rel=1e-12) and first / area == pytest.approx(0.7, abs=1e-12)
    assert moved.cog == pytest.approx((0.7, -0.2, 1.4))
    # a curve at 0 t/m at its aft end cannot move forward: refused with the reason
    light = Body(8.0, (8.0 / 3.0, 0.0, 1.0), weight_curve=((0.0, 0.0), (4.0, 4.0)))
    with pytest.raises(InvalidScene, match="weight_curve: moved with the CG"):
        moved_body(light, (0.1, 0.0, 0.0))


def test_allowables_without_a_weight_curve_are_refused():
    """[strength] with no body.weight_curve: refused with the reason, not ignored."""
    text = planning_text("block_sling_plan.toml", 0.4, TWO_CURVE).replace(f"weight_curve = {TWO_CURVE}\n", "")
    with pytest.raises(InvalidScene, match=r"\[strength\]: given without body.weight_curve"):
        loads_problem(text)
    # a held plan's too
    held = (EXAMPLES / "tanker_plan.toml").read_text(encoding="utf-8")
    allowable = "[strength]\nshear_force = [[0.0, 350.0], [82.05, 350.0]]\n\n"
    held = held.replace("[attitude]", allowable + "[attitude]", 1)
    with pytest.raises(InvalidScene, match=r"\[strength\]: given without body.weight_curve"):
        loads_problem(held)


def test_a_state_the_rigging_model_does_not_solve_fails_a_check(three, monkeypatch):
    """No number for it: the girder is the worst of the states solved, and a failed
    ``girder_states`` check names the one that was not."""
    poses = list(three.held_poses)[:3]
    monkeypatch.setattr(ApexSlingPlan, "held_poses", property(lambda self: poses))
    solve_rigging = sling_lift.solve_rigging

    def failing(scene):
        if scene.cranes[0].boom_height != three.scene.cranes[0].boom_height + poses[1][1][0]:
            return solve_rigging(scene)
        raise EquilibriumNotFound("rigging: no equilibrium (test)")

    monkeypatch.setattr(sling_lift, "solve_rigging", failing)
    fresh = dataclasses.replace(three)  # the same plan, nothing solved yet
    failed = [c for c in fresh.checks if not c.ok]
    assert [c.name for c in failed] == ["girder_states"]
    assert failed[0].title == "hull girder found at every state"
    assert failed[0].value == 1 and "1 of 3 states not solved" in failed[0].note
    assert "no equilibrium (test)" in failed[0].note
    solved = [h for h in fresh.hung if h.error is None]
    assert len(solved) == 2 and fresh.girder[0].scenario in [h.state for h in solved]
