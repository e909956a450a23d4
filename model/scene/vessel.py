"""A floating crane's vessel: its small-angle hydrostatics (``[[cranes]] vessel = {...}``).

The vessel is a linear spring under its crane's vertical hook load T, applied at the boom
tip (plan offset x_t forward, y_t to starboard of the centre of flotation, in the vessel's
axes)::

    heave = T / (density A_wp)                       [m, + down: the vessel sinks]
    heel  = T y_t / (displacement GM_T)              [rad, + starboard side down]
    trim  = T x_t / (displacement GM_L)              [rad, + bow down]
    tip drop = heave + y_t heel + x_t trim           [m, + down]

(the signs of ``docs/conventions.md``: a hook to starboard heels the vessel starboard down,
a hook forward of the flotation centre trims it bow down). A vessel carrying several cranes
sums their loads. A ballast moment set before the lift turns the vessel at rest and leaves
its response to the load (the tip drop) unchanged: the heel and trim reported under load
are those of the ballasted vessel.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from liftplan.model.errors import InvalidScene


def _number(path, value, lowest=None):
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise InvalidScene(f"{path} = {value!r}: expected a number") from None
    if not math.isfinite(number):
        raise InvalidScene(f"{path} = {value!r}: expected a finite number")
    if lowest == "> 0" and not number > 0.0:
        raise InvalidScene(f"{path} = {value!r}: expected a number > 0")
    return number


def _pair(path, value, unit):
    try:
        items = tuple(value)
    except TypeError:
        raise InvalidScene(f"{path} = {value!r}: expected two numbers [{unit}]") from None
    if len(items) != 2:
        raise InvalidScene(f"{path} = {value!r}: expected two numbers [{unit}]")
    return tuple(_number(path, v) for v in items)


@dataclass(frozen=True)
class Vessel:
    """A crane vessel's particulars, in the ``z-up`` frame.

    Parameters
    ----------
    displacement : float  [t]
        The vessel's displacement before the lift (with its crane and ballast).
    waterplane_area : float  [m2]
        A_wp at its waterline.
    gm_t, gm_l : float  [m]
        Transverse and longitudinal metacentric heights.
    flotation : tuple of 2 float  [m]
        Centre of flotation in world plan (x, y), ``z-up``.
    heading : float  [deg]
        The bow's direction in world plan from +x, > 0 towards +y (port), ``z-up``.
    density : float  [t/m3]
        Water density.
    max_heel, max_trim : float or None  [deg]
        The vessel's limits (absolute) under the load: checked when given.
    ballast : tuple of 2 float  [t m]
        Ballast moment set before the lift: (heeling, > 0 heels starboard down; trimming,
        > 0 trims bow down). The heel at rest is ballast[0] / (displacement GM_T).
    """

    displacement: float
    waterplane_area: float
    gm_t: float
    gm_l: float
    flotation: tuple[float, float]
    heading: float = 0.0
    density: float = 1.025
    max_heel: float | None = None
    max_trim: float | None = None
    ballast: tuple[float, float] = (0.0, 0.0)

    def __post_init__(self):
        for name in ("displacement", "waterplane_area", "gm_t", "gm_l", "density"):
            object.__setattr__(self, name, _number(f"vessel.{name}", getattr(self, name), "> 0"))
        object.__setattr__(self, "heading", _number("vessel.heading", self.heading))
        object.__setattr__(self, "flotation", _pair("vessel.flotation", self.flotation, "m"))
        object.__setattr__(self, "ballast", _pair("vessel.ballast", self.ballast, "t m"))
        for name in ("max_heel", "max_trim"):
            value = getattr(self, name)
            if value is not None:
                value = _number(f"vessel.{name}", value, "> 0")
                if value >= 90.0:
                    raise InvalidScene(f"vessel.{name} = {value!r}: expected a limit below 90 deg")
                object.__setattr__(self, name, value)

    @property
    def heave_stiffness(self):
        """density A_wp: the load per m of sinkage  [t/m]."""
        return self.density * self.waterplane_area

    @property
    def heel_stiffness(self):
        """displacement GM_T: the heeling moment per rad  [t m/rad]."""
        return self.displacement * self.gm_t

    @property
    def trim_stiffness(self):
        """displacement GM_L: the trimming moment per rad  [t m/rad]."""
        return self.displacement * self.gm_l

    def axes(self, plan):
        """A world plan point's offset from the flotation centre in the vessel's axes.

        Parameters
        ----------
        plan : sequence of 2 float  [m]
            World plan (x, y), ``z-up``.

        Returns
        -------
        tuple of 2 float  [m]
            (x_t forward, y_t to starboard).
        """
        h = math.radians(self.heading)
        dx, dy = plan[0] - self.flotation[0], plan[1] - self.flotation[1]
        forward = dx * math.cos(h) + dy * math.sin(h)
        starboard = dx * math.sin(h) - dy * math.cos(h)
        return forward, starboard
