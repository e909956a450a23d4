"""Screening every lug set at once: feasibility and a lower bound on its worst spread.

For all sets together (numpy, with the tensions from casadi's compiled ``held`` map), on
the screening scenarios Theta0 (the 3 x 3 grid of the tolerance box: corners, edge
midpoints, level, each with every vertex of the CG envelope):

* n = 3: no preload to choose; the tensions are fixed and the bound is the worst spread
  over Theta0 itself.
* n = 4: the admissible level preloads form a line T* = T0 + t v (v spans the null space of
  the level statics). Every constraint is an interval in t and the worst spread over Theta0
  is convex piecewise-linear in t, so the least worst spread over Theta0 (the exact value
  of the minimax LP on Theta0) is found by a vectorised golden-section search with a
  rigorous error margin.
* n >= 5: a bound that holds for any preload: for a rope pair (i, j) and two scenarios,
  the spread is at least half the change of T_i - T_j between them. T* cancels from that
  change except through Z = sum T*_i z_i (lug heights), a scalar; the bound is minimised
  over Z's range by the same 1-D search.

Every bound is over a subset of the box's scenarios, so it never exceeds the worst
spread of any preload over the whole box: a valid bound for pruning.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from liftplan.model.errors import PlanInfeasible
from liftplan.planner.problem.clearance import clear
from liftplan.planner.problem.fleet import rule_limits
from liftplan.planner.search.dual import PairWidening, staged_lp_bound
from liftplan.planner.search.rows import row_max, row_min, row_spread
from liftplan.planner.search.scenarios import (
    box_attitudes,
    held_model,
    level_bar_moment,
    pack,
    run_block,
    set_hinges,
)

# Why a set is infeasible (screening can show it for n <= 4; larger sets are left to the LP).
FEASIBLE = 0
COLLINEAR = 7
CODE_MARGIN = 8
CG_OUTSIDE = 1
LEVEL_SWL = 2
LEVEL_MIN_TENSION = 3
BOOM_RANGE = 4
BOX_SLACK = 5
BOX_OVERLOAD = 6
VESSEL_HEEL = 9
VESSEL_TRIM = 10
VESSEL_FREEBOARD = 11
REASONS = {
    COLLINEAR: "the lugs are collinear in plan (the statics are singular)",
    CG_OUTSIDE: "the CG lies outside the lugs' polygon in plan",
    LEVEL_SWL: "level tensions need more than the crane SWL allows (chart SWL / DAF, less the "
    "rigging, over the weight contingency)",
    LEVEL_MIN_TENSION: "level tensions cannot all reach min_tension",
    CODE_MARGIN: "a level tension exceeds the crane's SWL / (1 + the multi-crane code margin), "
    "less the rigging, over the weight contingency",
    BOOM_RANGE: "the boom heights needed lie outside the crane's boom-height range",
    BOX_SLACK: "a rope falls below min_tension somewhere in the tolerance box",
    BOX_OVERLOAD: "a rope exceeds the crane SWL (with the rules' DAF, contingency and rigging) "
    "somewhere in the tolerance box",
    VESSEL_HEEL: "a crane vessel heels beyond its max_heel at a worst state (the box, the CG "
    "envelope and the hook errors; the levelling ballast set for the level tension)",
    VESSEL_TRIM: "a crane vessel trims beyond its max_trim at a worst state (the box, the CG "
    "envelope and the hook errors; the levelling ballast set for the level tension)",
    VESSEL_FREEBOARD: "a crane vessel's lowest deck corner falls below its min_freeboard at a worst "
    "state (the box, the CG envelope and the hook errors; the levelling ballast set)",
}

CHUNK = 8192
#: Largest array a screening chunk holds (floats; 8 bytes each).
FLOATS = 16_000_000
_GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0
#: Golden-section steps: the bracket shrinks to 0.618^32 ~ 2e-7 of the preload range, and
#: the bound subtracts the Lipschitz constant times what is left.
_ITERATIONS = 32


@dataclass(frozen=True)
class Screening:
    """Screening of every lug set.

    Parameters
    ----------
    sets : numpy.ndarray, shape (N, n), int
        Candidate indices of each set (ascending). A set appears once per crane assignment.
    cranes : numpy.ndarray, shape (N, n), int
        Fleet index of the crane on each lug of the row.
    bound : numpy.ndarray, shape (N,)  [t]
        Lower bound on the set's worst spread over the box; inf where infeasible.
    reason : numpy.ndarray, shape (N,), int
        :data:`FEASIBLE` or a key of :data:`REASONS`.
    exact : bool
        True when ``bound`` is the exact minimax over the screening scenarios (n <= 4).
    priority : numpy.ndarray, shape (N,), optional
        The order in which a search best refines the rows' bounds (least first; not a bound):
        the bound itself, but with hook-height errors the pair bound without their widening
        (the widening makes the bound order the sets nearly backwards: on the tanker's 8 of 16
        the sets best with the errors have some of the highest bounds, and the best without
        them are among the best with them). Default: ``bound``.
    partial : numpy.ndarray, shape (N,), bool, optional
        With ``defer``: the rows whose dual bound is over their first scenarios only and
        below the target (:func:`~liftplan.planner.search.dual.staged_lp_bound`); to be
        bounded again. None otherwise.
    """

    sets: np.ndarray
    cranes: np.ndarray
    bound: np.ndarray
    reason: np.ndarray
    exact: bool
    partial: np.ndarray | None = None
    priority: np.ndarray | None = None

    def __post_init__(self):
        if self.priority is None:  # the bound itself orders the rows
            object.__setattr__(self, "priority", self.bound)


def all_sets(problem):
    """Every lug set, shape (N, n), in lexicographic order."""
    return _combinations(len(problem.candidates), problem.cranes)


def _combinations(count, n):
    """Every n-subset of range(count) as rows of ascending indices, in lexicographic order
    (as itertools.combinations, built column by column in numpy)."""
    rows = np.arange(count - n + 1, dtype=np.int64)[:, None]  # the first index
    for column in range(1, n):
        last = rows[:, -1]
        # each row continues with every index above its last that leaves room for the rest
        reach = count - n + column + 1
        counts = reach - (last + 1)
        nxt = np.repeat(last + 1, counts) + (
            np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
        )
        rows = np.column_stack([np.repeat(rows, counts, axis=0), nxt])
    return rows


def assignments(problem):
    """Distinct ways to put the fleet on n lugs (interchangeable cranes counted once).

    Returns
    -------
    numpy.ndarray, shape (P, n), int
        Row p: the fleet index of the crane on the k-th lug of a set (candidate order).
    """
    classes = problem.crane_classes
    if len(classes) == 1:  # one crane class: one way (no n! orderings to build and merge)
        return np.arange(problem.cranes, dtype=np.int64)[None, :]
    label = np.empty(problem.cranes, dtype=np.int64)
    for c, group in enumerate(classes):
        label[list(group)] = c
    patterns = _distinct_orders(label.tolist())
    rows = []
    for pattern in patterns:
        taken = [list(group) for group in classes]
        rows.append([taken[c].pop(0) for c in pattern])
    return np.array(rows, dtype=np.int64).reshape(-1, problem.cranes)


def _distinct_orders(labels):
    """Every distinct ordering of a multiset of labels, sorted (not the n! permutations)."""
    counts = {}
    for label in labels:
        counts[label] = counts.get(label, 0) + 1
    out, order = [], []

    def extend():
        if len(order) == len(labels):
            out.append(tuple(order))
            return
        for label in sorted(counts):
            if counts[label]:
                counts[label] -= 1
                order.append(label)
                extend()
                order.pop()
                counts[label] += 1

    extend()
    return out


def set_rows(problem, sets=None):
    """Every (set, assignment) row whose cranes all reach their lugs and keep their clearance.

    The rows are grown lug by lug (a crane class on the first lug of every set, then on the
    second, ...), each partial row dropped as soon as its newest crane cannot reach its lug or
    its boom clashes with an earlier one: sets x assignments is never held in memory, only the
    rows still possible. More than :data:`MAX_ROWS` rows at any step is refused with the count.
    The rows come out in the order of the product (set, then assignment as
    :func:`assignments` lists them).

    Returns
    -------
    sets, cranes : numpy.ndarray, shape (N, n), int
    out_of_reach : int
        Rows dropped because a crane cannot reach its lug.
    clashing : int
        Rows dropped because two booms cross or come nearer than ``plan.crane_clearance``
        (:mod:`liftplan.planner.problem.clearance`). A row with both causes is counted once,
        under the first found lug by lug (reach before clearance at each lug).
    """
    sets = all_sets(problem) if sets is None else np.asarray(sets, dtype=np.int64)
    swl, distances = problem.reach[1], problem.boom_distances
    classes = problem.crane_classes
    n = problem.cranes
    if len(classes) == 1 and distances is None and not np.any(np.isnan(swl[:, list(classes[0])])):
        return sets, np.broadcast_to(np.arange(n, dtype=np.int64), sets.shape), 0, 0  # one way
    counts = np.array([len(g) for g in classes])
    member = np.array([list(g) + [-1] * (counts.max() - len(g)) for g in classes], dtype=np.int64)
    row = np.arange(len(sets))  # the set of each partial row
    kind = np.empty((len(sets), 0), dtype=np.int64)  # crane class on each lug so far
    crane = np.empty((len(sets), 0), dtype=np.int64)  # fleet index on each lug so far
    used = np.zeros((len(sets), len(classes)), dtype=np.int64)
    log_fact = np.array([math.lgamma(k + 1) for k in range(n + 1)])
    out_of_reach = clashing = 0.0
    for k in range(n):
        lug = sets[row, k]
        grown = []
        for c in range(len(classes)):
            free = used[:, c] < counts[c]
            j = member[c, np.minimum(used[:, c], counts[c] - 1)]
            left = counts[None, :] - used
            left[:, c] -= 1
            # completions of each partial row once class c takes lug k: multinomial of the rest
            ways = np.exp(log_fact[n - k - 1] - log_fact[np.maximum(left, 0)].sum(axis=1))
            reach = free & ~np.isnan(swl[lug, j])
            out_of_reach += float(ways[free & ~reach].sum())
            ok = reach.copy()
            if distances is not None:
                least = np.full(len(row), np.inf)
                for m in range(k):
                    least = np.minimum(least, distances[sets[row, m], crane[:, m], lug, j])
                ok &= clear(least, problem.crane_clearance)
                clashing += float(ways[reach & ~ok].sum())
            if np.any(ok):
                step = used[ok].copy()
                step[:, c] += 1
                grown.append(
                    (
                        row[ok],
                        np.column_stack([kind[ok], np.full(ok.sum(), c)]),
                        np.column_stack([crane[ok], j[ok]]),
                        step,
                    )
                )
        if not grown:
            row = np.empty(0, dtype=np.int64)
            break
        row = np.concatenate([g[0] for g in grown])
        kind = np.concatenate([g[1] for g in grown])
        crane = np.concatenate([g[2] for g in grown])
        used = np.concatenate([g[3] for g in grown])
        if len(row) > MAX_ROWS:
            raise PlanInfeasible(
                f"the exact search would hold more than {MAX_ROWS} (set, assignment) rows in reach "
                f"and clear after {k + 1} of {n} lugs ({len(sets)} sets x {len(assignments(problem))} "
                "assignments); expected fewer candidates or distinct cranes, or "
                'plan.search = "mip" (no set enumerated)'
            )
    if len(row) == 0:
        empty = np.empty((0, n), dtype=np.int64)
        return empty, empty, int(round(out_of_reach)), int(round(clashing))
    order = np.lexsort([kind[:, m] for m in range(n - 1, -1, -1)] + [row])
    return sets[row[order]], crane[order], int(round(out_of_reach)), int(round(clashing))


#: Most partial (set, assignment) rows :func:`set_rows` holds at once.
MAX_ROWS = 5_000_000


#: Screening columns (rows x scenarios) above which the rows are first screened on the box
#: corners and level only, and the full screening scenarios are applied lazily (search).
FULL_COLUMNS = 400_000


def screen(problem, sets=None, cranes=None, coarse=None, dual=False, target=np.inf, defer=None):
    """Screen lug sets with their crane assignments (every feasible row by default).

    Parameters
    ----------
    problem : PlanProblem
    sets : numpy.ndarray, shape (N, n), optional
    cranes : numpy.ndarray, shape (N, n), optional
        Fleet indices per lug (default: the identity, any assignment of an equal fleet).
    coarse : bool, optional
        Screen on the tolerance box's corners and level (nominal CG) only: a weaker, cheaper
        bound. Default: when the full screening would exceed :data:`FULL_COLUMNS`.
    dual : bool
        n >= 5: also bound each set's preload LP over the screening scenarios through its
        dual (:mod:`~liftplan.planner.search.dual`; ~2 ms a set, nearly the LP's value);
        otherwise the preload-free pair bound only.
    target : float
        With ``dual``: a bound that reaches this need not be made tighter.
    defer : numpy.ndarray, shape (N,), bool, optional
        With ``dual`` and a target: these rows, when their first-stage dual bound falls short
        of the target, keep it and are flagged in ``Screening.partial`` (bounded again later
        by the caller) instead of being bounded over every scenario now.

    Returns
    -------
    Screening
    """
    if sets is None:
        sets, cranes, *_ = set_rows(problem)
    sets = np.asarray(sets, dtype=np.int64)
    if cranes is None:
        cranes = np.broadcast_to(np.arange(sets.shape[1]), sets.shape)
    cranes = np.asarray(cranes, dtype=np.int64)
    scenarios = screening_scenarios(problem, coarse=False, corners=dual and DUAL_CORNERS)
    if coarse is None:
        coarse = len(sets) * len(scenarios[0]) > FULL_COLUMNS
    if coarse:
        scenarios = screening_scenarios(problem, coarse=True)
    bound = np.empty(len(sets))
    reason = np.empty(len(sets), dtype=np.int64)
    partial = None if defer is None else np.zeros(len(sets), dtype=bool)
    priority = np.full(len(sets), np.inf)
    n = sets.shape[1]
    # sets per chunk: the gains (and the dual's null-space slopes) stay within FLOATS each
    chunk = max(1, min(CHUNK, FLOATS // (len(scenarios[0]) * n * (2 * n if dual else n))))
    hinged = problem.hinge_rows is not None
    for start in range(0, len(sets), chunk):
        part = np.arange(start, min(start + chunk, len(sets)))
        if not hinged:  # plan geometry first: the rest of the screening only where it can hold
            code = _plan_geometry(problem, sets[part])
            bound[part[code != FEASIBLE]] = np.inf
            reason[part] = code
            part = part[code == FEASIBLE]
            if part.size == 0:
                continue
        # collinear sets give singular statics (inf, nan): they are marked, not used
        with np.errstate(divide="ignore", invalid="ignore"):
            flags = None if partial is None else np.asarray(defer, dtype=bool)[part]
            order = np.full(len(part), np.nan)
            bound[part], reason[part] = _screen_chunk(
                problem, sets[part], cranes[part], scenarios, dual, target, flags, order
            )
            priority[part] = np.where(np.isnan(order), bound[part], order)
            if partial is not None:
                partial[part] = flags  # _screen_chunk left True only the rows it deferred
    return Screening(
        sets=sets,
        cranes=cranes,
        bound=bound,
        reason=reason,
        exact=problem.cranes <= 4 and not coarse,
        partial=partial,
        priority=priority,
    )


#: The dual bound's scenarios: the box corners and level (True) or the whole 3 x 3 grid,
#: each for every CG vertex.
DUAL_CORNERS = True


def screening_scenarios(problem, coarse=False, corners=False):
    """Screening scenarios: (x columns (m, 3) [m, rad, rad], CG offsets (m, 3) [m]).

    Full: the 3 x 3 box grid for every CG vertex (``corners``: its corners and level only).
    Coarse: the 4 corners and level, nominal CG.
    """
    grid = box_attitudes(problem, 3, 3)
    offsets = problem.cog_envelope.offsets()
    if corners:
        keep = np.all(np.abs(grid) == [problem.heel_tolerance, problem.trim_tolerance], axis=1)
        grid = grid[keep | np.all(grid == 0.0, axis=1)]
    if coarse:
        corners = (np.abs(grid[:, 0]) == problem.heel_tolerance) & (
            np.abs(grid[:, 1]) == problem.trim_tolerance
        )
        grid = grid[corners | np.all(grid == 0.0, axis=1)]
        offsets = offsets[:1]
    x = np.tile(
        np.column_stack(
            [
                np.full(len(grid), problem.lift_height),
                np.radians(grid[:, 0]),
                np.radians(grid[:, 1]),
            ]
        ),
        (len(offsets), 1),
    )
    return x, np.repeat(offsets, len(grid), axis=0)


def _screen_chunk(problem, sets, cranes, scenarios, dual=False, target=np.inf, defer=None, order=None):
    """Bound and rule-out code of each row of a chunk.

    ``defer`` (N,) bool, optional, changed in place: on entry the rows the dual bound may
    defer (:func:`~liftplan.planner.search.dual.staged_lp_bound`), on return the rows it did.
    ``order`` (N,) float, optional, filled in place where the rows' refinement order is not
    their bound (:attr:`Screening.priority`; NaN elsewhere).
    """
    count, n = sets.shape
    weight = problem.body.weight
    fleet = problem.fleet
    points = problem.points[sets]  # (N, n, 3)
    cog = np.array(problem.body.cog)
    yaw = math.radians(problem.yaw)
    rope_length = np.array([c.rope_length for c in fleet])[cranes]  # (N, n)
    rope_ea = np.array([c.EA for c in fleet])[cranes]
    stiffness = rope_ea / rope_length
    boom_zero = problem.lift_height + points[..., 2] + rope_length
    swl = problem.reach[1][sets, cranes]  # (N, n)
    scale = problem.goal.scale(swl)

    # level statics (yaw only)
    c, s = math.cos(yaw), math.sin(yaw)
    plan_x = c * points[..., 0] - s * points[..., 1]
    plan_y = s * points[..., 0] + c * points[..., 1]
    a_level = np.stack([np.ones((count, n)), plan_x, plan_y], axis=1)  # (N, 3, n)
    b_level = weight * np.array([1.0, c * cog[0] - s * cog[1], s * cog[0] + c * cog[1]])
    hinges = set_hinges(problem, sets)  # slings hinged about a pair (None: body-fixed points)
    if hinges is not None:  # a spreader bar's weight off its hook: the moment rows per set
        b_level = b_level - np.pad(level_bar_moment(problem, points, hinges), ((0, 0), (1, 0)))

    # tensions at the screening scenarios with zero preload, and their gains (all at once:
    # the CG is in the parameter vector, one column per (row, scenario))
    x, offsets = scenarios
    m = len(x)
    columns_p = pack(
        problem,
        points[:, None],
        (cog + offsets)[None],
        boom_zero[:, None],
        rope_length=rope_length[:, None],
        EA=rope_ea[:, None],
        hinges=None if hinges is None else hinges[:, None],
    )
    columns_p = columns_p.reshape(count * m, -1)
    columns_x = np.tile(x, (count, 1))
    q, _, gain = run_block(held_model(problem, n).held_columns, n, columns_x, columns_p)
    q = q.reshape(count, m, n)
    gain = gain.reshape(count, m, n, n) / stiffness[:, None, None, :]  # P_k

    inside = _cog_inside(plan_x, plan_y, b_level[..., 1:2] / weight, b_level[..., 2:3] / weight)
    boom_min = np.array([c.boom_min for c in fleet])[cranes]
    boom_max = np.array([c.boom_max for c in fleet])[cranes]
    limit, share_limit = rule_limits(problem, swl, cranes)
    preload_low = stiffness * (boom_min - boom_zero)
    preload_high = np.minimum(stiffness * (boom_max - boom_zero), share_limit)
    limits = (problem.min_tension, limit, share_limit)
    hook = _hook_margins(problem, cranes, gain * stiffness[:, None, None, :], scale)
    # particular level solution (least norm) and null space of the level statics
    collinear = _collinear(plan_x, plan_y)
    gram = a_level @ a_level.transpose(0, 2, 1)
    gram[collinear] = np.eye(3)  # placeholder: these sets are ruled out below
    rhs = np.broadcast_to(b_level, (count, 3))[..., None]
    particular = np.einsum("kji,kj->ki", a_level, np.linalg.solve(gram, rhs)[..., 0])
    reserve = problem.goal.peak
    if n == 3:
        bound, reason = _screen_fixed(
            particular, q, gain, inside, limits, (preload_low, preload_high), scale, hook, reserve
        )
    elif n == 4:
        bound, reason = _screen_line(
            particular,
            _null_vector(a_level),
            q,
            gain,
            inside,
            limits,
            (preload_low, preload_high),
            scale,
            hook,
            reserve,
        )
    else:
        bound, reason = _screen_pairs(
            particular,
            a_level,
            points[..., 2],
            q,
            gain,
            inside,
            limits,
            weight,
            scale,
            hook,
            (preload_low, preload_high),
            reserve,
            dual,
            target,
            defer,
            order,
        )
        if reserve:  # every scenario carries W on the ropes: max T_i / SWL_i >= W / sum SWL_i
            bound = np.where(np.isfinite(bound), np.maximum(bound, weight / swl.sum(axis=1)), bound)
    bound[collinear] = np.inf
    reason[collinear] = COLLINEAR
    if defer is not None:
        defer &= np.isfinite(bound) & (n >= 5) & dual
    return bound, reason


def _hook_margins(problem, cranes, gain, scale):
    """Largest effect of the hook-height errors within their tolerance at each screening
    scenario (exact: affine in the errors at a given attitude), or None without tolerances.

    gain : (N, m, n, n) dT/dH [t/m]; scale : (N, n) the objective's s_i.

    Returns
    -------
    margin : (N, m, n)  [t]   sum_j |G_ij| delta_j
    pair : PairWidening   sum_j |s_a G_aj - s_b G_bj| delta_j for every pair (a, b) at
        each scenario, (N, m, n, n), worked out for the scenarios asked only
    """
    delta = np.array(
        [problem.hook_tolerance if c.hook_tolerance is None else c.hook_tolerance for c in problem.fleet]
    )[cranes]  # (N, n)
    if not np.any(delta > 0.0):
        return None
    margin = np.einsum("kmij,kj->kmi", np.abs(gain), delta)
    return margin, PairWidening(gain * scale[:, None, :, None], delta)


def value_ceiling(scale, high, low, reserve=False):
    """The worst value any feasible preload of a row can have, shape (N,)  [t or -].

    Every row of the preload LP is s_a T_a - s_b T_b + c_ab with each tension within
    [L + m, H - m] (m its hook margin) and c_ab <= s_a m_a + s_b m_b, so it is at most
    max_a s_a H_a - min_b s_b L; for ``reserve`` s_a T_a + s_a m_a <= max_a s_a H_a. A lower
    bound above this proves the row infeasible.

    Parameters
    ----------
    scale : (N, n)   the objective's s_i
    high : (N, n)  [t]   the largest tension allowed in the box
    low : float  [t]   min_tension
    reserve : bool
    """
    top = row_max(scale * high)
    return top if reserve else top - row_min(scale * low)


def row_ceiling(problem, sets, cranes):
    """:func:`value_ceiling` of (set, assignment) rows, shape (N,)  [t or -]."""
    swl = problem.reach[1][sets, cranes]
    high = rule_limits(problem, swl, cranes)[0]
    return value_ceiling(problem.goal.scale(swl), high, problem.min_tension, problem.goal.peak)


def _worst_pairs(values, pair):
    """max over scenarios and ordered pairs of values_a - values_b + pair_ab, (N,)."""
    spread = values[..., :, None] - values[..., None, :] + pair
    return spread.reshape(len(values), -1).max(axis=1)


def _collinear(plan_x, plan_y):
    """Sets whose lugs lie on a line in plan (relative plan area below 1e-6).

    The tolerance sits above the rounding of sxx syy - sxy^2 (a few eps (sxx + syy)^2): with
    1e-18 a set with two coincident lift points (two sling rigs sharing a hook position) passed
    as not collinear and its singular statics stopped the screening."""
    dx = plan_x - plan_x.mean(axis=1, keepdims=True)
    dy = plan_y - plan_y.mean(axis=1, keepdims=True)
    sxx, syy, sxy = (dx * dx).sum(1), (dy * dy).sum(1), (dx * dy).sum(1)
    return sxx * syy - sxy**2 <= 1e-12 * (sxx + syy) ** 2


def _plan_geometry(problem, sets):
    """COLLINEAR or CG_OUTSIDE where the lugs' plan alone rules a set out, else FEASIBLE.

    CG_OUTSIDE only where the CG is outside the lugs' polygon by more than rounding (an
    angular gap above pi): no tensions >= 0 can then hold the level statics, whatever the
    ropes. (The screening's own tests decide the borderline cases.)"""
    yaw = math.radians(problem.yaw)
    c, s = math.cos(yaw), math.sin(yaw)
    points = problem.points[sets]
    plan_x = c * points[..., 0] - s * points[..., 1]
    plan_y = s * points[..., 0] + c * points[..., 1]
    cog = problem.body.cog
    cog_x, cog_y = c * cog[0] - s * cog[1], s * cog[0] + c * cog[1]
    angles = np.sort(np.arctan2(plan_y - cog_y, plan_x - cog_x), axis=1)
    gaps = np.diff(angles, axis=1, append=angles[:, :1] + 2 * math.pi)
    code = np.where(gaps.max(axis=1) > math.pi + 1e-9, CG_OUTSIDE, FEASIBLE)
    return np.where(_collinear(plan_x, plan_y), COLLINEAR, code)


def _cog_inside(plan_x, plan_y, cog_x, cog_y):
    """CG strictly inside the convex hull of each set's lugs in plan (no angular gap >= pi)."""
    angles = np.sort(np.arctan2(plan_y - cog_y, plan_x - cog_x), axis=1)
    gaps = np.diff(angles, axis=1, append=angles[:, :1] + 2 * math.pi)
    return gaps.max(axis=1) < math.pi - 1e-12


def _null_vector(a_level):
    """Null vector of each 3 x 4 matrix of rows (1, x, y), unit length: by cofactors, each
    minor det [1 1 1; x; y] of three columns being twice their triangle's signed area."""
    x, y = a_level[:, 1], a_level[:, 2]

    def area(a, b, c):
        return (x[:, b] - x[:, a]) * (y[:, c] - y[:, a]) - (x[:, c] - x[:, a]) * (y[:, b] - y[:, a])

    v = np.stack([area(1, 2, 3), -area(0, 2, 3), area(0, 1, 3), -area(0, 1, 2)], axis=1)
    return v / np.sqrt((v * v) @ np.ones(4))[:, None]


def _interval(alpha, beta, low, high, lo, hi):
    """Narrow [lo, hi] to the t with low <= alpha + beta t <= high on every row.

    alpha, beta: (N, r); low, high: broadcastable to (N, r). Empty rows get lo > hi.
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        to_low = (low - alpha) / beta
        to_high = (high - alpha) / beta
    pos, neg, flat = beta > 0, beta < 0, beta == 0
    lo = np.maximum(lo, row_max(np.where(pos, to_low, np.where(neg, to_high, -np.inf))))
    hi = np.minimum(hi, row_min(np.where(pos, to_high, np.where(neg, to_low, np.inf))))
    bad = row_max(flat & ((alpha < low) | (alpha > high)))
    lo = np.where(bad, np.inf, lo)
    return lo, hi


def _golden(f, lo, hi, lipschitz, where=False):
    """Vectorised golden-section minimum of convex f on [lo, hi]; returns a lower bound (and
    with ``where`` the point of the bracket where f was least)."""
    a, b = lo.copy(), hi.copy()
    c = b - _GOLDEN * (b - a)
    d = a + _GOLDEN * (b - a)
    fc, fd = f(c), f(d)
    for _ in range(_ITERATIONS):
        left = fc <= fd
        b = np.where(left, d, b)
        a = np.where(left, a, c)
        new = np.where(left, b - _GOLDEN * (b - a), a + _GOLDEN * (b - a))
        fn = f(new)
        c, d = np.where(left, new, d), np.where(left, c, new)
        fc, fd = np.where(left, fn, fd), np.where(left, fc, fn)
    # the minimiser stays in [a, b]; f(x*) >= f(c) - L |c - x*|
    bound = np.minimum(fc, fd) - lipschitz * (b - a)
    return (bound, np.where(fc <= fd, c, d)) if where else bound


def _screen_fixed(preload, q, gain, inside, limits, preload_range, scale, hook, reserve=False):
    tensions = np.einsum("kmij,kj->kmi", gain, preload) + q
    margin = 0.0 if hook is None else hook[0]
    reason = _classify_point(preload, tensions, inside, limits, preload_range, margin)
    if reserve:
        bound = row_max(scale[:, None, :] * (tensions + margin)).max(axis=1)
    elif hook is None:
        bound = row_spread(scale[:, None, :] * tensions).max(axis=1)
    else:
        bound = _worst_pairs(scale[:, None, :] * tensions, hook[1].full())
    return np.where(reason == FEASIBLE, bound, np.inf), reason


def _classify_point(preload, tensions, inside, limits, preload_range, margin=0.0):
    low, high, share = limits  # high, share: (N, n)
    reason = np.full(len(preload), FEASIBLE)
    checks = [
        (~inside, CG_OUTSIDE),
        (np.any(preload > high, axis=1), LEVEL_SWL),
        (np.any(preload < low, axis=1), LEVEL_MIN_TENSION),
        (np.any(preload > share, axis=1), CODE_MARGIN),
        (np.any((preload < preload_range[0]) | (preload > preload_range[1]), axis=1), BOOM_RANGE),
        (np.any(tensions - margin < low, axis=(1, 2)), BOX_SLACK),
        (np.any(tensions + margin > high[:, None, :], axis=(1, 2)), BOX_OVERLOAD),
    ]
    for failed, code in reversed(checks):  # the first failing check wins
        reason = np.where(failed, code, reason)
    return reason


def _screen_line(particular, null, q, gain, inside, limits, preload_range, scale, hook, reserve=False):
    count, m, n = q.shape
    low, high, share = limits  # high, share: (N, n)
    box_high = np.tile(high, (1, m))
    box_low = low
    if hook is not None:  # every tension within its limits for every hook error
        box_low = low + hook[0].reshape(count, -1)
        box_high = box_high - hook[0].reshape(count, -1)
    alpha = np.einsum("kmij,kj->kmi", gain, particular) + q  # T_k = alpha + t beta
    beta = np.einsum("kmij,kj->kmi", gain, null)
    lo = np.full(count, -np.inf)
    hi = np.full(count, np.inf)
    reason = np.full(count, FEASIBLE)
    steps = [
        (particular, null, 0.0, np.inf, CG_OUTSIDE),
        (particular, null, -np.inf, high, LEVEL_SWL),
        (particular, null, low, np.inf, LEVEL_MIN_TENSION),
        (particular, null, low, share, CODE_MARGIN),
        (particular, null, preload_range[0], preload_range[1], BOOM_RANGE),
        (alpha.reshape(count, -1), beta.reshape(count, -1), box_low, np.inf, BOX_SLACK),
        (alpha.reshape(count, -1), beta.reshape(count, -1), -np.inf, box_high, BOX_OVERLOAD),
    ]
    for a_rows, b_rows, row_low, row_high, code in steps:
        lo, hi = _interval(a_rows, b_rows, row_low, row_high, lo, hi)
        reason = np.where((reason == FEASIBLE) & ~(lo <= hi), code, reason)
    ok = reason == FEASIBLE
    bound = np.full(count, np.inf)
    if np.any(ok):
        sc = scale[ok][:, None, :]
        al, be = sc * alpha[ok], sc * beta[ok]
        pair = None if hook is None else hook[1].subset(ok).full()
        lift = 0.0 if hook is None else sc * hook[0][ok]  # reserve: s_i x the hook errors' rise

        def worst(t):
            values = al + t[:, None, None] * be
            if reserve:
                return row_max(values + lift).max(axis=1)
            if pair is None:
                return row_spread(values).max(axis=1)
            return _worst_pairs(values, pair)

        lipschitz = np.abs(be).max(axis=(1, 2)) if reserve else row_spread(be).max(axis=1)
        bound[ok] = _golden(worst, lo[ok], hi[ok], lipschitz)
    return bound, reason


def _screen_pairs(
    particular,
    a_level,
    heights,
    q,
    gain,
    inside,
    limits,
    weight,
    scale,
    hook,
    preload_range,
    reserve=False,
    dual=False,
    target=np.inf,
    defer=None,
    order=None,
):
    """n >= 5: the pair bound, or with ``dual`` the preload LP's dual bound (``defer``,
    ``order``: as :func:`_screen_chunk`)."""
    count, m, n = q.shape
    reason = np.where(inside, FEASIBLE, CG_OUTSIDE)
    reason = np.where(inside & (weight > limits[1].sum(axis=1)), LEVEL_SWL, reason)
    reason = np.where((reason == FEASIBLE) & (weight > limits[2].sum(axis=1)), CODE_MARGIN, reason)
    ok = reason == FEASIBLE
    bound = np.full(count, np.inf)
    deferred = np.zeros(count, dtype=bool)
    if not np.any(ok):
        if defer is not None:
            defer &= deferred
        return bound, reason
    part, P, qq, z = particular[ok], gain[ok], q[ok], heights[ok]
    null = np.linalg.svd(a_level[ok])[2][:, 3:, :].transpose(0, 2, 1)  # (N, n, n-3)
    alpha = np.einsum("kmij,kj->kmi", P, part) + qq
    w = np.einsum("kij,ki->kj", null, z)  # Z = z . T* = z . T0 + w . t
    ww = np.einsum("kj,kj->k", w, w)
    change = np.einsum("kmij,kjr->kmir", P, null) - null[:, None]  # = E_k w^T
    with np.errstate(divide="ignore", invalid="ignore"):
        e_vec = np.einsum("kmir,kr->kmi", change, w) / ww[:, None, None]
    coplanar = ww < 1e-18 * np.max(np.abs(z), axis=1) ** 2 + 1e-300
    e_vec[coplanar] = 0.0
    first, second = np.triu_indices(n, 1)
    sc = scale[ok][:, None, :]
    alpha, e_vec = sc * alpha, sc * e_vec  # the objective's s_i T_i (T* cancels as before)
    g = alpha[..., first] - alpha[..., second]  # (N, m, pairs)
    h = e_vec[..., first] - e_vec[..., second]
    z_fixed = np.einsum("ki,ki->k", z, part)
    lo = weight * z.min(axis=1) - z_fixed
    hi = weight * z.max(axis=1) - z_fixed
    lo = np.where(coplanar, 0.0, lo)
    hi = np.where(coplanar, 0.0, hi)

    if not dual:
        # the hook errors' widening of each pair, both ways (symmetric: (a, b) as (b, a))
        up = down = 0.0 if hook is None else hook[1].subset(ok).upper_triangle()

        def half_range(u, widen=True):
            # spread_k >= d_k + c + up_k and >= -(d_k + c) + down_k for the pair's unknown
            # preload offset c; the least over c of the largest is half their sum
            values = g + u[:, None, None] * h
            if not widen:
                return 0.5 * (values.max(axis=1) - values.min(axis=1)).max(axis=1)
            return 0.5 * ((values + up).max(axis=1) + (down - values).max(axis=1)).max(axis=1)

        lipschitz = 0.5 * np.ptp(h, axis=1).max(axis=1)
        bound[ok], where = _golden(half_range, lo, hi, lipschitz, where=True)
        bound[ok] = np.maximum(bound[ok], 0.0)
        if hook is not None and order is not None:  # the order: the bound without the widening
            order[ok] = half_range(where, widen=False)
        return bound, reason
    # the LP over the screening scenarios, bounded through its dual (planner/search/dual.py)
    big = 100.0 * weight  # as the LP clips "no limit"
    low = np.clip(np.maximum(preload_range[0][ok], limits[0]), -big, big)
    high = np.clip(np.minimum(np.minimum(preload_range[1][ok], limits[1][ok]), weight), -big, big)
    beta = np.einsum("kmij,kjd->kmid", P, null) * sc[..., None]
    tension_limits = (sc * limits[0], sc * limits[1][ok][:, None, :])
    # no feasible preload has a worse value than the limits allow: a bound past that proves
    # the set infeasible and needs no refining, plan or no plan
    target = np.minimum(target, value_ceiling(sc[:, 0, :], limits[1][ok], limits[0], reserve))
    pair = None
    if hook is not None:  # the hook errors, exact: on the limits, and each pair's widening
        margin = sc * hook[0][ok]
        tension_limits = (tension_limits[0] + margin, tension_limits[1] - margin)
        if reserve:
            alpha = alpha + margin
        else:
            pair = hook[1].subset(ok)
    # the caller keeps the larger of this and the pair bound
    bound[ok], deferred[ok] = staged_lp_bound(
        part,
        null,
        alpha,
        beta,
        low,
        high,
        tension_limits,
        reserve,
        target,
        pair,
        False if defer is None else defer[ok],
    )
    if defer is not None:
        defer &= deferred
    return bound, reason
