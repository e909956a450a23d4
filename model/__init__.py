"""liftplan's physics: the scene, the one casadi model, and its solvers.

Python API for planners::

    from liftplan.model import load_scene, solve
    scene = load_scene("examples/tanker_upright.toml")
    eq = solve(scene)                      # Equilibrium
    eq.tensions["T1"], eq.pose.heel
    eq2 = solve(scene.with_crane("T1", boom_height=41.0))

The names below are loaded on first use (PEP 562), so ``import liftplan.model`` (and the
command line's ``--help``) does not pay for casadi, numpy or pydantic until they are needed.
"""

import importlib
import sys
import types

#: Public name -> the submodule that defines it.
_EXPORTS = {
    **dict.fromkeys(("EquilibriumNotFound", "InvalidScene", "LiftPlanError", "PlanInfeasible",
                     "SolverFailed"), "errors"),
    **dict.fromkeys(("choi_to_zup", "rotation_matrix", "zup_to_choi"), "frames"),
    **dict.fromkeys(("Compartment", "Hull"), "hull"),
    **dict.fromkeys(("LoadCurve", "load_curve"), "lift"),
    **dict.fromkeys(("Equilibrium", "Pose", "SolverInfo"), "results"),
    **dict.fromkeys(("Analysis", "Attitude", "Body", "Crane", "Ground", "Lug", "Redundant", "Scene",
                     "Water"), "scene"),
    **dict.fromkeys(("load_scene", "loads_scene"), "scenefile"),
    **dict.fromkeys(("paper_elastic_tensions", "pick_model", "solve", "solve_elastic",
                     "solve_paper_elastic", "solve_rigid"), "solve"),
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
    """Keeps the function ``solve`` as the package attribute when the submodule of the same
    name is first imported (the import system would otherwise bind the module there)."""

    def __setattr__(self, name, value):
        if (isinstance(value, types.ModuleType) and _EXPORTS.get(name) == name
                and value.__name__ == f"{__name__}.{name}"):
            value = getattr(value, name)
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Package
