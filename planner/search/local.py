"""Local search over lug sets: many lifting points, where no enumeration can run.

26 lifting points among 80 candidates is C(80, 26) ~ 1e20 sets. The local search starts from
an even spread of the candidates round the CG (farthest-point order, so the lugs' polygon is
as wide as the candidates allow) and moves to the best set one swap away (one chosen
candidate for one unchosen) while that lowers the preload LP over the box corners and the CG
vertices, bounded through its dual for all the swaps at once
(:func:`~liftplan.planner.search.screen.screen` with ``dual=True``; a swap whose bound cannot
beat the current set stops early). The set it ends on is then evaluated exactly
(:class:`~liftplan.planner.search.evaluator.SetEvaluator`: the LP on a growing scenario list and
the dense check of the whole box).

It does so from the even spread and from RESTARTS perturbations of it (a third of the
candidates swapped at random, seeded) and keeps the best. The result is a local optimum:
good, not proved best; the plan states the lower bound that holds for every set (README
"Two lug lines") and says so (``search.stopped = "local"``).

Lugs in one body plane on equal ropes (:mod:`~liftplan.planner.search.coplanar`, no hook
tolerance): each swap that the screening bound does not rule out is ranked by the exact LP
over the screening's scenarios (:class:`~liftplan.planner.search.coplanar.PlaneLP` on the
corners they span; in order of the screening bound, a lower bound of it, so the best swap is
found without solving the rest), and candidates on
two lines add a first start: lugs at both ends of each line (:func:`line_starts`), the layout
that resists the CG's moves along the lines best; the perturbations are then of it.
"""

from __future__ import annotations

import math
import time

import numpy as np

from liftplan.model.errors import PlanInfeasible
from liftplan.planner.search.budget import Budget
from liftplan.planner.search.coplanar import PlaneLP, coplanar
from liftplan.planner.search.evaluator import (
    Interrupted,
    SearchStats,
    SetEvaluator,
    SetInfeasible,
)
from liftplan.planner.search.line_cells import applies, cell_bound
from liftplan.planner.search.lines import count_bounds, line_bound, two_lines
from liftplan.planner.search.progress import BAR_FORMAT, best_bound, phase, progress_bar
from liftplan.planner.search.scenarios import Scenario, box_attitudes, first_scenarios
from liftplan.planner.search.screen import FEASIBLE, REASONS, screen

#: Improvement below which a swap is not taken (relative to the current value).
IMPROVEMENT = 1e-6
#: Starts besides the even spread: each a perturbation of it (seeded).
RESTARTS = 3


def spread_start(problem, count=None):
    """An even spread of ``count`` candidates round the CG, candidate indices ascending.

    Farthest-point order from the candidate farthest from the CG in plan: each next candidate
    is the one farthest from those already taken, so the set spans the candidates' footprint.
    """
    count = problem.cranes if count is None else count
    plan = problem.plan_points
    cog = np.asarray(problem.body.cog[:2], dtype=float)
    taken = [int(np.argmax(np.linalg.norm(plan - cog, axis=1)))]
    distance = np.linalg.norm(plan - plan[taken[0]], axis=1)
    while len(taken) < count:
        k = int(np.argmax(distance))
        taken.append(k)
        distance = np.minimum(distance, np.linalg.norm(plan - plan[k], axis=1))
    return tuple(sorted(taken))


def line_starts(problem, spread=2):
    """Lugs at both ends of each of two lines: candidate sets (indices ascending), or [] if
    the candidates are not on two lines.

    The count on each line is the one with the least two-line bound. Line j takes k_j
    stations from one end and the rest from the other; k_j* brings the line's mean along it
    nearest the CG's, and every k_j within ``spread`` of it is returned.
    """
    lines = two_lines(problem)
    if lines is None:
        return []
    bounds = count_bounds(problem, lines, first_scenarios(problem))
    if not np.any(np.isfinite(bounds)):
        return []
    n0 = int(np.argmin(bounds))
    points = np.asarray(problem.points, dtype=float)
    along = points @ lines.direction
    target = float(np.asarray(problem.body.cog, dtype=float) @ lines.direction)
    options = []
    for line, count in ((0, n0), (1, problem.cranes - n0)):
        members = np.flatnonzero(lines.line == line)
        members = members[np.argsort(along[members], kind="stable")]
        ends = [np.r_[members[:k], members[len(members) - count + k :]] for k in range(count + 1)]
        best = min(range(count + 1), key=lambda k: abs(float(along[ends[k]].mean()) - target))
        options.append([ends[k] for k in range(max(0, best - spread), min(count, best + spread) + 1)])
    return [tuple(sorted(int(i) for i in np.r_[a, b])) for a in options[0] for b in options[1]]


