"""Flexible hull (issue 12 item 2): the hull girder as an elastic beam on the elastic ropes.

Closed forms (a uniform beam on two and three supports, rigid and elastic; torsion between
two lug stations), an independent frame solver (PyNite), the limit EI -> infinity (the
rigid ``elastic`` model), the strength block from the flexible solution, the least-model
rule of ``solve`` and bad input (the command line: tests/cli/test_flexible_hull_cli.py).

Geometry of the closed-form cases: a body 80 m long (x in [-40, 40]) of W = 800 t spread
uniformly (q = 10 t/m), lifted at "stations": a port and a starboard lug at the same x, y =
+-5 m, at the CG's height, each on a vertical rope of stiffness k = EA / l0 from hooks all at
one height with equal l0 (so the unloaded supports are level). A station is then one vertical
spring K = 2 k under the beam.
"""

from __future__ import annotations

import dataclasses
import math

import helpers
import numpy as np
import pytest
from helpers import EXAMPLES
from numpy.testing import assert_allclose

from liftplan.model import solve
from liftplan.model.errors import InvalidScene
from liftplan.model.scene.file import load_scene, loads_scene
from liftplan.model.scene.objects import (
    Analysis,
    Attitude,
    Body,
    Crane,
    GirderStiffness,
    Lug,
    Scene,
)
from liftplan.model.solve import solve_hull_on_ropes
from liftplan.model.strength import hull_girder
from liftplan.model.strength.beam import girder_mesh

W, L = 800.0, 80.0
Q = W / L
L0 = 30.0
FLEXIBLE = EXAMPLES / "tanker_flexible.toml"


def stations_scene(stations, ei, ea=5e4, gj=None, curve=None, hull="flexible", weight=W, cog_x=0.0):
    """Port/starboard lug pairs at body x ``stations`` on ropes of EA ``ea`` (one per station)."""
    curve = curve or ((-L / 2, Q), (L / 2, Q))
    ea = ea if isinstance(ea, list | tuple) else [ea] * len(stations)
    lugs, cranes = [], []
    for k, (x, stiffness) in enumerate(zip(stations, ea)):
        for side, y in (("P", 5.0), ("S", -5.0)):
            lugs.append(Lug(f"S{k}{side}", (x, y, 2.0)))
            cranes.append(Crane(lug=f"S{k}{side}", EA=stiffness, boom_height=40.0, rope_length=L0))
    return Scene(
        body=Body(weight, (cog_x, 0.0, 2.0), weight_curve=curve),
        lugs=tuple(lugs),
        cranes=tuple(cranes),
        attitude=Attitude(lift_height=5.0),
        analysis=Analysis(model="elastic", hull=hull),
        girder=GirderStiffness(EI=((0.0, ei),), GJ=None if gj is None else ((0.0, gj),)),
    )


def station_loads(eq, count):
    """Each station's load (port + starboard rope)  [t]."""
    return np.array(list(eq.tensions.values())).reshape(count, 2).sum(axis=1)


def three_supports(x1, springs, ei, q=Q, x0=-L / 2, x2=L / 2):
    """:func:`helpers.three_supports` on this beam (its ends by default)."""
    return helpers.three_supports(x1, springs, ei, q, x0, x2)


# -- closed forms -------------------------------------------------------------------------------


@pytest.mark.parametrize("ei", [1e5, 1e6, 3e7])
def test_uniform_beam_on_two_supports_deflects_as_the_closed_form(ei):
    """Stations at both ends: simply supported, w(s) = -q s (L^3 - 2 L s^2 + s^3) / (24 EI) from
    the chord (s from the aft end). Hermite elements of constant EI with consistent loads are
    exact at the nodes: round-off only (a linear solve of ~80 unknowns: 1e-10 of the peak)."""
    scene = stations_scene([-L / 2, L / 2], ei)
    eq = solve(scene)
    flex = eq.flexible_hull
    s = flex.x + L / 2
    exact = -Q * s * (L**3 - 2 * L * s**2 + s**3) / (24 * ei)
    assert flex.used == "flexible"
    assert_allclose(flex.deflection, exact, rtol=0, atol=1e-10 * np.max(np.abs(exact)))
    assert_allclose(flex.max_deflection.value, 5 * Q * L**4 / (384 * ei), rtol=1e-10)
    assert flex.max_deflection.x == pytest.approx(0.0, abs=1e-12)
    # determinate: the tensions are the statics' alone
    assert_allclose(list(eq.tensions.values()), [W / 4] * 4, rtol=1e-12)


