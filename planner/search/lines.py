"""A lower bound for every lug set when the candidates lie on two parallel lines.

Lugs along the two deck edges, the two sides' frames or two lifting beams: every candidate on
one of two parallel lines of the body. At any pose the two lines stay parallel in plan, so the
moment about their direction and the vertical force fix how much the lugs of each line carry
together, whatever the set and the preload:

    F1_k = W (g_k - a2_k) / (a1_k - a2_k),     F2_k = W - F1_k,

(a1, a2 the lines' and g the CG's plan offsets across the lines at scenario k). A set with n1
lugs on line 1 and n2 = n - n1 on line 2 has a largest tension at least F1 / n1 (and F2 / n2)
and a least at most the other, so its worst spread over the scenarios is at least

    B(n1) = max over k of |F1_k / n1 - F2_k / n2|,

and no set does better than min over the counts n1 the candidates allow of B(n1). It holds
for any rope model that keeps the statics (held preload, hook errors, any scenario subset), so
the local search's plan gets a certified gap and the MIP a cut on its count of lugs per line.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from liftplan.model.frames import rotation_matrix


@dataclass(frozen=True)
class TwoLines:
    """Candidates on two parallel lines.

    Parameters
    ----------
    line : numpy.ndarray of int, shape (C,)
        0 or 1: the line of each candidate.
    direction : numpy.ndarray, shape (3,)
        The lines' direction, body frame (unit).
    """

    line: np.ndarray
    direction: np.ndarray

    @property
    def counts(self):
        """Candidates on each line."""
        return np.bincount(self.line, minlength=2)


def two_lines(problem):
    """The two parallel lines the candidates lie on (3-D, body frame), or None.

    Of any three candidates at distinct positions two share a line, so the lines' direction is
    that of one of their three pairs: each is tried (O(C), so 10 000 candidates take
    milliseconds); a direction fits when the candidates' positions across it take exactly
    two values (1e-9 of the layout's size). The direction returned is that of the first pair
    (in index order) along it, so it does not depend on which three were tried.
    """
    points = np.asarray(problem.points, dtype=float)
    if len(points) < 4 or problem.hinge_rows is not None:
        return None
    size = max(1.0, float(np.ptp(points, axis=0).max()))
    tol = 1e-9 * size
    distinct = [0]  # three candidates at distinct positions (a pair nearer than 1e3 tol is one)
    for k in range(1, len(points)):
        if np.all(np.linalg.norm(points[distinct] - points[k], axis=1) >= 1e3 * tol):
            distinct.append(k)
            if len(distinct) == 3:
                break
    if len(distinct) < 3:
        return None  # every candidate at one or two positions: on one line
    for a, b in ((0, 1), (0, 2), (1, 2)):
        d = points[distinct[b]] - points[distinct[a]]
        labels = _split(points, d / np.linalg.norm(d), 0, tol)
        if labels is not None:
            first, d = _first_pair(points, labels, tol)
            return TwoLines(_split(points, d, first, tol), d)
    return None


def _split(points, d, ref, tol):
    """0/1 line labels when the points lie on two lines along unit ``d`` (1: the line of the
    first point off point ``ref``'s line), else None."""
    across = (points - points[ref]) - np.outer((points - points[ref]) @ d, d)
    far = np.linalg.norm(across, axis=1) > tol
    if not np.any(far):
        return None  # every candidate on one line
    k = int(np.argmax(far))
    second = np.linalg.norm(across - across[k], axis=1) <= tol
    return second.astype(int) if np.all(~far | second) else None


def _first_pair(points, labels, tol):
    """``i`` and the unit direction p_j - p_i of the first pair i < j (index order) on one
    line."""
    for i in range(len(points) - 1):
        rest = np.arange(i + 1, len(points))
        rest = rest[labels[rest] == labels[i]]
        gaps = np.linalg.norm(points[rest] - points[i], axis=1)
        rest = rest[gaps >= 1e3 * tol]
        if len(rest):
            d = points[rest[0]] - points[i]
            return i, d / np.linalg.norm(d)
    raise AssertionError("two lines, yet no two candidates on one")  # 3 distinct: 2 share one


def count_bounds(problem, lines, scenarios):
    """B(n1) for n1 = 0 .. n (module docstring), in the objective's unit; inf where no set has
    that count (too few candidates on a line, or every lug on one line: collinear); 0 for every
    count when the two lines lie one above the other in plan at some pose (no split).

    Parameters
    ----------
    problem : PlanProblem
    lines : TwoLines
    scenarios : list of Scenario
    """
    n, weight = problem.cranes, problem.body.weight
    points = np.asarray(problem.points, dtype=float)
    first = points[np.flatnonzero(lines.line == 0)[0]]
    second = points[np.flatnonzero(lines.line == 1)[0]]
    cog = np.array(problem.body.cog, dtype=float)
    share = np.empty(len(scenarios))
    rotations = {}  # one per attitude (the scenarios repeat them for each CG vertex)
    for k, s in enumerate(scenarios):
        rot = rotations.get((s.heel, s.trim))
        if rot is None:
            rot = rotations[(s.heel, s.trim)] = rotation_matrix(s.heel, s.trim, problem.yaw)
        along = (rot @ lines.direction)[:2]
        across = np.array([-along[1], along[0]])  # the lines' plan normal at this pose
        a1, a2 = across @ (rot @ first)[:2], across @ (rot @ second)[:2]
        if abs(a1 - a2) <= 1e-9 * max(1.0, float(np.ptp(points, axis=0).max())):
            return np.zeros(n + 1)  # one line above the other in plan: the statics split nothing
        g = across @ (rot @ (cog + np.asarray(s.cog_offset, dtype=float)))[:2]
        share[k] = weight * (g - a2) / (a1 - a2)  # what line 0's lugs carry together [t]
    out = np.full(n + 1, np.inf)
    counts = lines.counts
    for n1 in range(max(1, n - counts[1]), min(n - 1, counts[0]) + 1):
        out[n1] = float(np.max(np.abs(share / n1 - (weight - share) / (n - n1))))
    if problem.goal.per_swl:  # a width of T / SWL: equal SWL on every candidate (line_bound)
        out = out / float(np.nanmax(problem.reach[1]))
    return out


def line_bound(problem, scenarios):
    """No lug set does better than this over ``scenarios`` (a subset of the box): the least
    :func:`count_bounds` over the counts the candidates allow; 0 where it does not apply (no
    two lines; the ``reserve`` objective; ``utilisation`` with unequal SWLs)."""
    lines = two_lines(problem)
    if lines is None or problem.goal.peak:
        return 0.0
    swl = problem.reach[1]
    if problem.goal.per_swl and np.nanmax(swl) != np.nanmin(swl):
        return 0.0
    bounds = count_bounds(problem, lines, scenarios)
    return float(np.min(bounds)) if np.any(np.isfinite(bounds)) else 0.0
