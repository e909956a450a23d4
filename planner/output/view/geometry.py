"""What the 3D view draws: a lift's fixed parts and its states, as frozen dataclasses.

Every point here is a world (``z-up``) or body-frame point in metres, forces in t; the writers
turn them into the file's frame (:func:`to_file_frame`) for what a person reads.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Axis titles per file frame: (x, y, z), the unit and the direction each points.
AXIS_TITLES = {
    "z-up": ("x [m], forward", "y [m], to port", "z [m], up"),
    "choi": ("x [m], forward", "y [m], up", "z [m], to starboard"),
}
#: Index of the vertical axis in each file frame.
UP_AXIS = {"z-up": 2, "choi": 1}


def to_file_frame(points, frame):
    """World ``z-up`` points (k, 3) or (3,) in the file's frame (``choi``: (x, y, z) -> (x, z, -y))."""
    p = np.asarray(points, dtype=float)
    if frame != "choi":
        return p.copy()
    return np.stack([p[..., 0], p[..., 2], -p[..., 1]], axis=-1)


@dataclass(frozen=True)
class Rope:
    """One rope or sling leg of a state.

    Parameters
    ----------
    key : str
        Its key in the results: the lug label for one rope per lug (``tensions``), ``CRANE/LUG``
        for a sling leg, ``CRANE/top1|2`` for a spreader's top leg, the crane's name for the
        hoist rope from boom tip to hook of a sling.
    role : {"rope", "leg", "top", "hoist"}
    lower, upper : tuple of 3 float  [m]
        World ends (``z-up``): the lug (bar end, hook) and the boom tip (hook).
    tension : float  [t]
    utilisation : float or None  [-]
        Tension over its crane's SWL (hoist and one-rope cranes), None where none applies.
    lug : str or None
        The lug at its lower end (None for a top leg and a hoist rope).
    """

    key: str
    role: str
    lower: tuple[float, float, float]
    upper: tuple[float, float, float]
    tension: float
    utilisation: float | None = None
    lug: str | None = None


@dataclass(frozen=True)
class ViewState:
    """The body, its ropes and the cranes' tips in one state.

    Parameters
    ----------
    name : str
        What the state is ("level", "worst case: heel 2.0 deg, ...", "lift-off at 0.09 m").
    rotation : tuple of 3 tuples of 3 float
        The body's attitude matrix (``liftplan.model.frames.rotation_matrix``).
    origin : tuple of 3 float  [m]
        World position of the body-frame origin.
    cog : tuple of 3 float  [m]
        The CG in this state, body frame.
    ropes : tuple of Rope
    spreaders : tuple of (str, 3-tuple, 3-tuple)
        Crane name and the world ends of its spreader bar  [m].
    tips : dict of str to 3-tuple
        Boom tip of each crane (by crane name), world  [m].
    hoist : float or None  [m]
        A lift's state: its hoist on the load curve.
    """

    name: str
    rotation: tuple
    origin: tuple[float, float, float]
    cog: tuple[float, float, float]
    ropes: tuple[Rope, ...]
    spreaders: tuple = ()
    tips: dict | None = None
    hoist: float | None = None

    def world(self, body_points):
        """Body-frame points (k, 3) at this state's pose, world  [m]."""
        return np.asarray(body_points, dtype=float) @ np.asarray(self.rotation).T + np.asarray(self.origin)


@dataclass(frozen=True)
class CraneMark:
    """A crane as drawn: its name and slew centre in plan (None where the file gives none).

    Parameters
    ----------
    name : str
    centre : tuple of 2 float or None  [m]
        World plan position of the slew centre (``z-up``).
    """

    name: str
    centre: tuple[float, float] | None = None