def test_uniform_beam_on_three_rigid_supports():
    """Two equal spans on (nearly) rigid supports: reactions 3/8, 10/8, 3/8 of q l. The ropes'
    compliance 1 / K = 1.5e-7 m/t against the beam's (2 l)^3 / (48 EI) = 1.1e-2 m/t moves
    the reactions by about their ratio, 1.4e-5 relative: tolerance 1e-4."""
    ei, span = 1e6, L / 2
    eq = solve(stations_scene([-span, 0.0, span], ei, ea=1e8))
    assert_allclose(station_loads(eq, 3), np.array([3, 10, 3]) * Q * span / 8, rtol=1e-4)
    # and the exact spring solution (three-moment equation with settlements) to round-off
    exact, _ = three_supports(0.0, [2 * 1e8 / L0] * 3, ei)
    assert_allclose(station_loads(eq, 3), exact, rtol=1e-8)


@pytest.mark.parametrize(
    "x1, ea, ei",
    [
        (0.0, [5e4, 5e4, 5e4], 1e6),
        (10.0, [2e4, 8e4, 3e4], 1e6),
        (-15.0, [1e5, 2e4, 6e4], 3e5),
        (5.0, [5e4, 5e4, 5e4], 5e7),
    ],
)
def test_three_elastic_supports_by_the_three_moment_equation(x1, ea, ei):
    """Stations at both ends and at x1, each on its own rope stiffness: the station loads equal
    the three-moment equation with spring settlements (:func:`three_supports`).

    Tolerance: the closed form is level small-deflection theory; the model keeps the exact
    attitude, and unequal springs trim the body by theta, which scales every normal load by
    cos(theta): the deflection-driven part of the reactions moves by ~theta^2 / 2.
    rtol = theta^2 + 1e-10 (round-off)."""
    eq = solve(stations_scene([-L / 2, x1, L / 2], ei, ea=ea))
    exact, _ = three_supports(x1, [2 * e / L0 for e in ea], ei)
    theta = math.radians(eq.pose.trim)
    assert_allclose(station_loads(eq, 3), exact, rtol=theta**2 + 1e-10)


@pytest.mark.parametrize("gj", [2e5, 2e6, 2e7])
def test_twist_between_two_stations_by_closed_form(gj):
    """Four lugs at two stations x = -+a, y = +-b/2; hooks moved by the pure twist pattern
    +-eps/4 (sign(x) sign(y)). The pose cannot move (the pattern has no heave, heel or trim)
    and each station turns by phi_A = -phi_B; station A's torque balance

        k (-eps b / 4 - b^2 phi_A / 2) - (GJ / a) phi_A = 0

    (ropes k = EA / l0 at lever b / 2; hull torque GJ (phi_B - phi_A) / (2 a)) gives each
    rope's change |dT| = (k eps / 4) (GJ / a) / (k b^2 / 2 + GJ / a): the rigid hull's k eps / 4
    (GJ -> infinity), nothing when GJ -> 0. Linear: round-off only (1e-8 relative)."""
    a, b, eps, ea = 30.0, 10.0, 0.01, 5e4
    scene = stations_scene([-a, a], 1e7, ea=ea, gj=gj)
    base = solve(scene)
    sign = {"S0P": -1, "S0S": 1, "S1P": 1, "S1S": -1}
    for name, s in sign.items():
        scene = scene.with_crane(name, boom_height=40.0 + s * eps / 4)
    twisted = solve(scene)
    k, torsion = ea / L0, gj / a
    change = k * eps / 4 * torsion / (k * b**2 / 2 + torsion)
    for name, s in sign.items():
        assert_allclose(twisted.tensions[name] - base.tensions[name], s * change, rtol=1e-8)
    assert abs(twisted.pose.heel) < 1e-9 and abs(twisted.pose.trim) < 1e-9
    twist = twisted.flexible_hull.twist - base.flexible_hull.twist
    phi = -(k * eps * b / 4) / (k * b**2 / 2 + torsion)
    assert_allclose(np.interp([-a, a], twisted.flexible_hull.x, twist), np.degrees([phi, -phi]), rtol=1e-8)


