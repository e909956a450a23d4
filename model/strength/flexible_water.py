"""The flexible hull in water: the hull girder as an elastic beam on its ropes, the water and
the ground contact, in one casadi Newton system.

The rigid hull in water (:class:`liftplan.model.water.afloat.AfloatModel`) has the pose as its
unknowns: grounded, the tilts (a, b) about the world's horizontal axes with the body origin's
height zo following from the contact staying on the ground; hanging or afloat, zo as well.
Here the free beam unknowns d (Hermite deflections w and slopes w', :mod:`.beam`, the gauge
w = 0 at both ends) sit beside them, and every load reaches the beam where it acts:

* the weight curve's consistent loads (at the CG's height, as in air);
* the buoyancy per length of each deflected section: at three Gauss points per element the
  section x = s is cut from the hull mesh (the same oriented boundary segments as
  :mod:`.sections`) and clipped by the water plane with the section moved by the beam, a
  body point (s, y, z) rising by up_z w(s) - up_x (z - z_G) w'(s). The section's area and
  first moments are smooth (piecewise) functions of the pose and of w, w' there, so the
  water's own stiffness under the bending hull (rho x waterline breadth, a Winkler
  foundation) is in the Newton system's Jacobian exactly, not assumed;
* water trapped in compartments, a weight per length over each compartment's length;
* each rope's tension at its lug (its height moved by the beam, as in air), and the ground
  reaction R at the contact, which is a node of the beam: the contact is a point (the rigid
  grounded model's pivot), held on the ground, R whatever closes the vertical forces.

Equations: the moments about the contact (grounded; R = -(net vertical force without it)),
or the net force and moments (hanging or afloat), of the same forces on the undeformed
geometry, and the beam's equilibrium rows. Both use one quadrature of the buoyancy, so the
beam's loads are self-equilibrated whenever the statics hold (the gauge's dropped rows are
checked and reported). The quadrature is exact (3-point Gauss: the section area is quadratic
in x, the loads on the Hermite fields of degree <= 5) when the section's breaks (vertices and
waterline crossings, :func:`.sections.section_breaks`) are beam nodes: they are placed at the
chord's pose and the model is rebuilt until the solved pose moves none of them off a node.
The deflected waterline's own crossings are not placed (a second-order effect of w).

The casadi model is built once per discretisation (:class:`WaterBeamShape`: rope and node
counts, the lugs' and the contact's nodes, which station each section segment belongs to) and
cached (:func:`water_beam_model`); every number of the scene, the mesh and the start pose is a
parameter, so an EI sweep or a second mesh of the same size reuses it.

Torsion is not modelled in water (``hull.GJ`` is then unused, and the result says so): the
hull bends; its heel is the pose's.
"""

from __future__ import annotations

import dataclasses
import math
import threading
import time
from dataclasses import dataclass
from functools import cache, cached_property, lru_cache

import casadi as ca
import numpy as np

from liftplan.model.errors import EquilibriumNotFound, InvalidScene
from liftplan.model.frames import rotation_matrix, tilt
from liftplan.model.results import SolverInfo
from liftplan.model.statics.acceptance import RESIDUAL_TOL, schur_positive_definite
from liftplan.model.strength.beam import _GAUSS3, ELEMENTS, girder_mesh, hermite, hermite_slope, node_of
from liftplan.model.strength.flexible import TENSION_CHANGE, RigidHullNote, hull_report, tension_change
from liftplan.model.strength.piecewise import Piecewise
from liftplan.model.strength.sections import cut_segments, immersed_sections, section_breaks
from liftplan.model.water import solve_hydrostatic
from liftplan.model.water.afloat import buoyancy_weights
from liftplan.model.water.equilibrium import WaterSetup, equilibrium_result, tilted_rotation
from liftplan.model.water.state import water_state

#: Rebuilds of the beam mesh at the solved pose, at most (the section breaks on nodes). A
#: solve whose quadrature is still not the clipped hull's exact buoyancy after these is refused
#: (:attr:`WaterBeamState.accepted`); measured: every case of the tests and of the
#: flexible-ground study is exact at the first mesh, a trimmed light barge whose keel leaves the
#: water at the third (tests/model/test_flexible_water_contact.py).
REMESH = 4
#: How the beam is held to the pose's frame: ``"chord"`` (w = 0 at both ends: the pose is the
#: chord's) or ``"stern"`` (w = w' = 0 at the aft end: the pose is the aft section's). The
#: statics are taken on the undeformed geometry of that frame, so the two differ by a term of
#: the order of the deflection's slope (studies/flexible_ground.py measures it).
GAUGES = ("chord", "stern")
#: The gauge dependence per unit deflection: holding the beam at the stern instead of by its
#: chord moves the ground reaction by about this x W x (max deflection / length), the crane
#: load by 0.05-0.09 (measured, studies/flexible_ground.py: 0.112-0.126 over EI 7e6-7e10 t m2,
#: the stranded barge lifted at its bow; one scene, so an estimate, not a bound). A result
#: says so when it reaches :data:`GAUGE_NOTE` of a force the 1 % rule compares.
GAUGE_COEFFICIENT = 0.12
#: ... a tenth of the 1 % rule (:data:`~.flexible.TENSION_CHANGE`): the gauge could then sway it.
GAUGE_NOTE = 0.001
# A section break within this fraction of the length of a node is on it: a kink in the
# buoyancy per length delta off a node errs the quadrature by ~ (slope jump) delta^2
_ON_NODE = 1e-6


# -- the hull's sections (numeric, pose-free) ------------------------------------------------
def oriented_segments(triangles, kappa, stations):
    """The boundary segments of the sections x = s of a closed hull mesh, body frame.

    Each triangle the plane x = s cuts gives one segment of the section's boundary, oriented
    along e_x x n (n its outward normal) so that the section lies on its left (as
    :func:`.sections._segments`); which part of it is wet depends on the pose only.

    Parameters
    ----------
    triangles : numpy.ndarray, shape (m, 3, 3)  [m]
    kappa : numpy.ndarray, shape (m,)  [t/m3]
    stations : numpy.ndarray, shape (N,)  [m]
        Section positions, none at a vertex's x.

    Returns
    -------
    station : numpy.ndarray of int, shape (k,)
        The station of each segment.
    p, q : numpy.ndarray, shape (k, 2)  [m]
        Start and end (body y, z).
    weight : numpy.ndarray, shape (k,)  [t/m3]
        The triangle's kappa.
    """
    lo, hi = triangles[:, :, 0].min(axis=1), triangles[:, :, 0].max(axis=1)
    station, tri = np.nonzero((lo[None, :] < stations[:, None]) & (hi[None, :] > stations[:, None]))
    p, q = cut_segments(triangles[tri], stations[station])
    return station, p[:, 1:], q[:, 1:], kappa[tri]


