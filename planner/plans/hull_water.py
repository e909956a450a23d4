"""Held plans with the flexible hull or a start in water: the ranking redone on the model that governs.

The search ranks lug sets on the rigid hull in air (:func:`~.floating.plan_single_ropes`).
Then each ranked set is evaluated on what the planning file adds:

* ``[hull] EI``: the flexible hull at the set's worst states (:mod:`.flexible`); where it
  changes a tension by more than 1 % its objective value is the flexible one;
* ``[water]``: the state at the start of the lift in water (:mod:`.in_water`); the set's value
  is the larger of the box's and the value there.

The sets are ranked again on that governing value, those whose hull girder or in-water state
fails (a rope slack in water) after those that hold, and then those that fail a design-load
check after those that meet them (:func:`~.held.design_first`). The plan is the best of them, and it is
the best of every set: a set the search did not rank is, on the rigid hull in air, no better
than the last one ranked (the search proves its ranking), in water no better than in air, and
on the flexible hull no better by more than :func:`~.flexible.change_bound` (the bound of the
flexible correction over every set); when the best governing value is not below the last ranked
set's rigid value less that bound, no set outside the ranking can beat it (``certified``).
Otherwise the search is asked for a longer ranking (four times, up to :data:`MAX_RANKED` sets,
and not past ``[plan] time_limit``) and the sets evaluated again; where that ends uncertified
the plan says so (``certified`` false, and the bound). The reported ranking is the first
``top`` of it.
"""

from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass

import numpy as np

from liftplan.planner.plans.design_loads import DesignBuilder
from liftplan.planner.plans.flexible import change_bound, deflection_bounds, evaluate_flexible
from liftplan.planner.plans.floating import plan_single_ropes
from liftplan.planner.plans.held import Plan, design_first
from liftplan.planner.plans.in_water import in_water_case
from liftplan.planner.search.scenarios import LugSet

#: The longest ranking asked for to certify the re-ranking (each set costs a few flexible
#: solves, some 20 ms each on an idle core): beyond it the plan says it is not certified.
MAX_RANKED = 24
#: Up to this many (set, assignment) rows the ranking may be asked for all of them: every set
#: evaluated certifies the plan whatever the bound.
ALL_ROWS = 100


@dataclass(frozen=True)
class HullSearch:
    """How the ranking was redone on the governing model.

    Parameters
    ----------
    values : list of float  [t or -]
        Each reported set's governing value (what it is ranked on), best first.
    evaluated : int
        Sets evaluated on the flexible hull or in water (the search's longest ranking).
    margin : float  [t or -]
        The flexible hull's bound on any set's change of objective (0 without ``[hull] EI``).
    last_rigid : float  [t or -]
        The rigid value of the last set the search ranked.
    certified : bool
        No set outside the evaluated ones can beat the plan (module docstring).
    note : str
    """

    values: list
    evaluated: int
    margin: float
    last_rigid: float
    certified: bool
    note: str

    def to_json(self):
        return dataclasses.asdict(self)


def uses_hull_water(problem):
    """The problem gives ``[hull] EI`` or ``[water]``."""
    return problem.hull_stiffness is not None or problem.in_water is not None


