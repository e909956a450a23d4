"""The search's vectorised kernels against plain numpy / itertools, and the plan-geometry
pre-screen against the full screening (which it must never contradict)."""

import dataclasses
import itertools

import numpy as np
import pytest
from helpers import EXAMPLES

from liftplan.planner import load_problem
from liftplan.planner.search import rows
from liftplan.planner.search.screen import (
    CG_OUTSIDE,
    FEASIBLE,
    _combinations,
    _null_vector,
    _plan_geometry,
    _screen_chunk,
    screening_scenarios,
    set_rows,
)


@pytest.mark.parametrize("count, n", [(7, 3), (10, 4), (16, 5), (12, 12), (5, 1), (9, 2), (20, 6)])
def test_combinations_are_itertools_in_order(count, n):
    expected = np.array(list(itertools.combinations(range(count), n))).reshape(-1, n)
    assert np.array_equal(_combinations(count, n), expected)


@pytest.mark.parametrize("shape", [(5, 7, 4), (3, 2, 26), (11, 1), (4, 3, 1)])
def test_rope_axis_reductions_equal_numpy(shape):
    x = np.random.default_rng(2).normal(size=shape)
    assert np.array_equal(rows.row_max(x), x.max(axis=-1))
    assert np.array_equal(rows.row_min(x), x.min(axis=-1))
    assert np.array_equal(rows.row_spread(x), np.ptp(x, axis=-1))
    assert np.allclose(rows.row_sum(x), x.sum(axis=-1), rtol=1e-14, atol=1e-14)
    flags = x > 0.5
    assert np.array_equal(rows.row_max(flags), flags.any(axis=-1))


def test_null_vector_from_triangle_areas_is_the_cofactor_vector():
    rng = np.random.default_rng(3)
    a = np.concatenate([np.ones((40, 1, 4)), rng.normal(size=(40, 2, 4)) * 30.0], axis=1)
    v = _null_vector(a)
    cols = [np.delete(a, j, axis=2) for j in range(4)]
    w = np.stack([(-1) ** j * np.linalg.det(cols[j]) for j in range(4)], axis=1)
    w /= np.linalg.norm(w, axis=1, keepdims=True)
    assert np.abs(v - w).max() < 1e-12
    assert np.abs(np.einsum("kij,kj->ki", a, v)).max() < 1e-12 * 30.0


def test_plan_geometry_never_rules_out_a_set_the_full_screening_keeps():
    """Every set the pre-screen drops is one the full screening finds infeasible for the same
    reason (on the tanker, 4 and 5 of 16, every set)."""
    base = load_problem(EXAMPLES / "tanker_plan.toml")
    for n in (4, 5):
        problem = dataclasses.replace(base, cranes=n, hook_tolerance=0.0, fleet=())
        sets, cranes, *_ = set_rows(problem)
        code = _plan_geometry(problem, sets)
        assert np.any(code == CG_OUTSIDE) and np.any(code == FEASIBLE)
        dropped = code != FEASIBLE
        # the screening's own tests (without the pre-screen) on the dropped sets
        with np.errstate(divide="ignore", invalid="ignore"):
            bound, reason = _screen_chunk(
                problem, sets[dropped], cranes[dropped], screening_scenarios(problem)
            )
        assert np.all(np.isinf(bound))
        assert np.array_equal(reason, code[dropped])


def test_distinct_orders_of_a_multiset_are_itertools_set():
    from liftplan.planner.search.screen import _distinct_orders

    for labels in ([0, 0, 1], [0, 1, 1, 2], [0, 0, 0, 1, 1], [0, 1, 2, 3], [2, 2]):
        assert _distinct_orders(labels) == sorted(set(itertools.permutations(labels)))


def test_twenty_six_equal_cranes_on_their_twenty_six_points_is_one_row():
    """One crane class: one assignment, not 26! orderings (which never finished)."""
    from liftplan.planner.search.screen import assignments

    problem = load_problem(EXAMPLES / "hull154_26_given.toml")
    sets, cranes, out, _ = set_rows(problem)
    assert assignments(problem).shape == (1, 26) and sets.shape == (1, 26) and out == 0
