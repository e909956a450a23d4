"""The MIP's set-wise hook rows (planner/search/mip_hooks.py, set_tables and set_bounds):
each set's bound is its own linear program from the held model, no set the rows drop or
bound can beat the true optimum (brute force over every set), and the MIP's plan with a hook
tolerance is the exact search's."""

import dataclasses
import itertools

import numpy as np
import pytest
from scipy.optimize import linprog
from support.planning import small_problem

import liftplan.planner.search.mip as lug_mip
from liftplan.planner.search.evaluator import SetEvaluator, SetInfeasible
from liftplan.planner.search.methods import search
from liftplan.planner.search.mip_hooks import scenario_vectors, set_bounds, set_tables
from liftplan.planner.search.scenarios import LugSet, Scenario, first_scenarios


def _model_lp(problem, indices, scenarios, preload_box, band):
    """The set's least worst spread over ``scenarios`` with every hook error at its worst,
    from the held model alone: tensions and dT/dH of LugSet at a level preload, the preload
    free on the level statics within ``preload_box`` and the tensions -/+ their own widening
    within ``band`` (scipy's HiGHS). None when infeasible."""
    lugset = LugSet(problem, indices)
    n = len(indices)
    level = lug_mip.poses(problem, [Scenario(0.0, 0.0)])
    rows, b0 = level.a_mat[0][:, list(indices)], level.b_vec[0]
    start = np.linalg.lstsq(rows, b0, rcond=None)[0]
    null = np.linalg.svd(rows)[2][3:].T
    tensions, gain = lugset.tensions_and_gain(start, scenarios)
    # the changes from level do not depend on the preload (checked at another level preload)
    change = tensions - start
    if null.shape[1]:
        moved = start + 5.0 * null[:, 0]
        np.testing.assert_allclose(lugset.tensions_and_gain(moved, scenarios)[0] - moved, change, atol=1e-6)
    # and the hook errors' effect is the same at every attitude
    np.testing.assert_allclose(
        gain, np.broadcast_to(gain[0], gain.shape), atol=1e-6 * (1.0 + np.abs(gain).max())
    )
    delta = lugset.hook_tolerance
    own = np.abs(gain[0]) @ delta  # each rope's own worst change
    a, b = np.nonzero(~np.eye(n, dtype=bool))
    wide = np.abs(gain[0][a] - gain[0][b]) @ delta
    # variables (P, z): z >= P_a - P_b + change_ka - change_kb + W_ab at every k
    m = len(scenarios)
    upper, rhs = [], []
    for k in range(m):
        for p, q, w in zip(a, b, wide):
            row = np.zeros(n + 1)
            row[p], row[q], row[n] = 1.0, -1.0, -1.0
            upper.append(row)
            rhs.append(-(change[k, p] - change[k, q] + w))
    low = np.maximum(preload_box[0], band[0] + own - change.min(axis=0))
    high = np.minimum(preload_box[1], band[1] - own - change.max(axis=0))
    result = linprog(
        np.r_[np.zeros(n), 1.0],
        A_ub=np.array(upper),
        b_ub=np.array(rhs),
        A_eq=np.c_[rows, np.zeros(3)],
        b_eq=b0,
        bounds=[(lo, hi) for lo, hi in zip(low, high)] + [(None, None)],
        method="highs",
    )
    return result.fun if result.status == 0 else None


