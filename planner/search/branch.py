"""Branch and bound over lug sets, and the exact evaluation of one set.

1. :func:`~liftplan.planner.search.screen.screen` gives every set a lower bound on its worst
   spread (and rules out the sets it can prove infeasible).
2. Sets are evaluated best bound first. Evaluating a set solves the preload minimax LP
   (cvxpy / Clarabel) on a growing list of scenarios (cutting planes): after each solve the
   held-preload tensions are checked on a dense heel x trim grid (for every CG vertex)
   and around its worst point on two finer grids; the worst or violating scenario found is
   added and the LP solved again, until the search finds nothing worse than the LP.
3. The search stops when the next set's bound is no better than the k-th best worst spread
   found: no set left can enter the top k (every bound is a valid lower bound).
"""

from __future__ import annotations

import heapq
import math
import sys
import time
from collections import Counter
from dataclasses import dataclass, field

import numpy as np

from liftplan.model.errors import PlanInfeasible
from liftplan.planner.problem.definition import MAX_SETS
from liftplan.planner.search.bounds import PreloadMinimax
from liftplan.planner.search.lines import line_bound
from liftplan.planner.search.rows import row_spread
from liftplan.planner.search.scenarios import LugSet, Scenario, box_attitudes
from liftplan.planner.search.screen import (
    BOOM_RANGE,
    BOX_OVERLOAD,
    BOX_SLACK,
    CG_OUTSIDE,
    CODE_MARGIN,
    COLLINEAR,
    FEASIBLE,
    FULL_COLUMNS,
    LEVEL_MIN_TENSION,
    LEVEL_SWL,
    REASONS,
    screen,
    screening_scenarios,
    set_rows,
)

#: Dense check grid: heel x trim points over the box.
DENSE = 21
#: Finer grids around the worst dense point: points per side, and rounds.
ZOOM, ZOOM_ROUNDS = 11, 2
#: Cutting-plane rounds before the evaluation stops (and says so in ``converged``).
MAX_ROUNDS = 12
SLOTS = 9 * 9 + 3 * MAX_ROUNDS


def tolerance(problem):
    """Agreement asked between the LP and the dense search  [t]: 1 kg, or 1e-6 W."""
    return max(1e-3, 1e-6 * problem.body.weight)


class SetInfeasible(PlanInfeasible):
    """One lug set cannot hold the body; ``code`` is a key of :data:`~.screen.REASONS`."""

    def __init__(self, code):
        super().__init__(REASONS[code])
        self.code = code


@dataclass(frozen=True)
class SetResult:
    """A lug set, evaluated.

    Parameters
    ----------
    lugs : tuple of str
        Candidate names, in candidate order.
    indices : tuple of int
    cranes : tuple of int
        Fleet index of the crane on each lug.
    crane_names : tuple of str
    radius : numpy.ndarray  [m]
        Each crane's radius to its lug.
    swl : numpy.ndarray  [t]
        Each crane's SWL at that radius (chart).
    preload : numpy.ndarray  [t]
        Level tensions T* the plan dials in.
    boom_heights : numpy.ndarray  [m]
    nominal_spread : float  [t]
        Spread of T* (level, nominal CG).
    worst_spread : float  [t]
        Largest tension spread found over the box (and CG envelope) with T* held.
    worst : Scenario
        Where the objective's worst value occurs.
    bound : float  [t or -]
        The preload LP's optimum over its scenarios, in the objective's unit: no preload of
        this set and assignment does better.
    screen_bound : float  [t or -]
        The screening bound used to order and prune.
    tension_range : tuple of float  [t]
        Smallest and largest tension anywhere in the box.
    rope_max : numpy.ndarray  [t]
        Each rope's largest tension over the dense box grid and the CG envelope.
    rounds : int
        Cutting-plane rounds.
    converged : bool
        The dense search found nothing worse than the LP (within :func:`tolerance`).
    objective : str
        ``"spread"`` or ``"utilisation"``.
    worst_value : float  [t or -]
        The objective's largest value found over the box: the worst tension spread, or the
        worst max - min of T_i / SWL_i.
    worst_utilisation_spread : float  [-]
        Largest max - min of T_i / SWL_i found over the box.
    nominal_utilisation_spread : float  [-]
        max - min of T*_i / SWL_i at level.
    """

    lugs: tuple[str, ...]
    indices: tuple[int, ...]
    cranes: tuple[int, ...]
    crane_names: tuple[str, ...]
    radius: np.ndarray
    swl: np.ndarray
    preload: np.ndarray
    boom_heights: np.ndarray
    nominal_spread: float
    worst_spread: float
    worst: Scenario
    bound: float
    screen_bound: float
    tension_range: tuple[float, float]
    rope_max: np.ndarray
    rounds: int
    converged: bool
    objective: str = "spread"
    worst_value: float = 0.0
    worst_utilisation_spread: float = 0.0
    nominal_utilisation_spread: float = 0.0

    @property
    def max_utilisation(self):
        """Largest T_i / SWL_i anywhere in the box (dense grid, CG envelope)  [-]."""
        return float(np.max(self.rope_max / self.swl))

    @property
    def nominal_value(self):
        """The objective at level: nominal spread [t], nominal utilisation spread [-], or the
        largest nominal T / SWL [-] (reserve)."""
        if self.objective == "reserve":
            return float(np.max(self.preload / self.swl))
        return self.nominal_spread if self.objective == "spread" else self.nominal_utilisation_spread


