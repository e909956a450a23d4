"""Crane vessels as hull meshes: each vessel's heave, heel and trim under her hook loads from
the clipped-mesh hydrostatics, solved together with the body (the ``elastic`` model, in air).

A vessel given by her hull (``[[cranes]] vessel = { mesh = "barge.stl", ... }`` or ``box``)
floats with her weight (``displacement``) at her ``cog``; at rest (no hook load) she settles
where the clipped-mesh buoyancy balances them (heel and trim included, if her cog is off her
centre of buoyancy), and each of her boom tips is then above its lug at ``boom_height``. Under
the hook loads T_i, acting down at the tips (where the rope hangs from), she heaves, heels and
trims about the world's horizontal axes (``tilt``, as the hull in water does) until::

    B - W_v - sum T_i = 0,     moments of B (at its centre), W_v (at G) and T_i (at the tips) = 0

with B = density x the displaced volume of her mesh cut by the water plane, exact at any angle
(:mod:`liftplan.model.water.hydrostatics`). Her tips move with her, and each rope's stretch is
its tip's height less its lug's less its unstretched length. Unknowns: the body's (lift, heel,
trim) and per vessel (her origin's height over the water, two tilts); casadi's Newton solves
them together (residuals: the body's statics over W, W L and each vessel's balance over W_v,
W_v L_v, L_v her size), started from the rope-only start with the vessels at rest.

The water surface is at world height 0 (hull vessels are modelled in air, without ``[water]``):
what sets each tip's height over the water, and so the arm its load gains as she heels. At
small angles the vessel is the linear one of :mod:`liftplan.model.scene.vessel` with her
waterplane and metacentric heights (``tests/model/test_hull_vessels.py``).

Accepted: every residual <= 1e-9 of its scale, the body upright, and every vessel floating
stably (her own hydrostatic stiffness under the loads, the symmetric part of minus her rows'
Jacobian in her unknowns, positive definite).
"""

from __future__ import annotations

import hashlib
import math
import time
from functools import lru_cache

import casadi as ca
import numpy as np

from liftplan.model.errors import EquilibriumNotFound, InvalidScene
from liftplan.model.frames import attitude_angles, rotation_matrix, tilt
from liftplan.model.results import VesselState
from liftplan.model.scene.objects import name_list
from liftplan.model.statics.acceptance import RESIDUAL_TOL
from liftplan.model.statics.floating import tip_plan, with_vessels
from liftplan.model.statics.model import (
    NEWTON_OPTIONS,
    Layout,
    pose_points,
    rope_model,
    rope_tensions,
    statics_system,
)
from liftplan.model.statics.vertical import equilibrium_of, pack_params
from liftplan.model.water.equilibrium import unyaw
from liftplan.model.water.hydrostatics import MeshHydrostatics, wet_parts

#: What the crane values are read for (a missing one's message names it).
MODEL = "elastic (crane vessels as hulls)"


def _balance(triangles, density, rot, zo, weight, cog, loads, points):
    """A vessel's vertical force [t] and moments about o [t m] (o on the water plane above her
    origin): buoyancy up at its centre, her weight at G, hook loads down at ``points``."""
    sums = ca.mtimes(wet_parts(triangles, rot, zo)[:4, :], ca.DM.ones(len(triangles)) * density)
    buoy, moment = sums[0], sums[1:4]
    g = ca.mtimes(rot, cog) + ca.vertcat(0, 0, zo)
    force = buoy - weight - ca.sum1(loads)
    mx = moment[1] - weight * g[1] - ca.dot(loads, points[1, :].T)
    my = -(moment[0] - weight * g[0] - ca.dot(loads, points[0, :].T))
    return ca.vertcat(force, mx, my)


