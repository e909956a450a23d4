"""The exact search's shortcuts with hook-height tolerances (issue 24 item 4): none cuts off
the optimum.

* the hook widening is worked out only for the scenarios the dual bound takes
  (:class:`~liftplan.planner.search.dual.PairWidening`), its upper estimate ranking them;
* a row's dual bound may stop at its first stage and be bounded again later (deferred);
* the rows are refined in the order of their bound without the widening
  (:attr:`~liftplan.planner.search.screen.Screening.priority`), not of the bound itself;
* ties to solver rounding are then ranked by the lugs (:func:`~liftplan.planner.search.exact.rank_key`).

Each is checked against its definition or against brute force over every set (C = 7).
"""

from __future__ import annotations

import itertools
from types import SimpleNamespace

import numpy as np
import pytest
from support.planning import small_problem

from liftplan.planner.search import dual, exact
from liftplan.planner.search.evaluator import SetEvaluator, SetInfeasible
from liftplan.planner.search.methods import search
from liftplan.planner.search.screen import FEASIBLE, all_sets, screen


def _widening_case(seed, count=3, m=6, n=6):
    rng = np.random.default_rng(seed)
    scaled = rng.normal(size=(count, m, n, n)) * 10.0
    delta = rng.uniform(0.0, 0.05, size=(count, n))
    return scaled, delta


def _widening_by_definition(scaled, delta):
    """c_ab = sum_j |s_a G_aj - s_b G_bj| delta_j, one pair at a time."""
    count, m, n, _ = scaled.shape
    out = np.zeros((count, m, n, n))
    for k, s, a, b in itertools.product(range(count), range(m), range(n), range(n)):
        out[k, s, a, b] = np.abs(scaled[k, s, a] - scaled[k, s, b]) @ delta[k]
    return out


def test_pair_widening_at_some_scenarios_is_the_definitions():
    """full(), at(rows), subset() and upper_triangle() against the sum itself; the upper
    estimate u_a + u_b is never below c_ab (the scenarios it ranks may be any: a bound over
    some rows is a bound over all)."""
    scaled, delta = _widening_case(1)
    widening = dual.PairWidening(scaled, delta)
    expected = _widening_by_definition(scaled, delta)
    np.testing.assert_allclose(widening.full(), expected, rtol=1e-13, atol=1e-13)
    rows = np.array([[0, 3], [5, 1], [2, 2]])
    np.testing.assert_allclose(
        widening.at(rows), np.take_along_axis(expected, rows[..., None, None], axis=1), rtol=1e-13
    )
    np.testing.assert_allclose(widening.subset([2, 0]).full(), expected[[2, 0]], rtol=1e-13)
    first, second = np.triu_indices(scaled.shape[2], 1)
    np.testing.assert_allclose(widening.upper_triangle(), expected[..., first, second], rtol=1e-13)
    each = widening.each()
    assert np.all(expected <= each[..., :, None] + each[..., None, :] + 1e-12)


def _lp_case(seed, count=6, m=12, n=6, d=3):
    """Random pair rows with a hook widening, a preload box and wide limits."""
    rng = np.random.default_rng(seed)
    null = np.linalg.qr(rng.normal(size=(count, n, d)))[0]
    particular = rng.normal(size=(count, n)) * 5.0
    alpha = rng.normal(size=(count, m, n)) * 20.0
    beta = np.einsum("kmin,knd->kmid", rng.normal(size=(count, m, n, n)) * 0.5, null)
    scaled, delta = _widening_case(seed + 1, count, m, n)
    limits = (np.full((count, m, n), -500.0), np.full((count, m, n), 500.0))
    return particular, null, alpha, beta, particular - 4.0, particular + 4.0, limits, scaled, delta


@pytest.mark.parametrize("seed", [2, 3])
def test_deferred_and_lazy_bounds_are_below_every_preload(seed):
    """staged_lp_bound with the widening given lazily and every set deferrable: each bound
    (deferred or not) is at most the worst row at every sampled preload of the box; a deferred
    set is one whose first-stage bound fell short of the target; the bound with the widening
    worked out in full is valid the same way."""
    particular, null, alpha, beta, low, high, limits, scaled, delta = _lp_case(seed)
    count, m, n, d = beta.shape
    pair = _widening_by_definition(scaled, delta)
    # a target in reach of some sets, not of others
    free = dual.staged_lp_bound(particular, null, alpha, beta, low, high, limits, pair=pair)[0]
    target = np.median(free)
    lazy, partial = dual.staged_lp_bound(
        particular,
        null,
        alpha,
        beta,
        low,
        high,
        limits,
        target=target,
        pair=dual.PairWidening(scaled, delta),
        defer=True,
    )
    assert np.all(lazy[partial] < target)
    rng = np.random.default_rng(seed + 10)
    worst = np.full(count, np.inf)
    for _ in range(400):  # any preload in the box keeping the level statics (y in N's span)
        u = rng.uniform(-1, 1, size=(count, d)) * 4.0 / np.sqrt(d)
        values = alpha + np.einsum("kmid,kd->kmi", beta, u)
        rows = values[..., :, None] - values[..., None, :] + pair
        worst = np.minimum(worst, rows.reshape(count, -1).max(axis=1))
    assert np.all(lazy <= worst + 1e-9)
    assert np.all(free <= worst + 1e-9)


