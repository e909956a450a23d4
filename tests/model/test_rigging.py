"""Sling sets and spreader bars (the ``rigging`` model): closed forms, the vertical model
where the legs hang vertically, MoorPy with free hook points, bad input, invariance, the
sling-angle check and the JSON keys."""

import dataclasses
import math

import numpy as np
import pytest
from numpy.testing import assert_allclose
from support.moorpy_peer import moorpy_angles, moorpy_solve_rigging

from liftplan.model import (
    Attitude,
    Body,
    Crane,
    InvalidScene,
    Lug,
    Scene,
    loads_scene,
    rotation_matrix,
    solve,
    zup_to_choi,
)
from liftplan.model.scene.rigging_gear import Leg, RiggingLimits, Sling, Spreader, sling_ea
from liftplan.model.statics.rigging import rigging_checks

STIFF = 1e7  # t: legs that stretch by ~1e-5 of their length, for closed forms on the drawn geometry
W = 200.0


def block(slings, cog=(0.0, 0.0, 1.0), weight=W, lugs=None, tips=None, **scene):
    """A block on cranes "A" and "B" (boom 40 m, hoist 20 m, EA 60 000 t), slings given as
    {crane: Sling}; lugs default to a 20 x 6 m rectangle P1-P4 at z = 2."""
    lugs = lugs or {
        "P1": (-10.0, 3.0, 2.0),
        "P2": (-10.0, -3.0, 2.0),
        "P3": (10.0, 3.0, 2.0),
        "P4": (10.0, -3.0, 2.0),
    }
    tips = tips or {}
    cranes = tuple(
        Crane(
            name=name,
            sling=sling,
            boom_height=40.0,
            rope_length=20.0,
            EA=60000.0,
            swl=300.0,
            tip=tips.get(name),
        )
        for name, sling in slings.items()
    )
    return Scene(
        Body(weight, cog),
        tuple(Lug(n, at) for n, at in lugs.items()),
        cranes,
        Attitude(lift_height=10.0),
        **scene,
    )


def pair(a, b, length=8.0, **stiffness):
    stiffness = stiffness or {"EA": STIFF}
    return Sling((Leg(a, length, **stiffness), Leg(b, length, **stiffness)))


def test_symmetric_two_leg_sling_closed_form():
    """Each hook carries W/2 by symmetry, each leg W/2 / (2 sin a). With the solved angle the
    statics are exact (round-off); with the drawn angle (legs unstretched, sin a = h / l) the
    stiff legs' stretch (T l / EA ~ 5e-6 l) moves the angle by less than 1e-5 relative."""
    eq = solve(block({"A": pair("P1", "P2"), "B": pair("P3", "P4")}))
    assert eq.model == "rigging" and eq.solver.method == "newton"
    assert_allclose(list(eq.tensions.values()), [W / 2, W / 2], rtol=1e-12)
    legs = eq.rigging.legs
    solved = {k: (W / 2) / (2 * math.sin(math.radians(a))) for k, a in eq.rigging.sling_angles.items()}
    assert_allclose([legs[k] for k in solved], list(solved.values()), rtol=1e-9)
    drawn = (W / 2) / (2 * math.sqrt(8.0**2 - 3.0**2) / 8.0)
    assert_allclose(list(legs.values()), [drawn] * 4, rtol=1e-5)
    assert_allclose(eq.rigging.hook_positions["A"][:2], (-10.0, 0.0), atol=1e-9)


def test_four_leg_sling_on_a_rectangle_closed_form():
    """Two 4-leg slings on 4 x 6 m rectangles, CG in the middle: by the double symmetry every
    leg carries (W/2) / (4 sin a), with sin a = sqrt(l^2 - r^2) / l, r the half diagonal.
    Tolerance as the 2-leg case (stiff legs' stretch)."""
    lugs = {
        f"{side}{k}": (x + dx, dy, 0.0)
        for side, x in (("A", -10.0), ("B", 10.0))
        for k, (dx, dy) in enumerate(((-2, 3), (2, 3), (2, -3), (-2, -3)))
    }
    slings = {c: Sling(tuple(Leg(f"{c}{k}", 9.0, EA=STIFF) for k in range(4))) for c in "AB"}
    eq = solve(block(slings, cog=(0.0, 0.0, -1.0), lugs=lugs))
    r = math.hypot(2.0, 3.0)
    leg = (W / 2) / (4 * math.sqrt(9.0**2 - r**2) / 9.0)
    assert_allclose(list(eq.rigging.legs.values()), [leg] * 8, rtol=1e-5)
    assert_allclose(list(eq.tensions.values()), [W / 2] * 2, rtol=1e-12)
    assert not eq.slack


