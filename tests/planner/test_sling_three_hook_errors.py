"""Three cranes on slings honour the hook-height tolerance (review finding 2): three hooks fix the
body, so the crew's hook errors tilt it by the plane through them; the search's box is widened by
that tilt and every state is taken there. Checked against the plane fitted through every
corner of the hook errors, and against the rigging model hung with the hooks off by them."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from helpers import EXAMPLES

from liftplan.planner import load_problem, plan
from liftplan.planner.output.console.slings import sling_table
from liftplan.planner.plans.slings.apex import hook_error_tilts

DELTA = 0.4  # m, every hook


@pytest.fixture(scope="module")
def three(tmp_path_factory):
    source = (EXAMPLES / "block_three_slings_plan.toml").read_text()
    path = tmp_path_factory.mktemp("three") / "hooks.toml"
    path.write_text(source.replace("[plan]\n", f"[plan]\nhook_tolerance = {DELTA}\n", 1))
    return plan(load_problem(path))


def _corner_tilts(hooks):
    """(heel, trim) [deg] largest over every corner of the hook errors, each plane fitted here."""
    rows = np.column_stack([np.ones(3), hooks[:, :2]])
    best = np.zeros(2)
    for signs in itertools.product((-1.0, 1.0), repeat=3):
        _, slope_x, slope_y = np.linalg.solve(rows, DELTA * np.array(signs))
        best = np.maximum(best, np.degrees(np.arctan(np.abs([slope_y, slope_x]))))
    return best


def test_the_hook_errors_tilt_is_the_plane_through_them_and_widens_the_box(three):
    need = _corner_tilts(np.asarray(three.hooks))
    np.testing.assert_allclose(three.hook_need, need, rtol=1e-12)
    assert np.all(need > 3.0)  # well beyond the +-2 deg box
    assert np.all(np.asarray(three.hook_tilt) >= need - 1e-9)  # the box searched covers them
    box = three.to_json()["hooks"]["box_taken"]
    assert box["heel"] >= 2.0 + need[0] - 1e-9 and box["trim"] >= 2.0 + need[1] - 1e-9
    text = " ".join(sling_table(three).split())
    assert f"up to heel {need[0]:.2f}, trim {need[1]:.2f} deg more" in text
    assert hook_error_tilts(np.asarray(three.hooks), np.zeros(3)).tolist() == [0.0, 0.0]


def test_the_worst_legs_cover_the_rigging_model_with_the_hooks_off(three):
    hooks = np.asarray(three.hooks)
    rows = np.column_stack([np.ones(3), hooks[:, :2]])
    inverse = np.linalg.inv(rows)
    worst = dict(zip(three.labels, np.concatenate(three.legs_worst)))
    keys = {f"{three.cranes[lb]}/{three.lugs[lb]}": lb for lb in three.labels}
    for row in (1, 2):  # the errors that tilt it most in trim, then in heel
        errors = DELTA * np.sign(inverse[row])
        hung = three.hang((0.0, 0.0, 0.0), errors)
        eq = hung.solved
        tilted = abs(eq.pose.heel) if row == 2 else abs(eq.pose.trim)
        assert tilted > 2.0 + 1.0  # beyond the box the user wrote
        for key, label in keys.items():
            assert worst[label] >= eq.rigging.legs[key] * (1 - 1e-3), (key, row)
