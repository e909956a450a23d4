"""The planning problem: what to lift, where it may be held, with which cranes, under which rules.

Read this first. :mod:`.definition` holds the frozen :class:`PlanProblem` (body, candidate
strong points, tolerances, CG envelope) and checks it where it is made; :mod:`.fleet` the
cranes (positions, load charts, slings) and the rules' tension limits the search holds every
rope to; :mod:`.file` reads planning files (TOML; every key in ``docs/scene-files.md``);
:mod:`.report_info` the report's title block; :mod:`.plausibility` the unit-slip warnings.
"""

from liftplan.planner.problem.definition import Candidate, CogEnvelope, CraneSpec, PlanProblem
from liftplan.planner.problem.file import load_problem, loads_problem, problem_from_dict
from liftplan.planner.problem.fleet import FleetCrane, SlingSpec

__all__ = [
    "Candidate",
    "CogEnvelope",
    "CraneSpec",
    "FleetCrane",
    "PlanProblem",
    "SlingSpec",
    "load_problem",
    "loads_problem",
    "problem_from_dict",
]
