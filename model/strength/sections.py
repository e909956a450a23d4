"""Buoyancy per unit length of a clipped hull mesh, by sections along the body's x.

The hull below the water plane is a polyhedron: the hull's vertices under water and the
points where its edges cross the water plane. Its section by the plane x = s is a polygon
whose corners move linearly with s between the x of those vertices, so the section's area
A(s) is exactly a quadratic and its first moment about z = 0, S(s), a cubic there. Each is
sampled at four interior points of every such interval (interior: a face normal to x, like a
box's end, makes A jump at the interval's ends) and fitted exactly.

The section area comes from the triangles the plane x = s cuts: each gives a segment of the
section's boundary, oriented along e_x x n (n the outward normal, so the section lies on its
left), clipped to the wet side. With the reference point on the waterline of the section
plane, the waterline's own closing segments add nothing (Green's theorem, as
:mod:`liftplan.model.water.hydrostatics` does for the waterplane), so the cap is never built.
A triangle's kappa (t/m3, :func:`liftplan.model.water.afloat.buoyancy_weights`) weights its
segments: the sum is buoyancy per length, density x immersed area for an intact hull.
"""

from __future__ import annotations

import numpy as np

# Chebyshev points on (0, 1): interior, and well conditioned for a cubic fit
_NODES = 0.5 * (1.0 - np.cos((2 * np.arange(4) + 1) * np.pi / 8))
_FIT = np.linalg.inv(_NODES[:, None] ** np.arange(4))
# Breakpoints closer than this fraction of the hull's length are one (round-off of one vertex)
_MERGE = 1e-12
# Section pairs (station, triangle) handled at once, to bound memory on big meshes
_CHUNK = 200_000


def section_breaks(triangles, up, zo):
    """Where the immersed section's area stops being one quadratic in x  [m].

    Parameters
    ----------
    triangles : numpy.ndarray, shape (m, 3, 3)  [m]
        Body frame.
    up : numpy.ndarray, shape (3,)
        The world's up direction in the body frame (third row of the attitude matrix).
    zo : float  [m]
        Height of the body-frame origin above the water plane.
    """
    x = triangles[:, :, 0]
    height = triangles @ up + zo
    points = [x.ravel()]
    for a, b in ((0, 1), (1, 2), (2, 0)):
        ha, hb = height[:, a], height[:, b]
        cross = ha * hb < 0.0
        t = ha[cross] / (ha[cross] - hb[cross])
        points.append(x[cross, a] + t * (x[cross, b] - x[cross, a]))
    breaks = np.unique(np.concatenate(points))
    keep = np.concatenate([[True], np.diff(breaks) > _MERGE * max(breaks[-1] - breaks[0], 1.0)])
    return breaks[keep]


