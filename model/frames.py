"""Frames, angle conventions and units: written down once, here.

Units
-----
Lengths in m, forces and weights in t (tonne-force), rope stiffness EA in t, angles in
degrees at every public boundary (files, API, command line). Inside the casadi model angles
are radians.

World and body frames (``z-up``, the project's own)
---------------------------------------------------
x forward (towards the bow), y to port, z up. The body frame coincides with the world
frame at zero attitude, with the body-frame origin at world plan position (0, 0) and at
height ``lift_height`` above the datum z = 0.

The papers' frame (``choi``)
----------------------------
Choi & Shin (2000, 2003): x forward, y up, z to starboard, origin at the aft, port, bottom
corner of the hull's bounding box. A point (x, y, z) in it is (x, -z, y) in ``z-up``
(a proper rotation, so handedness is kept).

Attitude
--------
R = Rx(heel) @ Rz(yaw) @ Ry(trim), applied to body-frame vectors: r_world = R @ r_body.

* heel > 0: starboard side down (right-handed rotation about +x lifts +y, port).
* trim > 0: bow down (right-handed rotation about +y lowers +x).
* yaw > 0: bow to port (right-handed about +z).

The papers' R = Rx(psi) Ry(theta) Rz(phi) in their frame maps to heel = psi,
yaw = theta, trim = -phi.
"""

from __future__ import annotations

import math

import casadi as ca
import numpy as np

#: Frames a scene file may be written in.
FRAMES = ("z-up", "choi")
#: How each file frame is named in every output a person reads.
FRAME_TEXT = {
    "z-up": "z-up (x forward, y to port, z up)",
    "choi": "choi, the papers' frame (x forward, y up, z to starboard)",
}


def choi_to_zup(point):
    """Convert a point from the papers' frame to ``z-up``.

    Parameters
    ----------
    point : sequence of 3 float  [m]
        (x forward, y up, z to starboard).

    Returns
    -------
    tuple of 3 float  [m]
        (x forward, y to port, z up).
    """
    x, y, z = (float(v) for v in point)
    return (x, -z, y)


def zup_to_choi(point):
    """Inverse of :func:`choi_to_zup`.

    Parameters
    ----------
    point : sequence of 3 float  [m]
        (x forward, y to port, z up).

    Returns
    -------
    tuple of 3 float  [m]
        (x forward, y up, z to starboard).
    """
    x, y, z = (float(v) for v in point)
    return (x, z, -y)


def rotation(heel, trim, yaw=0.0):
    """Attitude matrix R = Rx(heel) Rz(yaw) Ry(trim) from angles in radians.

    Works on casadi symbols (SX, MX) and on plain floats alike: this is the one
    definition of the attitude used by every model.

    Parameters
    ----------
    heel, trim, yaw : float or casadi expression  [rad]

    Returns
    -------
    casadi matrix 3x3
    """
    ch, sh = ca.cos(heel), ca.sin(heel)
    ct, st = ca.cos(trim), ca.sin(trim)
    cy, sy = ca.cos(yaw), ca.sin(yaw)
    rx = ca.vertcat(ca.horzcat(1, 0, 0), ca.horzcat(0, ch, -sh), ca.horzcat(0, sh, ch))
    rz = ca.vertcat(ca.horzcat(cy, -sy, 0), ca.horzcat(sy, cy, 0), ca.horzcat(0, 0, 1))
    ry = ca.vertcat(ca.horzcat(ct, 0, st), ca.horzcat(0, 1, 0), ca.horzcat(-st, 0, ct))
    return ca.mtimes([rx, rz, ry])


def rotation_matrix(heel, trim, yaw=0.0):
    """Numeric attitude matrix from angles in degrees.

    Parameters
    ----------
    heel, trim, yaw : float  [deg]

    Returns
    -------
    numpy.ndarray, shape (3, 3)
    """
    return np.array(ca.DM(rotation(math.radians(heel), math.radians(trim), math.radians(yaw))))


def tilt(about_x, about_y):
    """Rotation Ry(about_y) Rx(about_x) about the world's horizontal axes (rad; casadi or
    float). The hydrostatic models' unknown tilts act on a start attitude R0 as
    R = tilt(a, b) R0, so they stay well defined at any start attitude, heel 90 deg
    included (where the body's own trim axis is vertical)."""
    ca_, sa = ca.cos(about_x), ca.sin(about_x)
    cb, sb = ca.cos(about_y), ca.sin(about_y)
    rx = ca.vertcat(ca.horzcat(1, 0, 0), ca.horzcat(0, ca_, -sa), ca.horzcat(0, sa, ca_))
    ry = ca.vertcat(ca.horzcat(cb, 0, sb), ca.horzcat(0, 1, 0), ca.horzcat(-sb, 0, cb))
    return ca.mtimes(ry, rx)


def attitude_angles(matrix):
    """Heel, trim and yaw of an attitude matrix, inverse of :func:`rotation_matrix`.

    R = Rx(heel) Rz(yaw) Ry(trim) has first row (cos yaw cos trim, -sin yaw,
    cos yaw sin trim) and second column (-sin yaw, cos heel cos yaw, sin heel cos yaw).

    Parameters
    ----------
    matrix : array_like, shape (3, 3)

    Returns
    -------
    tuple (heel, trim, yaw)  [deg]
        heel and trim in (-180, 180], yaw in [-90, 90].
    """
    r = np.asarray(matrix, dtype=float)
    yaw = math.asin(max(-1.0, min(1.0, -r[0, 1])))
    trim = math.atan2(r[0, 2], r[0, 0])
    heel = math.atan2(r[2, 1], r[1, 1])
    return math.degrees(heel), math.degrees(trim), math.degrees(yaw)
