"""What a sequence reports at one state: the loads, each lug's in its own frame."""

from __future__ import annotations

import math
from dataclasses import dataclass, field


@dataclass(frozen=True)
class LugLoad:
    """A lug's load in its own frame  [t].

    Parameters
    ----------
    load : float
        Magnitude.
    in_plane : float
        Component in the lug plate's plane.
    out_of_plane : float
        Component along the plate's normal (absolute).
    """

    load: float
    in_plane: float
    out_of_plane: float

    @property
    def off_plane_angle(self):
        """Angle between the load and the plate  [deg]."""
        return math.degrees(math.atan2(self.out_of_plane, self.in_plane)) if self.load > 0 else 0.0


@dataclass(frozen=True)
class SequenceState:
    """The body at one angle of a stage.

    Parameters
    ----------
    stage : str
    angle : float  [deg]
    tilt : float  [deg]
        Across the turning axis (found with two supports).
    held : bool
    hook_loads : dict of str to float  [t]
        Per crane of the stage (0 when slack).
    ground_reaction : float  [t]
        Vertical reaction at the pivot (0 without one, or lifted off).
    lug_loads : dict of str to LugLoad
        Every lug of the stage's cranes.
    sling_tensions : dict of str to float  [t]
        Sling legs, ``"CRANE/LUG"``.
    hooks : dict of str to tuple  [m]
        World position of each crane's hook (the rope's lower end: the lug or the sling's apex),
        the anchor (pivot, else centre of gravity) kept where it is at angle 0; in a move stage,
        each crane's boom tip (where the move has it).
    slack : tuple of str
    note : str
    heel, trim : float or None  [deg]
        A move stage: the body's attitude on its elastic ropes (``angle`` is then the stage
        parameter 0..1 and ``tilt`` 0); None in a turning stage.
    origin : tuple of 3 float or None  [m]
        A move stage: the world position of the body-frame origin.
    rotation : tuple of 3 tuples or None
        A move stage: the body -> world rotation (after a turning stage it includes the turn;
        ``heel`` and ``trim`` are measured from where the stage started).
    sling_hooks : dict of str to tuple
        A move stage: each sling crane's hook, world  [m].
    """

    stage: str
    angle: float
    tilt: float
    held: bool
    hook_loads: dict
    ground_reaction: float
    lug_loads: dict
    sling_tensions: dict
    hooks: dict
    slack: tuple
    note: str = ""
    heel: float | None = None
    trim: float | None = None
    origin: tuple | None = None
    rotation: tuple | None = None
    sling_hooks: dict = field(default_factory=dict)

    def to_json(self):
        if self.heel is not None:  # a move stage: no turning angle, its parameter and attitude
            turn = {
                "angle": None,
                "param": self.angle,
                "heel": self.heel,
                "trim": self.trim,
                "origin": list(self.origin),
            }
        else:
            turn = {"angle": self.angle}
        return {
            "stage": self.stage,
            **turn,
            "tilt": self.tilt,
            "held": self.held,
            "hook_loads": dict(self.hook_loads),
            "ground_reaction": self.ground_reaction,
            "lug_loads": {
                k: {"load": v.load, "in_plane": v.in_plane, "out_of_plane": v.out_of_plane}
                for k, v in self.lug_loads.items()
            },
            "sling_tensions": dict(self.sling_tensions),
            "hooks": {k: list(v) for k, v in self.hooks.items()},
            "slack": list(self.slack),
            "note": self.note,
        }
