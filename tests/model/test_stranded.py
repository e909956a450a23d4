"""Stranded-ship equilibrium (paper 001): the box barge, both methods, floating free, capsized."""

import json
import math
import subprocess
import sys

import pytest
from helpers import EXAMPLES
from numpy.testing import assert_allclose

from liftplan.model import solve
from liftplan.model.errors import InvalidScene
from liftplan.model.scene.hull import Hull
from liftplan.model.scene.objects import Attitude, Body, Ground, Scene, Water

BARGE = dict(
    body=Body(20000.0, (5.0, 0.0, 2.0)),
    water=Water(density=1.0273, level=0.0),
    hull=Hull.box([-50, -15, -5], [50, 15, 5]),
)


def barge(contact, **extra):
    return Scene(ground=Ground(contact, friction=0.5), **BARGE, **extra)


def within_print(value, printed, unit):
    """The paper truncates forces and centres and rounds angles: agreement to its printed
    precision means within one unit of its last printed digit."""
    assert abs(value - printed) <= unit, (value, printed, unit)


@pytest.mark.parametrize("method", ["newton", "paper-newton"])
def test_barge_case_1(method):
    eq = solve(barge((30.0, 0.0, -5.0)), method=method)
    a = eq.afloat
    within_print(-eq.pose.trim, 0.4, 0.1)  # bow up: trim < 0 here (+ bow down)
    within_print(eq.pose.heel, 0.0, 0.1)
    within_print(a.buoyancy, 16074, 1)
    within_print(a.ground_reaction, 3925, 1)
    for value, printed in zip(a.centre_of_gravity, (4.9, 0.0, 1.8)):
        within_print(value, printed, 0.1)
    for value, printed in zip(a.centre_of_buoyancy, (-1.1, 0.0, -2.6)):
        within_print(value, printed, 0.1)
    # the brief's independent recomputation, to its printed digits
    assert_allclose(-eq.pose.trim, 0.412, atol=5e-4)
    assert_allclose((a.buoyancy, a.ground_reaction), (16074.6, 3925.4), atol=0.05)
    assert a.freeing_force == pytest.approx(0.5 * a.ground_reaction)
    assert a.state == "grounded" and a.contact == (30.0, 0.0, -5.0)


@pytest.mark.parametrize("method", ["newton", "paper-newton"])
def test_barge_case_2(method):
    """Heel and trim together. The paper prints heel -3.2, the sign of ours (port side
    down, the CG's side of the contact), and trim +0.3 in its bow-up sense. Its printed
    centres have the y signs of the mirror case (contact at y = +2), so |y| is compared."""
    eq = solve(barge((30.0, -2.0, -5.0)), method=method)
    a = eq.afloat
    within_print(eq.pose.heel, -3.2, 0.1)
    within_print(-eq.pose.trim, 0.3, 0.1)
    within_print(a.buoyancy, 16247, 1)
    within_print(a.ground_reaction, 3752, 1)
    g, b = a.centre_of_gravity, a.centre_of_buoyancy
    for value, printed in zip((g[0], abs(g[1]), g[2]), (4.9, 0.3, 1.7)):
        within_print(value, printed, 0.1)
    for value, printed in zip((b[0], abs(b[1]), b[2]), (-0.8, 0.9, -2.6)):
        within_print(value, printed, 0.1)
    assert_allclose((-eq.pose.heel, -eq.pose.trim), (3.197, 0.291), atol=5e-4)
    assert_allclose((a.buoyancy, a.ground_reaction), (16247.9, 3752.1), atol=0.05)
    # moments about the contact vanish: W (G - R) = B (C - R) in plan
    r = a.contact
    for k in (0, 1):
        assert_allclose(eq.weight * (g[k] - r[k]), a.buoyancy * (b[k] - r[k]), atol=1e-6 * eq.weight)


def test_methods_agree_and_newton_is_quadratic():
    """Both reach the same pose to 1e-5 deg at the same acceptance; the paper's D leaves
    out the ground reaction's changing arm so it needs more steps on the coupled case."""
    scene = barge((30.0, -2.0, -5.0))
    newton, paper = solve(scene), solve(scene, method="paper-newton")
    assert_allclose((newton.pose.heel, newton.pose.trim), (paper.pose.heel, paper.pose.trim), atol=1e-5)
    assert newton.solver.iterations <= paper.solver.iterations


