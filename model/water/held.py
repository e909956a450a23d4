"""Water forces on a hull held at a given attitude and lift height (the given-attitude models).

``rigid`` and ``paper-elastic`` are told the pose, so nothing has to be solved for in the
water: at that pose the buoyancy B (the weight of the displaced water) and its centre C are
fixed numbers, and every force is vertical. Gravity W at G, trapped water T_w at its centre
and B at C therefore make one vertical force W + T_w - B on the line through

    P = (W G + T_w C_w - B C) / (W + T_w - B)      (plan coordinates, world frame)

and the ropes close the statics with that force, exactly as they close it with W at G in
air. Fully submerged, B and C are the whole displacement's (closed-mesh sums, a constant
force fixed in the body); piercing the surface they come from the hull clipped by the water
plane (:mod:`liftplan.model.water.hydrostatics`), with the same buoyancy weights as the forward
``hydrostatic`` model (:func:`liftplan.model.water.afloat.buoyancy_weights`: intact envelope, or a
flooded hull's steel and watertight compartments).

A ground contact carries nothing here: the scene puts the ground where the contact sits at
its own attitude and lift height, so the held pose is the contact just touching, and the
given-attitude answer is the one with the ground reaction at zero, the lift-off tensions
(any share the ground took would lower them).
"""

from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np

from liftplan.model.errors import EquilibriumNotFound
from liftplan.model.frames import rotation_matrix
from liftplan.model.results import Afloat
from liftplan.model.water.afloat import buoyancy_weights
from liftplan.model.water.hydrostatics import triangle_function
from liftplan.model.water.state import water_state


@dataclass(frozen=True)
class HeldLoads:
    """Water and gravity at a held pose, and the one vertical force they make.

    Parameters
    ----------
    afloat : Afloat
        Buoyancy, its centre, trapped water and state (world frame), ground reaction 0.
    net_weight : float  [t]
        W + trapped water - B: what the ropes carry together.
    net_point : tuple of 3 float  [m]
        A body-frame point on the line of action of ``net_weight``.
    constant : bool
        True when the hull is fully submerged (constant buoyancy fixed in the body).
    """

    afloat: Afloat
    net_weight: float
    net_point: tuple[float, float, float]
    constant: bool


def closed_sums(triangles):
    """Volume [m3] and first moment [m4] (body frame) of each closed group of triangles.

    Parameters
    ----------
    triangles : numpy.ndarray, shape (m, 3, 3)  [m]

    Returns
    -------
    numpy.ndarray, shape (m, 4)
        Per triangle: signed volume of the tetrahedron (0, a, b, c) and its first moment;
        summed over a closed, outward-wound mesh they are the enclosed volume and moment.
    """
    a, b, c = triangles[:, 0], triangles[:, 1], triangles[:, 2]
    vol = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0
    return np.column_stack([vol, vol[:, None] * (a + b + c) / 4.0])


def clipped_sums(triangles, rot, zo):
    """Wet volume and its first moment of each triangle at a pose (relative to o).

    Parameters
    ----------
    triangles : numpy.ndarray, shape (m, 3, 3)  [m]
    rot : numpy.ndarray, shape (3, 3)
    zo : float  [m]   height of the body origin above the water plane

    Returns
    -------
    numpy.ndarray, shape (m, 4)
    """
    count = len(triangles)
    data = ca.DM(np.asarray(triangles, dtype=float).reshape(-1, 9).T)
    flat = ca.DM(np.asarray(rot, dtype=float).ravel(order="F"))
    raw = triangle_function().map(count)(data, ca.repmat(flat, 1, count), ca.repmat(ca.DM(zo), 1, count))
    return np.asarray(raw)[:4].T


def held_loads(scene):
    """The water forces at the scene's attitude and lift height (:class:`HeldLoads`).

    Parameters
    ----------
    scene : Scene
        With ``hull`` and ``water``.

    Raises
    ------
    EquilibriumNotFound
        W + trapped water <= B at this pose: the hull would float up, and ropes cannot
        push it down.
    """
    att, water, hull, body = scene.attitude, scene.water, scene.hull, scene.body
    rot = rotation_matrix(att.heel, att.trim, att.yaw)
    zo = att.lift_height - water.level
    lift = np.array([0.0, 0.0, zo])
    tris, kappa, trapped = buoyancy_weights(hull, body.weight, water.density)
    heights = (rot @ hull.vertices.T)[2] + zo
    bottom, top = float(heights.min()), float(heights.max())
    constant = top < 0.0
    if constant:
        # the whole hull under water: its displacement, a force fixed in the body
        sums = closed_sums(tris)
        sums[:, 1:] = sums[:, 1:] @ rot.T + sums[:, :1] * lift
    else:
        sums = clipped_sums(tris, rot, zo)
    buoyancy = max(0.0, float(kappa @ sums[:, 0]))
    moment = kappa @ sums[:, 1:]
    envelope = slice(0, len(hull.triangles))  # the envelope's triangles come first
    immersed = float(np.sum(sums[envelope, 0]))
    trapped_weight, trapped_at = hull.trapped_water(water.density)
    gravity = rot @ np.asarray(body.cog) + lift
    net = body.weight + trapped_weight - buoyancy
    if not net > 1e-9 * body.weight:
        raise EquilibriumNotFound(
            f"at heel {att.heel:g} deg, trim {att.trim:g} deg, lift height {att.lift_height:g} m the "
            f"buoyancy {buoyancy:.6g} t exceeds W + trapped water {body.weight + trapped_weight:.6g} t: the "
            "hull would float up and ropes cannot push it down; expected a lift height where it hangs on "
            "the ropes"
        )
    first = body.weight * gravity - moment
    trapped_world = None
    if trapped_at is not None:
        trapped_world = rot @ np.asarray(trapped_at) + lift
        first = first + trapped_weight * trapped_world
    point = rot.T @ (first / net - lift)  # back to the body frame (only its plan line counts)
    origin = np.array([0.0, 0.0, water.level])  # world position of o

    def world(q):
        return tuple(float(v) for v in np.asarray(q) + origin)

    friction = scene.ground.friction if scene.ground is not None else None
    afloat = Afloat(
        state=water_state(False, bottom, top, net, body.weight + trapped_weight),
        buoyancy=buoyancy,
        displaced_volume=buoyancy / water.density,
        immersed_volume=immersed,
        trapped_water=trapped_weight,
        density=water.density,
        ground_reaction=0.0 if scene.ground is not None else None,
        freeing_force=0.0 if friction is not None else None,
        centre_of_buoyancy=world(moment / buoyancy) if buoyancy > 0.0 else None,
        centre_of_gravity=world(gravity),
        contact=world(rot @ np.asarray(scene.ground.contact) + lift) if scene.ground is not None else None,
        centre_of_trapped_water=world(trapped_world) if trapped_world is not None else None,
    )
    return HeldLoads(
        afloat=afloat, net_weight=net, net_point=tuple(float(v) for v in point), constant=constant
    )
