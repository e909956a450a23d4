"""Cranes that can be built: booms in plan that do not cross and keep their clearance.

Each crane of a fleet with a ``position`` stands at its slew centre and reaches its lug with
its boom: in plan, the segment from the slew centre to the boom tip above the lug (the hook
is above the lug at the level attitude, world plan coordinates with the plan's yaw, as the
radius of :mod:`liftplan.planner.problem.fleet`). The hoist line hangs from the tip, so in plan
it is the tip itself. Two cranes of one plan are buildable when their boom segments do not
cross and the least plan distance between them (boom to boom, boom to the other's hoist line,
tip to tip) is at least ``plan.crane_clearance``.

The default clearance is GL Noble Denton 0027/ND Rev 11, 16.2: 3 m between the lifted object,
its rigging and the crane booms for an offshore lift (smaller clearances "may be acceptable"
inshore: give the one you accept). A plan view is a necessary check, not a sufficient one: two
booms apart in plan never meet, two booms crossing in plan may pass at different heights, but
slewing and luffing crews treat a crossing as a collision.

Each crane's slew centre must also stand outside the hull's outline (``plan.outline``, when
given) by at least the clearance: a crane vessel cannot sit on or inside the wreck.
"""

from __future__ import annotations

import numpy as np

from liftplan.model.errors import InvalidScene

#: Least plan distance between two cranes' booms and hoist lines  [m] (0027/ND 16.2).
DEFAULT_CLEARANCE = 3.0


def point_segment_distance(p, a, b):
    """Plan distance from points p to segments a-b (broadcast, last axis 2)  [m]."""
    ab, ap = b - a, p - a
    length2 = np.sum(ab * ab, axis=-1)
    t = np.clip(np.sum(ap * ab, axis=-1) / np.where(length2 > 0.0, length2, 1.0), 0.0, 1.0)
    return np.linalg.norm(ap - t[..., None] * ab, axis=-1)


def segment_distance(a0, a1, b0, b1):
    """Least plan distance between segments a0-a1 and b0-b1 (broadcast, last axis 2)  [m];
    0 where they cross."""

    def cross(o, p, q):
        return (p[..., 0] - o[..., 0]) * (q[..., 1] - o[..., 1]) - (p[..., 1] - o[..., 1]) * (
            q[..., 0] - o[..., 0]
        )

    d1, d2 = cross(b0, b1, a0), cross(b0, b1, a1)
    d3, d4 = cross(a0, a1, b0), cross(a0, a1, b1)
    crossing = (d1 * d2 < 0.0) & (d3 * d4 < 0.0)
    ends = np.minimum.reduce(
        [
            point_segment_distance(a0, b0, b1),
            point_segment_distance(a1, b0, b1),
            point_segment_distance(b0, a0, a1),
            point_segment_distance(b1, a0, a1),
        ]
    )
    return np.where(crossing, 0.0, ends)


def boom_distances(positions, tips):
    """Least plan distance between every two booms, each crane on each candidate.

    Parameters
    ----------
    positions : (m, 2)  [m]
        Slew centres, world plan; a row of NaN for a crane without a position.
    tips : (C, 2)  [m]
        Candidates at level, world plan (the boom tips above them).

    Returns
    -------
    numpy.ndarray, shape (C, m, C, m)  [m]
        ``d[c, j, c2, j2]``: crane j on candidate c against crane j2 on candidate c2; inf where
        either crane has no position or j == j2 (a crane does not clash with itself).
    """
    count, m = len(tips), len(positions)
    a0 = np.broadcast_to(positions[None, :, None, None, :], (count, m, count, m, 2))
    a1 = np.broadcast_to(tips[:, None, None, None, :], (count, m, count, m, 2))
    b0 = np.broadcast_to(positions[None, None, None, :, :], (count, m, count, m, 2))
    b1 = np.broadcast_to(tips[None, None, :, None, :], (count, m, count, m, 2))
    d = segment_distance(a0, a1, b0, b1)
    d = np.where(np.isnan(d), np.inf, d)
    d[:, np.arange(m), :, np.arange(m)] = np.inf
    return d


def clear(distance, clearance):
    """True where booms keep the clearance: apart (never crossing or touching, whatever the
    clearance) and at least ``clearance`` [m] apart."""
    return (distance > 0.0) & (distance >= clearance)


def outline_distance(point, outline):
    """Signed plan distance of a point from a closed polygon  [m]: < 0 inside."""
    poly = np.asarray(outline, dtype=float)
    a, b = poly, np.roll(poly, -1, axis=0)
    edge = float(point_segment_distance(np.asarray(point, dtype=float)[None, :], a, b).min())
    x, y = point
    inside = False
    for (x0, y0), (x1, y1) in zip(a, b):  # ray casting
        if (y0 > y) != (y1 > y) and x < x0 + (y - y0) * (x1 - x0) / (y1 - y0):
            inside = not inside
    return -edge if inside else edge


def check_positions(fleet, outline, clearance, shown):
    """Refuse a crane whose slew centre is inside the hull's outline or nearer than the clearance.

    Parameters
    ----------
    fleet : tuple of FleetCrane
    outline : tuple of (x, y)  [m]   world plan at level (empty: nothing to check)
    clearance : float  [m]
    shown : callable
        (x, y) world plan -> text in the file's frame, for the message.
    """
    if len(outline) < 3:
        return
    for j, crane in enumerate(fleet):
        if crane.position is None:
            continue
        d = outline_distance(crane.position, outline)
        if d < clearance:
            where = "inside" if d < 0.0 else f"{d:.2f} m from"
            raise InvalidScene(
                f"cranes[{j}].position {shown(crane.position)} ({crane.name}): {where} the hull's "
                f"outline (plan.outline); expected the slew centre outside it by at least "
                f"plan.crane_clearance = {clearance:g} m"
            )
