"""Many-rope scenes (the 154 m hull with 2 x k lifting points) and numpy peers of the three
rope models, written here from the physics and independent of the casadi model.

Scenes: the particulars of ``examples/hull154_26_points.toml`` (W = 9 000 t, CG (-4.0, 0.3,
7.5) m, lugs at y = +/- 6 m, z = 16 m, stations spread evenly over x = -66 ... +66 m, strand
jacks EA = 161 000 t, H = 126 m, l0 = 109.8 m, SWL 900 t); ``per_side = 13`` is the example,
``per_side = 32`` its 64-point variant. With a seed, the cables, jacks and lug heights are
varied (as a real hoist is not perfectly even) so that no two tensions are alike.

Peers (all from the statics sum T = W, sum T x = W x_c, sum T y = W y_c, world plan
coordinates, rotation R = Rx(heel) Rz(yaw) Ry(trim) written out again here):

* elastic: ``scipy.optimize.root`` (MINPACK hybr) on the three equations in (a, heel, trim)
  with T_i = EA_i max(0, H_i - h_i - l0_i) / l0_i;
* paper-elastic: the (n + 3)-unknown system of Choi & Shin (2003), tensions and the plane's
  three coefficients together (A T = b and T_i = k_i (c0 + c1 x_i + c2 y_i)), by
  ``numpy.linalg.lstsq`` (not the 3x3 normal equations the model solves);
* rigid: the n x n system [A; held rows] T = [b; held tensions] by ``numpy.linalg.lstsq``
  (the model solves the 3x3 of the free lugs).
"""

from __future__ import annotations

import math

import numpy as np

from liftplan.model.scene.objects import Body, Crane, Lug, Redundant, Scene

WEIGHT = 9000.0  # t
COG = (-4.0, 0.3, 7.5)  # m
HALF_SPAN, ROW_Y, LUG_Z = 66.0, 6.0, 16.0  # m
EA, BOOM, LENGTH, SWL = 161000.0, 126.0, 109.8, 900.0  # t, m, m, t


def hull_scene(per_side, seed=None):
    """The 154 m hull on ``2 * per_side`` strand jacks (port row P01.., starboard S01..).

    Parameters
    ----------
    per_side : int
        Lifting points in each row, aft to fore.
    seed : int or None
        None: the even hoist of the example file. Otherwise an uneven one: the lugs'
        heights vary by +/- 0.3 m (the cables' lengths follow them), the unstretched cables
        by a further +/- 0.03 m, the jacks' heights by +/- 0.01 m and EA by +/- 10 %
        (uniform draws from ``numpy.random.default_rng(seed)``): every rope stays taut.

    Returns
    -------
    Scene
    """
    rng = np.random.default_rng(seed) if seed is not None else None

    def draw(half):
        return 0.0 if rng is None else float(rng.uniform(-half, half))

    xs = np.linspace(-HALF_SPAN, HALF_SPAN, per_side)
    lugs, cranes = [], []
    for side, y in (("P", ROW_Y), ("S", -ROW_Y)):
        for k, x in enumerate(xs):
            name = f"{side}{k + 1:02d}"
            dz = draw(0.3)
            lugs.append(Lug(name, (float(x), y, LUG_Z + dz)))
            cranes.append(
                Crane(
                    lug=name,
                    EA=EA + draw(0.1 * EA),
                    boom_height=BOOM + draw(0.01),
                    rope_length=LENGTH - dz + draw(0.03),
                    swl=SWL,
                )
            )
    return Scene(
        body=Body(WEIGHT, COG),
        lugs=tuple(lugs),
        cranes=tuple(cranes),
        name=f"154 m hull, {2 * per_side} lifting points",
    )