@lru_cache(maxsize=16)
def _rest_solver(key, triangles_bytes, count, density):
    """Newton for one hull at rest: (zo, a, b) given (R0 (9), W_v, G (3), L)."""
    triangles = np.frombuffer(triangles_bytes).reshape(count, 3, 3)
    x = ca.MX.sym("x", 3)
    p = ca.MX.sym("p", 14)
    rot = ca.mtimes(tilt(x[1], x[2]), ca.reshape(p[:9], 3, 3))
    rows = _balance(triangles, density, rot, x[0], p[9], p[10:13], ca.MX.zeros(0), ca.MX.zeros(3, 0))
    scaled = rows / ca.vertcat(p[9], p[9] * p[13], p[9] * p[13])
    residual = ca.Function("hull_rest_g", [x, p], [scaled])
    root = ca.rootfinder("hull_rest", "newton", residual, NEWTON_OPTIONS)
    stiffness = ca.Function("hull_rest_k", [x, p], [-ca.jacobian(scaled, x)])
    return root, residual, stiffness


@lru_cache(maxsize=16)
def _coupled_solver(n, hulls):
    """(z0, p) -> (z, T, stretch, residual, Jacobian) for n ropes and the given hulls
    ((key, triangles bytes, count, density) each); see the module docstring for p."""
    layout = Layout(n)
    m = len(hulls)
    per = 9 + 1 + 3 + 3 * n + n + n + 1
    p = ca.MX.sym("p", layout.size + m * per)
    z = ca.MX.sym("z", 3 + 3 * m)
    yaw, points, cog, weight, boom, length, stiffness, scale = layout.split(p[: layout.size])
    lugs, cog_w = pose_points(points, cog, z[1], z[2], yaw, z[0])
    a_mat, b_vec = statics_system(lugs, cog_w, weight)
    k = layout.size
    tips, parts = boom, []
    for v, (_, triangles_bytes, count, density) in enumerate(hulls):
        block = p[k + v * per : k + (v + 1) * per]
        r0, w_v, g_v = ca.reshape(block[:9], 3, 3), block[9], block[10:13]
        local = ca.reshape(block[13 : 13 + 3 * n], 3, n)
        rest = block[13 + 3 * n : 13 + 4 * n]
        member = block[13 + 4 * n : 13 + 5 * n]
        size = block[13 + 5 * n]
        zo, rot = z[3 + 3 * v], ca.mtimes(tilt(z[4 + 3 * v], z[5 + 3 * v]), r0)
        now = ca.mtimes(rot, local) + ca.repmat(ca.vertcat(0, 0, zo), 1, n)
        tips = tips + member * (now[2, :].T - rest)
        triangles = np.frombuffer(triangles_bytes).reshape(count, 3, 3)
        parts.append((triangles, density, rot, zo, w_v, g_v, member, now, size))
    tension, stretch = rope_tensions(tips, lugs[2, :].T, length, stiffness)
    rows = [(ca.mtimes(a_mat, tension) - b_vec) / ca.vertcat(weight, weight * scale, weight * scale)]
    for triangles, density, rot, zo, w_v, g_v, member, now, size in parts:
        forces = _balance(triangles, density, rot, zo, w_v, g_v, member * tension, now)
        rows.append(forces / ca.vertcat(w_v, w_v * size, w_v * size))
    residual = ca.vertcat(*rows)
    root = ca.rootfinder(
        "hull_vessels", "newton", ca.Function("hull_vessels_g", [z, p], [residual]), NEWTON_OPTIONS
    )
    z0 = ca.MX.sym("z0", z.shape[0])
    solved = root(z0, p)
    outputs = ca.Function("hull_vessels_out", [z, p], [tension, stretch, residual, ca.jacobian(residual, z)])
    return ca.Function("hull_vessels_solve", [z0, p], [solved, *outputs(solved, p)])


def _key(vessel):
    """A hull vessel's cache key: her mesh's bytes and her water's density."""
    data = np.ascontiguousarray(vessel.hull.triangles, dtype=float)
    digest = hashlib.sha1(data.tobytes()).hexdigest()
    return digest, data.tobytes(), len(data), float(vessel.density)


def _size(vessel):
    tris = np.asarray(vessel.hull.triangles).reshape(-1, 3)
    return float(np.max(np.ptp(tris, axis=0)))