# -- the rigid limit ------------------------------------------------------------------------------


def tanker_six_lugs(ei, hull="flexible"):
    """The tanker of examples/tanker_flexible.toml with a third pair of lugs amidships."""
    text = FLEXIBLE.read_text()
    text = text.replace("EI = [[0.0, 5.3e7], [82.05, 5.3e7]]", f"EI = [[0.0, {ei!r}], [82.05, {ei!r}]]")
    text = text.replace('hull = "auto"', f'hull = "{hull}"')
    text += """
[[lugs]]
name = "T5"
at = [40.9, 6.0, 12.0]

[[lugs]]
name = "T6"
at = [40.9, 6.0, 0.0]

[[cranes]]
lug = "T5"
boom_height = 40.0
rope_length = 32.85
swl = 400.0

[[cranes]]
lug = "T6"
boom_height = 40.0
rope_length = 32.85
swl = 400.0
"""
    return loads_scene(text, base=EXAMPLES)


def test_tends_to_the_rigid_hull_as_ei_grows():
    """Three stations (indeterminate along the hull): the tension change flexibility makes falls
    as 1 / EI (log-log slope -1 within 1 %, from 1e8 t m2 on: first order in the compliance)
    and reaches 1e-7 of the rigid tensions at 1e14 t m2."""
    eis = 10.0 ** np.arange(6, 15)
    change = []
    for ei in eis:
        eq = solve(tanker_six_lugs(float(ei)))
        flex = eq.flexible_hull
        rigid = np.array(list(flex.rigid_tensions.values()))
        change.append(np.max(np.abs(np.array(list(eq.tensions.values())) - rigid) / rigid))
    slope = np.polyfit(np.log10(eis[2:]), np.log10(change[2:]), 1)[0]
    assert slope == pytest.approx(-1.0, abs=0.01)
    assert change[-1] < 1e-7
    assert change[0] > 0.01  # a soft hull does change them


def test_tapered_stiffness_converges_with_the_elements():
    """EI varying linearly inside elements: the cubic Hermite field is no longer exact, and the
    tensions converge as the elements shrink (the change halves at least with each halving)."""
    scene = tanker_six_lugs(1e7)
    tapered = GirderStiffness(EI=((0.0, 2e6), (41.0, 2e7), (82.05, 2e6)))
    scene = dataclasses.replace(scene, girder=tapered)
    from liftplan.model.statics.vertical import pack_params
    from liftplan.model.strength.flexible import flexible_state

    x0 = [solve(scene).pose.lift_height, 0.0, 0.0]
    tensions = [
        flexible_state(scene, pack_params(scene, "elastic"), x0, elements=e).tensions
        for e in (10, 20, 40, 80)
    ]
    steps = [np.max(np.abs(b - a)) for a, b in zip(tensions[:-1], tensions[1:])]
    assert steps[1] < steps[0] / 3 and steps[2] < steps[1] / 3
    assert steps[2] < 1e-3 * W


# -- an independent frame solver ----------------------------------------------------------------


def pynite_beam(nodes, curve, springs, ei):
    """PyNite (3D frame FEM, exact cubic members) on the same beam: members between ``nodes``
    along X, the weight curve as linear distributed loads on each member (-Y), a vertical
    spring K at each station node; planar (Z, RX, RY held everywhere, X at one node).

    Returns
    -------
    dict of node x to (deflection [m], spring force [t])
    """
    from Pynite import FEModel3D

    model = FEModel3D()
    model.add_material("steel", E=ei, G=ei, nu=0.3, rho=0.0)
    model.add_section("girder", A=1e3, Iy=1.0, Iz=1.0, J=1.0)  # EI = E x 1
    names = []
    for k, x in enumerate(nodes):
        names.append(model.add_node(f"N{k}", float(x), 0.0, 0.0))
        model.def_support(names[-1], support_DX=k == 0, support_DZ=True, support_RX=True, support_RY=True)
    cx, cw = (np.array(v, dtype=float) for v in zip(*curve))
    for k in range(len(nodes) - 1):
        member = model.add_member(f"M{k}", names[k], names[k + 1], "steel", "girder")
        w1, w2 = np.interp([nodes[k], nodes[k + 1]], cx, cw)
        model.add_member_dist_load(member, "FY", -float(w1), -float(w2))
    for x, stiffness in springs.items():
        model.def_support_spring(names[list(nodes).index(x)], "DY", stiffness)
    model.analyze_linear(check_statics=False)
    return {x: model.nodes[n].DY["Combo 1"] for x, n in zip(nodes, names)}