def bars(weight=2.0, ea=None, top=5.0, bottom=4.0, stiff=STIFF):
    """Both cranes with a 6 m spreader over its pair of lugs (3 m either side of the hook)."""
    bar = {"EA": ea} if ea is not None else {}

    def sling(a, b):
        return Sling(
            (Leg(a, bottom, EA=stiff), Leg(b, bottom, EA=stiff)),
            Spreader(6.0, (Leg(None, top, EA=stiff), Leg(None, top, EA=stiff)), weight, **bar),
        )

    return {"A": sling("P1", "P2"), "B": sling("P3", "P4")}


def test_spreader_bar_hand_calculation():
    """Hand calculation, stiff gear: hook load F = W/2 + w (the bar's weight w), top legs at
    cos a = 3/5 carry F / (2 sin a) = F / 1.6, the bar is compressed by T_top cos a, the
    vertical bottom legs carry W/4 each. Tolerance 1e-4: the gear stretches by ~1e-5 of its
    length and the bar by C L / EA, which moves the 3-4-5 triangle's angles."""
    w = 2.0
    eq = solve(block(bars(weight=w, ea=STIFF)))
    hook = W / 2 + w
    top = hook / 1.6
    assert_allclose(list(eq.tensions.values()), [hook, hook], rtol=1e-12)
    legs, angles = eq.rigging.legs, eq.rigging.sling_angles
    assert_allclose([legs[k] for k in ("A/top1", "A/top2", "B/top1", "B/top2")], [top] * 4, rtol=1e-4)
    assert_allclose([legs[k] for k in ("A/P1", "A/P2", "B/P3", "B/P4")], [W / 4] * 4, rtol=1e-9)
    assert_allclose(list(eq.rigging.spreader_compression.values()), [0.6 * top] * 2, rtol=1e-4)
    assert_allclose(angles["A/top1"], math.degrees(math.asin(0.8)), atol=1e-3)
    assert angles["A/P1"] > 90.0 - 1e-3
    # the exact statics at the solved angles (round-off)
    sine = math.sin(math.radians(angles["A/top1"]))
    assert_allclose(legs["A/top1"], hook / (2 * sine), rtol=1e-9)


def test_vertical_legs_equal_the_vertical_model():
    """Spreader bars over their lugs, CG off-centre: the body hangs on four vertical legs whose
    upper ends are the bar ends. The vertical ``elastic`` model with those ends as boom tips
    (height H = end height, l0 and EA of the leg) gives the same tensions and pose. Tolerance
    1e-8: the bars' elastic shortening (C L / EA ~ 1e-4 m) leaves the legs ~1e-5 rad off
    vertical, a relative tension error of order 1e-10."""
    scene = block(bars(top=6.0, stiff=20000.0), cog=(1.5, 0.0, 1.0))
    eq = solve(scene)
    ends = eq.rigging.spreader_ends
    height = {"P1": ends["A"][0][2], "P2": ends["A"][1][2], "P3": ends["B"][0][2], "P4": ends["B"][1][2]}
    vertical = Scene(
        scene.body,
        scene.lugs,
        tuple(Crane(name, EA=20000.0, boom_height=height[name], rope_length=4.0) for name in scene.lug_names),
        Attitude(lift_height=eq.pose.lift_height),
    )
    ref = solve(vertical, "elastic")
    assert_allclose(
        [eq.rigging.legs[f"{c}/{lug}"] for c, lug in (("A", "P1"), ("A", "P2"), ("B", "P3"), ("B", "P4"))],
        list(ref.tensions.values()),
        rtol=1e-8,
    )
    assert_allclose(
        (eq.pose.heel, eq.pose.trim, eq.pose.lift_height),
        (ref.pose.heel, ref.pose.trim, ref.pose.lift_height),
        atol=1e-8,
    )
    assert eq.pose.trim > 0.01  # the off-centre CG really tilts it (bow down)