@pytest.mark.parametrize("cranes", [3, 4])
def test_set_bound_is_the_sets_own_lp(cranes):
    """Three and four lugs: each set's bound equals the linear program of its own rows built
    from the held model (tensions and their hook sensitivities at the scenarios), at every
    set of the seven candidates; a set it drops has no feasible preload there."""
    problem = small_problem(cranes, hook_tolerance=0.02)
    mip = lug_mip.LugMip(problem, 1e4)
    scenarios = first_scenarios(problem)
    data = lug_mip.poses(problem, scenarios)
    count = len(problem.candidates)
    kappa = np.full(count, mip.classes.stiffness[0])
    tables = set_tables(
        data.level_plan, kappa, np.full(count, 0.02), np.ones(count), cranes, np.ones(count, bool), 1e-3
    )
    assert len(tables.sets) == 35 if cranes == 4 else len(tables.sets) > 0
    level = lug_mip.poses(problem, [Scenario(0.0, 0.0)])
    band_low, band_high = lug_mip.tension_band(problem, mip.swl, mip.cutoff)
    preload_box = (np.maximum(mip.preload_low, band_low)[:, 0], np.minimum(mip.preload_high, band_high)[:, 0])
    band = (band_low[:, 0], np.minimum(mip.limit, band_high)[:, 0])
    bound = set_bounds(
        tables,
        kappa,
        np.ones(count),
        (level.a_mat[0], level.b_vec[0], scenario_vectors(data.a_mat, data.b_vec, data.level_plan)),
        preload_box,
        band,
        peak=False,
    )
    feasible = 0
    for indices, value in zip(tables.sets, bound):
        lp = _model_lp(
            problem,
            tuple(indices),
            scenarios,
            (preload_box[0][indices], preload_box[1][indices]),
            (band[0][indices], band[1][indices]),
        )
        if lp is None:
            assert value == np.inf
            continue
        feasible += 1
        assert value == pytest.approx(lp, rel=1e-7)
    assert feasible >= 3


def _brute_force(problem):
    evaluator = SetEvaluator(problem)
    values = {}
    for indices in itertools.combinations(range(len(problem.candidates)), problem.cranes):
        try:
            values[indices] = evaluator.evaluate(indices).worst_value
        except SetInfeasible:
            continue
    return evaluator, values


@pytest.mark.parametrize(
    "problem",
    [
        pytest.param(small_problem(4, hook_tolerance=0.02), id="4 spread"),
        pytest.param(small_problem(5, hook_tolerance=0.03), id="5 spread", marks=pytest.mark.slow),
        pytest.param(
            small_problem(4, hook_tolerance=0.02, objective="reserve"), id="4 reserve", marks=pytest.mark.slow
        ),
        pytest.param(small_problem(3, hook_tolerance=0.02), id="3 spread", marks=pytest.mark.slow),
    ],
)
def test_no_set_row_cuts_off_a_better_set(problem):
    """Brute force over every set of seven candidates with its hook errors: at a cutoff just
    above the optimum, and at one above every set's worst, every set that beats the cutoff is
    kept by the set-wise rows and its bound is at most its worst value (the bound is of the
    whole box, the dense check a part of it)."""
    evaluator, values = _brute_force(problem)
    best = min(values.values())
    for cutoff in (best * (1 + 1e-6), 2.0 * max(values.values())):
        mip = lug_mip.LugMip(problem, cutoff, dense=evaluator.dense)
        sets, bound = mip.set_bounds(first_scenarios(problem))
        kept = {tuple(int(i) for i in s): float(v) for s, v in zip(sets, bound)}
        better = [s for s, v in values.items() if v < cutoff]
        assert better
        for indices in better:
            assert indices in kept
            assert kept[indices] <= values[indices] * (1 + 1e-9)
    assert len(better) == len(values)


@pytest.mark.parametrize(
    "problem",
    [
        pytest.param(small_problem(4, hook_tolerance=0.02), id="4 spread"),
        pytest.param(
            small_problem(4, hook_tolerance=0.02, objective="reserve"), id="4 reserve", marks=pytest.mark.slow
        ),
    ],
)
def test_mip_plan_is_the_brute_forces(monkeypatch, problem):
    """The MIP with the set-wise rows, its first plan's bound set aside: it proves the brute
    force's least worst value, and its set is that set (or its mirror image)."""
    first = lug_mip._incumbent

    def unproved(problem, started):
        ranking, stats = first(problem, started)
        return ranking, dataclasses.replace(stats, lower_bound=0.0)

    monkeypatch.setattr(lug_mip, "_incumbent", unproved)
    _, values = _brute_force(problem)
    best = min(values.values())
    ranking, stats = search(dataclasses.replace(problem, search="mip"), 1)
    assert stats.stopped == "proved"
    assert ranking[0].worst_value == pytest.approx(best, rel=1e-6)
    assert values[ranking[0].indices] == pytest.approx(best, rel=1e-6)
    assert best * (1 - 1e-6) <= stats.lower_bound <= best * (1 + 1e-9)
