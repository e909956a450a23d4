"""The given-attitude models (``rigid``, ``paper-elastic``) on a hull in water (issue 15 item 3).

The forward ``hydrostatic`` model finds a hanging hull's pose; at that pose and lift height
the given-attitude models must give the same tensions, buoyancy and centres: with three
ropes the statics are determinate, with four ``rigid`` holds one of the forward tensions.
"""

import dataclasses

import numpy as np
import pytest
from helpers import example
from numpy.testing import assert_allclose

from liftplan.model import solve
from liftplan.model.errors import EquilibriumNotFound, InvalidScene
from liftplan.model.frames import rotation_matrix
from liftplan.model.scene.hull import Compartment, Hull
from liftplan.model.scene.objects import Analysis, Attitude, Body, Crane, Lug, Redundant, Scene, Water

RHO = 1.025
THREE = (("A", (10.0, 5.0, 6.0)), ("B", (50.0, 4.0, 6.0)), ("C", (28.0, -5.0, 6.0)))
FOUR = (("A", (10.0, 5.0, 6.0)), ("B", (50.0, 5.0, 6.0)), ("C", (50.0, -5.0, 6.0)), ("D", (10.0, -5.0, 6.0)))
# the same 1e-9 W the solvers accept at; measured 1e-12 W
TOL = 1e-9


def flooded_block(hook, lugs=THREE):
    """A flooded 60 x 12 x 6 m block, CG off the centre line, an air tank amidships and a
    tank of trapped water to port-aft of it, on ropes of equal length: it hangs tilted."""
    hull = Hull.box(
        [0, -6, 0],
        [60, 6, 6],
        flooding="flooded",
        steel_density=7.85,
        compartments=(
            Compartment("air", {"min": [28, -6, 0], "max": [34, 6, 2]}, "air"),
            Compartment("trapped", {"min": [20, -6, 0], "max": [26, 0, 3]}, "water"),
        ),
    )
    return Scene(
        body=Body(600.0, (31.0, 0.6, 2.5)),
        water=Water(RHO, 0.0),
        hull=hull,
        attitude=Attitude(lift_height=hook - 50.0),
        lugs=tuple(Lug(name, at) for name, at in lugs),
        cranes=tuple(Crane(name, EA=50000.0, boom_height=hook, rope_length=44.0) for name, _ in lugs),
    )


def intact_box(hook):
    """An intact 10 x 4 x 2 m box of 60 t, CG well off centre, half out of the water."""
    lugs = (("A", (-4.0, 1.5, 1.0)), ("B", (4.0, 1.0, 1.0)), ("C", (0.0, -1.5, 1.0)))
    return Scene(
        body=Body(60.0, (1.5, 0.5, 0.2)),
        water=Water(RHO, 0.0),
        hull=Hull.box([-5, -2, -1], [5, 2, 1]),
        attitude=Attitude(lift_height=hook - 11.0),
        lugs=tuple(Lug(name, at) for name, at in lugs),
        cranes=tuple(Crane(name, EA=800.0, boom_height=hook, rope_length=10.0) for name, _ in lugs),
    )


def held_at(scene, eq, **analysis):
    """The scene held at the forward answer's attitude and lift height."""
    p = eq.pose
    return dataclasses.replace(
        scene,
        attitude=Attitude(heel=p.heel, trim=p.trim, yaw=p.yaw, lift_height=p.lift_height),
        analysis=Analysis(**analysis) if analysis else scene.analysis,
    )


def same_water(given, forward, weight):
    a, b = given.afloat, forward.afloat
    assert a.state == b.state
    assert_allclose(a.buoyancy, b.buoyancy, rtol=0, atol=TOL * weight)
    assert_allclose(a.trapped_water, b.trapped_water, rtol=0, atol=TOL * weight)
    assert_allclose(a.immersed_volume, b.immersed_volume, rtol=1e-12, atol=1e-9)
    # centres to 1e-9 of the hull's 60 m (round-off of two summation orders)
    for key in ("centre_of_buoyancy", "centre_of_gravity", "centre_of_trapped_water"):
        if getattr(b, key) is None:
            assert getattr(a, key) is None
        else:
            assert_allclose(getattr(a, key), getattr(b, key), rtol=0, atol=1e-9 * 60.0)


@pytest.mark.parametrize(
    "hook, state, method",
    [
        (30.0, "hanging submerged", "linear (constant buoyancy)"),
        (46.0, "piercing the surface", "linear (clipped hull)"),
        (47.5, "piercing the surface", "linear (clipped hull)"),  # the surface cuts the trapped tank
        (49.0, "piercing the surface", "linear (clipped hull)"),  # and the air tank
    ],
)
@pytest.mark.parametrize("model", ["rigid", "paper-elastic"])
def test_three_ropes_equal_the_forward_model(hook, state, method, model):
    """Three ropes are statically determinate: at the forward answer's pose both models give
    its tensions to 1e-9 W, and the same buoyancy, trapped water and centres."""
    scene = flooded_block(hook)
    forward = solve(scene)
    assert forward.afloat.state == state
    assert forward.model == ("submerged" if state == "hanging submerged" else "hydrostatic")
    assert abs(forward.pose.heel) > 0.05 and abs(forward.pose.trim) > 0.01  # really tilted
    given = solve(held_at(scene, forward), model)
    assert given.model == model and given.solver.method == method
    tensions = np.array(list(given.tensions.values()))
    assert_allclose(tensions, list(forward.tensions.values()), rtol=0, atol=TOL * scene.body.weight)
    same_water(given, forward, scene.body.weight)
    assert given.afloat.ground_reaction is None


