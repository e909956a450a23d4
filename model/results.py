"""Result objects of a solve.

Results are in the ``z-up`` frame, as the scene is; :meth:`Equilibrium.to_json` writes
world coordinates (body position, hook positions, spreader ends) back in the frame of the
scene's file (``Equilibrium.frame``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar


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

    Every force is named for what it is. The hull carries its weight in air W at G and,
    in a flooded hull, the trapped water (``trapped_water``, a weight, at its own centre);
    the water pushes up with the buoyancy B (the weight of the displaced water, always
    >= 0) at the centre of buoyancy; the ground pushes up with F_R at the contact; the
    ropes carry the rest: sum T = W + trapped water - B - F_R. Submerged, a trapped
    compartment displaces water like any watertight space, so its part of B cancels its
    weight; clear of the water it is carried whole.

    Parameters
    ----------
    state : str
        One of :attr:`STATES`: ``"grounded"`` (resting on the ground contact, which carries
        F_R > 0), ``"hanging submerged"`` (free of the ground, held by the cranes, wholly
        below the surface), ``"piercing the surface"`` (held by the cranes, partly out of
        the water), ``"clear"`` (hanging clear of the water) or ``"afloat"`` (floating free:
        no ground reaction, no crane load).
    buoyancy : float  [t]
        Weight of the displaced water: ``density x displaced_volume`` (>= 0).
    displaced_volume : float  [m3]
        Volume of water displaced: the whole envelope below the surface for an intact
        hull; the steel and the watertight compartments (air or trapped water) below the
        surface for a flooded one.
    immersed_volume : float  [m3]
        Volume of the hull envelope below the water plane (equal to ``displaced_volume``
        for an intact hull; a flooded hull's water inside displaces nothing).
    trapped_water : float  [t]
        Weight of the water trapped in compartments, carried with the hull (0 without).
    density : float  [t/m3]
        Water density.
    ground_reaction : float or None  [t]
        F_R at the contact (None when no ground is modelled; 0 once free of it).
    freeing_force : float or None  [t]
        friction x F_R (None without a friction coefficient).
    centre_of_buoyancy : tuple of 3 float or None  [m]
        Centre of the displaced volume, where B acts (None when clear of the water).
    centre_of_gravity : tuple of 3 float  [m]
        The body's G (weight in air, without trapped water).
    contact : tuple of 3 float or None  [m]
        The ground contact point.
    centre_of_trapped_water : tuple of 3 float or None  [m]
        Centre of the trapped water (None without).
    """

    state: str
    buoyancy: float
    displaced_volume: float
    immersed_volume: float
    trapped_water: float
    density: float
    ground_reaction: float | None
    freeing_force: float | None
    centre_of_buoyancy: tuple[float, float, float] | None
    centre_of_gravity: tuple[float, float, float]
    contact: tuple[float, float, float] | None
    centre_of_trapped_water: tuple[float, float, float] | None = None

    STATES: ClassVar[dict[str, str]] = {
        "grounded": "resting on the ground contact",
        "hanging submerged": "hanging on the cranes, wholly under water",
        "piercing the surface": "hanging on the cranes, partly out of the water",
        "clear": "hanging on the cranes, clear of the water",
        "afloat": "floating free, no crane load",
    }

    def __post_init__(self):
        if self.state not in self.STATES:
            raise ValueError(f"Afloat.state = {self.state!r}: expected one of {', '.join(self.STATES)}")

    def crane_load(self, weight):
        """What the ropes carry together: W + trapped water - buoyancy - ground reaction  [t].

        Parameters
        ----------
        weight : float  [t]   the body's weight in air
        """
        return weight + self.trapped_water - self.buoyancy - (self.ground_reaction or 0.0)

    def to_json(self, frame="z-up"):
        """The water keys of ``solve --json``; points in the scene file's ``frame``.

        ``buoyancy``, ``ground_reaction`` and ``freeing_force`` mean what CONTRACT.md
        says (buoyancy: the weight of the displaced water)."""
        return {
            "state": self.state,
            "buoyancy": self.buoyancy,
            "ground_reaction": self.ground_reaction,
            "freeing_force": self.freeing_force,
            "displaced_volume": self.displaced_volume,
            "immersed_volume": self.immersed_volume,
            "trapped_water": self.trapped_water,
            "water_density": self.density,
            "centre_of_buoyancy": _maybe_in_frame(self.centre_of_buoyancy, frame),
            "centre_of_gravity": _maybe_in_frame(self.centre_of_gravity, frame),
            "centre_of_trapped_water": _maybe_in_frame(self.centre_of_trapped_water, frame),
            "contact": _maybe_in_frame(self.contact, frame),
        }


