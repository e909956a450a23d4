"""Inclined ropes: crane tips placed in the world, the 6-DOF equilibrium (pendulum effect).

Crane i's rope runs from its tip q_i (world) to its lug p_i (body). With the body at
position t and attitude R = R(heel, trim, yaw) (:mod:`liftplan.model.frames`), the lug is
at r_i = t + R p_i, the rope's length L_i = |q_i - r_i|, its tension
T_i = EA_i / l0_i max(0, L_i - l0_i), and it pulls the lug along (q_i - r_i) / L_i. Six
equations: the forces and the moments about the CG vanish. A crane without a ``tip`` has
its tip above the lug's start position (at zero attitude, the body origin at (0, 0,
lift_height)) at its boom height, so tips above the lugs reduce to the vertical-rope model
exactly where the equilibrium keeps the lugs under them (tested).

Horizontal rope forces are what the vertical model leaves out: they swing the body until
its CG sits where the rope directions balance, and they load the boom sideways.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from functools import cache

import casadi as ca
import numpy as np

from .errors import EquilibriumNotFound, InvalidScene
from .frames import rotation
from .results import Equilibrium, Pose, SolverInfo

RESIDUAL_TOL = 1e-9  # of W (forces) and W L (moments), as the vertical model


@dataclass(frozen=True)
class RopeForce:
    """Force of one rope on its lug (world frame).

    Parameters
    ----------
    force : tuple of 3 float  [t]
    horizontal : float  [t]
        Magnitude of the horizontal part (the side load on the crane's boom).
    angle : float  [deg]
        Rope inclination from the vertical.
    """

    force: tuple[float, float, float]
    horizontal: float
    angle: float


@cache
def inclined_model(n):
    """casadi residual and root-finder of the 6-DOF model with n ropes.

    x = (tx, ty, tz, heel, trim, yaw) (m, rad); p = [P (3n), tips (3n), l0 (n), EA (n), W,
    G (3), L].
    """
    x = ca.SX.sym("x", 6)
    p = ca.SX.sym("p", 8 * n + 5)
    points = ca.reshape(p[: 3 * n], 3, n)
    tips = ca.reshape(p[3 * n : 6 * n], 3, n)
    length = p[6 * n : 7 * n]
    ea = p[7 * n : 8 * n]
    weight, cog, scale = p[8 * n], p[8 * n + 1 : 8 * n + 4], p[8 * n + 4]
    rot = rotation(x[3], x[4], x[5])
    centre = x[:3] + ca.mtimes(rot, cog)
    force = ca.vertcat(0, 0, -weight)
    moment = ca.SX.zeros(3)
    tensions, vectors = [], []
    for i in range(n):
        lug = x[:3] + ca.mtimes(rot, points[:, i])
        d = tips[:, i] - lug
        span = ca.norm_2(d)
        tension = ea[i] / length[i] * ca.fmax(0, span - length[i])
        pull = tension * d / span
        force += pull
        moment += ca.cross(lug - centre, pull)
        tensions.append(tension)
        vectors.append(pull)
    residual = ca.vertcat(force / weight, moment / (weight * scale))
    function = ca.Function("inclined", [x, p], [residual, ca.vertcat(*tensions), ca.horzcat(*vectors)],
                           ["x", "p"], ["r", "tension", "pull"])
    root = ca.rootfinder("inclined_root", "newton", ca.Function("g", [x, p], [residual]),
                         {"abstol": 1e-13, "abstolStep": 1e-15, "max_iter": 80, "error_on_fail": False,
                          "show_eval_warnings": False})
    return function, root


def crane_tips(scene):
    """World tip positions, shape (n, 3)  [m]: the given ``tip``, or above the lug's start
    position at the boom height."""
    a = scene.attitude
    start = scene.lug_points() + [0.0, 0.0, a.lift_height]
    tips = []
    for crane, lug in zip(scene.cranes, start):
        if crane.tip is not None:
            tips.append(crane.tip)
        elif crane.boom_height is not None:
            tips.append((lug[0], lug[1], crane.boom_height))
        else:
            raise InvalidScene(f"cranes[{crane.lug}]: expected tip = [x, y, z] or boom_height")
    return np.array(tips, dtype=float)


def solve_inclined(scene):
    """6-DOF equilibrium on inclined ropes.

    Parameters
    ----------
    scene : Scene
        Cranes with ``rope_length`` and ``EA``, and ``tip`` or ``boom_height``. No hull.

    Returns
    -------
    Equilibrium
        ``model = "inclined"``; ``rope_forces`` holds each rope's force and inclination,
        ``position`` the body origin's world position.
    """
    if scene.hull is not None:
        raise InvalidScene(
            "cranes.tip: inclined ropes on a hull in water are not modelled; expected tips "
            "above the lugs (vertical ropes) for a scene with [hull] and [water]"
        )
    n = scene.n
    length, stiffness = scene.crane_values("rope_length", "inclined"), scene.crane_values("EA", "inclined")
    tips = crane_tips(scene)
    function, root = inclined_model(n)
    body = scene.body
    p = np.concatenate([scene.lug_points().ravel(), tips.ravel(),
                        length, stiffness,
                        [body.weight], body.cog, [max(scene.plan_diameter, 1.0)]])
    a = scene.attitude
    x0 = [0.0, 0.0, a.lift_height, math.radians(a.heel), math.radians(a.trim), math.radians(a.yaw)]
    begin = time.perf_counter()
    x = np.asarray(root(ca.DM(x0), ca.DM(p))).ravel()
    seconds = time.perf_counter() - begin
    iterations = int(root.stats().get("iter_count", -1))
    residual, tensions, pulls = (np.asarray(v) for v in function(x, p))
    residual = residual.ravel()
    worst = float(np.max(np.abs(residual))) if np.all(np.isfinite(residual)) else math.inf
    heel, trim, yaw = (math.degrees(v) for v in x[3:])
    taut = int(np.sum(tensions > 0))
    if not worst <= RESIDUAL_TOL or not (abs(heel) < 90 and abs(trim) < 90) or taut < 3:
        raise EquilibriumNotFound(
            f"inclined: no equilibrium with three or more taut ropes found (residual {worst:.3g} W, "
            f"heel {heel:.1f} deg, trim {trim:.1f} deg, {taut} taut); check tips, lengths and start"
        )
    names = scene.lug_names
    forces = {}
    for name, pull in zip(names, pulls.T):
        horizontal = float(math.hypot(pull[0], pull[1]))
        angle = math.degrees(math.atan2(horizontal, pull[2]))  # 0 for a slack rope's zero pull
        forces[name] = RopeForce(tuple(float(v) for v in pull), horizontal, angle)
    return Equilibrium(
        model="inclined",
        pose=Pose(heel=heel, trim=trim, yaw=yaw, lift_height=float(x[2])),
        tensions=dict(zip(names, tensions.ravel().tolist())),
        weight=body.weight,
        swl={c.lug: c.swl for c in scene.cranes},
        slack=tuple(name for name, t in zip(names, tensions.ravel()) if t <= 0.0),
        residual=worst * body.weight,
        solver=SolverInfo("newton", True, iterations, seconds),
        rope_forces=forces,
        position=(float(x[0]), float(x[1]), float(x[2])),
    )
