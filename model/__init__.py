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

from liftplan.model.lazy import lazy_package

TYPE_CHECKING = False  # typing.TYPE_CHECKING without importing typing (start-up)
if TYPE_CHECKING:  # what a type checker sees of the typed public API (loaded lazily below)
    from liftplan.model.results import Equilibrium as Equilibrium
    from liftplan.model.scene.file import load_scene as load_scene
    from liftplan.model.scene.file import loads_scene as loads_scene
    from liftplan.model.scene.objects import Scene as Scene
    from liftplan.model.solve import solve as solve
    from liftplan.model.version import __version__ as __version__

#: Public name -> the submodule that defines it.
_EXPORTS = {
    **dict.fromkeys(
        ("EquilibriumNotFound", "InvalidScene", "LiftPlanError", "PlanInfeasible", "SolverFailed"), "errors"
    ),
    **dict.fromkeys(("choi_to_zup", "rotation_matrix", "zup_to_choi"), "frames"),
    **dict.fromkeys(("Compartment", "Hull"), "scene.hull"),
    **dict.fromkeys(("LoadCurve", "load_curve"), "lift"),
    **dict.fromkeys(("BreakoutLoad", "breakout_load"), "water.breakout"),
    **dict.fromkeys(("Equilibrium", "Pose", "SolverInfo"), "results"),
    **dict.fromkeys(
        ("Analysis", "Attitude", "Body", "Crane", "Ground", "Lug", "Redundant", "Scene", "Water"),
        "scene.objects",
    ),
    **dict.fromkeys(("load_scene", "loads_scene"), "scene.file"),
    **dict.fromkeys(("pick_model", "solve"), "solve"),
    **dict.fromkeys(
        ("paper_elastic_tensions", "solve_elastic", "solve_paper_elastic", "solve_rigid"),
        "statics.vertical",
    ),
    **dict.fromkeys(("rigging_checks", "solve_rigging"), "statics.rigging"),
    **dict.fromkeys(("Leg", "RiggingLimits", "Sling", "Spreader", "sling_ea"), "scene.rigging_gear"),
    "RiggingState": "results",
    **dict.fromkeys(("hull_girder", "strength_checks"), "strength"),
    **dict.fromkeys(("HullForm", "Particulars", "fitted_hull"), "scene.hullfit"),
    "__version__": "version",
}

__all__ = sorted(n for n in _EXPORTS if not n.startswith("__"))  # __version__ is no API name

__getattr__, __dir__ = lazy_package(__name__, _EXPORTS)
