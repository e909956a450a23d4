"""The planner choosing rope lengths (payout) within each crane's range (issue 16, item 2).

A longer rope is softer: the twist stiffness (t per cm of diagonal hook error), and with it
the spread a hook-height tolerance adds, falls as EA / l0; but every metre of payout is a
metre more boom height, and the boom range ends somewhere. A crane given
``rope_length = { min, max }`` lets the planner choose.

Method: an outer search over lengths around the exact lug search. Each trial copies the
problem with fixed lengths and calls :func:`liftplan.planner.plan.plan` on it, which is
exact and certified for those lengths (lugs, crane assignment, preload). The cranes of one
class (interchangeable: :func:`~liftplan.planner.problem.fleet.crane_classes`) share one
length: that keeps them interchangeable, so the inner search still enumerates one crane
assignment per lug set instead of every permutation (24 x the rows for four equal cranes).

The trials: :data:`LENGTH_STEPS` evenly spaced lengths per class with a range (ends
included; fewer when several classes have ranges, at most :data:`MAX_GRID` combinations),
then :data:`REFINE_ROUNDS` rounds that halve the step about the best trial, one class at a
time. On the tanker (one class, 25 to 55 m, boom tips at most 60 m) the worst spread falls
monotonically with the length until the boom range makes the plan infeasible, so the
choice is the longest payout the boom range allows, which the halvings place to within
1/16 of the range. The plan's certified lower bound is the least of the trials' bounds:
certified over the lengths tried, not over the continuous range between them.

A time limit (``[plan] time_limit``) is the whole search's: each trial gets what is left of it
(its share, :attr:`LengthTrial.time_share`), and trials not started when it has run out are
not tried. A trial cut short by its share keeps its own lower bound when it found a plan; one
that found none claims no bound (0, the least any objective can be), nor does the search when
lengths it meant to try were left untried, so the plan's bound and gap stay honest over the
lengths an untimed search tries, and the search's ``stopped`` is ``"time_limit"``. The
plan's problem keeps the user's ``time_limit``, not the last trial's share. The plan's search
counts (sets ruled out, evaluated, pruned) are the chosen lengths' own, which add up to its
rows; :attr:`LengthSearch.evaluated` sums the sets evaluated over every length tried.

Cranes on slings (issue 24 item 3): the range is the hoist rope's, tip to hook, and each trial
is an exact sling plan (``inner``, passed by :func:`liftplan.planner.plan.plan`, which imports
both kinds of plan; they do not import each other). Two or three cranes on slings are
statically determinate, so the length changes only the boom heights: every length within the
booms' range plans the same, and the first (shortest) of equal values is kept (values compared
to 12 significant digits, so round-off does not pick among equals).
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass

import numpy as np

from liftplan.model.errors import PlanInfeasible
from liftplan.planner.plans.held import Plan, design_first, girder_first, plan_held
from liftplan.planner.search.evaluator import Interrupted
from liftplan.planner.search.progress import best_bound, progress_bar

LENGTH_STEPS = 5
#: Largest number of length combinations in the first pass (several classes with ranges).
MAX_GRID = 27
#: Halvings of the step about the best trial, per class.
REFINE_ROUNDS = 2


@dataclass(frozen=True)
class LengthTrial:
    """One set of lengths tried.

    Parameters
    ----------
    lengths : tuple of float  [m]
        One length per varying crane class (:attr:`LengthSearch.classes` order).
    value : float or None  [t or -]
        The plan's worst value of the objective at these lengths; None: no feasible plan.
    lower_bound : float  [t or -]
        The inner search's certified bound (inf when infeasible).
    lugs : tuple of str
        The lugs chosen at these lengths (empty when infeasible).
    reason : str
        Why no plan exists at these lengths ("" when one does).
    stopped : str
        Why the trial's search ended (:class:`~liftplan.planner.search.evaluator.SearchStats`
        ``stopped``; ``"time_limit"`` also for a trial that found no plan within its share of
        the time limit: its ``lower_bound`` is then 0, no bound claimed).
    time_share : float or None  [s]
        The trial's share of ``[plan] time_limit`` (what was left of it); None without one.
    evaluated : int or None
        Sets (rows) the trial's search evaluated; None where it found no plan.
    """

    lengths: tuple[float, ...]
    value: float | None
    lower_bound: float
    lugs: tuple[str, ...] = ()
    reason: str = ""
    stopped: str = "proved"
    time_share: float | None = None
    evaluated: int | None = None

    @property
    def cut_short(self):
        """True: the trial's search ended on its share of the time limit."""
        return self.stopped == "time_limit"


