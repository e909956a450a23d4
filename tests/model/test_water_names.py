"""In water, each force is named for what it is (issue 14 item 5).

Buoyancy is the weight of the displaced water (>= 0), trapped water is a weight of its
own, the state says grounded / hanging submerged / piercing the surface / clear / afloat,
the load curve's events are bisected between steps and its maximum load is a plateau
(a range of hoist), and the figure, console and JSON say all of it.
"""

import dataclasses

import numpy as np
import pytest
from helpers import example
from numpy.testing import assert_allclose

from liftplan.model import solve
from liftplan.model.frames import rotation_matrix
from liftplan.model.lift import EVENT_TOL, PLATEAU_REL, load_curve
from liftplan.model.scene.hull import Compartment, Hull
from liftplan.model.scene.objects import Body, Crane, Lug, Scene, Water
from liftplan.model.water import hull_heights, solve_in_water
from liftplan.planner.output.console.tables import equilibrium_table, load_curve_table

RHO = 1.025
STEEL = 600.0 / 7.85  # m3: the flooded blocks' steel
LUGS = (("A", (10.0, 5.0, 6.0)), ("B", (50.0, 5.0, 6.0)), ("C", (50.0, -5.0, 6.0)), ("D", (10.0, -5.0, 6.0)))


def symmetric_block(hook):
    """A flooded 60 x 12 x 6 m block symmetric fore-aft and side to side, so it hangs
    level: an air tank (z 0-2 m) under a tank of trapped water (z 2-4 m), both x 25-35 m."""
    hull = Hull.box(
        [0, -6, 0],
        [60, 6, 6],
        flooding="flooded",
        steel_density=7.85,
        compartments=(
            Compartment("air", {"min": [25, -6, 0], "max": [35, 6, 2]}, "air"),
            Compartment("trapped", {"min": [25, -6, 2], "max": [35, 6, 4]}, "water"),
        ),
    )
    return Scene(
        body=Body(600.0, (30.0, 0.0, 2.5)),
        water=Water(RHO, 0.0),
        hull=hull,
        lugs=tuple(Lug(name, at) for name, at in LUGS),
        cranes=tuple(Crane(name, EA=50000.0, boom_height=hook, rope_length=44.0) for name, _ in LUGS),
    )


def displaced(depth):
    """Closed form of the symmetric block's displaced volume [m3] with its keel ``depth``
    [m] under a level surface: the steel (spread like the envelope) and both tanks."""
    steel = STEEL * min(max(depth, 0.0), 6.0) / 6.0
    return steel + 120.0 * np.clip(depth, 0.0, 2.0) + 120.0 * np.clip(depth - 2.0, 0.0, 2.0)


@pytest.mark.parametrize(
    "hook, state",
    [
        (30.0, "hanging submerged"),
        (46.0, "piercing the surface"),
        (47.0, "piercing the surface"),
        (48.0, "piercing the surface"),
        (50.0, "piercing the surface"),
        (56.0, "clear"),
    ],
)
def test_buoyancy_is_the_weight_of_the_displaced_water(hook, state):
    """B = density x displaced volume, against the closed form of the level block at keel
    depths (20.1, 4.07, 3.1, 2.12, 0.18 m, clear) cutting the steel only, the trapped tank
    (twice), the air tank, and none; trapped water
    is a constant weight; the ropes carry W + trapped water - B."""
    eq = solve(symmetric_block(hook))
    a = eq.afloat
    assert a.state == state
    # symmetric: level to round-off, so the wall-sided closed form holds exactly
    assert abs(eq.pose.heel) < 1e-9 and abs(eq.pose.trim) < 1e-9
    depth = -hull_heights(symmetric_block(hook).hull, np.eye(3), eq.pose.lift_height)[0]
    # 1e-9 relative: the clipped sums are exact for a box, up to round-off
    assert_allclose(a.displaced_volume, displaced(depth), rtol=1e-9, atol=1e-9)
    assert_allclose(a.buoyancy, RHO * displaced(depth), rtol=1e-9, atol=1e-9)
    assert a.buoyancy >= 0.0 and a.buoyancy == pytest.approx(a.density * a.displaced_volume, rel=1e-12)
    assert_allclose(a.immersed_volume, 720.0 * min(max(depth, 0.0), 6.0), rtol=1e-9, atol=1e-9)
    assert a.trapped_water == pytest.approx(RHO * 240.0, rel=1e-12)
    # forces closed to 1e-9 W by the solve's acceptance
    assert_allclose(sum(eq.tensions.values()), 600.0 + RHO * 240.0 - a.buoyancy, rtol=1e-9)
    assert a.crane_load(eq.weight) == pytest.approx(sum(eq.tensions.values()), rel=1e-9)
    if state == "clear":
        assert a.buoyancy == 0.0 and a.centre_of_buoyancy is None


