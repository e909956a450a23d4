"""The MIP's hook-error rows over the whole hook box (planner/search/mip_hooks.py): exact at
every set, no set-wise row drops or over-bounds a set that beats the cutoff (brute force), and
the MIP's plan with a hook tolerance is the brute force's."""

import dataclasses
import itertools

import cvxpy as cp
import numpy as np
import pytest
from support.fleet import fleet_problem
from support.planning import small_problem

import liftplan.planner.search.mip as lug_mip
from liftplan.planner.search.evaluator import SetEvaluator, SetInfeasible
from liftplan.planner.search.methods import search
from liftplan.planner.search.mip_hooks import Columns, lug_coefficients, on_one_plane, residuals, widening
from liftplan.planner.search.scenarios import first_scenarios


def _fit_widening(plan, kappa, delta, chosen, c):
    """sum_S kappa delta |c - f| with f the kappa-weighted least-squares plane of c over S."""
    basis = np.column_stack([np.ones(len(plan)), plan])[chosen]
    w = kappa[chosen]
    mu = np.linalg.solve(basis.T @ (w[:, None] * basis), basis.T @ (w * c[chosen]))
    return float(np.sum(w * delta[chosen] * np.abs(c[chosen] - basis @ mu)))


def test_widening_is_the_closed_form_at_every_set():
    """With y fixed to a set, the rows' least widening is the closed form of the fit's
    residual (unequal stiffness and tolerance per column), for one lug's own row and for a
    pair's, and the diagonal's sum is n - 3."""
    rng = np.random.default_rng(7)
    count, n = 7, 5
    plan = rng.uniform(-20.0, 20.0, size=(count, 2))
    kappa = rng.uniform(1000.0, 2000.0, size=count)
    delta = rng.uniform(0.01, 0.03, size=count)
    columns = Columns(np.arange(count), kappa, delta, plan, n)
    for chosen in [(0, 1, 2, 4, 6), (1, 2, 3, 5, 6)]:
        y = cp.Variable(count, boolean=True)
        mask = np.isin(np.arange(count), chosen)
        own, cons = residuals(cp, y, columns, lug_coefficients(np.ones(count), np.arange(count), count), 1.0)
        rise, more = widening(cp, own, columns)
        wide, extra = widening(cp, own[0:1, :] - own[2:3, :], columns)
        trace = cp.sum(cp.hstack([own[i, i] for i in range(count)]))
        values = {}
        for name, target in {"own 4": rise[4], "pair 0-2": wide[0], "trace": trace}.items():
            problem = cp.Problem(cp.Minimize(target), cons + more + extra + [y == mask.astype(float)])
            problem.solve(solver=cp.HIGHS)
            values[name] = problem.value
        unit = np.eye(count)
        assert values["own 4"] == pytest.approx(_fit_widening(plan, kappa, delta, mask, unit[4]), rel=1e-7)
        assert values["pair 0-2"] == pytest.approx(
            _fit_widening(plan, kappa, delta, mask, unit[0] - unit[2]), rel=1e-7
        )
        assert values["trace"] == pytest.approx(n - 3, rel=1e-7)


def test_box_rows_give_each_set_its_exact_worst():
    """The MIP with its lugs fixed, over the first scenarios and the set's worst marked for
    the box rows, has the evaluator's worst value with the hook errors (the evaluator takes
    them from the held model's sensitivities; the MIP from the fit)."""
    problem = small_problem(4, hook_tolerance=0.02)
    assert on_one_plane(problem)
    evaluator = SetEvaluator(problem)
    checked = 0
    for indices in itertools.combinations(range(len(problem.candidates)), problem.cranes):
        if checked == 3:
            break
        try:
            result = evaluator.evaluate(indices)
        except SetInfeasible:
            continue
        checked += 1
        mip = lug_mip.LugMip(problem, 10 * result.worst_value)
        assert mip.box
        mip.mirror = None
        mip.usable = mip.usable & np.isin(np.arange(len(problem.candidates)), indices)[:, None]
        cuts = [lug_mip.Cut(s) for s in lug_mip.first_scenarios(problem)] + [
            lug_mip.Cut(result.worst, box=True)
        ]
        solution = mip.solve(cuts)
        assert solution.indices == indices
        assert solution.value == pytest.approx(result.worst_value, rel=1e-6)
    assert checked == 3


