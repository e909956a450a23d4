"""Hull girder: weight curve, shear force and bending moment of a solved state (model/strength/).

Closed forms (uniform beam on two and four lug stations), buoyancy per length of a box against
an independent polygon clipping, the curves' closure past both ends in every kind of solved
state, the maxima against an independent mpmath integration, the moment of an inclined hull
in water against the hydrostatics of its aft part, bad input (the command line:
tests/cli/test_strength_cli.py).
"""

from __future__ import annotations

import dataclasses
import math

import mpmath
import numpy as np
import pytest
from helpers import EXAMPLES, example
from numpy.testing import assert_allclose

from liftplan.model import solve
from liftplan.model.errors import InvalidScene
from liftplan.model.frames import rotation_matrix
from liftplan.model.scene.file import load_scene, loads_scene
from liftplan.model.scene.hull import Hull
from liftplan.model.scene.objects import Analysis, Attitude, Body, Crane, Lug, Redundant, Scene, Strength
from liftplan.model.strength import hull_girder, strength_checks
from liftplan.model.strength.girder import attitude_matrix
from liftplan.model.strength.sections import immersed_sections, sectional_buoyancy
from liftplan.model.water.hydrostatics import MeshHydrostatics

W, L = 800.0, 80.0


def beam(lugs, curve=None, attitude=None, model="paper-elastic", cog=(0.0, 0.0, 2.0), redundant=()):
    """A body of length L = 80 m (x in [-40, 40]) on vertical ropes at ``lugs`` (x, y)."""
    curve = curve or ((-L / 2, W / L), (L / 2, W / L))
    names = [f"L{k}" for k in range(len(lugs))]
    return Scene(
        body=Body(W, cog, weight_curve=curve),
        lugs=tuple(Lug(n, (x, y, 6.0)) for n, (x, y) in zip(names, lugs)),
        cranes=tuple(Crane(lug=n, EA=5e4, boom_height=40.0, rope_length=30.0) for n in names),
        attitude=attitude or Attitude(),
        analysis=Analysis(model=model, redundant=redundant),
    )


def with_uniform_curve(scene, start, end):
    """The scene with a uniform weight curve over [start, end] (its centroid must be the CG's x)."""
    per_length = scene.body.weight / (end - start)
    body = dataclasses.replace(scene.body, weight_curve=((start, per_length), (end, per_length)))
    return dataclasses.replace(scene, body=body)


def test_attitude_matrix_is_the_frames_definition():
    for angles in [(0, 0, 0), (3.0, -2.0, 0.5), (90.0, 10.0, -20.0), (-45.0, 89.0, 5.0)]:
        # the same products of sines and cosines, in numpy instead of casadi: round-off apart
        assert_allclose(attitude_matrix(*angles), rotation_matrix(*angles), rtol=0, atol=1e-15)


# -- closed forms -------------------------------------------------------------------------------


@pytest.mark.parametrize("a", [15.0, 20.0, 25.0, 32.0])
def test_uniform_beam_on_two_symmetric_lug_stations(a):
    """Lugs at x = -a and +a (port and starboard), W/2 at each station: M at midspan
    W a / 2 - W L / 8, at the lugs -w (L/2 - a)^2 / 2, Q just forward of the aft lugs
    W/2 - w (L/2 - a)."""
    scene = beam([(-a, 5.0), (a, 5.0), (a, -5.0), (-a, -5.0)])
    eq = solve(scene)
    g = hull_girder(scene, eq)
    w = W / L
    # a linear solve and polynomial integrals of a few terms: round-off of 1e4 t m is ~1e-12
    assert_allclose(list(eq.tensions.values()), [W / 4] * 4, rtol=1e-12)
    assert_allclose(g.moment_curve(0.0), W * a / 2 - W * L / 8, rtol=0, atol=1e-9)
    assert_allclose(g.moment_curve([-a, a]), [-w * (L / 2 - a) ** 2 / 2] * 2, rtol=0, atol=1e-9)
    assert_allclose(g.shear_curve(-a, "right"), W / 2 - w * (L / 2 - a), rtol=0, atol=1e-10)
    expected = max(abs(W * a / 2 - W * L / 8), w * (L / 2 - a) ** 2 / 2)
    assert_allclose(g.max_moment.value, expected, rtol=1e-12)
    assert_allclose(g.max_shear.value, max(W / 2 - w * (L / 2 - a), w * (L / 2 - a)), rtol=1e-12)