@dataclass(frozen=True)
class LiftView:
    """The whole 3D scene of a lift: fixed parts, and its states (the first the level one).

    Parameters
    ----------
    title : str
    frame : str
        The file's frame, ``"z-up"`` or ``"choi"``: every coordinate shown is in it.
    body : numpy.ndarray, shape (m, 3, 3)  [m]
        The body's surface, body frame: the hull mesh, or a prism on the plan outline, or a
        box around the lugs and the CG (see ``body_source``).
    body_source : str
        Where ``body`` comes from, in words.
    lugs : dict of str to 3-tuple  [m]
        Every lug or candidate, body frame.
    labels : dict of str to str
        The chosen lugs: lug or candidate name -> its label in the results (``L1``, ...).
    cranes : tuple of CraneMark
    cog_box : (3-tuple, 3-tuple) or None  [m]
        Lower and upper corners of the CG envelope, body frame.
    water_level : float or None  [m]
        World height of the water surface.
    seabed : float or None  [m]
        World height of the ground the body rests on.
    states : tuple of ViewState
    colour : {"utilisation", "tension"}
        What the ropes' colour shows: utilisation where every rope's crane has an SWL.
    """

    title: str
    frame: str
    body: np.ndarray
    body_source: str
    lugs: dict
    labels: dict
    cranes: tuple[CraneMark, ...]
    cog_box: tuple | None
    water_level: float | None
    seabed: float | None
    states: tuple[ViewState, ...]
    colour: str = "tension"

    def colour_values(self, state):
        """Each rope's colour value in ``state``: utilisation [-] or tension [t]."""
        if self.colour == "utilisation":
            return [r.utilisation for r in state.ropes]
        return [r.tension for r in state.ropes]

    @property
    def colour_title(self):
        return "utilisation [-]" if self.colour == "utilisation" else "tension [t]"

    def colour_range(self):
        """(low, high) of the colour values over every state (one colour bar for all)."""
        values = [v for s in self.states for v in self.colour_values(s) if v is not None]
        high = max(values, default=1.0)
        return 0.0, high if high > 0.0 else 1.0

    def bounds(self):
        """(lower, upper) world corners of everything drawn, over every state  [m]."""
        points = []
        for state in self.states:
            points.append(state.world(self.body.reshape(-1, 3)))
            for rope in state.ropes:
                points.append(np.array([rope.lower, rope.upper]))
        for crane in self.cranes:
            if crane.centre is not None:
                points.append(np.array([[*crane.centre, 0.0]]))
        allp = np.vstack(points)
        return allp.min(axis=0), allp.max(axis=0)

    def scene_json(self):
        """The data the page carries (``<script id="liftplan-scene">``), file frame.

        ``states``: per state its ``name``, and per rope that ends on a lug (key as in the
        results) the lug's position (``lugs``), the rope's upper end (``hooks``: the boom tip
        of a one-rope crane, the hook of a sling leg) and its tension (``tensions``); the other
        ropes (spreader top legs, hoist ropes) under ``other_ropes``.
        """

        def xyz(point):
            return [float(v) for v in to_file_frame(point, self.frame)]

        states = []
        for state in self.states:
            on_lugs = [r for r in state.ropes if r.lug is not None]
            states.append(
                {
                    "name": state.name,
                    **({} if state.hoist is None else {"hoist": state.hoist}),
                    "lugs": {r.key: xyz(r.lower) for r in on_lugs},
                    "hooks": {r.key: xyz(r.upper) for r in on_lugs},
                    "tensions": {r.key: float(r.tension) for r in on_lugs},
                    "utilisation": {r.key: r.utilisation for r in on_lugs},
                    "cog": xyz(state.world([state.cog])[0]),
                    "other_ropes": [
                        {
                            "key": r.key,
                            "role": r.role,
                            "ends": [xyz(r.lower), xyz(r.upper)],
                            "tension": r.tension,
                        }
                        for r in state.ropes
                        if r.lug is None
                    ],
                }
            )
        return {
            "title": self.title,
            "frame": self.frame,
            "units": {"length": "m", "force": "t", "angle": "deg"},
            "colour": self.colour,
            "states": states,
        }
