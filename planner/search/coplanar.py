"""Lugs in one plane of the body, held by equal ropes: every scenario is one effective CG.

When every candidate lies at one body height and every rope has the same stiffness EA / l0
(equal cranes, body-fixed lugs), the held-preload model is exactly

    T_k,i = P_i + kappa (h_k(p_i) - r_k,i) = P_i + c_k0 + c_k1 x_i + c_k2 y_i

(:mod:`~liftplan.planner.search.mip`): the hook plane's shift and the lug's rise are both
planes in the lug's body plan position (x_i, y_i), so each scenario adds a plane to the level
tensions. Its three coefficients come from the statics at the scenario's pose, which with
every lug at height z_L read, in the body frame,

    sum T = W,     sum T (x_i, y_i) = W g_hat,     g_hat = g_xy + M^-1 R[:2, 2] (g_z - z_L)

(R the pose's rotation, M = R[:2, :2]): a tilt acts as a shift of the CG in plan, by its
height above the lugs times the tilt. A scenario is then only its effective CG g_hat, and
the tensions at any g_hat in a polygon are affine in g_hat: the worst spread, the lowest and
the highest tension over the whole box are met at the corners of the polygon the scenarios'
effective CGs span (:func:`corner_scenarios`). :class:`PlaneLP` is the preload LP of a set on
those corners alone: the same value as the held model over the same scenarios, in a few
milliseconds instead of the dense search's second, which is what lets the local search
try every swap of 26 lugs among 80 candidates.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import sparse
from scipy.optimize import linprog
from scipy.spatial import ConvexHull, QhullError

from liftplan.model.frames import rotation_matrix
from liftplan.planner.search.scenarios import LugSet


@dataclass(frozen=True)
class Coplanar:
    """The candidates' common body height.

    Parameters
    ----------
    height : float  [m]
        Body z of every candidate.
    """

    height: float


def coplanar(problem):
    """:class:`Coplanar` when the plane model holds exactly, else None.

    It holds for body-fixed candidates (no hinges) at one body height (to 1e-9 of the
    layout's size) held by cranes of one rope stiffness EA / l0.
    """
    points = np.asarray(problem.points, dtype=float)
    if problem.hinge_rows is not None or len(points) < 3:
        return None
    stiffness = {round(c.EA / c.rope_length, 9) for c in problem.fleet}
    size = max(1.0, float(np.ptp(points, axis=0).max()))
    if len(stiffness) != 1 or np.ptp(points[:, 2]) > 1e-9 * size:
        return None
    return Coplanar(float(points[0, 2]))


def effective_cogs(problem, plane, scenarios):
    """Each scenario's effective CG in the body plan, shape (m, 2)  [m] (module docstring)."""
    cog = np.asarray(problem.body.cog, dtype=float)
    out = np.empty((len(scenarios), 2))
    for k, s in enumerate(scenarios):
        rot = rotation_matrix(s.heel, s.trim, problem.yaw)
        g = cog + np.asarray(s.cog_offset, dtype=float)
        out[k] = g[:2] + np.linalg.solve(rot[:2, :2], rot[:2, 2]) * (g[2] - plane.height)
    return out


def corner_scenarios(problem, plane, scenarios):
    """The scenarios at the corners of the polygon their effective CGs span.

    Every tension, and so every spread, is affine in the effective CG for a fixed set and
    preload: its worst over the scenarios is at one of these. A polygon of no area (a
    tolerance of zero in one direction) keeps the two ends of its segment, or its one point.
    """
    points = effective_cogs(problem, plane, scenarios)
    size = max(1.0, float(np.ptp(points, axis=0).max()))
    try:
        keep = ConvexHull(points).vertices
    except (QhullError, ValueError):  # a segment or a point
        span = points - points.mean(axis=0)
        if np.ptp(points, axis=0).max() <= 1e-12 * size:
            keep = [0]
        else:
            axis = np.linalg.svd(span, full_matrices=False)[2][0]
            along = span @ axis
            keep = sorted({int(np.argmin(along)), int(np.argmax(along))})
    return [scenarios[int(k)] for k in sorted(keep)]


class PlaneLP:
    """The preload LP of a lug set over the corner scenarios, on the plane model.

    Minimises the worst spread of s_i T_i (s = 1 for ``spread``, 1 / SWL for
    ``utilisation``), or for ``reserve`` the largest T_i / SWL_i, over the corners, with
    every tension within [min_tension, the rules' limit] there and the level tensions within
    the boom-height range, as
    :class:`~liftplan.planner.search.evaluator.SetEvaluator` does over its scenario list.

    Parameters
    ----------
    problem : PlanProblem
        Equal cranes on body-fixed candidates in one plane (:func:`coplanar`).
    scenarios : list of Scenario
        The scenarios to hold (their corners are kept).
    """

    def __init__(self, problem, scenarios):
        plane = coplanar(problem)
        if plane is None:
            raise ValueError("PlaneLP needs equal ropes on candidates in one body plane")
        self.problem = problem
        self.corners = corner_scenarios(problem, plane, scenarios)
        self.cogs = effective_cogs(problem, plane, self.corners)

    def value(self, indices):
        """The set's least worst objective over the corners  [objective unit]; inf if no
        preload holds it (or its lugs are collinear)."""
        problem = self.problem
        lugset = LugSet(problem, indices)
        n, m = lugset.n, len(self.cogs)
        xy = lugset.points[:, :2]
        rows = np.column_stack([np.ones(n), xy])  # (1, x, y) of each lug
        if np.linalg.matrix_rank(rows, tol=1e-9 * max(1.0, np.abs(xy).max())) < 3:
            return np.inf
        weight = problem.body.weight
        # variables: P (n), per corner c_k (3), lo_k, hi_k, then z
        c0, lo0, hi0, zi = n, n + 3 * m, n + 4 * m, n + 5 * m
        size = zi + 1
        eq_rows, eq_rhs = [], []
        level = np.zeros((3, size))
        level[:, :n] = rows.T
        eq_rows.append(level)
        eq_rhs.append(weight * np.r_[1.0, problem.body.cog[0], problem.body.cog[1]])
        gram = rows.T @ rows
        ub_blocks, ub_rhs = [], []
        scale = lugset.scale
        low_limit, high_limit = problem.min_tension, lugset.limit
        eye = np.eye(n)
        for k in range(m):
            block = np.zeros((3, size))
            block[:, :n] = rows.T
            block[:, c0 + 3 * k : c0 + 3 * k + 3] = gram
            eq_rows.append(block)
            eq_rhs.append(weight * np.r_[1.0, self.cogs[k]])
            tension = np.zeros((n, size))  # T_k = P + rows c_k
            tension[:, :n] = eye
            tension[:, c0 + 3 * k : c0 + 3 * k + 3] = rows
            scaled = scale[:, None] * tension
            ub_blocks += [-tension, tension]
            ub_rhs += [-np.full(n, low_limit), high_limit]
            if problem.goal.peak:  # z >= T_i / SWL_i
                upper = scaled.copy()
                upper[:, zi] = -1.0
                ub_blocks.append(upper)
                ub_rhs.append(np.zeros(n))
                continue
            upper = scaled.copy()
            upper[:, hi0 + k] = -1.0  # s T <= hi_k
            lower = -scaled
            lower[:, lo0 + k] = 1.0  # lo_k <= s T
            band = np.zeros((1, size))
            band[0, hi0 + k], band[0, lo0 + k], band[0, zi] = 1.0, -1.0, -1.0
            ub_blocks += [upper, lower, band]
            ub_rhs += [np.zeros(n), np.zeros(n), [0.0]]
        low, high = lugset.preload_range()
        bounds = [(float(a), float(b)) for a, b in zip(low, high)] + [(None, None)] * (size - n)
        cost = np.zeros(size)
        cost[zi] = 1.0
        result = linprog(
            cost,
            A_ub=sparse.csr_array(np.vstack(ub_blocks)),
            b_ub=np.concatenate(ub_rhs),
            A_eq=sparse.csr_array(np.vstack(eq_rows)),
            b_eq=np.concatenate(eq_rhs),
            bounds=bounds,
            method="highs",
        )
        return float(result.fun) if result.status == 0 else np.inf
