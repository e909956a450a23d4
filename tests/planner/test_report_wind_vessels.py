"""Review findings 8 and 9: the floating-crane report shows the wind and the ropes' own EA.

The tanker fleet on its vessels (``examples/tanker_floating_fleet.toml``) on six of its
candidates, with a wind of 20 m/s on the body and on Sheerleg A's boom. The report's basis
table gives the wind's speed, direction, the body's force, the CG envelope's widening and the
boom's tip error, as ``--json`` ``wind`` does; the assumptions say it. The "Crane fleet" table
gives each rope's EA as the file writes it (80000 / 40000 t), and the series stiffness of rope
and vessel at the planned lug in its own, named column; the assumptions put the vessel in series.
Then finding 3 with floating cranes: a capacity of BH1-S (250 t) that the search's best set overloads
(264.2 t; the next, the same lugs with Sheerleg B and Crane D swapped, 233.1 t) moves the
plan to the next set, and the plan's problem is that set's own series problem.
"""

from __future__ import annotations

import dataclasses
import html
import re

import pytest
from helpers import EXAMPLES

from liftplan.model.scene.wind import Wind, WindArea
from liftplan.planner.output.report.held import _assumptions, _basis
from liftplan.planner.plan import plan
from liftplan.planner.problem.file import load_problem
from liftplan.planner.problem.vessels import series_problem, wind_problem

KEEP = {"BH1-S", "BH4-P", "BH5-S", "BH8-S", "BH3-P", "BH4-S"}
ROPE_EA = {"Sheerleg A": 80000.0, "Sheerleg B": 80000.0, "Crane C": 40000.0, "Crane D": 40000.0}


def _problem(**changes):
    problem = load_problem(EXAMPLES / "tanker_floating_fleet.toml")
    boom = WindArea(area=150.0, cd=1.5, height=55.0, crane="Sheerleg A")
    wind = Wind(speed=20.0, body=WindArea(area=450.0, cd=1.2, height=9.0), booms=(boom,))
    candidates = tuple(c for c in problem.candidates if c.name in KEEP)
    return dataclasses.replace(problem, candidates=candidates, top=2, wind=wind, **changes)


@pytest.fixture(scope="module")
def windy():
    return plan(_problem())


def _rows(page, caption):
    """The rows of the table with that caption start, as lists of cell texts."""
    table = page.split(f"<caption>{caption}")[1].split("</table>")[0]
    rows = re.findall(r"<tr>(.*?)</tr>", table, flags=re.S)
    return [
        [html.unescape(re.sub(r"<[^>]+>", "", c)) for c in re.findall(r"<t[dh][^>]*>(.*?)</t[dh]>", r)]
        for r in rows
    ]


def test_the_basis_and_assumptions_show_the_wind(windy):
    data = windy.to_json()["wind"]
    page = "".join(_basis(windy))
    rows = {r[0]: r[1:] for r in _rows(page, "Inputs")}
    assert rows["wind speed"] == ["20", "m/s"]
    assert rows["wind direction"][0].startswith("any")
    assert rows["wind force on the body"] == [f"{data['body_force']:.2f}", "t"]
    assert rows["CG envelope widened in plan by the wind's couple"] == [f"{data['cog_widening']:.3f}", "m"]
    assert data["cog_widening"] > 0.01
    boom = data["booms"]["Sheerleg A"]
    key = "wind on Sheerleg A's boom: force, its tip error added to the hook tolerance"
    assert rows[key][0] == f"{boom['force']:.2f} t, +-{boom['hook_error']:.3f} m"
    # the hook tolerance row gives each hook's own, Sheerleg A's with its tip error
    label = next(k for k, v in windy.cranes.items() if v == "Sheerleg A")
    own = windy.hook_tolerances[label]
    assert own == pytest.approx(windy.problem.hook_tolerance + boom["hook_error"], rel=1e-12)
    assert f"{label} (Sheerleg A) +-{own:.3g}" in rows["hook-height tolerance (each hook's own)"][0]
    text = html.unescape("".join(_assumptions(windy)))
    assert "Wind 20 m/s from any direction" in text
    assert f"widened by {data['cog_widening']:.3f} m" in text
    assert f"on Sheerleg A's boom {boom['force']:.2f} t" in text


def test_the_crane_fleet_table_gives_the_ropes_own_ea_and_the_series_ea_apart(windy):
    page = "".join(_basis(windy))
    caption = "Crane fleet"
    header, *rows = _rows(page, caption)
    assert header[3] == "rope EA [t]" and header[4] == "effective EA, rope and vessel in series [t]"
    fleet = {c.name: c for c in windy.problem.fleet}
    for row in rows:
        name = row[0]
        assert float(row[3]) == ROPE_EA[name]  # as the file writes it
        # the chosen set takes every crane: each in series at its lug, below its rope's own
        assert float(row[4]) == pytest.approx(fleet[name].EA, abs=0.5)
        assert float(row[4]) < 0.5 * ROPE_EA[name]
    text = html.unescape("".join(_assumptions(windy)))
    assert "a floating crane's vessel is in series with its rope" in text
    assert "Rope stiffness is EA / l0 (unstretched length); a rope never" not in text


def test_a_capacity_moves_a_floating_plan_to_its_next_set_with_its_own_series_problem(windy):
    best = windy.chosen
    assert "BH1-S" in best.lugs and windy.ranked_design[1].ok
    problem = _capacity(_problem(), "BH1-S", 250.0)
    moved = plan(problem)
    assert moved.chosen.lugs == windy.ranking[1].lugs
    assert moved.chosen.crane_names == windy.ranking[1].crane_names
    assert all(c.ok for c in moved.checks) and moved.passed_over == 1
    exact = series_problem(wind_problem(problem), moved.chosen.indices, moved.chosen.cranes)
    assert moved.problem.fleet == exact.fleet
    assert [c.hook_tolerance for c in moved.problem.fleet] == [c.hook_tolerance for c in exact.fleet]


def _capacity(problem, name, capacity):
    candidates = tuple(
        dataclasses.replace(c, capacity=capacity) if c.name == name else c for c in problem.candidates
    )
    return dataclasses.replace(problem, candidates=candidates)
