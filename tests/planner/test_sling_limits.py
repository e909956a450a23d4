"""A two-crane sling plan honours ``plan.time_limit`` and refuses ``plan.search = "mip"`` (review
finding 2): the enumeration of every pair of rigs checks the clock between its stages and gives
no plan when the limit runs out before it ends; when it ends in time the console says how long
it took against the limit. It has no MIP (nor local search): asked for one, it says so."""

from __future__ import annotations

import pytest
from helpers import EXAMPLES

from liftplan.model.errors import InvalidScene, PlanInfeasible
from liftplan.planner import load_problem, plan
from liftplan.planner.output.console.slings import sling_table


def _with(tmp_path, text):
    source = (EXAMPLES / "block_sling_plan.toml").read_text()
    path = tmp_path / "limits.toml"
    path.write_text(source.replace("[plan]\n", "[plan]\n" + text, 1))
    return load_problem(path)


@pytest.mark.parametrize("search", ["mip", "local"])
def test_a_search_the_two_crane_plan_has_not_is_refused(tmp_path, search):
    with pytest.raises(InvalidScene, match=f'plan.search = "{search}".*expected search = "auto" or "exact"'):
        plan(_with(tmp_path, f'search = "{search}"\n'))


def test_a_time_limit_that_runs_out_stops_the_enumeration_without_a_plan(tmp_path):
    # 1 ns: over before the first crane's rigs are in, on any machine
    with pytest.raises(
        PlanInfeasible, match=r"plan.time_limit = 1e-09 s ran out after .* before the enumeration"
    ):
        plan(_with(tmp_path, "time_limit = 1e-9\n"))


def test_a_time_limit_kept_is_reported(tmp_path):
    result = plan(_with(tmp_path, 'time_limit = 1000\nsearch = "exact"\n'))
    data = result.to_json()
    assert data["limits"]["time_limit"] == 1000 and 0.0 < data["seconds"] < 1000
    text = " ".join(sling_table(result).split())
    assert f"ended in {result.seconds:.2f} s, within plan.time_limit = 1000 s" in text
