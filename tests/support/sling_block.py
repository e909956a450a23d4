"""The sunken block of ``examples/sunken_block_breakout.toml`` on slings, for the tests of the
breakout and the hoist rope lengths with slings (``tests/planner/test_sling_breakout.py``,
``tests/planner/test_sling_lengths.py``): its planning problem, and a 2-leg sling's hook and the
lever rule along the hook line written again from the geometry, for the brute forces."""

from __future__ import annotations

import math

import numpy as np
from helpers import EXAMPLES

from liftplan.planner.problem.file import loads_problem

BLOCK = """
name = "sunken block on slings, breakout"
[body]
weight = 600.0
weight_basis = "air"
cog = [30.0, 0.3, 2.5]
{candidates}
[plan]
{plan}
tolerance = {{ heel = 2.0, trim = 2.0 }}
breakout_scene = "sunken_block_breakout.toml"
{extra}
{cranes}
[attitude]
lift_height = -20.0
"""

EIGHT = [(x, side, y) for x in (5, 10, 50, 55) for side, y in (("P", 5.0), ("S", -5.0))]


def candidate_rows(rows, bulkheads=False):
    return "".join(
        f'[[candidates]]\nname = "F{x}{side}"\nat = [{x:.1f}, {y:.1f}, 6.0]\n'
        + (f'bulkhead = "frame {x}"\n' if bulkheads else "")
        for x, side, y in rows
    )


def crane_tables(swls, legs=2, length=12.0, rope="30.0"):
    return "".join(
        f'[[cranes]]\nname = "C{k + 1}"\nswl = {swl:.1f}\nEA = 50000.0\nrope_length = {rope}\n'
        f"sling = {{ legs = {legs}, length = {length:.1f}, diameter = 80.0 }}\n"
        for k, swl in enumerate(swls)
    )


def block(plan_keys, swls, rows=EIGHT, legs=2, length=12.0, bulkheads=False, rope="30.0", extra=""):
    """The sunken block's planning problem on slings (the breakout scene the example's)."""
    text = BLOCK.format(
        candidates=candidate_rows(rows, bulkheads),
        plan=plan_keys,
        extra=extra,
        cranes=crane_tables(swls, legs, length, rope),
    )
    return loads_problem(text, base=EXAMPLES)


def sling_apex(a, b, length):
    """An equal-legged 2-leg sling's hook: in the vertical plane through a and b, at ``length``
    from both (its own geometry, written here again)."""
    u = (b - a) / np.linalg.norm(b - a)
    up = np.array([0.0, 0.0, 1.0]) - u[2] * u
    up /= np.linalg.norm(up)
    half = 0.5 * np.linalg.norm(b - a)
    return 0.5 * (a + b) + math.sqrt(length**2 - half**2) * up


def turn_about(axis, angle, p):
    """p turned by ``angle`` [rad] about the unit ``axis`` through the origin (a matrix)."""
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    rot = np.eye(3) + math.sin(angle) * k + (1.0 - math.cos(angle)) * k @ k
    return p @ rot.T


def lever_shares(points, pair1, pair2, length, weight, at, tilt):
    """Two hooks' shares of ``weight`` acting at ``at`` with the body tilted by ``tilt`` [rad]
    along the level hook line: the lever rule along that line."""
    hooks = [sling_apex(points[i], points[j], length) for i, j in (pair1, pair2)]
    line = hooks[1] - hooks[0]
    e = np.array([line[0], line[1], 0.0]) / np.hypot(line[0], line[1])
    axis = np.cross([0.0, 0.0, 1.0], e)
    turned = [
        sling_apex(turn_about(axis, tilt, points[i]), turn_about(axis, tilt, points[j]), length)
        for i, j in (pair1, pair2)
    ]
    a1, a2 = (h @ e for h in turned)
    second = weight * (turn_about(axis, tilt, np.asarray(at)) @ e - a1) / (a2 - a1)
    return np.array([weight - second, second]), hooks, e


FOUR_LEG = [
    (x, side, y) for x in (5, 10, 50, 55) for side, y in (("P", 5.0), ("p", 3.0), ("s", -3.0), ("S", -5.0))
]