def test_priority_is_the_bound_without_the_hook_widening():
    """Without hook errors the refinement order is the bound itself; with them it is the pair
    bound without their widening, at most the bound with it (up to the golden search's
    margin) and at least the no-hook bound."""
    problem = small_problem(5, hook_tolerance=0.03)
    sets = all_sets(problem)
    plain = screen(small_problem(5, hook_tolerance=0.0), sets, coarse=True)
    assert np.array_equal(plain.priority, plain.bound)
    hooked = screen(problem, sets, coarse=True)
    ok = (hooked.reason == FEASIBLE) & (plain.reason == FEASIBLE)
    assert np.any(ok)
    weight = problem.body.weight
    assert np.all(hooked.priority[ok] >= plain.bound[ok] - 1e-6 * weight)
    assert np.all(hooked.priority[ok] <= hooked.bound[ok] + 1e-3 * weight)
    assert np.any(hooked.priority[ok] < hooked.bound[ok] - 1.0)  # the widening matters here


@pytest.fixture(scope="module")
def brute():
    """Every set of the 7-point tanker (6 cranes, hook errors 0.03 m) evaluated exactly."""
    problem = small_problem(6, hook_tolerance=0.03)
    evaluator = SetEvaluator(problem)
    values = {}
    for indices in itertools.combinations(range(len(problem.candidates)), 6):
        try:
            values[indices] = evaluator.evaluate(indices).worst_value
        except SetInfeasible:
            continue
    return problem, values


def test_search_in_small_batches_with_deferred_bounds_is_the_brute_forces(brute, monkeypatch):
    """The exact search refining two rows at a time (so that later batches have a target and
    defer some bounds, and the priority order differs from the bound's) ranks the brute
    force's three best sets, in its order, proved."""
    problem, values = brute
    deferred = []
    original = exact.screen

    def counting(*args, **kwargs):
        found = original(*args, **kwargs)
        if found.partial is not None:
            deferred.append(int(found.partial.sum()))
        return found

    monkeypatch.setattr(exact, "REFINE", 2)
    monkeypatch.setattr(exact, "screen", counting)
    ranking, stats = search(problem, top=3)
    assert stats.stopped == "proved"
    assert sum(deferred) > 0  # the deferral was exercised
    order = sorted(values, key=values.get)
    tol = 1e-6 * problem.body.weight
    for result, indices in zip(ranking, order[:3]):
        assert result.worst_value == pytest.approx(values[indices], abs=tol)
    assert tuple(ranking[0].indices) == order[0]
    assert stats.lower_bound <= values[order[0]] + tol


def test_the_priority_order_changes_the_refinement_order(brute):
    """The 7-point case is one where the two orders differ (else the test above would not
    test the priority)."""
    problem, _ = brute
    found = screen(problem, all_sets(problem), coarse=True)
    ok = np.isfinite(found.bound)
    assert not np.array_equal(np.argsort(found.priority[ok]), np.argsort(found.bound[ok]))


def test_ties_to_rounding_are_ranked_by_the_lugs():
    """Two rows equal to RANK_DIGITS significant digits rank by candidate indices whatever
    order they were evaluated in; a real difference still ranks by value."""

    def row(value, indices, nominal=5.0):
        return SimpleNamespace(worst_value=value, nominal_value=nominal, indices=indices, cranes=(0, 1))

    a = row(115.92856748503671, (0, 1, 2))
    b = row(115.9285674838608, (0, 1, 3))  # a mirror set, 1e-10 apart
    assert sorted([b, a], key=exact.rank_key) == [a, b]
    assert sorted([a, b], key=exact.rank_key) == [a, b]
    c = row(115.92, (0, 1, 4))
    assert sorted([a, c], key=exact.rank_key) == [c, a]
    assert exact.RANK_DIGITS >= 7  # 1e-7 relative: far finer than the 1 kg the LP is held to


def test_screening_reports_the_rows_it_deferred():
    """screen(defer=...) flags only rows it was allowed to defer, each below the target."""
    problem = small_problem(5, hook_tolerance=0.03)
    sets = all_sets(problem)
    first = screen(problem, sets, dual=True)
    target = float(np.median(first.bound[np.isfinite(first.bound)]))
    allowed = np.arange(len(sets)) % 2 == 0
    found = screen(problem, sets, dual=True, target=target, defer=allowed)
    assert found.partial is not None
    assert not np.any(found.partial & ~allowed)
    assert np.all(found.bound[found.partial] < target)
