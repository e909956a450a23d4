"""Sling geometry: where a crane's hook sits over the lugs its sling takes, and the legs' shares.

Lengths in m, loads in t, angles in degrees from the horizontal, body frame (z-up).

* 2 legs (:func:`pair_apex`): the sling hinges about the line between its two lugs and hangs
  in the vertical plane through them; the hook is not a body-fixed point.
* 3 legs (:func:`tripod_apex`): three legs of one length fix the hook to the body
  (trilateration): the apex above the lugs' circumcentre, square to their plane.
* 4 legs: the same apex where all four legs reach it as made (the lugs concyclic in one plane,
  :data:`FIT`); the sling is then indeterminate and the legs share the load by their stiffness
  (:func:`leg_split`), with the rules' skew factor on top (0027/ND Rev 11 5.6.12).
* Spreader bar (:func:`spreader_hook`): two bottom legs from the lugs to the bar's ends, two
  top legs from the ends to the hook, all in the vertical plane through the lugs.
"""

from __future__ import annotations

import numpy as np

#: How close (m) the fourth leg of a 4-leg sling must reach its lug as made for the sling to
#: count as four-legged. Further off, one leg hangs slack and the sling is a 3-leg sling.
FIT = 1e-3
#: Smallest triangle height (m) of three lugs: below it they are collinear for a tripod.
COLLINEAR = 0.05


def pair_apex(a, b, length):
    """Hook of an equal-legged 2-leg sling on lugs a, b: in the vertical plane through a and
    b, above them, at ``length`` from both (the sling hinges freely about the line ab, so it
    hangs in that plane whatever the body's attitude)  [m].

    Parameters
    ----------
    a, b : (..., 3)  [m]
    length : float  [m]
    """
    half = 0.5 * np.linalg.norm(b - a, axis=-1)
    along = (b - a) / (2 * half)[..., None]
    up = np.array([0.0, 0.0, 1.0]) - along[..., 2:3] * along  # vertical, square to ab
    up = up / np.linalg.norm(up, axis=-1, keepdims=True)
    return 0.5 * (a + b) + np.sqrt(length**2 - half**2)[..., None] * up


def tripod_apex(points, length):
    """Apex of equal legs of ``length`` on the first three of ``points``: the circumcentre of
    the three lugs plus the height sqrt(L^2 - rho^2) along their plane's upward normal.

    Parameters
    ----------
    points : (N, k, 3)  [m]   k >= 3 lugs of each sling
    length : float  [m]

    Returns
    -------
    apex : (N, 3)  [m]   NaN where the legs cannot reach (rho >= L) or the lugs are collinear
    reach : (N, k)  [m]   distance from the apex to every lug (the legs' fit)
    """
    p = np.asarray(points, dtype=float)
    a, b, c = p[:, 0], p[:, 1], p[:, 2]
    ab, ac = b - a, c - a
    n = np.cross(ab, ac)
    area2 = np.linalg.norm(n, axis=1)  # twice the triangle's area
    longest = np.max(
        np.stack(
            [np.linalg.norm(ab, axis=1), np.linalg.norm(ac, axis=1), np.linalg.norm(c - b, axis=1)], axis=1
        ),
        axis=1,
    )
    ok = area2 > COLLINEAR * longest
    with np.errstate(divide="ignore", invalid="ignore"):
        n2 = (n * n).sum(1)
        # circumcentre: a + (|ac|^2 (n x ab) + |ab|^2 (ac x n)) / (2 |n|^2)
        centre = a + (
            (ac * ac).sum(1)[:, None] * np.cross(n, ab) + (ab * ab).sum(1)[:, None] * np.cross(ac, n)
        ) / (2 * n2[:, None])
        rho2 = ((centre - a) ** 2).sum(1)
        unit = n / area2[:, None]
        unit = np.where(unit[:, 2:3] < 0.0, -unit, unit)  # the apex above the lugs' plane
        height = np.sqrt(length**2 - rho2)
        apex = centre + height[:, None] * unit
    apex[~(ok & (rho2 < length**2))] = np.nan
    reach = np.linalg.norm(apex[:, None, :] - p, axis=2)
    return apex, reach


def leg_angles(apex, points):
    """Each leg's angle from the horizontal at level  [deg]; apex (N, 3), points (N, k, 3)."""
    d = apex[:, None, :] - points
    return np.degrees(np.arctan2(d[..., 2], np.hypot(d[..., 0], d[..., 1])))


