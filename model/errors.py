"""One error hierarchy for the whole project.

Every message is one line that names what is wrong and what is expected, so the
command line can print it as it is.
"""


class LiftPlanError(Exception):
    """Base class of every error liftplan raises on purpose."""


class InvalidScene(LiftPlanError, ValueError):
    """The scene (file or objects) is malformed or physically impossible to solve."""


class EquilibriumNotFound(LiftPlanError):
    """No equilibrium exists for the scene, or the solver could not find one."""


class SolverFailed(LiftPlanError):
    """A numerical solver stopped without converging."""


class PlanInfeasible(LiftPlanError):
    """No lug set and boom heights satisfy the plan's limits."""