@pytest.mark.parametrize("hook", [10.8, 11.2])
@pytest.mark.parametrize("model", ["rigid", "paper-elastic"])
def test_intact_hull_piercing_the_surface(hook, model):
    """An intact box hung half out of the water, heeled and trimmed by degrees: the clipped
    hull at the forward pose gives the forward tensions to 1e-9 W."""
    scene = intact_box(hook)
    forward = solve(scene)
    assert forward.afloat.state == "piercing the surface"
    assert abs(forward.pose.heel) > 1.0 and abs(forward.pose.trim) > 1.0
    given = solve(held_at(scene, forward), model)
    assert_allclose(
        list(given.tensions.values()), list(forward.tensions.values()), rtol=0, atol=TOL * scene.body.weight
    )
    same_water(given, forward, scene.body.weight)


@pytest.mark.parametrize("hook", [30.0, 48.0])
def test_four_ropes_rigid_holding_one_forward_tension(hook):
    """Four ropes: ``rigid`` with rope A held at the forward tension gives the other three
    to 1e-9 W."""
    scene = flooded_block(hook, FOUR)
    forward = solve(scene)
    held = held_at(scene, forward, model="rigid", redundant=(Redundant("A", forward.tensions["A"]),))
    given = solve(held)
    assert_allclose(
        list(given.tensions.values()), list(forward.tensions.values()), rtol=0, atol=TOL * scene.body.weight
    )


@pytest.mark.parametrize("hook", [30.0, 48.0])
def test_four_ropes_paper_elastic_closure(hook):
    """Four ropes, ``paper-elastic``: W at G, trapped water at its centre, B at the centre of
    buoyancy and the tensions at the lugs balance (1e-9 W, 1e-9 W L), and the elongations
    T l / EA are affine in the lugs' plan coordinates (the paper's coplanar lugs)."""
    scene = flooded_block(hook, FOUR)
    eq = solve(held_at(scene, solve(scene)), "paper-elastic")
    a, p = eq.afloat, eq.pose
    rot = rotation_matrix(p.heel, p.trim, p.yaw)
    lugs = scene.lug_points() @ rot.T + [0.0, 0.0, p.lift_height]
    tensions = np.array(list(eq.tensions.values()))
    w = scene.body.weight
    assert_allclose(tensions.sum(), w + a.trapped_water - a.buoyancy, rtol=0, atol=TOL * w)
    down = w * np.asarray(a.centre_of_gravity) + a.trapped_water * np.asarray(a.centre_of_trapped_water)
    up = a.buoyancy * np.asarray(a.centre_of_buoyancy) + tensions @ lugs
    assert_allclose(up[:2], down[:2], rtol=0, atol=TOL * w * 60.0)
    length = np.array([c.boom_height for c in scene.cranes]) - lugs[:, 2]
    elongation = tensions * length / 50000.0
    phi = np.column_stack([np.ones(4), lugs[:, :2]])
    fit = np.linalg.lstsq(phi, elongation, rcond=None)
    # affine to round-off (elongations ~1e-3 m)
    assert_allclose(phi @ fit[0], elongation, rtol=0, atol=1e-13)
    # and the tensions are not simply those of the air: buoyancy takes its share
    air = solve(dataclasses.replace(held_at(scene, solve(scene)), water=None, hull=None), "paper-elastic")
    assert sum(air.tensions.values()) - tensions.sum() > 100.0


def test_ground_contact_carries_nothing():
    """With [ground] the held pose is the contact just touching: the ground reaction is 0
    (the lift-off tensions), the same tensions as without the ground."""
    scene = example("sunken_block_lift")
    with_ground = solve(scene, "paper-elastic")
    without = solve(dataclasses.replace(scene, ground=None), "paper-elastic")
    assert with_ground.afloat.ground_reaction == 0.0 and with_ground.afloat.freeing_force == 0.0
    assert with_ground.tensions == without.tensions
    assert_allclose(with_ground.afloat.contact, (30.0, 0.0, -20.0), rtol=0, atol=1e-12)
    # rigid with one held tension, and the balance W + trapped - B = sum T
    rigid = solve(
        dataclasses.replace(scene, analysis=Analysis(model="rigid", redundant=(Redundant("L1", 120.0),)))
    )
    a = rigid.afloat
    assert_allclose(sum(rigid.tensions.values()), a.crane_load(rigid.weight), rtol=0, atol=TOL * 600.0)
    assert rigid.tensions["L1"] == 120.0


def test_floating_hull_is_refused_in_one_line():
    """Held where B > W the hull would float up: ropes cannot push it down."""
    scene = dataclasses.replace(intact_box(10.0), attitude=Attitude(lift_height=-5.0))
    with pytest.raises(EquilibriumNotFound) as err:
        solve(scene, "paper-elastic")
    text = str(err.value)
    assert "\n" not in text and "buoyancy 82" in text and "exceeds W + trapped water 60 t" in text


def test_other_models_and_the_batched_map_still_refuse_water():
    scene = flooded_block(30.0)
    with pytest.raises(InvalidScene, match="model = 'elastic' leaves out the scene's"):
        solve(scene, "elastic")
    from liftplan.model import paper_elastic_tensions

    with pytest.raises(InvalidScene, match="batched map leaves out"):
        paper_elastic_tensions(scene, [0.0], [0.0])
