"""Review finding 3: the plan is the best ranked set that meets the design-load checks.

The search ranks lug sets by the objective; a lug's ``capacity`` (the rules' lug design load)
is checked only after it, on the ranked sets. Three of the tanker's seven deck points: the
search's best set C1 C2 C4 puts 478.3 t of design load on C1, the second C0 C3 C4 does not use
C1. With C1's capacity 470 t the plan must be the second set (the best ranked set that meets
every design check, as a brute force over the ranked sets finds); with C4's capacity 100 t (C4
is in every ranked set) none meets them and the plan stays the search's best, flagged.
"""

from __future__ import annotations

import dataclasses

import pytest
from support.planning import small_problem

from liftplan.planner import plan
from liftplan.planner.plans.design_loads import design_loads
from liftplan.planner.search.methods import search


def _with_capacity(problem, name, capacity):
    candidates = tuple(
        dataclasses.replace(c, capacity=capacity) if c.name == name else c for c in problem.candidates
    )
    return dataclasses.replace(problem, candidates=candidates)


@pytest.fixture(scope="module")
def searched():
    """The search's own ranking of the small problem (no design check in it)."""
    problem = small_problem(3, top=3)
    ranking, _ = search(problem, 3)
    return problem, ranking


def _brute_force(problem, ranking):
    """The first set of the search's ranking whose every design check passes, by the design
    chain run on each ranked set on its own (None when none passes)."""
    labels = [f"L{k + 1}" for k in range(problem.cranes)]
    designs = design_loads(problem, ranking, labels)
    passing = [r for r, d in zip(ranking, designs) if all(c.ok for c in d.checks)]
    return (passing[0] if passing else None), designs


def test_the_plan_is_the_best_ranked_set_that_meets_the_lug_capacity(searched):
    problem, ranking = searched
    problem = _with_capacity(problem, "C1", 470.0)
    expected, designs = _brute_force(problem, ranking)
    # the case is what it says: the search's best fails C1's lug check, a later set passes
    assert ranking[0].lugs == ("C1", "C2", "C4")
    first = {c.name: c for c in designs[0].checks if c.name == "lug_design_load"}
    assert not first["lug_design_load"].ok and first["lug_design_load"].subject == "C1"
    assert expected is not None and expected.lugs == ("C0", "C3", "C4")

    result = plan(problem)
    assert result.chosen.lugs == expected.lugs
    assert all(c.ok for c in result.checks)
    assert result.passed_over == 1
    assert "the plan is the best ranked set that meets every design-load check" in result.design_note
    # the search's best is still in the ranking, after the plan, flagged
    assert [r.lugs for r in result.ranking] == [r.lugs for r in [expected, ranking[0], ranking[2]]]
    assert [d.ok for d in result.ranked_design] == [True, False, False]
    # its value and the proved bound are the plan's own: every better set fails a check
    assert result.stats.best == pytest.approx(float(expected.worst_value))
    assert result.stats.lower_bound == pytest.approx(result.stats.best)
    data = result.to_json()
    assert data["design_first"]["met"] and data["design_first"]["passed_over"] == 1
    assert data["ranking"][0]["design_ok"] and not data["ranking"][1]["design_ok"]


def test_when_no_ranked_set_meets_them_the_plan_is_flagged_and_says_so(searched):
    problem, ranking = searched
    problem = _with_capacity(problem, "C4", 100.0)
    expected, _ = _brute_force(problem, ranking)
    assert expected is None  # C4 is in every ranked set
    result = plan(problem)
    assert result.chosen.lugs == ranking[0].lugs  # the order stands
    failed = [c for c in result.checks if not c.ok]
    assert [(c.name, c.subject) for c in failed] == [("lug_design_load", "C4")]
    assert result.design_note.startswith("none of the 3 ranked sets meets every design-load check")
    assert not result.to_json()["design_first"]["met"]