def test_matches_moorpy_free_hook_points():
    """Two 2-leg slings with unequal legs, an off-centre CG and tips splayed off the lugs'
    centroids: hook loads, legs and hook positions against MoorPy with the hooks as free
    points. Tolerance 1e-6 relative: MoorPy's lines weigh 1e-9 t/m and it stops at 1e-10 m."""
    tips = {"A": (-11.0, 1.0, 40.0), "B": (10.5, -0.5, 41.0)}
    slings = {
        "A": Sling((Leg("P1", 8.0, diameter=64.0), Leg("P2", 8.5, diameter=56.0))),
        "B": Sling((Leg("P3", 7.5, EA=30000.0), Leg("P4", 8.0, diameter=64.0))),
    }
    scene = block(slings, cog=(1.5, -0.8, 1.0), tips=tips)
    eq = solve(scene)
    assert max(f.horizontal for f in eq.rope_forces.values()) > 0.5  # hoists really inclined
    angles = moorpy_angles(rotation_matrix(eq.pose.heel, eq.pose.trim, eq.pose.yaw))
    start = np.array([*eq.position, *angles]) + [0.01, -0.01, 0.02, 0.01, -0.01, 0.01]
    hooks = {k: np.array(v) + [0.01, -0.01, 0.02] for k, v in eq.rigging.hook_positions.items()}
    loads, legs, positions = moorpy_solve_rigging(scene, tips, hooks, start)
    assert_allclose([eq.tensions[k] for k in loads], list(loads.values()), rtol=1e-6)
    assert_allclose([eq.rigging.legs[k] for k in legs], list(legs.values()), rtol=1e-6)
    for name, at in positions.items():
        assert_allclose(eq.rigging.hook_positions[name], at, atol=1e-6)


def test_slack_leg_carries_nothing():
    """A 4-leg sling with one leg 0.5 m long: it hangs slack (tension only), the other three
    carry the hook load, and its key is listed as slack."""
    lugs = {
        f"{side}{k}": (x + dx, dy, 0.0)
        for side, x in (("A", -10.0), ("B", 10.0))
        for k, (dx, dy) in enumerate(((-2, 3), (2, 3), (2, -3), (-2, -3)))
    }
    slings = {
        c: Sling(tuple(Leg(f"{c}{k}", 9.5 if (c, k) == ("A", 0) else 9.0, EA=20000.0) for k in range(4)))
        for c in "AB"
    }
    eq = solve(block(slings, cog=(0.0, 0.0, -1.0), lugs=lugs))
    assert eq.rigging.legs["A/A0"] == 0.0 and "A/A0" in eq.slack
    vertical = sum(
        eq.rigging.legs[f"A/A{k}"] * math.sin(math.radians(eq.rigging.sling_angles[f"A/A{k}"]))
        for k in range(4)
    )
    assert_allclose(vertical, eq.tensions["A"], rtol=1e-6)  # hoist nearly vertical (pendulum)


def test_diameter_gives_the_rules_ea():
    """EA = 80 000 N/mm2 x 0.785 d^2, in t (1 t = 9.80665 kN): 64 mm -> 26 230.0 t."""
    assert_allclose(sling_ea(64.0), 80000.0 * 0.785 * 64.0**2 / 9806.65, rtol=1e-15)
    assert_allclose(sling_ea(64.0), 26230.04, atol=0.005)
    assert Leg("P1", 8.0, diameter=64.0).stiffness == sling_ea(64.0)


