"""A check that could not be computed reads "not computed" with its reason, never "nan"."""

import math

from liftplan.model.checks import Check


def test_a_computed_check_prints_its_numbers():
    check = Check.upper("swl", "L2", 452.1, 400.0, "t", note="tension / SWL")
    assert check.line() == "FAIL swl L2: 452.1 t > 400 t (tension / SWL)"
    assert (check.shown("value"), check.shown("limit")) == ("452.1", "400")


def test_a_check_not_computed_fails_and_says_why_without_nan():
    # was: "FAIL design_loads all cranes: nan - > nan - (not computed: ...)"
    check = Check.upper(
        "design_loads", "all cranes", math.nan, math.nan, "-", note="not computed: rules.cog_factor: missing"
    )
    assert not check.ok and not check.computed
    assert check.line() == "FAIL design_loads all cranes: not computed: rules.cog_factor: missing"
    assert "nan" not in Check.lower("taut", "L1", math.nan, 0.0, "t").line()
    assert (check.shown("value"), check.shown("limit")) == ("-", "-")
    assert check.to_json()["value"] is None


def test_a_large_limit_reads_as_a_whole_number():
    # was "2.969e+04" in the ferry report's checks table
    check = Check.upper("bending_moment", "x = 23.9 m", 821.2, 29690.4, "t m")
    assert (check.shown("value"), check.shown("limit")) == ("821.2", "29690")
