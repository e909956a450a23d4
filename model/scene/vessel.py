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

Freeboard (when the vessel gives ``freeboard``, ``beam`` and ``length``): the deck edge is
taken level at ``freeboard`` above the water before the lift (the vessel at rest, no ballast
moment), the hull a box of ``beam`` x ``length`` centred on the flotation centre. A deck
point (x forward, y to starboard of the flotation centre) sinks by h + y phi + x theta (small
angles, phi and theta the heel and trim under the load with the ballast set), so the lowest
deck corner's freeboard is::

    f = freeboard - heave - (beam / 2) |phi| - (length / 2) |theta|      [m]

checked against ``min_freeboard`` (0: the deck edge at the water, when not given).
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
    freeboard : float or None  [m]
        The deck edge's height above the water before the lift (level, no ballast moment).
    min_freeboard : float or None  [m]
        The least freeboard allowed at the lowest deck corner under the load; 0 when
        ``freeboard`` is given without it.
    beam, length : float or None  [m]
        The hull's breadth and length, centred on the flotation centre: where the deck
        corners are. Required with ``freeboard``.
    hull : Hull or None
        Her hull as a closed mesh in her own axes (x forward, y to port, z up; ``z-up``):
        her heave, heel and trim under the hook loads from the clipped-mesh hydrostatics
        (:mod:`liftplan.model.water.hull_vessels`) instead of the small-angle particulars,
        which are then None (as are ballast and freeboard).
    cog : tuple of 3 float or None  [m]
        With ``hull``: her centre of gravity (crane and ballast included) in her axes.
    origin : tuple of 2 float or None  [m]
        With ``hull``: where her axes' origin lies in world plan (x, y), ``z-up``.
    """

    displacement: float
    waterplane_area: float | None = None
    gm_t: float | None = None
    gm_l: float | None = None
    flotation: tuple[float, float] | None = None
    heading: float = 0.0
    density: float = 1.025
    max_heel: float | None = None
    max_trim: float | None = None
    ballast: tuple[float, float] = (0.0, 0.0)
    freeboard: float | None = None
    min_freeboard: float | None = None
    beam: float | None = None
    length: float | None = None
    hull: object | None = None  # a Hull (liftplan.model.scene.hull)
    cog: tuple[float, float, float] | None = None
    origin: tuple[float, float] | None = None

    def __post_init__(self):
        linear = ("waterplane_area", "gm_t", "gm_l", "flotation")
        if self.hull is not None:
            self._check_hull(linear)
            linear = ()
        missing = [name for name in linear if getattr(self, name) is None]
        if missing:
            raise InvalidScene(
                f"vessel.{missing[0]}: missing; expected waterplane_area, gm_t, gm_l and flotation (the "
                "small-angle vessel), or her hull (mesh or box, with cog and origin)"
            )
        for name in ("displacement", *linear[:3], "density"):
            object.__setattr__(self, name, _number(f"vessel.{name}", getattr(self, name), "> 0"))
        object.__setattr__(self, "heading", _number("vessel.heading", self.heading))
        if linear:
            object.__setattr__(self, "flotation", _pair("vessel.flotation", self.flotation, "m"))
        object.__setattr__(self, "ballast", _pair("vessel.ballast", self.ballast, "t m"))
        for name in ("max_heel", "max_trim"):
            value = getattr(self, name)
            if value is not None:
                value = _number(f"vessel.{name}", value, "> 0")
                if value >= 90.0:
                    raise InvalidScene(f"vessel.{name} = {value!r}: expected a limit below 90 deg")
                object.__setattr__(self, name, value)
        self._check_freeboard()

    def _check_hull(self, linear):
        """A hull vessel: cog and origin given, no small-angle particulars, ballast or freeboard."""
        given = [
            n
            for n in (*linear, "freeboard", "beam", "length", "min_freeboard")
            if getattr(self, n) is not None
        ]
        if given:
            raise InvalidScene(
                f"vessel.{given[0]} given with the vessel's hull (mesh or box): expected her "
                "displacement, cog and origin alone (the hull gives her waterplane, stability and "
                "flotation centre; freeboard is not checked on a hull)"
            )
        if self.ballast != (0.0, 0.0):
            raise InvalidScene(
                "vessel.ballast given with the vessel's hull: expected the ballast in her displacement "
                "and cog (where it is)"
            )
        for name, size in (("cog", 3), ("origin", 2)):
            value = getattr(self, name)
            if value is None:
                raise InvalidScene(
                    f"vessel.{name}: missing with the vessel's hull; expected "
                    + (
                        "her centre of gravity [x, y, z] in the hull's axes"
                        if size == 3
                        else "where the hull's origin lies in plan (file frame)"
                    )
                )
            try:
                values = tuple(_number(f"vessel.{name}", v) for v in value)
            except TypeError:
                values = ()
            if len(values) != size:
                raise InvalidScene(f"vessel.{name} = {value!r}: expected {size} numbers [m]")
            object.__setattr__(self, name, values)

    def _check_freeboard(self):
        """freeboard with beam and length (the deck corners), min_freeboard only with freeboard."""
        for name in ("freeboard", "beam", "length"):
            value = getattr(self, name)
            if value is not None:
                object.__setattr__(self, name, _number(f"vessel.{name}", value, "> 0"))
        if self.min_freeboard is not None:
            object.__setattr__(self, "min_freeboard", _number("vessel.min_freeboard", self.min_freeboard))
        given = [n for n in ("freeboard", "beam", "length") if getattr(self, n) is not None]
        if given and len(given) < 3:
            missing = [n for n in ("freeboard", "beam", "length") if n not in given]
            raise InvalidScene(
                f"vessel.{given[0]} given without {' and '.join(missing)}: expected freeboard, beam and "
                "length together (the freeboard check needs where the deck corners are)"
            )
        if self.min_freeboard is not None and self.freeboard is None:
            raise InvalidScene(
                "vessel.min_freeboard given without freeboard: expected freeboard, beam and length "
                "with it (the freeboard before the lift and where the deck corners are)"
            )
        if self.freeboard is not None and self.min_freeboard is None:
            object.__setattr__(self, "min_freeboard", 0.0)

    def lowest_freeboard(self, heave, heel, trim):
        """The lowest deck corner's freeboard under the load (small angles, module docstring).

        Parameters
        ----------
        heave : float  [m]
            Sinkage under the load, > 0 down.
        heel, trim : float  [rad]
            The vessel's heel and trim under the load, the ballast moment included.

        Returns
        -------
        float or None  [m]
            freeboard - heave - beam |heel| / 2 - length |trim| / 2; None without ``freeboard``.
        """
        if self.freeboard is None:
            return None
        return self.freeboard - heave - 0.5 * self.beam * abs(heel) - 0.5 * self.length * abs(trim)

    def _small_angle(self):
        """Refuse the small-angle particulars of a vessel given by her hull."""
        if self.hull is not None:
            raise InvalidScene(
                "vessel given by her hull (mesh or box): modelled by the elastic model in air "
                "(liftplan solve); here the small-angle particulars are needed, expected "
                "waterplane_area, gm_t, gm_l and flotation instead of the hull"
            )

    @property
    def heave_stiffness(self):
        """density A_wp: the load per m of sinkage  [t/m]."""
        self._small_angle()
        return self.density * self.waterplane_area

    @property
    def heel_stiffness(self):
        """displacement GM_T: the heeling moment per rad  [t m/rad]."""
        self._small_angle()
        return self.displacement * self.gm_t

    @property
    def trim_stiffness(self):
        """displacement GM_L: the trimming moment per rad  [t m/rad]."""
        self._small_angle()
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
        self._small_angle()
        h = math.radians(self.heading)
        dx, dy = plan[0] - self.flotation[0], plan[1] - self.flotation[1]
        forward = dx * math.cos(h) + dy * math.sin(h)
        starboard = dx * math.sin(h) - dy * math.cos(h)
        return forward, starboard
