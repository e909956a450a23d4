"""``plan(problem)``: the one entry to every kind of plan, and the one place a kind is chosen.

A kind of plan is one row of :data:`KINDS`: its name, the test that says whether a planning
problem is of that kind, and the planner that makes it. The first row whose test passes
plans the problem; every result is a :class:`~liftplan.planner.plans.protocol.LiftPlan` that
carries its kind's name (``result.kind``), so the outputs never decide the kind again.

A new kind of plan is one module under :mod:`liftplan.planner.plans` (its planner and its
result class) and one row here, placed before the rows whose test would also pass.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from liftplan.planner.plans.hull_water import plan_hull_water
from liftplan.planner.plans.lengths import plan_lengths
from liftplan.planner.plans.protocol import LiftPlan
from liftplan.planner.plans.slings import plan_slings, uses_slings
from liftplan.planner.plans.strength import plan_strength, uses_strength
from liftplan.planner.plans.strength_slings import plan_strength_slings, uses_strength_slings
from liftplan.planner.problem.definition import PlanProblem
from liftplan.planner.search.evaluator import Interrupted


@dataclass(frozen=True)
class PlanKind:
    """One kind of plan.

    Parameters
    ----------
    name : str
        What ``result.kind`` says (``"held"``, ``"slings"``, ...).
    applies : callable
        ``applies(problem) -> bool``: the problem is of this kind.
    make : callable
        ``make(problem, top) -> LiftPlan``: the planner.
    """

    name: str
    applies: Callable[[PlanProblem], bool]
    make: Callable[[PlanProblem, int | None], LiftPlan]


def _slings(problem, top):
    """A sling plan; with hoist-rope payout ranges, the rope-length search around it (the
    two kinds of plan do not import each other: they meet here)."""
    if problem.chooses_rope_lengths:
        return plan_lengths(problem, top, inner=plan_slings)
    return plan_slings(problem, top)


def _strength(problem, top):
    """A plan for the hull girder: on single ropes, or on the slings' hooks
    (:mod:`~liftplan.planner.plans.strength_slings`)."""
    if uses_strength_slings(problem):
        return plan_strength_slings(problem, top)
    return plan_strength(problem, top)


#: The kinds of plan, tried in order: the first that applies plans the problem.
KINDS = (
    PlanKind("strength", uses_strength, _strength),  # the hull girder's objectives (also on slings)
    PlanKind("slings", uses_slings, _slings),  # cranes on sling sets or spreader bars
    PlanKind("lengths", lambda problem: problem.chooses_rope_lengths, plan_lengths),  # payout ranges
    PlanKind("held", lambda problem: True, plan_hull_water),  # single ropes, a held level preload
    # (with floating cranes: the vessels in series with the ropes, planner/plans/floating.py;
    # with [hull] EI or [water]: ranked again on the governing model, planner/plans/hull_water.py)
)


def plan_kind(problem: PlanProblem) -> PlanKind:
    """The kind of plan a problem asks for (the first row of :data:`KINDS` that applies)."""
    return next(kind for kind in KINDS if kind.applies(problem))


def plan(problem: PlanProblem, top: int | None = None) -> LiftPlan:
    """Plan a lift: lugs among the candidates, the crane on each, and boom heights.

    Parameters
    ----------
    problem : PlanProblem
    top : int, optional
        How many lug sets to rank (default ``problem.top``).

    Returns
    -------
    LiftPlan
        Of the kind :func:`plan_kind` picks: a :class:`~liftplan.planner.plans.held.Plan`
        (single ropes, also with rope-length ranges), a sling-lift plan
        (:class:`~liftplan.planner.plans.slings.lift.SlingLift`) or a
        :class:`~liftplan.planner.plans.strength.StrengthPlan`.

    Raises
    ------
    PlanInfeasible
        No lug set can hold the body within the tolerances and limits; the message names
        the causes and how many sets each ruled out.
    Interrupted
        Ctrl-C, in every kind: ``plan`` holds the best plan found so far (None when none
        was), ``phase`` where it landed, ``finished`` whether the search had ended.
    """
    if top is None:
        problem.check_top(problem.top)
    else:
        problem.check_top(top, "top")
    kind = plan_kind(problem)
    try:
        return kind.make(problem, top)
    except Interrupted:
        raise
    except KeyboardInterrupt:  # before the kind's planner had a plan to keep
        raise Interrupted([], None, phase=f"{kind.name} plan") from None
