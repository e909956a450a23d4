"""Issue 29 item 8: the plan says whether the body's weight is in air or in water
(``[body] weight_basis``), or that the file does not say."""

from __future__ import annotations

import pytest
from helpers import EXAMPLES

from liftplan.model.errors import InvalidScene
from liftplan.planner.plans.common import weight_json
from liftplan.planner.problem.file import load_problem, loads_problem


@pytest.mark.parametrize(
    "name, basis, text",
    [
        ("tanker_plan", "water", "weight W 904.00 t (in water)"),
        ("sunken_block_plan", "air", "weight W 600.00 t (in air)"),
        ("ferry_strength_plan", "air", "weight W 6000.00 t (in air)"),
        ("block_sling_plan", None, "weight W 180.00 t (in air or in water: not stated)"),
    ],
)
def test_the_examples_say_their_weight_basis(name, basis, text):
    problem = load_problem(EXAMPLES / f"{name}.toml")
    assert problem.weight_basis == basis
    assert problem.weight_text == text
    assert weight_json(problem) == {"value": problem.body.weight, "basis": basis or "not stated"}
    assert problem.weight_basis_text == ("not stated" if basis is None else f"in {basis}")


def test_a_basis_other_than_air_or_water_is_refused():
    text = (EXAMPLES / "block_sling_plan.toml").read_text()
    bad = text.replace("weight = 180.0", 'weight = 180.0\nweight_basis = "dry"', 1)
    with pytest.raises(InvalidScene) as err:
        loads_problem(bad, base=EXAMPLES)
    assert "weight_basis" in str(err.value) and "\n" not in str(err.value)


def _daf_warnings(text):
    from liftplan.planner.problem.plausibility import problem_warnings

    return [w for w in problem_warnings(loads_problem(text, base=EXAMPLES)) if "Table 5-1" in w]


def test_a_weight_in_water_with_the_in_air_daf_table_is_warned():
    """0027/ND Table 5-1 is the DAF table for lifts in air: a weight in water planned with it is
    said (one line, naming the key to give), and the warning goes once [rules] daf is given or
    the chart includes the dynamics."""
    text = (EXAMPLES / "tanker_plan.toml").read_text()
    (line,) = _daf_warnings(text)
    assert 'weight_basis = "water"' in line and "[rules] daf" in line and "\n" not in line
    assert _daf_warnings(text.replace('weight_basis = "water"', 'weight_basis = "air"')) == []
    assert "[rules]" not in text
    assert _daf_warnings(text + "\n[rules]\ndaf = 1.3\n") == []
    assert _daf_warnings(text + "\n[rules]\nchart_includes_dynamics = true\n") == []
