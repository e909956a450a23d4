"""Equalised 2-leg slings: one rope over a sheave at the hook (model/statics/rigging.py).

A 200 t body on four lugs (a rectangle 12 m x 8 m, lugs and CG at one height), lifted by
three cranes: FWD with a 2-leg sling to the two forward lugs, A-P and A-S with one rope each
to the aft lugs. With two separate legs the four lug loads have one redundancy (the twist:
a leg 5 cm short loads its lug against the other); with the legs one rope over a sheave
both carry one tension, the redundancy is gone and the loads are the three-support statics.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from liftplan.model import solve
from liftplan.model.errors import InvalidScene
from liftplan.model.frames import rotation_matrix
from liftplan.model.scene.objects import Analysis, Attitude, Body, Crane, Lug, Scene
from liftplan.model.scene.rigging_gear import Leg, Sling
from liftplan.planner.cli import main

A, B, W = 6.0, 4.0, 200.0
COG = (0.8, 0.6, 0.0)
LEG_EA = 20000.0
LUGS = (
    Lug("F-P", (A, B, 0.0)),
    Lug("F-S", (A, -B, 0.0)),
    Lug("A-P", (-A, B, 0.0)),
    Lug("A-S", (-A, -B, 0.0)),
)
# aft ropes as long as the forward hoist plus the legs' height, so the body hangs near level
AFT = 20.0 + np.sqrt(9.0**2 - B**2)


def scene(equalised, split=(9.0, 9.0), fwd_boom=40.0, aft_boom=40.0):
    sling = Sling(
        legs=(Leg("F-P", split[0], EA=LEG_EA), Leg("F-S", split[1], EA=LEG_EA)), equalised=equalised
    )
    cranes = (
        Crane(
            lug=None, name="FWD", boom_height=fwd_boom, rope_length=20.0, EA=40000.0, swl=300.0, sling=sling
        ),
        Crane(lug="A-P", boom_height=aft_boom, rope_length=AFT, EA=40000.0, swl=300.0),
        Crane(lug="A-S", boom_height=40.0, rope_length=AFT, EA=40000.0, swl=300.0),
    )
    return Scene(
        body=Body(weight=W, cog=COG),
        lugs=LUGS,
        cranes=cranes,
        attitude=Attitude(lift_height=5.0),
        analysis=Analysis(model="rigging"),
    )


def three_supports():
    """Hook loads of the determinate statics: FWD at the forward lugs' midpoint (A, 0),
    A-P at (-A, B), A-S at (-A, -B), vertical supports  [t]."""
    matrix = np.array([[1.0, 1.0, 1.0], [A, -A, -A], [0.0, B, -B]])
    return dict(zip(("FWD", "A-P", "A-S"), np.linalg.solve(matrix, W * np.array([1.0, *COG[:2]]))))


def loads(eq):
    return np.array([eq.tensions[k] for k in ("FWD", "A-P", "A-S")])


def test_equalised_legs_carry_one_tension_and_keep_the_rope_length():
    for fwd in (40.0, 40.3):  # whatever the hook height
        eq = solve(scene(True, fwd_boom=fwd))
        legs = eq.rigging.legs
        assert legs["FWD/F-P"] == pytest.approx(legs["FWD/F-S"], abs=1e-9 * W)
        # one rope: the spans hook-lug add up to the rope's 18 m stretched by T / EA
        rot = rotation_matrix(eq.pose.heel, eq.pose.trim, eq.pose.yaw)
        hook = np.array(eq.rigging.hook_positions["FWD"])
        spans = [np.linalg.norm(hook - (np.array(eq.position) + rot @ np.array(lug.at))) for lug in LUGS[:2]]
        tension = legs["FWD/F-P"]
        assert sum(spans) == pytest.approx(18.0 * (1.0 + tension / LEG_EA), abs=1e-9)


def test_an_equalised_pair_carries_no_twist_two_separate_legs_do():
    closed = np.array(list(three_supports().values()))
    splits = [(9.0, 9.0), (9.05, 8.95), (8.95, 9.05)]
    equalised = [loads(solve(scene(True, s))) for s in splits]
    separate = [loads(solve(scene(False, s))) for s in splits]
    # over a sheave only the rope's total length counts: how the 18 m is split between the
    # legs as given changes nothing (1e-7 W: the sheave's split is solved to 1e-9 W)
    for value in equalised[1:]:
        np.testing.assert_allclose(value, equalised[0], rtol=0, atol=1e-7 * W)
    # and the hook loads are the determinate three-support statics; 1e-3 W because the hoist
    # ropes incline a little as the body swings where the closed form takes them vertical
    # (measured 3.7e-4 W)
    for value in equalised:
        np.testing.assert_allclose(value, closed, rtol=0, atol=1e-3 * W)
    # two separate legs, one 10 cm shorter than the other: the short leg's lug takes load
    # from its neighbour and the aft ropes follow (the twist, here more than 1 t)
    assert np.max(np.abs(separate[1] - separate[2])) > 1.0
    assert np.max(np.abs(separate[1] - closed)) > 5e-3 * W


def test_raising_an_aft_hook_twists_separate_legs_not_an_equalised_pair():
    for equalised in (True, False):
        level, raised = (solve(scene(equalised, aft_boom=h)).rigging.legs for h in (40.0, 40.1))
        difference = raised["FWD/F-P"] - raised["FWD/F-S"] - (level["FWD/F-P"] - level["FWD/F-S"])
        if equalised:
            assert abs(raised["FWD/F-P"] - raised["FWD/F-S"]) <= 1e-9 * W
        else:  # 10 cm on one aft hook: about 1.1 t moved from one forward leg to the other
            assert abs(difference) > 1.0


SCENE = """
name = "equalised sling"
[body]
weight = 200.0
cog = [0.8, 0.6, 0.0]
[[lugs]]
name = "F-P"
at = [6.0, 4.0, 0.0]
[[lugs]]
name = "F-S"
at = [6.0, -4.0, 0.0]
[[lugs]]
name = "A-P"
at = [-6.0, 4.0, 0.0]
[[lugs]]
name = "A-S"
at = [-6.0, -4.0, 0.0]
[[cranes]]
name = "FWD"
boom_height = 40.0
rope_length = 20.0
EA = 40000.0
swl = 300.0
sling = { equalised = true, legs = [ { lug = "F-P", length = 9.05, EA = 20000.0 },
                                     { lug = "F-S", length = 8.95, EA = 20000.0 } ] }
