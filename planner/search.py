"""Branch and bound over lug sets, and the exact evaluation of one set.

1. :func:`~liftplan.planner.screen.screen` gives every set a lower bound on its worst
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

import time
from collections import Counter
from dataclasses import dataclass, field

import numpy as np

from liftplan.model.errors import PlanInfeasible

from .bounds import PreloadMinimax
from .scenarios import LugSet, Scenario, box_attitudes
from .screen import (
    BOOM_RANGE,
    BOX_OVERLOAD,
    BOX_SLACK,
    CG_OUTSIDE,
    FEASIBLE,
    LEVEL_MIN_TENSION,
    LEVEL_SWL,
    REASONS,
    screen,
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
    preload : numpy.ndarray  [t]
        Level tensions T* the plan dials in.
    boom_heights : numpy.ndarray  [m]
    nominal_spread : float  [t]
        Spread of T* (level, nominal CG).
    worst_spread : float  [t]
        Largest spread found over the box (and CG envelope) with T* held.
    worst : Scenario
        Where it occurs.
    bound : float  [t]
        The preload LP's optimum over its scenarios: no preload of this set does better.
    screen_bound : float  [t]
        The screening bound used to order and prune.
    tension_range : tuple of float  [t]
        Smallest and largest tension anywhere in the box.
    rope_max : numpy.ndarray  [t]
        Each rope's largest tension over the dense box grid and the CG envelope.
    rounds : int
        Cutting-plane rounds.
    converged : bool
        The dense search found nothing worse than the LP (within :func:`tolerance`).
    """

    lugs: tuple[str, ...]
    indices: tuple[int, ...]
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

    def utilisation(self, swl):
        """Largest tension in the box over the SWL  [-]."""
        return self.tension_range[1] / swl


@dataclass(frozen=True)
class SearchStats:
    """How the search went.

    Parameters
    ----------
    sets : int
        Lug sets in all.
    screened_out : int
        Proved infeasible by screening.
    evaluated : int
        Evaluated with the LP and the dense search.
    pruned : int
        Never evaluated: their bound could not beat the k-th best.
    infeasible : dict of str to int
        Reasons and counts of every infeasible set found.
    seconds : float  [s]
    """

    sets: int
    screened_out: int
    evaluated: int
    pruned: int
    infeasible: dict[str, int] = field(default_factory=dict)
    seconds: float = 0.0


