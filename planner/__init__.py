"""liftplan's planner: lugs among candidates and boom heights, reports, command line.

Python API::

    from liftplan.planner import load_problem, plan, write_report
    p = plan(load_problem("examples/tanker_plan.toml"))
    p.lugs, p.boom_heights, p.worst_spread

The names below are loaded on first use (PEP 562): the command line imports this package
for every command, and only ``plan`` needs cvxpy.
"""

from liftplan.model.lazy import lazy_package

TYPE_CHECKING = False  # typing.TYPE_CHECKING without importing typing (start-up)
if TYPE_CHECKING:  # what a type checker sees of the typed public API (loaded lazily below)
    from liftplan.model.version import __version__ as __version__
    from liftplan.planner.output.report.write import ReportFiles as ReportFiles
    from liftplan.planner.output.report.write import write_report as write_report
    from liftplan.planner.plan import plan as plan
    from liftplan.planner.plans.held import Plan as Plan
    from liftplan.planner.plans.protocol import LiftPlan as LiftPlan
    from liftplan.planner.problem.definition import PlanProblem as PlanProblem
    from liftplan.planner.problem.file import load_problem as load_problem
    from liftplan.planner.problem.file import loads_problem as loads_problem

#: Public name -> the submodule that defines it.
_EXPORTS = {
    **dict.fromkeys(("CraneCapacity", "GuidanceStep", "Plan", "SkewLoad"), "plans.held"),
    **dict.fromkeys(("LiftPlan",), "plans.protocol"),
    **dict.fromkeys(("KINDS", "plan", "plan_kind"), "plan"),
    **dict.fromkeys(("Candidate", "CogEnvelope", "CraneSpec", "PlanProblem"), "problem.definition"),
    **dict.fromkeys(("load_problem", "loads_problem"), "problem.file"),
    **dict.fromkeys(("ReportFiles", "write_report"), "output.report.write"),
    **dict.fromkeys(("view_figure", "write_view"), "output.view.api"),
    "__version__": "liftplan.model.version",
}

__all__ = sorted(n for n in _EXPORTS if not n.startswith("__"))  # __version__ is no API name

__getattr__, __dir__ = lazy_package(__name__, _EXPORTS)