class SwapsInterrupted(KeyboardInterrupt):
    """Ctrl-C during the swaps: ``indices`` is the best set reached so far (None when no
    start was feasible yet), ``value`` its screening value, ``moves`` the swaps taken."""

    def __init__(self, indices, value, moves):
        super().__init__("local search interrupted")
        self.indices, self.value, self.moves = indices, value, moves


def swaps(current, count):
    """Every set one swap away from ``current`` (ascending indices), shape (n (C - n), n)."""
    chosen = np.array(current)
    free = np.setdiff1d(np.arange(count), chosen)
    out = np.repeat(chosen[None, :], len(chosen) * len(free), axis=0)
    rows = np.arange(len(out))
    out[rows, np.repeat(np.arange(len(chosen)), len(free))] = np.tile(free, len(chosen))
    return np.sort(out, axis=1)


def local_search(
    problem,
    start=None,
    time_limit=None,
    max_moves=200,
    restarts=None,
    seed=0,
    work_limit=None,
    progress=False,
):
    """The best set one swap at a time (module docstring), from several starts; equal cranes.

    Parameters
    ----------
    problem : PlanProblem
    start : sequence of int, optional
        Candidate indices to start from (default :func:`spread_start`).
    time_limit : float, optional  [s]
        Stop moving after this long (the best set reached is still evaluated exactly).
    work_limit : int, optional
        Stop moving after this many swaps over all starts (a count: the same set on any
        machine).
    max_moves : int
        Swaps per start at most.
    restarts : int, optional
        Further starts, each the first start with a third of its candidates swapped for
        others at random (seeded), default :data:`RESTARTS`.
    seed : int
    progress : bool, optional
        A progress line on stderr (:mod:`~liftplan.planner.search.progress`; None: when
        stderr is a terminal): starts done, best value, swaps.

    Returns
    -------
    indices : tuple of int
        The best set reached.
    moves : int
        Swaps taken over all starts.
    bound : float
        The value the moves lowered: its exact LP over the screening scenarios on the plane
        model (coplanar lugs, no hook tolerance), else its LP bound over them.

    Raises
    ------
    PlanInfeasible
        Every start and every swap from them are infeasible.
    SwapsInterrupted
        Ctrl-C: with the best set reached so far.
    """
    if not problem.equal_cranes:
        raise PlanInfeasible(
            "the local search plans a fleet of equal cranes only; give the "
            "cranes one [crane] table, or fewer candidates for the exact search"
        )
    budget = Budget.of(time_limit, work_limit)
    count, n = len(problem.candidates), problem.cranes
    first = tuple(sorted(start)) if start is not None else spread_start(problem)
    rng = np.random.default_rng(seed)
    plane = _plane_lp(problem)
    lined = line_starts(problem) if start is None and plane is not None else []
    if lined:  # the two best end layouts first; the perturbations are of the best
        lined = sorted(lined, key=plane.value)[:2]
        first = lined[0]
    starts = lined + [first if not lined else spread_start(problem)]
    for _ in range(RESTARTS if restarts is None else restarts):
        kept = rng.choice(first, n - max(1, n // 3), replace=False)
        others = np.setdiff1d(np.arange(count), kept)
        starts.append(tuple(sorted(np.r_[kept, rng.choice(others, n - len(kept), replace=False)].tolist())))
    best, moves, reason = (None, math.inf), 0, None
    starts = list(dict.fromkeys(starts))  # a repeated start is run once
    bar = progress_bar(len(starts), progress, desc="local search: swaps", unit="starts", ticker=True)

    def seen(current, value, taken):  # each swap taken: the line shows the best so far
        if bar is not None:
            low = min(value, best[1])
            shown = low if math.isfinite(low) else None
            count = moves + taken
            bar.set_postfix_str(best_bound(shown, None, f"{count} swap{'' if count == 1 else 's'}"))

    try:
        for begin in starts:
            if budget.out() and best[0] is not None:
                break
            try:
                current, value, taken, why = _descend(problem, begin, budget, max_moves, plane, seen)
            except SwapsInterrupted as stop:  # the descent's set so far against the best
                if stop.indices is not None and stop.value < best[1]:
                    best = (stop.indices, stop.value)
                raise SwapsInterrupted(best[0], best[1], moves + stop.moves) from None
            moves += taken
            reason = reason or why
            if value < best[1]:
                best = (current, value)
            if bar is not None:
                bar.update(1)
    except KeyboardInterrupt as err:
        if isinstance(err, SwapsInterrupted):
            raise
        raise SwapsInterrupted(best[0], best[1], moves) from None
    finally:
        if bar is not None:
            bar.close()
    if best[0] is None:
        raise PlanInfeasible(
            f"the local search found no feasible set one swap from its starts "
            f"({reason}); expected more candidates round the CG or fewer cranes"
        )
    return best[0], moves, best[1]


def _plane_lp(problem):
    """:class:`PlaneLP` where the plane model is exact, else None. Its scenarios are the
    screening's (the 3 x 3 box grid at every CG vertex), so a swap's screening bound is a
    lower bound of its exact value and the swaps it rules out need no LP."""
    if (
        coplanar(problem) is None
        or problem.hook_tolerance > 0
        or any(c.hook_tolerance for c in problem.fleet)
    ):
        return None
    grid = box_attitudes(problem, 3, 3)
    return PlaneLP(
        problem,
        [
            Scenario(float(h), float(t), tuple(float(v) for v in o))
            for o in problem.cog_envelope.offsets()
            for h, t in grid
        ],
    )


def _descend(problem, current, budget, max_moves, plane=None, seen=None):
    """Swaps from one start while they lower the value: (set, value, swaps, why not).

    The value is the screening bound, or with ``plane`` its exact LP over the same scenarios.
    ``seen(set, value, swaps)`` is called after each swap. Ctrl-C raises
    :class:`SwapsInterrupted` with the set reached (None before the start was screened).
    """
    count = len(problem.candidates)
    value, moves = math.inf, 0
    try:
        first = screen(problem, np.array([current]), dual=True)
        start_value = float(first.bound[0]) if first.reason[0] == FEASIBLE else math.inf
        why = None if first.reason[0] == FEASIBLE else REASONS.get(int(first.reason[0]))
        if plane is not None and math.isfinite(start_value):
            start_value = plane.value(current)
        value = start_value
        while moves < max_moves:
            if budget.out():
                break
            near = swaps(current, count)
            target = value * (1.0 - IMPROVEMENT) if math.isfinite(value) else math.inf
            found = screen(problem, near, dual=True, target=target)
            ok = np.flatnonzero((found.reason == FEASIBLE) & (found.bound < target))
            if not len(ok):
                break
            if plane is None:
                k = int(ok[np.argmin(found.bound[ok])])
                best = float(found.bound[k])
            else:  # exact values in order of the bound, until the bound passes the best found
                k, best = None, target
                for j in ok[np.argsort(found.bound[ok], kind="stable")]:
                    if found.bound[j] >= best or budget.out() == "time_limit":
                        break
                    exact = plane.value(near[j])
                    if exact < best:
                        k, best = int(j), exact
                if k is None:
                    break
            current, value = tuple(int(i) for i in near[k]), best
            moves += 1
            budget.spend()
            if seen is not None:
                seen(current, value, moves)
    except KeyboardInterrupt:
        raise SwapsInterrupted(current if math.isfinite(value) else None, value, moves) from None
    return current, value, moves, why


def search_local(problem, started, top=1, progress=None):
    """:func:`~liftplan.planner.search.local.local_search`, its set evaluated exactly, and the
    lower bound that holds for every set: the two-line bound, refined cell by cell where the
    lugs are stations on two lines in one plane (:mod:`~liftplan.planner.search.line_cells`)
    towards the plan's value less the gap aimed at. With a time limit the search takes half of
    it and the bound the rest. Ctrl-C keeps a plan (:class:`Interrupted`): during the swaps the
    best set reached so far, checked over the box (a second Ctrl-C stops at once, without a
    plan); during the bound the plan with the bound so far. One plan: ``top`` is not used."""

    limit, work = problem.time_limit, problem.work_limit
    swap_work = None if work is None else max(1, work // 2)  # half for the swaps, half for the cells
    interrupted = None  # the phase Ctrl-C ended: the plan is then the best set so far, checked
    try:
        indices, moves, _ = local_search(
            problem,
            time_limit=None if limit is None else 0.5 * limit,
            work_limit=swap_work,
            progress=progress,
        )
    except SwapsInterrupted as stop:
        if stop.indices is None:  # no feasible set reached yet
            raise Interrupted([], None, phase="local search: swaps") from None
        indices, moves, interrupted = stop.indices, stop.moves, "local search: swaps"
    stopped = "work_limit" if swap_work is not None and moves >= swap_work else "local"
    evaluator = SetEvaluator(problem)
    what = "local search: checking its set over the box"
    try:
        with phase(what, progress):
            result = _checked_set(problem, evaluator, indices, moves)
    except KeyboardInterrupt:
        if interrupted is not None:  # a second Ctrl-C: stop at once
            raise
        interrupted = what  # the swaps had ended: their set is the plan, checked once more
        with phase(what, progress):
            result = _checked_set(problem, evaluator, indices, moves)
    if problem.goal.peak:  # every rope shares W: max T_i / SWL_i >= W / sum SWL
        bound = problem.body.weight / float(np.sum(result.swl))
    else:  # candidates on two lines: what each line carries is fixed by the statics
        try:
            with phase("local search: two-line bound", progress, best_bound(result.worst_value)):
                bound = line_bound(problem, evaluator.dense)
        except KeyboardInterrupt:
            if interrupted is not None:
                raise
            interrupted, bound = "local search: two-line bound", 0.0  # no bound but the trivial one
    if interrupted is not None:
        raise Interrupted(
            [result], _local_stats(problem, started, moves, bound, result, "interrupted"), phase=interrupted
        )
    if not problem.goal.peak and applies(problem) and bound < result.worst_value:
        deadline = None if limit is None else started + limit
        target = result.worst_value * (1.0 - problem.gap * (1.0 - 1e-9))  # gap <= target
        bar = progress_bar(None, progress, desc="local search: bound by cells", unit="cells", ticker=True)
        best, line = result.worst_value, bound

        def tick(done, total, low):
            if bar is not None:
                bar.total, bar.n, bar.bar_format = total, done, BAR_FORMAT
                bar.set_postfix_str(best_bound(best, low), refresh=False)

        cell_work = None if work is None else max(1, work - swap_work)
        try:
            cells = cell_bound(problem, evaluator.dense, target, deadline, tick, work=cell_work)
        except KeyboardInterrupt:  # outside a cell (between counts): the two-line bound
            raise Interrupted(
                [result],
                _local_stats(problem, started, moves, line, result, "interrupted"),
                phase="local search: bound by cells",
            ) from None
        finally:
            if bar is not None:
                bar.close()
        bound = max(bound, cells.value)
        if cells.interrupted:  # Ctrl-C: the plan, with the bound so far
            raise Interrupted(
                [result],
                _local_stats(problem, started, moves, bound, result, "interrupted"),
                phase="local search: bound by cells",
            )
        if not cells.complete:  # a limit left cells open: which one
            ran_out = cell_work is not None and cells.searched >= cell_work
            stopped = "work_limit" if ran_out else "time_limit"
    return [result], _local_stats(problem, started, moves, bound, result, stopped)


def _checked_set(problem, evaluator, indices, moves):
    """The local search's set evaluated exactly (:class:`SetResult`)."""
    try:
        return evaluator.evaluate(indices)
    except SetInfeasible as err:
        raise PlanInfeasible(
            f"the local search ended on {', '.join(problem.names[i] for i in indices)}"
            f" after {moves} swaps, which is infeasible over the box: "
            f"{REASONS[err.code]}"
        ) from None


def _local_stats(problem, started, moves, bound, result, stopped):
    """:class:`SearchStats` of a local search's plan."""
    return SearchStats(
        sets=problem.set_count,
        screened_out=0,
        evaluated=1,
        pruned=0,
        seconds=time.perf_counter() - started,
        rows=problem.set_count,
        refined=moves,
        lower_bound=min(bound, result.worst_value),
        best=result.worst_value,
        stopped=stopped,
        method="local",
    )