def _physical(stiffness, size):
    """A vessel's stiffness from her scaled rows (over W_v, W_v L_v) with her tilts' columns
    brought to m by her size L_v: a matrix of one unit (W_v t/m), whose signs the test reads."""
    return np.asarray(stiffness, dtype=float) @ np.diag([1.0, 1.0 / size, 1.0 / size])


def _stable(stiffness):
    k = np.asarray(stiffness, dtype=float)
    k = 0.5 * (k + k.T)
    return bool(np.min(np.linalg.eigvalsh(k)) > -1e-9 * np.max(np.abs(k)))


def rest_pose(vessel, name):
    """A hull vessel's pose at rest (no hook load): (zo [m], attitude R (3, 3)).

    Raises
    ------
    EquilibriumNotFound
        She does not float (heavier than her whole hull's buoyancy), or not stably.
    """
    key = _key(vessel)
    root, residual, stiffness = _rest_solver(*key)
    heading = rotation_matrix(0.0, 0.0, vessel.heading)
    tris = np.asarray(vessel.hull.triangles).reshape(-1, 3)
    lower, upper = tris.min(axis=0), tris.max(axis=0)
    draft = vessel.displacement / (vessel.density * (upper[0] - lower[0]) * (upper[1] - lower[1]))
    p = np.concatenate([heading.ravel(order="F"), [vessel.displacement], vessel.cog, [_size(vessel)]])
    x = np.asarray(root(ca.DM([-(lower[2] + draft), 0.0, 0.0]), ca.DM(p))).ravel()
    worst = float(np.max(np.abs(np.asarray(residual(x, p)))))
    if not (worst <= RESIDUAL_TOL and _stable(_physical(stiffness(x, p), p[-1]))):
        raise EquilibriumNotFound(
            f"cranes.vessel {name!r}: her hull does not float stably at rest with displacement "
            f"{vessel.displacement:g} t at cog {list(vessel.cog)} (residual {worst:.3g} W_v); expected a "
            "hull that floats her weight upright"
        )
    return float(x[0]), np.asarray(ca.DM(tilt(x[1], x[2]))) @ heading


def _check_kinds(scene):
    """Refuse hull vessels mixed with small-angle ones (one model of vessels per scene)."""
    hulls = [name for name, (v, _) in scene.vessels.items() if v.hull is not None]
    linear = [name for name, (v, _) in scene.vessels.items() if v.hull is None]
    if hulls and linear:
        raise InvalidScene(
            f"cranes.vessel {linear[0]!r}: small-angle vessels with hull vessels ({name_list(hulls)}) in one "
            "scene are not modelled; expected every vessel by her hull, or every one by her particulars"
        )