def test_invariance_reordering_and_mirroring():
    """Cranes listed the other way round, legs reordered, or the scene mirrored (y -> -y):
    the same leg and hook loads by name (mirror: heel and hook y change sign). Tolerance:
    round-off of a re-ordered Newton solve."""
    slings = {
        "A": Sling((Leg("P1", 8.0, diameter=64.0), Leg("P2", 8.5, diameter=56.0))),
        "B": Sling((Leg("P3", 7.5, EA=30000.0), Leg("P4", 8.0, diameter=64.0))),
    }
    base = solve(block(slings, cog=(1.5, -0.8, 1.0)))
    swapped = {"B": Sling(slings["B"].legs[::-1]), "A": Sling(slings["A"].legs[::-1])}
    other = solve(block(swapped, cog=(1.5, -0.8, 1.0)))
    for key, value in base.rigging.legs.items():
        assert_allclose(other.rigging.legs[key], value, rtol=1e-9)
    assert_allclose([other.tensions[k] for k in base.tensions], list(base.tensions.values()), rtol=1e-9)
    mirror_lugs = {
        "P1": (-10.0, -3.0, 2.0),
        "P2": (-10.0, 3.0, 2.0),
        "P3": (10.0, -3.0, 2.0),
        "P4": (10.0, 3.0, 2.0),
    }
    mirror = solve(block(slings, cog=(1.5, 0.8, 1.0), lugs=mirror_lugs))
    for key, value in base.rigging.legs.items():
        assert_allclose(mirror.rigging.legs[key], value, rtol=1e-9)
    assert_allclose((mirror.pose.heel, mirror.pose.trim), (-base.pose.heel, base.pose.trim), atol=1e-9)
    for name, at in base.rigging.hook_positions.items():
        assert_allclose(mirror.rigging.hook_positions[name], (at[0], -at[1], at[2]), atol=1e-9)


def test_sling_angle_check():
    """Legs below [rigging] min_sling_angle (60 deg default) fail; a lower limit passes them."""
    scene = block({"A": pair("P1", "P2", length=4.0), "B": pair("P3", "P4")})
    eq = solve(scene)
    angle = eq.rigging.sling_angles["A/P1"]
    # ~41 deg as drawn; the flat legs' stretch (T l / EA ~ 1e-5 l) lowers it by ~3e-3 deg
    assert_allclose(angle, math.degrees(math.asin(math.sqrt(16.0 - 9.0) / 4.0)), atol=1e-2)
    checks = {c.subject: c for c in rigging_checks(scene, eq)}
    assert set(checks) == {"A/P1", "A/P2", "B/P3", "B/P4"}
    assert not checks["A/P1"].ok and checks["A/P1"].limit == 60.0 and checks["A/P1"].unit == "deg"
    assert checks["B/P3"].ok
    relaxed = dataclasses.replace(scene, rigging=RiggingLimits(min_sling_angle=40.0))
    assert all(c.ok for c in rigging_checks(relaxed, eq))
    assert rigging_checks(scene, solve(block({"A": pair("P1", "P2"), "B": pair("P3", "P4")}))) != []


# -- files and bad input -----------------------------------------------------------------------
TOML = """
frame = "{frame}"
[body]
weight = 200.0
cog = {cog}
{lugs}
[[cranes]]
name = "A"
boom_height = 40.0
rope_length = 20.0
EA = 60000.0
sling = {{ legs = [ {a} ] }}
[[cranes]]
name = "B"
boom_height = 40.0
rope_length = 20.0
EA = 60000.0
sling = {{ legs = [ {b} ] }}
{extra}
"""
LUGS = {"P1": (-10.0, 3.0, 2.0), "P2": (-10.0, -3.0, 2.0), "P3": (10.0, 3.0, 2.0), "P4": (10.0, -3.0, 2.0)}
A = '{ lug = "P1", length = 8.0, diameter = 64.0 }, { lug = "P2", length = 8.0, diameter = 64.0 }'
B = '{ lug = "P3", length = 8.0, diameter = 64.0 }, { lug = "P4", length = 8.0, diameter = 64.0 }'


def text(a=A, b=B, extra="", frame="z-up", lugs=LUGS, cog=(0.0, 0.0, 1.0)):
    table = "".join(f'[[lugs]]\nname = "{n}"\nat = {list(at)}\n' for n, at in lugs.items())
    return TOML.format(a=a, b=b, extra=extra, frame=frame, lugs=table, cog=list(cog))