class GapMixin:
    """``gap`` and ``relative_gap`` from a dataclass's ``best`` and ``lower_bound``."""

    @property
    def gap(self):
        """Best worst value minus the certified lower bound, in the objective's unit (>= 0)."""
        return max(self.best - self.lower_bound, 0.0)

    @property
    def relative_gap(self):
        """:attr:`gap` over the best worst value  [-]."""
        return self.gap / self.best if self.best > 0 else 0.0


_ENDED = {
    "proved": "optimum proved",
    "gap": "within the gap target",
    "time_limit": "stopped at the time limit",
    "interrupted": "interrupted",
    "rounds": "stopped after its cutting-plane rounds",
}


@dataclass(frozen=True)
class SearchStats(GapMixin):
    """How the search went.

    Parameters
    ----------
    sets : int
        Lug sets in all (each with every crane assignment in reach: see ``rows``).
    screened_out : int
        Proved infeasible by screening.
    evaluated : int
        Evaluated with the LP and the dense search.
    pruned : int
        Never evaluated: their bound could not beat the k-th best.
    infeasible : dict of str to int
        Reasons and counts of every infeasible set found.
    seconds : float  [s]
    rows : int
        (set, crane assignment) pairs searched (equal cranes: one per set).
    out_of_reach : int
        (set, assignment) pairs dropped because a crane cannot reach its lug.
    refined : int
        Rows whose coarse screening bound was replaced by the full one before evaluation.
    lower_bound : float  [t or -]
        Certified: no lug set and assignment does better over the box than this (the least
        of the LP bounds of the rows evaluated and the screening bounds of the rows not).
    best : float  [t or -]
        The plan's worst value of the objective.
    stopped : {"proved", "gap", "time_limit", "interrupted", "local", "rounds"}
        Why the search ended: the top plans proved, the gap target reached, the time limit,
        Ctrl-C, a local optimum of the local search (its lower bound holds for every set but
        is not its value: :mod:`~liftplan.planner.search.lines`,
        :mod:`~liftplan.planner.search.line_cells`, or 0), or the MIP's cutting-plane rounds
        run out (its bound still holds).
    method : {"enumeration", "local", "mip"}
        How the sets were searched (``plan.search``; ``refined`` counts the local search's
        swaps, or the MIP's cutting-plane rounds).
    """

    sets: int
    screened_out: int
    evaluated: int
    pruned: int
    infeasible: dict[str, int] = field(default_factory=dict)
    seconds: float = 0.0
    rows: int = 0
    out_of_reach: int = 0
    refined: int = 0
    lower_bound: float = 0.0
    best: float = math.inf
    stopped: str = "proved"
    method: str = "enumeration"

    @property
    def summary(self):
        """What the search did, in one line."""
        if self.method == "mip":
            return (
                f"{self.sets} lug sets: one mixed-integer program over candidates, cranes and "
                f"scenarios (HiGHS), {self.refined} cutting-plane round"
                f"{'' if self.refined == 1 else 's'}, {self.evaluated} "
                f"sets evaluated, {_ENDED[self.stopped]} ({self.seconds:.2f} s)"
            )
        if self.stopped == "local":
            gap = 100 * self.relative_gap
            text = f"{gap:.2f} %" if gap < 10 else f"{gap:.1f} %"
            proved = (
                f"every set's worst is at least {self.lower_bound:.4g}: gap {text}"
                if self.lower_bound > 0
                else "no gap proved"
            )
            swaps = "swap" if self.refined == 1 else "swaps"
            return (
                f"{self.sets} lug sets: local search, {self.refined} {swaps} from its starts "
                f"to a local optimum ({proved}) ({self.seconds:.2f} s)"
            )
        return None