def leg_split(apex, points, load, stiffness=None):
    """Leg tensions of one sling: a load vector at the apex, legs to the lugs  [t].

    Two legs: least squares (exact when the load lies in the sling's plane). Three: the 3x3
    statics. Four (indeterminate): the legs share by stiffness, T_i = k_i u_i . d with
    (sum k_i u_i u_i^T) d = load, legs as made meeting at the apex (no slack, no preload);
    a leg that would go into compression is slack and the other three carry the load.

    Parameters
    ----------
    apex : (3,)  [m]
    points : (k, 3)  [m]
    load : (3,)  [t]   force the hook line applies at the apex (up, for a level lift)
    stiffness : (k,)  [t/m] or None (equal legs)

    Returns
    -------
    (k,)  [t]
    """
    u = np.asarray(apex, dtype=float) - np.asarray(points, dtype=float)
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    k = len(u)
    load = np.asarray(load, dtype=float)
    if k == 2:
        return np.linalg.lstsq(u.T, load, rcond=None)[0]
    if k == 3:
        return np.linalg.solve(u.T, load)
    stiff = np.ones(k) if stiffness is None else np.asarray(stiffness, dtype=float)
    active = np.ones(k, dtype=bool)
    while True:
        mat = (stiff[active, None, None] * u[active, :, None] * u[active, None, :]).sum(0)
        tension = np.zeros(k)
        tension[active] = stiff[active] * (u[active] @ np.linalg.solve(mat, load))
        if tension.min() >= -1e-12 * max(1.0, np.abs(load).max()) or active.sum() <= 3:
            return tension
        active[int(np.argmin(tension))] = False


