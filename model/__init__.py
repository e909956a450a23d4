"""liftplan's physics: the scene, the one casadi model, and its solvers.

Python API for planners::

    from liftplan.model import load_scene, solve
    scene = load_scene("examples/tanker_upright.toml")
    eq = solve(scene)                      # Equilibrium
    eq.tensions["T1"], eq.pose.heel
    eq2 = solve(scene.with_crane("T1", boom_height=41.0))
"""

from .errors import EquilibriumNotFound, InvalidScene, LiftPlanError, PlanInfeasible, SolverFailed
from .frames import choi_to_zup, rotation_matrix, zup_to_choi
from .hull import Compartment, Hull
from .lift import LoadCurve, load_curve
from .results import Equilibrium, Pose, SolverInfo
from .scene import Analysis, Attitude, Body, Crane, Ground, Lug, Redundant, Scene, Water
from .scenefile import load_scene, loads_scene
from .solve import (
    paper_elastic_tensions,
    pick_model,
    solve,
    solve_elastic,
    solve_paper_elastic,
    solve_rigid,
)

__all__ = [
    "Analysis", "Attitude", "Body", "Compartment", "Crane", "Equilibrium", "EquilibriumNotFound",
    "Ground", "Hull", "InvalidScene", "LiftPlanError", "LoadCurve", "Lug", "PlanInfeasible", "Pose",
    "Redundant", "Scene", "SolverFailed", "SolverInfo", "Water", "choi_to_zup", "load_curve",
    "load_scene", "loads_scene", "paper_elastic_tensions", "pick_model", "rotation_matrix", "solve",
    "solve_elastic", "solve_paper_elastic", "solve_rigid", "zup_to_choi",
]