def test_agrees_with_pynite_to_1e_6():
    """A non-uniform weight curve (stern heavy, taper to the bow) on four stations with unequal
    ropes: station loads and the deflection curve against PyNite's frame analysis.

    PyNite is linear and level; the model trims the body by theta ~ 3e-4 rad (unequal
    springs), which changes the normal loads by cos(theta) - 1 ~ 5e-8: both well inside the
    1e-6 relative asked (and round-off of PyNite's solve, ~1e-12)."""
    curve = ((-40.0, 14.0), (-25.0, 14.0), (-20.0, 9.0), (30.0, 9.0), (40.0, 4.0))
    from liftplan.model.scene.objects import curve_totals

    weight, moment = curve_totals(*zip(*curve))
    stations = [-36.0, -12.0, 10.0, 34.0]
    ea = [4e5, 2e5, 3e5, 1.5e5]
    ei = 2e6
    scene = stations_scene(stations, ei, ea=ea, curve=curve, weight=weight, cog_x=moment / weight)
    eq = solve(scene)
    assert abs(math.radians(eq.pose.trim)) < 1e-3
    mesh = girder_mesh(scene)
    springs = {x: 2 * e / L0 for x, e in zip(stations, ea)}
    peer = pynite_beam(mesh.x, curve, springs, ei)
    loads = np.array([springs[x] * -peer[x] for x in stations])
    assert_allclose(loads.sum(), weight, rtol=1e-9)
    assert_allclose(station_loads(eq, 4), loads, rtol=1e-6)
    dy = np.array([peer[x] for x in mesh.x])
    chord = dy[0] + (dy[-1] - dy[0]) * (mesh.x - mesh.x[0]) / (mesh.x[-1] - mesh.x[0])
    relative = dy - chord
    assert_allclose(eq.flexible_hull.deflection, relative, rtol=0, atol=1e-6 * np.max(np.abs(relative)))


# -- strength from the flexible solution, and the least-model rule -------------------------------


def test_strength_block_comes_from_the_flexible_tensions_and_closes():
    scene = tanker_six_lugs(2e6)
    eq = solve(scene)
    assert eq.flexible_hull.used == "flexible"
    girder = hull_girder(scene, eq)
    rope = {p.name: p.normal for p in girder.point_loads}
    # the girder's point loads are the flexible tensions' normal components (T cos(trim))
    assert_allclose(
        [rope[f"rope {n}"] for n in scene.lug_names],
        girder.normal_factor * np.array(list(eq.tensions.values())),
        rtol=1e-12,
    )
    shear, moment = girder.closure
    span = 82.05
    assert abs(shear) < 1e-9 * scene.body.weight and abs(moment) < 1e-9 * scene.body.weight * span


def test_auto_keeps_the_rigid_hull_within_one_percent_and_says_so():
    """Solve both hulls independently; auto's choice follows the measured largest change."""
    for ei, expected in ((1e10, "rigid"), (1e6, "flexible")):
        scene = tanker_six_lugs(ei, hull="auto")
        eq = solve(scene)
        rigid = solve_hull_on_ropes(scene, hull="rigid")
        flexible = solve_hull_on_ropes(scene, hull="flexible")
        change = max(
            abs(flexible.tensions[n] - rigid.tensions[n]) / rigid.tensions[n] for n in scene.lug_names
        )
        assert eq.flexible_hull.used == expected
        assert (change > 0.01) == (expected == "flexible")
        assert eq.flexible_hull.max_change == pytest.approx(change, rel=1e-9)
        used = flexible if expected == "flexible" else rigid
        assert eq.tensions == pytest.approx(used.tensions, rel=1e-12)
        assert expected in eq.flexible_hull.reason and "%" in eq.flexible_hull.reason


