"""Plans with floating cranes: the vessels in series with the ropes, checked by the model.

The tanker fleet on its vessels (``examples/tanker_floating_fleet.toml``) is planned once: its
scene (each crane with its vessel and its rope's own EA) solves, by the coupled ``elastic``
model, to the plan's level tensions, and the vessels' heel, trim and tip drop there are the
plan's; the worst-case heel is checked against the limit.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from helpers import EXAMPLES

from liftplan.model import solve
from liftplan.model.errors import InvalidScene
from liftplan.model.scene.file import loads_scene
from liftplan.model.scene.wind import GRAVITY, Wind, WindArea
from liftplan.model.scene.writer import scene_toml
from liftplan.planner.output.report.held import _vessel_section
from liftplan.planner.plan import plan
from liftplan.planner.plans.vessel_loads import VesselPlan
from liftplan.planner.problem.file import load_problem, loads_problem
from liftplan.planner.problem.vessels import reference_problem, series_problem, tip_compliance, wind_problem


@pytest.fixture(scope="module")
def floating():
    problem = load_problem(EXAMPLES / "tanker_floating_fleet.toml")
    return problem, plan(problem)


def test_the_plan_scene_solves_to_the_plan_with_its_vessels(floating):
    """The plan's boom heights with each vessel in series: the coupled elastic solve of its
    scene gives the plan's level tensions (to 1e-6 t), and each vessel's heel, trim and tip
    drop there equal the plan's report (to 1e-6)."""
    _, result = floating
    scene = result.scene
    assert all(c.vessel is not None for c in scene.cranes)
    assert {c.EA for c in scene.cranes} == {80000.0, 40000.0}  # the ropes' own EA
    eq = solve(scene)
    for label, tension in result.tensions.items():
        assert eq.tensions[label] == pytest.approx(tension, abs=1e-6)
    assert eq.pose.lift_height == pytest.approx(result.problem.lift_height, abs=1e-9)
    for v in result.vessels:
        state = eq.vessels[v.label]
        assert state.heel == pytest.approx(v.heel, abs=1e-6)
        assert state.trim == pytest.approx(v.trim, abs=1e-6)
        assert state.tip_drop == pytest.approx(v.tip_drop, abs=1e-6)
        assert state.levelling_ballast == pytest.approx(v.ballast, abs=1e-3)
        # at the level tension, the levelling ballast set, the deck lies level: the plan's worst
        # freeboard is at most the heave's alone
        vessel = next(c.vessel for c in scene.cranes if c.vessel_name == v.label)
        level = vessel.lowest_freeboard(state.heave, 0.0, 0.0)
        assert v.freeboard <= level + 1e-12
    # the plan's scene file carries the vessels, in the planning file's frame
    named = result.named_scene
    assert loads_scene(scene_toml(named)) == named


def test_the_plan_is_exact_for_its_lugs_and_the_vessels_matter(floating):
    """The plan's problem has each vessel in series at the lug its crane took (the compliance
    from the closed form); the reference problem the search used is stiffer; the plan's
    twist stiffness is less than the same lugs' on land."""
    problem, result = floating
    chosen = result.chosen
    for i, j in zip(chosen.indices, chosen.cranes):
        crane, given = result.problem.fleet[j], problem.fleet[j]
        c = float(tip_compliance(given.vessel, problem.plan_points[i])[0])
        assert crane.EA == pytest.approx(given.rope_length / (given.rope_length / given.EA + c), rel=1e-12)
        assert crane.rope_EA == given.EA
        assert reference_problem(problem).fleet[j].EA >= crane.EA * (1 - 1e-12)
    exact = series_problem(problem, chosen.indices, chosen.cranes)
    assert exact.fleet == result.problem.fleet
    land = dataclasses.replace(
        problem, fleet=tuple(dataclasses.replace(c, vessel=None) for c in problem.fleet)
    )
    on_land = plan(land)
    assert result.twist_stiffness < on_land.twist_stiffness


