"""Monte-Carlo hook-height errors on the forward elastic model: the plan's worst case holds."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import EXAMPLES

from liftplan.model.errors import InvalidScene
from liftplan.planner.batch.montecarlo import hook_monte_carlo
from liftplan.planner.plan import plan
from liftplan.planner.problem.file import load_problem


@pytest.fixture(scope="module")
def tanker_plan():
    return plan(load_problem(EXAMPLES / "tanker_plan.toml"))  # hook_tolerance = 0.02 m


def test_no_draw_inside_the_tolerance_exceeds_the_plan(tanker_plan):
    mc = hook_monte_carlo(tanker_plan, draws=3000, seed=7)
    assert mc.failed == 0 and np.all(mc.inside)
    solved = mc.tensions[mc.solved]
    # the plan's worst case covers every error in the box, every attitude of the tolerance box
    # and the CG envelope; 1e-6 t: both are solved to 1e-9 W
    assert mc.spread.max() <= tanker_plan.worst_spread + 1e-6
    assert np.all(solved.max(axis=0) <= np.asarray(tanker_plan.chosen.rope_max) + 1e-6)
    assert np.all(solved.max(axis=0) <= mc.design_load)
    summary = mc.summary()
    assert summary["p_spread_above_plan_worst"] == 0.0 and summary["p_above_swl"] == 0.0
    # the draws are not trivial: they spread the ropes well beyond the level spread
    assert summary["spread_p95"] > 2 * tanker_plan.spread


def test_draws_are_reproducible_and_larger_errors_exceed_the_plan(tanker_plan):
    first = hook_monte_carlo(tanker_plan, draws=200, seed=3)
    again = hook_monte_carlo(tanker_plan, draws=200, seed=3)
    np.testing.assert_array_equal(first.tensions, again.tensions)
    worse = hook_monte_carlo(tanker_plan, draws=2000, tolerance=0.1, seed=3).summary()
    # five times the planned tolerance: the crew's errors now exceed the plan's worst spread
    assert worse["p_spread_above_plan_worst"] > 0.2
    normal = hook_monte_carlo(tanker_plan, draws=500, distribution="normal", seed=3)
    assert not np.all(normal.inside)  # a normal draw leaves the box now and then


@pytest.mark.parametrize(("kwargs", "message"), [
    ({"draws": 0}, "draws = 0: expected an integer >= 1"),
    ({"distribution": "gauss"}, "expected uniform or normal"),
    ({"tolerance": -0.1}, "expected finite hook tolerances >= 0 m"),
])
def test_bad_input(tanker_plan, kwargs, message):
    with pytest.raises(InvalidScene, match=message):
        hook_monte_carlo(tanker_plan, **kwargs)
