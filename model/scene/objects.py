"""The scene: a rigid body hung from crane ropes (n >= 3 lugs), or from sling sets.

Frozen dataclasses in the ``z-up`` frame (see :mod:`liftplan.model.frames`), referring to
each other by lug name. Each object checks its own values where it is made, and
:class:`Scene` checks what needs the whole picture (names, statics), so a scene built from
Python is held to the same rules as one read from a file.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from liftplan.model.errors import InvalidScene
from liftplan.model.scene.rigging_gear import RiggingLimits, Sling
from liftplan.model.scene.tide import Tide
from liftplan.model.scene.vessel import Vessel
from liftplan.model.scene.wind import Wind

MODELS = ("elastic", "paper-elastic", "rigid", "hydrostatic", "inclined", "rigging")
FRAMES = ("z-up", "choi")  # as liftplan.model.frames.FRAMES (not imported: it pulls casadi in)

# Plan-area test for collinear lugs: the support polygon's area over its diameter squared.
# Below this the 3x3 statics matrix has a condition number above ~1e9: singular in t and m.
_COLLINEAR_AREA = 1e-9


#: Names listed in one error line; more are counted ("and 12 more"), so a 64-rope scene's
#: message stays one readable line.
NAMES_SHOWN = 8


def name_list(names, limit=NAMES_SHOWN):
    """Names joined by commas, the first ``limit`` of them and a count of the rest."""
    names = list(names)
    shown = ", ".join(str(name) for name in names[:limit])
    return shown if len(names) <= limit else f"{shown} and {len(names) - limit} more"


def finite(path, value):
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise InvalidScene(f"{path} = {value!r}: expected a number") from None
    if not math.isfinite(number):
        raise InvalidScene(f"{path} = {value!r}: expected a finite number")
    return number


def positive(path, value):
    number = finite(path, value)
    if number <= 0.0:
        raise InvalidScene(f"{path} = {value!r}: expected a number > 0")
    return number


def point(path, value):
    try:
        items = tuple(value)
    except TypeError:
        raise InvalidScene(f"{path} = {value!r}: expected [x, y, z] in m") from None
    if len(items) != 3:
        raise InvalidScene(f"{path} = {value!r}: expected [x, y, z] in m")
    return tuple(finite(path, v) for v in items)


def _set(obj, name, value):
    object.__setattr__(obj, name, value)


#: A weight curve must carry the body's weight to this fraction of W: a curve tabulated per
#: frame station from a loading manual, rounded to two or three figures, sums to its
#: lightship weight within a few tenths of a percent.
WEIGHT_CURVE_REL = 0.005
#: ... and put its centroid within this of the CG's x  [m]: the accuracy a CG is known to;
#: the moment it leaves (0.05 W, 45 t m on the 904 t tanker) is ~2 % of her peak moment.
WEIGHT_CURVE_CENTROID = 0.05


def polyline(path, value, unit, lowest=None, minimum=1):
    """Read ``[[x, value], ...]`` with x strictly increasing; returns a tuple of pairs.

    Parameters
    ----------
    path : str
        The key, for messages.
    value : sequence of pairs
    unit : str
        Unit of the values, for messages (``"t/m"``).
    lowest : {None, ">= 0", "> 0"}
        What the values must be.
    minimum : int
        Fewest points.
    """
    expected = f"expected [[x m, {unit}], ...] with x increasing"
    try:
        rows = [tuple(row) for row in value]
    except TypeError:
        raise InvalidScene(f"{path} = {value!r}: {expected}") from None
    if len(rows) < minimum:
        raise InvalidScene(f"{path} = {value!r}: {len(rows)} point(s); {expected}, {minimum} or more points")
    out = []
    for k, row in enumerate(rows):
        if len(row) != 2:
            raise InvalidScene(f"{path}[{k}] = {list(row)!r}: expected [x m, {unit}]")
        x, v = finite(f"{path}[{k}]", row[0]), finite(f"{path}[{k}]", row[1])
        if out and not x > out[-1][0]:
            raise InvalidScene(
                f"{path}[{k}] = [{x:g}, {v:g}]: x {x:g} m is not greater than the previous "
                f"point's {out[-1][0]:g} m; {expected} strictly"
            )
        if lowest == ">= 0" and v < 0.0:
            raise InvalidScene(
                f"{path}[{k}] = [{x:g}, {v:g}]: {v:g} {unit} is negative; expected >= 0 {unit}"
            )
        if lowest == "> 0" and not v > 0.0:
            raise InvalidScene(f"{path}[{k}] = [{x:g}, {v:g}]: expected a value > 0 {unit}")
        out.append((x, v))
    return tuple(out)


def curve_totals(x, w):
    """Integral [t] and first moment about x = 0 [t m] of a piecewise-linear weight curve
    (points x [m], values w [t/m], zero outside), exact."""
    x, w = np.asarray(x, dtype=float), np.asarray(w, dtype=float)
    h, w0, w1 = np.diff(x), w[:-1], w[1:]
    area = float(np.sum(h * (w0 + w1) / 2.0))
    # each trapezoid's first moment: h/6 (w0 (2 x0 + x1) + w1 (x0 + 2 x1))
    moment = float(np.sum(h / 6.0 * (w0 * (2 * x[:-1] + x[1:]) + w1 * (x[:-1] + 2 * x[1:]))))
    return area, moment


@dataclass(frozen=True)
class Body:
    """The lifted body.

    Parameters
    ----------
    weight : float  [t]
        Total weight W (in air, or in water when the scene says so).
    cog : tuple of 3 float  [m]
        Centre of gravity in the body frame.
    weight_curve : tuple of (float, float) or None  [m, t/m]
        Weight per unit length along the body's x axis, linear between the points and zero
        outside them (for the hull girder's shear force and bending moment,
        :mod:`liftplan.model.strength`). Its integral must be W within
        :data:`WEIGHT_CURVE_REL` and its centroid the CG's x within
        :data:`WEIGHT_CURVE_CENTROID`.
    """

    weight: float
    cog: tuple[float, float, float]
    weight_curve: tuple[tuple[float, float], ...] | None = None

    def __post_init__(self):
        _set(self, "weight", positive("body.weight", self.weight))
        _set(self, "cog", point("body.cog", self.cog))
        if self.weight_curve is not None:
            _set(self, "weight_curve", _checked_curve(self.weight_curve, self.weight, self.cog[0]))

    @cached_property
    def weight_curve_arrays(self):
        """The weight curve as read-only arrays (x [m], weight per length [t/m]); None without."""
        if self.weight_curve is None:
            return None
        x, w = (np.array(v, dtype=float) for v in zip(*self.weight_curve))
        x.setflags(write=False)
        w.setflags(write=False)
        return x, w


def _checked_curve(value, weight, cog_x):
    curve = polyline("body.weight_curve", value, "t/m", lowest=">= 0", minimum=2)
    area, moment = curve_totals(*zip(*curve))
    if not area > 0.0:
        raise InvalidScene(
            "body.weight_curve: carries no weight (every value 0 t/m); expected a "
            "curve whose integral is body.weight"
        )
    if abs(area - weight) > WEIGHT_CURVE_REL * weight:
        raise InvalidScene(
            f"body.weight_curve: integral {area:.6g} t differs from body.weight {weight:.6g} t by "
            f"{100 * abs(area - weight) / weight:.2f} %; expected within {100 * WEIGHT_CURVE_REL:g} %"
        )
    centroid = moment / area
    if abs(centroid - cog_x) > WEIGHT_CURVE_CENTROID:
        raise InvalidScene(
            f"body.weight_curve: centroid x {centroid:.4f} m differs from body.cog x {cog_x:.4f} m by "
            f"{abs(centroid - cog_x):.3g} m; expected within {WEIGHT_CURVE_CENTROID:g} m"
        )
    return curve


@dataclass(frozen=True)
class Strength:
    """Allowable envelopes of the hull girder (``[strength]``), linear between points and held
    at their end values beyond the first and last.

    Parameters
    ----------
    bending_moment : tuple of (float, float) or None  [m, t m]
        |M| allowed along the body's x.
    shear_force : tuple of (float, float) or None  [m, t]
        |Q| allowed along the body's x.
    """

    bending_moment: tuple[tuple[float, float], ...] | None = None
    shear_force: tuple[tuple[float, float], ...] | None = None

    def __post_init__(self):
        for name, unit in (("bending_moment", "t m"), ("shear_force", "t")):
            value = getattr(self, name)
            if value is not None:
                _set(self, name, polyline(f"strength.{name}", value, unit, lowest="> 0"))

    def allowable(self, name, x):
        """The envelope ``name`` at stations ``x`` [m] (None when not given)."""
        curve = getattr(self, name)
        if curve is None:
            return None
        xs, values = zip(*curve)
        return np.interp(x, xs, values)


#: How ``solve`` treats a hull with a stiffness (``[analysis] hull``).
HULL_MODELS = ("auto", "rigid", "flexible")


@dataclass(frozen=True)
class GirderStiffness:
    """Stiffness of the hull girder (``[hull] EI``, ``GJ``): the hull as an elastic beam along
    its x (:mod:`liftplan.model.strength.flexible`). Linear between points, the end values held
    beyond the first and last; every point must lie on the body (the weight curve's span).

    Parameters
    ----------
    EI : tuple of (float, float)  [m, t m2]
        Vertical bending stiffness (Young's modulus x the midship section's moment of inertia).
    GJ : tuple of (float, float) or None  [m, t m2]
        Torsional stiffness about the body's x; None: the hull is rigid in torsion.
    """

    EI: tuple[tuple[float, float], ...]
    GJ: tuple[tuple[float, float], ...] | None = None

    def __post_init__(self):
        _set(self, "EI", polyline("hull.EI", self.EI, "t m2", lowest="> 0"))
        if self.GJ is not None:
            _set(self, "GJ", polyline("hull.GJ", self.GJ, "t m2", lowest="> 0"))


def _check_girder(scene):
    """A hull stiffness needs the weight curve, and its points and the lugs on the body."""
    if scene.body.weight_curve is None:
        raise InvalidScene(
            "hull.EI: given but no body.weight_curve; expected a weight curve (the "
            "flexible hull is loaded by its weight along x)"
        )
    x, _ = scene.body.weight_curve_arrays
    lo, hi = float(x[0]), float(x[-1])
    slack = 1e-9 * (hi - lo)
    for name in ("EI", "GJ"):
        for k, (xk, value) in enumerate(getattr(scene.girder, name) or ()):
            if not lo - slack <= xk <= hi + slack:
                raise InvalidScene(
                    f"hull.{name}[{k}] = [{xk:g}, {value:g}]: x {xk:g} m lies outside the body "
                    f"(body.weight_curve from {lo:g} to {hi:g} m); expected stations on the body"
                )
    for lug in scene.lugs:
        if not lo - slack <= lug.at[0] <= hi + slack:
            raise InvalidScene(
                f"lugs[{lug.name}].at: x {lug.at[0]:g} m lies outside the hull girder "
                f"(body.weight_curve from {lo:g} to {hi:g} m); expected lugs on the body when "
                "hull.EI is given"
            )


@dataclass(frozen=True)
class Lug:
    """A lifting point on the body.

    Parameters
    ----------
    name : str
        Unique label, e.g. ``"T1"``.
    at : tuple of 3 float  [m]
        Position in the body frame.
    capacity : float or None  [t]
        The lug's allowed load in its plate's plane (checked by ``liftplan sequence``).
    capacity_out_of_plane : float or None  [t]
        The lug's allowed load across its plate (the out-of-plane component).
    normal : tuple of 3 float or None  [-]
        The lug plate's normal (its pin axis) in the body frame, a unit vector (scaled to
        one when read); None: the turning axis of a sequence.
    """

    name: str
    at: tuple[float, float, float]
    capacity: float | None = None
    capacity_out_of_plane: float | None = None
    normal: tuple[float, float, float] | None = None

    def __post_init__(self):
        if not isinstance(self.name, str) or not self.name.strip():
            raise InvalidScene(f"lugs.name = {self.name!r}: expected a non-empty string")
        _set(self, "at", point(f"lugs[{self.name}].at", self.at))
        for key in ("capacity", "capacity_out_of_plane"):
            if getattr(self, key) is not None:
                _set(self, key, positive(f"lugs[{self.name}].{key}", getattr(self, key)))
        if self.normal is not None:
            n = point(f"lugs[{self.name}].normal", self.normal)
            size = math.sqrt(sum(v * v for v in n))
            if not size > 0.0:
                raise InvalidScene(
                    f"lugs[{self.name}].normal = {list(self.normal)!r}: expected a non-zero vector"
                )
            _set(self, "normal", tuple(v / size for v in n))


@dataclass(frozen=True)
class Crane:
    """A crane: one rope from its tip to one lug, or a hoist rope to a hook with a sling set.

    Parameters
    ----------
    lug : str or None
        Name of the lug the rope is shackled to (None for a crane with a ``sling``).
    EA : float or None  [t]
        Axial stiffness of the rope (modulus times metallic area); with a sling, of the
        hoist rope from tip to hook.
    boom_height : float or None  [m]
        Height H of the boom tip (rope's upper end) above the datum z = 0.
    rope_length : float or None  [m]
        Unstretched rope length l0 between boom tip and lug (forward ``elastic`` model); with a
        sling, between boom tip and hook.
    swl : float or None  [t]
        Safe working load of the crane at its radius.
    tip : tuple of 3 float or None  [m]
        World position of the boom tip when it is not above the lug (inclined rope); with a
        sling, default above the centroid of the sling's lugs at the boom height.
    name : str or None
        The crane's label; needed with a ``sling`` (results are keyed by it). A crane on one
        lug is keyed by its lug, as the contract fixes.
    sling : Sling or None
        Legs (and a spreader bar) from the hook to 2-4 lugs, instead of ``lug``.
    vessel : Vessel or str or None
        The floating crane's vessel (its tip moves with it under the hook load), or the name
        of another crane whose vessel this crane shares; None: a crane on land (fixed tip).
    """

    lug: str | None = None
    EA: float | None = None
    boom_height: float | None = None
    rope_length: float | None = None
    swl: float | None = None
    tip: tuple[float, float, float] | None = None
    name: str | None = None
    sling: Sling | None = None
    vessel: Vessel | str | None = None

    def __post_init__(self):
        if self.name is not None and (not isinstance(self.name, str) or not self.name.strip()):
            raise InvalidScene(f"cranes.name = {self.name!r}: expected a non-empty string")
        where = f"cranes[{self.name or self.lug}]"
        if (self.lug is None) == (self.sling is None):
            raise InvalidScene(
                f"{where}: {'both lug and sling' if self.lug is not None else 'neither lug nor sling'}"
                ' given; expected lug = "NAME" (one rope to one lug) or sling = { legs = [...] }'
            )
        if self.sling is not None:
            if not isinstance(self.sling, Sling):
                raise InvalidScene(f"{where}.sling = {self.sling!r}: expected a Sling")
            if self.name is None:
                raise InvalidScene(
                    f"cranes[{', '.join(self.sling.lugs)}].name: missing; a crane with a sling "
                    "needs a name (its hook load and legs are reported under it)"
                )
        if self.EA is not None:
            _set(self, "EA", positive(f"{where}.EA", self.EA))
        if self.boom_height is not None:
            _set(self, "boom_height", finite(f"{where}.boom_height", self.boom_height))
        if self.rope_length is not None:
            _set(self, "rope_length", positive(f"{where}.rope_length", self.rope_length))
        if self.swl is not None:
            _set(self, "swl", positive(f"{where}.swl", self.swl))
        if self.tip is not None:
            _set(self, "tip", point(f"{where}.tip", self.tip))
        if self.vessel is not None and not isinstance(self.vessel, Vessel):
            if not isinstance(self.vessel, str) or not self.vessel.strip():
                raise InvalidScene(
                    f"{where}.vessel = {self.vessel!r}: expected a vessel table or the name of the "
                    "crane whose vessel this crane shares"
                )

    @property
    def vessel_name(self):
        """The name of the vessel this crane stands on (its own: its name, else its label; a
        shared one: the crane named), or None on land."""
        if self.vessel is None:
            return None
        return self.vessel if isinstance(self.vessel, str) else (self.name or self.label)

    @property
    def label(self):
        """The key of this crane's results: its lug (one rope) or its name (a sling)."""
        return self.lug if self.sling is None else self.name

    @property
    def lugs(self):
        """The lugs this crane holds."""
        return (self.lug,) if self.sling is None else self.sling.lugs


@dataclass(frozen=True)
class Attitude:
    """Body attitude and height for the given-attitude models (initial guess for ``elastic``).

    Parameters
    ----------
    heel : float  [deg]
        > 0 starboard side down (psi in Choi & Shin).
    trim : float  [deg]
        > 0 bow down (-phi in Choi & Shin).
    yaw : float  [deg]
        > 0 bow to port (theta in Choi & Shin).
    lift_height : float  [m]
        Height a of the body-frame origin above the datum.
    """

    heel: float = 0.0
    trim: float = 0.0
    yaw: float = 0.0
    lift_height: float = 0.0

    def __post_init__(self):
        for name in ("heel", "trim", "yaw", "lift_height"):
            _set(self, name, finite(f"attitude.{name}", getattr(self, name)))
        for name in ("heel", "trim"):
            if abs(getattr(self, name)) > 90.0:
                raise InvalidScene(
                    f"attitude.{name} = {getattr(self, name)!r}: expected a value in [-90, 90] deg"
                )


@dataclass(frozen=True)
class Redundant:
    """A tension set by the crane operators (the ``rigid`` model's redundant unknown).

    Parameters
    ----------
    lug : str
    tension : float  [t]
    """

    lug: str
    tension: float

    def __post_init__(self):
        t = finite(f"analysis.redundant[{self.lug}].tension", self.tension)
        if t < 0.0:
            raise InvalidScene(f"analysis.redundant[{self.lug}].tension = {self.tension!r}: expected >= 0 t")
        _set(self, "tension", t)


@dataclass(frozen=True)
class Analysis:
    """Which model to solve, and its extra data.

    Parameters
    ----------
    model : str or None
        ``"elastic"``, ``"paper-elastic"`` or ``"rigid"``; None lets the solver pick the
        least model the scene supports (see :func:`liftplan.model.solve.pick_model`).
    redundant : tuple of Redundant
        n - 3 tensions held by the operators, for ``rigid``.
    hull : {"auto", "rigid", "flexible"}
        With a hull stiffness (``Scene.girder``): ``auto`` solves the hull both rigid and
        flexible and keeps the rigid answer when no tension differs by more than 1 %;
        ``rigid`` and ``flexible`` force one (:func:`liftplan.model.solve.solve`).
    """

    model: str | None = None
    redundant: tuple[Redundant, ...] = ()
    hull: str = "auto"

    def __post_init__(self):
        if self.model is not None and self.model not in MODELS:
            raise InvalidScene(f"analysis.model = {self.model!r}: expected one of {', '.join(MODELS)}")
        if self.hull not in HULL_MODELS:
            raise InvalidScene(f"analysis.hull = {self.hull!r}: expected one of {', '.join(HULL_MODELS)}")
        _set(self, "redundant", tuple(self.redundant))


@dataclass(frozen=True)
class Water:
    """Sea water.

    Parameters
    ----------
    density : float  [t/m3]
        Mass density; buoyancy in t is density x displaced volume.
    level : float  [m]
        Height of the free surface (world z).
    """

    density: float = 1.025
    level: float = 0.0

    def __post_init__(self):
        _set(self, "density", positive("water.density", self.density))
        _set(self, "level", finite("water.level", self.level))


#: Time ratios pull_time / embedded_time over which Liu (1969, NCEL R-635) fitted the
#: breakout-time correlation; outside it the soil model is refused, not extrapolated.
LIU_RANGE = (1e-3, 10.0)


@dataclass(frozen=True)
class Breakout:
    """How hard the seabed holds a bedded hull (``[ground] breakout``); the force itself is
    :func:`liftplan.model.water.breakout.breakout_force`.

    One of three models (:attr:`model`):

    * ``factor``: the breakout force is this factor x the submerged weight at rest;
    * ``ncel`` (``shear_strength`` without the two times): the immediate breakout force of
      a cohesive seabed, NCEL (Lee 1973, R-755; the NCEL Handbook for Marine Geotechnical
      Engineering), ``bearing_factor`` x s_u x area x (1 + 0.2 D/B)(1 + 0.2 B/L), D the
      ``embedment``, B and L the contact's ``width`` and ``length``;
    * ``soil`` (``shear_strength`` with ``pull_time`` and ``embedded_time``, the model of
      before, kept as it was): ``bearing_factor`` x s_u x area times Liu's (1969)
      1.5 (pull_time / embedded_time)^-0.07. N_c s_u A is already the full-suction
      immediate force, so this likely counts suction twice; liftplan warns when it is used.

    Parameters
    ----------
    factor : float or None  [-]
        >= 0.
    shear_strength : float or None  [kPa]
        Undrained shear strength of the seabed soil, >= 0.
    area : float or None  [m2]
        Contact area; default the plan area of the hull's underside at rest.
    bearing_factor : float  [-]
        N_c of the reverse bearing capacity, > 0 (5.14: Prandtl, a long footing; the
        ``ncel`` model adds its own shape and depth factors to it).
    pull_time : float or None  [h]
        ``soil`` model: time allowed for the breakout pull, > 0.
    embedded_time : float or None  [h]
        ``soil`` model: time the hull has lain bedded, > 0.
    embedment : float  [m]
        ``ncel`` model: D, how deep the underside lies below the seabed surface, >= 0.
    width, length : float or None  [m]
        ``ncel`` model: B and L, the contact's shorter and longer plan sides, > 0; default
        the extents of the hull's underside at rest across and along its heading.
    clear : float  [m]
        The soil holds on with the full breakout force until the contact has risen this
        far above its bed, >= 0.
    """

    factor: float | None = None
    shear_strength: float | None = None
    area: float | None = None
    bearing_factor: float = 5.14
    pull_time: float | None = None
    embedded_time: float | None = None
    clear: float = 0.1
    embedment: float = 0.0
    width: float | None = None
    length: float | None = None

    @property
    def model(self):
        """``"factor"``, ``"ncel"`` (immediate breakout) or ``"soil"`` (Liu's time factor)."""
        if self.factor is not None:
            return "factor"
        return "ncel" if self.pull_time is None and self.embedded_time is None else "soil"

    def __post_init__(self):
        key = "ground.breakout"
        soil = {
            "shear_strength": self.shear_strength,
            "area": self.area,
            "pull_time": self.pull_time,
            "embedded_time": self.embedded_time,
            "width": self.width,
            "length": self.length,
        }
        given = [name for name, value in soil.items() if value is not None]
        if self.embedment != 0.0:
            given.append("embedment")
        if self.factor is not None:
            if given:
                raise InvalidScene(
                    f"{key}: factor and the soil model's {', '.join(given)} both given; expected "
                    "either factor (x the submerged weight) or a soil model, not both"
                )
            factor = finite(f"{key}.factor", self.factor)
            if factor < 0.0:
                raise InvalidScene(f"{key}.factor = {self.factor!r}: expected a number >= 0")
            _set(self, "factor", factor)
        elif self.shear_strength is None:
            raise InvalidScene(
                f"{key}: expected factor = ... (x the submerged weight) or shear_strength = ... kPa "
                "(the NCEL immediate breakout, with embedment; or with pull_time and embedded_time, "
                "the soil model of Liu's time factor)"
            )
        else:
            strength = finite(f"{key}.shear_strength", self.shear_strength)
            if strength < 0.0:
                raise InvalidScene(f"{key}.shear_strength = {self.shear_strength!r}: expected kPa >= 0")
            _set(self, "shear_strength", strength)
            if self.area is not None:
                _set(self, "area", positive(f"{key}.area", self.area))
            if self.model == "soil":
                self._check_times(key)
            else:
                embedment = finite(f"{key}.embedment", self.embedment)
                if embedment < 0.0:
                    raise InvalidScene(f"{key}.embedment = {self.embedment!r}: expected m >= 0")
                _set(self, "embedment", embedment)
                for name in ("width", "length"):
                    if getattr(self, name) is not None:
                        _set(self, name, positive(f"{key}.{name}", getattr(self, name)))
        _set(self, "bearing_factor", positive(f"{key}.bearing_factor", self.bearing_factor))
        clear = finite(f"{key}.clear", self.clear)
        if clear < 0.0:
            raise InvalidScene(f"{key}.clear = {self.clear!r}: expected m >= 0")
        _set(self, "clear", clear)

    def _check_times(self, key):
        """The ``soil`` model's two times and their ratio (Liu's fitted range)."""
        ncel = [name for name in ("width", "length") if getattr(self, name) is not None]
        if self.embedment != 0.0:
            ncel.append("embedment")
        if ncel:
            raise InvalidScene(
                f"{key}: {', '.join(ncel)} with pull_time and embedded_time; expected the NCEL "
                "immediate breakout (shear_strength with embedment, width, length; no times) or "
                "the soil model of Liu's time factor (pull_time and embedded_time), not both"
            )
        for name in ("pull_time", "embedded_time"):
            if getattr(self, name) is None:
                raise InvalidScene(f"{key}.{name}: missing, expected hours > 0 for the soil model")
            _set(self, name, positive(f"{key}.{name}", getattr(self, name)))
        ratio = self.pull_time / self.embedded_time
        low, high = LIU_RANGE
        if not low <= ratio <= high:
            raise InvalidScene(
                f"{key}: pull_time / embedded_time = {ratio:.3g}: outside {low:g} to {high:g}, the range "
                "Liu's (1969) time correlation was fitted to; expected times within it, or factor"
            )


@dataclass(frozen=True)
class Ground:
    """A point of the body resting on the ground; the body pivots about it.

    Parameters
    ----------
    contact : tuple of 3 float  [m]
        Body-frame point on the ground. At zero attitude it is at its body-frame position
        (raised by ``attitude.lift_height``), and the ground holds it there.
    friction : float or None  [-]
        Friction coefficient mu: freeing force = mu x ground reaction.
    """

    contact: tuple[float, float, float]
    friction: float | None = None
    breakout: Breakout | None = None

    def __post_init__(self):
        _set(self, "contact", point("ground.contact", self.contact))
        if self.friction is not None:
            mu = finite("ground.friction", self.friction)
            if mu < 0.0:
                raise InvalidScene(f"ground.friction = {self.friction!r}: expected a number >= 0")
            _set(self, "friction", mu)
        if self.breakout is not None and not isinstance(self.breakout, Breakout):
            raise InvalidScene(f"ground.breakout = {self.breakout!r}: expected a Breakout")


#: Discharge coefficient of a sharp-edged orifice (the vena contracta), the textbook 0.61.
DISCHARGE = 0.61


@dataclass(frozen=True)
class Opening:
    """An opening of a compartment that holds water (``[[hull.compartments]] openings``).

    Parameters
    ----------
    compartment : str
        The compartment's name.
    area : float  [m2]
        >= 0; 0 never drains, ``inf`` drains at once (the inside level follows the
        outside one, or the opening's sill).
    at : tuple of 3 float  [m]
        Body-frame point, on or in the compartment's box.
    discharge : float  [-]
        Discharge coefficient C_d in (0, 1]: flow = C_d x area x sqrt(2 g head).
    """

    compartment: str
    area: float
    at: tuple[float, float, float]
    discharge: float = DISCHARGE

    def __post_init__(self):
        key = f"hull.compartments[{self.compartment}].openings"
        bad = InvalidScene(f"{key}.area = {self.area!r}: expected m2 >= 0 (inf: drains at once)")
        try:
            area = float(self.area)
        except (TypeError, ValueError):
            raise bad from None
        if math.isnan(area) or area < 0.0:
            raise bad
        _set(self, "area", area)
        _set(self, "at", point(f"{key}.at", self.at))
        cd = finite(f"{key}.discharge", self.discharge)
        if not 0.0 < cd <= 1.0:
            raise InvalidScene(f"{key}.discharge = {self.discharge!r}: expected a coefficient in (0, 1]")
        _set(self, "discharge", cd)


@dataclass(frozen=True)
class Scene:
    """A body on n >= 3 vertical crane ropes, in the ``z-up`` frame.

    Parameters
    ----------
    body : Body
    lugs : tuple of Lug
    cranes : tuple of Crane
        Every lug held by exactly one crane's rope or sling leg; stored in the order of
        their (first) lugs.
    attitude : Attitude
    analysis : Analysis
    name : str
    water : Water or None
    hull : liftplan.model.scene.hull.Hull or None
        Needed with ``water`` (buoyancy acts on the hull).
    ground : Ground or None
    rigging : RiggingLimits
        Limits checked on sling sets (``[rigging]``).
    frame : str
        The frame the scene's file was written in (``"z-up"`` or ``"choi"``); the scene
        itself is always in ``z-up``, and JSON coordinates are written back in this frame.
    strength : Strength or None
        Allowable bending moment and shear force of the hull girder (needs
        ``body.weight_curve``).
    girder : GirderStiffness or None
        Bending (and torsional) stiffness of the hull girder: the hull is an elastic beam
        (needs ``body.weight_curve``; every lug on its span).
    openings : tuple of Opening
    tide : Tide or None
        The tide over the operation (:mod:`liftplan.model.scene.tide`): floating cranes and
        the water rise with it.
    wind : Wind or None
        The wind on the body and the floating cranes' booms (:mod:`liftplan.model.scene.wind`).
    """

    body: Body
    lugs: tuple[Lug, ...] = ()
    cranes: tuple[Crane, ...] = ()
    attitude: Attitude = field(default_factory=Attitude)
    analysis: Analysis = field(default_factory=Analysis)
    name: str = ""
    water: Water | None = None
    hull: object | None = None
    ground: Ground | None = None
    rigging: RiggingLimits = field(default_factory=RiggingLimits)
    frame: str = "z-up"
    strength: Strength | None = None
    girder: GirderStiffness | None = None
    openings: tuple[Opening, ...] = ()
    tide: Tide | None = None
    wind: Wind | None = None

    def __post_init__(self):
        if self.wind is not None and not isinstance(self.wind, Wind):
            raise InvalidScene(f"wind = {self.wind!r}: expected a Wind")
        if self.tide is not None and not isinstance(self.tide, Tide):
            raise InvalidScene(f"tide = {self.tide!r}: expected a Tide")
        if self.frame not in FRAMES:
            raise InvalidScene(f"frame = {self.frame!r}: expected one of {', '.join(FRAMES)}")
        if self.strength is not None:
            if not isinstance(self.strength, Strength):
                raise InvalidScene(f"strength = {self.strength!r}: expected a Strength")
            if self.body.weight_curve is None:
                raise InvalidScene(
                    "strength: allowable envelopes given but no body.weight_curve; expected "
                    "a weight curve (shear force and bending moment need it)"
                )
        lugs, cranes = tuple(self.lugs), tuple(self.cranes)
        if (self.water is None) != (self.hull is None):
            raise InvalidScene(
                "scene: [water] and [hull] go together (buoyancy needs both); expected both or neither"
            )
        if self.ground is not None and self.hull is None:
            raise InvalidScene("ground: a ground contact needs [hull] and [water]; expected them too")
        if self.ground is not None:
            _check_contact(self.ground.contact, self.hull)
        _set(self, "openings", tuple(self.openings))
        if self.openings:
            _check_openings(self)
        if not lugs and self.hull is not None:
            _set(self, "lugs", ())
            _set(self, "cranes", ())
            return
        if len(lugs) < 3:
            raise InvalidScene(
                f"lugs: {len(lugs)} given: expected three or more (two ropes cannot hold a body)"
            )
        names = [lug.name for lug in lugs]
        seen_names = set()
        for name in names:
            if name in seen_names:
                raise InvalidScene(f"lugs.name = {name!r}: duplicate, expected unique lug names")
            seen_names.add(name)
        holder = {}
        for crane in cranes:
            for lug in crane.lugs:
                key = "cranes.lug" if crane.sling is None else f"cranes[{crane.name}].sling.legs.lug"
                if lug not in names:
                    raise InvalidScene(f"{key} = {lug!r}: unknown lug, expected one of {name_list(names)}")
                if lug in holder:
                    if crane.sling is None and holder[lug].sling is None:
                        raise InvalidScene(
                            f"cranes.lug = {lug!r}: two cranes on one lug, expected one crane per lug"
                        )
                    raise InvalidScene(
                        f"{key} = {lug!r}: used twice (cranes {holder[lug].label} and {crane.label}); "
                        "expected each lug on one rope or sling leg"
                    )
                holder[lug] = crane
        for name in names:
            if name not in holder:
                raise InvalidScene(f"lugs[{name}]: no crane on it, expected one crane per lug")
        seen = {}
        for crane in cranes:
            for ident in {crane.label, crane.name} - {None}:
                if seen.setdefault(ident, crane) is not crane:
                    raise InvalidScene(
                        f"cranes.name = {ident!r}: names two cranes (a crane on one lug is also "
                        "known by its lug); expected unique crane names"
                    )
        # cranes in the order of their first lug: lug order for one rope per lug, as before
        order = {name: k for k, name in enumerate(names)}
        _set(self, "lugs", lugs)
        _set(self, "cranes", tuple(sorted(cranes, key=lambda c: min(order[lug] for lug in c.lugs))))
        held = set()
        for red in self.analysis.redundant:
            if red.lug not in names:
                raise InvalidScene(
                    f"analysis.redundant.lug = {red.lug!r}: unknown lug, expected one of {name_list(names)}"
                )
            if red.lug in held:
                raise InvalidScene(
                    f"analysis.redundant.lug = {red.lug!r}: held twice, expected each held lug once"
                )
            held.add(red.lug)
        if self.hull is None:
            _check_support(self)
        _check_vessels(cranes)
        if self.girder is not None:
            if not isinstance(self.girder, GirderStiffness):
                raise InvalidScene(f"girder = {self.girder!r}: expected a GirderStiffness")
            _check_girder(self)
        elif self.analysis.hull == "flexible":
            raise InvalidScene(
                'analysis.hull = "flexible": no hull.EI given; expected [hull] EI = '
                "[[x m, EI t m2], ...] for a flexible hull"
            )

    # -- look-ups ---------------------------------------------------------------
    @cached_property
    def lug_names(self):
        """Lug names in scene order."""
        return tuple(lug.name for lug in self.lugs)

    @property
    def n(self):
        """Number of ropes."""
        return len(self.lugs)

    def lug_points(self):
        """Lug positions, body frame, shape (n, 3)  [m]."""
        return self._lug_array.copy()

    @cached_property
    def _lug_array(self):
        return np.array([lug.at for lug in self.lugs], dtype=float).reshape(-1, 3)

    @property
    def hydrostatic(self):
        """True when the body is in water (buoyancy acts)."""
        return self.hull is not None

    @cached_property
    def plan_diameter(self):
        """Largest plan distance between two lugs  [m] (the moment residuals' length scale)."""
        if not self.lugs:
            return 0.0
        plan = self._lug_array[:, :2]
        # the farthest pair are corners of the convex hull: O(n log n), where all pairs of
        # thousands of lugs would take gigabytes
        corners = plan[_convex_hull([tuple(p) for p in plan]) or [0]]
        return float(np.max(np.linalg.norm(corners[:, None, :] - corners[None, :, :], axis=-1)))

    def crane_values(self, field, model):
        """Every crane's ``field`` in lug order; a missing one is an InvalidScene naming the
        crane and the model that needs it."""
        values = []
        for crane in self.cranes:
            value = getattr(crane, field)
            if value is None:
                raise InvalidScene(
                    f"cranes[{crane.label}].{field}: missing, the {model} model needs it for every crane"
                )
            values.append(value)
        return values

    def crane(self, key):
        """The crane on lug ``key``, or named ``key``."""
        for crane in self.cranes:
            if key in (crane.lug, crane.name):
                return crane
        known = [c.label for c in self.cranes]
        raise InvalidScene(
            f"crane = {key!r}: unknown crane, expected a lug or crane name of {name_list(known)}"
        )

    @cached_property
    def vessels(self):
        """The crane vessels: name -> (Vessel, indices of the cranes on it, in scene order).

        Empty when every crane stands on land.
        """
        tables = {c.vessel_name: c.vessel for c in self.cranes if isinstance(c.vessel, Vessel)}
        out = {}
        for name, vessel in tables.items():
            on = tuple(k for k, c in enumerate(self.cranes) if c.vessel_name == name)
            out[name] = (vessel, on)
        return out

    @property
    def slings(self):
        """True when a crane carries a sling set (the ``rigging`` model is needed)."""
        return any(c.sling is not None for c in self.cranes)

    # -- changed copies (the scene is frozen) ------------------------------------
    def with_crane(self, key, **changes):
        """A copy with crane ``key`` (lug or name) changed, e.g.
        ``scene.with_crane("T1", boom_height=41.0)``."""
        old = self.crane(key)
        cranes = tuple(dataclasses.replace(c, **changes) if c is old else c for c in self.cranes)
        return dataclasses.replace(self, cranes=cranes)

    def with_attitude(self, **changes):
        """A copy with the attitude changed, e.g. ``scene.with_attitude(heel=2.0)``."""
        return dataclasses.replace(self, attitude=dataclasses.replace(self.attitude, **changes))

    def with_body(self, **changes):
        """A copy with the body changed, e.g. ``scene.with_body(weight=950.0)``."""
        return dataclasses.replace(self, body=dataclasses.replace(self.body, **changes))

    def with_analysis(self, **changes):
        """A copy with the analysis changed, e.g. ``scene.with_analysis(model="rigid")``."""
        return dataclasses.replace(self, analysis=dataclasses.replace(self.analysis, **changes))


def _check_vessels(cranes):
    """Each shared vessel names a crane that carries a vessel table; vessel names unique."""
    own = {}
    for crane in cranes:
        if isinstance(crane.vessel, Vessel):
            name = crane.vessel_name
            if name in own:
                raise InvalidScene(
                    f"cranes[{crane.label}].vessel: a second vessel named {name!r}; expected one "
                    "vessel table per crane name"
                )
            own[name] = crane
    for crane in cranes:
        if isinstance(crane.vessel, str) and crane.vessel not in own:
            known = name_list(own) if own else "none given"
            raise InvalidScene(
                f"cranes[{crane.label}].vessel = {crane.vessel!r}: no crane of that name carries a "
                f"vessel table; expected the name of a crane with vessel = {{ ... }} ({known})"
            )


def _check_openings(scene):
    """Each opening on a water compartment of the hull, on or inside its box."""
    tanks = {c.name: c for c in (scene.hull.compartments if scene.hull is not None else ())}
    for opening in scene.openings:
        key = f"hull.compartments[{opening.compartment}].openings"
        tank = tanks.get(opening.compartment)
        if tank is None:
            raise InvalidScene(
                f"{key}: no compartment {opening.compartment!r}; expected one of "
                f"{name_list(tanks) or 'none (no compartments)'}"
            )
        if tank.contents != "water":
            raise InvalidScene(
                f'{key}: the compartment holds {tank.contents!r}; expected contents = "water" (openings '
                "drain trapped water; an air compartment with an opening would flood)"
            )
        lower, upper = (np.asarray(v, dtype=float) for v in (tank.box["min"], tank.box["max"]))
        slack = 1e-9 * max(1.0, float(np.max(np.abs(np.concatenate([lower, upper])))))
        at = np.asarray(opening.at)
        if np.any(at < lower - slack) or np.any(at > upper + slack):
            # in the file's frame: choi (x, y, z) is z-up (x, -z, y)
            shown = (lambda v: [v[0], v[2], -v[1]]) if scene.frame == "choi" else list
            corners = sorted([shown(lower.tolist()), shown(upper.tolist())])
            raise InvalidScene(
                f"{key}.at = {shown(list(opening.at))}: outside the compartment's box with corners "
                f"{corners[0]} and {corners[1]} (body frame); expected a point on or in it"
            )


def _convex_hull(points):
    """Counter-clockwise convex hull (Andrew's monotone chain); returns indices."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    def chain(indices):
        out = []
        for i in indices:
            while len(out) >= 2 and cross(points[out[-2]], points[out[-1]], points[i]) <= 0:
                out.pop()
            out.append(i)
        return out

    lower, upper = chain(order), chain(reversed(order))
    return lower[:-1] + upper[:-1]


#: How far a ground contact may lie outside the hull's bounding box, as a share of the hull's
#: largest side: a keel point or a bilge keel just off the modelled envelope is accepted, a
#: contact metres away is a typing error (450 m out, the hull pivots about a point in the water).
CONTACT_REACH = 0.05


def _check_contact(contact, hull):
    """Refuse a ground contact outside the hull's extent by more than :data:`CONTACT_REACH`."""
    lower, upper = hull.bounds
    outside = float(np.max(np.maximum(lower - contact, np.asarray(contact) - upper)))
    allowed = CONTACT_REACH * hull.size
    if outside > allowed:
        box = ", ".join(f"{a:g}..{b:g}" for a, b in zip(lower, upper, strict=True))
        raise InvalidScene(
            f"ground.contact = ({', '.join(f'{c:g}' for c in contact)}) m: {outside:.3g} m outside "
            f"the hull's extent (x, y, z {box} m, z-up body frame); expected a point on the hull, "
            f"within {allowed:.3g} m of it ({CONTACT_REACH:.0%} of its largest side)"
        )


def _check_support(scene):
    """Lugs must span a plan area, and the CG must lie over it (at level attitude)."""
    plan = scene.lug_points()[:, :2]
    diameter = scene.plan_diameter
    hull = _convex_hull([tuple(p) for p in plan])
    area = 0.0
    for k, i in enumerate(hull):
        j = hull[(k + 1) % len(hull)]
        area += plan[i, 0] * plan[j, 1] - plan[j, 0] * plan[i, 1]
    area *= 0.5
    if diameter == 0.0 or len(hull) < 3 or area < _COLLINEAR_AREA * diameter**2:
        raise InvalidScene(
            f"lugs {name_list(scene.lug_names)}: plan positions (x, y) are collinear, "
            "so the statics are singular: expected lugs spanning an area in plan"
        )
    cx, cy = scene.body.cog[:2]
    names = scene.lug_names
    for k, i in enumerate(hull):
        j = hull[(k + 1) % len(hull)]
        edge = plan[j] - plan[i]
        # signed distance of the CG from the edge, > 0 inside (hull is counter-clockwise)
        dist = (edge[0] * (cy - plan[i, 1]) - edge[1] * (cx - plan[i, 0])) / np.hypot(*edge)
        if dist < -1e-9 * diameter:
            on_edge = {names[i], names[j]}
            slack = [name for name in names if name not in on_edge]
            raise InvalidScene(
                f"body.cog = ({cx:g}, {cy:g}) m in plan lies {-dist:.3g} m outside the lugs' "
                f"support polygon beyond edge {names[i]}-{names[j]}: rope(s) "
                f"{name_list(slack)} would go slack; expected the CG over the lugs"
            )