def test_worst_heel_is_checked_against_the_limit(floating):
    """A vessel's worst heel over the box and the hook errors, its levelling ballast set, is
    (T - T0) y_t / (disp GM_T) at the rope's extreme tension; a limit below it fails the check."""
    _, result = floating
    v = result.vessels[0]
    fleet = {c.name: c for c in result.problem.fleet}
    vessel = fleet[v.crane].vessel
    swing = max(abs(v.worst_load[1] - v.load), abs(v.worst_load[0] - v.load))
    assert v.worst_heel == pytest.approx(
        math.degrees(swing * abs(v.offset[1]) / vessel.heel_stiffness), rel=1e-12
    )
    assert v.ballast == pytest.approx((-v.load * v.offset[1], -v.load * v.offset[0]), rel=1e-12)
    tight = dataclasses.replace(v, max_heel=0.5 * v.worst_heel)
    assert [c.ok for c in tight.checks()] == [False, True, True]
    names = ("vessel_heel", "vessel_trim", "vessel_freeboard")
    assert {(c.name, c.subject) for c in result.checks if c.name.startswith("vessel_")} == {
        (name, crane.name) for crane in result.problem.fleet for name in names
    }
    assert isinstance(v, VesselPlan)
    # the worst freeboard, closed form: least at the rope's lowest or highest tension
    corners = [
        vessel.freeboard
        - t / vessel.heave_stiffness
        - vessel.beam / 2 * abs((t - v.load) * v.offset[1]) / vessel.heel_stiffness
        - vessel.length / 2 * abs((t - v.load) * v.offset[0]) / vessel.trim_stiffness
        for t in v.worst_load
    ]
    assert v.freeboard == pytest.approx(min(corners), rel=1e-12)
    assert 1.0 < v.freeboard < vessel.freeboard
    low = dataclasses.replace(v, min_freeboard=v.freeboard + 0.01)
    assert [c.ok for c in low.checks() if c.name == "vessel_freeboard"] == [False]
    assert np.all([c.ok for c in result.checks])


def test_the_report_and_json_carry_the_vessels(floating):
    """plan --json's "vessels" and the report's crane-vessel table name every floating crane."""
    _, result = floating
    data = result.to_json()
    assert set(data["vessels"]) == {c.name for c in result.problem.fleet}
    for entry in data["vessels"].values():
        assert {"tip_drop", "extra_hoist", "ballast", "worst_heel", "worst_trim", "freeboard"} <= set(entry)
    html = "".join(_vessel_section(result))
    assert "Crane vessels" in html
    assert all(c.name in html for c in result.problem.fleet)


def test_wind_in_the_plan_widens_the_cg_envelope_and_the_hook_tolerances():
    """Wind from any direction: the body's couple F (h - h_lugs) / W widens the CG envelope in
    plan; a floating crane's boom wind moves its tip by up to F h sqrt((y_t / (disp GM_T))^2 +
    (x_t / (disp GM_L))^2), added to its hook tolerance at its lug (the most over its reach in
    the search's reference problem); a direction, or a boom on land, is refused in one line."""
    problem = load_problem(EXAMPLES / "tanker_floating_fleet.toml")
    boom = WindArea(area=150.0, cd=1.5, height=55.0, crane="Sheerleg A")
    wind = Wind(speed=20.0, body=WindArea(area=450.0, cd=1.2, height=9.0), booms=(boom,))
    windy = dataclasses.replace(problem, wind=wind)
    widened = wind_problem(windy)
    force = 0.5 * 1.225e-3 * 1.2 * 450.0 * 400.0 / GRAVITY
    shift = force * (9.0 - 6.0) / problem.body.weight  # the candidates at 6 m
    x, y, z = problem.cog_envelope.half_widths
    assert widened.cog_envelope.half_widths == pytest.approx((x + shift, y + shift, z), abs=1e-12)
    j = [c.name for c in problem.fleet].index("Sheerleg A")
    i = [c.name for c in problem.candidates].index("BH4-P")
    exact = series_problem(widened, (i,), (j,)).fleet[j]
    vessel = problem.fleet[j].vessel
    forward, starboard = vessel.axes(problem.plan_points[i])
    moment = 0.5 * 1.225e-3 * 1.5 * 150.0 * 400.0 / GRAVITY * 55.0
    error = moment * math.hypot(starboard / vessel.heel_stiffness, forward / vessel.trim_stiffness)
    assert exact.hook_tolerance == pytest.approx(problem.hook_tolerance + error, rel=1e-12)
    assert reference_problem(widened).fleet[j].hook_tolerance >= exact.hook_tolerance
    text = (
        EXAMPLES / "tanker_floating_fleet.toml"
    ).read_text() + "\n[wind]\nspeed = 20.0\ndirection = 90.0\n"
    with pytest.raises(InvalidScene, match="a plan takes the wind from any direction"):
        loads_problem(text)
    land = dataclasses.replace(windy, fleet=tuple(dataclasses.replace(c, vessel=None) for c in problem.fleet))
    with pytest.raises(InvalidScene, match=r"wind.booms\[Sheerleg A\]: the crane stands on land"):
        wind_problem(land)
