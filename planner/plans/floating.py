"""Held plans with floating cranes: the search with each vessel in series with its rope.

The vessel's tip compliance depends on the lug its crane takes (its offset from the flotation
centre). The search runs on the reference problem
(:func:`~liftplan.planner.problem.vessels.reference_problem`: each floating crane at its
stiffest lug in reach, the most twist a hook error can put in), whose stiffnesses its
screening bounds read; every set it evaluates is evaluated exactly, with each vessel in series
at the lug its crane takes (:class:`~liftplan.planner.search.evaluator.SetEvaluator`,
:func:`~liftplan.planner.problem.vessels.series_fleet`), and ruled out when its worst states
put a vessel beyond its heel or trim limit or below its least freeboard, the levelling ballast
set for its level tensions. So the ranking holds only sets that keep every vessel within its
limits, each with its exact value. The plan is the best of them; its problem is its own exact
one (:func:`~liftplan.planner.problem.vessels.series_problem`), so its boom heights, worst
case, hook tolerance, design loads and scene (each crane with its vessel and its rope's own EA)
are the coupled model's.
"""

from __future__ import annotations

from liftplan.planner.plans.held import Plan, girder_first, plan_held
from liftplan.planner.problem.vessels import reference_problem, series_problem, uses_vessels, wind_problem


def plan_single_ropes(problem, top=None):
    """:func:`plan_held`, or :func:`plan_floating` when a crane stands on a vessel; with a
    wind, the body's couple in the CG envelope first (:func:`wind_problem`)."""
    problem = wind_problem(problem)
    return plan_floating(problem, top) if uses_vessels(problem) else plan_held(problem, top)


def plan_floating(problem, top=None):
    """A held plan with floating cranes (module docstring).

    Parameters
    ----------
    problem : PlanProblem
        Some fleet cranes with a ``vessel``.
    top : int, optional

    Returns
    -------
    Plan
        Its ``problem`` the exact series problem of the chosen set; ``ranking`` the searched
        sets, each evaluated with its vessels in series at its own lugs, best first; the sets
        ruled out by a vessel's limit counted in ``stats.infeasible`` with their cause.

    Raises
    ------
    PlanInfeasible
        No set holds the body with its vessels in series at its lugs and every vessel within
        its limits; the message counts each cause.
    """
    first = plan_held(reference_problem(problem), top, girder_order=False)
    best = first.ranking[0]
    chosen = series_problem(problem, best.indices, best.cranes)
    ranked, girders = girder_first(chosen, first.ranking)
    return Plan(problem=chosen, ranking=ranked, stats=first.stats, girders=girders)
