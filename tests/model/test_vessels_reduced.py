"""The coupled solve with the crane vessels eliminated (T = G s0 on the body's three unknowns)
against the full Newton on body and vessels (three more unknowns per vessel): the same
equations, the same answers, whichever ropes go slack."""

from __future__ import annotations

import pytest
from test_vessels import _tanker, _twin_scene

from liftplan.model.statics.floating import solve_coupled

REDUCED = "newton (body and crane vessels) on the ropes' coupled stiffness"


def _same(scene):
    reduced, full = solve_coupled(scene), solve_coupled(scene, reduced=False)
    assert reduced.solver.method == REDUCED
    assert REDUCED not in full.solver.method
    w = scene.body.weight
    for name in scene.lug_names:
        assert reduced.tensions[name] == pytest.approx(full.tensions[name], abs=1e-9 * w)
    assert reduced.slack == full.slack
    assert reduced.pose.lift_height == pytest.approx(full.pose.lift_height, abs=1e-9)
    for name, state in full.vessels.items():
        assert reduced.vessels[name].heel == pytest.approx(state.heel, abs=1e-9)
        assert reduced.vessels[name].trim == pytest.approx(state.trim, abs=1e-9)
        assert reduced.vessels[name].heave == pytest.approx(state.heave, abs=1e-9)
    return reduced


def test_eliminated_vessels_equal_the_full_newton():
    """Four sheerlegs, and a barge under two cranes heeling by degrees: every tension to
    1e-9 W, every vessel's heave, heel and trim to 1e-9."""
    _same(_tanker())
    barge = _same(_twin_scene()).vessels["Barge"]
    assert abs(barge.heel) > 2.0


@pytest.mark.parametrize(("lug", "lower"), [("T2", 3.0), ("T3", 2.0), ("T1", 0.5)])
def test_slack_ropes_found_as_the_full_newton_finds_them(lug, lower):
    """A boom lowered until its rope goes slack (with all four taken taut, T2 or T3 lowered
    puts two ropes in compression: the set is changed one rope at a time): the same slack rope
    and tensions as the full Newton with its max(0, stretch) law."""
    scene = _twin_scene()
    scene = scene.with_crane(lug, boom_height=scene.crane(lug).boom_height - lower)
    eq = _same(scene)
    if lower > 1.0:
        assert eq.slack == (lug,) and eq.tensions[lug] == 0.0
