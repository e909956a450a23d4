"""The crane fleet: unequal cranes at fixed positions, each with its load chart.

A planning file lists the cranes with ``[[cranes]]`` (README "Crane fleet"); a file with only
``[crane]`` and ``[plan] cranes = n`` is a fleet of n equal cranes with no reach limit. The
planner decides which crane takes which lug; a crane can take a lug only within its chart's
reach, and its SWL there is read from the chart.

The radius of a crane on a lug is the plan distance from the crane's slew centre to the lug
at the level attitude (the hook is above the lug), in the world frame of the plan (the body
turned by the plan's yaw about the vertical through the body-frame origin).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from liftplan.model.errors import InvalidScene
from liftplan.model.rules import code_margin, dynamic_amplification
from liftplan.model.scene.objects import finite, positive
from liftplan.model.scene.rigging_gear import sling_ea
from liftplan.model.scene.vessel import Vessel


def _set(obj, name, value):
    object.__setattr__(obj, name, value)


@dataclass(frozen=True)
class SpreaderSpec:
    """A spreader bar under a crane's hook in a planning file (README "Sling lifts").

    Two top legs run from the hook to the bar's end pins, and the sling's two legs (the
    bottom legs) from the ends down to the two lugs the planner picks.

    Parameters
    ----------
    length : float  [m]
        Distance between the bar's end pins.
    top_length : float  [m]
        Each top leg's length, hook to bar end (same wire as the sling's legs).
    weight : float  [t]
        The bar with its shackles: part of the hook load and of the rigging weight.
    """

    length: float
    top_length: float
    weight: float = 0.0

    def __post_init__(self):
        _set(self, "length", positive("cranes.sling.spreader.length", self.length))
        _set(self, "top_length", positive("cranes.sling.spreader.top_length", self.top_length))
        weight = finite("cranes.sling.spreader.weight", self.weight)
        if weight < 0.0:
            raise InvalidScene(f"cranes.sling.spreader.weight = {self.weight!r}: expected >= 0 t")
        _set(self, "weight", weight)
        if self.top_length <= 0.5 * self.length:
            raise InvalidScene(
                f"cranes.sling.spreader.top_length = {self.top_length:g} m: expected more than half "
                f"the bar length {self.length:g} m (the top legs must meet above the bar)"
            )


@dataclass(frozen=True)
class SlingSpec:
    """A crane's sling set in a planning file: equal legs from its hook (or its spreader bar's
    ends) to the lugs the planner picks for it (README "Sling lifts").

    Parameters
    ----------
    length : float  [m]
        Each leg's length, pin to pin.
    legs : int
        Number of legs, 2 to 4: the planner takes that many candidates for the crane. A 2-leg
        sling hinges about its pair (the hook hangs in the vertical plane through it: a hinged
        lift point, any number of cranes); 3 and 4 legs fix the hook to the body.
    EA : float or None  [t]
        Each leg's axial stiffness; or give ``diameter``.
    diameter : float or None  [mm]
        Wire-rope diameter: EA = 80 000 N/mm2 x 0.785 d^2 (Noble Denton 0027/ND 5.6.13).
    spreader : SpreaderSpec or None
        A spreader bar between the hook and the legs (2 legs, one from each bar end).
    """

    length: float
    legs: int = 2
    EA: float | None = None
    diameter: float | None = None
    spreader: SpreaderSpec | None = None

    def __post_init__(self):

        _set(self, "length", positive("cranes.sling.length", self.length))
        if isinstance(self.legs, bool) or not isinstance(self.legs, int) or not 2 <= self.legs <= 4:
            raise InvalidScene(f"cranes.sling.legs = {self.legs!r}: expected 2, 3 or 4 legs")
        if (self.EA is None) == (self.diameter is None):
            raise InvalidScene("cranes.sling: expected exactly one of EA (t) or diameter (mm)")
        if self.diameter is not None:
            _set(self, "diameter", positive("cranes.sling.diameter", self.diameter))
            _set(self, "EA", sling_ea(self.diameter))
        else:
            _set(self, "EA", positive("cranes.sling.EA", self.EA))
        if self.spreader is not None:
            if not isinstance(self.spreader, SpreaderSpec):
                raise InvalidScene(
                    f"cranes.sling.spreader = {self.spreader!r}: expected {{ length, top_length, weight }}"
                )
            if self.legs != 2:
                raise InvalidScene(
                    f"cranes.sling.legs = {self.legs}: with a spreader bar expected 2 "
                    "(one leg from each bar end down to a lug)"
                )

    @property
    def body_fixed(self):
        """True when the hook is a body-fixed point (3 or 4 legs, no spreader)."""
        return self.legs >= 3 and self.spreader is None


@dataclass(frozen=True)
class FleetCrane:
    """One crane of the fleet.

    Parameters
    ----------
    name : str
    EA : float  [t]
        Hoist rope axial stiffness.
    rope_length : float  [m]
        Unstretched rope length l0 from boom tip to lug.
    position : tuple of 2 float or None  [m]
        Slew centre in plan (world x, y, z-up); None: anywhere (no reach limit).
    load_chart : tuple of (radius [m], SWL [t]) pairs
        Radii strictly increasing; SWL linear between points; the first radius is the least
        the crane can work at and the last its reach (no lug outside them). Empty when ``swl``
        is given.
    swl : float or None  [t]
        A fixed SWL at any radius (instead of a chart).
    boom_min, boom_max : float  [m]
        Range of the boom-tip height H above the datum.
    from_defaults : bool
        Made from the ``[crane]`` defaults (a problem re-makes such a fleet when its
        defaults or crane count change).
    sling : SlingSpec or None
        A sling set on the hook (``rope_length`` and ``EA`` are then the hoist rope's, tip
        to hook).
    hook_tolerance : float or None  [m]
        This hook's height tolerance, overriding ``[plan] hook_tolerance``.
    rope_length_range : tuple of 2 float or None  [m]
        (min, max) payout the planner may choose from (``rope_length = { min, max }``;
        :mod:`liftplan.planner.plans.lengths`); ``rope_length`` is then its max until chosen.
    vessel : Vessel or None
        A floating crane's vessel (:mod:`liftplan.model.scene.vessel`); None on land.
    rope_EA : float or None  [t]
        With a vessel, once the planner has put the vessel in series with the rope
        (:mod:`liftplan.planner.problem.vessels`): the hoist rope's own EA, ``EA`` being the
        series stiffness l0 / (l0 / EA_rope + c). None: ``EA`` is the rope's own.
    given : FleetCrane or None
        With a vessel in series: the crane as the file gives it (its own EA and hook
        tolerance), from which the planner puts the vessel in series at another lug. None: this
        is the crane as given. Not compared.
    """

    name: str
    EA: float
    rope_length: float
    position: tuple[float, float] | None = None
    load_chart: tuple[tuple[float, float], ...] = ()
    swl: float | None = None
    boom_min: float = -math.inf
    boom_max: float = math.inf
    from_defaults: bool = field(default=False, compare=False)
    sling: SlingSpec | None = None
    hook_tolerance: float | None = None
    rope_length_range: tuple[float, float] | None = None
    vessel: Vessel | None = None
    rope_EA: float | None = None
    given: FleetCrane | None = field(default=None, compare=False, repr=False)

    def __post_init__(self):
        if not isinstance(self.name, str) or not self.name.strip():
            raise InvalidScene(f"cranes.name = {self.name!r}: expected a non-empty string")
        key = f"cranes[{self.name}]"
        if self.vessel is not None:
            if not isinstance(self.vessel, Vessel):
                raise InvalidScene(
                    f"{key}.vessel = {self.vessel!r}: expected the vessel's particulars (a table); a "
                    "vessel shared by two cranes is not planned"
                )
            if self.sling is not None or self.rope_length_range is not None:
                raise InvalidScene(
                    f"{key}.vessel: a floating crane with a sling or a rope-length range is not "
                    "planned; expected one rope of fixed length"
                )
        if self.rope_length_range is not None:
            _set(self, "rope_length_range", length_range(f"{key}.rope_length", self.rope_length_range))
        if self.hook_tolerance is not None:
            value = finite(f"{key}.hook_tolerance", self.hook_tolerance)
            if value < 0.0:
                raise InvalidScene(f"{key}.hook_tolerance = {value!r}: expected >= 0 m")
            _set(self, "hook_tolerance", value)
        _set(self, "EA", positive(f"{key}.EA", self.EA))
        _set(self, "rope_length", positive(f"{key}.rope_length", self.rope_length))
        if self.position is not None:
            x, y = (finite(f"{key}.position", v) for v in tuple(self.position)[:2])
            _set(self, "position", (x, y))
        chart = tuple(tuple(p) for p in self.load_chart)
        if (self.swl is None) == (not chart):
            raise InvalidScene(f"{key}: expected exactly one of load_chart = [[radius, swl], ...] or swl")
        if self.swl is not None:
            _set(self, "swl", positive(f"{key}.swl", self.swl))
        if chart:
            if self.position is None:
                raise InvalidScene(
                    f"{key}.position: missing, expected the slew centre [x, y, z] "
                    "in m (a load chart needs it for the radius)"
                )
            points = []
            for pair in chart:
                if len(pair) != 2:
                    raise InvalidScene(
                        f"{key}.load_chart = {list(map(list, chart))}: expected [[radius m, SWL t], ...]"
                    )
                radius = finite(f"{key}.load_chart radius", pair[0])
                swl = finite(f"{key}.load_chart SWL", pair[1])
                if radius < 0.0:
                    raise InvalidScene(f"{key}.load_chart radius {radius:g}: expected >= 0 m")
                if swl <= 0.0:
                    raise InvalidScene(
                        f"{key}.load_chart SWL {swl:g} t at radius {radius:g} m: expected > 0 t"
                    )
                points.append((radius, swl))
            radii = [p[0] for p in points]
            if any(b <= a for a, b in zip(radii, radii[1:])):
                raise InvalidScene(f"{key}.load_chart radii {radii}: expected strictly increasing")
            for (r0, s0), (r1, s1) in zip(points, points[1:]):
                # a crane lifts less the further out it reaches (the overturning moment grows
                # with the radius): a rising SWL is a chart typed in the wrong order or column
                if s1 > s0:
                    raise InvalidScene(
                        f"{key}.load_chart: SWL rises from {s0:g} t at {r0:g} m to {s1:g} t at "
                        f"{r1:g} m; expected an SWL that never rises with radius (check the "
                        "order of the points and of [radius, SWL] in each)"
                    )
            _set(self, "load_chart", tuple(points))
        for name in ("boom_min", "boom_max"):
            value = getattr(self, name)
            if not (isinstance(value, int | float) and math.isinf(value)):
                _set(self, name, finite(f"{key}.boom_height.{name[5:]}", value))
        if self.boom_min > self.boom_max:
            raise InvalidScene(
                f"{key}.boom_height = {{min = {self.boom_min:g}, max = "
                f"{self.boom_max:g}}}: expected min <= max"
            )

    @property
    def stiffness(self):
        """Rope spring rate EA / l0  [t/m]."""
        return self.EA / self.rope_length

    @property
    def reach(self):
        """Largest radius of the chart  [m] (inf without a chart)."""
        return self.load_chart[-1][0] if self.load_chart else math.inf

    def radius(self, plan_points):
        """Plan distance from the slew centre to points (world x, y)  [m]; 0 without a position."""
        plan_points = np.asarray(plan_points, dtype=float)
        if self.position is None:
            return np.zeros(plan_points.shape[:-1])
        return np.hypot(plan_points[..., 0] - self.position[0], plan_points[..., 1] - self.position[1])

    def swl_at(self, radius):
        """SWL at a radius  [t]; NaN outside the chart's radii (a crane cannot luff its boom in
        past its least radius, nor out past its reach)."""
        radius = np.asarray(radius, dtype=float)
        if not self.load_chart:
            return np.full(radius.shape, self.swl)
        chart = np.array(self.load_chart)
        value = np.interp(radius, chart[:, 0], chart[:, 1])
        inside = (radius >= chart[0, 0] * (1 - 1e-12)) & (radius <= chart[-1, 0] * (1 + 1e-12))
        return np.where(inside, value, np.nan)

    def same_as(self, other):
        """True when the two cranes are interchangeable (all but the name equal)."""
        keys = (
            "EA",
            "rope_length",
            "position",
            "load_chart",
            "swl",
            "boom_min",
            "boom_max",
            "sling",
            "hook_tolerance",
            "rope_length_range",
            "vessel",
            "rope_EA",
        )
        return all(getattr(self, k) == getattr(other, k) for k in keys)


def length_range(key, value):
    """A (min, max) rope-length range, checked: 0 < min <= max  [m]."""
    low, high = (positive(f"{key}.{end}", v) for end, v in zip(("min", "max"), tuple(value)))
    if low > high:
        raise InvalidScene(f"{key} = {{min = {low:g}, max = {high:g}}}: expected min <= max")
    return (low, high)


def equal_fleet(spec, count):
    """``count`` equal cranes from the ``[crane]`` defaults, named ``crane 1`` ...

    Parameters
    ----------
    spec : CraneSpec
    count : int
    """
    return tuple(
        FleetCrane(
            name=f"crane {k + 1}",
            EA=spec.EA,
            rope_length=spec.rope_length,
            swl=spec.swl,
            boom_min=spec.boom_min,
            boom_max=spec.boom_max,
            from_defaults=True,
            rope_length_range=spec.rope_length_range,
        )
        for k in range(count)
    )


def crane_classes(fleet):
    """Group interchangeable cranes.

    Returns
    -------
    tuple of tuple of int
        Crane indices of each class, in fleet order of first appearance.
    """
    classes = []
    for j, crane in enumerate(fleet):
        for group in classes:
            if fleet[group[0]].same_as(crane):
                group.append(j)
                break
        else:
            classes.append([j])
    return tuple(tuple(g) for g in classes)


def reach_table(fleet, plan_points):
    """Radius and SWL of every crane at every candidate.

    Parameters
    ----------
    fleet : tuple of FleetCrane
    plan_points : (C, 2)  [m]   candidates at level, world plan coordinates

    Returns
    -------
    radius : (C, m)  [m]
    swl : (C, m)  [t]   NaN where the crane cannot reach the candidate
    """
    radius = np.column_stack([crane.radius(plan_points) for crane in fleet])
    swl = np.column_stack([crane.swl_at(radius[:, j]) for j, crane in enumerate(fleet)])
    return radius, swl


def rule_limits(problem, swl, cranes):
    """Tension limits the search holds every rope to, from the rules' design-load chain.

    The chain checks (worst x contingency + rigging) x DAF against the chart SWL and
    (nominal x contingency + rigging) x (1 + code margin) against it too (docs/design-loads.md);
    solved for the tension, these are linear limits, so the search keeps them exactly. The
    rules' tilt and the computed skew factor are checked on the plan afterwards.

    Parameters
    ----------
    problem : PlanProblem
    swl : array_like, shape (..., n)  [t]   chart SWL of each rope's crane at its radius
    cranes : array_like of int, shape (..., n)   fleet indices

    Returns
    -------
    in_box : numpy.ndarray  [t]   the largest tension allowed anywhere in the box
    share : numpy.ndarray  [t]   the largest level (nominal) tension the code margin allows
    """

    rules = problem.rules
    swl = np.asarray(swl, dtype=float)
    cranes = np.asarray(cranes)
    n = swl.shape[-1]
    rigging = np.array([rules.rigging_for(c.name) for c in problem.fleet])[cranes]
    contingency = rules.weight_contingency
    if rules.chart_includes_dynamics:
        daf = 1.0
    elif rules.daf is not None:
        daf = rules.daf
    else:
        # Table 5-1 at the design weight; below 100 t its factor falls with the hook load, so
        # the hook load is taken as the whole weight: the smallest factor (a limit the chain
        # can only tighten)
        weight = problem.body.weight * contingency
        daf = dynamic_amplification(weight, rules.location, static_hook_load=weight)
    margin = code_margin(n, rules.code_margin)
    in_box = (swl / daf - rigging) / contingency
    share = (swl / (1.0 + margin) - rigging) / contingency
    return in_box, share