def test_uniform_beam_on_four_lug_stations():
    """Lugs at x = -a, -c, c, a alternating sides (plan area, sum x = sum y = 0): the
    paper-elastic model's compatible tensions are W/4 each, statically determinate along x."""
    a, c, b = 30.0, 10.0, 5.0
    scene = beam([(-a, b), (-c, -b), (c, -b), (a, b)])
    eq = solve(scene)
    g = hull_girder(scene, eq)
    w, p = W / L, W / 4
    assert_allclose(list(eq.tensions.values()), [p] * 4, rtol=1e-12)  # linear solve, round-off
    closed = {
        -a: -w * (L / 2 - a) ** 2 / 2,
        -c: p * (a - c) - w * (L / 2 - c) ** 2 / 2,
        0.0: p * (a + c) - w * (L / 2) ** 2 / 2,
        c: p * (a - c) - w * (L / 2 - c) ** 2 / 2,
        a: -w * (L / 2 - a) ** 2 / 2,
    }
    # polynomial arithmetic on values of ~1e3 t m: round-off well below 1e-9 t m
    assert_allclose(g.moment_curve(list(closed)), list(closed.values()), rtol=0, atol=1e-9)
    # between the inner lugs M' = Q = 2p - w (x + L/2) vanishes at x = 0 (symmetry)
    peak = max(closed.values(), key=abs)
    assert_allclose(g.max_moment.value, abs(peak), rtol=1e-12)


# -- buoyancy per length of a box ---------------------------------------------------------------


def _clipped_area(y0, y1, z0, z1, up, zo, s):
    """Wet area and first moment (about z = 0) of the box section [y0, y1] x [z0, z1] at x = s:
    the rectangle clipped by g.(s, y, z) + zo < 0 (Sutherland-Hodgman), then the shoelace
    formula. Independent of the code under test, which sums cut triangle segments."""
    poly = [(y0, z0), (y1, z0), (y1, z1), (y0, z1)]

    def depth(p):
        return up[0] * s + up[1] * p[0] + up[2] * p[1] + zo

    out = []
    for k, p in enumerate(poly):
        q = poly[(k + 1) % len(poly)]
        dp, dq = depth(p), depth(q)
        if dp < 0:
            out.append(p)
        if (dp < 0) != (dq < 0):
            t = dp / (dp - dq)
            out.append((p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])))
    area = first = 0.0
    for k, p in enumerate(out):
        q = out[(k + 1) % len(out)]
        cross = p[0] * q[1] - q[0] * p[1]
        area += cross / 2
        first += (p[1] + q[1]) * cross / 6
    return area, first


@pytest.mark.parametrize(
    ("heel", "trim", "zo"),
    [
        (0.0, 0.0, 0.0),
        (0.0, 0.0, 3.0),
        (0.0, 0.0, -7.0),
        (10.0, 0.0, 1.0),
        (35.0, 0.0, -1.5),
        (70.0, 0.0, 2.0),
        (5.0, 2.0, 0.5),
        (-20.0, -3.0, -2.0),
    ],
)
def test_box_buoyancy_per_length_is_density_times_section(heel, trim, zo):
    lower, upper, density = (-50.0, -15.0, -5.0), (50.0, 15.0, 5.0), 1.025
    hull = Hull.box(lower, upper)
    up = rotation_matrix(heel, trim, 0.0)[2]
    kappa = np.full(len(hull.triangles), density)
    stations = np.linspace(-49.3, 49.7, 23)
    per_length, moment = immersed_sections(hull.triangles, kappa, up, zo, stations)
    expected = np.array([_clipped_area(lower[1], upper[1], lower[2], upper[2], up, zo, s) for s in stations])
    # both exact; sums of a few products of m-sized numbers: round-off ~1e-12 t/m
    assert_allclose(per_length, density * expected[:, 0], rtol=1e-12, atol=1e-10)
    assert_allclose(moment, density * expected[:, 1], rtol=1e-12, atol=1e-10)
    # the fitted piecewise polynomial is the same function (exact fit of a quadratic/cubic)
    breaks, fitted, fitted_moment = sectional_buoyancy(hull.triangles, kappa, up, zo)
    k = np.searchsorted(breaks, stations) - 1
    u = stations - breaks[k]
    values = sum(fitted[k, j] * u**j for j in range(4))
    assert_allclose(values, per_length, rtol=1e-10, atol=1e-9)
    # and its integral is the clipped mesh's displaced volume x density
    volume = MeshHydrostatics(hull.triangles).at(rotation_matrix(heel, trim, 0.0), zo).volume
    h = np.diff(breaks)
    total = float(np.sum(sum(fitted[:, j] * h ** (j + 1) / (j + 1) for j in range(4))))
    assert_allclose(total, density * volume, rtol=1e-12)


