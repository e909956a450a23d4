"""Many lifting points: the dual bound on each set's preload LP, and the local search."""

import dataclasses
import math

import numpy as np
import pytest
from helpers import EXAMPLES

from liftplan.model import PlanInfeasible
from liftplan.planner.problem.file import load_problem
from liftplan.planner.search.bounds import PreloadMinimax
from liftplan.planner.search.evaluator import SetEvaluator, SetInfeasible
from liftplan.planner.search.local import _plane_lp, local_search, spread_start, swaps
from liftplan.planner.search.methods import search
from liftplan.planner.search.scenarios import LugSet, Scenario
from liftplan.planner.search.screen import FEASIBLE, all_sets, screen, screening_scenarios


@pytest.fixture(scope="module")
def tanker():
    return load_problem(EXAMPLES / "tanker_plan.toml")


def corner_lp(problem, indices):
    """The preload LP (cvxpy + Clarabel) over the dual's scenarios: box corners and level,
    every CG vertex, with the hook errors exact; None when it is infeasible."""
    x, offsets = screening_scenarios(problem, corners=True)
    scenarios = [
        Scenario(float(np.degrees(h)), float(np.degrees(t)), tuple(map(float, o)))
        for (_, h, t), o in zip(x, offsets)
    ]
    lugset = LugSet(problem, indices)
    gains, q = lugset.affine(scenarios)
    hook = (gains * lugset.stiffness[None, None, :], lugset.hook_tolerance) if lugset.hook_uncertain else None
    count = len(scenarios)
    lp = PreloadMinimax(lugset.n, count, problem.objective)
    try:
        result = lp.solve(
            gains,
            q,
            *lugset.level_statics,
            lugset.preload_range(),
            (np.full((count, lugset.n), problem.min_tension), np.tile(lugset.limit, (count, 1))),
            scale=lugset.scale,
            hook=hook,
        )
    except PlanInfeasible:
        return None
    return result.worst_spread


CASES = [
    (5, 0.0, "spread"),
    (6, 0.0, "spread"),
    (5, 0.02, "spread"),
    (5, 0.0, "reserve"),
    (6, 0.02, "spread"),
]


@pytest.mark.parametrize("cranes, hook, objective", CASES)
def test_dual_bound_is_a_lower_bound_and_nearly_the_lp(tanker, cranes, hook, objective):
    """Weak duality: whatever the optimiser did, the bound never exceeds the LP it bounds
    (Clarabel's tolerance, 1e-6 W); it is within 0.5 % of it (a fixed count of Newton steps
    per tau: measured at most 0.16 % on these sets; ten steps close it), with hook errors too
    (their pair rows are exact in the smoothed problem, not shifted copies of the scenarios)."""
    problem = dataclasses.replace(tanker, cranes=cranes, hook_tolerance=hook, fleet=(), objective=objective)
    sets = all_sets(problem)
    rng = np.random.default_rng(7)
    pick = sets[rng.choice(len(sets), 24, replace=False)]
    found = screen(problem, pick, dual=True)
    checked = 0
    for indices, bound, reason in zip(pick, found.bound, found.reason):
        if reason != FEASIBLE:
            continue
        value = corner_lp(problem, indices)
        if value is None:
            continue  # an infeasible LP: any bound holds
        scale = problem.body.weight if objective == "spread" else 1.0
        assert bound <= value + 1e-6 * scale
        assert bound >= value - 5e-3 * abs(value) - 1e-9 * scale
        checked += 1
    assert checked >= 5


def test_swaps_are_every_set_one_exchange_away():
    near = swaps((0, 2, 5), 7)
    assert len(near) == 3 * 4
    assert all(len(set(s) & {0, 2, 5}) == 2 for s in near.tolist())
    assert len({tuple(s) for s in near.tolist()}) == len(near)


def test_spread_start_spans_the_candidates(tanker):
    start = spread_start(tanker)
    names = {tanker.names[i] for i in start}
    # the first is the candidate farthest from the CG, then the farthest from it, ...
    assert len(start) == 4 and {"BH1-P", "BH8-S"} <= names or {"BH1-S", "BH8-P"} <= names


def test_local_search_is_never_better_than_the_exact_search(tanker):
    """On the tanker with five cranes (4 368 sets) the local search ends on a feasible set whose
    exact worst is no lower than the proved optimum; its lower bound (the two deck lines'
    statics, planner/search/lines.py) is no higher than that optimum, and the plan says so."""
    problem = dataclasses.replace(tanker, cranes=5, hook_tolerance=0.0, fleet=())
    exact, exact_stats = search(problem, 1)
    assert exact_stats.stopped == "proved"
    local, stats = search(dataclasses.replace(problem, search="local"), 1)
    assert stats.stopped == "local" and 0.0 < stats.lower_bound <= exact[0].worst_value
    gap = 100 * stats.relative_gap
    assert f"gap {gap:.2f} %" in stats.summary if gap < 10 else f"gap {gap:.1f} %" in stats.summary
    tol = 1e-6 * problem.body.weight
    assert local[0].worst_value >= exact[0].worst_value - tol
    # the local optimum: the deck lugs are in one plane on equal ropes, so the search ranks
    # swaps by the exact LP over the box's corners; no swap beats the set on it
    indices, moves, value, cranes = local_search(problem)
    assert cranes == tuple(range(5))  # equal cranes: the identity
    assert tuple(local[0].indices) == indices
    plane = _plane_lp(problem)
    assert plane is not None and value == pytest.approx(plane.value(indices))
    near = swaps(indices, len(problem.candidates))
    assert min(plane.value(s) for s in near) >= value * (1 - 1e-6) - tol


def test_exact_search_refuses_too_many_sets(tanker):
    from liftplan.model import InvalidScene

    many = tanker.candidates * 1
    names = [dataclasses.replace(c, name=f"{c.name}-{k}") for k in range(8) for c in many]
    with pytest.raises(InvalidScene, match='search = "local"'):
        dataclasses.replace(tanker, candidates=tuple(names), cranes=8, search="exact")
    auto = dataclasses.replace(tanker, candidates=tuple(names), cranes=8)
    assert auto.search == "auto" and math.comb(128, 8) > 5_000_000


def test_set_evaluation_of_the_local_result_is_exact(tanker):
    problem = dataclasses.replace(tanker, cranes=5, hook_tolerance=0.0, fleet=(), search="local")
    ranking, _ = search(problem, 1)
    again = SetEvaluator(problem).evaluate(ranking[0].indices)
    assert again.worst_value == pytest.approx(ranking[0].worst_value, rel=1e-9)
    with pytest.raises(SetInfeasible):
        SetEvaluator(problem).evaluate((0, 1, 2, 3, 4))  # all aft: the CG is outside
