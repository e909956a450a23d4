"""Mirroring, reordering, translating, or rewriting a scene in the other frame must not
change its tensions. Tolerance 1e-9 relative: the solves converge to ~1e-13 and these
transformations only reorder floating-point sums."""

import dataclasses
import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from liftplan.model import Body, Lug, Redundant, loads_scene, rotation_matrix, solve, zup_to_choi


@pytest.fixture
def uneven(block):
    """The block with uneven boom heights and an off-centre CG: heels, trims, four tensions."""
    scene = block.with_crane("FP", boom_height=40.15).with_crane("AS", boom_height=39.95)
    return scene.with_body(cog=(1.5, -0.8, 2.5)).with_attitude(heel=1.5, trim=-2.0, lift_height=4.0)


MODELS = ["elastic", "paper-elastic", "rigid"]


def prepared(scene, model):
    if model == "rigid":
        return scene.with_analysis(model="rigid", redundant=(Redundant("AP", 200.0),))
    return scene.with_analysis(model=model)


def mirrored(scene):
    """Reflect y -> -y (port <-> starboard); heel changes sign."""
    lugs = tuple(Lug(lug.name, (lug.at[0], -lug.at[1], lug.at[2])) for lug in scene.lugs)
    cog = scene.body.cog
    att = scene.attitude
    return dataclasses.replace(
        scene,
        lugs=lugs,
        body=Body(scene.body.weight, (cog[0], -cog[1], cog[2])),
        attitude=dataclasses.replace(att, heel=-att.heel),
    )


@pytest.mark.parametrize("model", MODELS)
def test_mirror(uneven, model):
    scene = prepared(uneven, model)
    a, b = solve(scene), solve(mirrored(scene))
    assert_allclose(list(b.tensions.values()), list(a.tensions.values()), rtol=1e-9)
    assert b.pose.heel == pytest.approx(-a.pose.heel, abs=1e-9)
    assert b.pose.trim == pytest.approx(a.pose.trim, abs=1e-9)


@pytest.mark.parametrize("model", MODELS)
def test_reorder(uneven, model):
    scene = prepared(uneven, model)
    order = [2, 0, 3, 1]
    shuffled = dataclasses.replace(
        scene, lugs=tuple(scene.lugs[i] for i in order), cranes=tuple(reversed(scene.cranes))
    )
    a, b = solve(scene), solve(shuffled)
    assert list(b.tensions) == [scene.lugs[i].name for i in order]
    for name in a.tensions:
        assert b.tensions[name] == pytest.approx(a.tensions[name], rel=1e-9)


@pytest.mark.parametrize("model", MODELS)
def test_translate_body_frame(uneven, model):
    """Moving the body-frame origin by d moves every body coordinate by -d. The world is
    unchanged when the origin's height drops by the vertical part of R d."""
    scene = prepared(uneven, model)
    shift = np.array([7.0, -3.0, 2.0])
    att = scene.attitude
    lugs = tuple(Lug(lug.name, tuple(np.array(lug.at) - shift)) for lug in scene.lugs)
    cog = tuple(np.array(scene.body.cog) - shift)
    rz = (rotation_matrix(att.heel, att.trim, att.yaw) @ shift)[2]
    moved = dataclasses.replace(
        scene,
        lugs=lugs,
        body=Body(scene.body.weight, cog),
        attitude=dataclasses.replace(att, lift_height=att.lift_height + rz),
    )
    a, b = solve(scene), solve(moved)
    assert_allclose(list(b.tensions.values()), list(a.tensions.values()), rtol=1e-9)


@pytest.mark.parametrize("model", MODELS)
def test_other_frame_same_tensions(uneven, model):
    scene = prepared(uneven, model)

    def text(frame, point):
        pts = "\n".join(
            f'[[lugs]]\nname = "{lug.name}"\nat = [{", ".join(map(repr, point(lug.at)))}]'
            for lug in scene.lugs
        )
        cranes = "\n".join(
            f'[[cranes]]\nlug = "{c.lug}"\nboom_height = {c.boom_height!r}\n'
            f"rope_length = {c.rope_length!r}\nEA = {c.EA!r}"
            for c in scene.cranes
        )
        red = "".join(
            f'\nredundant = {{ lug = "{r.lug}", tension = {r.tension!r} }}' for r in scene.analysis.redundant
        )
        att = scene.attitude
        return (
            f'frame = "{frame}"\n[body]\nweight = {scene.body.weight!r}\n'
            f"cog = [{', '.join(map(repr, point(scene.body.cog)))}]\n{pts}\n{cranes}\n"
            f"[attitude]\nheel = {att.heel!r}\ntrim = {att.trim!r}\n"
            f'lift_height = {att.lift_height!r}\n[analysis]\nmodel = "{model}"{red}\n'
        )

    zup = solve(loads_scene(text("z-up", lambda p: p)))
    choi = solve(loads_scene(text("choi", zup_to_choi)))
    assert_allclose(list(choi.tensions.values()), list(zup.tensions.values()), rtol=1e-12)
    assert_allclose(list(zup.tensions.values()), list(solve(scene).tensions.values()), rtol=1e-12)


def test_conventions_heel_starboard_down_trim_bow_down():
    """heel > 0 lowers the starboard side (y < 0), trim > 0 lowers the bow (x > 0)."""
    starboard, bow = np.array([0.0, -1.0, 0.0]), np.array([1.0, 0.0, 0.0])
    assert (rotation_matrix(5.0, 0.0) @ starboard)[2] < 0
    assert (rotation_matrix(0.0, 5.0) @ bow)[2] < 0
    # rotation order R = Rx(heel) Rz(yaw) Ry(trim)
    h, y, t = (math.radians(a) for a in (10.0, 20.0, 30.0))
    rx = np.array([[1, 0, 0], [0, math.cos(h), -math.sin(h)], [0, math.sin(h), math.cos(h)]])
    rz = np.array([[math.cos(y), -math.sin(y), 0], [math.sin(y), math.cos(y), 0], [0, 0, 1]])
    ry = np.array([[math.cos(t), 0, math.sin(t)], [0, 1, 0], [-math.sin(t), 0, math.cos(t)]])
    assert_allclose(rotation_matrix(10.0, 30.0, 20.0), rx @ rz @ ry, atol=1e-15)


def test_heel_loads_the_high_side(tanker):
    """Heel 5 deg to starboard with the CG 3.5 m below the lugs: the lugs swing further to
    starboard than the CG, so the port (high) ropes T3, T4 (choi z = 0, z-up y = 0) take
    W 3.5/12 tan 5 deg more. A sign check of the whole chain, frame to tensions."""
    level = solve(tanker).tensions
    heeled = solve(tanker.with_attitude(heel=5.0)).tensions
    gain = heeled["T3"] + heeled["T4"] - level["T3"] - level["T4"]
    assert gain == pytest.approx(904 * 3.5 / 12 * math.tan(math.radians(5.0)), rel=1e-12)
