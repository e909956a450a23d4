"""liftplan's planner: lugs among candidates and boom heights, reports, command line.

Python API::

    from liftplan.planner import load_problem, plan, write_report
    p = plan(load_problem("examples/tanker_plan.toml"))
    p.lugs, p.boom_heights, p.worst_spread

The names below are loaded on first use (PEP 562): the command line imports this package
for every command, and only ``plan`` needs cvxpy.
"""

import importlib
import sys
import types

#: Public name -> the submodule that defines it.
_EXPORTS = {
    **dict.fromkeys(("CraneCapacity", "GuidanceStep", "Plan", "SkewLoad", "plan"), "plan"),
    **dict.fromkeys(("Candidate", "CogEnvelope", "CraneSpec", "PlanProblem"), "problem.definition"),
    **dict.fromkeys(("load_problem", "loads_problem"), "problem.file"),
    "write_report": "output.report",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name):
    try:
        module = _EXPORTS[name]
    except KeyError:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}") from None
    value = getattr(importlib.import_module(f"{__name__}.{module}"), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))


class _Package(types.ModuleType):
    """Keeps the function ``plan`` as the package attribute when the submodule of the same
    name is first imported (the import system would otherwise bind the module there)."""

    def __setattr__(self, name, value):
        if (isinstance(value, types.ModuleType) and _EXPORTS.get(name) == name
                and value.__name__ == f"{__name__}.{name}"):
            value = getattr(value, name)
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Package
