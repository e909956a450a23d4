"""The hull girder as finite elements: Euler-Bernoulli bending, optionally St Venant torsion.

The beam runs along the body's x over the weight curve's span. Its nodes are the weight
curve's breakpoints, the lugs' x, the stiffness curves' points, and enough points between
them that no element is longer than 1/:data:`ELEMENTS` of the span. Bending uses cubic
Hermite elements (deflection w [m, body +z] and slope w' [rad] at each node), torsion linear
elements (twist theta [rad] about the body x axis through the CG's y and z).

Exactness: between nodes the weight curve and the stiffness curves are linear, so the element
stiffness integrals (EI(x) N''^T N'', a cubic: 2-point Gauss) and the consistent loads
(q(x) N, a quartic: 3-point Gauss) are exact. With EI constant on each element, Hermite
elements give the exact nodal deflections of Euler-Bernoulli theory under these loads (the
element's shape functions contain the homogeneous solutions); with EI varying linearly
inside an element they converge as the elements shrink (tested).

Lug kinematics (body frame, small deflections, plane sections): a lug at (x, y, z) moves by
u = (-(z - z_G) w'(x), -(z - z_G) theta(x), w(x) + (y - y_G) theta(x)), the neutral axis and
the twist axis taken through the CG's height and y (the heights the girder's couples are
referred to, :mod:`.girder`). A body force f at the lug does the work f . u: the beam's
loads are f_z on w, -(z - z_G) f_x on w', and (y - y_G) f_z - (z - z_G) f_y on theta.
The weight per length acts at (y_G, z_G): -q up_z on w only.

Gauge: the beam's rigid motions are the body's pose, so w = 0 at both ends (the deflection is
measured from the chord through the ends) and, with torsion, theta_aft + theta_fore = 0 (the
pose's heel is the mean of the end sections').
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from liftplan.model.errors import InvalidScene
from liftplan.model.strength.girder import _weight

#: At least this many elements over the girder's length (more where the data have points).
ELEMENTS = 40
# Nodes closer than this fraction of the length are one node (a lug on a curve's point)
_MERGE = 1e-9

_GAUSS2 = (np.array([0.5 - 0.5 / np.sqrt(3.0), 0.5 + 0.5 / np.sqrt(3.0)]), np.array([0.5, 0.5]))
_GAUSS3 = (0.5 + 0.5 * np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)]), np.array([5.0, 8.0, 5.0]) / 18.0)


def hermite(t, h):
    """Cubic Hermite shape functions at t = u / h in [0, 1] of an element of length h  [m].

    Returns
    -------
    numpy.ndarray, shape (..., 4)
        Multipliers of (w_a, w'_a, w_b, w'_b).
    """
    t = np.asarray(t, dtype=float)
    return np.stack(
        [1 - 3 * t**2 + 2 * t**3, h * (t - 2 * t**2 + t**3), 3 * t**2 - 2 * t**3, h * (-(t**2) + t**3)],
        axis=-1,
    )


def _curvature(t, h):
    """Second derivatives d2N/du2 of :func:`hermite`  [1/m2, 1/m]."""
    t = np.asarray(t, dtype=float)
    return np.stack([(-6 + 12 * t) / h**2, (-4 + 6 * t) / h, (6 - 12 * t) / h**2, (-2 + 6 * t) / h], axis=-1)


def bending_stiffness(h, ei_a, ei_b):
    """Element stiffness matrix of a Hermite beam element with EI linear along it.

    Parameters
    ----------
    h : float  [m]
    ei_a, ei_b : float  [t m2]
        EI at the element's ends.

    Returns
    -------
    numpy.ndarray, shape (4, 4)  [t/m, t, t m]
        On (w_a, w'_a, w_b, w'_b); integral of EI N''^T N'' (exact: 2-point Gauss on a cubic).
    """
    t, weights = _GAUSS2
    b = _curvature(t, h)
    ei = ei_a + (ei_b - ei_a) * t
    return h * np.einsum("g,g,gi,gj->ij", weights, ei, b, b)


def load_vector(h, q_a, q_b):
    """Consistent nodal loads of a load per length linear from q_a to q_b  [t, t m]."""
    t, weights = _GAUSS3
    q = q_a + (q_b - q_a) * t
    return h * np.einsum("g,g,gi->i", weights, q, hermite(t, h))


@dataclass(frozen=True)
class GirderMesh:
    """The hull girder's elements for one scene.

    Parameters
    ----------
    x : numpy.ndarray, shape (m,)  [m]
        Node positions along the body's x, increasing; the first and last are the weight
        curve's ends.
    bending : numpy.ndarray, shape (m - 1, 4, 4)
        Element stiffness matrices (:func:`bending_stiffness`).
    torsion : numpy.ndarray or None, shape (m - 1,)  [t m]
        Element torsional stiffness GJ_mean / h (None: the hull is rigid in torsion).
    weight : numpy.ndarray, shape (2 m,)  [t, t m]
        Consistent nodal loads of the (corrected) weight curve, on (w_1, w'_1, w_2, ...),
        positive down (the curve's values).
    lug_nodes : tuple of int
        The node of each lug, in scene order.
    """

    x: np.ndarray
    bending: np.ndarray
    torsion: np.ndarray | None
    weight: np.ndarray
    lug_nodes: tuple[int, ...]

    @property
    def m(self):
        """Number of nodes."""
        return len(self.x)

    @property
    def free(self):
        """Number of free beam unknowns after the gauge: 2 m - 2 (+ m - 1 with torsion)."""
        return 2 * self.m - 2 + (self.m - 1 if self.torsion is not None else 0)

    def selection(self):
        """(n, m) one-hot matrix of the lugs' nodes."""
        out = np.zeros((len(self.lug_nodes), self.m))
        out[np.arange(len(self.lug_nodes)), self.lug_nodes] = 1.0
        return out

    def full(self, free):
        """Node values (w, w', theta) from the free unknowns (the gauge put back).

        Returns
        -------
        w, slope, twist : numpy.ndarray, shape (m,)  [m, rad, rad]
            ``twist`` is zeros without torsion.
        """
        free = np.asarray(free, dtype=float)
        m = self.m
        bending = np.zeros(2 * m)
        bending[free_layout(m)] = free[: 2 * m - 2]
        w, slope = bending[0::2], bending[1::2]
        twist = np.zeros(m)
        if self.torsion is not None:
            inner = free[2 * m - 2 :]
            twist = np.concatenate([inner, [-inner[0]]])
        return w, slope, twist

    def deflection(self, free, x):
        """Deflection w at body x (Hermite interpolation between nodes)  [m]."""
        w, slope, _ = self.full(free)
        x = np.asarray(x, dtype=float)
        k = np.clip(np.searchsorted(self.x, x, side="right") - 1, 0, self.m - 2)
        h = self.x[k + 1] - self.x[k]
        n = hermite((x - self.x[k]) / h, h)
        values = np.stack([w[k], slope[k], w[k + 1], slope[k + 1]], axis=-1)
        return np.sum(n * values, axis=-1)


def node_of(mesh_x, x):
    """Index of the node nearest body x  [m] (a point the mesh was built with)."""
    return int(np.argmin(np.abs(np.asarray(mesh_x) - x)))


def hermite_slope(t, h):
    """First derivatives dN/du of :func:`hermite`  [1/m, -]."""
    t = np.asarray(t, dtype=float)
    return np.stack(
        [(-6 * t + 6 * t**2) / h, 1 - 4 * t + 3 * t**2, (6 * t - 6 * t**2) / h, -2 * t + 3 * t**2], axis=-1
    )


def free_layout(m):
    """Indices into the full bending vector (w_1, w'_1, ..., w_m, w'_m) of the free unknowns:
    every slope and the inner deflections (the gauge holds w_1 = w_m = 0)."""
    return np.delete(np.arange(2 * m), [0, 2 * m - 2])


def girder_mesh(scene, elements=ELEMENTS, extra=()):
    """The elements of a scene's hull girder (``scene.girder`` and ``body.weight_curve``).

    Parameters
    ----------
    scene : Scene
    elements : int
        At least this many elements over the span.
    extra : sequence of float  [m]
        More node positions (in water: the ground contact, where the immersed section stops
        being one quadratic, compartment ends); those off the span are dropped.

    Returns
    -------
    GirderMesh
    """

    stiffness = scene.girder
    if stiffness is None:
        raise InvalidScene("hull.EI: missing; expected [[x m, EI t m2], ...] for a flexible hull")
    x_curve, _ = scene.body.weight_curve_arrays
    lo, hi = float(x_curve[0]), float(x_curve[-1])
    length = hi - lo
    lugs_x = scene.lug_points()[:, 0]
    points = [x_curve, lugs_x, [p[0] for p in stiffness.EI], np.asarray(extra, dtype=float).ravel()]
    if stiffness.GJ is not None:
        points.append([p[0] for p in stiffness.GJ])
    raw = np.sort(np.concatenate([np.asarray(p, dtype=float) for p in points]))
    raw = raw[(raw >= lo) & (raw <= hi)]
    keep = np.concatenate([[True], np.diff(raw) > _MERGE * length])
    coarse = raw[keep]
    coarse[0], coarse[-1] = lo, hi
    nodes = [coarse[:1]]
    for a, b in zip(coarse[:-1], coarse[1:]):
        parts = max(1, int(np.ceil((b - a) / length * elements - 1e-9)))
        nodes.append(np.linspace(a, b, parts + 1)[1:])
    x = np.concatenate(nodes)
    h = np.diff(x)
    ei = np.interp(x, *zip(*stiffness.EI))
    bending = np.array([bending_stiffness(hk, a, b) for hk, a, b in zip(h, ei[:-1], ei[1:])])
    torsion = None
    if stiffness.GJ is not None:
        gj = np.interp(x, *zip(*stiffness.GJ))
        torsion = 0.5 * (gj[:-1] + gj[1:]) / h
    curve, _ = _weight(scene.body)
    q = curve(x)  # the corrected weight curve is linear between the nodes
    q_left = curve(x[1:], "left")
    weight = np.zeros(2 * len(x))
    for k, (hk, qa, qb) in enumerate(zip(h, q[:-1], q_left)):
        weight[2 * k : 2 * k + 4] += load_vector(hk, qa, qb)
    lug_nodes = tuple(int(np.argmin(np.abs(x - xl))) for xl in lugs_x)
    return GirderMesh(x=x, bending=bending, torsion=torsion, weight=weight, lug_nodes=lug_nodes)