BAD = {
    "one leg": (A.split("},")[0] + "}", ["cranes[A].sling.legs", "1 given", "2 to 4"]),
    "five legs": (
        ", ".join([A] * 2 + ['{ lug = "P1", length = 8.0, EA = 1.0 }']),
        ["cranes[A].sling.legs", "5 given", "2 to 4"],
    ),
    "unknown lug": (A.replace('"P2"', '"Q9"'), ["cranes[A].sling.legs.lug = 'Q9'", "unknown lug"]),
    "lug twice in a sling": (A.replace('"P2"', '"P1"'), ["'P1'", "used twice"]),
    "lug on two cranes": (A.replace('"P2"', '"P3"'), ["'P3'", "used twice", "cranes A and B"]),
    "diameter <= 0": (
        A.replace("diameter = 64.0 }, {", "diameter = 0.0 }, {"),
        ["cranes[A].sling.legs[P1].diameter = 0.0", "> 0"],
    ),
    "both EA and diameter": (
        A.replace("diameter = 64.0 }, {", "diameter = 64.0, EA = 5e4 }, {"),
        ["cranes[A].sling.legs[P1]", "both EA and diameter", "exactly one"],
    ),
    "neither EA nor diameter": (A.replace(", diameter = 64.0 }, {", " }, {"), ["neither EA nor diameter"]),
    "negative length": (A.replace("length = 8.0", "length = -8.0", 1), ["legs[P1].length = -8.0"]),
}


@pytest.mark.parametrize(("a", "words"), BAD.values(), ids=BAD.keys())
def test_bad_slings_are_one_line_errors(a, words):
    with pytest.raises(InvalidScene) as err:
        loads_scene(text(a=a))
    message = str(err.value)
    assert "\n" not in message
    for word in words:
        assert word in message, message


def test_other_bad_rigging_input():
    no_name = text().replace('name = "A"\n', "", 1)
    with pytest.raises(InvalidScene, match=r"cranes\[P1, P2\].name: missing"):
        loads_scene(no_name)
    with pytest.raises(InvalidScene, match="min_sling_angle = 95.0"):
        loads_scene(text(extra="[rigging]\nmin_sling_angle = 95.0"))
    with pytest.raises(InvalidScene, match="both lug and sling"):
        loads_scene(text().replace('name = "A"\n', 'name = "A"\nlug = "P1"\n', 1))
    one_top = f"legs = [ {A} ], spreader = {{ length = 6.0, top = [ {{ length = 5.0, EA = 1e5 }} ] }}"
    with pytest.raises(InvalidScene, match=r"cranes\[A\].sling.spreader.top: 1 given"):
        loads_scene(text().replace(f"legs = [ {A} ]", one_top))
    scene = loads_scene(text())
    with pytest.raises(InvalidScene, match="the elastic model hangs one rope per lug"):
        solve(scene, "elastic")
    single = Scene(
        scene.body,
        scene.lugs[:3],
        (
            Crane(
                name="A",
                sling=Sling(tuple(Leg(n, 8.0, EA=1e5) for n in ("P1", "P2", "P3"))),
                boom_height=40.0,
                rope_length=20.0,
                EA=6e4,
            ),
        ),
    )
    with pytest.raises(InvalidScene, match="turn freely about its hoist rope"):
        solve(single)


def test_json_keys_and_file_frame():
    """`solve --json` keys for rigging; the hook positions and spreader ends in the file's
    frame (choi: (x, y, z) -> (x, z, -y)), the same lift written in both frames."""
    zup = loads_scene(text())
    choi_lugs = {n: zup_to_choi(at) for n, at in LUGS.items()}
    choi = loads_scene(text(frame="choi", lugs=choi_lugs, cog=zup_to_choi((0.0, 0.0, 1.0))))
    a, b = solve(zup).to_json(), solve(choi).to_json()
    for key in ("tensions", "hook_loads", "legs", "sling_angles", "hook_positions", "spreaders"):
        assert key in a
    assert a["tensions"] == a["hook_loads"] and set(a["legs"]) == {"A/P1", "A/P2", "B/P3", "B/P4"}
    assert a["frame"] == "z-up" and b["frame"] == "choi"
    assert_allclose(list(b["legs"].values()), list(a["legs"].values()), rtol=1e-9)
    for name, at in a["hook_positions"].items():
        assert_allclose(b["hook_positions"][name], zup_to_choi(at), atol=1e-9)
    assert_allclose(b["position"], zup_to_choi(a["position"]), atol=1e-9)


def test_example_block_two_slings():
    """The shipyard example solves with the rigging model, every sling angle within the
    default 60 deg limit and the hook loads carrying the block."""
    from helpers import example

    scene = example("block_two_slings")
    eq = solve(scene)
    assert eq.model == "rigging"
    assert_allclose(sum(eq.tensions.values()), scene.body.weight, rtol=1e-9)
    assert all(c.ok for c in rigging_checks(scene, eq))
