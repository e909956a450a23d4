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
candidates swapped at random, seeded) and keeps the best.

A fleet of unequal cranes (each at its position, with its chart) moves a (set, assignment)
row: a swap hands the leaving lug's crane to the candidate that comes in, and an exchange
swaps two lugs' cranes; rows a crane cannot reach or whose booms clash
(:mod:`~liftplan.planner.problem.clearance`) are never taken. A start's cranes are assigned
for the most chart SWL over its lugs (:func:`assign`). The result is a local optimum:
good, not proved best; the plan states the lower bound that holds for every set (README
"Two lug lines") and says so (``search.stopped = "local"``).

Lugs in one body plane on equal ropes (:mod:`~liftplan.planner.search.coplanar`, no hook
tolerance): each swap that the screening bound does not rule out is ranked by the exact LP
over the screening's scenarios (:class:`~liftplan.planner.search.coplanar.PlaneLP` on the
corners they span; in order of the screening bound, a lower bound of it, so the best swap is
found without solving the rest), and candidates on
two lines add a first start: lugs at both ends of each line (:func:`line_starts`), the layout
that resists the CG's moves along the lines best; the perturbations are then of it.

With a weight curve and ``[strength]`` the hull girder is in the moves
(:mod:`~liftplan.planner.search.local_girder`): rows rank as the exact search's ranking does,
those that keep the girder first, then the objective. A necessary screen keeps the swaps that
overload it whatever their preload out of the moves; each descent's end is checked exactly
(the plan's own check), best first, and one that overloads the girder is left for its best
swap that keeps it (else the one that overloads it least), the descent going on from there
(:func:`_keep_girder`).
"""

from __future__ import annotations

import heapq
import math
import time

import numpy as np

from liftplan.model.errors import PlanInfeasible
from liftplan.planner.problem.clearance import clear, segment_distance
from liftplan.planner.search.budget import Budget
from liftplan.planner.search.coplanar import PlaneLP, coplanar
from liftplan.planner.search.evaluator import (
    Interrupted,
    SearchStats,
    SetEvaluator,
    SetInfeasible,
)
from liftplan.planner.search.girder import applies as girder_applies
from liftplan.planner.search.line_cells import applies, cell_bound
from liftplan.planner.search.lines import count_bounds, line_bound, two_lines
from liftplan.planner.search.local_girder import LocalGirder
from liftplan.planner.search.progress import BAR_FORMAT, best_bound, phase, progress_bar
from liftplan.planner.search.scenarios import Scenario, box_attitudes, first_scenarios
from liftplan.planner.search.screen import FEASIBLE, REASONS, screen

#: Improvement below which a swap is not taken (relative to the current value).
IMPROVEMENT = 1e-6
#: Starts besides the even spread: each a perturbation of it (seeded).
RESTARTS = 3
#: The same for a fleet of unequal cranes, whose (set, assignment) landscape has more local
#: optima (tanker_fleet.toml: 3 perturbed starts end 13 % above the optimum, 10 find it).
FLEET_RESTARTS = 12
#: Descents from an end set that overloads the hull girder, over all starts (each one asks
#: the exact girder check of up to REPAIR_TRIES swaps, best value first, until one keeps it).
MAX_REPAIRS = 8
REPAIR_TRIES = 32


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
    """Ctrl-C during the swaps: ``row`` is the best (set, cranes) reached so far (None when no
    start was feasible yet), ``value`` its screening value, ``moves`` the swaps taken."""

    def __init__(self, row, value, moves):
        super().__init__("local search interrupted")
        self.row, self.value, self.moves = row, value, moves

    @property
    def indices(self):
        """The best set reached (candidate indices), or None."""
        return None if self.row is None else self.row[0]


def swaps(current, count):
    """Every set one swap away from ``current`` (ascending indices), shape (n (C - n), n)."""
    chosen = np.array(current)
    free = np.setdiff1d(np.arange(count), chosen)
    out = np.repeat(chosen[None, :], len(chosen) * len(free), axis=0)
    rows = np.arange(len(out))
    out[rows, np.repeat(np.arange(len(chosen)), len(free))] = np.tile(free, len(chosen))
    return np.sort(out, axis=1)


def assign(problem, indices):
    """Cranes for a set of lugs (fleet indices, one per lug, in the set's order): the
    assignment with the most chart SWL over the lugs that every crane can reach (scipy's
    linear assignment), or None when no assignment reaches every lug. Equal cranes: the
    identity."""
    n = len(indices)
    if problem.equal_cranes:
        return tuple(range(n))
    pairs = _most_swl(problem.reach[1][list(indices)])  # (n, m), NaN out of reach
    if pairs is None:
        return None
    out = np.empty(n, dtype=np.int64)
    out[pairs[0]] = pairs[1]
    return tuple(int(j) for j in out)


def reach_start(problem):
    """A set every crane of a fleet reaches: each crane on a candidate of its own, the most
    chart SWL over them (scipy's linear assignment over candidates x cranes), indices
    ascending; None when no such set exists."""
    pairs = _most_swl(problem.reach[1])
    return None if pairs is None else tuple(sorted(int(i) for i in pairs[0]))


def _most_swl(swl):
    """(rows, cranes) of the assignment with the most chart SWL in ``swl`` (rows x cranes,
    NaN out of reach), or None when some crane or row must take one out of reach."""
    from scipy.optimize import linear_sum_assignment  # noqa: PLC0415 (only fleets need it)

    rows, cranes = linear_sum_assignment(np.where(np.isnan(swl), 1e12, -np.nan_to_num(swl)))
    return None if np.any(np.isnan(swl[rows, cranes])) else (rows, cranes)


def neighbours(problem, indices, cranes):
    """Every row one move from (``indices``, ``cranes``) that every crane reaches with its
    booms clear: (sets (N, n), cranes (N, n)), each set ascending with its cranes alongside.

    Equal cranes: the swaps (:func:`swaps`), cranes the identity. A fleet: each swap keeps the
    leaving lug's crane on the candidate that comes in (alone, and with each exchange of two
    lugs' cranes: a crane that suits the new lug better takes it), and each exchange alone.
    """
    n, count = len(indices), len(problem.candidates)
    if problem.equal_cranes:
        sets = swaps(indices, count)
        return sets, np.broadcast_to(np.arange(n, dtype=np.int64), sets.shape)
    chosen, crane = np.array(indices), np.array(cranes)
    free = np.setdiff1d(np.arange(count), chosen)
    sets = np.repeat(chosen[None, :], n * len(free), axis=0)
    sets[np.arange(len(sets)), np.repeat(np.arange(n), len(free))] = np.tile(free, n)
    fleet = np.repeat(crane[None, :], len(sets), axis=0)
    pairs = [(i, j) for i in range(n) for j in range(i + 1, n)]
    moved = [fleet]
    for i, j in pairs:
        moved.append(fleet.copy())
        moved[-1][:, [i, j]] = fleet[:, [j, i]]
    exchanged = np.repeat(crane[None, :], len(pairs), axis=0)
    for k, (i, j) in enumerate(pairs):
        exchanged[k, [i, j]] = crane[[j, i]]
    sets = np.concatenate([sets] * len(moved) + [np.repeat(chosen[None, :], len(pairs), axis=0)])
    fleet = np.concatenate([*moved, exchanged])
    order = np.argsort(sets, axis=1)
    sets, fleet = np.take_along_axis(sets, order, 1), np.take_along_axis(fleet, order, 1)
    keep = buildable(problem, sets, fleet)
    return sets[keep], fleet[keep]


def buildable(problem, sets, cranes):
    """(N,) True where every crane of a row reaches its lug and no two booms clash."""
    swl = problem.reach[1]
    ok = ~np.any(np.isnan(swl[sets, cranes]), axis=1)
    positions = [c.position for c in problem.fleet]
    if sum(p is not None for p in positions) < 2:
        return ok
    xy = np.array([(np.nan, np.nan) if p is None else p for p in positions], dtype=float)
    tips = problem.plan_points
    for i in range(sets.shape[1]):
        for j in range(i + 1, sets.shape[1]):
            d = segment_distance(xy[cranes[:, i]], tips[sets[:, i]], xy[cranes[:, j]], tips[sets[:, j]])
            ok &= np.isnan(d) | clear(d, problem.crane_clearance)  # NaN: a crane without position
    return ok


def local_search(
    problem,
    start=None,
    time_limit=None,
    max_moves=200,
    restarts=None,
    seed=0,
    work_limit=None,
    progress=False,
    girder=None,
):
    """The best set one swap at a time (module docstring), from several starts.

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
        others at random (seeded), default :data:`RESTARTS` (:data:`FLEET_RESTARTS` for
        unequal cranes).
    seed : int
    progress : bool, optional
        A progress line on stderr (:mod:`~liftplan.planner.search.progress`; None: when
        stderr is a terminal): starts done, best value, swaps.
    girder : LocalGirder or False, optional
        The hull girder in the moves (:mod:`~liftplan.planner.search.local_girder`): with a
        weight curve and ``[strength]`` (default: one on a new evaluator), the swaps that
        overload it are not taken over those that keep it, and the set returned is the best
        reached that keeps it. False: the objective alone (for comparison).

    Returns
    -------
    indices : tuple of int
        The best set reached.
    moves : int
        Swaps taken over all starts.
    bound : float
        The value the moves lowered: its exact LP over the screening scenarios on the plane
        model (coplanar lugs, no hook tolerance), else its LP bound over them.
    cranes : tuple of int
        The fleet index of the crane on each lug of ``indices`` (equal cranes: the identity).

    Raises
    ------
    PlanInfeasible
        Every start and every swap from them are infeasible.
    SwapsInterrupted
        Ctrl-C: with the best set reached so far.
    """
    budget = Budget.of(time_limit, work_limit)
    count, n = len(problem.candidates), problem.cranes
    first = tuple(sorted(start)) if start is not None else spread_start(problem)
    rng = np.random.default_rng(seed)
    plane = _plane_lp(problem) if problem.equal_cranes else None
    lined = line_starts(problem) if start is None and plane is not None else []
    if lined:  # the two best end layouts first; the perturbations are of the best
        lined = sorted(lined, key=plane.value)[:2]
        first = lined[0]
    starts = lined + [first if not lined else spread_start(problem)]
    if start is None and not problem.equal_cranes and assign(problem, first) is None:
        # the even spread has a lug no crane of the fleet reaches: start where they reach
        first = reach_start(problem) or first
        starts.insert(0, first)
    if restarts is None:
        restarts = RESTARTS if problem.equal_cranes else FLEET_RESTARTS
    for _ in range(restarts):
        kept = rng.choice(first, n - max(1, n // 3), replace=False)
        others = np.setdiff1d(np.arange(count), kept)
        starts.append(tuple(sorted(np.r_[kept, rng.choice(others, n - len(kept), replace=False)].tolist())))
    if girder is None and girder_applies(problem):
        girder = LocalGirder(problem, SetEvaluator(problem))
    girder = girder or None
    best, moves, reason, ends = (None, math.inf), 0, None, []
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
            cranes = assign(problem, begin)
            if cranes is None:  # no crane of the fleet reaches one of its lugs
                reason = reason or "a start's lug is out of every crane's reach"
                continue
            try:
                current, value, taken, why = _descend(
                    problem, (begin, cranes), budget, max_moves, plane, seen, girder
                )
            except SwapsInterrupted as stop:  # the descent's set so far against the best
                if stop.row is not None and stop.value < best[1]:
                    best = (stop.row, stop.value)
                raise SwapsInterrupted(best[0], best[1], moves + stop.moves) from None
            moves += taken
            reason = reason or why
            if value < best[1]:
                best = (current, value)
            if math.isfinite(value):
                ends.append((current, value))
            if bar is not None:
                bar.update(1)
        if girder is not None and ends:  # the ends checked exactly, best first (local_girder)
            try:
                best, taken, _ = _keep_girder(problem, ends, budget, max_moves, plane, seen, girder)
            except SwapsInterrupted as stop:  # during a descent from an end: the best end so far
                raise SwapsInterrupted(best[0], best[1], moves + stop.moves) from None
            moves += taken
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
    (indices, cranes), value = best
    return indices, moves, value, cranes


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


def _descend(problem, current, budget, max_moves, plane=None, seen=None, girder=None, repair=False):
    """Moves from one start row (set, cranes) while they lower the value: (row, value,
    moves, why not).

    The value is the screening bound, or with ``plane`` its exact LP over the same scenarios.
    ``seen(row, value, moves)`` is called after each move. With ``girder``
    (:class:`~liftplan.planner.search.local_girder.LocalGirder`) the swaps its screen rules out
    or its exact check found to overload are never taken; ``repair``: the start overloads the
    girder, so the first move is to the best swap that keeps it (its exact check, whatever its
    value), and none is taken when no swap keeps it. Ctrl-C raises :class:`SwapsInterrupted`
    with the row reached (None before the start was screened).
    """
    value, moves = math.inf, 0
    try:
        if not buildable(problem, np.array([current[0]]), np.array([current[1]]))[0]:
            first = None  # the start's booms clash: any buildable row one move away is better
        else:
            first = screen(problem, np.array([current[0]]), np.array([current[1]]), dual=True)
        if first is None:
            start_value, why = math.inf, "a start's booms clash"
        else:
            start_value = float(first.bound[0]) if first.reason[0] == FEASIBLE else math.inf
            why = None if first.reason[0] == FEASIBLE else REASONS.get(int(first.reason[0]))
        if plane is not None and math.isfinite(start_value):
            start_value = plane.value(current[0])
        value = start_value
        while moves < max_moves:
            if budget.out():
                break
            near, near_cranes = neighbours(problem, *current)
            if not len(near):
                break
            # an overloaded start: any swap that keeps the girder is better, whatever its value
            target = value * (1.0 - IMPROVEMENT) if math.isfinite(value) and not repair else math.inf
            found = screen(problem, near, near_cranes, dual=True, target=target)
            ok = np.flatnonzero((found.reason == FEASIBLE) & (found.bound < target))
            if girder is not None and len(ok):
                ok = ok[girder.allowed(near[ok], near_cranes[ok])]
            if not len(ok):
                break
            order = ok[np.argsort(found.bound[ok], kind="stable")]
            rows = (near, near_cranes, found.bound)
            if repair:  # exact girder checks: the best swap that keeps it, else the least overload
                k, best, repair = _repair_swap(rows, order, plane, girder, girder.verdict(current).ratio)
            else:  # the bound is the value, or (plane) exact values in order of the bound
                k, best = _best_swap(rows, order, plane, budget, target)
            if k is None:
                break
            current, value = (tuple(int(i) for i in near[k]), tuple(int(j) for j in near_cranes[k])), best
            moves += 1
            budget.spend()
            if seen is not None:
                seen(current, value, moves)
    except KeyboardInterrupt:
        raise SwapsInterrupted(current if math.isfinite(value) else None, value, moves) from None
    return current, value, moves, why


def _best_swap(rows, order, plane, budget, best):
    """The swap with the least value below ``best``: (index or None, its value).

    ``rows`` is (sets, cranes, screening bound) of the swaps, ``order`` the ones to ask in
    ascending bound. The value is the bound, or with ``plane`` its exact LP (asked in order of
    the bound, a lower bound of it, until the bound passes the best found).
    """
    sets, _, bound = rows
    k = None
    for j in order:
        if bound[j] >= best or (k is not None and budget.out() == "time_limit"):
            break
        exact = float(bound[j]) if plane is None else plane.value(sets[j])
        if exact < best:
            k, best = int(j), exact
    return k, best


def _repair_swap(rows, order, plane, girder, ratio):
    """The swap out of a row that overloads the hull girder (its largest ratio ``ratio``):
    (index or None, its value, still overloaded).

    Up to :data:`REPAIR_TRIES` swaps in ascending bound (``rows``, ``order`` and ``plane`` as
    :func:`_best_swap`) are checked exactly: the one of least value that keeps the girder
    (asking stops once the bound passes its value), else the one of least girder ratio when
    below ``ratio`` (the overload shrinks: a step towards a set that keeps the girder).
    """
    sets, cranes, bound = rows
    keeper, least = (None, math.inf), (None, math.inf, ratio)
    for j in order[:REPAIR_TRIES]:
        if bound[j] >= keeper[1]:
            break
        value = float(bound[j]) if plane is None else plane.value(sets[j])
        verdict = girder.verdict((sets[j], cranes[j]))
        if verdict.keeps and value < keeper[1]:
            keeper = (int(j), value)
        elif verdict.feasible and verdict.ratio < least[2]:
            least = (int(j), value, verdict.ratio)
    if keeper[0] is not None:
        return keeper[0], keeper[1], False
    return least[0], least[1], True


def _keep_girder(problem, ends, budget, max_moves, plane, seen, girder):
    """The best end row that keeps the hull girder (:mod:`.local_girder`): each descent's end,
    best value first, checked exactly; one that overloads the girder is left for its best
    swap that keeps it and the descent goes on from there (its end checked in turn), at most
    :data:`MAX_REPAIRS` times.

    Parameters
    ----------
    ends : list of (row, value)
        The descents' ends.

    Returns
    -------
    best : (row, value)
        The best end checked that keeps the girder, else the best row that keeps it among all
        those checked (by its worst value); else the best feasible end checked (it overloads
        the girder), else the best end.
    moves : int
        Swaps taken from overloaded ends.
    kept : bool
        The girder holds on ``best``.
    """
    heap = [(value, k, row) for k, (row, value) in enumerate(dict(ends).items())]
    heapq.heapify(heap)
    fallback, moves, repairs, count = None, 0, 0, len(heap)
    while heap:
        if fallback is not None and budget.out():  # out of time or work: no more ends checked
            break
        value, _, row = heapq.heappop(heap)
        verdict = girder.verdict(row)
        if verdict.keeps:
            return (row, value), moves, True
        if not verdict.feasible:
            continue
        fallback = fallback or (row, value)
        if repairs >= MAX_REPAIRS:
            continue
        repairs += 1
        end, end_value, taken, _ = _descend(problem, row, budget, max_moves, plane, seen, girder, repair=True)
        moves += taken
        if taken:
            heapq.heappush(heap, (end_value, count, end))
            count += 1
    # a set that keeps the girder passed on the way (a descent from it ended on one that does
    # not): the best of them by its worst value
    kept = [(v.result.worst_value, key) for key, v in girder.verdicts.items() if v.keeps]
    if kept:
        value, row = min(kept)
        return (row, value), moves, True
    return fallback or min(ends, key=lambda e: e[1]), moves, False


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
    evaluator = SetEvaluator(problem)
    girder = LocalGirder.of(problem, evaluator) or False  # its checked sets are the plan's
    try:
        indices, moves, _, cranes = local_search(
            problem,
            time_limit=None if limit is None else 0.5 * limit,
            work_limit=swap_work,
            progress=progress,
            girder=girder,
        )
    except SwapsInterrupted as stop:
        if stop.row is None:  # no feasible set reached yet
            raise Interrupted([], None, phase="local search: swaps") from None
        (indices, cranes), moves, interrupted = stop.row, stop.moves, "local search: swaps"
    stopped = "work_limit" if swap_work is not None and moves >= swap_work else "local"
    what = "local search: checking its set over the box"
    try:
        with phase(what, progress):
            result = _checked_set(problem, evaluator, indices, cranes, moves, girder)
    except KeyboardInterrupt:
        if interrupted is not None:  # a second Ctrl-C: stop at once
            raise
        interrupted = what  # the swaps had ended: their set is the plan, checked once more
        with phase(what, progress):
            result = _checked_set(problem, evaluator, indices, cranes, moves)
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
    if not problem.goal.peak and problem.equal_cranes and applies(problem) and bound < result.worst_value:
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


def _checked_set(problem, evaluator, indices, cranes, moves, girder=False):
    """The local search's set evaluated exactly (:class:`SetResult`): the girder's exact
    check's evaluation when it took one."""
    known = girder.result((indices, cranes)) if girder else None
    if known is not None:
        return known
    try:
        return evaluator.evaluate(indices, cranes)
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
