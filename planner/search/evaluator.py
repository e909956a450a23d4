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

import math
from dataclasses import dataclass, field

import numpy as np

from liftplan.model.errors import PlanInfeasible
from liftplan.planner.problem.objectives import OBJECTIVES
from liftplan.planner.problem.vessels import has_limits, vessel_breach
from liftplan.planner.search.bounds import PreloadMinimax
from liftplan.planner.search.progress import best_bound
from liftplan.planner.search.rows import row_spread
from liftplan.planner.search.scenarios import Scenario, box_attitudes, set_lugset
from liftplan.planner.search.screen import (
    BOOM_RANGE,
    BOX_OVERLOAD,
    BOX_SLACK,
    CG_OUTSIDE,
    CODE_MARGIN,
    COLLINEAR,
    LEVEL_MIN_TENSION,
    LEVEL_SWL,
    REASONS,
    VESSEL_FREEBOARD,
    VESSEL_HEEL,
    VESSEL_TRIM,
)

#: Dense check grid: heel x trim points over the box.
DENSE = 21
#: Finer grids around the worst dense point: points per side, and rounds.
ZOOM, ZOOM_ROUNDS = 11, 2
#: The rule-out code of each vessel limit (:func:`~liftplan.planner.problem.vessels.vessel_breach`).
VESSEL_CODES = {"heel": VESSEL_HEEL, "trim": VESSEL_TRIM, "freeboard": VESSEL_FREEBOARD}
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
        goal = OBJECTIVES[self.objective]
        if goal.peak:
            return float(np.max(self.preload / self.swl))
        return self.nominal_utilisation_spread if goal.per_swl else self.nominal_spread


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
    "work_limit": "stopped at the work limit",
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
    clashing : int
        (set, assignment) pairs dropped because two cranes' booms cross in plan or come nearer
        than ``plan.crane_clearance`` (:mod:`liftplan.planner.problem.clearance`).
    refined : int
        Rows whose coarse screening bound was replaced by the full one before evaluation.
    lower_bound : float  [t or -]
        Certified: no lug set and assignment does better over the box than this (the least
        of the LP bounds of the rows evaluated and the screening bounds of the rows not).
    best : float  [t or -]
        The plan's worst value of the objective.
    stopped : {"proved", "gap", "time_limit", "work_limit", "interrupted", "local", "rounds"}
        Why the search ended: the top plans proved, the gap target reached, the time limit,
        the work limit (``[plan] work_limit``: the same plan on any machine), Ctrl-C, a local
        optimum of the local search (its lower bound holds for every set but is not its
        value: :mod:`~liftplan.planner.search.lines`,
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
    clashing: int = 0
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
        if self.method == "local":
            gap = 100 * self.relative_gap
            text = f"{gap:.2f} %" if gap < 10 else f"{gap:.1f} %"
            proved = (
                f"every set's worst is at least {self.lower_bound:.4g}: gap {text}"
                if self.lower_bound > 0
                else "no gap proved"
            )
            swaps = "swap" if self.refined == 1 else "swaps"
            end = "to a local optimum" if self.stopped == "local" else f"({_ENDED[self.stopped]})"
            return (
                f"{self.sets} lug sets: local search, {self.refined} {swaps} from its starts "
                f"{end} ({proved}) ({self.seconds:.2f} s)"
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
    rope_min : numpy.ndarray  [t]
        Each rope's lowest tension.
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
    rope_min: np.ndarray | None = None


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
    # each unordered pair once: its widening is symmetric, so the worse of (a, b) and (b, a)
    # is |s_a T_a - s_b T_b| + widening (the same number)
    first, second = np.triu_indices(n, 1)
    # scenarios per block of the pair terms: (block, n (n - 1) / 2, n) floats stay near 2 million
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
            out[rows] = (np.abs(values[rows][:, first] - values[rows][:, second]) + extra).max(axis=1)
        return out

    spread = pairwise(np.ones(n))
    utilisation = pairwise(1.0 / lugset.swl)
    goal = lugset.problem.goal
    if goal.peak:  # the largest T_i / SWL_i with every hook error
        value = ((tensions + margin) / lugset.swl).max(axis=1)
    else:
        value = utilisation if goal.per_swl else spread
    return value, tensions - margin, tensions + margin, spread, utilisation


def _limits(count, low, high):
    """(min_tension, SWL) per scenario and rope, each (count, n)  [t]."""
    high = np.asarray(high, dtype=float)
    return np.full((count, len(high)), float(low)), np.tile(high, (count, 1))


class SetEvaluator:
    """Evaluates lug sets of one problem (the LP is built once and re-solved).

    With floating cranes each set is evaluated with its vessels in series at its own lugs
    (:func:`~liftplan.planner.problem.vessels.series_fleet`, whatever stiffness the problem's
    fleet stands at), and a set whose worst states put a vessel beyond its ``max_heel`` or
    ``max_trim``, or below its ``min_freeboard``, is ruled out (:data:`VESSEL_CODES`): the
    states of the dense search (the box for every CG vertex, each with the hook errors at their
    worst), the levelling ballast set for the set's level tensions
    (:func:`~liftplan.planner.problem.vessels.vessel_worst`).
    """

    def __init__(self, problem):
        self.problem = problem
        self.limited = has_limits(problem)
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
            the message names the first constraint that cannot be met. Or (floating cranes)
            the set's preload, the LP's, puts a vessel beyond a limit at a worst state: the
            limits rule the set out as its plan stands, they are no constraint of the LP.
        """
        lugset = set_lugset(self.problem, indices, cranes)
        indices, cranes = lugset.indices, lugset.cranes
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
        if self.limited:
            cause = vessel_breach(self.problem, indices, cranes, preload, found.rope_min, found.rope_max)
            if cause is not None:
                raise SetInfeasible(VESSEL_CODES[cause])
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
        return self.tol if not self.problem.goal.per_swl else self.tol / float(np.min(lugset.swl))

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
        width, per_swl = not self.problem.goal.peak, self.problem.goal.per_swl
        return DenseSearch(
            worst=worst,
            low=(float(low.min()), self.dense[lowest]),
            over=(float(excess.max()), self.dense[over]),
            highest=float(high.max()),
            rope_max=high.max(axis=0),
            rope_min=low.min(axis=0),
            spread=max(float(spread.max()), worst[0] if width and not per_swl else 0.0),
            utilisation_spread=max(float(util.max()), worst[0] if width and per_swl else 0.0),
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


class Interrupted(KeyboardInterrupt):
    """Ctrl-C during a plan; ``ranking`` and ``stats`` hold the best found so far (the
    ranking may be empty), ``plan`` the best plan so far (None when none was found; set by
    each kind's planner), ``phase`` where the interrupt landed and ``finished`` whether the
    search had already ended (then ``plan`` is the search's answer, only what came after it,
    such as the report, was cut short)."""

    def __init__(self, ranking=(), stats=None, plan=None, phase="search", finished=False):
        super().__init__("search interrupted")
        self.ranking, self.stats, self.plan = list(ranking), stats, plan
        self.phase, self.finished = phase, finished


def tick(bar, ranking, lower_bound):
    if bar is None:
        return
    bar.update(1)
    if ranking:
        bar.set_postfix_str(best_bound(ranking[0].worst_value, lower_bound()), refresh=False)