def plan_hull_water(problem, top=None):
    """A held plan ranked on the flexible hull and the start in water (module docstring).

    Parameters
    ----------
    problem : PlanProblem
        With ``hull_stiffness`` or ``in_water`` (else it is :func:`plan_single_ropes`).
    top : int, optional

    Returns
    -------
    Plan
        With ``hull_models`` (``[hull] EI``) and ``hull_search``.
    """
    if not uses_hull_water(problem):
        return design_first(plan_single_ropes(problem, top))
    wanted = top or problem.top
    flexible = problem.hull_stiffness is not None
    bounds = deflection_bounds(problem) if flexible else None
    margin = change_bound(problem, bounds) if flexible else 0.0
    ask = wanted
    limit = problem.row_count if problem.row_count <= ALL_ROWS else max(MAX_RANKED, wanted)
    started = time.perf_counter()
    seen = {}  # (lugs, cranes) -> evaluation: a longer ranking repeats the sets ranked before
    while True:
        first = plan_single_ropes(problem, ask)
        rows = _evaluate(first, bounds, seen)
        order = sorted(range(len(rows)), key=lambda k: (not rows[k][2], rows[k][0], k))
        good = [rows[k][0] for k in order if rows[k][2]]
        last = max(float(r.worst_value) for r in first.ranking)
        complete = len(first.ranking) < ask or len(first.ranking) >= problem.row_count
        proved = first.stats.stopped == "proved"
        certified = proved and (complete or (bool(good) and last - margin >= good[0]))
        late = problem.time_limit is not None and time.perf_counter() - started > problem.time_limit
        # no set's rigid value exceeds the ceiling: past it only a ranking of every row certifies
        hopeless = bool(good) and good[0] + margin > ceiling(problem) and limit < problem.row_count
        if certified or not proved or ask >= limit or late or hopeless:
            break
        ask = min(4 * ask, limit)
    note = _note(certified, proved, complete, len(first.ranking), margin, last, good)
    keep = order[:wanted]
    ranking = [first.ranking[k] for k in keep]
    girders = None if first.girders is None else [first.ranked_girder[k] for k in keep]
    search = HullSearch(
        values=[rows[k][0] for k in keep],
        evaluated=len(first.ranking),
        margin=margin,
        last_rigid=last,
        certified=certified,
        note=note,
    )
    stats = governing_stats(first.stats, search.values[0], good, last, margin, certified, proved)
    plan = Plan(
        problem=first.problem,
        ranking=ranking,
        stats=stats,
        girders=girders,
        hull_models=[rows[k][1] for k in keep] if flexible else None,
        hull_search=search,
    )
    return design_first(plan)  # the sets that fail a design-load check after those that meet them


def governing_stats(stats, best, good, last, margin, certified, proved):
    """The search's stats restated on the governing model: the plan's ``best`` is its governing
    value, and the lower bound is one on the governing values of every set (the rigid search's
    bound is one on the rigid hull in air, which the governing value may exceed).

    A set the search ranked is bounded by its own governing value; one it did not rank is, with
    the ranking proved, no better than ``last - margin`` (module docstring), and without the
    proof no better than the search's lower bound less ``margin``. Certified, the bound is the
    plan's own value (gap 0)."""
    if certified:
        lower = best
    else:
        outside = (last if proved else stats.lower_bound) - margin
        lower = min([outside, *good[:1]])
    return dataclasses.replace(stats, best=best, lower_bound=min(lower, best))


def ceiling(problem):
    """No set's objective exceeds this  [t or -]: every tension the search admits lies within
    [min_tension, its limit], each limit below its crane's chart SWL, so a spread is below the
    largest SWL less min_tension and a T / SWL (or its spread) below 1."""
    if problem.goal.per_swl or problem.goal.peak:
        return 1.0
    return float(np.nanmax(problem.reach[1])) - problem.min_tension


def _evaluate(first, bounds, seen):
    """Each ranked set's (governing value, HullModel or None, holds) in the search's order."""
    problem = first.problem
    dense = DesignBuilder(problem).dense
    girders = first.ranked_girder
    out = []
    for k, result in enumerate(first.ranking):
        key = (result.indices, result.cranes, tuple(np.round(result.preload, 9)))
        if key in seen:
            out.append(seen[key])
            continue
        model = None if bounds is None else evaluate_flexible(problem, result, dense, bounds)
        value = float(result.worst_value) if model is None else model.value
        holds = all(w.ratio <= 1.0 for w in girders[k])
        if problem.in_water is not None:
            lugset = LugSet(problem, result.indices, result.cranes)
            case = in_water_case(problem, lugset, np.asarray(result.preload, dtype=float))
            value = max(value, case.value)
            holds = holds and case.holds
        seen[key] = (value, model, holds)
        out.append(seen[key])
    return out


def _note(certified, proved, complete, ranked, margin, last, good):
    if certified and complete:
        return f"every feasible set ({ranked}) evaluated on the governing model"
    if certified:
        return (
            f"{ranked} sets evaluated; any other is at least {last:.6g} on the rigid hull in air, "
            f"so no better than {last - margin:.6g} on the governing model, not below the plan's "
            f"{good[0]:.6g}"
        )
    if not proved:
        return "the search did not prove its ranking: the re-ranking holds over the ranked sets only"
    return (
        f"{ranked} sets evaluated; a set outside them is no better than {last - margin:.6g} on the "
        f"governing model (the flexible hull's bound {margin:.6g} on any set's change: safe but wide, "
        "docs/planning.md), "
        + (f"below the plan's {good[0]:.6g}: not certified" if good else "and none of them holds")
    )