def solve_hull_vessels(scene):
    """Body and hull vessels in one equilibrium (module docstring).

    Returns
    -------
    Equilibrium
        ``model = "elastic"``, with each vessel's heave, heel, trim and tip drops.

    Raises
    ------
    EquilibriumNotFound
        A vessel does not float at rest, or Newton's answer is not accepted.
    """
    _check_kinds(scene)
    n = scene.n
    level = 0.0  # the water surface's world height (module docstring)
    tips = tip_plan(scene)
    boom = np.array(scene.crane_values("boom_height", MODEL))
    vessels = list(scene.vessels.items())
    blocks, rests, z0 = [], [], []
    for name, (vessel, on) in vessels:
        zo, rot = rest_pose(vessel, name)
        member = np.zeros(n)
        member[list(on)] = 1.0
        rest = boom - level  # each tip's height over the water at rest
        world = np.column_stack([tips[:, 0] - vessel.origin[0], tips[:, 1] - vessel.origin[1], rest - zo])
        local = (rot.T @ world.T) * member  # her tips in her own axes (0 for others' cranes)
        blocks.append(
            np.concatenate(
                [
                    rot.ravel(order="F"),
                    [vessel.displacement],
                    vessel.cog,
                    local.ravel(order="F"),
                    rest,
                    member,
                    [_size(vessel)],
                ]
            )
        )
        rests.append((zo, rot))
        z0 += [zo, 0.0, 0.0]
    hulls = tuple(_key(v) for _, (v, _) in vessels)
    solver = _coupled_solver(n, hulls)
    rope = pack_params(scene, "elastic")
    p = np.concatenate([rope, *blocks])
    start = time.perf_counter()
    x0 = np.asarray(rope_model(n).elastic_start(ca.DM(rope))).ravel()
    z, tensions, stretch, residual, jacobian = (np.asarray(v) for v in solver(np.concatenate([x0, z0]), p))
    seconds = time.perf_counter() - start
    z, tensions, stretch, residual = z.ravel(), tensions.ravel(), stretch.ravel(), residual.ravel()
    worst = float(np.max(np.abs(residual))) if np.all(np.isfinite(residual)) else math.inf
    upright = abs(z[1]) < math.pi / 2 and abs(z[2]) < math.pi / 2
    own = [-jacobian[3 + 3 * v : 6 + 3 * v, 3 + 3 * v : 6 + 3 * v] for v in range(len(vessels))]
    stable = all(_stable(_physical(k, block[-1])) for k, block in zip(own, blocks))
    if not (worst <= RESIDUAL_TOL and upright and stable):
        raise EquilibriumNotFound(
            f"elastic with hull vessels: no accepted equilibrium (residual {worst:.3g} of W, upright "
            f"{upright}, every vessel stable {stable}); check that the boom heights and rope lengths can "
            "hold the body with three or more taut ropes"
        )
    slack = tuple(name for name, s in zip(scene.lug_names, stretch) if s <= 0.0)
    if n - len(slack) < 3:
        raise EquilibriumNotFound(
            f"elastic: only {n - len(slack)} rope(s) taut ({name_list(slack)} slack): expected three or more "
            "to hold the body"
        )
    row_scale = np.array([1.0, scene.plan_diameter, scene.plan_diameter]) * scene.body.weight
    eq = equilibrium_of(
        scene,
        "elastic",
        z[:3],
        tensions,
        residual[:3] * row_scale,
        "newton (body and hull vessels)",
        seconds,
        slack,
    )
    states = {}
    for v, (name, (vessel, on)) in enumerate(vessels):
        states[name] = _state(scene, vessel, on, rests[v], z[3 + 3 * v : 6 + 3 * v], blocks[v], tensions)
    return with_vessels(eq, states)


def _state(scene, vessel, on, rest, unknowns, block, tensions):
    """A hull vessel's :class:`VesselState`: heave of her rest flotation centre, heel and trim in
    her own axes (absolute), each tip's drop, the hooks' moments about her rest flotation centre."""
    n = scene.n
    zo_rest, rot_rest = rest
    zo, rot = unknowns[0], np.asarray(ca.DM(tilt(unknowns[1], unknowns[2]))) @ rot_rest
    flotation = MeshHydrostatics(vessel.hull.triangles).at(rot_rest, zo_rest).flotation
    centre = rot_rest.T @ (np.array([flotation[0], flotation[1], 0.0]) - [0.0, 0.0, zo_rest])
    local = block[13 : 13 + 3 * n].reshape(n, 3).T
    rest_heights = block[13 + 3 * n : 13 + 4 * n]
    heights = (rot @ local)[2] + zo
    # her attitude in her own axes, turned about the vertical to no yaw (the vertical forces leave
    # a turn about it free: the same equilibrium, as a hull in water is reported at its scene's yaw)
    heel, trim, _ = attitude_angles(unyaw(rotation_matrix(0.0, 0.0, -vessel.heading) @ rot, 0.0))
    labels = [c.label for c in scene.cranes]
    offset = local[:2].T - centre[:2]  # forward, port, in her axes
    loads = np.array([tensions[i] for i in on])
    heeling = float(loads @ -offset[list(on), 1])
    trimming = float(loads @ offset[list(on), 0])
    return VesselState(
        heave=float(-((rot @ centre)[2] + zo)),
        heel=heel,
        trim=trim,
        tip_drops={labels[i]: float(rest_heights[i] - heights[i]) for i in on},
        load=float(loads.sum()),
        levelling_ballast=(-heeling, -trimming),
        max_heel=vessel.max_heel,
        max_trim=vessel.max_trim,
        freeboard=None,
        min_freeboard=None,
    )
