"""The planner choosing rope lengths (issue 16, item 2; planner/plans/lengths.py).

The tanker with +-0.05 m hook errors and a 25 to 55 m payout range
(examples/tanker_lengths.toml) against today's fixed 30 m plan (examples/tanker_plan.toml).
"""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest
from helpers import EXAMPLES
from numpy.testing import assert_allclose

from liftplan.model import solve
from liftplan.model.errors import InvalidScene, PlanInfeasible
from liftplan.planner import load_problem, plan
from liftplan.planner.plans.held import Plan
from liftplan.planner.plans.lengths import LENGTH_STEPS, REFINE_ROUNDS, with_lengths
from liftplan.planner.problem.file import loads_problem


@pytest.fixture(scope="module")
def chosen():
    return plan(load_problem(EXAMPLES / "tanker_lengths.toml"))


@pytest.fixture(scope="module")
def today():
    """Today's plan: the fixed 30 m ropes, planned for +-0.02 m (tanker_plan.toml)."""
    return plan(load_problem(EXAMPLES / "tanker_plan.toml"))


def test_tanker_lengths_chosen_beside_todays_plan(chosen, today):
    problem = load_problem(EXAMPLES / "tanker_lengths.toml")
    # one class of four equal cranes: one length for all, within the range
    lengths = set(chosen.rope_lengths.values())
    assert len(lengths) == 1
    (length,) = lengths
    assert 25.0 <= length <= 55.0
    # 5 first-pass lengths and two halvings: the choice sits on the grid of step 30/16 m
    assert len(chosen.lengths.trials) <= LENGTH_STEPS + 2 * REFINE_ROUNDS
    assert (length - 25.0) / (30.0 / 16) == pytest.approx(round((length - 25.0) / (30.0 / 16)))
    # the choice is the best trial, and each trial is the exact plan at its lengths
    feasible = [t for t in chosen.lengths.trials if t.value is not None]
    assert chosen.worst_spread == pytest.approx(min(t.value for t in feasible), abs=1e-9)
    again = plan(with_lengths(problem, ((0, 1, 2, 3),), (length,)))
    assert again.chosen.lugs == chosen.chosen.lugs
    assert again.worst_spread == pytest.approx(chosen.worst_spread, abs=1e-6)
    # today's 30 m ropes cannot hold +-0.05 m within the limits at all (the search is exact)
    fixed = with_lengths(problem, ((0, 1, 2, 3),), (30.0,))
    with pytest.raises(PlanInfeasible):
        plan(fixed)
    # today's plan (lugs, boom heights, preload for +-0.02 m) under the same +-0.05 m: worse
    held = Plan(problem=fixed, ranking=[today.chosen], stats=today.stats).crew_margin((1.0,))[0]
    assert_allclose(held.tolerance, 0.05)
    assert held.worst_spread >= chosen.worst_spread
    assert not held.within_limits
    assert chosen.crew_margin((1.0,))[0].within_limits


def test_boom_heights_follow_from_the_lengths(chosen):
    problem = chosen.problem
    heights = np.array(list(chosen.boom_heights.values()))
    crane = problem.fleet[0]
    assert np.all(heights <= crane.boom_max + 1e-9) and np.all(heights >= crane.boom_min - 1e-9)
    # the plan's scene carries the chosen lengths, and its elastic solve gives the plan's
    # level tensions (the boom heights dial in the preload through l0: H = a + z + l0 + T l0/EA)
    scene = chosen.scene
    assert [c.rope_length for c in scene.cranes] == list(chosen.rope_lengths.values())
    eq = solve(scene)
    assert_allclose(
        [eq.tensions[k] for k in chosen.labels], list(chosen.tensions.values()), atol=1e-6
    )  # the plan and the forward model agree to the solve's tolerance


def test_json_carries_the_lengths(chosen):
    data = json.loads(json.dumps(chosen.to_json()))
    assert data["rope_lengths"] == chosen.rope_lengths
    assert set(data["rope_lengths"]) == set(data["lugs"])
    search = data["rope_length_search"]
    assert search["classes"][0]["min"] == 25.0 and search["classes"][0]["max"] == 55.0
    assert search["classes"][0]["chosen"] == data["rope_lengths"]["L1"]
    assert any(t["worst"] is None and t["reason"] for t in search["trials"])
    assert data["lower_bound"] <= data["worst_spread"] + 1e-9


def test_a_number_keeps_its_meaning(today):
    assert today.lengths is None
    assert "rope_lengths" not in today.to_json()
    assert set(today.rope_lengths.values()) == {30.0}


def test_a_range_of_one_length_is_that_fixed_length(today):
    problem = load_problem(EXAMPLES / "tanker_plan.toml")
    spec = dataclasses.replace(problem.crane, rope_length_range=(30.0, 30.0))
    result = plan(dataclasses.replace(problem, crane=spec, fleet=()))
    assert len(result.lengths.trials) == 1
    assert result.chosen.lugs == today.chosen.lugs
    assert result.worst_spread == pytest.approx(today.worst_spread, abs=1e-9)
    assert_allclose(result.chosen.boom_heights, today.chosen.boom_heights, atol=1e-9)


BASE = (EXAMPLES / "tanker_plan.toml").read_text()


@pytest.mark.parametrize(
    "bad",
    [
        "rope_length = { min = 40.0, max = 30.0 } ",
        "rope_length = { min = -1.0, max = 30.0 } ",
        "rope_length = { min = 25.0 } ",
    ],
)
def test_bad_ranges_are_one_line_errors(bad):
    with pytest.raises(InvalidScene) as err:
        loads_problem(BASE.replace("rope_length = 30.0 ", bad))
    text = str(err.value)
    assert "\n" not in text and "rope_length" in text


def test_the_search_counts_add_up_and_the_report_says_the_length_was_chosen(chosen):
    """Review findings 10 and 12: the counts are the chosen length's (one search's sets, each
    counted once), the sum over every length is named as such; the report lists the range and
    every length tried with its value, and says the bound holds over the lengths tried."""
    import re

    from liftplan.planner.output.console.held import plan_table
    from liftplan.planner.output.report.held import render_html

    stats, search = chosen.stats, chosen.lengths
    assert stats.screened_out + stats.evaluated + stats.pruned == stats.rows
    assert search.evaluated == sum(t.evaluated or 0 for t in search.trials) > stats.evaluated
    console = " ".join(plan_table(chosen).split())
    assert f"{stats.screened_out} ruled out by screening, {stats.evaluated} evaluated" in console
    assert f"{len(search.trials)} lengths tried" in console
    assert f"{search.evaluated} sets evaluated over them" in console
    report = re.sub(r"\s+", " ", re.sub(r"<[^>]+>", " ", render_html(chosen)))
    assert "Rope lengths chosen by the planner" in report and "25 to 55" in report
    for t in search.trials:
        value = "-" if t.value is None else f"{t.value:.2f}"
        assert f"{t.lengths[0]:.3f} {value}" in report
    assert "does better at any rope length tried" in report
    assert "proved (over the rope lengths tried)" in report
    assert f"sets evaluated over every length tried {search.evaluated}" in report
    assert f"evaluated (linear programme + dense search of the box) {stats.evaluated}" in report