def test_four_lugs_at_two_stations_are_determinate_along_the_hull():
    """The tanker's four lugs stand at two stations: bending cannot move the station loads, and
    with level hooks (no twist) nothing changes but the pose: the deflection turns the body by
    ~1e-5 rad more, which moves the lugs 3.5 m above the CG by ~1e-5 of their arm, so the
    tensions change by ~1e-5 of themselves (6.6e-6 measured): auto keeps the rigid hull."""
    eq = solve(load_scene(FLEXIBLE))
    assert eq.flexible_hull.used == "rigid"
    assert eq.flexible_hull.max_change < 1e-4
    assert eq.flexible_hull.max_deflection.value > 1e-3  # she does bend


def test_other_models_hold_the_hull_rigid_and_say_so():
    scene = load_scene(FLEXIBLE).with_analysis(model="paper-elastic")
    eq = solve(scene)
    assert eq.flexible_hull.used == "rigid" and "paper-elastic" in eq.flexible_hull.reason
    with pytest.raises(InvalidScene, match=r'analysis.hull = "flexible": the paper-elastic model'):
        solve(scene.with_analysis(hull="flexible"))


# -- bad input ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "edit, message",
    [
        ("EI = [[0.0, 0.0]]", r"hull.EI\[0\] = \[0, 0\]: expected a value > 0 t m2"),
        ("EI = [[0.0, -5e7]]", r"hull.EI\[0\] = \[0, -5e\+07\]: expected a value > 0 t m2"),
        ("EI = [[10.0, 5e7], [5.0, 5e7]]", r"hull.EI\[1\] = \[5, 5e\+07\]: x 5 m is not greater"),
        ("EI = [[0.0, 5e7], [90.0, 5e7]]", r"hull.EI\[1\] = \[90, 5e\+07\]: x 90 m lies outside the body"),
        ("EI = [[0.0, 5e7]]\nGJ = [[-3.0, 1e7]]", r"hull.GJ\[0\] = \[-3, 1e\+07\]: x -3 m lies outside"),
        ("GJ = [[0.0, 5e7]]", r"hull.GJ: given without hull.EI"),
        ('EI = "stiff"', r"hull.EI = 'stiff'"),
    ],
)
def test_bad_stiffness_is_one_line(edit, message):
    text = FLEXIBLE.read_text()
    start = text.index("[hull]")
    end = text.index("\n\n", start)
    text = text[:start] + "[hull]\n" + edit + text[end:]
    with pytest.raises(InvalidScene, match=message) as err:
        loads_scene(text, base=EXAMPLES)
    assert "\n" not in str(err.value)


def test_lug_off_the_body_and_missing_weight_curve_are_refused():
    text = FLEXIBLE.read_text()
    with pytest.raises(InvalidScene, match=r"lugs\[T2\].at: x 85 m lies outside the hull girder"):
        loads_scene(text.replace("at = [65.6, 6.0, 12.0]", "at = [85.0, 6.0, 12.0]"), base=EXAMPLES)
    start = text.index("weight_curve")
    end = text.index("]\n\n", start)
    text = text[:start] + text[end + 2 :]
    start = text.index("[strength]")
    end = text.index("\n\n", start)
    with pytest.raises(InvalidScene, match=r"hull.EI: given but no body.weight_curve"):
        loads_scene(text[:start] + text[end + 2 :], base=EXAMPLES)
    with pytest.raises(InvalidScene, match=r'analysis.hull = "flexible": no hull.EI given'):
        bare = stations_scene([-40.0, 40.0], 1e6)
        Scene(body=bare.body, lugs=bare.lugs, cranes=bare.cranes, analysis=Analysis(hull="flexible"))


def test_a_deflection_beyond_small_deflection_theory_is_said():
    """A hull 1000x too soft deflects metres: still solved (linear beam theory), and the
    result says it is outside that theory's range."""
    eq = solve(tanker_six_lugs(1e4))
    flex = eq.flexible_hull
    assert flex.max_deflection.value > 0.01 * 82.05 and not flex.small_deflection
    assert "beyond small-deflection beam theory" in flex.reason
    assert solve(tanker_six_lugs(5.3e7)).flexible_hull.small_deflection