@dataclass(frozen=True)
class LengthSearch:
    """How the rope lengths were chosen.

    Parameters
    ----------
    classes : tuple of tuple of str
        Names of the cranes that share each chosen length (one class each).
    ranges : tuple of (float, float)  [m]
        Each class's payout range.
    trials : tuple of LengthTrial
        Every length set tried, in the order tried.
    chosen : tuple of float  [m]
        The lengths of the plan.
    """

    classes: tuple[tuple[str, ...], ...]
    ranges: tuple[tuple[float, float], ...]
    trials: tuple[LengthTrial, ...]
    chosen: tuple[float, ...]

    #: Lengths the search meant to try but did not: the time limit had run out.
    not_tried: int = 0

    @property
    def lower_bound(self):
        """Least certified bound over the lengths tried  [t or -]; 0 (no bound claimed) when
        the time limit left lengths the search meant to try untried."""
        return 0.0 if self.not_tried else min(t.lower_bound for t in self.trials)

    @property
    def cut_short(self):
        """Trials cut short by the time limit."""
        return tuple(t for t in self.trials if t.cut_short)

    @property
    def evaluated(self):
        """Sets evaluated over every length tried (each trial's own search counted)."""
        return sum(t.evaluated or 0 for t in self.trials)

    def to_json(self):
        return {
            "classes": [
                {"cranes": list(names), "min": lo, "max": hi, "chosen": length}
                for names, (lo, hi), length in zip(self.classes, self.ranges, self.chosen)
            ],
            "trials": [
                {
                    "lengths": list(t.lengths),
                    "worst": t.value,
                    "lower_bound": t.lower_bound if math.isfinite(t.lower_bound) else None,
                    "lugs": list(t.lugs),
                    "reason": t.reason,
                    "stopped": t.stopped,
                    "time_share": t.time_share,
                    "evaluated": t.evaluated,
                }
                for t in self.trials
            ],
            "evaluated": self.evaluated,
            "not_tried": self.not_tried,
        }


def varying_classes(problem):
    """Crane classes whose cranes have a length range, as tuples of fleet indices."""
    return tuple(
        group for group in problem.crane_classes if problem.fleet[group[0]].rope_length_range is not None
    )


def with_lengths(problem, classes, lengths):
    """A copy of the problem with each class's cranes at a fixed rope length.

    Parameters
    ----------
    problem : PlanProblem
    classes : tuple of tuple of int
        Fleet indices per class.
    lengths : sequence of float  [m]
        One per class.

    Returns
    -------
    PlanProblem
        No ranges left; the objective is the original problem's (cranes of different
        lengths would otherwise make a default objective change to ``utilisation``).
    """
    fleet = list(problem.fleet)
    for group, length in zip(classes, lengths):
        for j in group:
            fleet[j] = dataclasses.replace(
                fleet[j], rope_length=float(length), rope_length_range=None, from_defaults=False
            )
    crane = problem.crane
    if crane is not None and crane.rope_length_range is not None:
        low, high = crane.rope_length_range
        crane = dataclasses.replace(crane, rope_length=high, rope_length_range=None)
    return dataclasses.replace(problem, fleet=tuple(fleet), crane=crane, objective=problem.objective)


def first_pass(ranges):
    """The first pass's lengths per class  [m] (see the module docstring)."""
    varying = sum(1 for lo, hi in ranges if hi > lo)
    steps = LENGTH_STEPS
    while varying and steps > 2 and steps**varying > MAX_GRID:
        steps -= 1
    return [np.linspace(lo, hi, steps) if hi > lo else np.array([lo]) for lo, hi in ranges]