def _brute_force(problem):
    evaluator = SetEvaluator(problem)
    values = {}
    for indices in itertools.combinations(range(len(problem.candidates)), problem.cranes):
        try:
            values[indices] = evaluator.evaluate(indices).worst_value
        except SetInfeasible:
            continue
    return evaluator, values


def _unproved(monkeypatch):
    """Set the first plan's own bound aside: the proof is then the MIP's."""
    first = lug_mip._incumbent

    def unproved(problem, started):
        ranking, stats = first(problem, started)
        return ranking, dataclasses.replace(stats, lower_bound=0.0)

    monkeypatch.setattr(lug_mip, "_incumbent", unproved)


@pytest.mark.parametrize(
    "problem",
    [
        pytest.param(small_problem(4, hook_tolerance=0.02), id="4 equal", marks=pytest.mark.slow),
        pytest.param(small_problem(5, hook_tolerance=0.03), id="5 equal", marks=pytest.mark.slow),
    ],
)
def test_mip_with_hook_tolerance_is_the_brute_forces(monkeypatch, problem):
    """Seven candidates, every set evaluated exactly with its hook errors: the MIP (box rows)
    proves the least worst value, and its set is that set."""
    _unproved(monkeypatch)
    _, values = _brute_force(problem)
    best = min(values, key=values.get)
    ranking, stats = search(dataclasses.replace(problem, search="mip"), 1)
    assert stats.stopped == "proved"
    assert ranking[0].indices == best
    assert ranking[0].worst_value == pytest.approx(values[best], rel=1e-6)
    assert stats.lower_bound <= values[best] * (1 + 1e-9)
    assert stats.lower_bound >= values[best] * (1 - 1e-6)


@pytest.mark.slow
def test_fleet_mip_with_hook_tolerance_is_the_brute_forces(monkeypatch):
    """Four unequal charted cranes (a class each, utilisation): the MIP's set, cranes and
    value are the exact search's with the hook tolerance."""
    _unproved(monkeypatch)
    problem = dataclasses.replace(fleet_problem(4, "utilisation"), hook_tolerance=0.02)
    exact, _ = search(dataclasses.replace(problem, search="exact"), 1)
    ranking, stats = search(dataclasses.replace(problem, search="mip"), 1)
    assert stats.stopped == "proved"
    assert (ranking[0].indices, ranking[0].cranes) == (exact[0].indices, exact[0].cranes)
    assert ranking[0].worst_value == pytest.approx(exact[0].worst_value, rel=1e-6)


@pytest.mark.parametrize(
    "problem",
    [
        pytest.param(small_problem(4, hook_tolerance=0.02), id="4 spread"),
        pytest.param(small_problem(5, hook_tolerance=0.03), id="5 spread", marks=pytest.mark.slow),
        pytest.param(
            small_problem(4, hook_tolerance=0.02, objective="reserve"), id="4 reserve", marks=pytest.mark.slow
        ),
        pytest.param(small_problem(3, hook_tolerance=0.02), id="3 spread", marks=pytest.mark.slow),
        pytest.param(
            small_problem(4, hook_tolerance=0.02, objective="utilisation"),
            id="4 utilisation",
            marks=pytest.mark.slow,
        ),
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


def test_reserve_plan_is_the_brute_forces(monkeypatch):
    """The ``reserve`` objective (each rope's own largest T / SWL with its hook errors, the
    set-wise rows' peak form), its first plan's bound set aside: the MIP proves the brute
    force's least worst value, and its set has that value (the spread's cases:
    :func:`test_mip_with_hook_tolerance_is_the_brute_forces`)."""
    problem = small_problem(4, hook_tolerance=0.02, objective="reserve")
    _unproved(monkeypatch)
    _, values = _brute_force(problem)
    best = min(values.values())
    ranking, stats = search(dataclasses.replace(problem, search="mip"), 1)
    assert stats.stopped == "proved"
    assert ranking[0].worst_value == pytest.approx(best, rel=1e-6)
    assert values[ranking[0].indices] == pytest.approx(best, rel=1e-6)
    assert best * (1 - 1e-6) <= stats.lower_bound <= best * (1 + 1e-9)
