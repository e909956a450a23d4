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
