"""The basis says which DAF column it used and whether it was assumed (issue 29 item 8: a
shipyard lift without [rules] location silently got the offshore DAF)."""

from __future__ import annotations

import pytest
from helpers import EXAMPLES

from liftplan.model.rules import Rules, read_rules
from liftplan.planner import load_problem, loads_problem, plan
from liftplan.planner.output.console.summary import summary
from liftplan.planner.output.report.held import render_html

ASSUMED = "offshore (assumed: [rules] location not given)"


def test_rules_say_when_the_location_was_assumed():
    assert Rules().location == "offshore" and Rules().location_assumed
    assert Rules().location_text == ASSUMED
    assert read_rules({"daf": 1.1}).location_assumed
    given = read_rules({"location": "offshore"})
    assert not given.location_assumed and given.location_text == "offshore"
    assert read_rules({"location": "inshore"}).location_text == "inshore"


@pytest.fixture(scope="module")
def tanker():
    return plan(load_problem(EXAMPLES / "tanker_plan.toml"))


def test_the_console_and_the_report_say_the_location_was_assumed(tanker):
    assert f"location: {ASSUMED}" in summary(tanker)
    assert ASSUMED in render_html(tanker)


def test_a_given_location_is_shown_as_given():
    text = (EXAMPLES / "tanker_plan.toml").read_text(encoding="utf-8") + '\n[rules]\nlocation = "inshore"\n'
    onshore = plan(loads_problem(text))
    console = summary(onshore)
    assert (
        "location: inshore (the DAF column" in console and "assumed" not in console.split("location:")[1][:30]
    )


def test_a_sling_plan_says_it_too():
    block = plan(load_problem(EXAMPLES / "block_sling_plan.toml"))
    assert f"location: {ASSUMED}" in summary(block)
