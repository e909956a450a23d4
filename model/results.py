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
        ``"linear"`` (exact solve of the linear statics), ``"newton"`` (casadi root-finder),
        ``"energy"`` (IPOPT on the potential energy) or ``"paper-newton"`` (the stranded-ship
        paper's J^T D J iteration).
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
class Afloat:
    """Water and ground forces of an equilibrium (world frame, ``z-up``).

    Parameters
    ----------
    state : str
        ``"grounded"`` (resting on the ground contact, which carries F_R > 0),
        ``"afloat"`` (free of the ground; floating or hanging in the water) or ``"clear"``
        (hanging clear of the water).
    buoyancy : float  [t]
        Net upward water force (displaced water less trapped water's lift; see
        :mod:`liftplan.model.hull`).
    volume : float  [m3]
        Envelope volume below the water plane.
    ground_reaction : float or None  [t]
        F_R at the contact (None when no ground is modelled; 0 when afloat).
    freeing_force : float or None  [t]
        friction x F_R (None without a friction coefficient).
    centre_of_buoyancy : tuple of 3 float or None  [m]
        Centre of the displaced envelope volume (None when clear of the water).
    centre_of_gravity : tuple of 3 float  [m]
    contact : tuple of 3 float or None  [m]
        The ground contact point.
    """

    state: str
    buoyancy: float
    volume: float
    ground_reaction: float | None
    freeing_force: float | None
    centre_of_buoyancy: tuple[float, float, float] | None
    centre_of_gravity: tuple[float, float, float]
    contact: tuple[float, float, float] | None


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
    afloat : Afloat or None
        Buoyancy and ground reaction, for a hull in water.
    rope_forces : dict of str to RopeForce or None
        Inclined ropes: each rope's force vector and inclination.
    position : tuple of 3 float or None  [m]
        Inclined ropes: world position of the body-frame origin (it swings in plan).
    """

    model: str
    pose: Pose
    tensions: dict[str, float]
    weight: float
    swl: dict[str, float | None]
    slack: tuple[str, ...]
    residual: float
    solver: SolverInfo
    afloat: Afloat | None = None
    rope_forces: dict | None = None
    position: tuple[float, float, float] | None = None

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
        return max(values) - min(values) if values else 0.0

    def to_json(self):
        """The JSON object of ``liftplan solve --json`` (keys fixed by CONTRACT.md)."""
        out = {
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
        if self.rope_forces is not None:
            out["horizontal_forces"] = {name: list(f.force[:2]) for name, f in self.rope_forces.items()}
            out["rope_angles"] = {name: f.angle for name, f in self.rope_forces.items()}
            out["position"] = list(self.position)
        if self.afloat is not None:
            a = self.afloat
            out.update({
                "state": a.state,
                "buoyancy": a.buoyancy,
                "ground_reaction": a.ground_reaction,
                "freeing_force": a.freeing_force,
                "displaced_volume": a.volume,
                "centre_of_buoyancy": a.centre_of_buoyancy,
                "centre_of_gravity": a.centre_of_gravity,
                "contact": a.contact,
            })
        return out
