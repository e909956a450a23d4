"""A plan's console summary, by its kind: one row per kind of plan (``plan.kind``)."""

from __future__ import annotations

from liftplan.planner.output.console.held import plan_table
from liftplan.planner.output.console.slings import sling_table
from liftplan.planner.output.console.strength import strength_table

#: plan kind (:data:`liftplan.planner.plan.KINDS`) -> its console summary.
SUMMARIES = {
    "held": plan_table,
    "lengths": plan_table,
    "slings": sling_table,
    "strength": strength_table,
}


def summary(plan):
    """The readable summary of any plan (``liftplan plan`` without ``--json``)  [text]."""
    return SUMMARIES[plan.kind](plan)
