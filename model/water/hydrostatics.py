"""Exact hydrostatics of a closed triangle mesh cut by the water plane, as casadi functions.

Method
------
Place the reference point o on the water plane, above the body-frame origin. The solid
below the plane is bounded by the wetted parts of the hull's triangles and by the
waterplane section (the "cap"). Summing signed tetrahedra (o, a, b, c) over the wetted
triangle pieces gives the submerged volume and its first moment exactly; the cap's
tetrahedra have no volume because o lies in the cap's plane, so the cap never has to be
built. Each triangle is cut by cases (0, 1, 2 or 3 vertices below the plane): with one
vertex k alone on its side the piece is the triangle (k, k|k+1, k|k+2) or the full
triangle minus it. The waterline segments of the cuts bound the cap; Green's theorem over
those segments gives the waterplane area, its centre and its second moments.

No small-angle step anywhere: the numbers are exact at any attitude (heel 90 deg, fully
submerged, clear of the water), to round-off. The casadi expressions are differentiated
exactly by the root-finders (the derivative of the submerged volume is the waterplane
area, and so on); :class:`Hydrostatics` gives the same properties by name for people and
for the paper's Newton step.

Frame: world ``z-up``; a body point v is at R v + (0, 0, zo) relative to o, where
R is the attitude matrix and zo is the body-frame origin's height above the water plane.
All returned positions are relative to o.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import casadi as ca
import numpy as np

# rows of the raw output vector
VOLUME, MOMENT, AREA, FIRST, SECOND = 0, slice(1, 4), 4, slice(5, 7), slice(7, 10)
RAW = 10


def _cut(p, q, dp, dq):
    """Point where edge p-q crosses the plane (depths dp, dq of opposite sign)."""
    den = dp - dq
    den = ca.if_else(den == 0, 1.0, den)  # never used when equal; keeps derivatives finite
    return p + (dp / den) * (q - p)


def _tetra(a, b, c):
    """Volume and first moment of tetrahedron (0, a, b, c)."""
    vol = ca.dot(a, ca.cross(b, c)) / 6.0
    return ca.vertcat(vol, vol * (a + b + c) / 4.0)


def _segment(p1, p2):
    """Green's-theorem integrals of a cap boundary segment p1 -> p2 (x, y only):
    area, (int x, int y), (int x^2, int y^2, int xy)."""
    x1, y1, x2, y2 = p1[0], p1[1], p2[0], p2[1]
    cross = x1 * y2 - x2 * y1
    return ca.vertcat(
        cross / 2.0,
        (x1 + x2) * cross / 6.0,
        (y1 + y2) * cross / 6.0,
        (x1 * x1 + x1 * x2 + x2 * x2) * cross / 12.0,
        (y1 * y1 + y1 * y2 + y2 * y2) * cross / 12.0,
        (x1 * y2 + 2 * x1 * y1 + 2 * x2 * y2 + x2 * y1) * cross / 24.0,
    )


@cache
def triangle_function():
    """casadi Function (tri[9], R[9], zo) -> raw[10] of one triangle's wet part.

    ``tri`` holds the body-frame vertices a, b, c; ``R`` the attitude column-major.
    Raw rows: volume, first moment (3), then cap area, first moments (2) and second
    moments int x^2, int y^2, int xy (3), all relative to o.
    """
    tri = ca.SX.sym("tri", 9)
    flat = ca.SX.sym("R", 9)
    rot = ca.reshape(flat, 3, 3)
    zo = ca.SX.sym("zo")
    shift = ca.vertcat(0, 0, zo)
    pts = [ca.mtimes(rot, tri[3 * k : 3 * k + 3]) + shift for k in range(3)]
    depth = [p[2] for p in pts]
    wet = [d < 0 for d in depth]
    full = _tetra(*pts)
    every = wet[0] * wet[1] * wet[2]
    solid = every * full
    cap = ca.SX.zeros(6)
    for k in range(3):
        a, b, c = pts[k], pts[(k + 1) % 3], pts[(k + 2) % 3]
        da, db, dc = depth[k], depth[(k + 1) % 3], depth[(k + 2) % 3]
        wa, wb, wc = wet[k], wet[(k + 1) % 3], wet[(k + 2) % 3]
        ab, ac = _cut(a, b, da, db), _cut(a, c, da, dc)
        piece = _tetra(a, ab, ac)
        alone_wet = wa * (1 - wb) * (1 - wc)
        alone_dry = (1 - wa) * wb * wc
        solid += alone_wet * piece + alone_dry * (full - piece)
        # the cap runs opposite to the wet polygon along the shared waterline
        cap += alone_wet * _segment(ac, ab) + alone_dry * _segment(ab, ac)
    return ca.Function("wet_triangle", [tri, flat, zo], [ca.vertcat(solid, cap)])


def wet_parts(triangles, rot, zo):
    """casadi expression, shape (10, m): each triangle's raw sums at a symbolic pose.

    Parameters
    ----------
    triangles : numpy.ndarray, shape (m, 3, 3)  [m]
    rot : casadi MX 3x3
        Attitude matrix.
    zo : casadi MX  [m]
    """
    data = ca.DM(np.asarray(triangles, dtype=float).reshape(-1, 9).T)
    count = data.shape[1]
    rot = ca.vec(rot)
    return triangle_function().map(count)(data, ca.repmat(rot, 1, count), ca.repmat(zo, 1, count))


def mesh_function(triangles):
    """casadi Function (R[9] column-major, zo) -> raw[10] summed over a mesh.

    Parameters
    ----------
    triangles : numpy.ndarray, shape (m, 3, 3)  [m]
    """
    flat, zo = ca.MX.sym("R", 9), ca.MX.sym("zo")
    per = wet_parts(triangles, ca.reshape(flat, 3, 3), zo)
    return ca.Function("hydrostatics", [flat, zo], [ca.sum2(per)])


@dataclass(frozen=True)
class Hydrostatics:
    """Submerged volume and waterplane of a hull at one pose.

    Positions are world-frame offsets (x forward, y to port, z up) from the point o on the
    water plane above the body-frame origin.

    Parameters
    ----------
    volume : float  [m3]
        Submerged volume.
    centre : tuple of 3 float or None  [m]
        Centre of buoyancy (None when dry).
    waterplane_area : float  [m2]
    flotation : tuple of 2 float or None  [m]
        Centre of the waterplane area (None when the hull does not cut the surface).
    inertia : tuple of 3 float  [m4]
        Second moments of the waterplane area about axes through its centre:
        (I_T about the x axis, I_L about the y axis, product I_xy).
    """

    volume: float
    centre: tuple[float, float, float] | None
    waterplane_area: float
    flotation: tuple[float, float] | None
    inertia: tuple[float, float, float]

    @property
    def bm_transverse(self):
        """Transverse metacentric radius BM_T = I_T / V  [m] (None when dry)."""
        return self.inertia[0] / self.volume if self.volume > 0 else None

    @property
    def bm_longitudinal(self):
        """Longitudinal metacentric radius BM_L = I_L / V  [m] (None when dry)."""
        return self.inertia[1] / self.volume if self.volume > 0 else None

    @classmethod
    def from_raw(cls, raw):
        """From the 10 raw sums of :func:`mesh_function`."""
        raw = np.asarray(raw, dtype=float).ravel()
        volume, area = float(raw[VOLUME]), float(raw[AREA])
        centre = tuple(float(v) for v in raw[MOMENT] / volume) if volume > 0 else None
        if area > 0:
            xf, yf = raw[FIRST] / area
            ixx, iyy, ixy = raw[SECOND]
            inertia = (float(iyy - area * yf**2), float(ixx - area * xf**2), float(ixy - area * xf * yf))
            flotation = (float(xf), float(yf))
        else:
            inertia, flotation = (0.0, 0.0, 0.0), None
        return cls(volume=volume, centre=centre, waterplane_area=area, flotation=flotation, inertia=inertia)


class MeshHydrostatics:
    """A hull mesh's hydrostatic function, built once.

    Parameters
    ----------
    triangles : numpy.ndarray, shape (m, 3, 3)  [m]
    """

    def __init__(self, triangles):
        self.function = mesh_function(triangles)

    def raw(self, rot, zo):
        """The 10 raw sums at a pose.

        Parameters
        ----------
        rot : array_like, shape (3, 3)
            Attitude matrix (:func:`~liftplan.model.frames.rotation_matrix`).
        zo : float  [m]
            Height of the body-frame origin above the water plane.
        """
        flat = np.asarray(rot, dtype=float).ravel(order="F")
        return np.asarray(self.function(flat, zo)).ravel()

    def at(self, rot, zo):
        """:class:`Hydrostatics` at a pose (see :meth:`raw`)."""
        return Hydrostatics.from_raw(self.raw(rot, zo))