@dataclass(frozen=True)
class RiggingState:
    """Sling legs, hooks and spreader bars of an equilibrium (``rigging`` model).

    Leg keys are ``"CRANE/LUG"`` for a leg to a lug and ``"CRANE/top1"``, ``"CRANE/top2"``
    for a spreader's top legs (hook to bar end 1, 2); CRANE is the crane's name.

    Parameters
    ----------
    legs : dict of str to float  [t]
        Leg tension (0 for a slack leg).
    sling_angles : dict of str to float  [deg]
        Leg angle from the horizontal at the equilibrium (90 for a vertical leg).
    leg_lugs : dict of str to str or None
        The lug at each leg's lower end (None for a top leg).
    hook_positions : dict of str to tuple of 3 float  [m]
        World position of each sling crane's hook (``z-up``).
    spreader_compression : dict of str to float  [t]
        Axial compression of each crane's spreader bar (> 0 compressed).
    spreader_ends : dict of str to tuple of two 3-tuples  [m]
        World positions of the bar's ends 1 and 2 (``z-up``).
    min_sling_angle : float  [deg]
        The limit the scene set (``[rigging] min_sling_angle``).
    """

    legs: dict[str, float]
    sling_angles: dict[str, float]
    leg_lugs: dict[str, str | None]
    hook_positions: dict[str, tuple[float, float, float]]
    spreader_compression: dict[str, float]
    spreader_ends: dict[str, tuple[tuple[float, float, float], tuple[float, float, float]]]
    min_sling_angle: float


def _in_frame(point, frame):
    """A world point from ``z-up`` to a file's frame (``choi``: (x, y, z) -> (x, z, -y))."""
    x, y, z = (float(v) for v in point)
    return [x, z, -y] if frame == "choi" else [x, y, z]


def _maybe_in_frame(point, frame):
    return None if point is None else _in_frame(point, frame)


@dataclass(frozen=True)
class VesselState:
    """A crane vessel under its hook loads (small-angle hydrostatics,
    :mod:`liftplan.model.scene.vessel`).

    Parameters
    ----------
    heave : float  [m]
        Sinkage under the load, > 0 down.
    heel : float  [deg]
        > 0 starboard side down; with the ballast moment set before the lift.
    trim : float  [deg]
        > 0 bow down; with the ballast moment set before the lift.
    tip_drops : dict of str to float  [m]
        Each of its cranes' boom-tip drop under the load (> 0 down), keyed as the tensions:
        the extra hoist that crane needs as the load comes on, beyond a crane on land.
    load : float  [t]
        The hook loads it carries.
    levelling_ballast : tuple of 2 float  [t m]
        The ballast moment (heeling, > 0 starboard down; trimming, > 0 bow down) that, set
        before the lift, leaves the vessel level under this load.
    max_heel, max_trim : float or None  [deg]
        Its limits, when given.
    freeboard : float or None  [m]
        The lowest deck corner's freeboard under the load (ballast included), when the
        vessel gives its ``freeboard``, ``beam`` and ``length``
        (:meth:`~liftplan.model.scene.vessel.Vessel.lowest_freeboard`).
    min_freeboard : float or None  [m]
        Its least allowed freeboard, when ``freeboard`` is given.
    """

    heave: float
    heel: float
    trim: float
    tip_drops: dict[str, float]
    load: float
    levelling_ballast: tuple[float, float]
    max_heel: float | None = None
    max_trim: float | None = None
    freeboard: float | None = None
    min_freeboard: float | None = None

    @property
    def tip_drop(self):
        """The largest of its cranes' tip drops  [m]."""
        return max(self.tip_drops.values())

    def to_json(self):
        """``{"heave", "heel", "trim", "tip_drop", ...}`` (the first four fixed by CONTRACT.md)."""
        return {
            "heave": self.heave,
            "heel": self.heel,
            "trim": self.trim,
            "tip_drop": self.tip_drop,
            "tip_drops": dict(self.tip_drops),
            "load": self.load,
            "levelling_ballast": {"heel": self.levelling_ballast[0], "trim": self.levelling_ballast[1]},
            "freeboard": self.freeboard,
        }


