"""liftplan's planner: lugs among candidates and boom heights, reports, command line.

Python API::

    from liftplan.planner import load_problem, plan, write_report
    p = plan(load_problem("examples/tanker_plan.toml"))
    p.lugs, p.boom_heights, p.worst_spread
"""

from .plan import CraneCapacity, GuidanceStep, Plan, SkewLoad, plan
from .problem import Candidate, CogEnvelope, CraneSpec, PlanProblem
from .problemfile import load_problem, loads_problem


def write_report(plan, directory):
    """Write the plan's report (see :func:`liftplan.planner.report.write_report`)."""
    from .report import write_report as write  # matplotlib is imported only here

    return write(plan, directory)


__all__ = [
    "Candidate", "CogEnvelope", "CraneCapacity", "CraneSpec", "GuidanceStep", "Plan",
    "PlanProblem", "SkewLoad", "load_problem", "loads_problem", "plan", "write_report",
]