# -- the curves close -------------------------------------------------------------------------


def _inclined_tanker():
    """The tanker on ropes whose tips stand 3 m aft and 2 m to port of the lugs (inclined)."""
    scene = example("tanker_upright")
    tips = {c.lug: lug for c, lug in zip(scene.cranes, scene.lug_points())}
    cranes = tuple(
        dataclasses.replace(
            c, rope_length=30.0, boom_height=None, tip=(tips[c.lug][0] - 3.0, tips[c.lug][1] + 2.0, 40.0)
        )
        for c in scene.cranes
    )
    return dataclasses.replace(scene, cranes=cranes, analysis=Analysis())


CLOSING = {
    "rigid, heeled and trimmed": lambda: beam(
        [(-30.0, 5.0), (25.0, 5.0), (25.0, -5.0), (-30.0, -5.0)],
        attitude=Attitude(heel=4.0, trim=-3.0, lift_height=2.0),
        model="rigid",
        redundant=(Redundant("L0", 190.0),),
    ),
    "paper-elastic, trimmed": lambda: with_uniform_curve(
        example("tanker_upright").with_attitude(heel=2.0, trim=5.0), 35.86 - 35.0, 35.86 + 35.0
    ),
    "elastic": lambda: with_uniform_curve(example("symmetric_block"), -20.0, 20.0),
    "inclined": lambda: with_uniform_curve(_inclined_tanker(), 35.86 - 35.0, 35.86 + 35.0),
    "rigging": lambda: with_uniform_curve(example("block_two_slings"), 0.4 - 7.6, 0.4 + 7.6),
    "hydrostatic, grounded": lambda: with_uniform_curve(example("stranded_barge"), -40.0, 50.0),
    "hydrostatic, trapped water": lambda: with_uniform_curve(example("sunken_block_lift"), 0.0, 60.0),
}


@pytest.mark.parametrize("case", CLOSING)
def test_curves_close_past_both_ends(case):
    scene = CLOSING[case]()
    eq = solve(scene)
    g = hull_girder(scene, eq)
    lo, hi = g.shear_curve.span
    length, weight = hi - lo, scene.body.weight
    if "inclined" in case or "trimmed" in case or "heeled" in case:
        assert max(abs(p.couple) for p in g.point_loads) > 1.0  # the axial couples are exercised
    # the residual of these solves is <= 1e-12 W; 1e-9 W and 1e-9 W L is the contract's bar
    assert eq.residual <= 1e-12 * weight
    assert_allclose(g.shear_curve([lo - 1.0, hi + 1.0]), 0.0, rtol=0, atol=1e-9 * weight)
    assert_allclose(g.moment_curve([lo - 1.0, hi + 1.0]), 0.0, rtol=0, atol=1e-9 * weight * length)
    assert_allclose(g.closure, 0.0, rtol=0, atol=1e-9 * weight * length)
    # the output arrays start and end at zero and carry both sides of each jump
    assert g.stations[0] == lo and g.stations[-1] == hi
    assert np.all(np.diff(g.stations) >= 0)
    assert_allclose([g.shear[0], g.moment[0]], 0.0, atol=1e-9 * weight * length)


# -- maxima against an independent integration --------------------------------------------------