@dataclass(frozen=True)
class Equilibrium:
    """Equilibrium of the body on its ropes.

    Parameters
    ----------
    model : str
        ``"elastic"``, ``"paper-elastic"``, ``"rigid"``, ``"hydrostatic"``, ``"inclined"``
        or ``"rigging"``.
    pose : Pose
    tensions : dict of str to float  [t]
        Rope tension at each crane, in scene order: by lug name for one rope per lug; with
        sling sets, the hook load by crane name (see ``rigging``).
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
    rigging : RiggingState or None
        Sling sets: legs, sling angles, hooks and spreaders. ``tensions`` then holds each
        crane's hook load (hoist rope tension), keyed by crane name (a one-rope crane by
        its lug).
    frame : str
        The scene file's frame; :meth:`to_json` writes world coordinates in it.
    flexible_hull : FlexibleHull or RigidHullNote or None
        With a hull stiffness (``[hull] EI``): which hull the tensions are of, the change
        flexibility makes and the deflection (:mod:`liftplan.model.strength.flexible`).
    vessels : dict of str to VesselState or None
        Floating cranes (``[[cranes]] vessel``): each crane vessel's heave, heel, trim and tip
        drops under the tensions.
    tide : TideState or None
        The tide the scene was solved at (``[tide]``).
    wind : WindState or None
        What the wind did (``[wind]``): its force on the body and the CG's downwind shift, its
        forces on the booms and the vessels' heel and trim from them, the tips' drops.
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
    rigging: RiggingState | None = None
    frame: str = "z-up"
    flexible_hull: object | None = None
    vessels: dict[str, VesselState] | None = None
    tide: object | None = None
    wind: object | None = None

    def file_point(self, point):
        """A world point (``z-up``) in the scene file's frame, as a list  [m]."""
        return _in_frame(point, self.frame)

    @property
    def share(self):
        """Each crane's share of the weight, keyed as ``tensions``  [-]."""
        return {name: t / self.weight for name, t in self.tensions.items()}

    @property
    def utilisation(self):
        """Tension over the crane's SWL, keyed as ``tensions`` (None where no SWL)  [-]."""
        return {name: (t / self.swl[name] if self.swl[name] else None) for name, t in self.tensions.items()}

    @property
    def spread(self):
        """Largest minus smallest tension  [t]."""
        values = list(self.tensions.values())
        return max(values) - min(values) if values else 0.0

    def to_json(self):
        """The JSON object of ``liftplan solve --json`` (keys fixed by CONTRACT.md).

        World coordinates (``position``, the water centres and contact, ``hook_positions``,
        spreader ends) are in the scene file's frame, named by ``"frame"``.
        """
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
            "frame": self.frame,
            "solver": {
                "method": self.solver.method,
                "iterations": self.solver.iterations,
                "seconds": self.solver.seconds,
            },
        }
        if self.rope_forces is not None:
            out["horizontal_forces"] = {name: list(f.force[:2]) for name, f in self.rope_forces.items()}
            out["rope_angles"] = {name: f.angle for name, f in self.rope_forces.items()}
            out["position"] = _in_frame(self.position, self.frame)
        if self.rigging is not None:
            r = self.rigging
            out.update(
                {
                    "hook_loads": dict(self.tensions),
                    "legs": dict(r.legs),
                    "sling_angles": dict(r.sling_angles),
                    "hook_positions": {k: _in_frame(v, self.frame) for k, v in r.hook_positions.items()},
                    "spreaders": {
                        k: {"compression": c, "ends": [_in_frame(e, self.frame) for e in r.spreader_ends[k]]}
                        for k, c in r.spreader_compression.items()
                    },
                }
            )
        if self.afloat is not None:
            out.update(self.afloat.to_json(self.frame))
        if self.flexible_hull is not None:
            out["flexible_hull"] = self.flexible_hull.to_json()
        if self.vessels is not None:
            out["vessels"] = {name: state.to_json() for name, state in self.vessels.items()}
        if self.tide is not None:
            out["tide"] = self.tide.to_json()
        if self.wind is not None:
            out["wind"] = self.wind.to_json()
        return out