def plan_lengths(problem, top=None, inner=None):
    """Plan lugs, boom heights and rope lengths (cranes with a ``rope_length`` range).

    Parameters
    ----------
    problem : PlanProblem
        At least one crane with ``rope_length_range``.
    top : int, optional
    inner : callable, optional
        ``inner(problem, top) -> plan``: the planner at fixed lengths. Default: the held
        plan of single ropes. Cranes on slings pass the sling planner
        (:func:`liftplan.planner.plan.plan` does): the range is then the hoist rope's, tip to
        hook, and the result a sling plan with ``with_lengths`` and ``length_summary``.

    Returns
    -------
    Plan or sling plan
        Planned at the chosen lengths (its ``problem`` is the copy with them fixed, so its
        scene, boom heights and design loads follow), with ``lengths`` the
        :class:`LengthSearch` and ``stats`` over every trial (the lower bound the least of
        theirs, the sets evaluated and seconds summed).

    Raises
    ------
    PlanInfeasible
        No length tried gives a feasible plan (the reason at the longest lengths).
    Interrupted
        Ctrl-C: ``plan`` is the best plan over the lengths tried so far (the interrupted
        trial's best plan among them), ``stats.stopped = "interrupted"``.
    """

    start = _clock()
    planner = inner
    classes = varying_classes(problem)
    ranges = tuple(problem.fleet[g[0]].rope_length_range for g in classes)
    results = {}
    trials = []
    grids = first_pass(ranges)
    most = len(_product(grids)) + 2 * REFINE_ROUNDS * len(ranges)  # trials at most
    bar = progress_bar(most, None, desc="rope lengths: trials", unit="trials", ticker=True)
    skipped = set()  # lengths not tried: the time limit had run out
    trying = None  # the lengths being tried

    def run(lengths):
        nonlocal trying
        key = tuple(round(float(v), 9) for v in lengths)
        if key in results:
            return results[key]
        trying = key
        inner = with_lengths(problem, classes, key)
        left = None
        if problem.time_limit is not None:  # the limit is the whole search's: each trial gets what is left
            left = problem.time_limit - (_clock() - start)
            if left <= 0.0:
                skipped.add(key)
                return None
            inner = dataclasses.replace(inner, time_limit=left)
        began = _clock()
        try:
            result = plan_held(inner, top, girder_order=False) if planner is None else planner(inner, top)
        except PlanInfeasible as err:
            result = None
            reason = str(err).replace("\n", " ")
            if left is not None and _clock() - began >= left:  # its share ran out: not proved infeasible
                trials.append(
                    LengthTrial(key, None, 0.0, reason=reason, stopped="time_limit", time_share=left)
                )
            else:
                trials.append(LengthTrial(key, None, math.inf, reason=reason, time_share=left))
        else:
            trials.append(dataclasses.replace(_trial(key, result), time_share=left))
        results[key] = result
        if bar is not None:
            bar.update(1)
            found = [_summary(r)[0] for r in results.values() if r is not None]
            low = min((t.lower_bound for t in trials), default=None)
            bar.set_postfix_str(best_bound(min(found, default=None), low))
        return result

    def value(key):
        result = results[key]
        # to 12 significant digits: lengths that plan the same (two or three cranes on slings,
        # statically determinate) tie, and the first (shortest) is kept, not round-off's pick
        return math.inf if result is None else float(f"{_summary(result)[0]:.12g}")

    try:
        for lengths in _product(grids):
            run(lengths)
        if not results:
            raise PlanInfeasible(
                f"rope lengths: no length set tried within the time limit {problem.time_limit:g} s "
                f"({_ranges_text(problem, classes, ranges)}); expected a longer plan.time_limit"
            )
        best = min(results, key=value)  # first (shortest) of equals: dicts keep insertion order
        steps = [(hi - lo) / max(len(g) - 1, 1) for (lo, hi), g in zip(ranges, grids)]
        for _ in range(REFINE_ROUNDS):
            for i, (lo, hi) in enumerate(ranges):
                steps[i] /= 2.0
                if steps[i] <= 0.0:
                    continue
                for sign in (-1.0, 1.0):
                    trial = list(best)
                    trial[i] = best[i] + sign * steps[i]
                    if lo - 1e-9 <= trial[i] <= hi + 1e-9:
                        run(trial)
                best = min(results, key=value)
    except KeyboardInterrupt as stop:  # the best plan over the lengths tried so far
        partial = getattr(stop, "plan", None)  # the interrupted trial's best plan, if any
        if partial is not None and trying not in results:
            trials.append(_trial(trying, partial, "interrupted: the best plan so far at these lengths"))
            results[trying] = partial
        what = f"rope lengths: trial {len(trials) + (partial is None)}"
        if not any(r is not None for r in results.values()):
            raise Interrupted([], None, phase=what) from None
        best = min(results, key=value)
        chosen = _chosen(problem, classes, ranges, trials, results, best, start, "interrupted")
        raise Interrupted(chosen.ranking, getattr(chosen, "stats", None), plan=chosen, phase=what) from None
    finally:
        if bar is not None:
            bar.close()
    if results[best] is None:
        longest = max(trials, key=lambda t: sum(t.lengths))
        raise PlanInfeasible(
            f"rope lengths: no feasible plan at any of {len(trials)} length sets tried within "
            f"{_ranges_text(problem, classes, ranges)}; at the longest ({_lengths_text(longest.lengths)}): "
            f"{longest.reason}"
        )
    stopped = "time_limit" if skipped or any(t.cut_short for t in trials) else None
    return _chosen(problem, classes, ranges, trials, results, best, start, stopped, len(skipped))


