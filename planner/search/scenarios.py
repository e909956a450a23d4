"""Tensions of a lug set across the tolerance box, as affine functions of the level preload.

Formulation (the planner's physics; README "Planning")
-----------------------------------------------------
With n >= 4 cranes the differential hoist sets the n - 3 redundant tensions: any statically
admissible set T* at the level attitude can be dialled in, through boom heights

    H_i = a + z_i + l0_i + T*_i / k_i,        k_i = EA_i / l0_i,

(a the lift height, z_i the lug's height in the body frame). A heel or trim deviation then
comes from hook motions that move the level hook pattern as a rigid body,
dH_i = c0 + c1 x_i + c2 y_i: they leave the twist (the preload) alone. At any pose the
statics fix c (a 3x3 linear solve: ``held`` in :class:`liftplan.model.statics.model.RopeModel`),
so with every rope taut the tensions at scenario k (attitude, CG position) are exactly

    T_k = P_k T* + q_k.

The worst spread over a set of scenarios is then a convex (piecewise-linear) function of
T*, and choosing T* is a linear program (:class:`liftplan.planner.search.bounds.PreloadMinimax`).
With n = 3 there is no preload to choose (P_k = 0).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from liftplan.model.frames import rotation_matrix
from liftplan.model.statics.model import BLOCK, hinged_model, rope_model
from liftplan.planner.problem.fleet import rule_limits
from liftplan.planner.problem.vessels import series_fleet, uses_vessels


def run_block(block, n, attitudes, params):
    """Evaluate ``held`` over many columns.

    Parameters
    ----------
    block : FastCall
        ``held_block`` (params shared) or ``held_columns`` (params per column).
    n : int
    attitudes : numpy.ndarray, shape (m, 3)
        Columns (lift a [m], heel [rad], trim [rad]).
    params : numpy.ndarray, shape (size,) or (m, size)

    Returns
    -------
    tensions : (m, n)  [t]
    hook_shift : (m, n)  [m]
    gain : (m, n, n)  dT/dH  [t/m]
    """
    count = attitudes.shape[0]
    shared = params.ndim == 1
    tensions = np.empty((count, n))
    shift = np.empty((count, n))
    gain = np.empty((count, n, n))
    for start in range(0, count, BLOCK):
        stop = min(start + BLOCK, count)
        size = stop - start
        x = np.zeros((BLOCK, 3))
        x[:size] = attitudes[start:stop]
        x[size:, 0] = attitudes[start, 0]  # padding: any valid pose
        if shared:
            p = params
        else:
            p = np.empty((BLOCK, params.shape[1]))
            p[:size] = params[start:stop]
            p[size:] = params[start]
            p = p.ravel()
        t_out, d_out, j_out = block(x.ravel(), p)
        tensions[start:stop] = t_out.reshape(BLOCK, n)[:size]
        shift[start:stop] = d_out.reshape(BLOCK, n)[:size]
        # dT/dH of column b is the b-th n x n block of an n x (n BLOCK) matrix, column-major
        gain[start:stop] = j_out.reshape(BLOCK, n, n)[:size].transpose(0, 2, 1)
    return tensions, shift, gain


def held_model(problem, n):
    """The rope model the problem's lift points need: :func:`~liftplan.model.statics.model.rope_model`
    for body-fixed candidates, :func:`~liftplan.model.statics.model.hinged_model` when the problem
    carries hinges (``PlanProblem.hinges``: slings hinged about a lug pair)."""
    return rope_model(n) if problem.hinge_rows is None else hinged_model(n)


def set_hinges(problem, sets):
    """Hinge rows (..., n, 8) of the candidates in ``sets`` (..., n), or None (body-fixed)."""
    rows = problem.hinge_rows
    return None if rows is None else rows[np.asarray(sets, dtype=np.int64)]


def level_bar_moment(problem, points, hinges):
    """Level-pose bar-weight moment, world plan (..., 2) [t m]: sum_i w_i (P_i - bar_i)_plan
    (zero without hinges or bars); see :func:`~liftplan.model.statics.model.hinged_points`.

    points : (..., n, 3) lift points at level (the hooks) [m]; hinges : (..., n, 8) or None.
    """
    points = np.asarray(points, dtype=float)
    if hinges is None:
        return np.zeros((*points.shape[:-2], 2))
    hinges = np.asarray(hinges, dtype=float)
    centre = 0.5 * (hinges[..., 0:3] + hinges[..., 3:6])
    centre[..., 2] += hinges[..., 6]
    lever = ((points - centre) * hinges[..., 7:8]).sum(axis=-2)
    return lever[..., :2] @ rotation_matrix(0.0, 0.0, problem.yaw)[:2, :2].T


def pack(problem, points, cog, boom, weight=None, rope_length=None, EA=None, hinges=None):
    """Parameter vectors (:class:`~liftplan.model.statics.model.Layout`) of lug sets.

    Parameters
    ----------
    problem : PlanProblem
    points : (..., n, 3)  [m]   lug positions, body frame (one set, or a batch of sets)
    cog : (..., 3)  [m]
    boom : (..., n)  [m]   boom-tip heights H
    weight : (...) [t], optional   the body weight (default the problem's)
    rope_length, EA : (..., n)  [m, t], optional
        Each rope's l0 and EA (default the first n cranes of the fleet, in fleet order).
    hinges : (..., n, 8), optional
        Hinge rows (:class:`~liftplan.model.statics.model.HingedLayout`; :func:`set_hinges`),
        appended for :func:`~liftplan.model.statics.model.hinged_model`.

    Returns
    -------
    numpy.ndarray, shape (..., 6 n + 6), or (..., 14 n + 6) with ``hinges``
    """
    weight = np.asarray(problem.body.weight if weight is None else weight, dtype=float)
    points, cog, boom = (np.asarray(v, dtype=float) for v in (points, cog, boom))
    n = points.shape[-2]
    shapes = [points.shape[:-2], cog.shape[:-1], boom.shape[:-1], weight.shape]
    if hinges is not None:
        hinges = np.asarray(hinges, dtype=float)
        shapes.append(hinges.shape[:-2])
    batch = np.broadcast_shapes(*shapes)
    points = np.broadcast_to(points, (*batch, n, 3))
    if rope_length is None:
        rope_length = [c.rope_length for c in problem.fleet[:n]]
    if EA is None:
        EA = [c.EA for c in problem.fleet[:n]]
    plan = points[..., :2]
    dx = plan[..., :, None, 0] - plan[..., None, :, 0]
    dy = plan[..., :, None, 1] - plan[..., None, :, 1]
    diameter = np.sqrt((dx * dx + dy * dy).reshape(*plan.shape[:-2], -1).max(axis=-1))

    def column(value, width):
        value = np.asarray(value, dtype=float)
        return np.broadcast_to(value[..., None] if width == 1 else value, (*batch, width))

    parts = [
        column(math.radians(problem.yaw), 1),
        points.reshape(*batch, 3 * n),
        column(cog, 3),
        column(weight, 1),
        column(boom, n),
        column(rope_length, n),
        column(EA, n),
        column(diameter, 1),
    ]
    if hinges is not None:
        parts.append(np.broadcast_to(hinges, (*batch, n, 8)).reshape(*batch, 8 * n))
    return np.concatenate(parts, axis=-1)


def box_attitudes(problem, heel_count, trim_count):
    """A heel x trim grid over the tolerance box, shape (m, 2)  [deg]."""
    heel = np.linspace(-problem.heel_tolerance, problem.heel_tolerance, heel_count)
    trim = np.linspace(-problem.trim_tolerance, problem.trim_tolerance, trim_count)
    grid = np.array(np.meshgrid(heel, trim, indexing="ij")).reshape(2, -1).T
    return np.unique(grid, axis=0) + 0.0  # a zero tolerance collapses the grid; no -0.0


@dataclass(frozen=True)
class Scenario:
    """One state the plan must hold: an attitude and a CG position.

    Parameters
    ----------
    heel, trim : float  [deg]
    cog_offset : tuple of 3 float  [m]   from the nominal CG, body frame
    """

    heel: float
    trim: float
    cog_offset: tuple[float, float, float] = (0.0, 0.0, 0.0)


def set_lugset(problem, indices, cranes=None):
    """A :class:`LugSet` with each floating crane in series with its vessel at the lug it takes
    (:func:`~liftplan.planner.problem.vessels.series_fleet`), whatever stiffness the problem's
    fleet stands at; the problem's own cranes where none floats."""
    if not uses_vessels(problem):
        return LugSet(problem, indices, cranes)
    indices = tuple(int(i) for i in indices)
    cranes = tuple(range(len(indices))) if cranes is None else tuple(int(j) for j in cranes)
    return LugSet(problem, indices, cranes, fleet=series_fleet(problem, indices, cranes))


class LugSet:
    """One choice of lugs and of the crane on each: level statics and tensions across scenarios.

    Parameters
    ----------
    problem : PlanProblem
    indices : sequence of int
        Candidate indices, in candidate order.
    cranes : sequence of int, optional
        Fleet index of the crane on each lug (default: crane k on the k-th lug, which is any
        assignment for a fleet of equal cranes).
    fleet : tuple of FleetCrane, optional
        The cranes to use instead of ``problem.fleet`` (fleet order; the same positions and
        charts): each floating crane in series with its vessel at the lug it takes
        (:func:`~liftplan.planner.problem.vessels.series_fleet`).
    """

    def __init__(self, problem, indices, cranes=None, fleet=None):
        self.problem = problem
        self.indices = tuple(int(i) for i in indices)
        self.n = len(self.indices)
        self.cranes = tuple(range(self.n)) if cranes is None else tuple(int(j) for j in cranes)
        self.points = problem.points[list(self.indices)]
        self.names = tuple(problem.names[i] for i in self.indices)
        fleet = [(problem.fleet if fleet is None else fleet)[j] for j in self.cranes]
        self.crane_names = tuple(c.name for c in fleet)
        self.rope_length = np.array([c.rope_length for c in fleet])
        self.EA = np.array([c.EA for c in fleet])
        self.stiffness = self.EA / self.rope_length
        self.boom_range = (np.array([c.boom_min for c in fleet]), np.array([c.boom_max for c in fleet]))
        radius, swl = problem.reach
        self.radius = radius[list(self.indices), list(self.cranes)]
        #: SWL of each crane at its radius [t] (NaN: the crane cannot reach its lug)
        self.swl = swl[list(self.indices), list(self.cranes)]
        #: each hook's height tolerance [m] (the crane's, else the plan's)
        self.hook_tolerance = np.array(
            [problem.hook_tolerance if c.hook_tolerance is None else c.hook_tolerance for c in fleet]
        )
        #: tension limits from the rules' chain: anywhere in the box, and at level [t]
        self.limit, self.share_limit = rule_limits(problem, self.swl, self.cranes)
        #: what the objective's spread is taken of: s_i T_i
        self.scale = problem.goal.scale(self.swl)
        # boom heights with every rope just unstretched at the level pose
        self.boom_zero = problem.lift_height + self.points[:, 2] + self.rope_length
        #: hinge rows of the lift points (None: body-fixed), see ``PlanProblem.hinges``
        self.hinges = set_hinges(problem, self.indices)
        self._model = held_model(problem, self.n)

    @cached_property
    def level_statics(self):
        """(A0, b0): level statics A0 T* = b0, rows (1, x, y)  [-, m], W (1, x_c, y_c)."""
        return self.statics_at(Scenario(0.0, 0.0))

    def statics_at(self, scenario):
        """(A, b) of the statics at a scenario's attitude and CG: A T = b  [-, m; t, t m]."""
        problem = self.problem
        if self.hinges is not None:  # hinged lift points: posed by the model itself
            x, _ = self._columns([scenario])
            p = pack(
                problem,
                self.points,
                np.array(problem.body.cog) + scenario.cog_offset,
                self.boom_zero,
                rope_length=self.rope_length,
                EA=self.EA,
                hinges=self.hinges,
            )
            a_flat, b_vec, _, _ = self._model.statics_fast(x[0], p)
            return a_flat.reshape(self.n, 3).T, b_vec
        rot = rotation_matrix(scenario.heel, scenario.trim, problem.yaw)
        plan = (self.points @ rot.T)[:, :2]
        cog = rot @ (np.array(problem.body.cog) + np.array(scenario.cog_offset))
        a_mat = np.vstack([np.ones(self.n), plan.T])
        return a_mat, problem.body.weight * np.array([1.0, cog[0], cog[1]])

    def preload_range(self):
        """Bounds on T* from the boom-height range and the crane code's margin  [t]."""
        low = self.stiffness * (self.boom_range[0] - self.boom_zero)
        high = np.minimum(self.stiffness * (self.boom_range[1] - self.boom_zero), self.share_limit)
        return low, high

    def boom_heights(self, preload):
        """Boom-tip heights that hold T* at the level pose  [m]."""
        return self.boom_zero + np.asarray(preload) / self.stiffness

    def _columns(self, scenarios):
        attitudes = np.array([[s.heel, s.trim] for s in scenarios], dtype=float)
        x = np.column_stack(
            [
                np.full(len(scenarios), self.problem.lift_height),
                np.radians(attitudes[:, 0]),
                np.radians(attitudes[:, 1]),
            ]
        )
        offsets = np.array([s.cog_offset for s in scenarios], dtype=float)
        return x, offsets

    def _evaluate(self, scenarios, boom):
        """``held`` at each scenario with the given boom heights, grouped by CG offset."""
        x, offsets = self._columns(scenarios)
        count = len(scenarios)
        tensions = np.empty((count, self.n))
        shift = np.empty((count, self.n))
        gain = np.empty((count, self.n, self.n))
        cog = np.array(self.problem.body.cog)
        for offset in np.unique(offsets, axis=0):
            rows = np.all(offsets == offset, axis=1)
            p = pack(
                self.problem,
                self.points,
                cog + offset,
                boom,
                rope_length=self.rope_length,
                EA=self.EA,
                hinges=self.hinges,
            )
            t, d, g = run_block(self._model.held_block, self.n, x[rows], p)
            tensions[rows], shift[rows], gain[rows] = t, d, g
        return tensions, shift, gain

    def affine(self, scenarios):
        """P_k, q_k with T_k = P_k T* + q_k.

        Returns
        -------
        gains : (m, n, n)  [-]
        offsets : (m, n)  [t]
        """
        tensions, _, gain = self._evaluate(scenarios, self.boom_zero)
        return gain / self.stiffness[None, None, :], tensions

    def tensions(self, preload, scenarios):
        """Tensions at each scenario with preload T* held, shape (m, n)  [t].

        Exact while every rope is taut (a negative value means that rope went slack).
        """
        return self._evaluate(scenarios, self.boom_heights(preload))[0]

    def tensions_and_gain(self, preload, scenarios):
        """Tensions (m, n) [t] and dT/dH (m, n, n) [t/m] at each scenario, preload held: a
        hook-height error e at a scenario's attitude changes the tensions by dT/dH e, exactly
        while every rope is taut."""
        tensions, _, gain = self._evaluate(scenarios, self.boom_heights(preload))
        return tensions, gain

    @property
    def hook_uncertain(self):
        """True when any hook has a height tolerance."""
        return bool(np.any(self.hook_tolerance > 0.0))

    def hook_shifts(self, preload, scenarios):
        """Rigid-body hook motions (dH, m) that bring the body to each scenario's attitude."""
        return self._evaluate(scenarios, self.boom_heights(preload))[1]

    def twist_gain(self, preload):
        """dT/dH at the level pose with the pose held  [t/m]: the twist (skew) response."""
        return self._evaluate([Scenario(0.0, 0.0)], self.boom_heights(preload))[2][0]


def first_scenarios(problem):
    """Level at the nominal CG, then each CG vertex at level and at the box's four corners."""
    h, t = problem.heel_tolerance, problem.trim_tolerance
    tilts = [(0.0, 0.0)] + sorted({(a, b) for a in (-h, h) for b in (-t, t)} - {(0.0, 0.0)})
    out = [Scenario(0.0, 0.0)]
    for offset in problem.cog_envelope.offsets():
        for a, b in tilts:
            s = Scenario(float(a), float(b), tuple(float(v) for v in offset))
            if s not in out:
                out.append(s)
    return out