def test_afloat_only_for_a_hull_floating_free():
    """Ropes slack (hooks too low) and an intact light box: it floats, state afloat, no
    crane load; the same box on a taut rope is 'piercing the surface', not afloat."""
    box = Hull.box([-5, -2, -1], [5, 2, 1])
    lugs = tuple(
        Lug(n, (x, y, 1.0)) for n, x, y in (("A", -4, 1.5), ("B", 4, 1.5), ("C", 4, -1.5), ("D", -4, -1.5))
    )

    def scene(hook):
        return Scene(
            body=Body(40.0, (0.0, 0.0, 0.0)),
            water=Water(RHO, 0.0),
            hull=box,
            lugs=lugs,
            cranes=tuple(Crane(lug.name, EA=5000.0, boom_height=hook, rope_length=10.0) for lug in lugs),
        )

    free = solve(scene(5.0)).afloat
    assert free.state == "afloat" and free.buoyancy == pytest.approx(40.0, rel=1e-9)
    held = solve(scene(11.8))
    assert held.afloat.state == "piercing the surface" and sum(held.tensions.values()) > 1.0


def test_moments_balance_at_the_named_centres():
    """W at G, trapped water at its centre, B at the centre of buoyancy, F_R at the contact
    and the ropes at their lugs balance in plan: the centres are where the forces act."""
    scene = example("sunken_block_lift")
    for eq in (solve(scene), solve(dataclasses.replace(scene, ground=None), "hydrostatic")):
        a = eq.afloat
        rot = rotation_matrix(eq.pose.heel, eq.pose.trim, eq.pose.yaw)
        origin = np.asarray(a.centre_of_gravity) - rot @ np.asarray(scene.body.cog)
        lugs = scene.lug_points() @ rot.T + origin
        down = eq.weight * np.asarray(a.centre_of_gravity) + a.trapped_water * np.asarray(
            a.centre_of_trapped_water
        )
        up = a.buoyancy * np.asarray(a.centre_of_buoyancy) + np.array(list(eq.tensions.values())) @ lugs
        if a.ground_reaction:
            up = up + a.ground_reaction * np.asarray(a.contact)
        # moments closed to 1e-9 W L by the acceptance (L = 60 m); 1e-8 W L leaves round-off room
        assert_allclose(up[:2], down[:2], atol=1e-8 * eq.weight * 60.0)


def test_solve_json_names_each_force():
    """The contract's keys mean what CONTRACT.md says; the new keys are there."""
    scene = example("sunken_block_lift")
    data = solve(scene).to_json()
    assert data["state"] == "grounded"
    assert data["buoyancy"] == pytest.approx(data["water_density"] * data["displaced_volume"], rel=1e-12)
    steel, air, tank = STEEL, 5 * 12 * 2, 6 * 12 * 2
    # grounded 20 m down, wholly submerged: the closed form; 1e-9 for the clipped sums' round-off
    assert_allclose(data["displaced_volume"], steel + air + tank, rtol=1e-9)
    assert_allclose(data["immersed_volume"], 60 * 12 * 6, rtol=1e-9)
    assert data["trapped_water"] == pytest.approx(RHO * tank, rel=1e-12)
    balance = scene.body.weight - data["buoyancy"] + data["trapped_water"] - data["ground_reaction"]
    assert_allclose(sum(data["tensions"].values()), balance, rtol=1e-9)  # closed to 1e-9 W
    assert data["freeing_force"] == pytest.approx(0.6 * data["ground_reaction"], rel=1e-12)
    assert len(data["centre_of_trapped_water"]) == 3