def free_three(scene):
    """Three lugs spanning an area: the first and last of the port row, the middle starboard."""
    per_side = scene.n // 2
    return {scene.lug_names[0], scene.lug_names[per_side - 1], scene.lug_names[per_side + per_side // 2]}


def held_scene(scene, tensions):
    """``scene`` for the rigid model, every lug but :func:`free_three` held at ``tensions``."""
    free = free_three(scene)
    held = tuple(Redundant(name, tensions[name]) for name in scene.lug_names if name not in free)
    return scene.with_analysis(model="rigid", redundant=held)


# -- numpy peers ---------------------------------------------------------------------------
def rotation(heel, trim, yaw=0.0):
    """R = Rx(heel) Rz(yaw) Ry(trim), angles in rad (heel > 0 starboard down, trim > 0 bow down)."""
    ch, sh = math.cos(heel), math.sin(heel)
    ct, st = math.cos(trim), math.sin(trim)
    cy, sy = math.cos(yaw), math.sin(yaw)
    rx = np.array([[1.0, 0.0, 0.0], [0.0, ch, -sh], [0.0, sh, ch]])
    rz = np.array([[cy, -sy, 0.0], [sy, cy, 0.0], [0.0, 0.0, 1.0]])
    ry = np.array([[ct, 0.0, st], [0.0, 1.0, 0.0], [-st, 0.0, ct]])
    return rx @ rz @ ry


def _arrays(scene):
    lugs = np.array([lug.at for lug in scene.lugs])
    cranes = {c.lug: c for c in scene.cranes}
    ordered = [cranes[name] for name in scene.lug_names]
    return (
        lugs,
        np.array(scene.body.cog),
        scene.body.weight,
        np.array([c.boom_height or 0.0 for c in ordered]),
        np.array([c.rope_length or 0.0 for c in ordered]),
        np.array([c.EA or 0.0 for c in ordered]),
    )


def _statics(lugs_world, cog_world, weight):
    a = np.vstack([np.ones(len(lugs_world)), lugs_world[:, 0], lugs_world[:, 1]])
    return a, weight * np.array([1.0, cog_world[0], cog_world[1]])


def numpy_elastic(scene):
    """Forward elastic equilibrium by ``scipy.optimize.root``.

    Returns
    -------
    x : numpy.ndarray  (lift [m], heel [rad], trim [rad])
    tensions : numpy.ndarray  [t], scene lug order
    residual : float  [-]  largest statics residual over W (moments over W x 132 m)
    """
    from scipy.optimize import root

    lugs, cog, weight, boom, length, stiffness = _arrays(scene)
    yaw = math.radians(scene.attitude.yaw)
    scale = np.array([weight, weight * 2 * HALF_SPAN, weight * 2 * HALF_SPAN])

    def state(x):
        rot = rotation(x[1], x[2], yaw)
        world = lugs @ rot.T + np.array([0.0, 0.0, x[0]])
        tension = stiffness * np.maximum(0.0, boom - world[:, 2] - length) / length
        a, b = _statics(world, rot @ cog + np.array([0.0, 0.0, x[0]]), weight)
        return tension, (a @ tension - b) / scale

    # start: level, all taut, the lift that carries W
    k = stiffness / length
    lift = (np.sum(k * (boom - lugs[:, 2] - length)) - weight) / np.sum(k)
    result = root(
        lambda x: state(x)[1],
        np.array([lift, 0.0, 0.0]),
        method="hybr",
        options={"xtol": 1e-15, "maxfev": 2000},
    )
    tension, residual = state(result.x)
    if not result.success and np.max(np.abs(residual)) > 1e-12:
        raise RuntimeError(f"scipy root did not converge: {result.message}")
    return result.x, tension, float(np.max(np.abs(residual)))


def numpy_paper_elastic(scene):
    """Choi & Shin (2003) at the scene's attitude: (n + 3) unknowns by least squares  [t]."""
    lugs, cog, weight, boom, _, stiffness = _arrays(scene)
    att = scene.attitude
    rot = rotation(math.radians(att.heel), math.radians(att.trim), math.radians(att.yaw))
    lift = np.array([0.0, 0.0, att.lift_height])
    world = lugs @ rot.T + lift
    a, b = _statics(world, rot @ cog + lift, weight)
    n = scene.n
    k = stiffness / (boom - world[:, 2])
    matrix = np.zeros((n + 3, n + 3))
    matrix[:3, :n] = a
    matrix[3:, :n] = np.eye(n)
    matrix[3:, n:] = -k[:, None] * a.T
    rhs = np.concatenate([b, np.zeros(n)])
    solution = np.linalg.lstsq(matrix, rhs, rcond=None)[0]
    return solution[:n]


def numpy_rigid(scene):
    """Choi et al. (2000) at the scene's attitude: [A; held rows] T = [b; held]  [t]."""
    lugs, cog, weight, *_ = _arrays(scene)
    att = scene.attitude
    rot = rotation(math.radians(att.heel), math.radians(att.trim), math.radians(att.yaw))
    lift = np.array([0.0, 0.0, att.lift_height])
    a, b = _statics(lugs @ rot.T + lift, rot @ cog + lift, weight)
    names = list(scene.lug_names)
    rows = [a] + [np.eye(scene.n)[[names.index(r.lug)]] for r in scene.analysis.redundant]
    rhs = np.concatenate([b, [r.tension for r in scene.analysis.redundant]])
    return np.linalg.lstsq(np.vstack(rows), rhs, rcond=None)[0]