def immersed_sections(triangles, kappa, up, zo, stations):
    """Buoyancy per length and its moment about the body's z = 0 at stations.

    Parameters
    ----------
    triangles : numpy.ndarray, shape (m, 3, 3)  [m]
        Body frame, outward normals.
    kappa : numpy.ndarray, shape (m,)  [t/m3]
        Buoyancy weight of each triangle (density for an intact hull).
    up : numpy.ndarray, shape (3,)
        World up in the body frame.
    zo : float  [m]
        Height of the body-frame origin above the water plane.
    stations : numpy.ndarray, shape (N,)  [m]
        Body x of the sections; none at a vertex's x.

    Returns
    -------
    per_length : numpy.ndarray, shape (N,)  [t/m]
        sum of kappa x immersed area.
    moment : numpy.ndarray, shape (N,)  [t m / m]
        sum of kappa x first moment of the immersed area about body z = 0.
    """
    stations = np.asarray(stations, dtype=float)
    lo, hi = triangles[:, :, 0].min(axis=1), triangles[:, :, 0].max(axis=1)
    per_length, moment = np.zeros(len(stations)), np.zeros(len(stations))
    step = max(1, _CHUNK // max(len(triangles), 1))
    for start in range(0, len(stations), step):
        s = stations[start : start + step]
        station, tri = np.nonzero((lo[None, :] < s[:, None]) & (hi[None, :] > s[:, None]))
        area, first = _segments(triangles[tri], s[station], up, zo)
        per_length[start : start + step] = np.bincount(station, kappa[tri] * area, minlength=len(s))
        moment[start : start + step] = np.bincount(station, kappa[tri] * first, minlength=len(s))
    return per_length, moment


def cut_segments(tris, s):
    """Where the plane x = s_k cuts each triangle k (which straddles it): the segment's ends
    p, q (k, 3) [m], ordered so that the section's outline runs counter-clockwise in (y, z)
    (the hull's outward normal on the right)."""
    d = tris[:, :, 0] - s[:, None]
    positive = d > 0.0
    lone = np.where(positive.sum(axis=1) == 1, np.argmax(positive, axis=1), np.argmin(positive, axis=1))
    rows = np.arange(len(tris))
    k0, k1, k2 = lone, (lone + 1) % 3, (lone + 2) % 3
    v0, v1, v2 = tris[rows, k0], tris[rows, k1], tris[rows, k2]
    d0, d1, d2 = d[rows, k0], d[rows, k1], d[rows, k2]
    p = v0 + (d0 / (d0 - d1))[:, None] * (v1 - v0)
    q = v0 + (d0 / (d0 - d2))[:, None] * (v2 - v0)
    normal = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    along = q - p
    flip = (-along[:, 1] * normal[:, 2] + along[:, 2] * normal[:, 1]) < 0.0
    return np.where(flip[:, None], q, p), np.where(flip[:, None], p, q)


def _segments(tris, s, up, zo):
    """Signed area and first moment (about z = 0) that each cut triangle's wet boundary
    segment adds to its section, with the reference point on the section's waterline."""
    p, q = cut_segments(tris, s)
    hp, hq = p @ up + zo, q @ up + zo
    wet_p, wet_q = hp < 0.0, hq < 0.0
    crossing = wet_p != wet_q
    t = np.where(crossing, hp / np.where(crossing, hp - hq, 1.0), 0.0)
    cut = p + t[:, None] * (q - p)
    p = np.where((crossing & ~wet_p)[:, None], cut, p)
    q = np.where((crossing & wet_p)[:, None], cut, q)
    wet = wet_p | wet_q
    # reference point: on the section's waterline, nearest the body's x axis
    across = up[1] ** 2 + up[2] ** 2
    level = (up[0] * s + zo) / across if across > 1e-24 else np.zeros_like(s)
    y0, z0 = -level * up[1], -level * up[2]
    area = 0.5 * ((p[:, 1] - y0) * (q[:, 2] - z0) - (p[:, 2] - z0) * (q[:, 1] - y0))
    area = np.where(wet, area, 0.0)
    return area, area * (z0 + p[:, 2] + q[:, 2]) / 3.0


def sectional_buoyancy(triangles, kappa, up, zo):
    """Buoyancy per length and its moment, exactly, as piecewise polynomials in x.

    Parameters
    ----------
    triangles, kappa, up, zo
        As :func:`immersed_sections`.

    Returns
    -------
    breaks : numpy.ndarray, shape (K + 1,)  [m]
    per_length : numpy.ndarray, shape (K, 4)
        Ascending coefficients in u = x - breaks[k] of the buoyancy per length [t/m]
        (a quadratic: its cubic coefficient is round-off).
    moment : numpy.ndarray, shape (K, 4)
        Same, of its first moment about the body's z = 0 [t m / m] (a cubic).
    """
    triangles = np.asarray(triangles, dtype=float)
    up = np.asarray(up, dtype=float)
    breaks = section_breaks(triangles, up, zo)
    h = np.diff(breaks)
    stations = (breaks[:-1, None] + h[:, None] * _NODES[None, :]).ravel()
    b, m = immersed_sections(triangles, np.asarray(kappa, dtype=float), up, zo, stations)
    scale = h[:, None] ** -np.arange(4)
    per_length = (b.reshape(-1, 4) @ _FIT.T) * scale
    moment = (m.reshape(-1, 4) @ _FIT.T) * scale
    return breaks, per_length, moment
