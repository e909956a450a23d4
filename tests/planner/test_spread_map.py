"""The spread map tops out at the starred worst (issue 29 item 5: its colour bar stopped near
60 t while the star said 91.7 t, the map leaving out the hook errors)."""

from __future__ import annotations

import pytest
from helpers import EXAMPLES

from liftplan.planner import load_problem, plan
from liftplan.planner.output.figures.plan import spread_map


@pytest.mark.parametrize("example", ["tanker_plan", "tanker_fleet"])
def test_the_maps_largest_value_is_the_plans_worst(example):
    p = plan(load_problem(EXAMPLES / f"{example}.toml"))
    assert p.lugset.hook_uncertain  # the case the map got wrong
    heel, trim, value = p.spread_map(41)
    worst = p.chosen.worst
    assert worst.heel in (heel[0], heel[-1]) and worst.trim in (trim[0], trim[-1])  # on the grid
    assert value.max() == pytest.approx(p.chosen.worst_value, rel=1e-9)
    fig = spread_map(p)
    colour_top = fig.axes[0].collections[0].get_array().max()
    assert colour_top == pytest.approx(p.chosen.worst_value, rel=1e-9)
    assert "hook errors" in fig.axes[0].get_title()