def _clock():
    """Seconds on the clock that measures the time limit (a function, so that a test can
    stand in for the machine's speed)."""
    return time.perf_counter()


def _summary(result):
    """(worst value, certified lower bound, lug names, rows evaluated) of a trial's plan: a
    held :class:`Plan`'s, or a sling plan's ``length_summary``."""
    if isinstance(result, Plan):
        chosen, stats = result.chosen, result.stats
        return float(chosen.worst_value), float(stats.lower_bound), tuple(chosen.lugs), stats.evaluated
    return result.length_summary


def _trial(key, result, reason=""):
    """The :class:`LengthTrial` of a plan at lengths ``key``."""
    value, bound, lugs, evaluated = _summary(result)
    own = getattr(result, "stats", None)
    stopped = "proved" if own is None else own.stopped
    return LengthTrial(key, value, bound, lugs, reason, stopped=stopped, evaluated=evaluated)


def _chosen(problem, classes, ranges, trials, results, best, start, stopped, not_tried=0):
    """The plan at the best lengths, with the length search and the stats over every trial
    (``stopped`` None: the chosen trial's own; the counts are the chosen trial's own, so they
    add up to its rows), its problem keeping the user's ``time_limit``."""
    chosen = _user_limit(results[best], problem.time_limit)
    search = LengthSearch(
        classes=tuple(tuple(problem.fleet[j].name for j in g) for g in classes),
        ranges=ranges,
        trials=tuple(trials),
        chosen=best,
        not_tried=not_tried,
    )
    own = getattr(chosen, "stats", None)  # a two-crane sling plan's search has none: exhaustive
    stats = (
        None
        if own is None
        else dataclasses.replace(
            own,
            lower_bound=min(search.lower_bound, own.lower_bound),
            seconds=_clock() - start,
            stopped=stopped or own.stopped,
        )
    )
    if not isinstance(chosen, Plan):  # a sling plan: its own outputs carry the search
        return chosen.with_lengths(search, stats)
    ranking, girders = girder_first(chosen.problem, chosen.ranking)
    plan = dataclasses.replace(chosen, ranking=ranking, girders=girders, stats=stats, lengths=search)
    return design_first(plan)  # the sets that fail a design-load check after those that meet them


def _user_limit(result, time_limit):
    """A trial's plan with its problem's ``time_limit`` the user's (the trial ran on its
    share of it)."""
    problem = getattr(result, "problem", None)
    if problem is None or not dataclasses.is_dataclass(result) or problem.time_limit == time_limit:
        return result
    return dataclasses.replace(result, problem=dataclasses.replace(problem, time_limit=time_limit))


def _product(grids):
    import itertools

    return [tuple(float(v) for v in combo) for combo in itertools.product(*grids)]


def _lengths_text(lengths):
    return ", ".join(f"{v:.2f} m" for v in lengths)


def _ranges_text(problem, classes, ranges):
    return "; ".join(
        f"{', '.join(problem.fleet[j].name for j in g)} {lo:g} to {hi:g} m"
        for g, (lo, hi) in zip(classes, ranges)
    )
