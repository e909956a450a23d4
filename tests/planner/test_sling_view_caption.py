"""The 3D view's worst state of a sling plan says which state it shows and gives the leg table's
worst beside it (review finding 15: examples/block_four_leg_plan.toml's caption said "largest
leg tension 24.5 t", the rigging model's in one state, where the leg table and the JSON give
25.48 t, the plan's own statics over every state)."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import EXAMPLES

from liftplan.planner import load_problem, plan
from liftplan.planner.output.view.states import plan_view


@pytest.fixture(scope="module")
def four_leg():
    return plan(load_problem(EXAMPLES / "block_four_leg_plan.toml"))


def test_the_caption_names_its_state_and_the_leg_table_s_worst(four_leg):
    worst = plan_view(four_leg).states[1]
    shown = max(r.tension for r in worst.ropes if r.role == "leg")
    table = max(four_leg.to_json()["worst_leg_tensions"].values())
    assert table == pytest.approx(float(np.max(np.concatenate(four_leg.legs_worst))))
    assert round(shown, 2) != round(table, 2)  # two models, two numbers: both named
    assert f"worst state on the rigging model: largest leg tension {shown:.2f} t in this state" in worst.name
    assert f"leg table: {table:.2f} t, the plan's own statics over every state" in worst.name