[[cranes]]
lug = "A-P"
boom_height = 40.0
rope_length = 28.06225774829855
EA = 40000.0
swl = 300.0
[[cranes]]
lug = "A-S"
boom_height = 40.0
rope_length = 28.06225774829855
EA = 40000.0
swl = 300.0
[attitude]
lift_height = 5.0
"""


def test_solve_reports_the_equalised_legs(tmp_path, capsys):
    path = tmp_path / "equalised.toml"
    path.write_text(SCENE, encoding="utf-8")
    assert main(["solve", str(path), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["model"] == "rigging"
    legs = data["legs"]
    assert legs["FWD/F-P"] == pytest.approx(legs["FWD/F-S"], abs=1e-9 * W)
    expected = loads(solve(scene(True)))
    np.testing.assert_allclose(
        [data["tensions"][k] for k in ("FWD", "A-P", "A-S")], expected, rtol=0, atol=1e-7 * W
    )
    # three legs cannot be one rope over one sheave: a one-line refusal, exit 2
    bad = SCENE.replace(
        '{ lug = "F-S", length = 8.95, EA = 20000.0 } ]',
        '{ lug = "F-S", length = 8.95, EA = 20000.0 }, { lug = "A-P", length = 9.0, EA = 20000.0 } ]',
    )
    path.write_text(
        bad.replace(
            '[[cranes]]\nlug = "A-P"\nboom_height = 40.0\nrope_length = '
            "28.06225774829855\nEA = 40000.0\nswl = 300.0\n",
            "",
        ),
        encoding="utf-8",
    )
    assert main(["solve", str(path), "--json"]) == 2
    err = capsys.readouterr().err.strip()
    assert "equalised = true with 3 legs" in err and "\n" not in err


@pytest.mark.parametrize(
    ("legs", "equalised", "match"),
    [
        ((Leg("F-P", 9.0, EA=LEG_EA), Leg("F-S", 9.0, EA=30000.0)), True, "the same EA"),
        (
            (Leg("F-P", 9.0, EA=LEG_EA), Leg("F-S", 9.0, EA=LEG_EA), Leg("A-P", 9.0, EA=LEG_EA)),
            True,
            "with 3 legs",
        ),
        ((Leg("F-P", 9.0, EA=LEG_EA), Leg("F-S", 9.0, EA=LEG_EA)), 1, "expected true or false"),
    ],
)
def test_equalised_needs_one_rope(legs, equalised, match):
    with pytest.raises(InvalidScene, match=match) as err:
        Sling(legs=legs, equalised=equalised)
    assert "\n" not in str(err.value)
