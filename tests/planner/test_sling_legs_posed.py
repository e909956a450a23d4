"""Two-crane sling plans: the worst leg is never below the rigging model's solve at any vertex
of the CG envelope and the tilt box (issue 29 item 1: the worst hook load split equally at the
level geometry gave 54.19 / 48.61 t; the body rolls about the hook line and loads the
low-side leg more: 56.66 / 50.83 t)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from helpers import EXAMPLES

from liftplan.model.statics.rigging import solve_rigging
from liftplan.planner import load_problem, plan


@pytest.fixture(scope="module")
def block():
    return plan(load_problem(EXAMPLES / "block_sling_plan.toml"))


def _solved_legs(block, offset, rise):
    """The plan's rigging scene with the CG moved and crane 1's hook raised by ``rise`` alone
    (crane 2 left where it is: another construction of the same tilt than the plan's)."""
    scene = block.scene
    body = dataclasses.replace(scene.body, cog=tuple(np.add(block.problem.body.cog, offset)))
    first = scene.cranes[0]
    raised = dataclasses.replace(
        first, boom_height=first.boom_height + rise, tip=(*first.tip[:2], first.tip[2] + rise)
    )
    eq = solve_rigging(dataclasses.replace(scene, body=body, cranes=(raised, *scene.cranes[1:])))
    return eq.rigging.legs


def test_the_worst_legs_cover_every_vertex_of_the_envelope_and_the_box(block):
    tilt = block.tolerances[0]
    span = float(np.linalg.norm(block.chosen.apex[1, :2] - block.chosen.apex[0, :2]))
    worst = dict(zip(block.labels, np.concatenate(block.legs_worst)))
    labels_of = {
        f"{name}/{block.problem.names[i]}": label
        for name, group in zip(block.crane_names, block.groups)
        for i, label in zip(group, [lb for lb in block.labels if block.cranes[lb] == name])
    }
    assert len(labels_of) == len(worst) == 4
    checked = 0
    for offset in block.problem.cog_envelope.offsets():
        for angle in (-tilt, 0.0, tilt):
            legs = _solved_legs(block, offset, span * np.tan(np.radians(angle)))
            for key, tension in legs.items():
                if key in labels_of:
                    assert worst[labels_of[key]] >= tension * (1 - 1e-6), (key, offset, angle)
                    checked += 1
    assert checked == 4 * 3 * len(block.problem.cog_envelope.offsets())


def test_the_roll_raises_the_worst_leg_and_the_lug_design_loads(block):
    split = np.concatenate(block.chosen.legs_worst)  # the equal split at the level geometry
    posed = np.concatenate(block.legs_worst)
    assert np.all(posed >= split) and posed.max() > 1.04 * split.max()
    assert posed.max() == pytest.approx(56.66, abs=0.01)
    lugs = [lug for crane in block.design.results for lug in crane.lugs]
    assert max(lug.design_load for lug in lugs) > 0
