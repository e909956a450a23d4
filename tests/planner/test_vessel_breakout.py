"""Breakout with floating cranes (issue 27, the planner side).

The sunken block of ``examples/sunken_block_plan.toml`` (with its breakout scene) raised by four
floating cranes, each on its own barge. At breakout the held model takes each rope in series
with its vessel at the lug its crane takes; here the breakout tensions, their hook-error gain
and each vessel's heel, trim and freeboard there are computed again in this file from the
vessels' particulars (a 3 x 3 solve: the level statics with the hook motions a plane) and
compared with the plan's, and a barge limit below its breakout heel fails its check.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from helpers import EXAMPLES

from liftplan.model.scene.vessel import Vessel
from liftplan.planner.plan import plan
from liftplan.planner.problem.file import load_problem
from liftplan.planner.problem.fleet import FleetCrane

EA, LENGTH = 50000.0, 44.0


def _crane(name, x, side, max_heel=2.0, displacement=4000.0):
    """A 400 t crane on its barge, 25 m off the block's side (``side`` +1 port, -1 starboard),
    the barge's bow at the block and its flotation centre 30 m behind the slew centre."""
    vessel = Vessel(
        displacement,
        1800.0,
        20.0,
        120.0,
        (x, side * 55.0),
        heading=-90.0 * side,
        max_heel=max_heel,
        max_trim=1.0,
        freeboard=2.5,
        beam=30.0,
        length=60.0,
        min_freeboard=1.0,
    )
    chart = ((15.0, 400.0), (35.0, 300.0))
    position = (x, side * 25.0)
    return FleetCrane(name, EA, LENGTH, position, chart, boom_min=20.0, boom_max=40.0, vessel=vessel)


def _problem(max_heel=2.0):
    given = load_problem(EXAMPLES / "sunken_block_plan.toml")
    fleet = (
        _crane("A", 15.0, 1, max_heel),
        _crane("B", 45.0, 1),
        _crane("C", 15.0, -1),
        _crane("D", 45.0, -1, displacement=8000.0),  # one barge twice as large: stiffer
    )
    return dataclasses.replace(given, fleet=fleet)


def _axes(vessel, point):
    """(forward, starboard) of a world plan point from the flotation centre  [m]."""
    h = math.radians(vessel.heading)
    dx, dy = point[0] - vessel.flotation[0], point[1] - vessel.flotation[1]
    return dx * math.cos(h) + dy * math.sin(h), dx * math.sin(h) - dy * math.cos(h)


@pytest.fixture(scope="module")
def floating():
    problem = _problem()
    return problem, plan(problem)


def _held(problem, ranked, stiffness=None):
    """A ranked set's breakout tensions [t] and their pose-held gain dT/dH [t/m], here:
    T = T* + K P c with P = (1, x, y) per lug (the hooks' plane motion) and c from the level
    statics P' T = total (1, x_p, y_p); dT = K (e + P c') with P' dT = 0 for hook errors e.
    K the series stiffness 1 / (l0 / EA + c_tip), or ``stiffness`` [t/m] when given."""
    points = problem.points[list(ranked.indices)]
    vessels = [problem.fleet[j].vessel for j in ranked.cranes]
    axes = [_axes(v, p[:2]) for v, p in zip(vessels, points)]
    compliance = np.array(
        [
            1 / (v.density * v.waterplane_area)
            + y**2 / (v.displacement * v.gm_t)
            + x**2 / (v.displacement * v.gm_l)
            for v, (x, y) in zip(vessels, axes)
        ]
    )
    k = np.diag(1.0 / (LENGTH / EA + compliance) if stiffness is None else stiffness)
    pattern = np.column_stack([np.ones(len(points)), points[:, 0], points[:, 1]])
    load = problem.breakout
    target = load.total * np.array([1.0, load.point[0], load.point[1]])
    c = np.linalg.solve(pattern.T @ k @ pattern, target - pattern.T @ ranked.preload)
    gain = k - k @ pattern @ np.linalg.solve(pattern.T @ k @ pattern, pattern.T @ k)
    return ranked.preload + k @ pattern @ c, gain


