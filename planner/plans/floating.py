"""Held plans with floating cranes: the search with each vessel in series with its rope.

The vessel's tip compliance depends on the lug its crane takes (its offset from the flotation
centre), while the search reads one stiffness per crane. So the search runs on the reference
problem (:func:`~liftplan.planner.problem.vessels.reference_problem`: each floating crane at
its stiffest lug in reach, the most twist a hook error can put in), and then every ranked set
is evaluated again, exactly, on the problem with each vessel in series at the lug its crane
takes (:func:`~liftplan.planner.problem.vessels.series_problem`), and ranked anew by that
evaluation. The plan is the best of them; its problem is its own exact one, so its boom
heights, worst case, hook tolerance, design loads and scene (each crane with its vessel and
its rope's own EA) are the coupled model's.
"""

from __future__ import annotations

from liftplan.model.errors import PlanInfeasible
from liftplan.planner.plans.held import Plan, girder_first, plan_held
from liftplan.planner.problem.vessels import reference_problem, series_problem, uses_vessels, wind_problem
from liftplan.planner.search.evaluator import SetEvaluator, SetInfeasible


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
        sets, each evaluated on its own exact problem, best first.

    Raises
    ------
    PlanInfeasible
        No set holds the body once its vessels are in series at its lugs (or none at all).
    """
    first = plan_held(reference_problem(problem), top, girder_order=False)
    evaluated = []
    for result in first.ranking:
        exact = series_problem(problem, result.indices, result.cranes)
        try:
            again = SetEvaluator(exact).evaluate(result.indices, result.cranes, result.screen_bound)
        except SetInfeasible:
            continue
        evaluated.append((again.worst_value, len(evaluated), again, exact))
    if not evaluated:
        raise PlanInfeasible(
            f"{len(first.ranking)} lug set(s) found with each floating crane at its stiffest lug, none "
            "of them holds the body with its vessels in series at its own lugs; expected stiffer "
            "vessels (GM, waterplane) or lugs nearer the vessels' axes"
        )
    evaluated.sort(key=lambda row: (row[0], row[1]))
    chosen = evaluated[0][3]
    ranking = [row[2] for row in evaluated]
    ranked, girders = girder_first(chosen, ranking)
    return Plan(problem=chosen, ranking=ranked, stats=first.stats, girders=girders)