@pytest.fixture(scope="module")
def curves():
    scene = example("sunken_block_lift")
    return {step: load_curve(scene, step=step) for step in (0.25, 0.1)}


def hanging_at(hoist):
    """The lift's hull hanging free of the ground, every hook raised by ``hoist``."""
    scene = example("sunken_block_lift")
    cranes = tuple(dataclasses.replace(c, boom_height=c.boom_height + hoist) for c in scene.cranes)
    return dataclasses.replace(scene, ground=None, cranes=cranes)


def heights(eq, scene):
    rot = rotation_matrix(eq.pose.heel, eq.pose.trim, eq.pose.yaw)
    return hull_heights(scene.hull, rot, eq.pose.lift_height - scene.water.level)


def test_events_are_bisected_between_steps(curves):
    """Lift-off, surface and clear, each within EVENT_TOL / 2 of where it happens, checked
    independently: hanging free at the event's hoist, the contact sits on the seabed (lift-
    off), the top is at the surface (surface) and the keel leaves it (clear). Above the
    seabed the hull rises at most 1:1 with the hooks, so the heights are within the
    event's tolerance."""
    curve = curves[0.25]
    assert [e.name for e in curve.events] == ["lift-off", "surface", "clear"]
    steps = set(np.round(curve.hoist, 9))
    for e in curve.events:
        assert 0.0 < e.tolerance <= EVENT_TOL / 2 and round(e.hoist, 9) not in steps
    off, surface, clear = curve.events
    assert curve.lift_off == off.hoist
    scene = example("sunken_block_lift")
    # 1e-9 m on top of the tolerance: the solves' own accuracy in height
    eq = solve(hanging_at(off.hoist))
    rot = rotation_matrix(eq.pose.heel, eq.pose.trim, eq.pose.yaw)
    contact = (rot @ np.asarray(scene.ground.contact))[2] + eq.pose.lift_height
    assert abs(contact - (-20.0)) <= off.tolerance + 1e-9
    top = heights(solve(hanging_at(surface.hoist)), scene)[1]
    assert abs(top) <= surface.tolerance + 1e-9
    bottom = heights(solve(hanging_at(clear.hoist)), scene)[0]
    assert abs(bottom) <= clear.tolerance + 1e-9
    # and on the grounded scene, either side of the bracket
    before = solve_in_water(scene, hoist=off.hoist - off.tolerance - 1e-6)
    after = solve_in_water(scene, hoist=off.hoist + off.tolerance + 1e-6)
    assert before.afloat.state == "grounded" and after.afloat.state == "hanging submerged"


