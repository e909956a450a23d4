"""The dual bound with hook-height tolerances: exact pair rows, one soft maximum per scenario.

The bound must stay below the true worst spread over every vertex of the hook box (the held
model itself, not the closed form), its smoothed objective's derivatives must be those of
the function it minimises, and the plan it prunes for must be the brute force's."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from support.planning import small_problem

from liftplan.planner.plan import plan
from liftplan.planner.search import dual
from liftplan.planner.search.evaluator import SetEvaluator, SetInfeasible
from liftplan.planner.search.scenarios import LugSet, Scenario
from liftplan.planner.search.screen import (
    FEASIBLE,
    all_sets,
    row_ceiling,
    screen,
    screening_scenarios,
)


def _corner_scenarios(problem):
    """The dual bound's scenarios (box corners and level, every CG vertex) as Scenarios."""
    x, offsets = screening_scenarios(problem, corners=True)
    return [
        Scenario(float(np.degrees(h)), float(np.degrees(t)), tuple(map(float, o)))
        for (_, h, t), o in zip(x, offsets)
    ]


def test_hook_gain_does_not_depend_on_the_preload():
    """dT/dH at a scenario is P_k EA / L whatever the boom heights (the held model is affine in
    the preload while every rope is taut): the hook widening c_ab is a constant of the set."""
    problem = small_problem(5, hook_tolerance=0.03)
    lugset = LugSet(problem, (0, 1, 2, 4, 6))
    scenarios = _corner_scenarios(problem)[:6]
    gains, _ = lugset.affine(scenarios)
    a_level, b_level = lugset.level_statics
    even = np.linalg.lstsq(a_level, b_level, rcond=None)[0]
    null = np.linalg.svd(a_level)[2][3:]  # (2, 5): preloads that keep the level statics
    for move in ((0.0, 0.0), (15.0, -10.0), (-20.0, 5.0)):
        preload = even + np.array(move) @ null
        tensions, gain = lugset.tensions_and_gain(preload, scenarios)
        assert np.all(tensions > 0)
        np.testing.assert_allclose(gain, gains * lugset.stiffness[None, None, :], rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("cranes", [5, 6])
def test_bound_is_below_the_worst_spread_over_every_hook_vertex(cranes):
    """For each set the dual bound (with the hook errors' pair rows) is at most the worst
    spread that the set's own best preload meets over the dual's scenarios and every vertex of
    the hook box, each vertex solved by the held model with the boom heights moved (the first
    three sets the exact evaluation finds feasible)."""
    problem = small_problem(cranes, hook_tolerance=0.03)
    sets = all_sets(problem)
    found = screen(problem, sets, dual=True)
    scenarios = _corner_scenarios(problem)
    evaluator = SetEvaluator(problem)
    checked = 0
    for indices, bound, reason in zip(sets, found.bound, found.reason):
        if reason != FEASIBLE:
            continue
        try:
            result = evaluator.evaluate(indices, screen_bound=bound)
        except SetInfeasible:
            continue
        lugset = LugSet(problem, indices)
        boom = lugset.boom_heights(result.preload)
        worst = -np.inf
        for signs in itertools.product((-1.0, 1.0), repeat=cranes):
            tensions = lugset._evaluate(scenarios, boom + np.array(signs) * lugset.hook_tolerance)[0]
            assert np.all(tensions > 0)  # every rope taut: the held model holds
            worst = max(worst, float(np.ptp(tensions, axis=1).max()))
        # the LP's preload is the best over the box, so no preload does better than it there
        assert bound <= worst + 1e-6 * problem.body.weight
        assert bound <= result.bound + 1e-6 * problem.body.weight
        checked += 1
        if checked == 3:
            break
    assert checked == 3


def _pair_case(seed, count=3, m=4, n=5, d=2):
    rng = np.random.default_rng(seed)
    alpha = rng.normal(size=(count, m, n)) * 20.0
    beta = rng.normal(size=(count, m, n, d)) * 3.0
    pair = np.abs(rng.normal(size=(count, m, n, n))) * 2.0
    pair = pair + pair.transpose(0, 1, 3, 2)
    pair[..., np.arange(n), np.arange(n)] = 0.0
    low = np.full((count, m, n), -200.0)
    high = np.full((count, m, n), 200.0)
    return alpha, beta, pair, low, high


def test_pair_weights_derivatives_are_the_smoothed_objectives():
    """Gradient and Hessian of the pair soft maximum (plus the limits' penalty) against central
    differences of :func:`dual._objective` itself."""
    alpha, beta, pair, low, high = _pair_case(4)
    count, m, n, d = beta.shape
    tau = np.full(count, 1.5)
    y = np.random.default_rng(5).normal(size=(count, d))

    def objective(point):
        values = alpha + np.einsum("kmid,kd->kmi", beta, point)
        return dual._objective(values, tau, False, low, high, pair)

    values = alpha + np.einsum("kmid,kd->kmi", beta, y)
    weights = dual._Weights(values, tau, False, low, high, pair)
    np.testing.assert_allclose(weights.objective, objective(y), rtol=1e-12)
    grad, hess = weights.derivatives(beta, beta.reshape(count, m * n, d))
    step = 1e-4
    for j in range(d):
        e = np.zeros(d)
        e[j] = step
        np.testing.assert_allclose(grad[:, j], (objective(y + e) - objective(y - e)) / (2 * step), rtol=1e-6)
        for i in range(d):
            f = np.zeros(d)
            f[i] = step
            second = (
                objective(y + e + f) - objective(y + e - f) - objective(y - e + f) + objective(y - e - f)
            ) / (4 * step * step)
            np.testing.assert_allclose(hess[:, i, j], second, rtol=1e-4, atol=1e-6)


def test_pair_certificate_is_a_lower_bound_for_any_preload():
    """The certificate from any point's weights is at most max_k,ab (V_a - V_b + c_ab) at every
    preload in the box (sampled), the pair rows' LP value being their least maximum."""
    alpha, beta, pair, low, high = _pair_case(6, count=2, n=6, d=3)
    count, m, n, d = beta.shape
    rng = np.random.default_rng(8)
    null = np.linalg.qr(rng.normal(size=(count, n, d)))[0]  # orthonormal columns
    particular = rng.normal(size=(count, n)) * 5.0
    box_low, box_high = particular - 4.0, particular + 4.0
    # the values move with T* = T_p + N y: beta of the rows is their slope along N
    beta = np.einsum("kmin,knd->kmid", rng.normal(size=(count, m, n, n)) * 0.5, null)
    for tau in (5.0, 0.5, 0.05):
        y = rng.normal(size=(count, d))
        values = alpha + np.einsum("kmid,kd->kmi", beta, y)
        weights = dual._Weights(values, np.full(count, tau), False, low, high, pair)
        bound = weights.certificate(particular, null, alpha, beta, box_low, box_high)
        for _ in range(200):
            # any preload in the box: T* - T_p in N's span (the level statics kept)
            u = rng.uniform(-1, 1, size=(count, d)) * 4.0 / np.sqrt(d)
            values = alpha + np.einsum("kmid,kd->kmi", beta, u)
            rows = values[..., :, None] - values[..., None, :] + pair
            assert np.all(bound <= rows.reshape(count, -1).max(axis=1) + 1e-9)


@pytest.mark.parametrize("cranes", [5, 6])
def test_plan_with_hook_tolerance_is_the_brute_forces(cranes):
    """Every set of the small problem evaluated exactly (no screening, no dual bound): the
    exact search's plan has the least worst spread, and its set is that set; every feasible
    set's value is below the ceiling of :func:`screen.value_ceiling`."""
    problem = small_problem(cranes, hook_tolerance=0.03, top=1)
    result = plan(problem)
    evaluator = SetEvaluator(problem)
    values = {}
    for indices in itertools.combinations(range(len(problem.candidates)), cranes):
        try:
            values[indices] = evaluator.evaluate(indices).worst_value
        except SetInfeasible:
            continue
    # no feasible set's value is above the ceiling past which a bound proves a set infeasible
    sets = np.array(list(values))
    ceiling = row_ceiling(problem, sets, np.broadcast_to(np.arange(cranes), sets.shape))
    assert np.all(np.array(list(values.values())) <= ceiling)
    best = min(values, key=values.get)
    assert result.stats.stopped == "proved"
    assert result.worst_spread == pytest.approx(values[best], abs=1e-6 * problem.body.weight)
    assert tuple(result.chosen.indices) == best
    assert result.stats.lower_bound <= values[best] + 1e-6 * problem.body.weight