def _sparse(rows, cols, values, shape):
    """A casadi sparse matrix from triplets (duplicates summed)."""
    dense = np.zeros(shape)
    np.add.at(dense, (np.asarray(rows, dtype=int), np.asarray(cols, dtype=int)), values)
    c, r = np.nonzero(dense.T)  # column-major: the order of casadi's nonzeros
    return ca.DM(ca.Sparsity.triplet(shape[0], shape[1], r.tolist(), c.tolist()), dense[r, c])


# -- the casadi model ------------------------------------------------------------------------
@dataclass(frozen=True)
class WaterBeamData:
    """One solve's mesh, start pose and contact (one scene): the model's shape
    (:func:`water_beam_shape`) and, with the scene, its parameters
    (:meth:`WaterBeamModel.parameters`) come from it.

    Parameters
    ----------
    mesh : GirderMesh
    rot0 : numpy.ndarray, shape (3, 3)
        Start attitude; the unknown tilts act on it.
    grounded : bool
    contact : numpy.ndarray or None, shape (3,)  [m]
        Body-frame contact point (grounded).
    ground : float  [m]
        The contact's height over the water plane (grounded).
    stations, weights : numpy.ndarray  [m, m]
        Gauss points along x and their quadrature weights.
    gauge : {"chord", "stern"}
        How the beam is held to the pose (:data:`GAUGES`).
    """

    mesh: object
    rot0: np.ndarray
    grounded: bool
    contact: np.ndarray | None
    ground: float
    stations: np.ndarray
    weights: np.ndarray
    gauge: str = "chord"


def gauge_fixed(m, gauge="chord"):
    """Indices into the full bending vector (w_1, w'_1, ..., w_m, w'_m) the gauge holds at 0."""
    if gauge not in GAUGES:
        raise ValueError(f"gauge = {gauge!r}: expected one of {GAUGES}")
    return [0, 2 * m - 2] if gauge == "chord" else [0, 1]


def gauge_free(m, gauge="chord"):
    """Indices of the free beam unknowns in the full bending vector (the rest held at 0)."""
    return np.delete(np.arange(2 * m), gauge_fixed(m, gauge))


def full_bending(m, free, gauge="chord"):
    """Node deflections w and slopes w' from the free unknowns of a gauge  [m, rad]."""
    bending = np.zeros(2 * m)
    bending[gauge_free(m, gauge)] = np.asarray(free, dtype=float)[: 2 * m - 2]
    return bending[0::2], bending[1::2]


def beam_at(mesh, w, slope, x):
    """Deflection and slope of the beam at body x (Hermite interpolation)  [m, rad]."""
    x = np.atleast_1d(np.asarray(x, dtype=float))
    k = np.clip(np.searchsorted(mesh.x, x, side="right") - 1, 0, mesh.m - 2)
    h = mesh.x[k + 1] - mesh.x[k]
    t = (x - mesh.x[k]) / h
    values = np.stack([w[k], slope[k], w[k + 1], slope[k + 1]], axis=-1)
    shape = np.stack([hermite(tk, hk) for tk, hk in zip(t, h)])
    turn = np.stack([hermite_slope(tk, hk) for tk, hk in zip(t, h)])
    return (shape * values).sum(-1), (turn * values).sum(-1)


@dataclass(frozen=True)
class WaterBeamShape:
    """What a :class:`WaterBeamModel` is built for: the discretisation, not the numbers.

    Two scenes (or two meshes of one scene) with equal shapes share one built model
    (:func:`water_beam_model`); every number (the pose it starts from, the ropes, the hull's
    section outlines, the mesh's node positions, stiffness and weight loads, the water trapped)
    is a parameter (:meth:`WaterBeamModel.parameters`).

    Parameters
    ----------
    n : int
        Ropes.
    m : int
        Beam nodes (3 Gauss stations per element: 3 (m - 1) stations).
    grounded : bool
    gauge : {"chord", "stern"}
    lug_nodes : tuple of int
        The node of each lug.
    contact_node : int
        The node of the ground contact (-1 when not grounded).
    segments : tuple of int
        The station of each section boundary segment of the buoyant triangles (hull and
        compartments, :func:`oriented_segments`), in order.
    envelope : tuple of int
        The same for the hull envelope's triangles (its immersed volume).
    trapped : int
        Compartments holding water (each a weight at its centre).
    """

    n: int
    m: int
    grounded: bool
    gauge: str
    lug_nodes: tuple
    contact_node: int
    segments: tuple
    envelope: tuple
    trapped: int

    @property
    def stations(self):
        """Gauss stations, 3 per element."""
        return 3 * (self.m - 1)

    @property
    def unknowns(self):
        """Size of z: the pose's (2 grounded, else 3) and the free beam unknowns."""
        return (2 if self.grounded else 3) + 2 * self.m - 2

    def blocks(self):
        """(name, size) of each block of the parameter vector, in order."""
        n, m, ns = self.n, self.m, self.stations
        k, ke = len(self.segments), len(self.envelope)
        return (
            ("rot0", 9),
            ("contact", 3),
            ("ground", 1),
            ("gravity", 1),
            ("weight", 1),
            ("cog", 3),
            ("reference", 3),
            ("span", 1),
            ("hooks", n),
            ("lengths", n),
            ("ea", n),
            ("points", 3 * n),
            ("stations", ns),
            ("weights", ns),
            ("shape_w", _station_pattern(m).nnz()),
            ("shape_s", _station_pattern(m).nnz()),
            ("segment_p", 2 * k),
            ("segment_q", 2 * k),
            ("kappa", k),
            ("envelope_p", 2 * ke),
            ("envelope_q", 2 * ke),
            ("trapped_line", 2 * ns),
            ("trapped", 4 * self.trapped),
            ("loads", 2 * m),
            ("stiffness", _stiffness_pattern(m).nnz()),
        )