def test_plateau_is_a_range_not_a_point(curves):
    """The issue's symptom: the peak was placed at 20.25 m at step 0.25 and elsewhere at
    step 0.1. Now both steps give the same range (ends bisected), every step inside it is
    within 0.1 % of the peak and every step outside below that, and just outside its
    start the load is below."""
    coarse, fine = curves[0.25].max_load, curves[0.1].max_load
    # the clear-of-water loads are constant: the peaks agree to the solves' round-off
    assert coarse.tension == pytest.approx(fine.tension, rel=1e-9)
    assert coarse.tolerance == pytest.approx(PLATEAU_REL * coarse.tension, rel=1e-12)
    assert len(coarse.plateau) == len(fine.plateau) == 1
    # each end is bisected to EVENT_TOL, so two curves differ by at most that
    assert abs(coarse.plateau[0][0] - fine.plateau[0][0]) <= EVENT_TOL
    assert coarse.plateau[0][1] == fine.plateau[0][1] == curves[0.1].hoist[-1] and coarse.to_end
    for curve in curves.values():
        m = curve.max_load
        ((start, end),) = m.plateau
        peak = curve.tensions.max(axis=1)
        inside = (curve.hoist >= start) & (curve.hoist <= end)
        assert np.all(peak[inside] >= m.tension - m.tolerance)
        assert np.all(peak[~inside] < m.tension - m.tolerance)
        # the plateau starts after the surface is pierced and before the hull is clear
        assert curve.event("surface").hoist < start < curve.event("clear").hoist
    start = coarse.plateau[0][0]
    below = solve(hanging_at(start - EVENT_TOL))
    above = solve(hanging_at(start + EVENT_TOL))
    threshold = coarse.tension - coarse.tolerance
    assert max(below.tensions.values()) < threshold <= max(above.tensions.values())


def test_events_do_not_depend_on_the_step(curves):
    coarse, fine = curves[0.25], curves[0.1]
    for a, b in zip(coarse.events, fine.events):
        assert a.name == b.name and abs(a.hoist - b.hoist) <= a.tolerance + b.tolerance


def test_figure_has_a_title_events_and_plateau(curves):
    """Every event is a vertical line on every panel and named on the loads panel; the
    title names the scene; the phases are written on the strip; the plateau is in the
    legend with its range."""
    from liftplan.planner.output.figures.plan import load_curve as draw

    curve = curves[0.25]
    fig = draw(curve, swl=400.0)
    strip, loads, water, pose = fig.axes[:4]
    assert "Load curve: sunken hull block, four-crane lift" in strip.get_title()
    labels = [t.get_text() for t in loads.texts]
    for e in curve.events:
        assert f"{e.name} {e.hoist:.3f} m" in labels
        for ax in (strip, loads, water, pose):
            xs = [line.get_xdata()[0] for line in ax.get_lines() if line.get_linestyle() == "-."]
            assert any(x == pytest.approx(e.hoist, abs=1e-12) for x in xs)
    phases = [t.get_text().strip() for t in strip.texts]
    assert phases == ["grounded", "hanging submerged", "piercing the surface", "clear"]
    legend = " ".join(t.get_text() for t in loads.get_legend().get_texts())
    start, end = curve.max_load.plateau[0]
    assert f"{start:.3f}-{end:.3f} m" in legend and "0.1 %" in legend
    water_legend = " ".join(t.get_text() for t in water.get_legend().get_texts())
    assert "weight of displaced water" in water_legend and "trapped water" in water_legend


def test_console_explains_the_sum_of_tensions(curves):
    """The solve table says why the cranes carry more or less than W, with numbers that
    add up; the load-curve table prints the plateau as a range and every event."""
    scene = example("sunken_block_lift")
    eq = solve(scene)
    text = equilibrium_table(scene, eq)
    a = eq.afloat
    assert "state: grounded" in text and "afloat" not in text
    line = next(x for x in text.splitlines() if x.startswith("sum of rope tensions"))
    assert (
        f"W {eq.weight:.1f} - B {a.buoyancy:.1f} + trapped water {a.trapped_water:.1f} "
        f"- F_R {a.ground_reaction:.1f}"
    ) in line
    assert f"{sum(eq.tensions.values()):.1f} t" in line
    assert f"displaced volume {a.displaced_volume:.1f} m3" in text
    curve = curves[0.25]
    table = load_curve_table(scene, curve)
    start, end = curve.max_load.plateau[0]
    assert f"over hoist {start:.3f}-{end:.3f} m" in table
    for e in curve.events:
        assert f"{e.name}: hoist {e.hoist:.4f} m" in table
    assert "hanging submerged" in table and "piercing the surface" in table
