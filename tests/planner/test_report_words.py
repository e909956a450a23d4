"""What a client reads (issue 29 item 6): checks named in words, no rounded "-0.000", and
every value in its objective's unit (a utilisation spread of 0.2947 was printed "0.29 t")."""

from __future__ import annotations

import re

from helpers import EXAMPLES

from liftplan.model.checks import TITLES, Check
from liftplan.planner import load_problem, plan
from liftplan.planner.output.report.held import render_html
from liftplan.planner.output.report.page import cell_text, count_text, range_text, table


def test_a_rounded_negative_zero_reads_as_zero():
    assert cell_text("-0.000") == "0.000" and cell_text("1.20, -0.00") == "1.20, 0.00"
    assert cell_text("-0.001") == "-0.001" and cell_text("-0.5") == "-0.5"
    assert cell_text("+-0") == "+-0" and cell_text("+-0.02") == "+-0.02"  # tolerances stay
    assert "-0.00" not in table(["a"], [["-0.00"]], "x")


def test_checks_are_named_in_words():
    check = Check.upper("design_hook_load", "crane A", 1.0, 2.0, "t")
    assert check.title == TITLES["design_hook_load"] == "design hook load within the chart SWL"
    assert Check.upper("some_new_check", "x", 1.0, 2.0, "t").title == "some new check"
    assert check.to_json()["name"] == "design_hook_load"  # the JSON keeps the name


def test_a_fleet_report_shows_its_objective_in_its_unit():
    fleet = plan(load_problem(EXAMPLES / "tanker_fleet.toml"))
    assert fleet.objective == "utilisation"
    text = re.sub(r"<[^>]+>", "|", render_html(fleet))
    row = re.search(r"least worst value for the recommended lugs[^|]*\|+([^|]+)\|+([^|]+)\|", text)
    assert row is not None and row[2] == "-" and float(row[1]) < 1.0
    assert "design_hook_load" not in text and "|-0.00" not in text


def test_a_sling_report_names_its_factors_in_words():
    from liftplan.planner.output.report.slings import render_html as sling_html

    text = re.sub(r"<[^>]+>", "|", sling_html(plan(load_problem(EXAMPLES / "block_sling_plan.toml"))))
    assert "weight contingency [-]" in text and "DAF [-]" in text
    assert "weight_contingency" not in text and "design_hook_load" not in text


def test_a_range_without_limits_reads_in_words():
    # was "boom height range -inf to inf" on the barge reports
    inf = float("inf")
    assert range_text(30.0, 60.0) == "30 to 60"
    assert range_text(30.0, inf) == "at least 30" and range_text(-inf, 60.0) == "at most 60"
    assert range_text(-inf, inf) == "not limited"


def test_a_huge_count_reads_as_a_power_of_ten():
    # was "768759815833950334240 lug sets" (hull154)
    assert count_text(1820) == "1820" and count_text(999_999_999) == "999999999"
    assert count_text(768759815833950334240) == "7.69 x 10^20"


def test_design_loads_not_computed_read_as_dashes_not_nan(tmp_path):
    # was "nan nan FAIL" in the console's crane table and "nan nan" in the report's checks
    # (no CG envelope and no [rules] cog_factor: the rules' chain cannot be computed)
    from liftplan.planner.output.console.summary import summary

    text = (EXAMPLES / "tanker_plan.toml").read_text()
    text = re.sub(r"cog_tolerance = \[[^]]*\]", "cog_tolerance = [0.0, 0.0, 0.0]", text)
    path = tmp_path / "plan.toml"
    path.write_text(text)
    planned = plan(load_problem(path))
    assert not planned.design_loads.ok
    console, page = summary(planned), render_html(planned)
    lines = [c.line() for c in planned.checks if not c.ok]
    want = "FAIL design_loads all cranes: not computed: rules.cog_factor"
    assert any(line.startswith(want) for line in lines)
    assert "nan" not in console + "".join(lines) and ">nan<" not in page
