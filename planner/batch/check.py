"""A fixed plan checked against many uncertain cases at once.

A case is a real weight, a real CG position and a heel/trim tolerance box (and the least
tension the engineer accepts). The plan's boom heights are fixed; with them held, the
operators keep the body near level by moving the hooks as a rigid body, which leaves the
preload alone (README "Planning"), so the tensions at each attitude of the box are the
``held`` model's, exact while every rope is taut. One batched casadi call evaluates every
(case, attitude) column.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from liftplan.model.scene.objects import _convex_hull
from liftplan.model.statics.model import rope_model
from liftplan.planner.search.scenarios import LugSet, pack, run_block

#: Outcomes of a checked case.
OK, UNSAFE, FAILED, INVALID = "ok", "unsafe", "failed", "invalid"


@dataclass(frozen=True)
class CheckCases:
    """Uncertain states to check a plan against (arrays of one length m).

    Parameters
    ----------
    weight : numpy.ndarray, shape (m,)  [t]
    cog : numpy.ndarray, shape (m, 3)  [m]
        Body frame (``z-up``).
    heel_tolerance, trim_tolerance : numpy.ndarray, shape (m,)  [deg]
        Half-widths of the attitude box.
    min_tension : numpy.ndarray, shape (m,)  [t]
    """

    weight: np.ndarray
    cog: np.ndarray
    heel_tolerance: np.ndarray
    trim_tolerance: np.ndarray
    min_tension: np.ndarray

    def __len__(self):
        return len(self.weight)


@dataclass(frozen=True)
class CheckResult:
    """A plan checked over each case's tolerance box.

    Parameters
    ----------
    status : list of str
        ``"ok"``; ``"unsafe"`` (a rope above the plan's limit, the tension the rules' chain
        allows under its crane's chart SWL - the limit the plan was made to -, or below the
        minimum tension);
        ``"failed"`` (a rope went slack: the all-taut model does not hold there); or
        ``"invalid"`` (the CG is not over the plan's lugs, as the scene rules require).
        The numbers of failed and invalid cases are NaN.
    reason : list of str
        Empty when ok; otherwise one line naming the rope, the value and the attitude.
    worst_spread : numpy.ndarray  [t]
        Largest max - min tension over the box.
    worst_heel, worst_trim : numpy.ndarray  [deg]
        Where it occurs.
    min_tension, max_tension : numpy.ndarray  [t]
        Smallest and largest tension anywhere in the box.
    utilisation : numpy.ndarray  [-]
        ``max_tension`` over the SWL.
    """

    status: list
    reason: list
    worst_spread: np.ndarray
    worst_heel: np.ndarray
    worst_trim: np.ndarray
    min_tension: np.ndarray
    max_tension: np.ndarray
    utilisation: np.ndarray


def unit_grid(count):
    """Heel x trim points on [-1, 1]^2, ``count`` per axis (level first when odd), (g, 2)."""
    if count < 2:
        return np.zeros((1, 2))
    axis = np.linspace(-1.0, 1.0, count)
    grid = np.array(np.meshgrid(axis, axis, indexing="ij")).reshape(2, -1).T
    return grid[np.argsort(np.abs(grid).sum(axis=1), kind="stable")]


def check_plan(problem, indices, preload, cases, grid=3, cranes=None):
    """Tensions of one plan over every case's tolerance box.

    Parameters
    ----------
    problem : PlanProblem
        Gives the candidates, crane, lift height and yaw (its weight and CG are replaced by
        each case's).
    indices : sequence of int
        The plan's candidate indices.
    preload : array_like, shape (n,)  [t]
        The plan's level tensions (they fix the boom heights).
    cases : CheckCases
    grid : int
        Attitudes per axis of each box (3: corners, edge middles and level).
    cranes : sequence of int, optional
        The plan's fleet index of the crane on each lug (default: crane k on the k-th lug);
        each rope is checked against its own crane's SWL at its radius.

    Returns
    -------
    CheckResult
    """
    lugset = LugSet(problem, indices, cranes)
    n, m = lugset.n, len(cases)
    units = unit_grid(grid)
    g = len(units)
    heel = cases.heel_tolerance[:, None] * units[None, :, 0]  # (m, g)
    trim = cases.trim_tolerance[:, None] * units[None, :, 1]
    x = np.column_stack(
        [np.full(m * g, problem.lift_height), np.radians(heel).ravel(), np.radians(trim).ravel()]
    )
    params = pack(
        problem,
        lugset.points,
        cases.cog,
        lugset.boom_heights(preload),
        cases.weight,
        rope_length=lugset.rope_length,
        EA=lugset.EA,
    )
    tensions, _, _ = run_block(rope_model(n).held_columns, n, x, np.repeat(params, g, axis=0))
    tensions = tensions.reshape(m, g, n)

    spread = np.ptp(tensions, axis=2)  # (m, g)
    worst = np.argmax(spread, axis=1)
    rows = np.arange(m)
    low, high = tensions.min(axis=(1, 2)), tensions.max(axis=(1, 2))
    swl = lugset.swl  # (n,): each crane's chart SWL at its radius
    # the limit the plan itself was made to (the rules' chain: chart SWL over the DAF, less the
    # rigging, over the contingency), not the bare chart SWL: one limit everywhere
    limit = lugset.limit
    flagged = ~np.all(np.isfinite(tensions), axis=(1, 2)) | np.any(
        (tensions < 0.0) | (tensions > limit) | (tensions < cases.min_tension[:, None, None]), axis=(1, 2)
    )
    status, reason = [OK] * m, [""] * m
    outside = outside_support(lugset.points[:, :2], cases.cog[:, :2])
    names = [problem.candidates[i].name for i in lugset.indices]
    for k in np.flatnonzero(flagged | (outside > 0)):  # only flagged cases need a reason
        if outside[k] > 0:
            status[k], reason[k] = (
                INVALID,
                (
                    f"body.cog lies {outside[k]:.3g} m outside the plan's lugs' support polygon (in "
                    "plan); expected the CG over the lugs"
                ),
            )
        else:
            status[k], reason[k] = _judge(
                tensions[k], heel[k], trim[k], limit, swl, cases.min_tension[k], names
            )
    failed = np.array([s in (FAILED, INVALID) for s in status])

    def blank(values):
        return np.where(failed, np.nan, values)

    return CheckResult(
        status=status,
        reason=reason,
        worst_spread=blank(spread[rows, worst]),
        worst_heel=blank(heel[rows, worst]),
        worst_trim=blank(trim[rows, worst]),
        min_tension=blank(low),
        max_tension=blank(high),
        utilisation=blank((tensions / swl).max(axis=(1, 2))),
    )


def outside_support(lugs, points):
    """How far each plan point lies outside the lugs' convex hull (0 inside)  [m].

    Parameters
    ----------
    lugs : numpy.ndarray, shape (n, 2)  [m]
    points : numpy.ndarray, shape (m, 2)  [m]

    Returns
    -------
    numpy.ndarray, shape (m,)  [m]
        The largest distance beyond a hull edge (the scene's own test, at level attitude),
        with the scene's rounding allowance of 1e-9 lug-set diameters.
    """
    hull = _convex_hull([tuple(p) for p in lugs])
    a = lugs[hull]
    edge = np.roll(a, -1, axis=0) - a  # counter-clockwise edges
    rel = points[:, None, :] - a[None, :, :]
    inside = (edge[None, :, 0] * rel[..., 1] - edge[None, :, 1] * rel[..., 0]) / np.hypot(*edge.T)
    beyond = np.max(-inside, axis=1)
    diameter = np.max(np.linalg.norm(lugs[:, None] - lugs[None], axis=-1))
    return np.where(beyond > 1e-9 * diameter, beyond, 0.0)


def _judge(tensions, heel, trim, limit, swl, min_tension, names):
    """Status and reason of one case from its (g, n) tensions; a rope is named by its plan
    label and its lug (``L20 (S07)``: with many ropes the label alone is hard to place)."""
    if not np.all(np.isfinite(tensions)):
        return FAILED, "tensions not finite: the lugs cannot hold the body (collinear?)"
    for test, bound, word, outcome in (
        (tensions < 0.0, 0.0, "slack", FAILED),
        (tensions > limit, limit, "over the plan's limit", UNSAFE),
        (tensions < min_tension, min_tension, "below min_tension", UNSAFE),
    ):
        if test.any():
            bound = np.broadcast_to(bound, tensions.shape)  # limit: one per rope
            j, i = np.unravel_index(np.argmax(np.abs(tensions - bound) * test), test.shape)
            bound = bound[j, i]
            where = f"at heel {heel[j]:+.2f}, trim {trim[j]:+.2f} deg"
            rope = f"rope L{i + 1} ({names[i]})"
            if outcome == FAILED:
                return FAILED, (f"{rope} slack {where}: the all-taut (held) model does not hold there")
            if word == "over the plan's limit":
                word = f"over the plan's limit {bound:.1f} t (chart SWL {swl[i]:g} t by the rules' chain)"
                return UNSAFE, f"{rope} {tensions[j, i]:.1f} t {word} {where}"
            return UNSAFE, f"{rope} {tensions[j, i]:.1f} t {word} {bound:g} t {where}"
    return OK, ""
