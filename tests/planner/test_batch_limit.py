"""One limit everywhere (issue 29 item 4): the check and Monte-Carlo studies judge a rope
against the limit the plan was made to (the rules' chain under the chart SWL: 317.5 t for
the tanker's 400 t cranes), not the bare chart SWL (a 1.3 x weight case at 317.6 t was 'ok')."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import EXAMPLES

from liftplan.planner import load_problem, plan
from liftplan.planner.batch.check import CheckCases, check_plan


@pytest.fixture(scope="module")
def tanker():
    return plan(load_problem(EXAMPLES / "tanker_plan.toml"))


def _check(tanker, factor):
    problem = tanker.problem
    cases = CheckCases(
        np.array([problem.body.weight * factor]),
        np.array([problem.body.cog]),
        np.array([problem.heel_tolerance]),
        np.array([problem.trim_tolerance]),
        np.array([1.0]),
    )
    chosen = tanker.chosen
    return check_plan(problem, chosen.indices, chosen.preload, cases, cranes=chosen.cranes)


def test_a_rope_between_the_plans_limit_and_the_swl_is_unsafe(tanker):
    limit, swl = tanker.lugset.limit, tanker.lugset.swl
    assert np.all(limit < swl)  # the chain leaves room under the chart
    result = _check(tanker, 1.3)
    assert limit.max() < result.max_tension[0] < swl.min()  # the case the SWL let pass
    assert result.status == ["unsafe"]
    assert f"over the plan's limit {limit.max():.1f} t (chart SWL 400 t" in result.reason[0]


def test_the_plans_own_weight_is_within_its_limit(tanker):
    result = _check(tanker, 1.0)
    assert result.status == ["ok"] and result.max_tension[0] <= tanker.lugset.limit.max()