def test_breakout_holds_each_rope_in_series_with_its_vessel(floating):
    """The breakout tensions of every ranked set, each with its vessels in series at its own
    lugs (:func:`_held`), to 1e-6 t, and their gain to 1e-6 of it; the rope's own EA would give
    other tensions (by more than 0.5 t) for the plan's set."""
    problem, result = floating
    assert problem.yaw == 0.0
    assert len(result.ranking) > 1
    for ranked, design in zip(result.ranking, result.ranked_design):
        tensions, gain = _held(problem, ranked)
        assert design.breakout.tensions == pytest.approx(tensions, abs=1e-6)
        assert design.breakout.gain == pytest.approx(gain, abs=1e-6 * np.abs(gain).max())
    case = result.design_loads.breakout
    rope_only, _ = _held(problem, result.chosen, np.full(4, EA / LENGTH))
    assert np.max(np.abs(rope_only - case.tensions)) > 0.5


def test_each_vessel_is_checked_at_breakout(floating):
    """Each vessel's heel, trim and freeboard at breakout, the ballast levelling it at its level
    tension T0: (T - T0) y_t / (disp GM_T) at the rope's least and largest breakout tension over
    the hook errors; a heel limit below it fails ``breakout_vessel_heel`` (the plan exits 4)."""
    problem, result = floating
    case = result.design_loads.breakout
    chosen = result.chosen
    widening = np.abs(case.gain) @ case.hook_tolerance
    names = []
    for k, (i, j) in enumerate(zip(chosen.indices, chosen.cranes)):
        vessel = problem.fleet[j].vessel
        forward, starboard = _axes(vessel, problem.points[i][:2])
        t0 = chosen.preload[k]
        ends = (case.tensions[k] - widening[k], case.tensions[k] + widening[k])
        swing = max(abs(t - t0) for t in ends)
        state = next(v for v in case.vessels if v.crane == problem.fleet[j].name)
        heel = math.degrees(swing * abs(starboard) / (vessel.displacement * vessel.gm_t))
        trim = math.degrees(swing * abs(forward) / (vessel.displacement * vessel.gm_l))
        assert (state.worst.heel, state.worst.trim) == pytest.approx((heel, trim), rel=1e-9)
        board = min(
            2.5
            - t / (vessel.density * vessel.waterplane_area)
            - 15.0 * abs((t - t0) * starboard) / (vessel.displacement * vessel.gm_t)
            - 30.0 * abs((t - t0) * forward) / (vessel.displacement * vessel.gm_l)
            for t in ends
        )
        assert state.worst.freeboard == pytest.approx(board, rel=1e-9)
        names.append(state.crane)
    assert state.worst.heel > 0.1  # the breakout heels the barges
    checks = {(c.name, c.subject): c for c in result.checks if c.name.startswith("breakout_vessel")}
    kinds = ("breakout_vessel_heel", "breakout_vessel_trim", "breakout_vessel_freeboard")
    assert set(checks) == {(kind, name) for kind in kinds for name in names}
    assert all(c.ok for c in checks.values())
    assert set(result.to_json()["breakout"]["vessels"]) == set(names)
    # a heel limit on crane A's barge below its breakout heel (above its box heel): flagged
    a = next(v for v in case.vessels if v.crane == "A")
    box = next(v for v in result.vessels if v.crane == "A").worst_heel
    assert box < a.worst.heel
    tight = plan(dataclasses.replace(_problem(max_heel=0.5 * (box + a.worst.heel)), top=1))
    failed = [c for c in tight.checks if not c.ok]
    assert [(c.name, c.subject) for c in failed] == [("breakout_vessel_heel", "A")]
    # with more sets ranked, one that meets every design check (breakout included) is the plan
    ranked = plan(_problem(max_heel=0.5 * (box + a.worst.heel)))
    assert all(c.ok for c in ranked.checks) and ranked.passed_over >= 1
