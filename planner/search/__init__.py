"""The search: which lug set, which crane on each lug, and which level preload.

Read this first. :mod:`.scenarios` turns a lug set and its cranes into tensions that are
affine in the level preload at every scenario (attitude, CG position) and in the hook
heights; :mod:`.bounds` holds the cvxpy/Clarabel linear programs (the preload minimax with the
hook-error margins, the admissible tensions); :mod:`.screen` bounds every (set, assignment)
row at once; :mod:`.branch` evaluates rows best bound first with cutting planes and proves
the plan's lower bound and gap.
"""

from liftplan.planner.search.evaluator import (
    DENSE,
    Interrupted,
    SearchStats,
    SetEvaluator,
    SetInfeasible,
    SetResult,
    robust,
)
from liftplan.planner.search.methods import search
from liftplan.planner.search.scenarios import LugSet, Scenario

__all__ = [
    "DENSE",
    "Interrupted",
    "LugSet",
    "Scenario",
    "SearchStats",
    "SetEvaluator",
    "SetInfeasible",
    "SetResult",
    "robust",
    "search",
]
