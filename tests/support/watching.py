"""The watched tanker: its plan made once per test run, its watch basis and a plan JSON."""

import functools
import json

from helpers import EXAMPLES

from liftplan.planner.plan import plan
from liftplan.planner.plans.watch_basis import watch_basis
from liftplan.planner.problem.file import load_problem


@functools.cache
def tanker_plan():
    """The plan of ``examples/tanker_plan.toml`` (the planner's own answer, ~5 s once)."""
    return plan(load_problem(EXAMPLES / "tanker_plan.toml"))


def tanker_basis():
    return watch_basis(tanker_plan())


def plan_json(folder):
    """A plan JSON holding the tanker's ``"watch"`` object, written in ``folder``."""
    path = folder / "plan.json"
    path.write_text(json.dumps({"watch": tanker_basis().to_json()}), encoding="utf-8")
    return path
