"""The lug-choice MIP on sling hooks hinged about their lug pairs (planner/search/mip.py,
``_hinged_poses``): its tension model is the hinged held model, and its plan is the brute
force's over every set and crane assignment."""

import dataclasses
import itertools

import numpy as np
import pytest
from helpers import EXAMPLES

import liftplan.planner.search.mip as lug_mip
from liftplan.model import PlanInfeasible
from liftplan.planner.plans.slings.apex import apex_problem
from liftplan.planner.problem.file import load_problem
from liftplan.planner.search.evaluator import SetEvaluator, SetInfeasible
from liftplan.planner.search.methods import search
from liftplan.planner.search.scenarios import LugSet, Scenario, box_attitudes

#: Ten of the three-sling block's 36 hooks (its exact optimum 3, 21, 32 among them).
SOME = (0, 3, 5, 9, 14, 18, 21, 27, 30, 32)


def _hooks(count=None):
    """The derived problem of examples/block_three_slings_plan.toml: each 2-leg sling's hook a
    lift point hinged about its lug pair (three unequal charted cranes); ``count``: ten hooks."""
    derived, _ = apex_problem(load_problem(EXAMPLES / "block_three_slings_plan.toml"))
    if count is None:
        return derived
    keep = list(SOME[:count])
    return dataclasses.replace(
        derived,
        candidates=tuple(derived.candidates[i] for i in keep),
        hinges=tuple(derived.hinges[i] for i in keep),
    )


def test_hinged_tension_model_is_the_held_model():
    """T_k = P + kappa (h_k - r_k) with each hook's posed row, rise and bar moment from the
    hinged model alone gives the hinged held model's tensions of a whole set."""
    problem = _hooks()
    assert problem.hinge_rows is not None
    scenarios = [
        Scenario(h, t, tuple(o))
        for o in problem.cog_envelope.offsets()[:2]
        for h, t in box_attitudes(problem, 3, 3)
    ]
    data = lug_mip.poses(problem, scenarios)
    for indices, cranes in [((3, 21, 32), (2, 0, 1)), ((0, 5, 9), (0, 1, 2))]:
        lugset = LugSet(problem, indices, cranes)
        a_level, b_level = lugset.level_statics
        preload = np.linalg.lstsq(a_level, b_level, rcond=None)[0]
        kappa, idx = lugset.stiffness, list(indices)
        basis = np.column_stack([np.ones(len(idx)), data.level_plan[idx]])
        got = []
        for a_mat, b_vec, rise, moment in zip(data.a_mat, data.b_vec, data.rise, data.moment):
            a = a_mat[:, idx]
            rhs = b_vec - moment[:, idx].sum(axis=1)
            c = np.linalg.solve(a @ (kappa[:, None] * basis), rhs - a @ (preload - kappa * rise[idx]))
            got.append(preload + kappa * (basis @ c - rise[idx]))
        np.testing.assert_allclose(got, lugset.tensions(preload, scenarios), atol=1e-9 * problem.body.weight)


@pytest.mark.slow
def test_mip_on_hinged_hooks_is_the_brute_forces(monkeypatch):
    """Ten hinged hooks, three unequal cranes: every set and every assignment evaluated
    exactly; the MIP (its first plan's own bound set aside) proves the least worst value with
    that set and assignment."""
    first = lug_mip._incumbent

    def unproved(problem, started):
        ranking, stats = first(problem, started)
        return ranking, dataclasses.replace(stats, lower_bound=0.0)

    monkeypatch.setattr(lug_mip, "_incumbent", unproved)
    problem = _hooks(10)
    evaluator = SetEvaluator(problem)
    swl = problem.reach[1]
    values = {}
    for indices in itertools.combinations(range(len(problem.candidates)), problem.cranes):
        for cranes in itertools.permutations(range(problem.cranes)):
            if np.any(np.isnan(swl[list(indices), list(cranes)])):
                continue
            try:
                values[indices, cranes] = evaluator.evaluate(indices, cranes).worst_value
            except SetInfeasible:
                continue
    best = min(values, key=values.get)
    ranking, stats = search(dataclasses.replace(problem, search="mip"), 1)
    assert stats.stopped == "proved"
    assert (ranking[0].indices, ranking[0].cranes) == best
    assert ranking[0].worst_value == pytest.approx(values[best], rel=1e-6)
    assert stats.lower_bound <= values[best] * (1 + 1e-9)


def test_spreader_bar_weight_is_refused_with_its_reason():
    problem = _hooks(10)
    rows = problem.hinge_rows.copy()
    rows[:, 7] = 2.0  # a bar of 2 t on every hook
    heavy = dataclasses.replace(problem, hinges=tuple(map(tuple, rows)), search="mip")
    with pytest.raises(PlanInfeasible, match="spreader bar's weight"):
        lug_mip.LugMip(heavy, 1.0)


def test_sling_plan_refuses_a_mip_optimum_that_shares_a_lug(monkeypatch):
    """The MIP ranks only the sets it evaluated: when its proved optimum has two slings on
    one lug, the next set without one is not proved best, and the sling plan says so."""
    from types import SimpleNamespace

    import liftplan.planner.plans.slings.apex as apex

    problem = dataclasses.replace(load_problem(EXAMPLES / "block_three_slings_plan.toml"), search="mip")
    _, rigs = apex_problem(problem)
    lugs = [set(map(int, r)) for r in rigs.lugs]
    shared = next(
        (i, j, k)
        for i, j, k in itertools.combinations(range(len(lugs)), 3)
        if lugs[i] & lugs[j] and not lugs[i] & lugs[k] and not lugs[j] & lugs[k]
    )
    apart = next(
        s
        for s in itertools.combinations(range(len(lugs)), 3)
        if not any(lugs[a] & lugs[b] for a, b in itertools.combinations(s, 2))
    )
    ranking = [SimpleNamespace(indices=shared), SimpleNamespace(indices=apart)]
    monkeypatch.setattr(apex, "search", lambda derived, ask: (ranking, SimpleNamespace(rows=1)))
    with pytest.raises(
        PlanInfeasible, match='search = "mip" proved a set of apexes whose slings share a lug'
    ):
        apex.plan_apex_slings(problem, top=1)
