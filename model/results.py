"""Result objects of a solve."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Pose:
    """Body pose (angles as in :mod:`liftplan.model.frames`).

    Parameters
    ----------
    heel : float  [deg]   > 0 starboard side down
    trim : float  [deg]   > 0 bow down
    yaw : float  [deg]
    lift_height : float  [m]   height of the body-frame origin above the datum
    """

    heel: float
    trim: float
    yaw: float
    lift_height: float


@dataclass(frozen=True)
class SolverInfo:
    """How a result was obtained.

    Parameters
    ----------
    method : str
        ``"linear"`` (exact solve of the linear statics), ``"newton"`` (casadi root-finder)
        or ``"energy"`` (IPOPT on the potential energy).
    converged : bool
    iterations : int or None
        Iterations, where the method reports them.
    seconds : float  [s]
        Wall time of the numerical solve.
    """

    method: str
    converged: bool
    iterations: int | None
    seconds: float


@dataclass(frozen=True)
class Equilibrium:
    """Equilibrium of the body on its ropes.

    Parameters
    ----------
    model : str
        ``"elastic"``, ``"paper-elastic"`` or ``"rigid"``.
    pose : Pose
    tensions : dict of str to float  [t]
        Rope tension by lug name, in scene order.
    weight : float  [t]
    swl : dict of str to float or None  [t]
        Safe working load by lug name (None where not given).
    slack : tuple of str
        Lugs whose rope carries nothing.
    residual : float  [t]
        Largest equilibrium error: force, and moments divided by the lugs' plan diameter.
    solver : SolverInfo
    """

    model: str
    pose: Pose
    tensions: dict[str, float]
    weight: float
    swl: dict[str, float | None]
    slack: tuple[str, ...]
    residual: float
    solver: SolverInfo

    @property
    def share(self):
        """Each rope's share of the weight, by lug name  [-]."""
        return {name: t / self.weight for name, t in self.tensions.items()}

    @property
    def utilisation(self):
        """Tension over the crane's SWL, by lug name (None where no SWL)  [-]."""
        return {
            name: (t / self.swl[name] if self.swl[name] else None)
            for name, t in self.tensions.items()
        }

    @property
    def spread(self):
        """Largest minus smallest tension  [t]."""
        values = list(self.tensions.values())
        return max(values) - min(values)

    def to_json(self):
        """The JSON object of ``liftplan solve --json`` (keys fixed by CONTRACT.md)."""
        return {
            "model": self.model,
            "converged": self.solver.converged,
            "tensions": dict(self.tensions),
            "heel": self.pose.heel,
            "trim": self.pose.trim,
            "yaw": self.pose.yaw,
            "lift_height": self.pose.lift_height,
            "weight": self.weight,
            "spread": self.spread,
            "share": self.share,
            "utilisation": self.utilisation,
            "slack": list(self.slack),
            "residual": self.residual,
            "solver": {
                "method": self.solver.method,
                "iterations": self.solver.iterations,
                "seconds": self.solver.seconds,
            },
        }
