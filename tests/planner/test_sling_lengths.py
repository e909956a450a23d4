"""Hoist rope payout ranges with cranes on slings (issue 24 item 3: they were refused).

``rope_length = { min, max }`` on sling cranes: the rope-length search of
:mod:`liftplan.planner.plans.lengths` runs around the sling planner, each trial an exact sling
plan at fixed hoist rope lengths (tip to hook). Shown here:

* two cranes on 2-leg slings (8 candidates), the booms' range binding: at every length tried,
  the trial's value is the brute force's over every pair of disjoint rigs x both assignments
  (the lever rule on the tilt and CG states, the roll, the rules' limits and each boom tip
  within its range), no plan exactly where the brute force has none; the chosen length is
  the first of the least, the plan's slings a brute-force optimum there, its boom heights
  follow from the length; JSON, console and report show the lengths and the breakout case;
* four cranes on 4-leg slings with hook errors, where the length changes the plan (a longer
  rope is softer, the twist smaller): every trial equals the sling plan at that fixed length,
  the worst falls with the length, and the longest length the booms allow is chosen.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from numpy.testing import assert_allclose
from support.sling_block import FOUR_LEG, block, lever_shares, sling_apex

from liftplan.planner.output.console.summary import summary
from liftplan.planner.output.report.slings import render_html
from liftplan.planner.plan import plan
from liftplan.planner.plans.lengths import varying_classes, with_lengths
from liftplan.planner.plans.slings import ApexSlingPlan, SlingPlan, plan_slings
from liftplan.planner.problem.fleet import rule_limits

RANGE = "{ min = 20.0, max = 40.0 }\nboom_height = { min = 0.0, max = 25.0 }"


@pytest.fixture(scope="module")
def two():
    problem = block(
        'objective = "utilisation"\nhook_tolerance = 0.02\ncog_tolerance = [0.5, 0.1, 0.3]',
        (600.0, 600.0),
        rope=RANGE,
    )
    return plan(problem)


def _brute_force(problem, length_l0):
    """{(pair 1, pair 2): worst T / SWL difference} of every feasible option at hoist rope
    length ``length_l0`` [m]."""
    points, weight, length = problem.points, problem.body.weight, 12.0
    swl, stiffness = np.array([600.0, 600.0]), 50000.0 / length_l0
    cog = np.asarray(problem.body.cog)
    offsets = [np.array(v) for v in itertools.product(*[(-h, h) for h in (0.5, 0.1, 0.3)])]
    rigs = [
        (i, j)
        for i, j in itertools.combinations(range(len(points)), 2)
        if np.linalg.norm(points[j] - points[i]) <= length  # legs at 60 deg or steeper
    ]
    in_box, level = rule_limits(problem, swl[None, :], np.array([[0, 1]]))
    values = {}
    for pair1, pair2 in itertools.product(rigs, rigs):
        if set(pair1) & set(pair2):
            continue
        hooks = [sling_apex(points[i], points[j], length) for i, j in (pair1, pair2)]
        if np.hypot(*(hooks[1] - hooks[0])[:2]) < 1e-6:
            continue
        nominal, hooks, e = lever_shares(points, pair1, pair2, length, weight, cog, 0.0)
        rolls = []
        for off in offsets:
            g = cog + off - hooks[0]
            side = g - (g @ e) * e
            rolls.append(math.degrees(math.atan2(np.hypot(side[0], side[1]), -side[2])))
        boom = problem.lift_height + np.array([h[2] for h in hooks]) + length_l0 + nominal / stiffness
        if max(rolls) > 2.0 + 1e-9 or np.any(boom > 25.0 + 1e-9) or np.any(boom < -1e-9):
            continue
        # the 2 deg tolerance and the hook errors' atan(2 x 0.02 m / span) along the hook line
        tilt = 2.0 + math.degrees(math.atan(2 * 0.02 / np.hypot(*(hooks[1] - hooks[0])[:2])))
        loads = np.array(
            [
                lever_shares(points, pair1, pair2, length, weight, cog + off, math.radians(t))[0]
                for off in offsets
                for t in (-tilt, 0.0, tilt)
            ]
        )
        if loads.min() <= 0.0 or np.any(loads > in_box) or np.any(nominal > level):
            continue
        values[(pair1, pair2)] = float(np.max(np.abs(loads[:, 0] - loads[:, 1]) / 600.0))
    return values


def test_two_cranes_every_length_tried_is_the_brute_force(two):
    assert isinstance(two, SlingPlan)
    search = two.lengths
    assert search is not None and search.classes == (("C1", "C2"),)
    trials = {t.lengths[0]: t for t in search.trials}
    assert len(trials) == len(search.trials) >= 5
    feasible = []
    for length, trial in trials.items():
        values = _brute_force(two.problem, length)
        if not values:
            assert trial.value is None and "boom_height" in trial.reason
            continue
        best = min(values.values())
        assert trial.value == pytest.approx(best, abs=1e-9)
        feasible.append(length)
    # the booms' range binds: some lengths plan, the longer ones do not
    assert feasible and len(feasible) < len(trials)
    # the length does not change a two-crane lift's shares (it is statically determinate), so
    # the first of the equal least is kept: the shortest tried
    assert search.chosen == (min(feasible),) == (20.0,)
    values = _brute_force(two.problem, 20.0)
    key = tuple(tuple(sorted(p)) for p in two.chosen.pairs)
    assert values[key] <= min(values.values()) + 1e-9
    assert two.rope_lengths == {"L1": 20.0, "L2": 20.0, "L3": 20.0, "L4": 20.0}
    # the plan's problem is at the chosen length: its boom heights follow from it
    stiffness = 50000.0 / 20.0
    expected = two.problem.lift_height + two.hooks[:, 2] + 20.0 + two.hook_nominal / stiffness
    assert_allclose(two.crane_boom_heights, expected, rtol=0, atol=1e-12)
    assert np.all(two.crane_boom_heights <= 25.0)


def test_two_cranes_json_console_report_show_lengths_and_breakout(two):
    out = two.to_json()
    assert out["rope_lengths"] == {f"L{k}": 20.0 for k in range(1, 5)}  # per lug, as single ropes
    classes = out["rope_length_search"]["classes"]
    assert classes == [{"cranes": ["C1", "C2"], "min": 20.0, "max": 40.0, "chosen": 20.0}]
    assert len(out["rope_length_search"]["trials"]) == len(two.lengths.trials)
    assert out["breakout"]["cranes"][0]["crane"] == "C1" and out["breakout"]["ok"] in (True, False)
    text = summary(two)
    assert "hoist rope length 20.000 m (tip to hook) chosen within 20 to 40 m" in text
    assert "breakout from the seabed" in text
    page = render_html(two)
    assert "Hoist rope lengths chosen by the planner" in page and "Breakout from the seabed" in page


def test_four_leg_slings_choose_the_longest_length_the_booms_allow():
    problem = block(
        "cranes = 4\nmin_tension = 20.0\nhook_tolerance = 0.05",
        (500.0,) * 4,
        rows=FOUR_LEG,
        legs=4,
        length=10.0,
        bulkheads=True,
        rope="{ min = 20.0, max = 60.0 }\nboom_height = { min = 0.0, max = 45.0 }",
        extra="[rigging]\nmin_sling_angle = 70.0\n[rules]\ncog_factor = 1.03",
    )
    result = plan(problem)
    assert isinstance(result, ApexSlingPlan) and result.lengths is not None
    trials = sorted(result.lengths.trials, key=lambda t: t.lengths)
    planned = [t for t in trials if t.value is not None]
    assert len(planned) >= 3 and len(planned) < len(trials)
    values = [t.value for t in planned]
    assert all(b < a for a, b in zip(values, values[1:]))  # softer ropes, less twist
    assert result.lengths.chosen == planned[-1].lengths
    assert planned[-1].lengths[0] < max(t.lengths[0] for t in trials)  # the booms end it
    # each trial is the exact sling plan at that fixed length (two of them, the ends)
    classes = varying_classes(problem)
    for trial in (planned[0], planned[-1]):
        fixed = plan_slings(with_lengths(problem, classes, trial.lengths))
        assert fixed.inner.chosen.worst_value == pytest.approx(trial.value, abs=1e-9)
    assert result.inner.chosen.worst_value == pytest.approx(planned[-1].value, abs=1e-9)
    assert result.stats.lower_bound <= result.inner.chosen.worst_value + 1e-9
    assert set(result.rope_lengths.values()) == {planned[-1].lengths[0]}
    assert "hoist rope length" in summary(result)