def test_maxima_equal_an_independent_mpmath_integration():
    """An uneven weight curve on four lugs at three stations, solved by paper-elastic at level:
    Q and M re-derived from their definition with mpmath (quadrature of the curve and sums of
    the rope forces), the extrema by mpmath root-finding of Q and q between breakpoints."""
    curve = ((-40.0, 4.0), (-31.0, 16.0), (-12.0, 9.0), (5.0, 13.0), (22.0, 7.5), (40.0, 5.0))
    x = np.array([p[0] for p in curve])
    w = np.array([p[1] for p in curve])
    area = float(np.sum(np.diff(x) * (w[:-1] + w[1:]) / 2))
    first = float(np.sum(np.diff(x) / 6 * (w[:-1] * (2 * x[:-1] + x[1:]) + w[1:] * (x[:-1] + 2 * x[1:]))))
    scene = beam(
        [(-28.0, 5.0), (3.0, 5.0), (30.0, 0.0), (-28.0, -5.0)], curve=curve, cog=(first / area, 0.0, 2.0)
    )
    scene = scene.with_body(weight=area)
    eq = solve(scene)
    g = hull_girder(scene, eq)
    mpmath.mp.dps = 30
    pts = [(float(p[0]), float(t)) for p, t in zip(scene.lug_points(), eq.tensions.values())]

    def load(s):
        s = mpmath.mpf(s)
        for (x0, w0), (x1, w1) in zip(curve[:-1], curve[1:]):
            if x0 <= s < x1:
                return w0 + (w1 - w0) * (s - x0) / (x1 - x0)
        return mpmath.mpf(0)

    def shear(s):
        nodes = [c[0] for c in curve if c[0] < s] + [s]
        return sum(t for xp, t in pts if xp <= s) - mpmath.quad(load, nodes)

    def moment(s):
        nodes = [c[0] for c in curve if c[0] < s] + [s]
        return sum(t * (s - xp) for xp, t in pts if xp <= s) - mpmath.quad(lambda v: load(v) * (s - v), nodes)

    breaks = sorted({c[0] for c in curve} | {p[0] for p in pts})
    best_m, best_q = (0, None), (0, None)
    for a, b in zip(breaks[:-1], breaks[1:]):
        eps = mpmath.mpf(10) ** -20
        for fun, deriv, best in ((moment, shear, "m"), (shear, load, "q")):
            points = [a + eps, b - eps]
            fa, fb = deriv(a + eps), deriv(b - eps)
            if fa * fb < 0:
                points.append(mpmath.findroot(deriv, (a + eps, b - eps), solver="bisect"))
            for s in points:
                value = abs(fun(s))
                if best == "m" and value > best_m[0]:
                    best_m = (value, s)
                if best == "q" and value > best_q[0]:
                    best_q = (value, s)
    # the reference is 30-digit; the code's float64 polynomials are good to ~1e-12: 1e-6 is
    # the bar, with room for nothing but round-off
    assert_allclose(g.max_moment.value, float(best_m[0]), rtol=1e-6)
    assert_allclose(g.max_shear.value, float(best_q[0]), rtol=1e-6)
    assert abs(g.max_moment.x - float(best_m[1])) <= 1e-6 * L  # found exactly, not on a grid
    assert abs(g.max_shear.x - float(best_q[1])) <= 1e-6 * L
    for s in (-35.0, -12.0, 0.0, 17.3, 39.0):  # and everywhere, to round-off
        assert_allclose(g.moment_curve(s), float(moment(s)), rtol=1e-10, atol=1e-8)


def test_inclined_hull_moment_equals_hydrostatics_of_the_aft_part():
    """The stranded barge (grounded, trimmed): M at a section, from the forces on the part
    aft of it, with that part's buoyancy taken from the clipped-mesh hydrostatics of the box
    cut at the section (a different method: volume by tetrahedra, not sections)."""
    scene = with_uniform_curve(example("stranded_barge"), -40.0, 50.0)
    eq = solve(scene)
    g = hull_girder(scene, eq)
    rot = rotation_matrix(eq.pose.heel, eq.pose.trim, eq.pose.yaw)
    up, zo, zg = rot[2], eq.pose.lift_height - scene.water.level, scene.body.cog[2]
    lower, upper = scene.hull.bounds
    rho = scene.water.density
    per_length = scene.body.weight / 90.0
    for s in (-30.0, -5.0, 12.5, 29.0, 31.0, 45.0):
        hs = MeshHydrostatics(Hull.box(lower, (s, upper[1], upper[2])).triangles).at(rot, zo)
        centre = rot.T @ (np.array(hs.centre) - [0.0, 0.0, zo])  # body frame
        buoy = rho * hs.volume * up  # body components of B
        length = s - (-40.0)
        weight = -per_length * length * up
        m = (s - centre[0]) * buoy[2] + (centre[2] - zg) * buoy[0]
        m += (s - (-40.0 + length / 2)) * weight[2]  # the curve, at z_G: no couple
        contact = np.array(scene.ground.contact)
        if contact[0] < s:
            reaction = eq.afloat.ground_reaction * up
            m += (s - contact[0]) * reaction[2] + (contact[2] - zg) * reaction[0]
        # two exact methods on the same pose: agreement to round-off of ~1e5 t m moments
        assert_allclose(g.moment_curve(s), m, rtol=1e-9, atol=1e-6)


