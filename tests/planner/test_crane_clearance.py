"""Issue 24 item 2: buildable plans. Booms that cross in plan, or come nearer than
``plan.crane_clearance``, are ruled out of every search; the chosen plan carries the checks;
a crane's radius stays within its chart's radii; a crane inside the hull's outline is refused.
"""

from __future__ import annotations

import dataclasses
import itertools
import json

import numpy as np
import pytest
from support.cli import run
from support.planning import EXAMPLES

from liftplan.model.errors import InvalidScene, PlanInfeasible
from liftplan.planner import plan
from liftplan.planner.problem.clearance import clear, segment_distance
from liftplan.planner.problem.file import load_problem, loads_problem
from liftplan.planner.search.evaluator import SetEvaluator, SetInfeasible
from liftplan.planner.search.screen import assignments

FLEET = EXAMPLES / "tanker_fleet.toml"


def test_segment_distance_against_sampling():
    """The closed form against the least distance of 400 x 400 points along each segment."""
    rng = np.random.default_rng(3)
    t = np.linspace(0.0, 1.0, 400)[:, None]
    for _ in range(40):
        a0, a1, b0, b1 = rng.uniform(-10, 10, (4, 2))
        pa, pb = a0 + t * (a1 - a0), b0 + t * (b1 - b0)
        sampled = np.min(np.linalg.norm(pa[:, None, :] - pb[None, :, :], axis=2))
        exact = float(segment_distance(a0, a1, b0, b1))
        assert exact <= sampled + 1e-12
        # sampling steps of at most |segment| / 399 each: within half a step of each
        assert sampled - exact <= 0.5 * (np.linalg.norm(a1 - a0) + np.linalg.norm(b1 - b0)) / 399 + 1e-12
    # crossing booms: distance 0; parallel booms 2 m apart: 2 m
    assert segment_distance(np.array([0, 0]), np.array([10, 10]), np.array([0, 10]), np.array([10, 0])) == 0
    assert segment_distance(np.array([0, 0]), np.array([10, 0]), np.array([0, 2]), np.array([10, 2])) == 2
    assert not clear(np.array(0.0), 0.0) and clear(np.array(3.0), 3.0) and not clear(np.array(2.9), 3.0)


@pytest.fixture(scope="module")
def small_fleet():
    """The tanker fleet on the ten candidates BH2 to BH6, no hook tolerance: small enough for
    the brute force over every set and assignment."""
    problem = load_problem(FLEET)
    keep = [i for i, c in enumerate(problem.candidates) if c.name[:3] in ("BH2", "BH3", "BH4", "BH5", "BH6")]
    return dataclasses.replace(
        problem, candidates=tuple(problem.candidates[i] for i in keep), hook_tolerance=0.0, top=1
    )


def _brute_force(problem):
    """Every (set, assignment) in reach evaluated: (value, lugs, cranes, least boom distance)."""
    evaluator = SetEvaluator(problem)
    swl, d = problem.reach[1], problem.boom_distances
    out = []
    for lugs in itertools.combinations(range(len(problem.candidates)), problem.cranes):
        for cranes in assignments(problem):
            if np.any(np.isnan(swl[list(lugs), cranes])):
                continue
            try:
                result = evaluator.evaluate(lugs, cranes)
            except SetInfeasible:
                continue
            least = min(
                d[lugs[a], cranes[a], lugs[b], cranes[b]] for a, b in itertools.combinations(range(4), 2)
            )
            out.append((result.worst_value, lugs, tuple(cranes), least))
    return sorted(out)


def test_the_plan_is_the_best_buildable_by_brute_force(small_fleet):
    rows = _brute_force(small_fleet)
    best_any = rows[0]
    best_clear = next(r for r in rows if clear(np.array(r[3]), small_fleet.crane_clearance))
    assert best_any[3] == 0.0  # the unconstrained optimum has two booms crossing
    assert best_clear[0] > best_any[0]
    result = plan(small_fleet)
    assert result.chosen.worst_value == pytest.approx(best_clear[0], rel=1e-6)
    assert tuple(result.chosen.indices) == best_clear[1] and tuple(result.chosen.cranes) == best_clear[2]
    assert result.stats.clashing > 0
    checks = [c for c in result.checks if c.name == "crane_clearance"]
    assert len(checks) == 4 and all(c.ok for c in checks)
    assert min(c.value for c in checks) == pytest.approx(best_clear[3])
    # the MIP rules out the same rows: same plan
    mip = plan(dataclasses.replace(small_fleet, search="mip"))
    assert tuple(mip.chosen.indices) == best_clear[1] and tuple(mip.chosen.cranes) == best_clear[2]


def test_a_larger_clearance_rules_out_more(small_fleet):
    base = plan(small_fleet)
    least = min(c.value for c in base.checks if c.name == "crane_clearance")
    wider = plan(dataclasses.replace(small_fleet, crane_clearance=least + 1.0))
    assert wider.stats.clashing > base.stats.clashing
    assert min(c.value for c in wider.checks if c.name == "crane_clearance") >= least + 1.0


def test_chart_radii_bound_the_reach(small_fleet):
    """Below a chart's first radius the crane cannot work: SWL NaN (out of reach)."""
    crane = small_fleet.fleet[0]
    first, last = crane.load_chart[0][0], crane.load_chart[-1][0]
    swl = crane.swl_at(np.array([first - 0.01, first, last, last + 0.01]))
    assert np.isnan(swl[0]) and np.isnan(swl[3]) and swl[1] == crane.load_chart[0][1]


def test_bad_clearance_and_a_crane_on_the_hull_are_refused():
    text = FLEET.read_text(encoding="utf-8")
    with pytest.raises(InvalidScene, match=r"plan.crane_clearance = -1.0: expected >= 0 m"):
        loads_problem(text.replace("top = 5", "top = 5\ncrane_clearance = -1.0"))
    inside = text.replace("position = [20.0, 0.0, 37.0]", "position = [20.0, 0.0, 6.0]")
    with pytest.raises(InvalidScene, match=r"cranes\[2\].position \(20, 0, 6\) \(Crane C\): inside the hull"):
        loads_problem(inside)


@pytest.mark.slow  # 5-6 s; the default run keeps under 10 minutes
def test_cli_reports_the_clearance(tmp_path):
    out = run("plan", str(FLEET), "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    assert data["search"]["clashing"] > 0
    checks = [c for c in data["checks"] if c["name"] == "crane_clearance"]
    assert len(checks) == 4 and all(c["ok"] and c["unit"] == "m" and c["limit"] == 3.0 for c in checks)


def test_two_crane_sling_plans_keep_the_clearance_too():
    """The two-crane sling search has its own enumeration: the clearance holds there as well."""
    problem = load_problem(EXAMPLES / "block_sling_plan.toml")
    base = plan(problem)
    a, b = (np.asarray(c.position, dtype=float) for c in problem.fleet)
    tips = [(np.asarray(h, dtype=float))[:2] for h in base.chosen.apex]  # level hooks, yaw 0 here
    least = float(segment_distance(a, tips[0], b, tips[1]))
    assert clear(np.array(least), problem.crane_clearance)
    with pytest.raises(PlanInfeasible, match=r"booms crossing or within plan.crane_clearance"):
        plan(dataclasses.replace(problem, crane_clearance=1000.0))
