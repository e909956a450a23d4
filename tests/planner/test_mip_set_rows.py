"""The MIP's set-wise hook rows (planner/search/mip_hooks.py, set_tables and set_bounds):
each set's bound is its own linear program from the held model (brute force over every set
against the evaluator and the MIP's plan: tests/planner/test_mip_hook_box.py)."""

import numpy as np
import pytest
from scipy.optimize import linprog
from support.planning import small_problem

import liftplan.planner.search.mip as lug_mip
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