@cache
def _station_pattern(m):
    """Sparsity of the Hermite rows (3 (m - 1) stations x 2 m: each station's element's 4
    unknowns)."""
    ns = 3 * (m - 1)
    rows = np.repeat(np.arange(ns), 4)
    cols = (2 * (np.arange(ns) // 3)[:, None] + np.arange(4)[None, :]).ravel()
    return ca.Sparsity.triplet(ns, 2 * m, rows.tolist(), cols.tolist())


@cache
def _stiffness_pattern(m):
    """Sparsity of the assembled bending stiffness (2 m x 2 m: overlapping 4 x 4 blocks)."""
    mask = np.zeros((2 * m, 2 * m))
    for e in range(m - 1):
        mask[2 * e : 2 * e + 4, 2 * e : 2 * e + 4] = 1.0
    return ca.sparsify(ca.DM(mask)).sparsity()


def _values(pattern, dense):
    """The entries of ``dense`` at the nonzeros of ``pattern``, in casadi's order."""
    rows, cols = pattern.get_triplet()
    return np.asarray(dense)[np.asarray(rows, dtype=int), np.asarray(cols, dtype=int)]


class WaterBeamModel:
    """The flexible hull in water as one casadi root-finding problem (module docstring), built
    for a :class:`WaterBeamShape`; use the cached :func:`water_beam_model`.

    Unknowns ``z``: grounded ``(a, b, d)``, else ``(zo, a, b, d)``; parameters ``p``:
    :meth:`parameters`. :attr:`solve` maps ``(z0, p)`` to the root; :attr:`evaluate` gives the
    physical outputs at ``(z, p)``; :attr:`stiffness` the tangent stiffness. Hold :attr:`lock`
    around a solve and its ``stats()`` (the model is shared between threads).
    """

    def __init__(self, shape):
        self.shape = shape
        self.lock = threading.Lock()
        m, n, ns = shape.m, shape.n, shape.stations
        self.npose = 2 if shape.grounded else 3
        z = ca.SX.sym("z", shape.unknowns)
        p = ca.SX.sym("p", sum(size for _, size in shape.blocks()))
        block, at = {}, 0
        for name, size in shape.blocks():
            block[name] = p[at : at + size]
            at += size
        weight_total, body_weight, cog = block["gravity"], block["weight"], block["cog"]
        z_g, span = cog[2], block["span"]
        if shape.grounded:
            tilts, free = z[0:2], z[2:]
        else:
            tilts, free = z[1:3], z[3:]
        rot = ca.mtimes(tilt(tilts[0], tilts[1]), ca.reshape(block["rot0"], 3, 3))
        up = rot[2, :].T
        # the full bending vector (the gauge's entries held at 0)
        keep = gauge_free(m, shape.gauge)
        bend = ca.SX.zeros(2 * m, 1)
        for k, row in enumerate(keep):
            bend[int(row)] = free[k]
        w_nodes, slope_nodes = bend[0::2], bend[1::2]

        def moved(node, dz):
            """Vertical world motion of a body point at node, dz above the CG [m]."""
            return up[2] * w_nodes[node] - up[0] * dz * slope_nodes[node]

        contact = block["contact"]
        if shape.grounded:
            zo = block["ground"] - ca.dot(up, contact) - moved(shape.contact_node, contact[2] - z_g)
        else:
            zo = z[0]
        # ropes: vertical, each lug's height moved by the beam
        tension, stretch = ca.SX.zeros(n, 1), ca.SX.zeros(n, 1)
        points = ca.reshape(block["points"], 3, n)
        hooks, lengths, ea = block["hooks"], block["lengths"], block["ea"]
        for i, node in enumerate(shape.lug_nodes):
            lug = points[:, i]
            height = ca.dot(up, lug) + zo + moved(node, lug[2] - z_g)
            stretch[i] = hooks[i] - height - lengths[i]
            tension[i] = ea[i] / lengths[i] * ca.fmax(0, stretch[i])
        # buoyancy per length at the Gauss stations of the deflected hull
        st, wdm = block["stations"], block["weights"]
        n_w = ca.SX(_station_pattern(m), block["shape_w"])
        n_s = ca.SX(_station_pattern(m), block["shape_s"])
        w_st, s_st = ca.mtimes(n_w, bend), ca.mtimes(n_s, bend)
        uz = up[2] - up[0] * s_st
        c0 = up[0] * st + zo + up[2] * w_st + up[0] * z_g * s_st
        seg = np.asarray(shape.segments, dtype=int)
        gather = _sparse(np.arange(len(seg)), seg, np.ones(len(seg)), (len(seg), ns))
        area_k, first_y, first_z = _clipped(
            ca.reshape(block["segment_p"], len(seg), 2),
            ca.reshape(block["segment_q"], len(seg), 2),
            block["kappa"],
            up[1],
            ca.mtimes(gather, uz),
            ca.mtimes(gather, c0),
        )
        scatter = gather.T
        b = ca.mtimes(scatter, area_k)  # t/m
        s_y = ca.mtimes(scatter, first_y)  # t m / m, about body y = 0
        s_z = ca.mtimes(scatter, first_z)  # t m / m, about body z = 0
        # trapped water per length (uniform over each compartment), and its first moments
        tw, tw_z = block["trapped_line"][0:ns], block["trapped_line"][ns : 2 * ns]
        buoyancy = ca.dot(wdm, b)
        # the hull envelope below the water (what an intact hull displaces; flooded, more)
        e_seg = np.asarray(shape.envelope, dtype=int)
        e_gather = _sparse(np.arange(len(e_seg)), e_seg, np.ones(len(e_seg)), (len(e_seg), ns))
        e_area = _clipped(
            ca.reshape(block["envelope_p"], len(e_seg), 2),
            ca.reshape(block["envelope_q"], len(e_seg), 2),
            ca.DM.ones(len(e_seg)),
            up[1],
            ca.mtimes(e_gather, uz),
            ca.mtimes(e_gather, c0),
        )[0]
        immersed = ca.dot(wdm, ca.mtimes(e_gather.T, e_area))
        # forces (world vertical, up) and moments about the reference point (world x, y)
        net = buoyancy + ca.sum1(tension) - weight_total
        ref = ca.mtimes(rot[0:2, :], contact if shape.grounded else block["reference"])
        first_buoy = ca.vertcat(
            *(ca.dot(wdm, rot[r, 0] * st * b + rot[r, 1] * s_y + rot[r, 2] * s_z) for r in range(3))
        )
        first = first_buoy[0:2] - body_weight * ca.mtimes(rot[0:2, :], cog)
        trapped = ca.reshape(block["trapped"], 4, shape.trapped)
        for j in range(shape.trapped):
            first -= trapped[0, j] * ca.mtimes(rot[0:2, :], trapped[1:4, j])
        if n:
            first += ca.mtimes(ca.mtimes(rot[0:2, :], points), tension)
        # moment of vertical forces f at (x, y): Mx = sum f (y - y_ref), My = -sum f (x - x_ref)
        mx = first[1] - ref[1] * net
        my = -(first[0] - ref[0] * net)
        reaction = -net if shape.grounded else ca.SX(0)
        # the beam's loads (body components of the world-vertical forces; virtual work)
        force = ca.SX.zeros(2 * m, 1)
        for i, node in enumerate(shape.lug_nodes):
            force[2 * node] += tension[i] * up[2]
            force[2 * node + 1] += -tension[i] * up[0] * (points[2, i] - z_g)
        if shape.grounded:
            node = shape.contact_node
            force[2 * node] += reaction * up[2]
            force[2 * node + 1] += -reaction * up[0] * (contact[2] - z_g)
        normal = wdm * (b - tw)
        couple = -up[0] * wdm * ((s_z - z_g * b) - (tw_z - z_g * tw))
        force += ca.mtimes(n_w.T, normal) * up[2] + ca.mtimes(n_s.T, couple)
        force -= up[2] * block["loads"]
        stiffness = ca.SX(_stiffness_pattern(m), block["stiffness"])
        rows = ca.mtimes(stiffness, bend) - force
        moment_rows = ca.DM([1.0 if r % 2 == 1 else 0.0 for r in range(2 * m)])
        row_scale = weight_total * (span * moment_rows + (1 - moment_rows))
        scaled_rows = rows / row_scale
        statics = [mx / (weight_total * span), my / (weight_total * span)]
        generalised = [mx, my]
        if not shape.grounded:
            statics.insert(0, net / weight_total)
            generalised.insert(0, net)
        residual = ca.vertcat(*statics, scaled_rows[keep.tolist()])
        dropped = scaled_rows[gauge_fixed(m, shape.gauge)]
        # generalised forces conjugate to z (pose: force and moments; beam: loads - K d)
        self._gen, self._z, self._p = ca.vertcat(*generalised, -rows[keep.tolist()]), z, p
        self.evaluate = ca.Function(
            "water_beam_eval",
            [z, p],
            [
                tension,
                stretch,
                reaction,
                zo,
                buoyancy,
                first_buoy,
                residual,
                dropped,
                b,
                s_z,
                ca.vertcat(tilts),
                force,
                immersed,
            ],
            ["z", "p"],
            [
                "tension",
                "stretch",
                "reaction",
                "zo",
                "buoyancy",
                "first_buoyancy",
                "residual",
                "dropped",
                "b",
                "s_z",
                "tilts",
                "force",
                "immersed",
            ],
        )
        self.solve = ca.rootfinder(
            "water_beam_newton",
            "newton",
            ca.Function("water_beam_g", [z, p], [residual]),
            {
                "abstol": 1e-13,
                "abstolStep": 1e-15,
                "max_iter": 60,
                "error_on_fail": False,
                "show_eval_warnings": False,
            },
        )

    @cached_property
    def stiffness(self):
        """(z, p) -> minus the Jacobian of the generalised forces (pose: net force and moments;
        beam: loads - K d), in t/m, t, t m/rad (built on first use: it is slow to build)."""
        return ca.Function("water_beam_stiffness", [self._z, self._p], [-ca.jacobian(self._gen, self._z)])

    @staticmethod
    def parameters(scene, setup, data, shape):
        """The parameter vector of one scene, mesh and start pose (``shape`` from
        :func:`water_beam_shape` of the same ``data``)."""
        mesh, m, ns = data.mesh, data.mesh.m, shape.stations
        body = scene.body
        st = np.asarray(data.stations, dtype=float)
        elem = np.clip(np.searchsorted(mesh.x, st, side="right") - 1, 0, m - 2)
        if not np.array_equal(elem, np.arange(ns) // 3):  # 3 Gauss points inside each element
            raise ValueError("water beam stations: expected three inside each element, in order")
        h = mesh.x[elem + 1] - mesh.x[elem]
        t = (st - mesh.x[elem]) / h
        cols = 2 * elem[:, None] + np.arange(4)[None, :]
        rows = np.repeat(np.arange(ns), 4)
        shape_w, shape_s = np.zeros((ns, 2 * m)), np.zeros((ns, 2 * m))
        shape_w[rows, cols.ravel()] = _rows(hermite, t, h)
        shape_s[rows, cols.ravel()] = _rows(hermite_slope, t, h)
        stiffness = np.zeros((2 * m, 2 * m))
        r, c, v = _global_stiffness(mesh)
        np.add.at(stiffness, (r, c), v)
        tris, kappa, trapped = buoyancy_weights(scene.hull, body.weight, scene.water.density)
        seg, p, q, kap = oriented_segments(tris, kappa, st)
        envelope = scene.hull.triangles
        e_seg, e_p, e_q, _ = oriented_segments(envelope, np.ones(len(envelope)), st)
        if tuple(seg.tolist()) != shape.segments or tuple(e_seg.tolist()) != shape.envelope:
            raise ValueError("water beam parameters: the segments are not the shape's")
        if scene.n:
            level = scene.water.level
            hooks = np.array(scene.crane_values("boom_height", "hydrostatic")) - level
            lengths = np.array(scene.crane_values("rope_length", "hydrostatic"))
            ea = np.array(scene.crane_values("EA", "hydrostatic"))
            points = np.asarray(scene.lug_points(), dtype=float).ravel()
        else:
            hooks = lengths = ea = points = np.zeros(0)
        tw, _, tw_z = _trapped_per_length(scene, st)
        parts = {
            "rot0": np.asarray(data.rot0, dtype=float).ravel(order="F"),
            "contact": np.zeros(3) if data.contact is None else np.asarray(data.contact, dtype=float),
            "ground": [float(data.ground)],
            "gravity": [float(setup.gravity)],
            "weight": [float(body.weight)],
            "cog": np.asarray(body.cog, dtype=float),
            "reference": np.asarray(setup.cog, dtype=float),
            "span": [float(mesh.x[-1] - mesh.x[0])],
            "hooks": hooks,
            "lengths": lengths,
            "ea": ea,
            "points": points,
            "stations": st,
            "weights": np.asarray(data.weights, dtype=float),
            "shape_w": _values(_station_pattern(m), shape_w),
            "shape_s": _values(_station_pattern(m), shape_s),
            "segment_p": p.ravel(order="F"),
            "segment_q": q.ravel(order="F"),
            "kappa": kap,
            "envelope_p": e_p.ravel(order="F"),
            "envelope_q": e_q.ravel(order="F"),
            "trapped_line": np.concatenate([tw, tw_z]),
            "trapped": np.array([[w, *np.asarray(centre, dtype=float)] for w, centre in trapped]).ravel(),
            "loads": np.asarray(mesh.weight, dtype=float),
            "stiffness": _values(_stiffness_pattern(m), stiffness),
        }
        out = [np.asarray(parts[name], dtype=float).ravel() for name, _ in shape.blocks()]
        for (name, size), part in zip(shape.blocks(), out):
            if part.size != size:
                raise ValueError(f"water beam parameter {name}: {part.size} values, expected {size}")
        return np.concatenate(out)


def water_beam_shape(scene, data):
    """The :class:`WaterBeamShape` of one scene, mesh and start pose."""
    tris, kappa, trapped = buoyancy_weights(scene.hull, scene.body.weight, scene.water.density)
    seg = oriented_segments(tris, kappa, data.stations)[0]
    envelope = scene.hull.triangles
    e_seg = oriented_segments(envelope, np.ones(len(envelope)), data.stations)[0]
    return WaterBeamShape(
        n=scene.n,
        m=data.mesh.m,
        grounded=bool(data.grounded),
        gauge=data.gauge,
        lug_nodes=tuple(int(k) for k in data.mesh.lug_nodes),
        contact_node=node_of(data.mesh.x, data.contact[0]) if data.grounded else -1,
        segments=tuple(seg.tolist()),
        envelope=tuple(e_seg.tolist()),
        trapped=len(trapped),
    )


#: Built models kept (each a few MB of casadi expressions; a study's sweep or a lift's steps
#: reuse one or two).
MODELS_KEPT = 8


@lru_cache(maxsize=MODELS_KEPT)
def water_beam_model(shape):
    """The cached :class:`WaterBeamModel` of a :class:`WaterBeamShape` (built once per
    discretisation: building it and its stiffness took ~1.8 s a scene)."""
    return WaterBeamModel(shape)


def stiffness(model, z, p):
    """Tangent stiffness at z for parameters p: minus the Jacobian of the generalised forces
    (pose: net force and moments; beam: loads - K d), in t/m, t, t m/rad."""
    return np.asarray(model.stiffness(ca.DM(z), ca.DM(p)))


def _rows(shape, t, h):
    """Shape-function rows (Hermite values or slopes) at local t of elements of length h."""
    return np.stack([shape(tk, hk) for tk, hk in zip(t, h)]).ravel()


def _global_stiffness(mesh):
    """Triplets of the assembled bending stiffness (2 m x 2 m)."""
    rows, cols, vals = [], [], []
    for e, k_e in enumerate(mesh.bending):
        index = 2 * e + np.arange(4)
        r, c = np.meshgrid(index, index, indexing="ij")
        rows.append(r.ravel())
        cols.append(c.ravel())
        vals.append(k_e.ravel())
    return np.concatenate(rows), np.concatenate(cols), np.concatenate(vals)


def _clipped(p, q, kappa, uy, uz, c0):
    """kappa x (area, first moment about y = 0, about z = 0) each wet segment adds to its
    section, the reference point on the section's waterline (Green's theorem: the waterline's
    closing segment adds nothing). Heights h = uy y + uz z + c0 (< 0: wet). p, q: (k, 2)
    segment ends (y, z) and kappa (k,), casadi."""
    py, pz, qy, qz = p[:, 0], p[:, 1], q[:, 0], q[:, 1]
    hp = uy * py + uz * pz + c0
    hq = uy * qy + uz * qz + c0
    wet_p, wet_q = hp < 0, hq < 0
    crossing = ca.logic_xor(wet_p, wet_q) if hasattr(ca, "logic_xor") else (wet_p + wet_q == 1)
    denominator = ca.if_else(crossing, hp - hq, 1)
    t = ca.if_else(crossing, hp / denominator, 0)
    cy, cz = py + t * (qy - py), pz + t * (qz - pz)
    move_p = ca.logic_and(crossing, ca.logic_not(wet_p))
    move_q = ca.logic_and(crossing, wet_p)
    ay, az = ca.if_else(move_p, cy, py), ca.if_else(move_p, cz, pz)
    by, bz = ca.if_else(move_q, cy, qy), ca.if_else(move_q, cz, qz)
    wet = ca.logic_or(wet_p, wet_q)
    across = uy**2 + uz**2
    y0, z0 = -c0 * uy / across, -c0 * uz / across
    area = 0.5 * ((ay - y0) * (bz - z0) - (az - z0) * (by - y0))
    area = ca.if_else(wet, area, 0) * kappa
    return area, area * (y0 + ay + by) / 3.0, area * (z0 + az + bz) / 3.0


def _trapped_per_length(scene, stations):
    """Water trapped in compartments per length at stations, and its first moments about body
    y = 0 and z = 0 (uniform over each compartment's length, at its centre)  [t/m, t m/m]."""
    tw, tw_y, tw_z = np.zeros(len(stations)), np.zeros(len(stations)), np.zeros(len(stations))
    for comp in scene.hull.compartments:
        if comp.contents != "water":
            continue
        lo, hi = np.asarray(comp.box["min"], dtype=float), np.asarray(comp.box["max"], dtype=float)
        inside = (stations > lo[0]) & (stations < hi[0])
        per_length = scene.water.density * (hi[1] - lo[1]) * (hi[2] - lo[2])
        tw[inside] += per_length
        tw_y[inside] += per_length * 0.5 * (lo[1] + hi[1])
        tw_z[inside] += per_length * 0.5 * (lo[2] + hi[2])
    return tw, tw_y, tw_z


# -- solving ---------------------------------------------------------------------------------
@dataclass(frozen=True)
class WaterBeamState:
    """A solved flexible hull in water (arrays; :func:`solve_hull_in_water` builds the result).

    Parameters
    ----------
    rotation : numpy.ndarray, shape (3, 3)
        The chord's attitude (through the beam's ends).
    zo : float  [m]
        Height of the body-frame origin over the water plane.
    beam : numpy.ndarray  [m, rad]
        Free beam unknowns (:meth:`.beam.GirderMesh.full`).
    tensions, stretch : numpy.ndarray  [t, m]
    reaction : float  [t]
        Ground reaction at the contact (0 when not grounded).
    buoyancy : float  [t]
        Total buoyancy of the deflected hull.
    immersed_volume : float  [m3]
        The deflected hull envelope's volume below the water plane (intact: buoyancy / density).
    first_buoyancy : numpy.ndarray, shape (3,)  [t m]
        Its first moment about the body origin (world axes, undeformed geometry).
    residual : float  [-]
        Largest scaled residual (forces / W, moments / (W L)), the gauge's dropped rows included.
    stable : bool
    buoyancy_curve : tuple of Piecewise
        Buoyancy per length [t/m] and its first moment about body z = 0 [t m/m] of the
        deflected hull: on each element the quadratic through its Gauss values (its integral
        and first moment are the quadrature the statics used, so the girder's curves close).
    mesh : GirderMesh
    iterations : int
    remeshed : int
        Mesh rebuilds to put the section breaks on nodes.
    quadrature_error : tuple of 2 float  [t, t m]
        The Gauss quadrature's buoyancy less the clipped hull's exact one at the solved chord
        pose, and the largest error of its first moments (nan when the solve diverged).
    quadrature_exact : bool
        Both within 1e-12 W (W L): the section breaks sit on beam nodes.
    gauge : str
        How the beam was held (:data:`GAUGES`); ``beam`` is that gauge's free unknowns.
    """

    rotation: np.ndarray
    zo: float
    beam: np.ndarray
    tensions: np.ndarray
    stretch: np.ndarray
    reaction: float
    buoyancy: float
    immersed_volume: float
    first_buoyancy: np.ndarray
    residual: float
    stable: bool
    buoyancy_curve: tuple
    mesh: object
    iterations: int
    remeshed: int
    quadrature_error: tuple = (0.0, 0.0)
    quadrature_exact: bool = True
    gauge: str = "chord"

    @property
    def accepted(self):
        """Residual within the tolerance, stable, and the buoyancy quadrature exact."""
        return bool(self.residual <= RESIDUAL_TOL and self.stable and self.quadrature_exact)

    def bending(self):
        """Node deflections w and slopes w' (the gauge's held entries put back)  [m, rad]."""
        return full_bending(self.mesh.m, self.beam, self.gauge)

    def refusal(self, where):
        """The one-line reason this state is not accepted (None when it is)."""
        if self.accepted:
            return None
        if not self.quadrature_exact and math.isfinite(self.residual):
            buoyancy, moment = self.quadrature_error
            why = (
                f"the buoyancy quadrature is not the hull's exact buoyancy after {self.remeshed + 1} "
                f"meshes (error {buoyancy:.3g} t, first moment {moment:.3g} t m): the section "
                "breaks did not settle on beam nodes"
            )
        elif self.residual > RESIDUAL_TOL:
            why = f"residual {self.residual:.3g}"
        else:
            why = "unstable (the stiffness is not positive definite)"
        return (
            f"hydrostatic, flexible hull {where}: no accepted equilibrium ({why}); "
            'expected a converged solve, or analysis.hull = "rigid"'
        )


def gauss_stations(x):
    """Three Gauss points per element of nodes x, and their weights  [m, m]."""
    t, weights = _GAUSS3
    h = np.diff(x)
    return (x[:-1, None] + h[:, None] * t[None, :]).ravel(), (h[:, None] * weights[None, :]).ravel()


def check_span(scene):
    """Refuse a hull mesh reaching past the weight curve (the beam's span) in one line."""
    x, _ = scene.body.weight_curve_arrays
    lo, hi = float(scene.hull.vertices[:, 0].min()), float(scene.hull.vertices[:, 0].max())
    tol = 1e-9 * (x[-1] - x[0])
    if lo < x[0] - tol or hi > x[-1] + tol:
        raise InvalidScene(
            f"hull: x from {lo:g} to {hi:g} m reaches past body.weight_curve (from {x[0]:g} to "
            f"{x[-1]:g} m); expected the weight curve to span the hull for a flexible hull in water"
        )


def water_beam_state(scene, rotation, zo, grounded, elements=ELEMENTS, gauge="chord"):
    """Solve the flexible hull in water from a start pose (the rigid hull's).

    Parameters
    ----------
    scene : Scene
        With ``hull``, ``water``, ``girder`` and ``body.weight_curve``.
    rotation : numpy.ndarray, shape (3, 3)
        Start attitude.
    zo : float  [m]
        Start height of the body origin over the water plane.
    grounded : bool
        Resting on the ground contact (it must carry load), or hanging / afloat.
    elements : int
    gauge : {"chord", "stern"}
        How the beam is held to the pose (:data:`GAUGES`); the solve uses ``"chord"``, the
        other measures the gauge dependence.

    Returns
    -------
    WaterBeamState
        Not accepted (:attr:`WaterBeamState.accepted`) when the quadrature is still not exact
        after :data:`REMESH` meshes: the caller refuses it (:meth:`WaterBeamState.refusal`).
    """

    check_span(scene)
    setup = WaterSetup(scene)
    tris, kappa, _ = buoyancy_weights(scene.hull, scene.body.weight, scene.water.density)
    contact = np.asarray(scene.ground.contact, dtype=float) if grounded else None
    rotation = np.asarray(rotation, dtype=float)
    for remeshed in range(REMESH):  # noqa: B007 (reported)
        extra = list(section_breaks(tris, rotation[2], zo)) + ([contact[0]] if grounded else [])
        mesh = girder_mesh(scene, elements, extra=extra)
        stations, weights = gauss_stations(mesh.x)
        data = WaterBeamData(
            mesh=mesh,
            rot0=rotation,
            grounded=grounded,
            contact=contact,
            ground=float(setup.ground_height),
            stations=stations,
            weights=weights,
            gauge=gauge,
        )
        shape = water_beam_shape(scene, data)
        model = water_beam_model(shape)
        params = WaterBeamModel.parameters(scene, setup, data, shape)
        z0 = np.zeros(model.npose + 2 * mesh.m - 2)
        if not grounded:
            z0[0] = zo
        with model.lock:  # the iteration count is the last call's
            z = np.asarray(model.solve(ca.DM(z0), ca.DM(params))).ravel()
            iterations = int(model.solve.stats().get("iter_count", -1))
        out = {k: np.asarray(v) for k, v in model.evaluate(z=ca.DM(z), p=ca.DM(params)).items()}
        new_rotation = tilted_rotation(out["tilts"].ravel(), rotation)
        new_zo = float(out["zo"].ravel()[0])
        rotation, zo = new_rotation, new_zo
        if not np.all(np.isfinite(z)):
            error, exact = (math.nan, math.nan), False
            break
        error = _quadrature_error(setup, tris, kappa, rotation, zo, stations, weights)
        exact = bool(
            abs(error[0]) <= 1e-12 * setup.gravity
            and abs(error[1]) <= 1e-12 * setup.gravity * scene.hull.size
        )
        if exact:
            break
    residual = float(max(np.max(np.abs(out["residual"])), np.max(np.abs(out["dropped"]))))
    if not math.isfinite(residual):
        residual = math.inf
    npose = model.npose
    free = z[npose:]
    return WaterBeamState(
        rotation=rotation,
        zo=zo,
        beam=free,
        tensions=out["tension"].ravel(),
        stretch=out["stretch"].ravel(),
        reaction=float(out["reaction"].ravel()[0]),
        buoyancy=float(out["buoyancy"].ravel()[0]),
        immersed_volume=float(out["immersed"].ravel()[0]),
        first_buoyancy=out["first_buoyancy"].ravel(),
        residual=residual,
        stable=schur_positive_definite(stiffness(model, z, params), npose),
        buoyancy_curve=_curves(mesh.x, out["b"].ravel(), out["s_z"].ravel()),
        mesh=mesh,
        iterations=iterations,
        remeshed=remeshed,
        quadrature_error=error,
        quadrature_exact=exact,
        gauge=gauge,
    )


def deflected_height(scene, state, points):
    """Heights over the water plane of body points of a solved flexible hull: the chord's pose
    plus the beam's deflection at each point's x (its vertical part, and the section's turn w'
    about the CG's height), as the model moves them  [m].

    Parameters
    ----------
    scene : Scene
    state : WaterBeamState
    points : array_like, shape (k, 3)  [m]
        Body frame.
    """
    points = np.atleast_2d(np.asarray(points, dtype=float))
    w, slope = state.bending()
    deflection, turn = beam_at(state.mesh, w, slope, points[:, 0])
    up = state.rotation[2]
    return (
        points @ up + state.zo + up[2] * deflection - up[0] * (points[:, 2] - float(scene.body.cog[2])) * turn
    )


def contact_height(scene, state):
    """Height over the water plane of the ground contact of a solved flexible hull  [m]
    (:func:`deflected_height`)."""
    return float(deflected_height(scene, state, [scene.ground.contact])[0])


def deflected_hull_heights(scene, state):
    """Lowest and highest point of the deflected hull envelope over the water plane  [m].

    Over the envelope's vertices and its sections at the Gauss stations the buoyancy is
    integrated on (the same section outlines, moved by the beam as the buoyancy's are): what
    :func:`.water.equilibrium.water_state` classifies, for the hull that carries the buoyancy
    rather than its chord."""
    envelope = scene.hull.triangles
    stations, _ = gauss_stations(state.mesh.x)
    seg, p, q, _ = oriented_segments(envelope, np.ones(len(envelope)), stations)
    section = np.concatenate([p, q])
    points = np.column_stack([np.concatenate([stations[seg], stations[seg]]), section])
    heights = deflected_height(scene, state, np.concatenate([scene.hull.vertices, points]))
    return float(heights.min()), float(heights.max())


def _quadrature_error(setup, tris, kappa, rotation, zo, stations, weights):
    """The Gauss quadrature of the sections (:func:`.sections.immersed_sections`) less the
    clipped hull's exact buoyancy [t] and the largest error of its first moments [t m] at this
    chord pose: a kink of the buoyancy per length inside an element leaves one."""

    up = rotation[2]
    per_length, moment = immersed_sections(tris, kappa, up, zo, stations)
    quadrature = np.array([weights @ per_length, weights @ (stations * per_length), weights @ moment])
    p = setup.params(rotation)
    out = setup.model.free.call({"x": ca.DM([zo, 0.0, 0.0]), "p": ca.DM(p)})
    exact_b = float(np.asarray(out["buoyancy"]).ravel()[0])
    world = np.asarray(out["moment"]).ravel()[:3]  # about o, world axes
    body = rotation.T @ (world - [0.0, 0.0, zo * exact_b])  # about the body origin, body axes
    exact = np.array([exact_b, body[0], body[2]])
    return float(quadrature[0] - exact[0]), float(np.max(np.abs(quadrature[1:] - exact[1:])))


def _curves(x, b, s_z):
    """Per element, the quadratic through the three Gauss values (ascending in u = x - x_k)."""
    t = _GAUSS3[0]
    inverse = np.linalg.inv(t[:, None] ** np.arange(3))
    h = np.diff(x)[:, None]
    scale = h ** -np.arange(3)
    return (
        Piecewise(x, (b.reshape(-1, 3) @ inverse.T) * scale),
        Piecewise(x, (s_z.reshape(-1, 3) @ inverse.T) * scale),
    )


# -- the solve: the least hull the scene needs -----------------------------------------------
def gauge_note(scene, state, forces):
    """The gauge's limit, said when it matters (else ""): the statics are taken on the chord's
    undeformed geometry, so the forces hold only to about :data:`GAUGE_COEFFICIENT` x W x
    (deflection / length); said when that reaches :data:`GAUGE_NOTE` of the smallest positive
    force the 1 % rule compares (tensions, ground reaction).

    Parameters
    ----------
    scene : Scene
    state : WaterBeamState
    forces : sequence of float  [t]
    """
    w, _ = state.bending()
    span = float(state.mesh.x[-1] - state.mesh.x[0])
    ratio = float(np.max(np.abs(w))) / span
    spread = GAUGE_COEFFICIENT * float(scene.body.weight) * ratio
    positive = [f for f in forces if f > 1e-9 * scene.body.weight]
    if not positive or spread < GAUGE_NOTE * min(positive):
        return ""
    return (
        f"equilibrium on the chord's undeformed geometry: with the deflection {ratio:.2g} x the "
        f"length, where the beam is held moves the forces by about {spread:.3g} t "
        f"({100 * spread / min(positive):.2g} % of the smallest, {min(positive):.4g} t; "
        f"measured {GAUGE_COEFFICIENT:g} W x deflection / length, studies/flexible_ground.py)"
    )


def _held_rigid(scene, method):
    """Why this water scene's hull is held rigid, or None when it can be flexible."""
    if method != "newton":
        return f"method {method!r} (the paper's iteration) holds the hull rigid"
    if scene.ground is not None and scene.ground.breakout is not None and scene.n:
        return "the breakout model (ground.breakout) holds the hull rigid"
    return None


def solve_hull_in_water(scene, method="newton", hull=None):
    """The ``hydrostatic`` model of a scene with a hull stiffness: the least hull it needs.

    The hull is solved rigid (:func:`liftplan.model.water.solve_hydrostatic`), then flexible
    from the rigid pose, grounded if the rigid hull is (:func:`water_beam_state`). The flexible
    answer is kept when it changes a tension or the ground reaction by more than
    :data:`~.flexible.TENSION_CHANGE`, or when ``hull`` (default ``scene.analysis.hull``) is
    ``"flexible"``; ``"rigid"`` skips the flexible solve.

    Returns
    -------
    Equilibrium
        With ``flexible_hull``.

    Raises
    ------
    InvalidScene
        ``analysis.hull = "flexible"`` on a combination held rigid (``paper-newton``, breakout).
    EquilibriumNotFound
        Either solve was not accepted, with the reason.
    """

    hull = hull or scene.analysis.hull
    rigid_scene = dataclasses.replace(
        scene, girder=None, analysis=dataclasses.replace(scene.analysis, hull="auto")
    )
    rigid = dataclasses.replace(solve_hydrostatic(rigid_scene, method=method), frame=scene.frame)
    held = _held_rigid(scene, method)
    if held is not None:
        if hull == "flexible":
            raise InvalidScene(
                f'analysis.hull = "flexible": {held}; expected method "newton" without '
                "ground.breakout for a flexible hull in water"
            )
        return dataclasses.replace(rigid, flexible_hull=RigidHullNote(held))
    if hull == "rigid":
        return dataclasses.replace(rigid, flexible_hull=RigidHullNote('analysis.hull = "rigid"'))
    grounded = rigid.afloat.state == "grounded"
    level = scene.water.level
    pose = rigid.pose
    begin = time.perf_counter()
    state = water_beam_state(
        scene, rotation_matrix(pose.heel, pose.trim, pose.yaw), pose.lift_height - level, grounded
    )
    sank = False
    if not grounded and scene.ground is not None and state.accepted:
        # the rigid hull floats or hangs clear of its contact; the bending one may reach it
        below = WaterSetup(scene).ground_height - contact_height(scene, state)
        if below > 1e-6 * scene.hull.size:
            grounded = sank = True
            state = water_beam_state(scene, state.rotation, state.zo, grounded)
    seconds = time.perf_counter() - begin
    where = "grounded" if grounded else "in water"
    if not state.accepted:
        raise EquilibriumNotFound(state.refusal(where))
    if sank and not state.reaction > 0.0:
        raise EquilibriumNotFound(
            f"hydrostatic, flexible hull: afloat the bending hull reaches below its ground contact, "
            f"grounded it lifts off it (reaction {state.reaction:.4g} t); no consistent contact found, "
            'expected analysis.hull = "rigid" or a stiffer hull.EI'
        )
    if grounded and not state.reaction > 0.0:
        raise EquilibriumNotFound(
            f"hydrostatic, flexible hull: the bending hull lifts off its ground contact (reaction "
            f'{state.reaction:.4g} t); expected a contact that carries load, or analysis.hull = "rigid"'
        )
    rigid_t = np.array([rigid.tensions[name] for name in scene.lug_names])
    weight = scene.body.weight
    change = tension_change(rigid_t, state.tensions, weight)
    ground = None
    if grounded:
        ground = (float(rigid.afloat.ground_reaction), state.reaction)
        change = np.append(change, tension_change([ground[0]], [ground[1]], weight))
    used = "flexible" if hull == "flexible" or (change.size and np.max(change) > TENSION_CHANGE) else "rigid"
    notes = (
        ["in water the hull bends but does not twist (hull.GJ unused)"] if scene.girder.GJ is not None else []
    )
    gauge = gauge_note(scene, state, list(state.tensions) + ([] if ground is None else [ground[1]]))
    if gauge:
        notes.append(gauge)
    note = "; ".join(notes)
    report = hull_report(
        scene,
        state.mesh,
        state,
        rigid_t,
        used,
        forced=hull == "flexible",
        ground=ground,
        buoyancy=state.buoyancy_curve,
        note=note,
    )
    if used == "rigid":
        return dataclasses.replace(rigid, flexible_hull=report)
    setup = WaterSetup(scene)
    info = SolverInfo("newton (flexible hull)", True, state.iterations, seconds)
    skeleton = equilibrium_result(setup, state.zo, state.rotation, 0.0, info, grounded=grounded)
    # the skeleton is the rigid hull at the chord's pose: put in the flexible forces
    turn = rotation_matrix(skeleton.pose.heel, skeleton.pose.trim, skeleton.pose.yaw) @ state.rotation.T
    af = skeleton.afloat
    centre = None
    if state.buoyancy > 0.0:  # the skeleton's G is placed right: the buoyancy's centre from it
        offset = state.first_buoyancy / state.buoyancy - state.rotation @ np.asarray(scene.body.cog)
        centre = tuple(float(v) for v in np.asarray(af.centre_of_gravity) + turn @ offset)
    bottom, top = deflected_hull_heights(scene, state)  # the bending hull's, not the chord's
    reaction = state.reaction if grounded else (0.0 if scene.ground is not None else None)
    friction = scene.ground.friction if scene.ground is not None else None
    afloat = dataclasses.replace(
        af,
        buoyancy=state.buoyancy,
        displaced_volume=state.buoyancy / scene.water.density,
        immersed_volume=state.immersed_volume,
        ground_reaction=reaction,
        centre_of_buoyancy=centre,
        freeing_force=friction * reaction if friction is not None and reaction is not None else None,
        state=water_state(grounded, bottom, top, float(state.tensions.sum()), setup.gravity),
    )
    names = scene.lug_names
    return dataclasses.replace(
        skeleton,
        tensions=dict(zip(names, state.tensions.tolist())),
        afloat=afloat,
        slack=tuple(name for name, s in zip(names, state.stretch) if s <= 0.0),
        residual=state.residual * setup.gravity,
        flexible_hull=report,
        frame=scene.frame,
    )
