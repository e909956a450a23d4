"""A plan that repeats on any machine (issue 29 item 12): [plan] work_limit stops a search
after counted work (rows, swaps, cells, rounds), not time; the plan says which limit stopped
it and carries its limits and the liftplan version; two runs give the same JSON."""

from __future__ import annotations

import dataclasses
import json

import pytest
from helpers import EXAMPLES

from liftplan.model.errors import InvalidScene
from liftplan.model.version import VERSION_KEY, stamped
from liftplan.planner import load_problem, loads_problem, plan


def _twice(problem):
    outs = []
    for _ in range(2):
        result = plan(problem)
        out = stamped(result.to_json())
        out["search"].pop("seconds")  # the one number a clock gives
        outs.append(json.dumps(out, sort_keys=True))
    return result, outs


@pytest.mark.parametrize(("search", "work"), [("exact", 5), ("local", 4)])
def test_two_runs_with_a_work_limit_give_the_same_json(search, work):
    problem = dataclasses.replace(
        load_problem(EXAMPLES / "tanker_plan.toml"), search=search, work_limit=work, time_limit=None
    )
    result, (first, second) = _twice(problem)
    assert first == second
    assert result.stats.stopped == "work_limit"
    data = json.loads(first)
    assert data["search"]["limits"] == {"search": search, "gap": 0.0, "time_limit": None, "work_limit": work}
    assert data["search"]["stopped"] == "work_limit" and VERSION_KEY in data


def test_the_exact_search_counts_its_rows():
    problem = dataclasses.replace(load_problem(EXAMPLES / "tanker_plan.toml"), work_limit=3)
    result = plan(problem)
    assert result.stats.evaluated == 3 and result.stats.stopped == "work_limit"
    assert result.stats.lower_bound <= result.chosen.worst_value


@pytest.mark.slow
def test_the_mip_counts_its_rounds():
    problem = dataclasses.replace(load_problem(EXAMPLES / "tanker_plan.toml"), search="mip", work_limit=2)
    result, (first, second) = _twice(problem)
    assert first == second and result.stats.refined == 2 and result.stats.stopped == "work_limit"


@pytest.mark.parametrize(
    ("example", "why"),
    [
        ("block_sling_plan.toml", "cranes on slings"),
        ("tanker_lengths.toml", "rope-length ranges"),
        ("ferry_strength_plan.toml", "plan.objective = "),
    ],
)
def test_plans_without_a_work_limit_refuse_it(example, why):
    text = (EXAMPLES / example).read_text(encoding="utf-8")
    text = text.replace("[plan]\n", "[plan]\nwork_limit = 10\n", 1)
    assert "work_limit = 10" in text
    with pytest.raises(InvalidScene, match=f"plan.work_limit: given with {why}"):
        loads_problem(text)


@pytest.mark.parametrize("value", ["0", "-3", "2.5", "true"])
def test_a_bad_work_limit_is_refused_in_one_line(value):
    text = (
        (EXAMPLES / "tanker_plan.toml")
        .read_text(encoding="utf-8")
        .replace("[plan]\n", f"[plan]\nwork_limit = {value}\n", 1)
    )
    with pytest.raises(InvalidScene, match="plan.work_limit"):
        loads_problem(text)