@dataclass(frozen=True)
class DenseSearch:
    """What the dense search over the box found for one preload (each with its scenario).

    Parameters
    ----------
    worst : (float, Scenario)
        The objective's largest value (tension spread [t] or utilisation spread [-]).
    low : (float, Scenario)
        The lowest tension [t].
    over : (float, Scenario)
        The largest excess of a tension over its crane's SWL [t] (negative: none).
    highest : float  [t]
    rope_max : numpy.ndarray  [t]
        Each rope's largest tension.
    spread : float  [t]
        The largest tension spread.
    utilisation_spread : float  [-]
        The largest max - min of T_i / SWL_i.
    """

    worst: tuple
    low: tuple
    over: tuple
    highest: float
    rope_max: np.ndarray
    spread: float
    utilisation_spread: float


def robust(tensions, gain, lugset, delta=None):
    """Each scenario's worst over the hook-height errors within their tolerance (exact:
    at a given attitude the tensions are affine in the errors while every rope is taut).

    Parameters
    ----------
    tensions : (m, n)  [t]
    gain : (m, n, n)  [t/m]   dT/dH at each scenario
    lugset : LugSet   (its ``scale``, ``swl`` and ``hook_tolerance``)
    delta : (n,)  [m], optional   hook tolerances other than the lugset's

    Returns
    -------
    value : (m,)   the objective's worst: max - min of s_i T_i [t or -], or for ``reserve``
        the largest T_i / SWL_i [-]
    low, high : (m, n)  [t]   each tension's lowest and highest
    spread : (m,)  [t]   the worst tension spread
    utilisation : (m,)  [-]   the worst max - min of T_i / SWL_i
    """
    m, n = tensions.shape
    delta = lugset.hook_tolerance if delta is None else np.asarray(delta, dtype=float)
    margin = np.abs(gain) @ delta
    first, second = np.nonzero(~np.eye(n, dtype=bool))
    # scenarios per block of the pair terms: (block, n (n - 1), n) floats stay near 4 million
    block = max(1, 4_000_000 // max(1, n * n * (n - 1)))

    def pairwise(scale):
        values = tensions * scale
        if not np.any(delta > 0.0):  # no hook errors: each scenario's max - min
            return row_spread(values)
        out = np.empty(m)
        for start in range(0, m, block):
            rows = slice(start, start + block)
            scaled = gain[rows] * scale[None, :, None]
            extra = np.abs(scaled[:, first] - scaled[:, second]) @ delta
            out[rows] = (values[rows][:, first] - values[rows][:, second] + extra).max(axis=1)
        return out

    spread = pairwise(np.ones(n))
    utilisation = pairwise(1.0 / lugset.swl)
    objective = lugset.problem.objective
    if objective == "reserve":  # the largest T_i / SWL_i with every hook error
        value = ((tensions + margin) / lugset.swl).max(axis=1)
    else:
        value = utilisation if objective == "utilisation" else spread
    return value, tensions - margin, tensions + margin, spread, utilisation


def _limits(count, low, high):
    """(min_tension, SWL) per scenario and rope, each (count, n)  [t]."""
    high = np.asarray(high, dtype=float)
    return np.full((count, len(high)), float(low)), np.tile(high, (count, 1))


class SetEvaluator:
    """Evaluates lug sets of one problem (the LP is built once and re-solved)."""

    def __init__(self, problem):
        self.problem = problem
        hooks = problem.hook_tolerance > 0 or any(c.hook_tolerance for c in problem.fleet)
        self.minimax = PreloadMinimax(problem.cranes, SLOTS, problem.objective, separable=not hooks)
        self.offsets = [tuple(map(float, o)) for o in problem.cog_envelope.offsets()]
        self.start = self._scenarios(3)
        self.dense = self._scenarios(DENSE)
        self.tol = tolerance(problem)

    def _scenarios(self, count):
        grid = box_attitudes(self.problem, count, count)
        return [Scenario(float(h), float(t), o) for o in self.offsets for h, t in grid]

    def evaluate(self, indices, cranes=None, screen_bound=0.0):
        """Evaluate one set with one crane assignment.

        Parameters
        ----------
        indices : sequence of int
            Candidate indices.
        cranes : sequence of int, optional
            Fleet index of the crane on each lug (default: the identity).
        screen_bound : float
            The screening bound, recorded in the result.

        Returns
        -------
        SetResult

        Raises
        ------
        SetInfeasible
            No preload of this set keeps every rope within [min_tension, SWL] over the box;
            the message names the first constraint that cannot be met.
        """
        lugset = LugSet(self.problem, indices, cranes)
        scenarios = list(self.start)
        a_level, b_level = lugset.level_statics
        if np.linalg.matrix_rank(a_level[:, :], tol=1e-9 * np.abs(a_level).max()) < 3:
            raise SetInfeasible(COLLINEAR)  # the statics are singular: no LP to solve
        low_limit, high_limit = self.problem.min_tension, lugset.limit
        rounds, converged = 0, False
        while True:
            rounds += 1
            gains, offsets = lugset.affine(scenarios)
            hook = (
                (gains * lugset.stiffness[None, None, :], lugset.hook_tolerance)
                if lugset.hook_uncertain
                else None
            )
            try:
                result = self.minimax.solve(
                    gains,
                    offsets,
                    a_level,
                    b_level,
                    lugset.preload_range(),
                    _limits(len(scenarios), low_limit, high_limit),
                    scale=lugset.scale,
                    hook=hook,
                )
            except PlanInfeasible:
                raise SetInfeasible(self.diagnose(lugset, scenarios)) from None
            found = self.dense_search(lugset, result.preload)
            worst, low, over = found.worst, found.low, found.over
            violated = low[0] < low_limit - self.tol or over[0] > self.tol
            if worst[0] <= result.worst_spread + self._tol(lugset) and not violated:
                converged = True
                break
            if rounds == MAX_ROUNDS or len(scenarios) + 3 > SLOTS:
                break
            cuts = [worst[1]] + ([low[1], over[1]] if violated else [])
            new = [s for s in dict.fromkeys(cuts) if s not in scenarios]
            if not new:
                break  # the LP already holds these points: nothing to cut with
            scenarios += new
        if not converged and (low[0] < low_limit - self.tol or over[0] > self.tol):
            raise SetInfeasible(BOX_SLACK if low[0] < low_limit - self.tol else BOX_OVERLOAD)
        preload = result.preload
        return SetResult(
            lugs=lugset.names,
            indices=lugset.indices,
            cranes=lugset.cranes,
            crane_names=lugset.crane_names,
            radius=lugset.radius,
            swl=lugset.swl,
            preload=preload,
            boom_heights=lugset.boom_heights(preload),
            nominal_spread=float(np.ptp(preload)),
            worst_spread=found.spread,
            worst=worst[1],
            bound=result.worst_spread,
            screen_bound=screen_bound,
            tension_range=(low[0], found.highest),
            rope_max=found.rope_max,
            rounds=rounds,
            converged=converged,
            objective=self.problem.objective,
            worst_value=worst[0],
            worst_utilisation_spread=found.utilisation_spread,
            nominal_utilisation_spread=float(np.ptp(preload / lugset.swl)),
        )

    def _tol(self, lugset):
        """Agreement asked in the objective's unit."""
        return self.tol if self.problem.objective == "spread" else self.tol / float(np.min(lugset.swl))

    def dense_search(self, lugset, preload):
        """The dense search over the box with T* held: see :class:`DenseSearch`.

        With hook-height tolerances each scenario's values are the exact worst over the hook
        errors too (:func:`robust`)."""
        tensions, gain = lugset.tensions_and_gain(preload, self.dense)
        value, low, high, spread, util = robust(tensions, gain, lugset)
        k = int(np.argmax(value))
        worst = (float(value[k]), self.dense[k])
        for _ in range(ZOOM_ROUNDS):
            local = self._around(worst[1])
            values = robust(*lugset.tensions_and_gain(preload, local), lugset)[0]
            j = int(np.argmax(values))
            if values[j] > worst[0]:
                worst = (float(values[j]), local[j])
        excess = high - lugset.limit
        lowest = np.unravel_index(np.argmin(low), low.shape)[0]
        over = np.unravel_index(np.argmax(excess), excess.shape)[0]
        return DenseSearch(
            worst=worst,
            low=(float(low.min()), self.dense[lowest]),
            over=(float(excess.max()), self.dense[over]),
            highest=float(high.max()),
            rope_max=high.max(axis=0),
            spread=max(float(spread.max()), worst[0] if self.problem.objective == "spread" else 0.0),
            utilisation_spread=max(
                float(util.max()), worst[0] if self.problem.objective == "utilisation" else 0.0
            ),
        )

    def _around(self, scenario):
        """A ZOOM x ZOOM grid of one dense cell either side of a scenario, inside the box."""
        problem = self.problem
        step_h = 2 * problem.heel_tolerance / (DENSE - 1)
        step_t = 2 * problem.trim_tolerance / (DENSE - 1)
        heel = np.clip(
            np.linspace(scenario.heel - step_h, scenario.heel + step_h, ZOOM),
            -problem.heel_tolerance,
            problem.heel_tolerance,
        )
        trim = np.clip(
            np.linspace(scenario.trim - step_t, scenario.trim + step_t, ZOOM),
            -problem.trim_tolerance,
            problem.trim_tolerance,
        )
        return [Scenario(float(h), float(t), scenario.cog_offset) for h in heel for t in trim]

    def diagnose(self, lugset, scenarios):
        """The first constraint group that makes a set infeasible (a key of REASONS)."""
        problem, swl = self.problem, lugset.limit
        a_level, b_level = lugset.level_statics
        level = [Scenario(0.0, 0.0)]
        g_level, q_level = lugset.affine(level)
        gains, offsets = lugset.affine(scenarios)
        free = (np.full(lugset.n, -np.inf), np.full(lugset.n, np.inf))
        inf = np.full((1, lugset.n), np.inf)
        ones = np.ones((1, lugset.n))
        steps = [
            (g_level, q_level, free, (0 * ones, inf), CG_OUTSIDE),
            (g_level, q_level, free, (0 * ones, swl * ones), LEVEL_SWL),
            (g_level, q_level, free, (problem.min_tension * ones, swl * ones), LEVEL_MIN_TENSION),
            (g_level, q_level, free, (problem.min_tension * ones, lugset.share_limit * ones), CODE_MARGIN),
            (g_level, q_level, lugset.preload_range(), (problem.min_tension * ones, swl * ones), BOOM_RANGE),
        ]
        count = len(scenarios)
        steps.append(
            (
                gains,
                offsets,
                lugset.preload_range(),
                (np.full((count, lugset.n), problem.min_tension), np.full((count, lugset.n), np.inf)),
                BOX_SLACK,
            )
        )
        for gain, offset, preload_range, limits, code in steps:
            try:
                self.minimax.solve(gain, offset, a_level, b_level, preload_range, limits)
            except PlanInfeasible:
                return code
        return BOX_OVERLOAD


#: Rows whose coarse screening bound is replaced by the full one at a time (256: fewer, larger
#: calls; 4 of 100 candidates 21.9 -> 18.3 s, 8 of 16 5.4 -> 4.6 s against 64).
REFINE = 256
#: n >= 5: refine the preload-free pair bound to the LP's dual bound before a row is
#: evaluated (False: the pair bound alone, as before; studies/planner_scale.py compares).
DUAL_BOUND = True


class Interrupted(KeyboardInterrupt):
    """Ctrl-C during the search; ``ranking`` and ``stats`` hold the best found so far (the
    ranking may be empty), ``plan`` is set by :func:`liftplan.planner.plan.plan`."""

    def __init__(self, ranking, stats):
        super().__init__("search interrupted")
        self.ranking, self.stats, self.plan = ranking, stats, None


def search(problem, top=None, progress=None):
    """Rank the best lug sets with their crane assignments.

    Best bound first over every (set, assignment) row: the search stops when no row left
    can enter the top k (the optimum is proved), when the best plan is within
    ``problem.gap`` of the certified lower bound, or at ``problem.time_limit``.

    Parameters
    ----------
    problem : PlanProblem
    top : int, optional
        How many to rank (default ``problem.top``).
    progress : bool, optional
        A progress bar on stderr (rows done, best, bound, gap). Default: when stderr is a
        terminal, shown once the search has run a second.

    Returns
    -------
    ranking : list of SetResult
        Best first (smallest worst value of the objective).
    stats : SearchStats
        With the certified lower bound and the gap.

    Raises
    ------
    PlanInfeasible
        No lug set is feasible; the message counts the causes.
    Interrupted
        Ctrl-C: carries the best ranking found so far.
    """
    started = time.perf_counter()
    top = top or problem.top
    if problem.search == "mip":
        from liftplan.planner.search.mip import search_mip

        return search_mip(problem, started, progress)
    if problem.search == "local" or (
        problem.search == "auto" and problem.set_count > auto_exact_limit(problem.cranes)
    ):
        return _local(problem, started, progress)
    sets, cranes, out_of_reach = set_rows(problem)
    if len(sets) == 0:
        raise PlanInfeasible(_unreachable(problem))
    screening = screen(problem, sets, cranes)
    evaluator = SetEvaluator(problem)
    reasons = Counter(
        dict(
            zip(
                *(
                    v.tolist()
                    for v in np.unique(screening.reason[screening.reason != FEASIBLE], return_counts=True)
                )
            )
        )
    )
    bound = screening.bound.copy()
    # rows whose bound is refined before they are evaluated: from the coarse screening, or
    # (n >= 5) from the preload-free pair bound to the LP's dual bound
    dual = problem.cranes >= 5 and DUAL_BOUND
    lazy = _coarse(screening, problem) or dual
    refined = np.full(len(bound), not lazy)
    heap = [(float(bound[k]), bool(not refined[k]), int(k)) for k in np.flatnonzero(np.isfinite(bound))]
    heapq.heapify(heap)
    feasible_rows = len(heap)
    ranking, evaluated, refine_count = [], 0, 0
    evaluated_bound = math.inf  # least LP bound of the rows evaluated feasible
    stopped = "proved"
    bar = _progress_bar(feasible_rows, progress)

    def lower_bound():
        return min(evaluated_bound, heap[0][0] if heap else math.inf)

    def stats_now():
        best = ranking[0].worst_value if ranking else math.inf
        return SearchStats(
            sets=problem.set_count,
            screened_out=int(np.sum(screening.reason != FEASIBLE)),
            evaluated=evaluated,
            pruned=feasible_rows - evaluated,
            infeasible={REASONS[c]: n for c, n in reasons.most_common()},
            seconds=time.perf_counter() - started,
            rows=len(sets),
            out_of_reach=out_of_reach,
            refined=refine_count,
            # stopped early: the two-line bound may be the better of two valid bounds
            lower_bound=min(
                lower_bound()
                if stopped == "proved"
                else max(lower_bound(), line_bound(problem, evaluator.dense)),
                best,
            ),
            best=best,
            stopped=stopped,
        )

    done = np.zeros(len(bound), dtype=bool)  # evaluated out of turn

    def evaluate(k, value):
        nonlocal evaluated, evaluated_bound
        evaluated += 1
        _tick(bar, ranking, lower_bound)
        try:
            result = evaluator.evaluate(sets[k], cranes[k], value)
        except SetInfeasible as err:
            reasons[err.code] += 1
            return
        evaluated_bound = min(evaluated_bound, result.bound)
        ranking.append(result)
        ranking.sort(key=lambda r: (r.worst_value, r.nominal_value))
        del ranking[top:]

    try:
        while heap:
            if len(ranking) >= top and heap[0][0] >= ranking[top - 1].worst_value:
                break
            if ranking:
                best, low = ranking[0].worst_value, min(lower_bound(), ranking[0].worst_value)
                if problem.gap > 0 and best - low <= problem.gap * best:
                    stopped = "gap"
                    break
                if problem.time_limit is not None and time.perf_counter() - started > problem.time_limit:
                    stopped = "time_limit"
                    break
            value, coarse, k = heapq.heappop(heap)
            if done[k]:
                continue
            if coarse:
                batch = [k] + [
                    heapq.heappop(heap)[2] for _ in range(min(REFINE - 1, len(heap))) if heap and heap[0][1]
                ]
                # a bound past the k-th best found need not be tightened further
                target = ranking[top - 1].worst_value if len(ranking) >= top else np.inf
                full = screen(problem, sets[batch], cranes[batch], coarse=False, dual=dual, target=target)
                refine_count += len(batch)
                dive = None
                for j, new_bound, reason in zip(batch, full.bound, full.reason):
                    refined[j] = True
                    if reason != FEASIBLE:
                        reasons[int(reason)] += 1
                        continue
                    entry = (max(float(new_bound), float(bound[j])), False, int(j))
                    heapq.heappush(heap, entry)
                    dive = entry if dive is None or entry < dive else dive
                if dive is not None and len(ranking) < top:
                    # no k-th best yet: evaluate the batch's best now, so that its value
                    # lets the next batches' bounds stop early (the row is not evaluated twice)
                    done[dive[2]] = True
                    evaluate(dive[2], dive[0])
                continue
            evaluate(k, value)
    except KeyboardInterrupt:
        stopped = "interrupted"
        raise Interrupted(ranking, stats_now()) from None
    finally:
        if bar is not None:
            bar.close()
    stats = stats_now()
    if not ranking:
        causes = "; ".join(f"{n} sets: {text}" for text, n in stats.infeasible.items())
        what = f"{problem.cranes} lugs among {len(problem.candidates)} candidates"
        if not problem.equal_cranes:
            what += f" with any assignment of the cranes in reach ({out_of_reach} out of reach)"
        if stopped == "time_limit":
            what += f" found within the time limit {problem.time_limit:g} s"
        raise PlanInfeasible(
            f"no set of {what} can hold the body within heel +-{problem.heel_tolerance:g} deg, "
            f"trim +-{problem.trim_tolerance:g} deg, tensions {problem.min_tension:g} t to "
            f"each crane's SWL ({causes})"
        )
    return ranking, stats


#: ``search = "auto"``: the exact search for five or more lugs up to this many sets
#: (studies/planner_scale.py on an idle machine: 5 of 24 candidates, 42 504 sets, proved in
#: 5.7 s; 5 of 40, 658 008 sets, proved in 151 s, where the local search is 0.9 % above in
#: 0.9 s; about a quarter of a millisecond a set, so some 50 s at this limit).
AUTO_EXACT_MANY = 200_000


def auto_exact_limit(cranes):
    """Lug sets up to which ``search = "auto"`` runs the exact search (n <= 4: its screening
    is the exact LP over the screening scenarios, and 5e6 sets screen in seconds)."""
    return MAX_SETS if cranes <= 4 else AUTO_EXACT_MANY


def _local(problem, started, progress=None):
    """:func:`~liftplan.planner.search.local.local_search`, its set evaluated exactly, and the
    lower bound that holds for every set: the two-line bound, refined cell by cell where the
    lugs are stations on two lines in one plane (:mod:`~liftplan.planner.search.line_cells`)
    towards the plan's value less the gap aimed at. With a time limit the search takes half
    of it and the bound the rest; Ctrl-C during the bound keeps the plan with the bound so far
    (:class:`Interrupted`)."""
    from liftplan.planner.search.line_cells import applies, cell_bound
    from liftplan.planner.search.local import local_search

    limit = problem.time_limit
    indices, moves, _ = local_search(problem, time_limit=None if limit is None else 0.5 * limit)
    evaluator = SetEvaluator(problem)
    try:
        result = evaluator.evaluate(indices)
    except SetInfeasible as err:
        raise PlanInfeasible(
            f"the local search ended on {', '.join(problem.names[i] for i in indices)}"
            f" after {moves} swaps, which is infeasible over the box: "
            f"{REASONS[err.code]}"
        ) from None
    if problem.objective == "reserve":  # every rope shares W: max T_i / SWL_i >= W / sum SWL
        bound = problem.body.weight / float(np.sum(result.swl))
    else:  # candidates on two lines: what each line carries is fixed by the statics
        bound = line_bound(problem, evaluator.dense)
        if applies(problem) and bound < result.worst_value:
            deadline = None if limit is None else started + limit
            target = result.worst_value * (1.0 - problem.gap * (1.0 - 1e-9))  # gap <= target
            bar = _progress_bar(None, progress)
            best = result.worst_value
            if bar is not None:
                bar.set_description("bound: cells")
                bar.unit = "cell"

            def tick(done, total, low):
                if bar is not None:
                    bar.total, bar.n = total, done
                    bar.set_postfix_str(
                        f"best {best:.4g}, bound {low:.4g}, gap {100 * (best - low) / best:.2g} %",
                        refresh=True,
                    )

            try:
                cells = cell_bound(problem, evaluator.dense, target, deadline, tick)
            finally:
                if bar is not None:
                    bar.close()
            bound = max(bound, cells.value)
            if cells.interrupted:  # Ctrl-C: the plan, with the bound so far
                raise Interrupted(
                    [result], _local_stats(problem, started, moves, bound, result, "interrupted")
                )
    return [result], _local_stats(problem, started, moves, bound, result, "local")


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


def _progress_bar(total, progress):
    if progress is False or (progress is None and not sys.stderr.isatty()):
        return None
    from tqdm import tqdm

    return tqdm(
        total=total, desc="plan", unit="set", file=sys.stderr, delay=1.0, leave=False, dynamic_ncols=True
    )


def _tick(bar, ranking, lower_bound):
    if bar is None:
        return
    bar.update(1)
    if ranking:
        best, low = ranking[0].worst_value, min(lower_bound(), ranking[0].worst_value)
        bar.set_postfix_str(
            f"best {best:.4g}, bound {low:.4g}, gap {100 * (best - low) / best:.2g} %"
            if best > 0
            else f"best {best:.4g}",
            refresh=False,
        )


def _coarse(screening, problem):
    return len(screening.sets) * len(screening_scenarios(problem)[0]) > FULL_COLUMNS


def _unreachable(problem):
    """Why no assignment puts every crane within reach of a distinct lug."""
    swl = problem.reach[1]
    counts = np.sum(~np.isnan(swl), axis=0)
    worst = int(np.argmin(counts))
    crane = problem.fleet[worst]
    return (
        f"no assignment puts every crane within reach of its own lug: crane "
        f"{crane.name} reaches {int(counts[worst])} of {len(problem.candidates)} candidates "
        f"(chart reach {crane.reach:g} m); expected cranes closer to the candidates or "
        "longer charts"
    )
