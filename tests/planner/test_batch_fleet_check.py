"""The batch check of a plan on an unequal fleet: each rope against its own crane's chart SWL
at its radius, with the plan's crane assignment (not the first cranes of the fleet in order,
nor one [crane] SWL for all)."""

import numpy as np
from helpers import EXAMPLES

from liftplan.planner import load_problem, plan
from liftplan.planner.batch.check import CheckCases, check_plan
from liftplan.planner.search.scenarios import LugSet, Scenario


def test_check_uses_each_ropes_crane_and_its_chart_swl():
    problem = load_problem(EXAMPLES / "tanker_fleet.toml")
    chosen = plan(problem).chosen
    assert len(set(np.round(chosen.swl, 6))) > 1  # the cranes differ: the test can tell
    cases = CheckCases(
        weight=np.array([problem.body.weight]),
        cog=np.array([problem.body.cog]),
        heel_tolerance=np.array([0.0]),
        trim_tolerance=np.array([0.0]),
        min_tension=np.array([0.0]),
    )
    result = check_plan(problem, chosen.indices, chosen.preload, cases, grid=3, cranes=chosen.cranes)
    lugset = LugSet(problem, chosen.indices, chosen.cranes)
    level = lugset.tensions(chosen.preload, [Scenario(0.0, 0.0)])[0]
    assert np.allclose(level, chosen.preload, rtol=1e-9, atol=1e-9)  # level holds T*
    assert result.status == ["ok"]
    assert abs(result.utilisation[0] - np.max(level / chosen.swl)) < 1e-9
    assert abs(result.max_tension[0] - level.max()) < 1e-9
