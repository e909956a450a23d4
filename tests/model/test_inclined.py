"""Inclined ropes (6 DOF): equal to the vertical model where both apply, pendulum closed
form, and MoorPy's 6-DOF solve on an inclined case."""

import dataclasses

import numpy as np
import pytest
from numpy.testing import assert_allclose
from support.moorpy_peer import moorpy_solve_6dof

from liftplan.model import rotation_matrix, solve


def with_tips(scene, tips):
    cranes = tuple(dataclasses.replace(c, tip=tuple(t)) for c, t in zip(scene.cranes, tips))
    return dataclasses.replace(scene, cranes=cranes).with_analysis(model=None)


def test_tips_above_the_lugs_equal_vertical_model(block):
    """Tips placed above the lugs' equilibrium positions of the vertical model: the 6-DOF
    model finds that same equilibrium, every rope vertical (tolerance: round-off)."""
    scene = block.with_body(cog=(1.5, -0.8, 2.5)).with_crane("FS", boom_height=40.1)
    vertical = solve(scene, "elastic")
    pose = vertical.pose
    lugs = scene.lug_points() @ rotation_matrix(pose.heel, pose.trim).T + [0, 0, pose.lift_height]
    tips = np.column_stack([lugs[:, :2], [c.boom_height for c in scene.cranes]])
    eq = solve(with_tips(scene, tips))
    assert eq.model == "inclined"
    assert_allclose(list(eq.tensions.values()), list(vertical.tensions.values()), rtol=1e-9)
    assert_allclose(
        (eq.pose.heel, eq.pose.trim, eq.pose.lift_height), (pose.heel, pose.trim, pose.lift_height), atol=1e-9
    )
    assert max(f.horizontal for f in eq.rope_forces.values()) < 1e-6


def test_pendulum_shift_of_all_tips(block):
    """All tips moved 2 m forward: the body swings under them, same tensions, no tilt."""
    base = solve(block, "elastic")
    lugs = block.lug_points() + [0, 0, block.attitude.lift_height]
    tips = np.column_stack([lugs[:, 0] + 2.0, lugs[:, 1], [c.boom_height for c in block.cranes]])
    eq = solve(with_tips(block, tips))
    assert_allclose(eq.position[:2], (2.0, 0.0), atol=1e-8)
    assert_allclose(list(eq.tensions.values()), list(base.tensions.values()), rtol=1e-9)
    assert_allclose((eq.pose.heel, eq.pose.trim, eq.pose.yaw), (0, 0, 0), atol=1e-9)


def test_inclined_matches_moorpy(block):
    """Tips splayed outward and one crane off to the side: 6-DOF against MoorPy. Tolerance
    1e-6 relative: MoorPy's lines weigh 1e-9 t/m and it stops at 1e-10 m."""
    lugs = block.lug_points() + [0, 0, block.attitude.lift_height]
    tips = np.column_stack([1.15 * lugs[:, 0], 1.1 * lugs[:, 1], [c.boom_height for c in block.cranes]])
    tips[0, 1] += 3.0
    scene = with_tips(block.with_body(cog=(0.8, -0.4, 2.5)), tips)
    eq = solve(scene)
    assert max(f.horizontal for f in eq.rope_forces.values()) > 1.0  # really inclined
    start = np.array([*eq.position[:2], eq.position[2] + 0.05, 0.002, -0.002, 0.001])
    theirs, world = moorpy_solve_6dof(scene, tips, start)
    assert_allclose(list(eq.tensions.values()), theirs, rtol=1e-6)
    rot = rotation_matrix(eq.pose.heel, eq.pose.trim, eq.pose.yaw)
    ours = scene.lug_points() @ rot.T + np.array(eq.position)
    assert_allclose(ours, world, atol=1e-6)
    # horizontal forces balance (no other horizontal force acts)
    total = np.sum([f.force for f in eq.rope_forces.values()], axis=0)
    assert_allclose(total, (0, 0, scene.body.weight), atol=1e-8 * scene.body.weight)


def test_inclined_json_has_horizontal_forces(block):
    lugs = block.lug_points() + [0, 0, block.attitude.lift_height]
    tips = np.column_stack([1.1 * lugs[:, 0], lugs[:, 1], [c.boom_height for c in block.cranes]])
    data = solve(with_tips(block, tips)).to_json()
    assert set(data["horizontal_forces"]) == set(block.lug_names)
    assert len(data["position"]) == 3


def test_vertical_model_refuses_tips(block):
    with pytest.raises(Exception, match="hangs the ropes vertically"):
        solve(with_tips(block, np.zeros((4, 3)) + [0, 0, 50]), "elastic")


def test_inclined_refused_in_water():
    from helpers import example

    scene = example("sunken_block_lift")
    cranes = (dataclasses.replace(scene.cranes[0], tip=(0.0, 0.0, 30.0)),) + scene.cranes[1:]
    with pytest.raises(Exception, match="not modelled"):
        solve(dataclasses.replace(scene, cranes=cranes))
