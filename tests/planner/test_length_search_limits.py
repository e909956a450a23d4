"""A rope-length search under a time limit, and what every search limit tells the user
(review findings 1, 10, 12 and 17; planner/plans/lengths.py, planner/output/console/limits.py,
planner/output/report/lengths.py).

The time limit is measured on ``lengths._clock``: the tests stand a counter in for it, so a
trial "runs out of time" where the test says, on any machine (the exact searches inside keep
the machine's clock, with a limit they never reach).
"""

from __future__ import annotations

import dataclasses
import json
import re

import pytest
from helpers import EXAMPLES

from liftplan.model.errors import PlanInfeasible
from liftplan.planner import load_problem, plan
from liftplan.planner.output.console.held import plan_table
from liftplan.planner.output.console.limits import limit_lines
from liftplan.planner.output.report.held import render_html
from liftplan.planner.plans import lengths as lengths_module

LIMIT = 1000.0  # s, on the stand-in clock
CUT = 51.25  # m: the length the untimed search chooses (worst spread 117.1 t), cut short here


def _text(html):
    return re.sub(r"\s+", " ", re.sub(r"<[^>]+>", " ", html))


@pytest.fixture(scope="module")
def cut():
    """tanker_lengths.toml with time_limit = 1000 s; the trial at 51.25 m uses up what is
    left of it without finding a plan (as a 0.1 s share did in the review)."""
    clock = [0.0]
    real = lengths_module.plan_held

    def trial(problem, top, **options):
        if problem.fleet[0].rope_length == CUT:
            clock[0] += problem.time_limit  # its whole share spent
            raise PlanInfeasible("no set of 4 lugs found within the time limit")
        return real(problem, top, **options)

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(lengths_module, "_clock", lambda: clock[0])
        mp.setattr(lengths_module, "plan_held", trial)
        problem = dataclasses.replace(load_problem(EXAMPLES / "tanker_lengths.toml"), time_limit=LIMIT)
        return plan(problem)


def test_a_trial_cut_short_claims_no_bound_and_the_plan_says_the_limit_stopped_it(cut):
    stats, search = cut.stats, cut.lengths
    # the untimed search finds 117.1 t at 51.25 m: a bound above that would be false
    assert stats.lower_bound <= 117.0
    assert stats.gap > 0.0 and cut.to_json()["gap"] > 0.0
    assert stats.stopped == "time_limit"
    # the cut trial is listed as cut short, not as proved infeasible
    (trial,) = [t for t in search.trials if t.lengths == (CUT,)]
    assert trial.cut_short and trial.value is None and trial.lower_bound == 0.0
    assert stats.lower_bound == 0.0  # lengths left untried: no bound claimed over them
    assert search.not_tried >= 1


def test_the_users_time_limit_is_echoed_and_each_share_named_apart(cut):
    data = json.loads(json.dumps(cut.to_json()))
    assert data["search"]["limits"]["time_limit"] == LIMIT
    assert data["search"]["stopped"] == "time_limit"
    assert cut.problem.time_limit == LIMIT
    shares = [t["time_share"] for t in data["rope_length_search"]["trials"]]
    assert shares[0] == LIMIT and all(0.0 < s <= LIMIT for s in shares)
    cut_trial = [t for t in data["rope_length_search"]["trials"] if t["lengths"] == [CUT]][0]
    assert cut_trial["stopped"] == "time_limit" and cut_trial["lower_bound"] == 0.0


def test_console_and_report_say_the_search_stopped(cut):
    console = plan_table(cut)
    flat = " ".join(console.split())
    assert "SEARCH STOPPED AT THE TIME LIMIT of 1000 s (1 of" in flat
    assert "rope-length trials cut short" in flat and "no lower bound claimed" in flat
    report = _text(render_html(cut))
    assert "SEARCH STOPPED AT THE TIME LIMIT of 1000 s" in report
    assert "time limit ([plan] time_limit) 1000 s" in report
    # a work limit is refused with rope-length ranges: the report does not suggest one
    assert "work limit ([plan] work_limit) instead" not in report
    assert "Rope-length ranges take no work limit" in report
    assert "none claimed" in report  # the cut trial's bound in the lengths table


def test_a_limit_that_stops_a_held_search_is_one_console_line():
    problem = dataclasses.replace(load_problem(EXAMPLES / "tanker_plan.toml"), work_limit=3)
    result = plan(problem)
    assert result.stats.stopped == "work_limit"
    console = plan_table(result)
    lines = [line for line in console.splitlines() if "SEARCH STOPPED" in line]
    assert len(lines) == 1 and lines[0].startswith("SEARCH STOPPED AT THE WORK LIMIT of 3 sets evaluated")
    flat = " ".join(console.split())
    assert f"gap {result.stats.gap:.2f} t" in flat or "gap 0)" in flat
    # the same search stopped by the time limit instead, with a gap left
    timed = dataclasses.replace(result.stats, stopped="time_limit", lower_bound=0.5 * result.stats.best)
    (line,) = limit_lines(timed, dataclasses.replace(problem, work_limit=None, time_limit=2.5))
    assert line.startswith(
        "SEARCH STOPPED AT THE TIME LIMIT of 2.5 s: the plan is the best found, not proved"
    )
    assert f"gap {timed.gap:.2f} t (50.0 %)" in line
    # a search that ended on its own says nothing of limits
    assert limit_lines(dataclasses.replace(result.stats, stopped="proved"), problem) == []
