"""Two-crane sling plans honour the hook-height tolerance (review finding 2): the crew's hook
errors tilt the body along the hook line on top of the tolerance, by up to
atan((delta_1 + delta_2) / span), and every state the plan checks is taken there.

Checked against the lever rule by hand (a 2-leg sling's hook hangs above the midpoint of its
turned lugs) and against the rigging model hung at the tilted state.
"""

from __future__ import annotations

import dataclasses
import html

import numpy as np
import pytest
from helpers import EXAMPLES
from scipy.spatial.transform import Rotation

from liftplan.model.statics.rigging import solve_rigging
from liftplan.planner import load_problem, plan
from liftplan.planner.output.console.slings import sling_table
from liftplan.planner.output.report.slings import render_html

DELTA = 0.4  # m, every hook


def _with(tmp_path, name, text, old="[plan]\n"):
    source = (EXAMPLES / "block_sling_plan.toml").read_text()
    assert old in source
    path = tmp_path / name
    path.write_text(source.replace(old, old + text, 1))
    return load_problem(path)


@pytest.fixture(scope="module")
def tilted(tmp_path_factory):
    return plan(_with(tmp_path_factory.mktemp("hooks"), "hooks.toml", f"hook_tolerance = {DELTA}\n"))


def _hand_hook_loads(result, tilt):
    """Each crane's largest body share by the lever rule along the hook line, over the CG
    envelope and the tilts -tilt, 0, +tilt [deg], worked out here  [t]."""
    problem, chosen = result.problem, result.chosen
    line = chosen.apex[1] - chosen.apex[0]
    line[2] = 0.0
    e = line / np.linalg.norm(line)
    axis = np.cross([0.0, 0.0, 1.0], e)
    weight = problem.body.weight
    worst = np.zeros(2)
    for angle in (-tilt, 0.0, tilt):
        turn = Rotation.from_rotvec(np.radians(angle) * axis)
        hooks = [turn.apply(problem.points[list(pair)]).mean(axis=0) @ e for pair in chosen.pairs]
        for offset in problem.cog_envelope.offsets():
            g = turn.apply(np.add(problem.body.cog, offset)) @ e
            second = weight * (g - hooks[0]) / (hooks[1] - hooks[0])
            worst = np.maximum(worst, [weight - second, second])
    return worst


def test_the_hook_errors_tilt_is_the_lever_rule_along_the_hook_line(tilted):
    span = float(np.linalg.norm(tilted.chosen.apex[1, :2] - tilted.chosen.apex[0, :2]))
    added = np.degrees(np.arctan(2 * DELTA / span))
    assert tilted.chosen.hook_tilt == pytest.approx(added, rel=1e-12)
    assert added > 3.0  # 0.8 m over the 14 m hook line
    by_hand = _hand_hook_loads(tilted, tilted.tolerances[0] + added)
    np.testing.assert_allclose(tilted.hook_worst, by_hand, rtol=1e-9)
    # more than the tolerance alone gives
    assert np.all(by_hand > _hand_hook_loads(tilted, tilted.tolerances[0]) + 1.0)
    assert abs(tilted.chosen.worst_tilt) == pytest.approx(tilted.tolerances[0] + added)


def test_the_worst_legs_cover_the_rigging_model_at_the_hook_errors_tilt(tilted):
    tilt = tilted.tolerances[0] + tilted.chosen.hook_tilt
    span = float(np.linalg.norm(tilted.chosen.apex[1, :2] - tilted.chosen.apex[0, :2]))
    scene = tilted.scene
    worst = dict(zip(tilted.labels, np.concatenate(tilted.legs_worst)))
    keys = {f"{tilted.cranes[lb]}/{tilted.lugs[lb]}": lb for lb in tilted.labels}
    for angle in (-tilt, tilt):
        rise = span * np.tan(np.radians(angle))  # crane 1's hook alone raised
        first = scene.cranes[0]
        raised = dataclasses.replace(
            first, boom_height=first.boom_height + rise, tip=(*first.tip[:2], first.tip[2] + rise)
        )
        eq = solve_rigging(dataclasses.replace(scene, cranes=(raised, *scene.cranes[1:])))
        for key, label in keys.items():
            assert worst[label] >= eq.rigging.legs[key] * (1 - 1e-6), (key, angle)


def test_a_crane_s_own_hook_tolerance_counts_and_the_outputs_say_so(tmp_path, tilted):
    own = plan(_with(tmp_path, "own.toml", "hook_tolerance = 0.05\n", old="[[cranes]]\n"))
    span = float(np.linalg.norm(own.chosen.apex[1, :2] - own.chosen.apex[0, :2]))
    assert own.chosen.hook_tilt == pytest.approx(np.degrees(np.arctan(0.05 / span)), rel=1e-12)
    hooks = tilted.to_json()["hooks"]
    assert hooks["tolerance"] == {"Crawler FWD": DELTA, "Crawler AFT": DELTA}
    assert hooks["tilt_along_hook_line"] == pytest.approx(tilted.chosen.hook_tilt)
    assert hooks["tilt_taken"] == pytest.approx(tilted.tolerances[0] + tilted.chosen.hook_tilt)
    text = sling_table(tilted)
    assert f"{tilted.chosen.hook_tilt:.2f} deg more along it" in " ".join(text.split())


def test_the_report_gives_the_hook_tolerances_and_what_they_do(tilted):
    page = html.unescape(render_html(tilted))
    assert "hook-height tolerance per crane" in page
    assert f"Crawler FWD +-{DELTA:g}, Crawler AFT +-{DELTA:g}" in page
    assert tilted.hook_tilt_text in page