def test_weight_curve_mismatch_is_spread_and_reported():
    """A curve 0.3 % heavy with its centroid 0.03 m forward: accepted, corrected exactly."""
    x0, x1 = -40.0 + 0.03, 40.0 + 0.03
    per_length = 1.003 * W / (x1 - x0)
    scene = beam(
        [(-20.0, 5.0), (20.0, 5.0), (20.0, -5.0), (-20.0, -5.0)], curve=((x0, per_length), (x1, per_length))
    )
    g = hull_girder(scene, solve(scene))
    assert_allclose(g.correction, (-0.003 * W, -0.03), rtol=1e-9)
    assert_allclose(g.closure, 0.0, atol=1e-9 * W * L)  # closes all the same
    assert_allclose(g.weight.integral().end(), W, rtol=1e-13)  # the corrected curve carries W


# -- checks -------------------------------------------------------------------------------------


def test_envelope_checks_at_the_worst_ratio_point():
    scene = beam([(-25.0, 5.0), (25.0, 5.0), (25.0, -5.0), (-25.0, -5.0)])
    envelope = ((-40.0, 1000.0), (0.0, 3000.0), (40.0, 1000.0))
    scene = dataclasses.replace(
        scene, strength=Strength(bending_moment=envelope, shear_force=((-40.0, 500.0), (40.0, 500.0)))
    )
    eq = solve(scene)
    g = hull_girder(scene, eq)
    checks = {c.name: c for c in strength_checks(scene, eq, g)}
    xs = np.linspace(-40.0, 40.0, 160001)
    ratio = np.abs(g.moment_curve(xs)) / np.interp(xs, *zip(*envelope))
    worst = checks["bending_moment"]
    # a 0.5 mm sampling step misses a smooth maximum by O(step^2): 1e-6 relative is ample
    assert_allclose(worst.value / worst.limit, ratio.max(), rtol=1e-6)
    assert worst.subject == f"x = {xs[np.argmax(ratio)]:.1f} m" and worst.unit == "t m"
    assert checks["shear_force"].limit == 500.0 and checks["shear_force"].ok


# -- bad input ----------------------------------------------------------------------------------

TANKER = (EXAMPLES / "tanker_strength.toml").read_text()


@pytest.mark.parametrize(
    ("old", "new", "fragments"),
    [
        ("[66.0, 10.13]", "[66.0, 11.13]", ["body.weight_curve: integral", "904 t", "expected within 0.5 %"]),
        (
            "[0.0, 4.0], [8.0, 19.34]",
            "[0.0, 4.6], [8.0, 19.34]",
            ["centroid x", "35.86", "expected within 0.05 m"],
        ),
        ("[20.0, 10.13]", "[17.0, 10.13]", ["body.weight_curve[3] = [17, 10.13]", "not greater", "18"]),
        ("[76.0, 8.10]", "[76.0, -8.10]", ["body.weight_curve[5]", "-8.1 t/m is negative", "expected >= 0"]),
        ("weight_curve = [", "weight_curve = [[1.0, 2.0]]\nold = [", ["unknown key"]),
        ("shear_force = [[0.0, 350.0]", "shear_force = [[0.0, 0.0]", ["strength.shear_force[0]", "> 0 t"]),
    ],
)
def test_bad_weight_curve_and_envelopes_are_one_line_errors(old, new, fragments):
    assert old in TANKER
    with pytest.raises(InvalidScene) as err:
        loads_scene(TANKER.replace(old, new, 1))
    message = str(err.value)
    assert "\n" not in message
    for fragment in fragments:
        assert fragment in message, message


def test_strength_without_a_weight_curve_is_refused():
    text = (EXAMPLES / "tanker_upright.toml").read_text() + "\n[strength]\nshear_force = [[0.0, 300.0]]\n"
    with pytest.raises(InvalidScene, match="strength: allowable envelopes given but no body.weight_curve"):
        loads_scene(text)


def test_console_summary():
    scene = load_scene(EXAMPLES / "tanker_strength.toml")
    from liftplan.planner.output.console.tables import equilibrium_table

    eq = solve(scene)
    g = hull_girder(scene, eq)
    text = equilibrium_table(scene, eq, girder=g)
    assert f"max |M| {g.max_moment.value:10.1f} t m at x = {g.max_moment.x:7.2f} m (sagging)" in text
    assert "allowable there 350.0 t" in text
    assert math.isclose(g.max_moment.signed, g.max_moment.value)  # sagging between the lugs