def test_floats_free_when_ground_reaction_would_be_negative():
    """A light barge whose contact is below its floating draft floats: the free-floating
    equilibrium is returned, ground reaction 0, and it equals the solve with no ground."""
    light = dict(BARGE, body=Body(14000.0, (5.0, 0.0, 2.0)))
    grounded = Scene(ground=Ground((30.0, 0.0, -5.0)), attitude=Attitude(lift_height=-3.0), **light)
    eq = solve(grounded)
    free = solve(Scene(**light))
    # floating free, no crane: the one case the word "afloat" is for
    assert eq.afloat.state == "afloat" and eq.afloat.ground_reaction == 0.0
    assert_allclose(
        (eq.pose.heel, eq.pose.trim, eq.pose.lift_height),
        (free.pose.heel, free.pose.trim, free.pose.lift_height),
        atol=1e-8,
    )
    assert_allclose(free.afloat.buoyancy, 14000.0, rtol=1e-9)
    # a floating box: B and G on one vertical
    assert_allclose(free.afloat.centre_of_buoyancy[:2], free.afloat.centre_of_gravity[:2], atol=1e-6)


def test_intact_hull_names_its_forces():
    """Intact: the displaced volume is the envelope below the water, nothing is trapped,
    B = density x displaced volume, and the console balances the ground reaction."""
    from liftplan.planner.output.console.tables import equilibrium_table

    scene = barge((30.0, -2.0, -5.0))
    eq = solve(scene)
    a = eq.afloat
    assert a.trapped_water == 0.0 and a.centre_of_trapped_water is None
    assert a.displaced_volume == pytest.approx(a.immersed_volume, rel=1e-12)
    assert a.buoyancy == pytest.approx(1.0273 * a.displaced_volume, rel=1e-12)
    text = equilibrium_table(scene, eq)
    assert f"ground reaction = W 20000.0 - B {a.buoyancy:.1f} = {a.ground_reaction:.1f} t" in text
    assert "state: grounded (resting on the ground contact)" in text and "trapped" not in text
    data = eq.to_json()
    assert data["displaced_volume"] == data["immersed_volume"] and data["trapped_water"] == 0.0


def test_contact_far_outside_the_hull_is_refused():
    """Issue 29 item 13: a ground contact 450 m outside the hull was accepted without a word
    (the hull pivoting about a point in open water); a keel point 1 m below the box (within
    5 % of its 100 m length) is still accepted."""
    with pytest.raises(InvalidScene, match=r"ground.contact = \(500, 0, -5\) m: 450 m outside the hull"):
        barge((500.0, 0.0, -5.0))
    assert barge((30.0, -2.0, -6.0)).ground.contact == (30.0, -2.0, -6.0)


def test_sinking_hull_is_reported():
    heavy = dict(BARGE, body=Body(40000.0, (5.0, 0.0, 2.0)))
    with pytest.raises(Exception, match="exceeds the buoyancy of the whole hull"):
        solve(Scene(**heavy))


@pytest.mark.parametrize("method", ["newton", "paper-newton"])
def test_capsized_on_its_side(method):
    """Heel 90 deg: the barge lies on its starboard side on a contact 12 m down. The
    body's trim axis is vertical there, so a pitch of the capsized hull shows as yaw."""
    scene = Scene(
        ground=Ground((30.0, -15.0, 0.0)),
        attitude=Attitude(heel=90.0, lift_height=-12.0),
        **dict(BARGE, body=Body(15000.0, (5.0, -10.0, 0.0))),
    )
    eq = solve(scene, method=method)
    a = eq.afloat
    assert eq.pose.heel == pytest.approx(90.0, abs=1e-6)
    assert a.state == "grounded" and a.ground_reaction > 0
    assert_allclose(a.buoyancy + a.ground_reaction, 15000.0, rtol=1e-12)
    r, g, b = a.contact, a.centre_of_gravity, a.centre_of_buoyancy
    for k in (0, 1):
        assert_allclose(eq.weight * (g[k] - r[k]), a.buoyancy * (b[k] - r[k]), atol=1e-6 * eq.weight)


def test_cli_stranded_json_keys():
    out = subprocess.run(
        [
            sys.executable,
            "-m",
            "liftplan.planner.cli",
            "solve",
            str(EXAMPLES / "stranded_barge.toml"),
            "--json",
        ],
        capture_output=True,
        text=True,
        check=True,
    )
    data = json.loads(out.stdout)
    for key in ("model", "converged", "heel", "trim", "buoyancy", "ground_reaction", "freeing_force"):
        assert key in data
    assert data["converged"] is True
    assert math.isclose(data["buoyancy"], 16247.9, abs_tol=0.05)
    assert math.isclose(data["freeing_force"], 0.5 * 3752.1, abs_tol=0.05)