class SetEvaluator:
    """Evaluates lug sets of one problem (the LP is built once and re-solved)."""

    def __init__(self, problem):
        self.problem = problem
        self.minimax = PreloadMinimax(problem.cranes, SLOTS)
        self.offsets = [tuple(map(float, o)) for o in problem.cog_envelope.offsets()]
        self.start = self._scenarios(3)
        self.dense = self._scenarios(DENSE)
        self.tol = tolerance(problem)

    def _scenarios(self, count):
        grid = box_attitudes(self.problem, count, count)
        return [Scenario(float(h), float(t), o) for o in self.offsets for h, t in grid]

    def _limits(self, count):
        spec = self.problem.crane
        return (np.full((count, self.problem.cranes), self.problem.min_tension),
                np.full((count, self.problem.cranes), spec.swl))

    def evaluate(self, indices, screen_bound=0.0):
        """Evaluate one set.

        Returns
        -------
        SetResult

        Raises
        ------
        SetInfeasible
            No preload of this set keeps every rope within [min_tension, SWL] over the box;
            the message names the first constraint that cannot be met.
        """
        lugset = LugSet(self.problem, indices)
        scenarios = list(self.start)
        a_level, b_level = lugset.level_statics
        rounds, converged = 0, False
        while True:
            rounds += 1
            gains, offsets = lugset.affine(scenarios)
            try:
                result = self.minimax.solve(gains, offsets, a_level, b_level,
                                            lugset.preload_range(), self._limits(len(scenarios)))
            except PlanInfeasible:
                raise SetInfeasible(self.diagnose(lugset, scenarios)) from None
            worst, low, high, rope_max = self._search(lugset, result.preload)
            violated = low[0] < self.problem.min_tension - self.tol or \
                high[0] > self.problem.crane.swl + self.tol
            if worst[0] <= result.worst_spread + self.tol and not violated:
                converged = True
                break
            if rounds == MAX_ROUNDS or len(scenarios) + 3 > SLOTS:
                break
            found = [worst[1]] + ([low[1], high[1]] if violated else [])
            new = [s for s in dict.fromkeys(found) if s not in scenarios]
            if not new:
                break  # the LP already holds these points: nothing to cut with
            scenarios += new
        if not converged and (low[0] < self.problem.min_tension - self.tol
                              or high[0] > self.problem.crane.swl + self.tol):
            raise SetInfeasible(
                BOX_SLACK if low[0] < self.problem.min_tension - self.tol else BOX_OVERLOAD
            )
        return SetResult(
            lugs=lugset.names,
            indices=lugset.indices,
            preload=result.preload,
            boom_heights=lugset.boom_heights(result.preload),
            nominal_spread=result.nominal_spread,
            worst_spread=worst[0],
            worst=worst[1],
            bound=result.worst_spread,
            screen_bound=screen_bound,
            tension_range=(low[0], high[0]),
            rope_max=rope_max,
            rounds=rounds,
            converged=converged,
        )

    def _search(self, lugset, preload):
        """Worst spread, lowest and highest tension over the box (with their scenarios), and
        each rope's largest tension on the dense grid."""
        tensions = lugset.tensions(preload, self.dense)
        spread = np.ptp(tensions, axis=1)
        k = int(np.argmax(spread))
        worst = (float(spread[k]), self.dense[k])
        for _ in range(ZOOM_ROUNDS):
            local = self._around(worst[1])
            values = np.ptp(lugset.tensions(preload, local), axis=1)
            j = int(np.argmax(values))
            if values[j] > worst[0]:
                worst = (float(values[j]), local[j])
        lowest = np.unravel_index(np.argmin(tensions), tensions.shape)[0]
        highest = np.unravel_index(np.argmax(tensions), tensions.shape)[0]
        low = (float(tensions.min()), self.dense[lowest])
        high = (float(tensions.max()), self.dense[highest])
        return worst, low, high, tensions.max(axis=0)

    def _around(self, scenario):
        """A ZOOM x ZOOM grid of one dense cell either side of a scenario, inside the box."""
        problem = self.problem
        step_h = 2 * problem.heel_tolerance / (DENSE - 1)
        step_t = 2 * problem.trim_tolerance / (DENSE - 1)
        heel = np.clip(np.linspace(scenario.heel - step_h, scenario.heel + step_h, ZOOM),
                       -problem.heel_tolerance, problem.heel_tolerance)
        trim = np.clip(np.linspace(scenario.trim - step_t, scenario.trim + step_t, ZOOM),
                       -problem.trim_tolerance, problem.trim_tolerance)
        return [Scenario(float(h), float(t), scenario.cog_offset) for h in heel for t in trim]

    def diagnose(self, lugset, scenarios):
        """The first constraint group that makes a set infeasible (a key of REASONS)."""
        problem, spec = self.problem, self.problem.crane
        a_level, b_level = lugset.level_statics
        level = [Scenario(0.0, 0.0)]
        g_level, q_level = lugset.affine(level)
        gains, offsets = lugset.affine(scenarios)
        free = (np.full(lugset.n, -np.inf), np.full(lugset.n, np.inf))
        inf = np.full((1, lugset.n), np.inf)
        ones = np.ones((1, lugset.n))
        steps = [
            (g_level, q_level, free, (0 * ones, inf), CG_OUTSIDE),
            (g_level, q_level, free, (0 * ones, spec.swl * ones), LEVEL_SWL),
            (g_level, q_level, free, (problem.min_tension * ones, spec.swl * ones),
             LEVEL_MIN_TENSION),
            (g_level, q_level, lugset.preload_range(),
             (problem.min_tension * ones, spec.swl * ones), BOOM_RANGE),
        ]
        count = len(scenarios)
        steps.append((gains, offsets, lugset.preload_range(),
                      (np.full((count, lugset.n), problem.min_tension), np.full((count, lugset.n),
                                                                               np.inf)), BOX_SLACK))
        for gain, offset, preload_range, limits, code in steps:
            try:
                self.minimax.solve(gain, offset, a_level, b_level, preload_range, limits)
            except PlanInfeasible:
                return code
        return BOX_OVERLOAD


def search(problem, top=None):
    """Rank the best lug sets.

    Parameters
    ----------
    problem : PlanProblem
    top : int, optional
        How many to rank (default ``problem.top``).

    Returns
    -------
    ranking : list of SetResult
        Best first (smallest worst spread).
    stats : SearchStats

    Raises
    ------
    PlanInfeasible
        No lug set is feasible; the message counts the causes.
    """
    started = time.perf_counter()
    top = top or problem.top
    screening = screen(problem)
    evaluator = SetEvaluator(problem)
    reasons = Counter(int(r) for r in screening.reason[screening.reason != FEASIBLE])
    order = np.argsort(screening.bound, kind="stable")
    order = order[np.isfinite(screening.bound[order])]
    ranking, evaluated = [], 0
    for k in order:
        if len(ranking) >= top and screening.bound[k] >= ranking[top - 1].worst_spread:
            break
        evaluated += 1
        try:
            result = evaluator.evaluate(screening.sets[k], float(screening.bound[k]))
        except SetInfeasible as err:
            reasons[err.code] += 1
            continue
        ranking.append(result)
        ranking.sort(key=lambda r: (r.worst_spread, r.nominal_spread))
        del ranking[top:]
    stats = SearchStats(
        sets=len(screening.sets),
        screened_out=int(np.sum(screening.reason != FEASIBLE)),
        evaluated=evaluated,
        pruned=len(order) - evaluated,
        infeasible={REASONS[c]: n for c, n in reasons.most_common()},
        seconds=time.perf_counter() - started,
    )
    if not ranking:
        causes = "; ".join(f"{n} sets: {text}" for text, n in stats.infeasible.items())
        raise PlanInfeasible(
            f"no set of {problem.cranes} lugs among {len(problem.candidates)} candidates can "
            f"hold the body within heel +-{problem.heel_tolerance:g} deg, trim "
            f"+-{problem.trim_tolerance:g} deg, tensions {problem.min_tension:g} to "
            f"{problem.crane.swl:g} t ({causes})"
        )
    return ranking, stats