def spreader_hook(a, b, bottom, bar, top, load, bar_weight, samples=181, refine=40):
    """Hook and bar ends of a spreader rig hanging from lugs a, b  [m].

    The rig hangs in the vertical plane through a and b: bottom legs (``bottom``) from each lug
    up to its bar end, the bar (``bar`` between its end pins, rigid), top legs (``top``) from the
    ends up to the hook. With the lugs held, the rig has one degree of freedom (the bar's sway);
    it settles where the potential -load x z_hook + (bar_weight / 2)(z_1 + z_2) is least (the
    hook pulled up by its load, the bar's weight at its ends), found on a grid of the bottom
    leg's angle and refined by golden-section search.

    Parameters
    ----------
    a, b : (N, 3)  [m]
    bottom, bar, top : float  [m]
    load : float or (N,)  [t]   the hook load the rig is pulled up by (its share of the weight)
    bar_weight : float  [t]

    Returns
    -------
    hook, end1, end2 : (N, 3)  [m]   NaN where the rig cannot close (the lugs too far apart)
    """
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    horizontal = b - a
    horizontal[:, 2] = 0.0
    span = np.linalg.norm(horizontal, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        e = horizontal / span[:, None]
    # 2-D coordinates in the plane: s along e from a, z up
    bs, bz = span, b[:, 2] - a[:, 2]
    load = np.broadcast_to(np.asarray(load, dtype=float), span.shape)

    def config(theta):
        e1 = np.stack([bottom * np.sin(theta), bottom * np.cos(theta)], axis=-1)
        # end 2 on the circle of radius ``bottom`` about b, at ``bar`` from end 1 (the higher
        # of the two intersections nearer b)
        centre = np.stack([bs, bz], axis=-1)
        d = centre - e1
        dist = np.linalg.norm(d, axis=-1)
        along = (dist**2 + bar**2 - bottom**2) / (2 * dist)
        h = np.sqrt(bar**2 - along**2)
        unit = d / dist[..., None]
        normal = np.stack([-unit[..., 1], unit[..., 0]], axis=-1)
        normal = np.where(normal[..., 1:2] < 0.0, -normal, normal)
        e2 = e1 + along[..., None] * unit + h[..., None] * normal
        mid, half = 0.5 * (e1 + e2), 0.5 * (e2 - e1)
        rise = np.sqrt(top**2 - (half**2).sum(-1))
        up = np.stack([-half[..., 1], half[..., 0]], axis=-1) / np.linalg.norm(half, axis=-1)[..., None]
        up = np.where(up[..., 1:2] < 0.0, -up, up)
        hook = mid + rise[..., None] * up
        energy = -load * hook[..., 1] + 0.5 * bar_weight * (e1[..., 1] + e2[..., 1])
        return hook, e1, e2, np.where(np.isfinite(energy), energy, np.inf)

    grid = np.linspace(-0.5 * np.pi, 0.5 * np.pi, samples)
    with np.errstate(invalid="ignore", divide="ignore"):
        energies = np.stack([config(np.full(span.shape, t))[3] for t in grid], axis=1)
        best = np.argmin(energies, axis=1)
        step = grid[1] - grid[0]
        lo, hi = grid[best] - step, grid[best] + step
        ratio = (np.sqrt(5.0) - 1.0) / 2.0
        for _ in range(refine):
            x1, x2 = hi - ratio * (hi - lo), lo + ratio * (hi - lo)
            left = config(x1)[3] <= config(x2)[3]
            hi, lo = np.where(left, x2, hi), np.where(left, lo, x1)
        hook, e1, e2, energy = config(0.5 * (lo + hi))
    bad = ~np.isfinite(energy)

    def world(q):
        out = a + q[:, 0:1] * e + q[:, 1:2] * np.array([0.0, 0.0, 1.0])
        out[bad] = np.nan
        return out

    return world(hook), world(e1), world(e2)


def hinge_rows(a, b, drop=0.0, bar_weight=0.0):
    """Hinge rows (N, 8) of :class:`~liftplan.model.statics.model.HingedLayout`: lugs a, b (N, 3)
    [m], the parallel bottom legs' drop c [m] (0: a 2-leg sling), the bar's weight w [t]."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    count = len(a)
    return np.column_stack([a, b, np.full(count, float(drop)), np.full(count, float(bar_weight))])


def _unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def hinged_hooks(rows, level_hooks, rot):
    """Hooks of slings hinged about their pairs with the body turned by ``rot``  [m].

    The numpy twin of :func:`liftplan.model.statics.model.hinged_points` (relative to the body
    origin's height): hook = A' + c e_z + s u + h n, with u along the turned pair, n the unit
    vertical square to it, and (s, h) the hook's place in the sling's plane at level.

    Parameters
    ----------
    rows : (N, 8)   hinge rows (:func:`hinge_rows`)
    level_hooks : (N, 3)  [m]   each hook at level, body frame
    rot : (3, 3)   the attitude (:func:`~liftplan.model.frames.rotation_matrix`)

    Returns
    -------
    (N, 3)  [m]   world frame, the body origin at height 0
    """
    rows = np.asarray(rows, dtype=float)
    a, b, drop = rows[:, 0:3], rows[:, 3:6], rows[:, 6:7]
    e_z = np.array([0.0, 0.0, 1.0])
    u0 = _unit(b - a)
    n0 = _unit(e_z - u0[:, 2:3] * u0)
    offset = np.asarray(level_hooks, dtype=float) - a - drop * e_z
    along = (offset * u0).sum(1, keepdims=True)
    height = (offset * n0).sum(1, keepdims=True)
    pa, pb = a @ rot.T, b @ rot.T
    u = _unit(pb - pa)
    n = _unit(e_z - u[:, 2:3] * u)
    return pa + drop * e_z + along * u + height * n


def parallel_spreader_legs(hook, lugs, drop, load, bar_weight):
    """Top and bottom leg tensions of a spreader whose bar spans its lugs (parallel bottom
    legs, vertical): world frame, a vertical hook load  [t].

    Each bar end E_j = lug_j + c e_z: its top leg, the bar (along the ends) and its bottom leg
    (straight down) balance half the bar's weight.

    Parameters
    ----------
    hook : (3,)  [m]
    lugs : (2, 3)  [m]
    drop : float  [m]   bottom leg length
    load : float  [t]   hook load (the body's share and the bar)
    bar_weight : float  [t]

    Returns
    -------
    bottom : (2,)  [t]
    top : (2,)  [t]
    """
    ends = np.asarray(lugs, dtype=float) + [0.0, 0.0, drop]
    top = leg_split(hook, ends, (0.0, 0.0, load))
    bottom = []
    for j in range(2):
        force = top[j] * _unit(hook - ends[j]) - np.array([0.0, 0.0, 0.5 * bar_weight])
        mat = np.column_stack([_unit(ends[1 - j] - ends[j]), [0.0, 0.0, -1.0]])
        bottom.append(np.linalg.lstsq(mat, -force, rcond=None)[0][1])
    return np.array(bottom), top
